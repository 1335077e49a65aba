#!/usr/bin/python3
"""Stress components of the agents (sigma_x, tau_xy, von Mises) and their displacement: research prototype.

    /usr/bin/python3 bench/research/agent_stress_prototype.py OUT_DIR [OUT_DIR ...] [--fan-angle 66 ...]

OUT_DIR is the folder `workbench compare CASE -o OUT_DIR` wrote (cells.csv, nodes.csv, fem/fem_cells.csv,
summary.json, lines.json, and the case file named in summary.json). The prototype handles what the seed
plate family is: a 2D rectangular plate of square agents, one load on a patch of the top face (pushed or
pulled along y), the base rigid and bonded. For each folder it prints the relative L2 error against the FEM
reference (far field and body, the comparison's own far mask) of:

  current     the C++ directional rule set as it is (cells.csv / nodes.csv; it has no tau_xy: 0)
  recovery    post-processing only: tau_xy, sigma_x from the C++ agents' sigma_y by the two equilibrium
              equations (rows scanned from a free side, d/dy from a local quadratic fit over rows)
  turning     the recommended rule: turning packets + tie + base layer (docs/research/stress-components.md)
  zero        1.0 by definition (the model that predicts nothing)

and, for the displacement, the share of side-edge nodes above the lowest tenth whose u_x has FEM's sign.
Everything here is numpy; nothing is written. Exit 2 with one line on a folder it cannot read."""
import argparse
import csv
import json
import os
import sys
import tomllib

import numpy as np
from scipy.special import erf

# ---------------------------------------------------------------------------------------------------------
# The recommended rule: defaults (fitted on the seed plate, 5 mm agents, load at x = 100 mm).
DEFAULTS = dict(fan_angle=66.0, fan_power=2.0, directions=32, diffusion_mm=2.0, base_layer=0.25, window_mm=5.0, reach=1.0)


def fan(directions, fan_angle, fan_power):
    """The directional rule set's entry fan: slopes tan(t), weights cos(t)^p (normalised)."""
    ang = np.radians(fan_angle) * ((2 * np.arange(directions) + 1) / directions - 1)
    w = np.cos(ang) ** fan_power
    return np.tan(ang), w / w.sum()


def column_shares(xk, sig, nx, h):
    """Share of a Gaussian (centre xk, sd sig, both [m]) in each agent column; the free sides mirror its tail."""
    edges = np.arange(nx + 1) * h
    W = nx * h
    out = np.zeros((len(xk), nx))
    for img, sgn in ((0, 1), (0, -1), (2 * W, -1)):
        c = img + sgn * xk
        cdf = 0.5 * (1 + erf((edges[None, :] - c[:, None]) / (np.sqrt(2) * sig[:, None])))
        out += np.diff(cdf, axis=1)
    return out


def turning_transfer(nx, ny, h, x0, force, thick, k):
    """Turning packets. The entry fan as in the directional rule set; each packet turns toward the lateral
    position where it belongs once the load fills the width (its quantile of the half-fan on its side of
    the load, spread over the width on that side): x(d) = x0 + L tanh(s d / L), slope s / cosh^2(s d / L).
    A target is never farther out than reach x the packet's straight ray at the far face (depth ny h).
    Diffusion: a Gaussian of variance diffusion * depth. The row's moment balance as in C++. Returns per
    agent sigma_y, the packets' shear tau = sum(F slope) / A and the balance's own sigma_y part.
    `force` is signed along the march (the inward normal of the loaded face): a pull is negative."""
    s0, w = fan(k["directions"], k["fan_angle"], k["fan_power"])
    A = h * thick
    W = nx * h
    q = np.cumsum(w) - w / 2
    xf = np.where(s0 < 0, x0 * q / 0.5, x0 + (W - x0) * (q - 0.5) / 0.5)
    L = xf - x0
    L = np.where(s0 * L > 0, L, np.sign(s0) * 1e-12)
    if k["reach"] > 0:
        # a packet turns no farther out than its straight ray would reach at the rigid face, times reach
        L = np.sign(L) * np.minimum(np.abs(L), k["reach"] * np.abs(s0) * ny * h)
    xs = (np.arange(nx) + 0.5) * h
    sy = np.zeros((nx, ny)); tau = np.zeros((nx, ny)); sy_bal = np.zeros((nx, ny))
    for j in range(ny - 1, -1, -1):
        d = (ny - 1 - j + 0.5) * h                      # depth of the row's centre below the loaded face
        if k.get("mirror"):
            # straight rays folded by the free sides (the current rule), deposited the same way
            x = np.abs(np.mod(x0 + s0 * d + W, 2 * W) - W)
            slope = s0 * np.sign(np.mod(x0 + s0 * d, 2 * W) - W) * -1
        else:
            arg = s0 * d / L
            x = x0 + L * np.tanh(arg)
            slope = s0 / np.cosh(arg) ** 2
        sig = np.full(len(s0), np.sqrt(max(k["diffusion_mm"] * 1e-3 * d, (0.3 * h) ** 2)))
        cw = column_shares(x, sig, nx, h) * (force * w)[:, None]
        f = cw.sum(0)
        tau[:, j] = (cw * slope[:, None]).sum(0) / A
        # The row's moment balance (as directional.cc): a linear, self-equilibrated correction.
        mu = np.sum(f * (xs - x0)); cu = xs.mean()
        delta = -mu / np.sum((xs - cu) ** 2) * (xs - cu)
        sy[:, j] = -(f + delta) / A
        sy_bal[:, j] = -delta / A
    return sy, tau, sy_bal


