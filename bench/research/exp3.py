exec(open('exp1.py').read().split("print('sy far'")[0])
def band(sx, ref):
    out=[]
    for lo,hi in ((0,4),(4,10),(10,20),(20,30),(30,35)):
        m=far.copy(); m[:, :lo]=False; m[:, hi:]=False
        out.append('%d-%d: err %.0f ref %.0f'%(lo,hi,np.linalg.norm((sx-ref)[m]),np.linalg.norm(ref[m])))
    return ' | '.join(out)
for src,name in ((fem['sy'],'FEM'),(ag['sy'],'agent')):
  for br in (0,3,6,10):
    sx,tau=sr.equilibrium_recovery(src,h,2,0,base_rows=br)
    print(name,br,'far %.3f body %.3f'%(sr.rel_l2(sx,fem['sx'],far),sr.rel_l2(sx,fem['sx'])), band(sx,fem['sx']))
