from exp11 import *
import exp11
def model2(name, variant, fa=66, fp=2.0, D=2.0, c_ell=0.25, win_mm=5.0, tau_win=None):
    nx, ny, h, lc, nu, plane, sign = cases.CASES[name]
    W=nx*h; i0=(lc[0]+lc[-1]+1)//2
    t=turning.turning_plate(nx,ny,h,lc,2.0*sign,fan_angle=fa,fan_power=fp,diffusion=D)
    sy=t['sy']; nu_eff = nu/(1-nu) if plane=='strain' else nu
    p=np.abs(sy[:,0]); xs=(np.arange(nx)+.5)*h; m=np.sum(p*xs)/p.sum(); var=np.sum(p*(xs-m)**2)/p.sum()
    ell=c_ell*min(np.sqrt(12*var),W)
    sxb,taub,_=base_layer(sy,h,nu_eff,ell)
    wr=np.full(ny,win_mm*1e-3/h)
    Qd=np.concatenate([np.zeros((1,ny)),np.cumsum(t['sy_delta'],0)*h],0)
    tdf=-ddy(Qd,h,wr); taud=0.5*(tdf[:-1]+tdf[1:])
    tau_p=t['txy_ray']
    if variant=='a': sx=scan_sx(ddy(tau_p,h,wr),h)
    elif variant=='b': sx=scan_sx(ddy(tau_p+taud,h,wr),h)
    elif variant=='c': sx=scan_sx(ddy(tau_p+taud,h,wr),h,close=None)
    elif variant=='d': sx=scan_sx(ddy(tau_p,h,wr),h,close=None)
    sx=sx+sxb; tau=tau_p+taub+taud
    vm=sr.von_mises(sx,sy,tau,nu,plane)
    ex,ey,g=sr.strains(sx,sy,tau,E,nu,plane)
    u=sr.displacement_from_load_line(ex,ey,g,h,i0) if DISP=="line" else sr.displacement_rows(ex,ey,g,h)
    return dict(sx=sx,sy=sy,txy=tau,vm=vm,u=u)
DISP="rows"
if __name__=="__main__":
 for n in cases.CASES:
  for v in "b":
    r=score(n,model2(n,v))
    print('%-14s'%n,v,' '.join('%.3f/%.3f'%r[k] for k in ('sx','sy','txy','vm','u')),' %.2f'%r['sign'])
