"""ecm-study's studies on a Dask cluster: each run of the plan is a task that runs its scene on a
worker through ecm.run_scene and sends its output folder back; the report (study.csv,
summary.json, pareto.png, and for `samples: N` the ensemble's files) is ecm-study's own code
(ecm._ecm._plan_study / _report_study over study/). Units: mm, N, MPa, tonne, s.

    /usr/bin/python3 -m ecm.study STUDY.yaml --scheduler tcp://HOST:8786 --out DIR
    /usr/bin/python3 -m ecm.study STUDY.yaml --workers 2 --out DIR     # a local cluster of 2 processes

    import ecm.study
    summary = ecm.study.run_study("data/studies/rve-coarse-ensemble.yaml", "out/ens",
                                  scheduler="tcp://HOST:8786")

Workers need the `ecm` package (PYTHONPATH=build/python) and no shared file system: a task
carries the scene's text and its material files, and returns the files the run wrote. The run
folders are written by the client, each at once (a temporary folder renamed into place, its
study_run.json last), so a study whose client stopped goes on where it was when started again:
the runs whose folder holds this scene's outputs are not run again. A worker that dies with a
run on it costs a retry of that run on another worker (Dask's scheduler reschedules it; the
retries are in dask.json). Format and design: docs/dask.md.
"""
import argparse
import hashlib
import json
import logging
import os
import shutil
import signal
import sys
import time

from . import _ecm


# ---------------------------------------------------------------------------------------------
# The task: runs on a worker


def _depth(name):
    """How many folders up a relative file name climbs (../../a.yaml: 2)."""
    parts = os.path.normpath(name).split(os.sep)
    return sum(1 for p in parts if p == "..")


def run_task(task):
    """Runs one scene on this machine: task = {scene_name, scene_text, files: {name as written:
    bytes}, threads, repeat}. Returns {files: {name: bytes} of the run's output folder, the
    repeat with the shortest wall time, cpu_time_s, worker, started, finished}."""
    import resource
    import socket
    import tempfile

    from . import run_scene

    with tempfile.TemporaryDirectory(prefix="ecm-task-") as tmp:
        climb = max([_depth(n) for n in task["files"]] + [0])
        scene_dir = os.path.join(tmp, "scene", *(["d"] * climb))
        os.makedirs(scene_dir)
        scene = os.path.join(scene_dir, task["scene_name"])
        with open(scene, "w", encoding="utf-8") as f:
            f.write(task["scene_text"])
        for name, data in task["files"].items():
            path = os.path.normpath(os.path.join(scene_dir, name))
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "wb") as f:
                f.write(data)
        started = time.time()
        best, best_wall, cpu = None, None, None
        for rep in range(task["repeat"]):
            out = os.path.join(tmp, "out%d" % rep)
            os.makedirs(out)
            before = resource.getrusage(resource.RUSAGE_SELF)
            error = None
            try:
                run_scene(scene, out, threads=task["threads"], snapshots=False, plot=False, check=False)
            except Exception as e:  # an invalid scene (e.g. seeding): the run fails, the study goes on
                error = str(e)
                with open(os.path.join(out, "error.txt"), "w", encoding="utf-8") as f:
                    f.write(error + "\n")
            after = resource.getrusage(resource.RUSAGE_SELF)
            used = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
            try:
                with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
                    summary = json.load(f)
            except (OSError, ValueError):
                summary = {}
            wall = summary.get("wall_time_s")
            if best is None or (wall is not None and (best_wall is None or wall < best_wall)):
                best, best_wall, cpu = out, wall, used
            if error is not None or summary.get("status") != "completed":
                break
        files = {}
        for name in sorted(os.listdir(best)):
            with open(os.path.join(best, name), "rb") as f:
                files[name] = f.read()
        return {"files": files, "cpu_time_s": cpu, "host": socket.gethostname(), "started": started,
                "finished": time.time()}


# ---------------------------------------------------------------------------------------------
# The client


