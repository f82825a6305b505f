#!/usr/bin/env python3
"""Would rough + cap curves need fewer delta_max (and s) nodes stored as a log form of u?
(doc/benchmarks.md "Stop 67: logu33"; offline, from one built table's node values.)

    python3 tools/bench/logu33_loo.py CSV [full]

CSV: an egw-table hysteresis CSV of format 6 (u = P/P_load(m) on the two-piece map at the
same n_s s nodes on every curve; its header gives the knees, tail_length and the loading
table). Stored quantities compared, each interpolated across delta_max and mapped back to u:
  u      the force ratio (format 6)
  ln u   ln(max(u, 1e-300)) (u = 0 floored: the stencil then sees -690)
  ln r   ln(P/P_load(delta)) = ln u - ln(P_load(delta)/P_load(m)) (EP-GW's -h; undefined
         below the loading table's cut-off, where P_load = 0: such nodes are skipped)
  ln(u+a) with a = 1e-3 and 1e-4 (the local force goal's own floor: an error e in it is
         e (u + a) in u, i.e. ~e of max(u, 1e-3) for a = 1e-3; finite at u = 0)
  u^2/3  local31's v (a Hertzian front linear in delta; not a log form, for comparison)
Part 1 (delta_max): on every q-th node (q = 2, 4, 8; the last node kept), the left-out
nodes' values from the table's stencil (interval j with m_j <= m < m_j+1; 4 nodes from
j - 1 or 6 from j - 2, clamped at the ends: doc/formats.md), at each fixed s node; q = 1 is
leave-one-out (j -+ 1, j -+ 2 (, j -+ 3)). Error |u~ - u|/max(u, 1e-3) at the left-out
nodes, worst per band of u ([0.1, 1], [0.01, 0.1), [0.003, 0.01), and [0, 0.003) split at
1e-3: below it the weighted build asks rel_tol of P(m) only under 5e-4, no reference) and
m < 1.3 | >= 1.3 delta_y (delta_y = 100: README's E-GW + cap), the count above 1e-4.
With "full" the stencil curves are evaluated as the table does: the knee interpolated with
the same weights, s recomputed from x = m - delta with it, each curve's cubic Hermite in s
(slopes: the stored ones for u, (du/ds)/u for ln u, ...) there; ln r stays at fixed s in
both modes (its slope in s would need dP_load/ddelta).
Part 2 (s): on every curve, each interior s node not at a break (1/2, 3/4) dropped and its
value from the cubic Hermite over its two neighbours (values and slopes in the
representation): |u~ - u|/max(u, 1e-3) per band, near the knee (s in [0.45, 0.5)), on the
second piece, in the tail (s > 3/4); the interval is twice today's, so the error at today's
spacing is ~1/16 of it where the data are smooth.
Part 3: an adaptive count of delta_max nodes per representation for 1e-4 (and 5e-5), the
errors at u >= 1e-3 only (the goal's references' floor): from
8-node intervals, each halved while its left-out nodes' worst exceeds the bound (q 8 -> 4 ->
2 -> today's 1); an interval still failing at q = 2 counts as today's nodes (a floor).
"""
import bisect
import math
import sys

DELTA_Y = 100.0
BANDS = [(0.1, 2.0), (0.01, 0.1), (0.003, 0.01), (0.001, 0.003), (-1.0, 0.001)]
BAND_NAMES = ["[0.1, 1]", "[0.01, 0.1)", "[0.003, 0.01)", "[0.001, 0.003)", "[0, 0.001)"]
U_GOAL = 1e-3   # part 3 counts errors at u >= this (the references' floor, stop 66)
M_SPLIT = 1.3 * DELTA_Y
FLOOR = 1e-300


def read(path):
    rows, knees, loading, head = [], [], [], {}
    for line in open(path):
        if line.startswith("# knee ="):
            knees.append(float(line.split("=")[1]))
        elif line.startswith("# loading = "):
            loading.append([float(x) for x in line.split("=")[1].split(",")])
        elif line.startswith("# ") and " = " in line:
            k, v = line[2:].split(" = ", 1)
            head[k.strip()] = v.strip()
        elif line[0] not in "#d":
            rows.append([float(x) for x in line.split(",")])
    n_m, n_s = int(head["n_delta_max"]), int(head["n_s"])
    assert len(rows) == n_m * n_s and len(knees) == n_m
    ms = [rows[j * n_s][0] for j in range(n_m)]
    s = [rows[i][2] for i in range(n_s)]
    u = [[rows[j * n_s + i][3] for i in range(n_s)] for j in range(n_m)]
    slope = [[rows[j * n_s + i][4] for i in range(n_s)] for j in range(n_m)]
    return (ms, s, u, slope, knees, float(head["tail_length"]), loading,
            int(head["loading.n_log"]))


