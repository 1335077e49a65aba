#!/usr/bin/python3
"""3D form of the turning rule (research prototype) on a comparison output of a block on a rigid base
loaded on a patch of its top face (cases/block3d.toml with the directional rule set):

    /usr/bin/python3 bench/research/turning3d.py OUT_DIR [OUT_DIR ...]

The 3D fan is the product of one fan per lateral axis (weights cos^p per axis, p = fan_power_3d); each
packet gets a target and a tanh path per axis, is deposited as a product of two Gaussians, carries the
shears tau_xy = sum F s_x / A and tau_zy = sum F s_z / A; sigma_x and sigma_z come from horizontal
equilibrium scanned along x and z (tau_xz taken as 0) plus the bonded base layer (eps_x = eps_z = 0 there).
Prints the errors against FEM, far field / body, beside the C++ agents' (no shear)."""
import sys, os, json, csv
import numpy as np
from agent_stress_prototype import fan, column_shares, fit_d1, scan_sigma_x, spread_width

K = dict(directions=32, fan_angle=66.0, fan_power=3.99, diffusion_mm=2.0, base_layer=0.25, window_mm=5.0)


def read(p):
    rows = list(csv.reader(open(p)))
    return {k: np.array([float(r[i]) if r[i] else np.nan for r in rows[1:]]) for i, k in enumerate(rows[0])}


def targets(s0, w, x0, W):
    q = np.cumsum(w) - w / 2
    xf = np.where(s0 < 0, x0 * q / 0.5, x0 + (W - x0) * (q - 0.5) / 0.5)
    return np.where(s0 * (xf - x0) > 0, xf - x0, np.sign(s0) * 1e-12)


