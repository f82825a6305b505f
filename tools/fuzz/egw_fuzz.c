/* egw-fuzz: calls every C function of include/egw.h with hostile arguments (NaN, +-Inf,
 * 0, -0, +-1e300, +-1e-300, subnormals, DBL_MAX, extreme integers, NULL pointers, bad
 * paths), one argument (or struct field) at a time on top of a valid call, each call in
 * a forked child under an alarm, and classifies every call:
 *   refused   status != EGW_OK, outputs unchanged (the documented exceptions aside)
 *   accepted  EGW_OK with finite outputs that pass the function's sanity checks
 *   silent    EGW_OK (or a status documented to write outputs) with NaN/Inf or
 *             impossible outputs (a negative force, ...)
 *   clobbered a refusal that changed an output (egw.h: outputs unchanged on failure)
 *   crashed   the child died on a signal or exited (abort, "Error allocating", stop)
 *   hung      the child outlived the time limit
 * The parent never calls egw itself (libgomp is not fork-safe once its thread pool
 * exists): a first child writes the tables the others read.
 *
 * Usage: egw-fuzz [--short] [-j jobs] [-t seconds] [-v] [-f function]
 *   --short  a few hundred cases (the test suite's mode); default: every case
 *   -t       time limit of a case (default 10 s; 3 times that for the functions that solve)
 * Exit status 0 when no case is silent, clobbered, crashed or hung; 1 otherwise; 2 on a
 * usage or set-up error. doc/fuzz.md describes the harness. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "egw.h"

/* ------------------------------------------------------------------ values */

enum { K_DBL, K_INT, K_PTR, K_STR };

static const double dvals_full[] = {NAN, INFINITY, -INFINITY, 0.0, -0.0, 1e300, -1e300,
                                    1e-300, -1e-300, 4.9e-324, 1e-310, DBL_MAX,
                                    1e-200, 1e-100, 1e100, 1e200};
static const char *dnames_full[] = {"NaN", "+Inf", "-Inf", "0", "-0", "1e300", "-1e300",
                                    "1e-300", "-1e-300", "4.9e-324", "1e-310", "DBL_MAX",
                                    "1e-200", "1e-100", "1e100", "1e200"};
/* pairs of the scale fields R, E, sigma, mu (full mode): both at once at these values */
static const double pvals[] = {1e-200, 1e-100, 1e100, 1e200};
static const char *pnames[] = {"1e-200", "1e-100", "1e100", "1e200"};
enum { N_PAIR_VALUES = 4 };
static const double dvals_short[] = {NAN, INFINITY, -INFINITY, 0.0, 1e300, -1e300, 1e-300,
                                     4.9e-324};
static const char *dnames_short[] = {"NaN", "+Inf", "-Inf", "0", "1e300", "-1e300",
                                     "1e-300", "4.9e-324"};
static const int ivals_full[] = {INT_MIN, -1, 0, 1, 2, 7, 8, 100000000, INT_MAX};
static const char *inames_full[] = {"INT_MIN", "-1", "0", "1", "2", "7", "8", "1e8",
                                    "INT_MAX"};
static const int ivals_short[] = {INT_MIN, -1, 0, 100000000, INT_MAX};
static const char *inames_short[] = {"INT_MIN", "-1", "0", "1e8", "INT_MAX"};
/* strings: index into these in the child (the long one is built there) */
static const char *snames[] = {"NULL", "\"\"", "missing dir", "a directory", "5000 chars"};
enum { N_STR = 5 };

static int short_mode = 0;
static char tmpdir[256];

static int n_values(int kind) {
  switch (kind) {
  case K_DBL: return short_mode ? (int)(sizeof dvals_short / sizeof *dvals_short)
                                : (int)(sizeof dvals_full / sizeof *dvals_full);
  case K_INT: return short_mode ? (int)(sizeof ivals_short / sizeof *ivals_short)
                                : (int)(sizeof ivals_full / sizeof *ivals_full);
  case K_PTR: return 1;
  default: return short_mode ? 2 : N_STR;
  }
}
static const char *value_name(int kind, int v) {
  switch (kind) {
  case K_DBL: return short_mode ? dnames_short[v] : dnames_full[v];
  case K_INT: return short_mode ? inames_short[v] : inames_full[v];
  case K_PTR: return "NULL";
  default: return snames[short_mode ? (v == 0 ? 0 : 4) : v];
  }
}

/* ------------------------------------------------------------------ one call */

typedef struct {
  int slot;  /* fuzzed slot, -1: the valid base call */
  int value; /* index into the slot kind's values */
  int slot2, value2; /* a second fuzzed slot (pairs of params scale fields), else -1 */
  /* results, filled in the child */
  int status;
  int silent, clobbered;
  char detail[200];
} fz_case;

static fz_case *cur;

static double D(int slot, double base) {
  if (cur->slot2 >= 0) {
    if (slot == cur->slot) return pvals[cur->value];
    if (slot == cur->slot2) return pvals[cur->value2];
    return base;
  }
  if (cur->slot != slot) return base;
  return short_mode ? dvals_short[cur->value] : dvals_full[cur->value];
}
static int I(int slot, int base) {
  if (cur->slot != slot) return base;
  return short_mode ? ivals_short[cur->value] : ivals_full[cur->value];
}
static void *P(int slot, void *base) { return cur->slot == slot ? NULL : base; }
static const char *S(int slot, const char *base) {
  static char long_path[5200];
  int v;
  if (cur->slot != slot) return base;
  v = short_mode ? (cur->value == 0 ? 0 : 4) : cur->value;
  switch (v) {
  case 0: return NULL;
  case 1: return "";
  case 2: return "/nonexistent-egw-fuzz-dir/x/y.egw";
  case 3: return tmpdir;
  default:
    snprintf(long_path, sizeof long_path, "%s/", tmpdir);
    for (size_t i = strlen(long_path); i < 5000; i++) long_path[i] = (i % 200 == 0) ? '/' : 'a';
    long_path[5000] = '\0';
    return long_path;
  }
}

#define SENT 0x5A
static void sentinel(void *p, size_t n) { memset(p, SENT, n); }
static int is_sentinel(const void *p, size_t n) {
  const unsigned char *b = p;
  for (size_t i = 0; i < n; i++)
    if (b[i] != SENT) return 0;
  return 1;
}
/* the first problem of a case, for the report: "<what> (<value>)" */
static void note(const char *what, const char *name, double x) {
  if (cur->detail[0]) return;
  snprintf(cur->detail, sizeof cur->detail, "%s%s (%g)", name, what, x);
}

/* outputs written when st is OK or (written_too) one more status: finite, else untouched */
static void out_doubles(int st, int written_too, const char *name, const double *x, int n,
                        size_t bytes) {
  if (st == EGW_OK || (written_too && st == written_too)) {
    for (int i = 0; i < n; i++)
      if (!isfinite(x[i])) {
        cur->silent = 1;
        note(" not finite", name, x[i]);
      }
  } else if (!is_sentinel(x, bytes)) {
    cur->clobbered = 1;
    note(" changed on refusal", name, x[0]);
  }
}
static void out_untouched(int st, const char *name, const void *x, size_t bytes) {
  if (st != EGW_OK && !is_sentinel(x, bytes)) {
    cur->clobbered = 1;
    note(" changed on refusal", name, 0.0);
  }
}
static void sane(int st, int cond, const char *what, double x) {
  if (st == EGW_OK && !cond) {
    cur->silent = 1;
    note("", what, x);
  }
}

/* ------------------------------------------------------------------ bases */

/* params slots: 8 fields from slot s */
static egw_params params_at(int s, int model, double psi) {
  egw_params p;
  egw_params_default(&p);
  p.model = I(s, model);
  p.radius = D(s + 1, 1.0);
  p.modulus = D(s + 2, 1.0);
  p.sigma = D(s + 3, model == EGW_MODEL_HERTZ ? 0.0 : 1e-3);
  p.mu = D(s + 4, 2.0);
  p.psi = D(s + 5, psi);
  p.hardness_coeff = D(s + 6, 0.6);
  p.plastic_ratio = D(s + 7, 54.0);
  return p;
}
#define PARAM_SLOTS(prefix)                                                              \
  {prefix "model", K_INT}, {prefix "radius", K_DBL}, {prefix "modulus", K_DBL},          \
      {prefix "sigma", K_DBL}, {prefix "mu", K_DBL}, {prefix "psi", K_DBL},              \
      {prefix "hardness_coeff", K_DBL}, { prefix "plastic_ratio", K_DBL }
static egw_options options_at(int s, double rel_tol) {
  egw_options o;
  egw_options_default(&o);
  o.n_radial = I(s, 0);
  o.rel_tol = D(s + 1, rel_tol);
  o.max_iter = I(s + 2, 0);
  o.method = I(s + 3, 0);
  o.n_threads = I(s + 4, 1);
  return o;
}
#define OPTION_SLOTS                                                                    \
  {"o.n_radial", K_INT}, {"o.rel_tol", K_DBL}, {"o.max_iter", K_INT}, {"o.method", K_INT}, \
      { "o.n_threads", K_INT }

static char table_path[300], universal_path[300];

static egw_table base_table(void) {
  egw_table t = NULL;
  if (egw_table_read(table_path, &t) != EGW_OK) {
    fprintf(stderr, "egw-fuzz: cannot read %s\n", table_path);
    _exit(3);
  }
  return t;
}
static egw_universal base_universal(void) {
  egw_universal u = NULL;
  if (egw_universal_read(universal_path, &u) != EGW_OK) {
    fprintf(stderr, "egw-fuzz: cannot read %s\n", universal_path);
    _exit(3);
  }
  return u;
}
/* a file of this child (concurrent children never share a path: two writers of one path
 * share its temporary file name, which egw's atomic write does not guard against) */
static char *out_path(const char *name) {
  static char path[8][400];
  static int next;
  char *p = path[next++ % 8];
  snprintf(p, sizeof path[0], "%s/%ld-%s", tmpdir, (long)getpid(), name);
  return p;
}

/* ------------------------------------------------------------------ the functions */

typedef struct {
  const char *name;
  int n_slots;
  struct { const char *name; int kind; } slots[48];
  int (*run)(void);
  int heavy; /* solves: sampled in the short mode */
} fz_function;

static int r_version(void) { return egw_get_version() == EGW_VERSION ? EGW_OK : -1; }

static int r_status_message(void) {
  char buf[64];
  int st;
  sentinel(buf, sizeof buf);
  st = egw_status_message(I(0, EGW_IO_ERROR), P(1, buf), I(2, (int)sizeof buf));
  if (st == EGW_OK && memchr(buf, 0, sizeof buf) == NULL) {
    cur->silent = 1;
    note("", "buf not NUL-terminated", 0.0);
  }
  return st;
}

/* egw_last_error returns the bytes its message needs (>= 1; a size query when buflen is
 * 0) or minus a status: mapped to EGW_OK / the status here. A message is first made by
 * a refused call, so that truncation at the fuzzed buflen is exercised. */
static int r_last_error(void) {
  char buf[4096]; /* above every message (a huge buflen must not overrun it); base 16 truncates */
  int n, len = I(1, 16);
  egw_params bad;
  egw_params_default(&bad);
  bad.sigma = -1.0;
  (void)egw_params_validate(&bad);
  sentinel(buf, sizeof buf);
  n = egw_last_error(P(0, buf), len);
  if (n == 0) { /* no documented value */
    cur->silent = 1;
    note("", "returned 0", 0.0);
    return EGW_OK;
  }
  if (n < 0) {
    out_untouched(-n, "buf", buf, sizeof buf);
    return -n;
  }
  if (len > 0 && len <= (int)sizeof buf) {
    const char *nul = memchr(buf, 0, sizeof buf);
    if (nul == NULL) {
      cur->silent = 1;
      note("", "buf not NUL-terminated", 0.0);
    } else if ((int)(nul - buf) != (n <= len ? n - 1 : len - 1)) {
      cur->silent = 1;
      note("", "returned length does not match the copy", (double)n);
    }
  } else if (len == 0 && !is_sentinel(buf, sizeof buf)) {
    cur->silent = 1;
    note("", "size query wrote to buf", (double)n);
  }
  return EGW_OK;
}

