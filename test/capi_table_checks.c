/* C tests of the table API of include/egw.h: build, evaluate, write, read,
 * free, universal tables, with good and bad input. Each egw_capi_test_table_* returns
 * the number of failed checks and prints why; test/test_capi_table.f90 runs them as a
 * test-drive suite. Exact references: the Hertz closed form, written out here. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "egw.h"

static int failures;
#define CHECK(cond) do { if (!(cond)) { failures++; \
  printf("    C check failed at %s:%d: %s\n", __FILE__, __LINE__, #cond); } } while (0)

static double p_hertz(double e, double r, double d) {
  return d > 0.0 ? 4.0 / 3.0 * e * sqrt(r) * pow(d, 1.5) : 0.0;
}
static int last_error_names(const char *name) {
  char buf[512];
  if (egw_last_error(buf, (int)sizeof buf) < 1) return 0;
  return strncmp(buf, name, strlen(name)) == 0;
}
/* Reader-side checks of a CalculiX curve, as CalculiX 2.20 reads it: every field of the
 * pair lines after the *SURFACE BEHAVIOR line at most 20 characters, at most 200 pairs.
 * Returns the number of pairs (-1 if a check fails); *first_x: first overclosure. */
static int calculix_pairs(const char *path, double *first_x) {
  FILE *fp = fopen(path, "r");
  char line[512];
  int data = 0, n = 0, ok = 1;
  if (fp == NULL) return -1;
  while (fgets(line, sizeof line, fp) != NULL) {
    if (data && line[0] != '*') {
      char *field = strtok(line, ",\n");
      int fields = 0;
      while (field != NULL) {
        while (*field == ' ') field++;
        if (strlen(field) > 20) ok = 0;
        if (fields == 1 && n == 0) *first_x = atof(field);
        fields++;
        field = strtok(NULL, ",\n");
      }
      if (fields != 2) ok = 0;
      n++;
    }
    if (strncmp(line, "*SURFACE BEHAVIOR", 17) == 0) data = 1;
  }
  fclose(fp);
  return ok && n <= 200 ? n : -1;
}
/* Does the file contain LAMMPS's "UNITS:" tag (case-sensitive, as LAMMPS reads it)? */
static int has_units_tag(const char *path) {
  FILE *fp = fopen(path, "r");
  char line[512];
  int found = 0;
  if (fp == NULL) return 0;
  while (fgets(line, sizeof line, fp) != NULL) found |= strstr(line, "UNITS:") != NULL;
  fclose(fp);
  return found;
}
static egw_params hertz_params(void) {
  egw_params p;
  egw_params_default(&p);
  p.model = EGW_MODEL_HERTZ; p.radius = 0.5; p.modulus = 2.0;
  return p;
}

/* Build and evaluate: the table's documented accuracy is rel_tol at check points;
 * between them 1.5 rel_tol (the Hermite error kernel peaks at the checked midpoints;
 * 1.5 allows the fourth derivative to vary across an interval). */
int egw_capi_test_table_build_eval(void) {
  egw_params p = hertz_params();
  egw_table t = NULL;
  egw_table_info info;
  double f = -1.0, k = -1.0, w = -1.0, a = -1.0;
  const double tol = 1e-6;
  failures = 0;
  CHECK(egw_table_build(&p, NULL, 0.0, 0.01, tol, &t) == EGW_OK && t != NULL);
  if (t == NULL) return failures;
  CHECK(egw_table_get_info(t, &info) == EGW_OK);
  CHECK(info.model == EGW_MODEL_HERTZ && info.n_nodes > 10 && info.delta_max == 0.01);
  CHECK(info.max_force_error <= tol && info.rel_tol == tol);
  /* P_ref = P(delta_max) for Hertz; tol P_ref / 2 <= P(cutoff) <= tol P_ref */
  CHECK(fabs(info.reference_force - p_hertz(2.0, 0.5, 0.01)) <= 1e-15 * info.reference_force);
  CHECK(p_hertz(2.0, 0.5, info.cutoff) <= tol * info.reference_force * (1 + 1e-12));
  for (int i = 1; i < 200; i++) {
    double d = info.cutoff + (0.01 - info.cutoff) * pow(i / 200.0, 2);
    CHECK(egw_table_eval(t, d, &f, &k) == EGW_OK);
    CHECK(fabs(f / p_hertz(2.0, 0.5, d) - 1.0) <= 1.5 * tol);
  }
  /* energy (8/15) E sqrt(R) (d^2.5 - d_c^2.5) within 1.5 rel_tol; a = sqrt(R d) */
  CHECK(egw_table_eval_all(t, 0.005, &f, &k, &w, &a) == EGW_OK);
  CHECK(fabs(w / (8.0 / 15.0 * 2.0 * sqrt(0.5) * (pow(0.005, 2.5) - pow(info.cutoff, 2.5)))
             - 1.0) <= 1.5 * tol);
  CHECK(a > 0.0);
  /* below the cut-off Hertz itself (the closed form to rounding), zero apart */
  CHECK(egw_table_eval(t, 0.5 * info.cutoff, &f, &k) == EGW_OK);
  CHECK(fabs(f / p_hertz(2.0, 0.5, 0.5 * info.cutoff) - 1.0) <= 1e-12);
  CHECK(egw_table_eval(t, -1.0, &f, &k) == EGW_OK && f == 0.0 && k == 0.0);
  /* above delta_max: the deep-overlap asymptote (Hertz's own form: the closed form to
   * the table's 1.5 tol at delta_max), flagged, outputs written */
  {
    char msg[256];
    CHECK(egw_table_eval(t, 0.011, &f, &k) == EGW_OUT_OF_RANGE);
    CHECK(fabs(f / p_hertz(2.0, 0.5, 0.011) - 1.0) <= 1.5 * tol);
    CHECK(last_error_names("delta"));
    /* the message is formed when asked (kept as numbers on the hot path): whole, with
     * both numbers, and a later error's message replaces it */
    CHECK(egw_table_eval(t, 0.011, &f, &k) == EGW_OUT_OF_RANGE);
    CHECK(egw_last_error(msg, (int)sizeof msg) > 1 &&
          strncmp(msg, "delta = 1.1", 11) == 0 && strstr(msg, "above the table's delta_max = 1.0") != NULL &&
          strstr(msg, "(values extrapolated)") != NULL);
    CHECK(egw_table_eval(t, 0.011, &f, &k) == EGW_OUT_OF_RANGE);
    CHECK(egw_table_eval(t, NAN, &f, &k) == EGW_INVALID_ARGUMENT);
    CHECK(egw_last_error(msg, (int)sizeof msg) > 1 && strstr(msg, "above") == NULL &&
          strstr(msg, "delta") != NULL);
  }
  /* the array evaluator: bit-for-bit egw_table_eval at each point, one status */
  {
    double d[5] = {-1.0, 0.5 * info.cutoff, 0.003, 0.01, 0.012}, fa[5], ka[5];
    double fs, ks;
    CHECK(egw_table_eval_array(t, 4, d, fa, ka) == EGW_OK);
    for (int i = 0; i < 4; i++) {
      egw_table_eval(t, d[i], &fs, &ks);
      CHECK(fa[i] == fs && ka[i] == ks);
    }
    CHECK(egw_table_eval_array(t, 5, d, fa, NULL) == EGW_OUT_OF_RANGE);
    egw_table_eval(t, d[4], &fs, &ks);
    CHECK(fa[4] == fs && last_error_names("delta"));
    d[2] = NAN;
    fa[0] = 7.0;
    CHECK(egw_table_eval_array(t, 5, d, fa, ka) == EGW_INVALID_ARGUMENT && fa[0] == 7.0);
    CHECK(last_error_names("delta[2]"));
    CHECK(egw_table_eval_array(t, -1, d, fa, ka) == EGW_INVALID_ARGUMENT);
    CHECK(egw_table_eval_array(t, 0, NULL, NULL, NULL) == EGW_OK);
    CHECK(egw_table_eval_array(NULL, 1, d, fa, ka) == EGW_NULL_POINTER);
  }
  f = 7.0;
  CHECK(egw_table_eval(t, NAN, &f, &k) == EGW_INVALID_ARGUMENT && f == 7.0);
  CHECK(egw_table_eval(t, 0.005, NULL, &k) == EGW_OK); /* unwanted outputs may be NULL */
  CHECK(egw_table_eval(NULL, 0.005, &f, &k) == EGW_NULL_POINTER);
  CHECK(egw_table_get_info(t, NULL) == EGW_NULL_POINTER);
  egw_table_free(&t);
  CHECK(t == NULL);
  /* bad input: statuses, messages, and no handle */
  {
    egw_table u = NULL;
    egw_params q = p;
    q.radius = -1.0;
    CHECK(egw_table_build(&q, NULL, 0.0, 0.01, tol, &u) == EGW_INVALID_PARAMETER && u == NULL);
    CHECK(last_error_names("radius"));
    CHECK(egw_table_build(&p, NULL, 0.0, 0.01, 0.0, &u) == EGW_INVALID_ARGUMENT && u == NULL);
    CHECK(last_error_names("rel_tol"));
    CHECK(egw_table_build(&p, NULL, 0.01, 0.0, tol, &u) == EGW_INVALID_ARGUMENT && u == NULL);
    CHECK(last_error_names("delta_max"));
    CHECK(egw_table_build(NULL, NULL, 0.0, 0.01, tol, &u) == EGW_NULL_POINTER);
    CHECK(egw_table_build(&p, NULL, 0.0, 0.01, tol, NULL) == EGW_NULL_POINTER);
  }
  return failures;
}

