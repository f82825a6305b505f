!> The rel_tol 1e-8 / 1e-9 unloading scan of README's pair about the kink (doc/benchmarks.md
!> "Stop 61: acc27"): solve_contact_unload in sigma units (R = 810569.469138702, E* =
!> sigma = 1, mu 4; p_y = 0.01, delta_y = 200 sigma, or no cap), EP-GW with psi 1, at
!> turning points m and overlaps delta = 0.95, 0.8, 0.6, 0.4, 0.2, 0.05, 0, -0.005, -0.01
!> m and 2.1221, 1, 5 sigma. One line a solve: model, cap, rel_tol, m, delta, ok or FAIL,
!> CPU s, force, est_rel_err (or the message).
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/acc27_unload_scan.f90 \
!>      $(find build -name libegw.a | head -1) -lfftw3_omp -lfftw3 -llapack -lblas -o /tmp/scan
!>   OMP_NUM_THREADS=1 /tmp/scan E-GW 1 1e-8 205 206 212.7   # model, cap (0/1), rel_tol, m...
program scan
   use egw, only: dp, contact_params, model_egw, model_gw, model_epgw, solver_options, egw_error, &
      & solve_result, solve_contact_unload
   implicit none
   type(contact_params) :: p
   type(egw_error), allocatable :: err
   type(solve_result) :: res
   real(dp) :: m, tol, t0, t1
   real(dp), parameter :: frac(9) = [0.95_dp, 0.8_dp, 0.6_dp, 0.4_dp, 0.2_dp, 0.05_dp, 0.0_dp, &
      & -0.005_dp, -0.01_dp]
   real(dp) :: deltas(12)
   character(len=32) :: arg, model
   integer :: k, j, cap
   call get_command_argument(1, model)
   call get_command_argument(2, arg); read (arg, *) cap
   call get_command_argument(3, arg); read (arg, *) tol
   p = contact_params(model=model_egw, radius=810569.469138702_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp*cap)
   if (model == "GW") p%model = model_gw
   if (model == "EP-GW") then
      p%model = model_epgw
      p%psi = 1.0_dp
   end if
   do k = 4, command_argument_count()
      call get_command_argument(k, arg); read (arg, *) m
      deltas(1:9) = frac*m
      deltas(10) = 2.1221_dp
      deltas(11) = 1.0_dp
      deltas(12) = 5.0_dp
      do j = 1, 12
         call cpu_time(t0)
         call solve_contact_unload(p, solver_options(rel_tol=tol, n_threads=1), deltas(j), m, res, err)
         call cpu_time(t1)
         if (allocated(err)) then
            print '(a,1x,i1,1x,es8.1,1x,f9.4,1x,f10.4,1x,a,1x,f7.2,1x,a)', trim(model), cap, tol, m, &
               & deltas(j), "FAIL", t1 - t0, trim(err%message)
            deallocate (err)
         else
            print '(a,1x,i1,1x,es8.1,1x,f9.4,1x,f10.4,1x,a,1x,f7.2,1x,es24.16,1x,es10.3)', trim(model), &
               & cap, tol, m, deltas(j), "ok  ", t1 - t0, res%force, res%est_rel_err
         end if
         flush (6)
      end do
   end do
end program scan