def turning_march(nx, ny, h, x0, force, thick, k):
    """The same rule as the directional rule set marches it (what C++ would do): packets per direction and
    agent at their force-weighted mean position; each row a packet moves by the slope of its direction's path
    at that depth, s0 / cosh^2(s0 d / L) (a table per direction and row: the diffusion spreads pieces about the
    path, the path alone turns), and splits into two halves at +-r (r^2 = diffusion x row height). A free side
    folds a piece's position back (its direction, and so its path, stays). Same returns as turning_transfer."""
    s0, w = fan(k["directions"], k["fan_angle"], k["fan_power"])
    n, A, W = len(s0), h * thick, nx * h
    q = np.cumsum(w) - w / 2
    xf = np.where(s0 < 0, x0 * q / 0.5, x0 + (W - x0) * (q - 0.5) / 0.5)
    L = np.where(s0 * (xf - x0) > 0, xf - x0, np.sign(s0) * 1e-12)
    if k["reach"] > 0:
        L = np.sign(L) * np.minimum(np.abs(L), k["reach"] * np.abs(s0) * ny * h)
    r = np.sqrt(k["diffusion_mm"] * 1e-3 * h)
    xs = (np.arange(nx) + 0.5) * h
    px, pd, pf = np.full(n, x0), np.arange(n), force * w
    sy = np.zeros((nx, ny)); tau = np.zeros((nx, ny)); sy_bal = np.zeros((nx, ny))
    for j in range(ny - 1, -1, -1):
        d = (ny - 1 - j + 0.5) * h
        slope = (s0 / np.cosh(s0 * d / L) ** 2)[pd]
        # the row's forces at the packets' positions half a row on (the agent centre), as the sweep books them
        xm = px + 0.5 * slope * h
        cell = np.clip((xm / h).astype(int), 0, nx - 1)
        f = np.bincount(cell, pf, nx)
        tau[:, j] = np.bincount(cell, pf * slope, nx) / A
        mu = np.sum(f * (xs - x0)); cu = xs.mean()
        delta = -mu / np.sum((xs - cu) ** 2) * (xs - cu)
        sy[:, j] = -(f + delta) / A
        sy_bal[:, j] = -delta / A
        x = px + slope * h
        x2 = np.concatenate([x - r, x + r]); d2 = np.concatenate([pd, pd]); f2 = np.concatenate([pf, pf]) * 0.5
        x2 = np.where(x2 < 0, -x2, x2); x2 = np.where(x2 > W, 2 * W - x2, x2)
        key = np.clip((x2 / h).astype(int), 0, nx - 1) * n + d2
        uk, inv = np.unique(key, return_inverse=True)
        F = np.bincount(inv, f2)
        px, pd, pf = np.bincount(inv, f2 * x2) / np.where(F != 0, F, 1), uk % n, F
    return sy, tau, sy_bal


def fit_d1(F, width):
    """First derivative along j (per row) of a local quadratic fit with a Gaussian window of width rows."""
    ny = F.shape[-1]
    Fr = F.reshape(-1, ny)
    d1 = np.empty_like(Fr); d2 = np.empty_like(Fr)
    jj = np.arange(ny)
    for j in range(ny):
        d = jj - j
        wgt = np.exp(-0.5 * (d / max(width, 1e-9)) ** 2)
        V = np.stack([np.ones(ny), d, d * d], 1)
        coef = np.linalg.solve(V.T @ (wgt[:, None] * V) + 1e-12 * np.eye(3), (V * wgt[:, None]).T @ Fr.T)
        d1[:, j], d2[:, j] = coef[1], 2 * coef[2]
    return d1.reshape(F.shape), d2.reshape(F.shape)


