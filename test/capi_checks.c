/* C tests of include/egw.h: every entry point, with good and bad input.
 * Each egw_capi_test_* returns the number of failed checks and prints why;
 * test/test_capi.f90 runs them as one test-drive suite. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "egw.h"

static int failures;
#define CHECK(cond) do { if (!(cond)) { failures++; \
  printf("    C check failed at %s:%d: %s\n", __FILE__, __LINE__, #cond); } } while (0)
/* relative closeness; tol states the accuracy the API documents */
static int close_rel(double a, double b, double tol) {
  return fabs(a - b) <= tol * fabs(b);
}
static int last_error_names(const char *name) {
  char buf[256];
  if (egw_last_error(buf, (int)sizeof buf) < 1) return 0;
  return strncmp(buf, name, strlen(name)) == 0;
}

int egw_capi_test_version(void) {
  failures = 0;
  CHECK(egw_get_version() == EGW_VERSION);
  return failures;
}

int egw_capi_test_status_message(void) {
  char buf[128];
  failures = 0;
  for (int s = EGW_OK; s <= EGW_UNSUPPORTED; s++) {
    CHECK(egw_status_message(s, buf, (int)sizeof buf) == EGW_OK);
    CHECK(strlen(buf) > 0);
  }
  CHECK(egw_status_message(EGW_OK, buf, (int)sizeof buf) == EGW_OK && strcmp(buf, "success") == 0);
  /* truncation keeps the NUL inside the buffer */
  CHECK(egw_status_message(EGW_OK, buf, 4) == EGW_OK && strcmp(buf, "suc") == 0);
  CHECK(egw_status_message(EGW_OK, NULL, 10) == EGW_NULL_POINTER);
  CHECK(egw_status_message(EGW_OK, buf, 0) == EGW_INVALID_ARGUMENT);
  return failures;
}

/* egw_last_error as include/egw.h defines it: the bytes the whole message needs
 * (strlen + 1) on a copy, a truncation and a size query; minus a status on errors,
 * which write nothing and keep the message. Exact: string lengths, no tolerance. */
int egw_capi_test_last_error(void) {
  egw_params p;
  char small[8], big[256];
  const char *expect = "sigma = ";
  int needed, n;
  failures = 0;
  egw_params_default(&p);
  p.sigma = -1e-3;
  CHECK(egw_params_validate(&p) == EGW_INVALID_PARAMETER);
  /* a size query (buf NULL or not), then the caller's allocation of that size */
  needed = egw_last_error(NULL, 0);
  CHECK(needed > (int)strlen(expect));
  CHECK(egw_last_error(big, 0) == needed);
  {
    char *msg = malloc((size_t)needed);
    CHECK(msg != NULL);
    if (msg) {
      memset(msg, 'x', (size_t)needed);
      CHECK(egw_last_error(msg, needed) == needed);
      CHECK(strlen(msg) == (size_t)needed - 1 && strncmp(msg, expect, strlen(expect)) == 0);
      free(msg);
    }
  }
  /* a buffer large enough: the whole message, return <= buflen */
  n = egw_last_error(big, (int)sizeof big);
  CHECK(n == needed && n <= (int)sizeof big && strlen(big) == (size_t)n - 1);
  /* truncation: buflen - 1 characters and the NUL; the return value exceeds buflen */
  memset(small, 'x', sizeof small);
  n = egw_last_error(small, (int)sizeof small);
  CHECK(n == needed && n > (int)sizeof small);
  CHECK(strlen(small) == sizeof small - 1 && strncmp(small, big, sizeof small - 1) == 0);
  /* a one-byte buffer holds the NUL only */
  CHECK(egw_last_error(small, 1) == needed && small[0] == '\0');
  /* errors: negative, nothing written, the message kept */
  CHECK(egw_last_error(NULL, 10) == -EGW_NULL_POINTER);
  memset(small, 'x', sizeof small);
  CHECK(egw_last_error(small, -1) == -EGW_INVALID_ARGUMENT && small[0] == 'x');
  CHECK(egw_last_error(big, (int)sizeof big) == needed &&
        strncmp(big, expect, strlen(expect)) == 0);
  /* a successful call does not clear it (the message is of the last FAILING call) */
  CHECK(egw_get_version() == EGW_VERSION && egw_last_error(NULL, 0) == needed);
  return failures;
}

