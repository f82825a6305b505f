/* C tests of the array kernels of include/egw.h (egw_*_array): each point equals the scalar
 * call bit for bit, strides 0 and 1 for inputs and params, NaN refused with the point's
 * index or turned into NaN with a count, threads do not change results.
 * test/test_capi_array.f90 runs them as a test-drive suite. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "egw.h"

static int failures;
#define CHECK(cond) do { if (!(cond)) { failures++; \
  printf("    C check failed at %s:%d: %s\n", __FILE__, __LINE__, #cond); } } while (0)
static int last_error_starts(const char *prefix) {
  char buf[512];
  if (egw_last_error(buf, (int)sizeof buf) < 1) return 0; /* the bytes needed, or < 0 */
  return strncmp(buf, prefix, strlen(prefix)) == 0;
}
static egw_params rough(int model) {
  egw_params p;
  egw_params_default(&p);
  p.model = model; p.radius = 5e-4; p.modulus = 3.678e10; p.sigma = 1e-6; p.mu = 4.0;
  return p;
}

int egw_capi_test_array_hertz(void) {
  enum { N = 5 };
  egw_params p[2];
  double delta[N] = {-1e-6, 0.0, 1e-7, 1e-6, 1e-5}, f[N], k[N], a[N];
  int nf = -1;
  failures = 0;
  p[0] = rough(EGW_MODEL_HERTZ); p[1] = p[0]; p[1].radius = 2e-3;
  CHECK(egw_hertz_array(p, 0, N, delta, 1, f, k, a, EGW_ARRAY_RAISE, &nf) == EGW_OK);
  CHECK(nf == 0);
  for (int i = 0; i < N; i++) {
    double fs, ks, as;
    CHECK(egw_hertz(&p[0], delta[i], &fs, &ks, &as) == EGW_OK);
    CHECK(f[i] == fs && k[i] == ks && a[i] == as);
  }
  /* per-point params (stride 1) against one shared overlap (stride 0) */
  CHECK(egw_hertz_array(p, 1, 2, &delta[3], 0, f, NULL, NULL, EGW_ARRAY_RAISE, NULL) == EGW_OK);
  for (int i = 0; i < 2; i++) {
    double fs;
    CHECK(egw_hertz(&p[i], delta[3], &fs, NULL, NULL) == EGW_OK);
    CHECK(f[i] == fs);
  }
  /* NaN: refused naming the point, or NaN with a count */
  delta[2] = NAN;
  CHECK(egw_hertz_array(p, 0, N, delta, 1, f, k, a, EGW_ARRAY_RAISE, NULL) == EGW_INVALID_ARGUMENT);
  CHECK(last_error_starts("point 2: delta = NaN"));
  CHECK(egw_hertz_array(p, 0, N, delta, 1, f, k, a, EGW_ARRAY_NAN, &nf) == EGW_OK);
  CHECK(nf == 1 && isnan(f[2]) && isnan(a[2]) && f[4] > 0.0);
  /* a bad point's params: named with its index */
  p[1].radius = -1.0;
  CHECK(egw_hertz_array(p, 1, 2, &delta[3], 0, f, NULL, NULL, EGW_ARRAY_RAISE, NULL) == EGW_INVALID_PARAMETER);
  CHECK(last_error_starts("point 1: radius"));
  /* a shared bad p fails whatever the flags */
  CHECK(egw_hertz_array(&p[1], 0, 2, &delta[3], 0, f, NULL, NULL, EGW_ARRAY_NAN, &nf) == EGW_INVALID_PARAMETER);
  /* argument checks */
  CHECK(egw_hertz_array(p, 0, -1, delta, 1, f, k, a, 0, NULL) == EGW_INVALID_ARGUMENT);
  CHECK(egw_hertz_array(p, -1, 1, delta, 1, f, k, a, 0, NULL) == EGW_INVALID_ARGUMENT);
  CHECK(egw_hertz_array(p, 0, 1, delta, -1, f, k, a, 0, NULL) == EGW_INVALID_ARGUMENT);
  CHECK(egw_hertz_array(p, 0, 1, delta, 1, f, k, a, 7, NULL) == EGW_INVALID_ARGUMENT);
  CHECK(egw_hertz_array(NULL, 0, 1, delta, 1, f, k, a, 0, NULL) == EGW_NULL_POINTER);
  CHECK(egw_hertz_array(p, 0, 1, NULL, 1, f, k, a, 0, NULL) == EGW_NULL_POINTER);
  CHECK(egw_hertz_array(p, 0, 0, delta, 1, f, k, a, 0, NULL) == EGW_OK);
  return failures;
}

