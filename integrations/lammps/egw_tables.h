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

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
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
  // > 0: Hertz with the flow-pressure cap (sigma 0, R = E* = 1, p_y = flow_pressure; the
  // reach in units of length, i.e. of delta_y = (pi p_y/2)^2 for p_y = 2/pi)
  double flow_pressure = 0;
  // > 0 with flow_pressure: a rough model with the cap for one equivalent radius, R/sigma
  // (sigma = E* = 1, p_y = flow_pressure/E*: the reach in units of sigma)
  double radius = 0;
  bool operator<(const HystKey &o) const;
};

/* one table, freed when its last holder (a law, or the registry) lets it go */
using Hyst = std::shared_ptr<struct egw_hysteresis_s>;

/* The OpenMP team of egw's table builds while it lives (egw builds its tables' points and
 * curves in OpenMP loops of the default team): n_threads, or with 0 every processor this
 * process may run on (omp_get_num_procs: its affinity mask), whatever OMP_NUM_THREADS says
 * (build/lammps/lmp sets it to 1 for the force loop, which would leave a single rank's
 * set-up on one core); the team before is restored at the end. */
struct BuildThreads {
  explicit BuildThreads(int n_threads);
  ~BuildThreads();
  BuildThreads(const BuildThreads &) = delete;
  BuildThreads &operator=(const BuildThreads &) = delete;
  int before;
};

/* The tables for keys, in order. Collective over comm (every rank calls with the same
 * keys): a table this process already holds is shared, the others are built with
 * delta_min = 0 (each its own cut-off) on rank i % nprocs, n_threads threads (0: the
 * processors of the node shared among its ranks that build at the same time; a rank
 * without a table to build waits without spinning; a single rank builds several tables
 * side by side, one thread each), and broadcast. On an egw failure
 * fail(message) is called on every rank.
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

/* A set of 1-D tables' cubics copied out of egw (egw_table_get_interpolant) for
 * evaluation inside the force loop, without a library call. The slices of one universal
 * table share their nodes, so a contact finds its interval once for both of its slices and,
 * where they interpolate p, blends their cubics into one (the value of interpolating their
 * forces linearly in ln mu, to rounding); in the separated tail, where they interpolate
 * ln p, it takes egw's resampled pieces of cubics in p (egw_table_get_tail: below), so
 * there too one blended cubic and no exp (ln-p intervals above 0, or a tail egw does not
 * resample: both exps). Serves cut-off < x < last node; egw_table_eval the rest (0 below,
 * deep overlaps, energy). n = 0: the tables' nodes differ, egw_table_eval serves
 * everything. */
