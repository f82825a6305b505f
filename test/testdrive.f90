!> A small unit-test harness with the public API of test-drive (fortran-lang),
!> written for egw because no registry is reachable here. A user online can
!> replace this file by the real test-drive without touching the test suites.
module testdrive
   use, intrinsic :: iso_fortran_env, only: error_unit, sp => real32, dp => real64, &
      & i1 => int8, i2 => int16, i4 => int32, i8 => int64
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   implicit none
   private

   public :: run_testsuite, run_selected, new_unittest, new_testsuite, test_failed, skip_test
   public :: select_test, select_suite, check, to_string
   public :: unittest_type, testsuite_type, error_type, test_interface, collect_interface

   integer, parameter :: success = 0, fatal = 1, skipped = 77

   !> Error handle returned by a test; unallocated means the test passed.
   type :: error_type
      integer :: stat = success
      character(len=:), allocatable :: message
   end type error_type

   abstract interface
      subroutine test_interface(error)
         import :: error_type
         type(error_type), allocatable, intent(out) :: error
      end subroutine test_interface
   end interface

   type :: unittest_type
      character(len=:), allocatable :: name
      procedure(test_interface), pointer, nopass :: test => null()
      logical :: should_fail = .false.
   end type unittest_type

   abstract interface
      subroutine collect_interface(testsuite)
         import :: unittest_type
         type(unittest_type), allocatable, intent(out) :: testsuite(:)
      end subroutine collect_interface
   end interface

   type :: testsuite_type
      character(len=:), allocatable :: name
      procedure(collect_interface), pointer, nopass :: collect => null()
   end type testsuite_type

   interface check
      module procedure check_stat, check_logical, check_float_dp, check_float_sp, &
         & check_int_i1, check_int_i2, check_int_i4, check_int_i8, check_bool, check_string
   end interface check

   interface to_string
      module procedure i4_to_string, i8_to_string
   end interface to_string

