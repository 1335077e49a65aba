#!/usr/bin/env bash
# SIGINT/SIGTERM end a run cleanly (docs/reliability.md, "Interruption"): exit 128 + signal, one
# line, the staging folder removed, the earlier output untouched, and no child process (the figure
# script and what it started) left running. The signal goes to the workbench process alone, as
# `kill` sends it. Usage: interruption.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

fake_python
sed "s#\.\./meshes#$src/meshes#" "$src/cases/pbd_strip.toml" >"$work/pbd.toml"
sed 's/^frames = .*/frames = 1000000/' "$work/pbd.toml" >"$work/long.toml"

# interrupted NAME SIGNAL CASE READY: runs `pbd CASE --animate` over an earlier output, sends SIGNAL
# once READY exists ("staging": once the run's staging folder does), and checks what is left.
interrupted() {
  local name=$1 sig=$2 case=$3 ready=$4 target="$work/$1" code
  code=$((128 + $(kill -l "$sig")))
  "$bin" pbd "$work/pbd.toml" -o "$target" 2>/dev/null  # the earlier output, to be kept
  local before
  before=$(snapshot "$target")
  mkdir -p "$work/fake_$name"
  # `env --default-signal`: a script's background job starts with SIGINT ignored.
  FAKE_DIR="$work/fake_$name" WORKBENCH_PYTHON="$work/fake/python" env --default-signal=INT \
    "$bin" pbd "$case" --animate -o "$target" 2>"$logs/$name.err" &
  local pid=$!
  [ "$ready" = staging ] && ready="$work/.$name.partial-$pid/frames/frame_00001.vtu"
  wait_for "$ready"
  kill -s "$sig" $pid
  wait $pid
  local rc=$?
  check "${name}_exit" $((rc != code)) "exit $rc, expected $code"
  [ "$(grep -c '^workbench:' "$logs/$name.err")" -eq 1 ] &&
    [ "$(tail -1 "$logs/$name.err")" = "workbench: interrupted by SIG$sig; unfinished output removed" ]
  check "${name}_message" $? "stderr: $(grep workbench: "$logs/$name.err")"
  [ ! -e "$work/.$name.partial-$pid" ]
  check "${name}_staging_removed" $? "left: $(ls -a "$work" | grep partial)"
  [ "$before" = "$(snapshot "$target")" ]
  check "${name}_earlier_output_kept" $? "the earlier output changed"
  children_ended "$name"
}

# children_ended NAME: the fake figure script of run NAME and its child are no longer running.
children_ended() {
  local name=$1
  for f in child grandchild; do
    if [ -e "$work/fake_$name/$f.pid" ]; then
      local p
      p=$(cat "$work/fake_$name/$f.pid")
      sleep 0.2  # let init reap it
      ! running "$p"
      check "${name}_${f}_ended" $? "the $f ($p) is still running"
      kill -KILL "$p" 2>/dev/null  # (only if the check failed: a process this test started)
    fi
  done
}

# compare_interrupted NAME SIGNAL: `compare` starts the figure script beside the FEM reference and
# waits for it at the end (the fake one never ends): interrupted once the script runs, the script
# and its child end, the staging folder goes, one line, exit 128 + signal.
compare_interrupted() {
  local name=$1 sig=$2 code
  code=$((128 + $(kill -l "$sig")))
  mkdir -p "$work/fake_$name"
  FAKE_DIR="$work/fake_$name" WORKBENCH_PYTHON="$work/fake/python" env --default-signal=INT \
    "$bin" compare "$work/figures.toml" -o "$work/$name" 2>"$logs/$name.err" &
  local pid=$!
  wait_for "$work/fake_$name/child.pid"
  kill -s "$sig" $pid
  wait $pid
  local rc=$?
  check "${name}_exit" $((rc != code)) "exit $rc, expected $code"
  [ "$(tail -1 "$logs/$name.err")" = "workbench: interrupted by SIG$sig; unfinished output removed" ]
  check "${name}_message" $? "stderr: $(grep workbench: "$logs/$name.err")"
  [ ! -e "$work/.$name.partial-$pid" ] && [ ! -e "$work/$name" ]
  check "${name}_staging_removed" $? "left: $(ls -a "$work")"
  children_ended "$name"
}

# During the figures (rendering the animation): the child and its own child must end too.
interrupted figures_int INT "$work/pbd.toml" "$work/fake_figures_int/child.pid"
interrupted figures_term TERM "$work/pbd.toml" "$work/fake_figures_term/child.pid"
# While computing (the model's time steps, frames being written into the staging folder).
interrupted compute_int INT "$work/long.toml" staging
interrupted compute_term TERM "$work/long.toml" staging
# compare, with the figures drawn beside the FEM reference.
sed -e "s#\.\./meshes#$src/meshes#" -e '/^figures *=/d' "$src/cases/gate_plate.toml" >"$work/figures.toml"
compare_interrupted compare_int INT
compare_interrupted compare_term TERM

echo "cli interruption: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
