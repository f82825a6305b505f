!> Runs the C tests of file output and input (test/capi_io_checks.c) as a test-drive
!> suite: 16 threads writing and rereading, failed writes, long paths, a full tmpfs.
module test_capi_io
   use, intrinsic :: iso_c_binding, only: c_int
   use testdrive, only: new_unittest, unittest_type, error_type, check, to_string
   implicit none
   private
   public :: collect_capi_io

   interface
      integer(c_int) function c_threads() bind(C, name="egw_capi_test_io_threads")
         import :: c_int
      end function c_threads
      integer(c_int) function c_failures() bind(C, name="egw_capi_test_io_failures")
         import :: c_int
      end function c_failures
      integer(c_int) function c_long_paths() bind(C, name="egw_capi_test_io_long_paths")
         import :: c_int
      end function c_long_paths
      integer(c_int) function c_full_disk() bind(C, name="egw_capi_test_io_full_disk")
         import :: c_int
      end function c_full_disk
   end interface

contains

   subroutine collect_capi_io(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("16 threads write and reread tables", t_threads), &
         & new_unittest("failed writes keep the old file", t_failures), &
         & new_unittest("paths beyond 4096 bytes", t_long_paths), &
         & new_unittest("full tmpfs, four formats (root)", t_full_disk) &
         & ]
   end subroutine collect_capi_io

   subroutine report(error, nfail)
      type(error_type), allocatable, intent(out) :: error
      integer(c_int), intent(in) :: nfail
      call check(error, int(nfail) == 0, to_string(int(nfail))//" C check(s) failed (see above)")
   end subroutine report

   subroutine t_threads(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_threads())
   end subroutine t_threads

   subroutine t_failures(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_failures())
   end subroutine t_failures

   subroutine t_long_paths(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_long_paths())
   end subroutine t_long_paths

   subroutine t_full_disk(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_full_disk())
   end subroutine t_full_disk

end module test_capi_io
