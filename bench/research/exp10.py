from exp8 import *
for name in ('seed5_x100','seed5_x50','wide400x100_5','seed2_x50'):
  nx, ny, h, lc, nu, plane, sign = cases.CASES[name]
  f=cases.fem(name); W=nx*h; i0=(lc[0]+lc[-1]+1)//2
  t=turning.turning_plate(nx,ny,h,lc,2.0,fan_angle=66,fan_power=2,diffusion=2)
  sxb,taub,_=base_layer(t['sy'],h,nu,0.25*W)
  sx=scan_sx(ddy(t['txy_ray'],h,np.full(ny,1.0)),h)+sxb; tau=t['txy_ray']+taub; sy=t['sy']
  for lab,(a,b,c) in (('model',(sx,sy,tau)),('fem',(f['sx'],f['sy'],f['txy']))):
    ex,ey,g=sr.strains(a,b,c,E,nu,plane)
    for m,u in (('base',sr.displacement_from_base(ex,ey,g,h)),('loadline',sr.displacement_from_load_line(ex,ey,g,h,i0))):
      jj=np.arange(ny+1)*h>0.1*ny*h
      sgn=np.mean(np.concatenate([np.sign(u[0,jj,0])==np.sign(f['u'][0,jj,0]), np.sign(u[-1,jj,0])==np.sign(f['u'][-1,jj,0])]))
      print(name,lab,m,'u %.3f ux %.3f uy %.3f sign %.2f'%(sr.rel_l2(u,f['u']),sr.rel_l2(u[...,0],f['u'][...,0]),sr.rel_l2(u[...,1],f['u'][...,1]),sgn))
