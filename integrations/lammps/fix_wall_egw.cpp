/* fix wall/egw: walls with egw's rough contact law.
 *
 *   fix ID group wall/egw MODEL TOL E v nu v [wall_material own|contact] [sigma v] [mu v | summit_density v
 *       summit_radius v] [psi v] [K v] [plastic_ratio v] [flow_pressure P | yield_stress Y]
 *       [overlap_max F] [temperature T] [<sub-models>]
 *       xplane|yplane|zplane lo hi | zcylinder radius [wiggle dim A period] [shear dim v]
 *       [contacts]
 *   fix ID group wall/egw/region MODEL TOL <the same keywords> region-ID [contacts]
 *
 * A wall contact is the contact of the particle's type (its pair_coeff I I in pair_style
 * egw) with the wall's own material and surface, combined as two types combine (E*, G*
 * from both bodies, sigma = sqrt(sigma_i^2 + sigma_wall^2), mu as in mixing), with m* = m_i
 * and R = R_i rc/(R_i + rc) from the wall's radius of curvature rc at the contact (R_i for
 * a flat wall, a sphere of infinite radius), as fix wall/gran; the wall's sub-models
 * (damping, tangential, rolling, twisting, heat) are the fix's own.  History per atom (one
 * contact per plane wall, one per region face), kept through exchange and restart. */
#include "fix_wall_egw.h"

#include "egw_contact.h"
#include "egw_history.h"
#include "egw_submodels_parse.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "region.h"
#include "error.h"
#include "force.h"
#include "input.h"
#include "modify.h"
#include "variable.h"
#include "memory.h"
#include "neighbor.h"
#include "pair.h"
#include "update.h"
#include "utils.h"

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

FixWallEGW::FixWallEGW(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), material_contact(false), tvar(-1), region(nullptr), history(nullptr),
    contacts(false), pair(nullptr)
{
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "Fix wall/egw requires atom_style sphere");
  model = EGW_MODEL_EGW, tol = 1e-4, overlap_max = 1.0;
  wallstyle = -1, axis = 2, lo = hi = cylradius = cyl_rc = 0.0, have_lo = have_hi = false;
  wiggle = wshear = 0, wdim = 0, amplitude = period = omega = vshear = 0.0;
  built_model = -1, warned_range = false;
  wall_temperature = 0.0, have_temperature = false;
  tmax = 1;
  if (std::string(arg[2]) == "wall/egw/region") {
    // fix ID group wall/egw/region MODEL TOL <keywords> [region] region-ID [contacts]
    int last = narg - 1;
    // fix wall/gran/region's keywords after the region ID (contacts, temperature T), in
    // any order
    while (last > 5) {
      if (std::string(arg[last]) == "contacts") {
        if (contacts) error->all(FLERR, "Fix wall/egw/region: keyword 'contacts' given twice");
        contacts = true, last--;
      } else if (std::string(arg[last]) == "temperature") {
        // 'region ID temperature' with its value missing: not a region named 'temperature'
        error->all(FLERR, "Fix wall/egw/region: keyword 'temperature' needs a value (T or "
                          "v_name)");
      } else if (last - 1 > 5 && std::string(arg[last - 1]) == "temperature") {
        set_temperature(arg[last]);
        last -= 2;
      } else
        break;
    }
    if (last < 5) error->all(FLERR, "Fix wall/egw/region: expected 'fix ID group wall/egw/region "
                                    "MODEL TOL <wall keywords> region-ID [contacts]'");
    region_id = arg[last];
    region = domain->get_region_by_id(region_id);
    if (!region) {
      // a keyword after 'region ID' that fix wall/gran/region does not take there either:
      // name it rather than call it a missing region
      for (int k = last - 1; k >= 5; k--)
        if (domain->get_region_by_id(arg[k]))
          error->all(FLERR, "Fix wall/egw/region: '{}' after the region ID '{}': only "
                            "'contacts' and 'temperature T' may follow it (as in fix "
                            "wall/gran/region); the wall keywords come before it",
                     arg[k + 1], arg[k]);
      error->all(FLERR, "Fix wall/egw/region: region ID '{}' does not exist", region_id);
    }
    wallstyle = REGION;
    tmax = std::max(1, region->tmax);
    restart_global = 1;    // the region's motion (as fix wall/gran/region)
    // granular's form 'region region-ID' (its wallstyle word) too: a granular deck's
    // fix line then changes only its normal model
    if (last - 1 >= 5 && std::string(arg[last - 1]) == "region") last--;
    parse(last, arg);
  } else
    parse(narg, arg);
  time_origin = update->ntimestep;

  // the history holds the hysteresis states when a contact may have hysteresis: EP-GW, or
  // a flow pressure of the wall or of a type known now (init() widens it if a type given
  // later needs it)
  bool hyst = model == EGW_MODEL_EPGW || wall.flow_pressure > 0;
  if (auto p = dynamic_cast<EgwTypeCoeffs *>(force->pair_match("egw", 1)))
    for (int t = 1; t <= atom->ntypes; t++)
      hyst = hyst || (p->type_coeff(t) && p->type_coeff(t)->flow_pressure > 0);

  restart_peratom = 1;
  create_attribute = 1;
  // fix wall/gran's columns; a heat model appends the heat into the atom (as granular's)
  ncols = wall.sub.heat != EgwSubmodels::HEAT_NONE ? 9 : 8;
  if (contacts) peratom_flag = 1, size_peratom_cols = ncols, peratom_freq = 1;
  set_layout(hyst ? EgwHistory::NHIST_EPGW : EgwHistory::NHIST_BASE);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
}

/* the per-atom history's layout for a contact history of core doubles (NHIST_BASE, or
 * NHIST_EPGW with the hysteresis states) and the sub-models' after it; every atom's history
 * starts afresh */
void FixWallEGW::set_layout(int core)
{
  hist_sub = wall.sub.needs_extra_history() ? core : -1;
  nhist = core + (hist_sub >= 0 ? EgwSubmodels::NHIST_SUB : 0);
  stride = wallstyle == REGION ? 1 + tmax * (1 + nhist) : nhist;
  maxexchange = stride + 1;    // pack_exchange: the history and its cleared flag
  memory->destroy(history);
  grow_arrays(atom->nmax);
  for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
}

