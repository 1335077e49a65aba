exec(open('exp5.py').read().split("for fa,fp")[0])
from stress_rules import base_layer
t=turning.turning_plate(nx,ny,h,lc,2.0,fan_angle=66,fan_power=2,diffusion=2,turn=1)
sx2=scan_sx(ddy(t['txy_ray'],h,np.full(ny,1.0)),h)
W=nx*h
for ell in (0.15,0.2,0.25):
  for taper in (True,False):
    for wsy in (False,True):
      sxb,taub,syb=base_layer(t['sy'],h,0.3,ell*W,wsy,taper)
      sx=sx2+sxb; tau=t['txy_ray']+taub; sy=t['sy']+syb
      print(ell,taper,wsy,'sx far %.3f body %.3f'%(sr.rel_l2(sx,fem['sx'],far),sr.rel_l2(sx,fem['sx'])),'tau far %.3f body %.3f'%(sr.rel_l2(tau,fem['txy'],far),sr.rel_l2(tau,fem['txy'])),'sy far %.3f'%sr.rel_l2(sy,fem['sy'],far), band(sx,fem['sx']))
