/*
 * egw.h - C API of egw, the extended Greenwood-Williamson contact library
 * (Zhao & Feng 2018, J. Appl. Mech. 85:101007, with the misprints listed in
 * doc/theory.md section 6 corrected).
 *
 * Conventions
 *   - Units: any consistent set (e.g. SI: m, Pa, N). Results carry the units
 *     implied by the inputs: force = modulus * length^2, pressure = modulus.
 *   - delta is the overlap of the undeformed sphere with the mean summit
 *     plane: > 0 overlap, < 0 separation. Forces and pressures are positive
 *     in compression.
 *   - Every int function returns EGW_OK (0) on success and a non-zero status
 *     otherwise (egw_last_error alone returns a length); it never aborts. On
 *     failure, outputs are left unchanged and egw_last_error() gives a message
 *     naming the offending argument.
 *   - All functions are thread-safe: they keep no shared state (the last-error
 *     message and the progress hook, egw_set_progress, are per thread), and any
 *     number of threads may write and read files at once (tested with 16 threads).
 *   - String arguments (paths) are read to their NUL, whatever their length.
 */
#ifndef EGW_H
#define EGW_H

#include <math.h>
#include <stddef.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Version of this header; egw_get_version() returns the library's. */
#define EGW_VERSION 306

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
  EGW_MODEL_EPGW = 3,  /* extended elasto-plastic GW (ZMC asperities) */
  EGW_MODEL_FLAT_LAW = 4 /* a rough-flat law (egw_flat_law): in tables built from one; a
                            solve needs the law (egw_solve_flat_law), not p alone */
};

/* Parameters of one contact (doc/theory.md section 1). */
typedef struct {
  int    model;          /* EGW_MODEL_HERTZ=0, GW=1, EGW=2, EPGW=3 (FLAT_LAW=4: tables) */
  double radius;         /* equivalent radius R, 1/R = 1/R1 + 1/R2; > 0 */
  double modulus;        /* effective modulus E*, 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2; > 0 */
  double sigma;          /* std of summit heights, sigma^2 = sigma1^2 + sigma2^2; 0 = smooth */
  double mu;             /* Greenwood-Tripp mu = (8/3) eta sigma sqrt(2 R beta); > 0 if sigma > 0 */
  double psi;            /* plasticity index of the paper, delta_ep = sigma/psi^2; 0 = elastic */
  double hardness_coeff; /* ZMC K, mean pressure K*H at yield onset; in (0, 1) */
  double plastic_ratio;  /* delta_p / delta_ep (ZMC: 54); > 1 */
  double flow_pressure;  /* bulk flow pressure p_y [pressure] (doc/theory.md section 12): the
                            contact pressure is capped at p_y (elastic-perfectly-plastic
                            half-space, Thornton 1997); 0 = no bulk yield, else in
                            (0, modulus). From the yield stress Y: p_y = 1.6 Y (the Hertz
                            first-yield peak; theory.md section 12 says why). Every
                            model: rough ones cap the total pressure in their own solve
                            (theory.md section 12, "Rough spheres with the cap").
                            Since 0.2.0. */
} egw_params;

/* 10000*major + 100*minor + patch. */
int egw_get_version(void);

/* Generic message of a status code, NUL-terminated, truncated to fit buflen.
 * Returns EGW_OK, EGW_NULL_POINTER (buf NULL) or EGW_INVALID_ARGUMENT (buflen < 1). */
int egw_status_message(int status, char *buf, int buflen);

/* Detailed message of the last failing egw call on this thread (empty if none),
 * e.g. "sigma = -1.000000000000000E-003: must be finite and >= 0", copied into buf
 * (buflen bytes).
 * Returns the bytes the whole message needs, strlen(message) + 1 (>= 1), in every case
 * that is not an error:
 *   - buflen >= that: the whole message and its NUL are written;
 *   - 0 < buflen < that (truncation): the first buflen - 1 characters and a NUL are
 *     written; a return value > buflen says so: allocate that many bytes and call again;
 *   - buflen == 0 (buf may be NULL): nothing is written (a size query), e.g.
 *       int n = egw_last_error(NULL, 0); char *msg = malloc(n); egw_last_error(msg, n);
 * Errors return a negative value and write nothing: -EGW_NULL_POINTER (buf NULL with
 * buflen > 0), -EGW_INVALID_ARGUMENT (buflen < 0). This call never changes the message.
 * (Unlike the other int functions it never returns EGW_OK: test > 0, or <= buflen.) */
int egw_last_error(char *buf, int buflen);

/* Progress of long calls (since 0.2.0): hook(done, stage, user) is called as this
 * thread's long calls proceed: egw_solve, egw_solve_unload, egw_restitution(...),
 * egw_time_step and the table, hysteresis and scene builds (a solve of rough + cap at
 * sigma/delta_y <= 2e-6 can take half a minute: its small-sigma route, doc/stability.md).
 * done lies in [0, 1] and never decreases within one call: 0 at its start, 1 at its
 * end; stage is a short NUL-terminated name of the step ("history", "small-sigma route:
 * wide histories", "unloading", "restitution: loading", "table build" ...), valid only
 * during the call. hook NULL switches reports off (the default: the library never prints).
 * The hook is per thread, like egw_last_error: set on a thread, it hears only the calls
 * made on that thread (no lock, no sharing); solves inside egw's own OpenMP regions
 * (builds, the *_array entries of more than one point) report through their build, or
 * not at all, not one by one; an array of one point reports as the scalar call. Calls
 * made inside an active OpenMP parallel region of the caller's report nothing either
 * (threads of other kinds, pthreads or Python threads, each hear their own calls). The
 * hook may call egw: those calls report nothing; a hook set from inside a hook hears the
 * rest of the call in progress. user is passed to the hook as it was given. */
typedef void (*egw_progress_fn)(double done, const char *stage, void *user);
void egw_set_progress(egw_progress_fn hook, void *user);

/* Fill p with the defaults: E-GW, R = E = 1, sigma = 0, mu = 1, psi = 0, K = 0.6, 54,
 * flow_pressure 0 (no bulk yield). */
void egw_params_default(egw_params *p);

/* Validate every field of p, including the ranges the numerics represent (normal doubles;
 * for sigma > 0 the scales sqrt(R sigma), E sqrt(sigma/R), E sqrt(R) sigma^1.5 within
 * 1e+-278, mu in [1e-20, 1e20]; psi 0 or in [1e-50, 1e50]; K >= 1e-20; rho_p <= 1e50;
 * for flow_pressure > 0 the cap's scales a_y = pi R p_y/(2 E*), delta_y = a_y^2/R and
 * P_y = (4/3) E* a_y^3/R within 1e+-278: doc/parameters.md section 5). EGW_INVALID_PARAMETER names the field and its valid
 * range; EGW_NULL_POINTER. */
int egw_params_validate(const egw_params *p);

/* mu = (8/3) eta sigma sqrt(2 R beta) from summit density eta (per unit area), summit
 * radius beta, roughness sigma and equivalent radius R (all >= 0, finite). */
int egw_mu_from_summits(double summit_density, double summit_radius, double sigma,
                        double radius, double *mu);

/* Plasticity index of the paper psi = sqrt(sigma/delta_ep) with the ZMC yield-onset
 * interference delta_ep = (3 pi K H/(4 E*))^2 beta (paper eqs. 36, 47):
 * psi = 4 E* / (3 pi K H) sqrt(sigma/beta), from the effective modulus E* and hardness H
 * [pressure] (both > 0), K in (0, 1), sigma >= 0 and summit radius beta > 0 [length].
 * EGW_INVALID_ARGUMENT names a bad argument (or an overflowing result). */
int egw_psi_from_hardness(double modulus, double hardness, double hardness_coeff,
                          double sigma, double summit_radius, double *psi);

/* F_n(h) = int_h^inf (s-h)^n phi(s) ds, phi the standard normal density (doc/theory.md
 * section 2). 0 <= n <= 150, h any non-NaN value (F_n(+inf) = 0). Relative error <= 1e-14
 * for n in {0, 1/2, 1, 3/2, 5/2}, <= 1e-12 otherwise. EGW_INVALID_ARGUMENT for NaN, n
 * outside [0, 150], or a value beyond the doubles (F_n(-inf) = +inf for n > 0). */
int egw_gauss_integral(double n, double h, double *value);

/* dF_n/dh = -n F_{n-1}(h) (-phi(h) for n = 0). Same domain and statuses. */
int egw_gauss_integral_deriv(double n, double h, double *value);

/* Complete elliptic integrals K(k), E(k) of MODULUS k (not the parameter m = k^2),
 * 0 <= k < 1; a few ulp. EGW_INVALID_ARGUMENT for k < 0, k >= 1 or NaN. */
int egw_ellipk(double k, double *value);
int egw_ellipe(double k, double *value);

/* Nominal pressure p_G(d) of the rough flat at separation d of the summit base plane
 * from a rigid smooth surface (doc/theory.md section 3): elastic asperities, or ZMC
 * asperities when p->model == EGW_MODEL_EPGW and p->psi > 0. Needs p->sigma > 0.
 * Units of p->modulus. egw_flat_pressure_deriv also returns dp_G/dd (<= 0). A separation
 * so deep that the pressure exceeds the doubles: EGW_INVALID_ARGUMENT. */
int egw_flat_pressure(const egw_params *p, double separation, double *pressure);
int egw_flat_pressure_deriv(const egw_params *p, double separation, double *pressure,
                            double *dpressure);

/* EP-GW rough flat on unloading and reloading (doc/theory.md, unloading): nominal
 * pressure p_G,u(d, d_min) of the rough flat at separation d after its closest approach
 * d_min [length], and dp_G,u/dd at fixed d_min (<= 0; dpressure may be NULL). d >= d_min:
 * each summit unloads elastically (Hertz, from its contact radius at maximum
 * interference) towards its residual interference; d < d_min: the loading law (the
 * approach is new: the caller's history becomes d). ZMC summits when p->model ==
 * EGW_MODEL_EPGW and p->psi > 0, else elastic summits (reversible: the loading law).
 * Needs p->sigma > 0. Statuses: EGW_INVALID_PARAMETER, EGW_INVALID_ARGUMENT (NaN
 * separation, non-finite separation_min), EGW_NULL_POINTER (p, pressure). */
int egw_flat_pressure_unload(const egw_params *p, double separation, double separation_min,
                             double *pressure, double *dpressure);

/* Hertz contact of smooth spheres (sigma ignored): force (4/3) E sqrt(R) delta^1.5,
 * stiffness dP/ddelta = 2 E a, contact radius a = sqrt(R delta); all 0 for delta <= 0.
 * Outputs other than NULL are written. EGW_INVALID_ARGUMENT for NaN/inf delta or a force
 * or stiffness beyond the doubles. */
int egw_hertz(const egw_params *p, double delta, double *force, double *stiffness,
              double *contact_radius);

/* ------------------------------------------------------------------------
 * Rough-sphere solver (doc/theory.md sections 4-5): the axisymmetric half-space
 * with the elliptic-integral kernel, coupled to the rough-flat law.
 * ------------------------------------------------------------------------ */

enum {
  EGW_METHOD_AUTO = 0,   /* Newton with line search, continuation when a cold start fails */
  EGW_METHOD_NEWTON = 1, /* Newton with line search (Jacobian factored by LAPACK) */
  EGW_METHOD_PICARD = 2  /* damped fixed point; fails where the problem is stiff */
};

typedef struct {
  int    n_radial;   /* mesh nodes; 0 = chosen from rel_tol, else 8 .. 4097 */
  double rel_tol;    /* target relative accuracy of the force (default 1e-6) */
  int    max_iter;   /* 0 = default */
  int    method;     /* EGW_METHOD_AUTO=0, EGW_METHOD_NEWTON=1, EGW_METHOD_PICARD=2 */
  int    n_threads;  /* 0 = OpenMP default; capped to the processor count */
} egw_options;

typedef struct {
  double force, stiffness, contact_radius, max_pressure;
  double est_rel_err;  /* estimated error of force relative to |force| (1 for force 0);
                          unloading after a capped loading is accepted against
                          rel_tol/2 of max(|force|, 1e-6 force(delta_max)), so below
                          that floor est_rel_err may exceed rel_tol (doc/theory.md 12) */
  double residual;     /* final nonlinear residual */
  int    iterations;
  int    method_used;
} egw_result;

