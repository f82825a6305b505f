!> Status codes and the error object every fallible egw routine returns.
!> Library code never prints or stops: it sets a status and a message that
!> names the offending argument, and the caller decides what to do.
module egw_status
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use egw_kinds, only: dp
   use egw_text, only: real_text, real_text_len, int_text, int_text_len
   implicit none
   private

   integer, parameter, public :: egw_ok = 0
   integer, parameter, public :: egw_invalid_argument = 1   !< bad argument to a routine
   integer, parameter, public :: egw_invalid_parameter = 2  !< a contact parameter failed validation
   integer, parameter, public :: egw_not_converged = 3      !< an iterative solve did not converge
   integer, parameter, public :: egw_io_error = 4           !< a file could not be opened/written/renamed
   integer, parameter, public :: egw_bad_file = 5           !< truncated, corrupted or wrong-version file
   integer, parameter, public :: egw_out_of_memory = 6      !< an allocation failed
   integer, parameter, public :: egw_null_pointer = 7       !< a required pointer was NULL (C API)
   integer, parameter, public :: egw_out_of_range = 8       !< an argument is outside a table's range
   integer, parameter, public :: egw_unsupported = 9        !< valid request that egw does not support
   integer, parameter, public :: egw_status_max = 9

   !> Error object: status code and a message naming what was wrong.
   type, public :: egw_error
      integer :: stat = egw_ok
      character(len=:), allocatable :: message
   end type egw_error

   public :: status_message, fatal_error, format_real, format_real_len, int_str
   public :: parameter_error, bad_file_error, tolerance_context, first_failure