static int r_params(void) {
  egw_params p = params_at(0, EGW_MODEL_EPGW, 0.5);
  egw_params_default(P(8, &p) ? &p : NULL);
  p = params_at(0, EGW_MODEL_EPGW, 0.5);
  return egw_params_validate(P(8, &p));
}

static int r_mu_from_summits(void) {
  double mu;
  int st;
  sentinel(&mu, sizeof mu);
  st = egw_mu_from_summits(D(0, 1e9), D(1, 1e-5), D(2, 1e-6), D(3, 1e-3), P(4, &mu));
  out_doubles(st, 0, "mu", &mu, 1, sizeof mu);
  return st;
}

static int r_psi_from_hardness(void) {
  double psi;
  int st;
  sentinel(&psi, sizeof psi);
  st = egw_psi_from_hardness(D(0, 70e9), D(1, 5e9), D(2, 0.6), D(3, 1e-6), D(4, 1e-5),
                             P(5, &psi));
  out_doubles(st, 0, "psi", &psi, 1, sizeof psi);
  return st;
}

static int r_gauss(void) {
  double v;
  int st;
  sentinel(&v, sizeof v);
  st = egw_gauss_integral(D(0, 1.5), D(1, 0.5), P(2, &v));
  out_doubles(st, 0, "value", &v, 1, sizeof v);
  sane(st, v >= 0, "F_n < 0", v);
  return st;
}

static int r_gauss_deriv(void) {
  double v;
  int st;
  sentinel(&v, sizeof v);
  st = egw_gauss_integral_deriv(D(0, 1.5), D(1, 0.5), P(2, &v));
  out_doubles(st, 0, "value", &v, 1, sizeof v);
  sane(st, v <= 0, "dF_n/dh > 0", v);
  return st;
}

static int r_ellipk(void) {
  double v;
  int st;
  sentinel(&v, sizeof v);
  st = egw_ellipk(D(0, 0.5), P(1, &v));
  out_doubles(st, 0, "value", &v, 1, sizeof v);
  return st;
}

static int r_ellipe(void) {
  double v;
  int st;
  sentinel(&v, sizeof v);
  st = egw_ellipe(D(0, 0.5), P(1, &v));
  out_doubles(st, 0, "value", &v, 1, sizeof v);
  return st;
}

static int r_flat_pressure(void) {
  egw_params p = params_at(0, EGW_MODEL_EPGW, 0.5);
  double v[2];
  int st;
  sentinel(v, sizeof v);
  st = egw_flat_pressure(P(8, &p), D(9, 1e-3), P(10, &v[0]));
  out_doubles(st, 0, "pressure", v, 1, sizeof v[0]);
  sane(st, v[0] >= 0, "pressure < 0", v[0]);
  sentinel(v, sizeof v);
  st = egw_flat_pressure_deriv(P(8, &p), D(9, 1e-3), P(10, &v[0]), P(11, &v[1]));
  out_doubles(st, 0, "pressure, dpressure", v, 2, sizeof v);
  sane(st, v[0] >= 0 && v[1] <= 0, "pressure < 0 or dpressure > 0", v[1]);
  return st;
}
static int r_flat_pressure_elastic(void) {
  egw_params p = params_at(0, EGW_MODEL_EGW, 0.0);
  double v[2];
  int st;
  sentinel(v, sizeof v);
  st = egw_flat_pressure_deriv(P(8, &p), D(9, -1e-3), P(10, &v[0]), P(11, &v[1]));
  out_doubles(st, 0, "pressure, dpressure", v, 2, sizeof v);
  sane(st, v[0] >= 0 && v[1] <= 0, "pressure < 0 or dpressure > 0", v[1]);
  return st;
}

static int r_flat_pressure_unload(void) {
  egw_params p = params_at(0, EGW_MODEL_EPGW, 0.5);
  double v[2];
  int st;
  sentinel(v, sizeof v);
  st = egw_flat_pressure_unload(P(8, &p), D(9, 1e-3), D(10, -1e-3), P(11, &v[0]),
                                P(12, &v[1]));
  out_doubles(st, 0, "pressure, dpressure", v, 2, sizeof v);
  sane(st, v[0] >= 0 && (cur->slot == 12 || v[1] <= 0), "pressure < 0 or dpressure > 0",
       v[1]);
  return st;
}

static int r_hertz(void) {
  egw_params p = params_at(0, EGW_MODEL_HERTZ, 0.0);
  double v[3];
  int st;
  sentinel(v, sizeof v);
  st = egw_hertz(P(8, &p), D(9, 1e-3), P(10, &v[0]), P(11, &v[1]), P(12, &v[2]));
  out_doubles(st, 0, "force, stiffness, a", v, 3, sizeof v);
  sane(st, v[0] >= 0 && v[1] >= 0 && v[2] >= 0, "negative Hertz output", v[0]);
  return st;
}

static void check_result(int st, const egw_result *r) {
  double d[6] = {r->force, r->stiffness, r->contact_radius, r->max_pressure, r->est_rel_err,
                 r->residual};
  if (st == EGW_OK) {
    out_doubles(st, 0, "res", d, 6, sizeof d);
    sane(st, r->force >= 0, "force < 0", r->force);
  } else {
    out_untouched(st, "*res", r, sizeof *r);
  }
}

static int r_solve(void) {
  egw_params p = params_at(0, EGW_MODEL_EGW, 0.0);
  egw_options o = options_at(9, 1e-4);
  egw_result r;
  int st;
  sentinel(&r, sizeof r);
  st = egw_solve(P(8, &p), P(14, &o), D(15, 2e-3), P(16, &r));
  check_result(st, &r);
  return st;
}
static int r_solve_epgw(void) {
  egw_params p = params_at(0, EGW_MODEL_EPGW, 0.5);
  egw_options o = options_at(9, 1e-4);
  egw_result r;
  int st;
  sentinel(&r, sizeof r);
  st = egw_solve(P(8, &p), P(14, &o), D(15, 2e-3), P(16, &r));
  check_result(st, &r);
  return st;
}

static int r_solve_unload(void) {
  egw_params p = params_at(0, EGW_MODEL_EPGW, 0.5);
  egw_options o = options_at(9, 1e-3);
  egw_result r;
  int st;
  sentinel(&r, sizeof r);
  st = egw_solve_unload(P(8, &p), P(14, &o), D(15, 2e-3), D(16, 4e-3), P(17, &r));
  check_result(st, &r);
  return st;
}

static int r_restitution(void) {
  egw_params p = params_at(0, EGW_MODEL_EPGW, 0.5);
  egw_options o = options_at(9, 1e-2);
  double v[3];
  int st;
  sentinel(v, sizeof v);
  st = egw_restitution_energy(P(8, &p), P(14, &o), D(15, 1e-3), D(16, 1e-2), P(17, &v[0]),
                              P(18, &v[1]), P(19, &v[2]));
  out_doubles(st, 0, "e, w_load, w_dissipated", v, 3, sizeof v);
  sane(st, cur->slot == 17 || (v[0] > 0 && v[0] <= 1), "e outside (0, 1]", v[0]);
  if (st == EGW_OK) { /* the plain form: the same coefficient */
    double e;
    sentinel(&e, sizeof e);
    st = egw_restitution(P(8, &p), P(14, &o), D(15, 1e-3), D(16, 1e-2), P(17, &e));
    out_doubles(st, 0, "e", &e, 1, sizeof e);
    sane(st, e == v[0] || cur->slot == 17, "egw_restitution differs from _energy", e);
  }
  return st;
}

static int r_restitution_overlap(void) {
  egw_params p = params_at(0, EGW_MODEL_EPGW, 0.5);
  egw_options o = options_at(9, 1e-2);
  double v[2];
  int st;
  sentinel(v, sizeof v);
  st = egw_restitution_overlap(P(8, &p), P(14, &o), D(15, 1e-3), D(16, 1e-2), P(17, &v[0]),
                               P(18, &v[1]));
  out_doubles(st, 0, "e, max_overlap", v, 2, sizeof v);
  sane(st, cur->slot == 17 || (v[0] > 0 && v[0] <= 1), "e outside (0, 1]", v[0]);
  sane(st, cur->slot == 18 || isfinite(v[1]), "max_overlap not finite", v[1]);
  return st;
}

static int r_time_step(void) {
  egw_params p = params_at(0, EGW_MODEL_EPGW, 0.5);
  egw_options o = options_at(9, 1e-2);
  double v[2];
  int st;
  sentinel(v, sizeof v);
  st = egw_time_step(P(8, &p), P(14, &o), D(15, 1e-3), D(16, 1e-2), D(17, 1e-3), P(18, &v[0]),
                     P(19, &v[1]));
  out_doubles(st, 0, "duration, time_step", v, 2, sizeof v);
  sane(st, cur->slot == 18 || v[0] > 0, "duration not > 0", v[0]);
  sane(st, cur->slot == 19 || (v[1] > 0 && (cur->slot == 18 || v[1] < v[0])),
       "time step not in (0, duration)", v[1]);
  return st;
}

/* the flow-pressure cap (Hertz, R = E* = 1, p_y = 2/pi: delta_y = 1, m* = 16/15: v_y = 1):
 * its own slots, p.flow_pressure among them */
#define CAP_SLOTS {"p.radius", K_DBL}, {"p.modulus", K_DBL}, {"p.flow_pressure", K_DBL}
static egw_params cap_params_at(int s) {
  egw_params p;
  egw_params_default(&p);
  p.model = EGW_MODEL_HERTZ;
  p.radius = D(s, 1.0);
  p.modulus = D(s + 1, 1.0);
  p.flow_pressure = D(s + 2, 2.0 / 3.141592653589793);
  return p;
}

static int r_first_yield(void) {
  egw_params p = cap_params_at(0);
  double v[2];
  int st;
  sentinel(v, sizeof v);
  st = egw_first_yield(P(3, &p), D(4, 16.0 / 15.0), P(5, &v[0]), P(6, &v[1]));
  out_doubles(st, 0, "delta_y, velocity_y", v, 2, sizeof v);
  sane(st, cur->slot == 5 || v[0] > 0, "delta_y not > 0", v[0]);
  sane(st, cur->slot == 6 || v[1] > 0, "velocity_y not > 0", v[1]);
  return st;
}

static int r_cap_solve_unload(void) {
  egw_params p = cap_params_at(0);
  egw_result r;
  int st;
  sentinel(&r, sizeof r);
  st = egw_solve_unload(P(3, &p), NULL, D(4, 4.0), D(5, 6.0), P(6, &r));
  check_result(st, &r);
  return st;
}

static int r_cap_restitution(void) {
  egw_params p = cap_params_at(0);
  double v[2];
  int st;
  sentinel(v, sizeof v);
  st = egw_time_step(P(3, &p), NULL, D(4, 16.0 / 15.0), D(5, 5.0), D(6, 1e-3), P(7, &v[0]),
                     P(8, &v[1]));
  out_doubles(st, 0, "duration, time_step", v, 2, sizeof v);
  sane(st, cur->slot == 7 || v[0] > 0, "duration not > 0", v[0]);
  sane(st, cur->slot == 8 || (v[1] > 0 && (cur->slot == 7 || v[1] < v[0])),
       "time step not in (0, duration)", v[1]);
  if (st == EGW_OK) {
    double e;
    sentinel(&e, sizeof e);
    st = egw_restitution(P(3, &p), NULL, D(4, 16.0 / 15.0), D(5, 5.0), &e);
    out_doubles(st, 0, "e", &e, 1, sizeof e);
    sane(st, e > 0 && e <= 1, "e outside (0, 1]", e);
  }
  return st;
}

/* a rough contact with the flow-pressure cap (GW by default; R = E* = 1, sigma = 1e-3,
 * mu = 2, p_y = 0.01: delta_y = 2.5e-4, the solve at 8 delta_y), fuzzing the fields the
 * cap's first-yield scales combine: a solve that succeeds at an overlap carries a force
 * > 0 (the summits touch) and a peak pressure at most p_y (flow_pressure = 1e-300 was
 * accepted and solved to force 0 before the scales were checked) */
