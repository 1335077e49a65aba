import csv, numpy as np, sys
def rd(p):
    r=list(csv.DictReader(open(p)))
    return {k.split(' ')[0]:np.array([float(x[k]) if x[k]!='' else np.nan for x in r]) for k in r[0]}
def score(agent_dir, fem_dir):
    A=rd(agent_dir+'/cells.csv'); F=rd(fem_dir+'/cells.csv')
    An=rd(agent_dir+'/nodes.csv'); Fn=rd(fem_dir+'/nodes.csv')
    far=F['far']>0
    out={}
    for c in ['sigma_x','sigma_y','tau_xy','von_mises']:
        a=A['agent_'+c][far]; f=F['fem_'+c][far]
        out[c]=round(np.linalg.norm(a-f)/np.linalg.norm(f),3)
    a=np.c_[An['agent_u_x'],An['agent_u_y']]; f=np.c_[Fn['fem_u_x'],Fn['fem_u_y']]
    out['disp_allnodes']=round(np.linalg.norm(a-f)/np.linalg.norm(f),3)
    return out
if __name__=="__main__": print(score(sys.argv[1], sys.argv[2]))