/* Fill o with the defaults: n_radial 0, rel_tol 1e-6, max_iter 0, AUTO, n_threads 0. */
void egw_options_default(egw_options *o);

/* Solve the contact of p at overlap delta (> 0 overlap, < 0 separation).
 * force: total normal force P (>= 0); stiffness: dP/ddelta by implicit differentiation;
 * contact_radius: effective a* = (3 pi/4) int r p dr / int p dr (= a for Hertz; Hertz
 * or sigma = 0 with the flow-pressure cap beyond first yield: the contact's edge a, where
 * p falls to 0, which is not a*: a fully capped disc has a* = 3 pi a/8 = 1.18 a, and a
 * rough + cap contact reports a*, so its contact_radius tends to a* of the smooth cap,
 * not to this a, as sigma -> 0; egw_solve_unload alike, its edge b);
 * max_pressure: max of the total pressure. Works for every model (Hertz exactly).
 * o may be NULL (defaults). Statuses: EGW_INVALID_PARAMETER (also parameters outside the
 * ranges the numerics represent, doc/parameters.md "Valid ranges"), EGW_INVALID_ARGUMENT
 * (delta not finite, delta/sigma > 1e15 for rough spheres, a Hertz force beyond the
 * doubles, bad options), EGW_NULL_POINTER, EGW_NOT_CONVERGED (also a mesh above 4097
 * nodes), EGW_OUT_OF_MEMORY; res is left untouched on any failure. */
int egw_solve(const egw_params *p, const egw_options *o, double delta, egw_result *res);

/* The flow-pressure cap (p->flow_pressure = p_y > 0; smooth spheres: Hertz or sigma = 0;
 * doc/theory.md section 12). Up to first yield delta_y = (pi p_y/(2 E*))^2 R every solve
 * is Hertz's, bit for bit. Above it: egw_solve is the cap's loading solve (force, loading
 * stiffness, contact radius, max_pressure <= p_y; est_rel_err of its 32/64-ring levels,
 * whatever o says), egw_solve_unload its elastic unloading from the deformed shape (0 at
 * and below the residual overlap), egw_restitution(_energy, _overlap) its head-on impact
 * (w_dissipated = (1 - e^2) m* v^2/2; e = 1 up to v_y; the smooth sphere's e within
 * ~3.3e-6 of an independent solve whatever o->rel_tol asks, as its solves: 3.2e-6 at
 * 2 v_y with rel_tol 1e-8, doc/theory.md 12). Beyond 1e6 delta_y or 1e4 v_y:
 * EGW_INVALID_ARGUMENT. Rough models (sigma > 0) with p_y > 0: egw_solve, egw_solve_unload
 * and egw_restitution(...) are the rough solver's, the cap on the total pressure (first
 * yield where the rough contact's largest total pressure reaches p_y); delta or delta_max
 * beyond 1e12 delta_y: EGW_INVALID_ARGUMENT naming it (doc/stability.md). egw_time_step
 * beyond v_y takes the smooth sphere's elastic unloading stiffness at delta_m (rough
 * spheres: an upper bound); egw_hysteresis_build gives Hertz + cap tables and GW, E-GW,
 * EP-GW + cap tables (doc/formats.md 6); egw_profile the smooth sphere's loading
 * profile beyond delta_y (p <= p_y; see egw_profile), egw_profile_unload its unloading
 * profile; both give a rough sphere's with the cap (the total pressure <= p_y; after a
 * history the small-sigma route loaded, the smooth cap's shifted to the route's force).
 * Not yet: force and universal tables (EGW_INVALID_PARAMETER). */

/* Unloading (and reloading) after the largest overlap delta_max (EP-GW, doc/theory.md 8):
 * delta > delta_max is the loading solve (egw_solve); delta <= delta_max loads to
 * delta_max, keeps the separation field d_max(r) of that solve and solves the contact with
 * the rough-flat unloading law p_G(d(r), d_max(r)) (the loading law wherever
 * d(r) < d_max(r)); delta = delta_max gives the loading solve at delta_max exactly.
 * force = P_Hertz(delta) + P_G (E-GW/EP-GW; classic GW P_G only); stiffness dP/ddelta on
 * the unloading curve (fixed history); elastic summits (GW, E-GW, psi = 0) are reversible.
 * The loading solve at delta_max is done at 1e-4 of rel_tol (at least 1e-10: the
 * unloading force can be far below the loading force, and the field it was loaded with is
 * not in the unloading solve's error estimate; where that loading does not converge, it is
 * done again at 1e-3, then 1e-2 of rel_tol, then at rel_tol: rough + cap at sigma/delta_y
 * <= 1e-6 needs the looser ones, and from a history at rel_tol the unloading near the
 * residual overlap can miss rel_tol under a small estimate, doc/stability.md "Rough + cap
 * as sigma -> 0") and kept for the next call on the same
 * thread. Near the residual overlap (a small central contact disc) E-GW and EP-GW +
 * cap at sigma/delta_y >= 1e-5 grade the disc's elements on every level (before: E-GW +
 * cap, sigma = 2e-5 delta_y, 0.1442 delta_max after 2 delta_y, rel_tol 1e-6: 5.6e-4 off
 * under an est_rel_err of 1.1e-7); at sigma/delta_y <= 1e-6 a converged unloading solve
 * of E-GW + cap is checked against the small-sigma route (which replaces it or the call
 * fails where they disagree). GW + cap's unloading there has no kink edges and its levels
 * refine every element. Known limit: between sigma/delta_y = 1e-6 and 1e-5 such solves
 * can still be accepted off by more than their est_rel_err (within rel_tol where
 * measured): cross-check forces within ~0.01 delta_max of the residual overlap at two
 * rel_tol (doc/stability.md "Stop 48 (resid14)", "Stop 49 (resid15)"). The history is kept per
 * thread: calls with the same p, o and delta_max (a sweep of the unloading curve) load it
 * once, one unloading solve each after the first (results identical either way; each
 * thread keeps its own, no lock). Statuses: as egw_solve, and EGW_INVALID_ARGUMENT
 * naming delta_max when it is not finite (smooth spheres: or its Hertz force or stiffness
 * is not a double); res is left untouched on any failure. */
int egw_solve_unload(const egw_params *p, const egw_options *o, double delta, double delta_max,
                     egw_result *res);

/* Coefficient of restitution e of a head-on impact (doc/theory.md 8): effective mass
 * m* = mass (1/m* = 1/m1 + 1/m2, > 0), approach speed velocity (> 0) from far apart;
 * e = sqrt(W_unload/W_load) with W_load = int_{-inf}^{delta_m} P_load ddelta = m* v^2/2
 * (defining the deepest overlap delta_m) and W_unload the same integral of the unloading
 * curve from delta_m, to about o->rel_tol. 0 < e <= 1; e = 1 for elastic summits (GW, E-GW,
 * psi = 0; exactly for Hertz and sigma = 0). Units: any consistent set (SI: kg, m/s).
 * Statuses: EGW_INVALID_PARAMETER, EGW_INVALID_ARGUMENT (mass or velocity not finite and
 * > 0, bad options; rough spheres: m* v^2/2 outside [1e-150, 3.4e37] E sqrt(R) sigma^2.5,
 * where the deepest overlap leaves the solver's range, doc/parameters.md section 5),
 * EGW_NULL_POINTER (p or e), EGW_NOT_CONVERGED (a solve failed: "restitution: rel_tol =
 * <o->rel_tol> (the caller's) not reached: ..." with the estimate the solve reached);
 * e is left untouched on any failure. */
int egw_restitution(const egw_params *p, const egw_options *o, double mass, double velocity,
                    double *e);

/* egw_restitution with its energies: w_load = W_load (= m* v^2/2 to the tolerance) and
 * w_dissipated = W_load - W_unload, the energy lost in the asperity layer (energy units).
 * Any of e, w_load, w_dissipated may be NULL (not wanted). Statuses as egw_restitution
 * (EGW_NULL_POINTER only for p); outputs untouched on failure. */
int egw_restitution_energy(const egw_params *p, const egw_options *o, double mass,
                           double velocity, double *e, double *w_load, double *w_dissipated);

/* egw_restitution with the deepest overlap delta_m of the impact [length] (> 0 pressed
 * together, < 0 still apart: slow rough impacts turn in the separated tail). e or
 * max_overlap may be NULL (not wanted). Statuses as egw_restitution_energy. */
int egw_restitution_overlap(const egw_params *p, const egw_options *o, double mass,
                            double velocity, double *e, double *max_overlap);

/* The time step of a DEM loop (doc/theory.md 10): for a head-on impact of effective mass
 * m* = mass at approach speed velocity (the fastest of the run: slower impacts are softer),
 * *duration = the time its force spends above 1 % of its peak (loading and unloading)
 * [time; adaptive Clenshaw-Curtis panels to ~1e-9 of the duration: Hertz 1e-11 of the
 * exact one; a rough sphere's unloading after the cap acted to a tenth of its solves'
 * own error estimate (EP-GW + cap: 2.3e-8 of a brute-force quadrature); as accurate as
 * the solves' forces, doc/theory.md 10], and
 * *time_step = the largest velocity-Verlet step whose error in the coefficient
 * of restitution stays below tolerance (in (0, 0.1]): dt = sqrt(tolerance/0.06)/omega,
 * omega^2 = K_max/m* with K_max the stiffest point of the impact (the unloading stiffness
 * at delta_m; with the flow-pressure cap beyond v_y the elastic unloading from the
 * flattened shape, ~2 E* a), at most 0.5/omega. A table-driven loop adds the table's own error. Either
 * output may be NULL. Statuses as egw_restitution, EGW_INVALID_ARGUMENT naming tolerance;
 * outputs untouched on failure. */
int egw_time_step(const egw_params *p, const egw_options *o, double mass, double velocity,
                  double tolerance, double *duration, double *time_step);

/* First yield under the flow-pressure cap (doc/theory.md section 12; doc/restitution.md):
 * *delta_y = (pi p_y/(2 E*))^2 R [length], the overlap at which the smooth sphere's peak
 * pressure 2 E* a/(pi R) reaches p_y = p->flow_pressure, and *velocity_y [length/time] the
 * approach speed of a head-on impact of effective mass m* = mass whose deepest overlap it
 * is, from (1/2) m* v_y^2 = (8/15) E* sqrt(R) delta_y^(5/2). Below v_y an impact is
 * elastic (e = 1 for Hertz), above it the cap dissipates: the model a scene needs (egw-table
 * scenes say "beyond first yield: Hertz + cap"). Closed forms of the smooth sphere with
 * p's R and E*, whatever p->model: a rough sphere's first yield, where its largest total
 * pressure reaches p_y, lies elsewhere (egw_solve's max_pressure tells where). flow_pressure 0 (no bulk yield): both DBL_MAX (never). Either
 * output may be NULL. Statuses: EGW_INVALID_PARAMETER, EGW_INVALID_ARGUMENT (mass not
 * finite and > 0, or a speed that is not a double for these units), EGW_NULL_POINTER (p);
 * outputs untouched on failure. Since 0.2.0. */
int egw_first_yield(const egw_params *p, double mass, double *delta_y, double *velocity_y);

/* Total pressure p(r) and surface deflection w(r) of the solved contact at the n radii
 * r[0..n-1] (>= 0, any order) into pressure[] and deflection[], each pointwise within
 * o->rel_tol of the profile's peak (pressure) and of its largest deflection: the contact
 * is solved again at rel_tol/10 (at most 4 times, down to 1e-12) until the profile
 * changes by less than that, so a profile costs a few solves. Same statuses, and
 * EGW_NOT_CONVERGED if the profile does not settle. With the cap (p->flow_pressure > 0,
 * smooth sphere) beyond first yield: p = p_y on the capped disc r <= c, the elastic
 * annulus's pressure (c, a) from the cap solver's rings (up to 256, whatever o->rel_tol:
 * pointwise within 1.5e-5 p_y of tools/reference/cap_reference.py at 2, 5, 20 delta_y),
 * 0 beyond a; deflection is then the surfaces' total normal displacement, elastic plus
 * the plastic crater (positive toward each other), so that the gap r^2/(2R) - delta + w
 * is 0 on [0, a]: w = delta - r^2/(2R) there, the elastic deflection beyond a (as for
 * Hertz). A rough sphere with the cap: the rough solver's total pressure (<= p_y, the
 * cap's law and plastic shift; within rel_tol as without the cap) and w the elastic
 * deflection (rough layer + Hertz's; the plastic shift is in the law, not in w). */
