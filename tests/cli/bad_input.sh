#!/usr/bin/env bash
# Bad input to `workbench agent`: each case must give exit code 2, exactly one line on stderr
# naming the file and the thing, and no output folder (not even a partial one).
# Usage: bad_input.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

base_case() {
  cat <<CASE
[mesh]
file = "$src/meshes/plate2d.geo"
[mesh.parameters]
h = 0.01
lw = 0.02
[material]
young = 206e9
poisson = 0.3
thickness = 0.002
[boundary]
rigid = ["base"]
[[load]]
group = "load"
direction = "-y"
force = 2.0
[agent]
rule_set = "patent"
CASE
}

# expect NAME EXPECTED_TEXT CASE_TEXT
expect() {
  local name=$1 expected=$2 text=$3
  local file="$work/$name.toml" out="$work/out_$name"
  printf '%s\n' "$text" >"$file"
  "$bin" agent "$file" -o "$out" >"$work/stdout" 2>"$work/stderr"
  local rc=$?
  local lines
  lines=$(wc -l <"$work/stderr")
  if [ "$rc" -ne 2 ] || [ "$lines" -ne 1 ] || ! grep -qF -- "$expected" "$work/stderr" || [ -e "$out" ] ||
     ls -a "$work" | grep -q partial; then
    echo "FAIL $name: exit $rc, $lines stderr lines, expected '$expected', got: $(cat "$work/stderr")"
    failures=$((failures + 1))
  else
    passed=$((passed + 1))
  fi
}

with() {  # replace the line starting with $1 by $2 in the base case
  base_case | awk -v key="$1" -v line="$2" 'index($0, key) == 1 { print line; next } { print }'
}

expect unknown_key "unknown_key.toml: unknown key 'material.yuong'" "$(with young 'yuong = 206e9')"
expect out_of_range "out_of_range.toml: agent.alpha1: in [0, 1] (got 1.5)" "$(base_case; echo 'alpha1 = 1.5')"
expect wrong_type "wrong_type.toml: load[0].force: must be a number, not a string" "$(with force 'force = "two"')"
expect bad_choice "bad_choice.toml: agent.rule_set: must be one of" "$(with rule_set 'rule_set = "literal"')"
expect odd_fan "odd_fan.toml: agent.directions: must be even" "$(with rule_set 'rule_set = "directional"'; echo 'directions = 31')"
expect flat_fan "flat_fan.toml: agent.fan_angle: in (0, 90) (got 90)" "$(with rule_set 'rule_set = "directional"'; echo 'fan_angle = 90')"
expect cyclic_gamma "cyclic_gamma.toml: agent.gamma: readings every_agent_all_operations / boundaries_return need gamma > 0" "$(base_case; echo 'gamma = 0.0'; echo 'readings = ["boundaries_return"]')"
expect cyclic_factor "cyclic_factor.toml: agent.readings: readings every_agent_all_operations / boundaries_return need every transfer factor below 1" "$(base_case; echo 'alpha3 = 1.0'; echo 'readings = ["every_agent_all_operations"]')"
expect cyclic_conserving "cyclic_conserving.toml: agent.readings: every_agent_all_operations and boundaries_return are readings of the patent rule set" "$(with rule_set 'rule_set = "conserving"'; echo 'readings = ["every_agent_all_operations"]')"
expect missing_group "missing_group.toml: boundary.rigid: group 'floor' is not a physical group" "$(with rigid 'rigid = ["floor"]')"
expect no_rigid "no_rigid.toml: boundary.rigid: no rigid faces" "$(with rigid 'rigid = []')"
expect triangles "triangles.geo: has Triangle 3 elements" "$(with file "file = \"$src/tests/data/triangles.geo\"" | sed '/^\[mesh.parameters\]/,/^lw/d' | sed 's/"load"/"load"/')"
# A connected diagonal staircase of 300 steps (two unit squares each, MSH 2.2): no lattice plane is
# empty, so its compressed box is its bounding box, 301 x 300 slots (0.017 GiB dense); on tiles of
# 64 x 16 it holds at least 300 / 16 tiles of 1024 slots, above 0.0035 GiB: refused at 0.003 (its
# 600 elements alone pass that limit).
{
  printf '$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n' $((4 * 301))
  for ((j = 0; j <= 300; j++)); do for ((d = 0; d < 4; d++)); do printf '%d %d %d 0\n' $((1 + 4 * j + d)) $((j - 1 + d)) $j; done; done
  printf '$EndNodes\n$Elements\n600\n'
  node() { echo $((1 + 4 * $2 + $1 - $2 + 1)); }
  for ((j = 0; j < 300; j++)); do for i in $j $((j + 1)); do
    printf '%d 3 2 1 1 %d %d %d %d\n' $((2 * j + i - j + 1)) "$(node $i $j)" "$(node $((i + 1)) $j)" "$(node $((i + 1)) $((j + 1)))" "$(node $i $((j + 1)))"
  done; done
  printf '$EndElements\n'
} >"$work/staircase.msh"
WORKBENCH_MEMORY_LIMIT=0.003 expect staircase "staircase.msh: the agent grid (600 agents of 1 m in a compressed box of 301 x 300 slots" "$(with file "file = \"$work/staircase.msh\"" | sed '/^\[mesh.parameters\]/,/^lw/d')"
expect bad_parameter "plate2d.geo: unknown mesh parameter 'hx'" "$(with 'h =' 'hx = 0.01')"
expect geo_error "plate2d.geo: plate2d.geo: W, H, lw and the patch's left end xc - lw/2 must be multiples of h" "$(with 'h =' 'h = 0.003')"
expect syntax "syntax.toml:2:" "$(base_case | sed '2s/.*/file = = "x"/')"
expect missing_mesh "nowhere.geo: no such mesh file" "$(with file 'file = "nowhere.geo"')"
expect other_section "other_section.toml: unknown key 'fem.degre'" "$(base_case; printf '[fem]\ndegre = 2\n')"
expect no_load "no_load.toml: load: missing" "$(base_case | sed '/^\[\[load\]\]/,/^force/d')"

# A case file that does not exist.
"$bin" agent "$work/absent.toml" -o "$work/out_absent" 2>"$work/stderr"
if [ $? -ne 2 ] || ! grep -qF "absent.toml: cannot read the case file" "$work/stderr" || [ -e "$work/out_absent" ]; then
  echo "FAIL absent: $(cat "$work/stderr")"
  failures=$((failures + 1))
else
  passed=$((passed + 1))
fi

# A failed run leaves an earlier output untouched.
mkdir -p "$work/out_keep" && echo old >"$work/out_keep/marker"
printf '%s\n' "$(with rigid 'rigid = []')" >"$work/keep.toml"
"$bin" agent "$work/keep.toml" -o "$work/out_keep" 2>/dev/null
if [ "$(cat "$work/out_keep/marker" 2>/dev/null)" != old ]; then
  echo "FAIL keep: a failed run touched the earlier output"
  failures=$((failures + 1))
else
  passed=$((passed + 1))
fi

# A case file with every model's sections ([fem], [compare]) runs under `workbench agent` too.
sed "s#\.\./meshes#$src/meshes#" "$src/cases/gate_plate.toml" >"$work/shared.toml"
if "$bin" agent "$work/shared.toml" -o "$work/out_shared" 2>"$work/stderr" && [ -s "$work/out_shared/agent.pvd" ]; then
  passed=$((passed + 1))
else
  echo "FAIL shared: $(tail -1 "$work/stderr")"
  failures=$((failures + 1))
fi

echo "cli bad input: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
