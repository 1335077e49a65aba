#!/usr/bin/env bash
# The default rule set (auto: per load the rule set that carries it) and an inclined load, end to
# end: cases/seed_plate_inclined.toml at 10 mm agents (2 N, 30 degrees from -y toward +x, no rule
# set named). The push onto the base marches, the shear along the top bends; both reach the base;
# the FEM takes the vector whole; the agents beat predicting nothing. A load no rule set carries is
# refused before anything runs. Usage: auto_inclined.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

cd "$work" || exit 1
sed -e "s#\.\./meshes#$src/meshes#" -e 's/^h = 0.002 /h = 0.01 /' -e 's/^lw = 0.004 /lw = 0.02 /' \
  "$src/cases/seed_plate_inclined.toml" >inclined.toml
printf 'figures = false\n' >>inclined.toml  # the last table is [compare]
"$bin" compare inclined.toml -o run >run.log 2>&1
check compare_runs $? "$(tail -3 run.log)"
grep -q 'auto chose directional' run.log && grep -q 'auto chose columns: .*carries by bending: columns along y to the clamp at y = 0 mm' run.log
check choices_logged $? "$(grep 'carry check' run.log)"

/usr/bin/python3 - run <<'EOF'
import json, math, sys
run = sys.argv[1]
agent = json.load(open(f"{run}/agent/agent_summary.json"))
summary = json.load(open(f"{run}/summary.json"))
fails = []
def need(ok, what):
    if not ok: fails.append(what)
need(agent["rule_set"] == "auto" and len(agent["rule_set_choices"]) == 2, f"rule_set {agent['rule_set']}, choices {agent.get('rule_set_choices')}")
chosen = sorted((c["march"], c["rule_set"]) for c in summary["carry_check"])
need([r for _, r in chosen] == ["columns", "directional"] and all(c["carries"] for c in summary["carry_check"]), f"carry check {chosen}")
# 2 N at 30 degrees: 1 N along +x, sqrt(3) N along -y.
fx, fy = agent["load_vector"]
need(abs(fx - 1.0) < 1e-12 and abs(fy + math.sqrt(3)) < 1e-12, f"load vector {fx}, {fy}")
need(abs(agent["load_balance"]["reaction_share"] - 1) < 1e-6, f"reaction share {agent['load_balance']['reaction_share']}")
# Each metric says whether it beats predicting nothing (error 1): these two must.
for name in ["far.sigma_y.rel_l2", "far.von_mises.rel_l2"]:
    m = summary["metrics"][name]
    need(0 < m["value"] < 1, f"{name} = {m['value']}")
print("\n".join(fails))
sys.exit(1 if fails else 0)
EOF
check summaries $? "see above"

# The FEM applies the vector whole: 1 N along +x and sqrt(3) N along -y, balanced by the base.
/usr/bin/python3 - run/fem <<'EOF'
import csv, math, sys
rows = {r["group"]: r for r in csv.DictReader(open(f"{sys.argv[1]}/fem_reactions.csv"))}
applied, base = rows["(applied)"], rows["base"]
ok = abs(float(applied["f_x [N]"]) - 1) < 1e-12 and abs(float(applied["f_y [N]"]) + math.sqrt(3)) < 1e-12
ok = ok and abs(float(base["f_x [N]"]) + 1) < 1e-6 and abs(float(base["f_y [N]"]) - math.sqrt(3)) < 1e-6
print("" if ok else f"FEM reactions {rows}")
sys.exit(0 if ok else 1)
EOF
check fem_takes_the_vector $? "see above"

# An axial pull on a cantilever's free end: no rigid face ahead, the clamp is along the load.
mkdir cases
sed -e "s#\.\./meshes#$src/meshes#" -e 's/^direction = "-y"/direction = "+x"/' -e '/^rule_set = "columns"/d' \
  "$src/cases/cantilever.toml" >cases/axial.toml
refused axial_refused 'axial.toml: load[0]: no rule set carries it (agent.rule_set = "auto")' cases "$bin" compare cases/axial.toml -o refused/axial
[ ! -e refused ]
check axial_nothing_left $? "left: $(ls -A refused 2>&1)"

echo "auto_inclined: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