int egw_profile(const egw_params *p, const egw_options *o, double delta, int n,
                const double *r, double *pressure, double *deflection);

/* Total pressure p(r) and deflection w(r) at the n radii r[0..n-1] of the unloading (or
 * reloading) contact at delta after the largest overlap delta_max: egw_solve_unload's
 * contact (its force is 2 pi int p r dr). delta >= delta_max: egw_profile at delta.
 * Reversible models (Hertz up to first yield, classic GW, E-GW, EP-GW with psi = 0): the
 * loading profile at delta. EP-GW: Hertz's pressure plus the rough unloading pressure
 * p_G(d(r), d_max(r)), w the rough layer's deflection plus Hertz's, pointwise within
 * o->rel_tol of the peak and the largest deflection (the unloading solve tightened by 10
 * until it settles; the history loaded at 1e-4 of rel_tol, where that does not converge
 * at 1e-3, 1e-2, 1 of it, as egw_solve_unload's). Smooth sphere with the cap
 * loaded beyond first yield: the elastic contact of the deformed shape (the cap solver
 * on 256 unloading rings, egw_solve_unload on 64); w is the surfaces' total displacement,
 * positive toward each other: elastic plus the permanent plastic crater u_pl(r), so that
 * the gap r^2/(2R) - delta + w >= 0 is 0 on the contact (w = delta - r^2/(2R) there), and
 * at or below the residual overlap p = 0, w = u_pl. Rough spheres with the cap: the
 * rough solver's total unloading pressure (<= p_y) within rel_tol, w elastic (as
 * egw_profile); after a history loaded by the small-sigma route (sigma/delta_y <= ~1e-6,
 * no rough field kept): the smooth cap's unloading profile at delta + D, D the shift with
 * which its force is the route's (egw_solve_unload's, EGW_NOT_CONVERGED where that
 * refuses; D = O((sigma/delta_y)^(2/3) delta_y)), w elastic (without u_pl) as above, and
 * p = w = 0 at or below the residual overlap. Statuses as egw_profile (EGW_INVALID_ARGUMENT for a delta_max that is
 * not finite, n < 0 or a bad radius, EGW_NULL_POINTER for p, r, pressure, deflection);
 * outputs untouched on failure. */
int egw_profile_unload(const egw_params *p, const egw_options *o, double delta,
                       double delta_max, int n, const double *r, double *pressure,
                       double *deflection);

/* ------------------------------------------------------------------------
 * Force tables for DEM and FE codes.
 * A table is built from full solves with nodes placed adaptively until the cubic
 * Hermite interpolant (slope = the solver's stiffness; ln P in the separated tail)
 * agrees with solves between nodes to rel_tol. Rough models: the nodes reach down to the
 * cut-off delta_c where the force has fallen to 1e-12 * P_ref (every larger force is
 * interpolated to rel_tol), and below it force and stiffness are exactly 0 (the model's
 * separated tail there is below 1e-12 * P_ref; doc/formats.md rule 1, doc/theory.md 9;
 * the energy counts from the cut-off, 0 below it). Hertz: the cut-off
 * is where P = rel_tol * P_ref, and below it Hertz itself. Above delta_max every table
 * follows the deep-overlap asymptote: Hertz's force (4/3) E sqrt(R) g^(3/2) on the overlap g
 * the rough layer leaves, delta = delta_max + (g - g_n) + a (g^(1/3) - g_n^(1/3)), a fitted
 * to the last node (C1, increasing; doc/theory.md 9, doc/formats.md). Within 1 % of solves
 * up to 0.2 R for every model from a last node >= 10 sigma (classic GW, mu >= 0.1) or
 * >= 2 sigma (E-GW, EP-GW; measured 0.2 % (GW) and 0.05 % from 20 sigma), so the nodes of a
 * rough table reach at least that far (or 0.2 R) whatever delta_max is asked: info.delta_max
 * may exceed it (a hysteresis table's loading curve likewise; its unloading grid ends at
 * the delta_max asked). P_ref = P(min(0, delta_max)) for rough models (the delta_max asked),
 * P(delta_max) for Hertz. Evaluation allocates nothing and is thread-safe. File formats:
 * doc/formats.md. The builds go through an on-disk cache (EGW_CACHE_DIR, else
 * $XDG_CACHE_HOME/egw or $HOME/.cache/egw; EGW_CACHE_DIR=off turns it off): a build done
 * before with the same arguments is read back (checksummed, verified, rebuilt if corrupt);
 * one entry per SIMD path (AVX2 + FMA or the baseline, EGW_SIMD=sse2), whose tables differ
 * in their last digits, so a shared cache hands each path its own bits.
 * ------------------------------------------------------------------------ */

typedef struct egw_table_s *egw_table;         /* opaque: one parameter set */
typedef struct egw_universal_s *egw_universal; /* opaque: every R, E, sigma, mu */

enum { EGW_FORMAT_CSV = 0, EGW_FORMAT_BINARY = 1, EGW_FORMAT_LAMMPS = 2, EGW_FORMAT_CALCULIX = 3 };

/* Facts about a table. */
typedef struct {
  int    model;               /* EGW_MODEL_* of the parameters */
  int    n_nodes;             /* interpolation nodes */
  double cutoff;              /* delta_c: first node; rough tables 0 below [length] */
  double delta_max;           /* last node [length]; above it the table extrapolates */
  double reference_force;     /* P_ref of the cut-off rule [force] */
  double rel_tol;             /* requested interpolation tolerance */
  double max_force_error;     /* measured max |P_table/P_solve - 1| at check solves */
  double max_stiffness_error; /* same for the stiffness (reported, not enforced) */
  int    checksum_missing;    /* warning: 1 if read from a CSV file without its checksum
                               * line (written before CSV format 3, or edited by hand):
                               * only the reader's sanity checks vouch for the numbers;
                               * 0 for built tables and checksummed files */
} egw_table_info;

/* Build the table of p over at least [delta_min, delta_max] with interpolation error
 * <= rel_tol (1e-10 <= rel_tol <= 0.1). Points are solved in parallel (OpenMP; o's
 * n_threads is set to 1 inside, its rel_tol tightened to min(o->rel_tol, rel_tol/10));
 * o may be NULL (defaults). The table starts at the cut-off delta_c, below delta_min if
 * the force there still exceeds 1e-12 * P_ref (rel_tol * P_ref for Hertz). *out receives
 * a handle only on success.
 * Statuses: EGW_INVALID_PARAMETER, EGW_INVALID_ARGUMENT (range, rel_tol, smooth spheres
 * with delta_max <= 0), EGW_NOT_CONVERGED (a solve failed, or the node limit of 20000
 * was reached; the message quotes the caller's rel_tol, the solves' and what was
 * reached), EGW_NULL_POINTER. */
int egw_table_build(const egw_params *p, const egw_options *o, double delta_min,
                    double delta_max, double rel_tol, egw_table *out);

/* Force [force] and stiffness dP/ddelta [force/length] at overlap delta. Below the
 * cut-off 0 (rough tables; Hertz: Hertz itself), above delta_max the deep-overlap
 * asymptote (see above), and
 * EGW_OUT_OF_RANGE is returned above delta_max WITH the outputs written (the one
 * exception to "outputs unchanged on failure"). NULL outputs are skipped.
 * EGW_INVALID_ARGUMENT for NaN delta, and (nothing written) for delta = +inf or a
 * continuation beyond the doubles; EGW_NULL_POINTER for t. Below a rough table's cut-off
 * (Hertz: delta < 0) the first test of the call: EGW_OK, force = stiffness = 0. */
int egw_table_eval(egw_table t, double delta, double *force, double *stiffness);

/* egw_table_eval at the n overlaps delta[0..n-1] in one call: force[i], stiffness[i]
 * (either may be NULL). A NaN overlap refuses the call (EGW_INVALID_ARGUMENT naming its
 * index) before anything is written, as does one whose continuation is not a double (+inf);
 * delta NULL with n > 0: EGW_NULL_POINTER; overlaps above delta_max are extrapolated as by
 * egw_table_eval and EGW_OUT_OF_RANGE names the first of them (all values written).
 * n = 0 does nothing; n < 0: EGW_INVALID_ARGUMENT. For callers that pay per call
 * (Python, scripting languages): the cost per point is that of egw_table_eval. */
int egw_table_eval_array(egw_table t, int n, const double *delta, double *force,
                         double *stiffness);

/* As egw_table_eval, plus the elastic energy int_{delta_c}^{delta} P ddelta of the
 * interpolant [force*length] and the effective contact radius a* [length] (monotone
 * cubic through the solver's values; not error-controlled). */
int egw_table_eval_all(egw_table t, double delta, double *force, double *stiffness,
                       double *energy, double *contact_radius);

/* Facts about t into *info. EGW_NULL_POINTER. */
int egw_table_get_info(egw_table t, egw_table_info *info);

/* The table's interpolant between its cut-off and delta_max, for a caller that evaluates
 * it in its own inner loop (e.g. blends two tables' cubics, or keeps a contact's
 * interval): nodes[0..n-1] (n = egw_table_info.n_nodes, ascending, nodes[0] = cutoff,
 * nodes[n-1] = delta_max) [length] and, for interval i (nodes[i] <= delta < nodes[i+1]),
 * the cubic v = c0 + c1 t + c2 t^2 + c3 t^3 in t = delta - nodes[i] with (c0..c3) =
 * coeffs[4i..4i+3] (coeffs holds 4(n-1) doubles). For i < *n_log (the separated tail,
 * where the table interpolates ln P) force = exp(v) and stiffness = force dv/dt; for
 * the others force = v, stiffness = dv/dt. Evaluated so (as egw_table_eval evaluates
 * it: same coefficients, same order of operations up to rounding) it gives
 * egw_table_eval's values on (cutoff, delta_max), except in the separated tail's ln P
 * intervals below 0: there egw_table_eval evaluates a resampling of this interpolant
 * without exp (equal pieces of a cubic in P, within 5e-2 rel_tol of it in the force
 * and rel_tol in the stiffness; doc/formats.md rule 3; egw_table_get_tail gives those
 * pieces); outside that interval use
 * egw_table_eval (0 or Hertz below, node value, deep-overlap asymptote). Statuses:
 * EGW_INVALID_ARGUMENT (capacity < n, nothing written; the message gives n),
 * EGW_NULL_POINTER. */
int egw_table_get_interpolant(egw_table t, int capacity, double *nodes, double *coeffs,
                              int *n_log);

/* The separated tail's resampled pieces, for a caller that evaluates tables in its own inner
 * loop (beside egw_table_get_interpolant's cubics) and wants egw_table_eval's values there
 * without exp. In a rough table's separated tail [cutoff, tail_end] (its ln P intervals up
 * to the last node <= 0) egw_table_eval evaluates N equal pieces, on each a cubic Hermite in
 * P through the ln P interpolant's values and slopes at the piece's ends, checked at 8
 * points of every piece to 2.5e-2 rel_tol of it in the force and 0.5 rel_tol in the
 * stiffness, and within 5e-2 rel_tol and rel_tol between them (doc/formats.md rule 3).
 * tables[0..n-1]: one table, or several on the same nodes (the slices of one universal
 * table at the same sigma, by egw_universal_slice or by egw_universal_slice_range with
 * the same delta_max: their nodes are x sigma), which get one grid: the fewest pieces (16, then 20 % more
 * at a time) on which every table's pieces meet its own rel_tol as above (where that count
 * is a table's own, its pieces are egw_table_eval's). On success *n_pieces = N, and with
 * capacity >= N: starts[0..N] (N + 1 doubles: starts[0] = cutoff, starts[N] = tail_end)
 * [length] and, for piece q of table k, the cubic in t = delta - starts[q] with
 * t2 = t t: force = (c0 + t c1) + t2 (c2 + t c3), stiffness = (c1 + 2 t c2) + 3 t2 c3, with
 * (c0..c3) = coeffs[4 (q n + k) .. 4 (q n + k) + 3] (4 n N doubles). The piece of delta:
 * q = min(N - 1, (int) ((delta - starts[0]) * (N / (starts[N] - starts[0])))); so
 * evaluated (same coefficients and order of operations: 3 t2 is (3 t2), not (3 t) t;
 * compiled without contraction into fused multiply-adds, e.g. gcc -ffp-contract=off)
 * one table's pieces give egw_table_eval's force and stiffness on
 * starts[0] < delta < starts[N] bit for bit.
 * capacity = 0 is a size query: only *n_pieces is written (starts, coeffs may be NULL).
 * Statuses (nothing written): EGW_NULL_POINTER (tables, a handle, n_pieces, and starts or
 * coeffs when capacity > 0); EGW_INVALID_ARGUMENT: n < 1 or n > 65535, capacity < 0 or
 * 0 < capacity < N (the message gives N), a table without resampled pieces (Hertz, a
 * flat-law table, no ln P interval below 0, or a tail that would take more than 8192
 * pieces: egw_table_eval takes exp there; the message says which), tables whose nodes or
 * ln P intervals differ from tables[0]'s, or a common grid beyond 8192 pieces. */
