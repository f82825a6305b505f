!> Normal contact of rough spheres: classic GW (Greenwood-Tripp), E-GW and EP-GW
!> (doc/theory.md §5; paper eqs. 10-13 and 28-35), with Hertz as sigma = 0.
!>
!> The solves in the caller's units, their validation and the unloading histories (their
!> contact profiles: egw_rough_profile). The problem is solved in scaled variables by
!> egw_sphere_solver: radii in units of sqrt(R sigma), gaps and deflections in sigma,
!> pressures in E sqrt(sigma/R), forces in E sqrt(R) sigma**1.5, so that scale invariance
!> is exact.
!>
!> Unloading (doc/theory.md §8, issue 10 item 3): a loading_history keeps the separation field
!> d_max(r) of the solve at delta_max (its mesh and nodal w_G); an unloading solve at
!> delta <= delta_max is the same problem with the unloading law at fixed d_max
!> (egw_sphere_solver).
!>
!> The flow-pressure cap (params%flow_pressure > 0; doc/theory.md §12) of a smooth sphere
!> is routed here and nowhere else: above first yield a smooth solve, history or unloading
!> solve is egw_cap_sphere's (cap_load, cap_unload with its default options); at or below
!> first yield it is Hertz, bit for bit as without the cap. A rough sphere takes the cap
!> inside its scaled problem (scaled_problem%cap, egw_flow_cap; "Rough spheres with the
!> cap"): the same solves, histories and unloading solves.
!>
!> This module is the public entry: it gathers the parts, one concern each, and keeps
!> every name reachable from here as before: one solve in the caller's units, its result
!> and input checks (egw_rough_solve), the loading solves (egw_rough_loading: solve_contact,
!> solve_contact_law), the loading histories and unloading solves (egw_rough_history), the
!> small-sigma route with the cap (egw_small_sigma_route).
module egw_rough_sphere
   use egw_sphere_solver, only: method_auto, method_newton, method_picard, solver_options, &
      & max_mesh_nodes
   use egw_rough_solve, only: solve_result, unload_start, validate_options, above_first_yield, &
      & cap_solve_options, check_input, check_unload_input, smooth_capped
   use egw_rough_loading, only: solve_contact, solve_contact_law
   use egw_rough_history, only: loading_history, load_history, solve_unload, &
      & solve_contact_unload, history_residual, history_cap_ratio, unloading_problem, &
      & history_cap, loaded_by_route
   implicit none
   private

   public :: method_auto, method_newton, method_picard, solver_options, max_mesh_nodes
   public :: solve_result
   public :: validate_options, solve_contact, solve_contact_law
   public :: load_history, solve_unload, solve_contact_unload
   public :: loading_history, unload_start
   public :: above_first_yield, cap_solve_options, history_residual, history_cap_ratio
   ! for egw_rough_profile (the profiles of these solves)
   public :: check_input, check_unload_input, smooth_capped, unloading_problem, &
      & history_cap, loaded_by_route
end module egw_rough_sphere
