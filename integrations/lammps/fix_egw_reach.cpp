/* fix EGW_REACH: pair_style egw's reneighboring guard (fix_egw_reach.h). */
#include "fix_egw_reach.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;
using namespace FixConst;

/* d among the two largest so far, top[0] >= top[1] */
static inline void keep_two(double d, double *top)
{
  if (d > top[1]) {
    if (d > top[0]) top[1] = top[0], top[0] = d;
    else top[1] = d;
  }
}

/* MPI reduction of (largest, second largest) pairs */
static void reduce_two(void *in, void *inout, int *len, MPI_Datatype *)
{
  auto a = static_cast<const double *>(in);
  auto b = static_cast<double *>(inout);
  for (int k = 0; k < *len; k++, a += 2, b += 2) keep_two(a[0], b), keep_two(a[1], b);
}

FixEGWReach::FixEGWReach(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
{
  if (narg != 3) error->all(FLERR, "Illegal fix EGW_REACH command (pair_style egw's own)");
  force_reneighbor = 1;    // Neighbor::decide() asks this fix every step
  next_reneighbor = -1;
  MPI_Type_contiguous(2, MPI_DOUBLE, &two_type);
  MPI_Type_commit(&two_type);
  MPI_Op_create(&reduce_two, 1, &two_op);
}

FixEGWReach::~FixEGWReach()
{
  MPI_Op_free(&two_op);
  MPI_Type_free(&two_type);
}

int FixEGWReach::setmask()
{
  return POST_INTEGRATE | POST_NEIGHBOR;
}

void FixEGWReach::set_limit(double distance)
{
  limit = distance > 0 ? distance : -1.0;
  next_reneighbor = -1;
}

void FixEGWReach::setup_post_neighbor()
{
  post_neighbor();
}

void FixEGWReach::post_neighbor()
{
  if (!(limit > 0)) return;
  nhold = atom->nlocal;
  xhold.resize(3 * (size_t) nhold);
  double **x = atom->x;
  for (int i = 0; i < nhold; i++)
    xhold[3 * i] = x[i][0], xhold[3 * i + 1] = x[i][1], xhold[3 * i + 2] = x[i][2];
}

/* after the step's positions (initial_integrate) and before Neighbor::decide(): a pair
 * has closed in by at most the sum of its two atoms' displacements since the build */
void FixEGWReach::post_integrate()
{
  if (!(limit > 0)) return;
  double top[2] = {0.0, 0.0};    // the two largest squared displacements of the local atoms
  if (atom->nlocal != nhold)     // atoms came or went without a build: rebuild
    top[0] = top[1] = HUGE_VAL;
  else {
    double **x = atom->x;
    const double *h = xhold.data();
    for (int i = 0; i < nhold; i++) {
      double dx = x[i][0] - h[3 * i], dy = x[i][1] - h[3 * i + 1], dz = x[i][2] - h[3 * i + 2];
      keep_two(dx * dx + dy * dy + dz * dz, top);
    }
  }
  if (comm->nprocs > 1) {    // the two largest of all ranks (ghosts move as their owners)
    double mine[2] = {top[0], top[1]};
    MPI_Allreduce(mine, top, 1, two_type, two_op, world);
  }
  if (std::sqrt(top[0]) + std::sqrt(top[1]) > limit) next_reneighbor = update->ntimestep;
}

double FixEGWReach::memory_usage()
{
  return (double) xhold.capacity() * sizeof(double);
}
