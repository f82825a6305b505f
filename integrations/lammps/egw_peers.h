/* What pair egw and fix wall/egw ask of each other, as two small interfaces: a wall reads
 * the particle types' coefficients and radii from the pair style, the pair style asks the
 * walls whether one exchanges heat.  Each class implements its side, so neither source
 * includes the other's header. */
#ifndef EGW_LAMMPS_PEERS_H
#define EGW_LAMMPS_PEERS_H

namespace LAMMPS_NS {

struct EgwCoeff;

/* pair egw as the walls see it */
class EgwTypeCoeffs {
 public:
  /* a type's own coefficients (pair_coeff I I); nullptr if not set */
  virtual const EgwCoeff *type_coeff(int t) const = 0;
  /* the largest and smallest radius of the type's atoms (0 while unknown) */
  virtual double type_radius_max(int t) const = 0;
  virtual double type_radius_min(int t) const = 0;

 protected:
  ~EgwTypeCoeffs() = default;
};

/* a wall/egw fix as the pair style sees it */
class EgwHeatWall {
 public:
  /* the wall exchanges heat with the atoms (a heat model) */
  virtual bool has_heat() const = 0;

 protected:
  ~EgwHeatWall() = default;
};

}    // namespace LAMMPS_NS

#endif
