exec(open('exp1.py').read().split("print('sy far'")[0])
import turning
from stress_rules import ddy, ddx, scan_sx
def band(sx, ref):
    out=[]
    for lo,hi in ((0,4),(4,10),(10,20),(20,30),(30,35)):
        m=far.copy(); m[:, :lo]=False; m[:, hi:]=False
        out.append('%d-%d: %.0f/%.0f'%(lo,hi,np.linalg.norm((sx-ref)[m]),np.linalg.norm(ref[m])))
    return ' | '.join(out)
for fa,fp,D,turn in ((66.1,2.59,2,1),(66.1,2.59,2,0.5),(66.1,2.59,2,2),(75,2.59,2,1),(60,2.59,2,1),(66,2,2,1),(66,3.5,2,1),(66,2.59,5,1),(66,2.59,0.5,1)):
  t=turning.turning_plate(nx,ny,h,lc,2.0,fan_angle=fa,fan_power=fp,diffusion=D,turn=turn)
  wid=np.full(ny,1.0)
  tau=t['txy_ray']
  sxs=t['sx_ray']+scan_sx(ddy(tau,h,wid)-ddy(-0*tau,h,wid),h)  # placeholder
  # horizontal equilibrium with the packets' own tau: sigma_x = scan of -dtau/dy
  sx2=scan_sx(ddy(tau,h,wid),h)
  print(fa,fp,D,turn,'sy far %.3f body %.3f'%(sr.rel_l2(t['sy'],fem['sy'],far),sr.rel_l2(t['sy'],fem['sy'])),
        'tau far %.3f body %.3f'%(sr.rel_l2(tau,fem['txy'],far),sr.rel_l2(tau,fem['txy'])),
        'sx scan far %.3f body %.3f'%(sr.rel_l2(sx2,fem['sx'],far),sr.rel_l2(sx2,fem['sx'])))
  sxa,taua=sr.equilibrium_recovery(t['sy'],h,1,0)
  print('      recovery from its sy: sx far %.3f tau far %.3f'%(sr.rel_l2(sxa,fem['sx'],far),sr.rel_l2(taua,fem['txy'],far)), band(sx2,fem['sx']))