/* Files through the C API: CSV and binary read back evaluate bit-for-bit the same;
 * corrupted or missing files fail cleanly; radii are checked. */
int egw_capi_test_table_files(void) {
  egw_params p = hertz_params();
  egw_table t = NULL, back = NULL;
  const char *csv = "build/capi_table.csv", *bin = "build/capi_table.egwt";
  failures = 0;
  CHECK(egw_table_build(&p, NULL, 0.0, 0.01, 1e-5, &t) == EGW_OK);
  if (t == NULL) return failures;
  CHECK(egw_table_set_radii(t, 1.0, 1.0) == EGW_OK);
  CHECK(egw_table_set_radii(t, 1.0, 3.0) == EGW_INVALID_ARGUMENT);
  CHECK(last_error_names("radius1"));
  CHECK(egw_table_write(t, csv, EGW_FORMAT_CSV) == EGW_OK);
  CHECK(egw_table_write(t, bin, EGW_FORMAT_BINARY) == EGW_OK);
  CHECK(egw_table_write(t, "build/capi_table.table", EGW_FORMAT_LAMMPS) == EGW_OK);
  CHECK(egw_table_write(t, "build/capi_table.inp", EGW_FORMAT_CALCULIX) == EGW_OK);
  CHECK(!has_units_tag("build/capi_table.table"));
  {
    /* CalculiX limits; shift: the curve starts at overclosure 0. The table at 1e-5 over
     * four decades of delta needs more than 200 pairs: error above rel_tol, reported. */
    double x0 = -1.0, err = -1.0;
    egw_table_info info;
    CHECK(egw_table_get_info(t, &info) == EGW_OK);
    CHECK(calculix_pairs("build/capi_table.inp", &x0) > 0);
    CHECK(fabs(x0 - info.cutoff) <= 1e-12 * info.cutoff); /* 13 significant digits */
    CHECK(egw_table_write_calculix(t, "build/capi_shift.inp", 1, &err) == EGW_OK);
    CHECK(calculix_pairs("build/capi_shift.inp", &x0) == 200 && x0 == 0.0);
    CHECK(err > 1e-5 && err < 1e-3);
    CHECK(egw_table_write_calculix(t, "build/capi_shift.inp", 0, NULL) == EGW_OK);
    CHECK(egw_table_write_calculix(NULL, "build/capi_shift.inp", 0, NULL)
          == EGW_NULL_POINTER);
  }
  {
    /* two sections; the second from R alone (R1 = R2 = 2R) */
    egw_table two[2] = {t, NULL};
    FILE *fp;
    char line[256];
    int sections = 0;
    CHECK(egw_table_build(&p, NULL, 0.0, 0.01, 1e-4, &two[1]) == EGW_OK);
    CHECK(egw_tables_write_lammps(2, two, "build/capi_two.table") == EGW_OK);
    fp = fopen("build/capi_two.table", "r");
    CHECK(fp != NULL);
    if (fp != NULL) {
      while (fgets(line, sizeof line, fp) != NULL)
        sections += strcmp(line, "EGW_1\n") == 0 || strcmp(line, "EGW_2\n") == 0;
      fclose(fp);
    }
    CHECK(sections == 2);
    CHECK(!has_units_tag("build/capi_two.table"));
    CHECK(egw_tables_write_lammps_units(2, two, "build/capi_si.table", "si") == EGW_OK);
    fp = fopen("build/capi_si.table", "r");
    CHECK(fp != NULL);
    if (fp != NULL) {
      CHECK(fgets(line, sizeof line, fp) != NULL && strncmp(line, "# DATE: ", 8) == 0 &&
            strstr(line, " UNITS: si ") != NULL);
      fclose(fp);
    }
    CHECK(egw_tables_write_lammps_units(2, two, "build/capi_bad.table", "SI")
          == EGW_INVALID_ARGUMENT);
    CHECK(last_error_names("units"));
    CHECK(egw_tables_write_lammps_units(2, two, "build/capi_bad.table", NULL)
          == EGW_NULL_POINTER);
    CHECK(last_error_names("units"));
    {
      egw_table second = two[1];
      two[1] = NULL;
      CHECK(egw_tables_write_lammps(2, two, "build/capi_two.table") == EGW_NULL_POINTER);
      CHECK(egw_tables_write_lammps(0, two, "build/capi_two.table") == EGW_INVALID_ARGUMENT);
      egw_table_free(&second);
    }
  }
  CHECK(egw_table_write(t, csv, 9) == EGW_INVALID_ARGUMENT);
  CHECK(last_error_names("format"));
  CHECK(egw_table_write(t, NULL, EGW_FORMAT_CSV) == EGW_NULL_POINTER);
  CHECK(egw_table_write(t, "build/no/such/dir/t.csv", EGW_FORMAT_CSV) == EGW_IO_ERROR);
  for (int which = 0; which < 2; which++) {
    back = NULL;
    CHECK(egw_table_read(which ? bin : csv, &back) == EGW_OK && back != NULL);
    if (back == NULL) continue;
    for (int i = 0; i <= 100; i++) {
      double d = 0.01 * i / 100.0, f1, k1, f2, k2;
      egw_table_eval(t, d, &f1, &k1);
      egw_table_eval(back, d, &f2, &k2);
      CHECK(f1 == f2 && k1 == k2);
    }
    egw_table_free(&back);
  }
  /* a flipped byte in the binary file: EGW_BAD_FILE, no handle */
  {
    FILE *fp = fopen(bin, "r+b");
    CHECK(fp != NULL);
    if (fp != NULL) {
      int c;
      fseek(fp, 200, SEEK_SET);
      c = fgetc(fp);
      fseek(fp, 200, SEEK_SET);
      fputc(c ^ 0x20, fp);
      fclose(fp);
    }
    back = NULL;
    CHECK(egw_table_read(bin, &back) == EGW_BAD_FILE && back == NULL);
    CHECK(last_error_names("path"));
  }
  back = NULL;
  CHECK(egw_table_read("build/does-not-exist.egwt", &back) == EGW_IO_ERROR && back == NULL);
  CHECK(egw_table_read(NULL, &back) == EGW_NULL_POINTER);
  CHECK(egw_table_read(csv, NULL) == EGW_NULL_POINTER);
  egw_table_free(&t);
  egw_table_free(&t);   /* *t == NULL: fine */
  egw_table_free(NULL); /* fine */
  CHECK(t == NULL);
  /* the rough flat for CalculiX */
  {
    egw_params q;
    egw_params_default(&q);
    q.sigma = 1e-3; q.mu = 4.0;
    CHECK(egw_write_flat_calculix(&q, 3e-3, 1e-5, "build/capi_flat.inp") == EGW_OK);
    {
      double x0 = -1.0, err = -1.0;
      CHECK(calculix_pairs("build/capi_flat.inp", &x0) > 0 && x0 < 0.0);
      CHECK(egw_write_flat_calculix_shifted(&q, 3e-3, 1e-3, 1, "build/capi_flat_s.inp",
                                            &err) == EGW_OK);
      /* 1e-3 fits in 200 pairs: the bisection result, error <= rel_tol */
      CHECK(calculix_pairs("build/capi_flat_s.inp", &x0) > 0 && x0 == 0.0);
      CHECK(err > 0.0 && err <= 1e-3);
    }
    /* a reversible curve cannot hold the cap: refused, naming flow_pressure (before
     * stop 63 (audit29) the uncapped p_G was written, up to ~30 p_y here) */
    q.flow_pressure = 1e-3;
    CHECK(egw_write_flat_calculix(&q, 3e-3, 1e-3, "build/capi_flat_cap.inp")
          == EGW_INVALID_PARAMETER);
    CHECK(last_error_names("flow_pressure"));
    CHECK(egw_write_flat_calculix_shifted(&q, 3e-3, 1e-3, 1, "build/capi_flat_cap.inp", NULL)
          == EGW_INVALID_PARAMETER);
    CHECK(last_error_names("flow_pressure"));
    q.flow_pressure = 0.0;
    q.sigma = 0.0;
    CHECK(egw_write_flat_calculix(&q, 3e-3, 1e-5, "build/capi_flat.inp")
          == EGW_INVALID_PARAMETER);
    CHECK(last_error_names("sigma"));
  }
  return failures;
}

