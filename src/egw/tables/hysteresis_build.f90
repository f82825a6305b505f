!> The build of egw_hysteresis tables (src/egw/tables/hysteresis.f90, whose interface block
!> declares build_hysteresis): the delta_max grid, each node's unloading curve from
!> solves, the bisection of both to rel_tol and the resampling onto the union s grid.
submodule (egw_hysteresis) egw_hysteresis_build
   use egw_status, only: egw_not_converged, egw_unsupported, fatal_error, format_real
   use egw_text, only: real_text, real_text_len
   use egw_params, only: validate_params, model_epgw, model_hertz
   use egw_rough_sphere, only: solve_result, loading_history, load_history, solve_unload, &
      & unload_start, cap_solve_options, solve_contact, history_residual, &
      & history_cap_ratio
   use egw_cap_sphere, only: cap_residual, cap_units, gamma_start
   use egw_cap_loading, only: build_cap_loading
   use egw_sphere_problem, only: deep_unloading
   use egw_law_pieces, only: law_pieces, zmc_law_pieces
   use egw_table, only: force_table, table_eval, build_table, table_eval_tail_law, &
      & table_prepare
   use egw_tolerance_probe, only: hysteresis_solve_tol, build_m_node_limit
   use egw_hysteresis_data, only: s_knee, s_zero, map_s, map_x, map_piece, map_iota, &
      & map_lengths, edge_breaks, edge_s, edge_xi, edge_segment, max_log_ratio, &
      & max_stencil, stencil_width, stencil_window, fine_length_tol
   implicit none

   !> Most nodes in s of one unloading curve, and of the delta_max grid.
   integer, parameter :: max_s_nodes = 400, max_m_nodes = build_m_node_limit
   !> The deepest turning point of a Hertz + cap table, in units of first yield delta_y.
   real(dp), parameter :: max_cap_range = 1000.0_dp
   !> Rough + cap tables refused before any solve (rough_cap_reach): at sigma/delta_y <=
   !> small_cap_sigma, a delta_max beyond max_layer_reach sigma (plastic summits:
   !> plastic_layer_reach). There the builds failed after 1 .. 150 s (an unloading solve's
   !> Newton stalling or its mesh needing more than 4097 nodes: the rough layer is ~
   !> (sigma/delta)**(2/3) of the contact radius wide). mu 4, p_y = 0.01 E*, TOL 1e-3,
   !> sigma/delta_y 1e-4 .. 1e-6: E-GW built at <= 2e5 sigma (9 builds; one at 3e5 too)
   !> and failed at >= 2.4e5 (16 of 16); EP-GW psi 1 built at <= 1.5e5 (4) and failed at
   !> >= 2e5 (3); GW failed at 3e5 (doc/stability.md "Stop 51 (tiny17)").
   real(dp), parameter :: small_cap_sigma = 1.0e-4_dp, max_layer_reach = 2.0e5_dp, &
      & plastic_layer_reach = 1.5e5_dp
   !> A rough + cap build that fails at sigma/delta_y below hint_sigma: its message adds
   !> sigma/delta_y and the routes the user can take (rough_cap_routes), as LAMMPS's.
   real(dp), parameter :: hint_sigma = 2.0e-3_dp
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
   !> Intervals (in s, or in delta_max relative to the grid's range) narrower than this
   !> are not split: at the residual-overlap edge of deep curves (dh/ds ~ 100) curves
   !> 1e-5 sigma apart differed by 3 % of the local force, the solves' own noise there
   !> (doc/benchmarks.md, local4 (e)).
   real(dp), parameter :: min_width = 2.0_dp**(-11)
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
   !> Hertz + cap tables: the share of rel_tol given to the loading table, whose error at
   !> a turning point multiplies the whole unloading curve (P = P_load,table(m) u); refine_m
   !> splits delta_max intervals until the force's whole error at the check curves' nodes,
   !> that share included (whole_mismatch), is within rel_tol (stop 53, doubt19: with both
   !> at rel_tol, 1e-4 to 100 delta_y reported 1.04e-4, to 8.5666 delta_y 1.23e-4).
   real(dp), parameter :: ratio_loading_share = 0.25_dp
   !> Hertz + cap tables: the least rel_tol built (a smaller one is refused at once). The
   !> cap solver's forces (32/64 rings) are smooth in delta and delta_max to ~3e-7 of
   !> themselves: at rel_tol 1e-6 the loading table to rel_tol/4 did not settle (and on
   !> main, to rel_tol, the curves' bisection to rel_tol/4 stalled at 3.2e-7 or the grid
   !> passed 400 delta_max nodes, to 2 and 10 delta_y; to 100 and 1000 delta_y tables were
   !> built 135x and 990x off rel_tol). 3e-6 met rel_tol with 278-289 delta_max nodes from
   !> 10 to 1000 delta_y (doc/stability.md "Stop 53 (doubt19)").
   real(dp), parameter :: ratio_least_tol = 3.0e-6_dp
   !> Rough + cap tables where the cap acts below delta_max: the least rel_tol built (a
   !> smaller one is refused after one loading solve). E-GW + cap (mu 4, p_y = 0.01 E*):
   !> sigma/delta_y 5e-3 to 3 delta_y at 1e-6 failed after 272 s CPU (an unloading solve
   !> at rel_tol/10 "reaches rel_tol >= 2.4e-7"; its delta_max grid at 209 nodes and
   !> splitting, the check curves' mismatch falling only ~2.7x per halving), at 3e-6 built
   !> (231 nodes, 87 s); README's scene, sigma/delta_y 1e-2 to 6 delta_y, at 3e-6 failed
   !> after 163 s ("the delta_max grid did not settle after 30 bisections"), at 1e-6 ran
   !> past 1200 s wall (stop 53); 1e-5 built on both (21 s, 101 nodes; 41 s, 154 nodes).
   !> Between 1e-5 and 3e-6 not mapped; doc/stability.md "Stop 54 (doubt20)".
   real(dp), parameter :: rough_least_tol = 1.0e-5_dp
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
   !> Log-ratio tables: a delta_max interval whose check misses by less than split_defer
   !> times the bound is not split in a pass where a neighbour that misses by more is:
   !> that split moves a node of its six-point stencil nearer (its midpoint's Lagrange
   !> product falls 2.5x with one neighbour split, 6.25x with both), and it is checked
   !> again with the new stencil, at no solve (its check curve is kept). egw-bench's
   !> table at 1e-4: 59 delta_max nodes against 67 (doc/benchmarks.md, stop 48).
   real(dp), parameter :: split_defer = 4.0_dp
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
      !> h = ln(c P_ext/P) at s of the edge map xi (edge_breaks of length), slopes as
      !> dh/d(m - delta) (the table's log_ratio); else the gap, slopes dg/ds
      logical :: log = .false.
      real(dp) :: xi(3) = 0.0_dp
      real(dp) :: p_turn = 0.0_dp   !< the solve's force at m (log: the weights' unit)
      !> per node the mismatch's weight (gap_at): min(1, P/(local_floor P(m))) (log),
      !> P_load(m)/max(P, local_floor P(m)) (Hertz + cap), 1 else
      real(dp), allocatable :: weight(:)
      type(loading_history) :: hist !< the loading solve at m (loaded: reused)
      !> the deflection of the curve's last unloading solve, the next one's start
      type(unload_start) :: start
   end type unloading_curve

contains

   ! build_hysteresis: interface and documentation in egw_hysteresis
   module subroutine build_hysteresis(params, options, delta_min, delta_max, rel_tol, table, &
      & error, progress)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta_min, delta_max, rel_tol
      type(hysteresis_table), intent(out) :: table
      type(egw_error), allocatable, intent(out) :: error
      ! a full header (not `module procedure`): gfortran 12 loses the interface of a
      ! procedure dummy in a separate module procedure body
      procedure(table_progress), optional :: progress
      real(dp) :: ratio
      character(len=:), allocatable :: place, routes
      call build_work(params, options, delta_min, delta_max, rel_tol, table, error, progress)
      if (.not. allocated(error)) return
      if (error%stat /= egw_not_converged) return
      ! a rough + cap build whose solves failed at small sigma/delta_y: what the user can do
      if (.not. (params%flow_pressure > 0.0_dp .and. params%model /= model_hertz .and. &
         & params%sigma > 0.0_dp)) return
      ratio = params%sigma/first_yield(params)
      if (.not. ratio < hint_sigma) return
      call rough_cap_where(params, delta_max, place)
      call rough_cap_routes(ratio, routes)
      error%message = error%message//" (rough + cap at "//place//": its tables may not "// &
         & "build at small sigma/delta_y; a smaller delta_max or rel_tol 1e-3 may let it "// &
         & "build, or "//routes//")"
   end subroutine build_hysteresis

   !> build_hysteresis's work (that routine adds the routes to a rough + cap failure).
   subroutine build_work(params, options, delta_min, delta_max, rel_tol, table, error, &
      & progress)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta_min, delta_max, rel_tol
      type(hysteresis_table), intent(out) :: table
      type(egw_error), allocatable, intent(out) :: error
      procedure(table_progress), optional :: progress
      type(unloading_curve), allocatable :: curves(:)
      real(dp), allocatable :: m(:)
      integer :: j, n, n_above
      logical :: rough_cap, shift

      call validate_params(params, error)
      if (allocated(error)) return
      ! a rough model with the cap (doc/theory.md section 12, "Rough spheres with the
      ! cap"): the EP-GW route below, its solves the rough solver's with the cap
      rough_cap = params%flow_pressure > 0.0_dp .and. params%model /= model_hertz .and. &
         & params%sigma > 0.0_dp
      if (.not. (rel_tol >= 1.0e-8_dp .and. rel_tol <= 0.1_dp)) then
         call fatal_error(error, egw_invalid_argument, "rel_tol = "//format_real(rel_tol)// &
            & ": must lie in [1e-8, 0.1]")
         return
      end if
      if (ieee_is_nan(delta_min) .or. .not. (delta_max > delta_min .and. &
         & delta_max < huge(1.0_dp))) then
         call fatal_error(error, egw_invalid_argument, "delta_min, delta_max = "// &
            & format_real(delta_min)//", "//format_real(delta_max)// &
            & ": need finite delta_min < delta_max")
         return
      end if
      if (params%flow_pressure > 0.0_dp .and. delta_max > max_cap_range*first_yield(params)) then
         call fatal_error(error, egw_invalid_argument, "delta_max = "//format_real(delta_max)// &
            & ": above 1000 delta_y (first yield delta_y = "//format_real(first_yield(params))// &
            & "), where a hysteresis table with the cap ends: a/R is ~70 p_y/E* there, far "// &
            & "beyond a half-space (doc/theory.md section 12)")
         return
      end if
      if (params%flow_pressure > 0.0_dp .and. .not. rough_cap .and. rel_tol < &
         & ratio_least_tol .and. delta_max > cap_first_turn(params)) then
         call fatal_error(error, egw_invalid_argument, "rel_tol = "//format_real(rel_tol)// &
            & ": below "//format_real(ratio_least_tol)//", the least a Hertz + cap "// &
            & "hysteresis table reaches (here to "//format_real(delta_max/ &
            & first_yield(params))//" delta_y): the cap solver's forces are smooth to ~3e-7 "// &
            & "of themselves, which its loading table and curves, built to rel_tol/4, need "// &
            & "(doc/stability.md, stop 53)")
         return
      end if
      if (rough_cap) then
         call rough_cap_reach(params, delta_max, error)
         if (allocated(error)) return
         if (rel_tol < rough_least_tol) then
            call rough_cap_floor(params, options, delta_max, rel_tol, error)
            if (allocated(error)) return
         end if
      end if
      if (params%flow_pressure > 0.0_dp .and. .not. rough_cap) then
         ! (a quarter of rel_tol: the curves store P/P_load(m), so the loading table's
         ! error at the turning point adds to theirs, which refine_m bounds by the rest)
         call build_cap_loading(params, options, delta_min, delta_max, &
            & ratio_loading_share*rel_tol, table%loading, error)
         ! (a bound it meets; the files state the table's rel_tol for both)
         if (.not. allocated(error)) table%loading%rel_tol = rel_tol
      else
         ! (a rough model with the cap: its capped loading curve, not a force law; plastic
         ! summits: on the ZMC law tabulated below, built here already)
         if (plastic_summits(params)) table%loading_law = zmc_law_pieces(params%psi, &
            & params%hardness_coeff, params%plastic_ratio)
         call build_table(params, options, delta_min, delta_max, rel_tol, table%loading, &
            & error, loading_curve=rough_cap, loading=table%loading_law)
      end if
      if (allocated(error)) return
      ! the loading branch evaluates its ln P intervals (table_eval = table_eval_cached)
      call table_prepare(table%loading, resample=.false.)
      table%params = params
      table%capped = hertz_capped(params)   ! (hysteresis_prepare sets it again)
      table%rel_tol = rel_tol
      table%delta_max = delta_max
      ! elastic summits (or none): unloading retraces the loading table exactly; the cap
      ! only dissipates from first yield on
      table%reversible = params%model /= model_epgw .or. params%psi == 0.0_dp .or. &
         & params%sigma == 0.0_dp
      ! (Hertz + cap: up to the first capped turning point the cap solver's contact is
      ! Hertz's, reversible)
      if (params%flow_pressure > 0.0_dp .and. .not. rough_cap) table%reversible = .not. &
         & delta_max > cap_first_turn(params)
      if (rough_cap .and. .not. plastic_summits(params)) then
         ! elastic summits: irreversible once the cap acts, i.e. once the largest total
         ! pressure reaches p_y somewhere (it grows with the overlap on loading)
         call cap_reached(params, options, rel_tol, delta_max, table%reversible, error)
         if (allocated(error)) return
         table%reversible = .not. table%reversible
      end if
      if (table%reversible) then
         call hysteresis_prepare(table)   ! the tag only
         return
      end if
      if (params%flow_pressure > 0.0_dp .and. .not. rough_cap) then
         call build_cap_curves(table, options, error, progress)
         return
      end if
      ! a rough model whose cap acts below delta_max (elastic summits: the table is
      ! irreversible only then): L(m) less the smooth cap's residual overlap (rough_length)
      shift = rough_cap
      if (rough_cap .and. plastic_summits(params)) then
         call cap_reached(params, options, rel_tol, delta_max, shift, error)
         if (allocated(error)) return
      end if
      ! log-ratio curves where the unloading force stays positive: EP-GW without the cap,
      ! and a rough model whose cap does not act below delta_max (the cap-free table);
      ! where it acts, the force vanishes below a residual overlap: the gap
      table%log_ratio = .not. shift
      ! delta_max grid: from the loading cut-off (1e-12 of P_ref: the slowest impacts turn
      ! in the tail, where summits yield too) to delta_max, dyadic (bisection keeps it so:
      ! the m buckets rely on it)
      n = 9
      m = table%loading%cutoff + (delta_max - table%loading%cutoff)* &
         & [(real(j, dp), j = 0, n - 1)]/real(n - 1, dp)
      m(n) = delta_max   ! exactly (the readers check it): the sum above may round off
      if (rough_cap .and. .not. plastic_summits(params)) then
         ! elastic summits: reversible below the first yield of the rough contact, m_y
         ! (where its largest total pressure reaches p_y), and the curves have a kink in
         ! m there (g = 0 below): the turning points start at m_y, as the smooth cap's at
         ! delta_y (hysteresis_prepare: elastic_limit = m(1))
         call rough_first_yield(params, options, rel_tol, table%loading%cutoff, delta_max, &
            & m(1), error)
         if (allocated(error)) return
         m = m(1) + (delta_max - m(1))*[(real(j, dp), j = 0, n - 1)]/real(n - 1, dp)
         m(n) = delta_max
      else if (table%loading%cutoff < 0.0_dp .and. delta_max > params%sigma) then
         ! a node at 0, where the smooth sphere's Hertz part sets in (m_breakpoint): five
         ! nodes up to it and n_above above, so that stencils need not straddle it (where
         ! the table reaches a sigma into contact: below, the onset is within its last
         ! node). Five above (four intervals; refine_m splits where they miss): nine
         ! were more than the LAMMPS pour's tables (mu 8-23, psi 0.5, to 140 sigma, 1e-4)
         ! need, which passed every check with five and 25 % less CPU time, and met
         ! solve_unload at 1e-7 within 3.8e-5 of P(delta_max) above 0 (5.6e-5 with nine;
         ! egw-bench's table at 1e-4 48 x 55 nodes against 50 x 55, the same 9.04e-5 at
         ! its checks). The cap's tables keep nine where the cap acts below delta_max
         ! (validated so, not measured again); where it never acts the table is the
         ! cap-free one, grid and all (test rough_cap_hysteresis's reduction).
         n_above = 5
         if (shift) n_above = 9
         m = [table%loading%cutoff*[(real(j, dp), j = 4, 1, -1)]/4.0_dp, &
            & delta_max*[(real(j, dp), j = 0, n_above - 1)]/real(n_above - 1, dp)]
         m(1) = table%loading%cutoff
         m(size(m)) = delta_max
         n = size(m)
      end if
      ! the two-piece s map (rough + cap where the cap acts below delta_max): the knee
      ! delta_r(m) at s_knee, delta = 0 at s_zero, the tail to twice the floor delta_u
      ! below 0 (at least 2 sigma) over [s_zero, 1] (turning points at or below 0, EP-GW's:
      ! that tail alone)
      table%mapped = rough_cap .and. shift
      if (table%mapped) table%tail_length = max(-2*unloading_floor(table%loading, &
         & table%rel_tol), 2*params%sigma)
      allocate (curves(n))
      ! the ZMC loading law tabulated once for every unloading solve (~25 % of psi 1's
      ! build was its integral; empty for elastic summits: the integral's F_3/2 is cheap)
      ! (built with the loading table above)
      ! and, with the cap, its Z_u at the deep plastic zone's h_min (~36 % of psi 1's build)
      if (plastic_summits(params) .and. rough_cap) call deep_unloading(params, &
         & table%loading_law)
      if (present(progress)) call progress(0, 2*n - 1)
      ! the s range: twice the largest (m - delta_u)/L of the first nodes, so that every
      ! curve reaches delta_u, where the loading force is rel_tol of P_ref (below, an
      ! unloading force is below the table's tolerance: the evaluation continues each
      ! curve in proportion to the loading tail, and the s grid keeps its resolution
      ! where the unloading forces are)
      call unloading_lengths(table, options, m, shift, curves, error)
      if (allocated(error)) return
      table%s_max = 2*maxval((m - unloading_floor(table%loading, table%rel_tol))/ &
         & curves%length)
      if (table%mapped) table%s_max = 1.0_dp   ! (length: the first piece's span)
      ! log-ratio curves on the edge map (s = 1 at its last break)
      if (table%log_ratio) table%s_max = 1.0_dp
      call build_curves(table, options, m, shift, curves, error)
      if (allocated(error)) return
      call refine_m(table, options, shift, m, curves, error, progress)
      if (allocated(error)) return
      call resample(table, m, curves)
      call hysteresis_prepare(table)
      table%loading_law = law_pieces()
   end subroutine build_work

   !> Refuses (egw_invalid_argument, naming rel_tol and rough_least_tol) a rough + cap
   !> table below rough_least_tol where the cap acts below delta_max (cap_reached: one
   !> loading solve, at 1e-4: whether p_y is reached needs no more); where it never acts
   !> the table is the cap-free one, built at any rel_tol.
   subroutine rough_cap_floor(params, options, delta_max, rel_tol, error)
      type(contact_params), intent(in) :: params   !< a rough model with the cap
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta_max, rel_tol
      type(egw_error), allocatable, intent(out) :: error
      logical :: acts
      call cap_reached(params, options, 1.0e-3_dp, delta_max, acts, error)
      if (allocated(error) .or. .not. acts) return
      call fatal_error(error, egw_invalid_argument, "rel_tol = "//format_real(rel_tol)// &
         & ": below "//format_real(rough_least_tol)//", the least a rough + cap "// &
         & "hysteresis table reaches where the cap acts (here to "//format_real(delta_max/ &
         & first_yield(params))//" delta_y): below it builds ran for minutes and failed, "// &
         & "an unloading solve at rel_tol/10 reaching only ~2.4e-7, or the delta_max grid "// &
         & "not settling (doc/stability.md, stop 54)")
   end subroutine rough_cap_floor

   !> Refuses (egw_unsupported, naming delta_max) a rough + cap table that reaches
   !> beyond max_layer_reach sigma (plastic summits: plastic_layer_reach) at sigma/delta_y
   !> <= small_cap_sigma, where such builds
   !> failed after up to minutes of solves, with the routes the user can take.
   subroutine rough_cap_reach(params, delta_max, error)
      type(contact_params), intent(in) :: params   !< a rough model with the cap
      real(dp), intent(in) :: delta_max
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: ratio, reach
      character(len=:), allocatable :: place, routes
      ratio = params%sigma/first_yield(params)
      reach = max_layer_reach
      if (plastic_summits(params)) reach = plastic_layer_reach
      if (.not. (ratio <= small_cap_sigma .and. delta_max > reach*params%sigma)) return
      call rough_cap_where(params, delta_max, place)
      call rough_cap_routes(ratio, routes)
      call fatal_error(error, egw_unsupported, "delta_max = "//format_real(delta_max)// &
         & ": rough + cap tables beyond "//sci3(reach)//" sigma at "// &
         & "sigma/delta_y <= "//sci3(small_cap_sigma)//" do not build (here "// &
         & place//"; their unloading solves stall or need "// &
         & "more than the mesh's nodes, the rough layer being ~(sigma/delta)^(2/3) of the "// &
         & 'contact radius wide: doc/stability.md "Stop 51 (tiny17)"): take delta_max <= '// &
         & format_real(reach*params%sigma)//", or "//routes)
   end subroutine rough_cap_reach

   !> "sigma/delta_y = r (first yield delta_y = d), delta_max = x sigma = y delta_y"
   !> (a subroutine: no deferred-length function results, see egw_text)
   subroutine rough_cap_where(params, delta_max, text)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: delta_max
      character(len=:), allocatable, intent(out) :: text
      real(dp) :: delta_y
      delta_y = first_yield(params)
      text = "sigma/delta_y = "//sci3(params%sigma/delta_y)//" (first yield delta_y"// &
         & " = "//sci3(delta_y)//"), delta_max = "//sci3(delta_max/params%sigma) &
         & //" sigma = "//sci3(delta_max/delta_y)//" delta_y"
   end subroutine rough_cap_where

   !> The routes of a rough + cap table that does not build at sigma/delta_y = ratio:
   !> Hertz + cap, the rough model's sigma -> 0 limit, with its bound (doc/theory.md
   !> section 12's table: the rough layer moves the loading force by ~0.15
   !> (sigma/delta_y)**(2/3) of it; near the residual overlap the unloading force by ~8.3
   !> (sigma/delta_y)**(2/3) of its own, doc/stability.md "Stop 49 (resid15)"), or single
   !> solves.
   subroutine rough_cap_routes(ratio, text)
      real(dp), intent(in) :: ratio   !< sigma/delta_y
      character(len=:), allocatable, intent(out) :: text
      real(dp) :: s23
      s23 = ratio**(2.0_dp/3.0_dp)
      text = "give sigma = 0 (or model Hertz) for the Hertz + cap table, the rough model's sigma -> 0 "// &
         & "limit: the rough layer moves the loading force by ~0.15 (sigma/delta_y)^(2/3)"// &
         & " = "//sci3(0.15_dp*s23)//" of it, the unloading force near the residual "// &
         & "overlap by ~8 (sigma/delta_y)^(2/3) = "//sci3(8.0_dp*s23)//" of its own;"// &
         & " or solve the contacts one by one (solve_unload, egw_solve_unload, restitution)"
   end subroutine rough_cap_routes

   !> x as ES10.3 writes it, for messages (a length from a specification function, not
   !> a deferred one: see egw_text).
   pure function sci3(x) result(str)
      real(dp), intent(in) :: x   !< any double
      character(len=real_text_len(x, 3, 2)) :: str
      str = real_text(x, 3, 2)
   end function sci3

   ! ---------------------------------------------------------------------------------------

   !> The unloading curves of Hertz + cap (doc/theory.md §12): turning points from the
   !> first capped one (cap_first_turn, delta_y (1 + 1e-4): up to it the cap solver's
   !> contact is Hertz's, reversible) to delta_max, 9 at first,
   !> then refine_m; L(m) = m - residual overlap and s_max = 1, so that s = 1 is where the
   !> unloading force vanishes on every curve (the one place where the curves are not
   !> smooth: (delta - delta_r)**(3/2) there), and the evaluation gives 0 below it.
   subroutine build_cap_curves(table, options, error, progress)
      type(hysteresis_table), intent(inout) :: table
      type(solver_options), intent(in) :: options
      type(egw_error), allocatable, intent(out) :: error
      procedure(table_progress), optional :: progress
      type(unloading_curve), allocatable :: curves(:)
      real(dp), allocatable :: m(:)
      real(dp) :: delta_y
      integer :: j, n
      ! (from the first capped turning point: up to it the solves are Hertz's; from first
      ! yield where the table ends within 1e-9 of it, which has no room for a grid)
      delta_y = cap_first_turn(table%params)
      if (.not. table%delta_max - delta_y > 1.0e-9_dp*delta_y) delta_y = &
         & first_yield(table%params)
      n = 9
      m = delta_y + (table%delta_max - delta_y)*[(real(j, dp), j = 0, n - 1)]/real(n - 1, dp)
      m(1) = delta_y
      m(n) = table%delta_max
      table%s_max = 1.0_dp
      ! the curves store u = P/P_load(m) (force_ratio; format version 5)
      table%force_ratio = .true.
      allocate (curves(n))
      if (present(progress)) call progress(0, 2*n - 1)
      call build_curves(table, options, m, .false., curves, error)
      if (allocated(error)) return
      call refine_m(table, options, .false., m, curves, error, progress)
      if (allocated(error)) return
      call resample(table, m, curves)
      call fine_lengths(table, curves, error)
      if (allocated(error)) return
      call hysteresis_prepare(table)
   end subroutine build_cap_curves

   !> The fine delta_max grid of a force_ratio table for L(m) = m - residual overlap
   !> (cap_length: the cap model's, no unloading solve): from the table's nodes (their
   !> curves' lengths), each interval bisected until 1/L's cubic Lagrange on the grid (the
   !> evaluation's, fine_inv_span) meets cap_length at its midpoint within fine_length_tol
   !> rel_tol relative (the midpoint's value kept as a node where it does not), the
   !> midpoints of a pass solved in parallel. Intervals narrower than min_width**2 of the
   !> range are not split (first yield, where delta_r(m) sets in, aside: not reached on
   !> the suite's tables).
   subroutine fine_lengths(table, curves, error)
      type(hysteresis_table), intent(inout) :: table
      type(unloading_curve), intent(in) :: curves(:)
      type(egw_error), allocatable, intent(out) :: error
      real(dp), allocatable :: x(:), l(:), mid(:), l_mid(:), new_x(:), new_l(:), gam(:), &
         & g_mid(:), new_g(:)
      real(dp), allocatable :: new_lm(:), new_gm(:)
      logical, allocatable :: done(:), split(:), new_done(:), fresh(:), solved(:), &
         & new_solved(:)
      integer, allocatable :: stats(:)
      character(len=256), allocatable :: messages(:)
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
         call first_failure(stats, messages, error)
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

   !> Whether the flow-pressure cap acts on the loading of a rough sphere up to delta_max:
   !> the largest total pressure of the loading solve there (at the curves' tolerance)
   !> reaches p_y (the cap holds it at p_y; rounding aside, 1e-9 below counts).
   subroutine cap_reached(params, options, rel_tol, delta_max, reached, error)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: rel_tol, delta_max
      logical, intent(out) :: reached
      type(egw_error), allocatable, intent(out) :: error
      type(solve_result) :: res
      reached = .false.
      call solve_contact(params, curve_options(options, rel_tol), delta_max, res, error)
      if (allocated(error)) return
      reached = res%max_pressure >= (1.0_dp - 1.0e-9_dp)*params%flow_pressure
   end subroutine cap_reached

   !> EP-GW with yielding summits (psi > 0): dissipative without the cap.
   elemental logical function plastic_summits(params)
      type(contact_params), intent(in) :: params
      plastic_summits = params%model == model_epgw .and. params%psi > 0.0_dp
   end function plastic_summits

   !> The first yield m_y of a rough sphere with the cap (elastic summits): the overlap in
   !> (lo, hi) where the loading solve's largest total pressure reaches p_y (cap_reached at
   !> hi), by bisection to 6e-8 of hi - lo: turning points below it unload on the loading
   !> curve (a misplaced m_y leaves out only the hysteresis of turning points that close
   !> above it, which starts from 0 at m_y; doc/theory.md section 12).
   subroutine rough_first_yield(params, options, rel_tol, lo, hi, m_y, error)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: rel_tol, lo, hi
      real(dp), intent(out) :: m_y
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: a, b, mid
      logical :: reached
      integer :: it
      a = lo
      b = hi
      do it = 1, 24
         mid = 0.5_dp*(a + b)
         call cap_reached(params, options, rel_tol, mid, reached, error)
         if (allocated(error)) return
         if (reached) then
            b = mid
         else
            a = mid
         end if
      end do
      m_y = a
   end subroutine rough_first_yield

   !> L(m) of a rough model with the cap: unloading_length of the cap-free loading solve at
   !> m, less (shift: where the cap acts below the table's delta_max) the smooth cap
   !> model's residual overlap delta_r(m) (0 up to first yield delta_y; cap_length). The
   !> capped solve's loading stiffness holds its capped set fixed and converges slowly
   !> (doc/theory.md section 12, Limits): L from it jumped by 5 % between neighbouring
   !> turning points, which no bisection in m removes; the cap-free L is smooth in m, and
   !> equal to the capped one where the cap does not act. The shift puts the knee of every
   !> curve, where the unloading contact separates near delta_r, at about one s (1/s_max,
   !> as the Hertz + cap curves' residual overlap at s = 1): with the cap-free L alone it
   !> moved from s = 0.48 to 0.29 between 1.2 and 5.7 delta_y (E-GW, sigma = delta_y/100),
   !> the curves' cubics in m met it at every s and the delta_max grid at 1e-4 needed 81
   !> nodes, its midpoint mismatch falling only ~h**1.5 (doc/benchmarks.md, stop 43).
   !> delta_r (C1 at delta_y, smooth above) keeps L smooth in m.
   subroutine rough_length(params, options, m, shift, length, error)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: m
      logical, intent(in) :: shift
      real(dp), intent(out) :: length
      type(egw_error), allocatable, intent(out) :: error
      type(contact_params) :: free
      type(solve_result) :: res
      real(dp) :: smooth
      free = params
      free%flow_pressure = 0.0_dp
      length = params%sigma
      call solve_contact(free, options, m, res, error)
      if (allocated(error)) return
      length = unloading_length(res%force, res%stiffness, params%sigma)
      if (.not. (shift .and. m > first_yield(params))) return
      call cap_length(params, m, smooth, error)
      if (allocated(error)) return
      ! (L_free >= m on the rough models: never below the smooth cap's m - delta_r)
      length = max(length - (m - smooth), smooth)
   end subroutine rough_length

   !> The unloading length of a Hertz + cap curve of turning point m: m minus the residual
   !> overlap of cap_load (on the public solves' options; cap_residual, the same value
   !> without the unloading's parts); m at and below first yield (Hertz: the residual
   !> overlap is 0).
   subroutine cap_length(params, m, length, error, gamma)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: m
      real(dp), intent(out) :: length
      type(egw_error), allocatable, intent(out) :: error
      !> cap_residual's start of c/a (0: its own), out: the solution's
      real(dp), intent(inout), optional :: gamma
      real(dp) :: residual, delta_y, a_y, force_y
      call cap_residual(params%radius, params%modulus, params%flow_pressure, m, &
         & cap_solve_options(), residual, error, gamma)
      if (allocated(error)) return
      call cap_units(params%radius, params%modulus, params%flow_pressure, delta_y, a_y, &
         & force_y)
      length = m - residual*delta_y
   end subroutine cap_length

   !> Bisect the delta_max intervals until, for each, the Lagrange combination of its
   !> stencil's curves meets the midpoint's own curve at every node of that curve within
   !> rel_tol. A midpoint's curve is a check curve: solved at the union of its two
   !> neighbours' s nodes (where their bisection found the curves need nodes; log-ratio
   !> curves: the nodes both hold, less check_skip's), not
   !> bisected itself (a node's curve costs twice its nodes in solves, one check solve an
   !> interval: the EP-GW table at 1e-4 of egw-bench 3933 -> 3100 solves). Check curves
   !> are kept until their interval is split, then bisected from the first nodes as a
   !> node's curve is (refine_curve, taking the check solves it meets: the same curve)
   !> and rechecked when the stencil changed: only new midpoints cost solves.
   subroutine refine_m(table, options, shift, m, curves, error, progress)
      type(hysteresis_table), intent(inout) :: table
      type(solver_options), intent(in) :: options
      logical, intent(in) :: shift   !< rough_length's
      real(dp), allocatable, intent(inout) :: m(:)
      type(unloading_curve), allocatable, intent(inout) :: curves(:)
      type(egw_error), allocatable, intent(out) :: error
      procedure(table_progress), optional :: progress
      type(unloading_curve), allocatable :: mids(:), new_curves(:), new_mids(:), built(:)
      real(dp), allocatable :: new_m(:), err_mid(:)
      logical, allocatable :: have_mid(:), new_have(:), wide(:)
      integer, allocatable :: idx(:), promoted(:)
      integer :: pass, j, k, n_split
      real(dp) :: m_bound
      logical, allocatable :: keep(:)
      ! the bound at the check curves' nodes: rel_tol; with the two-piece map rel_tol/2,
      ! for what falls between those nodes (E-GW + cap, 1e-4: 28 delta_max nodes with
      ! rel_tol met 1.2e-4 of P(m) off main's table between a check curve's s nodes, at
      ! s = 0.17 of m = 333 sigma, where main's 62 nodes erred by 5e-5 against 1e-6 solves)
      m_bound = table%rel_tol
      if (table%mapped) m_bound = 0.5_dp*table%rel_tol
      allocate (mids(size(m) - 1), have_mid(size(m) - 1))
      have_mid = .false.
      do pass = 1, 30
         idx = pack([(j, j = 1, size(m) - 1)], .not. have_mid)
         if (size(idx) > 0) then
            ! check curves, solved at their neighbours' nodes (the grid in s that the
            ! neighbours' bisection found; refine_curve completes one that becomes a node)
            allocate (built(size(idx)))
            ! (but s = 0, where every gap is 0 and so is the mismatch: its solve gives
            ! only the slope, which the check does not use)
            do k = 1, size(idx)
               if (log_table(table)) then
                  ! (log-ratio: the nodes both neighbours hold, where their values are
                  ! solves and the mismatch is the interpolation's in delta_max; a node of
                  ! one of them alone is its own bisection's, checked there to rel_tol/4:
                  ! egw-bench's table at 1e-4 58 x 75 nodes against 59 x 75 with the
                  ! union, build CPU -6 %, far_errors passing, the [-2, 3] sigma table's
                  ! 7.2e-5 -> 8.1e-5 (doc/benchmarks.md, stop 48))
                  call shared_nodes(curves(idx(k))%s, curves(idx(k) + 1)%s, built(k)%s)
               else
                  call merge_nodes(curves(idx(k))%s, curves(idx(k) + 1)%s, built(k)%s)
               end if
               built(k)%s = pack(built(k)%s, built(k)%s > 0.0_dp)
               ! (six-point log-ratio stencils: not where four points meet check_skip)
               if (log_table(table) .and. size(m) >= 6) then
                  allocate (keep(size(built(k)%s)))
                  do j = 1, size(built(k)%s)
                     keep(j) = check_weight(curves(idx(k)), curves(idx(k) + 1), &
                        & built(k)%s(j))*order_gap(table, m, curves, idx(k), &
                        & built(k)%s(j)) >= check_skip*m_bound
                  end do
                  built(k)%s = pack(built(k)%s, keep)
                  deallocate (keep)
               end if
            end do
            call build_curves(table, options, 0.5_dp*(m(idx) + m(idx + 1)), shift, built, &
               & error, check=.true.)
            if (allocated(error)) return
            do k = 1, size(idx)
               call move_curve(built(k), mids(idx(k)))
            end do
            deallocate (built)
            have_mid = .true.
         end if
         allocate (err_mid(size(m) - 1), wide(size(m) - 1))
         do j = 1, size(m) - 1
            ! (Hertz + cap: the force's error, the loading table's share included)
            if (table%force_ratio) then
               err_mid(j) = whole_mismatch(table, m, curves, j, mids(j))
            else
               err_mid(j) = stencil_mismatch(table, m, curves, j, mids(j))
            end if
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
         n_split = count(err_mid > m_bound .and. wide)
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
         if (size(m) + n_split > max_m_nodes) then
            call fatal_error(error, egw_not_converged, "hysteresis table: rel_tol = "// &
               & format_real(table%rel_tol)//" not reached: more than "// &
               & format_real(real(max_m_nodes, dp))//" delta_max nodes needed, the largest "// &
               & "mismatch between them still "//format_real(maxval(err_mid)))
            return
         end if
         allocate (new_m(size(m) + n_split), new_curves(size(m) + n_split), &
            & new_mids(size(m) + n_split - 1), new_have(size(m) + n_split - 1))
         new_have = .false.
         allocate (promoted(n_split))
         n_split = 0
         k = 0
         do j = 1, size(m)
            k = k + 1
            new_m(k) = m(j)
            call move_curve(curves(j), new_curves(k))
            if (j == size(m)) exit
            if (err_mid(j) > m_bound .and. wide(j)) then
               k = k + 1
               new_m(k) = 0.5_dp*(m(j) + m(j + 1))
               call move_curve(mids(j), new_curves(k))
               n_split = n_split + 1
               promoted(n_split) = k
            else
               call move_curve(mids(j), new_mids(k))
               new_have(k) = .true.
            end if
         end do
         call move_alloc(new_m, m)
         call move_alloc(new_curves, curves)
         call move_alloc(new_mids, mids)
         call move_alloc(new_have, have_mid)
         deallocate (err_mid, wide)
         ! the new nodes: bisected in s as every node's curve
         call verify_curves(table, curves, promoted, error)
         if (allocated(error)) return
         deallocate (promoted)
      end do
      call fatal_error(error, egw_not_converged, "hysteresis table: rel_tol = "// &
         & format_real(table%rel_tol)//" not reached: the delta_max grid did not settle "// &
         & "after 30 bisections")
   end subroutine refine_m

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
         ! weighted as in refine_curve: the local force's tolerance down to local_floor
         ! P(m) between the node curves too)
         if (table%force_ratio) then
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

   !> Whether the table's curves are log-ratio curves (build_hysteresis sets it: EP-GW
   !> without the cap or with a cap that does not act; curves on which the cap acts,
   !> whose force is 0 below a residual overlap, keep the gap).
   elemental logical function log_table(table)
      type(hysteresis_table), intent(in) :: table
      log_table = table%log_ratio
   end function log_table

   !> The overlap where the loading table's force falls to rel_tol of its reference force
   !> (bisection on the monotone table; its cut-off if the force there is larger).
   pure real(dp) function unloading_floor(loading, rel_tol) result(floor)
      type(force_table), intent(in) :: loading
      real(dp), intent(in) :: rel_tol
      real(dp) :: lo, hi, mid, f, k
      integer :: it
      lo = loading%cutoff
      hi = loading%delta_max
      floor = lo
      if (loading%force(1) >= rel_tol*loading%reference_force) return
      do it = 1, 100
         mid = 0.5_dp*(lo + hi)
         if (.not. (mid > lo .and. mid < hi)) exit
         call table_eval(loading, mid, f, k)
         if (f < rel_tol*loading%reference_force) then
            lo = mid
         else
            hi = mid
         end if
      end do
      floor = lo
   end function unloading_floor

   !> L(m) of the curves at m(:) (a loading solve each, in parallel; its history is kept
   !> in the curve for build_curves).
   subroutine unloading_lengths(table, options, m, shift, curves, error)
      type(hysteresis_table), intent(in) :: table
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: m(:)
      logical, intent(in) :: shift   !< rough_length's
      type(unloading_curve), intent(inout) :: curves(:)
      type(egw_error), allocatable, intent(out) :: error
      type(solver_options) :: serial
      integer :: stats(size(m)), j
      character(len=256) :: messages(size(m))
      serial = curve_options(options, table%rel_tol)
      stats = 0
      !$omp parallel do schedule(dynamic) default(shared) private(j)
      do j = 1, size(m)
         call one_length(j)
      end do
      !$omp end parallel do
      call first_failure(stats, messages, error)
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

   !> The options of one curve's solves: serial (the parallelism is over the curves), at
   !> hysteresis_solve_tol (a decade finer than the table's tolerance rel_tol).
   pure function curve_options(options, rel_tol) result(serial)
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: rel_tol
      type(solver_options) :: serial
      serial = options
      serial%n_threads = 1
      serial%rel_tol = hysteresis_solve_tol(options, rel_tol)
   end function curve_options

   !> The first failure of a parallel loop over curves (stats(j) /= 0, with its message) as
   !> error: the lowest j wins, whatever the threads' order.
   pure subroutine first_failure(stats, messages, error)
      integer, intent(in) :: stats(:)
      character(len=*), intent(in) :: messages(:)
      type(egw_error), allocatable, intent(out) :: error
      integer :: j
      do j = 1, size(stats)
         if (stats(j) /= 0) then
            call fatal_error(error, stats(j), trim(messages(j)))
            return
         end if
      end do
   end subroutine first_failure

   !> L = 1.5 P/K_unload: m minus the residual overlap of Hertzian unloading
   !> P (1 - (m - delta)/L)^{3/2}, and 1.5 times the decay length of the separated tail
   !> (P ~ exp(-(m - delta) K/P)): r(s) changes little with m at fixed s = (m - delta)/L.
   !> sigma where the force has underflowed.
   pure real(dp) function unloading_length(force, stiffness, sigma) result(length)
      real(dp), intent(in) :: force, stiffness, sigma
      length = sigma
      if (force > 0.0_dp .and. stiffness > 0.0_dp) length = 1.5_dp*force/stiffness
      if (.not. (length > 0.0_dp .and. length < huge(1.0_dp))) length = sigma
   end function unloading_length

   !> The unloading curves of the delta_max values m(:), in parallel (OpenMP; every curve
   !> is independent: its own loading history and solves); the first error wins. A curve
   !> whose history is loaded already (unloading_lengths) keeps it. check: solve each
   !> curve at the s nodes curves(j)%s holds (refine_m's check curves), without bisection.
   subroutine build_curves(table, options, m, shift, curves, error, check)
      type(hysteresis_table), intent(inout) :: table
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: m(:)
      logical, intent(in) :: shift   !< rough_length's
      type(unloading_curve), intent(inout) :: curves(:)
      type(egw_error), allocatable, intent(out) :: error
      logical, intent(in), optional :: check
      type(solver_options) :: serial
      real(dp) :: worst(size(m))
      integer :: stats(size(m)), j
      character(len=256) :: messages(size(m))
      logical :: only_check
      only_check = .false.
      if (present(check)) only_check = check
      serial = curve_options(options, table%rel_tol)
      stats = 0
      worst = 0.0_dp
      !$omp parallel do schedule(dynamic) default(shared) private(j)
      do j = 1, size(m)
         call one_curve(j)
      end do
      !$omp end parallel do
      call first_failure(stats, messages, error)
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
      type(hysteresis_table), intent(inout) :: table
      type(unloading_curve), intent(inout) :: curves(:)
      integer, intent(in) :: idx(:)
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: worst(size(idx))
      integer :: stats(size(idx)), k
      character(len=256) :: messages(size(idx))
      stats = 0
      worst = 0.0_dp
      !$omp parallel do schedule(dynamic) default(shared) private(k)
      do k = 1, size(idx)
         call one_verify(k)
      end do
      !$omp end parallel do
      call first_failure(stats, messages, error)
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
         if (.not. allocated(err)) call refine_curve(table, curves(idx(k)), worst(k), err, &
            & known)
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
         call load_history(table%params, options, m, curve%hist, res, error, &
            & table%loading_law, stiffness=.false.)
         if (allocated(error)) return
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
   !> (m - knee)/s_knee as its length (s_max = 1) and the pieces' slope scales.
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
      type(hysteresis_table), intent(in) :: table
      type(unloading_curve), intent(in) :: curve
      real(dp), intent(in) :: s
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
   !> done before (a check curve's), taken instead of solving again at their s.
   subroutine refine_curve(table, curve, worst, error, known)
      type(hysteresis_table), intent(in) :: table
      type(unloading_curve), intent(inout) :: curve
      real(dp), intent(out) :: worst
      type(egw_error), allocatable, intent(out) :: error
      type(unloading_curve), intent(in), optional :: known
      real(dp) :: s(max_s_nodes), gap(max_s_nodes), slope(max_s_nodes), &
         & weight(max_s_nodes), r_mid, d_mid, r_int, d_int, s_mid, err, w_mid, width, dxi, &
         & xi_mid, w_int
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
               s(i + 1) = s_mid
               gap(i + 1) = r_mid
               slope(i + 1) = d_mid
               weight(i + 1) = w_mid
               n = n + 1
               refined = .true.
               i = i + 1   ! the new left half is checked in the next sweep
            else
               checked(i) = .true.
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
      !> P_load(m)/max(P, local_floor P(m)) (Hertz + cap), else 1
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

   !> Put every curve on the union of their s nodes: the union refines each curve's own
   !> nodes, so the Hermite data there reproduce each curve's cubics exactly.
   pure subroutine resample(table, m, curves)
      type(hysteresis_table), intent(inout) :: table
      real(dp), intent(in) :: m(:)
      type(unloading_curve), intent(in) :: curves(:)
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

   !> Cubic Hermite r and dr/ds of a curve at s in [0, 1].
   pure subroutine curve_eval(curve, s, r, dr, stored)
      type(unloading_curve), intent(in) :: curve
      real(dp), intent(in) :: s
      real(dp), intent(out) :: r, dr
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
      call move_alloc(from%s, to%s)
      call move_alloc(from%gap, to%gap)
      call move_alloc(from%slope, to%slope)
   end subroutine move_curve

end submodule egw_hysteresis_build
