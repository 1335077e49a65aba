#!/usr/bin/python3
"""The DOLFINx peer of the FEM reference: the same 2D and 3D problems solved by DOLFINx (Debian's
python3-dolfinx, PETSc CG + GAMG with the rigid body modes as near-null space, to the same relative
true residual 1e-8), beside `workbench fem` on bench/fem/plate_1m.toml and bench/fem/block_1m.toml;
prints both solve times (wall and CPU: on a shared machine the CPU time is the fair measure), their
ratio and the largest displacement of each (they must agree).

  /usr/bin/python3 bench/fem/dolfinx_peer.py [build-dir] [plate|block ...]   # one core: taskset -c 1
"""
import os
import re
import subprocess
import sys
import tempfile
import time
from contextlib import ExitStack
from pathlib import Path

import numpy as np
import ufl
from dolfinx import fem, la, mesh
from dolfinx.fem.petsc import apply_lifting, assemble_matrix, assemble_vector, set_bc
from mpi4py import MPI
from petsc4py import PETSc

ROOT = Path(__file__).resolve().parents[2]
E, NU = 206e9, 0.3
# name: (case file, cells per axis, size [m], load patch edge [m], thickness [m] (2D), force [N])
PROBLEMS = {
    "plate": ("bench/fem/plate_1m.toml", (704, 704), (0.176, 0.176), 0.016, 0.002, 2.0),
    "block": ("bench/fem/block_1m.toml", (64, 64, 64), (0.04, 0.04, 0.04), 0.01, None, 2.0),
}


def rigid_body_modes(V, dim):
    """Translations and rotations as a PETSc near-null space (as DOLFINx's elasticity demo)."""
    index_map, bs = V.dofmap.index_map, V.dofmap.index_map_bs
    n = 3 if dim == 2 else 6
    modes = [la.create_petsc_vector(index_map, bs) for _ in range(n)]
    with ExitStack() as stack:
        basis = [np.asarray(stack.enter_context(m.localForm())) for m in modes]
        dofs = [V.sub(i).dofmap.list.array for i in range(dim)]
        for i in range(dim):
            basis[i][dofs[i]] = 1.0
        x = V.tabulate_dof_coordinates()[V.dofmap.list.array]
        if dim == 2:
            basis[2][dofs[0]], basis[2][dofs[1]] = -x[:, 1], x[:, 0]
        else:
            basis[3][dofs[0]], basis[3][dofs[1]] = -x[:, 1], x[:, 0]
            basis[4][dofs[0]], basis[4][dofs[2]] = x[:, 2], -x[:, 0]
            basis[5][dofs[2]], basis[5][dofs[1]] = x[:, 1], -x[:, 2]
    la.orthonormalize(modes)
    return PETSc.NullSpace().create(vectors=modes)


def patch_problem(msh, V, size, lw, thickness, force):
    """The benchmark's problem on `msh` in space V: linear elasticity (plane stress per unit thickness
    in 2D), clamped at y = 0, `force` N downwards on the centred lw-wide patch of the top face (lw x
    lw in 3D). Returns the bilinear form, the linear form and the clamp."""
    dim = len(size)
    mu = E / (2 * (1 + NU))
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    if dim == 2:
        lam = 2 * lam * mu / (lam + 2 * mu)  # plane stress, per unit thickness
    fdim = dim - 1

    def patch(x):
        inside = np.isclose(x[1], size[1])
        for a in ([0] if dim == 2 else [0, 2]):
            inside &= np.abs(x[a] - 0.5 * size[a]) <= 0.5 * lw + 1e-12
        return inside

    facets = mesh.locate_entities_boundary(msh, fdim, patch)
    tags = mesh.meshtags(msh, fdim, facets, np.full(len(facets), 1, dtype=np.int32))
    traction = np.zeros(dim)
    traction[1] = -force / (lw * (thickness if dim == 2 else lw))
    u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    eps = lambda w: ufl.sym(ufl.grad(w))
    sigma = lambda w: 2 * mu * eps(w) + lam * ufl.tr(eps(w)) * ufl.Identity(dim)
    a = fem.form(ufl.inner(sigma(u), eps(v)) * ufl.dx)
    ds = ufl.Measure("ds", domain=msh, subdomain_data=tags)
    L = fem.form(ufl.inner(fem.Constant(msh, traction), v) * ds(1))
    clamped = mesh.locate_entities_boundary(msh, fdim, lambda x: np.isclose(x[1], 0.0))
    bc = fem.dirichletbc(np.zeros(dim), fem.locate_dofs_topological(V, fdim, clamped), V)
    return a, L, bc


