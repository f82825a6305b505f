/* C tests of the flow-pressure cap through include/egw.h (doc/theory.md section 12):
 * egw_params.flow_pressure, the smooth-sphere solves, unloading and restitution against
 * test/data/cap_reference.csv (tools/reference/cap_reference.py, an independent solve of
 * the same cap model), and the refusals. R = E* = 1, p_y = 2/pi: delta_y = 1, P_y = 4/3,
 * m* = 16/15 makes v_y = 1. Run by test/test_capi.f90 (suite capi, "flow pressure"). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "egw.h"

static int failures;
#define CHECK(cond) do { if (!(cond)) { failures++; \
  printf("    C check failed at %s:%d: %s\n", __FILE__, __LINE__, #cond); } } while (0)

static int message_has(const char *text) {
  char buf[512];
  if (egw_last_error(buf, (int)sizeof buf) < 1) return 0;
  return strstr(buf, text) != NULL;
}

static egw_params capped(void) {
  egw_params p;
  egw_params_default(&p);
  p.model = EGW_MODEL_HERTZ;
  p.flow_pressure = 2.0 / M_PI;
  return p;
}

/* Defaults and validation: flow_pressure 0; negative, NaN, inf, >= modulus refused with
 * a message naming it; a rough model with the cap valid and solved (doc/theory.md
 * section 12, "Rough spheres with the cap"; the physics in test/test_rough_cap.f90). */
int egw_capi_test_flow_pressure_params(void) {
  egw_params p;
  failures = 0;
  egw_params_default(&p);
  CHECK(p.flow_pressure == 0.0);
  CHECK(egw_get_version() == EGW_VERSION && EGW_VERSION == 306);
#define BAD(value) do { egw_params q = p; q.flow_pressure = value; \
    CHECK(egw_params_validate(&q) == EGW_INVALID_PARAMETER); \
    CHECK(message_has("flow_pressure")); } while (0)
  BAD(-1.0);
  BAD(NAN);
  BAD(INFINITY);
  BAD(-INFINITY);
  BAD(1.0); /* = modulus: not a small-strain cap */
  /* R = E* = 1: a_y = pi p_y/2 = 1.6e-300, delta_y = a_y^2 underflowed to 0 (accepted
   * before; a GW + cap solve then returned EGW_OK with force 0) */
  BAD(1e-300);
  BAD(1e-200); /* a_y a normal double, delta_y = 2.5e-400 not */
#undef BAD
  {
    /* the cap's scales leave the doubles through R or E* too: named flow_pressure */
    egw_params q = capped();
    egw_result r;
    double delta_y = -1.0;
    q.radius = 1e-300; /* a_y = 1e-300 */
    CHECK(egw_params_validate(&q) == EGW_INVALID_PARAMETER);
    CHECK(message_has("flow_pressure") && message_has("radius"));
    q = capped();
    q.modulus = 1e300;
    q.flow_pressure = 2.0 / M_PI * 1e300; /* a_y = 1, P_y = (4/3) 1e300 */
    CHECK(egw_params_validate(&q) == EGW_INVALID_PARAMETER);
    CHECK(message_has("flow_pressure"));
    q = capped();
    q.model = EGW_MODEL_GW;
    q.sigma = 1e-3;
    q.mu = 2.0;
    q.flow_pressure = 1e-300;
    CHECK(egw_solve(&q, NULL, 2e-3, &r) == EGW_INVALID_PARAMETER);
    CHECK(message_has("flow_pressure"));
    /* inside the scales: p_y = 1e-50 (P_y = 5e-150); the closed forms
     * delta_y = a_y^2, (1/2) v_y^2 = (8/15) a_y^5 (R = E* = m* = 1) to a few roundings */
    q = capped();
    q.flow_pressure = 1e-50;
    CHECK(egw_params_validate(&q) == EGW_OK);
    {
      double velocity_y = -1.0, a_y = M_PI / 2.0 * 1e-50;
      CHECK(egw_first_yield(&q, 1.0, &delta_y, &velocity_y) == EGW_OK);
      CHECK(fabs(delta_y / (a_y * a_y) - 1.0) < 1e-14);
      CHECK(fabs(velocity_y / sqrt(16.0 / 15.0 * pow(a_y, 5.0)) - 1.0) < 1e-14);
    }
  }
  {
    egw_params q = capped();
    egw_result r;
    CHECK(egw_params_validate(&q) == EGW_OK);
    q.model = EGW_MODEL_EGW; /* sigma = 0: smooth, the cap is served */
    CHECK(egw_params_validate(&q) == EGW_OK);
    q.sigma = 1e-3;
    q.mu = 4.0;
    CHECK(egw_params_validate(&q) == EGW_OK);
    /* p_y = 2/pi: E-GW's capped force lies below the cap-free one, above 0 */
    {
      egw_result free;
      egw_params f = q;
      f.flow_pressure = 0.0;
      CHECK(egw_solve(&q, NULL, 2.0, &r) == EGW_OK);
      CHECK(egw_solve(&f, NULL, 2.0, &free) == EGW_OK);
      CHECK(r.force > 0.0 && r.force < free.force);
    }
  }
  return failures;
}

