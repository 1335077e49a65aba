"""Bending (research prototype): a column rule set for a body whose rigid face is not ahead of the load.
Cuts across the path to the support (columns of agents) carry the section resultants V, M from the load to
the clamp, column to column; each column distributes them linearly (Navier, like the directional rule set's
row moment balance) and its shear by a scan of the column (Jourawski). Displacement: the agents' strains
marched from the clamp (u = 0 there) along each row, u_y from du_y/dx = gamma - du_x/dy."""
import numpy as np


def cantilever_columns(nx, ny, h, P, load_col, E, nu, thick=0.002):
    """Clamp at x = 0 (left face rigid), load P (signed, +y up) on the top face of column load_col."""
    y = (np.arange(ny) + 0.5) * h
    yc = y.mean()
    I = thick * (np.sum(h * (y - yc) ** 2) + ny * h ** 3 / 12)     # per column, from its agents
    A = ny * h * thick
    xcen = (np.arange(nx) + 0.5) * h
    xload = (load_col + 0.5) * h
    # Section resultants, passed from the load toward the clamp (column to column): V = P, M = P (xload - x).
    V = np.where(xcen <= xload, P, 0.0)
    M = np.where(xcen <= xload, P * (xload - xcen), 0.0)
    sx = -(M[:, None] * (y - yc)[None, :]) / I                    # hogging under a downward P: top in tension

    # Jourawski: tau = V Q / (I t), Q the first moment of the agents above the level (a scan down the column).
    ytop = ny * h
    Q = 0.5 * thick * ((ytop - yc) ** 2 - (y - yc) ** 2)
    tau = (V[:, None] * Q[None, :]) / (I * thick)
    sy = np.zeros((nx, ny))
    return dict(sx=sx, sy=sy, txy=tau, V=V, M=M, reaction=P)


def march_from_clamp(sx, sy, txy, E, nu, h):
    """u = 0 on the clamped left face; u_x along each row by eps_x, u_y by du_y/dx = gamma - du_x/dy."""
    G = E / (2 * (1 + nu))
    ex, ey, g = (sx - nu * sy) / E, (sy - nu * sx) / E, txy / G
    nx, ny = ex.shape
    # u_x at node rows: integrate eps_x along x; node rows between agent rows take the mean of both.
    exn = np.concatenate([ex[:, :1], 0.5 * (ex[:, 1:] + ex[:, :-1]), ex[:, -1:]], 1)
    ux = np.concatenate([np.zeros((1, ny + 1)), np.cumsum(exn, 0) * h], 0)
    # u_y: marched from the clamp along the middle row of nodes (the centroid line: du_y/dx = gamma - du_x/dy
    # from the two agent rows around it), then eps_y integrated up and down each line of nodes from it.
    m = ny // 2
    dux_dy = (ux[:, m + 1] - ux[:, m - 1]) / (2 * h)                   # at the middle row's nodes
    gm = 0.5 * (g[:, m - 1] + g[:, m])                                  # per column, at the middle
    slope = gm - 0.5 * (dux_dy[1:] + dux_dy[:-1])
    mid = np.concatenate([[0.0], np.cumsum(slope) * h])
    eyn = np.concatenate([ey[:1], 0.5 * (ey[1:] + ey[:-1]), ey[-1:]], 0)   # (nx+1, ny) node lines
    up = np.concatenate([np.zeros((nx + 1, 1)), np.cumsum(eyn, 1) * h], 1)
    uy = mid[:, None] + up - up[:, m][:, None]
    return np.stack([ux, uy], 2)


if __name__ == "__main__":
    # Cantilevers clamped at x = 0, 2 N down on the top face of the last column; the Python FEM as reference.
    import plate_models as pm
    E, nu = 206e9, 0.3
    rel = lambda m, r, k: float(np.linalg.norm((m - r)[k]) / np.linalg.norm(r[k]))
    print("cantilever        tip u_y: FEM / columns / Euler-Bernoulli [nm]   ratio  reaction FEM/columns [N]  "
          "far: sigma_x tau_xy vonMises  body u")
    for (nx, ny, h) in ((40, 8, 0.005), (100, 20, 0.002), (20, 8, 0.005)):
        f = pm.fem_plate(nx, ny, h, E, nu, 2.0, [nx - 1], rigid="left", sub=4 if nx * ny < 1000 else 2)
        b = cantilever_columns(nx, ny, h, -2.0, nx - 1, E, nu)
        u = march_from_clamp(b["sx"], b["sy"], b["txy"], E, nu, h)
        I = 0.002 * (ny * h) ** 3 / 12
        eb = -2.0 * ((nx - .5) * h) ** 3 / (3 * E * I)
        far = np.ones((nx, ny), bool); far[-5:, :] = False; far[:5, :] = False   # 5 agents from load and clamp
        vm = np.sqrt(b["sx"] ** 2 + 3 * b["txy"] ** 2)
        print("%3.0f x %2.0f mm, h %.0f mm  %8.1f / %8.1f / %8.1f   %.3f   %.3f / %.3f   %.3f %.3f %.3f   %.3f" % (
            nx * h * 1e3, ny * h * 1e3, h * 1e3, f["u"][-1, ny // 2, 1] * 1e9, u[-1, ny // 2, 1] * 1e9, eb * 1e9,
            u[-1, ny // 2, 1] / f["u"][-1, ny // 2, 1], f["reaction"][:, 1].sum(), -b["reaction"],
            rel(b["sx"], f["sx"], far), rel(b["txy"], f["txy"], far), rel(vm, f["vm"], far), rel(u, f["u"], np.ones_like(u, bool))))
