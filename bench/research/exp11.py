import numpy as np, sys
import plate_models as pm, stress_rules as sr, turning, cases
from stress_rules import ddy, scan_sx, base_layer
E=206e9
def model(name, fa=66, fp=2.0, D=2.0, c_ell=0.25, win_mm=5.0, delta=True, ell_mode='spread', disp='loadline'):
    nx, ny, h, lc, nu, plane, sign = cases.CASES[name]
    W=nx*h; i0=(lc[0]+lc[-1]+1)//2
    t=turning.turning_plate(nx,ny,h,lc,2.0*sign,fan_angle=fa,fan_power=fp,diffusion=D)
    sy=t['sy']
    nu_eff = nu/(1-nu) if plane=='strain' else nu
    if ell_mode=='spread':
        p=np.abs(sy[:,0]); xs=(np.arange(nx)+.5)*h; m=np.sum(p*xs)/p.sum(); var=np.sum(p*(xs-m)**2)/p.sum()
        ell=c_ell*min(np.sqrt(12*var),W)
    else: ell=c_ell*W
    sxb,taub,_=base_layer(sy,h,nu_eff,ell)
    tau_p=t['txy_ray']
    if delta:
        sxd,taud=sr.equilibrium_recovery(t['sy_delta'],h,win_mm*1e-3/h,0)
    else: sxd=taud=0*sy
    tau=tau_p+taub+taud
    sx=scan_sx(ddy(tau_p,h,np.full(ny,win_mm*1e-3/h)),h)+sxb+sxd
    vm=sr.von_mises(sx,sy,tau,nu,plane)
    ex,ey,g=sr.strains(sx,sy,tau,E,nu,plane)
    u=sr.displacement_from_load_line(ex,ey,g,h,i0) if disp=='loadline' else sr.displacement_from_base(ex,ey,g,h)
    return dict(sx=sx,sy=sy,txy=tau,vm=vm,u=u)
def score(name, m):
    nx, ny, h, lc, nu, plane, sign = cases.CASES[name]
    f = cases.fem(name)
    xc=(np.arange(nx)+.5)*h; yc=(np.arange(ny)+.5)*h
    X,Y=np.meshgrid(xc,yc,indexing='ij'); x1,x2=lc[0]*h,(lc[-1]+1)*h; H=ny*h
    far=np.hypot(np.clip(X,x1,x2)-X, H-Y)>=5*h-1e-12
    XN,YN=np.meshgrid(np.arange(nx+1)*h,np.arange(ny+1)*h,indexing='ij')
    farn=np.hypot(np.clip(XN,x1,x2)-XN, H-YN)>=5*h-1e-12
    r={k:(sr.rel_l2(m[k],f[k],far),sr.rel_l2(m[k],f[k])) for k in ('sx','sy','txy','vm')}
    u,fu=m['u'],f['u']
    r['u']=(sr.rel_l2(u,fu,np.repeat(farn[...,None],2,2)),sr.rel_l2(u,fu))
    jj=np.arange(ny+1)*h>0.1*H
    r['sign']=np.mean(np.concatenate([np.sign(u[0,jj,0])==np.sign(fu[0,jj,0]), np.sign(u[-1,jj,0])==np.sign(fu[-1,jj,0])]))
    return r
if __name__=='__main__':
    kw=eval('dict(%s)'%(sys.argv[1] if len(sys.argv)>1 else ''))
    print('%-14s'%'case', ' '.join('%-11s'%k for k in ('sx f/b','sy f/b','txy f/b','vm f/b','u f/b')),'ux_sign')
    for n in cases.CASES:
        r=score(n,model(n,**kw))
        print('%-14s'%n,' '.join('%.3f/%.3f'%r[k] for k in ('sx','sy','txy','vm','u')),' %.2f'%r['sign'])
