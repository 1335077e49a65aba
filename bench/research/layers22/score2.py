import sys, numpy as np
import os
DATA = os.environ.get("LAYERS_DATA", ".")  # the folders of the README's commands
def err(a, f, m): return np.sqrt(np.sum((a-f)[m]**2)/np.sum(f[m]**2))
for n in sys.argv[1:]:
    c = np.genfromtxt(f"base_{n}/cells.csv", delimiter=",", names=True)
    o = np.genfromtxt(f"old_{n}/agent_cells.csv", delimiter=",", names=True)
    assert np.allclose(o["x_m"], c["x_m"]) and np.allclose(o["z_m"], c["z_m"])
    far = c["far"] > 0; body = np.ones_like(far)
    s = []
    for k in ["sigma_x", "sigma_y", "sigma_z", "tau_xy", "tau_yz", "tau_xz", "von_mises"]:
        s.append(f"{k} {err(o[k+'_Pa'], c['fem_'+k+'_Pa'], far):.3f}->{err(c['agent_'+k+'_Pa'], c['fem_'+k+'_Pa'], far):.3f}")
    fv = c["fem_von_mises_Pa"]
    s.append(f"body vm {err(o['von_mises_Pa'], fv, body):.3f}->{err(c['agent_von_mises_Pa'], fv, body):.3f}")
    print(n, " | ".join(s))
