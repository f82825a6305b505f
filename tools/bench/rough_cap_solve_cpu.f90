!> Stop 53 (stiff19): the CPU time (cpu_time, one thread) of rough + cap loading solves,
!> E-GW + cap, R = 1/RATIO, E* = sigma = 1, p_y = 2/pi (delta_y = R, sigma/delta_y =
!> RATIO), mu 4, at 1.5, 3, 6, 10, 20 delta_y, each solved REPS times at rel_tol RTOL;
!> prints the total and the stiffnesses' sum (to see two libraries solve the same).
!> Compare two libraries alternated in one script:
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/rough_cap_solve_cpu.f90 LIBEGW.a -llapack \
!>      -lblas -o /tmp/rough_cap_solve_cpu
!>   OMP_NUM_THREADS=1 /tmp/rough_cap_solve_cpu RATIO RTOL REPS     (e.g. 1e-4 1e-6 3)
program rough_cap_solve_cpu
   use egw_all
   implicit none
   real(dp), parameter :: xs(5) = [1.5_dp, 3.0_dp, 6.0_dp, 10.0_dp, 20.0_dp]
   type(contact_params) :: p
   type(egw_error), allocatable :: err
   type(solve_result) :: r
   real(dp) :: ratio, rtol, c0, c1, ksum
   integer :: i, k, reps
   character(len=32) :: arg
   call get_command_argument(1, arg); read (arg, *) ratio
   call get_command_argument(2, arg); read (arg, *) rtol
   call get_command_argument(3, arg); read (arg, *) reps
   p = contact_params(model=model_egw, radius=1.0_dp/ratio, modulus=1.0_dp, sigma=1.0_dp, &
      & mu=4.0_dp, flow_pressure=2/acos(-1.0_dp))
   ksum = 0
   call cpu_time(c0)
   do k = 1, reps
      do i = 1, size(xs)
         call solve_contact(p, solver_options(rel_tol=rtol, n_threads=1), xs(i)*p%radius, r, err)
         if (allocated(err)) then
            print '(a)', err%message
            stop 1
         end if
         if (k == 1) ksum = ksum + r%stiffness/p%radius
      end do
   end do
   call cpu_time(c1)
   print '(a,es8.1,a,es8.1,a,f9.4,a,es22.14)', 'ratio ', ratio, ' rel_tol ', rtol, &
      & ' cpu/solve ', (c1 - c0)/(reps*size(xs)), ' s  sum K/R ', ksum
end program rough_cap_solve_cpu
