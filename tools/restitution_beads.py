#!/usr/bin/env python3
"""e(v) of head-on bead-bead impacts, 1e-4 to 10 m/s, for glass and steel beads
(doc/restitution.md): roughness alone (EP-GW, no bulk yield), bulk alone (Hertz + the
flow-pressure cap), both (the rough model with flow_pressure, where the library serves it),
and the cap model's e(v/v_y) beside Thornton's closed form.

    PYTHONPATH=python/src EGW_LIBRARY=<libegw.so> python tools/restitution_beads.py
    (or the installed package: /work/main/.venv/bin/python tools/restitution_beads.py)

Writes doc/restitution/beads.csv, doc/restitution/cap_vs_thornton.csv and
doc/restitution/beads.png (with matplotlib). Materials: the table MATERIALS (sources in
doc/restitution.md).
"""
import argparse
import csv
import math
import os
import subprocess

import numpy as np

import egw

# Bead pairs of equal beads of radius r: R* = r/2, m* = m/2, E* = E/(2(1 - nu^2)).
# sigma_bead: rms summit height of one bead (sqrt(pi/2) Ra); the pair's sigma = sqrt(2) x.
MATERIALS = {
    "glass": dict(radius=1.0e-3, density=2500.0, youngs=70e9, poisson=0.22,
                  yield_stress=5.5e9 / 2.8, hardness=5.5e9, sigma_bead=30e-9,
                  summit_radius=10e-6),
    "steel": dict(radius=1.0e-3, density=7830.0, youngs=210e9, poisson=0.30,
                  yield_stress=2.0e9, hardness=7.5e9, sigma_bead=math.sqrt(math.pi / 2) * 0.1e-6,
                  summit_radius=20e-6),
}
MU = 4.0           # Greenwood-Tripp mu (summit density x radius; doc/restitution.md)
K = 0.6            # ZMC hardness coefficient (egw's default)
SPEEDS = np.geomspace(1e-4, 10.0, 26)


def pair(mat):
    r, rho = mat["radius"], mat["density"]
    m = 4.0 / 3.0 * math.pi * r**3 * rho
    estar = mat["youngs"] / (2.0 * (1.0 - mat["poisson"] ** 2))
    sigma = math.sqrt(2.0) * mat["sigma_bead"]
    # psi from delta_ep = sigma/psi^2 = (3 pi K H/(4 E*))^2 beta (doc/theory.md section 3)
    d_ep = (3 * math.pi * K * mat["hardness"] / (4 * estar)) ** 2 * mat["summit_radius"]
    psi = math.sqrt(sigma / d_ep)
    return dict(radius=r / 2, mass=m / 2, modulus=estar, sigma=sigma, psi=psi,
                flow_pressure=1.6 * mat["yield_stress"])


def first_yield_speed(p):
    return math.sqrt(16 / 15 * (math.pi / 2) ** 5 * p["flow_pressure"] ** 5 * p["radius"] ** 3
                     / (p["mass"] * p["modulus"] ** 4))


def curve(params, mass, options=None):
    """e at SPEEDS (nan where a solve fails: the note says where and why), None where the
    library refuses the model itself."""
    out, why = [], []
    for v in SPEEDS:
        try:
            r = egw.restitution(params, mass=mass, velocity=float(v), options=options)
            out.append((float(r.e), float(r.max_overlap)))
        except egw.InvalidArgumentError as exc:  # the model is not served by this library
            return None, str(exc)
        except egw.EgwError as exc:
            out.append((math.nan, math.nan))
            why.append(f"v = {v:.3g}: {str(exc)[:120]}")
    return out, "; ".join(why)


