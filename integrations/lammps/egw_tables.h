/* pair_style egw and fix wall/egw: the process-wide registry of egw tables (EP-GW
 * hysteresis tables one by one, GW/E-GW laws' 1-D tables and slices as sets).
 * Tables are normalised (R = E* = sigma = 1, delta in units of sigma, force in units of
 * E* sqrt(R) sigma^1.5), so a table depends only on the model, mu, psi, K, rho_p, its
 * reach and tolerance: every type pair and wall that needs the same one shares it, and
 * with several MPI ranks the missing tables are built split across the ranks and sent to
 * the others (egw's binary table file), instead of every rank building every table. */
#ifndef EGW_LAMMPS_TABLES_H
#define EGW_LAMMPS_TABLES_H

#include "egw.h"

#include <mpi.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace LAMMPS_NS {
namespace EgwTables {

/* what a normalised hysteresis table is built for (everything that changes its data) */
struct HystKey {
  int model = 0;
  double mu = 0, psi = 0, K = 0, rho = 0;
  double xmax = 0, tol = 0;    // reach [sigma] and rel_tol
  bool operator<(const HystKey &o) const;
};

/* one table, freed when its last holder (a law, or the registry) lets it go */
using Hyst = std::shared_ptr<struct egw_hysteresis_s>;

/* The tables for keys, in order. Collective over comm (every rank calls with the same
 * keys): a table this process already holds is shared, the others are built with
 * delta_min = 0 (each its own cut-off) on rank i % nprocs, n_threads threads (0: egw's
 * default), and broadcast. On an egw failure fail(message) is called on every rank.
 * n_built (may be null) receives the number of tables built in this call (all ranks). */
std::vector<Hyst> hysteresis(const std::vector<HystKey> &keys, MPI_Comm comm, int n_threads,
                             const std::function<void(const std::string &)> &fail,
                             int *n_built = nullptr);

/* what the 1-D tables of a GW/E-GW law are built for: kind 1 one table at mu, kind 2 the
 * slices of a universal table over [mu_lo, mu_hi] (EgwLaw::TABLE, UNIVERSAL) */
struct SliceKey {
  int kind = 0, model = 0;
  double mu = 0, mu_lo = 0, mu_hi = 0, psi = 0, K = 0, rho = 0, xmax = 0, tol = 0;
  bool operator<(const SliceKey &o) const;
};

/* a law's 1-D tables with what their build found; freed with their last holder */
struct SliceSet {
  std::vector<egw_table> tables;
  double xc = 0, lnmu0 = 0, inv_h = 0, interp_error = 0;
  ~SliceSet();
};
using Slices = std::shared_ptr<SliceSet>;

/* the set built for key in this process before, or null; keep() registers a new one (each
 * rank builds its own: these builds are not split across the ranks) */
Slices find_slices(const SliceKey &key);
void keep_slices(const SliceKey &key, const Slices &set);

/* drop the registry's own reference to every table no law holds (they are freed) */
void purge();

/* tables held by the registry */
int count();

/* The relative error of interpolating force linearly in ln mu between neighbouring nodes
 * of an equally spaced lattice (tables at ln mu_0 + k h, k = 0..n-1, n >= 3), estimated
 * without tables between the nodes: at a midpoint the error of the linear interpolant is
 * h^2/8 |p''|, and h^2 p'' at node k is the second difference p_{k-1} - 2 p_k + p_{k+1};
 * an interval takes the larger estimate of its two ends (one at the lattice's edges).
 * Checked at turning points 2, 10, 0.2 and 0.5 of xmax [sigma] and 6 points down each
 * unloading curve (to the cut-off xc <= 0), relative to the force at the turning point.
 * per_interval (may be null) receives each interval's estimate. */
double lnmu_error_estimate(const std::vector<egw_hysteresis> &nodes, double xc, double xmax,
                           std::vector<double> *per_interval = nullptr);

/* The same error measured against a table built at the interval's midpoint mid (the check
 * the estimate replaces: for tools/hyst_mu_check, which compares the two). */
double lnmu_error_midpoint(egw_hysteresis a, egw_hysteresis b, egw_hysteresis mid, double xc,
                           double xmax);

}    // namespace EgwTables
}    // namespace LAMMPS_NS

#endif
