!> The nonlinear solve of one mesh (doc/theory.md §7): w = H p(z + w) at the nodes by
!> Newton with a backtracking line search (egw_lapack's lu_factor/lu_solve, factors reused
!> while they contract) or damped Picard, from an initial deflection near the solution; the
!> force by the Gauss sum, and the stiffness by implicit differentiation of the converged
!> system.
module egw_sphere_iteration
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_progress, only: progress_note
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, egw_not_converged, &
      & egw_out_of_memory, fatal_error, format_real, int_str
   use egw_smooth_sphere, only: hertz_gap, hertz_pressure
   use egw_halfspace, only: build_mesh, mesh_nodes, node_index, assemble_influence, &
      & influence_cache, assemble_influence_cached, cached_point_values, keep_point_values, &
      & interpolate_nodal_walk, interpolate_nodal, radial_mesh, halfspace_kernel, gauss_legendre
   use egw_lapack, only: lu_factor, lu_solve
   use egw_solver_workspace, only: solver_workspace, reserve
   use egw_sphere_mesh, only: kink_radii
   use egw_sphere_problem, only: method_picard, solver_options, max_mesh_nodes, &
      & scaled_problem, discrete_solution, law_at, law_inverse, base_gap, base_gap_rate, &
      & closest_gap, gauss_values, gauss_gap, deflection_degree, pressure_points, rough_pressure, &
      & cap_fields, sums_total, smooth_stiffness
   implicit none
   private

   !> What evaluate writes into a solution (the fields at the Gauss points), kept so that
   !> Newton can go back to an iterate without evaluating it again.
   type :: evaluation
      real(dp), allocatable :: gap(:), p(:), dpdh(:), dpdd(:), unfloored(:)
   end type evaluation

   integer, parameter :: newton_max_default = 100, picard_max_default = 3000
   !> Unloading after a capped loading (floor_stiffness): kinks whose neighbourhood carries
   !> less than this fraction of the force are skipped (as egw_sphere_moving_mesh does).
   real(dp), parameter :: kink_weight = 1.0e-12_dp

   public :: solve_mesh, prepare_mesh, differentiate, gap_rate, initial_deflection, evaluate, residual, jacobian, &
      & newton, picard

