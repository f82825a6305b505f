/* pair_style egw: reading granular's sub-model keywords (pair_coeff and, later, wall fixes
 * share this). Definitions in pair_egw_coeff.cpp. */
#ifndef EGW_LAMMPS_SUBMODELS_PARSE_H
#define EGW_LAMMPS_SUBMODELS_PARSE_H

#include "egw_submodels.h"

#include <set>
#include <string>

namespace LAMMPS_NS {
class Error;
/* a finite number, the whole string */
bool egw_parse_number(const char *s, double &v);
/* one sub-model keyword at arg[i] into p; the index after it, or -1 if it is none */
int egw_submodels_parse(Error *error, const char *who, int narg, char **arg, int i,
                        EgwSubmodels::Params &p);
/* an ERROR when the keyword at arg[i] was given before on this line (seen: the keywords so
 * far): the first value would be dropped without a word. damping takes a value and a model
 * once each (granular's hertz/material coefficient and its damping model); friction is a
 * tangential model; yield_stress beside flow_pressure is egw_flow_parse's error. */
void egw_check_repeat(Error *error, const char *who, std::set<std::string> &seen, int narg,
                      char **arg, int i);
struct EgwCoeff;
/* a WARNING for keywords model (EGW_MODEL_*) ignores: psi, K, plastic_ratio (have_plastic)
 * with a model other than EP-GW; sigma, mu or summit data with Hertz, mu or summit data
 * with sigma 0; limit_damping with damping none.  Rank 0 only. */
void egw_warn_ignored(Error *error, const char *who, int model, const EgwCoeff &c,
                      bool have_sigma, bool have_plastic);
/* ranges that depend on more than one keyword (the damping value by its model, ...) */
void egw_submodels_check(Error *error, const char *who, EgwSubmodels::Params &p);
/* 'flow_pressure P' or 'yield_stress Y' (p_y = 1.6 Y) at arg[i] into c.flow_pressure and
 * c.flow_keyword; the index after it, or -1 if it is neither. given: -1 before the first,
 * then the keyword given (0, 1); the other one too, or a value that is not a finite
 * number >= 0, is an ERROR naming the keyword. */
int egw_flow_parse(Error *error, const char *who, int narg, char **arg, int i, EgwCoeff &c,
                   int &given);
/* an ERROR naming the keyword (flow_keyword: 0 flow_pressure, 1 yield_stress) when the
 * contact's p_y > 0 is not below its E*; what: the contact, for the message */
void egw_flow_check(Error *error, const char *who, const std::string &what,
                    double flow_pressure, int flow_keyword, double E_star);
/* an ERROR naming the keyword when the cap's first-yield scales of the contact (a_y, delta_y
 * and P_y at its equivalent radii R_lo, R_hi; 0: not known) leave egw's range, as
 * egw_params_validate refuses them (a p_y far below E*: delta_y underflowed, and the
 * contacts' overlaps in delta_y were NaN); radii not known: the scale (pi p_y/(2 E*))^2 of
 * delta_y/R must be a normal double */
void egw_flow_scale_check(Error *error, const char *who, const std::string &what,
                          double flow_pressure, int flow_keyword, double E_star, double R_lo,
                          double R_hi);
}    // namespace LAMMPS_NS

#endif
