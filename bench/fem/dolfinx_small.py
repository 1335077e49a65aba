#!/usr/bin/python3
"""The FEM at small sizes against DOLFINx, in the same run (issue 38): the seed plate (2D plane
stress) and block3d (3D) at mesh sizes h = 8 mm / n (8, 4, 2, 1 mm), Q1 and Q2, with an 8 mm load
patch (n cells wide). Both sides time the whole solve from the mesh to the cell stresses, warm:
min and median of N runs after one warm-up.

  workbench: one solve_fem call without its mesh_seconds (set-up, assembly, solve, cell stresses,
             displacements), `fem_bench --small=...` (bench/fem/bench_fem.cc), fem.solver = auto;
  DOLFINx:   function space, boundary conditions, forms, assembly, solve, the cell-average stress
             (a DG0 tensor per cell) and von Mises, from a mesh made beforehand; two solvers,
             MUMPS Cholesky (SPD) and CG + GAMG (rigid body modes, 1e-10 as the workbench), and
             its best of the two counts.

Prints per size both times (wall min / median and CPU min: on a shared machine the CPU time is the
steadier measure), their ratio (DOLFINx best / workbench: above 1 the workbench is faster) and the
largest |u| at the mesh vertices of each (they must agree). Beyond 50 000 DoFs 3 runs; MUMPS not
beyond 60 000 DoFs in 3D (minutes).

  taskset -c 1 /usr/bin/python3 bench/fem/dolfinx_small.py [build-dir] [--runs N] [--only plate|block]

--crossover: the workbench alone, each solver (direct, amg; mg on Q2) at more sizes, on the two
cases and on the solver sweep's unit square and cube (n cells per side), wall min / median and CPU
min: where `auto` should switch from the direct solver (fem.direct_limit).
"""
import argparse
import json
import statistics
import subprocess
import time
from pathlib import Path

import numpy as np
import ufl
from dolfinx import fem, mesh
from dolfinx.fem.petsc import apply_lifting, assemble_matrix, assemble_vector, set_bc
from mpi4py import MPI
from petsc4py import PETSc

from dolfinx_peer import patch_problem, rigid_body_modes

ROOT = Path(__file__).resolve().parents[2]
LW = 0.008  # load patch [m]
FORCE = 2.0  # N, downwards
# name: (case index of fem_bench --small, size [m], thickness [m] (2D), n (h = 8 mm / n) per degree)
PROBLEMS = {
    "plate": (0, (0.2, 0.2), 0.002, {1: (1, 2, 4, 8), 2: (1, 2, 4)}),
    "block": (1, (0.04, 0.04, 0.04), None, {1: (1, 2, 4, 8), 2: (1, 2, 4)}),
}
# name: (case index of fem_bench --small, n per degree)
CROSSOVER = {
    "plate": (0, {1: (1, 2, 3, 4, 5, 6), 2: (1, 2, 3)}),
    "block": (1, {1: (1, 2, 3), 2: (1, 2)}),
    "square": (2, {1: (25, 30, 35, 40, 45, 50), 2: (15, 20, 25, 30)}),
    "cube": (3, {1: (5, 6, 7, 8, 9, 10), 2: (3, 4, 5)}),
}
SOLVERS = {"auto": 0, "direct": 1, "amg": 2, "mg": 3}  # fem_bench --small's solver index
MUMPS_LIMIT_3D = 60000  # DoFs: beyond, MUMPS on a 3D mesh takes minutes (GAMG alone is timed)
LARGE = 50000  # DoFs: beyond, 3 runs (each takes seconds) instead of --runs


def make_mesh(size, n):
    cells = [round(s / LW * n) for s in size]
    if len(size) == 2:
        return mesh.create_rectangle(MPI.COMM_WORLD, [[0, 0], list(size)], cells, mesh.CellType.quadrilateral)
    return mesh.create_box(MPI.COMM_WORLD, [[0, 0, 0], list(size)], cells, mesh.CellType.hexahedron)


def solve(msh, size, thickness, degree, solver):
    """The whole solve from the mesh: returns the largest |u| at the vertices and the DoFs."""
    dim = len(size)
    V = fem.VectorFunctionSpace(msh, ("Lagrange", degree))
    a, L, bc = patch_problem(msh, V, size, LW, thickness, FORCE)

    A = assemble_matrix(a, bcs=[bc])
    A.assemble()
    b = assemble_vector(L)
    apply_lifting(b, [a], bcs=[[bc]])
    b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    set_bc(b, [bc])

    ksp = PETSc.KSP().create(msh.comm)
    ksp.setOperators(A)
    if solver == "mumps":
        A.setOption(PETSc.Mat.Option.SPD, True)  # MUMPS SYM=1: Cholesky without pivoting
        ksp.setType("preonly")
        ksp.getPC().setType("cholesky")
        ksp.getPC().setFactorSolverType("mumps")
    else:
        A.setNearNullSpace(rigid_body_modes(V, dim))
        ksp.setType("cg")
        ksp.setTolerances(rtol=1e-10)
        ksp.setNormType(PETSc.KSP.NormType.UNPRECONDITIONED)
        pc = ksp.getPC()
        pc.setType("gamg")
        opts = PETSc.Options()
        opts["mg_levels_ksp_type"] = "chebyshev"
        opts["mg_levels_pc_type"] = "jacobi"
        ksp.setFromOptions()
    uh = fem.Function(V)
    ksp.solve(b, uh.vector)
    uh.x.scatter_forward()
    if ksp.getConvergedReason() <= 0:
        raise RuntimeError(f"DOLFINx {solver} did not converge ({ksp.getConvergedReason()})")

    # Cell-average stresses (as the workbench's cell stresses) and von Mises from them.
    T = fem.TensorFunctionSpace(msh, ("DG", 0))
    tau = ufl.TestFunction(T)
    s = assemble_vector(fem.form(ufl.inner(sigma(uh), tau) * ufl.dx)).array.reshape(-1, dim, dim)
    volume = assemble_vector(fem.form(ufl.TestFunction(fem.FunctionSpace(msh, ("DG", 0)))
                                      * ufl.dx)).array
    full = np.zeros((len(volume), 3, 3))  # 2D: plane stress, sigma_zz = 0
    full[:, :dim, :dim] = s / volume[:, None, None]
    dev = full - np.einsum("cii->c", full)[:, None, None] / 3 * np.eye(3)
    von_mises = np.sqrt(1.5 * np.einsum("cij,cij->c", dev, dev))
    assert np.isfinite(von_mises).all()

    vertices = fem.locate_dofs_topological(V, 0, np.arange(msh.topology.index_map(0).size_local))
    umax = np.abs(uh.x.array.reshape(-1, dim)[vertices]).max()
    return umax, V.dofmap.index_map.size_global * dim


