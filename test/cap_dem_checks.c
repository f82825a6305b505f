/* A head-on impact with the flow-pressure cap through a DEM loop (issue 32 item 2), from C
 * as a DEM code calls it: velocity Verlet on egw_hysteresis_eval_state of a Hertz + cap
 * table (egw_hysteresis_build with p.flow_pressure), the step from egw_time_step (the
 * cap's unloading stiffness beyond v_y), against egw_restitution (the cap solver's
 * works). R = 1 mm, E* = 100 GPa, p_y = 1 GPa, m* = 1e-5 kg; a 3e-4 table over
 * [0, 10 delta_y] up to 10 v_y (delta_m = 6.8 delta_y) and a 3e-4 table over
 * [0, 35 delta_y] for 20 and 50 v_y (delta_m = 29.7 delta_y; the cap solver's force is
 * smooth in delta and delta_max, doc/theory.md section 12, so the wide table builds in
 * seconds). test/test_cap_hysteresis.f90 runs it. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "egw.h"

static int failures;
#define CHECK(cond) do { if (!(cond)) { failures++; \
  printf("    C check failed at %s:%d: %s\n", __FILE__, __LINE__, #cond); } } while (0)

/* e of one impact: from first touch (delta = 0) at speed v until the pair is apart again
 * and receding; a zeroed state is a new contact. */
static double verlet_e(egw_hysteresis h, double mass, double v, double dt, long *steps) {
  double state[EGW_HYSTERESIS_STATE_SIZE] = {0}, d = 0.0, vel = v, f = 0, k = 0, acc = 0;
  for (*steps = 0; *steps < 10000000L; (*steps)++) {
    vel += 0.5 * dt * acc;
    d += dt * vel;
    egw_hysteresis_eval_state(h, d, state, &f, &k);
    acc = -f / mass;
    vel += 0.5 * dt * acc;
    if (vel < 0.0 && d < 0.0) break;
  }
  return -vel / v;
}

/* The loop's e against egw_restitution within 1e-3 (the bound for the DEM loop)
 * from v_y to 50 v_y. The table's error in e is about rel_tol P(m) (m - delta_r)/(2 e
 * W_unload) ~ 1.25 rel_tol (W_unload ~ P(m)(m - delta_r)/2.5): 3e-4 tables give ~4e-4
 * (measured within 5e-5 of e from v_y to 50 v_y). Verlet's error (egw_time_step at 1e-4) is
 * 1e-4. At v_y (the turning point at first yield) the impact is Hertz's: e = 1 to
 * Verlet's error. */
