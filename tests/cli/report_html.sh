#!/usr/bin/env bash
# One page per study: report.html of an agent comparison (with figures), a PBD comparison and a
# calibration, each opened in headless Chromium and checked against its summary.json / report.json
# (tests/common/check_report.py: no console error, every image and link resolves, every number
# shown is the JSON's). The check itself fails on a page whose number differs from the JSON; a
# "worse than zero" flag in summary.json shows on the page; a report that cannot be rendered fails
# the study (exit 2, one error line) and leaves the previous result whole.
# Usage: report_html.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"
py=/usr/bin/python3
checker="$py $src/tests/common/check_report.py"
render="$py $src/compare/report_html.py"

# The gated plate with its figures (the page embeds them), and the PBD strip.
sed -e "s#^file = \"\.\./#file = \"$src/#" -e 's/^figures = false/figures = true/' "$src/cases/gate_plate.toml" >"$work/plate.toml"
"$bin" compare "$work/plate.toml" -o "$work/plate" >"$work/plate.log" 2>&1
check compare_plate $? "$(tail -2 "$work/plate.log")"
sed -e 's|^mesh = "\(.*\)"|mesh = "'"$src"'/cases/\1"|' -e 's|^file = "\(.*\)"|file = "'"$src"'/cases/\1"|' \
  "$src/cases/pbd_strip_fem.toml" >"$work/strip.toml"
"$bin" compare "$work/strip.toml" -o "$work/strip" >"$work/strip.log" 2>&1
check compare_pbd $? "$(tail -2 "$work/strip.log")"
# The same strip with one limit tightened: exit 1, and the page says which metric failed.
sed 's/^"centreline.deflection.rel_l2" = .*/"centreline.deflection.rel_l2" = 1.0e-9/' "$work/strip.toml" >"$work/tight.toml"
"$bin" compare "$work/tight.toml" -o "$work/tight" >"$work/tight.log" 2>&1
check compare_pbd_gate_fails $(( $? != 1 )) "exit status not 1: $(tail -2 "$work/tight.log")"
grep -q 'Gate FAILED: <span data-key="/gate/failed" data-format="num">1</span>' "$work/tight/report.html" &&
  grep -q 'data-key="/metrics/centreline.deflection.rel_l2/passed" data-format="pass">EXCEEDED<' "$work/tight/report.html"
check page_says_gate_failed $? "no 'Gate FAILED' with the exceeded metric on the page"
# A calibration of two cases (so that it cross-validates), a few evaluations, and a case held out
# (the load 40 mm off centre: scored, never fitted; check_report.py requires its every field).
cp "$work/plate.toml" "$work/plate_b.toml"
sed 's/^lw = 0.01$/lw = 0.01\nxc = 0.06/' "$work/plate.toml" >"$work/plate_off.toml"
printf '%s\n' 'title = "Report test calibration"' '[calibrate]' 'starts = 1' 'max_evaluations = 8' \
  '[[calibrate.case]]' 'file = "plate.toml"' '[[calibrate.case]]' 'file = "plate_b.toml"' \
  '[[calibrate.held_out]]' 'file = "plate_off.toml"' >"$work/cal.toml"
"$bin" calibrate "$work/cal.toml" -o "$work/cal" >"$work/cal.log" 2>&1
check calibrate $? "$(tail -2 "$work/cal.log")"
# The directional rule set, the plate's threshold the relative one (the case's own: gamma held).
sed 's/^gamma = 1.0e-6$/gamma_relative = 1e-9/' "$work/plate.toml" >"$work/plate_rel.toml"
printf '%s\n' '[calibrate]' 'rule_set = "directional"' 'starts = 1' 'max_evaluations = 4' 'cross_validate = false' \
  '[[calibrate.case]]' 'file = "plate_rel.toml"' >"$work/cal_dir.toml"
"$bin" calibrate "$work/cal_dir.toml" -o "$work/cal_dir" >"$work/cal_dir.log" 2>&1
check calibrate_directional $? "$(tail -2 "$work/cal_dir.log")"

$checker "$work/plate" "$work/strip" "$work/tight" "$work/cal" "$work/cal_dir"
check pages_in_chromium $? "see above"
# Every compared field in the first table; each badge explained; which threshold acts.
page="$work/plate/report.html"
for f in tau_xy von_mises u_x u_y; do grep -q "data-key=\"/metrics/far.$f.rel_l2/value\"" "$page" || echo "no far.$f on the page"; done >"$work/fields.log"
[ ! -s "$work/fields.log" ] && grep -q '<dt><span class="flag">resolved</span></dt>' "$page" &&
  grep -q 'gamma_relative</span> <span data-key="/agent/coefficients/gamma_relative" data-format="num">1e-09</span> (not in effect' "$page" &&
  grep -q '(the threshold in effect: gamma = <span data-key="/agent/threshold/gamma_in_effect" data-format="num">1e-06</span> N)' "$page"