def thornton(x):
    """Thornton (1997) e at x = v_y/v (x <= 1)."""
    return (math.sqrt(6 * math.sqrt(3) / 5) * math.sqrt(1 - x * x / 6)
            * (x / (x + 2 * math.sqrt(6 / 5 - x * x / 5))) ** 0.25)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default="doc/restitution")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        commit = "unknown"
    rows, notes, curves = [], [], {}
    for name, mat in MATERIALS.items():
        p = pair(mat)
        vy = first_yield_speed(p)
        notes.append(f"{name}: R* = {p['radius']:.3g} m, m* = {p['mass']:.3g} kg, "
                     f"E* = {p['modulus']:.3g} Pa, sigma = {p['sigma']:.3g} m, "
                     f"psi = {p['psi']:.3g}, mu = {MU}, p_y = {p['flow_pressure']:.3g} Pa, "
                     f"v_y = {vy:.3g} m/s")
        models = {
            "rough": lambda: egw.Params(model="EP-GW", radius=p["radius"], modulus=p["modulus"],
                                sigma=p["sigma"], mu=MU, psi=p["psi"], hardness_coeff=K),
            "bulk": lambda: egw.Params(model="Hertz", radius=p["radius"], modulus=p["modulus"],
                               flow_pressure=p["flow_pressure"]),
            "both": lambda: egw.Params(model="EP-GW", radius=p["radius"], modulus=p["modulus"],
                               sigma=p["sigma"], mu=MU, psi=p["psi"], hardness_coeff=K,
                               flow_pressure=p["flow_pressure"]),
        }
        for label, make in models.items():
            try:
                params = make()
            except egw.EgwError as exc:  # not served (yet) by this library
                notes.append(f"{name} {label}: not computed ({exc})")
                continue
            # rough + cap: its unloading solves reach rel_tol 1e-4 at every speed here, 1e-6
            # only up to ~2 v_y (doc/theory.md section 12, "Rough spheres with the cap")
            opts = egw.Options(rel_tol=1e-4) if label == "both" else None
            es, why = curve(params, p["mass"], opts)
            if es is None:
                notes.append(f"{name} {label}: not computed ({why})")
                continue
            if label == "both":
                notes.append(f"{name} {label}: solves at rel_tol 1e-4")
            if why:
                notes.append(f"{name} {label}: failed at {why}")
            curves[(name, label)] = es
            for v, (e, dm) in zip(SPEEDS, es):
                rows.append((name, label, v, e, dm, dm / p["sigma"], v / vy))
    path = os.path.join(args.out, "beads.csv")
    with open(path + ".tmp", "w", newline="") as fh:
        fh.write(f"# tools/restitution_beads.py at commit {commit}, egw {egw.version()}, "
                 f"library {os.environ.get('EGW_LIBRARY', 'of the installed package')}\n")
        for n in notes:
            fh.write(f"# {n}\n")
        w = csv.writer(fh)
        w.writerow(["material", "model", "v", "e", "delta_max", "delta_max_over_sigma",
                    "v_over_vy"])
        for r in rows:
            w.writerow([r[0], r[1]] + [f"{x:.6g}" for x in r[2:]])
    os.replace(path + ".tmp", path)
    # the cap model in its universal units (R = E* = 1, p_y = 2/pi, m* = 16/15: v_y = 1)
    unit = egw.Params(model="Hertz", radius=1.0, modulus=1.0, flow_pressure=2 / math.pi)
    path2 = os.path.join(args.out, "cap_vs_thornton.csv")
    with open(path2 + ".tmp", "w", newline="") as fh:
        fh.write(f"# tools/restitution_beads.py at commit {commit}\n")
        w = csv.writer(fh)
        w.writerow(["v_over_vy", "e_cap", "e_thornton"])
        for x in (1.5, 2, 3, 5, 10, 20, 50, 100):
            e = float(egw.restitution(unit, mass=16 / 15, velocity=float(x)).e)
            w.writerow([x, f"{e:.4f}", f"{thornton(1 / x):.4f}"])
    os.replace(path2 + ".tmp", path2)
    for n in notes:
        print(n)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no figure")
        return
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    for ax, name in zip(axes, MATERIALS):
        for label, style in (("rough", "b-"), ("bulk", "r-"), ("both", "k--")):
            if (name, label) in curves:
                ax.semilogx(SPEEDS, [e for e, _ in curves[(name, label)]], style,
                            label={"rough": "roughness alone (EP-GW)",
                                   "bulk": "bulk alone (Hertz + cap)",
                                   "both": "both (rough + cap)"}[label])
        ax.set_title(f"{name} beads, r = {MATERIALS[name]['radius'] * 1e3:g} mm")
        ax.set_xlabel("impact speed v [m/s]")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(loc="lower left", fontsize=8)
    axes[0].set_ylabel("coefficient of restitution e")
    fig.tight_layout()
    png = os.path.join(args.out, "beads.png")
    fig.savefig(png + ".tmp.png", dpi=110)
    os.replace(png + ".tmp.png", png)


if __name__ == "__main__":
    main()
