#!/usr/bin/env bash
# One case file serves every subcommand (docs/case-file.md): `workbench SUB CASE --check` reads the
# case, checks every section with its reader (schema/src/every_section.cc) and writes nothing. For every
# file in cases/ and every subcommand: the models the file is meant for accept it (exit 0); the
# others may miss a section they need (exit 2, one line), but none refuses a key as unknown.
# Usage: case_sections.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

# The files each model runs (the calibration file, cases/calibrate_*.toml, is another format).
runs() {  # runs SUB CASE_NAME: whether SUB is meant to run CASE_NAME
  case "$1:$2" in
    compare:cook | compare:pbd_sheet | compare:pbd_strip) return 1 ;;  # compare --check reads the meshes too
    compare:*) return 0 ;;
    pbd:pbd_*) return 0 ;;
    pbd:*) return 1 ;;
    agent:pbd_* | fem:pbd_sheet | fem:pbd_strip | agent:cook) return 1 ;;
    *) return 0 ;;
  esac
}

cd "$work" || exit 1
for file in "$src"/cases/*.toml; do
  name=$(basename "$file" .toml)
  [ "${name#calibrate_}" != "$name" ] && continue
  for sub in agent fem compare pbd; do
    "$bin" "$sub" "$file" --check >"$logs/out" 2>"$logs/err"
    rc=$?
    if runs "$sub" "$name"; then
      [ $rc -eq 0 ] && grep -q "checked, nothing written" "$logs/err"
      check "${sub}_$name" $? "exit $rc: $(tail -1 "$logs/err")"
    else
      [ $rc -eq 2 ] && [ "$(wc -l <"$logs/err")" -eq 1 ] && ! grep -q "unknown key" "$logs/err"
      check "${sub}_${name}_refused" $? "exit $rc: $(cat "$logs/err")"
    fi
  done
done
[ -z "$(ls -A "$work")" ]
check nothing_written $? "written: $(ls -A "$work")"

echo "cli case sections: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