def _material_files(scene_text, scene_file, data_dir):
    """The material files a scene names ({file: NAME} entries of materials:), resolved as the scene
    reader does (the scene's folder, then DATA_DIR/materials): {NAME as written: bytes}."""
    import yaml

    doc = yaml.safe_load(scene_text) or {}
    files = {}
    for m in doc.get("materials") or []:
        if not isinstance(m, dict) or not isinstance(m.get("file"), str):
            continue
        name = m["file"]
        if os.path.isabs(name):
            raise ValueError("%s: material file %s is an absolute path: a worker without this file system cannot "
                             "read it (name it relative to the scene)" % (scene_file, name))
        for candidate in (os.path.join(os.path.dirname(scene_file), name), os.path.join(data_dir, "materials", name)):
            if os.path.isfile(candidate):
                with open(candidate, "rb") as f:
                    files[name] = f.read()
                break
        else:
            raise FileNotFoundError("%s: material file '%s' not found" % (scene_file, name))
    return files


def _read(path):
    try:
        with open(path, encoding="utf-8") as f:
            return f.read()
    except OSError:
        return None


def _done(folder, scene_text):
    """A run folder with this scene's outputs (what _report_study reads)."""
    return _read(os.path.join(folder, "scene.yaml")) == scene_text and os.path.isfile(os.path.join(folder, "study_run.json"))


def _write_folder(folder, scene_text, result, repeat, reference_scene=False):
    """The run folder as ecm-study leaves it, written next to it and renamed into place: a stopped
    client leaves either the whole folder or none."""
    parent = os.path.dirname(folder)
    os.makedirs(parent, exist_ok=True)
    tmp = folder + ".incoming"
    shutil.rmtree(tmp, ignore_errors=True)
    os.makedirs(tmp)
    if not reference_scene:
        with open(os.path.join(tmp, "scene.yaml"), "w", encoding="utf-8") as f:
            f.write(scene_text)
    for name, data in result["files"].items():
        with open(os.path.join(tmp, name), "wb") as f:
            f.write(data)
    summary = {}
    if "summary.json" in result["files"]:
        summary = json.loads(result["files"]["summary.json"].decode())
    if not reference_scene:
        with open(os.path.join(tmp, "study_run.json"), "w", encoding="utf-8") as f:
            json.dump({"wall_time_s": summary.get("wall_time_s"), "updates_per_s": summary.get("particle_updates_per_s"),
                       "peak_rss_mb": None, "cpu_time_s": result.get("cpu_time_s"), "repeat": repeat,
                       "worker": result.get("worker"), "host": result.get("host")}, f, indent=2)
    old = folder + ".replaced"
    shutil.rmtree(old, ignore_errors=True)
    if os.path.exists(folder):
        os.rename(folder, old)
    os.rename(tmp, folder)
    shutil.rmtree(old, ignore_errors=True)


def _outcome(result):
    """What a run's own files say of it: (status, failure kind or None, message or None).
    status is the run's ("completed", "failed", "stopped"), or "failed" for a scene refused
    before it ran (error.txt)."""
    files = result.get("files", {})
    if "error.txt" in files:
        return "failed", "input", files["error.txt"].decode(errors="replace").strip()
    try:
        summary = json.loads(files["summary.json"].decode())
    except (KeyError, ValueError):
        return "failed", None, "the run left no summary.json"
    failure = summary.get("failure") or {}
    return summary.get("status", "failed"), failure.get("kind"), summary.get("error")


def _short(text, width=110):
    text = " ".join(str(text).split())
    return text if len(text) <= width else text[:width - 3] + "..."


def _duration(seconds):
    if seconds < 10:
        return "%.1f s" % seconds
    if seconds < 90:
        return "%.0f s" % seconds
    if seconds < 5400:
        return "%.0f min" % (seconds / 60)
    return "%.1f h" % (seconds / 3600)


