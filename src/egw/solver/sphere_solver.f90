!> The scaled half-space problem of a rough sphere and its discrete solve (doc/theory.md
!> §5), behind egw_rough_sphere's solves: meshes, continuation, Newton and Picard, the
!> error estimate and the implicit stiffness.
!>
!> Everything is solved in scaled variables (doc/theory.md §5 "useful facts"): radii in units of
!> sqrt(R sigma), gaps and deflections in sigma, pressures in E sqrt(sigma/R), forces in
!> E sqrt(R) sigma**1.5. Then R = E = sigma = 1, the Hertz radius is sqrt(delta/sigma) and
!> the rough-flat law is p_G = mu/(2 sqrt 2) f(h) with f the dimensionless law of
!> egw_asperity (f = F_{3/2} for elastic summits). Scale invariance is thus exact.
!>
!> Unknown: the rough deflection w_G at the nodes of continuous Lagrange elements. The
!> gap at the Gauss points is d = z + w_G (z the base gap: Hertz gap of eq. 28 for the
!> extended models at delta > 0, else r**2/2 - delta), the pressure there is p_G(d) exactly
!> (never interpolated), and w_G = H p_G is imposed at the nodes (collocation) with the
!> influence matrix of egw_halfspace. Newton with a backtracking line search (Jacobian by
!> LAPACK dgetf2/dgetrs, factors reused while they contract), or damped Picard. The force
!> is the Gauss sum of p_G(d).
!>
!> Mesh: graded in asinh((r - focus)/width) (egw_halfspace graded_edges) about the Hertz
!> edge (boundary layer width ~ a (sigma/delta)**(2/3)) with two geometric layers at it for
!> the extended models, about the computed gap's zero for classic GW deep in contact, and
!> about r = 0 otherwise; the outer radius grows until the force left outside is below
!> 1 % of the tolerance. Levels of decreasing step, each warm-started from the previous,
!> until the Richardson estimate from the last two (plus the tail) is below rel_tol/2.
!>
!> Unloading (doc/theory.md §8): with a closest-approach field (scaled_problem%closest) the
!> law is p_G = scale Z_u(d/sigma, d_max/sigma) at fixed d_max (egw_unloading), on the same
!> meshes with the same Newton, error estimate and stiffness (h_min does not depend on
!> delta or w, so the Jacobian and the implicit derivative keep their form); the meshes
!> also get element edges where p(r) is less smooth (first_unloading_level), and Z_u's
!> law-only work is done once (unloading_law_of).
!>
!> The work is split by concern: the problem and what is read off a solution
!> (egw_sphere_problem), the meshes (egw_sphere_mesh), one mesh's nonlinear solve
!> (egw_sphere_iteration), one level with its element edges and tail (egw_sphere_level),
!> the first level of a route (egw_sphere_first_level), the refinement levels and their
!> error estimate (egw_sphere_refine), the regimes where fallbacks apply
!> (egw_sphere_regime); this module runs the routes (default, guided, central-disc,
!> history-edges) and re-exports what egw_rough_sphere uses.
module egw_sphere_solver
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, egw_not_converged, fatal_error
   use egw_halfspace, only: influence_cache, clear_cache
   use egw_solver_workspace, only: solver_workspace
   use egw_sphere_problem, only: method_auto, method_newton, method_picard, solver_options, &
      & max_mesh_nodes, tiny_force, separation_field, scaled_problem, discrete_solution, scaled, &
      & normal, negligible, base_gap, closest_gap, effective_radius, total_pressure, &
      & smooth_force, smooth_stiffness, sums_total
   use egw_sphere_mesh, only: force_order, unload_order, mesh_family, first_mesh, &
      & focus_beyond, innermost_kink
   use egw_sphere_iteration, only: differentiate
   use egw_cap_sphere, only: cap_options, cap_history, cap_result, cap_load
   use egw_sphere_regime, only: yield_overlap, stall_fallbacks
   use egw_sphere_level, only: solve_with_tail
   use egw_sphere_refine, only: refine_levels
   use egw_sphere_first_level, only: first_unloading_level, first_cap_level, refocus_classic_gw, &
      & continuation
   implicit none
   private

   public :: method_auto, method_newton, method_picard, solver_options, max_mesh_nodes, &
      & tiny_force
   public :: separation_field, scaled_problem, discrete_solution
   public :: scaled, normal, negligible, base_gap, closest_gap, solve_scaled, differentiate, &
      & effective_radius, total_pressure, smooth_force, smooth_stiffness, solver_workspace

   !> The central-disc route (disc_cap_unload) only where the innermost kink edge is
   !> below this fraction of the Hertz radius. 0.5: at sigma/delta_y = 2e-4 (E-GW + cap,
   !> from 10.6 delta_y at 5.9 delta_y, issue 32) the disc's edge sat at 0.38 a and every
   !> other route stalled (Newton cycling between the Gauss points' branches of the
   !> total's floor at 0 in the unloaded centre); 0.25 refused it there.
   real(dp), parameter :: disc_fraction = 0.5_dp
   !> ... and, last of all routes (where the default, guided, central-disc and
   !> history-edges routes all failed) and only where the stall fallbacks apply
   !> (stall_fallbacks), below this fraction: the unloaded centre [0, c] of an unloading
   !> mid-way from a deep capped loading (the total at its floor 0 there, the gap within a
   !> sigma of d_max) spans most of the contact. E-GW + cap, sigma/delta_y = 2e-5, 164294
   !> sigma after 324999 (0.51 delta_max, 6.5 delta_y; c = 0.76 a, issue 32): Newton
   !> stalled on the first level of every other route (residual 0.17 .. 0.2, the Gauss
   !> points in elements ~0.1 a long switching between the floor and the stiff law); with
   !> [0, c] split with the step from the first level on it converged, 5.4e-7 of the force
   !> from a fixed mesh of 2049 nodes on the same history (doc/stability.md "Stop 50
   !> (tiny16)"). Not the first choice: refining so wide a disc costs nodes (at 2e-5 a
   !> table build then met a solve that needed more than max_mesh_nodes).
   real(dp), parameter :: wide_disc_fraction = 1.0_dp

contains

   !> Solve on meshes of decreasing step until the estimated force error is below rel_tol/2
   !> (or on the mesh fixed by n_radial), doc/theory.md §7 "Error control": the first
   !> level's mesh (first_mesh), the first level (first_unloading_level for unloading;
   !> continuation if a cold start fails; refocus_classic_gw), then the refinement levels
   !> (refine_levels).
   subroutine solve_scaled(problem, options, sol, est, method_used, error, warm, work)
      type(scaled_problem), intent(in) :: problem   !< the scaled problem (doc/theory.md section 5)
      !> the solver's options (rel_tol, method, n_radial)
      type(solver_options), intent(in) :: options
      type(discrete_solution), intent(out) :: sol   !< the finest level's solution
      real(dp), intent(out) :: est   !< its estimated relative force error
      integer, intent(out) :: method_used   !< method_newton or method_picard, the one that solved it
      type(egw_error), allocatable, intent(out) :: error   !< egw_not_converged or the failure met
      !> unloading: the solution of another solve of the same history (another delta),
      !> the start of the default route's locating solve (first_unloading_level)
      type(discrete_solution), intent(in), optional :: warm
      !> buffers of the caller's earlier solves, reused (else this solve's own)
      type(solver_workspace), intent(inout), optional :: work
      type(solver_workspace) :: own
      if (present(work)) then
         call solve_routes(problem, options, sol, est, method_used, error, work%cache, warm)
      else
         call solve_routes(problem, options, sol, est, method_used, error, own%cache, warm)
      end if
   end subroutine solve_scaled

   !> solve_scaled's routes, each starting from the cache cleared (clear_cache: as a new
   !> one, its storage reused).
   subroutine solve_routes(problem, options, sol, est, method_used, error, cache, warm)
      type(scaled_problem), intent(in) :: problem
      type(solver_options), intent(in) :: options
      type(discrete_solution), intent(out) :: sol
      real(dp), intent(out) :: est
      integer, intent(out) :: method_used
      type(egw_error), allocatable, intent(out) :: error
      type(influence_cache), intent(inout) :: cache
      type(discrete_solution), intent(in), optional :: warm
      type(egw_error), allocatable :: guided_error
      logical :: wide
      call clear_cache(cache)
      call solve_default(problem, options, sol, est, method_used, error, cache, warm)
      if (.not. allocated(error)) return
      ! Loading of an extended model with the cap that did not converge (small
      ! sigma/delta_y: the plastic zone's edge is a layer the default meshes do not
      ! resolve): the guided route; its own failure reports the default route's error.
      if (error%stat /= egw_not_converged .or. .not. allocated(problem%cap)) return
      if (options%n_radial > 0) return
      if (allocated(problem%closest)) then
         if (.not. problem%closest%extended) return
         call clear_cache(cache)
         call guided_cap_unload(problem, options, sol, est, method_used, guided_error, cache)
         ! then, unloading after a capped loading, the central-disc route (near the
         ! residual overlap; last, so that every solve that converged before it came
         ! is unchanged)
         ! (not at sigma/delta_y <= 2e-6, delta_y/sigma = (pi p_y/2)**2 here: below
         ! 1e-6 egw_rough_sphere's asymptotic route answers after a failure, unchanged)
         if (allocated(guided_error) .and. sums_total(problem) .and. &
            & stall_fallbacks(problem)) then
            deallocate (guided_error)
            call clear_cache(cache)
            call disc_cap_unload(problem, options, sol, est, method_used, guided_error, &
               & cache, refused=wide)
            ! and else the history-edges route (mid-unloading)
            if (allocated(guided_error)) then
               deallocate (guided_error)
               call clear_cache(cache)
               call history_cap_unload(problem, options, sol, est, method_used, &
                  & guided_error, cache)
            end if
            ! and last, where the stall fallbacks apply, the central-disc route on an
            ! unloaded centre up to the Hertz radius (wide_disc_fraction), where the
            ! central-disc route refused a wider disc (its first level converged)
            if (allocated(guided_error) .and. stall_fallbacks(problem) .and. wide) then
               deallocate (guided_error)
               call clear_cache(cache)
               call disc_cap_unload(problem, options, sol, est, method_used, guided_error, &
                  & cache, wide_disc_fraction)
            end if
         end if
      else
         if (.not. problem%extended) return
         call clear_cache(cache)
         call guided_cap_solve(problem, options, sol, est, method_used, guided_error, cache)
      end if
      if (.not. allocated(guided_error)) deallocate (error)
   end subroutine solve_routes

   !> The method a solve runs: options%method, Newton for auto.
   elemental integer function solve_method(options) result(method)
      type(solver_options), intent(in) :: options
      method = options%method
      if (method == method_auto) method = method_newton
   end function solve_method

   !> An unloading solve's Newton residual: a scaled residual of 1e-4 rel_tol (at most
   !> 1e-10; solve_default says why), never below residual_tol.
   elemental real(dp) function unload_residual_tol(residual_tol, rel_tol) result(tol)
      real(dp), intent(in) :: residual_tol, rel_tol
      tol = max(residual_tol, min(1.0e-10_dp, 1.0e-4_dp*rel_tol))
   end function unload_residual_tol

   !> Unloading after a capped loading (sums_total), the central-disc route, taken only
   !> where neither the default nor the guided route converged, and only where the
   !> innermost kink edge c is below disc_fraction of the Hertz radius a: the default
   !> route's levels with the elements inside c refined with the step relative to c
   !> (prob%refine_disc, sphere_mesh's disc_refined). Near the residual overlap the
   !> total pressure lives on such a disc [0, c], c = 0.04 .. 0.09 a (a the radius the
   !> mesh family is graded about), that held 1 to 5 graded elements: kept between levels
   !> (the fixed edges 0 and c) they agreed by accident, and refined with the step they
   !> shrank like step a, so the finest step was reached with estimates of 6.0e-7 ..
   !> 6.7e-7 (steel beads, E-GW + cap and EP-GW + cap, sigma 10 nm, doc/stability.md).
   subroutine disc_cap_unload(problem, options, sol, est, method_used, error, cache, &
      & fraction, refused)
      type(scaled_problem), intent(in) :: problem
      type(solver_options), intent(in) :: options
      type(discrete_solution), intent(out) :: sol
      real(dp), intent(out) :: est
      integer, intent(out) :: method_used
      type(egw_error), allocatable, intent(out) :: error
      !> the levels' influence matrices (shared elements), cleared
      type(influence_cache), intent(inout) :: cache
      !> the route only where c is below this fraction of a (default disc_fraction)
      real(dp), intent(in), optional :: fraction
      !> the route refused a disc beyond disc_fraction a (its first level converged)
      logical, intent(out), optional :: refused
      type(scaled_problem) :: prob
      type(mesh_family) :: mesh
      type(discrete_solution) :: coarse
      real(dp) :: disc, most
      if (present(refused)) refused = .false.
      most = disc_fraction
      if (present(fraction)) most = fraction
      prob = problem
      prob%refine_disc = .true.
      method_used = solve_method(options)
      prob%residual_tol = unload_residual_tol(prob%residual_tol, options%rel_tol)
      call first_mesh(prob, options, mesh)
      call first_unloading_level(prob, options, method_used, mesh, coarse, error, cache=cache)
      if (allocated(error)) return
      ! only where the innermost kink edge is a central disc's well inside the Hertz edge
      ! (elsewhere, e.g. mid-unloading at 0.67 delta_max, the route would only repeat the
      ! default route's levels)
      disc = innermost_kink(prob)
      ! (the wide route only where the first refused: c beyond disc_fraction a)
      if (.not. disc <= most*prob%a .or. (present(fraction) .and. disc <= &
         & disc_fraction*prob%a)) then
         if (present(refused)) refused = disc > disc_fraction*prob%a
         call fatal_error(error, egw_not_converged, "no central disc")
         return
      end if
      call refine_levels(prob, options, method_used, unload_order, mesh, coarse, sol, est, &
         & error, cache=cache)
   end subroutine disc_cap_unload

   !> Unloading after a capped loading (sums_total), the history-edges route, taken only
   !> where the default, guided and central-disc routes did not converge: the default
   !> route's levels with the element edges of the history's mesh as element edges of
   !> every level (prob%history_edges, sphere_mesh's with_history_edges). The
   !> closest-approach field d_max(r) is the history's piecewise quadratic deflection,
   !> whose slope jumps at the history's element edges; in the capped zone the unloading
   !> pressure follows d_max (the plastic shift and offset), so p(r) has a kink at each,
   !> inside the unloading elements, and the levels' forces moved irregularly (steel
   !> beads, sigma 42 nm, 0.67 delta_max after 5.5 delta_y: E-GW + cap 485.8159, 485.8014,
   !> 485.7965, 485.7979 on steps 0.124 .. 0.01, estimates down to 1.5e-6; EP-GW + cap
   !> 2.1e-6 off at the finest step, estimate 1.2e-6). With them one level met rel_tol,
   !> both within 9e-9 of the same route on the history's edges beyond 0.87 a only
   !> (fewer nodes, so that its bisection check ran).
   subroutine history_cap_unload(problem, options, sol, est, method_used, error, cache)
      type(scaled_problem), intent(in) :: problem
      type(solver_options), intent(in) :: options
      type(discrete_solution), intent(out) :: sol
      real(dp), intent(out) :: est
      integer, intent(out) :: method_used
      type(egw_error), allocatable, intent(out) :: error
      !> the levels' influence matrices (shared elements), cleared
      type(influence_cache), intent(inout) :: cache
      type(scaled_problem) :: prob
      prob = problem
      prob%history_edges = .true.
      call solve_default(prob, options, sol, est, method_used, error, cache)
   end subroutine history_cap_unload

   !> Unloading after a capped loading, the guided route (as guided_cap_solve): the
   !> smooth cap model's plastic radius at delta_max, where the history's plastic shift
   !> has its edge, is an element edge with layers on both sides (prob%kink_width) from
   !> the locating solve on; then first_unloading_level and the levels as on the default
   !> route.
   subroutine guided_cap_unload(problem, options, sol, est, method_used, error, cache)
      type(scaled_problem), intent(in) :: problem
      type(solver_options), intent(in) :: options
      type(discrete_solution), intent(out) :: sol
      real(dp), intent(out) :: est
      integer, intent(out) :: method_used
      type(egw_error), allocatable, intent(out) :: error
      !> the levels' influence matrices (shared elements), cleared
      type(influence_cache), intent(inout) :: cache
      type(discrete_solution) :: coarse, start
      type(scaled_problem) :: prob, at_max
      type(mesh_family) :: mesh
      real(dp) :: edge
      prob = problem
      method_used = solve_method(options)
      prob%residual_tol = unload_residual_tol(prob%residual_tol, options%rel_tol)
      call first_mesh(prob, options, mesh)
      at_max = prob
      at_max%delta = prob%closest%delta
      at_max%a = sqrt(at_max%delta)
      call smooth_cap_edge(at_max, edge, error)
      if (allocated(error)) return
      prob%branch = [edge]
      prob%n_branch = 0
      prob%kink_width = mesh%width
      ! started from the loading's deflection at delta_max (the rough part there is the
      ! offset's -p_s deep inside, ~1e5 sigma of deflection at sigma/delta_y = 1e-6, far
      ! from the initial deflection of the law)
      start%mesh = prob%closest%mesh
      start%w = prob%closest%w
      call first_unloading_level(prob, options, method_used, mesh, coarse, error, start, &
         & cache=cache)
      if (allocated(error)) return
      call refine_levels(prob, options, method_used, unload_order, mesh, coarse, sol, est, &
         & error, cache=cache)
   end subroutine guided_cap_unload

   !> Loading with the cap, the guided route (doc/theory.md §12 "Rough spheres with the
   !> cap", "Small sigma"): the smooth cap model's plastic radius c at the same delta
   !> (egw_cap_sphere's cap_load, in its universal units), which the rough solution's
   !> inner cap edge approaches as sigma -> 0, is an element edge of every level from the
   !> first, with geometric layers on both sides down to the Hertz edge's layer width
   !> (prob%kink_width, kink_layers); beyond the Hertz radius the family is focused there.
   !> Then the levels as on the default route (first_cap_level relocates the edge onto
   !> the rough solution's own cap edges).
   subroutine guided_cap_solve(problem, options, sol, est, method_used, error, cache)
      type(scaled_problem), intent(in) :: problem
      type(solver_options), intent(in) :: options
      type(discrete_solution), intent(out) :: sol
      real(dp), intent(out) :: est
      integer, intent(out) :: method_used
      type(egw_error), allocatable, intent(out) :: error
      !> the levels' influence matrices (shared elements), cleared
      type(influence_cache), intent(inout) :: cache
      type(discrete_solution) :: coarse, first
      type(scaled_problem) :: prob, relocated
      type(mesh_family) :: mesh, moved_mesh
      real(dp) :: edge
      prob = problem
      method_used = solve_method(options)
      call first_mesh(prob, options, mesh)
      call smooth_cap_edge(prob, edge, error)
      if (allocated(error)) return
      prob%branch = [edge]
      prob%n_branch = 1
      prob%kink_width = mesh%width
      call focus_beyond(mesh, edge)
      call solve_with_tail(prob, options, method_used, mesh%layered, mesh%focus, mesh%width, &
         & mesh%step_prev, mesh%outer, coarse, error, cache=cache)
      if (allocated(error)) return
      ! the edge relocated onto the rough solution's own cap edge; where that solve fails
      ! (from sigma/delta_y ~ 1e-7: the edge moves by more than a layer) the smooth edge
      ! is kept and the levels' kink error (add_kink_error) measures what it misses by
      relocated = prob
      moved_mesh = mesh
      first = coarse
      call first_cap_level(relocated, options, method_used, moved_mesh, first, error, cache=cache)
      if (.not. allocated(error)) then
         prob = relocated
         mesh = moved_mesh
         coarse = first
      end if
      if (allocated(error)) deallocate (error)
      call refine_levels(prob, options, method_used, force_order, mesh, coarse, sol, est, &
         & error, cache=cache)
   end subroutine guided_cap_solve

   !> The smooth cap model's plastic radius at prob's delta, in the scaled units of prob:
   !> cap_load in universal units (R = E* = 1, p_y = 0.01, delta in its delta_y), whose
   !> radius scales with a_y = pi p_y/2 (prob%cap%p_y the scaled p_y). Below first yield
   !> the Hertz radius (there is no plastic zone; the guided route is not needed there).
   subroutine smooth_cap_edge(prob, edge, error)
      type(scaled_problem), intent(in) :: prob
      real(dp), intent(out) :: edge
      type(egw_error), allocatable, intent(out) :: error
      real(dp), parameter :: p_unit = 0.01_dp
      type(cap_history) :: history
      type(cap_result) :: res
      real(dp) :: ratio, delta_y_unit
      edge = prob%a
      ratio = prob%delta/yield_overlap(prob)
      if (.not. ratio > 1.0_dp) return
      delta_y_unit = (0.5_dp*pi*p_unit)**2
      call cap_load(1.0_dp, 1.0_dp, p_unit, ratio*delta_y_unit, cap_options(), history, res, &
         & error, "delta")
      if (allocated(error)) return
      edge = res%cap_radius/(0.5_dp*pi*p_unit)*(0.5_dp*pi*prob%cap%p_y)
   end subroutine smooth_cap_edge

   !> The levels of solve_scaled's default route (all solves but guided_cap_solve's).
   subroutine solve_default(problem, options, sol, est, method_used, error, cache, warm)
      type(scaled_problem), intent(in) :: problem
      type(solver_options), intent(in) :: options
      type(discrete_solution), intent(out) :: sol
      real(dp), intent(out) :: est
      integer, intent(out) :: method_used
      type(egw_error), allocatable, intent(out) :: error
      !> the levels' influence matrices (shared elements), cleared
      type(influence_cache), intent(inout) :: cache
      type(discrete_solution), intent(in), optional :: warm   !< solve_scaled's
      type(discrete_solution) :: coarse, first
      type(scaled_problem) :: prob
      type(mesh_family) :: mesh, unfocused
      real(dp) :: order

      prob = problem
      order = force_order
      if (allocated(prob%closest)) order = unload_order
      method_used = solve_method(options)
      ! Unloading: Newton to a scaled residual of 1e-4 rel_tol (at most 1e-10, 1e-11 from
      ! rel_tol 1e-7 down), which moves the force by ~1e-4 rel_tol times the Jacobian's
      ! condition, far inside the tolerance and the Richardson margin; a level whose last
      ! step lands between 1e-11 and that (seen: 2.8e-11, 4.0e-11 on the reference cases)
      ! is spared an evaluation of Z_u over the mesh and an LU.
      if (allocated(prob%closest)) prob%residual_tol = &
         & unload_residual_tol(prob%residual_tol, options%rel_tol)
      call first_mesh(prob, options, mesh)
      if (allocated(prob%closest)) then
         call first_unloading_level(prob, options, method_used, mesh, coarse, error, &
            & cache=cache, warm=warm)
      else
         call solve_with_tail(prob, options, method_used, mesh%layered, mesh%focus, &
            & mesh%width, mesh%step_prev, mesh%outer, coarse, error, cache=cache)
      end if
      if (allocated(error)) then
         ! A cold start that fails (classic GW deep in contact is the stiff case) is retried
         ! by continuation in delta from a shallow contact.
         if (error%stat /= egw_not_converged .or. prob%delta <= 1.0_dp) return
         call continuation(prob, options, method_used, mesh%focus, mesh%width, &
            & mesh%step_prev, mesh%outer, coarse, error, cache=cache)
         if (allocated(error)) return
      end if
      if (.not. prob%extended .and. prob%delta > 1.0_dp) then
         unfocused = mesh
         if (stall_fallbacks(prob)) first = coarse
         call refocus_classic_gw(prob, options, method_used, mesh, coarse, error, cache=cache)
         if (allocated(error)) then
            ! GW with the cap: where the refocused first level does not converge (loading
            ! just past first yield, sigma/delta_y = 1e-4: Newton stalled at a residual of
            ! 1.8e-4), the levels go on in the first level's family
            if (.not. (stall_fallbacks(prob) .and. error%stat == egw_not_converged)) return
            deallocate (error)
            mesh = unfocused
            coarse = first
         end if
      end if
      if (allocated(prob%cap) .and. .not. allocated(prob%closest)) then
         call first_cap_level(prob, options, method_used, mesh, coarse, error, cache=cache)
         if (allocated(error)) return
      end if
      call refine_levels(prob, options, method_used, order, mesh, coarse, sol, est, error, &
         & cache=cache)
   end subroutine solve_default

end module egw_sphere_solver
