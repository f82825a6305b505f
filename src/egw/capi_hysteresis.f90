!> C API of hysteresis tables (include/egw.h, egw_hysteresis_*): opaque handles (c_loc of
!> an allocated hysteresis_table, released by egw_hysteresis_free), build and evaluation.
!> Errors go through egw_capi's per-thread last-error message (settle, require).
module egw_capi_hysteresis
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_null_ptr, &
      & c_associated, c_f_pointer, c_loc
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_ok, egw_invalid_argument, egw_out_of_range, &
      & fatal_error, format_real
   use egw_params, only: contact_params
   use egw_rough_sphere, only: solver_options
   use egw_hysteresis, only: hysteresis_table, build_hysteresis, hysteresis_eval
   use egw_capi, only: settle, require, read_params, read_options, put
   implicit none
   private

contains

   !> C: egw_hysteresis_build (see include/egw.h for units and statuses).
   function egw_hysteresis_build(p, o, delta_min, delta_max, rel_tol, out) result(stat) &
      & bind(C, name="egw_hysteresis_build")
      type(c_ptr), value, intent(in) :: p, o, out
      real(c_double), value, intent(in) :: delta_min, delta_max, rel_tol
      integer(c_int) :: stat
      type(contact_params) :: params
      type(solver_options) :: options
      type(hysteresis_table), pointer :: t
      type(c_ptr), pointer :: handle
      type(egw_error), allocatable :: error
      integer :: ios
      stat = require(out, "out")
      if (stat == egw_ok) stat = read_params(p, params)
      if (stat /= egw_ok) return
      call read_options(o, options)
      allocate (t, stat=ios)
      if (ios /= 0) then
         call fatal_error(error, egw_invalid_argument, "out: cannot allocate the table")
         stat = settle(error)
         return
      end if
      call build_hysteresis(params, options, delta_min, delta_max, rel_tol, t, error)
      stat = settle(error)
      if (stat /= egw_ok) then
         deallocate (t)
         return
      end if
      call c_f_pointer(out, handle)
      handle = c_loc(t)
   end function egw_hysteresis_build

   !> C: egw_hysteresis_eval; above the table's delta_max returns EGW_OUT_OF_RANGE with
   !> values and state written. No allocation, no lock (the handle is only read).
   function egw_hysteresis_eval(h, delta, state, force, stiffness) result(stat) &
      & bind(C, name="egw_hysteresis_eval")
      type(c_ptr), value, intent(in) :: h, state, force, stiffness
      real(c_double), value, intent(in) :: delta
      integer(c_int) :: stat
      type(hysteresis_table), pointer :: t
      real(c_double), pointer :: s
      real(dp) :: f, k
      if (.not. c_associated(h)) then
         stat = require(h, "h")
         return
      end if
      if (.not. c_associated(state)) then
         stat = require(state, "delta_max_state")
         return
      end if
      call c_f_pointer(state, s)
      if (ieee_is_nan(delta) .or. ieee_is_nan(s)) then
         stat = failure(egw_invalid_argument, "delta = "//format_real(delta)// &
            & ", delta_max_state = "//format_real(s)//": must be numbers")
         return
      end if
      call c_f_pointer(h, t)
      call hysteresis_eval(t, delta, s, f, k)
      call put(force, f)
      call put(stiffness, k)
      stat = egw_ok
      if (s > t%delta_max) stat = failure(egw_out_of_range, "delta_max_state = "// &
         & format_real(s)//": above the table's delta_max = "//format_real(t%delta_max)// &
         & " (loading extrapolated linearly, the last unloading curve's shape)")
   end function egw_hysteresis_eval

   !> C: egw_hysteresis_free(egw_hysteresis *h): releases the table, sets *h = NULL.
   subroutine egw_hysteresis_free(h) bind(C, name="egw_hysteresis_free")
      type(c_ptr), value, intent(in) :: h
      type(c_ptr), pointer :: handle
      type(hysteresis_table), pointer :: t
      if (.not. c_associated(h)) return
      call c_f_pointer(h, handle)
      if (.not. c_associated(handle)) return
      call c_f_pointer(handle, t)
      deallocate (t)
      handle = c_null_ptr
   end subroutine egw_hysteresis_free

   !> Record message as this thread's last error with status code; returns code.
   integer(c_int) function failure(code, message) result(stat)
      integer, intent(in) :: code
      character(len=*), intent(in) :: message
      type(egw_error), allocatable :: error
      call fatal_error(error, code, message)
      stat = settle(error)
   end function failure

end module egw_capi_hysteresis
