#!/usr/bin/env bash
# Every subcommand under `mpirun -np 2` against the same run on one rank: compare and calibrate run
# distributed and must give the serial run's numbers (every metric to 1e-8 relative, the fitted
# coefficients to 1e-6) and its files, written once; agent runs once, on rank 0; a failure on one
# rank ends both with one line. Usage: mpi_runs.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"
py=/usr/bin/python3
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# mpirun's session files in this test's own folder: in the shared /tmp/ompi.<host>.<uid> a job that
# ends removes the folder another test's job is creating its own in (open-mpi/ompi#8510).
export OMPI_MCA_orte_tmpdir_base="$logs/ompi"
mpi() { mpirun -q -np 2 "$bin" "$@"; }  # -q: no banner of its own beside our one line

# The gated plate at 10 mm agents (quick; its figures are off: what is compared is numbers and files).
agent_case | sed '/^\[compare.gate\]/,$d' >"$work/plate.toml"  # its gate names lines of the 5 mm grid

# 1. compare: the same exit code, the same numbers, the same files (but the FEM's VTU, one piece per
# rank under MPI), every line once.
"$bin" compare "$work/plate.toml" -o "$work/serial" >/dev/null 2>"$work/serial.log"
rc1=$?
mpi compare "$work/plate.toml" -o "$work/ranks" >/dev/null 2>"$work/ranks.log"
rc2=$?
check compare_exit $((rc1 != rc2 || rc1 > 1)) "serial exit $rc1, 2 ranks exit $rc2: $(tail -2 "$work/ranks.log")"
check compare_written_once $(($(grep -c '^compare: wrote' "$work/ranks.log") != 1)) "$(grep '^compare: wrote' "$work/ranks.log")"
check compare_reference_printed_once $(($(grep -c '^compare: reference' "$work/ranks.log") != 1)) \
  "$(grep '^compare: reference' "$work/ranks.log")"
$py - "$work/serial" "$work/ranks" <<'PY'
import json, math, os, sys
a, b = sys.argv[1], sys.argv[2]
files = lambda d: {os.path.relpath(os.path.join(r, f), d) for r, _, fs in os.walk(d) for f in fs
                   if not (r.endswith("fem") and (f.endswith(".vtu") or f.endswith(".pvtu") or f.endswith(".pvd")))}
bad = [f"only serial: {f}" for f in sorted(files(a) - files(b))] + [f"only 2 ranks: {f}" for f in sorted(files(b) - files(a))]
ma, mb = json.load(open(f"{a}/summary.json"))["metrics"], json.load(open(f"{b}/summary.json"))["metrics"]
if set(ma) != set(mb):
    bad.append(f"metric names differ: {sorted(set(ma) ^ set(mb))}")
worst = 0.0
for name in set(ma) & set(mb):
    if name.startswith("time."):
        continue
    x, y = ma[name]["value"], mb[name]["value"]
    if x == y or (math.isnan(x) and math.isnan(y)):
        continue
    if abs(x - y) <= 1e-12:  # e.g. fem.equilibrium_dev, itself round-off (2e-12)
        continue
    rel = abs(x - y) / max(abs(x), 1e-300)
    worst = max(worst, rel)
    if rel > 1e-8:
        bad.append(f"{name}: serial {x!r}, 2 ranks {y!r} (relative {rel:.1e})")
print(f"compare: largest relative difference of a metric (beyond 1e-12), serial against 2 ranks: {worst:.1e}")
if bad: print("\n".join(bad[:10]))
sys.exit(1 if bad else 0)
PY
check compare_same_numbers_and_files $? "see above"
test -f "$work/ranks/fem/fem_000.pvtu" && test -f "$work/ranks/fem/fem_000.1.vtu"
check compare_fem_pieces $? "no fem_000.pvtu with a piece per rank"

