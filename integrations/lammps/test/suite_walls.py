"""fix wall/egw and fix wall/egw/region against fix wall/gran: restitution, the
wall material, contact time, sinking through, restarts, rolling, bad input, curved walls."""
from lmp_common import *  # noqa: F401,F403 (the shared runner and constants)
from suite_pair import *  # noqa: F401,F403


M_BEAD = RHO * 4 / 3 * math.pi * RAD ** 3


def wall_run(pstyle, pcoeff, wallfix, v, dt, nrun, z0, **var):
    return lmp("wall.in", pstyle=pstyle, pcoeff=pcoeff, wallfix=wallfix, v=v, dt=dt, nrun=nrun,
               z0=z0, **var)


def test_wall_restitution():
    """A bead dropped head-on onto a fix wall/egw zplane of its own material at 0.01, 0.1 and
    1 m/s: the wall contact is the sphere-flat contact (R = R_i, m* = m_i, E* and sigma of
    two like bodies), so e is egw_restitution's for it: EP-GW (mu 4, psi 1, tables at 1e-3)
    within 1e-3 (the issue's bound) at every speed (measured 8e-6 at 0.01 m/s, where the
    impact turns in the rough tail, since the tables carry the tail's law; 2.4e-4 at 1 m/s
    with these 1e-3 tables).  E-GW within 1e-4 of 1 (dt = t_c/400: Verlet's energy error
    ~1e-5)."""
    sig, mu = 0.5e-6, 4.0
    E_flat = E / (2 * (1 - NU * NU))
    msgs, ok = [], True
    for v in (0.01, 0.1, 1.0):
        tc = 2.87 * (M_BEAD ** 2 / (RAD * E_flat ** 2 * v)) ** 0.2
        dt = tc / 400
        tail = 5e-6
        gap = max(0.5 * v * tc, 2 * tail)
        nrun = int((gap / v + 1.6 * tc + 3 * tail / v) / dt)
        for model, psi in (("EP-GW", 1), ("E-GW", 0)):
            c = f"E {E} nu {NU} sigma {sig} mu {mu} psi {psi}"
            rc, out = wall_run(f"egw {model} 1e-3", c, f"wall/egw {model} 1e-3 {c} zplane 0 NULL",
                               v, dt, nrun, RAD + gap)
            if rc != 0:
                return False, f"{model} at {v}: " + " ".join(
                    l for l in out.splitlines() if "ERROR" in l)
            e = result(out)[2] / v
            if model == "EP-GW":
                ref = float(subprocess.run(
                    [REST, "3", repr(E_flat), repr(RAD), repr(math.sqrt(2) * sig), repr(mu), "1",
                     "0.6", "54", repr(M_BEAD), repr(v), "1e-6"], stdout=subprocess.PIPE,
                    text=True).stdout)
                good = abs(e - ref) < 1e-3
                msgs.append(f"{v} m/s EP-GW e {e:.6f} vs {ref:.6f}")
            else:
                good = abs(e - 1) < 1e-4
                msgs.append(f"E-GW {e:.7f}")
            ok = ok and good
    return ok, "; ".join(msgs)


def wall_contact_time(pstyle, pcoeff, wallfix, v, dt, gap):
    """A bead of R = 1 mm thrown head-on at v onto a zplane at z = 0 from gap above it (no
    gravity): the contact time from the free flights before and after it, t_c = t_end -
    gap/v - z_end'/vz_end (z_end' the gap at the end), and the rebound speed."""
    nrun = int((gap / v + 1.5e-5) / dt)
    rc, out = wall_run(pstyle, pcoeff, wallfix, v, dt, nrun, RAD + gap, dumpz=1)
    if rc != 0:
        raise RuntimeError(" ".join(l for l in out.splitlines() if "ERROR" in l)[:300])
    vz = result(out)[2]
    z = float(re.findall(r"^ZEND (.*)$", out, re.M)[-1])
    return nrun * dt - gap / v - (z - RAD) / vz, vz


