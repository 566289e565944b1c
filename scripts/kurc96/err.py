import sys
import yaml
pub=yaml.safe_load(open('configs/papers/kurc96.yaml'))['tables']
errs=[];lines=[]
for l in open(sys.argv[1]):
    t,row,col,v=l.split(); v=float(v)
    p=pub.get(t,{}).get('rows',{}).get(row,{}).get(col)
    if p is None: lines.append(f"| {t} | {row} | {col} | {v:.6g} | — | — |"); continue
    e=(v-p)/p; errs.append((abs(e),t,row,col)); lines.append(f"| {t} | {row} | {col} | {v:.6g} | {p} | {e:+.3f} |")
print("\n".join(lines))
print("visible cells",len(errs),"mean |rel err| %.3f"%(sum(e[0] for e in errs)/len(errs)),"worst",max(errs))
t2=[e for e in errs if e[1]=='2']; print("table2 mean %.3f worst"%(sum(e[0] for e in t2)/len(t2)), max(t2))
t1=[e for e in errs if e[1]=='1']; print("table1 mean %.3f worst"%(sum(e[0] for e in t1)/len(t1)), max(t1))
