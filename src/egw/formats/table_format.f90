!> Writers and readers of force tables (doc/formats.md): egw CSV with a metadata header,
!> the versioned egw binary format with an FNV-1a checksum, LAMMPS `pair_style table`,
!> and CalculiX/Abaqus `*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR`.
!> Every write goes to a temporary file renamed over the target (egw_io), so a failed
!> write leaves an existing file untouched. Readers build into locals and hand over a
!> table only when the whole file has been checked: a bad file gives egw_bad_file and
!> no table. This module holds the interface and the dispatch; each format is a
!> submodule (table_format_csv.f90, table_format_binary.f90, table_format_lammps.f90,
!> table_format_calculix.f90), the checks they share another (table_format_checks.f90).
module egw_table_format
   use, intrinsic :: iso_fortran_env, only: int32, int64
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_ok, egw_bad_file, egw_io_error, egw_invalid_argument, &
      & egw_invalid_parameter, &
      & egw_unsupported, fatal_error, format_real, int_str, bad => bad_file_error
   use egw_params, only: contact_params, validate_params, model_name, model_epgw, model_hertz
   use egw_version, only: egw_version_string, egw_version_number
   use egw_io, only: write_file, read_file, text_buffer
   use egw_asperity, only: flat_pressure
   use egw_table, only: force_table, table_prepare, table_eval, table_energy, table_meta, &
      & set_table_meta
   use egw_table_universal, only: universal_table, universal_slice_params, &
      & universal_nodes_shared, move_universal
   use egw_text, only: real_text, real_text_len, parse_real, parse_int, csv_row
   implicit none
   private

   public :: split_checksum, checksum_line
   public :: write_table, read_table, write_universal, read_universal, write_lammps, &
      & write_calculix_flat, write_calculix_sphere, fnv1a32, checksum_i32, &
      & put_f64, get_f64, put_nodes, get_nodes, check_table

   integer, parameter, public :: format_csv = 0       !< egw CSV with metadata header
   integer, parameter, public :: format_binary = 1    !< egw binary, versioned, checksummed
   integer, parameter, public :: format_lammps = 2    !< LAMMPS pair_style table
   integer, parameter, public :: format_calculix = 3  !< CalculiX/Abaqus tabular overclosure

   !> Binary format version written and the only one read.
   integer(int32), parameter, public :: binary_version = 1
   character(len=8), parameter :: magic_table = "EGWTAB1D", magic_universal = "EGWTABUN"
   !> Most points a LAMMPS or CalculiX file gets (resampling is adaptive below this).
   integer, parameter :: max_export_points = 200000
   !> Column headers of the CSV tables (the first line from CSV format 2 on).
   character(len=*), parameter :: csv_columns_table = &
      & "delta,force,stiffness,energy,contact_radius"
   character(len=*), parameter :: csv_columns_universal = &
      & "mu_index,x,p,dp_dx,energy,contact_radius"
   ! numbers are written as ES25.17E3 (17 decimals: every double reads back bit for bit)
   !> CalculiX 2.20 keeps at most 200 pairs of a tabular curve (silently wrong beyond).
   integer, parameter, public :: calculix_max_pairs = 200

   ! Each format in a submodule: table_format_csv.f90, table_format_binary.f90,
   ! table_format_lammps.f90, table_format_calculix.f90; the checks they share in
   ! table_format_checks.f90.
   interface
      !> (table_format_csv.f90) egw CSV of a 1-D table, checksummed (CSV format 3).
      module subroutine write_table_csv(table, path, error)
         type(force_table), intent(in) :: table
         character(len=*), intent(in) :: path
         type(egw_error), allocatable, intent(out) :: error
      end subroutine write_table_csv

      !> (table_format_csv.f90) egw CSV of a universal table, checksummed.
      module subroutine write_universal_csv(table, path, error)
         type(universal_table), intent(in) :: table
         character(len=*), intent(in) :: path
         type(egw_error), allocatable, intent(out) :: error
      end subroutine write_universal_csv

      !> (table_format_csv.f90) A 1-D table from the text of a CSV file, checked.
      module subroutine parse_table_csv(path, text, table, error)
         character(len=*), intent(in) :: path, text
         type(force_table), intent(out) :: table
         type(egw_error), allocatable, intent(out) :: error
      end subroutine parse_table_csv

      !> (table_format_csv.f90) A universal table from the text of a CSV file, checked.
      module subroutine parse_universal_csv(path, text, table, error)
         character(len=*), intent(in) :: path, text
         type(universal_table), intent(out) :: table
         type(egw_error), allocatable, intent(out) :: error
      end subroutine parse_universal_csv

      !> (table_format_binary.f90) egw binary file of a 1-D table.
      module subroutine write_table_binary(table, path, error)
         type(force_table), intent(in) :: table
         character(len=*), intent(in) :: path
         type(egw_error), allocatable, intent(out) :: error
      end subroutine write_table_binary

      !> (table_format_binary.f90) egw binary file of a universal table.
      module subroutine write_universal_binary(table, path, error)
         type(universal_table), intent(in) :: table
         character(len=*), intent(in) :: path
         type(egw_error), allocatable, intent(out) :: error
      end subroutine write_universal_binary

      !> (table_format_binary.f90) A 1-D table from the bytes of a binary file, checked.
      module subroutine parse_table_binary(path, bytes, table, error)
         character(len=*), intent(in) :: path, bytes
         type(force_table), intent(out) :: table
         type(egw_error), allocatable, intent(out) :: error
      end subroutine parse_table_binary

      !> (table_format_binary.f90) A universal table from the bytes of a binary file.
      module subroutine parse_universal_binary(path, bytes, table, error)
         character(len=*), intent(in) :: path, bytes
         type(universal_table), intent(out) :: table
         type(egw_error), allocatable, intent(out) :: error
      end subroutine parse_universal_binary

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
      module subroutine write_lammps(tables, path, error, units, delta_reach)
         type(force_table), intent(in) :: tables(:)   !< one per type pair: sections EGW_1, ...
         character(len=*), intent(in) :: path   !< file to write (replaced atomically)
         !> allocated on failure (nothing replaced)
         type(egw_error), allocatable, intent(out) :: error
         !> optional LAMMPS units style of the numbers ("si", "metal", ...), for the header
         character(len=*), intent(in), optional :: units
         !> deepest overlap the sections reach (>= each table's delta_max; beyond delta_max
         !> the force continues linearly with the end stiffness, as table_eval does); LAMMPS
         !> stops with "Pair distance < table inner cutoff" at deeper overlaps
         real(dp), intent(in), optional :: delta_reach
      end subroutine write_lammps

      !> Node-to-surface sphere contact: force per node against overclosure = overlap delta,
      !> first pair (0, delta_c); at most calculix_max_pairs pairs placed so that the linear
      !> interpolation CalculiX applies reproduces the table (see fit_pairs). With shift,
      !> overclosure is measured from the cut-off, delta - delta_c (first pair (0, 0)):
      !> CalculiX makes node-to-surface contact springs only where the surfaces touch or
      !> penetrate, so a curve starting at negative overclosure is never reached there; the
      !> model's surfaces then stand for the spheres at overlap delta_c when they touch.
      !> max_error: the achieved error (as in the file's header).
      module subroutine write_calculix_sphere(t, path, error, shift, max_error)
         type(force_table), intent(in), target :: t   !< a sphere's force table
         character(len=*), intent(in) :: path   !< file to write (replaced atomically)
         !> allocated on failure (nothing replaced)
         type(egw_error), allocatable, intent(out) :: error
         logical, intent(in), optional :: shift   !< optional: overclosure from the cut-off delta_c
         real(dp), intent(out), optional :: max_error   !< optional: the error achieved
      end subroutine write_calculix_sphere

      !> Rough flat: nominal pressure p_G(d) (egw_asperity) against overclosure = -d, from
      !> the separation d_c where p_G has fallen to rel_tol * p_G(0) (first pair at zero
      !> pressure) to overclosure_max; at most calculix_max_pairs pairs (fit_pairs). With
      !> shift, overclosure is measured from d_c: overclosure = d_c - d (first pair (0, 0);
      !> the model's surfaces are the summit base planes at separation d_c, see
      !> write_calculix_sphere for why CalculiX needs this). max_error: the achieved error.
      module subroutine write_calculix_flat(params, overclosure_max, rel_tol, path, error, &
         & shift, max_error)
         !> the rough flat's parameters (sigma > 0; flow_pressure 0: a reversible curve
         !> cannot hold the cap, egw_invalid_parameter naming it)
         type(contact_params), intent(in) :: params
         real(dp), intent(in) :: overclosure_max   !< largest overclosure tabulated [length]
         real(dp), intent(in) :: rel_tol   !< tolerance of the piecewise-linear curve
         character(len=*), intent(in) :: path   !< file to write (replaced atomically)
         !> allocated on failure (nothing replaced)
         type(egw_error), allocatable, intent(out) :: error
         !> optional: overclosure from the first-contact separation
         logical, intent(in), optional :: shift
         real(dp), intent(out), optional :: max_error   !< optional: the error achieved
      end subroutine write_calculix_flat

      ! (table_format_checks.f90) shared by the readers and writers
      !> Everything a reader must verify before handing over a table: finite numbers;
      !> metadata in range; nodes strictly increasing from the cut-off; force, stiffness,
      !> energy and contact radius >= 0; force and energy non-decreasing in the overlap
      !> (the loading curve of every model rises: a dip is a corrupted or edited file).
      module subroutine check_table(path, where, t, error)
         !> the file, and the format's name, for the messages
         character(len=*), intent(in) :: path, where
         type(force_table), intent(in) :: t   !< the table as read
         !> egw_bad_file naming path and the first fault
         type(egw_error), allocatable, intent(out) :: error
      end subroutine check_table

      module subroutine check_universal_header(path, u, error)
         character(len=*), intent(in) :: path
         type(universal_table), intent(in) :: u
         type(egw_error), allocatable, intent(out) :: error
      end subroutine check_universal_header

      !> Every slice of u spans [x_cut, x_max] on the same nodes and ln P intervals.
      module subroutine check_universal_slices(path, u, error)
         character(len=*), intent(in) :: path
         type(universal_table), intent(in) :: u
         type(egw_error), allocatable, intent(out) :: error
      end subroutine check_universal_slices

      !> mu of slice j of a universal table (geometric in mu; the ends exact).
      pure module real(dp) function slice_mu(u, j)
         type(universal_table), intent(in) :: u
         integer, intent(in) :: j
      end function slice_mu

      module subroutine move_table(from, to)
         type(force_table), intent(inout) :: from
         type(force_table), intent(out) :: to
      end subroutine move_table

      pure module logical function row_ok(v)
         real(dp), intent(in) :: v(:)
      end function row_ok

      !> 17 significant digits: every double reads back bit-for-bit.
      pure module function fmt(x) result(str)
         real(dp), intent(in) :: x
         character(len=real_text_len(x, 17, 3)) :: str  ! not deferred: see egw_text
      end function fmt

      pure module logical function starts_with(str, prefix)
         character(len=*), intent(in) :: str, prefix
      end function starts_with
   end interface

