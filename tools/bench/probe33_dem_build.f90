!> cap_hysteresis's C DEM loop tables alone (test/cap_dem_checks.c: R 1, E* 1, p_y 2/pi,
!> sigma 0.1, mu 4, rel_tol 3e-4, -3 sigma to 1.2 DM; E-GW, then EP-GW psi 1): grid or error
!> (doc/benchmarks.md "Stop 67: probe33").   dem_build DM
program dem_build
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_egw, model_epgw
   use egw_rough_sphere, only: solver_options
   use egw_hysteresis, only: hysteresis_table, build_hysteresis
   implicit none
   type(contact_params) :: p
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   real(dp) :: dm
   integer :: i
   character(len=32) :: arg
   call get_command_argument(1, arg); read (arg, *) dm
   do i = 1, 2
      p = contact_params(model=merge(model_egw, model_epgw, i == 1), radius=1.0_dp, &
         & modulus=1.0_dp, sigma=0.1_dp, mu=4.0_dp, psi=merge(0.0_dp, 1.0_dp, i == 1), &
         & flow_pressure=2/pi)
      call build_hysteresis(p, solver_options(n_threads=1), -0.3_dp, 1.2_dp*dm, 3.0e-4_dp, t, err)
      if (allocated(err)) then
         print '(a,i0,a)', "model ", i, ": "//err%message
         deallocate (err)
      else
         print '(a,i0,a,i0,a,i0,a,es10.3)', "model ", i, ": ", size(t%m), " x ", size(t%s), &
            & ", max_error ", t%max_error
      end if
   end do
end program dem_build
