!> Normal contact of rough spheres: classic GW (Greenwood-Tripp), E-GW and EP-GW
!> (doc/theory.md §5; paper eqs. 10-13 and 28-35), with Hertz as sigma = 0.
!>
!> The solves in the caller's units, their validation and the unloading histories (their
!> contact profiles: egw_rough_profile). The problem is solved in scaled variables by
!> egw_sphere_solver: radii in units of sqrt(R sigma), gaps and deflections in sigma,
!> pressures in E sqrt(sigma/R), forces in E sqrt(R) sigma**1.5, so that scale invariance
!> is exact.
!>
!> Unloading (doc/theory.md §8, issue 10 item 3): a loading_history keeps the separation field
!> d_max(r) of the solve at delta_max (its mesh and nodal w_G); an unloading solve at
!> delta <= delta_max is the same problem with the unloading law at fixed d_max
!> (egw_sphere_solver).
!>
!> The flow-pressure cap (params%flow_pressure > 0; doc/theory.md §12) of a smooth sphere
!> is routed here and nowhere else: above first yield a smooth solve, history or unloading
!> solve is egw_cap_sphere's (cap_load, cap_unload with its default options); at or below
!> first yield it is Hertz, bit for bit as without the cap. A rough sphere takes the cap
!> inside its scaled problem (scaled_problem%cap, egw_flow_cap; "Rough spheres with the
!> cap"): the same solves, histories and unloading solves.
module egw_rough_sphere
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, egw_invalid_argument, egw_invalid_parameter, &
      & egw_not_converged, fatal_error, &
      & format_real, int_str
   use egw_params, only: contact_params, validate_params, model_hertz, model_gw, model_egw, &
      & model_epgw, model_flat_law, check_scaled_overlap, length_unit, pressure_unit, &
      & force_unit, stiffness_unit, product4
   use egw_progress, only: progress_begin, progress_end, progress_part, progress_report, &
      & progress_note
   use egw_smooth_sphere, only: hertz_pressure, hertz_force, &
      & hertz_stiffness, hertz_contact_radius
   use egw_unloading, only: unloading_law_of
   use egw_law_pieces, only: law_pieces
   use egw_flat_law, only: flat_law
   use egw_sphere_problem, only: force_floor, cap_never_acts
   use egw_sphere_regime, only: stall_overlap
   use egw_cap_limit, only: cap_limit, limit_load, limit_unload
   use egw_cap_sphere, only: cap_options, cap_result, cap_history, cap_load, cap_unload, &
      & cap_units
   use egw_sphere_solver, only: method_auto, method_newton, method_picard, solver_options, &
      & max_mesh_nodes, tiny_force, separation_field, scaled_problem, discrete_solution, &
      & scaled, normal, negligible, solve_scaled, differentiate, &
      & effective_radius, total_pressure, smooth_force, smooth_stiffness, solver_workspace
   use egw_sphere_moving_mesh, only: kink_following_rate
   implicit none
   private

   public :: method_auto, method_newton, method_picard, solver_options, max_mesh_nodes

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

   public :: validate_options, solve_contact, solve_contact_law
   public :: load_history, solve_unload, solve_contact_unload
   public :: unload_start
   public :: above_first_yield, cap_solve_options, history_residual, history_cap_ratio
   ! for egw_rough_profile (the profiles of these solves)
   public :: check_input, check_unload_input, smooth_capped, unloading_problem, &
      & history_cap, loaded_by_route

   !> With the cap: sigma/delta_y at or below which a solve that does not converge takes
   !> the asymptotic route (small_sigma_loading, small_sigma_unload; doc/theory.md §12
   !> "Small sigma"): from 2e-6 down, where the discrete solves fail at some overlaps.
   !> It meets sphere_solver's stall fallbacks (sigma/delta_y > 2e-6): with the route
   !> at 1e-6 and below, E-GW + cap (mu 4, p_y = 2/pi E*) between them failed with
   !> neither (loading at 1.2e-6, 1.5e-6 from 2 and 3 delta_y; unloading at 2e-6 from 2
   !> delta_y at 0.145 .. 0.2 delta_max, Newton stalling at rel_tol 1e-4 .. 1e-6;
   !> doc/stability.md "Stop 52 (small18)"). Converged solves there are unchanged (the
   !> route checks them only at small_sigma_check_limit, unload_check_limit). 1e-7 above
   !> 2e-6 (egw_sphere_regime's stall_overlap, the fallbacks' bound): that bound is
   !> computed in other units, and rounding there must leave no sigma to neither (at
   !> exactly 2e-6 neither applied before).
   real(dp), parameter :: small_sigma_limit = (1.0_dp + 1.0e-7_dp)/stall_overlap
   !> sigma/delta_y of the rough solves that give the asymptotic route its sigma**(2/3)
   !> correction: the nearer, and the farther that checks it. There the discrete solves
   !> converge at every overlap tried and their differences from the smooth cap fall by
   !> 4.5 (10**(2/3) = 4.6 for the pure law) from 1e-4 to 1e-5 (E-GW, mu 4, 2 delta_y,
   !> loading and unloading at 0.99 delta_max); from 1e-5 to 1e-6 by 5.5 .. 7.1, the
   !> 1e-6 solves being off by several 1e-6 under smaller estimates.
   !> Where a solve of that pair fails, the second pair (2e-5, 2e-4) answers (E-GW, mu 4,
   !> from 2.44 delta_y: the unloading solve at 1e-5 delta_y fails at 0.21 delta_max,
   !> Newton stalling); its correction is checked by its own farther solve alike.
   real(dp), parameter :: wide_sigmas(2, 2) = reshape([1.0e-5_dp, 1.0e-4_dp, 2.0e-5_dp, &
      & 2.0e-4_dp], [2, 2])
   !> sigma/delta_y at or below which a converged solve of small_sigma_limit's models is
   !> checked against the asymptotic route (small_sigma_loading/_unload): there the
   !> route's correction is <= 5 % of P(sigma_1) - P_cap, and discrete solves were found
   !> off by up to 800 times their estimates; at 1e-6 the route's own estimate is often
   !> above 5e-7, so a check there would refuse solves the guided route answers.
   real(dp), parameter :: small_sigma_check_limit = 1.0e-7_dp
   !> As small_sigma_check_limit for the unloading solves of a capped history: there from
   !> 1e-6 (small_sigma_limit) down. Near the residual overlap the discrete solves at
   !> sigma/delta_y = 1e-6 converge off by several times their estimates (E-GW + cap, mu 4,
   !> from 2 delta_y: 0.15 delta_max at rel_tol 2e-5 6.9e-6 off under 1.3e-6; the levels'
   !> answer there moves by 1e-5 .. 4e-4 with the mesh's kink set, doc/stability.md
   !> "Stop 49 (resid15)"), while the route's histories are loaded anyway and its check
   !> costs ~1 s.
   real(dp), parameter :: unload_check_limit = 1.0e-6_dp
   !> the wide solves' rel_tol in asymptotic_unloading's further order, relative to the
   !> solve's (at least validate_options' 1e-10)
   real(dp), parameter :: further_tol = 0.1_dp
   !> The loosest rel_tol of the route's wide histories (route_histories). Near the
   !> residual overlap an unloading force hangs on the history's plastic field (the
   !> residual overlap moves with it); from histories at rel_tol 1e-4 the wide solves at
   !> sigma/delta_y = 1e-5 .. 2e-4 disagreed by 1e-3 of the force there (E-GW, mu 4, from
   !> 2.44 delta_y at 0.197 delta_max: the route refused, estimate 3.7e-4), from 1e-6
   !> histories by 2e-5 (answered within its estimate).
   real(dp), parameter :: wide_history_tol = 1.0e-6_dp
   !> ... and the tightest: a history at a smaller rel_tol keeps its route's wide
   !> histories at this one. From 1e-8 ones (egw_solve_unload's history at 1e-6 delta_y,
   !> rel_tol 1e-5) they took 24 of the first call's 50 s, at 1e-7 ~1 s, and the route's
   !> answers at 0.145 .. 0.18 delta_max were no closer to the references (-8.8e-6,
   !> 1.1e-6, 3.8e-7, 1.0e-6 against -1.4e-6, 6.0e-7, 7.6e-7, 1.2e-6 at 1e-7; E-GW + cap,
   !> mu 4, from 2 delta_y; doc/stability.md "Rough + cap as sigma -> 0"). A history the
   !> route loaded (asymptotic: every unloading solve is the route's, and its rel_tol only
   !> said which route estimate was accepted) keeps them at this one whatever its rel_tol:
   !> at 1e-6 (egw_solve_unload's history at sigma/delta_y = 1e-7 loads only at its rel_tol
   !> 1e-5) 0.15 and 0.145 delta_max were refused (estimates 6.8e-6, 7.9e-6), at 1e-7 they
   !> answer within 1.9e-6 of the references.
   real(dp), parameter :: wide_history_floor = 1.0e-7_dp
   !> load_history's rough field d_max(r) at this fraction of its rel_tol (at least 1e-10;
   !> at rel_tol where that does not converge): its error is not in the unloading solves'
   !> estimates (doc/stability.md "Stop 51 (edge17)"). The route's wide histories keep
   !> theirs at their rel_tol (wide_history_tol, _floor).
   real(dp), parameter :: history_field_tol = 0.1_dp
   !> the unloading's force floor of the route's estimates, relative to P(delta_max)
   real(dp), parameter :: unload_floor = 1.0e-6_dp
   !> The rel_tol of the route's probe (route_floor), and the factor on it that bounds a
   !> probe solve's error (its estimate is no bound: 1.4 times it measured, doc/theory.md
   !> section 12). At sigma/delta_y = 1e-6 from 2 delta_y the route's loading estimate is
   !> 2.7e-7 at every rel_tol (the wide solves at 1e-9 took 24 s to show it); at probe_tol
   !> the four wide solves take ~1 s.
   real(dp), parameter :: probe_tol = 1.0e-7_dp, probe_margin = 10.0_dp

   !> Loading history of one contact: the loading solve at delta_max and its separation
   !> field, from which any number of unloading/reloading solves at delta <= delta_max
   !> follow (solve_unload). Read-only after load_history: one history may serve several
   !> threads at once. Above delta_max the loading curve holds; load a new history there.
   type, public :: loading_history
      logical :: loaded = .false.             !< set by a successful load_history
      type(contact_params) :: params          !< parameters of the loading solve
      type(solver_options) :: options         !< options of the loading and unloading solves
      real(dp) :: delta_max = 0.0_dp          !< largest overlap reached
      type(solve_result) :: loading           !< the loading solve at delta_max
      !> No rough field to remember (Hertz, sigma = 0, or too far apart to touch): the
      !> unloading curve is the loading curve.
      logical :: reversible = .true.
      !> A smooth sphere loaded beyond first yield of the flow-pressure cap: unloading is
      !> cap_unload's (elastic from the deformed shape).
      logical :: capped = .false.
      !> A rough sphere with the cap whose loading never reached p_y (cap_never_acts: no
      !> point of d_max(r) where the loading total can reach it): every unloading solve of
      !> this history is the cap-free one, the same equations (no gap shift, no offset, the
      !> floor never acts) without the cap's fields, kink scans and routes. (Tests set it
      !> false to solve on the cap's routes and compare.)
      logical :: cap_free = .false.
      type(separation_field), private :: closest
      type(cap_history), private :: cap
      !> Loaded by the small-sigma route (its discrete loading did not converge at
      !> sigma/delta_y <= 2e-6, or was replaced by the route's check at <= 1e-7): no rough
      !> field; every unloading solve is the route's.
      logical, private :: asymptotic = .false.
      !> The small-sigma route's own histories, loaded once with this one where the route
      !> may answer or check its unloading solves (asymptotic_applies at delta_max;
      !> route_histories): the rough model's separation fields after loading to delta_max
      !> at wide_sigmas and the smooth cap's loading (egw_cap_limit's three histories,
      !> extrapolated). Every route unloading solve reuses them (it reloaded them before:
      !> 0.5-20 s a solve).
      !> wide_loaded(j) false where a loading of pair j failed (the route then tries the
      !> other pair; it fails where both fail).
      logical, private :: wide_loaded(2) = .false.   !< per pair of wide_sigmas
      type(separation_field), private :: wide(2, 2)
      type(cap_limit), private :: wide_cap
      !> GW's ZMC loading law tabulated once by the caller (load_history's loading): the
      !> law of the unloading solves (empty: the integral).
      type(law_pieces), private :: loading_law
   end type loading_history

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

   !> The history solve_contact_unload loaded last on this thread, with the inputs it was
   !> loaded from: a sweep of overlaps after one delta_max (egw_solve_unload in a loop)
   !> loads it once. A history is a function of those inputs alone, so the results are
   !> those of a fresh load, bit for bit. threadprivate: each thread (OpenMP or the
   !> caller's own) keeps its own, in thread-local storage: no lock, no sharing.
   type :: history_cache
      logical :: valid = .false.
      type(contact_params) :: params
      type(solver_options) :: options
      real(dp) :: delta_max = 0.0_dp
      type(loading_history) :: history
   end type history_cache
   type(history_cache), save :: last_history
   !$omp threadprivate(last_history)


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

   !> Force, stiffness, effective contact radius and maximum pressure at overlap delta
   !> (> 0 overlap, < 0 separation) for any model of params. Hertz (and sigma = 0) in
   !> closed form; the rough models by the discrete solve, refined until the two-level
   !> estimate of the force error is below options%rel_tol/2 (n_radial = 0) or on the mesh
   !> of about n_radial nodes. Fails with egw_not_converged rather than return a doubtful
   !> answer. E-GW (EP-GW at psi = 0) with the cap at sigma/delta_y <= 2e-6 whose
   !> discrete solve does not converge: the asymptotic route (small_sigma_loading,
   !> doc/theory.md §12), if its estimate meets rel_tol; at sigma/delta_y <= 1e-7 a
   !> converged solve of those models is checked against that route
   !> (small_sigma_loading).
   !> Reports progress (egw_progress) as one long call, stage "solve".
   subroutine solve_contact(params, options, delta, result, error, loading)
      !> the contact (model, R, E*, sigma, mu, psi, K, rho_p)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options   !< mesh, tolerance, method and threads
      real(dp), intent(in) :: delta   !< overlap [length]: > 0 pressed together, < 0 apart
      !> force [force] >= 0, stiffness [force/length], contact radius [length], ...
      type(solve_result), intent(out) :: result
      !> allocated on failure (result is then not defined)
      type(egw_error), allocatable, intent(out) :: error
      !> GW's ZMC law of params tabulated once (zmc_law_pieces): the law where its
      !> parameters are params' (a hysteresis build's loading table), else ignored
      type(law_pieces), intent(in), optional :: loading
      if ((params%model == model_hertz .or. params%sigma == 0.0_dp) .and. .not. &
         & params%flow_pressure > 0.0_dp) then
         ! (the closed form, ~80 ns: no progress to report, and no 5 ns spent on it)
         call contact_solve(params, options, delta, result, error)
         return
      end if
      call progress_begin("solve")
      call contact_solve(params, options, delta, result, error, loading)
      call progress_end("solve")
   end subroutine solve_contact

   !> solve_contact's work.
   subroutine contact_solve(params, options, delta, result, error, loading)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta
      type(solve_result), intent(out) :: result
      type(egw_error), allocatable, intent(out) :: error
      type(law_pieces), intent(in), optional :: loading
      type(scaled_problem) :: prob
      type(discrete_solution) :: sol
      type(cap_history) :: cap

      call check_input(params, options, delta, error)
      if (allocated(error)) return
      if (smooth_capped(params, delta)) then
         call cap_loading(params, options, delta, cap, result, error, "delta")
         return
      end if
      if (params%model == model_hertz .or. params%sigma == 0.0_dp) then
         result%force = hertz_force(delta, params%radius, params%modulus)
         result%stiffness = hertz_stiffness(delta, params%radius, params%modulus)
         result%contact_radius = hertz_contact_radius(delta, params%radius)
         result%max_pressure = hertz_pressure(0.0_dp, delta, params%radius, params%modulus)
         ! p0 = (2/pi) E sqrt(delta/R): 2E/(pi R) alone may overflow where p0 does not
         if (delta > 0.0_dp .and. .not. normal(result%max_pressure)) result%max_pressure = &
            & product4(2.0_dp/pi, params%modulus, sqrt(delta), 1.0_dp/sqrt(params%radius))
         result%method_used = options%method
         if (.not. ieee_is_finite(result%max_pressure)) call fatal_error(error, &
            & egw_invalid_argument, "delta = "//format_real(delta)//": the Hertz peak " &
            & //"pressure (2/pi) E sqrt(delta/R) exceeds the largest double")
         return
      end if

      prob = scaled(params, delta, loading)
      if (negligible(prob)) then
         ! Beyond ~37 sigma apart the summit pressure underflows: the force is below
         ! 1e-250 E sqrt(R) sigma**1.5 and is returned as 0 with est_rel_err = 1 (honest:
         ! zero has relative error 1).
         result%method_used = options%method
         result%est_rel_err = 1.0_dp
         return
      end if
      call solve_rough(params, options, prob, sol, result, error)
      call progress_report(0.2_dp, "solve")
      call small_sigma_loading(params, options, delta, prob, result, error)
   end subroutine contact_solve

   !> The asymptotic route after the discrete loading solve of an extended model with
   !> elastic summits with the cap (asymptotic_applies; doc/theory.md §12 "Small sigma"):
   !> a solve that failed with egw_not_converged takes the route's answer if its estimate
   !> meets rel_tol/2; a converged one at sigma/delta_y <= small_sigma_check_limit is
   !> checked against it (use_asymptotic). Nothing changes where the route does not apply
   !> or its own solves fail.
   subroutine small_sigma_loading(params, options, delta, prob, result, error)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta
      type(scaled_problem), intent(in) :: prob
      type(solve_result), intent(inout) :: result
      type(egw_error), allocatable, intent(inout) :: error
      type(solve_result) :: asym
      real(dp) :: delta_y
      logical :: ok, floored
      if (.not. route_wanted(params, options, delta, prob%extended .and. &
         & allocated(prob%cap), error, small_sigma_check_limit, delta_y)) return
      call asymptotic_loading(params, options, delta, delta_y, allocated(error), asym, ok, &
         & floored)
      if (ok) call use_asymptotic(options, delta, asym, 0.0_dp, result, error)
      if (floored .and. allocated(error)) error%message = error%message//"; that estimate " &
         & //"is a lower bound from its solves at rel_tol "//format_real(probe_tol)// &
         & ": tighter solves cannot meet rel_tol/2"
   end subroutine small_sigma_loading

   !> As small_sigma_loading after the discrete unloading solve of a capped history, with
   !> asymptotic_unloading. The route's estimates are relative to max(|P|, floor), floor
   !> unload_floor P(delta_max) or the caller's force_floor (solve_unload's) if larger.
   subroutine small_sigma_unload(history, delta, force_floor, result, error)
      type(loading_history), intent(in) :: history
      real(dp), intent(in) :: delta, force_floor
      type(solve_result), intent(inout) :: result
      type(egw_error), allocatable, intent(inout) :: error
      type(solve_result) :: asym
      real(dp) :: delta_y, floor
      logical :: ok
      if (.not. route_wanted(history%params, history%options, history%delta_max, &
         & history%closest%extended .and. history%closest%capped, error, &
         & unload_check_limit, delta_y)) return
      floor = max(unload_floor*history%loading%force, force_floor)
      call asymptotic_unloading(history, delta, delta_y, floor, asym, ok)
      if (ok) then
         call use_asymptotic(history%options, delta, asym, floor, result, error)
      else if (allocated(error)) then
         error%message = error%message//"; nor by the small-sigma route (fewer than two " &
            & //"of its solves at sigma = 1e-5, 2e-5, 1e-4, 2e-4 delta_y converged)"
      end if
   end subroutine small_sigma_unload

   !> Whether the asymptotic route answers a failed solve (error allocated: only
   !> egw_not_converged) or checks a converged one (sigma/delta_y <= check_limit:
   !> small_sigma_check_limit, unload_check_limit); asymptotic_applies either way.
   !> delta_y of params.
   logical function route_wanted(params, options, delta, capped, error, check_limit, &
      & delta_y) result(wanted)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta
      logical, intent(in) :: capped
      type(egw_error), allocatable, intent(in) :: error
      real(dp), intent(in) :: check_limit
      real(dp), intent(out) :: delta_y
      wanted = asymptotic_applies(params, options, delta, capped, delta_y)
      if (.not. wanted) return
      if (allocated(error)) then
         wanted = error%stat == egw_not_converged
      else
         wanted = params%sigma <= check_limit*delta_y
      end if
   end function route_wanted

   !> The asymptotic route's loading answer at delta (doc/theory.md §12): the smooth cap
   !> model (cap_load on 100/200 rings, its sigma -> 0 limit) plus the rough layer's
   !> sigma**(2/3) correction from the same model's solves at wide_sigmas
   !> (asymptotic_result). ok false when one of those solves fails. After a failed
   !> discrete solve (failed) at rel_tol below probe_tol, the route is first taken at
   !> probe_tol (route_floor): where even a lower bound of its estimate misses rel_tol/2,
   !> that answer, its estimate the bound, is returned at once (floored true) instead of
   !> the wide solves at rel_tol, which cannot meet it (10-14 s each at 1e-9).
   subroutine asymptotic_loading(params, options, delta, delta_y, failed, asym, ok, floored)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta, delta_y
      logical, intent(in) :: failed
      type(solve_result), intent(out) :: asym
      logical, intent(out) :: ok, floored
      type(cap_history) :: history
      type(cap_result) :: cap
      type(solve_result) :: wide(2)
      type(egw_error), allocatable :: cap_error
      integer :: pair
      ok = .false.
      floored = .false.
      call cap_load(params%radius, params%modulus, params%flow_pressure, delta, &
         & cap_options(n_rings=100, n_levels=2), history, cap, cap_error, "delta")
      if (allocated(cap_error)) return
      if (failed .and. options%rel_tol < probe_tol) then
         call route_floor(params, options, delta, delta_y, cap, asym, floored)
         if (floored) then
            ok = .true.
            return
         end if
      end if
      do pair = 1, 2
         call wide_loading(params, options, delta, delta_y, pair, wide, ok)
         if (ok) exit
      end do
      if (.not. ok) return
      call asymptotic_result(params, cap, wide, wide_sigmas(:, pair), 0.0_dp, asym)
   end subroutine asymptotic_loading

   !> The rough model's loading solves at delta at wide_sigmas(:, pair) (options);
   !> ok false where one fails.
   subroutine wide_loading(params, options, delta, delta_y, pair, wide, ok)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta, delta_y
      integer, intent(in) :: pair
      type(solve_result), intent(out) :: wide(2)
      logical, intent(out) :: ok
      type(contact_params) :: wider
      type(scaled_problem) :: wide_prob
      type(discrete_solution) :: sol
      type(egw_error), allocatable :: wide_error
      integer :: k
      do k = 1, 2
         wider = params
         wider%sigma = wide_sigmas(k, pair)*delta_y
         wide_prob = scaled(wider, delta)
         call solve_rough(wider, options, wide_prob, sol, wide(k), wide_error)
         ! (up to 8 such solves after the discrete one: a sign of life; their fractions
         ! are the caller's)
         call progress_note("small-sigma route: loading")
         ok = .not. allocated(wide_error)
         if (.not. ok) return
      end do
   end subroutine wide_loading

   !> Whether the route at options%rel_tol cannot meet rel_tol/2, told from its solves at
   !> probe_tol (doc/theory.md section 12 "Small sigma: the route's floor"). The route's
   !> estimate is the cap solve's (100 rings, whatever rel_tol) plus the disagreement D
   !> of the two wide solves' corrections, D = (P_1 - P_cap) s_1 - (P_2 - P_cap) s_2 (the
   !> next order in sigma, a property of the model, not of rel_tol), plus the wide
   !> solves' errors: tighter wide solves move D by at most s_1 |dP_1| + s_2 |dP_2|,
   !> |dP_j| <= probe_margin probe_tol |P_j| (the probe's error, its estimate <= probe_tol/2,
   !> with a factor 10 for an estimate that is no bound, and the tight solve's, below it).
   !> So (cap error + |D| - that margin)/|P| bounds the tight route's estimate from below
   !> (|P| the probe's answer, less the same margin). floored true where that bound exceeds
   !> rel_tol/2 for every pair of wide_sigmas (the route takes the second pair where a
   !> solve of the first fails): asym is then the probe's answer, est_rel_err the
   !> smallest bound. Nothing is decided (floored false) where a probe solve fails.
   subroutine route_floor(params, options, delta, delta_y, cap, asym, floored)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta, delta_y
      type(cap_result), intent(in) :: cap
      type(solve_result), intent(out) :: asym
      logical, intent(out) :: floored
      type(solver_options) :: probe
      type(solve_result) :: wide(2), answer
      real(dp) :: shrink(2), margin, bound, lowest
      integer :: pair, k
      logical :: ok
      floored = .false.
      probe = options
      probe%rel_tol = probe_tol
      lowest = huge(1.0_dp)
      do pair = 1, 2
         call wide_loading(params, probe, delta, delta_y, pair, wide, ok)
         if (.not. ok) return
         call asymptotic_result(params, cap, wide, wide_sigmas(:, pair), 0.0_dp, answer)
         do k = 1, 2
            shrink(k) = (params%sigma/(wide_sigmas(k, pair)*delta_y))**(2.0_dp/3.0_dp)
         end do
         margin = probe_margin*probe_tol*sum(shrink*abs(wide%force))
         bound = (cap%force_error + abs((wide(1)%force - cap%force)*shrink(1) - &
            & (wide(2)%force - cap%force)*shrink(2)) - margin)/(abs(answer%force) + margin)
         if (.not. bound > 0.5_dp*options%rel_tol) return
         if (bound < lowest) then
            lowest = bound
            asym = answer
         end if
      end do
      asym%est_rel_err = lowest
      floored = .true.
   end subroutine route_floor

   !> The asymptotic route's unloading answer at delta after history: as
   !> asymptotic_loading, with the smooth cap's unloading from delta_max (limit_unload) and
   !> the rough model's histories and unloading solves at wide_sigmas. Where that answer's
   !> estimate misses rel_tol/2 or both pairs fail (near the residual overlap the sigma**(2/3)
   !> term's own next order dominates, and solves at 1e-5 delta_y fail), every wide solve
   !> is tried and the extrapolation in sigma**(2/3) goes one order further
   !> (extrapolated_result); the answer with the smaller estimate is kept.
   subroutine asymptotic_unloading(history, delta, delta_y, floor, asym, ok)
      type(loading_history), intent(in) :: history
      real(dp), intent(in) :: delta, delta_y
      real(dp), intent(in) :: floor   !< of the estimates (small_sigma_unload's)
      type(solve_result), intent(out) :: asym
      logical, intent(out) :: ok
      type(cap_result) :: cap
      type(solve_result) :: wide(2, 2), tight(2, 2), further
      type(egw_error), allocatable :: cap_error
      integer :: solved(2, 2), tight_solved(2, 2)   ! 0 not tried, 1 converged, -1 failed
      integer :: k, pair
      logical :: ok_further
      ok = .false.
      solved = 0
      do pair = 1, 2
         if (.not. history%wide_loaded(pair)) cycle
         do k = 1, 2
            call wide_unload(history, delta, delta_y, k, pair, wide, solved, &
               & history%options%rel_tol)
            if (solved(k, pair) < 0) exit
         end do
         if (all(solved(:, pair) == 1)) exit
      end do
      call limit_unload(history%wide_cap, delta, cap, cap_error)
      if (allocated(cap_error)) return
      if (pair <= 2) then
         call asymptotic_result(history%params, cap, wide(:, pair), wide_sigmas(:, pair), &
            & floor, asym)
         ok = .true.
         if (asym%est_rel_err <= 0.5_dp*history%options%rel_tol) return
      end if
      ! (every wide solve again at rel_tol/10: their estimates enter through weights up
      ! to ~0.5 at sigma/delta_y = 1e-6, and at rel_tol they alone missed rel_tol/2; one
      ! that fails there keeps its answer at rel_tol, or is tried at rel_tol; one that
      ! failed at rel_tol is not tried again: Newton stalls there, 2-8 s a solve)
      do pair = 1, 2
         if (.not. history%wide_loaded(pair)) cycle
         do k = 1, 2
            if (solved(k, pair) < 0) cycle
            tight = wide
            tight_solved = solved
            call wide_unload(history, delta, delta_y, k, pair, tight, tight_solved, &
               & max(further_tol*history%options%rel_tol, 1.0e-10_dp))
            if (tight_solved(k, pair) == 1) then
               wide(k, pair) = tight(k, pair)
               solved(k, pair) = 1
            else if (solved(k, pair) == 0) then
               call wide_unload(history, delta, delta_y, k, pair, wide, solved, &
                  & history%options%rel_tol)
            end if
         end do
      end do
      if (count(solved == 1) < 2) return
      call extrapolated_result(history%params, cap, pack(wide, solved == 1), &
         & pack(wide_sigmas, solved == 1), floor, further, &
         & ok_further)
      if (.not. ok_further) return
      if (ok) then
         if (further%est_rel_err >= asym%est_rel_err) return
      end if
      asym = further
      ok = .true.
   end subroutine asymptotic_unloading

   !> The rough unloading solve at delta of the route's history at wide_sigmas(k, pair),
   !> at rel_tol; solved(k, pair) 1 where it converged (wide(k, pair) its result), -1
   !> where it failed.
   subroutine wide_unload(history, delta, delta_y, k, pair, wide, solved, rel_tol)
      type(loading_history), intent(in) :: history
      real(dp), intent(in) :: delta, delta_y, rel_tol
      integer, intent(in) :: k, pair
      type(solve_result), intent(inout) :: wide(2, 2)
      integer, intent(inout) :: solved(2, 2)
      type(contact_params) :: wider
      type(solver_options) :: options
      type(egw_error), allocatable :: wide_error
      wider = history%params
      wider%sigma = wide_sigmas(k, pair)*delta_y
      options = history%options
      options%rel_tol = rel_tol
      call rough_unload(wider, options, history%wide(k, pair), delta, wide(k, pair), &
         & wide_error)
      solved(k, pair) = merge(-1, 1, allocated(wide_error))
      ! (at most 4 solves at rel_tol, then 4 tighter: 0.2 .. 1 of the unloading call, the
      ! pairs' solves at rel_tol counted by k + 2 pair - 2, the tighter ones by 4 more)
      call progress_report(0.2_dp + 0.1_dp*real(2*pair + k - 2 + merge(4, 0, &
         & rel_tol < history%options%rel_tol), dp), "small-sigma route: unloading")
   end subroutine wide_unload

   !> The small-sigma route's histories of hist (loaded, its params and options; see
   !> loading_history%wide_loaded), where the route may answer or check its unloading
   !> solves: the rough model loaded to delta_max at wide_sigmas (load_history, as the
   !> route's unloading solves did each time before) and the smooth cap's limit_load (three
   !> ring counts: one cap history's estimate misses its plastic field's error, which put
   !> the route's answers up to 7e-7 off under estimates of 3.4e-7; egw_cap_limit).
   !> Nothing where the route does not apply; wide_loaded false where a loading fails.
   recursive subroutine route_histories(hist)
      type(loading_history), intent(inout) :: hist
      type(contact_params) :: wider
      type(loading_history) :: wide_history
      type(solver_options) :: wide_options
      type(cap_result) :: cap
      type(solve_result) :: res
      type(egw_error), allocatable :: wide_error
      real(dp) :: delta_y
      integer :: k, pair
      logical :: loaded
      hist%wide_loaded = .false.
      if (.not. asymptotic_applies(hist%params, hist%options, hist%delta_max, &
         & hist%closest%extended .and. hist%closest%capped, delta_y)) return
      wide_options = hist%options
      wide_options%rel_tol = min(max(hist%options%rel_tol, wide_history_floor), &
         & wide_history_tol)
      if (hist%asymptotic) wide_options%rel_tol = wide_history_floor
      call limit_load(hist%params%radius, hist%params%modulus, hist%params%flow_pressure, &
         & hist%delta_max, hist%wide_cap, cap, wide_error)
      if (allocated(wide_error)) return
      do pair = 1, 2
         loaded = .true.
         do k = 1, 2
            wider = hist%params
            wider%sigma = wide_sigmas(k, pair)*delta_y
            ! (the route's histories: 0.6 .. 1 of the history's call, a quarter each; its
            ! discrete loading solve takes the most, 16 of 17 s at 1e-6 from 2 delta_y)
            call progress_part(0.6_dp + 0.1_dp*real(2*pair + k - 3, dp), &
               & 0.6_dp + 0.1_dp*real(2*pair + k - 2, dp))
            call progress_begin("history")
            call history_load(wider, wide_options, hist%delta_max, wide_history, res, &
               & wide_error, 1.0_dp)
            call progress_end("history")
            ! (above first yield at sigma = 1e-5 .. 2e-4 delta_y: a rough field, never
            ! the route's, reversible or smooth)
            loaded = .not. allocated(wide_error)
            if (loaded) loaded = .not. (wide_history%reversible .or. &
               & wide_history%capped .or. wide_history%asymptotic)
            if (.not. loaded) exit
            hist%wide(k, pair) = wide_history%closest
         end do
         if (allocated(wide_error)) deallocate (wide_error)
         hist%wide_loaded(pair) = loaded
      end do
   end subroutine route_histories

   !> Whether the asymptotic route may answer or check a solve (an extended model with the
   !> cap that acted, beyond first yield at delta, sigma/delta_y <= small_sigma_limit, no
   !> fixed mesh); delta_y of params. Elastic summits only (E-GW, EP-GW at psi = 0), whose
   !> layer's compliance is the sigma**(2/3) law: plastic summits (EP-GW, psi 1) carry the
   !> deep pressure like F_1, a sigma**(1/2) law, and their differences from the smooth cap
   !> fell by 5.3, then 3.7 from 1e-4 to 1e-6 delta_y (3 delta_y), where a 2/3 law scaled
   !> from 1e-5 delta_y to 1e-8 would be off by ~1e-6 under an estimate of ~1e-7 (the two
   !> corrections' disagreement does not show an exponent error that far down).
   logical function asymptotic_applies(params, options, delta, capped, delta_y) &
      & result(applies)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta
      logical, intent(in) :: capped
      real(dp), intent(out) :: delta_y
      real(dp) :: a_y, force_y
      applies = .false.
      delta_y = 0.0_dp
      if (options%n_radial > 0 .or. .not. capped) return
      if (.not. (params%model == model_egw .or. (params%model == model_epgw .and. &
         & params%psi == 0.0_dp))) return
      if (.not. above_first_yield(params, delta)) return
      call cap_units(params%radius, params%modulus, params%flow_pressure, delta_y, a_y, &
         & force_y)
      applies = params%sigma <= small_sigma_limit*delta_y
   end function asymptotic_applies

   !> The asymptotic route's answer (doc/theory.md §12 "Small sigma: the asymptotic
   !> route"): P(sigma) = P_cap + C sigma**(2/3), the rough layer's compliance (gap ~
   !> sigma (p/(mu E* sqrt(sigma/R)))**(2/3)) on the smooth cap model (cap, its sigma -> 0
   !> limit), C from the rough model's solve at sigmas(1) (a pair of wide_sigmas; wide(1));
   !> stiffness and contact radius alike, the maximum pressure p_y. est_rel_err: the cap solve's
   !> estimate, wide(1)'s times its factor, and the disagreement of the two solves'
   !> corrections at sigma (it bounds the neglected terms when they are of order sigma
   !> or higher, and shows an exponent other than 2/3), relative to max(|P|, floor)
   !> (huge where that is 0).
   subroutine asymptotic_result(params, cap, wide, sigmas, floor, asym)
      type(contact_params), intent(in) :: params
      type(cap_result), intent(in) :: cap
      type(solve_result), intent(in) :: wide(2)
      real(dp), intent(in) :: sigmas(2)   !< sigma/delta_y of wide
      real(dp), intent(in) :: floor
      type(solve_result), intent(out) :: asym
      real(dp) :: delta_y, a_y, force_y, shrink(2), total, wide_error
      integer :: k
      call cap_units(params%radius, params%modulus, params%flow_pressure, delta_y, a_y, &
         & force_y)
      do k = 1, 2
         shrink(k) = (params%sigma/(sigmas(k)*delta_y))**(2.0_dp/3.0_dp)
      end do
      asym = wide(1)
      asym%force = cap%force + (wide(1)%force - cap%force)*shrink(1)
      asym%stiffness = cap%stiffness + (wide(1)%stiffness - cap%stiffness)*shrink(1)
      ! (the cap's a*, the rough solver's definition: its edge a is up to 3 pi/8 smaller)
      asym%contact_radius = cap%effective_radius + (wide(1)%contact_radius - &
         & cap%effective_radius)*shrink(1)
      asym%max_pressure = params%flow_pressure
      total = max(abs(asym%force), floor)
      ! (a wide solve's force 0 is the underflow answer, est_rel_err 1 by convention: its
      ! absolute error is below the underflow threshold, not est_rel_err times the floor;
      ! unloading below the residual overlap from 10 delta_y at sigma/delta_y = 1e-10
      ! was refused with an estimate of exactly shrink(1) for it)
      wide_error = 0.0_dp
      if (wide(1)%force /= 0.0_dp) wide_error = wide(1)%est_rel_err*abs(wide(1)%force)
      asym%est_rel_err = huge(1.0_dp)
      if (total > 0.0_dp) asym%est_rel_err = (cap%force_error + shrink(1)*wide_error &
         & + abs((wide(1)%force - cap%force)*shrink(1) - (wide(2)%force - cap%force)* &
         & shrink(2)))/total
   end subroutine asymptotic_result

   !> The asymptotic route one order further (asymptotic_unloading's fallback; doc/theory.md
   !> section 12 "Small sigma: near the residual overlap"). The rough model's expansion
   !> P(sigma) = P_cap + A s + B s**2 + ..., s = sigma**(2/3), seen from a wide solve at
   !> sigma_j: e_j = (P_j - P_cap)/x_j, x_j = (sigma_j/sigma)**(2/3), is
   !> A s + B s**2 x_j + ..., a polynomial in x_j whose value at x = 1 is P(sigma) - P_cap.
   !> asymptotic_result takes e_1 (order 0). Here, with n >= 3 wide solves, the line
   !> through the two smallest sigmas' (x_1, e_1), (x_2, e_2) at x = 1 (order 1), its
   !> error the difference from the parabola through the three smallest (order 2); with
   !> n = 2, e_1 with the difference from that line (order 0, its error estimated as
   !> asymptotic_result's is not: it used |e_1 - e_2|, which for a pair 2 apart in sigma
   !> is 0.6 times e_1's error, for 10 apart 3.6 times). The order with the smaller
   !> estimate answers. est_rel_err: that difference, plus the cap solve's and the wide
   !> solves' estimates through the weights (the latter at both orders used), relative to
   !> max(|P|, floor). Stiffness and contact radius with the same weights; the force is
   !> kept >= 0. ok false with fewer than two wide solves.
   subroutine extrapolated_result(params, cap, wide, sigmas, floor, asym, ok)
      type(contact_params), intent(in) :: params
      type(cap_result), intent(in) :: cap
      type(solve_result), intent(in) :: wide(:)   !< converged wide solves
      real(dp), intent(in) :: sigmas(:)           !< their sigma/delta_y
      real(dp), intent(in) :: floor
      type(solve_result), intent(out) :: asym
      logical, intent(out) :: ok
      real(dp) :: delta_y, a_y, force_y, x(size(wide)), noise(size(wide)), lower(3), &
         & higher(3), est(2), total
      integer :: order(size(wide)), i, j, n, best
      n = size(wide)
      ok = n >= 2
      if (.not. ok) return
      call cap_units(params%radius, params%modulus, params%flow_pressure, delta_y, a_y, &
         & force_y)
      ! increasing sigma
      order = [(i, i = 1, n)]
      do i = 2, n
         j = i
         do while (j > 1)
            if (sigmas(order(j - 1)) <= sigmas(order(j))) exit
            order([j - 1, j]) = order([j, j - 1])
            j = j - 1
         end do
      end do
      do i = 1, n
         x(i) = (sigmas(order(i))*delta_y/params%sigma)**(2.0_dp/3.0_dp)
         associate (w => wide(order(i)))
            ! (a force 0 with est_rel_err 1 is the underflow answer: error below underflow)
            noise(i) = 0.0_dp
            if (w%force /= 0.0_dp) noise(i) = w%est_rel_err*abs(w%force)
         end associate
      end do
      est = huge(1.0_dp)
      do best = 1, min(2, n - 1)
         ! order best - 1 against order best
         lower = extrapolate(best)
         higher = extrapolate(best + 1)
         total = max(abs(lower(1)), floor)
         if (total > 0.0_dp) est(best) = (abs(higher(1) - lower(1)) + cap%force_error* &
            & (1.0_dp + spread(best) + spread(best + 1)) + error_sum(best) + &
            & error_sum(best + 1))/total
      end do
      best = minloc(est, 1)
      lower = extrapolate(best)
      asym = wide(order(1))
      asym%force = max(lower(1), 0.0_dp)
      asym%stiffness = lower(2)
      asym%contact_radius = lower(3)
      asym%max_pressure = params%flow_pressure
      asym%est_rel_err = est(best)
   contains
      !> Lagrange weights at x = 1 of the m smallest sigmas' nodes.
      pure function weights(m) result(w)
         integer, intent(in) :: m
         real(dp) :: w(m)
         integer :: p, q
         w = 1.0_dp
         do p = 1, m
            do q = 1, m
               if (q /= p) w(p) = w(p)*(1.0_dp - x(q))/(x(p) - x(q))
            end do
         end do
      end function weights
      !> force, stiffness, contact radius extrapolated from the m smallest sigmas
      pure function extrapolate(m) result(q)
         integer, intent(in) :: m
         real(dp) :: q(3), w(m)
         integer :: p
         w = weights(m)
         q = [cap%force, cap%stiffness, cap%effective_radius]
         do p = 1, m
            associate (v => wide(order(p)))
               q = q + w(p)/x(p)*([v%force, v%stiffness, v%contact_radius] - &
                  & [cap%force, cap%stiffness, cap%effective_radius])
            end associate
         end do
      end function extrapolate
      pure real(dp) function spread(m)
         integer, intent(in) :: m
         spread = sum(abs(weights(m))/x(1:m))
      end function spread
      pure real(dp) function error_sum(m)
         integer, intent(in) :: m
         error_sum = sum(abs(weights(m))/x(1:m)*noise(1:m))
      end function error_sum
   end subroutine extrapolated_result

   !> The asymptotic route's answer asym after a discrete solve at delta. A failed solve
   !> (error allocated) takes it if its estimate meets rel_tol/2 (result written, error
   !> deallocated), else error's message names the route's estimate. A converged one
   !> (result) stands where the two forces differ by at most their estimates together
   !> (relative to max(|P|, floor)); else the route's answer replaces it if that meets
   !> rel_tol/2, or error (egw_not_converged) names both.
   subroutine use_asymptotic(options, delta, asym, floor, result, error)
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta, floor
      type(solve_result), intent(in) :: asym
      type(solve_result), intent(inout) :: result
      type(egw_error), allocatable, intent(inout) :: error
      logical :: meets
      meets = asym%est_rel_err <= 0.5_dp*options%rel_tol
      ! (a failed solve where the smooth cap and the wide solves give force 0 alike, below
      ! the residual overlap and the rough tail's underflow: 0 with est_rel_err 1, as
      ! negligible())
      if (allocated(error) .and. asym%force == 0.0_dp .and. meets) then
         deallocate (error)
         result = asym
         result%est_rel_err = 1.0_dp
         return
      end if
      if (allocated(error)) then
         if (.not. meets) then
            error%message = error%message//"; the small-sigma route's estimate " &
               & //format_real(asym%est_rel_err)//" misses rel_tol/2 = " &
               & //format_real(0.5_dp*options%rel_tol)//" (doc/theory.md section 12)"
            return
         end if
         deallocate (error)
      else
         if (abs(result%force - asym%force) <= result%est_rel_err*abs(result%force) + &
            & asym%est_rel_err*max(abs(asym%force), floor)) return
         if (.not. meets) then
            call fatal_error(error, egw_not_converged, "delta = "//format_real(delta)// &
               & ": the discrete solve (force "//format_real(result%force)//", estimate " &
               & //format_real(result%est_rel_err)//") and the small-sigma route (force "// &
               & format_real(asym%force)//", estimate "//format_real(asym%est_rel_err)// &
               & ") disagree beyond their estimates (doc/theory.md section 12)")
            return
         end if
      end if
      result = asym
      ! (the route's estimate is relative to max(|P|, floor): the user's to |P|)
      result%est_rel_err = relative_to_force(asym%est_rel_err, floor, abs(asym%force))
   end subroutine use_asymptotic

   !> An error estimate relative to max(force, floor) (force >= 0) as one relative to force
   !> (solve_result%est_rel_err): 1 for force 0 (its error relative to the true force),
   !> huge(1.0) where the quotient would overflow.
   pure real(dp) function relative_to_force(est, floor, force) result(rel)
      real(dp), intent(in) :: est, floor, force
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

   !> Loading solve of a sphere whose local pressure is a rough-flat law of the caller's
   !> (a tabulated, Persson or BEM law; doc/theory.md §11): the law gives the whole
   !> pressure p(u) at the local mean separation u(r) = r**2/(2R) - delta + w(r), w the
   !> half-space deflection, so delta is the overlap with the law's reference plane (the
   !> mean plane of the heights for those laws). Of params only radius and modulus are
   !> used (R and E* of the pair); the solve is scaled by the law's length. Result and
   !> errors as solve_contact; also egw_invalid_parameter when the law was made with
   !> another E* than params%modulus.
   subroutine solve_contact_law(params, law, options, delta, result, error)
      type(contact_params), intent(in) :: params   !< radius R and modulus E*
      class(flat_law), intent(in) :: law           !< the rough-flat law p(u)
      type(solver_options), intent(in) :: options  !< mesh, tolerance, method and threads
      real(dp), intent(in) :: delta   !< overlap [length] with the law's reference plane
      type(solve_result), intent(out) :: result   !< force, stiffness, radius ... at delta
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      type(contact_params) :: lp
      type(scaled_problem) :: prob
      type(discrete_solution) :: sol

      lp = contact_params(model=model_flat_law, radius=params%radius, &
         & modulus=params%modulus, sigma=law%length(), flow_pressure=params%flow_pressure)
      call check_input(lp, options, delta, error, allow_flat_law=.true.)
      if (allocated(error)) then
         error%message = "flat law of length "//format_real(law%length())//": " &
            & //error%message
         return
      end if
      if (law%modulus() > 0.0_dp .and. abs(params%modulus - law%modulus()) > &
         & 1.0e-12_dp*law%modulus()) then
         call fatal_error(error, egw_invalid_parameter, "modulus = " &
            & //format_real(params%modulus)//": the flat law was made with E* = " &
            & //format_real(law%modulus())//"; the sphere must have the same")
         return
      end if
      prob = scaled(lp, delta)
      call law%rescaled(law%length(), pressure_unit(lp), prob%law)
      ! (the cap's root is the given law's)
      if (allocated(prob%cap)) call prob%cap%prepare(prob%law)
      if (negligible(prob)) then
         result%method_used = options%method
         result%est_rel_err = 1.0_dp
         return
      end if
      call solve_rough(lp, options, prob, sol, result, error)
   end subroutine solve_contact_law

   !> The discrete solve of a rough scaled problem (loading, or unloading when
   !> prob%closest is allocated), its stiffness, and the result in the caller's units.
   !> result is only written on success.
   subroutine solve_rough(params, options, prob, sol, result, error, warm, work, moved_rate)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(out) :: sol
      type(solve_result), intent(inout) :: result
      type(egw_error), allocatable, intent(out) :: error
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

   !> Load to delta_max and keep what unloading needs (the loading solve's separation
   !> field d_max(r)); result is the loading solve at delta_max. Errors as solve_contact
   !> (delta_max not finite: egw_invalid_argument naming delta_max); history and result
   !> are left untouched on any error. A delta_max so far apart that the summit pressure
   !> underflows (force 0, as solve_contact) gives a reversible history: nothing touched.
   !> Reports progress (egw_progress) as one long call, stage "history".
   recursive subroutine load_history(params, options, delta_max, history, result, error, &
      & loading, stiffness)
      type(contact_params), intent(in) :: params   !< the contact
      !> of the loading solve and of the unloading solves that follow
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta_max              !< largest overlap reached
      !> the contact's history; untouched on error
      type(loading_history), intent(inout) :: history
      type(solve_result), intent(inout) :: result   !< the loading solve at delta_max
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      !> GW's ZMC law of params tabulated once (zmc_law_pieces), the law of the loading
      !> solve and of the unloading solves that follow (one table for many histories of
      !> one build); ignored where its parameters are not params'
      type(law_pieces), intent(in), optional :: loading
      !> .false.: result's (and the history's) loading stiffness may be the implicit one
      !> (with the cap ~1e-3 off; it saves the three moved-mesh solves of solve_rough, at
      !> the history's tight rel_tol), for callers that use its force only (the table
      !> builds' curves); default .true.
      logical, intent(in), optional :: stiffness
      logical :: moved_rate
      moved_rate = .true.
      if (present(stiffness)) moved_rate = stiffness
      call progress_begin("history")
      call history_load(params, options, delta_max, history, result, error, history_field_tol, &
         & moved_rate, loading)
      if (present(loading) .and. .not. allocated(error)) history%loading_law = loading
      call progress_end("history")
   end subroutine load_history

   !> load_history's work.
   recursive subroutine history_load(params, options, delta_max, history, result, error, &
      & field_tol, moved_rate, loading)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta_max
      !> the rough field's rel_tol as a fraction of options%rel_tol (history_field_tol; 1
      !> for unload_from_scratch's histories, loaded at 1e-4 of the solve's already)
      real(dp), intent(in) :: field_tol
      !> load_history's stiffness (absent: .true.)
      logical, intent(in), optional :: moved_rate
      type(loading_history), intent(inout) :: history
      type(solve_result), intent(inout) :: result
      type(egw_error), allocatable, intent(out) :: error
      !> the tabulated ZMC law of params (load_history's), the loading solve's law: the
      !> integral's values to ~5e-13, at ~1/10 of its cost (issue 32: the loading solves
      !> of a psi 1 build spent ~8 % of its CPU in the integral, most in the cap's
      !> moved-mesh stiffness)
      type(law_pieces), intent(in), optional :: loading
      type(loading_history) :: hist
      type(scaled_problem) :: prob
      type(discrete_solution) :: sol
      type(solve_result) :: checked
      type(solver_options) :: field

      call check_unload_input(params, options, 0.0_dp, delta_max, error)
      if (allocated(error)) return
      if (params%model /= model_hertz) call check_scaled_overlap("delta_max", delta_max, &
         & params%sigma, error)
      if (allocated(error)) return
      if (params%model /= model_hertz .and. params%sigma > 0.0_dp) &
         & call check_cap_overlap("delta_max", delta_max, params, error)
      if (allocated(error)) return
      hist%params = params
      hist%options = options
      hist%delta_max = delta_max
      hist%capped = smooth_capped(params, delta_max)
      hist%reversible = (params%model == model_hertz .or. params%sigma == 0.0_dp) .and. &
         & .not. hist%capped
      if (.not. (hist%reversible .or. hist%capped)) then
         prob = scaled(params, delta_max, loading)
         hist%reversible = negligible(prob)
      end if
      if (hist%capped) then
         call cap_loading(params, options, delta_max, hist%cap, hist%loading, error, "delta_max")
         if (allocated(error)) return
      else if (hist%reversible) then
         call solve_contact(params, options, delta_max, hist%loading, error)
         if (allocated(error)) return
      else
         ! The field d_max(r) at field_tol of rel_tol (at least 1e-10): its error
         ! is not in the unloading solves' estimates, and near the unloading force's edge
         ! it dominates them (E-GW + cap, mu 4, sigma = delta_y/100, from 2.3 delta_y at
         ! 9.5e-4 P(m): 2.4e-6 P(m) off from fields at rel_tol 1e-6 .. 1e-4, whatever the
         ! unloading solve's rel_tol; 3e-8 from one at 1e-7; doc/stability.md "Stop 51
         ! (edge17)"). Where it does not converge, the field at rel_tol.
         field = options
         ! (never looser than asked: a rel_tol below 1e-10 keeps its own)
         field%rel_tol = min(options%rel_tol, max(1.0e-10_dp, field_tol*options%rel_tol))
         call solve_rough(params, field, prob, sol, hist%loading, error, &
            & moved_rate=moved_rate)
         if (allocated(error)) then
            if (error%stat == egw_not_converged .and. field%rel_tol < options%rel_tol) then
               deallocate (error)
               call solve_rough(params, options, prob, sol, hist%loading, error, &
                  & moved_rate=moved_rate)
            end if
         end if
         call progress_report(0.6_dp, "history: loading")
         if (allocated(error)) then
            ! A capped loading that does not converge at sigma/delta_y <= 2e-6 (E-GW,
            ! EP-GW at psi 0): the small-sigma route answers it (its estimate meeting
            ! rel_tol/2), and then every unloading solve of this history (no rough field
            ! to keep; doc/theory.md section 12 "Small sigma: the asymptotic route").
            call small_sigma_loading(params, options, delta_max, prob, hist%loading, error)
            if (allocated(error)) return
            call asymptotic_history(params, prob, hist, history, result)
            return
         end if
         ! ... and a converged one at sigma/delta_y <= 1e-7 is checked against the route
         ! as solve_contact's (10 delta_y at sigma/delta_y = 1e-10: 1.28e-5 above the
         ! smooth cap under an estimate of 1.5e-8); where the route's answer replaces it,
         ! the rough field is not trusted either: the route's history.
         checked = hist%loading
         call small_sigma_loading(params, options, delta_max, prob, hist%loading, error)
         if (allocated(error)) return
         if (hist%loading%force /= checked%force) then
            call asymptotic_history(params, prob, hist, history, result)
            return
         end if
         hist%closest%extended = prob%extended
         hist%closest%delta = prob%delta
         ! the cap acted (capped points: dp/dh = 0 at a nonzero pressure)
         hist%closest%capped = allocated(prob%cap) .and. any(sol%dpdh == 0.0_dp .and. &
            & sol%p /= 0.0_dp)
         hist%closest%force = smooth_force(prob) + sol%force
         call move_alloc(sol%w, hist%closest%w)
         hist%closest%mesh = sol%mesh
         hist%cap_free = cap_never_acts(prob, hist%closest)
         call route_histories(hist)
      end if
      hist%loaded = .true.
      result = hist%loading
      call move_history(hist, history)
   end subroutine history_load

   !> load_history's end where the small-sigma route answered the loading (hist%loading):
   !> a history without rough field whose unloading solves are the route's.
   recursive subroutine asymptotic_history(params, prob, hist, history, result)
      type(contact_params), intent(in) :: params
      type(scaled_problem), intent(in) :: prob
      type(loading_history), intent(inout) :: hist, history
      type(solve_result), intent(inout) :: result
      hist%asymptotic = .true.
      hist%closest%extended = prob%extended
      hist%closest%delta = prob%delta
      hist%closest%capped = .true.
      hist%closest%force = hist%loading%force/force_unit(params)
      hist%loaded = .true.
      call route_histories(hist)
      result = hist%loading
      call move_history(hist, history)
   end subroutine asymptotic_history

   !> history <- hist without copying the arrays.
   pure subroutine move_history(hist, history)
      type(loading_history), intent(inout) :: hist
      type(loading_history), intent(inout) :: history
      history%loaded = hist%loaded
      history%params = hist%params
      history%options = hist%options
      history%delta_max = hist%delta_max
      history%loading = hist%loading
      history%reversible = hist%reversible
      history%capped = hist%capped
      history%cap_free = hist%cap_free
      history%cap = hist%cap
      history%asymptotic = hist%asymptotic
      history%wide_loaded = hist%wide_loaded
      history%wide = hist%wide
      history%wide_cap = hist%wide_cap
      history%closest%extended = hist%closest%extended
      history%closest%delta = hist%closest%delta
      history%closest%capped = hist%closest%capped
      history%closest%force = hist%closest%force
      history%closest%mesh = hist%closest%mesh
      if (allocated(history%closest%w)) deallocate (history%closest%w)
      if (allocated(hist%closest%w)) call move_alloc(hist%closest%w, history%closest%w)
   end subroutine move_history

   !> Unloading/reloading solve at overlap delta after loading to history%delta_max:
   !> delta < delta_max solves doc/theory.md §5 with the unloading law p_G = C sigma**1.5
   !> Z_u(d/sigma, d_max/sigma) (the loading law wherever d(r) < d_max(r)); delta =
   !> delta_max returns the history's loading solve; delta > delta_max is the loading
   !> solve (the curve has left the history: load a new one). Same meshes, Newton, error
   !> estimate, stiffness (dP/d(delta) at fixed history) and egw_not_converged contract
   !> as solve_contact (after a capped loading at sigma/delta_y <= 2e-6 the asymptotic
   !> route too: small_sigma_unload). history is only read: thread-safe. result untouched
   !> on error. force_floor: where the caller needs the force only to an absolute error
   !> (restitution's work integral), the route's estimates are relative to at least it.
   !> Reports progress (egw_progress) as one long call, stage "unloading".
   subroutine solve_unload(history, delta, result, error, start, force_floor)
      type(loading_history), intent(in) :: history   !< from load_history (only read)
      real(dp), intent(in) :: delta                  !< overlap (> 0), separation (< 0)
      type(solve_result), intent(inout) :: result   !< the solve at delta; untouched on error
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      !> the caller's start for solves of this history: read (if of this history) and
      !> replaced by this solve's deflection; the result is the same to the solve's
      !> tolerance with or without it
      type(unload_start), intent(inout), optional :: start
      !> [force] >= 0: the small-sigma route's estimates relative to max(|P|, force_floor)
      !> (default 0: relative to |P|, at least 1e-6 P(delta_max))
      real(dp), intent(in), optional :: force_floor
      call progress_begin("unloading")
      call unload_solve(history, delta, result, error, start, force_floor)
      call progress_end("unloading")
   end subroutine solve_unload

   !> solve_unload's work.
   subroutine unload_solve(history, delta, result, error, start, force_floor)
      type(loading_history), intent(in) :: history
      real(dp), intent(in) :: delta
      type(solve_result), intent(inout) :: result
      type(egw_error), allocatable, intent(out) :: error
      type(unload_start), intent(inout), optional :: start
      real(dp), intent(in), optional :: force_floor
      type(scaled_problem) :: prob
      type(solve_result) :: res
      type(cap_result) :: cres
      real(dp) :: floor

      if (.not. history%loaded) then
         call fatal_error(error, egw_invalid_argument, &
            & "history: not loaded (call load_history first)")
         return
      end if
      if (.not. ieee_is_finite(delta)) then
         call fatal_error(error, egw_invalid_argument, "delta = "//format_real(delta) &
            & //": the overlap must be finite")
         return
      end if
      if (delta == history%delta_max) then
         result = history%loading
         return
      end if
      if (delta > history%delta_max .or. history%reversible) then
         call solve_contact(history%params, history%options, delta, res, error)
         if (.not. allocated(error)) result = res
         return
      end if
      if (history%capped) then
         call cap_unload(history%cap, delta, cres, error)
         if (.not. allocated(error)) call put_cap_result(cres, history%options, result)
         return
      end if
      ! (with the tabulated law: scaled prepares the cap on the law, ~8 evaluations)
      prob = scaled(history%params, delta, history%loading_law)
      if (negligible(prob)) then
         ! Unloading never presses harder than loading at the same delta (Z_u <= Z).
         res%method_used = history%options%method
         res%est_rel_err = 1.0_dp
         result = res
         return
      end if
      if (history%asymptotic) then
         ! (the small-sigma route's history: its answer, or the failure naming its estimate)
         call fatal_error(error, egw_not_converged, "delta = "//format_real(delta)// &
            & ": the history was loaded by the small-sigma route (its discrete " &
            & //"loading failed or was replaced), so only that route answers its unloading")
      else
         call rough_unload(history%params, history%options, history%closest, delta, res, &
            & error, start, history%loading_law, history%cap_free)
         call progress_report(0.2_dp, "unloading")
      end if
      floor = 0.0_dp
      if (present(force_floor)) floor = force_floor
      call small_sigma_unload(history, delta, floor, res, error)
      if (.not. allocated(error)) result = res
   end subroutine unload_solve

   !> The discrete unloading solve of a rough history (solve_unload's, without the
   !> asymptotic route); cap_free: the history's (loading_history%cap_free), the cap left out.
   subroutine rough_unload(params, options, closest, delta, result, error, start, loading, &
      & cap_free)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      type(separation_field), intent(in) :: closest   !< the history's loading field
      real(dp), intent(in) :: delta
      type(solve_result), intent(inout) :: result
      type(egw_error), allocatable, intent(out) :: error
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

   !> One unloading solve from scratch: load to delta_max, then solve_unload at delta
   !> (delta >= delta_max: just the loading solve at delta). The history is loaded at
   !> 1e-4 rel_tol (at least 1e-10): the unloading solve's estimate cannot see its error;
   !> where it does not converge at 1e-3, then 1e-2 rel_tol, then at rel_tol. The last
   !> history is kept per thread (history_cache): calls with the same params,
   !> options and delta_max load it once, with the same results. For several turning
   !> points at once use load_history (as tightly) and solve_unload. Errors as
   !> load_history and solve_unload; result untouched on error.
   !> Reports progress (egw_progress) as one long call, stage "unloading": the history's
   !> loading (its tries) in 0 .. 0.9, the unloading solve in 0.9 .. 1.
   subroutine solve_contact_unload(params, options, delta, delta_max, result, error)
      type(contact_params), intent(in) :: params   !< the contact
      !> of the unloading solve (the history is loaded tighter)
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta        !< overlap of this solve
      real(dp), intent(in) :: delta_max    !< largest overlap reached before
      type(solve_result), intent(inout) :: result   !< the solve at delta; untouched on error
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      call progress_begin("unloading")
      call unload_from_scratch(params, options, delta, delta_max, result, error)
      call progress_end("unloading")
   end subroutine solve_contact_unload

   !> solve_contact_unload's work.
   subroutine unload_from_scratch(params, options, delta, delta_max, result, error)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta, delta_max
      type(solve_result), intent(inout) :: result
      type(egw_error), allocatable, intent(out) :: error
      type(solve_result) :: loaded, res
      type(solver_options) :: tight
      !> the history's rel_tol as fractions of the solve's, tried in turn
      real(dp), parameter :: history_steps(4) = [1.0e-4_dp, 1.0e-3_dp, 1.0e-2_dp, 1.0_dp]
      integer :: step

      call check_unload_input(params, options, delta, delta_max, error)
      if (allocated(error)) return
      if (delta >= delta_max) then
         ! at or above the turning point: the loading solve itself (the history below is
         ! loaded more tightly than rel_tol)
         call progress_part(0.0_dp, 1.0_dp)
         call solve_contact(params, options, delta, res, error)
         if (.not. allocated(error)) result = res
         return
      end if
      if (.not. cached(last_history, params, options, delta_max)) then
         ! The history at 1e-4 of rel_tol (at least 1e-10): the unloading force below a
         ! separated or far-unloaded contact can be 1e-3..1e-20 of the loading force, and
         ! the field d_max(r) it was loaded with is shared by both of the unloading solve's
         ! levels, so its error is not in their estimate; nor is it bounded by the loading
         ! force's estimate. psi 10, delta -0.8 sigma after delta_max 10 sigma (mu 4):
         ! 6.0e-7 off the independent reference with histories at 1e-7..1e-9 (at every
         ! unloading rel_tol), 4e-10 at 1e-10; delta -1.0: 5.8e-7 at 1e-9 (also psi 10,
         ! delta_max 2: 1.0e-7 -> 4e-10; psi 5, delta -1.6 after 2: 1.9e-7 -> 2e-10).
         ! Where that history does not converge, 10 and 100 times looser ones, then the
         ! one at rel_tol: near the residual overlap a looser history's error is not small
         ! (E-GW + cap at sigma/delta_y = 1e-6 from 2 delta_y, rel_tol 1e-5, where 1e-9
         ! does not converge: from a history at rel_tol 0.15 delta_max was 8.9e-5 off under
         ! an estimate of 4.8e-7, from one at 1e-8 1.1e-6 off, within rel_tol; audit8).
         last_history%valid = .false.
         tight = options
         do step = 1, size(history_steps)
            tight%rel_tol = max(1.0e-10_dp, history_steps(step)*options%rel_tol)
            if (step > 1) then
               if (tight%rel_tol <= max(1.0e-10_dp, history_steps(step - 1)* &
                  & options%rel_tol)) cycle
            end if
            if (allocated(error)) deallocate (error)
            call progress_part(0.225_dp*real(step - 1, dp), 0.225_dp*real(step, dp))
            call progress_begin("history")
            call history_load(params, tight, delta_max, last_history%history, loaded, error, &
               & 1.0_dp)
            call progress_end("history")
            if (.not. allocated(error)) exit
            if (error%stat /= egw_not_converged) return
         end do
         if (allocated(error)) return
         last_history%valid = .true.
         last_history%params = params
         last_history%options = options
         last_history%delta_max = delta_max
      end if
      last_history%history%options = options
      call progress_part(0.9_dp, 1.0_dp)
      call solve_unload(last_history%history, delta, result, error)
   end subroutine unload_from_scratch

   !> The scaled problem of an unloading solve at delta (< history%delta_max) on a rough
   !> history: the loading problem at delta with the history's closest-approach field
   !> d_max(r) and the unloading law (egw_rough_profile's unloading profiles).
   pure function unloading_problem(history, delta) result(prob)
      type(loading_history), intent(in) :: history   !< a loaded rough history
      real(dp), intent(in) :: delta   !< overlap [length] of the unloading solve
      type(scaled_problem) :: prob   !< in scaled units (egw_sphere_problem)
      prob = scaled(history%params, delta, history%loading_law)
      allocate (prob%closest)
      prob%closest = history%closest
      prob%unload = unloading_law_of(prob%psi, prob%hardness, prob%plastic_ratio, &
         & history%loading_law)
   end function unloading_problem

   !> The smooth cap's loading history of a history with history%capped (a smooth sphere
   !> loaded beyond first yield: cap_unload_profile's input), a copy.
   pure function history_cap(history) result(cap)
      type(loading_history), intent(in) :: history   !< a loaded history
      type(cap_history) :: cap   !< egw_cap_sphere's history (empty unless capped)
      cap = history%cap
   end function history_cap

   !> Whether the small-sigma route loaded history (no rough field: only the route answers
   !> its unloading, and no unloading profile exists).
   pure logical function loaded_by_route(history)
      type(loading_history), intent(in) :: history   !< a loaded history
      loaded_by_route = history%asymptotic
   end function loaded_by_route

   !> Whether cache holds the history of exactly these inputs (every field equal).
   pure logical function cached(cache, params, options, delta_max)
      type(history_cache), intent(in) :: cache
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta_max
      cached = .false.
      if (.not. cache%valid) return
      associate (p => cache%params, o => cache%options)
         cached = p%model == params%model .and. p%radius == params%radius .and. &
            & p%modulus == params%modulus .and. p%sigma == params%sigma .and. &
            & p%mu == params%mu .and. p%psi == params%psi .and. &
            & p%hardness_coeff == params%hardness_coeff .and. &
            & p%plastic_ratio == params%plastic_ratio .and. &
            & p%flow_pressure == params%flow_pressure .and. &
            & o%n_radial == options%n_radial .and. o%rel_tol == options%rel_tol .and. &
            & o%max_iter == options%max_iter .and. o%method == options%method .and. &
            & o%n_threads == options%n_threads .and. cache%delta_max == delta_max
      end associate
   end function cached

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
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta
      type(cap_history), intent(out) :: history
      type(solve_result), intent(inout) :: result
      type(egw_error), allocatable, intent(out) :: error
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

   !> The residual overlap [length] of a capped history (capped: cap_load's on
   !> cap_solve_options, the value cap_residual gives at its delta_max); 0 otherwise.
   elemental real(dp) function history_residual(history) result(residual)
      type(loading_history), intent(in) :: history   !< a loading history (load_history)
      residual = 0.0_dp
      if (history%capped) residual = history%cap%residual*history%cap%delta_y
   end function history_residual

   !> c/a, the cap's radius over the contact's, of a capped history's loading (a start for
   !> cap_residual's search at a neighbouring overlap); 0 otherwise (elastic: none).
   elemental real(dp) function history_cap_ratio(history) result(ratio)
      type(loading_history), intent(in) :: history   !< a loading history (load_history)
      ratio = 0.0_dp
      if (history%capped .and. history%cap%contact > 0.0_dp) &
         & ratio = history%cap%cap/history%cap%contact
   end function history_cap_ratio

   !> A cap solve's result as a solve_result: est_rel_err from its two finest levels.
   pure subroutine put_cap_result(res, options, result)
      type(cap_result), intent(in) :: res
      type(solver_options), intent(in) :: options
      type(solve_result), intent(inout) :: result
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

   !> check_input for an unloading solve at delta after delta_max, and a finite delta_max.
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
   end subroutine check_unload_input

   !> A rough sphere with the cap: egw_invalid_argument naming name beyond rough_cap_range
   !> delta_y, where E-GW and EP-GW solves stop converging (doc/stability.md "Rough + cap far
   !> beyond first yield": converged to 2e12 .. 2e15 delta_y, failed a decade beyond,
   !> with a message naming neither delta nor p_y); no bead comes near (<= 1e4 delta_y at
   !> 10 m/s). The smooth cap's own range is 1e6 delta_y (egw_cap_sphere).
   pure subroutine check_cap_overlap(name, delta, params, error)
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: delta
      type(contact_params), intent(in) :: params
      type(egw_error), allocatable, intent(out) :: error
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

end module egw_rough_sphere
