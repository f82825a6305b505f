!> The meshes of a rough-sphere solve (doc/theory.md §7 "Unknowns and discretisation"):
!> the family's grading focus, width and outer radius, the steps of the levels, geometric
!> layers at the Hertz edge, element edges at the unloading law's branch radii and kinks,
!> and the outer radius grown where the pressure has not decayed.
module egw_sphere_mesh
   use egw_kinds, only: dp, pi
   use egw_halfspace, only: graded_edges, interpolate_nodal
   use egw_unloading, only: unloading_kinks
   use egw_sphere_problem, only: solver_options, scaled_problem, discrete_solution, law_at, &
      & law_inverse, estimated_gap, closest_gap, base_gap, deflection_degree, cap_excess, &
      & cap_excess_points
   implicit none
   private

   !> Step ratio of the first two levels, and the order assumed when extrapolating the
   !> difference of two levels to an error estimate: 3, the lowest seen on coarse meshes
   !> (5-6 asymptotically), so that the estimate errs on the safe side; 2 for unloading,
   !> whose (t - t*)**1.5 edges of Z_u inside elements slow it (with 3 the errors of
   !> egw-bench --unloading-sweep at rel_tol 1e-6 were up to 2-3 times their estimates,
   !> with 2 at most 1.8; the levels it accepts, and the bench times, did not change).
   real(dp), parameter :: coarsen = 1.5_dp, force_order = 3.0_dp, unload_order = 2.0_dp
   !> Geometric layers at the Hertz edge (number, size ratio).
   integer, parameter :: focus_layers = 2
   !> Layers of halving elements inside the Hertz edge with the cap (inner_layers)
   integer, parameter :: cap_edge_layers = 8
   real(dp), parameter :: focus_ratio = 0.25_dp
   !> Step (in asinh units) of the first level, and the finest allowed.
   real(dp), parameter :: finest_step = 0.01_dp, coarsest_step = 0.6_dp
   integer, parameter :: min_elements = 8
   !> Elements per unit of step across the central disc of disc_refined (2: at 1 the
   !> steel beads' E-GW + cap solve at 10 m/s accepted an estimate of 4.1e-7, at 2 of
   !> 1.3e-7, one level fewer elsewhere).
   real(dp), parameter :: disc_elements = 2.0_dp
   !> A kink of Z_u in Delta closer than this fraction of its element to a branch edge
   !> gets no edge of its own (with_kink_edges).
   real(dp), parameter :: near_kink = 0.3_dp

   public :: coarsen, force_order, unload_order, finest_step

   !> The meshes of a solve's levels: one family (grading focus and width, outer radius,
   !> geometric layers at the focus) and the steps (asinh units) of the level being solved
   !> and of the one before. Passed from step to step of solve_scaled.
   type :: mesh_family
      real(dp) :: focus = 0.0_dp, width = 0.0_dp, outer = 0.0_dp
      real(dp) :: step = 0.0_dp, step_prev = 0.0_dp
      logical :: layered = .false.
   end type mesh_family

   public :: mesh_family
   public :: kink_radii, cap_kink_radii, plastic_rim, edge_layer_width
   public :: first_mesh, coarsest_level_step, trim_to_unloading_decay, gap_edge, branch_radii, &
      & focus_beyond, innermost_kink, &
      & negligible_at, decayed_radius, focus_refined, with_edge, with_kink_edges, &
      & mesh_geometry, step_for_nodes, grown_outer, inner_layers, graded_inside, kink_layers, &
      & disc_refined, &
      & disc_graded, with_history_edges, split_kept


   !> The state of an Illinois root search (illinois_begin, illinois_step).
   type :: illinois_iteration
      real(dp) :: lo = 0, hi = 0, f_lo = 0, f_hi = 0   !< the bracket and f at its ends
      integer :: side = 0    !< the end that moved last (1: lo, -1: hi)
      integer :: steps = 0
      logical :: done = .false.
   end type illinois_iteration

