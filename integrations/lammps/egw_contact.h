/* pair_style egw and fix wall/egw: one contact's sub-model forces and torques beside the
 * normal law, in pair granular's order (damping, tangential, rolling, twisting, heat). */
#ifndef EGW_LAMMPS_CONTACT_H
#define EGW_LAMMPS_CONTACT_H

#include "egw_law.h"
#include "egw_submodels.h"

#include <cmath>

namespace LAMMPS_NS {
/* what the sub-models add to a contact's elastic normal force */
struct ContactForces {
  double Fdamp = 0, Fntot = 0;
  double fs[3] = {0, 0, 0};    // tangential force on i
  double fr[3] = {0, 0, 0};    // rolling resistance (its torque on i: R n x fr)
  double Mtw = 0;              // twisting torque on i about n
  double ti[3] = {0, 0, 0}, tj[3] = {0, 0, 0};    // torques on i and j
  double dq = 0;               // heat into i
};

/* granular's sequence for one contact: damping, F_n0 = |F_n|, tangential, rolling,
 * twisting, heat.  R: the rolling radius (the pair's equivalent radius, a wall's R_i);
 * radi, radj: the radii in the tangential velocity (radj = 0 for a wall); lever_i,
 * lever_j: the tangential force's lever arms (R - delta/2 for pairs, R_i for walls, as
 * granular); vr = v_i - v_j, wi/wj the spins, a = S/(2 E*) egw's contact radius; sub: the
 * sub-models' history (nullptr when no contact needs it). */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
inline void contact_submodels(const EgwLaw &L, double Fn, double S, double R, double radi,
                              double radj, double lever_i, double lever_j, const double *n,
                              const double *vr,
                              const double *wi, const double *wj, double meff, double *hist,
                              double *sub, bool update, double dt, double Ti, double Tj,
                              ContactForces &c)
{
  using namespace EgwSubmodels;
  const Params &P = L.sub;
  const double a = S > 0 ? S * L.half_inv_E : 0.0;
  double vnn = vr[0] * n[0] + vr[1] * n[1] + vr[2] * n[2];
  double eta_n = L.damp > 0 ? damping_eta(P.damping, L.damp, meff, S, a) : 0.0;
  c.Fdamp = -eta_n * vnn;
  c.Fntot = Fn + c.Fdamp;
  if (P.limit_damping && c.Fntot < 0.0) c.Fntot = 0.0;
  const double Fncrit = std::fabs(c.Fntot);
  if (P.tangential != TANG_NONE) {
    double w[3] = {radi * wi[0] + radj * wj[0], radi * wi[1] + radj * wj[1],
                   radi * wi[2] + radj * wj[2]};
    const double vt[3] = {vr[0] - vnn * n[0] - (w[1] * n[2] - w[2] * n[1]),
                          vr[1] - vnn * n[1] - (w[2] * n[0] - w[0] * n[2]),
                          vr[2] - vnn * n[2] - (w[0] * n[1] - w[1] * n[0])};
    double k = P.tangential == TANG_LINEAR_HISTORY ? L.kt : L.kt * a;
    double *a_prev = (P.tangential == TANG_MINDLIN_RESCALE ||
                      P.tangential == TANG_MINDLIN_RESCALE_FORCE) ? &sub[SUB_A_PREV] : nullptr;
    tangential_force(P.tangential, k, P.xt * eta_n, P.mu_t * Fncrit, a, n, vt,
                     &hist[EgwHistory::SHEAR], a_prev, update, dt, c.fs);
    // torques: - (n x fs) times the distance from each centre to the contact plane
    double t[3] = {n[1] * c.fs[2] - n[2] * c.fs[1], n[2] * c.fs[0] - n[0] * c.fs[2],
                   n[0] * c.fs[1] - n[1] * c.fs[0]};
    for (int d = 0; d < 3; d++) c.ti[d] = -lever_i * t[d], c.tj[d] = -lever_j * t[d];
  }
  if (P.rolling == ROLL_NONE && P.twisting == TWIST_NONE && P.heat == HEAT_NONE) return;
  double rel[3] = {wi[0] - wj[0], wi[1] - wj[1], wi[2] - wj[2]};
  if (P.rolling == ROLL_SDS) {
    const double vrl[3] = {R * (rel[1] * n[2] - rel[2] * n[1]), R * (rel[2] * n[0] - rel[0] * n[2]),
                           R * (rel[0] * n[1] - rel[1] * n[0])};
    rolling_sds(P.kr, P.gr, P.mur * Fncrit, n, vrl, &sub[SUB_ROLL], update, dt, c.fr);
    double tr[3] = {R * (n[1] * c.fr[2] - n[2] * c.fr[1]), R * (n[2] * c.fr[0] - n[0] * c.fr[2]),
                    R * (n[0] * c.fr[1] - n[1] * c.fr[0])};
    for (int d = 0; d < 3; d++) c.ti[d] += tr[d], c.tj[d] -= tr[d];
  }
  if (P.twisting != TWIST_NONE) {
    double magtwist = rel[0] * n[0] + rel[1] * n[1] + rel[2] * n[2];
    double k, g, mu;
    if (P.twisting == TWIST_MARSHALL) {    // Marshall's eq. 32, from the tangential model
      k = 0.5 * L.kt * a * a, g = 0.5 * P.xt * eta_n * a * a, mu = 2.0 / 3.0 * P.mu_t * a;
    } else
      k = P.ktw, g = P.gtw, mu = P.mutw;
    c.Mtw = twisting_torque(k, g, mu * Fncrit, magtwist, &sub[SUB_TWIST], update, dt);
    for (int d = 0; d < 3; d++) c.ti[d] += c.Mtw * n[d], c.tj[d] -= c.Mtw * n[d];
  }
  if (P.heat != HEAT_NONE) c.dq = heat_flow(P.heat, P.heat_coeff, a, Ti, Tj);
}
}    // namespace LAMMPS_NS

#endif
