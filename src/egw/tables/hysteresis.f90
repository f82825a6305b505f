!> Hysteresis tables for DEM (EP-GW loading, unloading and reloading, doc/theory.md §8):
!> the force of one parameter set over (delta, delta_max), with a per-contact history that
!> the caller owns (the largest overlap so far; -huge for a contact that never touched).
!>
!> Layout: the loading curve is a 1-D force table (egw_table). Below a turning point
!> m = delta_max the force is P = P_load(delta) - P_load(m) g(s, m): g is the hysteresis
!> gap relative to the force at the turning point, at s = (m - delta)/(s_max L(m)) with
!> L(m) = 1.5 P_load(m)/K_unload(m). For Hertzian unloading L is m minus the residual
!> overlap, and in the separated tail 1.5 times the force's decay length, so g depends
!> little on m at fixed s (the edge where the unloading force vanishes stays put); and
!> the gap, not the unloading force, is stored, so that tables of weakly plastic contacts
!> (g nearly 0) need few nodes. g(0, m) = 0: the force is continuous where unloading
!> starts and the loading table is used as it is. Below each curve's span the unloading
!> force keeps its ratio to the loading tail (unload_branch), and below the loading
!> table's cut-off delta_c it is 0 (the gap is taken to the loading tail below it).
!> Each node m_j carries g(., m_j) as a cubic Hermite curve in s (slopes from the solver's
!> stiffnesses, solves at rel_tol/10, s bisected until value and slope at every midpoint
!> meet the solves to rel_tol/4); between nodes g and 1/L are cubic Lagrange combinations
!> of four neighbouring curves, and the m grid is bisected until that combination meets
!> the midpoint's curve at all its nodes to rel_tol (the table's whole error there).
!> Every curve's cubics are then resampled onto the union of the s nodes (exactly: the
!> union refines every curve's own nodes), so that an evaluation needs one lookup in s and
!> one in m, served by uniform buckets: no search, no allocation, only the caller's
!> history changes. Elastic summits (not EP-GW, psi = 0) store no curves: unloading
!> retraces the loading table exactly.
module egw_hysteresis
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_is_finite, ieee_value, &
      & ieee_quiet_nan
   use, intrinsic :: iso_fortran_env, only: int64
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_invalid_argument, egw_out_of_range, fatal_error, &
      & format_real
   use egw_params, only: contact_params, model_hertz
   use egw_rough_sphere, only: solver_options
   use egw_table, only: force_table, table_eval, table_eval_cached, table_segment, gl_x, gl_w, &
      & segment_eval, table_energy, table_progress, table_interval, deep_coefficient, &
      & beyond_status
   use egw_table_ends, only: deep_reach
   use egw_cap_sphere, only: cap_units
   implicit none
   private

   public :: hysteresis_table, build_hysteresis, hysteresis_eval, hysteresis_eval_state, &
      & hysteresis_state_init, hysteresis_energy, hysteresis_energy_walk, hysteresis_prepare, &
      & m_breakpoint, &
      & stencil_first, m_coordinate, first_yield, hertz_capped

   !> Doubles of a contact's state for hysteresis_eval_state: (1) the largest overlap so far,
   !> then caches that name the table (3, its tag): of the turning point (2, the m they
   !> belong to): (4) the Lagrange stencil, (5) 1/(s_max L), (6) P_load, (7:10) the weights;
   !> (13) s_max L; of the piece of its unloading curve last used (make_piece): (11:12) its
   !> open ends, (14:17) its cubic in delta; of the loading table's interval last used
   !> (the piece's, while there is one): (18:19) its ends, (20:23) its cubic, (24) 1 where
   !> that is ln P (then the piece's cubic is the gap part). A contact that stays inside
   !> its piece (most DEM steps) touches nothing but its state.
   integer, parameter, public :: hysteresis_state_size = 24

   !> Finest bucket level (2**14 buckets): the grids are dyadic, so buckets at the finest
   !> level hold at most one node and the forward scan takes at most one step.
   integer, parameter :: max_bucket_level = 14

   !> Uniform buckets over [origin, origin + 1/scale]: bucket b holds the interval that
   !> contains the bucket's start.
   type, public :: grid_lookup
      real(dp) :: origin = 0.0_dp, scale = 0.0_dp
      integer :: n_bucket = 0
      integer, allocatable :: bucket(:)     !< (0:n_bucket)
   end type grid_lookup

   !> A hysteresis table of one parameter set (build_hysteresis).
   type :: hysteresis_table
      type(contact_params) :: params           !< parameters the table was built for
      real(dp) :: rel_tol = 0.0_dp             !< requested tolerance
      real(dp) :: delta_max = 0.0_dp           !< last delta_max node (table range)
      real(dp) :: max_error = 0.0_dp           !< largest mismatch found at check solves
      type(force_table) :: loading             !< the loading curve
      !> no plastic summits (not EP-GW, psi = 0 or sigma = 0): no unloading curves, the
      !> loading table serves loading and unloading alike (no spurious hysteresis)
      logical :: reversible = .false.
      real(dp), allocatable :: m(:)            !< delta_max nodes, increasing (n_m >= 4)
      !> L(m_j) = 1.5 P_load(m_j)/K_unload(m_j): the unloading length of a Hertzian
      !> contact (m - residual overlap), the scale of s
      real(dp), allocatable :: length(:)
      real(dp), allocatable :: inv_span(:)     !< 1/(s_max L(m_j)) (hysteresis_prepare)
      real(dp) :: s_max = 0.0_dp               !< s = (m - delta)/(s_max L(m)) lies in [0, 1]
      real(dp), allocatable :: s(:)            !< s nodes of every curve, 0 .. 1 (n_s)
      !> g(s, m_j) at the s nodes and dg/ds there: (n_s, n_m) (the stored table)
      real(dp), allocatable :: gap(:, :), slope(:, :)
      ! evaluation data (hysteresis_prepare)
      !> (4, n_m, n_s - 1): the cubic in t = (s - s_i)/(s_{i+1} - s_i) of curve j on
      !> interval i (the four curves of a Lagrange stencil share two cache lines)
      real(dp), allocatable :: coef(:, :, :)
      real(dp), allocatable :: inv_ds(:)       !< 1/(s_{i+1} - s_i)
      !> (n_m - 3, n_s - 1): the first and last s interval of the run around interval i
      !> on which the four curves of stencil first are each one cubic (the union nodes
      !> inside it are none of theirs): a state's piece spans the run
      integer, allocatable :: run_first(:, :), run_last(:, :)
      !> (n_m, n_s): int_0^{s_i} g(s, m_j) ds of each curve's cubics (hysteresis_energy)
      real(dp), allocatable :: gap_integral(:, :)
      !> the part of the unloading integral that the clip at 0 removes, int min(F, 0) dx
      !> over the whole span of the turning point m (F the span force before the clip),
      !> times 1/(s_max L(m) P_load(m)), at m = m_j + dip_u (m_{j+1} - m_j) in delta_max
      !> interval j: dip(k) for k = dip_first(j) .. dip_first(j + 1) - 1, dip_u increasing
      !> from 0 to 1 (energy_prepare; linear between samples)
      real(dp), allocatable :: dip(:), dip_u(:)
      integer, allocatable :: dip_first(:)   !< (n_m): interval j's first sample in dip
      !> (dip_samples, n_m - 1): the sample at the start of each of interval j's
      !> dip_samples equal parts (dip_u = (b - 1)/dip_samples): the search starts there
      integer, allocatable :: dip_base(:, :)
      !> (n_m - 1): per delta_max interval, an s below which no sample's span force is
      !> clipped (with a margin): an overlap at a smaller s needs no walk (energy_prepare)
      real(dp), allocatable :: dip_band(:)
      !> per sample (as dip): the fraction of the span [lo, m] from its start lo over which
      !> the sample's span force was clipped all along: an overlap in that of both samples
      !> around m (less a twentieth) returns only the energy below lo (energy_prepare)
      real(dp), allocatable :: dip_low(:)
      !> (4, n_m - 1): 1/prod(m_k - m_l) of the Lagrange weights of interval j's stencil
      real(dp), allocatable :: lagrange(:, :)
      type(grid_lookup) :: m_lookup, s_lookup
      !> an integer in [1, 2**52) hashed from the stored data: a state's cached turning
      !> point is used only by a table with the same data (hysteresis_eval_state)
      real(dp) :: tag = 0.0_dp
      !> index of the delta_max node at 0 where stencils stop (m_breakpoint; 0: none)
      integer :: m_break = 0
      !> turning points at or below it unload on the loading curve (hysteresis_prepare):
      !> the loading cut-off, or for the flow-pressure cap (capped) its first yield delta_y,
      !> below which the contact is Hertz's and reversible; a rough model with the cap:
      !> the first turning point m(1) (its rough first yield with elastic summits)
      real(dp) :: elastic_limit = 0.0_dp
      !> Hertz + flow-pressure cap (hertz_capped: flow_pressure > 0, smooth; doc/theory.md
      !> §12): L(m_j) is m_j minus the residual overlap, s_max = 1, and below s = 1 there
      !> is no force (a rough model with the cap is not capped here: EP-GW's layout)
      logical :: capped = .false.
      !> the largest overlap (or state) whose force stays well inside the doubles: where
      !> the loading table's deep-overlap law beyond delta_max reaches huge/4 (the C
      !> layer's input check; hysteresis_prepare, once: four powers, off the hot path)
      real(dp) :: input_limit = 0.0_dp
   end type hysteresis_table

   !> Turning points sampled per delta_max interval for the energy's clipped dips
   !> (energy_prepare): dip_samples + 1 evenly spaced, each gap bisected (to a width of
   !> 1/dip_samples_max of the interval) until linear interpolation meets the walk at its
   !> midpoint to dip_tol of the span's (unclipped) integral.
   integer, parameter :: dip_samples = 16, dip_samples_max = 1024
   real(dp), parameter :: dip_tol = 1.0e-9_dp

   !> One turning point's unloading curve (turning_point): what its span force needs.
   type :: unload_curve
      real(dp) :: m = 0.0_dp               !< the turning point
      real(dp) :: w(4) = 0.0_dp            !< Lagrange weights of its stencil
      real(dp) :: inv_span = 0.0_dp        !< 1/(s_max L(m))
      real(dp) :: f_m = 0.0_dp             !< P_load(m)
      integer :: first = 1                 !< the stencil's first curve
   end type unload_curve

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
   !> curve's tail). A state above the table's delta_max uses the last curve and returns
   !> egw_out_of_range (values written). NaN delta or state: egw_invalid_argument, nothing
   !> changed (force, stiffness 0); a state above delta_max whose force leaves the doubles:
   !> egw_invalid_argument, the values as computed (egw_hysteresis_eval's statuses). The
   !> optional error says the same with a message naming the argument (formed only when
   !> stat is not 0).
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
      real(dp) :: w(4), inv_span, f_m, c(4), s
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
         if (delta > table%delta_max) call beyond(table, "delta_max_state", &
            & delta_max_state, force, stiffness, stat, error)
         return
      end if
      if (.not. delta > table%loading%cutoff) return   ! below the cut-off: no force
      call turning_point(table, delta_max_state, first, w, inv_span, f_m)
      s = min((delta_max_state - delta)*inv_span, 1.0_dp)
      i = locate(table%s_lookup, table%s, s)
      call gap_combination(table, first, w, i, c)
      call unload_branch(table, c, i, s, delta_max_state, f_m, inv_span, delta, force, &
         & stiffness)
      if (delta_max_state > table%delta_max) call beyond(table, "delta_max_state", &
         & delta_max_state, force, stiffness, stat, error)
   end subroutine hysteresis_eval

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

   !> egw_invalid_argument for a NaN overlap delta or a NaN history (called name; a new
   !> contact starts from fresh, the way to start one).
   pure subroutine nan_error(delta, name, fresh, error)
      real(dp), intent(in) :: delta
      character(len=*), intent(in) :: name, fresh
      type(egw_error), allocatable, intent(out) :: error
      if (ieee_is_nan(delta)) then
         call fatal_error(error, egw_invalid_argument, "delta = NaN: must be a number")
      else
         call fatal_error(error, egw_invalid_argument, name//" = NaN: a new contact starts "// &
            & "from "//fresh)
      end if
   end subroutine nan_error

   !> hysteresis_eval with a state that also keeps what the evaluation needs of the turning
   !> point and of the piece of its unloading curve last used (hysteresis_state_size
   !> doubles; state(1) is delta_max_state, the rest caches that this routine fills): a
   !> contact that stays below the same turning point and inside the same piece evaluates
   !> one cubic (and an exp in the loading table's ln P tail), reading only its state. A
   !> piece is hysteresis_eval's unloading force where its run of s intervals (make_runs)
   !> and loading interval do not change, written out as a cubic in delta: the same values
   !> to rounding (test
   !> hysteresis: 1e-12 of the force at the turning point), the same statuses and
   !> histories. Only a state that this table filled is trusted (its tag, state(3)): any
   !> other (all zero, as a DEM code's zeroed contact arrays; hysteresis_state_init's;
   !> another table's; garbled) is a new contact, its history reset to -huge; but a NaN
   !> state(1), as a NaN delta, is refused (egw_invalid_argument, nothing changed, as
   !> egw_hysteresis_eval_state). The optional error says what stat says, with a message
   !> naming the argument (formed only when stat is not 0).
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
      real(dp) :: w(4), g(4), s
      integer :: first, i
      logical :: found
      stat = 0
      ! inside the cached piece (below the turning point, above the cut-off; NaN fails
      ! the tests): most DEM steps
      if (state(3) == table%tag .and. state(2) == state(1) .and. state(11) < delta .and. &
         & delta < state(12)) then
         call piece_force(state(11), state(14:17), state(18:24), delta, force, stiffness)
         if (state(1) > table%delta_max) call beyond(table, "state(1)", state(1), force, &
            & stiffness, stat, error)
         return
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
         state(2) = ieee_value(1.0_dp, ieee_quiet_nan)
         state(18:19) = state(2)
         state(3) = table%tag
      end if
      ! no piece unless one is made below (the loading interval may change)
      state(11:12) = ieee_value(1.0_dp, ieee_quiet_nan)
      if (.not. delta < state(1) .or. table%reversible .or. &
         & .not. state(1) > table%elastic_limit) then
         state(1) = max(state(1), delta)
         call table_eval_cached(table%loading, delta, state(18:24), force, stiffness)
         if (delta > table%delta_max) call beyond(table, "state(1)", state(1), force, &
            & stiffness, stat, error)
         return
      end if
      if (.not. delta > table%loading%cutoff) return   ! below the cut-off: no force
      if (.not. (state(2) == state(1) .and. state(4) >= 1.0_dp .and. &
         & state(4) <= size(table%m) - 3)) then
         call turning_point(table, state(1), first, w, state(5), state(6))
         state(2) = state(1)
         state(4) = real(first, dp)
         state(7:10) = w
         state(13) = 1.0_dp/state(5)
      end if
      ! hysteresis_eval's unloading branch from the cached turning point, and the piece
      first = int(state(4))
      s = min((state(1) - delta)*state(5), 1.0_dp)
      i = locate(table%s_lookup, table%s, s)
      call make_piece(table, state(7:10), first, i, s, state(1), delta, state(5), state(6), &
         & state(13), state(18:24), state(11:12), state(14:17), found)
      if (found) then
         call piece_force(state(11), state(14:17), state(18:24), delta, force, stiffness)
      else   ! (the interval's gap cubic only here: the piece has its own)
         call gap_combination(table, first, state(7:10), i, g)
         call unload_branch(table, g, i, s, state(1), state(6), state(5), delta, force, &
            & stiffness)
      end if
      if (state(1) > table%delta_max) call beyond(table, "state(1)", state(1), force, &
         & stiffness, stat, error)
   end subroutine hysteresis_eval_state

   !> The force and stiffness at delta inside a piece (make_piece: start lo, cubic c),
   !> with the loading interval seg it was made with: the cubic, plus exp of seg's cubic
   !> where that is ln P; 0 where the force is not positive.
   pure subroutine piece_force(lo, c, seg, delta, force, stiffness)
      real(dp), intent(in) :: lo, c(4), seg(7), delta
      real(dp), intent(out) :: force, stiffness
      real(dp) :: x, x2, p, k
      x = delta - lo
      x2 = x*x
      force = (c(1) + x*c(2)) + x2*(c(3) + x*c(4))
      stiffness = (c(2) + 2*x*c(3)) + 3*x2*c(4)
      if (seg(7) > 0.0_dp) then
         call segment_eval(seg, delta, p, k)
         force = force + p
         stiffness = stiffness + k
      end if
      if (.not. force > 0.0_dp) then
         force = 0.0_dp
         stiffness = 0.0_dp
      end if
   end subroutine piece_force

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
   pure subroutine make_piece(table, w, first, i, s, m, delta, iota, f_m, span, seg, ends, &
      & c, found)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: w(4), s, m, delta, iota, f_m, span
      integer, intent(in) :: first, i
      real(dp), intent(inout) :: seg(7)
      real(dp), intent(out) :: ends(2), c(4)
      logical, intent(out) :: found
      real(dp) :: lo, hi, t0, alpha, d, g(4), g_a, g_b, h_a, h_b, width
      integer :: a, b
      logical :: inside
      ends = ieee_value(1.0_dp, ieee_quiet_nan)
      c = 0.0_dp
      found = .false.
      if (.not. s < 1.0_dp) return   ! the clamp: g held
      if (.not. (seg(1) <= delta .and. delta < seg(2))) then
         call table_segment(table%loading, delta, seg, inside)   ! the interval around delta
         if (.not. inside) return
      end if
      ! s = (m - delta) iota in [s_i, s_{i+1}): delta in (m - s_{i+1}/iota, m - s_i/iota];
      ! the piece is open below (the cut-off itself has no force)
      a = table%run_first(first, i)
      b = table%run_last(first, i) + 1
      lo = max(m - table%s(b)*span, seg(1), table%loading%cutoff)
      hi = min(m - table%s(a)*span, seg(2))
      if (.not. (lo < delta .and. delta < hi)) return   ! rounding at an end
      ! the run's cubic in t = (s - s_a)/(s_b - s_a) from its end nodes' gaps and slopes
      width = table%s(b) - table%s(a)
      g_a = dot_product(w, table%gap(a, first:first + 3))
      g_b = dot_product(w, table%gap(b, first:first + 3))
      h_a = width*dot_product(w, table%slope(a, first:first + 3))
      h_b = width*dot_product(w, table%slope(b, first:first + 3))
      g = [g_a, h_a, 3*(g_b - g_a) - 2*h_a - h_b, 2*(g_a - g_b) + h_a + h_b]
      ! -f_m g(t), t = t0 + alpha x, as a cubic in x = delta - lo
      t0 = ((m - lo)*iota - table%s(a))/width
      alpha = -iota/width
      c(1) = -f_m*(g(1) + t0*(g(2) + t0*(g(3) + t0*g(4))))
      c(2) = -f_m*alpha*(g(2) + t0*(2*g(3) + 3*t0*g(4)))
      c(3) = -f_m*alpha**2*(g(3) + 3*t0*g(4))
      c(4) = -f_m*alpha**3*g(4)
      if (.not. seg(7) > 0.0_dp) then
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

   !> Elastic energy [force*length] that a contact at overlap delta returns if it
   !> separates now: the integral of its unloading curve from the loading cut-off to delta,
   !> int_{delta_c}^{delta} P_unload(x; m) dx with m = max(delta_max_state, delta), of the
   !> force hysteresis_eval returns (clipped at 0 where the interpolated curve dips below
   !> it within rel_tol, and 0 below the cut-off; those dips from samples per delta_max
   !> interval made by hysteresis_prepare, so that the cost is of the order of
   !> hysteresis_eval's). On the loading curve (delta = m) it is
   !> the part of the loading work that comes back; what the turning point leaves behind
   !> is dissipated. Reversible tables: the loading table's energy. The state is not
   !> changed. Statuses as hysteresis_eval (egw_hysteresis_energy's): NaN delta or state
   !> egw_invalid_argument (energy 0); max(delta, state) above delta_max egw_out_of_range
   !> (value written); an energy beyond the doubles egw_invalid_argument. The optional
   !> error says the same with a message naming the argument.
   pure subroutine hysteresis_energy(table, delta, delta_max_state, energy, stat, error)
      type(hysteresis_table), intent(in) :: table   !< built or read
      real(dp), intent(in) :: delta             !< overlap [length]
      real(dp), intent(in) :: delta_max_state   !< the contact's largest overlap so far
      real(dp), intent(out) :: energy           !< [force*length], >= 0
      integer, intent(out) :: stat              !< 0 or an egw status
      !> allocated when stat is not 0, with a message naming the argument
      type(egw_error), allocatable, intent(out), optional :: error
      call energy_value(table, delta, delta_max_state, energy, stat, .false.)
      if (stat == egw_invalid_argument) then
         if (present(error)) call nan_error(delta, "delta_max_state", "-huge(1.0_dp)", error)
      else if (.not. ieee_is_finite(energy)) then
         stat = egw_invalid_argument
         if (present(error)) call fatal_error(error, stat, "delta = "//format_real(delta)// &
            & ", delta_max_state = "//format_real(delta_max_state)// &
            & ": the energy there exceeds the doubles")
      else if (stat /= 0 .and. present(error)) then
         call beyond_status(table%delta_max, "max(delta, delta_max_state)", &
            & max(delta, delta_max_state), [energy], error)
      end if
   end subroutine hysteresis_energy

   !> hysteresis_energy by one walk over the whole span for the dips the evaluation clips
   !> (its cost grows with the pieces of the span, ~100x hysteresis_eval's): the reference
   !> that hysteresis_energy's samples are tested against. Same arguments and statuses
   !> (no error message).
   pure subroutine hysteresis_energy_walk(table, delta, delta_max_state, energy, stat)
      type(hysteresis_table), intent(in) :: table   !< built or read
      real(dp), intent(in) :: delta             !< overlap [length]
      real(dp), intent(in) :: delta_max_state   !< the contact's largest overlap so far
      real(dp), intent(out) :: energy           !< [force*length], >= 0
      integer, intent(out) :: stat              !< 0 or an egw status
      call energy_value(table, delta, delta_max_state, energy, stat, .true.)
      if (stat /= egw_invalid_argument .and. .not. ieee_is_finite(energy)) &
         & stat = egw_invalid_argument
   end subroutine hysteresis_energy_walk

   !> hysteresis_energy's value and status (NaN input, above delta_max); walk (the
   !> reference, hysteresis_energy_walk): the clipped dips from one walk over the span.
   pure subroutine energy_value(table, delta, delta_max_state, energy, stat, walk)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: delta, delta_max_state
      real(dp), intent(out) :: energy
      integer, intent(out) :: stat
      logical, intent(in) :: walk
      type(unload_curve) :: cv
      real(dp) :: m, d_1, lo, ratio, dips, x_top
      stat = 0
      energy = 0.0_dp
      if (ieee_is_nan(delta) .or. ieee_is_nan(delta_max_state)) then
         stat = egw_invalid_argument
         return
      end if
      m = max(delta_max_state, delta)
      if (m > table%delta_max) stat = egw_out_of_range
      if (.not. delta > table%loading%cutoff) return
      energy = table_energy(table%loading, delta)
      if (table%reversible .or. .not. m > table%elastic_limit) return
      cv%m = m
      call turning_point(table, m, cv%first, cv%w, cv%inv_span, cv%f_m)
      ! below the span's end d_1 the force is ratio P_load (unload_branch), above it
      ! P_load - f_m g(s), clipped at 0: int g(s(x)) dx over (lo, delta) with s = (m -
      ! x)/(s_max L) is (1/(s_max L)) times the integral of g over s from s(delta) to
      ! s(lo); the span starts at the cut-off if d_1 is below it (no force there)
      d_1 = m - 1.0_dp/cv%inv_span
      ratio = unload_tail_ratio(table, d_1, cv%f_m, dot_product(cv%w, &
         & table%gap(size(table%s), cv%first:cv%first + 3)))
      if (.not. delta > d_1) then
         energy = ratio*energy
         return
      end if
      lo = max(d_1, table%loading%cutoff)
      if (walk) then
         call span_dips(table, cv, lo, delta, dips, x_top)
      else
         dips = dips_below(table, cv, lo, delta)
      end if
      energy = ratio*table_energy(table%loading, lo) + (energy - table_energy(table%loading, &
         & lo)) - cv%f_m/cv%inv_span*(gap_primitive(table, cv, min((m - lo)*cv%inv_span, &
         & 1.0_dp)) - gap_primitive(table, cv, (m - delta)*cv%inv_span)) - dips
      energy = max(energy, 0.0_dp)
   end subroutine energy_value

   !> int_lo^delta min(F, 0) dx (F the span force of curve cv, lo its span's start): the
   !> dips that the evaluation clips, from the table's samples (energy_prepare) in O(1):
   !> over the whole span, interpolated linearly in m between the samples of m's interval
   !> (at an overlap in the stretch from lo that both samples around m clipped, dip_low:
   !> the integral of F from lo, all of it clipped), less the dips between delta and the
   !> band (dip_band: a short walk, only for an overlap in or below it; from lo instead
   !> where that is shorter). Above the band the span force at delta is looked at: a dip
   !> there that no sample saw (between them) gets the walk from lo, as a turning point
   !> above the table's delta_max (no samples).
   pure real(dp) function dips_below(table, cv, lo, delta) result(total)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: lo, delta
      real(dp) :: u, x_band, f, slope, x_top, above
      integer :: i, j, n, k
      if (.not. allocated(table%dip) .or. cv%m > table%delta_max) then
         call span_dips(table, cv, lo, delta, total, x_top)
         return
      end if
      j = locate(table%m_lookup, table%m, cv%m)
      u = min(max((cv%m - table%m(j))/(table%m(j + 1) - table%m(j)), 0.0_dp), 1.0_dp)
      ! the samples' gap around u: its equal part, then bisection (few samples in a part)
      i = min(int(u*dip_samples), dip_samples - 1) + 1
      k = table%dip_base(i, j)
      n = table%dip_first(j + 1) - 1
      if (i < dip_samples) n = table%dip_base(i + 1, j)
      do while (n - k > 1)
         i = (k + n)/2
         if (table%dip_u(i) <= u) then
            k = i
         else
            n = i
         end if
      end do
      if (delta - lo <= 0.95_dp*min(table%dip_low(k), table%dip_low(k + 1))*(cv%m - lo)) then
         ! in the stretch from lo that every sample clipped: all of it clipped (F(delta)
         ! looked at: a positive force there was not seen by the samples)
         call span_eval(table, cv, delta, f, slope)
         if (.not. f > 0.0_dp) then
            total = span_integral(table, cv, lo, delta)
            return
         end if
      end if
      u = (u - table%dip_u(k))/(table%dip_u(k + 1) - table%dip_u(k))
      total = ((1.0_dp - u)*table%dip(k) + u*table%dip(k + 1))*cv%f_m/cv%inv_span
      x_band = cv%m - table%dip_band(j)/cv%inv_span
      if (delta > x_band) then
         call span_eval(table, cv, delta, f, slope)
         if (.not. f > 0.0_dp) call span_dips(table, cv, lo, delta, total, x_top)
      else if (delta - lo < x_band - delta) then   ! the shorter walk: from lo
         call span_dips(table, cv, lo, delta, total, x_top)
      else
         call span_dips(table, cv, delta, x_band, above, x_top)
         total = min(total - above, 0.0_dp)
      end if
   end function dips_below

   !> int_0^s g(s', m) ds' of curve cv, s <= 1.
   pure real(dp) function gap_primitive(table, cv, s) result(total)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: s
      real(dp) :: t, h, x
      integer :: i, k
      x = min(s, 1.0_dp)
      i = locate(table%s_lookup, table%s, x)
      h = table%s(i + 1) - table%s(i)
      t = (x - table%s(i))/h
      total = 0.0_dp
      do k = 1, 4
         associate (c => table%coef(:, cv%first + k - 1, i))
            total = total + cv%w(k)*(table%gap_integral(cv%first + k - 1, i) + h*t*(c(1) + &
               & t*(c(2)/2 + t*(c(3)/3 + t*c(4)/4))))
         end associate
      end do
   end function gap_primitive

   !> The unclipped span force P_load(x) - f_m g(s(x)) of curve cv and its slope dF/dx
   !> (unload_branch before its clip).
   pure subroutine span_eval(table, cv, x, f, k)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: x
      real(dp), intent(out) :: f, k
      real(dp) :: s, c(4), g, dg, f_d, k_d
      integer :: i
      s = min((cv%m - x)*cv%inv_span, 1.0_dp)
      i = locate(table%s_lookup, table%s, s)
      call gap_combination(table, cv%first, cv%w, i, c)
      call gap_cubic(c, (s - table%s(i))*table%inv_ds(i), table%inv_ds(i), g, dg)
      call table_eval(table%loading, x, f_d, k_d)
      f = f_d - cv%f_m*g
      k = k_d + cv%f_m*dg*cv%inv_span
   end subroutine span_eval

   !> span_eval's force only.
   pure real(dp) function span_force(table, cv, x) result(f)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: x
      real(dp) :: k
      call span_eval(table, cv, x, f, k)
   end function span_force

   !> int_a^b min(F, 0) over the span force F of curve cv (total), the part of the closed
   !> form that the evaluation clips, and an x_top above which no sample was <= 0 (-huge:
   !> none was). F is smooth between the breaks of the loading intervals and of the s
   !> intervals (x = m - s_i/(s_max L)); a piece whose cubic Hermite of its end values and
   !> slopes stays positive is skipped (F is that cubic where the loading interval is
   !> linear, and close to it on ln P intervals); others are sampled at 9 points: where
   !> none is positive the piece's integral is the closed form's (span_integral), and
   !> where some are not the negative runs between their neighbours (roots by
   !> regula falsi) are integrated by 8-point Gauss-Legendre (exact for the cubic F of a
   !> linear loading interval). Dips narrower than an eighth of a piece go unseen: they are
   !> of the order of the interpolation noise times their width cubed. Every piece of
   !> [a, b] is looked at: stopping above 10 rel_tol f_m (the unloading force increases
   !> with delta) missed dips of LAMMPS's EP-GW tables (test energy_epgw: the unloading
   !> energy drift 1.7e-4 instead of 1.6e-5). Cost: the pieces of [a, b] (the reference
   !> walk, and energy_prepare's samples; dips_below walks only short stretches).
   pure subroutine span_dips(table, cv, a, b, total, x_top, x_low)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: a, b
      real(dp), intent(out) :: total, x_top
      !> the end of the run from a on which every sample was <= 0 (a: none)
      real(dp), intent(out), optional :: x_low
      real(dp) :: x_a, x_b, next, s_a, xs(0:8), fs(0:8), f_a, k_a, f_b, k_b
      integer :: i, k, it, n_load
      logical :: low_open
      total = 0.0_dp
      x_top = -huge(1.0_dp)
      call span_eval(table, cv, a, f_a, k_a)
      low_open = .not. f_a > 0.0_dp
      if (present(x_low)) x_low = a
      n_load = size(table%loading%delta)
      x_a = a
      do it = 1, 4*(n_load + size(table%s)) + 8
         if (.not. x_a < b) exit
         ! the next break above x_a: a loading node or an s node (s falls as x grows)
         x_b = b
         if (x_a < table%loading%delta_max) then
            i = table_interval(table%loading, x_a)
            x_b = min(x_b, table%loading%delta(i + 1))
         end if
         s_a = min((cv%m - x_a)*cv%inv_span, 1.0_dp)
         i = locate(table%s_lookup, table%s, s_a)
         next = cv%m - table%s(i)/cv%inv_span
         if (.not. next > x_a .and. i > 1) next = cv%m - table%s(i - 1)/cv%inv_span
         if (next > x_a) x_b = min(x_b, next)
         if (.not. x_b > x_a) exit   ! round-off at a break
         call span_eval(table, cv, x_b, f_b, k_b)
         if (hermite_positive(x_b - x_a, f_a, f_b, k_a, k_b)) then
            low_open = .false.
         else
            xs = x_a + (x_b - x_a)*[(real(k, dp), k=0, 8)]/8
            fs(0) = f_a
            do k = 1, 7
               fs(k) = span_force(table, cv, xs(k))
            end do
            fs(8) = f_b
            if (all(.not. fs > 0.0_dp)) then
               ! a piece below 0 at every sample: min(F, 0) = F, the closed form
               total = total + span_integral(table, cv, x_a, x_b)
               x_top = x_b
               if (low_open .and. present(x_low)) x_low = x_b
            else if (any(.not. fs > 0.0_dp)) then
               if (low_open .and. present(x_low)) then
                  k = findloc(fs > 0.0_dp, .true., dim=1) - 1   ! the first positive sample
                  x_low = xs(k - 1)
               end if
               low_open = .false.
               do k = 0, 7
                  total = total + negative_part(table, cv, xs(k), xs(k + 1), fs(k), &
                     & fs(k + 1))
                  if (.not. (fs(k) > 0.0_dp .and. fs(k + 1) > 0.0_dp)) x_top = xs(k + 1)
               end do
            else
               low_open = .false.
            end if
         end if
         x_a = x_b
         f_a = f_b
         k_a = k_b
      end do
   end subroutine span_dips

   !> int_a^b F dx of the span force of curve cv, a < b in its span (s <= 1), from the
   !> primitives: the loading table's energy less f_m/(s_max L) times the gap's integral.
   pure real(dp) function span_integral(table, cv, a, b) result(total)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: a, b
      total = table_energy(table%loading, b) - table_energy(table%loading, a) - &
         & cv%f_m/cv%inv_span*(gap_primitive(table, cv, (cv%m - a)*cv%inv_span) - &
         & gap_primitive(table, cv, (cv%m - b)*cv%inv_span))
   end function span_integral

   !> True when the cubic Hermite of (f0, k0) and (f1, k1) over a width h is positive
   !> on it: both ends positive and no interior minimum at or below 0.
   pure logical function hermite_positive(h, f0, f1, k0, k1) result(ok)
      real(dp), intent(in) :: h, f0, f1, k0, k1
      real(dp) :: c1, c2, c3, disc, t, r(2)
      integer :: j
      ok = f0 > 0.0_dp .and. f1 > 0.0_dp
      if (.not. ok) return
      ! p(t) = f0 + c1 t + c2 t^2 + c3 t^3 on [0, 1]; p'(t) = c1 + 2 c2 t + 3 c3 t^2
      c1 = h*k0
      c2 = 3*(f1 - f0) - h*(2*k0 + k1)
      c3 = 2*(f0 - f1) + h*(k0 + k1)
      if (abs(c3) > 0.0_dp) then
         disc = c2*c2 - 3*c3*c1
         if (disc < 0.0_dp) return   ! monotone
         r = [(-c2 - sqrt(disc))/(3*c3), (-c2 + sqrt(disc))/(3*c3)]
      else if (abs(c2) > 0.0_dp) then
         r = -c1/(2*c2)
      else
         return   ! linear
      end if
      do j = 1, 2
         t = r(j)
         if (t > 0.0_dp .and. t < 1.0_dp) ok = ok .and. f0 + t*(c1 + t*(c2 + t*c3)) > 0.0_dp
      end do
   end function hermite_positive

   !> int_x0^x1 min(F, 0) where F(x0) = f0, F(x1) = f1 and F changes sign at most once
   !> (the root to 1e-12 of the width: what remains is ~1e-24 of its slope times width^2).
   pure real(dp) function negative_part(table, cv, x0, x1, f0, f1) result(total)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: x0, x1, f0, f1
      real(dp) :: lo_x, hi_x, r, f_lo, f_hi, f_r
      integer :: j, side
      total = 0.0_dp
      if (f0 > 0.0_dp .and. f1 > 0.0_dp) return
      if (.not. f0 > 0.0_dp .and. .not. f1 > 0.0_dp) then
         total = min(gauss_integral(table, cv, x0, x1), 0.0_dp)
         return
      end if
      ! one end positive: the root by regula falsi (Illinois: a few evaluations, the
      ! bracket kept), then the negative side
      lo_x = x0
      hi_x = x1
      f_lo = f0
      f_hi = f1
      side = 0
      r = x0
      do j = 1, 60
         r = (lo_x*f_hi - hi_x*f_lo)/(f_hi - f_lo)
         if (.not. (r > lo_x .and. r < hi_x)) r = 0.5_dp*(lo_x + hi_x)
         if (.not. (r > lo_x .and. r < hi_x)) exit
         f_r = span_force(table, cv, r)
         if (abs(f_r) <= 1.0e-14_dp*max(abs(f0), abs(f1))) exit   ! at the root
         if ((f_r > 0.0_dp) .eqv. (f_lo > 0.0_dp)) then
            lo_x = r
            f_lo = f_r
            if (side == -1) f_hi = 0.5_dp*f_hi
            side = -1
         else
            hi_x = r
            f_hi = f_r
            if (side == 1) f_lo = 0.5_dp*f_lo
            side = 1
         end if
         if (hi_x - lo_x <= 1.0e-12_dp*(x1 - x0)) exit
      end do
      if (f0 > 0.0_dp) then
         total = min(gauss_integral(table, cv, r, x1), 0.0_dp)
      else
         total = min(gauss_integral(table, cv, x0, r), 0.0_dp)
      end if
   end function negative_part

   !> 8-point Gauss-Legendre integral of the span force of curve cv over [x0, x1].
   pure real(dp) function gauss_integral(table, cv, x0, x1) result(total)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: x0, x1
      integer :: q
      total = 0.0_dp
      do q = 1, size(gl_x)
         total = total + gl_w(q)*span_force(table, cv, x0 + (x1 - x0)*gl_x(q))
      end do
      total = total*(x1 - x0)
   end function gauss_integral

   !> The dips' samples (dip, dip_u, dip_first, dip_band): at turning points of each
   !> delta_max interval, the walk over the whole span (span_dips), normalised by
   !> P_load(m)/(s_max L(m)) (the scale of the span's force and of its width in s), so
   !> that a sample is a number of order rel_tol; dip_samples + 1 evenly spaced, then each
   !> gap bisected until linear interpolation meets the walk at its midpoint to dip_tol of
   !> the span's (unclipped) integral in the same units, or the gap is 1/dip_samples_max
   !> of the interval (dips come and go with m: bumps of a few hundredths of an interval
   !> were seen, and the walk's own jumps where it first sees a dip). dip_band: the
   !> smallest s above which a sample clipped anything, less a margin of a twentieth
   !> (dips move with m between samples); dip_low: per sample, the fraction of the span
   !> from its start over which it clipped everything. Called by hysteresis_prepare
   !> (cost: a walk per
   !> sample, 33 per interval where the dips are smooth in m, more where they are not).
   pure subroutine energy_prepare(table)
      type(hysteresis_table), intent(inout) :: table
      real(dp), allocatable :: store(:, :)
      real(dp) :: band, scale, u0, u1, q0, q1, top, low0, low1
      integer :: j, k, n_m, used
      n_m = size(table%m)
      if (allocated(table%dip)) deallocate (table%dip)
      if (allocated(table%dip_u)) deallocate (table%dip_u)
      if (allocated(table%dip_first)) deallocate (table%dip_first)
      if (allocated(table%dip_band)) deallocate (table%dip_band)
      if (allocated(table%dip_low)) deallocate (table%dip_low)
      if (allocated(table%dip_base)) deallocate (table%dip_base)
      allocate (table%dip_first(n_m), table%dip_band(n_m - 1), store(3, 64*n_m), &
         & table%dip_base(dip_samples, n_m - 1))
      used = 0
      do j = 1, n_m - 1
         band = huge(1.0_dp)
         table%dip_first(j) = used + 1
         u0 = 0.0_dp
         call dip_sample(table, j, u0, q0, top, scale, low0)
         band = min(band, top)
         call dip_push(store, used, [u0, q0, low0])
         do k = 1, dip_samples
            u1 = real(k, dp)/dip_samples
            call dip_sample(table, j, u1, q1, top, scale, low1)
            band = min(band, top)
            table%dip_base(k, j) = used   ! u0's sample
            call refine(table, j, u0, u1, q0, q1, low1, band, store, used)
            u0 = u1
            q0 = q1
         end do
         table%dip_band(j) = max(0.95_dp*band, 0.0_dp)
      end do
      table%dip_first(n_m) = used + 1
      table%dip_u = store(1, 1:used)
      table%dip = store(2, 1:used)
      table%dip_low = store(3, 1:used)
   end subroutine energy_prepare

   !> Append the samples of (u0, u1] of delta_max interval j (q0, q1 the samples at its
   !> ends, low1 u1's dip_low; u0's already stored): its midpoint's, then each half
   !> refined where linear interpolation misses the midpoint by more than dip_tol of the
   !> span's integral.
   pure recursive subroutine refine(table, j, u0, u1, q0, q1, low1, band, store, used)
      type(hysteresis_table), intent(in) :: table
      integer, intent(in) :: j
      real(dp), intent(in) :: u0, u1, q0, q1, low1
      real(dp), intent(inout) :: band
      real(dp), allocatable, intent(inout) :: store(:, :)
      integer, intent(inout) :: used
      real(dp) :: u_mid, q_mid, top, scale, low_mid
      u_mid = 0.5_dp*(u0 + u1)
      call dip_sample(table, j, u_mid, q_mid, top, scale, low_mid)
      band = min(band, top)
      if (abs(q_mid - 0.5_dp*(q0 + q1)) <= dip_tol*scale .or. &
         & u1 - u0 <= 2.0_dp/dip_samples_max) then
         call dip_push(store, used, [u_mid, q_mid, low_mid])
         call dip_push(store, used, [u1, q1, low1])
      else
         call refine(table, j, u0, u_mid, q0, q_mid, low_mid, band, store, used)
         call refine(table, j, u_mid, u1, q_mid, q1, low1, band, store, used)
      end if
   end subroutine refine

   !> Append a sample (u, q, low) to store (grown by doubling).
   pure subroutine dip_push(store, used, sample)
      real(dp), allocatable, intent(inout) :: store(:, :)
      integer, intent(inout) :: used
      real(dp), intent(in) :: sample(3)
      real(dp), allocatable :: grown(:, :)
      if (used == size(store, 2)) then
         allocate (grown(3, 2*used + 16))
         grown(:, 1:used) = store(:, 1:used)
         call move_alloc(grown, store)
      end if
      used = used + 1
      store(:, used) = sample
   end subroutine dip_push

   !> One sample of energy_prepare at fraction u of delta_max interval j: the normalised
   !> dips q, the s above which none was clipped (top; huge where none was) and the span's
   !> unclipped integral in the same units (scale, > 0), and the fraction of the span from
   !> its start over which every sample was clipped (low).
   pure subroutine dip_sample(table, j, u, q, top, scale, low)
      type(hysteresis_table), intent(in) :: table
      integer, intent(in) :: j
      real(dp), intent(in) :: u
      real(dp), intent(out) :: q, top, scale
      real(dp), intent(out) :: low   !< (x_low - lo)/(m - lo) of span_dips
      type(unload_curve) :: cv
      real(dp) :: lo, total, x_top, x_low
      q = 0.0_dp
      top = huge(1.0_dp)
      scale = tiny(1.0_dp)
      low = 0.0_dp
      cv%m = table%m(j) + (table%m(j + 1) - table%m(j))*u
      if (u >= 1.0_dp) cv%m = table%m(j + 1)
      if (.not. cv%m > table%elastic_limit) return
      call turning_point(table, cv%m, cv%first, cv%w, cv%inv_span, cv%f_m)
      if (.not. cv%f_m > 0.0_dp) return
      lo = max(cv%m - 1.0_dp/cv%inv_span, table%loading%cutoff)
      if (.not. lo < cv%m) return
      call span_dips(table, cv, lo, cv%m, total, x_top, x_low)
      q = total*cv%inv_span/cv%f_m
      low = (x_low - lo)/(cv%m - lo)
      if (x_top > -huge(1.0_dp)) top = (cv%m - x_top)*cv%inv_span
      scale = max(abs(span_integral(table, cv, lo, cv%m))*cv%inv_span/cv%f_m, tiny(1.0_dp))
   end subroutine dip_sample

   !> A new contact's state for hysteresis_eval_state: never touched (-huge), no cache.
   pure subroutine hysteresis_state_init(state)
      real(dp), intent(out) :: state(hysteresis_state_size)   !< the contact's new state
      state = 0.0_dp
      state(1) = -huge(1.0_dp)
   end subroutine hysteresis_state_init

   !> g and dg/ds of the cubic c in t = (s - s_i)/(s_{i+1} - s_i) (inv_ds = the 1/width);
   !> Estrin's scheme: shorter dependency chains than Horner.
   pure subroutine gap_cubic(c, t, inv_ds, g, dg)
      real(dp), intent(in) :: c(4), t, inv_ds
      real(dp), intent(out) :: g, dg
      real(dp) :: t2
      t2 = t*t
      g = (c(1) + t*c(2)) + t2*(c(3) + t*c(4))
      dg = ((c(2) + 2*t*c(3)) + 3*t2*c(4))*inv_ds
   end subroutine gap_cubic

   !> What the unloading branch needs of the turning point m: the Lagrange stencil of the
   !> m interval (clamped at the ends of the grid; the last curve above the table), its
   !> weights, 1/(s_max L) interpolated with them and the loading force P_load(m).
   pure subroutine turning_point(table, m, first, w, inv_span, f_m)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: m
      integer, intent(out) :: first
      real(dp), intent(out) :: w(4), inv_span, f_m
      real(dp) :: d(4), k_m
      integer :: j, n_m
      call table_eval(table%loading, m, f_m, k_m)
      n_m = size(table%m)
      j = locate(table%m_lookup, table%m, min(m, table%delta_max))
      first = stencil_first(j, n_m, table%m_break)
      d = m_coordinate(m, table%m_break) - m_coordinate(table%m(first:first + 3), table%m_break)
      w(1) = d(2)*d(3)*d(4)*table%lagrange(1, j)
      w(2) = d(1)*d(3)*d(4)*table%lagrange(2, j)
      w(3) = d(1)*d(2)*d(4)*table%lagrange(3, j)
      w(4) = d(1)*d(2)*d(3)*table%lagrange(4, j)
      if (m > table%delta_max) w = [0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp]
      ! 1/(s_max L) interpolated (no division on the hot path; smooth and > 0 as L)
      inv_span = w(1)*table%inv_span(first) + w(2)*table%inv_span(first + 1) + &
         & w(3)*table%inv_span(first + 2) + w(4)*table%inv_span(first + 3)
      if (.not. inv_span > 0.0_dp) inv_span = table%inv_span(j)
   end subroutine turning_point

   !> The gap cubic g(t) of the turning point (stencil first, weights w) on s interval i:
   !> the four curves' cubics (16 contiguous numbers) combined.
   pure subroutine gap_combination(table, first, w, i, c)
      type(hysteresis_table), intent(in) :: table
      integer, intent(in) :: first, i
      real(dp), intent(in) :: w(4)
      real(dp), intent(out) :: c(4)
      associate (cf => table%coef(:, first:first + 3, i))
         c(1) = w(1)*cf(1, 1) + w(2)*cf(1, 2) + w(3)*cf(1, 3) + w(4)*cf(1, 4)
         c(2) = w(1)*cf(2, 1) + w(2)*cf(2, 2) + w(3)*cf(2, 3) + w(4)*cf(2, 4)
         c(3) = w(1)*cf(3, 1) + w(2)*cf(3, 2) + w(3)*cf(3, 3) + w(4)*cf(3, 4)
         c(4) = w(1)*cf(4, 1) + w(2)*cf(4, 2) + w(3)*cf(4, 3) + w(4)*cf(4, 4)
      end associate
   end subroutine gap_combination

   !> The force and stiffness at delta (cut-off < delta < m) below the turning point m
   !> (P_load(m) = f_m, 1/(s_max L) = inv_span) from its gap cubic c on s interval i, at
   !> s = min((m - delta) inv_span, 1): P_load(delta) - P_load(m) g(s, m), 0 where that is
   !> not positive. Below the curve's span (s clamped at 1, where the loading force is
   !> below rel_tol of P_ref) the unloading force keeps its ratio to the loading force at
   !> the span's end (unload_tail_ratio): the loading tail, scaled.
   pure subroutine unload_branch(table, c, i, s, m, f_m, inv_span, delta, force, stiffness)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: c(4), s, m, f_m, inv_span, delta
      integer, intent(in) :: i
      real(dp), intent(out) :: force, stiffness
      real(dp) :: g, dg, f_d, k_d, ratio
      call gap_cubic(c, (s - table%s(i))*table%inv_ds(i), table%inv_ds(i), g, dg)
      call table_eval(table%loading, delta, f_d, k_d)
      if (s >= 1.0_dp) then
         ratio = unload_tail_ratio(table, m - 1.0_dp/inv_span, f_m, g)
         force = ratio*f_d
         stiffness = ratio*k_d
         return
      end if
      force = f_d - f_m*g
      stiffness = k_d + f_m*dg*inv_span
      if (.not. force > 0.0_dp) then
         force = 0.0_dp
         stiffness = 0.0_dp
      end if
   end subroutine unload_branch

   !> The unloading force over the loading force at the end d_1 of a curve's span, where
   !> its gap is g_1 (P_load(m) = f_m), in [0, 1]: below d_1 the unloading force is that
   !> ratio of the loading tail (continuous at d_1 where the force there is positive).
   pure real(dp) function unload_tail_ratio(table, d_1, f_m, g_1) result(ratio)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: d_1, f_m, g_1
      real(dp) :: f_1, k_1
      ratio = 0.0_dp
      if (table%capped) return   ! below the residual overlap: apart
      call table_eval(table%loading, d_1, f_1, k_1)
      if (f_1 > 0.0_dp) ratio = min(max(1.0_dp - f_m*g_1/f_1, 0.0_dp), 1.0_dp)
   end function unload_tail_ratio

   !> Derive the evaluation data (cubics on the union s grid, Lagrange denominators,
   !> lookup buckets, the curves' integrals, the data tag; reversible tables: the tag
   !> only) from the stored nodes; called by the build and by readers.
   pure subroutine hysteresis_prepare(table)
      type(hysteresis_table), intent(inout) :: table
      integer :: n_s, n_m, i, j, first, k, l
      real(dp) :: h
      table%tag = data_tag(table)
      table%capped = hertz_capped(table%params)
      table%elastic_limit = table%loading%cutoff
      if (table%capped) table%elastic_limit = max(table%elastic_limit, &
         & first_yield(table%params))
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
      if (table%reversible) return   ! no curves: the loading table serves
      n_s = size(table%s)
      n_m = size(table%m)
      if (allocated(table%coef)) deallocate (table%coef)
      if (allocated(table%inv_ds)) deallocate (table%inv_ds)
      if (allocated(table%lagrange)) deallocate (table%lagrange)
      if (allocated(table%gap_integral)) deallocate (table%gap_integral)
      if (allocated(table%run_first)) deallocate (table%run_first)
      if (allocated(table%run_last)) deallocate (table%run_last)
      table%inv_span = 1.0_dp/(table%s_max*table%length)
      allocate (table%coef(4, n_m, n_s - 1), table%inv_ds(n_s - 1), table%lagrange(4, n_m - 1))
      do i = 1, n_s - 1
         h = table%s(i + 1) - table%s(i)
         table%inv_ds(i) = 1.0_dp/h
         do j = 1, n_m
            associate (r0 => table%gap(i, j), r1 => table%gap(i + 1, j), &
               & d0 => h*table%slope(i, j), d1 => h*table%slope(i + 1, j))
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
      do j = 1, n_m - 1
         first = stencil_first(j, n_m, table%m_break)
         do k = 1, 4
            h = 1.0_dp
            do l = 1, 4
               if (l /= k) h = h*(m_coordinate(table%m(first + k - 1), table%m_break) - &
                  & m_coordinate(table%m(first + l - 1), table%m_break))
            end do
            table%lagrange(k, j) = 1.0_dp/h
         end do
      end do
      call make_lookup(table%m, table%m_lookup)
      call make_lookup(table%s, table%s_lookup)
      call make_runs(table)
      call energy_prepare(table)
   end subroutine hysteresis_prepare

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
      end do
      allocate (table%run_first(max(n_m - 3, 1), n_s - 1), &
         & table%run_last(max(n_m - 3, 1), n_s - 1))
      do first = 1, max(n_m - 3, 1)
         k = 1
         do i = 1, n_s - 1
            ! a union node that is one of the stencil's curves' own starts a new run
            if (i > 1) then
               if (.not. all(joined(first:min(first + 3, n_m), i))) k = i
            end if
            table%run_first(first, i) = k
         end do
         k = n_s - 1
         do i = n_s - 1, 1, -1
            if (i < n_s - 1) then
               if (.not. all(joined(first:min(first + 3, n_m), i + 1))) k = i
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

   !> capped at 2**max_bucket_level.
   pure subroutine make_lookup(x, lookup)
      real(dp), intent(in) :: x(:)
      type(grid_lookup), intent(out) :: lookup
      real(dp) :: width, finest, xb
      integer :: n, b, i, level
      n = size(x)
      width = x(n) - x(1)
      finest = minval(x(2:n) - x(1:n - 1))
      level = 3
      do while (level < max_bucket_level .and. width/2.0_dp**level > 0.75_dp*finest)
         level = level + 1
      end do
      lookup%n_bucket = 2**level
      lookup%origin = x(1)
      lookup%scale = lookup%n_bucket/width
      allocate (lookup%bucket(0:lookup%n_bucket))
      i = 1
      do b = 0, lookup%n_bucket
         xb = lookup%origin + b/lookup%scale
         do while (i < n - 1 .and. x(i + 1) <= xb)
            i = i + 1
         end do
         lookup%bucket(b) = i
      end do
   end subroutine make_lookup

   !> The node of the delta_max grid m at exactly 0, where the smooth sphere of the
   !> extended models first touches (its Hertz part grows as m^(3/2) from there: the curves
   !> are not smooth across it), if there are 4 nodes on each side (it included); else 0.
   pure integer function m_breakpoint(m) result(k)
      real(dp), intent(in) :: m(:)
      integer :: j
      k = 0
      do j = 4, size(m) - 3
         if (m(j) == 0.0_dp) k = j
      end do
   end function m_breakpoint

   !> The variable in which the curves are interpolated across delta_max: m itself, and
   !> with a breakpoint at 0 (k_b > 0) sqrt(m) above it, in which the curves just above it
   !> are smooth (the contact radius grows as sqrt(m)); no stencil mixes the two sides.
   elemental real(dp) function m_coordinate(m, k_b) result(x)
      real(dp), intent(in) :: m
      integer, intent(in) :: k_b
      x = m
      if (k_b > 0 .and. m > 0.0_dp) x = sqrt(m)
   end function m_coordinate

   !> The first of the four delta_max nodes of the Lagrange stencil of interval j (m_j <=
   !> m < m_{j+1}) of n_m nodes: centred, clamped at the grid's ends and, with a breakpoint
   !> node k_b (m_breakpoint), on interval j's side of it (the cubic does not straddle the
   !> onset of the Hertz part).
   pure integer function stencil_first(j, n_m, k_b) result(first)
      integer, intent(in) :: j, n_m, k_b
      first = min(max(j - 1, 1), n_m - 3)
      if (k_b > 0) then
         if (j < k_b) then
            first = min(first, k_b - 3)
         else
            first = max(first, k_b)
         end if
      end if
   end function stencil_first

   !> i with x(i) <= v < x(i+1), clamped to [1, n-1]: the bucket's interval, then a short
   !> forward scan (at most one step where the buckets are as fine as the grid).
   pure integer function locate(lookup, x, v) result(i)
      type(grid_lookup), intent(in) :: lookup
      real(dp), intent(in) :: x(:), v
      integer :: b, n
      n = size(x)
      b = min(max(int((v - lookup%origin)*lookup%scale), 0), lookup%n_bucket)
      i = lookup%bucket(b)
      do while (i < n - 1)
         if (x(i + 1) > v) exit
         i = i + 1
      end do
   end function locate

end module egw_hysteresis