int egw_table_get_tail(int n, const egw_table *tables, int capacity, double *starts,
                       double *coeffs, int *n_pieces);

/* Record the particle radii R1, R2 of the pair (LAMMPS distances r = R1 + R2 - delta).
 * They must give the table's R: 1/R = 1/R1 + 1/R2 (to 1e-12); otherwise
 * EGW_INVALID_ARGUMENT and nothing changes. Without radii the LAMMPS file is written for
 * two equal spheres R1 = R2 = 2R, and says so. */
int egw_table_set_radii(egw_table t, double radius1, double radius2);

/* Write t to path (NUL-terminated, any length) atomically: a temporary file beside path
 * is written, flushed, synced and closed, each step checked, then renamed over path; a
 * failed write (full disk, quota, I/O error, a directory in the way, a file-size limit
 * (ulimit -f: refused before writing)) returns EGW_IO_ERROR naming path and the system's
 * reason, removes the temporary file and leaves an existing file intact (doc/formats.md).
 * format: EGW_FORMAT_CSV, EGW_FORMAT_BINARY,
 * EGW_FORMAT_LAMMPS (one pair_style table section, keyword EGW_1), EGW_FORMAT_CALCULIX
 * (*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR: force per node against overlap, for
 * node-to-surface contact; at most EGW_CALCULIX_MAX_PAIRS pairs, see
 * egw_table_write_calculix). No UNITS: tag in LAMMPS files (egw_tables_write_lammps_units). Statuses: EGW_IO_ERROR, EGW_INVALID_ARGUMENT (unknown
 * format, non-finite data), EGW_NULL_POINTER. */
int egw_table_write(egw_table t, const char *path, int format);

/* LAMMPS file with one pair_style table section per table (keywords EGW_1 .. EGW_n, in
 * the order given), e.g. one per particle-type pair. Atomic like egw_table_write.
 * EGW_INVALID_ARGUMENT for n < 1, EGW_NULL_POINTER for a NULL array, handle or path. */
int egw_tables_write_lammps(int n, const egw_table *tables, const char *path);

/* Read an egw CSV or binary table (format recognised from the file's start). A
 * truncated, corrupted (checksum), wrong-version or inconsistent file, or one whose
 * numbers do not make a table, even under a valid checksum (not finite; negative force,
 * stiffness, energy or contact radius; a force that decreases with the overlap; a
 * stiffness or an energy inconsistent with the forces between nodes (a force jump the
 * stiffnesses do not give; an energy that is not the integral of the force); an interpolated
 * force that dips below 0 between nodes; a node value above 1e200 in magnitude; metadata
 * out of range: doc/formats.md section 1, "Checks on read")
 * gives EGW_BAD_FILE with a message saying what is wrong, and no table. A CSV file
 * without its checksum line (hand-edited) is read, with info.checksum_missing = 1.
 * EGW_IO_ERROR if it cannot be opened. *out receives a handle only on success. */
int egw_table_read(const char *path, egw_table *out);

/* Release a table; sets *t to NULL. NULL or *t == NULL is fine. */
void egw_table_free(egw_table *t);

/* CalculiX pressure-overclosure curve of the rough flat of p (p_G of doc/theory.md section 3,
 * overclosure = -separation) from zero pressure where p_G < rel_tol * p_G(0) up to
 * overclosure_max > 0 [length], linear-interpolation error <= rel_tol of the local
 * pressure if 200 pairs allow it (else the best 200: see egw_write_flat_calculix_shifted).
 * Needs p->sigma > 0 and p->flow_pressure = 0 (a reversible curve cannot hold the cap's
 * plastic flow; the FE model's material carries a bulk's yield: EGW_INVALID_PARAMETER naming
 * flow_pressure, since stop 63). Statuses as egw_table_write, EGW_INVALID_PARAMETER. */
int egw_write_flat_calculix(const egw_params *p, double overclosure_max, double rel_tol,
                            const char *path);

/* CalculiX limits, honoured by every CalculiX writer: fields of at most 20 characters
 * (numbers are written with 13 significant digits) and at most EGW_CALCULIX_MAX_PAIRS
 * pairs per tabular curve. When rel_tol needs more pairs, the pairs are placed to
 * minimise the largest linear-interpolation error; the error achieved (relative to
 * max(|value|, rel_tol * reference value)) is written in the file's header, with a
 * WARNING line if it exceeds rel_tol, and returned in *max_error (max_error may be NULL).
 * shift != 0: overclosure is measured from the curve's zero-force end (the cut-off
 * delta_c of the table, or the separation d_c of the flat), so the curve starts at
 * (0, 0): CalculiX makes node-to-surface contact springs only where surfaces touch or
 * penetrate and never reaches a negative-overclosure part. The model's surfaces then
 * stand for the sphere surfaces at overlap delta_c / the summit base planes at separation
 * d_c (doc/formats.md section 5). */
#define EGW_CALCULIX_MAX_PAIRS 200
int egw_table_write_calculix(egw_table t, const char *path, int shift, double *max_error);
int egw_write_flat_calculix_shifted(const egw_params *p, double overclosure_max,
                                    double rel_tol, int shift, const char *path,
                                    double *max_error);

/* As egw_tables_write_lammps, with the file's first line "# DATE: ... UNITS: <units>"
 * (a LAMMPS units style such as "si" or "metal"; LAMMPS then refuses the file under other
 * units). Use it only when the tables' parameters are in that style's units. Without it
 * (egw_tables_write_lammps, egw_table_write) the file has no UNITS: tag. */
int egw_tables_write_lammps_units(int n, const egw_table *tables, const char *path,
                                  const char *units);

/* ------------------------------------------------------------------------
 * Universal tables: p = P/(E sqrt(R) sigma^1.5) over x = delta/sigma and mu, for one
 * model (and psi, K, rho_p for EP-GW). One table serves every radius, modulus and
 * roughness of a polydisperse scene; mu is interpolated in ln mu (4-point Lagrange on
 * ln p in the separated tail, on p in the contact range, as the slices interpolate in
 * x) on a grid refined until solves at mid-grid mu agree to rel_tol (the slices are
 * built to rel_tol/2 on shared x nodes). Evaluation costs about 9 Hertz forces (a log
 * of mu, one lookup, one cubic, an exp in the tail): for one parameter set a 1-D table
 * is cheaper (~1.75 Hertz forces), and egw_universal_slice cuts one out of the
 * universal table without solves.
 * ------------------------------------------------------------------------ */

/* Build for p->model, p->psi, p->hardness_coeff, p->plastic_ratio (R, E, sigma, mu of p
 * are ignored) over mu in [mu_min, mu_max] (0 < mu_min < mu_max) and x up to x_max, from
 * the common cut-off (the lowest of the grid's cut-offs; below x_min if needed).
 * Statuses as egw_table_build. */
int egw_universal_build(const egw_params *p, const egw_options *o, double mu_min,
                        double mu_max, double x_min, double x_max, double rel_tol,
                        egw_universal *out);

/* Force and stiffness of the contact p (R, E, sigma > 0, mu; model, psi, K, rho_p must
 * equal the table's, else EGW_INVALID_ARGUMENT) at overlap delta: P = E sqrt(R)
 * sigma^1.5 p(delta/sigma, mu); at the cut-off the combined first node, below it 0
 * (rough models; Hertz: Hertz itself). mu outside the table: EGW_OUT_OF_RANGE, outputs unchanged. delta above
 * x_max*sigma: EGW_OUT_OF_RANGE with extrapolated outputs written (the deep-overlap
 * asymptote of the combined last node, as a 1-D table). EGW_INVALID_PARAMETER for
 * sigma, R or E <= 0. */
int egw_universal_eval(egw_universal u, const egw_params *p, double delta, double *force,
                       double *stiffness);

/* The 1-D table of the contact p (R, E, sigma > 0, mu; model, psi, K, rho_p equal to
 * u's) cut out of u: egw_table_eval on it gives egw_universal_eval's force [force] and
 * stiffness [force/length] at every delta [length] to rounding (relative ~1e-14: the
 * 4 slices' nodal data, ln p, d ln p/dx in the tail and p, dp/dx in the contact range,
 * are combined once, as the evaluation combines their cubics), including the 0 below
 * the cut-off and the asymptote above x_max*sigma, at the cost of a 1-D table
 * (no log, no mu interpolation, no exp in the contact range). info:
 * rel_tol and max_force_error are u's; a* = sqrt(R sigma) a*(x) with the same weights.
 * *out receives a handle only on success; free it with egw_table_free. Statuses:
 * EGW_OUT_OF_RANGE (mu outside [mu_min, mu_max]), EGW_INVALID_PARAMETER (p invalid,
 * sigma = 0), EGW_INVALID_ARGUMENT (model, psi, K, rho_p differ from u's),
 * EGW_NULL_POINTER. */
int egw_universal_slice(egw_universal u, const egw_params *p, egw_table *out);

/* As egw_universal_slice, trimmed to overlaps up to delta_max [length]: the slice keeps
 * the nodes up to the first at or above delta_max (values below unchanged), so its lookup
 * serves the overlaps a scene visits; above it the table extrapolates (EGW_OUT_OF_RANGE,
 * values written). This is the DEM path for a polydisperse scene: one call per particle
 * pair, then egw_table_eval at ~1.8 Hertz forces. EGW_INVALID_ARGUMENT for a delta_max
 * not finite or below the cut-off; otherwise the statuses of egw_universal_slice. */
int egw_universal_slice_range(egw_universal u, const egw_params *p, double delta_max,
                              egw_table *out);

/* Write (EGW_FORMAT_CSV or EGW_FORMAT_BINARY; LAMMPS and CalculiX need one parameter set:
 * EGW_UNSUPPORTED) and read, with the guarantees of egw_table_write / egw_table_read. */
int egw_universal_write(egw_universal u, const char *path, int format);
int egw_universal_read(const char *path, egw_universal *out);

/* Release a universal table; sets *u to NULL. NULL or *u == NULL is fine. */
void egw_universal_free(egw_universal *u);

/* ------------------------------------------------------------------------
 * EP-GW hysteresis tables for DEM (doc/theory.md section 8): loading, unloading and
 * reloading of one parameter set over (delta, delta_max), with a per-contact history
 * delta_max_state owned by the caller (a double per contact; a new contact starts at
 * -HUGE_VAL). Loading (delta >= state) follows the loading table and moves the state up;
 * below the state, the unloading curve of that state (reloading retraces it). Built
 * adaptively: solves at the midpoints of both grids agree to rel_tol of the local force
 * down to 1e-3 of the force at the turning point, and of 1e-3 of that below (EP-GW, and
 * rough models whose cap does not act, store ln(P_load/P); Hertz + cap stores the
 * unloading force over the turning point's, P/P_load(delta_max), with its residual overlap
 * on a finer delta_max grid: the same tolerance); rough models where the flow-pressure
 * cap acts store P/P_load(delta_max) on a two-piece map, their checks weighted to the local
 * force: the same tolerance (since egw 0.3.6; egw 0.3.5 built them to rel_tol of the
 * force at the turning point in ~1/5 of the time, and files it wrote read as such;
 * doc/formats.md section 6). Evaluation allocates nothing and takes no lock; a table is read-only
 * after the build, so any number of threads may evaluate it (each with its own states).
 * EP-GW alone does not let a packing come to rest: it dissipates only while a contact
 * loads beyond its past maximum overlap, and below it unloading and reloading retrace one
 * elastic curve (no loss), so contacts vibrating about equilibrium keep their energy. A
 * DEM needs damping beside it, as with any elastic law: a viscous term, e.g.
 * F = P - c d(delta)/dt with c = 2 zeta sqrt(m* K), K the stiffness these calls return
 * (example/dem_c/dem_c.c); in LAMMPS the damping sub-model of pair_style egw.
 * ------------------------------------------------------------------------ */
