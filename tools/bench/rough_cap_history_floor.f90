!> Which solve sets the rough + cap unloading force's error floor near the force's front
!> (doc/benchmarks.md "Stop 53 (local19)"): the history loaded at rel_tol A, its
!> unloading solves at rel_tol B (the history's options%rel_tol set to B after loading),
!> against a history and solves at 1e-8; local error |P - P_ref|/P_ref at the overlaps of
!> tools/bench/rough_cap_edge.f90's part 2 (m = 2.3 delta_y: P ~ 1e-3 .. 2e-2 P(m);
!> m = 4 delta_y: ~1e-3 .. 1e-2 P(m)). README's rough + cap numbers (delta_y = 100 sigma).
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/rough_cap_history_floor.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/rough_cap_history_floor
!>   OMP_NUM_THREADS=1 /tmp/rough_cap_history_floor
program rough_cap_history_floor
   use egw, only: dp, contact_params, model_egw, solver_options, solve_result, egw_error, &
      & loading_history, load_history, solve_unload
   implicit none
   type(contact_params) :: p
   type(egw_error), allocatable :: err
   type(loading_history) :: hist
   type(solve_result) :: peak, res, ref
   real(dp) :: ms(2), ds(3, 2), pairs(2, 4)
   integer :: i, k, q
   p = contact_params(model=model_egw, radius=810569.469138702_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   ms = [230.0_dp, 400.0_dp]
   ds(:, 1) = [4.92_dp, 10.0_dp, 20.0_dp]
   ds(:, 2) = [61.0_dp, 65.0_dp, 80.0_dp]
   ! (history rel_tol, unloading rel_tol)
   pairs = reshape([1.0e-5_dp, 1.0e-5_dp, 1.0e-6_dp, 1.0e-5_dp, 1.0e-7_dp, 1.0e-5_dp, &
      & 1.0e-6_dp, 1.0e-6_dp], [2, 4])
   do q = 1, 2
      do i = 1, 3
         call load_history(p, solver_options(rel_tol=1.0e-8_dp, n_threads=1), ms(q), hist, &
            & peak, err)
         if (allocated(err)) stop 1
         call solve_unload(hist, ds(i, q), ref, err)
         if (allocated(err)) stop 1
         do k = 1, 4
            call load_history(p, solver_options(rel_tol=pairs(1, k), n_threads=1), ms(q), &
               & hist, peak, err)
            if (allocated(err)) stop 1
            hist%options%rel_tol = pairs(2, k)
            call solve_unload(hist, ds(i, q), res, err)
            if (allocated(err)) stop 1
            print '(a,f6.2,a,f6.2,a,es8.1,a,es8.1,a,es10.3,a,es9.2)', "m/dy ", ms(q)/100, &
               & "  delta/sigma ", ds(i, q), "  history ", pairs(1, k), "  unload ", &
               & pairs(2, k), "  P/P(m) ", ref%force/peak%force, "  local error ", &
               & abs(res%force - ref%force)/ref%force
         end do
      end do
   end do
end program rough_cap_history_floor
