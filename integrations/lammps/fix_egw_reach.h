/* pair_style egw's reneighboring guard (an internal fix, EGW_REACH, that the pair style
 * creates): egw's contacts act from delta = -tail (the rough tail), before the spheres
 * touch. A size neighbor list (LAMMPS's cheapest for polydisperse grains: the pairs with
 * r <= R_i + R_j + skin at the build) holds every such contact only while no pair has
 * closed in by more than skin - tail since the build, so this fix asks for a rebuild once
 * the two largest displacements since the build add up to skin - tail (no pair can have
 * closed in by more; LAMMPS's own check, one atom moved skin/2, suffices only without a
 * tail). */
#ifndef EGW_LAMMPS_FIX_EGW_REACH_H
#define EGW_LAMMPS_FIX_EGW_REACH_H

#include "fix.h"

#include <mpi.h>
#include <vector>

namespace LAMMPS_NS {

class FixEGWReach : public Fix {
 public:
  FixEGWReach(class LAMMPS *, int, char **);
  ~FixEGWReach() override;
  int setmask() override;
  void setup_post_neighbor() override;
  void post_neighbor() override;
  void post_integrate() override;
  double memory_usage() override;
  /* rebuild once two atoms could have closed in by `distance` since the last build (the
   * sum of the two largest displacements); <= 0: never (a list that needs no guard) */
  void set_limit(double distance);

 private:
  double limit = -1.0;
  std::vector<double> xhold;    // local atoms' positions at the last build
  int nhold = -1;
  MPI_Datatype two_type;        // two doubles, and the reduction that keeps the two largest
  MPI_Op two_op;
};

}    // namespace LAMMPS_NS

#endif
