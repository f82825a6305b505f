!> The pieces of a hysteresis table's unloading curves that a contact's state keeps
!> (egw_hysteresis's hysteresis_eval_state, the continuation beyond a table in
!> egw_hysteresis_beyond): a piece made around an overlap, its force, and the unloading
!> branch of a turning point from its gap cubic. Apart from egw_hysteresis so that both
!> reach them (a module cannot use its user's private procedures).
module egw_hysteresis_piece
   use, intrinsic :: iso_fortran_env, only: int64
   use egw_kinds, only: dp
   use egw_table, only: table_eval, table_segment, segment_eval
   use egw_hysteresis_data, only: hysteresis_table, gap_cubic, unload_tail_ratio, &
      & map_x, map_piece, quiet_nan, unload_floor, max_stencil, stores_ratio
   implicit none
   private

   public :: piece_force, make_piece, unload_branch

   !> The loading interval's mark (state(24)) of a folded log-ratio piece (make_log_piece
   !> on a ln P interval): its cubic is ln P - h itself, its force exp of it. (2: the
   !> piece's cubic is -h, ln P the interval's; -1: P e^-h on a linear interval.)
   real(dp), parameter, public :: folded = 3.0_dp

contains

   !> The force and stiffness at delta inside a piece (make_piece: start lo, cubic c),
   !> with the loading interval seg it was made with: the cubic, plus exp of seg's cubic
   !> where that is ln P; 0 where the force is not positive. A log-ratio piece
   !> (make_log_piece: seg(7) folded on a ln P interval, c is ln P - h; 2 there with c
   !> -h; -1 on a linear one, c -h): exp(ln P - h), or P e^-h, one exp (piece_exp; egw.h's inline
   !> egw_hysteresis_eval_cached does the same arithmetic in the same order: the same
   !> bits). With hysteresis_eval_state's top, the reference of the served arithmetic's
   !> four copies (src/egw/capi/README.md: a change goes into all four).
   pure subroutine piece_force(lo, c, seg, delta, force, stiffness)
      !> the piece's start [length], its cubic in delta - lo, its loading interval, the overlap
      real(dp), intent(in) :: lo, c(4), seg(7), delta
      !> [force] and [force/length]; 0 where the force is not positive
      real(dp), intent(out) :: force, stiffness
      real(dp) :: x, x2, p, k, t, t2, v, d
      x = delta - lo
      x2 = x*x
      force = (c(1) + x*c(2)) + x2*(c(3) + x*c(4))
      stiffness = (c(2) + 2*x*c(3)) + 3*x2*c(4)
      if (seg(7) > 1.0_dp .or. seg(7) < 0.0_dp) then
         if (seg(7) == folded) then
            ! (force is ln P - h: exp(0 + force) and p (-0 + stiffness) below are
            ! exp(force) and p stiffness bit for bit, egw.h's arithmetic)
            v = 0.0_dp
            d = -0.0_dp
         else
            t = delta - seg(1)
            t2 = t*t
            v = (seg(3) + t*seg(4)) + t2*(seg(5) + t*seg(6))
            d = (seg(4) + 2*t*seg(5)) + 3*t2*seg(6)
         end if
         p = piece_exp(merge(v + force, force, seg(7) > 1.0_dp))
         if (seg(7) > 1.0_dp) then
            stiffness = p*(d + stiffness)
            force = p
         else
            stiffness = p*(d + v*stiffness)
            force = v*p
         end if
      else if (seg(7) > 0.0_dp) then
         call segment_eval(seg, delta, p, k)
         force = force + p
         stiffness = stiffness + k
      end if
      if (.not. force > 0.0_dp) then
         force = 0.0_dp
         stiffness = 0.0_dp
      end if
   end subroutine piece_force

   include "piece_exp.inc"

   !> The piece of the unloading curve of turning point m (P_load(m) = f_m, 1/(s_max L) =
   !> iota, its inverse span; stencil first) around delta for a state: the overlaps
   !> ends = (lo, hi) where s (its value at delta, clamped at 1) stays in the run of s
   !> intervals around i on which the stencil's curves are one cubic each and the loading
   !> table in its interval around delta (seg, refilled), with the force there as the
   !> cubic c in delta - lo; where the loading interval is ln P (seg(7) = 1) c is the gap
   !> part only and piece_force adds exp(ln P). The gap cubic is the Hermite cubic of the
   !> run's end nodes (weights w of the stencil), the same cubic as interval i's but
   !> conditioned on the whole run: interval i's own coefficients, re-expanded many of its
   !> widths away, would lose digits (4.6e-11 of f_m measured on a 1e-5 table). No piece
   !> (found false, NaN ends) at the clamp s = 1 or outside the loading table's intervals.
   pure subroutine make_piece(table, w, first, i, s, m, delta, iota, knee, f_m, seg, ends, &
      & c, found)
      type(hysteresis_table), intent(in) :: table   !< built or read (not log-ratio)
      !> the stencil's weights, s at delta, the turning point m, the overlap, 1/(s_max L),
      !> the map's knee and P_load(m)
      real(dp), intent(in) :: w(max_stencil), s, m, delta, iota, knee, f_m
      !> the stencil's first curve and the s interval of delta
      integer, intent(in) :: first, i
      !> the loading interval around delta (refilled where delta left it)
      real(dp), intent(inout) :: seg(7)
      !> the piece's overlaps (lo, hi) and its cubic in delta - lo (NaN, 0 if none)
      real(dp), intent(out) :: ends(2), c(4)
      logical, intent(out) :: found   !< whether a piece was made
      real(dp) :: lo, hi, t0, alpha, d, g(4), g_a, g_b, h_a, h_b, width, x_a, x_b, dsdx, &
         & scale(4)
      integer :: a, b
      logical :: inside
      ends = quiet_nan
      c = 0.0_dp
      found = .false.
      if (.not. s < 1.0_dp) return   ! the clamp: g held
      if (.not. (seg(1) <= delta .and. delta < seg(2))) then
         call table_segment(table%loading, delta, seg, inside)   ! the interval around delta
         if (.not. inside) return
      end if
      ! (curves of u, stores_ratio: the piece is f_m u alone, cut at seg's ends as a gap
      ! piece, so that piece_force and egw.h's inline read it as one; on a ln P loading
      ! interval they would add P_load: no piece there, hysteresis_eval's arithmetic
      ! instead)
      if (stores_ratio(table) .and. seg(7) > 0.0_dp) return
      ! s = (m - delta) iota in [s_i, s_{i+1}): delta in (m - s_{i+1}/iota, m - s_i/iota];
      ! the piece is open below (the cut-off itself has no force)
      a = table%run_first(first, i)
      b = table%run_last(first, i) + 1
      ! (a run lies in one piece of the map: its breaks end runs, make_runs)
      x_a = table%s(a)*(1.0_dp/iota)
      x_b = table%s(b)*(1.0_dp/iota)
      dsdx = iota
      if (table%mapped) then
         call map_x(table, m, knee, iota, table%s(a), x_a, dsdx)
         call map_x(table, m, knee, iota, table%s(b), x_b, dsdx)
      end if
      lo = max(m - x_b, seg(1), unload_floor(table))
      hi = min(m - x_a, seg(2))
      if (.not. (lo < delta .and. delta < hi)) return   ! rounding at an end
      ! the run's cubic in t = (s - s_a)/(s_b - s_a) from its end nodes' gaps and slopes
      width = table%s(b) - table%s(a)
      scale = 1.0_dp
      if (table%mapped) scale = table%piece_scale(map_piece(.true., 0.5_dp*(table%s(a) + &
         & table%s(b))), first:first + 3)
      g_a = dot_product(w(1:4), table%gap(a, first:first + 3))
      g_b = dot_product(w(1:4), table%gap(b, first:first + 3))
      h_a = width*dot_product(w(1:4), scale*table%slope(a, first:first + 3))
      h_b = width*dot_product(w(1:4), scale*table%slope(b, first:first + 3))
      g = [g_a, h_a, 3*(g_b - g_a) - 2*h_a - h_b, 2*(g_a - g_b) + h_a + h_b]
      ! -f_m g(t), t = t0 + alpha x, as a cubic in x = delta - lo (s linear in delta on
      ! the run: s_a + (m - delta - x_a) dsdx)
      if (table%mapped) then
         t0 = (m - lo - x_a)*dsdx/width
      else   ! (the linear map's arithmetic, bit for bit as before the map)
         t0 = ((m - lo)*iota - table%s(a))/width
      end if
      alpha = -dsdx/width
      c(1) = -f_m*(g(1) + t0*(g(2) + t0*(g(3) + t0*g(4))))
      c(2) = -f_m*alpha*(g(2) + t0*(2*g(3) + 3*t0*g(4)))
      c(3) = -f_m*alpha**2*(g(3) + 3*t0*g(4))
      c(4) = -f_m*alpha**3*g(4)
      if (stores_ratio(table)) then
         c = -c   ! f_m u(t), no loading cubic
      else if (.not. seg(7) > 0.0_dp) then
         ! the loading cubic in delta - seg(1), moved to delta - lo
         d = lo - seg(1)
         c(1) = c(1) + (seg(3) + d*(seg(4) + d*(seg(5) + d*seg(6))))
         c(2) = c(2) + (seg(4) + d*(2*seg(5) + 3*d*seg(6)))
         c(3) = c(3) + (seg(5) + 3*d*seg(6))
         c(4) = c(4) + seg(6)
      end if
      ends = [lo, hi]
      found = .true.
   end subroutine make_piece

   !> The force and stiffness at delta (cut-off < delta < m) below the turning point m
   !> (P_load(m) = f_m, 1/(s_max L) = inv_span) from its gap cubic c on s interval i, at
   !> s = min((m - delta) inv_span, 1): P_load(delta) - P_load(m) g(s, m) (tables that
   !> store u, stores_ratio: P_load(m) u(s, m); Hertz + cap's 0 from s = 1 on), 0 where
   !> that is not positive. Below the curve's span (s clamped at 1, where the loading
   !> force is below rel_tol of P_ref) the unloading force keeps its ratio to the loading
   !> force at the span's end (unload_tail_ratio): the loading tail, scaled.
   pure subroutine unload_branch(table, c, i, s, m, f_m, inv_span, knee, dsdx, delta, force, &
      & stiffness)
      type(hysteresis_table), intent(in) :: table   !< built or read (not log-ratio)
      !> ds/ddelta = -dsdx at delta (map_s; inv_span and knee: the turning point's map)
      real(dp), intent(in) :: c(4), s, m, f_m, inv_span, knee, dsdx, delta
      integer, intent(in) :: i   !< the s interval of s
      !> [force] and [force/length] at delta
      real(dp), intent(out) :: force, stiffness
      real(dp) :: g, dg, f_d, k_d, ratio, x_1, dummy
      call gap_cubic(c, (s - table%s(i))*table%inv_ds(i), table%inv_ds(i), g, dg)
      if (stores_ratio(table) .and. (s < 1.0_dp .or. table%capped)) then
         ! the curves' u = P/P_load(m): no loading force (Hertz + cap: 0 from s = 1 on,
         ! apart; u on the two-piece map: the loading tail scaled there, below)
         force = f_m*g
         stiffness = -f_m*dg*dsdx
         if (.not. (force > 0.0_dp .and. s < 1.0_dp)) then
            force = 0.0_dp
            stiffness = 0.0_dp
         end if
         return
      end if
      call table_eval(table%loading, delta, f_d, k_d)
      if (s >= 1.0_dp) then
         x_1 = 1.0_dp/inv_span
         if (table%mapped) call map_x(table, m, knee, inv_span, 1.0_dp, x_1, dummy)
         ratio = unload_tail_ratio(table, m - x_1, f_m, g)
         force = ratio*f_d
         stiffness = ratio*k_d
         return
      end if
      force = f_d - f_m*g
      stiffness = k_d + f_m*dg*dsdx
      if (.not. force > 0.0_dp) then
         force = 0.0_dp
         stiffness = 0.0_dp
      end if
   end subroutine unload_branch

end module egw_hysteresis_piece
