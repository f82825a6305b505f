"""Per curve of a format-6 rough + cap hysteresis CSV (u = force_ratio on the two-piece
map, the knee at s = 1/2): how many s nodes lie on the first piece (0 < s < 1/2) and how
many of them have u below 3e-2, 1e-2 and 1e-3 (the front, where front33's tighter unloading
solves would run; doc/benchmarks.md "Stop 67: front33"). A proxy for a curve's solves: the
table stores the shared s grid, not each curve's own bisection.

    python3 tools/bench/front33_front_nodes.py CSV [M_LO_OVER_DY]
"""
import sys


def main():
    path = sys.argv[1]
    m_lo = float(sys.argv[2]) if len(sys.argv) > 2 else 0.0
    curves = {}
    dy = 100.0  # README's scene: delta_y = 100 sigma
    with open(path) as f:
        header = f.readline()
        for line in f:
            if line.startswith("#"):
                continue
            m, _, s, u, _ = (float(v) for v in line.split(","))
            curves.setdefault(m, []).append((s, u))
    n_s = len(next(iter(curves.values())))
    rows = []
    for m in sorted(curves):
        if m < m_lo*dy:
            continue
        pts = curves[m]
        first = [(s, u) for s, u in pts if 0.0 < s < 0.5]
        c = [sum(1 for s, u in first if u < lim) for lim in (3e-2, 1e-2, 1e-3)]
        rows.append((m/dy, len(first), *c))
    print(f"{path}: {len(rows)} curves (m >= {m_lo} delta_y), {n_s} s nodes per curve")
    print("m/dy  first-piece nodes  u<3e-2  u<1e-2  u<1e-3")
    for r in rows[:: max(1, len(rows)//12)]:
        print(f"{r[0]:8.4f} {r[1]:5d} {r[2]:5d} {r[3]:5d} {r[4]:5d}")
    n = len(rows)
    tot = [sum(r[k] for r in rows) for k in range(1, 5)]
    print(f"mean per curve: first piece {tot[0]/n:.1f}, u<3e-2 {tot[1]/n:.1f}, "
          f"u<1e-2 {tot[2]/n:.1f}, u<1e-3 {tot[3]/n:.1f} of {n_s}; "
          f"u<3e-2 and u>=1e-3: {(tot[1]-tot[3])/n:.1f}")


if __name__ == "__main__":
    main()
