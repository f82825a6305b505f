!> Runs the C tests of the scene API (test/scene_checks.c) as a test-drive suite.
module test_capi_scene
   use, intrinsic :: iso_c_binding, only: c_int
   use testdrive, only: new_unittest, unittest_type, error_type, check, to_string
   implicit none
   private
   public :: collect_capi_scene

   interface
      integer(c_int) function c_read() bind(C, name="egw_capi_test_scene_read")
         import :: c_int
      end function c_read
      integer(c_int) function c_threads() bind(C, name="egw_capi_test_scene_threads")
         import :: c_int
      end function c_threads
      integer(c_int) function c_hertz() bind(C, name="egw_capi_test_scene_hertz")
         import :: c_int
      end function c_hertz
      integer(c_int) function c_table() bind(C, name="egw_capi_test_scene_table")
         import :: c_int
      end function c_table
   end interface

contains

   subroutine collect_capi_scene(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("default, validate, read", t_read), &
         & new_unittest("one file read by 8 threads 2400 times", t_threads), &
         & new_unittest("Hertz choice and bound", t_hertz), &
         & new_unittest("table choice and build", t_table) &
         & ]
   end subroutine collect_capi_scene

   subroutine report(error, nfail)
      type(error_type), allocatable, intent(out) :: error
      integer(c_int), intent(in) :: nfail
      call check(error, int(nfail) == 0, to_string(int(nfail))//" C check(s) failed (see above)")
   end subroutine report

   subroutine t_read(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_read())
   end subroutine t_read

   subroutine t_threads(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_threads())
   end subroutine t_threads

   subroutine t_hertz(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_hertz())
   end subroutine t_hertz

   subroutine t_table(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_table())
   end subroutine t_table

end module test_capi_scene