int egw_capi_test_cap_dem_loop(void) {
  const double ratios[6] = {1.0, 2.0, 5.0, 10.0, 20.0, 50.0};
  const double radius = 1e-3, modulus = 1e11, py = 1e9, mass = 1e-5;
  double delta_y = pow(M_PI * py / (2 * modulus), 2) * radius;
  double vy = sqrt(16.0 / 15.0 * pow(M_PI / 2, 5) * pow(py, 5) * pow(radius, 3) /
                   (mass * pow(modulus, 4)));
  egw_params p;
  egw_hysteresis tables[2] = {NULL, NULL};
  failures = 0;
  egw_params_default(&p);
  p.model = EGW_MODEL_HERTZ;
  p.radius = radius;
  p.modulus = modulus;
  p.flow_pressure = py;
  CHECK(egw_hysteresis_build(&p, NULL, 0.0, 10 * delta_y, 3e-4, &tables[0]) == EGW_OK);
  CHECK(egw_hysteresis_build(&p, NULL, 0.0, 35 * delta_y, 3e-4, &tables[1]) == EGW_OK);
  if (tables[0] == NULL || tables[1] == NULL) return failures;
  for (int i = 0; i < 6; i++) {
    egw_hysteresis h = tables[ratios[i] > 10.0];
    double v = ratios[i] * vy, duration = 0, dt = 0, e_ref = 0, delta_m = 0, e;
    long steps;
    CHECK(egw_time_step(&p, NULL, mass, v, 1e-4, &duration, &dt) == EGW_OK);
    CHECK(egw_restitution_overlap(&p, NULL, mass, v, &e_ref, &delta_m) == EGW_OK);
    if (!(dt > 0 && duration > 20 * dt)) {
      CHECK(dt > 0 && duration > 20 * dt);
      continue;
    }
    e = verlet_e(h, mass, v, dt, &steps);
    printf("    v = %4.0f v_y, delta_m = %6.2f delta_y: e loop %.5f, restitution %.5f "
           "(%+.1e, %ld steps)\n", ratios[i], delta_m / delta_y, e, e_ref, e - e_ref, steps);
    CHECK(fabs(e - e_ref) <= 1e-3);
  }
  egw_hysteresis_free(&tables[0]);
  egw_hysteresis_free(&tables[1]);
  /* rough + cap (test/test_rough_cap_hysteresis.f90): served; E-GW whose largest total
   * pressure stays below p_y is reversible there, as without the cap (its force the
   * cap-free table's, bit for bit); a table with the cap beyond 1000 delta_y is refused
   * naming delta_max, no handle */
  {
    egw_params q;
    egw_hysteresis r = NULL, free_h = NULL;
    egw_table free_t = NULL;
    char msg[512];
    double st = -1e300, f = 0, k = 0, f0 = 0, k0 = 0, dy;
    egw_params_default(&q);
    q.sigma = 0.01;
    q.mu = 4.0;
    CHECK(egw_table_build(&q, NULL, -q.sigma, q.sigma, 1e-3, &free_t) == EGW_OK);
    q.flow_pressure = 0.5 * q.modulus;
    CHECK(egw_hysteresis_build(&q, NULL, -q.sigma, q.sigma, 1e-3, &r) == EGW_OK && r != NULL);
    if (r != NULL && free_t != NULL) {
      CHECK(egw_hysteresis_eval(r, 0.5 * q.sigma, &st, &f, &k) == EGW_OK);
      CHECK(egw_table_eval(free_t, 0.5 * q.sigma, &f0, &k0) == EGW_OK);
      CHECK(fabs(f - f0) <= 1e-12 * f0 && f > 0);
    }
    egw_hysteresis_free(&r);
    egw_table_free(&free_t);
    q.flow_pressure = 0.01 * q.modulus;
    dy = pow(3.14159265358979323846 * q.flow_pressure / (2 * q.modulus), 2) * q.radius;
    CHECK(egw_hysteresis_build(&q, NULL, 0.0, 2000 * dy, 1e-3, &free_h) ==
          EGW_INVALID_ARGUMENT && free_h == NULL);
    egw_last_error(msg, sizeof msg);
    CHECK(strstr(msg, "delta_max") != NULL);
  }
  /* a scene file with the cap: egw-table reads it, the C struct has no field for it, so
   * egw_scene_read refuses it (naming flow_pressure) and leaves *s as it was */
  {
    egw_scene sc, before;
    char msg[512];
    const char *path = "build/cap_scene.nml";
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (f != NULL) {
      fputs("&scene\n  model = 'Hertz'\n  yield_stress = 1e9\n/\n", f);
      fclose(f);
      egw_scene_default(&sc);
      before = sc;
      CHECK(egw_scene_read(path, &sc) == EGW_INVALID_PARAMETER);
      egw_last_error(msg, sizeof msg);
      CHECK(strstr(msg, "flow_pressure") != NULL);
      CHECK(memcmp(&sc, &before, sizeof sc) == 0);
    }
  }
  return failures;
}

/* e of one impact through the DEM path of a force loop (the LAMMPS plugin's): the inline
 * egw_hysteresis_eval_cached first, egw_hysteresis_eval_state where it declines; from the
 * table's cut-off (no force below: as from far apart) at speed v until the pair is back
 * below it and receding. *fast counts the steps the inline call served. */
static double verlet_cached_e(egw_hysteresis h, double tag, int cached, double d0,
                              double mass, double v, double dt, long *fast) {
  double state[EGW_HYSTERESIS_STATE_SIZE] = {0}, d = d0, vel = v, f = 0, k = 0, acc = 0;
  *fast = 0;
  for (long n = 0; n < 10000000L; n++) {
    vel += 0.5 * dt * acc;
    d += dt * vel;
    if (cached && egw_hysteresis_eval_cached(tag, d, state, &f, &k))
      (*fast)++;
    else
      egw_hysteresis_eval_state(h, d, state, &f, &k);
    acc = -f / mass;
    vel += 0.5 * dt * acc;
    if (vel < 0.0 && d < d0) break;
  }
  return -vel / v;
}