class Loading:
    """P_load(delta): cubic Hermite of the loading table's nodes (force, stiffness), in
    ln P on the first n_log nodes' intervals (the log part below 0); 0 below the cut-off."""

    def __init__(self, nodes, n_log):
        self.d = [r[0] for r in nodes]
        self.p = [r[1] for r in nodes]
        self.k = [r[2] for r in nodes]
        self.n_log = n_log

    def __call__(self, x):
        d = self.d
        if x < d[0]:
            return 0.0
        if x >= d[-1]:
            return self.p[-1] + self.k[-1] * (x - d[-1])
        i = min(bisect.bisect_right(d, x) - 1, len(d) - 2)
        h = d[i + 1] - d[i]
        if i + 1 < self.n_log:
            y0, y1 = math.log(self.p[i]), math.log(self.p[i + 1])
            s0, s1 = self.k[i] / self.p[i], self.k[i + 1] / self.p[i + 1]
            return math.exp(hermite(y0, y1, s0 * h, s1 * h, (x - d[i]) / h))
        return hermite(self.p[i], self.p[i + 1], self.k[i] * h, self.k[i + 1] * h,
                       (x - d[i]) / h)


def hermite(y0, y1, d0, d1, t):
    """Cubic Hermite on [0, 1] with end slopes d0, d1 (already times the interval)."""
    t2, t3 = t * t, t * t * t
    return ((2 * t3 - 3 * t2 + 1) * y0 + (t3 - 2 * t2 + t) * d0 + (-2 * t3 + 3 * t2) * y1
            + (t3 - t2) * d1)


def x_of_s(s, m, k, tail):
    """x = m - delta on the two-piece map (knee k at s = 1/2, delta = 0 at 3/4)."""
    if s <= 0.5:
        return (m - k) * 2.0 * s
    if s <= 0.75:
        return (m - k) + k * 4.0 * (s - 0.5)
    return m + tail * 4.0 * (s - 0.75)


def s_of_x(x, m, k, tail):
    if x <= m - k:
        return 0.5 * x / (m - k)
    if x <= m:
        return 0.5 + 0.25 * (x - (m - k)) / k if k > 0 else 0.75
    return 0.75 + 0.25 * (x - m) / tail


def dx_ds(s, m, k, tail):
    return 2.0 * (m - k) if s < 0.5 else (4.0 * k if s < 0.75 else 4.0 * tail)


def weights(xs, x):
    w = []
    for a in range(len(xs)):
        v = 1.0
        for b in range(len(xs)):
            if b != a:
                v *= (x - xs[b]) / (xs[a] - xs[b])
        w.append(v)
    return w


class Rep:
    """A stored quantity f(u; m, delta) and its inverse."""

    def __init__(self, name, fwd, inv, dfdu):
        self.name, self.fwd, self.inv, self.dfdu = name, fwd, inv, dfdu


def representations(load):
    def lnr_f(u, m, d):
        pd = load(d)
        if pd <= 0.0:
            return None
        return math.log(max(u, FLOOR)) - math.log(pd / load(m))

    def lnr_i(f, m, d):
        return math.exp(min(f, 700.0)) * load(d) / load(m)

    reps = [Rep("u", lambda u, m, d: u, lambda f, m, d: f, lambda u: 1.0),
            Rep("ln u", lambda u, m, d: math.log(max(u, FLOOR)),
                lambda f, m, d: math.exp(min(f, 700.0)), lambda u: 1.0 / max(u, FLOOR)),
            Rep("ln r", lnr_f, lnr_i, lambda u: 1.0 / max(u, FLOOR))]
    for a in (1e-3, 1e-4):
        reps.append(Rep("ln(u+%g)" % a, lambda u, m, d, a=a: math.log(max(u, 0.0) + a),
                        lambda f, m, d, a=a: math.exp(min(f, 700.0)) - a,
                        lambda u, a=a: 1.0 / (max(u, 0.0) + a)))
    reps.append(Rep("u^2/3", lambda u, m, d: max(u, 0.0) ** (2.0 / 3.0),
                    lambda f, m, d: max(f, 0.0) ** 1.5,
                    lambda u: (2.0 / 3.0) * max(u, 1e-300) ** (-1.0 / 3.0)))
    return reps


