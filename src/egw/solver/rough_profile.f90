!> Contact profiles of a rough sphere in the caller's units (doc/theory.md §5, §8, §12):
!> the total pressure and deflection at given radii of a loading solve (contact_profile)
!> and of an unloading solve after loading to delta_max (contact_profile_unload), and the
!> rough pressure, separation and closest-approach separation of an unloading solve on a
!> loading history (unload_profile). The force's error control does not bound the
!> pressure pointwise, so each profile re-solves egw_rough_sphere's scaled problem at
!> rel_tol/10 until it settles; the smooth sphere with the flow-pressure cap beyond first
!> yield is egw_cap_profile's (cap_profile, cap_unload_profile).
module egw_rough_profile
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_invalid_argument, egw_not_converged, egw_unsupported, &
      & fatal_error, format_real, int_str
   use egw_params, only: contact_params, model_hertz, length_unit, pressure_unit
   use egw_smooth_sphere, only: hertz_pressure, hertz_deflection
   use egw_unloading, only: unloading_pressure
   use egw_halfspace, only: influence_row
   use egw_cap_sphere, only: cap_options
   use egw_cap_profile, only: cap_profile, cap_unload_profile
   use egw_sphere_solver, only: solver_options, scaled_problem, discrete_solution, scaled, &
      & negligible, base_gap, closest_gap, solve_scaled, total_pressure
   use egw_rough_sphere, only: solve_result, loading_history, load_history, check_input, &
      & check_unload_input, smooth_capped, unloading_problem, history_cap, loaded_by_route
   implicit none
   private

   public :: contact_profile, contact_profile_unload, unload_profile

   !> contact_profile: at most this many re-solves at rel_tol/10 each, down to the finest
   !> tolerance the solver's error estimate can resolve in double precision.
   integer, parameter :: profile_levels = 4
   !> capped_profile: the cap solver's rings (finest level)
   integer, parameter :: cap_profile_rings = 256
   !> the tightest rel_tol of those re-solves
   real(dp), parameter :: finest_profile_tol = 1.0e-12_dp

