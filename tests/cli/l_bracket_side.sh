#!/usr/bin/env bash
# An L-bracket clamped at its side (cases/l_bracket_side.toml: 200 x 200 mm, arm and foot 50 mm, the
# back x = 0 clamped, 2 N down at the foot's end), no rule set named: auto finds no rigid face ahead
# of the load and bends it to the clamp (the columns, the section spreading into the corner and the
# arm at 45 degrees, the clamp's layer giving sigma_y). Issue 40's targets: reaction = load to 1 %,
# far displacement <= 0.2 and von Mises <= 0.25, every stress component modelled and better than zero.
# Usage: l_bracket_side.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

cd "$work" || exit 1
sed -e "s#\.\./meshes#$src/meshes#" "$src/cases/l_bracket_side.toml" >bracket.toml
"$bin" compare bracket.toml -o run >run.log 2>&1
check compare_runs $? "$(tail -3 run.log)"
grep -q 'auto chose columns: carries by bending: columns along x to the clamp at x = 0 mm' run.log
check auto_chose_columns $? "$(grep 'carry check' run.log)"

/usr/bin/python3 - run <<'PY'
import json, sys
run = sys.argv[1]
agent = json.load(open(f"{run}/agent/agent_summary.json"))
summary = json.load(open(f"{run}/summary.json"))
m = summary["metrics"]
fails = []
def need(ok, what):
    if not ok: fails.append(what)
need(agent["rule_set"] == "auto" and [c["rule_set"] for c in summary["carry_check"]] == ["columns"], f"choices {summary['carry_check']}")
need(abs(agent["load_balance"]["reaction_share"] - 1) < 0.01, f"reaction share {agent['load_balance']['reaction_share']}")
need(m["far.displacement.rel_l2"]["value"] <= 0.2, f"far displacement {m['far.displacement.rel_l2']['value']}")
need(m["far.von_mises.rel_l2"]["value"] <= 0.25, f"far von Mises {m['far.von_mises.rel_l2']['value']}")
for c in ["sigma_x", "sigma_y", "tau_xy"]:
    e = m[f"far.{c}.rel_l2"]
    need(e.get("modelled", True) and 0 < e["value"] < 1, f"far.{c}.rel_l2 = {e['value']} (modelled {e.get('modelled', True)})")
print("\n".join(fails))
sys.exit(1 if fails else 0)
PY
check targets $? "see above"

echo "l_bracket_side: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
