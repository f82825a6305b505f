!> Where the rough + cap unloading curves have their kink at x = m - delta ~ delta_y
!> (doc/benchmarks.md "Stop 56: kink22"): a separated annulus opens inside the contact,
!> between the capped centre and the rim of the plastic zone, where the unloading's total
!> pressure (floored at 0) first reaches its floor. For each turning point m (sigma) of
!> README's rough + cap pair in sigma units (R = 810569.469138702, E* = sigma = 1, mu 4,
!> p_y = 0.01: delta_y = 200 sigma), printed:
!>  - x_k(profile): the unloading distance where a zero-pressure annulus first appears in
!>    contact_profile_unload's total pressure (rel_tol 1e-7, 1601 radii up to 40 m),
!>    bisected in x over [190, min(m, 215)] sigma to ~2e-4 sigma, and its inner radius r_k;
!>  - x_k(stiffness): the x of the largest second difference of the unloading stiffness
!>    (load_history at 1e-9, solve_unload at 1e-8) on a 0.01 sigma grid about x_k(profile);
!>  - r_0 = sqrt(R (m - delta_y)), where the Hertz pressure at m equals p_y, and the Hertz
!>    radius sqrt(R (m - x_k)) of the overlap at the kink, for comparison.
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/rough_cap_separation_kink.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/rough_cap_separation_kink
!>   OMP_NUM_THREADS=1 /tmp/rough_cap_separation_kink 206 230   # turning points m (sigma)
program rough_cap_separation_kink
   use egw, only: dp, contact_params, model_egw, solver_options, egw_error, &
      & contact_profile_unload, solve_result, loading_history, load_history, solve_unload
   implicit none
   integer, parameter :: n_r = 1601
   real(dp), parameter :: delta_y = 200.0_dp
   type(contact_params) :: p
   type(egw_error), allocatable :: err
   type(loading_history) :: hist
   type(solve_result) :: peak, res
   real(dp) :: m, lo, hi, mid, r(n_r), pr(n_r), w(n_r), r_k, k_s(-40:40), d2, best, x_s
   integer :: k, it, j
   character(len=32) :: arg
   p = contact_params(model=model_egw, radius=810569.469138702_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   print '(a)', "       m  x_k(profile)       r_k  x_k(stiffness)       r_0  Hertz radius at m - x_k"
   do k = 1, command_argument_count()
      call get_command_argument(k, arg)
      read (arg, *) m
      r = [(40.0_dp*m*j/(n_r - 1), j = 0, n_r - 1)]
      lo = 190.0_dp
      hi = min(m, 215.0_dp)
      r_k = 0.0_dp
      do it = 1, 16
         mid = 0.5_dp*(lo + hi)
         if (opened(mid)) then
            hi = mid
         else
            lo = mid
         end if
      end do
      if (.not. opened(hi)) then
         print '(f8.2,a)', m, "  no separated annulus for x in [190, min(m, 215)]"
         cycle
      end if
      call load_history(p, solver_options(rel_tol=1.0e-9_dp, n_threads=1), m, hist, peak, err)
      if (allocated(err)) error stop "load_history failed"
      hist%options%rel_tol = 1.0e-8_dp
      do j = -40, 40
         call solve_unload(hist, m - (hi + 0.01_dp*j), res, err)
         if (allocated(err)) error stop "solve_unload failed"
         k_s(j) = res%stiffness
      end do
      best = 0.0_dp
      x_s = hi
      do j = -39, 39
         d2 = abs(k_s(j + 1) - 2.0_dp*k_s(j) + k_s(j - 1))
         if (d2 > best) then
            best = d2
            x_s = hi + 0.01_dp*j
         end if
      end do
      print '(f8.2,f14.4,f10.1,f16.2,f10.1,f12.1)', m, hi, r_k, x_s, &
         & sqrt(p%radius*(m - delta_y)), sqrt(p%radius*max(m - hi, 0.0_dp))
      flush (6)
   end do
contains
   !> Whether the total unloading pressure at x has a zero inside the contact (a zero
   !> followed farther out by a positive pressure); r_k its first radius.
   logical function opened(x)
      real(dp), intent(in) :: x
      integer :: i, i0
      call contact_profile_unload(p, solver_options(rel_tol=1.0e-7_dp, n_threads=1), m - x, &
         & m, r, pr, w, err)
      if (allocated(err)) error stop "contact_profile_unload failed"
      opened = .false.
      do i0 = 2, n_r
         if (pr(i0) <= 0.0_dp) exit
      end do
      do i = i0, n_r
         if (pr(i) > 0.0_dp) then
            opened = .true.
            r_k = r(i0)
            return
         end if
      end do
   end function opened
end program rough_cap_separation_kink
