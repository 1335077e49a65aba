#!/usr/bin/python3
"""Reads every VTU under the given folders with meshio (Debian's python3-meshio), a reader that
shares no code with VTK, and checks the files against the CSVs written beside them:

- agent (agent_cells.csv): the last load step's cells are the CSV's rows (sigma, generation,
  face forces), its points the node ids of agent_nodes.csv (position, displacement);
- fem (fem_cells.csv): one cell per CSV row (stresses, von Mises; a refined reference: the
  children of each row's element, their mean the row's sigma), each CSV node a point of the
  file with its displacement (all of the file's points when not refined);
- compare (compare.vtu): one cell per cells.csv row (both models' sigma, the ratio NaN exactly
  where masked), the nodes of nodes.csv at the file's points (both displacements);
- pbd (pbd.pvd): the last frame's points are nodes.csv's (position, displacement, pinned).

    /usr/bin/python3 tests/common/check_meshio.py [--expect KIND=N ...] FOLDER...

Prints one line per file; exit 1 when a check fails or a kind was checked fewer times than expected.
"""
import argparse
import glob
import os
import sys

import meshio
import numpy as np


def read_csv(path):
    with open(path) as f:
        header = [h.split(" [")[0] for h in f.readline().strip().split(",")]
        rows = [line.rstrip("\n").split(",") for line in f]
    return {k: np.array([float(r[i]) if r[i] != "" else np.nan for r in rows]) for i, k in enumerate(header)}


def cell_array(mesh, name):
    return np.concatenate([np.asarray(block) for block in mesh.cell_data[name]]).reshape(len(np.concatenate(
        [c.data for c in mesh.cells])), -1)


def n_cells(mesh):
    return sum(len(c.data) for c in mesh.cells)


def same(a, b, what, problems, rtol=1e-12):
    a, b = np.asarray(a, float), np.asarray(b, float)
    if a.shape != b.shape:
        problems.append(f"{what}: shape {a.shape} against {b.shape}")
    elif not np.allclose(a, b, rtol=rtol, atol=1e-300, equal_nan=True):
        problems.append(f"{what}: largest difference {np.nanmax(np.abs(a - b))}")


def at_points(mesh, x, dim):
    """The file's point index of each CSV position (rows x dim); -1 where there is none."""
    index = {tuple(np.round(p[:dim], 12)): i for i, p in enumerate(mesh.points)}
    return np.array([index.get(tuple(np.round(p, 12)), -1) for p in x])


def check_agent(folder, problems):
    steps = sorted(glob.glob(os.path.join(folder, "agent_step_*.vtu")))
    mesh = meshio.read(steps[-1])
    cells, nodes = read_csv(os.path.join(folder, "agent_cells.csv")), read_csv(os.path.join(folder, "agent_nodes.csv"))
    dim = 3 if "z" in cells else 2
    if n_cells(mesh) != len(cells["cell"]):
        problems.append(f"{steps[-1]}: {n_cells(mesh)} cells, agent_cells.csv {len(cells['cell'])}")
        return
    for a in "xyz"[:dim]:
        same(cell_array(mesh, f"sigma_{a} [Pa]")[:, 0], cells[f"sigma_{a}"], f"sigma_{a}", problems)
    same(cell_array(mesh, "generation [-]")[:, 0], cells["generation"], "generation", problems)
    faces = ["-x", "+x", "-y", "+y", "-z", "+z"][:2 * dim]
    same(cell_array(mesh, "face_force [N]"), np.column_stack([cells[f"f_{f}"] for f in faces]), "face_force", problems)
    ids = nodes["node"].astype(int)
    same(mesh.points[ids, :dim], np.column_stack([nodes[a] for a in "xyz"[:dim]]), "node positions", problems)
    same(mesh.point_data["displacement [m]"][ids, :dim], np.column_stack([nodes[f"u_{a}"] for a in "xyz"[:dim]]),
         "displacement", problems)
    return steps[-1]


