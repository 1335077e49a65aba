from exp12 import *
import itertools
for c_ell,win,fa,fp in [(0.25,5,66,2),(0.2,5,66,2),(0.3,5,66,2),(0.25,2.5,66,2),(0.25,10,66,2),(0.25,5,72,2),(0.25,5,66,2.59),(0.25,5,60,1.5)]:
    rs={n:score(n,model2(n,'b',c_ell=c_ell,win_mm=win,fa=fa,fp=fp)) for n in cases.CASES}
    fit=rs['seed5_x100']
    print(c_ell,win,fa,fp,'fit:',' '.join('%s %.3f'%(k,fit[k][0]) for k in ('sx','sy','txy','vm','u')),
      '| worst held-out:',' '.join('%s %.3f'%(k,max(r[k][0] for n,r in rs.items() if n!='seed5_x100')) for k in ('sx','sy','txy','vm','u')),
      'wide sx %.3f txy %.3f u %.3f'%(rs['wide400x100_5']['sx'][0],rs['wide400x100_5']['txy'][0],rs['wide400x100_5']['u'][0]))