/* Universal Hertz table: p = (4/3) x^1.5 for every mu, so scaling by E sqrt(R)
 * sigma^1.5 at call time reproduces the Hertz force of any R, E, sigma to the 1-D
 * accuracy (1.5 rel_tol). */
int egw_capi_test_table_universal(void) {
  egw_params p = hertz_params(), c;
  egw_universal u = NULL, back = NULL;
  double f = -1.0, k = -1.0;
  const double tol = 1e-6;
  failures = 0;
  CHECK(egw_universal_build(&p, NULL, 0.5, 4.0, -1.0, 100.0, tol, &u) == EGW_OK && u != NULL);
  if (u == NULL) return failures;
  c = p;
  c.radius = 0.3; c.modulus = 7.0; c.sigma = 2e-3; c.mu = 1.3;
  for (int i = 1; i <= 40; i++) {
    double d = c.sigma * (1.0 + 99.0 * (i - 0.5) / 40);
    CHECK(egw_universal_eval(u, &c, d, &f, &k) == EGW_OK);
    CHECK(fabs(f / p_hertz(7.0, 0.3, d) - 1.0) <= 1.5 * tol);
  }
  CHECK(egw_universal_eval(u, &c, -1.0, &f, &k) == EGW_OK && f == 0.0 && k == 0.0);
  { egw_params q = c; q.mu = 8.0; f = 3.0;
    CHECK(egw_universal_eval(u, &q, 0.01, &f, &k) == EGW_OUT_OF_RANGE && f == 3.0);
    CHECK(last_error_names("mu")); }
  { egw_params q = c; q.model = EGW_MODEL_EGW;
    CHECK(egw_universal_eval(u, &q, 0.01, &f, &k) == EGW_INVALID_ARGUMENT);
    CHECK(last_error_names("model")); }
  { egw_params q = c; q.sigma = 0.0;
    CHECK(egw_universal_eval(u, &q, 0.01, &f, &k) == EGW_INVALID_PARAMETER); }
  CHECK(egw_universal_eval(u, &c, 1.0, &f, &k) == EGW_OUT_OF_RANGE && f > 0.0);
  CHECK(egw_universal_eval(u, &c, NAN, &f, &k) == EGW_INVALID_ARGUMENT);
  CHECK(egw_universal_eval(NULL, &c, 0.01, &f, &k) == EGW_NULL_POINTER);
  CHECK(egw_universal_eval(u, NULL, 0.01, &f, &k) == EGW_NULL_POINTER);
  CHECK(egw_universal_write(u, "build/capi_universal.egwu", EGW_FORMAT_BINARY) == EGW_OK);
  CHECK(egw_universal_write(u, "build/capi_universal.table", EGW_FORMAT_LAMMPS)
        == EGW_UNSUPPORTED);
  CHECK(egw_universal_read("build/capi_universal.egwu", &back) == EGW_OK && back != NULL);
  if (back != NULL) {
    double f2, k2;
    egw_universal_eval(u, &c, 0.05, &f, &k);
    egw_universal_eval(back, &c, 0.05, &f2, &k2);
    CHECK(f == f2 && k == k2);
  }
  { egw_universal v = NULL;
    CHECK(egw_universal_read("build/capi_table.csv", &v) == EGW_BAD_FILE && v == NULL); }
  /* the slice at c (mu between grid slices) evaluates like the universal table: the
   * same cubic in ln P from combined nodal data, so only rounding differs (a few ulp
   * of ln P ~ 1e-15 relative; 1e-12 leaves room); zero below the cut-off on both */
  { egw_table s = NULL;
    double fs, ks;
    CHECK(egw_universal_slice(u, &c, &s) == EGW_OK && s != NULL);
    if (s != NULL) {
      for (int i = 0; i <= 60; i++) {
        double d = c.sigma * (-2.0 + 112.0 * i / 60.0 + 1e-3); /* to 1.1 x_max */
        int su = egw_universal_eval(u, &c, d, &f, &k);
        int st = egw_table_eval(s, d, &fs, &ks);
        CHECK(su == st);
        CHECK(fabs(fs - f) <= 1e-12 * fabs(f) && fabs(ks - k) <= 1e-12 * fabs(k));
      }
    }
    egw_table_free(&s);
    CHECK(s == NULL);
    { egw_params q = c; q.mu = 8.0;
      CHECK(egw_universal_slice(u, &q, &s) == EGW_OUT_OF_RANGE && s == NULL);
      CHECK(last_error_names("mu")); }
    { egw_params q = c; q.model = EGW_MODEL_EGW;
      CHECK(egw_universal_slice(u, &q, &s) == EGW_INVALID_ARGUMENT && s == NULL); }
    CHECK(egw_universal_slice(NULL, &c, &s) == EGW_NULL_POINTER && s == NULL);
    CHECK(egw_universal_slice(u, &c, NULL) == EGW_NULL_POINTER);
    /* trimmed to delta <= 20 sigma: the same values below it (same cubics; 1e-12 as
     * above), then extrapolation flagged EGW_OUT_OF_RANGE */
    CHECK(egw_universal_slice_range(u, &c, 20.0 * c.sigma, &s) == EGW_OK && s != NULL);
    if (s != NULL) {
      for (int i = 0; i <= 40; i++) {
        double d = c.sigma * (-2.0 + 22.0 * i / 40.0 + 1e-3);
        int su = egw_universal_eval(u, &c, d, &f, &k);
        CHECK(egw_table_eval(s, d, &fs, &ks) == su);
        CHECK(fabs(fs - f) <= 1e-12 * fabs(f) && fabs(ks - k) <= 1e-12 * fabs(k));
      }
    }
    egw_table_free(&s);
    CHECK(egw_universal_slice_range(u, &c, NAN, &s) == EGW_INVALID_ARGUMENT && s == NULL);
    CHECK(last_error_names("delta_max")); }
  egw_universal_free(&back);
  egw_universal_free(&u);
  egw_universal_free(&u);
  egw_universal_free(NULL);
  CHECK(u == NULL && back == NULL);
  { egw_universal v = NULL;
    CHECK(egw_universal_build(&p, NULL, 4.0, 0.5, -1.0, 100.0, tol, &v) == EGW_INVALID_ARGUMENT
          && v == NULL);
    CHECK(last_error_names("mu_max")); }
  return failures;
}

