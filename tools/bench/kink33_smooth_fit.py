#!/usr/bin/env python3
"""A smooth break for tools/bench/kink33_break_loo.f90 (doc/benchmarks.md "Stop 67: kink33").

    python3 tools/bench/kink33_smooth_fit.py LOO_OUT [DEGREE]

LOO_OUT: kink33_break_loo's output with the break found by its bisection. x = m - delta_open
(sigma, delta_y = 100 sigma) at the nodes where delta_open is above the knee, fitted by least
squares with a Chebyshev polynomial of DEGREE (default 10) in t = (m/delta_y - 1.09)/0.07;
prints the fit's residuals per degree and writes LOO_OUT.smooth: "m/delta_y knee delta_b",
delta_b = max(m - fit, knee), the input for a second run with the break given.
"""
import math
import sys


def cheb(t, n):
    values = [1.0, t]
    for _ in range(2, n + 1):
        values.append(2 * t * values[-1] - values[-2])
    return values[:n + 1]


def main():
    path = sys.argv[1]
    degree = int(sys.argv[2]) if len(sys.argv) > 2 else 10
    rows = [[float(x) for x in line.split()[:4]] for line in open(path)
            if not line.startswith("#")]
    m = [r[0] for r in rows]
    knee = [r[1] for r in rows]
    opened = [r[2] for r in rows]
    sel = [i for i in range(len(m)) if opened[i] > knee[i]]

    def fit(deg):
        ts = [(m[i] - 1.09) / 0.07 for i in sel]
        y = [m[i] * 100 - opened[i] for i in sel]
        cols = [[cheb(t, deg)[j] for t in ts] for j in range(deg + 1)]
        # least squares by modified Gram-Schmidt (no numpy in the project's venv)
        n = deg + 1
        q = [c[:] for c in cols]
        r = [[0.0] * n for _ in range(n)]
        for j in range(n):
            for i in range(j):
                r[i][j] = sum(a * b for a, b in zip(q[i], q[j]))
                q[j] = [a - r[i][j] * b for a, b in zip(q[j], q[i])]
            r[j][j] = math.sqrt(sum(a * a for a in q[j]))
            q[j] = [a / r[j][j] for a in q[j]]
        qy = [sum(a * b for a, b in zip(q[j], y)) for j in range(n)]
        c = [0.0] * n
        for j in reversed(range(n)):
            c[j] = (qy[j] - sum(r[j][i] * c[i] for i in range(j + 1, n))) / r[j][j]

        def f(mm):
            return sum(a * b for a, b in zip(c, cheb((mm - 1.09) / 0.07, deg)))
        return f, [y[k] - f(m[i]) for k, i in enumerate(sel)]

    for deg in (4, 6, 8, 10, 12):
        _, res = fit(deg)
        print("degree %2d: residual rms %.2e, max %.2e sigma (%d nodes)" % (
            deg, math.sqrt(sum(x * x for x in res) / len(res)), max(abs(x) for x in res),
            len(sel)))
    f, _ = fit(degree)
    with open(path + ".smooth", "w") as out:
        for mi, ki in zip(m, knee):
            out.write("%.17g %.17g %.17g\n" % (mi, ki, max(mi * 100 - f(mi), ki)))


if __name__ == "__main__":
    main()