def test_wall_material_contact():
    """fix wall/egw ... wall_material contact: the wall's E and nu are the contact's, as fix
    wall/gran granular hertz/material's (E* = E/(2(1 - nu^2)), G* = E/(4(2 - nu)(1 + nu))).
    A glass bead (70 GPa, 0.22) thrown at 0.1 m/s onto a steel wall (200 GPa, 0.3), E-GW at
    sigma = 1e-16 (the smooth limit), TOL 1e-8, dt = t_c/400: the contact time within 1e-6
    (relative) of fix wall/gran's (measured ~1e-9); both within 1e-3 of Hertz's closed
    form 2.9432 (15 m/(16 E* sqrt R))^(2/5) v^(-1/5) with the wall's E* (Verlet at t_c/400
    and the free-flight extrapolation: measured ~1e-5); the default (wall_material own, E*
    of glass on steel) within 1e-3 of the closed form with that E* (1.32x longer)."""
    v, Ew, nuw = 0.1, 200e9, 0.3
    E_contact = Ew / (2 * (1 - nuw * nuw))
    E_own = 1 / ((1 - NU * NU) / E + (1 - nuw * nuw) / Ew)
    hertz = lambda Es: 2.94324 * (15 * M_BEAD / (16 * Es * math.sqrt(RAD))) ** 0.4 * v ** -0.2
    dt = hertz(E_contact) / 400
    gap = 10.37 * v * dt    # not a whole number of steps
    c = f"E {E} nu {NU} sigma 1e-16 mu 4"
    w = f"E {Ew} nu {nuw} sigma 1e-16 mu 4"
    t_egw, _ = wall_contact_time("egw E-GW 1e-8", c, f"wall/egw E-GW 1e-8 {w} wall_material "
                                 "contact zplane 0 NULL", v, dt, gap)
    t_gran, _ = wall_contact_time(
        "granular", f"hertz/material {E} 1.0 {NU} tangential mindlin NULL 0 0",
        f"wall/gran granular hertz/material {Ew} 1.0 {nuw} tangential mindlin NULL 0 0 "
        "damping coeff_restitution zplane 0 NULL", v, dt, gap)
    t_own, _ = wall_contact_time("egw E-GW 1e-8", c, f"wall/egw E-GW 1e-8 {w} zplane 0 NULL",
                                 v, dt, gap)
    d_gran = abs(t_egw - t_gran) / t_gran
    d_hertz = abs(t_egw - hertz(E_contact)) / hertz(E_contact)
    d_own = abs(t_own - hertz(E_own)) / hertz(E_own)
    ok = d_gran < 1e-6 and d_hertz < 1e-3 and d_own < 1e-3
    return ok, (f"t_c {t_egw:.9g} s vs wall/gran {t_gran:.9g} ({d_gran:.1e} < 1e-6), vs Hertz "
                f"{d_hertz:.1e}; own {t_own:.6g} s vs Hertz {d_own:.1e} (< 1e-3)")


def test_wall_sink_through():
    """A bead that sinks through a wall (a wall far too soft for the impact: E = 10 Pa, Hertz,
    1 m/s) stops the run with an ERROR naming the overlap ("sank through", "overlap") on the
    step its centre reaches the wall, for a zplane and a wall/egw/region block face, never
    a lost atom or a NaN later."""
    c = f"E {E} nu {NU}"
    bad = []
    for wall in ("wall/egw Hertz 1e-4 E 10 nu 0.3 zplane 0 NULL",
                 "wall/egw/region Hertz 1e-4 E 10 nu 0.3 wreg"):
        rc, out = wall_run("egw Hertz 1e-4", c, wall, 1.0, 1e-6, 3000, RAD + 1e-5)
        err = [l for l in out.splitlines() if "ERROR" in l]
        if rc == 0 or not err or "sank through" not in err[0] or (
                "region" not in wall and "overlap" not in err[0]) or "Lost atoms" in out:
            bad.append(f"{wall}: rc {rc} {err[:1]}")
    return not bad, "ERROR on sinking through, plane and region" + (
        "; " + "; ".join(bad) if bad else "")


