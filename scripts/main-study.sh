#!/usr/bin/env bash
# README command 1: set up, build, and run the main study: the seed's Fig. 7 plate with the three
# rule sets (patent, conserving, directional), each against the deal.II FEM reference on the same mesh
# (Figures 8-11, the load-step animation, VTU/PVD for ParaView, metrics).
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
bash scripts/setup.sh
bash scripts/build.sh
for case in seed_plate seed_plate_conserving seed_plate_directional; do
  echo "== main study: cases/$case.toml"
  build/cli/workbench compare "cases/$case.toml" -o "out/$case/compare"
done
echo "main study: results in out/seed_plate{,_conserving,_directional}/compare (figures/, summary.txt)"