FixWallEGW::~FixWallEGW()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(history);
  memory->destroy(array_atom);
  for (auto &l : law) l.release();
  EgwTables::purge();
}

/* MODEL TOL, the wall's keywords and sub-models, the wall style and its options */
void FixWallEGW::parse(int narg, char **arg)
{
  const char *who = "Fix wall/egw";
  if (narg < 5) error->all(FLERR, "{}: expected 'fix ID group wall/egw MODEL TOL <wall keywords> "
                                  "wallstyle args'", who);
  std::string m = arg[3];
  if (m == "Hertz" || m == "hertz") model = EGW_MODEL_HERTZ;
  else if (m == "GW" || m == "gw") model = EGW_MODEL_GW;
  else if (m == "E-GW" || m == "e-gw" || m == "EGW") model = EGW_MODEL_EGW;
  else if (m == "EP-GW" || m == "ep-gw" || m == "EPGW") model = EGW_MODEL_EPGW;
  else
    error->all(FLERR, "{}: MODEL = '{}': must be Hertz, GW, E-GW or EP-GW{}", who, m,
               m == "granular" || m == "hooke" || m == "hooke/history" || m == "hertz/history"
                   ? " (fix wall/gran's 'granular hertz/material E e nu ...' converts to "
                     "'wall/egw E-GW TOL E E nu nu sigma 1e-16 mu 4 wall_material contact "
                     "damping e ...': README's conversion table)"
                   : "");
  double v;
  if (!egw_parse_number(arg[4], v) || v < 1e-8 || v > 0.1)
    error->all(FLERR, "{}: TOL = '{}': must be a number in [1e-8, 0.1]", who, arg[4]);
  tol = v;
  bool haveE = false, havenu = false, havesig = false, havemu = false, haveeta = false,
       havebeta = false, haveplastic = false;
  int flow_given = -1;
  std::set<std::string> seen;   // keywords so far: one given twice is an ERROR
  int i = 5;
  auto number = [&](const std::string &key, int k) {
    if (k >= narg) error->all(FLERR, "{}: keyword '{}' needs a value", who, key);
    double x;
    if (!egw_parse_number(arg[k], x))
      error->all(FLERR, "{}: {} = '{}': not a finite number", who, key, arg[k]);
    return x;
  };
  // fix wall/gran granular's normal models: a converted line that kept one
  static const char *granular_normal[] = {"hooke", "hertz", "hertz/material", "dmt", "jkr",
                                          "mdr", "granular"};
  while (i < narg) {
    std::string key = arg[i];
    if (key == "xplane" || key == "yplane" || key == "zplane" || key == "zcylinder") break;
    for (const char *g : granular_normal)
      if (key == g)
        error->all(FLERR, "{}: '{}' (fix wall/gran's normal model) is not supported: egw's wall "
                          "takes keywords: E v nu v [wall_material own|contact] sigma v mu v "
                          "... ('granular hertz/material E e nu' is 'E E nu nu sigma 1e-16 mu 4 "
                          "wall_material contact damping e': README's conversion table)",
                   who, key);
    // temperature may also follow the wall style: set_temperature refuses it twice
    if (key != "temperature") egw_check_repeat(error, who, seen, narg, arg, i);
    int next = egw_submodels_parse(error, who, narg, arg, i, wall.sub);
    if (next < 0) next = egw_flow_parse(error, who, narg, arg, i, wall, flow_given);
    if (next > 0) {
      i = next;
      continue;
    }
    if (key == "temperature") {
      if (i + 1 >= narg) error->all(FLERR, "{}: keyword 'temperature' needs a value", who);
      set_temperature(arg[i + 1]);
      i += 2;
      continue;
    }
    if (key == "wall_material") {
      if (i + 1 >= narg) error->all(FLERR, "{}: keyword 'wall_material' needs a value", who);
      std::string w = arg[i + 1];
      if (w == "contact") material_contact = true;
      else if (w == "own") material_contact = false;
      else error->all(FLERR, "{}: wall_material = '{}': must be 'own' or 'contact'", who, w);
      i += 2;
      continue;
    }
    double x = number(key, i + 1);
    auto bad = [&](const char *rule) { error->all(FLERR, "{}: {} = {}: {}", who, key, x, rule); };
    if (key == "E") {
      if (x <= 0) bad("must be > 0");
      wall.E = x, haveE = true;
    } else if (key == "nu") {
      if (x <= -1.0 || x > 0.5) bad("must be in (-1, 0.5]");
      wall.nu = x, havenu = true;
    } else if (key == "sigma") {
      if (x < 0) bad("must be >= 0");
      wall.sigma = x, havesig = true;
    } else if (key == "mu") {
      if (x <= 0) bad("must be > 0");
      wall.mu = x, havemu = true;
    } else if (key == "summit_density") {
      if (x <= 0) bad("must be > 0");
      wall.eta = x, haveeta = true;
    } else if (key == "summit_radius") {
      if (x <= 0) bad("must be > 0");
      wall.beta = x, havebeta = true;
    } else if (key == "psi") {
      if (x < 0) bad("must be >= 0");
      wall.psi = x, haveplastic = true;
    } else if (key == "K") {
      if (x <= 0 || x >= 1) bad("must be in (0, 1)");
      wall.K = x, haveplastic = true;
    } else if (key == "plastic_ratio") {
      if (x <= 1) bad("must be > 1");
      wall.rho = x, haveplastic = true;
    } else if (key == "overlap_max") {
      if (x <= 0) bad("must be > 0");
      overlap_max = x;
    } else
      error->all(FLERR, "{}: unknown keyword '{}' (or a missing wall style xplane, yplane, "
                        "zplane, zcylinder)", who, key);
    i += 2;
  }
  egw_submodels_check(error, who, wall.sub);
  if (!haveE) error->all(FLERR, "{}: keyword 'E' (the wall's Young's modulus) is required", who);
  if (!havenu) error->all(FLERR, "{}: keyword 'nu' (the wall's Poisson ratio) is required", who);
  if (havemu && (haveeta || havebeta))
    error->all(FLERR, "{}: give either 'mu' or 'summit_density' and 'summit_radius', not both",
               who);
  if (haveeta != havebeta)
    error->all(FLERR, "{}: keyword '{}' needs '{}'", who,
               haveeta ? "summit_density" : "summit_radius",
               haveeta ? "summit_radius" : "summit_density");
  wall.mu_mode = havemu ? 1 : (haveeta ? 2 : 0);
  if (comm->me == 0) egw_warn_ignored(error, who, model, wall, havesig, haveplastic);
  // the wall's temperature and its heat model, once every place 'temperature' may stand
  // (before the wall style, or after it as fix wall/gran's) has been read
  auto check_heat = [&]() {
    if (wall.sub.heat != EgwSubmodels::HEAT_NONE && !have_temperature)
      error->all(FLERR, "{}: a heat model needs the wall's 'temperature T'", who);
    if (wall.sub.heat == EgwSubmodels::HEAT_NONE && have_temperature && comm->me == 0)
      error->warning(FLERR, "{}: 'temperature' without a heat model (heat area|radius) is "
                            "ignored", who);
  };
  wall.set = 1;

  if (wallstyle == REGION) {
    if (i < narg) error->all(FLERR, "{}: unknown keyword '{}'", who, arg[i]);
    check_heat();
    return;
  }
  if (i >= narg)
    error->all(FLERR, "{}: missing wall style (xplane, yplane, zplane, zcylinder)", who);
  std::string style = arg[i];
  if (style == "zcylinder") {
    wallstyle = ZCYLINDER, axis = 2;
    cylradius = number("zcylinder radius", i + 1);
    if (cylradius <= 0) error->all(FLERR, "{}: zcylinder radius = {}: must be > 0", who, cylradius);
    cyl_rc = -2.0 * cylradius;    // concave, with fix wall/gran's radius of curvature
    i += 2;
  } else {
    wallstyle = style == "xplane" ? XPLANE : style == "yplane" ? YPLANE : ZPLANE;
    axis = wallstyle;
    if (i + 2 >= narg) error->all(FLERR, "{}: '{}' needs lo and hi (a number or NULL)", who, style);
    if (std::string(arg[i + 1]) != "NULL") lo = number(style + " lo", i + 1), have_lo = true;
    if (std::string(arg[i + 2]) != "NULL") hi = number(style + " hi", i + 2), have_hi = true;
    if (!have_lo && !have_hi) error->all(FLERR, "{}: '{}' with both lo and hi NULL", who, style);
    if (have_lo && have_hi && lo >= hi) error->all(FLERR, "{}: {} lo >= hi", who, style);
    i += 3;
  }
  while (i < narg) {
    std::string key = arg[i];
    if (key != "temperature") egw_check_repeat(error, who, seen, narg, arg, i);
    auto dim_of = [&](int k) {
      if (k >= narg) error->all(FLERR, "{}: '{}' needs a dimension x, y or z", who, key);
      std::string d = arg[k];
      if (d == "x") return 0;
      if (d == "y") return 1;
      if (d == "z") return 2;
      error->all(FLERR, "{}: {} dimension '{}': must be x, y or z", who, key, d);
      return 0;
    };
    if (key == "wiggle") {
      wdim = dim_of(i + 1);
      amplitude = number("wiggle amplitude", i + 2);
      period = number("wiggle period", i + 3);
      if (period <= 0) error->all(FLERR, "{}: wiggle period = {}: must be > 0", who, period);
      if (wallstyle != ZCYLINDER && wdim != axis)
        error->all(FLERR, "{}: a plane wiggles along its normal ({})", who, "xyz"[axis]);
      if (wallstyle == ZCYLINDER && wdim != 2)
        error->all(FLERR, "{}: a zcylinder wiggles along z", who);
      wiggle = 1, omega = 2.0 * M_PI / period;
      i += 4;
    } else if (key == "shear") {
      wdim = dim_of(i + 1);
      vshear = number("shear velocity", i + 2);
      if (wallstyle != ZCYLINDER && wdim == axis)
        error->all(FLERR, "{}: a plane shears along its own plane", who);
      wshear = 1;
      i += 3;
    } else if (key == "contacts") {
      contacts = true;
      i += 1;
    } else if (key == "temperature") {
      // fix wall/gran's place for it: after the wall style's arguments
      if (i + 1 >= narg) error->all(FLERR, "{}: keyword 'temperature' needs a value", who);
      set_temperature(arg[i + 1]);
      i += 2;
    } else
      error->all(FLERR, "{}: unknown keyword '{}' after the wall style (wiggle, shear, contacts, "
                        "temperature)", who, key);
  }
  if (wiggle && wshear) error->all(FLERR, "{}: wiggle and shear together", who);
  check_heat();
}

