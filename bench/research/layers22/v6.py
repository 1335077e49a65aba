import sys, numpy as np
import os
DATA = os.environ.get("LAYERS_DATA", ".")  # the folders of the README's commands
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import layers as L, v3, v5
from v5 import run
def fit_weights(count, w):
    reach = max(1, int(np.ceil(4 * w)))
    W = np.zeros((count, count))
    for j in range(count):
        lo, hi = max(0, j - reach), min(count - 1, j + reach)
        d = np.arange(lo, hi + 1) - j; wt = np.exp(-0.5 * (d / w) ** 2)
        P = np.stack([np.ones_like(d), d, d * d], 1).astype(float)
        M = (P * wt[:, None]).T @ P
        if np.linalg.matrix_rank(M) < 3:
            a, b = max(0, j - 1), min(count - 1, j + 1); W[j, a] -= 1 / (b - a); W[j, b] += 1 / (b - a); continue
        row = np.linalg.inv(M)[1]
        W[j, lo:hi + 1] = wt * (P @ row)
    return W
WIN = float(sys.argv[1])
def dy(t, h, top):
    W = fit_weights(t.shape[1], WIN / h)
    return np.einsum("jk,ikl->ijl", W, t) / h
v5.dy = dy
for n, h in [("b_x0.006", .002), ("b_x0.020", .002), ("held", .002), ("dblock", .004)]:
    run(n, h, f"win{WIN}", lambda j, h: 0.0, 1)
