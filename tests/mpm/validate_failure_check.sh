#!/usr/bin/env bash
# scripts/validate.sh with a run made to fail: it must exit non-zero and name the run at the end;
# the same run listed in VALIDATE_KNOWN_FAILURES is reported and not counted. A run name that is
# not a scene with modifiers in their order is refused before any run, and a variant's scene is
# the shipped one with only its modifiers' lines changed.
# Usage: validate_failure_check.sh ECM_MPM VALIDATE_SH OUT_DIR
set -u
mpm=$1 validate=$2 out=$3
rm -rf "$out" && mkdir -p "$out"
failing=$out/failing-ecm-mpm
printf '#!/usr/bin/env bash\n"%s" "$@"\nexit 3\n' "$mpm" > "$failing"
chmod +x "$failing"
VALIDATE_BIN=$failing "$validate" "$out/runs" lpanel-coarse > "$out/log" 2>&1
code=$?
[[ $code != 0 ]] || { echo "FAIL: validate.sh exited 0 although a run failed"; cat "$out/log"; exit 1; }
grep -q "failed runs (1 of 1)" "$out/log" && grep -q "  lpanel-coarse (exit 3" "$out/log" \
  || { echo "FAIL: the failed run is not named at the end"; cat "$out/log"; exit 1; }
VALIDATE_BIN=$failing VALIDATE_KNOWN_FAILURES=lpanel-coarse "$validate" "$out/runs" lpanel-coarse > "$out/log-known" 2>&1
[[ $? == 0 ]] || { echo "FAIL: a known failure was counted"; cat "$out/log-known"; exit 1; }
VALIDATE_BIN=$mpm VALIDATE_KNOWN_FAILURES=lpanel-coarse "$validate" "$out/runs" lpanel-coarse > "$out/log-passed" 2>&1
[[ $? != 0 ]] && grep -q "but it completed" "$out/log-passed" \
  || { echo "FAIL: a known failure that completed was not reported"; cat "$out/log-passed"; exit 1; }
for bad in lpanel-coarse-tension den-rig-coarse-free-one-band den-rig-coarse-implicit-tension den-rig-coarse-one-band-one-band; do
  VALIDATE_BIN=$mpm "$validate" "$out/names" den-rig-coarse "$bad" > "$out/log-name" 2>&1
  [[ $? == 2 ]] && grep -q "not '$bad'" "$out/log-name" && [[ ! -d $out/names/den-rig-coarse ]] \
    || { echo "FAIL: $bad was not refused before the first run"; cat "$out/log-name"; exit 1; }
done
printf '#!/usr/bin/env bash\nexit 0\n' > "$out/idle-ecm-mpm"
chmod +x "$out/idle-ecm-mpm"
VALIDATE_BIN=$out/idle-ecm-mpm "$validate" "$out/scenes-only" den-rig-medium-implicit-one-band-free den-rig-coarse-tension > /dev/null 2>&1
source=$(dirname "$validate")/..
changed=$(diff "$source/data/validation/den-4b-rig-medium-implicit.yaml" "$out/scenes-only/scenes/den-rig-medium-implicit-one-band-free.yaml" | grep -c '^>')
grep -q '^  crack_path: free$' "$out/scenes-only/scenes/den-rig-medium-implicit-one-band-free.yaml" \
  && grep -q 'materials/den-concrete-hordijk.yaml}' "$out/scenes-only/scenes/den-rig-medium-implicit-one-band-free.yaml" \
  && grep -q 'material: den-concrete-hordijk}' "$out/scenes-only/scenes/den-rig-medium-implicit-one-band-free.yaml" \
  && [[ $changed == 5 ]] \
  || { echo "FAIL: den-rig-medium-implicit-one-band-free is not the shipped scene with one band and the free rule ($changed lines changed)"; exit 1; }
changed=$(diff "$source/data/validation/den-4b-rig-coarse.yaml" "$out/scenes-only/scenes/den-rig-coarse-tension.yaml" | grep -c '^>')
grep -q '^    x: free   # P_s = 0' "$out/scenes-only/scenes/den-rig-coarse-tension.yaml" && [[ $changed == 3 ]] \
  || { echo "FAIL: den-rig-coarse-tension is not the shipped scene without P_s ($changed lines changed)"; exit 1; }
echo "validate.sh: a failed run fails it and is named; known failures are kept true; bad names are refused; variants change their lines only"
