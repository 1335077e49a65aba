#!/usr/bin/env bash
# Loads a rule set cannot carry, bending, and pulls (docs/agent-model.md, "Tension", "The carry
# check", "Bending: the column rule set"):
# - cases/cantilever.toml (clamped at its left end, loaded down at its tip) with the directional
#   rule set: the comparison names the load and the reason before FEM starts, points to the columns
#   rule set, the summary and JUnit say it, and the gate fails with it (exit 1);
# - cases/cantilever.toml as shipped (the columns rule set): carried to the clamp by bending, said
#   before the run, the whole load a reaction, its gate passed;
# - the seed plate with the columns rule set (its rigid base lies ahead of the load, one support):
#   refused while the case is read, one line, exit 2, nothing written;
# - cases/seed_plate_pulled.toml: every error equals the pushed plate's (seed_plate_directional),
#   bit for bit (FEM is odd in the load, and so is every rule set).
# Usage: compare_loads.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

"$bin" case set "$src/cases/cantilever.toml" agent.rule_set=directional -o "$work/cantilever_directional.toml" >"$work/set.log" 2>&1
check derive_directional $? "$(cat "$work/set.log")"
"$bin" compare "$work/cantilever_directional.toml" -o "$work/cantilever" >"$work/log" 2>&1
rc=$?
check cantilever_exit $((rc != 1)) "exit $rc: $(tail -3 "$work/log")"
said=$(grep -n 'compare: carry check: load\[0\] (group "load", 2 N -y, march -y): rigid exits 0 mm^2, free exits 220 mm^2: cannot carry: no rigid face ahead of the loaded face (march -y)' "$work/log" | head -1 | cut -d: -f1)
fem=$(grep -n '^fem:' "$work/log" | head -1 | cut -d: -f1)
check said_before_fem $((${said:-999999} >= ${fem:-0})) "carry line ${said:-missing}, first fem line ${fem:-missing}"
grep -q 'rigid faces lie ahead along -x: reached by bending; rule_set = "columns" carries it: bending: columns along x to the clamp at x = 0 mm' "$work/log"
check points_to_columns $? "$(grep 'carry check' "$work/log")"
grep -q '^compare: gate: carry check: load\[0\] .*cannot carry' "$work/log"
check gate_reason $? "$(grep 'gate' "$work/log")"
grep -q '<testcase classname="compare" name="carry_check"><failure message="carry check: load\[0\]' "$work/cantilever/junit.xml"
check junit_reason $? "$(grep carry "$work/cantilever/junit.xml")"
grep -q 'WARNING: agent: carry check: load\[0\]' "$work/cantilever/summary.txt"
check summary_warning $? "$(grep WARNING "$work/cantilever/summary.txt")"
/usr/bin/python3 -c "
import json, sys
j = json.load(open(sys.argv[1]))
c = j['carry_check'][0]
ok = not c['carries'] and c['rigid_exit_area'] == 0 and abs(c['free_exit_area'] - 22 * 0.005 * 0.002) < 1e-15
ok = ok and j['gate']['failed'] >= 1 and 'cannot carry' in j['gate']['refused'][0]
sys.exit(0 if ok else 1)" "$work/cantilever/summary.json"
check summary_json $? "$(grep -A8 carry_check "$work/cantilever/summary.json" | head -12)"

# The shipped cantilever: the columns carry it to the clamp.
"$bin" compare "$src/cases/cantilever.toml" -o "$work/columns" >"$work/columns.log" 2>&1
check columns_exit $? "$(tail -3 "$work/columns.log")"
said=$(grep -n 'compare: carry check: load\[0\] (group "load", 2 N -y, march -x): rigid exits 80 mm^2, free exits 0 mm^2: carries by bending: columns along x to the clamp at x = 0 mm' "$work/columns.log" | head -1 | cut -d: -f1)
fem=$(grep -n '^fem:' "$work/columns.log" | head -1 | cut -d: -f1)
check columns_said_before_fem $((${said:-999999} >= ${fem:-0})) "carry line ${said:-missing}, first fem line ${fem:-missing}"
/usr/bin/python3 -c "
import json, sys
j = json.load(open(sys.argv[1]))
m, c = j['metrics'], j['carry_check'][0]
ok = c['carries'] and m['agent.reaction_share']['value'] == 1 and not j['gate'].get('refused')
ok = ok and m['far.displacement.rel_l2']['value'] < 0.3 and m['far.sigma_x.rel_l2']['value'] < 0.3
sys.exit(0 if ok else 1)" "$work/columns/summary.json"
check columns_summary $? "$(grep -A8 carry_check "$work/columns/summary.json" | head -12)"

# The seed plate on its base with the columns: refused while read (exit 2), nothing written.
mkdir -p "$work/refusal"
agent_case | sed 's/^rule_set = .*/rule_set = "columns"/' >"$work/plate_columns.toml"
refused columns_refuse_the_plate 'agent.rule_set: the columns rule set cannot carry the loads: the rigid faces along the beam axis x form one support' \
  "$work/refusal" "$bin" compare "$work/plate_columns.toml" -o "$work/refusal_out"
[ ! -e "$work/refusal_out" ]
check columns_refusal_wrote_nothing $? "$(ls "$work/refusal_out" 2>&1)"

# The pulled plate: the same errors as the pushed one, and its load carried to the base.
"$bin" compare "$src/cases/seed_plate_directional.toml" -o "$work/push" >"$work/push.log" 2>&1
check push_exit $? "$(tail -3 "$work/push.log")"
"$bin" compare "$src/cases/seed_plate_pulled.toml" -o "$work/pull" >"$work/pull.log" 2>&1
check pull_exit $? "$(tail -3 "$work/pull.log")"
grep -q 'carry check: load\[0\] (group "load", 2 N +y, march -y): rigid exits 400 mm^2, free exits 0 mm^2: carries' "$work/pull.log"
check pull_carries $? "$(grep 'carry check' "$work/pull.log")"
/usr/bin/python3 -c "
import json, sys
a, b = (json.load(open(f))['metrics'] for f in sys.argv[1:3])
bad = [k for k in a if not k.startswith('time') and a[k]['value'] != b[k]['value']]
ok = not bad and len(a) > 100 and b['agent.reaction_share']['value'] > 0.999
print('differ:', bad[:5]) if bad else None
sys.exit(0 if ok else 1)" "$work/push/summary.json" "$work/pull/summary.json"
check pulled_errors_equal_pushed $? "see above"

echo "compare loads: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
