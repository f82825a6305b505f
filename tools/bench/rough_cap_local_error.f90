!> The local error of an E-GW + cap hysteresis table between its node curves (issue 33
!> item 5; doc/benchmarks.md "Stop 51 (ratio17)"): |P_table - P_solve|/max(P_solve,
!> 1e-3 P(m)) at turning points m halfway along the table's delta_max intervals above
!> first yield (every stride-th), overlaps from m down to where the solve's force falls
!> below 1e-3 P(m) (n_d of them, graded toward that end), against load_history/solve_unload
!> at rel_tol 1e-7 (independent of the table). README's rough + cap numbers: R =
!> 810569.469138702, E* = 1, sigma = 1, mu 4, p_y = 0.01 (delta_y = 100 sigma); the table
!> from 0 to top delta_y. Prints the build's wall and CPU time (threads as
!> OMP_NUM_THREADS; CPU: cpu_time, the process's), the grid, the worst local error and
!> where, and by decade of P/P(m).
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -ffree-line-length-none -I$B tools/bench/rough_cap_local_error.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/rough_cap_local_error
!>   OMP_NUM_THREADS=1 /tmp/rough_cap_local_error 1e-4 6 1 24   # TOL, top, stride, n_d
!>   OMP_NUM_THREADS=1 /tmp/rough_cap_local_error 1e-4 6 1 24 0 # at the nodes themselves
!>   OMP_NUM_THREADS=1 /tmp/rough_cap_local_error 1e-4 6 1 24 0.5 1e-7 # curve solves at 1e-7
!>   OMP_NUM_THREADS=1 /tmp/rough_cap_local_error 1e-4 6 1 24 0.5 1e-6 by # and by turning point
program rough_cap_local_error
   use egw, only: dp, contact_params, model_egw, solver_options, solve_result, egw_error, &
      & hysteresis_table, build_hysteresis, hysteresis_eval, loading_history, &
      & load_history, solve_unload
   use iso_fortran_env, only: int64
   implicit none
   type(contact_params) :: p
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   type(loading_history) :: hist
   type(solve_result) :: peak, res
   type(solver_options) :: ref, defaults
   real(dp) :: dy, tol, top, m, d, f, k, state, e_loc, worst_loc, at(3), band(4), d_end, &
      & lo, hi, where, solve_tol, worst_m, cpu0, cpu1
   integer :: j, i, stat, b, stride, n_d, it, n_pts
   logical :: by_m
   integer(int64) :: c0, c1, rate
   character(len=32) :: arg
   call get_command_argument(1, arg)
   read (arg, *) tol
   call get_command_argument(2, arg)
   read (arg, *) top
   call get_command_argument(3, arg)
   read (arg, *) stride
   call get_command_argument(4, arg)
   read (arg, *) n_d
   ! (the fraction of the delta_max interval where the turning points lie: 0.5 unless given)
   where = 0.5_dp
   if (command_argument_count() >= 5) then
      call get_command_argument(5, arg)
      read (arg, *) where
   end if
   ! (the build's solver rel_tol: its default unless given; below 1e-6 the curves' solves
   ! take it, hysteresis_solve_tol)
   solve_tol = defaults%rel_tol
   if (command_argument_count() >= 6) then
      call get_command_argument(6, arg)
      read (arg, *) solve_tol
   end if
   ! (a seventh argument: the worst local error of every turning point too)
   by_m = command_argument_count() >= 7
   p = contact_params(model=model_egw, radius=810569.469138702_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   dy = 100.0_dp
   ref = solver_options(rel_tol=1.0e-7_dp, n_threads=1)
   call system_clock(c0, rate)
   call cpu_time(cpu0)
   call build_hysteresis(p, solver_options(rel_tol=solve_tol), 0.0_dp, top*dy, tol, t, err)
   call system_clock(c1)
   call cpu_time(cpu1)
   if (allocated(err)) then
      print '(a)', "build failed: "//err%message
      stop 1
   end if
   print '(a,es8.1,a,f6.1,a,f8.2,a,f8.2,a,i0,a,i0)', "E-GW + cap, rel_tol", tol, " to", &
      & top, " delta_y: build", real(c1 - c0, dp)/rate, " s wall,", cpu1 - cpu0, &
      & " s CPU, n_m ", size(t%m), ", n_s ", size(t%s)
   worst_loc = 0
   band = 0
   at = 0
   n_pts = 0
   do j = 1, size(t%m) - 1, stride
      m = t%m(j) + where*(t%m(j + 1) - t%m(j))
      if (m <= 1.01_dp*dy) cycle
      call load_history(p, ref, m, hist, peak, err)
      if (allocated(err)) stop 1
      ! the overlap where the solve's force is 1e-3 P(m) (bisection on the solves)
      lo = -3.0_dp
      hi = m
      do it = 1, 30
         d_end = 0.5_dp*(lo + hi)
         call solve_unload(hist, d_end, res, err)
         if (allocated(err)) stop 1
         if (res%force > 1.0e-3_dp*peak%force) then
            hi = d_end
         else
            lo = d_end
         end if
      end do
      d_end = hi
      worst_m = 0
      do i = 1, n_d
         d = m - (m - d_end)*(1.0_dp - (1.0_dp - i/real(n_d, dp))**2)
         call solve_unload(hist, d, res, err)
         if (allocated(err)) stop 1
         state = m
         call hysteresis_eval(t, d, state, f, k, stat)
         e_loc = abs(f - res%force)/max(res%force, 1.0e-3_dp*peak%force)
         n_pts = n_pts + 1
         worst_m = max(worst_m, e_loc)
         if (e_loc > worst_loc) then
            worst_loc = e_loc
            at = [m/dy, d/dy, res%force/peak%force]
         end if
         b = min(4, max(1, 1 + int(-log10(max(res%force/peak%force, 1.0e-12_dp)))))
         band(b) = max(band(b), e_loc)
      end do
      if (by_m) print '(a,f7.4,a,es9.2)', "    m/delta_y ", m/dy, "  worst local ", worst_m
   end do
   print '(a,i0,a,es9.2,a,3es10.2)', "  points ", n_pts, ", worst local ", worst_loc, &
      & " at m/delta_y, delta/delta_y, P/P(m)", at
   print '(a,4es9.2)', "  worst local by decade of P/P(m), [1, 0.1) ..:", band
end program rough_cap_local_error
