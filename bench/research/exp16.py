import numpy as np, plate_models as pm, bending, stress_rules as sr
E, nu = 206e9, 0.3
for (nx, ny, h) in ((40, 8, 0.005), (100, 20, 0.002), (20, 8, 0.005)):
    f = pm.fem_plate(nx, ny, h, E, nu, 2.0, [nx - 1], rigid='left', sub=4 if nx*ny < 1000 else 2)
    b = bending.cantilever_columns(nx, ny, h, -2.0, nx - 1, E, nu)
    u = bending.march_from_clamp(b['sx'], b['sy'], b['txy'], E, nu, h)
    L, D = nx * h, ny * h; I = 0.002 * D ** 3 / 12
    eb = -2.0 * ((nx - .5) * h) ** 3 / (3 * E * I)
    print(f'{L*1e3:.0f}x{D*1e3:.0f} mm, h {h*1e3:.0f} mm: FEM tip uy {f["u"][-1, ny//2, 1]*1e9:.2f} nm, columns {u[-1, ny//2, 1]*1e9:.2f} nm, EB {eb*1e9:.2f} nm; '
          f'FEM reaction y {f["reaction"][:, 1].sum():+.3f} N (load -2); columns reaction {b["reaction"]:+.1f} N')
    far = np.ones((nx, ny), bool); far[-5:, :] = False
    for k in ('sx', 'txy', 'sy'):
        print('   ', k, 'far %.3f body %.3f' % (sr.rel_l2(b[k], f[k], far) if k != 'sy' else 1.0, sr.rel_l2(b[k], f[k]) if k != 'sy' else 1.0))
    vm = sr.von_mises(b['sx'], b['sy'], b['txy'], nu); print('    vm far %.3f' % sr.rel_l2(vm, f['vm'], far))
    print('    u body %.3f  tip deflection ratio %.3f' % (sr.rel_l2(u, f['u']), u[-1, ny//2, 1] / f['u'][-1, ny//2, 1]))
