"""The material point from Python, as Python expects it (imported into `ecm`):

- `Material.update(state, strain_increment, H)` raises `ecm.UpdateFailed` (with the update's
  `status` and `result`) when the update does not converge; `check=False` returns the result
  instead, for callers that read `.status` themselves. `update_many` likewise, naming the points.
- A strain increment that is not three numbers is a TypeError that says what is expected.
- `softening_modulus` and `fracture_energy` take the keys of a material file (youngs_modulus,
  tensile_strength, ...), as `Material(...)` and `calibrate(...)` do, and `update` the scenes'
  `effective_size`; the former short names (E, ft, n, GF, h, Ep; H) still work for now, with a
  DeprecationWarning.

Units: mm, N, MPa (strains dimensionless, engineering shear)."""
import warnings as _warnings

import numpy as _np

from . import _ecm

# The keys of a material file (io/material_yaml.hpp), with symbol and unit, for help(ecm.Material).
MATERIAL_KEYS = (
    ("name", "", "a name for messages and outputs"),
    ("model", "", "enriched | smeared_crack | linear_elastic"),
    ("hypothesis", "", "plane_stress | plane_strain | three_dimensional"),
    ("youngs_modulus", "E", "MPa"),
    ("poisson_ratio", "nu", "-"),
    ("density", "rho", "t/mm^3, optional"),
    ("tensile_strength", "f_t'", "MPa; smeared_crack, enriched"),
    ("softening_modulus", "E_p", "MPa; smeared_crack, enriched"),
    ("softening_exponent", "n", "-, 0 < n < 0.5; smeared_crack, enriched"),
    ("band_width", "h", "mm; enriched"),
    ("second_band", "", "off | orthogonal; enriched"),
    ("fracture_energy", "G_F", "N/mm, optional (informational, or the crack band's target)"),
    ("regularised_for_size", "H", "mm; smeared_crack: E_p becomes the crack-band value for H"),
    ("file", "", "a material file to read instead (relative to the scene, then data/materials/)"),
)


class UpdateFailed(RuntimeError):
    """A material-point update that did not converge (a RuntimeError). `status` is the update's
    ("not converged", "snap-back", "effective size too small"; ecm.STATUS), `result` what it returned; the
    state was left as it was. Pass check=False to get the result instead of the exception."""

    def __init__(self, message, status, result):
        super().__init__(message)
        self.status = status
        self.result = result


def _increment(value, name="strain_increment"):
    try:
        array = _np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise TypeError("%s must be three numbers (eps_xx, eps_yy, gamma_xy), got %r" % (name, value)) from None
    if array.shape != (3,):
        raise TypeError("%s must be three numbers (eps_xx, eps_yy, gamma_xy), got shape %s" % (name, array.shape))
    return array


_compiled_update = _ecm.Material.update
_compiled_update_many = _ecm.Material.update_many


def _effective_size(function, effective_size, H):
    """The effective size from effective_size= (the scenes' key) or the former H= (deprecated)."""
    if H is not None:
        if effective_size is not None:
            raise TypeError("%s() takes effective_size, not both it and H" % function)
        _warnings.warn("%s(H=...): the keyword is now effective_size, the scenes' key" % function, DeprecationWarning,
                       stacklevel=3)
        return H
    if effective_size is None:
        raise TypeError("%s() needs effective_size, the effective size H (mm)" % function)
    return effective_size


def _update(self, state, strain_increment, effective_size=None, tangent=True, snap_back="release", substep_levels=0,
            check=True, H=None):
    """Updates `state` (a PointState) in place by the strain increment (eps_xx, eps_yy, gamma_xy)
    in the effective size H (`effective_size`, mm; the third argument); the state is committed
    only if the update converged. Returns an
    UpdateResult (stress in MPa, tangent, dissipation per unit volume in MPa, status, ...).
    snap_back: release (default) | stop; substep_levels: sub-steps 2 .. 2^levels of an update that
    does not converge. Raises ecm.UpdateFailed (with .status) if it did not converge, unless
    check=False, which returns the result to read .status from."""
    size = _effective_size("update", effective_size, H)
    result = _compiled_update(self, state, _increment(strain_increment), size, tangent, snap_back, substep_levels)
    if check and not result.converged:
        raise UpdateFailed("the update did not converge: %s (the state is unchanged; check=False returns the result)"
                           % result.status, result.status, result)
    return result


