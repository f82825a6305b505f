!> References for the shift route of rough + cap unloading near the residual overlap
!> (issue 32; doc/theory.md section 12 "Small sigma: the shift"; test_rough_cap's
!> test_shift_residual). E-GW, mu 4, R = E* = 1, p_y = 2/pi (delta_y = 1), from
!> delta_max = 2 delta_y. For each sigma_j/delta_y of 1e-5 .. 2e-4 the rough model's own
!> history (load_history at rel_tol, default 1e-8) and its discrete unloading solves at
!> 0.15 .. 0.1441 delta_max at rel_tol 1e-5, 1e-6 and 1e-7 (not the small-sigma route:
!> direct solves; a failure is printed as such), and for each converged one the shift D_j
!> with P_cap(delta + D_j) = P_j, P_cap the smooth cap's unloading (cap_unload, 100 and
!> 400 rings). tools/reference/shift_reference.py fits D_j/x_j, x_j = (sigma_j/sigma)**(2/3),
!> in x_j and evaluates it at the target sigma (x = 1); tools/reference/cap_near_residual.py
!> --at gives the independent smooth cap at delta + D. The smooth cap's own rows (100, 200,
!> 400 rings) come first.
!>
!> With `route [SIGMA [REL_TOL]]`: the solves as a user calls them at sigma/delta_y = SIGMA
!> (1e-6): history at rel_tol 1e-7, unloading at REL_TOL (1e-5) at 0.2 .. 0.144 delta_max in
!> that order: P/P_y, est_rel_err, CPU seconds, stiffness, or the refusal.
!>
!>     OMP_NUM_THREADS=1 fpm run --profile release --example small-sigma-shift \
!>        [-- [HISTORY_TOL] | route [SIGMA [REL_TOL]]] > shift.csv
!>     python tools/reference/shift_reference.py shift.csv
program small_sigma_shift
   use egw, only: dp, contact_params, model_egw, solver_options, solve_result, &
      & loading_history, load_history, solve_unload, egw_error
   use egw_cap_sphere, only: cap_options, cap_result, cap_history, cap_load, cap_unload
   implicit none
   real(dp), parameter :: pi = acos(-1.0_dp)
   real(dp), parameter :: sigmas(9) = [1.0e-5_dp, 2.0e-5_dp, 3.0e-5_dp, 4.0e-5_dp, &
      & 5.0e-5_dp, 7.0e-5_dp, 1.0e-4_dp, 1.5e-4_dp, 2.0e-4_dp]
   real(dp), parameter :: fractions(6) = [0.15_dp, 0.145_dp, 0.1446_dp, 0.1443_dp, &
      & 0.1442_dp, 0.1441_dp]
   real(dp), parameter :: unload_tols(3) = [1.0e-5_dp, 1.0e-6_dp, 1.0e-7_dp]
   integer, parameter :: rings(3) = [100, 200, 400]
   real(dp), parameter :: delta_max = 2.0_dp
   type(cap_history) :: caps(3)
   type(cap_result) :: cap
   type(egw_error), allocatable :: err
   type(contact_params) :: p
   type(loading_history) :: h
   type(solve_result) :: res
   real(dp) :: py, history_tol
   integer :: i, j, k
   character(len=16) :: arg
   py = 2.0_dp/pi
   history_tol = 1.0e-8_dp
   call get_command_argument(1, arg)
   if (arg == "route") then
      call route()
      stop
   end if
   if (len_trim(arg) > 0) read (arg, *) history_tol
   print '(a)', "kind,sigma,fraction,rel_tol,force,est_rel_err,shift_100,shift_400"
   do j = 1, size(rings)
      call cap_load(1.0_dp, 1.0_dp, py, delta_max, cap_options(n_rings=rings(j), &
         & n_levels=2), caps(j), cap, err, "delta_max")
      if (allocated(err)) error stop "the smooth cap's loading failed"
      print '("residual,",i0,",0,0,",es22.14)', rings(j), caps(j)%residual*caps(j)%delta_y
      do i = 1, size(fractions)
         call cap_unload(caps(j), fractions(i)*delta_max, cap, err)
         print '("cap,",i0,",",f7.4,",0,",es22.14,",",es10.3)', rings(j), fractions(i), &
            & cap%force, cap%force_error
      end do
   end do
   do k = 1, size(sigmas)
      p = contact_params(model=model_egw, radius=1.0_dp, modulus=1.0_dp, sigma=sigmas(k), &
         & mu=4.0_dp, flow_pressure=py)
      call load_history(p, solver_options(rel_tol=history_tol), delta_max, h, res, err)
      if (allocated(err)) then
         print '("history,",es9.2,",failed,",a)', sigmas(k), err%message
         deallocate (err)
         cycle
      end if
      do j = 1, size(unload_tols)
         h%options%rel_tol = unload_tols(j)
         do i = 1, size(fractions)
            call solve_unload(h, fractions(i)*delta_max, res, err)
            if (allocated(err)) then
               print '("failed,",es9.2,",",f7.4,",",es8.1)', sigmas(k), fractions(i), &
                  & unload_tols(j)
               deallocate (err)
               cycle
            end if
            print '("rough,",es9.2,",",f7.4,",",es8.1,",",es22.14,",",es10.3,",",es22.14,' &
               & //'",",es22.14)', sigmas(k), fractions(i), unload_tols(j), res%force, &
               & res%est_rel_err, shift_of(caps(1), res%force, fractions(i)*delta_max), &
               & shift_of(caps(3), res%force, fractions(i)*delta_max)
         end do
      end do
   end do
