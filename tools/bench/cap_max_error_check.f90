!> Stop 53 (doubt19): a cap hysteresis table's max_error against a dense independent
!> evaluation. MODEL 0: Hertz + cap (R = E* = 1, p_y = 2/pi: delta_y = 1, the table over
!> [-0.8567, TOP] delta_y); MODEL 1: E-GW + cap, mu 4, sigma = 1, delta_y = 100 sigma
!> (README's scene: R = 810569.469138702, E* = 1, p_y = 0.01; the table over [0, TOP] sigma).
!> Turning points at 1/4, 1/2, 3/4 of every NSKIP-th delta_max interval (all: NSKIP 1),
!> each loaded at rel_tol 1e-7 (load_history) and unloaded at 16 overlaps from m down to
!> where the force vanishes (bisected on the solves; graded toward it), solve_unload
!> against hysteresis_eval: the worst |P_table - P_solve| in units of the turning point's
!> solved force P(m) and of max(P_solve, 1e-3 P(m)), against the table's max_error.
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/cap_max_error_check.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/cap_max_error_check
!>   OMP_NUM_THREADS=1 EGW_CACHE_DIR=off /tmp/cap_max_error_check MODEL TOL TOP NSKIP
program cap_max_error_check
   use egw_all
   implicit none
   type(contact_params) :: p
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   type(loading_history) :: hist
   type(solve_result) :: top, res
   real(dp) :: tol, topm, m, lo, hi, d, f, k, state, e_pm, e_loc, w_pm, w_loc, dmin
   real(dp), parameter :: fr(3) = [0.25_dp, 0.5_dp, 0.75_dp]
   integer :: i, j, q, stat, model, nskip, n_pts, j_pm, j_loc
   character(len=32) :: arg
   call get_command_argument(1, arg); read (arg, *) model
   call get_command_argument(2, arg); read (arg, *) tol
   call get_command_argument(3, arg); read (arg, *) topm
   call get_command_argument(4, arg); read (arg, *) nskip
   if (model == 0) then
      p = contact_params(model=model_hertz, radius=1.0_dp, modulus=1.0_dp, &
         & flow_pressure=2/acos(-1.0_dp))
      dmin = -0.8567_dp
   else
      p = contact_params(model=model_egw, radius=810569.469138702_dp, modulus=1.0_dp, &
         & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
      dmin = 0.0_dp
   end if
   call build_hysteresis(p, solver_options(n_threads=1), dmin, topm, tol, t, err)
   if (allocated(err)) then
      print '(a)', err%message
      stop 1
   end if
   w_pm = 0
   w_loc = 0
   n_pts = 0
   j_pm = 0
   j_loc = 0
   do j = 1, size(t%m) - 1, nskip
      do q = 1, size(fr)
         m = t%m(j) + fr(q)*(t%m(j + 1) - t%m(j))
         call load_history(p, solver_options(rel_tol=1.0e-7_dp), m, hist, top, err)
         if (allocated(err)) then
            print '(a,es14.6,a,a)', 'load_history at m ', m, ': ', err%message
            stop 2
         end if
         lo = dmin - 10*(t%m(size(t%m)) - dmin)
         hi = m
         do i = 1, 50
            d = 0.5_dp*(lo + hi)
            call solve_unload(hist, d, res, err)
            if (allocated(err)) stop 3
            if (res%force > 1.0e-9_dp*top%force) then
               hi = d
            else
               lo = d
            end if
         end do
         e_pm = 0
         e_loc = 0
         do i = 0, 15
            d = hi + (m - hi)*(1 - (i/16.0_dp)**2)
            call solve_unload(hist, d, res, err)
            if (allocated(err)) stop 4
            state = m
            call hysteresis_eval(t, d, state, f, k, stat)
            e_pm = max(e_pm, abs(f - res%force)/top%force)
            e_loc = max(e_loc, abs(f - res%force)/max(res%force, 1.0e-3_dp*top%force))
            n_pts = n_pts + 1
         end do
         if (e_pm > w_pm) j_pm = j
         if (e_loc > w_loc) j_loc = j
         w_pm = max(w_pm, e_pm)
         w_loc = max(w_loc, e_loc)
      end do
   end do
   print '(a,i2,a,es9.2,a,f8.1,a,i4,a,es10.3,a,es10.3,a,i4,a,es10.3,a,i4,a,i6)', 'model ', &
      & model, ' tol ', tol, ' top ', topm, ' m nodes ', size(t%m), ' max_error ', &
      & t%max_error, ' measured /P(m) ', w_pm, ' (interval ', j_pm, ') /max(P,1e-3P(m)) ', &
      & w_loc, ' (interval ', j_loc, ') points ', n_pts
end program cap_max_error_check
