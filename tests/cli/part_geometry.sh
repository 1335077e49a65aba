#!/usr/bin/env bash
# A researcher's own part (issue 39): tests/data/patch_plate.geo, a 300 x 150 mm plate with an
# off-centre 40 mm hole and a 10 mm load patch at x = px. The agents' mesh and the reference's are
# checked to be the same body before anything is solved (a load patch moved from x = 200 mm to
# 100 mm is exit 2 naming the group and both positions); [mesh] unit scales a millimetre part to
# metres; [mesh] agent_size voxelizes the .geo inside the run; --check reads the meshes the run
# would use; each mesh error names what fixes it. Usage: part_geometry.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

geo="$src/tests/data/patch_plate.geo"
cd "$work" || exit 1
# The staircases: 5 mm agents, 60 x 30 of them less the hole's: 1748 agents; the patch is 2 faces.
"$bin" voxelize "$geo" -s 0.005 -o right.msh 2>/dev/null &&
  "$bin" voxelize "$geo" -s 0.005 -p px=0.1 -o left.msh 2>/dev/null &&
  "$bin" voxelize "$geo" -s 0.003 -o fine.msh 2>/dev/null &&
  "$bin" voxelize "$geo" -s 5 -p u=1000 -o millimetres.msh 2>/dev/null
check staircases $? "voxelize failed"

case_file() {  # case_file MESH [MESH_KEYS] [REFERENCE]: the plate on its base, 2 N down on the patch
  printf '[mesh]\nfile = "%s"\n%b[boundary]\nrigid = ["base"]\n[[load]]\ngroup = "patch"\nforce = 2.0\n' "$1" "${2:-}"
  printf '[agent]\nrule_set = "directional"\n[compare]\nfigures = false\n'
  [ -n "${3:-}" ] && printf '[compare.reference]\nmesh = "%s"\n' "$3"
}
mkdir cases
case_file ../left.msh "" "$geo" >cases/moved.toml
case_file ../right.msh "" "$geo" >cases/same.toml
case_file ../fine.msh "" "$geo" >cases/fine.toml
case_file ../millimetres.msh >cases/mm_as_m.toml
case_file ../millimetres.msh 'unit = "mm"\n' >cases/mm.toml
case_file ../right.msh >cases/m.toml
case_file ../millimetres.msh 'unit = "mm"\n' "$geo" >cases/mm_against_m.toml
case_file "$geo" >cases/triangles.toml
case_file "$src/tests/data/plate_mm.step" 'unit = "mm"\nagent_size = 0.005\n' >cases/bare_step.toml
case_file "$geo" 'agent_size = 0.005\n' >cases/voxelized.toml
case_file "$geo" 'agent_size = 0.005\n[mesh.parameters]\npx = 0.1\n' >cases/voxelized_left.toml
case_file "$src/tests/data/step_plate.geo" 'unit = "mm"\nagent_size = 0.005\n' >cases/step.toml
case_file ../right.msh '[mesh.parameters]\nh = 1\n' >cases/msh_parameters.toml
case_file ../right.msh 'unit = "inch"\n' >cases/inch.toml
sed 's/"base"/"bottom"/' cases/m.toml >cases/no_group.toml

# 1. The same body: the moved patch is refused by the run and by --check, naming the load group and
# both centres (x = 100 mm against 200 mm at y = 150 mm); nothing written.
moved="load[0].group 'patch': its centre is (0.1, 0.15) in the agents' mesh and (0.2, 0.15) in the reference's"
refused moved_patch_run "compare.reference.mesh: $moved" "$work/cases" "$bin" compare cases/moved.toml -o refused/moved
[ ! -e refused ]
check moved_patch_nothing_left $? "left: $(ls -A refused 2>&1)"
refused moved_patch_check "$moved" "$work" "$bin" compare cases/moved.toml --check
# A millimetre staircase against a metre reference: the bounding boxes differ a thousandfold.
refused bounding_box "the body's bounding box is (0, 0) to (0.3, 0.15) in the agents' mesh and (0, 0) to (0.0003, 0.00015)" \
  "$work" "$bin" compare cases/mm_against_m.toml --check
"$bin" compare cases/same.toml --check 2>"$logs/err"
[ $? -eq 0 ] && grep -q "checked, nothing written" "$logs/err" && ! grep -q warning "$logs/err"
check same_body $? "$(cat "$logs/err")"
# 3 mm agents: the 10 mm patch is 3 faces, 9 mm: -10 %, the pressure 1/0.9 - 1 = +11.1 %; a warning.
"$bin" compare cases/fine.toml --check 2>"$logs/err"
[ $? -eq 0 ] && grep -q "compare: warning: load\[0\].group 'patch': the agents' load patch has length 0.009 m, the true patch 0.01 m (-10 %); the force stays the case's 2 N, so the agents' pressure on it is 11.1 % off" "$logs/err"
check patch_warning $? "$(cat "$logs/err")"

