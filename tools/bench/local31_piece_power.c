/* What a served unloading piece would cost if a rough + cap table stored v = u^(2/3)
 * (doc/benchmarks.md "Stop 65: local31"): the served step of egw.h's
 * egw_hysteresis_eval_cached on a piece (its cubic in delta - lo, value and slope) as
 * today (a gap or force-ratio piece: the force is the cubic) against the same cubic taken
 * as v, the force P(m) v^(3/2) = v sqrt(v) (P(m) folded into the cubic's scale:
 * c' = P(m)^(2/3) c) and the stiffness 1.5 sqrt(v) dv/d(delta). 4096 contacts,
 * each a piece and an overlap moved a little every step (as a DEM's), 200 sweeps, the two
 * loops alternated, best of 7 rounds, ns per step; argv[1] = 1 or 2 runs that loop alone
 * (for `valgrind --tool=cachegrind --cache-sim=no`, instructions per step = Ir / (4096 *
 * 200) less the empty loop's, argv[1] = 3).
 *   cc -O2 -o /tmp/local31_piece_power tools/bench/local31_piece_power.c -lm
 *   /tmp/local31_piece_power            (timing)
 *   valgrind --tool=cachegrind --cache-sim=no /tmp/local31_piece_power 1   (and 2, 3) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

enum { N = 4096, SWEEPS = 200, ROUNDS = 7 };
static double lo[N], c[N][4], delta[N], step[N];

static double now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* today's piece: the force is the cubic */
static double sweep_cubic(void)
{
  double sink = 0.0;
  for (int r = 0; r < SWEEPS; r++)
    for (int i = 0; i < N; i++) {
      double d = delta[i] + step[i] * (r & 1 ? 1.0 : -1.0);
      double x = d - lo[i], x2 = x * x;
      double f = (c[i][0] + x * c[i][1]) + x2 * (c[i][2] + x * c[i][3]);
      double k = (c[i][1] + 2 * x * c[i][2]) + 3 * x2 * c[i][3];
      if (!(f > 0.0)) f = k = 0.0;
      sink += f + 1e-3 * k;
    }
  return sink;
}

/* the v piece: the cubic is v (scaled), the force v sqrt(v) */
static double sweep_power(void)
{
  double sink = 0.0;
  for (int r = 0; r < SWEEPS; r++)
    for (int i = 0; i < N; i++) {
      double d = delta[i] + step[i] * (r & 1 ? 1.0 : -1.0);
      double x = d - lo[i], x2 = x * x;
      double v = (c[i][0] + x * c[i][1]) + x2 * (c[i][2] + x * c[i][3]);
      double dv = (c[i][1] + 2 * x * c[i][2]) + 3 * x2 * c[i][3];
      double f = 0.0, k = 0.0;
      if (v > 0.0) {
        double q = sqrt(v);
        f = v * q;
        k = 1.5 * q * dv;
      }
      sink += f + 1e-3 * k;
    }
  return sink;
}

static double sweep_empty(void)
{
  double sink = 0.0;
  for (int r = 0; r < SWEEPS; r++)
    for (int i = 0; i < N; i++) sink += delta[i] + step[i] * (r & 1 ? 1.0 : -1.0);
  return sink;
}

int main(int argc, char **argv)
{
  srand(12345);
  for (int i = 0; i < N; i++) {
    lo[i] = (double)rand() / RAND_MAX;
    delta[i] = lo[i] + 0.5 + 0.4 * (double)rand() / RAND_MAX;
    step[i] = 1e-4 * (double)rand() / RAND_MAX;
    /* a decreasing positive cubic on [lo, lo + 1] */
    c[i][0] = 0.01 + 0.001 * (double)rand() / RAND_MAX;
    c[i][1] = 0.02;
    c[i][2] = 0.003;
    c[i][3] = -0.0005;
  }
  if (argc > 1) {
    int which = atoi(argv[1]);
    double s = which == 1 ? sweep_cubic() : which == 2 ? sweep_power() : sweep_empty();
    printf("%g\n", s);
    return 0;
  }
  double best[2] = {1e30, 1e30}, sink = 0.0;
  for (int round = 0; round < ROUNDS; round++) {
    double t0 = now();
    sink += sweep_cubic();
    double t1 = now();
    sink += sweep_power();
    double t2 = now();
    if (t1 - t0 < best[0]) best[0] = t1 - t0;
    if (t2 - t1 < best[1]) best[1] = t2 - t1;
  }
  printf("ns per step: cubic piece %.2f, v^(3/2) piece %.2f (sink %g)\n",
         1e9 * best[0] / (N * (double)SWEEPS), 1e9 * best[1] / (N * (double)SWEEPS), sink);
  return 0;
}
