/* The structs and constants of include/egw.h against the Fortran mirrors (bind(C) types
 * of src/egw/capi/capi*.f90 and the Fortran constants); test/test_capi_structs.f90 runs these
 * checks and holds the Fortran half (egw_test_fortran_struct).
 *
 * Every struct is initialised here by position and in Fortran by component name with the
 * same values: field k (in egw.h's order) holds k (int) or k + 0.25 (double), element j
 * of an array field 100 k + j, the fields of a nested egw_params 10 + theirs; the checks
 * below compare them field by field by name. A field added to egw.h and not here is a
 * compile error (the pragma below); one added to a Fortran type only is a compile error
 * of its Fortran structure constructor; a field of another type, place, order or size
 * shows as a sizeof or field mismatch. */
#pragma GCC diagnostic error "-Wmissing-field-initializers"
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include "egw.h"

/* the Fortran mirror of struct number which (order of the cases below): its c_sizeof,
 * and its reference value stored at out unless out is NULL */
size_t egw_test_fortran_struct(int which, void *out);

static int failures;
#define CHECK(cond) do { if (!(cond)) { failures++; \
  printf("    C check failed at %s:%d: %s\n", __FILE__, __LINE__, #cond); } } while (0)
/* the field f of the C reference c and the Fortran reference f_ (exact: the values are
 * small integers and quarters, exact in binary) */
#define SAME(f) CHECK(c.f == f_.f)
#define SAME_ARRAY(f) do { for (int j = 0; j < EGW_SCENE_MAX_TYPES; j++) SAME(f[j]); } while (0)
/* sizeof in C and c_sizeof of the Fortran type; then the Fortran reference into f_
 * (zeroed first, so a field Fortran does not write reads as 0) */
#define FETCH(type, which) \
  type f_; \
  memset(&f_, 0, sizeof f_); \
  CHECK(egw_test_fortran_struct(which, NULL) == sizeof(type)); \
  if (egw_test_fortran_struct(which, NULL) != sizeof(type)) return; \
  egw_test_fortran_struct(which, &f_)

#define PARAMS_REF(s) \
  {s + 1, s + 2.25, s + 3.25, s + 4.25, s + 5.25, s + 6.25, s + 7.25, s + 8.25, s + 9.25}
#define ARRAY_REF(k) {100 * k + 1, 100 * k + 2, 100 * k + 3, 100 * k + 4, 100 * k + 5, \
  100 * k + 6, 100 * k + 7, 100 * k + 8}

static void same_params(egw_params c, egw_params f_) {
  SAME(model); SAME(radius); SAME(modulus); SAME(sigma); SAME(mu); SAME(psi);
  SAME(hardness_coeff); SAME(plastic_ratio); SAME(flow_pressure);
}

static void check_params(void) {
  const egw_params c = PARAMS_REF(0);
  FETCH(egw_params, 0);
  same_params(c, f_);
}

static void check_options(void) {
  const egw_options c = {1, 2.25, 3, 4, 5};
  FETCH(egw_options, 1);
  SAME(n_radial); SAME(rel_tol); SAME(max_iter); SAME(method); SAME(n_threads);
}

static void check_result(void) {
  const egw_result c = {1.25, 2.25, 3.25, 4.25, 5.25, 6.25, 7, 8};
  FETCH(egw_result, 2);
  SAME(force); SAME(stiffness); SAME(contact_radius); SAME(max_pressure); SAME(est_rel_err);
  SAME(residual); SAME(iterations); SAME(method_used);
}

static void check_table_info(void) {
  const egw_table_info c = {1, 2, 3.25, 4.25, 5.25, 6.25, 7.25, 8.25, 9};
  FETCH(egw_table_info, 3);
  SAME(model); SAME(n_nodes); SAME(cutoff); SAME(delta_max); SAME(reference_force);
  SAME(rel_tol); SAME(max_force_error); SAME(max_stiffness_error); SAME(checksum_missing);
}

static void check_hysteresis_info(void) {
  const egw_hysteresis_info c = {1, 2, 3, 4, 5, 6.25, 7.25, 8.25, 9.25, 10.25,
                                 PARAMS_REF(11)};
  FETCH(egw_hysteresis_info, 4);
  SAME(model); SAME(reversible); SAME(n_delta_max); SAME(n_s); SAME(n_loading);
  SAME(cutoff); SAME(delta_max); SAME(reference_force); SAME(rel_tol); SAME(max_error);
  same_params(c.params, f_.params);
}

static void check_scene(void) {
  const egw_scene c = {1, 2, ARRAY_REF(3), 4.25, 5.25, ARRAY_REF(6), ARRAY_REF(7), 8.25,
                       9.25, 10.25, 11.25, 12.25, 13.25, 14.25, 15.25, 16.25, 17.25, 18.25,
                       19, 20.25};
  FETCH(egw_scene, 5);
  SAME(model); SAME(n_types); SAME_ARRAY(radius); SAME(radius_min); SAME(radius_max);
  SAME_ARRAY(modulus); SAME_ARRAY(poisson); SAME(effective_modulus); SAME(sigma_min);
  SAME(sigma_max); SAME(mu); SAME(summit_density); SAME(summit_radius); SAME(psi);
  SAME(hardness_coeff); SAME(plastic_ratio); SAME(delta_min); SAME(delta_max);
  SAME(delta_in_sigma); SAME(tol);
}

static void check_model_choice(void) {
  const egw_model_choice c = {1, 2, 3, 4, 5, 6.25, 7.25, 8.25, 9.25, 10.25, 11.25, 12.25};
  FETCH(egw_model_choice, 6);
  SAME(kind); SAME(n_sets); SAME(n_solves); SAME(hertz_relative_to_max); SAME(n_nodes);
  SAME(error_bound); SAME(hertz_error); SAME(measured_error); SAME(mu_min); SAME(mu_max);
  SAME(x_min); SAME(x_max);
}

int egw_capi_test_struct_layout(void) {
  failures = 0;
  check_params();
  check_options();
  check_result();
  check_table_info();
  check_hysteresis_info();
  check_scene();
  check_model_choice();
  return failures;
}

/* The header's constants, in the order of test_capi_structs.f90's names; the last is the
 * largest status code (Fortran: egw_status_max), so a status added on one side shows. */
void egw_capi_test_constants(int *values, int n) {
  const int c[] = {EGW_OK, EGW_INVALID_ARGUMENT, EGW_INVALID_PARAMETER, EGW_NOT_CONVERGED,
                   EGW_IO_ERROR, EGW_BAD_FILE, EGW_OUT_OF_MEMORY, EGW_NULL_POINTER,
                   EGW_OUT_OF_RANGE, EGW_UNSUPPORTED, EGW_MODEL_HERTZ, EGW_MODEL_GW,
                   EGW_MODEL_EGW, EGW_MODEL_EPGW, EGW_METHOD_AUTO, EGW_METHOD_NEWTON,
                   EGW_METHOD_PICARD, EGW_FORMAT_CSV, EGW_FORMAT_BINARY, EGW_FORMAT_LAMMPS,
                   EGW_FORMAT_CALCULIX, EGW_CALCULIX_MAX_PAIRS, EGW_HYSTERESIS_STATE_SIZE,
                   EGW_SCENE_MAX_TYPES, EGW_CHOICE_HERTZ, EGW_CHOICE_TABLE,
                   EGW_CHOICE_UNIVERSAL, EGW_VERSION, EGW_UNSUPPORTED};
  for (int i = 0; i < n && i < (int)(sizeof c / sizeof c[0]); i++) values[i] = c[i];
}