contains

   pure function status_text(stat) result(msg)
      integer, intent(in) :: stat
      character(len=64) :: msg
      select case (stat)
      case (egw_ok);                msg = "success"
      case (egw_invalid_argument);  msg = "invalid argument"
      case (egw_invalid_parameter); msg = "invalid contact parameter"
      case (egw_not_converged);     msg = "iterative solve did not converge"
      case (egw_io_error);          msg = "input/output error"
      case (egw_bad_file);          msg = "file is truncated, corrupted or of an unknown version"
      case (egw_out_of_memory);     msg = "out of memory"
      case (egw_null_pointer);      msg = "required pointer is NULL"
      case (egw_out_of_range);      msg = "argument outside the valid range"
      case (egw_unsupported);       msg = "unsupported request"
      case default;                 msg = "unknown status code"
      end select
   end function status_text

   !> Generic one-line description of a status code.
   pure function status_message(stat) result(msg)
      integer, intent(in) :: stat   !< an egw status code
      character(len=len_trim(status_text(stat))) :: msg  ! not deferred: see format_real
      msg = status_text(stat)
   end function status_message

   !> Allocate and fill an error; the message is prefixed by nothing so callers
   !> can compose "name = value: reason" themselves.
   pure subroutine fatal_error(error, stat, message)
      type(egw_error), allocatable, intent(out) :: error   !< allocated with stat and message
      integer, intent(in) :: stat   !< an egw_* status code
      character(len=*), intent(in) :: message   !< "name = value: reason"
      allocate (error)
      error%stat = stat
      error%message = message
   end subroutine fatal_error

   !> The first failure of a parallel loop (stats(i) /= 0, with its message) as error: the
   !> lowest i wins, whatever the threads' order. With what and at, the message says which
   !> item failed first, "what = at(i): " before the item's own message (a build that
   !> fails after minutes names where: the turning point of the curve, the overlap).
   pure subroutine first_failure(stats, messages, error, what, at)
      integer, intent(in) :: stats(:)   !< per item: 0 or the status
      character(len=*), intent(in) :: messages(:)   !< per item: the message
      type(egw_error), allocatable, intent(out) :: error   !< the first failure
      character(len=*), intent(in), optional :: what   !< the items' name, e.g. "delta_max"
      real(dp), intent(in), optional :: at(:)   !< per item: its value of what
      integer :: i
      do i = 1, size(stats)
         if (stats(i) /= 0) then
            if (present(what) .and. present(at)) then
               call fatal_error(error, stats(i), what//" = "//format_real(at(i))//": "// &
                  & trim(messages(i)))
            else
               call fatal_error(error, stats(i), trim(messages(i)))
            end if
            return
         end if
      end do
   end subroutine first_failure

   !> A tolerance that was not reached, told in the caller's terms: a not-converged
   !> error of a job asked for rel_tol (a table build, a restitution) whose inner solves
   !> ran at solve_tol gets the prefix "<what>: rel_tol = <rel_tol> (the caller's) not
   !> reached (its solves at <solve_tol>): ", so that the inner message (which quotes the
   !> solve's own tolerance and the estimate it reached) does not read as a success.
   !> Other errors, and one that already starts with "<what>: " (told by the job itself),
   !> are left as they are.
   pure subroutine tolerance_context(error, what, rel_tol, solve_tol)
      type(egw_error), intent(inout) :: error   !< the job's error
      character(len=*), intent(in) :: what      !< the job, e.g. "hysteresis table"
      real(dp), intent(in) :: rel_tol           !< the caller's tolerance
      real(dp), intent(in) :: solve_tol         !< that of its solves
      character(len=:), allocatable :: prefix
      if (error%stat /= egw_not_converged) return
      prefix = what//": rel_tol = "//format_real(rel_tol)//" (the caller's) not reached"
      if (.not. allocated(error%message)) error%message = ""
      ! already told by the job itself (a message that starts with its name)
      if (index(error%message, what//": ") == 1) return
      if (solve_tol /= rel_tol) prefix = prefix//" (its solves at "//format_real(solve_tol)//")"
      error%message = prefix//": "//error%message
   end subroutine tolerance_context

   !> Length of format_real(x).
   pure integer function format_real_len(x) result(n)
      real(dp), intent(in) :: x   !< any double
      if (ieee_is_nan(x)) then
         n = 3
      else if (abs(x) > huge(x)) then
         n = 4
      else
         n = real_text_len(x, 15, 3)
      end if
   end function format_real_len

   !> Shortest readable form of a real for messages (NaN and Inf spelled out).
   !> (The result's length comes from a specification function, not a deferred length:
   !> see egw_text on gfortran's static lengths of deferred-length results.)
   pure function format_real(x) result(str)
      real(dp), intent(in) :: x   !< any double
      character(len=format_real_len(x)) :: str
      if (ieee_is_nan(x)) then
         str = "NaN"
      else if (x > huge(x)) then
         str = "+Inf"
      else if (x < -huge(x)) then
         str = "-Inf"
      else
         str = real_text(x, 15, 3)  ! as ES23.15E3, without an internal WRITE (egw_text)
      end if
   end function format_real

   !> Decimal text of an integer, for messages.
   pure function int_str(i) result(str)
      integer, intent(in) :: i  !< the integer to spell
      character(len=int_text_len(i)) :: str  ! not deferred, not a WRITE: see egw_text
      str = int_text(i)
   end function int_str

   !> EGW_INVALID_PARAMETER with the message "name = value: reason".
   pure subroutine parameter_error(error, name, value, reason)
      type(egw_error), allocatable, intent(out) :: error  !< the error set
      character(len=*), intent(in) :: name    !< the parameter's name
      real(dp), intent(in) :: value           !< its offending value
      character(len=*), intent(in) :: reason  !< what it must be
      call fatal_error(error, egw_invalid_parameter, name//" = "//format_real(value)// &
         & ": "//reason)
   end subroutine parameter_error

   !> EGW_BAD_FILE with the message "path = path: what", replacing any earlier error.
   pure subroutine bad_file_error(error, path, what)
      type(egw_error), allocatable, intent(inout) :: error  !< the error set
      character(len=*), intent(in) :: path  !< the file read
      character(len=*), intent(in) :: what  !< what is wrong with it
      if (allocated(error)) deallocate (error)
      call fatal_error(error, egw_bad_file, "path = "//path//": "//what)
   end subroutine bad_file_error

end module egw_status
