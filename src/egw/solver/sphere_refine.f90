!> The refinement levels of the sphere solver (egw_sphere_solver; doc/theory.md §7
!> "Error control"): levels of decreasing step and their force error estimate
!> (Richardson, the tail, what the kink edges miss by), the kink edges relocated on a
!> level, and the central disc of an unloading after a capped loading.
module egw_sphere_refine
   use egw_progress, only: progress_note
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, egw_not_converged, fatal_error, format_real
   use egw_halfspace, only: interpolate_nodal, influence_cache
   use egw_sphere_problem, only: solver_options, tiny_force, scaled_problem, discrete_solution, &
      & base_gap, closest_gap, smooth_force, rough_pressure, cap_fields, force_floor, sums_total
   use egw_sphere_mesh, only: force_order, finest_step, mesh_family, kink_radii
   use egw_sphere_regime, only: yield_overlap, stall_fallbacks, gw_confirm, capped_history, &
      & halved_levels, capped_gw
   use egw_sphere_level, only: solve_with_tail, move_solution, copy_level, take_level
   implicit none
   private

   public :: refine_levels, relocate_kinks, central_disc

   !> The levels' central disc (central_disc): a contact ending below this fraction of
   !> the Hertz radius (kept up to twice it once a solve's levels have one).
   real(dp), parameter :: central_fraction = 0.25_dp
   !> The levels' central disc (central_disc) only at sigma/delta_y >= disc_sigma: at
   !> 1e-6 (E-GW + cap, 0.15 delta_max after 2 delta_y, c = 0.29 a) the disc's levels
   !> agreed while 6e-6 off and converged like step**1 beyond (kinks inside the disc
   !> that come and go); not examined further (doc/stability.md Stop 48).
   real(dp), parameter :: disc_sigma = 1.0e-5_dp

contains

   !> Levels of decreasing step (doc/theory.md §7 "Error control"), each warm-started from
   !> the last (coarse): the force of each and of the one before give the Richardson
   !> estimate |P_h - P_H|/((H/h)**order - 1) of the error of P_h, plus the tail and (for
   !> unloading) the kink offsets (add_kink_error); below rel_tol/2 the level is accepted,
   !> else the next step is predicted from the estimate. Unloading after a capped loading
   !> (sums_total): no level keeps an element of the level before (halved_levels).
   subroutine refine_levels(prob, options, method, order, mesh, coarse, sol, est, error, cache)
      !> the scaled problem (its kink edges and disc follow the levels)
      type(scaled_problem), intent(inout) :: prob
      type(solver_options), intent(in) :: options   !< the solver's options
      integer, intent(in) :: method   !< method_newton or method_picard
      real(dp), intent(in) :: order   !< order assumed by the Richardson estimate
      !> the route's mesh family, its step refined level by level
      type(mesh_family), intent(inout) :: mesh
      type(discrete_solution), intent(inout) :: coarse   !< the previous level
      type(discrete_solution), intent(out) :: sol   !< the accepted level's solution
      real(dp), intent(out) :: est   !< its estimated relative force error
      type(egw_error), allocatable, intent(out) :: error   !< egw_not_converged or the failure met
      type(influence_cache), intent(inout), optional :: cache   !< of the route's levels
      real(dp) :: total
      integer :: level
      logical :: confirm, confirming, vanished, halve, kept_any

      confirm = .false.
      confirming = .false.
      halve = halved_levels(prob, options)
      do level = 1, 12
         ! The previous level's solution is the initial guess: 2-3 Newton steps instead of 5-8.
         if (halve) then
            call solve_with_tail(prob, options, method, mesh%layered, mesh%focus, &
               & mesh%width, mesh%step, mesh%outer, sol, error, coarse, cache=cache, &
               & level_before=coarse%mesh%edge(0:coarse%mesh%n_elem), &
               & step_before=mesh%step_prev, kept=kept_any)
         else
            call solve_with_tail(prob, options, method, mesh%layered, mesh%focus, &
               & mesh%width, mesh%step, mesh%outer, sol, error, coarse, cache=cache)
         end if
         if (allocated(error)) then
            if (.not. skip_failed_level(prob, options, error, mesh)) return
            deallocate (error)
            cycle
         end if
         ! (a level that halved what it kept stands for the confirming level below, as
         ! the bisection check it replaced did: both see the kept elements' error; but
         ! not for the one rel_tol < 1e-6 asks for, two levels that agree by accident
         ! while both are off: E-GW + cap, README's pair, 2.1221 sigma after 209 sigma
         ! at rel_tol 1e-8, the first refinement level (step 0.275) accepted against the
         ! locating level (0.413) with an estimate of 3.8e-9 while 1.3e-8 off;
         ! doc/benchmarks.md "Stop 62: acc28")
         if (halve .and. options%rel_tol >= 1.0e-6_dp) confirm = confirm .or. kept_any
         if (options%n_radial == 0) prob%disc = central_disc(prob, sol)
         ! (a sign of life for a progress hook: a level of a hard solve takes seconds)
         call progress_note("solve: mesh level")
         total = abs(smooth_force(prob) + sol%force)
         est = 0.0_dp
         if (total < tiny_force) then
            ! Unloading far apart: the force has fallen to the underflow range, where
            ! relative differences are rounding noise. As for negligible(): 0, error 1.
            sol%p = 0.0_dp
            sol%force = 0.0_dp
            est = 1.0_dp
            return
         end if
         total = max(total, force_floor(prob))
         ! Discretisation (Richardson) plus the force estimated beyond the outer radius,
         ! which both levels share and their difference cannot see.
         if (total > 0.0_dp) est = discretisation_error(sol%force, coarse%force, total, &
            & mesh%step_prev/mesh%step, confirming, order) + sol%tail/total
         if (allocated(prob%branch) .and. total > 0.0_dp) then
            call add_kink_error(prob, options, method, order, confirming, mesh, coarse, sol, &
               & total, est, vanished, error, cache=cache)
            if (allocated(error)) return
            if (vanished) cycle
         end if
         ! Half the tolerance: a margin for the estimate itself.
         if (options%n_radial > 0) return
         if (est <= 0.5_dp*options%rel_tol) then
            ! Below rel_tol 1e-6 the two levels of an unloading solve can agree by accident
            ! while both are off (the elements beside a d = d_max edge: psi 10, delta 0.3
            ! after delta_max 1, rel_tol 1e-7: 1.6e-7 off under an estimate of 2.4e-9; 4 of
            ! the 92 solves of egw-bench --unloading-sweep at 1e-7, up to 2.7e-7): one level
            ! more, at half the step, whose estimate is the whole difference to the
            ! accepted level, not its Richardson fraction (later levels, if that fails, are
            ! estimated as before). The sweep then has none above rel_tol. EP-GW after a
            ! capped loading at any rel_tol (doc/theory.md section 12): sigma = delta_y/100,
            ! from 9.375 delta_y at rel_tol 1e-5 and 2.5e-6, two levels agreed while both
            ! were 1e-4 of P(delta_max) off (estimates ~1e-6), smoothly over a tenth of the
            ! unloading span, and a hysteresis table at 1e-4 did not build. (Not E-GW + cap,
            ! whose unloading law has no d = d_max branch: its table at 1e-4 to 6 delta_y
            ! moved by 2.7e-5 with the level, and its build took 1.7x as long.) Classic GW
            ! after a capped loading (gw_confirm, no kink edges) likewise: sigma/delta_y =
            ! 1e-4, 65764 sigma after 78759 at rel_tol 1e-4, the first two levels agreed to
            ! 4.2e-5 while 5e-4 off, and egw-table's build at 1e-3 did not (doc/stability.md
            ! "Stop 50 (gw16)"). Loading E-GW/EP-GW with the cap at any rel_tol: two levels
            ! agreed while both were off by as much as 20-90x their estimate (sigma/delta_y
            ! = 1e-5, 40 delta_y, rel_tol 1e-6: 1.9e-5 under 2.1e-7; 1e-2, 40 delta_y:
            ! 1.5e-6 under 2.8e-8 with the elements inside a graded), the cap's edge c
            ! moving through the levels' elements (doc/benchmarks.md "Stop 58: edge24").
            ! Classic GW after a capped loading at larger sigma/delta_y: only the first
            ! refinement level, estimated against the locating level, is confirmed. Both
            ! are coarse (13 elements) and near the unloading curve's knee they agreed to
            ! 1.3e-6 while 3.6e-4 of the force off (README's GW + cap, 128.0475 sigma after
            ! 399.04 sigma at rel_tol 1e-5; the next level sees it); past level 1 the
            ! levels were within their estimates (doc/benchmarks.md "Stop 68: gw34").
            if (confirm .or. .not. ((allocated(prob%branch) .and. &
               & (options%rel_tol < 1.0e-6_dp .or. capped_history(prob) .or. &
               & capped_loading(prob))) .or. gw_confirm(prob) .or. (level == 1 .and. &
               & capped_gw(prob))) .or. mesh%step <= finest_step) return
            confirm = .true.
            confirming = .true.
            mesh%step_prev = mesh%step
            mesh%step = max(finest_step, 0.5_dp*mesh%step)
            call copy_level(sol, coarse)
            cycle
         end if
         confirming = .false.
         if (mesh%step <= finest_step) exit
         mesh%step_prev = mesh%step
         mesh%step = max(finest_step, 0.25_dp*mesh%step, min(mesh%step/1.25_dp, &
            & mesh%step*(0.25_dp*options%rel_tol/est)**(1.0_dp/force_order)))
         call copy_level(sol, coarse)
      end do
      call fatal_error(error, egw_not_converged, "rel_tol = "//format_real(options%rel_tol) &
         & //" not reached: the finest mesh's force error estimate is "//format_real(est) &
         & //", above rel_tol/2 = "//format_real(0.5_dp*options%rel_tol) &
         & //" (half: a margin for the estimate); this solve reaches rel_tol >= " &
         & //format_real(2.0_dp*est))
   end subroutine refine_levels

   !> Loading an extended model (E-GW, EP-GW) with the cap: its levels end with a
   !> confirming level (refine_levels).
   pure logical function capped_loading(prob)
      type(scaled_problem), intent(in) :: prob
      capped_loading = prob%extended .and. allocated(prob%cap) .and. &
         & .not. allocated(prob%closest)
   end function capped_loading

   !> Unloading after a capped loading: a refinement level whose Newton did not converge
   !> (warm-started from the level before) is skipped: the next level at half its step,
   !> estimated against the last converged level (coarse) with their step ratio.
   logical function skip_failed_level(prob, options, error, mesh) result(skip)
      type(scaled_problem), intent(in) :: prob
      type(solver_options), intent(in) :: options
      type(egw_error), intent(in) :: error
      type(mesh_family), intent(inout) :: mesh
      skip = stall_fallbacks(prob) .and. allocated(prob%closest) .and. &
         & options%n_radial == 0 .and. error%stat == egw_not_converged .and. &
         & mesh%step > finest_step
      if (.not. skip) return
      mesh%step = max(finest_step, 0.5_dp*mesh%step)
   end function skip_failed_level

   !> Unloading (doc/theory.md §8): adds to est what the kink edges still miss by (both
   !> levels share it). Edges off by more than a tenth of rel_tol are moved and both levels
   !> (coarse, sol) solved again; vanished when the force has then fallen to the underflow
   !> range (est is then left as it was).
   subroutine add_kink_error(prob, options, method, order, confirming, mesh, coarse, sol, &
      & total, est, vanished, error, cache)
      type(scaled_problem), intent(inout) :: prob
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      real(dp), intent(in) :: order
      logical, intent(in) :: confirming   !< est is the whole difference of the levels
      type(mesh_family), intent(inout) :: mesh
      type(discrete_solution), intent(inout) :: coarse, sol
      real(dp), intent(in) :: total   !< |force| of the level (sol)
      real(dp), intent(inout) :: est
      logical, intent(out) :: vanished
      type(egw_error), allocatable, intent(out) :: error
      type(influence_cache), intent(inout), optional :: cache   !< of the route's levels
      real(dp), allocatable :: moved(:), kept_branch(:)
      real(dp) :: kink_err, total_again
      integer :: n_moved, kept_n
      type(discrete_solution) :: guess, moved_coarse, moved_sol

      vanished = .false.
      kink_err = kink_offset_error(prob, sol, options%rel_tol, moved, n_moved)/total
      if (kink_err > 0.1_dp*options%rel_tol .and. options%n_radial == 0) then
         kept_branch = prob%branch
         kept_n = prob%n_branch
         prob%branch = moved
         prob%n_branch = n_moved
         ! each level restarts from its own solution, copied without its matrices (the
         ! result, intent out, may not be the guess too; the levels stay as they were
         ! where the moved ones do not converge)
         call copy_level(coarse, guess)
         call solve_with_tail(prob, options, method, mesh%layered, mesh%focus, mesh%width, &
            & mesh%step_prev, mesh%outer, moved_coarse, error, guess, cache=cache)
         if (.not. allocated(error)) then
            call copy_level(sol, guess)
            if (halved_levels(prob, options)) then
               call solve_with_tail(prob, options, method, mesh%layered, mesh%focus, &
                  & mesh%width, mesh%step, mesh%outer, moved_sol, error, guess, &
                  & cache=cache, level_before=moved_coarse%mesh%edge(0: &
                  & moved_coarse%mesh%n_elem), step_before=mesh%step_prev)
            else
               call solve_with_tail(prob, options, method, mesh%layered, mesh%focus, &
                  & mesh%width, mesh%step, mesh%outer, moved_sol, error, guess, cache=cache)
            end if
         end if
         if (allocated(error)) then
            ! Unloading after a capped loading: where a level with the moved edges does
            ! not converge, both levels stay as they were, est with what their edges miss
            ! by (the next level relocates them again)
            if (.not. (stall_fallbacks(prob) .and. allocated(prob%closest) .and. &
               & error%stat == egw_not_converged)) return
            deallocate (error)
            prob%branch = kept_branch
            prob%n_branch = kept_n
            est = est + kink_err
            return
         end if
         call take_level(moved_coarse, coarse)
         call take_level(moved_sol, sol)
         total_again = abs(smooth_force(prob) + sol%force)
         vanished = total_again < tiny_force
         if (vanished) return
         total_again = max(total_again, force_floor(prob))
         kink_err = kink_offset_error(prob, sol, options%rel_tol, moved, n_moved)/total_again
         est = discretisation_error(sol%force, coarse%force, total_again, &
            & mesh%step_prev/mesh%step, confirming, order) + sol%tail/total_again
      end if
      est = est + kink_err
   end subroutine add_kink_error

   !> The relative discretisation error of the finer of two levels (forces fine, coarse,
   !> step ratio) out of their difference: its Richardson fraction for the order assumed,
   !> or the whole difference where the fraction is not trusted (conservative).
   pure real(dp) function discretisation_error(fine, coarse, total, ratio, whole, order) &
      & result(e)
      real(dp), intent(in) :: fine, coarse, total, ratio, order
      logical, intent(in) :: whole
      e = abs(fine - coarse)/total
      if (.not. whole) e = e/(ratio**order - 1.0_dp)
   end function discretisation_error

   !> Kink edges of an unloading solve placed from a solution with them in place (sol, the
   !> first level): while what the edges still miss by (kink_offset_error) exceeds a tenth
   !> of rel_tol, move them and solve that level again (at most 3 times).
   subroutine relocate_kinks(prob, options, method, layered, focus, width, step, outer, sol, &
      & error, cache)
      type(scaled_problem), intent(inout) :: prob   !< the scaled problem, its kink edges moved
      type(solver_options), intent(in) :: options   !< the solver's options
      integer, intent(in) :: method   !< method_newton or method_picard
      logical, intent(in) :: layered   !< geometric layers at the focus
      real(dp), intent(in) :: focus, width, step   !< the family's focus, layer width and step
      real(dp), intent(inout) :: outer   !< outer radius, grown where the tail is not negligible
      !> the level, solved again with the edges moved
      type(discrete_solution), intent(inout) :: sol
      type(egw_error), allocatable, intent(out) :: error   !< egw_not_converged or the failure met
      type(influence_cache), intent(inout), optional :: cache   !< of the route's levels
      type(discrete_solution) :: guess
      real(dp), allocatable :: moved(:)
      real(dp) :: total
      integer :: pass, n_moved
      if (options%n_radial > 0) return
      do pass = 1, 3
         total = abs(smooth_force(prob) + sol%force)
         if (.not. total > 0.0_dp) return
         total = max(total, force_floor(prob))
         if (kink_offset_error(prob, sol, options%rel_tol, moved, n_moved) &
            & <= 0.1_dp*options%rel_tol*total) return
         prob%branch = moved
         prob%n_branch = n_moved
         call move_solution(sol, guess)
         call solve_with_tail(prob, options, method, layered, focus, width, step, outer, sol, &
            & error, guess, cache=cache)
         if (allocated(error)) return
      end do
   end subroutine relocate_kinks

   !> Unloading after a capped loading (sums_total), sigma/delta_y >= disc_sigma: the
   !> radius c of sol's contact where it is a central disc far inside the Hertz radius a
   !> (below central_fraction a), else 0; the next levels grade the disc's elements about c
   !> (prob%disc, sphere_mesh's disc_graded). c: the outermost Gauss point of a positive
   !> total pressure, or the nearest kink edge (prob%branch) within twice that beyond it
   !> (the floor kink, the contact's edge). Set from the locating solve and again from
   !> every level. Near the residual overlap the family, graded about a, held the whole
   !> contact in ONE element [0, kink edge] on every level, a few times longer than the
   !> disc, whose error no level difference sees; the bisection check (once per solve,
   !> now halved_levels) missed it where the kink edge relocated between levels (an
   !> element kept only with both edges exactly the same): E-GW + cap,
   !> sigma = 2e-5 delta_y, 0.1442 delta_max after 2 delta_y, rel_tol 1e-6: 5.6e-4 off
   !> under an estimate of 1.1e-7; sigma = delta_y/100, 117.79 sigma after 380.09 sigma
   !> (the disc 0.12 in a = 10.9): rel_tol 1e-7 8.5e-7 of the force floor off under
   !> 1.6e-9 (doc/stability.md Stop 47 resid13, Stop 48 resid14).
   pure real(dp) function central_disc(prob, sol) result(c)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem, its disc so far
      type(discrete_solution), intent(in) :: sol   !< a level's solution
      logical, allocatable :: inside(:)
      c = prob%disc
      if (.not. sums_total(prob) .or. .not. allocated(sol%p_smooth)) return
      ! (delta_y/sigma = (pi p_y/2)**2 in these units)
      if (yield_overlap(prob) > 1.0_dp/disc_sigma) return
      inside = sol%p + sol%p_smooth > 0.0_dp
      if (.not. any(inside)) return
      c = maxval(sol%mesh%gauss_r, mask=inside)
      if (allocated(prob%branch)) then
         if (any(prob%branch >= c .and. prob%branch <= 2.0_dp*c)) c = minval(prob%branch, &
            & mask=prob%branch >= c .and. prob%branch <= 2.0_dp*c)
      end if
      ! (once a solve's levels have a disc, they keep it up to a/2: a level without it
      ! holds the disc in a few graded elements again, whose error the estimate cannot
      ! see; seen at 0.15 delta_max, sigma = 1e-6 delta_y, c from 0.25 a to 0.29 a)
      if (.not. (c <= central_fraction*prob%a .or. (prob%disc > 0.0_dp .and. &
         & c <= 2.0_dp*central_fraction*prob%a))) c = 0.0_dp
   end function central_disc

   !> Force an unloading solution misses because its kink edges (prob%branch) are off the
   !> kinks of its own field (moved: the kinks located again on sol, branch_radii): at a
   !> kink where dp/dr jumps by J, an edge e off it leaves a wedge of pressure J e**2/2 that
   !> no element polynomial holds, 2 pi r J e**2/2 of force (both levels share it: the
   !> Richardson estimate cannot see it). J by one-sided differences of p on the solution's
   !> field. The kinks of Z_u in Delta (d2p jumps) give J ~ 0: their wedges are e**3.
   !> A kink with no edge near it counts at the distance to the nearest edge of any kind.
   function kink_offset_error(prob, sol, rel_tol, moved, n_moved) result(err)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(in) :: sol
      real(dp), intent(in) :: rel_tol
      real(dp), allocatable, intent(out) :: moved(:)
      integer, intent(out) :: n_moved     !< how many of moved are d = d_max crossings
      real(dp) :: err
      real(dp) :: r, off, s, gapr, jump, pm(-2:2)
      integer :: k, i
      moved = kink_radii(prob, sol, 1.0e-4_dp*rel_tol, n_moved)
      err = 0.0_dp
      do k = 1, size(moved)
         r = moved(k)
         off = huge(1.0_dp)
         if (size(prob%branch) > 0) off = minval(abs(prob%branch - r))
         off = min(off, minval(abs(sol%mesh%edge(0:sol%mesh%n_elem) - r)))
         if (off == 0.0_dp) cycle
         ! difference step: well inside the gap to the neighbouring kinks
         gapr = r
         do i = 1, size(moved)
            if (i /= k) gapr = min(gapr, abs(moved(i) - r))
         end do
         s = 1.0e-3_dp*gapr
         if (.not. s > 0.0_dp) cycle   ! (kinks found twice: counted once)
         do i = -2, 2
            if (i /= 0) pm(i) = pressure_at(r + real(i, dp)*s)
         end do
         jump = ((pm(2) - pm(1)) - (pm(-1) - pm(-2)))/s
         err = err + pi*r*abs(jump)*off**2
      end do
   contains
      real(dp) function pressure_at(x) result(p)
         real(dp), intent(in) :: x
         real(dp) :: gm(1), pr(1), dpdh(1), dpdd(1)
         real(dp), allocatable :: p_smooth(:), dps(:), shift(:), offset(:)
         gm = 0.0_dp
         if (allocated(prob%closest)) gm = closest_gap(prob%closest, [x])
         if (allocated(prob%cap)) call cap_fields(prob, [x], gm, p_smooth, dps, shift, offset)
         call rough_pressure(prob, [base_gap(prob, x) + interpolate_nodal(sol%mesh, sol%w, x)], &
            & gm, p_smooth, dps, shift, offset, pr, dpdh, dpdd)
         p = pr(1)
      end function pressure_at
   end function kink_offset_error

end module egw_sphere_refine
