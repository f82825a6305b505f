!> A quick look, before a long build, at whether it can reach its tolerance (issue 22
!> item 5: a 1e-6 hysteresis table ran 21.6 min before one of its solves gave up). A few
!> solves of the kind the build needs, at its own solve tolerance, and for tight
!> tolerances a pilot table at 1e-3 whose delta_max grid, grown to the requested rel_tol,
!> estimates the build's: a failure there fails the build at once, in the caller's terms.
!> A probe that passes promises nothing (the build may still meet a solve that fails or
!> a limit; its message then quotes the caller's rel_tol too).
module egw_tolerance_probe
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_not_converged, format_real, fatal_error, int_str
   use egw_params, only: contact_params, model_epgw
   use egw_rough_sphere, only: solver_options, solve_result, solve_contact, &
      & solve_contact_unload
   use egw_hysteresis, only: hysteresis_table, build_hysteresis
   implicit none
   private

   public :: probe_hysteresis_tolerance, probe_hysteresis_size, hysteresis_solve_tol, &
      & m_node_limit

   !> The most delta_max nodes a hysteresis build may place (m_node_limit; u curves on
   !> the two-piece map: mapped_m_node_limit).
   integer, parameter, public :: build_m_node_limit = 400
   !> The most delta_max nodes of a table whose curves store u on the two-piece map
   !> (rough + cap where the cap acts): its check weighs a mismatch by the local force,
   !> up to 1/(1.5e-3) near the contact's front, and there the curves' kink that moves
   !> in s (the annulus opening, doc/benchmarks.md "Stop 67: kink33") lets the mismatch
   !> fall only as h^2 (3.2-4x a bisection), not as a cubic's h^4. cap_hysteresis's psi 1
   !> + cap DEM table at 3e-4 (sigma = delta_y/10) needs 458 nodes, 438 before its last
   !> pass, all in [0.87, 1.28] delta_y (doc/benchmarks.md "Stop 68: dem34").
   integer, parameter, public :: mapped_m_node_limit = 2*build_m_node_limit
   !> The pilot's tolerance, and the rel_tol below which a build is preceded by the pilot
   !> (above it even a pilot at the node limit estimates at most 2x its grid).
   real(dp), parameter :: pilot_tol = 1.0e-3_dp, pilot_below = 1.0e-4_dp
   !> Growth of the delta_max grid per decade of rel_tol, the largest measured with the
   !> log-ratio curves (tolerance relative to the local force; glass pair of issue 22:
   !> 61, 107, 235 nodes at 1e-3, 1e-4, 1e-5, x1.75 then x2.2, x1.96 a decade over both;
   !> on six-point stencils 42, 71, 170, x1.69 then x2.39, x2.01 a decade over both, with
   !> the check's skip (hysteresis_build's check_skip) 42, 67, 146, x1.60 then x2.18, with
   !> the deferred splits (split_defer) 37, 59, 139, x1.59 then x2.36, x1.94 over both,
   !> and check curves at the shared s nodes 37, 58, 131, x1.57 then x2.26;
   !> steel pair 80, 134, 249, x1.76 a decade). The gap curves before grew faster from a
   !> smaller pilot (glass 27, 50, 137: x2.74 in the second decade).
   real(dp), parameter :: m_growth_per_decade = 2.0_dp
   !> The build's solve tolerance from which on probe_hysteresis_tolerance does nothing
   !> (rel_tol 1e-4 with the default options).
   real(dp), parameter :: probe_solve_floor = 1.0e-5_dp