typedef struct egw_hysteresis_s *egw_hysteresis; /* opaque: one parameter set */

/* Build for p (EP-GW, or Hertz/sigma = 0 with p->flow_pressure > 0, for hysteresis: the
 * cap's turning points from the first capped one on, delta_y (1 + 1e-4), below which the
 * cap solver's contact is Hertz's (reversible), doc/theory.md 12; GW, E-GW, EP-GW
 * with p->flow_pressure > 0: EP-GW's curves from the rough solver with the cap, the
 * turning points of GW/E-GW from the rough first yield on, where the largest total
 * pressure reaches p_y (reversible when it never does up to delta_max); other models
 * give reversible curves; with p_y, delta_max above 1000 delta_y: EGW_INVALID_ARGUMENT;
 * Hertz + cap beyond its first capped turning point below rel_tol 3e-6, which its solves'
 * smoothness (~3e-7) does not let it reach, and a rough model + cap whose cap acts below
 * delta_max below rel_tol 1e-5 (below it builds failed after minutes: an unloading solve
 * at rel_tol/10 reaching ~2.4e-7, or the delta_max grid not settling; one loading solve
 * tells): EGW_INVALID_ARGUMENT naming rel_tol)
 * over overlaps [delta_min, delta_max] [length] to rel_tol in [1e-8, 0.1]; o may be NULL
 * (defaults). *out receives a handle only on success. The unloading curves are solved at rel_tol/10,
 * or at o->rel_tol where that is set below its default 1e-6 and below rel_tol/10 (the
 * loading table at min(o->rel_tol, rel_tol/10)); before a build (not on a cache hit), a
 * probe of 18 such solves (loading and unloading from delta_max and delta_max/2;
 * milliseconds at the usual tolerances) fails at once where they cannot reach it, rather
 * than after minutes of building; below rel_tol 1e-4 a pilot table at 1e-3 (a few
 * percent of a 1e-5 build) estimates the build's delta_max grid (growing 2x per
 * decade of rel_tol, as measured builds do) and refuses a rel_tol whose grid would pass
 * the build's limit of 400 nodes, naming the smallest rel_tol within it (the glass pair
 * of issue 22: 1e-6 refused in seconds, ~1.9e-6 within). A probe that passes promises
 * nothing: the build may still meet a failing solve or its limit. Every
 * EGW_NOT_CONVERGED message starts "hysteresis table: rel_tol = <the caller's> ..." and
 * says what the solves' tolerance was and what the failing solve reached (its error
 * estimate, and the rel_tol it could meet). Statuses: EGW_INVALID_PARAMETER, EGW_INVALID_ARGUMENT
 * (range, rel_tol), EGW_NOT_CONVERGED (a solve failed or a node limit was reached; a rough
 * model with the cap below sigma/delta_y 2e-3 adds sigma/delta_y and the routes: a smaller
 * delta_max, sigma 0 for Hertz + cap with its bound, single solves), EGW_UNSUPPORTED (a
 * rough model with the cap at sigma/delta_y <= 1e-4 with delta_max beyond 2e5 sigma,
 * plastic summits 1.5e5 sigma: such builds failed after their solves, so they are refused
 * before any, naming the same routes; doc/stability.md "Stop 51 (tiny17)"),
 * EGW_OUT_OF_MEMORY, EGW_NULL_POINTER. */
int egw_hysteresis_build(const egw_params *p, const egw_options *o, double delta_min,
                         double delta_max, double rel_tol, egw_hysteresis *out);

/* Force [force] and stiffness dP/ddelta [force/length] at overlap delta for the contact
 * whose history is *delta_max_state, updated to max(*delta_max_state, delta). force or
 * stiffness may be NULL. A state above the table's delta_max: EGW_OUT_OF_RANGE with the
 * values written (the last unloading curve, the loading table's deep-overlap asymptote;
 * on a ln(P_load/P) table the last curve's span stretched by the state's excess over
 * delta_max, its residual end kept: from 3 delta_max within 4e-5 of the turning point's
 * force of unloading solves, the deep loading law's own error there (EP-GW,
 * doc/benchmarks.md "Stop 48 (gain14)")). A Hertz + cap table whose delta_max reaches 35
 * delta_y (first yield delta_y; the contact is fully capped there) continues beyond it
 * exactly, EGW_OK: loading by P = pi a^2 p_y (delta/delta_y = alpha^2/2 + 8 alpha/pi^2,
 * alpha = a/a_y), unloading and reloading below a history m above delta_max by its last
 * curve scaled by r = alpha(m)/alpha(delta_max) (doc/theory.md 12 "Beyond a table"), to
 * the table's rel_tol at any depth (2, 5, 20 delta_max: test cap_hysteresis "beyond
 * delta_max: the fully capped continuation"); egw_hysteresis_eval_state and
 * egw_hysteresis_energy alike (a state unloading there keeps a piece of the last curve
 * moved to the contact, which egw_hysteresis_eval_cached serves as any piece; loading
 * steps there are calls). A rough + cap table to 35 delta_y or more with sigma/delta_y in
 * [0.01, 1] continues likewise (that law shifted and scaled to match the table's top, its
 * last curve scaled) up to a reach where its measured error bound meets the table's
 * rel_tol, at most 5 delta_max (E-GW, sigma/delta_y = 0.01 at 1e-3: 4.9 delta_max; 0.1:
 * 1.32; doc/theory.md 12 "Beyond a rough + cap table"), EGW_OK there. Other
 * tables with the flow-pressure cap (Hertz + cap below 35 delta_y, rough + cap otherwise
 * and past that reach) have no bound: above delta_max the loading force is Hertz's
 * asymptote, not the capped contact's,
 * and a state there unloads on the last curve, so the values drift fast (Hertz + cap to
 * 20 delta_y at rel_tol 1e-4: loading 7.8e-4, 1.6e-2, 0.15, 0.91 of the force too high at
 * 1.05, 1.25, 2, 5 delta_max, unloading up to 1.6e-2, 7.6e-2, 0.15 of the turning point's
 * force at 1.05, 1.25, 2 delta_max; E-GW + cap, sigma = delta_y/100, to 6 delta_y at 1e-3:
 * 2.3e-2, 0.11 at 1.08, 1.5 delta_max; doc/benchmarks.md "Stop 63"): build them to the
 * deepest overlap a run reaches (up to 1000 delta_y; Hertz + cap at least 35 delta_y).
 * Below the loading table's cut-off: 0 (a turning point at or below it unloads on the
 * loading curve, so 0 there too). With the flow-pressure cap a turning point at or below
 * first yield delta_y unloads on the loading curve (Hertz), one above it gives 0 below its
 * residual overlap.
 * EGW_INVALID_ARGUMENT for NaN delta or a NaN state (nothing changed);
 * EGW_NULL_POINTER for h or delta_max_state. */
int egw_hysteresis_eval(egw_hysteresis h, double delta, double *delta_max_state,
                        double *force, double *stiffness);

/* Doubles of a contact's state for egw_hysteresis_eval_state. */
#define EGW_HYSTERESIS_STATE_SIZE 24

/* egw_hysteresis_eval with a larger per-contact state that the caller owns and keeps with
 * the contact (EGW_HYSTERESIS_STATE_SIZE doubles, no allocation, no lock): state[0] is the
 * history (the largest overlap so far, as *delta_max_state above), state[1..23] caches that
 * this call fills: the turning point's data and the piece of its unloading curve last used
 * as one cubic in delta, so that a contact that stays below the same turning point and
 * inside the same piece (most DEM steps: a contact moves little) reads nothing but its
 * state (on a ln(P_load/P) table the piece spans the loading table's intervals: crossing
 * into the next one refills that interval alone). The values of egw_hysteresis_eval to
 * rounding (1e-12 of the loading force at the turning point), the same statuses and
 * history; but back at its history exactly on a piece of the separated tail, the unloading
 * curve's stiffness, its limit from below (1.1-1.4 times the loading curve's, which
 * egw_hysteresis_eval gives there, on test hysteresis's EP-GW table). Start a contact with
 * egw_hysteresis_state_init or with all zeros (as calloc'ed or zeroed contact arrays): both
 * mean a new contact. A state may be copied with its contact (restarts, migration between
 * ranks): it keeps its history with a table of the same data (a rebuild with the same
 * parameters, tolerance and options, or the same file). A state that no call filled for
 * this table (another table's, garbled) is a new contact: its history is reset, never read
 * as a turning point. The steps that egw_hysteresis_eval_cached below serves (a piece that
 * covers delta, zero pieces of separated contacts included, or loading further inside the
 * state's loading interval; not above the table's delta_max) this call answers at its top
 * from the state alone, with the same values and state: the inline's cost plus a call's.
 * EGW_INVALID_ARGUMENT for NaN delta or state[0] (nothing changed); EGW_NULL_POINTER for h
 * or state. */
int egw_hysteresis_eval_state(egw_hysteresis h, double delta,
                              double state[EGW_HYSTERESIS_STATE_SIZE], double *force,
                              double *stiffness);

/* The tag egw writes into the states h fills (a number of h's data, never 0; a table read
 * from h's file or rebuilt with the same data has the same tag), for
 * egw_hysteresis_eval_cached. EGW_NULL_POINTER for h or tag. */
int egw_hysteresis_state_tag(egw_hysteresis h, double *tag);

/* The steps of egw_hysteresis_eval_state that read nothing but the state, inline, for a
 * force loop in which a library call per contact costs as much as the evaluation: when
 * state was filled by the table with tag `tag` (egw_hysteresis_state_tag) and either
 * holds a piece of an unloading curve that covers delta, or delta loads the contact
 * further (delta >= state[0]) inside the loading table's interval the state holds -- most
 * DEM steps -- it writes the force and stiffness egw_hysteresis_eval_state would (the
 * same arithmetic on the state's cached cubics), changes the state as that call would
 * (loading further: state[0] = delta, the piece dropped; at state[0] exactly: nothing
 * changed) and returns 1; otherwise (also when
 * the values would not be finite) it returns 0 and changes nothing: call
 * egw_hysteresis_eval_state. It does not report
 * EGW_OUT_OF_RANGE (compare state[0] with egw_hysteresis_info.delta_max; a Hertz + cap
 * table to 35 delta_y or more continues beyond it, a rough + cap one to its reach
 * (egw_hysteresis_eval above), EGW_OK there) and refuses
 * nothing (what it does not serve, the call checks). It reads the state's layout, which
 * is egw's: use it with the library of the same version as this header (0.3.2's pieces
 * in the separated tail hold one cubic of ln P - h, state[23] = 3, which 0.3.1's inline
 * would misread: rebuild a program that uses it). C99 or C++.
 * A loop with the call inside keeps its sums in memory around it (no floating-point
 * register survives a call): a sweep of this inline over the contacts, the ones it
 * declines collected and called after the sweep, took 0.83-0.94 of the time of the call
 * in the loop (tools/bench/separated_hysteresis.c, "batch"; doc/benchmarks.md
 * "Stop 55: sep21"). */
#if defined(__cplusplus) || (defined(__STDC_VERSION__) && __STDC_VERSION__ >= 199901L)
/* exp(x) of a log-ratio piece's force, for egw_hysteresis_eval_cached (not an API of its
 * own): the library's piece_exp (src/egw/tables/piece_exp.inc, which explains it), the same
 * floating-point operations on the same constants in the same order (its scale 2^e t_j
 * formed from other integers, the same bits), so the same bits as
 * egw_hysteresis_eval_state (compile without FMA contraction, e.g. -std=c99 or
 * -ffp-contract=off, as for the cubics). Within 0.55 ulp of exp, 1 ulp of glibc's;
 * |x| >= 708 and NaN: libm's exp. */
/* 64-bit integers of its bit arithmetic: unsigned long long, which C++98 lacks (g++
 * -std=c++98 -pedantic warned); GCC and Clang have it there, its warning silenced for this
 * line, so that egw.h compiles without a warning in C89 to C11 and C++98 to C++17
 * (test/cli/header_std.sh) */
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wlong-long"
#endif
typedef unsigned long long egw_u64_;
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
static inline double egw_piece_exp_core_(double x);
static inline double egw_piece_exp_(double x)
{
  if (!(fabs(x) < 708.0)) return exp(x);
  return egw_piece_exp_core_(x);
}