def test_wall_bounces_start_afresh():
    """An EP-GW bead bouncing on a fix wall/egw zplane under gravity (0.1 m/s, g = 9.81,
    several impacts): each impact starts as a new contact (the history is zeroed when the
    bead leaves). The fix zeroes a far atom's history once, not on every step, and again
    after every reneighboring (atoms may have moved in memory): the run without any
    reneighboring (skin 10 mm) must match the run that reneighbors on every step (neigh_modify
    check no) bit for bit. A history left unzeroed starts an impact on an earlier one's
    unloading curve: forgetting that the bead touched the wall again (a bug tried on
    purpose) gave vz 0.03615 against 0.03107."""
    c = f"E {E} nu {NU} sigma 0.5e-6 mu 4 psi 1"
    wall = f"wall/egw EP-GW 1e-3 {c} zplane 0 NULL"
    dt, nrun = 2e-7, 250000
    runs = {}
    for name, var in (("never", dict(skin=0.01)), ("every step", dict(check="no"))):
        rc, out = wall_run("egw EP-GW 1e-3", c, wall, 0.1, dt, nrun, RAD + 1e-6, g=9.81, **var)
        if rc != 0:
            return False, f"{name}: " + " ".join(l for l in out.splitlines() if "ERROR" in l)
        runs[name] = result(out)
    vz = runs["never"][2]
    ok = runs["never"] == runs["every step"] and vz != 0.0
    return ok, (f"vz after {nrun} steps: {vz:.15g} (no reneighboring) vs "
                f"{runs['every step'][2]:.15g} (every step)")


def test_wall_rolling_vs_wall_gran():
    """A bead set down on a zplane under gravity, sliding at 0.05 m/s and spinning at 30 rad/s
    about x (it slides, rolls and comes to roll without slipping, resisted by rolling sds and
    twisting marshall, damping 0.7): fix wall/egw E-GW at sigma = 1e-16 (TOL 1e-8) against fix
    wall/gran granular hertz/material with the same sub-models: velocity and spin (times R)
    after 20 ms within 1e-6 of the initial speed (measured 1e-11)."""
    W = ("tangential mindlin NULL 1.0 0.3 rolling sds 1e5 0.05 0.2 twisting marshall "
         "damping coeff_restitution")
    kw = dict(vx=0.05, wx=30.0, g=9.81)
    rc1, o1 = wall_run("egw E-GW 1e-8", f"E {E} nu {NU} sigma 1e-16 mu 4",
                       f"wall/egw E-GW 1e-8 E {E} nu {NU} sigma 1e-16 mu 4 damping 0.7 {W} "
                       "zplane 0 NULL", 0.0, 1e-6, 20000, RAD, **kw)
    rc2, o2 = wall_run("granular", f"hertz/material {E} 0.7 {NU} {W}",
                       f"wall/gran granular hertz/material {E} 0.7 {NU} {W} zplane 0 NULL",
                       0.0, 1e-6, 20000, RAD, **kw)
    if rc1 != 0 or rc2 != 0:
        return False, " ".join(l for l in (o1 + o2).splitlines() if "ERROR" in l)
    a, b = result(o1), result(o2)
    dv = max(abs(x - y) for x, y in zip(a[:3], b[:3])) / 0.05
    dw = max(abs(x - y) for x, y in zip(a[3:], b[3:])) * RAD / 0.05
    moved = abs(a[0]) > 1e-3 and abs(a[4]) > 1.0
    ok = dv < 1e-6 and dw < 1e-6 and moved
    return ok, (f"vx {a[0]:.9g} vs {b[0]:.9g}, wy {a[4]:.9g} vs {b[4]:.9g}; max |dv|/v0 "
                f"{dv:.1e}, |dw| R/v0 {dw:.1e} (< 1e-6)")