/* Solves: loading and unloading against the reference at 1e-4 (a tenth of issue 32's
 * goal; egw's fitted 32/64-ring solve is within 3.3e-6 up to 100 delta_y), e within 1e-4
 * (the goal is 1 %; measured 1e-7). flow_pressure = 0 and overlaps up to first yield:
 * Hertz, bit for bit. */
int egw_capi_test_flow_pressure_solves(void) {
  const double load_x[3] = {2.0, 3.0, 10.0};
  const double load_ref[3] = {2.720383972669e+00, 4.696156337776e+00, 2.091895411785e+01};
  const double fy = 4.0 / 3.0;
  egw_params p = capped(), h;
  egw_result r, hz;
  double e, w_load, w_dis, e2;
  failures = 0;
  for (int i = 0; i < 3; i++) {
    CHECK(egw_solve(&p, NULL, load_x[i], &r) == EGW_OK);
    CHECK(fabs(r.force / fy - load_ref[i]) <= 1e-4 * load_ref[i]);
    CHECK(r.max_pressure <= p.flow_pressure * (1 + 1e-12));
    CHECK(r.contact_radius > sqrt(load_x[i])); /* wider than Hertz's sqrt(R delta) */
  }
  /* unloading from delta_max = 2 to 0.9 delta_max, and from 10 to 0.9 delta_max */
  CHECK(egw_solve_unload(&p, NULL, 1.8, 2.0, &r) == EGW_OK);
  CHECK(fabs(r.force / fy - 2.298961418756) <= 1e-4 * 2.298961418756);
  CHECK(egw_solve_unload(&p, NULL, 9.0, 10.0, &r) == EGW_OK);
  CHECK(fabs(r.force / fy - 1.535888043866e+01) <= 1e-4 * 1.535888043866e+01);
  /* below the residual overlap (0.144 delta_max after 2 delta_y): no force */
  CHECK(egw_solve_unload(&p, NULL, 0.2, 2.0, &r) == EGW_OK && r.force == 0.0);
  /* flow_pressure = 0 and any overlap at or below delta_y: Hertz exactly */
  h = p;
  h.flow_pressure = 0.0;
  {
    const double d[3] = {0.3, 0.999, 1.0};
    for (int i = 0; i < 3; i++) {
      CHECK(egw_solve(&p, NULL, d[i], &r) == EGW_OK && egw_solve(&h, NULL, d[i], &hz) == EGW_OK);
      CHECK(r.force == hz.force && r.stiffness == hz.stiffness &&
            r.contact_radius == hz.contact_radius && r.max_pressure == hz.max_pressure);
      /* reversible: unloading below first yield retraces Hertz */
      CHECK(egw_solve_unload(&p, NULL, 0.5 * d[i], d[i], &r) == EGW_OK);
      CHECK(egw_solve(&h, NULL, 0.5 * d[i], &hz) == EGW_OK && r.force == hz.force);
    }
  }
  CHECK(egw_solve(&h, NULL, 3.0, &hz) == EGW_OK);
  CHECK(fabs(hz.force / (4.0 / 3.0 * pow(3.0, 1.5)) - 1) < 4e-16); /* an ulp or two */
  /* restitution at v = 5 v_y (e = 0.8315491288598) and 0.5 v_y (elastic: 1) */
  CHECK(egw_restitution(&p, NULL, 16.0 / 15.0, 5.0, &e) == EGW_OK);
  CHECK(fabs(e - 0.8315491288598) <= 1e-4 * 0.8315491288598);
  CHECK(egw_restitution_energy(&p, NULL, 16.0 / 15.0, 5.0, &e2, &w_load, &w_dis) == EGW_OK);
  CHECK(e2 == e && fabs(w_load - 0.5 * 16.0 / 15.0 * 25.0) <= 1e-15 * w_load);
  CHECK(fabs(w_dis - (1 - e * e) * w_load) <= 1e-15 * w_load);
  CHECK(egw_restitution(&p, NULL, 16.0 / 15.0, 0.5, &e) == EGW_OK && e == 1.0);
  return failures;
}