/* ---- the stand-alone reader of doc/formats.md, verbatim (a C program without egw) ---- */

typedef struct {
  int32_t model, n, n_log;
  double params[7], meta[7]; /* as in the table above */
  double *delta, *force, *stiffness, *energy, *contact_radius; /* one block */
} plain_table;

static uint32_t fnv1a32(const unsigned char *p, size_t n) {
  uint32_t h = 2166136261u;
  for (size_t i = 0; i < n; i++) { h ^= p[i]; h *= 16777619u; }
  return h;
}

/* 0 on success; 1 cannot open/read; 2 not a valid egw 1-D table file */
static int plain_table_read(const char *path, plain_table *t) {
  FILE *fp = fopen(path, "rb");
  unsigned char *b;
  long size;
  int32_t version, bom;
  uint32_t sum;
  if (fp == NULL) return 1;
  fseek(fp, 0, SEEK_END); size = ftell(fp); fseek(fp, 0, SEEK_SET);
  b = malloc(size > 0 ? size : 1);
  if (b == NULL || size < 148 || fread(b, 1, size, fp) != (size_t)size) {
    fclose(fp); free(b); return size < 148 ? 2 : 1;
  }
  fclose(fp);
  memcpy(&version, b + 8, 4); memcpy(&bom, b + 12, 4); memcpy(&sum, b + size - 4, 4);
  memcpy(&t->model, b + 20, 4); memcpy(&t->n, b + 24, 4); memcpy(&t->n_log, b + 28, 4);
  if (memcmp(b, "EGWTAB1D", 8) != 0 || version != 1 || bom != 0x01020304
      || sum != fnv1a32(b, size - 4) || t->n < 2 || size != 148 + 40L * t->n) {
    free(b); return 2;
  }
  memcpy(t->params, b + 32, 56);
  memcpy(t->meta, b + 88, 56);
  t->delta = malloc(40L * t->n);
  memcpy(t->delta, b + 144, 40L * t->n);
  t->force = t->delta + t->n; t->stiffness = t->force + t->n;
  t->energy = t->stiffness + t->n; t->contact_radius = t->energy + t->n;
  free(b);
  return 0;
}
static void plain_table_eval(const plain_table *t, double d, double *f, double *k) {
  int lo = 0, hi = t->n - 1, n = t->n;
  if (d < t->delta[0]) { /* below a rough table's cut-off 0 (rule 1) */
    double r = d / t->delta[0];
    *f = *k = 0.0;
    if (t->model == 0 && d > 0.0) { /* Hertz: P_1 (d/d_1)^(3/2) */
      *f = t->force[0] * r * sqrt(r); *k = 1.5 * t->force[0] / t->delta[0] * sqrt(r);
    }
    return;
  }
  if (d >= t->delta[n - 1]) { /* rule 2: c = (4/3) E sqrt(R), params[0] = R, [1] = E */
    double p = t->force[n - 1], q = t->stiffness[n - 1], s = d - t->delta[n - 1];
    double c = 4.0 / 3.0 * t->params[1] * sqrt(t->params[0]), te, u, a, x, step;
    if (!(p > 0.0 && q > 0.0 && c > 0.0)) { *k = q; *f = p + q * s; return; }
    te = pow(cbrt(p) / cbrt(c), 2.0 / 3.0); u = 1.5 * p / q; a = 3.0 * (u - te * te * te) / te;
    x = fmin(te + s * te / (3.0 * u), cbrt(te * te * te + s) + sqrt(fmax(-a, 0.0)));
    for (int it = 0; s > 0.0 && it < 200; it++) { /* Newton from above: monotone */
      step = ((x - te) * (x * x + x * te + te * te + a) - s) / (3.0 * x * x + a);
      if (!(step > 4.0 * DBL_EPSILON * x)) break;
      x -= step;
    }
    if (!(s > 0.0) || x < te) x = te;
    *f = p * pow(x / te, 4.5); *k = 1.5 * *f / (x * (x * x + a / 3.0)); return;
  }
  while (hi - lo > 1) { int m = (lo + hi) / 2; if (d >= t->delta[m]) lo = m; else hi = m; }
  {
    int lg = lo < t->n_log; /* 0-based interval lo is 1-based lo+1 <= n_log */
    double h = t->delta[hi] - t->delta[lo], s = (d - t->delta[lo]) / h;
    double v0 = lg ? log(t->force[lo]) : t->force[lo], v1 = lg ? log(t->force[hi]) : t->force[hi];
    double d0 = lg ? t->stiffness[lo] / t->force[lo] : t->stiffness[lo];
    double d1 = lg ? t->stiffness[hi] / t->force[hi] : t->stiffness[hi];
    double v = (1 + 2 * s) * (1 - s) * (1 - s) * v0 + s * (1 - s) * (1 - s) * h * d0
             + s * s * (3 - 2 * s) * v1 + s * s * (s - 1) * h * d1;
    double dv = 6 * s * (s - 1) / h * (v0 - v1) + (1 - s) * (1 - 3 * s) * d0
              + s * (3 * s - 2) * d1;
    if (lg) { *f = exp(v); *k = *f * dv; } else { *f = v; *k = dv; }
  }
}

