"""tidy27: what the Python package answers to bad height maps and table calls (messages,
exception types, values), to compare two versions of python/src/egw: run it with each and
diff the outputs (temporary-directory names differ).

    python tidy27_python_answers.py > main.out
    PYTHONPATH=python/src EGW_LIBRARY=build's libegw.so python tidy27_python_answers.py > branch.out
"""
import numpy as np, os, tempfile, egw
from egw import topography as topo
print(egw.__file__)
out = []
def run(name, f):
    try:
        r = f(); out.append((name, "ok", type(r).__name__))
    except Exception as e:
        out.append((name, type(e).__name__, str(e)))
d = tempfile.mkdtemp()
np.save(os.path.join(d, "a.npy"), np.ones((2, 5)))
np.save(os.path.join(d, "nan.npy"), np.full((4, 4), np.nan))
np.save(os.path.join(d, "ok.npy"), np.random.default_rng(1).normal(size=(8, 8)))
for fn in ("a.npy", "nan.npy", "ok.npy"):
    p = os.path.join(d, fn)
    for ps in (1.0, -1.0, (1.0, np.inf), 1e-200, None):
        for unit in (None, "m", "parsec"):
            run(f"read {fn} {ps} {unit}", lambda: topo.read_height_map(p, ps, unit))
z = np.random.default_rng(2).normal(size=(8, 8))
for arr in (z, np.ones(5), np.ma.masked_array(z, mask=z > 1), np.where(z > 1, np.nan, z), z * 1e120):
    for ps in (None, 1.0, -1.0, 1e-200, (1.0, 2.0)):
        for unit in (None, "m", "parsec"):
            run(f"hm {arr.shape} {ps} {unit}", lambda: topo.height_map(arr, ps, unit))
# tables
p = egw.Params(model="Hertz", radius=1e-3, modulus=1e9)
t = egw.Table.build(p, 0.0, 1e-5, 1e-4)
f = os.path.join(d, "t.bin"); t.write(f); t2 = egw.Table.read(f)
run("table eval", lambda: t2.eval(np.linspace(0, 1e-5, 7)).__repr__())
out.append(("table eval values", repr(t2.eval(np.linspace(0, 1e-5, 7)))))
run("table write bad fmt", lambda: t.write(f, "xml"))
run("table read missing", lambda: egw.Table.read(os.path.join(d, "none.bin")))
run("table build bad", lambda: egw.Table.build(p, 1.0, 0.0, 1e-4))
run("table build nan", lambda: egw.Table.build(p, 0.0, float("nan"), 1e-4))
u = None
run("univ read missing", lambda: egw.UniversalTable.read(os.path.join(d, "none.bin")))
ph = egw.Params(model="Hertz", radius=1e-3, modulus=1e9, flow_pressure=1e7)
h = egw.HysteresisTable.build(ph, 0.0, 1e-4, 1e-3)
fh = os.path.join(d, "h.csv"); h.write(fh, "csv"); h2 = egw.HysteresisTable.read(fh)
st = h2.new_state(5)
out.append(("hyst", repr(h2.eval(np.linspace(0, 1e-4, 5), st))))
run("hyst build bad", lambda: egw.HysteresisTable.build(ph, 1.0, 0.0, 1e-3))
run("hyst write bad", lambda: h.write(fh, "lammps"))
run("hyst read csv as table", lambda: egw.HysteresisTable.read(f))
run("table build dict", lambda: egw.Table.build({}, 0.0, 1e-5, 1e-4))
run("table build options", lambda: egw.Table.build(p, 0.0, 1e-5, 1e-4, options="x"))
run("table build str delta", lambda: egw.Table.build(p, "a", 1e-5, 1e-4))
run("hyst build None", lambda: egw.HysteresisTable.build(None, 0.0, 1e-4, 1e-3))
run("hyst build options", lambda: egw.HysteresisTable.build(ph, 0.0, 1e-4, 1e-3, options=3))
run("univ build dict", lambda: egw.UniversalTable.build({}, 2.0, 8.0, -3.0, 10.0))
run("table read int", lambda: egw.Table.read(123))
run("table write format 7", lambda: t.write(f, 7))
run("univ read table file", lambda: egw.UniversalTable.read(f))
h.close()
run("closed write", lambda: h.write(fh))
for o in out: print(o)
