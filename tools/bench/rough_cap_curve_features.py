#!/usr/bin/env python3
"""Where the unloading curves of a rough + cap contact are not smooth, from solves alone
(doc/benchmarks.md, "Stop 46: where the rough + cap grids go").

The hysteresis gap of turning point m at overlap delta, as the table stores it (up to
the build's c_turn factor, within the solves' tolerance of 1):

    g(delta; m) = (P_load(delta) - P_unload(delta; m)) / P_load(m)

from egw.solve and egw.solve_unload at --tol (default 1e-6). Two modes:

  along a curve (default): g at x = m - delta = 0, h, 2h, ... (h = --step; --x-range) for each
  turning point of --m, with 1e4 h**2 times its second difference (g''); the x where
  the third difference is largest are the curve's kinks in g'' (printed last);

  across turning points (--at-delta D ...): g(D; m) for each m of --m at the fixed
  overlaps D, as the delta_max interpolation sees it at fixed s on the tail, and
  P_load(m) (g P_load(m) is the hysteresis force itself).

The parameters are the README's rough + cap benchmark row (egw-table --radius
810569.469138702, i.e. R = 405284.7 per contact, E* = 1, sigma = 1, mu = 4,
p_y = 0.01: delta_y = 100 sigma); --model and --psi as egw-table's.

usage: rough_cap_curve_features.py --model E-GW --m 150 200 [--step 2]
       rough_cap_curve_features.py --model EP-GW --psi 1 --at-delta -1.2 -0.2 \
           --m 0 0.01 0.02 0.04 0.08 0.16
"""
import argparse
import numpy as np
import egw


def gap(params, opts, delta, m, p_m, force=False):
    p_l = egw.solve(params, float(delta), opts).force
    p_u = egw.solve_unload(params, float(delta), float(m), opts).force
    return ((p_l - p_u) / p_m, p_u / p_m) if force else (p_l - p_u) / p_m


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--model", default="E-GW")
    ap.add_argument("--psi", type=float, default=0.0)
    ap.add_argument("--m", type=float, nargs="+", required=True, help="turning points")
    ap.add_argument("--step", type=float, default=2.0, help="x step along a curve")
    ap.add_argument("--x-range", type=float, nargs=2, default=None,
                    help="x from, to along a curve (default 0 to m)")
    ap.add_argument("--skip-delta", type=float, default=None,
                    help="no kinks reported within 4 of this overlap (e.g. the loading "
                         "curve's own onset of the cap)")
    ap.add_argument("--at-delta", type=float, nargs="*", default=[],
                    help="fixed overlaps: g across the turning points --m")
    ap.add_argument("--tol", type=float, default=1e-6)
    args = ap.parse_args()
    params = egw.Params(model=args.model, radius=810569.469138702 / 2, modulus=1.0,
                        sigma=1.0, mu=4.0, psi=args.psi, flow_pressure=0.01)
    opts = egw.Options(rel_tol=args.tol)
    p_ms = {m: egw.solve(params, float(m), opts).force for m in args.m}
    if args.at_delta:
        # (P_load(m) too: g P_load(m) = P_load(delta) - P_unload(delta; m), the hysteresis
        # force itself)
        print("P_load(m): " + "  ".join(f"m {m:g} {p_ms[m]:.6g}" for m in args.m))
        for d in args.at_delta:
            print(f"delta {d:g}: " + "  ".join(
                f"m {m:g} g {gap(params, opts, d, m, p_ms[m]):.5f}" for m in args.m),
                flush=True)
        return
    for m in args.m:
        lo, hi = (0.0, m) if args.x_range is None else args.x_range
        xs = np.arange(lo, min(hi, m), args.step)
        g, f = np.array([gap(params, opts, m - x, m, p_ms[m], True) for x in xs]).T
        d2 = np.zeros_like(g)
        d2[1:-1] = (g[2:] - 2 * g[1:-1] + g[:-2]) / args.step**2
        print(f"turning point m = {m:g}: x, delta, g, 1e4 g'', P_unload/P_load(m)")
        for x, gi, di, fi in zip(xs, g, d2, f):
            print(f"  {x:9.3f} {m - x:9.3f} {gi:.6f} {1e4 * di:9.4f} {fi:.5f}")
        # kinks of g'' where the unloading force is still above 5 % of P(m) (below, the
        # knee near the residual overlap, which the two-piece map holds at s = 1/2)
        d3 = np.abs(np.diff(d2))
        d3[(f[:-1] < 0.05) | (np.arange(d3.size) < 1) | (np.arange(d3.size) >= d3.size - 1)] = 0
        if args.skip_delta is not None:
            d3[np.abs(m - xs[:-1] - args.skip_delta) < 4] = 0
        top = np.argsort(d3)[::-1][:3]
        print(f"  m = {m:g}: largest changes of g'' between x = " +
              ", ".join(f"{xs[k]:.1f} and {xs[k + 1]:.1f} ({d3[k]:.1e})" for k in top
                        if d3[k] > 0), flush=True)


if __name__ == "__main__":
    main()
