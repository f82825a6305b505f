"""beyond31 (stop 65): the rough + cap continuation through the C and Python doors.

A table from egw-table (doc/benchmarks.md "Stop 65: beyond31", the cost paragraph: E-GW + cap
to 70 delta_y at 1e-3, sigma/delta_y 0.2, reach 1.18 X) read by egw.HysteresisTable;
loading to m = 1.1 X and 1.5 X, then unloading at 0.95 m: OutOfRangeWarning or not.
Run: EGW_LIBRARY=X/libegw.so PYTHONPATH=python/src python tools/bench/beyond31_python_door.py
    [TABLE.bin] (run from the directory holding t35/egw01/, or give the path)."""
import sys
import warnings
import numpy as np
import egw
t = egw.HysteresisTable.read(sys.argv[1] if len(sys.argv) > 1 else "t35/egw01/scene_hysteresis.bin")
X = t.info().delta_max
for mult in (1.1, 1.5):
    m = mult * X
    state = np.array([0.9 * X])
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        f_load, _ = t.eval(np.array([m]), state)
        state = np.array([m])
        f_un, _ = t.eval(np.array([0.95 * m]), state)
    print(f"m = {mult} X: loading {f_load[0]:.6e}, unloading at 0.95 m {f_un[0]:.6e}, "
          f"warnings: {[type(x.message).__name__ for x in w]}")
