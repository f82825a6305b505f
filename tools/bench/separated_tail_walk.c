/* Forces and stiffnesses of separated EP-GW contacts, printed bit for bit, to compare two
 * builds of egw (doc/benchmarks.md "Stop 56: tail22": 0.3.2's folded tail pieces against
 * 0.3.1's). The bench's contact (tools/bench/separated_hysteresis.c: R 0.5 mm, E* 36.8 GPa,
 * sigma 1 um, mu 4, psi 1, table 1e-4 over [-3, 30] sigma); for 7 turning points from
 * -2.5 to 10 sigma it unloads in 4000 steps to the loading table's cut-off, once through
 * egw_hysteresis_eval_state alone and once through egw.h's inline (the call where it does
 * not serve), and stops with status 2 if the two differ in a bit. Each line: turning
 * point's index, step, delta/sigma, force, stiffness, P_load at the turning point (%a).
 * Build as the bench (its header), against each build's egw.h and libegw.a:
 *   gcc -O2 -std=c99 -Iinclude tools/bench/separated_tail_walk.c LIB -lfftw3_omp -lfftw3 \
 *       -llapack -lblas -lgfortran -lquadmath -lgomp -lm -o /tmp/walk
 * Run: OMP_NUM_THREADS=1 EGW_CACHE_DIR=off /tmp/walk > out.txt */
#include <math.h>
#include <stdio.h>
#include "egw.h"

int main(void) {
  static const double hist[] = {-2.5, -1.5, -0.7, 0.0, 1.0, 3.0, 10.0};
  egw_params p;
  egw_hysteresis h = NULL;
  egw_hysteresis_info info;
  double tag, s = 1e-6;
  egw_params_default(&p);
  p.model = EGW_MODEL_EPGW;
  p.radius = 0.5e-3;
  p.modulus = 36.8e9;
  p.sigma = s;
  p.mu = 4.0;
  p.psi = 1.0;
  if (egw_hysteresis_build(&p, NULL, -3 * s, 30 * s, 1e-4, &h) != EGW_OK) return 1;
  egw_hysteresis_get_info(h, &info);
  egw_hysteresis_state_tag(h, &tag);
  for (int a = 0; a < 7; a++) {
    double st[EGW_HYSTERESIS_STATE_SIZE], st2[EGW_HYSTERESIS_STATE_SIZE], f, k, f2, k2, fm, km;
    egw_hysteresis_state_init(st);
    egw_hysteresis_state_init(st2);
    egw_hysteresis_eval_state(h, hist[a] * s, st, &fm, &km);
    egw_hysteresis_eval_state(h, hist[a] * s, st2, &f, &k);
    for (int i = 1; i <= 4000; i++) {
      double d = hist[a] * s - (hist[a] * s - info.cutoff) * i / 4000.0;
      egw_hysteresis_eval_state(h, d, st, &f, &k);
      if (!egw_hysteresis_eval_cached(tag, d, st2, &f2, &k2))
        egw_hysteresis_eval_state(h, d, st2, &f2, &k2);
      if (f != f2 || k != k2) {
        printf("inline and call differ at turning point %d, step %d\n", a, i);
        return 2;
      }
      printf("%d %d %.17g %a %a %a\n", a, i, d / s, f, k, fm);
    }
  }
  egw_hysteresis_free(&h);
  return 0;
}
