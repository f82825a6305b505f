!> Runs the C tests of include/egw.h (test/api/capi_checks.c) as a test-drive suite.
module test_capi
   use, intrinsic :: iso_c_binding, only: c_int
   use testdrive, only: new_unittest, unittest_type, error_type, check, to_string
   implicit none
   private
   public :: collect_capi

   interface
      integer(c_int) function c_version() bind(C, name="egw_capi_test_version")
         import :: c_int
      end function
      integer(c_int) function c_status() bind(C, name="egw_capi_test_status_message")
         import :: c_int
      end function
      integer(c_int) function c_last_error() bind(C, name="egw_capi_test_last_error")
         import :: c_int
      end function
      integer(c_int) function c_params() bind(C, name="egw_capi_test_params")
         import :: c_int
      end function
      integer(c_int) function c_gauss() bind(C, name="egw_capi_test_gauss")
         import :: c_int
      end function
      integer(c_int) function c_ellip() bind(C, name="egw_capi_test_ellip")
         import :: c_int
      end function
      integer(c_int) function c_flat() bind(C, name="egw_capi_test_flat_pressure")
         import :: c_int
      end function
      integer(c_int) function c_hertz() bind(C, name="egw_capi_test_hertz")
         import :: c_int
      end function
      integer(c_int) function c_solver() bind(C, name="egw_capi_test_solver")
         import :: c_int
      end function
      integer(c_int) function c_profile() bind(C, name="egw_capi_test_profile")
         import :: c_int
      end function
      integer(c_int) function c_cap_params() bind(C, name="egw_capi_test_flow_pressure_params")
         import :: c_int
      end function
      integer(c_int) function c_cap_solves() bind(C, name="egw_capi_test_flow_pressure_solves")
         import :: c_int
      end function
      integer(c_int) function c_cap_refusals() &
         & bind(C, name="egw_capi_test_flow_pressure_refusals")
         import :: c_int
      end function
      integer(c_int) function c_first_yield() bind(C, name="egw_capi_test_first_yield")
         import :: c_int
      end function
      integer(c_int) function c_progress() bind(C, name="egw_capi_test_progress")
         import :: c_int
      end function
   end interface

contains

   subroutine collect_capi(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("version", t_version), &
         & new_unittest("status messages", t_status), &
         & new_unittest("last error: length needed, truncation, query", t_last_error), &
         & new_unittest("params defaults and validation", t_params), &
         & new_unittest("gauss integral", t_gauss), &
         & new_unittest("elliptic integrals", t_ellip), &
         & new_unittest("flat pressure", t_flat), &
         & new_unittest("hertz", t_hertz), &
         & new_unittest("solve", t_solver), &
         & new_unittest("profile", t_profile), &
         & new_unittest("flow pressure: params", t_cap_params), &
         & new_unittest("flow pressure: solves against the cap reference", t_cap_solves), &
         & new_unittest("flow pressure: doors not served yet refuse", t_cap_refusals), &
         & new_unittest("flow pressure: egw_first_yield", t_first_yield), &
         & new_unittest("progress hook: monotone in [0, 1], NULL is off", &
         & t_progress) &
         & ]
   end subroutine collect_capi

   subroutine report(error, nfail)
      type(error_type), allocatable, intent(out) :: error
      integer(c_int), intent(in) :: nfail
      call check(error, int(nfail) == 0, to_string(int(nfail))//" C check(s) failed (see above)")
   end subroutine report

   subroutine t_version(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_version())
   end subroutine
   subroutine t_status(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_status())
   end subroutine
   subroutine t_last_error(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_last_error())
   end subroutine
   subroutine t_params(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_params())
   end subroutine
   subroutine t_gauss(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_gauss())
   end subroutine
   subroutine t_ellip(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_ellip())
   end subroutine
   subroutine t_flat(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_flat())
   end subroutine
   subroutine t_hertz(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_hertz())
   end subroutine

   subroutine t_solver(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_solver())
   end subroutine
   subroutine t_profile(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_profile())
   end subroutine
   subroutine t_cap_params(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_cap_params())
   end subroutine
   subroutine t_cap_solves(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_cap_solves())
   end subroutine
   subroutine t_cap_refusals(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_cap_refusals())
   end subroutine

   subroutine t_first_yield(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_first_yield())
   end subroutine

   subroutine t_progress(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_progress())
   end subroutine

end module test_capi
