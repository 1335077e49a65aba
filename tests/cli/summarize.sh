#!/usr/bin/env bash
# `workbench summarize`: the table holds, per folder, every metric of its summary.json (the same
# numbers), the metrics its rule set does not model (marked as summary.json marks them) and the case
# keys that differ between the folders' cases; a row without a metric has an empty cell; a missing folder or one without a summary is one line with exit 2.
# Usage: summarize.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

base="$src/cases/seed_plate.toml"
for rules in conserving patent; do
  "$bin" case set "$base" mesh.parameters.h=0.02 mesh.parameters.lw=0.04 compare.figures=false agent.rule_set=$rules -o "$work/$rules.toml" 2>"$logs/log"
  check "case_$rules" $? "$(cat "$logs/log")"
  "$bin" compare "$work/$rules.toml" -o "$work/runs/$rules" 2>"$logs/log"
  rc=$?
  check "compare_$rules" $((rc > 1)) "exit $rc: $(tail -3 "$logs/log")"
done
"$bin" compare "$src/cases/pbd_strip_fem.toml" -o "$work/runs/pbd" 2>"$logs/log"
check compare_pbd $? "$(tail -3 "$logs/log")"
# The two plates: one parameter, the rule set.
"$bin" summarize "$work/runs/conserving" "$work/runs/patent" -o "$work/plates.csv" --json "$work/plates.json" 2>"$logs/log"
check summarize_plates $? "$(cat "$logs/log")"
/usr/bin/python3 "$src/tests/cli/check_summary_table.py" "$work/plates.csv" "$work/plates.json" agent.rule_set
check plates_equal_summaries $? "see above"
# With the PBD strip, whose case differs in nearly every key.
"$bin" summarize "$work/runs/conserving" "$work/runs/patent" "$work/runs/pbd" -o "$work/table.csv" --json "$work/table.json" 2>"$logs/log"
check summarize_exit $? "$(cat "$logs/log")"
parameters=$(/usr/bin/python3 -c "import json, sys; print(' '.join(json.load(open(sys.argv[1]))['parameters']))" "$work/table.json")
/usr/bin/python3 "$src/tests/cli/check_summary_table.py" "$work/table.csv" "$work/table.json" $parameters
check table_equals_summaries $? "see above"
/usr/bin/python3 - "$work/table.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
# The PBD strip has no agent metrics, the plates no PBD ones: empty cells, not zeros.
assert rows[2]["agent.equilibrium_dev"] == "" and rows[0]["agent.equilibrium_dev"] != "", rows[2]
assert rows[0]["tip.deflection.rel_error"] == "" and rows[2]["tip.deflection.rel_error"] != "", rows[0]
assert [r["agent.rule_set"] for r in rows] == ["conserving", "patent", ""], [r["agent.rule_set"] for r in rows]
assert rows[2]["pbd.frames"] != "" and rows[0]["pbd.frames"] == "" and "mesh.parameters.h" in rows[0], rows[2]
PY
check empty_cells $? "see above"
# A component the rule set does not model is marked, as compare's summary marks it: both plate rule
# sets leave the shear out (its value 1, the zero model's), the PBD strip has nothing of the kind;
# a modelled metric is not marked.
/usr/bin/python3 - "$work/table.csv" "$work/table.json" <<'PY'
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1])))
marked = [r["not_modelled"].split() for r in rows]
for names, row in zip(marked[:2], rows):
    assert {"far.tau_xy.rel_l2", "body.tau_xy.rel_l2"} <= set(names), names
    assert all(".tau_xy." in n for n in names), names
    assert float(row["far.tau_xy.rel_l2"]) == 1.0, row["far.tau_xy.rel_l2"]
    assert float(row["far.sigma_y.rel_l2"]) < 1 and "far.sigma_y.rel_l2" not in names, names
assert marked[2] == [], marked[2]
assert [r["not_modelled"] for r in json.load(open(sys.argv[2]))["rows"]] == marked
PY
check not_modelled_marked $? "see above"

# The Python module gives the same table (when it is built).
if [ -d "$(dirname "$bin")/../python" ]; then
  PYTHONPATH="$(dirname "$bin")/../python" /usr/bin/python3 - "$work/table.json" "$work/runs/conserving" \
    "$work/runs/patent" "$work/runs/pbd" <<'PY'
import json, sys, workbench
t = workbench.summarize(sys.argv[2:])
assert t == json.load(open(sys.argv[1])), "workbench.summarize differs from the JSON table"
PY
  check python_module $? "see above"
fi

# A calibration's folder: every number of its report.json, named by its dotted place.
printf '[calibrate]\nrule_set = "conserving"\nstarts = 1\nmax_evaluations = 20\n[[calibrate.case]]\nfile = "conserving.toml"\n' >"$work/calibrate.toml"
"$bin" calibrate "$work/calibrate.toml" -o "$work/runs/calibration" >/dev/null 2>"$logs/log"
check calibrate $? "$(tail -3 "$logs/log")"
"$bin" summarize "$work/runs/calibration" -o "$work/calibration.csv" 2>"$logs/log"
check summarize_calibration $? "$(cat "$logs/log")"
/usr/bin/python3 - "$work/calibration.csv" "$work/runs/calibration/report.json" <<'PY'
import csv, json, sys
row = next(csv.DictReader(open(sys.argv[1])))
def numbers(j, prefix=""):
    for k, v in j.items():
        if isinstance(v, dict):
            yield from numbers(v, prefix + k + ".")
        elif isinstance(v, (int, float)) and not isinstance(v, bool):
            yield prefix + k, v
expected = dict(numbers(json.load(open(sys.argv[2]))))
assert set(row) - {"folder", "not_modelled"} == set(expected), sorted(set(row) ^ set(expected))
assert row["not_modelled"] == "", row["not_modelled"]  # a calibration's report.json marks none
assert all(float(row[k]) == v for k, v in expected.items()), [k for k, v in expected.items() if float(row[k]) != v]
assert "fitted.alpha2" in expected and "objective.fitted" in expected, sorted(expected)
PY
check calibration_table $? "see above"

mkdir -p "$work/empty"
"$bin" agent "$work/patent.toml" -o "$work/agent_only" 2>/dev/null
refused missing_folder "nowhere: no such folder" "$work/runs" "$bin" summarize "$work/runs/patent" "$work/nowhere" -o "$work/t2.csv"
refused no_summary "agent_only: has no summary.json" "$work/runs" "$bin" summarize "$work/runs/patent" "$work/agent_only" -o "$work/t2.csv"
refused not_ours "empty: has no summary.json" "$work/runs" "$bin" summarize "$work/empty" -o "$work/t2.csv"
refused exists "table.csv: exists (--force replaces it)" "$work/runs" "$bin" summarize "$work/runs/patent" -o "$work/table.csv"
[ ! -e "$work/t2.csv" ]
check nothing_written $? "t2.csv written"
"$bin" summarize "$work/runs/patent" -o "$work/table.csv" --force 2>"$logs/log"
check force $? "$(cat "$logs/log")"

echo "summarize: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
