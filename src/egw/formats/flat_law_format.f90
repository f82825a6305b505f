!> Rough-flat law files (doc/formats.md §7): egw CSV of a tabulated law, p(u) at nodes
!> with dp/du and, where the law has them, contact-area fractions; the law's length and
!> E* in the header; a checksum line. The reader also takes a user's own CSV (a header
!> line naming the columns `u` and `pressure`, optionally `dpdu` and `area`; '#' lines
!> `# length = ...` and `# modulus = ...`; no checksum line needed), and checks every
!> node through new_table_law.
module egw_flat_law_format
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_bad_file, fatal_error, int_str, bad => bad_file_error
   use egw_version, only: egw_version_string
   use egw_io, only: read_file, text_buffer
   use egw_text, only: parse_real, csv_row
   use egw_flat_law, only: table_flat_law, new_table_law
   use egw_table_format, only: split_checksum, checksum_line
   implicit none
   private

   public :: write_flat_law, read_flat_law

   character(len=*), parameter :: title = "# egw rough-flat law, CSV format 1"
   !> Most nodes a law file may hold (a corrupted or absurd file must not allocate wildly).
   integer, parameter :: max_nodes = 1000000

contains

   !> Write the law's nodes (u, pressure, dpdu[, area]) as egw CSV, atomically (a temporary
   !> file renamed over path). source: a word for the header (e.g. "table", "Persson",
   !> "BEM").
   subroutine write_flat_law(law, path, error, source)
      type(table_flat_law), intent(in) :: law   !< the law whose nodes are written
      character(len=*), intent(in) :: path   !< the file to write
      !> egw_io_error naming path and the reason
      type(egw_error), allocatable, intent(out) :: error
      character(len=*), intent(in), optional :: source   !< where the law came from, for the header
      type(text_buffer) :: out
      real(dp), allocatable :: p(:), d(:)
      integer :: i, n
      n = size(law%u)
      allocate (p(n), d(n))
      call law%pressure(law%u, p, d)
      if (allocated(law%area)) then
         call out%add("u,pressure,dpdu,area")
      else
         call out%add("u,pressure,dpdu")
      end if
      call out%add(title)
      call out%add("# egw_version = "//egw_version_string)
      if (present(source)) call out%add("# source = "//source)
      call out%add("# length = "//csv_row([law%length()]))
      call out%add("# modulus = "//csv_row([law%modulus()]))
      call out%add("# units = u, length [length]; pressure, modulus [pressure]; dpdu " &
         & //"[pressure/length]; area: contact-area fraction")
      call out%add("# conventions = u > 0 apart from the mean plane of the heights; " &
         & //"cubic Hermite in (u, ln pressure) between nodes, ln pressure linear beyond")
      do i = 1, n
         if (allocated(law%area)) then
            call out%add(csv_row([law%u(i), p(i), d(i), law%area(i)]))
         else
            call out%add(csv_row([law%u(i), p(i), d(i)]))
         end if
      end do
      call out%add("# end of law, "//int_str(n)//" rows")
      call out%add(checksum_line(out%text(1:out%n)))
      call out%write(path, error)
   end subroutine write_flat_law

   !> Read a law file (egw's, or a user's CSV as above): egw_bad_file naming the path and
   !> the line for anything malformed, egw_io_error when it cannot be read; the nodes are
   !> checked as new_table_law checks them.
   subroutine read_flat_law(path, law, error)
      character(len=*), intent(in) :: path   !< the file to read
      type(table_flat_law), intent(out) :: law   !< the law, its nodes checked
      type(egw_error), allocatable, intent(out) :: error   !< egw_bad_file or egw_io_error, as above
      character(len=:), allocatable :: text
      integer :: body
      logical :: missing
      call read_file(path, text, error)
      if (allocated(error)) return
      call split_checksum(path, text, body, missing, error)
      if (allocated(error)) return
      call parse(path, text(1:body), law, error)
   end subroutine read_flat_law

   subroutine parse(path, text, law, error)
      character(len=*), intent(in) :: path, text
      type(table_flat_law), intent(out) :: law
      type(egw_error), allocatable, intent(out) :: error
      real(dp), allocatable :: rows(:, :), dpdu(:), area(:)
      real(dp) :: length, modulus, v
      integer :: col(4), ncol, start, eol, line, n, k
      logical :: ok, have_columns
      character(len=:), allocatable :: s

      col = 0
      ncol = 0
      length = 0.0_dp
      modulus = 0.0_dp
      have_columns = .false.
      n = 0
      allocate (rows(4, 64))
      start = 1
      line = 0
      do while (start <= len(text))
         eol = index(text(start:), new_line("a"))
         if (eol == 0) then
            eol = len(text) + 1
         else
            eol = start + eol - 1
         end if
         line = line + 1
         s = trim(adjustl(text(start:eol - 1)))
         start = eol + 1
         if (len(s) > 0) then
            if (s(len(s):len(s)) == achar(13)) s = trim(s(1:len(s) - 1))  ! CRLF
         end if
         if (len(s) == 0) cycle
         if (s(1:1) == "#") then
            call header_value(s, "length", length, ok)
            if (ok) call header_value(s, "modulus", modulus, ok)
            if (.not. ok) then
               call bad(error, path, "line "//int_str(line)//": '"//s//"' is not a number")
               return
            end if
         else if (.not. have_columns) then
            call columns(s, col, ncol)
            if (col(1) == 0 .or. col(2) == 0) then
               call bad(error, path, "line "//int_str(line)//": the first line must name " &
                  & //"the columns u and pressure (optionally dpdu, area), e.g. " &
                  & //"'u,pressure'; found '"//s(1:min(len(s), 60))//"'")
               return
            end if
            have_columns = .true.
         else
            n = n + 1
            if (n > max_nodes) then
               call bad(error, path, "more than "//int_str(max_nodes)//" rows")
               return
            end if
            if (n > size(rows, 2)) rows = reshape(rows, [4, 2*size(rows, 2)], pad=rows)
            do k = 1, 4
               if (col(k) == 0) cycle
               call field(s, col(k), v, ok)
               if (.not. ok) then
                  call bad(error, path, "line "//int_str(line)//": field "// &
                     & int_str(col(k))//" is not a number (expected "//int_str(ncol)// &
                     & " comma-separated numbers)")
                  return
               end if
               rows(k, n) = v
            end do
         end if
      end do
      if (n < 2) then
         call bad(error, path, "a rough-flat law needs at least 2 rows of (u, pressure)")
         return
      end if
      ! the optional columns as present or absent arguments
      if (col(3) /= 0) dpdu = rows(3, :n)
      if (col(4) /= 0) area = rows(4, :n)
      call new_table_law(rows(1, :n), rows(2, :n), law, error, dpdu=dpdu, area=area, &
         & length=length, modulus=modulus)
      if (allocated(error)) then
         error%stat = egw_bad_file
         error%message = path//": "//error%message//" (row = node)"
      end if
   end subroutine parse

   !> "# key = number": ok and x set for that key; ok = .true. and x untouched for any
   !> other '#' line; ok = .false. when the key matches but the value is not a number.
   subroutine header_value(s, key, x, ok)
      character(len=*), intent(in) :: s, key
      real(dp), intent(inout) :: x
      logical, intent(out) :: ok
      integer :: eq
      real(dp) :: v
      ok = .true.
      eq = index(s, "=")
      if (eq == 0) return
      if (trim(adjustl(s(2:eq - 1))) /= key) return
      call parse_real(s(eq + 1:), v, ok)
      if (ok) x = v
   end subroutine header_value

   !> Positions of u, pressure, dpdu and area among the header's comma-separated names.
   subroutine columns(s, col, ncol)
      character(len=*), intent(in) :: s
      integer, intent(out) :: col(4), ncol
      integer :: a, b
      character(len=:), allocatable :: name
      col = 0
      ncol = 0
      a = 1
      do
         b = index(s(a:), ",")
         if (b == 0) then
            name = trim(adjustl(s(a:)))
         else
            name = trim(adjustl(s(a:a + b - 2)))
         end if
         ncol = ncol + 1
         select case (name)
         case ("u"); col(1) = ncol
         case ("pressure", "p"); col(2) = ncol
         case ("dpdu"); col(3) = ncol
         case ("area"); col(4) = ncol
         end select
         if (b == 0) exit
         a = a + b
      end do
   end subroutine columns

   !> The k-th comma-separated field of s as a number.
   subroutine field(s, k, x, ok)
      character(len=*), intent(in) :: s
      integer, intent(in) :: k
      real(dp), intent(out) :: x
      logical, intent(out) :: ok
      integer :: a, b, i
      a = 1
      x = 0.0_dp
      ok = .false.
      do i = 1, k - 1
         b = index(s(a:), ",")
         if (b == 0) return
         a = a + b
      end do
      b = index(s(a:), ",")
      if (b == 0) then
         call parse_real(s(a:), x, ok)
      else
         call parse_real(s(a:a + b - 2), x, ok)
      end if
   end subroutine field

end module egw_flat_law_format
