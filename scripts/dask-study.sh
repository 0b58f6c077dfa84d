#!/usr/bin/env bash
# A study on a Dask cluster of this machine: starts a scheduler and N workers of one thread each
# on the loopback address, measures the scheduler's round trip per task (200 empty tasks), runs
# the study through `python3 -m ecm.study`, and shuts the cluster down. The same client code runs
# against a cluster of many machines (docs/dask.md: start the workers there, or dask-jobqueue).
# Usage: scripts/dask-study.sh STUDY.yaml OUT_DIR [WORKERS (default 2)]
# Writes OUT_DIR (ecm-study's report, dask.json with the cluster's side) and OUT_DIR/overhead.json.
# Needs the build (build/python) and python3-dask / python3-distributed (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
[[ $# -ge 2 ]] || { echo "usage: scripts/dask-study.sh STUDY.yaml OUT_DIR [WORKERS]" >&2; exit 2; }
study=$1 out=$2 workers=${3:-2}
py=/usr/bin/python3  # Debian's: the one python3-dask installs into (another may be first on PATH)
export PYTHONPATH=$PWD/build/python${PYTHONPATH:+:$PYTHONPATH} OMP_NUM_THREADS=1 OMP_WAIT_POLICY=PASSIVE
mkdir -p "$out"
cluster=$(mktemp -d)
pids=()
stop() {  # SIGTERM, and SIGKILL for a worker still inside a run after 10 s
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  for _ in $(seq 100); do
    alive=0; for p in "${pids[@]}"; do kill -0 "$p" 2>/dev/null && alive=1; done
    ((alive)) || break; sleep 0.1
  done
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true; rm -rf "$cluster"
}
trap stop EXIT
$py -m distributed.cli.dask_scheduler --host 127.0.0.1 --port 0 --dashboard-address :0 \
  --scheduler-file "$cluster/scheduler.json" >"$cluster/scheduler.log" 2>&1 &
pids+=($!)
for _ in $(seq 600); do [[ -s $cluster/scheduler.json ]] && break; sleep 0.1; done
address=$($py -c "import json,sys; print(json.load(open(sys.argv[1]))['address'])" "$cluster/scheduler.json")
for i in $(seq "$workers"); do
  $py -m distributed.cli.dask_worker "$address" --nthreads 1 --no-nanny --host 127.0.0.1 --no-dashboard \
    --name "w$i" >"$cluster/worker$i.log" 2>&1 &
  pids+=($!)
done
$py - "$address" "$workers" "$out/overhead.json" <<'EOF'
import json, sys, time
from distributed import Client
address, n, path = sys.argv[1], int(sys.argv[2]), sys.argv[3]
with Client(address) as c:
    c.wait_for_workers(n, timeout=120)
    rounds = []
    for _ in range(3):
        start = time.perf_counter()
        c.gather(c.map(lambda i: i, range(200), pure=False))  # empty tasks: the scheduler's own time
        rounds.append((time.perf_counter() - start) / 200)
json.dump({"workers": n, "empty_tasks": 200, "seconds_per_task": rounds,
           "notes": "wall time of 200 empty tasks submitted at once / 200, three rounds"}, open(path, "w"), indent=2)
print("scheduler round trip: %.2f ms per empty task (best of 3)" % (1e3 * min(rounds)), file=sys.stderr)
EOF
$py -m ecm.study "$study" --scheduler "$address" --out "$out"
