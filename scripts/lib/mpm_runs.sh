# What the scripts that run ecm-mpm (den.sh, rve.sh, validate.sh) do with a run's exit status
# (io/cli_exit.hpp; docs/tools.md, "When a run fails"). Sourced, from the repository's root.

# ", KIND" of a failed run's summary.json (failure.kind), or nothing.
failureKind() {
  local k
  k=$(grep -m1 -o '"kind": *"[a-z_]*"' "$1/summary.json" 2>/dev/null | sed 's/.*"\([a-z_]*\)"$/\1/') || true
  [[ -n $k ]] && echo ", $k"
  return 0
}

# runStatus RC SCENE DIR: says on stderr what a status other than the run's own result means
# (0 completed; 1 and 10-20 failed with their outputs kept, which the caller's table shows).
runStatus() {
  case $1 in
    0 | 1 | 1[0-9] | 20) ;;
    2) echo "error: ecm-mpm could not run $2 (bad input, status 2)" >&2 ;;
    3) echo "warning: ecm-mpm stopped $2 with a checkpoint in $3 (resume with --restart)" >&2 ;;
    *) echo "error: ecm-mpm ended $2 with status $1" >&2 ;;
  esac
}
