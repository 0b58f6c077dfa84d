#!/usr/bin/env bash
# scripts/den.sh and scripts/rve.sh with their run made to fail (ecm-mpm cut short after 50 steps,
# then exit 1, its outputs kept): each must keep the run in its table, exit non-zero and name the
# run at the end.
# Usage: script_failure_check.sh ECM_MPM SOURCE_DIR OUT_DIR
set -u
mpm=$1 source=$2 out=$3
rm -rf "$out" && mkdir -p "$out"
failing=$out/failing-ecm-mpm
printf '#!/usr/bin/env bash\n"%s" "$@" --max-steps 50\nexit 1\n' "$mpm" > "$failing"
chmod +x "$failing"
cd "$source" || exit 1
for script in den rve; do
  upper=$(echo "$script" | tr a-z A-Z)
  env "${upper}_BIN=$failing" "${upper}_THREADS=1" "scripts/$script.sh" "$out/$script" coarse > "$out/$script.log" 2>&1
  code=$?
  [[ $code != 0 ]] || { echo "FAIL: $script.sh exited 0 although its run failed"; cat "$out/$script.log"; exit 1; }
  grep -q "^failed runs" "$out/$script.log" && grep -q "  coarse (exit 1" "$out/$script.log" \
    || { echo "FAIL: $script.sh does not name the failed run at the end"; cat "$out/$script.log"; exit 1; }
done
echo "den.sh and rve.sh: a failed run fails them and is named"
