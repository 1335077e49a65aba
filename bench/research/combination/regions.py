import numpy as np, sys
from score_cells import rd
A=rd(sys.argv[1]+'/cells.csv'); F=rd(sys.argv[1]+'/cells.csv')
far=F['far']>0; x=A['x']; y=A['y']; a0=float(sys.argv[2])
regs=[('foot x>a0+a0/2',far&(x>1.5*a0)&(y<a0)),('foot a0<x<1.5a0',far&(x>a0)&(x<1.5*a0)&(y<a0)),('corner',far&(x<a0)&(y<a0)),('arm y>a0',far&(y>a0))]
for c in ['sigma_x','sigma_y','tau_xy','von_mises']:
    tot=np.linalg.norm(F['fem_'+c][far])**2
    print(c, ' '.join('%s: %.3f'%(n, np.linalg.norm(A['agent_'+c][m]-F['fem_'+c][m])**2/tot) for n,m in regs))
