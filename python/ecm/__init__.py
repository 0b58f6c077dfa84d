"""ecm: enriched constitutive models for quasi-brittle fracture, from Python.

Units everywhere: mm, N, MPa, tonne, s (density in t/mm^3).

    import ecm
    concrete = ecm.Material.from_file("data/materials/den-concrete.yaml")
    point = ecm.PointState()
    result = concrete.update(point, [1e-4, 0, 0], effective_size=10.0)  # point updated in place
    run = ecm.run_point("data/point/uniaxial-tension-H10.yaml")  # run.history["sig_xx"], run.summary
    ecm.calibrate(youngs_modulus=32000, tensile_strength=3, fracture_energy=0.11,
                  band_width=0.05, softening_exponent=0.128)["Ep"]

The compiled part is ecm._ecm (python/src/); what the tools read and write is documented in
docs/inputs.md and docs/tools.md, and every function here reads the same inputs the same way.
"""
# Imported under private names: dir(ecm) and `from ecm import *` show the module's own API only.
import json as _json
import os as _os
import tempfile as _tempfile
from dataclasses import dataclass as _dataclass, field as _field

import numpy as _np

from ._ecm import (STATUS, BandState, CalibrationError, CheckpointError, InputError, Material, OutputError,
                   ParameterError, PointArray, PointState, UpdateResult, __version__)
from . import _ecm
from .material import UpdateFailed, fracture_energy, softening_modulus  # noqa: E402 (also wraps Material.update)
from .mpm_output import MpmOutput, read_mpm_output
from . import failures
from .failures import *  # noqa: F401,F403 (RunFailed and one class per failure kind)

__all__ = ["STATUS", "BandState", "CalibrationError", "CheckpointError", "InputError", "Material", "OutputError",
           "ParameterError", "PointArray", "PointState", "UpdateResult", "UpdateFailed", "__version__", "fracture_energy",
           "softening_modulus", "PointRun", "run_point", "run_point_3d", "snapback_study", "calibrate", "fit_softening",
           "run_scene", "load_scene", "MpmOutput", "read_mpm_output"] + failures.__all__


def _path_or_dict(x):
    return _os.fspath(x) if isinstance(x, _os.PathLike) else x


def load_scene(path):
    """Reads a YAML input file of the tools (an ecm-mpm or ecm-point scene, a study, a material)
    as the tools read it, into a dict to change and pass to run_scene, run_point, ...: numbers are
    numbers, strings strings, with YAML's rules as the tools apply them ('1e-6' is a number, which
    PyYAML reads as a string), and relative `file:` references made absolute. Errors in a dict name
    the key path ("<dict>: key 'solver.tolerance': ...")."""
    return _ecm._load_yaml(_os.fspath(path))


@_dataclass
class PointRun:
    """A point run: history (column of history.csv -> array, one entry per row) and summary
    (the content of summary.json)."""
    history: dict = _field(default_factory=dict)
    summary: dict = _field(default_factory=dict)


def run_point(scene, out=None):
    """Runs a point scene (a YAML file's path, or a dict with the same keys) as ecm-point does.
    With `out`, also writes ecm-point's output folder there."""
    columns, rows, summary = _ecm._run_point(_path_or_dict(scene), None if out is None else _os.fspath(out))
    return PointRun({c: rows[:, i].copy() for i, c in enumerate(columns)}, summary)


def run_point_3d(scene, out=None):
    """Runs a 3D point scene (hypothesis: three_dimensional; a YAML file's path or a dict) as
    ecm-point does and returns its history.csv as columns and its summary; the files go to `out`
    (a temporary folder if None)."""
    def read(folder):
        completed, _ = _ecm._run_point_3d(_path_or_dict(scene), _os.fspath(folder))
        table = _np.genfromtxt(_os.path.join(folder, "history.csv"), delimiter=",", names=True)
        with open(_os.path.join(folder, "summary.json")) as f:
            summary = _json.load(f)
        return PointRun({c: _np.asarray(table[c], dtype=float) for c in table.dtype.names}, summary)
    if out is None:
        with _tempfile.TemporaryDirectory(prefix="ecm-point-3d-") as tmp:
            return read(_os.path.join(tmp, "point"))
    return read(out)


def snapback_study(study, out=None):
    """The snap-back study over effective sizes (ecm-point --study): a YAML file's path or a dict.
    Returns {"rows": {column: array over H}, "snapback_size", "critical_size", ...}; the study's
    files go to `out` (a temporary folder if None)."""
    if out is None:
        with _tempfile.TemporaryDirectory(prefix="ecm-study-") as tmp:
            return _ecm._snapback_study(_path_or_dict(study), _os.path.join(tmp, "study"))
    return _ecm._snapback_study(_path_or_dict(study), _os.fspath(out))


def calibrate(file=None, out=None, **keys):
    """ecm-calibrate: the keys of a calibration input file as keywords (youngs_modulus,
    tensile_strength, fracture_energy, band_width, softening_exponent, softening_modulus,
    smeared_element_size, fit="hordijk", fit_csv=...), and/or the file itself (keywords win).
    Returns the summary (summary.json's content); with `out`, writes the tool's files there.
    write_material="m.yaml" and write_umat="card.inp" (with element_sizes=[2.5, ...] in mm and
    umat_dialect="calculix" or "abaqus") write the calibrated material and ecm's UMAT card as
    ecm-calibrate --write-material and --write-umat do (both need poisson_ratio)."""
    return _ecm._calibrate(None if file is None else _os.fspath(file), keys, None, None,
                           None if out is None else _os.fspath(out))


def fit_softening(w, traction, out=None, **keys):
    """Fits (E_p, n) to measured points (w in mm, traction in MPa) while dissipating exactly G_F,
    as ecm-calibrate --fit-csv does with the same points. keys: youngs_modulus, tensile_strength,
    fracture_energy, band_width. Returns the summary ("n", "Ep", "fit_residual", ...)."""
    w = _np.asarray(w, dtype=float).ravel().tolist()
    traction = _np.asarray(traction, dtype=float).ravel().tolist()
    return _ecm._calibrate(None, keys, w, traction, None if out is None else _os.fspath(out))


def run_scene(scene, out, threads=0, preset=None, snapshots=True, plot=True, restart=False, max_steps=0,
              progress=None, check=True):
    """Runs an ecm-mpm scene (a YAML file's path or a dict) into the folder `out`, as ecm-mpm does.
    progress(time, end_time, step) is called at every history row (time and end_time in s; the
    pseudo-time of an implicit scene); returning False (or raising, or Ctrl-C) stops the run with a
    checkpoint (resume with restart=True). A progress that is not callable is refused before the
    run (TypeError). The GIL is released while the run goes on. Returns a dict of the same keys
    for every scheme: status ("completed", "stopped" or "failed"), completed, stopped, error (the
    failure's message; None unless failed), failure (None unless failed: summary.json's failure,
    kind and where, with the message), steps, particles, peak_load_N (N), wall_time_s (s),
    checkpoint (path or None); read the folder with read_mpm_output(out).

    A run that fails raises its kind's exception (a RunFailed: ecm.NewtonNotConvergedError,
    ecm.LeftGridError, ...; ecm.failures lists them) after its outputs are closed, unless
    check=False, which returns the dict with status "failed" instead."""
    if progress is not None and not callable(progress):
        raise TypeError(f"progress must be callable as progress(time, end_time, step) or None, got {type(progress).__name__}")
    result = _ecm._run_scene(_path_or_dict(scene), _os.fspath(out), threads, preset, snapshots, plot, restart, max_steps,
                             progress)
    if check:
        failures.raise_for(result, _os.fspath(out))
    return result
