#!/usr/bin/env bash
# The 3D default reference converges (docs/compare.md, "The 3D default"): on a small block of cubes
# with the load off centre it is refined until its own body error is under the tolerance, and the
# summary says which level and error (the same number as the body metric's reference_error); where
# the memory limit stops it, summary.json, summary.txt, the page's data and the log say that the
# reference limits the judgement; calibration solves the same reference and says the same; a case
# that sets refine keeps its level; the tolerance is refused where no ladder runs. Usage: reference_3d.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

# 5 x 4 x 4 cubes of 2 mm, the 4 mm patch at x = 4 mm (off centre), Q2 on the agents' mesh 2,673
# DoFs, refined once 18,207, twice 133,947.
block() {  # block FILE [EXTRA_REFERENCE_KEYS]
  cat >"$1" <<EOF
title = "small block, load off centre"
[mesh]
file = "$src/meshes/block3d.geo"
[mesh.parameters]
W = 0.010
H = 0.008
D = 0.008
h = 0.002
lw = 0.004
xc = 0.004
[material]
young = 206e9
poisson = 0.3
[boundary]
rigid = ["base"]
[[load]]
group = "load"
direction = "-y"
force = 2.0
[steps]
count = 1
[agent]
rule_set = "conserving"
[compare]
figures = false
[compare.reference]
$2
EOF
}

# summary_check NAME SUMMARY PYTHON_CONDITION: the condition over s (summary.json) and c (its
# reference.convergence, None without it) must hold.
summary_check() {
  /usr/bin/python3 -c "
import json, sys
s = json.load(open(sys.argv[1]))
c = s['reference'].get('convergence')
ok = ($3)
if not ok: print(json.dumps(s['reference'], indent=1)); print(s['warnings'])
sys.exit(0 if ok else 1)" "$2"
  check "$1" $? "see above"
}

# 1. The default converges: Q2 on the agents' mesh is above a tolerance of 0.05, refined once it is
# under it; the level is the one solved, and its own error is the summary's body sigma_y reference_error.
block "$work/converges.toml" "tolerance = 0.05"
"$bin" compare "$work/converges.toml" -o "$work/converges" 2>"$work/converges.log"
rc=$?
check converges_exit "$rc" "exit $rc: $(tail -3 "$work/converges.log")"
summary_check converges_level "$work/converges/summary.json" "
c['converged'] and not c['limits_judgement'] and c['tolerance'] == 0.05 and c['field'] == 'sigma_y'
and [l['refine'] for l in c['levels']] == [0, 1] and s['reference']['refine'] == 1
and c['levels'][0]['own_error'] > 0.05 >= c['levels'][1]['own_error'] == c['own_error'] > 0
and c['own_error'] == s['metrics']['body.sigma_y.rel_l2']['reference_error']
and [l['dofs'] for l in c['levels']] == [2673, 18207] and s['reference']['dofs'] == 18207
and s['reference']['estimate'] == \"FEM Q2 on the agents' mesh\" and s['reference']['estimate_dofs'] == 2673
and not any('limits the judgement' in w for w in s['warnings'])"
grep -q "compare: reference level 0 (FEM Q2 on the agents' mesh, 2673 DoFs, .* s): its own error in the body's sigma_y .* > 0.05: refining once more" "$work/converges.log" &&
  grep -q "compare: reference level 1 (FEM Q2, the agents' mesh refined 1 time, 18207 DoFs, .* s): its own error in the body's sigma_y .* <= 0.05: converged" "$work/converges.log"
check converges_log $? "$(grep 'reference' "$work/converges.log")"

# 1a. A tighter tolerance (0.01) takes a third level, whose estimate is the level before, kept (not
# solved again: no estimate line after it in the log).
block "$work/level2.toml" "tolerance = 0.01"
"$bin" compare "$work/level2.toml" -o "$work/level2" 2>"$work/level2.log"
rc=$?
check level2_exit "$rc" "exit $rc: $(tail -3 "$work/level2.log")"
summary_check level2_level "$work/level2/summary.json" "
c['converged'] and [l['refine'] for l in c['levels']] == [0, 1, 2] and s['reference']['refine'] == 2
and [l['dofs'] for l in c['levels']] == [2673, 18207, 133947] and s['reference']['estimate_dofs'] == 18207
and c['levels'][0]['own_error'] > c['levels'][1]['own_error'] > 0.01 >= c['own_error'] > 0
and c['own_error'] == s['metrics']['body.sigma_y.rel_l2']['reference_error']"
[ "$(sed -n '/reference level 1/,$p' "$work/level2.log" | grep -c "error estimate")" -eq 0 ]
check level2_estimate_kept $? "$(grep -E 'reference|estimate' "$work/level2.log")"