int egw_capi_test_array_flat(void) {
  enum { N = 4 };
  egw_params p = rough(EGW_MODEL_EPGW);
  double d[N] = {-2e-6, 0.0, 1e-6, 4e-6}, pr[N], dp[N], pu[N], g[N], dg[N];
  double order[2] = {1.5, 0.0};
  failures = 0;
  p.psi = 1.0;
  CHECK(egw_flat_pressure_array(&p, 0, N, d, 1, pr, dp, EGW_ARRAY_RAISE, NULL) == EGW_OK);
  CHECK(egw_flat_pressure_unload_array(&p, 0, N, d, 1, d, 0, pu, NULL, EGW_ARRAY_RAISE, NULL)
        == EGW_OK);
  CHECK(egw_gauss_integral_array(N, order, 0, d, 1, g, dg, EGW_ARRAY_RAISE, NULL) == EGW_OK);
  for (int i = 0; i < N; i++) {
    double ps, dps, pus, gs, dgs;
    CHECK(egw_flat_pressure_deriv(&p, d[i], &ps, &dps) == EGW_OK);
    CHECK(pr[i] == ps && dp[i] == dps);
    CHECK(egw_flat_pressure_unload(&p, d[i], d[0], &pus, NULL) == EGW_OK);
    CHECK(pu[i] == pus);
    CHECK(egw_gauss_integral(1.5, d[i], &gs) == EGW_OK && g[i] == gs);
    CHECK(egw_gauss_integral_deriv(1.5, d[i], &dgs) == EGW_OK && dg[i] == dgs);
  }
  d[1] = NAN;
  CHECK(egw_flat_pressure_array(&p, 0, N, d, 1, pr, dp, EGW_ARRAY_RAISE, NULL) == EGW_INVALID_ARGUMENT);
  CHECK(last_error_starts("point 1: "));
  return failures;
}

int egw_capi_test_array_solve(void) {
  enum { N = 6 };
  egw_params p = rough(EGW_MODEL_EGW);
  egw_options o1, o2;
  egw_result r1[N], r2[N];
  double delta[N] = {-2e-6, 0.0, 1e-6, 3e-6, 1e-5, 2e-5};
  int nf = -1;
  failures = 0;
  egw_options_default(&o1); o1.n_threads = 1;
  o2 = o1; o2.n_threads = 2;
  CHECK(egw_solve_array(&p, 0, &o1, N, delta, 1, NULL, 0, r1, EGW_ARRAY_RAISE, NULL) == EGW_OK);
  CHECK(egw_solve_array(&p, 0, &o2, N, delta, 1, NULL, 0, r2, EGW_ARRAY_RAISE, NULL) == EGW_OK);
  for (int i = 0; i < N; i++) {
    egw_result rs;
    CHECK(egw_solve(&p, &o1, delta[i], &rs) == EGW_OK);
    CHECK(r1[i].force == rs.force && r1[i].stiffness == rs.stiffness);
    CHECK(r2[i].force == rs.force && r2[i].contact_radius == rs.contact_radius);
  }
  /* unloading after one delta_max (stride 0) */
  p.model = EGW_MODEL_EPGW; p.psi = 1.0;
  CHECK(egw_solve_array(&p, 0, &o2, 3, &delta[2], 1, &delta[5], 0, r2, EGW_ARRAY_RAISE, NULL)
        == EGW_OK);
  for (int i = 0; i < 3; i++) {
    egw_result rs;
    CHECK(egw_solve_unload(&p, &o1, delta[2 + i], delta[5], &rs) == EGW_OK);
    CHECK(r2[i].force == rs.force);
  }
  delta[3] = NAN;
  CHECK(egw_solve_array(&p, 0, &o2, N, delta, 1, NULL, 0, r2, EGW_ARRAY_RAISE, NULL)
        == EGW_INVALID_ARGUMENT);
  CHECK(last_error_starts("point 3: "));
  CHECK(egw_solve_array(&p, 0, &o2, N, delta, 1, NULL, 0, r2, EGW_ARRAY_NAN, &nf) == EGW_OK);
  CHECK(nf == 1 && isnan(r2[3].force) && r2[3].iterations == -1 && r2[5].force > 0.0);
  CHECK(egw_solve_array(&p, 0, &o2, N, delta, 1, NULL, 0, NULL, 0, NULL) == EGW_NULL_POINTER);
  o2.n_threads = -1;
  CHECK(egw_solve_array(&p, 0, &o2, N, delta, 1, NULL, 0, r2, 0, NULL) == EGW_INVALID_ARGUMENT);
  return failures;
}

