/* pair_style egw: the normal contact law of one particle-type pair, its parameters and the
 * egw tables that evaluate it (built once per run, scaled per contact by R, E*, sigma). */
#ifndef EGW_LAMMPS_LAW_H
#define EGW_LAMMPS_LAW_H

#include "egw.h"
#include "egw_history.h"
#include "egw_submodels.h"
#include "egw_tables.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace LAMMPS_NS {

/* What a contact's evaluation keeps between steps (pair egw: one per neighbor-list entry;
 * fix wall/egw: one per atom; both emptied when their tables are built): the law and R
 * its position t in the law's nodes in ln mu or ln R belongs to (EgwLaw::position: no log
 * while both are the same), and the inline tables' interval it was last in
 * (EgwTables::Inline::locate: no search while it stays there; any value is safe) */
struct EgwMemo {
  const void *law = nullptr;
  double R = NAN, t = 0.0;
  int interval = -1;
};

/* One body's coefficients as given with pair_coeff (or a wall fix): its material, surface
 * and the contact's sub-models (plain data: written to restart files). */
struct EgwCoeff {
  int set = 0;
  double E = 0, nu = 0, sigma = 0, mu = 0, eta = 0, beta = 0;
  int mu_mode = 0;
  double psi = 0, K = 0.6, rho = 54;
  EgwSubmodels::Params sub;       // damping, tangential, rolling, twisting, heat
  // 'law FILE': the contact's rough-flat law file (empty: GW's law from sigma, mu); kept
  // as characters so that the coefficients stay plain data (restart files, broadcasts)
  static constexpr int LAW_PATH_MAX = 512;
  char law_file[LAW_PATH_MAX] = {};
  // the body's bulk flow pressure p_y [pressure] (0: no bulk yield), given as
  // 'flow_pressure P' (flow_keyword 0) or 'yield_stress Y' (p_y = 1.6 Y, flow_keyword 1).
  // Last: a restart file's record from before them is this struct's prefix
  double flow_pressure = 0;
  int flow_keyword = 0;
};

/* Read the rough-flat law file `path` (egw_flat_law_read) on every rank of comm and check
 * that all ranks read the same law (its nodes, length, modulus and pressures at its ends);
 * a rank that cannot read it, or ranks that disagree, call fail(message) on every rank.
 * The caller frees the law (egw_flat_law_free). */
egw_flat_law egw_law_read_file(const std::string &path, MPI_Comm comm,
                               const std::function<void(const std::string &)> &fail);

/* The contact law of one particle-type pair: parameters and the egw tables that evaluate
 * it.  Tables are normalised (R = E* = sigma = 1, x = delta/sigma) unless stated. */
struct EgwLaw {
  enum Kind { HERTZ = 0, TABLE, UNIVERSAL, HYST, HYST_MU, FLAT, HYST_CAP, HYST_RCAP };
  // eval()'s statuses beyond egw's: the contact's mu lies outside the tables' range; its
  // R is not the one radius a rough + cap law was built for (HYST_RCAP)
  static constexpr int MU_OUTSIDE = -1000;
  static constexpr int R_OTHER = -1001;

