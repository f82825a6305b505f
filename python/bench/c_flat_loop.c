/* C loop of bench_arrays.py: egw_flat_pressure once per point over n separations spread
 * evenly in [lo, hi], best of `repeats`; prints ns per point and the sum of pressures. */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "egw.h"

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

int main(int argc, char **argv) {
  egw_params p;
  int n, repeats;
  double lo, hi, best = 1e300, sum = 0.0;
  double *d, *pr;
  if (argc != 9) {
    fprintf(stderr, "usage: c_flat_loop n repeats lo hi radius modulus sigma mu\n");
    return 2;
  }
  n = atoi(argv[1]); repeats = atoi(argv[2]); lo = atof(argv[3]); hi = atof(argv[4]);
  egw_params_default(&p);
  p.model = EGW_MODEL_EGW; p.radius = atof(argv[5]); p.modulus = atof(argv[6]);
  p.sigma = atof(argv[7]); p.mu = atof(argv[8]);
  d = malloc(sizeof *d * n); pr = malloc(sizeof *pr * n);
  for (int i = 0; i < n; i++) d[i] = lo + (hi - lo) * (i + 0.5) / n;
  for (int r = 0; r < repeats; r++) {
    double t0 = now();
    for (int i = 0; i < n; i++)
      if (egw_flat_pressure(&p, d[i], &pr[i]) != EGW_OK) return 1;
    if (now() - t0 < best) best = now() - t0;
  }
  for (int i = 0; i < n; i++) sum += pr[i];
  printf("%.6g %.17g\n", 1e9 * best / n, sum);
  free(d); free(pr);
  return 0;
}
