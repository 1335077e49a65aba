#!/usr/bin/python3
"""The shear of a hole (issue 23, plate_hole's tau_xy): candidate rules against FEM's tau_xy, from a 2D
`workbench compare` folder of a plate pulled along x past an enclosed hole (cells.csv: fem_tau_xy,
agent_tau_xy per agent). docs/agent-model.md, "Holes and notches (2D)".

    /usr/bin/python3 bench/research/hole_shear.py OUT_DIR [P_N]

P_N: the pull [N] (default 2). Far-field relative L2 of tau_xy for
- detour: each lateral line's force (P / rows) moved to the hole's nearer edge where it lies over air (the
  C++ paths), its shift a slope F dshift/dx / A, deposited as the C++ deposits force (Gaussian, sd
  sqrt(D depth), mirrored at the run's ends); 'taper': the shift started ahead of the hole and ended
  behind it (Gaussian in x of length k x the hole's half width);
- streamlines: every path a streamline of the potential flow past the circle of the hole's area;
- Kirsch: the shear of a circular hole of the same area in an infinite plate, the remote stress the
  row's force over its full width (what agent/src/stress_components.cc hole_shear adds).
Each alone and added to the agents' tau_xy of the folder (its packets', balance's and layer's)."""
import csv
import sys

import numpy as np
from scipy.special import erf


def load(folder):
    rows = list(csv.DictReader(open(folder + "/cells.csv")))
    x = np.array([float(r["x [m]"]) for r in rows]); y = np.array([float(r["y [m]"]) for r in rows])
    h = np.min(np.diff(np.unique(x)))
    i, j = np.round(x / h - 0.5).astype(int), np.round(y / h - 0.5).astype(int)
    nx, ny = i.max() + 1, j.max() + 1
    body = np.zeros((nx, ny), bool); body[i, j] = True
    grid = lambda k: np.where(body, 0.0, np.nan) + np.bincount(i * ny + j, [float(r[k] or 0) for r in rows], nx * ny).reshape(nx, ny)
    far = np.zeros((nx, ny), bool); far[i, j] = [r["far"] == "1" for r in rows]
    return h, body, far & body, grid("fem_tau_xy [Pa]"), grid("agent_tau_xy [Pa]")


def runs(col):
    out, j = [], 0
    while j < len(col):
        if col[j]:
            k = j
            while k + 1 < len(col) and col[k + 1]:
                k += 1
            out.append((j, k)); j = k + 1
        else:
            j += 1
    return out


def deposit(body, i, yc, sd, h):
    """A unit force about yc in column i (the C++ deposit: over the run it lies in, mirrored at its ends)."""
    ny = body.shape[1]
    jj = min(max(int(yc / h), 0), ny - 1)
    if not body[i, jj]:
        jj = min((abs(j - jj), j) for j in range(ny) if body[i, j])[1]
    lo, hi = [r for r in runs(body[i]) if r[0] <= jj <= r[1]][0]
    e = np.arange(lo, hi + 2) * h; elo, ehi = lo * h, (hi + 1) * h
    c0 = min(max(yc, elo), ehi)
    s = sum(np.diff(0.5 * (1 + erf((e - c) / (np.sqrt(2) * sd)))) for c in (c0, 2 * elo - c0, 2 * ehi - c0))
    out = np.zeros(ny); out[lo:hi + 1] = s / s.sum()
    return out


def detour(body, h, P, thick, D=0.002, taper=None):
    nx, ny = body.shape
    A, F = h * thick, P / ny
    ys, xs = (np.arange(ny) + 0.5) * h, (np.arange(nx) + 0.5) * h
    shift, half = np.zeros((nx, ny)), np.zeros((nx, ny))
    for i in range(nx):
        for p, y in enumerate(ys):
            jj = int(y / h)
            if body[i, jj]:
                continue
            j = min((abs(j - jj), j) for j in range(ny) if body[i, j])[1]
            lo, hi = [r for r in runs(body[i]) if r[0] <= j <= r[1]][0]
            shift[i, p] = min(max(y, lo * h), (hi + 1) * h) - y
            a = b = jj
            while a > 0 and not body[i, a - 1]: a -= 1
            while b < ny - 1 and not body[i, b + 1]: b += 1
            half[i, p] = 0.5 * (b - a + 1) * h
    if taper is not None:  # the largest tapered shift of the hole's rows
        eff = np.zeros_like(shift)
        for p in range(ny):
            for r in np.nonzero(shift[:, p])[0]:
                v = shift[r, p] * np.exp(-0.5 * ((xs - xs[r]) / (taper * half[r, p])) ** 2)
                eff[:, p] = np.where(np.abs(v) > np.abs(eff[:, p]), v, eff[:, p])
        shift = eff
    slope = np.gradient(shift, h, axis=0)  # tension: tau = sigma dy/dx
    tau = np.zeros((nx, ny))
    for i in range(nx):
        sd = max(np.sqrt(D * (nx - 1 - i + 0.5) * h), 0.3 * h)
        for p, y in enumerate(ys):
            if slope[i, p] != 0:
                tau[i] += F * slope[i, p] * deposit(body, i, y + shift[i, p], sd, h) / A
    return tau