/* egw_piece_exp_ for |x| < 708 (a folded piece's argument, tested by its caller) */
static inline double egw_piece_exp_core_(double x)
{
  /* [j] the double whose bits are t_j's less j 2^47, [32 + j] tail_j: 2^(j/32) = t_j (1 +
   * tail_j), j = 0 .. 31 (tools/reference/piece_exp_table.py) */
  static const double table[64] = {
      1.0, 0.9953235743270583, 0.9908868912137069, 0.9866952003384118, 0.9827538663326288,
      0.9790683712979462, 0.9756443173783458, 0.9724874293887887, 0.9696035575013605,
      0.9669986799902345, 0.964678906036742, 0.9626504785958666, 0.9609197773255048,
      0.9594933215798707, 0.9583777734684463, 0.957579940981916, 0.9571067811865476,
      0.9569654034885233, 0.9571630729697497, 0.9577072137967114, 0.9586054127039704,
      0.9598654225539432, 0.9614951659746271, 0.9635027390769825, 0.9658964152537145,
      0.968684649061239, 0.9718760801866497, 0.9754795375015536, 0.9795040432046712,
      0.98395881705515, 0.9888532806985737, 0.9941970620877001,
      0.0, 4.9997448722726326e-17, 8.189317638195515e-17, -7.402825309426177e-17,
      -2.7939114859515733e-17, 9.341710609905046e-17, 7.826573258636076e-17,
      3.2904726646008416e-17, 3.3484623336251524e-17, -6.346552106729483e-17,
      3.750854201303127e-17, 2.1023049675215714e-18, 1.9572585293112036e-17,
      -2.1571477251208752e-17, 5.68648095791174e-17, -4.8923067513522756e-17,
      -6.835808657661922e-17, -2.092304381843353e-17, -2.3591094770850053e-17,
      -6.735219232374683e-17, 5.1548301170786783e-17, -6.432131775424189e-18,
      1.5341410053603723e-17, -6.152602891550265e-17, 4.875160526227062e-17,
      -1.0772487078934056e-17, 1.685487290628973e-17, 1.01562190116415e-17,
      1.790126907604513e-17, -3.266924100901318e-17, -5.545065618639427e-17,
      4.5784915277060095e-17};
  double z, kd, r, r2, s;
  egw_u64_ bits, j, sb;
  z = x * 46.16624130844683 + 6755399441055744.0;
  kd = z - 6755399441055744.0;
  r = (x - kd * 0.021660849392446835) - kd * 5.145609244655338e-14;
  /* s = 2^e t_j (k = kd = 32 e + j) is t_j's bits plus (k - j) 2^52/32: table[j]'s plus
   * k 2^47, and z's bits are 1.5 2^52's plus k (|k| < 2^15), whose low 17 bits are k's:
   * bits << 47 = k 2^47 modulo 2^64. (piece_exp converts kd to an integer instead: here 2
   * instructions fewer and no cvttsd2si, stop 58) */
  memcpy(&bits, &z, sizeof bits);
  j = bits & 31;
  memcpy(&sb, &table[j], sizeof sb);
  sb += bits << 47;
  memcpy(&s, &sb, sizeof s);
  r2 = r * r;
  return s + s * (((table[32 + j] + r) + r2 * (0.5 + 0.16666666666666666 * r)) +
                  (r2 * r2) * ((0.041666666666666664 + 0.008333333333333333 * r) +
                               r2 * 0.001388888888888889));
}

/* The branches to the caller's library call marked unlikely (and the separated tail's
 * folded piece likely), so that the served steps are laid out straight; and the inline
 * inlined wherever it is called (GCC and Clang: gcc 12 -O2 made it an out-of-line
 * function, a call per contact, in a file that calls it twice; elsewhere the plain test
 * and inline). */
#if defined(__GNUC__)
#define EGW_UNLIKELY_(c) __builtin_expect(!!(c), 0)
#define EGW_LIKELY_(c) __builtin_expect(!!(c), 1)
#define EGW_ALWAYS_INLINE_ __attribute__((always_inline))
#else
#define EGW_UNLIKELY_(c) (c)
#define EGW_LIKELY_(c) (c)
#define EGW_ALWAYS_INLINE_
#endif

static inline EGW_ALWAYS_INLINE_ int egw_hysteresis_eval_cached(
    double tag, double delta, double state[EGW_HYSTERESIS_STATE_SIZE], double *force,
    double *stiffness)
{
  /* (one of the library's four copies of this arithmetic, kept the same bits: its
   * src/egw/capi/README.md) */
  /* state[2] the filling table's tag, [1] the turning point the caches belong to, [0]
   * the history, [10], [11] the piece's ends (open; [11] a zero or folded piece's too),
   * [13..16] its cubic in delta - [10], [17..23] the loading table's interval (ends,
   * cubic in delta - [17], > 0 where it is ln P; on a log-ratio table's piece, whose
   * cubic is -ln(P_load/P), 2 for ln P and -1 for a linear interval; 3 where the piece's
   * cubic is ln P - ln(P_load/P) itself, the force its exp: 0.3.2's pieces in the ln P
   * tail, which lie inside their loading interval). A log-ratio piece on a linear
   * interval spans loading intervals: it serves delta inside both its ends and the
   * loading interval's. Where the force is 0 below the loading table's cut-off (a contact
   * that has not touched, or one separated below its turning point's unloading curve)
   * the call leaves a zero piece and a zero linear interval from -sqrt(DBL_MAX)/4, so
   * that separated contacts are served here too, at once. */
  double f = 0.0, k = 0.0;
  int piece, loading;
  if (EGW_UNLIKELY_(!(state[2] == tag))) return 0;
  piece = state[1] == state[0] && state[10] < delta && delta <= state[11];
  if (piece && state[10] == -3.351951982485649e+153) {
    /* a zero piece (it starts at -sqrt(DBL_MAX)/4, the library's zero_lo): +0 and +0,
     * the values of its zero cubic and interval, as the call answers it. The library
     * writes it inside its zero interval, [17] = [10] and [11] <= [18] (zero_piece), so
     * the interval is not read (a cache line fewer); at its end [11] (the history, or
     * the unloading floor) the call gives the same +0 and leaves the state as it was.
     * (Tested here, after the piece's ends: the tail's steps keep main's branch layout,
     * 5 % faster than with this test first, stop 55) */
    if (force) *force = 0.0;
    if (stiffness) *stiffness = 0.0;
    return 1;
  }
  if (EGW_LIKELY_(piece && state[23] == 3.0)) {
    /* a folded log-ratio piece (the separated tail, 0.3.2): its cubic is ln P - h, the
     * force exp of it, one cubic and one exp; the library cuts it inside its loading
     * interval (not read) and keeps exp's argument within +-700 over it. Its end [11]
     * included: the step back at the history exactly is the piece's (stop 60). (Marked
     * likely: laid out straight, the tail's inline took 0.94 of the time, and a
     * contact's unloading piece (0.5 sigma, touched) 0.94 too, back at 0.3.1's: stop 56) */
    double x = delta - state[10], x2 = x * x;
    f = (state[13] + x * state[14]) + x2 * (state[15] + x * state[16]);
    k = (state[14] + 2 * x * state[15]) + 3 * x2 * state[16];
    /* (an argument beyond the library's bound, a garbled state: the call; below it the
     * force is positive and finite, so only the stiffness is tested) */
    if (EGW_UNLIKELY_(!(fabs(f) < 708.0))) return 0;
    f = egw_piece_exp_core_(f);
    k = f * k;
    if (EGW_UNLIKELY_(!(fabs(k) < HUGE_VAL))) return 0;
    if (force) *force = f;
    if (stiffness) *stiffness = k;
    return 1;
  }
  piece = piece && delta < state[11] && state[17] <= delta && delta < state[18];
  loading = !piece && delta >= state[0] && state[17] < delta && delta < state[18];
  if (EGW_UNLIKELY_(!piece && !loading)) return 0;
  if (piece) {
    double x = delta - state[10], x2 = x * x;
    f = (state[13] + x * state[14]) + x2 * (state[15] + x * state[16]);
    k = (state[14] + 2 * x * state[15]) + 3 * x2 * state[16];
  }
  if (loading || state[23] > 0.0 || (piece && state[23] < 0.0)) {
    /* the loading interval's force: all of it when loading; on a piece its ln P part, or
     * on a log-ratio piece the factor exp(-h) of the loading force (one exp) */
    double t = delta - state[17], t2 = t * t;
    double v = (state[19] + t * state[20]) + t2 * (state[21] + t * state[22]);
    double d = (state[20] + 2 * t * state[21]) + 3 * t2 * state[22];
    if (piece && (state[23] > 1.0 || state[23] < 0.0)) {
      double p = egw_piece_exp_(state[23] > 1.0 ? v + f : f);
      if (state[23] > 1.0) {
        k = p * (d + k);
        f = p;
      } else {
        k = p * (d + v * k);
        f = v * p;
      }
    } else if (state[23] > 0.0) {
      double p = exp(v);
      f = f + p;
      k = k + p * d;
    } else {
      f = v;
      k = d;
    }
  }
  if (piece && !(f > 0.0)) f = k = 0.0;
  /* not a number (a garbled state with this table's tag): the call refuses it */
  if (EGW_UNLIKELY_(!(f - f == 0.0 && k - k == 0.0))) return 0;
  if (loading && delta > state[0]) {
    state[10] = state[11] = NAN;    /* loading further: no piece, the new history */
    state[0] = delta;
  }                                 /* back at the history exactly: the piece kept */
  if (force) *force = f;
  if (stiffness) *stiffness = k;
  return 1;
}
#endif /* C99 or C++: inline */

/* Elastic energy [force*length] that a contact at overlap delta returns if it separates
 * now: the integral of its unloading curve (turning point max(delta_max_state, delta))
 * from the loading cut-off to delta. On the loading curve it is the part of the loading
 * work that comes back; the rest is dissipated when the contact unloads (a DEM code's
 * kinetic + this energy falls while contacts load and stays while they unload or reload).
 * Reversible tables: the loading curve's energy. The state is not changed. On a
 * ln(P_load/P) table (EP-GW) it is the loading energy times e^-eta, eta = ln(E_load/E)
 * tabulated per curve when the table is built or read and interpolated as the force's
 * log ratio (one exp a call): within rel_tol of max(energy, 1e-3 of the energy at the
 * turning point) of the integral of the force egw_hysteresis_eval returns (measured
 * 0.2-0.4 rel_tol), so kinetic + this energy drifts by up to that while a contact
 * unloads; overlaps within an s interval of the loading cut-off, and turning points
 * within ~1.5 sigma of it, integrate that force piece by piece instead (exact; a cost
 * that grows with the pieces). On a gap or force-ratio table of a rough model with the
 * cap acting it integrates that force,
 * 0 also where, far down the separated range, the interpolated curve dips below 0 within
 * rel_tol (those dips sampled per table when it is built or read; a few table lookups a
 * call); kinetic + this energy is constant to ~1e-8 of it while a contact unloads,
 * measured against quadrature of the force; on a Hertz + cap table (the force ratio) the
 * same, the force integrated from the residual overlap.
 * EGW_OUT_OF_RANGE above the table's delta_max (value written); EGW_INVALID_ARGUMENT for
 * NaN or overflowing input; EGW_NULL_POINTER for h or energy. */
int egw_hysteresis_energy(egw_hysteresis h, double delta, double delta_max_state,
                          double *energy);

/* A new contact's state: state[0] = -HUGE_VAL, the cache empty (all zeros means the same
 * to egw_hysteresis_eval_state). NULL is ignored. */
void egw_hysteresis_state_init(double state[EGW_HYSTERESIS_STATE_SIZE]);

/* egw_hysteresis_eval for n independent contacts in one call: delta[i] with history
 * delta_max_state[i] (updated), force[i], stiffness[i] (either may be NULL). A NaN overlap
 * or state, or one so large that the force would leave the doubles, refuses the call
 * (EGW_INVALID_ARGUMENT naming its index) before anything changes; NULL delta or
 * delta_max_state (n > 0): EGW_NULL_POINTER; EGW_OUT_OF_RANGE names the first contact
 * beyond the table (all values written). n = 0 does nothing; n < 0: EGW_INVALID_ARGUMENT.
 * For callers that pay per call (Python, scripting languages). */
