#!/usr/bin/env python3
"""Run block.inp in CalculiX with egw's rough-flat pressure-overclosure curve and check the
result against p_G. block.inp presses a steel block with a uniform 1, 10 and 100 MPa
(steps 1-3) onto a rigid base (frictionless, free lateral expansion): at the end of each
step the contact pressure must be the load over the current area at every slave node,
and the separation d of the summit base plane must give p_G(d) = that pressure, where
p_G(d) = C sigma^1.5 F_3/2(d/sigma) (doc/theory.md section 3) is computed here independently
of egw (quadrature of F_3/2, checked against doc/theory.md's values), with
C = mu E/(2 sigma sqrt(2R)) from the curve's header.
Usage: run.py FLAT_INC [CCX]   (FLAT_INC written by calculix_flat.f90; CCX default ccx)."""
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

LOADS = (1.0, 10.0, 100.0)  # MPa, the *DLOAD of block.inp's steps 1, 2, 3
E_BLOCK, NU_BLOCK = 210000.0, 0.3  # MPa, block.inp's *ELASTIC
# Tolerances. Pressure at the slave nodes: the load over the current area, which the free
# lateral (Poisson) expansion enlarges by (1 + nu q/E)^2, to CalculiX's equilibrium
# residual and 7-digit printing. p_G at the measured separation: the curve's
# linear-interpolation error (rel_tol = 1e-3) plus the above; the printed overclosure
# (7 digits) moves p_G by ~1e-6.
TOL_PRESSURE, TOL_PG = 1e-5, 1.2e-3
MAX_PAIRS = 200  # CalculiX 2.20 keeps a tabular curve in xiso(200) (springforc_n2f.f)


def f32(h, n=4000):
    """F_3/2(h) = int_0^inf t^1.5 phi(t + h) dt = int_0^inf 2 u^4 phi(u^2 + h) du (t = u^2:
    smooth integrand), Simpson's rule on [0, u_max] where phi has underflowed."""
    u_max = math.sqrt(max(40.0 - h, 0.0)) + 1.0
    g = lambda u: 2 * u**4 * math.exp(-0.5 * (u * u + h) ** 2) / math.sqrt(2 * math.pi)
    w = u_max / n
    s = g(0.0) + g(u_max) + sum((4 if i % 2 else 2) * g(i * w) for i in range(1, n))
    return s * w / 3


def dat_tables(dat):
    """time -> {"contact stress": rows, "relative contact displacement": rows} of a .dat
    file, rows = the numbers after the node number."""
    tables, rows = {}, None
    for line in dat.splitlines():
        m = re.match(r"\s*(contact stress|relative contact displacement) .*time\s+(\S+)", line)
        if m:
            rows = tables.setdefault(float(m.group(2)), {}).setdefault(m.group(1), [])
        elif rows is not None and re.match(r"\s+\d+\s", line):
            rows.append([float(v) for v in line.split()[1:]])
        elif line.strip():
            rows = None
    return tables


def check_step(table, load, d_c, c, sigma):
    """Checks at the end of one load step (table: that time's entry of dat_tables)."""
    if not table or len(table) != 2:
        print(f"calculix: no contact output for load {load:g} MPa: FAILED")
        return False
    pressure = [r[0] for r in table["contact stress"]]
    overclosure = [abs(r[0]) for r in table["relative contact displacement"]]  # -penetration
    ok = len(pressure) == 9 and len(overclosure) == 9
    d = d_c - sum(overclosure) / len(overclosure)           # separation of the base planes
    p_g = c * sigma**1.5 * f32(d / sigma)
    p_area = load / (1 + NU_BLOCK * load / E_BLOCK) ** 2
    checks = [("contact pressure / (load/area) (worst node)",
               max(pressure, key=lambda p: abs(p / p_area - 1)) / p_area, TOL_PRESSURE),
              ("p_G(separation) / contact pressure", p_g * len(pressure) / sum(pressure),
               TOL_PG)]
    print(f"load {load:g} MPa: separation {d:.6e} mm = {d / sigma:.4f} sigma, "
          f"overclosure spread {max(overclosure) - min(overclosure):.1e} mm")
    for what, ratio, tol in checks:
        good = abs(ratio - 1) < tol
        ok &= good
        print(f"  {what} = {ratio:.7f} (tolerance {tol:g}) {'ok' if good else 'FAILED'}")
    return ok


def main():
    flat, ccx = sys.argv[1], (sys.argv[2] if len(sys.argv) > 2 else "ccx")
    for h, ref in ((0.0, 0.430019993662260), (2.0, 6.64817762358709e-3)):
        assert abs(f32(h) / ref - 1) < 1e-10, "F_3/2 quadrature is off"  # doc/theory.md section 2
    header, pairs = [], []
    with open(flat) as f:
        for line in f:
            if re.match(r"\s*[-+.\d]", line):
                pairs.append(tuple(float(v) for v in line.split(",")))
            else:
                header.append(line.rstrip("\n"))
    meta = {k: float(v) for k, v in re.findall(r"\b(E|sigma|mu|R) = (\S+?),?(?=\s|$)",
                                               " ".join(header))}
    c = meta["mu"] * meta["E"] / (2 * meta["sigma"] * math.sqrt(2 * meta["R"]))
    # The curve is written with shift (calculix_flat.f90): overclosure measured from d_c,
    # the separation where p_G has fallen to rel_tol p_G(0), because CalculiX creates
    # node-to-surface contact springs only where the surfaces touch or penetrate. The
    # model's surfaces are the summit base planes at separation d_c.
    if len(pairs) > MAX_PAIRS or any(len(v.strip()) > 20 for line in open(flat)
                                     if re.match(r"\s*[-+.\d]", line)
                                     for v in line.split(",")):
        print(f"calculix: {len(pairs)} pairs or a field > 20 characters: CalculiX reads at "
              f"most {MAX_PAIRS} pairs of 20-character fields: FAILED")
        return 1
    m = re.search(r"d_c = (\S+?)\s", " ".join(header) + " ")
    if not m or pairs[0] != (0.0, 0.0):
        print("calculix: the curve is not shifted (no d_c in the header): FAILED")
        return 1
    d_c = float(m.group(1))
    with tempfile.TemporaryDirectory() as work:
        shutil.copy(flat, os.path.join(work, "flat.inc"))
        shutil.copy(os.path.join(os.path.dirname(os.path.abspath(__file__)), "block.inp"), work)
        subprocess.run([ccx, "-i", "block"], cwd=work, check=True, stdout=subprocess.DEVNULL)
        with open(os.path.join(work, "block.dat")) as f:
            dat = f.read()
    ok = True
    tables = dat_tables(dat)
    for step, load in enumerate(LOADS, start=1):          # step k ends at time k
        end = [t for t in tables if abs(t - step) < 1e-6]
        ok &= check_step(tables.get(end[0]) if end else None, load, d_c, c, meta["sigma"])
    print("calculix example: " + ("all checks passed" if ok else "FAILED"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
