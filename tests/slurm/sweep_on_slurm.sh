#!/usr/bin/env bash
# The sweep workflow (workflows/sweep) on a real Slurm: a one-node cluster of this machine
# (one_node_cluster.sh: munge, slurmctld, slurmd, everything in this test's scratch folder), the
# shipped Slurm profile with its account and partition set as docs/scaling.md says, a 2 x 2 sweep of
# the seed plate at coarse agents, one of its comparisons on 2 MPI ranks (srun inside its
# allocation). Checks: every comparison ran as a Slurm job (the MPI one with 2 tasks), the collected
# table equals the four summary.json files, the MPI job's metrics equal a serial run's of the same
# case (1e-8 relative, as ctest cli_mpi_runs; a metric the reference does not resolve within that
# reference's own error), and nothing of the cluster is left running.
# Usage: sweep_on_slurm.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/../cli/common.sh"
. "$(dirname "$0")/one_node_cluster.sh"
src=$(realpath "$src")  # the jobs run in another folder
py=/usr/bin/python3
cluster=$(mktemp -d)
trap 'stop_cluster; rm -rf "$work" "$logs" "$cluster"' EXIT
export USER=${USER:-$(id -un)}  # snakemake's Slurm executor reads it
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

start_cluster "$cluster" >"$logs/cluster" 2>&1
check cluster_idle $? "$(cat "$logs/cluster")"
[ "$failures" -eq 0 ] || exit 1

# The profile as a user makes it theirs: the partition set, the account line dropped (this cluster
# keeps no accounts; snakemake checks a given account with sacctmgr).
flow="$src/workflows/sweep"
mkdir -p "$work/profile"
sed -e 's/slurm_partition=YOUR_PARTITION/slurm_partition=test/' -e '/slurm_account=YOUR_ACCOUNT/d' \
  "$flow/slurm/config.yaml" >"$work/profile/config.yaml"
cat >"$work/parameters.csv" <<'CSV'
mesh.parameters.h,mesh.parameters.lw,agent.rule_set,ranks
0.02,0.04,conserving,1
0.02,0.04,patent,1
0.01,0.04,conserving,1
0.01,0.04,patent,2
CSV
cat >"$work/sweep.yaml" <<YAML
workbench: $bin
base_case: $src/cases/seed_plate.toml
parameters: $work/parameters.csv
out: sweep
YAML
# The node's memory may be below the profile's 8000 MB per comparison: ask for what there is.
node_mb=$(slurmd -C | sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p' | head -1)
memory=()
[ "${node_mb:-0}" -ge 8000 ] || memory=(--set-resources "compare:mem_mb=$((node_mb / 2))")
start=$(date +%s)
(cd "$work" && snakemake -s "$flow/Snakefile" --profile "$work/profile" --configfile "$work/sweep.yaml" \
  "${memory[@]}" --latency-wait 5 >"$logs/snakemake" 2>&1)
check snakemake_exit $? "$(tail -30 "$logs/snakemake"; tail -5 "$work"/.snakemake/slurm_logs/rule_compare/*.log 2>/dev/null)"
echo "sweep on Slurm: $(($(date +%s) - start)) s"

# Every comparison was a Slurm job: four submissions, each job's log, the MPI one with 2 tasks.
jobs=$(grep -o 'submitted with SLURM jobid [0-9]*' "$logs/snakemake" | awk '{print $NF}')
check four_slurm_jobs $(($(echo "$jobs" | grep -c .) != 4)) "jobs: $jobs"
tasks=$(for j in $jobs; do scontrol show job "$j" | grep -o 'NumTasks=[0-9]*'; done | sort | uniq -c | xargs)
check three_serial_one_mpi $(([ "$tasks" = "3 NumTasks=1 1 NumTasks=2" ] && echo 0) || echo 1) "$tasks"
states=$(for j in $jobs; do scontrol show job "$j" | grep -o 'JobState=[A-Z]*'; done | sort -u)
check jobs_completed $(([ "$states" = JobState=COMPLETED ] && echo 0) || echo 1) "$states"

(cd "$work" && $py "$src/tests/cli/check_summary_table.py" sweep/summary.csv sweep/summary.json \
  agent.rule_set mesh.parameters.h)
check table_equals_summaries $? "see above"
[ "$(head -c 4 "$work/sweep/figure.png" | tail -c 3)" = PNG ]
check figure $? "no figure.png"

# The MPI job (case_003) against the same case on one rank, outside Slurm.
"$bin" compare "$work/sweep/cases/case_003.toml" -o "$work/serial" >/dev/null 2>"$logs/serial"
check serial_run $(($? > 1)) "$(tail -2 "$logs/serial")"
test -f "$work/sweep/runs/case_003/fem/fem_000.1.vtu" && ! test -e "$work/sweep/runs/case_003/fem/fem_000.2.vtu"
check mpi_job_on_two_ranks $? "not one FEM piece per rank: $(ls "$work/sweep/runs/case_003/fem" | head)"
$py - "$work/serial/summary.json" "$work/sweep/runs/case_003/summary.json" <<'PY'
import json, math, sys
a, b = (json.load(open(f))["metrics"] for f in sys.argv[1:3])
bad, worst, loose = [], 0.0, 0
if set(a) != set(b):
    bad.append(f"metric names differ: {sorted(set(a) ^ set(b))}")
for name in sorted(set(a) & set(b)):
    if name.startswith("time."):
        continue
    x, y = a[name]["value"], b[name]["value"]
    if x == y or abs(x - y) <= 1e-12:
        continue
    rel = abs(x - y) / max(abs(x), 1e-300)
    # A metric the reference does not resolve (its own estimated error above 10 %: u_x on the plate's
    # axis of symmetry, round-off over round-off) may differ by as much as that error; others 1e-8.
    unresolved = a[name].get("resolved") is False or a[name].get("reference_error", 0) > 0.1
    if unresolved:
        loose += 1
    else:
        worst = max(worst, rel)
    if not rel <= (a[name]["reference_error"] if unresolved else 1e-8):
        bad.append(f"{name}: serial {x!r}, Slurm job on 2 ranks {y!r} (relative {rel:.1e})")
print(f"MPI job against serial: {len(a)} metrics, largest relative difference {worst:.1e} "
      f"({loose} the reference does not resolve: within its error)")
print("\n".join(bad[:10]))
sys.exit(1 if bad else 0)
PY
check mpi_job_equals_serial $? "see above"

stop_cluster
left=$(ps -eo pid=,args= | grep -F "$cluster" | grep -v grep)
check nothing_left_running $([ -z "$left" ] && echo 0 || echo 1) "$left"

echo "sweep_on_slurm: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
