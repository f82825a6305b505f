/* fix wall/egw[/region]: flat, cylindrical and region walls (their curvature as in fix
 * wall/gran) with egw's rough contact law (the wall's own material and surface combined
 * with the particle type's as two types combine) and pair granular's sub-models; per-atom
 * contact histories that migrate and go into restarts; fix wall/gran's 'contacts' array.
 * See integrations/lammps/README.md. */
#ifndef EGW_LAMMPS_FIX_WALL_EGW_H
#define EGW_LAMMPS_FIX_WALL_EGW_H

#include "fix.h"

#include "egw_law.h"
#include "egw_peers.h"

#include <vector>

namespace LAMMPS_NS {

class FixWallEGW : public Fix, public EgwHeatWall {
 public:
  FixWallEGW(class LAMMPS *, int, char **);
  ~FixWallEGW() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void post_force(int) override;
  double memory_usage() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  bool has_heat() const override { return wall.sub.heat != EgwSubmodels::HEAT_NONE; }

 protected:
  enum { XPLANE = 0, YPLANE, ZPLANE, ZCYLINDER, REGION };
  int model;                       // EGW_MODEL_*
  double tol, overlap_max;
  EgwCoeff wall;                   // the wall's material, surface and sub-models
  // wall_material own: the wall's E, nu are its own, combined with the particle's (E*, G*
  // as two types); contact: they are the contact's, as fix wall/gran's (E* = E/(2(1-nu^2)))
  bool material_contact;
  int wallstyle, axis;             // axis: 0, 1, 2 (the plane's normal; z for the cylinder)
  double lo, hi, cylradius;
  double cyl_rc;                   // zcylinder: the wall's radius of curvature (-2 radius)
  bool have_lo, have_hi;
  int wiggle, wshear, wdim;        // wiggle/shear along wdim
  double amplitude, period, omega, vshear;
  bigint time_origin;
  double wall_temperature;         // heat models: the wall's temperature
  bool have_temperature;
  std::string tvar_name;           // temperature v_name: the variable's name, its index
  int tvar;
  void set_temperature(const char *word);
  int nhist, hist_sub;
  class Region *region;            // wall/egw/region: the region's surfaces
  std::string region_id;
  int tmax;                        // contacts an atom may have at once (1 for planes)
  int stride;                      // doubles per atom: planes nhist; region 1 + tmax (1 + nhist)
  double **history;                // per atom: its wall contacts' histories (0: none)
  // per atom: its history is all zero (away from the wall since it was cleared); kept
  // with the atom as its history (copy_arrays, exchange; 0 after a restart)
  std::vector<char> cleared;
  void post_force_region();
  void clear_history(int i, double *h, int n);
  bool contacts;                   // the 'contacts' per-atom array (array_atom)
  int ncols;                       // its columns: 8 (fix wall/gran's), 9 with a heat model
  // the radii R_eff (over the region's curvatures) the tables must cover (summit data)
  std::vector<double> need_rlo, need_rhi;
  double effective_radius(double radi, double rc) const;
  void region_cover_radii(bool before_build);
  std::vector<EgwLaw> law;         // per particle type
  std::vector<double> built_rlo, built_rhi;
  std::vector<int> smooth_cap_warned;    // types whose rough + cap law took Hertz + cap
  int built_model;
  bool warned_range;
  const EgwTypeCoeffs *pair;    // pair egw: the particle types' coefficients

  void parse(int, char **);
  void set_layout(int core);
  void build_law(int type);
  void store_contact(int i, const double *x, const double *n, double dist,
                     const double *f, double radi, double dq);
  void wall_contact(int i, EgwLaw &L, double delta, double R, const double *n,
                    const double *vwall, double *hist, double dist, bool update_history,
                    double rc, EgwMemo *memo = nullptr);
  // planes and cylinders: each atom index's EgwMemo (the atom's R and law are its keys:
  // one that moved to another index misses once, never reads another's position); the
  // region: one per atom index and slot (tmax each)
  std::vector<EgwMemo> memo;
  void egw_fail(const std::string &);
  void sank_through(int i, double delta, double radi);
  void sank_through_region(int i, const double *h);
};

}    // namespace LAMMPS_NS

#endif
