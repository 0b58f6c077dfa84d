"""ecm-mpm runs from Python: the tool's folder bit for bit, the progress callback, stopping and
resuming through it (bitwise the uninterrupted run), the GIL released while the run goes on, and
bad input with the tool's message. The scene is the elastic bar (data/mpm/elastic-bar.yaml), a
fraction of a second per run."""
import threading
import time

import numpy as np
import pytest

import ecm
from conftest import run_tool


def test_a_run_writes_the_folder_the_tool_writes(source, tmp_path):
    scene = source / "data/mpm/elastic-bar.yaml"
    status, err = run_tool("ecm-mpm", scene, "-o", tmp_path / "cli", "--no-vtu", "--no-plot", "-q", "-t", 1)
    assert status == 0, err
    rows = []
    result = ecm.run_scene(scene, tmp_path / "py", threads=1, snapshots=False, plot=False,
                           progress=lambda t, end, step: rows.append((t, end, step)))
    assert result["completed"] and not result["error"]
    assert (tmp_path / "py/history.csv").read_bytes() == (tmp_path / "cli/history.csv").read_bytes()
    assert (tmp_path / "py/particles_final.csv").read_bytes() == (tmp_path / "cli/particles_final.csv").read_bytes()
    out = ecm.read_mpm_output(tmp_path / "py")
    assert len(rows) == len(out.history["step"]) - 1  # every row but the one at t = 0
    assert rows[-1][2] == result["steps"] == out.summary["steps"]
    assert np.array_equal(out.history["step"][1:], [r[2] for r in rows])
    assert out.particles["x_mm"].shape == (result["particles"],)


def test_a_callback_that_returns_false_stops_with_a_checkpoint_and_the_run_resumes_bitwise(source, tmp_path):
    scene = source / "data/mpm/elastic-bar.yaml"
    ecm.run_scene(scene, tmp_path / "whole", threads=1, snapshots=False, plot=False)
    stopped = ecm.run_scene(scene, tmp_path / "parts", threads=1, snapshots=False, plot=False,
                            progress=lambda t, end, step: t < 0.4 * end)
    assert stopped["stopped"] and stopped["checkpoint"]
    resumed = ecm.run_scene(scene, tmp_path / "parts", threads=2, snapshots=False, plot=False, restart=True)
    assert resumed["completed"]
    assert (tmp_path / "parts/history.csv").read_bytes() == (tmp_path / "whole/history.csv").read_bytes()


def test_an_exception_in_the_callback_stops_the_run_and_is_raised(source, tmp_path):
    def boom(t, end, step):
        raise KeyError("from the callback")
    with pytest.raises(KeyError, match="from the callback"):
        ecm.run_scene(source / "data/mpm/elastic-bar.yaml", tmp_path / "out", threads=1, snapshots=False, plot=False,
                      progress=boom)
    assert (tmp_path / "out/checkpoint.bin").exists()


def test_the_gil_is_released_while_a_run_goes_on(source, tmp_path):
    done = threading.Event()
    ticks = 0

    def run():
        ecm.run_scene(source / "data/mpm/elastic-bar.yaml", tmp_path / "out", threads=1, snapshots=False, plot=False)
        done.set()

    worker = threading.Thread(target=run)
    start = time.perf_counter()
    worker.start()
    while not done.is_set():  # Python keeps running beside the run: it holds no GIL
        ticks += 1
    worker.join()
    assert time.perf_counter() - start > 0.05 and ticks > 1000


def test_bad_input_raises_the_message_the_tool_prints(source, tmp_path):
    bad = tmp_path / "bad.yaml"
    text = (source / "data/mpm/elastic-bar.yaml").read_text().replace("cfl: 0.3", "cfl: 3.0")
    bad.write_text(text)
    status, err = run_tool("ecm-mpm", bad, "-o", tmp_path / "cli", "-q")
    assert status == 2
    with pytest.raises(ecm.InputError) as raised:
        ecm.run_scene(bad, tmp_path / "py")
    assert str(raised.value) in err and "cfl" in str(raised.value)


def test_an_implicit_scene_runs_as_the_tool_runs_it(source, tmp_path):
    """The bar of data/mpm/bar-snapback-implicit.yaml through its peak (0.002 mm of opening, 200
    load steps): the same folder as ecm-mpm writes, bit for bit, and the implicit columns and
    summary read back; the peak is the weak row's strength times the bar's section."""
    text = (source / "data/mpm/bar-snapback-implicit.yaml").read_text()
    scene = tmp_path / "bar.yaml"
    scene.write_text(text.replace("until: 0.04 ", "until: 0.002"))
    status, err = run_tool("ecm-mpm", scene, "-o", tmp_path / "cli", "--no-vtu", "--no-plot", "-q", "-t", 1)
    assert status == 0, err
    result = ecm.run_scene(scene, tmp_path / "py", threads=2, snapshots=False, plot=False)
    assert result["completed"] and result["steps"] == 200
    assert (tmp_path / "py/history.csv").read_bytes() == (tmp_path / "cli/history.csv").read_bytes()
    out = ecm.read_mpm_output(tmp_path / "py")
    assert out.summary["scheme"] == "implicit_static" and out.summary["relaxed_steps"] == 0
    assert out.summary["energy_balance"] < 1e-3
    assert np.all(np.diff(out.history["load_factor"][:80]) > 0.0)  # the top rises to the peak
    assert abs(result["peak_load_N"] - 2.9 * 20.0) < 1e-3 * 2.9 * 20.0


