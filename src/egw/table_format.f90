!> Writers and readers of force tables (doc/formats.md): egw CSV with a metadata header,
!> the versioned egw binary format with an FNV-1a checksum, LAMMPS `pair_style table`,
!> and CalculiX/Abaqus `*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR`.
!> Every write goes to a temporary file renamed over the target (egw_io), so a failed
!> write leaves an existing file untouched. Readers build into locals and hand over a
!> table only when the whole file has been checked: a bad file gives egw_bad_file and
!> no table.
module egw_table_format
   use, intrinsic :: iso_fortran_env, only: int32, int64
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_ok, egw_bad_file, egw_io_error, egw_invalid_argument, &
      & egw_invalid_parameter, &
      & egw_unsupported, fatal_error, format_real, int_str, bad => bad_file_error
   use egw_params, only: contact_params, validate_params, model_name, model_epgw
   use egw_version, only: egw_version_string, egw_version_number
   use egw_io, only: write_file, read_file, text_buffer
   use egw_asperity, only: flat_pressure
   use egw_table, only: force_table, table_prepare, table_eval, table_energy
   use egw_table_universal, only: universal_table, universal_slice_params, &
      & universal_nodes_shared, move_universal
   use egw_text, only: real_text, real_text_len, parse_real, parse_int
   implicit none
   private

   public :: split_checksum, checksum_line
   public :: write_table, read_table, write_universal, read_universal, write_lammps, &
      & write_calculix_flat, write_calculix_sphere, fnv1a32

   integer, parameter, public :: format_csv = 0       !< egw CSV with metadata header
   integer, parameter, public :: format_binary = 1    !< egw binary, versioned, checksummed
   integer, parameter, public :: format_lammps = 2    !< LAMMPS pair_style table
   integer, parameter, public :: format_calculix = 3  !< CalculiX/Abaqus tabular overclosure

   !> Binary format version written and the only one read.
   integer(int32), parameter, public :: binary_version = 1
   character(len=8), parameter :: magic_table = "EGWTAB1D", magic_universal = "EGWTABUN"
   integer(int32), parameter :: byte_order_mark = int(z'01020304', int32)
   !> Fixed part of a 1-D table file before the arrays (doc/formats.md).
   integer, parameter :: table_header_bytes = 144
   integer, parameter :: universal_header_bytes = 104, slice_header_bytes = 64
   !> Most points a LAMMPS or CalculiX file gets (resampling is adaptive below this).
   integer, parameter :: max_export_points = 200000
   !> Column headers of the CSV tables (the first line from CSV format 2 on).
   character(len=*), parameter :: csv_columns_table = &
      & "delta,force,stiffness,energy,contact_radius"
   character(len=*), parameter :: csv_columns_universal = &
      & "mu_index,x,p,dp_dx,energy,contact_radius"
   ! numbers are written as ES25.17E3 (17 decimals: every double reads back bit for bit)
   ! CalculiX reads only the first 20 characters of a field: numbers as ES20.12E3, 13
   ! significant digits (relative rounding <= 5e-13, below every rel_tol a curve can be
   ! asked for)
   !> CalculiX 2.20 keeps at most 200 pairs of a tabular curve (silently wrong beyond).
   integer, parameter, public :: calculix_max_pairs = 200

   !> key = value pairs of a CSV header.
   type :: header_dict
      character(len=64), allocatable :: keys(:)
      character(len=256), allocatable :: values(:)
      integer :: n = 0
   end type header_dict

   !> What resample_linear samples: the force of a table against overlap, or the
   !> rough-flat pressure against overclosure (a type, not an internal procedure, so no
   !> trampoline / executable stack is needed).
   type :: sampler
      type(force_table), pointer :: table => null()
      type(contact_params) :: params
      logical :: flat = .false.
      integer :: stat = egw_ok
   end type sampler

