!> Where the unloading force of an E-GW + cap contact rises, against the two-piece map's
!> knee (the smooth cap's residual overlap delta_r(m)); doc/benchmarks.md "Stop 52
!> (local18)". README's rough + cap numbers: R = 810569.469138702, E* = 1, sigma = 1,
!> mu 4, p_y = 0.01 (delta_y = 100 sigma). At every node above first yield of the 1e-4
!> table to TOP delta_y, on a rel_tol 1e-7 history: the overlaps d1, d2 where the
!> unloading force is 1e-3 and 4e-3 P(m) (bisected, 50 steps) and the front delta_f
!> where P^(2/3) through them (linear in delta for a (delta - delta_f)^(3/2) front, as
!> Hertz's) reaches 0; the same from 4e-3 and 1.6e-2 P(m) (the two differ by how far the
!> force is from the 3/2 law); P/P(m) at delta_f - 1 sigma (the asperity heights'
!> Gaussian foot below the front: positive, so a bisection on P > 0 finds the foot, not
!> the front, rough_cap_edge's "edge").
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -ffree-line-length-none -I$B tools/bench/rough_cap_front.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/rough_cap_front
!>   OMP_NUM_THREADS=1 /tmp/rough_cap_front 3    # TOP
program rough_cap_front
   use egw, only: dp, contact_params, model_egw, solver_options, solve_result, egw_error, &
      & loading_history, load_history, solve_unload, hysteresis_table, build_hysteresis
   implicit none
   type(contact_params) :: p
   type(egw_error), allocatable :: err
   type(loading_history) :: hist
   type(hysteresis_table) :: t
   type(solve_result) :: peak, res
   real(dp) :: m, lvl(3), dd(3), fr(2), top, foot
   integer :: j, k
   character(len=32) :: arg
   call get_command_argument(1, arg)
   read (arg, *) top
   p = contact_params(model=model_egw, radius=810569.469138702_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   call build_hysteresis(p, solver_options(), 0.0_dp, top*100.0_dp, 1.0e-4_dp, t, err)
   if (allocated(err)) stop 1
   lvl = [1.0e-3_dp, 4.0e-3_dp, 1.6e-2_dp]
   print '(a)', "  m/dy   knee/sigma  front/sigma (1e-3,4e-3)  (4e-3,1.6e-2)  front - knee" &
      & //"  d(1e-3 P(m)) - front  P/P(m) at front - 1 sigma"
   do j = 1, size(t%m)
      m = t%m(j)
      if (.not. t%knee(j) > 0.0_dp) cycle
      call load_history(p, solver_options(rel_tol=1.0e-7_dp, n_threads=1), m, hist, peak, err)
      if (allocated(err)) stop 2
      do k = 1, 3
         dd(k) = level(lvl(k)*peak%force)
      end do
      fr(1) = front(dd(1), dd(2), lvl(1), lvl(2))
      fr(2) = front(dd(2), dd(3), lvl(2), lvl(3))
      call solve_unload(hist, fr(1) - 1.0_dp, res, err)
      if (allocated(err)) stop 3
      foot = res%force/peak%force
      print '(f7.4,f11.3,f14.3,f16.3,f14.3,f16.3,es22.2)', m/100, t%knee(j), fr(1), fr(2), &
         & fr(1) - t%knee(j), dd(1) - fr(1), foot
   end do
contains
   !> The overlap below m where the unloading force is f (bisection on [-20 sigma, m]).
   real(dp) function level(f) result(d)
      real(dp), intent(in) :: f
      real(dp) :: lo, hi
      integer :: it
      lo = -20.0_dp
      hi = m
      do it = 1, 50
         d = 0.5_dp*(lo + hi)
         call solve_unload(hist, d, res, err)
         if (allocated(err)) stop 4
         if (res%force > f) then
            hi = d
         else
            lo = d
         end if
      end do
      d = hi
   end function level
   !> Where P^(2/3), linear through (d_a, l_a) and (d_b, l_b), reaches 0.
   pure real(dp) function front(d_a, d_b, l_a, l_b) result(d)
      real(dp), intent(in) :: d_a, d_b, l_a, l_b
      d = d_a - (d_b - d_a)*l_a**(2.0_dp/3)/(l_b**(2.0_dp/3) - l_a**(2.0_dp/3))
   end function front
end program rough_cap_front
