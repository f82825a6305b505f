!> Stability map of the rough-sphere solver (issue 5 item 3): every method (AUTO, NEWTON,
!> PICARD) on a sweep over mu, delta/sigma, psi and K (classic GW, E-GW, EP-GW), with the
!> status, iterations and the relative error of the force. The error is measured against
!> the independent reference test/data/sphere_reference.csv where a point coincides with
!> one of its rows, else against a tight AUTO solve (rel_tol = 1e-9 on a fixed mesh of 300
!> nodes, used where its own error estimate is <= 1e-8). Every point is also
!> solved in physical units with sigma/R = 1e-9, R = 1e3, E = 2e11 to show that the scaled
!> force P/(E sqrt(R) sigma**1.5) does not depend on them.
!>
!> Usage: fpm run --profile release --example stability-map [-- out/stability_map.csv]
!> (points in parallel with OpenMP, one thread per solve).
program stability_map
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw, only: dp, contact_params, solver_options, solve_result, solve_contact, &
      & egw_error, egw_ok, model_gw, model_egw, model_epgw, method_auto, method_newton, &
      & method_picard
   implicit none

   real(dp), parameter :: mus(*) = [0.01_dp, 0.1_dp, 1.0_dp, 10.0_dp, 100.0_dp, 1000.0_dp]
   real(dp), parameter :: deltas(*) = [-10.0_dp, -6.0_dp, -3.0_dp, -1.0_dp, 0.0_dp, &
      & 1.0_dp, 3.0_dp, 10.0_dp, 100.0_dp, 1.0e3_dp, 1.0e4_dp, 1.0e5_dp]
   real(dp), parameter :: psis(*) = [1.0_dp, 10.0_dp, 50.0_dp]
   real(dp), parameter :: hardnesses(*) = [0.2_dp, 0.6_dp, 0.95_dp]
   character(len=*), parameter :: method_names(0:2) = ["AUTO  ", "NEWTON", "PICARD"]
   character(len=*), parameter :: model_names(1:3) = ["GW  ", "EGW ", "EPGW"]

   type :: sweep_point
      integer :: model = model_egw
      real(dp) :: mu = 1.0_dp, delta = 0.0_dp, psi = 0.0_dp, hardness = 0.6_dp
   end type sweep_point

   type(sweep_point), allocatable :: points(:)
   character(len=:), allocatable :: path
   character(len=256) :: arg
   character(len=200), allocatable :: lines(:, :)
   integer :: n, i, j, k, unit, n_fail(0:2), n_bad(0:2)
   real(dp) :: worst_scale

   path = "out/stability_map.csv"
   if (command_argument_count() > 0) then
      call get_command_argument(1, arg)
      path = trim(arg)
   end if

   ! The sweep: classic GW and E-GW (psi = 0), EP-GW for every psi and K.
   allocate (points(0))
   do i = 1, size(mus)
      do j = 1, size(deltas)
         points = [points, sweep_point(model_gw, mus(i), deltas(j), 0.0_dp, 0.6_dp), &
            & sweep_point(model_egw, mus(i), deltas(j), 0.0_dp, 0.6_dp)]
         do k = 1, size(psis)*size(hardnesses)
            points = [points, sweep_point(model_epgw, mus(i), deltas(j), &
               & psis((k - 1)/size(hardnesses) + 1), hardnesses(mod(k - 1, size(hardnesses)) + 1))]
         end do
      end do
   end do
   n = size(points)
   allocate (lines(0:2, n))
   n_fail = 0
   n_bad = 0
   worst_scale = 0.0_dp

   !$omp parallel do schedule(dynamic, 1) reduction(+:n_fail, n_bad) reduction(max:worst_scale)
   do i = 1, n
      call sweep(points(i), lines(:, i), n_fail, n_bad, worst_scale)
   end do
   !$omp end parallel do

   call execute_command_line("mkdir -p out")
   open (newunit=unit, file=path, status="replace", action="write")
   write (unit, '(a)') "# egw stability map: fpm run --profile release --example stability-map"
   write (unit, '(a)') "# status 0 = OK, 3 = NOT_CONVERGED; error = |P - P_ref|/P_ref with "// &
      & "P_ref from test/data/sphere_reference.csv (ref = independent) or an AUTO solve at "// &
      & "rel_tol = 1e-9, n_radial = 300 (ref = tight); -1 = no reference; "// &
      & "scale_dev = relative difference of the "// &
      & "scaled force at sigma/R = 1e-9, R = 1e3, E = 2e11 (AUTO rows only)"
   write (unit, '(a)') "model,method,mu,delta_over_sigma,psi,K,status,iterations,force,"// &
      & "est_rel_err,error,ref,scale_dev"
   do i = 1, n
      do j = 0, 2
         write (unit, '(a)') trim(lines(j, i))
      end do
   end do
   close (unit)
   print '(a,i0,a,a)', "points: ", n, "  written to ", path
   do j = 0, 2
      print '(a8,a,i4,a,i4)', method_names(j), ": not converged ", n_fail(j), &
         & ",  OK with error > rel_tol: ", n_bad(j)
   end do
   print '(a,es9.2)', "max scale_dev (sigma/R = 1e-9, R = 1e3, E = 2e11): ", worst_scale