/* The documented reader loads the binary file and evaluates it like egw: same node
 * count, metadata, and force/stiffness to 1e-12 relative (the reader evaluates the
 * Hermite basis form, egw the polynomial form: different rounding, and exp() in the
 * log tail amplifies it by |ln P| < 30), except in the separated tail below 0, where
 * egw_table_eval takes its resampling of the same interpolant (egw.h, formats.md
 * rule 3: within 5e-2 rel_tol in P and rel_tol in K). A corrupted copy is refused. */
int egw_capi_test_table_plain_reader(void) {
  egw_params p;
  egw_table t = NULL;
  egw_table_info info;
  plain_table pt;
  const char *path = "build/capi_plain.egwt";
  failures = 0;
  egw_params_default(&p);
  p.sigma = 1e-3; p.mu = 4.0; /* E-GW: exercises the log tail too */
  CHECK(egw_table_build(&p, NULL, -6e-3, 5e-3, 1e-5, &t) == EGW_OK);
  if (t == NULL) return failures;
  CHECK(egw_table_write(t, path, EGW_FORMAT_BINARY) == EGW_OK);
  CHECK(egw_table_get_info(t, &info) == EGW_OK);
  CHECK(plain_table_read(path, &pt) == 0);
  CHECK(pt.n == info.n_nodes && pt.model == EGW_MODEL_EGW && pt.n_log > 0);
  CHECK(pt.meta[1] == info.cutoff && pt.meta[2] == info.delta_max && pt.params[3] == 4.0);
  for (int i = 0; i <= 400; i++) {
    double d = -7e-3 + 13e-3 * i / 400.0, f1, k1, f2, k2;
    int st = egw_table_eval(t, d, &f1, &k1);
    CHECK(st == EGW_OK || st == EGW_OUT_OF_RANGE);
    plain_table_eval(&pt, d, &f2, &k2);
    if (d < info.cutoff) /* rule 1: 0 below the cut-off of a rough table, as the reader */
      CHECK(f2 == 0.0 && f1 == 0.0 && k1 == 0.0);
    else if (d < 0.0) /* the resampled tail: 5e-2 rel_tol in P, rel_tol in K (egw.h) */
      CHECK(fabs(f1 - f2) <= 5e-2 * 1e-5 * fabs(f2) && fabs(k1 - k2) <= 1e-5 * fabs(k2));
    else
      CHECK(fabs(f1 - f2) <= 1e-12 * fabs(f1) && fabs(k1 - k2) <= 1e-12 * fabs(k1) + 1e-300);
  }
  free(pt.delta);
  {
    /* egw_table_get_interpolant: its cubics, evaluated as egw.h says, give
     * egw_table_eval's values on (cutoff, delta_max) to 1e-14 relative (same coefficients
     * and order of operations, up to the compiler's rounding; exp() amplifies an ulp of
     * ln P by |ln P| < 30, as above); a too small capacity or NULL is refused */
    int n = info.n_nodes, nl = -1, i;
    double *x = malloc(sizeof(double) * n), *c = malloc(sizeof(double) * 4 * n);
    CHECK(egw_table_get_interpolant(t, n - 1, x, c, &nl) == EGW_INVALID_ARGUMENT && nl == -1);
    CHECK(last_error_names("capacity"));
    CHECK(egw_table_get_interpolant(t, n, NULL, c, &nl) == EGW_NULL_POINTER);
    CHECK(egw_table_get_interpolant(NULL, n, x, c, &nl) == EGW_NULL_POINTER);
    CHECK(egw_table_get_interpolant(t, n, x, c, &nl) == EGW_OK);
    CHECK(nl > 0 && nl < n - 1 && x[0] == info.cutoff && x[n - 1] == info.delta_max);
    for (i = 0; i + 1 < n; i++) CHECK(x[i] < x[i + 1]);
    i = 0;
    for (int j = 1; j < 2000; j++) {
      double d = info.cutoff + (info.delta_max - info.cutoff) * j / 2000.0, f1, k1, f2, k2;
      while (d >= x[i + 1]) i++;
      double tt = d - x[i], *ci = &c[4 * i];
      double v = (ci[0] + tt * ci[1]) + tt * tt * (ci[2] + tt * ci[3]);
      double dv = (ci[1] + 2 * tt * ci[2]) + 3 * tt * tt * ci[3];
      f2 = i < nl ? exp(v) : v;
      k2 = i < nl ? f2 * dv : dv;
      CHECK(egw_table_eval(t, d, &f1, &k1) == EGW_OK);
      if (i < nl && x[i + 1] <= 0.0) /* the resampled tail, as above */
        CHECK(fabs(f1 - f2) <= 5e-2 * 1e-5 * fabs(f2) && fabs(k1 - k2) <= 1e-5 * fabs(k2));
      else
        CHECK(fabs(f1 - f2) <= 1e-14 * fabs(f1) && fabs(k1 - k2) <= 1e-14 * fabs(k1) + 1e-300);
    }
    free(x);
    free(c);
  }
  {
    FILE *fp = fopen(path, "r+b");
    if (fp != NULL) { fseek(fp, 150, SEEK_SET); fputc(0x55, fp); fclose(fp); }
    CHECK(plain_table_read(path, &pt) == 2);
  }
  egw_table_free(&t);
  return failures;
}

