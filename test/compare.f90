!> Helpers the suites share to compare egw's Fortran and C doors: bitwise equality of
!> doubles, the C API's last error message, egw_table_eval and egw_hysteresis_eval_state
!> as a C caller sees them.
module test_compare
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_ptr, c_loc
   use egw_kinds, only: dp
   implicit none
   private
   public :: same_bits, last_error_c, c_table_eval, c_eval_state

   interface
      !> include/egw.h: int egw_table_eval(egw_table t, double delta, double *force,
      !> double *stiffness)
      integer(c_int) function c_table_eval(h, delta, force, stiffness) &
         & bind(C, name="egw_table_eval")
         import :: c_int, c_double, c_ptr
         type(c_ptr), value :: h, force, stiffness
         real(c_double), value :: delta
      end function c_table_eval
      !> include/egw.h: int egw_hysteresis_eval_state(egw_hysteresis h, double delta,
      !> double state[], double *force, double *stiffness), called as a C program does
      integer(c_int) function c_eval_state(h, delta, state, force, stiffness) &
         & bind(C, name="egw_hysteresis_eval_state")
         import :: c_int, c_double, c_ptr
         type(c_ptr), value :: h, state, force, stiffness
         real(c_double), value :: delta
      end function c_eval_state
   end interface

contains

   !> a and b the same double (NaN equal to NaN).
   elemental logical function same_bits(a, b)
      real(dp), intent(in) :: a, b
      same_bits = a == b .or. (ieee_is_nan(a) .and. ieee_is_nan(b))
   end function same_bits

   !> This thread's last C error message (egw_last_error), at most 999 characters.
   function last_error_c() result(text)
      character(len=:), allocatable :: text
      character(kind=c_char), target :: buf(1000)
      integer :: n
      interface
         integer(c_int) function c_last_error(b, buflen) bind(C, name="egw_last_error")
            import :: c_int, c_ptr
            type(c_ptr), value :: b
            integer(c_int), value :: buflen
         end function c_last_error
      end interface
      n = min(c_last_error(c_loc(buf), size(buf)), size(buf)) - 1
      allocate (character(len=n) :: text)
      text = transfer(buf(1:n), text)
   end function last_error_c

end module test_compare
