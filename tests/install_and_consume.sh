#!/usr/bin/env bash
# Installs the workbench from the build tree into a scratch prefix, then builds and runs
# examples/embed against it with find_package(workbench): the libraries are consumable as installed.
# Usage: install_and_consume.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 source=$2
scratch=$(mktemp -d "${TMPDIR:-/tmp}/workbench_install.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
quiet() { "$@" >"$scratch/log" 2>&1 || { cat "$scratch/log"; echo "install_and_consume: failed: $*"; exit 1; }; }
quiet cmake --install "$build" --prefix "$scratch/prefix"
quiet cmake -S "$source/examples/embed" -B "$scratch/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$scratch/prefix"
quiet cmake --build "$scratch/build"
"$scratch/build/embed"
# Nothing of the source tree is needed at run time: the program found only installed files.
grep -q "$source" "$scratch/prefix/lib/cmake/workbench/workbenchTargets.cmake" \
  && { echo "installed package config points into the source tree"; exit 1; }
echo "install_and_consume: the installed package builds and runs examples/embed"
