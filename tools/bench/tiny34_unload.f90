!> The sigma/delta_y = 1e-5 table's check-curve solves (rough_cap_hysteresis's "E-GW + cap at
!> sigma/delta_y = 1e-5 to 2e5 sigma" test, doc/benchmarks.md "Stop 68: tiny34") as the build
!> makes them since front33's history tolerance: the history to M at HIST_TOL, its unloading
!> solves at UNLOAD_TOL (start_curve's rel_tol/100 and rel_tol/10: 1e-5 and 1e-4 at the
!> test's 1e-3), each against a reference (history and unloading at REF_TOL; 0: none).
!>   B=$(dirname $(find build -path '*/egw_hysteresis_lengths.mod' | head -1))
!>   gfortran -O2 -fopenmp -ffree-line-length-none -I$B tools/bench/tiny34_unload.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/tiny34_unload
!>   OMP_NUM_THREADS=1 /tmp/tiny34_unload M HIST_TOL UNLOAD_TOL REF_TOL DELTA...
!> Prints per overlap P/P(m), est_rel_err and (with a reference) |P - P_ref|/P_ref.
program tiny34_unload
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_egw
   use egw_rough_sphere, only: solver_options, solve_result, loading_history, load_history, &
      & solve_unload
   implicit none
   type(contact_params) :: p
   type(loading_history) :: h, h_ref
   type(solve_result) :: top, top_ref, res, ref
   type(egw_error), allocatable :: err
   type(solver_options) :: opt
   real(dp) :: m, d, hist_tol, unload_tol, ref_tol
   integer :: i
   character(len=64) :: arg
   call get_command_argument(1, arg); read (arg, *) m
   call get_command_argument(2, arg); read (arg, *) hist_tol
   call get_command_argument(3, arg); read (arg, *) unload_tol
   call get_command_argument(4, arg); read (arg, *) ref_tol
   p = contact_params(model=model_egw, radius=810569469.1387022_dp/2, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   opt = solver_options(n_threads=1, rel_tol=hist_tol)
   call load_history(p, opt, m, h, top, err, stiffness=.false.)
   if (allocated(err)) then
      print *, "history: ", err%message; stop 1
   end if
   h%options%rel_tol = unload_tol
   if (ref_tol > 0.0_dp) then
      opt%rel_tol = ref_tol
      call load_history(p, opt, m, h_ref, top_ref, err, stiffness=.false.)
      if (allocated(err)) then
         print *, "reference history: ", err%message; stop 1
      end if
   end if
   print '(a,es12.5,a,es9.2,a,es9.2,a,es9.2)', "P(m) ", top%force, " history ", hist_tol, &
      & " unloading ", unload_tol, " reference ", ref_tol
   do i = 5, command_argument_count()
      call get_command_argument(i, arg); read (arg, *) d
      call solve_unload(h, d, res, err)
      if (allocated(err)) then
         print '(a,es23.16,a)', "delta ", d, ": "//err%message
         deallocate (err)
         cycle
      end if
      if (ref_tol > 0.0_dp) then
         call solve_unload(h_ref, d, ref, err)
         if (allocated(err)) then
            print '(a,es23.16,a)', "delta ", d, " reference: "//err%message
            deallocate (err)
            cycle
         end if
         print '(a,es23.16,a,es12.5,a,es10.3,a,es10.3,a,es10.3)', "delta ", d, " P/P(m) ", &
            & res%force/top%force, " est ", res%est_rel_err, " err ", &
            & abs(res%force - ref%force)/abs(ref%force), " ref_est ", ref%est_rel_err
      else
         print '(a,es23.16,a,es12.5,a,es10.3)', "delta ", d, " P/P(m) ", res%force/top%force, &
            & " est ", res%est_rel_err
      end if
   end do
end program tiny34_unload