int FixWallEGW::setmask()
{
  return POST_FORCE | POST_FORCE_RESPA | MIN_POST_FORCE;
}

/* the wall's temperature: a number, or v_name (an equal-style variable, evaluated every
 * step, as fix wall/gran's) */
void FixWallEGW::set_temperature(const char *word)
{
  // before and after the wall style (or the region ID) both: which one was meant?
  if (have_temperature)
    error->all(FLERR, "Fix wall/egw: keyword 'temperature' given twice ('{}' the second)", word);
  have_temperature = true;
  if (utils::strmatch(word, "^v_")) {
    tvar_name = word + 2;
    return;
  }
  if (!egw_parse_number(word, wall_temperature))
    error->all(FLERR, "Fix wall/egw: temperature = '{}': neither a finite number nor v_name",
               word);
  tvar_name.clear();
}

/* atom i's centre has reached or crossed the wall (delta >= R_i): the wall let it through
 * (too soft a wall or too large a time step); stop now, naming the overlap, rather than
 * let LAMMPS find a lost atom later */
void FixWallEGW::sank_through(int i, double delta, double radi)
{
  error->one(FLERR, "Fix wall/egw {}: atom {} sank through the wall: overlap {:.6g} >= its "
                    "radius {:.6g} (its centre reached the wall's surface): a stiffer wall "
                    "(E, or wall_material contact for fix wall/gran's E), a smaller time step or "
                    "a slower impact", id, atom->tag[i], delta, radi);
}

/* region walls: atom i (history h of the last step) has no contact now, or (h null) a
 * deep one now; if it had a deep one (overlap >= R_i/2, its wall id stored negative) or has
 * one now, and its centre is outside the region with its faces closed (an open region
 * matches every point and measures its faces from outside too), it went through a wall */