int egw_capi_test_params(void) {
  egw_params p;
  failures = 0;
  egw_params_default(&p);
  egw_params_default(NULL); /* documented no-op */
  CHECK(p.model == EGW_MODEL_EGW && p.radius == 1.0 && p.modulus == 1.0 && p.sigma == 0.0);
  CHECK(p.mu == 1.0 && p.psi == 0.0 && p.hardness_coeff == 0.6 && p.plastic_ratio == 54.0);
  CHECK(egw_params_validate(&p) == EGW_OK);
  CHECK(egw_params_validate(NULL) == EGW_NULL_POINTER);
  CHECK(last_error_names("p"));
#define BAD(field, value, name) do { egw_params q = p; q.field = value; \
    CHECK(egw_params_validate(&q) == EGW_INVALID_PARAMETER); CHECK(last_error_names(name)); } while (0)
  BAD(model, 4, "model");
  BAD(model, -1, "model");
  BAD(radius, 0.0, "radius");
  BAD(radius, NAN, "radius");
  BAD(modulus, -1.0, "modulus");
  BAD(modulus, INFINITY, "modulus");
  BAD(sigma, -1e-3, "sigma");
  BAD(sigma, NAN, "sigma");
  BAD(psi, -0.5, "psi");
  BAD(hardness_coeff, 1.0, "hardness_coeff");
  BAD(hardness_coeff, 0.0, "hardness_coeff");
  BAD(plastic_ratio, 1.0, "plastic_ratio");
  { egw_params q = p; q.sigma = 1e-3; q.mu = 0.0;
    CHECK(egw_params_validate(&q) == EGW_INVALID_PARAMETER); CHECK(last_error_names("mu")); }
#undef BAD
  {
    double mu = 0.0;
    /* (8/3) * 3/8 * 1 * sqrt(2*2*1) = 2 */
    CHECK(egw_mu_from_summits(0.375, 1.0, 1.0, 2.0, &mu) == EGW_OK && close_rel(mu, 2.0, 4e-16));
    CHECK(egw_mu_from_summits(-1.0, 1.0, 1.0, 2.0, &mu) == EGW_INVALID_ARGUMENT);
    CHECK(last_error_names("summit_density"));
    CHECK(egw_mu_from_summits(1.0, 1.0, 1.0, 2.0, NULL) == EGW_NULL_POINTER);
  }
  {
    /* psi = 4 E/(3 pi K H) sqrt(sigma/beta): with E = 3 pi, K H = 0.5 * 8, sigma/beta = 4
     * it is 4 * 3 pi/(3 pi * 4) * 2 = 2 exactly (up to the rounding of pi's products) */
    double psi = -1.0;
    CHECK(egw_psi_from_hardness(3.0 * M_PI, 8.0, 0.5, 4e-6, 1e-6, &psi) == EGW_OK &&
          close_rel(psi, 2.0, 4e-16));
    psi = -1.0;
    CHECK(egw_psi_from_hardness(1.0, 0.0, 0.5, 1.0, 1.0, &psi) == EGW_INVALID_ARGUMENT &&
          psi == -1.0);
    CHECK(last_error_names("hardness"));
    CHECK(egw_psi_from_hardness(1.0, 1.0, 1.0, 1.0, 1.0, &psi) == EGW_INVALID_ARGUMENT);
    CHECK(last_error_names("hardness_coeff"));
    CHECK(egw_psi_from_hardness(1e300, 1e-300, 0.5, 1.0, 1.0, &psi) == EGW_INVALID_ARGUMENT);
    CHECK(egw_psi_from_hardness(1.0, 1.0, 0.5, 1.0, 0.0, &psi) == EGW_INVALID_ARGUMENT);
    CHECK(last_error_names("summit_radius"));
  }
  return failures;
}

