!> egw_all: the public names of egw's modules (the constants of egw_kinds, the mesh,
!> kernels and numerical helpers, the table internals, file helpers ...), for power users
!> and the tests; the C layer (capi/) and the inner modules of the solver's levels and of
!> the builds (sphere_*, cap_*, hysteresis_curves, ...) are used by their own names.
!> Programs that only compute contacts `use egw` (src/egw.f90), whose shorter list does
!> not collide with the names of a host code.
module egw_all
   use egw_kinds
   use egw_version
   use egw_status
   use egw_params
   use egw_gauss
   use egw_ellip
   use egw_asperity
   use egw_unloading
   use egw_flat_law
   use egw_flat_law_format
   use egw_table_ends
   use egw_hysteresis
   use egw_hysteresis_format
   use egw_smooth_sphere
   use egw_halfspace
   use egw_rough_sphere
   use egw_rough_profile
   use egw_impact
   use egw_progress
   use egw_table
   use egw_table_tail
   use egw_table_universal
   use egw_table_format
   use egw_scene
   use egw_io
   use egw_cache
   use egw_flat_bem
   use egw_flat_persson
   implicit none
   public
end module egw_all