def _suspicious(keys, dask_scheduler=None):
    """On the scheduler: how many workers died while running each task (Dask's `suspicious`)."""
    return {k: (dask_scheduler.tasks[k].suspicious if k in dask_scheduler.tasks else None) for k in keys}


def run_study(study, out, scheduler=None, client=None, workers=None, threads=1, progress=True):
    """Runs the study file `study` on a Dask cluster into the folder `out` and writes ecm-study's
    report there. The cluster: an existing distributed.Client (`client`), a scheduler address
    (`scheduler`, e.g. "tcp://HOST:8786"), or a local cluster of `workers` processes of one
    thread. threads: OpenMP threads of each run. Returns summary.json's content; dask.json holds
    the cluster's side (workers, retries, times)."""
    from distributed import Client, LocalCluster

    study = os.fspath(study)
    out = os.fspath(out)
    plan = _ecm._plan_study(study)
    os.makedirs(out, exist_ok=True)
    own_cluster = None
    if client is None:
        if scheduler is None:
            # The workers start with SIGINT ignored (Python keeps an ignored SIGINT ignored): a
            # Ctrl-C at the terminal reaches the whole process group, and only this client is to
            # answer it (one line, main()), not each worker with a traceback.
            previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
            try:
                own_cluster = LocalCluster(n_workers=workers or 2, threads_per_worker=1, processes=True,
                                           dashboard_address=":0")
            finally:
                signal.signal(signal.SIGINT, previous)
            scheduler = own_cluster
        try:
            client = Client(scheduler, timeout=30)
        except OSError as e:
            if own_cluster is not None:
                own_cluster.close()
            raise ConnectionError("cannot reach the Dask scheduler at %s: %s" % (scheduler, e)) from e
    try:
        return _run(plan, study, out, client, threads, progress)
    except KeyboardInterrupt:
        # Stopping with runs in flight: Dask then logs their cancellation; nothing of it is news.
        logging.getLogger("distributed").setLevel(logging.CRITICAL)
        raise
    finally:
        if own_cluster is not None:
            client.close()
            own_cluster.close()


def _worker_task(task):
    """run_task, with the worker's address in the result."""
    from distributed import get_worker

    result = run_task(task)
    result["worker"] = get_worker().address
    return result


