!> Stop 58 (edge24): the rough + cap loading force's error against its estimate. E-GW + cap,
!> sigma = 1, R = 1/RATIO, E* = 1, p_y = 2/pi (delta_y = R, sigma/delta_y = RATIO), mu 4;
!> X in delta_y. One row per X and rel_tol: ratio, x, rel_tol, force, est_rel_err, CPU s.
!> The rows at the smallest rel_tol are the references of the others (by hand or
!> tools/bench/rough_cap_force_error.py).
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/rough_cap_force_error.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/kf
!>   OMP_NUM_THREADS=1 EGW_CACHE_DIR=off /tmp/kf RATIO "RTOL1 RTOL2 ..." X...
program rough_cap_force_error
   use egw_all
   implicit none
   type(contact_params) :: p
   type(egw_error), allocatable :: err
   type(solve_result) :: r
   real(dp) :: ratio, x, t0, t1, tols(8)
   character(len=200) :: arg
   integer :: i, j, nt, ios
   call get_command_argument(1, arg); read (arg, *) ratio
   call get_command_argument(2, arg)
   tols = 0
   read (arg, *, iostat=ios) tols
   nt = count(tols > 0)
   p = contact_params(model=model_egw, radius=1.0_dp/ratio, modulus=1.0_dp, sigma=1.0_dp, &
      & mu=4.0_dp, flow_pressure=2/acos(-1.0_dp))
   do i = 3, command_argument_count()
      call get_command_argument(i, arg); read (arg, *) x
      do j = 1, nt
         call cpu_time(t0)
         call solve_contact(p, solver_options(rel_tol=tols(j), n_threads=1), x*p%radius, r, err)
         call cpu_time(t1)
         if (allocated(err)) then
            print '(es10.2,f6.1,es10.2,a,a)', ratio, x, tols(j), ' error: ', err%message
            deallocate (err)
            cycle
         end if
         print '(es10.2,",",f6.1,",",es10.2,",",es24.16,",",es10.2,",",f8.3)', ratio, x, &
            & tols(j), r%force, r%est_rel_err, t1 - t0
      end do
   end do
end program rough_cap_force_error
