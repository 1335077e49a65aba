import sys, numpy as np
import os
DATA = os.environ.get("LAYERS_DATA", ".")  # the folders of the README's commands
def vm(sx, sy, sz, txy, tyz, txz):
    return np.sqrt(0.5*((sx-sy)**2+(sy-sz)**2+(sz-sx)**2) + 3*(txy**2+tyz**2+txz**2))
def err(a, f, m): return np.sqrt(np.sum((a-f)[m]**2)/np.sum(f[m]**2))
for n in sys.argv[2:]:
    c = np.genfromtxt(f"{DATA}/base_{n}/cells.csv", delimiter=",", names=True)
    a = np.genfromtxt(f"{sys.argv[1]}_{n}/agent_cells.csv", delimiter=",", names=True)
    assert np.allclose(a["x_m"], c["x_m"]) and np.allclose(a["z_m"], c["z_m"])
    far = c["far"] > 0; body = np.ones_like(far)
    s = []
    for k in ["sigma_x", "sigma_y", "sigma_z", "tau_xy", "tau_yz", "tau_xz"]:
        s.append(f"{k} {err(c['agent_'+k+'_Pa'], c['fem_'+k+'_Pa'], far):.3f}->{err(a[k+'_Pa'], c['fem_'+k+'_Pa'], far):.3f}")
    fv = c["fem_von_mises_Pa"]
    s.append(f"vm far {err(c['agent_von_mises_Pa'], fv, far):.3f}->{err(a['von_mises_Pa'], fv, far):.3f} body {err(c['agent_von_mises_Pa'], fv, body):.3f}->{err(a['von_mises_Pa'], fv, body):.3f}")
    print(n, " | ".join(s))
