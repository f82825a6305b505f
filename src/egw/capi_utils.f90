!> Strings across the C API (include/egw.h), in one place: every C string argument
!> is read by c_string (its full strlen length: no silent truncation, whatever its
!> length) and every message is copied out by copy_to_c. The capi*.f90 modules hold
!> the entry points.
module egw_capi_utils
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_ptr, c_size_t, c_null_char, &
      & c_associated, c_f_pointer
   use egw_status, only: egw_ok, egw_invalid_argument, egw_null_pointer
   implicit none
   private

   public :: c_string, copy_to_c

   interface
      !> strlen of libc: the length of a NUL-terminated C string.
      pure function c_strlen(s) result(n) bind(C, name="strlen")
         import :: c_ptr, c_size_t
         type(c_ptr), value, intent(in) :: s
         integer(c_size_t) :: n
      end function c_strlen
   end interface

contains

   !> The NUL-terminated C string at ptr (not NULL) as a Fortran string of its full
   !> length. (A subroutine: gfortran 12 keeps the length of a deferred-length function
   !> result in a static variable, which concurrent callers would share; see egw_text.)
   subroutine c_string(ptr, str)
      type(c_ptr), intent(in) :: ptr
      character(len=:), allocatable, intent(out) :: str
      character(kind=c_char), pointer :: chars(:)
      integer(c_size_t) :: n
      integer :: i
      n = c_strlen(ptr)
      if (n > huge(1)) n = huge(1)  ! 2 GiB: no path or units string is that long
      allocate (character(len=int(n)) :: str)
      if (n == 0) return
      call c_f_pointer(ptr, chars, [n])
      do i = 1, int(n)
         str(i:i) = chars(i)
      end do
   end subroutine c_string

   !> Copy a Fortran string into a C buffer of buflen bytes, NUL-terminated, truncated
   !> to buflen - 1 characters. EGW_NULL_POINTER (buf NULL), EGW_INVALID_ARGUMENT
   !> (buflen < 1); nothing written then.
   integer(c_int) function copy_to_c(str, buf, buflen) result(stat)
      character(len=*), intent(in) :: str
      type(c_ptr), intent(in) :: buf
      integer(c_int), intent(in) :: buflen
      character(kind=c_char), pointer :: chars(:)
      integer :: i, n
      stat = egw_ok
      if (.not. c_associated(buf)) then
         stat = egw_null_pointer
         return
      end if
      if (buflen < 1) then
         stat = egw_invalid_argument
         return
      end if
      call c_f_pointer(buf, chars, [buflen])
      n = min(len(str), int(buflen) - 1)
      do i = 1, n
         chars(i) = str(i:i)
      end do
      chars(n + 1) = c_null_char
   end function copy_to_c

end module egw_capi_utils
