#!/usr/bin/env python3
"""Run in.collide in LAMMPS on each section of an egw pair_style table file (written by
lammps_tables.f90) and check the collisions. Scene: two glass beads, density 2500 kg/m^3,
approach speed 0.2 m/s; radii, R and E are read from the table's section headers.
  EGW_1 (Hertz): max overlap and contact time against the closed forms, restitution 1.
  EGW_2 (E-GW): restitution 1 (elastic) and max overlap where the table's energy column
                equals the initial kinetic energy of the relative motion.
Usage: run.py TABLE [LMP]   (LMP: the LAMMPS binary, default lmp). Exit 1 on failure."""
import math
import os
import re
import subprocess
import sys
import tempfile

RHO, V0 = 2500.0, 0.2
# Tolerances. The file's linear-interpolation error is <= rel_tol * P_ref = 1e-5 P_ref
# (P_ref = P(2 um) for Hertz, 6.7x the peak force of this collision), so the elastic
# energy is off by <= 7e-5 and the overlap by <= 3e-5 (delta ~ energy^(2/5)); the time
# step t_c/5000 adds ~4e-7. Restitution: Verlet conserves energy to ~(pi/5000)^2.
TOL_HERTZ, TOL_ENERGY, TOL_RESTITUTION = 2e-4, 2e-4, 1e-5


def sections(path):
    """Section name -> dict(rsum, radius, modulus, n, rows[(r, energy, force)])."""
    out, meta, name = {}, {}, None
    with open(path) as f:
        lines = f.read().splitlines()
    for i, line in enumerate(lines):
        m = re.search(r"model (\S+), R = (\S+), E = (\S+),", line)
        if m:
            meta = {"model": m.group(1), "radius": float(m.group(2)),
                    "modulus": float(m.group(3))}
        m = re.search(r"R1 \+ R2 = (\S+)", line)
        if m:
            meta["rsum"] = float(m.group(1))
        if re.fullmatch(r"EGW_\d+", line.strip()):
            name = line.strip()
            n = int(lines[i + 1].split()[1])
            rows = [tuple(map(float, l.split()[1:4])) for l in lines[i + 3:i + 3 + n]]
            out[name] = dict(meta, n=n, rows=rows)
    return out


def collide(lmp, table, name, s, workdir):
    """Run LAMMPS; return (max overlap, contact time between delta = 0 crossings,
    restitution, reduced mass)."""
    mass = RHO * 4 / 3 * math.pi * (s["rsum"] / 2) ** 3
    m_eff = mass / 2
    d_h = (15 * m_eff * V0**2 / (16 * s["modulus"] * math.sqrt(s["radius"]))) ** 0.4
    dt = math.sqrt(m_eff / (2 * s["modulus"] * math.sqrt(s["radius"] * d_h))) * math.pi / 5000
    r_start = max(s["rows"][-1][0], s["rsum"]) + 1e-3 * d_h  # outside cutoff and delta = 0
    steps = int(2 * (r_start - s["rsum"]) / V0 / dt + 3 * 5000)
    traj = os.path.join(workdir, name + ".traj")
    cmd = [lmp, "-in", os.path.join(os.path.dirname(os.path.abspath(__file__)), "in.collide"),
           "-echo", "none", "-nocite", "-log", os.path.join(workdir, name + ".log")]
    for k, v in dict(table=table, section=name, n=max(s["n"], 1000), rsum=s["rsum"],
                     r0=r_start, mass=mass, v0=V0, dt=dt, steps=steps, out=traj).items():
        cmd += ["-var", k, repr(v) if isinstance(v, float) else str(v)]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    t, d, v = [], [], []
    with open(traj) as f:
        for line in f:
            if not line.startswith("#"):
                a, b, c = line.split()
                t.append(int(a) * dt); d.append(float(b)); v.append(float(c))
    assert d[-1] < min(0.0, s["rsum"] - s["rows"][-1][0]), name + ": still in contact"
    cross = [t[i] + dt * d[i] / (d[i] - d[i + 1]) for i in range(len(d) - 1)
             if (d[i] <= 0) != (d[i + 1] <= 0)]
    return max(d), cross[1] - cross[0], -v[-1] / V0, m_eff, d_h


def energy_at(rows, r):
    """Energy column at distance r (linear between the file's rows; r ascending)."""
    for (r0, e0, _), (r1, e1, _) in zip(rows, rows[1:]):
        if r0 <= r <= r1:
            return e0 + (e1 - e0) * (r - r0) / (r1 - r0)
    raise ValueError("r outside the table")


def main():
    table, lmp = sys.argv[1], (sys.argv[2] if len(sys.argv) > 2 else "lmp")
    ok = True
    with tempfile.TemporaryDirectory() as work:
        # LAMMPS reads a "UNITS:" tag on a potential file's first line as a unit style;
        # egw's "# UNITS: consistent ..." is not one, so drop that tag from a copy.
        copy = os.path.join(work, "egw_pair.table")
        with open(table) as f, open(copy, "w") as g:
            text = f.read().split("\n", 1)
            g.write(text[0].replace("UNITS:", "units") + "\n" + text[1])
        secs = sections(copy)
        for name, s in secs.items():
            d_max, t_c, e, m_eff, d_h = collide(lmp, copy, name, s, work)
            if s["model"] == "Hertz":
                t_h = 2 * d_h / V0 * 0.4 * math.gamma(0.4) * math.sqrt(math.pi) / math.gamma(0.9)
                checks = [("max overlap / Hertz", d_max / d_h, TOL_HERTZ),
                          ("contact time / Hertz", t_c / t_h, TOL_HERTZ)]
            else:
                e_max = energy_at(s["rows"], s["rsum"] - d_max)
                checks = [("energy at max overlap / KE", e_max / (m_eff * V0**2 / 2), TOL_ENERGY)]
            checks.append(("restitution", e, TOL_RESTITUTION))
            print(f"{name} ({s['model']}): max overlap {d_max:.6e} m, "
                  f"time with delta > 0 {t_c:.6e} s")
            for what, ratio, tol in checks:
                good = abs(ratio - 1) < tol
                ok &= good
                print(f"  {what} = {ratio:.8f} (tolerance {tol:g}) {'ok' if good else 'FAILED'}")
    print("lammps example: " + ("all checks passed" if ok else "FAILED"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
