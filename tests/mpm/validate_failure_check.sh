#!/usr/bin/env bash
# scripts/validate.sh with a run made to fail: it must exit non-zero and name the run at the end;
# the same run listed in VALIDATE_KNOWN_FAILURES is reported and not counted.
# Usage: validate_failure_check.sh ECM_MPM VALIDATE_SH OUT_DIR
set -u
mpm=$1 validate=$2 out=$3
rm -rf "$out" && mkdir -p "$out"
failing=$out/failing-ecm-mpm
printf '#!/usr/bin/env bash\n"%s" "$@"\nexit 3\n' "$mpm" > "$failing"
chmod +x "$failing"
VALIDATE_BIN=$failing "$validate" "$out/runs" lpanel-coarse-tracked > "$out/log" 2>&1
code=$?
[[ $code != 0 ]] || { echo "FAIL: validate.sh exited 0 although a run failed"; cat "$out/log"; exit 1; }
grep -q "failed runs (1 of 1)" "$out/log" && grep -q "  lpanel-coarse-tracked (exit 3" "$out/log" \
  || { echo "FAIL: the failed run is not named at the end"; cat "$out/log"; exit 1; }
VALIDATE_BIN=$failing VALIDATE_KNOWN_FAILURES=lpanel-coarse-tracked "$validate" "$out/runs" lpanel-coarse-tracked > "$out/log-known" 2>&1
[[ $? == 0 ]] || { echo "FAIL: a known failure was counted"; cat "$out/log-known"; exit 1; }
VALIDATE_BIN=$mpm VALIDATE_KNOWN_FAILURES=lpanel-coarse-tracked "$validate" "$out/runs" lpanel-coarse-tracked > "$out/log-passed" 2>&1
[[ $? != 0 ]] && grep -q "but it completed" "$out/log-passed" \
  || { echo "FAIL: a known failure that completed was not reported"; cat "$out/log-passed"; exit 1; }
echo "validate.sh: a failed run fails it and is named; known failures are kept true"