# 1c. Calibration solves the same reference (compare/reference.h's solve_reference): the same
# levels and own errors as compare's, its log's lines, and its errors before the fit (the case's own
# coefficients) compare's body norms, every field, to the last bit.
printf '%s\n' '[calibrate]' 'rule_set = "conserving"' 'starts = 1' 'max_evaluations = 4' 'keep_load = false' \
  '[[calibrate.case]]' "file = \"$work/converges.toml\"" >"$work/calibrate.toml"
"$bin" calibrate "$work/calibrate.toml" -o "$work/calibrate" >"$work/calibrate.log" 2>&1
rc=$?
check calibrate_exit "$rc" "exit $rc: $(tail -3 "$work/calibrate.log")"
/usr/bin/python3 -c "
import json, sys
r = json.load(open(sys.argv[1]))['cases']['converges']
s = json.load(open(sys.argv[2]))
a, b = r['reference']['convergence'], s['reference']['convergence']
levels = lambda c: [(l['refine'], l['dofs'], l['own_error']) for l in c['levels']]
ok = levels(a) == levels(b) and [l[:2] for l in levels(a)] == [(0, 2673), (1, 18207)] and a['converged']
ok = ok and r['reference']['refine'] == 1 and r['reference']['dofs'] == 18207 and a['own_error'] == b['own_error'] < 0.05
differ = [f for f, e in r['before'].items() if e != s['metrics'][f'body.{f}.rel_l2']['value']]
print('levels', levels(a), levels(b), 'differ', differ) if not ok or differ else None
sys.exit(0 if ok and not differ and len(r['before']) == 11 else 1)" "$work/calibrate/report.json" "$work/converges/summary.json"
check calibrate_same_reference $? "see above"
grep -q "compare: reference level 1 (FEM Q2, the agents' mesh refined 1 time, 18207 DoFs, .* s): its own error in the body's sigma_y .* <= 0.05: converged" "$work/calibrate.log"
check calibrate_log $? "$(grep 'reference' "$work/calibrate.log")"

# 1b. On 2 MPI ranks every rank takes the same decision: the same levels, each said once, the same
# own errors to 1e-8.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMPI_MCA_orte_tmpdir_base="$logs/ompi"  # mpirun's session files in this test's own folder
mpirun -q -np 2 "$bin" compare "$work/converges.toml" -o "$work/ranks" >/dev/null 2>"$work/ranks.log"
rc=$?
check ranks_exit "$rc" "exit $rc: $(tail -3 "$work/ranks.log")"
check ranks_said_once $(($(grep -c '^compare: reference level' "$work/ranks.log") != 2)) "$(grep 'reference level' "$work/ranks.log")"
/usr/bin/python3 -c "
import json, sys
a, b = (json.load(open(f))['reference']['convergence'] for f in sys.argv[1:3])
ok = [l['refine'] for l in b['levels']] == [0, 1] and b['converged']
ok = ok and all(abs(x['own_error'] - y['own_error']) <= 1e-8 * x['own_error'] for x, y in zip(a['levels'], b['levels']))
sys.exit(0 if ok else 1)" "$work/converges/summary.json" "$work/ranks/summary.json"
check ranks_same_levels $? "$(grep 'reference level' "$work/ranks.log")"

# 2. The level it stops at is solved as a case with that refine solves it: the same reference, the
# same metrics (the explicit case has no convergence block).
block "$work/refine1.toml" "refine = 1"
"$bin" compare "$work/refine1.toml" -o "$work/refine1" 2>"$work/refine1.log"
rc=$?
check refine1_exit "$rc" "exit $rc: $(tail -3 "$work/refine1.log")"
/usr/bin/python3 -c "
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
same = [k for k in a['metrics'] if not k.startswith('time.') and a['metrics'][k] != b['metrics'][k]]
ok = not same and 'convergence' not in b['reference'] and b['reference']['refine'] == 1
print('differ:', same[:5]) if same else None
sys.exit(0 if ok else 1)" "$work/converges/summary.json" "$work/refine1/summary.json"
check explicit_refine_same $? "see above"
cmp -s "$work/converges/fem/fem_cells.csv" "$work/refine1/fem/fem_cells.csv"
check explicit_refine_same_fem $? "fem_cells.csv differ"
! grep -q "reference level" "$work/refine1.log"
check explicit_refine_no_ladder $? "$(grep 'reference level' "$work/refine1.log")"

