!> What the command-line programs need from the C library beyond Fortran: whether stderr
!> is a terminal (progress bars there, plain lines in logs) and ending the process with
!> a status but without the runtime's "ERROR STOP" line and backtrace.
module egw_terminal
   use, intrinsic :: iso_c_binding, only: c_int
   use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
   implicit none
   private

   public :: stderr_is_terminal, exit_process

   interface
      integer(c_int) function c_isatty(fd) bind(C, name="isatty")
         import :: c_int
         integer(c_int), value :: fd
      end function c_isatty
      subroutine c_exit(status) bind(C, name="exit")
         import :: c_int
         integer(c_int), value :: status
      end subroutine c_exit
   end interface

contains

   !> True if file descriptor 2 (stderr) is a terminal.
   logical function stderr_is_terminal()
      stderr_is_terminal = c_isatty(2_c_int) == 1
   end function stderr_is_terminal

   !> Flush the standard units and end the process with the given exit status.
   subroutine exit_process(status)
      integer, intent(in) :: status
      flush (output_unit)
      flush (error_unit)
      call c_exit(int(status, c_int))
   end subroutine exit_process

end module egw_terminal
