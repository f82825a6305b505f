!> Issue 13 items 2, 3, 6 (test/input_checks.c: inputs at the edges of the doubles give a
!> finite correct result or a status naming the argument and its range, in bounded time,
!> outputs untouched on refusal) and the fuzz harness in its short mode
!> (tools/fuzz/egw_fuzz.c: every C function with NaN, +-Inf, 0, +-1e300, 1e-300,
!> subnormals and extreme integers, each call forked under an alarm; fails on any
!> silent, clobbered, crashed or hung case). The harness runs as the egw-fuzz built
!> beside this tester (build/<profile>/app), like the cli suite's egw-table.
module test_input
   use, intrinsic :: iso_c_binding, only: c_int
   use testdrive, only: new_unittest, unittest_type, error_type, check, test_failed, to_string
   implicit none
   private
   public :: collect_input

   interface
      integer(c_int) function c_gauss() bind(C, name="egw_input_test_gauss")
         import :: c_int
      end function
      integer(c_int) function c_ranges() bind(C, name="egw_input_test_ranges")
         import :: c_int
      end function
      integer(c_int) function c_hertz() bind(C, name="egw_input_test_hertz")
         import :: c_int
      end function
      integer(c_int) function c_solve() bind(C, name="egw_input_test_solve")
         import :: c_int
      end function
      integer(c_int) function c_tables() bind(C, name="egw_input_test_tables")
         import :: c_int
      end function
      integer(c_int) function c_scene() bind(C, name="egw_input_test_scene")
         import :: c_int
      end function
   end interface

contains

   subroutine collect_input(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("gauss: order range, small n, overflow", t_gauss), &
         & new_unittest("parameter ranges, named", t_ranges), &
         & new_unittest("hertz at the edges of the doubles", t_hertz), &
         & new_unittest("solve: tiny delta, res, n_radial, threads", t_solve), &
         & new_unittest("tables: ranges, continuations", t_tables), &
         & new_unittest("scene choice: bounded Hertz check", t_scene), &
         & new_unittest("egw-fuzz --short: no silent/crash/hang", t_fuzz) &
         & ]
   end subroutine collect_input

   subroutine report(error, nfail)
      type(error_type), allocatable, intent(out) :: error
      integer(c_int), intent(in) :: nfail
      call check(error, int(nfail) == 0, to_string(int(nfail))//" C check(s) failed (see above)")
   end subroutine report

   subroutine t_gauss(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_gauss())
   end subroutine
   subroutine t_ranges(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_ranges())
   end subroutine
   subroutine t_hertz(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_hertz())
   end subroutine
   subroutine t_solve(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_solve())
   end subroutine
   subroutine t_tables(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_tables())
   end subroutine
   subroutine t_scene(error)
      type(error_type), allocatable, intent(out) :: error
      call report(error, c_scene())
   end subroutine

   !> egw-fuzz --short (a few hundred forked cases, 10 s alarm each); exit status 0 iff
   !> no case was silent, clobbered, crashed or hung and every valid base call succeeded.
   subroutine t_fuzz(error)
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
      exe = tester(:cut)//"app/egw-fuzz"
      call execute_command_line("'"//exe//"' --short -j 2 -t 10", exitstat=stat, &
         & cmdstat=cmdstat)
      call check(error, cmdstat, 0, "could not run "//exe)
      if (allocated(error)) return
      call check(error, stat, 0, "egw-fuzz --short found silent, clobbered, crashed or " &
         & //"hung calls (see above)")
   end subroutine t_fuzz

end module test_input