/* |error| bound of a cubic (c0 + t c1) + t^2 (c2 + t c3) and its slope evaluated in
 * doubles: each of the <= 7 operations rounds once, relative 2^-53 of the partial sums,
 * which are bounded by the sum of the terms' magnitudes; 8 DBL_EPSILON of that sum covers
 * them (two evaluations of the same formula differ by at most twice one's error). */
static double cubic_rounding(const double *c, double t) {
  return 8.0 * DBL_EPSILON * (fabs(c[0]) + fabs(t * c[1]) + fabs(t * t * c[2]) +
                              fabs(t * t * t * c[3]) + 1e-300);
}
static double slope_rounding(const double *c, double t) {
  return 8.0 * DBL_EPSILON * (fabs(c[1]) + fabs(2.0 * t * c[2]) + fabs(3.0 * t * t * c[3]) +
                              1e-300);
}
/* The ln P interpolant of a table (egw_table_get_interpolant's cubics with exp: the
 * table's own rule 3, not its resampling) at d in its interval i < n_log. */
static void ln_interpolant(const double *x, const double *c, int i, double d, double *f,
                           double *k) {
  double t = d - x[i];
  const double *a = &c[4 * i];
  double v = (a[0] + t * a[1]) + t * t * (a[2] + t * a[3]);
  double dv = (a[1] + 2 * t * a[2]) + 3 * t * t * a[3];
  *f = exp(v);
  *k = *f * dv;
}

/* egw_table_get_tail: the resampled tail's pieces of one table, evaluated as egw.h says
 * at 5 points inside each piece, give egw_table_eval's force and stiffness (the same
 * cubics: to the rounding of a cubic, cubic_rounding; bit for bit when both compilers
 * round alike); the pieces start at the cut-off, are equal and end at a node <= 0 that
 * ends an ln P interval. Two slices of an E-GW universal table on one grid: each slice's
 * pieces within 5e-2 rel_tol of its ln P interpolant (rule 3) in the force and rel_tol in
 * the stiffness at 5 points of every piece (the resampling's contract: 2.5e-2 and
 * 0.5 rel_tol at its 8 check points, twice that between them, as test_table's
 * resampled-tail test); one table twice gives its own pieces bit for bit. Refused, with
 * nothing written: NULL arguments, too small buffers, n < 1, a table without a tail
 * (Hertz), tables on different nodes. */