contains

   !> Build the mesh on edges, assemble, and solve the discrete equations; then the force,
   !> its delta-derivative (implicit differentiation), moments and the tail estimate.
   subroutine solve_mesh(prob, options, method, edges, sol, error, guess, cache)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(solver_options), intent(in) :: options   !< the solver's options
      integer, intent(in) :: method   !< method_newton or method_picard
      real(dp), intent(in) :: edges(0:)   !< element boundaries, edges(0) = 0, increasing
      type(discrete_solution), intent(out) :: sol   !< the solution on that mesh
      !> egw_not_converged (too many nodes, no convergence) or egw_out_of_memory
      type(egw_error), allocatable, intent(out) :: error
      type(discrete_solution), intent(in), optional :: guess  !< solution on another mesh
      !> influence matrices of the caller's earlier meshes: shared coefficients reused
      type(influence_cache), intent(inout), optional :: cache
      integer :: n, ng, max_iter
      real(dp) :: kappa, rn

      call prepare_mesh(prob, options, edges, sol, error, cache)
      if (allocated(error)) return
      n = mesh_nodes(sol%mesh)
      ng = size(sol%mesh%gauss_r)
      if (present(guess)) then
         ! Interpolated; beyond the guess's mesh its outermost value (w_G varies slowly there).
         allocate (sol%w(n))
         call interpolate_nodal_walk(guess%mesh, guess%w, &
            & min(sol%mesh%node, guess%mesh%edge(guess%mesh%n_elem)), sol%w)
      else
         call initial_deflection(prob, sol)
      end if

      max_iter = options%max_iter
      if (method == method_picard) then
         if (max_iter == 0) max_iter = picard_max_default
         call picard(prob, sol, max_iter, error)
      else
         if (max_iter == 0) max_iter = newton_max_default
         call newton(prob, sol, max_iter, error)
         ! The cap's guided route (prob%kink_width > 0; egw_sphere_solver's
         ! guided_cap_solve): a guess interpolated from another mesh can put the steep
         ! gap of the plastic zone's edge layers off, where Newton stalls; from the
         ! initial deflection it converges on these meshes (their layers resolve the edge)
         if (allocated(error) .and. prob%kink_width > 0.0_dp .and. present(guess)) then
            deallocate (error, sol%w)
            call initial_deflection(prob, sol)
            call newton(prob, sol, max_iter, error)
         end if
      end if
      if (allocated(error)) return

      sol%force = 2.0_dp*pi*sum(sol%mesh%gauss_w*sol%mesh%gauss_r*sol%p)
      ! unloading after a capped loading: the total pressure (sums_total)
      if (sums_total(prob)) sol%force = total_force(prob, sol%mesh, sol%p, sol%p_smooth)
      sol%moment0 = sum(sol%mesh%gauss_w*sol%p)
      sol%moment1 = sum(sol%mesh%gauss_w*sol%mesh%gauss_r*sol%p)
      ! Force beyond the outer radius if p keeps falling like at the last two Gauss points.
      rn = sol%mesh%gauss_r(ng)
      kappa = 0.0_dp
      if (sol%p(ng) > 0.0_dp .and. sol%p(ng - 1) > sol%p(ng)) &
         & kappa = log(sol%p(ng - 1)/sol%p(ng))/(rn - sol%mesh%gauss_r(ng - 1))
      if (kappa > 0.0_dp) then
         sol%tail = 2.0_dp*pi*rn*sol%p(ng)*(1.0_dp/kappa + 1.0_dp/(rn*kappa**2))
      else
         sol%tail = huge(1.0_dp)
         if (sol%p(ng) == 0.0_dp) sol%tail = 0.0_dp
      end if
   end subroutine solve_mesh

   !> The set-up of one mesh's solve, everything before the first iterate: the mesh on
   !> edges, its influence matrix, the base gap and its delta-rate at the Gauss points, and
   !> with the cap its fields (from the history's closest approach when unloading). Shared
   !> by solve_mesh and the moved-mesh chord solves (egw_sphere_moving_mesh).
   subroutine prepare_mesh(prob, options, edges, sol, error, cache, rules)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(solver_options), intent(in) :: options   !< the solver's options (threads)
      real(dp), intent(in) :: edges(0:)   !< element boundaries, edges(0) = 0, increasing
      type(discrete_solution), intent(out) :: sol   !< the mesh and its fields, no w yet
      !> egw_not_converged (too many nodes) or egw_out_of_memory
      type(egw_error), allocatable, intent(out) :: error
      !> influence matrices of the caller's earlier meshes: shared coefficients reused
      type(influence_cache), intent(inout), optional :: cache
      !> a mesh whose Gauss rules are taken (without cache; the same numbers, less work)
      type(radial_mesh), intent(in), optional :: rules
      integer :: n, ng, stat
      logical, allocatable :: known(:)
      logical :: reuse

      if ((size(edges) - 1)*deflection_degree + 1 > max_mesh_nodes) then
         call fatal_error(error, egw_not_converged, "delta = "//format_real(prob%delta) &
            & //" (in units of sigma): the mesh would need " &
            & //int_str((size(edges) - 1)*deflection_degree + 1)//" nodes, more than " &
            & //int_str(max_mesh_nodes))
         return
      end if
      if (present(cache)) then
         ! (the rules of the caller's first mesh, the same numbers: ~1 % of a build)
         call build_mesh(edges, deflection_degree, pressure_points, sol%mesh, cache%rules)
         if (.not. allocated(cache%rules%log_lw)) cache%rules = sol%mesh
      else if (present(rules)) then
         call build_mesh(edges, deflection_degree, pressure_points, sol%mesh, rules)
      else
         call build_mesh(edges, deflection_degree, pressure_points, sol%mesh)
      end if
      n = mesh_nodes(sol%mesh)
      ng = size(sol%mesh%gauss_r)
      ! unloading with the cap: the law at gap_min where an earlier level of the solve has
      ! the same Gauss points (cap_fields; the history, prob%closest, is the key)
      reuse = present(cache) .and. allocated(prob%closest) .and. allocated(prob%cap)
      if (reuse) then
         allocate (sol%law_min(ng), known(ng))
         call cached_point_values(cache, sol%mesh, prob%closest%delta, sol%law_min, known)
      end if
      allocate (sol%infl(n, ng), stat=stat)
      if (stat == 0) then
         if (present(cache)) then
            call assemble_influence_cached(sol%mesh, sol%infl, options%n_threads, cache, &
               & stat)
         else
            call assemble_influence(sol%mesh, sol%mesh%node, sol%infl, options%n_threads, &
               & stat)
         end if
      end if
      if (stat /= 0) then
         call fatal_error(error, egw_out_of_memory, "the influence matrix of " &
            & //int_str(n)//" nodes could not be allocated")
         return
      end if
      sol%base = base_gap(prob, sol%mesh%gauss_r)
      sol%dbase = base_gap_rate(prob, sol%mesh%gauss_r)
      if (allocated(prob%closest)) sol%gap_min = closest_gap(prob%closest, sol%mesh%gauss_r)
      if (allocated(prob%cap)) then
         if (allocated(sol%gap_min)) then
            if (reuse) then
               call cap_fields(prob, sol%mesh%gauss_r, sol%gap_min, sol%p_smooth, sol%dps, &
                  & sol%shift, sol%offset, sol%law_min, known)
               call keep_point_values(cache, sol%mesh, prob%closest%delta, sol%law_min)
            else
               call cap_fields(prob, sol%mesh%gauss_r, sol%gap_min, sol%p_smooth, sol%dps, &
                  & sol%shift, sol%offset, sol%law_min)
            end if
         else
            call cap_fields(prob, sol%mesh%gauss_r, 0.0_dp*sol%mesh%gauss_r, sol%p_smooth, &
               & sol%dps, sol%shift, sol%offset)
         end if
      end if
   end subroutine prepare_mesh

   !> Unloading after a capped loading (sums_total): the force, the Gauss sum of the total
   !> pressure p + p_s, with p_s's share of every element above the floor at all its Gauss
   !> points (edges inside the Hertz radius a) in closed form. Where the floor holds the
   !> total at 0 the Gauss sum is exact; above it the Gauss sum of p_s's sqrt(a - r) edge
   !> converged like step**1.5 where the floor kink sat just inside a, an element of length
   !> L ending d from a with L/d ~ 150 (E-GW + cap, README's pair, 2.1221 sigma after
   !> 212.7 sigma: 4.7e-9 of the force at the finest step, rel_tol 1e-8 not reached;
   !> doc/benchmarks.md "Stop 61: acc27"). The rough part is smooth inside a.
   pure real(dp) function total_force(prob, mesh, p, p_smooth) result(force)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem (extended, delta > 0)
      type(radial_mesh), intent(in) :: mesh   !< the solution's mesh
      real(dp), intent(in) :: p(:), p_smooth(:)   !< rough and Hertz pressures at its Gauss points
      real(dp) :: q1, q2, s1, s2, r2
      integer :: e, g0, g1
      force = 2.0_dp*pi*sum(mesh%gauss_w*mesh%gauss_r*(p + p_smooth))
      do e = 1, mesh%n_elem
         if (.not. mesh%edge(e - 1) < prob%a) exit
         g0 = (e - 1)*mesh%n_gauss + 1
         g1 = e*mesh%n_gauss
         if (any(.not. p(g0:g1) + p_smooth(g0:g1) > 0.0_dp)) cycle
         ! int 2 pi r (2/pi) sqrt(a**2 - r**2) dr over [r1, r2] = (4/3)(q1**1.5 - q2**1.5),
         ! q = a**2 - r**2, written (4/3)(q1 - q2)(q1 + s1 s2 + q2)/(s1 + s2), s = sqrt(q),
         ! q1 - q2 = (r2 - r1)(r2 + r1): no cancellation
         r2 = min(mesh%edge(e), prob%a)
         q1 = (prob%a - mesh%edge(e - 1))*(prob%a + mesh%edge(e - 1))
         q2 = (prob%a - r2)*(prob%a + r2)
         s1 = sqrt(q1)
         s2 = sqrt(q2)
         force = force - 2.0_dp*pi*sum(mesh%gauss_w(g0:g1)*mesh%gauss_r(g0:g1)*p_smooth(g0:g1)) &
            & + (4.0_dp/3.0_dp)*(r2 - mesh%edge(e - 1))*(r2 + mesh%edge(e - 1)) &
            & *(q1 + s1*s2 + q2)/(s1 + s2)
      end do
   end function total_force

   !> d(force)/d(delta) of the converged discrete solution by implicit differentiation:
   !> J dw/d(delta) = infl (p' dz/d(delta)) with J the Jacobian at the solution. Newton's
   !> last factors belong to an iterate near the solution: iterative refinement with them
   !> (residuals with the exact J) contracts by |J_old**-1 (J - J_old)| << 1 per sweep
   !> and spares an LU; without them, or if refinement stalls, J itself is factored.
   subroutine differentiate(prob, sol, error, work)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(discrete_solution), intent(inout) :: sol   !< converged; its delta-derivatives filled
      !> egw_not_converged (singular Jacobian) or egw_out_of_memory
      type(egw_error), allocatable, intent(out) :: error
      !> the caller's buffers (the Jacobian's taken from it; else allocated here)
      type(solver_workspace), intent(inout), optional :: work
      real(dp), allocatable :: own(:)
      integer :: n, stat
      n = size(sol%w)
      if (present(work)) then
         call reserve(work%jac, n*n, stat)
         if (stat == 0) call differentiate_in(prob, sol, work%jac, error)
      else
         allocate (own(n*n), stat=stat)
         if (stat == 0) call differentiate_in(prob, sol, own, error)
      end if
      if (stat /= 0) call fatal_error(error, egw_out_of_memory, "the Jacobian of " &
         & //int_str(n)//" nodes could not be allocated")
   end subroutine differentiate

   !> differentiate's work, its Jacobian in jac (the first n**2 entries of the buffer).
   subroutine differentiate_in(prob, sol, jac, error)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(inout) :: sol
      real(dp), intent(inout) :: jac(size(sol%w), size(sol%w))
      type(egw_error), allocatable, intent(out) :: error
      real(dp), allocatable :: x(:, :), rate(:), free_rate(:)
      logical :: edge_capped
      ! Newton and Picard return with the law evaluated at the converged w (their last
      ! evaluate); only a solution whose fields no longer match w is evaluated again (the
      ! same pure computation, so the same numbers either way). Unloading: the law's
      ! integrals Z_u are ~45 % of a hysteresis build, this evaluation a third of the
      ! finest level's.
      if (.not. evaluated_at_w(sol)) call evaluate(prob, sol)
      if (sums_total(prob)) then
         call floor_stiffness(prob, sol, jac, error)
         return
      end if
      call rate_system(prob, sol, jac, x, edge_capped, free_rate, error)
      if (allocated(error)) return
      if (edge_capped) then
         ! (solve_rough adds the Hertz stiffness, which the total holds)
         rate = gauss_values(sol%mesh, x(:, 1)) - 1.0_dp
         sol%dforce = 2.0_dp*pi*sum(sol%mesh%gauss_w*sol%mesh%gauss_r*(sol%dpdh*rate + &
            & free_rate)) - smooth_stiffness(prob)
         return
      end if
      rate = sol%dbase + gauss_values(sol%mesh, x(:, 1))
      sol%dforce = 2.0_dp*pi*sum(sol%mesh%gauss_w*sol%mesh%gauss_r*(sol%dpdh*rate + sol%dpdd))
   end subroutine differentiate_in

   !> differentiate after a capped loading (sums_total): d(force)/d(delta) of the total
   !> pressure, with what the Gauss sums of the fixed mesh miss at the floor (the total
   !> held at 0) put back (doc/benchmarks.md "Stop 63: stiffb29"; the README pair,
   !> 209 and 212.7 sigma: 1e-6 .. 6e-6 of the stiffness near the bottom):
   !> - on an element inside the Hertz radius a whose Gauss points all sit at the floor,
   !>   the rough part's rate -d(p_s)/d(delta) = -(1/pi)/sqrt(delta - r**2) has the
   !>   1/sqrt(a - r) edge where the element ends at a: its force rate in closed form,
   !>   and in the right-hand side of the rate system its values scaled to the element's
   !>   exact integral (the deflection of such a short element is its integral's);
   !> - a kink of the total pressure (the floor's, a branch of the law: its rate jumps by
   !>   J) a distance e from its element edge leaves a sliver of width e in which the
   !>   Gauss points' side of the kink stands for the other: J e 2 pi r of force rate
   !>   and its deflection (the kernel over the sliver) missed, first order in e where
   !>   the force's own error is J e**2 (the edges follow the kinks only to the force's
   !>   tolerance: 209 sigma, 1 sigma, e = 2.5e-6). Both put back, the deflection's
   !>   share through the same Jacobian (extra columns of the rate system).
   subroutine floor_stiffness(prob, sol, jac, error)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(inout) :: sol
      real(dp), intent(inout) :: jac(size(sol%w), size(sol%w))
      type(egw_error), allocatable, intent(out) :: error
      real(dp), allocatable :: x(:, :), free_rate(:), source(:), slivers(:, :), kinks(:), &
         & edges(:), weighted(:), rate(:)
      logical, allocatable :: floored(:)
      logical :: edge_capped
      integer :: e, g0, g1, k
      real(dp) :: jump, q1, q2, r2

      call floored_elements(prob, sol, floored, source)
      call kink_slivers(prob, sol, kinks, edges, slivers)
      call rate_system(prob, sol, jac, x, edge_capped, free_rate, error, source, slivers)
      if (allocated(error)) return
      weighted = 2.0_dp*pi*sol%mesh%gauss_w*sol%mesh%gauss_r
      rate = sol%dpdh*(sol%dbase + gauss_values(sol%mesh, x(:, 1)))
      sol%dforce = 0.0_dp
      do e = 1, sol%mesh%n_elem
         g0 = (e - 1)*sol%mesh%n_gauss + 1
         g1 = e*sol%mesh%n_gauss
         if (.not. floored(e)) then
            sol%dforce = sol%dforce + sum(weighted(g0:g1)*(rate(g0:g1) + sol%dpdd(g0:g1)))
            cycle
         end if
         ! int 2 pi r (1/pi)/sqrt(a**2 - r**2) dr over [r1, r2] = 2 (sqrt(q1) - sqrt(q2)),
         ! q = a**2 - r**2
         r2 = min(sol%mesh%edge(e), prob%a)
         q1 = (prob%a - sol%mesh%edge(e - 1))*(prob%a + sol%mesh%edge(e - 1))
         q2 = (prob%a - r2)*(prob%a + r2)
         sol%dforce = sol%dforce + sum(weighted(g0:g1)*rate(g0:g1)) &
            & - 2.0_dp*(r2 - sol%mesh%edge(e - 1))*(r2 + sol%mesh%edge(e - 1)) &
            & /(sqrt(q1) + sqrt(q2))
      end do
      do k = 1, size(kinks)
         ! the total's rate on the kink's two sides, and the sliver's share: its own
         ! force rate and that of the deflection it adds (x(:, 1 + k) per unit jump)
         jump = total_rate_at(prob, sol, x(:, 1), kinks(k)*(1.0_dp - 1.0e-9_dp)) &
            & - total_rate_at(prob, sol, x(:, 1), kinks(k)*(1.0_dp + 1.0e-9_dp))
         sol%dforce = sol%dforce + jump*(pi*(kinks(k) + edges(k))*(kinks(k) - edges(k)) &
            & + sum(weighted*sol%dpdh*gauss_values(sol%mesh, x(:, 1 + k))))
      end do
   end subroutine floor_stiffness

   !> Which elements lie inside the Hertz radius with all their Gauss points at the floor
   !> (floor_stiffness), and the right-hand side's rate at fixed gap: sol%dpdd, on those
   !> elements scaled so that its Gauss sum is the exact int (1/pi)/sqrt(a**2 - r**2) dr.
   pure subroutine floored_elements(prob, sol, floored, source)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(in) :: sol
      logical, allocatable, intent(out) :: floored(:)
      real(dp), allocatable, intent(out) :: source(:)
      integer :: e, g0, g1
      real(dp) :: r1, r2, exact, summed
      allocate (floored(sol%mesh%n_elem))
      source = sol%dpdd
      floored = .false.
      do e = 1, sol%mesh%n_elem
         r1 = sol%mesh%edge(e - 1)
         if (.not. r1 < prob%a) exit
         g0 = (e - 1)*sol%mesh%n_gauss + 1
         g1 = e*sol%mesh%n_gauss
         if (.not. all(sol%dpdd(g0:g1) < 0.0_dp)) cycle
         floored(e) = .true.
         r2 = min(sol%mesh%edge(e), prob%a)
         ! int dr/sqrt(a**2 - r**2) = theta(r1) - theta(r2), theta = acos(r/a) written
         ! atan2(sqrt((a - r)(a + r)), r): no cancellation next to a
         exact = -(atan2(sqrt((prob%a - r1)*(prob%a + r1)), r1) &
            & - atan2(sqrt((prob%a - r2)*(prob%a + r2)), r2))/pi
         summed = sum(sol%mesh%gauss_w(g0:g1)*sol%dpdd(g0:g1))
         source(g0:g1) = sol%dpdd(g0:g1)*(exact/summed)
      end do
   end subroutine floored_elements

   !> The strong kinks of sol's total pressure (kink_radii's first: the floor's, the law's
   !> branch) that lie off their nearest element edge but closer to it than its element's
   !> first Gauss point (so that all of that element's points sit on one side), the edges,
   !> and per kink the deflection at the nodes of a unit pressure on the sliver between
   !> them, signed as the kink's offset from the edge (floor_stiffness).
   subroutine kink_slivers(prob, sol, kinks, edges, slivers)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(in) :: sol
      real(dp), allocatable, intent(out) :: kinks(:), edges(:), slivers(:, :)
      integer, parameter :: n_points = 4
      real(dp), allocatable :: found(:)
      real(dp) :: t(n_points), w(n_points), r_edge, gap_edge, lo, hi, first_point
      integer :: n_first, k, i, ie, m
      logical, allocatable :: keep(:)
      found = kink_radii(prob, sol, kink_weight, n_first)
      found = found(1:n_first)
      allocate (keep(size(found)), edges(size(found)))
      keep = .false.
      ! (the local Gauss points' distance from an element end, as a fraction of it)
      first_point = 0.5_dp*(1.0_dp - maxval(abs(sol%mesh%local_s)))
      do k = 1, size(found)
         ie = minloc(abs(sol%mesh%edge(0:sol%mesh%n_elem) - found(k)), 1) - 1
         r_edge = sol%mesh%edge(ie)
         edges(k) = r_edge
         ! (the history's kinks, fixed in r, sit on their edges to rounding: a sliver
         ! below 1e-12 r moves the stiffness by < 1e-10 even where the rate jumps by
         ! ~100, next to a; not worth its solve)
         if (abs(found(k) - r_edge) <= 1.0e-12_dp*found(k)) cycle
         ! the element the sliver lies in
         if (found(k) > r_edge) then
            if (ie == sol%mesh%n_elem) cycle
            gap_edge = first_point*(sol%mesh%edge(ie + 1) - r_edge)
         else
            if (ie == 0) cycle
            gap_edge = first_point*(r_edge - sol%mesh%edge(ie - 1))
         end if
         keep(k) = abs(found(k) - r_edge) < 0.5_dp*gap_edge
      end do
      kinks = pack(found, keep)
      edges = pack(edges, keep)
      m = size(sol%w)
      allocate (slivers(m, size(kinks)))
      call gauss_legendre(n_points, t, w)
      do k = 1, size(kinks)
         lo = min(kinks(k), edges(k))
         hi = max(kinks(k), edges(k))
         do i = 1, m
            if (sol%mesh%node(i) == edges(k) .and. edges(k) > 0.0_dp) then
               ! the kernel's log edge, (2/pi) ln(8 r/s) at distance s, integrated (at
               ! r = 0 the kernel is smooth: the Gauss sum below)
               slivers(i, k) = 2.0_dp/pi*(hi - lo)*(log(8.0_dp*edges(k)/(hi - lo)) + 1.0_dp)
            else
               slivers(i, k) = 0.5_dp*(hi - lo)*sum(w*halfspace_kernel(sol%mesh%node(i), &
                  & lo + 0.5_dp*(hi - lo)*(t + 1.0_dp)))
            end if
         end do
         slivers(:, k) = sign(1.0_dp, kinks(k) - edges(k))*slivers(:, k)
      end do
   end subroutine kink_slivers

   !> The total pressure's delta-rate at radius r of a solution whose deflection's rate is
   !> x (nodal): d(p_s)/d(delta) + dp/dh (dz/d(delta) + x) + dp/d(delta), evaluated at r
   !> as evaluate does at the Gauss points (0 where the floor holds the total).
   function total_rate_at(prob, sol, x, r) result(rate)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(in) :: sol
      real(dp), intent(in) :: x(:), r
      real(dp) :: rate
      real(dp) :: radius(1), gap(1), gap_min(1), p(1), dpdh(1), dpdd(1)
      real(dp), allocatable :: p_smooth(:), dps(:), shift(:), offset(:)
      radius = r
      gap_min = closest_gap(prob%closest, radius)
      gap = base_gap(prob, r) + interpolate_nodal(sol%mesh, sol%w, r)
      call cap_fields(prob, radius, gap_min, p_smooth, dps, shift, offset)
      call rough_pressure(prob, gap, gap_min, p_smooth, dps, shift, offset, p, dpdh, dpdd)
      rate = dps(1) + dpdh(1)*(base_gap_rate(prob, r) + interpolate_nodal(sol%mesh, x, r)) &
         & + dpdd(1)
   end function total_rate_at

   !> The delta-derivative of a converged loading solution's gap as a nodal field: the
   !> gap's rate at r is base_gap_rate(r) + the field interpolated at r, or, where the
   !> capped zone holds the Hertz edge (total), the field less 1 (differentiate's system
   !> for the total deflection). Its Jacobian built here, solved with Newton's last
   !> factors as differentiate does. sol: evaluated at its w (as differentiate leaves it);
   !> else egw_not_converged.
   subroutine gap_rate(prob, sol, field, total, error)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(discrete_solution), intent(in) :: sol   !< converged, evaluated at its w
      real(dp), allocatable, intent(out) :: field(:)   !< the nodal field
      logical, intent(out) :: total   !< the field is the total deflection's rate
      !> egw_not_converged (not evaluated, singular Jacobian) or egw_out_of_memory
      type(egw_error), allocatable, intent(out) :: error
      real(dp), allocatable :: jac(:, :), x(:, :), free_rate(:)
      integer :: n, stat
      total = .false.
      if (.not. evaluated_at_w(sol)) then
         call fatal_error(error, egw_not_converged, "delta = "//format_real(prob%delta) &
            & //" (in units of sigma): the gap's rate of a solution not evaluated at its w")
         return
      end if
      n = size(sol%w)
      allocate (jac(n, n), stat=stat)
      if (stat /= 0) then
         call fatal_error(error, egw_out_of_memory, "the Jacobian of " &
            & //int_str(n)//" nodes could not be allocated")
         return
      end if
      call rate_system(prob, sol, jac, x, total, free_rate, error)
      if (allocated(error)) return
      field = x(:, 1)
   end subroutine gap_rate

   !> The implicit derivative's linear system at a solution evaluated at its w:
   !> J x = infl (p' dz/d(delta) + dp/d(delta)), x = dw/d(delta), or where the capped zone
   !> holds the Hertz edge (edge_capped) the same J with the total deflection's right-hand
   !> side (free_rate: uncapped_rate). Newton's last factors belong to an iterate near
   !> the solution: iterative refinement with them (residuals with the exact J) contracts
   !> by |J_old**-1 (J - J_old)| << 1 per sweep and spares an LU; without them, or if
   !> refinement stalls, J itself is factored (in jac).
   !> source: the rough part's dp/d(delta) at fixed gap in the right-hand side (absent:
   !> sol%dpdd); extra: more right-hand sides, solved into x(:, 2:) with the same matrix
   !> (x(:, 1) the same numbers with or without them).
   subroutine rate_system(prob, sol, jac, x, edge_capped, free_rate, error, source, extra)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(in) :: sol
      real(dp), intent(inout) :: jac(size(sol%w), size(sol%w))
      real(dp), allocatable, intent(out) :: x(:, :)
      logical, intent(out) :: edge_capped
      real(dp), allocatable, intent(out) :: free_rate(:)
      type(egw_error), allocatable, intent(out) :: error
      real(dp), intent(in), optional :: source(:), extra(:, :)
      integer, parameter :: max_sweeps = 6
      real(dp), allocatable :: rhs(:), b(:, :), corr(:)
      integer, allocatable :: ipiv(:)
      integer :: n, info, k, n_extra
      logical :: refined, done
      logical, allocatable :: pending(:)
      n = size(sol%w)
      edge_capped = .false.
      n_extra = 0
      if (present(extra)) n_extra = size(extra, 2)
      allocate (x(n, 1 + n_extra), b(n, 1 + n_extra), corr(n), stat=info)
      if (info /= 0) then
         call fatal_error(error, egw_out_of_memory, "the Jacobian of " &
            & //int_str(n)//" nodes could not be allocated")
         return
      end if
      call jacobian(sol, jac)
      ! with the cap the rough part also moves with delta at fixed gap (sol%dpdd)
      edge_capped = capped_at_edge(prob, sol)
      if (edge_capped) then
         ! The capped zone holds the Hertz edge a: the total pressure there is p_y, the
         ! rough part p_y - p_s, whose rate -d(p_s)/d(delta) = -(1/pi)/sqrt(delta - r**2)
         ! has the Hertz stiffness's 1/sqrt(a - r) edge, which the Gauss sums integrate to
         ! ~1e-3 of the stiffness only (beyond ~3 delta_y, sigma = delta_y/100). Written
         ! for the total instead, the capped points' rates cancel exactly: the gap rate is
         ! -1 + H[d(p_s)/d(delta) where p_s > 0 but not capped] + H[rough rate elsewhere],
         ! the same Jacobian with another right-hand side (uncapped_rate: the first term's
         ! pressure), and dP/d(delta) = int (uncapped_rate + dp/dh gap rate); see
         ! doc/theory.md §12 "Rough spheres with the cap".
         free_rate = uncapped_rate(prob, sol)
         rhs = matmul(sol%infl, free_rate - sol%dpdh)
      else if (present(source)) then
         rhs = matmul(sol%infl, sol%dpdh*sol%dbase + source)
      else
         rhs = matmul(sol%infl, sol%dpdh*sol%dbase + sol%dpdd)
      end if
      b(:, 1) = rhs
      if (n_extra > 0) b(:, 2:) = extra
      x = b
      ! pending(k): column k still to be solved with J's own factors
      allocate (pending(1 + n_extra))
      pending = .true.
      if (allocated(sol%lu)) then
         if (size(sol%lu, 1) == n) then
            ! (the extra columns refined alike, each on its own, once the first is; one
            ! whose refinement stalls is solved with J's factors below, not left as is)
            call refine(1, refined)
            if (refined) then
               pending(1) = .false.
               do k = 2, 1 + n_extra
                  call refine(k, done)
                  pending(k) = .not. done
               end do
            end if
         end if
      end if
      if (any(pending)) then
         allocate (ipiv(n))
         call lu_factor(n, jac, ipiv, info)
         if (info /= 0) then
            call fatal_error(error, egw_not_converged, "delta = "//format_real(prob%delta) &
               & //" (in units of sigma): singular Jacobian at the solution")
            return
         end if
         do k = 1, 1 + n_extra
            if (.not. pending(k)) cycle
            x(:, k) = b(:, k)
            call lu_solve(n, jac, ipiv, x(:, k))
         end do
      end if
   contains
      !> column k of x solved with Newton's last factors and refined with the exact J
      subroutine refine(k, converged)
         integer, intent(in) :: k
         logical, intent(out) :: converged
         integer :: sweep
         converged = .false.
         call lu_solve(n, sol%lu, sol%pivots, x(:, k))
         do sweep = 1, max_sweeps
            call less_product(n, jac, x(:, k), b(:, k), corr)
            call lu_solve(n, sol%lu, sol%pivots, corr)
            x(:, k) = x(:, k) + corr
            if (maxval(abs(corr)) <= 1.0e-14_dp*maxval(abs(x(:, k)))) then
               converged = .true.
               return
            end if
         end do
      end subroutine refine
   end subroutine rate_system

   !> r = b - jac x, with jac x summed column after column as gfortran's inline matmul
   !> sums it (the same numbers). rate_system's refinement wrote it inside its contained
   !> procedure, where jac, x and b are the host's: the compiler reloaded their
   !> descriptors at every element (scalar, ~20 instructions an element) and that loop
   !> was ~11 % of a rough + cap build's CPU (doc/benchmarks.md "Stop 64: psi30").
   pure subroutine less_product(n, jac, x, b, r)
      integer, intent(in) :: n
      real(dp), intent(in) :: jac(n, n), x(n), b(n)
      real(dp), intent(out) :: r(n)
      real(dp) :: t(n)
      integer :: j
      t = 0.0_dp
      do j = 1, n
         t = t + jac(:, j)*x(j)
      end do
      r = b - t
   end subroutine less_product

   !> Loading with the cap of an extended model (differentiate): whether the Gauss point
   !> nearest the Hertz edge a from inside is capped (sol%dpdd < 0 there).
   pure logical function capped_at_edge(prob, sol) result(capped)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(in) :: sol
      integer :: g
      capped = .false.
      if (.not. (allocated(prob%cap) .and. prob%extended)) return
      if (allocated(prob%closest)) return
      g = count(sol%mesh%gauss_r < prob%a)
      if (g < 1) return
      capped = sol%dpdd(g) < 0.0_dp
   end function capped_at_edge

   !> d(p_s)/d(delta) at the Gauss points inside the Hertz radius that are not capped, 0
   !> elsewhere (differentiate, capped_at_edge).
   pure function uncapped_rate(prob, sol) result(rate)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(in) :: sol
      real(dp) :: rate(size(sol%dps))
      rate = 0.0_dp
      where (sol%mesh%gauss_r < prob%a .and. .not. sol%dpdd < 0.0_dp) rate = sol%dps
   end function uncapped_rate

   !> Whether the gap, pressure and its derivatives of sol are those of its w (as
   !> evaluate leaves them): the gap is recomputed exactly as evaluate does and compared.
   pure logical function evaluated_at_w(sol) result(same)
      type(discrete_solution), intent(in) :: sol
      same = .false.
      if (.not. (allocated(sol%gap) .and. allocated(sol%p) .and. allocated(sol%dpdh) &
         & .and. allocated(sol%dpdd))) return
      if (size(sol%gap) /= size(sol%base)) return
      same = all(sol%gap == sol%base + gauss_values(sol%mesh, sol%w))
   end function evaluated_at_w

   !> Initial rough deflection. Separated spheres: 0 (the base gap is already close).
   !> Extended models: inside the Hertz radius the gap is w_G itself, and a disc of radius a
   !> under uniform pressure p sags by 2 p a at its centre (E = 1), so w_G ~ w_c with
   !> w_c = 2 a p_G(w_c), flat inside a and falling like the flat-punch field (2/pi)
   !> asin(a/r) outside. From w = 0 Newton needs 7 LUs at delta/sigma = 1e4, from this 3.
   !> Classic GW at delta > 0: the deflection whose gap gives the Hertz pressure through
   !> the law (capped near the edge), so that w ~ w_H: the stiff case starts close to its
   !> solution.
   pure subroutine initial_deflection(prob, sol)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(discrete_solution), intent(inout) :: sol   !< its mesh built; w set
      integer :: i
      real(dp) :: r, h, target, lo, hi, f, dfdh
      real(dp), parameter :: h_cap = 1.5_dp
      allocate (sol%w(mesh_nodes(sol%mesh)))
      sol%w = 0.0_dp
      if (prob%delta <= 0.0_dp) return
      if (prob%extended) then
         ! Bisection for w_c - 2 a p_G(w_c) = 0 (increasing in w_c; p_G(40) underflows).
         lo = 0.0_dp
         hi = 40.0_dp
         do i = 1, 50
            h = 0.5_dp*(lo + hi)
            call law_at(prob, h, f, dfdh)
            if (h < 2.0_dp*prob%a*f) then
               lo = h
            else
               hi = h
            end if
         end do
         where (sol%mesh%node <= prob%a)
            sol%w = h
         elsewhere
            sol%w = h*2.0_dp/pi*asin(prob%a/sol%mesh%node)
         end where
         return
      end if
      do i = 1, size(sol%w)
         r = sol%mesh%node(i)
         target = hertz_pressure(r, prob%delta, 1.0_dp, 1.0_dp)
         h = h_cap
         if (target > 0.0_dp) h = min(h_cap, law_inverse(prob, target))
         sol%w(i) = hertz_gap(r, prob%delta, 1.0_dp) + h - base_gap(prob, r)
      end do
   end subroutine initial_deflection

   !> Gap, pressure and its derivative at the Gauss points for the current w (the
   !> unloading law at the closest-approach gaps when unloading; the cap: rough_pressure).
   pure subroutine evaluate(prob, sol)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(discrete_solution), intent(inout) :: sol   !< w given; gap, p, dp/dh filled
      if (allocated(sol%gap)) then
         if (size(sol%gap) /= size(sol%base)) deallocate (sol%gap)
      end if
      if (.not. allocated(sol%gap)) allocate (sol%gap(size(sol%base)))
      call gauss_gap(sol%mesh, sol%w, sol%base, sol%gap)
      sol%p = sol%gap       ! (sized as the gap)
      sol%dpdh = sol%gap
      sol%dpdd = sol%gap
      if (allocated(sol%gap_min) .and. allocated(prob%cap)) then
         ! (kept for the cap's kink scan, cap_excess_points)
         if (allocated(sol%unfloored)) then
            if (size(sol%unfloored) /= size(sol%gap)) deallocate (sol%unfloored)
         end if
         if (.not. allocated(sol%unfloored)) allocate (sol%unfloored(size(sol%gap)))
         call rough_pressure(prob, sol%gap, sol%gap_min, sol%p_smooth, sol%dps, sol%shift, &
            & sol%offset, sol%p, sol%dpdh, sol%dpdd, sol%unfloored)
      else if (allocated(sol%gap_min)) then
         call rough_pressure(prob, sol%gap, sol%gap_min, sol%p_smooth, sol%dps, sol%shift, &
            & sol%offset, sol%p, sol%dpdh, sol%dpdd)
      else
         call rough_pressure(prob, sol%gap, sol%gap, sol%p_smooth, sol%dps, sol%shift, &
            & sol%offset, sol%p, sol%dpdh, sol%dpdd)
      end if
   end subroutine evaluate

   !> Copies evaluate's fields of sol into kept.
   pure subroutine keep_evaluation(sol, kept)
      type(discrete_solution), intent(in) :: sol   !< evaluated
      type(evaluation), intent(inout) :: kept   !< its fields
      call copy_field(sol%gap, kept%gap)
      call copy_field(sol%p, kept%p)
      call copy_field(sol%dpdh, kept%dpdh)
      call copy_field(sol%dpdd, kept%dpdd)
      call copy_field(sol%unfloored, kept%unfloored)
   end subroutine keep_evaluation

   !> Puts kept's fields back into sol (as keep_evaluation found them).
   pure subroutine restore_evaluation(kept, sol)
      type(evaluation), intent(in) :: kept   !< from keep_evaluation
      type(discrete_solution), intent(inout) :: sol   !< its fields restored
      call copy_field(kept%gap, sol%gap)
      call copy_field(kept%p, sol%p)
      call copy_field(kept%dpdh, sol%dpdh)
      call copy_field(kept%dpdd, sol%dpdd)
      call copy_field(kept%unfloored, sol%unfloored)
   end subroutine restore_evaluation

   !> b = a, allocation included (b deallocated where a is not allocated; reused when the
   !> sizes agree).
   pure subroutine copy_field(a, b)
      real(dp), allocatable, intent(in) :: a(:)
      real(dp), allocatable, intent(inout) :: b(:)
      if (.not. allocated(a)) then
         if (allocated(b)) deallocate (b)
         return
      end if
      if (allocated(b)) then
         if (size(b) /= size(a)) deallocate (b)
      end if
      if (.not. allocated(b)) allocate (b(size(a)))
      b(:) = a
   end subroutine copy_field

   !> Residual F = w - H p_G(z + w) (at the current evaluate()) and its scaled max norm.
   pure subroutine residual(sol, res, norm)
      type(discrete_solution), intent(in) :: sol   !< evaluated at the current w
      real(dp), intent(out) :: res(:)   !< F at the nodes
      real(dp), intent(out) :: norm   !< its scaled max norm
      res = sol%w - matmul(sol%infl, sol%p)
      norm = maxval(abs(res))/max(1.0_dp, maxval(abs(sol%w)))
   end subroutine residual

   !> Jacobian J = I - infl diag(p') interp. A column of J (a node of element e) gets the
   !> element's Gauss columns of infl in one pass (c(q) = p'_q interp(j, q)), not one pass
   !> a Gauss point; points where p' = 0 (capped, floored, separated) are left out. No
   !> pass zeroes J first: a column's first element writes it (0 - sum, then 1 + that on
   !> the diagonal: the numbers of 0 - sum and 1 - sum to the bit), a column no element
   !> writes is the identity's.
   pure subroutine jacobian(sol, jac)
      type(discrete_solution), intent(in) :: sol   !< evaluated at the current w
      real(dp), intent(out) :: jac(:, :)   !< J, nodes x nodes
      integer :: e, q, j, g0, col, n_used, used(sol%mesh%n_gauss), i
      real(dp) :: c(sol%mesh%n_gauss), acc
      logical :: written(size(jac, 2))
      written = .false.
      do e = 1, sol%mesh%n_elem
         g0 = (e - 1)*sol%mesh%n_gauss
         n_used = 0
         do q = 1, sol%mesh%n_gauss
            if (sol%dpdh(g0 + q) /= 0.0_dp) then
               n_used = n_used + 1
               used(n_used) = g0 + q
            end if
         end do
         if (n_used == 0) cycle
         do j = 0, sol%mesh%degree
            col = node_index(sol%mesh, e, j)
            do q = 1, n_used
               c(q) = sol%dpdh(used(q))*sol%mesh%interp(j, used(q) - g0)
            end do
            if (.not. written(col)) then
               if (n_used == sol%mesh%n_gauss .and. n_used == 6) then
                  do i = 1, size(jac, 1)
                     jac(i, col) = 0.0_dp - (((c(1)*sol%infl(i, g0 + 1) &
                        & + c(2)*sol%infl(i, g0 + 2)) + (c(3)*sol%infl(i, g0 + 3) &
                        & + c(4)*sol%infl(i, g0 + 4))) + (c(5)*sol%infl(i, g0 + 5) &
                        & + c(6)*sol%infl(i, g0 + 6)))
                  end do
               else
                  do i = 1, size(jac, 1)
                     acc = 0.0_dp
                     do q = 1, n_used
                        acc = acc + c(q)*sol%infl(i, used(q))
                     end do
                     jac(i, col) = 0.0_dp - acc
                  end do
               end if
               jac(col, col) = 1.0_dp + jac(col, col)
               written(col) = .true.
            else if (n_used == sol%mesh%n_gauss .and. n_used == 6) then
               ! (the solver's six points: the sum unrolled, one pass over the column)
               do i = 1, size(jac, 1)
                  jac(i, col) = jac(i, col) - (((c(1)*sol%infl(i, g0 + 1) &
                     & + c(2)*sol%infl(i, g0 + 2)) + (c(3)*sol%infl(i, g0 + 3) &
                     & + c(4)*sol%infl(i, g0 + 4))) + (c(5)*sol%infl(i, g0 + 5) &
                     & + c(6)*sol%infl(i, g0 + 6)))
               end do
            else
               do i = 1, size(jac, 1)
                  acc = 0.0_dp
                  do q = 1, n_used
                     acc = acc + c(q)*sol%infl(i, used(q))
                  end do
                  jac(i, col) = jac(i, col) - acc
               end do
            end if
         end do
      end do
      do col = 1, size(jac, 2)
         if (written(col)) cycle
         jac(:, col) = 0.0_dp
         jac(col, col) = 1.0_dp
      end do
   end subroutine jacobian

   !> Newton with backtracking (Armijo on |F|_2). Converged when the scaled residual is
   !> below prob%residual_tol: 1e-11 (the rounding floor of H p is ~1e-12 for w ~ 1e6;
   !> looser for unloading, see solve_scaled), or the step is at rounding level with a
   !> residual below 1e-9.
   !> The LU factors are kept once Newton is in its quadratic regime (the last full step
   !> cut |F|_2 at least chord_start-fold): a full step with the old factors (chord step) is
   !> accepted when it cuts |F|_2 at least chord_gain-fold, else the Jacobian is refactored
   !> at the same iterate and the Newton step with line search taken. Near the solution a
   !> chord step contracts like |w - w*|, so the fallback only costs one evaluation, while
   !> the LU (n**3) is most of an iteration's cost on the solver's meshes. Far from the
   !> solution chord steps would cost iterations: max_iter counts both kinds alike.
   subroutine newton(prob, sol, max_iter, error)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(discrete_solution), intent(inout) :: sol   !< in: the start; out: the solution
      integer, intent(in) :: max_iter   !< iterations allowed (chord and Newton steps alike)
      !> egw_not_converged or egw_out_of_memory
      type(egw_error), allocatable, intent(out) :: error
      real(dp), parameter :: chord_gain = 10.0_dp, chord_start = 100.0_dp
      real(dp), allocatable :: jac(:, :), res(:), step(:, :), w0(:), res_try(:)
      integer, allocatable :: ipiv(:)
      type(evaluation) :: kept
      integer :: n, it, info, k
      real(dp) :: norm, norm_try, lambda, f2, f2_try
      logical :: factored, have_lu, converged

      n = size(sol%w)
      allocate (jac(n, n), res(n), step(n, 1), ipiv(n), res_try(n), stat=info)
      if (info /= 0) then
         call fatal_error(error, egw_out_of_memory, "the Jacobian of " &
            & //int_str(n)//" nodes could not be allocated")
         return
      end if
      call evaluate(prob, sol)
      call residual(sol, res, norm)
      factored = .false.
      have_lu = .false.
      converged = .false.
      do it = 1, max_iter + 1
         sol%iterations = it - 1
         sol%residual = norm
         converged = norm <= prob%residual_tol
         if (converged .or. it > max_iter) exit
         w0 = sol%w
         f2 = sum(res**2)
         lambda = 1.0_dp
         if (factored) then
            step(:, 1) = -res
            call lu_solve(n, jac, ipiv, step(:, 1))
            ! (w0's evaluation kept: a chord step that fails restores it, not re-evaluates
            ! it; evaluate is pure, so the same bits)
            call keep_evaluation(sol, kept)
            sol%w = w0 + step(:, 1)
            call evaluate(prob, sol)
            call residual(sol, res_try, norm_try)
            f2_try = sum(res_try**2)
            factored = f2_try <= f2/chord_gain**2 .and. ieee_is_finite(f2_try)
            if (.not. factored) then
               sol%w = w0
               call restore_evaluation(kept, sol)
            end if
         end if
         if (.not. factored) then
            call jacobian(sol, jac)
            call lu_factor(n, jac, ipiv, info)
            ! (a sign of life for a progress hook: on 4097 nodes an LU takes seconds)
            call progress_note("solve: Newton step")
            have_lu = info == 0
            if (.not. have_lu) exit
            factored = .true.
            step(:, 1) = -res
            call lu_solve(n, jac, ipiv, step(:, 1))
            do k = 1, 40
               sol%w = w0 + lambda*step(:, 1)
               call evaluate(prob, sol)
               call residual(sol, res_try, norm_try)
               f2_try = sum(res_try**2)
               if (f2_try <= (1.0_dp - 1.0e-4_dp*lambda)*f2) exit
               lambda = 0.5_dp*lambda
            end do
            ! Factors from far away (damped, or slow) are not worth reusing. Every solve
            ! takes chord steps, EP-GW unloading (psi > 0) with and without the cap alike:
            ! its law's kink at d = d_max (dp/dh jumps) slows them (seen: 5 chord steps
            ! from 1e-4 to 1e-11 where Newton takes 2), and a failed one no longer pays a
            ! second evaluation (keep_evaluation): the psi 1 + cap table of the README
            ! builds in 0.93-0.98 of the CPU, EP-GW psi 1 to 30 sigma without the cap in
            ! 1.003x the instructions (its meshes are small: LU 1.6 %, Z_u's integral 47 %;
            ! doc/benchmarks.md "Stop 55: psi21"). One rule for both keeps an unloading the
            ! cap never touches the cap-free one, bit for bit.
            factored = lambda == 1.0_dp .and. f2_try <= f2/chord_start**2
         end if
         res = res_try
         norm = norm_try
         if (maxval(abs(lambda*step(:, 1))) <= 1.0e-14_dp*max(1.0_dp, maxval(abs(sol%w))) &
            & .and. norm <= 1.0e-9_dp) then
            sol%iterations = it
            sol%residual = norm
            converged = .true.
            exit
         end if
      end do
      if (converged) then
         ! Keep the last factors for differentiate.
         if (have_lu) then
            call move_alloc(jac, sol%lu)
            call move_alloc(ipiv, sol%pivots)
         end if
         return
      end if
      sol%iterations = max_iter
      sol%residual = norm
      call fatal_error(error, egw_not_converged, "delta = "//format_real(prob%delta) &
         & //" (in units of sigma): Newton did not converge in "//int_str(max_iter) &
         & //" iterations, residual "//format_real(norm))
   end subroutine newton

   !> Damped fixed point w <- w - omega (w - H p_G(z + w)); omega halves when the residual
   !> grows and recovers slowly while it falls. Converged at a scaled residual of 1e-11.
   !> Where the spectral radius of H |dp/dw| is large (classic GW at small sigma/delta)
   !> omega must become tiny and the iteration runs out of max_iter: not converged.
   subroutine picard(prob, sol, max_iter, error)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(discrete_solution), intent(inout) :: sol   !< in: the start; out: the solution
      integer, intent(in) :: max_iter   !< iterations allowed
      type(egw_error), allocatable, intent(out) :: error   !< egw_not_converged
      real(dp), allocatable :: res(:), w0(:)
      real(dp) :: norm, norm_old, omega
      integer :: it
      allocate (res(size(sol%w)))
      omega = 0.5_dp
      call evaluate(prob, sol)
      call residual(sol, res, norm)
      do it = 1, max_iter + 1
         sol%iterations = it - 1
         sol%residual = norm
         if (norm <= 1.0e-11_dp) return
         if (it > max_iter) exit
         w0 = sol%w
         norm_old = norm
         sol%w = w0 - omega*res
         call evaluate(prob, sol)
         call residual(sol, res, norm)
         if (norm > norm_old) then
            omega = 0.5_dp*omega
         else
            omega = min(1.0_dp, 1.05_dp*omega)
         end if
      end do
      sol%iterations = max_iter
      sol%residual = norm
      call fatal_error(error, egw_not_converged, "delta = "//format_real(prob%delta) &
         & //" (in units of sigma): Picard did not converge in "//int_str(max_iter) &
         & //" iterations, residual "//format_real(norm))
   end subroutine picard

end module egw_sphere_iteration
