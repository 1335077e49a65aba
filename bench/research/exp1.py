import numpy as np, sys, time, pickle, os
import plate_models as pm, stress_rules as sr
E, nu = 206e9, 0.3
def case(nx, ny, h, lc, **kw):
    key = f"/work/proto23/fem_{nx}_{ny}_{h}_{lc[0]}_{kw}.pkl".replace(' ', '')
    if os.path.exists(key): return pickle.load(open(key, 'rb'))
    r = pm.fem_plate(nx, ny, h, kw.get('E', E), kw.get('nu', nu), 2.0, lc, sub=kw.get('sub', 4 if nx <= 50 else 2), plane=kw.get('plane', 'stress'))
    pickle.dump(r, open(key, 'wb')); return r
nx=ny=40; h=0.005; lc=[19,20]
fem = case(nx, ny, h, lc)
ag = pm.directional_plate(nx, ny, lc, 2.0, h=h)
xc=(np.arange(nx)+.5)*h; yc=(np.arange(ny)+.5)*h
X,Y=np.meshgrid(xc,yc,indexing='ij')
x1,x2=lc[0]*h,(lc[-1]+1)*h; H=ny*h
dist=np.hypot(np.clip(X,x1,x2)-X, H-Y)
far=dist>=5*h-1e-12
print('sy far', sr.rel_l2(ag['sy'],fem['sy'],far), 'body', sr.rel_l2(ag['sy'],fem['sy']))
print('sx_ray far', sr.rel_l2(ag['sx_ray'],fem['sx'],far), 'tau_ray far', sr.rel_l2(ag['txy_ray'],fem['txy'],far))
for src,name in ((fem['sy'],'FEM sy'),(ag['sy'],'agent sy')):
  for w0,g in ((0.5,0),(1,0),(2,0),(1,0.1),(1,0.2),(1,0.3),(2,0.2),(2,0.4)):
    sx,tau=sr.equilibrium_recovery(src,h,w0,g)
    print(name,w0,g,'sx far %.3f body %.3f  tau far %.3f body %.3f'%(sr.rel_l2(sx,fem['sx'],far),sr.rel_l2(sx,fem['sx']),sr.rel_l2(tau,fem['txy'],far),sr.rel_l2(tau,fem['txy'])))