int egw_capi_test_gauss(void) {
  double v = -1.0;
  failures = 0;
  /* doc/theory.md section 2 check values (15 significant digits), documented error 1e-14 */
  CHECK(egw_gauss_integral(1.5, 0.0, &v) == EGW_OK && close_rel(v, 0.430019993662260, 2e-14));
  CHECK(egw_gauss_integral(1.5, 2.0, &v) == EGW_OK && close_rel(v, 6.64817762358709e-3, 2e-14));
  CHECK(egw_gauss_integral(1.5, 6.0, &v) == EGW_OK && close_rel(v, 8.20358058981517e-11, 2e-14));
  CHECK(egw_gauss_integral(1.5, -5.0, &v) == EGW_OK && close_rel(v, 11.3493877980066, 2e-14));
  /* F_0 = erfc(h/sqrt 2)/2 */
  CHECK(egw_gauss_integral(0.0, 1.0, &v) == EGW_OK && close_rel(v, 0.5 * erfc(1.0 / sqrt(2.0)), 1e-14));
  /* dF_0/dh = -phi(h) */
  CHECK(egw_gauss_integral_deriv(0.0, 1.0, &v) == EGW_OK
        && close_rel(v, -exp(-0.5) / sqrt(2.0 * M_PI), 1e-14));
  /* far tail underflows to zero, never NaN */
  CHECK(egw_gauss_integral(1.5, 60.0, &v) == EGW_OK && v == 0.0);
  v = 7.0;
  CHECK(egw_gauss_integral(-1.0, 0.0, &v) == EGW_INVALID_ARGUMENT && v == 7.0);
  CHECK(last_error_names("n"));
  CHECK(egw_gauss_integral(1.5, NAN, &v) == EGW_INVALID_ARGUMENT);
  CHECK(last_error_names("h"));
  CHECK(egw_gauss_integral(NAN, 0.0, &v) == EGW_INVALID_ARGUMENT);
  CHECK(egw_gauss_integral(1.5, 0.0, NULL) == EGW_NULL_POINTER);
  CHECK(egw_gauss_integral_deriv(-1.0, 0.0, &v) == EGW_INVALID_ARGUMENT);
  return failures;
}

int egw_capi_test_ellip(void) {
  double v = 0.0;
  failures = 0;
  CHECK(egw_ellipk(0.0, &v) == EGW_OK && close_rel(v, M_PI / 2, 4.5e-16));
  CHECK(egw_ellipe(0.0, &v) == EGW_OK && close_rel(v, M_PI / 2, 4.5e-16));
  /* K(1/sqrt 2) = Gamma(1/4)^2 / (4 sqrt(pi)) = 1.854074677301372 (lemniscate), a few ulp */
  CHECK(egw_ellipk(sqrt(0.5), &v) == EGW_OK && close_rel(v, 1.8540746773013719, 1e-15));
  /* E(1/sqrt 2) = 1.350643881047675 */
  CHECK(egw_ellipe(sqrt(0.5), &v) == EGW_OK && close_rel(v, 1.3506438810476755, 1e-15));
  CHECK(egw_ellipk(1.0, &v) == EGW_INVALID_ARGUMENT);
  CHECK(last_error_names("k"));
  CHECK(egw_ellipk(-0.1, &v) == EGW_INVALID_ARGUMENT);
  CHECK(egw_ellipk(NAN, &v) == EGW_INVALID_ARGUMENT);
  CHECK(egw_ellipe(1.5, &v) == EGW_INVALID_ARGUMENT);
  CHECK(egw_ellipk(0.5, NULL) == EGW_NULL_POINTER);
  return failures;
}

