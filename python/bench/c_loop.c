/* The C side of python/bench/bench_eval.py: evaluate a table read from argv[1] at n
 * overlaps spread over [argv[3], argv[4]] with one egw_table_eval call per point, repeated
 * argv[2]-fold; prints the best time per point in ns and the force sum (so the loop is
 * not optimised away). */
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
  if (argc != 6) {
    fprintf(stderr, "usage: c_loop table n repeats delta_lo delta_hi\n");
    return 2;
  }
  egw_table t = NULL;
  if (egw_table_read(argv[1], &t) != EGW_OK) {
    char msg[256];
    egw_last_error(msg, sizeof msg);
    fprintf(stderr, "c_loop: %s\n", msg);
    return 1;
  }
  int n = atoi(argv[2]), repeats = atoi(argv[3]);
  double lo = atof(argv[4]), hi = atof(argv[5]);
  double *delta = malloc(sizeof(double) * n);
  for (int i = 0; i < n; i++) delta[i] = lo + (hi - lo) * (i + 0.5) / n;
  double best = 1e300, sum = 0.0;
  for (int r = 0; r < repeats; r++) {
    double t0 = now();
    for (int i = 0; i < n; i++) {
      double f, k;
      egw_table_eval(t, delta[i], &f, &k);
      sum += f;
    }
    double dt = now() - t0;
    if (dt < best) best = dt;
  }
  printf("%.3f %.17g\n", 1e9 * best / n, sum);
  free(delta);
  egw_table_free(&t);
  return 0;
}
