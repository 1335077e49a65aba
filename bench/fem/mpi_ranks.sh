#!/usr/bin/env bash
# FEM reference on 1 and 2 MPI ranks: the 1e6-DoF plate with geometric multigrid (bench/fem/plate_1m.toml)
# and with ML AMG (plate_1m_amg.toml), the 8e5-DoF 3D block with geometric multigrid (block_1m.toml):
# phase times, iterations and peak memory per rank.
#   bash bench/fem/mpi_ranks.sh [build-dir [case ...]]      e.g. bash bench/fem/mpi_ranks.sh build block_1m
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
shift || true
cases=${*:-plate_1m plate_1m_amg block_1m}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
out=$(mktemp -d)
for case in $cases; do
  for ranks in 1 2; do
    echo "== $case, $ranks rank(s), load: $(cut -d' ' -f1-3 /proc/loadavg)"
    /usr/bin/time -f "wall %e s, user CPU %U s (all ranks), peak RSS %M KiB (largest rank)" \
      mpirun -np "$ranks" "$build/cli/workbench" fem "bench/fem/$case.toml" -o "$out/$case-$ranks" 2>&1 | grep -v "^fem: wrote"
  done
done
rm -rf "$out"
