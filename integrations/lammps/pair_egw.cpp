/* pair_style egw: egw's rough-sphere contact law as a LAMMPS granular pair style.
 *
 *   pair_style egw MODEL TOL [rmin R] [rmax R] [overlap_max F] [tail_energy W]
 *   pair_coeff I J E v nu v sigma v [mu v | summit_density v summit_radius v] [psi v]
 *              [K v] [plastic_ratio v] [damping e] [friction mu_t]
 *   pair_coeff I J E v nu v law FILE [damping e] [friction mu_t]   (a rough-flat law file)
 *
 * Normal force: egw's tables scaled per contact by R, E*, sigma (exact for any radius
 * distribution); EP-GW keeps each contact's delta_max; damping in the coeff_restitution
 * convention of pair granular with egw's stiffness; Mindlin friction with the Coulomb
 * limit.  Histories live in a fix NEIGH_HISTORY (as pair granular's).  The physics and its
 * error bounds: integrations/lammps/README.md.  This file: the pair style's life cycle, its
 * tables per run, compute() and single(); the law in egw_law.*, the sub-models in
 * egw_submodels.h, the histories in egw_history.h, coefficients in pair_egw_coeff.cpp,
 * restart in pair_egw_history.cpp. */
#include "pair_egw.h"
#include "egw_history.h"
#include "egw_contact.h"
#include "egw_submodels.h"
#include "fix_egw_reach.h"

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
#include <cstdint>
#include <cstring>

using namespace LAMMPS_NS;
using namespace EgwHistory;

/* ---------------------------------------------------------------------- */

PairEGW::PairEGW(LAMMPS *lmp) : Pair(lmp)
{
  single_enable = 1;
  // single(): granular's 12 (tangential force, rolling, twisting, x_i - x_j), then egw's
  // overlap, delta_max, stiffness, elastic and damping normal force
  single_extra = 17;
  svector = new double[single_extra];
  no_virial_fdotr_compute = 1;
  restartinfo = 1;
  finitecutflag = 1;
  beyond_contact = 1;                 // the rough tail acts before the spheres touch
  nondefault_history_transfer = 1;    // delta_max is not negated for the partner's copy
  model = EGW_MODEL_EGW;
  nhist = NHIST_BASE;
  hist_sub = -1;
  heat_any = false;
  hyst_any = false;
  tol = 1e-4;
  rmin_user = rmax_user = 0.0;
  overlap_max = 1.0;    // granular decks reach 0.57 R in a pour
  tail_energy = 0.0;    // contacts reach the tables' cut-off
  fix_history = nullptr;
  list_was_size = false, list_trigger = -1.0;
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
  if (modify->get_fix_by_id("EGW_REACH")) modify->delete_fix("EGW_REACH");
  for (auto &row : law)
    for (auto &l : row) l.release();
  EgwTables::purge();
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
  // rmin/rmax given: they are the range (an atom or insertion outside it is an error)
  for (int t = 1; t <= n; t++) {
    if (rmax_user > 0 && rad_max[t] > rmax_user)
      error->all(FLERR, "Pair egw: type {} has radius {} above rmax = {} (pair_style egw ... "
                        "rmax; atoms and fix pour/deposit insertions count)", t, rad_max[t],
                 rmax_user);
    if (rmin_user > 0 && rad_min[t] != HUGE_VAL && rad_min[t] < rmin_user)
      error->all(FLERR, "Pair egw: type {} has radius {} below rmin = {} (pair_style egw ... "
                        "rmin)", t, rad_min[t], rmin_user);
    if (rmax_user > 0) rad_max[t] = rmax_user;
    if (rad_min[t] == HUGE_VAL || rad_min[t] > rad_max[t]) rad_min[t] = 0.5 * rad_max[t];
    if (rmin_user > 0) rad_min[t] = rmin_user;
  }
}

/* build the tables of law (i, j) for equivalent radii in [R_lo, R_hi] */
void PairEGW::build_tables(int i, int j, double R_lo, double R_hi)
{
  EgwLaw &L = law[i][j];
  std::string what = fmt::format("tables of types {} {}", i, j);
  L.build(R_lo, R_hi, tol, overlap_max, world, comm->nprocs > 1 ? 1 : 0,
          [&](const std::string &msg) { error->all(FLERR, "Pair egw: {}: {}", what, msg); });
  built_rlo[i][j] = R_lo, built_rhi[i][j] = R_hi;
  if (comm->me == 0)
    utils::logmesg(lmp, "pair egw: types {} {}: {}\n", i, j, L.describe(R_lo, R_hi));
}

