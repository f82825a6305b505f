!> The unloading curves of a hysteresis build, one per turning point m: the curve in s
!> (its map, first nodes, the gap or log-ratio of its solves at each s), bisected in s to
!> rel_tol/4 (refine_curve) with its Hermite midpoint estimate, solved in parallel over the
!> curves (build_curves, verify_curves), and evaluated between its nodes (curve_eval).
!> doc/theory.md §8.
module egw_hysteresis_curves
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_not_converged, fatal_error, format_real, first_failure
   use egw_rough_sphere, only: solver_options, solve_result, loading_history, load_history, &
      & solve_unload, unload_start, history_residual
   use egw_table, only: table_eval, table_eval_tail_law
   use egw_hysteresis_data, only: hysteresis_table, s_knee, s_zero, map_x, map_piece, &
      & map_iota, map_lengths, edge_breaks, edge_xi, edge_segment, max_log_ratio
   use egw_hysteresis, only: first_yield
   use egw_hysteresis_lengths, only: rough_length, cap_length, log_table, curve_options, &
      & unloading_length
   implicit none
   private

   public :: unloading_curve, min_width, unloading_lengths, build_curves, verify_curves, &
      & curve_offset, curve_eval, local_weight

   !> Most nodes in s of one unloading curve.
   integer, parameter :: max_s_nodes = 400
   !> The first s nodes of every curve (bisection adds nodes between them); with the
   !> two-piece map (mapped) its breaks s_knee = 1/2 and s_zero = 3/4 too.
   real(dp), parameter :: first_nodes(5) = [0.0_dp, 0.0625_dp, 0.25_dp, 0.5_dp, 1.0_dp], &
      & mapped_first_nodes(6) = [0.0_dp, 0.0625_dp, 0.25_dp, s_knee, s_zero, 1.0_dp], &
      & tail_first_nodes(7) = [0.0_dp, s_zero, s_zero + 0.25_dp*0.0625_dp, &
      & s_zero + 0.25_dp*0.125_dp, s_zero + 0.25_dp*0.25_dp, s_zero + 0.25_dp*0.5_dp, 1.0_dp]
   !> The first s nodes of a log-ratio curve: the edge map's breaks 1/2, 3/4, 1 among them
   !> (no interval straddles one).
   real(dp), parameter :: first_log_nodes(7) = [0.0_dp, 0.0625_dp, 0.25_dp, 0.5_dp, &
      & 0.625_dp, 0.75_dp, 1.0_dp]
   !> Log-ratio curves: both bisections weigh a mismatch in h (the relative error of the
   !> force) by min(1, P/(local_floor P(m))): the tolerance holds relative to the local
   !> force down to local_floor of the turning point's, and relative to that below.
   real(dp), parameter :: local_floor = 1.0e-3_dp
   !> Rough + cap tables' u curves (u = P/P_load(m) on the two-piece map): both
   !> bisections weigh a mismatch in u by local_weight(u, c) = max(1, 1/(c max(u,
   !> local_floor))) from u >= local_cut (1 below: the weight would chase the last tail
   !> where the force has all but vanished), so that the table holds rel_tol relative to
   !> the local force down to local_floor P(m) (issue 33 item 5): refine_curve's s
   !> bisection, whose bound is rel_tol/4, with c = s_share (the local force's rel_tol/2);
   !> refine_m's check across delta_max (stencil_mismatch), whose bound is rel_tol less
   !> the stencil's s errors, with c = m_share, and its skips alike (hysteresis_grid's
   !> skip_weight: unweighted, the skip's estimate in u cleared every check node near the
   !> front, where u ~ 1e-3). Measured on README's E-GW + cap table at 1e-4 against 5808
   !> rel_tol 1e-8 solves down to 1e-3 P(m): every P/P(m) band's worst 9.6e-5 of the
   !> local force, unweighted 2.1e-2; m_share 2 left 1.1e-4, 4 2.0e-4 (doc/benchmarks.md
   !> "Stop 66: goal33").
   real(dp), parameter :: s_share = 2.0_dp, local_cut = 5.0e-4_dp
   !> u curves: s intervals narrower than this are bisected on the tolerance relative to
   !> P(m) only. Near the knee the unloading solves (at hysteresis_solve_tol, relative to
   !> P(m)) scatter by ~4e-7 P(m) with their start: on README's GW + cap table at 1e-4 two
   !> solves at one overlap gave u = 1.20302e-3 and 1.20345e-3, 3.6e-4 of the local force,
   !> and the weighted bisection split that interval to zero width and failed ("needs
   !> more than 400 nodes"; doc/benchmarks.md "Stop 67: onset33"). README's E-GW + cap
   !> table's finest s interval is 2^-13: this floor leaves it as it is.
   real(dp), parameter :: u_min_width = 2.0_dp**(-14)
   !> u curves: their histories at this fraction of the curve solves' rel_tol. On
   !> README's GW + cap table at 1e-4 a history at rel_tol/100 (1e-6, its field at 1e-7,
   !> force estimate 9e-9) put the unloading force at 1.09 delta_y, u = 1e-3 .. 3e-3, off
   !> by 2.7e-7 P(m), 1.2e-4 of the local force (5e-7, 3e-7: 1.1e-4; 2e-7: 1.4e-5; 1e-7:
   !> 8e-7); at rel_tol/1000 every band of its table is within 5.3e-5 of the local force
   !> (E-GW + cap: as at rel_tol/100; 1.1x the build's CPU on both; doc/benchmarks.md
   !> "Stop 68: gw34"). (Until egw_sphere_refine confirmed classic GW's first refinement
   !> level, that table's refine_m did not settle with them: the knee's 3.6e-4 errors.)
   real(dp), parameter :: hist_share = 1.0e-2_dp
   real(dp), parameter, public :: m_share = 1.5_dp
   !> Intervals (in s, or in delta_max relative to the grid's range) narrower than this
   !> are not split: at the residual-overlap edge of deep curves (dh/ds ~ 100) curves
   !> 1e-5 sigma apart differed by 3 % of the local force, the solves' own noise there
   !> (doc/benchmarks.md, local4 (e)).
   real(dp), parameter :: min_width = 2.0_dp**(-11)
   !> Log-ratio curves: an s interval is not solved at its middle where the cubic Hermite
   !> there lies within midpoint_skip of the bisection's bound rel_tol/4 of the quintic
   !> Hermite through it and a neighbouring node (each side that has one, the larger
   !> difference, weighted by the larger of its ends' weights; midpoint_estimate): an
   !> embedded estimate, accepted without the solve whose only use would have been to
   !> accept it. egw-bench's table at 1e-4: 856 of 1954 midpoint solves fewer, the same
   !> grid (no interval that the solve splits was skipped; the largest error among the
   !> skipped 0.68 of rel_tol/4); at 0.5 eight intervals that the solves split were
   !> skipped, up to 2.2 of rel_tol/4 (doc/benchmarks.md, stop 48).
   real(dp), parameter :: midpoint_skip = 0.3_dp
   !> Gap curves (rough + cap): an s interval is not solved at its middle where the cubic
   !> there lies within gap_skip of the bisection's bound rel_tol/4 of the quintic Hermite
   !> through it and a neighbouring node on its piece of the map (gap_estimate), unless an
   !> end is a first node (s = 0, whose slope is taken at 1e-4; the map's breaks, where the
   !> curves bend most): an embedded estimate, as midpoint_skip's. Or, on a promoted
   !> check curve, where the larger of that estimate and the mismatches both its
   !> neighbours in delta_max accepted on the same interval lies within neighbour_skip of
   !> the bound. Either alone misjudged: README's rough + cap scenes at 1e-4 (E-GW, GW,
   !> EP-GW psi 1; every midpoint solved and compared) had intervals the quintic put
   !> within 0.1 of the bound and the solve at 1.6-1.7 of it (all at a first node), and
   !> intervals both neighbours accepted within 0.3 of it whose solve missed by up to 1.7
   !> (one neighbour's midpoint can meet its cubic by chance); the two rules together
   !> cleared 181, 105 and 251 midpoints of 1122, 539 and 1655, none that the solve would
   !> have split, the largest of their solves' mismatches 0.37, 0.81 and 0.33 of the bound
   !> (doc/benchmarks.md, stop 60: grid26). neighbour_skip 0.3 (stop 63, node29, on the
   !> grids of refine_m's split on gap_bound, the same audit): 199, 108 and 308 of 1055,
   !> 515 and 1591 cleared, none that the solve would split, largest 0.37, 0.81 and 0.77;
   !> ~2 % fewer solves.
   real(dp), parameter :: gap_skip = 0.1_dp, neighbour_skip = 0.3_dp
   !> Ratios below this are stored as 0 (far below every tolerance, far above subnormals).
   real(dp), parameter :: tiny_ratio = 1.0e-100_dp

   !> The unloading curve of one delta_max node during the build: g and dg/ds at nodes s,
   !> and what its solves need (start_curve): a check curve (a midpoint of refine_m,
   !> solved at its neighbours' nodes) is bisected in s (refine_curve) only when it
   !> becomes a node.
   type :: unloading_curve
      real(dp) :: length = 0.0_dp   !< L(m) = 1.5 P_load(m)/K_unload(m)
      real(dp), allocatable :: s(:), gap(:), slope(:)
      real(dp) :: m = 0.0_dp        !< its turning point
      real(dp) :: span = 0.0_dp     !< s_max L: delta = m - s span (the first piece's)
      !> the two-piece map's knee delta_r(m) (mapped; 0 else) and, per piece, (ds/dx of
      !> the first piece)/(ds/dx of the piece): the stored slope times it is dg/ds there
      real(dp) :: knee = 0.0_dp, piece_scale(3) = 1.0_dp
      real(dp) :: scale = 1.0_dp    !< the loading table's force at m (g's unit)
      real(dp) :: c_turn = 1.0_dp   !< the solve's force at m over scale
      logical :: verified = .false. !< bisected in s to rel_tol/4 (refine_curve)
      !> refine_curve's largest accepted mismatch: its cubics' error in s (max_error's
      !> share from the s direction, gap_bound)
      real(dp) :: worst = 0.0_dp
      !> per s interval, the mismatch refine_curve accepted there (measured, or the
      !> estimate that cleared it: gap_skip, neighbour_skip)
      real(dp), allocatable :: mismatch(:)
      !> h = ln(c P_ext/P) at s of the edge map xi (edge_breaks of length), slopes as
      !> dh/d(m - delta) (the table's log_ratio); else the gap, slopes dg/ds
      logical :: log = .false.
      real(dp) :: xi(3) = 0.0_dp
      real(dp) :: p_turn = 0.0_dp   !< the solve's force at m (log: the weights' unit)
      !> per node the mismatch's weight (gap_at): min(1, P/(local_floor P(m))) (log),
      !> P_load(m)/max(P, local_floor P(m)) (Hertz + cap), local_weight(u, s_share) (u on
      !> the two-piece map), 1 else
      real(dp), allocatable :: weight(:)
      type(loading_history) :: hist !< the loading solve at m (loaded: reused)
      !> the deflection of the curve's last unloading solve, the next one's start
      type(unload_start) :: start
   end type unloading_curve

contains

   !> The mismatch refine_curve would find at the middle of s interval i of a log-ratio
   !> curve with nodes s, h, dh/dxi and weights, estimated (midpoint_skip): the
   !> interval's cubic Hermite against the quintic Hermite through it and the node before
   !> or after it (each that exists, the larger difference), in xi = m - delta (h is
   !> smooth in xi across the edge map's breaks), value and slope as refine_curve weighs
   !> them, by the larger weight of the interval's ends. huge where the curve has fewer
   !> than three nodes, or a node of those has h = max_log_ratio (the force vanished).
   pure real(dp) function midpoint_estimate(curve, s, h, dh, weight, i) result(est)
      type(unloading_curve), intent(in) :: curve
      real(dp), intent(in) :: s(:), h(:), dh(:), weight(:)
      integer, intent(in) :: i
      real(dp) :: x(3), x_a, x_mid, width, dxi, r, dr, q, dq, w
      integer :: side, a, k, n
      n = size(s)
      est = huge(1.0_dp)
      if (n < 3) return
      if (maxval(h(max(i - 1, 1):min(i + 2, n))) >= max_log_ratio) return
      call edge_xi(curve%xi, s(i), x_a, dxi, edge_segment(s(i), s(i + 1)))
      call edge_xi(curve%xi, 0.5_dp*(s(i) + s(i + 1)), x_mid)
      width = (s(i + 1) - s(i))*dxi
      ! the interval's cubic at its middle (curve_eval's, in xi)
      call hermite_cubic(width, h(i), dh(i), h(i + 1), dh(i + 1), 0.5_dp, r, dr)
      w = max(weight(i), weight(i + 1))
      est = 0.0_dp
      do side = 0, 1
         a = i - 1 + side   ! the nodes a .. a + 2
         if (a < 1 .or. a + 2 > n) cycle
         do k = 1, 3
            call edge_xi(curve%xi, s(a + k - 1), x(k))
         end do
         call hermite_quintic(x, h(a:a + 2), dh(a:a + 2), x_mid, q, dq)
         est = max(est, w*max(abs(q - r), 0.25_dp*width*abs(dq - dr)))
      end do
   end function midpoint_estimate

   !> The mismatch refine_curve would find at the middle of s interval i of a gap curve
   !> (nodes s, g and stored slopes d; gap_skip), estimated as midpoint_estimate's: the
   !> interval's cubic against the quintic Hermite through it and the node before or
   !> after it (each side whose three nodes lie on the interval's piece of the map, in s,
   !> where the map is linear; the larger difference). huge where no side does.
   pure real(dp) function gap_estimate(curve, s, g, d, i) result(est)
      type(unloading_curve), intent(in) :: curve
      real(dp), intent(in) :: s(:), g(:), d(:)
      integer, intent(in) :: i
      real(dp) :: f, width, s_mid, r, dr, q, dq
      integer :: side, a, piece
      est = huge(1.0_dp)
      s_mid = 0.5_dp*(s(i) + s(i + 1))
      piece = map_piece(.true., s_mid)
      ! (the stored slopes are the first piece's: dg/ds on this piece, as curve_eval)
      f = curve%piece_scale(piece)
      width = s(i + 1) - s(i)
      call hermite_cubic(width, g(i), f*d(i), g(i + 1), f*d(i + 1), 0.5_dp, r, dr)
      do side = 0, 1
         a = i - 1 + side   ! the nodes a .. a + 2
         if (a < 1 .or. a + 2 > size(s)) cycle
         if (map_piece(.true., 0.5_dp*(s(a) + s(a + 1))) /= piece .or. &
            & map_piece(.true., 0.5_dp*(s(a + 1) + s(a + 2))) /= piece) cycle
         call hermite_quintic(s(a:a + 2), g(a:a + 2), f*d(a:a + 2), s_mid, q, dq)
         if (est == huge(1.0_dp)) est = 0.0_dp
         est = max(est, max(abs(q - r), 0.25_dp*width*abs(dq - dr)))
      end do
   end function gap_estimate

   !> The mismatch the bisected curve c accepted on its s interval [a, b]; huge where it
   !> has no such interval.
   pure real(dp) function accepted_mismatch(c, a, b) result(err)
      type(unloading_curve), intent(in) :: c
      real(dp), intent(in) :: a, b
      integer :: i
      err = huge(1.0_dp)
      if (.not. (c%verified .and. allocated(c%mismatch))) return
      i = findloc(c%s, a, 1)
      if (i < 1 .or. i >= size(c%s)) return
      if (c%s(i + 1) == b) err = c%mismatch(i)
   end function accepted_mismatch

   !> The cubic Hermite on an interval of the given width (values f, slopes d at its
   !> ends) and its slope, at the fraction t of it.
   pure subroutine hermite_cubic(width, f_a, d_a, f_b, d_b, t, v, dv)
      real(dp), intent(in) :: width, f_a, d_a, f_b, d_b, t
      real(dp), intent(out) :: v, dv
      v = (1 + 2*t)*(1 - t)**2*f_a + t*(1 - t)**2*width*d_a + t*t*(3 - 2*t)*f_b + &
         & t*t*(t - 1)*width*d_b
      dv = 6*t*(t - 1)/width*(f_a - f_b) + (1 - t)*(1 - 3*t)*d_a + t*(3*t - 2)*d_b
   end subroutine hermite_cubic

   !> The quintic through three points x with values f and slopes d (Newton's form on
   !> the doubled nodes) and its slope, at xv.
   pure subroutine hermite_quintic(x, f, d, xv, v, dv)
      real(dp), intent(in) :: x(3), f(3), d(3), xv
      real(dp), intent(out) :: v, dv
      real(dp) :: z(6), c(6)
      integer :: j, l
      z = [x(1), x(1), x(2), x(2), x(3), x(3)]
      c = [f(1), f(1), f(2), f(2), f(3), f(3)]
      ! first divided differences: the slopes at the doubled nodes
      do j = 6, 2, -1
         if (mod(j, 2) == 0) then
            c(j) = d(j/2)
         else
            c(j) = (c(j) - c(j - 1))/(z(j) - z(j - 1))
         end if
      end do
      do l = 2, 5
         do j = 6, l + 1, -1
            c(j) = (c(j) - c(j - 1))/(z(j) - z(j - l))
         end do
      end do
      v = c(6)
      dv = 0.0_dp
      do j = 5, 1, -1
         dv = dv*(xv - z(j)) + v
         v = v*(xv - z(j)) + c(j)
      end do
   end subroutine hermite_quintic

   !> L(m) of the curves at m(:) (a loading solve each, in parallel; its history is kept
   !> in the curve for build_curves).
   subroutine unloading_lengths(table, options, m, shift, curves, error)
      type(hysteresis_table), intent(in) :: table   !< the table being built
      type(solver_options), intent(in) :: options   !< the build's solver options
      real(dp), intent(in) :: m(:)   !< turning points [length]
      logical, intent(in) :: shift   !< rough_length's
      !> their curves: length (and history) set
      type(unloading_curve), intent(inout) :: curves(:)
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      type(solver_options) :: serial
      integer :: stats(size(m)), j
      character(len=512) :: messages(size(m))
      serial = curve_options(options, table%rel_tol)
      stats = 0
      ! (largest delta_max first: see build_curves)
      !$omp parallel do schedule(dynamic) default(shared) private(j)
      do j = size(m), 1, -1
         call one_length(j)
      end do
      !$omp end parallel do
      call first_failure(stats, messages, error, "the unloading length at delta_max", m)
   contains
      subroutine one_length(j)
         integer, intent(in) :: j
         type(egw_error), allocatable :: err
         type(solve_result) :: top, res
         if (table%mapped) then
            curves(j)%m = m(j)
            call mapped_length(table, m(j), curves(j), err)
         else if (table%params%flow_pressure > 0.0_dp) then   ! (rough: the smooth cap's)
            call rough_length(table%params, serial, m(j), shift, curves(j)%length, err)
         else
            call load_history(table%params, serial, m(j), curves(j)%hist, top, err, &
               & table%loading_law)
            if (.not. allocated(err)) call solve_unload(curves(j)%hist, m(j), res, err)
            if (.not. allocated(err)) curves(j)%length = unloading_length(top%force, &
               & res%stiffness, table%params%sigma)
         end if
         if (allocated(err)) then
            stats(j) = err%stat
            messages(j) = err%message
            return
         end if
      end subroutine one_length
   end subroutine unloading_lengths

   !> The unloading curves of the delta_max values m(:) (increasing), in parallel (OpenMP;
   !> every curve is independent: its own loading history and solves; the largest delta_max
   !> first); the first error wins. A curve
   !> whose history is loaded already (unloading_lengths) keeps it. check: solve each
   !> curve at the s nodes curves(j)%s holds (refine_m's check curves), without bisection.
   subroutine build_curves(table, options, m, shift, curves, error, check)
      type(hysteresis_table), intent(inout) :: table   !< the table being built
      type(solver_options), intent(in) :: options   !< the build's solver options
      real(dp), intent(in) :: m(:)   !< turning points [length]
      logical, intent(in) :: shift   !< rough_length's
      type(unloading_curve), intent(inout) :: curves(:)   !< their curves, built
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      logical, intent(in), optional :: check   !< solve at the held s nodes only (check curves)
      type(solver_options) :: serial
      real(dp) :: worst(size(m))
      integer :: stats(size(m)), j
      character(len=512) :: messages(size(m))
      logical :: only_check
      only_check = .false.
      if (present(check)) only_check = check
      serial = curve_options(options, table%rel_tol)
      stats = 0
      worst = 0.0_dp
      ! largest delta_max first: a curve's solves cost more the deeper its turning point
      ! (wider contact, more rings), up to 50x the first's, so that in increasing order
      ! the last, dearest curves left one thread idle (the longest-first schedule: README's
      ! rough + cap builds at 1e-4, from per-curve thread CPU times, 2 threads: E-GW 4 %,
      ! GW 16 %, EP-GW psi 1 7 % shorter; doc/benchmarks.md "Stop 56: par22"). Each curve
      ! writes only its own entries: the order changes no bit of the table.
      !$omp parallel do schedule(dynamic) default(shared) private(j)
      do j = size(m), 1, -1
         call one_curve(j)
      end do
      !$omp end parallel do
      call first_failure(stats, messages, error, "the unloading curve from delta_max", m)
      if (allocated(error)) return
      table%max_error = max(table%max_error, maxval(worst))
   contains
      subroutine one_curve(j)
         integer, intent(in) :: j
         type(egw_error), allocatable :: err
         real(dp), allocatable :: s(:)
         type(unload_start) :: none
         call start_curve(table, serial, m(j), shift, curves(j), err)
         if (.not. allocated(err)) then
            if (only_check) then
               s = curves(j)%s
            else
               s = start_nodes(table, m(j))
            end if
            call solve_nodes(table, curves(j), s, err)
         end if
         if (.not. (allocated(err) .or. only_check)) call refine_curve(table, curves(j), &
            & worst(j), err)
         curves(j)%worst = worst(j)
         ! (a check curve's start is not used again, move_curve leaves it behind: freed
         ! here with the solver's buffers it carries, so that the check curves solved in
         ! parallel do not all hold them until the last is done)
         if (only_check) curves(j)%start = none
         if (allocated(err)) then
            stats(j) = err%stat
            messages(j) = err%message
         end if
      end subroutine one_curve
   end subroutine build_curves

   !> refine_curve on curves(idx(:)) (check curves that became nodes), in parallel.
   subroutine verify_curves(table, curves, idx, error)
      type(hysteresis_table), intent(inout) :: table   !< the table being built
      type(unloading_curve), intent(inout) :: curves(:)   !< the grid's curves
      integer, intent(in) :: idx(:)   !< which of curves to bisect
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      real(dp) :: worst(size(idx))
      integer :: stats(size(idx)), k
      character(len=512) :: messages(size(idx))
      stats = 0
      worst = 0.0_dp
      ! (largest delta_max first, idx increasing: see build_curves)
      !$omp parallel do schedule(dynamic) default(shared) private(k)
      do k = size(idx), 1, -1
         call one_verify(k)
      end do
      !$omp end parallel do
      call first_failure(stats, messages, error, "the unloading curve from delta_max", &
         & curves(idx)%m)
      if (allocated(error) .or. size(idx) == 0) return
      table%max_error = max(table%max_error, maxval(worst))
   contains
      subroutine one_verify(k)
         integer, intent(in) :: k
         type(egw_error), allocatable :: err
         type(unloading_curve) :: known
         real(dp), allocatable :: first(:)
         integer :: i, at
         first = start_nodes(table, curves(idx(k))%m)
         known%s = curves(idx(k))%s
         known%gap = curves(idx(k))%gap
         known%slope = curves(idx(k))%slope
         known%weight = curves(idx(k))%weight
         ! the bisection of a node's curve from its first nodes, the check solves taken
         ! where it meets them (all first nodes but s = 0): the curve a node built at once
         ! has
         curves(idx(k))%s = first
         deallocate (curves(idx(k))%gap, curves(idx(k))%slope, curves(idx(k))%weight)
         allocate (curves(idx(k))%gap(size(first)), curves(idx(k))%slope(size(first)), &
            & curves(idx(k))%weight(size(first)))
         do i = 1, size(first)
            at = findloc(known%s, first(i), 1)
            if (at > 0) then
               curves(idx(k))%gap(i) = known%gap(at)
               curves(idx(k))%slope(i) = known%slope(at)
               curves(idx(k))%weight(i) = known%weight(at)
            else
               call gap_at(table, curves(idx(k)), first(i), curves(idx(k))%gap(i), &
                  & curves(idx(k))%slope(i), curves(idx(k))%weight(i), err)
               if (allocated(err)) exit
            end if
         end do
         ! (its neighbours in delta_max, the nodes it was inserted between, bisected
         ! already and not written in this pass: neighbour_skip)
         if (.not. allocated(err)) then
            if (table%mapped .and. idx(k) > 1 .and. idx(k) < size(curves)) then
               call refine_curve(table, curves(idx(k)), worst(k), err, known, &
                  & curves(idx(k) - 1), curves(idx(k) + 1))
            else
               call refine_curve(table, curves(idx(k)), worst(k), err, known)
            end if
         end if
         curves(idx(k))%worst = worst(k)
         if (allocated(err)) then
            stats(k) = err%stat
            messages(k) = err%message
         end if
      end subroutine one_verify
   end subroutine verify_curves

   !> What the solves of the unloading curve of delta_max = m need: its loading history
   !> (loaded here unless the curve holds one for m), the force scale and L(m).
   subroutine start_curve(table, options, m, shift, curve, error)
      type(hysteresis_table), intent(in) :: table
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: m
      logical, intent(in) :: shift   !< rough_length's
      type(unloading_curve), intent(inout) :: curve
      type(egw_error), allocatable, intent(out) :: error
      type(solve_result) :: res
      type(solver_options) :: hist_options
      real(dp) :: f_turn, k_turn
      curve%m = m
      curve%verified = .false.
      if (curve%hist%loaded .and. curve%hist%delta_max == m) then
         res = curve%hist%loading
      else
         ! (stiffness: with the cap the history's loading stiffness is never read here, the
         ! curves' slopes start at s = 1e-4: the three moved-mesh solves of each history,
         ! at its rel_tol/10, are saved, ~3 % of an E-GW + cap build's instructions, the
         ! same tables; without the cap it changes nothing)
         ! u curves: the history at hist_share of the curve solves' rel_tol (its field
         ! d_max(r) at a tenth of that: load_history), its unloading solves at theirs:
         ! near the front an error of the field moves the unloading force by an absolute
         ! amount, which their local weight multiplies by up to 1/(s_share local_floor);
         ! other curves' histories at the curve solves' rel_tol, as before
         hist_options = options
         if (table%ratio_on_map) hist_options%rel_tol = hist_share*options%rel_tol
         call load_history(table%params, hist_options, m, curve%hist, res, error, &
            & table%loading_law, stiffness=.false.)
         if (allocated(error)) return
         curve%hist%options%rel_tol = options%rel_tol
      end if
      f_turn = res%force
      ! gaps relative to the loading table's force at the turning point (what the
      ! evaluation multiplies them by)
      call table_eval(table%loading, m, curve%scale, k_turn)
      if (.not. curve%scale > 0.0_dp) curve%scale = table%loading%reference_force*table%rel_tol
      ! the solve's force at the turning point over the table's: the log ratio's loading
      ! force is scaled by it, the gap's unloading force by its inverse, so that either
      ! vanishes there continuously (the table's own error, <= rel_tol of the force, would
      ! otherwise be a jump that no refinement in s removes) and the curve is the solves'
      ! times P_table(m)/P_solve(m): relative to the local force (the gap scaled the
      ! loading force instead: its error (1 - c) P_load(delta) stayed where the unloading
      ! force vanishes, 6.2e-5 P(m) at Hertz + cap's residual overlap at 1e-3)
      curve%c_turn = 1.0_dp
      if (f_turn > 0.0_dp .and. curve%scale > 0.0_dp) curve%c_turn = f_turn/curve%scale
      if (table%capped .and. curve%hist%capped) then
         ! (the history's own cap_load: its residual overlap is cap_length's, no second solve)
         curve%length = m - history_residual(curve%hist)
      else if (table%capped) then
         call cap_length(table%params, m, curve%length, error)
      else if (table%mapped) then
         call mapped_length(table, m, curve, error)
      else if (table%params%flow_pressure > 0.0_dp) then
         call rough_length(table%params, options, m, shift, curve%length, error)
      else
         call solve_unload(curve%hist, m, res, error)
         if (.not. allocated(error)) curve%length = unloading_length(f_turn, res%stiffness, &
            & table%params%sigma)
      end if
      if (allocated(error)) return
      curve%span = table%s_max*curve%length
      curve%log = log_table(table)
      curve%p_turn = f_turn
      if (curve%log) call edge_breaks(curve%length, table%params%sigma, curve%xi)
   end subroutine start_curve

   !> The two-piece map of the curve of turning point m (mapped): its knee, the smooth cap
   !> model's residual overlap delta_r(m) (0 up to first yield), the first piece's span
   !> (m - knee)/s_knee as its length (s_max = 1) and the pieces' slope scales. delta_r
   !> puts the rough curves' zero edge at s = 1/2 from ~1.4 delta_y on; knees that follow
   !> their other features (the half-force edge, the annulus kink, c delta_r) built denser
   !> grids (doc/benchmarks.md, stop 64: knee30).
   subroutine mapped_length(table, m, curve, error)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: m
      type(unloading_curve), intent(inout) :: curve
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: smooth
      curve%knee = 0.0_dp
      if (m > first_yield(table%params)) then   ! (then m > 0)
         call cap_length(table%params, m, smooth, error)
         if (allocated(error)) return
         curve%knee = min(max(m - smooth, 0.0_dp), 0.99_dp*m)
      end if
      curve%length = 1.0_dp/map_iota(table, m, curve%knee)
      curve%piece_scale = map_lengths(table, m, curve%knee)/table%tail_length
   end subroutine mapped_length

   !> x = m - delta at s on the curve (its map, map_x) and the piece's dx/ds over the
   !> first piece's (piece_scale).
   pure real(dp) function curve_offset(table, curve, s) result(x)
      type(hysteresis_table), intent(in) :: table   !< the table being built
      type(unloading_curve), intent(in) :: curve   !< the curve
      real(dp), intent(in) :: s   !< its coordinate s
      real(dp) :: dsdx
      x = s*curve%span   ! (unless mapped: the arithmetic of the linear map, bit for bit)
      if (table%mapped) call map_x(table, curve%m, curve%knee, 1.0_dp/curve%span, s, x, dsdx)
   end function curve_offset

   !> The first s nodes of the table's curves (first_nodes; mapped: its breaks too, and
   !> the tail's nodes at or below 0; log-ratio: the edge map's breaks).
   pure function start_nodes(table, m) result(s)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: m
      real(dp), allocatable :: s(:)
      s = first_nodes
      if (table%mapped) s = mapped_first_nodes
      if (table%log_ratio) s = first_log_nodes
      if (table%mapped .and. .not. m > 0.0_dp) s = tail_first_nodes
   end function start_nodes

   !> The curve's g and dg/ds at the nodes s (increasing, in [0, 1]), solved.
   subroutine solve_nodes(table, curve, s, error)
      type(hysteresis_table), intent(in) :: table
      type(unloading_curve), intent(inout) :: curve
      real(dp), intent(in) :: s(:)
      type(egw_error), allocatable, intent(out) :: error
      integer :: i
      curve%s = s
      if (allocated(curve%gap)) deallocate (curve%gap, curve%slope)
      if (allocated(curve%weight)) deallocate (curve%weight)
      allocate (curve%gap(size(s)), curve%slope(size(s)), curve%weight(size(s)))
      do i = 1, size(s)
         call gap_at(table, curve, s(i), curve%gap(i), curve%slope(i), curve%weight(i), &
            & error)
         if (allocated(error)) return
      end do
   end subroutine solve_nodes

   !> Bisect the curve's s intervals (from the nodes it holds) until the Hermite curve
   !> agrees with the solves at every midpoint to rel_tol/4 (an interval that passed is not
   !> solved again); worst: the largest mismatch accepted. known: solves of this curve
   !> done before (a check curve's), taken instead of solving again at their s. Gap
   !> curves: midpoints cleared by an estimate are not solved (gap_skip; with lower and
   !> upper, neighbour_skip).
   subroutine refine_curve(table, curve, worst, error, known, lower, upper)
      type(hysteresis_table), intent(in) :: table
      type(unloading_curve), intent(inout) :: curve
      real(dp), intent(out) :: worst
      type(egw_error), allocatable, intent(out) :: error
      type(unloading_curve), intent(in), optional :: known
      !> its neighbours in delta_max, bisected (a promoted check curve's)
      type(unloading_curve), intent(in), optional :: lower, upper
      real(dp) :: s(max_s_nodes), gap(max_s_nodes), slope(max_s_nodes), &
         & weight(max_s_nodes), r_mid, d_mid, r_int, d_int, s_mid, err, w_mid, width, dxi, &
         & xi_mid, w_int, mismatch(max_s_nodes), est
      integer :: n, i, k
      logical :: refined, checked(max_s_nodes)
      type(unloading_curve) :: probe
      type(loading_history) :: unloaded
      type(unload_start) :: none
      worst = 0.0_dp
      n = size(curve%s)
      s(1:n) = curve%s
      gap(1:n) = curve%gap
      slope(1:n) = curve%slope
      weight(1:n) = curve%weight
      checked(1:n - 1) = .false.
      mismatch(1:n - 1) = 0.0_dp
      do
         refined = .false.
         i = 1
         do while (i < n)
            if (checked(i)) then
               i = i + 1
               cycle
            end if
            s_mid = 0.5_dp*(s(i) + s(i + 1))
            k = 0
            if (present(known)) k = findloc(known%s, s_mid, 1)
            ! (log-ratio, no solve there yet: an interval at the width limit is not split,
            ! whatever its mismatch; one whose estimate meets midpoint_skip is accepted)
            if (curve%log .and. k == 0) then
               err = 0.0_dp
               if (.not. s(i + 1) - s(i) < min_width) err = midpoint_estimate(curve, s(1:n), &
                  & gap(1:n), slope(1:n), weight(1:n), i)
               if (err <= midpoint_skip*0.25_dp*table%rel_tol) then
                  checked(i) = .true.
                  worst = max(worst, err)
                  i = i + 1
                  cycle
               end if
            end if
            if (table%mapped .and. k == 0) then
               est = gap_estimate(curve, s(1:n), gap(1:n), slope(1:n), i)
               ! (u curves: weighted as the mismatch below)
               if (table%ratio_on_map) est = est*max(weight(i), weight(i + 1))
               err = huge(1.0_dp)
               if (.not. (any(s(i) == [0.0_dp, s_knee, s_zero]) .or. &
                  & any(s(i + 1) == [s_knee, s_zero, 1.0_dp]))) then
                  if (est <= gap_skip*0.25_dp*table%rel_tol) err = est
               end if
               if (err == huge(1.0_dp) .and. present(lower) .and. present(upper)) then
                  err = max(est, accepted_mismatch(lower, s(i), s(i + 1)), &
                     & accepted_mismatch(upper, s(i), s(i + 1)))
                  if (err > neighbour_skip*0.25_dp*table%rel_tol) err = huge(1.0_dp)
               end if
               if (err < huge(1.0_dp)) then
                  checked(i) = .true.
                  mismatch(i) = err
                  worst = max(worst, err)
                  i = i + 1
                  cycle
               end if
            end if
            if (k > 0) then
               r_mid = known%gap(k)
               d_mid = known%slope(k)
               w_mid = known%weight(k)
            else
               call gap_at(table, curve, s_mid, r_mid, d_mid, w_mid, error)
               if (allocated(error)) return
            end if
            probe%s = s(i:i + 1)
            probe%gap = gap(i:i + 1)
            probe%slope = slope(i:i + 1)
            probe%piece_scale = curve%piece_scale
            probe%log = curve%log
            probe%xi = curve%xi
            call curve_eval(probe, s_mid, r_int, d_int)
            ! the slope's mismatch too: a midpoint value can agree by chance where the
            ! curve bends (near the residual overlap) while a quarter point does not (dg/ds
            ! on the interval's piece of the two-piece map; log-ratio: slopes per xi, the
            ! interval's width in xi, the mismatch weighted)
            width = s(i + 1) - s(i)
            if (curve%log) then
               call edge_xi(curve%xi, s_mid, xi_mid, dxi, edge_segment(s(i), s(i + 1)))
               width = width*dxi
            end if
            ! (log-ratio: weighted by the largest of the interval's weights, at its ends and
            ! middle: with the middle's alone, where the force falls steeply across the
            ! interval, a cubic's error nearer its start, where the force and so the weight
            ! is larger, passed; far_errors at every delta_max interval found 1.08 rel_tol of
            ! the local force at m = -5.69 sigma, P ~ 1e-4 P(m), on the 1e-4 [-3, 30] sigma
            ! table, and with the s check at rel_tol/8 4.2 rel_tol at s = 0.64 over m in
            ! [0.26, 2.9] sigma; the weights are 1 on gap curves: unchanged there). Not
            ! where the force has vanished at an end or the middle (h = max_log_ratio):
            ! the jump to it would be split to the width limit and the resampled cubics
            ! there overshoot the readers' range [-1, max_log_ratio]
            w_int = w_mid
            if (max(gap(i), gap(i + 1), r_mid) < max_log_ratio) w_int = max(w_mid, &
               & weight(i), weight(i + 1))
            ! (u curves: an interval narrower than u_min_width keeps the tolerance relative
            ! to P(m), which the solves meet)
            if (table%ratio_on_map .and. s(i + 1) - s(i) < u_min_width) w_int = 1.0_dp
            err = w_int*max(abs(r_int - r_mid), &
               & 0.25_dp*width*abs(d_int - d_mid*curve%piece_scale(map_piece(table%mapped, &
               & s_mid))))
            if (curve%log .and. s(i + 1) - s(i) < min_width) err = 0.0_dp   ! not split
            if (err > 0.25_dp*table%rel_tol) then
               if (n == max_s_nodes) then
                  call fatal_error(error, egw_not_converged, "hysteresis table: rel_tol = "// &
                     & format_real(table%rel_tol)//" not reached: the unloading curve at "// &
                     & "delta_max = "//format_real(curve%m)//" needs more than 400 nodes "// &
                     & "for rel_tol/4, its mismatch still "//format_real(err))
                  return
               end if
               s(i + 2:n + 1) = s(i + 1:n)
               gap(i + 2:n + 1) = gap(i + 1:n)
               slope(i + 2:n + 1) = slope(i + 1:n)
               weight(i + 2:n + 1) = weight(i + 1:n)
               checked(i + 2:n) = checked(i + 1:n - 1)
               checked(i:i + 1) = .false.
               mismatch(i + 2:n) = mismatch(i + 1:n - 1)
               s(i + 1) = s_mid
               gap(i + 1) = r_mid
               slope(i + 1) = d_mid
               weight(i + 1) = w_mid
               n = n + 1
               refined = .true.
               i = i + 1   ! the new left half is checked in the next sweep
            else
               checked(i) = .true.
               mismatch(i) = err
               worst = max(worst, err)
            end if
            i = i + 1
         end do
         if (.not. refined) exit
      end do
      curve%s = s(1:n)
      curve%gap = gap(1:n)
      curve%slope = slope(1:n)
      curve%weight = weight(1:n)
      curve%mismatch = mismatch(1:n - 1)
      curve%verified = .true.
      curve%hist = unloaded   ! (no more solves: its mesh and field freed)
      curve%start = none
   end subroutine refine_curve

   !> The hysteresis gap g = (P_ext(delta) - P_unload(delta)/c)/P_load(m) and dg/ds at
   !> delta = m - s span, P_ext the loading table with its tail below the cut-off (below
   !> the cut-off too: the curve is a neighbour of others in the m direction), c the
   !> solve's force at m over the table's; g = 0 at the turning point, so that the force
   !> is continuous there, and the table's force P_load(delta) - P_load(m) g is the
   !> solve's over c. At s = 0 the slope is the unloading branch's, dg/ds(0+).
   subroutine gap_at(table, curve, x, g, dg, weight, error)
      type(hysteresis_table), intent(in) :: table
      type(unloading_curve), intent(inout) :: curve   !< (its start replaced)
      real(dp), intent(in) :: x
      real(dp), intent(out) :: g, dg
      !> the mismatch's weight there: min(1, P/(local_floor P(m))) (log);
      !> P_load(m)/max(P, local_floor P(m)) (Hertz + cap), local_weight(u, s_share) (u on
      !> the two-piece map), else 1
      real(dp), intent(out) :: weight
      type(egw_error), allocatable, intent(out) :: error
      type(solve_result) :: res
      real(dp) :: p_ext, k_ext, x_solve
      logical :: at_turn
      g = 0.0_dp
      dg = 0.0_dp
      weight = 1.0_dp
      if (curve%log) then
         call log_ratio_at(table, curve, x, g, dg, weight, error)
         return
      end if
      ! At s = 0 solve_unload returns the loading solve, whose stiffness is the loading
      ! branch's; unloading leaves the turning point stiffer (mu 4, psi 2, m = sigma:
      ! 2.740 against 2.539), so a slope of ~0 there made the first interval's cubic
      ! wrong and the bisection halve it down to s ~ 6e-5 (10 nodes, 20 solves a
      ! curve). The slope at s = 1e-4 instead: g is smooth there (g/s linear in s from
      ! 0.5 down to 1e-6 sigma), the difference is ~1e-4 g'' and the checks below see
      ! what remains. (Nearer than ~1e-7 sigma to m an unloading solve's stiffness is
      ! off: d - d_max is then below the error of the interpolated d_max field.)
      x_solve = x
      if (x == 0.0_dp) x_solve = 1.0e-4_dp
      ! (the overlap of s on the curve's map: m - s span unless mapped)
      x_solve = curve_offset(table, curve, x_solve)
      ! (a mapped turning point at or below 0: s <= s_zero is the turning point itself;
      ! its slope, on the tail, is the unloading branch's, as at s = 0 above)
      at_turn = x_solve == 0.0_dp
      if (at_turn) x_solve = curve_offset(table, curve, s_zero + 1.0e-4_dp*(1.0_dp - s_zero))
      call solve_unload(curve%hist, curve%m - x_solve, res, error, curve%start)
      if (allocated(error)) return
      ! the loading force continued below its cut-off by the tail law (table_eval
      ! gives 0 there), so that the gap stays smooth across it
      call table_eval_tail_law(table%loading, curve%m - x_solve, p_ext, k_ext)
      if (table%force_ratio) then
         ! u = P/P_load(m) of the solves times 1/c (the gap's scaling): 1 at s = 0, 0 at
         ! s = 1 (the residual overlap of L), du/ds = -K span/(c P_load(m))
         g = 1.0_dp
         if (x > 0.0_dp) g = max(res%force, 0.0_dp)/(curve%c_turn*curve%scale)
         if (x >= 1.0_dp) g = 0.0_dp
         dg = 0.0_dp
         if (res%force > 0.0_dp) dg = -res%stiffness*curve%span/(curve%c_turn*curve%scale)
         if (curve%p_turn > 0.0_dp .and. x > 0.0_dp) &
            & weight = curve%scale/max(res%force, local_floor*curve%p_turn)
         if (abs(g) < tiny_ratio) g = 0.0_dp
         if (abs(dg) < tiny_ratio) dg = 0.0_dp
         return
      end if
      if (table%mapped .and. table%ratio_on_map) then
         ! u = P/P_load(m) on the two-piece map (format 6): P over the solve's force at m
         ! (c_turn scale), so that P_load(m) u is the solve's force over c as the gap's
         ! table force is; 1 at the turning point (s <= s_zero of one at or below 0);
         ! slopes du/dx times tail_length, as the gap's
         g = 1.0_dp
         if (x > 0.0_dp .and. .not. at_turn) g = max(res%force, 0.0_dp)/ &
            & (curve%c_turn*curve%scale)
         dg = -res%stiffness*table%tail_length/(curve%c_turn*curve%scale)
         if (x > 0.0_dp .and. .not. at_turn .and. curve%p_turn > 0.0_dp) &
            & weight = local_weight(g, s_share)
         if (abs(g) < tiny_ratio) g = 0.0_dp
         if (abs(dg) < tiny_ratio) dg = 0.0_dp
         return
      end if
      if (x > 0.0_dp .and. .not. at_turn) g = (p_ext - res%force/curve%c_turn)/curve%scale
      ! Hertz + cap: refine_curve's weight, g's unit over max(P, local_floor P(m)), so that
      ! each curve's cubics hold the tolerance relative to the local force down to
      ! local_floor P(m) (near the residual overlap P ~ (delta - delta_r)**1.5: the last
      ! intervals halved ~6 times more; 1e-4: 20 -> 50 s nodes, build CPU 1.4x).
      ! Not rough + cap (E-GW + cap at 1e-3: 19 -> 137 s nodes in the tail, build 2x),
      ! nor stencil_mismatch's check in m: between the curves the gap's interpolation
      ! carries the loading table's error at delta, ~rel_tol P_load(delta), which does not
      ! vanish at the residual overlap (103 delta_max nodes against 15 at 1e-3, 1e-4 did
      ! not settle; doc/stability.md, stop 49)
      if (table%capped .and. curve%p_turn > 0.0_dp .and. x > 0.0_dp) &
         & weight = curve%scale/max(res%force, local_floor*curve%p_turn)
      ! (dg/ds of the linear map; the two-piece map: dg/dx times tail_length)
      if (table%mapped) then
         dg = (res%stiffness/curve%c_turn - k_ext)*table%tail_length/curve%scale
      else
         dg = (res%stiffness/curve%c_turn - k_ext)*curve%span/curve%scale
      end if
      ! far below the cut-off the forces underflow: no subnormal numbers in the table
      ! (they would slow every evaluation that touches them by two orders)
      if (abs(g) < tiny_ratio) g = 0.0_dp
      if (abs(dg) < tiny_ratio) dg = 0.0_dp
   end subroutine gap_at

   !> The weight of a mismatch in u = P/P_load(m) on a rough + cap table's u curve:
   !> max(1, 1/(c max(u, local_floor))) from u >= local_cut, 1 below, so that a weighted
   !> mismatch of rel_tol is c rel_tol of the local force down to local_floor P(m).
   elemental real(dp) function local_weight(u, c) result(w)
      real(dp), intent(in) :: u   !< the curve's u there
      real(dp), intent(in) :: c   !< the local force's share (s_share, m_share)
      w = 1.0_dp
      if (u >= local_cut) w = max(1.0_dp, 1.0_dp/(c*max(u, local_floor)))
   end function local_weight

   !> gap_at of a log-ratio curve: h = ln(c P_ext(delta)/P_unload(delta)) (h = 0 at the
   !> turning point: the force is continuous there) and dh/dxi = K/P - K_ext/P_ext at
   !> delta = m - xi(s) on the curve's edge map (at s = 0 the unloading branch's slope,
   !> from s = 1e-4, as gap_at); max_log_ratio (slope 0) where the force has vanished.
   subroutine log_ratio_at(table, curve, x, h, dh, weight, error)
      type(hysteresis_table), intent(in) :: table
      type(unloading_curve), intent(inout) :: curve
      real(dp), intent(in) :: x
      real(dp), intent(out) :: h, dh, weight
      type(egw_error), allocatable, intent(out) :: error
      type(solve_result) :: res
      real(dp) :: p_ext, k_ext, xi
      h = max_log_ratio
      dh = 0.0_dp
      weight = 0.0_dp
      call edge_xi(curve%xi, max(x, 1.0e-4_dp), xi)
      call solve_unload(curve%hist, curve%m - xi, res, error, curve%start)
      if (allocated(error)) return
      call table_eval_tail_law(table%loading, curve%m - xi, p_ext, k_ext)
      if (curve%p_turn > 0.0_dp) then
         weight = min(1.0_dp, max(res%force, 0.0_dp)/(local_floor*curve%p_turn))
      else
         weight = 1.0_dp
      end if
      if (x == 0.0_dp) weight = 1.0_dp
      if (.not. (res%force > 0.0_dp .and. p_ext > 0.0_dp)) return
      h = log(curve%c_turn*p_ext/res%force)
      dh = res%stiffness/res%force - k_ext/p_ext
      if (x == 0.0_dp) h = 0.0_dp
      if (.not. h < max_log_ratio) then
         h = max_log_ratio
         dh = 0.0_dp
      end if
      if (abs(h) < tiny_ratio) h = 0.0_dp
      if (abs(dh) < tiny_ratio) dh = 0.0_dp
   end subroutine log_ratio_at

   !> Cubic Hermite r and dr/ds of a curve at s in [0, 1].
   pure subroutine curve_eval(curve, s, r, dr, stored)
      type(unloading_curve), intent(in) :: curve   !< the curve
      real(dp), intent(in) :: s   !< its coordinate s
      real(dp), intent(out) :: r, dr   !< the curve's value and d/ds at s
      !> dr in the stored slopes' unit (the first piece's dg/ds; 0 on a piece of no
      !> width), not dg/ds on s's piece
      logical, intent(in), optional :: stored
      real(dp) :: h, t, h00, h10, h01, h11, f, fac, x
      integer :: i, lo, hi, mid
      lo = 1
      hi = size(curve%s)
      do while (hi - lo > 1)
         mid = (lo + hi)/2
         if (curve%s(mid) <= s) then
            lo = mid
         else
            hi = mid
         end if
      end do
      i = lo
      h = curve%s(i + 1) - curve%s(i)
      t = min(max((s - curve%s(i))/h, 0.0_dp), 1.0_dp)
      ! the stored slopes are the first piece's: dg/ds on the interval's piece
      f = curve%piece_scale(map_piece(.true., 0.5_dp*(curve%s(i) + curve%s(i + 1))))
      ! log-ratio: slopes per xi, dxi/ds of the interval's segment
      if (curve%log) then
         call edge_xi(curve%xi, curve%s(i), x, fac, edge_segment(curve%s(i), curve%s(i + 1)))
         h = h*fac
      end if
      h00 = (1 + 2*t)*(1 - t)**2
      h10 = t*(1 - t)**2
      h01 = t*t*(3 - 2*t)
      h11 = t*t*(t - 1)
      ! (f = 1, every table without the map: the arithmetic before it, bit for bit)
      r = h00*curve%gap(i) + h10*h*(f*curve%slope(i)) + h01*curve%gap(i + 1) &
         & + h11*h*(f*curve%slope(i + 1))
      dr = 6*t*(t - 1)/h*(curve%gap(i) - curve%gap(i + 1)) &
         & + (1 - t)*(1 - 3*t)*(f*curve%slope(i)) + t*(3*t - 2)*(f*curve%slope(i + 1))
      if (present(stored)) then
         if (stored .and. f /= 1.0_dp) then
            dr = 0.0_dp
            if (f > 0.0_dp) dr = (6*t*(t - 1)/h*(curve%gap(i) - curve%gap(i + 1)))/f + &
               & ((1 - t)*(1 - 3*t)*curve%slope(i) + t*(3*t - 2)*curve%slope(i + 1))
         end if
      end if
   end subroutine curve_eval

end module egw_hysteresis_curves
