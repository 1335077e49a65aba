"""Oracle: lateral stresses (sigma_x, sigma_z, tau_xz) per horizontal layer by minimum
complementary energy given sigma_y, tau_xy, tau_yz (plane stress in the layer, body force
d tau_xy/dy, d tau_yz/dy, initial strain -nu sigma_y / E)."""
import sys, numpy as np, scipy.sparse as sp, scipy.sparse.linalg as spl
import os
DATA = os.environ.get("LAYERS_DATA", ".")  # the folders of the README's commands

def load(folder):
    d = np.genfromtxt(folder + "/cells.csv", delimiter=",", names=True)
    return d

def grid_of(d, h):
    ix = np.rint((d["x_m"] - h / 2) / h).astype(int)
    iy = np.rint((d["y_m"] - h / 2) / h).astype(int)
    iz = np.rint((d["z_m"] - h / 2) / h).astype(int)
    return ix, iy, iz

def q1_layer(nx, nz, h, E, nu):
    """Stiffness of a plane-stress Q1 layer (2x2 Gauss), and per cell the B matrices."""
    C = E / (1 - nu**2) * np.array([[1, nu, 0], [nu, 1, 0], [0, 0, (1 - nu) / 2]])
    g = [-1 / np.sqrt(3), 1 / np.sqrt(3)]
    Bs = []
    for xi in g:
        for et in g:
            dN = 0.25 * np.array([[-(1 - et), (1 - et), (1 + et), -(1 + et)],
                                  [-(1 - xi), -(1 + xi), (1 + xi), (1 - xi)]]) * 2 / h
            B = np.zeros((3, 8))
            B[0, 0::2] = dN[0]; B[1, 1::2] = dN[1]; B[2, 0::2] = dN[1]; B[2, 1::2] = dN[0]
            Bs.append(B)
    w = (h / 2) ** 2
    Ke = sum(B.T @ C @ B for B in Bs) * w
    return C, Bs, Ke, w

def solve_layer(mask, sy, fx, fz, h, E, nu, spring=0.0):
    nx, nz = mask.shape
    C, Bs, Ke, w = q1_layer(nx, nz, h, E, nu)
    node = lambda i, k: i * (nz + 1) + k
    nn = (nx + 1) * (nz + 1)
    rows, cols, vals = [], [], []
    F = np.zeros(2 * nn)
    cells = np.argwhere(mask)
    dofs_of = {}
    for i, k in cells:
        ns = [node(i, k), node(i + 1, k), node(i + 1, k + 1), node(i, k + 1)]
        dofs = np.array([[2 * n, 2 * n + 1] for n in ns]).ravel()
        dofs_of[(i, k)] = dofs
        e0 = np.array([-nu * sy[i, k] / E, -nu * sy[i, k] / E, 0.0])
        fe = sum(B.T @ C @ e0 for B in Bs) * w
        fe = fe.copy()
        fe[0::2] += fx[i, k] * h * h / 4
        fe[1::2] += fz[i, k] * h * h / 4
        F[dofs] += fe
        r, c = np.meshgrid(dofs, dofs, indexing="ij")
        rows.append(r.ravel()); cols.append(c.ravel()); vals.append(Ke.ravel())
    K = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(2 * nn, 2 * nn))
    used = np.unique(np.concatenate(list(dofs_of.values())))
    Ku = K[used][:, used] + sp.identity(len(used)) * 1e-9 * Ke[0, 0]
    if spring > 0:
        cnt = np.zeros(2 * nn)
        for dofs in dofs_of.values(): cnt[dofs] += spring * h * h / 4
        Ku = Ku + sp.diags(cnt[used])
    u = np.zeros(2 * nn)
    u[used] = spl.spsolve(Ku.tocsc(), F[used])
    out = np.zeros((nx, nz, 3))
    for (i, k), dofs in dofs_of.items():
        e0 = np.array([-nu * sy[i, k] / E, -nu * sy[i, k] / E, 0.0])
        s = np.mean([C @ (B @ u[dofs] - e0) for B in Bs], axis=0)
        out[i, k] = s
    return out

def main(folder, h, E=206e9, nu=0.3, source="fem", c=0.0):
    d = load(folder)
    ix, iy, iz = grid_of(d, h)
    nx, ny, nz = ix.max() + 1, iy.max() + 1, iz.max() + 1
    def field(name):
        a = np.full((nx, ny, nz), np.nan); a[ix, iy, iz] = d[name]; return a
    sy = field(source + "_sigma_y_Pa"); txy = field(source + "_tau_xy_Pa"); tyz = field(source + "_tau_yz_Pa")
    mask = ~np.isnan(sy)
    dtxy = np.gradient(np.nan_to_num(txy), h, axis=1); dtyz = np.gradient(np.nan_to_num(tyz), h, axis=1)
    res = np.zeros((nx, ny, nz, 3))
    for j in range(ny):
        G = E / (2 * (1 + nu)); y = (j + 0.5) * h
        res[:, j, :, :] = solve_layer(mask[:, j, :], np.nan_to_num(sy[:, j, :]), dtxy[:, j, :], dtyz[:, j, :], h, E, nu, c * G / (y * h))
    far = d["far"] > 0
    out = {}
    for c, name in enumerate(["sigma_x", "sigma_z", "tau_xz"]):
        got = res[ix, iy, iz, c]; fem = d["fem_" + name + "_Pa"]; ag = d["agent_" + name + "_Pa"]
        e = np.sqrt(np.sum((got - fem)[far] ** 2) / np.sum(fem[far] ** 2))
        e0 = np.sqrt(np.sum((ag - fem)[far] ** 2) / np.sum(fem[far] ** 2))
        out[name] = (e, e0)
    return out

if __name__ == "__main__":
    folder, h, src, c = sys.argv[1], float(sys.argv[2]), sys.argv[3], float(sys.argv[4])
    for k, (e, e0) in main(folder, h, source=src, c=c).items():
        print(f"{k}: layers {e:.3f}  shipped {e0:.3f}")
