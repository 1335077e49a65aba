from exp12 import *
np.set_printoptions(precision=2, suppress=True, linewidth=250)
for n in ('seed5_x50','wide400x100_5'):
  m=model2(n,'b'); f=cases.fem(n)
  print(n,'ux %.3f uy %.3f'%(sr.rel_l2(m['u'][...,0],f['u'][...,0]),sr.rel_l2(m['u'][...,1],f['u'][...,1])))
  print(' fem left ux', f['u'][0,::4,0]*1e9); print(' mod left ux', m['u'][0,::4,0]*1e9)
  print(' fem right ux', f['u'][-1,::4,0]*1e9); print(' mod right ux', m['u'][-1,::4,0]*1e9)
  print(' fem top ux', f['u'][::4,-1,0]*1e9); print(' mod top ux', m['u'][::4,-1,0]*1e9)
  print(' fem top uy', f['u'][::4,-1,1]*1e9); print(' mod top uy', m['u'][::4,-1,1]*1e9)
