!> The facade `use egw` (src/egw.f90): it gives the user-facing API and leaves a host
!> code's own names free. This module uses all of egw and declares names that egw's
!> internals also have (pi, unset, sqrt2, fatal_error, build_mesh, int_str); were any of
!> them re-exported by egw again, this file would not compile. The test runs the README's
!> Fortran example, and the names of its rough-flat-law table, through the facade alone.
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
         & new_unittest("host names free beside use egw", t_host_names), &
         & new_unittest("README's rough-flat laws through use egw", t_flat_laws) &
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

   !> README's "Rough-flat laws beyond GW" names these Fortran procedures; through `use egw`
   !> alone (before audit22 only through their modules): Persson's curve of a self-affine
   !> spectrum rises in pressure as the separation falls, and egw's BEM of one cosine wave
   !> h = cos(2 pi x/L) (mean 0, highest 1) touches nothing at a mean separation of 1.5
   !> (exactly 0: every gap > 0) and carries a load at 0.5.
   subroutine t_flat_laws(error)
      type(error_type), allocatable, intent(out) :: error
      type(egw_error), allocatable :: status
      type(persson_options) :: persson
      type(bem_options) :: opt
      type(bem_state) :: state
      type(bem_result) :: apart, pressed
      real(dp), allocatable :: q(:), c(:), u(:), p(:), area(:), dpdu(:)
      real(dp) :: heights(32, 32)
      integer :: i
      call self_affine_psd(0.8_dp, 1.0e-6_dp, 1.0e3_dp, 1.0e4_dp, 1.0e7_dp, q, c, status)
      if (.not. allocated(status)) call persson_flat_curve(q, c, 1.0e9_dp, 1.0e3_dp, &
         & 1.0e6_dp, 4, persson, u, p, area, dpdu, status)
      call check(error, .not. allocated(status), "Persson's curve through use egw failed")
      if (allocated(error)) return
      call check(error, size(p) > 2 .and. all(p(2:) > p(:size(p) - 1)) .and. &
         & all(u(2:) < u(:size(u) - 1)) .and. all(dpdu < 0.0_dp), &
         & "Persson: the pressure rises as the separation falls")
      if (allocated(error)) return
      do i = 1, 32
         heights(i, :) = cos(2.0_dp*acos(-1.0_dp)*(i - 1)/32.0_dp)
      end do
      opt%n_threads = 1
      call bem_solve_gap(heights, 1.0_dp, 1.0_dp, 1.5_dp, opt, state, apart, status)
      if (.not. allocated(status)) call bem_solve_gap(heights, 1.0_dp, 1.0_dp, 0.5_dp, opt, &
         & state, pressed, status)
      call bem_state_release(state)
      call check(error, .not. allocated(status), "the BEM through use egw failed")
      if (allocated(error)) return
      call check(error, apart%mean_pressure == 0.0_dp .and. apart%area_fraction == 0.0_dp &
         & .and. pressed%mean_pressure > 0.0_dp .and. pressed%area_fraction > 0.0_dp, &
         & "the BEM: nothing touches at 1.5, a load at 0.5")
   end subroutine t_flat_laws

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
