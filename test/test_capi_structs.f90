!> The C structs and constants of include/egw.h against their Fortran mirrors
!> (test/struct_checks.c holds the C half). Each mirrored struct gets the same values on
!> both sides: here by component name, in C by position, and C compares them field by
!> field by name. A field added to one side only is a compile error of this suite (a
!> Fortran structure constructor must give every component; the C file turns
!> -Wmissing-field-initializers into an error); a field of another type, place, order or
!> size shows as a sizeof or a field mismatch.
module test_capi_structs
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_size_t, c_sizeof, &
      & c_associated, c_f_pointer, c_int8_t
   use testdrive, only: new_unittest, unittest_type, error_type, check, to_string
   use egw_status, only: egw_ok, egw_invalid_argument, egw_invalid_parameter, &
      & egw_not_converged, egw_io_error, egw_bad_file, egw_out_of_memory, egw_null_pointer, &
      & egw_out_of_range, egw_unsupported, egw_status_max
   use egw_params, only: model_hertz, model_gw, model_egw, model_epgw
   use egw_rough_sphere, only: method_auto, method_newton, method_picard
   use egw_table_format, only: format_csv, format_binary, format_lammps, format_calculix, &
      & calculix_max_pairs
   use egw_hysteresis, only: hysteresis_state_size
   use egw_scene, only: max_types, choice_hertz, choice_table, choice_universal
   use egw_version, only: egw_version_number
   use egw_capi_utils, only: egw_params_c, egw_options_c, egw_result_c
   use egw_capi_table, only: egw_table_info_c
   use egw_capi_hysteresis, only: egw_hysteresis_info_c
   use egw_capi_scene, only: egw_scene_c, egw_model_choice_c
   implicit none
   private
   public :: collect_capi_structs

   !> The structs compared, numbered as in test/struct_checks.c.
   integer, parameter :: n_structs = 7

   interface
      !> C: the failed checks of every struct (sizeof and each field).
      integer(c_int) function c_struct_layout() bind(C, name="egw_capi_test_struct_layout")
         import :: c_int
      end function
      !> C: the header's constants in the order of constant_names.
      subroutine c_constants(values, n) bind(C, name="egw_capi_test_constants")
         import :: c_int
         integer(c_int), intent(out) :: values(*)
         integer(c_int), value, intent(in) :: n
      end subroutine
   end interface