void PairEGW::init_style()
{
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "Pair egw requires atom_style sphere (radius, rmass, omega, torque)");
  if (comm->ghost_velocity == 0)
    error->all(FLERR, "Pair egw requires ghost atoms store velocity: use 'comm_modify vel yes'");

  // the histories: the normal law's, then the sub-models' if any type pair needs them
  // (pair_style or pair_coeff given again with another size: every history starts afresh)
  int ntypes = atom->ntypes;
  bool extra = false;
  heat_any = false;
  for (int i = 1; i <= ntypes; i++)
    for (int j = i; j <= ntypes; j++)
      if (pcoeff[i][j].set) {
        extra = extra || pcoeff[i][j].sub.needs_extra_history();
        heat_any = heat_any || pcoeff[i][j].sub.heat != EgwSubmodels::HEAT_NONE;
      }
  int core = NHIST_BASE;    // EP-GW's hysteresis states: beside the list (hyst_cache)
  hist_sub = extra ? core : -1;
  int want = core + (extra ? EgwSubmodels::NHIST_SUB : 0);
  if (heat_any && (!atom->temperature_flag || !atom->heatflow_flag))
    error->all(FLERR, "Pair egw: a heat model needs atoms with temperature and heatflow "
                      "(atom_style sphere/temp, or fix property/atom temperature heatflow)");
  bool wall_heat = false;
  for (auto f : modify->get_fix_by_style("^wall/egw")) {
    auto w = dynamic_cast<EgwHeatWall *>(f);
    wall_heat = wall_heat || (w && w->has_heat());
  }
  if (!heat_any && !wall_heat && !modify->get_fix_by_style("^heat/flow").empty())
    error->all(FLERR, "Pair egw: fix heat/flow needs a heat model in pair_coeff or a fix "
                      "wall/egw (heat area h_s or heat radius k_s): without one no heat flows "
                      "between contacts");
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
  EgwTables::purge();    // tables no law holds since the last run
  int n = atom->ntypes;
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) {
      if (!setflag[i][j] && !(pcoeff[i][i].set && pcoeff[j][j].set)) continue;
      double rlo_i = rad_min[i], rlo_j = rad_min[j], rhi_i = rad_max[i], rhi_j = rad_max[j];
      double R_hi = rhi_i > 0 && rhi_j > 0 ? rhi_i * rhi_j / (rhi_i + rhi_j) : 0.0;
      double R_lo = rlo_i > 0 && rlo_j > 0 ? rlo_i * rlo_j / (rlo_i + rlo_j) : 0.0;
      make_law(i, j, R_lo, R_hi);
      EgwLaw &L = law[i][j];
      bool needs_r = L.kind == EgwLaw::UNIVERSAL || L.kind == EgwLaw::HYST_MU ||
          L.kind == EgwLaw::FLAT || L.kind == EgwLaw::HYST_RCAP;
      if (needs_r && !(R_hi > 0))
        error->all(FLERR, "Pair egw: types {} {}: no atoms and no fix pour/deposit give their "
                          "radii (needed for {}): add 'rmin R rmax R' to pair_style",
                   i, j, L.kind == EgwLaw::FLAT ? "a law's tables"
                       : L.kind == EgwLaw::HYST_RCAP ? "a rough surface with flow_pressure"
                                                     : "mu from summit data");
      if (!(R_hi > 0)) R_hi = R_lo = 1.0 / std::max(L.inv_sigma, 1e-300);
      if (R_lo > R_hi) R_lo = R_hi;
      // a rough + cap law of one radius (monodisperse types) is one table for it; every
      // other law of one radius gets a margin (tables over a range of mu or R)
      bool one_radius = L.kind == EgwLaw::HYST_RCAP && rlo_i == rhi_i && rlo_j == rhi_j;
      if (R_lo == R_hi && !one_radius) R_lo = R_hi / 1.05;
      bool covered = built_rhi[i][j] > 0 &&
          (!needs_r || (R_lo >= built_rlo[i][j] && R_hi <= built_rhi[i][j]));
      if (!covered) build_tables(i, j, R_lo, R_hi);
      // the contacts' reach from the energy the tail holds (cheap: every run)
      double tail_old = L.tail;
      L.set_reach(tail_energy, tol, built_rhi[i][j]);
      if (comm->me == 0 && L.kind != EgwLaw::HERTZ && L.kind != EgwLaw::HYST_CAP &&
          (!covered || L.tail != tail_old))
        utils::logmesg(lmp, "pair egw: types {} {}: contacts reach delta_t = {:.6g} ({:.4g} "
                            "sigma; the tables' cut-off {:.4g} sigma), the tail's loading work "
                            "below it {:.3g}{}\n", i, j, -L.tail, L.xt, L.xc, L.tail_work,
                       tail_energy > 0
                           ? fmt::format(" (<= TOL x tail_energy = {:.3g})", tol * tail_energy)
                           : std::string(" (tail_energy 0: the tables' cut-off)"));
    }
  // a law file without its modulus holds pressures for one E* only: every type pair using
  // it must have that E* (a '# modulus = E*' line in the file lets egw scale it instead)
  std::vector<std::pair<int, int>> flat_pairs;
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++)
      if (law[i][j].kind == EgwLaw::FLAT && !(law[i][j].law_modulus > 0))
        flat_pairs.emplace_back(i, j);
  for (auto &a : flat_pairs)
    for (auto &b : flat_pairs) {
      const EgwLaw &A = law[a.first][a.second], &B = law[b.first][b.second];
      if (A.law_file != B.law_file || std::fabs(A.E_star - B.E_star) <= 1e-12 * A.E_star)
        continue;
      error->all(FLERR, "Pair egw: law {} has no modulus line, so its pressures fit one E* "
                        "only, but types {} {} have E* = {} and types {} {} E* = {}: add "
                        "'# modulus = <the E* it was made with>' to the file (egw then scales "
                        "it to each E*) or use one file per E*",
                 A.law_file, a.first, a.second, A.E_star, b.first, b.second, B.E_star);
    }
  hyst_any = memo_any = false;
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) {
      const EgwLaw &L = law[i][j];
      memo_any = memo_any || L.kind == EgwLaw::TABLE || L.kind == EgwLaw::UNIVERSAL ||
          L.kind == EgwLaw::HYST_MU || L.kind == EgwLaw::FLAT ||
          (L.kind == EgwLaw::HYST_RCAP && L.hyst.size() > 1);
    }
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++)
      hyst_any = hyst_any || law[i][j].kind == EgwLaw::HYST ||
          law[i][j].kind == EgwLaw::HYST_MU || law[i][j].kind == EgwLaw::HYST_CAP ||
          law[i][j].kind == EgwLaw::HYST_RCAP;
  // one state per block unless a law interpolates two tables (the blocks of an earlier run
  // are dropped when that changes: their contacts refill from their histories)
  int stride = EGW_HYSTERESIS_STATE_SIZE;
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++)
      if (law[i][j].kind == EgwLaw::HYST_MU ||
          (law[i][j].kind == EgwLaw::HYST_RCAP && law[i][j].hyst.size() > 1))
        stride = HYST_CACHE;
  if (stride != hyst_stride) {
    hyst_stride = stride;
    hyst_cache.clear(), hyst_cache_tags.clear(), hyst_live.clear(), hyst_free.clear();
    rows_calls = -1;
  }
  law_of.assign((n + 1) * (n + 1), nullptr);
  tail_of.assign((n + 1) * (n + 1), 0.0);
  for (int i = 1; i <= n; i++)
    for (int j = 1; j <= n; j++) {
      EgwLaw &L = law[std::min(i, j)][std::max(i, j)];
      law_of[i * (n + 1) + j] = &L;
      tail_of[i * (n + 1) + j] = L.tail;
    }
  entry_memo.clear(), rows_calls = -1;    // positions in this run's tables
  tables_ready = true;
  request_list();
}

