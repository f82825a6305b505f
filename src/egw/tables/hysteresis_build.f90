!> The build of egw_hysteresis tables (src/egw/tables/hysteresis.f90, whose interface block
!> declares build_hysteresis): the delta_max grid, each node's unloading curve from
!> solves, the bisection of both to rel_tol and the resampling onto the union s grid.
!> The build driver and rough + cap refusals live here; the curves in s in
!> egw_hysteresis_curves, the delta_max grid in egw_hysteresis_grid, the lengths L(m) in
!> egw_hysteresis_lengths.
submodule (egw_hysteresis) egw_hysteresis_build
   use egw_status, only: egw_not_converged, egw_unsupported, fatal_error, format_real
   use egw_text, only: real_text, real_text_len
   use egw_params, only: validate_params, model_epgw, model_hertz
   use egw_cap_loading, only: build_cap_loading
   use egw_sphere_problem, only: deep_unloading
   use egw_law_pieces, only: law_pieces, zmc_law_pieces
   use egw_table, only: build_table, table_prepare
   use egw_hysteresis_lengths, only: cap_reached, plastic_summits, unloading_floor, &
      & curve_options
   use egw_rough_yield, only: rough_first_yield
   use egw_hysteresis_curves, only: unloading_curve, unloading_lengths, build_curves
   use egw_hysteresis_grid, only: fine_lengths, refine_m, resample
   implicit none

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
   !> Hertz + cap tables and rough + cap tables where the cap acts: the share of rel_tol
   !> given to the loading table, whose error at a turning point multiplies the whole
   !> unloading curve (P = P_load,table(m) u); for Hertz + cap refine_m
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
      real(dp) :: loading_tol
      integer :: j, n, n_above
      logical :: rough_cap, shift, acts

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
      ! a rough model: whether its cap acts on the loading up to delta_max (the largest
      ! total pressure reaches p_y), before the loading table, whose tolerance follows it
      acts = .false.
      if (rough_cap) then
         call cap_reached(params, options, rel_tol, delta_max, acts, error)
         if (allocated(error)) return
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
         ! where the cap acts the curves store u = P/P_load(m) on the two-piece map, and
         ! the table's force is P_load,table(m) u: the loading table's relative error at m
         ! is the local force's all along the curve (8e-5 at 3.3 delta_y on README's E-GW
         ! + cap table at 1e-4), so it gets a quarter of rel_tol, as Hertz + cap's; where
         ! the cap never acts the table is the cap-free one, at rel_tol
         loading_tol = rel_tol
         if (acts) loading_tol = ratio_loading_share*rel_tol
         call build_table(params, options, delta_min, delta_max, loading_tol, table%loading, &
            & error, loading_curve=rough_cap, loading=table%loading_law)
         if (allocated(error) .and. acts) call quarter_context(error, rel_tol)
         if (.not. allocated(error)) table%loading%rel_tol = rel_tol
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
      ! elastic summits: irreversible once the cap acts, i.e. once the largest total
      ! pressure reaches p_y somewhere (it grows with the overlap on loading)
      if (rough_cap .and. .not. plastic_summits(params)) table%reversible = .not. acts
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
      if (rough_cap .and. plastic_summits(params)) shift = acts
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
         ! (to 6e-8 of the bracket: turning points below m_y unload on the loading curve; a
         ! misplaced m_y leaves out only the hysteresis of those just above it, which
         ! starts from 0 at m_y; doc/theory.md section 12)
         call rough_first_yield(params, curve_options(options, rel_tol), &
            & table%loading%cutoff, delta_max, 6.0e-8_dp*(delta_max - table%loading%cutoff), &
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
      ! the curves store u = P/P_load(m) on the map (format version 6): no loading force
      ! in them, so that their cubics and the delta_max blend carry no loading-table
      ! error; 0.82x the instructions of the gap's at the same tolerance, every error
      ! band equal or lower (doc/benchmarks.md, stops 65 local31 and 66 umap33)
      table%ratio_on_map = table%mapped
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

   !> A failed rough + cap loading table, built to a quarter of the caller's rel_tol:
   !> its message names the table and says whose tolerance it quotes.
   pure subroutine quarter_context(error, rel_tol)
      type(egw_error), intent(inout) :: error   !< the loading build's error
      real(dp), intent(in) :: rel_tol           !< the caller's tolerance
      character(len=*), parameter :: caller = " (the caller's)"
      integer :: k
      if (.not. allocated(error%message)) error%message = ""
      k = index(error%message, caller)
      if (k > 0) error%message = error%message(:k - 1)//" (a quarter of the caller's "// &
         & format_real(rel_tol)//")"//error%message(k + len(caller):)
      error%message = "the capped loading table: "//error%message
   end subroutine quarter_context

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

end submodule egw_hysteresis_build
