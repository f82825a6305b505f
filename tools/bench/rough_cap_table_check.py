#!/usr/bin/env python3
"""Compare rough + cap hysteresis tables (egw-table's scene_hysteresis.bin) with each
other and with rel_tol 1e-7 unloading solves (doc/benchmarks.md, "Stop 43: rough + cap
builds").

usage: rough_cap_table_check.py A.bin [B.bin] [--solves N] [--rel-tol R]

A against B: max |P_A - P_B|/P(m) over every delta_max node of both tables and the
midpoints between them, each unloading curve sampled at 201 overlaps from m down to
where the loading force is 1e-6 of P(m) (P(m): the loading force at m). Against solves:
egw.solve_unload at rel_tol 1e-7 (an independent, finer computation: the tables' solves
ran at 1e-5) at a grid of turning points and overlaps, error in units of P(m).
"""
import argparse
import numpy as np
import egw


def curve_deltas(table, m, n=201):
    st = egw.HysteresisTable.new_state(())
    p_m = float(table.eval(m, st)[0])
    lo, hi = -50.0, m
    for _ in range(80):   # where the loading force falls to 1e-6 of P(m)
        mid = 0.5 * (lo + hi)
        if float(table.eval(mid, egw.HysteresisTable.new_state(()))[0]) < 1e-6 * p_m:
            lo = mid
        else:
            hi = mid
    return np.linspace(lo, m, n), p_m


def unload(table, m, deltas):
    state = np.full(deltas.shape, m)
    return table.eval(deltas, state)[0]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("a")
    ap.add_argument("b", nargs="?")
    ap.add_argument("--solves", type=int, default=0, help="turning points for solves")
    ap.add_argument("--m", type=float, nargs="*", default=[],
                    help="more turning points for solves")
    ap.add_argument("--rel-tol", type=float, default=1e-7,
                    help="rel_tol of the reference solves (default 1e-7)")
    ap.add_argument("--worst", type=int, default=0,
                    help="solves where A and B differ most, at this many turning points")
    args = ap.parse_args()
    ta = egw.HysteresisTable.read(args.a)
    if args.b:
        tb = egw.HysteresisTable.read(args.b)
        nodes = np.unique(np.concatenate([_nodes(args.a), _nodes(args.b)]))
        nodes = nodes[nodes > nodes[0]]   # (the first node: g = 0, both tables exact)
        pts = np.unique(np.concatenate([nodes, 0.5 * (nodes[1:] + nodes[:-1])]))
        worst = (0.0, None)
        diffs = []
        for m in pts:
            d, p_m = curve_deltas(ta, m)
            e = np.abs(unload(ta, m, d) - unload(tb, m, d)) / p_m
            diffs.append((e.max(), m, d[e.argmax()], p_m))
            if e.max() > worst[0]:
                worst = (e.max(), m)
        print(f"A vs B: {len(pts)} turning points x 201 overlaps: max |dP|/P(m) = "
              f"{worst[0]:.3e} (at m = {worst[1]:.3f})")
        diffs.sort(reverse=True)
        params = _params(args.a)
        opts = egw.Options(rel_tol=1e-7)
        for e, m, d, p_m in diffs[:args.worst]:
            ref = egw.solve_unload(params, float(d), float(m), opts).force
            x = np.array([d])
            print(f"largest differences: m {m:9.3f} delta {d:9.3f} A-B {e:.2e} ref {ref:.6e}"
                  f"  errA {abs(unload(ta, m, x)[0] - ref) / p_m:.2e}"
                  f"  errB {abs(unload(tb, m, x)[0] - ref) / p_m:.2e}", flush=True)
    if args.solves:
        params = _params(args.a)
        tabs = [ta] + ([tb] if args.b else [])
        m_lo, m_hi = _nodes(args.a)[0], _nodes(args.a)[-1]
        worst = [0.0] * len(tabs)
        opts = egw.Options(rel_tol=args.rel_tol)
        ms = np.linspace(m_lo, m_hi, args.solves + 2)[1:-1] * (1 + 1e-3 / np.pi)
        for m in np.concatenate([ms, args.m]):
            d_all, p_m = curve_deltas(ta, m)
            for f in (0.02, 0.1, 0.3, 0.5, 0.7, 0.85, 0.95):
                d = np.array([m - f * (m - d_all[0])])
                try:
                    ref = egw.solve_unload(params, float(d[0]), float(m), opts).force
                except egw.NotConvergedError as exc:
                    print(f"m {m:9.3f} delta {d[0]:9.3f}: the reference solve failed ({exc})")
                    continue
                line = f"m {m:9.3f} delta {d[0]:9.3f} ref {ref:.8e}"
                for k, t in enumerate(tabs):
                    e = abs(float(unload(t, m, d)[0]) - ref) / p_m
                    worst[k] = max(worst[k], e)
                    line += f"  err{'AB'[k]} {e:.2e}"
                print(line, flush=True)
        print(f"against rel_tol {args.rel_tol:g} solves: max |dP|/P(m): " +
              ", ".join(f"{'AB'[k]} {w:.3e}" for k, w in enumerate(worst)))


def _header(path_bin):
    csv = path_bin[:-4] + ".csv"
    h = {}
    for line in open(csv):
        if line.startswith("# ") and " = " in line:
            k, v = line[2:].split(" = ", 1)
            h[k.strip()] = v.strip()
    return h


def _nodes(path_bin):
    csv = path_bin[:-4] + ".csv"
    m = [float(l.split(",")[0]) for l in open(csv)
         if l[:1].isdigit() or l[:1] == "-"]
    return np.unique(m)


def _params(path_bin):
    h = _header(path_bin)
    names = {"1": "GW", "2": "E-GW", "3": "EP-GW"}
    return egw.Params(model=names[h["model"].split()[0]], radius=float(h["radius"]),
                      modulus=float(h["modulus"]), sigma=float(h["sigma"]),
                      mu=float(h["mu"]), psi=float(h["psi"]),
                      hardness_coeff=float(h["hardness_coeff"]),
                      plastic_ratio=float(h["plastic_ratio"]),
                      flow_pressure=float(h["flow_pressure"]))


if __name__ == "__main__":
    main()