/* A half list with per-neighbor history. A size list (the pairs within R_i + R_j + skin at
 * the build, as pair granular's) when the rough tail reaches at most skin/4 beyond touching
 * and fix EGW_REACH rebuilds it before any pair can have closed in by skin - tail (the two
 * largest displacements since the build add up to it; LAMMPS's own check, one atom moved
 * skin/2, comes later); otherwise a plain list to the types' largest radii + tail + skin
 * (more pairs: every pair of a polydisperse type's smaller grains, ~45 % more in the pour).
 * The guard needs post_integrate before each step's Neighbor::decide() and a box whose
 * images do not move: a run with the Verlet family and no fix that changes the box. */
/* why request_list() took the plain list, for the log */
std::string PairEGW::plain_reason(double tail_max, const std::string &box_fixes) const
{
  std::vector<std::string> why;
  if (tail_max > 0.25 * neighbor->skin)
    why.push_back(fmt::format("the tail {:.6g} > skin/4 = {:.6g}", tail_max,
                              0.25 * neighbor->skin));
  if (update->whichflag != 1) why.push_back("not a run (a minimization)");
  if (utils::strmatch(update->integrate_style, "^respa")) why.push_back("run_style respa");
  if (!box_fixes.empty()) why.push_back(box_fixes + " changes the box");
  if (neighbor->build_once) why.push_back("neigh_modify once yes");
  std::string s;
  for (auto &w : why) s += (s.empty() ? "" : "; ") + w;
  return s;
}

