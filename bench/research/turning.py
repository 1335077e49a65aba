"""Turning packets (research prototype): the directional fan, but each packet turns toward the lateral
position where it belongs once the load fills the width (its quantile of the fan), instead of being mirrored
by the free sides. Continuous form (no packet splitting): diffusion as a Gaussian of variance D * depth."""
import numpy as np
from scipy.special import erf


def cell_weights(xk, sig, nx, h):
    """Share of a Gaussian (centre xk [m], sd sig [m]) in each agent column, mirrored at both free sides."""
    edges = np.arange(nx + 1) * h
    W = nx * h
    out = np.zeros((len(xk), nx))
    for img, sgn in ((0, 1), (0, -1), (2 * W, -1), (-2 * W, -1)):
        c = img + sgn * xk
        cdf = 0.5 * (1 + erf((edges[None, :] - c[:, None]) / (np.sqrt(2) * sig[:, None])))
        out += np.diff(cdf, axis=1)
    return out


def turning_plate(nx, ny, h, load_cells, P, thick=0.002, directions=32, fan_angle=66.1, fan_power=2.59,
                  diffusion=2.0, turn=1.0, moment_balance=True, target="split"):
    n = directions
    ang = np.radians(fan_angle) * ((2 * np.arange(n) + 1) / n - 1)
    s0, w = np.tan(ang), np.cos(ang) ** fan_power
    w /= w.sum()
    A = h * thick
    W = nx * h
    q = np.cumsum(w) - w / 2                 # quantile of each packet in the fan
    sy = np.zeros((nx, ny)); txy = np.zeros((nx, ny)); sxr = np.zeros((nx, ny)); dl = np.zeros((nx, ny))
    dtau = np.zeros((nx, ny))
    for c in load_cells:
        F0 = P / len(load_cells)
        x0 = (c + 0.5) * h
        # Where each packet belongs once the load fills the width: the fan's quantiles, the half of the fan on
        # each side of the load spread over the width on that side (the row's moment balance does the rest).
        xf = np.where(s0 < 0, x0 * q / 0.5, x0 + (W - x0) * (q - 0.5) / 0.5) if target == "split" else q * W
        L = xf - x0
        L = np.where(s0 * L > 0, L, np.sign(s0) * 1e-9)
        for j in range(ny - 1, -1, -1):
            d = (ny - 1 - j + 0.5) * h              # depth of the row's centre below the loaded face
            arg = s0 * d / L * turn
            x = x0 + L * np.tanh(arg) / turn
            slope = s0 / np.cosh(arg) ** 2
            sig = np.full(n, np.sqrt(max(diffusion * 1e-3 * d, (0.3 * h) ** 2)))
            cw = cell_weights(x, sig, nx, h) * (F0 * w)[:, None]   # (n, nx) force per agent column
            f = cw.sum(0)
            sy[:, j] -= f / A
            txy[:, j] += (cw * slope[:, None]).sum(0) / A
            sxr[:, j] -= (cw * slope[:, None] ** 2).sum(0) / A
            if moment_balance:
                xs = (np.arange(nx) + 0.5) * h
                mu = np.sum(f * (xs - x0)); cu = xs.mean(); suu = np.sum((xs - cu) ** 2)
                delta = -mu / suu * (xs - cu)
                sy[:, j] -= delta / A; dl[:, j] -= delta / A
    return dict(sy=sy, txy_ray=txy, sx_ray=sxr, sy_delta=dl)
