#!/usr/bin/env python3
"""A/B of two builds of the plugin against pair granular on one deck, for a shared machine.
  python3 integrations/lammps/bench/ab_cpu.py ROUNDS DECK [NAME VALUE ...]
Interleaved rounds of: granular (runner A), egw with runner A, egw with runner B. Per run
the CPU time (user + sys of lmp and mpiexec, from the children's rusage: other sessions'
load on the shared cores inflates wall time far more than CPU time) minus the same deck's
CPU time with its runs set to 0 steps (20 for the pour, whose averaging needs them; the
set-up, best of 2), and LAMMPS's wall-clock loop and pair times; each round's ratios.
With 2 ranks compare wall times (mpich's ranks wait busily: CPU time counts the waits).
Environment: EGW_AB_A, EGW_AB_B the two runners (build/lammps/lmp of two builds; B
defaults to this tree's), EGW_AB_MODEL extra egw variables 'k=v,k=v' (e.g.
'model=EP-GW,sig=1e-3,plastic=psi 1'), EGW_AB_NP ranks (default 1)."""
import os, re, resource, subprocess, sys, tempfile
rounds = int(sys.argv[1]); deck = os.path.abspath(sys.argv[2]); extra = sys.argv[3:]
egwvars = [kv.split("=", 1) for kv in os.environ.get("EGW_AB_MODEL", "").split(",") if kv]
ev = [a for kv in egwvars for a in ("-var", kv[0], kv[1])]
ex = [a for k in range(0, len(extra), 2) for a in ("-var", extra[k], extra[k + 1])]
ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", ".."))
R = {"A": os.environ.get("EGW_AB_A", ""),
     "B": os.environ.get("EGW_AB_B") or os.path.join(ROOT, "build", "lammps", "lmp")}
if not R["A"]:
    sys.exit("ab_cpu: set EGW_AB_A to the runner of the build to compare with")
np_ = os.environ.get("EGW_AB_NP", "1")
def cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN); return r.ru_utime + r.ru_stime
def run(lmp, law, zero=False):
    xx = list(ex)
    if zero:   # set-up only: every run of the deck with 0 steps (the first -var of a name wins)
        xx = [a for k in range(0, len(ex), 3) for a in ex[k:k + 3]
              if ex[k + 1] not in ("nrun", "n1", "n2")]
        z = "20" if deck.endswith("pour.in") else "0"    # the pour's averaging needs nrun >= 20
        xx += ["-var", "nrun", z, "-var", "n1", "0", "-var", "n2", "0"]
    args = ([lmp, "-np", np_, "-in", deck, "-var", "law", law] + xx +
            (ev if law == "egw" else []) + ["-log", "none", "-nocite"])
    c0 = cpu()
    with tempfile.TemporaryDirectory(prefix="egw-ab-") as tmp:
        out = subprocess.run(args, cwd=tmp, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             text=True).stdout
    c = cpu() - c0
    loops = [float(x) for x in re.findall(r"Loop time of ([0-9.eE+-]+)", out)]
    pairs = [float(x) for x in re.findall(r"^Pair\s+\|\s*\S+\s*\|\s*([0-9.eE+-]+)", out, re.M)]
    if not loops: print(out[-2000:]); sys.exit(1)
    return c, sum(loops), sum(pairs)
setup = {k: min(run(R["A" if k == "gran" else k], "granular" if k == "gran" else "egw",
                     True)[0] for _ in range(2)) for k in ("gran", "A", "B")}
print("A = " + R["A"] + ", B = " + R["B"])
print("set-up CPU (0 steps): " + ", ".join(f"{k} {v:.2f} s" for k, v in setup.items()), flush=True)
for r in range(rounds):
    g = run(R["A"], "granular"); b = run(R["A"], "egw"); n = run(R["B"], "egw")
    cg, cb, cn = g[0] - setup["gran"], b[0] - setup["A"], n[0] - setup["B"]
    la = open("/proc/loadavg").read().split()[0]
    print(f"round {r + 1} load {la}: CPU loop gran {cg:.2f} A {cb:.2f} B {cn:.2f} -> /gran "
          f"A {cb / cg:.3f} B {cn / cg:.3f}, B/A {cn / cb:.3f} | wall loop gran {g[1]:.2f} "
          f"A {b[1]:.2f} B {n[1]:.2f} (/gran {b[1] / g[1]:.3f} {n[1] / g[1]:.3f}) | pair gran "
          f"{g[2]:.2f} A {b[2]:.2f} B {n[2]:.2f} (/gran {b[2] / g[2]:.3f} "
          f"{n[2] / g[2]:.3f})", flush=True)