void PairEGW::request_list()
{
  double tail_max = 0.0;
  for (double t : tail_of) tail_max = std::max(tail_max, t);
  // a fix that changes the box moves the periodic images and so the pairs' distances
  // without moving the atoms; one that changes only the sub-domains (fix balance:
  // BOX_CHANGE_DOMAIN, atoms migrating on reneighboring steps) does not
  std::string box_fixes;
  for (auto f : modify->get_fix_list())
    if (f->box_change & ~Fix::BOX_CHANGE_DOMAIN)
      box_fixes += fmt::format("{}fix {} ({})", box_fixes.empty() ? "" : ", ", f->id, f->style);
  bool guard_works = update->whichflag == 1 && !utils::strmatch(update->integrate_style, "^respa")
      && box_fixes.empty() && !neighbor->build_once;
  bool size = !(tail_max > 0) || (guard_works && tail_max <= 0.25 * neighbor->skin);
  double trigger = size && tail_max > 0 ? neighbor->skin - tail_max : 0.0;
  if (size) neighbor->add_request(this, NeighConst::REQ_SIZE | NeighConst::REQ_HISTORY);
  else neighbor->add_request(this, NeighConst::REQ_HISTORY);
  // found by its ID on every run (the pointer of an earlier run may be gone with 'unfix')
  auto reach = dynamic_cast<FixEGWReach *>(modify->get_fix_by_id("EGW_REACH"));
  if (trigger > 0 && reach == nullptr)
    reach = dynamic_cast<FixEGWReach *>(modify->add_fix("EGW_REACH all EGW_REACH", 1));
  if (reach) reach->set_limit(trigger);
  if (comm->me == 0 && (size != list_was_size || trigger != list_trigger))
    utils::logmesg(lmp, "pair egw: {}\n",
                   size ? (trigger > 0 ? fmt::format("a size neighbor list, rebuilt once two "
                                                     "atoms may have closed in by skin - tail = "
                                                     "{:.6g} (the tail: {:.6g})", trigger,
                                                     tail_max)
                                       : std::string("a size neighbor list"))
                        : fmt::format("a neighbor list to the types' largest radii + the tail "
                                      "{:.6g} + skin (a size list needs the tail <= skin/4 "
                                      "and a Verlet run, reneighboring, with a fixed box; "
                                      "here: {})", tail_max, plain_reason(tail_max,
                                      box_fixes)));
  list_was_size = size, list_trigger = trigger;
}

double PairEGW::init_one(int i, int j)
{
  int a = std::min(i, j), b = std::max(i, j);
  if (!setflag[a][b] && !(pcoeff[a][a].set && pcoeff[b][b].set))
    error->all(FLERR, "Pair egw: coefficients of types {} {} not set", i, j);
  const EgwLaw &L = law[a][b];
  if (i != j) law[j][i] = EgwLaw();    // unused: compute() reads law[min][max]
  double cut = rad_max[i] + rad_max[j] + L.tail;
  if (!(rad_max[i] > 0) || !(rad_max[j] > 0)) {
    // a type with no radius yet has no contacts; the cut-off still reaches as far as the
    // largest type's own, so that pair_write calls single(), which says why it cannot write
    double big = *std::max_element(rad_max.begin(), rad_max.end());
    cut = 2.0 * big + L.tail;
  }
  if (!(cut > 0)) cut = 2.0 * L.tail + 1e-300;
  return cut;
}

/* ---------------------------------------------------------------------- */

/* the elastic normal force of a contact from its law; out-of-range overlaps warn once,
 * a mu outside the tables or a failed evaluation stop the run */
inline void PairEGW::normal(EgwLaw &L, double delta, double R, double *hist, double *cache,
                            double &F, double &S, double &U, int want_energy, EgwMemo *memo)
{
  int st = L.eval(delta, R, hist, cache, F, S, U, want_energy, false, memo);
  if (st != EGW_OK) report(L, st, delta, R);
}

