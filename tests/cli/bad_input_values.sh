#!/usr/bin/env bash
# Bad values and bad meshes (input validation): non-finite or huge numbers, meshes gmsh
# would crash on, problems too large for the memory limit, a load on a rigid group, a diverging
# PBD run. Each must give exit code 2, exactly one line on stderr naming the file and the key
# (besides the progress a PBD run logged before it failed),
# no output folder (not even a partial one), and a sentinel file beside the target untouched.
# Usage: bad_input_values.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"
export WORKBENCH_MEMORY_LIMIT=16  # GiB: the refusals below do not depend on this machine's memory

plate() {  # plate H LW [EXTRA]: the seed plate with mesh parameters h and lw
  cat <<CASE
[mesh]
file = "$src/meshes/plate2d.geo"
[mesh.parameters]
h = $1
lw = $2
[material]
young = 206e9
thickness = 0.002
[boundary]
rigid = ["base"]
[[load]]
group = "${3:-load}"
force = 2.0
CASE
}

msh_plate() {  # msh_plate FILE: the plate case on a .msh
  plate 0.01 0.02 | sed -e "s#$src/meshes/plate2d.geo#$1#" -e '/^\[mesh.parameters\]/,/^lw/d'
}

rod() {  # rod N [EXTRA_LINE]
  printf '[pbd]\nmesh = "%s"\nmesh_parameters = { L = 1, N = %s }\npinned = ["clamp"]\nframes = 3\nsubsteps = 2\n%s\n' \
    "$src/meshes/rod2d.geo" "$1" "${2:-}"
}

# expect NAME SUBCOMMAND EXPECTED_TEXT CASE_TEXT
expect() {
  local name=$1 cmd=$2 expected=$3 text=$4
  local dir="$work/$name"
  mkdir -p "$dir"
  local file="$dir/case.toml" out="$dir/out"
  printf '%s\n' "$text" >"$file"
  echo keep >"$dir/sentinel"
  timeout 120 "$bin" "$cmd" "$file" -o "$out" >"$dir/stdout" 2>"$dir/stderr"
  local rc=$?
  local lines
  lines=$(grep -vc '^pbd: ' "$dir/stderr")  # a run that fails while stepping has logged its progress
  if [ "$rc" -ne 2 ] || [ "$lines" -ne 1 ] || ! grep -qF -- "$expected" "$dir/stderr" || [ -e "$out" ] ||
     ls -a "$dir" | grep -q partial || [ "$(cat "$dir/sentinel")" != keep ]; then
    check "$name" 1 "exit $rc, $lines stderr lines, expected '$expected', got: $(head -c 600 "$dir/stderr")"
  else
    check "$name" 0 ""
  fi
}

c="case.toml"
expect nan_h agent "$c: mesh.parameters.h: must be a finite number (got nan)" "$(plate nan 0.02)"
expect nan_lw fem "$c: mesh.parameters.lw: must be a finite number (got nan)" "$(plate 0.01 nan)"
expect inf_N pbd "$c: pbd.mesh_parameters.N: must be a finite number (got inf)" "$(rod inf)"
expect nan_L pbd "$c: pbd.mesh_parameters.L: must be a finite number (got nan)" "$(rod 8 | sed 's/L = 1/L = nan/')"
expect huge_force agent "$c: load[0].force: magnitude above 1e+100" "$(plate 0.01 0.02 | sed 's/force = 2.0/force = 1e300/')"
expect tiny_thickness fem "$c: material.thickness: magnitude below 1e-100" "$(plate 0.01 0.02 | sed 's/thickness = 0.002/thickness = 1e-300/')"
expect huge_node_force pbd "$c: pbd.node_force: every entry magnitude above 1e+100" "$(rod 8 'node_force = [0, -1e300, 0]')"
expect diverging_pbd pbd "$c: pbd.gravity, pbd.node_force, pbd.time_step: the simulation diverged" \
  "$(rod 8 $'node_force = [0, -1e90, 0]\ntime_step = 1e60')"
expect rigid_load agent "$c: load[0].group: group 'base' is clamped (boundary.rigid)" "$(plate 0.01 0.02 base)"
expect rigid_load_compare compare "$c: load[0].group: group 'base' is clamped" "$(plate 0.01 0.02 base)"
expect too_many_agents agent "plate2d.geo: about 8e+08 elements (estimated from the .geo's curve divisions and mesh sizes) need an estimated" \
  "$(plate 1e-5 2e-5)"
expect wrapped_division_count agent "plate2d.geo: curve 1 would need about 5e+10 transfinite divisions" \
  "$(plate 0.02 0.04 | sed 's/^lw = 0.04/lw = 0.04\nW = 1e9/')"
expect too_many_segments pbd "rod2d.geo: about 1e+09 elements" "$(rod 1e9)"
body_force_case=$(sed -e "s#\.\./#$src/#g" -e 's/^body_force = .*/body_force = [0, -1e300]/' "$src/cases/pbd_strip_fem.toml")
expect huge_body_force compare "$c: fem.body_force: every entry magnitude above 1e+100" "$body_force_case"
for mesh in negative_tag duplicated nan_node; do
  for cmd in agent fem; do
    expect "msh_${mesh}_$cmd" "$cmd" "$src/tests/data/$mesh.msh: " "$(msh_plate "$src/tests/data/$mesh.msh")"
  done
done
expect msh_tag_message agent "negative_tag.msh: bad element node tag '-105'" "$(msh_plate "$src/tests/data/negative_tag.msh")"
expect msh_dup_message fem "duplicated.msh: elements 2 and 3 are the same element" "$(msh_plate "$src/tests/data/duplicated.msh")"
expect msh_nan_message agent "nan_node.msh: node 3 has a non-finite coordinate" "$(msh_plate "$src/tests/data/nan_node.msh")"
rod 8 >"$work/good.toml"  # a VTU of our own, cut short
"$bin" pbd "$work/good.toml" -o "$work/good" 2>/dev/null
head -c 1200 "$work/good/frames/frame_00000.vtu" >"$work/truncated.vtu"
expect truncated_vtu pbd "truncated.vtu: VTK could not read it (a truncated or malformed VTK XML file)" \
  "$(printf '[pbd]\nmesh = "%s"\nframes = 2\n' "$work/truncated.vtu")"

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
