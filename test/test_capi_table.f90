!> Runs the C tests of the table API (test/capi_table_checks.c) as a test-drive suite.
module test_capi_table
   use, intrinsic :: iso_c_binding, only: c_int
   use testdrive, only: new_unittest, unittest_type, error_type, check, to_string
   implicit none
   private
   public :: collect_capi_table

   interface
      integer(c_int) function c_build_eval() bind(C, name="egw_capi_test_table_build_eval")
         import :: c_int
      end function c_build_eval
      integer(c_int) function c_files() bind(C, name="egw_capi_test_table_files")
         import :: c_int
      end function c_files
      integer(c_int) function c_universal() bind(C, name="egw_capi_test_table_universal")
         import :: c_int
      end function c_universal
      integer(c_int) function c_plain() bind(C, name="egw_capi_test_table_plain_reader")
         import :: c_int
      end function c_plain
      integer(c_int) function c_tail() bind(C, name="egw_capi_test_table_tail")
         import :: c_int
      end function c_tail
      integer(c_int) function c_tail_header() bind(C, name="egw_capi_test_table_tail_header")
         import :: c_int
      end function c_tail_header
   end interface

contains

   subroutine collect_capi_table(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("build and eval", t_build_eval), &
         & new_unittest("files", t_files), &
         & new_unittest("universal", t_universal), &
         & new_unittest("documented plain C reader", t_plain), &
         & new_unittest("the resampled tail's pieces (egw_table_get_tail)", t_tail), &
         & new_unittest("egw_table_get_tail as egw.h words it", t_tail_header) &
         & ]
   end subroutine collect_capi_table

   subroutine report(error, nfail)
      type(error_type), allocatable, intent(out) :: error
      integer(c_int), intent(in) :: nfail
      call check(error, int(nfail) == 0, to_string(int(nfail))//" C check(s) failed (see above)")
   end subroutine report

   subroutine t_build_eval(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_build_eval())
   end subroutine t_build_eval

   subroutine t_files(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_files())
   end subroutine t_files

   subroutine t_universal(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_universal())
   end subroutine t_universal

   subroutine t_plain(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_plain())
   end subroutine t_plain

   subroutine t_tail(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_tail())
   end subroutine t_tail

   subroutine t_tail_header(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_tail_header())
   end subroutine t_tail_header

end module test_capi_table
