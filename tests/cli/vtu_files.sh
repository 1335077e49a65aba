#!/usr/bin/env bash
# Every kind of VTU the workbench writes opens in VTK's XML reader with named, unit-labelled arrays,
# named components and no NaN outside masked ratio cells (tests/common/check_vtu.py): the agent
# load steps, the comparison, the FEM on Q1/Q2 quadrilaterals, P1/P2 triangles, hexahedra, tetrahedra and two
# MPI ranks (PVTU), the PBD frames; and no CSV beside them holds a "-0". Usage: vtu_files.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"
checker="/usr/bin/python3 $src/tests/common/check_vtu.py"
run() {  # run NAME COMMAND...: the command writes into $work/NAME
  local name=$1
  shift
  "$@" >"$work/$name.log" 2>&1
  check "$name" $? "exit status $?: $(tail -2 "$work/$name.log")"
}
# A case file in $work with its mesh path made absolute and extra lines appended.
variant() {  # variant SOURCE_CASE NAME EXTRA_TOML
  sed "s|^file = \"\(.*\)\"|file = \"$(dirname "$1")/\1\"|" "$1" >"$work/$2.toml"
  printf '%s\n' "$3" >>"$work/$2.toml"
}

run compare "$bin" compare "$src/cases/gate_plate.toml" -o "$work/compare"
# The seed plate's patent rule set leaves most agents unreached (zero stress: the -0 case), 10 mm agents.
sed -e "s#\.\./meshes#$src/meshes#" -e 's/^h = 0.002 .*/h = 0.01/' -e 's/^lw = 0.004 .*/lw = 0.02/' \
  -e 's/^count = 20 .*/count = 2/' "$src/cases/seed_plate.toml" >"$work/patent.toml"
echo "figures = false" >>"$work/patent.toml"  # the last table of the case is [compare]
run compare_patent "$bin" compare "$work/patent.toml" -o "$work/compare_patent"
run fem_q2 "$bin" fem "$src/tests/fem/cases/small_plate.toml" -o "$work/fem_q2"
run fem_p1 "$bin" fem "$src/tests/fem/cases/tri_plate.toml" -o "$work/fem_p1"
variant "$src/tests/fem/cases/tri_plate.toml" tri_p2 $'[fem]\ndegree = 2'
run fem_p2 "$bin" fem "$work/tri_p2.toml" -o "$work/fem_p2"
run fem_hex "$bin" fem "$src/tests/fem/cases/block_q1.toml" -o "$work/fem_hex"
# Tetrahedra: a unit cube, clamped at y = 0, pushed down at y = 1.
cat >"$work/tet.geo" <<'GEO'
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Mesh.MeshSizeMax = 0.4;
Physical Surface("base") = {3};
Physical Surface("load") = {4};
Physical Volume("block") = {1};
GEO
printf '%s\n' '[mesh]' 'file = "tet.geo"' '[material]' 'young = 1.0' '[boundary]' 'rigid = ["base"]' '[[load]]' \
  'group = "load"' 'direction = "-y"' 'force = 1.0' >"$work/tet.toml"
run fem_tet "$bin" fem "$work/tet.toml" -o "$work/fem_tet"
sed -e 's|^mesh = "\(.*\)"|mesh = "'"$src"'/cases/\1"|' -e 's|^frames = .*|frames = 5|' "$src/cases/pbd_strip.toml" >"$work/strip.toml"
run pbd "$bin" pbd "$work/strip.toml" -o "$work/pbd"
if command -v mpirun >/dev/null; then
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 \
    OMPI_MCA_orte_tmpdir_base="$logs/ompi" run fem_mpi mpirun -np 2 "$bin" fem "$src/tests/fem/cases/small_plate.toml" -o "$work/fem_mpi"
  test -f "$work/fem_mpi/fem_000.pvtu"
  check fem_mpi_pvtu $? "no fem_000.pvtu"
fi

$checker --unique-points --expect-files 12 "$work"
check vtu_files $? "a VTU file fails the checks above"
# No CSV value prints as "-0" (the VTU writer turns -0 into 0; the CSV writers' inputs must not hold one).
! grep -rlE -- '(^|,)-0(,|$)' --include='*.csv' "$work"
check no_negative_zero_csv $? "a CSV file holds -0"
# The serial FEM file: one point per mesh vertex, stresses as cell data, no rank array.
/usr/bin/python3 - "$work/fem_q2/fem_000.vtu" "$work/fem_p2/fem_000.vtu" <<'PY'
import sys
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
for path in sys.argv[1:]:
    r = vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    g = r.GetOutput()
    cells = g.GetCellData()
    assert cells.GetArray("sigma_y [Pa]") and cells.GetArray("von_mises [Pa]"), path
    assert not cells.GetArray("rank [-]") and not g.GetPointData().GetArray("sigma_y [Pa]"), path
    types = {g.GetCellType(i) for i in range(g.GetNumberOfCells())}
    assert types <= {5, 9}, (path, types)  # linear triangles / quadrilaterals for Q2 and P2 alike
    print(path, g.GetNumberOfPoints(), "points", g.GetNumberOfCells(), "cells", "types", types)
PY
check fem_cell_data $? "stresses not as cell data on linear cells, or a rank array in a serial file"
echo "$passed checks passed, $failures failed"
[ "$failures" -eq 0 ]
