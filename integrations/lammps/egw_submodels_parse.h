/* pair_style egw: reading granular's sub-model keywords (pair_coeff and, later, wall fixes
 * share this). Definitions in pair_egw_coeff.cpp. */
#ifndef EGW_LAMMPS_SUBMODELS_PARSE_H
#define EGW_LAMMPS_SUBMODELS_PARSE_H

#include "egw_submodels.h"

namespace LAMMPS_NS {
class Error;
/* a finite number, the whole string */
bool egw_parse_number(const char *s, double &v);
/* one sub-model keyword at arg[i] into p; the index after it, or -1 if it is none */
int egw_submodels_parse(Error *error, const char *who, int narg, char **arg, int i,
                        EgwSubmodels::Params &p);
struct EgwCoeff;
/* a WARNING for keywords model (EGW_MODEL_*) ignores: psi, K, plastic_ratio (have_plastic)
 * with a model other than EP-GW; sigma, mu or summit data with Hertz.  Rank 0 only. */
void egw_warn_ignored(Error *error, const char *who, int model, const EgwCoeff &c,
                      bool have_sigma, bool have_plastic);
/* ranges that depend on more than one keyword (the damping value by its model, ...) */
void egw_submodels_check(Error *error, const char *who, EgwSubmodels::Params &p);
}    // namespace LAMMPS_NS

#endif
