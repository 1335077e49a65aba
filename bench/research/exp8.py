import numpy as np, sys
import plate_models as pm, stress_rules as sr, turning, cases
from stress_rules import ddy, scan_sx, base_layer
E=206e9
def evaluate(name, fa=66, fp=2.0, D=2.0, ell=0.25, win_mm=5.0, verbose=False, mirrored=False):
    nx, ny, h, lc, nu, plane, sign = cases.CASES[name]
    f = cases.fem(name)
    xc=(np.arange(nx)+.5)*h; yc=(np.arange(ny)+.5)*h
    X,Y=np.meshgrid(xc,yc,indexing='ij'); x1,x2=lc[0]*h,(lc[-1]+1)*h; H=ny*h; W=nx*h
    far=np.hypot(np.clip(X,x1,x2)-X, H-Y)>=5*h-1e-12
    XN,YN=np.meshgrid(np.arange(nx+1)*h,np.arange(ny+1)*h,indexing='ij')
    farn=np.hypot(np.clip(XN,x1,x2)-XN, H-YN)>=5*h-1e-12
    if mirrored:
        t=pm.directional_plate(nx,ny,lc,2.0*sign,h=h)
        sx,tau=sr.equilibrium_recovery(t['sy'],h,2,0); sy=t['sy']
    else:
        t=turning.turning_plate(nx,ny,h,lc,2.0*sign,fan_angle=fa,fan_power=fp,diffusion=D)
        nu_eff = nu/(1-nu) if plane=='strain' else nu
        sxb,taub,_=base_layer(t['sy'],h,nu_eff,ell*W)
        sx=scan_sx(ddy(t['txy_ray'],h,np.full(ny,win_mm*1e-3/h)),h)+sxb
        tau=t['txy_ray']+taub; sy=t['sy']
    vm=sr.von_mises(sx,sy,tau,nu,plane)
    ex,ey,g=sr.strains(sx,sy,tau,E,nu,plane)
    u=sr.displacement_from_base(ex,ey,g,h)
    fu=f['u']
    # u_x sign on both side edges above the lowest tenth
    jj=np.arange(ny+1)*h>0.1*H
    sgn=np.mean(np.concatenate([np.sign(u[0,jj,0])==np.sign(fu[0,jj,0]), np.sign(u[-1,jj,0])==np.sign(fu[-1,jj,0])]))
    r={}
    for k,a,b in (('sx',sx,f['sx']),('sy',sy,f['sy']),('txy',tau,f['txy']),('vm',vm,f['vm'])):
        r[k]=(sr.rel_l2(a,b,far),sr.rel_l2(a,b))
    r['u']=(sr.rel_l2(u,fu,np.repeat(farn[...,None],2,2)),sr.rel_l2(u,fu))
    r['ux_sign']=sgn
    # the same displacement march fed with FEM's own stresses (how much the march itself costs)
    exf,eyf,gf=sr.strains(f['sx'],f['sy'],f['txy'],E,nu,plane)
    uf=sr.displacement_from_base(exf,eyf,gf,h)
    r['u_from_fem_stress']=sr.rel_l2(uf,fu)
    return r
if __name__=='__main__':
    kw=eval('dict(%s)'%(sys.argv[1] if len(sys.argv)>1 else ''))
    print('%-14s'%'case', ' '.join('%-11s'%k for k in ('sx f/b','sy f/b','txy f/b','vm f/b','u f/b')),'ux_sign u(FEMstress)')
    for n in cases.CASES:
        r=evaluate(n,**kw)
        print('%-14s'%n,' '.join('%.3f/%.3f'%r[k] for k in ('sx','sy','txy','vm','u')),' %.2f  %.3f'%(r['ux_sign'],r['u_from_fem_stress']))
