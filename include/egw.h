/*
 * egw.h - C API of egw, the extended Greenwood-Williamson contact library
 * (Zhao & Feng 2018, J. Appl. Mech. 85:101007, with the misprints listed in
 * DESIGN.md section 6 corrected).
 *
 * Conventions
 *   - Units: any consistent set (e.g. SI: m, Pa, N). Results carry the units
 *     implied by the inputs: force = modulus * length^2, pressure = modulus.
 *   - delta is the overlap of the undeformed sphere with the mean summit
 *     plane: > 0 overlap, < 0 separation. Forces and pressures are positive
 *     in compression.
 *   - Every int function returns EGW_OK (0) on success and a non-zero status
 *     otherwise; it never aborts. On failure, outputs are left unchanged and
 *     egw_last_error() returns a message naming the offending argument.
 *   - All functions are thread-safe: they keep no shared state (the last-error
 *     message is per thread).
 */
#ifndef EGW_H
#define EGW_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Version of this header; egw_get_version() returns the library's. */
#define EGW_VERSION 100

/* Status codes. */
enum {
  EGW_OK = 0,
  EGW_INVALID_ARGUMENT = 1,  /* an argument of the call is invalid (NaN, out of domain) */
  EGW_INVALID_PARAMETER = 2, /* a field of egw_params failed validation */
  EGW_NOT_CONVERGED = 3,     /* an iterative solve did not converge */
  EGW_IO_ERROR = 4,          /* a file could not be opened, written or renamed */
  EGW_BAD_FILE = 5,          /* a file is truncated, corrupted or of an unknown version */
  EGW_OUT_OF_MEMORY = 6,     /* an allocation failed */
  EGW_NULL_POINTER = 7,      /* a required pointer argument was NULL */
  EGW_OUT_OF_RANGE = 8,      /* an argument lies outside a table's range */
  EGW_UNSUPPORTED = 9        /* a valid request that egw does not support */
};

/* Models. */
enum {
  EGW_MODEL_HERTZ = 0, /* smooth spheres, closed form */
  EGW_MODEL_GW = 1,    /* classic Greenwood-Williamson / Greenwood-Tripp */
  EGW_MODEL_EGW = 2,   /* extended elastic GW */
  EGW_MODEL_EPGW = 3   /* extended elasto-plastic GW (ZMC asperities) */
};

/* Parameters of one contact (DESIGN.md section 1). */
typedef struct {
  int    model;          /* EGW_MODEL_HERTZ=0, EGW_MODEL_GW=1, EGW_MODEL_EGW=2, EGW_MODEL_EPGW=3 */
  double radius;         /* equivalent radius R, 1/R = 1/R1 + 1/R2; > 0 */
  double modulus;        /* effective modulus E*, 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2; > 0 */
  double sigma;          /* std of summit heights, sigma^2 = sigma1^2 + sigma2^2; 0 = smooth */
  double mu;             /* Greenwood-Tripp mu = (8/3) eta sigma sqrt(2 R beta); > 0 if sigma > 0 */
  double psi;            /* plasticity index of the paper, delta_ep = sigma/psi^2; 0 = elastic */
  double hardness_coeff; /* ZMC K, mean pressure K*H at yield onset; in (0, 1) */
  double plastic_ratio;  /* delta_p / delta_ep (ZMC: 54); > 1 */
} egw_params;

/* 10000*major + 100*minor + patch. */
int egw_get_version(void);

/* Generic message of a status code, NUL-terminated, truncated to fit buflen.
 * Returns EGW_OK, EGW_NULL_POINTER (buf NULL) or EGW_INVALID_ARGUMENT (buflen < 1). */
int egw_status_message(int status, char *buf, int buflen);

/* Detailed message of the last failing egw call on this thread (empty if none),
 * e.g. "sigma = -1.0E-003: must be finite and >= 0". Same returns as above. */
int egw_last_error(char *buf, int buflen);

/* Fill p with the defaults: E-GW, R = E = 1, sigma = 0, mu = 1, psi = 0, K = 0.6, 54. */
void egw_params_default(egw_params *p);

/* Validate every field of p. EGW_INVALID_PARAMETER names the field; EGW_NULL_POINTER. */
int egw_params_validate(const egw_params *p);

/* mu = (8/3) eta sigma sqrt(2 R beta) from summit density eta (per unit area), summit
 * radius beta, roughness sigma and equivalent radius R (all >= 0, finite). */
int egw_mu_from_summits(double summit_density, double summit_radius, double sigma,
                        double radius, double *mu);