void FixWallEGW::sank_through_region(int i, const double *h)
{
  if (update->setupflag) return;
  bool deep = h == nullptr;
  for (int s = 0; h && s < (int) h[0]; s++) deep = deep || h[1 + s * (1 + nhist)] < 0.0;
  if (!deep) return;
  double *xi = atom->x[i];
  int open = region->openflag;
  region->openflag = 0;
  bool inside = region->match(xi[0], xi[1], xi[2]);
  region->openflag = open;
  if (inside) return;
  error->one(FLERR, "Fix wall/egw/region {}: atom {} sank through the region's wall: overlap "
                    ">= half its radius {:.6g} on the last step, its centre now outside the "
                    "region: a stiffer wall (E, or wall_material contact for fix wall/gran's E), "
                    "a smaller time step or a slower impact", id, atom->tag[i], atom->radius[i]);
}

void FixWallEGW::egw_fail(const std::string &what)
{
  char buf[512];
  egw_last_error(buf, sizeof(buf));
  error->all(FLERR, "Fix wall/egw: {}: {}", what, buf);
}

/* The contact's equivalent radius against a wall of radius of curvature rc at the contact
 * (LAMMPS's region convention: 0 flat, > 0 convex, < 0 concave): R_eff = R_i rc/(R_i + rc),
 * as fix wall/gran[/region] granular; <= 0 when a concave wall is tighter than the atom. */
double FixWallEGW::effective_radius(double radi, double rc) const
{
  if (rc == 0.0) return radi;
  return radi * rc / (radi + rc);
}

/* the law of the wall against particle type t: both bodies' coefficients combined, the
 * fix's sub-models, tables for R = R_eff over the type's radii and the wall's curvatures */
void FixWallEGW::build_law(int t)
{
  memo.clear();    // positions in the tables built before
  const EgwCoeff *c = pair->type_coeff(t);
  if (!c)
    error->all(FLERR, "Fix wall/egw: type {} has no pair_coeff {} {} in pair_style egw", t, t, t);
  if (c->law_file[0])
    error->all(FLERR, "Fix wall/egw: type {} has a rough-flat law (pair_coeff {} {} ... law {}): "
                      "walls do not take flat laws yet (a law is the contact's surface; the "
                      "wall contact's is not known)", t, t, t, c->law_file);
  if (model != EGW_MODEL_HERTZ && c->sigma + wall.sigma > 0 && c->mu_mode == 0 && wall.mu_mode == 0)
    error->all(FLERR, "Fix wall/egw: type {} and the wall are rough but neither gives mu or "
                      "summit data", t);
  EgwLaw L;
  if (!L.combine(*c, wall))
    error->all(FLERR, "Fix wall/egw: type {} and the wall give mu in different ways (mu vs "
                      "summit_density/summit_radius)", t);
  if (material_contact) {
    // the wall's E and nu are the contact's (fix wall/gran granular hertz/material): E*
    // and G* of two bodies of that material, E/(2(1-nu^2)) and E/(4(2-nu)(1+nu))
    L.E_star = wall.E / (2.0 * (1.0 - wall.nu * wall.nu));
    L.G_star = wall.E / (4.0 * (2.0 - wall.nu) * (1.0 + wall.nu));
  }
  L.sub = wall.sub;
  egw_flow_check(error, "Fix wall/egw", fmt::format("type {} against the wall", t),
                 L.flow_pressure, L.flow_keyword, L.E_star);
  L.setup(model);
  double rhi = pair->type_radius_max(t), rlo = pair->type_radius_min(t);
  bool radii_known = rhi > 0;
  if (L.kind == EgwLaw::HYST_RCAP && !(rhi > 0))
    error->all(FLERR, "Fix wall/egw: type {}: flow_pressure with a rough surface (sigma = "
                      "{:.6g}) needs the type's radii (no atoms and no fix pour give them): "
                      "its tables are built for the equivalent radii of the type's atoms "
                      "against the wall (the cap's first yield delta_y grows with R beside "
                      "sigma); add 'rmin R rmax R' to pair_style egw", t, L.sigma);
  if (!(rhi > 0)) rhi = rlo = 1.0 / std::max(L.inv_sigma, 1e-300);
  if (rlo > rhi || !(rlo > 0)) rlo = 0.5 * rhi;
  // a rough + cap law of one radius is one table for it (egw_law.h, HYST_RCAP), but a
  // region's curvatures give other radii
  if (rlo == rhi && (L.kind != EgwLaw::HYST_RCAP || wallstyle == REGION)) rlo = rhi / 1.05;
  if (wallstyle == ZCYLINDER) {    // R_eff grows with R_i (concave wall)
    double a = effective_radius(rlo, cyl_rc), b = effective_radius(rhi, cyl_rc);
    if (a > 0 && b > 0) rlo = a, rhi = b;
  }
  if (wallstyle == REGION && t < (int) need_rhi.size() && need_rhi[t] > 0)
    rlo = std::min(rlo, need_rlo[t]), rhi = std::max(rhi, need_rhi[t]);
  egw_flow_scale_check(error, "Fix wall/egw", fmt::format("type {} against the wall", t),
                       L.flow_pressure, L.flow_keyword, L.E_star, radii_known ? rlo : 0.0,
                       radii_known ? rhi : 0.0);
  // rough + cap with sigma far below the first-yield overlap: its Hertz + cap limit
  std::string note = L.smooth_cap_limit(rlo, rhi);
  if (!note.empty() && comm->me == 0 &&
      std::find(smooth_cap_warned.begin(), smooth_cap_warned.end(), t) == smooth_cap_warned.end()) {
    smooth_cap_warned.push_back(t);
    error->warning(FLERR, "Fix wall/egw {}: type {} against the wall: {}", id, t, note);
  }
  bool covered = built_rhi[t] > 0 && rlo >= built_rlo[t] && rhi <= built_rhi[t] &&
      law[t].kind == L.kind && law[t].E_star == L.E_star && law[t].sigma == L.sigma &&
      law[t].flow_pressure == L.flow_pressure && built_model == model;
  if (covered) return;
  law[t].release();
  law[t] = L;
  std::string what = fmt::format("tables of type {} against the wall", t);
  law[t].build(rlo, rhi, tol, overlap_max, world, comm->nprocs > 1 ? 1 : 0,
               [&](const std::string &msg) { error->all(FLERR, "Fix wall/egw: {}: {}", what, msg); });
  built_rlo[t] = rlo, built_rhi[t] = rhi;
  if (comm->me == 0)
    utils::logmesg(lmp, "fix wall/egw {}: type {}: {}\n", id, t, law[t].describe(rlo, rhi));
}

