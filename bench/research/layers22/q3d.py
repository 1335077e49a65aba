"""Quasi-3D: the layers' in-plane displacements coupled by interlayer shear G du/dy and held at the
bonded base; the agents' shears as given (their d/dy a body force), sigma_y's Poisson strain."""
import sys, numpy as np, scipy.sparse as sp, scipy.sparse.linalg as spl
import os
DATA = os.environ.get("LAYERS_DATA", ".")  # the folders of the README's commands
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import layers as L
from v2 import grid_fields, err
E, nu = 206e9, 0.3
def solve(f, h, couple=1.0, base=True):
    sy, txy, tyz = [np.nan_to_num(f[k]) for k in ("sy", "txy", "tyz")]
    mask = ~np.isnan(f["sy"])
    nx, ny, nz = sy.shape
    C, Bs, Ke, w = L.q1_layer(nx, nz, h, E, nu)
    Ke = Ke * h  # thickness h
    dtxy = np.gradient(txy, h, axis=1); dtyz = np.gradient(tyz, h, axis=1)
    nn = (nx + 1) * (nz + 1)
    node = lambda i, k: i * (nz + 1) + k
    rows, cols, vals = [], [], []; F = np.zeros(2 * nn * ny)
    G = E / (2 * (1 + nu))
    nodearea = np.zeros((ny, nn))
    for j in range(ny):
        for i, k in np.argwhere(mask[:, j, :]):
            ns = [node(i, k), node(i + 1, k), node(i + 1, k + 1), node(i, k + 1)]
            d = np.array([[2 * (j * nn + n), 2 * (j * nn + n) + 1] for n in ns]).ravel()
            e0 = np.array([-nu * sy[i, j, k] / E] * 2 + [0.0])
            fe = sum(B.T @ C @ e0 for B in Bs) * w * h
            fe[0::2] += dtxy[i, j, k] * h ** 3 / 4; fe[1::2] += dtyz[i, j, k] * h ** 3 / 4
            F[d] += fe
            r, c = np.meshgrid(d, d, indexing="ij"); rows.append(r.ravel()); cols.append(c.ravel()); vals.append(Ke.ravel())
            for n in ns: nodearea[j, n] += h * h / 4
    K = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(2 * nn * ny,) * 2)
    # interlayer shear springs: between layer j and j+1 at nodes both have, G / h * area; base: G / (h/2)
    ii, jj, vv = [], [], []
    for j in range(ny):
        for n in range(nn):
            a = nodearea[j, n]
            if a == 0: continue
            if j + 1 < ny and nodearea[j + 1, n] > 0:
                k = couple * G / h * min(a, nodearea[j + 1, n])
                for c in (0, 1):
                    p, q = 2 * (j * nn + n) + c, 2 * ((j + 1) * nn + n) + c
                    ii += [p, q, p, q]; jj += [p, q, q, p]; vv += [k, k, -k, -k]
            if j == 0 and base:
                k = couple * G / (h / 2) * a
                for c in (0, 1):
                    p = 2 * n + c; ii.append(p); jj.append(p); vv.append(k)
    K = K + sp.csr_matrix((vv, (ii, jj)), shape=K.shape)
    used = np.flatnonzero(np.abs(K.diagonal()) > 0)
    u = np.zeros(len(F))
    u[used] = spl.spsolve((K[used][:, used] + sp.identity(len(used)) * 1e-12 * K.diagonal().max()).tocsc(), F[used])
    res = np.zeros((nx, ny, nz, 5))
    for j in range(ny):
        for i, k in np.argwhere(mask[:, j, :]):
            ns = [node(i, k), node(i + 1, k), node(i + 1, k + 1), node(i, k + 1)]
            d = np.array([[2 * (j * nn + n), 2 * (j * nn + n) + 1] for n in ns]).ravel()
            e0 = np.array([-nu * sy[i, j, k] / E] * 2 + [0.0])
            res[i, j, k, :3] = np.mean([C @ (B @ u[d] - e0) for B in Bs], axis=0)
            # the interlayer shears at the cell: mean of its nodes' G du/dy (centred between layers)
            uc = u[d].reshape(4, 2).mean(0)
            def at(jj):
                if jj < 0: return np.zeros(2)
                if jj >= ny or not mask[i, jj, k]: return None
                dd = np.array([[2 * (jj * nn + n), 2 * (jj * nn + n) + 1] for n in ns]).ravel()
                return u[dd].reshape(4, 2).mean(0)
            up, dn = at(j + 1), at(j - 1) if j > 0 else None
            if j == 0: g = (uc - 0) / (h / 2) if up is None else (up - 0) / (1.5 * h)
            elif up is None: g = (uc - dn) / h
            else: g = (up - dn) / (2 * h)
            res[i, j, k, 3:] = couple * G * g
    return res
def run(name, h, src, couple, base, add_shear):
    c = L.load(f"{DATA}/base_{name}")
    far = c["far"] > 0
    nl = np.genfromtxt(f"{DATA}/nl_{name}/agent_cells.csv", delimiter=",", names=True)
    if src == "agent":
        idx, f = grid_fields(nl, h, {"sy": "sigma_y_Pa", "txy": "tau_xy_Pa", "tyz": "tau_yz_Pa"})
    else:
        idx, f = grid_fields(c, h, {"sy": "fem_sigma_y_Pa", "txy": "fem_tau_xy_Pa", "tyz": "fem_tau_yz_Pa"})
    r = solve(f, h, couple, base)[idx]
    out = []
    for k, comp in enumerate(["sigma_x", "sigma_z", "tau_xz"]):
        out.append(f"{comp} {err(r[:, k], c['fem_'+comp+'_Pa'], far):.3f}")
    if add_shear:
        txy = (nl["tau_xy_Pa"] if src == "agent" else c["fem_tau_xy_Pa"]) + r[:, 3]
        out.append(f"tau_xy+ {err(txy, c['fem_tau_xy_Pa'], far):.3f} (was {err(nl['tau_xy_Pa'], c['fem_tau_xy_Pa'], far):.3f})")
    print(f"{name:9s} {src} couple {couple} base {base} " + " ".join(out), flush=True)
if __name__ == "__main__":
    for n, h in [("b_x0.006", .002), ("b_x0.020", .002), ("held", .002), ("dblock", .004)]:
        for couple in [float(x) for x in sys.argv[1:]]:
            run(n, h, "agent", couple, True, True)
