"""3D von Mises of the agents against FEM (block3d): the C++ stresses without shear, and with the shear of
straight rays from the load point (tau_ay = sigma_y * lateral offset / depth per lateral axis a)."""
import sys, json, csv, numpy as np
def read(p):
    rows = list(csv.reader(open(p))); return {k: np.array([float(r[i]) if r[i] else np.nan for r in rows[1:]]) for i, k in enumerate(rows[0])}
for folder in sys.argv[1:]:
    a = read(folder + '/agent/agent_cells.csv'); f = read(folder + '/fem/fem_cells.csv'); c = read(folder + '/cells.csv')
    s = json.load(open(folder + '/summary.json')); lines = json.load(open(folder + '/lines.json'))
    x0, ytop, z0 = [l for l in lines if l['kind'] == 'along'][0]['from']
    h = s['agent']['agent_size']; ytop += h / 2
    far = c['far'] > 0.5
    sx, sy, sz = a['sigma_x [Pa]'], a['sigma_y [Pa]'], a['sigma_z [Pa]']
    def vm(sx, sy, sz, txy, tyz, txz):
        return np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2) + 3 * (txy ** 2 + tyz ** 2 + txz ** 2))
    fv = f['von_mises [Pa]']
    d = ytop - a['y [m]']
    txy = sy * (a['x [m]'] - x0) / d; tyz = sy * (a['z [m]'] - z0) / d
    rel = lambda m, r, k: np.linalg.norm((m - r)[k]) / np.linalg.norm(r[k])
    allc = np.ones_like(far)
    v0 = vm(sx, sy, sz, 0, 0, 0); v1 = vm(sx, sy, sz, txy, tyz, 0)
    print(folder, 'sigma_y far %.3f body %.3f' % (rel(sy, f['sigma_y [Pa]'], far), rel(sy, f['sigma_y [Pa]'], allc)),
          '| von Mises, no shear: far %.3f body %.3f' % (rel(v0, fv, far), rel(v0, fv, allc)),
          '| with ray shear: far %.3f body %.3f' % (rel(v1, fv, far), rel(v1, fv, allc)),
          '| FEM shear in FEM vm: far %.3f' % rel(vm(sx, sy, sz, f['tau_xy [Pa]'], f['tau_yz [Pa]'], f['tau_xz [Pa]']), fv, far))
    z = 0 * sx
    fs = (f['tau_xy [Pa]'], f['tau_yz [Pa]'], f['tau_xz [Pa]'])
    lat = np.hypot(a['x [m]'] - x0, a['z [m]'] - z0)
    # Boussinesq rays: the lateral stresses along a ray, s^2 sigma_y per axis (what C++ has) vs none.
    print('   lateral 0 + FEM shear: far %.3f | lateral 0 + ray shear: far %.3f body %.3f | lateral 0, no shear: far %.3f'
          % (rel(vm(z, sy, z, *fs), fv, far), rel(vm(z, sy, z, txy, tyz, 0), fv, far), rel(vm(z, sy, z, txy, tyz, 0), fv, allc),
             rel(vm(z, sy, z, 0, 0, 0), fv, far)))