  // the coefficients as given or mixed
  double E_star = 0, G_star = 0, sigma = 0;
  int mu_mode = 0;                 // 0 none (smooth), 1 mu given, 2 from summit data
  double mu = 0, eta = 0, beta = 0;
  double psi = 0, K = 0.6, rho = 54;
  // the contact's flow pressure p_y (0: none; the smaller of the two bodies' positive
  // values, combine()) and the keyword that gave it (0 flow_pressure, 1 yield_stress)
  double flow_pressure = 0;
  int flow_keyword = 0;
  // HYST_CAP (a smooth sphere with the cap): first yield delta_y = cap_c R, cap_c =
  // (pi p_y/(2 E*))^2; one table in units of delta_y (R = E* = 1, p_y = 2/pi: delta_y =
  // 1), universal: F = E* sqrt(R) delta_y^1.5 p(delta/delta_y) (doc/theory.md section 12)
  double cap_c = 0;
  // its reach at most CAP_X_MAX delta_y, egw's limit for tables with the cap (a/R is ~70
  // p_y/E* there), its rel_tol at least CAP_TOL_MIN. The reach costs little: the contact is
  // fully capped from ~20 delta_y on, where the unloading curves in s are one shape, so
  // nodes grow about as ln(reach) (egw-table, one thread, no disk cache, doc/benchmarks.md
  // "Stop 57: capreach": 40 -> 1000 delta_y at 1e-3 0.9 -> 1.2 s CPU, 29 -> 39 nodes; at
  // 1e-4 2.1 -> 2.7 s). It was 40 (~60 v_y): e at 76 v_y 2.3 % low, extrapolated, warned
  static constexpr double CAP_X_MAX = 1000.0;
  static constexpr double CAP_TOL_MIN = 1e-5;
  // Beyond a table that reaches at least CAP_FULL_MIN delta_y (the contact fully capped:
  // its elastic edge ring thinner than 1e-7 a from 32 delta_y on, doc/theory.md section 12
  // trap iv) egw continues it by the fully capped continuation (egw_hysteresis_eval_state
  // and egw_hysteresis_energy, status OK: the library's cap_full_reach, the same 35; until
  // stop 64 this plugin's own copy, cap_continue): exact in the cap model, so no reach
  // WARNING there
  static constexpr double CAP_FULL_MIN = 35.0;
  double tol_cap = 0, built_tol = 0;    // the cap table's rel_tol, and the TOL asked for
  double cap_wanted = 0;           // overlap_max R in delta_y (the reach before the cap)
  // HYST_RCAP (a rough model with the cap): the cap's delta_y ~ R next to sigma, so no
  // table normalised by sigma serves every R: hysteresis tables in x = delta/sigma, each
  // built for one equivalent radius with R/sigma and p_y/E* (sigma = E* = 1): F = E*
  // sigma^2 p(x). One table for a law of one radius rcap_R (monodisperse types); for a
  // range of radii, tables at nodes on a lattice in ln(R/sigma) (k h, h = ln 2 / 2^m, as
  // the ln-mu lattice: laws with overlapping ranges share nodes), a contact interpolating
  // its two neighbours linearly in ln R with a state each (as HYST_MU), the level m
  // refined until the estimated interpolation error (LNMU_SAFETY times) is within TOL.
  // The reach: overlap_max R, at most RCAP_X_MAX delta_y of the smallest radius rcap_R_ref
  // (or 30 sigma where that is farther, within egw's 1000 delta_y) (E-GW + cap
  // to 20 delta_y at 1e-3: 3.5 s at sigma = delta_y/100, EP-GW 22 s at delta_y/10 on 2
  // threads, 2026-11-29: builds that grow fast with the reach)
  static constexpr double RCAP_X_MAX = 20.0;
  static constexpr int RCAP_MAX_LEVEL = 5;
  // sigma/delta_y at or below which a rough + cap law takes the Hertz + cap table (its
  // sigma -> 0 limit, smooth_cap_limit) with a WARNING: egw's rough + cap tables do not
  // build there in a run (E-GW, mu 4, p_y = 0.01 E*, TOL 1e-3, one rank, 2026-11-30,
  // bench/rcap_tiny_sigma.py: at 2e-6, 1e-5, 2e-5, 5e-5 an ERROR after 10-33 s (Newton not
  // converged), at 1e-6 and below none after 150 s; 7e-5 and 1e-4 build, 30 s and 23 s
  // under load 9; e at 2 and 5 v_y 1.2e-4 and 1.3e-4 below the smooth cap's there). The
  // smooth cap's force is within ~0.15 (5e-5)^(2/3) = 2e-4 of the rough one's at the limit
  static constexpr double RCAP_SIGMA_MIN = 5e-5;
  /* a rough + cap law (HYST_RCAP) whose sigma is at most RCAP_SIGMA_MIN of the first-yield
   * overlap of its largest equivalent radius R_hi becomes the smooth sphere with the cap
   * (HYST_CAP), the rough model's sigma -> 0 limit; returns the WARNING's text naming
   * sigma/delta_y and the bound of the difference at the smallest radius R_lo (0: R_hi)
   * (empty: the law is unchanged) */
  std::string smooth_cap_limit(double R_lo, double R_hi);
  double rcap_R = 0, rcap_F = 0;   // the (largest) radius, E* sigma^2
  double rcap_R_lo = 0, rcap_R_ref = 0;    // the smallest radius; the reach's delta_y radius
  double lnr0 = 0, inv_hr = 0;     // the first node's ln(R/sigma), 1 / node spacing
  inline int r_position(double R, double &t) const;
  /* mu_position (ln mu nodes) or r_position (ln R nodes, rough + cap) through memo: the
   * t of an earlier call for the same R (no log), else computed and kept there; memo
   * null: computed. The same t to the bit. */
  inline int position(double R, double &t, EgwMemo *memo) const;
  /* the two tables k, k + 1 (hyst) at x interpolated with weight w on k + 1, their states
   * in cache (HYST_MU, HYST_RCAP over radii); *dmax the contact's delta_max [x] */
  inline int eval_two(int k, double w, double x, double *dmax, double *cache, int want_energy,
                      bool states_are_history, double &p, double &dp, double &u) const;
  EgwSubmodels::Params sub;        // damping, tangential, rolling, twisting, heat
  double damp = 0;                 // the damping model's factor (damping_factor)
  double kt = 0;                   // tangential k_t (mindlin NULL: 8 G*)
  double half_inv_E = 0;           // 1/(2 E*): egw's contact radius a = S/(2 E*)
  // evaluation
  int kind = HERTZ;
  double xc = 0;                   // the tables' cut-off delta_c/sigma (<= 0)
  double xt = 0;                   // the contacts' reach delta_t/sigma (xc <= xt <= 0)
  double tail = 0;                 // -delta_t [length]: contacts live while delta > -tail
  double tail_work = 0;            // the loading work the tail holds below delta_t [energy]
  double reach = 0;                // the tables' largest overlap [length] (inf: Hertz)
  bool capped = false;             // reach capped at HYST_X_MAX sigma (hysteresis)
  static constexpr double HYST_X_MAX = 140.0;
  bool capped_solver = false;      // reach capped at TABLE_X_MAX sigma (any table)
  static constexpr double TABLE_X_MAX = 5e14;
  // EP-GW with summit data: the ln-mu lattice's estimate is multiplied by LNMU_SAFETY
  // before it is compared with TOL; at most LNMU_MAX_LEVEL refinements (h = ln 2 / 2^m)
  static constexpr double LNMU_SAFETY = 1.25;
  static constexpr int LNMU_MAX_LEVEL = 6;
  double s05 = 0, s15 = 0, s25 = 0, inv_sigma = 0;
  double mu_lo = 0, mu_hi = 0;     // mu range of the tables (summit data)
  double interp_error = 0;         // measured ln-mu interpolation error (summit data)
  egw_table table = nullptr;
  egw_universal universal = nullptr;
  std::vector<egw_hysteresis> hyst;    // evaluated; owned by hyst_held (shared: egw_tables.h)
  std::vector<EgwTables::Hyst> hyst_held;
  std::vector<double> hyst_tag, hyst_dmax;    // hyst's state tags and delta_max [sigma]
  int hyst_built = 0;              // hysteresis tables this law's build made (others shared)
  std::vector<egw_table> slices;   // 1-D slices of universal at nodes in ln mu (summit data)
  EgwTables::Slices slices_held;   // owns table or slices (shared: egw_tables.h)
  const EgwTables::Inline *fast = nullptr;    // their cubics for the force loop, or null
  double lnmu0 = 0, inv_h = 0;     // first node, 1 / node spacing
  std::vector<double> lnmu;        // nodes of hyst in ln mu (summit data)
  egw_params prm{};                // model, psi, K, rho_p (+ R, E, sigma, mu at eval)
  // FLAT ('law FILE'): tables of the law's sphere at nodes in ln sqrt(R) (mu = 1, so that
  // mu_at(R) = sqrt(R) and mu_position serve), in physical units with E* = flat_modulus;
  // a contact's force is flat_scale sqrt(R) times the tables' F/sqrt(R_k), interpolated
  // geometrically (linear in ln F against ln sqrt(R)) between neighbouring nodes
  std::string law_file;
  double law_modulus = 0;          // the file's E* (0: not known)
  double flat_modulus = 0;         // E* the tables are built with (the file's, else E_star)
  double flat_scale = 1;           // E_star / flat_modulus
  std::vector<egw_table> flat;     // owned
  std::vector<double> flat_inv_sqrt_r;    // 1/sqrt(R_k)
  double tol_built = 0;            // TOL of the FLAT tables' build
  static constexpr size_t FLAT_MAX_TABLES = 33;

