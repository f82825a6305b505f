!> The suite rough_cap_hysteresis's table (test/test_rough_cap_hysteresis.f90's get_table:
!> E-GW + cap, R 1 mm, E* 1e11, p_y 1 GPa, sigma = delta_y/100, mu 4, -3 sigma to 10
!> delta_y at 1e-3), one thread: its n_m, n_s, max_error and build CPU (doc/benchmarks.md
!> "Stop 66: goal33": test_max_error's cost grows with n_m).
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis_lengths.mod' | head -1))
!>   gfortran -O2 -fopenmp -ffree-line-length-none -I$B tools/bench/goal33_suite_table.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/goal33_suite_table
!>   OMP_NUM_THREADS=1 /tmp/goal33_suite_table
program suite_table
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_egw
   use egw_rough_sphere, only: solver_options
   use egw_hysteresis, only: hysteresis_table, build_hysteresis, first_yield
   implicit none
   real(dp), parameter :: pi = acos(-1.0_dp), radius = 1.0e-3_dp, modulus = 1.0e11_dp, &
      & py = 1.0e9_dp
   real(dp), parameter :: sigma = 1.0e-2_dp*(pi*py/(2*modulus))**2*radius
   type(contact_params) :: p
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   real(dp) :: c0, c1
   p = contact_params(model=model_egw, radius=radius, modulus=modulus, sigma=sigma, &
      & mu=4.0_dp, flow_pressure=py)
   call cpu_time(c0)
   call build_hysteresis(p, solver_options(n_threads=1), -3*sigma, 10*first_yield(p), &
      & 1.0e-3_dp, t, err)
   call cpu_time(c1)
   if (allocated(err)) print '(a)', err%message
   print '(a,i0,a,i0,a,es10.3,a,f8.2)', "n_m ", size(t%m), " n_s ", size(t%s), &
      & " max_error ", t%max_error, " cpu ", c1 - c0
end program suite_table
