/* egw-restitution: the library's coefficient of restitution of a head-on impact, the
 * reference the LAMMPS examples and tests print next to the simulated rebound.
 *   egw-restitution MODEL E_STAR R SIGMA MU PSI K RHO_P MASS SPEED [REL_TOL [STEP_TOL
 *                   [FLOW_PRESSURE]]]
 * MODEL: 0 Hertz, 1 GW, 2 E-GW, 3 EP-GW; E_STAR, R, SIGMA, MU of the contact (egw_params),
 * MASS the effective mass m*, SPEED the approach speed, FLOW_PRESSURE the contact's p_y
 * (egw_params.flow_pressure; default 0). Prints e; with STEP_TOL > 0 also the deepest
 * overlap delta_m (egw_restitution_overlap), the contact duration and the time step of
 * egw_time_step for that tolerance ("e delta_m duration dt"; STEP_TOL 0: only e and
 * delta_m). MODEL may also be a name (Hertz, GW, E-GW, EP-GW, any case). Exit status 1
 * and egw's message on failure, 2 and a message naming the argument when one is not a
 * number (or a model). */
#include "egw.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* argv[i] as a double; a word that is not a whole number (atof would read "abc" as 0 and
 * "1e-3x" as 1e-3) stops the program naming the argument. */
static double number(char **argv, int i, const char *name)
{
  char *end;
  double x = strtod(argv[i], &end);
  if (end == argv[i] || *end != '\0') {
    fprintf(stderr, "egw-restitution: %s = '%s': not a number\n", name, argv[i]);
    exit(2);
  }
  return x;
}

/* MODEL: 0 .. 3 or its name (before, atoi read "E-GW" and "EP-GW" as 0: Hertz). */
static int model(const char *word)
{
  static const char *names[] = {"Hertz", "GW", "E-GW", "EP-GW"};
  for (int m = 0; m < 4; ++m) {
    char digit[2] = {(char)('0' + m), '\0'};
    if (strcasecmp(word, names[m]) == 0 || strcmp(word, digit) == 0) return m;
  }
  fprintf(stderr, "egw-restitution: MODEL = '%s': must be 0 (Hertz), 1 (GW), 2 (E-GW) or "
                  "3 (EP-GW)\n", word);
  exit(2);
}

int main(int argc, char **argv)
{
  if (argc < 11 || argc > 14) {
    fprintf(stderr, "usage: egw-restitution MODEL E_STAR R SIGMA MU PSI K RHO_P MASS SPEED "
                    "[REL_TOL [STEP_TOL [FLOW_PRESSURE]]]\n");
    return 2;
  }
  egw_params p;
  egw_params_default(&p);
  p.model = model(argv[1]);
  p.modulus = number(argv, 2, "E_STAR");
  p.radius = number(argv, 3, "R");
  p.sigma = number(argv, 4, "SIGMA");
  p.mu = number(argv, 5, "MU");
  p.psi = number(argv, 6, "PSI");
  p.hardness_coeff = number(argv, 7, "K");
  p.plastic_ratio = number(argv, 8, "RHO_P");
  if (argc == 14) p.flow_pressure = number(argv, 13, "FLOW_PRESSURE");
  double mass = number(argv, 9, "MASS"), speed = number(argv, 10, "SPEED");
  egw_options o;
  egw_options_default(&o);
  o.rel_tol = argc >= 12 ? number(argv, 11, "REL_TOL") : 1e-6;
  double e = 0.0, delta_m = 0.0, duration = 0.0, dt = 0.0;
  double step_tol = argc >= 13 ? number(argv, 12, "STEP_TOL") : 0.0;
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