  void release();
  /* the tables of `from` (a law with the same coefficients) and what their build found,
   * from build() to set_reach()'s inputs; `from` is left released */
  void take_tables(EgwLaw &from);
  /* the coefficients of two unlike bodies combined (E*, G*, sigma, mu as two types mix);
   * false when they give mu in different ways (mu vs summit data) */
  bool combine(const EgwCoeff &a, const EgwCoeff &b);
  /* the coefficients of one body against itself (like types) */
  void like(const EgwCoeff &c);
  /* the evaluation for egw model `model` from the coefficients (kind, scales, prm) */
  void setup(int model);
  /* the tables for equivalent radii in [R_lo, R_hi] up to overlap_max R_hi (n_threads 0:
   * egw's default). Collective over comm (hysteresis tables are shared and split across
   * the ranks, egw_tables.h). An egw call that fails calls fail(egw's message) on every
   * rank. */
  void build(double R_lo, double R_hi, double tol, double overlap_max, MPI_Comm comm,
             int n_threads, const std::function<void(const std::string &)> &fail);
  /* the hysteresis tables for keys (EgwTables::hysteresis, collective) held by this law:
   * hyst, their tags and reaches; hyst_built counts those built; returns the smallest
   * cut-off */
  double hold_hysteresis(const std::vector<EgwTables::HystKey> &keys, MPI_Comm comm,
                         const std::function<void(const std::string &)> &fail_with);
  /* build() of a rough + cap law (HYST_RCAP): one table (R_lo = R_hi) or the ln-R nodes */
  void build_rcap(double R_lo, double R_hi, double tol, double overlap_max, MPI_Comm comm,
                  const std::function<void(const std::string &)> &fail);
  /* build() of a FLAT law: reads law_file (every rank), sets sigma to its length */
  void build_flat(double R_lo, double R_hi, double tol, double overlap_max, MPI_Comm comm,
                  const egw_options &o, const std::function<void(const std::string &)> &fail);
  /* the contacts' reach delta_t = xt sigma (sets xt, tail, tail_work): the largest overlap
   * below which the loading work of the tail is at most frac * w_ref [energy] for every
   * contact of radius up to R_hi (the tail's work grows with R and mu), never below the
   * tables' cut-off and never above the overlap where the loading force is frac of its
   * value at delta = 0 (a contact forms with at most that force step); w_ref <= 0: the
   * tables' cut-off.  After build(). */
  void set_reach(double w_ref, double frac, double R_hi);
  /* what was built, for the log */
  std::string describe(double R_lo, double R_hi) const;
  /* the contact's mu at R (summit data) */
  double mu_at(double R) const { return mu * std::sqrt(R); }
  inline int mu_position(double R, double &t) const;
  /* elastic normal force F, stiffness S = dF/ddelta and (want_energy) the energy U at
   * overlap delta of a contact of radius R with history hist; EP-GW's two hysteresis
   * states in cache (EgwHistory::HYST_CACHE doubles: filled again from hist's delta_max
   * when they do not hold it, e.g. new, zeroed or another table's); egw's status (EGW_OK,
   * EGW_OUT_OF_RANGE beyond the tables, ...) or MU_OUTSIDE */
  /* memo (may be null): what the contact keeps between steps (EgwMemo; pair egw: per
   * neighbor-list entry), read and updated; the same values with or without it */
  inline int eval(double delta, double R, double *hist, double *cache, double &F, double &S,
                  double &U, int want_energy, bool states_are_history = false,
                  EgwMemo *memo = nullptr) const;
  /* the force loop's common case of eval without energy, for inlining: a GW/E-GW contact
   * inside its inline tables (TABLE, UNIVERSAL with fast): F and S as eval gives them (to
   * the bit), true; otherwise false (nothing written): call eval */
  inline bool eval_tables(double delta, double R, EgwMemo *memo, double &F, double &S) const;
  /* eval_tables, or an EP-GW contact of one table (HYST) whose cache holds its history
   * (served inline by egw_hysteresis_eval_cached, else by one egw call): F, S, the
   * history's delta_max and the state as eval without energy leaves them (to the bit),
   * and eval's status; otherwise -1 (nothing changed): call eval */
  inline int eval_fast(double delta, double R, double *hist, double *cache, EgwMemo *memo,
                       double &F, double &S) const;
  /* wall/egw's eval_fast, its states in hist itself (at EgwHistory::HYST_A): eval_tables,
   * or an EP-GW contact of one table (HYST) by egw_law_hyst_eval on that state (the
   * inline cached test, else one egw call; no switch, no call of eval): F, S, the
   * history and the state as eval without energy leaves them (to the bit), and eval's
   * status; otherwise -1 (nothing changed): call eval */
  inline int eval_hist_fast(double delta, double R, double *hist, EgwMemo *memo, double &F,
                            double &S) const;
  /* the one-table EP-GW step of eval_fast and eval_hist_fast: egw_law_hyst_eval on state
   * (refill: a cache beside the history, else the state in the history), *dmax from it,
   * F and S */
  inline int hyst_step(double delta, double R, double *dmax, double *state, bool refill,
                       double &F, double &S) const;
  /* the same with the states in hist itself (at EgwHistory::HYST_A: wall/egw's layout),
   * where they are the history (all zeros: a new contact) */
  int eval(double delta, double R, double *hist, double &F, double &S, double &U,
           int want_energy, EgwMemo *memo = nullptr) const
  {
    return eval(delta, R, hist, hist + EgwHistory::HYST_A, F, S, U, want_energy, true, memo);
  }
};