/* Issue 32's C DEM loop on ROUGH + cap tables (E-GW + cap and EP-GW + cap, psi = 1: the
 * two-piece s map, doc/formats.md 6), as a DEM code runs it: the step from egw_time_step
 * at 1e-4, velocity Verlet through egw_hysteresis_eval_cached / _eval_state, against
 * egw_restitution (rel_tol 1e-6) within 1e-3 (the bound) at 3 and 8 v_y. Cap units
 * R = E* = 1, p_y = 2/pi (delta_y = 1), m* = 16/15 (v_y = 1); sigma = delta_y/10, mu = 4;
 * tables at 3e-4 over [-3 sigma, 1.2 delta_m(8 v_y)] (delta_m = 5.6 delta_y). Budget: a
 * gap table's force error <= rel_tol P(m) on the unloading curve over (delta_r, m), with
 * W_unload ~ P(m)(m - delta_r)/2.5, moves e by <= 1.25 rel_tol e; the loading curve's
 * (relative to the local force) by <= rel_tol/2 e; Verlet at the 1e-4 step by <= 1e-4:
 * <= 6.3e-4 in all (measured 2e-6 .. 7e-5). The inline path returns eval_state's values
 * to rounding (1e-12 of the turning point's force, egw.h): both loops' e within 1e-9,
 * and the inline path serves some of the steps. Before this only the Hertz + cap loop
 * above ran in C (the rough + cap loop in Fortran, test_rough_cap_hysteresis). */
int egw_capi_test_rough_cap_dem_loop(void) {
  const int models[2] = {EGW_MODEL_EGW, EGW_MODEL_EPGW};
  const double speeds[2] = {3.0, 8.0}, mass = 16.0 / 15.0;
  failures = 0;
  for (int i = 0; i < 2; i++) {
    egw_params p;
    egw_options o;
    egw_hysteresis h = NULL;
    egw_hysteresis_info info;
    double tag = 0, delta_m = 0, e_ref = 0;
    egw_params_default(&p);
    egw_options_default(&o);
    o.rel_tol = 1e-6;
    p.model = models[i];
    p.radius = 1.0;
    p.modulus = 1.0;
    p.flow_pressure = 2.0 / M_PI;
    p.sigma = 0.1;
    p.mu = 4.0;
    p.psi = models[i] == EGW_MODEL_EPGW ? 1.0 : 0.0;
    CHECK(egw_restitution_overlap(&p, &o, mass, speeds[1], &e_ref, &delta_m) == EGW_OK);
    CHECK(delta_m > 5.0 && delta_m < 6.0); /* beyond first yield, inside the table */
    CHECK(egw_hysteresis_build(&p, NULL, -3 * p.sigma, 1.2 * delta_m, 3e-4, &h) == EGW_OK);
    if (h == NULL) continue;
    CHECK(egw_hysteresis_get_info(h, &info) == EGW_OK && !info.reversible);
    CHECK(egw_hysteresis_state_tag(h, &tag) == EGW_OK);
    for (int j = 0; j < 2; j++) {
      double v = speeds[j], duration = 0, dt = 0, e_state, e_cached;
      long fast_state, fast;
      CHECK(egw_restitution(&p, &o, mass, v, &e_ref) == EGW_OK);
      CHECK(egw_time_step(&p, NULL, mass, v, 1e-4, &duration, &dt) == EGW_OK);
      if (!(dt > 0 && duration > 20 * dt)) {
        CHECK(dt > 0 && duration > 20 * dt);
        continue;
      }
      e_state = verlet_cached_e(h, tag, 0, info.cutoff, mass, v, dt, &fast_state);
      e_cached = verlet_cached_e(h, tag, 1, info.cutoff, mass, v, dt, &fast);
      printf("    %s + cap, v = %.0f v_y: e loop %.7f (inline %.7f, %ld steps served "
             "inline), restitution %.7f (%+.1e)\n", i == 0 ? "E-GW" : "EP-GW", v, e_state,
             e_cached, fast, e_ref, e_state - e_ref);
      CHECK(fabs(e_state - e_ref) <= 1e-3);
      CHECK(fabs(e_cached - e_state) <= 1e-9 && fast > 0);
    }
    egw_hysteresis_free(&h);
  }
  return failures;
}
