! Builds one EP-GW hysteresis table (mu 4, sigma 1, R 1, E* 1) and prints its grid and
! build time: the delta_max node counts of doc/benchmarks.md "Stop 46 (local12)".
! Arguments: psi delta_min delta_max rel_tol. Build as tools/bench/log_energy_ratio_check.f90.
! With tools/bench/local12_stencil_variants.patch applied to the library (an experiment,
! not the library's code), EGW_L12_VARIANT selects the delta_max check's representation:
! 0 local11's (four-point Lagrange in h), 6 six-point Lagrange (and hysteresis_eval on
! six points), 7 the six-point check with the four-point evaluation, 1 / 11 h over the
! curve's h at s = 1/2 / 5/8, 16 both 1 and 6, 21 / 23 the edge map of each curve's xi
! where h = 1 / 3 instead of L, 26 both 21 and 6, 8 eight-point Lagrange (check only);
! EGW_L12_COORD=3 / 4: m^(1/3) / m^(1/4) above the m = 0 node instead of sqrt(m) (build
! and evaluation); EGW_L12_DEBUG=1 prints each failing
! midpoint (pass, interval, s, h of the midpoint curve, the stencil's h, weight, error).
program hysteresis_nodes
   use egw_kinds, only: dp
   use egw_params, only: contact_params, model_epgw
   use egw_rough_sphere, only: solver_options
   use egw_status, only: egw_error
   use egw_hysteresis, only: hysteresis_table, build_hysteresis
   implicit none
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   character(len=32) :: arg
   real(dp) :: rel_tol, dmin, dmax, psi
   integer(8) :: c0, c1, rate
   call get_command_argument(1, arg); read (arg, *) psi
   call get_command_argument(2, arg); read (arg, *) dmin
   call get_command_argument(3, arg); read (arg, *) dmax
   call get_command_argument(4, arg); read (arg, *) rel_tol
   call system_clock(c0, rate)
   call build_hysteresis(contact_params(model=model_epgw, radius=1.0_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, psi=psi), solver_options(), dmin, dmax, rel_tol, t, err)
   call system_clock(c1)
   if (allocated(err)) then
      print '(a)', 'build failed: '//err%message
      stop
   end if
   print '(a, i0, a, i0, a, es10.3, a, f8.2, a)', 'grid ', size(t%m), ' x ', size(t%s), &
      & ', max error at checks ', t%max_error, ', ', real(c1 - c0, dp)/real(rate, dp), ' s wall'
   ! where the delta_max nodes are (in units of sigma)
   print '(a, 5(1x, i0))', 'delta_max nodes in (-inf, 0), [0, 1), [1, 5), [5, 15), [15, inf):', &
      & count(t%m < 0), count(t%m >= 0 .and. t%m < 1), count(t%m >= 1 .and. t%m < 5), &
      & count(t%m >= 5 .and. t%m < 15), count(t%m >= 15)
end program hysteresis_nodes