def dolfinx_times(size, thickness, degree, n, solver, runs):
    """Wall min, median and CPU min seconds, largest |u|, DoFs."""
    msh = make_mesh(size, n)
    umax, dofs = solve(msh, size, thickness, degree, solver)  # warm-up (forms compiled and cached)
    wall, cpu = [], []
    for _ in range(runs):
        t0, c0 = time.perf_counter(), time.process_time()
        umax, dofs = solve(msh, size, thickness, degree, solver)
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    return min(wall), statistics.median(wall), min(cpu), umax, dofs


def workbench_times(build, case, degree, n, runs, solver="auto"):
    """fem_bench --small: wall min, median and CPU min seconds, largest |u|, DoFs, the solver's name."""
    out = subprocess.run([str(build / "bench" / "fem" / "fem_bench"),
                          f"--small={case},{degree},{n},{SOLVERS[solver]},{runs}",
                          "--benchmark_filter=^Small/", "--benchmark_format=json"],
                         capture_output=True, text=True, check=True)
    b = json.loads(out.stdout)["benchmarks"][0]
    return b["min_s"], b["median_s"], b["cpu_min_s"], b["u_max"], int(b["dofs"]), b["label"]


def ms(t):
    """Wall min / median (CPU min) in ms."""
    return f"{1e3 * t[0]:.1f} / {1e3 * t[1]:.1f} ({1e3 * t[2]:.1f})" if t else "-"


def peer(build, runs, only):
    print("| problem | Q | h [mm] | DoFs | workbench min / median (CPU min) [ms] | its solver "
          "| DOLFINx MUMPS min / median (CPU min) [ms] | DOLFINx GAMG min / median (CPU min) [ms] "
          "| DOLFINx best / workbench, wall min (CPU min) | largest \\|u\\| workbench, DOLFINx [m] |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, (case, size, thickness, ladder) in PROBLEMS.items():
        if only and name != only:
            continue
        for degree, ns in ladder.items():
            for n in ns:
                dofs = len(size) * (round(size[0] / LW * n) * degree + 1) ** len(size)
                m = runs if dofs <= LARGE else 3
                ours = workbench_times(build, case, degree, n, m)
                assert ours[4] == dofs
                mumps = (dolfinx_times(size, thickness, degree, n, "mumps", m)
                         if len(size) == 2 or dofs <= MUMPS_LIMIT_3D else None)
                gamg = dolfinx_times(size, thickness, degree, n, "gamg", m)
                best = min(t for t in (mumps, gamg) if t)
                best_cpu = min(t[2] for t in (mumps, gamg) if t)
                print(f"| {name} | {degree} | {8 / n:g} | {dofs} | {ms(ours)} | {ours[5]} | {ms(mumps)} | {ms(gamg)} "
                      f"| **{best[0] / ours[0]:.2f}** ({best_cpu / ours[2]:.2f}) | {ours[3]:.6e}, {best[3]:.6e} |",
                      flush=True)


def crossover(build, runs, only):
    print("| problem | Q | mesh | DoFs | direct min / median (CPU min) [ms] | amg | mg | auto picks |")
    print("|---|---|---|---|---|---|---|---|")
    for name, (case, ladder) in CROSSOVER.items():
        if only and name != only:
            continue
        for degree, ns in ladder.items():
            for n in ns:
                t = {s: workbench_times(build, case, degree, n, runs, s)
                     for s in (["direct", "amg", "mg"] if degree == 2 else ["direct", "amg"])}
                auto = workbench_times(build, case, degree, n, 1)
                mesh = f"h = {8 / n:.3g} mm" if case < 2 else f"{n}^{case} cells"
                print(f"| {name} | {degree} | {mesh} | {t['direct'][4]} | {ms(t['direct'])} | {ms(t['amg'])} "
                      f"| {ms(t.get('mg'))} | {auto[5]} |", flush=True)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("build", nargs="?", default=str(ROOT / "build"))
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--only", choices=list(CROSSOVER))
    parser.add_argument("--crossover", action="store_true")
    args = parser.parse_args()
    (crossover if args.crossover else peer)(Path(args.build), args.runs, args.only)


if __name__ == "__main__":
    main()
