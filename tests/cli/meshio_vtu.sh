#!/usr/bin/env bash
# Every VTU the workbench writes reads in meshio (Debian's python3-meshio, a reader that shares no
# code with VTK) and holds what the CSV files beside it hold (tests/common/check_meshio.py): the
# agent model, FEM, an agent comparison (with its agent/ and fem/), the PBD rod and a PBD comparison.
# Usage: meshio_vtu.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"
run() {  # run NAME COMMAND...: the command writes into $work/NAME
  local name=$1
  shift
  "$@" >"$work/$name.log" 2>&1
  check "$name" $? "exit status $?: $(tail -2 "$work/$name.log")"
}
sed -e "s#^file = \"\.\./#file = \"$src/#" "$src/cases/gate_plate.toml" >"$work/plate.toml"
run agent "$bin" agent "$work/plate.toml" -o "$work/agent"
run fem "$bin" fem "$src/tests/fem/cases/small_plate.toml" -o "$work/fem"
run compare "$bin" compare "$work/plate.toml" -o "$work/compare"
sed -e 's|^mesh = "\(.*\)"|mesh = "'"$src"'/cases/\1"|' -e 's|^frames = .*|frames = 5|' "$src/cases/pbd_strip.toml" >"$work/rod.toml"
run pbd "$bin" pbd "$work/rod.toml" -o "$work/pbd"
sed -e 's|^mesh = "\(.*\)"|mesh = "'"$src"'/cases/\1"|' -e 's|^file = "\(.*\)"|file = "'"$src"'/cases/\1"|' \
  "$src/cases/pbd_strip_fem.toml" >"$work/strip.toml"
run compare_pbd "$bin" compare "$work/strip.toml" -o "$work/compare_pbd"
/usr/bin/python3 "$src/tests/common/check_meshio.py" --expect agent=2 --expect fem=3 --expect compare=1 --expect pbd=2 "$work"
check meshio_reads_every_vtu $? "see above"
echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
