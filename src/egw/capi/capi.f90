!> The C API (include/egw.h): the one layer of egw that touches iso_c_binding.
!> Each entry point converts C arguments, calls the Fortran API, and turns an
!> egw_error into a status code plus a per-thread last-error message.
module egw_capi
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_associated, c_f_pointer, &
      & c_null_ptr, c_funptr, c_null_funptr, c_f_procpointer, c_char, c_null_char
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_ok, status_message, format_real, tolerance_context
   use egw_params, only: contact_params, mu_from_summits, psi_from_hardness
   use egw_version, only: egw_version_number
   use egw_progress, only: set_progress
   use egw_rough_sphere, only: solver_options, solve_result, solve_contact, &
      & solve_contact_unload
   use egw_rough_profile, only: contact_profile, contact_profile_unload
   use egw_impact, only: restitution, time_step
   use egw_gauss, only: get_gauss_integral, get_gauss_integral_deriv
   use egw_ellip, only: get_ellipk, get_ellipe
   use egw_asperity, only: flat_pressure
   use egw_unloading, only: flat_pressure_unload
   ! (the Hertz module is not called egw_hertz, nor the restitution module egw_restitution:
   ! gfortran 12 resolves their procedures to a bind(C) routine whose label equals the
   ! module name)
   use egw_smooth_sphere, only: hertz_contact
   use egw_capi_utils, only: copy_to_c, copy_last_error, settle, require, invalid, &
      & check_nonneg, check_positive, check_count, put, put_settled, egw_params_c, &
      & egw_options_c, from_params, read_params, read_contact, put_result
   implicit none
   private

   abstract interface
      !> A special function of egw_gauss: value at order n and lower limit h.
      pure subroutine of_order(n, h, value, error)
         import :: dp, egw_error
         real(dp), intent(in) :: n, h
         real(dp), intent(out) :: value
         type(egw_error), allocatable, intent(out) :: error
      end subroutine of_order
      !> A complete elliptic integral of egw_ellip: value at modulus k.
      pure subroutine of_modulus(k, value, error)
         import :: dp, egw_error
         real(dp), intent(in) :: k
         real(dp), intent(out) :: value
         type(egw_error), allocatable, intent(out) :: error
      end subroutine of_modulus
      !> The C progress hook of egw_set_progress (include/egw.h).
      subroutine c_progress_hook(done, stage, user) bind(C)
         import :: c_double, c_char, c_ptr
         real(c_double), value, intent(in) :: done
         character(kind=c_char), intent(in) :: stage(*)
         type(c_ptr), value, intent(in) :: user
      end subroutine c_progress_hook
   end interface

   !> This thread's C progress hook and its user pointer (egw_set_progress): per thread,
   !> as egw_progress's hook that forwards to it (report_c).
   type(c_funptr), save :: c_hook = c_null_funptr
   type(c_ptr), save :: c_user = c_null_ptr
   !$omp threadprivate(c_hook, c_user)