contains

   subroutine collect_capi_structs(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("struct sizes and fields match egw.h", t_layout), &
         & new_unittest("status, model, method, format constants", t_constants) &
         & ]
   end subroutine collect_capi_structs

   subroutine t_layout(error)
      type(error_type), allocatable, intent(out) :: error
      integer(c_int) :: nfail
      nfail = c_struct_layout()
      call check(error, int(nfail) == 0, to_string(int(nfail))// &
         & " C check(s) of the struct mirrors failed (see above)")
   end subroutine t_layout

   subroutine t_constants(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), parameter :: names(29) = [character(len=26) :: &
         & "EGW_OK", "EGW_INVALID_ARGUMENT", "EGW_INVALID_PARAMETER", "EGW_NOT_CONVERGED", &
         & "EGW_IO_ERROR", "EGW_BAD_FILE", "EGW_OUT_OF_MEMORY", "EGW_NULL_POINTER", &
         & "EGW_OUT_OF_RANGE", "EGW_UNSUPPORTED", "EGW_MODEL_HERTZ", "EGW_MODEL_GW", &
         & "EGW_MODEL_EGW", "EGW_MODEL_EPGW", "EGW_METHOD_AUTO", "EGW_METHOD_NEWTON", &
         & "EGW_METHOD_PICARD", "EGW_FORMAT_CSV", "EGW_FORMAT_BINARY", "EGW_FORMAT_LAMMPS", &
         & "EGW_FORMAT_CALCULIX", "EGW_CALCULIX_MAX_PAIRS", "EGW_HYSTERESIS_STATE_SIZE", &
         & "EGW_SCENE_MAX_TYPES", "EGW_CHOICE_HERTZ", "EGW_CHOICE_TABLE", &
         & "EGW_CHOICE_UNIVERSAL", "EGW_VERSION", "EGW_UNSUPPORTED (last status)"]
      integer, parameter :: fortran(size(names)) = [egw_ok, egw_invalid_argument, &
         & egw_invalid_parameter, egw_not_converged, egw_io_error, egw_bad_file, &
         & egw_out_of_memory, egw_null_pointer, egw_out_of_range, egw_unsupported, &
         & model_hertz, model_gw, model_egw, model_epgw, method_auto, method_newton, &
         & method_picard, format_csv, format_binary, format_lammps, format_calculix, &
         & calculix_max_pairs, hysteresis_state_size, max_types, choice_hertz, &
         & choice_table, choice_universal, egw_version_number, egw_status_max]
      integer(c_int) :: c_values(size(names))
      integer :: i
      c_values = -1
      call c_constants(c_values, size(names, kind=c_int))
      do i = 1, size(names)
         call check(error, int(c_values(i)) == fortran(i), trim(names(i))//" = "// &
            & to_string(int(c_values(i)))//" in egw.h, "//to_string(fortran(i))//" in Fortran")
         if (allocated(error)) return
      end do
   end subroutine t_constants

   !> For C: the size of the Fortran mirror of struct `which` (0 .. n_structs - 1, in the
   !> order of test/struct_checks.c), and, when out is not NULL, its reference value
   !> stored there: field k (in egw.h's order) holds k (int) or k + 0.25 (double),
   !> element j of an array field 100 k + j, the fields of a nested egw_params 10 + theirs.
   integer(c_size_t) function fortran_struct(which, out) result(size) &
      & bind(C, name="egw_test_fortran_struct")
      integer(c_int), value, intent(in) :: which
      type(c_ptr), value, intent(in) :: out
      type(egw_params_c) :: params
      type(egw_options_c) :: options
      type(egw_result_c) :: result
      type(egw_table_info_c) :: table_info
      type(egw_hysteresis_info_c) :: hysteresis_info
      type(egw_scene_c) :: scene
      type(egw_model_choice_c) :: choice
      integer(c_int8_t), parameter :: byte(1) = 0_c_int8_t  ! transfer's mold
      size = 0
      select case (which)
      case (0)
         params = ref_params(0)
         size = c_sizeof(params)
         call store(out, transfer(params, byte))
      case (1)
         options = egw_options_c(n_radial=1, rel_tol=2.25_c_double, max_iter=3, method=4, &
            & n_threads=5)
         size = c_sizeof(options)
         call store(out, transfer(options, byte))
      case (2)
         result = egw_result_c(force=1.25_c_double, stiffness=2.25_c_double, &
            & contact_radius=3.25_c_double, max_pressure=4.25_c_double, &
            & est_rel_err=5.25_c_double, residual=6.25_c_double, iterations=7, method_used=8)
         size = c_sizeof(result)
         call store(out, transfer(result, byte))
      case (3)
         table_info = egw_table_info_c(model=1, n_nodes=2, cutoff=3.25_c_double, &
            & delta_max=4.25_c_double, reference_force=5.25_c_double, rel_tol=6.25_c_double, &
            & max_force_error=7.25_c_double, max_stiffness_error=8.25_c_double, &
            & checksum_missing=9)
         size = c_sizeof(table_info)
         call store(out, transfer(table_info, byte))
      case (4)
         hysteresis_info = egw_hysteresis_info_c(model=1, reversible=2, n_delta_max=3, n_s=4, &
            & n_loading=5, cutoff=6.25_c_double, delta_max=7.25_c_double, &
            & reference_force=8.25_c_double, rel_tol=9.25_c_double, max_error=10.25_c_double, &
            & params=ref_params(11))
         size = c_sizeof(hysteresis_info)
         call store(out, transfer(hysteresis_info, byte))
      case (5)
         scene = egw_scene_c(model=1, n_types=2, radius=array(3), radius_min=4.25_c_double, &
            & radius_max=5.25_c_double, modulus=array(6), poisson=array(7), &
            & effective_modulus=8.25_c_double, sigma_min=9.25_c_double, &
            & sigma_max=10.25_c_double, mu=11.25_c_double, summit_density=12.25_c_double, &
            & summit_radius=13.25_c_double, psi=14.25_c_double, &
            & hardness_coeff=15.25_c_double, plastic_ratio=16.25_c_double, &
            & delta_min=17.25_c_double, delta_max=18.25_c_double, delta_in_sigma=19, &
            & tol=20.25_c_double)
         size = c_sizeof(scene)
         call store(out, transfer(scene, byte))
      case (6)
         choice = egw_model_choice_c(kind=1, n_sets=2, n_solves=3, hertz_relative_to_max=4, &
            & n_nodes=5, error_bound=6.25_c_double, hertz_error=7.25_c_double, &
            & measured_error=8.25_c_double, mu_min=9.25_c_double, mu_max=10.25_c_double, &
            & x_min=11.25_c_double, x_max=12.25_c_double)
         size = c_sizeof(choice)
         call store(out, transfer(choice, byte))
      end select
   end function fortran_struct

   !> Copy the bytes of a reference value to out (nothing when NULL).
   subroutine store(out, bytes)
      type(c_ptr), intent(in) :: out
      integer(c_int8_t), intent(in) :: bytes(:)
      integer(c_int8_t), pointer :: target(:)
      if (.not. c_associated(out)) return
      call c_f_pointer(out, target, [size(bytes)])
      target = bytes
   end subroutine store

   !> The reference egw_params, its field k holding shift + k (+ 0.25 for a double).
   pure function ref_params(shift) result(p)
      integer, intent(in) :: shift
      type(egw_params_c) :: p
      real(c_double) :: s
      s = real(shift, c_double)
      p = egw_params_c(model=shift + 1, radius=s + 2.25_c_double, modulus=s + 3.25_c_double, &
         & sigma=s + 4.25_c_double, mu=s + 5.25_c_double, psi=s + 6.25_c_double, &
         & hardness_coeff=s + 7.25_c_double, plastic_ratio=s + 8.25_c_double, &
         & flow_pressure=s + 9.25_c_double)
   end function ref_params

   !> The reference array field number k: element j holds 100 k + j.
   pure function array(k) result(x)
      integer, intent(in) :: k
      real(c_double) :: x(max_types)
      integer :: j
      x = [(real(100*k + j, c_double), j = 1, max_types)]
   end function array

end module test_capi_structs
