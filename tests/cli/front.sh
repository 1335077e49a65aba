#!/usr/bin/env bash
# `workbench front` on the gate plate (5 mm agents) with short ladders: its error at the case's own
# agent size is `workbench compare`'s, number for number; a field its rule set does not model gets
# no verdict; each speed-up is the FEM's time at that error read log-log off front.json's own
# points; the gate passes, fails (exit 1) or refuses bad names (exit 2); more than one MPI rank is
# refused. Usage: front.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

case_file() {  # the gate plate with a short front: agents 10 (not meshable: the load patch), 5 and 2.5 mm,
  # FEM Q1 5, 2.5 and 1.25 mm, 2 runs each
  sed -e "s#\.\./meshes#$src/meshes#" "$src/cases/gate_plate.toml"
  printf '\n[front]\nagent_sizes = [2, 1, 0.5]\nfem_sizes = [1, 0.5, 0.25]\nfem_degrees = [1]\nruns = 2\n'
  printf '[front.gate]\non_front = ["body.sigma_y.rel_l2"]\n%s\n' "${1:-}"
}
case_file >"$work/front.toml"

"$bin" front "$work/front.toml" -o "$work/front" 2>"$work/log"
rc=$?
check front_exit $((rc != 0)) "exit $rc: $(tail -3 "$work/log")"
for f in front.json front.csv report.html figures/front_sigma_y.png fem/fem.pvd; do
  [ -s "$work/front/$f" ]
  check "output_$f" $? "missing $f"
done
"$bin" compare "$work/front.toml" -o "$work/compare" 2>"$work/compare.log"
check compare_exit $? "$(tail -3 "$work/compare.log")"

/usr/bin/python3 - "$work/front/front.json" "$work/compare/summary.json" <<'PY'
import json, sys
front, summary = (json.load(open(p)) for p in sys.argv[1:])
bad = []
points = {p["label"]: p for p in front["points"]}
own = points[front["case_point"]]
if front["case_point"] != "agent conserving 5 mm":
    bad.append(f"case point {front['case_point']}")
# The front's error at the case's own size is the comparison's, bit for bit.
for name in front["metrics"]:
    if own["errors"][name] != summary["metrics"][name]["value"]:
        bad.append(f"{name}: front {own['errors'][name]} compare {summary['metrics'][name]['value']}")
    if front["reference"]["errors"][name] != summary["metrics"][name]["reference_error"]:
        bad.append(f"{name}: reference error differs")
# The ladders: 2 agent points (10 mm is left out, said why), 3 FEM points; work counts that say what was solved.
labels = sorted(points)
if labels != ["agent conserving 2.5 mm", "agent conserving 5 mm", "fem Q1 1.25 mm", "fem Q1 2.5 mm", "fem Q1 5 mm"]:
    bad.append(f"points {labels}")
if len(front["skipped"]) != 1 or not front["skipped"][0].startswith("agent conserving at 10 mm: ") or \
        "multiples of h" not in front["skipped"][0]:
    bad.append(f"skipped {front['skipped']}")
if points["agent conserving 5 mm"]["work"]["agents"] != 1600 or points["agent conserving 2.5 mm"]["work"]["agents"] != 6400:
    bad.append("agent counts")
if points["fem Q1 5 mm"]["work"]["dofs"] != 2 * 41 * 41 or points["fem Q1 1.25 mm"]["work"]["dofs"] != 2 * 161 * 161:
    bad.append("FEM DoFs")
for p in front["points"]:
    if not 0 < p["seconds"]["min"] <= p["seconds"]["median"]:
        bad.append(f"{p['label']}: times {p['seconds']}")
# The conserving rule set leaves tau_xy at zero: its points list it as not modelled, and no agent
# point has a verdict in it (the FEM points keep theirs).
shear = ["body.tau_xy.rel_l2", "body.tau_xy.rel_max", "far.tau_xy.rel_l2", "far.tau_xy.rel_max"]
for label, p in points.items():
    if sorted(p.get("not_modelled", [])) != (shear if p["model"] == "agent" else []):
        bad.append(f"{label}: not_modelled {p.get('not_modelled')}")
judged = {(v["point"], v["metric"]) for v in front["verdicts"]}
if any((label, m) in judged for label in points if label.startswith("agent") for m in shear) or \
        ("fem Q1 5 mm", "far.tau_xy.rel_l2") not in judged:
    bad.append("verdicts in tau_xy")
if front["gate"] != {"checked": 1, "failed": 0, "failures": []}:
    bad.append(f"gate {front['gate']}")
print("\n".join(bad))
sys.exit(1 if bad else 0)
PY
check front_numbers $? "see above"
/usr/bin/python3 "$src/tests/common/front_by_hand.py" "$work/front/front.json" 10
check front_speedups $? "see above"
/usr/bin/python3 "$src/tests/common/check_report.py" "$work/front" >"$work/check.log" 2>&1
check report_values $? "$(tail -3 "$work/check.log")"

# A speed-up the case's own agents do not show fails the gate: exit 1, the metric named. (They are
# less accurate than every FEM point here: the FEM of their error costs at most the cheapest FEM's
# time, so no least speed-up is shown, however small.)
case_file 'min_speedup = {"far.sigma_y.rel_l2" = 1e-6}' >"$work/tight.toml"
"$bin" front "$work/tight.toml" -o "$work/tight" 2>"$work/log"
rc=$?
check tight_exit $((rc != 1)) "exit $rc: $(tail -3 "$work/log")"
grep -q "front: gate FAILED: front.gate.min_speedup.far.sigma_y.rel_l2: agent conserving 5 mm: speed-up at most .* (less accurate than every FEM point): not shown to reach 1e-06" "$work/log"
check tight_message $? "$(grep gate "$work/log")"

# Bad input: a gate on no metric, a size parameter the mesh lacks, more than one rank.
case_file 'min_speedup = {"far.sigma_q.rel_l2" = 2}' >"$work/bad_name.toml"
refused bad_gate_name "front.gate.min_speedup.far.sigma_q.rel_l2" "$work/front" "$bin" front "$work/bad_name.toml" -o "$work/no"
sed 's/^\[front\]$/[front]\nsize_parameter = "size"/' "$work/front.toml" >"$work/bad_size.toml"
refused bad_size "front.size_parameter" "$work/front" "$bin" front "$work/bad_size.toml" -o "$work/no"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMPI_MCA_orte_tmpdir_base="$logs/ompi"  # mpirun's session files in this test's own folder
mkdir -p "$logs/ompi"
before=$(ls -A "$work")
mpirun -q -np 2 "$bin" front "$work/front.toml" -o "$work/no" >/dev/null 2>"$logs/ranks"
rc=$?
[ "$rc" -eq 2 ] && [ "$(grep -c "workbench: error" "$logs/ranks")" -eq 1 ] && grep -q "run it without mpirun" "$logs/ranks" &&
  [ "$before" = "$(ls -A "$work")" ]
check two_ranks $? "exit $rc: $(cat "$logs/ranks")"
[ ! -e "$work/no" ]
check nothing_written $? "$work/no exists"

echo "front: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
