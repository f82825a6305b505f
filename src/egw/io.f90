!> Atomic file output: write to a temporary file beside the target, then rename it
!> over the target, so an existing file is never truncated or left half-written.
!> rename(2) is atomic within a file system; libc's rename is reached through an
!> interface block (a system call, not part of the C API).
module egw_io
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
   use egw_status, only: egw_error, egw_io_error, fatal_error
   implicit none
   private

   public :: open_temporary, commit_temporary, discard_temporary, rename_file

   interface
      function c_rename(from, to) result(stat) bind(C, name="rename")
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: from(*), to(*)
         integer(c_int) :: stat
      end function c_rename
   end interface

contains

   !> Open a fresh temporary file for path; tmp_path receives its name.
   !> binary (default false): unformatted stream access, for byte-exact binary formats.
   subroutine open_temporary(path, unit, tmp_path, error, binary)
      character(len=*), intent(in) :: path
      integer, intent(out) :: unit
      character(len=:), allocatable, intent(out) :: tmp_path
      type(egw_error), allocatable, intent(out) :: error
      logical, intent(in), optional :: binary
      integer :: ios
      character(len=256) :: msg
      logical :: stream
      stream = .false.
      if (present(binary)) stream = binary
      tmp_path = path//".egw-tmp"
      if (stream) then
         open (newunit=unit, file=tmp_path, status="replace", action="write", &
            & form="unformatted", access="stream", iostat=ios, iomsg=msg)
      else
         open (newunit=unit, file=tmp_path, status="replace", action="write", &
            & form="formatted", iostat=ios, iomsg=msg)
      end if
      if (ios /= 0) then
         call fatal_error(error, egw_io_error, "path = "//path//": cannot create "// &
            & tmp_path//" ("//trim(msg)//")")
      end if
   end subroutine open_temporary

   !> Close the temporary file and rename it over path.
   subroutine commit_temporary(unit, tmp_path, path, error)
      integer, intent(in) :: unit
      character(len=*), intent(in) :: tmp_path, path
      type(egw_error), allocatable, intent(out) :: error
      integer :: ios
      close (unit, iostat=ios)
      if (ios /= 0) then
         call discard_file(tmp_path)
         call fatal_error(error, egw_io_error, "path = "//path//": cannot close "//tmp_path)
         return
      end if
      call rename_file(tmp_path, path, error)
      if (allocated(error)) call discard_file(tmp_path)
   end subroutine commit_temporary

   !> Rename a file onto path (atomic within a file system; replaces an existing path).
   subroutine rename_file(from, path, error)
      character(len=*), intent(in) :: from, path
      type(egw_error), allocatable, intent(out) :: error
      if (c_rename(from//c_null_char, path//c_null_char) /= 0) then
         call fatal_error(error, egw_io_error, "path = "//path//": cannot rename "// &
            & from//" onto it")
      end if
   end subroutine rename_file

   !> Abandon a temporary file (after a failure while writing it).
   subroutine discard_temporary(unit, tmp_path)
      integer, intent(in) :: unit
      character(len=*), intent(in) :: tmp_path
      integer :: ios
      close (unit, status="delete", iostat=ios)
      if (ios /= 0) call discard_file(tmp_path)
   end subroutine discard_temporary

   subroutine discard_file(path)
      character(len=*), intent(in) :: path
      integer :: unit, ios
      open (newunit=unit, file=path, status="old", iostat=ios)
      if (ios == 0) close (unit, status="delete", iostat=ios)
   end subroutine discard_file

end module egw_io
