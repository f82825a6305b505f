/* capi_eval: evaluate egw's documented closed forms and kernels through the C API only
 * (include/egw.h), one request per stdin line, for tools/reference/capi_accuracy.py.
 * Lines: "gauss N H", "gaussd N H", "ellipk K", "ellipe K",
 *        "hertz R E DELTA", "yield R E PY MASS", "cap R E PY DELTA",
 *        "flat PSI K RHO H" (R = E* = sigma = 1, mu = 2 sqrt 2: p_G = Phi(h)).
 * Output per line: the status and the results with 17 significant digits. */
#include <stdio.h>
#include <math.h>
#include <string.h>
#include "egw.h"

int main(void) {
  char line[512], what[32];
  while (fgets(line, sizeof line, stdin)) {
    double a = 0, b = 0, c = 0, d = 0, v1 = 0, v2 = 0, v3 = 0;
    int st, n = sscanf(line, "%31s %lf %lf %lf %lf", what, &a, &b, &c, &d);
    if (!strcmp(what, "flat")) {
      egw_params p;
      egw_params_default(&p);
      p.model = a > 0 ? EGW_MODEL_EPGW : EGW_MODEL_EGW;
      p.sigma = 1.0;
      p.mu = 2.0 * sqrt(2.0);
      p.psi = a;
      p.hardness_coeff = b;
      p.plastic_ratio = c;
      st = egw_flat_pressure_deriv(&p, d, &v1, &v2);
      printf("%d %.17g %.17g %.17g\n", st, v1, v2, v3);
      continue;
    }
    if (n < 2) continue;
    if (!strcmp(what, "gauss")) {
      st = egw_gauss_integral(a, b, &v1);
    } else if (!strcmp(what, "gaussd")) {
      st = egw_gauss_integral_deriv(a, b, &v1);
    } else if (!strcmp(what, "ellipk")) {
      st = egw_ellipk(a, &v1);
    } else if (!strcmp(what, "ellipe")) {
      st = egw_ellipe(a, &v1);
    } else {
      egw_params p;
      egw_params_default(&p);
      p.model = EGW_MODEL_HERTZ;
      p.radius = a;
      p.modulus = b;
      if (!strcmp(what, "hertz")) {
        st = egw_hertz(&p, c, &v1, &v2, &v3);
      } else if (!strcmp(what, "yield")) {
        p.flow_pressure = c;
        st = egw_first_yield(&p, d, &v1, &v2);
      } else if (!strcmp(what, "cap")) {
        egw_result r;
        p.flow_pressure = c;
        st = egw_solve(&p, NULL, d, &r);
        if (st == EGW_OK) { v1 = r.force; v2 = r.contact_radius; v3 = r.max_pressure; }
      } else {
        fprintf(stderr, "capi_eval: unknown request %s\n", what);
        return 2;
      }
    }
    printf("%d %.17g %.17g %.17g\n", st, v1, v2, v3);
  }
  return 0;
}
