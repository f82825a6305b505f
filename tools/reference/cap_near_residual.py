"""Smooth cap unloading near the residual overlap (issue 32, sigma -> 0 of rough + cap).

The rows of test/data/cap_reference.csv stop at 0.8 delta_max; the small-sigma checks of
test_rough_cap need the smooth cap's unloading force just above the residual overlap,
where it is a small difference. Same independent solve as cap_reference.py (its Loaded
class: piecewise-linear rings, exact disc kernels), Richardson over m, 2m, 4m.

    python tools/reference/cap_near_residual.py [--m 20]   # -> stdout, csv rows

With --at F1 F2 ...: only delta_max = 2 delta_y, at those fractions of delta_max (the
shifted overlaps delta + D of test_rough_cap's shift-route references, stop 47).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cap_reference import Loaded, load_at_delta, richardson  # noqa: E402

CASES = {2.0: [0.145, 0.15, 0.16, 0.18, 0.2], 10.0: [0.53, 0.6]}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--m", type=int, default=20)
    ap.add_argument("--at", type=float, nargs="+", default=None)
    args = ap.parse_args()
    ms = [args.m, 2 * args.m, 4 * args.m]
    cases = CASES if args.at is None else {2.0: args.at}
    print("model,x,y,value,error,order")
    for dm, fracs in cases.items():
        lds = [Loaded(load_at_delta(dm, m)[0], m) for m in ms]
        res = [ld.residual() / dm for ld in lds]
        ext, err, order = richardson(res)
        print(f"residual,{dm:.6g},0,{ext:.12e},{err:.3e},{order:.3g}", flush=True)
        for r in fracs:
            q = [ld.unload_at(r * dm) for ld in lds]
            ext, err, order = richardson(q)
            print(f"unload,{dm:.6g},{r:.10g},{ext:.12e},{err:.3e},{order:.3g}", flush=True)


if __name__ == "__main__":
    main()
