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
!> also get element edges where p(r) is less smooth (first_unloading_level), Newton takes
!> no chord steps, and Z_u's law-only work is done once (unloading_law_of).
!>
!> The work is split by concern: the problem and what is read off a solution
!> (egw_sphere_problem), the meshes (egw_sphere_mesh), one mesh's nonlinear solve
!> (egw_sphere_iteration); this module runs the levels and re-exports what egw_rough_sphere
!> uses.
module egw_sphere_solver
   use egw_progress, only: progress_note
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, egw_not_converged, fatal_error, format_real
   use egw_unloading, only: unloading_law_of, unloading_kinks
   use egw_halfspace, only: graded_edges, interpolate_nodal, influence_cache, clear_cache
   use egw_solver_workspace, only: solver_workspace
   use egw_sphere_problem, only: method_auto, method_newton, method_picard, solver_options, &
      & max_mesh_nodes, tiny_force, separation_field, scaled_problem, discrete_solution, &
      & deflection_degree, &
      & scaled, normal, negligible, base_gap, closest_gap, law_inverse, &
      & effective_radius, total_pressure, smooth_force, smooth_stiffness, rough_pressure, &
      & cap_fields, force_floor, cap_excess, sums_total
   use egw_sphere_mesh, only: force_order, unload_order, finest_step, mesh_family, &
      & first_mesh, trim_to_unloading_decay, gap_edge, branch_radii, kink_radii, with_edge, &
      & with_kink_edges, focus_refined, grown_outer, negligible_at, inner_layers, &
      & mesh_geometry, kink_layers, plastic_rim, disc_refined, with_history_edges, &
      & edge_layer_width, step_for_nodes, coarsen, disc_graded, split_kept
   use egw_sphere_iteration, only: solve_mesh, differentiate
   use egw_cap_sphere, only: cap_options, cap_history, cap_result, cap_load
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
   !> The levels' central disc (central_disc): a contact ending below this fraction of
   !> the Hertz radius (kept up to twice it once a solve's levels have one).
   real(dp), parameter :: central_fraction = 0.25_dp
   !> The levels' central disc (central_disc) only at sigma/delta_y >= disc_sigma: at
   !> 1e-6 (E-GW + cap, 0.15 delta_max after 2 delta_y, c = 0.29 a) the disc's levels
   !> agreed while 6e-6 off and converged like step**1 beyond (kinks inside the disc
   !> that come and go); not examined further (doc/stability.md Stop 48).
   real(dp), parameter :: disc_sigma = 1.0e-5_dp
   !> The default route's levels refine the central disc [0, c] with the step (as the
   !> central-disc route does, disc_refined) where the innermost kink c of an unloading
   !> after a capped loading is below this fraction of the Hertz radius
   !> (first_unloading_level; branch mesh13's disc_split, doc/benchmarks.md "Stop 47
   !> (mesh13)", "Stop 49 (rcost15)") ...
   real(dp), parameter :: disc_split = 0.5_dp
   !> ... and only at sigma/delta_y at least this (measured at 1e-2 and 0.0105; at 1e-6
   !> a rough_cap solve came out 1.7e-5 off under an estimate of 3.6e-6)
   real(dp), parameter :: disc_split_sigma = 1.0e-3_dp
   !> Classic GW unloading after a capped loading takes refine_levels' confirming level at
   !> sigma/delta_y at most this: at 1e-4 and 2e-4 two coarse levels agreed while up to 5e-4
   !> off (doc/stability.md "Stop 50 (gw16)"); at 1e-2 (README's GW + cap build to 6 delta_y
   !> at 1e-4, within 6.7e-5 of rel_tol 1e-7 solves without it) it cost 4x the build's CPU.
   real(dp), parameter :: gw_confirm_sigma = 1.0e-3_dp

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
            & (0.5_dp*pi*problem%cap%p_y)**2 < 0.5e6_dp) then
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
      disc = huge(1.0_dp)
      if (allocated(prob%branch)) then
         if (any(prob%branch > 0.0_dp)) disc = minval(prob%branch, mask=prob%branch > 0.0_dp)
      end if
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
      if (edge > mesh%focus + 4.0_dp*mesh%width) then
         mesh%focus = edge
         mesh%width = edge_layer_width(edge)
         mesh%layered = .true.
         mesh%outer = max(mesh%outer, edge + 4.0_dp*mesh%width)
      end if
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
      ratio = prob%delta/(0.5_dp*pi*prob%cap%p_y)**2
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

   !> The first level of an unloading solve (doc/theory.md §8 "Sphere"): a locating solve
   !> on a coarser mesh places the element edges at the kinks of p(r) (prob%branch) and
   !> trims the mesh to where the unloading pressure has died (trim_to_unloading_decay);
   !> then the first level itself, whose kink edges are relocated (relocate_kinks).
   subroutine first_unloading_level(prob, options, method, mesh, coarse, error, start, cache, &
      & warm)
      type(scaled_problem), intent(inout) :: prob
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      type(mesh_family), intent(inout) :: mesh
      type(discrete_solution), intent(out) :: coarse
      type(egw_error), allocatable, intent(out) :: error
      type(influence_cache), intent(inout), optional :: cache   !< of the route's levels
      !> start of the locating solve (the cap's guided route; else the initial deflection)
      type(discrete_solution), intent(in), optional :: start
      !> a solution of another solve of the same history: the locating solve's start
      !> where start is absent (if that locating solve fails, it is solved again from
      !> the initial deflection)
      type(discrete_solution), intent(in), optional :: warm
      type(discrete_solution) :: first
      type(scaled_problem) :: locate
      real(dp) :: reach   !< past the plastic rim: the least outer radius of every level
      ! Unloading: where d crosses d_max the law switches branch and p(r) has a kink
      ! (dp/dh jumps), which costs an element holding it its order (and the Richardson
      ! estimate its meaning); so do, more weakly (d2p/dh2 jumps), the radii where
      ! d - d_max crosses a kink of Z_u in Delta (unloading_kinks). Without those (seen:
      ! errors 10-35x the estimate) or with one edge off its kink, both levels carry the
      ! same kink error, which their difference cannot see. The crossings, from a solve
      ! on a mesh of twice the step (a quarter of a level's cost), become element edges
      ! of every level. (Three times the step was cheaper, but placed an edge far enough
      ! off to leave an error of 4.8e-7 under an estimate of 3e-9.)
      ! That solve only places edges and starts the next: Newton stops at a residual of
      ! 1e-6, whose error in the gap is below that mesh's own (the next level starts
      ! from an interpolation error of 1e-4..1e-6 anyway): one evaluation of Z_u over the
      ! mesh and an LU fewer in most cases; on the 12 reference cases the edges, forces
      ! and estimates are those of a fully converged locating solve to 3 digits.
      ! Nor does it need the geometric layers at the Hertz edge (16 of its ~41 nodes):
      ! without them the 12 reference cases keep their errors (<= 1.2e-7) and a sweep
      ! of 40 random unloading solves agrees with rel_tol 1e-9 solves as well as with
      ! the layers (worst 5e-7, the same case either way).
      ! After a capped loading deep in the cap the unloading contact ends near the rim of
      ! the history's plastic zone, far outside the Hertz edge (the focus), in a layer as
      ! thin as the loading's there (first_cap_level): there the graded elements are
      ! ~ step (rim - focus) long, and the levels' forces are not yet asymptotic (EP-GW,
      ! sigma = delta_y/100, psi 1, from 18.9 delta_y, delta = 17.65 delta_y, rel_tol 1e-5:
      ! the contact ends within 53.0 .. 53.5 of the rim 53.8, elements 2.6 long there; the
      ! levels agreed to 1.3e-6 while 6.6e-5 off, and a hysteresis table at 1e-4 to 20
      ! delta_y did not build). The rim becomes an element edge with geometric layers on
      ! both sides, of the loading's layer width there (a property of the history: the same
      ! edges on every level).
      ! A fixed mesh (n_radial) gets no layers but reaches past the rim as well, its step
      ! set again for n_radial nodes: the contact can end in an annulus at the rim beyond
      ! a band where the pressure is exactly 0, which the tail check cannot see (its
      ! pressure at the outer radius is 0). E-GW + cap, steel beads (sigma 42 nm, R 0.5 mm,
      ! p_y 3.2 GPa) from 5.51 delta_y: the outer radius 10.7 .. 10.9 sqrt(R sigma) lay
      ! inside the rim 12.08, and from 0.58 to 0.67 delta_max every n_radial from 257 to
      ! 2049 gave the same force up to 2.7e-3 low (estimates ~1e-9), and P(delta) jumped
      ! by 0.33 % at 0.67 delta_max (doc/stability.md).
      ! Every mesh reaches past the rim, also where the rim lies within four layer widths
      ! of the focus (no layers of its own there): the outer radius from the law's decay
      ! can end inside it, and the annulus with it (E-GW + cap, R/sigma = 70711, p_y =
      ! 0.01 E*, from 68.14 sigma = 3.9 delta_y: at 44.3 sigma, rim 8.30, focus 6.66 +
      ! 4 x 0.47, outer 8.17 at rel_tol 1e-6, 8.30 at 1e-8; the force 2.1e-3 low under an
      ! estimate of 2.8e-8, at every n_radial, and a hysteresis table at 1e-3 to 20
      ! delta_y did not build; audit9).
      reach = 0.0_dp
      if (sums_total(prob)) then
         prob%rim = plastic_rim(prob)
         if (prob%rim > 0.0_dp) reach = prob%rim + 4.0_dp*edge_layer_width(prob%rim)
         if (prob%rim > mesh%focus + 4.0_dp*mesh%width .and. options%n_radial == 0) then
            prob%rim_width = edge_layer_width(prob%rim)
         else
            prob%rim = 0.0_dp
         end if
         if (reach > mesh%outer) then
            mesh%outer = reach
            if (options%n_radial > 0) then
               mesh%step = step_for_nodes(prob%extended, mesh%focus, mesh%width, &
                  & mesh%outer, options%n_radial)
               mesh%step_prev = coarsen*mesh%step
            end if
         end if
      end if
      locate = prob
      locate%residual_tol = 1.0e-6_dp
      ! The locating solve from the deflection of the history's last solve (a table's
      ! curve at the neighbouring s): the rough deflection after a capped loading is far
      ! from the initial deflection's (the shift and offset), and Newton took 5.6
      ! iterations from it, 3.3 from a warm start (E-GW + cap, the table of
      ! doc/benchmarks.md "Stop 44"). Only edges and the next start come from this solve.
      if (present(warm) .and. .not. present(start)) then
         call solve_with_tail(locate, options, method, .false., mesh%focus, mesh%width, &
            & 2.0_dp*mesh%step_prev, mesh%outer, first, error, warm, cache=cache)
         if (allocated(error)) then
            deallocate (error)
            call solve_with_tail(locate, options, method, .false., mesh%focus, mesh%width, &
               & 2.0_dp*mesh%step_prev, mesh%outer, first, error, cache=cache)
         end if
      else
         call solve_with_tail(locate, options, method, .false., mesh%focus, mesh%width, &
            & 2.0_dp*mesh%step_prev, mesh%outer, first, error, start, cache=cache)
      end if
      ! (after a capped loading, a locating solve that failed from its start again by
      ! continuation in delta from the history's deflection at delta_max: unloading_descent)
      if (allocated(error) .and. options%n_radial == 0 .and. prob%closest%capped .and. &
         & stall_fallbacks(prob)) then
         deallocate (error)
         call unloading_descent(locate, options, method, mesh, first, error, cache)
      end if
      if (allocated(error)) then
         deallocate (error)
         call solve_with_tail(prob, options, method, mesh%layered, mesh%focus, mesh%width, &
            & mesh%step_prev, mesh%outer, coarse, error, start, cache=cache)
         return
      end if
      ! Edges only where the pressure is not negligible: a kink where r p is below
      ! 1e-4 rel_tol of its peak cannot move the force by rel_tol even if its elements
      ! were wholly wrong, and such edges (seen: r p at 1e-45 of the peak, in the far
      ! tail) cost a level of elements 4 nodes each.
      prob%branch = kink_radii(prob, first, 1.0e-4_dp*options%rel_tol, prob%n_branch)
      if (prob%closest%extended) prob%amax_edge = .not. negligible_at(first, &
         & sqrt(prob%closest%delta), 1.0e-4_dp*options%rel_tol)
      if (options%n_radial == 0) call trim_to_unloading_decay(prob, options, first, mesh)
      if (options%n_radial == 0) prob%disc = central_disc(prob, first)
      ! After a capped loading (sums_total) the innermost kink c can lie well inside the
      ! Hertz radius a the family is graded about: [0, c] is then one graded element on
      ! the first levels (between the fixed edges 0 and c), whose forces agree while both
      ! are off; the bisection check (now halved_levels) found it, and the levels then
      ! refined the whole mesh by
      ! a global step until the graded edges split [0, c] (E-GW + cap, sigma =
      ! delta_y/100 to 6 delta_y at 1e-4: 110 of 1444 checks found the disc off by 1e-7
      ! .. 2.9e-4 at c/a 0.05 .. 0.4, and the levels after them held 300-550 nodes, 47 %
      ! of the build's LU work). Below disc_split a the disc's elements shrink with the
      ! step from the first level on (disc_refined, as on the central-disc route; it
      ! takes the place of central_disc's grading there). Only at sigma/delta_y >=
      ! disc_split_sigma (delta_y/sigma = (pi p_y/2)**2 in these units), where it was
      ! measured: at 1e-6 (rough_cap's "solve_contact_unload near the residual", c =
      ! 0.21 a) the split disc came out 1.7e-5 off under an estimate of 3.6e-6.
      if (sums_total(prob) .and. options%n_radial == 0 .and. allocated(prob%branch)) then
         if (any(prob%branch > 0.0_dp) .and. (0.5_dp*pi*prob%cap%p_y)**2 <= &
            & 1.0_dp/disc_split_sigma) prob%refine_disc = prob%refine_disc .or. &
            & minval(prob%branch, mask=prob%branch > 0.0_dp) <= disc_split*prob%a
      end if
      ! (the trimmed mesh still reaches past the rim: the contact can end just inside it)
      mesh%outer = max(mesh%outer, reach)
      ! The first level only enters the estimate through its difference to the next
      ! (divided by 2.4) and places the kinks again: Newton to a scaled residual of
      ! 1e-2 rel_tol (at most 1e-8) moves its force by far less than the estimate's
      ! margin and its kinks by ~1e-8 sigma, and takes one step fewer (psi 10, delta 0.5
      ! after delta_max 1: 1.59 -> 1.47 ms; the 16 references and a 100-solve sweep
      ! unchanged to 3 digits at rel_tol 1e-6..1e-8).
      locate = prob
      locate%residual_tol = max(prob%residual_tol, min(1.0e-8_dp, &
         & 1.0e-2_dp*options%rel_tol))
      call solve_with_tail(locate, options, method, mesh%layered, mesh%focus, mesh%width, &
         & mesh%step_prev, mesh%outer, coarse, error, first, cache=cache)
      ! The locating solve (twice the step, no kink edges) places the kinks 3e-4..3e-3
      ! off (psi 10 after delta_max 2: at delta 0 the edges were 2.3e-3 off, an error
      ! of 9e-7 that every level shared, so rel_tol 1e-8 was never reached and the
      ! rel_tol 1e-7 answer was 2e-7 off the reference under an estimate of 5e-8).
      ! Relocated from the first level (kink edges in place, a finer mesh) and that
      ! level solved again until the offset costs less than a tenth of rel_tol.
      if (.not. allocated(error)) call relocate_kinks(prob, options, method, mesh%layered, &
         & mesh%focus, mesh%width, mesh%step_prev, mesh%outer, coarse, error, cache=cache)
   end subroutine first_unloading_level

   !> Unloading after a capped loading, the locating solve (locate, on the coarse mesh
   !> of first_unloading_level) where it failed from its start: continuation in delta
   !> from the history's own deflection at delta_max (the unloading solution there), at
   !> descent_stages overlaps evenly from delta_max down to locate%delta, each solved from
   !> the one before. Newton stalled from the initial and the neighbouring curve's
   !> deflections on every route (E-GW + cap, sigma/delta_y = 1e-4, 71049 sigma after
   !> 116562: residual 7.6e-3, issue 32); from here it converged (at sigma/delta_y = 2e-5
   !> and 1e-5, 0.5 and 0.65 delta_max, the first level stalls after it, unresolved).
   subroutine unloading_descent(locate, options, method, mesh, sol, error, cache)
      type(scaled_problem), intent(in) :: locate
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      type(mesh_family), intent(inout) :: mesh
      type(discrete_solution), intent(out) :: sol
      type(egw_error), allocatable, intent(out) :: error
      type(influence_cache), intent(inout), optional :: cache
      integer, parameter :: descent_stages = 8
      type(scaled_problem) :: stage
      type(discrete_solution) :: previous
      integer :: k
      previous%mesh = locate%closest%mesh
      previous%w = locate%closest%w
      stage = locate
      do k = 1, descent_stages
         stage%delta = locate%closest%delta + (locate%delta - locate%closest%delta)* &
            & real(k, dp)/real(descent_stages, dp)
         if (k == descent_stages) stage%delta = locate%delta
         stage%a = sqrt(max(stage%delta, 0.0_dp))
         ! (as scaled(): the extended models' Hertz part only at delta > 0)
         stage%extended = locate%closest%extended .and. stage%delta > 0.0_dp
         call solve_with_tail(stage, options, method, .false., mesh%focus, mesh%width, &
            & 2.0_dp*mesh%step_prev, mesh%outer, sol, error, previous, cache=cache)
         if (allocated(error)) return
         previous = sol
      end do
   end subroutine unloading_descent

   !> Loading with the cap (doc/theory.md §12 "Rough spheres with the cap"): the cap edges
   !> of the first level's solution (coarse) become element edges (prob%branch: where
   !> p_s + p reaches p_y, dp/dr jumps), the first level is solved again with them and
   !> they are relocated on it (relocate_kinks), as for the unloading's kinks.
   subroutine first_cap_level(prob, options, method, mesh, coarse, error, cache)
      type(scaled_problem), intent(inout) :: prob
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      type(mesh_family), intent(inout) :: mesh
      type(discrete_solution), intent(inout) :: coarse
      type(egw_error), allocatable, intent(out) :: error
      type(influence_cache), intent(inout), optional :: cache   !< of the route's levels
      type(discrete_solution) :: first
      real(dp) :: edge
      prob%branch = kink_radii(prob, coarse, 1.0e-4_dp*options%rel_tol, prob%n_branch)
      if (size(prob%branch) == 0) then
         deallocate (prob%branch)
         return
      end if
      ! Beyond ~2 delta_y the capped contact outgrows the Hertz radius and ends, just past
      ! its outermost cap edge, in a layer as thin as the Hertz edge's (the smooth cap's
      ! pressure jumps from p_y to 0 there, trap iv): the family is refocused there (the
      ! Hertz edge, where the base gap has its onset, stays an element edge).
      edge = maxval(prob%branch)
      if (edge > mesh%focus + 4.0_dp*mesh%width) then
         mesh%focus = edge
         mesh%width = edge_layer_width(edge)
         mesh%layered = .true.
         mesh%outer = max(mesh%outer, edge + 4.0_dp*mesh%width)
      end if
      call move_solution(coarse, first)
      call solve_with_tail(prob, options, method, mesh%layered, mesh%focus, mesh%width, &
         & mesh%step_prev, mesh%outer, coarse, error, first, cache=cache)
      if (.not. allocated(error)) call relocate_kinks(prob, options, method, mesh%layered, &
         & mesh%focus, mesh%width, mesh%step_prev, mesh%outer, coarse, error, cache=cache)
   end subroutine first_cap_level

   !> Classic GW deep in contact (doc/theory.md §5 "Useful facts", §7): with
   !> p_H(0) >> C sigma**1.5 (centre gap below -3 sigma) the solution ends in a thin layer
   !> around d = 0 whose place is only known from a solution (near, not at, the Hertz
   !> edge): the mesh family is refocused there and the first level (coarse) solved again.
   subroutine refocus_classic_gw(prob, options, method, mesh, coarse, error, cache)
      type(scaled_problem), intent(in) :: prob
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      type(mesh_family), intent(inout) :: mesh
      type(discrete_solution), intent(inout) :: coarse
      type(egw_error), allocatable, intent(out) :: error
      type(influence_cache), intent(inout), optional :: cache   !< of the route's levels
      type(discrete_solution) :: first
      if (.not. law_inverse(prob, 2.0_dp*prob%a/pi) < -3.0_dp) return
      call gap_edge(coarse, mesh%focus, mesh%width)
      mesh%layered = .true.
      ! The first level again, on the refocused mesh family: two levels of different
      ! families can agree by accident (seen: both 1.3e-7 off at mu = 0.1,
      ! delta/sigma = 100, their difference 1.5e-8), so Richardson needs one family.
      call move_solution(coarse, first)
      call solve_with_tail(prob, options, method, mesh%layered, mesh%focus, mesh%width, &
         & mesh%step_prev, mesh%outer, coarse, error, first, cache=cache)
   end subroutine refocus_classic_gw

   !> Levels of decreasing step (doc/theory.md §7 "Error control"), each warm-started from
   !> the last (coarse): the force of each and of the one before give the Richardson
   !> estimate |P_h - P_H|/((H/h)**order - 1) of the error of P_h, plus the tail and (for
   !> unloading) the kink offsets (add_kink_error); below rel_tol/2 the level is accepted,
   !> else the next step is predicted from the estimate. Unloading after a capped loading
   !> (sums_total): no level keeps an element of the level before (halved_levels).
   subroutine refine_levels(prob, options, method, order, mesh, coarse, sol, est, error, cache)
      type(scaled_problem), intent(inout) :: prob
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      real(dp), intent(in) :: order   !< order assumed by the Richardson estimate
      type(mesh_family), intent(inout) :: mesh
      type(discrete_solution), intent(inout) :: coarse   !< the previous level
      type(discrete_solution), intent(out) :: sol
      real(dp), intent(out) :: est
      type(egw_error), allocatable, intent(out) :: error
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
         ! the bisection check it replaced did)
         if (halve) confirm = confirm .or. kept_any
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
            ! "Stop 50 (gw16)").
            if (confirm .or. .not. ((allocated(prob%branch) .and. &
               & (options%rel_tol < 1.0e-6_dp .or. capped_history(prob))) .or. &
               & gw_confirm(prob)) .or. mesh%step <= finest_step) return
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

   !> Whether the fallbacks of solves that stall with the cap apply (skip_failed_level,
   !> add_kink_error, unloading_descent, solve_default's refocus):
   !> with the cap at sigma/delta_y > 2e-6 (delta_y/sigma = (pi p_y/2)**2 here). Below,
   !> egw_rough_sphere's small-sigma route answers a failed solve, and the discrete
   !> levels the fallbacks let converge were off by more than their estimate (E-GW + cap,
   !> sigma/delta_y = 1e-6 from 2 delta_y, 0.16 delta_max at rel_tol 1e-5: 2.4e-5 off the
   !> reference, test rough_cap 'sigma/delta_y = 1e-6: unloading near the residual
   !> overlap', where the route answers within 7.6e-7).
   pure logical function stall_fallbacks(prob)
      type(scaled_problem), intent(in) :: prob
      stall_fallbacks = .false.
      if (allocated(prob%cap)) stall_fallbacks = (0.5_dp*pi*prob%cap%p_y)**2 < 0.5e6_dp
   end function stall_fallbacks

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

   !> Classic GW unloading after a loading on which the flow-pressure cap acted.
   pure logical function capped_gw(prob)
      type(scaled_problem), intent(in) :: prob
      capped_gw = .false.
      if (allocated(prob%closest) .and. allocated(prob%cap)) capped_gw = &
         & prob%closest%capped .and. .not. prob%closest%extended
   end function capped_gw

   !> capped_gw at sigma/delta_y <= gw_confirm_sigma (delta_y/sigma = (pi p_y/2)**2 here).
   pure logical function gw_confirm(prob)
      type(scaled_problem), intent(in) :: prob
      gw_confirm = capped_gw(prob)
      if (gw_confirm) gw_confirm = (0.5_dp*pi*prob%cap%p_y)**2 >= 1.0_dp/gw_confirm_sigma
   end function gw_confirm

   !> EP-GW unloading after a loading on which the flow-pressure cap acted.
   pure logical function capped_history(prob)
      type(scaled_problem), intent(in) :: prob
      capped_history = .false.
      if (allocated(prob%closest) .and. prob%psi > 0.0_dp) capped_history = &
         & prob%closest%capped
   end function capped_history

   !> Unloading after a capped loading (sums_total), the levels of a discretisation
   !> error estimate (n_radial 0): each level halves the elements it would keep of the
   !> level before (cut into kept_parts: solve_with_tail's level_before, sphere_mesh's
   !> split_kept). Richardson
   !> assumes that every element shrinks with the step, but an element between two fixed
   !> edges (r = 0, kink edges, the layers at a and at the rim) stays the same while the
   !> step exceeds it, and its error is in both levels: near the residual overlap the
   !> total pressure lives on such a disc [0, 0.091] (E-GW, sigma = 0.059 delta_y, delta
   !> = 0.0174 delta_y after 1.297 delta_y), one element at steps 0.19, 0.15 and 0.076,
   !> whose levels agreed to 6e-8 while all were 8.2e-6 off (doc/theory.md section 12).
   !> Cut into at least the step ratio's parts (2 on the first refinement level, whose
   !> step is 1.5 times finer), those elements shrink at least like the step, so the
   !> Richardson estimate with the step ratio is conservative for them. Until stop 51
   !> an accepted level was solved again with them halved (a bisection check, the
   !> difference added whole to its estimate): the same mesh as the halved level, one
   !> mesh solve more in 56 % of the unloading solves of an E-GW + cap table
   !> (doc/benchmarks.md "Stop 51 (mesh17)").
   pure logical function halved_levels(prob, options)
      type(scaled_problem), intent(in) :: prob
      type(solver_options), intent(in) :: options
      halved_levels = sums_total(prob) .and. options%n_radial == 0
   end function halved_levels

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

   !> Continuation in delta: solve at delta/sigma = 1 from a cold start, then at delta
   !> values growing by at most a factor 4 up to prob%delta, each started from the previous
   !> solution stretched by the Hertz similarity (r ~ sqrt(delta), w ~ delta).
   subroutine continuation(prob, options, method, focus, width, step, outer, sol, error, cache)
      type(scaled_problem), intent(in) :: prob
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      real(dp), intent(in) :: focus, width, step
      real(dp), intent(inout) :: outer
      type(discrete_solution), intent(out) :: sol
      type(egw_error), allocatable, intent(out) :: error
      type(influence_cache), intent(inout), optional :: cache   !< of the route's levels
      type(scaled_problem) :: stage
      type(discrete_solution) :: previous
      real(dp) :: stage_focus, stage_width, stage_outer, ratio, delta_prev
      integer :: k, n_stages

      n_stages = ceiling(log(prob%delta)/log(4.0_dp))
      stage = prob
      do k = 0, n_stages
         stage%delta = prob%delta**(real(k, dp)/real(n_stages, dp))
         stage%a = sqrt(stage%delta)
         if (k == n_stages) then
            ! The last stage is the problem itself, on its own mesh.
            stage = prob
            stage_focus = focus
            stage_width = width
            stage_outer = outer
         else
            call mesh_geometry(stage, options%rel_tol, stage_focus, stage_width, stage_outer)
         end if
         if (k == 0) then
            call solve_with_tail(stage, options, method, stage%extended, stage_focus, &
               & stage_width, step, stage_outer, sol, error, cache=cache)
         else
            ratio = stage%delta/delta_prev
            previous%mesh%edge = previous%mesh%edge*sqrt(ratio)
            previous%w = previous%w*ratio
            call solve_with_tail(stage, options, method, stage%extended, stage_focus, &
               & stage_width, step, stage_outer, sol, error, previous, cache=cache)
         end if
         if (allocated(error)) return
         previous = sol
         delta_prev = stage%delta
      end do
      outer = stage_outer
   end subroutine continuation

   !> Solve on the mesh of the given step, growing the outer radius (kept for the next
   !> levels) until the force estimated beyond it is below 1 % of the tolerance.
   subroutine solve_with_tail(prob, options, method, layered, focus, width, step, outer, sol, &
      & error, guess, cache, level_before, step_before, kept)
      type(scaled_problem), intent(in) :: prob
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      logical, intent(in) :: layered   !< geometric layers at the focus
      real(dp), intent(in) :: focus, width, step
      real(dp), intent(inout) :: outer
      type(discrete_solution), intent(out) :: sol
      type(egw_error), allocatable, intent(out) :: error
      type(influence_cache), intent(inout), optional :: cache   !< of the route's levels
      type(discrete_solution), intent(in), optional :: guess  !< solution on another mesh
      !> the level before's element edges: the elements this mesh keeps of it cut into
      !> kept_parts(step_before/step) (split_kept), unless that needs more than
      !> max_mesh_nodes (refine_levels); with step_before, its step
      real(dp), intent(in), optional :: level_before(0:), step_before
      !> level_before given and an element of it kept (and halved, but for the node limit)
      logical, intent(out), optional :: kept
      real(dp) :: total, keep
      integer :: attempt, i
      real(dp), allocatable :: edges(:)
      type(discrete_solution) :: previous   !< the last attempt's mesh and w

      if (present(kept)) kept = .false.
      do attempt = 1, 8
         edges = graded_edges(focus, width, outer, step)
         if (layered) edges = focus_refined(edges, focus)
         ! Unloading after an extended loading: d_max has its (r - a_max)**1.5 onset at
         ! the loading Hertz edge; an element edge there keeps the elements smooth.
         if (allocated(prob%closest)) then
            ! The (r - a_max)**1.5 onset is milder than a kink: moving a graded edge onto it
            ! (as for the kinks) made the elements beside it uneven and cost accuracy (delta
            ! 0.5, delta_max 1, psi 10: error 7e-8 -> 2e-7, one level more); it keeps the
            ! insertion unless within a tenth of an element of an edge.
            if (prob%closest%extended .and. prob%amax_edge) edges = with_edge(edges, &
               & sqrt(prob%closest%delta))
            ! After a capped loading the offset (flow_cap's plastic_shift) is p_s(delta_max)
            ! in the capped body, with the loading Hertz pressure's sqrt(a_max - r) edge at
            ! a_max, and the total pressure can step from its floor 0 to ~p_s there within
            ! ~1e-3 a_max: a_max an element edge always, with halving layers inside it, as
            ! the loading's a (inner_layers). Without them EP-GW (sigma = delta_y, mu 4,
            ! psi 1) unloading from 6 delta_y missed rel_tol 1e-6 at 7 of 70 overlaps: its
            ! levels' forces alternated by 1.2e-3 (estimates 6e-7 .. 6e-4).
            if (prob%closest%extended .and. prob%amax_edge .and. prob%closest%capped) then
               edges = with_kink_edges(edges, [sqrt(prob%closest%delta)], focus, 1, 0.0_dp)
               edges = inner_layers(edges, sqrt(prob%closest%delta))
            end if
            ! the rim of the history's plastic zone (first_unloading_level)
            if (prob%rim > 0.0_dp) then
               edges = with_kink_edges(edges, [prob%rim], focus, 1, sqrt(prob%closest%delta))
               edges = kink_layers(edges, prob%rim, prob%rim_width)
            end if
            if (allocated(prob%branch)) then
               keep = 0.0_dp
               if (prob%closest%extended .and. prob%amax_edge) keep = sqrt(prob%closest%delta)
               edges = with_kink_edges(edges, prob%branch, focus, prob%n_branch, keep)
               ! (the guided route: layers at the edges of the history's plastic zone,
               ! where the shift and the offset start, cap_excess kinds 2 and 3, not at the
               ! d = d_max crossings, which the capped body has in numbers there)
               if (prob%kink_width > 0.0_dp) then
                  do i = 1, size(prob%branch)
                     if (min(abs(cap_excess(prob, prob%branch(i), 0.0_dp, 2)), &
                        & abs(cap_excess(prob, prob%branch(i), 0.0_dp, 3))) <= 1.0e-6_dp &
                        & *prob%cap%p_y) edges = kink_layers(edges, prob%branch(i), &
                        & prob%kink_width)
                  end do
               end if
            end if
            ! Summed as the total pressure (sums_total), p_s's sqrt(a - r) edge at the Hertz
            ! radius a (the focus) is in the Gauss sum, and in the rough part where the total
            ! is floored at 0 (there p = -p_s): 5 halving layers inside a, as on loading.
            ! Without them the levels converged like h**1.5 (E-GW, steel beads, sigma =
            ! 0.059 delta_y, delta = 0.0174 delta_y after 1.297 delta_y: 9.6e-7 at the
            ! finest step, egw_not_converged at rel_tol 1e-6). (8 layers: the E-GW + cap
            ! table of theory.md section 12 built 2.8x slower than without; 5: 2.2x, and
            ! 3 left the error at 0.018 delta_y above its estimate, 2.5e-7 > 1.95e-7.)
            if (sums_total(prob) .and. prob%delta > 0.0_dp) edges = inner_layers(edges, &
               & sqrt(prob%delta), 5)
            ! (the central-disc route: the disc's elements shrink with the step; elsewhere
            ! a contact that is a central disc far inside the Hertz radius, central_disc:
            ! its elements graded about its edge, the kink edges put back inside it)
            if (prob%refine_disc .and. allocated(prob%branch)) then
               edges = disc_refined(edges, prob%branch, step)
            else if (options%n_radial == 0 .and. prob%disc > 0.0_dp) then
               edges = disc_graded(edges, prob%disc, step)
               if (allocated(prob%branch)) edges = with_kink_edges(edges, prob%branch, &
                  & focus, prob%n_branch, 0.0_dp)
            end if
            ! (the history-edges route: the kinks of the history's d_max(r))
            if (prob%history_edges) edges = with_history_edges(edges, &
               & prob%closest%mesh%edge(1:prob%closest%mesh%n_elem))
         else if (allocated(prob%branch)) then
            ! loading with the cap: its edges (cap_kink_radii) and, extended models, the
            ! Hertz edge a always (moved onto or inserted, even where the family was
            ! refocused off it, first_cap_level) with halving layers inside it
            ! (inner_layers): where capped, the rough part p_y - p_s has the sqrt(a - r)
            ! edge of p_s (with a inside an element the force was off by 8.5e-5 under an
            ! estimate of 5e-7 at 9.7 delta_y, sigma = delta_y/100, rel_tol 1e-6)
            if (prob%extended) then
               edges = with_kink_edges(edges, [prob%a, prob%branch], focus, &
                  & prob%n_branch + 1, 0.0_dp)
               edges = inner_layers(edges, prob%a)
            else
               edges = with_kink_edges(edges, prob%branch, focus, prob%n_branch, 0.0_dp)
            end if
            if (prob%kink_width > 0.0_dp) then
               do i = 1, size(prob%branch)
                  edges = kink_layers(edges, prob%branch(i), prob%kink_width)
               end do
            end if
         end if
         if (present(level_before) .and. present(step_before)) call halve_kept(edges, &
            & level_before, kept_parts(step_before/step), kept)
         call solve_mesh(prob, options, method, edges, sol, error, guess, cache=cache)
         if (allocated(error) .and. attempt > 1 .and. capped_gw(prob)) then
            ! Classic GW unloading after a capped loading: a mesh grown by the tail check
            ! that stalls from the caller's start (the initial deflection: 25-30 Gauss
            ! points beyond the law's underflow, where dp/dh = 0 and Newton's step cannot
            ! see them; sigma/delta_y = 1e-4, 53532 sigma after 65012: residual 0.57, the
            ! solve failed at 0.78 after unloading_descent and the continuation in delta)
            ! is solved again from the last attempt's converged solution (doc/stability.md
            ! "Stop 50 (gw16)"); only where it failed, so converging solves are unchanged.
            if (error%stat == egw_not_converged .and. stall_fallbacks(prob)) then
               deallocate (error)
               call solve_mesh(prob, options, method, edges, sol, error, previous, cache=cache)
            end if
         end if
         if (allocated(error)) return
         total = abs(smooth_force(prob) + sol%force)
         if (total > 0.0_dp) total = max(total, force_floor(prob))
         if (sol%tail <= 0.01_dp*options%rel_tol*total .or. total == 0.0_dp) return
         outer = grown_outer(prob, sol, options%rel_tol*total, outer)
         if (capped_gw(prob)) then
            previous%mesh = sol%mesh
            previous%w = sol%w
         end if
      end do
      call fatal_error(error, egw_not_converged, "delta = "//format_real(prob%delta) &
         & //" (in units of sigma): the pressure does not decay within the outer radius " &
         & //format_real(outer))
   end subroutine solve_with_tail

   !> edges with the elements they keep of coarse's cut into parts (sphere_mesh's
   !> split_kept), where that needs at most max_mesh_nodes (else as they were); kept:
   !> whether they kept any.
   pure subroutine halve_kept(edges, coarse, parts, kept)
      real(dp), allocatable, intent(inout) :: edges(:)
      real(dp), intent(in) :: coarse(0:)
      integer, intent(in) :: parts
      logical, intent(out), optional :: kept
      real(dp), allocatable :: halved(:)
      halved = split_kept(edges, coarse, parts)
      if (present(kept)) kept = size(halved) > size(edges)
      if ((size(halved) - 1)*deflection_degree + 1 > max_mesh_nodes) return
      call move_alloc(halved, edges)
   end subroutine halve_kept

   !> The parts a kept element is cut into on a level whose step is ratio times finer
   !> than the level before's: at least 2 and at least ratio (the levels' steps shrink by
   !> 1.25 .. 4), so that it shrinks at least like the step and the Richardson estimate
   !> with that ratio stays conservative for it.
   elemental integer function kept_parts(ratio) result(parts)
      real(dp), intent(in) :: ratio
      parts = max(2, ceiling(ratio - 1.0e-9_dp))
   end function kept_parts

   !> Kink edges of an unloading solve placed from a solution with them in place (sol, the
   !> first level): while what the edges still miss by (kink_offset_error) exceeds a tenth
   !> of rel_tol, move them and solve that level again (at most 3 times).
   subroutine relocate_kinks(prob, options, method, layered, focus, width, step, outer, sol, &
      & error, cache)
      type(scaled_problem), intent(inout) :: prob
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      logical, intent(in) :: layered
      real(dp), intent(in) :: focus, width, step
      real(dp), intent(inout) :: outer
      type(discrete_solution), intent(inout) :: sol
      type(egw_error), allocatable, intent(out) :: error
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
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(in) :: sol
      logical, allocatable :: inside(:)
      c = prob%disc
      if (.not. sums_total(prob) .or. .not. allocated(sol%p_smooth)) return
      ! (delta_y/sigma = (pi p_y/2)**2 in these units)
      if ((0.5_dp*pi*prob%cap%p_y)**2 > 1.0_dp/disc_sigma) return
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

   !> to <- from as a guess (its mesh and w, all solve_mesh reads of a guess; w moved).
   pure subroutine move_solution(from, to)
      type(discrete_solution), intent(inout) :: from
      type(discrete_solution), intent(out) :: to
      to%mesh = from%mesh
      call move_alloc(from%w, to%w)
   end subroutine move_solution

   !> to <- from but for the influence matrix and the LU factors (n x 3n and n x n
   !> doubles, most of a level's memory), which only the iteration and differentiate of
   !> the solution that owns them read: a level kept as the coarse level (its force, mesh
   !> and w) is a copy of the rest. from is returned as it came.
   pure subroutine copy_level(from, to)
      type(discrete_solution), intent(inout) :: from
      type(discrete_solution), intent(inout) :: to
      real(dp), allocatable :: infl(:, :), lu(:, :)
      integer, allocatable :: pivots(:)
      call move_alloc(from%infl, infl)
      call move_alloc(from%lu, lu)
      call move_alloc(from%pivots, pivots)
      to = from
      call move_alloc(infl, from%infl)
      call move_alloc(lu, from%lu)
      call move_alloc(pivots, from%pivots)
   end subroutine copy_level

   !> to <- from whole, the influence matrix and the LU factors moved (not copied): from
   !> loses them.
   pure subroutine take_level(from, to)
      type(discrete_solution), intent(inout) :: from
      type(discrete_solution), intent(inout) :: to
      call copy_level(from, to)
      call move_alloc(from%infl, to%infl)
      call move_alloc(from%lu, to%lu)
      call move_alloc(from%pivots, to%pivots)
   end subroutine take_level

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

end module egw_sphere_solver
