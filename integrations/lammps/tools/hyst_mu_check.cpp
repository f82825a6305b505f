/* hyst_mu_check: checks two facts the plugin's EP-GW set-up rests on (egw_tables.h).
 *
 *   hyst_mu_check lattice MU_LO MU_HI LEVEL PSI K TOL XMAX
 *     nodes on the plugin's ln-mu lattice (ln mu = k h, h = ln 2 / 2^LEVEL) over
 *     [MU_LO, MU_HI]; for every interval the second-difference estimate of the linear
 *     interpolation's error (what the plugin uses) and the error measured against a table
 *     built at the interval's midpoint (the check it replaced). One line per interval:
 *       interval K MU_A MU_B estimate E midpoint M
 *   hyst_mu_check scaling R E_STAR SIGMA MU PSI K TOL XMAX
 *     a hysteresis table built with these physical parameters against the normalised one
 *     (R = E* = sigma = 1) scaled by E* sqrt(R) sigma^1.5 (force) and sigma (overlap): the
 *     largest difference at the check points relative to the turning point's force:
 *       scaling max_rel_diff D
 *   hyst_mu_check inline MODEL MU_LO MU_HI N TOL XMAX
 *     the force loop's copy of 1-D tables (EgwTables::Inline): N slices of a universal
 *     table of MODEL (2 GW, 3 E-GW) at equal steps in ln mu over [MU_LO, MU_HI] (N = 1: one
 *     slice at MU_LO), evaluated by Inline at 20000 overlaps over (cut-off, XMAX) and
 *     weights w in [0, 1] between neighbouring slices, against egw_table_eval of the two
 *     slices interpolated p0 + w (p1 - p0); the largest relative differences of force and
 *     stiffness, the tables' nodes and ln-p intervals:
 *       inline max_rel_diff D max_rel_diff_stiffness DS nodes N n_log L
 *     and the largest difference of the same evaluations with a hint (locate()'s interval
 *     carried from the last overlap, as a contact's EgwMemo) from those without: 0 expected
 *       inline hint_diff H
 * Tables are built with egw's defaults (threads, cache). */
#include "../egw_tables.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

static void fail(const std::string &m)
{
  std::fprintf(stderr, "hyst_mu_check: %s\n", m.c_str());
  std::exit(1);
}

static EgwTables::HystKey key(double mu, double psi, double K, double tol, double xmax)
{
  EgwTables::HystKey k;
  egw_params p;
  egw_params_default(&p);
  k.model = EGW_MODEL_EPGW, k.mu = mu, k.psi = psi, k.K = K, k.rho = p.plastic_ratio;
  k.tol = tol, k.xmax = xmax;
  return k;
}