int egw_capi_test_table_tail(void) {
  egw_params p;
  egw_table t = NULL, h = NULL, pair[2];
  egw_table_info info;
  const double tol = 1e-4;
  int n = -1, nq, st;
  failures = 0;
  egw_params_default(&p);
  p.sigma = 1e-3; p.mu = 4.0;
  CHECK(egw_table_build(&p, NULL, -6e-3, 5e-3, tol, &t) == EGW_OK);
  if (t == NULL) return failures;
  CHECK(egw_table_get_info(t, &info) == EGW_OK);
  /* the size query */
  CHECK(egw_table_get_tail(1, &t, 0, NULL, NULL, &n) == EGW_OK && n >= 16 && n <= 8192);
  if (n < 16 || n > 8192) { egw_table_free(&t); return failures; }
  nq = n;
  {
    double *s = malloc(sizeof(double) * (nq + 1)), *c = malloc(sizeof(double) * 4 * nq);
    int nn = info.n_nodes, nl = -1, last;
    double *x = malloc(sizeof(double) * nn), *ci = malloc(sizeof(double) * 4 * nn);
    /* refusals: nothing written, the message names the argument */
    s[0] = -7.0; n = -1;
    CHECK(egw_table_get_tail(1, &t, nq - 1, s, c, &n) == EGW_INVALID_ARGUMENT);
    CHECK(n == -1 && s[0] == -7.0 && last_error_names("capacity"));
    CHECK(egw_table_get_tail(1, &t, -1, NULL, NULL, &n) == EGW_INVALID_ARGUMENT && n == -1);
    CHECK(last_error_names("capacity"));
    CHECK(egw_table_get_tail(0, &t, nq, s, c, &n) == EGW_INVALID_ARGUMENT && n == -1);
    CHECK(last_error_names("n"));
    CHECK(egw_table_get_tail(1, NULL, nq, s, c, &n) == EGW_NULL_POINTER && n == -1);
    CHECK(last_error_names("tables"));
    { egw_table none = NULL;
      CHECK(egw_table_get_tail(1, &none, nq, s, c, &n) == EGW_NULL_POINTER && n == -1);
      CHECK(last_error_names("tables[0]")); }
    CHECK(egw_table_get_tail(1, &t, nq, s, c, NULL) == EGW_NULL_POINTER && s[0] == -7.0);
    CHECK(last_error_names("n_pieces"));
    CHECK(egw_table_get_tail(1, &t, nq, NULL, c, &n) == EGW_NULL_POINTER && n == -1);
    CHECK(last_error_names("starts"));
    CHECK(egw_table_get_tail(1, &t, nq, s, NULL, &n) == EGW_NULL_POINTER && n == -1);
    CHECK(last_error_names("coeffs"));
    /* a Hertz table has no separated tail */
    { egw_params q = hertz_params();
      CHECK(egw_table_build(&q, NULL, 0.0, 1e-3, 1e-4, &h) == EGW_OK);
      CHECK(egw_table_get_tail(1, &h, nq, s, c, &n) == EGW_INVALID_ARGUMENT && n == -1);
      CHECK(last_error_names("tables[0]") && s[0] == -7.0); }
    /* tables on different nodes get no common grid */
    pair[0] = t; pair[1] = h;
    CHECK(egw_table_get_tail(2, pair, nq, s, c, &n) == EGW_INVALID_ARGUMENT && n == -1);
    CHECK(last_error_names("tables[1]"));
    /* the pieces */
    CHECK(egw_table_get_tail(1, &t, nq, s, c, &n) == EGW_OK && n == nq);
    CHECK(egw_table_get_interpolant(t, nn, x, ci, &nl) == EGW_OK && nl > 0);
    CHECK(s[0] == info.cutoff && s[nq] <= 0.0);
    for (last = 0; last < nn && x[last] != s[nq]; last++) {}
    CHECK(last < nn && last <= nl && (last == nl || x[last + 1] > 0.0));
    for (int q = 0; q < nq; q++) {
      double w = (s[nq] - s[0]) / nq;
      CHECK(s[q] < s[q + 1] && fabs(s[q + 1] - s[q] - w) <= 1e-9 * w);
      for (int j = 1; j <= 5; j++) {
        double d = s[q] + (s[q + 1] - s[q]) * (j - 0.5) / 5.0, f1, k1;
        int qq = (int) ((d - s[0]) * (nq / (s[nq] - s[0])));
        double tt;
        const double *a;
        if (qq > nq - 1) qq = nq - 1;
        tt = d - s[qq];
        a = &c[4 * qq];
        st = egw_table_eval(t, d, &f1, &k1);
        CHECK(st == EGW_OK);
        CHECK(fabs(f1 - ((a[0] + tt * a[1]) + tt * tt * (a[2] + tt * a[3])))
              <= cubic_rounding(a, tt));
        CHECK(fabs(k1 - ((a[1] + 2 * tt * a[2]) + 3 * tt * tt * a[3]))
              <= slope_rounding(a, tt));
      }
    }
    /* one table twice: one grid, its own pieces for both */
    pair[0] = t; pair[1] = t;
    {
      double *s2 = malloc(sizeof(double) * (nq + 1)), *c2 = malloc(sizeof(double) * 8 * nq);
      int n2 = -1;
      CHECK(egw_table_get_tail(2, pair, nq, s2, c2, &n2) == EGW_OK && n2 == nq);
      for (int q = 0; n2 == nq && q < nq; q++)
        for (int j = 0; j < 4; j++)
          CHECK(c2[8 * q + j] == c[4 * q + j] && c2[8 * q + 4 + j] == c[4 * q + j]);
      CHECK(memcmp(s, s2, sizeof(double) * (nq + 1)) == 0);
      free(s2);
      free(c2);
    }
    free(s); free(c); free(x); free(ci);
  }
  egw_table_free(&h);
  egw_table_free(&t);
  /* two slices of an E-GW universal table (shared nodes) on one grid */
  {
    egw_universal u = NULL;
    egw_table sl[2] = {NULL, NULL};
    egw_params q;
    egw_params_default(&q);
    q.sigma = 1e-3; q.radius = 1.0;
    CHECK(egw_universal_build(&q, NULL, 1.0, 8.0, -6.0, 5.0, tol, &u) == EGW_OK);
    if (u == NULL) return failures;
    q.mu = 1.5; CHECK(egw_universal_slice(u, &q, &sl[0]) == EGW_OK);
    q.mu = 6.0; CHECK(egw_universal_slice(u, &q, &sl[1]) == EGW_OK);
    egw_universal_free(&u);
    if (sl[0] == NULL || sl[1] == NULL) { egw_table_free(&sl[0]); egw_table_free(&sl[1]);
      return failures; }
    CHECK(egw_table_get_tail(2, sl, 0, NULL, NULL, &n) == EGW_OK && n >= 16 && n <= 8192);
    nq = n;
    {
      double *s = malloc(sizeof(double) * (nq + 1)), *c = malloc(sizeof(double) * 8 * nq);
      egw_table_info in0;
      CHECK(egw_table_get_info(sl[0], &in0) == EGW_OK);
      {
        int nn = in0.n_nodes, nl = -1;
        double *x = malloc(sizeof(double) * nn), *ci = malloc(sizeof(double) * 4 * nn);
        CHECK(egw_table_get_tail(2, sl, nq, s, c, &n) == EGW_OK && n == nq);
        for (int k = 0; k < 2; k++) {
          egw_table_info ik;
          int i = 0;
          CHECK(egw_table_get_info(sl[k], &ik) == EGW_OK);
          CHECK(egw_table_get_interpolant(sl[k], nn, x, ci, &nl) == EGW_OK && nl > 0);
          CHECK(s[0] == x[0]);
          for (int qd = 0; qd < nq; qd++)
            for (int j = 1; j <= 5; j++) {
              double d = s[qd] + (s[qd + 1] - s[qd]) * (j - 0.5) / 5.0, fe, ke, tt;
              const double *a = &c[4 * (2 * qd + k)];
              while (d >= x[i + 1]) i++;
              ln_interpolant(x, ci, i, d, &fe, &ke);
              tt = d - s[qd];
              CHECK(fabs((a[0] + tt * a[1]) + tt * tt * (a[2] + tt * a[3]) - fe)
                    <= 5e-2 * ik.rel_tol * fe);
              CHECK(fabs((a[1] + 2 * tt * a[2]) + 3 * tt * tt * a[3] - ke)
                    <= ik.rel_tol * fabs(ke));
            }
        }
        free(x); free(ci);
      }
      free(s); free(c);
    }
    egw_table_free(&sl[0]);
    egw_table_free(&sl[1]);
  }
  return failures;
}