def _run(plan, study, out, client, threads, progress):
    from distributed import as_completed

    started = time.time()
    runs_dir = os.path.join(out, "runs")
    if os.path.isdir(runs_dir):  # what a client stopped while writing a folder left beside it
        for name in os.listdir(runs_dir):
            if name.endswith((".incoming", ".replaced")):
                shutil.rmtree(os.path.join(runs_dir, name), ignore_errors=True)
    jobs = []  # (run id or "reference", folder, scene text, scene file, is the reference scene)
    if plan["kind"] == "mpm":
        if plan["reference_scene"]:
            ref = plan["reference_scene"]
            text = _read(ref)
            folder = os.path.join(out, "reference")
            summary = _read(os.path.join(folder, "summary.json"))
            if not (summary and json.loads(summary).get("status") == "completed"):
                jobs.append(("reference", folder, text, ref, True))
        for r in plan["runs"]:
            folder = os.path.join(out, r["directory"])
            if not _done(folder, r["scene_text"]):
                jobs.append((r["id"], folder, r["scene_text"], r["scene_file"], False))
    futures, meta = [], {}
    for ident, folder, text, scene_file, is_ref in jobs:
        task = {"scene_name": os.path.basename(scene_file), "scene_text": text, "threads": threads,
                "repeat": 1 if is_ref else plan["repeat"],
                "files": _material_files(text, scene_file, plan["data_dir"])}
        digest = hashlib.sha1(text.encode()).hexdigest()[:12]
        key = "ecm-study-%s-%s-%s" % (plan["name"], ident if is_ref else "%03d" % ident, digest)
        f = client.submit(_worker_task, task, key=key, pure=False, retries=0)
        futures.append(f)
        meta[f.key] = (ident, folder, text, is_ref, time.time())
    skipped = (len(plan["runs"]) + (1 if plan["reference_scene"] else 0)) - len(jobs) if plan["kind"] == "mpm" else 0
    slots_now = sum(w.get("nthreads", 1) for w in client.scheduler_info()["workers"].values()) or 1
    if progress:
        if plan["kind"] == "mpm":
            print("%s: %d runs to do on %d workers (%d already done in %s)" %
                  (plan["name"], len(jobs), len(client.scheduler_info()["workers"]), skipped, out), file=sys.stderr)
        else:
            print("%s: a point study: its %d runs run here, on the client, not on the cluster (a point run "
                  "takes milliseconds, less than a Dask task's round trip; docs/dask.md)" %
                  (plan["name"], len(plan["runs"])), file=sys.stderr)
        if futures and getattr(client, "dashboard_link", None):
            print("dashboard: %s" % client.dashboard_link, file=sys.stderr)
    records = []
    done = 0
    computed = []  # compute_s of the runs done so far, for the ETA
    for f in as_completed(futures):
        ident, folder, text, is_ref, submitted = meta[f.key]
        retries = client.run_on_scheduler(_suspicious, [f.key]).get(f.key)
        record = {"run": ident, "key": f.key, "worker_deaths": retries}
        try:
            result = f.result()
            _write_folder(folder, text, result, plan["repeat"], reference_scene=is_ref)
            status, kind, message = _outcome(result)
            record.update(worker=result.get("worker"), host=result.get("host"), started=result["started"] - started,
                          finished=result["finished"] - started, compute_s=result["finished"] - result["started"],
                          arrived=time.time() - started, status=status, failure_kind=kind, error=message)
            computed.append(record["compute_s"])
        except Exception as e:  # the task raised, or Dask gave up on it (KilledWorker): the run is not run
            record.update(status="lost", error="%s: %s" % (type(e).__name__, e))
        f.release()
        records.append(record)
        done += 1
        if progress:
            line = "[%d/%d] run %s: %s" % (done, len(futures), ident, record["status"])
            if record["status"] == "lost":
                line += " (%s)" % _short(record["error"])
            elif record["status"] != "completed":
                line += " (%s%s)" % (record["failure_kind"] + ": " if record.get("failure_kind") else "",
                                     _short(record.get("error") or "no message"))
            if "compute_s" in record:
                line += ", %s" % _duration(record["compute_s"])
            if retries:
                line += ", worker died %d x: retried" % retries
            if computed and done < len(futures):
                line += "; about %s to go" % _duration(sum(computed) / len(computed) * (len(futures) - done) / slots_now)
            print(line, file=sys.stderr)
    wall = time.time() - started
    report = _ecm._report_study(study, out, threads)
    workers = client.scheduler_info()["workers"]
    slots = sum(w.get("nthreads", 1) for w in workers.values())
    compute = sum(r.get("compute_s", 0.0) for r in records)
    cluster = {"scheduler": client.scheduler.address, "workers": len(workers), "worker_threads": slots,
               "run_threads": threads, "tasks": len(futures), "already_done": skipped, "wall_time_s": wall,
               "task_compute_s": compute,
               "idle_per_task_s": (wall * slots - compute) / len(futures) if futures else None,
               "retried_runs": sum(1 for r in records if r.get("worker_deaths")), "lost_runs":
               sum(1 for r in records if r["status"] == "lost"),
               "failed_runs": sorted(str(r["run"]) for r in records if r["status"] not in ("completed", "lost")),
               "all_completed": report["all_completed"],
               "runs": records,
               "notes": "times in s from the client's start; compute_s: the task on its worker (scene files written, "
                        "the run, outputs read); idle_per_task_s = (wall x worker threads - sum of compute_s) / tasks: "
                        "scheduling, transfers and the tail where workers wait for the last runs; worker_deaths: "
                        "Dask's count of workers that died while running the task (each a retry elsewhere); status: the "
                        "run's own (completed, failed, stopped) or lost (never run); a point study's runs run on the "
                        "client (tasks 0)"}
    with open(os.path.join(out, "dask.json"), "w", encoding="utf-8") as fh:
        json.dump(cluster, fh, indent=2)
    with open(os.path.join(out, "summary.json"), encoding="utf-8") as fh:
        summary = json.load(fh)
    if progress:
        if report.get("ensemble_text"):
            print(report["ensemble_text"], end="", file=sys.stderr)
        print("%d runs -> %s (study.csv, summary.json, %s, dask.json), %.1f s" %
              (len(plan["runs"]), out, "ensemble.csv, weibull.png" if report.get("ensemble") else "pareto.png", wall),
              file=sys.stderr)
        not_done = [r for r in records if r["status"] != "completed"]
        if not_done:
            print("%d of %d runs did not complete:" % (len(not_done), len(records)), file=sys.stderr)
            for r in sorted(not_done, key=lambda r: str(r["run"])):
                print("  run %s: %s (%s)" % (r["run"], r["status"], _short(r.get("error") or r.get("failure_kind") or "")),
                      file=sys.stderr)
    return summary


