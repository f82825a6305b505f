/* pair_style egw: egw's rough-sphere normal contact (Hertz, GW, E-GW, EP-GW) as a LAMMPS
 * granular pair style, with coeff_restitution damping, Mindlin friction and per-contact
 * histories kept by a fix NEIGH_HISTORY.  Loaded as a plugin (egwplugin.cpp); see
 * integrations/lammps/README.md for the syntax and the physics. */
#ifndef EGW_PAIR_EGW_H
#define EGW_PAIR_EGW_H

#include "pair.h"

#include "egw.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

/* The contact law of one particle-type pair: parameters and the egw tables that evaluate
 * it.  Tables are normalised (R = E* = sigma = 1, x = delta/sigma) unless stated. */
struct EgwLaw {
  // the coefficients as given or mixed
  double E_star = 0, G_star = 0, sigma = 0;
  int mu_mode = 0;                 // 0 none (smooth), 1 mu given, 2 from summit data
  double mu = 0, eta = 0, beta = 0;
  double psi = 0, K = 0.6, rho = 54;
  double e = 1, damp = 0;          // restitution e; damp = 2 sqrt(5/6) beta(e)
  double mu_t = 0;                 // Coulomb friction coefficient (0: no friction)
  // evaluation
  int kind = 0;                    // KIND_* in pair_egw.cpp
  double xc = 0;                   // cut-off delta_c/sigma (<= 0)
  double tail = 0;                 // -delta_c [length]
  double s05 = 0, s15 = 0, s25 = 0, inv_sigma = 0;
  double mu_lo = 0, mu_hi = 0;     // mu range of the tables (summit data)
  double interp_error = 0;         // measured ln-mu interpolation error (EP-GW, summits)
  egw_table table = nullptr;
  egw_universal universal = nullptr;
  std::vector<egw_hysteresis> hyst;
  std::vector<egw_table> slices;   // 1-D slices of universal at nodes in ln mu (summit data)
  double lnmu0 = 0, inv_h = 0;     // first node, 1 / node spacing
  std::vector<double> lnmu;        // nodes of hyst in ln mu (summit data)
  egw_params prm{};                // model, psi, K, rho_p (+ R, E, sigma, mu at eval)
  void release();
};

class PairEGW : public Pair {
 public:
  PairEGW(class LAMMPS *);
  ~PairEGW() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  double single(int, int, int, int, double, double, double, double &) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  void transfer_history(double *, double *, int, int) override;
  double memory_usage() override;

 protected:
  int model;            // EGW_MODEL_*
  int nhist;            // doubles of history per contact (NHIST_* in pair_egw.cpp)
  double tol;           // table tolerance
  double rmin_user, rmax_user, overlap_max;
  class Fix *fix_history;
  int freeze_group_bit;
  bool tables_ready;
  bool warned_range;
  int built_model;                           // settings the tables were built with
  double built_tol, built_overlap;    // one warning per rank for overlaps beyond the tables

  // per type (index 1..ntypes): own coefficients as given with pair_coeff I I
  struct Coeff {
    int set = 0;
    double E = 0, nu = 0, sigma = 0, mu = 0, eta = 0, beta = 0;
    int mu_mode = 0;
    double psi = 0, K = 0.6, rho = 54, e = 1, mu_t = 0;
  };
  std::vector<std::vector<Coeff>> pcoeff;    // [i][j], explicit pair_coeff I J
  std::vector<std::vector<EgwLaw>> law;      // [i][j] = [j][i]
  std::vector<double> rad_max, rad_min;      // per type, for cut-offs and table ranges
  std::vector<std::vector<double>> built_rlo, built_rhi;

  void allocate();
  void parse_coeff(int, char **, Coeff &);
  void make_law(int, int);
  void build_tables(int, int, double, double);
  void type_radii();
  void egw_fail(const std::string &what);
  inline double mu_position(EgwLaw &, double R, double *hist);
  inline void normal(EgwLaw &, double delta, double R, double *hist, double &F, double &S,
                     double &U, int want_energy);
};

}    // namespace LAMMPS_NS

#endif