int egw_capi_test_flat_pressure(void) {
  egw_params p;
  double pr = 0.0, dpr = 0.0;
  /* F_3/2(0) (doc/theory.md §2) and F_1/2(0) = 2^(1/4) Gamma(3/4)/(2 sqrt(pi)) (mpmath, 30 digits) */
  const double f32_0 = 0.430019993662260, f12_0 = 0.411089479331229276;
  failures = 0;
  egw_params_default(&p);
  p.sigma = 1e-3; p.mu = 4.0;
  /* p_G(0) = C sigma^1.5 F_3/2(0), C = mu E / (2 sigma sqrt(2R)) (doc/theory.md section 3) */
  {
    double c = p.mu * p.modulus / (2.0 * p.sigma * sqrt(2.0 * p.radius));
    CHECK(egw_flat_pressure(&p, 0.0, &pr) == EGW_OK
          && close_rel(pr, c * pow(p.sigma, 1.5) * f32_0, 1e-13));
    CHECK(egw_flat_pressure_deriv(&p, 0.0, &pr, &dpr) == EGW_OK
          && close_rel(dpr, -1.5 * c * sqrt(p.sigma) * f12_0, 1e-13));
  }
  /* ZMC asperities carry less than elastic ones at the same separation */
  {
    egw_params q = p; double pe = 0.0, pp = 0.0;
    q.model = EGW_MODEL_EPGW; q.psi = 4.0;
    CHECK(egw_flat_pressure(&p, -2e-3, &pe) == EGW_OK);
    CHECK(egw_flat_pressure(&q, -2e-3, &pp) == EGW_OK && pp < pe && pp > 0.0);
  }
  { egw_params q = p; q.sigma = 0.0;
    CHECK(egw_flat_pressure(&q, 0.0, &pr) == EGW_INVALID_PARAMETER); CHECK(last_error_names("sigma")); }
  { egw_params q = p; q.radius = -1.0;
    CHECK(egw_flat_pressure(&q, 0.0, &pr) == EGW_INVALID_PARAMETER); CHECK(last_error_names("radius")); }
  CHECK(egw_flat_pressure(&p, NAN, &pr) == EGW_INVALID_ARGUMENT);
  CHECK(last_error_names("separation"));
  CHECK(egw_flat_pressure(NULL, 0.0, &pr) == EGW_NULL_POINTER);
  CHECK(egw_flat_pressure(&p, 0.0, NULL) == EGW_NULL_POINTER);
  CHECK(egw_flat_pressure_deriv(&p, 0.0, &pr, NULL) == EGW_NULL_POINTER);
  /* unloading: Z_u(-0.5, -1) = 0.0999943188254676126 for psi = 4, K = 0.6, rho_p = 54
   * (tools/reference/unload_refs.py, two forms agreeing to 20+ digits); 1e-12 promised */
  {
    egw_params q = p; double pu = 7.0, dpu = 7.0, pl = 0.0;
    double c = q.mu * q.modulus / (2.0 * q.sigma * sqrt(2.0 * q.radius));
    q.model = EGW_MODEL_EPGW; q.psi = 4.0; q.hardness_coeff = 0.6; q.plastic_ratio = 54.0;
    CHECK(egw_flat_pressure_unload(&q, -0.5e-3, -1.0e-3, &pu, &dpu) == EGW_OK);
    CHECK(close_rel(pu, c * pow(q.sigma, 1.5) * 0.0999943188254676126, 1e-12) && dpu < 0.0);
    CHECK(egw_flat_pressure(&q, -0.5e-3, &pl) == EGW_OK && pu < pl); /* below loading */
    CHECK(egw_flat_pressure_unload(&q, -0.5e-3, -1.0e-3, &pu, NULL) == EGW_OK);
    CHECK(egw_flat_pressure_unload(&q, -1.5e-3, -1.0e-3, &pu, NULL) == EGW_OK); /* reload */
    CHECK(egw_flat_pressure(&q, -1.5e-3, &pl) == EGW_OK && pu == pl);
    pu = 7.0;
    CHECK(egw_flat_pressure_unload(&q, NAN, 0.0, &pu, &dpu) == EGW_INVALID_ARGUMENT && pu == 7.0);
    CHECK(last_error_names("separation"));
    CHECK(egw_flat_pressure_unload(&q, 0.0, INFINITY, &pu, &dpu) == EGW_INVALID_ARGUMENT);
    CHECK(last_error_names("separation_min"));
    CHECK(egw_flat_pressure_unload(&q, 0.0, 0.0, NULL, &dpu) == EGW_NULL_POINTER);
    CHECK(egw_flat_pressure_unload(NULL, 0.0, 0.0, &pu, &dpu) == EGW_NULL_POINTER);
  }
  return failures;
}

