import sys, numpy as np
import os
DATA = os.environ.get("LAYERS_DATA", ".")  # the folders of the README's commands
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import layers as L
E, nu = 206e9, 0.3
def grid_fields(d, h, names):
    ix, iy, iz = L.grid_of(d, h)
    shape = (ix.max()+1, iy.max()+1, iz.max()+1)
    out = {}
    for k, n in names.items():
        a = np.full(shape, np.nan); a[ix, iy, iz] = d[n]; out[k] = a
    return (ix, iy, iz), out
def layers(f, h):
    sy, txy, tyz = f["sy"], f["txy"], f["tyz"]
    mask = ~np.isnan(sy)
    dtxy = np.gradient(np.nan_to_num(txy), h, axis=1); dtyz = np.gradient(np.nan_to_num(tyz), h, axis=1)
    res = np.zeros(sy.shape + (3,))
    for j in range(sy.shape[1]):
        res[:, j, :, :] = L.solve_layer(mask[:, j, :], np.nan_to_num(sy[:, j, :]), dtxy[:, j, :], dtyz[:, j, :], h, E, nu)
    return res
def err(got, fem, far): return np.sqrt(np.sum((got-fem)[far]**2)/np.sum(fem[far]**2))
def run(name, h, verbose=False):
    c = L.load(f"{DATA}/base_{name}")
    far = c["far"] > 0
    nl = np.genfromtxt(f"{DATA}/nl_{name}/agent_cells.csv", delimiter=",", names=True)
    assert np.allclose(nl["x_m"], c["x_m"]) and np.allclose(nl["y_m"], c["y_m"]) and np.allclose(nl["z_m"], c["z_m"])
    idx, fb = grid_fields(c, h, {"sy": "agent_sigma_y_Pa", "txy": "agent_tau_xy_Pa", "tyz": "agent_tau_yz_Pa"})
    _, fn = grid_fields(nl, h, {"sy": "sigma_y_Pa", "txy": "tau_xy_Pa", "tyz": "tau_yz_Pa"})
    ra = layers(fb, h)[idx]; rn = layers(fn, h)[idx]
    comps = ["sigma_x", "sigma_z", "tau_xz"]
    row = {}
    for k, comp in enumerate(comps):
        fem = c["fem_" + comp + "_Pa"]; ship = c["agent_" + comp + "_Pa"]; base = ship - nl[comp + "_Pa"]
        row[comp] = dict(ship=err(ship, fem, far), A=err(ra[:, k], fem, far), C=err(rn[:, k], fem, far), B=err(rn[:, k] + base, fem, far))
    print(name, " | ".join(f"{comp}: " + " ".join(f"{v}={x:.3f}" for v, x in r.items()) for comp, r in row.items()))
for n, h in [("b_x0.006", .002), ("b_x0.020", .002), ("held", .002), ("dblock", .004)]:
    run(n, h)

def vm(sx, sy, sz, txy, tyz, txz):
    return np.sqrt(0.5*((sx-sy)**2+(sy-sz)**2+(sz-sx)**2) + 3*(txy**2+tyz**2+txz**2))
def detail(name, h):
    c = L.load(f"{DATA}/base_{name}")
    far = c["far"] > 0; body = np.ones_like(far)
    nl = np.genfromtxt(f"{DATA}/nl_{name}/agent_cells.csv", delimiter=",", names=True)
    idx, fn = grid_fields(nl, h, {"sy": "sigma_y_Pa", "txy": "tau_xy_Pa", "tyz": "tau_yz_Pa"})
    rn = layers(fn, h)[idx]
    new = {}
    for k, comp in enumerate(["sigma_x", "sigma_z", "tau_xz"]):
        new[comp] = rn[:, k] + c["agent_" + comp + "_Pa"] - nl[comp + "_Pa"]
    v = vm(new["sigma_x"], c["agent_sigma_y_Pa"], new["sigma_z"], c["agent_tau_xy_Pa"], c["agent_tau_yz_Pa"], new["tau_xz"])
    fv = c["fem_von_mises_Pa"]; sv = c["agent_von_mises_Pa"]
    print(name, f"vm far {err(sv, fv, far):.3f}->{err(v, fv, far):.3f} body {err(sv, fv, body):.3f}->{err(v, fv, body):.3f}")
    fem = c["fem_sigma_x_Pa"]; got = new["sigma_x"]; iy = idx[1]
    tot = np.sum(fem[far]**2)
    print(" ".join(f"{j}:{np.sum((got-fem)[far & (iy==j)]**2)/tot:.3f}" for j in range(iy.max()+1)))
    return c, new, idx
if __name__ == "__main__" and len(sys.argv) > 1:
    for n, h in [("b_x0.006", .002), ("b_x0.020", .002), ("held", .002), ("dblock", .004)]:
        detail(n, h)
