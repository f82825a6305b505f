/*
 * egw_scene_api.h - scenes and the model choice (C API of egw_scene).
 * Meant to be pasted into include/egw.h after the table section (it needs egw_options,
 * egw_table and egw_universal); until then include egw.h first. Units: any consistent
 * set (SI suggested). doc/scenes.md describes scenes and the choice rule.
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
 */
#ifndef EGW_SCENE_API_H
#define EGW_SCENE_API_H

#ifdef __cplusplus
extern "C" {
#endif

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
 * "radius(2) = ...", "K = ..."). EGW_NULL_POINTER. */
int egw_scene_validate(const egw_scene *s);

/* Read the namelist group &scene of the file at path (NUL-terminated; variables in
 * doc/scenes.md): the values it gives replace those of *s, the result is validated;
 * *s is unchanged on failure. EGW_IO_ERROR (cannot open), EGW_BAD_FILE (no &scene,
 * unknown variable, unreadable value), EGW_INVALID_PARAMETER (a bad value, named),
 * EGW_NULL_POINTER. */
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

#ifdef __cplusplus
}
#endif

#endif /* EGW_SCENE_API_H */