contains

   !> Rough (asperity) pressure p_G, separation d and closest-approach separation d_max
   !> at the radii r(:) >= 0 of the unloading solve at delta < history%delta_max (where
   !> d < d_max the loading law holds; elsewhere the unloading law). For delta >=
   !> delta_max or a reversible history, d_max = d. Errors as solve_unload, and sizes or
   !> radii that do not fit (egw_invalid_argument); outputs untouched on error.
   subroutine unload_profile(history, delta, r, pressure, separation, separation_min, error)
      type(loading_history), intent(in) :: history   !< from load_history (only read)
      real(dp), intent(in) :: delta   !< overlap [length] of the unloading solve
      real(dp), intent(in) :: r(:)                   !< radii, >= 0
      real(dp), intent(inout) :: pressure(:)         !< p_G at r
      real(dp), intent(inout) :: separation(:)       !< d at r
      real(dp), intent(inout) :: separation_min(:)   !< d_max at r
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      type(scaled_problem) :: prob
      type(discrete_solution) :: sol
      real(dp), allocatable :: row(:), rs(:), gap(:), gap_min(:), f(:), dfdh(:)
      real(dp) :: est, length, c
      integer :: i, method_used

      if (history%capped .or. (history%params%flow_pressure > 0.0_dp .and. &
         & .not. history%reversible)) then
         call fatal_error(error, egw_unsupported, "flow_pressure = " &
            & //format_real(history%params%flow_pressure)//": the unloading profile " &
            & //"with the cap (beyond first yield, or rough) is not available yet (forces are)")
         return
      end if
      if (size(pressure) /= size(r) .or. size(separation) /= size(r) .or. &
         & size(separation_min) /= size(r)) then
         call fatal_error(error, egw_invalid_argument, "pressure/separation/separation_min:" &
            & //" sizes differ from size(r) = "//int_str(size(r)))
         return
      end if
      call check_radii(r, size(r), size(r), error)   ! (the sizes checked above)
      if (allocated(error)) return
      if (.not. history%loaded .or. .not. ieee_is_finite(delta)) then
         call fatal_error(error, egw_invalid_argument, "delta = "//format_real(delta) &
            & //" or history: the overlap must be finite and the history loaded")
         return
      end if
      if (history%reversible .or. delta >= history%delta_max) then
         call fatal_error(error, egw_invalid_argument, "delta = "//format_real(delta) &
            & //": the unloading profile needs delta < delta_max and a rough history")
         return
      end if
      prob = unloading_problem(history, delta)
      length = length_unit(history%params)
      rs = r/length
      if (negligible(prob)) then
         gap = base_gap(prob, rs)
         f = 0.0_dp*rs
      else
         call solve_scaled(prob, history%options, sol, est, method_used, error)
         if (allocated(error)) return
         allocate (row(size(sol%p)), gap(size(r)), f(size(r)), dfdh(size(r)))
         do i = 1, size(r)
            call influence_row(sol%mesh, rs(i), row)
            gap(i) = base_gap(prob, rs(i)) + dot_product(row, sol%p)
         end do
      end if
      gap_min = closest_gap(prob%closest, rs)
      if (.not. negligible(prob)) call unloading_pressure(prob%unload, gap, gap_min, f, dfdh)
      c = pressure_unit(history%params)
      pressure = c*prob%scale*f
      separation = history%params%sigma*gap
      separation_min = history%params%sigma*gap_min
   end subroutine unload_profile

   !> Total pressure p and deflection w at the radii r(:) >= 0 of the unloading (or
   !> reloading) solve at delta after loading to delta_max (solve_contact_unload's
   !> contact): delta >= delta_max is contact_profile at delta; reversible histories (Hertz
   !> below first yield, GW/E-GW, EP-GW with psi = 0: the unloading law is the loading
   !> law) too; the smooth sphere with the cap loaded beyond first yield is
   !> cap_unload_profile's (w the surfaces' total displacement, plastic crater included);
   !> EP-GW: Hertz + the rough unloading pressure p_G(d, d_max) (unload_profile) and w
   !> the rough layer's deflection + Hertz's, the unloading solve tightened by 10 until
   !> the profile changes by at most rel_tol of its peak (pressure) and of its largest
   !> deflection (the history loaded at 1e-4 of rel_tol, at least 1e-10). A rough sphere
   !> with the cap: capped_rough_unload_profile; after a history the small-sigma route
   !> loaded (no rough field): egw_unsupported.
   subroutine contact_profile_unload(params, options, delta, delta_max, r, pressure, &
      & deflection, error)
      type(contact_params), intent(in) :: params   !< the contact
      type(solver_options), intent(in) :: options   !< tolerance of the solves
      real(dp), intent(in) :: delta       !< overlap of the profile [length]
      real(dp), intent(in) :: delta_max   !< largest overlap reached before [length]
      real(dp), intent(in) :: r(:)             !< radii, >= 0
      real(dp), intent(out) :: pressure(:)     !< total pressure at r, size(r)
      real(dp), intent(out) :: deflection(:)   !< total deflection at r, size(r)
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      type(loading_history) :: hist
      type(solve_result) :: loaded
      type(solver_options) :: tight
      type(scaled_problem) :: prob
      real(dp), allocatable :: pg(:), d(:), dmin(:), p_prev(:), w_prev(:), p_new(:), &
         & w_new(:), rs(:)
      integer :: i, level
      logical :: converged

      call check_unload_input(params, options, delta, delta_max, error)
      if (allocated(error)) return
      if (delta >= delta_max .or. ((params%model == model_hertz .or. params%sigma == &
         & 0.0_dp) .and. .not. smooth_capped(params, delta_max))) then
         call contact_profile(params, options, delta, r, pressure, deflection, error)
         return
      end if
      call check_radii(r, size(pressure), size(deflection), error)
      if (allocated(error)) return
      tight = options
      tight%rel_tol = max(1.0e-10_dp, 1.0e-4_dp*options%rel_tol)
      call load_history(params, tight, delta_max, hist, loaded, error)
      if (allocated(error)) return
      if (hist%capped) then
         call cap_unload_profile(history_cap(hist), cap_profile_rings, delta, r, pressure, &
            & deflection, error)
         return
      end if
      if (hist%reversible) then
         call contact_profile(params, options, delta, r, pressure, deflection, error)
         return
      end if
      if (loaded_by_route(hist)) then
         call fatal_error(error, egw_unsupported, "flow_pressure = " &
            & //format_real(params%flow_pressure)//", delta_max = "//format_real(delta_max) &
            & //": the history was loaded by the small-sigma route (no rough field), whose " &
            & //"unloading profile is not available (forces are)")
         return
      end if
      if (params%flow_pressure > 0.0_dp) then
         call capped_rough_unload_profile(hist, options, delta, r, pressure, deflection, &
            & error)
         return
      end if
      ! the rough unloading pressure p_G and separation d: the rough layer's deflection
      ! is d - sigma base_gap (base_gap: the Hertz-deformed or rigid gap)
      prob = scaled(params, delta)
      rs = r/length_unit(params)
      allocate (pg(size(r)), d(size(r)), dmin(size(r)), p_new(size(r)), w_new(size(r)), &
         & p_prev(size(r)), w_prev(size(r)))
      hist%options = options
      converged = .false.
      do level = 0, profile_levels
         call unload_profile(hist, delta, r, pg, d, dmin, error)
         if (allocated(error)) return
         do i = 1, size(r)
            w_new(i) = d(i) - params%sigma*base_gap(prob, rs(i))
         end do
         p_new = pg
         if (prob%extended) then
            p_new = p_new + hertz_pressure(r, delta, params%radius, params%modulus)
            w_new = w_new + hertz_deflection(r, delta, params%radius)
         end if
         if (level > 0) then
            converged = settled(p_new, p_prev, w_new, w_prev, options%rel_tol)
            if (converged) exit
         end if
         p_prev = p_new
         w_prev = w_new
         if (hist%options%rel_tol <= finest_profile_tol) exit
         hist%options%rel_tol = max(hist%options%rel_tol/10.0_dp, finest_profile_tol)
      end do
      if (.not. converged) then
         call fatal_error(error, egw_not_converged, "profile_unload: the pressure profile " &
            & //"did not settle to rel_tol = "//format_real(options%rel_tol)//" of its peak")
         return
      end if
      pressure = p_new
      deflection = w_new
   end subroutine contact_profile_unload

   !> The scaled problem prob (loading, or unloading on a history's field) solved at
   !> options%rel_tol, then again at rel_tol/10 (down to finest_profile_tol) until its
   !> total pressure and deflection at the radii r (>= 0, checked) change by at most
   !> rel_tol of the peak pressure and of the largest deflection; egw_not_converged
   !> (naming what, the caller's entry) if they do not. In params' units.
   subroutine settled_profile(prob, options, params, r, pressure, deflection, error, what)
      type(scaled_problem), intent(inout) :: prob
      type(solver_options), intent(in) :: options
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: r(:)
      real(dp), intent(out) :: pressure(:), deflection(:)
      type(egw_error), allocatable, intent(out) :: error
      character(len=*), intent(in) :: what
      type(discrete_solution) :: sol
      type(solver_options) :: level_options
      real(dp) :: est
      real(dp), allocatable :: rs_all(:), p_prev(:), w_prev(:), p_new(:), w_new(:)
      integer :: i, method_used, level
      logical :: converged
      ! The force's error control does not bound the pressure pointwise (classic GW deep
      ! in contact: 2e-4 of the peak at rel_tol 1e-6). Solve again at rel_tol/10 until
      ! the profile changes by at most rel_tol of its peak (pressure) and of the largest
      ! deflection: the finer of the two is then the answer.
      rs_all = [0.0_dp, r/length_unit(params)]
      do i = 2, size(rs_all)
         if (.not. ieee_is_finite(rs_all(i))) then
            call fatal_error(error, egw_invalid_argument, "r("//int_str(i - 1)//") = " &
               & //format_real(r(i - 1))//": r/sqrt(R sigma) exceeds the largest double")
            return
         end if
         ! the fields are even and smooth in r: below 1e-150 of the scaled length they
         ! equal their value at 0 to rounding (and the kernels' 1/r would overflow)
         if (rs_all(i) < 1.0e-150_dp) rs_all(i) = 0.0_dp
      end do
      allocate (p_prev(size(rs_all)), w_prev(size(rs_all)), p_new(size(rs_all)), &
         & w_new(size(rs_all)))
      level_options = options
      converged = .false.
      do level = 0, profile_levels
         call solve_scaled(prob, level_options, sol, est, method_used, error)
         if (allocated(error)) return
         call profile_values(prob, sol, rs_all, p_new, w_new)
         if (level > 0) then
            converged = settled(p_new, p_prev, w_new, w_prev, options%rel_tol)
            if (converged) exit
         end if
         p_prev = p_new
         w_prev = w_new
         if (level_options%rel_tol <= finest_profile_tol) exit
         level_options%rel_tol = max(level_options%rel_tol/10.0_dp, finest_profile_tol)
      end do
      if (.not. converged) then
         call fatal_error(error, egw_not_converged, what//": the pressure profile did " &
            & //"not settle to rel_tol = "//format_real(options%rel_tol)//" of its peak")
         return
      end if
      pressure = p_new(2:)*pressure_unit(params)
      deflection = w_new(2:)*params%sigma
   end subroutine settled_profile

   !> contact_profile_unload of a rough sphere with the cap after the discrete loading
   !> history hist: the unloading solve (the history's closest field, the cap's law and
   !> plastic shift: total_pressure) re-done at rel_tol/10 until the profile settles (as
   !> contact_profile); w the elastic deflection (rough layer + Hertz's).
   subroutine capped_rough_unload_profile(hist, options, delta, r, pressure, deflection, &
      & error)
      type(loading_history), intent(in) :: hist
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta, r(:)
      real(dp), intent(out) :: pressure(:), deflection(:)
      type(egw_error), allocatable, intent(out) :: error
      type(scaled_problem) :: prob
      prob = unloading_problem(hist, delta)
      if (negligible(prob)) then
         pressure = 0.0_dp
         deflection = 0.0_dp
         return
      end if
      call settled_profile(prob, options, hist%params, r, pressure, deflection, error, &
         & "profile_unload")
   end subroutine capped_rough_unload_profile


   !> Total pressure p and deflection w (Hertz + rough part for E-GW/EP-GW, the GW part for
   !> classic GW, Hertz for model_hertz or sigma = 0) at the radii r(:) >= 0, pointwise
   !> within options%rel_tol of the peak pressure and of the largest deflection (re-solved
   !> at rel_tol/10 until the profile settles; egw_not_converged if it does not).
   subroutine contact_profile(params, options, delta, r, pressure, deflection, error)
      type(contact_params), intent(in) :: params   !< the contact
      type(solver_options), intent(in) :: options   !< tolerance of the solves
      real(dp), intent(in) :: delta   !< overlap [length]: > 0 pressed together, < 0 apart
      real(dp), intent(in) :: r(:)             !< radii, >= 0
      real(dp), intent(out) :: pressure(:)     !< total pressure at r, size(r)
      real(dp), intent(out) :: deflection(:)   !< total deflection at r, size(r)
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      type(scaled_problem) :: prob

      call check_input(params, options, delta, error)
      if (allocated(error)) return
      call check_radii(r, size(pressure), size(deflection), error)
      if (allocated(error)) return
      if (smooth_capped(params, delta)) then
         call capped_profile(params, delta, r, pressure, deflection, error)
         return
      end if
      if (params%model == model_hertz .or. params%sigma == 0.0_dp) then
         pressure = hertz_pressure(r, delta, params%radius, params%modulus)
         deflection = hertz_deflection(r, delta, params%radius)
         if (.not. all(ieee_is_finite(pressure) .and. ieee_is_finite(deflection))) &
            & call fatal_error(error, egw_invalid_argument, "delta = "//format_real(delta) &
            & //": the Hertz pressure or deflection at r exceeds the largest double")
         return
      end if

      prob = scaled(params, delta)
      if (negligible(prob)) then
         pressure = 0.0_dp
         deflection = 0.0_dp
         return
      end if
      call settled_profile(prob, options, params, r, pressure, deflection, error, "profile")
   end subroutine contact_profile

   !> contact_profile of the smooth sphere with the cap beyond first yield (cap_profile) on
   !> up to cap_profile_rings rings, whatever options%rel_tol: the rings' pressures
   !> converge as (1/rings)**2 (a change of 3e-5 p_y from 128 to 256 rings at 2 delta_y),
   !> so rel_tol 1e-6 would take ~4000 rings. Measured against
   !> tools/reference/cap_reference.py --profile 2 5 20: p within 1.5e-5 p_y (the
   !> reference's own error: up to 3.1e-5), w within 1e-9 delta_y; 2 pi int p r dr within
   !> 5.2e-6 of the force from 1.5 to 30 delta_y (test_cap_sphere, test_cap_profile).
   subroutine capped_profile(params, delta, r, pressure, deflection, error)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: delta, r(:)
      real(dp), intent(out) :: pressure(:), deflection(:)
      type(egw_error), allocatable, intent(out) :: error
      call cap_profile(params%radius, params%modulus, params%flow_pressure, delta, &
         & cap_options(n_rings=cap_profile_rings/2, n_levels=2), r, pressure, deflection, &
         & error)
   end subroutine capped_profile

   !> Total pressure and deflection of a solved contact at scaled radii rs (scaled units).
   subroutine profile_values(prob, sol, rs, pressure, deflection)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(in) :: sol
      real(dp), intent(in) :: rs(:)
      real(dp), intent(out) :: pressure(:), deflection(:)
      real(dp), allocatable :: row(:)
      real(dp) :: wg, f(1), dfdh(1)
      integer :: i
      allocate (row(size(sol%p)))
      do i = 1, size(rs)
         call influence_row(sol%mesh, rs(i), row)
         wg = dot_product(row, sol%p)
         if (allocated(prob%cap)) then
            ! the cap on the total pressure (its law and plastic shift: total_pressure)
            pressure(i) = total_pressure(prob, sol, rs(i))
         else
            call prob%law%pressure([base_gap(prob, rs(i)) + wg], f, dfdh)
            pressure(i) = f(1)
            if (prob%extended) pressure(i) = pressure(i) + &
               & hertz_pressure(rs(i), prob%delta, 1.0_dp, 1.0_dp)
         end if
         deflection(i) = wg
         if (prob%extended) deflection(i) = deflection(i) + &
            & hertz_deflection(rs(i), prob%delta, 1.0_dp)
      end do
   end subroutine profile_values

   !> A profile's radii and outputs: pressure and deflection of sizes n_pressure and
   !> n_deflection as long as r, every radius finite and >= 0; else egw_invalid_argument
   !> naming the sizes or the first radius refused.
   pure subroutine check_radii(r, n_pressure, n_deflection, error)
      real(dp), intent(in) :: r(:)   !< radii [length]
      integer, intent(in) :: n_pressure, n_deflection   !< the outputs' sizes
      type(egw_error), allocatable, intent(out) :: error
      integer :: i
      if (n_pressure /= size(r) .or. n_deflection /= size(r)) then
         call fatal_error(error, egw_invalid_argument, "pressure/deflection: size " &
            & //int_str(n_pressure)//"/"//int_str(n_deflection) &
            & //" differs from size(r) = "//int_str(size(r)))
         return
      end if
      do i = 1, size(r)
         if (.not. ieee_is_finite(r(i)) .or. r(i) < 0.0_dp) then
            call fatal_error(error, egw_invalid_argument, "r("//int_str(i)//") = " &
               & //format_real(r(i))//": radii must be finite and >= 0")
            return
         end if
      end do
   end subroutine check_radii

   !> Whether a profile settled from one level to the next: its pressures p and deflections
   !> w changed by at most rel_tol of the largest |p| and of the largest |w|.
   pure logical function settled(p_new, p_prev, w_new, w_prev, rel_tol)
      real(dp), intent(in) :: p_new(:), p_prev(:)   !< pressures, this level and the last
      real(dp), intent(in) :: w_new(:), w_prev(:)   !< deflections, likewise
      real(dp), intent(in) :: rel_tol   !< the caller's tolerance
      settled = maxval(abs(p_new - p_prev)) <= rel_tol*maxval(abs(p_new)) .and. &
         & maxval(abs(w_new - w_prev)) <= rel_tol*maxval(abs(w_new))
   end function settled

end module egw_rough_profile