def test_wall_restart_and_ranks():
    """fix wall/egw EP-GW with friction, an oblique impact: a run split by write_restart in
    mid contact (unloading, tangential spring loaded) and continued by read_restart with the
    fix given again ends as the uninterrupted split run (1e-12 of the speed: the per-atom
    delta_max, hysteresis state and displacement came back); the same impact on 2 ranks
    ends the same (1e-12; the bead stays on one rank here: migration of the per-atom
    history is exercised by the pour example on 2 ranks, not compared bit for bit)."""
    c = f"E {E} nu {NU} sigma 0.5e-6 mu 4 psi 1"
    wall = f"wall/egw EP-GW 1e-3 {c} damping 0.9 damping coeff_restitution tangential mindlin NULL 1.0 0.3 zplane 0 NULL"
    kw = dict(vx=0.05, wx=40.0, n1=5600, n2=3000)
    rc1, o1 = wall_run("egw E-GW 1e-3", c, wall, 0.1, 2e-8, 8600, RAD + 1e-5, restart=1,
                       rfile="wall.restart", **kw)
    rc2, o2 = lmp("wall_restart.in", rfile="wall.restart", wallfix=wall, n2=3000)
    rc3, o3 = lmp("wall.in", np=2, pstyle="egw E-GW 1e-3", pcoeff=c, wallfix=wall, v=0.1,
                  dt=2e-8, nrun=8600, z0=RAD + 1e-5, **kw)
    if rc1 or rc2 or rc3:
        return False, " ".join(l for l in (o1 + o2 + o3).splitlines() if "ERROR" in l)
    a, b, c3 = result(o1), result(o2), result(o3)
    d = max(abs(x - y) for x, y in zip(a[:3], b[:3])) / 0.1
    dw = max(abs(x - y) for x, y in zip(a[3:], b[3:])) * RAD / 0.1
    d2 = max(abs(x - y) for x, y in zip(a, c3)) / 0.1
    bounced = a[2] > 0.05 and abs(a[0] - 0.05) > 1e-4
    ok = d < 1e-12 and dw < 1e-12 and d2 < 1e-12 and bounced
    return ok, (f"restart: max |dv|/v {d:.1e}, |dw| R/v {dw:.1e}; 2 ranks: {d2:.1e} (< 1e-12); "
                f"vz after {a[2]:.6g}, vx {a[0]:.6g}")


