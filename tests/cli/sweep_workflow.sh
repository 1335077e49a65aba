#!/usr/bin/env bash
# The sweep workflow (workflows/sweep) on its example table, 2 agent sizes x 2 rule sets of the
# seed plate, with `snakemake --cores 2` in a scratch folder: four cases, four comparisons, the
# collected table equal to the four summary.json files, the figure drawn.
# Usage: sweep_workflow.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

flow="$src/workflows/sweep"
snakemake -s "$flow/Snakefile" --directory "$work" --cores 2 --quiet \
  --config workbench="$bin" base_case="$src/cases/seed_plate.toml" parameters="$flow/parameters.csv" out=sweep \
  >"$logs/log" 2>&1
check snakemake_exit $? "$(tail -20 "$logs/log")"
rows=$(($(wc -l <"$flow/parameters.csv") - 1))
cases=$(ls "$work"/sweep/runs/*/summary.json 2>/dev/null | wc -l)
check one_run_per_row $((cases != rows || rows != 4)) "$cases summaries for $rows rows"
(cd "$work" && /usr/bin/python3 "$src/tests/cli/check_summary_table.py" sweep/summary.csv sweep/summary.json \
  agent.rule_set mesh.parameters.h)  # the folders are relative to where snakemake ran
check table_equals_summaries $? "see above"
/usr/bin/python3 - "$work/sweep/summary.csv" "$flow/parameters.csv" <<'PY'
import csv, sys
table = list(csv.DictReader(open(sys.argv[1])))
wanted = list(csv.DictReader(open(sys.argv[2])))
got = [(float(r["mesh.parameters.h"]), r["agent.rule_set"]) for r in table]
assert got == [(float(w["mesh.parameters.h"]), w["agent.rule_set"]) for w in wanted], got
PY
check rows_follow_the_table $? "see above"
[ "$(head -c 4 "$work/sweep/figure.png" | tail -c 3)" = PNG ]
check figure $? "no figure.png"

echo "sweep_workflow: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