def scan_sigma_x(dtau_dy, h):
    """Horizontal equilibrium d sigma_x/dx = -d tau/dy along each row from the left free side (sigma_x = 0);
    the remainder at the right free side is taken out by a linear tie across the row. Face values -> agents."""
    nx, ny = dtau_dy.shape
    faces = np.concatenate([np.zeros((1, ny)), -np.cumsum(dtau_dy, 0) * h], 0)
    faces -= np.linspace(0, 1, nx + 1)[:, None] * faces[-1][None, :]
    return 0.5 * (faces[:-1] + faces[1:])


def shear_from_sigma_y(sy, h, width):
    """Vertical equilibrium d tau/dx = -d sigma_y/dy, each row scanned from the left free side."""
    nx, ny = sy.shape
    Q = np.concatenate([np.zeros((1, ny)), np.cumsum(sy, 0) * h], 0)
    d1, _ = fit_d1(Q, width)
    t = -d1 / h
    return 0.5 * (t[:-1] + t[1:])


def base_layer(sy, h, nu_eff, ell):
    """The bonded base holds eps_x = 0, so sigma_x = nu sigma_y on it, fading linearly to 0 at ell above it and
    near a free side as 1 - exp(-d / y) (d the distance to the side, y the height); its tau_xy from horizontal
    equilibrium integrated down from the top of the layer (zero there)."""
    nx, ny = sy.shape
    X, Y = np.meshgrid((np.arange(nx) + 0.5) * h, (np.arange(ny) + 0.5) * h, indexing="ij")
    e = 1 - np.exp(-np.minimum(X, nx * h - X) / Y)
    sx_b = nu_eff * sy * np.clip(1 - Y / ell, 0, None) * e
    dsx = np.gradient(sx_b, h, axis=0)
    tau_b = np.cumsum(dsx[:, ::-1], 1)[:, ::-1] * h - 0.5 * dsx * h
    return sx_b, tau_b


def spread_width(p, h):
    """Width of a force distribution over a row: sqrt(12 variance) (W for a uniform one)."""
    p = np.abs(p)
    xs = (np.arange(len(p)) + 0.5) * h
    if not p.sum() > 0:
        return len(p) * h
    m = np.sum(p * xs) / p.sum()
    return np.sqrt(12 * np.sum(p * (xs - m) ** 2) / p.sum())


def turning_rule(g, k, march=False):
    """sigma_x, sigma_y, tau_xy of the recommended rule on plate g (march: the packet march, else the
    continuous form)."""
    nx, ny, h = g["nx"], g["ny"], g["h"]
    transfer = turning_march if march else turning_transfer
    sy, tau_p, sy_bal = transfer(nx, ny, h, g["x0"], g["force"], g["thick"], k)
    wr = k["window_mm"] * 1e-3 / h
    tau_bal = shear_from_sigma_y(sy_bal, h, wr)
    ell = k["base_layer"] * min(spread_width(sy[:, 0], h), nx * h)
    sx_b, tau_b = base_layer(sy, h, g["nu_eff"], ell)
    d1, _ = fit_d1(tau_p + tau_bal, wr)
    sx = scan_sigma_x(d1 / h, h) + sx_b
    return sx, sy, tau_p + tau_bal + tau_b


def recovery_rule(g, sy, k):
    """Post-processing of the C++ agents' sigma_y alone: tau and sigma_x by the equilibrium scans, the base
    layer added. d/dy through the same local fit (window_mm)."""
    h = g["h"]
    wr = k["window_mm"] * 1e-3 / h
    tau = shear_from_sigma_y(sy, h, wr)
    ell = k["base_layer"] * min(spread_width(sy[:, 0], h), g["nx"] * h)
    sx_b, tau_b = base_layer(sy, h, g["nu_eff"], ell)
    d1, _ = fit_d1(tau, wr)
    return scan_sigma_x(d1 / h, h) + sx_b, sy, tau + tau_b


def von_mises(sx, sy, tau, nu, plane_strain):
    sz = nu * (sx + sy) if plane_strain else 0 * sx
    return np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2) + 3 * tau ** 2)


