"""Issue 40 near-side prototype: a comparison's cells.csv as grids, the tie scan (the C++ one), far rel. L2."""
import csv, json, math, os
import numpy as np

def read(run):
    rows = list(csv.DictReader(open(os.path.join(run, 'cells.csv'))))
    x = np.array([float(r['x [m]']) for r in rows]); y = np.array([float(r['y [m]']) for r in rows])
    h = np.min(np.diff(np.unique(x)))
    i = np.round((x - x.min()) / h).astype(int); j = np.round((y - y.min()) / h).astype(int)
    nx, ny = i.max() + 1, j.max() + 1
    out = {'h': h, 'x': np.zeros((ny, nx)), 'y': np.zeros((ny, nx))}
    out['x'][j, i] = x; out['y'][j, i] = y
    for k in rows[0]:
        if k.startswith('agent_') or k.startswith('fem_') or k == 'far':
            a = np.zeros((ny, nx)); a[j, i] = [float(r[k]) for r in rows]
            out[k.split(' ')[0]] = a
    return out

def rel_l2(a, f, far):
    m = far > 0
    return math.sqrt(np.sum((a[m] - f[m]) ** 2) / np.sum(f[m] ** 2))

def fit_weights(j, count, window, reach):
    first = max(0, j - reach); last = min(count - 1, j + reach)
    d = np.arange(first, last + 1) - j
    w = np.exp(-0.5 * (d / window) ** 2)
    P = np.stack([np.ones_like(d), d, d * d], 1).astype(float)
    M = (P * w[:, None]).T @ P
    if np.linalg.matrix_rank(M) < 3:
        c = np.zeros(last - first + 1); lo = max(0, j - 1); hi = min(count - 1, j + 1)
        c[lo - first] -= 1.0 / (hi - lo); c[hi - first] += 1.0 / (hi - lo); return first, c
    row = np.linalg.inv(M)[1]
    return first, w * (row[0] + row[1] * d + row[2] * d * d)

def d_dy(field, h, window=1.0):
    """Slope along y (axis 0) of a least-squares quadratic with Gaussian weights (the C++ fitted_slope)."""
    ny = field.shape[0]; reach = max(1, int(math.ceil(4 * window)))
    out = np.zeros_like(field)
    for j in range(ny):
        first, c = fit_weights(j, ny, window, reach)
        out[j] = c @ field[first:first + len(c)] / h
    return out

def tie(tau, h, window=1.0):
    """sigma_x by horizontal equilibrium scanned from x = 0 (each row a run), the rest taken out linearly."""
    dt = d_dy(tau, h, window)
    ny, nx = tau.shape
    faces = np.zeros((ny, nx + 1))
    faces[:, 1:] = -h * np.cumsum(dt, axis=1)
    rest = faces[:, -1:]
    faces -= rest * np.arange(nx + 1)[None, :] / nx
    return 0.5 * (faces[:, :-1] + faces[:, 1:])

def summary_metrics(run):
    m = json.load(open(os.path.join(run, 'summary.json')))['metrics']
    return {c: m[f'far.{c}.rel_l2']['value'] for c in ['sigma_x', 'sigma_y', 'tau_xy', 'von_mises']}