contains

   ! =========================================================== dispatch

   !> Write a table in one of the formats (format_csv, format_binary, format_lammps,
   !> format_calculix).
   subroutine write_table(table, path, format, error)
      type(force_table), intent(in) :: table   !< built or read
      character(len=*), intent(in) :: path   !< file to write (replaced atomically)
      integer, intent(in) :: format   !< format_csv or format_binary
      !> allocated on failure (nothing replaced)
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
      character(len=*), intent(in) :: path   !< a file of write_table (CSV or binary)
      type(force_table), intent(out) :: table   !< the table; empty on error
      !> allocated on failure (egw_bad_file says what is wrong)
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
      type(universal_table), intent(in) :: table   !< built or read
      character(len=*), intent(in) :: path   !< file to write (replaced atomically)
      integer, intent(in) :: format   !< format_csv or format_binary
      !> allocated on failure (nothing replaced)
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
      character(len=*), intent(in) :: path   !< a file of write_universal
      type(universal_table), intent(out) :: table   !< the table; empty on error
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
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

   !> The checksum line of a CSV file: body = the bytes before it (all of text if
   !> there is none, then missing = true); a checksum that does not match is an error.
   subroutine split_checksum(path, text, body, missing, error)
      character(len=*), intent(in) :: path, text   !< the file (messages), and its whole text
      integer, intent(out) :: body   !< bytes of text before the checksum line
      logical, intent(out) :: missing   !< true: no checksum line
      !> egw_bad_file naming path: a checksum that does not match
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

   !> The CSV checksum line of the bytes above it.
   pure function checksum_line(above) result(line)
      character(len=*), intent(in) :: above   !< the file's bytes before the line
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

   !> FNV-1a 32-bit hash of a byte string (offset basis 2166136261, prime 16777619),
   !> returned in the low 32 bits of an int64. Products stay below 2^57: no overflow.
   pure function fnv1a32(bytes) result(h)
      character(len=*), intent(in) :: bytes   !< any bytes
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
      integer(int64), intent(in) :: h   !< a checksum in 0 .. 2^32 - 1
      if (h >= 2147483648_int64) then
         checksum_i32 = int(h - 4294967296_int64, int32)
      else
         checksum_i32 = int(h, int32)
      end if
   end function checksum_i32

   !> Append the doubles v to the binary buffer buf at pos (native byte order; the
   !> formats' byte-order mark says which), advancing pos.
   pure subroutine put_f64(buf, pos, v)
      character(len=*), intent(inout) :: buf   !< the buffer, long enough
      integer, intent(inout) :: pos   !< the next byte to write (1-based)
      real(dp), intent(in) :: v(:)   !< the doubles to append
      integer :: nb
      nb = 8*size(v)
      if (nb == 0) return
      buf(pos:pos + nb - 1) = transfer(v, buf(pos:pos + nb - 1))
      pos = pos + nb
   end subroutine put_f64

   !> Read size(v) doubles from buf at pos, advancing pos.
   pure subroutine get_f64(buf, pos, v)
      character(len=*), intent(in) :: buf   !< the file's bytes
      integer, intent(inout) :: pos   !< the next byte to read (1-based)
      real(dp), intent(out) :: v(:)   !< the doubles read
      integer :: nb
      nb = 8*size(v)
      if (nb == 0) return
      v = transfer(buf(pos:pos + nb - 1), v, size(v))
      pos = pos + nb
   end subroutine get_f64

   !> Append a force table's nodes to the binary buffer buf at pos, advancing pos: the
   !> arrays delta, force, stiffness, energy, contact_radius, one after the other
   !> (doc/formats.md; the 1-D, universal and hysteresis binaries share this layout).
   pure subroutine put_nodes(buf, pos, t)
      character(len=*), intent(inout) :: buf   !< the buffer, long enough
      integer, intent(inout) :: pos   !< the next byte to write (1-based)
      type(force_table), intent(in) :: t   !< the table whose nodes are written
      call put_f64(buf, pos, t%delta)
      call put_f64(buf, pos, t%force)
      call put_f64(buf, pos, t%stiffness)
      call put_f64(buf, pos, t%energy)
      call put_f64(buf, pos, t%contact_radius)
   end subroutine put_nodes

   !> Allocate a force table's n nodes and read them from buf at pos in put_nodes'
   !> layout, advancing pos (the caller has checked that buf holds them).
   pure subroutine get_nodes(buf, pos, n, t)
      character(len=*), intent(in) :: buf   !< the file's bytes
      integer, intent(inout) :: pos   !< the next byte to read (1-based)
      integer, intent(in) :: n   !< nodes to read
      type(force_table), intent(inout) :: t   !< gets delta ... contact_radius(n)
      allocate (t%delta(n), t%force(n), t%stiffness(n), t%energy(n), t%contact_radius(n))
      call get_f64(buf, pos, t%delta)
      call get_f64(buf, pos, t%force)
      call get_f64(buf, pos, t%stiffness)
      call get_f64(buf, pos, t%energy)
      call get_f64(buf, pos, t%contact_radius)
   end subroutine get_nodes

end module egw_table_format