contains

   !> All methods at one point; lines(method) receives the CSV rows.
   subroutine sweep(pt, lines, n_fail, n_bad, worst_scale)
      type(sweep_point), intent(in) :: pt
      character(len=*), intent(out) :: lines(0:2)
      integer, intent(inout) :: n_fail(0:2), n_bad(0:2)
      real(dp), intent(inout) :: worst_scale
      type(contact_params) :: p, phys
      type(solver_options) :: opts
      type(solve_result) :: res, tight, res_phys
      type(egw_error), allocatable :: err
      real(dp) :: ref, error, scale_dev, sigma
      character(len=11) :: ref_kind
      integer :: method, stat

      p = contact_params(model=pt%model, mu=pt%mu, sigma=1.0_dp, psi=pt%psi, &
         & hardness_coeff=pt%hardness)
      ref_kind = "independent"
      if (.not. independent_reference(pt, ref)) then
         ref_kind = "tight"
         ref = -1.0_dp
         ! On its own fine mesh (~300 nodes, 4-6 times the default's): an adaptive solve at
         ! 1e-9 would often stop on the default's meshes and compare a solve with itself.
         call solve_contact(p, solver_options(rel_tol=1.0e-9_dp, n_radial=300, n_threads=1), &
            & pt%delta, tight, err)
         if (.not. allocated(err)) then
            if (tight%est_rel_err <= 1.0e-8_dp .or. tight%force == 0.0_dp) ref = tight%force
         end if
         if (ref < 0.0_dp) ref_kind = "none"
      end if
      do method = method_auto, method_picard
         opts = solver_options(method=method, n_threads=1)
         call solve_contact(p, opts, pt%delta, res, err)
         stat = egw_ok
         if (allocated(err)) stat = err%stat
         error = -1.0_dp
         if (stat == egw_ok .and. ref > 0.0_dp) error = abs(res%force - ref)/ref
         if (stat == egw_ok .and. ref == 0.0_dp .and. res%force == 0.0_dp) error = 0.0_dp
         if (stat /= egw_ok) n_fail(method) = n_fail(method) + 1
         if (stat == egw_ok .and. (error > opts%rel_tol .or. .not. ieee_is_finite(res%force))) &
            & n_bad(method) = n_bad(method) + 1
         scale_dev = -1.0_dp
         if (method == method_auto .and. stat == egw_ok) then
            ! sigma/R = 1e-9 with R = 1e3 and E = 2e11: sigma = 1e-6.
            phys = p
            phys%radius = 1.0e3_dp
            phys%modulus = 2.0e11_dp
            sigma = 1.0e-9_dp*phys%radius
            phys%sigma = sigma
            call solve_contact(phys, opts, pt%delta*sigma, res_phys, err)
            if (.not. allocated(err) .and. res%force > 0.0_dp) then
               scale_dev = abs(res_phys%force/(phys%modulus*sqrt(phys%radius)*sigma**1.5_dp) &
                  & - res%force)/res%force
               worst_scale = max(worst_scale, scale_dev)
            end if
         end if
         ! A failed solve returns no result: iterations -1, force 0.
         if (stat /= egw_ok) res%iterations = -1
         write (lines(method), '(a,",",a,",",es10.3,",",es11.4,",",f5.1,",",f5.2,",",i0,",",i0, &
            & ",",es24.16,",",es10.3,",",es10.3,",",a,",",es10.3)') &
            & trim(model_names(pt%model)), trim(method_names(method)), pt%mu, pt%delta, &
            & pt%psi, pt%hardness, stat, res%iterations, res%force, res%est_rel_err, error, &
            & trim(ref_kind), scale_dev
      end do
   end subroutine sweep

   !> The force of test/data/sphere_reference.csv at this point (rho_p = 54), if any.
   logical function independent_reference(pt, force) result(found)
      type(sweep_point), intent(in) :: pt
      real(dp), intent(out) :: force
      character(len=512) :: line
      character(len=8) :: model, set
      real(dp) :: delta, mu, psi, hardness, rho, f
      integer :: unit, ios
      found = .false.
      force = -1.0_dp
      open (newunit=unit, file="test/data/sphere_reference.csv", status="old", &
         & action="read", iostat=ios)
      if (ios /= 0) return
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:1) == "#" .or. line(1:6) == "model,") cycle
         read (line, *) model, set, delta, mu, psi, hardness, rho, f
         if (trim(model) /= trim(model_names(pt%model)) .or. delta /= pt%delta .or. &
            & mu /= pt%mu .or. rho /= 54.0_dp) cycle
         if (pt%model == model_epgw .and. (psi /= pt%psi .or. hardness /= pt%hardness)) cycle
         found = .true.
         force = f
         exit
      end do
      close (unit)
   end function independent_reference

end program stability_map
