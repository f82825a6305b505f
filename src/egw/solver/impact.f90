!> Coefficient of restitution and dissipated energy of a head-on impact of rough spheres
!> (doc/theory.md §8, issue 10 item 5): effective mass m*, approach speed v from far apart,
!>
!>   W_load = int_{-inf}^{delta_m} P_load d(delta) = m* v**2/2   (defines delta_m),
!>   W_unload = int_{-inf}^{delta_m} P_unload(delta; delta_m) d(delta),
!>   e = sqrt(W_unload/W_load),  dissipated = W_load - W_unload.
!>
!> The integrals use the solver's force and stiffness: on each interval the two-point
!> Hermite rule (h/2)(P_a + P_b) + (h**2/12)(k_a - k_b), bisected until it agrees with its
!> two halves to a tenth of rel_tol, relative to the larger of the interval's integral and
!> its share (by length) of the whole (the integrands are positive). Below delta_lo
!> the force decays faster than exponentially (Gaussian summit heights), so
!> int_{-inf}^{delta_lo} P <= P(delta_lo)**2/k(delta_lo); delta_lo is lowered until that
!> bound is below rel_tol/20 of the impact energy and the bound is added to both integrals.
module egw_impact
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, egw_invalid_argument, egw_not_converged, egw_unsupported, &
      & fatal_error, &
      & format_real
   use egw_progress, only: progress_begin, progress_end, progress_part, progress_report
   use egw_params, only: contact_params, model_hertz, model_egw, model_epgw, validate_params, &
      & overlap_ratio_max
   use egw_rough_sphere, only: solver_options, solve_result, solve_contact, validate_options, &
      & loading_history, load_history, solve_unload, above_first_yield, cap_solve_options, &
      & unloading_problem, loaded_by_route
   use egw_rough_yield, only: cap_acts, rough_first_yield
   use egw_sphere_solver, only: scaled_problem, discrete_solution, solve_scaled, negligible
   use egw_sphere_problem, only: cap_excess, base_gap
   use egw_halfspace, only: influence_row
   use egw_cap_sphere, only: cap_options, cap_restitution, cap_history, cap_result, cap_load, &
      & cap_unload, cap_units
   implicit none
   private

   public :: restitution, time_step

   !> Velocity Verlet's error in e over one impact, measured over glass and steel EP-GW
   !> pairs from 1e-4 to 10 m/s (doc/theory.md §10): |delta e| <= verlet_error (omega dt)**2
   !> with omega**2 = K_max/m*, the stiffest point of the impact.
   real(dp), parameter :: verlet_error = 0.03_dp
   !> The contact duration's quadrature (half_time): Chebyshev-Lobatto panels of 17 nodes,
   !> bisected to duration_tol of the duration, at most max_panel_depth times.
   integer, parameter :: max_panel_depth = 30
   real(dp), parameter :: duration_tol = 1.0e-9_dp
   !> The forces' relative noise in units of rel_tol (the history's solves at 1e-4 of it,
   !> the rough solves' errors well inside their estimates)
   real(dp), parameter :: noise_level = 1.0e-3_dp
   !> ... or, on a rough sphere's curves, where larger, this share of the largest
   !> est_rel_err of a panel's solves: a force error eps moves W, hence v**2, by at most
   !> eps and the time by eps/2, so the duration is not known better than that; a panel
   !> whose 9- and 17-point rules agree within a tenth of it is kept (the unloading solves
   !> after a capped loading accept relative to a force floor: est_rel_err 1e-7 .. 5e-7,
   !> and 1e-3 rel_tol had their noise bisected to depth 7, 28 panels at EP-GW + cap 1.9
   !> delta_y, now 12; the loading solves' ~5e-9 leave noise_level in charge). Not on the
   !> smooth cap's curves: there it moved the duration by 8.7e-9 and saved no time (its
   !> panels, 5.9e-10 from a DOP853 on the same forces, resolve its error estimate's
   !> bound, not noise).
   real(dp), parameter :: est_share = 0.1_dp
   !> Depth of the interval bisection, and steps allowed to find delta_lo and delta_m.
   integer, parameter :: max_depth = 24, max_steps = 400
   !> The unloading solves' force floor (solve_unload's force_floor), in units of the
   !> unloading integral's work density w = W_load/(delta_m - delta_lo): where a solve's
   !> estimate is relative to max(|P|, floor) and meets rel_tol/2, its error adds at most
   !> rel_tol/2 (W_unload + 0.5 W_load) to W_unload, so at most (rel_tol/4)(1 + 0.5/e**2)
   !> to e (0.75 rel_tol for e >= 0.5; without it rel_tol/4). Near the residual overlap
   !> the small-sigma route's relative estimate of a force 1e-2 .. 1e-5 of P(delta_m)
   !> misses rel_tol/2 (sigma/delta_y = 1e-6, 3 v_y, rel_tol 1e-5: 1.6e-5 at 0.197
   !> delta_m, restitution refused) where its absolute error is far below the integral's.
   real(dp), parameter :: unload_force_floor = 0.5_dp
   !> Smallest impact energy in units of E sqrt(R) sigma**2.5 (see check).
   real(dp), parameter :: min_scaled_energy = 1.0e-150_dp

   !> One force curve: loading (history not loaded) or unloading from a history.
   type :: force_curve
      type(contact_params) :: params
      type(solver_options) :: options
      type(loading_history) :: history
      logical :: unloading = .false.
      !> Work per unit overlap below which an interval needs no relative accuracy: the
      !> integral's error budget spread over its range (energy/span), so that the far tail,
      !> negligible but decaying like a Gaussian, is not bisected to relative precision.
      real(dp) :: work_density = 0.0_dp
   end type force_curve

