#!/usr/bin/env bash
# cases/cook.toml from the command line: the rows of fem_nodes.csv at the loaded edge's mid-point
# (48, 52) and the top-right corner (48, 60) hold the published 23.96 and the corner's 25.137
# (docs/fem-reference.md, "Cook's membrane"). Usage: fem_cook.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"
"$bin" fem "$src/cases/cook.toml" -o "$work/out" 2>"$work/log" || { echo "FAIL: exit $?: $(tail -3 "$work/log")"; exit 1; }
uy() { awk -F, -v x="$1" -v y="$2" 'NR > 1 && $2 == x && $3 == y { print $5 }' "$work/out/fem_nodes.csv"; }
mid=$(uy 48 52)
corner=$(uy 48 60)
echo "u_y(48, 52) = $mid (published 23.96), u_y(48, 60) = $corner"
awk -v m="$mid" -v c="$corner" 'BEGIN { exit !(m != "" && c != "" && (m - 23.96)^2 < 0.005^2 && (c - 25.137)^2 < 0.01^2) }' \
  || { echo "FAIL: outside 23.96 +- 0.005 / 25.137 +- 0.01"; exit 1; }
