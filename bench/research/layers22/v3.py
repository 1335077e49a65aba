import sys, numpy as np
import os
DATA = os.environ.get("LAYERS_DATA", ".")  # the folders of the README's commands
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import layers as L
from v2 import grid_fields, err, vm, E, nu
def dy(t, h, top):
    """d/dy along axis 1; top: how the top (free, loaded) face's end is treated."""
    g = np.gradient(t, h, axis=1)
    if top == "face0":   # quadratic through the two top cells and tau = 0 on the top face
        t1, t2 = t[:, -2, :], t[:, -1, :]   # at -3h/2, -h/2 from the face at 0
        # p(s) = a s^2 + b s + c with p(0)=0, p(-h/2)=t2, p(-3h/2)=t1 ; derivative at -h/2
        s1, s2 = -1.5*h, -0.5*h
        A = np.array([[s1*s1, s1], [s2*s2, s2]])
        inv = np.linalg.inv(A)
        a = inv[0,0]*t1 + inv[0,1]*t2; b = inv[1,0]*t1 + inv[1,1]*t2
        g[:, -1, :] = 2*a*s2 + b
    return g
def layers(f, h, top):
    sy, txy, tyz = f["sy"], f["txy"], f["tyz"]
    mask = ~np.isnan(sy)
    dtxy = dy(np.nan_to_num(txy), h, top); dtyz = dy(np.nan_to_num(tyz), h, top)
    res = np.zeros(sy.shape + (3,))
    for j in range(sy.shape[1]):
        res[:, j, :, :] = L.solve_layer(mask[:, j, :], np.nan_to_num(sy[:, j, :]), dtxy[:, j, :], dtyz[:, j, :], h, E, nu)
    return res
def run(name, h, top):
    c = L.load(f"{DATA}/base_{name}")
    far = c["far"] > 0; body = np.ones_like(far)
    nl = np.genfromtxt(f"{DATA}/nl_{name}/agent_cells.csv", delimiter=",", names=True)
    idx, fn = grid_fields(nl, h, {"sy": "sigma_y_Pa", "txy": "tau_xy_Pa", "tyz": "tau_yz_Pa"})
    rn = layers(fn, h, top)[idx]
    new = {}
    for k, comp in enumerate(["sigma_x", "sigma_z", "tau_xz"]):
        new[comp] = rn[:, k] + c["agent_" + comp + "_Pa"] - nl[comp + "_Pa"]
    v = vm(new["sigma_x"], c["agent_sigma_y_Pa"], new["sigma_z"], c["agent_tau_xy_Pa"], c["agent_tau_yz_Pa"], new["tau_xz"])
    fv = c["fem_von_mises_Pa"]
    s = " ".join(f"{k} {err(new[k], c['fem_'+k+'_Pa'], far):.3f}" for k in new)
    iy = idx[1]; ny = iy.max()+1
    tot = np.sum(fv**2)
    by = " ".join(f"{np.sum((v-fv)[iy==j]**2)/tot:.3f}" for j in range(ny-4, ny))
    print(f"{name:9s} {top:6s} {s} | vm far {err(v, fv, far):.3f} body {err(v, fv, body):.3f} (top 4 layers' body share {by})")
for top in ["grad", "face0"]:
    for n, h in [("b_x0.006", .002), ("b_x0.020", .002), ("held", .002), ("dblock", .004)]:
        run(n, h, top)
