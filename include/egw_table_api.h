/*
 * egw_table_api.h - force tables for DEM and FE codes (C API of egw's tables).
 * Meant to be pasted into include/egw.h after the solver section (it needs egw_params
 * and egw_options); until then include egw.h first. Units as in egw.h: any consistent
 * set; delta > 0 overlap, < 0 separation; forces positive in compression.
 *
 * A table is built from full solves with nodes placed adaptively until the cubic
 * Hermite interpolant (slope = the solver's stiffness; ln P in the separated tail)
 * agrees with solves between nodes to rel_tol. Below the cut-off delta_c, where the
 * force has fallen to rel_tol * P_ref, force and stiffness are exactly 0 (jump <=
 * rel_tol * P_ref). P_ref = P(min(0, delta_max)) for rough models, P(delta_max) for
 * Hertz. Evaluation allocates nothing and is thread-safe. File formats: doc/formats.md.
 */
#ifndef EGW_TABLE_API_H
#define EGW_TABLE_API_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct egw_table_s *egw_table;         /* opaque: one parameter set */
typedef struct egw_universal_s *egw_universal; /* opaque: every R, E, sigma, mu */

enum { EGW_FORMAT_CSV = 0, EGW_FORMAT_BINARY = 1, EGW_FORMAT_LAMMPS = 2, EGW_FORMAT_CALCULIX = 3 };

/* Facts about a table. */
typedef struct {
  int    model;               /* EGW_MODEL_* of the parameters */
  int    n_nodes;             /* interpolation nodes */
  double cutoff;              /* delta_c: force and stiffness are 0 below [length] */
  double delta_max;           /* last node [length]; above it the table extrapolates */
  double reference_force;     /* P_ref of the cut-off rule [force] */
  double rel_tol;             /* requested interpolation tolerance */
  double max_force_error;     /* measured max |P_table/P_solve - 1| at check solves */
  double max_stiffness_error; /* same for the stiffness (reported, not enforced) */
} egw_table_info;

/* Build the table of p over at least [delta_min, delta_max] with interpolation error
 * <= rel_tol (1e-10 <= rel_tol <= 0.1). Points are solved in parallel (OpenMP; o's
 * n_threads is set to 1 inside, its rel_tol tightened to min(o->rel_tol, rel_tol/10));
 * o may be NULL (defaults). The table starts at the cut-off delta_c, below delta_min if
 * the force there still exceeds rel_tol * P_ref. *out receives a handle only on success.
 * Statuses: EGW_INVALID_PARAMETER, EGW_INVALID_ARGUMENT (range, rel_tol, smooth spheres
 * with delta_max <= 0), EGW_NOT_CONVERGED (a solve failed, or the node limit of 20000
 * was reached), EGW_NULL_POINTER. */
int egw_table_build(const egw_params *p, const egw_options *o, double delta_min,
                    double delta_max, double rel_tol, egw_table *out);

/* Force [force] and stiffness dP/ddelta [force/length] at overlap delta. Exactly 0 below
 * the cut-off. Above delta_max the force continues linearly with the stiffness at
 * delta_max (C1, below a convex force law) and EGW_OUT_OF_RANGE is returned WITH the
 * outputs written (the one exception to "outputs unchanged on failure"). NULL outputs
 * are skipped. EGW_INVALID_ARGUMENT for NaN delta; EGW_NULL_POINTER for t. */
int egw_table_eval(egw_table t, double delta, double *force, double *stiffness);

/* As egw_table_eval, plus the elastic energy int_{delta_c}^{delta} P ddelta of the
 * interpolant [force*length] and the effective contact radius a* [length] (monotone
 * cubic through the solver's values; not error-controlled). */
int egw_table_eval_all(egw_table t, double delta, double *force, double *stiffness,
                       double *energy, double *contact_radius);

/* Facts about t into *info. EGW_NULL_POINTER. */
int egw_table_get_info(egw_table t, egw_table_info *info);

