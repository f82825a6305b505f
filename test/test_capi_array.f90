!> Runs the C tests of the array kernels (test/array_checks.c) as a test-drive suite.
module test_capi_array
   use, intrinsic :: iso_c_binding, only: c_int
   use testdrive, only: new_unittest, unittest_type, error_type, check, to_string
   implicit none
   private
   public :: collect_capi_array

   interface
      integer(c_int) function c_hertz() bind(C, name="egw_capi_test_array_hertz")
         import :: c_int
      end function c_hertz
      integer(c_int) function c_flat() bind(C, name="egw_capi_test_array_flat")
         import :: c_int
      end function c_flat
      integer(c_int) function c_solve() bind(C, name="egw_capi_test_array_solve")
         import :: c_int
      end function c_solve
      integer(c_int) function c_impact() bind(C, name="egw_capi_test_array_impact")
         import :: c_int
      end function c_impact
      integer(c_int) function c_universal() bind(C, name="egw_capi_test_array_universal")
         import :: c_int
      end function c_universal
   end interface

contains

   subroutine collect_capi_array(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("hertz", t_hertz), &
         & new_unittest("flat pressure and gauss", t_flat), &
         & new_unittest("solves over threads", t_solve), &
         & new_unittest("restitution and time step", t_impact), &
         & new_unittest("universal table", t_universal) &
         & ]
   end subroutine collect_capi_array

   subroutine report(error, nfail)
      type(error_type), allocatable, intent(out) :: error
      integer(c_int), intent(in) :: nfail
      call check(error, int(nfail) == 0, to_string(int(nfail))//" C check(s) failed (see above)")
   end subroutine report

   subroutine t_hertz(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_hertz())
   end subroutine t_hertz

   subroutine t_flat(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_flat())
   end subroutine t_flat

   subroutine t_solve(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_solve())
   end subroutine t_solve

   subroutine t_impact(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_impact())
   end subroutine t_impact

   subroutine t_universal(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_universal())
   end subroutine t_universal

end module test_capi_array
