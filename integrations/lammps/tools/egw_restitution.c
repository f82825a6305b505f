/* egw-restitution: the library's coefficient of restitution of a head-on impact, the
 * reference the LAMMPS examples and tests print next to the simulated rebound.
 *   egw-restitution MODEL E_STAR R SIGMA MU PSI K RHO_P MASS SPEED [REL_TOL [STEP_TOL
 *                   [FLOW_PRESSURE]]]
 * MODEL: 0 Hertz, 1 GW, 2 E-GW, 3 EP-GW; E_STAR, R, SIGMA, MU of the contact (egw_params),
 * MASS the effective mass m*, SPEED the approach speed, FLOW_PRESSURE the contact's p_y
 * (egw_params.flow_pressure; default 0). Prints e; with STEP_TOL > 0 also the deepest
 * overlap delta_m (egw_restitution_overlap), the contact duration and the time step of
 * egw_time_step for that tolerance ("e delta_m duration dt"; STEP_TOL 0: only e and
 * delta_m). Exit status 1 and egw's message on failure. */
#include "egw.h"

#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
  if (argc < 11 || argc > 14) {
    fprintf(stderr, "usage: egw-restitution MODEL E_STAR R SIGMA MU PSI K RHO_P MASS SPEED "
                    "[REL_TOL [STEP_TOL [FLOW_PRESSURE]]]\n");
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
  if (argc == 14) p.flow_pressure = atof(argv[13]);
  double mass = atof(argv[9]), speed = atof(argv[10]);
  egw_options o;
  egw_options_default(&o);
  o.rel_tol = argc >= 12 ? atof(argv[11]) : 1e-6;
  double e = 0.0, delta_m = 0.0, duration = 0.0, dt = 0.0;
  double step_tol = argc >= 13 ? atof(argv[12]) : 0.0;
  int st = egw_restitution_overlap(&p, &o, mass, speed, &e, &delta_m);
  if (st == EGW_OK && step_tol > 0)
    st = egw_time_step(&p, NULL, mass, speed, step_tol, &duration, &dt);
  if (st != EGW_OK) {
    char msg[512];
    egw_last_error(msg, sizeof msg);
    fprintf(stderr, "egw-restitution: %s\n", msg);
    return 1;
  }
  if (step_tol > 0)
    printf("%.12g %.12g %.12g %.12g\n", e, delta_m, duration, dt);
  else if (argc >= 13)
    printf("%.12g %.12g\n", e, delta_m);
  else
    printf("%.12g\n", e);
  return 0;
}