contains

   !> Coefficient of restitution e and dissipated energy of a head-on impact with effective
   !> mass m* (1/m* = 1/m1 + 1/m2) and approach speed v, for the contact params (all models;
   !> elastic models and psi = 0 give e = 1 to the tolerance; Hertz and sigma = 0 exactly 1).
   !> Accurate to about options%rel_tol. Errors: invalid params/options as solve_contact,
   !> mass or velocity not finite and > 0 (egw_invalid_argument naming it), a failed solve
   !> (egw_not_converged). e, dissipated and max_overlap are untouched on any error.
   !> Reports progress (egw_progress) as one long call: the loading curve to 0.15
   !> ("restitution: loading"), the history to 0.5, the unloading integral to 1.
   subroutine restitution(params, options, mass, velocity, e, dissipated, error, max_overlap, &
         & work_load)
      type(contact_params), intent(in) :: params   !< the contact
      type(solver_options), intent(in) :: options   !< tolerance of the solves and integrals
      real(dp), intent(in) :: mass        !< effective mass m* > 0
      real(dp), intent(in) :: velocity    !< approach speed v > 0
      real(dp), intent(inout) :: e             !< coefficient of restitution, 0 < e <= 1
      real(dp), intent(inout) :: dissipated    !< W_load - W_unload (energy units)
      !> allocated on failure (outputs untouched)
      type(egw_error), allocatable, intent(out) :: error
      real(dp), intent(inout), optional :: max_overlap  !< delta_m, the deepest overlap
      real(dp), intent(inout), optional :: work_load    !< W_load as integrated (~ m* v**2/2)
      call progress_begin("restitution")
      call impact(params, options, mass, velocity, e, dissipated, error, max_overlap, &
         & work_load)
      call progress_end("restitution")
   end subroutine restitution

   !> restitution's work.
   subroutine impact(params, options, mass, velocity, e, dissipated, error, max_overlap, &
         & work_load)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: mass, velocity
      real(dp), intent(inout) :: e, dissipated
      type(egw_error), allocatable, intent(out) :: error
      real(dp), intent(inout), optional :: max_overlap, work_load
      type(force_curve) :: curve
      type(solve_result) :: res
      real(dp) :: energy, delta_lo, delta_m, w_load, w_unload, tail_load
      real(dp), allocatable :: nodes(:)

      call check(params, options, mass, velocity, error)
      if (allocated(error)) return
      energy = 0.5_dp*mass*velocity**2
      if (params%flow_pressure > 0.0_dp .and. (params%model == model_hertz .or. &
         & params%sigma == 0.0_dp)) then
         ! The smooth sphere with the flow-pressure cap (a rough one takes the cap in its
         ! solves: the integrals below)
         call cap_impact(params, mass, velocity, e, dissipated, error, max_overlap, work_load)
         return
      end if
      if (params%model == model_hertz .or. params%sigma == 0.0_dp) then
         ! Smooth elastic spheres: W_unload = W_load exactly; delta_m from (8/15) E sqrt(R)
         ! delta**2.5 = energy.
         if (present(max_overlap)) max_overlap = (15.0_dp*energy/(8.0_dp*params%modulus &
            & *sqrt(params%radius)))**0.4_dp
         if (present(work_load)) work_load = energy
         e = 1.0_dp
         dissipated = 0.0_dp
         return
      end if
      curve%params = params
      curve%options = options
      call lower_limit(curve, energy, delta_lo, tail_load, error)
      if (allocated(error)) return
      ! The range is at most up to the Hertz turning point plus a few sigma (the rough
      ! models press at least as hard as Hertz beyond contact, GW nearly so).
      curve%work_density = energy/(max(0.0_dp, (15.0_dp*energy/(8.0_dp*params%modulus &
         & *sqrt(params%radius)))**0.4_dp) - delta_lo + params%sigma)
      call turning_point(curve, energy, delta_lo, tail_load, delta_m, w_load, nodes, error)
      if (allocated(error)) return
      call progress_part(0.15_dp, 0.5_dp)
      call load_history(params, options, delta_m, curve%history, res, error)
      if (allocated(error)) return
      curve%unloading = .true.
      curve%work_density = w_load/(delta_m - delta_lo)
      call work(curve, [delta_lo, pack(nodes, nodes > delta_lo .and. nodes < delta_m), &
         & delta_m], w_unload, error)
      if (allocated(error)) return
      w_unload = w_unload + tail_bound(curve, delta_lo, error)
      if (allocated(error)) return
      ! P_unload <= P_load pointwise, so W_unload <= W_load: an excess is quadrature noise
      ! within the tolerance.
      w_unload = min(w_unload, w_load)
      e = sqrt(w_unload/w_load)
      dissipated = w_load - w_unload
      if (present(max_overlap)) max_overlap = delta_m
      if (present(work_load)) work_load = w_load
   end subroutine impact

   !> restitution of a smooth sphere with the flow-pressure cap: egw_cap_sphere's
   !> cap_restitution (e = 1 up to the first-yield speed v_y) on restitution_options;
   !> dissipated = (1 - e**2) m* v**2/2 (its loading work is m* v**2/2 by construction).
   subroutine cap_impact(params, mass, velocity, e, dissipated, error, max_overlap, work_load)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: mass, velocity
      real(dp), intent(inout) :: e, dissipated
      type(egw_error), allocatable, intent(out) :: error
      real(dp), intent(inout), optional :: max_overlap, work_load
      real(dp) :: e_cap, delta_m, energy
      call cap_restitution(params%radius, params%modulus, params%flow_pressure, mass, &
         & velocity, restitution_options(), e_cap, error, max_overlap=delta_m)
      if (allocated(error)) return
      energy = 0.5_dp*mass*velocity**2
      e = e_cap
      dissipated = (1.0_dp - e_cap**2)*energy
      if (present(max_overlap)) max_overlap = delta_m
      if (present(work_load)) work_load = energy
   end subroutine cap_impact

   !> The cap solver's options for restitution (doc/theory.md section 12): the solves'
   !> (fitted meshes of 64 rings, 32 for the estimate) with 16 Gauss points per work
   !> integral. Measured against test/data/cap_reference.csv from 2 to 100 v_y: within
   !> 3.4e-6 of e (the goal is 1 %).
   pure function restitution_options() result(options)
      type(cap_options) :: options
      options = cap_solve_options()
      options%n_quad = 16
   end function restitution_options

   pure subroutine check(params, options, mass, velocity, error)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: mass, velocity
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: log_energy
      call validate_params(params, error)
      if (allocated(error)) return
      call validate_options(options, error)
      if (allocated(error)) return
      if (.not. (ieee_is_finite(mass) .and. mass > 0.0_dp)) then
         call fatal_error(error, egw_invalid_argument, "mass = "//format_real(mass) &
            & //": the effective mass must be finite and > 0")
      else if (.not. (ieee_is_finite(velocity) .and. velocity > 0.0_dp)) then
         call fatal_error(error, egw_invalid_argument, "velocity = "//format_real(velocity) &
            & //": the approach speed must be finite and > 0")
      else if (.not. ieee_is_finite(0.5_dp*mass*velocity**2)) then
         call fatal_error(error, egw_invalid_argument, "mass, velocity = "//format_real(mass) &
            & //", "//format_real(velocity)//": the kinetic energy overflows")
      else if (params%model /= model_hertz .and. params%sigma > 0.0_dp) then
         ! The scaled impact energy m v**2/2 / (E sqrt(R) sigma**2.5) (in logarithms: the
         ! energy unit itself may not be a double) must lie where the solver works: at most
         ! twice the Hertz work (8/15) x**2.5 to the deepest overlap x = delta/sigma = 1e15
         ! (E-GW and EP-GW add to it; classic GW has approached it long before), at least
         ! 1e-150 (the turning point then lies where the force is still ~1e100 above the
         ! solver's underflow cut of 1e-250; at 1e-250 it is lost). Refused at once rather
         ! than marching ~100 solves to the limit, or integrating subnormal forces.
         log_energy = log(0.5_dp*mass) + 2.0_dp*log(velocity) - (log(params%modulus) &
            & + 0.5_dp*log(params%radius) + 2.5_dp*log(params%sigma))
         if (log_energy > log(2.0_dp*8.0_dp/15.0_dp) + 2.5_dp*log(overlap_ratio_max) .or. &
            & log_energy < log(min_scaled_energy)) then
            call fatal_error(error, egw_invalid_argument, "mass, velocity = " &
               & //format_real(mass)//", "//format_real(velocity)//": the impact energy " &
               & //"m v**2/2 in units of E sqrt(R) sigma**2.5, exp("//format_real(log_energy) &
               & //"), must lie in ["//format_real(min_scaled_energy)//", " &
               & //format_real(2.0_dp*8.0_dp/15.0_dp*overlap_ratio_max**2.5_dp) &
               & //"] (the deepest overlap within the solver's range)")
         end if
      end if
   end subroutine check

   !> Force and stiffness of the curve at delta.
   subroutine evaluate(curve, delta, force, stiffness, error)
      type(force_curve), intent(in) :: curve
      real(dp), intent(in) :: delta
      real(dp), intent(out) :: force, stiffness
      type(egw_error), allocatable, intent(out) :: error
      type(solve_result) :: res
      if (curve%unloading) then
         call solve_unload(curve%history, delta, res, error, &
            & force_floor=unload_force_floor*curve%work_density)
      else
         call solve_contact(curve%params, curve%options, delta, res, error)
      end if
      force = res%force
      stiffness = res%stiffness
   end subroutine evaluate

   !> Bound of int_{-inf}^{delta} P: P**2/k (P decays faster than exp(k/P (delta' - delta))
   !> below delta in the separated tail); 0 where the force has underflowed.
   real(dp) function tail_bound(curve, delta, error) result(tail)
      type(force_curve), intent(in) :: curve
      real(dp), intent(in) :: delta
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: force, stiffness
      tail = 0.0_dp
      call evaluate(curve, delta, force, stiffness, error)
      if (allocated(error)) return
      if (force > 0.0_dp .and. stiffness > 0.0_dp) tail = force*force/stiffness
   end function tail_bound

   !> Lowest overlap of the integrals: from -sigma down in steps of sigma until the tail
   !> bound is below rel_tol/20 of the impact energy.
   subroutine lower_limit(curve, energy, delta_lo, tail, error)
      type(force_curve), intent(in) :: curve
      real(dp), intent(in) :: energy
      real(dp), intent(out) :: delta_lo, tail
      type(egw_error), allocatable, intent(out) :: error
      integer :: i
      delta_lo = 0.0_dp
      do i = 1, max_steps
         delta_lo = -real(i, dp)*curve%params%sigma
         tail = tail_bound(curve, delta_lo, error)
         if (allocated(error)) return
         if (tail <= 0.05_dp*curve%options%rel_tol*energy) return
      end do
      call fatal_error(error, egw_not_converged, "energy = "//format_real(energy) &
         & //": no separation found where the force's tail is negligible")
   end subroutine lower_limit

   !> delta_m with W_load(delta_m) = energy: march up from delta_lo, integrating as it goes,
   !> until W passes the energy; then in the last interval Newton on the Hermite model of W
   !> (W' = P, W'' = k), each candidate integrated exactly, until W is within rel_tol/10.
   !> nodes: the overlaps visited (a starting partition for the unloading integral).
   subroutine turning_point(curve, energy, delta_lo, tail, delta_m, w_load, nodes, error)
      type(force_curve), intent(in) :: curve
      real(dp), intent(in) :: energy, delta_lo, tail
      real(dp), intent(out) :: delta_m, w_load
      real(dp), allocatable, intent(out) :: nodes(:)
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: a, pa, ka, b, pb, kb, wa, wb, step, piece, sigma, x, w_try, p_x, k_x
      integer :: i
      logical :: bracketed
      sigma = curve%params%sigma
      a = delta_lo
      call evaluate(curve, a, pa, ka, error)
      if (allocated(error)) return
      wa = tail
      nodes = [a]
      bracketed = .false.
      do i = 1, max_steps
         ! Next overlap from the quadratic model of W, at most 2 sigma + delta/2 ahead.
         step = quadratic_step(energy - wa, pa, ka)
         step = min(step, 2.0_dp*sigma + 0.5_dp*max(a, 0.0_dp))
         step = max(step, 1.0e-3_dp*sigma)
         b = a + step
         call evaluate(curve, b, pb, kb, error)
         if (allocated(error)) return
         call integrate(curve, a, pa, ka, b, pb, kb, 0, piece, error)
         if (allocated(error)) return
         wb = wa + piece
         call progress_report(0.15_dp*min(1.0_dp, max(0.0_dp, wb/energy)), &
            & "restitution: loading")
         nodes = [nodes, b]
         if (wb >= energy) then
            bracketed = .true.
            exit
         end if
         a = b; pa = pb; ka = kb; wa = wb
      end do
      if (.not. bracketed) then
         call fatal_error(error, egw_not_converged, "energy = "//format_real(energy) &
            & //": the loading work did not reach the impact energy")
         return
      end if
      ! Bracket [a, b]: W(a) < energy <= W(b).
      do i = 1, 60
         if (abs(wb - energy) <= 0.1_dp*curve%options%rel_tol*energy) then
            delta_m = b
            w_load = wb
            return
         end if
         x = a + quadratic_step(energy - wa, pa, ka)
         if (.not. (x > a .and. x < b)) x = 0.5_dp*(a + b)
         call evaluate(curve, x, p_x, k_x, error)
         if (allocated(error)) return
         call integrate(curve, a, pa, ka, x, p_x, k_x, 0, piece, error)
         if (allocated(error)) return
         w_try = wa + piece
         if (w_try >= energy) then
            b = x; pb = p_x; kb = k_x; wb = w_try
         else
            a = x; pa = p_x; ka = k_x; wa = w_try
            if (abs(wa - energy) <= 0.1_dp*curve%options%rel_tol*energy) then
               delta_m = a
               w_load = wa
               return
            end if
         end if
      end do
      call fatal_error(error, egw_not_converged, "energy = "//format_real(energy) &
         & //": the turning point was not located")
   end subroutine turning_point

   !> Smallest s > 0 with p s + k s**2/2 = gap (k >= 0; gap/p if k <= 0).
   pure real(dp) function quadratic_step(gap, p, k) result(s)
      real(dp), intent(in) :: gap, p, k
      if (k > 0.0_dp) then
         s = 2.0_dp*gap/(p + sqrt(p*p + 2.0_dp*k*gap))
      else if (p > 0.0_dp) then
         s = gap/p
      else
         s = huge(1.0_dp)
      end if
   end function quadratic_step

   !> int of the curve over the partition delta(:) (increasing).
   subroutine work(curve, delta, total, error)
      type(force_curve), intent(in) :: curve
      real(dp), intent(in) :: delta(:)
      real(dp), intent(out) :: total
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: pa, ka, pb, kb, piece
      integer :: i
      total = 0.0_dp
      call evaluate(curve, delta(1), pa, ka, error)
      if (allocated(error)) return
      do i = 2, size(delta)
         call evaluate(curve, delta(i), pb, kb, error)
         if (allocated(error)) return
         call integrate(curve, delta(i - 1), pa, ka, delta(i), pb, kb, 0, piece, error)
         if (allocated(error)) return
         total = total + piece
         pa = pb
         ka = kb
         if (curve%unloading) call progress_report(0.5_dp + 0.5_dp*real(i - 1, dp)/ &
            & real(size(delta) - 1, dp), "restitution: unloading")
      end do
   end subroutine work

   !> Adaptive Hermite quadrature of the curve on [a, b] given P and k at both ends.
   recursive subroutine integrate(curve, a, pa, ka, b, pb, kb, depth, total, error)
      type(force_curve), intent(in) :: curve
      real(dp), intent(in) :: a, pa, ka, b, pb, kb
      integer, intent(in) :: depth
      real(dp), intent(out) :: total
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: m, pm, km, whole, left, right
      whole = hermite_rule(a, pa, ka, b, pb, kb)
      m = 0.5_dp*(a + b)
      call evaluate(curve, m, pm, km, error)
      if (allocated(error)) return
      left = hermite_rule(a, pa, ka, m, pm, km)
      right = hermite_rule(m, pm, km, b, pb, kb)
      total = left + right
      ! The rule is exact for cubics: halving cuts its error 16-fold, so |halves - whole|
      ! is ~15 times the error of the halves.
      if (abs(total - whole) <= 1.5_dp*curve%options%rel_tol*max(abs(total), &
         & curve%work_density*(b - a)) .or. depth >= max_depth) then
         total = total + (total - whole)/15.0_dp
         return
      end if
      call integrate(curve, a, pa, ka, m, pm, km, depth + 1, left, error)
      if (allocated(error)) return
      call integrate(curve, m, pm, km, b, pb, kb, depth + 1, right, error)
      if (allocated(error)) return
      total = left + right
   end subroutine integrate

   !> Integral of the cubic Hermite interpolant of (P, k) at a and b.
   pure real(dp) function hermite_rule(a, pa, ka, b, pb, kb) result(s)
      real(dp), intent(in) :: a, pa, ka, b, pb, kb
      real(dp) :: h
      h = b - a
      s = 0.5_dp*h*(pa + pb) + h*h/12.0_dp*(ka - kb)
   end function hermite_rule

   !> The contact duration of a head-on impact (effective mass m*, approach speed v) and
   !> the largest velocity-Verlet time step that keeps the integration's error in the
   !> coefficient of restitution below tolerance (doc/theory.md §10):
   !>   dt = sqrt(tolerance/(2 verlet_error))/omega,  omega**2 = K_max/m*,
   !> K_max the stiffest point of the impact (the unloading stiffness at the deepest
   !> overlap delta_m; the loading one for elastic contacts; with the flow-pressure cap
   !> beyond first yield the elastic unloading from the flattened shape, ~2 E* a),
   !> capped at 0.5/omega. The
   !> duration is the time the force spends above 1 % of its peak P(delta_m), loading and
   !> unloading, from the solver's force curves (adaptive Clenshaw-Curtis panels in
   !> sqrt(delta_m - delta), half_time); a DEM step should resolve it too (dt is far below it for tolerance <= 1e-3).
   !> For the fastest impact of a run: slower ones are softer. Errors as restitution, and
   !> tolerance not in (0, 0.1] (egw_invalid_argument); outputs untouched on error.
   !> Progress (egw_progress): one call, the restitution 0 .. 0.6 of it, the history at
   !> delta_m 0.6 .. 0.8, the unloading solve 0.8 .. 0.9; the duration's solves are silent.
   subroutine time_step(params, options, mass, velocity, tolerance, duration, step, error)
      type(contact_params), intent(in) :: params   !< the contact
      type(solver_options), intent(in) :: options   !< tolerance of the solves
      real(dp), intent(in) :: mass        !< effective mass m* > 0 [mass]
      real(dp), intent(in) :: velocity    !< largest approach speed v > 0 [length/time]
      real(dp), intent(in) :: tolerance   !< allowed error of e from the time step, (0, 0.1]
      real(dp), intent(inout) :: duration   !< contact duration [time]
      real(dp), intent(inout) :: step       !< largest Verlet time step [time]
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      call progress_begin("time step")
      call impact_time_step(params, options, mass, velocity, tolerance, duration, step, error)
      call progress_end("time step")
   end subroutine time_step

   !> time_step's work.
   subroutine impact_time_step(params, options, mass, velocity, tolerance, duration, step, &
         & error)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: mass, velocity, tolerance
      real(dp), intent(inout) :: duration, step
      type(egw_error), allocatable, intent(out) :: error
      type(loading_history) :: hist
      type(solve_result) :: top, res
      real(dp) :: e, dissipated, delta_m, k_max, omega, t_load, t_unload
      if (.not. (tolerance > 0.0_dp .and. tolerance <= 0.1_dp)) then
         call fatal_error(error, egw_invalid_argument, "tolerance = "// &
            & format_real(tolerance)//": must lie in (0, 0.1]")
         return
      end if
      call progress_part(0.0_dp, 0.6_dp)
      call restitution(params, options, mass, velocity, e, dissipated, error, &
         & max_overlap=delta_m)
      if (allocated(error)) return
      if ((params%model == model_hertz .or. .not. params%sigma > 0.0_dp) .and. &
         & .not. delta_m > tiny(1.0_dp)) then
         ! a smooth sphere's speed so small (subnormal) that the deepest overlap underflows:
         ! no curve to time, the caller's value named (not a solver's failure); a rough
         ! sphere's deepest overlap may be < 0 (its impact energy is bounded in check)
         call fatal_error(error, egw_invalid_argument, "velocity = "//format_real(velocity) &
            & //": the deepest overlap "//format_real(delta_m)//" underflows (mass, " &
            & //"velocity too small for a time step)")
         return
      end if
      call progress_part(0.6_dp, 0.8_dp)
      call load_history(params, options, delta_m, hist, top, error)
      if (allocated(error)) return
      if (above_first_yield(params, delta_m)) then
         ! the flow-pressure cap: the stiffest point is the elastic unloading from the
         ! flattened shape at delta_m (solve_unload at delta_max is the loading solve,
         ! whose tangent holds the capped rings fixed: ~0 once the contact is capped)
         call cap_unload_stiffness(params, delta_m, res%stiffness, error)
         if (allocated(error)) return
         if (.not. top%stiffness > 0.0_dp) top%stiffness = res%stiffness
      else
         call progress_part(0.8_dp, 0.9_dp)
         call solve_unload(hist, delta_m, res, error)
         if (allocated(error)) return
      end if
      k_max = max(top%stiffness, res%stiffness)
      if (.not. (k_max > 0.0_dp .and. top%force > 0.0_dp)) then
         call fatal_error(error, egw_not_converged, "velocity = "//format_real(velocity)// &
            & ": no contact stiffness at the deepest overlap "//format_real(delta_m))
         return
      end if
      call half_time(hist, .false., mass, delta_m, top%force, top%stiffness, t_load, error)
      if (allocated(error)) return
      call half_time(hist, .true., mass, delta_m, top%force, res%stiffness, t_unload, error)
      if (allocated(error)) return
      omega = sqrt(k_max/mass)
      step = min(sqrt(tolerance/(2*verlet_error)), 0.5_dp)/omega
      duration = t_load + t_unload
   end subroutine impact_time_step

   !> The unloading stiffness at the turning point delta_max (> delta_y) of a smooth sphere
   !> with the flow-pressure cap: cap_unload at delta_max on the public solves' options,
   !> elastic from the deformed shape (2 E* a for an axisymmetric punch of contact radius
   !> a, here the cap's flattened contact).
   subroutine cap_unload_stiffness(params, delta_max, stiffness, error)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: delta_max
      real(dp), intent(out) :: stiffness
      type(egw_error), allocatable, intent(out) :: error
      type(cap_history) :: hist
      type(cap_result) :: res
      stiffness = 0.0_dp
      call cap_load(params%radius, params%modulus, params%flow_pressure, delta_max, &
         & cap_solve_options(), hist, res, error)
      if (allocated(error)) return
      call cap_unload(hist, delta_max, res, error)
      if (allocated(error)) return
      stiffness = res%stiffness
   end subroutine cap_unload_stiffness

   !> The time from the overlap where the force is 1 % of P(delta_m) to delta_m (loading)
   !> or back (unloading): t = int dx/v(x), v(x)**2 = (2/m*) W(x), W(x) = int_x^{delta_m} P.
   !> With x = delta_m - u**2 (the 1/sqrt singularity at the turning point becomes
   !> regular) t = int_0^{u_max} 2u/v du and W(u) = int_0^u 2s P(delta_m - s**2) ds, both on
   !> the same Chebyshev-Lobatto panels in u: W at every node from the panel's interpolant
   !> of 2s P integrated exactly (Clenshaw-Curtis' cumulative matrix), t by its last row.
   !> The 17-point rule's error on a panel is extrapolated from its nested 9- and 5-point
   !> rules at their observed (algebraic) rate; a panel is kept when that error (with W's
   !> share) is within duration_tol of t (lower bound u_max sqrt(2 m*/P_m)) per unit of
   !> panel length (at least u_max/16), or its rules differ by no more than the solves'
   !> noise; else bisected. The panels grade themselves towards a branch point beyond u_max
   !> (Hertz's at delta = 0, 2.4 % of u_max past it: 4 panels) and a kink; those a rough
   !> sphere's law places inside are panel ends, the panels before them graded
   !> (rough_breaks).
   subroutine half_time(hist, unloading, mass, delta_m, p_m, k_m, time, error)
      type(loading_history), intent(in) :: hist
      logical, intent(in) :: unloading
      real(dp), intent(in) :: mass, delta_m
      real(dp), intent(in) :: p_m, k_m   !< the curve's force and stiffness at delta_m
      real(dp), intent(out) :: time
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: u_max, s_16(0:16, 0:16), s_8(0:8, 0:8), s_4(0:4, 0:4)
      real(dp) :: a, b, w_a, p_a, g_0, t(3), w(3), budget, err, noise, u_y, cuts(2), est, share
      ! the stack holds at most the 4 first panels and one per bisection
      real(dp) :: p(0:16), ends(max_panel_depth + 3)
      integer :: n_ends, depth(max_panel_depth + 3), d, n_cuts, k
      ! graded(i): the panel ending at ends(i) has a branch point at its right end
      logical :: graded(max_panel_depth + 3), g
      time = 0.0_dp
      call onset(hist, unloading, delta_m, p_m, k_m, u_max, error)
      if (allocated(error)) return
      s_16 = cc_cumulative(16)
      s_8 = cc_cumulative(8)
      s_4 = cc_cumulative(4)
      ! dt/du at u = 0: W ~ P_m u**2
      g_0 = sqrt(2*mass/p_m)
      budget = duration_tol*g_0   ! per unit length of u
      noise = noise_level*hist%options%rel_tol
      ! the solves' own estimates count on a rough sphere's curves (est_share)
      share = 0.0_dp
      if (hist%params%model /= model_hertz .and. hist%params%sigma > 0.0_dp) share = est_share
      a = 0.0_dp
      w_a = 0.0_dp
      p_a = p_m
      ! pending right ends (a stack, nearest on top) and their depths
      ! [0, u_max/2] then [u_max/2, u_max]: a single panel rarely suffices; the smooth
      ! sphere's loading with the cap splits at first yield (Hertz below, a kink there)
      n_ends = 2
      ends(1:2) = [u_max, 0.5_dp*u_max]
      graded = .false.
      u_y = yield_break(hist, unloading, delta_m, u_max)
      if (u_y > 0.0_dp) then
         n_ends = 3
         ends(1:3) = [u_max, u_y, 0.5_dp*u_y]
      end if
      ! a rough sphere's branch points (rough_breaks): [0, c_1], [c_1, c_2], ..., [c_n,
      ! u_max], graded towards each c_k (EP-GW + cap, 1 mm glass beads at 0.5, 1, 3 m/s:
      ! 3, 3, 5 loading panels; 22 before at 1.1 m/s)
      call rough_breaks(hist, unloading, delta_m, u_max, cuts, n_cuts, error)
      if (allocated(error)) return
      if (n_cuts > 0) then
         n_ends = 1
         ends(1) = u_max
         do k = n_cuts, 1, -1
            n_ends = n_ends + 1
            ends(n_ends) = cuts(k)
            graded(n_ends) = .true.
         end do
         ! an unloading curve's [0, c_1] in two panels, as [0, u_max] without breaks (the
         ! capped unloading's centre lift-off near u_max: as one it was bisected anyway;
         ! the bench pair at 3 v_y 7 panels solved, 8 as one)
         if (unloading) then
            n_ends = n_ends + 1
            ends(n_ends) = 0.5_dp*cuts(1)
         end if
      end if
      depth(1:n_ends) = 1
      do while (n_ends > 0)
         b = ends(n_ends)
         d = depth(n_ends)
         g = graded(n_ends)
         call panel(hist, unloading, mass, delta_m, a, b, g, p_a, w_a, g_0, s_16, s_8, &
            & s_4, p, t, w, est, error)
         if (allocated(error)) return
         ! the 17-point rule's error from the 9- and 5-point ones' (their observed rate);
         ! W's reaches the rest of the time (<= ~u_max g_0) as half its relative
         ! error
         err = extrapolated_error(t) + u_max*g_0*extrapolated_error(w)/max(w(1), tiny(w(1)))
         ! kept: within the budget of its length (at least u_max/16: a singular point
         ! costs a few budgets u_max/16 in all), or its 9-point rule is within the solves'
         ! own noise of the 17-point one (nothing left to learn): 1e-3 rel_tol, or a tenth
         ! of the largest error the panel's solves estimate for themselves
         if (err > budget*max(b - a, u_max/16) .and. abs(t(1) - t(2)) > max(noise, &
            & share*est)*abs(t(1)) .and. d < max_panel_depth - 1) then
            ! bisect: the left half next, the right one pending (graded as its parent)
            ends(n_ends) = b
            depth(n_ends) = d + 1
            n_ends = n_ends + 1
            ends(n_ends) = 0.5_dp*(a + b)
            depth(n_ends) = d + 1
            graded(n_ends) = .false.
            cycle
         end if
         time = time + t(1)
         a = b
         w_a = w(1)
         p_a = p(16)
         n_ends = n_ends - 1
      end do
   end subroutine half_time

   !> u at first yield delta_y on the loading curve of a smooth sphere with the cap, where
   !> its force leaves Hertz's with a kink, if it lies inside (5 %, 95 %) of [0, u_max]
   !> (else, an unloading curve or without the cap, 0).
   pure real(dp) function yield_break(hist, unloading, delta_m, u_max) result(u_y)
      type(loading_history), intent(in) :: hist
      logical, intent(in) :: unloading
      real(dp), intent(in) :: delta_m, u_max
      real(dp) :: delta_y, a_y, force_y
      u_y = 0.0_dp
      if (unloading .or. .not. hist%params%flow_pressure > 0.0_dp .or. .not. &
         & (hist%params%model == model_hertz .or. hist%params%sigma == 0.0_dp)) return
      call cap_units(hist%params%radius, hist%params%modulus, hist%params%flow_pressure, &
         & delta_y, a_y, force_y)
      if (delta_y < delta_m) u_y = sqrt(delta_m - delta_y)
      if (.not. (u_y > 0.05_dp*u_max .and. u_y < 0.95_dp*u_max)) u_y = 0.0_dp
   end function yield_break

   !> Break points c_k (in u, increasing) of a rough sphere's curve where its force has a
   !> branch point, a term ~(delta - x_k)**(3/2) on the side of the larger overlap, found
   !> from the law (the panels ending there are graded, panel): E-GW's and EP-GW's smooth
   !> part, P = P_H(delta) + P_G with P_H = 0 at delta <= 0 (doc/theory.md section 5), at
   !> delta = 0 on loading and on the unloading of a history the cap did not reach (its
   !> smooth part is Hertz's at the current delta); with the cap, on loading, the rough
   !> first yield m_y where the largest pressure reaches p_y (the capped region grows from
   !> nothing there; rough_first_yield), on unloading where the centre lifts off
   !> (centre_lift_off: the contact's inner disc shrinks to nothing there). Kept where
   !> they lie inside (1 %, 99 %) of [0, u_max].
   subroutine rough_breaks(hist, unloading, delta_m, u_max, cuts, n_cuts, error)
      type(loading_history), intent(in) :: hist
      logical, intent(in) :: unloading
      real(dp), intent(in) :: delta_m, u_max
      real(dp), intent(out) :: cuts(2)
      integer, intent(out) :: n_cuts
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: m_y, x_c
      logical :: capped
      n_cuts = 0
      cuts = 0.0_dp
      if (hist%params%model == model_hertz .or. .not. hist%params%sigma > 0.0_dp) return
      capped = cap_acts(hist%loading%max_pressure, hist%params%flow_pressure)
      if (capped .and. .not. unloading) then
         ! (to 1e-10 of u_max**2: a break that far off a (delta - m_y)**(3/2) term leaves
         ! ~1e-15 of the duration)
         call rough_first_yield(hist%params, hist%options, delta_m - u_max**2, delta_m, &
            & 1.0e-10_dp*u_max**2, m_y, error)
         if (allocated(error)) return
         call add(sqrt(max(delta_m - m_y, 0.0_dp)))
      else if (capped) then
         call centre_lift_off(hist, delta_m, u_max, x_c)
         call add(sqrt(max(delta_m - x_c, 0.0_dp)))
      end if
      if ((hist%params%model == model_egw .or. hist%params%model == model_epgw) .and. &
         & .not. (capped .and. unloading)) call add(sqrt(max(delta_m, 0.0_dp)))
      if (n_cuts == 2) then
         if (cuts(1) > cuts(2)) cuts = cuts(2:1:-1)
      end if
   contains
      subroutine add(c)
         real(dp), intent(in) :: c
         if (c > 0.01_dp*u_max .and. c < 0.99_dp*u_max) then
            n_cuts = n_cuts + 1
            cuts(n_cuts) = c
         end if
      end subroutine add
   end subroutine rough_breaks

   !> Where the centre lifts off on the unloading curve of a rough history with the cap
   !> (doc/theory.md section 12, "Plastic displacement and unloading"): the overlap x_c
   !> in [delta_m - u_max**2, delta_m) where the total pressure at r = 0 before the floor
   !> falls to 0. At delta_m it is p_y where the cap reached the centre; it falls as the
   !> Hertz part unloads beneath the rough part's offset, and below x_c the floor holds
   !> the centre at 0: the contact's inner disc has shrunk to nothing (a ring remains),
   !> and the stiffness loses a c sqrt(delta - x_c) term (EP-GW + cap, the bench pair at
   !> 3 v_y: p(0) 3.8e6 Pa at 3.5e-8 m, 0 at 3.0e-8 m; x_c = 3.384e-8 m). Regula falsi
   !> (Illinois) on that pressure from discrete unloading solves (solve_scaled on the
   !> history's options; no stiffness), until a step is within 1e-6 of u_max**2 (there
   !> 7 solves and one at delta_m - u_max**2; an x_c off by a little leaves the branch
   !> point just inside a panel, which then bisects). x_c = delta_m (no break) where the
   !> centre is still pressed at delta_m - u_max**2 or a solve fails (the panels then
   !> bisect towards the kink as before).
   subroutine centre_lift_off(hist, delta_m, u_max, x_c)
      type(loading_history), intent(in) :: hist   !< a rough history the cap reached
      real(dp), intent(in) :: delta_m, u_max
      real(dp), intent(out) :: x_c   !< the overlap where the centre lifts off
      type(egw_error), allocatable :: error
      type(scaled_problem) :: prob
      real(dp) :: lo, hi, g_lo, g_hi, x, g, tol, x_prev
      integer :: it, last
      x_c = delta_m
      if (hist%reversible .or. hist%capped .or. hist%cap_free .or. loaded_by_route(hist)) &
         & return
      lo = delta_m - u_max**2
      call centre_pressure(lo, g_lo, error)
      if (allocated(error) .or. .not. g_lo < 0.0_dp) return
      ! (at delta_m the total before the floor is p_y where the cap reached)
      hi = delta_m
      prob = unloading_problem(hist, delta_m)
      if (.not. allocated(prob%cap)) return
      g_hi = prob%cap%p_y
      tol = 1.0e-6_dp*u_max**2
      last = 0
      x = lo
      do it = 1, 12
         x_prev = x
         x = (lo*g_hi - hi*g_lo)/(g_hi - g_lo)
         if (.not. (x > lo .and. x < hi)) x = 0.5_dp*(lo + hi)
         if (abs(x - x_prev) <= tol) exit
         call centre_pressure(x, g, error)
         if (allocated(error)) then
            x_c = delta_m
            return
         end if
         if (g < 0.0_dp) then
            lo = x
            g_lo = g
            ! (Illinois: the end kept twice is halved)
            if (last < 0) g_hi = 0.5_dp*g_hi
            last = -1
         else
            hi = x
            g_hi = g
            if (last > 0) g_lo = 0.5_dp*g_lo
            last = 1
         end if
         if (hi - lo <= tol) exit
      end do
      x_c = max(lo, min(x, hi))
   contains
      !> The total pressure at r = 0 before the floor (scaled) of the unloading solve at
      !> delta (-1 where the contact is negligible).
      subroutine centre_pressure(delta, p0, error)
         real(dp), intent(in) :: delta
         real(dp), intent(out) :: p0
         type(egw_error), allocatable, intent(out) :: error
         type(scaled_problem) :: prob
         type(discrete_solution) :: sol
         real(dp), allocatable :: row(:)
         real(dp) :: est
         integer :: method_used
         p0 = -1.0_dp
         prob = unloading_problem(hist, delta)
         if (negligible(prob) .or. .not. allocated(prob%cap)) return
         call solve_scaled(prob, hist%options, sol, est, method_used, error)
         if (allocated(error)) return
         allocate (row(size(sol%p)))
         call influence_row(sol%mesh, 0.0_dp, row)
         p0 = cap_excess(prob, 0.0_dp, base_gap(prob, 0.0_dp) + dot_product(row, sol%p), 1)
      end subroutine centre_pressure
   end subroutine centre_lift_off

   !> One panel [a, b] of half_time: the force at its 17 Chebyshev-Lobatto nodes (p(0) =
   !> p_a given), W at the nodes from w_a, and the panel's time t and W(b) w by the 17-,
   !> 9- and 5-point rules (nested: every 2nd, 4th node).
   subroutine panel(hist, unloading, mass, delta_m, a, b, graded, p_a, w_a, g_0, s_16, s_8, &
         & s_4, p, t, w, est, error)
      type(loading_history), intent(in) :: hist
      logical, intent(in) :: unloading
      real(dp), intent(in) :: mass, delta_m, a, b, p_a, w_a, g_0
      !> a branch point (delta - c)**(3/2) at b: nodes in s with u = b - (b - a)(1 - s)**2,
      !> s in [0, 1], where it is (1 - s)**3, smooth
      logical, intent(in) :: graded
      real(dp), intent(in) :: s_16(0:, 0:), s_8(0:, 0:), s_4(0:, 0:)
      real(dp), intent(out) :: p(0:16), t(3), w(3)
      real(dp), intent(out) :: est   !< the largest est_rel_err of its solves (P > 0)
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: u(0:16), f(0:16), jac(0:16), s
      type(solve_result) :: res
      integer :: j
      ! u(s) and du/dt (t = 2s - 1 in [-1, 1], the rules' variable)
      do j = 0, 16
         s = 0.5_dp*(1.0_dp - cos(pi*j/16))
         if (graded) then
            u(j) = a + (b - a)*s*(2.0_dp - s)
            jac(j) = (b - a)*(1.0_dp - s)
         else
            u(j) = a + (b - a)*s
            jac(j) = 0.5_dp*(b - a)
         end if
      end do
      u(16) = b
      p(0) = p_a
      est = 0.0_dp
      do j = 1, 16
         call curve_point(hist, unloading, delta_m - u(j)**2, res, error)
         if (allocated(error)) return
         p(j) = res%force
         if (res%force > 0.0_dp) est = max(est, res%est_rel_err)
      end do
      f = 2*u*p*jac
      call rule(s_16, 1, t(1), w(1))
      call rule(s_8, 2, t(2), w(2))
      call rule(s_4, 4, t(3), w(3))
   contains
      !> The rule on every stride-th node: W at its nodes, the panel's time, W(b).
      subroutine rule(s, stride, time, work)
         real(dp), intent(in) :: s(0:, 0:)
         integer, intent(in) :: stride
         real(dp), intent(out) :: time, work
         real(dp) :: ww(0:16/stride)
         ww = w_a + matmul(s, f(0:16:stride))
         time = dot_product(s(16/stride, :), speed_inverse(u(0:16:stride), ww) &
            & *jac(0:16:stride))
         work = ww(16/stride)
      end subroutine rule
      !> 2u/v = 2u/sqrt(2 W/m*), its limit g_0 at u = 0; a zero-work stretch (a zero force
      !> at the turning point, then v from the next points) counts nothing.
      elemental real(dp) function speed_inverse(uu, ww) result(gg)
         real(dp), intent(in) :: uu, ww
         if (uu == 0.0_dp) then
            gg = g_0
         else if (ww > 0.0_dp) then
            gg = 2*uu/sqrt(2*ww/mass)
         else
            gg = 0.0_dp
         end if
      end function speed_inverse
   end subroutine panel

   !> The error of q(1), the finest of three nested rules q(1:3) (17, 9, 5 points), from
   !> their observed rate: e_8 = |q1 - q2|, e_4 = |q1 - q3|, e_16 ~ e_8 (e_8/e_4) (the
   !> algebraic rate; a geometric one would give (e_8/e_4)**2, which the cap's unloading
   !> curve at 3 v_y missed 40-fold: 2.1e-8 of the duration against a brute-force
   !> quadrature), at most e_8 where the rules do not converge.
   pure real(dp) function extrapolated_error(q) result(e)
      real(dp), intent(in) :: q(3)
      real(dp) :: e_8, e_4
      e_8 = abs(q(1) - q(2))
      e_4 = abs(q(1) - q(3))
      e = e_8
      if (e_8 < e_4) e = e_8*(e_8/e_4)
   end function extrapolated_error

   !> Clenshaw-Curtis' cumulative matrix on the Chebyshev-Lobatto nodes t_i = -cos(pi i/n):
   !> s(i, j) = int_{-1}^{t_i} l_j, l_j the nodes' Lagrange polynomials (so s(n, :) are the
   !> Clenshaw-Curtis weights): l_j's Chebyshev coefficients, integrated term by term.
   pure function cc_cumulative(n) result(s)
      integer, intent(in) :: n
      real(dp) :: s(0:n, 0:n)
      real(dp) :: c(0:n), t_at(0:n+1, 0:n), theta(0:n), sgn
      integer :: i, j, k
      do i = 0, n
         theta(i) = pi*real(n - i, dp)/n   ! t_i = cos(theta_i)
      end do
      ! int_{-1}^{t_i} T_k for k = 0 .. n
      do i = 0, n
         do k = 0, n
            sgn = merge(1.0_dp, -1.0_dp, mod(k, 2) == 0)   ! T_k(-1) = (-1)**k
            if (k == 0) then
               t_at(k, i) = cos(theta(i)) + 1.0_dp
            else if (k == 1) then
               t_at(k, i) = 0.5_dp*(cos(theta(i))**2 - 1.0_dp)
            else
               t_at(k, i) = (cos((k + 1)*theta(i)) + sgn)/(2.0_dp*(k + 1)) &
                  & - (cos((k - 1)*theta(i)) + sgn)/(2.0_dp*(k - 1))
            end if
         end do
      end do
      do j = 0, n
         ! coefficients of l_j: c_k = (2/n) (1/2 at j = 0, n) cos(k theta_j), c_0, c_n halved
         do k = 0, n
            c(k) = 2.0_dp/n*cos(k*theta(j))
            if (j == 0 .or. j == n) c(k) = 0.5_dp*c(k)
            if (k == 0 .or. k == n) c(k) = 0.5_dp*c(k)
         end do
         do i = 0, n
            s(i, j) = sum(c*t_at(0:n, i))
         end do
      end do
   end function cc_cumulative

   !> u_max = sqrt(delta_m - x_1) with the force at x_1 1 % of P(delta_m): a bracket
   !> widened from the Hertzian unloading length 1.5 P/K, then Newton on the solves'
   !> stiffness kept inside it (bisection where it leaves), to 1e-13 of delta_m - x_1
   !> (t changes by dx_1/v(x_1): ~1e-13 of t).
   subroutine onset(hist, unloading, delta_m, p_m, k_m, u_max, error)
      type(loading_history), intent(in) :: hist
      logical, intent(in) :: unloading
      real(dp), intent(in) :: delta_m, p_m, k_m
      real(dp), intent(out) :: u_max
      type(egw_error), allocatable, intent(out) :: error
      type(solve_result) :: res
      real(dp) :: lo, hi, x, x_new, target, width
      integer :: it
      target = 0.01_dp*p_m
      hi = delta_m
      width = 1.5_dp*p_m/k_m
      lo = delta_m - width
      do it = 1, 60
         call curve_point(hist, unloading, lo, res, error)
         if (allocated(error)) return
         if (res%force <= target) exit
         hi = lo
         width = 2*width
         lo = delta_m - width
      end do
      x = lo
      do it = 1, 100
         if (res%force > target) then
            hi = x
         else
            lo = x
         end if
         if (res%force == target) exit
         x_new = x - (res%force - target)/res%stiffness
         if (.not. (x_new > lo .and. x_new < hi)) x_new = 0.5_dp*(lo + hi)
         if (abs(x_new - x) <= 1.0e-13_dp*(delta_m - x) .or. hi - lo <= 1.0e-13_dp*width) then
            x = x_new
            exit
         end if
         x = x_new
         call curve_point(hist, unloading, x, res, error)
         if (allocated(error)) return
      end do
      u_max = sqrt(max(delta_m - x, 0.0_dp))
   end subroutine onset

   !> Force and stiffness at x on the loading curve, or on the unloading curve of hist.
   subroutine curve_point(hist, unloading, x, res, error)
      type(loading_history), intent(in) :: hist
      logical, intent(in) :: unloading
      real(dp), intent(in) :: x
      type(solve_result), intent(inout) :: res
      type(egw_error), allocatable, intent(out) :: error
      if (unloading) then
         call solve_unload(hist, x, res, error)
      else
         call solve_contact(hist%params, hist%options, x, res, error)
      end if
   end subroutine curve_point

end module egw_impact
