!> Decimal text of integers and doubles, both ways, in plain Fortran (no internal I/O):
!> the results' lengths are known before the call (see below), and the reader is
!> stricter than a list-directed READ (one number per field, no null values, no
!> separators or repeat counts). Doubles are converted exactly: the binary value is expanded into a big decimal
!> integer and rounded half-to-even (what glibc's printf and gfortran's ES edit
!> descriptor do), and text is read to the nearest double by an exact comparison
!> with the halfway points (so 17 significant digits read back bit for bit).
!>
!> The functions' results have lengths given by specification functions (int_text_len,
!> real_text_len), not deferred lengths: gfortran 12 keeps the length of a deferred-
!> length (character(len=:), allocatable) function result in a static variable of the
!> caller, which threads running the same line at once overwrite (wrong lengths, blank
!> CSV fields, garbled messages, heap corruption). egw's functions returning text all
!> follow this rule; text of unknown length comes from subroutines with a deferred-
!> length intent(out) argument, which are safe.
module egw_text
   use, intrinsic :: iso_fortran_env, only: int64
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_is_finite, ieee_value, &
      & ieee_positive_inf, ieee_negative_inf, ieee_quiet_nan, ieee_next_after
   use egw_kinds, only: dp
   implicit none
   private

   public :: int_text, real_text, parse_real, parse_int, int_text_len, real_text_len
   public :: csv_row, csv_row_len, to_lower

   interface int_text
      module procedure int_text_32, int_text_64
   end interface int_text
   interface int_text_len
      module procedure int_text_len_32, int_text_len_64
   end interface int_text_len

   !> Limbs of the big integers, base 10^9 (enough for 400 digits times 10^-1100).
   integer, parameter :: max_limbs = 200
   integer(int64), parameter :: limb_base = 1000000000_int64
   !> Most significant digits parse_real accepts.
   integer, parameter :: max_digits = 400
   integer, parameter :: qp = selected_real_kind(33)

   type :: big_int
      integer(int64) :: limb(max_limbs) = 0  ! little-endian, base 10^9
      integer :: n = 1
   end type big_int

