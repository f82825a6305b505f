!> C API of scenes (include/egw.h): the egw_scene
!> struct, reading a namelist scene file, the model choice and the build of its tables
!> as egw_table / egw_universal handles (released by egw_table_free /
!> egw_universal_free), and the first yield of an impact (egw_first_yield). Errors go
!> through egw_capi_utils' per-thread last-error message.
module egw_capi_scene
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_null_ptr, &
      & c_associated, c_f_pointer, c_loc
   use egw_progress, only: progress_begin, progress_end, progress_count
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_ok, egw_invalid_parameter, fatal_error, format_real
   use egw_rough_sphere, only: solver_options
   use egw_table, only: force_table
   use egw_table_universal, only: universal_table
   use egw_scene, only: scene_input, contact_scene, model_choice, scene_tables, max_types, &
      & default_scene_input, read_scene_file, validate_scene_input, resolve_scene, &
      & choose_model, build_scene_tables, choice_table, choice_universal
   use egw_capi_utils, only: settle, require, read_options, c_string, copy_to_c, read_params, &
      & check_positive, invalid, put
   use egw_params, only: contact_params
   use egw_impact_regime, only: first_yield_overlap, yield_speed
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private

   !> Mirror of the C struct egw_scene (field order of scene_input).
   type, bind(C) :: egw_scene_c
      integer(c_int) :: model, n_types
      real(c_double) :: radius(max_types), radius_min, radius_max
      real(c_double) :: modulus(max_types), poisson(max_types), effective_modulus
      real(c_double) :: sigma_min, sigma_max, mu, summit_density, summit_radius
      real(c_double) :: psi, hardness_coeff, plastic_ratio, delta_min, delta_max
      integer(c_int) :: delta_in_sigma
      real(c_double) :: tol
   end type egw_scene_c

   !> Mirror of the C struct egw_model_choice.
   type, bind(C) :: egw_model_choice_c
      integer(c_int) :: kind, n_sets, n_solves, hertz_relative_to_max, n_nodes
      real(c_double) :: error_bound, hertz_error, measured_error, mu_min, mu_max, x_min, x_max
   end type egw_model_choice_c

   public :: egw_scene_c, egw_model_choice_c