void FixWallEGW::init()
{
  if (wallstyle == REGION) {
    region = domain->get_region_by_id(region_id);
    if (!region) error->all(FLERR, "Fix wall/egw/region: region ID '{}' does not exist", region_id);
  }
  if (!tvar_name.empty()) {
    tvar = input->variable->find(tvar_name.c_str());
    if (tvar < 0)
      error->all(FLERR, "Fix wall/egw: temperature variable '{}' does not exist", tvar_name);
    if (!input->variable->equalstyle(tvar))
      error->all(FLERR, "Fix wall/egw: temperature variable '{}' is not equal-style", tvar_name);
  }
  pair = dynamic_cast<EgwTypeCoeffs *>(force->pair_match("egw", 1));
  if (!pair)
    error->all(FLERR, "Fix wall/egw needs pair_style egw (the particle types' coefficients)");
  int n = atom->ntypes;
  if ((int) law.size() != n + 1) {
    for (auto &l : law) l.release();
    law.assign(n + 1, EgwLaw());
    built_rlo.assign(n + 1, 0.0), built_rhi.assign(n + 1, 0.0);
    need_rlo.assign(n + 1, 0.0), need_rhi.assign(n + 1, 0.0);
  }
  // a curved region with summit data: the R the atoms meet, before the first build
  if (wallstyle == REGION) region_cover_radii(true);
  for (int t = 1; t <= n; t++)
    if (pair->type_coeff(t)) build_law(t);
  built_model = model;
  // a type's flow pressure given after this fix: the histories must hold the states
  bool hyst = false;
  for (int t = 1; t <= n; t++)
    hyst = hyst || law[t].kind == EgwLaw::HYST || law[t].kind == EgwLaw::HYST_MU ||
        law[t].kind == EgwLaw::HYST_CAP || law[t].kind == EgwLaw::HYST_RCAP;
  if (hyst && nhist - (hist_sub >= 0 ? EgwSubmodels::NHIST_SUB : 0) < EgwHistory::NHIST_EPGW) {
    int touching = 0, any = 0;
    for (int i = 0; i < atom->nlocal; i++) touching = touching || !cleared[i];
    MPI_Allreduce(&touching, &any, 1, MPI_INT, MPI_MAX, world);
    if (any && comm->me == 0)
      error->warning(FLERR, "Fix wall/egw {}: a type's flow pressure (given after the fix) "
                            "gives its wall contacts hysteresis: every wall contact's history "
                            "starts afresh", id);
    set_layout(EgwHistory::NHIST_EPGW);
  }
  if (wall.sub.heat != EgwSubmodels::HEAT_NONE && (!atom->temperature_flag || !atom->heatflow_flag))
    error->all(FLERR, "Fix wall/egw: a heat model needs atoms with temperature and heatflow "
                      "(fix property/atom temperature heatflow)");
}

void FixWallEGW::setup(int vflag)
{
  if (wallstyle == REGION) region_cover_radii(false);
  post_force(vflag);
}

/* Curved region walls with summit data or a rough surface with the flow-pressure cap: a
 * contact's mu (or its rough + cap table) follows its R_eff, which the region's curvature
 * moves away from R_i, so the tables must cover the R_eff the atoms can meet.  Collective: at set-up and at every reneighboring (all ranks at the same step)
 * each atom's region contacts within its reach + the neighbor skin (what it can touch
 * before the next reneighboring) are found, the ranges reduced over ranks, and a type's
 * tables rebuilt (5 % wider) when they do not cover its range.  before_build (init(),
 * the tables not built yet): the ranges only, for the first build. */
void FixWallEGW::region_cover_radii(bool before_build)
{
  int n = atom->ntypes;
  bool any = false;
  for (int t = 1; t <= n; t++) {
    if (before_build) {
      const EgwCoeff *c = pair->type_coeff(t);
      // summit data (mu follows R) or a flow pressure (rough + cap tables follow R)
      any = any || wall.mu_mode == 2 || (c && c->mu_mode == 2) || wall.flow_pressure > 0 ||
          (c && c->flow_pressure > 0);
    } else
      any = any || law[t].kind == EgwLaw::UNIVERSAL || law[t].kind == EgwLaw::HYST_MU ||
          law[t].kind == EgwLaw::HYST_RCAP;
  }
  if (!any) return;
  std::vector<double> lo(n + 1, HUGE_VAL), hi(n + 1, 0.0);
  double **x = atom->x, *radius = atom->radius;
  int *mask = atom->mask, *type = atom->type;
  if (region->dynamic_check()) region->prematch();
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit) || !region->match(x[i][0], x[i][1], x[i][2])) continue;
    int t = type[i];
    int nc = region->surface(x[i][0], x[i][1], x[i][2], radius[i] + law[t].tail + neighbor->skin);
    for (int m = 0; m < nc; m++) {
      double R = effective_radius(radius[i], region->contact[m].radius);
      if (R > 0) lo[t] = std::min(lo[t], R), hi[t] = std::max(hi[t], R);
    }
  }
  std::vector<double> glo(n + 1), ghi(n + 1);
  MPI_Allreduce(lo.data(), glo.data(), n + 1, MPI_DOUBLE, MPI_MIN, world);
  MPI_Allreduce(hi.data(), ghi.data(), n + 1, MPI_DOUBLE, MPI_MAX, world);
  for (int t = 1; t <= n; t++) {
    if (before_build) {
      if (ghi[t] > 0) need_rlo[t] = glo[t] / 1.05, need_rhi[t] = ghi[t] * 1.05;
      continue;
    }
    if (!(ghi[t] > 0) || !(law[t].kind == EgwLaw::UNIVERSAL || law[t].kind == EgwLaw::HYST_MU ||
                           law[t].kind == EgwLaw::HYST_RCAP))
      continue;
    if (glo[t] >= built_rlo[t] && ghi[t] <= built_rhi[t]) continue;
    need_rlo[t] = std::min(glo[t], built_rlo[t]) / 1.05;
    need_rhi[t] = std::max(ghi[t], built_rhi[t]) * 1.05;
    build_law(t);
  }
}