#define ROUGH_CAP_SLOTS {"p.model", K_INT}, {"p.radius", K_DBL}, {"p.modulus", K_DBL}, \
    {"p.sigma", K_DBL}, {"p.flow_pressure", K_DBL}
static int r_rough_cap_solve(void) {
  egw_params p;
  egw_options o;
  egw_result r;
  double delta = D(6, 2e-3);
  int st;
  egw_params_default(&p);
  p.model = I(0, EGW_MODEL_GW);
  p.radius = D(1, 1.0);
  p.modulus = D(2, 1.0);
  p.sigma = D(3, 1e-3);
  p.mu = 2.0;
  p.flow_pressure = D(4, 0.01);
  egw_options_default(&o);
  o.rel_tol = 1e-3;
  sentinel(&r, sizeof r);
  st = egw_solve(P(5, &p), &o, delta, P(7, &r));
  check_result(st, &r);
  sane(st, !(delta > 0) || r.force > 0, "force not > 0 at an overlap", r.force);
  sane(st, !(p.flow_pressure > 0) || r.max_pressure <= p.flow_pressure * (1 + 1e-9),
       "max_pressure above p_y", r.max_pressure);
  return st;
}

/* array kernels (capi_array.f90): n and strides clamped to the arrays' sizes (beyond them
 * is the caller's undefined behaviour); outputs may be partly written on refusal
 * (egw.h), so only finiteness on success is checked */
static int clamp_count(int n, int max) { return n > max ? max : n; }
static int clamp_stride(int s) { return s > 1 ? 1 : s; }
static void array_out(int st, const char *name, const double *x, int n) {
  if (st != EGW_OK) return;
  for (int i = 0; i < n; i++)
    if (!isfinite(x[i])) {
      cur->silent = 1;
      note(" not finite", name, x[i]);
    }
}
static int r_hertz_array(void) {
  egw_params p = params_at(0, EGW_MODEL_HERTZ, 0.0);
  double d[3] = {-1e-3, D(11, 1e-3), 2e-3}, f[3], k[3], a[3];
  int n = clamp_count(I(10, 3), 3), nf = 0, st;
  sentinel(f, sizeof f);
  st = egw_hertz_array(P(8, &p), clamp_stride(I(9, 0)), n, P(12, d), clamp_stride(I(13, 1)),
                       P(14, f), P(15, k), P(16, a), I(17, EGW_ARRAY_RAISE), P(18, &nf));
  if (cur->slot != 14 && cur->slot != 17) array_out(st, "force", f, n > 0 ? n : 0);
  return st;
}
static int r_flat_pressure_array(void) {
  egw_params p = params_at(0, EGW_MODEL_EPGW, 0.5);
  double d[3] = {-1e-3, D(11, 1e-3), 2e-3}, dm[1] = {D(14, 0.0)}, pr[3], dp[3];
  int n = clamp_count(I(10, 3), 3), st;
  sentinel(pr, sizeof pr);
  st = egw_flat_pressure_unload_array(P(8, &p), clamp_stride(I(9, 0)), n, P(12, d),
                                      clamp_stride(I(13, 1)), P(15, dm), 0, P(16, pr),
                                      P(17, dp), I(18, EGW_ARRAY_RAISE), NULL);
  if (cur->slot != 16 && cur->slot != 18) array_out(st, "pressure", pr, n > 0 ? n : 0);
  return st;
}
static int r_solve_array(void) {
  egw_params p = params_at(0, EGW_MODEL_EPGW, 0.5);
  egw_options o = options_at(9, 1e-3);
  double d[2] = {D(15, 2e-3), 1e-3}, dm[1] = {D(16, 4e-3)};
  egw_result r[2];
  int n = clamp_count(I(17, 2), 2), st;
  sentinel(r, sizeof r);
  st = egw_solve_array(P(8, &p), 0, P(14, &o), n, d, 1, P(18, dm), 0, P(19, r),
                       I(20, EGW_ARRAY_RAISE), NULL);
  if (cur->slot != 20)
    for (int i = 0; i < (n > 0 ? n : 0); i++) array_out(st, "res.force", &r[i].force, 1);
  return st;
}
static int r_restitution_array(void) {
  egw_params p = params_at(0, EGW_MODEL_EPGW, 0.5);
  egw_options o = options_at(9, 1e-2);
  double m[1] = {D(15, 1e-3)}, v[2] = {D(16, 1e-2), 2e-2}, e[2], dm[2];
  int n = clamp_count(I(17, 2), 2), st;
  sentinel(e, sizeof e);
  st = egw_restitution_array(P(8, &p), 0, P(14, &o), n, P(18, m), 0, v, 1, P(19, e), NULL,
                             NULL, dm, I(20, EGW_ARRAY_RAISE), NULL);
  if (cur->slot != 19 && cur->slot != 20) array_out(st, "e", e, n > 0 ? n : 0);
  return st;
}
static int r_time_step_array(void) {
  egw_params p = params_at(0, EGW_MODEL_EPGW, 0.5);
  egw_options o = options_at(9, 1e-2);
  double m[1] = {D(15, 1e-3)}, v[1] = {D(16, 1e-2)}, tc[1], dt[1];
  int st;
  sentinel(dt, sizeof dt);
  st = egw_time_step_array(P(8, &p), 0, P(14, &o), 1, m, 0, v, 0, D(17, 1e-3), tc, P(18, dt),
                           I(19, EGW_ARRAY_RAISE), NULL);
  if (cur->slot != 18 && cur->slot != 19) array_out(st, "time_step", dt, 1);
  return st;
}

static int r_profile(void) {
  egw_params p = params_at(0, EGW_MODEL_EGW, 0.0);
  egw_options o = options_at(9, 1e-3);
  double r[3] = {0.0, 0.03, 0.1}, pr[3], w[3];
  int st, n = I(16, 3);
  if (n > 3 || n < 0) n = n < 0 ? n : 3;
  sentinel(pr, sizeof pr);
  sentinel(w, sizeof w);
  r[1] = D(17, 0.03);
  st = egw_profile(P(8, &p), P(14, &o), D(15, 2e-3), n, P(18, r), P(19, pr), P(20, w));
  out_doubles(st, 0, "pressure", pr, n > 0 ? n : 0, sizeof pr);
  out_doubles(st, 0, "deflection", w, n > 0 ? n : 0, sizeof w);
  return st;
}

/* a rough-flat law from a 3-node table (n clamped to the arrays' size), evaluated */
static int r_flat_law(void) {
  double u[3] = {0.0, 1e-6, 2e-6}, p[3] = {1e6, 3e5, 1e5}, a[3] = {0.3, 0.1, 0.02}, v[3];
  egw_flat_law law;
  int st, n = I(6, 3);
  if (n > 3) n = 3;
  u[1] = D(0, 1e-6);
  p[1] = D(1, 3e5);
  a[1] = D(2, 0.1);
  sentinel(&law, sizeof law);
  st = egw_flat_law_from_table(P(3, u), P(4, p), NULL, P(5, a), n, D(7, 0.0), D(8, 1e9),
                               P(9, &law));
  out_untouched(st, "*out", &law, sizeof law);
  if (st != EGW_OK) return st;
  sentinel(v, sizeof v);
  st = egw_flat_law_pressure(law, D(10, 1.5e-6), &v[0], &v[1]);
  out_doubles(st, 0, "pressure, dpdu", v, 2, 2 * sizeof *v);
  sane(st, v[0] >= 0 && v[1] <= 0, "pressure < 0 or dp/du > 0", v[0]);
  if (egw_flat_law_contact_area(law, D(10, 1.5e-6), &v[2]) == EGW_OK)
    sane(EGW_OK, v[2] >= 0 && v[2] <= 1, "contact area outside [0, 1]", v[2]);
  egw_flat_law_free(&law);
  return st;
}

/* the sphere solve with an exponential flat law (length 1e-6 m, E* of p) */
static int r_solve_flat_law(void) {
  egw_params p = params_at(0, EGW_MODEL_EGW, 0.0);
  egw_options o = options_at(9, 1e-4);
  double u[2] = {0.0, 3e-6}, pr[2] = {1e7, 1e7 * exp(-3.0)};
  egw_flat_law law = NULL;
  egw_result r;
  int st;
  if (egw_flat_law_from_table(u, pr, NULL, NULL, 2, 0.0, 0.0, &law) != EGW_OK) return -1;
  sentinel(&r, sizeof r);
  st = egw_solve_flat_law(P(8, &p), P(15, law), P(14, &o), D(16, 1e-6), P(17, &r));
  check_result(st, &r);
  egw_flat_law_free(&law);
  return st;
}
static int r_table_build_flat_law(void) {
  egw_params p = params_at(0, EGW_MODEL_EGW, 0.0);
  egw_options o = options_at(9, 1e-3);
  double u[2] = {0.0, 3e-6}, pr[2] = {1e7, 1e7 * exp(-3.0)};
  egw_flat_law law = NULL;
  egw_table t;
  int st;
  if (egw_flat_law_from_table(u, pr, NULL, NULL, 2, 0.0, 0.0, &law) != EGW_OK) return -1;
  sentinel(&t, sizeof t);
  st = egw_table_build_flat_law(P(8, &p), P(15, law), P(14, &o), D(16, -3e-6), D(17, 2e-6),
                                D(18, 1e-3), P(19, &t));
  out_untouched(st, "*out", &t, sizeof t);
  if (st == EGW_OK) {
    double f = -1.0, k = -1.0;
    egw_table_eval(t, 0.0, &f, &k);
    sane(st, isfinite(f) && isfinite(k) && f >= 0, "flat-law table force at 0", f);
    egw_table_free(&t);
  }
  egw_flat_law_free(&law);
  return st;
}

static int r_table_build(void) {
  egw_params p = params_at(0, EGW_MODEL_EGW, 0.0);
  egw_options o = options_at(9, 1e-3);
  egw_table t;
  int st;
  sentinel(&t, sizeof t);
  st = egw_table_build(P(8, &p), P(14, &o), D(15, -2e-3), D(16, 1e-2), D(17, 1e-2),
                       P(18, &t));
  out_untouched(st, "*out", &t, sizeof t);
  if (st == EGW_OK) {
    double f, k;
    egw_table_info info;
    if (egw_table_get_info(t, &info) != EGW_OK || !isfinite(info.cutoff) ||
        !isfinite(info.delta_max) || !isfinite(info.reference_force)) {
      cur->silent = 1;
      note("", "table info not finite", 0.0);
    }
    egw_table_eval(t, info.delta_max, &f, &k);
    sane(st, isfinite(f) && isfinite(k) && f >= 0, "table force at delta_max", f);
    egw_table_free(&t);
  }
  return st;
}
static int r_table_build_epgw(void) {
  egw_params p = params_at(0, EGW_MODEL_EPGW, 0.5);
  egw_options o = options_at(9, 1e-3);
  egw_table t;
  int st;
  sentinel(&t, sizeof t);
  st = egw_table_build(P(8, &p), P(14, &o), D(15, -2e-3), D(16, 1e-2), D(17, 1e-2),
                       P(18, &t));
  out_untouched(st, "*out", &t, sizeof t);
  if (st == EGW_OK) egw_table_free(&t);
  return st;
}

static int r_table_eval(void) {
  egw_table t = base_table();
  double v[4], d = D(1, 5e-3);
  int st;
  sentinel(v, sizeof v);
  st = egw_table_eval(P(0, t), d, P(2, &v[0]), P(3, &v[1]));
  out_doubles(st, EGW_OUT_OF_RANGE, "force, stiffness", v, 2, 2 * sizeof *v);
  sane(st, v[0] >= 0 && v[1] >= 0, "negative table output", v[0]);
  sentinel(v, sizeof v);
  st = egw_table_eval_all(P(0, t), d, P(2, &v[0]), P(3, &v[1]), P(4, &v[2]), P(5, &v[3]));
  out_doubles(st, EGW_OUT_OF_RANGE, "force, stiffness, energy, a", v, 4, sizeof v);
  egw_table_free(&t);
  return st;
}