def test_bad_wall():
    """Bad fix wall/egw input (29 cases): a LAMMPS ERROR naming the keyword, a non-zero exit,
    never a crash or hang. 'temperature' without its value after a region ID said "region ID
    'temperature' does not exist" before, and one given twice was taken silently; fix
    wall/gran's 'hertz/material E e nu' kept in a converted line said "unknown keyword" (stop
    49), 'granular' as MODEL now names the conversion; a keyword given twice was taken
    silently, its first value dropped (stop 58; after the wall style, stop 59); a wall keyword
    after the region ID was called a missing region (stop 59)."""
    c = f"E {E} nu {NU} sigma 0.5e-6 mu 4"
    cases = [
        (f"wall/egw E-GW 1e-4 {c}", "wall style"),
        (f"wall/egw E-GW 1e-4 {c} colour red zplane 0 NULL", "colour"),
        (f"wall/egw E-GW 1e-4 nu {NU} zplane 0 NULL", "E"),
        (f"wall/egw E-GW 1e-4 {c} zcylinder -1", "zcylinder"),
        (f"wall/egw E-GW 1e-4 {c} zplane NULL NULL", "NULL"),
        (f"wall/egw E-GW 1e-4 {c} zplane 0 NULL wiggle q 1 1", "wiggle"),
        (f"wall/egw E-GW 1e-4 {c} zplane 0 NULL shear z 1", "shear"),
        (f"wall/egw Foo 1e-4 {c} zplane 0 NULL", "MODEL"),
        (f"wall/egw E-GW 1e-4 {c} tangential mindlin NULL 1 zplane 0 NULL", "tangential"),
        (f"wall/egw E-GW 1e-4 {c} damping tsuji damping 2 zplane 0 NULL", "damping"),
        (f"wall/egw E-GW 1e-4 {c} zplane 0 NULL contacts 3", "'3'"),
        (f"wall/egw/region E-GW 1e-4 {c} nowhere contacts", "nowhere"),
        (f"wall/egw E-GW 1e-4 {c} wall_material", "wall_material"),
        (f"wall/egw E-GW 1e-4 {c} wall_material rigid zplane 0 NULL", "wall_material"),
        (f"wall/egw E-GW 1e-4 {c} temperature abc zplane 0 NULL", "temperature"),
        (f"wall/egw E-GW 1e-4 {c} temperature v_nowhere zplane 0 NULL", "nowhere"),
        (f"wall/egw/region E-GW 1e-4 {c} nowhere temperature", "'temperature' needs a value"),
        (f"wall/egw E-GW 1e-4 {c} zplane 0 NULL temperature", "'temperature' needs a value"),
        (f"wall/egw E-GW 1e-4 {c} temperature 300 zplane 0 NULL temperature 200",
         "'temperature' given twice"),
        # fix wall/gran's normal model kept in a converted line (was "unknown keyword")
        (f"wall/egw E-GW 1e-4 hertz/material {E} 0.5 {NU} zplane 0 NULL",
         "'hertz/material' (fix wall/gran's normal model) is not supported"),
        (f"wall/egw granular hertz/material {E} 0.5 {NU} zplane 0 NULL",
         "MODEL = 'granular': must be Hertz, GW, E-GW or EP-GW (fix wall/gran's"),
        # a keyword given twice: the first value was dropped without a word (audit24)
        (f"wall/egw E-GW 1e-4 {c} damping 0.5 damping 0.7 zplane 0 NULL",
         "'damping <value>' given twice"),
        (f"wall/egw E-GW 1e-4 {c} wall_material contact wall_material own zplane 0 NULL",
         "'wall_material' given twice"),
        (f"wall/egw E-GW 1e-4 {c} mu 4 zplane 0 NULL", "'mu' given twice"),
        # after the wall style or the region ID too (stop 59: the first wiggle was dropped)
        (f"wall/egw E-GW 1e-4 {c} zplane 0 NULL wiggle z 1e-5 1 wiggle z 2e-5 1",
         "'wiggle' given twice"),
        (f"wall/egw E-GW 1e-4 {c} zplane 0 NULL shear x 1 shear y 1", "'shear' given twice"),
        (f"wall/egw/region E-GW 1e-4 {c} region wreg contacts contacts",
         "'contacts' given twice"),
        # a wall keyword after the region ID (was "region ID 'limit_damping' does not exist")
        (f"wall/egw/region E-GW 1e-4 {c} region wreg limit_damping",
         "'limit_damping' after the region ID 'wreg'"),
        (f"wall/egw/region E-GW 1e-4 {c} wreg damping 0.5 contacts",
         "'damping' after the region ID 'wreg'"),
    ]
    bad = []
    for wall, key in cases:
        rc, out = wall_run("egw E-GW 1e-4", c, wall, 0.1, 1e-8, 0, RAD + 1e-5)
        fault = refusal_fault(rc, out, key)
        if fault:
            bad.append(f"{wall!r}: {fault}")
    return refusal_verdict(len(cases), bad)


def test_wall_region():
    """fix wall/egw/region on a block region's open-topped box: an oblique EP-GW impact with
    friction on its floor ends as on a wall/egw zplane at the same height (1e-12: the same
    contact), and a run split by write_restart/read_restart in mid contact ends as the
    uninterrupted one (1e-12: the per-atom slots with their wall ids come back), the
    continuation's fix given in granular's form '... region wreg' (the same fix)."""
    c = f"E {E} nu {NU} sigma 0.5e-6 mu 4 psi 1"
    sub = "damping 0.9 tangential mindlin NULL 1.0 0.3"
    plane = f"wall/egw EP-GW 1e-3 {c} {sub} zplane 0 NULL"
    reg = f"wall/egw/region EP-GW 1e-3 {c} {sub} wreg"
    kw = dict(vx=0.05, wx=40.0, n1=5600, n2=3000)
    rc1, o1 = wall_run("egw E-GW 1e-3", c, plane, 0.1, 2e-8, 8600, RAD + 1e-5, **kw)
    rc2, o2 = wall_run("egw E-GW 1e-3", c, reg, 0.1, 2e-8, 8600, RAD + 1e-5, restart=1,
                       rfile="wallreg.restart", **kw)
    # the continuation gives the fix in granular's form 'region region-ID'
    rc3, o3 = lmp("wall_restart.in", rfile="wallreg.restart",
                  wallfix=reg.replace(" wreg", " region wreg"), n2=3000)
    if rc1 or rc2 or rc3:
        return False, " ".join(l for l in (o1 + o2 + o3).splitlines() if "ERROR" in l)
    a, b, r = result(o1), result(o2), result(o3)
    scale = [0.1] * 3 + [0.1 / RAD] * 3
    d_plane = max(abs(x - y) / s for x, y, s in zip(a, b, scale))
    d_rest = max(abs(x - y) / s for x, y, s in zip(b, r, scale))
    ok = d_plane < 1e-12 and d_rest < 1e-12 and a[2] > 0.05
    return ok, f"region vs plane {d_plane:.1e}, restart {d_rest:.1e} (< 1e-12); vz {b[2]:.6g}"


