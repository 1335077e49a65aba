exec(open('exp1.py').read().split("print('sy far'")[0])
D=0.002
def band(sx, ref):
    out=[]
    for lo,hi in ((0,4),(4,10),(10,20),(20,30),(30,35)):
        m=far.copy(); m[:, :lo]=False; m[:, hi:]=False
        out.append('%d-%d: %.0f/%.0f'%(lo,hi,np.linalg.norm((sx-ref)[m]),np.linalg.norm(ref[m])))
    return ' | '.join(out)
sy=ag['sy']; syp=sy-ag['sy_delta']
wid=lambda w0,g: w0+g*(ny-1-np.arange(ny))
for w0 in (1,2,3):
  Qd=np.concatenate([np.zeros((1,ny)),np.cumsum(ag['sy_delta'],0)*h],0)
  tau_d=-ddy if False else None
  from stress_rules import ddy, ddx, scan_sx
  tdf=-ddy(Qd,h,wid(w0,0)); tau_delta=0.5*(tdf[:-1]+tdf[1:])
  tau_diff=(D/2)*ddx(syp,h)
  for name,tau in (('ray',ag['txy_ray']),('ray+diff',ag['txy_ray']+tau_diff),('ray+diff+delta',ag['txy_ray']+tau_diff+tau_delta)):
    sxs=scan_sx(ddy(tau,h,wid(w0,0)),h)
    print(w0,name,'tau far %.3f body %.3f'%(sr.rel_l2(tau,fem['txy'],far),sr.rel_l2(tau,fem['txy'])),'sx scan far %.3f body %.3f'%(sr.rel_l2(sxs,fem['sx'],far),sr.rel_l2(sxs,fem['sx'])), band(sxs,fem['sx']))
# V1: ray - tie
sxr=ag['sx_ray']; tie=np.linspace(sxr[0],sxr[-1],nx)
s1=sxr-tie
print('ray-tie far %.3f body %.3f'%(sr.rel_l2(s1,fem['sx'],far),sr.rel_l2(s1,fem['sx'])), band(s1,fem['sx']))
print('ray    far %.3f body %.3f'%(sr.rel_l2(sxr,fem['sx'],far),sr.rel_l2(sxr,fem['sx'])), band(sxr,fem['sx']))
