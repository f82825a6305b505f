!> Which measured regime a scaled sphere problem is in, for the sphere solver's levels
!> (egw_sphere_solver): where the fallbacks of solves that stall with the cap apply, the
!> capped histories whose levels take a confirming level, and where the levels halve
!> the elements they keep.
module egw_sphere_regime
   use egw_kinds, only: dp, pi
   use egw_sphere_problem, only: solver_options, scaled_problem, sums_total
   implicit none
   private

   public :: yield_overlap, stall_fallbacks, capped_gw, gw_confirm, capped_history, halved_levels
   public :: stall_overlap

   !> delta_y/sigma below which stall_fallbacks apply (sigma/delta_y > 2e-6); at and above
   !> it egw_rough_sphere's small-sigma route answers (its small_sigma_limit is this bound).
   real(dp), parameter :: stall_overlap = 0.5e6_dp

   !> Classic GW unloading after a capped loading takes refine_levels' confirming level at
   !> sigma/delta_y at most this: at 1e-4 and 2e-4 two coarse levels agreed while up to 5e-4
   !> off (doc/stability.md "Stop 50 (gw16)"); at 1e-2 (README's GW + cap build to 6 delta_y
   !> at 1e-4, within 6.7e-5 of rel_tol 1e-7 solves without it) it cost 4x the build's CPU.
   !> Above it refine_levels confirms only an acceptance at the first refinement level
   !> (capped_gw; near the unloading curve's knee that pair agreed while 3.6e-4 off).
   real(dp), parameter :: gw_confirm_sigma = 1.0e-3_dp

contains

   !> delta_y/sigma of a problem with the cap, (pi p_y/2)**2 in its scaled units (p_y in
   !> E* sqrt(sigma/R)): first yield of the smooth sphere, delta_y = R (pi p_y/(2 E*))**2.
   pure real(dp) function yield_overlap(prob) result(ratio)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem, with the cap
      ratio = (0.5_dp*pi*prob%cap%p_y)**2
   end function yield_overlap

   !> Whether the fallbacks of solves that stall with the cap apply (skip_failed_level,
   !> add_kink_error, unloading_descent, solve_default's refocus):
   !> with the cap at sigma/delta_y > 2e-6 (delta_y/sigma = (pi p_y/2)**2 here). Below,
   !> egw_rough_sphere's small-sigma route answers a failed solve, and the discrete
   !> levels the fallbacks let converge were off by more than their estimate (E-GW + cap,
   !> sigma/delta_y = 1e-6 from 2 delta_y, 0.16 delta_max at rel_tol 1e-5: 2.4e-5 off the
   !> reference, test rough_cap 'sigma/delta_y = 1e-6: unloading near the residual
   !> overlap', where the route answers within 7.6e-7).
   pure logical function stall_fallbacks(prob)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      stall_fallbacks = .false.
      if (allocated(prob%cap)) stall_fallbacks = yield_overlap(prob) < stall_overlap
   end function stall_fallbacks

   !> Classic GW unloading after a loading on which the flow-pressure cap acted.
   pure logical function capped_gw(prob)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      capped_gw = .false.
      if (allocated(prob%closest) .and. allocated(prob%cap)) capped_gw = &
         & prob%closest%capped .and. .not. prob%closest%extended
   end function capped_gw

   !> capped_gw at sigma/delta_y <= gw_confirm_sigma (delta_y/sigma = (pi p_y/2)**2 here).
   pure logical function gw_confirm(prob)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      gw_confirm = capped_gw(prob)
      if (gw_confirm) gw_confirm = yield_overlap(prob) >= 1.0_dp/gw_confirm_sigma
   end function gw_confirm

   !> EP-GW unloading after a loading on which the flow-pressure cap acted.
   pure logical function capped_history(prob)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      capped_history = .false.
      if (allocated(prob%closest) .and. prob%psi > 0.0_dp) capped_history = &
         & prob%closest%capped
   end function capped_history

   !> Unloading after a capped loading (sums_total), the levels of a discretisation
   !> error estimate (n_radial 0): each level halves the elements it would keep of the
   !> level before (cut into kept_parts: solve_with_tail's level_before, sphere_mesh's
   !> split_kept). Richardson
   !> assumes that every element shrinks with the step, but an element between two fixed
   !> edges (r = 0, kink edges, the layers at a and at the rim) stays the same while the
   !> step exceeds it, and its error is in both levels: near the residual overlap the
   !> total pressure lives on such a disc [0, 0.091] (E-GW, sigma = 0.059 delta_y, delta
   !> = 0.0174 delta_y after 1.297 delta_y), one element at steps 0.19, 0.15 and 0.076,
   !> whose levels agreed to 6e-8 while all were 8.2e-6 off (doc/theory.md section 12).
   !> Cut into at least the step ratio's parts (2 on the first refinement level, whose
   !> step is 1.5 times finer), those elements shrink at least like the step, so the
   !> Richardson estimate with the step ratio is conservative for them. Until stop 51
   !> an accepted level was solved again with them halved (a bisection check, the
   !> difference added whole to its estimate): the same mesh as the halved level, one
   !> mesh solve more in 56 % of the unloading solves of an E-GW + cap table
   !> (doc/benchmarks.md "Stop 51 (mesh17)").
   pure logical function halved_levels(prob, options)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(solver_options), intent(in) :: options   !< the solver's options (n_radial)
      halved_levels = sums_total(prob) .and. options%n_radial == 0
   end function halved_levels

end module egw_sphere_regime