def test_drum_example():
    """The drum example (300 grains in a rotating cylinder region, fix wall/egw/region,
    6000 steps) runs to the end without ERROR or NaN, and its grains' mean height after the
    fall is granular's (pair granular + fix wall/gran/region, the same deck) within 2 % of
    the drum radius (sigma = 1.4 um against 2 mm grains)."""
    out = {}
    for law in ("egw", "granular"):
        args = [LMP, "-in", os.path.join(ROOT, "integrations", "lammps", "examples", "drum.in"),
                "-log", "none", "-nocite", "-var", "law", law, "-var", "nrun", "6000"]
        p = subprocess.run(args, cwd=TMP, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           text=True, timeout=600)
        m = re.search(r"DRUM atoms (\d+) ke (\S+) mean_x (\S+) mean_z (\S+)", p.stdout)
        if p.returncode or not m or re.search(r"\bnan\b", p.stdout, re.I):
            return False, f"{law}: rc {p.returncode} " + " ".join(
                l for l in p.stdout.splitlines() if "ERROR" in l)
        out[law] = [float(x) for x in m.groups()]
    dz = abs(out["egw"][3] - out["granular"][3]) / 0.02
    ok = out["egw"][0] == 300 and dz < 0.02
    return ok, (f"mean z egw {out['egw'][3]:.6g}, granular {out['granular'][3]:.6g} "
                f"(|diff| {dz:.1e} of the radius < 2e-2)")


def curved_run(shape, pstyle, pcoeff, wallfix, nmid=0, nrun=6000):
    """curved.in: the bead 10 um from a curved wall, 0.1 m/s towards it, 0.03 m/s along it,
    spinning (contact from step ~5000 for ~400 steps at dt 2e-8)."""
    return lmp("curved.in", shape=shape, pstyle=pstyle, pcoeff=pcoeff, wallfix=wallfix, v=0.1,
               dt=2e-8, nrun=nrun, nmid=nmid)


CURVED_SUB = ("tangential mindlin NULL 1.0 0.3 rolling sds 1e5 0.05 0.2 twisting marshall "
              "damping coeff_restitution")