int egw_hysteresis_eval_array(egw_hysteresis h, int n, const double *delta,
                              double *delta_max_state, double *force, double *stiffness);

/* Release a hysteresis table; sets *h to NULL. NULL or *h == NULL is fine. */
void egw_hysteresis_free(egw_hysteresis *h);

/* Write h to path (NUL-terminated) atomically (temporary file, then rename: a failed write
 * leaves an existing file intact). format: EGW_FORMAT_CSV (unloading data as rows
 * delta_max,length,s and log_ratio,dlog_ratio_dxi (EP-GW), force_ratio,dforce_ratio_ds
 * (Hertz + cap, with its fine delta_max grid, CSV format 5; rough models with the cap
 * acting, on the two-piece s map with its knees, format 6, binary version 6) or
 * gap,dgap_ds (rough models with the cap acting, written by egw 0.3.4 and earlier);
 * loading curve and metadata as '#' lines; a checksum line last) or EGW_FORMAT_BINARY (versioned, checksummed); doc/formats.md section 6.
 * Statuses: EGW_IO_ERROR, EGW_INVALID_ARGUMENT (other formats), EGW_NULL_POINTER. */
int egw_hysteresis_write(egw_hysteresis h, const char *path, int format);

/* Read a hysteresis table written by egw_hysteresis_write (CSV or binary, recognised from
 * the file's start). *out receives a handle only for a file that passed every check
 * (checksum; finite values; the loading curve every check of egw_table_read, stiffness
 * and energy consistent with its forces included; increasing grids; gaps 0 at the
 * turning point and within [0, 1], with slopes that keep each curve near that range, or
 * log ratios 0 there and within [-100, 100], where the force is served an unloading
 * force at most twice its turning point's, or force ratios 1 there, 0 at the residual
 * overlap and within [0, 1 + 10 rel_tol], with a fine grid that holds every delta_max
 * node, or, on the two-piece s map of a rough model with the cap (version 6), force ratios
 * 1 there and within [-10 rel_tol, 1 + 10 rel_tol]: doc/formats.md section 6; Hertz + cap
 * files of egw before stop 50, version 2, and rough + cap files of the gap on the map,
 * version 4, are read as written). An EP-GW
 * file of the gap curves (binary version 1 / CSV format 1 with curves, egw before the log
 * ratio) is refused: rebuild it.
 * Statuses: EGW_IO_ERROR (cannot open), EGW_BAD_FILE (what is wrong in the message),
 * EGW_NULL_POINTER. */
int egw_hysteresis_read(const char *path, egw_hysteresis *out);

typedef struct {
  int    model;        /* EGW_MODEL_* of the parameters */
  int    reversible;   /* 1: no plastic summits, unloading retraces the loading table */
  int    n_delta_max;  /* delta_max nodes (0 when reversible) */
  int    n_s;          /* nodes in s of every unloading curve (0 when reversible) */
  int    n_loading;    /* nodes of the loading table */
  double cutoff;       /* delta_c [length]: the loading table's first node, where the loading
                        * force is 1e-12 of reference_force (rough models; Hertz: rel_tol of
                        * it). Not a zero-force edge: below it the loading force follows the
                        * table's continuation (egw_table_eval: the model's separated tail;
                        * Hertz its closed form), and a contact whose
                        * history is at or below it unloads on that tail (reversible there);
                        * the unloading curve of a turning point above it ends at it (force 0
                        * below, for unloading and reloading only) */
  double delta_max;    /* last delta_max node [length] */
  double reference_force; /* P_ref [force] of the loading table's cut-off rule: the loading
                           * force at min(0, delta_max) for rough models, at delta_max for
                           * Hertz (egw_table_info.reference_force of the loading curve) */
  double rel_tol;      /* requested tolerance, relative to max(P, 1e-3 P(m)) (ln(P_load/P)
                        * curves) or to the force at the turning point P(m) (the cap acting) */
  double max_error;    /* largest mismatch found at the build's check solves, in rel_tol's
                        * units (relative to P(m) on a rough model's with the cap, gap
                        * curves or force ratios on the two-piece map; to the local
                        * force down to 1e-3 P(m) on Hertz + cap's force-ratio curves and
                        * the ln(P_load/P) curves). It includes delta_max intervals too
                        * narrow to split (Hertz + cap: 2^-24 delta_y, others 2^-11 of the
                        * range): above rel_tol where those intervals miss it. Hertz + cap,
                        * whose check solves are the cap solver's own: the force's error
                        * there, the loading table's at the turning point included (its
                        * grid refined on it; the loading table built to rel_tol/4): met
                        * from 2 to 1000 delta_y at 1e-4, 1e-5 and 3e-6, at or above the
                        * error measured between the nodes (1e-5 to 20 delta_y: 9.8e-6
                        * reported, 8.6e-6 measured at 447 turning points; doc/stability.md
                        * "Stop 53 (doubt19)"). Rough + cap: the check curves' mismatch
                        * plus the stencil's Lebesgue sum times its curves' error in s,
                        * plus the solves' rel_tol (rel_tol/10), a bound for what falls
                        * between the check curves' s nodes (E-GW + cap, sigma/delta_y
                        * 1e-2, to 6 delta_y: 1e-3 7.7e-4 reported, 4.9e-4 of P(m)
                        * measured between the nodes; 1e-4 9.9e-5, 9.0e-5; it may exceed
                        * rel_tol; doc/stability.md "Stop 54 (doubt20)") */
  egw_params params;   /* the parameters the table was built for */
} egw_hysteresis_info;

/* Facts about h into *info. EGW_NULL_POINTER. */
int egw_hysteresis_get_info(egw_hysteresis h, egw_hysteresis_info *info);

/* ------------------------------------------------------------------------
 * Scenes and the model choice. Units: any consistent set (SI suggested).
 * doc/scenes.md describes scenes and the choice rule.
 *
 * A scene states the particle types (radii; or a continuous radius range of one
 * material), materials (E and nu per type, or E* of every pair), the combined
 * roughness sigma of a pair (one value or a range), mu (or the summit density eta and
 * radius beta: mu = (8/3) eta sigma sqrt(2 R beta) per pair), the model, the overlap
 * range and a relative force tolerance. egw picks the cheapest model meeting it:
 *   1. Hertz, exactly, for smooth spheres (model Hertz or sigma = 0);
 *   2. Hertz when its error measure is <= tol for every pair parameter set, where the
 *      measure is max |P_Hertz/P - 1| over the overlaps when delta_min > 0, and
 *      max |P_Hertz - P| / P(delta_max) when delta_min <= 0 (Hertz gives 0 at
 *      separations where the rough force is not; measured relative to the scene's
 *      largest force). P from full solves at delta = 0 and 4 overlaps per decade;
 *   3. one 1-D table when the scene has one parameter set (one pair, one sigma);
 *   4. the universal 2-D table otherwise (mu and delta/sigma ranges from the scene).
 * ------------------------------------------------------------------------ */

#define EGW_SCENE_MAX_TYPES 8

/* A scene (field order matters: mirrors the Fortran type). */
typedef struct {
  int    model;                          /* EGW_MODEL_* */
  int    n_types;                        /* particle types 1..8; 0: radius range */
  double radius[EGW_SCENE_MAX_TYPES];    /* particle radius of each type [length] */
  double radius_min, radius_max;         /* radius range when n_types = 0 [length] */
  double modulus[EGW_SCENE_MAX_TYPES];   /* Young's modulus E per type [pressure];
                                            0 for a type >= 2: type 1's material */
  double poisson[EGW_SCENE_MAX_TYPES];   /* Poisson's ratio per type, (-1, 0.5] */
  double effective_modulus;              /* E* of every pair if > 0 (then E, nu unused) */
  double sigma_min, sigma_max;           /* combined summit-height std of a pair [length];
                                            equal: one value; both 0: smooth */
  double mu;                             /* Greenwood-Tripp mu if > 0, else from: */
  double summit_density;                 /* eta [1/length^2] */
  double summit_radius;                  /* beta [length] */
  double psi, hardness_coeff, plastic_ratio; /* EP-GW: psi >= 0, K in (0,1), rho_p > 1 */
  double delta_min, delta_max;           /* overlap range (delta < 0: separation) */
  int    delta_in_sigma;                 /* 0: delta in length; 1: in units of sigma */
  double tol;                            /* relative force tolerance, 1e-8 .. 0.1 */
} egw_scene;

enum { EGW_CHOICE_HERTZ = 0, EGW_CHOICE_TABLE = 1, EGW_CHOICE_UNIVERSAL = 2 };

/* A model choice and its error bound. */
typedef struct {
  int    kind;                  /* EGW_CHOICE_* */
  int    n_sets;                /* distinct pair parameter sets of the scene */
  int    n_solves;              /* full solves spent on the Hertz check */
  int    hertz_relative_to_max; /* 1: Hertz measure relative to P(delta_max) */
  int    n_nodes;               /* table nodes (universal: x nodes * mu nodes); build only */
  double error_bound;           /* Hertz: its measured error; tables: tol they are built to */
  double hertz_error;           /* the Hertz error measure (0 for smooth spheres) */
  double measured_error;        /* max rel. force error at the build's check solves;
                                   egw_scene_build only (Hertz: = error_bound) */
  double mu_min, mu_max;        /* mu range of the pairs */
  double x_min, x_max;          /* delta/sigma range of the pairs (0 if smooth) */
} egw_model_choice;

/* The embedded default scene of egw-table: two 1 mm glass beads (E = 70 GPa,
 * nu = 0.22), sigma = 1 um, mu = 4, E-GW, overlaps -2 .. 20 sigma, tol = 1e-4.
 * NULL is ignored. */
void egw_scene_default(egw_scene *s);

/* Check *s: EGW_OK or EGW_INVALID_PARAMETER with a message naming the field (e.g.
 * "radius(2) = ...", "K (hardness_coeff) = ..."). EGW_NULL_POINTER. */
int egw_scene_validate(const egw_scene *s);

/* Read the namelist group &scene of the file at path (NUL-terminated; variables in
 * doc/scenes.md): the values it gives replace those of *s, the result is validated;
 * *s is unchanged on failure. The file is read whole and parsed in memory: any number
 * of threads may read the same file at once. EGW_IO_ERROR (cannot open or read),
 * EGW_BAD_FILE (no &scene, unknown variable, unreadable value, control bytes of a
 * binary file), EGW_INVALID_PARAMETER (a bad value, named), EGW_NULL_POINTER. */
int egw_scene_read(const char *path, egw_scene *s);

/* Choose the cheapest model meeting s->tol (full solves for the Hertz check only, in
 * parallel; o may be NULL). reason (may be NULL) receives a one-line explanation,
 * NUL-terminated, truncated to reason_len bytes. Statuses: EGW_INVALID_PARAMETER,
 * EGW_INVALID_ARGUMENT (options), EGW_NOT_CONVERGED (a solve failed),
 * EGW_NULL_POINTER. */
int egw_scene_choose(const egw_scene *s, const egw_options *o, egw_model_choice *choice,
                     char *reason, int reason_len);

/* Choose, then build the chosen tables at s->tol: *table receives a handle for
 * EGW_CHOICE_TABLE (particle radii recorded for LAMMPS), *universal for
 * EGW_CHOICE_UNIVERSAL, the other (both for Hertz) is set to NULL; release them with
 * egw_table_free / egw_universal_free. *choice also gets measured_error and n_nodes.
 * Statuses as egw_scene_choose and egw_table_build; on failure no handle is created. */
int egw_scene_build(const egw_scene *s, const egw_options *o, egw_model_choice *choice,
                    egw_table *table, egw_universal *universal);

/* ======================================================================== Array kernels
 * (src/egw/capi/capi_array.f90) One call evaluates n points. Every input is read with its
 * own stride in elements: 0 = one value shared by all points, 1 = one value per point
 * (larger strides skip elements); the parameters too (p_stride 0: *p for every point,
 * validated once before any point; 1: p[i] for point i, validated with it). Outputs are
 * contiguous arrays of n (NULL where an output is documented as optional: not wanted).
 * flags: EGW_ARRAY_RAISE stops at a failing point and returns its status, the message
 * (egw_last_error) prefixed "point i: " with i its index from 0 (the lowest failing index
 * among the points tried; outputs of points already done are written, the failed one is
 * NaN); EGW_ARRAY_NAN gives a failing point NaN outputs (egw_result: NaN and iterations
 * = -1), goes on, stores the number of failed points at *n_failed (may be NULL) and
 * returns EGW_OK. Common statuses (whatever flags): EGW_INVALID_ARGUMENT (n < 0, a negative
 * stride, unknown flags, o->n_threads < 0), EGW_NULL_POINTER (p or an input or res is
 * NULL), EGW_INVALID_PARAMETER (a shared *p invalid). Inputs and outputs must not overlap.
 * n is an int: split larger arrays. Thread safe as the scalar calls. */
