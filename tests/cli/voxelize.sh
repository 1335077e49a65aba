#!/usr/bin/env bash
# `workbench voxelize`: a staircase .msh written whole (its agents and groups said), an existing file
# refused, and under a file-size limit one line naming the file the user asked for (not the staged
# one), exit 2, nothing left behind. Usage: voxelize.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

"$bin" voxelize "$src/tests/data/disc.geo" -s 0.1 -o "$work/disc.msh" 2>"$work/log"
check write_exit $? "$(cat "$work/log")"
grep -q "^voxelize: wrote $work/disc.msh$" "$work/log" && [ -s "$work/disc.msh" ]
check write_file $? "$(cat "$work/log")"
# A disc of radius 1 m at 0.1 m agents: pi / 0.01 = 314 agents, give or take the staircase's rim.
agents=$(sed -n 's/^voxelize: \([0-9]*\) agents of 0.1 m.*/\1/p' "$work/log")
[ -n "$agents" ] && [ "$agents" -ge 290 ] && [ "$agents" -le 340 ]
check write_agents $? "agents: $agents"

cp "$work/disc.msh" "$work/before.msh"
"$bin" voxelize "$src/tests/data/disc.geo" -s 0.05 -o "$work/disc.msh" 2>"$work/log"
rc=$?
check exists_exit $((rc != 2)) "exit $rc"
grep -q "disc.msh: exists; the workbench does not overwrite a file it did not write" "$work/log" &&
  cmp -s "$work/disc.msh" "$work/before.msh"
check exists_untouched $? "$(cat "$work/log")"

# From the .msh just written (a .geo would hit the limit first in the mesher's own scratch file).
(ulimit -f 8 && exec "$bin" voxelize "$work/disc.msh" -s 0.01 -o "$work/small.msh") 2>"$work/log"
rc=$?
check limit_exit $((rc != 2)) "exit $rc: $(cat "$work/log")"
[ "$(wc -l <"$work/log")" -eq 1 ] && grep -q "$work/small.msh.*File too large" "$work/log" && ! grep -q "partial" "$work/log"
check limit_message $? "$(cat "$work/log")"
[ ! -e "$work/small.msh" ] && [ -z "$(ls -A "$work" | grep partial)" ]
check limit_nothing_left $? "$(ls -A "$work")"

echo "voxelize: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
