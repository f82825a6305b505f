!> CPU of README's E-GW + cap loading solves (mu 4, sigma = delta_y/100, p_y = 0.01 E*) with
!> and without the moved-mesh stiffness (solve_contact's stiffness=.false.), at delta = 0,
!> 5, ..., 600 sigma, one thread; prints the points where the default solve takes > 0.05 s
!> and the totals (doc/benchmarks.md "Stop 61: build27").
!> Build against the fpm objects (paths as fpm names them):
!>   gfortran -O2 -fopenmp -I build/gfortran_<mods> tools/bench/capped_loading_stiffness_cost.f90 \
!>     build/gfortran_<lib>/egw/libegw.a -lfftw3_omp -lfftw3 -llapack -lblas -lmvec -lm
!> usage: EGW_CACHE_DIR=off ./a.out REL_TOL
program capped_loading_stiffness_cost
   use egw
   implicit none
   type(contact_params) :: p
   type(solver_options) :: o
   type(solve_result) :: r
   type(egw_error), allocatable :: e
   real(dp) :: t0, t1, t2, d, with_k, without_k
   integer :: i
   character(len=32) :: arg
   p = contact_params(model=model_egw, radius=810569.469138702_dp/2, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   o%n_threads = 1
   call get_command_argument(1, arg)
   read (arg, *) o%rel_tol
   with_k = 0
   without_k = 0
   do i = 0, 120
      d = 5.0_dp*i
      call cpu_time(t0)
      call solve_contact(p, o, d, r, e)
      call cpu_time(t1)
      call solve_contact(p, o, d, r, e, stiffness=.false.)
      call cpu_time(t2)
      with_k = with_k + t1 - t0
      without_k = without_k + t2 - t1
      if (t1 - t0 > 0.05_dp) print '(f12.5, 2f9.4)', d, t1 - t0, t2 - t1
   end do
   print '(a, 2f9.3)', 'total (default, stiffness=.false.)', with_k, without_k
end program capped_loading_stiffness_cost