def test_wall_curvature_vs_wall_gran():
    """Curved walls: a bead (R = 1 mm) meets obliquely, spinning, the inside of a cylinder
    region of radius 5 mm (a drum: concave, LAMMPS's radius of curvature -2 x 5 mm, R_eff =
    1.11 mm), the outside of a sphere region of radius 3 mm (convex, +3 mm, R_eff = 0.75 mm),
    the outside of a cylinder region of radius 3 mm (+6 mm, R_eff = 0.86 mm), and a fix
    wall/egw zcylinder of radius 5 mm (-10 mm, as fix wall/gran): fix wall/egw[/region] E-GW
    at sigma = 1e-16 (TOL 1e-8) with mindlin, rolling sds and twisting marshall against fix
    wall/gran[/region] granular hertz/material, the same sub-models: velocities and spins
    (times R) after the contact within 1e-6 of the speed (the issue's bound; measured
    ~1e-8).  The bound discriminates: the drum's contact taken flat (a zplane at the drum's
    bottom) ends more than 1e-4 away."""
    c = f"E {E} nu {NU} sigma 1e-16 mu 4"
    msgs, ok, res = [], True, {}
    for shape, egw_wall, gran_wall in (
            ("drum", "wreg", "region wreg"), ("ball", "wreg", "region wreg"),
            ("post", "wreg", "region wreg"), ("zcyl", "zcylinder 0.005", "zcylinder 0.005"),
            ("flat", "zplane -0.005 NULL", None)):
        style = "wall/egw" if "plane" in egw_wall or "cylinder" in egw_wall else "wall/egw/region"
        rc1, o1 = curved_run("drum" if shape == "flat" else shape, "egw E-GW 1e-8", c,
                             f"{style} E-GW 1e-8 {c} damping 0.7 {CURVED_SUB} {egw_wall}")
        if rc1:
            return False, f"{shape}: " + " ".join(l for l in o1.splitlines() if "ERROR" in l)
        res[shape] = result(o1)
        if gran_wall is None:
            continue
        gstyle = "wall/gran/region" if gran_wall.startswith("region") else "wall/gran"
        rc2, o2 = curved_run(shape, "granular", f"hertz/material {E} 0.7 {NU} {CURVED_SUB}",
                             f"{gstyle} granular hertz/material {E} 0.7 {NU} {CURVED_SUB} "
                             f"{gran_wall}")
        if rc2:
            return False, f"{shape} granular: " + " ".join(l for l in o2.splitlines() if "ERROR" in l)
        a, b = res[shape], result(o2)
        d = max(max(abs(x - y) for x, y in zip(a[:3], b[:3])) / 0.1,
                max(abs(x - y) for x, y in zip(a[3:], b[3:])) * RAD / 0.1)
        ok = ok and d < 1e-6
        msgs.append(f"{shape} {d:.1e}")
    a, b = res["drum"], res["flat"]
    dflat = max(max(abs(x - y) for x, y in zip(a[:3], b[:3])) / 0.1,
                max(abs(x - y) for x, y in zip(a[3:], b[3:])) * RAD / 0.1)
    ok = ok and dflat > 1e-4
    return ok, ", ".join(msgs) + f" (< 1e-6); drum taken flat: {dflat:.1e} (> 1e-4)"


def test_wall_curvature_summit():
    """A curved wall with mu from summit data: the drum contact's mu is that of its own R_eff
    = R_i r_c/(R_i + r_c) = 1.11 mm, beyond the bead's radius, so the fix widens its tables to
    the R_eff the atoms can meet (log: 'for R in [..., 0.001167]') and the contact equals the
    same contact with mu = (8/3) eta sigma sqrt(2 R_eff beta) given (computed here): E-GW,
    sigma 0.5 um per body, tables at 1e-4, velocities and spins within 1e-4 of the speed
    (the tables' tolerance; measured 5e-6).  Twice: the bead 10 um from the shell at the
    start (the tables are built for it at once), and 100 um away (dt 1e-7: it comes within
    reach only later, and the tables are rebuilt at a reneighboring: two builds logged)."""
    sig, eta, beta = 0.5e-6, 1e10, 1e-5
    Reff = RAD * 0.01 / (0.01 - RAD)
    mu = 8 / 3 * eta * math.sqrt(2) * sig * math.sqrt(2 * Reff * beta)
    msgs, ok = [], True
    for tag, var, builds in (("at once", {}, 1),
                             ("later", dict(gap=1e-4, dt=1e-7, nrun=11000), 2)):
        out = []
        for c in (f"summit_density {eta} summit_radius {beta}", f"mu {mu!r}"):
            cc = f"E {E} nu {NU} sigma {sig} {c}"
            kw = dict(shape="drum", pstyle="egw E-GW 1e-4", pcoeff=cc, v=0.1, dt=2e-8,
                      nrun=6000, nmid=0,
                      wallfix=f"wall/egw/region E-GW 1e-4 {cc} damping 0.7 damping coeff_restitution "
                              "tangential mindlin NULL 1.0 0.3 wreg")
            kw.update(var)
            rc, o = lmp("curved.in", **kw)
            if rc:
                return False, " ".join(l for l in o.splitlines() if "ERROR" in l)
            out.append((result(o), o))
        (a, oa), (b, _) = out
        d = max(max(abs(x - y) for x, y in zip(a[:3], b[:3])) / 0.1,
                max(abs(x - y) for x, y in zip(a[3:], b[3:])) * RAD / 0.1)
        widened = re.findall(r"fix wall/egw w: type 1: .*R in \[(\S+), (\S+)\]", oa)
        rhi = float(widened[-1][1]) if widened else 0.0
        ok = ok and d < 1e-4 and rhi >= Reff and len(widened) == builds
        msgs.append(f"{tag}: {len(widened)} build(s), R up to {rhi:.4g}, summit data vs mu "
                    f"given {d:.1e}")
    return ok, f"mu(R_eff = {Reff:.4g}) = {mu:.5g}; " + "; ".join(msgs) + " (< 1e-4)"