extern const char *egw_law_kind_name[];

/* a law's model and kind, for messages: "EP-GW + flow-pressure cap (hysteresis table)" */
std::string egw_law_name(const EgwLaw &L);

/* whether a law's force F and stiffness S are finite (one test each, no libm call): a law
 * whose parameters or table give forces beyond the doubles answers EGW_OK with an inf or a
 * NaN (Hertz's closed form at E* ~ 1e308, a table's absurd node), which the callers stop
 * with an ERROR naming the contact (pair_style egw, fix wall/egw) */
inline bool egw_law_finite(double F, double S)
{
  return __builtin_expect(std::fabs(F) <= DBL_MAX && std::fabs(S) <= DBL_MAX, 1);
}

/* what a user can do about a contact beyond the tables' reach (the warning's advice) */
inline const char *egw_reach_advice(const EgwLaw &L)
{
  if (L.kind == EgwLaw::HYST_RCAP)
    return "the rough + cap table stops at 20 delta_y or 30 sigma, whichever is farther, and "
           "at most 1000 delta_y (the first-yield overlap delta_y = (pi p_y/(2 E*))^2 R): "
           "beyond it the force is the table's extrapolation, not the cap model's";
  if (L.kind == EgwLaw::HYST_CAP)
    return "the flow-pressure cap's table stops at overlap_max R, below 35 delta_y (the "
           "first-yield overlap delta_y = (pi p_y/(2 E*))^2 R), where the contact is not yet "
           "fully capped and no exact continuation follows: beyond it the force is the "
           "table's extrapolation, not the cap model's; raise overlap_max";
  if (L.capped_solver)
    return "the tables stop at 5e14 sigma, within egw's range of delta/sigma (sigma is that "
           "small against the radii; the deep law tends to Hertz there)";
  if (L.capped)
    return "EP-GW's hysteresis tables stop at 140 sigma (the deep law continues them)";
  return "raise 'overlap_max'";
}