# 3. The memory limit stops it: Q2 on the agents' mesh fits in 0.25 GiB (about 0.20 GiB), refined
# once (about 0.31 GiB) does not. It runs, exit 0, and everything says the reference limits the judgement.
block "$work/memory.toml" ""
printf '[compare.gate]\n"fem.equilibrium_dev" = 0.01\n' >>"$work/memory.toml"  # (the page shows a gate)
WORKBENCH_MEMORY_LIMIT=0.25 "$bin" compare "$work/memory.toml" -o "$work/memory" 2>"$work/memory.log"
rc=$?
check memory_exit "$rc" "exit $rc: $(tail -3 "$work/memory.log")"
summary_check memory_limits "$work/memory/summary.json" "
not c['converged'] and c['limits_judgement'] and c['tolerance'] == 0.03 and s['reference']['refine'] == 0
and [l['refine'] for l in c['levels']] == [0] and c['own_error'] > 0.03
and c['own_error'] == s['metrics']['body.sigma_y.rel_l2']['reference_error']
and 'the next level (FEM Q2, the agents\\' mesh refined 1 time) would not fit' in c['stopped']
and 'above its memory limit of 0.25 GiB' in c['stopped']
and sum(w.startswith('the reference limits the judgement: its own error in the body\\'s sigma_y is ') and 'above the tolerance 0.03' in w
        and c['stopped'] in w for w in s['warnings']) == 1"
grep -q "^WARNING: the reference limits the judgement" "$work/memory/summary.txt"
check memory_summary_txt $? "$(head -5 "$work/memory/summary.txt")"
grep -q "compare: warning: the reference limits the judgement: its own error in the body's sigma_y is .* above the tolerance 0.03" "$work/memory.log" &&
  grep -q "compare: reference level 0 .*: stopping" "$work/memory.log"
check memory_log $? "$(grep 'reference' "$work/memory.log")"
# Calibration says so too: report.json's reference, report.txt's warnings.
printf '%s\n' '[calibrate]' 'rule_set = "conserving"' 'starts = 1' 'max_evaluations = 2' 'keep_load = false' \
  '[[calibrate.case]]' "file = \"$work/memory.toml\"" >"$work/calibrate_memory.toml"
WORKBENCH_MEMORY_LIMIT=0.25 "$bin" calibrate "$work/calibrate_memory.toml" -o "$work/calibrate_memory" >"$work/calibrate_memory.log" 2>&1
rc=$?
check calibrate_memory_exit "$rc" "exit $rc: $(tail -3 "$work/calibrate_memory.log")"
summary_check calibrate_memory_limits "$work/memory/summary.json" "
c == {**json.load(open('$work/calibrate_memory/report.json'))['cases']['memory']['reference']['convergence'],
      'levels': c['levels']} and c['limits_judgement']"
grep -q "^calibrate: WARNING: memory: the reference limits the judgement: its own error in the body's sigma_y is .* above the tolerance 0.03" "$work/calibrate_memory/report.txt"
check calibrate_memory_report_txt $? "$(grep WARNING "$work/calibrate_memory/report.txt")"
# The page: the warning and the convergence row, every value its summary's (headless Chromium).
[ "$(grep -c "the reference limits the judgement" "$work/memory/report.html")" -eq 2 ]
check memory_page_says_so $? "$(grep -c "limits the judgement" "$work/memory/report.html") mentions"
out=$(/usr/bin/python3 "$src/tests/common/check_report.py" "$work/memory" 2>&1)
check memory_page_checked $? "$out"

# 4. The tolerance where no ladder runs is refused: with refine, with degree 1, in 2D.
block "$work/both.toml" "refine = 1
tolerance = 0.05"
refused tolerance_with_refine "both.toml: compare.reference.tolerance: the reference converges to a tolerance only without refine" \
  "$work" "$bin" compare "$work/both.toml" -o "$work/both"
block "$work/q1.toml" "degree = 1
tolerance = 0.05"
refused tolerance_with_q1 "q1.toml: compare.reference.tolerance: the reference converges to a tolerance only without degree = 1" \
  "$work" "$bin" compare "$work/q1.toml" -o "$work/q1"
# (refused once the mesh is read: the output folder's parent has held its staging folder, removed)
mkdir "$work/in"
{ agent_case; printf '\n[compare.reference]\ntolerance = 0.05\n'; } >"$work/in/plate.toml"
refused tolerance_in_2d "plate.toml: compare.reference.tolerance: a 2D reference keeps its level" \
  "$work/in" "$bin" compare "$work/in/plate.toml" -o "$work/plate"
[ ! -e "$work/plate" ]
check tolerance_in_2d_no_output $? "output written"

echo "3D reference: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
