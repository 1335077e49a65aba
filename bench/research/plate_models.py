"""Research helpers (issue: agent stress components): a plane Q1 FEM on a rectangular agent grid and a
Python port of the 2D directional rule set, so that rules can be tried on bodies the comparison does not
ship (pulled plates, cantilevers) without building the C++.  /usr/bin/python3 (numpy, scipy)."""
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla


def fem_plate(nx, ny, h, E, nu, P, load_cells, load_side="top", rigid="base", sub=4, plane="stress", thick=0.002,
              load_dir=(0.0, -1.0)):
    """Q1 FEM on an nx x ny grid of agents of size h [m], each cut into sub x sub elements.
    rigid: 'base' (j = 0 edge clamped) or 'left' (x = 0 edge clamped) or a list of both.
    load_cells: agent indices along the loaded edge; P [N] spread uniformly over them, direction load_dir.
    Returns per-agent mean sx, sy, txy, vm (plane) and node displacements on the agent nodes (nx+1, ny+1, 2)."""
    if plane == "strain":
        Ee, nue = E / (1 - nu ** 2), nu / (1 - nu)
    else:
        Ee, nue = E, nu
    D = Ee / (1 - nue ** 2) * np.array([[1, nue, 0], [nue, 1, 0], [0, 0, (1 - nue) / 2]])
    NX, NY, e = nx * sub, ny * sub, h / sub
    g = 1 / np.sqrt(3)
    Ke = np.zeros((8, 8))
    def Bmat(xi, eta):
        dN = 0.25 * np.array([[-(1 - eta), (1 - eta), (1 + eta), -(1 + eta)],
                              [-(1 - xi), -(1 + xi), (1 + xi), (1 - xi)]]) * (2 / e)
        B = np.zeros((3, 8))
        B[0, 0::2] = dN[0]; B[1, 1::2] = dN[1]; B[2, 0::2] = dN[1]; B[2, 1::2] = dN[0]
        return B
    for xi in (-g, g):
        for eta in (-g, g):
            B = Bmat(xi, eta)
            Ke += B.T @ D @ B * (e / 2) ** 2 * thick
    ii, jj = np.meshgrid(np.arange(NX), np.arange(NY), indexing="ij")
    n0 = (jj * (NX + 1) + ii).ravel()
    nodes = np.stack([n0, n0 + 1, n0 + NX + 2, n0 + NX + 1], 1)
    dofs = np.stack([2 * nodes, 2 * nodes + 1], 2).reshape(-1, 8)
    rows = np.repeat(dofs, 8, 1).ravel(); cols = np.tile(dofs, (1, 8)).ravel()
    ndof = 2 * (NX + 1) * (NY + 1)
    K = sp.coo_matrix((np.tile(Ke.ravel(), NX * NY), (rows, cols)), shape=(ndof, ndof)).tocsr()
    f = np.zeros(ndof)
    # Load: uniform traction over the loaded agents' faces on the given side.
    per = P / (len(load_cells) * sub)
    for c in load_cells:
        for s in range(sub):
            if load_side == "top":
                a, b = (NY) * (NX + 1) + c * sub + s, (NY) * (NX + 1) + c * sub + s + 1
            elif load_side == "bottom":
                a, b = c * sub + s, c * sub + s + 1
            elif load_side == "right":
                a, b = (c * sub + s) * (NX + 1) + NX, (c * sub + s + 1) * (NX + 1) + NX
            for n in (a, b):
                f[2 * n] += 0.5 * per * load_dir[0]; f[2 * n + 1] += 0.5 * per * load_dir[1]
    fixed = np.zeros(ndof, bool)
    rig = [rigid] if isinstance(rigid, str) else rigid
    for r in rig:
        if r == "base":
            n = np.arange(NX + 1)
        elif r == "left":
            n = np.arange(NY + 1) * (NX + 1)
        elif r == "right":
            n = np.arange(NY + 1) * (NX + 1) + NX
        elif r == "top":
            n = NY * (NX + 1) + np.arange(NX + 1)
        fixed[2 * n] = True; fixed[2 * n + 1] = True
    free = ~fixed
    u = np.zeros(ndof)
    u[free] = spla.spsolve(K[free][:, free].tocsc(), f[free])
    react = K @ u - f
    # Stress at element centres -> agent means.
    B0 = Bmat(0, 0)
    s = (D @ (B0 @ u[dofs].T)).T  # (nel, 3)
    s = s.reshape(NX, NY, 3)
    s = s.reshape(nx, sub, ny, sub, 3).mean(axis=(1, 3))
    sx, sy, txy = s[..., 0], s[..., 1], s[..., 2]
    szz = nu * (sx + sy) if plane == "strain" else 0 * sx
    vm = np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - szz) ** 2 + (szz - sx) ** 2) + 3 * txy ** 2)
    U = u.reshape(NY + 1, NX + 1, 2)[::sub, ::sub].transpose(1, 0, 2)
    return dict(sx=sx, sy=sy, txy=txy, vm=vm, u=U, reaction=react.reshape(-1, 2))


