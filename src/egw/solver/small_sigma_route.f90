!> The small-sigma route of a rough sphere with the flow-pressure cap (doc/theory.md §12
!> "Small sigma: the asymptotic route"): where the discrete solves at sigma/delta_y <= 2e-6
!> fail or are checked, the smooth cap's answer plus the rough layer's sigma**(2/3)
!> correction from solves at wider sigmas (wide_sigmas), one order further near the
!> residual overlap, and how its answer replaces or checks a discrete one.
module egw_small_sigma_route
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_not_converged, fatal_error, format_real
   use egw_params, only: contact_params, model_egw, model_epgw
   use egw_progress, only: progress_report, progress_note
   use egw_sphere_regime, only: stall_overlap
   use egw_cap_limit, only: cap_limit, limit_unload
   use egw_cap_sphere, only: cap_options, cap_result, cap_history, cap_load, cap_units
   use egw_sphere_solver, only: solver_options, separation_field, scaled_problem, &
      & discrete_solution, scaled
   use egw_rough_solve, only: solve_result, solve_rough, rough_unload, above_first_yield, &
      & relative_to_force
   implicit none
   private

   public :: small_sigma_loading, route_wanted, asymptotic_applies, asymptotic_unloading, &
      & use_asymptotic
   public :: wide_sigmas, unload_check_limit, unload_floor

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
   !> the unloading's force floor of the route's estimates, relative to P(delta_max)
   real(dp), parameter :: unload_floor = 1.0e-6_dp
   !> The rel_tol of the route's probe (route_floor), and the factor on it that bounds a
   !> probe solve's error (its estimate is no bound: 1.4 times it measured, doc/theory.md
   !> section 12). At sigma/delta_y = 1e-6 from 2 delta_y the route's loading estimate is
   !> 2.7e-7 at every rel_tol (the wide solves at 1e-9 took 24 s to show it); at probe_tol
   !> the four wide solves take ~1 s.
   real(dp), parameter :: probe_tol = 1.0e-7_dp, probe_margin = 10.0_dp