int egw_capi_test_hertz(void) {
  egw_params p;
  double f = -1.0, k = -1.0, a = -1.0;
  failures = 0;
  egw_params_default(&p);
  p.model = EGW_MODEL_HERTZ; p.radius = 2.0; p.modulus = 3.0;
  /* delta = 0.02: a = sqrt(R delta) = 0.2, P = (4/3) E sqrt(R) delta^1.5, k = 2 E a */
  CHECK(egw_hertz(&p, 0.02, &f, &k, &a) == EGW_OK);
  CHECK(close_rel(a, 0.2, 4e-16));
  CHECK(close_rel(f, 4.0 / 3.0 * 3.0 * sqrt(2.0) * pow(0.02, 1.5), 4e-15));
  CHECK(close_rel(k, 2.0 * 3.0 * 0.2, 4e-16));
  CHECK(egw_hertz(&p, -0.01, &f, &k, &a) == EGW_OK && f == 0.0 && k == 0.0 && a == 0.0);
  CHECK(egw_hertz(&p, 0.02, &f, NULL, NULL) == EGW_OK); /* unwanted outputs may be NULL */
  CHECK(egw_hertz(&p, NAN, &f, &k, &a) == EGW_INVALID_ARGUMENT);
  CHECK(last_error_names("delta"));
  CHECK(egw_hertz(&p, INFINITY, &f, &k, &a) == EGW_INVALID_ARGUMENT);
  { egw_params q = p; q.modulus = 0.0;
    CHECK(egw_hertz(&q, 0.01, &f, &k, &a) == EGW_INVALID_PARAMETER); CHECK(last_error_names("modulus")); }
  CHECK(egw_hertz(NULL, 0.01, &f, &k, &a) == EGW_NULL_POINTER);
  return failures;
}

int egw_capi_test_solver(void) {
  egw_params p;
  egw_options o;
  egw_result res;
  failures = 0;
  egw_options_default(&o);
  egw_options_default(NULL); /* no-op */
  CHECK(o.n_radial == 0 && o.rel_tol == 1e-6 && o.max_iter == 0 && o.method == EGW_METHOD_AUTO
        && o.n_threads == 0);
  egw_params_default(&p);
  /* Hertz model: closed form exactly (R = 2, E = 3, delta = 0.02: a = 0.2) */
  p.model = EGW_MODEL_HERTZ; p.radius = 2.0; p.modulus = 3.0;
  CHECK(egw_solve(&p, &o, 0.02, &res) == EGW_OK);
  CHECK(close_rel(res.force, 4.0 / 3.0 * 3.0 * sqrt(2.0) * pow(0.02, 1.5), 1e-12));
  CHECK(close_rel(res.stiffness, 2.0 * 3.0 * 0.2, 1e-12));
  CHECK(close_rel(res.contact_radius, 0.2, 1e-12));
  CHECK(close_rel(res.max_pressure, 2.0 * 3.0 * 0.2 / (M_PI * 2.0), 1e-12));
  /* a rough model with sigma = 0 is Hertz too; options may be NULL */
  p.model = EGW_MODEL_EGW; p.sigma = 0.0;
  CHECK(egw_solve(&p, NULL, 0.02, &res) == EGW_OK);
  CHECK(close_rel(res.force, 4.0 / 3.0 * 3.0 * sqrt(2.0) * pow(0.02, 1.5), 1e-12));
  /* doc/theory.md section 5 table (R = E = 1, delta = 0.01, mu = 4, delta/sigma = 10):
   * P/P_H = 1.13475 (E-GW), 0.97696 (GW), quoted to a few 1e-5 */
  {
    const double ph = 4.0 / 3.0 * pow(0.01, 1.5);
    egw_params_default(&p);
    p.sigma = 1e-3; p.mu = 4.0;
    CHECK(egw_solve(&p, &o, 0.01, &res) == EGW_OK && close_rel(res.force / ph, 1.13475, 5e-5));
    CHECK(res.iterations > 0 && res.est_rel_err < 1e-5 && res.stiffness > 0.0);
    p.model = EGW_MODEL_GW;
    CHECK(egw_solve(&p, &o, 0.01, &res) == EGW_OK && close_rel(res.force / ph, 0.97696, 5e-5));
  }
  /* bad input */
  CHECK(egw_solve(&p, &o, 0.01, NULL) == EGW_NULL_POINTER);
  CHECK(egw_solve(NULL, &o, 0.01, &res) == EGW_NULL_POINTER);
  CHECK(egw_solve(&p, &o, NAN, &res) == EGW_INVALID_ARGUMENT);
  CHECK(last_error_names("delta"));
  { egw_options q = o; q.rel_tol = -1.0;
    CHECK(egw_solve(&p, &q, 0.01, &res) == EGW_INVALID_ARGUMENT); CHECK(last_error_names("rel_tol")); }
  { egw_options q = o; q.method = 9;
    CHECK(egw_solve(&p, &q, 0.01, &res) == EGW_INVALID_ARGUMENT); CHECK(last_error_names("method")); }
  { egw_params q = p; q.mu = -4.0;
    CHECK(egw_solve(&q, &o, 0.01, &res) == EGW_INVALID_PARAMETER); CHECK(last_error_names("mu")); }
  return failures;
}

