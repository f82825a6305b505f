!> Force tables of one parameter set for DEM and FE codes: force, stiffness, elastic
!> energy and contact radius against overlap delta, built from full solves with nodes
!> placed adaptively, and evaluated at about the cost of the Hertz closed form.
!>
!> Interpolation: cubic Hermite in delta with the solver's exact stiffness as the
!> derivative (C1, exact at the nodes; table_eval's resampled tail, force_table%fine_seg,
!> within 5e-2 rel_tol there). In the separated tail (delta <= 0 for rough
!> models, where P decays like a Gaussian in delta/sigma) the cubic interpolates ln P with
!> derivative K/P, so the relative error stays bounded however small P gets. The nodes
!> reach down to the cut-off delta_c, where P has fallen to tail_floor * P_ref for rough
!> models (1e-12: every force above 1e-12 of P_ref is interpolated to rel_tol; P_ref is
!> the force at delta = min(0, delta_max), the first contact of the mean planes) and to
!> rel_tol * P_ref at delta_max for Hertz. Below delta_c a rough table gives exactly 0
!> (its force there is below 1e-12 P_ref: the jump at delta_c is that small; doc/theory.md
!> §9), a Hertz table Hertz's closed form, a flat-law table an exponential continuation;
!> above delta_max the deep-overlap asymptote (deep_force: Hertz's force on the overlap
!> the rough layer leaves), C1 there.
!>
!> Error control: the force at the midpoint of every interval against a solve. For
!> smooth spheres the stiffness is checked too (10 rel_tol), because P ~ delta^(3/2)
!> near the cut-off hides its sqrt(delta) stiffness from the force check. For rough
!> models the stiffness is the Hermite slope and is checked only on the interval
!> starting at delta = 0 (a node), to max(10 rel_tol, 1e-4) while it is wider than
!> 1e-6 sigma (max_stiffness_error records
!> it at the check points): P(0) > 0 there, so the delta^(3/2) onset is seen by the force
!> check, while the solver's stiffness just above 0 is not consistent with its force to
!> better than ~1e-4 (the bulk contact patch is far below the mesh), which drove builds
!> with the 10 rel_tol check below rel_tol ~ 5e-6 into the node limit.
module egw_table
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan, ieee_value, &
      & ieee_quiet_nan
   use egw_kinds, only: dp
   use egw_search, only: bracket_interval
   use egw_status, only: egw_error, egw_invalid_argument, egw_not_converged, &
      & egw_out_of_range, fatal_error, format_real, int_str, tolerance_context
   use egw_params, only: contact_params, validate_params, model_hertz, model_gw, model_egw, &
      & model_epgw, model_flat_law, check_scaled_overlap, refuse_flow_pressure, is_rough
   use egw_rough_sphere, only: solver_options, solve_result, solve_contact, solve_contact_law
   use egw_flat_law, only: flat_law
   use egw_law_pieces, only: law_pieces
   use egw_smooth_sphere, only: hertz_force, hertz_stiffness
   use egw_table_ends, only: tail_force, deep_law, deep_law_fit, deep_law_force, &
      & deep_law_energy, deep_law_radius_factor
   use egw_table_tail, only: tail_last_node, resample_tails, tail_resample_tol, min_fine
   implicit none
   private

   public :: build_table, build_table_law, build_table_fixed_cutoff, build_tables_shared, &
      & table_interval, &
      & table_eval, table_eval_tail_law, table_eval_cached, table_segment, segment_eval, &
      & table_eval_log, table_eval_all, &
      & table_covers, table_energy, &
      & table_contact_radius, table_set_radii, table_prepare, table_is_ready, table_find_cutoff, &
      & deep_coefficient, deep_law_floor, deep_law_floor_x
   public :: below_cutoff, beyond_status
   public :: table_meta, set_table_meta

   public :: table_progress

   abstract interface
      !> Progress hook of the table builds, called from the serial part of a build (never
      !> inside an OpenMP region, so it need not be thread-safe) after every batch of
      !> solves: done = solves finished so far, total = done + solves known to be pending.
      !> The total grows as adaptive refinement splits intervals; done never decreases
      !> within one build, 0 <= done <= total, and the last call has done == total.
      subroutine table_progress(done, total)
         integer, intent(in) :: done, total
      end subroutine table_progress
   end interface

   !> Hard limits of the adaptive build (a table that needs more is not converging:
   !> the solver's noise is above rel_tol).
   integer, parameter :: max_nodes = 20000, max_rounds = 200
   !> Most lookup buckets of a table (table_prepare): 64 kB.
   integer, parameter :: max_buckets = 16384
   !> Rough models: the nodes reach down to where P = tail_floor * P_ref (the force at the
   !> first contact of the mean planes), so that every force above 1e-12 of P(delta_max)
   !> is interpolated to rel_tol; below, 0.
   real(dp), parameter, public :: tail_floor = 1.0e-12_dp

   !> One-parameter-set force table. Arrays are the nodes (delta ascending); the
   !> evaluation data (seg, bucket) are derived from them by table_prepare.
   type, public :: force_table
      type(contact_params) :: params              !< parameters the table was built for
      real(dp) :: rel_tol = 0.0_dp                !< requested interpolation tolerance
      real(dp) :: cutoff = 0.0_dp                 !< delta_c: first node (rough: 0 below)
      real(dp) :: delta_max = 0.0_dp              !< last node
      real(dp) :: reference_force = 0.0_dp        !< P_ref of the cut-off rule
      real(dp) :: max_force_error = 0.0_dp        !< max |P_table/P_solve - 1| at check points
      real(dp) :: max_stiffness_error = 0.0_dp    !< same for the stiffness (not enforced)
      real(dp) :: radius_sum = 0.0_dp             !< R1 + R2 if known, 0 otherwise
      integer :: n_log = 0                        !< intervals 1..n_log interpolate ln P
      !> read from a CSV file without its checksum line (hand-edited?): only the sanity
      !> checks of the reader vouch for its numbers
      logical :: checksum_missing = .false.
      real(dp), allocatable :: delta(:)           !< overlap at the nodes
      real(dp), allocatable :: force(:)           !< solver force P at the nodes
      real(dp), allocatable :: stiffness(:)       !< solver stiffness dP/ddelta
      real(dp), allocatable :: energy(:)          !< int_{delta_c}^{delta} P of the interpolant
      real(dp), allocatable :: contact_radius(:)  !< solver effective contact radius a*
      ! evaluation data
      !> (0:4, n): node delta(i) and the cubic c1..c4 in t = delta - delta(i) of interval i
      !> (seg(0, n) = delta_max ends the forward scan; one cache line per interval)
      real(dp), allocatable :: seg(:, :)
      real(dp), allocatable :: radius_slope(:)    !< monotone Hermite slopes of a*
      !> Rough tables' tail [cutoff, tail_end] (ln P intervals below 0) resampled for
      !> table_eval: equal pieces of width 1/fine_scale, each a cubic Hermite in P
      !> (fine_seg(0:4, :) as seg) within tail_resample_tol of the ln P interpolant, found
      !> by one multiplication: no lookup and no exp on the hot path (issue 33: a tail
      !> evaluation cost 7.7x an inline Hertz force). Empty (size 0) where there is no
      !> such tail or it would take more than max_fine pieces (egw_table_tail; then exp).
      real(dp), allocatable :: fine_seg(:, :)
      real(dp) :: fine_scale = 0.0_dp
      real(dp) :: tail_end = -huge(1.0_dp)        !< end of fine_seg's range, else -huge
      integer, allocatable :: bucket(:)           !< (0:n_bucket+1): interval at bucket start
      integer :: n_bucket = 0
      real(dp) :: bucket_scale = 0.0_dp
      real(dp) :: bucket_origin = 0.0_dp          !< overlap at the first node
      !> some bucket spans > 6 intervals (its entry is negated: bisect there)
      logical :: crowded = .false.
      !> below this overlap force and stiffness are exactly 0 (rough models: the cut-off;
      !> Hertz: 0; flat laws: -huge): the first test of an evaluation
      real(dp) :: zero_below = -huge(1.0_dp)
      !> the deep-overlap law fitted to the last node (table_prepare): above delta_max
      !> an evaluation needs no fit (sigma -> 0 puts every contact there)
      type(deep_law) :: deep
   end type force_table

   !> 8-point Gauss-Legendre rule on [0, 1] for the energy of log-space intervals,
   !> where exp(cubic) has no closed-form integral (exact to ~1e-16 relative for the
   !> near-quadratic ln P of a refined interval); hysteresis_energy's clipped dips too.
   real(dp), parameter, public :: gl_x(8) = 0.5_dp + 0.5_dp*[-0.9602898564975363_dp, &
      & -0.7966664774136267_dp, -0.5255324099163290_dp, -0.1834346424956498_dp, &
      & 0.1834346424956498_dp, 0.5255324099163290_dp, 0.7966664774136267_dp, &
      & 0.9602898564975363_dp]
   real(dp), parameter, public :: gl_w(8) = 0.5_dp*[0.1012285362903763_dp, &
      & 0.2223810344533745_dp, 0.3137066458778873_dp, 0.3626837833783620_dp, &
      & 0.3626837833783620_dp, 0.3137066458778873_dp, 0.2223810344533745_dp, &
      & 0.1012285362903763_dp]

   interface
   ! the builds: in the submodule egw_table_build (table_build.f90)

      !> Build a table over [delta_min, delta_max] with interpolation error <= rel_tol.
      !> The table starts at the cut-off delta_c where P = rel_tol*P_ref (below delta_min
      !> if the force at delta_min is still larger than that) and ends at delta_max, or at
      !> deep_law_floor where that is higher (P_ref stays delta_max's). The solver runs with
      !> options%n_threads = 1 inside an OpenMP loop over points, and with its rel_tol
      !> tightened to min(options%rel_tol, rel_tol/10) so that its own error does not
      !> dominate the interpolation check. The optional progress hook (table_progress)
      !> counts solves; the cut-off search is counted in done but not reported on its own
      !> (its length is not known in advance).
      module subroutine build_table(params, options, delta_min, delta_max, rel_tol, table, error, &
         & progress, loading_curve, loading)
         type(contact_params), intent(in) :: params   !< one parameter set
         type(solver_options), intent(in) :: options !< of the solves (rel_tol at most rel_tol/10)
         real(dp), intent(in) :: delta_min   !< smallest overlap of interest [length] (< 0: apart)
         real(dp), intent(in) :: delta_max   !< largest overlap tabulated [length]
         real(dp), intent(in) :: rel_tol   !< interpolation tolerance of the force, relative
         type(force_table), intent(out) :: table   !< the table; empty on error
         type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
         procedure(table_progress), optional :: progress   !< optional hook (table_progress)
         !> true: the loading curve of a hysteresis table (build_hysteresis), which may have
         !> the flow-pressure cap (a capped loading curve is no reversible force law, so a
         !> force table refuses flow_pressure otherwise); default false
         logical, intent(in), optional :: loading_curve
         !> GW's ZMC law of params tabulated once (zmc_law_pieces), the solves' law where
         !> its parameters are params' (a hysteresis build's: its curves' law too)
         type(law_pieces), intent(in), optional :: loading
      end subroutine build_table

      !> build_table for a sphere pair whose local pressure is a rough-flat law (doc/theory.md
      !> §10; solve_contact_law): R and E* from params, delta the overlap with the law's
      !> reference plane. The table's params are model_flat_law with sigma the law's length;
      !> below the cut-off its tail is the exponential continuation of the first node,
      !> P = P_c exp((K_c/P_c)(delta - delta_c)) (the rigid sphere on the law's own
      !> exponential large-separation end), above the last node the deep-overlap asymptote
      !> as for classic GW (both laws give the whole pressure), nodes up to 10 length units.
      module subroutine build_table_law(params, law, options, delta_min, delta_max, rel_tol, &
         & table, error, progress)
         type(contact_params), intent(in) :: params   !< radius R and modulus E* of the pair
         class(flat_law), intent(in) :: law           !< the rough-flat law
         type(solver_options), intent(in) :: options   !< the solver's options of every solve
         real(dp), intent(in) :: delta_min, delta_max, rel_tol   !< as build_table
         type(force_table), intent(out) :: table   !< the built table, prepared
         !> a solve's failure or an unreached rel_tol
         type(egw_error), allocatable, intent(out) :: error
         procedure(table_progress), optional :: progress   !< optional hook (table_progress)
      end subroutine build_table_law

      !> Build a table whose cut-off is fixed at cutoff (used by the universal table,
      !> whose slices share one cut-off). P_ref is computed as in build_table. With
      !> log_space, every interval interpolates ln P (the universal table combines slices
      !> in log space; the force must be positive from the cut-off on).
      module subroutine build_table_fixed_cutoff(params, options, cutoff, delta_max, rel_tol, &
         & log_space, table, error)
         type(contact_params), intent(in) :: params   !< validated parameters of the table
         type(solver_options), intent(in) :: options   !< the solver's options of every solve
         !> first node, last node [length], rel_tol as build_table
         real(dp), intent(in) :: cutoff, delta_max, rel_tol
         logical, intent(in) :: log_space   !< interpolate ln P on every interval
         type(force_table), intent(out) :: table   !< the built table, prepared
         !> a solve's failure or an unreached rel_tol
         type(egw_error), allocatable, intent(out) :: error
      end subroutine build_table_fixed_cutoff

      !> Tables of several parameter sets on one common set of nodes, all from the fixed
      !> cutoff to delta_max (the mu slices of a universal table, which then needs one
      !> lookup for all slices). P_ref of each set as in build_table. Progress (optional
      !> table_progress hook) counts solves of (node, set) pairs, starting from solves_before
      !> (default 0) so that a caller running several builds can report one monotone
      !> sequence; solves returns the count at the end (solves_before included).
      module subroutine build_tables_shared(params, options, cutoff, delta_max, rel_tol, &
         & log_space, tables, error, progress, solves_before, solves)
         type(contact_params), intent(in) :: params(:)   !< validated parameters, one set per table
         type(solver_options), intent(in) :: options   !< the solver's options of every solve
         !> first node, last node [length], rel_tol as build_table
         real(dp), intent(in) :: cutoff, delta_max, rel_tol
         logical, intent(in) :: log_space   !< interpolate ln P on every interval
         !> one per parameter set, on the same nodes, prepared
         type(force_table), intent(inout) :: tables(:)
         !> a solve's failure or an unreached rel_tol
         type(egw_error), allocatable, intent(out) :: error
         !> optional hook (table_progress): solves done and total, from solves_before
         procedure(table_progress), optional :: progress
         !> solves counted before this build (default 0)
         integer, intent(in), optional :: solves_before
         integer, intent(out), optional :: solves   !< solves_before plus this build's solves
      end subroutine build_tables_shared

      !> Cut-off rule: P_ref = P(min(0, delta_max)) for rough models, P(delta_max) for Hertz;
      !> delta_c is where P falls to between rel_tol*P_ref/2 and rel_tol*P_ref (bisection
      !> on solves; P is increasing in delta).
      module subroutine table_find_cutoff(params, options, delta_min, delta_max, rel_tol, cutoff, &
         & p_ref, error)
         type(contact_params), intent(in) :: params   !< validated parameters of the table
         type(solver_options), intent(in) :: options   !< the solver's options of every solve
         !> build_table's range [length] and rel_tol
         real(dp), intent(in) :: delta_min, delta_max, rel_tol
         real(dp), intent(out) :: cutoff, p_ref   !< delta_c [length] and P_ref [force]
         type(egw_error), allocatable, intent(out) :: error   !< a solve's failure
      end subroutine table_find_cutoff
   end interface

contains

   !> A table's scalars as the files store them, in this order: rel_tol, cutoff,
   !> delta_max, reference_force, max_force_error, max_stiffness_error, radius_sum.
   pure function table_meta(t) result(a)
      type(force_table), intent(in) :: t  !< the table
      real(dp) :: a(7)
      a = [t%rel_tol, t%cutoff, t%delta_max, t%reference_force, t%max_force_error, &
         & t%max_stiffness_error, t%radius_sum]
   end function table_meta

   !> The scalars of table_meta back into t.
   pure subroutine set_table_meta(t, a)
      type(force_table), intent(inout) :: t  !< the table
      real(dp), intent(in) :: a(7)           !< table_meta's values
      t%rel_tol = a(1)
      t%cutoff = a(2)
      t%delta_max = a(3)
      t%reference_force = a(4)
      t%max_force_error = a(5)
      t%max_stiffness_error = a(6)
      t%radius_sum = a(7)
   end subroutine set_table_meta

   !> Derive the evaluation data (coefficients, energy, lookup buckets) from the nodes.
   !> Called by the builder and by the readers; deterministic, so a table read back
   !> evaluates bit-for-bit like the one written.
   pure subroutine table_prepare(table, resample)
      type(force_table), intent(inout) :: table   !< its nodes set; the evaluation data derived
      !> resample the ln P tail for table_eval (default); .false. for a hysteresis
      !> table's loading table, whose evaluations go through its ln P intervals
      !> (table_eval_cached) and must match table_eval's bit for bit
      logical, intent(in), optional :: resample
      integer :: n, i
      real(dp) :: h, v0, v1, d0, d1, s

      n = size(table%delta)
      if (allocated(table%seg)) deallocate (table%seg)
      if (allocated(table%radius_slope)) deallocate (table%radius_slope)
      if (allocated(table%bucket)) deallocate (table%bucket)
      if (allocated(table%energy)) deallocate (table%energy)
      allocate (table%seg(0:4, n), table%radius_slope(n), table%energy(n))
      table%seg = 0.0_dp
      table%seg(0, :) = table%delta
      do i = 1, n - 1
         h = table%delta(i + 1) - table%delta(i)
         if (i <= table%n_log) then
            v0 = log(table%force(i))
            v1 = log(table%force(i + 1))
            d0 = table%stiffness(i)/table%force(i)
            d1 = table%stiffness(i + 1)/table%force(i + 1)
         else
            v0 = table%force(i)
            v1 = table%force(i + 1)
            d0 = table%stiffness(i)
            d1 = table%stiffness(i + 1)
         end if
         s = (v1 - v0)/h
         table%seg(1, i) = v0
         table%seg(2, i) = d0
         table%seg(3, i) = (3*s - 2*d0 - d1)/h
         table%seg(4, i) = (d0 + d1 - 2*s)/h**2
      end do
      table%zero_below = zero_overlap(table%params, table%cutoff)
      table%deep = deep_law_fit(table%delta_max, table%force(n), table%stiffness(n), &
         & deep_coefficient(table%params))
      call resample_tail(table, resample)
      ! energy: exact integral of the interpolant (Hermite rule in linear intervals; the
      ! resampled tail's pieces)
      table%energy(1) = 0.0_dp
      do i = 1, n - 1
         table%energy(i + 1) = table%energy(i) + interval_integral(table, i, &
            & table%delta(i + 1) - table%delta(i))
      end do
      call monotone_slopes(table%delta, table%contact_radius, table%radius_slope)
      ! buckets: uniform in delta, 8 per interval on average, doubled while more than
      ! 1/64 of them span more than 6 intervals (up to max_buckets); lookups scan forward
      ! from the bucket's interval, and in the few crowded buckets (nodes graded towards
      ! delta = 0) bisect.
      ! (Buckets uniform in sign(delta) sqrt|delta| would spread graded nodes, but the
      ! sqrt on the lookup path made an evaluation ~1.8x slower, measured.)
      call fit_buckets(table)
   end subroutine table_prepare

   !> The tail's ln P intervals [cutoff, delta(last)] (last the last node <= 0 that ends
   !> one: n_log + 1 for the tables egw builds) as equal pieces of cubic Hermite in P
   !> (force_table%fine_seg: egw_table_tail's resample_tails, one table), for rough
   !> tables (not flat laws, whose every interval is ln P): within tail_resample_tol
   !> rel_tol / 2 of the ln P interpolant, relative to it, and their slopes within
   !> 10 tail_resample_tol rel_tol of its slope. Deterministic.
   pure subroutine resample_tail(table, resample)
      type(force_table), intent(inout) :: table
      logical, intent(in), optional :: resample   !< .false.: none
      integer :: n_fine, last
      real(dp), allocatable :: pieces(:, :)
      if (allocated(table%fine_seg)) deallocate (table%fine_seg)
      allocate (table%fine_seg(0:4, 0))
      table%fine_scale = 0.0_dp
      table%tail_end = -huge(1.0_dp)
      if (table%n_log < 1 .or. table%params%model == model_flat_law .or. &
         & .not. is_rough(table%params)) return
      if (present(resample)) then
         if (.not. resample) return
      end if
      last = tail_last_node(table%delta, table%n_log)
      if (last == 0) return
      call resample_tails(size(table%delta), 1, table%delta, table%force, table%stiffness, &
         & table%seg, table%n_log, last, [tail_resample_tol*table%rel_tol], min_fine, &
         & pieces, n_fine)
      if (n_fine == 0) return
      call move_alloc(pieces, table%fine_seg)
      table%fine_scale = n_fine/(table%delta(last) - table%delta(1))
      table%tail_end = table%delta(last)
   end subroutine resample_tail

   !> The overlap below which table_eval is exactly 0: rough models (not flat laws) their
   !> cut-off (the force there is below 1e-12 P_ref; doc/formats.md rule 1), Hertz 0 (or
   !> its cut-off if that is lower); -huge otherwise.
   pure real(dp) function zero_overlap(params, cutoff) result(delta)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: cutoff
      delta = -huge(1.0_dp)
      if (params%model == model_flat_law) return
      if (is_rough(params)) then
         delta = cutoff
      else
         delta = min(cutoff, 0.0_dp)
      end if
   end function zero_overlap

   !> Buckets uniform in delta, 8 per interval, doubled while more than 1/64 of them span
   !> more than 6 intervals (up to max_buckets); those left crowded are marked.
   pure subroutine fit_buckets(table)
      type(force_table), intent(inout) :: table
      integer :: n_crowded
      table%n_bucket = 8*(size(table%delta) - 1)
      do
         if (allocated(table%bucket)) deallocate (table%bucket)
         allocate (table%bucket(0:table%n_bucket + 1))
         call make_buckets(table)
         ! crowded: spans more than 6 intervals. Refine while more than 1/64 of the
         ! buckets are (a small array stays in L1 cache; a rare bisection is cheaper)
         n_crowded = count(table%bucket(1:table%n_bucket + 1) - &
            & table%bucket(0:table%n_bucket) + 1 > 6)
         table%crowded = n_crowded > 0
         if (64*n_crowded <= table%n_bucket .or. 2*table%n_bucket > max_buckets) exit
         table%n_bucket = 2*table%n_bucket
      end do
      ! buckets still spanning more than 6 intervals (a few, at nodes graded towards a
      ! singular point) are marked by a negative entry: lookups there bisect
      if (table%crowded) then
         where ([table%bucket(1:table%n_bucket + 1) - table%bucket(0:table%n_bucket) + 1 > 6, &
            & .false.]) table%bucket = -table%bucket
      end if
   end subroutine fit_buckets

   !> Fill the lookup buckets: bucket b holds the interval containing the point whose
   !> overlap is origin + (b - 1e-6)/scale, so rounding never puts it past the
   !> interval of a delta that maps to b, and evaluation only scans forward.
   pure subroutine make_buckets(table)
      type(force_table), intent(inout) :: table
      integer :: n, i, b
      real(dp) :: xb
      n = size(table%delta)
      table%bucket_origin = table%delta(1)
      table%bucket_scale = table%n_bucket/(table%delta(n) - table%bucket_origin)
      i = 1
      do b = 0, table%n_bucket + 1
         xb = table%bucket_origin + (b - 1.0e-6_dp)/table%bucket_scale
         do while (i < n - 1)
            if (xb < table%delta(i + 1)) exit
            i = i + 1
         end do
         table%bucket(b) = i
      end do
   end subroutine make_buckets

   !> True when the evaluation data are present (a built or read table).
   pure logical function table_is_ready(table)
      type(force_table), intent(in) :: table   !< any table
      table_is_ready = allocated(table%seg) .and. allocated(table%bucket) .and. &
         & allocated(table%fine_seg)
   end function table_is_ready

   !> Force and stiffness at overlap delta: below the cut-off below_cutoff's (exactly 0 for
   !> rough models, whose force at the cut-off is below 1e-12 P_ref), above delta_max the
   !> deep-overlap asymptote (deep_force, a C1 continuation; see table_covers). No
   !> allocation, no shared state: safe in OpenMP loops over contacts. The optional error
   !> says what egw_table_eval's status says (the values are written as without it):
   !> egw_invalid_argument for a NaN delta (force and stiffness 0) or one whose
   !> continuation above delta_max leaves the doubles
   !> (+Inf, or far enough to overflow); egw_out_of_range above delta_max (the values of
   !> the deep-overlap asymptote, not checked against solves by the build). Without an
   !> error the call costs what it did: the checks run only outside (cutoff, delta_max).
   pure subroutine table_eval(table, delta, force, stiffness, error)
      type(force_table), intent(in) :: table   !< built or read
      real(dp), intent(in) :: delta   !< overlap [length]: > 0 pressed together, < 0 apart
      real(dp), intent(out) :: force   !< normal force [force], >= 0 (repulsive)
      real(dp), intent(out) :: stiffness   !< dP/ddelta [force/length]
      !> allocated for a NaN or overflowing delta, or one above delta_max (see above)
      type(egw_error), allocatable, intent(out), optional :: error
      if (delta > table%cutoff .and. delta < table%tail_end) then
         ! the resampled tail: one piece by one multiplication, a cubic in P
         call fine_kernel(table%fine_seg, size(table%fine_seg, 2), table%cutoff, &
            & table%fine_scale, delta, force, stiffness)
      else if (delta > table%cutoff .and. delta < table%delta_max) then
         ! hot path: bucket lookup, forward scan, one cubic (no search, no allocation)
         call eval_kernel(table%seg, table%bucket, table%n_bucket, table%bucket_origin, &
            & table%bucket_scale, table%n_log, size(table%seg, 2), delta, force, stiffness)
      else
         call table_beyond(table, delta, force, stiffness)
         if (present(error)) call beyond_status(table%delta_max, "delta", delta, &
            & [force, stiffness], error)
      end if
   end subroutine table_eval

   !> table_eval, except below a rough table's cut-off: there the model's separated tail
   !> law (tail_force, doc/theory.md §9, matched to the first node) instead of 0. Not what
   !> a table evaluates: the force's physical continuation, for builders that compare a
   !> solve with the loading force below the cut-off (the hysteresis gaps).
   pure subroutine table_eval_tail_law(table, delta, force, stiffness)
      type(force_table), intent(in) :: table   !< built or read
      real(dp), intent(in) :: delta   !< overlap [length]
      real(dp), intent(out) :: force   !< normal force [force], >= 0
      real(dp), intent(out) :: stiffness   !< dP/ddelta [force/length]
      if (delta < table%cutoff .and. is_rough(table%params) .and. &
         & table%params%model /= model_flat_law) then
         call tail_force(table%cutoff, table%force(1), table%stiffness(1), &
            & table%params%sigma, plastic_summits(table%params), delta, force, stiffness)
      else
         call table_eval(table, delta, force, stiffness)
      end if
   end subroutine table_eval_tail_law

   !> The status of an evaluation at x (called name) outside a table's (cutoff, delta_max)
   !> with the values it gave (egw_table_eval's statuses, as messages):
   !> none at or below delta_max; a NaN x or values that left the doubles
   !> egw_invalid_argument; above delta_max egw_out_of_range. Shared by the 1-D, universal
   !> and hysteresis evaluations.
   pure subroutine beyond_status(delta_max, name, x, values, error)
      real(dp), intent(in) :: delta_max   !< the table's last node [length]
      character(len=*), intent(in) :: name   !< the argument, e.g. "delta"
      real(dp), intent(in) :: x           !< its value
      real(dp), intent(in) :: values(:)   !< what the evaluation gave (force, stiffness, ...)
      type(egw_error), allocatable, intent(out) :: error   !< allocated as said above
      if (ieee_is_nan(x)) then
         call fatal_error(error, egw_invalid_argument, name//" = NaN: must be a number")
      else if (.not. all(ieee_is_finite(values))) then
         call fatal_error(error, egw_invalid_argument, name//" = "//format_real(x)// &
            & ": the continuation above the table's delta_max = "//format_real(delta_max)// &
            & " exceeds the largest double")
      else if (x > delta_max) then
         call fatal_error(error, egw_out_of_range, name//" = "//format_real(x)// &
            & ": above the table's delta_max = "//format_real(delta_max)// &
            & " (values extrapolated)")
      end if
   end subroutine beyond_status

   !> table_eval outside (cutoff, delta_max): the node values at the ends, below_cutoff
   !> below the cut-off, the deep-overlap asymptote above delta_max.
   pure subroutine table_beyond(table, delta, force, stiffness)
      type(force_table), intent(in) :: table
      real(dp), intent(in) :: delta
      real(dp), intent(out) :: force, stiffness
      integer :: n
      n = size(table%delta)
      if (delta >= table%delta_max) then
         call table_deep(table, delta, force, stiffness)
      else if (delta == table%cutoff) then
         force = table%force(1)
         stiffness = table%stiffness(1)
      else if (delta < table%zero_below) then
         force = 0.0_dp
         stiffness = 0.0_dp
      else
         call below_cutoff(table%params, table%cutoff, table%force(1), table%stiffness(1), &
            & delta, force, stiffness)
      end if
   end subroutine table_beyond

   !> The deep-overlap asymptote above delta_max (force and stiffness).
   pure subroutine table_deep(table, delta, force, stiffness)
      type(force_table), intent(in) :: table
      real(dp), intent(in) :: delta   !< >= table%delta_max
      real(dp), intent(out) :: force, stiffness
      call deep_law_force(table_deep_law(table), delta, force, stiffness)
   end subroutine table_deep

   !> The deep-overlap law of the last node: the one table_prepare fitted, else (a table
   !> not yet prepared) fitted now; the same values either way.
   pure function table_deep_law(table) result(law)
      type(force_table), intent(in) :: table
      type(deep_law) :: law
      integer :: n
      if (table%deep%ready) then
         law = table%deep
      else
         n = size(table%delta)
         law = deep_law_fit(table%delta_max, table%force(n), table%stiffness(n), &
            & deep_coefficient(table%params))
      end if
   end function table_deep_law

   !> The force below the cut-off delta_c of a table of params whose first node has force
   !> p_c and stiffness k_c: rough models 0 (p_c <= 1e-12 P_ref; the separated tail below
   !> it, doc/theory.md §9, is smaller still); Hertz P_c (delta/delta_c)^(3/2), the closed
   !> form itself (k_c unused), and 0 apart; flat laws exponential_tail. NaN gives 0 (the
   !> C layer refuses it before). The universal table calls it with a slice's params
   !> (x = delta/sigma).
   pure subroutine below_cutoff(params, delta_c, p_c, k_c, delta, force, stiffness)
      type(contact_params), intent(in) :: params   !< the table's parameters
      real(dp), intent(in) :: delta_c, p_c, k_c    !< first node: overlap, force, stiffness
      real(dp), intent(in) :: delta                !< overlap [length], < delta_c
      real(dp), intent(out) :: force, stiffness   !< force [force] and stiffness dP/ddelta at delta
      if (params%model == model_flat_law) then
         call exponential_tail(delta_c, p_c, k_c, delta, force, stiffness)
      else if (is_rough(params)) then
         force = 0.0_dp
         stiffness = 0.0_dp
      else if (delta > 0.0_dp .and. delta_c > 0.0_dp) then
         force = p_c*(delta/delta_c)**1.5_dp
         stiffness = 1.5_dp*force/delta
      else
         force = 0.0_dp
         stiffness = 0.0_dp
      end if
   end subroutine below_cutoff

   !> The tail of a flat-law table below its cut-off: P = p_c exp((k_c/p_c)(delta -
   !> delta_c)), C1 at delta_c, 0 as delta -> -inf (and for p_c or k_c not positive).
   pure subroutine exponential_tail(delta_c, p_c, k_c, delta, force, stiffness)
      real(dp), intent(in) :: delta_c, p_c, k_c, delta
      real(dp), intent(out) :: force, stiffness
      force = 0.0_dp
      stiffness = 0.0_dp
      if (.not. (p_c > 0.0_dp .and. k_c > 0.0_dp)) return
      force = p_c*exp((k_c/p_c)*(delta - delta_c))
      stiffness = force*(k_c/p_c)
   end subroutine exponential_tail

   !> table_eval through the caller's copy seg of the interval last used (table_segment's
   !> layout; anything else, e.g. NaN ends, is a miss), refilled when delta leaves it: the
   !> values of table_eval, without the lookup while delta stays inside (a DEM contact).
   pure subroutine table_eval_cached(table, delta, seg, force, stiffness)
      type(force_table), intent(in) :: table   !< a prepared table
      real(dp), intent(in) :: delta   !< overlap [length]
      !> the caller's interval (table_segment's layout), refilled on a miss
      real(dp), intent(inout) :: seg(7)
      !> force [force] and stiffness dP/ddelta, as table_eval
      real(dp), intent(out) :: force, stiffness
      logical :: found
      if (.not. (seg(1) <= delta .and. delta < seg(2) .and. delta > table%cutoff)) then
         call table_segment(table, delta, seg, found)
         if (.not. found) then
            seg(1:2) = ieee_value(1.0_dp, ieee_quiet_nan)
            call table_eval(table, delta, force, stiffness)
            return
         end if
      end if
      call segment_eval(seg, delta, force, stiffness)
   end subroutine table_eval_cached

   !> Force and stiffness at delta from an interval seg of table_segment's layout:
   !> eval_kernel's arithmetic on the copied interval (the same values).
   pure subroutine segment_eval(seg, delta, force, stiffness)
      !> an interval of table_segment's layout, and the overlap [length] in it
      real(dp), intent(in) :: seg(7), delta
      real(dp), intent(out) :: force, stiffness   !< force [force] and stiffness dP/ddelta
      real(dp) :: t, t2, v, d
      t = delta - seg(1)
      t2 = t*t
      v = (seg(3) + t*seg(4)) + t2*(seg(5) + t*seg(6))
      d = (seg(4) + 2*t*seg(5)) + 3*t2*seg(6)
      if (seg(7) > 0.0_dp) then
         force = exp(v)
         stiffness = force*d
      else
         force = v
         stiffness = d
      end if
   end subroutine segment_eval

   !> The interval of the table that holds delta, for a caller that keeps it while delta
   !> stays inside (a DEM contact): seg = [lo, hi, c1, c2, c3, c4, log] with lo <= delta <
   !> hi, the cubic in delta - lo and log = 1 where it is ln P; table_eval_cached evaluates
   !> it exactly as table_eval does for lo <= delta < hi and delta > cutoff (the cut-off
   !> itself has its own value), except in a rough table's ln P tail, where table_eval
   !> takes the resampled pieces (fine_seg: within 5e-2 rel_tol of these).
   !> found = .false. outside (cut-off, delta_max), where
   !> table_eval has no interval.
   pure subroutine table_segment(table, delta, seg, found)
      type(force_table), intent(in) :: table   !< a prepared table
      real(dp), intent(in) :: delta   !< overlap [length]
      real(dp), intent(out) :: seg(7)   !< the interval holding delta (0 where not found)
      logical, intent(out) :: found   !< delta in (cutoff, delta_max)
      integer :: i
      seg = 0.0_dp
      found = delta > table%cutoff .and. delta < table%delta_max
      if (.not. found) return
      i = kernel_locate(table%seg, table%bucket, table%n_bucket, table%bucket_origin, &
         & table%bucket_scale, size(table%seg, 2), delta)
      seg(1) = table%seg(0, i)
      seg(2) = table%seg(0, i + 1)
      seg(3:6) = table%seg(1:4, i)
      if (i <= table%n_log) seg(7) = 1.0_dp
   end subroutine table_segment

   !> Evaluation on plain explicit-shape arrays: the same lookup and cubic through the
   !> table's allocatable components costs ~1.6x as much (descriptor loads and index
   !> arithmetic on the critical path of a latency-bound evaluation).
   pure subroutine eval_kernel(seg, bucket, n_bucket, origin, scale, n_log, n, delta, force, &
      & stiffness)
      integer, intent(in) :: n_bucket, bucket(0:n_bucket + 1), n_log, n
      real(dp), intent(in) :: seg(0:4, n), origin, scale, delta
      real(dp), intent(out) :: force, stiffness
      integer :: i
      real(dp) :: t, t2, v, d
      i = kernel_locate(seg, bucket, n_bucket, origin, scale, n, delta)
      ! the cubic (Estrin's scheme: shorter dependency chains than Horner); written out
      ! again in segment_eval (a copied interval), which must give the same values
      t = delta - seg(0, i)
      t2 = t*t
      v = (seg(1, i) + t*seg(2, i)) + t2*(seg(3, i) + t*seg(4, i))
      d = (seg(2, i) + 2*t*seg(3, i)) + 3*t2*seg(4, i)
      if (i <= n_log) then
         force = exp(v)
         stiffness = force*d
      else
         force = v
         stiffness = d
      end if
   end subroutine eval_kernel

   !> The resampled tail at cutoff < delta < tail_end: piece int((delta - cutoff) scale)
   !> and its cubic in P (explicit-shape, as eval_kernel, for the same reason).
   pure subroutine fine_kernel(fine_seg, n_fine, cutoff, scale, delta, force, stiffness)
      integer, intent(in) :: n_fine
      real(dp), intent(in) :: fine_seg(0:4, n_fine), cutoff, scale, delta
      real(dp), intent(out) :: force, stiffness
      integer :: j
      real(dp) :: t, t2
      j = min(int((delta - cutoff)*scale), n_fine - 1) + 1
      t = delta - fine_seg(0, j)
      t2 = t*t
      force = (fine_seg(1, j) + t*fine_seg(2, j)) + t2*(fine_seg(3, j) + t*fine_seg(4, j))
      stiffness = (fine_seg(2, j) + 2*t*fine_seg(3, j)) + 3*t2*fine_seg(4, j)
   end subroutine fine_kernel

   !> The interval i of delta in (seg(0, 1), seg(0, n)): seg(0, i) <= delta < seg(0, i+1).
   pure integer function kernel_locate(seg, bucket, n_bucket, origin, scale, n, delta) &
      & result(i)
      integer, intent(in) :: n_bucket, bucket(0:n_bucket + 1), n
      real(dp), intent(in) :: seg(0:4, n), origin, scale, delta
      integer :: b, hi, mid
      b = min(max(int((delta - origin)*scale), 0), n_bucket)
      i = bucket(b)
      if (i < 0) then
         ! crowded bucket (fit_buckets): bisect between its first and last interval
         i = -i
         hi = min(abs(bucket(b + 1)) + 1, n)
         do while (hi - i > 1)
            mid = (i + hi)/2
            if (delta >= seg(0, mid)) then
               i = mid
            else
               hi = mid
            end if
         end do
      end if
      ! seg(0, n) = delta_max > delta ends the scan
      do while (delta >= seg(0, i + 1))
         i = i + 1
      end do
   end function kernel_locate

   !> ln P and d ln P/ddelta at delta in (cutoff, delta_max) (used by the universal table
   !> to interpolate across mu in log space without an exp per slice).
   pure subroutine table_eval_log(table, delta, log_force, dlog_force)
      type(force_table), intent(in) :: table   !< a prepared table, ln P from the cut-off on
      real(dp), intent(in) :: delta   !< overlap [length] in (cutoff, delta_max)
      real(dp), intent(out) :: log_force, dlog_force   !< ln P and d ln P/ddelta [1/length]
      integer :: i, n
      real(dp) :: t, v, d

      n = size(table%delta)
      if (delta >= table%delta_max) then
         call table_deep(table, delta, v, d)
         log_force = log(v)
         dlog_force = d/v
         return
      end if
      i = find_interval(table, max(delta, table%cutoff))
      t = delta - table%delta(i)
      v = table%seg(1, i) + t*(table%seg(2, i) + t*(table%seg(3, i) + t*table%seg(4, i)))
      d = table%seg(2, i) + t*(2*table%seg(3, i) + 3*t*table%seg(4, i))
      if (i <= table%n_log) then
         log_force = v
         dlog_force = d
      else
         log_force = log(v)
         dlog_force = d/v
      end if
   end subroutine table_eval_log

   !> True when delta lies in [cutoff, delta_max] or below the cut-off (below_cutoff's
   !> values hold there); false above delta_max (the deep-overlap asymptote, not checked
   !> against solves by the build) or for NaN.
   elemental logical function table_covers(table, delta)
      type(force_table), intent(in) :: table   !< built or read
      real(dp), intent(in) :: delta   !< overlap [length]
      table_covers = delta <= table%delta_max
   end function table_covers

   !> Elastic energy int_{delta_c}^{delta} P ddelta of the interpolant (0 at and below the
   !> cut-off, measured from it as the force is 0 below it for rough models; above
   !> delta_max, of the deep-overlap asymptote).
   pure function table_energy(table, delta) result(energy)
      type(force_table), intent(in) :: table   !< built or read
      real(dp), intent(in) :: delta   !< overlap [length]
      real(dp) :: energy
      integer :: i, n
      n = size(table%delta)
      if (.not. delta > table%cutoff) then
         energy = 0.0_dp
      else if (delta >= table%delta_max) then
         energy = table%energy(n) + deep_law_energy(table_deep_law(table), delta)
      else
         i = find_interval(table, delta)
         energy = table%energy(i) + interval_integral(table, i, delta - table%delta(i))
      end if
   end function table_energy

   !> Effective contact radius a* at delta (monotone cubic Hermite through the solver's
   !> node values; 0 below the cut-off; above delta_max it grows as sqrt(g), Hertz's a on
   !> deep_force's layer overlap g). Not part of the adaptive error control.
   pure function table_contact_radius(table, delta) result(radius)
      type(force_table), intent(in) :: table   !< built or read
      real(dp), intent(in) :: delta   !< overlap [length]
      real(dp) :: radius
      integer :: i, n
      real(dp) :: h, t, h00, h10, h01, h11
      n = size(table%delta)
      if (.not. delta >= table%cutoff) then
         radius = 0.0_dp
      else if (delta >= table%delta_max) then
         radius = table%contact_radius(n)*deep_law_radius_factor(table_deep_law(table), &
            & delta)
      else
         i = find_interval(table, delta)
         h = table%delta(i + 1) - table%delta(i)
         t = (delta - table%delta(i))/h
         h00 = (1 + 2*t)*(1 - t)**2
         h10 = t*(1 - t)**2
         h01 = t**2*(3 - 2*t)
         h11 = t**2*(t - 1)
         radius = h00*table%contact_radius(i) + h10*h*table%radius_slope(i) + &
            & h01*table%contact_radius(i + 1) + h11*h*table%radius_slope(i + 1)
      end if
   end function table_contact_radius

   !> All four tabulated quantities at delta.
   !> error: as table_eval's, and egw_invalid_argument where the energy or the contact
   !> radius above delta_max leaves the doubles (egw_table_eval_all's statuses).
   pure subroutine table_eval_all(table, delta, force, stiffness, energy, contact_radius, &
      & error)
      type(force_table), intent(in) :: table   !< built or read
      real(dp), intent(in) :: delta   !< overlap [length]
      real(dp), intent(out) :: force   !< normal force [force], >= 0
      real(dp), intent(out) :: stiffness   !< dP/ddelta [force/length]
      real(dp), intent(out) :: energy   !< int P ddelta from the cut-off [force*length]
      real(dp), intent(out) :: contact_radius   !< effective contact radius a* [length]
      !> allocated for a NaN or overflowing delta, or one above delta_max (table_eval)
      type(egw_error), allocatable, intent(out), optional :: error
      call table_eval(table, delta, force, stiffness)
      energy = table_energy(table, delta)
      contact_radius = table_contact_radius(table, delta)
      if (.not. present(error)) return
      if (delta > table%cutoff .and. delta < table%delta_max) return
      call beyond_status(table%delta_max, "delta", delta, [force, stiffness, energy, &
         & contact_radius], error)
   end subroutine table_eval_all

   !> Record the particle radii R1, R2 of the pair (used by the LAMMPS writer for
   !> r = R1 + R2 - delta). They must reproduce the table's R: 1/R = 1/R1 + 1/R2.
   pure subroutine table_set_radii(table, radius1, radius2, error)
      type(force_table), intent(inout) :: table   !< the table whose pair gets its radii
      real(dp), intent(in) :: radius1   !< particle radius R1 [length], > 0
      real(dp), intent(in) :: radius2   !< particle radius R2 [length], > 0
      !> allocated when 1/R1 + 1/R2 is not the table's 1/R
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: r_eq
      if (.not. (ieee_is_finite(radius1) .and. radius1 > 0.0_dp)) then
         call fatal_error(error, egw_invalid_argument, "radius1 = "//format_real(radius1)// &
            & ": must be finite and > 0")
         return
      end if
      if (.not. (ieee_is_finite(radius2) .and. radius2 > 0.0_dp)) then
         call fatal_error(error, egw_invalid_argument, "radius2 = "//format_real(radius2)// &
            & ": must be finite and > 0")
         return
      end if
      r_eq = radius1*radius2/(radius1 + radius2)
      ! 1e-12: a few roundings of the harmonic mean
      if (abs(r_eq - table%params%radius) > 1.0e-12_dp*table%params%radius) then
         call fatal_error(error, egw_invalid_argument, "radius1 = "//format_real(radius1)// &
            & ", radius2 = "//format_real(radius2)//": equivalent radius "// &
            & format_real(r_eq)//" differs from the table's "//format_real(table%params%radius))
         return
      end if
      table%radius_sum = radius1 + radius2
   end subroutine table_set_radii

   !> Interval i (delta(i) <= delta < delta(i+1)) for cutoff <= delta < delta_max, found
   !> in O(1) by the table's buckets (used by the universal table, whose slices share
   !> their nodes).
   pure integer function table_interval(table, delta) result(i)
      type(force_table), intent(in) :: table   !< a prepared table
      real(dp), intent(in) :: delta   !< overlap [length] in [cutoff, delta_max)
      i = find_interval(table, delta)
   end function table_interval

   ! ------------------------------------------------------------------ internals

   !> Interval i with delta(i) <= delta < delta(i+1), from the bucket of delta and a
   !> short forward scan (typically 0 or 1 step; bisection if the bucket is crowded).
   pure integer function find_interval(table, delta) result(i)
      type(force_table), intent(in) :: table
      real(dp), intent(in) :: delta
      integer :: b, hi
      b = min(max(int((delta - table%bucket_origin)*table%bucket_scale), 0), table%n_bucket)
      i = abs(table%bucket(b))
      hi = abs(table%bucket(b + 1)) + 1
      if (hi - i > 6) then
         ! crowded bucket (graded nodes near a singular point): bisect
         hi = min(hi, size(table%seg, 2))
         i = i - 1 + bracket_interval(table%seg(0, i:hi), delta)
      end if
      ! seg(0, n) = delta_max > delta ends the scan
      do while (delta >= table%seg(0, i + 1))
         i = i + 1
      end do
   end function find_interval

   !> Integral of the interpolated force over [delta(i), delta(i) + t].
   pure real(dp) function interval_integral(table, i, t) result(s)
      type(force_table), intent(in) :: table
      integer, intent(in) :: i
      real(dp), intent(in) :: t
      integer :: q
      real(dp) :: u
      if (i <= table%n_log .and. table%delta(i) < table%tail_end) then
         ! the resampled tail: table_eval's pieces, integrated exactly
         s = fine_integral(table, table%delta(i), table%delta(i) + t)
      else if (i <= table%n_log) then
         s = 0.0_dp
         do q = 1, size(gl_x)
            u = gl_x(q)*t
            s = s + gl_w(q)*exp(table%seg(1, i) + u*(table%seg(2, i) + u*(table%seg(3, i) &
               & + u*table%seg(4, i))))
         end do
         s = s*t
      else
         s = t*(table%seg(1, i) + t*(table%seg(2, i)/2 + t*(table%seg(3, i)/3 + &
            & t*table%seg(4, i)/4)))
      end if
   end function interval_integral

   !> Integral over [a, b] (inside [cutoff, tail_end]) of the resampled tail's pieces.
   pure real(dp) function fine_integral(table, a, b) result(s)
      type(force_table), intent(in) :: table
      real(dp), intent(in) :: a, b
      integer :: j, ja, jb, n_fine
      real(dp) :: u0, u1, c(0:4)
      n_fine = size(table%fine_seg, 2)
      ja = min(max(int((a - table%cutoff)*table%fine_scale), 0), n_fine - 1) + 1
      jb = min(max(int((b - table%cutoff)*table%fine_scale), 0), n_fine - 1) + 1
      s = 0.0_dp
      do j = ja, jb
         c = table%fine_seg(:, j)
         u0 = max(a, c(0)) - c(0)
         u1 = b - c(0)
         if (j < n_fine) u1 = min(b, table%fine_seg(0, j + 1)) - c(0)
         if (u1 > u0) s = s + (antiderivative(c, u1) - antiderivative(c, u0))
      end do
   contains
      pure real(dp) function antiderivative(c, u) result(w)
         real(dp), intent(in) :: c(0:4), u
         w = u*(c(1) + u*(c(2)/2 + u*(c(3)/3 + u*c(4)/4)))
      end function antiderivative
   end function fine_integral

   !> Monotone Hermite slopes (Fritsch-Butland harmonic mean) for the contact radius.
   pure subroutine monotone_slopes(x, y, d)
      real(dp), intent(in) :: x(:), y(:)
      real(dp), intent(out) :: d(:)
      integer :: n, i
      real(dp) :: s0, s1
      n = size(x)
      if (n < 2) then
         d = 0.0_dp
         return
      end if
      d(1) = (y(2) - y(1))/(x(2) - x(1))
      d(n) = (y(n) - y(n - 1))/(x(n) - x(n - 1))
      do i = 2, n - 1
         s0 = (y(i) - y(i - 1))/(x(i) - x(i - 1))
         s1 = (y(i + 1) - y(i))/(x(i + 1) - x(i))
         if (s0*s1 > 0.0_dp) then
            d(i) = 2*s0*s1/(s0 + s1)
         else
            d(i) = 0.0_dp
         end if
      end do
   end subroutine monotone_slopes

   !> The lowest last node of a table of params from which the deep-overlap law above it
   !> (deep_force) stays within 1 % of solves up to 0.2 R (doc/theory.md §9): deep_law_floor_x
   !> sigma, capped at 0.2 R; -huge (no floor) for Hertz and smooth spheres.
   elemental real(dp) function deep_law_floor(params) result(d)
      type(contact_params), intent(in) :: params   !< validated parameters of the table
      d = -huge(1.0_dp)
      if (is_rough(params)) d = min(deep_law_floor_x(params%model)*params%sigma, &
         & 0.2_dp*params%radius)
   end function deep_law_floor

   !> deep_law_floor in units of sigma: GW 10, E-GW and EP-GW 2 (test table "deep-overlap
   !> law vs solves": at most 0.6 % (GW) and 0.75 % (E-GW, EP-GW psi 0.5-20) for mu
   !> 0.1-1000; from sigma EP-GW reaches 1.8 %, from 0.5 sigma 4 %); -huge for Hertz.
   elemental real(dp) function deep_law_floor_x(model) result(x)
      integer, intent(in) :: model   !< model_* constant
      x = -huge(1.0_dp)
      if (model == model_gw .or. model == model_flat_law) x = 10.0_dp
      if (model == model_egw .or. model == model_epgw) x = 2.0_dp
   end function deep_law_floor_x

   !> The Hertz constant (4/3) E sqrt(R) of params, which every model's force approaches
   !> deep in contact (deep_force); 4/3 for the universal table's slices (R = E = 1).
   elemental real(dp) function deep_coefficient(params) result(c)
      type(contact_params), intent(in) :: params   !< the table's parameters
      c = (4.0_dp/3.0_dp)*params%modulus*sqrt(params%radius)
   end function deep_coefficient

   !> EP-GW with yielding summits (psi > 0): its tail carries their slope (tail_force).
   pure logical function plastic_summits(params)
      type(contact_params), intent(in) :: params
      plastic_summits = params%model == model_epgw .and. params%psi > 0.0_dp
   end function plastic_summits

end module egw_table
