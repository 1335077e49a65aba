#!/usr/bin/env bash
# gmsh meshes a .geo in a child process (forked by the workbench's mesher server, common/gmsh/gmsh_session.h): the .geo
# files on which gmsh 4.8 crashed inside the workbench (tests/data/gmsh_crashes, found by the
# fuzzer's long mode, docs/reliability.md) end `agent` and `fem` with exit 2, one error line naming
# the .geo, no output folder and no temporary folder left; an interruption while the mesher runs
# ends both processes cleanly. Usage: geo_mesher.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

# case_for GEO: a case reading GEO, with the groups of Cook's membrane (2D) or the 3D block.
case_for() {
  if [[ $(basename "$1") == block3d_* ]]; then
    printf 'title = "t"\n[mesh]\nfile = "%s"\n[material]\nyoung = 206e9\npoisson = 0.3\n[boundary]\nrigid = ["base"]\n' "$1"
    printf '[[load]]\ngroup = "load"\ndirection = "-y"\nforce = 2.0\n[steps]\ncount = 2\n[fem]\ndegree = 1\n'
  else
    printf 'title = "t"\n[mesh]\nfile = "%s"\n[material]\nyoung = 1.0\npoisson = 0.3\nthickness = 1.0\n' "$1"
    printf '[boundary]\nrigid = ["left"]\n[[load]]\ngroup = "right"\ndirection = "+y"\nforce = 1.0\n'
  fi
}

# Each run gets its own TMPDIR (in $work/tmp), where none of the workbench's own files may be left
# (OpenMPI's session folder may be), and its output folder in $work/runs, which must stay empty (no
# output, no staging folder).
mkdir -p "$work/runs" "$work/tmp"
workbench_files() { ls -A "$1" | grep '^workbench-'; }
for geo in "$src"/tests/data/gmsh_crashes/*.geo; do
  name=$(basename "$geo" .geo)
  case_for "$geo" >"$work/$name.toml"
  for command in agent fem; do
    tmp="$work/tmp/${name}_$command"
    mkdir -p "$tmp"
    refused "${name}_$command" "$geo: gmsh failed meshing it (" "$src/tests/data/gmsh_crashes" \
      env TMPDIR="$tmp" "$bin" "$command" "$work/$name.toml" -o "$work/runs/${name}_$command"
    [ -z "$(ls -A "$work/runs")" ]
    check "${name}_${command}_no_output" $? "left: $(ls -A "$work/runs")"
    [ -z "$(workbench_files "$tmp")" ]
    check "${name}_${command}_temporary_removed" $? "left: $(workbench_files "$tmp")"
  done
done

# A good .geo still meshes, with nothing left in the temporary folder.
mkdir -p "$work/tmp/good"
sed "s#\.\./meshes#$src/meshes#" "$src/cases/cook.toml" | sed 's/^n = .*/n = 4/' >"$work/cook.toml"
TMPDIR="$work/tmp/good" "$bin" fem "$work/cook.toml" -o "$work/good" 2>"$logs/good.err"
check good_exit $? "$(tail -1 "$logs/good.err")"
[ -s "$work/good/fem_nodes.csv" ] && [ -z "$(workbench_files "$work/tmp/good")" ]
check good_output_and_nothing_left $? "$(ls "$work/good" "$work/tmp/good")"

# SIGINT while the mesher meshes a large membrane: exit 130, one line, the mesher ended, its
# temporary folder removed, no output folder.
mkdir -p "$work/tmp/int"
sed 's/^n = .*/n = 1000/' "$work/cook.toml" >"$work/large.toml"
TMPDIR="$work/tmp/int" env --default-signal=INT "$bin" fem "$work/large.toml" -o "$work/out_int" 2>"$logs/int.err" &
pid=$!
# The workbench's mesher server (a child named geo-mesher, forked at its start) meshes it in a
# process of its own (the server's child).
server= mesher=
for _ in $(seq 600); do
  server=$(pgrep -P $pid -x geo-mesher) && mesher=$(pgrep -P "$server") && break
  sleep 0.1
done
check interrupt_mesher_started $([ -n "$mesher" ]; echo $?) "no mesher process seen (server: $server)"
kill -INT $pid
wait $pid
rc=$?
check interrupt_exit $((rc != 130)) "exit $rc, expected 130: $(cat "$logs/int.err")"
[ "$(tail -1 "$logs/int.err")" = "workbench: interrupted by SIGINT; unfinished output removed" ]
check interrupt_message $? "stderr: $(cat "$logs/int.err")"
sleep 0.2
{ [ -z "$mesher" ] || ! running "$mesher"; } && { [ -z "$server" ] || ! running "$server"; }
check interrupt_mesher_ended $? "the mesher ($mesher) or its server ($server) is still running"
for p in $mesher $server; do kill -KILL "$p" 2>/dev/null; done  # (only if the check failed: processes this test started)
[ -z "$(workbench_files "$work/tmp/int")" ] && [ ! -e "$work/out_int" ]
check interrupt_nothing_left $? "left: $(workbench_files "$work/tmp/int") $(ls -d "$work/out_int" 2>/dev/null)"

echo "geo_mesher: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
