"""Held-out suite on the Python FEM (Q1, each agent cut into sub x sub elements)."""
import numpy as np, os, pickle
import plate_models as pm
CASES = {
  # name: nx, ny, h, load cells, E, nu, plane, sign
  'seed5_x100': (40, 40, 0.005, [19, 20], 0.3, 'stress', 1),
  'seed5_x50': (40, 40, 0.005, [9, 10], 0.3, 'stress', 1),
  'seed2_x100': (100, 100, 0.002, [49, 50], 0.3, 'stress', 1),
  'seed2_x50': (100, 100, 0.002, [24, 25], 0.3, 'stress', 1),
  'strain5_x100': (40, 40, 0.005, [19, 20], 0.3, 'strain', 1),
  'nu01_5_x100': (40, 40, 0.005, [19, 20], 0.1, 'stress', 1),
  'nu045_5_x100': (40, 40, 0.005, [19, 20], 0.45, 'stress', 1),
  'wide400x100_5': (80, 20, 0.005, [39, 40], 0.3, 'stress', 1),
  'pulled5_x100': (40, 40, 0.005, [19, 20], 0.3, 'stress', -1),
  'pulled2_x50': (100, 100, 0.002, [24, 25], 0.3, 'stress', -1),
}
def fem(name):
    nx, ny, h, lc, nu, plane, sign = CASES[name]
    key = f"/work/proto23/pyfem_{name}.pkl"
    if os.path.exists(key):
        return pickle.load(open(key, 'rb'))
    r = pm.fem_plate(nx, ny, h, 206e9, nu, 2.0 * sign, lc, sub=4 if nx * ny <= 3200 else 2, plane=plane)
    pickle.dump(r, open(key, 'wb'))
    return r
if __name__ == '__main__':
    import sys, time
    for n in (sys.argv[1:] or CASES):
        t = time.time(); fem(n); print(n, time.time() - t, flush=True)