/* what normal() says about an evaluation's status other than EGW_OK */
void PairEGW::report(const EgwLaw &L, int st, double delta, double R)
{
  if (st == EgwLaw::MU_OUTSIDE)
    error->one(FLERR, "Pair egw: contact with R = {} has mu = {} outside the tables' "
                      "[{}, {}]: widen the radius range with pair_style egw ... rmin/rmax",
               R, L.mu_at(R), L.mu_lo, L.mu_hi);
  if (st == EgwLaw::R_OTHER)
    error->one(FLERR, "Pair egw: contact with R = {} but its rough + cap law (flow_pressure "
                      "with sigma > 0) was built for R in [{}, {}] only (atoms of another "
                      "radius added after the run's set-up?): give the types' radius range "
                      "with pair_style egw ... rmin/rmax", R, L.rcap_R_lo, L.rcap_R);
  if (st == EGW_OUT_OF_RANGE && !warned_range) {
    warned_range = true;
    error->warning(FLERR, "Pair egw: overlap {:.6g} = {:.3g} R (R = {:.6g}) beyond the tables' "
                          "reach {:.6g} (overlap_max = {} of the type pair's largest R): force "
                          "from egw's deep-overlap law above its last node; {} (warned once)",
                   delta, delta / R, R, L.reach, overlap_max, egw_reach_advice(L));
  }
  if (st != EGW_OK && st != EGW_OUT_OF_RANGE) {
    char buf[512];
    egw_last_error(buf, sizeof(buf));
    error->one(FLERR, "Pair egw: evaluation failed at overlap {}: {}", delta, buf);
  }
}

/* a law's force or stiffness that is not finite with status OK (egw_law_finite): an ERROR
 * naming the pair, the overlap and the law, before it reaches the atoms' forces */
void PairEGW::not_finite(const EgwLaw &L, int i, int j, double delta, double R, double F,
                         double S)
{
  error->one(FLERR, "Pair egw: atoms {} and {} (types {} {}), overlap {} (R = {}): the normal "
                    "law {} gave force {} and stiffness {}, not finite: its parameters (E, "
                    "radii) or its table file give forces beyond the doubles",
             atom->tag[i], atom->tag[j], atom->type[i], atom->type[j], delta, R,
             egw_law_name(L), F, S);
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
  double *temperature = atom->temperature, *heatflow = atom->heatflow;

  auto view = reinterpret_cast<NeighHistoryView *>(fix_history);
  int **firsttouch = view->firstflag;
  double **firsthist = view->firstvalue;

  int inum = list->inum;
  int *ilist = list->ilist, *numneigh = list->numneigh, **firstneigh = list->firstneigh;
  double ncontact = 0.0;
  const bool cached = hyst_any;    // EP-GW, the cap: hysteresis states per list entry
  if (cached || memo_any) list_rows();
  const size_t n_entries = cached ? entry_first[inum] : 0;
  // (a pair with a ghost under newton off is counted by both ranks)

  const int nt1 = atom->ntypes + 1;
  for (int ii = 0; ii < inum; ii++) {
    int i = ilist[ii];
    const int irow = type[i] * nt1;
    const double *tail_i = &tail_of[irow];
    double xi = x[i][0], yi = x[i][1], zi = x[i][2], radi = radius[i];
    int *touch = firsttouch[i];
    double *allhist = firsthist[i];
    int *jlist = firstneigh[i];
    int jnum = numneigh[i];

    for (int jj = 0; jj < jnum; jj++) {
      if (cached) {    // the block (its first state) of the entry HYST_PREFETCH ahead
        size_t ahead = entry_first[ii] + jj + HYST_PREFETCH;
        if (ahead < n_entries && hyst_slot[ahead] >= 0) {
          const double *b = &hyst_cache[(size_t) hyst_slot[ahead] * hyst_stride];
          __builtin_prefetch(b), __builtin_prefetch(b + 8), __builtin_prefetch(b + 16);
        }
      }
      int j = jlist[jj] & NEIGHMASK;
      double dx = xi - x[j][0], dy = yi - x[j][1], dz = zi - x[j][2];
      double rsq = dx * dx + dy * dy + dz * dz;
      double radj = radius[j];
      double reach = radi + radj + tail_i[type[j]];
      if (rsq >= reach * reach) {
        // a pair beyond the reach has no history: a contact that forms starts afresh
        // (EgwHistory::start sets every value), so nothing is cleared here (and the flag
        // written only when set: most pairs of the list never touch)
        if (touch[jj]) touch[jj] = 0;
        continue;
      }
      EgwLaw &L = *law_of[irow + type[j]];
      double *hist = &allhist[nhist * jj];
      double r = std::sqrt(rsq), rinv = 1.0 / r;
      double nx = dx * rinv, ny = dy * rinv, nz = dz * rinv;
      double delta = radi + radj - r;
      double R = radi * radj / (radi + radj);
      if (!touch[jj]) {
        touch[jj] = 1;
        EgwHistory::start(hist, nhist);
      }
      double Fn, S, U;
      double *cache = nullptr;
      EgwMemo *memo = nullptr;
      if (cached || memo_any) {
        size_t e = entry_first[ii] + jj;
        if (memo_any) memo = &entry_memo[e];
        if (cached)
          cache = hyst_slot[e] >= 0 ? &hyst_cache[(size_t) hyst_slot[e] * hyst_stride]
                                    : hyst_block(e, atom->tag[i], atom->tag[j]);
      }
      // GW/E-GW inside the inline tables, EP-GW of one table within its state's piece,
      // without energy (most steps) here, the rest in normal() (U: eval's 0 without energy)
      int st = eflag ? -1 : L.eval_fast(delta, R, hist, cache, memo, Fn, S);
      if (st < 0) normal(L, delta, R, hist, cache, Fn, S, U, eflag, memo);
      else {
        U = 0.0;
        if (st != EGW_OK) report(L, st, delta, R);
      }
      if (!egw_law_finite(Fn, S)) not_finite(L, i, j, delta, R, Fn, S);
      ncontact += (newton_pair || j < nlocal) ? 1.0 : 0.5;

      double mi = rmass[i], mj = rmass[j];
      double meff = mi * mj / (mi + mj);
      if (mask[i] & freeze_group_bit) meff = mj;
      if (mask[j] & freeze_group_bit) meff = mi;
      const double n[3] = {nx, ny, nz};
      const double vr[3] = {v[i][0] - v[j][0], v[i][1] - v[j][1], v[i][2] - v[j][2]};
      ContactForces c;
      contact_submodels(L, Fn, S, R, radi, radj, radi - 0.5 * delta, radj - 0.5 * delta, n, vr,
                        omega[i], omega[j], meff, hist, hist_sub >= 0 ? &hist[hist_sub] : nullptr,
                        history_update, dt, heat_any ? temperature[i] : 0.0,
                        heat_any ? temperature[j] : 0.0, c);
      double fx = c.Fntot * nx + c.fs[0], fy = c.Fntot * ny + c.fs[1],
             fz = c.Fntot * nz + c.fs[2];
      f[i][0] += fx, f[i][1] += fy, f[i][2] += fz;
      torque[i][0] += c.ti[0], torque[i][1] += c.ti[1], torque[i][2] += c.ti[2];
      if (heat_any) heatflow[i] += c.dq;
      if (newton_pair || j < nlocal) {
        f[j][0] -= fx, f[j][1] -= fy, f[j][2] -= fz;
        torque[j][0] += c.tj[0], torque[j][1] += c.tj[1], torque[j][2] += c.tj[2];
        if (heat_any) heatflow[j] -= c.dq;
      }
      if (evflag) ev_tally_xyz(i, j, nlocal, newton_pair, U, 0.0, fx, fy, fz, dx, dy, dz);
    }
  }
  pvector[0] = ncontact;
}