static int r_table_eval_array(void) {
  egw_table t = base_table();
  double d[3] = {-1e-3, D(1, 5e-3), 1e-2}, f[3], k[3];
  int n = I(2, 3), st;
  if (n > 3) n = 3;
  sentinel(f, sizeof f);
  sentinel(k, sizeof k);
  st = egw_table_eval_array(P(0, t), n, P(3, d), P(4, f), P(5, k));
  out_doubles(st, EGW_OUT_OF_RANGE, "force", f, n > 0 ? n : 0, sizeof f);
  out_doubles(st, EGW_OUT_OF_RANGE, "stiffness", k, n > 0 ? n : 0, sizeof k);
  egw_table_free(&t);
  return st;
}

static int r_table_info_radii(void) {
  egw_table t = base_table();
  egw_table_info info;
  int st;
  sentinel(&info, sizeof info);
  st = egw_table_get_info(P(0, t), P(1, &info));
  out_untouched(st, "info", &info, sizeof info);
  if (st == EGW_OK) {
    double d[6] = {info.cutoff, info.delta_max, info.reference_force, info.rel_tol,
                   info.max_force_error, info.max_stiffness_error};
    out_doubles(st, 0, "info", d, 6, sizeof d);
  }
  st = egw_table_set_radii(P(0, t), D(2, 2.0), D(3, 2.0));
  egw_table_free(&t);
  return st;
}

/* egw_table_get_interpolant: capacity fuzzed (arrays of 4096 nodes passed, never fewer
 * than the capacity says), every pointer NULL in turn; written: finite, ascending nodes */
static int r_table_interpolant(void) {
  egw_table t = base_table();
  static double nodes[4096], coeffs[4 * 4096];
  int n_log, st, cap = I(1, 4096);
  if (cap > 4096) cap = 4096;   /* the arrays' size: a larger one is the caller's UB */
  sentinel(nodes, sizeof nodes);
  sentinel(coeffs, sizeof coeffs);
  sentinel(&n_log, sizeof n_log);
  st = egw_table_get_interpolant(P(0, t), cap, P(2, nodes), P(3, coeffs), P(4, &n_log));
  if (st == EGW_OK) {
    egw_table_info info;
    egw_table_get_info(t, &info);
    out_doubles(st, 0, "nodes", nodes, info.n_nodes, 0);
    out_doubles(st, 0, "coeffs", coeffs, 4 * (info.n_nodes - 1), 0);
    for (int i = 0; i + 1 < info.n_nodes; i++)
      sane(st, nodes[i] < nodes[i + 1], "nodes not ascending", nodes[i]);
    sane(st, n_log >= 0 && n_log < info.n_nodes, "n_log out of range", n_log);
  } else {
    out_untouched(st, "nodes", nodes, sizeof nodes);
    out_untouched(st, "coeffs", coeffs, sizeof coeffs);
    out_untouched(st, "n_log", &n_log, sizeof n_log);
  }
  egw_table_free(&t);
  return st;
}

/* egw_table_get_tail: n (the base table once or twice) and capacity fuzzed (arrays of 8192
 * pieces passed, never fewer than the capacity says), every pointer NULL in turn; written:
 * a count in [16, 8192] and, with a capacity, finite ascending starts and finite cubics */
static int r_table_tail(void) {
  egw_table t[2];
  static double starts[8193], coeffs[8 * 8192];
  int n_pieces, st, n = I(0, 1), cap = I(2, 8192);
  if (n > 2) n = 2;          /* a count above the array's length is the caller's lie */
  if (cap > 8192) cap = 8192; /* the arrays' size: a larger one is the caller's UB */
  t[0] = base_table();
  t[1] = base_table();
  sentinel(starts, sizeof starts);
  sentinel(coeffs, sizeof coeffs);
  sentinel(&n_pieces, sizeof n_pieces);
  st = egw_table_get_tail(n, P(1, t), cap, P(3, starts), P(4, coeffs), P(5, &n_pieces));
  if (st == EGW_OK) {
    sane(st, n_pieces >= 16 && n_pieces <= 8192, "n_pieces out of range", n_pieces);
    if (cap > 0 && n_pieces >= 16 && n_pieces <= 8192) {
      out_doubles(st, 0, "starts", starts, n_pieces + 1, 0);
      out_doubles(st, 0, "coeffs", coeffs, 4 * n * n_pieces, 0);
      for (int q = 0; q < n_pieces; q++)
        sane(st, starts[q] < starts[q + 1], "starts not ascending", starts[q]);
    } else {
      out_untouched(EGW_INVALID_ARGUMENT, "starts", starts, sizeof starts);
      out_untouched(EGW_INVALID_ARGUMENT, "coeffs", coeffs, sizeof coeffs);
    }
  } else {
    out_untouched(st, "starts", starts, sizeof starts);
    out_untouched(st, "coeffs", coeffs, sizeof coeffs);
    out_untouched(st, "n_pieces", &n_pieces, sizeof n_pieces);
  }
  egw_table_free(&t[0]);
  egw_table_free(&t[1]);
  return st;
}

static int r_table_write(void) {
  egw_table t = base_table();
  double err;
  int st, fmt = I(2, EGW_FORMAT_CSV);
  const char *path = S(1, out_path("w.csv"));
  sentinel(&err, sizeof err);
  st = egw_table_write(P(0, t), path, fmt);
  if (st == EGW_OK) {
    egw_table back = NULL;
    if ((fmt == EGW_FORMAT_CSV || fmt == EGW_FORMAT_BINARY) && egw_table_read(path, &back) != EGW_OK) {
      cur->silent = 1;
      note("", "written table does not read back", 0.0);
    }
    egw_table_free(&back);
  }
  if (st == EGW_OK) {
    st = egw_table_write_calculix(P(0, t), S(1, out_path("w.inp")), I(2, 1), P(3, &err));
    out_doubles(st, 0, "max_error", &err, 1, sizeof err);
  }
  egw_table_free(&t);
  return st;
}

static int r_tables_lammps(void) {
  egw_table t[2];
  int st;
  int n = I(0, 2);
  if (n > 2) n = 2; /* a count above the array's length is the caller's lie (UB in C) */
  t[0] = base_table();
  t[1] = base_table();
  st = egw_tables_write_lammps(n, P(1, t), S(2, out_path("w.table")));
  if (st == EGW_OK)
    st = egw_tables_write_lammps_units(n, P(1, t), S(2, out_path("u.table")), S(3, "si"));
  egw_table_free(&t[0]);
  egw_table_free(&t[1]);
  return st;
}

static int r_table_read(void) {
  egw_table t;
  int st;
  sentinel(&t, sizeof t);
  st = egw_table_read(S(0, table_path), P(1, &t));
  out_untouched(st, "*out", &t, sizeof t);
  if (st == EGW_OK) egw_table_free(&t);
  egw_table_free(NULL);
  return st;
}

/* Persson's law of a two-node power-law PSD, n clamped to the arrays */
static int r_flat_law_psd(void) {
  double q[2] = {1e4, 1e6}, c[2] = {1e-24, 1e-24 * pow(100.0, -3.6)};
  egw_flat_law law;
  int st, n = I(2, 2);
  if (n > 2) n = 2;
  q[1] = D(0, 1e6);
  c[1] = D(1, c[1]);
  sentinel(&law, sizeof law);
  st = egw_flat_law_from_psd(P(3, q), P(4, c), n, D(5, 1e9), D(6, 0.0), D(7, 0.0),
                             P(8, &law));
  out_untouched(st, "*out", &law, sizeof law);
  if (st == EGW_OK) {
    double v[2];
    int s2 = egw_flat_law_pressure(law, 1e-7, &v[0], &v[1]);
    sane(s2, isfinite(v[0]) && v[0] >= 0 && v[1] <= 0, "Persson pressure", v[0]);
    egw_flat_law_free(&law);
  }
  return st;
}

/* the BEM law of an 8 x 8 map (a cosine bump), nx and ny clamped to the array */
static int r_flat_law_heights(void) {
  double h[64];
  egw_flat_law law;
  int st, nx = I(1, 8), ny = I(2, 8);
  for (int i = 0; i < 64; i++) h[i] = 1e-7 * cos(0.785398 * (i % 8)) * cos(0.785398 * (i / 8));
  h[9] = D(0, h[9]);
  if (nx > 8) nx = 8;
  if (ny > 8) ny = 8;
  sentinel(&law, sizeof law);
  st = egw_flat_law_from_heights(P(3, h), nx, ny, D(4, 1e-6), D(5, 1e9), D(6, 0.0),
                                 D(7, 0.0), NULL, P(8, &law));
  out_untouched(st, "*out", &law, sizeof law);
  if (st == EGW_OK) egw_flat_law_free(&law);
  return st;
}

/* a law in other units */
static int r_flat_law_rescale(void) {
  double u[2] = {0.0, 1e-6}, p[2] = {1.0, 0.5};
  egw_flat_law law = NULL, out;
  int st;
  if (egw_flat_law_from_table(u, p, NULL, NULL, 2, 0.0, 0.0, &law) != EGW_OK) return -1;
  sentinel(&out, sizeof out);
  st = egw_flat_law_rescale(P(0, law), D(1, 1e-6), D(2, 1.0), P(3, &out));
  out_untouched(st, "*out", &out, sizeof out);
  if (st == EGW_OK) {
    /* probed inside its nodes: far beyond them (u = 0.5 after unit_length = 1e100 put
     * the last node at 1e-106) the continuation's pressure is 0, rightly */
    double v[2], u_max = 0.0;
    int s2 = egw_flat_law_info(out, NULL, NULL, NULL, NULL, &u_max, NULL);
    if (s2 == EGW_OK) s2 = egw_flat_law_pressure(out, 0.5 * u_max, &v[0], &v[1]);
    sane(s2, isfinite(v[0]) && v[0] > 0 && v[1] <= 0, "rescaled pressure", v[0]);
    egw_flat_law_free(&out);
  }
  egw_flat_law_free(&law);
  return st;
}

/* a law written (path fuzzed) and read back (its file's path fuzzed too) */
static int r_flat_law_file(void) {
  double u[2] = {0.0, 1e-6}, p[2] = {1.0, 0.5};
  egw_flat_law law = NULL, back;
  const char *path = S(1, out_path("law.csv"));
  int st;
  if (egw_flat_law_from_table(u, p, NULL, NULL, 2, 0.0, 0.0, &law) != EGW_OK) return -1;
  st = egw_flat_law_write(P(0, law), path);
  if (st == EGW_OK) {
    sentinel(&back, sizeof back);
    st = egw_flat_law_read(S(2, path), P(3, &back));
    out_untouched(st, "*out", &back, sizeof back);
    if (st == EGW_OK) egw_flat_law_free(&back);
  }
  egw_flat_law_free(&law);
  return st;
}

static int r_flat_calculix(void) {
  egw_params p = params_at(0, EGW_MODEL_EPGW, 0.5);
  double err;
  int st;
  sentinel(&err, sizeof err);
  st = egw_write_flat_calculix_shifted(P(8, &p), D(9, 3e-3), D(10, 1e-3), I(11, 1),
                                       S(12, out_path("flat.inp")), P(13, &err));
  out_doubles(st, 0, "max_error", &err, 1, sizeof err);
  if (st == EGW_OK) st = egw_write_flat_calculix(P(8, &p), D(9, 3e-3), D(10, 1e-3),
                                                 S(12, out_path("flat2.inp")));
  return st;
}

static int r_universal_build(void) {
  egw_params p = params_at(0, EGW_MODEL_EGW, 0.0);
  egw_options o = options_at(9, 1e-3);
  egw_universal u;
  int st;
  sentinel(&u, sizeof u);
  st = egw_universal_build(P(8, &p), P(14, &o), D(15, 1.0), D(16, 4.0), D(17, -2.0),
                           D(18, 10.0), D(19, 3e-2), P(20, &u));
  out_untouched(st, "*out", &u, sizeof u);
  if (st == EGW_OK) egw_universal_free(&u);
  return st;
}

