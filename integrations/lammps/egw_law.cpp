/* pair_style egw: building the tables of a type pair's normal law (egw_law.h). */
#include "egw_law.h"

#include "fmt/format.h"

using namespace LAMMPS_NS;

const char *LAMMPS_NS::egw_law_kind_name[] = {
    "Hertz (closed form)", "1-D table in delta/sigma",
    "1-D slices of a universal table, linear in ln mu (R-dependent mu)", "hysteresis table",
    "hysteresis tables at nodes in ln mu, linear in ln mu",
    "rough-flat law: 1-D tables at nodes in ln R, geometric in R",
    "flow-pressure cap: one hysteresis table in units of the first-yield overlap delta_y",
    "rough surface with the flow-pressure cap: hysteresis tables in delta/sigma, one per "
    "equivalent radius (one radius, or nodes in ln R, linear in ln R)"};

std::string LAMMPS_NS::egw_law_name(const EgwLaw &L)
{
  static const char *models[] = {"Hertz", "GW", "E-GW", "EP-GW"};
  const int m = L.prm.model;
  std::string name = L.kind == EgwLaw::FLAT ? std::string("law ") + L.law_file
      : m >= 0 && m < 4 ? std::string(models[m]) : fmt::format("model {}", m);
  if (L.prm.flow_pressure > 0) name += " + flow-pressure cap";
  return name + " (" + egw_law_kind_name[L.kind] + ")";
}

