#!/usr/bin/env bash
# Faults under load (docs/reliability.md, "Faults under load"): several studies at once, each into
# a folder holding an earlier result of its own, some of them killed with SIGKILL part way, one under
# a full disk (`ulimit -f`, a batch system's file-size limit). Afterwards every folder holds either
# its earlier result byte for byte or a whole new one; the next run into a killed folder removes the
# killed run's debris; every whole new result, and every rerun's, equals a serial run's byte for byte
# (the numbers; `time.*` metrics and the case path in the stamp aside).
# Usage: faults_under_load.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"
py=/usr/bin/python3
export TMPDIR="$logs/tmp"  # the killed runs' temporary folders (the mesher's, MPI's) go with the test
mkdir -p "$TMPDIR"

# Two studies: `agent` (the gated plate at 10 mm agents, 6 load steps: a VTU each) and `compare`
# (the same plate against its FEM reference, no figures). The earlier results come from another
# load (force 1.0), so that an earlier and a new result differ in every number.
agent_case | sed '/^\[compare.gate\]/,$d' | sed 's/^force = 2.0/force = 1.0/' >"$work/earlier.toml"
agent_case | sed '/^\[compare.gate\]/,$d' >"$work/case.toml"
printf '[steps]\ncount = 6\n' >>"$work/earlier.toml"
printf '[steps]\ncount = 6\n' >>"$work/case.toml"
# The runs to be killed draw figures with a stand-in for Python that never says "drawn": each holds
# still with its comparison's files in its staging folder, which is the state it is killed in.
sed 's/^figures = false/figures = true/' "$work/case.toml" >"$work/held.toml"
fake_python

# digest DIR: every file's path and SHA-256, timings aside (as tests/same_outputs.py sets them
# aside): JSON keys starting with "time" or ending in "seconds", CSV rows of seconds and memory, the text
# reports and logs (their numbers are in summary.json); the stamp without its case path.
timeless_json='
import json, sys
def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items() if not (k.startswith("time") or k.endswith("seconds"))}
    return [strip(v) for v in x] if isinstance(x, list) else x
print(json.dumps(strip(json.load(open(sys.argv[1]))), sort_keys=True))'
digest() {
  (cd "$1" && find . -type f | sort | while read -r f; do
    case "$f" in
      ./.workbench-output) echo "$f $(grep -v '^case' "$f" | sha256sum | cut -c1-64)" ;;
      *.json) echo "$f $($py -c "$timeless_json" "$f" | sha256sum | cut -c1-64)" ;;
      *summary.csv) echo "$f $(grep -v '_seconds,\|memory' "$f" | sha256sum | cut -c1-64)" ;;
      *.txt|*.log|*.html) echo "$f" ;;
      *) echo "$f $(sha256sum <"$f" | cut -c1-64)" ;;
    esac
  done)
}

# The serial runs: what a whole new result must be.
for study in agent compare; do
  "$bin" $study "$work/case.toml" -o "$work/serial_$study" >/dev/null 2>"$logs/serial_$study" || [ $? -eq 1 ]
  check "serial_$study" $? "$(tail -2 "$logs/serial_$study")"
  digest "$work/serial_$study" >"$logs/serial_$study.digest"
done

# Nine folders, each with an earlier result: agent a1..a4, compare c1, c2 and k1..k3.
folders=(a1 a2 a3 a4 c1 c2 k1 k2 k3)
killed=(k1 k2 k3)  # SIGKILL while held
full=a4            # a file-size limit of 64 KB, which a VTU of this plate exceeds
study_of() { [[ $1 == a* ]] && echo agent || echo compare; }
mkdir -p "$work/runs"
for f in "${folders[@]}"; do
  "$bin" "$(study_of "$f")" "$work/earlier.toml" -o "$work/runs/$f" >/dev/null 2>"$logs/earlier_$f" || [ $? -eq 1 ]
  check "earlier_$f" $? "$(tail -2 "$logs/earlier_$f")"
  digest "$work/runs/$f" >"$logs/earlier_$f.digest"
done

