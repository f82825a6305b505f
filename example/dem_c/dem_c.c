/* DEM loop on an egw table, in C (the C twin of example/dem_fortran): two glass beads
 * (R1 = R2 = 1 mm, E = 70 GPa, nu = 0.22, 2500 kg/m^3) collide head-on at 0.2 m/s,
 * velocity Verlet, SI units. Smooth (Hertz table): max overlap and contact time against
 * the closed forms. Rough (E-GW, sigma = 0.1 um, mu = 4): restitution 1 (elastic) and the
 * max overlap where the table's elastic energy equals the initial kinetic energy.
 * Tolerances 1e-5 as in dem_fortran.f90 (table rel_tol 1e-5, time step t_c/5000).
 * Elasto-plastic (EP-GW, sigma = 0.5 um, mu = 4, psi = 1): the same loop on a hysteresis
 * table (egw_hysteresis_eval_state: the contact's state, EGW_HYSTERESIS_STATE_SIZE doubles
 * that keep its history and what the next step can reuse; egw_hysteresis_eval with one
 * double gives the same values, slower) dissipates energy; its
 * restitution is printed next to egw_restitution's (agreement to 1e-4: the table's
 * rel_tol 1e-4 of the force at the turning point bounds the energies to a few 1e-5; the
 * loop starts at the table's cut-off, below which no force acts). Then the same contact
 * under a constant load: EP-GW alone leaves it vibrating (no loss below its past maximum
 * overlap); a viscous damping term beside the law, as a DEM needs, brings it to rest.
 * Exits with status 1 if a check fails. */
#include <math.h>
#include <stdio.h>
#include "egw.h"

static const double R1 = 1e-3, YOUNG = 70e9, NU = 0.22, RHO = 2500, V0 = 0.2;
static const double PI = 3.14159265358979323846;
static int failed = 0;

static void check(const char *what, int passed) {
  if (!passed) { printf("FAILED: %s\n", what); failed = 1; }
}

static egw_table make_table(const egw_params *p) {
  egw_table t = NULL;
  if (egw_table_build(p, NULL, -10 * p->sigma, 2e-6, 1e-5, &t) != EGW_OK) {
    char msg[512];
    egw_last_error(msg, (int)sizeof msg);
    printf("egw_table_build failed: %s\n", msg);
    return NULL;
  }
  return t;
}

/* Velocity Verlet for the overlap delta of two equal spheres (reduced mass m) from just
 * outside the cut-off until they separate; contact time between crossings of d_touch. */
static void collide(egw_table t, double m, double d_touch, double dt, double *d_max,
                    double *t_contact, double *restitution) {
  egw_table_info info;
  double d, d_old, v = V0, f, time = 0, t_in = -1;
  egw_table_get_info(t, &info);
  d = fmin(info.cutoff, d_touch) - 1e-9;
  egw_table_eval(t, d, &f, NULL);
  *d_max = d;
  for (;;) {
    d_old = d;
    v -= dt / 2 * f / m;
    d += dt * v;
    egw_table_eval(t, d, &f, NULL);
    v -= dt / 2 * f / m;
    time += dt;
    if (d_old <= d_touch && d > d_touch) t_in = time - dt * (d - d_touch) / (d - d_old);
    if (d > *d_max) *d_max = d;
    if (t_in >= 0 && d <= d_touch) break;
  }
  *t_contact = time - dt * (d_touch - d) / (d_old - d) - t_in;
  *restitution = -v / V0;
}

