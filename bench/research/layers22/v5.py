import sys, numpy as np
import os
DATA = os.environ.get("LAYERS_DATA", ".")  # the folders of the README's commands
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import layers as L
from v2 import grid_fields, err, vm, E, nu
from v3 import dy
def layers(f, h, springs):
    sy, txy, tyz = f["sy"], f["txy"], f["tyz"]
    mask = ~np.isnan(sy)
    dtxy = dy(np.nan_to_num(txy), h, "grad"); dtyz = dy(np.nan_to_num(tyz), h, "grad")
    res = np.zeros(sy.shape + (3,))
    for j in range(sy.shape[1]):
        res[:, j, :, :] = L.solve_layer(mask[:, j, :], np.nan_to_num(sy[:, j, :]), dtxy[:, j, :], dtyz[:, j, :], h, E, nu, springs(j))
    return res
G = E / (2 * (1 + nu))
def run(name, h, label, springs, add_base):
    c = L.load(f"{DATA}/base_{name}")
    far = c["far"] > 0; body = np.ones_like(far)
    nl = np.genfromtxt(f"{DATA}/nl_{name}/agent_cells.csv", delimiter=",", names=True)
    idx, fn = grid_fields(nl, h, {"sy": "sigma_y_Pa", "txy": "tau_xy_Pa", "tyz": "tau_yz_Pa"})
    rn = layers(fn, h, lambda j: springs(j, h))[idx]
    new = {}
    for k, comp in enumerate(["sigma_x", "sigma_z", "tau_xz"]):
        new[comp] = rn[:, k] + add_base * (c["agent_" + comp + "_Pa"] - nl[comp + "_Pa"])
    txy = c["agent_tau_xy_Pa"] if add_base else nl["tau_xy_Pa"]
    tyz = c["agent_tau_yz_Pa"] if add_base else nl["tau_yz_Pa"]
    v = vm(new["sigma_x"], c["agent_sigma_y_Pa"], new["sigma_z"], txy, tyz, new["tau_xz"])
    fv = c["fem_von_mises_Pa"]
    s = " ".join(f"{k} {err(new[k], c['fem_'+k+'_Pa'], far):.3f}" for k in new)
    s += f" tau_xy {err(txy, c['fem_tau_xy_Pa'], far):.3f}"
    print(f"{name:9s} {label:10s} {s} | vm far {err(v, fv, far):.3f} body {err(v, fv, body):.3f}")
if __name__ == "__main__":
    variants = {
        "B": (lambda j, h: 0.0, 1),
        "D1": (lambda j, h: G / (0.5 * h) / h if j == 0 else 0.0, 0),
        "D1+B": (lambda j, h: G / (0.5 * h) / h if j == 0 else 0.0, 1),
        "D2": (lambda j, h: G / ((j + 0.5) * h) / h if j <= 1 else 0.0, 0),
    }
    for label, (s, b) in variants.items():
        for n, h in [("b_x0.006", .002), ("b_x0.020", .002), ("held", .002), ("dblock", .004)]:
            run(n, h, label, s, b)