def test_wall_contacts_vs_wall_gran():
    """The 'contacts' per-atom array of fix wall/egw[/region] mid-contact (the bead pressed
    into the drum's shell, and into a zcylinder), against fix wall/gran[/region] granular's
    own contacts columns (E-GW sigma = 1e-16, TOL 1e-8, as above): flag 1, the wall's force
    on the atom within 1e-6 of its magnitude (and equal to the atom's force fx, fy, fz: the
    wall is its only force, 1e-12), the contact point on the wall and the radius to 1e-12;
    with heat area the ninth column (heat into the atom) within 1e-6 of granular's."""
    c = f"E {E} nu {NU} sigma 1e-16 mu 4"
    msgs, ok = [], True
    for shape, egw_wall, gran_wall in (("drum", "wall/egw/region", "wall/gran/region"),
                                       ("zcyl", "wall/egw", "wall/gran")):
        ew = "wreg contacts" if shape == "drum" else "zcylinder 0.005 contacts"
        gw = "region wreg contacts" if shape == "drum" else "zcylinder 0.005 contacts"
        rc1, o1 = curved_run(shape, "egw E-GW 1e-8", c,
                             f"{egw_wall} E-GW 1e-8 {c} damping 0.7 {CURVED_SUB} {ew}", nmid=5200)
        rc2, o2 = curved_run(shape, "granular", f"hertz/material {E} 0.7 {NU} {CURVED_SUB}",
                             f"{gran_wall} granular hertz/material {E} 0.7 {NU} {CURVED_SUB} {gw}",
                             nmid=5200)
        rows = []
        for rc, o in ((rc1, o1), (rc2, o2)):
            m = re.search(r"^MID (.*)$", o, re.M)
            if rc or not m:
                return False, f"{shape}: rc {rc} " + " ".join(l for l in o.splitlines() if "ERROR" in l)
            rows.append([float(x) for x in m.group(1).split()])
        a, b = rows
        fmag = math.sqrt(sum(x * x for x in b[1:4]))
        df = max(abs(x - y) for x, y in zip(a[1:4], b[1:4])) / fmag
        dself = max(abs(x - y) for x, y in zip(a[1:4], a[8:11])) / fmag
        dpt = max(abs(x - y) for x, y in zip(a[4:8], b[4:8])) / RAD
        good = a[0] == 1 and b[0] == 1 and df < 1e-6 and dself < 1e-12 and dpt < 1e-9 and fmag > 0
        ok = ok and good
        msgs.append(f"{shape}: |F| {fmag:.6g}, force {df:.1e}, point+radius {dpt:.1e} of R")
    g = "tangential linear_nohistory 0 0 heat area 1e5"
    hw = []
    for ps, pc, wf in (("egw E-GW 1e-8", c, f"wall/egw E-GW 1e-8 {c} heat area 1e5 temperature 200 "
                                           "zplane 0 NULL contacts"),
                       ("granular", f"hertz/material {E} 1.0 {NU} {g}",
                        f"wall/gran granular hertz/material {E} 1.0 {NU} {g} zplane 0 NULL "
                        "temperature 200 contacts")):
        rc, o = lmp("heatwall.in", pstyle=ps, pcoeff=pc, wallfix=wf, contacts=1)
        m = re.search(r"^CONTACTS9 (\S+)", o, re.M)
        if rc or not m:
            return False, "heat: " + " ".join(l for l in o.splitlines() if "ERROR" in l)
        hw.append(float(m.group(1)))
    dq = abs(hw[0] - hw[1]) / abs(hw[1])
    ok = ok and dq < 1e-6 and hw[1] < 0
    return ok, "; ".join(msgs) + f" (1e-6; the point 1e-9 of R: the trajectories differ by ~1e-9 of the speed); heat column {hw[0]:.9g} vs {hw[1]:.9g} ({dq:.1e})"