int egw_capi_test_profile(void) {
  egw_params p;
  const double r[3] = {0.0, 0.1, 0.3};
  double pr[3], w[3];
  failures = 0;
  egw_params_default(&p);
  p.model = EGW_MODEL_HERTZ;
  /* Hertz, delta = 0.04, R = E = 1: a = 0.2, p0 = 2a/pi; w(0) = delta,
   * w(r <= a) = delta - r^2/2; p = 0 outside */
  CHECK(egw_profile(&p, NULL, 0.04, 3, r, pr, w) == EGW_OK);
  CHECK(close_rel(pr[0], 0.4 / M_PI, 1e-12) && close_rel(w[0], 0.04, 1e-12));
  CHECK(close_rel(pr[1], 0.4 / M_PI * sqrt(1.0 - 0.25), 1e-12));
  CHECK(close_rel(w[1], 0.04 - 0.005, 1e-12));
  /* outside, corrected eq. (15): w = a^2/(pi R) [sqrt(r^2/a^2 - 1) + (2 - r^2/a^2) asin(a/r)] */
  CHECK(pr[2] == 0.0);
  CHECK(close_rel(w[2], 0.04 / M_PI * (sqrt(2.25 - 1.0) + (2.0 - 2.25) * asin(0.2 / 0.3)), 1e-12));
  /* E-GW: rough pressure adds to Hertz everywhere */
  {
    double ph[3], wh[3];
    egw_params q = p;
    q.model = EGW_MODEL_EGW; q.sigma = 1e-3; q.mu = 4.0;
    CHECK(egw_profile(&p, NULL, 0.01, 3, r, ph, wh) == EGW_OK);
    CHECK(egw_profile(&q, NULL, 0.01, 3, r, pr, w) == EGW_OK);
    CHECK(pr[0] > ph[0] && pr[2] > ph[2] && w[0] > wh[0]);
  }
  CHECK(egw_profile(&p, NULL, 0.04, 0, r, pr, w) == EGW_OK); /* nothing asked, nothing done */
  CHECK(egw_profile(&p, NULL, 0.04, -1, r, pr, w) == EGW_INVALID_ARGUMENT);
  CHECK(last_error_names("n"));
  CHECK(egw_profile(&p, NULL, 0.04, 3, NULL, pr, w) == EGW_NULL_POINTER);
  CHECK(egw_profile(&p, NULL, 0.04, 3, r, pr, NULL) == EGW_NULL_POINTER);
  {
    const double rbad[1] = {-1.0};
    CHECK(egw_profile(&p, NULL, 0.04, 1, rbad, pr, w) == EGW_INVALID_ARGUMENT);
  }
  /* egw_profile_unload: Hertz is reversible (the loading profile at delta, bit for bit),
   * delta >= delta_max the loading profile; bad input named, outputs untouched */
  {
    double pu[3], wu[3];
    CHECK(egw_profile(&p, NULL, 0.04, 3, r, pr, w) == EGW_OK);
    CHECK(egw_profile_unload(&p, NULL, 0.04, 0.09, 3, r, pu, wu) == EGW_OK);
    CHECK(pu[0] == pr[0] && pu[1] == pr[1] && pu[2] == pr[2] && wu[0] == w[0] &&
          wu[2] == w[2]);
    CHECK(egw_profile_unload(&p, NULL, 0.04, 0.01, 3, r, pu, wu) == EGW_OK);
    CHECK(pu[0] == pr[0] && wu[2] == w[2]);
    pu[0] = 7.0;
    CHECK(egw_profile_unload(&p, NULL, 0.04, NAN, 3, r, pu, wu) == EGW_INVALID_ARGUMENT);
    CHECK(last_error_names("delta_max") && pu[0] == 7.0);
    CHECK(egw_profile_unload(&p, NULL, NAN, 0.09, 3, r, pu, wu) == EGW_INVALID_ARGUMENT);
    CHECK(last_error_names("delta"));
    CHECK(egw_profile_unload(&p, NULL, 0.04, 0.09, -1, r, pu, wu) == EGW_INVALID_ARGUMENT);
    CHECK(last_error_names("n"));
    CHECK(egw_profile_unload(NULL, NULL, 0.04, 0.09, 3, r, pu, wu) == EGW_NULL_POINTER);
    CHECK(egw_profile_unload(&p, NULL, 0.04, 0.09, 3, NULL, pu, wu) == EGW_NULL_POINTER);
    CHECK(egw_profile_unload(&p, NULL, 0.04, 0.09, 3, r, NULL, wu) == EGW_NULL_POINTER);
    CHECK(egw_profile_unload(&p, NULL, 0.04, 0.09, 3, r, pu, NULL) == EGW_NULL_POINTER);
    CHECK(pu[0] == 7.0);
    {
      const double rbad[1] = {-1.0};
      CHECK(egw_profile_unload(&p, NULL, 0.04, 0.09, 1, rbad, pu, wu) == EGW_INVALID_ARGUMENT);
      CHECK(last_error_names("r(1)"));
    }
  }
  return failures;
}

