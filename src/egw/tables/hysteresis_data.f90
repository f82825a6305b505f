!> The data of an egw_hysteresis table and the arithmetic every use of it shares: the
!> table type, the turning point's Lagrange stencil and weights, the gap cubics of its
!> unloading curve, and the bucket lookups of the delta_max and s grids (the evaluation
!> in egw_hysteresis, the energy in egw_unload_energy, the build in its submodule).
!>
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
!> of four neighbouring curves (log-ratio tables: quintic, of six; stencil_window), and
!> the m grid is bisected until that combination meets
!> the midpoint's curve at all its nodes to rel_tol (the table's whole error there).
!> Every curve's cubics are then resampled onto the union of the s nodes (exactly: the
!> union refines every curve's own nodes), so that an evaluation needs one lookup in s and
!> one in m, served by uniform buckets: no search, no allocation, only the caller's
!> history changes. Elastic summits (not EP-GW, psi = 0) store no curves: unloading
!> retraces the loading table exactly. Rough + cap tables whose cap acts below delta_max
!> (mapped) take s piecewise linear in m - delta instead (the two-piece map, map_s;
!> turning points at or below 0 only its tail). Hertz + cap tables (force_ratio, format
!> version 5) store the unloading force itself, u = P/P_load(m), P = P_load(m) u(s, m),
!> with 1/L on a fine delta_max grid of their own (fine_inv_span).
module egw_hysteresis_data
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use, intrinsic :: iso_fortran_env, only: int64
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_invalid_argument, fatal_error
   use egw_params, only: contact_params
   use egw_table, only: force_table, table_eval, segment_eval
   use egw_law_pieces, only: law_pieces
   implicit none
   private

   public :: hysteresis_table, grid_lookup, unload_curve, nan_error, gap_cubic, &
      & turning_point, gap_combination, unload_tail_ratio, make_lookup, m_breakpoint, &
      & m_coordinate, stencil_first, locate, turning_knee, map_s, map_x, map_piece, &
      & map_iota, map_lengths, edge_breaks, edge_s, edge_xi, edge_segment, log_branch, &
      & max_log_ratio, log_unload, stencil_width, stencil_window, stencil_sum, unload_floor, &
      & stores_ratio

   !> Doubles of a contact's state for hysteresis_eval_state: (1) the largest overlap so far,
   !> then caches that name the table (3, its tag): of the turning point (2, the m they
   !> belong to): (4) the Lagrange stencil, (5) 1/(s_max L), (6) P_load, (7:10) the weights
   !> (a log-ratio table's six-point stencil: (5:10) the weights, its pieces need neither
   !> 1/(s_max L) nor P_load); (13) s_max L; of the piece of its unloading curve last used (make_piece): (11:12) its
   !> open ends, (14:17) its cubic in delta; of the loading table's interval last used
   !> (the piece's, while there is one): (18:19) its ends, (20:23) its cubic, (24) 1 where
   !> that is ln P (then the piece's cubic is the gap part). A contact that stays inside
   !> its piece (most DEM steps) touches nothing but its state.
   integer, parameter, public :: hysteresis_state_size = 24

   !> Most delta_max nodes of a Lagrange stencil: log-ratio tables interpolate their curves
   !> across delta_max on six nodes (stencil_width), the gap tables on four.
   integer, parameter, public :: max_stencil = 6

   !> The two-piece s map of rough + cap tables (mapped; doc/theory.md section 12): every
   !> curve's knee (the smooth cap's residual overlap delta_r(m)) at s = s_knee and
   !> delta = 0 (where the loading curve's Hertz part sets in) at s = s_zero, the tail below
   !> 0 over [s_zero, 1] in a fixed length; nodes of every curve (dyadic: the union grid
   !> keeps them exactly).
   real(dp), parameter, public :: s_knee = 0.5_dp, s_zero = 0.75_dp

   !> The relative error of L(m) that a force_ratio table's fine grid is bisected to, in
   !> units of rel_tol: near the residual overlap u ~ (1 - s)**1.5, so a relative error e
   !> of L (of s) is 1.5 e/(1 - s) of the local force, 1 - s ~ 1e-3**(2/3) = 0.01 where u
   !> is 1e-3 (the floor of the local tolerance): e <= rel_tol/4 0.01/1.5 = rel_tol/600.
   !> (1/L on the table's own nodes left 0.057 of the local force at 1e-3 on stop 49's
   !> 15 nodes, four times finer 4.1e-4; four times finer on a 29-node grid graded
   !> towards first yield 1.1e-3: doc/stability.md stops 49 and 50)
   real(dp), parameter, public :: fine_length_tol = 1.0_dp/600

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
      !> largest weighted mismatch found at check solves (rel_tol's units; egw.h's
      !> egw_hysteresis_info.max_error: it includes intervals too narrow to split, and is
      !> above rel_tol where they miss it; on gap curves the error in s between the check
      !> curves' nodes too, hysteresis_build's gap_bound)
      real(dp) :: max_error = 0.0_dp
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
      !> interval i (the four curves of a Lagrange stencil share two cache lines, the six
      !> of a log-ratio table's three)
      real(dp), allocatable :: coef(:, :, :)
      real(dp), allocatable :: inv_ds(:)       !< 1/(s_{i+1} - s_i)
      !> (n_m - n_w + 1, n_s - 1): the first and last s interval of the run around interval
      !> i on which the n_w curves of the stencil window first are each one cubic (the
      !> union nodes inside it are none of theirs): a state's piece spans the run
      integer, allocatable :: run_first(:, :), run_last(:, :)
      !> (n_m, n_s): int_0^{s_i} g(s, m_j) ds of each curve's cubics (hysteresis_energy)
      real(dp), allocatable :: gap_integral(:, :)
      !> log-ratio tables, (4, n_m, n_s - 1): the cubic in t (as coef) of each curve's
      !> eta = ln(E_load(delta)/E(delta)), E its energy from the cut-off (hysteresis_energy),
      !> E_load the loading table's; from exact values and slopes at the s nodes
      !> (log_energy_prepare, called by hysteresis_prepare)
      real(dp), allocatable :: energy_coef(:, :, :)
      !> log-ratio tables, (n_m - 1): delta_max intervals whose energy is the walk's
      !> (where energy_coef missed it at the interval's middle curve; log_energy_prepare)
      logical, allocatable :: energy_walk(:)
      !> log-ratio tables, (n_m): each curve's first s node at or below the loading
      !> cut-off (n_s + 1: none): an s interval that reaches it on a curve of the stencil
      !> takes the walk from the cut-off (log_energy_prepare)
      integer, allocatable :: energy_cut(:)
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
      !> nodes of the window of every stencil (stencil_width: 6 for log-ratio tables of 6
      !> or more delta_max nodes, 4 else; hysteresis_prepare)
      integer :: n_w = 4
      !> (max_stencil, n_m - 1): 1/prod(m_k - m_l) of the Lagrange weights of interval j's
      !> stencil at the nodes of its window (stencil_window), 0 at a window node outside the
      !> stencil (and at 5, 6 where n_w = 4)
      real(dp), allocatable :: lagrange(:, :)
      !> (n_m): m_coordinate of the delta_max nodes (hysteresis_prepare: no sqrt per
      !> node in turning_point)
      real(dp), allocatable :: m_coord(:)
      type(grid_lookup) :: m_lookup, s_lookup
      !> an integer in [1, 2**52) hashed from the stored data: a state's cached turning
      !> point is used only by a table with the same data (hysteresis_eval_state)
      real(dp) :: tag = 0.0_dp
      !> the curves store h = ln(P_load(delta)/P) (log_ratio: EP-GW without the cap, or a
      !> rough model whose cap does not act below delta_max; set by the build and the
      !> readers) instead of the gap g, at s of the edge map (edge_breaks: s piecewise linear in m - delta,
      !> the residual-overlap edge at s in [1/2, 3/4] for every m), slopes as
      !> dh/d(m - delta); s_max = 1 and inv_span = 1/L (hysteresis_prepare)
      logical :: log_ratio = .false.
      !> (3, n_m): dxi/ds of each curve's edge-map segments (log_ratio; hysteresis_prepare):
      !> a stored slope dh/dxi times it is the curve's dh/ds there
      real(dp), allocatable :: xi_scale(:, :)
      !> log-ratio tables, (2, n_m, n_s): gap and slope at each s node, the curves side by
      !> side (hysteresis_prepare): a state's piece reads a stencil's six curves at a run's
      !> two end nodes from four cache lines, not from gap's and slope's 24
      real(dp), allocatable :: gap_slope(:, :, :)
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
      !> first yield of the flow-pressure cap delta_y (first_yield; 0 without the cap), set
      !> by hysteresis_prepare at build and read: the continuation's scale beyond delta_max
      !> (egw_hysteresis_beyond), not recomputed at every call there
      real(dp) :: delta_yield = 0.0_dp
      !> Hertz + cap, format version 5 (the build's since stop 50): the curves store the
      !> unloading force itself, u = P/P_load(m) (1 at s = 0, 0 at s = 1) with du/ds, in
      !> place of the gap (P = P_load(m) sum_k w_k u_k(s), no loading force below the
      !> turning point), and 1/L comes from fine_length, not from length: the table
      !> holds rel_tol of the local force down to 1e-3 of the turning point's between its
      !> node curves too (doc/stability.md, stops 49 and 50)
      logical :: force_ratio = .false.
      !> force_ratio: L(m) = m - residual overlap (the cap model's) on its own delta_max
      !> grid fine_m (n_f, increasing, from m(1) to m(n_m), every node of m among them
      !> with its length), finer than m's where 1/L's cubic interpolation needs it
      !> (the build bisects it to fine_length_tol): the stored data
      real(dp), allocatable :: fine_m(:), fine_length(:)
      !> force_ratio: 1/L at fine_m and the Lagrange denominators of the four-node stencils
      !> fine_m(k .. k + 3) (4, n_f - 3), their buckets (hysteresis_prepare)
      real(dp), allocatable :: fine_inv(:), fine_lagrange(:, :)
      type(grid_lookup) :: fine_lookup
      !> rough + cap with the two-piece s map (format version 4): s = (m - delta)/(s_max
      !> L(m)) with L(m) = (m - knee(m))/s_knee down to the knee, then linear to s_zero at
      !> delta = 0, then on below 0 at slope (1 - s_zero)/tail_length (map_s; a turning
      !> point at or below 0 has only that tail, from s_zero); the stored slopes are
      !> dg/d(m - delta) times tail_length (continuous across the breaks), the cubics'
      !> slopes on each piece scaled by piece_scale
      logical :: mapped = .false.
      real(dp), allocatable :: knee(:)         !< (n_m) the knee delta_r(m_j) (mapped)
      real(dp) :: tail_length = 0.0_dp         !< the tail piece's length in delta (mapped)
      !> mapped, format version 6 (the build's since stop 66): the curves store the
      !> unloading force u = P/P_load(m) (1 at s = 0) with du/ds times tail_length on the
      !> two-piece map, in place of the gap: P = P_load(m) sum_k w_k u_k(s), no loading
      !> force below the turning point; below the tail's end (s = 1) the loading tail
      !> scaled as the gap's. The loading table's error at delta does not enter the
      !> curves (doc/benchmarks.md, stops 65 local31 and 66 umap33). Not force_ratio:
      !> L(m) stays the map's, the cut-off the loading table's. (Version 4: the gap.)
      logical :: ratio_on_map = .false.
      !> (3, n_m): per curve and piece, (dx/ds of the piece)/tail_length, x = m - delta: the
      !> stored slope times it is dg/ds on that piece (hysteresis_prepare; 1 unless mapped)
      real(dp), allocatable :: piece_scale(:, :)
      !> the largest overlap (or state) whose force stays well inside the doubles: where
      !> the loading table's deep-overlap law beyond delta_max reaches huge/4 (the C
      !> layer's input check; hysteresis_prepare, once: four powers, off the hot path)
      real(dp) :: input_limit = 0.0_dp
      !> During the build only (emptied at its end; in no format): GW's ZMC loading law
      !> tabulated once (zmc_law_pieces) for every curve's unloading solves (EP-GW, psi > 0)
      type(law_pieces) :: loading_law
   end type hysteresis_table

   !> One turning point's unloading curve (turning_point): what its span force needs.
   type :: unload_curve
      real(dp) :: m = 0.0_dp               !< the turning point
      !> Lagrange weights of its stencil's window (table%n_w of them; 0 beyond)
      real(dp) :: w(max_stencil) = 0.0_dp
      real(dp) :: inv_span = 0.0_dp        !< 1/(s_max L(m))
      real(dp) :: f_m = 0.0_dp             !< P_load(m)
      integer :: first = 1                 !< the stencil's first curve
      real(dp) :: knee = 0.0_dp            !< its knee (mapped tables; turning_knee)
   end type unload_curve

   !> The largest ln(P_load/P) a log-ratio curve stores (e^-100 ~ 4e-44: far below every
   !> tolerance, far above subnormals): where the unloading force has vanished or
   !> underflowed.
   real(dp), parameter :: max_log_ratio = 100.0_dp

   !> A quiet NaN (ieee_value's bits, 0x7FF8000000000000) as a constant: the states' "no
   !> piece" mark, written on the DEM hot path, where ieee_value is a library call
   real(dp), parameter, public :: quiet_nan = transfer(9221120237041090560_int64, 1.0_dp)

contains

   !> egw_invalid_argument for a NaN overlap delta or a NaN history (called name; a new
   !> contact starts from fresh, the way to start one).
   pure subroutine nan_error(delta, name, fresh, error)
      real(dp), intent(in) :: delta   !< the overlap given (named in the message if NaN)
      character(len=*), intent(in) :: name    !< the history argument's name, for the message
      character(len=*), intent(in) :: fresh   !< the fresh-contact value, for the message
      type(egw_error), allocatable, intent(out) :: error   !< egw_invalid_argument, always
      if (ieee_is_nan(delta)) then
         call fatal_error(error, egw_invalid_argument, "delta = NaN: must be a number")
      else
         call fatal_error(error, egw_invalid_argument, name//" = NaN: a new contact starts "// &
            & "from "//fresh)
      end if
   end subroutine nan_error

   !> g and dg/ds of the cubic c in t = (s - s_i)/(s_{i+1} - s_i) (inv_ds = the 1/width);
   !> Estrin's scheme: shorter dependency chains than Horner.
   pure subroutine gap_cubic(c, t, inv_ds, g, dg)
      real(dp), intent(in) :: c(4)     !< the cubic's coefficients in t (coef's layout)
      real(dp), intent(in) :: t        !< (s - s_i)/(s_{i+1} - s_i), in [0, 1] on the interval
      real(dp), intent(in) :: inv_ds   !< 1/(s_{i+1} - s_i)
      real(dp), intent(out) :: g       !< the cubic's value at t (g; h in log-ratio tables)
      real(dp), intent(out) :: dg      !< its derivative in s
      real(dp) :: t2
      t2 = t*t
      g = (c(1) + t*c(2)) + t2*(c(3) + t*c(4))
      dg = ((c(2) + 2*t*c(3)) + 3*t2*c(4))*inv_ds
   end subroutine gap_cubic

   !> What the unloading branch needs of the turning point m: the Lagrange stencil of the
   !> m interval (clamped at the ends of the grid; the last curve above the table): the
   !> first node of its window (stencil_window) and the weights of the window's table%n_w
   !> nodes (0 beyond them, and at window nodes outside the stencil), 1/(s_max L)
   !> interpolated with them and the loading force P_load(m). seg
   !> (optional): an interval of the loading table (table_segment's layout, e.g. a state's
   !> copy from its last loading step); where it holds m above the resampled tail, P_load(m)
   !> comes from it without the table's lookup (eval_kernel's arithmetic: the same value).
   pure subroutine turning_point(table, m, first, w, inv_span, f_m, knee, seg)
      type(hysteresis_table), intent(in) :: table   !< the table (prepared)
      !> the turning point delta_max (above the table's last node: its last curve)
      real(dp), intent(in) :: m
      integer, intent(out) :: first    !< the first delta_max node of the stencil's window
      !> Lagrange weights of the window's table%n_w nodes (0 beyond)
      real(dp), intent(out) :: w(max_stencil)
      !> 1/(s_max L(m)) (log-ratio tables: 1/L, above the table stretched; mapped: the
      !> first piece's ds/dx, map_iota)
      real(dp), intent(out) :: inv_span
      real(dp), intent(out) :: f_m     !< the loading force P_load(m)
      real(dp), intent(out) :: knee   !< the map's knee (turning_knee; 0 unless mapped)
      !> an interval of the loading table (table_segment's layout): P_load(m) from it
      !> where it holds m
      real(dp), intent(in), optional :: seg(7)
      real(dp) :: d(max_stencil), k_m, lead(max_stencil), trail
      integer :: j, n_m, k, lo, hi
      logical :: held
      held = .false.
      if (present(seg)) held = seg(1) <= m .and. m < seg(2) .and. &
         & m > table%loading%cutoff .and. m >= table%loading%tail_end .and. &
         & seg(2) <= table%loading%delta_max
      if (held) then
         call segment_eval(seg, m, f_m, k_m)
      else
         call table_eval(table%loading, m, f_m, k_m)
      end if
      n_m = size(table%m)
      j = locate(table%m_lookup, table%m, min(m, table%delta_max))
      w = 0.0_dp
      if (table%n_w == 4) then
         first = stencil_first(j, n_m, table%m_break)
         d(1:4) = m_coordinate(m, table%m_break) - table%m_coord(first:first + 3)
         w(1) = d(2)*d(3)*d(4)*table%lagrange(1, j)
         w(2) = d(1)*d(3)*d(4)*table%lagrange(2, j)
         w(3) = d(1)*d(2)*d(4)*table%lagrange(3, j)
         w(4) = d(1)*d(2)*d(3)*table%lagrange(4, j)
         if (m > table%delta_max) w(1:4) = [0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp]
         ! 1/(s_max L) interpolated (no division on the hot path; smooth and > 0 as L)
         inv_span = w(1)*table%inv_span(first) + w(2)*table%inv_span(first + 1) + &
            & w(3)*table%inv_span(first + 2) + w(4)*table%inv_span(first + 3)
      else
         ! the window's nodes: prod_{l /= k} (x - x_l) from products before and after k,
         ! a node outside the stencil (lagrange 0) counted as 1
         call stencil_window(j, n_m, table%m_break, table%n_w, first, lo, hi)
         d(1:table%n_w) = m_coordinate(m, table%m_break) - &
            & table%m_coord(first:first + table%n_w - 1)
         where (table%lagrange(1:table%n_w, j) == 0.0_dp) d(1:table%n_w) = 1.0_dp
         lead(1) = 1.0_dp
         do k = 2, table%n_w
            lead(k) = lead(k - 1)*d(k - 1)
         end do
         trail = 1.0_dp
         do k = table%n_w, 1, -1
            w(k) = lead(k)*trail*table%lagrange(k, j)
            trail = trail*d(k)
         end do
         if (m > table%delta_max) then
            w = 0.0_dp
            w(table%n_w) = 1.0_dp
         end if
         inv_span = stencil_sum(table%n_w, w, table%inv_span(first:first + table%n_w - 1))
      end if
      if (table%force_ratio) inv_span = fine_inv_span(table, m)
      if (.not. inv_span > 0.0_dp) inv_span = table%inv_span(j)
      ! above the table a log-ratio table's last curve is stretched to span m - delta_max
      ! more, so that its residual end stays where the last curve's is: s of (m - delta)
      ! at the last curve's span would reach s = 1 (h = ln(P_load/P) at its largest, P ~ 0)
      ! at m - L, a drop of the force to 0 within a few sigma, ~100 times the loading
      ! stiffness, where egw_solve_unload's force stays within 1e-4 of P_load (EP-GW,
      ! mu 2, psi 1, m = 420 sigma, L = 140 sigma: doc/benchmarks.md "Stop 48 (gain14)")
      if (table%log_ratio .and. m > table%delta_max) &
         & inv_span = 1.0_dp/(1.0_dp/inv_span + (m - table%delta_max))
      knee = 0.0_dp
      if (table%mapped) then
         ! the first piece's 1/span from the interpolated knee, so that the pieces meet
         knee = turning_knee(table, first, w, m)
         inv_span = map_iota(table, m, knee)
      end if
   end subroutine turning_point

   !> 1/L at the turning point m of a force_ratio table: cubic Lagrange on the four fine
   !> nodes around m's fine interval (clamped at the grid's ends; at and above delta_max
   !> the last node's).
   pure real(dp) function fine_inv_span(table, m) result(inv)
      type(hysteresis_table), intent(in) :: table   !< a force_ratio table (prepared)
      real(dp), intent(in) :: m        !< the turning point
      real(dp) :: d(4)
      integer :: n_f, first
      n_f = size(table%fine_m)
      if (m >= table%delta_max) then
         inv = table%fine_inv(n_f)
         return
      end if
      first = min(max(locate(table%fine_lookup, table%fine_m, m) - 1, 1), n_f - 3)
      d = m - table%fine_m(first:first + 3)
      associate (w => table%fine_lagrange(:, first))
         inv = d(2)*d(3)*d(4)*w(1)*table%fine_inv(first) + &
            & d(1)*d(3)*d(4)*w(2)*table%fine_inv(first + 1) + &
            & d(1)*d(2)*d(4)*w(3)*table%fine_inv(first + 2) + &
            & d(1)*d(2)*d(3)*w(4)*table%fine_inv(first + 3)
      end associate
   end function fine_inv_span

   !> The knee of turning point m (stencil first, weights w) of a mapped table: the
   !> nodes' knees interpolated over the stencil's table%n_w nodes, kept in [0, 0.99 m]
   !> (0 <= delta_r < m: the clamp only catches the interpolation's overshoot near first
   !> yield); 0 unless mapped.
   pure real(dp) function turning_knee(table, first, w, m) result(knee)
      type(hysteresis_table), intent(in) :: table   !< the table (its knee(:) where mapped)
      integer, intent(in) :: first     !< the stencil's first delta_max node (turning_point)
      real(dp), intent(in) :: w(max_stencil)   !< the stencil's Lagrange weights (turning_point)
      real(dp), intent(in) :: m        !< the turning point delta_max
      knee = 0.0_dp
      if (.not. (table%mapped .and. m > 0.0_dp)) return
      if (table%n_w == 4) then
         knee = w(1)*table%knee(first) + w(2)*table%knee(first + 1) + &
            & w(3)*table%knee(first + 2) + w(4)*table%knee(first + 3)
      else   ! today's mapped tables have 4-node windows; a wider one sums all its nodes
         knee = stencil_sum(table%n_w, w, table%knee(first:first + table%n_w - 1))
      end if
      knee = min(max(knee, 0.0_dp), 0.99_dp*m)
   end function turning_knee

   !> The piece (1, 2, 3) of the two-piece map that holds s (an interval's midpoint:
   !> the breaks are nodes); 1 unless mapped.
   elemental integer function map_piece(mapped, s) result(p)
      logical, intent(in) :: mapped    !< whether the table has the two-piece map (table%mapped)
      real(dp), intent(in) :: s        !< the unloading coordinate, in [0, 1]
      p = 1
      if (.not. mapped) return
      if (s > s_knee) p = 2
      if (s > s_zero) p = 3
   end function map_piece

   !> s and ds/dx at x = m - delta >= 0 on the curve of turning point m (knee, iota: the
   !> first piece's ds/dx): x iota unless mapped; mapped, linear through (0, 0),
   !> (m - knee, s_knee), (m, s_zero) and on at slope (1 - s_zero)/tail_length (not
   !> clamped: the callers clamp at 1).
   pure subroutine map_s(table, m, knee, iota, x, s, dsdx)
      type(hysteresis_table), intent(in) :: table   !< the table (mapped, tail_length)
      real(dp), intent(in) :: m        !< the turning point delta_max
      real(dp), intent(in) :: knee     !< its knee delta_r(m) (turning_knee; mapped)
      real(dp), intent(in) :: iota     !< the first piece's ds/dx (turning_point's inv_span)
      real(dp), intent(in) :: x        !< m - delta, >= 0
      real(dp), intent(out) :: s       !< the unloading coordinate at x (not clamped at 1)
      real(dp), intent(out) :: dsdx    !< ds/dx of the piece that holds x
      if (table%mapped .and. .not. m > 0.0_dp) then
         ! a turning point at or below 0: the first two pieces are the point x = 0
         dsdx = (1.0_dp - s_zero)/table%tail_length
         s = s_zero + x*dsdx
         return
      end if
      dsdx = iota
      s = x*iota
      if (.not. table%mapped .or. .not. s > s_knee) return
      if (x <= m) then   ! (knee > 0 here: with knee = 0, x <= m is s <= s_knee)
         dsdx = (s_zero - s_knee)/knee
         s = s_knee + (x - (m - knee))*dsdx
      else
         dsdx = (1.0_dp - s_zero)/table%tail_length
         s = s_zero + (x - m)*dsdx
      end if
   end subroutine map_s

   !> x = m - delta at s on the curve of turning point m (map_s's inverse), and ds/dx of
   !> the piece that holds s (at a break: the piece below it in s).
   pure subroutine map_x(table, m, knee, iota, s, x, dsdx)
      type(hysteresis_table), intent(in) :: table   !< the table (mapped, tail_length)
      real(dp), intent(in) :: m        !< the turning point delta_max
      real(dp), intent(in) :: knee     !< its knee delta_r(m) (turning_knee; mapped)
      real(dp), intent(in) :: iota     !< the first piece's ds/dx (turning_point's inv_span)
      real(dp), intent(in) :: s        !< the unloading coordinate, >= 0
      real(dp), intent(out) :: x       !< m - delta at s
      !> ds/dx of the piece that holds s (huge for a piece of no width)
      real(dp), intent(out) :: dsdx
      if (table%mapped .and. .not. m > 0.0_dp) then   ! (map_s)
         dsdx = (1.0_dp - s_zero)/table%tail_length
         x = max(s - s_zero, 0.0_dp)/dsdx
         if (s <= s_zero) dsdx = huge(1.0_dp)   ! (a piece of no width)
         return
      end if
      dsdx = iota
      x = s*(1.0_dp/iota)   ! (the linear map's span 1/iota, as a state holds it)
      if (.not. table%mapped .or. s <= s_knee) return
      if (s <= s_zero) then
         dsdx = (s_zero - s_knee)/max(knee, tiny(1.0_dp))   ! (knee 0: a piece of no width)
         x = (m - knee) + knee*(s - s_knee)/(s_zero - s_knee)
      else
         dsdx = (1.0_dp - s_zero)/table%tail_length
         x = m + table%tail_length*(s - s_zero)/(1.0_dp - s_zero)
      end if
   end subroutine map_x

   !> ds/dx of the first piece of the two-piece map of turning point m with its knee:
   !> s_knee/(m - knee); at or below 0 (no first piece) the tail's, (1 - s_zero)/tail_length.
   pure real(dp) function map_iota(table, m, knee) result(iota)
      type(hysteresis_table), intent(in) :: table   !< the table (its tail_length)
      real(dp), intent(in) :: m        !< the turning point delta_max
      real(dp), intent(in) :: knee     !< its knee delta_r(m), 0 <= knee < m where m > 0
      iota = (1.0_dp - s_zero)/table%tail_length
      if (m > 0.0_dp) iota = s_knee/(m - knee)
   end function map_iota

   !> dx/ds of the three pieces of the two-piece map of turning point m with its knee (0
   !> for a piece of no width).
   pure function map_lengths(table, m, knee) result(dxds)
      type(hysteresis_table), intent(in) :: table   !< the table (its tail_length)
      real(dp), intent(in) :: m        !< the turning point delta_max
      real(dp), intent(in) :: knee     !< its knee delta_r(m), 0 <= knee < m where m > 0
      real(dp) :: dxds(3)
      dxds = [0.0_dp, 0.0_dp, table%tail_length/(1.0_dp - s_zero)]
      if (m > 0.0_dp) dxds(1:2) = [(m - knee)/s_knee, knee/(s_zero - s_knee)]
   end function map_lengths

   !> The gap cubic g(t) of the turning point (stencil first, weights w) on s interval i:
   !> the window's curves' cubics (16 or 24 contiguous numbers) combined.
   pure subroutine gap_combination(table, first, w, i, c)
      type(hysteresis_table), intent(in) :: table   !< the table (prepared: coef, n_w)
      integer, intent(in) :: first     !< the stencil's first delta_max node (turning_point)
      integer, intent(in) :: i         !< the s interval, 1 .. n_s - 1
      real(dp), intent(in) :: w(max_stencil)   !< the stencil's Lagrange weights (turning_point)
      !> the combined cubic in t on interval i (of g; of h in log-ratio tables)
      real(dp), intent(out) :: c(4)
      if (table%n_w == 4) then
         associate (cf => table%coef(:, first:first + 3, i))
            c(1) = w(1)*cf(1, 1) + w(2)*cf(1, 2) + w(3)*cf(1, 3) + w(4)*cf(1, 4)
            c(2) = w(1)*cf(2, 1) + w(2)*cf(2, 2) + w(3)*cf(2, 3) + w(4)*cf(2, 4)
            c(3) = w(1)*cf(3, 1) + w(2)*cf(3, 2) + w(3)*cf(3, 3) + w(4)*cf(3, 4)
            c(4) = w(1)*cf(4, 1) + w(2)*cf(4, 2) + w(3)*cf(4, 3) + w(4)*cf(4, 4)
         end associate
      else
         associate (cf => table%coef(:, first:first + 5, i))
            c = ((w(1)*cf(:, 1) + w(2)*cf(:, 2)) + (w(3)*cf(:, 3) + w(4)*cf(:, 4))) + &
               & (w(5)*cf(:, 5) + w(6)*cf(:, 6))
         end associate
      end if
   end subroutine gap_combination

   !> sum_k w(k) x(k) over a stencil's window of n_w (4 or 6) nodes (dot_product's for 4).
   pure real(dp) function stencil_sum(n_w, w, x) result(v)
      integer, intent(in) :: n_w       !< nodes of the window, 4 or 6
      real(dp), intent(in) :: w(max_stencil)   !< the weights (the first n_w are used)
      real(dp), intent(in) :: x(:)     !< the values at the window's nodes (at least n_w)
      if (n_w == 4) then
         v = dot_product(w(1:4), x(1:4))
      else
         v = ((w(1)*x(1) + w(2)*x(2)) + (w(3)*x(3) + w(4)*x(4))) + (w(5)*x(5) + w(6)*x(6))
      end if
   end function stencil_sum

   !> The unloading force over the loading force at the end d_1 of a curve's span, where
   !> its gap is g_1 (P_load(m) = f_m), in [0, 1]: below d_1 the unloading force is that
   !> ratio of the loading tail (continuous at d_1 where the force there is positive).
   pure real(dp) function unload_tail_ratio(table, d_1, f_m, g_1) result(ratio)
      type(hysteresis_table), intent(in) :: table   !< the table (its loading curve; capped: 0)
      real(dp), intent(in) :: d_1      !< the overlap at the end of the curve's span (s = 1)
      real(dp), intent(in) :: f_m      !< the loading force P_load(m) at the turning point
      !> the gap g at s = 1 (a table that stores_ratio: u there)
      real(dp), intent(in) :: g_1
      real(dp) :: f_1, k_1
      ratio = 0.0_dp
      if (table%capped) return   ! below the residual overlap: apart
      call table_eval(table%loading, d_1, f_1, k_1)
      if (.not. f_1 > 0.0_dp) return
      if (stores_ratio(table)) then   ! (u on the two-piece map: P = f_m u there)
         ratio = min(max(f_m*g_1/f_1, 0.0_dp), 1.0_dp)
      else
         ratio = min(max(1.0_dp - f_m*g_1/f_1, 0.0_dp), 1.0_dp)
      end if
   end function unload_tail_ratio

   !> Whether the table's curves store the unloading force u = P/P_load(m) rather than
   !> the gap: a Hertz + cap table's (force_ratio, format 5) or a rough + cap table's on
   !> the two-piece map (ratio_on_map, format 6). P = P_load(m) u(s, m) then, with no
   !> loading force below the turning point.
   elemental logical function stores_ratio(table)
      type(hysteresis_table), intent(in) :: table   !< built or read
      stores_ratio = table%force_ratio .or. (table%mapped .and. table%ratio_on_map)
   end function stores_ratio

   !> The overlap at and below which an unloading curve has no force: the loading table's
   !> cut-off (the gap and log-ratio curves need the loading force); -huge for force_ratio
   !> tables, whose force f_m u(s) needs none (their curves end at s = 1, the residual
   !> overlap, which lies below the cut-off for turning points within ~1 % of first yield:
   !> 7e-4 P(m) was dropped there at 1e-3, doc/stability.md stop 50).
   elemental real(dp) function unload_floor(table) result(floor)
      type(hysteresis_table), intent(in) :: table   !< the table (its loading cut-off)
      floor = table%loading%cutoff
      if (table%force_ratio) floor = -huge(1.0_dp)
   end function unload_floor

   !> Uniform buckets over the grid x, their width at most 3/4 of its finest interval,
   !> capped at 2**max_bucket_level.
   pure subroutine make_lookup(x, lookup)
      real(dp), intent(in) :: x(:)     !< the grid, strictly increasing, at least 2 nodes
      type(grid_lookup), intent(out) :: lookup   !< its buckets (locate)
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
      real(dp), intent(in) :: m(:)     !< the delta_max nodes, increasing
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
      real(dp), intent(in) :: m        !< a delta_max (node or turning point)
      integer, intent(in) :: k_b       !< the breakpoint node (m_breakpoint; 0: none)
      x = m
      if (k_b > 0 .and. m > 0.0_dp) x = sqrt(m)
   end function m_coordinate

   !> The first of the four delta_max nodes of the Lagrange stencil of interval j (m_j <=
   !> m < m_{j+1}) of n_m nodes: centred, clamped at the grid's ends and, with a breakpoint
   !> node k_b (m_breakpoint), on interval j's side of it (the cubic does not straddle the
   !> onset of the Hertz part).
   pure integer function stencil_first(j, n_m, k_b) result(first)
      integer, intent(in) :: j         !< the delta_max interval, 1 .. n_m - 1
      integer, intent(in) :: n_m       !< delta_max nodes of the grid, >= 4
      integer, intent(in) :: k_b       !< the breakpoint node (m_breakpoint; 0: none)
      first = min(max(j - 1, 1), n_m - 3)
      if (k_b > 0) then
         if (j < k_b) then
            first = min(first, k_b - 3)
         else
            first = max(first, k_b)
         end if
      end if
   end function stencil_first

   !> Nodes of the window of every Lagrange stencil of a table (its curves store log_ratio;
   !> n_m delta_max nodes): six for log-ratio tables of six or more nodes (their curves'
   !> error in delta_max is the force's relative error down to 1e-3 of the turning point's:
   !> four nodes needed 109 on egw-bench's range at 1e-4, six 71; doc/benchmarks.md stop
   !> 46), four else.
   pure integer function stencil_width(log_ratio, n_m) result(n_w)
      logical, intent(in) :: log_ratio   !< the curves store h = ln(P_load/P) (table%log_ratio)
      integer, intent(in) :: n_m       !< delta_max nodes of the grid
      n_w = 4
      if (log_ratio .and. n_m >= 6) n_w = 6
   end function stencil_width

   !> The window of n_w (4 or 6, at most n_m) nodes first .. first + n_w - 1 of the Lagrange
   !> stencil of interval j and the stencil's nodes in it, window positions lo .. hi: with
   !> n_w = 4 stencil_first's four; with 6 the six nodes around the interval (j - 2 ..
   !> j + 3, clamped at the grid's ends) on its side of a breakpoint k_b, or where that
   !> side has fewer than six nodes, stencil_first's four inside a window of six.
   pure subroutine stencil_window(j, n_m, k_b, n_w, first, lo, hi)
      integer, intent(in) :: j         !< the delta_max interval, 1 .. n_m - 1
      integer, intent(in) :: n_m       !< delta_max nodes of the grid, >= n_w
      integer, intent(in) :: k_b       !< the breakpoint node (m_breakpoint; 0: none)
      integer, intent(in) :: n_w       !< nodes of the window, 4 or 6 (stencil_width)
      integer, intent(out) :: first    !< the window's first delta_max node
      integer, intent(out) :: lo       !< the stencil's first position in the window
      integer, intent(out) :: hi       !< the stencil's last position in the window
      integer :: k
      first = stencil_first(j, n_m, k_b)
      lo = 1
      hi = 4
      if (n_w == 4) return
      k = min(max(j - 2, 1), n_m - 5)
      if (k_b > 0) then
         if (j < k_b) then
            k = min(k, k_b - 5)
         else
            k = max(k, k_b)
         end if
      end if
      if (k >= 1 .and. k + 5 <= n_m) then
         first = k
         hi = 6
      else
         k = min(max(first - 1, 1), n_m - 5)
         lo = first - k + 1
         hi = lo + 3
         first = k
      end if
   end subroutine stencil_window

   !> The edge map of a log-ratio curve of unloading length L (roughness sigma): the
   !> values xi(1:3) of m - delta at s = 1/2, 3/4 and 1. For a deep turning point (L >> sigma)
   !> the residual-overlap edge, where the unloading force vanishes within a rounding ~sigma
   !> wide, lies at xi ~ L: s in [1/2, 3/4] spans L - 1.5 sigma .. L + 4 sigma there
   !> whatever m, so the edge sits at a fixed s at a fixed width (the curves' shared s
   !> nodes resolve it for every m); [3/4, 1] the 12 sigma of the separated tail beyond.
   !> A shallow one (L <~ sigma, the separated tail) gets L .. 5 L and 12 sigma more.
   !> xi(1) >= L/4 > 0.
   pure subroutine edge_breaks(length, sigma, xi)
      !> above this length the breaks are formed scaled by it (length**2 stays finite below)
      real(dp), parameter :: huge_length = 1.0e150_dp
      real(dp), intent(in) :: length   !< the curve's unloading length L (> 0)
      real(dp), intent(in) :: sigma    !< the summit heights' standard deviation (unit of L)
      real(dp), intent(out) :: xi(3)   !< m - delta at s = 1/2, 3/4, 1, increasing
      if (length < huge_length) then
         xi(1) = length - 1.5_dp*sigma*length**2/(length**2 + sigma**2)
         xi(2) = length + 4.0_dp*sigma*length/(length + sigma)
      else
         ! a last curve stretched far above the table (turning_point): length**2 and
         ! sigma length would overflow; the same breaks scaled by length
         xi(1) = length - 1.5_dp*sigma/(1.0_dp + (sigma/length)**2)
         xi(2) = length + 4.0_dp*sigma/(1.0_dp + sigma/length)
      end if
      xi(3) = xi(2) + 12.0_dp*sigma
   end subroutine edge_breaks

   !> The segment (1, 2, 3) of the edge map that holds the s interval [a, b] (its breaks
   !> 1/2, 3/4 are s nodes of every curve: no interval straddles one).
   elemental integer function edge_segment(a, b) result(k)
      real(dp), intent(in) :: a        !< the interval's lower end in s
      real(dp), intent(in) :: b        !< its upper end in s
      real(dp) :: c
      c = 0.5_dp*(a + b)
      k = 3
      if (c < 0.75_dp) k = 2
      if (c < 0.5_dp) k = 1
   end function edge_segment

   !> s of xi = m - delta on the edge map xi (edge_breaks), not clamped (> 1 beyond the
   !> span), and ds/dxi there.
   pure subroutine edge_s(xi_b, x, s, ds)
      real(dp), intent(in) :: xi_b(3)  !< the edge map's breaks (edge_breaks)
      real(dp), intent(in) :: x        !< xi = m - delta, >= 0
      real(dp), intent(out) :: s       !< the unloading coordinate (not clamped at 1)
      real(dp), intent(out) :: ds      !< ds/dxi of the segment that holds x
      if (x <= xi_b(1)) then
         ds = 0.5_dp/xi_b(1)
         s = x*ds
      else if (x <= xi_b(2)) then
         ds = 0.25_dp/(xi_b(2) - xi_b(1))
         s = 0.5_dp + (x - xi_b(1))*ds
      else if (xi_b(3) > xi_b(2)) then
         ds = 0.25_dp/(xi_b(3) - xi_b(2))
         s = 0.75_dp + (x - xi_b(2))*ds
      else
         ! breaks that rounding merged (a last curve stretched to L with ulp(L) > 12 sigma,
         ! turning_point): x > xi_b(2) = xi_b(3) is beyond the span, where s is held at 1
         ! (log_branch); 0.25/0 would make ds infinite and the stiffness 0*Inf = NaN
         ds = 0.0_dp
         s = 1.0_dp
      end if
   end subroutine edge_s

   !> xi = m - delta at s in [0, 1] on the edge map xi_b (edge_s inverted), and dxi/ds on
   !> segment k (1..3).
   pure subroutine edge_xi(xi_b, s, x, dxi, k)
      real(dp), intent(in) :: xi_b(3)  !< the edge map's breaks (edge_breaks)
      real(dp), intent(in) :: s        !< the unloading coordinate, in [0, 1]
      real(dp), intent(out) :: x       !< xi = m - delta at s
      real(dp), intent(out), optional :: dxi   !< dxi/ds on segment k (set only with k)
      integer, intent(in), optional :: k       !< the segment (1..3, edge_segment) for dxi
      real(dp) :: d(3)
      d = [2*xi_b(1), 4*(xi_b(2) - xi_b(1)), 4*(xi_b(3) - xi_b(2))]
      if (s <= 0.5_dp) then
         x = s*d(1)
      else if (s <= 0.75_dp) then
         x = xi_b(1) + (s - 0.5_dp)*d(2)
      else
         x = xi_b(2) + (s - 0.75_dp)*d(3)
      end if
      if (present(dxi) .and. present(k)) dxi = d(k)
   end subroutine edge_xi

   !> The force and stiffness at delta (cut-off < delta < m) of a log-ratio table below
   !> the turning point m from the cubic c of h = ln(P_load/P) on s interval i, at s (not
   !> clamped: above 1 h is held at its value at s = 1, as the gap's tail ratio), ds/dxi
   !> = ds: P = P_load(delta) e^-h, dP/ddelta = e^-h (K_load + P_load dh/ds ds/dxi).
   pure subroutine log_branch(table, c, i, s, ds, delta, force, stiffness)
      type(hysteresis_table), intent(in) :: table   !< a log-ratio table (loading curve, s grid)
      real(dp), intent(in) :: c(4)     !< the cubic of h on interval i (gap_combination)
      real(dp), intent(in) :: s        !< the unloading coordinate (>= 1: h held at s = 1)
      real(dp), intent(in) :: ds       !< ds/dxi at delta (edge_s)
      real(dp), intent(in) :: delta    !< the overlap, cut-off < delta < m
      integer, intent(in) :: i         !< the s interval that holds s, 1 .. n_s - 1
      real(dp), intent(out) :: force   !< the unloading force P
      real(dp), intent(out) :: stiffness   !< dP/ddelta
      real(dp) :: h, dh, f_d, k_d, e
      call table_eval(table%loading, delta, f_d, k_d)
      if (s >= 1.0_dp) then
         h = ((c(1) + c(2)) + (c(3) + c(4)))
         dh = 0.0_dp
      else
         call gap_cubic(c, (s - table%s(i))*table%inv_ds(i), table%inv_ds(i), h, dh)
      end if
      e = exp(-h)
      force = f_d*e
      stiffness = e*(k_d + f_d*dh*ds)
   end subroutine log_branch

   !> The unloading force and stiffness at delta (cut-off < delta < m) of a log-ratio
   !> table below the turning point m (stencil first, weights w, interpolated unloading
   !> length L = length): s on the edge map of L, its interval's cubic, log_branch.
   pure subroutine log_unload(table, first, w, length, m, delta, force, stiffness)
      type(hysteresis_table), intent(in) :: table   !< the table (log-ratio, prepared)
      integer, intent(in) :: first     !< the stencil's first delta_max node (turning_point)
      real(dp), intent(in) :: w(max_stencil)   !< the stencil's Lagrange weights (turning_point)
      real(dp), intent(in) :: length   !< the interpolated unloading length L (1/inv_span)
      real(dp), intent(in) :: m        !< the turning point delta_max
      real(dp), intent(in) :: delta    !< the overlap, cut-off < delta < m
      real(dp), intent(out) :: force   !< the unloading force P
      real(dp), intent(out) :: stiffness   !< dP/ddelta
      real(dp) :: xi_b(3), s, ds, c(4)
      integer :: i
      call edge_breaks(length, table%params%sigma, xi_b)
      call edge_s(xi_b, m - delta, s, ds)
      s = min(s, 1.0_dp)
      i = locate(table%s_lookup, table%s, s)
      call gap_combination(table, first, w, i, c)
      call log_branch(table, c, i, s, ds, delta, force, stiffness)
   end subroutine log_unload

   !> i with x(i) <= v < x(i+1), clamped to [1, n-1]: the bucket's interval, then a short
   !> forward scan (at most one step where the buckets are as fine as the grid).
   pure integer function locate(lookup, x, v) result(i)
      type(grid_lookup), intent(in) :: lookup   !< the buckets of x (make_lookup)
      real(dp), intent(in) :: x(:)     !< the grid, strictly increasing, at least 2 nodes
      real(dp), intent(in) :: v        !< the value to locate (outside the grid: clamped)
      integer :: b, n
      n = size(x)
      b = min(max(int((v - lookup%origin)*lookup%scale), 0), lookup%n_bucket)
      i = lookup%bucket(b)
      do while (i < n - 1)
         if (x(i + 1) > v) exit
         i = i + 1
      end do
   end function locate

end module egw_hysteresis_data
