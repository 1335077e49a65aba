#!/usr/bin/env bash
# [[calibrate.held_out]]: a case scored with the start and the fitted coefficients, never fitted.
# Its errors in report.json are `workbench compare`'s body norms of the case file as it is (before)
# and of its calibrated case file (after), every field; a held-out case that is missing, named like
# a fitted one or given a key it does not take is refused (exit 2, one line, nothing written).
# Usage: calibrate_held_out.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

# The seed plate at 10 mm agents, the load centred (fitted) and 40 mm off centre (held out).
agent_case | sed '/^better_than_zero/d; /^\[compare.gate\]/,$d' >"$work/centred.toml"
sed 's/^lw = 0.02$/lw = 0.02\nxc = 0.06/' "$work/centred.toml" >"$work/offcentre.toml"
grep -q '^xc = 0.06$' "$work/offcentre.toml"
check offcentre_case $? "the load was not moved"
printf '%s\n' '[calibrate]' 'rule_set = "conserving"' 'starts = 1' 'max_evaluations = 12' 'keep_load = false' \
  '[[calibrate.case]]' 'file = "centred.toml"' '[[calibrate.held_out]]' 'file = "offcentre.toml"' >"$work/cal.toml"
"$bin" calibrate "$work/cal.toml" -o "$work/cal" >"$work/cal.log" 2>&1
check calibrate $? "$(tail -2 "$work/cal.log")"
grep -q "^held out (scored with the start and the fitted coefficients, never fitted):" "$work/cal/report.txt"
check report_txt_held_out $? "no held-out table in report.txt"

# The held-out case compared as it is and as calibrated (a gate may fail: exit 1 still writes).
"$bin" compare "$work/offcentre.toml" -o "$work/before" >"$work/before.log" 2>&1
[ $? -le 1 ] && [ -f "$work/before/summary.json" ]
check compare_before $? "$(tail -2 "$work/before.log")"
"$bin" compare "$work/cal/calibrated/offcentre.toml" -o "$work/after" >"$work/after.log" 2>&1
[ $? -le 1 ] && [ -f "$work/after/summary.json" ]
check compare_after $? "$(tail -2 "$work/after.log")"
/usr/bin/python3 - "$work" <<'PY'
import json, math, sys
w = sys.argv[1]
report = json.load(open(f"{w}/cal/report.json"))
held = report["held_out"]["offcentre"]
bad = [] if "offcentre" not in report["cases"] else ["the held-out case is among the fitted cases"]
for when in ("before", "after"):
    summary = json.load(open(f"{w}/{when}/summary.json"))
    if set(held[when]) != set(summary["fields"]):
        bad.append(f"{when}: fields {sorted(held[when])}, compare's {summary['fields']}")
    for field, error in held[when].items():
        body = summary["metrics"][f"body.{field}.rel_l2"]["value"]
        if not math.isclose(error, body, rel_tol=1e-9):
            bad.append(f"{when} {field}: calibrate {error}, compare {body}")
if held["before"]["sigma_y"] == held["after"]["sigma_y"]:
    bad.append("the fit did not move the held-out case's sigma_y")
print("\n".join(bad))
sys.exit(1 if bad else 0)
PY
check held_out_errors_are_compares $? "see above"

# Refused before anything is solved, the earlier output untouched.
printf '%s\n' '[calibrate]' '[[calibrate.case]]' 'file = "centred.toml"' '[[calibrate.held_out]]' 'file = "nowhere.toml"' >"$work/missing.toml"
refused held_out_missing "nowhere.toml: cannot read the case file" "$work/cal" "$bin" calibrate "$work/missing.toml" -o "$work/cal"
printf '%s\n' '[calibrate]' '[[calibrate.case]]' 'file = "centred.toml"' '[[calibrate.held_out]]' 'file = "centred.toml"' >"$work/twice.toml"
refused held_out_named_like_a_fitted_case "calibrate.held_out[0].file: a case named \"centred\" is listed already" "$work/cal" \
  "$bin" calibrate "$work/twice.toml" -o "$work/cal"
printf '%s\n' '[calibrate]' '[[calibrate.case]]' 'file = "centred.toml"' '[[calibrate.held_out]]' 'file = "offcentre.toml"' 'weight = 2' >"$work/weighted.toml"
refused held_out_weight "weight" "$work/cal" "$bin" calibrate "$work/weighted.toml" -o "$work/cal"

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
