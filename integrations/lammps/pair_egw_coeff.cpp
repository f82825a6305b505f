/* pair_style egw: its settings (pair_style egw MODEL TOL ...), each type's coefficients
 * (pair_coeff) and the law of a type pair mixed from them. */
#include "pair_egw.h"
#include "egw_submodels.h"

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

namespace {
const char *model_names[] = {"Hertz", "GW", "E-GW", "EP-GW"};
}

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
  L.damp = EgwSubmodels::restitution_factor(L.e);
  if (model == EGW_MODEL_HERTZ || L.sigma == 0.0) L.kind = EgwLaw::HERTZ;
  else if (model == EGW_MODEL_EPGW && L.psi > 0)
    L.kind = L.mu_mode == 1 ? EgwLaw::HYST : EgwLaw::HYST_MU;
  else L.kind = L.mu_mode == 1 ? EgwLaw::TABLE : EgwLaw::UNIVERSAL;
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
