!> One unloading solve of README's rough + cap pair in sigma units (R = 810569.469138702,
!> E* = sigma = 1, mu 4, p_y = 0.01: delta_y = 200 sigma), E-GW or EP-GW (psi 1): prints
!> "RES m delta rel_tol force stiffness est_rel_err" (doc/benchmarks.md "Stop 63:
!> stiffb29"; tools/bench/unload_quotient.sh takes its quotients).
!>
!>   B=build/gfortran_28C1B7C106A83FFE   # the directory of egw.mod
!>   gfortran -O2 -fopenmp -I$B -J/tmp tools/bench/unload_point.f90 \
!>      $(find build -name libegw.a | head -1) -lfftw3_omp -lfftw3 -llapack -lblas -o /tmp/point
!>   OMP_NUM_THREADS=1 /tmp/point 209 1 1e-8 [EP-GW]
program unload_point
   use egw, only: dp, contact_params, model_egw, model_epgw, solver_options, egw_error, &
      & solve_result, solve_contact_unload
   implicit none
   type(contact_params) :: p
   real(dp) :: m, delta, tol
   character(len=32) :: arg
   type(solve_result) :: res
   type(egw_error), allocatable :: err
   call get_command_argument(1, arg); read (arg, *) m
   call get_command_argument(2, arg); read (arg, *) delta
   call get_command_argument(3, arg); read (arg, *) tol
   p = contact_params(model=model_egw, radius=810569.469138702_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   call get_command_argument(4, arg)
   if (arg == "EP-GW") then
      p%model = model_epgw
      p%psi = 1.0_dp
   end if
   call solve_contact_unload(p, solver_options(rel_tol=tol, n_threads=1), delta, m, res, err)
   if (allocated(err)) then
      print '(a)', "FAIL "//trim(err%message)
      stop 1
   end if
   print '(a,2f10.5,es9.1,3es24.15)', 'RES', m, delta, tol, res%force, res%stiffness, &
      & res%est_rel_err
end program unload_point