contains

   ! =========================================================== dispatch

   !> Write a table in one of the formats (format_csv, format_binary, format_lammps,
   !> format_calculix).
   subroutine write_table(table, path, format, error)
      type(force_table), intent(in) :: table
      character(len=*), intent(in) :: path
      integer, intent(in) :: format
      type(egw_error), allocatable, intent(out) :: error
      if (.not. allocated(table%delta)) then
         call fatal_error(error, egw_invalid_argument, "table: not built or read")
         return
      end if
      select case (format)
      case (format_csv)
         call write_table_csv(table, path, error)
      case (format_binary)
         call write_table_binary(table, path, error)
      case (format_lammps)
         call write_lammps([table], path, error)
      case (format_calculix)
         call write_calculix_sphere(table, path, error)
      case default
         call fatal_error(error, egw_invalid_argument, "format = "//int_str(format)// &
            & ": unknown (0 CSV, 1 binary, 2 LAMMPS, 3 CalculiX)")
      end select
   end subroutine write_table

   !> Read an egw CSV or binary table file (the format is recognised from its start).
   subroutine read_table(path, table, error)
      character(len=*), intent(in) :: path
      type(force_table), intent(out) :: table
      type(egw_error), allocatable, intent(out) :: error
      character(len=:), allocatable :: bytes
      call read_file(path, bytes, error)
      if (allocated(error)) return
      if (len(bytes) >= 8) then
         if (bytes(1:8) == magic_table) then
            call parse_table_binary(path, bytes, table, error)
            return
         end if
      end if
      if (starts_with(bytes, "# egw force table") .or. &
         & starts_with(bytes, csv_columns_table//new_line("a")//"# egw force table")) then
         call parse_table_csv(path, bytes, table, error)
      else
         call fatal_error(error, egw_bad_file, "path = "//path// &
            & ": not an egw table (neither binary magic "//magic_table//" nor CSV header)")
      end if
   end subroutine read_table

   !> Write a universal table (format_csv or format_binary; the DEM/FE formats need one
   !> parameter set: build or slice a 1-D table for them).
   subroutine write_universal(table, path, format, error)
      type(universal_table), intent(in) :: table
      character(len=*), intent(in) :: path
      integer, intent(in) :: format
      type(egw_error), allocatable, intent(out) :: error
      if (.not. allocated(table%slices)) then
         call fatal_error(error, egw_invalid_argument, "table: not built or read")
         return
      end if
      select case (format)
      case (format_csv)
         call write_universal_csv(table, path, error)
      case (format_binary)
         call write_universal_binary(table, path, error)
      case (format_lammps, format_calculix)
         call fatal_error(error, egw_unsupported, "format = "//int_str(format)// &
            & ": LAMMPS and CalculiX files hold one parameter set; use a 1-D table")
      case default
         call fatal_error(error, egw_invalid_argument, "format = "//int_str(format)// &
            & ": unknown (0 CSV, 1 binary)")
      end select
   end subroutine write_universal

   !> Read an egw CSV or binary universal table.
   subroutine read_universal(path, table, error)
      character(len=*), intent(in) :: path
      type(universal_table), intent(out) :: table
      type(egw_error), allocatable, intent(out) :: error
      character(len=:), allocatable :: bytes
      call read_file(path, bytes, error)
      if (allocated(error)) return
      if (len(bytes) >= 8) then
         if (bytes(1:8) == magic_universal) then
            call parse_universal_binary(path, bytes, table, error)
            return
         end if
      end if
      if (starts_with(bytes, "# egw universal table") .or. &
         & starts_with(bytes, csv_columns_universal//new_line("a")//"# egw universal table")) &
         & then
         call parse_universal_csv(path, bytes, table, error)
      else
         call fatal_error(error, egw_bad_file, "path = "//path//": not an egw universal "// &
            & "table (neither binary magic "//magic_universal//" nor CSV header)")
      end if
   end subroutine read_universal

   ! =========================================================== CSV

   subroutine write_table_csv(table, path, error)
      type(force_table), intent(in) :: table
      character(len=*), intent(in) :: path
      type(egw_error), allocatable, intent(out) :: error
      integer :: i
      type(text_buffer) :: out
      ! the column header first and the metadata as '#' lines: pandas.read_csv(path,
      ! comment="#"), numpy.loadtxt(path, delimiter=",", skiprows=1) and
      ! numpy.genfromtxt(path, delimiter=",", names=True) read it as it is
      call out%add(csv_columns_table)
      call out%add("# egw force table, CSV format 3")
      call out%add("# egw_version = "//egw_version_string)
      call write_params_csv(out, table%params)
      call write_table_meta_csv(out, "", table)
      call out%add("# units = consistent set of the parameters: delta, "// &
         & "contact_radius [length]; force [modulus*length^2]; stiffness [modulus*length]; "// &
         & "energy [modulus*length^3]")
      call out%add("# interpolation = cubic Hermite in delta with stiffness as slope; "// &
         & "ln(force) in intervals 1..n_log; force = 0 below cutoff; energy = int of force "// &
         & "from cutoff")
      do i = 1, size(table%delta)
         if (.not. row_ok([table%delta(i), table%force(i), table%stiffness(i), &
            & table%energy(i), table%contact_radius(i)])) then
            call fatal_error(error, egw_invalid_argument, "table: node "//int_str(i)// &
               & " is not finite; nothing written")
            return
         end if
         call out%add(csv_row([table%delta(i), table%force(i), table%stiffness(i), &
            & table%energy(i), table%contact_radius(i)]))
      end do
      call out%add("# end of table, "//int_str(size(table%delta))//" rows")
      call add_checksum(out)
      call out%write(path, error)
   end subroutine write_table_csv

   subroutine write_universal_csv(table, path, error)
      type(universal_table), intent(in) :: table
      character(len=*), intent(in) :: path
      type(egw_error), allocatable, intent(out) :: error
      integer :: i, j, nrows
      type(text_buffer) :: out
      call out%add(csv_columns_universal)  ! first: see write_table_csv
      call out%add("# egw universal table, CSV format 3")
      call out%add("# egw_version = "//egw_version_string)
      call out%add("# model = "//int_str(table%model)//" ("//model_name(table%model)//")")
      call kv(out, "psi", table%psi)
      call kv(out, "hardness_coeff", table%hardness_coeff)
      call kv(out, "plastic_ratio", table%plastic_ratio)
      call kv(out, "rel_tol", table%rel_tol)
      call kv(out, "x_cut", table%x_cut)
      call kv(out, "x_max", table%x_max)
      call kv(out, "mu_min", table%mu_min)
      call kv(out, "mu_max", table%mu_max)
      call kv(out, "max_mu_error", table%max_mu_error)
      call out%add("# n_mu = "//int_str(table%n_mu))
      call out%add("# units = dimensionless: x = delta/sigma; p = P/(E sqrt(R) "// &
         & "sigma^1.5); dp_dx; energy = W/(E sqrt(R) sigma^2.5); contact_radius = "// &
         & "a/sqrt(R sigma); mu_j = mu_min (mu_max/mu_min)^((j-1)/(n_mu-1))")
      do j = 1, table%n_mu
         call kv(out, "slice."//int_str(j)//".mu", table%slices(j)%params%mu)
         call write_table_meta_csv(out, "slice."//int_str(j)//".", table%slices(j))
      end do
      nrows = 0
      do j = 1, table%n_mu
         associate (s => table%slices(j))
            do i = 1, size(s%delta)
               if (.not. row_ok([s%delta(i), s%force(i), s%stiffness(i), s%energy(i), &
                  & s%contact_radius(i)])) then
                  call fatal_error(error, egw_invalid_argument, "table: slice "// &
                     & int_str(j)//" node "//int_str(i)//" is not finite; nothing written")
                  return
               end if
               call out%add(int_str(j)//","//csv_row([s%delta(i), s%force(i), &
                  & s%stiffness(i), s%energy(i), s%contact_radius(i)]))
               nrows = nrows + 1
            end do
         end associate
      end do
      call out%add("# end of table, "//int_str(nrows)//" rows")
      call add_checksum(out)
      call out%write(path, error)
   end subroutine write_universal_csv

   subroutine write_params_csv(out, p)
      type(text_buffer), intent(inout) :: out
      type(contact_params), intent(in) :: p
      call out%add("# model = "//int_str(p%model)//" ("//model_name(p%model)//")")
      call kv(out, "radius", p%radius)
      call kv(out, "modulus", p%modulus)
      call kv(out, "sigma", p%sigma)
      call kv(out, "mu", p%mu)
      call kv(out, "psi", p%psi)
      call kv(out, "hardness_coeff", p%hardness_coeff)
      call kv(out, "plastic_ratio", p%plastic_ratio)
   end subroutine write_params_csv

   subroutine write_table_meta_csv(out, prefix, t)
      type(text_buffer), intent(inout) :: out
      character(len=*), intent(in) :: prefix
      type(force_table), intent(in) :: t
      call kv(out, prefix//"rel_tol", t%rel_tol)
      call kv(out, prefix//"cutoff", t%cutoff)
      call kv(out, prefix//"delta_max", t%delta_max)
      call kv(out, prefix//"reference_force", t%reference_force)
      call kv(out, prefix//"max_force_error", t%max_force_error)
      call kv(out, prefix//"max_stiffness_error", t%max_stiffness_error)
      call kv(out, prefix//"radius_sum", t%radius_sum)
      call out%add("# "//prefix//"n_nodes = "//int_str(size(t%delta)))
      call out%add("# "//prefix//"n_log = "//int_str(t%n_log))
   end subroutine write_table_meta_csv

   subroutine parse_table_csv(path, text, table, error)
      character(len=*), intent(in) :: path, text
      type(force_table), intent(out) :: table
      type(egw_error), allocatable, intent(out) :: error
      type(header_dict) :: dict
      type(force_table) :: t
      real(dp), allocatable :: rows(:, :)
      integer, allocatable :: idx(:)
      integer :: n

      call parse_csv(path, text, 5, csv_columns_table, dict, rows, idx, error, &
         & t%checksum_missing)
      if (allocated(error)) return
      call get_params(path, dict, t%params, error)
      if (allocated(error)) return
      call get_table_meta(path, dict, "", t, n, error)
      if (allocated(error)) return
      if (size(rows, 2) /= n) then
         call bad(error, path, "n_nodes = "//int_str(n)//" but "//int_str(size(rows, 2))// &
            & " data rows")
         return
      end if
      call set_nodes(t, rows)
      call check_table(path, "", t, error)
      if (allocated(error)) return
      call table_prepare(t)
      call move_table(t, table)
   end subroutine parse_table_csv

   subroutine parse_universal_csv(path, text, table, error)
      character(len=*), intent(in) :: path, text
      type(universal_table), intent(out) :: table
      type(egw_error), allocatable, intent(out) :: error
      type(header_dict) :: dict
      type(universal_table) :: u
      real(dp), allocatable :: rows(:, :)
      integer, allocatable :: idx(:)
      integer :: j, n, first
      real(dp) :: mu
      character(len=:), allocatable :: prefix
      logical :: missing

      call parse_csv(path, text, 5, csv_columns_universal, dict, rows, &
         & idx, error, missing)
      if (allocated(error)) return
      call get_int(path, dict, "model", u%model, error)
      if (.not. allocated(error)) call get_real(path, dict, "psi", u%psi, error)
      if (.not. allocated(error)) call get_real(path, dict, "hardness_coeff", &
         & u%hardness_coeff, error)
      if (.not. allocated(error)) call get_real(path, dict, "plastic_ratio", &
         & u%plastic_ratio, error)
      if (.not. allocated(error)) call get_real(path, dict, "rel_tol", u%rel_tol, error)
      if (.not. allocated(error)) call get_real(path, dict, "x_cut", u%x_cut, error)
      if (.not. allocated(error)) call get_real(path, dict, "x_max", u%x_max, error)
      if (.not. allocated(error)) call get_real(path, dict, "mu_min", u%mu_min, error)
      if (.not. allocated(error)) call get_real(path, dict, "mu_max", u%mu_max, error)
      if (.not. allocated(error)) call get_real(path, dict, "max_mu_error", u%max_mu_error, error)
      if (.not. allocated(error)) call get_int(path, dict, "n_mu", u%n_mu, error)
      if (allocated(error)) return
      call check_universal_header(path, u, error)
      if (allocated(error)) return
      allocate (u%slices(u%n_mu))
      first = 1
      do j = 1, u%n_mu
         prefix = "slice."//int_str(j)//"."
         call get_table_meta(path, dict, prefix, u%slices(j), n, error)
         if (.not. allocated(error)) call get_real(path, dict, prefix//"mu", mu, error)
         if (allocated(error)) return
         if (abs(mu - slice_mu(u, j)) > 1.0e-12_dp*mu) then
            call bad(error, path, "slice "//int_str(j)//": mu = "//format_real(mu)// &
               & " is not on the grid")
            return
         end if
         if (first + n - 1 > size(rows, 2)) then
            call bad(error, path, "slice "//int_str(j)//": fewer data rows than n_nodes")
            return
         end if
         if (any(idx(first:first + n - 1) /= j)) then
            call bad(error, path, "slice "//int_str(j)//": rows out of order or missing")
            return
         end if
         u%slices(j)%params = universal_slice_params(u%model, u%psi, u%hardness_coeff, &
            & u%plastic_ratio, mu)
         call set_nodes(u%slices(j), rows(:, first:first + n - 1))
         call check_table(path, "slice "//int_str(j)//": ", u%slices(j), error)
         if (allocated(error)) return
         call table_prepare(u%slices(j))
         first = first + n
      end do
      if (first - 1 /= size(rows, 2)) then
         call bad(error, path, "more data rows than the slices' n_nodes")
         return
      end if
      call check_common_cutoff(path, u, error)
      if (allocated(error)) return
      if (.not. universal_nodes_shared(u)) then
         call bad(error, path, "slices do not share their nodes or ln p intervals")
         return
      end if
      call move_universal(u, table)
   end subroutine parse_universal_csv

   !> Split a CSV file into its "# key = value" header, check the column header line,
   !> read ncol reals per data row (after an integer index when the columns start with
   !> "mu_index") and require the "# end of table, N rows" trailer (so that a file cut
   !> inside its last number is detected). A last line "# fnv1a32 = ..." (CSV format
   !> 3) must match the checksum of the bytes above it; checksum_missing tells whether
   !> it was absent (a format 1 or 2 file, or a hand-edited one).
   subroutine parse_csv(path, file_text, ncol, columns, dict, rows, idx, error, &
      & checksum_missing)
      character(len=*), intent(in) :: path, file_text, columns
      logical, intent(out) :: checksum_missing
      integer, intent(in) :: ncol
      type(header_dict), intent(out) :: dict
      real(dp), allocatable, intent(out) :: rows(:, :)
      integer, allocatable, intent(out) :: idx(:)
      type(egw_error), allocatable, intent(out) :: error
      integer :: pos, eol, nrow, line_no, eq, cap, n_end
      logical :: in_data, ended, indexed, ok
      character(len=:), allocatable :: line
      real(dp) :: vals(ncol)
      integer :: j, body

      call split_checksum(path, file_text, body, checksum_missing, error)
      if (allocated(error)) return
      associate (text => file_text(1:body))
      indexed = starts_with(columns, "mu_index")
      cap = 1024
      allocate (rows(ncol, cap), idx(cap), dict%keys(64), dict%values(64))
      nrow = 0
      pos = 1
      line_no = 0
      in_data = .false.
      ended = .false.
      do while (pos <= len(text))
         eol = index(text(pos:), new_line("a"))
         if (eol == 0) then
            ! a complete file ends with a newline: a missing one means truncation
            call bad(error, path, "truncated (last line has no end of line)")
            return
         end if
         line = text(pos:pos + eol - 2)
         pos = pos + eol
         line_no = line_no + 1
         if (len(line) > 0) then
            if (line(len(line):len(line)) == achar(13)) line = line(1:len(line) - 1)
         end if
         if (ended) then
            if (len_trim(line) > 0) then
               call bad(error, path, "line "//int_str(line_no)//": text after the end line")
               return
            end if
            cycle
         end if
         if (starts_with(line, "# end of table,")) then
            call parse_int(first_token(line(16:)), n_end, ok)
            if (.not. ok .or. n_end /= nrow .or. .not. in_data) then
               call bad(error, path, "line "//int_str(line_no)//": end line does not match "// &
                  & int_str(nrow)//" data rows")
               return
            end if
            ended = .true.
         else if (starts_with(line, "#")) then
            if (nrow > 0) then
               call bad(error, path, "line "//int_str(line_no)//": comment inside the data")
               return
            end if
            eq = index(line, "=")
            if (eq > 0) call dict_add(dict, adjustl(trim(line(2:eq - 1))), &
               & adjustl(trim(line(eq + 1:))))
         else if (.not. in_data) then
            if (trim(line) /= columns) then
               call bad(error, path, "line "//int_str(line_no)//": expected column header '"// &
                  & columns//"'")
               return
            end if
            in_data = .true.
         else
            call split_row(line, indexed, j, vals, ok)
            if (.not. ok) then
               call bad(error, path, "line "//int_str(line_no)//": cannot read "// &
                  & int_str(ncol)//" numbers")
               return
            end if
            if (nrow == cap) then
               cap = 2*cap
               call grow(rows, idx, cap)
            end if
            nrow = nrow + 1
            rows(:, nrow) = vals
            idx(nrow) = j
         end if
      end do
      if (.not. ended) then
         call bad(error, path, "truncated (no '# end of table' line)")
         return
      end if
      rows = rows(:, 1:nrow)
      idx = idx(1:nrow)
      end associate
   end subroutine parse_csv

   !> The checksum line of a CSV file: body = the bytes before it (all of text if
   !> there is none, then missing = true); a checksum that does not match is an error.
   subroutine split_checksum(path, text, body, missing, error)
      character(len=*), intent(in) :: path, text
      integer, intent(out) :: body
      logical, intent(out) :: missing
      type(egw_error), allocatable, intent(out) :: error
      character(len=*), parameter :: key = "# fnv1a32 = "
      integer :: start
      body = len(text)
      missing = .true.
      if (len(text) < 2) return
      if (text(len(text):len(text)) /= new_line("a")) return
      start = index(text(1:len(text) - 1), new_line("a"), back=.true.) + 1
      if (.not. starts_with(text(start:), key)) return
      missing = .false.
      body = start - 1
      ! the whole line, so that no byte of the file escapes the check
      if (text(start:len(text) - 1) /= checksum_line(text(1:body))) then
         call bad(error, path, "checksum mismatch: the file was changed after egw wrote "// &
            & "it (corrupted, or edited by hand: an edited file is read, unchecked, once "// &
            & "its '# fnv1a32' line is deleted)")
      end if
   end subroutine split_checksum

   !> Append the checksum line of CSV format 3: the FNV-1a hash of all bytes above it.
   subroutine add_checksum(out)
      type(text_buffer), intent(inout) :: out
      call out%add(checksum_line(out%text(1:out%n)))
   end subroutine add_checksum

   pure function checksum_line(above) result(line)
      character(len=*), intent(in) :: above
      character(len=60) :: line
      line = "# fnv1a32 = "//hex8(fnv1a32(above))//" (checksum of the bytes above this line)"
   end function checksum_line

   !> The low 32 bits of h as 8 lowercase hexadecimal digits.
   pure function hex8(h) result(str)
      integer(int64), intent(in) :: h
      character(len=8) :: str
      character(len=*), parameter :: symbols = "0123456789abcdef"
      integer :: i, d
      do i = 1, 8
         d = int(iand(ishft(h, -4*(8 - i)), 15_int64))
         str(i:i) = symbols(d + 1:d + 1)
      end do
   end function hex8

   ! =========================================================== binary

   subroutine write_table_binary(table, path, error)
      type(force_table), intent(in) :: table
      character(len=*), intent(in) :: path
      type(egw_error), allocatable, intent(out) :: error
      character(len=:), allocatable :: buf
      integer :: n, pos
      n = size(table%delta)
      if (.not. (row_ok(table%delta) .and. row_ok(table%force) .and. row_ok(table%stiffness) &
         & .and. row_ok(table%energy) .and. row_ok(table%contact_radius))) then
         call fatal_error(error, egw_invalid_argument, "table: a node is not finite; "// &
            & "nothing written")
         return
      end if
      allocate (character(len=table_header_bytes + 40*n + 4) :: buf)
      buf(1:8) = magic_table
      pos = 9
      call put_i32(buf, pos, binary_version)
      call put_i32(buf, pos, byte_order_mark)
      call put_i32(buf, pos, int(egw_version_number, int32))
      call put_i32(buf, pos, int(table%params%model, int32))
      call put_i32(buf, pos, int(n, int32))
      call put_i32(buf, pos, int(table%n_log, int32))
      call put_f64(buf, pos, [table%params%radius, table%params%modulus, table%params%sigma, &
         & table%params%mu, table%params%psi, table%params%hardness_coeff, &
         & table%params%plastic_ratio])
      call put_f64(buf, pos, [table%rel_tol, table%cutoff, table%delta_max, &
         & table%reference_force, table%max_force_error, table%max_stiffness_error, &
         & table%radius_sum])
      call put_f64(buf, pos, table%delta)
      call put_f64(buf, pos, table%force)
      call put_f64(buf, pos, table%stiffness)
      call put_f64(buf, pos, table%energy)
      call put_f64(buf, pos, table%contact_radius)
      call write_checked(path, buf, pos, error)
   end subroutine write_table_binary

   subroutine write_universal_binary(table, path, error)
      type(universal_table), intent(in) :: table
      character(len=*), intent(in) :: path
      type(egw_error), allocatable, intent(out) :: error
      character(len=:), allocatable :: buf
      integer :: nbytes, pos, j, n
      nbytes = universal_header_bytes + 4
      do j = 1, table%n_mu
         nbytes = nbytes + slice_header_bytes + 40*size(table%slices(j)%delta)
      end do
      allocate (character(len=nbytes) :: buf)
      buf(1:8) = magic_universal
      pos = 9
      call put_i32(buf, pos, binary_version)
      call put_i32(buf, pos, byte_order_mark)
      call put_i32(buf, pos, int(egw_version_number, int32))
      call put_i32(buf, pos, int(table%model, int32))
      call put_i32(buf, pos, int(table%n_mu, int32))
      call put_i32(buf, pos, 0_int32)
      call put_f64(buf, pos, [table%psi, table%hardness_coeff, table%plastic_ratio, &
         & table%rel_tol, table%x_cut, table%x_max, table%mu_min, table%mu_max, &
         & table%max_mu_error])
      do j = 1, table%n_mu
         associate (s => table%slices(j))
            n = size(s%delta)
            call put_i32(buf, pos, int(n, int32))
            call put_i32(buf, pos, int(s%n_log, int32))
            call put_f64(buf, pos, [s%rel_tol, s%cutoff, s%delta_max, s%reference_force, &
               & s%max_force_error, s%max_stiffness_error, s%params%mu])
            call put_f64(buf, pos, s%delta)
            call put_f64(buf, pos, s%force)
            call put_f64(buf, pos, s%stiffness)
            call put_f64(buf, pos, s%energy)
            call put_f64(buf, pos, s%contact_radius)
         end associate
      end do
      call write_checked(path, buf, pos, error)
   end subroutine write_universal_binary

   !> Append the checksum of buf(1:pos-1) and write buf atomically.
   subroutine write_checked(path, buf, pos, error)
      character(len=*), intent(in) :: path
      character(len=*), intent(inout) :: buf
      integer, intent(inout) :: pos
      type(egw_error), allocatable, intent(out) :: error
      call put_i32(buf, pos, checksum_i32(fnv1a32(buf(1:pos - 1))))
      call write_file(path, buf(1:pos - 1), error)
   end subroutine write_checked

   subroutine parse_table_binary(path, bytes, table, error)
      character(len=*), intent(in) :: path, bytes
      type(force_table), intent(out) :: table
      type(egw_error), allocatable, intent(out) :: error
      type(force_table) :: t
      integer :: pos, n
      integer(int32) :: model
      real(dp) :: p(7), meta(7)

      call check_binary_frame(path, bytes, table_header_bytes, error)
      if (allocated(error)) return
      pos = 21
      model = get_i32(bytes, pos)
      n = get_i32(bytes, pos)
      t%n_log = get_i32(bytes, pos)
      if (n < 2 .or. len(bytes) /= table_header_bytes + 40*int(n, int64) + 4) then
         call bad(error, path, "n_nodes = "//int_str(n)//" does not match the file size "// &
            & int_str(len(bytes)))
         return
      end if
      call get_f64(bytes, pos, p)
      call get_f64(bytes, pos, meta)
      t%params = contact_params(model=int(model), radius=p(1), modulus=p(2), sigma=p(3), &
         & mu=p(4), psi=p(5), hardness_coeff=p(6), plastic_ratio=p(7))
      call set_meta(t, meta)
      allocate (t%delta(n), t%force(n), t%stiffness(n), t%energy(n), t%contact_radius(n))
      call get_f64(bytes, pos, t%delta)
      call get_f64(bytes, pos, t%force)
      call get_f64(bytes, pos, t%stiffness)
      call get_f64(bytes, pos, t%energy)
      call get_f64(bytes, pos, t%contact_radius)
      call validate_params(t%params, error)
      if (allocated(error)) then
         call bad(error, path, "stored parameters invalid: "//error%message)
         return
      end if
      call check_table(path, "", t, error)
      if (allocated(error)) return
      call table_prepare(t)
      call move_table(t, table)
   end subroutine parse_table_binary

   subroutine parse_universal_binary(path, bytes, table, error)
      character(len=*), intent(in) :: path, bytes
      type(universal_table), intent(out) :: table
      type(egw_error), allocatable, intent(out) :: error
      type(universal_table) :: u
      integer :: pos, j, n
      real(dp) :: h(9), meta(7)

      call check_binary_frame(path, bytes, universal_header_bytes, error)
      if (allocated(error)) return
      pos = 21
      u%model = get_i32(bytes, pos)
      u%n_mu = get_i32(bytes, pos)
      pos = pos + 4
      call get_f64(bytes, pos, h)
      u%psi = h(1); u%hardness_coeff = h(2); u%plastic_ratio = h(3); u%rel_tol = h(4)
      u%x_cut = h(5); u%x_max = h(6); u%mu_min = h(7); u%mu_max = h(8); u%max_mu_error = h(9)
      call check_universal_header(path, u, error)
      if (allocated(error)) return
      allocate (u%slices(u%n_mu))
      do j = 1, u%n_mu
         if (pos + slice_header_bytes > len(bytes) - 4) then
            call bad(error, path, "slice "//int_str(j)//": file too short")
            return
         end if
         n = get_i32(bytes, pos)
         u%slices(j)%n_log = get_i32(bytes, pos)
         call get_f64(bytes, pos, meta)
         if (n < 2 .or. pos - 1 + 40*int(n, int64) > len(bytes) - 4) then
            call bad(error, path, "slice "//int_str(j)//": n_nodes = "//int_str(n)// &
               & " does not fit the file size")
            return
         end if
         associate (s => u%slices(j))
            call set_meta(s, [meta(1:6), 0.0_dp])
            s%params = universal_slice_params(u%model, u%psi, u%hardness_coeff, &
               & u%plastic_ratio, meta(7))
            allocate (s%delta(n), s%force(n), s%stiffness(n), s%energy(n), s%contact_radius(n))
            call get_f64(bytes, pos, s%delta)
            call get_f64(bytes, pos, s%force)
            call get_f64(bytes, pos, s%stiffness)
            call get_f64(bytes, pos, s%energy)
            call get_f64(bytes, pos, s%contact_radius)
            if (abs(meta(7) - slice_mu(u, j)) > 1.0e-12_dp*meta(7)) then
               call bad(error, path, "slice "//int_str(j)//": mu = "//format_real(meta(7))// &
                  & " is not on the grid")
               return
            end if
            call check_table(path, "slice "//int_str(j)//": ", s, error)
            if (allocated(error)) return
            call table_prepare(s)
         end associate
      end do
      if (pos /= len(bytes) - 3) then
         call bad(error, path, "file size does not match its slices")
         return
      end if
      call check_common_cutoff(path, u, error)
      if (allocated(error)) return
      if (.not. universal_nodes_shared(u)) then
         call bad(error, path, "slices do not share their nodes or ln p intervals")
         return
      end if
      call move_universal(u, table)
   end subroutine parse_universal_binary

   !> Magic, version, byte order, minimum size and checksum of a binary file.
   subroutine check_binary_frame(path, bytes, header_bytes, error)
      character(len=*), intent(in) :: path, bytes
      integer, intent(in) :: header_bytes
      type(egw_error), allocatable, intent(out) :: error
      integer :: pos
      integer(int32) :: version, bom, stored
      if (len(bytes) < header_bytes + 4) then
         call bad(error, path, "truncated: "//int_str(len(bytes))//" bytes, header needs "// &
            & int_str(header_bytes + 4))
         return
      end if
      pos = 9
      version = get_i32(bytes, pos)
      bom = get_i32(bytes, pos)
      if (bom /= byte_order_mark) then
         call bad(error, path, "byte order mark "//int_str(int(bom))//": written on a "// &
            & "machine of the other endianness, or corrupted")
         return
      end if
      if (version /= binary_version) then
         call bad(error, path, "format version "//int_str(int(version))// &
            & " is not supported (this egw reads version "//int_str(int(binary_version))//")")
         return
      end if
      pos = len(bytes) - 3
      stored = get_i32(bytes, pos)
      if (stored /= checksum_i32(fnv1a32(bytes(1:len(bytes) - 4)))) then
         call bad(error, path, "checksum mismatch: file is corrupted or truncated")
         return
      end if
   end subroutine check_binary_frame

   !> FNV-1a 32-bit hash of a byte string (offset basis 2166136261, prime 16777619),
   !> returned in the low 32 bits of an int64. Products stay below 2^57: no overflow.
   pure function fnv1a32(bytes) result(h)
      character(len=*), intent(in) :: bytes
      integer(int64) :: h
      integer :: i
      integer(int64), parameter :: mask = int(z'FFFFFFFF', int64)
      h = 2166136261_int64
      do i = 1, len(bytes)
         h = ieor(h, int(ichar(bytes(i:i)), int64))
         h = iand(h*16777619_int64, mask)
      end do
   end function fnv1a32

   !> The unsigned 32-bit checksum as the int32 with the same bits.
   pure integer(int32) function checksum_i32(h)
      integer(int64), intent(in) :: h
      if (h >= 2147483648_int64) then
         checksum_i32 = int(h - 4294967296_int64, int32)
      else
         checksum_i32 = int(h, int32)
      end if
   end function checksum_i32

   ! =========================================================== LAMMPS

   !> LAMMPS pair_style table file, one section per table (particle-type pair), keywords
   !> EGW_1, EGW_2, ... Distances r = R1 + R2 - delta, uniform in r (N points R rlo rhi),
   !> from the largest overlap (rlo) to the cut-off (rhi); energy = work of the force from
   !> the cut-off, force = -dE/dr = P. N is doubled (from 500) until linear interpolation
   !> between the points reproduces the table to rel_tol * P_ref.
   !>
   !> The first line carries no `UNITS:` tag unless units is given: LAMMPS (29 Sep 2021
   !> and later) reads `UNITS: <style>` on a potential file's first line and refuses the
   !> file when <style> differs from the run's units command. egw's numbers are in the
   !> units of the parameters; pass units (a LAMMPS units style such as "si", "metal")
   !> only when they are that style's force/length/energy units: it is then written as
   !> `# DATE: ... UNITS: <units>` and LAMMPS checks it against the input deck.
   subroutine write_lammps(tables, path, error, units, delta_reach)
      type(force_table), intent(in) :: tables(:)
      character(len=*), intent(in) :: path
      type(egw_error), allocatable, intent(out) :: error
      character(len=*), intent(in), optional :: units
      !> deepest overlap the sections reach (>= each table's delta_max; beyond delta_max
      !> the force continues linearly with the end stiffness, as table_eval does); LAMMPS
      !> stops with "Pair distance < table inner cutoff" at deeper overlaps
      real(dp), intent(in), optional :: delta_reach
      integer :: s, i, n
      type(text_buffer) :: out
      real(dp) :: rsum, rlo, rhi, r, d, f, k, e, reach
      character(len=:), allocatable :: note

      do s = 1, size(tables)
         if (.not. allocated(tables(s)%delta)) then
            call fatal_error(error, egw_invalid_argument, "tables("//int_str(s)// &
               & "): not built or read")
            return
         end if
      end do
      if (present(units)) then
         if (len_trim(units) == 0 .or. verify(trim(units), &
            & "abcdefghijklmnopqrstuvwxyz") /= 0) then
            call fatal_error(error, egw_invalid_argument, "units = '"//units// &
               & "': must be a LAMMPS units style (lowercase letters, e.g. si)")
            return
         end if
      end if
      if (present(units)) then
         call out%add("# DATE: "//egw_version_string//" UNITS: "//trim(units)// &
            & " CONTRIBUTOR: egw")
      else
         ! lowercase on purpose: an uppercase UNITS: tag is a unit style for LAMMPS
         call out%add("# egw tables, units: those of the egw parameters (force = "// &
            & "modulus*length^2, energy = force*length)")
      end if
      call out%add("# egw "//egw_version_string//" contact force tables for "// &
         & "pair_style table (linear or spline, N >= the section's N)")
      do s = 1, size(tables)
         associate (t => tables(s))
            if (t%radius_sum > 0.0_dp) then
               rsum = t%radius_sum
               note = "R1 + R2 = "//fmt(rsum)//" (particle radii)"
            else
               rsum = 4*t%params%radius
               note = "R1 = R2 = 2R = "//fmt(2*t%params%radius)//": built from the "// &
                  & "equivalent radius R alone, distances are for two equal spheres"
            end if
            reach = t%delta_max
            if (present(delta_reach)) reach = max(reach, delta_reach)
            rlo = rsum - reach
            rhi = rsum - t%cutoff
            n = lammps_points(t, rsum, rlo, rhi)
            call out%add("")
            call out%add("# section EGW_"//int_str(s)//": model "// &
               & model_name(t%params%model)//", R = "//fmt(t%params%radius)//", E = "// &
               & fmt(t%params%modulus)//", sigma = "//fmt(t%params%sigma)//", mu = "// &
               & fmt(t%params%mu)//", psi = "//fmt(t%params%psi)//", K = "// &
               & fmt(t%params%hardness_coeff)//", rho_p = "//fmt(t%params%plastic_ratio))
            if (t%params%model == model_epgw) call out%add("# EP-GW: the LOADING "// &
               & "curve only (pair_style table is a function of r alone: no unloading "// &
               & "hysteresis, restitution 1; egw_hysteresis_* carries the dissipation)")
            call out%add("# r = R1 + R2 - delta with "//note)
            call out%add("# force = -dE/dr = P(delta) >= 0 (repulsive), zero for r > "// &
               & fmt(rhi)//" (pair cutoff); energy = int of P from the cut-off")
            call out%add("# rel_tol = "//fmt(t%rel_tol)//" relative to P_ref = "// &
               & fmt(t%reference_force))
            call out%add("# ends: r > "//fmt(rhi)//" (delta < cutoff): no force; r < "// &
               & fmt(rlo)//" (delta > "//fmt(reach)//"): LAMMPS stops with 'Pair distance "// &
               & "< table inner cutoff'")
            if (reach > t%delta_max) call out%add("# delta in ("// &
               & fmt(t%delta_max)//", "//fmt(reach)//"]: beyond the table's delta_max, "// &
               & "force continued linearly with the end stiffness")
            if (t%params%model == model_epgw .and. t%params%psi > 0.0_dp) call out%add(&
               & "# EP-GW: loading curve only (pair_style table has no history: no "// &
               & "unloading hysteresis, no plastic dissipation)")
            if (rlo <= 0.0_dp) then
               call fatal_error(error, egw_invalid_argument, "delta_max = "// &
                  & format_real(reach)//": r = R1 + R2 - delta_max must be > 0")
               return
            end if
            call out%add("EGW_"//int_str(s))
            call out%add("N "//int_str(n)//" R "//fmt(rlo)//" "//fmt(rhi))
            call out%add("")
            do i = 1, n
               r = rlo + (rhi - rlo)*(i - 1)/(n - 1)
               d = rsum - r
               if (i == n) d = t%cutoff
               call table_eval(t, d, f, k)
               e = table_energy(t, d)
               if (.not. row_ok([r, e, f])) then
                  call fatal_error(error, egw_invalid_argument, "tables("//int_str(s)// &
                     & "): not finite at delta = "//format_real(d)//"; nothing written")
                  return
               end if
               call out%add(int_str(i)//" "//fmt(r)//" "//fmt(e)//" "//fmt(f))
            end do
         end associate
      end do
      call out%write(path, error)
   end subroutine write_lammps

   !> Points of a LAMMPS section: doubled until the midpoint linear-interpolation error
   !> of the force is <= rel_tol * P_ref everywhere (or the point limit is reached).
   function lammps_points(t, rsum, rlo, rhi) result(n)
      type(force_table), intent(in) :: t
      real(dp), intent(in) :: rsum, rlo, rhi
      integer :: n, i
      real(dp) :: h, f0, f1, fm, k, worst
      n = 500
      do
         h = (rhi - rlo)/(n - 1)
         worst = 0
         call table_eval(t, rsum - rlo, f0, k)
         do i = 1, n - 1
            call table_eval(t, rsum - (rlo + i*h), f1, k)
            call table_eval(t, rsum - (rlo + (i - 0.5_dp)*h), fm, k)
            worst = max(worst, abs(0.5_dp*(f0 + f1) - fm))
            f0 = f1
         end do
         if (worst <= t%rel_tol*t%reference_force .or. 2*n > max_export_points) exit
         n = 2*n - 1
      end do
   end function lammps_points

   ! =========================================================== CalculiX

   !> Node-to-surface sphere contact: force per node against overclosure = overlap delta,
   !> first pair (0, delta_c); at most calculix_max_pairs pairs placed so that the linear
   !> interpolation CalculiX applies reproduces the table (see fit_pairs). With shift,
   !> overclosure is measured from the cut-off, delta - delta_c (first pair (0, 0)):
   !> CalculiX makes node-to-surface contact springs only where the surfaces touch or
   !> penetrate, so a curve starting at negative overclosure is never reached there; the
   !> model's surfaces then stand for the spheres at overlap delta_c when they touch.
   !> max_error: the achieved error (as in the file's header).
   subroutine write_calculix_sphere(t, path, error, shift, max_error)
      type(force_table), intent(in), target :: t
      character(len=*), intent(in) :: path
      type(egw_error), allocatable, intent(out) :: error
      logical, intent(in), optional :: shift
      real(dp), intent(out), optional :: max_error
      real(dp), allocatable :: x(:), y(:)
      real(dp) :: achieved, origin
      type(text_buffer) :: out
      type(sampler) :: smp
      logical :: shifted
      shifted = .false.
      if (present(shift)) shifted = shift
      smp%table => t
      call fit_pairs(smp, t%cutoff, t%delta_max, t%rel_tol, t%rel_tol*t%reference_force, &
         & x, y, achieved)
      if (present(max_error)) max_error = achieved
      if (smp%stat /= egw_ok) then
         call fatal_error(error, smp%stat, "table: force not finite; nothing written")
         return
      end if
      y(1) = 0.0_dp
      origin = 0.0_dp
      if (shifted) origin = t%cutoff
      call out%add("** egw "//egw_version_string//": rough-sphere contact, model "// &
         & model_name(t%params%model)//", R = "//fmt(t%params%radius)//", E = "// &
         & fmt(t%params%modulus)//", sigma = "//fmt(t%params%sigma)//", mu = "// &
         & fmt(t%params%mu))
      if (t%params%model == model_epgw) call out%add("** EP-GW: the LOADING curve "// &
         & "only (a pressure-overclosure curve has no history: no unloading hysteresis)")
      if (shifted) then
         call out%add("** node-to-surface contact: FORCE per node against "// &
            & "overclosure = delta - delta_c (shifted: overlap delta = overclosure + "// &
            & fmt(t%cutoff)//"); force 0 below overclosure 0")
      else
         call out%add("** node-to-surface contact: FORCE per node against "// &
            & "overclosure (= overlap delta); force 0 below overclosure "//fmt(t%cutoff))
      end if
      call write_error_comment(out, t%rel_tol, achieved, size(x))
      call write_pairs(out, x - origin, y, error)
      if (allocated(error)) return
      call out%write(path, error)
   end subroutine write_calculix_sphere

   !> Rough flat: nominal pressure p_G(d) (egw_asperity) against overclosure = -d, from
   !> the separation d_c where p_G has fallen to rel_tol * p_G(0) (first pair at zero
   !> pressure) to overclosure_max; at most calculix_max_pairs pairs (fit_pairs). With
   !> shift, overclosure is measured from d_c: overclosure = d_c - d (first pair (0, 0);
   !> the model's surfaces are the summit base planes at separation d_c, see
   !> write_calculix_sphere for why CalculiX needs this). max_error: the achieved error.
   subroutine write_calculix_flat(params, overclosure_max, rel_tol, path, error, shift, &
      & max_error)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: overclosure_max, rel_tol
      character(len=*), intent(in) :: path
      type(egw_error), allocatable, intent(out) :: error
      logical, intent(in), optional :: shift
      real(dp), intent(out), optional :: max_error
      real(dp), allocatable :: x(:), y(:)
      real(dp) :: p0, dp0, pc, d_c, step, achieved, origin
      integer :: it
      type(text_buffer) :: out
      type(sampler) :: smp
      logical :: shifted

      shifted = .false.
      if (present(shift)) shifted = shift
      call validate_params(params, error)
      if (allocated(error)) return
      if (.not. params%sigma > 0.0_dp) then
         call fatal_error(error, egw_invalid_parameter, "sigma = "//format_real(params%sigma)// &
            & ": a rough flat needs sigma > 0")
         return
      end if
      if (.not. (rel_tol >= 1.0e-12_dp .and. rel_tol <= 0.1_dp)) then
         call fatal_error(error, egw_invalid_argument, "rel_tol = "//format_real(rel_tol)// &
            & ": must lie in [1e-12, 0.1]")
         return
      end if
      if (.not. (ieee_is_finite(overclosure_max) .and. overclosure_max > 0.0_dp)) then
         call fatal_error(error, egw_invalid_argument, "overclosure_max = "// &
            & format_real(overclosure_max)//": must be finite and > 0")
         return
      end if
      call flat_pressure(params, 0.0_dp, p0, dp0, error)
      if (allocated(error)) return
      ! separation where p_G falls below rel_tol * p_G(0): step out by sigma
      d_c = 0.0_dp
      step = params%sigma
      do it = 1, 200
         d_c = d_c + step
         call flat_pressure(params, d_c, pc, dp0, error)
         if (allocated(error)) return
         if (pc <= rel_tol*p0) exit
      end do
      smp%params = params
      smp%flat = .true.
      call fit_pairs(smp, -d_c, overclosure_max, rel_tol, rel_tol*p0, x, y, achieved)
      if (present(max_error)) max_error = achieved
      if (smp%stat /= egw_ok) then
         call fatal_error(error, smp%stat, "flat_pressure failed while sampling p_G")
         return
      end if
      y(1) = 0.0_dp
      origin = 0.0_dp
      if (shifted) origin = -d_c
      call out%add("** egw "//egw_version_string//": rough flat, GW nominal "// &
         & "pressure p_G (doc/theory.md section 3), model "//model_name(params%model)// &
         & ", E = "//fmt(params%modulus)//", sigma = "//fmt(params%sigma)//", mu = "// &
         & fmt(params%mu)//", R = "//fmt(params%radius)//", psi = "//fmt(params%psi))
      if (shifted) then
         call out%add("** PRESSURE against overclosure = d_c - separation of the "// &
            & "summit base plane, d_c = "//fmt(d_c)//" (shifted); pressure 0 for "// &
            & "overclosure < 0")
      else
         call out%add("** PRESSURE against overclosure = -separation of the summit "// &
            & "base plane; pressure 0 for overclosure < "//fmt(-d_c))
      end if
      call write_error_comment(out, rel_tol, achieved, size(x))
      call write_pairs(out, x - origin, y, error)
      if (allocated(error)) return
      call out%write(path, error)
   end subroutine write_calculix_flat

   !> Header lines on the interpolation error achieved (and a warning if above rel_tol).
   subroutine write_error_comment(out, rel_tol, achieved, n)
      type(text_buffer), intent(inout) :: out
      integer, intent(in) :: n
      real(dp), intent(in) :: rel_tol, achieved
      call out%add("** linear interpolation between pairs within rel_tol = "// &
         & fmt(rel_tol)//" requested; max error achieved = "//fmt(achieved)// &
         & " (relative to max(|value|, rel_tol*reference)); "//int_str(n)//" pairs")
      if (achieved > rel_tol) call out%add("** WARNING: rel_tol not met within "// &
         & "CalculiX's limit of "//int_str(calculix_max_pairs)//" pairs per curve")
   end subroutine write_error_comment

   subroutine write_pairs(out, x, y, error)
      type(text_buffer), intent(inout) :: out
      real(dp), intent(in) :: x(:), y(:)
      type(egw_error), allocatable, intent(out) :: error
      integer :: i
      call out%add("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR")
      do i = 1, size(x)
         if (.not. row_ok([x(i), y(i)])) then
            call fatal_error(error, egw_invalid_argument, "value at overclosure "// &
               & format_real(x(i))//" is not finite; nothing written")
            return
         end if
         call out%add(fmt20(y(i))//", "//fmt20(x(i)))
      end do
   end subroutine write_pairs

   !> At most calculix_max_pairs points on [a, b] for linear interpolation of g. First
   !> the bisection of resample_linear at rel_tol; if that needs more points, they are
   !> placed by equidistributing the interpolation error: on the fine bisection grid
   !> interval j has midpoint error e_j ~ c h_j^2, so covering it with m_j intervals
   !> gives e_j/m_j^2, and the largest error over the curve is smallest when m_j is
   !> proportional to sqrt(e_j): the new points split the cumulative sum of sqrt(e_j)
   !> equally. achieved = the largest midpoint error of the result, relative to
   !> max(|g|, floor) (floor = rel_tol * the curve's reference value: the tail below it
   !> needs only absolute accuracy).
   subroutine fit_pairs(g, a, b, rel_tol, floor, x, y, achieved)
      type(sampler), intent(inout) :: g
      real(dp), intent(in) :: a, b, rel_tol, floor
      real(dp), allocatable, intent(out) :: x(:), y(:)
      real(dp), intent(out) :: achieved
      real(dp), allocatable :: xf(:), yf(:), w(:)
      real(dp) :: target, frac
      integer :: nf, j, k
      call resample_linear(g, a, b, rel_tol, xf, yf)
      nf = size(xf)
      if (g%stat /= egw_ok) return
      if (nf <= calculix_max_pairs) then
         call move_alloc(xf, x)
         call move_alloc(yf, y)
      else
         allocate (w(0:nf - 1))
         w(0) = 0.0_dp
         do j = 1, nf - 1
            w(j) = w(j - 1) + sqrt(midpoint_error(g, xf(j), xf(j + 1), yf(j), yf(j + 1), &
               & floor))
         end do
         allocate (x(calculix_max_pairs), y(calculix_max_pairs))
         x(1) = a
         x(calculix_max_pairs) = b
         j = 1
         do k = 2, calculix_max_pairs - 1
            target = w(nf - 1)*(k - 1)/(calculix_max_pairs - 1)
            do while (w(j) < target .and. j < nf - 1)
               j = j + 1
            end do
            ! target lies in fine interval j: w(j-1) <= target <= w(j)
            frac = 0.5_dp
            if (w(j) > w(j - 1)) frac = (target - w(j - 1))/(w(j) - w(j - 1))
            x(k) = xf(j) + frac*(xf(j + 1) - xf(j))
         end do
         ! keep the points strictly increasing (plateaus of w can stack them)
         do k = 2, calculix_max_pairs - 1
            x(k) = max(x(k), x(k - 1) + 1.0e-9_dp*(b - a))
         end do
         do k = 1, calculix_max_pairs
            y(k) = sample(g, x(k))
         end do
         call equalise_errors(g, floor, x, y)
      end if
      achieved = 0.0_dp
      do k = 1, size(x) - 1
         achieved = max(achieved, midpoint_error(g, x(k), x(k + 1), y(k), y(k + 1), floor))
      end do
   end subroutine fit_pairs

   !> A few passes of de Boor's equidistribution on the points themselves: interval k
   !> with midpoint error e_k would need sqrt(e_k/eps) intervals for error eps, so the
   !> points are moved to split the cumulative sum of sqrt(e_k) (linear within each
   !> interval) equally. The fine-grid estimate of fit_pairs is only a start (its
   !> errors are sampled once per fine interval); the best set of the passes is kept.
   subroutine equalise_errors(g, floor, x, y)
      type(sampler), intent(inout) :: g
      real(dp), intent(in) :: floor
      real(dp), intent(inout) :: x(:), y(:)
      real(dp) :: w(0:size(x) - 1), xn(size(x)), yn(size(x)), xo(size(x)), best, worst, e, &
         & target, frac
      integer :: n, pass, k, j
      n = size(x)
      best = huge(1.0_dp)
      xn = x
      yn = y
      do pass = 1, 8
         w(0) = 0.0_dp
         worst = 0.0_dp
         do k = 1, n - 1
            e = midpoint_error(g, xn(k), xn(k + 1), yn(k), yn(k + 1), floor)
            worst = max(worst, e)
            w(k) = w(k - 1) + sqrt(e)
         end do
         if (worst < best) then
            best = worst
            x = xn
            y = yn
         end if
         if (pass == 8 .or. .not. w(n - 1) > 0.0_dp) exit
         ! new points from the current set (the weights belong to it)
         xo = xn
         j = 1
         do k = 2, n - 1
            target = w(n - 1)*(k - 1)/(n - 1)
            do while (w(j) < target .and. j < n - 1)
               j = j + 1
            end do
            frac = 0.5_dp
            if (w(j) > w(j - 1)) frac = (target - w(j - 1))/(w(j) - w(j - 1))
            xn(k) = xo(j) + frac*(xo(j + 1) - xo(j))
         end do
         do k = 2, n - 1
            xn(k) = max(xn(k), xn(k - 1) + 1.0e-9_dp*(x(n) - x(1)))
         end do
         do k = 1, n
            yn(k) = sample(g, xn(k))
         end do
      end do
   end subroutine equalise_errors

   !> |linear interpolant - g| at the midpoint of [xl, xr], relative to max(|g|, floor).
   real(dp) function midpoint_error(g, xl, xr, yl, yr, floor) result(e)
      type(sampler), intent(inout) :: g
      real(dp), intent(in) :: xl, xr, yl, yr, floor
      real(dp) :: ym
      ym = sample(g, 0.5_dp*(xl + xr))
      e = abs(0.5_dp*(yl + yr) - ym)/max(abs(ym), floor, tiny(1.0_dp))
   end function midpoint_error

   !> Points on [a, b] such that linear interpolation of g has midpoint error
   !> <= rel_tol * |g(mid)| (bisection; at most max_export_points points).
   subroutine resample_linear(g, a, b, rel_tol, x, y)
      type(sampler), intent(inout) :: g
      real(dp), intent(in) :: a, b, rel_tol
      real(dp), allocatable, intent(out) :: x(:), y(:)
      real(dp), allocatable :: sx(:), sy(:)
      integer :: n, top
      real(dp) :: xl, yl, xr, yr, xm, ym
      ! depth-first bisection with an explicit stack of right ends
      allocate (x(1024), y(1024), sx(200), sy(200))
      n = 1
      x(1) = a
      y(1) = sample(g, a)
      top = 1
      sx(1) = b
      sy(1) = sample(g, b)
      do while (top > 0)
         xl = x(n); yl = y(n)
         xr = sx(top); yr = sy(top)
         xm = 0.5_dp*(xl + xr)
         ym = sample(g, xm)
         if (.not. ieee_is_finite(ym)) then
            if (g%stat == egw_ok) g%stat = egw_invalid_argument
            exit
         end if
         if (abs(0.5_dp*(yl + yr) - ym) > rel_tol*abs(ym) .and. top < size(sx) .and. &
            & n < max_export_points .and. xm > xl .and. xm < xr) then
            top = top + 1
            sx(top) = xm
            sy(top) = ym
         else
            if (n == size(x)) then
               x = [x, x]
               y = [y, y]
            end if
            n = n + 1
            x(n) = xr
            y(n) = yr
            top = top - 1
         end if
      end do
      x = x(1:n)
      y = y(1:n)
   end subroutine resample_linear

   !> Value of the sampled curve at x (records a failure of flat_pressure in g%stat).
   real(dp) function sample(g, x)
      type(sampler), intent(inout) :: g
      real(dp), intent(in) :: x
      real(dp) :: k
      type(egw_error), allocatable :: e
      if (g%flat) then
         call flat_pressure(g%params, -x, sample, k, e)
         if (allocated(e) .and. g%stat == egw_ok) g%stat = e%stat
      else
         call table_eval(g%table, x, sample, k)
      end if
   end function sample

   ! =========================================================== checks and helpers

   !> Everything a reader must verify before handing over a table: finite numbers;
   !> metadata in range; nodes strictly increasing from the cut-off; force, stiffness,
   !> energy and contact radius >= 0; force and energy non-decreasing in the overlap
   !> (the loading curve of every model rises: a dip is a corrupted or edited file).
   subroutine check_table(path, where, t, error)
      character(len=*), intent(in) :: path, where
      type(force_table), intent(in) :: t
      type(egw_error), allocatable, intent(out) :: error
      integer :: n, i
      n = size(t%delta)
      if (n < 2) then
         call bad(error, path, where//"fewer than 2 nodes")
         return
      end if
      call check_meta(path, where, t, error)
      if (allocated(error)) return
      do i = 1, n
         if (.not. row_ok([t%delta(i), t%force(i), t%stiffness(i), t%energy(i), &
            & t%contact_radius(i)])) then
            call bad(error, path, where//"node "//int_str(i)//" is not finite")
            return
         end if
         if (t%force(i) < 0.0_dp) then
            call bad(error, path, where//"node "//int_str(i)//": negative force "// &
               & format_real(t%force(i)))
            return
         end if
         if (t%stiffness(i) < 0.0_dp) then
            call bad(error, path, where//"node "//int_str(i)//": negative stiffness "// &
               & format_real(t%stiffness(i)))
            return
         end if
         if (t%energy(i) < 0.0_dp) then
            call bad(error, path, where//"node "//int_str(i)//": negative energy "// &
               & format_real(t%energy(i)))
            return
         end if
         if (t%contact_radius(i) < 0.0_dp) then
            call bad(error, path, where//"node "//int_str(i)//": negative contact "// &
               & "radius "//format_real(t%contact_radius(i)))
            return
         end if
         if (i == 1) cycle
         if (t%force(i) < t%force(i - 1)) then
            call bad(error, path, where//"node "//int_str(i)//": force "// &
               & format_real(t%force(i))//" below the previous node's "// &
               & format_real(t%force(i - 1))//" (the force must not decrease)")
            return
         end if
         if (t%energy(i) < t%energy(i - 1)) then
            call bad(error, path, where//"node "//int_str(i)//": energy decreases")
            return
         end if
      end do
      if (any(t%delta(2:n) <= t%delta(1:n - 1))) then
         call bad(error, path, where//"delta is not strictly increasing")
         return
      end if
      if (t%n_log < 0 .or. t%n_log > n - 1) then
         call bad(error, path, where//"n_log = "//int_str(t%n_log)//" out of range")
         return
      end if
      if (t%n_log > 0) then
         if (any(t%force(1:t%n_log + 1) <= 0.0_dp)) then
            call bad(error, path, where//"log-space interval with a zero force")
            return
         end if
      end if
      if (t%cutoff /= t%delta(1) .or. t%delta_max /= t%delta(n)) then
         call bad(error, path, where//"cutoff/delta_max disagree with the nodes")
         return
      end if
   end subroutine check_table

   !> The metadata of a table: finite, rel_tol in (0, 0.1], P_ref > 0, errors and
   !> R1 + R2 >= 0.
   subroutine check_meta(path, where, t, error)
      character(len=*), intent(in) :: path, where
      type(force_table), intent(in) :: t
      type(egw_error), allocatable, intent(out) :: error
      if (.not. (t%rel_tol > 0.0_dp .and. t%rel_tol <= 0.1_dp)) then
         call bad(error, path, where//"rel_tol = "//format_real(t%rel_tol)// &
            & ": must lie in (0, 0.1]")
      else if (.not. (ieee_is_finite(t%reference_force) .and. t%reference_force > 0)) then
         call bad(error, path, where//"reference_force = "// &
            & format_real(t%reference_force)//": must be finite and > 0")
      else if (.not. (ieee_is_finite(t%max_force_error) .and. t%max_force_error >= 0 &
         & .and. ieee_is_finite(t%max_stiffness_error) .and. t%max_stiffness_error >= 0)) &
         & then
         call bad(error, path, where//"max_force_error = "// &
            & format_real(t%max_force_error)//", max_stiffness_error = "// &
            & format_real(t%max_stiffness_error)//": must be finite and >= 0")
      else if (.not. (ieee_is_finite(t%radius_sum) .and. t%radius_sum >= 0)) then
         call bad(error, path, where//"radius_sum = "//format_real(t%radius_sum)// &
            & ": must be finite and >= 0 (0: not set)")
      end if
   end subroutine check_meta

   subroutine check_universal_header(path, u, error)
      character(len=*), intent(in) :: path
      type(universal_table), intent(in) :: u
      type(egw_error), allocatable, intent(out) :: error
      if (u%n_mu < 4 .or. u%n_mu > 100000) then
         call bad(error, path, "n_mu = "//int_str(u%n_mu)//": need at least 4")
      else if (.not. (u%rel_tol > 0.0_dp .and. u%rel_tol <= 0.1_dp)) then
         call bad(error, path, "rel_tol = "//format_real(u%rel_tol)//": must lie in (0, 0.1]")
      else if (.not. (ieee_is_finite(u%max_mu_error) .and. u%max_mu_error >= 0)) then
         call bad(error, path, "max_mu_error = "//format_real(u%max_mu_error)// &
            & ": must be finite and >= 0")
      else if (.not. (ieee_is_finite(u%x_cut) .and. ieee_is_finite(u%x_max) .and. &
         & u%x_cut < u%x_max)) then
         call bad(error, path, "x_cut = "//format_real(u%x_cut)//", x_max = "// &
            & format_real(u%x_max)//": need finite x_cut < x_max")
      else if (.not. (ieee_is_finite(u%mu_min) .and. u%mu_min > 0.0_dp .and. &
         & ieee_is_finite(u%mu_max) .and. u%mu_max > u%mu_min)) then
         call bad(error, path, "mu range ["//format_real(u%mu_min)//", "// &
            & format_real(u%mu_max)//"] invalid")
      else
         call validate_params(universal_slice_params(u%model, u%psi, u%hardness_coeff, &
            & u%plastic_ratio, u%mu_min), error)
         if (allocated(error)) call bad(error, path, "stored parameters invalid: "// &
            & error%message)
      end if
   end subroutine check_universal_header

   subroutine check_common_cutoff(path, u, error)
      character(len=*), intent(in) :: path
      type(universal_table), intent(in) :: u
      type(egw_error), allocatable, intent(out) :: error
      integer :: j
      do j = 1, u%n_mu
         if (u%slices(j)%cutoff /= u%x_cut .or. u%slices(j)%delta_max /= u%x_max) then
            call bad(error, path, "slice "//int_str(j)//": range differs from x_cut, x_max")
            return
         end if
      end do
   end subroutine check_common_cutoff

   pure real(dp) function slice_mu(u, j)
      type(universal_table), intent(in) :: u
      integer, intent(in) :: j
      if (j == 1) then
         slice_mu = u%mu_min
      else if (j == u%n_mu) then
         slice_mu = u%mu_max
      else
         slice_mu = exp(log(u%mu_min) + (log(u%mu_max) - log(u%mu_min))*(j - 1)/(u%n_mu - 1))
      end if
   end function slice_mu

   subroutine set_nodes(t, rows)
      type(force_table), intent(inout) :: t
      real(dp), intent(in) :: rows(:, :)
      t%delta = rows(1, :)
      t%force = rows(2, :)
      t%stiffness = rows(3, :)
      t%energy = rows(4, :)
      t%contact_radius = rows(5, :)
   end subroutine set_nodes

   pure subroutine set_meta(t, meta)
      type(force_table), intent(inout) :: t
      real(dp), intent(in) :: meta(7)
      t%rel_tol = meta(1)
      t%cutoff = meta(2)
      t%delta_max = meta(3)
      t%reference_force = meta(4)
      t%max_force_error = meta(5)
      t%max_stiffness_error = meta(6)
      t%radius_sum = meta(7)
   end subroutine set_meta

   subroutine get_params(path, dict, p, error)
      character(len=*), intent(in) :: path
      type(header_dict), intent(in) :: dict
      type(contact_params), intent(out) :: p
      type(egw_error), allocatable, intent(out) :: error
      call get_int(path, dict, "model", p%model, error)
      if (.not. allocated(error)) call get_real(path, dict, "radius", p%radius, error)
      if (.not. allocated(error)) call get_real(path, dict, "modulus", p%modulus, error)
      if (.not. allocated(error)) call get_real(path, dict, "sigma", p%sigma, error)
      if (.not. allocated(error)) call get_real(path, dict, "mu", p%mu, error)
      if (.not. allocated(error)) call get_real(path, dict, "psi", p%psi, error)
      if (.not. allocated(error)) call get_real(path, dict, "hardness_coeff", &
         & p%hardness_coeff, error)
      if (.not. allocated(error)) call get_real(path, dict, "plastic_ratio", &
         & p%plastic_ratio, error)
      if (allocated(error)) return
      call validate_params(p, error)
      if (allocated(error)) call bad(error, path, "stored parameters invalid: "//error%message)
   end subroutine get_params

   subroutine get_table_meta(path, dict, prefix, t, n, error)
      character(len=*), intent(in) :: path, prefix
      type(header_dict), intent(in) :: dict
      type(force_table), intent(inout) :: t
      integer, intent(out) :: n
      type(egw_error), allocatable, intent(out) :: error
      call get_real(path, dict, prefix//"rel_tol", t%rel_tol, error)
      if (.not. allocated(error)) call get_real(path, dict, prefix//"cutoff", t%cutoff, error)
      if (.not. allocated(error)) call get_real(path, dict, prefix//"delta_max", &
         & t%delta_max, error)
      if (.not. allocated(error)) call get_real(path, dict, prefix//"reference_force", &
         & t%reference_force, error)
      if (.not. allocated(error)) call get_real(path, dict, prefix//"max_force_error", &
         & t%max_force_error, error)
      if (.not. allocated(error)) call get_real(path, dict, prefix//"max_stiffness_error", &
         & t%max_stiffness_error, error)
      if (.not. allocated(error)) call get_real(path, dict, prefix//"radius_sum", &
         & t%radius_sum, error)
      if (.not. allocated(error)) call get_int(path, dict, prefix//"n_nodes", n, error)
      if (.not. allocated(error)) call get_int(path, dict, prefix//"n_log", t%n_log, error)
   end subroutine get_table_meta

   subroutine get_real(path, dict, key, x, error)
      character(len=*), intent(in) :: path, key
      type(header_dict), intent(in) :: dict
      real(dp), intent(out) :: x
      type(egw_error), allocatable, intent(out) :: error
      integer :: i
      logical :: ok
      i = dict_find(dict, key)
      x = 0.0_dp
      if (i == 0) then
         call bad(error, path, "header key '"//key//"' missing")
         return
      end if
      call parse_real(first_token(dict%values(i)), x, ok)
      if (.not. ok .or. .not. ieee_is_finite(x)) then
         call bad(error, path, "header key '"//key//"' = '"//trim(dict%values(i))// &
            & "' is not a finite number")
      end if
   end subroutine get_real

   subroutine get_int(path, dict, key, k, error)
      character(len=*), intent(in) :: path, key
      type(header_dict), intent(in) :: dict
      integer, intent(out) :: k
      type(egw_error), allocatable, intent(out) :: error
      integer :: i
      logical :: ok
      i = dict_find(dict, key)
      k = 0
      if (i == 0) then
         call bad(error, path, "header key '"//key//"' missing")
         return
      end if
      call parse_int(first_token(dict%values(i)), k, ok)
      if (.not. ok) call bad(error, path, "header key '"//key//"' = '"// &
         & trim(dict%values(i))//"' is not an integer")
   end subroutine get_int

   pure integer function dict_find(dict, key) result(i)
      type(header_dict), intent(in) :: dict
      character(len=*), intent(in) :: key
      do i = 1, dict%n
         if (trim(dict%keys(i)) == key) return
      end do
      i = 0
   end function dict_find

   pure subroutine dict_add(dict, key, value)
      type(header_dict), intent(inout) :: dict
      character(len=*), intent(in) :: key, value
      character(len=64), allocatable :: k2(:)
      character(len=256), allocatable :: v2(:)
      if (dict%n == size(dict%keys)) then
         allocate (k2(2*dict%n), v2(2*dict%n))
         k2(1:dict%n) = dict%keys
         v2(1:dict%n) = dict%values
         call move_alloc(k2, dict%keys)
         call move_alloc(v2, dict%values)
      end if
      dict%n = dict%n + 1
      dict%keys(dict%n) = key
      dict%values(dict%n) = value
   end subroutine dict_add

   pure subroutine grow(rows, idx, cap)
      real(dp), allocatable, intent(inout) :: rows(:, :)
      integer, allocatable, intent(inout) :: idx(:)
      integer, intent(in) :: cap
      real(dp), allocatable :: r2(:, :)
      integer, allocatable :: i2(:)
      allocate (r2(size(rows, 1), cap), i2(cap))
      r2(:, 1:size(rows, 2)) = rows
      i2(1:size(idx)) = idx
      call move_alloc(r2, rows)
      call move_alloc(i2, idx)
   end subroutine grow

   subroutine move_table(from, to)
      type(force_table), intent(inout) :: from
      type(force_table), intent(out) :: to
      to%params = from%params
      to%rel_tol = from%rel_tol
      to%cutoff = from%cutoff
      to%delta_max = from%delta_max
      to%reference_force = from%reference_force
      to%max_force_error = from%max_force_error
      to%max_stiffness_error = from%max_stiffness_error
      to%radius_sum = from%radius_sum
      to%n_log = from%n_log
      to%checksum_missing = from%checksum_missing
      to%n_bucket = from%n_bucket
      to%bucket_scale = from%bucket_scale
      to%bucket_origin = from%bucket_origin
      to%crowded = from%crowded
      call move_alloc(from%delta, to%delta)
      call move_alloc(from%force, to%force)
      call move_alloc(from%stiffness, to%stiffness)
      call move_alloc(from%energy, to%energy)
      call move_alloc(from%contact_radius, to%contact_radius)
      call move_alloc(from%seg, to%seg)
      call move_alloc(from%radius_slope, to%radius_slope)
      call move_alloc(from%bucket, to%bucket)
   end subroutine move_table

   pure subroutine put_i32(buf, pos, v)
      character(len=*), intent(inout) :: buf
      integer, intent(inout) :: pos
      integer(int32), intent(in) :: v
      buf(pos:pos + 3) = transfer(v, buf(pos:pos + 3))
      pos = pos + 4
   end subroutine put_i32

   pure subroutine put_f64(buf, pos, v)
      character(len=*), intent(inout) :: buf
      integer, intent(inout) :: pos
      real(dp), intent(in) :: v(:)
      integer :: nb
      nb = 8*size(v)
      if (nb == 0) return
      buf(pos:pos + nb - 1) = transfer(v, buf(pos:pos + nb - 1))
      pos = pos + nb
   end subroutine put_f64

   integer(int32) function get_i32(buf, pos) result(v)
      character(len=*), intent(in) :: buf
      integer, intent(inout) :: pos
      v = transfer(buf(pos:pos + 3), v)
      pos = pos + 4
   end function get_i32

   pure subroutine get_f64(buf, pos, v)
      character(len=*), intent(in) :: buf
      integer, intent(inout) :: pos
      real(dp), intent(out) :: v(:)
      integer :: nb
      nb = 8*size(v)
      if (nb == 0) return
      v = transfer(buf(pos:pos + nb - 1), v, size(v))
      pos = pos + nb
   end subroutine get_f64

   subroutine kv(out, key, x)
      type(text_buffer), intent(inout) :: out
      character(len=*), intent(in) :: key
      real(dp), intent(in) :: x
      call out%add("# "//key//" = "//fmt(x))
   end subroutine kv

   pure logical function row_ok(v)
      real(dp), intent(in) :: v(:)
      row_ok = all(ieee_is_finite(v))
   end function row_ok

   !> 17 significant digits: every double reads back bit-for-bit.
   pure function fmt(x) result(str)
      real(dp), intent(in) :: x
      character(len=real_text_len(x, 17, 3)) :: str  ! not deferred: see egw_text
      str = real_text(x, 17, 3)  ! ES25.17E3
   end function fmt

   !> 20 characters at most (CalculiX fields), 13 significant digits.
   pure function fmt20(x) result(str)
      real(dp), intent(in) :: x
      character(len=real_text_len(x, 12, 3)) :: str
      str = real_text(x, 12, 3)  ! ES20.12E3
   end function fmt20

   pure integer function csv_row_len(v) result(n)
      real(dp), intent(in) :: v(:)
      integer :: i
      n = size(v) - 1
      do i = 1, size(v)
         n = n + real_text_len(v(i), 17, 3)
      end do
   end function csv_row_len

   pure function csv_row(v) result(str)
      real(dp), intent(in) :: v(:)
      character(len=csv_row_len(v)) :: str  ! not deferred: see egw_text
      integer :: i, pos, n
      pos = 0
      do i = 1, size(v)
         if (i > 1) then
            str(pos + 1:pos + 1) = ","
            pos = pos + 1
         end if
         n = real_text_len(v(i), 17, 3)
         str(pos + 1:pos + n) = real_text(v(i), 17, 3)
         pos = pos + n
      end do
   end function csv_row

   pure integer function first_token_len(text) result(n)
      character(len=*), intent(in) :: text
      n = index(trim(adjustl(text))//" ", " ") - 1
   end function first_token_len

   !> The text up to the first blank (after leading blanks).
   pure function first_token(text) result(token)
      character(len=*), intent(in) :: text
      character(len=first_token_len(text)) :: token  ! not deferred: see egw_text
      token = adjustl(text)
   end function first_token

   !> A data row: an integer index (if indexed) and size(vals) reals, separated by
   !> commas; blanks around fields allowed, nothing else.
   pure subroutine split_row(line, indexed, j, vals, ok)
      character(len=*), intent(in) :: line
      logical, intent(in) :: indexed
      integer, intent(out) :: j
      real(dp), intent(out) :: vals(:)
      logical, intent(out) :: ok
      integer :: start, comma, k, nfield
      j = 0
      vals = 0.0_dp
      nfield = size(vals)
      if (indexed) nfield = nfield + 1
      start = 1
      do k = 1, nfield
         comma = index(line(start:), ",")
         if (k < nfield) then
            ok = comma > 0
            if (.not. ok) return
            comma = start + comma - 1
         else
            ok = comma == 0
            if (.not. ok) return
            comma = len(line) + 1
         end if
         if (indexed .and. k == 1) then
            call parse_int(line(start:comma - 1), j, ok)
         else
            call parse_real(line(start:comma - 1), vals(k - merge(1, 0, indexed)), ok)
         end if
         if (.not. ok) return
         start = comma + 1
      end do
   end subroutine split_row

   pure logical function starts_with(str, prefix)
      character(len=*), intent(in) :: str, prefix
      starts_with = .false.
      if (len(str) >= len(prefix)) starts_with = str(1:len(prefix)) == prefix
   end function starts_with

end module egw_table_format
