#!/usr/bin/env bash
# FEM reference on 1 and 2 MPI ranks: the 1e6-DoF plate (bench/fem/plate_1m.toml), phase times,
# AMG iterations and peak memory per rank.   bash bench/fem/mpi_ranks.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
out=$(mktemp -d)
for ranks in 1 2; do
  echo "== $ranks rank(s)"
  /usr/bin/time -f "wall %e s, peak RSS %M KiB (largest rank)" \
    mpirun -np "$ranks" "$build/cli/workbench" fem bench/fem/plate_1m.toml -o "$out/r$ranks" 2>&1 | grep -v "^fem: wrote"
done
rm -rf "$out"
