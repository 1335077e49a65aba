#!/usr/bin/env bash
# What the durable commit costs (every file and folder of the output fsync'ed before it is renamed
# into place, the parent folder after): the seed study (`workbench compare cases/seed_plate.toml`)
# and the agent's 20 load steps (`workbench agent cases/seed_plate.toml`), each with the syncs
# (WORKBENCH_SYNC unset) and without (WORKBENCH_SYNC=off), alternating in the same run, over an
# earlier output as in daily use. Prints the median of RUNS wall times of each and the ratio.
#
#   taskset -c 1 bash bench/io/durable_commit.sh build 5 [OUT_PARENT]
#
# OUT_PARENT (default: a folder under /tmp) chooses the file system the output goes to.
set -eu
build=$(realpath "${1:-build}")
runs=${2:-5}
src=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d "${3:-/tmp}/durable_commit.XXXXXX")
trap 'rm -rf "$work"' EXIT
bin="$build/cli/workbench"
sed "s#\.\./meshes#$src/meshes#" "$src/cases/seed_plate.toml" >"$work/seed_plate.toml"

now() { date +%s.%N; }
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
echo "file system of the output: $(df -T "$work" | awk 'NR == 2 {print $2, $1}')"
for command in agent compare; do
  : >"$work/on" && : >"$work/off"
  "$bin" "$command" "$work/seed_plate.toml" -o "$work/out" >/dev/null 2>&1  # the earlier output
  for r in $(seq "$runs"); do
    for mode in on off; do
      t=$(now)
      if [ "$mode" = off ]; then export WORKBENCH_SYNC=off; else unset WORKBENCH_SYNC; fi
      "$bin" "$command" "$work/seed_plate.toml" -o "$work/out" >/dev/null 2>&1 || { echo "$command failed"; exit 1; }
      awk -v a="$(now)" -v b="$t" 'BEGIN {print a - b}' | tee -a "$work/$mode" | sed "s/^/$command $mode: /" >&2
    done
  done
  unset WORKBENCH_SYNC
  on=$(median <"$work/on")
  off=$(median <"$work/off")
  files=$(find "$work/out" | wc -l)
  bytes=$(du -sb "$work/out" | cut -f1)
  awk -v c="$command" -v on="$on" -v off="$off" -v f="$files" -v b="$bytes" 'BEGIN {
    printf "%s: %d files and folders, %.1f MB; median of the runs: %.3f s with the syncs, %.3f s without, ratio %.3f, %+.3f s\n",
           c, f, b / 1e6, on, off, on / off, on - off }'
done
