"""A study on a real Dask cluster (python/ecm/study.py): the test starts a scheduler and two
workers of one thread on the loopback address (separate processes, no nanny), runs the 8-sample
small RVE ensemble (data/studies/rve-small-ensemble.yaml, seconds per run) through
`python3 -m ecm.study`, and compares it with ecm-study's own run of the same file: study.csv is
the same bit for bit but for the columns of time, rate and memory and the Pareto marks (which
follow from the times), and the ensemble's files are the same bytes. A worker SIGKILLed while
runs are on it costs a retry (Dask's scheduler gives its runs to the other worker), not a
result; a client killed mid-study and started again runs only what it had not written. The
cluster is shut down by the test. Run as its own ctest (Python.dask); skipped where the Debian
packages python3-dask and python3-distributed are missing."""
import csv
import json
import os
import signal
import subprocess
import sys
import time

import pytest

pytest.importorskip("distributed", reason="the Dask path needs the Debian packages python3-dask and "
                                          "python3-distributed (scripts/setup.sh installs them)")

from conftest import BUILD, SOURCE  # noqa: E402

STUDY = SOURCE / "data/studies/rve-small-ensemble.yaml"
# Columns that measure the machine, not the run (and the Pareto marks, chosen by wall time).
MACHINE = {"wall_time_s", "cpu_time_s", "updates_per_s", "peak_rss_mb", "pareto"}


def _start(args, log):
    return subprocess.Popen([sys.executable, "-m", *args], stdout=log, stderr=subprocess.STDOUT,
                            env=dict(os.environ, OMP_NUM_THREADS="1"))


def _stop(p):
    if p.poll() is None:
        p.send_signal(signal.SIGTERM)
        try:
            p.wait(20)
        except subprocess.TimeoutExpired:
            p.kill()
            p.wait()


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """A scheduler and two one-thread workers on 127.0.0.1; yields (address, [worker processes])."""
    d = tmp_path_factory.mktemp("cluster")
    file = d / "scheduler.json"
    log = open(d / "cluster.log", "w")
    procs = [_start(["distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port", "0",
                     "--dashboard-address", ":0", "--scheduler-file", str(file)], log)]
    try:
        for _ in range(600):
            if file.exists() and file.stat().st_size > 0:
                break
            time.sleep(0.1)
        address = json.loads(file.read_text())["address"]
        workers = [_start(["distributed.cli.dask_worker", address, "--nthreads", "1", "--no-nanny",
                           "--host", "127.0.0.1", "--no-dashboard", "--name", "w%d" % i], log) for i in range(2)]
        procs += workers
        from distributed import Client
        with Client(address, timeout=60) as c:
            c.wait_for_workers(2, timeout=120)
        yield address, workers, procs
    finally:
        for p in reversed(procs):
            _stop(p)
        log.close()
        assert all(p.poll() is not None for p in procs)  # the cluster is down


@pytest.fixture(scope="module")
def local(tmp_path_factory):
    """ecm-study's own run of the study (one thread per run, each in a child process)."""
    out = tmp_path_factory.mktemp("local") / "study"
    p = subprocess.run([str(BUILD / "study/ecm-study"), str(STUDY), "--out", str(out), "--threads", "1", "-q"],
                       capture_output=True, text=True, check=False)
    assert p.returncode == 0, p.stderr
    return out


