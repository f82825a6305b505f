/* Cost of an EP-GW hysteresis contact that is separated, as a DEM meets it when a
 * neighbour enters the skin (a state fresh from egw_hysteresis_state_init) or after it
 * touched, against an inline Hertz formula (issue 33 item 5: <= 2x beyond the cut-off,
 * <= 5x in the tail). egw.h alone.
 *
 * Build (from the worktree; LIB the fpm archive, e.g. build/gfortran_<hash>/egw/libegw.a):
 *   gcc -O2 -std=c99 -Iinclude tools/bench/separated_hysteresis.c LIB \
 *       -lfftw3_omp -lfftw3 -llapack -lblas -lgfortran -lquadmath -lgomp -lm \
 *       -o /tmp/sephyst
 * Run: OMP_NUM_THREADS=1 /tmp/sephyst [rounds [case]]   (prints CPU ns per evaluation, the
 * minimum over the rounds, and the ratio to the inline Hertz loop of the same round; case,
 * e.g. "tail-history-call", runs that case alone (and Hertz): for `perf stat -e
 * instructions`, whose count over 3 rounds less 1 round, halved, is one round's).
 *
 * Contact: E-GW/EP-GW R 0.5 mm, E* 36.8 GPa, sigma 1 um, mu 4, psi 1; table rel_tol 1e-4
 * over [-3, 30] sigma (the loading table's cut-off lies below -3 sigma). 256 contacts, each
 * evaluated at x0 + (uniform +-0.005 sigma) overlaps from a table of 4096, 2^22
 * evaluations a case. Cases: x0 = cut-off - 2 sigma ("beyond"), -2.5 sigma ("tail",
 * between the cut-off and 0) and 0.5 sigma ("contact", stop 56: in contact, below the
 * history of 1 sigma when touched, loading when fresh); states fresh (egw_hysteresis_state_init before the loop:
 * never touched) or with a history (loaded to 1 sigma before the loop: separated);
 * paths: "inline" = egw_hysteresis_eval_cached, egw_hysteresis_eval_state when it does
 * not serve; "call" = egw_hysteresis_eval_state alone, each path in its own loop (as a
 * DEM force loop has one; before stop 54 they shared one loop with a test of the path;
 * main's times are the same in both shapes); "batch" (stop 55) = the inline in a sweep
 * over the 256 contacts (each once, as a DEM time step), the contacts it does not serve
 * called after the sweep: no call in the hot loop, so that gcc keeps the sum in a
 * register there (with a call in the loop no xmm register survives it, and the sum's
 * store and reload lie on the loop's dependency chain). Hertz: (4/3) E* sqrt(R) |d|^1.5 and its
 * stiffness, inline (|d| so that it computes, as a contact in touch), summed the same way;
 * gcc -O2 does not vectorize it (an FP sum; a scalar sqrtsd a step). */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "egw.h"

#define NC 256
#define ND 4096
#define NEVAL (1 << 22)

/* The process's CPU time (stop 57: one thread, so its loops' time; on a loaded machine the
 * wall clock also counts other processes' turns) */
static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static double st[NC][EGW_HYSTERESIS_STATE_SIZE];
static double dl[ND];
static volatile double sink;

/* One loop per path (noinline: each compiled alone, as a force routine is). */
static __attribute__((noinline)) double loop_inline(egw_hysteresis h, double tag,
                                                    double x0) {
  double acc = 0.0, f, k;
  for (int n = 0; n < NEVAL; n++) {
    int j = n & (NC - 1);
    double d = x0 + dl[(n * 257) & (ND - 1)];
    if (!egw_hysteresis_eval_cached(tag, d, st[j], &f, &k))
      egw_hysteresis_eval_state(h, d, st[j], &f, &k);
    acc += f + k;
  }
  return acc;
}

static __attribute__((noinline)) double loop_call(egw_hysteresis h, double x0) {
  double acc = 0.0, f, k;
  for (int n = 0; n < NEVAL; n++) {
    int j = n & (NC - 1);
    double d = x0 + dl[(n * 257) & (ND - 1)];
    egw_hysteresis_eval_state(h, d, st[j], &f, &k);
    acc += f + k;
  }
  return acc;
}

/* "batch": a sweep of the inline over the contacts, then the call for those it did not
 * serve (contact j is evaluated once a sweep, at the overlap loop_inline gives it). */
