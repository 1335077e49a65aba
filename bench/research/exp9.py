from exp8 import *
name='seed5_x100'
nx, ny, h, lc, nu, plane, sign = cases.CASES[name]
f=cases.fem(name); W=nx*h
t=turning.turning_plate(nx,ny,h,lc,2.0,fan_angle=66,fan_power=2,diffusion=2)
sxb,taub,_=base_layer(t['sy'],h,nu,0.25*W)
sx=scan_sx(ddy(t['txy_ray'],h,np.full(ny,1.0)),h)+sxb; tau=t['txy_ray']+taub; sy=t['sy']
np.set_printoptions(precision=2, suppress=True, linewidth=250)
for lab,(a,b,c) in (('model',(sx,sy,tau)),('fem',(f['sx'],f['sy'],f['txy'])),('model sx/sy, fem tau',(sx,sy,f['txy'])),('fem sx/sy, model tau',(f['sx'],f['sy'],tau))):
    ex,ey,g=sr.strains(a,b,c,E,nu,plane); u=sr.displacement_from_base(ex,ey,g,h)
    print(lab,'left ux e9', u[0,::4,0]*1e9, 'uy err %.3f ux err %.3f'%(sr.rel_l2(u[...,1],f['u'][...,1]),sr.rel_l2(u[...,0],f['u'][...,0])))
print('fem left ux e9', f['u'][0,::4,0]*1e9)
print('fem centre uy e9', f['u'][20,::4,1]*1e9)
