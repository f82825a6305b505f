"""Stop 58 (edge24): rough_cap_force_error.f90's rows against its rel_tol 1e-9 rows.

    python3 tools/bench/rough_cap_force_error.py REFS.txt ROWS.txt...

REFS: rows at rel_tol 1e-9; prints, per (ratio, x, rel_tol) of ROWS, the force's
relative error, its estimate, their ratio, and BAD where the error exceeds rel_tol.
"""
import sys
def load(f):
    d={}
    for l in open(f):
        if 'error' in l: continue
        t=[x.strip() for x in l.split(',')]
        if len(t)<6: continue
        d[(float(t[0]),float(t[1]),float(t[2]))]=(float(t[3]),float(t[4]))
    return d
ref=load(sys.argv[1]); d={}
for f in sys.argv[2:]: d.update(load(f))
worst={}
for k in sorted(d):
    r=(k[0],k[1],1e-9)
    if r not in ref: continue
    F,est=d[k]; e=F/ref[r][0]-1
    print(f"{k[0]:.0e} {k[1]:5.1f} {k[2]:.0e} err {e:+.2e} est {est:.2e} err/est {abs(e)/est:6.1f} {'BAD' if abs(e)>k[2] else ''}")
