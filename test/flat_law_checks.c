/* C tests of the rough-flat law entry points of include/egw.h (egw_flat_law_from_table,
 * egw_flat_law_pressure, egw_flat_law_contact_area, egw_flat_law_info, egw_flat_law_free,
 * egw_solve_flat_law, egw_table_build_flat_law) with good and bad input. Returns the
 * number of failed checks and prints why; test/test_flat_law.f90 runs it. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>
#include "egw.h"

static int failures;
#define CHECK(cond) do { if (!(cond)) { failures++; \
  printf("    C check failed at %s:%d: %s\n", __FILE__, __LINE__, #cond); } } while (0)
static int last_error_names(const char *name) {
  char buf[256];
  if (egw_last_error(buf, (int)sizeof buf) < 1) return 0;
  return strstr(buf, name) != NULL;
}

/* An exponential law p = p0 exp(-u/l) on a nearly rigid sphere (p0/E* = 1e-12): the force
 * is 2 pi R p0 l exp(delta/l) (the integral of p over the rigid gap r^2/(2R) - delta);
 * the half-space's deflection changes it by ~ p0 sqrt(R l)/(E* l) ~ 1e-10, so 1e-7. */
int egw_capi_test_flat_law(void) {
  const double l = 1e-6, p0 = 1.0, R = 1e-2, E = 1e12;
  double u[2] = {0.0, 3e-6}, p[2], area[2] = {0.5, 0.1};
  egw_flat_law law = NULL;
  egw_params par;
  egw_result res;
  double pr, d, a, length, modulus, u_min, u_max;
  int n, has_area;
  failures = 0;
  p[0] = p0;
  p[1] = p0 * exp(-u[1] / l);
  CHECK(egw_flat_law_from_table(u, p, NULL, area, 2, 0.0, E, &law) == EGW_OK);
  CHECK(law != NULL);
  CHECK(egw_flat_law_pressure(law, 5e-6, &pr, &d) == EGW_OK);
  CHECK(fabs(pr - p0 * exp(-5.0)) <= 1e-13 * pr && fabs(d + pr / l) <= 1e-12 * pr / l);
  CHECK(egw_flat_law_contact_area(law, 1.5e-6, &a) == EGW_OK && fabs(a - 0.3) < 1e-15);
  CHECK(egw_flat_law_info(law, &n, &length, &modulus, &u_min, &u_max, &has_area) == EGW_OK);
  CHECK(n == 2 && fabs(length - l) <= 1e-13 * l && modulus == E && u_min == 0.0 &&
        u_max == 3e-6 && has_area == 1);
  /* the law in units of (l, p0): p' = exp(-u'), its length 1 and E* E/p0, exactly (the
   * units are powers of 2 apart from l, so 1e-15: one division) */
  {
    egw_flat_law s = NULL, keep = law;
    double ls, ms;
    CHECK(egw_flat_law_rescale(law, l, p0, &s) == EGW_OK && s != NULL && s != law);
    CHECK(egw_flat_law_pressure(s, 5.0, &pr, &d) == EGW_OK);
    CHECK(fabs(pr - exp(-5.0)) <= 1e-13 * pr && fabs(d + pr) <= 1e-12 * pr);
    CHECK(egw_flat_law_info(s, NULL, &ls, &ms, NULL, &u_max, NULL) == EGW_OK);
    CHECK(fabs(ls - 1.0) <= 1e-13 && fabs(ms - E / p0) <= 1e-15 * ms &&
          fabs(u_max - 3.0) <= 1e-15 * 3.0);
    egw_flat_law_free(&s);
    CHECK(s == NULL && law == keep);
    s = (egw_flat_law) &ls;   /* refused: outputs unchanged */
    CHECK(egw_flat_law_rescale(law, 0.0, 1.0, &s) == EGW_INVALID_ARGUMENT &&
          s == (egw_flat_law) &ls);
    CHECK(egw_flat_law_rescale(law, 1.0, NAN, &s) == EGW_INVALID_ARGUMENT);
    CHECK(egw_flat_law_rescale(NULL, 1.0, 1.0, &s) == EGW_NULL_POINTER);
  }
  egw_params_default(&par);
  par.radius = R;
  par.modulus = E;
  for (int k = 0; k < 3; k++) {
    double delta = (k - 1) * 2e-6, exact = 2.0 * M_PI * R * p0 * l * exp(delta / l);
    CHECK(egw_solve_flat_law(&par, law, NULL, delta, &res) == EGW_OK);
    CHECK(fabs(res.force - exact) <= 1e-7 * exact);
    CHECK(fabs(res.stiffness - exact / l) <= 1e-6 * exact / l);
  }
  /* a 1-D table of the same pair: within its tolerance 1e-6 of the closed form (plus the
   * solves' 1e-7) from 8 lengths apart to 4 lengths in, the exponential tail below its
   * cut-off (the law's own: within 1e-6 too), and the same after a file round trip */
  {
    egw_table t = NULL, back = NULL;
    egw_table_info info;
    char path[] = "build/flat_law_table_XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    if (fd >= 0) close(fd);
    CHECK(egw_table_build_flat_law(&par, law, NULL, -8e-6, 4e-6, 1e-6, &t) == EGW_OK);
    CHECK(egw_table_get_info(t, &info) == EGW_OK && info.model == EGW_MODEL_FLAT_LAW);
    CHECK(egw_table_write(t, path, EGW_FORMAT_BINARY) == EGW_OK);
    CHECK(egw_table_read(path, &back) == EGW_OK);
    remove(path);
    for (int k = 0; k <= 60; k++) {
      double delta = -40e-6 + k * 0.7e-6, exact = 2.0 * M_PI * R * p0 * l * exp(delta / l);
      double f = -1.0, fb = -1.0, st = -1.0;
      if (delta > 4e-6) break;
      CHECK(egw_table_eval(t, delta, &f, &st) == EGW_OK);
      CHECK(fabs(f - exact) <= 1.2e-6 * exact);
      CHECK(fabs(st - exact / l) <= 1e-4 * exact / l);
      CHECK(back != NULL && egw_table_eval(back, delta, &fb, NULL) == EGW_OK && fb == f);
    }
    egw_table_free(&t);
    egw_table_free(&back);
    egw_params bad = par;
    bad.model = EGW_MODEL_FLAT_LAW;
    CHECK(egw_solve(&bad, NULL, 0.0, &res) == EGW_INVALID_PARAMETER &&
          last_error_names("flat law"));
    CHECK(egw_table_build(&bad, NULL, -1e-6, 1e-6, 1e-4, &t) == EGW_INVALID_PARAMETER);
    CHECK(egw_solve_flat_law(&bad, law, NULL, 0.0, &res) == EGW_OK &&
          fabs(res.force - 2.0 * M_PI * R * p0 * l) <= 1e-7 * res.force);
  }
  /* files: egw's CSV round trip (the same law at nodes and between them, bit for bit:
   * the slopes are stored as dp/du), a user's two-column CSV, malformed files */
  {
    char path[] = "build/flat_law_file_XXXXXX";
    int fd = mkstemp(path);
    egw_flat_law back = NULL;
    double pb, db;
    FILE *f;
    CHECK(fd >= 0);
    if (fd >= 0) close(fd);
    CHECK(egw_flat_law_write(law, path) == EGW_OK);
    CHECK(egw_flat_law_read(path, &back) == EGW_OK);
    for (int k = 0; k < 7; k++) {
      double x = -1e-6 + k * 0.9e-6;
      egw_flat_law_pressure(law, x, &pr, &d);
      CHECK(egw_flat_law_pressure(back, x, &pb, &db) == EGW_OK);
      CHECK(fabs(pb - pr) <= 1e-15 * pr && fabs(db - d) <= 1e-14 * fabs(d));
    }
    CHECK(egw_flat_law_contact_area(back, 1.5e-6, &a) == EGW_OK && fabs(a - 0.3) < 1e-15);
    {
      double length0;
      egw_flat_law_info(law, NULL, &length0, NULL, NULL, NULL, NULL);
      CHECK(egw_flat_law_info(back, NULL, &length, &modulus, NULL, NULL, NULL) == EGW_OK &&
            length == length0 && modulus == E);
    }
    egw_flat_law_free(&back);
    f = fopen(path, "w");
    fprintf(f, "u,pressure\n# length = 1e-6\n0,1\n1e-6,0.36787944117144233\n");
    fclose(f);
    CHECK(egw_flat_law_read(path, &back) == EGW_OK);
    CHECK(egw_flat_law_pressure(back, 2e-6, &pb, NULL) == EGW_OK &&
          fabs(pb - exp(-2.0)) <= 1e-14);
    egw_flat_law_free(&back);
    f = fopen(path, "w");
    fprintf(f, "u,pressure\n0,1\n1e-6,x\n");
    fclose(f);
    CHECK(egw_flat_law_read(path, &back) == EGW_BAD_FILE && last_error_names("line 3") &&
          back == NULL);
    f = fopen(path, "w");
    fprintf(f, "delta,force\n0,1\n1e-6,0.5\n");
    fclose(f);
    CHECK(egw_flat_law_read(path, &back) == EGW_BAD_FILE && last_error_names("columns u"));
    f = fopen(path, "w");
    fprintf(f, "u,pressure\n0,1\n1e-6,2\n");
    fclose(f);
    CHECK(egw_flat_law_read(path, &back) == EGW_BAD_FILE && last_error_names("p(2)"));
    remove(path);
    CHECK(egw_flat_law_read(path, &back) == EGW_IO_ERROR);
  }
  /* bad input */
  CHECK(egw_flat_law_pressure(law, NAN, &pr, NULL) == EGW_INVALID_ARGUMENT &&
        last_error_names("u"));
  par.modulus = 2.0 * E;
  CHECK(egw_solve_flat_law(&par, law, NULL, 0.0, &res) == EGW_INVALID_PARAMETER &&
        last_error_names("modulus"));
  CHECK(egw_solve_flat_law(&par, NULL, NULL, 0.0, &res) == EGW_NULL_POINTER &&
        last_error_names("law"));
  /* the flow-pressure cap (doc/theory.md 12 "Rough spheres with the cap"): a law's solve
   * caps the total pressure at p_y (max_pressure = p_y to rounding: the cap clamps it), the
   * force below the uncapped one; a cap above every pressure changes nothing; a law's force
   * table refuses it naming it, as egw_table_build does (it dropped it: audit25). The
   * same law on a soft sphere (E* = 1e3 p0: 3e-6 is ~12 delta_y at the p_y below; on the
   * rigid one delta_y is 2.5e-12 and the solve refuses delta beyond 1e12 delta_y) */
  par.modulus = E;
  {
    egw_result free_res, capped;
    egw_table tc = NULL;
    egw_flat_law soft = NULL;
    egw_params sp = par;
    sp.modulus = 1e3 * p0;
    CHECK(egw_flat_law_from_table(u, p, NULL, NULL, 2, 0.0, sp.modulus, &soft) == EGW_OK);
    CHECK(egw_solve_flat_law(&sp, soft, NULL, 3e-6, &free_res) == EGW_OK);
    sp.flow_pressure = 0.5 * free_res.max_pressure;
    CHECK(egw_solve_flat_law(&sp, soft, NULL, 3e-6, &capped) == EGW_OK &&
          capped.max_pressure <= sp.flow_pressure * (1.0 + 1e-12) &&
          capped.max_pressure >= sp.flow_pressure * (1.0 - 1e-12) &&
          capped.force < free_res.force);
    sp.flow_pressure = 2.0 * free_res.max_pressure;
    CHECK(egw_solve_flat_law(&sp, soft, NULL, 3e-6, &capped) == EGW_OK &&
          fabs(capped.force - free_res.force) <= 1e-12 * free_res.force);
    CHECK(egw_table_build_flat_law(&sp, soft, NULL, -8e-6, 4e-6, 1e-4, &tc) ==
          EGW_INVALID_PARAMETER && last_error_names("flow_pressure") && tc == NULL);
    egw_flat_law_free(&soft);
  }
  par.flow_pressure = 0.0;
  egw_flat_law_free(&law);
  CHECK(law == NULL);
  egw_flat_law_free(&law);
  egw_flat_law_free(NULL);
  CHECK(egw_flat_law_from_table(u, p, NULL, NULL, 2, 0.0, 0.0, &law) == EGW_OK);
  CHECK(egw_flat_law_contact_area(law, 1e-6, &a) == EGW_UNSUPPORTED);
  egw_flat_law_free(&law);
  u[1] = u[0];
  CHECK(egw_flat_law_from_table(u, p, NULL, NULL, 2, 0.0, 0.0, &law) == EGW_INVALID_ARGUMENT
        && last_error_names("u(2)") && law == NULL);
  u[1] = 3e-6;
  p[1] = 2.0 * p0;
  CHECK(egw_flat_law_from_table(u, p, NULL, NULL, 2, 0.0, 0.0, &law) == EGW_INVALID_ARGUMENT
        && last_error_names("p(2)") && law == NULL);
  CHECK(egw_flat_law_from_table(u, p, NULL, NULL, 1, 0.0, 0.0, &law) == EGW_INVALID_ARGUMENT
        && last_error_names("n = 1"));
  CHECK(egw_flat_law_from_table(NULL, p, NULL, NULL, 2, 0.0, 0.0, &law) == EGW_NULL_POINTER);
  return failures;
}