/* One pair's force for compute pair/local and pair_write.  compute pair/local (during a
 * run): the two atoms' radii and the contact's history as compute() keeps it (found in i's
 * or j's neighbor list; a pair not in contact has none), evaluated on a copy, so that
 * nothing changes.  pair_write (no run in progress): each type's largest radius (atoms and
 * fix pour/deposit), a contact loaded for the first time, at rest.  Returns the tallied
 * energy; fforce is the normal force (elastic + damping) over r.  svector: granular's 12
 * (tangential force on i (3) and its magnitude, rolling resistance (3) and its magnitude,
 * twisting torque, x_i - x_j (3)), then egw's: overlap delta, delta_max (-inf: never
 * touched), stiffness dP/ddelta, elastic and damping normal force. */
double PairEGW::single(int i, int j, int itype, int jtype, double rsq, double /*factor_coul*/,
                       double /*factor_lj*/, double &fforce)
{
  fforce = 0.0;
  for (int k = 0; k < single_extra; k++) svector[k] = 0.0;
  svector[13] = -HUGE_VAL;
  if (!tables_ready || !allocated)
    error->all(FLERR, "Pair egw: single() before the tables are built (pair_write and compute "
                      "pair/local need pair_coeff for every type pair and atoms or rmin/rmax)");
  int a = std::min(itype, jtype), b = std::max(itype, jtype);
  EgwLaw &L = law[a][b];
  const bool writing = update->whichflag == 0;    // pair_write: no atoms involved
  double radi, radj;
  int nall = atom->nlocal + atom->nghost;
  if (writing) {
    radi = rad_max[itype], radj = rad_max[jtype];
    if (!(radi > 0) || !(radj > 0))
      error->all(FLERR, "Pair egw: pair_write for types {} {}: a type without atoms or a fix "
                        "pour/deposit has no radius (pair_write uses each type's largest)",
                 itype, jtype);
  } else {
    if (!atom->radius_flag || i < 0 || j < 0 || i >= nall || j >= nall)
      error->one(FLERR, "Pair egw: single() needs two atoms of the run (compute pair/local)");
    radi = atom->radius[i], radj = atom->radius[j];
  }
  double r = std::sqrt(rsq);
  double delta = radi + radj - r;
  if (!(r > 0) || delta <= -L.tail) return 0.0;
  double R = radi * radj / (radi + radj);

  double hist[NHIST_EPGW + EgwSubmodels::NHIST_SUB];
  EgwHistory::start(hist, NHIST_EPGW);
  for (int k = NHIST_EPGW; k < NHIST_EPGW + EgwSubmodels::NHIST_SUB; k++) hist[k] = 0.0;
  auto view = reinterpret_cast<NeighHistoryView *>(fix_history);
  if (!writing && view && view->firstflag && list && list->firstneigh) {
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
          // seen from j, the partner's copy (displacements negated)
          if (side) EgwHistory::transfer(h, hist, nhist);
        }
        found = true;
        break;
      }
    }
  }
  double Fn, S, U;
  double cache[HYST_CACHE] = {0.0};    // filled from the history's delta_max
  normal(L, delta, R, hist, cache, Fn, S, U, 1);
  double dx[3] = {0.0, 0.0, r}, n[3] = {0.0, 0.0, 1.0}, vr[3] = {0, 0, 0};
  double wi[3] = {0, 0, 0}, wj[3] = {0, 0, 0}, meff = 1.0, Ti = 0, Tj = 0;
  if (!writing) {
    double **x = atom->x, **v = atom->v;
    for (int d = 0; d < 3; d++) {
      dx[d] = x[i][d] - x[j][d], n[d] = dx[d] / r, vr[d] = v[i][d] - v[j][d];
      wi[d] = atom->omega[i][d], wj[d] = atom->omega[j][d];
    }
    double mi = atom->rmass[i], mj = atom->rmass[j];
    meff = mi * mj / (mi + mj);
    if (atom->mask[i] & freeze_group_bit) meff = mj;
    if (atom->mask[j] & freeze_group_bit) meff = mi;
    if (heat_any) Ti = atom->temperature[i], Tj = atom->temperature[j];
  }
  int sub = hist_sub >= 0 ? NHIST_EPGW : -1;
  if (sub >= 0 && hist_sub != NHIST_EPGW)    // the sub-models' history after a shorter core
    for (int k = 0; k < EgwSubmodels::NHIST_SUB; k++) hist[NHIST_EPGW + k] = hist[hist_sub + k];
  ContactForces c;
  contact_submodels(L, Fn, S, R, radi, radj, radi - 0.5 * delta, radj - 0.5 * delta, n, vr, wi,
                    wj, meff, hist, sub >= 0 ? &hist[sub] : nullptr, false, 0.0, Ti, Tj, c);
  fforce = c.Fntot / r;
  for (int d = 0; d < 3; d++) svector[d] = c.fs[d], svector[4 + d] = c.fr[d];
  svector[3] = EgwSubmodels::len3(c.fs);
  svector[7] = EgwSubmodels::len3(c.fr);
  svector[8] = c.Mtw;
  for (int d = 0; d < 3; d++) svector[9 + d] = dx[d];
  svector[12] = delta;
  bool hyst = L.kind == EgwLaw::HYST || L.kind == EgwLaw::HYST_MU || L.kind == EgwLaw::HYST_RCAP;
  // EP-GW's delta_max is kept in units of sigma, the cap's in units of delta_y = cap_c R
  double unit = hyst ? L.sigma : L.kind == EgwLaw::HYST_CAP ? L.cap_c * R : 1.0;
  svector[13] = hist[EgwHistory::DELTA_MAX] * unit;
  svector[14] = S;
  svector[15] = Fn;
  svector[16] = c.Fdamp;
  return U;
}