def _table(folder):
    with open(folder / "study.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    return [{k: v for k, v in r.items() if k not in MACHINE} for r in rows]


def _same_report(dask_out, local_out):
    assert _table(dask_out) == _table(local_out)
    assert len(_table(dask_out)) >= 8
    for name in ("ensemble.csv", "ensemble_samples.csv"):
        assert (dask_out / name).read_bytes() == (local_out / name).read_bytes(), name
    assert not (dask_out / "pareto.png").exists()  # no Pareto front among samples
    for f in ("summary.json", "ensemble_histogram.png", "weibull.png"):
        assert (dask_out / f).exists(), f
    for r in _table(dask_out):  # every run's outputs, e.g. history.csv, bit for bit
        assert (dask_out / r["directory"] / "history.csv").read_bytes() == \
               (local_out / r["directory"] / "history.csv").read_bytes()


def _client(address, out, log):
    return subprocess.Popen([sys.executable, "-m", "ecm.study", str(STUDY), "--scheduler", address, "--out", str(out)],
                            stdout=log, stderr=subprocess.STDOUT)


def _written(out):
    runs = out / "runs"
    if not runs.exists():
        return []
    return sorted(p.name for p in runs.iterdir() if not p.name.endswith((".incoming", ".replaced")) and (p / "study_run.json").exists())


def _wait_for(predicate, seconds, what):
    end = time.time() + seconds
    while time.time() < end:
        if predicate():
            return
        time.sleep(0.05)
    pytest.fail("timed out waiting for " + what)


def test_a_client_stopped_mid_study_goes_on_without_running_anything_twice(cluster, local, tmp_path):
    address, _, _ = cluster
    out = tmp_path / "study"
    with open(tmp_path / "client1.log", "w") as log:
        first = _client(address, out, log)
        _wait_for(lambda: len(_written(out)) >= 2 or first.poll() is not None, 300, "two runs written")
        first.kill()
        first.wait()
    before = {n: (out / "runs" / n / "study_run.json").stat().st_mtime_ns for n in _written(out)}
    assert 2 <= len(before) < 8, "the client was to be stopped mid-study"
    with open(tmp_path / "client2.log", "w") as log:
        assert _client(address, out, log).wait(300) == 0, (tmp_path / "client2.log").read_text()
    cluster_side = json.loads((out / "dask.json").read_text())
    assert cluster_side["already_done"] == len(before)
    assert cluster_side["tasks"] == 8 - len(before)
    for n, stamp in before.items():  # not run again, not rewritten
        assert (out / "runs" / n / "study_run.json").stat().st_mtime_ns == stamp
    _same_report(out, local)


def test_a_failed_run_is_named_as_it_comes_and_at_the_end_and_the_study_exits_1(cluster, tmp_path):
    """The elastic bar released at 100 mm/s and at 1e8 mm/s: the second leaves the grid in its
    first step. Its line says failed with the kind, the closing lines list it, dask.json names it,
    and the client exits 1 (ecm-study's status for a study with a failed run)."""
    address, _, _ = cluster
    study = tmp_path / "one-fails.yaml"
    study.write_text("# Units: mm, N, MPa, t, s.\nname: one-fails\nscene: %s\nset:\n  end_time: 3.0e-5\n"
                     "design: grid\nknobs:\n  bodies[0].initial_velocity: [[100, 0], [1.0e8, 0]]\n"
                     "reference:\n  closed_form: bar_vibration\n  condition: clamp\n" % (SOURCE / "data/mpm/elastic-bar.yaml"))
    p = subprocess.run([sys.executable, "-m", "ecm.study", str(study), "--scheduler", address, "--out", str(tmp_path / "out")],
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 1, p.stderr
    assert "] run 2: failed (left_grid: step 1: particle" in p.stderr, p.stderr
    assert "] run 1: completed" in p.stderr, p.stderr
    assert "1 of 2 runs did not complete:\n  run 2: failed (step 1: particle" in p.stderr, p.stderr
    assert "dashboard: http" in p.stderr, p.stderr
    assert json.loads((tmp_path / "out/dask.json").read_text())["failed_runs"] == ["2"]


def test_ctrl_c_stops_the_client_in_one_line_and_the_same_command_resumes(tmp_path):
    """Ctrl-C at a terminal reaches the whole process group: the client and its local cluster's
    workers. Sent so (SIGINT to the group) once a first run is written: one line with the count
    and the command to resume, no traceback, exit 130, no process of the group left; the command
    run again finishes the study without running the written runs again."""
    out = tmp_path / "study"
    command = [sys.executable, "-m", "ecm.study", str(STUDY), "--out", str(out), "--workers", "1"]
    p = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True,
                         env=dict(os.environ, OMP_NUM_THREADS="1"))
    _wait_for(lambda: len(_written(out)) >= 1 or p.poll() is not None, 300, "a first run written")
    os.killpg(p.pid, signal.SIGINT)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 130, err
    assert "Traceback" not in err and "KeyboardInterrupt" not in err, err
    lines = [l for l in err.splitlines() if l.startswith("stopped:")]
    assert len(lines) == 1 and "to resume: python3 -m ecm.study" in lines[0], err
    written = len(_written(out))

    def group_gone():
        try:
            os.killpg(p.pid, 0)
            return False
        except ProcessLookupError:
            return True
    _wait_for(group_gone, 60, "the local cluster's processes to end")
    again = subprocess.run(command, capture_output=True, text=True, timeout=600, env=dict(os.environ, OMP_NUM_THREADS="1"))
    assert again.returncode == 0, again.stderr
    assert json.loads((out / "dask.json").read_text())["already_done"] == written


def test_a_worker_killed_mid_study_costs_a_retry_not_a_result(cluster, local, tmp_path):
    address, workers, _ = cluster
    out = tmp_path / "study"
    with open(tmp_path / "client.log", "w") as log:
        client = _client(address, out, log)
        _wait_for(lambda: len(_written(out)) >= 1 or client.poll() is not None, 300, "a first run written")
        workers[0].send_signal(signal.SIGKILL)  # both workers hold runs: one is lost mid-run
        workers[0].wait()
        assert client.wait(300) == 0, (tmp_path / "client.log").read_text()
    cluster_side = json.loads((out / "dask.json").read_text())
    assert cluster_side["retried_runs"] >= 1, cluster_side
    assert cluster_side["lost_runs"] == 0
    assert sorted(r["run"] for r in cluster_side["runs"]) == list(range(1, 9))  # each run once in the report
    summary = json.loads((out / "summary.json").read_text())
    assert summary["all_completed"]
    _same_report(out, local)
