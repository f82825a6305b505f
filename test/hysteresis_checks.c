/* C tests of the hysteresis-table entry points of include/egw.h (egw_hysteresis_build,
 * egw_hysteresis_eval, egw_hysteresis_free), with good and bad input. Returns the number of
 * failed checks and prints why; test/test_hysteresis.f90 runs it. */
#include <math.h>
#include <stdio.h>
#include "egw.h"

static int failures;
#define CHECK(cond) do { if (!(cond)) { failures++; \
  printf("    C check failed at %s:%d: %s\n", __FILE__, __LINE__, #cond); } } while (0)

int egw_capi_test_hysteresis(void) {
  egw_params p;
  egw_hysteresis h = NULL;
  egw_result load, unload;
  double state, f, k, f2, k2;
  failures = 0;
  egw_params_default(&p);
  p.model = EGW_MODEL_EPGW; p.radius = 100.0; p.sigma = 1.0; p.mu = 4.0; p.psi = 1.0;
  /* bad input: delta_max < delta_min, NULL out; no handle created */
  CHECK(egw_hysteresis_build(&p, NULL, 4.0, -2.0, 1e-2, &h) == EGW_INVALID_ARGUMENT);
  CHECK(h == NULL);
  CHECK(egw_hysteresis_build(&p, NULL, -2.0, 4.0, 1e-2, NULL) == EGW_NULL_POINTER);
  CHECK(egw_hysteresis_build(&p, NULL, -2.0, 4.0, 1e-2, &h) == EGW_OK);
  if (h == NULL) return failures + 1;
  /* new contact: the loading curve (rel_tol 1e-2 of the solve) and the state moves up */
  state = -INFINITY;
  CHECK(egw_hysteresis_eval(h, 3.0, &state, &f, &k) == EGW_OK);
  CHECK(state == 3.0);
  CHECK(egw_solve(&p, NULL, 3.0, &load) == EGW_OK);
  CHECK(fabs(f - load.force) <= 1e-2 * load.force);
  /* unloading: the unloading solve to rel_tol * P_load(state), below loading */
  CHECK(egw_hysteresis_eval(h, 2.0, &state, &f, &k) == EGW_OK);
  CHECK(state == 3.0);
  CHECK(egw_solve_unload(&p, NULL, 2.0, 3.0, &unload) == EGW_OK);
  CHECK(fabs(f - unload.force) <= 1e-2 * load.force);
  CHECK(egw_solve(&p, NULL, 2.0, &load) == EGW_OK);
  CHECK(f < load.force);
  /* reloading below the state: the same curve */
  CHECK(egw_hysteresis_eval(h, 2.0, &state, &f2, &k2) == EGW_OK);
  CHECK(f2 == f && k2 == k);
  /* NaN: refused, nothing written */
  f2 = -1.0;
  CHECK(egw_hysteresis_eval(h, NAN, &state, &f2, &k2) == EGW_INVALID_ARGUMENT);
  CHECK(f2 == -1.0 && state == 3.0);
  CHECK(egw_hysteresis_eval(h, 1.0, NULL, &f2, &k2) == EGW_NULL_POINTER);
  CHECK(egw_hysteresis_eval(NULL, 1.0, &state, &f2, &k2) == EGW_NULL_POINTER);
  /* beyond the table: values written, EGW_OUT_OF_RANGE */
  CHECK(egw_hysteresis_eval(h, 5.0, &state, &f2, &k2) == EGW_OUT_OF_RANGE);
  CHECK(state == 5.0 && isfinite(f2) && f2 > 0.0);
  egw_hysteresis_free(&h);
  CHECK(h == NULL);
  egw_hysteresis_free(&h);
  egw_hysteresis_free(NULL);
  return failures;
}
