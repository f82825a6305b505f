!> One discrete solve of a rough sphere in the caller's units (solve_rough: loading, or
!> unloading on a history's field, rough_unload) and what every solve of egw_rough_sphere
!> shares: its result type, the checks of its input, the smooth sphere's flow-pressure cap
!> behind the public doors (cap_loading on cap_solve_options). doc/theory.md §5, §8, §12.
module egw_rough_solve
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_invalid_argument, egw_not_converged, fatal_error, &
      & format_real, int_str
   use egw_params, only: contact_params, validate_params, model_hertz, check_scaled_overlap, &
      & length_unit, pressure_unit, force_unit, stiffness_unit
   use egw_smooth_sphere, only: hertz_pressure, hertz_force, hertz_stiffness
   use egw_unloading, only: unloading_law_of
   use egw_law_pieces, only: law_pieces
   use egw_sphere_problem, only: force_floor
   use egw_cap_sphere, only: cap_options, cap_result, cap_history, cap_load, cap_units
   use egw_sphere_solver, only: method_auto, method_picard, solver_options, max_mesh_nodes, &
      & separation_field, scaled_problem, discrete_solution, scaled, normal, solve_scaled, &
      & differentiate, effective_radius, total_pressure, smooth_force, smooth_stiffness, &
      & solver_workspace
   use egw_sphere_moving_mesh, only: kink_following_rate
   implicit none
   private

   !> Result of a solve, in the caller's units. Field order matches the C struct egw_result.
   type, public :: solve_result
      real(dp) :: force = 0.0_dp           !< total normal force P
      real(dp) :: stiffness = 0.0_dp       !< dP/d(delta), by implicit differentiation
      !> a* = (3 pi/4) int r p dr / int p dr (Hertz + cap beyond first yield: the edge a)
      real(dp) :: contact_radius = 0.0_dp
      real(dp) :: max_pressure = 0.0_dp    !< maximum of the total pressure
      !> estimated error of P relative to |P| itself: |P_true - P| <~ est_rel_err |P| (1 for
      !> P = 0). A solve accepts when its error estimate is below rel_tol/2 of |P| or, for
      !> unloading after a capped loading, of a floor (1e-6 P(delta_max); restitution's
      !> unloading solves half its work density) if that is larger: below the floor
      !> est_rel_err can exceed rel_tol (doc/theory.md section 12, "The force floor").
      real(dp) :: est_rel_err = 0.0_dp
      real(dp) :: residual = 0.0_dp        !< final scaled nonlinear residual
      integer :: iterations = 0            !< nonlinear iterations of the final solve
      integer :: method_used = method_auto !< method that produced the result
      !> A loading solve with the cap whose stiffness is the implicit derivative on the
      !> accepted mesh held fixed while the cap's kinks move through it: the derivative of
      !> the converged answer on the moved mesh failed (a solve, the kinks' match) or was
      !> not asked (load_history's stiffness = .false.). Up to ~1e-3 of the stiffness off
      !> then (doc/theory.md section 12); .false. for every other solve.
      logical :: implicit_stiffness = .false.
   end type solve_result

   public :: validate_options, check_input, check_unload_input, check_cap_overlap
   public :: solve_rough, rough_unload, relative_to_force
   public :: above_first_yield, smooth_capped, cap_loading, cap_solve_options, put_cap_result
   public :: unload_start

   !> The start of the next unloading solve of one history (solve_unload's start): the
   !> rough deflection of that history's last converged discrete unloading solve, which
   !> starts the next one's locating solve (doc/theory.md section 12, "Solves of one
   !> history"). Owned by one caller (a curve of a table build), never shared between
   !> threads; a start of another history (another delta_max) is not used. It also
   !> carries the solver's buffers (solver_workspace), which the solves it starts reuse.
   type :: unload_start
      logical, private :: valid = .false.
      real(dp), private :: delta_max = 0.0_dp
      type(discrete_solution), private :: sol   !< its mesh and w only
      type(solver_workspace), private :: work
   end type unload_start

contains

   !> Check the options; the message names the offending field and its value.
   pure subroutine validate_options(options, error)
      type(solver_options), intent(in) :: options   !< the options to check
      !> allocated, naming the field, when one is invalid
      type(egw_error), allocatable, intent(out) :: error
      if (options%n_radial /= 0 .and. (options%n_radial < 8 .or. &
         & options%n_radial > max_mesh_nodes)) then
         call fatal_error(error, egw_invalid_argument, "n_radial = "//int_str(options%n_radial) &
            & //": must be 0 (automatic) or lie in [8, "//int_str(max_mesh_nodes)//"]")
      else if (.not. ieee_is_finite(options%rel_tol) .or. .not. options%rel_tol >= 1.0e-10_dp &
         & .or. options%rel_tol > 0.1_dp) then
         call fatal_error(error, egw_invalid_argument, "rel_tol = "//format_real(options%rel_tol) &
            & //": must lie in [1e-10, 0.1]")
      else if (options%max_iter < 0) then
         call fatal_error(error, egw_invalid_argument, "max_iter = "//int_str(options%max_iter) &
            & //": must be >= 0 (0 = default)")
      else if (options%method < method_auto .or. options%method > method_picard) then
         call fatal_error(error, egw_invalid_argument, "method = "//int_str(options%method) &
            & //": must be 0 (auto), 1 (Newton) or 2 (Picard)")
      else if (options%n_threads < 0) then
         call fatal_error(error, egw_invalid_argument, "n_threads = " &
            & //int_str(options%n_threads)//": must be >= 0 (0 = OpenMP default)")
      end if
   end subroutine validate_options

   !> The discrete solve of a rough scaled problem (loading, or unloading when
   !> prob%closest is allocated), its stiffness, and the result in the caller's units.
   !> result is only written on success.
   subroutine solve_rough(params, options, prob, sol, result, error, warm, work, moved_rate)
      type(contact_params), intent(in) :: params   !< the contact (its units)
      type(solver_options), intent(in) :: options   !< tolerance, mesh, method and threads
      type(scaled_problem), intent(in) :: prob   !< the scaled problem (egw_sphere_problem)
      type(discrete_solution), intent(out) :: sol   !< the converged discrete solution
      type(solve_result), intent(inout) :: result   !< the solve in the caller's units
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      !> unloading: a solution of another solve of the same history (solve_scaled's)
      type(discrete_solution), intent(in), optional :: warm
      !> the buffers of the caller's earlier solves (solve_scaled's, differentiate's)
      type(solver_workspace), intent(inout), optional :: work
      !> loading with the cap: .false. keeps the implicit stiffness (no moved-mesh solves);
      !> absent: .true.
      logical, intent(in), optional :: moved_rate
      type(solve_result) :: res
      real(dp) :: est, force_scale, pmax, rate
      logical :: moved, want_moved

      call solve_scaled(prob, options, sol, est, res%method_used, error, warm, work)
      if (allocated(error)) return
      if (sol%force == 0.0_dp .and. est >= 1.0_dp) then
         ! Underflow range (tiny_force): 0 with relative error 1, as negligible().
         res%est_rel_err = 1.0_dp
         result = res
         return
      end if
      call differentiate(prob, sol, error, work)
      if (allocated(error)) return
      want_moved = .true.
      if (present(moved_rate)) want_moved = moved_rate
      if (want_moved .and. allocated(prob%cap) .and. .not. allocated(prob%closest)) then
         ! loading with the cap: the derivative of the converged answer, on the accepted
         ! mesh moved with its kinks (the implicit one can be ~1e-3 off; issue 32)
         rate = sol%dforce
         call kink_following_rate(prob, options, sol, rate, moved)
         sol%dforce = rate
         res%implicit_stiffness = .not. moved
      else if (allocated(prob%cap) .and. .not. allocated(prob%closest)) then
         ! (not asked: the caller reads the force only)
         res%implicit_stiffness = .true.
      end if

      force_scale = force_unit(params)
      res%force = force_scale*(smooth_force(prob) + sol%force)
      if (normal(force_scale/params%sigma)) then
         res%stiffness = force_scale/params%sigma*(smooth_stiffness(prob) + sol%dforce)
      else
         res%stiffness = stiffness_unit(params)*(smooth_stiffness(prob) + sol%dforce)
      end if
      res%contact_radius = length_unit(params)*effective_radius(prob, sol)
      pmax = max(total_pressure(prob, sol, 0.0_dp), maxval(sol%p))
      if (prob%extended) pmax = max(pmax, &
         & maxval(hertz_pressure(sol%mesh%gauss_r, prob%delta, 1.0_dp, 1.0_dp) + sol%p))
      res%max_pressure = pressure_unit(params)*pmax
      ! (est is relative to max(|P|, force_floor): the user's is relative to |P|)
      res%est_rel_err = relative_to_force(est, force_floor(prob), abs(smooth_force(prob) + &
         & sol%force))
      res%residual = sol%residual
      res%iterations = sol%iterations
      if (.not. all(ieee_is_finite([res%force, res%stiffness, res%contact_radius, &
         & res%max_pressure, res%est_rel_err, res%residual]))) then
         ! a safety net: validate_params keeps the scales normal, so this is a solver bug
         call fatal_error(error, egw_not_converged, "delta = "//format_real(prob%delta) &
            & //" (in units of sigma): the solve gave a non-finite force, stiffness or radius")
         return
      end if
      result = res
   end subroutine solve_rough

   !> The discrete unloading solve of a rough history (solve_unload's, without the
   !> asymptotic route); cap_free: the history's (loading_history%cap_free), the cap left out.
   subroutine rough_unload(params, options, closest, delta, result, error, start, loading, &
      & cap_free)
      type(contact_params), intent(in) :: params   !< the history's contact
      type(solver_options), intent(in) :: options   !< the history's options
      type(separation_field), intent(in) :: closest   !< the history's loading field
      real(dp), intent(in) :: delta   !< overlap [length] of the unloading solve
      type(solve_result), intent(inout) :: result   !< the solve at delta; untouched on error
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      type(unload_start), intent(inout), optional :: start   !< solve_unload's
      type(law_pieces), intent(in), optional :: loading   !< the history's tabulated law
      logical, intent(in), optional :: cap_free   !< the history's cap_free: the cap left out
      type(scaled_problem) :: prob
      type(discrete_solution) :: sol
      logical :: warm
      prob = scaled(params, delta, loading)
      if (present(cap_free)) then
         if (cap_free .and. allocated(prob%cap)) deallocate (prob%cap)
      end if
      allocate (prob%closest)
      prob%closest = closest
      prob%unload = unloading_law_of(prob%psi, prob%hardness, prob%plastic_ratio, loading)
      warm = .false.
      if (present(start)) warm = start%valid .and. start%delta_max == closest%delta
      if (warm) then
         call solve_rough(params, options, prob, sol, result, error, start%sol, start%work)
      else if (present(start)) then
         call solve_rough(params, options, prob, sol, result, error, work=start%work)
      else
         call solve_rough(params, options, prob, sol, result, error)
      end if
      if (allocated(error) .or. .not. present(start)) return
      if (.not. allocated(sol%w)) return
      start%valid = .true.
      start%delta_max = closest%delta
      start%sol%mesh = sol%mesh
      call move_alloc(sol%w, start%sol%w)
   end subroutine rough_unload

   !> An error estimate relative to max(force, floor) (force >= 0) as one relative to force
   !> (solve_result%est_rel_err): 1 for force 0 (its error relative to the true force),
   !> huge(1.0) where the quotient would overflow.
   pure real(dp) function relative_to_force(est, floor, force) result(rel)
      real(dp), intent(in) :: est, floor, force   !< the estimate, its floor, the force >= 0
      real(dp) :: absolute
      rel = est
      if (floor <= force) return
      if (force == 0.0_dp) then
         rel = 1.0_dp
         return
      end if
      absolute = est*floor
      rel = huge(1.0_dp)
      if (force > absolute/huge(1.0_dp)) rel = absolute/force
   end function relative_to_force

   !> Whether params (validated) have the flow-pressure cap and delta lies beyond its first
   !> yield delta_y = (pi p_y/(2 E*))**2 R (Hertz p_max = p_y): the cap model's range.
   !> At or below delta_y the cap never acts and the solves are Hertz's.
   elemental logical function above_first_yield(params, delta) result(above)
      type(contact_params), intent(in) :: params   !< the contact
      real(dp), intent(in) :: delta   !< overlap [length]
      real(dp) :: delta_y, a_y, force_y
      above = .false.
      if (.not. params%flow_pressure > 0.0_dp) return
      call cap_units(params%radius, params%modulus, params%flow_pressure, delta_y, a_y, &
         & force_y)
      above = delta > delta_y
   end function above_first_yield

   !> Whether params are a smooth sphere (Hertz or sigma = 0) with the cap beyond first
   !> yield: egw_cap_sphere's range. A rough sphere's cap lives in its scaled problem.
   elemental logical function smooth_capped(params, delta)
      type(contact_params), intent(in) :: params   !< the contact (validated)
      real(dp), intent(in) :: delta   !< overlap [length]
      smooth_capped = (params%model == model_hertz .or. params%sigma == 0.0_dp) .and. &
         & above_first_yield(params, delta)
   end function smooth_capped

   !> The smooth sphere with the cap loaded to delta (> delta_y): egw_cap_sphere's solve
   !> on cap_solve_options and the history its unloading needs.
   subroutine cap_loading(params, options, delta, history, result, error, name)
      type(contact_params), intent(in) :: params   !< the contact (smooth, with the cap)
      type(solver_options), intent(in) :: options   !< the solve's options (its method)
      real(dp), intent(in) :: delta   !< overlap [length] > delta_y
      type(cap_history), intent(out) :: history   !< what its unloading needs
      type(solve_result), intent(inout) :: result   !< the loading solve at delta
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      character(len=*), intent(in) :: name   !< the overlap's name in messages
      type(cap_result) :: res
      call cap_load(params%radius, params%modulus, params%flow_pressure, delta, &
         & cap_solve_options(), history, res, error, name)
      if (allocated(error)) return
      call put_cap_result(res, options, result)
   end subroutine cap_loading

   !> The cap solver's options behind every public door (doc/theory.md section 12): the
   !> fitted meshes of 64 rings (32 for the error estimate). Measured: every row of
   !> test/data/cap_reference.csv (loading, residual, unloading, restitution, 1 to 100
   !> delta_y) within 3.3e-6.
   pure function cap_solve_options() result(options)
      type(cap_options) :: options
      options = cap_options(n_rings=32, n_levels=2)
   end function cap_solve_options

   !> A cap solve's result as a solve_result: est_rel_err from its two finest levels.
   pure subroutine put_cap_result(res, options, result)
      type(cap_result), intent(in) :: res   !< egw_cap_sphere's result
      type(solver_options), intent(in) :: options   !< the solve's options (its method)
      type(solve_result), intent(inout) :: result   !< the same as a solve_result
      result = solve_result(force=res%force, stiffness=res%stiffness, &
         & contact_radius=res%contact_radius, max_pressure=res%max_pressure, &
         & method_used=options%method)
      if (res%force > 0.0_dp) result%est_rel_err = res%force_error/res%force
   end subroutine put_cap_result

   !> The checks of every solve's input: params (validate_params), options
   !> (validate_options), a finite delta whose Hertz force and stiffness stay finite
   !> (smooth), or within the solver's range of delta/sigma and, with the cap, at most
   !> 1e12 delta_y (rough: check_scaled_overlap, check_cap_overlap).
   pure subroutine check_input(params, options, delta, error, allow_flat_law)
      type(contact_params), intent(in) :: params   !< the contact
      type(solver_options), intent(in) :: options   !< the solve's options
      real(dp), intent(in) :: delta   !< overlap [length]
      !> allocated (egw_invalid_parameter or egw_invalid_argument, naming the value) when
      !> an input is refused
      type(egw_error), allocatable, intent(out) :: error
      logical, intent(in), optional :: allow_flat_law   !< the caller has the law
      call validate_params(params, error, allow_flat_law)
      if (allocated(error)) return
      call validate_options(options, error)
      if (allocated(error)) return
      if (.not. ieee_is_finite(delta)) then
         call fatal_error(error, egw_invalid_argument, "delta = "//format_real(delta) &
            & //": the overlap must be finite")
         return
      end if
      if (params%model == model_hertz .or. params%sigma == 0.0_dp) then
         if (.not. (ieee_is_finite(hertz_force(delta, params%radius, params%modulus)) .and. &
            & ieee_is_finite(hertz_stiffness(delta, params%radius, params%modulus)))) &
            & call fatal_error(error, egw_invalid_argument, "delta = "//format_real(delta) &
            & //": the Hertz force (4/3) E sqrt(R) delta**1.5 or stiffness 2 E sqrt(R delta)" &
            & //" exceeds the largest double")
      else
         call check_scaled_overlap("delta", delta, params%sigma, error)
         if (.not. allocated(error)) call check_cap_overlap("delta", delta, params, error)
      end if
   end subroutine check_input

   !> check_input for an unloading solve at delta after delta_max, and a finite delta_max
   !> (smooth spheres: one whose Hertz force and stiffness stay finite).
   pure subroutine check_unload_input(params, options, delta, delta_max, error)
      type(contact_params), intent(in) :: params   !< the contact
      type(solver_options), intent(in) :: options   !< the solve's options
      real(dp), intent(in) :: delta       !< overlap [length] of the unloading solve
      real(dp), intent(in) :: delta_max   !< largest overlap reached before [length]
      !> allocated (egw_invalid_parameter or egw_invalid_argument, naming the value) when
      !> an input is refused
      type(egw_error), allocatable, intent(out) :: error
      call check_input(params, options, delta, error)
      if (allocated(error)) return
      if (.not. ieee_is_finite(delta_max)) then
         call fatal_error(error, egw_invalid_argument, "delta_max = "//format_real(delta_max) &
            & //": the largest overlap must be finite")
         return
      end if
      ! a smooth sphere is loaded to delta_max first: its Hertz force must be a double, and
      ! the message names delta_max (the loading solve's own check would name delta)
      if (params%model == model_hertz .or. params%sigma == 0.0_dp) then
         if (.not. (ieee_is_finite(hertz_force(delta_max, params%radius, params%modulus)) &
            & .and. ieee_is_finite(hertz_stiffness(delta_max, params%radius, &
            & params%modulus)))) call fatal_error(error, egw_invalid_argument, "delta_max = " &
            & //format_real(delta_max)//": the Hertz force (4/3) E sqrt(R) delta_max**1.5 or" &
            & //" stiffness 2 E sqrt(R delta_max) at the largest overlap exceeds the largest double")
      end if
   end subroutine check_unload_input

   !> A rough sphere with the cap: egw_invalid_argument naming name beyond rough_cap_range
   !> delta_y, where E-GW and EP-GW solves stop converging (doc/stability.md "Rough + cap far
   !> beyond first yield": converged to 2e12 .. 2e15 delta_y, failed a decade beyond,
   !> with a message naming neither delta nor p_y); no bead comes near (<= 1e4 delta_y at
   !> 10 m/s). The smooth cap's own range is 1e6 delta_y (egw_cap_sphere).
   pure subroutine check_cap_overlap(name, delta, params, error)
      character(len=*), intent(in) :: name   !< the overlap's name in the message
      real(dp), intent(in) :: delta   !< overlap [length]
      type(contact_params), intent(in) :: params   !< the contact (validated)
      type(egw_error), allocatable, intent(out) :: error   !< allocated beyond the range
      real(dp), parameter :: rough_cap_range = 1.0e12_dp
      real(dp) :: delta_y, a_y, force_y
      if (.not. params%flow_pressure > 0.0_dp) return
      call cap_units(params%radius, params%modulus, params%flow_pressure, delta_y, a_y, &
         & force_y)
      if (delta > rough_cap_range*delta_y) call fatal_error(error, egw_invalid_argument, &
         & name//" = "//format_real(delta)//": beyond 1e12 delta_y = " &
         & //format_real(rough_cap_range*delta_y)//" (delta_y = (pi p_y/(2 E*))**2 R, " &
         & //"flow_pressure = "//format_real(params%flow_pressure) &
         & //"; the rough + cap solver's range)")
   end subroutine check_cap_overlap

end module egw_rough_solve
