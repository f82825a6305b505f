/* pair_style egw: contact histories (the partner's copy) and restart files (settings and
 * each type pair's coefficients; the histories themselves travel with fix NEIGH_HISTORY). */
#include "pair_egw.h"

#include <cstddef>

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "utils.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

/* the partner's copy: delta_max as is, the tangential displacement negated */
void PairEGW::transfer_history(double *source, double *target, int, int)
{
  EgwHistory::transfer(source, target, nhist);
}

/* ---------------------------------------------------------------------- restart */

void PairEGW::write_restart_settings(FILE *fp)
{
  fwrite(&model, sizeof(int), 1, fp);
  fwrite(&tol, sizeof(double), 1, fp);
  fwrite(&rmin_user, sizeof(double), 1, fp);
  fwrite(&rmax_user, sizeof(double), 1, fp);
  fwrite(&overlap_max, sizeof(double), 1, fp);
  fwrite(&tail_energy, sizeof(double), 1, fp);
}

void PairEGW::read_restart_settings(FILE *fp)
{
  if (comm->me == 0) {
    utils::sfread(FLERR, &model, sizeof(int), 1, fp, nullptr, error);
    utils::sfread(FLERR, &tol, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &rmin_user, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &rmax_user, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &overlap_max, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &tail_energy, sizeof(double), 1, fp, nullptr, error);
  }
  MPI_Bcast(&model, 1, MPI_INT, 0, world);
  MPI_Bcast(&tol, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&rmin_user, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&rmax_user, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&overlap_max, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&tail_energy, 1, MPI_DOUBLE, 0, world);
}

void PairEGW::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  // the coefficients' record size, negative (never a setflag): files from before it have
  // none, and their records end before flow_pressure (read_restart)
  int size_mark = -(int) sizeof(Coeff);
  fwrite(&size_mark, sizeof(int), 1, fp);
  int n = atom->ntypes;
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) {
      fwrite(&setflag[i][j], sizeof(int), 1, fp);
      if (setflag[i][j]) fwrite(&pcoeff[i][j], sizeof(Coeff), 1, fp);
    }
}

void PairEGW::read_restart(FILE *fp)
{
  read_restart_settings(fp);
  allocate();
  int n = atom->ntypes;
  // a negative mark gives the record size; a file without it (written before the flow
  // pressure) starts with setflag[1][1], and its records are Coeff up to flow_pressure
  int first = 0;
  if (comm->me == 0) utils::sfread(FLERR, &first, sizeof(int), 1, fp, nullptr, error);
  MPI_Bcast(&first, 1, MPI_INT, 0, world);
  size_t size = first < 0 ? (size_t) -first : offsetof(Coeff, flow_pressure);
  if (size > sizeof(Coeff))
    error->all(FLERR, "Pair egw: the restart file's coefficients ({} bytes) are from a newer "
                      "plugin (this one's: {})", size, sizeof(Coeff));
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) {
      if (i == 1 && j == 1 && first >= 0) setflag[i][j] = first;
      else if (comm->me == 0)
        utils::sfread(FLERR, &setflag[i][j], sizeof(int), 1, fp, nullptr, error);
      MPI_Bcast(&setflag[i][j], 1, MPI_INT, 0, world);
      if (setflag[i][j]) {
        pcoeff[i][j] = Coeff();    // an older record leaves the newer fields' defaults
        if (comm->me == 0) utils::sfread(FLERR, &pcoeff[i][j], size, 1, fp, nullptr, error);
        MPI_Bcast(&pcoeff[i][j], sizeof(Coeff), MPI_BYTE, 0, world);
      }
    }
}
