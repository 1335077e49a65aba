"""Opens every VTU, PVTU and PVD under the given folders with ParaView's own readers and checks
what a ParaView user sees: the file opens, it has points and cells, every array is named with its
unit ("sigma_y [Pa]"), a PVD series has its time steps. Run by hand with ParaView's pvpython (not a
ctest: Debian 12's python3-paraview conflicts with the python3-vtk9 / libvtk9-dev the build needs;
README, "Python, notebooks, ParaView", says how it was run without installing it):

    pvpython tests/common/check_paraview.py FOLDER...
"""
import os
import re
import sys

from paraview import servermanager
from paraview.simple import Delete, OpenDataFile

UNIT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]* \[[^\]]+\]$")


def check(path):
    reader = OpenDataFile(path)
    if reader is None:
        return ["ParaView has no reader for it"], ""
    reader.UpdatePipeline()
    info = reader.GetDataInformation()
    problems = []
    if info.GetNumberOfPoints() == 0 or info.GetNumberOfCells() == 0:
        problems.append("no points or no cells")
    names = list(reader.PointData.keys()) + list(reader.CellData.keys())
    problems += [f"array '{n}' has no unit" for n in names if not UNIT.match(n) and n != "vtkOriginalIndices"]
    steps = len(reader.TimestepValues) if path.endswith(".pvd") and hasattr(reader.TimestepValues, "__len__") else 0
    text = f"{info.GetNumberOfPoints()} points, {info.GetNumberOfCells()} cells, {len(names)} arrays" + (
        f", {steps} time steps" if steps else "")
    Delete(reader)
    return problems, text


def main():
    failed = files = 0
    for top in sys.argv[1:]:
        for folder, _, names in sorted(os.walk(top)):
            for name in sorted(names):
                if not name.endswith((".vtu", ".pvtu", ".pvd")):
                    continue
                path = os.path.join(folder, name)
                problems, text = check(path)
                files += 1
                failed += bool(problems)
                print(f"{path}: " + ("FAILED: " + "; ".join(problems) if problems else text))
    print(f"ParaView {servermanager.vtkSMProxyManager.GetParaViewSourceVersion()}: {files} files, {failed} failed")
    return 1 if failed or not files else 0


if __name__ == "__main__":
    sys.exit(main())