def directional_plate(nx, ny, load_cells, P, directions=32, fan_angle=66.1, fan_power=2.59, diffusion=2.0, h=0.002,
                      thick=0.002, moment_balance=True):
    """2D directional rule set on a rectangular plate, load -y on the top faces of load_cells, rigid base.
    Returns per-agent sigma_y [Pa] (x index first) as docs/agent-model.md defines it, plus sx from rays."""
    n = directions
    ang = np.radians(fan_angle) * ((2 * np.arange(n) + 1) / n - 1)
    slope, w = np.tan(ang), np.cos(ang) ** fan_power
    w /= w.sum()
    A = h * thick
    top = np.zeros((nx, ny)); bot = np.zeros((nx, ny)); side = np.zeros((nx, ny)); shear = np.zeros((nx, ny)); dl = np.zeros((nx, ny))
    r = np.sqrt(diffusion * 1e-3 * h) / h
    for c in load_cells:
        F0 = P / len(load_cells)
        # packets: arrays of (x position in agents, direction index, force)
        px = np.full(n, c + 0.5); pd = np.arange(n); pf = F0 * w
        for j in range(ny - 1, -1, -1):
            cell = np.clip(px.astype(int), 0, nx - 1)
            np.add.at(top[:, j], cell, pf); np.add.at(bot[:, j], cell, pf)
            np.add.at(side[:, j], cell, pf * slope[pd] ** 2)
            np.add.at(shear[:, j], cell, pf * slope[pd])
            rowf = np.bincount(cell, pf, nx)
            if moment_balance:
                xs = np.arange(nx) + 0.5
                mu = np.sum(rowf * (xs - (c + 0.5)))
                cu = xs.mean(); suu = np.sum((xs - cu) ** 2)
                delta = -mu / suu * (xs - cu)
                top[:, j] += delta; bot[:, j] += delta; dl[:, j] += delta
            if j == 0:
                break
            # move: offset within agent kept
            x = px + slope[pd]
            xs2 = np.concatenate([x - r, x + r]); d2 = np.concatenate([pd, pd]); f2 = np.concatenate([pf, pf]) * 0.5
            # fold at free sides
            for _ in range(4):
                lo = xs2 < 0; xs2[lo] = -xs2[lo]; d2[lo] = n - 1 - d2[lo]
                hi = xs2 > nx; xs2[hi] = 2 * nx - xs2[hi]; d2[hi] = n - 1 - d2[hi]
            # merge by (cell, dir) at force-weighted mean position
            cell2 = np.clip(xs2.astype(int), 0, nx - 1)
            key = cell2 * n + d2
            uk, inv = np.unique(key, return_inverse=True)
            F = np.bincount(inv, f2); M = np.bincount(inv, f2 * xs2)
            px = M / F; pd = uk % n; pf = F
    sy = -0.5 * (top + bot) / A
    sx_ray = -side / A
    # A packet moving down-right (slope > 0) under a downward load: tau_xy = +slope * sigma_y.
    return dict(sy=sy, sx_ray=sx_ray, txy_ray=shear / A, sy_delta=-dl / A)