static double force_after(egw_hysteresis h, double xt, double x, double scale_x)
{
  double s = -HUGE_VAL, p = 0, dp;
  egw_hysteresis_eval(h, xt * scale_x, &s, &p, &dp);
  egw_hysteresis_eval(h, x * scale_x, &s, &p, &dp);
  return p;
}

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "lattice" && argc == 9) {
    double mu_lo = atof(argv[2]), mu_hi = atof(argv[3]);
    int level = atoi(argv[4]);
    double psi = atof(argv[5]), K = atof(argv[6]), tol = atof(argv[7]), xmax = atof(argv[8]);
    double h = std::log(2.0) / (1 << level);
    int k0 = (int) std::floor(std::log(mu_lo) / h), k1 = (int) std::ceil(std::log(mu_hi) / h);
    if (k1 - k0 < 2) k1 = k0 + 2;
    std::vector<EgwTables::HystKey> keys, mids;
    for (int k = k0; k <= k1; k++) keys.push_back(key(std::exp(k * h), psi, K, tol, xmax));
    for (int k = k0; k < k1; k++) mids.push_back(key(std::exp((k + 0.5) * h), psi, K, tol, xmax));
    auto nodes = EgwTables::hysteresis(keys, MPI_COMM_WORLD, 0, fail);
    auto mid = EgwTables::hysteresis(mids, MPI_COMM_WORLD, 0, fail);
    std::vector<egw_hysteresis> raw;
    double xc = 0.0;
    for (auto &t : nodes) {
      raw.push_back(t.get());
      egw_hysteresis_info in;
      egw_hysteresis_get_info(t.get(), &in);
      xc = std::min(xc, in.cutoff);
    }
    std::vector<double> est;
    EgwTables::lnmu_error_estimate(raw, xc, xmax, &est);
    for (int k = 0; k + 1 < (int) raw.size(); k++)
      std::printf("interval %d %.6g %.6g estimate %.4e midpoint %.4e\n", k0 + k,
                  std::exp((k0 + k) * h), std::exp((k0 + k + 1) * h), est[k],
                  EgwTables::lnmu_error_midpoint(raw[k], raw[k + 1], mid[k].get(), xc, xmax));
  } else if (mode == "scaling" && argc == 10) {
    double R = atof(argv[2]), E = atof(argv[3]), sigma = atof(argv[4]), mu = atof(argv[5]);
    double psi = atof(argv[6]), K = atof(argv[7]), tol = atof(argv[8]), xmax = atof(argv[9]);
    auto unit = EgwTables::hysteresis({key(mu, psi, K, tol, xmax)}, MPI_COMM_WORLD, 0, fail);
    egw_params p;
    egw_params_default(&p);
    p.model = EGW_MODEL_EPGW, p.radius = R, p.modulus = E, p.sigma = sigma, p.mu = mu;
    p.psi = psi, p.hardness_coeff = K;
    egw_hysteresis phys = nullptr;
    if (egw_hysteresis_build(&p, nullptr, 0.0, xmax * sigma, tol, &phys)) {
      char b[1024];
      egw_last_error(b, sizeof b);
      fail(b);
    }
    egw_hysteresis_info in;
    egw_hysteresis_get_info(unit[0].get(), &in);
    double xc = in.cutoff, scale = E * std::sqrt(R) * std::pow(sigma, 1.5), d = 0.0;
    for (double xt : {-2.0, 0.0, 2.0, 10.0, 0.2 * xmax, 0.5 * xmax, xmax})
      for (double f : {1.0, 0.95, 0.8, 0.5, 0.2, 0.0}) {
        double x = xc + f * (xt - xc);
        double ft = force_after(unit[0].get(), xt, xt, 1.0);
        double a = force_after(unit[0].get(), xt, x, 1.0);
        double b = force_after(phys, xt, x, sigma) / scale;
        if (ft > 0) d = std::max(d, std::fabs(a - b) / ft);
      }
    std::printf("scaling max_rel_diff %.4e\n", d);
    egw_hysteresis_free(&phys);
  } else if (mode == "inline" && argc == 8) {
    int model = atoi(argv[2]), n = atoi(argv[5]);
    double mu_lo = atof(argv[3]), mu_hi = atof(argv[4]), tol = atof(argv[6]);
    double xmax = atof(argv[7]);
    egw_params p;
    egw_params_default(&p);
    p.model = model, p.radius = p.modulus = p.sigma = 1.0;    // normalised, as the plugin's
    egw_universal u = nullptr;
    auto check = [](int st) {
      if (st == EGW_OK) return;
      char b[1024];
      egw_last_error(b, sizeof b);
      fail(b);
    };
    check(egw_universal_build(&p, nullptr, mu_lo, n == 1 ? 1.02 * mu_lo : mu_hi, 0.0, xmax, tol,
                              &u));
    std::vector<egw_table> slices;
    for (int k = 0; k < n; k++) {
      p.mu = n == 1 ? mu_lo : std::exp(std::log(mu_lo) + k * std::log(mu_hi / mu_lo) / (n - 1));
      egw_table s = nullptr;
      check(egw_universal_slice(u, &p, &s));
      slices.push_back(s);
    }
    EgwTables::Inline fast;
    if (!fast.make(slices)) fail("Inline::make refused the slices (nodes differ)");
    double dmax = 0.0, smax = 0.0, tmax = 0.0, tsmax = 0.0, hint_diff = 0.0;
    int hint = -1;    // carried from overlap to overlap, as a contact's memo (EgwMemo)
    for (int j = 1; j < 20000; j++) {
      // overlaps crowded towards contact, where the nodes are (and the pour's contacts)
      double f = j / 20000.0, x = fast.x_lo + (fast.x_hi - fast.x_lo) * f * f * f;
      // a table over many decades (sigma -> 0, log-spaced buckets): every decade, and the
      // tail and contact in detail
      if (fast.x_hi > 1024.0 && j % 3 == 1) x = std::exp(f * std::log(fast.x_hi));
      if (fast.x_hi > 1024.0 && j % 3 == 2) x = fast.x_lo + (2.0 - fast.x_lo) * f;
      int k = n == 1 ? 0 : j % (n - 1);
      double w = n == 1 ? 0.0 : (j % 7) / 6.0, p0, d0, p1 = 0, d1 = 0, pf, df;
      if (!fast.covers(x)) continue;
      check(egw_table_eval(slices[k], x, &p0, &d0));
      if (n > 1) check(egw_table_eval(slices[k + 1], x, &p1, &d1));
      fast.eval(x, k, w, pf, df);
      // with the hint: the last overlap's interval, or one step on (a contact's next step)
      for (double xh : {x, x * (1.0 + 1e-4) + 1e-7}) {
        double ph, dh, pn, dn;
        if (!fast.covers(xh)) continue;
        fast.eval(xh, k, w, ph, dh, &hint);
        fast.eval(xh, k, w, pn, dn);
        hint_diff = std::max({hint_diff, std::fabs(ph - pn), std::fabs(dh - dn)});
      }
      double pr = n == 1 ? p0 : p0 + w * (p1 - p0), dr = n == 1 ? d0 : d0 + w * (d1 - d0);
      double ep = std::fabs(pf - pr) / std::fabs(pr);
      double es = std::fabs(df - dr) / std::max(std::fabs(dr), 1e-300);
      if (x < 0.0) {    // the resampled tail (egw_table_get_tail): slices on one grid
        tmax = std::max(tmax, ep), tsmax = std::max(tsmax, es);
      } else {
        dmax = std::max(dmax, ep), smax = std::max(smax, es);
      }
    }
    std::printf("inline max_rel_diff %.4e max_rel_diff_stiffness %.4e nodes %d n_log %d\n", dmax,
                smax, fast.n, fast.n_log);
    std::printf("inline tail_rel_diff %.4e tail_rel_diff_stiffness %.4e tol %.4e\n", tmax,
                tsmax, tol);
    std::printf("inline hint_diff %.4e\n", hint_diff);
    for (auto &s : slices) egw_table_free(&s);
    egw_universal_free(&u);
  } else {
    std::fprintf(stderr, "usage: hyst_mu_check lattice MU_LO MU_HI LEVEL PSI K TOL XMAX\n"
                         "       hyst_mu_check scaling R E_STAR SIGMA MU PSI K TOL XMAX\n"
                         "       hyst_mu_check inline MODEL MU_LO MU_HI N TOL XMAX\n");
    return 2;
  }
  MPI_Finalize();
  return 0;
}