/* The header's own evaluation of egw_table_get_tail's pieces (egw.h: t2 = t t; force
 * (c0 + t c1) + t2 (c2 + t c3), stiffness (c1 + 2 t c2) + 3 t2 c3; no fused multiply-adds). */
#if defined(__GNUC__) && !defined(__clang__)
__attribute__((optimize("fp-contract=off")))
#endif
static void tail_piece(const double *s, const double *c, int nq, int n, int k, double d,
                       double *f, double *kk) {
  int q = (int) ((d - s[0]) * (nq / (s[nq] - s[0])));
  double t, t2;
  const double *a;
  if (q > nq - 1) q = nq - 1;
  t = d - s[q];
  t2 = t * t;
  a = &c[4 * ((size_t) q * n + k)];
  *f = (a[0] + t * a[1]) + t2 * (a[2] + t * a[3]);
  *kk = (a[1] + 2 * t * a[2]) + 3 * t2 * a[3];
}

/* egw_table_get_tail as egw.h words it, at 200 points of every piece of one E-GW table at
 * rel_tol 1e-6 and 1e-4: the pieces evaluated as the header writes them are
 * egw_table_eval's force and stiffness bit for bit (this file is compiled without FMA
 * contraction, as the library), and within the header's bounds of the ln P interpolant
 * (egw_table_get_interpolant's cubics with exp): 5e-2 rel_tol in the force, rel_tol in the
 * stiffness between the 8 check points (measured here: 0.0066 and 0.502 rel_tol at 1e-6,
 * above the 0.5 rel_tol egw.h stated before stop 44's audit8). Slices of one universal
 * table at different sigma have different nodes (x sigma): refused, naming tables[1],
 * nothing written; at the same sigma one grid. */
int egw_capi_test_table_tail_header(void) {
  const double tols[2] = {1e-6, 1e-4};
  failures = 0;
  for (int it = 0; it < 2; it++) {
    egw_params p;
    egw_table t = NULL;
    egw_table_info info;
    int nq = -1, nn, nl = -1;
    double *s, *c, *x, *ci, worst_f = 0.0, worst_k = 0.0;
    long differ = 0;
    egw_params_default(&p);
    p.sigma = 1e-3; p.mu = 4.0;
    CHECK(egw_table_build(&p, NULL, -2e-3, 2e-2, tols[it], &t) == EGW_OK);
    if (t == NULL) return failures;
    CHECK(egw_table_get_info(t, &info) == EGW_OK);
    CHECK(egw_table_get_tail(1, &t, 0, NULL, NULL, &nq) == EGW_OK && nq >= 16 && nq <= 8192);
    if (nq < 16 || nq > 8192) { egw_table_free(&t); return failures; }
    nn = info.n_nodes;
    s = malloc(sizeof(double) * (nq + 1)); c = malloc(sizeof(double) * 4 * nq);
    x = malloc(sizeof(double) * nn); ci = malloc(sizeof(double) * 4 * nn);
    CHECK(egw_table_get_tail(1, &t, nq, s, c, &nq) == EGW_OK);
    CHECK(egw_table_get_interpolant(t, nn, x, ci, &nl) == EGW_OK && nl > 0);
    for (int q = 0, i = 0; q < nq; q++)
      for (int j = 1; j <= 200; j++) {
        double d = s[q] + (s[q + 1] - s[q]) * (j - 0.5) / 200.0, f, k, fe, ke, fi, ki;
        tail_piece(s, c, nq, 1, 0, d, &f, &k);
        CHECK(egw_table_eval(t, d, &fe, &ke) == EGW_OK);
        if (f != fe || k != ke) differ++;
        while (d >= x[i + 1]) i++;
        ln_interpolant(x, ci, i, d, &fi, &ki);
        if (fabs(f / fi - 1.0) > worst_f) worst_f = fabs(f / fi - 1.0);
        if (fabs(k / ki - 1.0) > worst_k) worst_k = fabs(k / ki - 1.0);
      }
    printf("    get_tail header, rel_tol %.0e: %d pieces, %ld of %d points not bit for bit; "
           "against ln P: force %.3g rel_tol, stiffness %.3g rel_tol\n", tols[it], nq, differ,
           200 * nq, worst_f / info.rel_tol, worst_k / info.rel_tol);
    CHECK(differ == 0);
    CHECK(worst_f <= 5e-2 * info.rel_tol);
    CHECK(worst_k <= info.rel_tol);
    free(s); free(c); free(x); free(ci);
    egw_table_free(&t);
  }
  {
    egw_universal u = NULL;
    egw_table sl[3] = {NULL, NULL, NULL};
    egw_params q;
    int n = -1;
    double s[4] = {-7.0, -7.0, -7.0, -7.0};
    egw_params_default(&q);
    q.sigma = 1e-3; q.radius = 1.0;
    CHECK(egw_universal_build(&q, NULL, 1.0, 8.0, -6.0, 5.0, 1e-4, &u) == EGW_OK);
    if (u == NULL) return failures;
    q.mu = 1.5; CHECK(egw_universal_slice(u, &q, &sl[0]) == EGW_OK);
    q.mu = 6.0; q.radius = 3.0; q.modulus = 2.0;
    CHECK(egw_universal_slice(u, &q, &sl[1]) == EGW_OK);
    q.sigma = 2e-3; CHECK(egw_universal_slice(u, &q, &sl[2]) == EGW_OK);
    egw_universal_free(&u);
    if (sl[0] && sl[1] && sl[2]) {
      CHECK(egw_table_get_tail(2, sl, 0, NULL, NULL, &n) == EGW_OK && n >= 16);
      n = -1;
      CHECK(egw_table_get_tail(2, &sl[1], 0, NULL, NULL, &n) == EGW_INVALID_ARGUMENT);
      CHECK(n == -1 && last_error_names("tables[1]"));
      CHECK(egw_table_get_tail(3, sl, 1, s, s, &n) == EGW_INVALID_ARGUMENT);
      CHECK(n == -1 && s[0] == -7.0 && s[1] == -7.0 && last_error_names("tables[2]"));
    }
    for (int k = 0; k < 3; k++) egw_table_free(&sl[k]);
  }
  return failures;
}
