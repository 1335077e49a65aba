#!/usr/bin/env bash
# README command 2: set up, build, and pass the whole test suite (what CI runs).
#  1. install what is missing (scripts/setup.sh)
#  2. build and run every test under ctest
#  3. build the libraries without deal.II with AddressSanitizer + UBSan and run their tests
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1

bash scripts/setup.sh
bash scripts/build.sh
(cd build && ctest --output-on-failure -j "$(nproc)")

echo "== sanitizers: libraries without deal.II (ASan + UBSan)"
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DWORKBENCH_WITH_FEM=OFF -DWORKBENCH_SANITIZE=ON >/dev/null
cmake --build build-sanitize -j "$(nproc)"
# gmsh 4.8 leaks a few bytes inside libgmsh when a .geo stops at Error(): suppressed, ours are not.
(cd build-sanitize && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  LSAN_OPTIONS="suppressions=$PWD/../tests/lsan.supp" ctest --output-on-failure -j "$(nproc)" -L sanitize)