contains

   !> Before build_hysteresis(params, options, ., delta_max, rel_tol): at the turning points
   !> delta_max and delta_max/2 (if > 0), the loading solve and the unloading solves from
   !> it at eight fractions of its unloading length 1.5 P/K, 0.03 .. 0.99 (the curves the
   !> build solves at the most s nodes; where unloading solves are hardest, beside the
   !> kinks of d = d_max and far down the curve), at the build's solve tolerance
   !> hysteresis_solve_tol. Unreachable tolerances show as
   !> sporadic solves that stop on the finest mesh (psi 10 at 1e-10: 1 in 18 points along
   !> a curve), which the build's hundreds of solves are sure to meet. A solve that does not converge
   !> (egw_not_converged) fails the probe with a message that quotes the caller's rel_tol,
   !> the solves' tolerance, the overlaps and what the solve reached; any other error
   !> (invalid input) is left to the build's own checks (no error here). Reversible
   !> contacts (no plastic summits) need no unloading solves: nothing is done. Cost: 18
   !> solves (milliseconds at the usual tolerances, seconds at 1e-10). Nor is anything
   !> done where the build's solves are at 1e-5 or looser (probe_solve_floor): such a
   !> build takes seconds, and a solve of it that fails stops it after its first pass
   !> over the 9-14 first delta_max nodes; the probe would cost 5-10 % of it (LAMMPS's
   !> EP-GW set-up at TOL 1e-4).
   subroutine probe_hysteresis_tolerance(params, options, delta_max, rel_tol, error)
      type(contact_params), intent(in) :: params   !< the contact of the build
      type(solver_options), intent(in) :: options  !< the build's solver options
      real(dp), intent(in) :: delta_max            !< the build's largest overlap [length]
      real(dp), intent(in) :: rel_tol              !< the build's (the caller's) tolerance
      !> allocated only when a solve cannot reach the tolerance
      type(egw_error), allocatable, intent(out) :: error
      real(dp), parameter :: fractions(8) = [0.03_dp, 0.1_dp, 0.3_dp, 0.5_dp, 0.7_dp, &
         & 0.9_dp, 0.95_dp, 0.99_dp]
      type(solver_options) :: opts
      type(solve_result) :: top, res
      real(dp) :: span, delta, m
      integer :: i, j
      if (.not. (params%model == model_epgw .and. params%psi > 0.0_dp .and. &
         & params%sigma > 0.0_dp)) return
      opts = options
      opts%rel_tol = hysteresis_solve_tol(options, rel_tol)
      if (opts%rel_tol >= 0.999_dp*probe_solve_floor) return   ! (rounding aside)
      do j = 1, 2
         m = delta_max
         if (j == 2) then
            if (.not. delta_max > 0.0_dp) return
            m = 0.5_dp*delta_max
         end if
         call solve_contact(params, opts, m, top, error)
         if (allocated(error)) then
            call explain(error, m, m)
            return
         end if
         if (.not. (top%force > 0.0_dp .and. top%stiffness > 0.0_dp)) return
         span = 1.5_dp*top%force/top%stiffness
         do i = 1, size(fractions)
            delta = m - fractions(i)*span
            call solve_contact_unload(params, opts, delta, m, res, error)
            if (allocated(error)) then
               call explain(error, delta, m)
               return
            end if
         end do
      end do
   contains
      !> A not-converged solve in the caller's terms; other errors dropped (the build
      !> reports invalid input itself).
      subroutine explain(error, delta, m)
         type(egw_error), allocatable, intent(inout) :: error
         real(dp), intent(in) :: delta, m
         if (error%stat /= egw_not_converged) then
            deallocate (error)
            return
         end if
         error%message = "hysteresis table: rel_tol = "//format_real(rel_tol)// &
            & " (the caller's) cannot be reached, found before the build: its curves "// &
            & "are solved at "//format_real(opts%rel_tol)//", and the solve at delta = "// &
            & format_real(delta)//" after delta_max = "//format_real(m)//" fails: "// &
            & error%message
      end subroutine explain
   end subroutine probe_hysteresis_tolerance

   !> The tolerance of a hysteresis build's unloading curve solves (build_hysteresis) for
   !> the table's rel_tol: rel_tol/10, or options%rel_tol where the caller set that below
   !> its default (1e-6) and below rel_tol/10.
   pure real(dp) function hysteresis_solve_tol(options, rel_tol) result(tol)
      type(solver_options), intent(in) :: options   !< the build's solver options
      real(dp), intent(in) :: rel_tol               !< the table's tolerance
      type(solver_options), parameter :: defaults = solver_options()
      ! Not min(options%rel_tol, rel_tol/10) as the 1-D tables: the table's accuracy is
      ! set by its checks against these solves (rel_tol/4 in s, rel_tol in delta_max),
      ! which tighter solves do not change. The default options (1e-6) gave a 1e-4 table
      ! (egw-bench --hysteresis) the same grid (50 x 55) and errors (to 3 digits: 9.0e-5
      ! at the checks, 7.0e-5 against 207 solves at 1e-8) at 1e-5 as at 1e-6, for 21%
      ! less CPU time (2 runs each, on a busy machine). A caller who sets a tighter
      ! options%rel_tol still gets it (and the probe's quick failure where it is out of
      ! reach).
      tol = 0.1_dp*rel_tol
      if (options%rel_tol < defaults%rel_tol) tol = min(tol, options%rel_tol)
   end function hysteresis_solve_tol

   !> The most delta_max nodes of a build (refine_m's limit): mapped_m_node_limit for u
   !> curves on the two-piece map, else build_m_node_limit.
   pure integer function m_node_limit(on_map) result(n)
      logical, intent(in) :: on_map   !< the table's ratio_on_map
      n = build_m_node_limit
      if (on_map) n = mapped_m_node_limit
   end function m_node_limit

   !> Before build_hysteresis(params, options, delta_min, delta_max, rel_tol) with rel_tol
   !> below 1e-4 (plastic summits only): a pilot table at 1e-3 over the same range (a few
   !> percent of a 1e-5 build's solves), whose delta_max grid of n_p nodes, grown by 2x
   !> per decade to rel_tol (m_growth_per_decade: an estimate from measured builds, not a
   !> bound), gives the build's n_p 2^log10(1e-3/rel_tol). Above the build's m_node_limit the
   !> build would run for many minutes (the glass pair at 1e-6: 21.6 min) and then stop at
   !> the limit or at a solve: refused now, egw_not_converged, with a message that quotes
   !> the caller's rel_tol, the pilot's grid, the estimate and the smallest rel_tol within
   !> the limit. A pilot that fails to converge fails the probe in the same terms; other
   !> errors are left to the build. pilot_nodes (optional): n_p, 0 without a pilot.
   subroutine probe_hysteresis_size(params, options, delta_min, delta_max, rel_tol, error, &
      & pilot_nodes)
      type(contact_params), intent(in) :: params   !< the contact of the build
      type(solver_options), intent(in) :: options  !< the build's solver options
      real(dp), intent(in) :: delta_min, delta_max   !< the build's range [length]
      real(dp), intent(in) :: rel_tol              !< the build's (the caller's) tolerance
      !> allocated only when the build is estimated out of reach
      type(egw_error), allocatable, intent(out) :: error
      integer, intent(out), optional :: pilot_nodes   !< the pilot's delta_max nodes
      type(hysteresis_table) :: pilot
      real(dp) :: estimate, reach
      integer :: n_p, limit
      character(len=16) :: short
      if (present(pilot_nodes)) pilot_nodes = 0
      if (.not. (params%model == model_epgw .and. params%psi > 0.0_dp .and. &
         & params%sigma > 0.0_dp .and. rel_tol < pilot_below .and. rel_tol > 0.0_dp)) return
      call build_hysteresis(params, options, delta_min, delta_max, pilot_tol, pilot, error)
      if (allocated(error)) then
         if (error%stat /= egw_not_converged) then
            deallocate (error)   ! invalid input: the build's own checks report it
            return
         end if
         error%message = "hysteresis table: rel_tol = "//format_real(rel_tol)// &
            & " (the caller's) cannot be reached, found before the build: a pilot table "// &
            & "at 1e-3 fails already: "//error%message
         return
      end if
      n_p = size(pilot%m)
      if (present(pilot_nodes)) pilot_nodes = n_p
      estimate = n_p*m_growth_per_decade**log10(pilot_tol/rel_tol)
      ! (the build's own limit: the pilot's curves are of the build's kind)
      limit = m_node_limit(pilot%ratio_on_map)
      if (.not. estimate > limit) return
      ! the rel_tol whose estimate is the limit
      reach = pilot_tol/10.0_dp**(log(real(limit, dp)/n_p)/ &
         & log(m_growth_per_decade))
      ! (the text spells pilot_tol and m_growth_per_decade out)
      write (short, '(es8.1)') reach
      call fatal_error(error, egw_not_converged, "hysteresis table: rel_tol = "// &
         & format_real(rel_tol)//" (the caller's) cannot be reached within the build's "// &
         & "limit of "//int_str(limit)//" delta_max nodes, found before the "// &
         & "build: a pilot table at 1e-3 needed "//int_str(n_p)//", and at about 2x "// &
         & "per decade of rel_tol (as measured builds grow) rel_tol = "//format_real(rel_tol) &
         & //" needs ~"//int_str(nint(estimate))//" (a build of many minutes that would "// &
         & "stop at the limit); rel_tol >= ~"//trim(adjustl(short))//" is within it")
   end subroutine probe_hysteresis_size

end module egw_tolerance_probe
