# `cmake --install build --prefix P` installs the libraries that make sense on their own, with
# their headers under P/include/ecm/ (included as "material/material.hpp") and a CMake package:
# find_package(ecm) then gives ecm::material and ecm::calibration (examples/point_path/), with
# "ecm/version.hpp" and the documents the headers cite in share/doc/ecm/ (docs/cpp.md).
# The tools' own libraries (io, driver, mpm, study) read and write files through yaml-cpp and
# nlohmann-json in their headers and are not installed.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS ecm_material ecm_calibration EXPORT ecmTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/material DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/ecm FILES_MATCHING PATTERN "*.hpp")
install(FILES ${PROJECT_BINARY_DIR}/generated/ecm/version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/ecm/ecm)
# The installed headers cite docs/model.md (the model's decisions), docs/material.md and docs/fe-codes.md (the 3D point and the UMAT); the
# consumer's page is docs/cpp.md. They go to share/doc/ecm/.
install(FILES docs/model.md docs/material.md docs/fe-codes.md docs/cpp.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES calibration/calibration_error.hpp calibration/fracture_energy.hpp calibration/softening_curve.hpp
              calibration/softening_fit.hpp calibration/target_curve.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/ecm/calibration)

set(ecm_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/ecm)
install(EXPORT ecmTargets NAMESPACE ecm:: DESTINATION ${ecm_cmake_dir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/ecmConfig.cmake.in ${PROJECT_BINARY_DIR}/ecmConfig.cmake
                              INSTALL_DESTINATION ${ecm_cmake_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/ecmConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/ecmConfig.cmake ${PROJECT_BINARY_DIR}/ecmConfigVersion.cmake
        DESTINATION ${ecm_cmake_dir})
