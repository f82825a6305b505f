/* pair_style egw: the contact's sub-models beside egw's normal law, as pair granular
 * names them: normal damping (coeff_restitution with egw's stiffness) and the tangential
 * Mindlin spring with its Coulomb limit.  Inline: called once per contact and step. */
#ifndef EGW_LAMMPS_SUBMODELS_H
#define EGW_LAMMPS_SUBMODELS_H

#include <cmath>

namespace LAMMPS_NS {
namespace EgwSubmodels {

constexpr double TWO_ROOT_FIVE_SIXTHS = 1.82574185835055380345;    // 2 sqrt(5/6)

/* 2 sqrt(5/6) beta(e), beta = -ln e / sqrt(pi^2 + ln^2 e): the coeff_restitution factor */
inline double restitution_factor(double e)
{
  if (!(e < 1.0)) return 0.0;
  double le = std::log(e);
  return TWO_ROOT_FIVE_SIXTHS * (-le) / std::sqrt(M_PI * M_PI + le * le);
}

/* damping coeff_restitution: -eta v_n with eta = factor sqrt(m* S), S = egw's dP/ddelta
 * (for Hertz S = 2 E* a, pair granular's own eta); none where S <= 0 */
inline double damping_force(double factor, double meff, double S, double vn)
{
  if (factor > 0 && S > 0) return -factor * std::sqrt(meff * S) * vn;
  return 0.0;
}

/* Mindlin tangential spring k_t = 8 G* a with a = S/(2 E*) (the contact radius for Hertz),
 * the displacement xi kept in the tangent plane at its length (as pair granular) and
 * advanced by vt dt when the history is updated, the force limited to mu_t |F_n|.
 * n: the unit normal, vt: the relative tangential velocity at the contact; fs: the force. */
inline void mindlin(double G_star, double E_star, double mu_t, double S, double Fn,
                    const double *n, const double *vt, double *xi, bool update, double dt,
                    double *fs)
{
  double kt = S > 0 ? 4.0 * G_star / E_star * S : 0.0;
  if (update) {
    double rsht = xi[0] * n[0] + xi[1] * n[1] + xi[2] * n[2];
    if (rsht != 0.0) {    // keep the displacement in the tangent plane, same length
      double mag = std::sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
      xi[0] -= rsht * n[0], xi[1] -= rsht * n[1], xi[2] -= rsht * n[2];
      double mag2 = std::sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
      if (mag2 > 0) {
        double s = mag / mag2;
        xi[0] *= s, xi[1] *= s, xi[2] *= s;
      }
    }
    xi[0] += vt[0] * dt, xi[1] += vt[1] * dt, xi[2] += vt[2] * dt;
  }
  fs[0] = -kt * xi[0], fs[1] = -kt * xi[1], fs[2] = -kt * xi[2];
  double f = std::sqrt(fs[0] * fs[0] + fs[1] * fs[1] + fs[2] * fs[2]);
  double fcrit = mu_t * std::fabs(Fn);
  if (f > fcrit) {
    if (f > 0 && kt > 0) {
      double s = fcrit / f;
      fs[0] *= s, fs[1] *= s, fs[2] *= s;
      xi[0] = -fs[0] / kt, xi[1] = -fs[1] / kt, xi[2] = -fs[2] / kt;
    } else
      fs[0] = fs[1] = fs[2] = 0.0;
  }
}

}    // namespace EgwSubmodels
}    // namespace LAMMPS_NS

#endif
