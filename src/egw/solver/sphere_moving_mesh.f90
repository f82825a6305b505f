!> The loading stiffness with the flow-pressure cap as the derivative of the converged
!> answer (issue 32, doc/theory.md §12 "Rough spheres with the cap"): the accepted
!> level's discrete force at delta and delta (1 + h) on its mesh moved with the problem,
!> the Hertz edge a and the cap's kinks c (where the total pressure reaches p_y) carried
!> to their places at delta (1 + h) at the rate at which each kink stays at its edge, the
!> elements between them stretched linearly.
!>
!> Why: the implicit derivative (egw_sphere_iteration's differentiate) holds the mesh
!> fixed while a and c move through it; the Gauss sums of the kinked rates are then off
!> by up to ~1e-3 of the stiffness at rel_tol 1e-6, where the converged forces, whose
!> mesh edges follow a and c from level to level, are right to ~rel_tol and smooth in
!> delta (stop 52, doubt18). On a mesh that moves with the kinks, the discrete force is
!> as smooth in delta as the converged one, and its quotient agrees with quotients of
!> forces solved at rel_tol 1e-8 to a fraction of rel_tol once the elements whose error
!> moves fastest are split (steep_split; stop 57: <= 3.0e-7 at rel_tol 1e-6, where
!> sigma/delta_y 1e-4, 10 delta_y was 1.7e-5 off; doc/theory.md §12 Limits).
module egw_sphere_moving_mesh
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, egw_not_converged, fatal_error, format_real
   use egw_sphere_problem, only: solver_options, method_newton, scaled_problem, &
      & discrete_solution, base_gap, base_gap_rate, law_at, cap_excess, deflection_degree, &
      & max_mesh_nodes
   use egw_halfspace, only: interpolate_nodal, mesh_nodes
   use egw_lapack, only: lu_solve
   use egw_sphere_mesh, only: cap_kink_radii
   use egw_sphere_iteration, only: solve_mesh, prepare_mesh, gap_rate, evaluate, residual
   implicit none
   private

   public :: kink_following_rate

   !> The relative step h of delta. The forces at delta and delta (1 + h) come from Newton
   !> on the same mesh from the converged deflection (to round-off), so the quotient's
   !> round-off is ~1e-16/h of the force; its truncation h/2 delta P''/P' is ~0.45 h of
   !> the stiffness (E-GW + cap, sigma/delta_y 1e-2 at 10 delta_y on a rel_tol 1e-9 mesh:
   !> -4.5e-6, -4.5e-7, -6e-8 at h = 1e-5, 1e-6, 1e-7; at 1e-8 the round-off, +-5e-8,
   !> doc/benchmarks.md "Stop 57: stiff23"), and the kink's motion over the step stays
   !> far inside its edge's Gauss points.
   real(dp), parameter :: step = 1.0e-7_dp
   !> Where the capped zone holds the Hertz edge, the derivative's mesh splits each
   !> element of the layer past the outermost kink into layer_parts (steep_split); a
   !> layer element is one whose inner edge's pressure exceeds layer_pressure p_y and
   !> across which the pressure falls more than 1/layer_drop-fold.
   integer, parameter :: layer_parts = 4
   real(dp), parameter :: layer_pressure = 1.0e-20_dp, layer_drop = 0.1_dp
   !> cap_kink_radii skips kinks whose neighbourhood carries less than this fraction of
   !> the force (as the first level does with 1e-4 rel_tol: far below any tolerance).
   real(dp), parameter :: negligible_weight = 1.0e-12_dp
   !> follow_kink's fixed point at most this many times the distance of its two rates
   !> from the first (else the implicit stiffness, flagged).
   real(dp), parameter :: far_point = 10.0_dp

contains

   !> d(force)/d(delta) of the rough part of sol (a loading solve with the cap, the
   !> accepted level) on its mesh moved with the Hertz edge and the cap's kinks at their
   !> rate: an edge put at each kink (placed) and the force there; then the force at delta
   !> (1 + h) on the mesh moved with a guess of the kinks' rate (the accepted level's
   !> fixed-mesh rate), and with the rate the kink had on it, each solved from the
   !> solution on placed by chord steps (chord_solve); the rate at which the kink stays
   !> where its edge is found from the two, the force there interpolated, and the
   !> quotient taken (follow_kink). rate:
   !> the scaled stiffness of the rough part; ok = .false. (rate untouched) where a solve
   !> failed, a kink was lost, the moved edges would not increase, or at delta <= 0: the
   !> caller keeps the implicit one and says so (solve_result's implicit_stiffness).
   !> Where the cap leaves no kink the implicit rate is exact as it is: ok, rate untouched.
   subroutine kink_following_rate(prob, options, sol, rate, ok)
      type(scaled_problem), intent(in) :: prob   !< the scaled loading problem with the cap
      type(solver_options), intent(in) :: options   !< the solver's options (threads)
      type(discrete_solution), intent(in) :: sol   !< the accepted level's solution
      real(dp), intent(inout) :: rate   !< d(rough force)/d(delta), scaled
      logical, intent(out) :: ok   !< whether rate was replaced
      type(scaled_problem) :: moved
      type(discrete_solution) :: at
      type(egw_error), allocatable :: error
      real(dp), allocatable :: placed(:), knots(:), kinks(:), rates(:)
      real(dp) :: force

      ok = .false.
      knots = cap_kink_radii(prob, sol, negligible_weight)
      ! (no kink: the cap does not act, and the implicit stiffness is the cap-free one's
      ! bit for bit, test_rough_cap's test_no_cap_load)
      if (size(knots) == 0) then
         ok = .true.
         return
      end if
      if (.not. (prob%delta > 0.0_dp)) return
      ! (the accepted mesh has its cap edges where the first level put them; an edge
      ! exactly at each kink makes the quotient insensitive to how well the kinks' motion
      ! is known: E-GW + cap, sigma/delta_y = 1e-4 at 20 delta_y, 1.0e-3 off -> 3e-5)
      placed = with_knots(sol%mesh%edge(0:sol%mesh%n_elem), knots)
      placed = steep_split(prob, sol, placed, maxval(knots))
      moved = prob
      moved%residual_tol = 0.0_dp
      call solve_mesh(moved, options, method_newton, placed, at, error, guess=sol)
      if (allocated(error)) return
      kinks = cap_kink_radii(moved, at, negligible_weight)
      if (size(kinks) /= size(knots)) return
      ! (one kink: the rate only starts follow_kink's fixed point, which its two solves
      ! locate whatever the start, so the accepted level's will do: its linear system
      ! is ~1/16 of an LU on placed, which refinement with Newton's last factors did not
      ! spare at 3.4 delta_y; more kinks: moved at their rates on placed)
      if (size(knots) == 1) then
         call kink_rates(prob, sol, knots, rates, error)
      else
         call kink_rates(moved, at, kinks, rates, error)
      end if
      if (allocated(error)) return
      call follow_kink(moved, options, at, placed, knots, kinks, rates, force, ok)
      if (.not. ok) return
      ! (one-sided: its truncation ~0.45 h of the stiffness, see step; a central
      ! quotient would cost one solve more)
      rate = (force - at%force)/(step*prob%delta)
   end subroutine kink_following_rate

   !> The force at delta (1 + h) on sol's mesh (placed, an edge at each kink) moved with
   !> the Hertz edge and the kinks at the rate at which each stays at its edge. The
   !> discrete kink is pinned to its edge in part: where the mesh moves it at m, it moves
   !> at D(m) = D_0 + f m (f: 0.65, 0.15, ~0 at 1.5, 10, 20 delta_y, E-GW + cap,
   !> sigma/delta_y 1e-4), so its rate on a mesh that follows it is the fixed point m* of
   !> D. Two solves at delta (1 + h): on the mesh moved at m_A, the fixed-mesh rate
   !> (kink_rates, of the accepted level), and at m_B = D(m_A); D from the kinks found on them, the force at m*
   !> interpolated linearly in m between theirs (the force and D are smooth in m while the
   !> kink keeps to its edge's side of the Gauss points). m* within 3e-4 of the rate of
   !> the kinks of rel_tol 1e-8 solves at delta (1 +- 1e-3), where m_A, the fixed-mesh
   !> rate, is up to 3x off (2.8e-3 against 8.5e-3 at 1.5 delta_y, 1e-4) and stop 53's
   !> kinks re-found on a solve at delta (1 + h) 1.8x (doc/benchmarks.md "Stop 55:
   !> dcap21"). More than one kink: each moved at its fixed-mesh rate (f taken as 0; not
   !> met in the measured scenes). ok = .false. where a solve failed, a kink was lost or
   !> the moved edges would not increase.
   subroutine follow_kink(prob, options, sol, placed, knots, kinks, rates, force, ok)
      type(scaled_problem), intent(in) :: prob   !< the scaled loading problem at delta
      type(solver_options), intent(in) :: options   !< the solver's options (threads)
      type(discrete_solution), intent(in) :: sol   !< its solution on placed
      real(dp), intent(in) :: placed(0:)   !< sol's edges
      real(dp), intent(in) :: knots(:)   !< the edges at the kinks
      real(dp), intent(in) :: kinks(:), rates(:)   !< sol's kinks and their fixed-mesh rates
      real(dp), intent(out) :: force   !< the scaled force at delta (1 + h)
      logical, intent(out) :: ok   !< whether force was found
      type(scaled_problem) :: ahead
      real(dp) :: m(2), found(2), forces(2), pinned, fixed_point
      integer :: k
      ok = .false.
      ahead = prob
      call shift_delta(ahead, prob%delta*(1.0_dp + step))
      m(1) = rates(1)
      if (size(knots) > 1) then
         call force_ahead(rates, force, found(1), ok)
         return
      end if
      do k = 1, 2
         if (k == 2) m(2) = found(1)
         call force_ahead([m(k)], forces(k), found(k), ok)
         if (.not. ok) return
         ! (the kink kept to its mesh's motion: m(1) is the fixed point)
         if (k == 1 .and. abs(found(1) - m(1)) <= 1.0e-9_dp*abs(m(1))) then
            force = forces(1)
            return
         end if
      end do
      ok = .false.
      pinned = (found(2) - found(1))/(m(2) - m(1))
      if (.not. pinned < 1.0_dp) return
      fixed_point = (found(1) - pinned*m(1))/(1.0_dp - pinned)
      ! (a kink nearly stuck to its edge, f -> 1, puts the fixed point far beyond the two
      ! solves, where the line is not to be trusted: measured up to 2.9 times their
      ! distance, at 1.5 delta_y)
      if (.not. abs(fixed_point - m(1)) <= far_point*abs(m(2) - m(1))) return
      force = forces(1) + (forces(2) - forces(1))*(fixed_point - m(1))/(m(2) - m(1))
      ok = abs(force) < huge(1.0_dp)
   contains
      !> the force at delta (1 + h) on placed moved with the kinks at rates mk, and the
      !> rate of the first kink found on it
      subroutine force_ahead(mk, f, rate_found, done)
         real(dp), intent(in) :: mk(:)
         real(dp), intent(out) :: f, rate_found
         logical, intent(out) :: done
         type(discrete_solution) :: near
         type(egw_error), allocatable :: error
         real(dp), allocatable :: from(:), to(:), edges(:), again(:)
         done = .false.
         f = 0.0_dp
         rate_found = 0.0_dp
         from = knots
         to = knots + mk*prob%delta*step
         if (prob%extended) then
            ! (a = sqrt(delta): its motion is known exactly)
            from = [prob%a, from]
            to = [ahead%a, to]
         end if
         edges = moved_edges(placed, from, to, sqrt(1.0_dp + step))
         if (size(edges) == 0) return
         call chord_solve(ahead, options, sol, edges, near, done)
         if (.not. done) then
            call solve_mesh(ahead, options, method_newton, edges, near, error, guess=sol)
            if (allocated(error)) return
         end if
         done = .false.
         again = cap_kink_radii(ahead, near, negligible_weight)
         if (size(again) /= size(kinks)) return
         f = near%force
         rate_found = (again(1) - kinks(1))/(step*prob%delta)
         done = .true.
      end subroutine force_ahead
   end subroutine follow_kink

   !> The solution of prob on edges, sol's mesh moved by ~h (the same elements and nodes),
   !> from sol's deflection by chord steps with sol's last Newton factors: the moved
   !> system differs from sol's by ~h, so each step contracts by ~|J_sol**-1 (J - J_sol)|
   !> and costs an evaluation and a triangular solve, where Newton from sol interpolated
   !> factored the moved mesh's Jacobian (n**3, the split mesh's ~930 nodes at 3.4
   !> delta_y: most of the stiffness's cost). Converged as Newton (egw_sphere_iteration)
   !> with residual_tol 0: a step at rounding level and a residual below 1e-9; ok =
   !> .false. where sol has no factors, the steps stop contracting or max_chord is spent
   !> (the caller then solves with Newton).
   subroutine chord_solve(prob, options, sol, edges, near, ok)
      type(scaled_problem), intent(in) :: prob   !< the scaled loading problem with the cap
      type(solver_options), intent(in) :: options   !< the solver's options (threads)
      type(discrete_solution), intent(in) :: sol   !< converged on edges' unmoved mesh
      real(dp), intent(in) :: edges(0:)   !< sol's edges moved
      type(discrete_solution), intent(out) :: near   !< the solution on edges
      logical, intent(out) :: ok   !< whether near converged
      integer, parameter :: max_chord = 30
      real(dp), allocatable :: res(:), dw(:)
      real(dp) :: norm, last
      integer :: n, it, stat
      type(egw_error), allocatable :: error
      ok = .false.
      if (.not. (allocated(sol%lu) .and. allocated(sol%pivots))) return
      call prepare_mesh(prob, options, edges, near, error, rules=sol%mesh)
      if (allocated(error)) return
      n = mesh_nodes(near%mesh)
      if (n /= size(sol%w) .or. size(sol%lu, 1) /= n) return
      allocate (res(n), dw(n), stat=stat)
      if (stat /= 0) return
      near%w = sol%w
      call evaluate(prob, near)
      call residual(near, res, norm)
      last = huge(1.0_dp)
      do it = 1, max_chord
         dw = -res
         call lu_solve(n, sol%lu, sol%pivots, dw)
         near%w = near%w + dw
         call evaluate(prob, near)
         call residual(near, res, norm)
         if (.not. norm < huge(1.0_dp)) return
         if (maxval(abs(dw)) <= 1.0e-14_dp*max(1.0_dp, maxval(abs(near%w))) .and. &
            & norm <= 1.0e-9_dp) then
            ok = .true.
            exit
         end if
         ! (a step that does not shrink: the factors are too far from the moved system)
         if (.not. maxval(abs(dw)) < 0.5_dp*last) return
         last = maxval(abs(dw))
      end do
      if (.not. ok) return
      near%iterations = it
      near%residual = norm
      near%force = 2.0_dp*pi*sum(near%mesh%gauss_w*near%mesh%gauss_r*near%p)
   end subroutine chord_solve

   !> dc/d(delta) of each cap kink c of a loading solution on its fixed mesh: the kink is
   !> where the cap excess e(r, delta) = p_s + law(gap) - p_y of the solution's field
   !> vanishes, so dc/d(delta) = -(de/d(delta))/(de/dr), with the gap's delta-rate from
   !> the implicit derivative of the discrete solution (gap_rate) and de/dr a central
   !> quotient of e on the nodal field. Matches kinks re-found on the same mesh at delta
   !> (1 + 1e-8) to 1.3e-3 of the rate. An error where a rate is not finite.
   subroutine kink_rates(prob, sol, knots, rates, error)
      type(scaled_problem), intent(in) :: prob   !< the scaled loading problem with the cap
      type(discrete_solution), intent(in) :: sol   !< its solution, evaluated at its w
      real(dp), intent(in) :: knots(:)   !< the kinks (cap_kink_radii)
      real(dp), allocatable, intent(out) :: rates(:)   !< dc/d(delta) of each
      !> egw_not_converged (no derivative), egw_out_of_memory
      type(egw_error), allocatable, intent(out) :: error
      real(dp), allocatable :: field(:)
      real(dp) :: c, ds, gap, p, dpdh, gap_rate_c, dps, de_dd, de_dr
      logical :: total
      integer :: k
      allocate (rates(size(knots)))
      call gap_rate(prob, sol, field, total, error)
      if (allocated(error)) return
      do k = 1, size(knots)
         c = knots(k)
         gap = base_gap(prob, c) + interpolate_nodal(sol%mesh, sol%w, c)
         call law_at(prob, gap, p, dpdh)
         if (total) then
            gap_rate_c = interpolate_nodal(sol%mesh, field, c) - 1.0_dp
         else
            gap_rate_c = base_gap_rate(prob, c) + interpolate_nodal(sol%mesh, field, c)
         end if
         ! p_s = (2/pi) sqrt(delta - r**2): d p_s/d delta = (1/pi)/sqrt(delta - r**2)
         dps = 0.0_dp
         if (prob%extended .and. c < prob%a) dps = 1.0_dp/(pi*sqrt(prob%delta - c*c))
         de_dd = dps + dpdh*gap_rate_c
         ! (the nodal interpolant is only C0 at an element edge: the quotient straddling
         ! one takes the mean of both sides' slopes)
         ds = 1.0e-6_dp*c
         de_dr = (excess(c + ds) - excess(c - ds))/(2.0_dp*ds)
         rates(k) = -de_dd/de_dr
         if (.not. (abs(rates(k)) < huge(1.0_dp))) then
            call fatal_error(error, egw_not_converged, "delta = "//format_real(prob%delta) &
               & //" (in units of sigma): the motion of the cap's kink at r = " &
               & //format_real(c)//" is not finite")
            return
         end if
      end do
   contains
      !> the cap excess at r on the nodal field
      pure real(dp) function excess(r)
         real(dp), intent(in) :: r
         excess = cap_excess(prob, r, base_gap(prob, r) + interpolate_nodal(sol%mesh, &
            & sol%w, r), 1)
      end function excess
   end subroutine kink_rates

   !> placed with the elements split whose discretisation error moves fastest with delta,
   !> where the capped zone holds the Hertz edge a (c, the outermost kink, beyond it):
   !> past c the contact ends in a layer where the pressure falls from p_y to nothing
   !> within one or two of the accepted mesh's elements (E-GW + cap, sigma/delta_y 1e-4 at
   !> 10 delta_y: one element 0.5 wide from 52 to 1e-27), and that layer slides through
   !> the element's Gauss points at the small rate by which it and the mesh's motion
   !> differ. Only elements across which the pressure falls more than ten-fold are split:
   !> at 3.4 delta_y, 1e-2, the pressure past c falls gradually over 23 graded elements
   !> (1 .. 0.013 p_y, each less than 4.5-fold) before the last four drop it to 1e-16
   !> p_y; splitting the gradual ones moved none of the 21 points below by more than
   !> 1.3e-8 and cost ~2/3 of the derivative's mesh there (doc/benchmarks.md "Stop 62:
   !> stiff28"). The forces of those meshes are within rel_tol, their derivatives on the
   !> moving mesh were not: sigma/delta_y 1e-4 at 10 delta_y -1.7e-5, at 20 delta_y
   !> 2.3e-6, 1e-5 at 10 delta_y 1.5e-6 (doc/benchmarks.md "Stop 57: stiff23"); with
   !> layer_parts = 4 within 3.3e-7 of fourth-order quotients of rel_tol 1e-8 forces at
   !> 21 points (1e-2 x 1.5 .. 40, 1e-3 x 1.5 .. 20, 1e-4, 1e-5 x 1.5, 10, 20 delta_y).
   !> The elements inside a, split in two at stop 57 (there 1e-2 at 20 delta_y was
   !> -7.7e-6 without), are no longer split: on today's accepted meshes (stop 58's at
   !> the Hertz edge) the split moved none of those 21 by more than 4.3e-8, and it cost
   !> half the derivative at 3.4 delta_y, 1e-2 (61 of the 91 elements lie inside a;
   !> doc/benchmarks.md "Stop 62: stiff28"). Unchanged where c lies inside a (no layer:
   !> the contact ends in the rough part's own decay) or where the split mesh would
   !> exceed max_mesh_nodes.
   function steep_split(prob, sol, placed, c) result(edges)
      type(scaled_problem), intent(in) :: prob   !< the scaled loading problem with the cap
      type(discrete_solution), intent(in) :: sol   !< the accepted level's solution
      real(dp), intent(in) :: placed(:)   !< its edges with an edge at each kink
      real(dp), intent(in) :: c   !< the outermost kink
      real(dp), allocatable :: edges(:)
      real(dp) :: lo, hi, p, p_out, dpdh
      integer :: i, j, parts
      edges = placed
      if (.not. (prob%extended .and. c > prob%a)) return
      edges = placed(1:1)
      do i = 1, size(placed) - 1
         lo = placed(i)
         hi = placed(i + 1)
         parts = 1
         if (lo >= c*(1.0_dp - 1.0e-12_dp)) then
            ! (the pressure falls outwards: its inner edge's is the element's largest)
            call law_at(prob, base_gap(prob, lo) + interpolate_nodal(sol%mesh, sol%w, lo), &
               & p, dpdh)
            call law_at(prob, base_gap(prob, hi) + interpolate_nodal(sol%mesh, sol%w, hi), &
               & p_out, dpdh)
            if (p > layer_pressure*prob%cap%p_y .and. p_out < layer_drop*p) &
               & parts = layer_parts
         end if
         edges = [edges, (lo + (hi - lo)*real(j, dp)/real(parts, dp), j = 1, parts - 1), hi]
      end do
      if ((size(edges) - 1)*deflection_degree + 1 > max_mesh_nodes) edges = placed
   end function steep_split

   !> prob at another overlap (what scaled() makes of delta: the overlap and its Hertz
   !> radius; the law and the cap do not depend on delta).
   pure subroutine shift_delta(prob, delta)
      type(scaled_problem), intent(inout) :: prob
      real(dp), intent(in) :: delta
      prob%delta = delta
      prob%a = sqrt(max(delta, 0.0_dp))
   end subroutine shift_delta

   !> edges (increasing, from 0) with each knot inserted where no edge is within 1e-9 of it.
   pure function with_knots(edges, knots) result(placed)
      real(dp), intent(in) :: edges(:), knots(:)
      real(dp), allocatable :: placed(:)
      integer :: i, j
      placed = edges
      do i = 1, size(knots)
         if (.not. knots(i) > 0.0_dp .or. knots(i) >= placed(size(placed))) cycle
         if (minval(abs(placed - knots(i))) <= 1.0e-9_dp*knots(i)) cycle
         j = count(placed < knots(i))
         placed = [placed(1:j), knots(i), placed(j + 1:)]
      end do
   end function with_knots

   !> edges moved piecewise linearly: each knot to its target, those beyond the outermost
   !> knot scaled by outer_scale about it; empty if the knots are not distinct or the
   !> moved edges do not increase.
   pure function moved_edges(edges, knots, targets, outer_scale) result(moved)
      real(dp), intent(in) :: edges(0:), knots(:), targets(:), outer_scale
      real(dp), allocatable :: moved(:)
      real(dp) :: k(0:size(knots)), t(0:size(knots))
      integer :: i, j, m
      m = size(knots)
      ! (knots and targets sorted together, with r = 0 fixed)
      k(0) = 0.0_dp
      t(0) = 0.0_dp
      k(1:m) = knots
      t(1:m) = targets
      do i = 2, m
         do j = i, 2, -1
            if (k(j) >= k(j - 1)) exit
            k([j - 1, j]) = k([j, j - 1])
            t([j - 1, j]) = t([j, j - 1])
         end do
      end do
      if (any(k(1:m) <= k(0:m - 1)) .or. any(t(1:m) <= t(0:m - 1))) then
         allocate (moved(0))
         return
      end if
      allocate (moved(0:ubound(edges, 1)))
      do i = 0, ubound(edges, 1)
         if (edges(i) >= k(m)) then
            moved(i) = t(m) + (edges(i) - k(m))*outer_scale
         else
            j = 1
            do while (edges(i) >= k(j))
               j = j + 1
            end do
            moved(i) = t(j - 1) + (edges(i) - k(j - 1))*(t(j) - t(j - 1))/(k(j) - k(j - 1))
         end if
      end do
      if (any(moved(1:) <= moved(:ubound(moved, 1) - 1))) then
         deallocate (moved)
         allocate (moved(0))
      end if
   end function moved_edges

end module egw_sphere_moving_mesh
