"""The L-bracket's root section: the columns' 45-degree spread against a Flamant-weighted section
(the prototype of the columns' Flamant's fan, agent/src/columns.cc `flamant_fan`; issue 40's 2D
cantilever target; docs/agent-model.md, "Flamant's fan"). Run it on folders of the build before the
fan (c48ad7d): it reads the 45-degree rule's fields back.

Usage: /usr/bin/python3 bench/research/stubby/flamant_section.py CMP_DIR [CMP_DIR ...]
each CMP_DIR a `workbench compare` folder of a 2D L-bracket clamped at x = 0 (meshes/l_bracket_side.geo,
the columns rule set under auto). Prints, per folder, the far-field rel. L2 against FEM of sigma_x,
sigma_y, tau_xy and von Mises for each section and shear, and the plane sections' tip deflection.

The rules (nothing fitted; h and the foot's depth read from the cells):
- per column i the moment M_i and the shear V_i are the built rule's (read back from its agent_sigma_x
  and agent_tau_xy: the statics are the same for every section);
- the section: the foot's rows (y < A, the corner block below the foot's top) count whole; an agent
  of the arm at a height eta above the foot's top counts with a weight w(eta):
    '45'      w = 1 for eta <= d, else 0 (the built rule: the 45-degree spread),
    'flamant' w = d^4 / (d^2 + eta^2)^2: the foot's tension chord enters the arm at the re-entrant
              corner as a force along the arm's edge; Flamant's half-plane under a tangential point
              force has sigma_x = -2 P d^3 / (pi t (d^2 + eta^2)^2) on a section d ahead of it,
    'tri2', 'exp': a linear fall to 0 at 2 d, exp(-eta / d) (tried beside it);
  d = the column's distance from the corner plane x = A to its clamp-side face (the 45-degree
  spread's height there). Navier over the weighted section: sigma_x = w M (y - c) / I, c and I weighted;
- the shear: 'jour' Jourawski over the weighted section (b = w t), 'equil' the equilibrium of the
  part of each column above a level with its neighbours' (d tau / dy = -d sigma_x / dx in columns:
  tau at the face between columns i and i + 1 = (S_{i+1}(y) - S_i(y)) / (h t), S the force of
  sigma_x above y; a cell the mean of its faces). On a prismatic part 'equil' is Jourawski (to the
  within-agent profile); over a widening section it holds the tapered beam's shear, which changes
  sign across the corner block as FEM's does. It integrates to V exactly (N = 0).
- sigma_y is the built rule's (its clamp's layer would follow the new sigma_x; not redone here).
"""
import csv
import sys

import numpy as np


def read(path):
    rows = list(csv.DictReader(open(path)))
    return {k.split(' ')[0]: np.array([float(r[k]) if r[k] != '' else np.nan for r in rows]) for k in rows[0]}


def gridded(folder):
    """The cells of a comparison folder on the agents' grid: (fields[name][ix, iy], h)."""
    cells = read(folder + '/cells.csv')
    h = np.min(np.diff(np.unique(np.round(cells['x'], 9))))
    ix = np.round(cells['x'] / h - 0.5).astype(int)
    iy = np.round(cells['y'] / h - 0.5).astype(int)
    out = {}
    for k, v in cells.items():
        g = np.full((ix.max() + 1, iy.max() + 1), np.nan)
        g[ix, iy] = v
        out[k] = g
    out['solid'] = ~np.isnan(out['fem_sigma_x'])
    return out, h


WEIGHTS = {
    '45': lambda eta, d: (eta <= d + 1e-12).astype(float),
    'flamant': lambda eta, d: 1 / (1 + (eta / d) ** 2) ** 2,
    'tri2': lambda eta, d: np.clip(1 - eta / (2 * d), 0, 1),
    'exp': lambda eta, d: np.exp(-eta / d),
}