def band_of(u):
    return next(b for b, (lo, hi) in enumerate(BANDS) if lo <= u < hi)


def stencil(coarse, m, width):
    n = len(coarse)
    j = max(q for q in range(n - 1) if coarse[q] <= m)
    back = 1 if width == 4 else 2
    f = min(max(j - back, 0), n - width)
    return list(range(f, f + width))


class Tally:
    def __init__(self):
        self.worst = {}
        self.over = {}
        self.count = {}

    def add(self, key, e):
        if e > self.worst.get(key, (-1.0, None))[0]:
            self.worst[key] = (e, None)
        self.count[key] = self.count.get(key, 0) + 1
        if e > 1e-4:
            self.over[key] = self.over.get(key, 0) + 1

    def cell(self, key):
        if key not in self.worst:
            return "-"
        return "%.1e (%d/%d)" % (self.worst[key][0], self.over.get(key, 0), self.count[key])


def values_at_fixed_s(rep, ms, s, u, knees, tail):
    """The stored quantity at every node; None where undefined."""
    out = []
    for j, m in enumerate(ms):
        row = []
        for i, si in enumerate(s):
            d = m - x_of_s(si, m, knees[j], tail)
            row.append(rep.fwd(u[j][i], m, d))
        out.append(row)
    return out


def curve_slopes(rep, ms, s, u, slope, knees, tail):
    """d(stored)/dx at every node (the stored du/dx tail_length over tail_length; ln r:
    not used, its slope would need dP_load/ddelta)."""
    return [[None if rep.name == "ln r" else rep.dfdu(u[j][i]) * slope[j][i] / tail
             for i in range(len(s))] for j in range(len(ms))]


def hermite_curve(vals, slopes, s, si, m, k, tail):
    """A curve's cubic Hermite at si, its slopes times dx/ds of the interval's piece."""
    n = len(s)
    i = min(bisect.bisect_right(s, si) - 1, n - 2)
    h = s[i + 1] - s[i]
    g = dx_ds(0.5 * (s[i] + s[i + 1]), m, k, tail) * h
    return hermite(vals[i], vals[i + 1], slopes[i] * g, slopes[i + 1] * g, (si - s[i]) / h)