contains

   function new_unittest(name, test, should_fail) result(self)
      character(len=*), intent(in) :: name
      procedure(test_interface) :: test
      logical, intent(in), optional :: should_fail
      type(unittest_type) :: self
      self%name = name
      self%test => test
      if (present(should_fail)) self%should_fail = should_fail
   end function new_unittest

   function new_testsuite(name, collect) result(self)
      character(len=*), intent(in) :: name
      procedure(collect_interface) :: collect
      type(testsuite_type) :: self
      self%name = name
      self%collect => collect
   end function new_testsuite

   !> Run every test of a suite; stat is incremented once per failed test.
   subroutine run_testsuite(collect, unit, stat, parallel)
      procedure(collect_interface) :: collect
      integer, intent(in) :: unit
      integer, intent(inout) :: stat
      logical, intent(in), optional :: parallel
      type(unittest_type), allocatable :: suite(:)
      integer :: it
      call collect(suite)
      do it = 1, size(suite)
         call run_unittest(suite(it), unit, stat)
      end do
      if (present(parallel)) continue
   end subroutine run_testsuite

   !> Run the one test called name; an unknown name counts as a failure.
   subroutine run_selected(collect, name, unit, stat)
      procedure(collect_interface) :: collect
      character(len=*), intent(in) :: name
      integer, intent(in) :: unit
      integer, intent(inout) :: stat
      type(unittest_type), allocatable :: suite(:)
      integer :: it
      call collect(suite)
      it = select_test(suite, name)
      if (it > 0 .and. it <= size(suite)) then
         call run_unittest(suite(it), unit, stat)
      else
         write (unit, '(a)') "# unknown test '"//name//"'"
         stat = stat + 1
      end if
   end subroutine run_selected

   subroutine run_unittest(test, unit, stat)
      type(unittest_type), intent(in) :: test
      integer, intent(in) :: unit
      integer, intent(inout) :: stat
      type(error_type), allocatable :: error
      character(len=:), allocatable :: label
      logical :: failed

      call test%test(error)
      if (allocated(error)) then
         if (error%stat == skipped) then
            write (unit, '(2x,a,t50,a)') test%name, "[SKIPPED]"
            if (allocated(error%message)) write (unit, '(4x,a)') error%message
            return
         end if
      end if
      failed = allocated(error) .neqv. test%should_fail
      if (test%should_fail) then
         label = merge("[UNEXPECTED PASS]", "[EXPECTED FAIL]  ", failed)
      else
         label = merge("[FAILED]", "[PASSED]", failed)
      end if
      write (unit, '(2x,a,t50,a)') test%name, trim(label)
      if (failed) then
         stat = stat + 1
         if (allocated(error)) then
            if (allocated(error%message)) write (unit, '(4x,a)') error%message
         end if
      end if
   end subroutine run_unittest

   integer function select_test(tests, name) result(pos)
      type(unittest_type), intent(in) :: tests(:)
      character(len=*), intent(in) :: name
      integer :: it
      pos = 0
      do it = 1, size(tests)
         if (name == tests(it)%name) then
            pos = it
            return
         end if
      end do
   end function select_test

   integer function select_suite(suites, name) result(pos)
      type(testsuite_type), intent(in) :: suites(:)
      character(len=*), intent(in) :: name
      integer :: it
      pos = 0
      do it = 1, size(suites)
         if (name == suites(it)%name) then
            pos = it
            return
         end if
      end do
   end function select_suite

   subroutine test_failed(error, message, more)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in) :: message
      character(len=*), intent(in), optional :: more
      call set_error(error, fatal, message, more)
   end subroutine test_failed

   subroutine skip_test(error, message, more)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in), optional :: message
      character(len=*), intent(in), optional :: more
      call set_error(error, skipped, message, more)
   end subroutine skip_test

   subroutine set_error(error, stat, message, more)
      type(error_type), allocatable, intent(out) :: error
      integer, intent(in) :: stat
      character(len=*), intent(in), optional :: message, more
      allocate (error)
      error%stat = stat
      error%message = ""
      if (present(message)) error%message = message
      if (present(more)) error%message = error%message//" ("//more//")"
   end subroutine set_error

   subroutine check_stat(error, stat, message, more)
      type(error_type), allocatable, intent(out) :: error
      integer, intent(in) :: stat
      character(len=*), intent(in), optional :: message, more
      if (stat /= success) then
         call set_error(error, fatal, default_msg(message, "non-zero exit code encountered"), more)
      end if
   end subroutine check_stat

   subroutine check_logical(error, expression, message, more)
      type(error_type), allocatable, intent(out) :: error
      logical, intent(in) :: expression
      character(len=*), intent(in), optional :: message, more
      if (.not. expression) then
         call set_error(error, fatal, default_msg(message, "condition not fullfilled"), more)
      end if
   end subroutine check_logical

   !> Real check: absolute difference against thr, or relative to |expected| when rel.
   subroutine check_float_dp(error, actual, expected, message, more, thr, rel)
      type(error_type), allocatable, intent(out) :: error
      real(dp), intent(in) :: actual, expected
      character(len=*), intent(in), optional :: message, more
      real(dp), intent(in), optional :: thr
      logical, intent(in), optional :: rel
      real(dp) :: tol, diff
      logical :: relative
      tol = epsilon(expected)
      if (present(thr)) tol = thr
      relative = .false.
      if (present(rel)) relative = rel
      if (ieee_is_nan(actual) .neqv. ieee_is_nan(expected)) then
         call set_error(error, fatal, default_msg(message, "NaN where a number was expected"), more)
         return
      end if
      if (ieee_is_nan(actual)) return
      if (actual == expected) return
      diff = abs(actual - expected)
      if (relative) then
         if (diff > tol*abs(expected)) call set_error(error, fatal, default_msg(message, &
            & "floating point value mismatch")//": actual "//real_str(actual)//" expected " &
            & //real_str(expected)//" rel.diff "//real_str(diff/abs(expected)), more)
      else
         if (diff > tol) call set_error(error, fatal, default_msg(message, &
            & "floating point value mismatch")//": actual "//real_str(actual)//" expected " &
            & //real_str(expected)//" abs.diff "//real_str(diff), more)
      end if
   end subroutine check_float_dp

   subroutine check_float_sp(error, actual, expected, message, more, thr, rel)
      type(error_type), allocatable, intent(out) :: error
      real(sp), intent(in) :: actual, expected
      character(len=*), intent(in), optional :: message, more
      real(sp), intent(in), optional :: thr
      logical, intent(in), optional :: rel
      real(dp) :: tol
      tol = epsilon(expected)
      if (present(thr)) tol = thr
      call check_float_dp(error, real(actual, dp), real(expected, dp), message, more, tol, rel)
   end subroutine check_float_sp

   subroutine check_int_i1(error, actual, expected, message, more)
      type(error_type), allocatable, intent(out) :: error
      integer(i1), intent(in) :: actual, expected
      character(len=*), intent(in), optional :: message, more
      call check_int_i8(error, int(actual, i8), int(expected, i8), message, more)
   end subroutine check_int_i1

   subroutine check_int_i2(error, actual, expected, message, more)
      type(error_type), allocatable, intent(out) :: error
      integer(i2), intent(in) :: actual, expected
      character(len=*), intent(in), optional :: message, more
      call check_int_i8(error, int(actual, i8), int(expected, i8), message, more)
   end subroutine check_int_i2

   subroutine check_int_i4(error, actual, expected, message, more)
      type(error_type), allocatable, intent(out) :: error
      integer(i4), intent(in) :: actual, expected
      character(len=*), intent(in), optional :: message, more
      call check_int_i8(error, int(actual, i8), int(expected, i8), message, more)
   end subroutine check_int_i4

   subroutine check_int_i8(error, actual, expected, message, more)
      type(error_type), allocatable, intent(out) :: error
      integer(i8), intent(in) :: actual, expected
      character(len=*), intent(in), optional :: message, more
      if (actual /= expected) call set_error(error, fatal, default_msg(message, &
         & "integer value mismatch")//": actual "//i8_to_string(actual)//" expected " &
         & //i8_to_string(expected), more)
   end subroutine check_int_i8

   subroutine check_bool(error, actual, expected, message, more)
      type(error_type), allocatable, intent(out) :: error
      logical, intent(in) :: actual, expected
      character(len=*), intent(in), optional :: message, more
      if (actual .neqv. expected) call set_error(error, fatal, &
         & default_msg(message, "logical value mismatch"), more)
   end subroutine check_bool

   subroutine check_string(error, actual, expected, message, more)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in) :: actual, expected
      character(len=*), intent(in), optional :: message, more
      if (actual /= expected) call set_error(error, fatal, default_msg(message, &
         & "character string mismatch")//": actual '"//actual//"' expected '"//expected//"'", more)
   end subroutine check_string

   pure function default_msg(message, fallback) result(msg)
      character(len=*), intent(in), optional :: message
      character(len=*), intent(in) :: fallback
      character(len=:), allocatable :: msg
      if (present(message)) then
         msg = message
      else
         msg = fallback
      end if
   end function default_msg

   pure function i4_to_string(val) result(str)
      integer(i4), intent(in) :: val
      character(len=:), allocatable :: str
      str = i8_to_string(int(val, i8))
   end function i4_to_string

   pure function i8_to_string(val) result(str)
      integer(i8), intent(in) :: val
      character(len=:), allocatable :: str
      character(len=24) :: buf
      write (buf, '(i0)') val
      str = trim(buf)
   end function i8_to_string

   function real_str(x) result(str)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: str
      character(len=32) :: buf
      write (buf, '(es24.16e3)') x
      str = trim(adjustl(buf))
   end function real_str

end module testdrive