def displacement(sx, sy, tau, g):
    """Nodes (nx+1, ny+1, 2) from the agent strains, the rigid base holding u = 0. u_y: eps_y integrated up
    each column (nodes: mean of their columns). u_x: eps_x integrated along each row of nodes; the row's
    constant is the mean over the row of the marches up from the base, du_x/dy = gamma_xy - du_y/dx."""
    E, nu, h = g["E_eff"], g["nu_eff"], g["h"]
    G = E / (2 * (1 + nu))
    ex, ey, gam = (sx - nu * sy) / E, (sy - nu * sx) / E, tau / G
    nx, ny = ex.shape
    col = np.concatenate([np.zeros((nx, 1)), np.cumsum(ey, 1) * h], 1)
    uy = np.zeros((nx + 1, ny + 1)); uy[:-1] += col; uy[1:] += col; uy[1:-1] /= 2
    uyc = 0.5 * (uy[:, :-1] + uy[:, 1:])
    colx = np.concatenate([np.zeros((nx, 1)), np.cumsum(gam - (uyc[1:] - uyc[:-1]) / h, 1) * h], 1)
    march = np.zeros((nx + 1, ny + 1)); march[:-1] += colx; march[1:] += colx; march[1:-1] /= 2
    exn = np.concatenate([ex[:, :1], 0.5 * (ex[:, 1:] + ex[:, :-1]), ex[:, -1:]], 1)
    line = np.concatenate([np.zeros((1, ny + 1)), np.cumsum(exn, 0) * h], 0)
    ux = line + np.mean(march - line, axis=0)[None, :]
    ux[:, 0] = 0.0  # the rigid base holds its nodes
    return np.stack([ux, uy], 2)


# ---------------------------------------------------------------------------------------------------------
def fail(folder, what):
    print(f"agent_stress_prototype: {folder}: {what}", file=sys.stderr)
    sys.exit(2)


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    head = rows[0]
    return {name: np.array([float(r[i]) if r[i] != "" else np.nan for r in rows[1:]]) for i, name in enumerate(head)}


def load_folder(folder):
    """The plate, its load and both models' fields on the agent grid ([i, j], j = 0 at the base)."""
    try:
        summary = json.load(open(os.path.join(folder, "summary.json")))
        cells = read_csv(os.path.join(folder, "cells.csv"))
        femc = read_csv(os.path.join(folder, "fem", "fem_cells.csv"))
        nodes = read_csv(os.path.join(folder, "nodes.csv"))
        lines = json.load(open(os.path.join(folder, "lines.json")))
    except (OSError, ValueError, KeyError) as e:
        fail(folder, f"not a finished 2D comparison output ({e})")
    # summary.json names the case as given to compare: relative to where it ran (here, the folder's parent
    # or the repository)
    repo = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    tries = [summary["case"], os.path.join(folder, "..", summary["case"]), os.path.join(repo, summary["case"])]
    case_path = next((c for c in tries if os.path.exists(c)), summary["case"])
    try:
        case = tomllib.load(open(case_path, "rb"))
    except (OSError, tomllib.TOMLDecodeError) as e:
        fail(folder, f"case file {summary['case']}: {e}")
    h = summary["agent"]["agent_size"]
    if "z [m]" in cells or len(case.get("load", [])) != 1 or case.get("boundary", {}).get("rigid") != ["base"]:
        fail(folder, "the prototype handles a 2D plate with one load and a rigid base only")
    i = np.rint(cells["x [m]"] / h - 0.5).astype(int)
    j = np.rint(cells["y [m]"] / h - 0.5).astype(int)
    nx, ny = i.max() + 1, j.max() + 1
    if len(i) != nx * ny:
        fail(folder, "the prototype handles a full rectangular plate of agents only")
    def grid(v):
        out = np.full((nx, ny), np.nan); out[i, j] = v; return out
    load = case["load"][0]
    if load["direction"] not in ("-y", "+y"):
        fail(folder, "the prototype handles a load along y on the top face only")
    along = [l for l in lines if l["kind"] == "along"][0]
    mat = case["material"]
    E, nu = float(mat["young"]), float(mat["poisson"])
    strain = case.get("fem", {}).get("model", "plane_stress") == "plane_strain"
    lw = case["mesh"].get("parameters", {}).get("lw", 2 * h)
    g = dict(nx=nx, ny=ny, h=h, x0=along["from"][0], lw=lw, thick=float(mat.get("thickness", 1.0)), E=E, nu=nu,
             strain=strain, E_eff=E / (1 - nu ** 2) if strain else E, nu_eff=nu / (1 - nu) if strain else nu,
             # signed along the march into the body (-y from the top face): a pull is negative
             force=float(load["force"]) * (1.0 if load["direction"] == "-y" else -1.0),
             far_distance=summary["far_distance"])
    fem = dict(sx=grid(femc["sigma_x [Pa]"]), sy=grid(femc["sigma_y [Pa]"]), tau=grid(femc["tau_xy [Pa]"]),
               vm=grid(femc["von_mises [Pa]"]))
    cur = dict(sx=grid(cells["agent_sigma_x [Pa]"]), sy=grid(cells["agent_sigma_y [Pa]"]))
    cur["tau"] = 0 * cur["sx"]
    cur["vm"] = von_mises(cur["sx"], cur["sy"], cur["tau"], nu, strain)
    far = grid(cells["far"]) > 0.5
    ni, nj = nodes["i"].astype(int), nodes["j"].astype(int)
    def ngrid(a, b):
        out = np.full((nx + 1, ny + 1, 2), np.nan); out[ni, nj, 0] = a; out[ni, nj, 1] = b; return out
    fem["u"] = ngrid(nodes["fem_u_x [m]"], nodes["fem_u_y [m]"])
    cur["u"] = ngrid(nodes["agent_u_x [m]"], nodes["agent_u_y [m]"])
    # Far nodes: as compare: at least far_distance from the loaded face (top, x0 +- lw/2).
    XN, YN = np.meshgrid(np.arange(nx + 1) * h, np.arange(ny + 1) * h, indexing="ij")
    x1, x2 = g["x0"] - lw / 2, g["x0"] + lw / 2
    g["far_nodes"] = np.hypot(np.clip(XN, x1, x2) - XN, ny * h - YN) >= g["far_distance"] * (1 - 1e-9)
    g["far"] = far
    return g, fem, cur


