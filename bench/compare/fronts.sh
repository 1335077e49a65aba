#!/usr/bin/env bash
# The cost-accuracy fronts behind docs/performance.md ("Issue 38: the cost-accuracy front"): the
# shipped fronts (cases/front_plate.toml, cases/front_block.toml) and the same bodies with the load
# elsewhere (the plate's patch at x = 52 mm, the block's at x = 12 mm), each `workbench front` with
# RUNS timed runs per point. Prints, per front, every point (min ms, far sigma_y, far von Mises, body
# displacement) and the case's own agents' verdicts; keeps the output folders in OUT.
#
#   taskset -c 1 bash bench/compare/fronts.sh build out/fronts 5        # one core, as the docs quote
#   taskset -c 1 bash bench/compare/fronts.sh build out/fronts 5 plate  # the 2D ones only
set -eu
build=$(realpath "${1:-build}")
out=${2:-out/fronts}
runs=${3:-5}
which=${4:-all}
src=$(cd "$(dirname "$0")/../.." && pwd)
bin="$build/cli/workbench"
mkdir -p "$out"
cases=()
[ "$which" = block ] || cases+=(plate plate_x52)
[ "$which" = plate ] || cases+=(block block_x12)
for name in "${cases[@]}"; do
  base=${name%%_*}
  sed -e "s#\.\./meshes#$src/meshes#" -e "s/^runs = .*/runs = $runs/" "$src/cases/front_$base.toml" >"$out/$name.toml"
  case $name in  # xc: the patch's centre [m], every rung's grid holding the patch whole
    plate_x52) sed -i 's/^lw = \(.*\)$/lw = \1\nxc = 0.052/' "$out/$name.toml" ;;
    block_x12) sed -i 's/^lw = \(.*\)$/lw = \1\nxc = 0.012/' "$out/$name.toml" ;;
  esac
  rm -rf "$out/$name"
  "$bin" front "$out/$name.toml" -o "$out/$name" 2>"$out/$name.log"
  echo "== $name"
  grep -A20 "^front: point" "$out/$name.log" | grep -v "^front: wrote\|^compare: \|^report: "
done
