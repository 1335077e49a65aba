#!/usr/bin/env bash
# What meshing a .geo in a child process (workbench-geo-mesher, common/gmsh/gmsh_session.h) costs:
# `workbench COMMAND cases/seed_plate.toml` (whole process, wall time) with two builds, OLD (gmsh
# meshing in the workbench process) and NEW, alternating in the same run. Prints the median of RUNS
# wall times of each and the difference, and of the FEM reference's mesh_seconds (fem_summary.csv:
# its gmsh load, which a comparison's second load of the .geo finds meshed before).
#
#   taskset -c 1 bash bench/gmsh/geo_mesher.sh OLD_BUILD NEW_BUILD 5 [COMMAND]   (COMMAND: compare)
set -eu
old=$(realpath "$1")
new=$(realpath "$2")
runs=${3:-5}
command=${4:-compare}
src=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sed "s#\.\./meshes#$src/meshes#" "$src/cases/seed_plate.toml" >"$work/seed_plate.toml"

now() { date +%s.%N; }
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
for r in $(seq "$runs"); do
  for build in old new; do
    bin="${!build}/cli/workbench"
    t=$(now)
    "$bin" "$command" "$work/seed_plate.toml" -o "$work/out_$build" >/dev/null 2>&1 || { echo "$build failed"; exit 1; }
    awk -v a="$(now)" -v b="$t" 'BEGIN {print a - b}' | tee -a "$work/$build" | sed "s/^/$command $build: /" >&2
    grep -h '^mesh_seconds,' "$work/out_$build"/fem_summary.csv "$work/out_$build"/fem/fem_summary.csv 2>/dev/null |
      cut -d, -f2 >>"$work/mesh_$build"
  done
done
awk -v c="$command" -v o="$(median <"$work/old")" -v n="$(median <"$work/new")" 'BEGIN {
  printf "%s cases/seed_plate.toml: median of the runs: %.3f s meshing in the process, %.3f s in the child, %+.3f s (%+.1f %%)\n",
         c, o, n, n - o, 100 * (n - o) / o }'
awk -v o="$(median <"$work/mesh_old")" -v n="$(median <"$work/mesh_new")" 'BEGIN {
  printf "the FEM reference'"'"'s mesh_seconds: median %.3f s meshing in the process, %.3f s in the child\n", o, n }'
