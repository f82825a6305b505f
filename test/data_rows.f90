!> The data rows of a reference CSV under test/data (comment lines "#..." and the header
!> "model,..." skipped), for the suites that check egw against them.
module data_rows
   use testdrive, only: error_type, test_failed
   implicit none
   private
   public :: read_data_rows

   !> Longest row read (the reference files' rows are under 300 characters).
   integer, parameter, public :: row_length = 512

contains

   !> rows = the data rows of path, in order; a missing file fails the test with a hint
   !> (the suites run from the project root).
   subroutine read_data_rows(path, rows, error)
      character(len=*), intent(in) :: path
      character(len=row_length), allocatable, intent(out) :: rows(:)
      type(error_type), allocatable, intent(out) :: error
      character(len=row_length) :: line
      integer :: unit, ios
      allocate (rows(0))
      open (newunit=unit, file=path, status="old", action="read", iostat=ios)
      if (ios /= 0) then
         call test_failed(error, "cannot open "//path//" (run the tests from the project root)")
         return
      end if
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:1) == "#" .or. line(1:6) == "model,") cycle
         rows = [character(len=row_length) :: rows, line]
      end do
      close (unit)
   end subroutine read_data_rows

end module data_rows
