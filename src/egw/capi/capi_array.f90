!> The array entry points of the C API (include/egw.h, "Array kernels"): each evaluates n
!> points in one call, every input read with its own stride (0 = one value for all points,
!> 1 = one per point), the parameters too. A failing point either stops the call with a
!> message naming its index (EGW_ARRAY_RAISE) or gets NaN outputs (EGW_ARRAY_NAN). Solves
!> and impacts run their points over OpenMP threads, each solve single-threaded inside.
module egw_capi_array
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_associated, c_f_pointer, &
      & c_loc, c_char, c_null_ptr
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
   !$ use omp_lib, only: omp_get_max_threads, omp_get_num_procs
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_ok, egw_invalid_argument, egw_out_of_range, &
      & fatal_error, format_real, int_str
   use egw_params, only: contact_params, validate_params
   use egw_rough_sphere, only: solver_options, solve_result, solve_contact, solve_contact_unload
   use egw_impact, only: restitution, time_step
   use egw_gauss, only: get_gauss_integral, get_gauss_integral_deriv
   use egw_asperity, only: flat_pressure
   use egw_unloading, only: flat_pressure_unload
   use egw_smooth_sphere, only: hertz_force, hertz_stiffness, hertz_contact_radius
   use egw_capi_utils, only: settle, require, invalid, failure, check_count, double_array, &
      & egw_params_c, egw_result_c, to_params, read_options, copy_last_error
   implicit none
   private

   !> flags of every array entry point (include/egw.h)
   integer(c_int), parameter :: array_raise = 0, array_nan = 1

   !> The parameters of the points: one egw_params for all (stride 0, validated once) or
   !> one per point (stride 1, each validated with its point).
   type :: params_view
      type(egw_params_c), pointer :: cp(:) => null()
      integer :: stride = 0
      type(contact_params) :: shared
   end type params_view

   !> n points of one evaluator: run computes point i (from 0) into the outputs, fail sets
   !> them to NaN. Inputs and outputs are pointers into the caller's arrays; the points
   !> write disjoint elements, so they may run on any thread.
   type, abstract :: point_task
      type(params_view) :: params
   contains
      procedure(run_point), deferred :: run
      procedure(fail_point), deferred :: fail
   end type point_task

   abstract interface
      subroutine run_point(self, i, params, error)
         import :: point_task, contact_params, egw_error
         class(point_task), intent(in) :: self
         integer, intent(in) :: i
         type(contact_params), intent(in) :: params
         type(egw_error), allocatable, intent(out) :: error
      end subroutine run_point
      subroutine fail_point(self, i)
         import :: point_task
         class(point_task), intent(in) :: self
         integer, intent(in) :: i
      end subroutine fail_point
   end interface

   !> Hertz: force, stiffness, contact radius at delta.
   type, extends(point_task) :: hertz_task
      real(c_double), pointer :: delta(:) => null()
      integer :: delta_stride = 0
      real(c_double), pointer :: force(:) => null(), stiffness(:) => null(), &
         & contact_radius(:) => null()
      !> points already done by hertz_shared (allocated only by it)
      logical, allocatable :: done(:)
   contains
      procedure :: run => hertz_run
      procedure :: fail => hertz_fail
   end type hertz_task

   !> Rough flat: p_G(d) and dp_G/dd, or the unloading p_G,u(d, d_min) when d_min given.
   type, extends(point_task) :: flat_task
      real(c_double), pointer :: separation(:) => null(), separation_min(:) => null()
      integer :: separation_stride = 0, separation_min_stride = 0
      real(c_double), pointer :: pressure(:) => null(), dpressure(:) => null()
   contains
      procedure :: run => flat_run
      procedure :: fail => flat_fail
   end type flat_task

   !> F_n(h) and dF_n/dh (parameters unused).
   type, extends(point_task) :: gauss_task
      real(c_double), pointer :: order(:) => null(), h(:) => null()
      integer :: order_stride = 0, h_stride = 0
      real(c_double), pointer :: value(:) => null(), derivative(:) => null()
   contains
      procedure :: run => gauss_run
      procedure :: fail => gauss_fail
   end type gauss_task

   !> Solves: loading at delta, or unloading after delta_max when delta_max given.
   type, extends(point_task) :: solve_task
      type(solver_options) :: options
      real(c_double), pointer :: delta(:) => null(), delta_max(:) => null()
      integer :: delta_stride = 0, delta_max_stride = 0
      type(egw_result_c), pointer :: res(:) => null()
   contains
      procedure :: run => solve_run
      procedure :: fail => solve_fail
   end type solve_task

   !> Impacts of mass and velocity: restitution (e, energies, delta_m) or, when
   !> want_time_step, the contact duration and Verlet step for tolerance.
   type, extends(point_task) :: impact_task
      type(solver_options) :: options
      real(c_double), pointer :: mass(:) => null(), velocity(:) => null()
      integer :: mass_stride = 0, velocity_stride = 0
      logical :: want_time_step = .false.
      real(dp) :: tolerance = 0.0_dp
      real(c_double), pointer :: e(:) => null(), w_load(:) => null(), &
         & w_dissipated(:) => null(), max_overlap(:) => null()
      real(c_double), pointer :: duration(:) => null(), step(:) => null()
   contains
      procedure :: run => impact_run
      procedure :: fail => impact_fail
   end type impact_task

   interface
      !> The scalar C entry of capi_table.f90 (its module keeps it private): the array form
      !> calls it per point, so the two agree by construction.
      function universal_eval_c(h, p, delta, force, stiffness) result(stat) &
         & bind(C, name="egw_universal_eval")
         import :: c_ptr, c_double, c_int
         type(c_ptr), value, intent(in) :: h, p, force, stiffness
         real(c_double), value, intent(in) :: delta
         integer(c_int) :: stat
      end function universal_eval_c
   end interface