# All at once.
declare -A pid
for f in "${folders[@]}"; do
  case $f in
    k*) mkdir -p "$work/fake_$f"
        FAKE_DIR="$work/fake_$f" WORKBENCH_PYTHON="$work/fake/python" "$bin" compare "$work/held.toml" -o "$work/runs/$f" \
          >/dev/null 2>"$logs/run_$f" & ;;
    "$full") (ulimit -f 64 && exec "$bin" agent "$work/case.toml" -o "$work/runs/$f" >/dev/null 2>"$logs/run_$f") & ;;
    *) "$bin" "$(study_of "$f")" "$work/case.toml" -o "$work/runs/$f" >/dev/null 2>"$logs/run_$f" & ;;
  esac
  pid[$f]=$!
done
for f in "${killed[@]}"; do
  # Held: the figures' stand-in started and the comparison's tables and VTU written (the summary
  # and the report follow the figures, which never come).
  staging="$work/runs/.$f.partial-${pid[$f]}"
  for _ in $(seq 1200); do
    [ -e "$work/fake_$f/child.pid" ] && [ -e "$staging/steps.csv" ] && [ -e "$staging/compare.vtu" ] && break
    running "${pid[$f]}" || break
    sleep 0.1
  done
  ls -A "$staging" >"$logs/held_$f" 2>&1
  kill -KILL "${pid[$f]}"
done
declare -A rc
for f in "${folders[@]}"; do
  wait "${pid[$f]}"
  rc[$f]=$?
done
for f in "${killed[@]}"; do  # the stand-in and its child outlive the killed workbench: ours to end
  kill -KILL "$(cat "$work/fake_$f/child.pid")" "$(cat "$work/fake_$f/grandchild.pid")" 2>/dev/null
done

outcome=""
for f in "${folders[@]}"; do
  now=$(digest "$work/runs/$f")
  if [ "$now" = "$(cat "$logs/earlier_$f.digest")" ]; then state=earlier
  elif [ "$now" = "$(cat "$logs/serial_$(study_of "$f").digest")" ]; then state=new
  else state=mixed; fi
  outcome+="$f:${rc[$f]}:$state "
  check "${f}_earlier_or_whole_new" $([ $state != mixed ] && echo 0 || echo 1) \
    "exit ${rc[$f]}, neither the earlier result nor a whole new one: $(diff <(echo "$now") "$logs/serial_$(study_of "$f").digest" | head -4)"
  case $f in
    k*) check "${f}_killed_while_held" $(([ "${rc[$f]}" = 137 ] && [ $state = earlier ] && grep -q compare.vtu "$logs/held_$f" && echo 0) || echo 1) \
          "exit ${rc[$f]}, $state, staging held: $(tr '\n' ' ' <"$logs/held_$f")" ;;
    "$full") check "${f}_full_disk" $(([ "${rc[$f]}" = 2 ] && [ $state = earlier ] && grep -q 'write failed (File too large)' "$logs/run_$f" && echo 0) || echo 1) \
          "exit ${rc[$f]}, $state: $(tail -1 "$logs/run_$f")" ;;
    *) check "${f}_survivor_equals_serial" $(([ $state = new ] && [ "${rc[$f]}" -le 1 ] && echo 0) || echo 1) "exit ${rc[$f]}, $state" ;;
  esac
done
echo "faults_under_load: $outcome"
debris=$(ls -A "$work/runs" | grep -cE '^\.k[0-9]\.partial-')
check killed_runs_leave_debris $((debris != ${#killed[@]})) "$debris staging folders of the killed runs (expected ${#killed[@]})"
check full_disk_leaves_none $(ls -A "$work/runs" | grep -q "^\.$full\." && echo 1 || echo 0) "$(ls -A "$work/runs")"

# The next run into each killed folder (all at once) removes its debris and writes the new result.
for f in "${killed[@]}"; do
  "$bin" compare "$work/case.toml" -o "$work/runs/$f" >/dev/null 2>"$logs/rerun_$f" &
  pid[$f]=$!
done
for f in "${killed[@]}"; do
  wait "${pid[$f]}"
  check "${f}_rerun" $(($? > 1)) "$(tail -2 "$logs/rerun_$f")"
  check "${f}_rerun_equals_serial" $([ "$(digest "$work/runs/$f")" = "$(cat "$logs/serial_compare.digest")" ] && echo 0 || echo 1) "differs"
done
left=$(ls -A "$work/runs" | grep -E '\.(partial|old)-')
check debris_removed $([ -z "$left" ] && echo 0 || echo 1) "left: $left"

echo "faults_under_load: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