static int r_universal_eval(void) {
  egw_universal u = base_universal();
  egw_params p = params_at(0, EGW_MODEL_EGW, 0.0);
  double v[2];
  int st;
  sentinel(v, sizeof v);
  st = egw_universal_eval(P(8, u), P(9, &p), D(10, 3e-3), P(11, &v[0]), P(12, &v[1]));
  out_doubles(st, EGW_OUT_OF_RANGE, "force, stiffness", v, 2, sizeof v);
  sane(st, v[0] >= 0 && v[1] >= 0, "negative universal output", v[0]);
  egw_universal_free(&u);
  return st;
}

static int r_universal_eval_array(void) {
  egw_universal u = base_universal();
  egw_params p = params_at(0, EGW_MODEL_EGW, 0.0);
  double d[2] = {D(11, 3e-3), 1e-3}, f[2], k[2];
  int n = clamp_count(I(10, 2), 2), st;
  sentinel(f, sizeof f);
  st = egw_universal_eval_array(P(8, u), P(9, &p), 0, n, d, 1, P(12, f), P(13, k),
                                I(14, EGW_ARRAY_RAISE), NULL);
  if (cur->slot != 12 && cur->slot != 14) array_out(st, "force", f, n > 0 ? n : 0);
  egw_universal_free(&u);
  return st;
}

static int r_universal_slice(void) {
  egw_universal u = base_universal();
  egw_params p = params_at(0, EGW_MODEL_EGW, 0.0);
  egw_table t;
  int st;
  sentinel(&t, sizeof t);
  st = egw_universal_slice_range(P(8, u), P(9, &p), D(10, 5e-3), P(11, &t));
  out_untouched(st, "*out", &t, sizeof t);
  if (st == EGW_OK) egw_table_free(&t);
  sentinel(&t, sizeof t);
  if (st == EGW_OK) {
    st = egw_universal_slice(P(8, u), P(9, &p), P(11, &t));
    out_untouched(st, "*out", &t, sizeof t);
    if (st == EGW_OK) egw_table_free(&t);
  }
  egw_universal_free(&u);
  return st;
}

static int r_universal_io(void) {
  egw_universal u = base_universal(), back;
  int st;
  st = egw_universal_write(P(0, u), S(1, out_path("u.csv")), I(2, EGW_FORMAT_CSV));
  sentinel(&back, sizeof back);
  if (st == EGW_OK) {
    st = egw_universal_read(S(1, out_path("u.csv")), P(3, &back));
    out_untouched(st, "*out", &back, sizeof back);
    if (st == EGW_OK) egw_universal_free(&back);
  }
  egw_universal_free(&u);
  egw_universal_free(NULL);
  return st;
}

static int r_hysteresis(void) {
  egw_params p = params_at(0, EGW_MODEL_EPGW, 0.5);
  egw_options o = options_at(9, 1e-3);
  egw_hysteresis h;
  int st;
  sentinel(&h, sizeof h);
  st = egw_hysteresis_build(P(8, &p), P(14, &o), D(15, -1e-3), D(16, 4e-3), D(17, 5e-2),
                            P(18, &h));
  out_untouched(st, "*out", &h, sizeof h);
  if (st == EGW_OK) egw_hysteresis_free(&h);
  egw_hysteresis_free(NULL);
  return st;
}

static int r_hysteresis_eval(void) {
  egw_params p = params_at(100, EGW_MODEL_EPGW, 0.5); /* slots >= 100: never fuzzed */
  egw_options o = options_at(100, 1e-3);
  egw_hysteresis h = NULL;
  double state, v[2];
  int st;
  if (egw_hysteresis_build(&p, &o, -1e-3, 4e-3, 5e-2, &h) != EGW_OK) _exit(3);
  state = D(1, 3e-3);
  sentinel(v, sizeof v);
  st = egw_hysteresis_eval(P(0, h), D(2, 2e-3), P(3, &state), P(4, &v[0]), P(5, &v[1]));
  out_doubles(st, EGW_OUT_OF_RANGE, "force, stiffness", v, 2, sizeof v);
  sane(st, v[0] >= 0, "negative hysteresis force", v[0]);
  if (st == EGW_OK && !isfinite(state)) {
    cur->silent = 1;
    note(" not finite", "state", state);
  }
  egw_hysteresis_free(&h);
  return st;
}

/* the state API: state[0] and every cache entry fuzzed (garbage caches must be ignored) */
static int r_hysteresis_eval_state(void) {
  egw_params p = params_at(100, EGW_MODEL_EPGW, 0.5); /* slots >= 100: never fuzzed */
  egw_options o = options_at(100, 1e-3);
  egw_hysteresis h = NULL;
  double state[EGW_HYSTERESIS_STATE_SIZE], v[2], m0;
  int st;
  if (egw_hysteresis_build(&p, &o, -1e-3, 4e-3, 5e-2, &h) != EGW_OK) _exit(3);
  egw_hysteresis_state_init(state);
  egw_hysteresis_eval_state(h, 3e-3, state, &v[0], &v[1]); /* loaded to 3e-3, ... */
  egw_hysteresis_eval_state(h, 2e-3, state, &v[0], &v[1]); /* a valid cache ... */
  for (int i = 1; i < EGW_HYSTERESIS_STATE_SIZE; i++)      /* ... or garbage */
    state[i] = D(3, state[i]);
  state[0] = D(1, 3e-3);
  m0 = state[0];
  sentinel(v, sizeof v);
  st = egw_hysteresis_eval_state(P(0, h), D(2, 2e-3), P(4, state), P(5, &v[0]), P(6, &v[1]));
  out_doubles(st, EGW_OUT_OF_RANGE, "force, stiffness", v, 2, sizeof v);
  sane(st, v[0] >= 0, "negative hysteresis force", v[0]);
  if (st != EGW_OK && st != EGW_OUT_OF_RANGE && memcmp(&m0, &state[0], sizeof m0) != 0) {
    cur->clobbered = 1;
    note(" changed on refusal", "state[0]", state[0]);
  }
  if (st == EGW_OK && !isfinite(state[0])) {
    cur->silent = 1;
    note(" not finite", "state[0]", state[0]);
  }
  if (st == EGW_OK && cur->slot == 3) { /* garbage caches: a new contact, never a wrong force */
    double plain = -HUGE_VAL, f;
    egw_hysteresis_eval(h, 2e-3, &plain, &f, NULL);
    sane(st, v[0] == f, "a garbage state not read as a new contact", v[0]);
  }
  egw_hysteresis_state_init(P(4, state));
  egw_hysteresis_free(&h);
  return st;
}

/* egw.h's inline egw_hysteresis_eval_cached with its tag (egw_hysteresis_state_tag):
 * state[0], delta, every cache entry and the tag fuzzed; a step it serves must give
 * exactly what egw_hysteresis_eval_state gives (values and state), never a value that call
 * refuses; state and tag pointers are not optional for the inline step (not fuzzed) */
static int r_hysteresis_eval_cached(void) {
  egw_params p = params_at(100, EGW_MODEL_EPGW, 0.5); /* slots >= 100: never fuzzed */
  egw_options o = options_at(100, 1e-3);
  egw_hysteresis h = NULL;
  double state[EGW_HYSTERESIS_STATE_SIZE], a[EGW_HYSTERESIS_STATE_SIZE];
  double b[EGW_HYSTERESIS_STATE_SIZE], tag = 0.0, fa = NAN, ka = NAN, fb = NAN, kb = NAN, d;
  int st, hit;
  if (egw_hysteresis_build(&p, &o, -1e-3, 4e-3, 5e-2, &h) != EGW_OK) _exit(3);
  st = egw_hysteresis_state_tag(P(0, h), &tag);
  if (st != EGW_OK) {
    egw_hysteresis_free(&h);
    return st;
  }
  egw_hysteresis_state_init(state);
  egw_hysteresis_eval_state(h, 3e-3, state, &fa, &ka); /* loaded to 3e-3, ... */
  egw_hysteresis_eval_state(h, 2e-3, state, &fa, &ka); /* a valid cache ... */
  for (int i = 1; i < EGW_HYSTERESIS_STATE_SIZE; i++)  /* ... or garbage */
    state[i] = D(3, state[i]);
  state[0] = D(1, 3e-3);
  d = D(2, 2.1e-3);
  tag = D(4, tag);
  memcpy(a, state, sizeof a);
  memcpy(b, state, sizeof b);
  hit = egw_hysteresis_eval_cached(tag, d, a, &fa, &ka);
  st = egw_hysteresis_eval_state(h, d, b, &fb, &kb);
  if (hit && st != EGW_OK && st != EGW_OUT_OF_RANGE) {
    cur->silent = 1;
    note(" served a step egw_hysteresis_eval_state refuses", "delta", d);
  } else if (hit && !(fa == fb && ka == kb && memcmp(a, b, sizeof a) == 0)) {
    cur->silent = 1;
    note(" differs from egw_hysteresis_eval_state", "force", fa);
  } else if (!hit && memcmp(a, state, sizeof a) != 0) {
    cur->clobbered = 1;
    note(" changed the state without serving", "state[0]", a[0]);
  }
  egw_hysteresis_free(&h);
  return hit ? EGW_OK : st;
}

static int r_hysteresis_energy(void) {
  egw_params p = params_at(100, EGW_MODEL_EPGW, 0.5); /* slots >= 100: never fuzzed */
  egw_options o = options_at(100, 1e-3);
  egw_hysteresis h = NULL;
  double u;
  int st;
  if (egw_hysteresis_build(&p, &o, -1e-3, 4e-3, 5e-2, &h) != EGW_OK) _exit(3);
  sentinel(&u, sizeof u);
  st = egw_hysteresis_energy(P(0, h), D(2, 2e-3), D(1, 3e-3), P(3, &u));
  out_doubles(st, EGW_OUT_OF_RANGE, "energy", &u, 1, sizeof u);
  sane(st, u >= 0, "negative energy", u);
  egw_hysteresis_free(&h);
  return st;
}

static int r_hysteresis_eval_array(void) {
  egw_params p = params_at(100, EGW_MODEL_EPGW, 0.5); /* slots >= 100: never fuzzed */
  egw_options o = options_at(100, 1e-3);
  egw_hysteresis h = NULL;
  double d[3] = {2e-3, D(2, 2.5e-3), -1e-3}, state[3] = {3e-3, D(1, 3e-3), 3e-3};
  double state0[3], f[3], k[3];
  int n = I(3, 3), st;
  if (n > 3) n = 3;
  if (egw_hysteresis_build(&p, &o, -1e-3, 4e-3, 5e-2, &h) != EGW_OK) _exit(3);
  memcpy(state0, state, sizeof state);
  sentinel(f, sizeof f);
  sentinel(k, sizeof k);
  st = egw_hysteresis_eval_array(P(0, h), n, P(4, d), P(5, state), P(6, f), P(7, k));
  out_doubles(st, EGW_OUT_OF_RANGE, "force", f, n > 0 ? n : 0, sizeof f);
  out_doubles(st, EGW_OUT_OF_RANGE, "stiffness", k, n > 0 ? n : 0, sizeof k);
  if (st != EGW_OK && st != EGW_OUT_OF_RANGE && memcmp(state0, state, sizeof state) != 0) {
    cur->clobbered = 1;
    note(" changed on refusal", "delta_max_state", state[0]);
  }
  egw_hysteresis_free(&h);
  return st;
}