/* the position t of the contact's mu = mu(R) in the ln-mu nodes (MU_OUTSIDE beyond them) */
inline int EgwLaw::mu_position(double R, double &t) const
{
  double m = mu_at(R);
  if (!(m >= mu_lo && m <= mu_hi)) return MU_OUTSIDE;
  t = (std::log(m) - lnmu0) * inv_h;
  return EGW_OK;
}

/* the position t of the contact's R in the ln-R nodes of a rough + cap law over radii
 * (R_OTHER beyond them; an end node's R, e.g. R/sigma = 2 on the lattice, within
 * rounding) */
inline int EgwLaw::r_position(double R, double &t) const
{
  t = (std::log(R * inv_sigma) - lnr0) * inv_hr;
  int n = (int) hyst.size();
  if (!(t >= -1e-9 && t <= n - 1 + 1e-9)) return R_OTHER;
  t = std::min(std::max(t, 0.0), n - 1.0);
  return EGW_OK;
}

inline int EgwLaw::position(double R, double &t, EgwMemo *memo) const
{
  if (memo && memo->R == R && memo->law == this) {
    t = memo->t;
    return EGW_OK;
  }
  int st = kind == HYST_RCAP ? r_position(R, t) : mu_position(R, t);
  if (memo && st == EGW_OK) memo->law = this, memo->R = R, memo->t = t;
  return st;
}

/* egw_hysteresis_eval_state at x with the state s. refill: s is a cache that must hold the
 * contact's history xm (delta_max/sigma, -inf for a new contact); one that does not
 * (dropped, or filled for another table, which egw reads as a new contact) is filled again
 * by loading a new contact to xm. Otherwise s is the history itself. */