contains

   !> Length of int_text(i) (sign and digits).
   pure integer function int_text_len_32(i) result(n)
      integer, intent(in) :: i   !< any integer
      n = int_text_len_64(int(i, int64))
   end function int_text_len_32

   !> Length of int_text(i) for an int64 (sign and digits).
   pure integer function int_text_len_64(i) result(n)
      integer(int64), intent(in) :: i   !< any int64
      integer(int64) :: v
      n = merge(2, 1, i < 0)
      v = i/10
      do while (v /= 0)
         n = n + 1
         v = v/10
      end do
   end function int_text_len_64

   !> Decimal text of an integer (as the I0 edit descriptor writes it).
   pure function int_text_32(i) result(str)
      integer, intent(in) :: i   !< any integer
      character(len=int_text_len_32(i)) :: str
      str = int_text_64(int(i, int64))
   end function int_text_32

   !> Decimal text of an int64.
   pure function int_text_64(i) result(str)
      integer(int64), intent(in) :: i   !< any int64
      character(len=int_text_len_64(i)) :: str
      integer(int64) :: v
      integer :: pos
      v = i
      pos = len(str) + 1
      do
         pos = pos - 1
         str(pos:pos) = achar(iachar("0") + abs(int(mod(v, 10_int64))))
         v = v/10
         if (v == 0) exit
      end do
      if (i < 0) str(1:1) = "-"
   end function int_text_64

   !> x as the ES edit descriptor ESw.dEe writes it, without leading blanks: one digit,
   !> the point, `decimals` digits, "E", the exponent's sign and `exp_digits` digits
   !> (more if needed); "NaN", "Infinity", "-Infinity" for those.
   pure subroutine real_text_sub(x, decimals, exp_digits, str)
      real(dp), intent(in) :: x
      integer, intent(in) :: decimals, exp_digits
      character(len=:), allocatable, intent(out) :: str
      character(len=:), allocatable :: digits, ex
      integer :: e10, nd
      if (ieee_is_nan(x)) then
         str = "NaN"
         return
      end if
      if (.not. ieee_is_finite(x)) then
         if (x > 0) then
            str = "Infinity"
         else
            str = "-Infinity"
         end if
         return
      end if
      nd = decimals + 1
      call decimal_digits(abs(x), nd, digits, e10)
      allocate (character(len=int_text_len(abs(e10))) :: ex)
      ex = int_text(abs(e10))
      if (len(ex) < exp_digits) ex = repeat("0", exp_digits - len(ex))//ex
      str = digits(1:1)//"."//digits(2:nd)//"E"//merge("+", "-", e10 >= 0)//ex
      if (sign(1.0_dp, x) < 0) str = "-"//str
   end subroutine real_text_sub

   !> Length of real_text(x, decimals, exp_digits) (cheap unless the exponent's digits
   !> are in doubt: then x is converted).
   pure integer function real_text_len(x, decimals, exp_digits) result(n)
      real(dp), intent(in) :: x   !< any double (NaN and Inf too)
      !> digits after the point (d), and of the exponent (e)
      integer, intent(in) :: decimals, exp_digits
      character(len=:), allocatable :: text
      real(dp) :: magnitude
      if (ieee_is_nan(x)) then
         n = 3
      else if (.not. ieee_is_finite(x)) then
         n = merge(8, 9, x > 0)
      else
         ! sign, digit, point, decimals, "E", exponent sign, exponent digits
         n = merge(1, 0, sign(1.0_dp, x) < 0) + 4 + decimals + exp_digits
         if (x /= 0.0_dp .and. exp_digits < 3) then
            magnitude = abs(log10(abs(x)))
            if (magnitude > 10.0_dp**exp_digits - 3) then
               call real_text_sub(x, decimals, exp_digits, text)
               n = len(text)
            end if
         end if
      end if
   end function real_text_len

   !> x as ESw.dEe writes it (see real_text_sub).
   pure function real_text(x, decimals, exp_digits) result(str)
      real(dp), intent(in) :: x   !< any double (NaN and Inf too)
      !> digits after the point (d), and of the exponent (e)
      integer, intent(in) :: decimals, exp_digits
      character(len=real_text_len(x, decimals, exp_digits)) :: str
      character(len=:), allocatable :: text
      call real_text_sub(x, decimals, exp_digits, text)
      str = text
   end function real_text

   !> Read an integer: optional blanks, an optional sign, digits, optional blanks.
   pure subroutine parse_int(text, k, ok)
      character(len=*), intent(in) :: text   !< the text to read
      integer, intent(out) :: k   !< its value (meaningful only when ok)
      logical, intent(out) :: ok   !< false for other text or a value beyond the default integer
      character(len=:), allocatable :: t
      integer(int64) :: v
      integer :: i, first
      k = 0
      t = trim(adjustl(text))
      ok = len(t) > 0
      if (.not. ok) return
      first = 1
      if (t(1:1) == "+" .or. t(1:1) == "-") first = 2
      ok = len(t) >= first .and. len(t) - first < 12
      if (.not. ok) return
      v = 0
      do i = first, len(t)
         if (.not. is_digit(t(i:i))) then
            ok = .false.
            return
         end if
         v = 10*v + (iachar(t(i:i)) - iachar("0"))
      end do
      if (t(1:1) == "-") v = -v
      ok = v >= -huge(k) - 1_int64 .and. v <= huge(k)
      if (ok) k = int(v)
   end subroutine parse_int

   !> Read a real: optional blanks, sign, digits with an optional point, an optional
   !> exponent (E, e, D or d, optional sign, digits); also NaN, Inf, Infinity. The
   !> nearest double (ties to even); beyond the range: +-Infinity or +-0.
   pure subroutine parse_real(text, x, ok)
      character(len=*), intent(in) :: text   !< the text to read
      real(dp), intent(out) :: x   !< the nearest double (meaningful only when ok)
      logical, intent(out) :: ok   !< false for text of another form
      character(len=:), allocatable :: t, lower
      character(len=max_digits) :: digits
      integer :: i, nd, e10, ex, first
      logical :: negative, seen_digit, seen_point
      x = 0.0_dp
      t = trim(adjustl(text))
      ok = .false.
      if (len(t) == 0) return
      negative = t(1:1) == "-"
      first = 1
      if (t(1:1) == "+" .or. t(1:1) == "-") first = 2
      lower = to_lower(t(first:))
      if (lower == "nan") then
         x = ieee_value(x, ieee_quiet_nan)
         ok = .true.
         return
      else if (lower == "inf" .or. lower == "infinity") then
         x = ieee_value(x, merge(ieee_negative_inf, ieee_positive_inf, negative))
         ok = .true.
         return
      end if
      nd = 0
      e10 = 0
      seen_digit = .false.
      seen_point = .false.
      i = first
      do while (i <= len(t))
         if (is_digit(t(i:i))) then
            seen_digit = .true.
            if (nd > 0 .or. t(i:i) /= "0") then
               nd = nd + 1
               if (nd > max_digits) return
               digits(nd:nd) = t(i:i)
               if (seen_point) e10 = e10 - 1
            else if (seen_point) then
               e10 = e10 - 1
            end if
         else if (t(i:i) == "." .and. .not. seen_point) then
            seen_point = .true.
         else
            exit
         end if
         i = i + 1
      end do
      if (.not. seen_digit) return
      if (i <= len(t)) then
         if (index("eEdD", t(i:i)) == 0 .or. i == len(t)) return
         call parse_int(t(i + 1:), ex, ok)
         if (.not. ok) return
         ok = .false.
         if (abs(ex) > 100000) then
            ! far beyond the range of a double (and of e10 arithmetic)
            if (nd > 0) then
               if (ex > 0) then
                  x = ieee_value(x, ieee_positive_inf)
               else
                  x = 0.0_dp
               end if
            end if
            if (negative) x = -x
            ok = .true.
            return
         end if
         e10 = e10 + ex
      end if
      ok = .true.
      if (nd > 0) x = nearest_double(digits(1:nd), e10)
      if (negative) x = -x
   end subroutine parse_real

   ! ------------------------------------------------------------ internals

   !> The first nd significant decimal digits of y > 0 (or zeros), rounded half to even,
   !> and the decimal exponent e10 of the first: y ~ 0.d1d2... x 10^(e10+1).
   pure subroutine decimal_digits(y, nd, digits, e10)
      real(dp), intent(in) :: y
      integer, intent(in) :: nd
      character(len=:), allocatable, intent(out) :: digits
      integer, intent(out) :: e10
      type(big_int) :: b
      character(len=:), allocatable :: all
      integer(int64) :: m
      integer :: e2, i
      logical :: up
      if (y == 0.0_dp) then
         digits = repeat("0", nd)
         e10 = 0
         return
      end if
      call split_double(y, m, e2)
      call big_set(b, m)
      if (e2 >= 0) then
         call big_mul_pow2(b, e2)
         e10 = 0
      else
         call big_mul_pow5(b, -e2)
         e10 = e2
      end if
      call big_text(b, all)
      ! y = all x 10^e10 exactly; the first digit's exponent:
      e10 = e10 + len(all) - 1
      if (len(all) <= nd) then
         digits = all//repeat("0", nd - len(all))
         return
      end if
      digits = all(1:nd)
      ! round half to even on the exact remainder
      if (all(nd + 1:nd + 1) > "5") then
         up = .true.
      else if (all(nd + 1:nd + 1) < "5") then
         up = .false.
      else
         up = verify(all(nd + 2:), "0") /= 0
         if (.not. up) up = mod(iachar(digits(nd:nd)) - iachar("0"), 2) == 1
      end if
      if (.not. up) return
      do i = nd, 1, -1
         if (digits(i:i) == "9") then
            digits(i:i) = "0"
         else
            digits(i:i) = achar(iachar(digits(i:i)) + 1)
            return
         end if
      end do
      ! 99..9 rounded up to 100..0
      digits = "1"//digits(1:nd - 1)
      e10 = e10 + 1
   end subroutine decimal_digits

   !> y > 0 finite as m 2^e2 with an integer m < 2^53 (exact, subnormals included).
   pure subroutine split_double(y, m, e2)
      real(dp), intent(in) :: y
      integer(int64), intent(out) :: m
      integer, intent(out) :: e2
      e2 = exponent(y) - digits(y)
      ! below the smallest normal exponent the last bits of the scaled fraction are 0
      if (e2 < minexponent(y) - digits(y)) e2 = minexponent(y) - digits(y)
      m = int(scale(y, -e2), int64)
   end subroutine split_double

   !> The double nearest to 0.digits... no: to the integer `digits` times 10^e10 (digits
   !> has no leading zero), ties to even.
   pure function nearest_double(digits, e10) result(x)
      character(len=*), intent(in) :: digits
      integer, intent(in) :: e10
      real(dp) :: x
      real(qp) :: q
      integer :: i, nq, iter, c
      integer(int64) :: m
      integer :: e2
      real(dp) :: lower, upper
      ! beyond the range: decided by the position of the first digit
      if (e10 + len(digits) > 310) then
         x = ieee_value(x, ieee_positive_inf)
         return
      else if (e10 + len(digits) < -330) then
         x = 0.0_dp
         return
      end if
      ! a close candidate from quad precision (113 bits), then exact corrections
      nq = min(len(digits), 34)
      q = 0.0_qp
      do i = 1, nq
         q = 10*q + (iachar(digits(i:i)) - iachar("0"))
      end do
      q = q*10.0_qp**(e10 + len(digits) - nq)
      x = real(q, dp)
      do iter = 1, 4
         if (.not. ieee_is_finite(x)) return
         if (x == 0.0_dp) then
            ! compare with half the smallest subnormal
            c = compare_halfway(digits, e10, 1_int64, minexponent(x) - digits_of(x) - 1)
            if (c > 0) x = ieee_next_after(0.0_dp, 1.0_dp)
            return
         end if
         call split_double(x, m, e2)
         ! upper halfway point (2m+1) 2^(e2-1)
         c = compare_halfway(digits, e10, 2*m + 1, e2 - 1)
         if (c > 0 .or. (c == 0 .and. mod(m, 2_int64) == 1)) then
            upper = ieee_next_after(x, huge(x))
            if (upper > huge(x)) then
               x = ieee_value(x, ieee_positive_inf)
               return
            end if
            x = upper
            if (c == 0) return
            cycle
         end if
         ! lower halfway point: (2m-1) 2^(e2-1), or (4m-1) 2^(e2-2) just above a power of 2
         if (m == 2_int64**(digits_of(x) - 1) .and. e2 > minexponent(x) - digits_of(x)) then
            c = compare_halfway(digits, e10, 4*m - 1, e2 - 2)
         else
            c = compare_halfway(digits, e10, 2*m - 1, e2 - 1)
         end if
         if (c < 0 .or. (c == 0 .and. mod(m, 2_int64) == 1)) then
            lower = ieee_next_after(x, 0.0_dp)
            x = lower
            if (c == 0) return
            cycle
         end if
         return
      end do
   end function nearest_double

   pure integer function digits_of(x)
      real(dp), intent(in) :: x
      digits_of = digits(x)
   end function digits_of

   !> Sign of digits x 10^e10 - h x 2^e2 (h > 0), exactly.
   pure integer function compare_halfway(digits, e10, h, e2) result(c)
      character(len=*), intent(in) :: digits
      integer, intent(in) :: e10, e2
      integer(int64), intent(in) :: h
      type(big_int) :: a, b
      call big_from_digits(a, digits)
      call big_set(b, h)
      if (e10 >= 0) then
         call big_mul_pow2(a, e10)
         call big_mul_pow5(a, e10)
      else
         call big_mul_pow2(b, -e10)
         call big_mul_pow5(b, -e10)
      end if
      if (e2 >= 0) then
         call big_mul_pow2(b, e2)
      else
         call big_mul_pow2(a, -e2)
      end if
      c = big_compare(a, b)
   end function compare_halfway

   pure subroutine big_set(b, v)
      type(big_int), intent(out) :: b
      integer(int64), intent(in) :: v
      integer(int64) :: r
      r = v
      b%n = 0
      do
         b%n = b%n + 1
         b%limb(b%n) = mod(r, limb_base)
         r = r/limb_base
         if (r == 0) exit
      end do
   end subroutine big_set

   pure subroutine big_from_digits(b, digits)
      type(big_int), intent(out) :: b
      character(len=*), intent(in) :: digits
      integer :: hi, lo, i
      integer(int64) :: v
      b%n = 0
      hi = len(digits)
      do while (hi >= 1)
         lo = max(1, hi - 8)
         v = 0
         do i = lo, hi
            v = 10*v + (iachar(digits(i:i)) - iachar("0"))
         end do
         b%n = b%n + 1
         b%limb(b%n) = v
         hi = lo - 1
      end do
      if (b%n == 0) b%n = 1
   end subroutine big_from_digits

   !> b = b * f for 0 < f < 2^31 (limb * f + carry stays below 2^63).
   pure subroutine big_mul_small(b, f)
      type(big_int), intent(inout) :: b
      integer(int64), intent(in) :: f
      integer(int64) :: carry, t
      integer :: i
      carry = 0
      do i = 1, b%n
         t = b%limb(i)*f + carry
         b%limb(i) = mod(t, limb_base)
         carry = t/limb_base
      end do
      do while (carry > 0)
         b%n = b%n + 1
         b%limb(b%n) = mod(carry, limb_base)
         carry = carry/limb_base
      end do
   end subroutine big_mul_small

   pure subroutine big_mul_pow2(b, k)
      type(big_int), intent(inout) :: b
      integer, intent(in) :: k
      integer :: left
      left = k
      do while (left >= 30)
         call big_mul_small(b, 2_int64**30)
         left = left - 30
      end do
      if (left > 0) call big_mul_small(b, 2_int64**left)
   end subroutine big_mul_pow2

   pure subroutine big_mul_pow5(b, k)
      type(big_int), intent(inout) :: b
      integer, intent(in) :: k
      integer :: left
      left = k
      do while (left >= 13)
         call big_mul_small(b, 5_int64**13)
         left = left - 13
      end do
      if (left > 0) call big_mul_small(b, 5_int64**left)
   end subroutine big_mul_pow5

   pure integer function big_compare(a, b) result(c)
      type(big_int), intent(in) :: a, b
      integer :: i
      c = 0
      if (a%n /= b%n) then
         c = merge(1, -1, a%n > b%n)
         return
      end if
      do i = a%n, 1, -1
         if (a%limb(i) /= b%limb(i)) then
            c = merge(1, -1, a%limb(i) > b%limb(i))
            return
         end if
      end do
   end function big_compare

   !> Decimal digits of b without leading zeros.
   pure subroutine big_text(b, str)
      type(big_int), intent(in) :: b
      character(len=:), allocatable, intent(out) :: str
      character(len=9) :: chunk
      integer(int64) :: v
      integer :: i, j
      allocate (character(len=int_text_len(b%limb(b%n))) :: str)
      str = int_text(b%limb(b%n))
      do i = b%n - 1, 1, -1
         v = b%limb(i)
         do j = 9, 1, -1
            chunk(j:j) = achar(iachar("0") + int(mod(v, 10_int64)))
            v = v/10
         end do
         str = str//chunk
      end do
   end subroutine big_text

   pure logical function is_digit(ch)
      character, intent(in) :: ch
      is_digit = ch >= "0" .and. ch <= "9"
   end function is_digit

   !> s with its ASCII capitals A-Z as small letters, every other byte as it is (the
   !> C locale's tolower, whatever the locale; keywords and names are matched this way).
   pure function to_lower(s) result(t)
      character(len=*), intent(in) :: s   !< any text
      character(len=len(s)) :: t          !< s in small letters
      integer :: i
      t = s
      do i = 1, len(s)
         if (s(i:i) >= "A" .and. s(i:i) <= "Z") t(i:i) = achar(iachar(s(i:i)) + 32)
      end do
   end function to_lower

   !> Length of csv_row(v).
   pure integer function csv_row_len(v) result(n)
      real(dp), intent(in) :: v(:)  !< the row's values
      integer :: i
      n = size(v) - 1
      do i = 1, size(v)
         n = n + real_text_len(v(i), 17, 3)
      end do
   end function csv_row_len

   !> The values v as one CSV row, 17 significant digits each (every double reads back bit
   !> for bit), separated by commas.
   pure function csv_row(v) result(str)
      real(dp), intent(in) :: v(:)  !< the row's values
      character(len=csv_row_len(v)) :: str  ! not deferred: see above
      integer :: i, pos, n
      pos = 0
      do i = 1, size(v)
         if (i > 1) then
            str(pos + 1:pos + 1) = ","
            pos = pos + 1
         end if
         n = real_text_len(v(i), 17, 3)
         str(pos + 1:pos + n) = real_text(v(i), 17, 3)
         pos = pos + n
      end do
   end function csv_row

end module egw_text