static int r_hysteresis_io(void) {
  egw_params p = params_at(100, EGW_MODEL_EPGW, 0.5);
  egw_options o = options_at(100, 1e-3);
  egw_hysteresis h = NULL, back;
  egw_hysteresis_info info;
  int st, st2;
  if (egw_hysteresis_build(&p, &o, -1e-3, 4e-3, 5e-2, &h) != EGW_OK) _exit(3);
  sentinel(&info, sizeof info);
  st2 = egw_hysteresis_get_info(P(0, h), P(4, &info));
  out_untouched(st2, "info", &info, sizeof info);
  if (st2 == EGW_OK) {
    double v[5] = {info.cutoff, info.delta_max, info.reference_force, info.rel_tol,
                   info.max_error};
    out_doubles(st2, 0, "info", v, 5, sizeof v);
    sane(st2, info.reference_force > 0.0 && info.cutoff < info.delta_max,
         "info.reference_force > 0, cutoff < delta_max", info.reference_force);
  }
  st = egw_hysteresis_write(P(0, h), S(1, out_path("h.csv")), I(2, EGW_FORMAT_CSV));
  sentinel(&back, sizeof back);
  if (st == EGW_OK) {
    st = egw_hysteresis_read(S(1, out_path("h.csv")), P(3, &back));
    out_untouched(st, "*out", &back, sizeof back);
    if (st == EGW_OK) egw_hysteresis_free(&back);
  }
  egw_hysteresis_free(&h);
  return st != EGW_OK ? st : st2;
}

/* scene slots: 0 model, 1 n_types, 2 radius[0], 3 radius[1], 4 radius_min, 5 radius_max,
 * 6 modulus[0], 7 poisson[0], 8 effective_modulus, 9 sigma_min, 10 sigma_max, 11 mu,
 * 12 summit_density, 13 summit_radius, 14 psi, 15 K, 16 rho_p, 17 delta_min,
 * 18 delta_max, 19 delta_in_sigma, 20 tol */
static egw_scene scene_at(int model) {
  egw_scene s;
  egw_scene_default(&s);
  s.model = I(0, model);
  s.n_types = I(1, 2);
  s.radius[0] = D(2, 1e-3);
  s.radius[1] = D(3, 2e-3);
  s.modulus[1] = 0.0;
  s.poisson[1] = 0.0;
  s.radius_min = D(4, 1e-3);
  s.radius_max = D(5, 2e-3);
  s.modulus[0] = D(6, 70e9);
  s.poisson[0] = D(7, 0.22);
  s.effective_modulus = D(8, 0.0);
  s.sigma_min = D(9, 1e-6);
  s.sigma_max = D(10, 2e-6);
  s.mu = D(11, 4.0);
  s.summit_density = D(12, 0.0);
  s.summit_radius = D(13, 0.0);
  s.psi = D(14, model == EGW_MODEL_EPGW ? 0.5 : 0.0);
  s.hardness_coeff = D(15, 0.6);
  s.plastic_ratio = D(16, 54.0);
  s.delta_min = D(17, -2.0);
  s.delta_max = D(18, 10.0);
  s.delta_in_sigma = I(19, 1);
  s.tol = D(20, 1e-2);
  return s;
}
#define SCENE_SLOTS                                                                      \
  {"s.model", K_INT}, {"s.n_types", K_INT}, {"s.radius[0]", K_DBL}, {"s.radius[1]", K_DBL}, \
      {"s.radius_min", K_DBL}, {"s.radius_max", K_DBL}, {"s.modulus[0]", K_DBL},             \
      {"s.poisson[0]", K_DBL}, {"s.effective_modulus", K_DBL}, {"s.sigma_min", K_DBL},       \
      {"s.sigma_max", K_DBL}, {"s.mu", K_DBL}, {"s.summit_density", K_DBL},                  \
      {"s.summit_radius", K_DBL}, {"s.psi", K_DBL}, {"s.hardness_coeff", K_DBL},             \
      {"s.plastic_ratio", K_DBL}, {"s.delta_min", K_DBL}, {"s.delta_max", K_DBL},            \
      {"s.delta_in_sigma", K_INT}, { "s.tol", K_DBL }

static void check_choice(int st, const egw_model_choice *c) {
  if (st == EGW_OK) {
    double d[7] = {c->error_bound, c->hertz_error, c->measured_error, c->mu_min, c->mu_max,
                   c->x_min, c->x_max};
    out_doubles(st, 0, "choice", d, 7, sizeof d);
  } else {
    out_untouched(st, "*choice", c, sizeof *c);
  }
}

static int r_scene_validate(void) {
  egw_scene s = scene_at(EGW_MODEL_EGW);
  egw_scene_default(NULL);
  return egw_scene_validate(P(21, &s));
}

static int r_scene_choose(void) {
  egw_scene s = scene_at(EGW_MODEL_EGW);
  egw_options o = options_at(21, 1e-4);
  egw_model_choice c;
  char reason[200];
  int st;
  sentinel(&c, sizeof c);
  st = egw_scene_choose(P(26, &s), P(27, &o), P(28, &c), P(29, reason), I(30, 200));
  check_choice(st, &c);
  return st;
}
static int r_scene_choose_epgw(void) {
  egw_scene s = scene_at(EGW_MODEL_EPGW);
  egw_model_choice c;
  int st;
  sentinel(&c, sizeof c);
  st = egw_scene_choose(&s, NULL, &c, NULL, 0);
  check_choice(st, &c);
  return st;
}

static int r_scene_build(void) {
  egw_scene s = scene_at(EGW_MODEL_EGW);
  egw_model_choice c;
  egw_table t;
  egw_universal u;
  int st;
  s.n_types = I(1, 1); /* one parameter set: a 1-D table */
  s.sigma_max = D(10, s.sigma_min);
  sentinel(&c, sizeof c);
  sentinel(&t, sizeof t);
  sentinel(&u, sizeof u);
  st = egw_scene_build(P(21, &s), NULL, P(22, &c), P(23, &t), P(24, &u));
  check_choice(st, &c);
  if (st == EGW_OK) {
    egw_table_free(&t);
    egw_universal_free(&u);
  }
  return st;
}

static int r_scene_read(void) {
  egw_scene s, s0;
  int st;
  FILE *f = fopen(out_path("scene.nml"), "w");
  if (!f) _exit(3);
  fprintf(f, "&scene\n model = 'E-GW', sigma_min = 1e-6, sigma_max = 1e-6,\n"
             " delta_min_sigma = -2, delta_max_sigma = %.17g, tol = %.17g\n/\n",
          D(1, 20.0), D(2, 1e-3));
  fclose(f);
  egw_scene_default(&s);
  s0 = s;
  st = egw_scene_read(S(0, out_path("scene.nml")), P(3, &s));
  if (st != EGW_OK && memcmp(&s, &s0, sizeof s) != 0) {
    cur->clobbered = 1;
    note("", "*s changed on refusal", 0.0);
  }
  return st;
}

/* egw_set_progress: the hook (NULL: off) hears a rough solve on this thread, done in
 * [0, 1] with a stage, the user pointer as given; NULL hears nothing. */
static int progress_calls, progress_bad;
static void *progress_user;
static void fuzz_progress(double done, const char *stage, void *user) {
  progress_calls++;
  if (!(done >= 0.0 && done <= 1.0) || stage == NULL || user != progress_user) progress_bad++;
}
static int r_set_progress(void) {
  egw_params p;
  egw_result r;
  int st;
  egw_params_default(&p);
  p.model = EGW_MODEL_EGW; p.sigma = 1e-3; p.mu = 4.0;
  progress_calls = progress_bad = 0;
  progress_user = P(1, &progress_calls);
  egw_set_progress(cur->slot == 0 ? NULL : fuzz_progress, progress_user);
  st = egw_solve(&p, NULL, 1e-3, &r);
  egw_set_progress(NULL, NULL);
  if (progress_bad || (cur->slot == 0) != (progress_calls == 0)) {
    cur->silent = 1;
    note("", "progress hook called wrongly", (double)progress_calls);
  }
  return st;
}

