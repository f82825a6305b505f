!> The CPU time (one thread, cpu_time) of the five Hertz + cap tables of egw-bench --cap
!> (R = 1 mm, E* = 100 GPa, p_y = 1 GPa; 1e-3, 3e-4, 1e-4 to 10 delta_y, 3e-4 and 1e-4 to
!> 35 delta_y) and their grids: compare two libraries alternated in one script
!> (doc/stability.md "Stop 49 (capl15)"). Build as tools/bench/cap_local_error.f90.
program cap_build_cpu
   use egw, only: dp, contact_params, model_hertz, solver_options, egw_error, hysteresis_table, build_hysteresis
   implicit none
   real(dp), parameter :: tols(5) = [1e-3_dp, 3e-4_dp, 1e-4_dp, 3e-4_dp, 1e-4_dp], rng(5) = [10._dp, 10._dp, 10._dp, 35._dp, 35._dp]
   type(contact_params) :: p
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   real(dp) :: dy, c0, c1, tot
   integer :: i
   p = contact_params(model=model_hertz, radius=1.0e-3_dp, modulus=1.0e11_dp, flow_pressure=1.0e9_dp)
   dy = (acos(-1.0_dp)*1e9_dp/(2*1e11_dp))**2*1e-3_dp
   tot = 0
   do i = 1, 5
      call cpu_time(c0)
      call build_hysteresis(p, solver_options(n_threads=1), 0.0_dp, rng(i)*dy, tols(i), t, err)
      call cpu_time(c1)
      tot = tot + c1 - c0
      write (*, '(es8.1,f5.1,f7.2,a,i0,a,i0)', advance='no') tols(i), rng(i), c1 - c0, " s ", size(t%m), "x", size(t%s)
      write (*, '(a)', advance='no') " | "
   end do
   print '(a,f7.2)', " total cpu ", tot
end program cap_build_cpu
