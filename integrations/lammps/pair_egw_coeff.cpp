/* pair_style egw: its settings (pair_style egw MODEL TOL ...), each type's coefficients
 * (pair_coeff) and the law of a type pair mixed from them. */
#include "pair_egw.h"
#include "egw_submodels.h"
#include "egw_submodels_parse.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "utils.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

namespace {
const char *model_names[] = {"Hertz", "GW", "E-GW", "EP-GW"};
}

bool LAMMPS_NS::egw_parse_number(const char *s, double &v)
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
  rmin_user = rmax_user = 0.0, overlap_max = 1.0, tail_energy = 0.0;    // the defaults
  if (!egw_parse_number(arg[1], v) || v < 1e-8 || v > 0.1)
    error->all(FLERR, "Pair style egw: TOL = '{}': must be a number in [1e-8, 0.1]", arg[1]);
  tol = v;
  std::set<std::string> seen;
  for (int i = 2; i < narg; i += 2) {
    std::string key = arg[i];
    // pair_style granular's optional global cutoff, kept in a converted line
    if (egw_parse_number(arg[i], v))
      error->all(FLERR, "Pair style egw: '{}' where a keyword is expected (rmin, rmax, "
                        "overlap_max, tail_energy): a global cutoff (pair_style granular's "
                        "argument) is not supported by egw", key);
    egw_check_repeat(error, "Pair style egw", seen, narg, arg, i);
    if (i + 1 >= narg) error->all(FLERR, "Pair style egw: keyword '{}' needs a value", key);
    if (key == "tail_energy") {
      if (!egw_parse_number(arg[i + 1], v) || v < 0.0)
        error->all(FLERR, "Pair style egw: tail_energy = '{}': must be a number >= 0 (an "
                          "energy; 0: contacts reach the tables' cut-off)", arg[i + 1]);
      tail_energy = v;
      continue;
    }
    if (!egw_parse_number(arg[i + 1], v) || v <= 0.0)
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

/* one of granular's sub-model keywords at arg[i] (damping, tangential, rolling,
 * twisting, heat, limit_damping, and egw's friction): read into p, return the index after
 * it; -1 if arg[i] is none of them.  who: "Pair coeff egw" or the wall fix's name. */
int LAMMPS_NS::egw_submodels_parse(Error *error, const char *who, int narg, char **arg, int i,
                       EgwSubmodels::Params &p)
{
  using namespace EgwSubmodels;
  std::string key = arg[i];
  auto need = [&](int n, const char *syntax) {
    if (i + n >= narg)
      error->all(FLERR, "{}: '{}' needs {} value(s): {} {}", who, key, n, key, syntax);
  };
  auto num = [&](int k, const char *name, double lo, bool lo_open, double hi, bool hi_open) {
    double v;
    const char *s = arg[k];
    if (!egw_parse_number(s, v))
      error->all(FLERR, "{}: {} {} = '{}': not a finite number", who, key, name, s);
    bool ok = (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
    if (!ok)
      error->all(FLERR, "{}: {} {} = {}: must be in {}{}, {}{}", who, key, name, s,
                 lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]");
    return v;
  };
  const double inf = HUGE_VAL;
  // granular's words egw does not have: refused by name, never read as something else
  auto unsupported = [&](const std::string &what) {
    error->all(FLERR, "{}: {} is not supported by egw (pair granular's; egw has: damping "
                      "velocity|mass_velocity|viscoelastic|tsuji|coeff_restitution|none, "
                      "tangential linear_nohistory|linear_history|mindlin[_rescale][/force], "
                      "rolling sds|none, twisting marshall|sds|none, heat area|radius|none, "
                      "limit_damping)", who, what);
  };
  if (key == "cutoff" || key == "synchronized_verlet")
    unsupported(fmt::format("keyword '{}'", key));
  if (key == "limit_damping") {
    p.limit_damping = 1;
    return i + 1;
  }
  if (key == "damping") {
    need(1, "<value> or velocity|mass_velocity|viscoelastic|tsuji|coeff_restitution");
    std::string m = arg[i + 1];
    if (m == "velocity") p.damping = DAMP_VELOCITY;
    else if (m == "mass_velocity") p.damping = DAMP_MASS_VELOCITY;
    else if (m == "viscoelastic") p.damping = DAMP_VISCOELASTIC;
    else if (m == "tsuji") p.damping = DAMP_TSUJI;
    else if (m == "coeff_restitution") p.damping = DAMP_COEFF_RESTITUTION;
    else if (m == "none") p.damping = DAMP_NONE;
    else {
      double v;
      if (!egw_parse_number(arg[i + 1], v))
        unsupported(fmt::format("damping model '{}' (nor is it a number)", m));
      p.damp_value = v, p.damp_value_set = 1;
    }
    return i + 2;
  }
  if (key == "friction") {
    need(1, "mu_t");
    p.tangential = TANG_MINDLIN, p.kt_null = 1, p.xt = 0.0;
    p.mu_t = num(i + 1, "mu_t", 0, false, inf, true);
    return i + 2;
  }
  if (key == "tangential") {
    need(1, "MODEL args (linear_nohistory x_t mu_t | linear_history k_t x_t mu_t | "
            "mindlin[_rescale][/force] k_t|NULL x_t mu_t)");
    std::string m = arg[i + 1];
    if (m == "linear_nohistory") {
      need(3, "linear_nohistory x_t mu_t");
      p.tangential = TANG_LINEAR_NOHISTORY;
      p.xt = num(i + 2, "x_t", 0, false, inf, true);
      p.mu_t = num(i + 3, "mu_t", 0, false, inf, true);
      return i + 4;
    }
    int t = m == "linear_history" ? TANG_LINEAR_HISTORY
        : m == "mindlin" ? TANG_MINDLIN
        : m == "mindlin_rescale" ? TANG_MINDLIN_RESCALE
        : m == "mindlin/force" ? TANG_MINDLIN_FORCE
        : m == "mindlin_rescale/force" ? TANG_MINDLIN_RESCALE_FORCE : -1;
    if (t < 0) unsupported(fmt::format("tangential model '{}'", m));
    need(4, (m + " k_t x_t mu_t").c_str());
    p.tangential = t;
    if (t != TANG_LINEAR_HISTORY && std::string(arg[i + 2]) == "NULL") p.kt_null = 1;
    else p.kt_null = 0, p.kt = num(i + 2, "k_t", 0, true, inf, true);
    p.xt = num(i + 3, "x_t", 0, false, inf, true);
    p.mu_t = num(i + 4, "mu_t", 0, false, inf, true);
    return i + 5;
  }
  if (key == "rolling") {
    need(1, "sds k_r gamma_r mu_r");
    if (std::string(arg[i + 1]) == "none") {
      p.rolling = ROLL_NONE;
      return i + 2;
    }
    if (std::string(arg[i + 1]) != "sds")
      unsupported(fmt::format("rolling model '{}'", arg[i + 1]));
    need(4, "sds k_r gamma_r mu_r");
    p.rolling = ROLL_SDS;
    p.kr = num(i + 2, "k_r", 0, true, inf, true);
    p.gr = num(i + 3, "gamma_r", 0, false, inf, true);
    p.mur = num(i + 4, "mu_r", 0, false, inf, true);
    return i + 5;
  }
  if (key == "twisting") {
    need(1, "marshall | sds k_tw gamma_tw mu_tw");
    std::string m = arg[i + 1];
    if (m == "marshall") {
      p.twisting = TWIST_MARSHALL;
      return i + 2;
    }
    if (m == "none") {
      p.twisting = TWIST_NONE;
      return i + 2;
    }
    if (m != "sds") unsupported(fmt::format("twisting model '{}'", m));
    need(4, "sds k_tw gamma_tw mu_tw");
    p.twisting = TWIST_SDS;
    p.ktw = num(i + 2, "k_tw", 0, true, inf, true);
    p.gtw = num(i + 3, "gamma_tw", 0, false, inf, true);
    p.mutw = num(i + 4, "mu_tw", 0, false, inf, true);
    return i + 5;
  }
  if (key == "heat") {
    need(1, "area h_s | radius k_s | none");
    std::string m = arg[i + 1];
    if (m == "none") {
      p.heat = HEAT_NONE, p.heat_coeff = 0.0;
      return i + 2;
    }
    need(2, "area h_s | radius k_s");
    if (m == "area") p.heat = HEAT_AREA;
    else if (m == "radius") p.heat = HEAT_RADIUS;
    else unsupported(fmt::format("heat model '{}'", m));
    p.heat_coeff = num(i + 2, m == "area" ? "h_s" : "k_s", 0, false, inf, true);
    return i + 3;
  }
  return -1;
}

/* a keyword given twice on one line: an ERROR naming it (egw_submodels_parse.h) */
void LAMMPS_NS::egw_check_repeat(Error *error, const char *who, std::set<std::string> &seen,
                                 int narg, char **arg, int i)
{
  std::string key = arg[i], slot = key;
  double v;
  if (key == "friction") slot = "tangential";
  else if (key == "damping" && i + 1 < narg)
    slot = egw_parse_number(arg[i + 1], v) ? "damping <value>" : "damping <model>";
  if (!seen.insert(slot).second)
    error->all(FLERR, "{}: keyword '{}' given twice{}: give it once (the first would be "
                      "dropped without a word)", who, slot,
               key == "friction" ? " (friction is a tangential model)" : "");
}

/* 'flow_pressure P' or 'yield_stress Y' (p_y = 1.6 Y, doc/theory.md section 12) at
 * arg[i] into c: the index after it, -1 if arg[i] is neither. Refused: a value that is not
 * a finite number >= 0, and both keywords for one body. who: as egw_submodels_parse. */
int LAMMPS_NS::egw_flow_parse(Error *error, const char *who, int narg, char **arg, int i,
                              EgwCoeff &c, int &given)
{
  std::string key = arg[i];
  if (key != "flow_pressure" && key != "yield_stress") return -1;
  if (i + 1 >= narg) error->all(FLERR, "{}: keyword '{}' needs a value", who, key);
  int kw = key == "yield_stress";
  if (given >= 0 && given != kw)
    error->all(FLERR, "{}: flow_pressure and yield_stress together: give one (yield_stress Y "
                      "is flow_pressure 1.6 Y)", who);
  double v;
  if (!egw_parse_number(arg[i + 1], v))
    error->all(FLERR, "{}: {} = '{}': not a finite number", who, key, arg[i + 1]);
  if (v < 0)
    error->all(FLERR, "{}: {} = {}: must be >= 0 (a {} [pressure]; 0: no bulk yield)", who, key,
               arg[i + 1], kw ? "yield stress" : "flow pressure");
  given = kw;
  c.flow_keyword = kw;
  c.flow_pressure = kw ? 1.6 * v : v;
  return i + 2;
}

/* the contact's p_y below its E*: an ERROR naming the keyword that gave it */
void LAMMPS_NS::egw_flow_check(Error *error, const char *who, const std::string &what,
                               double flow_pressure, int flow_keyword, double E_star)
{
  if (!(flow_pressure > 0) || flow_pressure < E_star) return;
  if (flow_keyword)
    error->all(FLERR, "{}: yield_stress = {} (p_y = 1.6 Y = {}) for {}: p_y must be below the "
                      "contact's E* = {} (the cap is a small-strain model)", who,
               flow_pressure / 1.6, flow_pressure, what, E_star);
  error->all(FLERR, "{}: flow_pressure = {} for {}: must be below the contact's E* = {} (the "
                    "cap is a small-strain model)", who, flow_pressure, what, E_star);
}

/* the cap's scales of the contact within egw's range: egw_params_validate at its radii */
void LAMMPS_NS::egw_flow_scale_check(Error *error, const char *who, const std::string &what,
                                     double flow_pressure, int flow_keyword, double E_star,
                                     double R_lo, double R_hi)
{
  if (!(flow_pressure > 0)) return;
  std::string key = flow_keyword ? fmt::format("yield_stress = {} (p_y = 1.6 Y = {})",
                                               flow_pressure / 1.6, flow_pressure)
                                 : fmt::format("flow_pressure = {}", flow_pressure);
  double r = M_PI * flow_pressure / (2.0 * E_star);
  if (!(r * r >= DBL_MIN))
    error->all(FLERR, "{}: {} for {}: with the contact's E* = {} the first-yield overlap "
                      "delta_y = (pi p_y/(2 E*))^2 R is not a double for any radius (p_y/E* "
                      "= {:.3g}: the cap never acts; flow_pressure 0 for no bulk yield)",
               who, key, what, E_star, flow_pressure / E_star);
  for (double R : {R_lo, R_hi}) {
    if (!(R > 0)) continue;
    egw_params q;
    egw_params_default(&q);
    q.model = EGW_MODEL_HERTZ, q.radius = R, q.modulus = E_star, q.flow_pressure = flow_pressure;
    if (egw_params_validate(&q) == EGW_OK) continue;
    char msg[512];
    egw_last_error(msg, sizeof msg);
    error->all(FLERR, "{}: {} for {} at the equivalent radius R = {}: egw refuses it: {}", who,
               key, what, R, msg);
  }
}

/* keywords the model ignores: a WARNING naming them (as Python's egw warns) */
void LAMMPS_NS::egw_warn_ignored(Error *error, const char *who, int model, const EgwCoeff &c,
                                 bool have_sigma, bool have_plastic)
{
  const char *names[] = {"Hertz", "GW", "E-GW", "EP-GW"};
  if (have_plastic && model != EGW_MODEL_EPGW)
    error->warning(FLERR, "{}: psi, K and plastic_ratio are EP-GW's; model {} ignores them",
                   who, names[model]);
  if (model == EGW_MODEL_HERTZ && (c.mu_mode != 0 || (have_sigma && c.sigma > 0)))
    error->warning(FLERR, "{}: model Hertz is smooth: it ignores sigma, mu and summit data",
                   who);
  // a smooth body's surface data: EgwLaw::combine takes the rough partner's (or none)
  if (model != EGW_MODEL_HERTZ && c.sigma == 0 && c.mu_mode != 0)
    error->warning(FLERR, "{}: sigma 0 is a smooth surface: it ignores mu and summit data (a "
                          "contact takes its rough partner's)", who);
  // egw's elastic force is never negative: only a damping force can make the total so
  if (c.sub.limit_damping && c.sub.damping == EgwSubmodels::DAMP_NONE)
    error->warning(FLERR, "{}: limit_damping with damping none is ignored (no damping force "
                          "to limit)", who);
}

/* the damping value's range once the model is known */
void LAMMPS_NS::egw_submodels_check(Error *error, const char *who, EgwSubmodels::Params &p)
{
  using namespace EgwSubmodels;
  bool restitution = p.damping == DAMP_TSUJI || p.damping == DAMP_COEFF_RESTITUTION;
  if (!p.damp_value_set) p.damp_value = restitution ? 1.0 : 0.0;
  if (p.damping == DAMP_NONE && p.damp_value_set && p.damp_value != 0.0)
    error->all(FLERR, "{}: damping {} with damping none: no damping model takes it (give a "
                      "model, e.g. viscoelastic, granular's default)", who, p.damp_value);
  double v = p.damp_value;
  if (restitution && !(v > 0 && v <= 1))
    error->all(FLERR, "{}: damping = {}: the restitution coefficient must be in (0, 1]", who, v);
  if (!restitution && !(v >= 0))
    error->all(FLERR, "{}: damping = {}: eta_n0 must be >= 0", who, v);
  if (p.twisting == TWIST_MARSHALL && !p.tangential_history())
    error->all(FLERR, "{}: twisting marshall needs a tangential model with history "
                      "(linear_history or mindlin*)", who);
}

void PairEGW::parse_coeff(int narg, char **arg, Coeff &c)
{
  bool haveE = false, havenu = false, havesig = false, havemu = false, haveeta = false,
       havebeta = false, haveplastic = false, havelaw = false;
  int flow_given = -1;
  std::set<std::string> seen;
  c = Coeff();
  static const char *granular_normal[] = {"hooke", "hertz", "hertz/material", "dmt", "jkr",
                                          "mdr"};
  for (int i = 2; i < narg;) {
    std::string key = arg[i];
    for (const char *g : granular_normal)
      if (key == g)
        error->all(FLERR, "Pair coeff egw: '{}' (pair granular's normal model) is not supported: "
                          "egw's normal law takes keywords: E v nu v sigma v mu v ... (damping, "
                          "tangential, rolling, twisting and heat as in granular)", key);
    egw_check_repeat(error, "Pair coeff egw", seen, narg, arg, i);
    int next = egw_submodels_parse(error, "Pair coeff egw", narg, arg, i, c.sub);
    if (next < 0) next = egw_flow_parse(error, "Pair coeff egw", narg, arg, i, c, flow_given);
    if (next > 0) {
      i = next;
      continue;
    }
    if (i + 1 >= narg) error->all(FLERR, "Pair coeff egw: keyword '{}' needs a value", key);
    if (key == "law") {
      std::string path = arg[i + 1];
      if (path.size() >= sizeof(c.law_file))
        error->all(FLERR, "Pair coeff egw: law = '{}': a path of at most {} characters", path,
                   sizeof(c.law_file) - 1);
      // read now (every rank) so that a missing or bad file stops at this line
      egw_flat_law fl = egw_law_read_file(path, world, [&](const std::string &msg) {
        error->all(FLERR, "Pair coeff egw: {}", msg);
      });
      egw_flat_law_free(&fl);
      std::strncpy(c.law_file, path.c_str(), sizeof(c.law_file) - 1);
      havelaw = true;
      i += 2;
      continue;
    }
    double v;
    if (!egw_parse_number(arg[i + 1], v))
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
      c.psi = v, haveplastic = true;
    } else if (key == "K") {
      if (v <= 0 || v >= 1) bad("must be in (0, 1)");
      c.K = v, haveplastic = true;
    } else if (key == "plastic_ratio") {
      if (v <= 1) bad("must be > 1");
      c.rho = v, haveplastic = true;
    } else
      error->all(FLERR, "Pair coeff egw: unknown keyword '{}'", key);
    i += 2;
  }
  egw_submodels_check(error, "Pair coeff egw", c.sub);
  if (!haveE) error->all(FLERR, "Pair coeff egw: keyword 'E' is required");
  if (!havenu) error->all(FLERR, "Pair coeff egw: keyword 'nu' is required");
  if (havelaw) {
    // the file is the contact's whole rough surface: GW's parameters would contradict it
    const char *other = havesig ? "sigma" : havemu ? "mu" : haveeta ? "summit_density"
        : havebeta ? "summit_radius" : haveplastic ? "psi/K/plastic_ratio" : nullptr;
    if (other)
      error->all(FLERR, "Pair coeff egw: law {} with '{}': the law file is the contact's rough "
                        "surface (no sigma, mu, summit data, psi, K or plastic_ratio with it)",
                 c.law_file, other);
    if (flow_given >= 0 && c.flow_pressure > 0)
      error->all(FLERR, "Pair coeff egw: law {} with '{}': a rough-flat law with the "
                        "flow-pressure cap is not available (egw's cap serves smooth spheres: "
                        "sigma 0 or model Hertz)", c.law_file,
                 flow_given ? "yield_stress" : "flow_pressure");
    check_law_model(c.law_file);
    c.set = 1;
    return;
  }
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
  // like types: E* = E/(2(1-nu^2)) (unlike types and walls are checked when mixed)
  egw_flow_check(error, "Pair coeff egw", fmt::format("types {} {}", arg[0], arg[1]),
                 c.flow_pressure, c.flow_keyword, c.E / (2.0 * (1.0 - c.nu * c.nu)));
  if (comm->me == 0) egw_warn_ignored(error, "Pair coeff egw", model, c, havesig, haveplastic);
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

/* a flat law is elastic and rough: refused with Hertz (smooth) and EP-GW (plastic summits,
 * hysteresis) as the pair style's MODEL */
void PairEGW::check_law_model(const char *file)
{
  if (model == EGW_MODEL_HERTZ || model == EGW_MODEL_EPGW)
    error->all(FLERR, "Pair coeff egw: law {} with pair_style egw {}: a rough-flat law is "
                      "elastic and rough (unloading = loading); use pair_style egw GW or E-GW "
                      "(the law replaces their model for this type pair)", file,
               model_names[model]);
}

/* the sub-models of unlike types without their own pair_coeff: the same models in both,
 * their numbers geometric means (as e and mu_t always were) */
EgwSubmodels::Params PairEGW::mix_submodels(int i, int j, const EgwSubmodels::Params &a,
                                            const EgwSubmodels::Params &b)
{
  auto differ = [&](const char *what) {
    error->all(FLERR, "Pair egw: types {} and {} have different {} models: set pair_coeff {} {} "
                      "explicitly", i, j, what, i, j);
  };
  if (a.damping != b.damping) differ("damping");
  if (a.tangential != b.tangential || a.kt_null != b.kt_null) differ("tangential");
  if (a.rolling != b.rolling) differ("rolling");
  if (a.twisting != b.twisting) differ("twisting");
  if (a.heat != b.heat) differ("heat");
  auto g = [](double x, double y) { return std::sqrt(x * y); };
  EgwSubmodels::Params m = a;
  m.damp_value = g(a.damp_value, b.damp_value);
  m.limit_damping = a.limit_damping || b.limit_damping;
  m.kt = g(a.kt, b.kt), m.xt = g(a.xt, b.xt), m.mu_t = g(a.mu_t, b.mu_t);
  m.kr = g(a.kr, b.kr), m.gr = g(a.gr, b.gr), m.mur = g(a.mur, b.mur);
  m.ktw = g(a.ktw, b.ktw), m.gtw = g(a.gtw, b.gtw), m.mutw = g(a.mutw, b.mutw);
  m.heat_coeff = g(a.heat_coeff, b.heat_coeff);
  return m;
}

/* the law of pair (i, j), i <= j: explicit coefficients as for like types, else mixed;
 * R_lo, R_hi its equivalent radii (0: not known) */
void PairEGW::make_law(int i, int j, double R_lo, double R_hi)
{
  EgwLaw L;
  if (pcoeff[i][j].set) {
    L.like(pcoeff[i][j]);
  } else {
    const Coeff &a = pcoeff[i][i], &b = pcoeff[j][j];
    if (!a.set || !b.set) error->all(FLERR, "Pair egw: coefficients of types {} {} not set", i, j);
    if (std::strcmp(a.law_file, b.law_file) != 0)
      error->all(FLERR, "Pair egw: types {} and {} have different rough surfaces (law '{}' vs "
                        "'{}'; a law is the contact's): set pair_coeff {} {} explicitly", i, j,
                 a.law_file, b.law_file, i, j);
    if (!L.combine(a, b))
      error->all(FLERR, "Pair egw: types {} and {} give mu in different ways (mu vs "
                        "summit_density/summit_radius): set pair_coeff {} {} explicitly",
                 i, j, i, j);
    L.sub = mix_submodels(i, j, a.sub, b.sub);
  }
  if (!L.law_file.empty()) check_law_model(L.law_file.c_str());
  egw_flow_check(error, "Pair egw", fmt::format("types {} {}", i, j), L.flow_pressure,
                 L.flow_keyword, L.E_star);
  egw_flow_scale_check(error, "Pair egw", fmt::format("types {} {}", i, j), L.flow_pressure,
                       L.flow_keyword, L.E_star, R_lo, R_hi);
  L.setup(model);
  // rough + cap with sigma far below the first-yield overlap: its Hertz + cap limit
  std::string note = L.smooth_cap_limit(R_lo, R_hi);
  if (!note.empty() && comm->me == 0 &&
      std::find(smooth_cap_warned.begin(), smooth_cap_warned.end(), std::make_pair(i, j)) ==
          smooth_cap_warned.end()) {
    smooth_cap_warned.emplace_back(i, j);
    error->warning(FLERR, "Pair egw: types {} {}: {}", i, j, note);
  }
  // keep the tables of an unchanged law
  EgwLaw &old = law[i][j];
  // (a law's sigma is its file's length, known once built: the file name stands for it)
  bool same = old.E_star == L.E_star && (old.sigma == L.sigma || L.kind == EgwLaw::FLAT) &&
      old.mu_mode == L.mu_mode &&
      old.mu == L.mu && old.psi == L.psi && old.K == L.K && old.rho == L.rho &&
      old.flow_pressure == L.flow_pressure &&
      old.kind == L.kind && old.prm.model == L.prm.model && old.law_file == L.law_file &&
      built_rhi[i][j] > 0;
  if (same) {
    L.take_tables(old);
  } else {
    old.release();
    built_rhi[i][j] = 0.0;
  }
  law[i][j] = L;
}
