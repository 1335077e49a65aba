#!/usr/bin/python3
"""What sets the agents' u_x on the side far from an off-centre load (issue 23: u_x of FEM's sign at every
side node), from 2D `workbench compare` folders of the seed plate (a dense box on a rigid base at y = 0,
steel, directional rule set with turning paths). docs/agent-model.md, "Turning paths: measured".

    /usr/bin/python3 bench/research/ux_sign.py OUT_DIR [OUT_DIR ...]

The displacement march of agent/src/fields.cc (node_displacements_marched) re-done in numpy (it reproduces
the folder's agent u_x to round-off), fed with the agents' stresses with one field swapped for FEM's, and
with the bonded base layer (agent/src/stress_components.cc half_plane_layer, the elastic half-plane's) replaced
by another: the local layer it replaced (nu sigma_y of the agent, over 0.25 x the pressure's width), or the
candidate nu p(x) (p the base row's sigma_y) spread along x by a Gaussian of sd c y (mirrored at the free
sides), over a height `share` x the pressure's width. Per row: the share of side nodes (above the lowest tenth) whose u_x
has FEM's sign, the heights [mm] where u_x changes sign on the far side, far-field sigma_x and tau_xy."""
import csv
import sys

import numpy as np
from scipy.fft import dst, idst
from scipy.special import erf

E, NU = 206e9, 0.3


def load(folder):
    rows = list(csv.DictReader(open(folder + "/cells.csv")))
    x = np.array([float(r["x [m]"]) for r in rows]); y = np.array([float(r["y [m]"]) for r in rows])
    h = np.min(np.diff(np.unique(x)))
    i, j = np.round(x / h - 0.5).astype(int), np.round(y / h - 0.5).astype(int)
    nx, ny = i.max() + 1, j.max() + 1
    f = {"h": h, "nx": nx, "ny": ny, "far": np.zeros((nx, ny), bool)}
    f["far"][i, j] = [r["far"] == "1" for r in rows]
    for k in ("sigma_x", "sigma_y", "tau_xy"):
        for who in ("agent", "fem"):
            g = np.zeros((nx, ny)); g[i, j] = [float(r["%s_%s [Pa]" % (who, k)]) for r in rows]; f[who + "_" + k] = g
    f["agent_u_x"], f["fem_u_x"] = np.zeros((nx + 1, ny + 1)), np.zeros((nx + 1, ny + 1))
    for r in csv.DictReader(open(folder + "/nodes.csv")):
        for who in ("agent", "fem"):
            f[who + "_u_x"][int(r["i"]), int(r["j"])] = float(r["%s_u_x [m]" % who])
    return f


def marched(sx, sy, tau, h):
    """u_x of node_displacements_marched: the rows' eps_x line plus the row mean of the column marches."""
    nx, ny = sx.shape
    ex, ey, G = (sx - NU * sy) / E, (sy - NU * sx) / E, E / (2 * (1 + NU))
    col = np.zeros((nx, ny + 1)); col[:, 1:] = np.cumsum(ey * h, axis=1)
    uy = np.zeros((nx + 1, ny + 1)); uy[:-1] += col; uy[1:] += col; uy[1:-1] /= 2
    uy[0], uy[nx] = 1.5 * col[0] - 0.5 * col[1], 1.5 * col[nx - 1] - 0.5 * col[nx - 2]  # the sides: extrapolated
    mid = 0.5 * (uy[:, :-1] + uy[:, 1:])
    carried = np.cumsum((tau / G - np.diff(mid, axis=0) / h) * h, axis=1)  # (nx, ny): at node rows 1..ny
    march = np.zeros((nx + 1, ny + 1))
    w_lo = np.where(np.arange(nx) == 0, 1.0, 0.5)[:, None]; w_hi = np.where(np.arange(nx) == nx - 1, 1.0, 0.5)[:, None]
    march[:-1, 1:] += w_lo * carried; march[1:, 1:] += w_hi * carried
    ux = np.zeros((nx + 1, ny + 1))
    for k in range(1, ny + 1):
        b, a = k - 1, min(k, ny - 1)
        line = np.concatenate([[0], np.cumsum(0.5 * (ex[:, b] + ex[:, a]) * h)])
        ux[:, k] = line + np.mean(march[:, k] - line)
    return ux


def layer_shear(L, h):
    """The layer's shear by horizontal equilibrium, integrated down each column from the top (0 there)."""
    step = np.gradient(L, h, axis=0) * h
    above = np.cumsum(step[:, ::-1], axis=1)[:, ::-1] - step
    return above + 0.5 * step