def part1(reps, ms, s, u, slope, knees, tail, full):
    n_m = len(ms)
    results = {}
    for rep in reps:
        f = values_at_fixed_s(rep, ms, s, u, knees, tail)
        fs = curve_slopes(rep, ms, s, u, slope, knees, tail) if full else None
        for width in (4, 6):
            for q in (1, 2, 4, 8):
                tally = Tally()
                per_node = {}
                if q == 1:
                    left = list(range(width // 2, n_m - width // 2))
                else:
                    keep = list(range(0, n_m, q))
                    if keep[-1] != n_m - 1:
                        keep.append(n_m - 1)
                    left = [j for j in range(n_m) if j not in set(keep)]
                for j in left:
                    m = ms[j]
                    if q == 1:
                        half = width // 2
                        idx = [j + o for o in range(-half, half + 1) if o != 0]
                    else:
                        idx = [keep[c] for c in stencil([ms[k] for k in keep], m, width)]
                    w = weights([ms[k] for k in idx], m)
                    kt = sum(wk * knees[k] for wk, k in zip(w, idx))
                    kt = min(max(kt, 0.0), 0.99 * m)
                    worst_here = 0.0
                    for i, si in enumerate(s):
                        if si == 0.0:
                            continue
                        d = m - x_of_s(si, m, knees[j], tail)
                        if full and rep.name != "ln r":
                            st = s_of_x(m - d, m, kt, tail)
                            vals = [hermite_curve(f[k], fs[k], s, min(st, 1.0), ms[k],
                                                  knees[k], tail) for k in idx]
                        else:
                            vals = [f[k][i] for k in idx]
                        if any(v is None for v in vals) or f[j][i] is None:
                            continue
                        ut = rep.inv(sum(wk * v for wk, v in zip(w, vals)), m, d)
                        e = abs(ut - u[j][i]) / max(u[j][i], 1e-3)
                        if not e < 1e300:
                            e = 1e300
                        side = 0 if m < M_SPLIT else 1
                        tally.add((band_of(u[j][i]), side), e)
                        if u[j][i] >= U_GOAL:
                            worst_here = max(worst_here, e)
                    per_node[j] = worst_here
                results[(rep.name, width, q)] = (tally, per_node)
    return results


def part2(reps, ms, s, u, slope, knees, tail):
    """Drop each interior s node (not a break) and Hermite over its neighbours."""
    zones = [("s < 0.45", lambda x: x < 0.45), ("[0.45, 0.5)", lambda x: 0.45 <= x < 0.5),
             ("(0.5, 0.75)", lambda x: 0.5 < x < 0.75), ("tail > 0.75", lambda x: x > 0.75)]
    out = {}
    for rep in reps:
        if rep.name == "ln r":
            continue
        f = values_at_fixed_s(rep, ms, s, u, knees, tail)
        tal = Tally()
        for j, m in enumerate(ms):
            for i in range(1, len(s) - 1):
                a, b = s[i - 1], s[i + 1]
                if s[i] in (0.5, 0.75) or a < 0.5 < b or a < 0.75 < b:
                    continue
                sl = []
                for q in (i - 1, i + 1):
                    sp = 0.5 * (a + b)
                    du = slope[j][q] * dx_ds(sp, m, knees[j], tail) / tail
                    sl.append(rep.dfdu(u[j][q]) * du)
                h = b - a
                v = hermite(f[j][i - 1], f[j][i + 1], sl[0] * h, sl[1] * h, (s[i] - a) / h)
                d = m - x_of_s(s[i], m, knees[j], tail)
                ut = rep.inv(v, m, d)
                e = abs(ut - u[j][i]) / max(u[j][i], 1e-3)
                if not e < 1e300:
                    e = 1e300
                z = next(k for k, (_, test) in enumerate(zones) if test(s[i]))
                tal.add((band_of(u[j][i]), z), e)
        out[rep.name] = tal
    return zones, out


def part3(results, ms, reps, bound):
    """Adaptive node count from stride-8 intervals halved while their error > bound."""
    n_m = len(ms)
    counts = {}
    for rep in reps:
        for width in (4, 6):
            nodes_lo = nodes_hi = 0
            floor_hit = 0
            for a in range(0, n_m - 1, 8):
                b = min(a + 8, n_m - 1)

                def err(q, lo, hi):
                    per = results[(rep.name, width, q)][1]
                    return max((per.get(j, 0.0) for j in range(lo + 1, hi)), default=0.0)

                def split(q, lo, hi):
                    nonlocal floor_hit
                    if hi - lo <= 1:
                        return 1
                    if err(q, lo, hi) <= bound:
                        return 1
                    if q == 2:
                        floor_hit += 1
                        return hi - lo
                    mid = lo + q // 2
                    return split(q // 2, lo, min(mid, hi)) + (split(q // 2, mid, hi)
                                                              if mid < hi else 0)

                n = split(8, a, b)
                if ms[a] < M_SPLIT:
                    nodes_lo += n
                else:
                    nodes_hi += n
            counts[(rep.name, width)] = (nodes_lo + 1, nodes_hi, floor_hit)
    return counts


def main():
    path = sys.argv[1]
    full = len(sys.argv) > 2 and sys.argv[2] == "full"
    ms, s, u, slope, knees, tail, loading, n_log = read(path)
    load = Loading(loading, n_log)
    reps = representations(load)
    n_lo = sum(1 for m in ms if m < M_SPLIT)
    print("%s: %d x %d nodes (%d below 1.3 delta_y), tail_length %.4f, %s" % (
        path, len(ms), len(s), n_lo, tail, "full (knee + Hermite in s)" if full
        else "fixed s"))
    zeros = sum(1 for row in u for v in row if v <= 0.0)
    small = sum(1 for row in u for v in row if 0.0 < v < 1e-6)
    print("u <= 0 at %d nodes, 0 < u < 1e-6 at %d; u's least %.3e" % (
        zeros, small, min(v for row in u for v in row)))
    below = sum(1 for j, m in enumerate(ms) for si in s
                if load(m - x_of_s(si, m, knees[j], tail)) <= 0.0)
    print("nodes below the loading cut-off (ln r undefined): %d" % below)
    print("how much u changes between neighbouring curves at one s (|ln(u_j+1/u_j)|, both "
          "> 0), per band of u: median, 99th percentile, max")
    for b, name in enumerate(BAND_NAMES):
        r = sorted(abs(math.log(u[j + 1][i] / u[j][i])) for j in range(len(ms) - 1)
                   for i in range(len(s)) if u[j][i] > 0 and u[j + 1][i] > 0
                   and band_of(u[j][i]) == b)
        if r:
            print("  %-14s %.2e  %.2e  %.2e  (%d pairs)" % (
                name, r[len(r) // 2], r[int(0.99 * (len(r) - 1))], r[-1], len(r)))
    results = part1(reps, ms, s, u, slope, knees, tail, full)
    print("\nPart 1: delta_max interpolation, worst |u~ - u|/max(u, 1e-3) at left-out nodes "
          "(above 1e-4 / points), m < 1.3 | >= 1.3 delta_y")
    print("rep          pts q  " + "  ".join("%-36s" % b for b in BAND_NAMES))
    for rep in reps:
        for width in (4, 6):
            for q in (1, 2, 4, 8):
                tally = results[(rep.name, width, q)][0]
                cells = ["%s | %s" % (tally.cell((b, 0)), tally.cell((b, 1)))
                         for b in range(len(BANDS))]
                print("%-12s %d  %d  %s" % (rep.name, width, q,
                                             "  ".join("%-36s" % c for c in cells)))
    zones, s_res = part2(reps, ms, s, u, slope, knees, tail)
    print("\nPart 2: s, each interior node dropped, Hermite over 2 intervals; worst per band "
          "(above 1e-4 / points) per zone of s")
    for z, (zname, _) in enumerate(zones):
        print("zone %s" % zname)
        for rep in reps:
            if rep.name not in s_res:
                continue
            tal = s_res[rep.name]
            print("  %-12s %s" % (rep.name, "  ".join("%-22s" % tal.cell((b, z))
                                                      for b in range(len(BANDS)))))
    # slopes d ln u/ds around the knee and in the tail
    print("\nslopes: |du/ds| and |d ln u/ds| = |du/ds|/u, median over curves, at s nodes")
    for target in (0.3, 0.45, 0.49, 0.4995, 0.5, 0.6, 0.74, 0.76, 0.9, 1.0):
        i = min(range(len(s)), key=lambda q: abs(s[q] - target))
        du, dl, uu = [], [], []
        for j, m in enumerate(ms):
            sp = s[i] if i + 1 < len(s) else s[i] - 1e-9
            d = slope[j][i] * dx_ds(sp, m, knees[j], tail) / tail
            du.append(abs(d))
            uu.append(u[j][i])
            if u[j][i] > 0:
                dl.append(abs(d) / u[j][i])
        du.sort(), dl.sort(), uu.sort()
        print("  s = %.5f: u median %.2e (min %.2e)  |du/ds| %.2e  |d ln u/ds| %.2e "
              "(max %.2e; %d of %d curves with u = 0)" % (
                  s[i], uu[len(uu) // 2], uu[0], du[len(du) // 2],
                  dl[len(dl) // 2] if dl else float("nan"), dl[-1] if dl else float("nan"),
                  len(ms) - len(dl), len(ms)))
    for bound in (1e-4, 5e-5):
        counts = part3(results, ms, reps, bound)
        print("\nPart 3: adaptive delta_max nodes for %.0e at u >= %g (today's %d = %d + %d; "
              "floor hits = 2-node intervals still over at q = 2)" % (
                  bound, U_GOAL, len(ms), n_lo, len(ms) - n_lo))
        for rep in reps:
            for width in (4, 6):
                lo, hi, fl = counts[(rep.name, width)]
                print("  %-12s %d pts: %d (%d below 1.3 delta_y + %d), floor hits %d" % (
                    rep.name, width, lo + hi, lo, hi, fl))


if __name__ == "__main__":
    main()