/* F_n(h) = int_h^inf (s-h)^n phi(s) ds, phi the standard normal density (DESIGN.md
 * section 2). n >= 0, h any non-NaN value (F_n(+inf) = 0). Relative error <= 1e-14 for
 * n in {0, 1/2, 1, 3/2, 5/2}, <= 1e-12 otherwise. EGW_INVALID_ARGUMENT for NaN or n < 0. */
int egw_gauss_integral(double n, double h, double *value);

/* dF_n/dh = -n F_{n-1}(h) (-phi(h) for n = 0). Same domain and statuses. */
int egw_gauss_integral_deriv(double n, double h, double *value);

/* Complete elliptic integrals K(k), E(k) of MODULUS k (not the parameter m = k^2),
 * 0 <= k < 1; a few ulp. EGW_INVALID_ARGUMENT for k < 0, k >= 1 or NaN. */
int egw_ellipk(double k, double *value);
int egw_ellipe(double k, double *value);

/* Nominal pressure p_G(d) of the rough flat at separation d of the summit base plane
 * from a rigid smooth surface (DESIGN.md section 3): elastic asperities, or ZMC
 * asperities when p->model == EGW_MODEL_EPGW and p->psi > 0. Needs p->sigma > 0.
 * Units of p->modulus. egw_flat_pressure_deriv also returns dp_G/dd (<= 0). */
int egw_flat_pressure(const egw_params *p, double separation, double *pressure);
int egw_flat_pressure_deriv(const egw_params *p, double separation, double *pressure,
                            double *dpressure);

/* Hertz contact of smooth spheres (sigma ignored): force (4/3) E sqrt(R) delta^1.5,
 * stiffness dP/ddelta = 2 E a, contact radius a = sqrt(R delta); all 0 for delta <= 0.
 * Outputs other than NULL are written. EGW_INVALID_ARGUMENT for NaN/inf delta. */
int egw_hertz(const egw_params *p, double delta, double *force, double *stiffness,
              double *contact_radius);

/* ------------------------------------------------------------------------
 * Rough-sphere solver (DESIGN.md sections 4-5): the axisymmetric half-space
 * with the elliptic-integral kernel, coupled to the rough-flat law.
 * ------------------------------------------------------------------------ */

enum {
  EGW_METHOD_AUTO = 0,   /* Newton with line search, continuation when a cold start fails */
  EGW_METHOD_NEWTON = 1, /* Newton with line search (Jacobian factored by LAPACK) */
  EGW_METHOD_PICARD = 2  /* damped fixed point; fails where the problem is stiff */
};

typedef struct {
  int    n_radial;   /* mesh nodes; 0 = chosen from rel_tol */
  double rel_tol;    /* target relative accuracy of the force (default 1e-6) */
  int    max_iter;   /* 0 = default */
  int    method;     /* EGW_METHOD_AUTO=0, EGW_METHOD_NEWTON=1, EGW_METHOD_PICARD=2 */
  int    n_threads;  /* 0 = OpenMP default */
} egw_options;

typedef struct {
  double force, stiffness, contact_radius, max_pressure;
  double est_rel_err;  /* estimated relative error of force */
  double residual;     /* final nonlinear residual */
  int    iterations;
  int    method_used;
} egw_result;

/* Fill o with the defaults: n_radial 0, rel_tol 1e-6, max_iter 0, AUTO, n_threads 0. */
void egw_options_default(egw_options *o);

/* Solve the contact of p at overlap delta (> 0 overlap, < 0 separation).
 * force: total normal force P (>= 0); stiffness: dP/ddelta by implicit differentiation;
 * contact_radius: effective a* = (3 pi/4) int r p dr / int p dr (= a for Hertz);
 * max_pressure: max of the total pressure. Works for every model (Hertz exactly).
 * o may be NULL (defaults). Statuses: EGW_INVALID_PARAMETER, EGW_INVALID_ARGUMENT (delta
 * not finite, bad options), EGW_NULL_POINTER, EGW_NOT_CONVERGED (res still holds the
 * last iterate's diagnostics; its force must not be used). */
int egw_solve(const egw_params *p, const egw_options *o, double delta, egw_result *res);

/* Total pressure p(r) and surface deflection w(r) of the solved contact at the n radii
 * r[0..n-1] (>= 0, any order) into pressure[] and deflection[]. Same statuses. */
int egw_profile(const egw_params *p, const egw_options *o, double delta, int n,
                const double *r, double *pressure, double *deflection);

#ifdef __cplusplus
}
#endif

#endif /* EGW_H */