/* the 'contacts' row of atom i (fix wall/gran's columns): 1, the wall's force on the
 * atom, the contact point on the wall (the centre less dist along the normal n from the
 * wall to the centre), the atom's radius; with a heat model the heat flow into the atom */
void FixWallEGW::store_contact(int i, const double *x, const double *n, double dist,
                               const double *f, double radi, double dq)
{
  double *row = array_atom[i];
  row[0] = 1.0;
  for (int d = 0; d < 3; d++) row[1 + d] = f[d], row[4 + d] = x[d] - dist * n[d];
  row[7] = radi;
  if (ncols > 8) row[8] = dq;
}

/* One wall contact of atom i at overlap delta (R its radius, n the normal from the wall
 * to the centre, vwall the wall's velocity there, hist its history, dist the centre's
 * distance for the contacts array): the normal law, granular's sub-models, the force and
 * torque on the atom and its heat, and the contacts row. rc: the wall's radius of
 * curvature there (0 flat; for the mu message only). */
void FixWallEGW::wall_contact(int i, EgwLaw &L, double delta, double R, const double *n,
                              const double *vwall, double *hist, double dist,
                              bool update_history, double rc, EgwMemo *memo)
{
  double Fn, S, U;
  // GW/E-GW inside the inline tables and EP-GW of one table inline (egw_law.h), the rest
  // through eval (its switch and a call: ~150 instructions a contact in in.pour.drum)
  int st = L.eval_hist_fast(delta, R, hist, memo, Fn, S);
  if (st < 0) st = L.eval(delta, R, hist, Fn, S, U, 0, memo);
  if (st == EgwLaw::MU_OUTSIDE)
    error->one(FLERR, "Fix wall/egw: contact with R = {} (R_i = {}, the wall's radius of "
                      "curvature {}) has mu = {} outside the tables' [{}, {}]: widen the radius "
                      "range with pair_style egw ... rmin/rmax",
               R, atom->radius[i], rc, L.mu_at(R), L.mu_lo, L.mu_hi);
  if (st == EgwLaw::R_OTHER)
    error->one(FLERR, "Fix wall/egw: contact with R = {} (R_i = {}, the wall's radius of "
                      "curvature {}) but its rough + cap law (flow_pressure with sigma > 0) "
                      "was built for R in [{}, {}] only: give the types' radius range with "
                      "pair_style egw ... rmin/rmax", R, atom->radius[i], rc, L.rcap_R_lo,
               L.rcap_R);
  if (st == EGW_OUT_OF_RANGE && !warned_range) {
    warned_range = true;
    error->warning(FLERR, "Fix wall/egw: overlap {:.6g} = {:.3g} R (R = {:.6g}) beyond the "
                          "tables' reach {:.6g} (overlap_max = {}): force from egw's "
                          "deep-overlap law above its last node; {} (warned once)", delta,
                   delta / R, R, L.reach, overlap_max, egw_reach_advice(L));
  }
  if (st != EGW_OK && st != EGW_OUT_OF_RANGE) {
    char buf[512];
    egw_last_error(buf, sizeof(buf));
    error->one(FLERR, "Fix wall/egw: evaluation failed at overlap {}: {}", delta, buf);
  }
  if (!egw_law_finite(Fn, S))    // (an ERROR naming the atom: egw_law_finite)
    error->one(FLERR, "Fix wall/egw {}: atom {} (type {}), overlap {} (R = {}): the normal law "
                      "{} gave force {} and stiffness {}, not finite: its parameters (E, "
                      "radii) or its table file give forces beyond the doubles",
               id, atom->tag[i], atom->type[i], delta, R, egw_law_name(L), Fn, S);
  double **v = atom->v, **f = atom->f, **torque = atom->torque;
  const double zero[3] = {0.0, 0.0, 0.0}, radi = atom->radius[i];
  const bool heat = wall.sub.heat != EgwSubmodels::HEAT_NONE;
  const double vr[3] = {v[i][0] - vwall[0], v[i][1] - vwall[1], v[i][2] - vwall[2]};
  ContactForces c;
  contact_submodels(L, Fn, S, R, radi, 0.0, radi, 0.0, n, vr, atom->omega[i], zero,
                    atom->rmass[i], hist, hist_sub >= 0 ? &hist[hist_sub] : nullptr,
                    update_history, update->dt, heat ? atom->temperature[i] : 0.0,
                    wall_temperature, c);
  if (heat) atom->heatflow[i] += c.dq;
  const double fw[3] = {c.Fntot * n[0] + c.fs[0], c.Fntot * n[1] + c.fs[1],
                        c.Fntot * n[2] + c.fs[2]};
  f[i][0] += fw[0], f[i][1] += fw[1], f[i][2] += fw[2];
  torque[i][0] += c.ti[0], torque[i][1] += c.ti[1], torque[i][2] += c.ti[2];
  if (contacts) store_contact(i, atom->x[i], n, dist, fw, radi, c.dq);
}

/* atom i away from the wall: its history all zero (a new contact when it comes back),
 * written only once after it left (rewriting every far atom's EP-GW history, 55 doubles,
 * on every step was 6 % of the pour's loop); the flag moves with the atom */
inline void FixWallEGW::clear_history(int i, double *h, int n)
{
  if (cleared[i]) return;
  std::fill(h, h + n, 0.0);
  cleared[i] = 1;
}