contains

   !> C: egw_set_progress: this thread's progress hook (NULL: off) and its user pointer.
   subroutine egw_set_progress(hook, user) bind(C, name="egw_set_progress")
      !> egw_progress_fn: called with done in [0, 1], the stage and user (NULL: off)
      type(c_funptr), value, intent(in) :: hook
      type(c_ptr), value, intent(in) :: user   !< passed to the hook as given
      c_hook = hook
      c_user = user
      if (c_associated(hook)) then
         call set_progress(report_c)
      else
         call set_progress()
      end if
   end subroutine egw_set_progress

   !> egw_progress's hook on a thread with a C hook: done and the stage, NUL-terminated.
   subroutine report_c(done, stage)
      real(dp), intent(in) :: done
      character(len=*), intent(in) :: stage
      procedure(c_progress_hook), pointer :: hook
      character(kind=c_char, len=len(stage) + 1) :: text
      if (.not. c_associated(c_hook)) return
      call c_f_procpointer(c_hook, hook)
      text = stage//c_null_char
      call hook(real(done, c_double), text, c_user)
   end subroutine report_c

   !> 10000*major + 100*minor + patch.
   function egw_get_version() result(version) bind(C, name="egw_get_version")
      integer(c_int) :: version
      version = int(egw_version_number, c_int)
   end function egw_get_version

   !> C: egw_status_message (include/egw.h): the generic text of a status code.
   function egw_status_message(status, buf, buflen) result(stat) &
      & bind(C, name="egw_status_message")
      integer(c_int), value, intent(in) :: status   !< C: `int status`
      type(c_ptr), value, intent(in) :: buf   !< C: `char *buf` (out)
      integer(c_int), value, intent(in) :: buflen   !< C: `int buflen` (bytes at buf)
      integer(c_int) :: stat
      stat = copy_to_c(status_message(int(status)), buf, buflen)
   end function egw_status_message

   !> C: egw_last_error: this thread's message of the last failing call; returns the
   !> bytes it needs whole (length + 1), or minus a status (copy_last_error).
   function egw_last_error(buf, buflen) result(needed) bind(C, name="egw_last_error")
      type(c_ptr), value, intent(in) :: buf   !< C: `char *buf` (out)
      integer(c_int), value, intent(in) :: buflen   !< C: `int buflen` (bytes at buf)
      integer(c_int) :: needed
      needed = copy_last_error(buf, buflen)
   end function egw_last_error

   !> C: egw_params_default: fill an egw_params with the defaults.
   subroutine egw_params_default(p) bind(C, name="egw_params_default")
      type(c_ptr), value, intent(in) :: p   !< C: `egw_params *p` (filled with the defaults)
      type(egw_params_c), pointer :: cp
      if (.not. c_associated(p)) return
      call c_f_pointer(p, cp)
      cp = from_params(contact_params())
   end subroutine egw_params_default

   !> C: egw_params_validate: EGW_INVALID_PARAMETER naming the first bad field.
   function egw_params_validate(p) result(stat) bind(C, name="egw_params_validate")
      type(c_ptr), value, intent(in) :: p   !< C: `const egw_params *p` (the contact's parameters)
      integer(c_int) :: stat
      type(contact_params) :: params
      stat = read_params(p, params)
   end function egw_params_validate

   !> C: egw_mu_from_summits: mu = (8/3) eta sigma sqrt(2 R beta).
   function egw_mu_from_summits(summit_density, summit_radius, sigma, radius, mu) &
      & result(stat) bind(C, name="egw_mu_from_summits")
      !> C: `double summit_density`; `double summit_radius`; `double sigma`; `double radius`
      real(c_double), value, intent(in) :: summit_density, summit_radius, sigma, radius
      type(c_ptr), value, intent(in) :: mu   !< C: `double *mu` (out)
      integer(c_int) :: stat
      real(dp) :: value
      stat = check_nonneg("summit_density", summit_density)
      if (stat == egw_ok) stat = check_nonneg("summit_radius", summit_radius)
      if (stat == egw_ok) stat = check_nonneg("sigma", sigma)
      if (stat == egw_ok) stat = check_nonneg("radius", radius)
      if (stat == egw_ok) stat = require(mu, "mu")
      if (stat /= egw_ok) return
      value = mu_from_summits(summit_density, summit_radius, sigma, radius)
      if (.not. ieee_is_finite(value)) then
         stat = invalid("mu = (8/3) eta sigma sqrt(2 R beta) exceeds the largest double: " &
            & //"summit_density = "//format_real(summit_density)//", sigma = " &
            & //format_real(sigma))
         return
      end if
      call put(mu, value)
   end function egw_mu_from_summits

   !> C: egw_psi_from_hardness (include/egw.h).
   function egw_psi_from_hardness(modulus, hardness, hardness_coeff, sigma, summit_radius, &
      & psi) result(stat) bind(C, name="egw_psi_from_hardness")
      !> C: `double modulus`; `double hardness`; `double hardness_coeff`; `double sigma`;
      !> `double summit_radius`
      real(c_double), value, intent(in) :: modulus, hardness, hardness_coeff, sigma, &
         & summit_radius
      type(c_ptr), value, intent(in) :: psi   !< C: `double *psi` (out)
      integer(c_int) :: stat
      real(dp) :: value
      stat = check_positive("modulus", modulus)
      if (stat == egw_ok) stat = check_positive("hardness", hardness)
      if (stat == egw_ok) stat = check_nonneg("sigma", sigma)
      if (stat == egw_ok) stat = check_positive("summit_radius", summit_radius)
      if (stat == egw_ok .and. .not. (hardness_coeff > 0.0_dp .and. hardness_coeff < 1.0_dp)) &
         & then
         stat = invalid("hardness_coeff = "//format_real(hardness_coeff)// &
            & ": K must lie in (0, 1)")
      end if
      if (stat == egw_ok) stat = require(psi, "psi")
      if (stat /= egw_ok) return
      value = psi_from_hardness(modulus, hardness, hardness_coeff, sigma, summit_radius)
      if (.not. ieee_is_finite(value)) then
         stat = invalid("psi = E/(K H) sqrt(sigma/beta) overflows: modulus/hardness = "// &
            & format_real(modulus/hardness)//", sigma/summit_radius = "// &
            & format_real(sigma/summit_radius))
         return
      end if
      call put(psi, value)
   end function egw_psi_from_hardness

   !> C: egw_gauss_integral: F_n(h).
   function egw_gauss_integral(n, h, value) result(stat) bind(C, name="egw_gauss_integral")
      real(c_double), value, intent(in) :: n, h   !< C: `double n`; `double h`
      type(c_ptr), value, intent(in) :: value   !< C: `double *value` (out)
      integer(c_int) :: stat
      stat = order_c(get_gauss_integral, n, h, value)
   end function egw_gauss_integral

   !> C: egw_gauss_integral_deriv: dF_n/dh.
   function egw_gauss_integral_deriv(n, h, value) result(stat) &
      & bind(C, name="egw_gauss_integral_deriv")
      real(c_double), value, intent(in) :: n, h   !< C: `double n`; `double h`
      type(c_ptr), value, intent(in) :: value   !< C: `double *value` (out)
      integer(c_int) :: stat
      stat = order_c(get_gauss_integral_deriv, n, h, value)
   end function egw_gauss_integral_deriv

   !> C: egw_ellipk: K(k) of modulus k.
   function egw_ellipk(k, value) result(stat) bind(C, name="egw_ellipk")
      real(c_double), value, intent(in) :: k   !< C: `double k`
      type(c_ptr), value, intent(in) :: value   !< C: `double *value` (out)
      integer(c_int) :: stat
      stat = modulus_c(get_ellipk, k, value)
   end function egw_ellipk

   !> C: egw_ellipe: E(k) of modulus k.
   function egw_ellipe(k, value) result(stat) bind(C, name="egw_ellipe")
      real(c_double), value, intent(in) :: k   !< C: `double k`
      type(c_ptr), value, intent(in) :: value   !< C: `double *value` (out)
      integer(c_int) :: stat
      stat = modulus_c(get_ellipe, k, value)
   end function egw_ellipe

   !> C: egw_flat_pressure: p_G(d) of the rough flat.
   function egw_flat_pressure(p, separation, pressure) result(stat) &
      & bind(C, name="egw_flat_pressure")
      !> C: `const egw_params *p` (the contact's parameters); `double *pressure` (out)
      type(c_ptr), value, intent(in) :: p, pressure
      real(c_double), value, intent(in) :: separation   !< C: `double separation`
      integer(c_int) :: stat
      stat = require(pressure, "pressure")
      if (stat /= egw_ok) return
      stat = flat_pressure_c(p, separation, pressure, pressure, .false.)
   end function egw_flat_pressure

   !> C: egw_flat_pressure_deriv: p_G(d) and dp_G/dd.
   function egw_flat_pressure_deriv(p, separation, pressure, dpressure) result(stat) &
      & bind(C, name="egw_flat_pressure_deriv")
      !> C: `const egw_params *p` (the contact's parameters); `double *pressure` (out);
      !> `double *dpressure` (out)
      type(c_ptr), value, intent(in) :: p, pressure, dpressure
      real(c_double), value, intent(in) :: separation   !< C: `double separation`
      integer(c_int) :: stat
      stat = require(pressure, "pressure")
      if (stat == egw_ok) stat = require(dpressure, "dpressure")
      if (stat /= egw_ok) return
      stat = flat_pressure_c(p, separation, pressure, dpressure, .true.)
   end function egw_flat_pressure_deriv

   !> C: egw_flat_pressure_unload (include/egw.h). dpressure may be NULL.
   function egw_flat_pressure_unload(p, separation, separation_min, pressure, dpressure) &
      & result(stat) bind(C, name="egw_flat_pressure_unload")
      !> C: `const egw_params *p` (the contact's parameters); `double *pressure` (out);
      !> `double *dpressure` (out)
      type(c_ptr), value, intent(in) :: p, pressure, dpressure
      !> C: `double separation`; `double separation_min`
      real(c_double), value, intent(in) :: separation, separation_min
      integer(c_int) :: stat
      type(contact_params) :: params
      type(egw_error), allocatable :: error
      real(dp) :: pg, dpg
      stat = require(pressure, "pressure")
      if (stat == egw_ok) stat = read_params(p, params)
      if (stat /= egw_ok) return
      pg = 0.0_dp
      dpg = 0.0_dp
      call flat_pressure_unload(params, separation, separation_min, pg, dpg, error)
      stat = settle(error)
      if (stat /= egw_ok) return
      call put(pressure, pg)
      call put(dpressure, dpg)
   end function egw_flat_pressure_unload

   !> C: egw_hertz: force, stiffness and contact radius of smooth spheres.
   function hertz_c(p, delta, force, stiffness, contact_radius) result(stat) &
      & bind(C, name="egw_hertz")
      !> C: `const egw_params *p` (the contact's parameters); `double *force` (out); `double
      !> *stiffness` (out); `double *contact_radius` (out)
      type(c_ptr), value, intent(in) :: p, force, stiffness, contact_radius
      real(c_double), value, intent(in) :: delta   !< C: `double delta`
      integer(c_int) :: stat
      type(contact_params) :: params
      type(egw_error), allocatable :: error
      real(dp) :: f, k, a
      stat = read_params(p, params)
      if (stat /= egw_ok) return
      call hertz_contact(params, delta, f, k, a, error)
      stat = settle(error)
      if (stat /= egw_ok) return
      call put(force, f)
      call put(stiffness, k)
      call put(contact_radius, a)
   end function hertz_c

   !> C: egw_options_default: fill an egw_options with the defaults.
   subroutine egw_options_default(o) bind(C, name="egw_options_default")
      type(c_ptr), value, intent(in) :: o   !< C: `egw_options *o` (filled with the defaults)
      type(egw_options_c), pointer :: co
      type(solver_options) :: defaults
      if (.not. c_associated(o)) return
      call c_f_pointer(o, co)
      co = egw_options_c(n_radial=int(defaults%n_radial, c_int), rel_tol=defaults%rel_tol, &
         & max_iter=int(defaults%max_iter, c_int), method=int(defaults%method, c_int), &
         & n_threads=int(defaults%n_threads, c_int))
   end subroutine egw_options_default

   !> C: egw_solve: the rough-sphere solve at one overlap (include/egw.h).
   function egw_solve(p, o, delta, res) result(stat) bind(C, name="egw_solve")
      !> C: `const egw_params *p` (the contact's parameters); `const egw_options *o` (solver
      !> options, NULL: the defaults); `egw_result *res` (out)
      type(c_ptr), value, intent(in) :: p, o, res
      real(c_double), value, intent(in) :: delta   !< C: `double delta`
      integer(c_int) :: stat
      stat = solve_c(p, o, delta, .false., 0.0_dp, res)
   end function egw_solve

   !> C: egw_solve_unload: the unloading solve at delta after a maximum delta_max.
   function egw_solve_unload(p, o, delta, delta_max, res) result(stat) &
      & bind(C, name="egw_solve_unload")
      !> C: `const egw_params *p` (the contact's parameters); `const egw_options *o` (solver
      !> options, NULL: the defaults); `egw_result *res` (out)
      type(c_ptr), value, intent(in) :: p, o, res
      !> C: `double delta`; `double delta_max`
      real(c_double), value, intent(in) :: delta, delta_max
      integer(c_int) :: stat
      stat = solve_c(p, o, delta, .true., delta_max, res)
   end function egw_solve_unload

   !> C: egw_restitution: the coefficient of restitution of an impact.
   function egw_restitution(p, o, mass, velocity, e) result(stat) &
      & bind(C, name="egw_restitution")
      !> C: `const egw_params *p` (the contact's parameters); `const egw_options *o` (solver
      !> options, NULL: the defaults); `double *e` (out)
      type(c_ptr), value, intent(in) :: p, o, e
      real(c_double), value, intent(in) :: mass, velocity   !< C: `double mass`; `double velocity`
      integer(c_int) :: stat
      stat = require(e, "e")
      if (stat /= egw_ok) return
      stat = restitution_c(p, o, mass, velocity, e, c_null_ptr, c_null_ptr, c_null_ptr)
   end function egw_restitution

   !> C: egw_restitution_energy: the same with the work of loading and the dissipated energy.
   function egw_restitution_energy(p, o, mass, velocity, e, w_load, w_dissipated) &
      & result(stat) bind(C, name="egw_restitution_energy")
      !> C: `const egw_params *p` (the contact's parameters); `const egw_options *o` (solver
      !> options, NULL: the defaults); `double *e` (out); `double *w_load` (out); `double
      !> *w_dissipated` (out)
      type(c_ptr), value, intent(in) :: p, o, e, w_load, w_dissipated
      real(c_double), value, intent(in) :: mass, velocity   !< C: `double mass`; `double velocity`
      integer(c_int) :: stat
      stat = restitution_c(p, o, mass, velocity, e, w_load, w_dissipated, c_null_ptr)
   end function egw_restitution_energy

   !> C: egw_restitution_overlap: e and the deepest overlap delta_m of the impact.
   function egw_restitution_overlap(p, o, mass, velocity, e, max_overlap) result(stat) &
      & bind(C, name="egw_restitution_overlap")
      !> C: `const egw_params *p` (the contact's parameters); `const egw_options *o` (solver
      !> options, NULL: the defaults); `double *e` (out); `double *max_overlap` (out)
      type(c_ptr), value, intent(in) :: p, o, e, max_overlap
      real(c_double), value, intent(in) :: mass, velocity   !< C: `double mass`; `double velocity`
      integer(c_int) :: stat
      stat = restitution_c(p, o, mass, velocity, e, c_null_ptr, c_null_ptr, max_overlap)
   end function egw_restitution_overlap

   !> C: egw_time_step: the contact duration and the largest Verlet step for a tolerance.
   function egw_time_step(p, o, mass, velocity, tolerance, duration, step) result(stat) &
      & bind(C, name="egw_time_step")
      !> C: `const egw_params *p` (the contact's parameters); `const egw_options *o` (solver
      !> options, NULL: the defaults); `double *duration` (out); `double *time_step` (out)
      type(c_ptr), value, intent(in) :: p, o, duration, step
      !> C: `double mass`; `double velocity`; `double tolerance`
      real(c_double), value, intent(in) :: mass, velocity, tolerance
      integer(c_int) :: stat
      type(contact_params) :: params
      type(solver_options) :: options
      type(egw_error), allocatable :: error
      real(dp) :: t_c, dt
      stat = read_contact(p, o, params, options)
      if (stat /= egw_ok) return
      t_c = 0.0_dp
      dt = 0.0_dp
      call time_step(params, options, mass, velocity, tolerance, t_c, dt, error)
      if (allocated(error)) call tolerance_context(error, "time step (its restitution)", &
         & options%rel_tol, options%rel_tol)
      stat = settle(error)
      if (stat /= egw_ok) return
      call put(duration, t_c)
      call put(step, dt)
   end function egw_time_step

   !> C: egw_profile: pressure and deflection of the solved contact at given radii.
   function egw_profile(p, o, delta, n, r, pressure, deflection) result(stat) &
      & bind(C, name="egw_profile")
      !> C: `const egw_params *p` (the contact's parameters); `const egw_options *o` (solver
      !> options, NULL: the defaults); `const double *r`; `double *pressure` (out); `double
      !> *deflection` (out)
      type(c_ptr), value, intent(in) :: p, o, r, pressure, deflection
      real(c_double), value, intent(in) :: delta   !< C: `double delta`
      integer(c_int), value, intent(in) :: n   !< C: `int n`
      integer(c_int) :: stat
      stat = profile_c(p, o, delta, delta, .false., n, r, pressure, deflection)
   end function egw_profile

   !> C: egw_profile_unload: pressure and deflection of the unloading (reloading) solve
   !> at delta after the largest overlap delta_max, at given radii.
   function egw_profile_unload(p, o, delta, delta_max, n, r, pressure, deflection) &
      & result(stat) bind(C, name="egw_profile_unload")
      !> C: `const egw_params *p`; `const egw_options *o` (NULL: the defaults); `const
      !> double *r`; `double *pressure` (out); `double *deflection` (out)
      type(c_ptr), value, intent(in) :: p, o, r, pressure, deflection
      !> C: `double delta`; `double delta_max`
      real(c_double), value, intent(in) :: delta, delta_max
      integer(c_int), value, intent(in) :: n   !< C: `int n`
      integer(c_int) :: stat
      stat = profile_c(p, o, delta, delta_max, .true., n, r, pressure, deflection)
   end function egw_profile_unload

   ! ---------------------------------------------------------------- helpers

   !> egw_profile's and egw_profile_unload's check, call and copy: contact_profile at delta,
   !> or (unloading) contact_profile_unload at delta after delta_max; pressure and
   !> deflection untouched on failure.
   integer(c_int) function profile_c(p, o, delta, delta_max, unloading, n, r, pressure, &
      & deflection) result(stat)
      type(c_ptr), intent(in) :: p, o, r, pressure, deflection
      real(c_double), intent(in) :: delta, delta_max
      logical, intent(in) :: unloading
      integer(c_int), intent(in) :: n
      type(contact_params) :: params
      type(solver_options) :: options
      real(c_double), pointer :: cr(:), cp(:), cw(:)
      real(dp), allocatable :: pr(:), w(:)
      type(egw_error), allocatable :: error
      stat = check_count(n)
      if (stat == egw_ok) stat = read_contact(p, o, params, options)
      if (stat == egw_ok) stat = require(r, "r")
      if (stat == egw_ok) stat = require(pressure, "pressure")
      if (stat == egw_ok) stat = require(deflection, "deflection")
      if (stat /= egw_ok) return
      call c_f_pointer(r, cr, [n])
      call c_f_pointer(pressure, cp, [n])
      call c_f_pointer(deflection, cw, [n])
      allocate (pr(n), w(n))
      if (unloading) then
         call contact_profile_unload(params, options, delta, delta_max, cr, pr, w, error)
      else
         call contact_profile(params, options, delta, cr, pr, w, error)
      end if
      stat = settle(error)
      if (stat /= egw_ok) return
      cp = pr
      cw = w
   end function profile_c

   !> Restitution with its energies into nullable double* (NULL: not wanted); all
   !> outputs untouched on failure.
   integer(c_int) function restitution_c(p, o, mass, velocity, e, w_load, w_dissipated, &
      & max_overlap) result(stat)
      type(c_ptr), intent(in) :: p, o, e, w_load, w_dissipated, max_overlap
      real(c_double), intent(in) :: mass, velocity
      type(contact_params) :: params
      type(solver_options) :: options
      type(egw_error), allocatable :: error
      real(dp) :: coefficient, dissipated, work, delta_m
      stat = read_contact(p, o, params, options)
      if (stat /= egw_ok) return
      coefficient = 1.0_dp
      dissipated = 0.0_dp
      work = 0.0_dp
      delta_m = 0.0_dp
      call restitution(params, options, mass, velocity, coefficient, dissipated, error, &
         & work_load=work, max_overlap=delta_m)
      if (allocated(error)) call tolerance_context(error, "restitution", options%rel_tol, &
         & options%rel_tol)
      stat = settle(error)
      if (stat /= egw_ok) return
      call put(e, coefficient)
      call put(w_load, work)
      call put(w_dissipated, dissipated)
      call put(max_overlap, delta_m)
   end function restitution_c

   !> Rough-flat pressure p_G at separation into pressure, and dp_G/dd into dpressure
   !> when want_deriv (both not NULL then); outputs untouched on failure.
   integer(c_int) function flat_pressure_c(p, separation, pressure, dpressure, want_deriv) &
      & result(stat)
      type(c_ptr), intent(in) :: p, pressure, dpressure
      real(c_double), intent(in) :: separation
      logical, intent(in) :: want_deriv
      type(contact_params) :: params
      type(egw_error), allocatable :: error
      real(dp) :: pg, dpg
      stat = read_params(p, params)
      if (stat /= egw_ok) return
      call flat_pressure(params, separation, pg, dpg, error)
      stat = settle(error)
      if (stat /= egw_ok) return
      call put(pressure, pg)
      if (want_deriv) call put(dpressure, dpg)
   end function flat_pressure_c

   !> The loading (unloading = .false.) or unloading solve at delta, the result at res
   !> (checked first; untouched on any failure, egw.h).
   integer(c_int) function solve_c(p, o, delta, unloading, delta_max, res) result(stat)
      type(c_ptr), intent(in) :: p, o, res
      real(c_double), intent(in) :: delta, delta_max
      logical, intent(in) :: unloading
      type(contact_params) :: params
      type(solver_options) :: options
      type(solve_result) :: result
      type(egw_error), allocatable :: error
      stat = require(res, "res")
      if (stat == egw_ok) stat = read_contact(p, o, params, options)
      if (stat /= egw_ok) return
      if (unloading) then
         call solve_contact_unload(params, options, delta, delta_max, result, error)
      else
         call solve_contact(params, options, delta, result, error)
      end if
      stat = settle(error)
      if (stat == egw_ok) call put_result(res, result)
   end function solve_c

   !> A function of order and limit (egw_gauss) into the double* value (checked first).
   integer(c_int) function order_c(special, n, h, value) result(stat)
      procedure(of_order) :: special
      real(dp), intent(in) :: n, h
      type(c_ptr), intent(in) :: value
      type(egw_error), allocatable :: error
      real(dp) :: f
      stat = require(value, "value")
      if (stat /= egw_ok) return
      call special(n, h, f, error)
      stat = put_settled(value, f, error)
   end function order_c

   !> A function of the modulus (egw_ellip) into the double* value (checked first).
   integer(c_int) function modulus_c(special, k, value) result(stat)
      procedure(of_modulus) :: special
      real(dp), intent(in) :: k
      type(c_ptr), intent(in) :: value
      type(egw_error), allocatable :: error
      real(dp) :: f
      stat = require(value, "value")
      if (stat /= egw_ok) return
      call special(k, f, error)
      stat = put_settled(value, f, error)
   end function modulus_c

end module egw_capi