egw_flat_law LAMMPS_NS::egw_law_read_file(const std::string &path, MPI_Comm comm,
                                          const std::function<void(const std::string &)> &fail)
{
  int me = 0, nprocs = 1;
  MPI_Comm_rank(comm, &me);
  MPI_Comm_size(comm, &nprocs);
  egw_flat_law law = nullptr;
  int st = egw_flat_law_read(path.c_str(), &law);
  char msg[1024] = "";
  if (st != EGW_OK) egw_last_error(msg, sizeof(msg));
  // the lowest rank that failed says why, on every rank
  int first_bad = st != EGW_OK ? me : nprocs, bad = nprocs;
  MPI_Allreduce(&first_bad, &bad, 1, MPI_INT, MPI_MIN, comm);
  if (bad < nprocs) {
    MPI_Bcast(msg, sizeof(msg), MPI_CHAR, bad, comm);
    egw_flat_law_free(&law);
    fail(fmt::format("law {}: {}{}", path, msg,
                     nprocs > 1 ? fmt::format(" (rank {})", bad) : std::string()));
    return nullptr;
  }
  // every rank reads the file itself: they must have read the same law
  int n = 0, has_area = 0;
  double print[8] = {0};
  egw_flat_law_info(law, &n, &print[1], &print[2], &print[3], &print[4], &has_area);
  print[0] = n + 0.5 * has_area;
  egw_flat_law_pressure(law, print[3], &print[5], nullptr);
  egw_flat_law_pressure(law, print[4], &print[6], nullptr);
  egw_flat_law_pressure(law, 0.5 * (print[3] + print[4]), &print[7], nullptr);
  double lo[8], hi[8];
  MPI_Allreduce(print, lo, 8, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(print, hi, 8, MPI_DOUBLE, MPI_MAX, comm);
  for (int k = 0; k < 8; k++)
    if (lo[k] != hi[k]) {
      egw_flat_law_free(&law);
      fail(fmt::format("law {}: the ranks read different laws (each rank reads the file "
                       "itself: give every rank the same file)", path));
      return nullptr;
    }
  return law;
}

void EgwLaw::like(const EgwCoeff &c)
{
  E_star = c.E / (2.0 * (1.0 - c.nu * c.nu));
  double G = c.E / (2.0 * (1.0 + c.nu));
  G_star = G / (2.0 * (2.0 - c.nu));
  sigma = std::sqrt(2.0) * c.sigma;
  mu_mode = c.mu_mode, mu = c.mu, eta = c.eta, beta = c.beta;
  psi = c.psi, K = c.K, rho = c.rho, sub = c.sub;
  flow_pressure = c.flow_pressure, flow_keyword = c.flow_keyword;
  law_file = c.law_file;
}

bool EgwLaw::combine(const EgwCoeff &a, const EgwCoeff &b)
{
  E_star = 1.0 / ((1 - a.nu * a.nu) / a.E + (1 - b.nu * b.nu) / b.E);
  double Ga = a.E / (2 * (1 + a.nu)), Gb = b.E / (2 * (1 + b.nu));
  G_star = 1.0 / ((2 - a.nu) / Ga + (2 - b.nu) / Gb);
  sigma = std::sqrt(a.sigma * a.sigma + b.sigma * b.sigma);
  if (a.mu_mode != b.mu_mode && a.sigma > 0 && b.sigma > 0) return false;
  mu_mode = a.sigma > 0 ? a.mu_mode : b.mu_mode;
  const EgwCoeff &r = a.sigma > 0 ? a : b;
  if (a.sigma > 0 && b.sigma > 0) {
    mu = std::sqrt(a.mu * b.mu);
    eta = std::sqrt(a.eta * b.eta);
    beta = std::sqrt(a.beta * b.beta);
  } else {
    mu = r.mu, eta = r.eta, beta = r.beta;
  }
  psi = 0.5 * (a.psi + b.psi), K = 0.5 * (a.K + b.K), rho = 0.5 * (a.rho + b.rho);
  // the flow pressure: the smaller of the bodies' positive p_y (0: no bulk yield). Both
  // surfaces carry the same contact pressure, so the softer body reaches its p_y first and
  // from then on flows and holds the pressure there; a body without p_y does not yield
  const EgwCoeff *soft = nullptr;
  for (const EgwCoeff *c : {&a, &b})
    if (c->flow_pressure > 0 && (!soft || c->flow_pressure < soft->flow_pressure)) soft = c;
  flow_pressure = soft ? soft->flow_pressure : 0.0;
  flow_keyword = soft ? soft->flow_keyword : 0;
  // a law is the contact's (the pair's combined surface): two types with the same law
  // file mix to it (independent surfaces' spectra add: C_ij = C_ii/2 + C_jj/2 = C_law);
  // the caller refuses two different files, or a law against sigma/mu
  law_file = a.law_file;
  return true;
}

void EgwLaw::setup(int model)
{
  damp = EgwSubmodels::damping_factor(sub.damping, sub.damp_value);
  kt = sub.kt_null ? 8.0 * G_star : sub.kt;
  half_inv_E = 0.5 / E_star;
  if (!law_file.empty()) {
    // sigma: the law's length (read in build()); mu = 1 so that mu_at(R) = sqrt(R)
    kind = FLAT, mu_mode = 0, mu = 1.0;
    egw_params_default(&prm);
    prm.model = EGW_MODEL_FLAT_LAW;
    return;
  }
  if (model == EGW_MODEL_HERTZ || sigma == 0.0) kind = flow_pressure > 0 ? HYST_CAP : HERTZ;
  else if (flow_pressure > 0) kind = HYST_RCAP;
  else if (model == EGW_MODEL_EPGW && psi > 0) kind = mu_mode == 1 ? HYST : HYST_MU;
  else kind = mu_mode == 1 ? TABLE : UNIVERSAL;
  egw_params_default(&prm);
  prm.model = (model == EGW_MODEL_EPGW && psi == 0) ? EGW_MODEL_EGW : model;
  prm.radius = 1, prm.modulus = 1, prm.sigma = sigma > 0 ? 1 : 0;
  prm.mu = mu_mode == 1 ? mu : 1.0;
  prm.psi = psi, prm.hardness_coeff = K, prm.plastic_ratio = rho;
  if (sigma > 0) {
    s05 = std::sqrt(sigma), s15 = sigma * s05, s25 = s15 * sigma;
    inv_sigma = 1.0 / sigma;
  }
  if (mu_mode == 2) mu = 8.0 / 3.0 * eta * sigma * std::sqrt(2.0 * beta);    // x sqrt(R)
  if (kind == HYST_CAP || kind == HYST_RCAP) {
    double r = M_PI * flow_pressure / (2.0 * E_star);
    cap_c = r * r;
  }
}

void EgwLaw::release()
{
  table = nullptr;    // table and slices: freed with their last holder (slices_held)
  egw_universal_free(&universal);
  hyst.clear();    // shared tables: freed with their last holder
  hyst_held.clear();
  hyst_tag.clear(), hyst_dmax.clear();
  slices.clear();
  slices_held.reset();
  fast = nullptr;
  lnmu.clear();
  for (auto &t : flat) egw_table_free(&t);
  flat.clear(), flat_inv_sqrt_r.clear();
}

void EgwLaw::take_tables(EgwLaw &from)
{
  release();
  table = from.table, universal = from.universal, hyst = from.hyst;
  hyst_held = from.hyst_held, hyst_tag = from.hyst_tag, hyst_dmax = from.hyst_dmax;
  hyst_built = from.hyst_built, slices = from.slices, slices_held = from.slices_held;
  fast = from.fast, lnmu0 = from.lnmu0, inv_h = from.inv_h, lnmu = from.lnmu;
  xc = from.xc, tail = from.tail, reach = from.reach, capped = from.capped;
  tol_cap = from.tol_cap, built_tol = from.built_tol, cap_wanted = from.cap_wanted;
  capped_solver = from.capped_solver, mu_lo = from.mu_lo, mu_hi = from.mu_hi;
  interp_error = from.interp_error;
  flat = from.flat, flat_inv_sqrt_r = from.flat_inv_sqrt_r;
  law_modulus = from.law_modulus, flat_modulus = from.flat_modulus;
  flat_scale = from.flat_scale, sigma = from.sigma, inv_sigma = from.inv_sigma;
  tol_built = from.tol_built, rcap_R = from.rcap_R, rcap_F = from.rcap_F;
  rcap_R_lo = from.rcap_R_lo, rcap_R_ref = from.rcap_R_ref;
  lnr0 = from.lnr0, inv_hr = from.inv_hr;
  s05 = from.s05, s15 = from.s15, s25 = from.s25;
  from.flat.clear();
  from.universal = nullptr;    // now ours (the shared tables are counted by their holders)
  from.release();
}

void EgwLaw::build(double R_lo, double R_hi, double tol, double overlap_max, MPI_Comm comm,
                   int n_threads, const std::function<void(const std::string &)> &fail_with)
{
  release();
  auto fail = [&]() {
    char buf[1024];
    egw_last_error(buf, sizeof(buf));
    fail_with(buf);
  };
  egw_options o;
  egw_options_default(&o);
  if (n_threads > 0) o.n_threads = n_threads;
  if (kind == FLAT) {
    build_flat(R_lo, R_hi, tol, overlap_max, comm, o, fail_with);
    return;
  }
  if (kind == HYST_RCAP) {
    build_rcap(R_lo, R_hi, tol, overlap_max, comm, fail_with);
    return;
  }
  if (kind == HYST_CAP) {
    // one table in units of delta_y (universal: R = E* = 1, p_y = 2/pi), reaching
    // overlap_max R, at most CAP_X_MAX delta_y, shared through the registry (and egw's
    // disk cache: one build per machine)
    EgwTables::HystKey k;
    k.model = EGW_MODEL_HERTZ, k.flow_pressure = 2.0 / M_PI;
    cap_wanted = overlap_max / cap_c;
    k.xmax = std::min(CAP_X_MAX, cap_wanted);
    capped = cap_wanted > CAP_X_MAX;
    k.tol = tol_cap = std::max(tol, CAP_TOL_MIN);
    built_tol = tol;
    hyst_built = 0;
    hold_hysteresis({k}, comm, fail_with);
    xc = 0.0, tail = 0.0;    // a smooth sphere: no force before it touches
    reach = k.xmax * cap_c * R_hi;
    fast = nullptr;
    return;
  }
  double xmax = 30.0;
  if (sigma > 0) xmax = std::max(30.0, overlap_max * R_hi / sigma);
  // hysteresis tables capped at 140 sigma: their nodes (set-up time, memory) grow with the
  // reach, and deeper contacts take egw's deep law (a 280 sigma table is right too:
  // doc/benchmarks.md, Deep tables)
  capped = (kind == HYST || kind == HYST_MU) && xmax > HYST_X_MAX;
  if (capped) xmax = HYST_X_MAX;
  // and every table within the solver's range of delta/sigma (1e15), with room: a sigma
  // far below the radii (sigma -> 0, e.g. 1e-16 in LJ units) takes egw's deep law
  // (Hertz's constant, exact as sigma -> 0) beyond, with the reach warning
  capped_solver = xmax > TABLE_X_MAX;
  if (capped_solver) xmax = TABLE_X_MAX;
  // GW/E-GW: a law with the same normalised tables as one built before (another type pair
  // or wall fix) shares them
  EgwTables::SliceKey skey;
  skey.kind = kind, skey.model = prm.model, skey.psi = psi, skey.K = K, skey.rho = rho;
  skey.xmax = xmax, skey.tol = tol;
  if (kind == TABLE) skey.mu = mu;
  if (kind == UNIVERSAL)
    skey.mu_lo = mu * std::sqrt(R_lo) / 1.02, skey.mu_hi = mu * std::sqrt(R_hi) * 1.02;
  EgwTables::Slices shared;
  if (kind == TABLE || kind == UNIVERSAL) shared = EgwTables::find_slices(skey);
  if (shared) {
    slices_held = shared;
    xc = shared->xc, lnmu0 = shared->lnmu0, inv_h = shared->inv_h;
    interp_error = shared->interp_error;
    if (kind == TABLE) table = shared->tables[0];
    else slices = shared->tables, mu_lo = skey.mu_lo, mu_hi = skey.mu_hi;
  } else if (kind == HERTZ) {
    xc = 0, tail = 0;
  } else if (kind == TABLE) {
    if (egw_table_build(&prm, &o, 0.0, xmax, tol, &table)) fail();
    egw_table_info in;
    egw_table_get_info(table, &in);
    xc = in.cutoff;
    slices_held = std::make_shared<EgwTables::SliceSet>();
    slices_held->tables = {table};
    slices_held->fast.make(slices_held->tables);
    slices_held->xc = xc;
    EgwTables::keep_slices(skey, slices_held);
  } else if (kind == UNIVERSAL) {
    // the universal table at TOL/2, cut into 1-D slices (no solves) at nodes in ln mu; a
    // contact interpolates its two neighbouring slices linearly in ln mu, with the nodes
    // refined until that agrees with the universal table to TOL/2 at every midpoint
    mu_lo = mu * std::sqrt(R_lo) / 1.02, mu_hi = mu * std::sqrt(R_hi) * 1.02;
    if (egw_universal_build(&prm, &o, mu_lo, mu_hi, 0.0, xmax, 0.5 * tol, &universal))
      fail();
    auto slice_at = [&](double m) {
      egw_params p = prm;
      p.mu = m;
      egw_table s = nullptr;
      if (egw_universal_slice(universal, &p, &s)) fail();
      return s;
    };
    xc = 0.0;
    for (double m : {mu_lo, mu_hi}) {
      egw_table s = slice_at(m);
      egw_table_info in;
      egw_table_get_info(s, &in);
      xc = std::min(xc, in.cutoff);
      egw_table_free(&s);
    }
    std::vector<double> xs;
    for (int k = 0; k <= 40; k++) xs.push_back(xc * (1.0 - k / 40.0));
    for (int k = 1; k <= 80; k++) xs.push_back(1e-3 * std::pow(xmax / 1e-3, k / 80.0));
    double a = std::log(mu_lo), b = std::log(mu_hi);
    for (int n = 3;; n = 2 * n - 1) {
      for (auto &t : slices) egw_table_free(&t);
      slices.clear();
      double h = (b - a) / (n - 1);
      for (int k = 0; k < n; k++) slices.push_back(slice_at(std::exp(a + k * h)));
      lnmu0 = a, inv_h = 1.0 / h;
      double err = 0.0;
      for (int k = 0; k + 1 < n; k++) {
        egw_params p = prm;
        p.mu = std::exp(a + (k + 0.5) * h);
        double pref = 0, dum;
        egw_universal_eval(universal, &p, 0.0, &pref, &dum);
        for (double x : xs) {
          double pu, p0, p1;
          egw_universal_eval(universal, &p, x, &pu, &dum);
          egw_table_eval(slices[k], x, &p0, &dum);
          egw_table_eval(slices[k + 1], x, &p1, &dum);
          err = std::max(err, std::fabs(0.5 * (p0 + p1) - pu) / std::max(pu, pref));
        }
      }
      interp_error = err;
      if (err <= 0.5 * tol || n > 1000) break;
    }
    egw_universal_free(&universal);
    slices_held = std::make_shared<EgwTables::SliceSet>();
    slices_held->tables = slices;
    slices_held->fast.make(slices_held->tables);
    slices_held->xc = xc, slices_held->lnmu0 = lnmu0, slices_held->inv_h = inv_h;
    slices_held->interp_error = interp_error;
    EgwTables::keep_slices(skey, slices_held);
  } else {
    // EP-GW: one hysteresis table (mu given) or tables at nodes in ln mu (summit data),
    // normalised and shared through the registry (egw_tables.h): every type pair and wall
    // with the same mu, psi, K, rho_p, reach and TOL uses the same table
    auto key_at = [&](double m) {
      EgwTables::HystKey k;
      k.model = prm.model, k.mu = m, k.psi = psi, k.K = K, k.rho = rho;
      k.xmax = xmax, k.tol = tol;
      return k;
    };
    auto acquire = [&](const std::vector<EgwTables::HystKey> &keys) {
      xc = hold_hysteresis(keys, comm, fail_with);
    };
    hyst_built = 0;
    if (kind == HYST) {
      acquire({key_at(mu)});
    } else {
      // nodes on a lattice in ln mu shared by every law (ln mu = k h, h = ln 2 / 2^m), so
      // that laws with overlapping mu ranges share tables; linear interpolation between
      // neighbours. The level m is refined until the interpolation error, estimated from
      // second differences of the node tables (no tables between the nodes), times 1.25 is
      // within TOL of the force at the turning point. The factor covers the estimate's
      // own error: against tables built at the midpoints it was 0.93-1.14 of the
      // measured error (tools/hyst_mu_check, pour example's mu range, levels 1 and 2).
      mu_lo = mu * std::sqrt(R_lo) / 1.02, mu_hi = mu * std::sqrt(R_hi) * 1.02;
      double a = std::log(mu_lo), b = std::log(mu_hi);
      for (int level = 1;; level++) {
        double h = std::log(2.0) / (1 << level);
        int k0 = (int) std::floor(a / h), k1 = (int) std::ceil(b / h);
        if (k1 - k0 < 2) k1 = k0 + 2;    // three nodes: the estimate is a second difference
        std::vector<EgwTables::HystKey> keys;
        for (int k = k0; k <= k1; k++) keys.push_back(key_at(std::exp(k * h)));
        acquire(keys);
        interp_error = EgwTables::lnmu_error_estimate(hyst, xc, xmax);
        lnmu0 = k0 * h, inv_h = 1.0 / h;
        if (LNMU_SAFETY * interp_error <= tol || level >= LNMU_MAX_LEVEL) break;
      }
      lnmu.clear();
      for (size_t k = 0; k < hyst.size(); k++) lnmu.push_back(lnmu0 + k / inv_h);
    }
  }
  tail = -xc * sigma;
  reach = kind == HERTZ ? HUGE_VAL : xmax * sigma;
  fast = slices_held && slices_held->fast.n > 0 ? &slices_held->fast : nullptr;
}

double EgwLaw::hold_hysteresis(const std::vector<EgwTables::HystKey> &keys, MPI_Comm comm,
                               const std::function<void(const std::string &)> &fail_with)
{
  int built = 0;
  // n_threads 0: the node's processors shared among the ranks that build (egw_tables.h)
  hyst_held = EgwTables::hysteresis(keys, comm, 0, fail_with, &built);
  hyst_built += built;
  hyst.clear(), hyst_tag.clear(), hyst_dmax.clear();
  double cut = 0.0;
  for (auto &t : hyst_held) {
    hyst.push_back(t.get());
    egw_hysteresis_info in;
    egw_hysteresis_get_info(t.get(), &in);
    cut = std::min(cut, in.cutoff);    // each table ends at its own cut-off
    double tag = 0.0;
    egw_hysteresis_state_tag(t.get(), &tag);
    hyst_tag.push_back(tag), hyst_dmax.push_back(in.delta_max);
  }
  return cut;
}

void EgwLaw::build_rcap(double R_lo, double R_hi, double tol, double overlap_max,
                        MPI_Comm comm, const std::function<void(const std::string &)> &fail_with)
{
  // tables in delta/sigma with R/sigma and p_y/E*, shared through the registry (and egw's
  // disk cache) with every law of the same numbers: one for a law of one radius (R_lo =
  // R_hi: pair egw and fix wall/egw pass the types' one radius), else at the nodes of a
  // lattice in ln(R/sigma) covering [R_lo, R_hi]
  rcap_R = R_hi, rcap_R_lo = R_lo;
  // sigma far below the first-yield overlap: the callers took the law to its smooth limit
  // (smooth_cap_limit) before building; no table would build in a run here
  double ratio = sigma / (cap_c * R_hi);
  if (ratio <= RCAP_SIGMA_MIN)
    fail_with(fmt::format("sigma/delta_y = {:.3g} at or below {:g} reached the rough + cap "
                          "build (the Hertz + cap limit was not taken)", ratio, RCAP_SIGMA_MIN));
  // a build that fails (egw's solves do not converge at small sigma/delta_y, a few 1e-4
  // and below with the default reach, doc/stability.md "Stop 49 (lmp15)"): its message and
  // what the user can do
  auto fail_rcap = [&](const std::string &msg) {
    if (!(ratio < 2e-3)) fail_with(msg);
    fail_with(fmt::format("{} (rough + cap at sigma/delta_y = {:.3g}: egw's rough + cap tables "
                          "may not build below ~1e-3 of delta_y; a smaller overlap_max or TOL "
                          "1e-3 may let it build, or give sigma 0 for Hertz + cap, which "
                          "differs from this law by ~0.15 (sigma/delta_y)^(2/3) = {:.2g} of the "
                          "force)", msg, ratio, 0.15 * std::cbrt(ratio * ratio)));
  };
  // h = ln 2 / 4 first: level 1's lowest node (R steps of 41 %) may lie 29 % below R_lo
  const int FIRST_LEVEL = 2;
  double a = std::log(R_lo * inv_sigma), b = std::log(R_hi * inv_sigma);
  auto lattice = [&](int level, int &k0, int &k1) {
    double h = std::log(2.0) / (1 << level);
    k0 = (int) std::floor(a / h), k1 = (int) std::ceil(b / h);
    if (k1 - k0 < 2) k1 = k0 + 2;    // three nodes: the estimate is a second difference
    return h;
  };
  // the reach (one for every node, so that the levels share tables): overlap_max R_hi, at
  // most RCAP_X_MAX delta_y of R_lo (the node below R_lo, at most 2^(1/4) smaller from the
  // first level, 2, on, reaches up to 24 of its own), but 30 sigma where sigma is the larger
  // scale (as EP-GW's least reach), and at most egw's limit, 1000 delta_y of that node
  int k0, k1;
  lattice(FIRST_LEVEL, k0, k1);
  double r_min = R_lo == R_hi ? R_hi : sigma * std::exp(k0 * std::log(2.0) / 4);
  rcap_R_ref = R_lo;
  double dy = cap_c * R_lo;
  double want = overlap_max * R_hi;
  double lim = std::min(std::max(RCAP_X_MAX * dy, 30.0 * sigma), 1000.0 * cap_c * r_min);
  double len = std::max(std::min(want, lim), std::min(30.0 * sigma, lim));
  cap_wanted = want / dy;
  capped = want > len;
  auto key_at = [&](double R) {
    EgwTables::HystKey k;
    k.model = prm.model, k.mu = mu_mode == 1 ? mu : mu_at(R), k.psi = psi, k.K = K;
    k.rho = rho, k.flow_pressure = flow_pressure / E_star, k.radius = R / sigma;
    k.xmax = len / sigma;
    k.tol = tol;
    return k;
  };
  tol_cap = built_tol = tol;
  hyst_built = 0;
  interp_error = 0.0;
  if (R_lo == R_hi) {
    xc = hold_hysteresis({key_at(R_hi)}, comm, fail_rcap);
    lnr0 = b, inv_hr = 0.0;
  } else {
    // linear in ln R between neighbouring nodes; the level refined until the error
    // estimated from second differences of the node tables (EgwTables::lnmu_error_estimate,
    // as HYST_MU's ln mu) times LNMU_SAFETY is within TOL of the turning-point force
    for (int level = FIRST_LEVEL;; level++) {
      double h = lattice(level, k0, k1);
      std::vector<EgwTables::HystKey> keys;
      for (int k = k0; k <= k1; k++) keys.push_back(key_at(sigma * std::exp(k * h)));
      xc = hold_hysteresis(keys, comm, fail_rcap);
      interp_error = EgwTables::lnmu_error_estimate(hyst, xc, len / sigma);
      lnr0 = k0 * h, inv_hr = 1.0 / h;
      if (LNMU_SAFETY * interp_error <= tol || level >= RCAP_MAX_LEVEL) break;
    }
  }
  rcap_F = E_star * sigma * sigma;
  tail = -xc * sigma;
  reach = len;
  fast = nullptr;
}

std::string EgwLaw::smooth_cap_limit(double R_lo, double R_hi)
{
  if (kind != HYST_RCAP || !(R_hi > 0) || !(cap_c > 0)) return std::string();
  // the largest radius has the largest delta_y, so the smallest sigma/delta_y: where that
  // is at or below the limit, the nodes of the rough + cap tables there do not build
  double dy = cap_c * R_hi, ratio = sigma / dy;
  if (!(ratio <= RCAP_SIGMA_MIN)) return std::string();
  kind = HYST_CAP;
  // the bound at the smallest radius (the largest sigma/delta_y)
  double r_lo = R_lo > 0 && R_lo < R_hi ? R_lo : R_hi, worst = sigma / (cap_c * r_lo);
  std::string range = r_lo < R_hi ? fmt::format(" ({:.3g} at the smallest R = {:.6g})", worst,
                                                r_lo)
                                   : std::string();
  // the rough layer, as sigma -> 0: before contact its tail carries ~ E* sqrt(R) sigma^1.5,
  // (sigma/delta_y)^1.5 of the first-yield force E* sqrt(R) delta_y^1.5; in contact its
  // compliance moves the force by ~0.15 (sigma/delta_y)^(2/3) of it (egw's E-GW + cap
  // against the smooth cap, 1e-3 ... 1e-6 of delta_y: doc/theory.md section 12)
  return fmt::format(
      "the contact's sigma = {:.6g} with flow_pressure {:.6g}: sigma/delta_y = {:.3g} at R = "
      "{:.6g} (first yield delta_y = {:.6g}){}, at or below {:g}: the Hertz + cap table is "
      "used (rough + cap reduces to smooth + cap as sigma -> 0: the rough tail's force is "
      "~(sigma/delta_y)^1.5 = {:.2g} of the first-yield force, and the rough layer moves the "
      "loaded force by ~0.15 (sigma/delta_y)^(2/3) = {:.2g} of it); egw's rough + cap "
      "tables do not build in a run there (their solves fail or take minutes). Give sigma 0 "
      "for a smooth contact",
      sigma, flow_pressure, ratio, R_hi, dy, range, RCAP_SIGMA_MIN, worst * std::sqrt(worst),
      0.15 * std::cbrt(worst * worst));
}

void EgwLaw::build_flat(double R_lo, double R_hi, double tol, double overlap_max,
                        MPI_Comm comm, const egw_options &o,
                        const std::function<void(const std::string &)> &fail_with)
{
  egw_flat_law fl = egw_law_read_file(law_file, comm, fail_with);
  int n_nodes = 0, has_area = 0;
  double u_lo = 0, u_hi = 0;
  egw_flat_law_info(fl, &n_nodes, &sigma, &law_modulus, &u_lo, &u_hi, &has_area);
  // an elastic, frictionless, non-adhesive law is p = E* f(u): the file's law made with
  // E*_law serves the contact's E* as F(delta; E*) = (E*/E*_law) F(delta; E*_law) (the
  // deflection, pressure over E*, is the same); a law without a modulus is taken as given
  flat_modulus = law_modulus > 0 ? law_modulus : E_star;
  flat_scale = E_star / flat_modulus;
  s05 = std::sqrt(sigma), s15 = sigma * s05, s25 = s15 * sigma, inv_sigma = 1.0 / sigma;
  double xmax = std::max(30.0, overlap_max * R_hi / sigma);
  capped_solver = xmax > TABLE_X_MAX;
  if (capped_solver) xmax = TABLE_X_MAX;
  auto fail = [&]() {
    char buf[1024];
    egw_last_error(buf, sizeof(buf));
    egw_flat_law_free(&fl);
    fail_with(fmt::format("law {}: {}", law_file, buf));
  };
  // the law's sphere at R = r^2, r = sqrt(R) (the node variable), to TOL/2 (the check
  // below compares tables, so what it measures includes their own errors)
  auto table_at = [&](double r) {
    egw_params p;
    egw_params_default(&p);
    p.model = EGW_MODEL_FLAT_LAW, p.radius = r * r, p.modulus = flat_modulus;
    egw_table t = nullptr;
    if (egw_table_build_flat_law(&p, fl, &o, 0.0, xmax * sigma, 0.5 * tol, &t)) fail();
    return t;
  };
  // nodes in ln sqrt(R) over the range (2 % margin, as the ln-mu slices); the midpoints'
  // tables check the interpolation of F/sqrt(R) (geometric, as eval) to TOL/2 and become
  // nodes of the next level; the last level's midpoints are kept as nodes too
  double a = std::log(std::sqrt(R_lo) / 1.02), b = std::log(std::sqrt(R_hi) * 1.02);
  std::vector<double> r = {std::exp(a), std::exp(b)};
  flat = {table_at(r[0]), table_at(r[1])};
  auto cutoff_of = [&](egw_table t) {
    egw_table_info in;
    egw_table_get_info(t, &in);
    return in.cutoff / sigma;
  };
  for (;;) {
    std::vector<double> rm;
    std::vector<egw_table> mid;
    for (size_t k = 0; k + 1 < r.size(); k++) {
      rm.push_back(std::sqrt(r[k] * r[k + 1]));
      mid.push_back(table_at(rm.back()));
    }
    xc = 0.0;
    for (auto t : flat) xc = std::min(xc, cutoff_of(t));
    for (auto t : mid) xc = std::min(xc, cutoff_of(t));
    std::vector<double> xs;
    for (int k = 0; k <= 40; k++) xs.push_back(xc * (1.0 - k / 40.0));
    for (int k = 1; k <= 80; k++) xs.push_back(1e-3 * std::pow(xmax / 1e-3, k / 80.0));
    double err = 0.0, dum;
    for (size_t k = 0; k < mid.size(); k++) {
      double gref = 0;
      egw_table_eval(mid[k], 0.0, &gref, &dum);
      gref /= rm[k];
      for (double x : xs) {
        double fm, f0, f1;
        egw_table_eval(mid[k], x * sigma, &fm, &dum);
        egw_table_eval(flat[k], x * sigma, &f0, &dum);
        egw_table_eval(flat[k + 1], x * sigma, &f1, &dum);
        double g = fm / rm[k], g0 = f0 / r[k], g1 = f1 / r[k + 1];
        double gi = g0 > 0 && g1 > 0 ? std::sqrt(g0 * g1) : 0.5 * (g0 + g1);    // as eval
        err = std::max(err, std::fabs(gi - g) / std::max(g, gref));
      }
    }
    interp_error = err;
    std::vector<double> r2;
    std::vector<egw_table> t2;
    for (size_t k = 0; k < r.size(); k++) {
      r2.push_back(r[k]), t2.push_back(flat[k]);
      if (k < mid.size()) r2.push_back(rm[k]), t2.push_back(mid[k]);
    }
    r = r2, flat = t2;
    // at most 33 tables (set-up time: a wide radius range); the log says what was reached
    if (err <= 0.5 * tol || r.size() >= FLAT_MAX_TABLES) break;
  }
  egw_flat_law_free(&fl);
  flat_inv_sqrt_r.clear();
  for (double x : r) flat_inv_sqrt_r.push_back(1.0 / x);
  mu_lo = r.front(), mu_hi = r.back();
  tol_built = tol;
  lnmu0 = a, inv_h = (r.size() - 1) / (b - a);
  tail = -xc * sigma;
  reach = xmax * sigma;
}

std::string EgwLaw::describe(double R_lo, double R_hi) const
{
  std::string extra;
  if (kind == UNIVERSAL || kind == HYST_MU)
    extra = fmt::format(", mu in [{:.4g}, {:.4g}] for R in [{:.4g}, {:.4g}]", mu_lo, mu_hi,
                        R_lo, R_hi);
  if (kind == HYST_MU)
    extra += fmt::format(", {} mu nodes (ln mu spacing {:.4g}), estimated ln-mu interpolation "
                         "error {:.2g} of the turning-point force", lnmu.size(), 1.0 / inv_h,
                         interp_error);
  if (kind == HYST || kind == HYST_MU)
    extra += fmt::format(", hysteresis tables built for it: {} (the others shared)", hyst_built);
  if (kind == HYST_CAP) {
    // the contact radius at the reach x (delta_y): fully capped from ~20 delta_y on, x =
    // alpha^2/2 + 8 alpha/pi^2 in a_y = sqrt(R delta_y) (doc/theory.md section 12), a/R =
    // alpha sqrt(cap_c); a half-space stops being a sphere from a/R ~0.24 on (issue 32)
    double x = hyst_dmax.empty() ? 0.0 : hyst_dmax[0], k = 8.0 / (M_PI * M_PI);
    double a_r = (std::sqrt(k * k + 2.0 * x) - k) * std::sqrt(cap_c);
    extra = fmt::format(", flow pressure p_y = {:.6g} (from {}), first yield delta_y = {:.6g} R, "
                        "the table reaches {:.4g} delta_y (a/R ~{:.2g} there{}) at rel_tol "
                        "{:.2g}{}, built for it: {} (the others shared)", flow_pressure,
                        flow_keyword ? "yield_stress: 1.6 Y" : "flow_pressure", cap_c, x, a_r,
                        a_r > 0.24 ? ": the half-space model leaves its range from a/R ~0.24 on"
                                   : "",
                        tol_cap,
                        tol_cap > built_tol
                            ? fmt::format(" (TOL raised to the cap's least, {:g})", CAP_TOL_MIN)
                            : std::string(),
                        hyst_built);
  }
  if (kind == HYST_RCAP && hyst.size() <= 1)
    extra = fmt::format(", R = {:.6g} (the types' one radius), flow pressure p_y = {:.6g} (from "
                        "{}), first yield delta_y = {:.6g} ({:.4g} sigma), the table reaches "
                        "{:.4g} sigma at rel_tol {:.2g}, built for it: {} (the others shared)",
                        rcap_R, flow_pressure,
                        flow_keyword ? "yield_stress: 1.6 Y" : "flow_pressure", cap_c * rcap_R,
                        cap_c * rcap_R / sigma, hyst_dmax.empty() ? 0.0 : hyst_dmax[0], tol_cap,
                        hyst_built);
  if (kind == HYST_RCAP && hyst.size() > 1)
    extra = fmt::format(", R in [{:.6g}, {:.6g}]: {} tables at nodes in ln R (spacing {:.4g}), "
                        "estimated ln-R interpolation error {:.2g} of the turning-point "
                        "force{}, flow pressure p_y = {:.6g} (from {}), first yield delta_y = "
                        "{:.6g} R, the tables reach {:.4g} sigma at rel_tol {:.2g}, built for "
                        "it: {} (the others shared)", rcap_R_lo, rcap_R, hyst.size(), 1.0 / inv_hr,
                        interp_error,
                        LNMU_SAFETY * interp_error > tol_cap
                            ? fmt::format(" (ABOVE TOL/{:g}: the finest level {} was reached, "
                                          "narrow the radius range with rmin/rmax)",
                                          LNMU_SAFETY, (int) RCAP_MAX_LEVEL)
                            : std::string(),
                        flow_pressure, flow_keyword ? "yield_stress: 1.6 Y" : "flow_pressure",
                        cap_c, hyst_dmax.empty() ? 0.0 : hyst_dmax[0], tol_cap, hyst_built);
  if (kind == FLAT)
    extra = fmt::format(", law {} (its modulus {}; forces x E*/{:.6g}), {} tables for R in "
                        "[{:.4g}, {:.4g}], measured ln-R interpolation error {:.2g} (at twice "
                        "the final spacing; tables built to TOL/2{}); sigma below = the "
                        "law's length", law_file, law_modulus > 0 ? fmt::format("{:.6g}", law_modulus)
                        : std::string("not given: pressures as they are"), flat_modulus,
                        flat.size(), R_lo, R_hi, interp_error,
                        interp_error > 0.5 * tol_built
                            ? fmt::format("; ABOVE TOL/2 = {:.2g}: the table limit {} was "
                                          "reached, narrow the radius range (rmin/rmax)",
                                          0.5 * tol_built, (int) FLAT_MAX_TABLES)
                            : std::string());
  if (kind == UNIVERSAL)
    extra += fmt::format(", {} slices, measured ln-mu interpolation error {:.2g} "
                         "(universal table built to TOL/2)", slices.size(), interp_error);
  return fmt::format("{}, E* = {:.6g}, sigma = {:.6g}, cut-off {:.6g} (the tables' first node; "
                     "0 below), reach {:.6g}{}", egw_law_kind_name[kind], E_star, sigma,
                     xc * sigma, reach, extra) +
      (capped_solver ? fmt::format(" (capped at {:g} sigma, the solver's range)", TABLE_X_MAX)
                     : std::string()) +
      (kind == HYST_CAP && !hyst_dmax.empty() && hyst_dmax[0] >= CAP_FULL_MIN
           ? fmt::format(" (beyond it, to overlap_max R = {:.4g} delta_y and farther, the fully "
                         "capped continuation, exact in the cap model: doc/theory.md section 12)",
                         cap_wanted)
       : capped && (kind == HYST_CAP || kind == HYST_RCAP)
           ? fmt::format(" (capped at {:.4g} delta_y; overlap_max R is {:.4g} delta_y)",
                         kind == HYST_CAP ? CAP_X_MAX : reach / (cap_c * rcap_R_ref), cap_wanted)
       : capped ? fmt::format(" (capped at {} sigma: hysteresis tables beyond it cost more "
                              "than they bring)", HYST_X_MAX)
                : std::string());
}

void EgwLaw::set_reach(double w_ref, double frac, double R_hi)
{
  xt = xc, tail = -xc * sigma, tail_work = 0.0;
  if (kind == HERTZ || kind == HYST_CAP || !(sigma > 0) || !(R_hi > 0)) return;
  // the loading force p(x) of each table (R = E* = sigma = 1); the tail's work grows with
  // mu, so every node's table is integrated and the lowest reach kept
  std::vector<std::function<double(double)>> curves;
  if (kind == TABLE)
    curves.push_back([this](double x) {
      double p = 0, dp;
      egw_table_eval(table, x, &p, &dp);
      return p;
    });
  for (const egw_table &s : slices)
    curves.push_back([s](double x) {
      double p = 0, dp;
      egw_table_eval(s, x, &p, &dp);
      return p;
    });
  for (size_t k = 0; k < flat.size(); k++)    // in the units of the other tables' x, p
    curves.push_back([this, k](double x) {
      double f = 0, df;
      egw_table_eval(flat[k], x * sigma, &f, &df);
      return f * flat_inv_sqrt_r[k] / (flat_modulus * s15);
    });
  for (const egw_hysteresis &h : hyst)
    curves.push_back([h](double x) {
      double p = 0, dp, st = -HUGE_VAL;    // a new contact: the loading curve
      egw_hysteresis_eval(h, x, &st, &p, &dp);
      return p;
    });
  // the work in table units: E* sqrt(R) sigma^2.5 w(x), largest for the largest R (rough +
  // cap: its table's R/sigma, E* sigma^3 w(x))
  const double scale = kind == HYST_RCAP ? rcap_F * sigma : E_star * std::sqrt(R_hi) * s25;
  const double w_max = w_ref > 0 ? frac * w_ref / scale : 0.0;
  const double h = 1e-3;    // Simpson steps in x: the tail varies on the scale of sigma
  double x_best = 0.0, w_best = HUGE_VAL;
  for (auto &p : curves) {
    // the force step where a contact forms stays below frac of the force at delta = 0
    const double p_top = frac * p(0.0);
    // w(x) = int_{-inf}^{x} p from the cut-off (the tables give 0 below it, where the
    // model's tail holds at most p(xc) l, l = p / (dp/dx) its decay length, ~1e-12 of
    // P_ref sigma: counted, conservatively)
    double p0 = p(xc), d0 = (p(xc + 1e-6) - p0) / 1e-6;
    double w = d0 > 0 ? p0 * p0 / d0 : 0.0;
    double x = xc, xr = xc, wr = w;
    if (w_max > 0)
      while (x < 0.0) {
        double pa = p(x), pm = p(x + 0.5 * h), pb = p(x + h);
        if (pb > p_top) break;
        double wn = w + h * (pa + 4 * pm + pb) / 6;
        if (wn > w_max) break;
        w = wn, x += h;
        xr = x, wr = w;
      }
    if (xr < x_best) x_best = xr, w_best = wr;
  }
  xt = x_best;
  tail = -xt * sigma;
  tail_work = w_best * scale;
}
