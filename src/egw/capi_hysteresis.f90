!> C API of the EP-GW hysteresis tables (include/egw.h): an opaque handle to a Fortran
!> hysteresis_table (c_loc of an allocated object, released by egw_hysteresis_free).
module egw_capi_hysteresis
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_null_ptr, c_associated, &
      & c_f_pointer, c_loc
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_is_finite
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_ok, egw_invalid_argument, egw_out_of_range, &
      & egw_out_of_memory, &
      & fatal_error, format_real
   use egw_params, only: contact_params
   use egw_rough_sphere, only: solver_options
   use egw_hysteresis, only: hysteresis_table, build_hysteresis, hysteresis_eval
   use egw_capi, only: settle, require, read_params, read_options, put
   implicit none
   private

contains

   !> C: egw_hysteresis_build (include/egw.h).
   function egw_hysteresis_build(p, o, delta_min, delta_max, rel_tol, out) result(stat) &
      & bind(C, name="egw_hysteresis_build")
      type(c_ptr), value, intent(in) :: p, o, out
      real(c_double), value, intent(in) :: delta_min, delta_max, rel_tol
      integer(c_int) :: stat
      type(contact_params) :: params
      type(solver_options) :: options
      type(hysteresis_table), pointer :: h
      type(c_ptr), pointer :: handle
      type(egw_error), allocatable :: error
      integer :: alloc_stat
      stat = require(out, "out")
      if (stat == egw_ok) stat = read_params(p, params)
      if (stat /= egw_ok) return
      call read_options(o, options)
      allocate (h, stat=alloc_stat)
      if (alloc_stat /= 0) then
         call fatal_error(error, egw_out_of_memory, "hysteresis table: out of memory")
         stat = settle(error)
         return
      end if
      call build_hysteresis(params, options, delta_min, delta_max, rel_tol, h, error)
      stat = settle(error)
      if (stat /= egw_ok) then
         deallocate (h)
         return
      end if
      call c_f_pointer(out, handle)
      handle = c_loc(h)
   end function egw_hysteresis_build

   !> C: egw_hysteresis_eval: the per-contact hot path (no allocation, no lock).
   function egw_hysteresis_eval(hp, delta, state, force, stiffness) result(stat) &
      & bind(C, name="egw_hysteresis_eval")
      type(c_ptr), value, intent(in) :: hp, state, force, stiffness
      real(c_double), value, intent(in) :: delta
      integer(c_int) :: stat
      type(hysteresis_table), pointer :: h
      real(c_double), pointer :: s
      type(egw_error), allocatable :: error
      real(dp) :: f, k, m
      integer :: st
      stat = require(hp, "h")
      if (stat == egw_ok) stat = require(state, "delta_max_state")
      if (stat /= egw_ok) return
      if (ieee_is_nan(delta)) then
         call fatal_error(error, egw_invalid_argument, "delta = NaN: must be a number")
         stat = settle(error)
         return
      end if
      call c_f_pointer(hp, h)
      call c_f_pointer(state, s)
      if (ieee_is_nan(s)) then
         call fatal_error(error, egw_invalid_argument, "delta_max_state = NaN: a new "// &
            & "contact starts from -HUGE_VAL")
         stat = settle(error)
         return
      end if
      m = s
      call hysteresis_eval(h, delta, m, f, k, st)
      if (.not. (ieee_is_finite(f) .and. ieee_is_finite(k))) then  ! input guard (issue 13)
         call fatal_error(error, egw_invalid_argument, "delta = "//format_real(delta)// &
            & ", delta_max_state = "//format_real(s)//": the force there exceeds the doubles")
         stat = settle(error)
         return
      end if
      s = m
      call put(force, f)
      call put(stiffness, k)
      stat = int(st, c_int)
      if (stat == egw_out_of_range) then
         call fatal_error(error, egw_out_of_range, "delta_max_state = "//format_real(m)// &
            & ": above the table's delta_max = "//format_real(h%delta_max)// &
            & " (values extrapolated)")
         stat = settle(error)
      end if
   end function egw_hysteresis_eval

   !> C: egw_hysteresis_free: release a table; sets *h to NULL (NULL is fine).
   subroutine egw_hysteresis_free(hp) bind(C, name="egw_hysteresis_free")
      type(c_ptr), value, intent(in) :: hp
      type(c_ptr), pointer :: handle
      type(hysteresis_table), pointer :: h
      if (.not. c_associated(hp)) return
      call c_f_pointer(hp, handle)
      if (.not. c_associated(handle)) return
      call c_f_pointer(handle, h)
      deallocate (h)
      handle = c_null_ptr
   end subroutine egw_hysteresis_free

end module egw_capi_hysteresis
