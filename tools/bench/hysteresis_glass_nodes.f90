! The delta_max x s grid and build time of test hysteresis's glass pair (issue 22: R 0.5 mm,
! E* of glass, sigma 1 um, mu 4, psi 2, [-3, 30] um) at the rel_tol given as argument:
! the growth of the log-ratio tables' delta_max grid per decade of rel_tol, which
! tolerance_probe's m_growth_per_decade bounds. Build as tools/bench/hysteresis_nodes.f90.
program hysteresis_glass_nodes
   use egw_kinds, only: dp
   use egw_params, only: contact_params, model_epgw
   use egw_rough_sphere, only: solver_options
   use egw_status, only: egw_error
   use egw_hysteresis, only: hysteresis_table, build_hysteresis
   implicit none
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   character(len=32) :: arg
   real(dp) :: rel_tol
   integer(8) :: c0, c1, rate
   call get_command_argument(1, arg)
   read (arg, *) rel_tol
   call system_clock(c0, rate)
   call build_hysteresis(contact_params(model=model_epgw, radius=0.5e-3_dp, &
      & modulus=70.0e9_dp/(2*(1 - 0.22_dp**2)), sigma=1.0e-6_dp, mu=4.0_dp, psi=2.0_dp, &
      & hardness_coeff=0.6_dp, plastic_ratio=54.0_dp), solver_options(), -3.0e-6_dp, &
      & 3.0e-5_dp, rel_tol, t, err)
   call system_clock(c1)
   if (allocated(err)) then
      print '(a)', 'build failed: '//err%message
      stop
   end if
   print '(a, es8.1, a, i0, a, i0, a, es10.3, a, f8.2, a)', 'glass ', rel_tol, ': grid ', &
      & size(t%m), ' x ', size(t%s), ', max error at checks ', t%max_error, ', ', &
      & real(c1 - c0, dp)/real(rate, dp), ' s wall'
end program hysteresis_glass_nodes