inline int egw_law_hyst_refill(egw_hysteresis h, double x, double xm, double *s, double &p,
                               double &dp);
inline int egw_law_hyst_eval(egw_hysteresis h, double tag, double dmax, double x, double xm,
                             double *s, double &p, double &dp, bool refill)
{
  // most steps: the state's piece of its unloading curve covers x, or x loads further
  // inside its loading interval (egw.h's inline egw_hysteresis_eval_cached: the steps of
  // egw_hysteresis_eval_state that read only the state, the same values without a call)
  if ((!refill || s[0] == xm) && egw_hysteresis_eval_cached(tag, x, s, &p, &dp))
    return s[0] > dmax ? EGW_OUT_OF_RANGE : EGW_OK;
  if (!refill) return egw_hysteresis_eval_state(h, x, s, &p, &dp);
  return egw_law_hyst_refill(h, x, xm, s, p, dp);
}

/* egw_law_hyst_eval's call of egw when the cache s of history xm did not serve x */
inline int egw_law_hyst_refill(egw_hysteresis h, double x, double xm, double *s, double &p,
                               double &dp)
{
  if (!(s[0] == xm)) {
    egw_hysteresis_state_init(s);
    if (xm > -HUGE_VAL) egw_hysteresis_eval_state(h, xm, s, &p, &dp);
  }
  int st = egw_hysteresis_eval_state(h, x, s, &p, &dp);
  if (s[0] < xm) {    // egw did not know the state (another table's): its history was reset
    egw_hysteresis_state_init(s);
    egw_hysteresis_eval_state(h, xm, s, &p, &dp);
    st = egw_hysteresis_eval_state(h, x, s, &p, &dp);
  }
  return st;
}

inline int EgwLaw::eval_two(int k, double w, double x, double *dmax, double *cache,
                            int want_energy, bool states_are_history, double &p, double &dp,
                            double &u) const
{
  double p0, p1, d0, d1;
  double *sa = cache, *sb = cache + EGW_HYSTERESIS_STATE_SIZE;
  int st = egw_law_hyst_eval(hyst[k], hyst_tag[k], hyst_dmax[k], x, *dmax, sa, p0, d0,
                             !states_are_history);
  int st2 = egw_law_hyst_eval(hyst[k + 1], hyst_tag[k + 1], hyst_dmax[k + 1], x, *dmax, sb,
                              p1, d1, !states_are_history);
  if (st == EGW_OK || st == EGW_OUT_OF_RANGE) st = st2 == EGW_OUT_OF_RANGE ? st : st2;
  *dmax = sa[0];
  double u0 = 0.0, u1 = 0.0;
  if (want_energy) {
    egw_hysteresis_energy(hyst[k], x, sa[0], &u0);
    egw_hysteresis_energy(hyst[k + 1], x, sb[0], &u1);
  }
  p = p0 + w * (p1 - p0), dp = d0 + w * (d1 - d0), u = u0 + w * (u1 - u0);
  return st;
}

#if defined(__GNUC__)
__attribute__((always_inline))
#endif
inline bool EgwLaw::eval_tables(double delta, double R, EgwMemo *memo, double &F,
                                double &S) const
{
  if ((kind != TABLE && kind != UNIVERSAL) || !fast) return false;
  double x = delta * inv_sigma;
  if (!fast->covers(x)) return false;
  int k = 0;
  double w = 0.0, t, p, dp;
  if (kind == UNIVERSAL) {    // eval's steps: the slices' pair, p and dp blended by fast
    if (position(R, t, memo) != EGW_OK) return false;
    int n = (int) slices.size();
    k = std::max(0, std::min(n - 2, (int) t));
    w = t - k;
  }
  fast->eval(x, k, w, p, dp, memo ? &memo->interval : nullptr);
  double sr = E_star * std::sqrt(R);
  F = sr * s15 * p, S = sr * s05 * dp;
  return true;
}

#if defined(__GNUC__)
__attribute__((always_inline))
#endif
inline int EgwLaw::eval_fast(double delta, double R, double *hist, double *cache,
                             EgwMemo *memo, double &F, double &S) const
{
  if (kind != HYST) return eval_tables(delta, R, memo, F, S) ? EGW_OK : -1;
  // eval's HYST steps without energy for a cache that holds the history (a refill of the
  // state's turning point or piece, ~1/3 of the drum's evaluations, skips normal() too)
  double *dmax = &hist[EgwHistory::DELTA_MAX];
  if (!cache || !(cache[0] == *dmax)) return -1;
  return hyst_step(delta, R, dmax, cache, true, F, S);
}

