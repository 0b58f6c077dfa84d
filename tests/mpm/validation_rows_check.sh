#!/usr/bin/env bash
# The rows of docs/validation.md against a rerun: scripts/validate.sh OUT_DIR RUN... writes the
# rows its report generates (OUT_DIR/docs-rows.md, scripts/validation/report.py), and
# scripts/validation/check_doc_rows.py fails when a documented figure moved (tolerance: half a
# unit of the docs' last digit plus 0.2 %) or a row is missing, or fewer than AT_LEAST rows were
# compared. Usage: validation_rows_check.sh SOURCE_DIR VALIDATE_SH OUT_DIR AT_LEAST RUN...
set -u
source=$1 validate=$2 out=$3 atLeast=$4
shift 4
rm -rf "$out"
"$validate" "$out" "$@" > "$out.log" 2>&1 || { echo "FAIL: validate.sh failed"; cat "$out.log"; exit 1; }
python3 "$source/scripts/validation/check_doc_rows.py" "$source/docs/validation.md" "$out/docs-rows.md" --at-least "$atLeast"
