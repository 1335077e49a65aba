import sys, numpy as np
import os
DATA = os.environ.get("LAYERS_DATA", ".")  # the folders of the README's commands
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import layers as L
from v2 import grid_fields, err, vm, E, nu
from v3 import layers
def run(name, h, subst, add_base=1):
    c = L.load(f"{DATA}/base_{name}")
    far = c["far"] > 0
    nl = np.genfromtxt(f"{DATA}/nl_{name}/agent_cells.csv", delimiter=",", names=True)
    idx, fn = grid_fields(nl, h, {"sy": "sigma_y_Pa", "txy": "tau_xy_Pa", "tyz": "tau_yz_Pa"})
    _, ff = grid_fields(c, h, {"sy": "fem_sigma_y_Pa", "txy": "fem_tau_xy_Pa", "tyz": "fem_tau_yz_Pa"})
    for k in subst: fn[k] = ff[k]
    rn = layers(fn, h, "grad")[idx]
    out = []
    for k, comp in enumerate(["sigma_x", "sigma_z", "tau_xz"]):
        new = rn[:, k] + add_base * (c["agent_" + comp + "_Pa"] - nl[comp + "_Pa"])
        out.append(f"{comp} {err(new, c['fem_'+comp+'_Pa'], far):.3f}")
    print(f"{name:9s} fem:{','.join(subst) or '-':12s} base{add_base} " + " ".join(out))
for n, h in [("b_x0.006", .002), ("held", .002), ("b_x0.020", .002)]:
    for subst in [[], ["sy"], ["txy", "tyz"], ["sy", "txy", "tyz"]]:
        for b in [1, 0]:
            run(n, h, subst, b)