contains

   !> The asymptotic route after the discrete loading solve of an extended model with
   !> elastic summits with the cap (asymptotic_applies; doc/theory.md §12 "Small sigma"):
   !> a solve that failed with egw_not_converged takes the route's answer if its estimate
   !> meets rel_tol/2; a converged one at sigma/delta_y <= small_sigma_check_limit is
   !> checked against it (use_asymptotic). Nothing changes where the route does not apply
   !> or its own solves fail.
   subroutine small_sigma_loading(params, options, delta, prob, result, error)
      type(contact_params), intent(in) :: params   !< the contact
      type(solver_options), intent(in) :: options   !< the discrete solve's options
      real(dp), intent(in) :: delta   !< overlap [length]
      type(scaled_problem), intent(in) :: prob   !< the discrete solve's scaled problem
      !> the discrete solve's; the route's if taken
      type(solve_result), intent(inout) :: result
      !> the discrete solve's; as use_asymptotic
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

   !> Whether the asymptotic route answers a failed solve (error allocated: only
   !> egw_not_converged) or checks a converged one (sigma/delta_y <= check_limit:
   !> small_sigma_check_limit, unload_check_limit); asymptotic_applies either way.
   !> delta_y of params.
   logical function route_wanted(params, options, delta, capped, error, check_limit, &
      & delta_y) result(wanted)
      type(contact_params), intent(in) :: params   !< the contact
      type(solver_options), intent(in) :: options   !< the solve's options
      real(dp), intent(in) :: delta   !< overlap [length] (of a history: delta_max)
      logical, intent(in) :: capped   !< an extended model whose cap acted
      type(egw_error), allocatable, intent(in) :: error   !< the discrete solve's
      real(dp), intent(in) :: check_limit   !< sigma/delta_y at or below which to check
      real(dp), intent(out) :: delta_y   !< first yield of params [length]
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

   !> The asymptotic route's unloading answer at delta after a history (its params, options
   !> and the route's histories: loading_history's wide_loaded, wide, wide_cap): as
   !> asymptotic_loading, with the smooth cap's unloading from delta_max (limit_unload) and
   !> the rough model's histories and unloading solves at wide_sigmas. Where that answer's
   !> estimate misses rel_tol/2 or both pairs fail (near the residual overlap the sigma**(2/3)
   !> term's own next order dominates, and solves at 1e-5 delta_y fail), every wide solve
   !> is tried and the extrapolation in sigma**(2/3) goes one order further
   !> (extrapolated_result); the answer with the smaller estimate is kept.
   subroutine asymptotic_unloading(params, options, wide_loaded, wide_fields, wide_cap, delta, &
      & delta_y, floor, asym, ok)
      type(contact_params), intent(in) :: params   !< the history's contact
      type(solver_options), intent(in) :: options   !< the history's options
      !> per pair of wide_sigmas: the route's histories loaded (loading_history's wide_loaded)
      logical, intent(in) :: wide_loaded(2)
      !> their separation fields at wide_sigmas (loading_history's wide)
      type(separation_field), intent(in) :: wide_fields(2, 2)
      type(cap_limit), intent(in) :: wide_cap   !< the smooth cap's limit_load histories
      real(dp), intent(in) :: delta, delta_y   !< overlap [length], first yield [length]
      real(dp), intent(in) :: floor   !< of the estimates (small_sigma_unload's)
      type(solve_result), intent(out) :: asym   !< the route's answer
      logical, intent(out) :: ok   !< false where its solves fail
      type(cap_result) :: cap
      type(solve_result) :: wide(2, 2), tight(2, 2), further
      type(egw_error), allocatable :: cap_error
      integer :: solved(2, 2), tight_solved(2, 2)   ! 0 not tried, 1 converged, -1 failed
      integer :: k, pair
      logical :: ok_further
      ok = .false.
      solved = 0
      do pair = 1, 2
         if (.not. wide_loaded(pair)) cycle
         do k = 1, 2
            call wide_unload(params, options, wide_fields, delta, delta_y, k, pair, wide, &
               & solved, options%rel_tol)
            if (solved(k, pair) < 0) exit
         end do
         if (all(solved(:, pair) == 1)) exit
      end do
      call limit_unload(wide_cap, delta, cap, cap_error)
      if (allocated(cap_error)) return
      if (pair <= 2) then
         call asymptotic_result(params, cap, wide(:, pair), wide_sigmas(:, pair), &
            & floor, asym)
         ok = .true.
         if (asym%est_rel_err <= 0.5_dp*options%rel_tol) return
      end if
      ! (every wide solve again at rel_tol/10: their estimates enter through weights up
      ! to ~0.5 at sigma/delta_y = 1e-6, and at rel_tol they alone missed rel_tol/2; one
      ! that fails there keeps its answer at rel_tol, or is tried at rel_tol; one that
      ! failed at rel_tol is not tried again: Newton stalls there, 2-8 s a solve)
      do pair = 1, 2
         if (.not. wide_loaded(pair)) cycle
         do k = 1, 2
            if (solved(k, pair) < 0) cycle
            tight = wide
            tight_solved = solved
            call wide_unload(params, options, wide_fields, delta, delta_y, k, pair, tight, &
               & tight_solved, max(further_tol*options%rel_tol, 1.0e-10_dp))
            if (tight_solved(k, pair) == 1) then
               wide(k, pair) = tight(k, pair)
               solved(k, pair) = 1
            else if (solved(k, pair) == 0) then
               call wide_unload(params, options, wide_fields, delta, delta_y, k, pair, wide, &
                  & solved, options%rel_tol)
            end if
         end do
      end do
      if (count(solved == 1) < 2) return
      call extrapolated_result(params, cap, pack(wide, solved == 1), &
         & pack(wide_sigmas, solved == 1), floor, further, &
         & ok_further)
      if (.not. ok_further) return
      if (ok) then
         if (further%est_rel_err >= asym%est_rel_err) return
      end if
      asym = further
      ok = .true.
   end subroutine asymptotic_unloading

   !> The rough unloading solve at delta of the route's history at wide_sigmas(k, pair)
   !> (wide_fields(k, pair), params with that sigma, history_options at rel_tol),
   !> at rel_tol; solved(k, pair) 1 where it converged (wide(k, pair) its result), -1
   !> where it failed.
   subroutine wide_unload(params, history_options, wide_fields, delta, delta_y, k, pair, wide, &
      & solved, rel_tol)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: history_options
      type(separation_field), intent(in) :: wide_fields(2, 2)
      real(dp), intent(in) :: delta, delta_y, rel_tol
      integer, intent(in) :: k, pair
      type(solve_result), intent(inout) :: wide(2, 2)
      integer, intent(inout) :: solved(2, 2)
      type(contact_params) :: wider
      type(solver_options) :: options
      type(egw_error), allocatable :: wide_error
      wider = params
      wider%sigma = wide_sigmas(k, pair)*delta_y
      options = history_options
      options%rel_tol = rel_tol
      call rough_unload(wider, options, wide_fields(k, pair), delta, wide(k, pair), &
         & wide_error)
      solved(k, pair) = merge(-1, 1, allocated(wide_error))
      ! (at most 4 solves at rel_tol, then 4 tighter: 0.2 .. 1 of the unloading call, the
      ! pairs' solves at rel_tol counted by k + 2 pair - 2, the tighter ones by 4 more)
      call progress_report(0.2_dp + 0.1_dp*real(2*pair + k - 2 + merge(4, 0, &
         & rel_tol < history_options%rel_tol), dp), "small-sigma route: unloading")
   end subroutine wide_unload

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
      type(contact_params), intent(in) :: params   !< the contact
      type(solver_options), intent(in) :: options   !< the solve's options
      real(dp), intent(in) :: delta   !< overlap [length]
      logical, intent(in) :: capped   !< an extended model whose cap acted
      real(dp), intent(out) :: delta_y   !< first yield of params [length]
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
      type(solver_options), intent(in) :: options   !< the solve's options
      real(dp), intent(in) :: delta, floor   !< overlap [length], the estimates' floor [force]
      type(solve_result), intent(in) :: asym   !< the route's answer
      !> the discrete solve's; the route's if taken
      type(solve_result), intent(inout) :: result
      type(egw_error), allocatable, intent(inout) :: error   !< the discrete solve's; see above
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

end module egw_small_sigma_route
