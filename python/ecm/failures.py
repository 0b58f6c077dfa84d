"""The exceptions of a failed ecm-mpm run: one class per failure kind, all RunFailed.

A run that fails (ecm.run_scene with check=True, the default) raises the class of its kind with
the run's message; the kind is data all the way from where the solver detected it (the table is
mpm/core/errors.cpp, the same names as summary.json's failure.kind and one ecm-mpm exit status
each), so a caller catches a kind rather than reading the message:

    try:
        ecm.run_scene("beam.yaml", "out")
    except ecm.NewtonNotConvergedError as e:
        print(e.step, e.likely_limit_point)   # and e.result, e.out: the run's dict and folder

Units: mm (position_mm).
"""
from . import _ecm


class RunFailed(RuntimeError):
    """A run that failed; its outputs so far are in `out`. Attributes: kind (summary.json's
    failure.kind), exit_status (ecm-mpm's), step, particle and position_mm (None where the failure
    has no particle), material_status, residual, likely_limit_point, file (the
    file an output failure could not write), result (run_scene's dict) and
    out (the output folder)."""

    kind = None

    def __init__(self, message, result=None, out=None):
        super().__init__(message)
        self.result = result or {}
        self.out = out
        failure = self.result.get("failure") or {}
        self.exit_status = failure.get("exit_status")
        self.step = failure.get("step")
        self.particle = failure.get("particle")
        self.position_mm = failure.get("position_mm")
        self.material_status = failure.get("material_status")
        self.residual = failure.get("residual")
        self.likely_limit_point = failure.get("likely_limit_point", False)
        self.file = failure.get("file")


# One class per kind of the table, named after it: left_grid -> LeftGridError (output ->
# RunOutputError, beside the module's OutputError for an output folder that cannot be used).
def _class_name(kind):
    return "RunOutputError" if kind == "output" else "".join(w.capitalize() for w in kind.split("_")) + "Error"


FAILURE_CLASSES = {}
for _kind, _status, _meaning in _ecm._failure_kinds():
    _cls = type(_class_name(_kind), (RunFailed,),
                {"kind": _kind, "__doc__": f"A run failed: {_meaning} (failure.kind '{_kind}', ecm-mpm exit status {_status}).",
                 "__module__": "ecm"})
    FAILURE_CLASSES[_kind] = _cls
    globals()[_cls.__name__] = _cls

__all__ = ["RunFailed", "FAILURE_CLASSES"] + [c.__name__ for c in FAILURE_CLASSES.values()]


def raise_for(result, out):
    """Raises the failure of a run_scene result (a no-op unless its status is "failed")."""
    if result.get("status") != "failed":
        return
    failure = result.get("failure") or {}
    cls = FAILURE_CLASSES.get(failure.get("kind"), RunFailed)
    raise cls(result.get("error") or "the run failed", result, out)