struct Inline {
  int n = 0, n_log = 0, ns = 0;    // nodes, intervals of ln p (the first ones), tables
  double x_lo = 0, x_hi = 0;       // first and last node [sigma]
  std::vector<double> x;           // nodes [sigma]
  std::vector<double> c;           // interval i, table k: c[4 (i ns + k) + 0..3]
  std::vector<int> bucket;         // the interval holding each bucket's start
  double origin = 0, scale = 0;
  int nb = 0;
  bool log_buckets = false;        // buckets uniform in bucket_coord (tables reaching far)
  // The separated tail (x_lo to tail_end, the last node <= 0, where the tables hold ln p)
  // as egw_table_get_tail hands it out: n_piece equal pieces, on each every table's cubic
  // in p (one table: egw_table_eval's own pieces, so the same values bit for bit; the
  // slices of a universal table: one grid on which each slice meets egw's tail tolerance,
  // 2.5e-2 rel_tol of its ln-p interpolant at egw's check points). Without them (egw
  // refuses: no ln-p interval below 0, or a tail beyond egw's 8192 pieces) tail_end = x_lo:
  // the exps. A contact there finds its piece by one multiplication and takes no exp;
  // between two slices one blended cubic, as above 0.
  int n_piece = 0;
  double tail_end = 0, piece_scale = 0;
  std::vector<double> piece_x;     // the pieces' starts
  std::vector<double> piece_c;     // piece q, table k: piece_c[4 (q ns + k) + 0..3]
  /* a monotone coordinate: x below 1, above it 1 + log2(x) with the mantissa taken
   * linearly (exact at powers of 2; from the double's bits, no library call), so that a
   * table over many decades (sigma -> 0: x up to 5e14) gets buckets per octave */
  static double bucket_coord(double xv)
  {
    if (!(xv >= 1.0)) return xv;
    std::uint64_t b;
    std::memcpy(&b, &xv, sizeof b);
    return (double) (int) (b >> 52) - 1022.0 +
        (double) (b & ((std::uint64_t(1) << 52) - 1)) * 0x1p-52;
  }
  /* the interval i with x[i] <= xv < x[i + 1], for x_lo < xv < x_hi; hint (may be null):
   * an interval to try first (any int: checked), set to the one found (a contact moves
   * little between steps: mostly no search) */
  int locate(double xv, int *hint) const
  {
    if (hint) {
      int i = *hint;
      if (i >= 0 && i < n - 1 && x[i] <= xv && xv < x[i + 1]) return i;
      return *hint = locate(xv);
    }
    return locate(xv);
  }
  int locate(double xv) const
  {
    double u = log_buckets ? bucket_coord(xv) : xv;
    int b = std::min(nb - 1, (int) ((u - origin) * scale));
    int i = bucket[b];
    while (xv >= x[i + 1]) i++;
    return i;
  }
  /* fill from tables (false, n = 0: their nodes or ln-p intervals differ) */
  bool make(const std::vector<egw_table> &tables);
  bool covers(double xv) const { return xv > x_lo && xv < x_hi; }    // false when n = 0
  /* p and dp/dx at x (covers(x)) of table k, or (ns > 1) of tables k and k + 1
   * interpolated linearly in ln mu with weight w on k + 1; hint: locate()'s */
#if defined(__GNUC__)
  __attribute__((always_inline))
#endif
  void eval(double xv, int k, double w, double &p, double &dp, int *hint = nullptr) const
  {
    if (xv < tail_end) {    // a piece of the resampled tail: cubics in p
      int q = std::min(n_piece - 1, (int) ((xv - x_lo) * piece_scale));
      double t = xv - piece_x[q];
      cubic_p(&piece_c[4 * (q * ns + k)], t, w, p, dp);
      return;
    }
    int i = locate(xv, hint);
    double t = xv - x[i], t2 = t * t;
    const double *a = &c[4 * (i * ns + k)];
    // egw's cubic in Estrin's form, as egw_table_eval evaluates it
    if (ns == 1) {
      double v = (a[0] + t * a[1]) + t2 * (a[2] + t * a[3]);
      double d = (a[1] + 2 * t * a[2]) + 3 * t2 * a[3];
      if (i < n_log) p = std::exp(v), dp = p * d;
      else p = v, dp = d;
      return;
    }
    const double *b = a + 4;    // table k + 1, same interval
    if (i < n_log) {
      double v0 = (a[0] + t * a[1]) + t2 * (a[2] + t * a[3]);
      double v1 = (b[0] + t * b[1]) + t2 * (b[2] + t * b[3]);
      double d0 = (a[1] + 2 * t * a[2]) + 3 * t2 * a[3];
      double d1 = (b[1] + 2 * t * b[2]) + 3 * t2 * b[3];
      double p0 = std::exp(v0), p1 = std::exp(v1);
      p = p0 + w * (p1 - p0);
      dp = p0 * d0 + w * (p1 * d1 - p0 * d0);
      return;
    }
    cubic_p(a, t, w, p, dp);
  }
  /* p and dp/dx of the cubic in p at a (ns == 1), or (ns > 1) of the cubics at a and a + 4
   * blended with weight w on the second (the blended cubic is the blend of their values) */
#if defined(__GNUC__)
  __attribute__((always_inline))
#endif
  void cubic_p(const double *a, double t, double w, double &p, double &dp) const
  {
    double t2 = t * t;
    if (ns == 1) {
      p = (a[0] + t * a[1]) + t2 * (a[2] + t * a[3]);
      dp = (a[1] + 2 * t * a[2]) + 3 * t2 * a[3];
      return;
    }
    const double *b = a + 4;
    double c0 = a[0] + w * (b[0] - a[0]), c1 = a[1] + w * (b[1] - a[1]);
    double c2 = a[2] + w * (b[2] - a[2]), c3 = a[3] + w * (b[3] - a[3]);
    p = (c0 + t * c1) + t2 * (c2 + t * c3);
    dp = (c1 + 2 * t * c2) + 3 * t2 * c3;
  }
  /* fill piece_x, piece_c from egw_table_get_tail (make()): false where egw refuses */
  bool take_tail(const std::vector<egw_table> &tables);
};

/* a law's 1-D tables with what their build found; freed with their last holder */
struct SliceSet {
  std::vector<egw_table> tables;
  double xc = 0, lnmu0 = 0, inv_h = 0, interp_error = 0;
  Inline fast;                     // their cubics, for the force loop
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
