!> What a rough + cap table's node curves would err by near the force's front if they
!> stored another quantity on the same s nodes (issue 33 item 5; doc/benchmarks.md "Stop
!> 58: local24"). README's E-GW + cap table at TOL (as rough_cap_local_decompose.f90's)
!> is built; on each node curve above 1.01 delta_y its union s grid is taken, mapped to
!> x = m - delta by the table's two-piece map, and the curve solved there and at every
!> interval's middle (the build's curve solves: history at the curves' tolerance with the
!> build's ZMC law). On each interval (both ends x > 0) the cubic Hermite in x (the map is
!> linear on each piece, so this is the stored cubic in s) of three quantities, against
!> the middle's solve, relative to max(P, 1e-3 P(m)):
!>   gap: P_ext(delta) - P (what the table stores, over P_load(m)), slope K - K_ext,
!>   u:   P (over P_load(m): force_ratio's u), slope -K,
!>   ln:  ln P, slope -K/P (error |exp(cubic) - P|).
!> Worst and median per P/P(m) band of the middle. The gap row is the table's own s error
!> (the node curves' cubics on the union grid reproduce each curve's own).
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis_lengths.mod' | head -1))
!>   gfortran -O2 -fopenmp -ffree-line-length-none -I$B tools/bench/rough_cap_front_layout.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/rough_cap_front_layout
!>   OMP_NUM_THREADS=1 /tmp/rough_cap_front_layout 1e-4
program rough_cap_front_layout
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_egw
   use egw_rough_sphere, only: solver_options, solve_result, loading_history, load_history, &
      & solve_unload
   use egw_hysteresis, only: hysteresis_table, build_hysteresis, first_yield
   use egw_hysteresis_data, only: map_x, map_iota
   use egw_hysteresis_lengths, only: curve_options
   use egw_table, only: table_eval_tail_law
   implicit none
   integer, parameter :: n_band = 4, max_pts = 20000
   real(dp), parameter :: band_lo(n_band) = [0.1_dp, 0.01_dp, 0.003_dp, 0.001_dp]
   type(contact_params) :: p
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   type(loading_history) :: h
   type(solve_result) :: peak, res
   type(solver_options) :: opt
   real(dp) :: tol, dy, m, iota, dsdx, xm, pm, km, pe, ke, g(3), scale, w, t_mid, v
   real(dp), allocatable :: x(:), f(:), k(:), fe(:), kexp(:)
   real(dp) :: e(3, max_pts), frac(max_pts)
   integer :: j, i, n, ns, q
   character(len=32) :: arg
   call get_command_argument(1, arg)
   read (arg, *) tol
   p = contact_params(model=model_egw, radius=405284.734569351_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   dy = first_yield(p)
   call build_hysteresis(p, solver_options(n_threads=1), 0.0_dp, 6*dy, tol, t, err)
   if (allocated(err)) then
      print '(a)', "build failed: "//err%message
      stop 1
   end if
   opt = curve_options(solver_options(), tol)
   ns = size(t%s)
   print '(a,i0,a,i0,a,es9.2)', "table ", size(t%m), " x ", ns, ", curve solves at ", &
      & opt%rel_tol
   allocate (x(ns), f(ns), k(ns), fe(ns), kexp(ns))
   n = 0
   do j = 1, size(t%m)
      m = t%m(j)
      if (m <= 1.01_dp*dy) cycle
      call load_history(p, opt, m, h, peak, err, t%loading_law, stiffness=.false.)
      if (allocated(err)) stop 2
      iota = map_iota(t, m, t%knee(j))
      do i = 1, ns
         call map_x(t, m, t%knee(j), iota, t%s(i), x(i), dsdx)
         call solve_unload(h, m - x(i), res, err)
         if (allocated(err)) stop 3
         f(i) = res%force
         k(i) = res%stiffness
         call table_eval_tail_law(t%loading, m - x(i), fe(i), kexp(i))
      end do
      do i = 1, ns - 1
         if (.not. (x(i) > 0.0_dp .and. x(i + 1) > x(i))) cycle
         if (.not. (f(i) > 0.0_dp .and. f(i + 1) > 0.0_dp)) cycle
         call map_x(t, m, t%knee(j), iota, 0.5_dp*(t%s(i) + t%s(i + 1)), xm, dsdx)
         call solve_unload(h, m - xm, res, err)
         if (allocated(err)) stop 4
         pm = res%force
         km = res%stiffness
         call table_eval_tail_law(t%loading, m - xm, pe, ke)
         if (.not. pm >= 1.0e-3_dp*peak%force) cycle
         w = x(i + 1) - x(i)
         t_mid = (xm - x(i))/w
         scale = max(pm, 1.0e-3_dp*peak%force)
         ! (slopes in x = m - delta: dP/dx = -K)
         v = hermite(w, t_mid, fe(i) - f(i), k(i) - kexp(i), fe(i + 1) - f(i + 1), &
            & k(i + 1) - kexp(i + 1))
         g(1) = abs(v - (pe - pm))/scale
         v = hermite(w, t_mid, f(i), -k(i), f(i + 1), -k(i + 1))
         g(2) = abs(v - pm)/scale
         v = hermite(w, t_mid, log(f(i)), -k(i)/f(i), log(f(i + 1)), -k(i + 1)/f(i + 1))
         g(3) = abs(exp(v) - pm)/scale
         n = n + 1
         e(:, n) = g
         frac(n) = pm/peak%force
      end do
   end do
   print '(a,i0)', "interval middles with P >= 1e-3 P(m): ", n
   print '(a)', "band P/P(m) | n | worst gap, u, ln | median gap, u, ln"
   do i = 1, n_band
      v = 1.0_dp + 1.0e-9_dp
      if (i > 1) v = band_lo(i - 1)
      q = count(frac(1:n) >= band_lo(i) .and. frac(1:n) < v)
      if (q == 0) cycle
      print '(a,f6.3,a,f6.3,a,i5,a,3es9.2,a,3es9.2)', "  [", band_lo(i), ",", v, ")", q, &
         & " |", (maxval(e(j, 1:n), mask=frac(1:n) >= band_lo(i) .and. frac(1:n) < v), &
         & j = 1, 3), " |", (median(pack(e(j, 1:n), frac(1:n) >= band_lo(i) .and. &
         & frac(1:n) < v)), j = 1, 3)
   end do
contains
   pure real(dp) function hermite(width, s, fa, da, fb, db) result(r)
      real(dp), intent(in) :: width, s, fa, da, fb, db
      r = (1 + 2*s)*(1 - s)**2*fa + s*(1 - s)**2*width*da + s*s*(3 - 2*s)*fb + &
         & s*s*(s - 1)*width*db
   end function hermite

   real(dp) function median(y0) result(r)
      real(dp), intent(in) :: y0(:)
      real(dp) :: y(size(y0)), tmp
      integer :: a, b
      y = y0
      do a = 2, size(y)
         tmp = y(a)
         b = a - 1
         do while (b >= 1)
            if (y(b) <= tmp) exit
            y(b + 1) = y(b)
            b = b - 1
         end do
         y(b + 1) = tmp
      end do
      r = y((size(y) + 1)/2)
   end function median
end program rough_cap_front_layout
