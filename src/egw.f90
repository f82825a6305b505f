!> egw: extended Greenwood-Williamson contact of rough spheres (Zhao & Feng 2018).
!> `use egw` gives a Fortran user the whole public API; the C API is include/egw.h.
module egw
   use egw_kinds, only: dp
   use egw_version, only: egw_version_string, egw_version_number, get_egw_version
   use egw_status
   use egw_params
   use egw_gauss
   use egw_ellip
   use egw_asperity
   use egw_unloading
   use egw_hysteresis
   use egw_hysteresis_format
   use egw_smooth_sphere
   use egw_halfspace
   use egw_rough_sphere
   use egw_impact
   use egw_table
   use egw_table_universal
   use egw_table_format
   use egw_scene
   use egw_io
   implicit none
   public
end module egw
