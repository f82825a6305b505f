!> README's E-GW + cap table (as tools/bench/rough_cap_local_decompose.f90's: R =
!> 405284.734569351 effective, E* 1, sigma 1, mu 4, flow pressure 0.01, to 6 delta_y), built
!> at 1e-4 with the library's switches, one thread (doc/benchmarks.md "Stop 66: goal33").
!> Without arguments: its delta_max nodes in delta_y, n_s, max_error and the build's CPU.
!> With M DELTA (sigma, e.g. from a probe's "ref" line): the table's error there split into
!> the stencil curves' own error in s and the interpolation in delta_max. s is the table's
!> s of delta on m's interpolated map; on each stencil curve k (node m_k) at that s,
!> delta_k = m_k - x_k(s): the table there (a node: that curve alone) against a solve on
!> m_k's history at the build's curve tolerance, u = P/P(m_k). Prints the loading table's
!> own error at m (the table's force is P_load,table(m) u), per curve w_k, u_k and its
!> table's error, then sum w_k u_k against the solve at (m, delta) (the delta_max
!> interpolation of exact curves) and sum w_k (table error)_k, all over max(u, 1e-3).
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis_lengths.mod' | head -1))
!>   gfortran -O2 -fopenmp -ffree-line-length-none -I$B tools/bench/goal33_split.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/goal33_split
!>   OMP_NUM_THREADS=1 /tmp/goal33_split [M DELTA]
program goal33_split
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_egw
   use egw_rough_sphere, only: solver_options, solve_result, loading_history, load_history, &
      & solve_unload
   use egw_hysteresis, only: hysteresis_table, build_hysteresis, hysteresis_eval, first_yield
   use egw_hysteresis_data, only: turning_point, map_s, map_x, map_iota, max_stencil
   use egw_hysteresis_lengths, only: curve_options
   implicit none
   type(hysteresis_table) :: t
   type(contact_params) :: p
   type(solver_options) :: opt
   type(egw_error), allocatable :: err
   type(solve_result) :: peak, res
   type(loading_history) :: h
   real(dp) :: m, d, w(max_stencil), inv_span, f_m, knee, seg(7), s, dsdx, u_ex, scale, &
      & f, k, u_sum, e_sum, cpu(2)
   integer :: first, j
   p = contact_params(model=model_egw, radius=405284.734569351_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   call cpu_time(cpu(1))
   call build_hysteresis(p, solver_options(n_threads=1), 0.0_dp, 6*first_yield(p), 1e-4_dp, &
      & t, err)
   call cpu_time(cpu(2))
   if (allocated(err)) stop 1
   if (command_argument_count() < 2) then
      print '(a,f8.2,a,i0,a,i0,a,es10.3)', "build CPU", cpu(2) - cpu(1), " s, n_m ", &
         & size(t%m), ", n_s ", size(t%s), ", max_error ", t%max_error
      print '(a)', "m/delta_y:"
      print '(10f8.4)', t%m/first_yield(p)
      stop
   end if
   m = real_arg(1)
   d = real_arg(2)
   opt = curve_options(solver_options(), 1e-4_dp)
   call turning_point(t, m, first, w, inv_span, f_m, knee, seg)
   call map_s(t, m, knee, inv_span, m - d, s, dsdx)
   call loading_reference(m, f_m)
   call unload_at(m, d, u_ex)
   scale = max(u_ex, 1.0e-3_dp)
   call table_at(m, d, f)
   print '(a,f10.4,a,f10.4,a,f8.5,a,es10.3,a,es10.3)', "m", m, " delta", d, " s", s, &
      & " u", u_ex, " table error", (f - u_ex)/scale
   u_sum = 0.0_dp
   e_sum = 0.0_dp
   do j = 1, 4
      if (w(j) /= 0.0_dp) call one_curve(t%m(first + j - 1), t%knee(first + j - 1), w(j))
   end do
   print '(a,es10.3,a,es10.3)', "  delta_max interpolation of the solves", &
      & (u_sum - u_ex)/scale, ", the curves' s error weighted", e_sum/scale
contains
   !> command-line argument i as a real
   real(dp) function real_arg(i) result(v)
      integer, intent(in) :: i
      character(len=64) :: text
      call get_command_argument(i, text)
      read (text, *) v
   end function real_arg

   !> the loading table's error at m against a rel_tol 1e-8 history
   subroutine loading_reference(m, f_m)
      real(dp), intent(in) :: m, f_m
      type(loading_history) :: h_ref
      type(solve_result) :: peak_ref
      call load_history(p, solver_options(rel_tol=1.0e-8_dp, n_threads=1), m, h_ref, &
         & peak_ref, err)
      print '(a,es10.3)', "P_load,table(m)/P(m) - 1:", f_m/peak_ref%force - 1
   end subroutine loading_reference

   !> u = P/P(m) of a solve at delta after loading to m (the build's curve tolerance)
   subroutine unload_at(m, delta, u)
      real(dp), intent(in) :: m, delta
      real(dp), intent(out) :: u
      call load_history(p, opt, m, h, peak, err, t%loading_law, stiffness=.false.)
      call solve_unload(h, delta, res, err)
      u = res%force/peak%force
   end subroutine unload_at

   !> the table's u at delta after the turning point m: its force over P_load,table(m)
   subroutine table_at(m, delta, u)
      real(dp), intent(in) :: m, delta
      real(dp), intent(out) :: u
      real(dp) :: state, w_m(max_stencil), span_m, f_mm, knee_m, seg_m(7)
      integer :: first_m, stat
      state = m
      call hysteresis_eval(t, delta, state, u, k, stat)
      call turning_point(t, m, first_m, w_m, span_m, f_mm, knee_m, seg_m)
      u = u/f_mm
   end subroutine table_at

   !> stencil curve m_k (its knee, weight w_k) at the point's s: u solved and tabled
   subroutine one_curve(m_k, knee_k, w_k)
      real(dp), intent(in) :: m_k, knee_k, w_k
      real(dp) :: x_k, d_k, u_k, u_tab, dxds
      call map_x(t, m_k, knee_k, map_iota(t, m_k, knee_k), s, x_k, dxds)
      d_k = m_k - x_k
      call unload_at(m_k, d_k, u_k)
      call table_at(m_k, d_k, u_tab)
      print '(a,f10.4,a,f9.5,a,es10.3,a,es10.3)', "  curve m_k", m_k, " w", w_k, " u_k", &
         & u_k, " (table - solve)/scale", (u_tab - u_k)/scale
      u_sum = u_sum + w_k*u_k
      e_sum = e_sum + w_k*(u_tab - u_k)
   end subroutine one_curve
end program goal33_split
