!> The on-disk cache of table builds: a build that was done once (same parameters, range,
!> tolerance and solver options, same egw) is read back instead of solved again, so that
!> a DEM or LAMMPS run that builds its tables at start-up pays for them once per machine.
!> Entries are the tables' own checksummed binary files, written atomically (egw_io) under
!> a name hashed from everything the build depends on; one that is missing, corrupt, or
!> does not match the request field by field is ignored and rebuilt. The key includes the
!> solver's SIMD path (egw_simd: AVX2 + FMA or the baseline), whose tables differ in their
!> last digits, so that a cache shared between machines hands each path its own bits.
!> The cache directory is EGW_CACHE_DIR, else $XDG_CACHE_HOME/egw, else
!> $HOME/.cache/egw; EGW_CACHE_DIR=off turns it off. A cache that cannot be written costs
!> nothing but the rebuild.
module egw_cache
   use, intrinsic :: iso_fortran_env, only: int64
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_version, only: egw_version_number
   use egw_io, only: make_directories
   use egw_simd, only: simd_level
   use egw_params, only: contact_params, refuse_flow_pressure
   use egw_rough_sphere, only: solver_options
   use egw_table, only: force_table, build_table, table_progress
   use egw_table_universal, only: universal_table, build_universal
   use egw_hysteresis, only: hysteresis_table, build_hysteresis
   use egw_tolerance_probe, only: probe_hysteresis_tolerance, probe_hysteresis_size
   use egw_table_format, only: write_table, read_table, write_universal, read_universal, &
      & format_binary
   use egw_hysteresis_format, only: write_hysteresis, read_hysteresis
   implicit none
   private

   public :: cache_directory, build_table_cached, build_universal_cached, &
      & build_hysteresis_cached, fnv1a_mix

   !> Bumped whenever a build's algorithm changes what it produces, so that entries of an
   !> earlier build (same parameters) are not taken for the new one (5: the smooth Hertz +
   !> cap solver; 6: the hysteresis build's check curves, whose tables at 1e-5 differ, and
   !> the rough + cap solver's meshes, 2026-11-29; 7: rough + cap unloading after a capped
   !> loading, a_max an element edge, and the guided route at small sigma/delta_y; 8: rough
   !> + cap unloading solves confirmed by a level more, the capped loading table's slope
   !> check; 9: that unloading with halving layers inside the Hertz edge and a bisection
   !> check; 10: the hysteresis build's first delta_max grid above 0, five nodes, not nine,
   !> in tables without the cap; 11: unloading deep in the cap with the plastic zone's rim
   !> an element edge with layers, and converged solves at sigma/delta_y <= 1e-7 checked
   !> against the asymptotic route; 12: rough + cap hysteresis tables' L(m) less the smooth
   !> cap's residual overlap where the cap acts; 13: histories at sigma/delta_y <= 1e-6 by
   !> the asymptotic route where their loading fails or its check replaces it; 14: that
   !> route's wide histories at rel_tol <= 1e-6 and its unloading one order further near
   !> the residual overlap; 15: unloading solves' locating solve warm-started from the
   !> curve's last solve, lu_factor's rank-2 updates and the Jacobian's columns in one
   !> pass: forces moved by <= 5.2e-9 of themselves, tables by <= 5.9e-8 of P(m); 16:
   !> rough + cap tables with elastic summits on the two-piece s map, format version 4;
   !> 17: rough + cap unloading meshes reach past the plastic rim also where it lies
   !> within the Hertz edge's layers; 18: the small-sigma route's wide histories at
   !> rel_tol >= 1e-7, and at 1e-7 for a history the route loaded: route answers at
   !> sigma/delta_y <= 1e-6 move within their estimates; 19: rough + cap tables with
   !> plastic summits on the two-piece s map too (turning points at or below 0 on its
   !> tail), every mapped table's slopes stored as dg/dx times tail_length; 20: EP-GW
   !> hysteresis tables without the cap store ln(P_load/P) on the edge map, to rel_tol of
   !> the local force (format version 3), their delta_max intervals at m = 0 split down to
   !> 1/32 of the others' width limit; 21: both of 19 and 20 (branch local10's 19 and 20
   !> had the log-ratio tables without 19's map, main's 19 not the log-ratio tables);
   !> 22: rough + cap unloading's plastic shift in the deep zone from one root of law = p_y
   !> per mesh (flow_cap's plastic_shifts): tables moved by <= 4.3e-15 of P(m), same grids;
   !> 23 (main): unloading with elastic summits (GW, E-GW, with or without the cap) takes
   !> Newton's chord steps: rough + cap tables moved by <= 5.3e-9 of P(m), same grids;
   !> 23 (branch local12): the log-ratio curves' s bisection weighted by the largest weight
   !> of each interval (ends and middle), not the middle's; 24 (branch local13): local12's
   !> 23 with main's 22, the log-ratio curves on six-point stencils in delta_max; 25: their
   !> check curves not solved where four points meet check_skip (hysteresis_build); 26:
   !> both of 25 and main's 23; 25 (main): the loading law's series panel by reciprocals
   !> (egw_gauss series_panel: F values move by <= 5 ulp): the EP-GW + cap table of issue
   !> 32 moved by <= 9.7e-10 relative in its gaps, same grids; 27 (branch local14): local13's
   !> 26 with main's 25; 28: log-ratio curves' s midpoints accepted on an embedded
   !> estimate (midpoint_skip) and delta_max splits deferred beside larger misses
   !> (split_defer; hysteresis_build): other grids; 29: their check curves solved at the
   !> s nodes both neighbours hold (not the union) (branch local14); 27 (main): unloading
   !> after a capped loading (extended models, sigma/delta_y >= 1e-5) grades a
   !> central-disc contact's elements about its edge on every level (sphere_solver's
   !> central_disc): rough + cap tables moved; 28 (main): rough + cap unloading's
   !> central-disc route up to a disc edge of 0.5 a (was 0.25); 29: main's 28 with branch
   !> local14's log-ratio tables (its 29); 30 (main): unloading after a capped loading
   !> refines a central disc inside an innermost kink below a/2 with the step at
   !> sigma/delta_y >= 1e-3 (sphere_solver's disc_split, branch mesh13's, via rcost15):
   !> rough + cap tables moved; 31 (main): gap curves hold the unloading solve over c =
   !> P_solve(m)/P_table(m) (was: the loading force times c), Hertz + cap curves bisected
   !> in s relative to the local force (capl15); 32 (main): rough + cap unloading solves
   !> that stalled converge by sphere_solver's fallbacks (skipped levels, kink edges kept,
   !> unloading_descent; GW + cap loading unrefocused; tbl15): tables that failed build,
   !> others whose solves had stalled on a route moved (E-GW + cap at sigma/delta_y = 2e-4
   !> to 12 delta_y at 1e-3: 3.6e-7 of P(m)); 34 (gw16): classic GW unloading after
   !> a capped loading takes one confirming level more at sigma/delta_y <= 1e-3, and a
   !> tail-grown mesh that stalled is solved again from the last attempt: GW + cap tables
   !> there moved; 33 was capu16's Hertz + cap force ratio, format 5 (other models' not; README's GW + cap build at 1e-2 byte-identical);
   !> 35 (psi17): the cap's root of law = p_y solved once per problem (flow_cap's
   !> prepare): rough + cap tables move by rounding (EP-GW + cap psi 1: 3.2e-15 of P(m));
   !> 36 (audit17): the small-sigma route (rough + cap, sigma/delta_y <= ~1e-6) reports
   !> the rough solver's a* as contact radius (was: extrapolated towards the smooth cap's
   !> edge a); forces unchanged, the loading tables' contact radii there moved.
   !> 37 (mesh17): unloading after a capped loading (extended models) halves on every
   !> level the elements it keeps of the level before, in place of the accepted level's
   !> bisection check (sphere_solver's halved_levels): rough + cap tables moved (E-GW +
   !> cap to 6 delta_y at 1e-4: 5.1e-6 of P(m)).
   !> 38 (edge17): a rough history's field d_max(r) is loaded at 0.1 of rel_tol
   !> (load_history): every rough hysteresis table moved (README's E-GW + cap to 6
   !> delta_y at 1e-4: gaps by up to 3.0e-6, the same 37 x 50 grid).
   !> 39 (doubt18): Hertz + cap tables start their curves at the first capped turning
   !> point (cap_first_turn) and split delta_max intervals down to 2^-18 of the range:
   !> other grids near first yield (1e-4 to 20 delta_y: 47 -> 58 delta_max nodes).
   !> 40 (zmc18): EP-GW hysteresis tables (psi > 0) unload with the ZMC loading law
   !> tabulated once per build (egw_law_pieces): README's EP-GW + cap psi 1 table to 6
   !> delta_y at 1e-4 moved by up to 3.3e-9 of P(m), the same grid.
   !> 41 (doubt19): Hertz + cap tables split delta_max intervals down to 2^-24 delta_y
   !> (was 2^-18 of the range) on the force's whole error, their loading table built to
   !> rel_tol/4: other grids from 20 delta_y at 1e-4, everywhere at 1e-5.
   !> 42 (zu19): EP-GW + cap tables (psi > 0) unload their deep plastic zone with Z_u
   !> tabulated at h_y (egw_unloading's tabulate_unloading): README's psi 1 table to 6
   !> delta_y at 1e-4 moved by up to 3.2e-15 of P(m), the same grid.
   !> 43 (stiff19): rough + cap loading stiffness (the Hermite slopes of rough + cap
   !> loading tables) from the accepted mesh moved with its kinks (egw_sphere_moving_mesh)
   !> 44 (doubt20): rough + cap tables' max_error bounds the error between the check
   !> curves' s nodes (hysteresis_build's gap_bound) and adds the solves' rel_tol: the
   !> stored max_error changes, the grids and curves do not.
   !> 45 (psi20): EP-GW histories (psi > 0) load with the ZMC law tabulated once per
   !> build (egw_law_pieces, as their unloading): README's EP-GW + cap psi 1 table to 6
   !> delta_y at 1e-4 moved by up to 4.2e-9 of P(m), the same grid.
   !> 46 (asm21): on AVX2 + FMA the half-space's log-product weights of near pieces are
   !> computed four lanes wide (egw_simd_log_piece): coefficients move in their last
   !> digits, so do the AVX2 path's tables (the baseline's are unchanged).
   !> 47 (psi21): EP-GW unloading solves (psi > 0) take Newton's chord steps, with the cap
   !> and without: README's psi 1 + cap table moved by up to 3.6e-9 of P(m), EP-GW psi 1
   !> to 30 sigma by 3.3e-10, the same grids; and their loading tables solve on the
   !> build's tabulated ZMC law (as their curves): psi 1 + cap 1.7e-11 more.
   !> 48 (dcap21): rough + cap loading stiffness (the Hermite slopes of rough + cap
   !> loading tables) on the mesh moved with its kinks at their rate (the fixed point of
   !> the kink's motion, egw_sphere_moving_mesh's follow_kink): the tables' bits change.
   !> 49 (psi22): on AVX2 + FMA the EP-GW unloading integral's nodes are evaluated four
   !> lanes wide (egw_unloading's egw_unload_integrands): Z_u moves by rounding (<= 1.9e-13),
   !> the AVX2 path's EP-GW tables with it (README's psi 1 + cap: 3.8e-15 of P(m)).
   !> 50 (kink22): rough + cap loading solves insert a cap or Hertz edge unless an element
   !> edge lies within 1 % (was 10 %) of an element of it (egw_sphere_level's
   !> loading_move_room): their meshes, histories and tables change within their rel_tol.
   !> 51 (stiff23): rough + cap loading stiffness (the Hermite slopes of rough + cap
   !> loading tables) on a derivative mesh with the layer past the cap's edge and the
   !> elements inside a split (egw_sphere_moving_mesh's steep_split), step 1e-7: the
   !> tables' bits change (forces unchanged).
   !> 52 (audit24): a table's cut-off search from a delta_min so far below the contact that
   !> 200 trisections do not reach its length scale is bracketed again from above
   !> (table_build's find_cutoff): such tables (E-GW, sigma 1e-6, delta_min -1e100: cut-off
   !> -3.8e4 at force 0, 1020 nodes) change; the others' bits do not.
   !> 53 (stop 58, build24): rough + cap builds skip the check solves that two shifted
   !> four-point stencils clear (hysteresis_grid's gap_check_skip): the promoted check
   !> curves' solves start from other solves, the tables' bits change (2e-8 of P(m)).
   !> 54 (stop 58, edge24): rough + cap loading solves of E-GW/EP-GW grade the elements
   !> inside a towards it where the capped zone reaches past a (egw_sphere_mesh's
   !> graded_inside) and end with a confirming level at every rel_tol (egw_sphere_refine):
   !> their forces, histories and tables change within their rel_tol.
   !> 55 (stop 60, grid26): rough + cap builds leave the s midpoints that an estimate
   !> clears unsolved (hysteresis_curves' gap_skip, neighbour_skip): later solves of a
   !> curve start from other solves, the tables' bits change (<= 1e-9 of P(m)).
   !> 56 (stop 61, acc27): unloading solves after a capped loading (E-GW, EP-GW + cap) sum
   !> p_s in closed form on the elements above the floor (egw_sphere_iteration's
   !> total_force): their forces and accepted levels change, so do the tables' bits.
   !> 57 (stop 62, stiff28): rough + cap loading stiffness (the Hermite slopes of rough +
   !> cap loading tables) from chord steps on the moved meshes and without stop 57's
   !> split of the elements inside a (egw_sphere_moving_mesh): the slopes move by <= 4e-8
   !> of the stiffness, the tables' bits with them (forces unchanged).
   !>     And (yield28) a rough + cap table's first yield m_y (its first turning
   !> point) by egw_rough_yield's secant to the same tolerance as the bisection before:
   !> m_y moves within 6e-8 of the bracket, so do the tables' bits.
   !> 58 (stop 63, unl29): an unloading's locating solve after a capped loading without
   !> the history's layers (egw_sphere_level's locating): other kink edges and starts,
   !> E-GW and EP-GW + cap tables within 2.5e-5 of P(m) (GW + cap unchanged).
   !>     And (node29) rough + cap builds split a delta_max interval where the bound
   !> they report (gap_bound plus the solves' rel_tol) exceeds rel_tol, not where the
   !> check curve's mismatch exceeds rel_tol/2 (egw_hysteresis_grid's refine_m): other
   !> delta_max grids (README's E-GW + cap 38 -> 36 nodes), the tables' bits with them;
   !> and their s bisection clears midpoints at neighbour_skip 0.3 (was 0.2).
   !>     And (stiffb29) the implicit stiffness of unloading solves after a capped
   !> loading (E-GW, EP-GW + cap) puts back what the Gauss sums miss at the floor
   !> (egw_sphere_iteration's floor_stiffness): the Hermite slopes near the bottom move,
   !> and with them the s midpoints the builds solve and the later solves' starts: the
   !> tables' bits change (<= 2.6e-5 of P(m) at 1e-4, forces of single solves unchanged).
   !> 59 (stop 64, lay30): unloading solves after a capped loading above rel_tol 1e-6
   !> take fewer layers inside a and a wider last layer at the rim (egw_sphere_level's
   !> floor_layer_count, rim_layer_width): E-GW and EP-GW + cap tables at 1e-4 within
   !> 1.2e-6 of P(m) of 58's (tables at tol <= 1e-5, solves at <= 1e-6, unchanged).
   !> 60 (stop 65, psi31): Z_u's integral takes wider panels in the Gaussian's tail
   !> (egw_unloading's tail_width): Z_u and dZ_u/dh move by rounding (<= 8e-16 relative),
   !> and EP-GW tables' bits with them.
   !> 61 (stop 66, umap33): rough + cap tables on the two-piece map store u =
   !> P/P_load(m) instead of the gap (format version 6, egw_hysteresis_data's
   !> ratio_on_map): other s and delta_max grids and other curves.
   !> 62 (stop 68, 0.3.6): rough + cap tables where the cap acts weigh their checks to
   !> the local force (egw_hysteresis_curves' local_weight), build their loading table
   !> to rel_tol/4 and their curves' histories to rel_tol/1000, and classic GW's
   !> unloading after a capped loading confirms its first refinement level: other grids
   !> (README's E-GW + cap at 1e-4: 179 x 157 nodes).
   integer, parameter, public :: cache_revision = 62


contains

   !> The cache directory (created if missing): EGW_CACHE_DIR, else $XDG_CACHE_HOME/egw,
   !> else $HOME/.cache/egw. dir = "" when the cache is off (EGW_CACHE_DIR=off) or no
   !> directory can be had.
   subroutine cache_directory(dir)
      character(len=:), allocatable, intent(out) :: dir   !< the directory, or ""
      character(len=:), allocatable :: base
      call environment("EGW_CACHE_DIR", dir)
      if (dir == "off") then
         dir = ""
         return
      end if
      if (len(dir) == 0) then
         call environment("XDG_CACHE_HOME", base)
         if (len(base) == 0) then
            call environment("HOME", base)
            if (len(base) > 0) base = base//"/.cache"
         end if
         if (len(base) == 0) return
         dir = base//"/egw"
      end if
      if (.not. make_directories(dir)) dir = ""
   end subroutine cache_directory

   !> build_table through the cache: the same table, read back when this build was done
   !> before. hit reports which (optional); progress as build_table's.
   subroutine build_table_cached(params, options, delta_min, delta_max, rel_tol, table, &
      & error, hit, progress)
      type(contact_params), intent(in) :: params   !< one parameter set
      type(solver_options), intent(in) :: options  !< of the solves
      real(dp), intent(in) :: delta_min, delta_max, rel_tol   !< as build_table
      type(force_table), intent(out) :: table   !< the table; empty on error
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      logical, intent(out), optional :: hit   !< true when read from the cache
      procedure(table_progress), optional :: progress   !< as build_table
      character(len=:), allocatable :: path
      type(egw_error), allocatable :: ignored
      logical :: found
      ! not in the key (params_key): refused before any cache lookup
      call refuse_flow_pressure(params, "a force table", error)
      if (allocated(error)) return
      call entry_path("table", [params_key(params), options_key(options), delta_min, &
         & delta_max, rel_tol], path)
      found = .false.
      if (len(path) > 0) then
         call read_table(path, table, ignored)
         ! (an empty table after a failed read compares as unlike any request)
         found = same_request(table%params, table%rel_tol, table%delta_max, params, &
            & rel_tol, delta_max) .and. .not. allocated(ignored)
      end if
      if (present(hit)) hit = found
      if (found) return
      call build_table(params, options, delta_min, delta_max, rel_tol, table, error, progress)
      if (allocated(error) .or. len(path) == 0) return
      call write_table(table, path, format_binary, ignored)
   end subroutine build_table_cached

   !> build_universal through the cache (arguments as build_universal).
   subroutine build_universal_cached(model, psi, hardness_coeff, plastic_ratio, options, &
      & mu_min, mu_max, x_min, x_max, rel_tol, u, error, hit, progress)
      integer, intent(in) :: model   !< model of the slices
      real(dp), intent(in) :: psi, hardness_coeff, plastic_ratio   !< EP-GW parameters
      type(solver_options), intent(in) :: options   !< of the solves
      real(dp), intent(in) :: mu_min, mu_max, x_min, x_max, rel_tol   !< as build_universal
      type(universal_table), intent(out) :: u   !< the table; empty on error
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      logical, intent(out), optional :: hit   !< true when read from the cache
      procedure(table_progress), optional :: progress   !< as build_universal
      character(len=:), allocatable :: path
      type(egw_error), allocatable :: ignored
      logical :: found
      call entry_path("universal", [real(model, dp), psi, hardness_coeff, plastic_ratio, &
         & options_key(options), mu_min, mu_max, x_min, x_max, rel_tol], path)
      found = .false.
      if (len(path) > 0) then
         call read_universal(path, u, ignored)
         found = .not. allocated(ignored)
      end if
      if (present(hit)) hit = found
      if (found) return
      call build_universal(model, psi, hardness_coeff, plastic_ratio, options, mu_min, &
         & mu_max, x_min, x_max, rel_tol, u, error, progress)
      if (allocated(error) .or. len(path) == 0) return
      call write_universal(u, path, format_binary, ignored)
   end subroutine build_universal_cached

   !> build_hysteresis through the cache: the same table, read back when this build was
   !> done before (arguments as build_hysteresis; the progress hook is called by a build
   !> only). hit reports which (optional). A build is preceded by
   !> probe_hysteresis_tolerance and probe_hysteresis_size: a rel_tol its solves cannot
   !> reach, or whose delta_max grid is estimated beyond the build's limit, fails in
   !> seconds.
   subroutine build_hysteresis_cached(params, options, delta_min, delta_max, rel_tol, &
      & table, error, progress, hit)
      type(contact_params), intent(in) :: params   !< one parameter set
      type(solver_options), intent(in) :: options  !< of the solves
      real(dp), intent(in) :: delta_min, delta_max, rel_tol   !< as build_hysteresis
      type(hysteresis_table), intent(out) :: table   !< the table; empty on error
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      procedure(table_progress), optional :: progress   !< as build_hysteresis
      logical, intent(out), optional :: hit   !< true when read from the cache
      character(len=:), allocatable :: path
      type(egw_error), allocatable :: ignored
      logical :: found
      ! flow_pressure (Hertz or a rough model + cap; params_key has model and sigma) is in
      ! the key only where it is set: the other entries keep their names
      call entry_path("hysteresis", [params_key(params), options_key(options), delta_min, &
         & delta_max, rel_tol, pack([params%flow_pressure], params%flow_pressure /= 0.0_dp)], &
         & path)
      found = .false.
      if (len(path) > 0) then
         call read_hysteresis(path, table, ignored)
         ! (an empty table after a failed read compares as unlike any request)
         found = same_request(table%params, table%rel_tol, table%delta_max, params, &
            & rel_tol, delta_max) .and. .not. allocated(ignored)
      end if
      if (present(hit)) hit = found
      if (found) return
      ! a miss: an unreachable rel_tol fails in seconds, not after the build's minutes (the
      ! probes solve rough models; a Hertz + cap build takes seconds)
      if (params%flow_pressure == 0.0_dp) then
         call probe_hysteresis_tolerance(params, options, delta_max, rel_tol, error)
         if (allocated(error)) return
         call probe_hysteresis_size(params, options, delta_min, delta_max, rel_tol, error)
         if (allocated(error)) return
      end if
      call build_hysteresis(params, options, delta_min, delta_max, rel_tol, table, error, &
         & progress)
      if (allocated(error) .or. len(path) == 0) return
      call write_hysteresis(table, path, format_binary, ignored)
   end subroutine build_hysteresis_cached

   ! ---------------------------------------------------------------------------------------

   !> The file of a cache entry: <dir>/<kind>-<16 hex digits of the key>.bin, "" when the
   !> cache is off. The key hashes the kind, egw's version, cache_revision, the SIMD path
   !> in use and values.
   subroutine entry_path(kind, values, path)
      character(len=*), intent(in) :: kind
      real(dp), intent(in) :: values(:)
      character(len=:), allocatable, intent(out) :: path
      character(len=:), allocatable :: dir
      integer(int64) :: h
      integer :: i
      call cache_directory(dir)
      path = ""
      if (len(dir) == 0) return
      h = -3750763034362895579_int64   ! the FNV-1a 64 offset basis 14695981039346656037
      do i = 1, len(kind)
         call fnv1a_mix(h, int(iachar(kind(i:i)), int64))
      end do
      call fnv1a_mix(h, int(egw_version_number, int64))
      call fnv1a_mix(h, int(cache_revision, int64))
      ! the AVX2 path's tables differ from the baseline's in their last digits: one entry
      ! per path, so that a shared cache never hands one path's bits to the other
      call fnv1a_mix(h, int(simd_level(), int64))
      do i = 1, size(values)
         call fnv1a_mix(h, transfer(values(i), h))
      end do
      path = dir//"/"//kind//"-"//hex(h)//".bin"
   end subroutine entry_path

   !> One 64-bit word into an FNV-1a hash (byte by byte; the multiply modulo 2**64).
   !> The product by the FNV prime 2**40 + 435 is formed on 32-bit halves: a signed
   !> int64 product that overflows is undefined, and gfortran -O3 folded the seven
   !> multiplies of a word's zero bytes to huge(h), whatever came before (the key then
   !> lost that word: the SIMD path's 0 and 1 gave one name).
   pure subroutine fnv1a_mix(h, word)
      integer(int64), intent(inout) :: h   !< the hash so far
      integer(int64), intent(in) :: word   !< the word mixed in, low byte first
      integer(int64), parameter :: low32 = 4294967295_int64, low24 = 16777215_int64
      integer(int64) :: lo, hi, p
      integer :: k
      do k = 0, 7
         h = ieor(h, iand(shiftr(word, 8*k), 255_int64))
         lo = iand(h, low32)
         hi = shiftr(h, 32)
         ! h*435 on the halves (each product < 2**41), plus h*2**40, whose low word is 0
         p = lo*435_int64
         hi = iand(hi*435_int64 + shiftr(p, 32) + shiftl(iand(lo, low24), 8), low32)
         h = ior(shiftl(hi, 32), iand(p, low32))
      end do
   end subroutine fnv1a_mix

   !> 16 lower-case hex digits of h.
   pure function hex(h) result(text)
      integer(int64), intent(in) :: h
      character(len=16) :: text
      character(len=16), parameter :: digits = "0123456789abcdef"
      integer :: k, d
      do k = 1, 16
         d = int(iand(shiftr(h, 4*(16 - k)), 15_int64))
         text(k:k) = digits(d + 1:d + 1)
      end do
   end function hex

   !> The fields of params in a fixed order, for the key.
   pure function params_key(p) result(v)
      type(contact_params), intent(in) :: p
      real(dp) :: v(8)
      v = [real(p%model, dp), p%radius, p%modulus, p%sigma, p%mu, p%psi, p%hardness_coeff, &
         & p%plastic_ratio]
   end function params_key

   !> The options that change a build's result (not the thread count: builds give the same
   !> table on any number of threads).
   pure function options_key(o) result(v)
      type(solver_options), intent(in) :: o
      real(dp) :: v(4)
      v = [real(o%n_radial, dp), o%rel_tol, real(o%max_iter, dp), real(o%method, dp)]
   end function options_key

   !> A cached table (parameters a, tolerance, delta_max) is the one requested (b, ...),
   !> field by field: the file's name is only a hash.
   pure logical function same_request(a, a_rel_tol, a_delta_max, b, b_rel_tol, b_delta_max)
      type(contact_params), intent(in) :: a, b
      real(dp), intent(in) :: a_rel_tol, a_delta_max, b_rel_tol, b_delta_max
      same_request = all(params_key(a) == params_key(b)) .and. a_rel_tol == b_rel_tol .and. &
         & a_delta_max == b_delta_max .and. a%flow_pressure == b%flow_pressure
   end function same_request

   !> The value of an environment variable, "" when unset.
   subroutine environment(name, value)
      character(len=*), intent(in) :: name
      character(len=:), allocatable, intent(out) :: value
      integer :: n, stat
      call get_environment_variable(name, length=n, status=stat)
      if (stat /= 0 .or. n == 0) then
         value = ""
         return
      end if
      allocate (character(len=n) :: value)
      call get_environment_variable(name, value, status=stat)
      if (stat /= 0) value = ""
   end subroutine environment

end module egw_cache
