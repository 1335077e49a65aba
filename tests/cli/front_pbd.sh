#!/usr/bin/env bash
# `workbench front` on a PBD case (cases/pbd_strip_fem.toml, short ladders): the error of the case's
# own substeps x iterations is `workbench compare`'s, number for number; the reference's own error is
# that of the FEM strip of half its cells, which is a point of the FEM's ladder; the work counts say
# what ran; each speed-up is the FEM's time at that error read log-log off front.json's own points;
# a rod under another load than the strip's, or a strip without the cells parameter, is refused
# (exit 2, nothing written), by the run and by --check. Usage: front_pbd.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

case_file() {  # PBD 250, 500, 1000 substeps x 4 iterations; FEM Q2 at 50, 100, 200 cells along the strip;
  # a gate the PBD point passes (its speed-up is at least the cheapest FEM's time over its own)
  sed -e "s#\.\./meshes#$src/meshes#" -e "s#\.\./tests#$src/tests#" "$src/cases/pbd_strip_fem.toml"
  printf '\n[front]\npbd_substeps = [250, 500, 1000]\npbd_iterations = [4]\nfem_sizes = [4, 2, 1]\n'
  printf 'fem_degrees = [2]\nruns = 1\n[front.gate]\nmin_speedup = {"tip.deflection.rel_error" = 1e-6}\n'
}
case_file >"$work/front.toml"

"$bin" front "$work/front.toml" -o "$work/front" 2>"$work/log"
rc=$?
check front_exit $((rc != 0)) "exit $rc: $(tail -3 "$work/log")"
for f in front.json front.csv report.html figures/front_centreline_deflection.png figures/front_tip_deflection.png; do
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
if sorted(points) != ["fem Q2 100 cells", "fem Q2 200 cells", "fem Q2 50 cells", "pbd 1000 x 4", "pbd 250 x 4",
                      "pbd 500 x 4"] or front["case_point"] != "pbd 1000 x 4":
    bad.append(f"points {sorted(points)}, case point {front['case_point']}")
own = points["pbd 1000 x 4"]
for name in ("centreline.deflection.rel_l2", "tip.deflection.rel_error"):
    # The case's own point is the comparison's PBD run against the same reference, bit for bit.
    if own["errors"][name] != summary["metrics"][name]["value"]:
        bad.append(f"{name}: front {own['errors'][name]} compare {summary['metrics'][name]['value']}")
    # The reference's own error is the 100-cell strip's; the 200-cell strip is the reference itself.
    if front["reference"]["errors"][name] != points["fem Q2 100 cells"]["errors"][name]:
        bad.append(f"{name}: reference error {front['reference']['errors'][name]}")
    if not points["fem Q2 200 cells"]["errors"][name] < 1e-9:
        bad.append(f"{name}: the case's own strip is off the reference: {points['fem Q2 200 cells']['errors'][name]}")
# Work: 100 frames x substeps x 4 iterations x the rod's constraints (40 segments and a ghost node
# behind the clamp: 42 nodes), the same constraints at every rung.
per = points["pbd 1000 x 4"]["work"]["projections"] / (100 * 1000 * 4)
for s in (250, 500, 1000):
    w = points[f"pbd {s} x 4"]["work"]
    if (w["frames"], w["substeps"], w["iterations_per_substep"], w["nodes"]) != (100, s, 4, 42) or \
            w["projections"] != 100 * s * 4 * per or per != int(per) or not 40 <= per <= 82:
        bad.append(f"pbd {s} work {w}")
if points["fem Q2 50 cells"]["work"]["dofs"] != 2 * (2 * 50 + 1) * (2 * 2 + 1):
    bad.append(f"FEM DoFs {points['fem Q2 50 cells']['work']['dofs']}")
# Fewer substeps stop short of rest: the error grows as the substeps fall.
e = [points[f"pbd {s} x 4"]["errors"]["tip.deflection.rel_error"] for s in (1000, 500, 250)]
if not e[0] < e[1] < e[2]:
    bad.append(f"tip errors by substeps 1000, 500, 250: {e}")
if front["gate"] != {"checked": 1, "failed": 0, "failures": []}:
    bad.append(f"gate {front['gate']}")
print("\n".join(bad))
sys.exit(1 if bad else 0)
PY
check front_numbers $? "see above"
/usr/bin/python3 "$src/tests/common/front_by_hand.py" "$work/front/front.json" 6
check front_speedups $? "see above"
/usr/bin/python3 "$src/tests/common/check_report.py" "$work/front" >"$work/check.log" 2>&1
check report_values $? "$(tail -3 "$work/check.log")"

# Two bodies or two loads are an error, not a bad score; a cells parameter the mesh lacks names the key.
sed 's/^total_mass = 0.157/total_mass = 0.2/' "$work/front.toml" >"$work/heavier.toml"
refused other_load "pbd.total_mass" "$work/front" "$bin" front "$work/heavier.toml" -o "$work/no"
sed 's/^\[front\]$/[front]\ncells_parameter = "n"/' "$work/front.toml" >"$work/bad_cells.toml"
refused bad_cells "front.cells_parameter" "$work/front" "$bin" front "$work/bad_cells.toml" -o "$work/no"
# --check refuses them too, before any solve.
refused other_load_check "pbd.total_mass" "$work/front" "$bin" front "$work/heavier.toml" --check
refused bad_cells_check "front.cells_parameter" "$work/front" "$bin" front "$work/bad_cells.toml" --check
"$bin" front "$work/front.toml" --check >"$work/check.out" 2>&1
check check_passes $? "$(cat "$work/check.out")"

echo "front_pbd: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
