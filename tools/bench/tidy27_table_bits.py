"""tidy27: the bits a build writes, to compare two libegw builds (a refactor must leave
them unchanged). Writes 1-D (Hertz, E-GW), universal (E-GW) and hysteresis (Hertz + cap,
EP-GW) tables as binary and CSV into DIR, reads each back and writes it again (*.again).

    EGW_CACHE_DIR=off EGW_LIBRARY=/path/a/libegw.so python tidy27_table_bits.py /tmp/a
    EGW_CACHE_DIR=off EGW_LIBRARY=/path/b/libegw.so python tidy27_table_bits.py /tmp/b
    for f in /tmp/a/*; do cmp "$f" /tmp/b/"${f##*/}"; done
"""
import os, sys
import egw
d = sys.argv[1]
os.makedirs(d, exist_ok=True)
cases = {
    "hertz": egw.Params(model="Hertz", radius=1e-3, modulus=1e9),
    "egw": egw.Params(model="E-GW", radius=1e-3, modulus=1e9, sigma=1e-7, mu=4.0),
}
for name, p in cases.items():
    t = egw.Table.build(p, -5e-7 if name != "hertz" else 0.0, 2e-6, 1e-4)
    for fmt in ("binary", "csv"):
        f = os.path.join(d, f"{name}.{fmt}")
        t.write(f, fmt)
        egw.Table.read(f).write(f + ".again", fmt)
u = egw.UniversalTable.build(egw.Params(model="E-GW"), 2.0, 8.0, -3.0, 10.0, 1e-3)
for fmt in ("binary", "csv"):
    f = os.path.join(d, f"universal.{fmt}")
    u.write(f, fmt)
    egw.UniversalTable.read(f).write(f + ".again", fmt)
for name, p in {"cap": egw.Params(model="Hertz", radius=1e-3, modulus=1e9, flow_pressure=1e7),
                "epgw": egw.Params(model="EP-GW", radius=1e-3, modulus=1e9, sigma=1e-7, mu=4.0,
                                   psi=1.0)}.items():
    h = egw.HysteresisTable.build(p, -3e-7 if name == "epgw" else 0.0,
                                  3e-6 if name == "epgw" else 1e-4, 1e-3)
    for fmt in ("binary", "csv"):
        f = os.path.join(d, f"hyst_{name}.{fmt}")
        h.write(f, fmt)
        egw.HysteresisTable.read(f).write(f + ".again", fmt)
print("written", len(os.listdir(d)))
