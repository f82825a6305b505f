!> The facade `use egw` (src/egw.f90): it gives the user-facing API and leaves a host
!> code's own names free. This module uses all of egw and declares names that egw's
!> internals also have (pi, unset, sqrt2, fatal_error, build_mesh, int_str); were any of
!> them re-exported by egw again, this file would not compile. The test runs the README's
!> Fortran example through the facade alone.
module test_facade
   use testdrive, only: new_unittest, unittest_type, error_type, check
   use egw
   implicit none
   private
   public :: collect_facade

   ! a host DEM code's own names, which egw's facade must not take
   real(dp), parameter :: pi = 3.141592653589793_dp, sqrt2 = 1.4142135623730951_dp
   real(dp), parameter :: unset = -1.0_dp

contains

   subroutine collect_facade(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("README example through use egw", t_readme), &
         & new_unittest("host names free beside use egw", t_host_names) &
         & ]
   end subroutine collect_facade

   !> The README's example, E-GW flat pressure at zero separation, through the facade
   !> alone (the values are checked in the asperity suite): success, and a finite positive
   !> pressure that falls as the separation grows.
   subroutine t_readme(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: p
      type(egw_error), allocatable :: status
      real(dp) :: pressure, dpdd
      p = contact_params(model=model_egw, radius=0.5e-3_dp, modulus=36.8e9_dp, sigma=1e-6_dp, &
         & mu=4.0_dp)
      call flat_pressure(p, 0.0_dp, pressure, dpdd, status)
      call check(error, .not. allocated(status), "flat_pressure through use egw failed")
      if (allocated(error)) return
      call check(error, pressure > 0.0_dp .and. pressure < huge(pressure) .and. dpdd < 0.0_dp, &
         & "pressure > 0 and falling with the separation")
   end subroutine t_readme

   !> The host's names resolve to the host's values (the real check is that this module
   !> compiles beside `use egw`).
   subroutine t_host_names(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: text
      call fatal_error(text)
      call build_mesh(text)
      call check(error, unset < 0.0_dp .and. abs(pi*pi/(sqrt2*sqrt2) - 4.934802200544679_dp) &
         & < 1e-14_dp .and. text == "host host" .and. int_str(7) == 7, &
         & "the host's own pi, sqrt2, unset, fatal_error, build_mesh and int_str")
   end subroutine t_host_names

   pure subroutine fatal_error(text)
      character(len=:), allocatable, intent(out) :: text
      text = "host"
   end subroutine fatal_error

   pure subroutine build_mesh(text)
      character(len=:), allocatable, intent(inout) :: text
      text = text//" host"
   end subroutine build_mesh

   pure integer function int_str(i)
      integer, intent(in) :: i
      int_str = i
   end function int_str

end module test_facade