def weights(kind, solid, h):
    nx, ny = solid.shape
    y = (np.arange(ny) + 0.5) * h
    foot = int(solid[-1].sum())  # the foot's rows: the last column is the foot's end
    eta = np.where(y > foot * h, y - foot * h, 0.0)
    w = np.zeros(solid.shape)
    for i in range(nx):
        d = max(0.0, foot * h - (i + 1) * h) + h
        w[i] = np.where(y < foot * h, 1.0, WEIGHTS[kind](eta, d)) * solid[i]
    return w


def navier(M, w, h, t):
    y = (np.arange(w.shape[1]) + 0.5) * h
    area = (w * h * t).sum(1)
    c = (w * y).sum(1) * h * t / area
    inertia = (w * ((y - c[:, None]) ** 2 * h + h ** 3 / 12) * t).sum(1)
    return w * M[:, None] * (y - c[:, None]) / inertia[:, None], area, inertia


def above(sig, h, t):
    """S at each level's bottom face: the force of sigma_x above it, per column."""
    S = np.zeros((sig.shape[0], sig.shape[1] + 1))
    S[:, :-1] = np.cumsum(sig[:, ::-1], axis=1)[:, ::-1] * h * t
    return S


def jourawski(sig, V, M, w, h, t):
    S = above(sig, h, t)
    Sc = 0.5 * (S[:, :-1] + S[:, 1:])
    with np.errstate(all='ignore'):
        return np.nan_to_num(np.where(w > 1e-3, (V / M)[:, None] * Sc / (w * t), 0.0))


def equilibrium_shear(sig, h, t):
    S = above(sig, h, t)
    T = (S[1:] - S[:-1]) / (h * t)
    Tc = 0.5 * (T[:, :-1] + T[:, 1:])
    out = np.zeros(sig.shape)
    out[:-1] += Tc
    out[1:] += Tc
    count = np.full(sig.shape[0], 2.0)
    count[[0, -1]] = 1
    return out / count[:, None]


def von_mises(sx, sy, txy):
    return np.sqrt(sx * sx + sy * sy - sx * sy + 3 * txy * txy)


def scores(G, sx, sy, txy):
    far = (G['far'] > 0) & G['solid']
    ours = {'sigma_x': sx, 'sigma_y': sy, 'tau_xy': txy, 'von_mises': von_mises(sx, sy, txy)}
    return ' '.join(f"{k} {np.linalg.norm((v - G['fem_' + k])[far]) / np.linalg.norm(G['fem_' + k][far]):.3f}"
                    for k, v in ours.items())


def tip_deflection(M, V, area, inertia, h, E=206e9, nu=0.3):
    """The plane sections' march from the clamp (Euler-Bernoulli + shear on 5/6 of the area)."""
    G = E / (2 * (1 + nu))
    theta = w = 0.0
    for i in range(len(M)):
        theta_next = theta - M[i] / (E * inertia[i]) * h
        w += 0.5 * (theta + theta_next) * h + V[i] / (G * area[i] * 5 / 6) * h
        theta = theta_next
    return w


def main(folders):
    t = 1.0  # the thickness cancels out of every stress here
    for folder in folders:
        G, h = gridded(folder)
        sx, sy, tx = [np.nan_to_num(G['agent_' + k]) for k in ('sigma_x', 'sigma_y', 'tau_xy')]
        y = (np.arange(sx.shape[1]) + 0.5) * h
        M = (sx * y).sum(1) * h * t  # N = 0: the moment about any level
        V = tx.sum(1) * h * t
        print(folder, 'built:', scores(G, sx, sy, tx))
        tips = {}
        for kind in WEIGHTS:
            w = weights(kind, G['solid'], h)
            s, area, inertia = navier(M, w, h, t)
            print(f'  {kind:8s} jour  ', scores(G, s, sy, jourawski(s, V, M, w, h, t)))
            print(f'  {kind:8s} equil ', scores(G, s, sy, equilibrium_shear(s, h, t)))
            tips[kind] = tip_deflection(M, V, area, inertia, h)
        print('  tip deflection flamant / 45:', f"{tips['flamant'] / tips['45']:.3f}")


if __name__ == '__main__':
    main(sys.argv[1:])
