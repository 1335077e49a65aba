#!/usr/bin/env bash
# README command 1: set up, build, and run the main study (the seed's Fig. 7 plate).
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
bash scripts/setup.sh
bash scripts/build.sh
build/cli/workbench agent cases/seed_plate.toml -o out/seed_plate/agent
echo "main study: results in out/seed_plate/"
