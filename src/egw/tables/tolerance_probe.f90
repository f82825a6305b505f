!> A quick look, before a long build, at whether the solves it needs can reach their
!> tolerance (issue 22 item 5: a 1e-6 hysteresis table ran 21.6 min before one of its
!> solves gave up). A few solves of the kind the build needs, at its own solve
!> tolerance: a failure there fails the build at once, in the caller's terms. A probe
!> that passes promises nothing (the build may still meet a solve that fails; its
!> message then quotes the caller's rel_tol too).
module egw_tolerance_probe
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_not_converged, format_real
   use egw_params, only: contact_params, model_epgw
   use egw_rough_sphere, only: solver_options, solve_result, solve_contact, &
      & solve_contact_unload
   implicit none
   private

   public :: probe_hysteresis_tolerance, hysteresis_solve_tol

contains

   !> Before build_hysteresis(params, options, ., delta_max, rel_tol): at the turning points
   !> delta_max and delta_max/2 (if > 0), the loading solve and the unloading solves from
   !> it at eight fractions of its unloading length 1.5 P/K, 0.03 .. 0.99 (the curves the
   !> build solves at the most s nodes; where unloading solves are hardest, beside the
   !> kinks of d = d_max and far down the curve), at the build's solve tolerance
   !> hysteresis_solve_tol. Unreachable tolerances show as
   !> sporadic solves that stop on the finest mesh (psi 10 at 1e-10: 1 in 18 points along
   !> a curve), which the build's hundreds of solves are sure to meet. A solve that does not converge
   !> (egw_not_converged) fails the probe with a message that quotes the caller's rel_tol,
   !> the solves' tolerance, the overlaps and what the solve reached; any other error
   !> (invalid input) is left to the build's own checks (no error here). Reversible
   !> contacts (no plastic summits) need no unloading solves: nothing is done. Cost: 18
   !> solves (milliseconds at the usual tolerances, seconds at 1e-10).
   subroutine probe_hysteresis_tolerance(params, options, delta_max, rel_tol, error)
      type(contact_params), intent(in) :: params   !< the contact of the build
      type(solver_options), intent(in) :: options  !< the build's solver options
      real(dp), intent(in) :: delta_max            !< the build's largest overlap [length]
      real(dp), intent(in) :: rel_tol              !< the build's (the caller's) tolerance
      !> allocated only when a solve cannot reach the tolerance
      type(egw_error), allocatable, intent(out) :: error
      real(dp), parameter :: fractions(8) = [0.03_dp, 0.1_dp, 0.3_dp, 0.5_dp, 0.7_dp, &
         & 0.9_dp, 0.95_dp, 0.99_dp]
      type(solver_options) :: opts
      type(solve_result) :: top, res
      real(dp) :: span, delta, m
      integer :: i, j
      if (.not. (params%model == model_epgw .and. params%psi > 0.0_dp .and. &
         & params%sigma > 0.0_dp)) return
      opts = options
      opts%rel_tol = hysteresis_solve_tol(options, rel_tol)
      do j = 1, 2
         m = delta_max
         if (j == 2) then
            if (.not. delta_max > 0.0_dp) return
            m = 0.5_dp*delta_max
         end if
         call solve_contact(params, opts, m, top, error)
         if (allocated(error)) then
            call explain(error, m, m)
            return
         end if
         if (.not. (top%force > 0.0_dp .and. top%stiffness > 0.0_dp)) return
         span = 1.5_dp*top%force/top%stiffness
         do i = 1, size(fractions)
            delta = m - fractions(i)*span
            call solve_contact_unload(params, opts, delta, m, res, error)
            if (allocated(error)) then
               call explain(error, delta, m)
               return
            end if
         end do
      end do
   contains
      !> A not-converged solve in the caller's terms; other errors dropped (the build
      !> reports invalid input itself).
      subroutine explain(error, delta, m)
         type(egw_error), allocatable, intent(inout) :: error
         real(dp), intent(in) :: delta, m
         if (error%stat /= egw_not_converged) then
            deallocate (error)
            return
         end if
         error%message = "hysteresis table: rel_tol = "//format_real(rel_tol)// &
            & " (the caller's) cannot be reached, found before the build: its curves "// &
            & "are solved at "//format_real(opts%rel_tol)//", and the solve at delta = "// &
            & format_real(delta)//" after delta_max = "//format_real(m)//" fails: "// &
            & error%message
      end subroutine explain
   end subroutine probe_hysteresis_tolerance

   !> The tolerance of a hysteresis build's unloading curve solves (build_hysteresis) for
   !> the table's rel_tol: rel_tol/10, or options%rel_tol where the caller set that below
   !> its default (1e-6) and below rel_tol/10.
   pure real(dp) function hysteresis_solve_tol(options, rel_tol) result(tol)
      type(solver_options), intent(in) :: options   !< the build's solver options
      real(dp), intent(in) :: rel_tol               !< the table's tolerance
      type(solver_options), parameter :: defaults = solver_options()
      ! Not min(options%rel_tol, rel_tol/10) as the 1-D tables: the table's accuracy is
      ! set by its checks against these solves (rel_tol/4 in s, rel_tol in delta_max),
      ! which tighter solves do not change. The default options (1e-6) gave a 1e-4 table
      ! (egw-bench --hysteresis) the same grid (50 x 55) and errors (to 3 digits: 9.0e-5
      ! at the checks, 7.0e-5 against 207 solves at 1e-8) at 1e-5 as at 1e-6, for 21%
      ! less CPU time (2 runs each, on a busy machine). A caller who sets a tighter
      ! options%rel_tol still gets it (and the probe's quick failure where it is out of
      ! reach).
      tol = 0.1_dp*rel_tol
      if (options%rel_tol < defaults%rel_tol) tol = min(tol, options%rel_tol)
   end function hysteresis_solve_tol

end module egw_tolerance_probe