int main(void) {
  egw_params p;
  egw_table t;
  egw_table_info info;
  double m = RHO * 4 * PI * R1 * R1 * R1 / 3 / 2; /* reduced mass m1 m2/(m1 + m2) */
  double d_max, t_c, e, d_h, t_h, dt, lo, hi, mid, energy;
  egw_params_default(&p);
  p.model = EGW_MODEL_HERTZ;
  p.radius = R1 / 2;
  p.modulus = YOUNG / (2 * (1 - NU * NU));
  /* Hertz: (1/2) m V0^2 = (8/15) E sqrt(R) d^(5/2); t_c = 2 (d_h/V0) (2/5) B(2/5, 1/2) */
  d_h = pow(15 * m * V0 * V0 / (16 * p.modulus * sqrt(p.radius)), 0.4);
  t_h = 2 * d_h / V0 * 0.4 * tgamma(0.4) * sqrt(PI) / tgamma(0.9);
  dt = sqrt(m / (2 * p.modulus * sqrt(p.radius * d_h))) * PI / 5000;
  if (!(t = make_table(&p))) return 1;
  collide(t, m, 0.0, dt, &d_max, &t_c, &e);
  egw_table_free(&t);
  printf("Hertz max overlap [m], closed form: %.6e %.6e\n", d_max, d_h);
  printf("Hertz contact time [s], closed form: %.6e %.6e\n", t_c, t_h);
  check("Hertz max overlap", fabs(d_max / d_h - 1) < 1e-5);
  check("Hertz contact time", fabs(t_c / t_h - 1) < 1e-5);
  check("Hertz restitution", fabs(e - 1) < 1e-5);

  p.model = EGW_MODEL_EGW;
  p.sigma = 0.1e-6;
  p.mu = 4;
  if (!(t = make_table(&p))) return 1;
  egw_table_get_info(t, &info);
  collide(t, m, info.cutoff, dt, &d_max, &t_c, &e);
  for (lo = info.cutoff, hi = info.delta_max; hi - lo > 1e-12 * hi;) { /* energy = KE */
    mid = (lo + hi) / 2;
    egw_table_eval_all(t, mid, NULL, NULL, &energy, NULL);
    if (energy < m * V0 * V0 / 2) lo = mid; else hi = mid;
  }
  egw_table_free(&t);
  printf("E-GW max overlap [m], energy balance: %.6e %.6e\n", d_max, mid);
  printf("E-GW contact time [s]: %.6e, restitution: %.8f\n", t_c, e);
  check("E-GW max overlap", fabs(d_max / mid - 1) < 1e-5);
  check("E-GW restitution", fabs(e - 1) < 1e-5);
  check("roughness softens the contact", d_max - info.cutoff > d_h && t_c > t_h);

  /* EP-GW on a hysteresis table: loading, then the unloading curve of the history */
  {
    egw_hysteresis h = NULL;
    egw_hysteresis_info hinfo;
    double d, d0, d_old, v = V0, f, state[EGW_HYSTERESIS_STATE_SIZE], e_ref, t_ep, dt_ep;
    p.model = EGW_MODEL_EPGW;
    p.sigma = 0.5e-6;
    p.psi = 1;
    if (egw_hysteresis_build(&p, NULL, -3 * p.sigma, 3 * d_h, 1e-4, &h) != EGW_OK) {
      char msg[512];
      egw_last_error(msg, (int)sizeof msg);
      printf("egw_hysteresis_build failed: %s\n", msg);
      return 1;
    }
    egw_hysteresis_get_info(h, &hinfo);
    /* the step for this impact: Verlet's error in e below 1e-5 (doc/theory.md 10) */
    if (egw_time_step(&p, NULL, m, V0, 1e-5, &t_ep, &dt_ep) != EGW_OK) {
      printf("egw_time_step failed\n");
      return 1;
    }
    printf("EP-GW contact duration [s]: %.6e, time step [s]: %.6e\n", t_ep, dt_ep);
    /* below the cut-off the force is under 1e-12 of the reference: as from far apart */
    d0 = d = hinfo.cutoff;
    egw_hysteresis_state_init(state); /* a new contact */
    egw_hysteresis_eval_state(h, d, state, &f, NULL);
    do { /* velocity Verlet until the spheres are back where they started */
      d_old = d;
      v -= dt_ep / 2 * f / m;
      d += dt_ep * v;
      egw_hysteresis_eval_state(h, d, state, &f, NULL);
      v -= dt_ep / 2 * f / m;
    } while (!(d < d0 && d < d_old));
    e = -v / V0;
    /* EP-GW alone does not bring a contact to rest: pressed by a constant load (a bead
     * under a weight), it vibrates about equilibrium below its past maximum overlap,
     * where unloading and reloading retrace one elastic curve and lose nothing. A DEM
     * needs damping beside the law: here a viscous term -c v with c = 2 zeta sqrt(m K),
     * K the table's stiffness at the current overlap, zeta = 0.3 (0 for the comparison).
     * Over 40 contact durations the damped contact comes to rest (kinetic energy below
     * 1e-6 of the impact's), the undamped one keeps vibrating (above 1 %). */
    {
      double load = m * V0 / t_ep, k, c, ke_late[2], ke0 = m * V0 * V0 / 2;
      double rest[EGW_HYSTERESIS_STATE_SIZE]; /* its own contact: state[0] is printed below */
      long step, n_steps = (long)(40 * t_ep / dt_ep);
      int damped;
      for (damped = 0; damped < 2; damped++) {
        double zeta = damped ? 0.3 : 0.0;
        d = hinfo.cutoff;
        v = V0;
        ke_late[damped] = 0;
        egw_hysteresis_state_init(rest);
        egw_hysteresis_eval_state(h, d, rest, &f, &k);
        c = 2 * zeta * sqrt(m * fmax(k, 0.0));
        for (step = 0; step < n_steps; step++) { /* Verlet, the drag at the half step */
          v += dt_ep / 2 * (load - f - c * v) / m;
          d += dt_ep * v;
          egw_hysteresis_eval_state(h, d, rest, &f, &k);
          c = 2 * zeta * sqrt(m * fmax(k, 0.0));
          v += dt_ep / 2 * (load - f - c * v) / m;
          if (step > 3 * n_steps / 4) ke_late[damped] = fmax(ke_late[damped], m * v * v / 2);
        }
      }
      printf("EP-GW under a load, largest kinetic energy over the last 10 contact "
             "durations / the impact's: undamped %.3e, viscous damping (zeta 0.3) %.3e\n",
             ke_late[0] / ke0, ke_late[1] / ke0);
      check("EP-GW alone keeps a loaded contact vibrating", ke_late[0] > 1e-2 * ke0);
      check("viscous damping beside EP-GW brings it to rest", ke_late[1] < 1e-6 * ke0);
    }
    egw_hysteresis_free(&h);
    if (egw_restitution(&p, NULL, m, V0, &e_ref) != EGW_OK) {
      printf("egw_restitution failed\n");
      return 1;
    }
    printf("EP-GW max overlap [m]: %.6e, restitution (table loop, egw_restitution): "
           "%.6f %.6f\n", state[0], e, e_ref);
    check("EP-GW dissipates", e < 1 - 1e-3);
    check("EP-GW restitution = egw_restitution", fabs(e - e_ref) < 1e-4);
  }
  if (failed) return 1;
  printf("dem_c: all checks passed\n");
  return 0;
}
