!> The delta_max grid of a hysteresis build: its intervals bisected until the Lagrange
!> combination of each stencil's curves meets the midpoint's check curve (refine_m, with
!> the error bound between the nodes, gap_bound, and the deferred splits), the fine grid
!> of a Hertz + cap table's lengths (fine_lengths), and the curves resampled onto the
!> union s grid the table stores (resample). doc/theory.md §8.
module egw_hysteresis_grid
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_not_converged, fatal_error, format_real, first_failure
   use egw_rough_sphere, only: solver_options, history_cap_ratio
   use egw_cap_sphere, only: cap_units, gamma_start
   use egw_table, only: table_progress
   use egw_tolerance_probe, only: hysteresis_solve_tol, m_node_limit
   use egw_hysteresis_data, only: hysteresis_table, map_s, map_iota, edge_breaks, edge_s, &
      & edge_xi, max_stencil, stencil_width, stencil_window, fine_length_tol, m_breakpoint, &
      & m_coordinate, map_x
   use egw_hysteresis, only: first_yield
   use egw_hysteresis_lengths, only: cap_length, log_table
   use egw_hysteresis_curves, only: unloading_curve, min_width, build_curves, verify_curves, &
      & curve_offset, curve_eval, local_weight, m_share
   implicit none
   private

   public :: fine_lengths, refine_m, resample

   !> Hertz + cap (force-ratio) tables: delta_max intervals narrower than this (of the
   !> range) are not split. The curves change fastest just above the first capped turning
   !> point (cap_first_turn): at 1e-4 to 20 delta_y the first intervals at 2^-11 missed by
   !> 1.3e-3 of the local force (1.5e-3 against solves), their mismatch halving in ~2
   !> bisections; split further the table met 1e-4 with 58 nodes (7.1e-5) and 1e-3 with 27,
   !> 1e-5 with 146 leaving two intervals at this width (1.5e-5); doc/stability.md
   !> "Stop 52 (doubt18)". (The cap solver ignores rel_tol: its check solves are the same
   !> solves a user's reference makes, so a mismatch here is the table's own error.)
   !> In units of delta_y, not of the range (stop 53, doubt19): the curves' fast change
   !> above first yield has delta_y's scale whatever the range, and 2^-18 of a range of
   !> 100 or 1000 delta_y stopped the first intervals at 1e-4 and 1e-5 missing by 1.0e-4 ..
   !> 9.9e-4 (doc/stability.md "Stop 53 (doubt19)"); 2^-24 delta_y (6e-8) lies below the
   !> narrowest interval the tables down to rel_tol 2e-6 needed (3.7e-6 delta_y).
   real(dp), parameter :: ratio_min_width = 2.0_dp**(-24)
   !> Log-ratio tables on six-point stencils: a check curve is not solved at a node s of
   !> its neighbours where the four-point stencil's h at its turning point lies within
   !> check_skip rel_tol of the six-point one's (weighted by a bound on its weight there,
   !> check_weight; order_gap): an embedded estimate, the six-point combination being the
   !> more accurate (four points needed 109 delta_max nodes where six need 71), so it is
   !> taken to meet rel_tol there. The checks keep the nodes where the interpolation in
   !> delta_max can still miss: egw-bench's table at 1e-4, 1522 of ~3770 check solves
   !> fewer, build CPU -29 %, 67 x 78 nodes; far_errors unchanged on the suite's three
   !> tables; 1.0 rel_tol measured too (doc/benchmarks.md, stop 47).
   real(dp), parameter :: check_skip = 0.3_dp
   !> Gap tables (rough + cap, mapped): a check curve is not solved at a node s of its
   !> neighbours where the evaluation's four-point stencil and a stencil shifted by one
   !> node (each side that has one, the larger difference; shift_gap) lie within
   !> gap_check_skip of the bound at the same delta: an embedded estimate (on an even grid
   !> at the interval's middle the difference is ~2.7x the centred stencil's error), so
   !> the interval is taken to meet the bound there; err_mid takes the estimate, and where
   !> a neighbour's split changes the stencil the nodes it no longer clears are solved.
   !> An interval with no node left gets no check curve (nor its loading solve). README's
   !> E-GW + cap build at 1e-4: 1580 -> 600 check solves, 2604 -> 1874 in all (the
   !> promoted check curves' bisection 593 -> 843: it meets fewer check solves), the same
   !> 38 x 50 nodes, the table within 2.0e-8 of P(m) of the unskipped build's
   !> (doc/benchmarks.md, stop 58).
   real(dp), parameter :: gap_check_skip = 0.3_dp
   !> Log-ratio tables: a delta_max interval whose check misses by less than split_defer
   !> times the bound is not split in a pass where a neighbour that misses by more is:
   !> that split moves a node of its six-point stencil nearer (its midpoint's Lagrange
   !> product falls 2.5x with one neighbour split, 6.25x with both), and it is checked
   !> again with the new stencil, at no solve (its check curve is kept). egw-bench's
   !> table at 1e-4: 59 delta_max nodes against 67 (doc/benchmarks.md, stop 48).
   real(dp), parameter :: split_defer = 4.0_dp

   !> The s nodes of a check curve left unsolved (gap_check_skip).
   type :: skipped_nodes
      real(dp), allocatable :: s(:)
   end type skipped_nodes

contains

   !> The fine delta_max grid of a force_ratio table for L(m) = m - residual overlap
   !> (cap_length: the cap model's, no unloading solve): from the table's nodes (their
   !> curves' lengths), each interval bisected until 1/L's cubic Lagrange on the grid (the
   !> evaluation's, fine_inv_span) meets cap_length at its midpoint within fine_length_tol
   !> rel_tol relative (the midpoint's value kept as a node where it does not), the
   !> midpoints of a pass solved in parallel. Intervals narrower than min_width**2 of the
   !> range are not split (first yield, where delta_r(m) sets in, aside: not reached on
   !> the suite's tables).
   subroutine fine_lengths(table, curves, error)
      type(hysteresis_table), intent(inout) :: table   !< the table being built
      type(unloading_curve), intent(in) :: curves(:)   !< the table's curves
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      real(dp), allocatable :: x(:), l(:), mid(:), l_mid(:), new_x(:), new_l(:), gam(:), &
         & g_mid(:), new_g(:)
      real(dp), allocatable :: new_lm(:), new_gm(:)
      logical, allocatable :: done(:), split(:), new_done(:), fresh(:), solved(:), &
         & new_solved(:)
      integer, allocatable :: stats(:)
      character(len=512), allocatable :: messages(:)
      real(dp) :: w(4), inv, delta_y, a_y, force_y
      integer :: pass, k, n, first, q, i
      x = table%m
      l = curves%length
      ! c/a of the cap at each node (the curves' histories'; 0: unknown): the midpoints'
      ! searches start from their neighbours' (one_length; the same residual overlaps to
      ! ~1e-13)
      gam = history_cap_ratio(curves%hist)
      call cap_units(table%params%radius, table%params%modulus, table%params%flow_pressure, &
         & delta_y, a_y, force_y)
      ! (an interval's midpoint solved once: kept, with its c/a, while the interval is
      ! not split, for its checks again after a neighbour's split; it was solved again)
      allocate (done(size(x) - 1), solved(size(x) - 1), l_mid(size(x) - 1), &
         & g_mid(size(x) - 1))
      done = .false.
      solved = .false.
      l_mid = 0.0_dp
      g_mid = 0.0_dp
      do pass = 1, 40
         n = size(x)
         mid = 0.5_dp*(x(1:n - 1) + x(2:n))
         allocate (stats(n - 1), messages(n - 1), split(n - 1))
         stats = 0
         !$omp parallel do schedule(dynamic) default(shared) private(k)
         do k = 1, n - 1
            if (.not. (done(k) .or. solved(k))) call one_length(k)
         end do
         !$omp end parallel do
         call first_failure(stats, messages, error, "the unloading length at delta_max", &
            & mid(1:n - 1))
         if (allocated(error)) return
         solved = solved .or. .not. done
         split = .false.
         do k = 1, n - 1
            if (done(k)) cycle
            first = min(max(k - 1, 1), n - 3)
            call lagrange_weights(mid(k), x(first:first + 3), w)
            inv = sum(w/l(first:first + 3))
            split(k) = abs(inv*l_mid(k) - 1.0_dp) > fine_length_tol*table%rel_tol .and. &
               & x(k + 1) - x(k) >= min_width**2*(x(n) - x(1))
            done(k) = .not. split(k)
         end do
         if (.not. any(split)) exit
         allocate (new_x(n + count(split)), new_l(n + count(split)), new_g(n + count(split)), &
            & new_done(n + count(split) - 1), fresh(n + count(split)), &
            & new_solved(n + count(split) - 1), new_lm(n + count(split) - 1), &
            & new_gm(n + count(split) - 1))
         q = 0
         fresh = .false.
         do k = 1, n
            q = q + 1
            new_x(q) = x(k)
            new_l(q) = l(k)
            new_g(q) = gam(k)
            if (k == n) exit
            new_done(q) = done(k)
            new_solved(q) = solved(k) .and. .not. split(k)
            new_lm(q) = l_mid(k)
            new_gm(q) = g_mid(k)
            if (split(k)) then
               q = q + 1
               new_x(q) = mid(k)
               new_l(q) = l_mid(k)
               new_g(q) = g_mid(k)
               new_solved(q) = .false.
               new_lm(q) = 0.0_dp
               new_gm(q) = 0.0_dp
               fresh(q) = .true.
            end if
         end do
         ! (an interval whose stencil holds a new node: checked again)
         do i = 1, size(new_done)
            first = min(max(i - 1, 1), size(new_x) - 3)
            if (any(fresh(first:first + 3))) new_done(i) = .false.
         end do
         deallocate (fresh)
         call move_alloc(new_x, x)
         call move_alloc(new_l, l)
         call move_alloc(new_g, gam)
         call move_alloc(new_solved, solved)
         call move_alloc(new_lm, l_mid)
         call move_alloc(new_gm, g_mid)
         call move_alloc(new_done, done)
         deallocate (stats, messages, split)
      end do
      table%fine_m = x
      table%fine_length = l
   contains
      subroutine one_length(k)
         integer, intent(in) :: k
         type(egw_error), allocatable :: err
         real(dp) :: g, offset
         integer :: c, j
         ! t = ln(g/(1 - g)): gamma_start's at the midpoint plus the mean of its
         ! neighbours' offsets from theirs (gamma_start's own error is smooth in m; the
         ! neighbours' mean of t alone missed more than gamma_start: 2.5 against 2.3 ms a
         ! call, the offsets 1.6 ms)
         g = 0.0_dp
         offset = 0.0_dp
         c = 0
         do j = k, k + 1
            if (.not. inside(gam(j))) cycle
            offset = offset + logit(gam(j)) - logit(gamma_start(x(j)/delta_y))
            c = c + 1
         end do
         if (c > 0) g = 1.0_dp/(1.0_dp + exp(-(logit(gamma_start(mid(k)/delta_y)) + &
            & offset/c)))
         call cap_length(table%params, mid(k), l_mid(k), err, g)
         g_mid(k) = g
         if (allocated(err)) then
            stats(k) = err%stat
            messages(k) = err%message
         end if
      end subroutine one_length

      pure real(dp) function logit(g)
         real(dp), intent(in) :: g
         logit = log(g/(1.0_dp - g))
      end function logit

      !> (a start of c/a: in (0, 1))
      elemental logical function inside(g)
         real(dp), intent(in) :: g
         inside = g > 0.0_dp .and. g < 1.0_dp
      end function inside
   end subroutine fine_lengths

   !> Bisect the delta_max intervals until, for each, the Lagrange combination of its
   !> stencil's curves meets the midpoint's own curve at every node of that curve within
   !> rel_tol. A midpoint's curve is a check curve: solved at the union of its two
   !> neighbours' s nodes (where their bisection found the curves need nodes; log-ratio
   !> curves: the nodes both hold, less check_skip's), not
   !> bisected itself (a node's curve costs twice its nodes in solves, one check solve an
   !> interval: the EP-GW table at 1e-4 of egw-bench 3933 -> 3100 solves). Check curves
   !> are kept until their interval is split, then bisected from the first nodes as a
   !> node's curve is (refine_curve, taking the check solves it meets: the same curve)
   !> and rechecked when the stencil changed: only new midpoints cost solves. Gap tables:
   !> not at the nodes where two shifted stencils agree (gap_check_skip, shift_gap), and an
   !> interval is split where the bound the table reports (gap_bound plus the solves'
   !> rel_tol) exceeds rel_tol.
   subroutine refine_m(table, options, shift, m, curves, error, progress)
      type(hysteresis_table), intent(inout) :: table   !< the table being built
      type(solver_options), intent(in) :: options   !< the build's solver options
      logical, intent(in) :: shift   !< rough_length's
      real(dp), allocatable, intent(inout) :: m(:)   !< the delta_max grid, refined
      type(unloading_curve), allocatable, intent(inout) :: curves(:)   !< its curves, with it
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      procedure(table_progress), optional :: progress   !< called with (curves built, pending)
      type(unloading_curve), allocatable :: mids(:), new_curves(:), new_mids(:), built(:)
      real(dp), allocatable :: new_m(:), err_mid(:)
      logical, allocatable :: have_mid(:), new_have(:), wide(:), miss(:)
      integer, allocatable :: idx(:), promoted(:), fresh(:)
      integer :: pass, j, k, n_split
      real(dp) :: m_bound
      ! (gap tables: per interval the nodes its check curve was not solved at)
      type(skipped_nodes), allocatable :: skipped(:), new_skipped(:)
      ! the bound at the check curves' nodes: rel_tol; with the two-piece map rel_tol/2,
      ! for what falls between those nodes (E-GW + cap, 1e-4: 28 delta_max nodes with
      ! rel_tol met 1.2e-4 of P(m) off main's table between a check curve's s nodes, at
      ! s = 0.17 of m = 333 sigma, where main's 62 nodes erred by 5e-5 against 1e-6 solves);
      ! since stop 63 the two-piece map's split is on gap_bound (below), rel_tol/2 the
      ! scale of its check skips
      m_bound = table%rel_tol
      if (table%mapped) m_bound = 0.5_dp*table%rel_tol
      allocate (mids(size(m) - 1), have_mid(size(m) - 1), skipped(size(m) - 1))
      have_mid = .false.
      do pass = 1, 30
         ! (a kept check curve whose stencil changed: solved at the skipped nodes where
         ! the estimate no longer meets gap_check_skip, its history reused)
         call solve_uncleared(table, options, shift, m, curves, m_bound, have_mid, mids, &
            & skipped, error)
         if (allocated(error)) return
         idx = pack([(j, j = 1, size(m) - 1)], .not. have_mid)
         if (size(idx) > 0) then
            ! check curves, solved at their neighbours' nodes (the grid in s that the
            ! neighbours' bisection found; refine_curve completes one that becomes a node)
            allocate (built(size(idx)))
            do k = 1, size(idx)
               call check_nodes(table, m, curves, idx(k), m_bound, built(k)%s, &
                  & skipped(idx(k))%s)
            end do
            call solve_checks(table, options, shift, m, idx, built, mids, error)
            if (allocated(error)) return
            deallocate (built)
            have_mid = .true.
         end if
         allocate (err_mid(size(m) - 1), wide(size(m) - 1))
         do j = 1, size(m) - 1
            ! (Hertz + cap: the force's error, the loading table's share included)
            if (table%force_ratio) then
               err_mid(j) = whole_mismatch(table, m, curves, j, mids(j))
            else if (allocated(mids(j)%s)) then
               err_mid(j) = stencil_mismatch(table, m, curves, j, mids(j))
            else
               err_mid(j) = 0.0_dp
            end if
            ! (the estimate at the nodes left unsolved: below gap_check_skip of the bound)
            if (allocated(skipped(j)%s)) err_mid(j) = max(err_mid(j), &
               & skip_estimate(table, m, curves, j, skipped(j)%s))
         end do
         ! (log-ratio: an interval narrower than min_width of the range is not split; at
         ! the node m = 0, where the Hertz part sets in and the curves change as sqrt(m),
         ! 1/32 of that: its first interval met its check curve to 9.5e-4 at min_width)
         wide = .true.
         if (table%force_ratio) wide = m(2:) - m(:size(m) - 1) >= &
            & ratio_min_width*first_yield(table%params)
         if (log_table(table)) then
            wide = m(2:) - m(:size(m) - 1) >= min_width*(m(size(m)) - m(1))
            where (m(:size(m) - 1) == 0.0_dp .or. m(2:) == 0.0_dp) wide = &
               & m(2:) - m(:size(m) - 1) >= min_width/32*(m(size(m)) - m(1))
         end if
         ! (not in the last third of the passes, so that deferring never brings a grid
         ! to their limit)
         if (log_table(table) .and. pass <= 20) call defer_splits(err_mid, m_bound, wide)
         miss = err_mid > m_bound .and. wide
         ! (gap tables: split where the bound the table reports below, gap_bound and the
         ! solves' rel_tol, exceeds rel_tol; m_bound stays the scale of the skips)
         if (table%mapped) then
            do j = 1, size(m) - 1
               miss(j) = wide(j) .and. gap_bound(table, m, curves, j, err_mid(j)) + &
                  & hysteresis_solve_tol(options, table%rel_tol) > table%rel_tol
            end do
         end if
         n_split = count(miss)
         ! built: the nodes' curves and the kept midpoints'; pending: two per split
         if (present(progress)) call progress(2*size(m) - 1, 2*size(m) - 1 + 2*n_split)
         if (n_split == 0) then
            table%max_error = max(table%max_error, maxval(err_mid))
            ! (gap curves: the bound between the check curves' s nodes too, gap_bound, and
            ! the solves' own error, which every mismatch above leaves out: their rel_tol,
            ! twice what their estimates meet; README's scene at 1e-4 measured 8.99e-5
            ! against 8.89e-5 without it, doc/stability.md "Stop 54 (doubt20)")
            if (table%mapped) then
               do j = 1, size(m) - 1
                  table%max_error = max(table%max_error, gap_bound(table, m, curves, j, &
                     & err_mid(j)) + hysteresis_solve_tol(options, table%rel_tol))
               end do
            end if
            ! (Hertz + cap: err_mid is what the table's force misses there, the loading
            ! table's error at the turning point included, P = P_load,table(m) sum w u; at
            ! the nodes' curves that error alone)
            if (table%force_ratio) table%max_error = max(table%max_error, &
               & maxval(abs(1.0_dp - curves%c_turn)/curves%c_turn))
            return
         end if
         if (size(m) + n_split > m_node_limit(table%ratio_on_map)) then
            call fatal_error(error, egw_not_converged, "hysteresis table: rel_tol = "// &
               & format_real(table%rel_tol)//" not reached: more than "// &
               & format_real(real(m_node_limit(table%ratio_on_map), dp))// &
               & " delta_max nodes needed, the largest "// &
               & "mismatch between them still "//format_real(maxval(err_mid)))
            return
         end if
         allocate (new_m(size(m) + n_split), new_curves(size(m) + n_split), &
            & new_mids(size(m) + n_split - 1), new_have(size(m) + n_split - 1), &
            & new_skipped(size(m) + n_split - 1))
         new_have = .false.
         allocate (promoted(n_split))
         n_split = 0
         k = 0
         do j = 1, size(m)
            k = k + 1
            new_m(k) = m(j)
            call move_curve(curves(j), new_curves(k))
            if (j == size(m)) exit
            if (miss(j)) then
               k = k + 1
               new_m(k) = 0.5_dp*(m(j) + m(j + 1))
               call move_curve(mids(j), new_curves(k))
               n_split = n_split + 1
               promoted(n_split) = k
            else
               call move_curve(mids(j), new_mids(k))
               if (allocated(skipped(j)%s)) call move_alloc(skipped(j)%s, new_skipped(k)%s)
               new_have(k) = .true.
            end if
         end do
         call move_alloc(new_m, m)
         call move_alloc(new_curves, curves)
         call move_alloc(new_mids, mids)
         call move_alloc(new_have, have_mid)
         call move_alloc(new_skipped, skipped)
         deallocate (err_mid, wide)
         ! the new nodes: bisected in s as every node's curve; one whose check curve has
         ! no solve (every node cleared by the estimate: split for its stencil's share of
         ! gap_bound) built from its first nodes
         fresh = pack(promoted, [(.not. allocated(curves(promoted(k))%s), &
            & k = 1, size(promoted))])
         if (size(fresh) > 0) then
            promoted = pack(promoted, [(allocated(curves(promoted(k))%s), &
               & k = 1, size(promoted))])
            allocate (built(size(fresh)))
            call build_curves(table, options, m(fresh), shift, built, error)
            if (allocated(error)) return
            do k = 1, size(fresh)
               call move_curve(built(k), curves(fresh(k)))
            end do
            deallocate (built)
         end if
         call verify_curves(table, curves, promoted, error)
         if (allocated(error)) return
         deallocate (promoted)
      end do
      call fatal_error(error, egw_not_converged, "hysteresis table: rel_tol = "// &
         & format_real(table%rel_tol)//" not reached: the delta_max grid did not settle "// &
         & "after 30 bisections")
   end subroutine refine_m

   !> The s nodes at which the check curve of delta_max interval j is solved (s) and, on gap
   !> tables, those left to the estimate (skipped; gap_check_skip): its neighbours' union
   !> (log-ratio: the nodes both hold, less check_skip's), s = 0 aside.
   pure subroutine check_nodes(table, m, curves, j, m_bound, s, skipped)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: m(:), m_bound
      type(unloading_curve), intent(in) :: curves(:)
      integer, intent(in) :: j
      real(dp), allocatable, intent(out) :: s(:), skipped(:)
      logical, allocatable :: keep(:)
      integer :: i
      if (log_table(table)) then
         ! (log-ratio: the nodes both neighbours hold, where their values are
         ! solves and the mismatch is the interpolation's in delta_max; a node of
         ! one of them alone is its own bisection's, checked there to rel_tol/4:
         ! egw-bench's table at 1e-4 58 x 75 nodes against 59 x 75 with the
         ! union, build CPU -6 %, far_errors passing, the [-2, 3] sigma table's
         ! 7.2e-5 -> 8.1e-5 (doc/benchmarks.md, stop 48))
         call shared_nodes(curves(j)%s, curves(j + 1)%s, s)
      else
         call merge_nodes(curves(j)%s, curves(j + 1)%s, s)
      end if
      ! (but s = 0, where every gap is 0 and so is the mismatch: its solve gives only the
      ! slope, which the check does not use)
      s = pack(s, s > 0.0_dp)
      ! (six-point log-ratio stencils: not where four points meet check_skip)
      if (log_table(table) .and. size(m) >= 6) then
         allocate (keep(size(s)))
         do i = 1, size(s)
            keep(i) = check_weight(curves(j), curves(j + 1), s(i))*order_gap(table, m, &
               & curves, j, s(i)) >= check_skip*m_bound
         end do
         s = pack(s, keep)
         deallocate (keep)
      end if
      ! (gap tables: not where two four-point stencils meet gap_check_skip)
      if (table%mapped .and. size(m) >= 5) then
         allocate (keep(size(s)))
         do i = 1, size(s)
            keep(i) = skip_weight(table, curves(j), curves(j + 1), s(i))* &
               & shift_gap(table, m, curves, j, s(i)) >= gap_check_skip*m_bound
         end do
         skipped = pack(s, .not. keep)
         s = pack(s, keep)
      end if
   end subroutine check_nodes

   !> Solve the check curves built(:) (their nodes s set) of the delta_max intervals idx(:)
   !> into mids(idx): gap tables' intervals with no node left get an empty curve instead,
   !> without its loading solve.
   subroutine solve_checks(table, options, shift, m, idx, built, mids, error)
      type(hysteresis_table), intent(inout) :: table
      type(solver_options), intent(in) :: options
      logical, intent(in) :: shift
      real(dp), intent(in) :: m(:)
      integer, intent(in) :: idx(:)
      type(unloading_curve), intent(inout) :: built(:), mids(:)
      type(egw_error), allocatable, intent(out) :: error
      type(unloading_curve), allocatable :: solved(:)
      type(unloading_curve) :: blank
      integer, allocatable :: sel(:)
      integer :: k
      sel = [(k, k = 1, size(idx))]
      if (table%mapped) sel = pack(sel, [(size(built(k)%s) > 0, k = 1, size(idx))])
      allocate (solved(size(sel)))
      do k = 1, size(sel)
         call move_curve(built(sel(k)), solved(k))
      end do
      call build_curves(table, options, 0.5_dp*(m(idx(sel)) + m(idx(sel) + 1)), shift, &
         & solved, error, check=.true.)
      if (allocated(error)) return
      do k = 1, size(idx)
         call move_curve(blank, mids(idx(k)))
      end do
      do k = 1, size(sel)
         call move_curve(solved(k), mids(idx(sel(k))))
      end do
   end subroutine solve_checks

   !> Gap tables: the kept check curves (have_mid) whose skipped nodes a changed stencil no
   !> longer clears (shift_gap against gap_check_skip) solved there, on their own loading
   !> histories, and those nodes joined to theirs.
   subroutine solve_uncleared(table, options, shift, m, curves, m_bound, have_mid, mids, &
      & skipped, error)
      type(hysteresis_table), intent(inout) :: table
      type(solver_options), intent(in) :: options
      logical, intent(in) :: shift
      real(dp), intent(in) :: m(:), m_bound
      type(unloading_curve), intent(in) :: curves(:)
      logical, intent(in) :: have_mid(:)
      type(unloading_curve), intent(inout) :: mids(:)
      type(skipped_nodes), intent(inout) :: skipped(:)
      type(egw_error), allocatable, intent(out) :: error
      type(skipped_nodes) :: need(size(mids))
      type(unloading_curve), allocatable :: extra(:)
      integer, allocatable :: redo(:)
      logical, allocatable :: keep(:)
      integer :: j, k
      do j = 1, size(mids)
         if (.not. have_mid(j) .or. .not. allocated(skipped(j)%s)) cycle
         if (size(skipped(j)%s) == 0) cycle
         allocate (keep(size(skipped(j)%s)))
         do k = 1, size(skipped(j)%s)
            keep(k) = skip_weight(table, curves(j), curves(j + 1), skipped(j)%s(k))* &
               & shift_gap(table, m, curves, j, skipped(j)%s(k)) >= gap_check_skip*m_bound
         end do
         need(j)%s = pack(skipped(j)%s, keep)
         skipped(j)%s = pack(skipped(j)%s, .not. keep)
         deallocate (keep)
      end do
      redo = pack([(j, j = 1, size(mids))], [(allocated(need(j)%s), j = 1, size(mids))])
      if (size(redo) > 0) redo = pack(redo, [(size(need(redo(k))%s) > 0, k = 1, size(redo))])
      if (size(redo) == 0) return
      allocate (extra(size(redo)))
      do k = 1, size(redo)
         extra(k) = mids(redo(k))
         call move_alloc(need(redo(k))%s, extra(k)%s)
      end do
      call build_curves(table, options, 0.5_dp*(m(redo) + m(redo + 1)), shift, extra, &
         & error, check=.true.)
      if (allocated(error)) return
      do k = 1, size(redo)
         call join_nodes(extra(k), mids(redo(k)))
         call move_curve(extra(k), mids(redo(k)))
      end do
   end subroutine solve_uncleared

   !> A gap curve table's (rough + cap's, relative to P(m)) error bound on delta_max
   !> interval j: its check curve's mismatch err_mid, found at that curve's s nodes, plus
   !> the stencil's Lebesgue sum (the largest sum |w| at seven points of the interval)
   !> times its curves' largest error in s (refine_curve's, their cubics' mismatch at
   !> their intervals' middles): between the check curve's s nodes each stencil curve's
   !> cubic errs by up to that, the weights carrying it into the evaluation (refine_m adds
   !> the solves' rel_tol). err_mid alone
   !> under-reported the dense check's error ~1.5x (E-GW + cap, sigma/delta_y 5e-3, to
   !> 3 delta_y: 1e-3 2.47e-4 against 3.9e-4 of P(m), 1e-4 4.33e-5 against 6.7e-5;
   !> doc/stability.md "Stop 54 (doubt20)").
   pure real(dp) function gap_bound(table, m, curves, j, err_mid) result(bound)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: m(:)
      type(unloading_curve), intent(in) :: curves(:)
      integer, intent(in) :: j
      real(dp), intent(in) :: err_mid   !< the check curve's mismatch (stencil_mismatch)
      real(dp) :: w(max_stencil), xm(max_stencil), lebesgue
      integer :: first, lo, hi, k_b, i
      k_b = m_breakpoint(m)
      call stencil_window(j, size(m), k_b, stencil_width(table%log_ratio, size(m)), first, &
         & lo, hi)
      first = first + lo - 1
      hi = hi - lo + 1
      xm(1:hi) = m_coordinate(m(first:first + hi - 1), k_b)
      lebesgue = 0.0_dp
      do i = 1, 7
         call lagrange_weights(m_coordinate(m(j) + real(i, dp)/8.0_dp*(m(j + 1) - m(j)), &
            & k_b), xm(1:hi), w(1:hi))
         lebesgue = max(lebesgue, sum(abs(w(1:hi))))
      end do
      bound = err_mid + lebesgue*maxval(curves(first:first + hi - 1)%worst)
   end function gap_bound

   !> Splits deferred (log-ratio tables, split_defer): wide(j) is cleared where interval j
   !> misses the bound by less than split_defer times it and a neighbour misses by more.
   !> The interval of the largest miss is always split (the passes end).
   pure subroutine defer_splits(err_mid, bound, wide)
      real(dp), intent(in) :: err_mid(:), bound
      logical, intent(inout) :: wide(:)
      logical :: fails(size(err_mid))
      integer :: j, n
      n = size(err_mid)
      fails = err_mid > bound .and. wide
      do j = 1, n
         if (.not. fails(j) .or. err_mid(j) >= split_defer*bound) cycle
         if (j > 1) then
            if (fails(j - 1) .and. err_mid(j - 1) > err_mid(j)) wide(j) = .false.
         end if
         if (j < n) then
            if (fails(j + 1) .and. err_mid(j + 1) > err_mid(j)) wide(j) = .false.
         end if
      end do
   end subroutine defer_splits

   !> The weight of a check skip's estimate at s between the node curves a and b: on u
   !> curves (rough + cap, ratio_on_map) the largest local_weight(u, m_share) of their
   !> nodes around s, the check's own weight there (unweighted, the estimate in u cleared
   !> every check node near the front, where u ~ 1e-3, and the weighted check never saw
   !> it: README's E-GW + cap table at 1e-4 erred by 1.3e-3 of the local force at 1e-3
   !> P(m) from 3.2 to 5.1 delta_y; doc/benchmarks.md "Stop 66: goal33"); 1 else.
   pure real(dp) function skip_weight(table, a, b, s) result(w)
      type(hysteresis_table), intent(in) :: table
      type(unloading_curve), intent(in) :: a, b   !< the interval's node curves
      real(dp), intent(in) :: s                   !< the check node
      w = 1.0_dp
      if (.not. table%ratio_on_map) return
      w = max(around(a), around(b))
   contains
      !> c's weight at its last node at or below s and its first at or above, the larger
      pure real(dp) function around(c) result(wc)
         type(unloading_curve), intent(in) :: c
         integer :: i
         wc = 1.0_dp
         if (.not. c%p_turn > 0.0_dp) return
         do i = 1, size(c%s)
            if (c%s(i) <= s) wc = local_weight(c%gap(i), m_share)
            if (c%s(i) >= s) then
               wc = max(wc, local_weight(c%gap(i), m_share))
               exit
            end if
         end do
      end function around
   end function skip_weight

   !> The largest shift_gap of interval j at the nodes s.
   pure real(dp) function skip_estimate(table, m, curves, j, s) result(est)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: m(:), s(:)
      type(unloading_curve), intent(in) :: curves(:)
      integer, intent(in) :: j
      integer :: i
      est = 0.0_dp
      do i = 1, size(s)
         est = max(est, skip_weight(table, curves(j), curves(j + 1), s(i))* &
            & shift_gap(table, m, curves, j, s(i)))
      end do
   end function skip_estimate

   !> Gap tables (mapped): |g_A - g_B| at the turning point halfway along delta_max
   !> interval j, where A is the evaluation's four-point stencil and B that stencil
   !> shifted by one node (each side where one fits on the interval's side of the
   !> breakpoint; the larger difference), both at the same m - delta, that of s on A's
   !> interpolated map, each stencil's s from its own interpolated knee (map_s), so that
   !> the knee's interpolation counts as in the check (stencil_mismatch); huge where no
   !> shifted stencil fits.
   pure real(dp) function shift_gap(table, m, curves, j, s) result(d)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: m(:), s
      type(unloading_curve), intent(in) :: curves(:)
      integer, intent(in) :: j
      real(dp) :: mid, x, v_a, v_b
      integer :: first, lo, hi, k_b, shift, n
      d = huge(1.0_dp)
      n = size(m)
      k_b = m_breakpoint(m)
      mid = 0.5_dp*(m(j) + m(j + 1))
      call stencil_window(j, n, k_b, 4, first, lo, hi)
      call combine(first, .true., x, v_a)
      do shift = -1, 1, 2
         if (first + shift < 1 .or. first + shift + 3 > n) cycle
         if (k_b > 0) then
            if (j < k_b .and. first + shift + 3 > k_b) cycle
            if (j >= k_b .and. first + shift < k_b) cycle
         end if
         call combine(first + shift, .false., x, v_b)
         if (d == huge(1.0_dp)) d = 0.0_dp
         d = max(d, abs(v_a - v_b))
      end do
   contains
      !> The stencil first .. first + 3 at the turning point mid: its g at x (at s, and x
      !> set from its map, where at_s).
      pure subroutine combine(first, at_s, x, v)
         integer, intent(in) :: first
         logical, intent(in) :: at_s
         real(dp), intent(inout) :: x
         real(dp), intent(out) :: v
         real(dp) :: w(4), knee, iota, s_p, r, dr, dsdx
         integer :: k
         call lagrange_weights(m_coordinate(mid, k_b), m_coordinate(m(first:first + 3), &
            & k_b), w)
         knee = min(max(sum(w*curves(first:first + 3)%knee), 0.0_dp), &
            & 0.99_dp*max(mid, 0.0_dp))
         iota = map_iota(table, mid, knee)
         if (at_s) then
            call map_x(table, mid, knee, iota, s, x, dsdx)
            s_p = s
         else
            call map_s(table, mid, knee, iota, x, s_p, dsdx)
            s_p = min(s_p, 1.0_dp)
         end if
         v = 0.0_dp
         do k = 1, 4
            call curve_eval(curves(first + k - 1), s_p, r, dr)
            v = v + w(k)*r
         end do
      end subroutine combine
   end function shift_gap

   !> |h6 - h4| at s of the turning point halfway along delta_max interval j: the node
   !> curves combined on the six-point and on the four-point stencil of the interval, each
   !> at xi = m - delta of s on the six-point stencil's edge map (its interpolated L), so
   !> that the difference of the interpolated L's maps counts as in the check; huge where
   !> the interval's side of the m = 0 node has fewer than six nodes (both are four there).
   pure real(dp) function order_gap(table, m, curves, j, s) result(d)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: m(:), s
      type(unloading_curve), intent(in) :: curves(:)
      integer, intent(in) :: j
      real(dp) :: x, xm(max_stencil), w(max_stencil), v(2), r, dr, length, xi_b(3), xi, &
         & s_p, ds
      integer :: first, lo, hi, k, pass, k_b, n
      d = huge(1.0_dp)
      k_b = m_breakpoint(m)
      x = m_coordinate(0.5_dp*(m(j) + m(j + 1)), k_b)
      xi = 0.0_dp
      do pass = 1, 2
         call stencil_window(j, size(m), k_b, merge(6, 4, pass == 1), first, lo, hi)
         first = first + lo - 1
         n = hi - lo + 1
         if (pass == 1 .and. n < 6) return
         xm(1:n) = m_coordinate(m(first:first + n - 1), k_b)
         call lagrange_weights(x, xm(1:n), w(1:n))
         length = 1.0_dp/sum(w(1:n)/curves(first:first + n - 1)%length)
         call edge_breaks(length, table%params%sigma, xi_b)
         if (pass == 1) then
            call edge_xi(xi_b, s, xi)
            s_p = s
         else
            call edge_s(xi_b, xi, s_p, ds)
            s_p = min(s_p, 1.0_dp)
         end if
         v(pass) = 0.0_dp
         do k = 1, n
            call curve_eval(curves(first + k - 1), s_p, r, dr)
            v(pass) = v(pass) + w(k)*r
         end do
      end do
      d = abs(v(1) - v(2))
   end function order_gap

   !> The Lagrange weights at x of the nodes xm (the stencil's coordinates in m).
   pure subroutine lagrange_weights(x, xm, w)
      real(dp), intent(in) :: x, xm(:)
      real(dp), intent(out) :: w(:)   !< size(xm)
      integer :: k, l
      do k = 1, size(xm)
         w(k) = 1.0_dp
         do l = 1, size(xm)
            if (l /= k) w(k) = w(k)*(x - xm(l))/(xm(k) - xm(l))
         end do
      end do
   end subroutine lagrange_weights

   !> A bound on the weight min(1, P/(local_floor P(m))) at s of the check curve between the
   !> node curves a and b: twice the larger of their weights at their last node at or
   !> below s (the force falls along s), at most 1.
   pure real(dp) function check_weight(a, b, s) result(w)
      type(unloading_curve), intent(in) :: a, b
      real(dp), intent(in) :: s
      w = min(1.0_dp, 2*max(weight_before(a), weight_before(b)))
   contains
      pure real(dp) function weight_before(c) result(wc)
         type(unloading_curve), intent(in) :: c
         integer :: i
         wc = 1.0_dp
         do i = 1, size(c%s)
            if (c%s(i) <= s) wc = c%weight(i)
         end do
      end function weight_before
   end function check_weight

   !> Largest |r_stencil - r_mid| of interval j over the nodes of the midpoint curve (solves):
   !> the table's whole error there, its interpolation in s included (the curves are built
   !> to rel_tol/4, so that what remains is mostly the error in m, which bisection removes).
   !> The stencil is the evaluation's (stencil_window: six nodes for log-ratio curves).
   pure real(dp) function stencil_mismatch(table, m, curves, j, mid) result(err)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: m(:)
      type(unloading_curve), intent(in) :: curves(:), mid
      integer, intent(in) :: j
      real(dp) :: x, w(max_stencil), r, dr, v, s, length, xm(max_stencil), knee, offset, &
         & dsdx, xi_b(3), xi, ds
      integer :: first, k, i, k_b, lo, hi
      k_b = m_breakpoint(m)
      call stencil_window(j, size(m), k_b, stencil_width(table%log_ratio, size(m)), first, &
         & lo, hi)
      first = first + lo - 1   ! (the stencil's own nodes: w(1:n))
      hi = hi - lo + 1
      x = m_coordinate(0.5_dp*(m(j) + m(j + 1)), k_b)
      xm(1:hi) = m_coordinate(m(first:first + hi - 1), k_b)
      call lagrange_weights(x, xm(1:hi), w(1:hi))
      ! the table's s of the midpoint curve's delta: with the interpolated L(m)
      ! as the evaluation: 1/L interpolated
      length = 1.0_dp/sum(w(1:hi)/curves(first:first + hi - 1)%length)
      ! mapped: the knee interpolated and the first piece's span from it (turning_point)
      knee = min(max(sum(w(1:hi)*curves(first:first + hi - 1)%knee), 0.0_dp), &
         & 0.99_dp*max(mid%m, 0.0_dp))
      if (table%mapped) length = 1.0_dp/map_iota(table, mid%m, knee)
      err = 0.0_dp
      ! (log-ratio: the edge map of the interpolated L, the mismatch in h weighted)
      if (mid%log) call edge_breaks(length, table%params%sigma, xi_b)
      do i = 1, size(mid%s)
         if (mid%log) then
            call edge_xi(mid%xi, mid%s(i), xi)
            call edge_s(xi_b, xi, s, ds)
            s = min(s, 1.0_dp)
         else if (table%mapped) then
            offset = curve_offset(table, mid, mid%s(i))
            call map_s(table, mid%m, knee, 1.0_dp/length, offset, s, dsdx)
            s = min(s, 1.0_dp)
         else if (table%force_ratio) then
            ! (1/L from the fine grid, of which the midpoint is a node: its own L)
            s = mid%s(i)
         else
            s = min(mid%s(i)*mid%length/length, 1.0_dp)
         end if
         v = 0.0_dp
         do k = 1, hi
            call curve_eval(curves(first + k - 1), s, r, dr)
            v = v + w(k)*r
         end do
         ! (gap curves: relative to P(m), their weight is refine_curve's alone; u curves
         ! weighted: the local force's tolerance down to local_floor P(m) between the
         ! node curves too; Hertz + cap's as in refine_curve, on the two-piece map by
         ! local_weight with m_share)
         if (table%ratio_on_map .and. mid%p_turn > 0.0_dp) then
            err = max(err, local_weight(mid%gap(i), m_share)*abs(v - mid%gap(i)))
         else if (table%force_ratio .or. table%ratio_on_map) then
            err = max(err, mid%weight(i)*abs(v - mid%gap(i)))
         else if (.not. mid%log) then
            err = max(err, abs(v - mid%gap(i)))
         else
            err = max(err, mid%weight(i)*abs(v - mid%gap(i)))
         end if
      end do
   end function stencil_mismatch

   !> A force-ratio (Hertz + cap) table's error at the nodes of the check curve of interval
   !> j relative to max(P, local_floor P(m)): the stencil's sum of u against the check
   !> solves' P/P_load,table(m) (c_turn u), so that the loading table's error at the
   !> turning point counts as in the evaluation. Its stencil, s and weights: stencil_mismatch's.
   pure real(dp) function whole_mismatch(table, m, curves, j, mid) result(err)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: m(:)
      type(unloading_curve), intent(in) :: curves(:), mid
      integer, intent(in) :: j
      type(unloading_curve) :: shifted
      shifted = mid
      shifted%gap = mid%c_turn*mid%gap
      err = stencil_mismatch(table, m, curves, j, shifted)
   end function whole_mismatch

   !> Put every curve on the union of their s nodes: the union refines each curve's own
   !> nodes, so the Hermite data there reproduce each curve's cubics exactly.
   pure subroutine resample(table, m, curves)
      type(hysteresis_table), intent(inout) :: table   !< the table being built
      real(dp), intent(in) :: m(:)   !< the delta_max grid
      type(unloading_curve), intent(in) :: curves(:)   !< its curves
      real(dp), allocatable :: all_s(:), union(:)
      integer :: j, i, n
      all_s = curves(1)%s
      do j = 2, size(curves)
         call merge_nodes(all_s, curves(j)%s, union)
         call move_alloc(union, all_s)
      end do
      n = size(all_s)
      table%m = m
      table%length = curves%length
      if (table%mapped) table%knee = curves%knee
      table%s = all_s(1:n)
      allocate (table%gap(n, size(m)), table%slope(n, size(m)))
      do j = 1, size(m)
         do i = 1, n
            call curve_eval(curves(j), table%s(i), table%gap(i, j), table%slope(i, j), &
               & stored=.true.)
         end do
      end do
   end subroutine resample

   !> c = the union of the increasing node lists a and b, increasing, each value once.
   pure subroutine merge_nodes(a, b, c)
      real(dp), intent(in) :: a(:), b(:)
      real(dp), allocatable, intent(out) :: c(:)
      real(dp) :: work(size(a) + size(b)), next
      integer :: i, j, n
      i = 1
      j = 1
      n = 0
      do while (i <= size(a) .or. j <= size(b))
         if (j > size(b)) then
            next = a(i)
         else if (i > size(a)) then
            next = b(j)
         else
            next = min(a(i), b(j))
         end if
         n = n + 1
         work(n) = next
         if (i <= size(a)) then
            if (a(i) == next) i = i + 1
         end if
         if (j <= size(b)) then
            if (b(j) == next) j = j + 1
         end if
      end do
      c = work(1:n)
   end subroutine merge_nodes

   !> c = the values that both increasing node lists a and b hold, increasing.
   pure subroutine shared_nodes(a, b, c)
      real(dp), intent(in) :: a(:), b(:)
      real(dp), allocatable, intent(out) :: c(:)
      real(dp) :: work(min(size(a), size(b)))
      integer :: i, j, n
      i = 1
      j = 1
      n = 0
      do while (i <= size(a) .and. j <= size(b))
         if (a(i) == b(j)) then
            n = n + 1
            work(n) = a(i)
            i = i + 1
            j = j + 1
         else if (a(i) < b(j)) then
            i = i + 1
         else
            j = j + 1
         end if
      end do
      c = work(1:n)
   end subroutine shared_nodes

   !> Add the nodes (s, gap, slope, weight) of the check curve old to those of into (none
   !> of them the same), increasing in s.
   pure subroutine join_nodes(into, old)
      type(unloading_curve), intent(inout) :: into
      type(unloading_curve), intent(in) :: old
      real(dp), allocatable :: s(:), g(:), d(:), w(:)
      integer :: i, k, n
      real(dp) :: v(4)
      if (.not. allocated(old%s)) return
      s = [into%s, old%s]
      g = [into%gap, old%gap]
      d = [into%slope, old%slope]
      w = [into%weight, old%weight]
      n = size(s)
      do i = 2, n
         v = [s(i), g(i), d(i), w(i)]
         k = i - 1
         do while (k >= 1)
            if (s(k) <= v(1)) exit
            s(k + 1) = s(k)
            g(k + 1) = g(k)
            d(k + 1) = d(k)
            w(k + 1) = w(k)
            k = k - 1
         end do
         s(k + 1) = v(1)
         g(k + 1) = v(2)
         d(k + 1) = v(3)
         w(k + 1) = v(4)
      end do
      call move_alloc(s, into%s)
      call move_alloc(g, into%gap)
      call move_alloc(d, into%slope)
      call move_alloc(w, into%weight)
   end subroutine join_nodes

   pure subroutine move_curve(from, to)
      type(unloading_curve), intent(inout) :: from
      type(unloading_curve), intent(out) :: to
      to%length = from%length
      to%m = from%m
      to%span = from%span
      to%scale = from%scale
      to%c_turn = from%c_turn
      to%knee = from%knee
      to%piece_scale = from%piece_scale
      to%verified = from%verified
      to%worst = from%worst
      to%hist = from%hist
      to%log = from%log
      to%xi = from%xi
      to%p_turn = from%p_turn
      if (allocated(from%weight)) call move_alloc(from%weight, to%weight)
      if (allocated(from%mismatch)) call move_alloc(from%mismatch, to%mismatch)
      call move_alloc(from%s, to%s)
      call move_alloc(from%gap, to%gap)
      call move_alloc(from%slope, to%slope)
   end subroutine move_curve

end module egw_hysteresis_grid