def run(folder, k=K):
    s = json.load(open(os.path.join(folder, "summary.json")))
    c = read(os.path.join(folder, "cells.csv")); f = read(os.path.join(folder, "fem", "fem_cells.csv"))
    a = read(os.path.join(folder, "agent", "agent_cells.csv"))
    lines = json.load(open(os.path.join(folder, "lines.json")))
    x0, _, z0 = [l for l in lines if l["kind"] == "along"][0]["from"]
    h = s["agent"]["agent_size"]; P = s["agent"]["applied"]; nu = 0.3; A = h * h
    ii = np.rint(c["x [m]"] / h - .5).astype(int); jj = np.rint(c["y [m]"] / h - .5).astype(int); kk = np.rint(c["z [m]"] / h - .5).astype(int)
    nx, ny, nz = ii.max() + 1, jj.max() + 1, kk.max() + 1
    def grid(v):
        o = np.full((nx, ny, nz), np.nan); o[ii, jj, kk] = v; return o
    s0, w = fan(k["directions"], k["fan_angle"], k["fan_power"])
    Lx, Lz = targets(s0, w, x0, nx * h), targets(s0, w, z0, nz * h)
    sy = np.zeros((nx, ny, nz)); txy = np.zeros_like(sy); tzy = np.zeros_like(sy); balx = np.zeros_like(sy); balz = np.zeros_like(sy)
    xs, zs = (np.arange(nx) + .5) * h, (np.arange(nz) + .5) * h
    for j in range(ny - 1, -1, -1):
        d = (ny - 1 - j + .5) * h
        px = x0 + Lx * np.tanh(s0 * d / Lx); sx_ = s0 / np.cosh(s0 * d / Lx) ** 2
        pz = z0 + Lz * np.tanh(s0 * d / Lz); sz_ = s0 / np.cosh(s0 * d / Lz) ** 2
        sig = np.full(len(s0), np.sqrt(max(k["diffusion_mm"] * 1e-3 * d, (0.3 * h) ** 2)))
        cx = column_shares(px, sig, nx, h) * w[:, None]           # (n, nx) per x-direction
        cz = column_shares(pz, sig, nz, h) * w[:, None]           # (n, nz)
        F = P * np.einsum("ai,bk->ik", cx, cz)
        txy[:, j] = P * np.einsum("ai,bk->ik", cx * sx_[:, None], cz) / A
        tzy[:, j] = P * np.einsum("ai,bk->ik", cx, cz * sz_[:, None]) / A
        # the row's moment balance in both lateral axes (a plane through the layer's agents)
        X, Z = np.meshgrid(xs - xs.mean(), zs - zs.mean(), indexing="ij")
        mu = np.sum(F * (X + xs.mean() - x0)); mv = np.sum(F * (Z + zs.mean() - z0))
        dx_, dz_ = -mu / np.sum(X * X) * X, -mv / np.sum(Z * Z) * Z
        sy[:, j] = -(F + dx_ + dz_) / A; balx[:, j] = -dx_ / A; balz[:, j] = -dz_ / A
    wr = k["window_mm"] * 1e-3 / h
    # the balance's shear: its x-part by vertical equilibrium scanned along x, its z-part along z
    from agent_stress_prototype import shear_from_sigma_y
    for kz in range(nz):
        txy[:, :, kz] += shear_from_sigma_y(balx[:, :, kz], h, wr)
    for kx in range(nx):
        tzy[kx] += shear_from_sigma_y(balz[kx].T, h, wr).T
    # horizontal equilibrium along x (per z slice) and along z (per x slice)
    sxx = np.zeros_like(sy); szz = np.zeros_like(sy)
    for kz in range(nz):
        d1, _ = fit_d1(txy[:, :, kz], wr); sxx[:, :, kz] = scan_sigma_x(d1 / h, h)
    for kx in range(nx):
        d1, _ = fit_d1(tzy[kx].T, wr); szz[kx] = scan_sigma_x(d1 / h, h).T
    # bonded base: eps_x = eps_z = 0 -> sigma_x = sigma_z = nu / (1 - nu) sigma_y, fading as in 2D
    Y = (np.arange(ny) + .5)[None, :, None] * h
    ell = k["base_layer"] * min(spread_width(sy[:, 0, :].sum(1), h), nx * h)
    ph = np.clip(1 - Y / ell, 0, None)
    ex = 1 - np.exp(-np.minimum(xs, nx * h - xs)[:, None, None] / Y)
    ez = 1 - np.exp(-np.minimum(zs, nz * h - zs)[None, None, :] / Y)
    sxb = nu / (1 - nu) * sy * ph * ex; szb = nu / (1 - nu) * sy * ph * ez
    def down(dv):
        return np.cumsum(dv[:, ::-1], 1)[:, ::-1] * h - 0.5 * dv * h
    txy_b = down(np.gradient(sxb, h, axis=0)); tzy_b = down(np.gradient(szb, h, axis=2))
    sx = sxx + sxb; sz = szz + szb; tx = txy + txy_b; tz = tzy + tzy_b
    vm = np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2) + 3 * (tx ** 2 + tz ** 2))
    fem = dict(sx=grid(f["sigma_x [Pa]"]), sy=grid(f["sigma_y [Pa]"]), sz=grid(f["sigma_z [Pa]"]),
               txy=grid(f["tau_xy [Pa]"]), tyz=grid(f["tau_yz [Pa]"]), vm=grid(f["von_mises [Pa]"]))
    cur = dict(sx=grid(a["sigma_x [Pa]"]), sy=grid(a["sigma_y [Pa]"]), sz=grid(a["sigma_z [Pa]"]))
    cur["vm"] = np.sqrt(0.5 * ((cur["sx"] - cur["sy"]) ** 2 + (cur["sy"] - cur["sz"]) ** 2 + (cur["sz"] - cur["sx"]) ** 2))
    far = grid(c["far"]) > .5; body = np.ones_like(far)
    rel = lambda m, r, msk: np.linalg.norm((m - r)[msk]) / np.linalg.norm(r[msk])
    mod = dict(sx=sx, sy=sy, sz=sz, txy=tx, tyz=tz, vm=vm)
    print(os.path.basename(os.path.normpath(folder)))
    for name, m in (("current", cur), ("turning", mod)):
        print("  %-8s" % name, " ".join("%s %.3f/%.3f" % (q, rel(m.get(q, 0 * sy), fem[q], far), rel(m.get(q, 0 * sy), fem[q], body))
                                       for q in ("sx", "sy", "sz", "txy", "tyz", "vm")))


if __name__ == "__main__":
    for folder in sys.argv[1:]:
        run(folder)
