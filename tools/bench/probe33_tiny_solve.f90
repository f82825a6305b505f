!> One unloading solve of the sigma/delta_y = 1e-5 table (rough_cap_hysteresis's "1e-5 to 2e5
!> sigma" test, weight33's failing check node; doc/benchmarks.md "Stop 67: probe33"): the
!> history to M at the build's curve options for TOL, then solve_unload at each DELTA.
!>   tiny_solve M TOL 0 DELTA...
program tiny_solve
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_egw
   use egw_rough_sphere, only: solver_options, solve_result, loading_history, load_history, &
      & solve_unload
   use egw_hysteresis_lengths, only: curve_options
   implicit none
   type(contact_params) :: p
   type(loading_history) :: h
   type(solve_result) :: top, res
   type(egw_error), allocatable :: err
   type(solver_options) :: opt
   real(dp) :: m, d, tol
   integer :: i, n
   character(len=64) :: arg
   call get_command_argument(1, arg); read (arg, *) m
   call get_command_argument(2, arg); read (arg, *) tol
   call get_command_argument(3, arg); read (arg, *) n
   p = contact_params(model=model_egw, radius=810569469.1387022_dp/2, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   opt = curve_options(solver_options(n_threads=1), tol)
   print *, "curve rel_tol", opt%rel_tol
   call load_history(p, opt, m, h, top, err)
   if (allocated(err)) then
      print *, "history: ", err%message; stop 1
   end if
   print '(a,es12.5)', "P(m) ", top%force
   do i = 3, command_argument_count()
      if (i == 3) cycle
      call get_command_argument(i, arg); read (arg, *) d
      call solve_unload(h, d, res, err)
      if (allocated(err)) then
         print '(a,es14.7,a)', "delta ", d, ": "//err%message
         deallocate (err)
      else
         print '(a,es14.7,a,es12.5,a,es12.5,a,es10.3,a,es10.3)', "delta ", d, " P ", res%force, &
            & " P/P(m) ", res%force/top%force, " a ", res%contact_radius, " est ", res%est_rel_err
      end if
   end do
end program tiny_solve
