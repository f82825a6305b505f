!> Stop 51 (edge17): rough + cap unloading near the edge, history field against rel_tol.
!> README's E-GW + cap (sigma = delta_y/100, mu 4): at m = 2.3 and 4 delta_y, three overlaps
!> above the edge, history + unloading at rel_tol 1e-4 .. 1e-6 against both at 1e-9 (the
!> error in P(m) and of the local force; CPU time per rel_tol). doc/stability.md "Stop 51 (edge17)".
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/rough_cap_edge_history.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/rough_cap_edge_history
!>   OMP_NUM_THREADS=1 /tmp/rough_cap_edge_history
program rough_cap_edge_history
   use egw, only: dp, contact_params, model_egw, solver_options, solve_result, egw_error, &
      & loading_history, load_history, solve_unload
   implicit none
   type(contact_params) :: p
   type(egw_error), allocatable :: err
   type(loading_history) :: h
   type(solve_result) :: peak, res, ref
   real(dp) :: ms(2) = [230.0_dp, 400.0_dp], ds(3, 2), tol, t0, t1, tt(3)
   integer :: q, i, k
   ds(:, 1) = [4.92_dp, 10.0_dp, 20.0_dp]
   ds(:, 2) = [61.0_dp, 65.0_dp, 80.0_dp]
   p = contact_params(model=model_egw, radius=810569.469138702_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   tt = 0
   do q = 1, 2
      do i = 1, 3
         call load_history(p, solver_options(rel_tol=1.0e-9_dp, n_threads=1), ms(q), h, peak, err)
         if (allocated(err)) stop 1
         call solve_unload(h, ds(i, q), ref, err)
         if (allocated(err)) stop 2
         do k = 4, 6
            tol = 10.0_dp**(-k)
            call cpu_time(t0)
            call load_history(p, solver_options(rel_tol=tol, n_threads=1), ms(q), h, peak, err)
            if (allocated(err)) stop 3
            call solve_unload(h, ds(i, q), res, err)
            if (allocated(err)) stop 4
            call cpu_time(t1)
            tt(k - 3) = tt(k - 3) + t1 - t0
            print '(a,f5.0,a,f5.1,a,es9.2,a,es8.1,a,es9.2,a,es9.2)', 'm ', ms(q), ' d ', ds(i, q), &
               & ' P/Pm ', ref%force/peak%force, ' tol ', tol, ' err/Pm ', &
               & (res%force - ref%force)/peak%force, ' err/P ', (res%force - ref%force)/ref%force
         end do
      end do
   end do
   print '(a,3f8.3)', 'cpu s at 1e-4, 1e-5, 1e-6 (history + one unloading, 6 cases): ', tt
end program
