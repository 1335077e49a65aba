#!/usr/bin/python3
"""Bending by columns (research prototype) on a comparison output of a beam on supports at its bottom
(cases/notched_beam.toml): the load goes to the supports by statics (reactions from the balance of forces
and moments), each column of agents carries the section resultants V, M passed column to column from the
ends, distributes M linearly over its own agents (Navier about the column's centroid) and V by a scan down
the column (Jourawski); the deflection is the agents' curvature and shear strain marched along the beam
from the left support, its rigid rotation set by the right support. Prints the errors against FEM.

    /usr/bin/python3 bench/research/beam_columns.py OUT_DIR  [--support-mm 10] [--patch-mm 12]"""
import argparse, csv, json, os, sys
import numpy as np


def read(p):
    rows = list(csv.reader(open(p)))
    return {k: np.array([float(r[i]) if r[i] else np.nan for r in rows[1:]]) for i, k in enumerate(rows[0])}


ap = argparse.ArgumentParser()
ap.add_argument("folder"); ap.add_argument("--pinned", action="store_true", help="supports free to slide (no thrust)"); ap.add_argument("--support-mm", type=float, default=10); ap.add_argument("--patch-mm", type=float, default=12)
args = ap.parse_args()
s = json.load(open(os.path.join(args.folder, "summary.json")))
c = read(os.path.join(args.folder, "cells.csv")); f = read(os.path.join(args.folder, "fem", "fem_cells.csv"))
nd = read(os.path.join(args.folder, "nodes.csv"))
h = s["agent"]["agent_size"]; P = -s["agent"]["applied"]     # downward
E, nu, t = 206e9, 0.3, 0.002
i = np.rint(c["x [m]"] / h - 0.5).astype(int); j = np.rint(c["y [m]"] / h - 0.5).astype(int)
nx, ny = i.max() + 1, j.max() + 1
present = np.zeros((nx, ny), bool); present[i, j] = True
L = nx * h
xc = (np.arange(nx) + 0.5) * h
# Statics: supports' centres at support_mm / 2 from each end, the load at mid-span.
a, b = args.support_mm * 1e-3 / 2, L - args.support_mm * 1e-3 / 2
xl = L / 2
R1 = -P * (b - xl) / (b - a); R2 = -P - R1
V = np.where(xc < a, 0, R1) + np.where(xc > xl, P, 0) + np.where(xc > b, R2, 0)
M = R1 * np.clip(xc - a, 0, None) + P * np.clip(xc - xl, 0, None) + R2 * np.clip(xc - b, 0, None)
sx = np.zeros((nx, ny)); tau = np.zeros((nx, ny))
y = (np.arange(ny) + 0.5) * h
for k in range(nx):
    m = present[k]
    yc = y[m].mean()
    I = t * (np.sum(h * (y[m] - yc) ** 2) + m.sum() * h ** 3 / 12)
    sx[k, m] = -M[k] * (y[m] - yc) / I
    # first moment of the agents above each level (scan down the column from its top)
    q = np.cumsum((t * h * (y - yc) * m)[::-1])[::-1] - 0.5 * t * h * (y - yc) * m
    tau[k, m] = -V[k] * q[m] / (I * t)
# Supports that hold the bottom face (FEM's rigid groups hold u_x too): the beam's bottom fibre cannot lengthen
# between them, so they pull it back with a thrust H at y = 0 (one unknown: compatibility over the span, two scans).
A_k = np.array([t * h * present[k].sum() for k in range(nx)])
e_k = np.array([y[present[k]].mean() for k in range(nx)])
I_k = np.array([t * (np.sum(h * (y[present[k]] - e_k[k]) ** 2) + present[k].sum() * h ** 3 / 12) for k in range(nx)])
span = (xc > a) & (xc < b)
H = 0.0 if args.pinned else np.sum((M * e_k / I_k)[span]) / np.sum((1 / A_k + e_k ** 2 / I_k)[span])
for k in np.nonzero(span)[0]:
    m = present[k]
    sx[k, m] += -H / A_k[k] + H * e_k[k] * (y[m] - e_k[k]) / I_k[k]
M_eff = M - np.where(span, H * e_k, 0.0)     # the thrust's moment about each centroid
print("thrust H = %.3f N" % H)
# Deflection of the centroid line: curvature M/EI and shear V/(G A) marched from the left support.
G = E / (2 * (1 + nu))
EI = np.array([E * t * (np.sum(h * (y[present[k]] - y[present[k]].mean()) ** 2) + present[k].sum() * h ** 3 / 12) for k in range(nx)])
GA = np.array([G * t * h * present[k].sum() * 5 / 6 for k in range(nx)])
xn = np.arange(nx + 1) * h
rot = np.concatenate([[0], np.cumsum(M_eff / EI * h)])                   # slope change from bending, at nodes
w = np.concatenate([[0], np.cumsum(0.5 * (rot[1:] + rot[:-1]) * h)]) + np.concatenate([[0], -np.cumsum(V / GA * h)])  # shear: down where V > 0 (reaction up)
w -= np.interp(a, xn, w) + (np.interp(b, xn, w) - np.interp(a, xn, w)) * (xn - a) / (b - a)
fem_uy = {}
for ii, uy in zip(nd["i"].astype(int), nd["fem_u_y [m]"]):
    fem_uy.setdefault(ii, []).append(uy)
fem_mid = np.array([np.mean(fem_uy[k]) for k in range(nx + 1)])
sxf = np.full((nx, ny), np.nan); sxf[i, j] = f["sigma_x [Pa]"]
tf = np.full((nx, ny), np.nan); tf[i, j] = f["tau_xy [Pa]"]
syf = np.full((nx, ny), np.nan); syf[i, j] = f["sigma_y [Pa]"]
far = np.zeros((nx, ny), bool); far[i, j] = c["far"] > 0.5
rel = lambda m, r, k: np.linalg.norm((m - r)[k]) / np.linalg.norm(r[k])
vm = np.sqrt(sx ** 2 + 3 * tau ** 2); vmf = np.full((nx, ny), np.nan); vmf[i, j] = f["von_mises [Pa]"]
print("reaction: columns %.4f + %.4f N = %.4f N (load %.4f N); C++ directional: %.4f N reaches a rigid face"
      % (R1, R2, R1 + R2, -P, s["agent"]["rigid_reaction"]))
print("sigma_x far %.3f body %.3f | tau_xy far %.3f body %.3f | sigma_y (0) 1.000 | von Mises far %.3f body %.3f"
      % (rel(sx, sxf, far), rel(sx, sxf, present), rel(tau, tf, far), rel(tau, tf, present), rel(vm, vmf, far), rel(vm, vmf, present)))
k = nx // 2
print("mid-span deflection (mean over the column's nodes): columns %.3e m, FEM %.3e m, ratio %.3f; "
      "deflection line rel L2 %.3f" % (w[k], fem_mid[k], w[k] / fem_mid[k], np.linalg.norm(w - fem_mid) / np.linalg.norm(fem_mid)))
if os.environ.get("SHOW_COLUMN"):
    np.set_printoptions(precision=0, suppress=True, linewidth=200)
    kcol = int(os.environ["SHOW_COLUMN"])
    print("column", kcol, "tau FEM", tf[kcol]); print("tau columns", tau[kcol])
    print("sx FEM", sxf[kcol]); print("sx columns", sx[kcol]); print("sy FEM", syf[kcol])
