!> The loading stiffness with the flow-pressure cap as the derivative of the converged
!> answer (issue 32, doc/theory.md §12 "Rough spheres with the cap"): the accepted
!> level's discrete force at delta (1 +- h) on its mesh moved with the problem, the Hertz
!> edge a and the cap's kinks c (where the total pressure reaches p_y) carried to their
!> places at delta (1 +- h), the elements between them stretched linearly.
!>
!> Why: the implicit derivative (egw_sphere_iteration's differentiate) holds the mesh
!> fixed while a and c move through it; the Gauss sums of the kinked rates are then off
!> by up to ~1e-3 of the stiffness at rel_tol 1e-6, where the converged forces, whose
!> mesh edges follow a and c from level to level, are right to ~rel_tol and smooth in
!> delta (stop 52, doubt18). On a mesh that moves with the kinks, the discrete force is
!> as smooth in delta as the converged one, and its central quotient agrees with
!> quotients of forces solved at rel_tol 1e-9 to a few rel_tol.
module egw_sphere_moving_mesh
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_sphere_problem, only: solver_options, method_newton, scaled_problem, &
      & discrete_solution
   use egw_sphere_mesh, only: cap_kink_radii
   use egw_sphere_iteration, only: solve_mesh
   implicit none
   private

   public :: kink_following_rate

   !> The relative step h of delta. The forces at delta (1 +- h) come from Newton on the
   !> same mesh from the converged deflection (to round-off), so the quotient's round-off
   !> is ~1e-16/h of the force; its truncation h**2 of the curvature. 1e-6: both below
   !> 1e-9 of the stiffness.
   real(dp), parameter :: step = 1.0e-6_dp
   !> cap_kink_radii skips kinks whose neighbourhood carries less than this fraction of
   !> the force (as the first level does with 1e-4 rel_tol: far below any tolerance).
   real(dp), parameter :: negligible_weight = 1.0e-12_dp

contains

   !> d(force)/d(delta) of the rough part of sol (a loading solve with the cap, the
   !> accepted level) on its mesh moved with the Hertz edge and the cap's kinks: the kinks
   !> at delta (1 + h) from a solve on the mesh scaled with the Hertz radius, those at
   !> delta (1 - h) mirrored (the kinks move smoothly: the mirror's error is O(h**2)),
   !> then the forces on the two moved meshes. rate: the scaled stiffness of the rough
   !> part; ok = .false. (rate untouched) where a solve failed, the kinks could not be
   !> matched or the moved edges would not increase, or at delta <= 0: the caller keeps
   !> the implicit one and says so (solve_result's implicit_stiffness). Where the cap
   !> leaves no kink the implicit rate is exact as it is: ok, rate untouched.
   subroutine kink_following_rate(prob, options, sol, rate, ok)
      type(scaled_problem), intent(in) :: prob   !< the scaled loading problem with the cap
      type(solver_options), intent(in) :: options   !< the solver's options (threads)
      type(discrete_solution), intent(in) :: sol   !< the accepted level's solution
      real(dp), intent(inout) :: rate   !< d(rough force)/d(delta), scaled
      logical, intent(out) :: ok   !< whether rate was replaced
      type(scaled_problem) :: moved
      type(discrete_solution) :: near
      type(egw_error), allocatable :: error
      real(dp), allocatable :: edges(:), placed(:), knots(:), ahead(:), behind(:)
      real(dp) :: force(2), sign_h
      integer :: n, side

      ok = .false.
      knots = cap_kink_radii(prob, sol, negligible_weight)
      ! (no kink: the cap does not act, and the implicit stiffness is the cap-free one's
      ! bit for bit, test_rough_cap's test_no_cap_load)
      if (size(knots) == 0) then
         ok = .true.
         return
      end if
      if (.not. (prob%delta > 0.0_dp)) return
      n = sol%mesh%n_elem
      edges = sol%mesh%edge(0:n)
      ! (the accepted mesh has its cap edges where the first level put them; an edge
      ! exactly at each kink makes the quotient insensitive to how well the kinks' motion
      ! is known: E-GW + cap, sigma/delta_y = 1e-4 at 20 delta_y, 1.0e-3 off -> 3e-5)
      placed = with_knots(edges, knots)
      if (prob%extended) knots = [prob%a, knots]
      ! the kinks at delta (1 + h), from the mesh scaled with the Hertz radius
      moved = prob
      moved%residual_tol = 0.0_dp
      call shift_delta(moved, prob%delta*(1.0_dp + step))
      call solve_mesh(moved, options, method_newton, edges*sqrt(1.0_dp + step), near, error, &
         & guess=sol)
      if (allocated(error)) return
      ahead = cap_kink_radii(moved, near, negligible_weight)
      if (prob%extended) ahead = [moved%a, ahead]
      if (size(ahead) /= size(knots)) return
      behind = 2.0_dp*knots - ahead
      do side = 1, 2
         sign_h = merge(1.0_dp, -1.0_dp, side == 1)
         moved = prob
         moved%residual_tol = 0.0_dp
         call shift_delta(moved, prob%delta*(1.0_dp + sign_h*step))
         if (side == 1) then
            edges = moved_edges(placed, knots, ahead, sqrt(1.0_dp + step))
         else
            edges = moved_edges(placed, knots, behind, sqrt(1.0_dp - step))
         end if
         if (size(edges) == 0) return
         call solve_mesh(moved, options, method_newton, edges, near, error, guess=sol)
         if (allocated(error)) return
         force(side) = near%force
      end do
      rate = (force(1) - force(2))/(2.0_dp*step*prob%delta)
      ok = .true.
   end subroutine kink_following_rate

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
