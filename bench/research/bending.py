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
    dux_dy = np.diff(0.5 * (ux[1:] + ux[:-1]), axis=1) / h          # per agent
    slope = g - dux_dy                                              # du_y/dx per agent
    sl = np.concatenate([slope[:, :1], 0.5 * (slope[:, 1:] + slope[:, :-1]), slope[:, -1:]], 1)
    uy = np.concatenate([np.zeros((1, ny + 1)), np.cumsum(sl, 0) * h], 0)
    return np.stack([ux, uy], 2)