def test_a_progress_that_is_not_callable_is_refused_before_the_run(source, tmp_path):
    # Issue: progress=5 ran to the first row, then raised TypeError and left a checkpoint.
    with pytest.raises(TypeError, match="progress must be callable"):
        ecm.run_scene(source / "data/mpm/elastic-bar.yaml", tmp_path / "out", progress=5)
    assert not (tmp_path / "out").exists()


def test_a_stopped_run_returns_the_same_dict_for_every_scheme(source, tmp_path):
    # Issue: after a callback stop, 'error' was '' for the explicit scheme and a message for the implicit one.
    text = (source / "data/mpm/bar-snapback-implicit.yaml").read_text()
    implicit = tmp_path / "bar.yaml"
    implicit.write_text(text.replace("until: 0.04 ", "until: 0.002"))
    results = [ecm.run_scene(scene, tmp_path / name, threads=1, snapshots=False, plot=False,
                             progress=lambda t, end, step: step < 3)
               for scene, name in ((source / "data/mpm/elastic-bar.yaml", "explicit"), (implicit, "implicit"))]
    for r in results:
        assert r["status"] == "stopped" and r["stopped"] and not r["completed"] and r["error"] is None
        assert r["checkpoint"]
    assert results[0].keys() == results[1].keys()


def test_a_scene_loaded_with_load_scene_runs_as_its_file(source, tmp_path):
    scene = ecm.load_scene(source / "data/mpm/elastic-bar.yaml")
    ecm.run_scene(scene, tmp_path / "dict", threads=1, snapshots=False, plot=False)
    ecm.run_scene(source / "data/mpm/elastic-bar.yaml", tmp_path / "file", threads=1, snapshots=False, plot=False)
    assert (tmp_path / "dict/history.csv").read_bytes() == (tmp_path / "file/history.csv").read_bytes()


# A failed run: its kind travels as data (mpm/core/errors.hpp) to the exit status, summary.json and
# the exception. The implicit bar asked for a tolerance below round-off (1e-16, and the same to
# accept a stalled step) cannot converge its first step: newton_not_converged, exit status 14.
def _unconvergeable_bar(source, tmp_path):
    text = (source / "data/mpm/bar-snapback-implicit.yaml").read_text()
    text = text.replace("until: 0.04 ", "until: 0.0002").replace(
        "tolerance: 1e-6 ", "tolerance: 1e-16\n  accept_tolerance: 1e-16\n  max_iterations: 2\n  max_halvings: 2\n")
    scene = tmp_path / "bar.yaml"
    scene.write_text(text)
    return scene


def test_every_failure_kind_has_its_own_exception_class():
    kinds = ecm._ecm._failure_kinds()
    assert len(kinds) == len(ecm.failures.FAILURE_CLASSES) == len({c for c in ecm.failures.FAILURE_CLASSES.values()})
    for name, status, meaning in kinds:
        cls = ecm.failures.FAILURE_CLASSES[name]
        assert issubclass(cls, ecm.RunFailed) and issubclass(cls, RuntimeError)
        assert cls.kind == name and getattr(ecm, cls.__name__) is cls and cls.__name__ in ecm.__all__
        assert str(status) in cls.__doc__ and meaning in cls.__doc__


def test_a_failed_run_raises_its_kind_and_the_tool_exits_with_its_status(source, tmp_path):
    scene = _unconvergeable_bar(source, tmp_path)
    status, err = run_tool("ecm-mpm", scene, "-o", tmp_path / "cli", "--no-vtu", "--no-plot", "-q", "-t", 1)
    assert status == 14, err  # newton_not_converged (io/cli_exit.hpp, mpm/core/errors.cpp)
    summary = ecm.read_mpm_output(tmp_path / "cli").summary
    assert summary["status"] == "failed" and summary["failure"]["kind"] == "newton_not_converged"
    assert summary["failure"]["exit_status"] == 14 and summary["failure"]["step"] == 1
    with pytest.raises(ecm.NewtonNotConvergedError) as raised:
        ecm.run_scene(scene, tmp_path / "py", threads=1, snapshots=False, plot=False)
    e = raised.value
    assert e.kind == "newton_not_converged" and e.exit_status == 14 and e.step == 1
    assert not e.likely_limit_point  # nothing has cracked yet
    assert e.out == str(tmp_path / "py") and e.result["status"] == "failed"
    assert str(e) == summary["error"]  # the same message as the tool's
    assert (tmp_path / "py/history.csv").read_bytes() == (tmp_path / "cli/history.csv").read_bytes()
    # check=False: the dict, with the failure as data.
    r = ecm.run_scene(scene, tmp_path / "unchecked", threads=1, snapshots=False, plot=False, check=False)
    assert r["status"] == "failed" and r["failure"]["kind"] == "newton_not_converged" and r["failure"]["step"] == 1
    assert r["failure"]["particle"] is None and r["failure"]["position_mm"] is None