void FixWallEGW::post_force(int /*vflag*/)
{
  if (contacts)
    for (int i = 0; i < atom->nlocal; i++)
      for (int k = 0; k < ncols; k++) array_atom[i][k] = 0.0;
  // commands between runs may change atoms without the per-atom callbacks' care for the
  // flag: each far atom's history is cleared once again in a run's set-up
  if (update->setupflag) std::fill(cleared.begin(), cleared.begin() + atom->nlocal, 0);
  // the wall temperature's variable evaluated as fix wall/gran does: without scheduling the
  // computes for the next step (clearstep/addstep_compute would make LAMMPS tally energies
  // on every step, for EP-GW a cost of its own); a variable of an energy compute stops
  // with LAMMPS's "Energy was not tallied on needed timestep", as with fix wall/gran
  if (tvar >= 0 && has_heat()) wall_temperature = input->variable->compute_equal(tvar);
  if (wallstyle == REGION) {
    post_force_region();
    return;
  }
  const bool update_history = update->setupflag == 0;
  const double dt = update->dt;
  double **x = atom->x, *radius = atom->radius;
  int *mask = atom->mask, *type = atom->type, nlocal = atom->nlocal;

  // the wall's position and velocity (wiggle along the normal, shear in its plane)
  double t = (update->ntimestep - time_origin) * dt;
  double wlo = lo, whi = hi, vwall[3] = {0.0, 0.0, 0.0};
  if (wiggle) {
    double s = amplitude * std::sin(omega * t);
    if (have_lo) wlo = lo + s;
    if (have_hi) whi = hi + s;
    vwall[wdim] = amplitude * omega * std::cos(omega * t);
  } else if (wshear)
    vwall[wdim] = vshear;

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    EgwLaw &L = law[type[i]];
    double radi = radius[i];
    // the distance from the centre to the wall (most atoms are beyond the reach: the
    // normal from the wall to the centre only for the others)
    double dist, rxy = 0.0;
    bool low = true;
    if (wallstyle == ZCYLINDER) {
      rxy = std::sqrt(x[i][0] * x[i][0] + x[i][1] * x[i][1]);
      dist = cylradius - rxy;
    } else {
      double dlo = have_lo ? x[i][axis] - wlo : HUGE_VAL;
      double dhi = have_hi ? whi - x[i][axis] : HUGE_VAL;
      low = dlo <= dhi;
      dist = low ? dlo : dhi;
    }
    double delta = radi - dist;
    if (!(delta > -L.tail)) {
      clear_history(i, history[i], nhist);
      continue;
    }
    if (!(delta < radi)) sank_through(i, delta, radi);
    double *hist = history[i];
    double n[3] = {0.0, 0.0, 0.0};
    if (wallstyle != ZCYLINDER) n[axis] = low ? 1.0 : -1.0;
    else if (rxy > 0) n[0] = -x[i][0] / rxy, n[1] = -x[i][1] / rxy;
    else n[0] = 1.0;
    cleared[i] = 0;
    if (!(built_rhi[type[i]] > 0))
      error->one(FLERR, "Fix wall/egw: an atom of type {} touches the wall but the type has no "
                        "pair_coeff in pair_style egw", type[i]);
    // the cylinder's curvature (concave) enters R as in fix wall/gran
    double R = wallstyle == ZCYLINDER ? effective_radius(radi, cyl_rc) : radi;
    if (!(R > 0))
      error->one(FLERR, "Fix wall/egw: an atom of radius {} does not fit the zcylinder of radius "
                        "{}", radi, cylradius);
    if (memo.size() < (size_t) nlocal) memo.resize(atom->nmax);
    wall_contact(i, L, delta, R, n, vwall, hist, dist, update_history,
                 wallstyle == ZCYLINDER ? cyl_rc : 0.0, &memo[i]);
  }
}

/* The region's surfaces: each atom inside the region keeps up to tmax contacts, each
 * with the id of its wall (the region's iwall) and its history; per atom: [0] the number
 * of contacts, then per slot the wall id + 1 and the history.  A contact's R is R_eff
 * from R_i and the region's radius of curvature there (flat faces: R_i). */