contains

   ! ------------------------------------------------------------ entry points

   !> C: egw_universal_eval_array (include/egw.h).
   function egw_universal_eval_array(u, p, p_stride, n, delta, delta_stride, force, &
      & stiffness, flags, n_failed) result(stat) bind(C, name="egw_universal_eval_array")
      !> C: `egw_universal u`; `const egw_params *p` (the contact's parameters); `const
      !> double *delta`; `double *force` (out); `double *stiffness` (out); `int *n_failed`
      !> (failed points, may be NULL)
      type(c_ptr), value, intent(in) :: u, p, delta, force, stiffness, n_failed
      !> C: `int p_stride` (elements between points); `int n`; `int delta_stride` (elements
      !> between points); `int flags` (EGW_ARRAY_RAISE or EGW_ARRAY_NAN)
      integer(c_int), value, intent(in) :: p_stride, n, delta_stride, flags
      integer(c_int) :: stat
      real(c_double), pointer :: d(:), f(:), k(:)
      type(egw_params_c), pointer :: cp(:)
      real(c_double), target :: fi, ki
      character(len=:), allocatable :: message
      integer :: i, failed, ds
      logical :: outside
      stat = check_count(n)
      if (stat == egw_ok) stat = check_flags(flags)
      if (stat == egw_ok) stat = check_stride("p_stride", p_stride)
      if (stat == egw_ok) stat = require(u, "u")
      if (stat == egw_ok) stat = require(p, "p")
      if (stat == egw_ok) stat = open_input(delta, "delta", delta_stride, n, d, ds)
      if (stat /= egw_ok) return
      call c_f_pointer(p, cp, [extent(n, p_stride)])
      f => double_array(force, n)
      k => double_array(stiffness, n)
      failed = 0
      outside = .false.
      do i = 0, n - 1
         fi = ieee_value(1.0_dp, ieee_quiet_nan)
         ki = fi
         stat = universal_eval_c(u, c_loc(cp(1 + i*p_stride)), d(1 + i*ds), c_loc(fi), &
            & c_loc(ki))
         if (stat == egw_out_of_range) outside = .true.
         if (stat /= egw_ok .and. stat /= egw_out_of_range) then
            if (flags == array_raise) then
               call last_error_text(message)
               stat = failure(int(stat), "point "//int_str(i)//": "//message)
               return
            end if
            failed = failed + 1
         end if
         if (associated(f)) f(i + 1) = fi
         if (associated(k)) k(i + 1) = ki
      end do
      call put_int(n_failed, failed)
      stat = egw_ok
      if (outside) stat = failure(egw_out_of_range, "some points lie outside the table " &
         & //"(extrapolated above x_max, NaN where mu is outside it)")
   end function egw_universal_eval_array

   !> C: egw_hertz_array (include/egw.h).
   function egw_hertz_array(p, p_stride, n, delta, delta_stride, force, stiffness, &
      & contact_radius, flags, n_failed) result(stat) bind(C, name="egw_hertz_array")
      !> C: `const egw_params *p` (the contact's parameters); `const double *delta`; `double
      !> *force` (out); `double *stiffness` (out); `double *contact_radius` (out); `int
      !> *n_failed` (failed points, may be NULL)
      type(c_ptr), value, intent(in) :: p, delta, force, stiffness, contact_radius, n_failed
      !> C: `int p_stride` (elements between points); `int n`; `int delta_stride` (elements
      !> between points); `int flags` (EGW_ARRAY_RAISE or EGW_ARRAY_NAN)
      integer(c_int), value, intent(in) :: p_stride, n, delta_stride, flags
      integer(c_int) :: stat
      type(hertz_task) :: task
      stat = open_common(n, flags, p, p_stride, task%params)
      if (stat == egw_ok) stat = open_input(delta, "delta", delta_stride, n, task%delta, &
         & task%delta_stride)
      if (stat /= egw_ok) return
      task%force => double_array(force, n)
      task%stiffness => double_array(stiffness, n)
      task%contact_radius => double_array(contact_radius, n)
      if (p_stride == 0) then
         call hertz_shared(task, int(n))
         if (all(task%done)) then
            call put_int(n_failed, 0)
            return
         end if
      end if
      stat = run_points(task, int(n), flags, n_failed, 0)
   end function egw_hertz_array

   !> C: egw_flat_pressure_array (include/egw.h).
   function egw_flat_pressure_array(p, p_stride, n, separation, separation_stride, pressure, &
      & dpressure, flags, n_failed) result(stat) bind(C, name="egw_flat_pressure_array")
      !> C: `const egw_params *p` (the contact's parameters); `const double *separation`;
      !> `double *pressure` (out); `double *dpressure` (out); `int *n_failed` (failed
      !> points, may be NULL)
      type(c_ptr), value, intent(in) :: p, separation, pressure, dpressure, n_failed
      !> C: `int p_stride` (elements between points); `int n`; `int separation_stride`
      !> (elements between points); `int flags` (EGW_ARRAY_RAISE or EGW_ARRAY_NAN)
      integer(c_int), value, intent(in) :: p_stride, n, separation_stride, flags
      integer(c_int) :: stat
      type(flat_task) :: task
      stat = open_common(n, flags, p, p_stride, task%params)
      if (stat == egw_ok) stat = open_input(separation, "separation", separation_stride, n, &
         & task%separation, task%separation_stride)
      if (stat /= egw_ok) return
      task%pressure => double_array(pressure, n)
      task%dpressure => double_array(dpressure, n)
      stat = run_points(task, int(n), flags, n_failed, 0)
   end function egw_flat_pressure_array

   !> C: egw_flat_pressure_unload_array (include/egw.h).
   function egw_flat_pressure_unload_array(p, p_stride, n, separation, separation_stride, &
      & separation_min, separation_min_stride, pressure, dpressure, flags, n_failed) &
      & result(stat) bind(C, name="egw_flat_pressure_unload_array")
      !> C: `const egw_params *p` (the contact's parameters); `const double *separation`;
      !> `const double *separation_min`; `double *pressure` (out); `double *dpressure`
      !> (out); `int *n_failed` (failed points, may be NULL)
      type(c_ptr), value, intent(in) :: p, separation, separation_min, pressure, dpressure, &
         & n_failed
      !> C: `int p_stride` (elements between points); `int n`; `int separation_stride`
      !> (elements between points); `int separation_min_stride` (elements between points);
      !> `int flags` (EGW_ARRAY_RAISE or EGW_ARRAY_NAN)
      integer(c_int), value, intent(in) :: p_stride, n, separation_stride, &
         & separation_min_stride, flags
      integer(c_int) :: stat
      type(flat_task) :: task
      stat = open_common(n, flags, p, p_stride, task%params)
      if (stat == egw_ok) stat = open_input(separation, "separation", separation_stride, n, &
         & task%separation, task%separation_stride)
      if (stat == egw_ok) stat = open_input(separation_min, "separation_min", &
         & separation_min_stride, n, task%separation_min, task%separation_min_stride)
      if (stat /= egw_ok) return
      task%pressure => double_array(pressure, n)
      task%dpressure => double_array(dpressure, n)
      stat = run_points(task, int(n), flags, n_failed, 0)
   end function egw_flat_pressure_unload_array

   !> C: egw_gauss_integral_array (include/egw.h).
   function egw_gauss_integral_array(n, order, order_stride, h, h_stride, value, derivative, &
      & flags, n_failed) result(stat) bind(C, name="egw_gauss_integral_array")
      !> C: `const double *order`; `const double *h`; `double *value` (out); `double
      !> *derivative` (out); `int *n_failed` (failed points, may be NULL)
      type(c_ptr), value, intent(in) :: order, h, value, derivative, n_failed
      !> C: `int n`; `int order_stride` (elements between points); `int h_stride` (elements
      !> between points); `int flags` (EGW_ARRAY_RAISE or EGW_ARRAY_NAN)
      integer(c_int), value, intent(in) :: n, order_stride, h_stride, flags
      integer(c_int) :: stat
      type(gauss_task) :: task
      stat = check_count(n)
      if (stat == egw_ok) stat = check_flags(flags)
      if (stat == egw_ok) stat = open_input(order, "order", order_stride, n, task%order, &
         & task%order_stride)
      if (stat == egw_ok) stat = open_input(h, "h", h_stride, n, task%h, task%h_stride)
      if (stat /= egw_ok) return
      task%value => double_array(value, n)
      task%derivative => double_array(derivative, n)
      stat = run_points(task, int(n), flags, n_failed, 0)
   end function egw_gauss_integral_array

   !> C: egw_solve_array (include/egw.h).
   function egw_solve_array(p, p_stride, o, n, delta, delta_stride, delta_max, &
      & delta_max_stride, res, flags, n_failed) result(stat) bind(C, name="egw_solve_array")
      !> C: `const egw_params *p` (the contact's parameters); `const egw_options *o` (solver
      !> options, NULL: the defaults); `const double *delta`; `const double *delta_max`;
      !> `egw_result *res` (out); `int *n_failed` (failed points, may be NULL)
      type(c_ptr), value, intent(in) :: p, o, delta, delta_max, res, n_failed
      !> C: `int p_stride` (elements between points); `int n`; `int delta_stride` (elements
      !> between points); `int delta_max_stride` (elements between points); `int flags`
      !> (EGW_ARRAY_RAISE or EGW_ARRAY_NAN)
      integer(c_int), value, intent(in) :: p_stride, n, delta_stride, delta_max_stride, flags
      integer(c_int) :: stat
      type(solve_task) :: task
      integer :: threads
      stat = open_common(n, flags, p, p_stride, task%params)
      if (stat == egw_ok) stat = open_input(delta, "delta", delta_stride, n, task%delta, &
         & task%delta_stride)
      if (stat == egw_ok .and. c_associated(delta_max)) stat = open_input(delta_max, &
         & "delta_max", delta_max_stride, n, task%delta_max, task%delta_max_stride)
      if (stat == egw_ok) stat = require(res, "res")
      if (stat == egw_ok) stat = open_options(o, task%options, threads)
      if (stat /= egw_ok) return
      if (n > 0) call c_f_pointer(res, task%res, [n])
      stat = run_points(task, int(n), flags, n_failed, threads)
   end function egw_solve_array

   !> C: egw_restitution_array (include/egw.h).
   function egw_restitution_array(p, p_stride, o, n, mass, mass_stride, velocity, &
      & velocity_stride, e, w_load, w_dissipated, max_overlap, flags, n_failed) result(stat) &
      & bind(C, name="egw_restitution_array")
      !> C: `const egw_params *p` (the contact's parameters); `const egw_options *o` (solver
      !> options, NULL: the defaults); `const double *mass`; `const double *velocity`;
      !> `double *e` (out); `double *w_load` (out); `double *w_dissipated` (out); `double
      !> *max_overlap` (out); `int *n_failed` (failed points, may be NULL)
      type(c_ptr), value, intent(in) :: p, o, mass, velocity, e, w_load, w_dissipated, &
         & max_overlap, n_failed
      !> C: `int p_stride` (elements between points); `int n`; `int mass_stride` (elements
      !> between points); `int velocity_stride` (elements between points); `int flags`
      !> (EGW_ARRAY_RAISE or EGW_ARRAY_NAN)
      integer(c_int), value, intent(in) :: p_stride, n, mass_stride, velocity_stride, flags
      integer(c_int) :: stat
      stat = impact_points(p, p_stride, o, n, mass, mass_stride, velocity, velocity_stride, &
         & flags, n_failed, [e, w_load, w_dissipated, max_overlap], .false., 0.0_dp)
   end function egw_restitution_array

   !> C: egw_time_step_array (include/egw.h).
   function egw_time_step_array(p, p_stride, o, n, mass, mass_stride, velocity, &
      & velocity_stride, tolerance, duration, step, flags, n_failed) result(stat) &
      & bind(C, name="egw_time_step_array")
      !> C: `const egw_params *p` (the contact's parameters); `const egw_options *o` (solver
      !> options, NULL: the defaults); `const double *mass`; `const double *velocity`;
      !> `double *duration` (out); `double *time_step` (out); `int *n_failed` (failed
      !> points, may be NULL)
      type(c_ptr), value, intent(in) :: p, o, mass, velocity, duration, step, n_failed
      !> C: `int p_stride` (elements between points); `int n`; `int mass_stride` (elements
      !> between points); `int velocity_stride` (elements between points); `int flags`
      !> (EGW_ARRAY_RAISE or EGW_ARRAY_NAN)
      integer(c_int), value, intent(in) :: p_stride, n, mass_stride, velocity_stride, flags
      real(c_double), value, intent(in) :: tolerance   !< C: `double tolerance`
      integer(c_int) :: stat
      stat = impact_points(p, p_stride, o, n, mass, mass_stride, velocity, velocity_stride, &
         & flags, n_failed, [duration, step, c_null_ptr, c_null_ptr], .true., tolerance)
   end function egw_time_step_array

   ! ------------------------------------------------------------ the points

   !> Hertz of validated params (hertz_contact without its per-call validation).
   subroutine hertz_run(self, i, params, error)
      class(hertz_task), intent(in) :: self
      integer, intent(in) :: i
      type(contact_params), intent(in) :: params
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: delta, f, k
      if (allocated(self%done)) then
         if (self%done(i + 1)) return
      end if
      delta = self%delta(1 + i*self%delta_stride)
      if (.not. ieee_is_finite(delta)) then
         call fatal_error(error, egw_invalid_argument, "delta = "//format_real(delta) &
            & //": the overlap must be finite")
         return
      end if
      f = hertz_force(delta, params%radius, params%modulus)
      k = hertz_stiffness(delta, params%radius, params%modulus)
      if (.not. (ieee_is_finite(f) .and. ieee_is_finite(k))) then
         call fatal_error(error, egw_invalid_argument, "delta = "//format_real(delta) &
            & //": the Hertz force or stiffness exceeds the largest double")
         return
      end if
      if (associated(self%force)) self%force(i + 1) = f
      if (associated(self%stiffness)) self%stiffness(i + 1) = k
      if (associated(self%contact_radius)) self%contact_radius(i + 1) = &
         & hertz_contact_radius(delta, params%radius)
   end subroutine hertz_run

   !> The common case of one R and E* (validated): points whose every intermediate is a
   !> normal double are done here in a tight loop, with the operations of hertz_force,
   !> hertz_stiffness and hertz_contact_radius in their order (the same values bit for
   !> bit); the others are left to hertz_run, which is run after (overwriting nothing
   !> here: a point done here is computed again identically there only when it was not).
   subroutine hertz_shared(task, n)
      type(hertz_task), intent(inout) :: task
      integer, intent(in) :: n
      real(dp) :: radius, c_force, c_stiffness, d, rd, a, t, f
      integer :: i
      logical :: want_f, want_k, want_a
      radius = task%params%shared%radius
      c_force = (4.0_dp/3.0_dp)*task%params%shared%modulus
      c_stiffness = 2.0_dp*task%params%shared%modulus
      want_f = associated(task%force)
      want_k = associated(task%stiffness)
      want_a = associated(task%contact_radius)
      allocate (task%done(n))
      do i = 1, n
         d = task%delta(1 + (i - 1)*task%delta_stride)
         task%done(i) = .false.
         if (d > 0.0_dp .and. d <= huge(d)) then
            rd = radius*d
            if (.not. (rd >= tiny(rd) .and. rd <= huge(rd))) cycle
            a = sqrt(rd)
            t = c_force*a
            f = t*d
            if (.not. (t >= tiny(t) .and. t <= huge(t) .and. f >= tiny(f) .and. &
               & f <= huge(f) .and. c_stiffness*a <= huge(a))) cycle
         else if (d <= 0.0_dp .and. d >= -huge(d)) then
            a = 0.0_dp
            f = 0.0_dp
         else
            cycle
         end if
         if (want_f) task%force(i) = f
         if (want_k) task%stiffness(i) = c_stiffness*a
         if (want_a) task%contact_radius(i) = a
         task%done(i) = .true.
      end do
   end subroutine hertz_shared

   subroutine hertz_fail(self, i)
      class(hertz_task), intent(in) :: self
      integer, intent(in) :: i
      call put_nan(self%force, i)
      call put_nan(self%stiffness, i)
      call put_nan(self%contact_radius, i)
   end subroutine hertz_fail

   subroutine flat_run(self, i, params, error)
      class(flat_task), intent(in) :: self
      integer, intent(in) :: i
      type(contact_params), intent(in) :: params
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: d, pg, dpg
      d = self%separation(1 + i*self%separation_stride)
      pg = 0.0_dp
      dpg = 0.0_dp
      if (associated(self%separation_min)) then
         call flat_pressure_unload(params, d, &
            & self%separation_min(1 + i*self%separation_min_stride), pg, dpg, error)
      else
         call flat_pressure(params, d, pg, dpg, error)
      end if
      if (allocated(error)) return
      if (associated(self%pressure)) self%pressure(i + 1) = pg
      if (associated(self%dpressure)) self%dpressure(i + 1) = dpg
   end subroutine flat_run

   subroutine flat_fail(self, i)
      class(flat_task), intent(in) :: self
      integer, intent(in) :: i
      call put_nan(self%pressure, i)
      call put_nan(self%dpressure, i)
   end subroutine flat_fail

   subroutine gauss_run(self, i, params, error)
      class(gauss_task), intent(in) :: self
      integer, intent(in) :: i
      type(contact_params), intent(in) :: params
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: order, h, f, df
      associate (unused => params)
      end associate
      order = self%order(1 + i*self%order_stride)
      h = self%h(1 + i*self%h_stride)
      f = 0.0_dp
      df = 0.0_dp
      if (associated(self%value)) call get_gauss_integral(order, h, f, error)
      if (allocated(error)) return
      if (associated(self%derivative)) call get_gauss_integral_deriv(order, h, df, error)
      if (allocated(error)) return
      if (associated(self%value)) self%value(i + 1) = f
      if (associated(self%derivative)) self%derivative(i + 1) = df
   end subroutine gauss_run

   subroutine gauss_fail(self, i)
      class(gauss_task), intent(in) :: self
      integer, intent(in) :: i
      call put_nan(self%value, i)
      call put_nan(self%derivative, i)
   end subroutine gauss_fail

   subroutine solve_run(self, i, params, error)
      class(solve_task), intent(in) :: self
      integer, intent(in) :: i
      type(contact_params), intent(in) :: params
      type(egw_error), allocatable, intent(out) :: error
      type(solve_result) :: result
      real(dp) :: delta
      delta = self%delta(1 + i*self%delta_stride)
      if (associated(self%delta_max)) then
         call solve_contact_unload(params, self%options, delta, &
            & self%delta_max(1 + i*self%delta_max_stride), result, error)
      else
         call solve_contact(params, self%options, delta, result, error)
      end if
      if (allocated(error)) return
      self%res(i + 1) = egw_result_c(force=result%force, stiffness=result%stiffness, &
         & contact_radius=result%contact_radius, max_pressure=result%max_pressure, &
         & est_rel_err=result%est_rel_err, residual=result%residual, &
         & iterations=int(result%iterations, c_int), method_used=int(result%method_used, c_int))
   end subroutine solve_run

   subroutine solve_fail(self, i)
      class(solve_task), intent(in) :: self
      integer, intent(in) :: i
      real(dp) :: nan
      nan = ieee_value(1.0_dp, ieee_quiet_nan)
      self%res(i + 1) = egw_result_c(force=nan, stiffness=nan, contact_radius=nan, &
         & max_pressure=nan, est_rel_err=nan, residual=nan, iterations=-1_c_int, &
         & method_used=-1_c_int)
   end subroutine solve_fail

   subroutine impact_run(self, i, params, error)
      class(impact_task), intent(in) :: self
      integer, intent(in) :: i
      type(contact_params), intent(in) :: params
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: mass, velocity, e, dissipated, work, delta_m, t_c, dt
      mass = self%mass(1 + i*self%mass_stride)
      velocity = self%velocity(1 + i*self%velocity_stride)
      if (self%want_time_step) then
         t_c = 0.0_dp
         dt = 0.0_dp
         call time_step(params, self%options, mass, velocity, self%tolerance, t_c, dt, error)
         if (allocated(error)) return
         if (associated(self%duration)) self%duration(i + 1) = t_c
         if (associated(self%step)) self%step(i + 1) = dt
         return
      end if
      e = 1.0_dp
      dissipated = 0.0_dp
      work = 0.0_dp
      delta_m = 0.0_dp
      call restitution(params, self%options, mass, velocity, e, dissipated, error, &
         & work_load=work, max_overlap=delta_m)
      if (allocated(error)) return
      if (associated(self%e)) self%e(i + 1) = e
      if (associated(self%w_load)) self%w_load(i + 1) = work
      if (associated(self%w_dissipated)) self%w_dissipated(i + 1) = dissipated
      if (associated(self%max_overlap)) self%max_overlap(i + 1) = delta_m
   end subroutine impact_run

   subroutine impact_fail(self, i)
      class(impact_task), intent(in) :: self
      integer, intent(in) :: i
      call put_nan(self%e, i)
      call put_nan(self%w_load, i)
      call put_nan(self%w_dissipated, i)
      call put_nan(self%max_overlap, i)
      call put_nan(self%duration, i)
      call put_nan(self%step, i)
   end subroutine impact_fail

   ! ------------------------------------------------------------ the driver

   !> Run the n points of task, over threads OpenMP threads (0: serially). EGW_ARRAY_RAISE:
   !> at a failing point the call stops (points not yet started are skipped) and returns
   !> its status with its message prefixed by "point i: " (the lowest failing index among
   !> those tried); EGW_ARRAY_NAN: failing points get NaN outputs, their number goes to the
   !> nullable int* n_failed, and the call returns EGW_OK.
   integer(c_int) function run_points(task, n, flags, n_failed, threads) result(stat)
      class(point_task), intent(in) :: task
      integer, intent(in) :: n, threads
      integer(c_int), intent(in) :: flags
      type(c_ptr), intent(in) :: n_failed
      integer, allocatable :: point_stat(:)
      integer :: i, first
      logical :: stop_now
      allocate (point_stat(n))
      point_stat = egw_ok
      stop_now = .false.
      ! (one point runs on the calling thread: a parallel region, even of one busy
      ! thread, would silence its progress reports, egw_progress; Python's scalar calls
      ! are arrays of one point)
      if (threads > 1 .and. n > 1) then
         !$omp parallel do schedule(dynamic, 1) num_threads(threads) default(shared)
         do i = 0, n - 1
            call run_one(task, i, flags, stop_now, point_stat(i + 1))
         end do
         !$omp end parallel do
      else
         do i = 0, n - 1
            call run_one(task, i, flags, stop_now, point_stat(i + 1))
            if (stop_now) exit
         end do
      end if
      stat = egw_ok
      if (flags == array_nan) then
         call put_int(n_failed, count(point_stat /= egw_ok))
         return
      end if
      call put_int(n_failed, 0)
      first = findloc(point_stat /= egw_ok, .true., dim=1)
      if (first > 0) stat = failed_message(task, first - 1)
   end function run_points

   !> Point i of task; its status into point_stat. Skipped once stop_now is set
   !> (EGW_ARRAY_RAISE after a failure).
   subroutine run_one(task, i, flags, stop_now, point_stat)
      class(point_task), intent(in) :: task
      integer, intent(in) :: i
      integer(c_int), intent(in) :: flags
      logical, intent(inout) :: stop_now
      integer, intent(out) :: point_stat
      type(egw_error), allocatable :: error
      logical :: skip
      point_stat = egw_ok
      !$omp atomic read
      skip = stop_now
      if (skip) return
      call point(task, i, error)
      if (.not. allocated(error)) return
      point_stat = error%stat
      call task%fail(i)
      if (flags == array_raise) then
         !$omp atomic write
         stop_now = .true.
      end if
   end subroutine run_one

   !> Point i of task with its params (validated here when one per point).
   subroutine point(task, i, error)
      class(point_task), intent(in) :: task
      integer, intent(in) :: i
      type(egw_error), allocatable, intent(out) :: error
      type(contact_params) :: params
      if (task%params%stride == 0) then
         call task%run(i, task%params%shared, error)
         return
      end if
      params = to_params(task%params%cp(1 + i*task%params%stride))
      call validate_params(params, error)
      if (.not. allocated(error)) call task%run(i, params, error)
   end subroutine point

   !> The status of the failed point i with its message, recorded on the calling thread
   !> (the point is run again here: workers' messages stay on the workers).
   integer(c_int) function failed_message(task, i) result(stat)
      class(point_task), intent(in) :: task
      integer, intent(in) :: i
      type(egw_error), allocatable :: error
      call point(task, i, error)
      if (.not. allocated(error)) then
         stat = failure(egw_invalid_argument, "point "//int_str(i)//": failed")
         return
      end if
      stat = settle(error)
      stat = failure(int(stat), "point "//int_str(i)//": "//error%message)
   end function failed_message

   ! ------------------------------------------------------------ argument checks

   !> The checks of every entry with params: n >= 0, flags, p (not NULL) read with its
   !> stride; a shared p (stride 0) is validated once here.
   integer(c_int) function open_common(n, flags, p, p_stride, view) result(stat)
      integer(c_int), intent(in) :: n, flags, p_stride
      type(c_ptr), intent(in) :: p
      type(params_view), intent(out) :: view
      type(egw_error), allocatable :: error
      stat = check_count(n)
      if (stat == egw_ok) stat = check_flags(flags)
      if (stat == egw_ok) stat = check_stride("p_stride", p_stride)
      if (stat == egw_ok) stat = require(p, "p")
      if (stat /= egw_ok) return
      view%stride = int(p_stride)
      call c_f_pointer(p, view%cp, [extent(n, p_stride)])
      if (p_stride /= 0) return
      view%shared = to_params(view%cp(1))
      call validate_params(view%shared, error)
      stat = settle(error)
   end function open_common

   !> An impact array (restitution, or with want_time_step the time step for tolerance):
   !> its inputs checked, its outputs (e, w_load, w_dissipated, max_overlap; or duration,
   !> step) taken, its points run over the threads.
   integer(c_int) function impact_points(p, p_stride, o, n, mass, mass_stride, velocity, &
      & velocity_stride, flags, n_failed, outputs, want_time_step, tolerance) result(stat)
      type(c_ptr), intent(in) :: p, o, mass, velocity, n_failed, outputs(4)
      integer(c_int), intent(in) :: p_stride, n, mass_stride, velocity_stride, flags
      logical, intent(in) :: want_time_step
      real(dp), intent(in) :: tolerance
      type(impact_task) :: task
      integer :: threads
      threads = 0
      stat = open_common(n, flags, p, p_stride, task%params)
      if (stat == egw_ok) stat = open_input(mass, "mass", mass_stride, n, task%mass, &
         & task%mass_stride)
      if (stat == egw_ok) stat = open_input(velocity, "velocity", velocity_stride, n, &
         & task%velocity, task%velocity_stride)
      if (stat == egw_ok) stat = open_options(o, task%options, threads)
      ! The tolerance is shared by the points, as a shared *p: refused whatever the flags
      ! (under EGW_ARRAY_NAN every point came back NaN with EGW_OK and no message).
      if (stat == egw_ok .and. want_time_step .and. &
         & .not. (tolerance > 0.0_dp .and. tolerance <= 0.1_dp)) &
         & stat = invalid("tolerance = "//format_real(tolerance)//": must lie in (0, 0.1]")
      if (stat /= egw_ok) return
      task%want_time_step = want_time_step
      if (want_time_step) then
         task%tolerance = tolerance
         task%duration => double_array(outputs(1), n)
         task%step => double_array(outputs(2), n)
      else
         task%e => double_array(outputs(1), n)
         task%w_load => double_array(outputs(2), n)
         task%w_dissipated => double_array(outputs(3), n)
         task%max_overlap => double_array(outputs(4), n)
      end if
      stat = run_points(task, int(n), flags, n_failed, threads)
   end function impact_points

   !> Options from the nullable o; the points' thread count from its n_threads (0: OpenMP
   !> default; at most the processors: libgomp aborts when it cannot create a team), each
   !> solve then single-threaded inside.
   integer(c_int) function open_options(o, options, threads) result(stat)
      type(c_ptr), intent(in) :: o
      type(solver_options), intent(out) :: options
      integer, intent(out) :: threads
      stat = egw_ok
      call read_options(o, options)
      if (options%n_threads < 0) then
         stat = invalid("n_threads = "//int_str(options%n_threads)// &
            & ": must be >= 0 (0 = OpenMP default)")
         return
      end if
      threads = options%n_threads
      if (threads == 0) then
         threads = 1
         !$ threads = omp_get_max_threads()
      end if
      !$ threads = min(threads, omp_get_num_procs())
      options%n_threads = 1
   end function open_options

   !> An input array (not NULL) of n points with its stride (0 or more).
   integer(c_int) function open_input(ptr, name, stride, n, x, x_stride) result(stat)
      type(c_ptr), intent(in) :: ptr
      character(len=*), intent(in) :: name
      integer(c_int), intent(in) :: stride, n
      real(c_double), pointer, intent(out) :: x(:)
      integer, intent(out) :: x_stride
      x => null()
      x_stride = int(stride)
      stat = check_stride(name//"_stride", stride)
      if (stat == egw_ok) stat = require(ptr, name)
      if (stat /= egw_ok) return
      call c_f_pointer(ptr, x, [extent(n, stride)])
   end function open_input

   !> Elements spanned by n points at stride (at least one: a shared value is read).
   pure integer function extent(n, stride)
      integer(c_int), intent(in) :: n, stride
      extent = max(1, 1 + (int(n) - 1)*int(stride))
   end function extent

   integer(c_int) function check_stride(name, stride) result(stat)
      character(len=*), intent(in) :: name
      integer(c_int), intent(in) :: stride
      stat = egw_ok
      if (stride < 0) stat = invalid(name//" = "//int_str(int(stride))//": must be >= 0")
   end function check_stride

   integer(c_int) function check_flags(flags) result(stat)
      integer(c_int), intent(in) :: flags
      stat = egw_ok
      if (flags /= array_raise .and. flags /= array_nan) stat = invalid("flags = " &
         & //int_str(int(flags))//": must be EGW_ARRAY_RAISE (0) or EGW_ARRAY_NAN (1)")
   end function check_flags

   subroutine put_nan(x, i)
      real(c_double), pointer, intent(in) :: x(:)
      integer, intent(in) :: i
      if (associated(x)) x(i + 1) = ieee_value(1.0_dp, ieee_quiet_nan)
   end subroutine put_nan

   !> This thread's last error message (as egw_last_error). (A subroutine: gfortran 12
   !> keeps a deferred-length function result's length in a static variable; egw_text.)
   subroutine last_error_text(text)
      character(len=:), allocatable, intent(out) :: text
      character(kind=c_char, len=1), target :: buf(1024)
      integer :: i, stat, n
      stat = copy_last_error(c_loc(buf), int(size(buf), c_int))
      n = 0
      do i = 1, size(buf)
         if (buf(i) == achar(0)) exit
         n = i
      end do
      allocate (character(len=n) :: text)
      do i = 1, n
         text(i:i) = buf(i)
      end do
   end subroutine last_error_text

   subroutine put_int(ptr, k)
      type(c_ptr), intent(in) :: ptr
      integer, intent(in) :: k
      integer(c_int), pointer :: target
      if (.not. c_associated(ptr)) return
      call c_f_pointer(ptr, target)
      target = int(k, c_int)
   end subroutine put_int

end module egw_capi_array
