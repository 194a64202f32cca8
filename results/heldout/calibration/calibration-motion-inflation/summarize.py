"""Summary of run.sh: failures (aligned ATE above 3x the smoother's or dead reckoning's), mean / median / p90 and
the NEES median per inflation and association, over all 216 worlds and per world kind; writes OUT/runs.csv."""
import glob
import json
import re
import sys

import pandas as pd
rel=pd.read_csv(sys.argv[1] + '/results.csv')
sm=rel[rel['filter']=='smoother'][['world','clutter','seed','ate_aligned_rmse_m']].rename(columns={'ate_aligned_rmse_m':'sm'})
base_j=rel[(rel['filter']=='fastslam2')&(rel.relocalize==False)][['world','clutter','seed','ate_aligned_rmse_m','dead_reckoning_ate_m','nees_median']].assign(cfg='jcbb k1')
orc=pd.read_csv(sys.argv[3])
base_k=orc[(orc['filter']=='fastslam2')&(orc.assoc=='known')][['world','clutter','seed','ate_aligned_rmse_m','dead_reckoning_ate_m','nees_median']].assign(cfg='known k1')
rows=[]
for p in glob.glob(sys.argv[2] + '/runs/*/*/result.json'):
    cfg=p.split('/')[-3]; b=p.split('/')[-2]
    m=re.match(r'(\w+)-n300-t600-c(\d+)-s(\d+)',b)
    r=json.load(open(p))
    k,a=cfg.split('-')
    rows.append(dict(world=m.group(1),clutter=float(m.group(2)),seed=int(m.group(3)),ate_aligned_rmse_m=r['ate_aligned_rmse_m'],dead_reckoning_ate_m=r['dead_reckoning_ate_m'],nees_median=r['nees_median'],cfg=f'{a} {k}'))
d=pd.concat([base_j,base_k,pd.DataFrame(rows)])
d=d.merge(sm,on=['world','clutter','seed'])
d['fail']=(d.ate_aligned_rmse_m>3*d.sm)|(d.ate_aligned_rmse_m>d.dead_reckoning_ate_m)
d.to_csv(sys.argv[2] + '/runs.csv', index=False)
def agg(g): return pd.Series(dict(n=len(g),fail=int(g.fail.sum()),mean=g.ate_aligned_rmse_m.mean(),med=g.ate_aligned_rmse_m.median(),p90=g.ate_aligned_rmse_m.quantile(0.9),nees=g.nees_median.median()))
print(d.groupby('cfg').apply(agg).round(3).to_string())
print(d.groupby(['world','cfg']).apply(agg).round(3).to_string())
