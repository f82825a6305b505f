!> What the C API's entry points (capi*.f90, include/egw.h) share, in one place: the
!> per-thread last-error message (settle, require, invalid, failure), the argument checks
!> every entry makes (NULL, NaN, counts, ranges), handles in and out, the C mirrors of
!> egw_params, egw_options and egw_result with their conversions, and strings: every C
!> string argument is read by c_string or c_path (its full strlen length: no silent
!> truncation, whatever its length) and every message is copied out by copy_to_c. The
!> capi*.f90 modules hold the entry points, each as check arguments -> call -> copy out.
module egw_capi_utils
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_char, c_ptr, c_size_t, &
      & c_null_char, c_null_ptr, c_associated, c_f_pointer
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_ok, egw_invalid_argument, egw_null_pointer, &
      & egw_out_of_range, status_message, format_real, int_str
   use egw_params, only: contact_params, validate_params, refuse_flow_pressure
   use egw_rough_sphere, only: solver_options, solve_result
   implicit none
   private

   public :: c_string, c_path, copy_to_c, copy_last_error
   public :: settle, require, invalid, failure, above_delta_max
   public :: check_nonneg, check_positive, check_number, check_count
   public :: put, put_settled, put_handle_settled, take_handle, double_array
   public :: egw_params_c, egw_options_c, egw_result_c, to_params, from_params, read_params, &
      & read_options, read_contact, put_result, refuse_cap

   !> Mirror of the C struct egw_params.
   type, bind(C) :: egw_params_c
      integer(c_int) :: model
      real(c_double) :: radius, modulus, sigma, mu, psi, hardness_coeff, plastic_ratio
      real(c_double) :: flow_pressure
   end type egw_params_c

   !> Last error message of this thread: the only mutable state of egw, kept per thread
   !> so that concurrent callers never see each other's messages.
   !> (16384 characters: a message naming a path of PATH_MAX = 4096 bytes fits whole.)
   character(len=16384), save :: last_message = ""
   !$omp threadprivate(last_message)
   !> An EGW_OUT_OF_RANGE message kept as its numbers (above_delta_max): extrapolated
   !> evaluations are a DEM hot path (every deep contact, every step), so the text is
   !> formed only when egw_last_error asks for it. Cleared by every other message.
   logical, save :: pending = .false.
   character(len=64), save :: pending_name = ""
   real(dp), save :: pending_x = 0.0_dp, pending_limit = 0.0_dp
   !$omp threadprivate(pending, pending_name, pending_x, pending_limit)

   !> Mirror of the C struct egw_options.
   type, bind(C) :: egw_options_c
      integer(c_int) :: n_radial
      real(c_double) :: rel_tol
      integer(c_int) :: max_iter, method, n_threads
   end type egw_options_c

   !> Mirror of the C struct egw_result.
   type, bind(C) :: egw_result_c
      real(c_double) :: force, stiffness, contact_radius, max_pressure, est_rel_err, residual
      integer(c_int) :: iterations, method_used
   end type egw_result_c

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
      type(c_ptr), intent(in) :: ptr   !< a NUL-terminated C string, not NULL
      character(len=:), allocatable, intent(out) :: str   !< its characters
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
      character(len=*), intent(in) :: str   !< the text to copy
      type(c_ptr), intent(in) :: buf   !< char* of buflen bytes
      integer(c_int), intent(in) :: buflen   !< bytes at buf, >= 1
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

   !> Convert the C struct to the Fortran type.
   pure function to_params(cp) result(params)
      type(egw_params_c), intent(in) :: cp   !< the C struct egw_params
      type(contact_params) :: params
      params = contact_params(model=int(cp%model), radius=cp%radius, modulus=cp%modulus, &
         & sigma=cp%sigma, mu=cp%mu, psi=cp%psi, hardness_coeff=cp%hardness_coeff, &
         & plastic_ratio=cp%plastic_ratio, flow_pressure=cp%flow_pressure)
   end function to_params

   !> The C struct egw_params of Fortran contact_params (field by field).
   pure function from_params(params) result(cp)
      type(contact_params), intent(in) :: params   !< the Fortran parameters
      type(egw_params_c) :: cp
      cp = egw_params_c(model=int(params%model, c_int), radius=params%radius, &
         & modulus=params%modulus, sigma=params%sigma, mu=params%mu, psi=params%psi, &
         & hardness_coeff=params%hardness_coeff, plastic_ratio=params%plastic_ratio, &
         & flow_pressure=params%flow_pressure)
   end function from_params

   !> Read and validate a const egw_params*.
   integer(c_int) function read_params(p, params, allow_flat_law) result(stat)
      type(c_ptr), intent(in) :: p   !< const egw_params* (NULL: EGW_NULL_POINTER)
      type(contact_params), intent(out) :: params   !< the validated parameters
      logical, intent(in), optional :: allow_flat_law   !< EGW_MODEL_FLAT_LAW is valid
      type(egw_params_c), pointer :: cp
      type(egw_error), allocatable :: error
      stat = require(p, "p")
      if (stat /= egw_ok) return
      call c_f_pointer(p, cp)
      params = to_params(cp)
      call validate_params(params, error, allow_flat_law)
      stat = settle(error)
   end function read_params

   !> EGW_INVALID_PARAMETER (message recorded) when params have the flow-pressure cap and
   !> the request (what) does not serve it yet; EGW_OK otherwise.
   integer(c_int) function refuse_cap(params, what) result(stat)
      type(contact_params), intent(in) :: params   !< the contact's parameters
      character(len=*), intent(in) :: what   !< the request, for the message
      type(egw_error), allocatable :: error
      call refuse_flow_pressure(params, what, error)
      stat = settle(error)
   end function refuse_cap

   !> Options from a nullable const egw_options* (NULL: defaults); checked by the solver.
   subroutine read_options(o, options)
      type(c_ptr), intent(in) :: o   !< const egw_options* (NULL: defaults)
      type(solver_options), intent(out) :: options   !< the solver's options
      type(egw_options_c), pointer :: co
      if (.not. c_associated(o)) return
      call c_f_pointer(o, co)
      options%n_radial = int(co%n_radial)
      options%rel_tol = co%rel_tol
      options%max_iter = int(co%max_iter)
      options%method = int(co%method)
      options%n_threads = int(co%n_threads)
   end subroutine read_options

   !> The inputs of a solve: validated params from p (read_params), options from the
   !> nullable o (read_options, read only when p passed).
   integer(c_int) function read_contact(p, o, params, options, allow_flat_law) result(stat)
      type(c_ptr), intent(in) :: p   !< const egw_params*
      type(c_ptr), intent(in) :: o   !< const egw_options* (NULL: defaults)
      type(contact_params), intent(out) :: params   !< the validated parameters
      type(solver_options), intent(out) :: options   !< the solver's options
      logical, intent(in), optional :: allow_flat_law   !< EGW_MODEL_FLAT_LAW is valid
      stat = read_params(p, params, allow_flat_law)
      if (stat == egw_ok) call read_options(o, options)
   end function read_contact

   !> Store a solve_result at a C egw_result* (not NULL).
   subroutine put_result(res, result)
      type(c_ptr), intent(in) :: res   !< egw_result*, not NULL
      type(solve_result), intent(in) :: result   !< the solve's result
      type(egw_result_c), pointer :: cres
      call c_f_pointer(res, cres)
      cres = egw_result_c(force=result%force, stiffness=result%stiffness, &
         & contact_radius=result%contact_radius, max_pressure=result%max_pressure, &
         & est_rel_err=result%est_rel_err, residual=result%residual, &
         & iterations=int(result%iterations, c_int), method_used=int(result%method_used, c_int))
   end subroutine put_result

   !> Status of an error (recording its message), EGW_OK when none.
   integer(c_int) function settle(error) result(stat)
      !> the call's error, unallocated on success
      type(egw_error), allocatable, intent(in) :: error
      stat = egw_ok
      if (.not. allocated(error)) return
      stat = int(error%stat, c_int)
      pending = .false.
      if (allocated(error%message)) then
         last_message = error%message
      else
         last_message = status_message(error%stat)
      end if
   end function settle

   !> EGW_OK if ptr is not NULL, else EGW_NULL_POINTER with a message naming the argument.
   integer(c_int) function require(ptr, name) result(stat)
      type(c_ptr), intent(in) :: ptr   !< the pointer argument
      character(len=*), intent(in) :: name   !< its name in egw.h
      stat = egw_ok
      if (c_associated(ptr)) return
      stat = egw_null_pointer
      pending = .false.
      last_message = name//": NULL pointer"
   end function require

   !> EGW_OK if x is finite and >= 0, else EGW_INVALID_ARGUMENT naming it.
   integer(c_int) function check_nonneg(name, x) result(stat)
      character(len=*), intent(in) :: name   !< the argument's name in egw.h
      real(dp), intent(in) :: x   !< its value
      stat = check_finite(name, x, x >= 0.0_dp, ">= 0")
   end function check_nonneg

   !> EGW_OK if x is finite and > 0, else EGW_INVALID_ARGUMENT naming it.
   integer(c_int) function check_positive(name, x) result(stat)
      character(len=*), intent(in) :: name   !< the argument's name in egw.h
      real(dp), intent(in) :: x   !< its value
      stat = check_finite(name, x, x > 0.0_dp, "> 0")
   end function check_positive

   !> EGW_OK if x is finite and meets its bound (bound_met), else EGW_INVALID_ARGUMENT.
   integer(c_int) function check_finite(name, x, bound_met, bound) result(stat)
      character(len=*), intent(in) :: name, bound
      real(dp), intent(in) :: x
      logical, intent(in) :: bound_met
      stat = egw_ok
      if (ieee_is_finite(x) .and. bound_met) return
      stat = invalid(name//" = "//format_real(x)//": must be finite and "//bound)
   end function check_finite

   !> EGW_OK unless x is NaN (EGW_INVALID_ARGUMENT naming it); Inf passes, the callee
   !> judges it. (The name of an array element is built only on failure: array loops.)
   integer(c_int) function check_number(name, x, index) result(stat)
      character(len=*), intent(in) :: name     !< the argument's name in egw.h
      real(dp), intent(in) :: x   !< its value
      integer, intent(in), optional :: index   !< x is name[index] (C, from 0)
      stat = egw_ok
      if (.not. ieee_is_nan(x)) return
      if (present(index)) then
         stat = invalid(name//"["//int_str(index)//"] = NaN: must be a number")
      else
         stat = invalid(name//" = NaN: must be a number")
      end if
   end function check_number

   !> EGW_OK if the array length n is >= 0, else EGW_INVALID_ARGUMENT.
   integer(c_int) function check_count(n) result(stat)
      integer(c_int), intent(in) :: n   !< the argument called n in egw.h
      stat = egw_ok
      if (n < 0) stat = invalid("n = "//int_str(int(n))//": must be >= 0")
   end function check_count

   !> Store x at a C double* (NULL: nothing wanted).
   subroutine put(ptr, x)
      type(c_ptr), intent(in) :: ptr   !< double* (NULL: not wanted)
      real(dp), intent(in) :: x   !< the value
      real(c_double), pointer :: target
      if (.not. c_associated(ptr)) return
      call c_f_pointer(ptr, target)
      target = x
   end subroutine put

   !> The n doubles at a nullable double* (NULL: not associated, nothing wanted there).
   function double_array(ptr, n) result(array)
      type(c_ptr), intent(in) :: ptr   !< double* (NULL: not wanted)
      integer(c_int), intent(in) :: n   !< the length, >= 0
      real(c_double), pointer :: array(:)
      array => null()
      if (c_associated(ptr)) call c_f_pointer(ptr, array, [n])
   end function double_array

   !> Status of a call's error (as settle); on success x stored at the nullable double*
   !> ptr (as put), on failure ptr untouched.
   integer(c_int) function put_settled(ptr, x, error) result(stat)
      type(c_ptr), intent(in) :: ptr   !< double* (NULL: not wanted)
      real(dp), intent(in) :: x   !< the value
      !> the call's error, unallocated on success
      type(egw_error), allocatable, intent(in) :: error
      stat = settle(error)
      if (stat == egw_ok) call put(ptr, x)
   end function put_settled

   !> Status of the build or read that made an object (as settle); on success the object
   !> is handed to C, its address stored at *out. On failure *out is untouched and the
   !> caller releases the object (no handle to a half-made table).
   integer(c_int) function put_handle_settled(out, object, error) result(stat)
      type(c_ptr), intent(in) :: out      !< egw_table*, egw_universal*, ... (not NULL)
      type(c_ptr), intent(in) :: object   !< c_loc of the allocated object
      !> the build's or read's error, unallocated on success
      type(egw_error), allocatable, intent(in) :: error
      type(c_ptr), pointer :: handle
      stat = settle(error)
      if (stat /= egw_ok) return
      call c_f_pointer(out, handle)
      handle = object
   end function put_handle_settled

   !> Take a handle back from C for release: the address at *h, and *h set to NULL.
   !> NULL h or NULL *h gives c_null_ptr (nothing to release).
   function take_handle(h) result(object)
      type(c_ptr), intent(in) :: h   !< egw_table*, egw_universal*, egw_hysteresis*
      type(c_ptr) :: object
      type(c_ptr), pointer :: handle
      object = c_null_ptr
      if (.not. c_associated(h)) return
      call c_f_pointer(h, handle)
      object = handle
      handle = c_null_ptr
   end function take_handle

   !> EGW_INVALID_ARGUMENT, recording message as this thread's last error.
   integer(c_int) function invalid(message) result(stat)
      character(len=*), intent(in) :: message  !< the message, naming the argument
      stat = failure(egw_invalid_argument, message)
   end function invalid

   !> The status code, recording message as this thread's last error.
   integer(c_int) function failure(code, message) result(stat)
      integer, intent(in) :: code               !< an EGW_* status
      character(len=*), intent(in) :: message  !< the message, naming the argument
      stat = int(code, c_int)
      pending = .false.
      last_message = message
   end function failure

   !> EGW_OUT_OF_RANGE for x (called name) above a table's delta_max = limit, the values
   !> written extrapolated; the message "name = x: above the table's delta_max = limit
   !> (values extrapolated)" is formed when egw_last_error asks (no text on the hot path).
   integer(c_int) function above_delta_max(name, x, limit) result(stat)
      character(len=*), intent(in) :: name   !< the argument, e.g. "delta"
      real(dp), intent(in) :: x, limit   !< the value, and the table's delta_max
      stat = int(egw_out_of_range, c_int)
      pending = .true.
      pending_name = name
      pending_x = x
      pending_limit = limit
   end function above_delta_max

   !> Copy this thread's last error message into a C buffer and return the bytes it needs
   !> whole (its length + 1 for the NUL; >= 1): buflen >= that copies it whole, 0 < buflen
   !> < that copies its first buflen - 1 characters and the NUL (the return value above
   !> buflen tells the caller to allocate that many and call again), buflen = 0 (buf may
   !> then be NULL) writes nothing (a size query). -EGW_NULL_POINTER for buf NULL with
   !> buflen > 0, -EGW_INVALID_ARGUMENT for buflen < 0: nothing written, and the last
   !> error is kept (this call never records one).
   integer(c_int) function copy_last_error(buf, buflen) result(needed)
      type(c_ptr), intent(in) :: buf         !< char* of buflen bytes, or NULL
      integer(c_int), intent(in) :: buflen   !< its size in bytes
      integer(c_int) :: stat
      if (buflen < 0) then
         needed = -int(egw_invalid_argument, c_int)
         return
      end if
      if (buflen > 0 .and. .not. c_associated(buf)) then
         needed = -int(egw_null_pointer, c_int)
         return
      end if
      if (pending) then
         last_message = trim(pending_name)//" = "//format_real(pending_x)// &
            & ": above the table's delta_max = "//format_real(pending_limit)// &
            & " (values extrapolated)"
         pending = .false.
      end if
      needed = int(len_trim(last_message) + 1, c_int)
      if (buflen > 0) stat = copy_to_c(trim(last_message), buf, buflen)
   end function copy_last_error

   !> A NUL-terminated C string argument (a path, or the argument called name) as a
   !> Fortran string of its full length; NULL (EGW_NULL_POINTER) and "" (EGW_INVALID_ARGUMENT)
   !> are refused with a message naming the argument.
   integer(c_int) function c_path(path, fpath, name) result(stat)
      type(c_ptr), intent(in) :: path                        !< const char*
      character(len=:), allocatable, intent(out) :: fpath    !< its text
      character(len=*), intent(in), optional :: name         !< its name (default "path")
      character(len=:), allocatable :: label
      label = "path"
      if (present(name)) label = name
      stat = require(path, label)
      if (stat /= egw_ok) return
      call c_string(path, fpath)
      if (len(fpath) == 0) stat = invalid(label//": empty")
   end function c_path

end module egw_capi_utils
