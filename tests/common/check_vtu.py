#!/usr/bin/python3
"""Opens every VTU/PVTU under the given folders with VTK's own XML readers and checks what a
ParaView user relies on: every array named with a unit ("name [unit]"), every component of a
vector array named, no NaN except in a ratio's masked cells, no negative zero, cells in VTK's
vertex order (positive area/volume), cells on shared points (no duplicated vertices). Prints one line per file; exit 1 on the first failed file set.

    /usr/bin/python3 tests/common/check_vtu.py [--expect-files N] [--unique-points] FOLDER...
"""
import argparse
import glob
import os
import re
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkFiltersVerdict import vtkMeshQuality
from vtkmodules.vtkIOXML import vtkXMLPUnstructuredGridReader, vtkXMLUnstructuredGridReader

UNIT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]* \[[^\]]+\]$")


def arrays(data):
    for i in range(data.GetNumberOfArrays()):
        yield data.GetAbstractArray(i)


def check(path, unique_points):
    problems = []
    reader = vtkXMLPUnstructuredGridReader() if path.endswith(".pvtu") else vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() != 0:
        return [f"VTK could not read it (error code {reader.GetErrorCode()})"]
    grid = reader.GetOutput()
    if grid.GetNumberOfPoints() == 0 or grid.GetNumberOfCells() == 0:
        return ["no points or no cells"]
    masked = {}
    data_sets = {"point": grid.GetPointData(), "cell": grid.GetCellData()}
    for where, data in data_sets.items():
        for a in arrays(data):
            name = a.GetName() or ""
            if not UNIT.match(name):
                problems.append(f"{where} array '{name}' has no unit ('name [unit]')")
            for c in range(a.GetNumberOfComponents()):
                if a.GetNumberOfComponents() > 1 and not a.GetComponentName(c):
                    problems.append(f"{where} array '{name}' component {c} has no name")
            v = vtk_to_numpy(a).reshape(a.GetNumberOfTuples(), -1)
            if np.any(np.isinf(v)):
                problems.append(f"{where} array '{name}' holds an infinity")
            if np.any((v == 0) & np.signbit(v)):
                problems.append(f"{where} array '{name}' holds a negative zero")
            if name.startswith("ratio_masked_"):
                masked[name.split(" ")[0][len("ratio_masked_"):]] = v[:, 0] != 0
    for where, data in data_sets.items():
        for a in arrays(data):
            name = a.GetName() or ""
            nan = np.isnan(vtk_to_numpy(a).reshape(a.GetNumberOfTuples(), -1)).any(axis=1)
            if not nan.any():
                continue
            m = re.match(r"^ratio_sigma_(\w+) ", name)
            allowed = masked.get(m.group(1)) if m else None
            if allowed is None or np.any(nan & ~allowed):
                problems.append(f"{where} array '{name}' holds NaN outside masked cells")
            elif np.any(allowed & ~nan):
                problems.append(f"{where} array '{name}' has a value in a masked cell")
    # Cells in VTK's vertex order: every quadrilateral, tetrahedron and hexahedron has a positive
    # signed area/volume (a wrong order folds or inverts it).
    quality = vtkMeshQuality()
    quality.SetInputData(grid)
    quality.SetQuadQualityMeasureToArea()
    quality.SetTetQualityMeasureToVolume()
    quality.SetHexQualityMeasureToVolume()
    quality.Update()
    types = np.array([grid.GetCellType(i) for i in range(grid.GetNumberOfCells())])
    measure = vtk_to_numpy(quality.GetOutput().GetCellData().GetArray("Quality"))
    solid = np.isin(types, (9, 10, 12))
    if np.any(measure[solid] <= 0):
        problems.append(f"{np.count_nonzero(measure[solid] <= 0)} cells with a non-positive area or volume")
    if unique_points:
        pts = vtk_to_numpy(grid.GetPoints().GetData())
        unique = len(np.unique(np.round(pts, 12), axis=0))
        if unique != len(pts):
            problems.append(f"{len(pts)} points but {unique} distinct positions (duplicated vertices)")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folders", nargs="+")
    ap.add_argument("--expect-files", type=int, default=1, help="fail with fewer files than this")
    ap.add_argument("--unique-points", action="store_true", help="each point position once per file")
    a = ap.parse_args()
    files = []
    for folder in a.folders:
        found = glob.glob(os.path.join(folder, "**", "*.vtu"), recursive=True)
        found += glob.glob(os.path.join(folder, "**", "*.pvtu"), recursive=True)
        files += sorted(found)
    failed = 0
    for path in files:
        # A PVTU repeats the vertices its pieces share: the check is per file.
        problems = check(path, a.unique_points and path.endswith(".vtu"))
        print(("FAIL " if problems else "ok   ") + path + (": " + "; ".join(problems) if problems else ""))
        failed += bool(problems)
    if len(files) < a.expect_files:
        print(f"FAIL: {len(files)} VTU files, expected at least {a.expect_files}")
        return 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