def layer(sy, h, share=0.25, spread=None):
    """The C++ layer (spread None: nu sigma_y of the agent itself) or the candidate (nu p(x) spread by sd spread y)."""
    nx, ny = sy.shape
    p = np.abs(sy[:, 0]); x = (np.arange(nx) + 0.5) * h
    mean = np.sum(p * x) / p.sum()
    ell = share * min(np.sqrt(12 * max(0.0, np.sum(p * x * x) / p.sum() - mean ** 2)), nx * h)
    y = (np.arange(ny) + 0.5) * h
    side = np.minimum(np.arange(nx) + 0.5, nx - np.arange(nx) - 0.5) * h
    shape = np.maximum(0, 1 - y[None, :] / ell) * (1 - np.exp(-side[:, None] / y[None, :]))
    if spread is None:
        return NU * sy * shape
    e, W, L = np.arange(nx + 1) * h, nx * h, np.zeros_like(sy)
    for k in range(ny):
        if y[k] >= ell:
            break
        sd = max(spread * y[k], 0.3 * h)
        kernel = sum(np.diff(0.5 * (1 + erf((e[None, :] - c[:, None]) / (np.sqrt(2) * sd))), axis=1) for c in (x, -x, 2 * W - x))
        L[:, k] = NU * (sy[:, 0] @ kernel)
    return L * shape


def half_plane(sy, h):
    """The C++ layer: nu p(x) in sine modes of the width, mode k reaching height y as (1 - k y / 2) exp(-k y)."""
    nx, ny = sy.shape
    amplitude, k = dst(NU * sy[:, 0], type=2, norm="ortho"), np.pi * np.arange(1, nx + 1) / (nx * h)
    L = np.zeros((nx, ny))
    for j in range(ny):
        ky = k * (j + 0.5) * h
        L[:, j] = idst(amplitude * (1 - ky / 2) * np.exp(-ky), type=2, norm="ortho")
    return L


def report(name, f, sx, sy, tau):
    h, nx, ny = f["h"], f["nx"], f["ny"]
    ux, fx = marched(sx, sy, tau, h), f["fem_u_x"]
    ks = [k for k in range(ny + 1) if k > 0.1 * ny]
    same = np.mean(np.sign(np.concatenate([ux[0, ks], ux[nx, ks]])) == np.sign(np.concatenate([fx[0, ks], fx[nx, ks]])))
    far_side = nx if abs(fx[nx, ny // 4]) < abs(fx[0, ny // 4]) else 0
    def crossings(u):
        c = u[far_side]
        return ",".join("%.0f" % ((k + c[k] / (c[k] - c[k + 1])) * h * 1e3) for k in range(1, ny // 2) if np.sign(c[k]) != np.sign(c[k + 1])) or "-"
    m = f["far"]
    rel = lambda a, b: np.sqrt(np.sum((a[m] - b[m]) ** 2) / np.sum(b[m] ** 2))
    print("| %s | %.3f | %s (FEM %s) | %.3f | %.3f |" % (name, same, crossings(ux), crossings(fx), rel(sx, f["fem_sigma_x"]), rel(tau, f["fem_tau_xy"])), flush=True)


def main():
    if len(sys.argv) < 2:
        print("usage: ux_sign.py OUT_DIR [OUT_DIR ...]", file=sys.stderr)
        sys.exit(2)
    print("| folder: stresses | u_x sign, side nodes | far side's sign changes [mm] | sigma_x | tau_xy |\n|---|---|---|---|---|")
    for folder in sys.argv[1:]:
        f = load(folder)
        name = folder.rstrip("/").split("/")[-1]
        a = {k: f["agent_" + k] for k in ("sigma_x", "sigma_y", "tau_xy")}
        report(name + ": the agents'", f, a["sigma_x"], a["sigma_y"], a["tau_xy"])
        for swap in ("sigma_x", "tau_xy"):
            b = dict(a); b[swap] = f["fem_" + swap]
            report(name + ": FEM's " + swap, f, b["sigma_x"], b["sigma_y"], b["tau_xy"])
        report(name + ": FEM's all", f, f["fem_sigma_x"], f["fem_sigma_y"], f["fem_tau_xy"])
        L0 = half_plane(a["sigma_y"], f["h"])
        for share, spread in ((0.25, None), (0.5, 3.0), (0.4, 3.0)):
            L = layer(a["sigma_y"], f["h"], share, spread)
            report(name + ": layer %.2f, spread %s" % (share, "%gy" % spread if spread else "none"), f, a["sigma_x"] - L0 + L,
                   a["sigma_y"], a["tau_xy"] - layer_shear(L0, f["h"]) + layer_shear(L, f["h"]))


if __name__ == "__main__":
    main()