/* Progress hook (egw_set_progress, issue 32): a recorder of the reports of one call. */
typedef struct {
  int calls, out_of_range, decreasing, saw_stage, user_ok;
  double first, last;
  const char *want_stage;
} progress_log;
static void record_progress(double done, const char *stage, void *user) {
  progress_log *log = (progress_log *)user;
  if (log == NULL) return;
  log->user_ok = 1;
  if (!(done >= 0.0 && done <= 1.0)) log->out_of_range++;
  if (log->calls == 0) log->first = done;
  else if (done < log->last) log->decreasing++;
  log->last = done;
  if (stage != NULL && log->want_stage != NULL && strcmp(stage, log->want_stage) == 0)
    log->saw_stage = 1;
  log->calls++;
}
static void progress_reset(progress_log *log, const char *stage) {
  memset(log, 0, sizeof *log);
  log->first = -1.0; log->last = -1.0;
  log->want_stage = stage;
}

/* A hook that hands over to another from inside itself (its second report): the new
 * hook hears the rest of the same call, still never decreasing, and ends at 1. */
static progress_log handover_log;
static int handover_calls;
static void handover(double done, const char *stage, void *user) {
  (void)done; (void)stage; (void)user;
  if (++handover_calls == 2) egw_set_progress(record_progress, &handover_log);
}

/* The hook hears a restitution (EP-GW, sigma 1, psi 2: a history and an unloading
 * integral, ~0.1 s) and a table build: called, the user pointer passed through, done in
 * [0, 1] and never decreasing, 0 first and 1 last, the inner stages reported; a NULL hook
 * switches it off (no call, same answer). Fails on main: no egw_set_progress. */
