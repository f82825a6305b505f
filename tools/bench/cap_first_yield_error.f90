!> Stop 52 (doubt18): a Hertz + cap hysteresis table's error near first yield against the
!> cap solver. R = E* = 1, p_y = 2/pi (delta_y = 1), table over [-0.8567, TOP] delta_y at TOL;
!> turning points at 0.1, 0.25, 0.5, 0.75, 0.9 of the delta_max intervals above delta_y (the
!> first NJ + 2 of them, all if NJ = 0), each unloaded at 40 overlaps graded toward its
!> residual overlap (bisected on the solves): the worst |P_table - P_solve|/max(P_solve,
!> 1e-3 P(m)) per turning point, and the table's max_error. doc/stability.md "Stop 52".
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/cap_first_yield_error.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/cap_first_yield_error
!>   OMP_NUM_THREADS=1 EGW_CACHE_DIR=off /tmp/cap_first_yield_error TOL TOP NJ
program cap_first_yield_error
   use egw_all
   implicit none
   type(contact_params) :: p
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   type(loading_history) :: hist
   type(solve_result) :: top, res
   real(dp) :: tol, topm, m, lo, hi, d, f, k, state, local, worst, wj
   real(dp), parameter :: fr(5) = [0.1_dp, 0.25_dp, 0.5_dp, 0.75_dp, 0.9_dp]
   integer :: i, j, q, stat, nj
   character(len=32) :: arg
   call get_command_argument(1, arg); read (arg, *) tol
   call get_command_argument(2, arg); read (arg, *) topm
   call get_command_argument(3, arg); read (arg, *) nj
   p = contact_params(model=model_hertz, radius=1.0_dp, modulus=1.0_dp, &
      & flow_pressure=2/acos(-1.0_dp))
   call build_hysteresis(p, solver_options(n_threads=1), -0.8567_dp, topm, tol, t, err)
   if (allocated(err)) then
      print '(a)', err%message
      stop 1
   end if
   print '(a,es12.4,a,i0,a,es22.15)', 'max_error ', t%max_error, ' delta_max nodes ', &
      & size(t%m), ' first ', t%m(1)
   worst = 0
   do j = 1, size(t%m) - 1
      if (t%m(j + 1) <= 1.0_dp) cycle
      if (nj > 0 .and. j > nj + 2) exit
      do q = 1, size(fr)
         m = t%m(j) + fr(q)*(t%m(j + 1) - t%m(j))
         call load_history(p, solver_options(rel_tol=1.0e-8_dp), m, hist, top, err)
         if (allocated(err)) stop 2
         lo = 0
         hi = m
         do i = 1, 60
            d = 0.5_dp*(lo + hi)
            call solve_unload(hist, d, res, err)
            if (res%force > 0) then
               hi = d
            else
               lo = d
            end if
         end do
         wj = 0
         do i = 1, 40
            d = hi + (m - hi)*10.0_dp**(-i/10.0_dp)
            call solve_unload(hist, d, res, err)
            state = m
            call hysteresis_eval(t, d, state, f, k, stat)
            local = max(res%force, 1.0e-3_dp*top%force)
            wj = max(wj, abs(f - res%force)/local)
         end do
         worst = max(worst, wj)
         print '(a,i4,f6.2,es14.6,2es11.3)', 'interval', j, fr(q), m, wj, t%m(j + 1) - t%m(j)
      end do
   end do
   print '(a,es12.4)', 'worst ', worst
end program cap_first_yield_error
