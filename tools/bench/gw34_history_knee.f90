!> One rough + cap history of README's scene (R = 405284.734569351 effective, E* = sigma =
!> 1, mu 4, p_y = 0.01: delta_y = 100 sigma; GW + cap, or E-GW + cap with
!> EGW_PROBE_MODEL=E-GW) at M sigma and rel_tol HTOL (no law table), its unloading solves at
!> UTOL, at the overlaps given, against a history and solve at rel_tol 1e-9. Per overlap:
!> delta, P_ref, P, u = P_ref/P(m), |P - P_ref|/max(P_ref, 1e-3 P(m)) and the solve's
!> est_rel_err (doc/benchmarks.md "Stop 68: gw34": the knee window and the histories
!> near first yield).
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis_lengths.mod' | head -1))
!>   gfortran -O2 -fopenmp -ffree-line-length-none -I$B tools/bench/gw34_history_knee.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/gw34_history_knee
!>   OMP_NUM_THREADS=1 /tmp/gw34_history_knee 399.0373536808676 1e-6 1e-5 128.0475 128.0494
!>   OMP_NUM_THREADS=1 /tmp/gw34_history_knee 109.18738302827924 1e-6 1e-5 1.9280419159118125
program gw34_history_knee
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_gw, model_egw
   use egw_rough_sphere, only: solver_options, solve_result, loading_history, load_history, &
      & solve_unload
   implicit none
   type(contact_params) :: p
   type(egw_error), allocatable :: err
   type(loading_history) :: h, hr
   type(solve_result) :: res, rr, pk
   real(dp) :: m, htol, utol, d, pm
   character(len=64) :: arg
   integer :: i
   p = contact_params(model=model_gw, radius=405284.734569351_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   call get_environment_variable("EGW_PROBE_MODEL", arg)
   if (trim(arg) == "E-GW") p%model = model_egw
   call get_command_argument(1, arg)
   read (arg, *) m
   call get_command_argument(2, arg)
   read (arg, *) htol
   call get_command_argument(3, arg)
   read (arg, *) utol
   call load_history(p, solver_options(rel_tol=1.0e-9_dp, n_threads=1), m, hr, pk, err)
   if (allocated(err)) stop "reference history failed"
   pm = pk%force
   call load_history(p, solver_options(rel_tol=htol, n_threads=1), m, h, res, err)
   if (allocated(err)) stop "history failed"
   h%options%rel_tol = utol
   do i = 4, command_argument_count()
      call get_command_argument(i, arg)
      read (arg, *) d
      call solve_unload(hr, d, rr, err)
      if (allocated(err)) then
         print '(a,f16.8,a)', "reference failed at ", d, ": "//err%message
         deallocate (err)
         cycle
      end if
      call solve_unload(h, d, res, err)
      if (allocated(err)) then
         print '(a,f16.8,a)', "solve failed at ", d, ": "//err%message
         deallocate (err)
         cycle
      end if
      print '(f16.8,2es25.16,a,es11.4,a,es10.3,a,es10.3)', d, rr%force, res%force, " u ", &
         & rr%force/pm, " err_local ", abs(res%force - rr%force)/max(rr%force, 1e-3_dp*pm), &
         & " est ", res%est_rel_err
   end do
end program gw34_history_knee
