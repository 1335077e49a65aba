#!/bin/bash
# Issue 40, a load near a side: the 15 plates of docs/agent-model.md "Loads near a side", each as
# "side" (the default), "image" (agent.near_side = image), and both with agent.closed_forms =
# left_out (L_*, Li_*: the tie and the packets' shear without the half-plane's layer), compared
# against FEM. Usage: plates.sh OUT [TREE]  (TREE: a built checkout, default this one)
set -e
OUT=${1:?usage: plates.sh OUT [TREE]}
T=${2:-$(git -C "$(dirname "$0")" rev-parse --show-toplevel)}
WB=$T/build/cli/workbench
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$OUT/cases" "$OUT/runs"
cd "$OUT/cases"
base="mesh.parameters.h=0.005 mesh.parameters.lw=0.01 steps.count=1 compare.figures=false"
S=$T/cases/seed_plate_directional.toml
for x in 10 20 30 40 50 100; do
  $WB case set $S $base mesh.parameters.xc=$(/usr/bin/python3 -c "print($x / 1000)") -o x$x.toml
done
$WB case set $S $base mesh.parameters.W=0.3 mesh.parameters.H=0.15 mesh.parameters.xc=0.03 -o w300x30.toml
$WB case set $S $base mesh.parameters.W=0.1 mesh.parameters.H=0.4 -o tall.toml
$WB case set $S $base mesh.parameters.W=0.4 mesh.parameters.H=0.1 -o wide.toml
$WB case set $S mesh.parameters.xc=0.1 steps.count=1 compare.figures=false -o mm2x100.toml
$WB case set $S mesh.parameters.xc=0.05 steps.count=1 compare.figures=false -o mm2x50.toml
sed "s#\.\./meshes#$T/meshes#" $T/cases/directional_plate.toml > dplate.toml
$WB case set $S mesh.parameters.h=0.005 mesh.parameters.lw=0.06 steps.count=1 compare.figures=false -o patch60.toml
$WB case set $S $base mesh.parameters.xc=0.07 material.poisson=0.1 -o nu01.toml
$WB case set $S $base mesh.parameters.xc=0.07 material.poisson=0.45 -o nu045.toml
PLATES="x10 x20 x30 x40 x50 x100 w300x30 tall wide mm2x100 mm2x50 dplate patch60 nu01 nu045"
for n in $PLATES; do
  $WB case set $n.toml agent.near_side=image -o i_$n.toml
  $WB case set $n.toml agent.closed_forms=left_out -o L_$n.toml
  $WB case set i_$n.toml agent.closed_forms=left_out -o Li_$n.toml
done
for n in $PLATES; do
  $WB compare $n.toml -o ../runs/side/$n > /dev/null
  $WB compare i_$n.toml -o ../runs/image/i_$n > /dev/null
  $WB compare L_$n.toml -o ../runs/cf/L_$n > /dev/null
  $WB compare Li_$n.toml -o ../runs/cf/Li_$n > /dev/null
done
echo "plates.sh: wrote $OUT/runs"
