#!/usr/bin/env bash
# The seed study, `workbench compare cases/seed_plate.toml`, as a whole process (wall and CPU with
# the figures' processes) for several builds of the project, alternating in one run, so that their
# ratios are measured on one machine at one time (docs/performance.md, issue 25). Each SOURCE_DIR is
# a checkout with its build in SOURCE_DIR/build (a git worktree of another commit, say).
#
#   bash bench/compare/seed_study_builds.sh ROUNDS SOURCE_DIR [SOURCE_DIR ...]
#
# Prints each run, then per build the median over the rounds of its wall and CPU time over the
# first build's in the same round.
set -eu
rounds=$1
shift
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for r in $(seq "$rounds"); do
  for k in $(seq $#); do
    src=$(realpath "${!k}")
    /usr/bin/time -f "%e %U %S" -o "$work/time" "$src/build/cli/workbench" compare "$src/cases/seed_plate.toml" \
      -o "$work/out$k" >/dev/null 2>"$work/log" || { tail -3 "$work/log"; exit 1; }
    read -r wall user sys <"$work/time"
    echo "round $r build $k ($src): wall $wall s, CPU $(awk -v u="$user" -v s="$sys" 'BEGIN {print u + s}') s" | tee -a "$work/runs"
    rm -rf "$work/out$k"
  done
done
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
for k in $(seq 2 $#); do
  for what in wall CPU; do
    ratio=$(awk -v k="$k" -v what="$what" '
      { for (i = 1; i <= NF; ++i) if ($i == what) t = $(i + 1); if ($4 == 1) first[$2] = t; if ($4 == k) mine[$2] = t }
      END { for (r in mine) print mine[r] / first[r] }' "$work/runs" | median)
    echo "build $k / build 1, $what: median $ratio"
  done
done