static fz_function functions[] = {
    {"egw_get_version", 0, {{0}}, r_version, 0},
    {"egw_status_message", 3, {{"status", K_INT}, {"buf", K_PTR}, {"buflen", K_INT}},
     r_status_message, 0},
    {"egw_last_error", 2, {{"buf", K_PTR}, {"buflen", K_INT}}, r_last_error, 0},
    {"egw_set_progress", 2, {{"hook", K_PTR}, {"user", K_PTR}}, r_set_progress, 0},
    {"egw_params_validate", 9, {PARAM_SLOTS("p."), {"p", K_PTR}}, r_params, 0},
    {"egw_mu_from_summits", 5,
     {{"summit_density", K_DBL}, {"summit_radius", K_DBL}, {"sigma", K_DBL}, {"radius", K_DBL},
      {"mu", K_PTR}},
     r_mu_from_summits, 0},
    {"egw_psi_from_hardness", 6,
     {{"modulus", K_DBL}, {"hardness", K_DBL}, {"hardness_coeff", K_DBL}, {"sigma", K_DBL},
      {"summit_radius", K_DBL}, {"psi", K_PTR}},
     r_psi_from_hardness, 0},
    {"egw_gauss_integral", 3, {{"n", K_DBL}, {"h", K_DBL}, {"value", K_PTR}}, r_gauss, 0},
    {"egw_gauss_integral_deriv", 3, {{"n", K_DBL}, {"h", K_DBL}, {"value", K_PTR}},
     r_gauss_deriv, 0},
    {"egw_ellipk", 2, {{"k", K_DBL}, {"value", K_PTR}}, r_ellipk, 0},
    {"egw_ellipe", 2, {{"k", K_DBL}, {"value", K_PTR}}, r_ellipe, 0},
    {"egw_flat_pressure(_deriv) EP-GW", 12,
     {PARAM_SLOTS("p."), {"p", K_PTR}, {"separation", K_DBL}, {"pressure", K_PTR},
      {"dpressure", K_PTR}},
     r_flat_pressure, 0},
    {"egw_flat_pressure_deriv E-GW", 12,
     {PARAM_SLOTS("p."), {"p", K_PTR}, {"separation", K_DBL}, {"pressure", K_PTR},
      {"dpressure", K_PTR}},
     r_flat_pressure_elastic, 0},
    {"egw_flat_pressure_unload", 13,
     {PARAM_SLOTS("p."), {"p", K_PTR}, {"separation", K_DBL}, {"separation_min", K_DBL},
      {"pressure", K_PTR}, {"dpressure", K_PTR}},
     r_flat_pressure_unload, 0},
    {"egw_hertz", 13,
     {PARAM_SLOTS("p."), {"p", K_PTR}, {"delta", K_DBL}, {"force", K_PTR}, {"stiffness", K_PTR},
      {"contact_radius", K_PTR}},
     r_hertz, 0},
    {"egw_solve E-GW", 17,
     {PARAM_SLOTS("p."), {"p", K_PTR}, OPTION_SLOTS, {"o", K_PTR}, {"delta", K_DBL},
      {"res", K_PTR}},
     r_solve, 1},
    {"egw_solve EP-GW", 17,
     {PARAM_SLOTS("p."), {"p", K_PTR}, OPTION_SLOTS, {"o", K_PTR}, {"delta", K_DBL},
      {"res", K_PTR}},
     r_solve_epgw, 1},
    {"egw_solve_unload", 18,
     {PARAM_SLOTS("p."), {"p", K_PTR}, OPTION_SLOTS, {"o", K_PTR}, {"delta", K_DBL},
      {"delta_max", K_DBL}, {"res", K_PTR}},
     r_solve_unload, 1},
    {"egw_restitution(_energy)", 20,
     {PARAM_SLOTS("p."), {"p", K_PTR}, OPTION_SLOTS, {"o", K_PTR}, {"mass", K_DBL},
      {"velocity", K_DBL}, {"e", K_PTR}, {"w_load", K_PTR}, {"w_dissipated", K_PTR}},
     r_restitution, 1},
    {"egw_restitution_overlap", 19,
     {PARAM_SLOTS("p."), {"p", K_PTR}, OPTION_SLOTS, {"o", K_PTR}, {"mass", K_DBL},
      {"velocity", K_DBL}, {"e", K_PTR}, {"max_overlap", K_PTR}},
     r_restitution_overlap, 1},
    {"egw_time_step", 20,
     {PARAM_SLOTS("p."), {"p", K_PTR}, OPTION_SLOTS, {"o", K_PTR}, {"mass", K_DBL},
      {"velocity", K_DBL}, {"tolerance", K_DBL}, {"duration", K_PTR}, {"time_step", K_PTR}},
     r_time_step, 1},
    {"egw_solve rough (flow_pressure)", 8,
     {ROUGH_CAP_SLOTS, {"p", K_PTR}, {"delta", K_DBL}, {"res", K_PTR}},
     r_rough_cap_solve, 1},
    {"egw_first_yield", 7,
     {CAP_SLOTS, {"p", K_PTR}, {"mass", K_DBL}, {"delta_y", K_PTR}, {"velocity_y", K_PTR}},
     r_first_yield, 0},
    {"egw_solve_unload (flow_pressure)", 7,
     {CAP_SLOTS, {"p", K_PTR}, {"delta", K_DBL}, {"delta_max", K_DBL}, {"res", K_PTR}},
     r_cap_solve_unload, 1},
    {"egw_time_step, egw_restitution (flow_pressure)", 9,
     {CAP_SLOTS, {"p", K_PTR}, {"mass", K_DBL}, {"velocity", K_DBL}, {"tolerance", K_DBL},
      {"duration", K_PTR}, {"time_step", K_PTR}},
     r_cap_restitution, 1},
    {"egw_hertz_array", 19,
     {PARAM_SLOTS("p."), {"p", K_PTR}, {"p_stride", K_INT}, {"n", K_INT}, {"delta[1]", K_DBL},
      {"delta", K_PTR}, {"delta_stride", K_INT}, {"force", K_PTR}, {"stiffness", K_PTR},
      {"contact_radius", K_PTR}, {"flags", K_INT}, {"n_failed", K_PTR}},
     r_hertz_array, 0},
    {"egw_flat_pressure_unload_array", 19,
     {PARAM_SLOTS("p."), {"p", K_PTR}, {"p_stride", K_INT}, {"n", K_INT},
      {"separation[1]", K_DBL}, {"separation", K_PTR}, {"separation_stride", K_INT},
      {"separation_min[0]", K_DBL}, {"separation_min", K_PTR}, {"pressure", K_PTR},
      {"dpressure", K_PTR}, {"flags", K_INT}},
     r_flat_pressure_array, 0},
    {"egw_solve_array (unload)", 21,
     {PARAM_SLOTS("p."), {"p", K_PTR}, OPTION_SLOTS, {"o", K_PTR}, {"delta[0]", K_DBL},
      {"delta_max[0]", K_DBL}, {"n", K_INT}, {"delta_max", K_PTR}, {"res", K_PTR},
      {"flags", K_INT}},
     r_solve_array, 1},
    {"egw_restitution_array", 21,
     {PARAM_SLOTS("p."), {"p", K_PTR}, OPTION_SLOTS, {"o", K_PTR}, {"mass[0]", K_DBL},
      {"velocity[0]", K_DBL}, {"n", K_INT}, {"mass", K_PTR}, {"e", K_PTR}, {"flags", K_INT}},
     r_restitution_array, 1},
    {"egw_time_step_array", 20,
     {PARAM_SLOTS("p."), {"p", K_PTR}, OPTION_SLOTS, {"o", K_PTR}, {"mass[0]", K_DBL},
      {"velocity[0]", K_DBL}, {"tolerance", K_DBL}, {"time_step", K_PTR}, {"flags", K_INT}},
     r_time_step_array, 1},
    {"egw_profile", 21,
     {PARAM_SLOTS("p."), {"p", K_PTR}, OPTION_SLOTS, {"o", K_PTR}, {"delta", K_DBL},
      {"n", K_INT}, {"r[1]", K_DBL}, {"r", K_PTR}, {"pressure", K_PTR}, {"deflection", K_PTR}},
     r_profile, 1},
    {"egw_flat_law_from_table, _pressure, _contact_area", 11,
     {{"u[1]", K_DBL}, {"p[1]", K_DBL}, {"area[1]", K_DBL}, {"u", K_PTR}, {"p", K_PTR},
      {"area", K_PTR}, {"n", K_INT}, {"length", K_DBL}, {"modulus", K_DBL}, {"out", K_PTR},
      {"u (eval)", K_DBL}},
     r_flat_law, 0},
    {"egw_solve_flat_law", 18,
     {PARAM_SLOTS("p."), {"p", K_PTR}, OPTION_SLOTS, {"o", K_PTR}, {"law", K_PTR},
      {"delta", K_DBL}, {"res", K_PTR}},
     r_solve_flat_law, 1},
    {"egw_table_build_flat_law", 20,
     {PARAM_SLOTS("p."), {"p", K_PTR}, OPTION_SLOTS, {"o", K_PTR}, {"law", K_PTR},
      {"delta_min", K_DBL}, {"delta_max", K_DBL}, {"rel_tol", K_DBL}, {"out", K_PTR}},
     r_table_build_flat_law, 1},
    {"egw_table_build E-GW", 19,
     {PARAM_SLOTS("p."), {"p", K_PTR}, OPTION_SLOTS, {"o", K_PTR}, {"delta_min", K_DBL},
      {"delta_max", K_DBL}, {"rel_tol", K_DBL}, {"out", K_PTR}},
     r_table_build, 1},
    {"egw_table_build EP-GW", 19,
     {PARAM_SLOTS("p."), {"p", K_PTR}, OPTION_SLOTS, {"o", K_PTR}, {"delta_min", K_DBL},
      {"delta_max", K_DBL}, {"rel_tol", K_DBL}, {"out", K_PTR}},
     r_table_build_epgw, 1},
    {"egw_table_eval(_all)", 6,
     {{"t", K_PTR}, {"delta", K_DBL}, {"force", K_PTR}, {"stiffness", K_PTR}, {"energy", K_PTR},
      {"contact_radius", K_PTR}},
     r_table_eval, 0},
    {"egw_table_eval_array", 6,
     {{"t", K_PTR}, {"delta[1]", K_DBL}, {"n", K_INT}, {"delta", K_PTR}, {"force", K_PTR},
      {"stiffness", K_PTR}},
     r_table_eval_array, 0},
    {"egw_table_get_info/set_radii", 4,
     {{"t", K_PTR}, {"info", K_PTR}, {"radius1", K_DBL}, {"radius2", K_DBL}},
     r_table_info_radii, 0},
    {"egw_table_get_interpolant", 5,
     {{"t", K_PTR}, {"capacity", K_INT}, {"nodes", K_PTR}, {"coeffs", K_PTR}, {"n_log", K_PTR}},
     r_table_interpolant, 0},
    {"egw_table_get_tail", 6,
     {{"n", K_INT}, {"tables", K_PTR}, {"capacity", K_INT}, {"starts", K_PTR}, {"coeffs", K_PTR},
      {"n_pieces", K_PTR}},
     r_table_tail, 0},
    {"egw_table_write(_calculix)", 4,
     {{"t", K_PTR}, {"path", K_STR}, {"format/shift", K_INT}, {"max_error", K_PTR}},
     r_table_write, 0},
    {"egw_tables_write_lammps(_units)", 4,
     {{"n", K_INT}, {"tables", K_PTR}, {"path", K_STR}, {"units", K_STR}}, r_tables_lammps, 0},
    {"egw_table_read", 2, {{"path", K_STR}, {"out", K_PTR}}, r_table_read, 0},
    {"egw_flat_law_from_psd", 9,
     {{"q[1]", K_DBL}, {"C[1]", K_DBL}, {"n", K_INT}, {"q", K_PTR}, {"C", K_PTR},
      {"modulus", K_DBL}, {"p_min", K_DBL}, {"p_max", K_DBL}, {"out", K_PTR}},
     r_flat_law_psd, 0},
    {"egw_flat_law_from_heights", 9,
     {{"heights[9]", K_DBL}, {"nx", K_INT}, {"ny", K_INT}, {"heights", K_PTR}, {"pixel", K_DBL},
      {"modulus", K_DBL}, {"p_min", K_DBL}, {"p_max", K_DBL}, {"out", K_PTR}},
     r_flat_law_heights, 1},
    {"egw_flat_law_rescale", 4,
     {{"law", K_PTR}, {"unit_length", K_DBL}, {"pressure_unit", K_DBL}, {"out", K_PTR}},
     r_flat_law_rescale, 0},
    {"egw_flat_law_write, egw_flat_law_read", 4,
     {{"law", K_PTR}, {"path (write)", K_STR}, {"path (read)", K_STR}, {"out", K_PTR}},
     r_flat_law_file, 0},
    {"egw_write_flat_calculix(_shifted)", 14,
     {PARAM_SLOTS("p."), {"p", K_PTR}, {"overclosure_max", K_DBL}, {"rel_tol", K_DBL},
      {"shift", K_INT}, {"path", K_STR}, {"max_error", K_PTR}},
     r_flat_calculix, 1},
    {"egw_universal_build", 21,
     {PARAM_SLOTS("p."), {"p", K_PTR}, OPTION_SLOTS, {"o", K_PTR}, {"mu_min", K_DBL},
      {"mu_max", K_DBL}, {"x_min", K_DBL}, {"x_max", K_DBL}, {"rel_tol", K_DBL}, {"out", K_PTR}},
     r_universal_build, 1},
    {"egw_universal_eval", 13,
     {PARAM_SLOTS("p."), {"u", K_PTR}, {"p", K_PTR}, {"delta", K_DBL}, {"force", K_PTR},
      {"stiffness", K_PTR}},
     r_universal_eval, 0},
    {"egw_universal_eval_array", 15,
     {PARAM_SLOTS("p."), {"u", K_PTR}, {"p", K_PTR}, {"n", K_INT}, {"delta[0]", K_DBL},
      {"force", K_PTR}, {"stiffness", K_PTR}, {"flags", K_INT}},
     r_universal_eval_array, 0},
    {"egw_universal_slice(_range)", 12,
     {PARAM_SLOTS("p."), {"u", K_PTR}, {"p", K_PTR}, {"delta_max", K_DBL}, {"out", K_PTR}},
     r_universal_slice, 0},
    {"egw_universal_write/read", 4,
     {{"u", K_PTR}, {"path", K_STR}, {"format", K_INT}, {"out", K_PTR}}, r_universal_io, 0},
    {"egw_hysteresis_build", 19,
     {PARAM_SLOTS("p."), {"p", K_PTR}, OPTION_SLOTS, {"o", K_PTR}, {"delta_min", K_DBL},
      {"delta_max", K_DBL}, {"rel_tol", K_DBL}, {"out", K_PTR}},
     r_hysteresis, 1},
    {"egw_hysteresis_eval", 6,
     {{"h", K_PTR}, {"*state", K_DBL}, {"delta", K_DBL}, {"state", K_PTR}, {"force", K_PTR},
      {"stiffness", K_PTR}},
     r_hysteresis_eval, 1},
    {"egw_hysteresis_eval_state", 7,
     {{"h", K_PTR}, {"state[0]", K_DBL}, {"delta", K_DBL}, {"state[1..]", K_DBL},
      {"state", K_PTR}, {"force", K_PTR}, {"stiffness", K_PTR}},
     r_hysteresis_eval_state, 1},
    {"egw_hysteresis_eval_cached", 5,
     {{"h", K_PTR}, {"state[0]", K_DBL}, {"delta", K_DBL}, {"state[1..]", K_DBL},
      {"tag", K_DBL}},
     r_hysteresis_eval_cached, 1},
    {"egw_hysteresis_energy", 4,
     {{"h", K_PTR}, {"delta_max_state", K_DBL}, {"delta", K_DBL}, {"energy", K_PTR}},
     r_hysteresis_energy, 1},
    {"egw_hysteresis_eval_array", 8,
     {{"h", K_PTR}, {"*state[1]", K_DBL}, {"delta[1]", K_DBL}, {"n", K_INT}, {"delta", K_PTR},
      {"state", K_PTR}, {"force", K_PTR}, {"stiffness", K_PTR}},
     r_hysteresis_eval_array, 1},
    {"egw_hysteresis_write/read/get_info", 5,
     {{"h", K_PTR}, {"path", K_STR}, {"format", K_INT}, {"out", K_PTR}, {"info", K_PTR}},
     r_hysteresis_io, 1},
    {"egw_scene_validate", 22, {SCENE_SLOTS, {"s", K_PTR}}, r_scene_validate, 0},
    {"egw_scene_choose", 31,
     {SCENE_SLOTS, OPTION_SLOTS, {"s", K_PTR}, {"o", K_PTR}, {"choice", K_PTR},
      {"reason", K_PTR}, {"reason_len", K_INT}},
     r_scene_choose, 1},
    {"egw_scene_choose EP-GW", 21, {SCENE_SLOTS}, r_scene_choose_epgw, 1},
    {"egw_scene_build", 25,
     {SCENE_SLOTS, {"s", K_PTR}, {"choice", K_PTR}, {"table", K_PTR}, {"universal", K_PTR}},
     r_scene_build, 1},
    {"egw_scene_read", 4,
     {{"path", K_STR}, {"delta_max", K_DBL}, {"tol", K_DBL}, {"s", K_PTR}}, r_scene_read, 1},
};
enum { N_FUNCTIONS = sizeof functions / sizeof *functions };