def _update_many(self, points, strain_increments, effective_size=None, tangent=False, snap_back="release",
                 substep_levels=0, check=True, H=None):
    """update() of every point of a PointArray (in place) with the rows of an (N, 3) array of
    strain increments; effective_size H (mm) a number or one per point. Returns a dict of arrays: stress (N, 3),
    dissipation (N,), status (N,) (an index into ecm.STATUS), and tangent (N, 3, 3) if asked. The
    GIL is released while it runs. If any point did not converge (its state unchanged, the others
    updated), raises ecm.UpdateFailed naming them, with the dict as .result, unless check=False."""
    size = _effective_size("update_many", effective_size, H)
    out = _compiled_update_many(self, points, strain_increments, size, tangent, snap_back, substep_levels)
    failed = _np.flatnonzero(out["status"] != 0)
    if check and failed.size:
        first = _ecm.STATUS[int(out["status"][failed[0]])]
        raise UpdateFailed("%d of %d updates did not converge (first: point %d, %s); those points are unchanged, the "
                           "others updated; check=False returns the arrays" % (failed.size, len(out["status"]),
                                                                              failed[0], first), first, out)
    return out


_ecm.Material.update = _update
_ecm.Material.update_many = _update_many
_ecm.Material.__doc__ = (
    "A material: model (enriched | smeared_crack | linear_elastic) and parameters, read and checked as the tools "
    "read a material file. Material(**keys), Material.from_file(path) or Material.from_dict(d). Keys "
    "(units: mm, N, MPa, tonne):\n" + "\n".join("    %-21s %-5s %s" % k for k in MATERIAL_KEYS))

_OLD_NAMES = {"E": "youngs_modulus", "ft": "tensile_strength", "n": "softening_exponent", "GF": "fracture_energy",
              "h": "band_width", "Ep": "softening_modulus"}


def _keys(function, given, needed):
    keys = {}
    for name, value in given.items():
        if name in _OLD_NAMES:
            _warnings.warn("%s(%s=...): the keyword is now %s, the material file's key" % (function, name, _OLD_NAMES[name]),
                           DeprecationWarning, stacklevel=3)
            name = _OLD_NAMES[name]
        if name not in needed:
            raise TypeError("%s() takes %s, not %s" % (function, ", ".join(needed), name))
        keys[name] = value
    missing = [k for k in needed if k not in keys]
    if missing:
        raise TypeError("%s() needs %s" % (function, ", ".join(missing)))
    return keys


def softening_modulus(**keys):
    """E_p (MPa) such that a band of width band_width h (mm) with youngs_modulus E (MPa),
    tensile_strength f_t' (MPa) and softening_exponent n dissipates fracture_energy G_F (N/mm)."""
    k = _keys("softening_modulus", keys, ("youngs_modulus", "tensile_strength", "softening_exponent", "fracture_energy",
                                          "band_width"))
    return _ecm.softening_modulus(k["youngs_modulus"], k["tensile_strength"], k["softening_exponent"],
                                  k["fracture_energy"], k["band_width"])


def fracture_energy(**keys):
    """G_F (N/mm) = h int_0^1 F(D) dD of the band's damage law (Eq. (13)), from youngs_modulus E
    (MPa), tensile_strength f_t' (MPa), softening_modulus E_p (MPa), softening_exponent n and
    band_width h (mm)."""
    k = _keys("fracture_energy", keys, ("youngs_modulus", "tensile_strength", "softening_modulus",
                                        "softening_exponent", "band_width"))
    return _ecm.fracture_energy(k["youngs_modulus"], k["tensile_strength"], k["softening_modulus"],
                                k["softening_exponent"], k["band_width"])