# 2. Units: the millimetre staircase read as metres is a 300 m plate, a warning naming mesh.unit; with
# unit = "mm" the agents give what the metre staircase gives, byte for byte.
"$bin" agent cases/mm_as_m.toml --check 2>"$logs/err"
[ $? -eq 0 ] && grep -q "agent: warning: .*millimetres.msh: the body is 300 m long .*set mesh.unit" "$logs/err"
check unit_warning $? "$(cat "$logs/err")"
"$bin" fem cases/mm_as_m.toml -o out/mm_as_m_fem 2>"$logs/err" && grep -q "fem: warning: .*millimetres.msh: the body is 300 m long" "$logs/err"
check unit_warning_fem $? "$(cat "$logs/err")"
"$bin" agent cases/mm.toml -o out/mm 2>"$logs/err" && "$bin" agent cases/m.toml -o out/m 2>>"$logs/err" &&
  ! grep -q warning: "$logs/err" && cmp -s out/mm/agent_cells.csv out/m/agent_cells.csv
check unit_mm_same_agents $? "$(cat "$logs/err")"
"$bin" voxelize "$geo" -p u=1000 -u mm -s 0.005 -o millimetres_in_m.msh 2>"$logs/err" &&
  grep -q "^voxelize: 1748 agents of 0.005 m in a 60 x 30 box" "$logs/err"
check voxelize_unit $? "$(cat "$logs/err")"
refused unit_unknown 'mesh.unit: must be one of "m", "cm", "mm" (got "inch")' "$work" "$bin" agent cases/inch.toml --check

# 3. One geometry file: [mesh] agent_size voxelizes the .geo in the run, the same 1748 agents as
# `workbench voxelize` wrote, the same results.
"$bin" agent cases/voxelized.toml -o out/voxelized 2>"$logs/err" &&
  [ "$(($(wc -l <out/voxelized/agent_cells.csv) - 1))" -eq 1748 ] && cmp -s out/voxelized/agent_cells.csv out/m/agent_cells.csv
check agent_size $? "$(cat "$logs/err")"

# The comparison of that case: the reference on the .geo itself (the true geometry), FEM on the
# agents' staircase beside it: every metric what the voxelized .msh against the .geo gives.
"$bin" compare cases/voxelized.toml -o out/voxelized_compare 2>"$logs/err" &&
  "$bin" compare cases/same.toml -o out/same_compare 2>>"$logs/err" &&
  [ -s out/voxelized_compare/agent_staircase.msh ] && /usr/bin/python3 - out/voxelized_compare out/same_compare <<'EOF'
import json, sys
a, b = (json.load(open(d + "/summary.json"))["metrics"] for d in sys.argv[1:])
differ = [k for k in a if not k.startswith("time.") and a[k] != b[k]]
sys.exit(f"differ: {differ[:5]}" if differ or len(a) < 100 else 0)
EOF
check agent_size_compare $? "$(tail -3 "$logs/err")"
# The same [mesh.parameters] for both models: the patch at px = 100 mm in the agents and the reference
# alike (the check passes), its load line at x = 100 mm.
"$bin" compare cases/voxelized_left.toml -o out/left 2>"$logs/err" && grep -q line_x100y147p5_x100y2p5 out/left/summary.txt
check agent_size_parameters $? "$(tail -3 "$logs/err")"
# A millimetre STEP file merged by a .geo, unit = "mm": the same 1748 agents as the metre .geo, byte
# for byte; its comparison within 1 % of the metre one's body sigma_y error (0.082: the two references
# mesh the hole differently), its lines named in millimetres.
"$bin" agent cases/step.toml -o out/step 2>"$logs/err" && cmp -s out/step/agent_cells.csv out/m/agent_cells.csv
check step_mm_agents $? "$(cat "$logs/err")"
"$bin" compare cases/step.toml -o out/step_compare 2>"$logs/err" && grep -q line_x200y147p5_x200y2p5 out/step_compare/summary.txt &&
  /usr/bin/python3 - out/step_compare out/same_compare <<'EOF'
import json, sys
a, b = (json.load(open(d + "/summary.json"))["metrics"]["body.sigma_y.rel_l2"]["value"] for d in sys.argv[1:])
sys.exit(0 if 0.07 < b < 0.09 and abs(a - b) < 0.01 * b else f"body.sigma_y.rel_l2 {a} against {b}")
EOF
check step_mm_compare $? "$(tail -3 "$logs/err")"

# 4. --check reads the mesh the run would use, and each mesh error names what fixes it.
refused triangles_compare_check "has Triangle 3 elements; the agent method needs a structured mesh of 4-node squares (Transfinite + Recombine); for a body of any shape give [mesh] agent_size" \
  "$work" "$bin" compare cases/triangles.toml --check
refused triangles_names_voxelize '`workbench voxelize`' "$work" "$bin" agent cases/triangles.toml --check
refused bare_step "plate_mm.step: a mesh must be a gmsh .geo or .msh file; a CAD file is read through a .geo that Merges it" \
  "$work" "$bin" compare cases/bare_step.toml --check
refused msh_parameters_compare "mesh parameters ([mesh.parameters], pbd.mesh_parameters) apply to .geo files only" \
  "$work" "$bin" compare cases/msh_parameters.toml --check
refused msh_parameters_fem "mesh parameters ([mesh.parameters]" "$work" "$bin" fem cases/msh_parameters.toml --check
refused fem_group "boundary.rigid: group 'bottom' is not a physical group of right.msh" \
  "$work" "$bin" fem cases/no_group.toml --check

echo "part geometry: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
