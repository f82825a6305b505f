/* egw-restitution: the library's coefficient of restitution of a head-on impact, the
 * reference the LAMMPS examples and tests print next to the simulated rebound.
 *   egw-restitution MODEL E_STAR R SIGMA MU PSI K RHO_P MASS SPEED [REL_TOL [STEP_TOL]]
 * MODEL: 0 Hertz, 1 GW, 2 E-GW, 3 EP-GW; E_STAR, R, SIGMA, MU of the contact (egw_params),
 * MASS the effective mass m*, SPEED the approach speed. Prints e; with STEP_TOL also the
 * deepest overlap delta_m (egw_restitution_overlap), the contact duration and the time
 * step of egw_time_step for that tolerance ("e delta_m duration dt"). Exit status 1 and
 * egw's message on failure. */
#include "egw.h"

#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
  if (argc < 11 || argc > 13) {
    fprintf(stderr, "usage: egw-restitution MODEL E_STAR R SIGMA MU PSI K RHO_P MASS SPEED "
                    "[REL_TOL [STEP_TOL]]\n");
    return 2;
  }
  egw_params p;
  egw_params_default(&p);
  p.model = atoi(argv[1]);
  p.modulus = atof(argv[2]);
  p.radius = atof(argv[3]);
  p.sigma = atof(argv[4]);
  p.mu = atof(argv[5]);
  p.psi = atof(argv[6]);
  p.hardness_coeff = atof(argv[7]);
  p.plastic_ratio = atof(argv[8]);
  double mass = atof(argv[9]), speed = atof(argv[10]);
  egw_options o;
  egw_options_default(&o);
  o.rel_tol = argc >= 12 ? atof(argv[11]) : 1e-6;
  double e = 0.0, delta_m = 0.0, duration = 0.0, dt = 0.0;
  int st = egw_restitution_overlap(&p, &o, mass, speed, &e, &delta_m);
  if (st == EGW_OK && argc == 13)
    st = egw_time_step(&p, NULL, mass, speed, atof(argv[12]), &duration, &dt);
  if (st != EGW_OK) {
    char msg[512];
    egw_last_error(msg, sizeof msg);
    fprintf(stderr, "egw-restitution: %s\n", msg);
    return 1;
  }
  if (argc == 13)
    printf("%.12g %.12g %.12g %.12g\n", e, delta_m, duration, dt);
  else
    printf("%.12g\n", e);
  return 0;
}
