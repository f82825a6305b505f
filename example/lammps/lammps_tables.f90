!> Writes egw_pair.table for example/lammps: two pair_style table sections for two glass
!> beads (R1 = R2 = 1 mm, E = 70 GPa, nu = 0.22; SI units): EGW_1 smooth (Hertz), EGW_2
!> rough (E-GW, sigma = 0.1 um, mu = 4). Both tables run to a 2 um overlap at rel_tol
!> 1e-5. Usage: lammps-tables [output path]  (default egw_pair.table)
program lammps_tables
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_hertz, model_egw
   use egw_rough_sphere, only: solver_options
   use egw_table, only: force_table, build_table, table_set_radii
   use egw_table_format, only: write_lammps
   implicit none
   real(dp), parameter :: r1 = 1.0e-3_dp, e_young = 70.0e9_dp, nu = 0.22_dp
   type(contact_params) :: p
   type(force_table) :: tables(2)
   type(egw_error), allocatable :: error
   character(len=256) :: path

   path = "egw_pair.table"
   if (command_argument_count() >= 1) call get_command_argument(1, path)
   p = contact_params(model=model_hertz, radius=r1/2, modulus=e_young/(2*(1 - nu**2)))
   call build_table(p, solver_options(), 0.0_dp, 2.0e-6_dp, 1.0e-5_dp, tables(1), error)
   if (.not. allocated(error)) call table_set_radii(tables(1), r1, r1, error)
   p%model = model_egw
   p%sigma = 0.1e-6_dp
   p%mu = 4
   if (.not. allocated(error)) call build_table(p, solver_options(), -10*p%sigma, &
      & 2.0e-6_dp, 1.0e-5_dp, tables(2), error)
   if (.not. allocated(error)) call table_set_radii(tables(2), r1, r1, error)
   if (.not. allocated(error)) call write_lammps(tables, trim(path), error)
   if (allocated(error)) then
      write (*, '(a)') "lammps-tables: "//error%message
      error stop 1
   end if
   write (*, '(a)') "lammps-tables: wrote "//trim(path)
end program lammps_tables
