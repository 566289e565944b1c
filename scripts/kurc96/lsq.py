import sys
rows=[l.split() for l in open('sys.argv[1]')]
P_span=[322,481,1038,1124,2142,2087]; Z_span=[316,470,1015,1099,2104,2029]
P_zb=[434,471,520,579,1079,701]; Z_zb=[578,585,647,702,1128,805]
P_m=[348,341,323,408,684,451]; Z_m=[2015,1940,1930,1958,2043,1958]
def solve(A,b):
    n=len(A[0]); M=[[sum(A[k][i]*A[k][j] for k in range(len(A))) for j in range(n)] for i in range(n)]
    v=[sum(A[k][i]*b[k] for k in range(len(A))) for i in range(n)]
    for i in range(n):
        piv=M[i][i]
        for j in range(i+1,n):
            f=M[j][i]/piv
            for c in range(n): M[j][c]-=f*M[i][c]
            v[j]-=f*v[i]
    x=[0]*n
    for i in reversed(range(n)):
        x[i]=(v[i]-sum(M[i][c]*x[c] for c in range(i+1,n)))/M[i][i]
    return x
def report(name,A,b,x):
    errs=[(sum(a*xx for a,xx in zip(r,x))-bb)/bb for r,bb in zip(A,b)]
    print(name,["%.4g"%v for v in x],"mean|err| %.3f max %.3f"%(sum(map(abs,errs))/len(errs),max(map(abs,errs))))
# span (ms): a per poly, b per span, c per insert step -> ms
A=[];b=[]
for r,p,z in zip(rows,P_span,Z_span):
    po,sp,ins=float(r[1]),float(r[2]),float(r[3])
    A.append([po,sp,ins]);b.append(p); A.append([po,sp,0]);b.append(z)
x=solve(A,b); report("span a,b,c (ms)",A,b,x)
A2=[[r[0]] for r in A[::1]]
x1=solve([[a[0]] for a in A],b); report("span a only",[[a[0]] for a in A],b,x1)
x2=solve([[a[0],a[2]] for a in A],b); report("span a,c",[[a[0],a[2]] for a in A],b,x2)
# zbuf: d per pixel, g per init location (N^2=160000)
A=[];b=[]
for r,p,z in zip(rows,P_zb,Z_zb):
    px=float(r[4]); A.append([px,0]);b.append(p); A.append([px,160000]);b.append(z)
x=solve(A,b); report("zbuf d,g (ms)",A,b,x)
# merge: base + compare*slope + copy*slope
A=[];b=[]
for r,p,z in zip(rows,P_m,Z_m):
    pr0,prc,prs,zx0,zxc=map(float,r[6:11])
    A.append([prc,prs]);b.append(p-pr0); A.append([zxc,0]);b.append(z-zx0)
x=solve(A,b); 
bb=[P_m[i//2] if i%2==0 else Z_m[i//2] for i in range(12)]
base=[float(rows[i//2][6]) if i%2==0 else float(rows[i//2][9]) for i in range(12)]
errs=[(base[i]+sum(a*xx for a,xx in zip(A[i],x))-bb[i])/bb[i] for i in range(12)]
print("merge compare,copy (us)",x,"mean %.3f max %.3f"%(sum(map(abs,errs))/12,max(map(abs,errs))))