def scores(g, m, fem):
    def rel(a, b, mask):
        return float(np.linalg.norm((a - b)[mask]) / np.linalg.norm(b[mask]))
    body = np.ones_like(g["far"])
    r = {f: (rel(m[f], fem[f], g["far"]), rel(m[f], fem[f], body)) for f in ("sx", "sy", "tau", "vm")}
    fn = np.repeat(g["far_nodes"][..., None], 2, 2)
    r["u"] = (rel(m["u"], fem["u"], fn), rel(m["u"], fem["u"], np.ones_like(fn)))
    jj = np.arange(g["ny"] + 1) * g["h"] > 0.1 * g["ny"] * g["h"]
    side = np.concatenate([np.sign(m["u"][e, jj, 0]) == np.sign(fem["u"][e, jj, 0]) for e in (0, -1)])
    r["ux_sign"] = float(np.mean(side))
    # the same where FEM's u_x is at least 5 % of its largest on the side edges (away from its sign changes)
    big = np.concatenate([np.abs(fem["u"][e, jj, 0]) >= 0.05 * np.abs(fem["u"][[0, -1]][:, jj, 0]).max() for e in (0, -1)])
    r["ux_sign_5"] = float(np.mean(side[big]))
    return r


def evaluate(folder, k):
    g, fem, cur = load_folder(folder)
    out = {"current": scores(g, cur, fem)}
    for name, (sx, sy, tau) in (("recovery", recovery_rule(g, cur["sy"], k)), ("turning", turning_rule(g, k)),
                                ("march", turning_rule(g, k, march=True)),
                                ("mirror", turning_rule(g, dict(k, mirror=True)))):
        m = dict(sx=sx, sy=sy, tau=tau, vm=von_mises(sx, sy, tau, g["nu"], g["strain"]))
        m["u"] = displacement(sx, sy, tau, g)
        out[name] = scores(g, m, fem)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folders", nargs="+")
    for key, val in DEFAULTS.items():
        ap.add_argument("--" + key.replace("_", "-"), type=type(val), default=val)
    args = ap.parse_args()
    k = {key: getattr(args, key) for key in DEFAULTS}
    results = [(folder, evaluate(folder, k)) for folder in args.folders]  # every folder read before printing
    for folder, res in results:
        for model, r in res.items():
            if not all(np.isfinite(v).all() for v in r.values()):
                fail(folder, f"a non-finite error for the {model} model")
    print("relative L2 against FEM, far field / body (zero model: 1.000); ux_sign: share of side-edge nodes "
          "above the lowest tenth with FEM's sign of u_x")
    print("%-16s %-9s %-13s %-13s %-13s %-13s %-13s %s" % ("case", "model", "sigma_x", "sigma_y", "tau_xy",
                                                            "von_Mises", "displacement", "ux_sign (>= 5 %)"))
    for folder, res in results:
        for model, r in res.items():
            print("%-16s %-9s %s  %.2f (%.2f)" % (os.path.basename(os.path.normpath(folder)), model,
                                                 " ".join("%.3f / %.3f" % r[f] for f in ("sx", "sy", "tau", "vm", "u")),
                                                 r["ux_sign"], r["ux_sign_5"]))


if __name__ == "__main__":
    main()
