/* C tests of issue 13 items 2, 3 and 6: inputs at the edge of the doubles give a finite
 * correct result or a status naming the argument (with the valid range), in bounded
 * time, and outputs stay untouched on refusal. Each egw_input_test_* returns the number
 * of failed checks; test/test_input.f90 runs them as the "input" suite. References are
 * closed forms evaluated here (tgamma, pow), never egw's own output, except where a
 * check is a continuity or consistency property (stated). */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "egw.h"

static const double PI = 3.14159265358979323846;

static int failures;
#define CHECK(cond) do { if (!(cond)) { failures++; \
  printf("    C check failed at %s:%d: %s\n", __FILE__, __LINE__, #cond); } } while (0)
static int close_rel(double a, double b, double tol) { return fabs(a - b) <= tol * fabs(b); }
/* the last error starts with name and (when given) contains text */
static int names(const char *name, const char *text) {
  char buf[512];
  if (egw_last_error(buf, (int)sizeof buf) < 1) return 0;
  if (strncmp(buf, name, strlen(name)) != 0) {
    printf("    last error: %s\n", buf);
    return 0;
  }
  return text == NULL || strstr(buf, text) != NULL;
}
static egw_params rough(int model) {
  egw_params p;
  egw_params_default(&p);
  p.model = model;
  p.sigma = 1e-3;
  p.mu = 2.0;
  if (model == EGW_MODEL_EPGW) p.psi = 0.5;
  return p;
}

/* item 6: the Gaussian integral's order and overflow */
int egw_input_test_gauss(void) {
  double v = 42.0;
  failures = 0;
  CHECK(egw_gauss_integral(INFINITY, 0.0, &v) == EGW_INVALID_ARGUMENT && names("n = +Inf", "[0,"));
  CHECK(egw_gauss_integral(1e300, 0.0, &v) == EGW_INVALID_ARGUMENT && names("n =", NULL));
  CHECK(egw_gauss_integral(151.0, 0.0, &v) == EGW_INVALID_ARGUMENT && v == 42.0);
  CHECK(egw_gauss_integral_deriv(INFINITY, 0.0, &v) == EGW_INVALID_ARGUMENT && v == 42.0);
  /* F_n(-Inf) = +Inf for n > 0: beyond the doubles, refused; F_0(-Inf) = 1 */
  CHECK(egw_gauss_integral(1.5, -INFINITY, &v) == EGW_INVALID_ARGUMENT && names("h = -Inf", NULL));
  CHECK(egw_gauss_integral(1.5, -1e300, &v) == EGW_INVALID_ARGUMENT && v == 42.0);
  CHECK(egw_gauss_integral(0.0, -INFINITY, &v) == EGW_OK && v == 1.0);
  /* F_150(0) = 2^74.5 Gamma(75.5)/sqrt(2 pi) (closed form); documented 1e-12 */
  {
    double ref = exp(74.5 * log(2.0) + lgamma(75.5)) / sqrt(2.0 * PI);
    CHECK(egw_gauss_integral(150.0, 0.0, &v) == EGW_OK && close_rel(v, ref, 1e-12));
  }
  /* dF_n/dh at tiny n: -n F_{n-1}(0) = -2^(n/2) Gamma(n/2 + 1)/sqrt(2 pi) (closed form);
   * before the fix n = 1e-15 was 8e-4 off and n <= 1e-16 gave -Inf */
  {
    const double ns[] = {1e-5, 1e-8, 1e-12, 1e-15, 1e-300, 4.9e-324};
    for (int i = 0; i < 6; i++) {
      double n = ns[i];
      double ref = -exp(0.5 * n * log(2.0) + lgamma(0.5 * n + 1.0)) / sqrt(2.0 * PI);
      v = 42.0;
      CHECK(egw_gauss_integral_deriv(n, 0.0, &v) == EGW_OK && close_rel(v, ref, 1e-12));
    }
    /* at h = 2: -n F_{n-1}(2) = -(F_{n+1}(2) + 2 F_n(2)) (integration by parts, no
     * cancellation at h > 0), from the fitted orders at n -> 0: -(F_1(2) + 2 F_0(2)),
     * F_1(h) = phi(h) - h Q(h), F_0 = Q: so -phi(2) to O(n) = 1e-10 relative */
    CHECK(egw_gauss_integral_deriv(1e-10, 2.0, &v) == EGW_OK &&
          close_rel(v, -exp(-2.0) / sqrt(2.0 * PI), 1e-9));
    /* far below: n F_{n-1}(h) = n |h|^(n-1) exactly (every summit above h) */
    CHECK(egw_gauss_integral_deriv(1e-6, -1e200, &v) == EGW_OK &&
          close_rel(v, -1e-6 * pow(1e200, 1e-6 - 1.0), 1e-12));
  }
  return failures;
}

/* items 2, 6: parameters outside what the numerics represent are refused with the range */
int egw_input_test_ranges(void) {
  egw_params p;
  double v = 42.0, dv = 43.0;
  failures = 0;
  p = rough(EGW_MODEL_EGW);
  p.sigma = 4.9e-324;
  CHECK(egw_params_validate(&p) == EGW_INVALID_PARAMETER && names("sigma", "normal"));
  p = rough(EGW_MODEL_EGW);
  p.sigma = 1e-300; /* E sqrt(R) sigma^1.5 = 1e-450: not a double */
  CHECK(egw_flat_pressure(&p, 0.0, &v) == EGW_INVALID_PARAMETER && names("sigma", "sigma**1.5"));
  p = rough(EGW_MODEL_EGW);
  p.sigma = 1e300;
  CHECK(egw_params_validate(&p) == EGW_INVALID_PARAMETER && names("sigma", NULL));
  p = rough(EGW_MODEL_EPGW);
  p.psi = 1e-300;
  CHECK(egw_flat_pressure(&p, 0.0, &v) == EGW_INVALID_PARAMETER && names("psi", "["));
  p.psi = 4.9e-324;
  CHECK(egw_params_validate(&p) == EGW_INVALID_PARAMETER && names("psi", NULL));
  p = rough(EGW_MODEL_EPGW);
  p.hardness_coeff = 1e-300;
  CHECK(egw_params_validate(&p) == EGW_INVALID_PARAMETER && names("hardness_coeff", "["));
  p = rough(EGW_MODEL_EPGW);
  p.plastic_ratio = 1e300;
  CHECK(egw_params_validate(&p) == EGW_INVALID_PARAMETER && names("plastic_ratio", NULL));
  p = rough(EGW_MODEL_EGW);
  p.mu = 1e300;
  CHECK(egw_flat_pressure(&p, 0.0, &v) == EGW_INVALID_PARAMETER && names("mu", "["));
  p.mu = 1e-300;
  CHECK(egw_params_validate(&p) == EGW_INVALID_PARAMETER && names("mu", NULL));
  p = rough(EGW_MODEL_HERTZ);
  p.sigma = 0.0;
  p.radius = 4.9e-324; /* used to underflow a = sqrt(R delta) to 0 */
  CHECK(egw_params_validate(&p) == EGW_INVALID_PARAMETER && names("radius", "subnormal"));
  CHECK(v == 42.0);
  /* the edges themselves are accepted and finite */
  p = rough(EGW_MODEL_EPGW);
  p.psi = 1e-50;
  p.hardness_coeff = 1e-20;
  p.mu = 1e20;
  CHECK(egw_flat_pressure_deriv(&p, 0.0, &v, &dv) == EGW_OK && isfinite(v) && isfinite(dv));
  /* a finite pressure whose old coefficient C = mu E/(2 sigma sqrt(2R)) overflowed:
   * p_G(0) = mu E sqrt(sigma/R)/(2 sqrt 2) F_3/2(0), F_3/2(0) = 2^(1/4) Gamma(5/4)/sqrt(2 pi) */
  p = rough(EGW_MODEL_EGW);
  p.modulus = 1e200;
  p.sigma = 1e-100;
  p.mu = 1e19;
  {
    double ref = 1e19 * 1e200 * 1e-50 / (2.0 * sqrt(2.0)) * pow(2.0, 0.25) * tgamma(1.25) /
                 sqrt(2.0 * PI);
    CHECK(egw_flat_pressure(&p, 0.0, &v) == EGW_OK && close_rel(v, ref, 1e-14));
  }
  /* a separation so deep that p_G overflows: refused, untouched */
  p = rough(EGW_MODEL_EGW);
  v = 42.0;
  CHECK(egw_flat_pressure(&p, -1e300, &v) == EGW_INVALID_ARGUMENT && names("separation", NULL));
  CHECK(egw_flat_pressure(&p, -INFINITY, &v) == EGW_INVALID_ARGUMENT && v == 42.0);
  /* mu from summits that overflows */
  CHECK(egw_mu_from_summits(1e300, 1.0, 1e300, 1.0, &v) == EGW_INVALID_ARGUMENT &&
        names("mu", NULL) && v == 42.0);
  return failures;
}

/* item 6: Hertz at the edges of the doubles */
int egw_input_test_hertz(void) {
  egw_params p;
  double f = 42.0, k = 42.0, a = 42.0;
  failures = 0;
  egw_params_default(&p);
  p.model = EGW_MODEL_HERTZ;
  CHECK(egw_hertz(&p, 1e300, &f, &k, &a) == EGW_INVALID_ARGUMENT && names("delta", "largest"));
  CHECK(f == 42.0 && k == 42.0 && a == 42.0);
  /* R delta = 1e-310 is subnormal: a = sqrt(R) sqrt(delta) keeps every digit */
  p.radius = 1e-300;
  CHECK(egw_hertz(&p, 1e-10, &f, &k, &a) == EGW_OK);
  CHECK(close_rel(a, 1e-155, 4e-16));
  CHECK(close_rel(f, 4.0 / 3.0 * 1e-150 * 1e-15, 8e-16));
  /* (4/3) E a = 1.3e-310 is subnormal on the way, the force 1.3e-300 is not: every digit
   * kept (a = sqrt(1e-30 1e10) = 1e-10) */
  p.radius = 1e-30;
  p.modulus = 1e-300;
  CHECK(egw_hertz(&p, 1e10, &f, &k, &a) == EGW_OK && close_rel(f, 4.0 / 3.0 * 1e-300, 8e-16));
  /* E a overflows: the stiffness 2 E a is beyond the doubles, refused */
  p.radius = 1e300;
  p.modulus = 1e300;
  f = 42.0;
  CHECK(egw_hertz(&p, 1e-200, &f, &k, &a) == EGW_INVALID_ARGUMENT && f == 42.0);
  return failures;
}

/* items 2, 3, 6: the solver */
int egw_input_test_solve(void) {
  egw_params p = rough(EGW_MODEL_EGW);
  egw_options o;
  egw_result r, r0, sentinel;
  failures = 0;
  egw_options_default(&o);
  o.rel_tol = 1e-6;
  o.n_threads = 1;
  memset(&sentinel, 0x5A, sizeof sentinel);
  /* delta = 4.9e-324 is delta/sigma = 4.9e-321: 0 to the solver's precision. Continuity
   * of P at 0 (the property; both solves are the same discrete problem): equal */
  CHECK(egw_solve(&p, &o, 0.0, &r0) == EGW_OK && r0.force > 0.0);
  CHECK(egw_solve(&p, &o, 4.9e-324, &r) == EGW_OK && close_rel(r.force, r0.force, 1e-15));
  p.model = EGW_MODEL_EPGW;
  p.psi = 1.0;
  CHECK(egw_solve(&p, &o, 0.0, &r0) == EGW_OK);
  CHECK(egw_solve(&p, &o, 4.9e-324, &r) == EGW_OK && close_rel(r.force, r0.force, 1e-15));
  /* scale invariance at the edges of the doubles: P = E sqrt(R) sigma^1.5 p(delta/sigma),
   * k = E sqrt(R sigma) p'(delta/sigma) exactly (the scaled problems are identical; only
   * the unit's few roundings differ: 1e-14). sigma^1.5 = 1e-450 alone underflows, the
   * force unit 2.2e-152 does not (it used to give a force of 0) */
  {
    egw_params unit = rough(EGW_MODEL_EGW), big = rough(EGW_MODEL_EGW);
    unit.sigma = 1.0;
    big.radius = 5e-4;
    big.modulus = 1e300;
    big.sigma = 1e-300;
    CHECK(egw_solve(&unit, &o, 2.0, &r0) == EGW_OK);
    CHECK(egw_solve(&big, &o, 2e-300, &r) == EGW_OK);
    CHECK(close_rel(r.force, r0.force * (1e300 * sqrt(5e-4) * 1e-300 * 1e-150), 1e-14));
    CHECK(close_rel(r.stiffness, r0.stiffness * (1e300 * sqrt(5e-4) * 1e-150), 1e-14));
    CHECK(close_rel(r.contact_radius, r0.contact_radius * sqrt(5e-4) * 1e-150, 1e-14));
  }
  /* Hertz through egw_solve: p0 = (2/pi) E sqrt(delta/R) = 6.4e294 although 2E/(pi R)
   * alone overflows (it used to return max_pressure = +Inf with EGW_OK) */
  {
    egw_params h;
    egw_params_default(&h);
    h.model = EGW_MODEL_HERTZ;
    h.modulus = 1e300;
    h.radius = 1e-10;
    CHECK(egw_solve(&h, &o, 1e-20, &r) == EGW_OK);
    CHECK(close_rel(r.max_pressure, 2.0 / PI * 1e300 * 1e-5, 1e-15));
    CHECK(close_rel(r.force, 4.0 / 3.0 * 1e300 * 1e-5 * 1e-30, 1e-15));
  }
  p = rough(EGW_MODEL_EGW);
  /* refusals leave *res untouched (egw.h conventions) */
  r = sentinel;
  p.sigma = 1e300;
  CHECK(egw_solve(&p, &o, 1e-3, &r) == EGW_INVALID_PARAMETER && names("sigma", NULL));
  CHECK(memcmp(&r, &sentinel, sizeof r) == 0);
  p = rough(EGW_MODEL_EGW);
  CHECK(egw_solve(&p, &o, 1e300, &r) == EGW_INVALID_ARGUMENT && names("delta", "1.0"));
  CHECK(memcmp(&r, &sentinel, sizeof r) == 0);
  {
    egw_options bad = o;
    bad.method = EGW_METHOD_PICARD;
    bad.max_iter = 1; /* cannot converge in one damped step */
    CHECK(egw_solve(&p, &bad, 2e-3, &r) == EGW_NOT_CONVERGED);
    CHECK(memcmp(&r, &sentinel, sizeof r) == 0);
  }
  /* item 3: n_radial = 1e8 and INT_MAX refused (it used to exit in the allocator or run
   * for minutes), n_threads = INT_MAX capped (it used to abort in libgomp) */
  {
    egw_options big = o;
    big.n_radial = 100000000;
    CHECK(egw_solve(&p, &big, 2e-3, &r) == EGW_INVALID_ARGUMENT && names("n_radial", "4097"));
    big.n_radial = INT_MAX;
    CHECK(egw_solve(&p, &big, 2e-3, &r) == EGW_INVALID_ARGUMENT);
    CHECK(memcmp(&r, &sentinel, sizeof r) == 0);
    big = o;
    big.n_threads = INT_MAX;
    CHECK(egw_solve(&p, &o, 2e-3, &r0) == EGW_OK);
    /* the assembly fills whole rows per thread: the same numbers with any team size */
    CHECK(egw_solve(&p, &big, 2e-3, &r) == EGW_OK && r.force == r0.force);
  }
  return failures;
}

/* items 2, 6: tables, universal tables and the scene choice */
int egw_input_test_tables(void) {
  egw_params p = rough(EGW_MODEL_EGW);
  egw_table t = NULL, t2 = (egw_table)&t;
  egw_universal u = (egw_universal)&t;
  double f = 42.0, k = 42.0, e = 42.0, a = 42.0;
  failures = 0;
  /* delta_max = 1e300 (delta/sigma = 1e303) used to run for minutes: refused at once */
  CHECK(egw_table_build(&p, NULL, -2e-3, 1e300, 1e-2, &t2) == EGW_INVALID_ARGUMENT &&
        names("delta_max", "sigma"));
  CHECK(t2 == (egw_table)&t);
  p.model = EGW_MODEL_EPGW;
  p.psi = 1e-300;
  CHECK(egw_table_build(&p, NULL, -2e-3, 1e-2, 1e-2, &t2) == EGW_INVALID_PARAMETER &&
        names("psi", NULL));
  p = rough(EGW_MODEL_HERTZ);
  p.sigma = 0.0;
  CHECK(egw_table_build(&p, NULL, 0.0, 1e300, 1e-2, &t2) == EGW_INVALID_ARGUMENT &&
        names("delta_max", "Hertz"));
  p = rough(EGW_MODEL_EGW);
  CHECK(egw_universal_build(&p, NULL, 1.0, 4.0, -2.0, 1e300, 1e-2, &u) == EGW_INVALID_ARGUMENT &&
        names("x_max", NULL));
  CHECK(egw_universal_build(&p, NULL, 1e-300, 4.0, -2.0, 10.0, 1e-2, &u) == EGW_INVALID_PARAMETER &&
        names("mu", NULL));
  CHECK(egw_universal_build(&p, NULL, 1.0, 1e300, -2.0, 10.0, 1e-2, &u) == EGW_INVALID_PARAMETER &&
        names("mu", NULL));
  CHECK(u == (egw_universal)&t);

  p = rough(EGW_MODEL_EGW);
  CHECK(egw_table_build(&p, NULL, -2e-3, 1e-2, 1e-2, &t) == EGW_OK);
  if (t) {
    /* above delta_max the deep-overlap asymptote P_n r^(3/2): +Inf and 1e300 leave the
     * doubles (refused, nothing written) */
    CHECK(egw_table_eval(t, INFINITY, &f, &k) == EGW_INVALID_ARGUMENT && names("delta = +Inf", NULL));
    CHECK(f == 42.0 && k == 42.0);
    CHECK(egw_table_eval(t, 1e300, &f, &k) == EGW_INVALID_ARGUMENT && f == 42.0 && k == 42.0);
    /* at 1e150 the force ~ (1e150/u_0)^1.5 P_n ~ 1e229 is still a double: written; the
     * energy ~ P delta/2.5 ~ 1e379 is not: eval_all refuses, nothing written */
    CHECK(egw_table_eval(t, 1e150, &f, &k) == EGW_OUT_OF_RANGE && isfinite(f) && f > 1e220);
    f = k = 42.0;
    CHECK(egw_table_eval_all(t, 1e150, &f, &k, &e, &a) == EGW_INVALID_ARGUMENT && e == 42.0 &&
          f == 42.0);
    {
      double d[2] = {1e-3, INFINITY}, fs[2] = {42.0, 42.0};
      CHECK(egw_table_eval_array(t, 2, d, fs, NULL) == EGW_INVALID_ARGUMENT &&
            names("delta[1]", NULL) && fs[0] == 42.0);
      CHECK(egw_table_eval_array(t, 2, NULL, fs, NULL) == EGW_NULL_POINTER && names("delta", NULL));
    }
    /* below the cut-off the force is exactly 0, also at -Inf */
    CHECK(egw_table_eval(t, -INFINITY, &f, &k) == EGW_OK && f == 0.0 && k == 0.0);
    /* 2 delta_max: extrapolated, finite, written */
    CHECK(egw_table_eval(t, 2e-2, &f, &k) == EGW_OUT_OF_RANGE && isfinite(f) && f > 0.0);
    egw_table_free(&t);
  }
  return failures;
}

/* item 2: the scene choice samples a bounded number of overlaps */
int egw_input_test_scene(void) {
  egw_scene s;
  egw_model_choice c;
  failures = 0;
  egw_scene_default(&s);
  s.delta_min = 1e-300; /* in units of sigma: used to ask for 1200 Hertz-check solves */
  s.tol = 1e-2;
  CHECK(egw_scene_choose(&s, NULL, &c, NULL, 0) == EGW_OK);
  /* 4 per decade from 1e-12 sigma to 20 sigma: 55 samples */
  CHECK(c.n_solves <= 60 && c.kind != EGW_CHOICE_HERTZ);
  s.delta_max = 1e300;
  CHECK(egw_scene_choose(&s, NULL, &c, NULL, 0) != EGW_OK);
  return failures;
}