def hole_of(body, h):
    air = ~body
    X, Y = np.meshgrid((np.arange(body.shape[0]) + 0.5) * h, (np.arange(body.shape[1]) + 0.5) * h, indexing="ij")
    area = air.sum() * h * h
    return X[air].mean(), Y[air].mean(), np.sqrt(area / np.pi), X, Y


def streamlines(body, h, P, thick, D=0.002, sub=4):
    from scipy.optimize import brentq
    nx, ny = body.shape
    xc, yc, R, _, _ = hole_of(body, h)
    A, F = h * thick, P / (ny * sub)
    xs = (np.arange(nx) + 0.5) * h
    tau = np.zeros((nx, ny))
    for y0 in (np.arange(ny * sub) + 0.5) * h / sub:
        def y_of(x):
            b = abs(y0 - yc)
            if b == 0:
                return yc
            f = lambda y: y * (1 - R * R / ((x - xc) ** 2 + y * y)) - b
            return yc + np.sign(y0 - yc) * brentq(f, max(b, np.sqrt(max(R * R - (x - xc) ** 2, 0)) + 1e-12), b + R + 1)
        yy = np.array([y_of(x) for x in xs])
        slope = np.gradient(yy, h)
        for i in range(nx):
            tau[i] += F * slope[i] * deposit(body, i, yy[i], max(np.sqrt(D * (nx - 1 - i + 0.5) * h), 0.3 * h), h) / A
    return tau


def kirsch(body, h, P, thick):
    xc, yc, a, X, Y = hole_of(body, h)
    s = P / (body.shape[1] * h * thick)
    dx, dy = X - xc, Y - yc
    r = np.maximum(np.hypot(dx, dy), a); th = np.arctan2(dy, dx)
    q2, q4, c2, s2 = (a / r) ** 2, (a / r) ** 4, np.cos(2 * th), np.sin(2 * th)
    srr = s / 2 * (1 - q2) + s / 2 * (1 - 4 * q2 + 3 * q4) * c2
    stt = s / 2 * (1 + q2) - s / 2 * (1 + 3 * q4) * c2
    srt = -s / 2 * (1 + 2 * q2 - 3 * q4) * s2
    return (srr - stt) * np.sin(th) * np.cos(th) + srt * np.cos(2 * th)


def main():
    if len(sys.argv) < 2:
        print("usage: hole_shear.py OUT_DIR [P_N]", file=sys.stderr)
        sys.exit(2)
    P = float(sys.argv[2]) if len(sys.argv) > 2 else 2.0
    h, body, far, fem, agent = load(sys.argv[1])
    err = lambda t: np.sqrt(np.sum((t[far] - fem[far]) ** 2) / np.sum(fem[far] ** 2))
    print("| rule | tau_xy alone | + the agents' tau_xy |\n|---|---|---|")
    print("| zero / the agents now | 1.000 | %.3f |" % err(agent))
    for name, t in [("detour in the hole's rows", detour(body, h, P, 0.002)),
                    ("detour tapered, 1.5 half widths", detour(body, h, P, 0.002, taper=1.5)),
                    ("potential-flow streamlines", streamlines(body, h, P, 0.002)),
                    ("Kirsch (the C++ rule)", kirsch(body, h, P, 0.002))]:
        print("| %s | %.3f | %.3f |" % (name, err(t), err(t + np.nan_to_num(agent))), flush=True)


if __name__ == "__main__":
    main()
