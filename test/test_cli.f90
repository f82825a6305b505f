!> Runs the command-line checks of egw-table (test/cli/egw_table_cli.sh) against the
!> egw-table built beside this tester (same build directory: build/<profile>/app).
module test_cli
   use testdrive, only: new_unittest, unittest_type, error_type, check, test_failed, to_string
   implicit none
   private
   public :: collect_cli

contains

   subroutine collect_cli(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [new_unittest("egw-table: errors, --sigma 0, progress in logs", test_table), &
         & new_unittest("egw.h: C89-C11, C++98-C++17 -pedantic, no warning", test_header)]
   end subroutine collect_cli

   subroutine test_table(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: tester, exe
      integer :: n, stat, cmdstat, cut
      call get_command_argument(0, length=n)
      allocate (character(len=n) :: tester)
      call get_command_argument(0, tester)
      cut = index(tester, "/test/", back=.true.)
      if (cut == 0) then
         call test_failed(error, "cannot locate the build directory from "//tester)
         return
      end if
      exe = tester(:cut)//"app/egw-table"
      call execute_command_line("sh test/cli/egw_table_cli.sh '"//exe//"'", exitstat=stat, &
         & cmdstat=cmdstat)
      call check(error, cmdstat, 0, "could not run test/cli/egw_table_cli.sh")
      if (allocated(error)) return
      call check(error, stat, 0, to_string(stat)//" CLI check(s) failed (see above)")
   end subroutine test_table

   !> include/egw.h compiled as C89, C99, C11 and C++98, C++11, C++17 with -pedantic -Wall
   !> -Wextra -Werror (test/cli/header_std.sh): a C or C++ user's strictest flags see no
   !> warning (C++98 warned on long long in egw_piece_exp_ before audit23).
   subroutine test_header(error)
      type(error_type), allocatable, intent(out) :: error
      integer :: stat, cmdstat
      call execute_command_line("sh test/cli/header_std.sh include", exitstat=stat, &
         & cmdstat=cmdstat)
      call check(error, cmdstat, 0, "could not run test/cli/header_std.sh")
      if (allocated(error)) return
      call check(error, stat, 0, to_string(stat)//" compilation(s) of egw.h warned (see above)")
   end subroutine test_header

end module test_cli
