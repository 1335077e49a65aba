#!/usr/bin/env bash
# `workbench case set`: a derived key reads back, the author's comments stay, the mesh path still
# names the mesh from another folder (and stays relative beside the original), a bad key or value
# is one line with exit 2 and nothing written, an existing file is replaced only with --force.
# Usage: case_set.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

base="$src/cases/gate_plate.toml"
mkdir -p "$work/out"
"$bin" case set "$base" mesh.parameters.h=0.01 mesh.parameters.lw=0.02 agent.rule_set=patent load.0.force=3 \
  'agent.readings=["entering_face_stress"]' title=derived -o "$work/out/a.toml" 2>"$logs/log"
check set_exit $? "$(cat "$logs/log")"
/usr/bin/python3 - "$work/out/a.toml" "$src/meshes/plate2d.geo" <<'PY'
import sys, tomllib, os
c = tomllib.load(open(sys.argv[1], "rb"))
assert c["mesh"]["parameters"]["h"] == 0.01 and c["mesh"]["parameters"]["lw"] == 0.02, c["mesh"]
assert c["agent"]["rule_set"] == "patent" and c["agent"]["gamma"] == 1e-6, c["agent"]
assert c["agent"]["readings"] == ["entering_face_stress"], c["agent"]
assert c["load"][0]["force"] == 3 and c["load"][0]["group"] == "load", c["load"]
assert c["title"] == "derived" and c["compare"]["gate"]["far.sigma_y.rel_l2"] == 0.99
assert os.path.isabs(c["mesh"]["file"]) and os.path.samefile(c["mesh"]["file"], sys.argv[2]), c["mesh"]["file"]
PY
check read_back $? "$(cat "$work/out/a.toml")"
grep -q '^"line_x100y197p5_x100y2p5.sigma_y.rel_l2" = 0.7   # the line under the load, x = 100 mm$' "$work/out/a.toml"
check comments_kept $? "the gate's comment is gone"
grep -q '^# Derived by `workbench case set ' "$work/out/a.toml"
check provenance $? "$(head -1 "$work/out/a.toml")"
# The derived case runs: its mesh resolves from the new folder.
"$bin" agent "$work/out/a.toml" --check 2>"$logs/log"
check mesh_resolves $? "$(cat "$logs/log")"

# Beside the original the relative mesh path stays as the author wrote it.
mkdir -p "$work/tree/cases" "$work/tree/meshes"
cp "$base" "$work/tree/cases/" && cp "$src/meshes/plate2d.geo" "$work/tree/meshes/"
"$bin" case set "$work/tree/cases/gate_plate.toml" agent.alpha3=0.2 -o "$work/tree/cases/b.toml" 2>"$logs/log"
check beside_exit $? "$(cat "$logs/log")"
grep -q '^file = "../meshes/plate2d.geo"' "$work/tree/cases/b.toml"
check beside_relative $? "$(grep '^file' "$work/tree/cases/b.toml")"
grep -q '^alpha3 = 0.2$' "$work/tree/cases/b.toml"
check beside_added $? "$(sed -n '/\[agent\]/,/^$/p' "$work/tree/cases/b.toml")"

# Refusals: one line, exit 2, nothing written.
refused bad_key "agent.alpah1" "$work/out" "$bin" case set "$base" agent.alpah1=0.3 -o "$work/out/c.toml"
refused bad_value "agent.alpha1: in [0, 1] (got 1.5)" "$work/out" "$bin" case set "$base" agent.alpha1=1.5 -o "$work/out/c.toml"
refused bad_type "steps.count: must be an integer" "$work/out" "$bin" case set "$base" steps.count=x -o "$work/out/c.toml"
refused not_a_setting "agent: expected KEY=VALUE" "$work/out" "$bin" case set "$base" agent -o "$work/out/c.toml"
refused no_entry "load[3]: no such entry" "$work/out" "$bin" case set "$base" load.3.force=1 -o "$work/out/c.toml"
refused entry_not_key "load.0: names an entry" "$work/out" "$bin" case set "$base" load.0=1 -o "$work/out/c.toml"
refused bad_toml "agent.readings: \"[1,\" is not a TOML value" "$work/out" "$bin" case set "$base" 'agent.readings=[1,' -o "$work/out/c.toml"
refused missing_mesh "mesh.file: no such file" "$work/out" "$bin" case set "$base" mesh.file=nowhere.geo -o "$work/out/c.toml"
refused missing_case "nowhere.toml: cannot read the case file" "$work/out" "$bin" case set "$work/nowhere.toml" agent.alpha1=0.3 -o "$work/out/c.toml"
refused exists "a.toml: exists (--force replaces it)" "$work/out" "$bin" case set "$base" agent.alpha1=0.3 -o "$work/out/a.toml"
"$bin" case set "$base" agent.alpha1=0.3 -o "$work/out/a.toml" --force 2>"$logs/log"
check force_exit $? "$(cat "$logs/log")"
grep -q '^alpha1 = 0.3$' "$work/out/a.toml" && ! grep -q '^rule_set = "patent"' "$work/out/a.toml"
check force_replaced $? "$(sed -n '/\[agent\]/,/^$/p' "$work/out/a.toml")"
[ -z "$(find "$work/out" -name '.*partial*')" ]
check no_partial $? "$(ls -a "$work/out")"

echo "case_set: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