contains

   !> C: egw_scene_default (the embedded default scene of egw-table).
   subroutine egw_scene_default(s) bind(C, name="egw_scene_default")
      type(c_ptr), value, intent(in) :: s   !< C: `egw_scene *s` (filled with the defaults)
      type(egw_scene_c), pointer :: cs
      if (.not. c_associated(s)) return
      call c_f_pointer(s, cs)
      cs = to_c(default_scene_input())
   end subroutine egw_scene_default

   !> C: egw_scene_validate.
   function egw_scene_validate(s) result(stat) bind(C, name="egw_scene_validate")
      type(c_ptr), value, intent(in) :: s   !< C: `const egw_scene *s`
      integer(c_int) :: stat
      type(scene_input) :: input
      type(egw_error), allocatable :: error
      stat = get_scene(s, input)
      if (stat /= egw_ok) return
      call validate_scene_input(input, error)
      stat = settle(error)
   end function egw_scene_validate

   !> C: egw_scene_read: the file's &scene values replace those of *s (validated; *s
   !> unchanged on failure).
   function egw_scene_read(path, s) result(stat) bind(C, name="egw_scene_read")
      !> C: `const char *path` (NUL-terminated); `egw_scene *s` (out)
      type(c_ptr), value, intent(in) :: path, s
      integer(c_int) :: stat
      type(scene_input) :: input
      type(egw_scene_c), pointer :: cs
      type(egw_error), allocatable :: error
      character(len=:), allocatable :: fpath
      stat = require(path, "path")
      if (stat == egw_ok) stat = require(s, "s")
      if (stat /= egw_ok) return
      call c_f_pointer(s, cs)
      input = from_c(cs)
      call c_string(path, fpath)  ! its full length (egw_capi_utils)
      call read_scene_file(fpath, input, error)
      if (.not. allocated(error) .and. input%flow_pressure /= 0.0_dp) then
         ! the C struct has no field for it: refused rather than dropped
         call fatal_error(error, egw_invalid_parameter, "path = "//fpath// &
            & ": flow_pressure (or yield_stress) is not in the C struct egw_scene; set "// &
            & "egw_params.flow_pressure and build with egw_hysteresis_build (egw-table reads it)")
      end if
      stat = settle(error)
      if (stat == egw_ok) cs = to_c(input)
   end function egw_scene_read

   !> C: egw_scene_choose: the model choice; reason (nullable, reason_len bytes) gets
   !> the explanation, NUL-terminated and truncated.
   function egw_scene_choose(s, o, choice, reason, reason_len) result(stat) &
      & bind(C, name="egw_scene_choose")
      !> C: `const egw_scene *s`; `const egw_options *o` (solver options, NULL: the
      !> defaults); `egw_model_choice *choice` (out); `char *reason` (out)
      type(c_ptr), value, intent(in) :: s, o, choice, reason
      integer(c_int), value, intent(in) :: reason_len   !< C: `int reason_len`
      integer(c_int) :: stat
      type(contact_scene) :: scene
      type(model_choice) :: mc
      type(solver_options) :: options
      type(egw_error), allocatable :: error
      type(egw_model_choice_c), pointer :: cc
      stat = require(choice, "choice")
      if (stat == egw_ok) stat = resolved(s, scene)
      if (stat /= egw_ok) return
      call read_options(o, options)
      call choose_model(scene, options, mc, error)
      stat = settle(error)
      if (stat /= egw_ok) return
      call c_f_pointer(choice, cc)
      cc = choice_to_c(mc)
      if (c_associated(reason) .and. reason_len >= 1) &
         & stat = copy_to_c(mc%reason, reason, reason_len)
   end function egw_scene_choose

   !> C: egw_scene_build: choose, then build the chosen tables; *table receives a handle
   !> for EGW_CHOICE_TABLE, *universal for EGW_CHOICE_UNIVERSAL, both NULL otherwise.
   function egw_scene_build(s, o, choice, table, universal) result(stat) &
      & bind(C, name="egw_scene_build")
      !> C: `const egw_scene *s`; `const egw_options *o` (solver options, NULL: the
      !> defaults); `egw_model_choice *choice` (out); `egw_table *table` (out);
      !> `egw_universal *universal` (out)
      type(c_ptr), value, intent(in) :: s, o, choice, table, universal
      integer(c_int) :: stat
      type(contact_scene) :: scene
      type(model_choice) :: mc
      type(scene_tables) :: built
      type(solver_options) :: options
      type(egw_error), allocatable :: error
      type(egw_model_choice_c), pointer :: cc
      type(c_ptr), pointer :: th, uh
      type(force_table), pointer :: t
      type(universal_table), pointer :: u
      stat = require(choice, "choice")
      if (stat == egw_ok) stat = require(table, "table")
      if (stat == egw_ok) stat = require(universal, "universal")
      if (stat == egw_ok) stat = resolved(s, scene)
      if (stat /= egw_ok) return
      call read_options(o, options)
      call progress_begin("table build")
      call choose_model(scene, options, mc, error)
      if (.not. allocated(error)) call build_scene_tables(scene, mc, options, built, error, &
         & progress_count)
      call progress_end("table build")
      stat = settle(error)
      if (stat /= egw_ok) return
      call c_f_pointer(choice, cc)
      cc = choice_to_c(mc)
      cc%measured_error = built%measured_error
      cc%n_nodes = int(built%n_nodes, c_int)
      call c_f_pointer(table, th)
      call c_f_pointer(universal, uh)
      th = c_null_ptr
      uh = c_null_ptr
      select case (built%kind)
      case (choice_table)
         allocate (t)
         t = built%table
         th = c_loc(t)
      case (choice_universal)
         allocate (u)
         u = built%universal
         uh = c_loc(u)
      end select
   end function egw_scene_build

   ! ---------------------------------------------------------------- helpers

   integer(c_int) function get_scene(s, input) result(stat)
      type(c_ptr), intent(in) :: s
      type(scene_input), intent(out) :: input
      type(egw_scene_c), pointer :: cs
      stat = require(s, "s")
      if (stat /= egw_ok) return
      call c_f_pointer(s, cs)
      input = from_c(cs)
   end function get_scene

   integer(c_int) function resolved(s, scene) result(stat)
      type(c_ptr), intent(in) :: s
      type(contact_scene), intent(out) :: scene
      type(scene_input) :: input
      type(egw_error), allocatable :: error
      stat = get_scene(s, input)
      if (stat /= egw_ok) return
      call resolve_scene(input, scene, error)
      stat = settle(error)
   end function resolved

   pure function to_c(s) result(cs)
      type(scene_input), intent(in) :: s
      type(egw_scene_c) :: cs
      cs%model = int(s%model, c_int)
      cs%n_types = int(s%n_types, c_int)
      cs%radius = s%radius
      cs%radius_min = s%radius_min
      cs%radius_max = s%radius_max
      cs%modulus = s%modulus
      cs%poisson = s%poisson
      cs%effective_modulus = s%effective_modulus
      cs%sigma_min = s%sigma_min
      cs%sigma_max = s%sigma_max
      cs%mu = s%mu
      cs%summit_density = s%summit_density
      cs%summit_radius = s%summit_radius
      cs%psi = s%psi
      cs%hardness_coeff = s%hardness_coeff
      cs%plastic_ratio = s%plastic_ratio
      cs%delta_min = s%delta_min
      cs%delta_max = s%delta_max
      cs%delta_in_sigma = int(s%delta_in_sigma, c_int)
      cs%tol = s%tol
   end function to_c

   pure function from_c(cs) result(s)
      type(egw_scene_c), intent(in) :: cs
      type(scene_input) :: s
      s%model = int(cs%model)
      s%n_types = int(cs%n_types)
      s%radius = cs%radius
      s%radius_min = cs%radius_min
      s%radius_max = cs%radius_max
      s%modulus = cs%modulus
      s%poisson = cs%poisson
      s%effective_modulus = cs%effective_modulus
      s%sigma_min = cs%sigma_min
      s%sigma_max = cs%sigma_max
      s%mu = cs%mu
      s%summit_density = cs%summit_density
      s%summit_radius = cs%summit_radius
      s%psi = cs%psi
      s%hardness_coeff = cs%hardness_coeff
      s%plastic_ratio = cs%plastic_ratio
      s%delta_min = cs%delta_min
      s%delta_max = cs%delta_max
      s%delta_in_sigma = int(cs%delta_in_sigma)
      s%tol = cs%tol
   end function from_c

   pure function choice_to_c(mc) result(cc)
      type(model_choice), intent(in) :: mc
      type(egw_model_choice_c) :: cc
      cc%kind = int(mc%kind, c_int)
      cc%n_sets = int(mc%n_sets, c_int)
      cc%n_solves = int(mc%n_solves, c_int)
      cc%hertz_relative_to_max = merge(1_c_int, 0_c_int, mc%hertz_relative_to_max)
      cc%n_nodes = 0
      cc%error_bound = mc%error_bound
      cc%hertz_error = mc%hertz_error
      cc%measured_error = 0.0_dp
      cc%mu_min = mc%mu_min
      cc%mu_max = mc%mu_max
      cc%x_min = mc%x_min
      cc%x_max = mc%x_max
   end function choice_to_c

   !> C: egw_first_yield: the smooth sphere's first-yield overlap and impact speed under
   !> the flow-pressure cap (scene/impact_regime: closed forms); +HUGE where p_y = 0.
   function egw_first_yield(p, mass, delta_y, velocity_y) result(stat) &
      & bind(C, name="egw_first_yield")
      !> C: `const egw_params *p` (the contact's parameters); `double *delta_y` (out);
      !> `double *velocity_y` (out)
      type(c_ptr), value, intent(in) :: p, delta_y, velocity_y
      real(c_double), value, intent(in) :: mass   !< C: `double mass`
      integer(c_int) :: stat
      type(contact_params) :: params
      real(dp) :: d_y, v_y
      stat = read_params(p, params)
      if (stat == egw_ok) stat = check_positive("mass", mass)
      if (stat /= egw_ok) return
      if (params%flow_pressure > 0.0_dp) then
         d_y = first_yield_overlap(params)
         v_y = yield_speed(params, mass)
         if (.not. (ieee_is_finite(v_y) .and. v_y > 0.0_dp .and. d_y > 0.0_dp)) then
            stat = invalid("mass = "//format_real(mass)//": with flow_pressure, radius "// &
               & "and modulus the first-yield speed is not a positive double")
            return
         end if
      else
         d_y = huge(1.0_dp)   ! no bulk yield: never
         v_y = huge(1.0_dp)
      end if
      call put(delta_y, d_y)
      call put(velocity_y, v_y)
   end function egw_first_yield

end module egw_capi_scene
