!> Loading histories of rough spheres and the unloading solves on them (doc/theory.md §8,
!> §12): load_history keeps the separation field d_max(r) of the loading solve at
!> delta_max (a smooth sphere with the cap: egw_cap_sphere's history; the small-sigma
!> route's own histories where that route may answer), solve_unload solves at delta <=
!> delta_max with the unloading law at fixed d_max, solve_contact_unload loads (once per
!> thread and inputs) and solves.
module egw_rough_history
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_invalid_argument, egw_not_converged, fatal_error, &
      & format_real
   use egw_params, only: contact_params, model_hertz, check_scaled_overlap, force_unit
   use egw_progress, only: progress_begin, progress_end, progress_part, progress_report
   use egw_unloading, only: unloading_law_of
   use egw_law_pieces, only: law_pieces
   use egw_sphere_problem, only: cap_never_acts
   use egw_cap_limit, only: cap_limit, limit_load
   use egw_cap_sphere, only: cap_result, cap_history, cap_unload
   use egw_sphere_solver, only: solver_options, separation_field, scaled_problem, &
      & discrete_solution, scaled, negligible, smooth_force
   use egw_rough_solve, only: solve_result, unload_start, check_unload_input, &
      & check_cap_overlap, smooth_capped, cap_loading, put_cap_result, solve_rough, &
      & rough_unload
   use egw_small_sigma_route, only: small_sigma_loading, route_wanted, asymptotic_applies, &
      & asymptotic_unloading, use_asymptotic, wide_sigmas, unload_check_limit, unload_floor
   use egw_rough_loading, only: solve_contact
   implicit none
   private

   public :: load_history, solve_unload, solve_contact_unload
   public :: history_residual, history_cap_ratio
   ! for egw_rough_profile (the profiles of these solves)
   public :: unloading_problem, history_cap, loaded_by_route

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
      call asymptotic_unloading(history%params, history%options, history%wide_loaded, &
         & history%wide, history%wide_cap, delta, delta_y, floor, asym, ok)
      if (ok) then
         call use_asymptotic(history%options, delta, asym, floor, result, error)
      else if (allocated(error)) then
         error%message = error%message//"; nor by the small-sigma route (fewer than two " &
            & //"of its solves at sigma = 1e-5, 2e-5, 1e-4, 2e-4 delta_y converged)"
      end if
   end subroutine small_sigma_unload

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

end module egw_rough_history
