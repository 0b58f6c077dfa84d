// Materials and the material-point update from Python: ecm.Material (from a YAML file, a dict or
// keywords, through the same reader as the tools), ecm.PointState (a plain, copyable, picklable
// state: strain, integrity, bands), ecm.UpdateResult, and ecm.PointArray with update_many for
// arrays of points.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <vector>

#include "io/material_yaml.hpp"
#include "io/yaml_input.hpp"
#include "material/material.hpp"
#include "python/src/bindings.hpp"

namespace ecm::python {

namespace {

SnapBackPolicy policyOf(const std::string& s) {
  if (s == "stop") return SnapBackPolicy::Stop;
  if (s == "release") return SnapBackPolicy::Release;
  throw py::value_error("snap_back must be 'stop' or 'release', got '" + s + "'");
}

UpdateOptions optionsOf(bool tangent, const std::string& snapBack, int substepLevels) {
  UpdateOptions o(policyOf(snapBack), tangent);
  if (substepLevels < 0 || substepLevels > 20) throw py::value_error("substep_levels must be in [0, 20]");
  o.substepLevels = substepLevels;
  return o;
}

EffectiveSize sizeOf(double effectiveSize) {
  if (!(effectiveSize > 0.0)) throw py::value_error("effective size H must be > 0 mm");
  return EffectiveSize::fixed(effectiveSize);
}

Material materialFromText(const std::string& text, const std::string& name) {
  return Material(io::readMaterial(io::parseYaml(text, name)));
}

// Pickling: a band as a plain tuple (normal, jump, onset strain, integrity, f).
py::tuple bandTuple(const BandState& b) {
  return py::make_tuple(b.crackNormal, b.jump, b.onsetStrain, b.integrity, b.volumeFraction);
}
BandState bandFromTuple(const py::tuple& t) {
  if (t.size() != 5) throw py::value_error("a BandState is pickled as 5 values");
  BandState b;
  b.crackNormal = t[0].cast<Vec2>();
  b.jump = t[1].cast<Vec2>();
  b.onsetStrain = t[2].cast<Voigt>();
  b.integrity = t[3].cast<double>();
  b.volumeFraction = t[4].cast<double>();
  return b;
}
py::object optionalBand(const std::optional<BandState>& b) { return b ? py::object(bandTuple(*b)) : py::object(py::none()); }
std::optional<BandState> bandFromObject(const py::handle& o) {
  if (o.is_none()) return std::nullopt;
  return bandFromTuple(o.cast<py::tuple>());
}
py::tuple pointTuple(const MaterialPoint& p) {
  return py::make_tuple(p.strain, p.integrity, optionalBand(p.band), optionalBand(p.secondBand));
}
MaterialPoint pointFromTuple(const py::tuple& t) {
  if (t.size() != 4) throw py::value_error("a PointState is pickled as 4 values");
  MaterialPoint p;
  p.strain = t[0].cast<Voigt>();
  p.integrity = t[1].cast<double>();
  p.band = bandFromObject(t[2]);
  p.secondBand = bandFromObject(t[3]);
  return p;
}

}  // namespace

// ecm.PointArray: N points' states side by side.
struct Batch {
  std::vector<MaterialPoint> points;
};

void bindMaterial(py::module_& m) {
  py::class_<BandState>(m, "BandState", "A cracked point's band: normal n, jump [u] (mm), onset strain, integrity 1 - D, f = h/H")
      .def(py::init<>())
      .def_readwrite("crack_normal", &BandState::crackNormal)
      .def_readwrite("jump", &BandState::jump)
      .def_readwrite("onset_strain", &BandState::onsetStrain)
      .def_readwrite("integrity", &BandState::integrity)
      .def_readwrite("volume_fraction", &BandState::volumeFraction)
      .def_property_readonly("damage", &BandState::damage)
      .def_property_readonly("normal_jump", &BandState::normalJump)
      .def(py::pickle([](const BandState& b) { return bandTuple(b); }, [](const py::tuple& t) { return bandFromTuple(t); }))
      .def("__repr__", [](const BandState& b) {
        return "BandState(normal=[" + std::to_string(b.crackNormal[0]) + ", " + std::to_string(b.crackNormal[1]) +
               "], damage=" + std::to_string(b.damage()) + ", normal_jump=" + std::to_string(b.normalJump()) + " mm)";
      });

  py::class_<MaterialPoint>(m, "PointState",
                            "The state of one material point: strain (eps_xx, eps_yy, gamma_xy), the smeared crack's "
                            "integrity, and the enriched point's bands (None while intact). Plain data: copy and pickle it.")
      .def(py::init<>())
      .def(py::init([](const Voigt& strain) {
             MaterialPoint p;
             p.strain = strain;
             return p;
           }),
           py::arg("strain"))
      .def_readwrite("strain", &MaterialPoint::strain)
      .def_readwrite("integrity", &MaterialPoint::integrity)
      .def_readwrite("band", &MaterialPoint::band)
      .def_readwrite("second_band", &MaterialPoint::secondBand)
      .def_property_readonly("damage", &MaterialPoint::damage)
      .def(py::pickle([](const MaterialPoint& p) { return pointTuple(p); }, [](const py::tuple& t) { return pointFromTuple(t); }))
      .def("__copy__", [](const MaterialPoint& p) { return p; })
      .def("__deepcopy__", [](const MaterialPoint& p, const py::dict&) { return p; })
      .def("__repr__", [](const MaterialPoint& p) {
        return "PointState(strain=[" + std::to_string(p.strain[0]) + ", " + std::to_string(p.strain[1]) + ", " +
               std::to_string(p.strain[2]) + "], damage=" + std::to_string(p.damage()) +
               (p.band ? ", cracked" : ", intact") + ")";
      });

  py::class_<UpdateResult>(m, "UpdateResult", "What one update gives: stress (MPa), consistent tangent, dissipation "
                                              "(per unit volume, MPa) and status")
      .def_readonly("stress", &UpdateResult::stress)
      .def_readonly("tangent", &UpdateResult::tangent)
      .def_readonly("dissipation", &UpdateResult::dissipation)
      .def_property_readonly("status", [](const UpdateResult& r) { return std::string(toString(r.status)); })
      .def_property_readonly("converged", &UpdateResult::converged)
      .def_readonly("residual", &UpdateResult::residual)
      .def_readonly("iterations", &UpdateResult::iterations)
      .def_readonly("released", &UpdateResult::released)
      .def_readonly("substeps", &UpdateResult::substeps)
      .def_readonly("refused_size", &UpdateResult::refusedSize)
      .def("__repr__", [](const UpdateResult& r) {
        return "UpdateResult(status='" + std::string(toString(r.status)) + "', stress=[" + std::to_string(r.stress[0]) +
               ", " + std::to_string(r.stress[1]) + ", " + std::to_string(r.stress[2]) + "] MPa)";
      });

  py::class_<Batch>(m, "PointArray", "N material points' states, for Material.update_many")
      .def(py::init([](std::size_t n) { return Batch{std::vector<MaterialPoint>(n)}; }), py::arg("n"))
      .def(py::init([](const std::vector<MaterialPoint>& points) { return Batch{points}; }), py::arg("points"))
      .def("__len__", [](const Batch& b) { return b.points.size(); })
      .def("__getitem__",
           [](const Batch& b, std::size_t i) {
             if (i >= b.points.size()) throw py::index_error("point " + std::to_string(i) + " of " + std::to_string(b.points.size()));
             return b.points[i];
           })
      .def("__setitem__",
           [](Batch& b, std::size_t i, const MaterialPoint& p) {
             if (i >= b.points.size()) throw py::index_error("point " + std::to_string(i) + " of " + std::to_string(b.points.size()));
             b.points[i] = p;
           })
      .def_property_readonly("strain",
                             [](const Batch& b) {
                               py::array_t<double> a({static_cast<py::ssize_t>(b.points.size()), py::ssize_t{3}});
                               auto v = a.mutable_unchecked<2>();
                               for (std::size_t i = 0; i < b.points.size(); ++i)
                                 for (int c = 0; c < 3; ++c) v(static_cast<py::ssize_t>(i), c) = b.points[i].strain[c];
                               return a;
                             })
      .def_property_readonly("damage",
                             [](const Batch& b) {
                               py::array_t<double> a(static_cast<py::ssize_t>(b.points.size()));
                               auto v = a.mutable_unchecked<1>();
                               for (std::size_t i = 0; i < b.points.size(); ++i) v(static_cast<py::ssize_t>(i)) = b.points[i].damage();
                               return a;
                             })
      .def(py::pickle(
          [](const Batch& b) {
            py::list l;
            for (const MaterialPoint& p : b.points) l.append(pointTuple(p));
            return l;
          },
          [](const py::list& l) {
            Batch b;
            for (const auto& t : l) b.points.push_back(pointFromTuple(t.cast<py::tuple>()));
            return b;
          }));

  py::class_<Material>(m, "Material",
                       "A material: model (enriched | smeared_crack | linear_elastic) and parameters, read and checked "
                       "as the tools read a material file (io/material_yaml.hpp). Material(**keys), "
                       "Material.from_file(path) or Material.from_dict(d).")
      .def(py::init([](const py::kwargs& keys) { return materialFromText(yamlText(keys), "<keywords>"); }))
      .def_static("from_file", [](const std::filesystem::path& path) { return Material(io::loadMaterialFile(path)); },
                  py::arg("path"))
      .def_static("from_dict", [](const py::dict& d) { return materialFromText(yamlText(d), "<dict>"); }, py::arg("d"))
      .def_property_readonly("name", [](const Material& mat) { return mat.params().name; })
      .def_property_readonly("model", [](const Material& mat) { return std::string(toString(mat.params().model)); })
      .def_property_readonly("stiffness", &Material::stiffness, "elastic a: strain -> stress (Voigt, engineering shear)")
      .def("to_yaml", [](const Material& mat) { return io::materialYaml(mat.params()); })
      .def(
          "update",
          [](const Material& mat, MaterialPoint& point, const Voigt& increment, double effectiveSize, bool tangent,
             const std::string& snapBack, int substepLevels) {
            return mat.update(point, increment, sizeOf(effectiveSize), optionsOf(tangent, snapBack, substepLevels));
          },
          py::arg("state"), py::arg("strain_increment"), py::arg("H"), py::arg("tangent") = true,
          py::arg("snap_back") = "stop", py::arg("substep_levels") = 0,
          "Updates `state` in place by the strain increment (eps_xx, eps_yy, gamma_xy) in the effective size H (mm); "
          "the state is committed only if the result converged.")
      .def("stress", &Material::stress, py::arg("state"), "the stress (MPa) of a state, without changing it")
      .def(
          "update_many",
          [](const Material& mat, Batch& batch, const py::array_t<double, py::array::c_style | py::array::forcecast>& increments,
             const py::object& effectiveSize, bool tangent, const std::string& snapBack, int substepLevels) {
            const auto n = static_cast<py::ssize_t>(batch.points.size());
            if (increments.ndim() != 2 || increments.shape(0) != n || increments.shape(1) != 3)
              throw py::value_error("strain_increments must be an array of shape (" + std::to_string(n) + ", 3)");
            std::vector<double> sizes;
            if (py::isinstance<py::float_>(effectiveSize) || py::isinstance<py::int_>(effectiveSize)) {
              sizes.assign(static_cast<std::size_t>(n), effectiveSize.cast<double>());
            } else {
              const auto h = effectiveSize.cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
              if (h.ndim() != 1 || h.shape(0) != n) throw py::value_error("H must be a number or an array of shape (" + std::to_string(n) + ",)");
              sizes.assign(h.data(), h.data() + n);
            }
            for (const double h : sizes) sizeOf(h);
            const UpdateOptions options = optionsOf(tangent, snapBack, substepLevels);
            py::array_t<double> stress({n, py::ssize_t{3}}), dissipation(n);
            py::array_t<std::int8_t> status(n);
            py::array_t<double> tangents = tangent ? py::array_t<double>({n, py::ssize_t{3}, py::ssize_t{3}}) : py::array_t<double>();
            const double* d = increments.data();
            double* s = stress.mutable_data();
            double* w = dissipation.mutable_data();
            std::int8_t* st = status.mutable_data();
            double* t = tangent ? tangents.mutable_data() : nullptr;
            {
              py::gil_scoped_release free;
              for (py::ssize_t i = 0; i < n; ++i) {
                const auto k = static_cast<std::size_t>(i);
                const UpdateResult r = mat.update(batch.points[k], Voigt(d[3 * i], d[3 * i + 1], d[3 * i + 2]),
                                                  EffectiveSize::fixed(sizes[k]), options);
                for (int c = 0; c < 3; ++c) s[3 * i + c] = r.stress[c];
                w[i] = r.dissipation;
                st[i] = static_cast<std::int8_t>(r.status);
                if (t)
                  for (int a = 0; a < 3; ++a)
                    for (int b = 0; b < 3; ++b) t[9 * i + 3 * a + b] = r.tangent(a, b);
              }
            }
            py::dict out;
            out["stress"] = stress;
            out["dissipation"] = dissipation;
            out["status"] = status;
            if (tangent) out["tangent"] = tangents;
            return out;
          },
          py::arg("points"), py::arg("strain_increments"), py::arg("H"), py::arg("tangent") = false,
          py::arg("snap_back") = "stop", py::arg("substep_levels") = 0,
          "update() of every point of a PointArray (in place) with the rows of an (N, 3) array of strain increments; "
          "returns a dict of arrays: stress (N, 3), dissipation (N,), status (N,) (an index into ecm.STATUS), and "
          "tangent (N, 3, 3) if asked. The GIL is released while it runs.");

  py::list statuses;
  for (const UpdateStatus s : {UpdateStatus::Converged, UpdateStatus::NotConverged, UpdateStatus::SnapBack, UpdateStatus::SizeTooSmall})
    statuses.append(toString(s));
  m.attr("STATUS") = py::tuple(statuses);
}

}  // namespace ecm::python
