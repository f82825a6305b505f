!> What a hysteresis table read from a file must satisfy before it is evaluated
!> (doc/formats.md §6): valid parameters, a sane loading curve, increasing grids, curves
!> within their bounds and, on log-ratio tables, no served force above twice its turning
!> point's. The readers of egw_hysteresis_format call these after parsing either format.
module egw_hysteresis_checks
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp
   use egw_status, only: egw_error, int_str, format_real, bad => bad_file_error
   use egw_params, only: validate_params
   use egw_table, only: table_eval
   use egw_table_format, only: check_table
   use egw_hysteresis, only: hysteresis_table, first_yield, hertz_capped, cap_first_turn
   use egw_hysteresis_data, only: s_knee, s_zero, map_piece, map_iota, map_lengths, &
      & max_log_ratio, edge_breaks, edge_xi
   implicit none
   private

   public :: check_hysteresis, check_log_served

contains

   !> What a hysteresis table must satisfy to be evaluated: valid parameters, a sane
   !> loading curve (everything a force table's reader checks, check_table: finite;
   !> increasing nodes; force >= 0 and non-decreasing; stiffness >= 0 and consistent with
   !> the force differences; energies consistent with the forces) and unloading grid (m
   !> from the cut-off to delta_max, s from 0 to 1, both increasing; gap finite, 0 at
   !> s = 0 and within [0, 1] up to the tables' errors; its slopes small enough that no
   !> curve strays far from [0, 1] between nodes: check_gap_slopes).
   subroutine check_hysteresis(path, t, error)
      character(len=*), intent(in) :: path   !< the file's path (for the message)
      type(hysteresis_table), intent(in) :: t   !< the table as read
      !> egw_bad_file naming what is wrong (not allocated: the table passes)
      type(egw_error), allocatable, intent(out) :: error
      integer :: n, n_m, n_s
      real(dp) :: first
      call validate_params(t%params, error)
      if (allocated(error)) then
         call bad(error, path, "stored parameters invalid: "//error%message)
         return
      end if
      if (.not. (t%rel_tol >= 1.0e-8_dp .and. t%rel_tol <= 0.1_dp) .or. &
         & .not. (t%max_error >= 0.0_dp .and. t%max_error < huge(1.0_dp))) then
         call bad(error, path, "rel_tol or max_error out of range")
         return
      end if
      associate (l => t%loading)
         n = size(l%delta)
         if (.not. (all(ieee_is_finite(l%delta)) .and. all(ieee_is_finite(l%force)) .and. &
            & all(ieee_is_finite(l%stiffness)) .and. all(ieee_is_finite(l%energy)) .and. &
            & all(ieee_is_finite(l%contact_radius)) .and. &
            & all(ieee_is_finite([l%rel_tol, l%reference_force, l%max_force_error, &
            & l%max_stiffness_error, l%radius_sum])))) then
            call bad(error, path, "loading curve: a value is not finite")
            return
         end if
         if (any(l%delta(2:n) <= l%delta(1:n - 1)) .or. l%cutoff /= l%delta(1) .or. &
            & l%delta_max /= l%delta(n) .or. t%delta_max > l%delta(n)) then
            call bad(error, path, "loading curve: nodes not increasing, or cutoff/delta_max "// &
               & "disagree with them")
            return
         end if
         if (any(l%force < 0.0_dp) .or. any(l%force(2:n) < l%force(1:n - 1)) .or. &
            & any(l%stiffness < 0.0_dp) .or. any(l%energy < 0.0_dp) .or. &
            & any(l%contact_radius < 0.0_dp) .or. .not. l%reference_force > 0.0_dp) then
            call bad(error, path, "loading curve: force, stiffness, energy or contact radius "// &
               & "negative, or force decreasing")
            return
         end if
         if (l%n_log < 0 .or. l%n_log > n - 1 .or. l%rel_tol /= t%rel_tol) then
            call bad(error, path, "loading curve: n_log or rel_tol out of range")
            return
         end if
         if (l%n_log > 0) then
            if (any(l%force(1:l%n_log + 1) <= 0.0_dp)) then
               call bad(error, path, "loading curve: log-space interval with a zero force")
               return
            end if
         end if
         call check_table(path, "loading curve: ", l, error)
         if (allocated(error)) return
      end associate
      n_m = size(t%m)
      n_s = size(t%s)
      if (t%reversible) then
         if (n_m /= 0 .or. n_s /= 0) call bad(error, path, "a reversible table has no curves")
         return
      end if
      if (n_m < 4 .or. n_s < 2) then
         call bad(error, path, "fewer than 4 delta_max nodes or 2 s nodes")
         return
      end if
      if (.not. (all(ieee_is_finite(t%m)) .and. all(ieee_is_finite(t%s)) .and. &
         & all(ieee_is_finite(t%gap)) .and. all(ieee_is_finite(t%slope)) .and. &
         & all(ieee_is_finite(t%length)) .and. ieee_is_finite(t%s_max))) then
         call bad(error, path, "unloading data: a value is not finite")
         return
      end if
      if (any(t%length <= 0.0_dp) .or. .not. t%s_max > 0.0_dp) then
         call bad(error, path, "unloading data: length and s_max must be > 0")
         return
      end if
      first = t%loading%cutoff
      if (hertz_capped(t%params)) first = first_yield(t%params)
      ! a rough model with the cap and elastic summits starts at its rough first yield
      if (t%params%flow_pressure > 0.0_dp .and. .not. hertz_capped(t%params) .and. &
         & t%m(1) >= first) first = t%m(1)
      ! (Hertz + cap from stop 52: the first capped turning point; earlier files delta_y)
      if (hertz_capped(t%params)) then
         if (t%m(1) == cap_first_turn(t%params)) first = t%m(1)
      end if
      if (any(t%m(2:n_m) <= t%m(1:n_m - 1)) .or. t%m(1) /= first .or. &
         & t%m(n_m) /= t%delta_max .or. any(t%s(2:n_s) <= t%s(1:n_s - 1)) .or. &
         & t%s(1) /= 0.0_dp .or. t%s(n_s) /= 1.0_dp) then
         call bad(error, path, "unloading grid: delta_max from the cut-off (first yield "// &
            & "delta_y, or the first capped turning point, with the flow-pressure cap; a "// &
            & "rough model with the cap: at or above "// &
            & "the cut-off) to delta_max "// &
            & "and s from 0 to 1 must increase")
         return
      end if
      if (t%log_ratio) then
         call check_log_curves(path, t, error)
         return
      end if
      if (t%force_ratio) then
         call check_ratio_curves(path, t, error)
         if (.not. allocated(error)) call check_gap_slopes(path, t, error)
         return
      end if
      if (t%mapped .and. t%ratio_on_map) then
         call check_map_ratio(path, t, error)
         if (allocated(error)) return
         call check_map(path, t, error)
         if (.not. allocated(error)) call check_gap_slopes(path, t, error)
         return
      end if
      ! the gap is relative to the turning-point force: within [0, 1] up to the tables'
      ! own errors
      if (any(t%gap(1, :) /= 0.0_dp) .or. any(t%gap < -10*t%rel_tol) .or. &
         & any(t%gap > 1.0_dp + 10*t%rel_tol)) then
         call bad(error, path, "unloading data: gap must be 0 at s = 0 and within [0, 1]")
         return
      end if
      if (t%mapped) then
         call check_map(path, t, error)
         if (allocated(error)) return
      end if
      call check_gap_slopes(path, t, error)
   end subroutine check_hysteresis

   !> The force-ratio curves of format 5 (Hertz + cap): the cap's smooth sphere, s_max = 1,
   !> u = P/P_load(m) 1 at s = 0, 0 at s = 1 and within [0, 1 + 10 rel_tol] (an unloading
   !> force never exceeds its turning point's; the solves' own error aside), and the fine
   !> grid: at least 4 nodes, finite, increasing from m(1) to m(n_m), every delta_max node
   !> among them with its curve's length, each length in (0, its delta_max] (L = m -
   !> residual overlap).
   subroutine check_ratio_curves(path, t, error)
      character(len=*), intent(in) :: path
      type(hysteresis_table), intent(in) :: t
      type(egw_error), allocatable, intent(out) :: error
      integer :: n_f, j, k
      if (.not. (hertz_capped(t%params) .and. t%s_max == 1.0_dp)) then
         call bad(error, path, "force-ratio curves (format 5): need Hertz (or sigma = 0) "// &
            & "with the cap and s_max = 1")
         return
      end if
      if (any(t%gap(1, :) /= 1.0_dp) .or. any(t%gap(size(t%s), :) /= 0.0_dp) .or. &
         & any(t%gap < 0.0_dp) .or. any(t%gap > 1.0_dp + 10*t%rel_tol)) then
         call bad(error, path, "unloading data: force_ratio must be 1 at s = 0, 0 at "// &
            & "s = 1 and within [0, 1 + 10 rel_tol]")
         return
      end if
      if (.not. (allocated(t%fine_m) .and. allocated(t%fine_length))) then
         call bad(error, path, "force-ratio curves (format 5): no fine grid")
         return
      end if
      n_f = size(t%fine_m)
      if (n_f < 4 .or. size(t%fine_length) /= n_f) then
         call bad(error, path, "force-ratio curves (format 5): fine grid of "// &
            & int_str(n_f)//" nodes (at least 4)")
         return
      end if
      if (.not. (all(ieee_is_finite(t%fine_m)) .and. all(ieee_is_finite(t%fine_length)))) then
         call bad(error, path, "force-ratio curves (format 5): a fine grid value is not finite")
         return
      end if
      if (any(t%fine_m(2:n_f) <= t%fine_m(1:n_f - 1)) .or. t%fine_m(1) /= t%m(1) .or. &
         & t%fine_m(n_f) /= t%m(size(t%m))) then
         call bad(error, path, "force-ratio curves (format 5): the fine grid must increase "// &
            & "from the first delta_max node to the last")
         return
      end if
      if (any(t%fine_length <= 0.0_dp) .or. any(t%fine_length > t%fine_m)) then
         call bad(error, path, "force-ratio curves (format 5): each fine length must lie "// &
            & "in (0, its delta_max]")
         return
      end if
      do j = 1, size(t%m)
         k = findloc(t%fine_m, t%m(j), 1)
         if (k == 0) then
            call bad(error, path, "force-ratio curves (format 5): delta_max node "// &
               & int_str(j)//" is not a node of the fine grid")
            return
         end if
         if (t%fine_length(k) /= t%length(j)) then
            call bad(error, path, "force-ratio curves (format 5): fine length at delta_max "// &
               & "node "//int_str(j)//" = "//format_real(t%fine_length(k))// &
               & " differs from the curve's length "//format_real(t%length(j)))
            return
         end if
      end do
   end subroutine check_ratio_curves

   !> The curves of format 6 (u = P/P_load(m) on the two-piece map): u 1 at s = 0 and
   !> within [-10 rel_tol, 1 + 10 rel_tol] (an unloading force is never negative and never
   !> exceeds its turning point's; the solves' and the resampled cubics' own errors aside:
   !> built tables dip to -0.15 rel_tol, E-GW + cap at 1e-3, where the evaluation clips the
   !> force at 0); the map itself: check_map. (Not 0 at s = 1: the tail's end, where a
   !> turning point at or below 0 keeps much of its force.)
   subroutine check_map_ratio(path, t, error)
      character(len=*), intent(in) :: path
      type(hysteresis_table), intent(in) :: t
      type(egw_error), allocatable, intent(out) :: error
      if (any(t%gap(1, :) /= 1.0_dp) .or. any(t%gap < -10*t%rel_tol) .or. &
         & any(t%gap > 1.0_dp + 10*t%rel_tol)) then
         call bad(error, path, "unloading data (format 6): force_ratio must be 1 at s = 0 "// &
            & "and within [-10 rel_tol, 1 + 10 rel_tol]")
      end if
   end subroutine check_map_ratio

   !> The two-piece map of format 4 (and 6): a rough model with the cap (flow_pressure > 0, not
   !> Hertz + cap), s_max = 1, tail_length > 0, each knee in [0, 0.99 max(m, 0)] and its
   !> length 1/map_iota ((m - knee)/s_knee above 0; to rounding), the breaks s_knee and
   !> s_zero nodes.
   subroutine check_map(path, t, error)
      character(len=*), intent(in) :: path
      type(hysteresis_table), intent(in) :: t
      type(egw_error), allocatable, intent(out) :: error
      integer :: j
      if (.not. (t%params%flow_pressure > 0.0_dp .and. .not. hertz_capped(t%params) .and. &
         & t%s_max == 1.0_dp .and. t%tail_length > 0.0_dp .and. &
         & ieee_is_finite(t%tail_length) .and. size(t%knee) == size(t%m))) then
         call bad(error, path, "two-piece s map (format 4): needs a rough model with the "// &
            & "cap, s_max = 1 and a finite tail_length > 0")
         return
      end if
      if (.not. (all(ieee_is_finite(t%knee)) .and. all(t%knee >= 0.0_dp) .and. &
         & all(t%knee <= 0.99_dp*max(t%m, 0.0_dp)))) then
         call bad(error, path, "two-piece s map (format 4): each knee must lie in [0, "// &
            & "0.99 delta_max]")
         return
      end if
      do j = 1, size(t%m)
         if (.not. abs(t%length(j)*map_iota(t, t%m(j), t%knee(j)) - 1.0_dp) <= 1.0e-12_dp) then
            call bad(error, path, "two-piece s map (format 4): curve "//int_str(j)// &
               & ": length "//format_real(t%length(j))//" is not its first piece's span "// &
               & "((delta_max - knee)/s_knee; above the tail's at or below 0)")
            return
         end if
      end do
      if (findloc(t%s, s_knee, 1) == 0 .or. findloc(t%s, s_zero, 1) == 0) &
         & call bad(error, path, "two-piece s map (format 4): s = 1/2 and 3/4 must be nodes")
   end subroutine check_map

   !> The log-ratio curves (EP-GW without the cap): s_max = 1, the edge map's breaks 1/2
   !> and 3/4 among the s nodes (no interval straddles one), h = ln(P_load/P) 0 at s = 0
   !> and within [-max_log_ratio, max_log_ratio] (below the loading table's cut-off, where
   !> the curves run on the loading tail's continuation and the evaluation returns 0, h
   !> reaches -1.48 on LAMMPS's column's types 2 2 table, mu 3, psi 0.3, R*/sigma 283,
   !> 1e-3, where the bound was -1 and the ranks could not share it; above it -0.27 on its
   !> pour tables, mu 8-23, psi 0.5, to 140 sigma: check_log_served bounds those nodes by
   !> the turning point's force), and no cubic rising by more
   !> than 10 max_log_ratio over an interval from its slopes (|dh/dxi| dxi; built tables:
   !> up to 452 on the last interval of egw-bench's 1e-4 table (mu 4, psi 2, to 30
   !> sigma), 469 to 140 sigma at 1e-3, where h climbs from ~50 at s = 3/4 to the stored
   !> 100 over the separated tail's 12 sigma; the bound was 4 max_log_ratio and refused
   !> the first; a crafted slope of 1e300 does not pass).
   subroutine check_log_curves(path, t, error)
      character(len=*), intent(in) :: path
      type(hysteresis_table), intent(in) :: t
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: xi_b(3), x0, x1
      integer :: i, j
      if (t%s_max /= 1.0_dp .or. .not. (any(t%s == 0.5_dp) .and. any(t%s == 0.75_dp))) then
         call bad(error, path, "unloading grid: log-ratio curves need s_max = 1 and the "// &
            & "edge map's breaks s = 0.5, 0.75 among the s nodes")
         return
      end if
      if (any(t%gap(1, :) /= 0.0_dp) .or. any(t%gap < -max_log_ratio) .or. &
         & any(t%gap > max_log_ratio)) then
         call bad(error, path, "unloading data: log_ratio must be 0 at s = 0 and within "// &
            & "[-"//format_real(max_log_ratio)//", "//format_real(max_log_ratio)//"]")
         return
      end if
      do j = 1, size(t%m)
         call edge_breaks(t%length(j), t%params%sigma, xi_b)
         do i = 1, size(t%s) - 1
            call edge_xi(xi_b, t%s(i), x0)
            call edge_xi(xi_b, t%s(i + 1), x1)
            if (max(abs(t%slope(i, j)), abs(t%slope(i + 1, j)))*(x1 - x0) > &
               & 10*max_log_ratio) then
               call bad(error, path, "unloading data: curve "//int_str(j)//", s nodes "// &
                  & int_str(i)//", "//int_str(i + 1)//": slope "// &
                  & format_real(max(abs(t%slope(i, j)), abs(t%slope(i + 1, j))))// &
                  & " inconsistent with the log ratio")
               return
            end if
         end do
      end do
   end subroutine check_log_curves

   !> Log-ratio nodes where the force is served (overlap m_j - xi above the loading
   !> table's cut-off): the unloading force P_load(delta) e**(-h) at most twice the force
   !> P_load(m_j) at the curve's turning point. An unloading force never exceeds its
   !> turning point's (the loading force does not decrease, the unloading curve lies
   !> below it within the table's tolerance); built tables reach h = -0.27 at served nodes
   !> far below the turning point (P ~ 5e-9 P(m), LAMMPS's pour tables; 193 tables of the
   !> on-disk cache scanned, doc/stability.md "Stop 49 (audit15)"), where this bound is
   !> h >= -19; the factor 2 leaves room for rel_tol up to 0.1. The bound [-100, 100] of
   !> check_log_curves let a crafted node h = -99 through: a force 3.8e37 P(m). Needs the
   !> loading table prepared (table_eval).
   subroutine check_log_served(path, t, error)
      character(len=*), intent(in) :: path   !< the file's path (for the message)
      type(hysteresis_table), intent(in) :: t   !< the table as read
      !> egw_bad_file naming what is wrong (not allocated: the table passes)
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: xi_b(3), xi, delta, p_m, p_d, k
      integer :: i, j
      do j = 1, size(t%m)
         if (.not. t%m(j) > t%loading%cutoff) cycle
         call table_eval(t%loading, t%m(j), p_m, k)
         if (.not. p_m > 0.0_dp) cycle
         call edge_breaks(t%length(j), t%params%sigma, xi_b)
         do i = 2, size(t%s)
            call edge_xi(xi_b, t%s(i), xi)
            delta = t%m(j) - xi
            if (.not. delta > t%loading%cutoff) cycle
            call table_eval(t%loading, delta, p_d, k)
            if (.not. p_d > 0.0_dp) cycle
            if (t%gap(i, j) < log(p_d/p_m) - log(2.0_dp)) then
               call bad(error, path, "unloading data: curve "//int_str(j)//", s node "// &
                  & int_str(i)//": log_ratio "//format_real(t%gap(i, j))// &
                  & " gives an unloading force of "//format_real(p_d*exp(-t%gap(i, j)))// &
                  & ", above twice the turning point's "//format_real(p_m))
               return
            end if
         end do
      end do
   end subroutine check_log_served

   !> The gap's slopes: |dg/ds| (s_{i+1} - s_i) <= 2 at both ends of every interval of
   !> every curve, so that a curve's cubic stays within about 1 of the chord of its
   !> nodes (their gaps lie in [0, 1]): the unloading force within the loading force at
   !> the turning point of the loading curve. Built tables stay below 0.4 (rel_tol 1e-2
   !> .. 1e-4, psi 0.5 .. 10, mu 0.3 .. 50); a crafted slope of 1e300 does not.
   subroutine check_gap_slopes(path, t, error)
      character(len=*), intent(in) :: path
      type(hysteresis_table), intent(in) :: t
      type(egw_error), allocatable, intent(out) :: error
      real(dp), parameter :: rise_bound = 2.0_dp
      real(dp) :: h, scale(3)
      integer :: i, j
      do j = 1, size(t%m)
         ! the two-piece map: dg/ds on each piece is the stored slope times its scale
         scale = 1.0_dp
         if (t%mapped) scale = map_lengths(t, t%m(j), t%knee(j))/t%tail_length
         do i = 1, size(t%s) - 1
            h = t%s(i + 1) - t%s(i)
            h = h*scale(map_piece(t%mapped, 0.5_dp*(t%s(i) + t%s(i + 1))))
            if (max(abs(t%slope(i, j)), abs(t%slope(i + 1, j)))*h > rise_bound) then
               call bad(error, path, "unloading data: curve "//int_str(j)//", s nodes "// &
                  & int_str(i)//", "//int_str(i + 1)//": slope "// &
                  & format_real(max(abs(t%slope(i, j)), abs(t%slope(i + 1, j))))// &
                  & " inconsistent with the gap (it rises more than "// &
                  & format_real(rise_bound)//" over the interval)")
               return
            end if
         end do
      end do
   end subroutine check_gap_slopes

end module egw_hysteresis_checks
