from exp12 import *
np.set_printoptions(precision=0, suppress=True, linewidth=250)
n='wide400x100_5'; m=model2(n,'b'); f=cases.fem(n)
for j in (17,12,8,4,1):
  for k in ('sx','txy','sy'):
    print(j,k,'fem',f[k][20:61:2,j]); print(j,k,'mod',m[k][20:61:2,j])