static __attribute__((noinline)) double loop_batch(egw_hysteresis h, double tag,
                                                   double x0) {
  double acc = 0.0, f, k;
  int miss[NC];
  for (int n = 0; n < NEVAL; n += NC) {
    int m = 0;
    for (int j = 0; j < NC; j++) {
      double d = x0 + dl[((n + j) * 257) & (ND - 1)], fi, ki;
      if (egw_hysteresis_eval_cached(tag, d, st[j], &fi, &ki))
        acc += fi + ki;
      else
        miss[m++] = j;
    }
    for (int i = 0; i < m; i++) {
      int j = miss[i];
      egw_hysteresis_eval_state(h, x0 + dl[((n + j) * 257) & (ND - 1)], st[j], &f, &k);
      acc += f + k;
    }
  }
  return acc;
}

int main(int argc, char **argv) {
  int rounds = argc > 1 ? atoi(argv[1]) : 5;
  const char *only = argc > 2 ? argv[2] : NULL;
  egw_params p;
  egw_hysteresis h = NULL;
  egw_hysteresis_info info;
  double tag, sigma = 1e-6, best[3][2][3], hertz_best = 1e30, ratio[3][2][3];
  const char *where[3] = {"beyond", "tail", "contact"}, *hist[2] = {"fresh", "history"},
             *path[3] = {"inline", "call", "batch"};
  egw_params_default(&p);
  p.model = EGW_MODEL_EPGW;
  p.radius = 0.5e-3;
  p.modulus = 36.8e9;
  p.sigma = sigma;
  p.mu = 4.0;
  p.psi = 1.0;
  if (egw_hysteresis_build(&p, NULL, -3 * sigma, 30 * sigma, 1e-4, &h) != EGW_OK) {
    printf("build failed\n");
    return 1;
  }
  egw_hysteresis_get_info(h, &info);
  egw_hysteresis_state_tag(h, &tag);
  printf("cut-off %.4f sigma, version %d\n", info.cutoff / sigma, egw_get_version());
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 2; b++)
      for (int c = 0; c < 3; c++) best[a][b][c] = 1e30, ratio[a][b][c] = 1e30;
  unsigned long long seed = 20261130;
  for (int r = 0; r < rounds; r++) {
    double hertz, c43 = 4.0 / 3.0 * p.modulus * sqrt(p.radius), acc = 0.0, t0;
    for (int i = 0; i < ND; i++) {
      seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
      dl[i] = (((seed >> 11) * 0x1.0p-53) - 0.5) * 0.01 * sigma;
    }
    t0 = now();
    for (int n = 0; n < NEVAL; n++) {
      double d = fabs(-2.5 * sigma + dl[(n * 257) & (ND - 1)]), s = sqrt(d);
      acc += c43 * d * s + 1.5 * c43 * s;
    }
    hertz = (now() - t0) / NEVAL;
    sink = acc;
    if (hertz < hertz_best) hertz_best = hertz;
    for (int w = 0; w < 3; w++)
      for (int hi = 0; hi < 2; hi++)
        for (int pa = 0; pa < 3; pa++) {
          double x0 = w == 0 ? info.cutoff - 2 * sigma : w == 1 ? -2.5 * sigma : 0.5 * sigma, f, k, dt;
          char name[32];
          snprintf(name, sizeof name, "%s-%s-%s", where[w], hist[hi], path[pa]);
          if (only != NULL && strcmp(only, name) != 0) continue;
          for (int j = 0; j < NC; j++) {
            egw_hysteresis_state_init(st[j]);
            if (hi) egw_hysteresis_eval_state(h, 1.0 * sigma, st[j], &f, &k);
          }
          t0 = now();
          sink = pa == 0   ? loop_inline(h, tag, x0)
                 : pa == 1 ? loop_call(h, x0)
                           : loop_batch(h, tag, x0);
          dt = (now() - t0) / NEVAL;
          if (dt < best[w][hi][pa]) best[w][hi][pa] = dt;
          if (dt / hertz < ratio[w][hi][pa]) ratio[w][hi][pa] = dt / hertz;
        }
  }
  printf("inline Hertz %.2f ns (min of %d rounds)\n", 1e9 * hertz_best, rounds);
  for (int w = 0; w < 3; w++)
    for (int hi = 0; hi < 2; hi++)
      for (int pa = 0; pa < 3; pa++)
        if (best[w][hi][pa] < 1e30)
          printf("%-7s %-7s %-6s %6.2f ns  %5.2fx Hertz (best round ratio %5.2fx)\n",
                 where[w], hist[hi], path[pa], 1e9 * best[w][hi][pa],
                 best[w][hi][pa] / hertz_best, ratio[w][hi][pa]);
  egw_hysteresis_free(&h);
  return 0;
}