int egw_capi_test_progress(void) {
  egw_params p;
  egw_options o;
  egw_table t = NULL;
  progress_log log;
  double e = -1.0, e_off = -1.0;
  failures = 0;
  egw_params_default(&p);
  p.model = EGW_MODEL_EPGW; p.sigma = 1.0; p.mu = 4.0; p.psi = 2.0; p.hardness_coeff = 0.6;
  egw_options_default(&o);
  o.rel_tol = 1e-5;
  progress_reset(&log, "restitution: unloading");
  egw_set_progress(record_progress, &log);
  CHECK(egw_restitution(&p, &o, 1.0, 1.0, &e) == EGW_OK && e > 0.0 && e < 1.0);
  CHECK(log.calls >= 4 && log.user_ok);
  CHECK(log.out_of_range == 0 && log.decreasing == 0);
  CHECK(log.first == 0.0 && log.last == 1.0);
  CHECK(log.saw_stage);
  if (log.calls < 4 || !log.saw_stage)
    printf("    restitution: %d reports, stage seen %d\n", log.calls, log.saw_stage);
  /* a table build (Hertz, cheap): its own stage */
  progress_reset(&log, "table build");
  { egw_params h; egw_params_default(&h); h.model = EGW_MODEL_HERTZ;
    CHECK(egw_table_build(&h, NULL, 0.0, 0.01, 1e-6, &t) == EGW_OK && t != NULL); }
  egw_table_free(&t);
  CHECK(log.calls >= 2 && log.saw_stage && log.decreasing == 0 && log.out_of_range == 0);
  CHECK(log.first == 0.0 && log.last == 1.0);
  /* an array entry of one point (Python's scalar egw.restitution) reports as the scalar
   * call does, with two threads asked for: on main its OpenMP region (active with 2
   * threads) silenced the hook */
  progress_reset(&log, "restitution: unloading");
  { egw_options o2 = o; double m = 1.0, v = 1.0, e_arr = -1.0;
    o2.n_threads = 2;
    CHECK(egw_restitution_array(&p, 0, &o2, 1, &m, 0, &v, 0, &e_arr, NULL, NULL, NULL,
                                EGW_ARRAY_RAISE, NULL) == EGW_OK && e_arr == e); }
  CHECK(log.calls >= 4 && log.saw_stage && log.decreasing == 0 && log.out_of_range == 0);
  CHECK(log.first == 0.0 && log.last == 1.0);
  if (log.calls < 4) printf("    restitution_array of one point: %d reports\n", log.calls);
  /* egw_time_step (a restitution, a history, an unloading and the duration's solves):
   * one call, never decreasing; on main each of its solves reported as an outermost call
   * (184 reports, 58 decreasing) */
  progress_reset(&log, "history");
  { double duration = -1.0, step = -1.0;
    CHECK(egw_time_step(&p, &o, 1.0, 1.0, 1e-3, &duration, &step) == EGW_OK &&
          duration > 0.0 && step > 0.0); }
  CHECK(log.calls >= 4 && log.saw_stage && log.decreasing == 0 && log.out_of_range == 0);
  CHECK(log.first == 0.0 && log.last == 1.0);
  if (log.decreasing > 0)
    printf("    time_step: %d reports, %d decreasing\n", log.calls, log.decreasing);
  /* a hook replaced from inside itself: on main the new hook heard each nested call of
   * the restitution as an outermost one (0 .. 1 again and again, done decreasing) */
  progress_reset(&handover_log, NULL);
  handover_calls = 0;
  egw_set_progress(handover, NULL);
  { double e_h = -1.0;
    CHECK(egw_restitution(&p, &o, 1.0, 1.0, &e_h) == EGW_OK && e_h == e); }
  CHECK(handover_calls == 2 && handover_log.calls >= 2);
  CHECK(handover_log.decreasing == 0 && handover_log.out_of_range == 0);
  CHECK(handover_log.last == 1.0);
  if (handover_log.decreasing > 0)
    printf("    handed-over hook: %d reports, %d decreasing\n", handover_log.calls,
           handover_log.decreasing);
  /* NULL: off, the answer unchanged */
  progress_reset(&log, NULL);
  egw_set_progress(NULL, &log);
  CHECK(egw_restitution(&p, &o, 1.0, 1.0, &e_off) == EGW_OK && e_off == e);
  CHECK(log.calls == 0);
  return failures;
}