# 2. calibrate: two small cases (one with the load moved off centre), few evaluations, and a
# third position held out (scored on every rank, written once).
sed 's/^lw = 0.02/lw = 0.02\nxc = 0.05/' "$work/plate.toml" >"$work/offcentre.toml"
sed 's/^lw = 0.02/lw = 0.02\nxc = 0.14/' "$work/plate.toml" >"$work/held.toml"
cat >"$work/cal.toml" <<EOF
title = "two plates"
[calibrate]
rule_set = "conserving"
starts = 2
seed = 1
max_evaluations = 25
[calibrate.objective]
sigma_x = 0.0
sigma_y = 1.0
displacement = 1.0
[[calibrate.case]]
file = "$work/plate.toml"
[[calibrate.case]]
file = "$work/offcentre.toml"
[[calibrate.held_out]]
file = "$work/held.toml"
EOF
"$bin" calibrate "$work/cal.toml" -o "$work/cal1" >/dev/null 2>"$work/cal1.log"
check calibrate_serial $? "$(tail -2 "$work/cal1.log")"
mpi calibrate "$work/cal.toml" -o "$work/cal2" >/dev/null 2>"$work/cal2.log"
check calibrate_ranks $? "$(tail -2 "$work/cal2.log")"
check calibrate_printed_once $(($(grep -c '^calibrate: wrote' "$work/cal2.log") != 1)) "$(grep -c wrote "$work/cal2.log") lines"
$py - "$work/cal1" "$work/cal2" <<'PY'
import json, math, os, sys
a, b = (json.load(open(f"{d}/report.json")) for d in sys.argv[1:3])
bad = []
for k, x in a["fitted"].items():
    y = b["fitted"][k]
    if not math.isclose(x, y, rel_tol=1e-6, abs_tol=1e-12):
        bad.append(f"fitted {k}: serial {x!r}, 2 ranks {y!r}")
if not math.isclose(a["objective"]["fitted"], b["objective"]["fitted"], rel_tol=1e-6):
    bad.append(f"objective: {a['objective']} against {b['objective']}")
for when in ("before", "after"):
    for f, x in a["held_out"]["held"][when].items():
        if not math.isclose(x, b["held_out"]["held"][when][f], rel_tol=1e-6):
            bad.append(f"held out {when} {f}: serial {x!r}, 2 ranks {b['held_out']['held'][when][f]!r}")
files = lambda d: sorted(os.path.relpath(os.path.join(r, f), d) for r, _, fs in os.walk(d) for f in fs)
if files(sys.argv[1]) != files(sys.argv[2]):
    bad.append(f"files differ: {files(sys.argv[1])} against {files(sys.argv[2])}")
if bad: print("\n".join(bad))
sys.exit(1 if bad else 0)
PY
check calibrate_same_fit $? "see above"

# 3. agent is not distributed: it runs once, on rank 0, and writes once.
mpi agent "$work/plate.toml" -o "$work/agent" >/dev/null 2>"$work/agent.log"
check agent_ranks $? "$(tail -2 "$work/agent.log")"
check agent_written_once $(($(grep -c '^agent: wrote' "$work/agent.log") != 1)) "$(cat "$work/agent.log")"
grep -q 'runs once, on rank 0' "$work/agent.log"
check agent_says_rank_0 $? "$(head -2 "$work/agent.log")"

# 4. The memory estimate knows the ranks: the plate at 2 mm agents, Q2 refined twice (about 1.3 M
# DoFs, 2 GB) under a limit of 1 GiB is refused before it is solved, with the machines it needs
# (each with this machine's cores as ranks), on one rank and on two ranks of this machine alike.
sed -e 's/^h = 0.01/h = 0.002/' -e 's/^degree = 1/degree = 2\nrefine = 2/' "$work/plate.toml" >"$work/big.toml"
# (The staging folder is made before the mesh is read and removed again: $work keeps its entries,
# not its time stamp, so what is checked is the entries.)
mem_refused() {  # NAME EXPECTED COMMAND...: exit 2, one line, nothing left in $work
  local name=$1 expected=$2 before
  shift 2
  before=$(ls -A "$work")
  WORKBENCH_MEMORY_LIMIT=1 "$@" >/dev/null 2>"$logs/mem"
  local rc=$?
  [ "$rc" -eq 2 ] && [ "$(wc -l <"$logs/mem")" -eq 1 ] && grep -qF -- "$expected" "$logs/mem" && [ "$before" = "$(ls -A "$work")" ]
  check "$name" $? "exit $rc: $(cat "$logs/mem")"
}
mem_refused memory_refused "run it on 4 machines of this memory, e.g. mpirun -np $((4 * $(nproc)))" \
  "$bin" fem "$work/big.toml" -o "$work/big"
mem_refused memory_refused_ranks "on each of its 2 ranks" mpirun -q -np 2 -x WORKBENCH_MEMORY_LIMIT "$bin" fem "$work/big.toml" -o "$work/big"

# 5. A failure on rank 0 alone (its output folder cannot be made) ends both ranks: exit 2, one line.
mkdir -p "$work/theirs" && echo "not ours" >"$work/theirs/notes.txt"
refused compare_refused_once "theirs" "$work/theirs" mpirun -q -np 2 "$bin" compare "$work/plate.toml" -o "$work/theirs"

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
