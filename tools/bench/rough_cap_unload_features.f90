!> The two features of the rough + cap unloading curves that make a hysteresis table's
!> delta_max grid dense just above the rough first yield when it is held to the local force
!> (doc/benchmarks.md "Stop 54: local20"), measured with the library's solves alone
!> (load_history at 1e-8, solve_unload at 1e-7; no table). README's rough + cap pair: R =
!> 810569.469138702, E* = 1, sigma = 1, mu 4, p_y = 0.01 (Hertz first yield delta_y =
!> 200 sigma; the rough first yield m_y ~ 198.2 sigma). Turning points m = M0, M0 + DM, ...
!> (N of them).
!>
!> 1. The front: P/P(m) at fixed overlaps delta (sigma) as m grows. Below ~210.7 sigma the
!>    end of the contact branch, delta_f(m), lies below delta = 0; where it passes, the
!>    force at that delta falls by decades within a few sigma of m.
!> 2. A kink at x ~ delta_y: P/P(m) at fixed unloading distances x = m - delta. The rough
!>    curves above first yield have a kink in their stiffness near x = delta_y (its cause
!>    not established: the smooth Hertz + cap curve from 230 sigma has none there); printed:
!>    the kink's x on curves
!>    at m = 206 and 230 (largest jump of the stiffness's slope on a 0.25 sigma grid).
!> 3. What that does to interpolation in m: the worst four-point Lagrange error at the
!>    midpoint of the middle interval, stencil spacing h, relative to max(P, 1e-3 P(m)) (the
!>    local-force check of the tables), at fixed delta (what a table's s amounts to near the
!>    front) and at fixed x, for m >= 206 sigma (both) and for m >= M0 (fixed delta).
!>
!> 4. A jump in m of the build's solves: P/P(m) at delta = 2.1221 sigma for m = 209.314 ...
!>    209.321 sigma, with the curve solves of a 1e-4 table (history 1e-7, unloading 1e-5,
!>    as local19's prototype) against 1e-9/1e-8: the error changes by 1.3e-4 of the local
!>    force between 209.3175 and 209.3180 (a discretisation switch), where a 1e-4 table's
!>    delta_max check splits an interval to the minimum width.
!> 5. The smooth cap model at the same x: the Hertz + cap curve from 230 sigma (model_hertz,
!>    the same p_y), its stiffness and the stiffness's increments every 0.5 sigma over x =
!>    197 ... 203 sigma (no kink there).
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/rough_cap_unload_features.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/rough_cap_unload_features
!>   OMP_NUM_THREADS=1 /tmp/rough_cap_unload_features 196 0.25 121   # M0, DM, N (sigma)
program rough_cap_unload_features
   use egw, only: dp, contact_params, model_egw, model_hertz, solver_options, solve_result, &
      & egw_error, loading_history, load_history, solve_unload
   implicit none
   integer, parameter :: n_d = 9, n_x = 7
   real(dp), parameter :: deltas(n_d) = [-2.0_dp, -1.5_dp, -1.0_dp, -0.5_dp, 0.0_dp, &
      & 1.0_dp, 2.0_dp, 4.0_dp, 8.0_dp]
   real(dp), parameter :: xs(n_x) = [190.0_dp, 195.0_dp, 198.0_dp, 200.0_dp, 201.0_dp, &
      & 202.0_dp, 203.0_dp]
   type(contact_params) :: p
   real(dp), allocatable :: m(:), u_d(:, :), u_x(:, :)
   real(dp) :: m0, dm
   integer :: n, i, k, step
   character(len=32) :: arg
   call get_command_argument(1, arg)
   read (arg, *) m0
   call get_command_argument(2, arg)
   read (arg, *) dm
   call get_command_argument(3, arg)
   read (arg, *) n
   p = contact_params(model=model_egw, radius=810569.469138702_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   allocate (m(n), u_d(n, n_d), u_x(n, n_x))
   do i = 1, n
      m(i) = m0 + (i - 1)*dm
      call curve_values(m(i), [deltas, m(i) - xs], u_d(i, :), u_x(i, :))
   end do

   print '(a)', "1. P/P(m) at fixed delta (sigma):"
   print '(a10,9f10.1)', "m", deltas
   do i = 1, n, max(1, nint(1.0_dp/dm))
      print '(f10.2,9es10.2)', m(i), u_d(i, :)
   end do
   print '(a)', "2. P/P(m) at fixed x = m - delta (sigma):"
   print '(a10,7f10.1)', "m", xs
   do i = 1, n, max(1, nint(2.0_dp/dm))
      print '(f10.2,7es10.2)', m(i), u_x(i, :)
   end do
   call kink_at(206.0_dp)
   call kink_at(230.0_dp)
   print '(a)', "3. worst 4-point Lagrange midpoint error in m / max(P, 1e-3 P(m)):"
   do step = 8, 2, -2
      if (step == 6) cycle
      print '(a,f5.2,a)', "  h = ", step*dm, " sigma, m >= 206:"
      print '(a,9es9.1)', "    fixed delta ", (worst(u_d(:, k), step, 206.0_dp), k = 1, n_d)
      print '(a,7es9.1)', "    fixed x     ", (worst(u_x(:, k), step, 206.0_dp), k = 1, n_x)
      print '(a,9es9.1)', "    fixed delta, m >= M0 ", (worst(u_d(:, k), step, m0), k = 1, n_d)
   end do
   call solve_jump()
   call smooth_cap(230.0_dp)
contains
   !> Part 5 (see the header).
   subroutine smooth_cap(mm)
      real(dp), intent(in) :: mm
      type(contact_params) :: h
      type(loading_history) :: hist
      type(solve_result) :: peak, res
      type(egw_error), allocatable :: err
      real(dp) :: k_prev, x
      integer :: j
      h = contact_params(model=model_hertz, radius=p%radius, modulus=p%modulus, &
         & flow_pressure=p%flow_pressure)
      call load_history(h, solver_options(rel_tol=1.0e-8_dp, n_threads=1), mm, hist, peak, &
         & err)
      if (allocated(err)) error stop "load_history failed (Hertz + cap)"
      hist%options%rel_tol = 1.0e-7_dp
      print '(a,f6.1,a)', "5. Hertz + cap from m = ", mm, ": x, stiffness, its increment"
      k_prev = 0.0_dp
      do j = 0, 12
         x = 197.0_dp + 0.5_dp*j
         call solve_unload(hist, mm - x, res, err)
         if (allocated(err)) error stop "solve_unload failed (Hertz + cap)"
         if (j > 0) print '(f10.2,2es14.5)', x, res%stiffness, res%stiffness - k_prev
         k_prev = res%stiffness
      end do
   end subroutine smooth_cap

   !> Part 4 (see the header).
   subroutine solve_jump()
      type(loading_history) :: hist
      type(solve_result) :: peak, res
      type(egw_error), allocatable :: err
      real(dp) :: tols(2, 2), v(2), mm
      integer :: j, q
      tols = reshape([1.0e-7_dp, 1.0e-5_dp, 1.0e-9_dp, 1.0e-8_dp], [2, 2])
      print '(a)', "4. P/P(m) at delta = 2.1221 sigma: build's solves (1e-7/1e-5), 1e-9/1e-8, "// &
         & "relative difference"
      do j = 0, 14
         mm = 209.314_dp + 0.0005_dp*j
         do q = 1, 2
            call load_history(p, solver_options(rel_tol=tols(1, q), n_threads=1), mm, hist, &
               & peak, err)
            if (allocated(err)) error stop "load_history failed"
            hist%options%rel_tol = tols(2, q)
            call solve_unload(hist, 2.1221_dp, res, err)
            if (allocated(err)) error stop "solve_unload failed"
            v(q) = res%force/peak%force
         end do
         print '(f12.4,2es20.12,es10.2)', mm, v, v(1)/v(2) - 1
      end do
   end subroutine solve_jump

   !> P/P(m) of the curve of turning point mm at the overlaps d (first n_d into a, the
   !> rest into b).
   subroutine curve_values(mm, d, a, b)
      real(dp), intent(in) :: mm, d(:)
      real(dp), intent(out) :: a(:), b(:)
      type(loading_history) :: hist
      type(solve_result) :: peak, res
      type(egw_error), allocatable :: err
      real(dp) :: v(size(d))
      integer :: j
      call load_history(p, solver_options(rel_tol=1.0e-8_dp, n_threads=1), mm, hist, peak, &
         & err)
      if (allocated(err)) error stop "load_history failed"
      hist%options%rel_tol = 1.0e-7_dp
      do j = 1, size(d)
         call solve_unload(hist, d(j), res, err)
         if (allocated(err)) error stop "solve_unload failed"
         v(j) = res%force/peak%force
      end do
      a = v(1:size(a))
      b = v(size(a) + 1:)
   end subroutine curve_values

   !> The unloading distance x of the largest jump of dK/ddelta on the curve of turning
   !> point mm, stiffness sampled every 0.25 sigma over x in [delta_y - 8, delta_y + 8].
   subroutine kink_at(mm)
      real(dp), intent(in) :: mm
      type(loading_history) :: hist
      type(solve_result) :: peak, res
      type(egw_error), allocatable :: err
      integer, parameter :: n_k = 65
      real(dp) :: x(n_k), k_s(n_k), jump, best
      integer :: j, at
      call load_history(p, solver_options(rel_tol=1.0e-8_dp, n_threads=1), mm, hist, peak, &
         & err)
      if (allocated(err)) error stop "load_history failed"
      hist%options%rel_tol = 1.0e-7_dp
      do j = 1, n_k
         x(j) = 192.0_dp + 0.25_dp*(j - 1)
         call solve_unload(hist, mm - x(j), res, err)
         if (allocated(err)) error stop "solve_unload failed"
         k_s(j) = res%stiffness
      end do
      best = 0.0_dp
      at = 2
      do j = 2, n_k - 1
         ! (the change of the stiffness's slope across node j, relative to the slope)
         jump = abs((k_s(j + 1) - k_s(j)) - (k_s(j) - k_s(j - 1)))/ &
            & max(abs(k_s(j + 1) - k_s(j - 1)), tiny(1.0_dp))
         if (mm - x(j + 1) > 0.0_dp .and. jump > best) then
            best = jump
            at = j
         end if
      end do
      print '(a,f7.1,a,f7.2,a,es9.2)', "   curve at m = ", mm, ": stiffness kink at x = ", &
         & x(at), " sigma, slope change/slope ", best
   end subroutine kink_at

   !> The worst Lagrange midpoint error of u(m) (nodes step samples apart) over m >= from.
   real(dp) function worst(u, step, from) result(e)
      real(dp), intent(in) :: u(:), from
      integer, intent(in) :: step
      real(dp) :: w, v, xm
      integer :: i0, a, b, idx(4), j
      e = 0.0_dp
      do i0 = 1, size(u) - 3*step
         idx = [i0, i0 + step, i0 + 2*step, i0 + 3*step]
         j = i0 + step + step/2
         xm = m(j)
         if (xm < from) cycle
         v = 0.0_dp
         do a = 1, 4
            w = 1.0_dp
            do b = 1, 4
               if (b /= a) w = w*(xm - m(idx(b)))/(m(idx(a)) - m(idx(b)))
            end do
            v = v + w*u(idx(a))
         end do
         e = max(e, abs(v - u(j))/max(u(j), 1.0e-3_dp))
      end do
   end function worst
end program rough_cap_unload_features
