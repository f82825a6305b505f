!> Tests of egw_text (numbers to text and back without Fortran I/O) and egw_io's
!> checked writes. References: gfortran's own formatted I/O, run here on one thread
!> (an independent implementation: libgfortran over glibc's exact conversions), and
!> /dev/full, a device on which every write fails with ENOSPC (a full disk).
module test_text_io
   use, intrinsic :: iso_fortran_env, only: int64
   use, intrinsic :: iso_c_binding, only: c_int
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_is_finite
   use testdrive, only: new_unittest, unittest_type, error_type, check, to_string
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_io_error
   use egw_text, only: int_text, real_text, parse_real, parse_int, to_lower
   use egw_io, only: write_stream, write_file, read_file
   implicit none
   private
   public :: collect_text_io

contains

   subroutine collect_text_io(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("real_text is ES, bit patterns", test_format_random), &
         & new_unittest("parse_real: nearest double", test_parse_random), &
         & new_unittest("special values and bad text", test_special), &
         & new_unittest("integers", test_integers), &
         & new_unittest("full device: EGW_IO_ERROR", test_full_device), &
         & new_unittest("write_file onto a directory, read_file of one", test_directory), &
         & new_unittest("no deferred-length function results", test_no_deferred), &
         & new_unittest("to_lower = C's tolower, every byte", test_to_lower) &
         & ]
   end subroutine collect_text_io

   !> 20000 random bit patterns (every exponent, subnormals included): real_text equals
   !> gfortran's ES25.17E3 and ES20.12E3 output, and reads back bit for bit.
   subroutine test_format_random(error)
      type(error_type), allocatable, intent(out) :: error
      integer :: i
      integer(int64) :: bits
      real(dp) :: x, y, r(2)
      character(len=40) :: buf
      logical :: ok
      call random_seed()
      do i = 1, 20000
         call random_number(r)
         bits = int(r(1)*2.0_dp**62, int64)*2 + int(r(2)*2, int64)
         x = transfer(bits, x)
         if (.not. ieee_is_finite(x)) cycle
         write (buf, '(es25.17e3)') x
         call check(error, real_text(x, 17, 3), trim(adjustl(buf)))
         if (allocated(error)) return
         write (buf, '(es20.12e3)') x
         call check(error, real_text(x, 12, 3), trim(adjustl(buf)))
         if (allocated(error)) return
         call parse_real(real_text(x, 17, 3), y, ok)
         call check(error, ok .and. transfer(y, bits) == transfer(x, bits), &
            & "round trip of "//real_text(x, 17, 3))
         if (allocated(error)) return
      end do
   end subroutine test_format_random

   !> Text of 1 to 19 significant digits (ties included) reads to what gfortran's
   !> list-directed READ gives.
   subroutine test_parse_random(error)
      type(error_type), allocatable, intent(out) :: error
      integer :: i, nd
      real(dp) :: x, y, z, r(3)
      character(len=48) :: buf, fmtx
      logical :: ok
      do i = 1, 20000
         call random_number(r)
         x = (r(1) + 0.5_dp)*10.0_dp**int(620*r(2) - 310)
         nd = 1 + int(19*r(3))
         write (fmtx, '(a,i0,a,i0,a)') "(es", nd + 10, ".", nd - 1, "e3)"
         write (buf, fmtx) x
         read (buf, *) z
         call parse_real(buf, y, ok)
         call check(error, ok .and. (y == z .or. (y == 0 .and. z == 0)), &
            & "parse_real('"//trim(adjustl(buf))//"') = "//real_text(y, 17, 3)// &
            & ", gfortran reads "//real_text(z, 17, 3))
         if (allocated(error)) return
      end do
      ! exact halfway cases round to even: 2^53 + 1 and 2^53 + 3
      call parse_real("9007199254740993", y, ok)
      call check(error, ok .and. y == 9007199254740992.0_dp, "tie 2^53+1 to even")
      if (allocated(error)) return
      call parse_real("9007199254740995", y, ok)
      call check(error, ok .and. y == 9007199254740996.0_dp, "tie 2^53+3 to even")
   end subroutine test_parse_random

   subroutine test_special(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: y
      logical :: ok
      call parse_real("4.9406564584124654E-324", y, ok)
      call check(error, ok .and. y > 0 .and. y == tiny(y)*2.0_dp**(-52), "min subnormal")
      if (allocated(error)) return
      call parse_real("1e400", y, ok)
      call check(error, ok .and. .not. ieee_is_finite(y) .and. y > 0, "overflow to +Inf")
      if (allocated(error)) return
      call parse_real(" -1.5D3 ", y, ok)
      call check(error, ok .and. y == -1500.0_dp, "D exponent, blanks")
      if (allocated(error)) return
      call parse_real("nan", y, ok)
      call check(error, ok .and. ieee_is_nan(y), "NaN")
      if (allocated(error)) return
      call check(error, real_text(-0.0_dp, 17, 3), "-0.00000000000000000E+000")
      if (allocated(error)) return
      call check(error, real_text(huge(1.0_dp), 17, 3), "1.79769313486231571E+308")
      if (allocated(error)) return
      call check(error, real_text(1.0e100_dp, 4, 2), "1.0000E+100")
      if (allocated(error)) return
      block
         character(len=12), parameter :: bad(7) = [character(len=12) :: "", "abc", "1.0e", &
            & "1..0", "1,0", "--1", "1e5x"]
         integer :: i
         do i = 1, size(bad)
            call parse_real(bad(i), y, ok)
            call check(error, .not. ok, "'"//trim(bad(i))//"' accepted")
            if (allocated(error)) return
         end do
      end block
   end subroutine test_special

   subroutine test_integers(error)
      type(error_type), allocatable, intent(out) :: error
      integer :: k, v
      character(len=16) :: buf
      logical :: ok
      do k = -100000, 100000, 37
         write (buf, '(i0)') k
         call check(error, int_text(k), trim(buf))
         if (allocated(error)) return
      end do
      call check(error, int_text(-huge(1) - 1), "-2147483648")
      if (allocated(error)) return
      call parse_int(" -42 ", v, ok)
      call check(error, ok .and. v == -42, "parse_int")
      if (allocated(error)) return
      call parse_int("2147483648", v, ok)
      call check(error, .not. ok, "int overflow accepted")
      if (allocated(error)) return
      call parse_int("4.0", v, ok)
      call check(error, .not. ok, "4.0 read as an integer")
   end subroutine test_integers

   !> Every write to /dev/full fails with ENOSPC, as on a full disk: the checked write
   !> (the one write_file uses for its temporary file) must report it, not succeed.
   subroutine test_full_device(error)
      type(error_type), allocatable, intent(out) :: error
      type(egw_error), allocatable :: e
      logical :: exists
      inquire (file="/dev/full", exist=exists)
      if (.not. exists) return  ! not Linux: nothing to check
      call write_stream("/dev/full", repeat("x", 100000), e)
      call check(error, allocated(e), "writing to /dev/full reported success")
      if (allocated(error)) return
      call check(error, e%stat == egw_io_error, "status "//to_string(e%stat))
      if (allocated(error)) return
      call check(error, index(e%message, "No space left") > 0, e%message)
      if (allocated(error)) return
      ! a short write too (it fails only when flushed)
      call write_stream("/dev/full", "x", e)
      call check(error, allocated(e), "a 1-byte write to /dev/full reported success")
      if (allocated(error)) return
      call write_stream("/dev/null", "x", e)
      call check(error, .not. allocated(e), "writing to /dev/null failed")
   end subroutine test_full_device

   !> A directory in the way: egw_io_error, and no temporary file beside it.
   subroutine test_directory(error)
      type(error_type), allocatable, intent(out) :: error
      type(egw_error), allocatable :: e
      character(len=:), allocatable :: bytes
      character(len=*), parameter :: dir = "build/test_text_io"
      integer :: stat
      call execute_command_line("mkdir -p "//dir//"/in_the_way/x", exitstat=stat)
      call write_file(dir//"/in_the_way", "text", e)
      call check(error, allocated(e), "writing onto a directory reported success")
      if (allocated(error)) return
      call check(error, e%stat == egw_io_error .and. index(e%message, "cannot rename") > 0, &
         & e%message)
      if (allocated(error)) return
      call execute_command_line("ls -a "//dir//" | grep -q egw-tmp", exitstat=stat)
      call check(error, stat /= 0, "a temporary file was left in "//dir)
      if (allocated(error)) return
      call write_file(dir//"/ok.txt", "two"//new_line("a")//"lines"//new_line("a"), e)
      call check(error, .not. allocated(e), "write_file failed")
      if (allocated(error)) return
      call read_file(dir//"/ok.txt", bytes, e)
      call check(error, .not. allocated(e) .and. bytes == "two"//new_line("a")//"lines"// &
         & new_line("a"), "read_file does not give back what was written")
      if (allocated(error)) return
      ! a directory given as a file (a table, scene or law path): the system's reason, not
      ! the huge "size" a directory seeks to (before: "larger than 2147483647 bytes")
      call read_file(dir//"/in_the_way", bytes, e)
      call check(error, allocated(e), "reading a directory reported success")
      if (allocated(error)) return
      call check(error, e%stat == egw_io_error .and. index(e%message, "Is a directory") > 0, &
         & e%message)
   end subroutine test_directory

   !> No function in src/ returns character(len=:), allocatable: gfortran 12 keeps the
   !> length of such a result in a static variable of the caller, so threads calling
   !> the same line at once corrupt text and the heap (egw_text explains the remedy).
   subroutine test_no_deferred(error)
      type(error_type), allocatable, intent(out) :: error
      type(egw_error), allocatable :: e
      character(len=:), allocatable :: list, text, offenders
      integer :: stat, start, eol
      call execute_command_line("mkdir -p build && ls src/*.f90 src/egw/*/*.f90 "// &
         & "> build/test_text_io_sources.txt", exitstat=stat)
      call read_file("build/test_text_io_sources.txt", list, e)
      call check(error, stat == 0 .and. .not. allocated(e), "cannot list src/*.f90")
      if (allocated(error)) return
      offenders = ""
      start = 1
      do while (start < len(list))
         eol = index(list(start:), new_line("a")) + start - 1
         if (eol < start) eol = len(list) + 1
         call read_file(list(start:eol - 1), text, e)
         if (.not. allocated(e)) call scan_functions(list(start:eol - 1), text, offenders)
         start = eol + 1
      end do
      call check(error, len(offenders) == 0, "deferred-length function results:"//offenders)
   end subroutine test_no_deferred

   !> Append "file:function" for each function of text whose result is declared
   !> character(len=:), allocatable.
   subroutine scan_functions(path, text, offenders)
      character(len=*), intent(in) :: path, text
      character(len=:), allocatable, intent(inout) :: offenders
      character(len=:), allocatable :: lower, name, res
      integer :: at, open_paren, body_end, k, r, decl, eol
      lower = text
      do k = 1, len(lower)
         if (lower(k:k) >= "A" .and. lower(k:k) <= "Z") lower(k:k) = achar(iachar(lower(k:k)) + 32)
      end do
      at = 1
      do
         k = index(lower(at:), "function ")
         if (k == 0) exit
         at = at + k - 1 + len("function ")
         ! a declaration, not "end function" or a comment
         eol = index(lower(1:at), new_line("a"), back=.true.)
         if (index(lower(eol + 1:at), "end") > 0 .or. index(lower(eol + 1:at), "!") > 0) cycle
         open_paren = index(lower(at:), "(") + at - 1
         if (open_paren < at) exit
         name = trim(adjustl(lower(at:open_paren - 1)))
         if (len(name) == 0 .or. verify(name, "abcdefghijklmnopqrstuvwxyz0123456789_") /= 0) &
            & cycle
         body_end = index(lower(at:), "end function") + at - 1
         if (body_end < at) exit
         res = name
         eol = index(lower(at:), new_line("a")) + at - 1
         r = index(lower(at:eol), "result(")
         if (r > 0) res = lower(at + r + 6:at + r + 5 + index(lower(at + r + 6:eol), ")") - 1)
         decl = at
         do
            k = index(lower(decl:body_end), "character(len=:), allocatable")
            if (k == 0) exit
            decl = decl + k - 1
            eol = index(lower(decl:), new_line("a")) + decl - 1
            if (has_word(lower(index(lower(decl:eol), "::") + decl + 1:eol), res) .and. &
               & index(lower(decl:eol), "intent") == 0) then
               offenders = offenders//" "//path//":"//name
               exit
            end if
            decl = eol
         end do
      end do
   end subroutine scan_functions

   pure logical function has_word(text, word)
      character(len=*), intent(in) :: text, word
      character(len=*), parameter :: ident = "abcdefghijklmnopqrstuvwxyz0123456789_"
      integer :: k, at
      has_word = .false.
      at = 1
      do
         k = index(text(at:), word)
         if (k == 0) return
         k = at + k - 1
         has_word = .true.
         if (k > 1) has_word = index(ident, text(k - 1:k - 1)) == 0
         if (has_word .and. k + len(word) <= len(text)) &
            & has_word = index(ident, text(k + len(word):k + len(word))) == 0
         if (has_word) return
         at = k + 1
      end do
   end function has_word

   !> to_lower on all 256 bytes at once equals the C library's tolower byte by byte (an
   !> independent implementation; a Fortran program runs in the "C" locale, where only
   !> A-Z change). Bytes compare exactly: no tolerance.
   subroutine test_to_lower(error)
      type(error_type), allocatable, intent(out) :: error
      interface
         pure function c_tolower(c) result(lower) bind(C, name="tolower")
            import :: c_int
            integer(c_int), value, intent(in) :: c
            integer(c_int) :: lower
         end function c_tolower
      end interface
      character(len=256) :: bytes, lower
      integer :: i
      do i = 0, 255
         bytes(i + 1:i + 1) = achar(i)
      end do
      lower = to_lower(bytes)
      do i = 0, 255
         call check(error, iachar(lower(i + 1:i + 1)), int(c_tolower(int(i, c_int))), &
            & "byte "//to_string(i))
         if (allocated(error)) return
      end do
   end subroutine test_to_lower

end module test_text_io
