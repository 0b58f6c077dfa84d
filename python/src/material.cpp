// Materials and the material-point update from Python: ecm.Material (from a YAML file, a dict or
// keywords, through the same reader as the tools), ecm.PointState (a plain, copyable, picklable
// state: strain, integrity, bands), ecm.UpdateResult, and ecm.PointArray with update_many for
// arrays of points.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <sstream>
#include <vector>

#include "io/material_yaml.hpp"
#include "io/yaml_input.hpp"
#include "material/material.hpp"
#include "python/src/bindings.hpp"

namespace ecm::python {

namespace {

SnapBackPolicy policyOf(const std::string& s) {
  if (const std::optional<SnapBackPolicy> p = snapBackPolicyOf(s)) return *p;
  throw py::value_error("snap_back must be 'stop' or 'release', got '" + s + "'");
}

UpdateOptions optionsOf(bool tangent, const std::string& snapBack, int substepLevels) {
  UpdateOptions o(policyOf(snapBack), tangent);
  if (substepLevels < 0 || substepLevels > 20) throw py::value_error("substep_levels must be in [0, 20]");
  o.substepLevels = substepLevels;
  return o;
}

std::string number(double v) {
  std::ostringstream o;
  o.precision(17);
  o << v;
  return o.str();
}

// The checks of a state given from Python (the C++ update trusts its caller): every number
// finite, a unit crack normal, integrity x = 1 - D in (0, 1], f = h/H in (0, 1 / (1 + 1e-6)]
// (H >= h (1 + 1e-6), docs/model.md "The smallest effective size").
void checkFinite(const auto& v, const std::string& what) {
  if (!v.allFinite()) throw py::value_error(what + " must be finite");
}
void checkIntegrity(double x, const std::string& what) {
  if (!(x > 0.0 && x <= 1.0)) throw py::value_error(what + " (1 - D) must be in (0, 1], got " + number(x));
}
void checkNormal(const Vec2& n, const std::string& what) {
  if (!n.allFinite() || !(std::abs(n.norm() - 1.0) <= 1e-6))
    throw py::value_error(what + " must be a unit vector, got [" + number(n[0]) + ", " + number(n[1]) + "]");
}
void checkVolumeFraction(double f, const std::string& what) {
  if (!(f > 0.0 && f <= 1.0 / (1.0 + kMinimumSizeMargin)))
    throw py::value_error(what + " (f = h/H) must be in (0, 1/(1 + 1e-6)], got " + number(f));
}
void checkBand(const BandState& b, const std::string& what) {
  checkNormal(b.crackNormal, what + ".crack_normal");
  checkFinite(b.jump, what + ".jump");
  checkFinite(b.onsetStrain, what + ".onset_strain");
  checkIntegrity(b.integrity, what + ".integrity");
  checkVolumeFraction(b.volumeFraction, what + ".volume_fraction");
}
void checkPoint(const MaterialPoint& p) {
  checkFinite(p.strain, "PointState.strain");
  checkIntegrity(p.integrity, "PointState.integrity");
  if (p.band) checkBand(*p.band, "PointState.band");
  if (p.secondBand) {
    if (!p.band) throw py::value_error("PointState.second_band needs a first band");
    checkBand(*p.secondBand, "PointState.second_band");
  }
}

// H (mm) for this material: finite, > 0, and for the enriched model at least its smallest size.
EffectiveSize sizeOf(const Material& mat, double effectiveSize) {
  if (!(effectiveSize > 0.0 && std::isfinite(effectiveSize)))
    throw py::value_error("effective size H must be a finite number > 0 mm, got " + number(effectiveSize));
  const MaterialParams& p = mat.params();
  if (p.model == ModelKind::Enriched)
    if (const std::string problem = effectiveSizeProblem(effectiveSize, p.bandWidth, p.secondBand == SecondBandOption::Off ? 1 : 2);
        !problem.empty())
      throw py::value_error("effective size H: " + problem);
  return EffectiveSize::fixed(effectiveSize);
}

Material materialFromDict(const py::handle& keys, const std::string& name) {
  return Material(readDict(keys, name, [](const io::YamlMap& m) { return io::readMaterial(m); }));
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
  checkBand(b, "BandState");
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
  checkPoint(p);
  return p;
}

}  // namespace

// ecm.PointArray: N points' states side by side.
struct Batch {
  std::vector<MaterialPoint> points;
};

void bindMaterial(py::module_& m) {
  py::class_<BandState>(m, "BandState",
                        "A cracked point's band (docs/model.md): crack_normal n (unit vector, fixed at onset), jump [u] "
                        "(mm, since onset), onset_strain (eps_xx, eps_yy, gamma_xy at onset), integrity x = 1 - D in (0, 1] "
                        "and volume_fraction f = h/H in (0, 1). Values are checked when set; a band is checked as a whole "
                        "when it is given to a PointState or an update.")
      .def(py::init<>())
      .def_property(
          "crack_normal", [](const BandState& b) { return b.crackNormal; },
          [](BandState& b, const Vec2& n) { checkNormal(n, "BandState.crack_normal"), b.crackNormal = n; },
          "the band's normal n (unit vector), fixed at onset")
      .def_property(
          "jump", [](const BandState& b) { return b.jump; },
          [](BandState& b, const Vec2& j) { checkFinite(j, "BandState.jump"), b.jump = j; },
          "the displacement jump [u] across the band since onset (x, y; mm)")
      .def_property(
          "onset_strain", [](const BandState& b) { return b.onsetStrain; },
          [](BandState& b, const Voigt& e) { checkFinite(e, "BandState.onset_strain"), b.onsetStrain = e; },
          "the strain of both phases at onset (eps_xx, eps_yy, gamma_xy; engineering shear)")
      .def_property(
          "integrity", [](const BandState& b) { return b.integrity; },
          [](BandState& b, double x) { checkIntegrity(x, "BandState.integrity"), b.integrity = x; },
          "x = 1 - D of the band, in (0, 1]")
      .def_property(
          "volume_fraction", [](const BandState& b) { return b.volumeFraction; },
          [](BandState& b, double f) { checkVolumeFraction(f, "BandState.volume_fraction"), b.volumeFraction = f; },
          "f = h/H, Eq. (1), in (0, 1/(1 + 1e-6)]")
      .def_property_readonly("damage", &BandState::damage, "D = 1 - integrity")
      .def_property_readonly("normal_jump", &BandState::normalJump, "[u] . n (mm): the band's opening")
      .def(py::pickle([](const BandState& b) { return bandTuple(b); }, [](const py::tuple& t) { return bandFromTuple(t); }))
      .def("__repr__", [](const BandState& b) {
        return "BandState(normal=[" + std::to_string(b.crackNormal[0]) + ", " + std::to_string(b.crackNormal[1]) +
               "], damage=" + std::to_string(b.damage()) + ", normal_jump=" + std::to_string(b.normalJump()) + " mm)";
      });

  const auto optionalBandSetter = [](const char* what) {
    return [what](MaterialPoint& p, const std::optional<BandState>& b, std::optional<BandState> MaterialPoint::*member) {
      if (b) checkBand(*b, what);
      p.*member = b;
    };
  };
  py::class_<MaterialPoint>(m, "PointState",
                            "The state of one material point: strain (eps_xx, eps_yy, gamma_xy; engineering shear), the "
                            "smeared crack's integrity 1 - D, and the enriched point's bands (None while intact). Plain "
                            "data: copy and pickle it. Values are checked when set and before every update.")
      .def(py::init<>())
      .def(py::init([](const Voigt& strain) {
             checkFinite(strain, "PointState.strain");
             MaterialPoint p;
             p.strain = strain;
             return p;
           }),
           py::arg("strain"))
      .def_property(
          "strain", [](const MaterialPoint& p) { return p.strain; },
          [](MaterialPoint& p, const Voigt& e) { checkFinite(e, "PointState.strain"), p.strain = e; },
          "the macroscopic strain (eps_xx, eps_yy, gamma_xy; engineering shear)")
      .def_property(
          "integrity", [](const MaterialPoint& p) { return p.integrity; },
          [](MaterialPoint& p, double x) { checkIntegrity(x, "PointState.integrity"), p.integrity = x; },
          "x = 1 - D of a smeared-crack point, in (0, 1] (1 for the other models)")
      .def_property(
          "band", [](const MaterialPoint& p) { return p.band; },
          [setter = optionalBandSetter("PointState.band")](MaterialPoint& p, const std::optional<BandState>& b) {
            setter(p, b, &MaterialPoint::band);
          },
          "the enriched point's band (a BandState, a copy), None while intact")
      .def_property(
          "second_band", [](const MaterialPoint& p) { return p.secondBand; },
          [setter = optionalBandSetter("PointState.second_band")](MaterialPoint& p, const std::optional<BandState>& b) {
            setter(p, b, &MaterialPoint::secondBand);
          },
          "the second band (second_band: orthogonal; a BandState, a copy), None until it opens")
      .def_property_readonly("damage", &MaterialPoint::damage, "D of the (first) band, or of the smeared crack")
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
      .def_readonly("stress", &UpdateResult::stress, "(sig_xx, sig_yy, sig_xy) at the end of the increment (MPa)")
      .def_readonly("tangent", &UpdateResult::tangent,
                    "the consistent tangent d sigma / d eps (3 x 3, MPa; engineering shear), Eq. (10)")
      .def_readonly("dissipation", &UpdateResult::dissipation,
                    "energy dissipated in this increment per unit volume (MPa = N mm / mm^3), >= 0")
      .def_property_readonly(
          "status", [](const UpdateResult& r) { return std::string(toString(r.status)); },
          "'converged', 'not_converged', 'snap_back' or 'size_too_small' (the entries of ecm.STATUS)")
      .def_property_readonly("converged", &UpdateResult::converged, "whether the state was updated")
      .def_readonly("residual", &UpdateResult::residual, "the traction-continuity residual of Eq. (6) at the end (MPa)")
      .def_readonly("iterations", &UpdateResult::iterations, "Newton iterations taken")
      .def_readonly("released", &UpdateResult::released,
                    "whether a snap-back was released onto the stable branch (snap_back='release')")
      .def_readonly("substeps", &UpdateResult::substeps, "the sub-steps the increment was taken in (1: none)")
      .def_readonly("refused_size", &UpdateResult::refusedSize,
                    "with status 'size_too_small': the effective size H (mm) that was refused")
      .def("__repr__", [](const UpdateResult& r) {
        return "UpdateResult(status='" + std::string(toString(r.status)) + "', stress=[" + std::to_string(r.stress[0]) +
               ", " + std::to_string(r.stress[1]) + ", " + std::to_string(r.stress[2]) + "] MPa)";
      });

  // A Python index (negative from the end) into n points.
  const auto index = [](py::ssize_t i, std::size_t n) {
    const py::ssize_t size = static_cast<py::ssize_t>(n);
    if (i < -size || i >= size) throw py::index_error("point " + std::to_string(i) + " of " + std::to_string(n));
    return static_cast<std::size_t>(i < 0 ? i + size : i);
  };
  py::class_<Batch>(m, "PointArray",
                    "N material points' states (PointState each), for Material.update_many. p[i] is a copy of point i "
                    "(negative i from the end); p[i] = state sets it. strain is an (N, 3) array (eps_xx, eps_yy, "
                    "gamma_xy), damage an (N,) array of D.")
      .def(py::init([](std::size_t n) { return Batch{std::vector<MaterialPoint>(n)}; }), py::arg("n"), "n intact points")
      .def(py::init([](const std::vector<MaterialPoint>& points) {
             for (const MaterialPoint& p : points) checkPoint(p);
             return Batch{points};
           }),
           py::arg("points"), "copies of the given PointStates")
      .def("__len__", [](const Batch& b) { return b.points.size(); })
      .def("__getitem__", [index](const Batch& b, py::ssize_t i) { return b.points[index(i, b.points.size())]; })
      .def("__setitem__",
           [index](Batch& b, py::ssize_t i, const MaterialPoint& p) {
             const std::size_t k = index(i, b.points.size());
             checkPoint(p);
             b.points[k] = p;
           })
      .def_property_readonly("strain",
                             [](const Batch& b) {
                               py::array_t<double> a({static_cast<py::ssize_t>(b.points.size()), py::ssize_t{3}});
                               auto v = a.mutable_unchecked<2>();
                               for (std::size_t i = 0; i < b.points.size(); ++i)
                                 for (int c = 0; c < 3; ++c) v(static_cast<py::ssize_t>(i), c) = b.points[i].strain[c];
                               return a;
                             },
                             "(N, 3) array of the strains (eps_xx, eps_yy, gamma_xy), a copy")
      .def_property_readonly("damage",
                             [](const Batch& b) {
                               py::array_t<double> a(static_cast<py::ssize_t>(b.points.size()));
                               auto v = a.mutable_unchecked<1>();
                               for (std::size_t i = 0; i < b.points.size(); ++i) v(static_cast<py::ssize_t>(i)) = b.points[i].damage();
                               return a;
                             },
                             "(N,) array of the damage D, a copy")
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
      .def(py::init([](const py::kwargs& keys) { return materialFromDict(keys, "<keywords>"); }))
      .def_static("from_file", [](const std::filesystem::path& path) { return Material(io::loadMaterialFile(path)); },
                  py::arg("path"))
      .def_static("from_dict", [](const py::dict& d) { return materialFromDict(d, "<dict>"); }, py::arg("d"))
      .def_property_readonly("name", [](const Material& mat) { return mat.params().name; })
      .def_property_readonly("model", [](const Material& mat) { return std::string(toString(mat.params().model)); })
      .def_property_readonly("stiffness", &Material::stiffness, "elastic a: strain -> stress (Voigt, engineering shear)")
      .def("to_yaml", [](const Material& mat) { return io::materialYaml(mat.params()); })
      .def(
          "update",
          [](const Material& mat, MaterialPoint& point, const Voigt& increment, double effectiveSize, bool tangent,
             const std::string& snapBack, int substepLevels) {
            checkPoint(point);
            checkFinite(increment, "strain_increment");
            return mat.update(point, increment, sizeOf(mat, effectiveSize), optionsOf(tangent, snapBack, substepLevels));
          },
          py::arg("state"), py::arg("strain_increment"), py::arg("H"), py::arg("tangent") = true,
          py::arg("snap_back") = toString(kDefaultSnapBack), py::arg("substep_levels") = 0,
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
            // H: a number (a NumPy scalar included) or one per point.
            const auto h = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(effectiveSize);
            if (!h || !(h.ndim() == 0 || (h.ndim() == 1 && h.shape(0) == n))) {
              PyErr_Clear();
              throw py::value_error("H must be a number or an array of shape (" + std::to_string(n) + ",)");
            }
            std::vector<double> sizes(static_cast<std::size_t>(n), h.ndim() == 0 ? *h.data() : 0.0);
            if (h.ndim() == 1) sizes.assign(h.data(), h.data() + n);
            for (const double size : sizes) sizeOf(mat, size);
            for (const MaterialPoint& p : batch.points) checkPoint(p);
            for (py::ssize_t i = 0; i < 3 * n; ++i)
              if (!std::isfinite(increments.data()[i])) throw py::value_error("strain_increments must be finite");
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
          py::arg("snap_back") = toString(kDefaultSnapBack), py::arg("substep_levels") = 0,
          "update() of every point of a PointArray (in place) with the rows of an (N, 3) array of strain increments; "
          "returns a dict of arrays: stress (N, 3), dissipation (N,), status (N,) (an index into ecm.STATUS), and "
          "tangent (N, 3, 3) if asked. The GIL is released while it runs.");

  py::list statuses;
  for (const UpdateStatus s : {UpdateStatus::Converged, UpdateStatus::NotConverged, UpdateStatus::SnapBack, UpdateStatus::SizeTooSmall})
    statuses.append(toString(s));
  m.attr("STATUS") = py::tuple(statuses);
}

}  // namespace ecm::python
