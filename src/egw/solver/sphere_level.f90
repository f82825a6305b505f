!> One level of the sphere solver (egw_sphere_solver): its element edges where the
!> problem's field is less smooth (kinks, onsets, the plastic rim, a central disc), its
!> mesh solve (egw_sphere_iteration) with the outer radius grown until the tail is
!> negligible; and levels moved or copied without their matrices.
module egw_sphere_level
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_not_converged, fatal_error, format_real
   use egw_halfspace, only: graded_edges, influence_cache
   use egw_sphere_problem, only: solver_options, max_mesh_nodes, scaled_problem, &
      & discrete_solution, deflection_degree, smooth_force, force_floor, cap_excess, sums_total
   use egw_sphere_mesh, only: with_edge, with_kink_edges, focus_refined, grown_outer, &
      & inner_layers, graded_inside, kink_layers, disc_refined, with_history_edges, disc_graded, &
      & split_kept
   use egw_sphere_iteration, only: solve_mesh
   use egw_sphere_regime, only: stall_fallbacks, capped_gw
   implicit none
   private

   public :: solve_with_tail, move_solution, copy_level, take_level

   !> Loading with the cap: an element edge is moved onto a kink (the cap edges, the Hertz
   !> edge a) only where it lies within this fraction of both elements beside it; else
   !> the kink is inserted (with_kink_edges). With its default 0.1 the choice switched
   !> where a kink, moving with delta, passed a tenth of an element from an edge, and
   !> the mesh of every level with it: a history's field then jumped in delta_max (the
   !> README's E-GW + cap pair at rel_tol 1e-7, delta_max 209.3175 -> 209.3180 sigma:
   !> 37 -> 38 elements, the cap edge 0.2539 from an edge against a room of 0.25399;
   !> its unloading force at 2.12 sigma jumped by 1.3e-4 of itself, where the
   !> curves are smooth; doc/benchmarks.md "Stop 56: kink22"). At 0.01 a switch moves
   !> one edge by at most 1 % of its element.
   real(dp), parameter :: loading_move_room = 0.01_dp
   !> Loading with the cap where the capped zone reaches past the Hertz edge a: the
   !> largest length/distance-to-a of an element inside a (graded_inside), the coarsest
   !> level's step: a Bernstein-ellipse rho >= 6.5 for p_y - p_s's sqrt(a - r) edge
   !> (doc/benchmarks.md "Stop 58: edge24").
   real(dp), parameter :: inside_grading = 0.6_dp
   !> Unloading after a capped loading: the layers at the Hertz radius a and at the rim of
   !> the history's plastic zone are those its guards were measured with up to this
   !> rel_tol, and coarser above it (floor_layer_count, rim_layer_width): at the tables'
   !> 1e-5 their error was below rel_tol/10 on README's E-GW + cap pair, and the levels,
   !> half of whose elements they were, ~0.8 of the CPU (doc/benchmarks.md "Stop 64:
   !> lay30").
   real(dp), parameter :: layers_tol = 1.0e-6_dp

contains

   !> Solve on the mesh of the given step, growing the outer radius (kept for the next
   !> levels) until the force estimated beyond it is below 1 % of the tolerance.
   subroutine solve_with_tail(prob, options, method, layered, focus, width, step, outer, sol, &
      & error, guess, cache, level_before, step_before, kept, locating)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(solver_options), intent(in) :: options   !< the solver's options
      integer, intent(in) :: method   !< method_newton or method_picard
      logical, intent(in) :: layered   !< geometric layers at the focus
      real(dp), intent(in) :: focus, width, step   !< the family's focus, layer width and step
      real(dp), intent(inout) :: outer   !< outer radius, grown where the tail is not negligible
      type(discrete_solution), intent(out) :: sol   !< the level's solution
      type(egw_error), allocatable, intent(out) :: error   !< egw_not_converged or the failure met
      type(influence_cache), intent(inout), optional :: cache   !< of the route's levels
      type(discrete_solution), intent(in), optional :: guess  !< solution on another mesh
      !> the level before's element edges: the elements this mesh keeps of it cut into
      !> kept_parts(step_before/step) (split_kept), unless that needs more than
      !> max_mesh_nodes (refine_levels); with step_before, its step
      real(dp), intent(in), optional :: level_before(0:), step_before
      !> level_before given and an element of it kept (and halved, but for the node limit)
      logical, intent(out), optional :: kept
      !> an unloading's locating solve (first_unloading_level): without the history's
      !> layers (below), its edges kept
      logical, intent(in), optional :: locating
      real(dp) :: total, keep
      logical :: layers
      integer :: attempt, i
      real(dp), allocatable :: edges(:)
      type(discrete_solution) :: previous   !< the last attempt's mesh and w

      if (present(kept)) kept = .false.
      ! The layers at a_max, at the rim and inside a resolve the total pressure's edges
      ! for the levels' estimate; a locating solve only places the kink edges and starts
      ! the first level, which has them all and whose kinks relocate_kinks moves again.
      ! Without them README's E-GW + cap build spent ~70 % less CPU in its locating solves
      ! and took ~0.9 of the CPU (doc/benchmarks.md "Stop 63: unl29").
      layers = .true.
      if (present(locating)) layers = .not. locating
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
               if (layers) edges = inner_layers(edges, sqrt(prob%closest%delta))
            end if
            ! the rim of the history's plastic zone (first_unloading_level)
            if (prob%rim > 0.0_dp) then
               edges = with_kink_edges(edges, [prob%rim], focus, 1, sqrt(prob%closest%delta))
               if (layers) edges = kink_layers(edges, prob%rim, &
                  & rim_layer_width(prob%rim_width, options%rel_tol))
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
            ! Fewer above rel_tol 1e-6 (floor_layer_count).
            if (sums_total(prob) .and. prob%delta > 0.0_dp .and. layers) edges = &
               & inner_layers(edges, sqrt(prob%delta), floor_layer_count(options%rel_tol))
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
                  & prob%n_branch + 1, 0.0_dp, loading_move_room)
               ! (and, where the capped zone reaches past a, the elements inside it graded
               ! towards a, graded_inside, at the ratio inside_grading on every level: its
               ! error there ~1e-10 of the force; graded with the level's step, the
               ! confirming level that ends such solves doubled those elements, and
               ! README's rough + cap builds took 1.8x their time, stop 58)
               if (size(prob%branch) > 0) then
                  if (maxval(prob%branch) > prob%a) edges = graded_inside(edges, prob%a, &
                     & max(step, inside_grading))
               end if
               edges = inner_layers(edges, prob%a)
            else
               edges = with_kink_edges(edges, prob%branch, focus, prob%n_branch, 0.0_dp, &
                  & loading_move_room)
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

   !> The halving layers inside the Hertz radius a of an unloading after a capped loading
   !> (solve_with_tail): 5 at rel_tol <= layers_tol, one fewer for each factor 2**1.5 of
   !> rel_tol above it (each halving cuts the last layer's share of p_s's sqrt(a - r)
   !> edge error by that factor), at least 1: 3 at 1e-5, 1 at 1e-4. The guard's case
   !> (E-GW + cap steel beads, 0.017419 delta_y after 1.2971 delta_y) came out 3.3e-6 off
   !> at 1e-5 with 3 and 2.5e-5 off at 1e-4 with 1, its estimates 2.5e-6 and 1.8e-5
   !> (5.5e-7 and 5.2e-7 with 5; doc/benchmarks.md "Stop 64: lay30").
   pure integer function floor_layer_count(rel_tol) result(n)
      real(dp), intent(in) :: rel_tol   !< the solve's tolerance
      n = 5
      if (rel_tol > layers_tol) n = max(1, n - floor(log(rel_tol/layers_tol)/(1.5_dp* &
         & log(2.0_dp))))
   end function floor_layer_count

   !> The last layer's width at the rim of the history's plastic zone (kink_layers): the
   !> contact's edge layer there (width, first_unloading_level) at rel_tol <= layers_tol,
   !> wider by (rel_tol/layers_tol)**0.6 above it (4x at 1e-5, 16x at 1e-4: two and four
   !> halvings fewer on each side). The guard's case (EP-GW + cap, sigma = delta_y/100,
   !> 17.65375 after 18.90625 delta_y: the contact ends 0.5 inside the rim) came out 1.0e-6
   !> of its force off at 1e-5 and 9.5e-7 at 1e-4, its estimates 1.7e-6 and 5.3e-7
   !> (4.0e-7 at both with the edge layer's width).
   pure real(dp) function rim_layer_width(width, rel_tol) result(w)
      real(dp), intent(in) :: width   !< the contact's edge layer width at the rim
      real(dp), intent(in) :: rel_tol   !< the solve's tolerance
      w = width*max(1.0_dp, rel_tol/layers_tol)**0.6_dp
   end function rim_layer_width

   !> The parts a kept element is cut into on a level whose step is ratio times finer
   !> than the level before's: at least 2 and at least ratio (the levels' steps shrink by
   !> 1.25 .. 4), so that it shrinks at least like the step and the Richardson estimate
   !> with that ratio stays conservative for it.
   elemental integer function kept_parts(ratio) result(parts)
      real(dp), intent(in) :: ratio
      parts = max(2, ceiling(ratio - 1.0e-9_dp))
   end function kept_parts

   !> to <- from as a guess (its mesh and w, all solve_mesh reads of a guess; w moved).
   pure subroutine move_solution(from, to)
      type(discrete_solution), intent(inout) :: from   !< the solution, its w moved out
      type(discrete_solution), intent(out) :: to   !< a guess: from's mesh and w
      to%mesh = from%mesh
      call move_alloc(from%w, to%w)
   end subroutine move_solution

   !> to <- from but for the influence matrix and the LU factors (n x 3n and n x n
   !> doubles, most of a level's memory), which only the iteration and differentiate of
   !> the solution that owns them read: a level kept as the coarse level (its force, mesh
   !> and w) is a copy of the rest. from is returned as it came.
   pure subroutine copy_level(from, to)
      type(discrete_solution), intent(inout) :: from   !< the level, returned as it came
      type(discrete_solution), intent(inout) :: to   !< the copy, without the matrices
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
      type(discrete_solution), intent(inout) :: from   !< the level, its matrices moved out
      type(discrete_solution), intent(inout) :: to   !< the level whole
      call copy_level(from, to)
      call move_alloc(from%infl, to%infl)
      call move_alloc(from%lu, to%lu)
      call move_alloc(from%pivots, to%pivots)
   end subroutine take_level

end module egw_sphere_level