void FixWallEGW::post_force_region()
{
  const bool update_history = update->setupflag == 0;
  double **x = atom->x, *radius = atom->radius;
  int *mask = atom->mask, *type = atom->type, nlocal = atom->nlocal;
  if (update->setupflag == 0 && neighbor->ago == 0) region_cover_radii(false);
  if (region->dynamic_check()) region->prematch();
  bool moving = region->dynamic_check();
  if (moving) region->set_velocity();
  std::vector<double> keep((size_t) tmax * (1 + nhist));
  std::vector<int> pick(tmax), from(tmax);
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double *h = history[i];
    EgwLaw &L = law[type[i]];
    double radi = radius[i];
    int nc;
    if (cleared[i]) {
      // most atoms: a history known to be zero (the flag, not the row: reading h[0] of
      // every atom was a cache miss each, 2/3 of the fix's own time in in.pour.drum with
      // EP-GW, whose rows are ~100 doubles a slot apart). With no wall within reach there
      // is nothing to do whether the centre is inside the region or not, so the surfaces
      // are asked first and match() only for an atom that has some: match() and surface()
      // each transform the point into the rotating region's frame (a sincos each), and
      // match() on every atom was ~13 % of in.pour.drum's instructions. surface() reports
      // contacts of the region's interior side, so an atom outside rarely gets here; for
      // those (open faces, other region styles) match() decides as before.
      nc = region->surface(x[i][0], x[i][1], x[i][2], radi + L.tail);
      if (nc == 0 || !region->match(x[i][0], x[i][1], x[i][2])) continue;
    } else {
      if (!region->match(x[i][0], x[i][1], x[i][2])) {
        sank_through_region(i, h);
        clear_history(i, h, stride);
        continue;
      }
      // an atom with a contact on the last step: its first slot's lines (the history,
      // EP-GW's state, the sub-models') on their way while the region finds its surfaces
      for (int k = 0; k < 1 + (int) std::min<size_t>(1 + nhist, 64); k += 8)
        __builtin_prefetch(h + k);
      nc = region->surface(x[i][0], x[i][1], x[i][2], radi + L.tail);
    }
    int nold = (int) h[0], nnew = 0;
    if (nc == 0 && nold == 0) {
      cleared[i] = 1;
      continue;
    }
    // the contacts within reach (at most tmax) and the slot each wall had on the last step
    // (-1: a new contact). Most steps each keeps its slot (or a new one comes after the
    // old ones): then the histories are updated where they are; otherwise through keep
    // (copying every contact's history twice a step was most of the fix's memory traffic
    // in in.pour.drum with EP-GW, ~60 doubles a slot)
    const size_t width = 1 + (size_t) nhist;
    bool in_place = true;
    for (int m = 0; m < nc && nnew < tmax; m++) {
      double r = region->contact[m].r;
      if (!(radi - r > -L.tail) || !(r > 0)) continue;
      double wid = region->contact[m].iwall + 1.0;
      int s_old = -1;
      for (int s = 0; s < nold && s_old < 0; s++)    // this wall's history from the last step
        if (std::fabs(h[1 + s * width]) == wid) s_old = s;
      pick[nnew] = m, from[nnew] = s_old;
      if (s_old >= 0 ? s_old != nnew : nnew < nold) in_place = false;
      nnew++;
    }
    for (int k = 0; k < nnew; k++) {
      int m = pick[k];
      double r = region->contact[m].r;
      double delta = radi - r;
      if (!(built_rhi[type[i]] > 0))
        error->one(FLERR, "Fix wall/egw/region: an atom of type {} touches the region but the "
                          "type has no pair_coeff in pair_style egw", type[i]);
      if (delta >= 0.5 * radi) sank_through_region(i, nullptr);
      double wid = region->contact[m].iwall + 1.0;
      double *slot = in_place ? &h[1 + k * width] : &keep[k * width];
      if (from[k] < 0) std::fill(slot + 1, slot + width, 0.0);    // a new contact
      else if (!in_place)
        std::copy(&h[2 + from[k] * width], &h[1 + (from[k] + 1) * width], slot + 1);
      // the wall's id + 1, negative for a deep contact (delta >= R_i/2: sank_through_region)
      slot[0] = delta >= 0.5 * radi ? -wid : wid;
      double *hist = &slot[1];
      double n[3] = {region->contact[m].delx / r, region->contact[m].dely / r,
                     region->contact[m].delz / r};
      double R = effective_radius(radi, region->contact[m].radius);
      if (!(R > 0))
        error->one(FLERR, "Fix wall/egw/region: an atom of radius {} does not fit the region's "
                          "concave surface of radius of curvature {}", radi,
                   -region->contact[m].radius);
      double vwall[3] = {0.0, 0.0, 0.0};
      if (moving) region->velocity_contact(vwall, x[i], m);
      // several contacts: the contacts row holds the last one (as fix wall/gran/region);
      // a memo per atom index and slot (keyed by law and R as the planes': one that moved
      // to another index or slot misses once)
      if (memo.size() < (size_t) nlocal * tmax) memo.resize((size_t) atom->nmax * tmax);
      wall_contact(i, L, delta, R, n, vwall, hist, r, update_history, region->contact[m].radius,
                   &memo[(size_t) i * tmax + k]);
    }
    if (nnew == 0) sank_through_region(i, h);
    // the slots in use now (h[0] of them are read), zeros over those the last step used
    // beyond them; the rest of the stride is left as it is (writing all tmax slots of every
    // atom on every step was most of the fix's time in in.pour.drum)
    h[0] = nnew;
    if (!in_place) std::copy(keep.begin(), keep.begin() + nnew * width, h + 1);
    if (nold > nnew) std::fill(h + 1 + nnew * width, h + 1 + nold * width, 0.0);
    cleared[i] = nnew == 0;    // no slot in use: the row is all zero again
  }
}

/* ---------------------------------------------------------------------- per-atom history */

double FixWallEGW::memory_usage()
{
  return (double) atom->nmax * stride * sizeof(double) +
      (double) memo.capacity() * sizeof(EgwMemo);
}

void FixWallEGW::grow_arrays(int nmax)
{
  memory->grow(history, nmax, stride, "fix_wall_egw:history");
  cleared.resize(nmax, 0);
  if (contacts) memory->grow(array_atom, nmax, ncols, "fix_wall_egw:array_atom");
}

void FixWallEGW::copy_arrays(int i, int j, int /*delflag*/)
{
  for (int k = 0; k < stride; k++) history[j][k] = history[i][k];
  cleared[j] = cleared[i];
  if (contacts)
    for (int k = 0; k < ncols; k++) array_atom[j][k] = array_atom[i][k];
}

/* the 'contacts' rows are not exchanged: post_force fills them every step before output */
void FixWallEGW::set_arrays(int i)
{
  for (int k = 0; k < stride; k++) history[i][k] = 0.0;
  cleared[i] = 1;
  if (contacts)
    for (int k = 0; k < ncols; k++) array_atom[i][k] = 0.0;
}

int FixWallEGW::pack_exchange(int i, double *buf)
{
  for (int k = 0; k < stride; k++) buf[k] = history[i][k];
  buf[stride] = cleared[i];
  return stride + 1;
}

int FixWallEGW::unpack_exchange(int nlocal, double *buf)
{
  for (int k = 0; k < stride; k++) history[nlocal][k] = buf[k];
  cleared[nlocal] = buf[stride] != 0.0;
  return stride + 1;
}

int FixWallEGW::pack_restart(int i, double *buf)
{
  buf[0] = stride + 1;
  for (int k = 0; k < stride; k++) buf[k + 1] = history[i][k];
  return stride + 1;
}

void FixWallEGW::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  int size = static_cast<int>(extra[nlocal][m]) - 1;
  m++;
  for (int k = 0; k < stride; k++) history[nlocal][k] = k < size ? extra[nlocal][m + k] : 0.0;
  cleared[nlocal] = 0;
}

int FixWallEGW::size_restart(int /*nlocal*/)
{
  return stride + 1;
}

int FixWallEGW::maxsize_restart()
{
  return stride + 1;
}

/* ------------------------------------------------------------ the region's motion (global) */

/* a moving region's wall velocity comes from its previous displacement and angle: they go
 * into restart files, so that a run continued by read_restart moves the wall as before */
void FixWallEGW::write_restart(FILE *fp)
{
  if (wallstyle != REGION || comm->me) return;
  int len = 0;
  region->length_restart_string(len);
  fwrite(&len, sizeof(int), 1, fp);
  region->write_restart(fp);
}

void FixWallEGW::restart(char *buf)
{
  if (wallstyle != REGION) return;
  int n = 0;
  if (!region->restart(buf, n)) {
    error->warning(FLERR, "Fix wall/egw/region: region {} differs from the restart file's; "
                          "its motion starts afresh", region_id);
    region->reset_vel();
  }
}