def main(argv=None):
    p = argparse.ArgumentParser(prog="python3 -m ecm.study",
                                description="ecm-study's study on a Dask cluster (units: mm, N, MPa, t, s)")
    p.add_argument("study", help="study file (YAML), as ecm-study's")
    p.add_argument("-o", "--out", help="output folder (default: out/STUDY-NAME); run again to resume")
    p.add_argument("--scheduler", help="the Dask scheduler's address, e.g. tcp://HOST:8786")
    p.add_argument("--workers", type=int, default=2, help="without --scheduler: a local cluster of N processes")
    p.add_argument("-t", "--threads", type=int, default=1, help="OpenMP threads of each run (default 1)")
    p.add_argument("-q", "--quiet", action="store_true", help="no line per run on stderr")
    a = p.parse_args(argv)
    if a.threads < 1 or a.workers < 1:
        p.error("--threads and --workers must be >= 1")
    try:
        import distributed  # noqa: F401
    except ImportError:
        print("error: the Dask path needs the Debian packages python3-dask and python3-distributed "
              "(scripts/setup.sh installs them)", file=sys.stderr)
        return 2
    try:
        plan_name = _ecm._plan_study(a.study)["name"]
    except (_ecm.InputError, OSError) as e:
        print("error: %s" % e, file=sys.stderr)
        return 2
    out = a.out or os.path.join("out", plan_name)
    try:
        summary = run_study(a.study, out, scheduler=a.scheduler, workers=a.workers, threads=a.threads,
                            progress=not a.quiet)
    except KeyboardInterrupt:
        written = len([n for n in os.listdir(os.path.join(out, "runs"))
                       if not n.endswith((".incoming", ".replaced"))]) if os.path.isdir(os.path.join(out, "runs")) else 0
        where = "--scheduler %s" % a.scheduler if a.scheduler else "--workers %d" % a.workers
        print("stopped: %d run folders written in %s; to resume: python3 -m ecm.study %s --out %s %s"
              % (written, out, a.study, out, where), file=sys.stderr)
        return 130
    except ConnectionError as e:  # a scheduler address that does not answer: a bad command line
        print("error: %s" % e, file=sys.stderr)
        return 2
    except (_ecm.InputError, ValueError, FileNotFoundError) as e:  # e.g. a material file not found
        print("error: %s" % e, file=sys.stderr)
        return 2
    except (_ecm.OutputError, OSError) as e:
        print("error: %s" % e, file=sys.stderr)
        return 1
    return 0 if summary.get("all_completed") else 1


if __name__ == "__main__":
    # Through the package's module, not __main__: the task functions must pickle by reference
    # (ecm.study.run_task), for workers that import ecm themselves.
    from ecm import study as _study

    sys.exit(_study.main())
