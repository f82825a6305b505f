!> Offline estimate of a third break of the rough + cap map at the annulus's opening
!> (doc/benchmarks.md "Stop 67: kink33"). README's E-GW + cap (as kink33_annulus.f90:
!> R = 405284.734569351 effective, E* = sigma = 1, mu 4, p_y = 0.01, delta_y = 100 sigma).
!> Reads lines "m/delta_y knee/sigma [delta_b/sigma]" (a table's delta_max nodes and its
!> knees k(m), from its CSV; a third column: the break given, no search) on stdin; per line
!> a history at rel_tol 1e-8 and:
!>  - delta_open, the overlap where the unloading's floored total pressure first holds a
!>    separated annulus (kink33_annulus's test, 8001 radii to 3 sqrt(R m); bisected 16
!>    times, solves at 1e-7), and the
!>    break delta_b = max(delta_open, k);
!>  - u = P/P(m) (P(m) the history's loading force; unloading solves at 1e-8, at 1e-6
!>    where that fails) at 24 points s_i = 1/2 - 0.06 (i/24)**2 of today's first piece,
!>    delta = k + (m - k)(1 - 2 s_i) ("old"), at the same s_i on [delta_b, m], delta =
!>    delta_b + (m - delta_b)(1 - 2 s_i) ("new"), and at 6 points of [k, delta_b],
!>    delta = k + (delta_b - k) j/7 ("low").
!> Prints one line per m: m/delta_y, k, delta_open, delta_b, then the 24 old, 24 new and
!> 6 low u; on stderr the solves retried at 1e-6. tools/bench/kink33_loo.py takes the leave-one-out errors in m at fixed s.
!>
!>   B=$(dirname $(find build -path '*/egw_sphere_problem.mod' | head -1))
!>   gfortran -O2 -fopenmp -ffree-line-length-none -I$B tools/bench/kink33_break_loo.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/kink33_break_loo
!>   OMP_NUM_THREADS=1 /tmp/kink33_break_loo < mlist.txt > loo.out
program kink33_break_loo
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_egw
   use egw_rough_sphere, only: solver_options, solve_result, loading_history, load_history, &
      & solve_unload, unloading_problem
   use egw_sphere_problem, only: scaled_problem, discrete_solution, total_pressure, negligible
   use egw_sphere_solver, only: solve_scaled
   use egw_hysteresis, only: first_yield
   implicit none
   integer, parameter :: n_r = 8001, n_old = 24, n_low = 6
   type(contact_params) :: p
   type(egw_error), allocatable :: err
   type(loading_history) :: hist
   type(solve_result) :: peak
   real(dp) :: dy, m, knee, lo, hi, d, d_b, s(n_old), u_old(n_old), u_new(n_old), u_low(n_low)
   integer :: i, it, ios
   real(dp) :: given
   character(len=256) :: line
   p = contact_params(model=model_egw, radius=405284.734569351_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   dy = first_yield(p)
   s = [(0.5_dp - 0.06_dp*(i/real(n_old, dp))**2, i = 1, n_old)]
   do
      read (*, '(a)', iostat=ios) line
      if (ios /= 0) exit
      given = -huge(1.0_dp)
      read (line, *, iostat=ios) m, knee, given
      if (ios /= 0) read (line, *) m, knee
      m = m*dy
      call load_history(p, solver_options(rel_tol=1.0e-8_dp, n_threads=1), m, hist, peak, err)
      if (allocated(err)) then
         print '(a,f10.5,a)', "# history failed at ", m/dy, ": "//err%message
         deallocate (err)
         cycle
      end if
      if (given > -huge(1.0_dp)) then   ! (the break given: no search)
         lo = given
         hi = given
      else
         hi = m - dy + 6.0_dp
      end if
      do while (given == -huge(1.0_dp) .and. opened(hi) .and. hi < m)
         hi = hi + 5.0_dp
      end do
      lo = hi
      do while (given == -huge(1.0_dp) .and. .not. opened(lo))
         hi = lo
         lo = lo - 0.25_dp
         if (lo < -2.0_dp) exit
      end do
      if (lo >= -2.0_dp .and. given == -huge(1.0_dp)) then
         do it = 1, 16
            d = 0.5_dp*(lo + hi)
            if (opened(d)) then
               lo = d
            else
               hi = d
            end if
         end do
      end if
      d_b = max(lo, knee)
      hist%options%rel_tol = 1.0e-8_dp
      do i = 1, n_old
         u_old(i) = u_at(knee + (m - knee)*(1.0_dp - 2.0_dp*s(i)))
         u_new(i) = u_at(d_b + (m - d_b)*(1.0_dp - 2.0_dp*s(i)))
      end do
      do i = 1, n_low
         u_low(i) = u_at(knee + (d_b - knee)*i/real(n_low + 1, dp))
      end do
      print '(f19.15,3es24.16,54es24.16)', m/dy, knee, lo, d_b, u_old, u_new, u_low
      flush (6)
   end do
contains
   !> P/P(m) of the unloading solve at d (at 1e-6 where 1e-8 fails; -1 if that fails too)
   real(dp) function u_at(d) result(u)
      real(dp), intent(in) :: d
      type(solve_result) :: res
      call solve_unload(hist, d, res, err)
      if (allocated(err)) then
         deallocate (err)
         write (0, '(a,f19.15,es24.16)') "# retried at 1e-6: m/delta_y, delta ", m/dy, d
         hist%options%rel_tol = 1.0e-6_dp
         call solve_unload(hist, d, res, err)
         hist%options%rel_tol = 1.0e-8_dp
         if (allocated(err)) then
            deallocate (err)
            u = -1.0_dp
            return
         end if
      end if
      u = res%force/peak%force
   end function u_at

   !> kink33_annulus's test: the floored total pressure at d has a zero inside the contact
   logical function opened(d)
      real(dp), intent(in) :: d
      type(scaled_problem) :: q
      type(discrete_solution) :: sol
      real(dp) :: est, pr(n_r)
      integer :: i, method
      opened = .false.
      q = unloading_problem(hist, d)
      if (negligible(q)) return
      call solve_scaled(q, solver_options(rel_tol=1.0e-7_dp, n_threads=1), sol, est, method, &
         & err)
      if (allocated(err)) then
         deallocate (err)
         call solve_scaled(q, solver_options(rel_tol=1.0e-6_dp, n_threads=1), sol, est, &
            & method, err)
         if (allocated(err)) then
            deallocate (err)
            return
         end if
      end if
      do i = 1, n_r
         pr(i) = total_pressure(q, sol, 3.0_dp*sqrt(m/p%sigma)*(i - 1)/(n_r - 1))
      end do
      opened = interior_zero(pr)
   end function opened

   !> A zero of the pressures pr (floored total, on increasing radii) followed by a
   !> positive pressure farther out.
   logical function interior_zero(pr)
      real(dp), intent(in) :: pr(:)
      real(dp) :: top
      integer :: i, i0
      interior_zero = .false.
      top = maxval(pr)
      do i0 = 2, size(pr)
         if (pr(i0) <= 1.0e-14_dp*top) exit
      end do
      do i = i0, size(pr)
         if (pr(i) > 1.0e-14_dp*top) then
            interior_zero = .true.
            return
         end if
      end do
   end function interior_zero
end program kink33_break_loo
