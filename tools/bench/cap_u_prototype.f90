!> A prototype of the Hertz + cap table that stores the unloading force itself, u(s, m) =
!> P_unload(m - s L(m))/P(m) (doc/stability.md "Stop 49 (capl15)"), outside the library:
!> on the delta_max nodes, lengths L and s grid of the table egw builds (its curves'
!> grids), u and du/ds from solve_unload at every (m_j, s_i), cubic Hermite in s, cubic
!> Lagrange in m on the table's four-node stencils with 1/L interpolated as the table does,
!> P = P_load(m) sum w_k u_k(s). Measured as tools/bench/cap_local_error.f90 measures the
!> table (the same curves and overlaps, the same solves), side by side with it: does the
!> interpolation in m of u hold the local force where the gap's does not? And with the
!> solves' own residual overlap in place of the interpolated L (where the error is then)?
!>
!>   (build as tools/bench/cap_local_error.f90)
!>   OMP_NUM_THREADS=1 /tmp/cap_u_prototype 1e-3 10
program cap_u_prototype
   use egw, only: dp, contact_params, model_hertz, solver_options, solve_result, &
      & egw_error, hysteresis_table, build_hysteresis, hysteresis_eval, loading_history, &
      & load_history, solve_unload
   use egw_cap_sphere, only: cap_history, cap_result, cap_load
   use egw_rough_sphere, only: cap_solve_options
   implicit none
   integer, parameter :: n_fine(3) = [2, 4, 8]
   type(contact_params) :: p
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   type(loading_history) :: hist
   type(solve_result) :: peak, res
   real(dp), allocatable :: u(:, :), du(:, :), p_node(:)
   real(dp) :: dy, tol, top, m, d, lo, hi, f, k, state, f_u, f_x, e_gap, e_u, e_x, worst(4), &
      & band(6, 4), p_m, pm_solve, f_g, e_g, p_d, worst_fine(3)
   real(dp), allocatable :: m_fine(:, :), l_fine(:, :)
   integer :: q, nf
   integer :: j, i, n_m, n_s, b
   character(len=32) :: arg
   call get_command_argument(1, arg)
   read (arg, *) tol
   call get_command_argument(2, arg)
   read (arg, *) top
   dy = (acos(-1.0_dp)*1.0e9_dp/(2*1.0e11_dp))**2*1.0e-3_dp
   p = contact_params(model=model_hertz, radius=1.0e-3_dp, modulus=1.0e11_dp, &
      & flow_pressure=1.0e9_dp)
   call build_hysteresis(p, solver_options(n_threads=1), 0.0_dp, top*dy, tol, t, err)
   if (allocated(err)) stop 1
   n_m = size(t%m)
   n_s = size(t%s)
   allocate (u(n_s, n_m), du(n_s, n_m), p_node(n_m))
   do j = 1, n_m   ! the curves of u, solved at the table's nodes
      call load_history(p, solver_options(n_threads=1), t%m(j), hist, peak, err)
      if (allocated(err)) stop 1
      p_node(j) = peak%force
      do i = 1, n_s
         d = t%m(j) - t%s(i)*t%length(j)
         if (i == 1) d = t%m(j) - 1.0e-4_dp*t%length(j)   ! (the unloading branch's slope)
         call solve_unload(hist, d, res, err)
         if (allocated(err)) stop 1
         u(i, j) = max(res%force, 0.0_dp)/peak%force
         du(i, j) = -res%stiffness*t%length(j)/peak%force
      end do
      u(1, j) = 1.0_dp
      u(n_s, j) = 0.0_dp
   end do
   ! 1/L on k-fold finer delta_max grids (k = n_fine): the cap model's residual overlap
   ! (cap_load, as the build's cap_length) at every node, no unloading solve
   nf = (n_m - 1)*n_fine(size(n_fine)) + 1
   allocate (m_fine(nf, size(n_fine)), l_fine(nf, size(n_fine)))
   do q = 1, size(n_fine)
      do j = 1, (n_m - 1)*n_fine(q) + 1
         i = (j - 1)/n_fine(q) + 1
         if (i < n_m) then
            m_fine(j, q) = t%m(i) + (t%m(i + 1) - t%m(i))*mod(j - 1, n_fine(q))/n_fine(q)
         else
            m_fine(j, q) = t%m(n_m)
         end if
         l_fine(j, q) = m_fine(j, q) - residual(m_fine(j, q))
      end do
   end do
   worst_fine = 0
   print '(a,es8.1,a,i0,a,i0)', "Hertz + cap, rel_tol", tol, ": the table's grid ", n_m, &
      & " x ", n_s
   worst = 0
   band = 0
   do j = 1, 9   ! cap_local_error's curves and overlaps
      m = dy*(1.2_dp + (top - 1.3_dp)*(real(j, dp) - 0.377_dp)/9)
      call load_history(p, solver_options(rel_tol=1.0e-8_dp, n_threads=1), m, hist, &
         & peak, err)
      if (allocated(err)) stop 1
      lo = 0.0_dp
      hi = m
      do i = 1, 60
         d = 0.5_dp*(lo + hi)
         call solve_unload(hist, d, res, err)
         if (res%force > 0.0_dp) then
            hi = d
         else
            lo = d
         end if
      end do
      state = -huge(1.0_dp)
      call hysteresis_eval(t, m, state, p_m, k, i)   ! P_load(m) of the table
      pm_solve = peak%force
      do i = 1, 41
         d = hi + (m - hi)*10.0_dp**(-(i - 1)/10.0_dp)
         call solve_unload(hist, d, res, err)
         state = m
         call hysteresis_eval(t, d, state, f, k, b)
         f_u = p_m*u_eval(m, d, 0.0_dp)
         f_x = p_m*u_eval(m, d, 1.0_dp/(m - hi))
         state = -huge(1.0_dp)
         call hysteresis_eval(t, d, state, p_d, k, b)   ! P_load(delta)
         f_g = max(p_d - p_m*gap_eval(m, d, 1.0_dp/(m - hi)), 0.0_dp)
         e_g = abs(f_g - res%force)/max(res%force, 1.0e-3_dp*pm_solve)
         do q = 1, size(n_fine)
            worst_fine(q) = max(worst_fine(q), abs(p_m*u_eval(m, d, fine_inv_l(m, q)) - &
               & res%force)/max(res%force, 1.0e-3_dp*pm_solve))
         end do
         e_gap = abs(f - res%force)/max(res%force, 1.0e-3_dp*pm_solve)
         e_u = abs(f_u - res%force)/max(res%force, 1.0e-3_dp*pm_solve)
         e_x = abs(f_x - res%force)/max(res%force, 1.0e-3_dp*pm_solve)
         worst = max(worst, [e_gap, e_u, e_x, e_g])
         b = min(6, max(1, 1 + int(-log10(max(res%force/pm_solve, 1.0e-12_dp)))))
         band(b, :) = max(band(b, :), [e_gap, e_u, e_x, e_g])
      end do
   end do
   print '(a,4es10.2)', "  worst local: gap table, u, u with the solves' L(m), gap with it", &
      & worst
   print '(a,6es9.2)', "  gap table by decade of P/P(m):  ", band(:, 1)
   print '(a,6es9.2)', "  u prototype by decade of P/P(m):", band(:, 2)
   print '(a,6es9.2)', "  u, the solves' residual overlap:", band(:, 3)
   print '(a,6es9.2)', "  the gap, the solves' overlap:   ", band(:, 4)
   print '(a,3i3,a,3es10.2)', "  u, 1/L on grids", n_fine, " times finer in m:", worst_fine
contains
   !> u at (m, delta): the table's stencil and 1/L (or exact_inv_l where it is > 0: the
   !> map of the solves' own residual overlap), each curve's cubic Hermite at s.
   real(dp) function u_eval(m, delta, exact_inv_l) result(v)
      real(dp), intent(in) :: m, delta, exact_inv_l
      real(dp) :: w(4), inv_l, s, tt, h, val
      integer :: jj, first, kk, ll, ii
      jj = max(1, min(n_m - 1, count(t%m <= m)))
      first = min(max(jj - 1, 1), n_m - 3)
      do kk = 1, 4
         w(kk) = 1.0_dp
         do ll = 1, 4
            if (ll /= kk) w(kk) = w(kk)*(m - t%m(first + ll - 1))/ &
               & (t%m(first + kk - 1) - t%m(first + ll - 1))
         end do
      end do
      inv_l = sum(w/t%length(first:first + 3))
      if (exact_inv_l > 0.0_dp) inv_l = exact_inv_l
      s = min((m - delta)*inv_l, 1.0_dp)
      ii = max(1, min(n_s - 1, count(t%s <= s)))
      h = t%s(ii + 1) - t%s(ii)
      tt = (s - t%s(ii))/h
      v = 0.0_dp
      do kk = 1, 4
         ll = first + kk - 1
         val = (1 + 2*tt)*(1 - tt)**2*u(ii, ll) + tt*(1 - tt)**2*h*du(ii, ll) + &
            & tt*tt*(3 - 2*tt)*u(ii + 1, ll) + tt*tt*(tt - 1)*h*du(ii + 1, ll)
         v = v + w(kk)*val
      end do
      v = max(v, 0.0_dp)
   end function u_eval

   !> The cap model's residual overlap at m (cap_load on the cap solver's options).
   real(dp) function residual(m) result(d_r)
      real(dp), intent(in) :: m
      type(cap_history) :: h
      type(cap_result) :: r
      call cap_load(p%radius, p%modulus, p%flow_pressure, m, cap_solve_options(), h, r, err)
      if (allocated(err)) stop 1
      d_r = h%residual*h%delta_y
   end function residual

   !> 1/L at m, cubic Lagrange in m on the q-th finer grid (four-node stencils).
   real(dp) function fine_inv_l(m, q) result(v)
      real(dp), intent(in) :: m
      integer, intent(in) :: q
      real(dp) :: w(4)
      integer :: n, jj, first, kk, ll
      n = (n_m - 1)*n_fine(q) + 1
      jj = max(1, min(n - 1, count(m_fine(1:n, q) <= m)))
      first = min(max(jj - 1, 1), n - 3)
      do kk = 1, 4
         w(kk) = 1.0_dp
         do ll = 1, 4
            if (ll /= kk) w(kk) = w(kk)*(m - m_fine(first + ll - 1, q))/ &
               & (m_fine(first + kk - 1, q) - m_fine(first + ll - 1, q))
         end do
      end do
      v = sum(w/l_fine(first:first + 3, q))
   end function fine_inv_l

   !> The table's own gap at (m, delta) with the map of the solves' residual overlap
   !> (inv_l = 1/(m - delta_r)): its stencil, stored gaps and slopes, cubic Hermite in s.
   real(dp) function gap_eval(m, delta, inv_l) result(v)
      real(dp), intent(in) :: m, delta, inv_l
      real(dp) :: w(4), s, tt, h
      integer :: jj, first, kk, ll, ii
      jj = max(1, min(n_m - 1, count(t%m <= m)))
      first = min(max(jj - 1, 1), n_m - 3)
      do kk = 1, 4
         w(kk) = 1.0_dp
         do ll = 1, 4
            if (ll /= kk) w(kk) = w(kk)*(m - t%m(first + ll - 1))/ &
               & (t%m(first + kk - 1) - t%m(first + ll - 1))
         end do
      end do
      s = min((m - delta)*inv_l, 1.0_dp)
      ii = max(1, min(n_s - 1, count(t%s <= s)))
      h = t%s(ii + 1) - t%s(ii)
      tt = (s - t%s(ii))/h
      v = 0.0_dp
      do kk = 1, 4
         ll = first + kk - 1
         v = v + w(kk)*((1 + 2*tt)*(1 - tt)**2*t%gap(ii, ll) + &
            & tt*(1 - tt)**2*h*t%slope(ii, ll) + tt*tt*(3 - 2*tt)*t%gap(ii + 1, ll) + &
            & tt*tt*(tt - 1)*h*t%slope(ii + 1, ll))
      end do
   end function gap_eval
end program cap_u_prototype
