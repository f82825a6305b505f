!> Hysteresis tables for DEM (EP-GW loading, unloading and reloading, doc/theory.md §8):
!> the force of one parameter set over (delta, delta_max), with a per-contact history that
!> the caller owns (the largest overlap so far; -huge for a contact that never touched):
!> the evaluation, with and without a per-contact state, and the preparation of a built or
!> read table. The layout: egw_hysteresis_data; the energy: egw_unload_energy; a state's
!> pieces: egw_hysteresis_piece; beyond delta_max: egw_hysteresis_beyond; the adaptive
!> build: the submodule egw_hysteresis_build (hysteresis_build.f90).
module egw_hysteresis
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_is_finite
   use, intrinsic :: iso_fortran_env, only: int64
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, egw_invalid_argument, egw_out_of_range, fatal_error, &
      & format_real
   use egw_params, only: contact_params, model_hertz
   use egw_rough_sphere, only: solver_options
   use egw_table, only: table_eval, table_eval_cached, table_segment, segment_eval, &
      & table_progress, deep_coefficient, beyond_status
   use egw_table_ends, only: deep_reach
   use egw_cap_sphere, only: cap_units, elastic_margin
   use egw_hysteresis_data, only: hysteresis_table, hysteresis_state_size, nan_error, &
      & gap_cubic, turning_point, gap_combination, unload_tail_ratio, make_lookup, &
      & m_breakpoint, m_coordinate, stencil_first, locate, quiet_nan, turning_knee, map_s, &
      & map_x, map_piece, s_knee, s_zero, map_lengths, log_unload, edge_breaks, &
      & edge_segment, edge_s, edge_xi, max_stencil, stencil_width, stencil_window, stencil_sum, &
      & unload_floor
   use egw_unload_energy, only: hysteresis_energy_walk, log_energy_prepare, energy_prepare
   use egw_hysteresis_piece, only: piece_force, make_piece, unload_branch, folded
   use egw_hysteresis_beyond, only: cap_full_reach, cap_continues, cap_continue, &
      & continue_state, hysteresis_energy
   implicit none
   private

   public :: hysteresis_table, build_hysteresis, hysteresis_eval, hysteresis_eval_state, &
      & hysteresis_state_init, hysteresis_energy, hysteresis_energy_walk, hysteresis_prepare, &
      & m_breakpoint, &
      & stencil_first, m_coordinate, first_yield, hertz_capped, cap_first_turn, &
      & cap_continues, cap_full_reach
   public :: hysteresis_state_size, zero_lo, folded

   !> The start of a zero piece and zero loading interval (zero_piece): a real piece never
   !> starts there, and the cubics' powers of delta - zero_lo stay finite.
   real(dp), parameter :: zero_lo = -0.25_dp*sqrt(huge(1.0_dp))

   interface
      !> Build the hysteresis table of params over overlaps [delta_min, delta_max] to rel_tol
      !> (relative to the force at the turning point). Errors: invalid params or range,
      !> solves that fail (egw_not_converged), node limits reached.
      module subroutine build_hysteresis(params, options, delta_min, delta_max, rel_tol, &
         & table, error, progress)
         type(contact_params), intent(in) :: params   !< one parameter set (EP-GW dissipates)
         !> solver options (the loading table's solves at min(options%rel_tol, rel_tol/10),
         !> the unloading curves' at hysteresis_solve_tol: rel_tol/10, or options%rel_tol
         !> if set below its default 1e-6 and below that)
         type(solver_options), intent(in) :: options
         real(dp), intent(in) :: delta_min      !< smallest overlap of interest (< 0: separation)
         real(dp), intent(in) :: delta_max      !< largest overlap (and delta_max) tabulated
         real(dp), intent(in) :: rel_tol        !< tolerance, in [1e-8, 0.1]
         type(hysteresis_table), intent(out) :: table   !< the table, empty on error
         type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
         !> called with (unloading curves built, built + known pending) from the serial part
         !> of the build (the loading table's own solves are not counted)
         procedure(table_progress), optional :: progress
      end subroutine build_hysteresis
   end interface

contains

   !> Force [force] and stiffness dP/ddelta [force/length] at overlap delta for a contact
   !> whose history is delta_max_state (the largest overlap so far; -huge(1.0) for a new
   !> contact), which is updated to max(state, delta). Loading (delta >= state) follows the
   !> loading table; unloading and reloading below the state the unloading curve of the
   !> state, 0 below the loading table's cut-off (where the loading force is below 1e-12
   !> of the reference force; a state at or below the cut-off unloads on the loading
   !> curve's tail; force_ratio tables, Hertz + cap: down to the residual overlap, which
   !> needs no loading force). A state above the table's delta_max uses the last curve (log-ratio
   !> tables: its span stretched by the state's excess, turning_point) and returns
   !> egw_out_of_range (values written); a Hertz + cap table that reaches cap_full_reach
   !> continues exactly above it instead (cap_continue, status 0), and a rough + cap one
   !> to 35 delta_y or more up to its measured reach (cap_continues). NaN delta or state:
   !> egw_invalid_argument, nothing changed (force, stiffness 0); a state above delta_max
   !> whose force leaves the doubles: egw_invalid_argument, the values as computed
   !> (egw_hysteresis_eval's statuses). The optional error says the same with a message
   !> naming the argument (formed only when stat is not 0).
   pure subroutine hysteresis_eval(table, delta, delta_max_state, force, stiffness, stat, &
      & error)
      type(hysteresis_table), intent(in) :: table   !< built or read
      real(dp), intent(in) :: delta   !< overlap [length] (> 0 in contact, < 0 apart)
      !> the contact's history: its largest overlap so far [length]
      real(dp), intent(inout) :: delta_max_state
      real(dp), intent(out) :: force       !< normal force [force], >= 0 (repulsive)
      real(dp), intent(out) :: stiffness   !< dP/ddelta [force/length]
      integer, intent(out) :: stat         !< 0 or an egw status
      !> allocated when stat is not 0, with a message naming the argument
      type(egw_error), allocatable, intent(out), optional :: error
      real(dp) :: w(max_stencil), inv_span, f_m, c(4), s, knee, dsdx
      integer :: first, i
      stat = 0
      force = 0.0_dp
      stiffness = 0.0_dp
      if (ieee_is_nan(delta) .or. ieee_is_nan(delta_max_state)) then
         stat = egw_invalid_argument
         if (present(error)) call nan_error(delta, "delta_max_state", &
            & "-huge(1.0_dp)", error)
         return
      end if
      ! turning points at or below the cut-off (the lowest m node) unload on the loading
      ! tail: their forces are below 1e-12 of the reference force
      if (.not. delta < delta_max_state .or. table%reversible .or. &
         & .not. delta_max_state > table%elastic_limit) then
         delta_max_state = max(delta_max_state, delta)
         call table_eval(table%loading, delta, force, stiffness)
         if (delta > table%delta_max) call past_top(table, delta, "delta_max_state", &
            & delta_max_state, force, stiffness, stat, error)
         return
      end if
      if (delta_max_state > table%delta_max) then   ! (a capped table's continuation)
         if (cap_continues(table, delta_max_state)) then
            call past_top(table, delta, "delta_max_state", delta_max_state, force, &
               & stiffness, stat, error)
            return
         end if
      end if
      if (.not. delta > unload_floor(table)) return   ! below the cut-off: no force
      call turning_point(table, delta_max_state, first, w, inv_span, f_m, knee)
      if (table%log_ratio) then
         call log_unload(table, first, w, 1.0_dp/inv_span, delta_max_state, delta, force, &
            & stiffness)
      else
         ! (the linear map inline: no call on the path of every table without the map)
         s = (delta_max_state - delta)*inv_span
         dsdx = inv_span
         if (table%mapped) call map_s(table, delta_max_state, knee, inv_span, &
            & delta_max_state - delta, s, dsdx)
         s = min(s, 1.0_dp)
         i = locate(table%s_lookup, table%s, s)
         call gap_combination(table, first, w, i, c)
         call unload_branch(table, c, i, s, delta_max_state, f_m, inv_span, knee, dsdx, &
            & delta, force, stiffness)
      end if
      if (delta_max_state > table%delta_max) call beyond(table, "delta_max_state", &
         & delta_max_state, force, stiffness, stat, error)
   end subroutine hysteresis_eval

   !> An evaluation above the table's delta_max (loading past it, or a history x, called
   !> name, above it): a table that continues there (cap_continues: Hertz + cap from 35
   !> delta_y, rough + cap to its reach) answers by the fully capped continuation
   !> (cap_continue: force and stiffness replaced, history moved
   !> to max(x, delta), stat 0, or egw_invalid_argument where they leave the doubles);
   !> any other keeps the values it was given and takes beyond's status.
   pure subroutine past_top(table, delta, name, x, force, stiffness, stat, error)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: delta
      character(len=*), intent(in) :: name
      real(dp), intent(inout) :: x, force, stiffness
      integer, intent(out) :: stat
      type(egw_error), allocatable, intent(out), optional :: error
      if (cap_continues(table, max(x, delta))) then
         call cap_continue(table, delta, x, force, stiffness)
         stat = 0
         if (ieee_is_finite(force) .and. ieee_is_finite(stiffness)) return
      end if
      call beyond(table, name, x, force, stiffness, stat, error)
   end subroutine past_top


   !> The status of an evaluation whose turning point (or overlap) x, called name, lies
   !> above the table's delta_max, with the force and stiffness it gave: egw_out_of_range,
   !> or egw_invalid_argument where they left the doubles; error (optional) with the
   !> message, formed only here (the hot path allocates nothing).
   pure subroutine beyond(table, name, x, force, stiffness, stat, error)
      type(hysteresis_table), intent(in) :: table
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: x, force, stiffness
      integer, intent(out) :: stat
      type(egw_error), allocatable, intent(out), optional :: error
      stat = egw_out_of_range
      if (.not. (ieee_is_finite(force) .and. ieee_is_finite(stiffness))) &
         & stat = egw_invalid_argument
      if (present(error)) call beyond_status(table%delta_max, name, x, [force, stiffness], &
         & error)
   end subroutine beyond

   !> hysteresis_eval with a state that also keeps what the evaluation needs of the turning
   !> point and of the piece of its unloading curve last used (hysteresis_state_size
   !> doubles; state(1) is delta_max_state, the rest caches that this routine fills): a
   !> contact that stays below the same turning point and inside the same piece evaluates
   !> one cubic (and an exp in the loading table's ln P tail), reading only its state. A
   !> piece is hysteresis_eval's unloading force where its run of s intervals (make_runs)
   !> and loading interval do not change, written out as a cubic in delta (a log-ratio
   !> table's: h = ln(P_load/P) over the whole run on a linear loading interval, the
   !> interval beside it, taken alone when the contact crosses into the next; on a ln P
   !> interval ln P - h, one cubic inside it, make_log_piece): the same values to rounding (test
   !> hysteresis: 1e-12 of the force at the turning point), the same statuses and histories; but
   !> back at the history exactly on a folded piece (the separated tail) the unloading curve's
   !> stiffness, the piece's limit from below (hysteresis_eval: the loading curve's there).
   !> Where the force is 0 below the cut-off (a contact that has not touched, or one below its
   !> turning point's unloading floor) the state keeps a zero piece (zero_piece), so that
   !> separated contacts too read only their state. Only a state that this table filled is
   !> trusted (its tag, state(3)): any other (all zero, as a DEM code's zeroed contact arrays;
   !> hysteresis_state_init's; another table's; garbled) is a new contact, its history reset to
   !> -huge; but a NaN state(1), as a NaN delta, is refused (egw_invalid_argument, nothing
   !> changed, as egw_hysteresis_eval_state). Beyond a capped table that continues
   !> (cap_continues) loading steps are this call's (no piece), and unloading ones below
   !> a history there keep a piece of the last curve moved to the contact
   !> (continue_state): hysteresis_eval's values to rounding. The optional error says
   !> what stat says, with a message naming the argument (formed only when stat is not 0).
   pure subroutine hysteresis_eval_state(table, delta, state, force, stiffness, stat, error)
      type(hysteresis_table), intent(in) :: table   !< built or read
      real(dp), intent(in) :: delta   !< overlap [length] (> 0 in contact, < 0 apart)
      !> the contact's state (hysteresis_state_init): state(1) its largest overlap so far
      real(dp), intent(inout) :: state(hysteresis_state_size)
      real(dp), intent(out) :: force       !< normal force [force], >= 0 (repulsive)
      real(dp), intent(out) :: stiffness   !< dP/ddelta [force/length]
      integer, intent(out) :: stat         !< 0 or an egw status
      !> allocated when stat is not 0, with a message naming the argument
      type(egw_error), allocatable, intent(out), optional :: error
      real(dp) :: w(max_stencil), g(4), s, knee, dsdx, xi_b(3), ds, inv_span, f_m
      integer :: first, i
      logical :: found, inside
      stat = 0
      ! a zero piece (zero_piece: separated, no force): 0, no status, as the call that
      ! made it (hysteresis_eval returns there before its delta_max check). zero_piece
      ! writes it with its zero interval around it (state(18) = state(11), state(12) <=
      ! state(19)), so that interval is not read (a cache line fewer for a DEM's contact
      ! arrays); at its end state(12) (the history, or the unloading floor) the steps
      ! below give the same zeros and leave the state as it is, so the piece serves it.
      if (state(3) == table%tag .and. state(11) == zero_lo .and. state(11) < delta .and. &
         & delta <= state(12) .and. state(2) == state(1)) then
         force = 0.0_dp
         stiffness = 0.0_dp
         return
      end if
      ! inside the cached piece and its loading interval (below the turning point, above
      ! the cut-off; NaN fails the tests): most DEM steps. A log-ratio piece on a linear
      ! loading interval spans its run of s intervals across the loading table's linear
      ! intervals (make_log_piece): one that left its loading interval for the next linear
      ! one takes it (table_segment), its cubic of h kept; into a ln P interval (and a
      ! folded piece, ln P - h, out of its own) it is remade. A folded piece (the
      ! separated tail) serves its end too, where its cubic is as accurate as inside: the
      ! step back at the history exactly (stop 60: the loading route there, libm's exp,
      ! cost a mispredicted branch a return), the force the loading curve's to rounding
      ! (h = 0 at s = 0), the stiffness the unloading curve's, its limit from below (test
      ! hysteresis "served steps: ..."); it lies inside its loading interval (not read).
      if (state(3) == table%tag .and. state(2) == state(1) .and. state(11) < delta .and. &
         & (delta < state(12) .or. (delta == state(12) .and. state(24) == folded))) then
         inside = state(24) == folded .or. (state(18) <= delta .and. delta < state(19))
         if (.not. inside .and. state(24) < 0.0_dp) then
            ! (into a ln P interval the piece is remade below, folded)
            call table_segment(table%loading, delta, state(18:24), inside)
            inside = inside .and. .not. state(24) > 0.0_dp
            if (inside) state(24) = -1.0_dp
         end if
         if (inside) then
            call piece_force(state(11), state(14:17), state(18:24), delta, force, stiffness)
            ! (a continued table's piece beyond it: status 0, continue_state)
            if (state(1) > table%delta_max) then
               if (.not. cap_continues(table, state(1))) call beyond(table, "state(1)", &
                  & state(1), force, stiffness, stat, error)
            end if
            return
         end if
      end if
      force = 0.0_dp
      stiffness = 0.0_dp
      if (ieee_is_nan(delta) .or. ieee_is_nan(state(1))) then
         stat = egw_invalid_argument
         if (present(error)) call nan_error(delta, "state(1)", "hysteresis_state_init", error)
         return
      end if
      if (.not. state(3) == table%tag) then
         ! a state this table did not fill (all zero as calloc'ed, from
         ! hysteresis_state_init, another table's, garbled): a new contact, so that a
         ! history it did not write never becomes a turning point
         call hysteresis_state_init(state)
         state(2) = quiet_nan
         state(18:19) = state(2)
         state(3) = table%tag
      end if
      ! no piece unless one is made below (the loading interval may change); but a
      ! contact back at its history exactly (delta = state(1)) inside the loading interval
      ! keeps its piece: the turning point and the interval stay, and so does the piece
      ! (egw.h's inline loading step keeps it too: the two leave the same state)
      if (.not. (delta == state(1) .and. state(18) <= delta .and. delta < state(19))) &
         & state(11:12) = quiet_nan
      if (.not. delta < state(1) .or. table%reversible .or. &
         & .not. state(1) > table%elastic_limit) then
         state(1) = max(state(1), delta)
         call table_eval_cached(table%loading, delta, state(18:24), force, stiffness)
         if (delta > table%delta_max) call past_top(table, delta, "state(1)", state(1), &
            & force, stiffness, stat, error)
         ! a contact whose history lies where the loading force is 0 (below a rough
         ! table's cut-off: never touched, or separated before it touched): a zero piece
         ! and a zero loading interval up to there, so that its next calls (egw.h's
         ! inline too) read only the state
         if (state(1) < table%loading%zero_below .and. .not. table%force_ratio) &
            & call zero_piece(table%loading%zero_below, delta < state(1), state)
         return
      end if
      if (state(1) > table%delta_max) then   ! (a capped table's continuation)
         if (cap_continues(table, state(1))) then
            ! (a piece of the last curve, moved to the contact: continue_state)
            call continue_state(table, delta, state, force, stiffness)
            if (.not. (ieee_is_finite(force) .and. ieee_is_finite(stiffness))) call beyond( &
               & table, "state(1)", state(1), force, stiffness, stat, error)
            return
         end if
      end if
      if (.not. delta > unload_floor(table)) then   ! below the cut-off: no force
         ! (a zero piece there, so that the next calls below it read only the state;
         ! its turning-point data kept where they are state(1)'s)
         if (.not. table%force_ratio) call zero_piece(unload_floor(table), .true., state, &
            & unload_floor(table))
         return
      end if
      if (.not. (state(2) == state(1) .and. state(4) >= 1.0_dp .and. &
         & state(4) <= size(table%m) - table%n_w + 1)) then
         ! (P_load of the turning point from the loading interval the state holds)
         if (table%log_ratio) then
            ! (six weights in (5:10): the log-ratio pieces need neither 1/L nor P_load(m))
            call turning_point(table, state(1), first, w, inv_span, f_m, knee, &
               & state(18:24))
            state(11 - table%n_w:10) = w(1:table%n_w)
            state(13) = 1.0_dp/inv_span
         else
            call turning_point(table, state(1), first, w, state(5), state(6), knee, &
               & state(18:24))
            state(7:10) = w(1:4)
            state(13) = 1.0_dp/state(5)
         end if
         state(2) = state(1)
         state(4) = real(first, dp)
      end if
      ! hysteresis_eval's unloading branch from the cached turning point, and the piece
      first = int(state(4))
      if (table%log_ratio) then
         ! (fixed-size copies: no memcpy call on the refill path)
         if (table%n_w == 6) then
            w(1:6) = state(5:10)
         else
            w(1:4) = state(7:10)
            w(5:6) = 0.0_dp
         end if
         call edge_breaks(state(13), table%params%sigma, xi_b)
         call edge_s(xi_b, state(1) - delta, s, ds)
         s = min(s, 1.0_dp)
         i = locate(table%s_lookup, table%s, s)
         call make_log_piece(table, w, first, i, s, state(1), delta, xi_b, &
            & state(18:24), state(11:12), state(14:17), found)
         if (found) then
            call piece_force(state(11), state(14:17), state(18:24), delta, force, stiffness)
         else   ! (the clamp s = 1, or rounding at a piece's end: hysteresis_eval's)
            call log_unload(table, first, w, state(13), state(1), delta, force, stiffness)
         end if
         if (state(1) > table%delta_max) call beyond(table, "state(1)", state(1), force, &
            & stiffness, stat, error)
         return
      end if
      s = (state(1) - delta)*state(5)
      dsdx = state(5)
      knee = 0.0_dp
      w = 0.0_dp
      w(1:4) = state(7:10)
      if (table%mapped) then
         ! (the knee from the cached weights: the state has no room for it)
         knee = turning_knee(table, first, w, state(1))
         call map_s(table, state(1), knee, state(5), state(1) - delta, s, dsdx)
      end if
      s = min(s, 1.0_dp)
      i = locate(table%s_lookup, table%s, s)
      call make_piece(table, w, first, i, s, state(1), delta, state(5), knee, &
         & state(6), state(18:24), state(11:12), state(14:17), found)
      if (found) then
         call piece_force(state(11), state(14:17), state(18:24), delta, force, stiffness)
      else   ! (the interval's gap cubic only here: the piece has its own)
         call gap_combination(table, first, w, i, g)
         call unload_branch(table, g, i, s, state(1), state(6), state(5), knee, dsdx, delta, &
            & force, stiffness)
      end if
      if (state(1) > table%delta_max) call beyond(table, "state(1)", state(1), force, &
         & stiffness, stat, error)
   end subroutine hysteresis_eval_state


   !> make_piece of a log-ratio table: the piece around delta where the run of s
   !> intervals around i (one cubic per curve of the stencil first, weights w; inside one
   !> segment of the edge map xi_b of the turning point m, where s is linear in delta)
   !> does not change, as -h, a cubic c in delta - lo, ends = (lo, hi) the run's overlaps
   !> (above the cut-off), seg the loading interval around delta. On a ln P interval (the
   !> separated tail) the piece is cut at seg's ends, as the gap pieces are, and c is
   !> ln P - h, one cubic (seg(7) = folded): its force is one exp of one cubic (issue 33
   !> item 5: the tail's step ~0.6 of the two cubics' instructions), kept only where
   !> |ln P - h| <= 700 over the piece (piece_exp's range test then never taken), else
   !> c = -h on the cut piece (seg(7) = 2). On a linear interval the piece is not cut at
   !> seg's ends: a contact that crosses into the next loading interval keeps it and
   !> refills seg alone (hysteresis_eval_state; egw.h's inline tests both); seg(7) = -1
   !> there (P e^-h). Every other use of seg reads seg(7) > 0 as ln P: the same. No piece
   !> (found false, NaN ends) at the clamp s = 1 or outside the loading table's intervals.
   pure subroutine make_log_piece(table, w, first, i, s, m, delta, xi_b, seg, ends, c, found)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: w(max_stencil), s, m, delta, xi_b(3)
      integer, intent(in) :: first, i
      real(dp), intent(inout) :: seg(7)
      real(dp), intent(out) :: ends(2), c(4)
      logical, intent(out) :: found
      real(dp) :: lo, hi, t0, alpha, g(4), g_a, g_b, h_a, h_b, width, x_a, x_b, ds, s_0, &
         & x_0, v_a(max_stencil), v_b(max_stencil), scale, f(4), d_lo, span
      integer :: a, b, k, j, q
      logical :: inside, fold
      ends = quiet_nan
      c = 0.0_dp
      found = .false.
      if (.not. s < 1.0_dp) return   ! the clamp: h held
      if (.not. (seg(1) <= delta .and. delta < seg(2))) then
         call table_segment(table%loading, delta, seg, inside)   ! the interval around delta
         if (.not. inside) return
      end if
      seg(7) = merge(2.0_dp, -1.0_dp, seg(7) > 0.0_dp)
      a = table%run_first(first, i)
      b = table%run_last(first, i) + 1
      k = edge_segment(table%s(a), table%s(b))
      call edge_xi(xi_b, table%s(a), x_a)
      call edge_xi(xi_b, table%s(b), x_b)
      ! the run's overlaps; on a linear loading interval not cut at seg's ends (h one
      ! cubic in delta across the intervals: hysteresis_eval_state then refills seg
      ! alone), on a ln P interval cut there, so that ln P - h is one cubic (folded below)
      lo = max(m - x_b, table%loading%cutoff)
      hi = m - x_a
      if (.not. (lo < delta .and. delta < hi)) return   ! rounding at an end
      fold = seg(7) > 0.0_dp .and. max(lo, seg(1)) < delta .and. delta < min(hi, seg(2))
      if (fold) then
         lo = max(lo, seg(1))
         hi = min(hi, seg(2))
      end if
      ! the run's cubic in t = (s - s_a)/(s_b - s_a) from its end nodes' values and slopes
      ! (dh/dxi times each curve's dxi/ds on segment k)
      width = table%s(b) - table%s(a)
      ! (one pass over gap_slope, the stencil's curves side by side at nodes a and b; the
      ! six-point sums as stencil_sum's, inline: no call on the refill path)
      h_a = 0.0_dp
      h_b = 0.0_dp
      do j = 1, table%n_w
         q = first + j - 1
         scale = table%xi_scale(k, q)
         v_a(j) = w(j)*table%gap_slope(1, q, a)
         v_b(j) = w(j)*table%gap_slope(1, q, b)
         h_a = h_a + w(j)*table%gap_slope(2, q, a)*scale
         h_b = h_b + w(j)*table%gap_slope(2, q, b)*scale
      end do
      if (table%n_w == 6) then
         g_a = ((v_a(1) + v_a(2)) + (v_a(3) + v_a(4))) + (v_a(5) + v_a(6))
         g_b = ((v_b(1) + v_b(2)) + (v_b(3) + v_b(4))) + (v_b(5) + v_b(6))
      else
         g_a = stencil_sum(4, w, table%gap_slope(1, first:first + 3, a))
         g_b = stencil_sum(4, w, table%gap_slope(1, first:first + 3, b))
      end if
      h_a = width*h_a
      h_b = width*h_b
      g = [g_a, h_a, 3*(g_b - g_a) - 2*h_a - h_b, 2*(g_a - g_b) + h_a + h_b]
      ! s = s_0 + (m - delta - x_0) ds on segment k; t = t0 + alpha x, x = delta - lo
      select case (k)
      case (1)
         s_0 = 0.0_dp
         x_0 = 0.0_dp
         ds = 0.5_dp/xi_b(1)
      case (2)
         s_0 = 0.5_dp
         x_0 = xi_b(1)
         ds = 0.25_dp/(xi_b(2) - xi_b(1))
      case default
         s_0 = 0.75_dp
         x_0 = xi_b(2)
         ds = 0.25_dp/(xi_b(3) - xi_b(2))
      end select
      t0 = (s_0 + (m - lo - x_0)*ds - table%s(a))/width
      alpha = -ds/width
      c(1) = -(g(1) + t0*(g(2) + t0*(g(3) + t0*g(4))))
      c(2) = -alpha*(g(2) + t0*(2*g(3) + 3*t0*g(4)))
      c(3) = -alpha**2*(g(3) + 3*t0*g(4))
      c(4) = -alpha**3*g(4)
      if (fold) then
         ! ln P - h: the loading cubic in delta - seg(1) moved to delta - lo and added
         ! (make_piece's re-expansion, lo - seg(1) within seg), kept where its argument
         ! bound over the piece leaves piece_exp's range test untaken (|x| < 708: a
         ! folded piece's exp never takes libm's); else the cut piece as -h alone
         d_lo = lo - seg(1)
         f(1) = c(1) + (seg(3) + d_lo*(seg(4) + d_lo*(seg(5) + d_lo*seg(6))))
         f(2) = c(2) + (seg(4) + d_lo*(2*seg(5) + 3*d_lo*seg(6)))
         f(3) = c(3) + (seg(5) + 3*d_lo*seg(6))
         f(4) = c(4) + seg(6)
         span = hi - lo
         if (abs(f(1)) + span*(abs(f(2)) + span*(abs(f(3)) + span*abs(f(4)))) <= &
            & 700.0_dp) then
            c = f
            seg(7) = folded
         end if
      end if
      ends = [lo, hi]
      found = .true.
   end subroutine make_log_piece

   !> The caches of a state whose history state(1) lies below zero_below, the loading
   !> table's overlap below which its force and stiffness are 0 (both +0, as table_eval
   !> returns there): a linear loading interval of zero cubic over (lo, zero_below), lo =
   !> -sqrt(huge)/4 so that the cubics' powers of delta - lo stay finite, and after a call
   !> below the history (unloading) also a piece of zero cubic over (lo, state(1)) for the
   !> turning point state(1) (its turning-point data marked stale, state(4) = 0). Below
   !> the cut-off a state at or under elastic_limit is evaluated by the loading table
   !> (hysteresis_eval_state), so both give that call's values: the piece below state(1),
   !> the interval loading further. A call loading further leaves no piece, as
   !> egw_hysteresis_eval_cached's loading step (state(1) = delta, the piece dropped, the
   !> interval kept): the inline step and the call leave the same state. A lower delta
   !> than lo, or one at zero_below or above, takes the call.
   !> A turning point above elastic_limit (unload_floor given: the piece ends there, below
   !> which its unloading force is 0) keeps its turning-point data where they are its own
   !> (state(2) = state(1)); the loading interval is then never read (no loading below
   !> the history, and the piece's interval is linear). The piece always lies in the
   !> interval written with it (state(18) = state(11) = lo; state(12) = state(1) <
   !> zero_below, or floor = state(19)), and only this routine writes lo into state(11):
   !> the zero exits (hysteresis_eval_state's, the C entry's, egw.h's inline) read the
   !> piece alone (test hysteresis 'C egw_hysteresis_build, _eval, _free').
   pure subroutine zero_piece(zero_below, unloading, state, floor)
      real(dp), intent(in) :: zero_below   !< the loading table's zero_below
      logical, intent(in) :: unloading     !< the call's delta below the history state(1)
      real(dp), intent(inout) :: state(hysteresis_state_size)   !< a tagged state
      !> the unloading floor of a turning point above elastic_limit (the piece's end)
      real(dp), intent(in), optional :: floor
      real(dp), parameter :: lo = zero_lo
      if (.not. state(1) > lo) return
      if (unloading) then
         if (.not. state(2) == state(1)) state(4) = 0.0_dp
         state(2) = state(1)
         state(11) = lo
         state(12) = state(1)
         if (present(floor)) state(12) = floor
         state(14:17) = 0.0_dp
      end if
      state(18) = lo
      state(19) = zero_below
      state(20:24) = 0.0_dp
   end subroutine zero_piece

   !> A new contact's state for hysteresis_eval_state: never touched (-huge), no cache.
   pure subroutine hysteresis_state_init(state)
      real(dp), intent(out) :: state(hysteresis_state_size)   !< the contact's new state
      state = 0.0_dp
      state(1) = -huge(1.0_dp)
   end subroutine hysteresis_state_init


   !> Derive the evaluation data (cubics on the union s grid, Lagrange denominators,
   !> lookup buckets, the curves' integrals, the data tag; reversible tables: the tag
   !> only) from the stored nodes; called by the build and by readers.
   subroutine hysteresis_prepare(table)
      !> the table: its stored nodes in, its evaluation data added
      type(hysteresis_table), intent(inout) :: table
      integer :: n_s, n_m, i, j, first, k, l, lo, hi
      real(dp) :: h, xi_b(3)
      real(dp), allocatable :: dxi_ds(:, :)
      table%tag = data_tag(table)
      table%capped = hertz_capped(table%params)
      table%delta_yield = 0.0_dp
      if (table%params%flow_pressure > 0.0_dp) table%delta_yield = first_yield(table%params)
      table%elastic_limit = table%loading%cutoff
      if (table%capped) table%elastic_limit = max(table%elastic_limit, table%delta_yield)
      ! (from stop 52 a Hertz + cap table's first curve is at cap_first_turn, above delta_y:
      ! turning points up to it are Hertz's, as the cap solver's; earlier tables: delta_y)
      if (table%capped .and. allocated(table%m)) then
         if (size(table%m) > 0) table%elastic_limit = max(table%elastic_limit, table%m(1))
      end if
      ! a rough model with the cap: its curves start at the first turning point (the
      ! cut-off, or with elastic summits the rough first yield, below which it is elastic)
      if (table%params%flow_pressure > 0.0_dp .and. .not. table%capped .and. &
         & .not. table%reversible) then
         if (size(table%m) > 0) table%elastic_limit = max(table%elastic_limit, table%m(1))
      end if
      associate (l => table%loading)
         table%input_limit = deep_reach(l%delta_max, l%force(size(l%force)), &
            & l%stiffness(size(l%stiffness)), deep_coefficient(l%params), &
            & 0.25_dp*huge(1.0_dp))
      end associate
      if (table%reversible) table%log_ratio = .false.
      if (table%reversible) return   ! no curves: the loading table serves
      n_s = size(table%s)
      n_m = size(table%m)
      if (allocated(table%coef)) deallocate (table%coef)
      if (allocated(table%inv_ds)) deallocate (table%inv_ds)
      if (allocated(table%lagrange)) deallocate (table%lagrange)
      if (allocated(table%m_coord)) deallocate (table%m_coord)
      if (allocated(table%gap_integral)) deallocate (table%gap_integral)
      if (allocated(table%run_first)) deallocate (table%run_first)
      if (allocated(table%run_last)) deallocate (table%run_last)
      table%inv_span = 1.0_dp/(table%s_max*table%length)
      if (allocated(table%piece_scale)) deallocate (table%piece_scale)
      allocate (table%piece_scale(3, n_m))
      table%piece_scale = 1.0_dp
      if (table%mapped) then
         ! (dx/ds of piece p)/tail_length: the stored slopes are dg/dx times tail_length
         ! (map_s; a piece of no width: 0)
         do j = 1, n_m
            table%piece_scale(:, j) = map_lengths(table, table%m(j), table%knee(j))/ &
               & table%tail_length
         end do
      end if
      table%n_w = stencil_width(table%log_ratio, n_m)
      allocate (table%coef(4, n_m, n_s - 1), table%inv_ds(n_s - 1), &
         & table%lagrange(max_stencil, n_m - 1))
      ! dxi/ds of each curve's edge-map segments (log-ratio: slopes are dh/dxi); 1 else
      allocate (dxi_ds(3, n_m))
      dxi_ds = 1.0_dp
      if (table%log_ratio) then
         do j = 1, n_m
            call edge_breaks(table%length(j), table%params%sigma, xi_b)
            dxi_ds(:, j) = [2*xi_b(1), 4*(xi_b(2) - xi_b(1)), 4*(xi_b(3) - xi_b(2))]
         end do
      end if
      table%xi_scale = dxi_ds
      if (allocated(table%gap_slope)) deallocate (table%gap_slope)
      if (table%log_ratio) then
         allocate (table%gap_slope(2, n_m, n_s))
         do i = 1, n_s
            table%gap_slope(1, :, i) = table%gap(i, :)
            table%gap_slope(2, :, i) = table%slope(i, :)
         end do
      end if
      do i = 1, n_s - 1
         h = table%s(i + 1) - table%s(i)
         table%inv_ds(i) = 1.0_dp/h
         ! the interval's piece of the map: two-piece (mapped) or edge map (log-ratio)
         k = map_piece(table%mapped, 0.5_dp*(table%s(i) + table%s(i + 1)))
         if (table%log_ratio) k = edge_segment(table%s(i), table%s(i + 1))
         do j = 1, n_m
            associate (r0 => table%gap(i, j), r1 => table%gap(i + 1, j), &
               & d0 => h*dxi_ds(k, j)*table%slope(i, j)*table%piece_scale(k, j), &
               & d1 => h*dxi_ds(k, j)*table%slope(i + 1, j)*table%piece_scale(k, j))
               table%coef(:, j, i) = [r0, d0, 3*(r1 - r0) - 2*d0 - d1, 2*(r0 - r1) + d0 + d1]
            end associate
         end do
      end do
      ! the curves' integrals from s = 0 to every node (exact for the Hermite cubics)
      allocate (table%gap_integral(n_m, n_s))
      table%gap_integral(:, 1) = 0.0_dp
      do i = 1, n_s - 1
         table%gap_integral(:, i + 1) = table%gap_integral(:, i) + (table%s(i + 1) - &
            & table%s(i))*(table%coef(1, :, i) + table%coef(2, :, i)/2 + &
            & table%coef(3, :, i)/3 + table%coef(4, :, i)/4)
      end do
      table%m_break = m_breakpoint(table%m)
      table%m_coord = m_coordinate(table%m, table%m_break)
      table%lagrange = 0.0_dp
      do j = 1, n_m - 1
         call stencil_window(j, n_m, table%m_break, table%n_w, first, lo, hi)
         do k = lo, hi
            h = 1.0_dp
            do l = lo, hi
               if (l /= k) h = h*(m_coordinate(table%m(first + k - 1), table%m_break) - &
                  & m_coordinate(table%m(first + l - 1), table%m_break))
            end do
            table%lagrange(k, j) = 1.0_dp/h
         end do
      end do
      call make_lookup(table%m, table%m_lookup)
      call make_lookup(table%s, table%s_lookup)
      if (table%force_ratio) call fine_prepare(table)
      call make_runs(table)
      ! (log-ratio tables: P_load e^-h is never below 0, no dips to sample)
      if (.not. table%log_ratio) call energy_prepare(table)
      if (table%log_ratio) call log_energy_prepare(table)
   end subroutine hysteresis_prepare

   !> 1/L on the fine delta_max grid of a force_ratio table, the Lagrange denominators of
   !> each four-node stencil (first .. first + 3) and the grid's buckets, for turning_point.
   pure subroutine fine_prepare(table)
      type(hysteresis_table), intent(inout) :: table
      integer :: n_f, j, k, l
      real(dp) :: h
      n_f = size(table%fine_m)
      if (allocated(table%fine_lagrange)) deallocate (table%fine_lagrange)
      table%fine_inv = 1.0_dp/table%fine_length
      allocate (table%fine_lagrange(4, n_f - 3))
      do j = 1, n_f - 3
         do k = 1, 4
            h = 1.0_dp
            do l = 1, 4
               if (l /= k) h = h*(table%fine_m(j + k - 1) - table%fine_m(j + l - 1))
            end do
            table%fine_lagrange(k, j) = 1.0_dp/h
         end do
      end do
      call make_lookup(table%fine_m, table%fine_lookup)
   end subroutine fine_prepare

   !> Whether params are a smooth sphere (Hertz or sigma = 0) with the flow-pressure cap:
   !> a table of the cap solver's curves (capped). A rough model with the cap is built and
   !> evaluated as EP-GW's (its solves cap the total pressure; doc/theory.md section 12).
   elemental logical function hertz_capped(params)
      type(contact_params), intent(in) :: params   !< the table's parameters
      hertz_capped = params%flow_pressure > 0.0_dp .and. (params%model == model_hertz .or. &
         & params%sigma == 0.0_dp)
   end function hertz_capped

   !> First yield of the flow-pressure cap, delta_y = (pi p_y/(2 E*))**2 R (doc/theory.md
   !> §12; egw_cap_sphere's cap_units): the first turning point that leaves a hysteresis.
   pure real(dp) function first_yield(params) result(delta_y)
      type(contact_params), intent(in) :: params   !< with flow_pressure > 0
      real(dp) :: a_y, force_y
      call cap_units(params%radius, params%modulus, params%flow_pressure, delta_y, a_y, &
         & force_y)
   end function first_yield

   !> The first turning point of a Hertz + cap table's unloading curves (its delta_max node
   !> m(1) since stop 52): the least double m that egw_cap_sphere's solves take as capped,
   !> m/delta_y > 1 + elastic_margin. Up to it they are Hertz's (the cap's zone ~0.03 a wide,
   !> residual overlap ~1e-6 delta_y), and just above it the curves jump from Hertz's by
   !> ~3e-4 of the local force at 1e-3 P(m): a stencil across that jump met its check curve
   !> only to 3-4e-4 at every width (doc/stability.md "Stop 52 (doubt18)"). The table serves
   !> turning points up to m(1) by the loading curve (reversible), as the solves do.
   pure real(dp) function cap_first_turn(params) result(m)
      type(contact_params), intent(in) :: params   !< with flow_pressure > 0
      real(dp) :: delta_y, a_y, force_y
      integer :: k
      call cap_units(params%radius, params%modulus, params%flow_pressure, delta_y, a_y, &
         & force_y)
      m = delta_y*(1.0_dp + elastic_margin)
      ! (the solves divide by delta_y: step up until that quotient passes the margin)
      do k = 1, 64
         if (m/delta_y > 1.0_dp + elastic_margin) exit
         m = nearest(m, 1.0_dp)
      end do
   end function cap_first_turn

   !> run_first/run_last: for each stencil, the runs of s intervals joined by union nodes
   !> that are none of its four curves' own nodes. Such a node is where a curve's cubics
   !> on both sides are one polynomial (the union grid resamples them exactly): their
   !> second and third derivatives agree there to rounding (1e-12 of g, at most ~1).
   pure subroutine make_runs(table)
      type(hysteresis_table), intent(inout) :: table
      real(dp), parameter :: same = 1.0e-12_dp
      logical :: joined(size(table%m), size(table%s))
      integer :: n_s, n_m, i, j, first, k
      real(dp) :: r
      n_s = size(table%s)
      n_m = size(table%m)
      joined = .false.
      do i = 2, n_s - 1
         r = (table%s(i + 1) - table%s(i))/(table%s(i) - table%s(i - 1))
         do j = 1, n_m
            associate (a => table%coef(:, j, i - 1), b => table%coef(:, j, i))
               ! second and third derivatives times the right width's powers, in units of g
               joined(j, i) = abs((2*a(3) + 6*a(4))*r**2 - 2*b(3)) <= same .and. &
                  & abs(6*a(4)*r**3 - 6*b(4)) <= same
            end associate
         end do
         ! the two-piece map's breaks end every run (s is linear in delta on a run)
         if (table%mapped .and. (table%s(i) == s_knee .or. table%s(i) == s_zero)) &
            & joined(:, i) = .false.
      end do
      allocate (table%run_first(max(n_m - table%n_w + 1, 1), n_s - 1), &
         & table%run_last(max(n_m - table%n_w + 1, 1), n_s - 1))
      do first = 1, max(n_m - table%n_w + 1, 1)
         k = 1
         do i = 1, n_s - 1
            ! a union node that is one of the stencil's curves' own starts a new run
            if (i > 1) then
               if (.not. all(joined(first:min(first + table%n_w - 1, n_m), i))) k = i
            end if
            table%run_first(first, i) = k
         end do
         k = n_s - 1
         do i = n_s - 1, 1, -1
            if (i < n_s - 1) then
               if (.not. all(joined(first:min(first + table%n_w - 1, n_m), i + 1))) k = i
            end if
            table%run_last(first, i) = k
         end do
      end do
   end subroutine make_runs

   !> FNV-1a (64-bit, word by word) of the stored data and the loading table's nodes,
   !> folded into an integer in [1, 2**52) held exactly by a double.
   pure real(dp) function data_tag(table) result(tag)
      type(hysteresis_table), intent(in) :: table
      integer(int64), parameter :: mask = 2_int64**52 - 1
      integer(int64) :: h
      h = -3750763034362895579_int64   ! the FNV offset basis 14695981039346656037
      call mix(h, [table%s_max, table%rel_tol, table%delta_max])
      if (.not. table%reversible) then
         call mix(h, table%m)
         call mix(h, table%length)
         call mix(h, table%s)
         call mix(h, reshape(table%gap, [size(table%gap)]))
         call mix(h, reshape(table%slope, [size(table%slope)]))
         if (table%mapped) then
            call mix(h, table%knee)
            call mix(h, [table%tail_length])
            ! (the same numbers read as u or as the gap are different tables)
            if (table%ratio_on_map) call mix(h, [1.0_dp])
         end if
         if (table%force_ratio) then
            call mix(h, table%fine_m)
            call mix(h, table%fine_length)
         end if
      end if
      call mix(h, table%loading%delta)
      call mix(h, table%loading%force)
      call mix(h, table%loading%stiffness)
      tag = real(1_int64 + mod(iand(h, mask), mask), dp)
   contains
      pure subroutine mix(h, x)
         integer(int64), intent(inout) :: h
         real(dp), intent(in) :: x(:)
         integer(int64), parameter :: prime = 1099511628211_int64
         integer :: i
         do i = 1, size(x)
            h = ieor(h, transfer(x(i), h))*prime   ! wraps modulo 2**64 (two's complement)
         end do
      end subroutine mix
   end function data_tag

end module egw_hysteresis
