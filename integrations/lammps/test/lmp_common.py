"""Shared by the LAMMPS plugin's test suites (run_tests.py): the runner of decks through
build/lammps/lmp, their RESULT and thermo lines, the collision deck's beads, egw-restitution
as the reference e, pair_style granular's line for the same beads, and the verdicts the
suites share (velocity and spin gaps of two runs; refusals of bad input)."""
import math
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", ".."))
LMP = os.path.join(ROOT, "build", "lammps", "lmp")
REST = os.path.join(ROOT, "build", "lammps", "egw-restitution")

# the collision deck's beads: R = 1 mm glass, E = 70 GPa, nu = 0.22, 2500 kg/m^3
E, NU, RAD, RHO = 70e9, 0.22, 1e-3, 2500.0
E_STAR = E / (2 * (1 - NU * NU))           # like types: E* = E / (2 (1 - nu^2))
R_STAR = RAD / 2
M_STAR = RHO * 4 / 3 * math.pi * RAD ** 3 / 2
V = 0.1                                     # each bead; approach speed 2 V
DT = 4e-8                                   # ~ t_c / 200 at 2 V (Hertz, t_c ~ 8.3 us)
TMP = tempfile.mkdtemp(prefix="egw-lammps-test-")


def lmp(deck, np=1, _timeout=600, **var):
    """Run a deck; return (returncode, combined output). _timeout [s]: a run that takes
    longer raises subprocess.TimeoutExpired (the test fails)."""
    args = [LMP, "-np", str(np), "-in", os.path.join(HERE, deck), "-log", "none",
            "-nocite"]
    for k, v in var.items():
        args += ["-var", k, str(v)]
    p = subprocess.run(args, cwd=TMP, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       text=True, timeout=_timeout)
    return p.returncode, p.stdout


def result(out):
    m = re.findall(r"^RESULT (.*)$", out, re.M)
    if not m:
        raise RuntimeError("no RESULT line; output tail:\n" + "\n".join(out.splitlines()[-15:]))
    return [float(x) for x in m[-1].split()]


def thermo(out):
    """Rows of numbers of the thermo output (step ke pe etotal ...)."""
    rows = []
    for line in out.splitlines():
        f = line.split()
        if f and all(re.match(r"^-?[0-9.]+(e[-+]?[0-9]+)?$", x) for x in f) and len(f) >= 3:
            rows.append([float(x) for x in f])
    return rows


def collision(pstyle, pcoeff, yoff=0.0, wz=0.0, nrun=6000, np=1, newton="on", thermo_every=1000,
              n1=None, restart=0, rfile="restart.bin", r2=RAD, check="yes", pairlocal=0, wx=0.0,
              gap=2e-5):
    n1 = nrun // 2 if n1 is None else n1
    # the beads start gap (20 um) apart along the line they first touch on (~2500 steps)
    x0 = (math.sqrt((RAD + r2) ** 2 - yoff ** 2) + gap) / 2
    return lmp("collision.in", np=np, pstyle=pstyle, pcoeff=pcoeff, v=V, x0=x0, yoff=yoff, wz=wz,
               d2=2 * r2, check=check,
               dt=DT, n1=n1, n2=nrun - n1, newton=newton, thermo=thermo_every,
               restart=restart, rfile=rfile, pairlocal=pairlocal, wx=wx)


def velocity_spin_gaps(a, b):
    """Of two collision.in RESULT lines (vx1 vy1 vx2 vy2 w1 w2): the largest velocity
    difference over the approach scale V, and the largest spin difference times RAD over V."""
    return (max(abs(x - y) for x, y in zip(a[:4], b[:4])) / V,
            max(abs(x - y) for x, y in zip(a[4:], b[4:])) / (V / RAD))


def pair_write(pstyle, pcoeff, path, np=1):
    """pairwrite.in: pair_write of types 1 and 2 (1 and 0.5 mm beads) into path. Returns ""
    when the run ended well and wrote path, else its exit code and first ERROR line."""
    rc, out = lmp("pairwrite.in", np=np, pstyle=pstyle, pcoeff=pcoeff, file=path)
    if rc != 0 or not os.path.exists(path):
        return "rc %d: %s" % (rc, [l for l in out.splitlines() if "ERROR" in l][:1])
    return ""


def pair_write_rows(path):
    """The numbered rows of a pair_write file, split (index, r, energy, force)."""
    return [l.split() for l in open(path) if re.match(r"^\s+\d+\s", l)]


def restitution_of(out):
    vx1, vy1, vx2, vy2, w1, w2 = result(out)
    return (vx2 - vx1) / (2 * V)


def reference_e(model, sigma, mu, psi, tol=1e-6, R=R_STAR, m=M_STAR):
    p = subprocess.run([REST, str(model), repr(E_STAR), repr(R), repr(sigma), repr(mu),
                        repr(psi), "0.6", "54", repr(m), repr(2 * V), repr(tol)],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if p.returncode:
        raise RuntimeError(p.stdout)
    return float(p.stdout)


GRANULAR = ("granular", "hertz/material {E} {e} {nu} tangential mindlin NULL 0.0 {mut} "
            "damping coeff_restitution")


def granular(e=1.0, mut=0.0, Ey=E):
    return GRANULAR[1].format(E=Ey, e=e, nu=NU, mut=mut)


# an analytic rough-flat law p(u) = P0 exp(-u/U0) tabulated on 61 nodes (exact: the law's
# interpolant is linear in ln p, and so is this law)
LAW_P0, LAW_U0 = 1e7, 0.5e-6


def write_user_law(path, scale=1.0, modulus=None):
    """The analytic law as a user's CSV (u, pressure; optional '# modulus' line), pressures
    times scale."""
    with open(path, "w") as f:
        f.write("u,pressure\n")
        if modulus is not None:
            f.write(f"# modulus = {modulus!r}\n")
        for k in range(61):
            u = -1e-6 + k * 1e-7
            f.write(f"{u!r},{scale * LAW_P0 * math.exp(-u / LAW_U0)!r}\n")


def refusal_fault(rc, out, key):
    """What went wrong in a run that must stop with a LAMMPS ERROR naming key: "" when it
    did (a non-zero exit, key in the first ERROR line, no crash), else its exit code and
    first ERROR line."""
    err = [l for l in out.splitlines() if "ERROR" in l]
    crashed = re.search(r"Segmentation|signal|backtrace|core dumped|Abort", out)
    if rc == 0 or not err or key not in err[0] or crashed:
        return f"rc {rc}, {err[:1]}"
    return ""


def refusal_verdict(n, bad):
    """(passed, message) of n bad-input cases, bad the faults of those not refused."""
    return not bad, f"{n - len(bad)}/{n} refused with the keyword named" + (
        "; " + "; ".join(bad) if bad else "")