contains

   !> The mesh family of the first level (doc/theory.md §7 "Unknowns and discretisation"):
   !> grading focus, width and outer radius (mesh_geometry), and the steps of the first
   !> level (step_prev) and of the next (step).
   pure subroutine first_mesh(prob, options, mesh)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(solver_options), intent(in) :: options   !< the solver's options (rel_tol, n_radial)
      type(mesh_family), intent(out) :: mesh   !< the family's geometry and steps
      call mesh_geometry(prob, options%rel_tol, mesh%focus, mesh%width, mesh%outer)
      mesh%layered = prob%extended
      if (options%n_radial > 0) then
         mesh%step = step_for_nodes(prob%extended, mesh%focus, mesh%width, mesh%outer, &
            & options%n_radial)
         mesh%step_prev = coarsen*mesh%step
      else
         mesh%step_prev = coarsest_level_step(prob, mesh)
         mesh%step = mesh%step_prev/coarsen
      end if
   end subroutine first_mesh

   !> Step of the first level of an automatic mesh family.
   pure real(dp) function coarsest_level_step(prob, mesh) result(step)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(mesh_family), intent(in) :: mesh   !< its mesh family
      ! Deep contacts resolve the same relative error on coarser steps (the rough part,
      ! where the error lives, weighs less): start coarser there ...
      step = coarsest_step*max(1.0_dp, prob%delta)**0.1_dp
      ! ... but never fewer than min_elements graded elements: on fewer, two levels can
      ! agree by accident (not yet asymptotic) and the estimate would be worthless.
      step = min(step, (asinh(mesh%focus/mesh%width) &
         & + asinh((mesh%outer - mesh%focus)/mesh%width))/real(min_elements, dp))
   end function coarsest_level_step

   !> The outer radius (and the steps) of an unloading solve from where the unloading
   !> pressure of the locating solve (first) has died (doc/theory.md §8).
   pure subroutine trim_to_unloading_decay(prob, options, first, mesh)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem (unloading)
      type(solver_options), intent(in) :: options   !< the solver's options
      type(discrete_solution), intent(in) :: first   !< the locating solve
      type(mesh_family), intent(inout) :: mesh   !< its outer radius and steps trimmed
      real(dp) :: trimmed
      ! mesh_geometry sizes the mesh for the loading law, whose Gaussian tail reaches
      ! far out, but Z_u vanishes once the summits it holds have recovered, so r p
      ! falls far faster (seen: 1e-19 of the loading tail at the same radius). A mesh
      ! trimmed to where r p is below 1e-6 rel_tol of its peak (the force beyond is
      ! then ~1e-6 rel_tol, and the tail check of solve_with_tail still guards it)
      ! puts the same number of elements where the force is. At delta -1 after
      ! delta_max 1, psi 10 (a force of 1.4e-18 from a peak at r ~ 0.1 that has fallen
      ! by 1e-12 at r ~ 0.5, on a mesh out to 3.2) this spares a third level. On a
      ! sweep of 120 unloading solves (psi 1-10, delta_max -0.5..20) the 14 trimmed
      ! ones moved by at most 4e-8, except psi 10, delta 0 after delta_max 2, where
      ! the untrimmed solve was 9.7e-6 off its own rel_tol 1e-7 answer and the
      ! trimmed one is 2.1e-7 off.
      trimmed = decayed_radius(first, 1.0e-6_dp*options%rel_tol)
      ! Only a mesh that shrinks by half: a slight trim gains little and moves the
      ! edges, which can cost a level (seen: outer 3.59 -> 3.36 at delta 0.5 after
      ! delta_max 1, psi 10, a third level).
      ! (trimmed is 0 where the pressure is 0 throughout: nothing to trim to.)
      if (trimmed > 0.0_dp .and. trimmed <= 0.5_dp*mesh%outer) then
         ! At the centre focus the grading width must fit inside the trimmed mesh.
         if (mesh%focus == 0.0_dp) mesh%width = min(mesh%width, 0.5_dp*trimmed)
         mesh%outer = max(trimmed, mesh%focus + 2.0_dp*mesh%width)
         mesh%step_prev = coarsest_level_step(prob, mesh)
         mesh%step = mesh%step_prev/coarsen
      end if
   end subroutine trim_to_unloading_decay

   !> Where the gap of a solution last crosses 0 (linear between Gauss points), and the
   !> distance over which it grows by one sigma there; focus and width unchanged if the
   !> gap never crosses 0.
   pure subroutine gap_edge(sol, focus, width)
      type(discrete_solution), intent(in) :: sol   !< a solution
      !> the gap's last zero and its one-sigma width (scaled)
      real(dp), intent(inout) :: focus, width
      real(dp) :: slope
      integer :: g
      do g = size(sol%gap) - 1, 1, -1
         if (sol%gap(g) < 0.0_dp .and. sol%gap(g + 1) >= 0.0_dp) then
            slope = (sol%gap(g + 1) - sol%gap(g))/(sol%mesh%gauss_r(g + 1) - sol%mesh%gauss_r(g))
            focus = sol%mesh%gauss_r(g) - sol%gap(g)/slope
            width = min(width, 1.0_dp/slope)
            return
         end if
      end do
   end subroutine gap_edge

   !> The family refocused at edge (its layer width there, geometric layers, the outer
   !> radius at least four widths past it) where edge lies beyond four layer widths of
   !> the focus; else unchanged. A contact that ends there (the cap's plastic radius, an
   !> outer cap edge) ends in a layer as thin as the Hertz edge's.
   pure subroutine focus_beyond(mesh, edge)
      type(mesh_family), intent(inout) :: mesh   !< the family, refocused or not
      real(dp), intent(in) :: edge   !< the radius (scaled) it may be refocused at
      if (edge > mesh%focus + 4.0_dp*mesh%width) then
         mesh%focus = edge
         mesh%width = edge_layer_width(edge)
         mesh%layered = .true.
         mesh%outer = max(mesh%outer, edge + 4.0_dp*mesh%width)
      end if
   end subroutine focus_beyond

   !> The innermost positive kink edge of prob%branch, huge() where it has none.
   pure real(dp) function innermost_kink(prob) result(c)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      c = huge(1.0_dp)
      if (.not. allocated(prob%branch)) return
      if (any(prob%branch > 0.0_dp)) c = minval(prob%branch, mask=prob%branch > 0.0_dp)
   end function innermost_kink

   !> The radii where p(r) of a solution has kinks that become element edges: unloading,
   !> the branch radii (d = d_max crossings, then the kinks of Z_u in Delta); with the cap
   !> its edges (cap_kink_radii) first. n_first: how many radii (the first) are kinks where
   !> dp/dr jumps (the cap's and the d = d_max crossings); the rest are milder.
   function kink_radii(prob, sol, negligible_weight, n_first) result(radii)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(discrete_solution), intent(in) :: sol   !< a solution
      real(dp), intent(in) :: negligible_weight   !< skip radii where negligible_at says so
      integer, intent(out) :: n_first   !< how many radii (the first) are strong kinks
      real(dp), allocatable :: radii(:), branch(:)
      integer :: n_branch
      allocate (radii(0))
      n_first = 0
      if (allocated(prob%cap)) radii = cap_kink_radii(prob, sol, negligible_weight)
      n_first = size(radii)
      if (.not. allocated(prob%closest)) return
      branch = branch_radii(prob, sol, [0.0_dp, unloading_kinks(prob%unload)], &
         & negligible_weight, n_branch)
      radii = [radii, branch]
      n_first = n_first + n_branch
   end function kink_radii

   !> Unloading after a capped loading: the outermost radius of the history's plastic
   !> zone, where cap_excess of kind 2 (the cap edge at delta_max) changes sign, bracketed
   !> by the Gauss points of the history's mesh and solved there (Illinois); 0 if none.
   !> A property of the history alone (its d_max field and p_s(delta_max)).
   function plastic_rim(prob) result(rim)
      !> the scaled problem, unloading after a capped loading
      type(scaled_problem), intent(in) :: prob
      real(dp) :: rim
      real(dp) :: f0, f1, mid
      real(dp), allocatable :: r(:)
      integer :: g
      type(illinois_iteration) :: root
      rim = 0.0_dp
      if (.not. (allocated(prob%cap) .and. allocated(prob%closest))) return
      r = prob%closest%mesh%gauss_r
      f1 = cap_excess(prob, r(size(r)), 0.0_dp, 2)
      do g = size(r) - 1, 1, -1
         f0 = f1
         f1 = cap_excess(prob, r(g), 0.0_dp, 2)
         if (f0 < 0.0_dp .eqv. f1 < 0.0_dp) cycle
         mid = r(g) + f1/(f1 - f0)*(r(g + 1) - r(g))
         call illinois_begin(root, r(g), r(g + 1), f1, f0, mid)
         do while (.not. root%done)
            call illinois_step(root, cap_excess(prob, mid, 0.0_dp, 2), mid)
         end do
         rim = mid
         return
      end do
   end function plastic_rim

   !> Radii where the cap puts a kink into p(r) of a solution (cap_excess changes sign; its
   !> kinds 1 to 3), at most 8 of each kind: bracketed by the Gauss points, then solved on
   !> the solution's own field (Illinois), as branch_radii.
   function cap_kink_radii(prob, sol, negligible_weight) result(radii)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem, with the cap
      type(discrete_solution), intent(in) :: sol   !< a solution
      real(dp), intent(in) :: negligible_weight   !< skip radii where negligible_at says so
      real(dp), allocatable :: radii(:)
      real(dp) :: f0, f1, lo, hi, mid, at_points(size(sol%gap), 3)
      integer :: g, kind, found
      type(illinois_iteration) :: root
      allocate (radii(0))
      ! the brackets from the solve's own cap fields at its Gauss points
      call cap_excess_points(prob, sol, at_points)
      do kind = 1, 3
         found = 0
         f1 = at_points(1, kind)
         do g = 1, size(sol%gap) - 1
            f0 = f1
            f1 = at_points(g + 1, kind)
            if ((f0 < 0.0_dp .eqv. f1 < 0.0_dp) .or. found >= 8) cycle
            if (negligible_at(sol, 0.5_dp*(sol%mesh%gauss_r(g) + sol%mesh%gauss_r(g + 1)), &
               & negligible_weight)) cycle
            lo = sol%mesh%gauss_r(g)
            hi = sol%mesh%gauss_r(g + 1)
            mid = lo + f0/(f0 - f1)*(hi - lo)
            call illinois_begin(root, lo, hi, excess(lo), excess(hi), mid)
            do while (.not. root%done)
               call illinois_step(root, excess(mid), mid)
            end do
            ! kinds 2 and 3 coincide where p_s(delta_max) = 0: one edge
            if (size(radii) > 0) then
               if (minval(abs(radii - mid)) <= 1.0e-12_dp*mid) cycle
            end if
            radii = [radii, mid]
            found = found + 1
         end do
      end do
   contains
      !> cap_excess of this kind at r on the nodal field
      pure real(dp) function excess(r)
         real(dp), intent(in) :: r
         excess = cap_excess(prob, r, base_gap(prob, r) + interpolate_nodal(sol%mesh, sol%w, r), &
            & kind)
      end function excess
   end function cap_kink_radii

   !> Radii where the gap of a solution crosses its closest-approach gap plus one of the
   !> levels (0: the branch; the kinks of Z_u in Delta), at most 16. Bracketed by the Gauss
   !> points where gap - gap_min - level changes sign, then bisected on the solution's own
   !> field (nodal interpolation of w, the history's d_max): an edge placed off the kink by
   !> the linear interpolation's error (~ spacing^2 x curvature) left both levels with the
   !> same error, which their difference (the Richardson estimate) cannot see.
   function branch_radii(prob, sol, levels, negligible_weight, n_first) result(radii)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem (unloading)
      type(discrete_solution), intent(in) :: sol   !< a solution
      real(dp), intent(in) :: levels(:)   !< gap - gap_min levels (scaled), levels(1) = 0
      real(dp), intent(in) :: negligible_weight  !< skip radii where negligible_at says so
      integer, intent(out) :: n_first            !< how many radii (the first) are of levels(1)
      real(dp), allocatable :: radii(:)
      real(dp) :: f0, f1, lo, hi, mid
      integer :: g, k
      type(illinois_iteration) :: root
      allocate (radii(0))
      n_first = 0
      do k = 1, size(levels)
         do g = 1, size(sol%gap) - 1
            f0 = sol%gap(g) - sol%gap_min(g) - levels(k)
            f1 = sol%gap(g + 1) - sol%gap_min(g + 1) - levels(k)
            if ((f0 < 0.0_dp .eqv. f1 < 0.0_dp) .or. size(radii) >= 16) cycle
            if (negligible_at(sol, 0.5_dp*(sol%mesh%gauss_r(g) + sol%mesh%gauss_r(g + 1)), &
               & negligible_weight)) cycle
            lo = sol%mesh%gauss_r(g)
            hi = sol%mesh%gauss_r(g + 1)
            mid = lo + f0/(f0 - f1)*(hi - lo)
            call illinois_begin(root, lo, hi, excess(lo), excess(hi), mid)
            do while (.not. root%done)
               call illinois_step(root, excess(mid), mid)
            end do
            radii = [radii, mid]
         end do
         if (k == 1) n_first = size(radii)
      end do
   contains
      !> gap - gap_min - level at r from the nodal field
      pure real(dp) function excess(r)
         real(dp), intent(in) :: r
         real(dp) :: gm(1)
         gm = closest_gap(prob%closest, [r])
         excess = base_gap(prob, r) + interpolate_nodal(sol%mesh, sol%w, r) - gm(1) - levels(k)
      end function excess
   end function branch_radii

   !> Root finding in [lo, hi] where f(lo), f(hi) differ in sign: Illinois (regula falsi
   !> that halves the value kept twice), ~8 evaluations of the field to full precision
   !> where bisection took 40-50. Reverse communication (the caller evaluates f at mid
   !> between illinois_begin and each illinois_step until done), so that the function,
   !> which reads the caller's solution, is no procedure argument (an internal procedure
   !> passed as one needs a trampoline and an executable stack, which loaders refuse).
   pure subroutine illinois_begin(it, lo, hi, f_lo, f_hi, mid)
      type(illinois_iteration), intent(out) :: it
      real(dp), intent(in) :: lo, hi, f_lo, f_hi   !< the bracket and f at its ends
      !> in: the caller's estimate, kept when the ends do not bracket a root; out: the
      !> point to evaluate next (or the result when it%done)
      real(dp), intent(inout) :: mid
      it%lo = lo
      it%hi = hi
      it%f_lo = f_lo
      it%f_hi = f_hi
      it%done = (f_lo < 0.0_dp) .eqv. (f_hi < 0.0_dp)
      if (.not. it%done) call illinois_propose(it, mid)
   end subroutine illinois_begin

   !> One Illinois step with f_mid = f(mid): the bracket shrinks, and mid becomes the next
   !> point to evaluate, or the root (it%done: f(mid) = 0, the bracket at round-off, or
   !> 60 steps).
   pure subroutine illinois_step(it, f_mid, mid)
      type(illinois_iteration), intent(inout) :: it
      real(dp), intent(in) :: f_mid
      real(dp), intent(inout) :: mid
      if (f_mid == 0.0_dp) then
         it%done = .true.
         return
      end if
      if ((f_mid < 0.0_dp) .eqv. (it%f_lo < 0.0_dp)) then
         it%lo = mid
         it%f_lo = f_mid
         if (it%side == 1) it%f_hi = 0.5_dp*it%f_hi
         it%side = 1
      else
         it%hi = mid
         it%f_hi = f_mid
         if (it%side == -1) it%f_lo = 0.5_dp*it%f_lo
         it%side = -1
      end if
      it%steps = it%steps + 1
      it%done = it%hi - it%lo <= 8.0_dp*epsilon(1.0_dp)*it%hi .or. it%steps >= 60
      if (.not. it%done) call illinois_propose(it, mid)
   end subroutine illinois_step

   !> The regula falsi point of the bracket (its midpoint where that falls outside; done
   !> where even that does not lie strictly inside).
   pure subroutine illinois_propose(it, mid)
      type(illinois_iteration), intent(inout) :: it
      real(dp), intent(out) :: mid
      mid = (it%lo*it%f_hi - it%hi*it%f_lo)/(it%f_hi - it%f_lo)
      if (.not. (mid > it%lo .and. mid < it%hi)) mid = 0.5_dp*(it%lo + it%hi)
      if (.not. (mid > it%lo .and. mid < it%hi)) it%done = .true.
   end subroutine illinois_propose

   !> True when r p(r) of a solution, at the two Gauss points around r (or the last one),
   !> is at most weight times its largest value over the mesh.
   pure logical function negligible_at(sol, r, weight)
      type(discrete_solution), intent(in) :: sol   !< a solution
      real(dp), intent(in) :: r, weight   !< scaled radius, and the fraction of the peak
      real(dp) :: peak, local
      integer :: g, ng
      ng = size(sol%p)
      peak = maxval(abs(sol%p*sol%mesh%gauss_r))
      g = 1
      do while (g < ng)
         if (sol%mesh%gauss_r(g + 1) >= r) exit
         g = g + 1
      end do
      local = abs(sol%p(g)*sol%mesh%gauss_r(g))
      if (g < ng) local = max(local, abs(sol%p(g + 1)*sol%mesh%gauss_r(g + 1)))
      negligible_at = local <= weight*peak
   end function negligible_at

   !> The Gauss radius just past the last one where r p of a solution exceeds weight times
   !> its peak (the last Gauss radius if that is the last point; 0 if p is 0 throughout).
   pure real(dp) function decayed_radius(sol, weight) result(r)
      type(discrete_solution), intent(in) :: sol   !< a solution
      real(dp), intent(in) :: weight   !< fraction of the peak of r p
      real(dp) :: peak
      integer :: g, ng
      ng = size(sol%p)
      peak = maxval(abs(sol%p*sol%mesh%gauss_r))
      r = 0.0_dp
      if (.not. peak > 0.0_dp) return
      do g = ng, 1, -1
         if (abs(sol%p(g)*sol%mesh%gauss_r(g)) > weight*peak) exit
      end do
      r = sol%mesh%gauss_r(min(g + 1, ng))
   end function decayed_radius

   !> Geometric layers on both sides of the focus (the Hertz edge of the extended models),
   !> where the pressure has its one-sided (r - a)**1.5 onset: a polynomial on an element
   !> touching a converges only algebraically, on geometric layers exponentially.
   pure function focus_refined(edge, focus) result(refined)
      real(dp), intent(in) :: edge(0:), focus   !< element boundaries, and the focus radius
      real(dp), allocatable :: refined(:)
      real(dp) :: left, right
      integer :: i, k, n
      n = size(edge) - 1
      k = -1
      if (focus > 0.0_dp) k = findloc(edge, focus, dim=1) - 1
      if (k <= 0 .or. k >= n .or. focus_layers == 0) then
         refined = edge
         return
      end if
      left = focus - edge(k - 1)
      right = edge(k + 1) - focus
      refined = [edge(0:k - 1), (focus - left*focus_ratio**i, i=1, focus_layers), focus, &
         & (focus + right*focus_ratio**i, i=focus_layers, 1, -1), edge(k + 1:n)]
   end function focus_refined

   !> edge with the element that ends at the edge r (an edge of it, exactly) split into
   !> cap_edge_layers elements halving towards r. Loading with the cap (doc/theory.md §12
   !> "Rough spheres with the cap"): where the cap holds the total pressure at p_y just
   !> inside the Hertz edge a, the rough part p_y - p_s has the Hertz pressure's
   !> sqrt(a - r) edge, which an element's polynomial holds only to ~ its length**1.5 (the
   !> levels then converge like step**1.5 and their Richardson estimate, of order 5, saw
   !> a tenth of the error: 1.1e-5 under 7e-7 at 9.7 delta_y, sigma = delta_y/100). Each
   !> layer is as long as its distance to a, so its polynomial error is ~1e-5 of its
   !> share, and the last, 2**-8 of the element, leaves (2**-8)**1.5 of the error. n: that
   !> many layers instead (unloading after a capped loading takes 5, egw_sphere_level).
   pure function inner_layers(edge, r, n) result(out)
      real(dp), intent(in) :: edge(0:), r   !< element boundaries, and the edge r (one of them)
      integer, intent(in), optional :: n   !< layers (default cap_edge_layers)
      real(dp), allocatable :: out(:)
      real(dp) :: h
      integer :: k, i, layers
      layers = cap_edge_layers
      if (present(n)) layers = n
      out = edge
      k = findloc(edge, r, dim=1) - 1
      if (k < 1) return
      h = edge(k) - edge(k - 1)
      out = [edge(0:k - 1), (r - h*0.5_dp**i, i=1, layers), edge(k:)]
   end function inner_layers

   !> edge with each element inside the edge r (an edge of it, exactly), before the
   !> element ending at r, split so that no part is longer than ratio times its distance
   !> to r: elements graded geometrically towards r. Loading with the cap (doc/theory.md
   !> section 12): where the capped zone holds the Hertz edge a, the rough part p_y - p_s
   !> has the sqrt(a - r) edge there, and an element of length L whose end is d from a
   !> holds it only to ~ rho**(-2 pressure_points), rho of the Bernstein ellipse of
   !> 1 + 2 d/L. Graded about a focus beyond a (the cap's edge c), the family's elements
   !> had L/d up to ~6 there (rho ~ 2), an error that changed with the fragment left of
   !> the element at a from level to level and that their estimate did not see (E-GW +
   !> cap, sigma/delta_y = 1e-2, 20 delta_y, rel_tol 1e-6: 4.8e-6 of P under an estimate
   !> of 4.4e-8; doc/benchmarks.md "Stop 58: edge24"). With ratio the level's step
   !> (rho >= 6.5 at the coarsest step) that error is ~1e-10 and shrinks with the step.
   pure function graded_inside(edge, r, ratio) result(out)
      !> element boundaries, the edge r (one of them), the largest length/distance
      real(dp), intent(in) :: edge(0:), r, ratio
      real(dp), allocatable :: out(:)
      real(dp) :: e1
      integer :: k, j, m
      out = edge
      k = findloc(edge, r, dim=1) - 1
      if (k < 2 .or. .not. ratio > 0.0_dp) return
      ! from edge(k-1) inwards: a new edge at e1 - ratio (r - e1) wherever the element
      ! beyond e1 is longer than that (filled from the right end of out)
      deallocate (out)
      allocate (out(0:size(edge) - 1 + ceiling(log(r/(r - edge(k - 1)))/log(1.0_dp + &
         & ratio)) + 1))
      m = ubound(out, 1) + 1
      e1 = edge(k - 1)
      j = k - 2
      do while (j >= 0)
         m = m - 1
         if (e1 - edge(j) > ratio*(r - e1)*(1.0_dp + 1.0e-12_dp)) then
            e1 = e1 - ratio*(r - e1)
         else
            e1 = edge(j)
            j = j - 1
         end if
         out(m) = e1
      end do
      out = [out(m:), edge(k - 1:)]
   end function graded_inside

   !> edge with the two elements beside the edge r (an edge of it, exactly) split into
   !> layers halving towards r until the one at r is at most width long (at most 40 each
   !> side). Loading with the cap at small sigma/delta_y (egw_sphere_solver's
   !> guided_cap_solve): at the inner cap edge the gap goes from the stiff rough layer's
   !> few sigma to the plastic zone's deep overlap within ~ a (sigma/delta)**(2/3), as
   !> thin as the Hertz edge's layer, and an element much longer than that holding it
   !> gave Newton an oscillating discrete problem (doc/theory.md §12, "Small sigma").
   pure function kink_layers(edge, r, width) result(out)
      !> element boundaries, the edge r (one of them), the last layer's width
      real(dp), intent(in) :: edge(0:), r, width
      real(dp), allocatable :: out(:)
      real(dp) :: left, right
      integer :: k, n, nl, nr, i
      out = edge
      n = size(edge) - 1
      k = findloc(edge, r, dim=1) - 1
      if (k < 1 .or. k >= n .or. .not. width > 0.0_dp) return
      left = r - edge(k - 1)
      right = edge(k + 1) - r
      nl = min(40, max(0, ceiling(log(left/width)/log(2.0_dp))))
      nr = min(40, max(0, ceiling(log(right/width)/log(2.0_dp))))
      out = [edge(0:k - 1), (r - left*0.5_dp**i, i=1, nl), r, (r + right*0.5_dp**i, &
         & i=nr, 1, -1), edge(k + 1:n)]
   end function kink_layers

   !> edge with r added as an element edge (the element holding r split in two) unless r
   !> is outside (0, outer) or within a tenth of its element's length of an edge already.
   pure function with_edge(edge, r) result(out)
      real(dp), intent(in) :: edge(0:), r   !< element boundaries, and the radius to add
      real(dp), allocatable :: out(:)
      integer :: k, n
      n = size(edge) - 1
      out = edge
      if (.not. (r > 0.0_dp .and. r < edge(n))) return
      k = 1
      do while (edge(k) < r)
         k = k + 1
      end do
      if (min(edge(k) - r, r - edge(k - 1)) <= 0.1_dp*(edge(k) - edge(k - 1))) return
      out = [edge(0:k - 1), r, edge(k:n)]
   end function with_edge

   !> edge with each of the radii r (kinks of the unloading pressure) made an element edge:
   !> the edge nearest r is moved onto it when that is at most a tenth of both elements
   !> beside it away (and is not 0, the outer radius, the focus or an edge placed for an
   !> earlier r), else r is inserted (the element holding it split in two). Formerly an r
   !> within a tenth of an element of an edge was skipped, which left the kink inside the
   !> element on one level and not on the other: the Richardson estimate then measured
   !> the kink, not the discretisation (seen: 3.8e-7 for an error of 2e-9). The a_max edge
   !> (keep) and the focus layers are never moved onto a kink (without the a_max edge the
   !> unloading forces of psi 10 after delta_max 1, 2 were off by up to 1.3e-6).
   pure function with_kink_edges(edge, radii, focus, n_strong, keep, move_room) result(out)
      !> element boundaries, kink radii, the focus
      real(dp), intent(in) :: edge(:), radii(:), focus
      integer, intent(in) :: n_strong   !< radii(:n_strong): d = d_max crossings
      real(dp), intent(in) :: keep      !< an edge never moved (the a_max edge; 0: none)
      !> how far (a fraction of both elements beside it) an edge is moved onto a kink
      !> rather than the kink inserted; absent: 0.1
      real(dp), intent(in), optional :: move_room
      real(dp), allocatable :: out(:)   ! indices 1..m (the edges' 0..n)
      logical, allocatable :: fixed(:)
      real(dp) :: r, room, fraction
      integer :: i, j, k, m, kf
      fraction = 0.1_dp
      if (present(move_room)) fraction = move_room
      allocate (out(size(edge)))
      out(:) = edge
      fixed = out == focus .or. out == keep
      ! nor the focus layers
      if (focus > 0.0_dp .and. any(out == focus)) then
         kf = findloc(out, focus, dim=1)
         fixed(max(1, kf - focus_layers):min(size(out), kf + focus_layers)) = .true.
      end if
      do i = 1, size(radii)
         r = radii(i)
         m = size(out)
         if (.not. (r > 0.0_dp .and. r < out(m))) cycle
         k = 2
         do while (out(k) < r)
            k = k + 1
         end do
         ! A kink of Z_u in Delta (d2p jumps) within near_kink of its element of a branch
         ! edge (dp jumps) gets no edge of its own: the element that short between them
         ! cost 6 % of the solve (psi 10, delta 0.5 after delta_max 1: Delta reaches e
         ! 0.016 past the branch edge) for an error of order its length cubed (on the 16
         ! references the forces moved by at most 7.5e-8 at rel_tol 1e-7, within the
         ! tolerance and the estimate).
         if (i > n_strong .and. n_strong > 0) then
            if (minval(abs(radii(:n_strong) - r)) < near_kink*(out(k) - out(k - 1))) cycle
         end if
         ! nearest edge j of the element (out(k-1), out(k)] holding r
         j = k
         if (r - out(k - 1) < out(k) - r) j = k - 1
         if (abs(out(j) - r) <= 4.0_dp*epsilon(1.0_dp)*r) then
            fixed(j) = .true.
            cycle
         end if
         if (j > 1 .and. j < m) then
            room = fraction*min(out(j) - out(j - 1), out(j + 1) - out(j))
            if (.not. fixed(j) .and. abs(out(j) - r) <= room) then
               out(j) = r
               fixed(j) = .true.
               cycle
            end if
         end if
         out = [out(:k - 1), r, out(k:)]
         fixed = [fixed(:k - 1), .true., fixed(k:)]
      end do
   end function with_kink_edges

   !> edge with every element inside the innermost positive radius c of radii split into
   !> equal parts no longer than c step/disc_elements (disc_elements per unit of step
   !> across [0, c]), so that they shrink with the level's step as the graded ones do.
   !> Unloading after a capped loading near the residual overlap (egw_sphere_solver's
   !> disc_cap_unload): the total pressure lives on a central disc [0, c] whose edge is a
   !> floor kink, c << the Hertz radius the family is graded about, so the disc held 1-5
   !> graded elements of ~ step a, kept from level to level between the fixed edges 0 and
   !> c until the step fell below c/a: the levels agreed to 1e-7 while 5e-5 off (steel
   !> beads, E-GW + cap, sigma 10 nm, delta 0.4 delta_max after 5.5 delta_y).
   pure function disc_refined(edge, radii, step) result(out)
      !> element boundaries, kink radii, the level's step
      real(dp), intent(in) :: edge(0:), radii(:), step
      real(dp), allocatable :: out(:)
      real(dp) :: c
      integer :: e, j, parts
      out = edge
      if (.not. any(radii > 0.0_dp)) return
      c = minval(radii, mask=radii > 0.0_dp)
      out = [edge(0)]
      do e = 1, size(edge) - 1
         parts = 1
         if (edge(e) <= c) parts = ceiling((edge(e) - edge(e - 1))/c*disc_elements/step)
         out = [out, (edge(e - 1) + (edge(e) - edge(e - 1))*real(j, dp)/real(parts, dp), &
            & j=1, parts - 1), edge(e)]
      end do
   end function disc_refined

   !> edge with its elements inside the radius c (0 < c < the outer radius) replaced by
   !> elements graded as the family's, in asinh((c - r)/w) about c with w the layer width
   !> of a contact edge at c (edge_layer_width), disc_elements per unit of the level's step;
   !> c becomes an edge. Unloading after a capped loading whose contact is a central disc
   !> [0, c] far inside the Hertz radius a the family is graded about (egw_sphere_refine's
   !> central_disc): the graded elements there are ~ step a long, so the disc lay in one to
   !> a few of them, kept from level to level (fixed edges 0 and c), whose forces agreed
   !> while off (E-GW + cap, sigma = 2e-5 delta_y, 0.1442 delta_max after 2 delta_y: 5.6e-4
   !> under an estimate of 1.1e-7, doc/stability.md Stop 47). Graded rather than in equal
   !> parts (disc_refined) so that the elements at the disc's edge, where the contact
   !> ends in a layer ~ c (sigma/delta)**(2/3) thin, shrink towards it (a choice: not
   !> measured against equal parts where both apply).
   pure function disc_graded(edge, c, step) result(out)
      !> element boundaries, the disc's radius, the level's step (asinh units)
      real(dp), intent(in) :: edge(0:), c, step
      real(dp), allocatable :: out(:)
      real(dp) :: w, xi_c
      integer :: n, i, k
      out = edge
      if (.not. (c > 0.0_dp .and. c < edge(size(edge) - 1))) return
      w = edge_layer_width(c)
      xi_c = asinh(c/w)
      n = max(1, ceiling(disc_elements*xi_c/step))
      k = 0
      do while (edge(k) <= c)
         k = k + 1
      end do
      out = [0.0_dp, (c - w*sinh(xi_c*real(n - i, dp)/real(n, dp)), i=1, n), edge(k:)]
   end function disc_graded

   !> edge with the radii inside (0, edge's outer radius) added as element edges (the
   !> element holding each split), except where an edge lies within 1e-9 max(1, r)
   !> already: both increasing. Unloading after a capped loading (egw_sphere_solver's
   !> history_cap_unload): the closest-approach field d_max(r) is the history's nodal
   !> deflection, piecewise quadratic, whose slope jumps at the history's element edges,
   !> and in the capped zone the unloading pressure follows d_max (the plastic shift and
   !> offset): kinks of p(r) at every history edge, inside the unloading elements.
   pure function with_history_edges(edge, radii) result(out)
      real(dp), intent(in) :: edge(0:), radii(:)   !< element boundaries, and the history's edges
      real(dp), allocatable :: out(:)
      real(dp) :: x
      logical :: own, last_own
      integer :: i, j, m, n
      n = size(edge) - 1
      allocate (out(size(edge) + size(radii)))
      last_own = .false.
      m = 0
      i = 0
      j = 1
      ! a merge of the two increasing lists, each x appended unless outside (0, the outer
      ! radius) or within the tolerance of the last kept (an edge of edge then replaces a
      ! radius kept just before it)
      do while (i <= n)
         own = .true.
         if (j <= size(radii)) own = radii(j) >= edge(i)
         if (own) then
            x = edge(i)
            i = i + 1
         else
            x = radii(j)
            j = j + 1
            if (.not. (x > 0.0_dp .and. x < edge(n))) cycle
         end if
         if (m > 0 .and. .not. (own .and. last_own)) then
            if (abs(x - out(m)) <= 1.0e-9_dp*max(1.0_dp, x)) then
               if (own) out(m) = x
               last_own = last_own .or. own
               cycle
            end if
         end if
         m = m + 1
         out(m) = x
         last_own = own
      end do
      out = out(:m)
   end function with_history_edges

   !> edge with every element whose both ends are edges of coarse (the level before) cut
   !> at coarse's edges between them and each piece into parts equal parts: no element of
   !> the new level is one of coarse's, nor coarser than coarse there (both increasing,
   !> edge(0) = coarse(0) = 0). An element between two fixed edges (r = 0, kink edges, the
   !> layers at a, the rim) stays the same while the step exceeds it, and its error is
   !> then in both levels, which their difference cannot see; cut into at least the step
   !> ratio's parts, it shrinks at least like the rest (egw_sphere_refine's refine_levels).
   pure function split_kept(edge, coarse, parts) result(out)
      real(dp), intent(in) :: edge(0:)     !< the new level's element boundaries
      real(dp), intent(in) :: coarse(0:)   !< the level before's
      integer, intent(in) :: parts         !< parts of each piece (at least 2)
      real(dp), allocatable :: out(:)
      integer :: i, j, k, q, m, n, nc, l
      n = size(edge) - 1
      nc = size(coarse) - 1
      allocate (out(0:n + parts*nc + 1))
      out(0) = edge(0)
      m = 0
      j = 0   ! coarse(j): the first of coarse's edges at or beyond edge(i - 1)
      do i = 1, n
         do while (j < nc .and. coarse(j) < edge(i - 1))
            j = j + 1
         end do
         k = j
         if (coarse(j) == edge(i - 1)) then
            do while (k < nc .and. coarse(k) < edge(i))
               k = k + 1
            end do
         end if
         if (k > j .and. coarse(k) == edge(i)) then
            do q = j + 1, k
               do l = 1, parts - 1
                  out(m + l) = coarse(q - 1) + (coarse(q) - coarse(q - 1))*real(l, dp)/ &
                     & real(parts, dp)
               end do
               out(m + parts) = coarse(q)
               m = m + parts
            end do
         else
            m = m + 1
            out(m) = edge(i)
         end if
      end do
      out = out(0:m)
   end function split_kept

   !> Width of the boundary layer outside a contact edge at radius edge (scaled units):
   !> where the gap outside a Hertz-like edge, (4/3)(a**2/pi)(2 s/a)**1.5, reaches one
   !> sigma, s_b = (a/2)(3 pi/(4 a**2))**(2/3), at most 1 (mesh_geometry's Hertz edge; the
   !> solver's cap edges and the plastic rim take the same).
   elemental real(dp) function edge_layer_width(edge) result(width)
      real(dp), intent(in) :: edge   !< the contact edge's scaled radius
      width = min(1.0_dp, 0.5_dp*edge*(0.75_dp*pi/edge**2)**(2.0_dp/3.0_dp))
   end function edge_layer_width

   !> Focus of the mesh grading (Hertz edge or 0), its width, and the first outer radius.
   !> Outside the Hertz edge the gap grows like (4/3)(a**2/pi)(2 s/a)**1.5 (s = r - a), so
   !> it reaches one sigma at s_b = (a/2)(3 pi/(4 a**2))**(2/3): the boundary layer whose
   !> relative width is ~ (sigma/delta)**(2/3).
   pure subroutine mesh_geometry(prob, rel_tol, focus, width, outer)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      real(dp), intent(in) :: rel_tol   !< the solve's tolerance
      !> grading focus, its width, the outer radius (scaled)
      real(dp), intent(out) :: focus, width, outer
      real(dp) :: h_ref, f_ref, h_cut, f, dfdh, lo, hi, mid
      integer :: i

      if (prob%a > 1.0_dp .or. (prob%extended .and. prob%a > 0.0_dp)) then
         ! The extended models need a node at a, where z has its (r - a)**1.5 onset.
         focus = prob%a
         width = edge_layer_width(prob%a)
      else
         focus = 0.0_dp
         width = min(1.0_dp, 1.0_dp/sqrt(max(1.0_dp, -prob%delta)))
      end if
      ! Gap where the law has fallen by 1e-3 rel_tol from its value at the closest point.
      h_ref = max(0.0_dp, -prob%delta)
      if (.not. prob%extended .and. prob%delta > 0.0_dp) h_ref = 0.0_dp
      call law_at(prob, h_ref, f_ref, dfdh)
      h_cut = h_ref
      do i = 1, 400
         h_cut = h_cut + 0.25_dp
         call law_at(prob, h_cut, f, dfdh)
         if (f <= 1.0e-3_dp*rel_tol*f_ref) exit
      end do
      ! Classic GW at delta > 0 has its gap below the Hertz gap by up to the centre value
      ! -h(p_H(0)) (eq. 19; ~15 sigma at sigma/delta = 1e-5): reach that much further out.
      if (.not. prob%extended .and. prob%delta > 0.0_dp) h_cut = h_cut &
         & + max(0.0_dp, -law_inverse(prob, 2.0_dp*prob%a/pi))
      ! Radius where the Hertz (or rigid) gap reaches h_cut: bisection, the gap grows with r.
      lo = prob%a
      hi = prob%a + sqrt(2.0_dp*(h_cut + abs(prob%delta))) + 10.0_dp
      do i = 1, 100
         mid = 0.5_dp*(lo + hi)
         if (estimated_gap(prob, mid) < h_cut) then
            lo = mid
         else
            hi = mid
         end if
      end do
      outer = max(hi, focus + 2.0_dp*width)
      ! With the cap the contact outgrows the Hertz radius (from ~2 delta_y on): up to the
      ! radius of a uniform disc at p_y, r**2/2 + (4/pi) p_y r = delta (doc/theory.md §12,
      ! trap iv), with the same margin beyond it.
      if (allocated(prob%cap) .and. prob%delta > 0.0_dp) then
         mid = 4.0_dp*prob%cap%p_y/pi
         mid = 2.0_dp*prob%delta/(mid + sqrt(mid*mid + 2.0_dp*prob%delta))
         outer = max(outer, mid + (outer - prob%a))
      end if
   end subroutine mesh_geometry

   !> Step that gives about n_nodes nodes with graded_edges.
   pure real(dp) function step_for_nodes(extended, focus, width, outer, n_nodes) result(step)
      logical, intent(in) :: extended   !< E-GW or EP-GW (a graded focus)
      !> grading focus, its width, the outer radius (scaled)
      real(dp), intent(in) :: focus, width, outer
      integer, intent(in) :: n_nodes   !< nodes wanted
      real(dp) :: xi_total
      integer :: graded_nodes
      xi_total = asinh(focus/width) + asinh((outer - focus)/width)
      ! The focus layers add 2 focus_layers elements when the focus is inside the mesh.
      graded_nodes = n_nodes - 1
      if (extended .and. focus > 0.0_dp) graded_nodes = graded_nodes &
         & - 2*focus_layers*deflection_degree
      step = xi_total*real(deflection_degree, dp) &
         & /real(max(graded_nodes, 2*deflection_degree), dp)
   end function step_for_nodes

   !> New outer radius when the pressure at the old one leaves too much force outside:
   !> the pressure falls at least like exp(-kappa (r - outer)) with kappa from the last
   !> two Gauss points.
   pure real(dp) function grown_outer(prob, sol, allowed, outer) result(new_outer)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(discrete_solution), intent(in) :: sol   !< a solution on the old outer radius
      real(dp), intent(in) :: allowed, outer   !< force allowed outside, and the old outer radius
      real(dp) :: kappa
      integer :: n
      n = size(sol%p)
      kappa = 0.0_dp
      if (sol%p(n) > 0.0_dp .and. sol%p(n - 1) > sol%p(n)) kappa = log(sol%p(n - 1)/sol%p(n)) &
         & /(sol%mesh%gauss_r(n) - sol%mesh%gauss_r(n - 1))
      if (kappa > 0.0_dp) then
         new_outer = outer + max(0.25_dp*(outer - prob%a), &
            & log(max(sol%tail/(0.001_dp*allowed), 2.0_dp))/kappa)
      else
         new_outer = outer + 0.5_dp*(outer - prob%a)
      end if
      if (prob%a > 0.0_dp) new_outer = max(new_outer, prob%a*1.05_dp)
   end function grown_outer

end module egw_sphere_mesh
