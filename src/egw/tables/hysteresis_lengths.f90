!> What a hysteresis build knows of a turning point m before its curve: the unloading
!> length L(m) of its curve (unloading_length, cap_length, rough_length), where the
!> flow-pressure cap acts on a rough sphere's loading (cap_reached; where it starts:
!> egw_rough_yield), the loading table's floor, and the options and first failure of the
!> build's parallel solves over curves. doc/theory.md §8, §12.
module egw_hysteresis_lengths
   use egw_kinds, only: dp
   use egw_status, only: egw_error, format_real
   use egw_params, only: contact_params, model_epgw
   use egw_rough_sphere, only: solver_options, solve_result, cap_solve_options, &
      & solve_contact
   use egw_cap_sphere, only: cap_residual, cap_units
   use egw_rough_yield, only: cap_acts
   use egw_table, only: force_table, table_eval
   use egw_tolerance_probe, only: hysteresis_solve_tol
   use egw_hysteresis_data, only: hysteresis_table
   use egw_hysteresis, only: first_yield
   implicit none
   private

   public :: cap_reached, plastic_summits, rough_length, cap_length, &
      & log_table, unloading_floor, curve_options, unloading_length



contains

   !> Whether the flow-pressure cap acts on the loading of a rough sphere up to delta_max:
   !> the largest total pressure of the loading solve there (at the curves' tolerance)
   !> reaches p_y (cap_acts).
   subroutine cap_reached(params, options, rel_tol, delta_max, reached, error)
      type(contact_params), intent(in) :: params   !< the contact
      type(solver_options), intent(in) :: options   !< the build's solver options
      real(dp), intent(in) :: rel_tol, delta_max   !< the table's tolerance, overlap
      logical, intent(out) :: reached   !< the cap acts on the loading up to delta_max
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      type(solve_result) :: res
      reached = .false.
      ! (its largest pressure only: no moved-mesh stiffness)
      call solve_contact(params, curve_options(options, rel_tol), delta_max, res, error, &
         & stiffness=.false.)
      ! (the solve's message in its scaled units: which solve of the build, in the user's)
      if (allocated(error)) error%message = "the capped loading solve at delta = "// &
         & format_real(delta_max)//": "//error%message
      if (allocated(error)) return
      reached = cap_acts(res%max_pressure, params%flow_pressure)
   end subroutine cap_reached

   !> EP-GW with yielding summits (psi > 0): dissipative without the cap.
   elemental logical function plastic_summits(params)
      type(contact_params), intent(in) :: params   !< the contact
      plastic_summits = params%model == model_epgw .and. params%psi > 0.0_dp
   end function plastic_summits

   !> L(m) of a rough model with the cap: unloading_length of the cap-free loading solve at
   !> m, less (shift: where the cap acts below the table's delta_max) the smooth cap
   !> model's residual overlap delta_r(m) (0 up to first yield delta_y; cap_length). The
   !> capped solve's loading stiffness holds its capped set fixed and converges slowly
   !> (doc/theory.md section 12, Limits): L from it jumped by 5 % between neighbouring
   !> turning points, which no bisection in m removes; the cap-free L is smooth in m, and
   !> equal to the capped one where the cap does not act. The shift puts the knee of every
   !> curve, where the unloading contact separates near delta_r, at about one s (1/s_max,
   !> as the Hertz + cap curves' residual overlap at s = 1): with the cap-free L alone it
   !> moved from s = 0.48 to 0.29 between 1.2 and 5.7 delta_y (E-GW, sigma = delta_y/100),
   !> the curves' cubics in m met it at every s and the delta_max grid at 1e-4 needed 81
   !> nodes, its midpoint mismatch falling only ~h**1.5 (doc/benchmarks.md, stop 43).
   !> delta_r (C1 at delta_y, smooth above) keeps L smooth in m.
   subroutine rough_length(params, options, m, shift, length, error)
      type(contact_params), intent(in) :: params   !< the contact
      type(solver_options), intent(in) :: options   !< the build's solver options
      real(dp), intent(in) :: m   !< turning point [length]
      logical, intent(in) :: shift   !< less the smooth cap's residual overlap
      real(dp), intent(out) :: length   !< L(m) [length]
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      type(contact_params) :: free
      type(solve_result) :: res
      real(dp) :: smooth
      free = params
      free%flow_pressure = 0.0_dp
      length = params%sigma
      call solve_contact(free, options, m, res, error)
      if (allocated(error)) return
      length = unloading_length(res%force, res%stiffness, params%sigma)
      if (.not. (shift .and. m > first_yield(params))) return
      call cap_length(params, m, smooth, error)
      if (allocated(error)) return
      ! (L_free >= m on the rough models: never below the smooth cap's m - delta_r)
      length = max(length - (m - smooth), smooth)
   end subroutine rough_length

   !> The unloading length of a Hertz + cap curve of turning point m: m minus the residual
   !> overlap of cap_load (on the public solves' options; cap_residual, the same value
   !> without the unloading's parts); m at and below first yield (Hertz: the residual
   !> overlap is 0).
   subroutine cap_length(params, m, length, error, gamma)
      type(contact_params), intent(in) :: params   !< the contact
      real(dp), intent(in) :: m   !< turning point [length]
      real(dp), intent(out) :: length   !< L(m) [length]
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      !> cap_residual's start of c/a (0: its own), out: the solution's
      real(dp), intent(inout), optional :: gamma
      real(dp) :: residual, delta_y, a_y, force_y
      call cap_residual(params%radius, params%modulus, params%flow_pressure, m, &
         & cap_solve_options(), residual, error, gamma)
      if (allocated(error)) return
      call cap_units(params%radius, params%modulus, params%flow_pressure, delta_y, a_y, &
         & force_y)
      length = m - residual*delta_y
   end subroutine cap_length

   !> Whether the table's curves are log-ratio curves (build_hysteresis sets it: EP-GW
   !> without the cap or with a cap that does not act; curves on which the cap acts,
   !> whose force is 0 below a residual overlap, keep the gap).
   elemental logical function log_table(table)
      type(hysteresis_table), intent(in) :: table   !< the table being built
      log_table = table%log_ratio
   end function log_table

   !> The overlap where the loading table's force falls to rel_tol of its reference force
   !> (bisection on the monotone table; its cut-off if the force there is larger).
   pure real(dp) function unloading_floor(loading, rel_tol) result(floor)
      type(force_table), intent(in) :: loading   !< the loading table
      real(dp), intent(in) :: rel_tol   !< the fraction of its reference force
      real(dp) :: lo, hi, mid, f, k
      integer :: it
      lo = loading%cutoff
      hi = loading%delta_max
      floor = lo
      if (loading%force(1) >= rel_tol*loading%reference_force) return
      do it = 1, 100
         mid = 0.5_dp*(lo + hi)
         if (.not. (mid > lo .and. mid < hi)) exit
         call table_eval(loading, mid, f, k)
         if (f < rel_tol*loading%reference_force) then
            lo = mid
         else
            hi = mid
         end if
      end do
      floor = lo
   end function unloading_floor

   !> The options of one curve's solves: serial (the parallelism is over the curves), at
   !> hysteresis_solve_tol (a decade finer than the table's tolerance rel_tol).
   pure function curve_options(options, rel_tol) result(serial)
      type(solver_options), intent(in) :: options   !< the build's solver options
      real(dp), intent(in) :: rel_tol   !< the table's tolerance
      type(solver_options) :: serial
      serial = options
      serial%n_threads = 1
      serial%rel_tol = hysteresis_solve_tol(options, rel_tol)
   end function curve_options

   !> L = 1.5 P/K_unload: m minus the residual overlap of Hertzian unloading
   !> P (1 - (m - delta)/L)^{3/2}, and 1.5 times the decay length of the separated tail
   !> (P ~ exp(-(m - delta) K/P)): r(s) changes little with m at fixed s = (m - delta)/L.
   !> sigma where the force has underflowed.
   pure real(dp) function unloading_length(force, stiffness, sigma) result(length)
      real(dp), intent(in) :: force, stiffness, sigma   !< P(m), K_unload(m), sigma
      length = sigma
      if (force > 0.0_dp .and. stiffness > 0.0_dp) length = 1.5_dp*force/stiffness
      if (.not. (length > 0.0_dp .and. length < huge(1.0_dp))) length = sigma
   end function unloading_length

end module egw_hysteresis_lengths