check page_fields_badges_threshold $? "$(cat "$work/fields.log")"
# The held-out case on the page with its errors before and after; its calibrated case file.
grep -q 'data-key="/held_out/plate_off/before/tau_xy"' "$work/cal/report.html" &&
  grep -q 'data-key="/held_out/plate_off/after/sigma_y"' "$work/cal/report.html" && [ -f "$work/cal/calibrated/plate_off.toml" ]
check page_held_out $? "no held-out case on the calibration page"
# The directional fit shows its own coefficients, not the seed rule sets'; the case's relative threshold acts.
page="$work/cal_dir/report.html"
grep -q 'data-key="/fitted/fan_angle"' "$page" && ! grep -q 'data-key="/fitted/alpha' "$page" &&
  ! grep -q 'data-key="/fitted/beta"' "$page" &&
  grep -q 'data-key="/cases/plate_rel/threshold/coefficient" data-format="text">gamma_relative<' "$page" &&
  grep -q 'data-key="/cases/plate_rel/threshold/fitted" data-format="num">2e-09<' "$page"
check page_directional_coefficients $? "the directional calibration's page shows the patent coefficients or not its threshold"
ls "$work/plate/figures/"*.png >/dev/null 2>&1 && [ "$(grep -c '<img src="data:image/png;base64,' "$work/plate/report.html")" -ge 5 ]
check figures_embedded $? "fewer than five embedded PNG figures on the plate's page"

# The check fails on a page that shows a number the JSON does not hold.
cp -r "$work/plate" "$work/tampered"
$py - "$work/tampered/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["metrics"]["body.sigma_y.rel_l2"]["value"] *= 1.01
json.dump(s, open(sys.argv[1], "w"))
PY
$checker "$work/tampered" >"$work/tampered.log" 2>&1
[ $? -eq 1 ] && grep -q "/metrics/body.sigma_y.rel_l2/value: shows" "$work/tampered.log"
check check_catches_a_wrong_number $? "$(cat "$work/tampered.log")"

# ... and on a page with a console error (an inline script, refused by the page's policy) and an
# image that does not decode.
cp -r "$work/cal" "$work/broken_page"
sed -i 's|</body>|<script>console.error("x")</script><img src="data:image/png;base64,AAAA"></body>|' "$work/broken_page/report.html"
$checker "$work/broken_page" >"$work/broken_page.log" 2>&1
[ $? -eq 1 ] && grep -q "log error: .*Content Security Policy" "$work/broken_page.log" &&
  grep -q "not an embedded image that loaded" "$work/broken_page.log"
check check_catches_console_errors_and_broken_images $? "$(cat "$work/broken_page.log")"

# A boolean beside an error (e.g. worse than a zero model) shows as a flag, and the check requires it.
cp -r "$work/plate" "$work/flagged"
$py - "$work/flagged/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["metrics"]["far.sigma_y.rel_l2"]["worse_than_zero"] = True
s["metrics"]["body.sigma_y.rel_l2"]["worse_than_zero"] = False
json.dump(s, open(sys.argv[1], "w"))
PY
$render "$work/flagged" >/dev/null && $checker "$work/flagged" >/dev/null &&
  grep -q 'data-key="/metrics/far.sigma_y.rel_l2/worse_than_zero" data-format="flag">worse than zero<' "$work/flagged/report.html" &&
  ! grep -q 'data-key="/metrics/body.sigma_y.rel_l2/worse_than_zero"' "$work/flagged/report.html"
check worse_than_zero_flag $? "the flag is not shown (or shown when false)"

# A template that does not render: the study fails (exit 2, the error as its last line), the
# previous result stays whole and no page is left half written. The strip's page is rendered by
# report_html.py, the plate's by figures.py, which drew the plate's figures beside the study.
scripts=$(dirname "$bin")/../share/workbench
cp -r "$scripts" "$work/scripts"
echo '{{ d.no_such_key }}' >>"$work/scripts/compare/report.html.j2"
for study in strip plate; do
  before=$(snapshot "$work/$study")
  WORKBENCH_SCRIPT_DIR="$work/scripts" "$bin" compare "$work/$study.toml" -o "$work/$study" >"$work/broken.log" 2>&1
  rc=$?
  [ $rc -eq 2 ] && tail -1 "$work/broken.log" | grep -q "^workbench: error: report_html.py failed: .*no_such_key" &&
    [ "$(grep -c '^workbench: error' "$work/broken.log")" -eq 1 ] && [ "$before" = "$(snapshot "$work/$study")" ]
  check "broken_report_fails_the_study ($study)" $? "exit $rc: $(tail -1 "$work/broken.log")"
done
rm "$work/flagged/report.html"
$py "$work/scripts/compare/report_html.py" "$work/flagged" 2>"$work/render.err"
[ $? -eq 1 ] && [ ! -e "$work/flagged/report.html" ] && [ ! -e "$work/flagged/report.html.part" ] && [ "$(wc -l <"$work/render.err")" -eq 1 ]
check no_half_page $? "$(cat "$work/render.err")"

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