/* compute()'s per-entry rows, laid out anew when the list was rebuilt */
void PairEGW::list_rows()
{
  if (neighbor->ncalls == rows_calls && (int) entry_first.size() == list->inum + 1 &&
      entry_memo.size() == (memo_any ? entry_first.back() : entry_memo.size()))
    return;
  rows_calls = neighbor->ncalls;
  int inum = list->inum;
  entry_first.resize(inum + 1);
  size_t n = 0;
  for (int ii = 0; ii < inum; ii++) {
    entry_first[ii] = n;
    n += list->numneigh[list->ilist[ii]];
  }
  entry_first[inum] = n;
  // an entry's memo is checked where it is used (its law and R key the position, the
  // interval is a hint), so it stays as it was when the entry becomes another pair (emptied
  // with every run's tables: init_style)
  if (memo_any) entry_memo.resize(n);
  if (hyst_any) hyst_cache_rows();
}

/* EP-GW: a pair of hysteresis states per contact (a block), found from its neighbor-list
 * entry (hyst_slot, -1: none yet); the slots are laid out anew when the list is rebuilt.
 * A block stays where it is while its contact is listed: the new entry of a contact
 * (found by the two atoms' IDs, either order: the states are the same for both atoms)
 * takes the block it had; blocks no entry takes are free for new contacts. A new block is
 * marked empty (a NaN never equals a delta_max) and filled from the history when used
 * (egw_law.h). The pour and the drum reneighbor every 2-8 steps: moving every block to its
 * entry's new place (48 doubles each, into a second copy of all blocks) was 3-4 % of the
 * drum's EP-GW samples; the map reads the blocks' IDs only and keeps one copy. (The blocks
 * are then not in list order: the drum's pair time was the same within the noise,
 * 3.66-4.76 s against 3.77-4.05 s moving, three interleaved rounds at load 3.) */