int egw_capi_test_array_impact(void) {
  egw_params p = rough(EGW_MODEL_EPGW);
  egw_options o;
  double mass = 1e-3, v[3] = {0.01, 0.1, 1.0}, e[3], wl[3], wd[3], dm[3], tc[3], dt[3];
  failures = 0;
  p.psi = 1.0;
  egw_options_default(&o); o.n_threads = 2;
  CHECK(egw_restitution_array(&p, 0, &o, 3, &mass, 0, v, 1, e, wl, wd, dm, EGW_ARRAY_RAISE,
                              NULL) == EGW_OK);
  CHECK(egw_time_step_array(&p, 0, &o, 3, &mass, 0, v, 1, 1e-3, tc, dt, EGW_ARRAY_RAISE, NULL)
        == EGW_OK);
  o.n_threads = 1;
  for (int i = 0; i < 3; i++) {
    double es, wls, wds, dms, tcs, dts;
    CHECK(egw_restitution_energy(&p, &o, mass, v[i], &es, &wls, &wds) == EGW_OK);
    CHECK(egw_restitution_overlap(&p, &o, mass, v[i], NULL, &dms) == EGW_OK);
    CHECK(e[i] == es && wl[i] == wls && wd[i] == wds && dm[i] == dms);
    CHECK(egw_time_step(&p, &o, mass, v[i], 1e-3, &tcs, &dts) == EGW_OK);
    CHECK(tc[i] == tcs && dt[i] == dts);
  }
  v[1] = -1.0;
  CHECK(egw_restitution_array(&p, 0, &o, 3, &mass, 0, v, 1, e, NULL, NULL, NULL,
                              EGW_ARRAY_RAISE, NULL) == EGW_INVALID_ARGUMENT);
  CHECK(last_error_starts("point 1: "));
  /* the shared tolerance is refused whatever the flags, outputs untouched (audit25: under
   * EGW_ARRAY_NAN it gave EGW_OK, every point NaN, no message) */
  {
    double bad_tol[3] = {0.0, NAN, 0.2}, tc2[3] = {7.0, 7.0, 7.0};
    int nf = -1;
    v[1] = 0.1;
    for (int i = 0; i < 3; i++) {
      for (int flags = EGW_ARRAY_RAISE; flags <= EGW_ARRAY_NAN; flags++) {
        CHECK(egw_time_step_array(&p, 0, &o, 3, &mass, 0, v, 1, bad_tol[i], tc2, NULL, flags,
                                  &nf) == EGW_INVALID_ARGUMENT);
        CHECK(last_error_starts("tolerance = "));
        CHECK(tc2[0] == 7.0 && tc2[1] == 7.0 && tc2[2] == 7.0 && nf == -1);
      }
    }
  }
  return failures;
}

int egw_capi_test_array_universal(void) {
  egw_params p = rough(EGW_MODEL_EGW), c[3];
  egw_universal u = NULL;
  double d[3] = {-1e-6, 1e-6, 3e-6}, f[3], k[3];
  int nf = -1;
  failures = 0;
  CHECK(egw_universal_build(&p, NULL, 2.0, 6.0, -2.0, 10.0, 1e-3, &u) == EGW_OK && u != NULL);
  if (u == NULL) return failures;
  for (int i = 0; i < 3; i++) { c[i] = p; c[i].mu = 2.5 + i; c[i].radius = 1e-4 * (i + 1); }
  CHECK(egw_universal_eval_array(u, c, 1, 3, d, 1, f, k, EGW_ARRAY_RAISE, &nf) == EGW_OK);
  CHECK(nf == 0);
  for (int i = 0; i < 3; i++) {
    double fs, ks;
    CHECK(egw_universal_eval(u, &c[i], d[i], &fs, &ks) == EGW_OK);
    CHECK(f[i] == fs && k[i] == ks);
  }
  /* mu outside the table: NaN there and EGW_OUT_OF_RANGE; a NaN overlap: refused */
  c[1].mu = 50.0;
  CHECK(egw_universal_eval_array(u, c, 1, 3, d, 1, f, k, EGW_ARRAY_RAISE, &nf) == EGW_OUT_OF_RANGE);
  CHECK(isnan(f[1]) && f[2] > 0.0);
  c[1].mu = 3.0; d[2] = NAN;
  CHECK(egw_universal_eval_array(u, c, 1, 3, d, 1, f, k, EGW_ARRAY_RAISE, NULL) == EGW_INVALID_ARGUMENT);
  CHECK(last_error_starts("point 2: delta"));
  CHECK(egw_universal_eval_array(u, c, 1, 3, d, 1, f, k, EGW_ARRAY_NAN, &nf) == EGW_OK);
  CHECK(nf == 1 && isnan(f[2]));
  CHECK(egw_universal_eval_array(NULL, c, 1, 3, d, 1, f, k, 0, NULL) == EGW_NULL_POINTER);
  egw_universal_free(&u);
  return failures;
}
