!> Which stored quantity lets a rough + cap table's existing node layout meet the local
!> force near the unloading front (issue 33 item 5; doc/benchmarks.md "Stop 65: local31").
!> README's E-GW + cap table at TOL (as rough_cap_local_decompose.f90's: R = 405284.734569351
!> effective, sigma 1, mu 4, p_y 0.01, to 6 delta_y) is built for its delta_max nodes, knees,
!> two-piece map and loading table. Four representations r of a curve's unloading force P
!> (Ps = the curve's loading solve at m, Pt = the table's loading force at m, Pe = the
!> loading table with its tail at delta):
!>   gap: Pe(delta)/Pt(m) - P/Ps(m)  (today's, format 4)      force Pe(delta) - Pt(m) r
!>   u:   P/Ps(m)                     (format 5's force ratio) force Pt(m) r
!>   v:   u**(2/3)                    (a Hertzian front linear) force Pt(m) r**1.5
!>   ln:  ln u                        (an exponential tail linear) force Pt(m) e**r
!> (ii) On each node curve the build's s bisection is replayed (from the
!>   two-piece map's first nodes; cubic Hermite in x = m - delta on each piece; midpoint
!>   value and 1/4 width x slope mismatch in force units; min width 2**-11; at most 400
!>   nodes; no skips) for every representation under three criteria: "turn", rel_tol/4 of
!>   Ps(m) (today's for rough + cap, with Ps for Pt); "loc", rel_tol/4 of max(P_min, 1e-3
!>   Ps(m)) (P_min the smallest of the interval's ends' and middle's forces) where its
!>   largest is >= 5e-4 Ps(m), of Ps(m) on intervals wholly below that (local25's cut: the
!>   tail's solve noise); "goal", the smaller of turn's and rel_tol/2 of loc's scale (the
!>   goal, rel_tol of the local force, with a margin of 2). Each final interval is then
!>   solved at its quarter points: the error relative to max(P, 1e-3 Ps(m)) per P/Ps(m)
!>   band (points with P >= 1e-3 Ps(m)), curves above 1.01 delta_y; nodes and midpoint
!>   solves summed over those curves. The cubics are held to P Pt(m)/Ps(m) (a table's node
!>   values), the quarter points' errors taken against it.
!> (iii) At each delta_max midpoint above 1.01 delta_y, 12 overlaps graded as
!>   rough_cap_local_decompose's toward where the table's force is 1e-3 P(m): the four
!>   stencil node curves solved exactly at the overlap's s (the table's map, knee
!>   interpolated), each representation combined with the table's cubic Lagrange weights
!>   and taken back to a force, against the midpoint's own solve: the delta_max
!>   interpolation's error alone, relative to max(P, 1e-3 P(m)); a "mid" line per overlap
!>   (m/delta_y, delta/delta_y, P/P(m), the four errors). With both: also a "tot" line per
!>   overlap, the stencil curves' own fitted cubics of (ii) combined instead of their exact
!>   solves (what a table of each representation and criterion would serve there).
!> Curve solves as the build's (curve_options, its ZMC law, no stiffness in the history).
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis_lengths.mod' | head -1))
!>   gfortran -O2 -fopenmp -ffree-line-length-none -I$B tools/bench/local31_front_repr.f90 \
!>      $(find build -name libegw.a | head -1) -lfftw3_omp -lfftw3 -llapack -lblas \
!>      -o /tmp/local31_front_repr
!>   OMP_NUM_THREADS=1 /tmp/local31_front_repr 1e-4 [ii|iii|both|shape] [FRONT] [ZETA] \
!>      [LEVELS] [TOP]
!>
!> shape: on seven node curves, P/P(m), the local power K (delta - knee)/P and K/P at
!> delta = knee + (16 ... -16) sigma.
!> FRONT > 0: every node curve's knee (at s = 1/2 of the map) is moved from the smooth cap's
!> delta_r(m) to where that curve's own solve falls to FRONT Ps(m) (bisected on solves):
!> the curves then meet at matched relative positions across delta_max (0: the table's).
!> ZETA (default 1): (iii)'s cubic Lagrange weights taken in (m - m_1)**ZETA, m_1 the
!> first delta_max node (the rough first yield), instead of in m.
!> LEVELS > 0: (iii) only below TOP delta_y (default 1.3), on the table's delta_max grid with
!> its intervals there halved LEVELS times (the new nodes' knees the table's cubic Lagrange
!> of its knees).
program local31_front_repr
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_egw
   use egw_rough_sphere, only: solver_options, solve_result, loading_history, load_history, &
      & solve_unload
   use egw_hysteresis, only: hysteresis_table, build_hysteresis, hysteresis_eval, first_yield
   use egw_hysteresis_data, only: map_x, map_s, map_iota, s_knee, s_zero
   use egw_hysteresis_lengths, only: curve_options
   use egw_table, only: table_eval_tail_law
   implicit none
   integer, parameter :: n_rep = 4, n_crit = 3, n_band = 4, max_pts = 200000, &
      & max_memo = 20000, max_nodes = 400
   character(len=4), parameter :: rep_name(n_rep) = ["gap ", "u   ", "v   ", "ln  "], &
      & crit_name(n_crit) = ["turn", "loc ", "goal"]
   real(dp), parameter :: band_lo(n_band) = [0.1_dp, 0.01_dp, 0.003_dp, 0.0_dp], &
      & u_floor = 1.0e-30_dp
   type(contact_params) :: p
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   type(solver_options) :: opt
   real(dp) :: tol, dy
   character(len=8) :: what
   ! one curve's solves: s, P, K, Pe, Ke
   real(dp) :: memo(5, max_memo)
   integer :: n_memo
   ! the errors: (ii) per representation and criterion; (iii) per representation
   real(dp), allocatable :: e2(:, :, :), f2(:, :, :), e3(:, :), f3(:)
   integer :: n2(n_rep, n_crit), n3, nodes(n_rep, n_crit), solves(n_rep, n_crit), &
      & last_nodes(n_rep, n_crit)
   !> each node curve's final cubics of (ii) per representation and criterion: nodes s, x,
   !> r and dr/dx (the stored curve a table of that kind would hold)
   type :: curve_fit
      real(dp), allocatable :: s(:), x(:), r(:), d(:)
   end type curve_fit
   type(curve_fit), allocatable :: fits(:, :, :)
   !> (ii) + (iii): at the midpoints, the stencil's fitted cubics combined (a table of
   !> each representation and criterion), error / max(P, 1e-3 P(m))
   real(dp), allocatable :: e4(:, :, :)
   !> the two-piece map's knee per node curve: the table's (the smooth cap's delta_r) or,
   !> with FRONT, where the curve's own solve falls to FRONT Ps(m)
   real(dp), allocatable :: knee(:)
   real(dp) :: front
   !> the delta_max stencil's weights taken in (m - m_1)**zeta_power (m_1 the first node,
   !> the rough first yield; 1: the table's, in m)
   real(dp) :: zeta_power = 1.0_dp
   !> (iii) on a delta_max grid whose intervals below refine_top delta_y (TOP) are halved LEVELS
   !> times (the new nodes' knees the table's cubic Lagrange of its knees), only there
   integer :: levels = 0
   real(dp) :: refine_top = 1.3_dp
   character(len=32) :: arg
   call get_command_argument(1, arg)
   read (arg, *) tol
   what = "both"
   if (command_argument_count() >= 2) call get_command_argument(2, what)
   ! README's E-GW + cap scene (effective radius: egw-table's --radius is R1 + R2)
   p = contact_params(model=model_egw, radius=405284.734569351_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   dy = first_yield(p)
   opt = curve_options(solver_options(), tol)
   call build_hysteresis(p, solver_options(n_threads=1), 0.0_dp, 6*dy, tol, t, err)
   if (allocated(err)) error stop "the table's build failed"
   knee = t%knee
   front = 0.0_dp
   if (command_argument_count() >= 3) then
      call get_command_argument(3, arg)
      read (arg, *) front
      if (front > 0.0_dp) call front_knees()
   end if
   if (command_argument_count() >= 4) then
      call get_command_argument(4, arg)
      read (arg, *) zeta_power
   end if
   if (command_argument_count() >= 5) then
      call get_command_argument(5, arg)
      read (arg, *) levels
   end if
   if (command_argument_count() >= 6) then
      call get_command_argument(6, arg)
      read (arg, *) refine_top
   end if
   print '(a,i0,a,i0,a,es9.2,a,es10.3)', "table ", size(t%m), " x ", size(t%s), &
      & ", curve solves at ", opt%rel_tol, ", max_error ", t%max_error
   if (what == "shape") then
      call front_shape()
      stop
   end if
   if (what /= "iii") call node_curves()
   if (what /= "ii") call midpoints()
contains
   !> The front's shape on a few node curves: at delta = knee + y sigma, P/P(m), the local
   !> power n = K (delta - knee)/P (3/2 on a Hertzian front ending at the knee) and the
   !> decay rate K/P per sigma (constant on an exponential tail).
   subroutine front_shape()
      type(loading_history) :: h
      type(solve_result) :: peak
      real(dp), parameter :: y(14) = [16.0_dp, 8.0_dp, 4.0_dp, 2.0_dp, 1.0_dp, 0.5_dp, &
         & 0.25_dp, 0.0_dp, -0.5_dp, -1.0_dp, -2.0_dp, -4.0_dp, -8.0_dp, -16.0_dp]
      real(dp) :: q(5), d, s_of, dsdx
      integer :: j, i
      do j = 1, size(t%m)
         if (.not. any(abs(t%m(j)/dy - [1.0615_dp, 1.2574_dp, 1.767_dp, 2.7076_dp, &
            & 3.9619_dp, 4.1187_dp, 6.0_dp]) < 2.0e-3_dp)) cycle
         call load_history(p, opt, t%m(j), h, peak, err, t%loading_law, stiffness=.false.)
         if (allocated(err)) stop 10
         print '(a,f8.4,a,f9.3,a)', "shape m/dy ", t%m(j)/dy, ", knee ", knee(j), &
            & " sigma: y = delta - knee, s, P/P(m), n = K y/P, K/P"
         do i = 1, size(y)
            d = knee(j) + y(i)
            if (d >= t%m(j)) cycle
            call solve_at(h, d, q)
            call map_s(t, t%m(j), knee(j), map_iota(t, t%m(j), knee(j)), t%m(j) - d, s_of, &
               & dsdx)
            print '(a,f8.3,f9.5,es11.3,2f9.4)', "  ", y(i), s_of, q(2)/peak%force, &
               & q(3)*y(i)/max(q(2), tiny(1.0_dp)), q(3)/max(q(2), tiny(1.0_dp))
         end do
      end do
   end subroutine front_shape

   !> knee(j) = the overlap where node curve j's unloading solve is front Ps(m_j) (bisected
   !> on solves, kept in [0, 0.99 m_j]).
   subroutine front_knees()
      type(loading_history) :: h
      type(solve_result) :: peak, res
      real(dp) :: lo, hi, d
      integer :: j, it
      do j = 1, size(t%m)
         if (t%m(j) <= 0.0_dp) cycle
         call load_history(p, opt, t%m(j), h, peak, err, t%loading_law, stiffness=.false.)
         if (allocated(err)) stop 8
         lo = 0.0_dp
         hi = t%m(j)
         do it = 1, 40
            d = 0.5_dp*(lo + hi)
            call solve_unload(h, d, res, err)
            if (allocated(err)) stop 9
            if (res%force > front*peak%force) then
               hi = d
            else
               lo = d
            end if
         end do
         knee(j) = min(hi, 0.99_dp*t%m(j))
         if (hi == t%m(j)) knee(j) = 0.0_dp
         print '(a,f9.5,a,f10.5,a,f10.5)', "knee m/dy ", t%m(j)/dy, ": table's ", &
            & t%knee(j), ", front ", knee(j)
      end do
   end subroutine front_knees

   !> (ii): the s bisection replayed per representation and criterion on every node curve.
   subroutine node_curves()
      type(loading_history) :: h
      type(solve_result) :: peak
      real(dp) :: m, ps, pt, ke
      integer :: j, a, c, total_memo
      allocate (e2(max_pts, n_rep, n_crit), f2(max_pts, n_rep, n_crit))
      allocate (fits(size(t%m), n_rep, n_crit))
      n2 = 0
      nodes = 0
      solves = 0
      total_memo = 0
      do j = 1, size(t%m)
         m = t%m(j)
         call load_history(p, opt, m, h, peak, err, t%loading_law, stiffness=.false.)
         if (allocated(err)) stop 2
         ps = peak%force
         call table_eval_tail_law(t%loading, m, pt, ke)
         n_memo = 0
         do a = 1, n_rep
            do c = 1, n_crit
               call replay_curve(h, j, ps, pt, a, c)
            end do
         end do
         total_memo = total_memo + n_memo
         print '(a,f8.4,a,12i5,a,i6)', "curve m/dy ", m/dy, " nodes gap/u/v/ln x turn/loc/goal", &
            & ((count_nodes(a, c), c = 1, n_crit), a = 1, n_rep), "  distinct solves ", n_memo
      end do
      print '(a)', "(ii) node curves' s bisection replayed: nodes (sum over curves), " // &
         & "midpoint solves, quarter-point error / max(P, 1e-3 P(m)) worst (median) per band"
      do c = 1, n_crit
         do a = 1, n_rep
            call band_line("  "//crit_name(c)//" "//rep_name(a), e2(:, a, c), f2(:, a, c), &
               & n2(a, c), nodes(a, c), solves(a, c))
         end do
      end do
   end subroutine node_curves

   integer function count_nodes(a, c) result(k)
      integer, intent(in) :: a, c
      k = last_nodes(a, c)
   end function count_nodes

   !> One curve's s bisection for representation a under criterion c, then its quarter points.
   subroutine replay_curve(h, j, ps, pt, a, c)
      type(loading_history), intent(in) :: h
      integer, intent(in) :: j, a, c
      !> the curve's loading solve and the table's loading force at m: the table's curve
      !> holds P Pt/Ps (its force at m is Pt's), which the cubics are held to
      real(dp), intent(in) :: ps, pt
      real(dp) :: s(max_nodes), x(max_nodes), r(max_nodes), d(max_nodes), pf(max_nodes), &
         & s_mid, x_mid, r_mid, d_mid, p_mid, w, tq, v, dv, f_int, df_int, df_mid, scale, &
         & lo_f, e_val, iota, q(5), dsdx
      logical :: done(max_nodes), refined
      integer :: n, i, k
      iota = map_iota(t, t%m(j), knee(j))
      n = 6
      s(1:n) = [0.0_dp, 0.0625_dp, 0.25_dp, s_knee, s_zero, 1.0_dp]
      do i = 1, n
         call point(h, j, iota, s(i), q)
         call map_x(t, t%m(j), knee(j), iota, s(i), x(i), dsdx)
         call represent(a, q, ps, pt, r(i), d(i), pf(i))
      end do
      done = .false.
      do
         refined = .false.
         i = 1
         do while (i < n)
            if (done(i)) then
               i = i + 1
               cycle
            end if
            s_mid = 0.5_dp*(s(i) + s(i + 1))
            call point(h, j, iota, s_mid, q)
            call map_x(t, t%m(j), knee(j), iota, s_mid, x_mid, dsdx)
            if (t%m(j) > 1.01_dp*dy) solves(a, c) = solves(a, c) + 1
            call represent(a, q, ps, pt, r_mid, d_mid, p_mid)
            w = x(i + 1) - x(i)
            call hermite(w, (x_mid - x(i))/w, r(i), d(i), r(i + 1), d(i + 1), v, dv)
            call force_of(a, v, dv, q(4), -q(5), pt, f_int, df_int)
            df_mid = -q(3)*pt/ps
            e_val = max(abs(f_int - q(2)*pt/ps), 0.25_dp*w*abs(df_int - df_mid))
            scale = ps
            lo_f = min(pf(i), pf(i + 1), q(2))
            if (c >= 2 .and. max(pf(i), pf(i + 1), q(2)) >= 5.0e-4_dp*ps) &
               & scale = max(lo_f, 1.0e-3_dp*ps)
            if (c == 3) scale = min(ps, 2*scale)
            if (e_val > 0.25_dp*tol*scale .and. s(i + 1) - s(i) >= 2.0_dp**(-11) &
               & .and. n < max_nodes) then
               s(i + 2:n + 1) = s(i + 1:n)
               x(i + 2:n + 1) = x(i + 1:n)
               r(i + 2:n + 1) = r(i + 1:n)
               d(i + 2:n + 1) = d(i + 1:n)
               pf(i + 2:n + 1) = pf(i + 1:n)
               done(i + 2:n + 1) = done(i + 1:n)
               done(i:i + 1) = .false.
               s(i + 1) = s_mid
               x(i + 1) = x_mid
               r(i + 1) = r_mid
               d(i + 1) = d_mid
               pf(i + 1) = p_mid
               n = n + 1
               refined = .true.
               i = i + 1
            else
               done(i) = .true.
            end if
            i = i + 1
         end do
         if (.not. refined) exit
      end do
      last_nodes(a, c) = n
      fits(j, a, c)%s = s(1:n)
      fits(j, a, c)%x = x(1:n)
      fits(j, a, c)%r = r(1:n)
      fits(j, a, c)%d = d(1:n)
      ! (the statistics: curves above 1.01 delta_y, as the probes')
      if (.not. t%m(j) > 1.01_dp*dy) return
      nodes(a, c) = nodes(a, c) + n
      ! the quarter points of every final interval, against their own solves
      do i = 1, n - 1
         do k = 1, 2
            tq = merge(0.25_dp, 0.75_dp, k == 1)
            s_mid = s(i) + tq*(s(i + 1) - s(i))
            call point(h, j, iota, s_mid, q)
            call map_x(t, t%m(j), knee(j), iota, s_mid, x_mid, dsdx)
            if (.not. q(2) >= 1.0e-3_dp*ps) cycle
            w = x(i + 1) - x(i)
            call hermite(w, (x_mid - x(i))/w, r(i), d(i), r(i + 1), d(i + 1), v, dv)
            call force_of(a, v, dv, q(4), -q(5), pt, f_int, df_int)
            if (n2(a, c) == max_pts) cycle
            n2(a, c) = n2(a, c) + 1
            e2(n2(a, c), a, c) = abs(f_int - q(2)*pt/ps)/max(q(2), 1.0e-3_dp*ps)
            f2(n2(a, c), a, c) = q(2)/ps
         end do
      end do
   end subroutine replay_curve

   !> (iii): the delta_max interpolation alone at the midpoints, per representation.
   subroutine midpoints()
      type(loading_history), allocatable :: hs(:)
      type(loading_history) :: hm, empty
      type(solve_result) :: peak, res
      real(dp), allocatable :: ps(:), pt(:), mg(:), kg(:)
      real(dp) :: m, wts(4), knee_m, iota, d_end, d, sv, dsdx, xj, &
         & q(5), rj(4, n_rep), v, dv, pe, ke, ptm, fi, dfi, pm
      integer :: j, i, l, a, c, first, nm
      call refined_grid(mg, kg)
      nm = size(mg)
      allocate (hs(nm), ps(nm), pt(nm))
      allocate (e3(max_pts, n_rep), f3(max_pts), e4(max_pts, n_rep, n_crit))
      ps = 0.0_dp
      n3 = 0
      do j = 1, nm - 1
         m = 0.5_dp*(mg(j) + mg(j + 1))
         if (m <= 1.01_dp*dy .or. mg(j) <= 1.01_dp*dy) cycle
         if (levels > 0 .and. mg(j + 1) > refine_top*dy) exit
         first = min(max(j - 1, 1), nm - 3)
         do l = 1, first - 1
            if (ps(l) > 0.0_dp) then
               hs(l) = empty
               ps(l) = 0.0_dp
            end if
         end do
         do l = first, first + 3
            if (ps(l) > 0.0_dp) cycle
            call load_history(p, opt, mg(l), hs(l), peak, err, t%loading_law, &
               & stiffness=.false.)
            if (allocated(err)) stop 5
            ps(l) = peak%force
            call table_eval_tail_law(t%loading, mg(l), pt(l), ke)
         end do
         do l = 1, 4
            wts(l) = lagrange((mg(first:first + 3) - mg(1))**zeta_power, l, &
               & (m - mg(1))**zeta_power)
         end do
         knee_m = min(max(sum(wts*kg(first:first + 3)), 0.0_dp), 0.99_dp*m)
         iota = map_iota(t, m, knee_m)
         call load_history(p, opt, m, hm, peak, err, t%loading_law, stiffness=.false.)
         if (allocated(err)) stop 6
         pm = peak%force
         call table_eval_tail_law(t%loading, m, ptm, ke)
         d_end = table_front(m, 1.0e-3_dp*pm)
         do i = 1, 12
            d = m - (m - d_end)*(1.0_dp - (1.0_dp - i/12.0_dp)**2)
            call solve_unload(hm, d, res, err)
            if (allocated(err)) stop 7
            call map_s(t, m, knee_m, iota, m - d, sv, dsdx)
            sv = min(sv, 1.0_dp)
            do l = 1, 4
               call map_x(t, mg(first + l - 1), kg(first + l - 1), &
                  & map_iota(t, mg(first + l - 1), kg(first + l - 1)), sv, xj, dsdx)
               call solve_at(hs(first + l - 1), mg(first + l - 1) - xj, q)
               do a = 1, n_rep
                  call represent(a, q, ps(first + l - 1), pt(first + l - 1), rj(l, a), dv, fi)
               end do
            end do
            call table_eval_tail_law(t%loading, d, pe, ke)
            n3 = n3 + 1
            f3(n3) = res%force/pm
            do a = 1, n_rep
               v = sum(wts*rj(:, a))
               call force_of(a, v, 0.0_dp, pe, ke, ptm, fi, dfi)
               e3(n3, a) = abs(fi - res%force)/max(res%force, 1.0e-3_dp*pm)
            end do
            print '(a,f9.5,f10.5,es10.2,4es10.2)', "mid ", m/dy, d/dy, f3(n3), e3(n3, :)
            if (allocated(fits) .and. levels == 0) then
               do a = 1, n_rep
                  do c = 1, n_crit
                     v = 0.0_dp
                     do l = 1, 4
                        v = v + wts(l)*fit_value(fits(first + l - 1, a, c), sv)
                     end do
                     call force_of(a, v, 0.0_dp, pe, ke, ptm, fi, dfi)
                     e4(n3, a, c) = abs(fi - res%force)/max(res%force, 1.0e-3_dp*pm)
                  end do
               end do
               print '(a,f9.5,f10.5,es10.2,12es10.2)', "tot ", m/dy, d/dy, f3(n3), &
                  & ((e4(n3, a, c), c = 1, n_crit), a = 1, n_rep)
            end if
         end do
      end do
      print '(a)', "(iii) delta_max interpolation alone at the midpoints (exact stencil " // &
         & "solves at the overlap's s): error / max(P, 1e-3 P(m)) worst (median) per band"
      do a = 1, n_rep
         call band_line("  "//rep_name(a), e3(:, a), f3, n3, 0, 0)
      end do
      if (.not. (allocated(fits) .and. levels == 0)) return
      print '(a)', "(ii) + (iii) at the midpoints: the stencil curves' fitted cubics of (ii) " // &
         & "combined (a table of that representation and criterion), worst (median) per band"
      do c = 1, n_crit
         do a = 1, n_rep
            call band_line("  "//crit_name(c)//" "//rep_name(a), e4(:, a, c), f3, n3, 0, 0)
         end do
      end do
   end subroutine midpoints

   !> A fitted curve's cubic Hermite value at s (in x: the map is linear on each piece,
   !> whose breaks are nodes).
   real(dp) function fit_value(fit, s) result(v)
      type(curve_fit), intent(in) :: fit
      real(dp), intent(in) :: s
      integer :: lo, hi, mid
      real(dp) :: w, xs, dv
      lo = 1
      hi = size(fit%s)
      do while (hi - lo > 1)
         mid = (lo + hi)/2
         if (fit%s(mid) <= s) then
            lo = mid
         else
            hi = mid
         end if
      end do
      ! (x at s by the linear map on the interval)
      xs = fit%x(lo) + (s - fit%s(lo))/(fit%s(lo + 1) - fit%s(lo))*(fit%x(lo + 1) - fit%x(lo))
      w = fit%x(lo + 1) - fit%x(lo)
      call hermite(w, (xs - fit%x(lo))/w, fit%r(lo), fit%d(lo), fit%r(lo + 1), &
         & fit%d(lo + 1), v, dv)
   end function fit_value

   !> The table's delta_max nodes and knees, intervals below refine_top delta_y halved
   !> levels times.
   subroutine refined_grid(mg, kg)
      real(dp), allocatable, intent(out) :: mg(:), kg(:)
      real(dp), allocatable :: add(:)
      real(dp) :: w(4)
      integer :: lev, j, f, l, nm
      mg = t%m
      kg = knee
      nm = size(t%m)
      do lev = 1, levels
         ! (each interval below refine_top delta_y gets its middle, in order)
         add = [mg(1)]
         do j = 1, size(mg) - 1
            if (0.5_dp*(mg(j) + mg(j + 1)) < refine_top*dy) add = [add, 0.5_dp*(mg(j) + &
               & mg(j + 1))]
            add = [add, mg(j + 1)]
         end do
         mg = add
      end do
      deallocate (kg)
      allocate (kg(size(mg)))
      do j = 1, size(mg)
         f = findloc(t%m, mg(j), 1)
         if (f > 0) then
            kg(j) = knee(f)
            cycle
         end if
         f = count(t%m <= mg(j))
         f = min(max(f - 1, 1), nm - 3)
         do l = 1, 4
            w(l) = lagrange(t%m(f:f + 3), l, mg(j))
         end do
         kg(j) = min(max(sum(w*knee(f:f + 3)), 0.0_dp), 0.99_dp*mg(j))
      end do
   end subroutine refined_grid


   !> The curve's solve at s (memo: s, P, K, Pe, Ke); s = 0 takes its slope at s = 1e-4.
   subroutine point(h, j, iota, s, q)
      type(loading_history), intent(in) :: h
      integer, intent(in) :: j
      real(dp), intent(in) :: iota, s
      real(dp), intent(out) :: q(5)
      real(dp) :: x, dsdx, q0(5)
      integer :: i
      do i = 1, n_memo
         if (memo(1, i) == s) then
            q = memo(:, i)
            return
         end if
      end do
      call map_x(t, t%m(j), knee(j), iota, s, x, dsdx)
      call solve_at(h, t%m(j) - x, q)
      if (s == 0.0_dp) then
         call map_x(t, t%m(j), knee(j), iota, 1.0e-4_dp, x, dsdx)
         call solve_at(h, t%m(j) - x, q0)
         q(3) = q0(3)
      end if
      q(1) = s
      if (n_memo < max_memo) then
         n_memo = n_memo + 1
         memo(:, n_memo) = q
      end if
   end subroutine point

   !> [., P, K, Pe, Ke] at delta on history h.
   subroutine solve_at(h, delta, q)
      type(loading_history), intent(in) :: h
      real(dp), intent(in) :: delta
      real(dp), intent(out) :: q(5)
      type(solve_result) :: res
      call solve_unload(h, delta, res, err)
      if (allocated(err)) then
         print '(a,es12.4,a)', "solve failed at ", delta, ": "//err%message
         stop 3
      end if
      q(1) = 0.0_dp
      q(2) = max(res%force, 0.0_dp)
      q(3) = res%stiffness
      call table_eval_tail_law(t%loading, delta, q(4), q(5))
   end subroutine solve_at

   !> Representation a of solve q at x = m - delta: value r, dr/dx, and the force.
   subroutine represent(a, q, ps, pt, r, dr, force)
      integer, intent(in) :: a
      real(dp), intent(in) :: q(5), ps, pt
      real(dp), intent(out) :: r, dr, force
      real(dp) :: u
      force = q(2)
      u = max(q(2)/ps, u_floor)
      select case (a)
      case (1)
         r = q(4)/pt - q(2)/ps
         dr = -q(5)/pt + q(3)/ps
      case (2)
         r = q(2)/ps
         dr = -q(3)/ps
      case (3)
         r = u**(2.0_dp/3.0_dp)
         dr = -(2.0_dp/3.0_dp)*u**(-1.0_dp/3.0_dp)*q(3)/ps
         if (q(2)/ps < u_floor) dr = 0.0_dp
      case default
         r = log(u)
         dr = -q(3)/max(q(2), u_floor*ps)
         if (q(2)/ps < u_floor) dr = 0.0_dp
      end select
   end subroutine represent

   !> The force (and dP/dx) of representation a's value v (dv/dx) at an overlap whose
   !> loading table force is pe (dPe/dx = dpe), the turning point's force pt (the unit).
   pure subroutine force_of(a, v, dv, pe, dpe, pt, f, df)
      integer, intent(in) :: a
      real(dp), intent(in) :: v, dv, pe, dpe, pt
      real(dp), intent(out) :: f, df
      real(dp) :: vv
      select case (a)
      case (1)
         f = pe - pt*v
         df = dpe - pt*dv
      case (2)
         f = pt*v
         df = pt*dv
      case (3)
         vv = max(v, 0.0_dp)
         f = pt*vv**1.5_dp
         df = pt*1.5_dp*sqrt(vv)*dv
      case default
         f = pt*exp(min(v, 0.5_dp))
         df = f*dv
      end select
      f = max(f, 0.0_dp)
   end subroutine force_of

   pure subroutine hermite(width, s, fa, da, fb, db, v, dv)
      real(dp), intent(in) :: width, s, fa, da, fb, db
      real(dp), intent(out) :: v, dv
      v = (1 + 2*s)*(1 - s)**2*fa + s*(1 - s)**2*width*da + s*s*(3 - 2*s)*fb + &
         & s*s*(s - 1)*width*db
      dv = 6*s*(s - 1)/width*(fa - fb) + (1 - s)*(1 - 3*s)*da + s*(3*s - 2)*db
   end subroutine hermite

   pure real(dp) function lagrange(nodes, k, x) result(w)
      real(dp), intent(in) :: nodes(4), x
      integer, intent(in) :: k
      integer :: l
      w = 1.0_dp
      do l = 1, 4
         if (l /= k) w = w*(x - nodes(l))/(nodes(k) - nodes(l))
      end do
   end function lagrange

   subroutine band_line(label, e, f, n, n_nodes, n_solves)
      character(len=*), intent(in) :: label
      real(dp), intent(in) :: e(:), f(:)
      integer, intent(in) :: n, n_nodes, n_solves
      integer :: b, cnt
      real(dp) :: hi_b
      logical :: sel(n)
      character(len=400) :: line
      write (line, '(a,a,i6,a,i6,a)') label, " nodes", n_nodes, " mid solves", n_solves, " |"
      do b = 1, n_band
         hi_b = 1.0_dp + 1.0e-9_dp
         if (b > 1) hi_b = band_lo(b - 1)
         sel = f(1:n) >= band_lo(b) .and. f(1:n) < hi_b
         cnt = count(sel)
         if (cnt == 0) cycle
         write (line, '(a,i5,es9.2,a,es8.1,a)') trim(line), cnt, maxval(e(1:n), mask=sel), &
            & " (", median(pack(e(1:n), sel)), ") |"
      end do
      print '(a)', trim(line)
   end subroutine band_line

   !> The median (the ((n + 1)/2)-th smallest) of y, by counting: a few hundred values.
   real(dp) function median(y) result(r)
      real(dp), intent(in) :: y(:)
      integer :: i, rank
      rank = (size(y) + 1)/2
      r = y(1)
      do i = 1, size(y)
         if (count(y < y(i)) < rank .and. count(y <= y(i)) >= rank) then
            r = y(i)
            return
         end if
      end do
   end function median

   !> The overlap below m where the table's force on the curve unloading from m falls to
   !> level (bisected between -3 sigma and m).
   real(dp) function table_front(m, level) result(d)
      real(dp), intent(in) :: m, level
      real(dp) :: below, above, f, k, state
      integer :: stat
      below = -3.0_dp
      above = m
      do while (above - below > 1.0e-12_dp*m)
         d = 0.5_dp*(below + above)
         state = m
         call hysteresis_eval(t, d, state, f, k, stat)
         if (f > level) above = d
         if (.not. f > level) below = d
      end do
      d = above
   end function table_front
end program local31_front_repr