#if defined(__GNUC__)
__attribute__((always_inline))
#endif
inline int EgwLaw::eval_hist_fast(double delta, double R, double *hist, EgwMemo *memo,
                                  double &F, double &S) const
{
  if (kind != HYST) return eval_tables(delta, R, memo, F, S) ? EGW_OK : -1;
  // eval's HYST steps with states_are_history and without energy
  return hyst_step(delta, R, &hist[EgwHistory::DELTA_MAX], hist + EgwHistory::HYST_A, false,
                   F, S);
}

#if defined(__GNUC__)
__attribute__((always_inline))
#endif
inline int EgwLaw::hyst_step(double delta, double R, double *dmax, double *state, bool refill,
                             double &F, double &S) const
{
  double p, dp;
  int st = egw_law_hyst_eval(hyst[0], hyst_tag[0], hyst_dmax[0], delta * inv_sigma, *dmax,
                             state, p, dp, refill);
  *dmax = state[0];
  double sr = E_star * std::sqrt(R);
  F = sr * s15 * p, S = sr * s05 * dp;
  return st;
}

inline int EgwLaw::eval(double delta, double R, double *hist, double *cache, double &F,
                        double &S, double &U, int want_energy, bool states_are_history,
                        EgwMemo *memo) const
{
  using namespace EgwHistory;
  double *dmax = &hist[DELTA_MAX];
  int st = EGW_OK;
  double sr = E_star * std::sqrt(R);
  switch (kind) {
    case HERTZ: {
      if (delta > 0) {
        double a = std::sqrt(R * delta);
        F = 4.0 / 3.0 * E_star * a * delta;
        S = 2.0 * E_star * a;
        U = 0.4 * F * delta;
      } else
        F = S = U = 0.0;
      return EGW_OK;
    }
    case TABLE: {
      double p, dp, u = 0, ac;
      double x = delta * inv_sigma;
      if (fast && fast->covers(x)) {
        // the force from the tables' cubics in every step (egw's values to rounding; with
        // or without energy, so that output steps do not change a trajectory)
        fast->eval(x, 0, 0.0, p, dp, memo ? &memo->interval : nullptr);
        if (want_energy) egw_table_eval_all(table, x, nullptr, nullptr, &u, nullptr);
      } else if (want_energy) {
        st = egw_table_eval_all(table, x, &p, &dp, &u, &ac);
      } else {
        st = egw_table_eval(table, x, &p, &dp);
      }
      F = sr * s15 * p, S = sr * s05 * dp, U = sr * s25 * u;
      break;
    }
    case UNIVERSAL: {
      double t;
      if (position(R, t, memo) != EGW_OK) return MU_OUTSIDE;
      int n = (int) slices.size();
      int k = std::max(0, std::min(n - 2, (int) t));
      double w = t - k;
      double x = delta * inv_sigma, p0, p1, d0, d1, u0 = 0, u1 = 0, ac;
      if (fast && fast->covers(x)) {    // as TABLE; p0, d0 already interpolated in ln mu
        fast->eval(x, k, w, p0, d0, memo ? &memo->interval : nullptr);
        p1 = p0, d1 = d0;
        if (want_energy) {
          egw_table_eval_all(slices[k], x, nullptr, nullptr, &u0, nullptr);
          egw_table_eval_all(slices[k + 1], x, nullptr, nullptr, &u1, nullptr);
        }
      } else if (want_energy) {
        st = egw_table_eval_all(slices[k], x, &p0, &d0, &u0, &ac);
        egw_table_eval_all(slices[k + 1], x, &p1, &d1, &u1, &ac);
      } else {
        st = egw_table_eval(slices[k], x, &p0, &d0);
        egw_table_eval(slices[k + 1], x, &p1, &d1);
      }
      F = sr * s15 * (p0 + w * (p1 - p0));
      S = sr * s05 * (d0 + w * (d1 - d0));
      U = sr * s25 * (u0 + w * (u1 - u0));
      break;
    }
    case HYST:
    case HYST_RCAP:
    case HYST_CAP: {
      // one table (HYST_MU below interpolates two), its state (table units) with its
      // turning point's cache in cache[0..23]; x in the table's unit of length with the
      // force, stiffness and energy units: HYST sigma, E* sqrt(R) sigma^1.5; HYST_RCAP
      // sigma, E* sigma^2 (the table of this law's one radius); HYST_CAP the contact's
      // first yield delta_y = cap_c R, E* sqrt(R) delta_y^1.5
      double x, fF, fS, fU, top = hyst_dmax[0];
      if (kind == HYST) {
        x = delta * inv_sigma, fF = sr * s15, fS = sr * s05, fU = sr * s25;
      } else if (kind == HYST_RCAP) {
        x = delta * inv_sigma, fF = rcap_F, fS = rcap_F * inv_sigma, fU = rcap_F * sigma;
        if (hyst.size() > 1) {    // tables at nodes in ln R: the contact's two neighbours
          double t, p, dp, u;
          if (position(R, t, memo) != EGW_OK) return R_OTHER;
          int k = std::min((int) hyst.size() - 2, (int) t);
          st = eval_two(k, t - k, x, dmax, cache, want_energy, states_are_history, p, dp, u);
          F = fF * p, S = fS * dp, U = fU * u;
          break;
        }
        if (!(std::fabs(R - rcap_R) <= 1e-9 * rcap_R)) return R_OTHER;
      } else {
        double s = cap_c * R, sq = sr * std::sqrt(s);    // E* sqrt(R) delta_y^0.5
        x = delta / s, fF = sq * s, fS = sq, fU = sq * s * s;
        // beyond a table to CAP_FULL_MIN delta_y or more egw continues it, status OK: its
        // unloading pieces there (served inline too) are not out of range
        if (top >= CAP_FULL_MIN) top = HUGE_VAL;
      }
      double p, dp;
      st = egw_law_hyst_eval(hyst[0], hyst_tag[0], top, x, *dmax, cache, p, dp,
                             !states_are_history);
      *dmax = cache[0];
      // the energy the contact returns if it separates now (the rest of its loading work
      // is dissipated): kinetic + this falls while contacts load, stays while they unload
      double u = 0.0;
      if (want_energy) egw_hysteresis_energy(hyst[0], x, cache[0], &u);
      F = fF * p, S = fS * dp, U = fU * u;
      break;
    }
    case FLAT: {
      double t;
      if (position(R, t, memo) != EGW_OK) return MU_OUTSIDE;
      int n = (int) flat.size();
      int k = std::max(0, std::min(n - 2, (int) t));
      double w = n > 1 ? t - k : 0.0;
      int k1 = n > 1 ? k + 1 : k;
      double f0, f1, d0, d1, u0 = 0, u1 = 0, ac;
      if (want_energy) {
        st = egw_table_eval_all(flat[k], delta, &f0, &d0, &u0, &ac);
        egw_table_eval_all(flat[k1], delta, &f1, &d1, &u1, &ac);
      } else {
        st = egw_table_eval(flat[k], delta, &f0, &d0);
        egw_table_eval(flat[k1], delta, &f1, &d1);
      }
      // geometric in R (linear in ln F): exact where F is a power of R, as Hertz's
      // (F/sqrt(R) constant) and a rigid sphere's on the law's exponential end (F ~ R)
      double s = flat_scale * std::sqrt(R);
      double g0 = f0 * flat_inv_sqrt_r[k], g1 = f1 * flat_inv_sqrt_r[k1];
      auto geo = [w](double a, double b) {
        return a > 0 && b > 0 ? a * std::exp(w * std::log(b / a)) : a + w * (b - a);
      };
      double g = geo(g0, g1);
      F = s * g;
      S = f0 > 0 && f1 > 0 ? F * ((1.0 - w) * d0 / f0 + w * d1 / f1)
                           : s * ((1.0 - w) * d0 * flat_inv_sqrt_r[k] +
                                  w * d1 * flat_inv_sqrt_r[k1]);
      U = s * geo(u0 * flat_inv_sqrt_r[k], u1 * flat_inv_sqrt_r[k1]);
      break;
    }
    case HYST_MU: {
      double x = delta * inv_sigma;
      double t;
      if (position(R, t, memo) != EGW_OK) return MU_OUTSIDE;
      int n = (int) hyst.size();
      int k = std::max(0, std::min(n - 2, (int) t));
      double p, dp, u;
      st = eval_two(k, t - k, x, dmax, cache, want_energy, states_are_history, p, dp, u);
      F = sr * s15 * p, S = sr * s05 * dp, U = sr * s25 * u;
      break;
    }
  }
  return st;
}

}    // namespace LAMMPS_NS

#endif
