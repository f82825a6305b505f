!> egw-table: writes force-overlap and pressure-separation tables for a contact scene.
!> With no arguments it runs the embedded default scene (two 1 mm glass beads with
!> 1 um combined roughness, SI units) and writes its curves as CSV under out/.
program egw_table_app
   use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
   use egw, only: dp, egw_version_string, contact_params, model_egw, model_name, &
      & egw_error, validate_params, flat_pressure, hertz_force, hertz_stiffness, &
      & hertz_contact_radius, open_temporary, commit_temporary, discard_temporary, &
      & format_real
   implicit none

   type(contact_params) :: scene
   type(egw_error), allocatable :: error
   character(len=:), allocatable :: out_dir, arg
   integer :: iarg, n_points

   out_dir = "out"
   n_points = 201
   iarg = 1
   do while (iarg <= command_argument_count())
      call get_arg(iarg, arg)
      select case (arg)
      case ("-h", "--help")
         call usage()
         stop
      case ("-o", "--out")
         iarg = iarg + 1
         if (iarg > command_argument_count()) call die("--out needs a directory")
         call get_arg(iarg, out_dir)
      case default
         call die("unknown argument '"//arg//"' (see --help)")
      end select
      iarg = iarg + 1
   end do

   scene = default_scene()
   call validate_params(scene, error)
   if (allocated(error)) call die(error%message)

   write (output_unit, '(a)') "egw-table "//egw_version_string//": default scene, model " &
      & //model_name(scene%model)
   write (output_unit, '(a)') "  R = "//format_real(scene%radius)//" m, E* = " &
      & //format_real(scene%modulus)//" Pa, sigma = "//format_real(scene%sigma) &
      & //" m, mu = "//format_real(scene%mu)
   call execute_command_line("mkdir -p '"//out_dir//"'")

   call write_hertz_curve(scene, out_dir//"/hertz_force.csv", n_points, error)
   if (allocated(error)) call die(error%message)
   call write_flat_curve(scene, out_dir//"/rough_flat_pressure.csv", n_points, error)
   if (allocated(error)) call die(error%message)

contains

   !> Two glass beads, R1 = R2 = 1 mm (R = 0.5 mm), E = 70 GPa, nu = 0.22 each,
   !> combined summit-height std 1 um, Greenwood-Tripp mu = 4, E-GW.
   function default_scene() result(p)
      type(contact_params) :: p
      real(dp), parameter :: e_glass = 70.0e9_dp, nu_glass = 0.22_dp
      p = contact_params()
      p%model = model_egw
      p%radius = 1.0_dp/(1.0_dp/1.0e-3_dp + 1.0_dp/1.0e-3_dp)
      p%modulus = 1.0_dp/(2.0_dp*(1.0_dp - nu_glass**2)/e_glass)
      p%sigma = 1.0e-6_dp
      p%mu = 4.0_dp
   end function default_scene

   !> Hertz force, stiffness and contact radius for overlaps 0 .. 20 sigma.
   subroutine write_hertz_curve(p, path, n, error)
      type(contact_params), intent(in) :: p
      character(len=*), intent(in) :: path
      integer, intent(in) :: n
      type(egw_error), allocatable, intent(out) :: error
      character(len=:), allocatable :: tmp
      integer :: unit, i
      real(dp) :: delta, delta_max
      delta_max = 20.0_dp*p%sigma
      call open_temporary(path, unit, tmp, error)
      if (allocated(error)) return
      call write_header(unit, p, "Hertz force-overlap curve of the smooth spheres (DESIGN.md s5)")
      write (unit, '(a)') "delta_m,force_N,stiffness_N_per_m,contact_radius_m"
      do i = 0, n - 1
         delta = delta_max*real(i, dp)/real(n - 1, dp)
         write (unit, '(4(es24.16e3,:,","))') delta, hertz_force(delta, p%radius, p%modulus), &
            & hertz_stiffness(delta, p%radius, p%modulus), hertz_contact_radius(delta, p%radius)
      end do
      call commit_temporary(unit, tmp, path, error)
      if (.not. allocated(error)) call report(path, n, "delta in [0, "//format_real(delta_max)//"] m")
   end subroutine write_hertz_curve

   !> Rough-flat nominal pressure p_G(d) and dp_G/dd for separations -4 sigma .. 6 sigma.
   subroutine write_flat_curve(p, path, n, error)
      type(contact_params), intent(in) :: p
      character(len=*), intent(in) :: path
      integer, intent(in) :: n
      type(egw_error), allocatable, intent(out) :: error
      character(len=:), allocatable :: tmp
      integer :: unit, i
      real(dp) :: d, pg, dpg, d_min, d_max
      d_min = -4.0_dp*p%sigma
      d_max = 6.0_dp*p%sigma
      call open_temporary(path, unit, tmp, error)
      if (allocated(error)) return
      call write_header(unit, p, "rough-flat pressure-separation law p_G(d) (DESIGN.md s3)")
      write (unit, '(a)') "separation_m,pressure_Pa,dpressure_dseparation_Pa_per_m"
      do i = 0, n - 1
         d = d_min + (d_max - d_min)*real(i, dp)/real(n - 1, dp)
         call flat_pressure(p, d, pg, dpg, error)
         if (allocated(error)) then
            call discard_temporary(unit, tmp)
            return
         end if
         write (unit, '(3(es24.16e3,:,","))') d, pg, dpg
      end do
      call commit_temporary(unit, tmp, path, error)
      if (.not. allocated(error)) call report(path, n, "separation in [" &
         & //format_real(d_min)//", "//format_real(d_max)//"] m")
   end subroutine write_flat_curve

   subroutine write_header(unit, p, title)
      integer, intent(in) :: unit
      type(contact_params), intent(in) :: p
      character(len=*), intent(in) :: title
      write (unit, '(a)') "# egw "//egw_version_string//": "//title
      write (unit, '(a)') "# units: SI (m, Pa, N)"
      write (unit, '(a)') "# model = "//model_name(p%model)
      write (unit, '(a)') "# radius = "//format_real(p%radius)
      write (unit, '(a)') "# modulus = "//format_real(p%modulus)
      write (unit, '(a)') "# sigma = "//format_real(p%sigma)
      write (unit, '(a)') "# mu = "//format_real(p%mu)
      write (unit, '(a)') "# psi = "//format_real(p%psi)
      write (unit, '(a)') "# hardness_coeff = "//format_real(p%hardness_coeff)
      write (unit, '(a)') "# plastic_ratio = "//format_real(p%plastic_ratio)
   end subroutine write_header

   subroutine report(path, n, what)
      character(len=*), intent(in) :: path, what
      integer, intent(in) :: n
      write (output_unit, '(a,i0,a)') "  wrote "//path//" (", n, " rows, "//what//")"
   end subroutine report

   subroutine usage()
      write (output_unit, '(a)') "usage: egw-table [--out DIR]"
      write (output_unit, '(a)') "  Writes the Hertz force-overlap curve and the rough-flat"
      write (output_unit, '(a)') "  pressure-separation curve of the default scene as CSV."
      write (output_unit, '(a)') "  --out DIR   output directory (default: out)"
   end subroutine usage

   subroutine die(message)
      character(len=*), intent(in) :: message
      write (error_unit, '(a)') "egw-table: error: "//message
      error stop 2
   end subroutine die

   subroutine get_arg(i, val)
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: val
      integer :: n
      call get_command_argument(i, length=n)
      allocate (character(len=n) :: val)
      call get_command_argument(i, val)
   end subroutine get_arg

end program egw_table_app