contains
   !> The route as a user calls it (see the header).
   subroutine route()
      real(dp), parameter :: at(11) = [0.2_dp, 0.18_dp, 0.16_dp, 0.15_dp, 0.145_dp, &
         & 0.1446_dp, 0.1443_dp, 0.1442_dp, 0.1441_dp, 0.14408_dp, 0.144_dp]
      real(dp) :: ratio, rel_tol, t0, t1
      character(len=16) :: value
      ratio = 1.0e-6_dp
      rel_tol = 1.0e-5_dp
      call get_command_argument(2, value)
      if (len_trim(value) > 0) read (value, *) ratio
      call get_command_argument(3, value)
      if (len_trim(value) > 0) read (value, *) rel_tol
      p = contact_params(model=model_egw, radius=1.0_dp, modulus=1.0_dp, sigma=ratio, &
         & mu=4.0_dp, flow_pressure=py)
      call cpu_time(t0)
      call load_history(p, solver_options(rel_tol=1.0e-7_dp), delta_max, h, res, err)
      call cpu_time(t1)
      if (allocated(err)) then
         print '(a)', "history: "//err%message
         return
      end if
      print '("# history at sigma/delta_y ",es9.2,": ",f7.2," s")', ratio, t1 - t0
      h%options%rel_tol = rel_tol
      do i = 1, size(at)
         call cpu_time(t0)
         call solve_unload(h, at(i)*delta_max, res, err)
         call cpu_time(t1)
         if (allocated(err)) then
            print '("route,",f8.5,",refused,",f7.2,",",a)', at(i), t1 - t0, err%message
            deallocate (err)
         else
            print '("route,",f8.5,",",es22.14,",",es10.3,",",f7.2,",",es14.6)', at(i), &
               & res%force/(4.0_dp/3.0_dp), res%est_rel_err, t1 - t0, res%stiffness
         end if
      end do
   end subroutine route

   !> D with cap_unload(c, delta + D) = force (bisection and Newton; -huge where force is
   !> not in (0, P_cap(delta_max))).
   real(dp) function shift_of(c, force, delta) result(shift)
      type(cap_history), intent(in) :: c
      real(dp), intent(in) :: force, delta
      type(cap_result) :: r
      type(egw_error), allocatable :: e
      real(dp) :: lo, hi, y
      integer :: it
      shift = -huge(1.0_dp)
      if (.not. force > 0.0_dp) return
      lo = c%residual*c%delta_y
      hi = delta_max
      y = delta
      do it = 1, 200
         call cap_unload(c, y, r, e)
         if (r%force > force) then
            hi = y
         else
            lo = y
         end if
         if (abs(r%force - force) <= 1.0e-15_dp*force .or. hi - lo < 1.0e-16_dp) exit
         if (r%stiffness > 0.0_dp) y = y - (r%force - force)/r%stiffness
         if (.not. (y > lo .and. y < hi)) y = 0.5_dp*(lo + hi)
      end do
      shift = y - delta
   end function shift_of
end program small_sigma_shift
