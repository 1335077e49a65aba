import sys, numpy as np
import os
DATA = os.environ.get("LAYERS_DATA", ".")  # the folders of the README's commands
def vm(sx, sy, sz, txy, tyz, txz):
    return np.sqrt(0.5*((sx-sy)**2+(sy-sz)**2+(sz-sx)**2) + 3*(txy**2+tyz**2+txz**2))
def err(a, f, m): return np.sqrt(np.sum((a-f)[m]**2)/np.sum(f[m]**2))
for n in sys.argv[2:]:
    c = np.genfromtxt(f"{DATA}/base_{n}/cells.csv", delimiter=",", names=True)
    a = np.genfromtxt(f"{sys.argv[1]}_{n}/agent_cells.csv", delimiter=",", names=True)
    body = np.ones(len(c), bool); fv = c["fem_von_mises_Pa"]
    def v(src, sy):
        g = lambda k: src[k] if k in src.dtype.names else None
        return vm(src[p+"sigma_x_Pa"], sy, src[p+"sigma_z_Pa"], src[p+"tau_xy_Pa"], src[p+"tau_yz_Pa"], src[p+"tau_xz_Pa"])
    p = "agent_"; old = v(c, c["agent_sigma_y_Pa"]); oldf = v(c, c["fem_sigma_y_Pa"])
    p = ""; new = v(a, a["sigma_y_Pa"]); newf = v(a, c["fem_sigma_y_Pa"])
    print(n, f"body vm old {err(old, fv, body):.3f} new {err(new, fv, body):.3f} | with FEM's sigma_y: old {err(oldf, fv, body):.3f} new {err(newf, fv, body):.3f}")