/* Record the particle radii R1, R2 of the pair (LAMMPS distances r = R1 + R2 - delta).
 * They must give the table's R: 1/R = 1/R1 + 1/R2 (to 1e-12); otherwise
 * EGW_INVALID_ARGUMENT and nothing changes. Without radii the LAMMPS file is written for
 * two equal spheres R1 = R2 = 2R, and says so. */
int egw_table_set_radii(egw_table t, double radius1, double radius2);

/* Write t to path (NUL-terminated) atomically (temporary file, then rename: a failed
 * write leaves an existing file intact). format: EGW_FORMAT_CSV, EGW_FORMAT_BINARY,
 * EGW_FORMAT_LAMMPS (one pair_style table section, keyword EGW_1), EGW_FORMAT_CALCULIX
 * (*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR: force per node against overlap, for
 * node-to-surface contact). Statuses: EGW_IO_ERROR, EGW_INVALID_ARGUMENT (unknown
 * format, non-finite data), EGW_NULL_POINTER. */
int egw_table_write(egw_table t, const char *path, int format);

/* LAMMPS file with one pair_style table section per table (keywords EGW_1 .. EGW_n, in
 * the order given), e.g. one per particle-type pair. Atomic like egw_table_write.
 * EGW_INVALID_ARGUMENT for n < 1, EGW_NULL_POINTER for a NULL array, handle or path. */
int egw_tables_write_lammps(int n, const egw_table *tables, const char *path);

/* Read an egw CSV or binary table (format recognised from the file's start). A
 * truncated, corrupted (checksum), wrong-version or inconsistent file gives EGW_BAD_FILE
 * with a message saying what is wrong, and no table. EGW_IO_ERROR if it cannot be
 * opened. *out receives a handle only on success. */
int egw_table_read(const char *path, egw_table *out);

/* Release a table; sets *t to NULL. NULL or *t == NULL is fine. */
void egw_table_free(egw_table *t);

/* CalculiX pressure-overclosure curve of the rough flat of p (p_G of DESIGN.md section 3,
 * overclosure = -separation) from zero pressure where p_G < rel_tol * p_G(0) up to
 * overclosure_max > 0 [length], linear-interpolation error <= rel_tol of the local
 * pressure. Needs p->sigma > 0. Statuses as egw_table_write, EGW_INVALID_PARAMETER. */
int egw_write_flat_calculix(const egw_params *p, double overclosure_max, double rel_tol,
                            const char *path);

/* ------------------------------------------------------------------------
 * Universal tables: p = P/(E sqrt(R) sigma^1.5) over x = delta/sigma and mu, for one
 * model (and psi, K, rho_p for EP-GW). One table serves every radius, modulus and
 * roughness of a polydisperse scene; mu is interpolated in ln mu (4-point Lagrange on
 * ln p) on a grid refined until solves at mid-grid mu agree to rel_tol (the slices are
 * built to rel_tol/2 on shared x nodes). Evaluation costs about 10 Hertz forces (a log
 * of mu, one lookup, one cubic, an exp): for one parameter set a 1-D table is cheaper.
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
 * sigma^1.5 p(delta/sigma, mu). Exactly 0 below the cut-off. mu outside the table:
 * EGW_OUT_OF_RANGE, outputs unchanged. delta above x_max*sigma: EGW_OUT_OF_RANGE with
 * extrapolated outputs written. EGW_INVALID_PARAMETER for sigma, R or E <= 0. */
int egw_universal_eval(egw_universal u, const egw_params *p, double delta, double *force,
                       double *stiffness);

/* Write (EGW_FORMAT_CSV or EGW_FORMAT_BINARY; LAMMPS and CalculiX need one parameter set:
 * EGW_UNSUPPORTED) and read, with the guarantees of egw_table_write / egw_table_read. */
int egw_universal_write(egw_universal u, const char *path, int format);
int egw_universal_read(const char *path, egw_universal *out);

/* Release a universal table; sets *u to NULL. NULL or *u == NULL is fine. */
void egw_universal_free(egw_universal *u);

#ifdef __cplusplus
}
#endif

#endif /* EGW_TABLE_API_H */