def check_fem(folder, problems):
    path = os.path.join(folder, "fem_000.vtu")
    mesh = meshio.read(path)
    cells, nodes = read_csv(os.path.join(folder, "fem_cells.csv")), read_csv(os.path.join(folder, "fem_nodes.csv"))
    dim = 3 if "z" in cells else 2
    # A refined reference (a comparison's fem/): the file has each element's 2^dim children per
    # refinement, in groups (deal.II's order); the CSV has the element, its values the children's mean.
    children = n_cells(mesh) // len(cells["cell"])
    if n_cells(mesh) != children * len(cells["cell"]) or children not in [2 ** (dim * r) for r in range(5)]:
        problems.append(f"{path}: {n_cells(mesh)} cells, fem_cells.csv {len(cells['cell'])}")
        return
    cell_points = np.concatenate([c.data for c in mesh.cells])
    centres = mesh.points[cell_points].mean(axis=1).reshape(-1, children, 3).mean(axis=1)
    same(centres[:, :dim], np.column_stack([cells[a] for a in "xyz"[:dim]]), "cell centres", problems)
    for name in ("sigma_x", "sigma_y", "von_mises") if children == 1 else ("sigma_x", "sigma_y"):
        mean = cell_array(mesh, f"{name} [Pa]")[:, 0].reshape(-1, children).mean(axis=1)
        if children == 1:  # the FEM file holds its stresses in single precision (6e-8)
            same(mean, cells[name], name, problems, rtol=2e-7)
        elif np.abs(mean - cells[name]).max() > 1e-6 * np.abs(cells[name]).max():  # measured: 9e-9 (gate plate)
            problems.append(f"{path}: {name}: the children's mean is not fem_cells.csv's value")
    # fem_nodes.csv: the mesh's nodes (of the unrefined mesh), each a vertex of the file.
    where = at_points(mesh, np.column_stack([nodes[a] for a in "xyz"[:dim]]), dim)
    if (where < 0).any() or (children == 1 and len(where) != len(mesh.points)):
        problems.append(f"{path}: {len(mesh.points)} points, {(where >= 0).sum()} of {len(where)} CSV nodes among them")
        return
    same(mesh.point_data["displacement [m]"][where, :dim], np.column_stack([nodes[f"u_{a}"] for a in "xyz"[:dim]]),
         "displacement", problems)
    return path


def check_compare(folder, problems):
    path = os.path.join(folder, "compare.vtu")
    mesh = meshio.read(path)
    cells, nodes = read_csv(os.path.join(folder, "cells.csv")), read_csv(os.path.join(folder, "nodes.csv"))
    dim = 3 if "z" in cells else 2
    if n_cells(mesh) != len(cells["cell"]):
        problems.append(f"{path}: {n_cells(mesh)} cells, cells.csv {len(cells['cell'])}")
        return
    for name in ("agent_sigma_x", "agent_sigma_y", "fem_sigma_x", "fem_sigma_y", "ratio_sigma_y", "generation"):
        unit = {"generation": "-", "ratio_sigma_y": "-"}.get(name, "Pa")
        same(cell_array(mesh, f"{name} [{unit}]")[:, 0], cells[name], name, problems)
    nan = np.isnan(cell_array(mesh, "ratio_sigma_y [-]")[:, 0])
    if not np.array_equal(nan, cells["masked_y"] == 1):
        problems.append(f"{path}: ratio_sigma_y is NaN where cells.csv's masked_y is not 1")
    where = at_points(mesh, np.column_stack([nodes[a] for a in "xyz"[:dim]]), dim)
    if (where < 0).any():
        problems.append(f"{path}: {(where < 0).sum()} nodes of nodes.csv are no point of the file")
        return
    for model in ("agent", "fem"):
        same(mesh.point_data[f"{model}_u [m]"][where, :dim], np.column_stack([nodes[f"{model}_u_{a}"] for a in "xyz"[:dim]]),
             f"{model}_u", problems)
    return path


def check_pbd(folder, problems):
    frames = sorted(glob.glob(os.path.join(folder, "frames", "*.vtu")))
    mesh = meshio.read(frames[-1])
    nodes = read_csv(os.path.join(folder, "nodes.csv"))
    if len(mesh.points) != len(nodes["node"]):
        problems.append(f"{frames[-1]}: {len(mesh.points)} points, nodes.csv {len(nodes['node'])}")
        return
    same(mesh.points, np.column_stack([nodes[a] for a in "xyz"]), "positions", problems)
    same(mesh.point_data["displacement [m]"], np.column_stack([nodes[f"u_{a}"] for a in "xyz"]), "displacement", problems)
    same(mesh.point_data["pinned [-]"], nodes["pinned"], "pinned", problems)
    return frames[-1]


KINDS = {"agent": ("agent_cells.csv", check_agent), "fem": ("fem_cells.csv", check_fem),
         "compare": ("compare.vtu", check_compare), "pbd": ("pbd.pvd", check_pbd)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folders", nargs="+")
    ap.add_argument("--expect", action="append", default=[], help="KIND=N: at least N folders of that kind")
    args = ap.parse_args()
    problems, checked, files = [], {k: 0 for k in KINDS}, 0
    for top in args.folders:
        for folder, _, names in sorted(os.walk(top)):
            for name in sorted(n for n in names if n.endswith(".vtu")):
                mesh = meshio.read(os.path.join(folder, name))  # every file reads
                if len(mesh.points) == 0 or n_cells(mesh) == 0:
                    problems.append(f"{folder}/{name}: no points or no cells")
                files += 1
            for kind, (marker, check) in KINDS.items():
                if marker in names:
                    before = len(problems)
                    path = check(folder, problems)
                    checked[kind] += 1
                    if len(problems) == before:
                        print(f"{path}: {kind}: agrees with the CSV files")
    for e in args.expect:
        kind, n = e.split("=")
        if checked[kind] < int(n):
            problems.append(f"{checked[kind]} {kind} folders checked, expected {n}")
    for p in problems:
        print("FAIL", p)
    print(f"{files} VTU files read with meshio {meshio.__version__}; checked {checked}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
