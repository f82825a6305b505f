"""CPU cost and duration of egw.time_step per model (issue 32: egw_time_step with the cap).

The cases: a glass pair of the DEM loop (R = 1 mm beads, E = 70 GPa, nu = 0.22, sigma = 1 um,
mu 4; Hertz, GW, E-GW, EP-GW psi 2, with p_y = 1 GPa for the capped ones at 3 v_y).
Compare libraries by running this script once per library, alternated in the same rounds
(stops 60-62, doc/benchmarks.md "Stop 62: yield28"):

    for r in 1 2 3; do for lib in A.so B.so; do
      EGW_LIBRARY=$lib PYTHONPATH=python/src .venv/bin/python tools/bench/time_step_cost.py "EP-GW+cap 3vy"
    done; done

(no arguments: every case). Prints the duration (to compare bits) and user + sys CPU of the
call; ratios between libraries mean something only within one round.
"""
import math
import resource
import sys

import egw


def cases():
    """(name, params, mass, velocity) of each case."""
    radius, modulus, nu, density, sigma = 1e-3, 70e9, 0.22, 2500.0, 1e-6
    mass = density*4.0/3.0*math.pi*radius**3/2.0
    e_star = modulus/(2.0*(1.0 - nu*nu))
    rough = dict(radius=radius/2.0, modulus=e_star, sigma=sigma, mu=4.0)
    p_y = 1e9
    hertz_cap = egw.Params(model="Hertz", radius=radius/2.0, modulus=e_star, flow_pressure=p_y)
    v_y = egw.first_yield(hertz_cap, mass=mass).speed
    return [
        ("Hertz", egw.Params(model="Hertz", radius=radius/2.0, modulus=e_star), mass, 0.1),
        ("Hertz+cap 3vy", hertz_cap, mass, 3.0*v_y),
        ("Hertz+cap 0.5vy", hertz_cap, mass, 0.5*v_y),
        ("GW", egw.Params(model="GW", **rough), mass, 0.01),
        ("E-GW", egw.Params(model="E-GW", **rough), mass, 0.01),
        ("EP-GW", egw.Params(model="EP-GW", psi=2.0, **rough), mass, 0.01),
        ("EP-GW slow", egw.Params(model="EP-GW", psi=2.0, **rough), mass, 1e-4),
        ("EP-GW+cap 3vy", egw.Params(model="EP-GW", psi=2.0, flow_pressure=p_y, **rough),
         mass, 3.0*v_y),
    ]


def main(selected):
    for name, params, mass, velocity in cases():
        if selected and name not in selected:
            continue
        before = resource.getrusage(resource.RUSAGE_SELF)
        step = egw.time_step(params, mass=mass, velocity=velocity, tolerance=1e-3)
        after = resource.getrusage(resource.RUSAGE_SELF)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        print(f"{name:16s} v={velocity:.4g} duration={step.duration:.16e} "
              f"step={step.step:.6e} cpu={cpu:.3f}s", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
