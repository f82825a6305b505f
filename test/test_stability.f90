!> Stability of the rough-sphere solver across its documented range (doc/stability.md):
!> a coarse subset of the stability map (example/stability_map) at the corners of
!> mu in [0.01, 1000], delta/sigma in [-10, 1e5], psi in [0, 50], K in [0.2, 0.95], for
!> every method. Asserts that AUTO converges everywhere, that a failure is always
!> egw_not_converged, that no method returns OK with a non-finite result or with a force
!> error above rel_tol (against the independent references, and between methods), and that
!> Picard fails where doc/theory.md §5 says it must (classic GW, large spectral radius).
module test_stability
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use testdrive, only: new_unittest, unittest_type, error_type, check, test_failed
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_not_converged
   use egw_params, only: contact_params, model_gw, model_egw, model_epgw
   use egw_rough_sphere, only: solver_options, solve_result, solve_contact, method_auto, &
      & method_newton, method_picard
   implicit none
   private
   public :: collect_stability

   !> Picard iterations allowed here: the map's failures at 3000 fail at 300 as well, and
   !> the test stays fast (a failure must come back as egw_not_converged either way).
   integer, parameter :: picard_iter = 300

contains

   subroutine collect_stability(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("corners of the range: status and consistency", test_corners), &
         & new_unittest("every method against independent references", test_references), &
         & new_unittest("rel_tol 1e-3 and 1e-9 against references", test_tolerances), &
         & new_unittest("Picard fails on stiff GW, AUTO does not", test_picard_fails) &
         & ]
   end subroutine collect_stability

   !> One solve; stat = 0 on success. A failure must be egw_not_converged (the inputs are
   !> valid), and a success must be finite with est_rel_err within rel_tol/2 (the solver's
   !> stopping rule).
   subroutine solve_checked(error, p, method, delta, res, stat)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params), intent(in) :: p
      integer, intent(in) :: method
      real(dp), intent(in) :: delta
      type(solve_result), intent(out) :: res
      integer, intent(out) :: stat
      type(solver_options) :: opts
      type(egw_error), allocatable :: err
      opts = solver_options(method=method, n_threads=1)
      if (method == method_picard) opts%max_iter = picard_iter
      call solve_contact(p, opts, delta, res, err)
      stat = 0
      if (allocated(err)) then
         stat = err%stat
         call check(error, stat, egw_not_converged, "failure status at "//where(p, delta, method) &
            & //": "//err%message)
         return
      end if
      call check(error, ieee_is_finite(res%force) .and. ieee_is_finite(res%stiffness) .and. &
         & ieee_is_finite(res%contact_radius) .and. ieee_is_finite(res%max_pressure) .and. &
         & res%force >= 0.0_dp, "non-finite or negative result at "//where(p, delta, method))
      if (allocated(error)) return
      call check(error, res%force == 0.0_dp .or. res%est_rel_err <= 0.5_dp*opts%rel_tol, &
         & "OK with est_rel_err above rel_tol/2 at "//where(p, delta, method))
   end subroutine solve_checked

   !> Corners and centre of the documented range, every model and method: AUTO must
   !> converge; Newton and Picard may fail (status checked in solve_checked) but, when OK,
   !> agree with AUTO within 2 rel_tol (each is within rel_tol of the truth: the error
   !> estimate is Richardson with a conservative order, stopped at rel_tol/2; the map
   !> (doc/stability) shows errors <= 1.3e-7 at rel_tol = 1e-6).
   subroutine test_corners(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: mus(3) = [0.01_dp, 1.0_dp, 1000.0_dp]
      real(dp), parameter :: deltas(4) = [-10.0_dp, 0.0_dp, 10.0_dp, 1.0e5_dp]
      type(contact_params) :: p
      type(solve_result) :: auto, res
      integer :: i, j, k, method, stat
      do i = 1, size(mus)
         do j = 1, size(deltas)
            do k = 1, 4
               select case (k)
               case (1); p = contact_params(model=model_gw, mu=mus(i), sigma=1.0_dp)
               case (2); p = contact_params(model=model_egw, mu=mus(i), sigma=1.0_dp)
               case (3); p = contact_params(model=model_epgw, mu=mus(i), sigma=1.0_dp, &
                  & psi=50.0_dp, hardness_coeff=0.2_dp)
               case default; p = contact_params(model=model_epgw, mu=mus(i), sigma=1.0_dp, &
                  & psi=1.0_dp, hardness_coeff=0.95_dp)
               end select
               call solve_checked(error, p, method_auto, deltas(j), auto, stat)
               if (allocated(error)) return
               call check(error, stat == 0, "AUTO failed at "//where(p, deltas(j), method_auto))
               if (allocated(error)) return
               do method = method_newton, method_picard
                  ! Picard on deep classic GW is the known failure (test_picard_fails).
                  if (method == method_picard .and. k == 1 .and. deltas(j) > 1.0e3_dp) cycle
                  call solve_checked(error, p, method, deltas(j), res, stat)
                  if (allocated(error)) return
                  if (stat /= 0 .or. auto%force == 0.0_dp) cycle
                  call check(error, res%force, auto%force, "force differs from AUTO at " &
                     & //where(p, deltas(j), method), rel=.true., thr=2.0e-6_dp)
                  if (allocated(error)) return
               end do
            end do
         end do
      end do
   end subroutine test_corners

   !> Every 6th row of test/data/sphere_reference.csv (independent solver, its error
   !> <= 6e-11) for every method: OK results must be within rel_tol = 1e-6 (the promise of
   !> the default options); AUTO must be OK.
   subroutine test_references(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), parameter :: path = "test/data/sphere_reference.csv"
      character(len=512) :: line
      character(len=8) :: model, set
      real(dp) :: delta, mu, psi, hardness, rho, force
      type(contact_params) :: p
      type(solve_result) :: res
      integer :: unit, ios, row, method, stat
      open (newunit=unit, file=path, status="old", action="read", iostat=ios)
      if (ios /= 0) then
         call test_failed(error, "cannot open "//path//" (run the tests from the project root)")
         return
      end if
      row = 0
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:1) == "#" .or. line(1:6) == "model,") cycle
         row = row + 1
         if (mod(row, 6) /= 1) cycle
         read (line, *) model, set, delta, mu, psi, hardness, rho, force
         p = contact_params(mu=mu, sigma=1.0_dp, psi=psi, plastic_ratio=rho)
         select case (trim(model))
         case ("GW"); p%model = model_gw
         case ("EGW"); p%model = model_egw
         case default; p%model = model_epgw; p%hardness_coeff = hardness
         end select
         do method = method_auto, method_picard
            call solve_checked(error, p, method, delta, res, stat)
            if (allocated(error)) exit
            if (method == method_auto) call check(error, stat == 0, "AUTO failed at " &
               & //where(p, delta, method))
            if (allocated(error)) exit
            if (stat /= 0) cycle
            call check(error, res%force, force, "force vs reference at " &
               & //where(p, delta, method), &
               & rel=.true., thr=1.0e-6_dp)
            if (allocated(error)) exit
         end do
         if (allocated(error)) exit
      end do
      close (unit)
   end subroutine test_references

   !> The promise holds at other tolerances too: every 26th reference row (GW, E-GW, EP-GW
   !> from delta/sigma = -6 to 1e4) at rel_tol = 1e-3 and 1e-9 must be within rel_tol
   !> (over all 208 rows the worst error is 0.71 rel_tol at 1e-8, 0.65 at 1e-9, 5e-4 at
   !> 1e-3; the references' own error, <= 6e-11, is 0.06 of 1e-9).
   subroutine test_tolerances(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), parameter :: path = "test/data/sphere_reference.csv"
      real(dp), parameter :: tols(2) = [1.0e-3_dp, 1.0e-9_dp]
      character(len=512) :: line
      character(len=8) :: model, set
      real(dp) :: delta, mu, psi, hardness, rho, force
      type(contact_params) :: p
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      integer :: unit, ios, row, k
      open (newunit=unit, file=path, status="old", action="read", iostat=ios)
      if (ios /= 0) then
         call test_failed(error, "cannot open "//path//" (run the tests from the project root)")
         return
      end if
      row = 0
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:1) == "#" .or. line(1:6) == "model,") cycle
         row = row + 1
         if (mod(row, 26) /= 5) cycle
         read (line, *) model, set, delta, mu, psi, hardness, rho, force
         p = contact_params(mu=mu, sigma=1.0_dp, psi=psi, plastic_ratio=rho)
         select case (trim(model))
         case ("GW"); p%model = model_gw
         case ("EGW"); p%model = model_egw
         case default; p%model = model_epgw; p%hardness_coeff = hardness
         end select
         do k = 1, size(tols)
            call solve_contact(p, solver_options(rel_tol=tols(k), n_threads=1), delta, res, err)
            if (allocated(err)) then
               call test_failed(error, "AUTO failed at "//where(p, delta, method_auto)//": " &
                  & //err%message)
               exit
            end if
            call check(error, res%force, force, "force vs reference at "// &
               & where(p, delta, method_auto), rel=.true., thr=tols(k))
            if (allocated(error)) exit
         end do
         if (allocated(error)) exit
      end do
      close (unit)
   end subroutine test_tolerances

   !> Classic GW at delta/sigma = 1e5, mu = 10: the spectral radius of H |dp/dw| is far
   !> above 1 (doc/theory.md §5), so damped Picard must report egw_not_converged (never a wrong
   !> OK), while AUTO (Newton with line search and continuation) converges.
   subroutine test_picard_fails(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: p
      type(solve_result) :: res
      integer :: stat
      p = contact_params(model=model_gw, mu=10.0_dp, sigma=1.0_dp)
      call solve_checked(error, p, method_picard, 1.0e5_dp, res, stat)
      if (allocated(error)) return
      call check(error, stat, egw_not_converged, "Picard on stiff classic GW must fail")
      if (allocated(error)) return
      call solve_checked(error, p, method_auto, 1.0e5_dp, res, stat)
      if (allocated(error)) return
      call check(error, stat, 0, "AUTO on stiff classic GW must converge")
   end subroutine test_picard_fails

   !> "model mu delta/sigma psi K method" for messages.
   function where(p, delta, method) result(s)
      type(contact_params), intent(in) :: p
      real(dp), intent(in) :: delta
      integer, intent(in) :: method
      character(len=:), allocatable :: s
      character(len=160) :: buf
      write (buf, '("model ",i0,", mu ",es9.2,", delta/sigma ",es9.2,", psi ",f4.1,", K ",f4.2, &
         & ", method ",i0)') p%model, p%mu, delta, p%psi, p%hardness_coeff, method
      s = trim(buf)
   end function where

end module test_stability
