/* pair_style egw: the contact's sub-models beside egw's normal law, by pair granular's
 * names and formulas (LAMMPS manual, pair_style granular): normal damping, tangential,
 * rolling, twisting and heat.  Where granular uses the contact radius a, egw's contact
 * radius a = S/(2 E*) is used (S = dP/ddelta egw's normal stiffness: Hertz's sqrt(R delta)
 * for a smooth contact; for any axisymmetric contact the radius that gives its incremental
 * stiffness, Barber's theorem).  Inline: called once per contact and step. */
#ifndef EGW_LAMMPS_SUBMODELS_H
#define EGW_LAMMPS_SUBMODELS_H

#include <algorithm>
#include <cmath>

namespace LAMMPS_NS {
namespace EgwSubmodels {

enum Damping { DAMP_VELOCITY = 0, DAMP_MASS_VELOCITY, DAMP_VISCOELASTIC, DAMP_TSUJI,
               DAMP_COEFF_RESTITUTION, DAMP_NONE };
enum Tangential { TANG_NONE = 0, TANG_LINEAR_NOHISTORY, TANG_LINEAR_HISTORY, TANG_MINDLIN,
                  TANG_MINDLIN_RESCALE, TANG_MINDLIN_FORCE, TANG_MINDLIN_RESCALE_FORCE };
enum Rolling { ROLL_NONE = 0, ROLL_SDS };
enum Twisting { TWIST_NONE = 0, TWIST_MARSHALL, TWIST_SDS };
enum Heat { HEAT_NONE = 0, HEAT_AREA, HEAT_RADIUS };

constexpr double TWO_ROOT_FIVE_SIXTHS = 1.82574185835055380345;    // 2 sqrt(5/6)
constexpr double EPSILON = 1e-10;    // granular's threshold for rotating a history

// per contact, after the normal law's history: the contact radius of the last step
// (mindlin_rescale), the rolling displacement (3) and the twisting angle
constexpr int SUB_A_PREV = 0, SUB_ROLL = 1, SUB_TWIST = 4, NHIST_SUB = 5;

/* the sub-models of a type pair as given (plain data: written to restart files) */
struct Params {
  int damping = DAMP_VISCOELASTIC;    // granular's default
  double damp_value = 1.0;    // e (tsuji, coeff_restitution) or eta_n0 (the others)
  int damp_value_set = 0;
  int limit_damping = 0;
  int tangential = TANG_NONE;
  int kt_null = 1;            // mindlin: k_t = 8 G* (NULL)
  double kt = 0, xt = 0, mu_t = 0;
  int rolling = ROLL_NONE;
  double kr = 0, gr = 0, mur = 0;
  int twisting = TWIST_NONE;
  double ktw = 0, gtw = 0, mutw = 0;
  int heat = HEAT_NONE;
  double heat_coeff = 0;
  bool needs_extra_history() const
  {
    return tangential == TANG_MINDLIN_RESCALE || tangential == TANG_MINDLIN_RESCALE_FORCE ||
        rolling != ROLL_NONE || twisting != TWIST_NONE;
  }
  bool tangential_history() const { return tangential >= TANG_LINEAR_HISTORY; }
};

/* the damping model's constant factor: coeff_restitution 2 sqrt(5/6) beta(e) with beta =
 * -ln e / sqrt(pi^2 + ln^2 e); tsuji alpha(e) (Marshall's polynomial, eq. 53) times
 * sqrt(2/3); the others eta_n0 itself */
inline double damping_factor(int model, double value)
{
  if (model == DAMP_NONE) return 0.0;
  if (model == DAMP_COEFF_RESTITUTION) {
    if (!(value < 1.0)) return 0.0;
    double le = std::log(value);
    return TWO_ROOT_FIVE_SIXTHS * (-le) / std::sqrt(M_PI * M_PI + le * le);
  }
  if (model == DAMP_TSUJI) {
    double e = value, e2 = e * e;
    double alpha = 1.2728 - 4.2783 * e + 11.087 * e2 - 22.348 * e2 * e + 27.467 * e2 * e2 -
        18.022 * e2 * e2 * e + 4.8218 * e2 * e2 * e2;
    return alpha * std::sqrt(2.0 / 3.0);
  }
  return value;
}

/* eta_n of the damping model: velocity eta0, mass_velocity eta0 m*, viscoelastic
 * eta0 m* a, tsuji and coeff_restitution factor sqrt(m* S) (granular's sqrt(m* F/delta)
 * with its Hertz secant stiffness F/delta = 2/3 S, folded into the factor for tsuji; for
 * coeff_restitution granular's sqrt(3/2) makes it S).  Zero out of contact (S <= 0). */
inline double damping_eta(int model, double factor, double meff, double S, double a)
{
  if (!(S > 0)) return 0.0;
  switch (model) {
    case DAMP_VELOCITY: return factor;
    case DAMP_MASS_VELOCITY: return factor * meff;
    case DAMP_VISCOELASTIC: return factor * meff * a;
    default: return factor * std::sqrt(meff * S);
  }
}

/* remove the component of v along n and restore its length (a history follows the
 * tangent plane as the contact tumbles) */
inline void rotate_rescale(double *v, const double *n)
{
  double mag = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  double vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
  v[0] -= vn * n[0], v[1] -= vn * n[1], v[2] -= vn * n[2];
  double mag2 = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (mag2 > 0) {
    double s = mag / mag2;
    v[0] *= s, v[1] *= s, v[2] *= s;
  }
}

inline double len3(const double *v)
{
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* The tangential force fs on i.  n: unit normal (from j to i), vt: relative tangential
 * velocity at the contact, eta_t = x_t eta_n, Fscrit = mu_t F_n0, k: the spring
 * (linear_history: k_t; mindlin family: k_t a), xi: the displacement (or, /force
 * variants, the elastic force) kept per contact, a_prev: the last contact radius
 * (rescale variants; nullptr otherwise). */
inline void tangential_force(int model, double k, double eta_t, double Fscrit, double a,
                             const double *n, const double *vt, double *xi, double *a_prev,
                             bool update, double dt, double *fs)
{
  if (model == TANG_LINEAR_NOHISTORY) {
    double vrel = len3(vt);
    double f = vrel != 0.0 ? std::min(Fscrit, eta_t * vrel) / vrel : 0.0;
    fs[0] = -f * vt[0], fs[1] = -f * vt[1], fs[2] = -f * vt[2];
    return;
  }
  const bool force_hist = model == TANG_MINDLIN_FORCE || model == TANG_MINDLIN_RESCALE_FORCE;
  // on unloading, the rescale variants shrink the history with the contact radius
  if (a_prev && a < *a_prev && *a_prev > 0) {
    double s = a / *a_prev;
    xi[0] *= s, xi[1] *= s, xi[2] *= s;
  }
  if (update) {
    double rsht = xi[0] * n[0] + xi[1] * n[1] + xi[2] * n[2];
    double lever = force_hist ? 1.0 : k;
    if (std::fabs(rsht) * lever > EPSILON * Fscrit) rotate_rescale(xi, n);
    double step = force_hist ? -k * dt : dt;
    xi[0] += step * vt[0], xi[1] += step * vt[1], xi[2] += step * vt[2];
    if (a_prev) *a_prev = a;
  }
  double fd[3] = {-eta_t * vt[0], -eta_t * vt[1], -eta_t * vt[2]};
  if (force_hist) fs[0] = xi[0], fs[1] = xi[1], fs[2] = xi[2];
  else fs[0] = -k * xi[0], fs[1] = -k * xi[1], fs[2] = -k * xi[2];
  fs[0] += fd[0], fs[1] += fd[1], fs[2] += fd[2];
  double f = len3(fs);
  if (f > Fscrit) {
    if (len3(xi) != 0.0) {
      double s = Fscrit / f;
      fs[0] *= s, fs[1] *= s, fs[2] *= s;
      // the history becomes the elastic part of the limited force
      xi[0] = fs[0] - fd[0], xi[1] = fs[1] - fd[1], xi[2] = fs[2] - fd[2];
      if (!force_hist) {
        double inv = k > 0 ? -1.0 / k : 0.0;
        xi[0] *= inv, xi[1] *= inv, xi[2] *= inv;
      }
    } else
      fs[0] = fs[1] = fs[2] = 0.0;
  }
}

/* Rolling sds: the rolling resistance fr (a force at the contact; its torque on i is
 * R n x fr) from the rolling displacement rd, k_r, gamma_r and the limit mu_r F_n0;
 * vrl = R (omega_i - omega_j) x n. */
inline void rolling_sds(double kr, double gr, double Frcrit, const double *n, const double *vrl,
                        double *rd, bool update, double dt, double *fr)
{
  double h[3] = {rd[0], rd[1], rd[2]};
  if (update) {
    double rn = h[0] * n[0] + h[1] * n[1] + h[2] * n[2];
    if (std::fabs(rn) * kr > EPSILON * Frcrit) rotate_rescale(h, n);
    h[0] += dt * vrl[0], h[1] += dt * vrl[1], h[2] += dt * vrl[2];
  }
  for (int d = 0; d < 3; d++) fr[d] = -kr * h[d] - gr * vrl[d];
  double f = len3(fr);
  if (f > Frcrit) {
    if (len3(h) != 0.0 && kr > 0) {
      for (int d = 0; d < 3; d++) h[d] = -(Frcrit / (kr * f)) * fr[d] - gr / kr * vrl[d];
      double s = Frcrit / f;
      fr[0] *= s, fr[1] *= s, fr[2] *= s;
    } else
      fr[0] = fr[1] = fr[2] = 0.0;
  }
  if (update) rd[0] = h[0], rd[1] = h[1], rd[2] = h[2];
}

/* Twisting (Marshall's eqs. 30, 34, 44): the twisting torque about n from the twist
 * angle tw, stiffness k, damping g and the limit Mtcrit; magtwist = (omega_i - omega_j).n */
inline double twisting_torque(double k, double g, double Mtcrit, double magtwist, double *tw,
                              bool update, double dt)
{
  if (update) *tw += magtwist * dt;
  double M = -k * *tw - g * magtwist;
  double sign = (magtwist > 0) - (magtwist < 0);
  if (std::fabs(M) > Mtcrit) {
    *tw = k > 0 ? (Mtcrit * sign - g * magtwist) / k : 0.0;
    M = -Mtcrit * sign;
  }
  return M;
}

/* heat flowing into i: radius 2 k_s a (T_j - T_i), area h_s pi a^2 (T_j - T_i) */
inline double heat_flow(int model, double coeff, double a, double Ti, double Tj)
{
  if (model == HEAT_RADIUS) return 2.0 * coeff * a * (Tj - Ti);
  if (model == HEAT_AREA) return coeff * M_PI * a * a * (Tj - Ti);
  return 0.0;
}

}    // namespace EgwSubmodels
}    // namespace LAMMPS_NS

#endif