/* Doors that do not serve the cap yet refuse it with a message naming flow_pressure. */
int egw_capi_test_flow_pressure_refusals(void) {
  egw_params p = capped();
  egw_table t = NULL;
  egw_hysteresis hy = NULL;
  double duration, step, r[2] = {0.0, 0.5}, pr[2], w[2];
  failures = 0;
  CHECK(egw_table_build(&p, NULL, -1.0, 5.0, 1e-3, &t) == EGW_INVALID_PARAMETER && t == NULL);
  CHECK(message_has("flow_pressure"));
  /* served now (Hertz + cap hysteresis tables, the time step: test/cap_dem_checks.c) */
  CHECK(egw_hysteresis_build(&p, NULL, -1.0, 5.0, 1e-3, &hy) == EGW_OK && hy != NULL);
  egw_hysteresis_free(&hy);
  CHECK(egw_time_step(&p, NULL, 16.0 / 15.0, 5.0, 1e-3, &duration, &step) == EGW_OK &&
        step > 0 && duration > step);
  /* served now beyond first yield (delta_y = 1 here): p = p_y on the capped disc (its
   * radius 1.27 a_y at 3 delta_y, tools/reference/cap_reference.py), w = delta - r^2/2 on
   * the contact (the surfaces' total displacement, plastic crater included) */
  CHECK(egw_profile(&p, NULL, 3.0, 2, r, pr, w) == EGW_OK);
  CHECK(pr[0] == p.flow_pressure && pr[1] == p.flow_pressure);
  CHECK(fabs(w[0] - 3.0) <= 1e-14 && fabs(w[1] - (3.0 - 0.125)) <= 1e-14);
  /* rough + cap: its loading and unloading profiles are served (total pressure <= p_y) */
  {
    egw_params q = p;
    q.model = EGW_MODEL_EGW;
    q.sigma = 1e-3;
    q.mu = 4.0;
    q.flow_pressure = 0.01;
    CHECK(egw_profile(&q, NULL, 2e-3, 2, r, pr, w) == EGW_OK);
    CHECK(pr[0] <= 0.01 * (1 + 1e-12) && pr[0] > 0.009);
    CHECK(egw_profile_unload(&q, NULL, 1e-3, 2e-3, 2, r, pr, w) == EGW_OK);
    CHECK(pr[0] <= 0.01 * (1 + 1e-12) && pr[0] > 0.0);
  }
  /* below first yield the profile is Hertz's */
  CHECK(egw_profile(&p, NULL, 0.5, 2, r, pr, w) == EGW_OK);
  return failures;
}

/* egw_first_yield: in the cap's units (R = E* = 1, p_y = 2/pi: delta_y = 1, P_y = 4/3; m* =
 * 16/15: v_y = 1, since (1/2) m* v_y^2 = (8/15) delta_y^(5/2)) both are 1 to a few ulp;
 * for a steel pair (R = 0.5 mm, E* = 115 GPa, p_y = 1.6 GPa) against the same energy balance
 * written out, and egw_restitution_overlap's deepest overlap at v_y is delta_y (the
 * solver's Hertz impact: 1e-9). flow_pressure 0: DBL_MAX; bad mass, NULL p refused. */
int egw_capi_test_first_yield(void) {
  egw_params p = capped(), s = capped(), h = capped();
  double dy = 0, vy = 0, dm = 0, m;
  failures = 0;
  CHECK(egw_first_yield(&p, 16.0 / 15.0, &dy, &vy) == EGW_OK);
  CHECK(fabs(dy - 1) <= 4e-16 && fabs(vy - 1) <= 8e-16);
  s.radius = 0.5e-3, s.modulus = 115e9, s.flow_pressure = 1.6e9;
  m = 7800 * 4.0 / 3.0 * M_PI * 1e-9 / 2; /* two 1 mm steel beads */
  CHECK(egw_first_yield(&s, m, &dy, &vy) == EGW_OK);
  {
    double d = pow(M_PI * 1.6e9 / (2 * 115e9), 2) * 0.5e-3;
    double v = sqrt(2 * (8.0 / 15.0) * 115e9 * sqrt(0.5e-3) * pow(d, 2.5) / m);
    CHECK(fabs(dy / d - 1) <= 1e-14 && fabs(vy / v - 1) <= 1e-14);
  }
  CHECK(egw_restitution_overlap(&s, NULL, m, vy, NULL, &dm) == EGW_OK);
  CHECK(fabs(dm / dy - 1) <= 1e-9);
  CHECK(egw_first_yield(&s, m, NULL, NULL) == EGW_OK);
  h.flow_pressure = 0.0;
  CHECK(egw_first_yield(&h, 1.0, &dy, &vy) == EGW_OK && dy == DBL_MAX && vy == DBL_MAX);
  dy = vy = -1;
  CHECK(egw_first_yield(&p, 0.0, &dy, &vy) == EGW_INVALID_ARGUMENT && dy == -1 && vy == -1);
  CHECK(message_has("mass"));
  CHECK(egw_first_yield(&p, NAN, &dy, &vy) == EGW_INVALID_ARGUMENT);
  CHECK(egw_first_yield(NULL, 1.0, &dy, &vy) == EGW_NULL_POINTER);
  p.flow_pressure = -1;
  CHECK(egw_first_yield(&p, 1.0, &dy, &vy) == EGW_INVALID_PARAMETER);
  CHECK(message_has("flow_pressure"));
  return failures;
}