void PairEGW::hyst_cache_rows()
{
  auto key = [](tagint a, tagint b) {
    uint64_t lo = (uint64_t) std::min(a, b), hi = (uint64_t) std::max(a, b);
    return (lo << 32) ^ hi;    // a collision (64-bit IDs) only costs a refill: egw_law.h
  };
  // the live blocks by the pair's IDs: a table of twice their number rounded up to a
  // power of 2 (keys are never 0: IDs start at 1)
  size_t nblock = hyst_cache_tags.size() / 2, size = 16, nlive = 0;
  for (size_t b = 0; b < nblock; b++) nlive += hyst_live[b] != 0;
  while (size < 2 * nlive) size *= 2;
  hyst_old.assign(size, {0, 0});
  const size_t mask = size - 1;
  auto slot_of = [&](uint64_t k) {
    size_t h = (size_t) ((k * 0x9E3779B97F4A7C15ull) >> 32) & mask;
    while (hyst_old[h].first != 0 && hyst_old[h].first != k) h = (h + 1) & mask;
    return h;
  };
  for (size_t b = 0; b < nblock; b++)
    if (hyst_live[b]) {
      uint64_t k = key(hyst_cache_tags[2 * b], hyst_cache_tags[2 * b + 1]);
      hyst_old[slot_of(k)] = {k, b};
    }
  std::fill(hyst_live.begin(), hyst_live.end(), 0);
  int inum = list->inum;
  tagint *tag = atom->tag;
  auto view = reinterpret_cast<NeighHistoryView *>(fix_history);
  hyst_slot.assign(entry_first[inum], -1);
  if (nlive > 0)
    for (int ii = 0; ii < inum; ii++) {
      int i = list->ilist[ii];
      int *jlist = list->firstneigh[i];
      int *touch = view->firstflag[i];
      for (int jj = 0; jj < list->numneigh[i]; jj++) {
        if (!touch[jj]) continue;
        const auto &hit = hyst_old[slot_of(key(tag[i], tag[jlist[jj] & NEIGHMASK]))];
        if (hit.first == 0 || hyst_live[hit.second]) continue;    // none, or taken
        hyst_slot[entry_first[ii] + jj] = (int) hit.second;
        hyst_live[hit.second] = 1;
      }
    }
  hyst_free.clear();
  for (size_t b = nblock; b-- > 0;)
    if (!hyst_live[b]) hyst_free.push_back((int) b);
}

/* a new, empty block for list entry e (atoms with IDs ti, tj): a free one, else one more */
double *PairEGW::hyst_block(size_t e, tagint ti, tagint tj)
{
  size_t b;
  if (!hyst_free.empty()) {
    b = (size_t) hyst_free.back();
    hyst_free.pop_back();
    hyst_cache_tags[2 * b] = ti, hyst_cache_tags[2 * b + 1] = tj;
    hyst_live[b] = 1;
  } else {
    b = hyst_cache_tags.size() / 2;
    hyst_cache.resize((b + 1) * hyst_stride);
    hyst_cache_tags.push_back(ti), hyst_cache_tags.push_back(tj);
    hyst_live.push_back(1);
  }
  hyst_slot[e] = (int) b;
  double *c = &hyst_cache[b * hyst_stride];
  for (int k = 0; k < hyst_stride; k += EGW_HYSTERESIS_STATE_SIZE) c[k] = NAN;
  return c;
}

double PairEGW::memory_usage()
{
  return (double) hyst_cache.capacity() * sizeof(double) +
      (double) entry_first.capacity() * sizeof(size_t) +
      (double) entry_memo.capacity() * sizeof(EgwMemo) +
      (double) (hyst_slot.capacity() + hyst_free.capacity()) * sizeof(int) +
      (double) hyst_cache_tags.capacity() * sizeof(tagint) + (double) hyst_live.capacity() +
      (double) hyst_old.capacity() * sizeof(hyst_old[0]);
}