#define EGW_ARRAY_RAISE 0
#define EGW_ARRAY_NAN 1

/* egw_hertz at n overlaps delta (stride delta_stride); force, stiffness, contact_radius may
 * be NULL. A point fails for a non-finite delta or an overflowing force. */
int egw_hertz_array(const egw_params *p, int p_stride, int n, const double *delta,
                    int delta_stride, double *force, double *stiffness,
                    double *contact_radius, int flags, int *n_failed);

/* egw_flat_pressure_deriv at n separations: pressure and dpressure (either may be NULL). */
int egw_flat_pressure_array(const egw_params *p, int p_stride, int n,
                            const double *separation, int separation_stride,
                            double *pressure, double *dpressure, int flags, int *n_failed);

/* egw_flat_pressure_unload at n points (separation, separation_min). */
int egw_flat_pressure_unload_array(const egw_params *p, int p_stride, int n,
                                   const double *separation, int separation_stride,
                                   const double *separation_min, int separation_min_stride,
                                   double *pressure, double *dpressure, int flags,
                                   int *n_failed);

/* egw_gauss_integral (value) and egw_gauss_integral_deriv (derivative) at n points of
 * order and h; either output may be NULL. */
int egw_gauss_integral_array(int n, const double *order, int order_stride, const double *h,
                             int h_stride, double *value, double *derivative, int flags,
                             int *n_failed);

/* egw_solve at n overlaps delta, or egw_solve_unload when delta_max is not NULL; the
 * results in res[0..n-1] (not NULL). The points run over o->n_threads OpenMP threads
 * (o NULL or n_threads 0: the OpenMP default), each solve single-threaded inside; results
 * equal the scalar calls' whatever the thread count. */
int egw_solve_array(const egw_params *p, int p_stride, const egw_options *o, int n,
                    const double *delta, int delta_stride, const double *delta_max,
                    int delta_max_stride, egw_result *res, int flags, int *n_failed);

/* egw_restitution_energy and egw_restitution_overlap at n impacts (mass, velocity): e,
 * w_load, w_dissipated, max_overlap (each may be NULL); threads as egw_solve_array. */
int egw_restitution_array(const egw_params *p, int p_stride, const egw_options *o, int n,
                          const double *mass, int mass_stride, const double *velocity,
                          int velocity_stride, double *e, double *w_load,
                          double *w_dissipated, double *max_overlap, int flags,
                          int *n_failed);

/* egw_time_step at n impacts (mass, velocity) with one tolerance: duration and time_step
 * (each may be NULL); threads as egw_solve_array. The tolerance is shared: one outside
 * (0, 0.1] is EGW_INVALID_ARGUMENT naming it whatever flags, outputs untouched. */
int egw_time_step_array(const egw_params *p, int p_stride, const egw_options *o, int n,
                        const double *mass, int mass_stride, const double *velocity,
                        int velocity_stride, double tolerance, double *duration,
                        double *time_step, int flags, int *n_failed);

/* egw_universal_eval at n points: the contacts p (stride p_stride; each evaluated as the
 * scalar call checks it) at overlaps delta; force and stiffness may be NULL. A point with
 * mu outside the table gets NaN, a point above x_max*sigma the extrapolated values: the
 * call then returns EGW_OUT_OF_RANGE (all points written, message says so). Other
 * failures follow flags. */
int egw_universal_eval_array(egw_universal u, const egw_params *p, int p_stride, int n,
                             const double *delta, int delta_stride, double *force,
                             double *stiffness, int flags, int *n_failed);

/* ------------------------------------------------------------------------
 * Rough-flat laws beyond GW (doc/theory.md 11). A rough flat pressed onto a smooth rigid
 * flat carries a mean pressure p [pressure] at a mean separation u [length] (u > 0 apart,
 * measured from the law's reference plane: the mean plane of the heights for a tabulated,
 * Persson or BEM law; p >= 0; dp/du <= 0). egw_flat_law is such a law; the sphere solve
 * egw_solve_flat_law takes one in place of GW's law of independent summits: the local
 * pressure at radius r is p(u(r)) with u(r) = r^2/(2R) - delta + w(r), w the half-space
 * deflection, so delta is the overlap with the law's reference plane (delta_m; for the
 * mean plane, GW's delta = delta_m + y_s). Laws are read-only once made: one law may
 * serve any number of threads at once.
 * ------------------------------------------------------------------------ */

typedef struct egw_flat_law_s *egw_flat_law; /* opaque: one rough-flat law */

/* A tabulated law from n >= 2 nodes: u[i] strictly ascending [length], p[i] > 0 strictly
 * decreasing [pressure]; dpdu[i] <= 0 (NULL: slopes from the nodes) and area[i] in [0, 1],
 * the contact-area fraction (NULL: the law has none). Interpolation: a monotone cubic
 * Hermite in (u, ln p) (C1, exact at the nodes); beyond both ends ln p continues linearly
 * with the end slope (p ~ exp(-u/u0), the large-separation law of Persson's theory and of
 * BEM). length [length]: the law's natural length, the unit the sphere solve scales by
 * (the surface's rms height; 0: the decay length -1/(d ln p/du) at the last node).
 * modulus: the E* the law was computed with (0: not known; else egw_solve_flat_law
 * refuses another E*). *out receives a handle only on success; free it with
 * egw_flat_law_free. Statuses: EGW_INVALID_ARGUMENT (naming the node), EGW_NULL_POINTER. */
int egw_flat_law_from_table(const double *u, const double *p, const double *dpdu,
                            const double *area, int n, double length, double modulus,
                            egw_flat_law *out);

/* Persson's law (doc/theory.md 11: PRL 99 125502 (2007) with the elastic-energy factor
 * gamma = 0.42 of Yang & Persson 2008) of an isotropic 2-D power spectrum: n >= 2 nodes
 * q[i] [rad/length] ascending, C[i] >= 0 [length^4] (<h^2> = 2 pi int q C dq; a power law
 * between nodes, 0 outside), E* = modulus. Nodes at 10 mean pressures a decade from p_min
 * to p_max [pressure] (0: 1e-6 E* and 1e-1 E*), with exact dp/du and the contact-area
 * fraction; length = the spectrum's rms height; modulus recorded. Statuses:
 * EGW_INVALID_ARGUMENT (naming q(i), C(i), modulus, p_min, p_max), EGW_NULL_POINTER. */
int egw_flat_law_from_psd(const double *q, const double *C, int n, double modulus,
                          double p_min, double p_max, egw_flat_law *out);

/* egw's periodic FFT boundary-element law of a height map (doc/theory.md 11): heights
 * [length] row-major, ny rows of nx pixels (heights[iy*nx + ix], a numpy (ny, nx) array),
 * one period of a periodic surface, square pixels of size pixel [length], E* = modulus;
 * frictionless, non-adhesive, hard wall, the half-space's Fourier stiffness E*|q|/2 on the
 * pixels (as ContactMechanics' periodic FFT system); load-controlled solves at 10 mean
 * pressures a decade from p_min to p_max [pressure] (0: 1e-6 E* and 1e-1 E*), each
 * warm-started, with the contact-area fraction and the exact incremental stiffness as
 * -dp/du; the sweep stops before full contact. length = the map's rms height; o: NULL or
 * options (n_threads used: OpenMP and FFTW threads). Statuses: EGW_INVALID_ARGUMENT (a bad
 * map; pixel or modulus outside [1e-100, 1e100]; pressures outside [1e-12 E*, E*]),
 * EGW_NOT_CONVERGED (a load's solve), EGW_UNSUPPORTED
 * (full contact at p_min already), EGW_NULL_POINTER. */
int egw_flat_law_from_heights(const double *heights, int nx, int ny, double pixel,
                              double modulus, double p_min, double p_max,
                              const egw_options *o, egw_flat_law *out);

/* Mean pressure *pressure [pressure] and *dpdu [pressure/length] at mean separation u
 * [length] (NULL outputs skipped). EGW_INVALID_ARGUMENT for NaN u; EGW_NULL_POINTER. */
int egw_flat_law_pressure(egw_flat_law law, double u, double *pressure, double *dpdu);

/* Contact-area fraction A/A0 in [0, 1] at u (linear between nodes, the end values beyond
 * them). EGW_UNSUPPORTED for a law made without area data; EGW_INVALID_ARGUMENT for NaN
 * u; EGW_NULL_POINTER. */
int egw_flat_law_contact_area(egw_flat_law law, double u, double *area);

/* Facts about a law (NULL outputs skipped): nodes, length, modulus (0: not known), the
 * nodes' separation range [u_min, u_max] and has_area (1 if it carries contact areas). */
int egw_flat_law_info(egw_flat_law law, int *n_nodes, double *length, double *modulus,
                      double *u_min, double *u_max, int *has_area);

/* The same law in other units: separations (and its length) divided by unit_length,
 * pressures (and its E*) by pressure_unit, both in [1e-100, 1e100]; e.g. a DEM code's
 * normalised units. *out receives a new handle only on success. Statuses:
 * EGW_INVALID_ARGUMENT (naming the unit), EGW_NULL_POINTER. */
int egw_flat_law_rescale(egw_flat_law law, double unit_length, double pressure_unit,
                         egw_flat_law *out);

/* Release a law; sets *law to NULL. NULL or *law == NULL is fine. */
void egw_flat_law_free(egw_flat_law *law);

/* Write the law as egw CSV (doc/formats.md 7: columns u, pressure, dpdu[, area], the
 * length and modulus in '#' lines, a checksum line), atomically. Statuses as
 * egw_table_write (EGW_IO_ERROR naming the path), EGW_NULL_POINTER. */
int egw_flat_law_write(egw_flat_law law, const char *path);

/* Read a law file: egw's CSV, or a user's CSV whose first line names the columns u and
 * pressure (optionally dpdu, area), with optional '# length = ...' and '# modulus = ...'
 * lines and no checksum needed (one that is there must match). *out receives a handle
 * only on success. Statuses: EGW_IO_ERROR, EGW_BAD_FILE (naming the path and line or
 * node), EGW_NULL_POINTER. */
int egw_flat_law_read(const char *path, egw_flat_law *out);

/* The loading solve of a sphere pair with a rough-flat law: R = p->radius, E* =
 * p->modulus (the other fields of p must be valid, as egw_params_default leaves them, and
 * are not used but p->flow_pressure: with it the total pressure is capped at p_y, the law
 * below it, doc/theory.md 12; p->model may be EGW_MODEL_FLAT_LAW), delta [length] the
 * overlap with the law's reference plane. Results, options and statuses as egw_solve, plus
 * EGW_INVALID_PARAMETER when the law was made with another E* than p->modulus. Unloading
 * is EP-GW's alone (egw_solve_unload). */
int egw_solve_flat_law(const egw_params *p, egw_flat_law law, const egw_options *o,
                       double delta, egw_result *res);

/* A 1-D force table (egw_table_build's machinery and tolerance) of the pair R =
 * p->radius, E* = p->modulus with the law, delta the overlap with the law's reference
 * plane. The table's model is EGW_MODEL_FLAT_LAW with sigma = the law's length; it is
 * evaluated, written and read like any table (egw_table_eval, egw_table_write,
 * egw_table_read: a file needs no law): below the cut-off the exponential continuation of
 * the first node P = P_c exp((K_c/P_c)(delta - delta_c)), above the last node the
 * deep-overlap asymptote, nodes at least to 10 lengths. Not cached on disk (a law is not
 * a few numbers). Statuses as egw_table_build and egw_solve_flat_law; p->flow_pressure > 0
 * is EGW_INVALID_PARAMETER naming it (force tables have no cap, as egw_table_build). */
int egw_table_build_flat_law(const egw_params *p, egw_flat_law law, const egw_options *o,
                             double delta_min, double delta_max, double rel_tol,
                             egw_table *out);

#ifdef __cplusplus
}
#endif

#endif /* EGW_H */