/* ------------------------------------------------------------------ the runner */

enum { C_REFUSED, C_ACCEPTED, C_SILENT, C_CLOBBERED, C_CRASHED, C_HUNG, C_KINDS };
static const char *class_names[] = {"refused", "accepted", "silent", "clobbered", "crashed",
                                    "hung"};

typedef struct {
  int function, slot, value, slot2, value2;
} job;

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static void describe(const job *j, char *buf, size_t n) {
  const fz_function *f = &functions[j->function];
  if (j->slot < 0)
    snprintf(buf, n, "%s (valid base call)", f->name);
  else if (j->slot2 >= 0)
    snprintf(buf, n, "%s %s = %s, %s = %s", f->name, f->slots[j->slot].name, pnames[j->value],
             f->slots[j->slot2].name, pnames[j->value2]);
  else
    snprintf(buf, n, "%s %s = %s", f->name, f->slots[j->slot].name,
             value_name(f->slots[j->slot].kind, j->value));
}

/* child: run one case, write the fz_case to fd */
static void child(const job *j, int fd, int limit) {
  fz_case c;
  memset(&c, 0, sizeof c);
  c.slot = j->slot;
  c.value = j->value;
  c.slot2 = j->slot2;
  c.value2 = j->value2;
  cur = &c;
  /* the solving functions get 3 limits: a valid call may take seconds on a loaded machine
   * (egw_restitution at the default rel_tol 1e-6: ~6 s alone) */
  alarm((unsigned)(functions[j->function].heavy ? 3 * limit : limit));
  c.status = functions[j->function].run();
  if (c.status != EGW_OK && !c.detail[0]) egw_last_error(c.detail, (int)sizeof c.detail);
  if (write(fd, &c, sizeof c) != (ssize_t)sizeof c) _exit(4);
  _exit(0);
}

static int setup_tables(int limit) {
  pid_t pid = fork();
  int ws;
  if (pid < 0) return -1;
  if (pid == 0) {
    egw_params p;
    egw_options o;
    egw_table t = NULL;
    egw_universal u = NULL;
    alarm((unsigned)(limit * 6));
    egw_params_default(&p);
    p.sigma = 1e-3;
    p.mu = 2.0;
    egw_options_default(&o);
    o.n_threads = 1;
    if (egw_table_build(&p, &o, -2e-3, 1e-2, 1e-3, &t) != EGW_OK) _exit(1);
    if (egw_table_write(t, table_path, EGW_FORMAT_BINARY) != EGW_OK) _exit(1);
    if (egw_universal_build(&p, &o, 1.0, 4.0, -2.0, 10.0, 3e-2, &u) != EGW_OK) _exit(1);
    if (egw_universal_write(u, universal_path, EGW_FORMAT_BINARY) != EGW_OK) _exit(1);
    _exit(0);
  }
  if (waitpid(pid, &ws, 0) < 0 || !WIFEXITED(ws) || WEXITSTATUS(ws) != 0) return -1;
  return 0;
}

static void remove_tree(const char *dir) {
  char cmd[600];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0) fprintf(stderr, "egw-fuzz: could not remove %s\n", dir);
}

int main(int argc, char **argv) {
  int jobs = 2, limit = 10, verbose = 0;
  const char *only = NULL;
  job *list = NULL;
  int n_jobs = 0, cap = 0;
  long counts[C_KINDS] = {0};
  int bad = 0;
  double t0 = now(), slowest = 0.0;
  char slowest_name[400] = "";

  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--short") == 0) short_mode = 1;
    else if (strcmp(argv[i], "-v") == 0) verbose = 1;
    else if (strcmp(argv[i], "-j") == 0 && i + 1 < argc) jobs = atoi(argv[++i]);
    else if (strcmp(argv[i], "-t") == 0 && i + 1 < argc) limit = atoi(argv[++i]);
    else if (strcmp(argv[i], "-f") == 0 && i + 1 < argc) only = argv[++i];
    else {
      fprintf(stderr, "usage: egw-fuzz [--short] [-j jobs] [-t seconds] [-v] [-f function]\n");
      return 2;
    }
  }
  if (jobs < 1) jobs = 1;
  if (limit < 1) limit = 1;
  /* each solve on one thread: -j children share the cores. libgomp reads
   * OMP_NUM_THREADS when it is loaded, before main, so a setenv here alone would change
   * nothing: the harness runs itself again with the variable set (once; on failure it
   * goes on with OpenMP's default). */
  {
    const char *omp = getenv("OMP_NUM_THREADS");
    if (!(omp && strcmp(omp, "1") == 0)) {
      setenv("OMP_NUM_THREADS", "1", 1);
      execv("/proc/self/exe", argv);
    }
  }

  snprintf(tmpdir, sizeof tmpdir, "%s/egw-fuzz-XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
  if (!mkdtemp(tmpdir)) {
    perror("egw-fuzz: mkdtemp");
    return 2;
  }
  snprintf(table_path, sizeof table_path, "%s/base.egwt", tmpdir);
  snprintf(universal_path, sizeof universal_path, "%s/base.egwu", tmpdir);
  if (setup_tables(limit) != 0) {
    fprintf(stderr, "egw-fuzz: building the base tables failed\n");
    remove_tree(tmpdir);
    return 2;
  }

  /* the cases: each function's valid call, then one slot at a time over its values;
   * the short mode keeps every 4th case (every 9th of the solving functions) */
  for (int f = 0; f < N_FUNCTIONS; f++) {
    int k = 0;
    if (only && !strstr(functions[f].name, only)) continue;
    for (int s = -1; s < functions[f].n_slots; s++) {
      int nv = s < 0 ? 1 : n_values(functions[f].slots[s].kind);
      for (int v = 0; v < nv; v++, k++) {
        if (short_mode && s >= 0 && (k % (functions[f].heavy ? 9 : 4)) != 0) continue;
        if (n_jobs == cap) {
          cap = cap ? 2 * cap : 256;
          list = realloc(list, cap * sizeof *list);
          if (!list) return 2;
        }
        list[n_jobs++] = (job){f, s, v, -1, -1};
      }
    }
    /* full mode: pairs of R, E, sigma, mu (slots 1..4 of functions whose first slots are
     * the params fields) at the normal extremes: valid one at a time, maybe not together */
    if (!short_mode && functions[f].n_slots > 4 && strcmp(functions[f].slots[1].name, "p.radius") == 0) {
      for (int a = 1; a <= 4; a++)
        for (int b = a + 1; b <= 4; b++)
          for (int va = 0; va < N_PAIR_VALUES; va++)
            for (int vb = 0; vb < N_PAIR_VALUES; vb++) {
              if (n_jobs == cap) {
                cap *= 2;
                list = realloc(list, cap * sizeof *list);
                if (!list) return 2;
              }
              list[n_jobs++] = (job){f, a, va, b, vb};
            }
    }
  }

  printf("egw-fuzz: %d cases (%s mode), %d at a time, %d s limit each\n", n_jobs,
         short_mode ? "short" : "full", jobs, limit);
  fflush(stdout);

  {
    pid_t *pids = calloc(jobs, sizeof *pids);
    int *fds = calloc(jobs, sizeof *fds), *which = calloc(jobs, sizeof *which);
    double *start = calloc(jobs, sizeof *start);
    int next = 0, running = 0;
    while (next < n_jobs || running > 0) {
      while (running < jobs && next < n_jobs) {
        int slot = 0, pfd[2];
        while (pids[slot]) slot++;
        if (pipe(pfd) != 0) { perror("pipe"); return 2; }
        fflush(stdout);
        pid_t pid = fork();
        if (pid < 0) { perror("fork"); return 2; }
        if (pid == 0) {
          close(pfd[0]);
          child(&list[next], pfd[1], limit);
        }
        close(pfd[1]);
        pids[slot] = pid;
        fds[slot] = pfd[0];
        which[slot] = next++;
        start[slot] = now();
        running++;
      }
      {
        int ws, slot;
        pid_t pid = waitpid(-1, &ws, 0);
        if (pid < 0) { perror("waitpid"); return 2; }
        for (slot = 0; slot < jobs && pids[slot] != pid; slot++) {}
        if (slot == jobs) continue;
        fz_case c;
        int cls;
        char desc[400], why[260] = "";
        double dt = now() - start[slot];
        ssize_t got = read(fds[slot], &c, sizeof c);
        close(fds[slot]);
        pids[slot] = 0;
        running--;
        describe(&list[which[slot]], desc, sizeof desc);
        if (WIFSIGNALED(ws) && WTERMSIG(ws) == SIGALRM) {
          cls = C_HUNG;
          snprintf(why, sizeof why, "no answer within %d s",
                   functions[list[which[slot]].function].heavy ? 3 * limit : limit);
        } else if (WIFSIGNALED(ws)) {
          cls = C_CRASHED;
          snprintf(why, sizeof why, "signal %d (%s)", WTERMSIG(ws), strsignal(WTERMSIG(ws)));
        } else if (got != (ssize_t)sizeof c || WEXITSTATUS(ws) != 0) {
          cls = C_CRASHED;
          snprintf(why, sizeof why, "exited with status %d", WEXITSTATUS(ws));
        } else if (c.silent) {
          cls = C_SILENT;
          snprintf(why, sizeof why, "status %d: %s", c.status, c.detail);
        } else if (c.clobbered) {
          cls = C_CLOBBERED;
          snprintf(why, sizeof why, "status %d: %s", c.status, c.detail);
        } else if (c.status == EGW_OK) {
          cls = C_ACCEPTED;
        } else {
          cls = C_REFUSED;
          snprintf(why, sizeof why, "status %d: %s", c.status, c.detail);
        }
        counts[cls]++;
        if (dt > slowest) {
          slowest = dt;
          snprintf(slowest_name, sizeof slowest_name, "%s", desc);
        }
        if (cls >= C_SILENT) bad++;
        if (cls >= C_SILENT || verbose)
          printf("  %-9s %s: %s (%.2f s)\n", class_names[cls], desc, why, dt);
        /* the base call of each function must succeed */
        if (list[which[slot]].slot < 0 && cls != C_ACCEPTED) {
          printf("  FAILED    %s: the valid call did not succeed (%s)\n", desc, why);
          bad++;
        }
      }
    }
    free(pids);
    free(fds);
    free(which);
    free(start);
  }
  remove_tree(tmpdir);
  printf("egw-fuzz: tried %d, refused %ld, accepted %ld, silent %ld, clobbered %ld, "
         "crashed %ld, hung %ld (%.1f s; slowest %.2f s: %s)\n",
         n_jobs, counts[C_REFUSED], counts[C_ACCEPTED], counts[C_SILENT], counts[C_CLOBBERED],
         counts[C_CRASHED], counts[C_HUNG], now() - t0, slowest, slowest_name);
  free(list);
  return bad ? 1 : 0;
}
