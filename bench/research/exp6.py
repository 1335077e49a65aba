exec(open('exp5.py').read().split("for fa,fp")[0])
t=turning.turning_plate(nx,ny,h,lc,2.0,fan_angle=66,fan_power=2,diffusion=2,turn=1)
sx2=scan_sx(ddy(t['txy_ray'],h,np.full(ny,1.0)),h)
np.set_printoptions(precision=0, suppress=True, linewidth=250)
for j in (8,6,4,2,0):
  print('row',j,'sx FEM  ', fem['sx'][::2,j]); print('row',j,'sx turn ', sx2[::2,j])
  print('row',j,'sy FEM  ', fem['sy'][::2,j]); print('row',j,'sy turn ', t['sy'][::2,j])
  print('row',j,'tau FEM  ', fem['txy'][::2,j]); print('row',j,'tau turn ', t['txy_ray'][::2,j])
print('centre sx FEM', fem['sx'][19,:12]); print('centre sx turn', sx2[19,:12])