def dolfinx_solve(cells, size, lw, thickness, force):
    """Setup, assembly, solve and solve CPU seconds, iterations, largest |u| [m]."""
    dim = len(cells)
    t0 = time.perf_counter()
    if dim == 2:
        msh = mesh.create_rectangle(MPI.COMM_WORLD, [[0, 0], list(size)], list(cells), mesh.CellType.quadrilateral)
    else:
        msh = mesh.create_box(MPI.COMM_WORLD, [[0, 0, 0], list(size)], list(cells), mesh.CellType.hexahedron)
    V = fem.VectorFunctionSpace(msh, ("Lagrange", 1))
    a, L, bc = patch_problem(msh, V, size, lw, thickness, force)
    setup = time.perf_counter() - t0

    t0 = time.perf_counter()
    A = assemble_matrix(a, bcs=[bc])
    A.assemble()
    b = assemble_vector(L)
    apply_lifting(b, [a], bcs=[[bc]])
    b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    set_bc(b, [bc])
    assembly = time.perf_counter() - t0

    t0, c0 = time.perf_counter(), time.process_time()
    A.setNearNullSpace(rigid_body_modes(V, dim))
    opts = PETSc.Options()
    opts["ksp_type"] = "cg"
    opts["ksp_rtol"] = 1e-8
    opts["ksp_norm_type"] = "unpreconditioned"  # ||K u - f|| / ||f||, as the workbench
    opts["pc_type"] = "gamg"
    opts["pc_gamg_type"] = "agg"
    opts["mg_levels_ksp_type"] = "chebyshev"
    opts["mg_levels_pc_type"] = "jacobi"
    solver = PETSc.KSP().create(msh.comm)
    solver.setFromOptions()
    solver.setOperators(A)
    uh = fem.Function(V)
    solver.solve(b, uh.vector)
    uh.x.scatter_forward()
    solve, solve_cpu = time.perf_counter() - t0, time.process_time() - c0
    if solver.getConvergedReason() <= 0:
        raise RuntimeError(f"DOLFINx CG + GAMG did not converge ({solver.getConvergedReason()})")
    umax = msh.comm.allreduce(np.abs(uh.x.array).max(initial=0.0), op=MPI.MAX)
    return setup, assembly, solve, solve_cpu, solver.getIterationNumber(), umax


def workbench_solve(build, case):
    """Solve seconds (wall, CPU), iterations and largest |u| component of `workbench fem case`; the
    CPU time is the sum of the solver's phases in the WORKBENCH_FEM_PROFILE table (deal.II's
    TimerOutput: every section but the mesh and DoF setup ones)."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "fem"
        run = subprocess.run([str(build / "cli" / "workbench"), "fem", str(ROOT / case), "-o", str(out)],
                             capture_output=True, text=True, check=True, env={**os.environ, "WORKBENCH_FEM_PROFILE": "1"})
        m = re.search(r"solved with .*: (\d+) iterations, relative residual \S+ \(([0-9.e+-]+) s\)", run.stderr)
        setup = {"create triangulation", "boundary ids", "refine", "distribute dofs", "constraints",
                 "sparsity pattern", "matrix reinit"}
        cpu_table = run.stderr.split("Total CPU time")[1].split("Total wallclock time")[0]
        cpu = sum(float(t) for name, t in re.findall(r"^\| (\S.*?) +\| +\d+ \| +([0-9.e+-]+)s \|", cpu_table, re.M)
                  if name not in setup)
        nodes = np.genfromtxt(out / "fem_nodes.csv", delimiter=",", names=True)
        umax = max(np.abs(nodes[c]).max() for c in nodes.dtype.names if c.startswith("u"))
    return float(m.group(2)), cpu, int(m.group(1)), umax


def main():
    args = sys.argv[1:]
    build = Path(args[0]) if args and args[0] not in PROBLEMS else ROOT / "build"
    names = [a for a in args if a in PROBLEMS] or list(PROBLEMS)
    for name in names:
        case, cells, size, lw, thickness, force = PROBLEMS[name]
        setup, assembly, solve, solve_cpu, its, umax = dolfinx_solve(cells, size, lw, thickness, force)
        ours, ours_cpu, our_its, our_umax = workbench_solve(build, case)
        if MPI.COMM_WORLD.rank == 0:
            dofs = len(cells) * np.prod([c + 1 for c in cells])
            print(f"{name} ({dofs} DoFs, {MPI.COMM_WORLD.size} rank(s)): DOLFINx CG+GAMG setup {setup:.2f} s, "
                  f"assembly {assembly:.2f} s, solve {solve:.2f} s (CPU {solve_cpu:.2f} s, {its} it., "
                  f"max |u| {umax:.6e} m); workbench solve {ours:.2f} s (CPU {ours_cpu:.2f} s, {our_its} it., "
                  f"max |u| {our_umax:.6e} m); peer / workbench solve: {solve / ours:.2f} wall, "
                  f"{solve_cpu / ours_cpu:.2f} CPU")


if __name__ == "__main__":
    main()
