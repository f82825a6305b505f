!> The local error of Hertz + cap and E-GW + cap hysteresis tables (issue 33 item 5;
!> doc/stability.md "Stop 49 (capl15)"): |P_table - P_solve|/max(P_solve, 1e-3 P(m))
!> along unloading curves of turning points between the table's nodes, against
!> load_history/solve_unload at rel_tol 1e-8 (Hertz + cap: the cap solver, whose
!> options are its own), with the build time (one thread) and the grid.
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -ffree-line-length-none -I$B tools/bench/cap_local_error.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/cap_local_error
!>   OMP_NUM_THREADS=1 /tmp/cap_local_error hertz 1e-3 10     # table [0, 10 delta_y]
!>   OMP_NUM_THREADS=1 /tmp/cap_local_error egw 1e-3 10 100   # sigma = delta_y/100
!>
!> R = 1 mm, E* = 100 GPa, p_y = 1 GPa. Hertz + cap: 9 turning points in
!> [1.2, top] delta_y, 41 overlaps graded toward the residual overlap delta_r (bisected on
!> the solves): delta - delta_r = (m - delta_r) 10**(-k/10), k = 0 .. 40 (P down to
!> ~1e-6 P(m)). E-GW + cap (table from -3 sigma, mu 4): 5 turning points in
!> [1.5, 9.5] delta_y, 50 overlaps from m to -2 sigma (denser near m). Prints the worst
!> error over P(m), the worst local error and where, and the worst local error by decade
!> of P/P(m): [1, 0.1), [0.1, 0.01), ... (the last: below 1e-5, and P = 0).
program cap_local_error
   use egw, only: dp, contact_params, model_hertz, model_egw, solver_options, &
      & solve_result, egw_error, hysteresis_table, build_hysteresis, hysteresis_eval, &
      & loading_history, load_history, solve_unload
   use iso_fortran_env, only: int64
   implicit none
   type(contact_params) :: p
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   type(loading_history) :: hist
   type(solve_result) :: peak, res
   real(dp) :: dy, tol, top, sdiv, sig, m, d, lo, hi, f, k, state, e_loc, worst_pm, &
      & worst_loc, at(3), band(6)
   integer :: j, i, stat, b, n_m, n_d
   integer(int64) :: c0, c1, rate
   character(len=32) :: arg, model
   logical :: hertz
   call get_command_argument(1, model)
   call get_command_argument(2, arg)
   read (arg, *) tol
   call get_command_argument(3, arg)
   read (arg, *) top
   sdiv = 100
   if (command_argument_count() >= 4) then
      call get_command_argument(4, arg)
      read (arg, *) sdiv
   end if
   hertz = model == "hertz"
   dy = (acos(-1.0_dp)*1.0e9_dp/(2*1.0e11_dp))**2*1.0e-3_dp
   sig = dy/sdiv
   if (hertz) then
      p = contact_params(model=model_hertz, radius=1.0e-3_dp, modulus=1.0e11_dp, &
         & flow_pressure=1.0e9_dp)
      lo = 0.0_dp
   else
      p = contact_params(model=model_egw, radius=1.0e-3_dp, modulus=1.0e11_dp, &
         & flow_pressure=1.0e9_dp, sigma=sig, mu=4.0_dp)
      lo = -3*sig
   end if
   call system_clock(c0, rate)
   call build_hysteresis(p, solver_options(n_threads=1), lo, top*dy, tol, t, err)
   call system_clock(c1)
   if (allocated(err)) then
      print '(a)', "build failed: "//err%message
      stop 1
   end if
   print '(a,a,es8.1,a,f6.1,a,f8.2,a,i0,a,i0)', trim(model), " + cap, rel_tol", tol, &
      & " to", top, " delta_y: build", real(c1 - c0, dp)/rate, " s wall, n_m ", size(t%m), &
      & ", n_s ", size(t%s)
   worst_pm = 0
   worst_loc = 0
   band = 0
   at = 0
   n_m = merge(9, 5, hertz)
   n_d = merge(41, 50, hertz)
   do j = 1, n_m
      if (hertz) then
         m = dy*(1.2_dp + (top - 1.3_dp)*(real(j, dp) - 0.377_dp)/n_m)
      else
         m = dy*(1.5_dp + (top - 2.0_dp)*(real(j, dp) - 0.377_dp)/n_m)
      end if
      call load_history(p, solver_options(rel_tol=1.0e-8_dp, n_threads=1), m, hist, &
         & peak, err)
      if (allocated(err)) stop 1
      if (hertz) then   ! the residual overlap of the solves
         lo = 0.0_dp
         hi = m
         do i = 1, 60
            d = 0.5_dp*(lo + hi)
            call solve_unload(hist, d, res, err)
            if (allocated(err)) stop 1
            if (res%force > 0.0_dp) then
               hi = d
            else
               lo = d
            end if
         end do
      end if
      do i = 1, n_d
         if (hertz) then
            d = hi + (m - hi)*10.0_dp**(-(i - 1)/10.0_dp)
         else
            d = m - (m + 2*sig)*(i/real(n_d, dp))**0.7_dp
         end if
         call solve_unload(hist, d, res, err)
         if (allocated(err)) stop 1
         state = m
         call hysteresis_eval(t, d, state, f, k, stat)
         worst_pm = max(worst_pm, abs(f - res%force)/peak%force)
         e_loc = abs(f - res%force)/max(res%force, 1.0e-3_dp*peak%force)
         if (e_loc > worst_loc) then
            worst_loc = e_loc
            at = [m/dy, d/dy, res%force/peak%force]
         end if
         b = min(6, max(1, 1 + int(-log10(max(res%force/peak%force, 1.0e-12_dp)))))
         band(b) = max(band(b), e_loc)
      end do
   end do
   print '(a,es9.2,a,es9.2,a,3es10.2)', "  worst/P(m) ", worst_pm, ", worst local ", &
      & worst_loc, " at m/delta_y, delta/delta_y, P/P(m)", at
   print '(a,6es9.2)', "  worst local by decade of P/P(m):", band
end program cap_local_error
