!> Writers and readers of hysteresis tables (doc/formats.md §6): egw CSV (the unloading
!> data as rows, the loading curve and metadata as '#' lines, a checksum line last) and the
!> versioned egw binary format (FNV-1a checksum). Writes are atomic (egw_io); a reader
!> checks the whole file, and what a table must satisfy (egw_hysteresis_checks), before
!> it hands one over.
module egw_hysteresis_format
   use, intrinsic :: iso_fortran_env, only: int32, int64
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_bad_file, egw_io_error, egw_invalid_argument, &
      & fatal_error, int_str, format_real, bad => bad_file_error
   use egw_params, only: contact_params, model_name
   use egw_version, only: egw_version_string, egw_version_number
   use egw_io, only: write_file, read_file, text_buffer
   use egw_text, only: real_text, real_text_len, csv_row
   use egw_table, only: force_table, table_prepare, table_meta, set_table_meta
   use egw_table_format, only: format_csv, format_binary, fnv1a32, checksum_i32, put_f64, &
      & get_f64, put_nodes, get_nodes, split_checksum, checksum_line
   use egw_hysteresis, only: hysteresis_table, hysteresis_prepare
   use egw_hysteresis_checks, only: check_hysteresis, check_log_served
   implicit none
   private

   public :: write_hysteresis, read_hysteresis

   character(len=8), parameter :: magic = "EGWHYST1"
   !> Version 1: no flow-pressure cap; version 2 (the cap, params%flow_pressure > 0: Hertz
   !> + cap, or a rough model + cap, told apart by model and sigma as the evaluation does):
   !> flow_pressure follows the seven parameters (one float64 more in the header); version 3
   !> (log_ratio curves: EP-GW without the cap, or a rough model whose cap does not act)
   !> the layout of version 2 (flow_pressure >= 0), the curves h = ln(P_load/P) on the
   !> edge map with slopes dh/d(m - delta) in place of the gap and dg/ds. Reversible
   !> tables without the cap are still written as version 1.
   !> A version-1 file with curves (egw before the log-ratio curves) is refused: rebuild.
   !> Version 4 (a rough model + cap with the two-piece s map, table%mapped): as version
   !> 2, then tail_length after flow_pressure, and each curve's knee after the lengths;
   !> version 2 files of rough models + cap are read with their linear map, as written.
   !> Version 5 (Hertz + cap storing the unloading force, table%force_ratio): as version 2,
   !> then n_f (the fine grid's nodes, as a float64) after flow_pressure, the fine grid's
   !> delta_max nodes and lengths (fine_m, fine_length: n_f each) after the lengths, and
   !> the curves u = P/P_load(m) and du/ds in place of the gap and dg/ds; version 2 files
   !> of Hertz + cap are read as gap tables, as written.
   !> Version 6 (a rough model + cap with the two-piece s map storing the unloading force,
   !> table%ratio_on_map; the build's since stop 66): version 4's layout (tail_length,
   !> knees), the curves u = P/P_load(m) and du/ds times tail_length in place of the gap
   !> and its slope; version 4 files are read as gap tables, as written.
   integer(int32), parameter :: hysteresis_version = 1, cap_version = 2, log_version = 3, &
      & mapped_version = 4, ratio_version = 5, mapped_ratio_version = 6
   integer(int32), parameter :: byte_order_mark = int(z'01020304', int32)
   !> Fixed part of a binary file before the arrays: magic, 9 int32, 18 float64.
   integer, parameter :: header_bytes = 8 + 4*9 + 8*18
   character(len=*), parameter :: csv_columns = "delta_max,length,s,gap,dgap_ds"
   character(len=*), parameter :: csv_title = "# egw hysteresis table, CSV format 1"
   !> The title of a Hertz + cap table (a flow_pressure line): an egw that knows only
   !> format 1 refuses it rather than read it without the cap.
   character(len=*), parameter :: csv_title_cap = "# egw hysteresis table, CSV format 2"
   !> The title of a table with the two-piece s map (tail_length and knee lines).
   character(len=*), parameter :: csv_title_mapped = "# egw hysteresis table, CSV format 4"
   !> A force-ratio table's header (Hertz + cap, format 5): u = P/P_load(m) and du/ds, and
   !> fine_length lines.
   character(len=*), parameter :: csv_columns_ratio = "delta_max,length,s,force_ratio,"// &
      & "dforce_ratio_ds"
   character(len=*), parameter :: csv_title_ratio = "# egw hysteresis table, CSV format 5"
   !> A rough + cap table storing u on the two-piece map (format 6): format 5's columns,
   !> format 4's tail_length and knee lines.
   character(len=*), parameter :: csv_title_mapped_ratio = &
      & "# egw hysteresis table, CSV format 6"
   !> A log-ratio table's header (columns and title): h = ln(P_load/P) and dh/dxi.
   character(len=*), parameter :: csv_columns_log = "delta_max,length,s,log_ratio,"// &
      & "dlog_ratio_dxi"
   character(len=*), parameter :: csv_title_log = "# egw hysteresis table, CSV format 3"
   !> What a file of the gap curves that the log-ratio curves replaced is told.
   character(len=*), parameter :: rebuild_note = ": an EP-GW table of the gap curves "// &
      & "(egw before the log-ratio curves, doc/formats.md section 6), which this egw "// &
      & "does not read: rebuild the table (egw-table, egw_hysteresis_build)"
   !> Most rows a hysteresis file may announce (a corrupted count must not allocate wildly).
   integer, parameter :: max_rows = 10000000

   !> What parse_csv has read so far, from line to line: the line number, grid sizes and
   !> metadata (-1 and -huge: not read yet), the loading nodes and rows read, and the
   !> numbers of the last of those (v).
   type :: csv_reading
      integer :: line = 0
      integer :: n_load = -1, n_m = -1, n_s = -1, model = -1, rev = -1, n_log = -1
      integer :: k_load = 0, k_row = 0
      real(dp) :: p(7) = -huge(1.0_dp), lmeta(7) = -huge(1.0_dp)
      real(dp) :: flow_pressure = 0.0_dp   !< format 2 only
      integer :: format = 1                !< the CSV title's format
      integer :: k_knee = 0                !< knee lines read (format 4)
      integer :: k_fine = 0                !< fine lines read (format 5)
      integer :: n_f = -1                  !< n_fine (format 5; -1: not read)
      logical :: log = .false.             !< format 3 (log-ratio curves)
      real(dp) :: v(5)
   end type csv_reading

contains

   !> Write a hysteresis table to path in format_csv or format_binary (egw_table_format's
   !> constants). Errors: egw_invalid_argument (unknown format, a table not built),
   !> egw_io_error (nothing replaced then).
   subroutine write_hysteresis(table, path, format, error)
      type(hysteresis_table), intent(in) :: table   !< built or read
      character(len=*), intent(in) :: path          !< file to write (replaced atomically)
      integer, intent(in) :: format                 !< format_csv or format_binary
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      if (.not. allocated(table%loading%delta)) then
         call fatal_error(error, egw_invalid_argument, "table: not built or read")
         return
      end if
      select case (format)
      case (format_csv)
         call write_csv(table, path, error)
      case (format_binary)
         call write_binary(table, path, error)
      case default
         call fatal_error(error, egw_invalid_argument, "format = "//int_str(format)// &
            & ": hysteresis tables are written as 0 (CSV) or 1 (binary)")
      end select
   end subroutine write_hysteresis

   !> Read a hysteresis table written by write_hysteresis (CSV or binary, recognised from
   !> the file's start). A file that is truncated, corrupted or inconsistent gives
   !> egw_bad_file with what is wrong, and table is left empty.
   subroutine read_hysteresis(path, table, error)
      character(len=*), intent(in) :: path           !< a file of write_hysteresis
      type(hysteresis_table), intent(out) :: table   !< the table, empty on error
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      character(len=:), allocatable :: bytes
      call read_bytes(path, bytes, error)
      if (allocated(error)) return
      if (starts_with(bytes, magic)) then
         call parse_binary(path, bytes, table, error)
      else if (starts_with(bytes, csv_columns//new_line("a")//csv_title) .or. &
         & starts_with(bytes, csv_columns//new_line("a")//csv_title_cap) .or. &
         & starts_with(bytes, csv_columns//new_line("a")//csv_title_mapped) .or. &
         & starts_with(bytes, csv_columns_ratio//new_line("a")//csv_title_ratio) .or. &
         & starts_with(bytes, csv_columns_ratio//new_line("a")//csv_title_mapped_ratio) .or. &
         & starts_with(bytes, csv_columns_log//new_line("a")//csv_title_log)) then
         call parse_csv(path, bytes, table, error)
      else
         call fatal_error(error, egw_bad_file, "path = "//path//": not an egw hysteresis "// &
            & "table (neither binary magic "//magic//" nor its CSV header)")
         return
      end if
      if (allocated(error)) then   ! (a parse may have filled part of it)
         call clear(table)
         return
      end if
      call check_hysteresis(path, table, error)
      if (allocated(error)) then
         call clear(table)
         return
      end if
      call table_prepare(table%loading, resample=.false.)
      if (table%log_ratio .and. .not. table%reversible) then
         call check_log_served(path, table, error)
         if (allocated(error)) then
            call clear(table)
            return
         end if
      end if
      call hysteresis_prepare(table)
   end subroutine read_hysteresis

   ! ---------------------------------------------------------------------------- binary

   subroutine write_binary(table, path, error)
      type(hysteresis_table), intent(in) :: table
      character(len=*), intent(in) :: path
      type(egw_error), allocatable, intent(out) :: error
      character(len=:), allocatable :: buf
      integer :: pos, n_load, n_m, n_s
      integer(int32) :: version
      integer :: extra
      n_load = size(table%loading%delta)
      call grid_sizes(table, n_m, n_s)
      version = hysteresis_version
      extra = 0
      if (table%log_ratio) then
         version = log_version
         extra = 8
      else if (table%params%flow_pressure /= 0.0_dp) then
         version = cap_version
         extra = 8
      end if
      if (table%mapped .and. .not. table%reversible) then
         version = mapped_version
         if (table%ratio_on_map) version = mapped_ratio_version   ! (the same layout)
         extra = 16 + 8*n_m
      end if
      if (table%force_ratio .and. .not. table%reversible) then
         version = ratio_version
         extra = 16 + 16*size(table%fine_m)
      end if
      allocate (character(len=header_bytes + extra + 8*(5*n_load + 2*n_m + n_s + &
         & 2*n_m*n_s) + 4) :: buf)
      buf(1:8) = magic
      pos = 9
      call put_i32(buf, pos, [version, byte_order_mark, &
         & int(egw_version_number, int32), int(table%params%model, int32), &
         & merge(1_int32, 0_int32, table%reversible), int(n_load, int32), &
         & int(table%loading%n_log, int32), int(n_m, int32), int(n_s, int32)])
      call put_f64(buf, pos, params_array(table%params))
      if (version /= hysteresis_version) call put_f64(buf, pos, [table%params%flow_pressure])
      if (version == mapped_version .or. version == mapped_ratio_version) &
         & call put_f64(buf, pos, [table%tail_length])
      if (version == ratio_version) call put_f64(buf, pos, [real(size(table%fine_m), dp)])
      call put_f64(buf, pos, [table%rel_tol, table%delta_max, table%max_error, table%s_max])
      call put_f64(buf, pos, table_meta(table%loading))
      call put_nodes(buf, pos, table%loading)
      if (.not. table%reversible) then
         call put_f64(buf, pos, table%m)
         call put_f64(buf, pos, table%length)
         if (version == mapped_version .or. version == mapped_ratio_version) &
            & call put_f64(buf, pos, table%knee)
         if (version == ratio_version) then
            call put_f64(buf, pos, table%fine_m)
            call put_f64(buf, pos, table%fine_length)
         end if
         call put_f64(buf, pos, table%s)
         call put_f64(buf, pos, reshape(table%gap, [n_m*n_s]))
         call put_f64(buf, pos, reshape(table%slope, [n_m*n_s]))
      end if
      call put_i32(buf, pos, [checksum_i32(fnv1a32(buf(1:pos - 1)))])
      ! atomic, every step checked, ulimit -f refused before writing (egw_io)
      call write_file(path, buf(1:pos - 1), error)
   end subroutine write_binary

   subroutine parse_binary(path, bytes, table, error)
      character(len=*), intent(in) :: path, bytes
      type(hysteresis_table), intent(inout) :: table
      type(egw_error), allocatable, intent(out) :: error
      integer(int32) :: head(9), stored(1)
      integer(int64) :: expected
      integer :: pos, n_load, n_m, n_s, extra, n_f, pos_f
      real(dp) :: p(7), meta(4), lmeta(7), flow(1), tail(1), count_f(1)
      logical :: map_layout
      if (len(bytes) < header_bytes + 4) then
         call bad(error, path, "truncated: "//int_str(len(bytes))//" bytes")
         return
      end if
      pos = len(bytes) - 3
      call get_i32(bytes, pos, stored)
      if (stored(1) /= checksum_i32(fnv1a32(bytes(1:len(bytes) - 4)))) then
         call bad(error, path, "checksum mismatch: file is corrupted or truncated")
         return
      end if
      pos = 9
      call get_i32(bytes, pos, head)
      if (head(2) /= byte_order_mark) then
         call bad(error, path, "byte order mark: written on a machine of the other "// &
            & "endianness, or corrupted")
         return
      end if
      if (head(1) /= hysteresis_version .and. head(1) /= cap_version .and. &
         & head(1) /= log_version .and. head(1) /= mapped_version .and. &
         & head(1) /= ratio_version .and. head(1) /= mapped_ratio_version) then
         call bad(error, path, "format version "//int_str(int(head(1)))//" is not "// &
            & "supported (this egw reads versions "//int_str(int(hysteresis_version))// &
            & " to "//int_str(int(mapped_ratio_version))//")")
         return
      end if
      if (head(1) == hysteresis_version .and. head(5) == 0) then
         call bad(error, path, "format version 1 with curves"//rebuild_note)
         return
      end if
      if (head(1) == log_version .and. head(5) /= 0) then
         call bad(error, path, "format version 3 of a reversible table (version 3 is the "// &
            & "log-ratio curves')")
         return
      end if
      extra = 0
      if (head(1) == cap_version .or. head(1) == log_version) extra = 8
      n_load = head(6)
      n_m = head(8)
      n_s = head(9)
      ! (versions 4 and 6: the two-piece map's tail_length and knees)
      map_layout = head(1) == mapped_version .or. head(1) == mapped_ratio_version
      if (map_layout) extra = 16 + 8*max(min(n_m, max_rows), 0)
      if (head(1) == ratio_version .and. head(5) /= 0) then
         call bad(error, path, "format version 5 of a reversible table (version 5 is the "// &
            & "force-ratio curves')")
         return
      end if
      n_f = 0
      count_f = 0.0_dp
      if (head(1) == ratio_version) then
         ! (n_f, a float64 after flow_pressure, needed for the size)
         if (len(bytes) >= header_bytes + 16) then
            pos_f = 9 + 4*9 + 8*8
            call get_f64(bytes, pos_f, count_f)
            if (count_f(1) >= 4.0_dp .and. count_f(1) <= max_rows) n_f = int(count_f(1))
            if (real(n_f, dp) /= count_f(1)) n_f = 0
         end if
         if (n_f == 0) then
            call bad(error, path, "format version 5: the fine grid's node count n_f = "// &
               & format_real(count_f(1))//" is not an integer in [4, "// &
               & int_str(max_rows)//"]")
            return
         end if
         extra = 16 + 16*n_f
      end if
      if (n_load < 2 .or. n_load > max_rows .or. n_m < 0 .or. n_m > max_rows .or. &
         & n_s < 0 .or. n_s > max_rows) then
         call bad(error, path, "node counts out of range")
         return
      end if
      expected = header_bytes + extra + 8_int64*(5*int(n_load, int64) + 2*n_m + n_s + &
         & 2*int(n_m, int64)*n_s) + 4
      if (len(bytes, int64) /= expected) then
         call bad(error, path, "node counts do not match the file size "// &
            & int_str(len(bytes)))
         return
      end if
      call get_f64(bytes, pos, p)
      flow = 0.0_dp
      tail = 0.0_dp
      if (extra > 0) call get_f64(bytes, pos, flow)
      if (map_layout) call get_f64(bytes, pos, tail)
      if (head(1) == ratio_version) call get_f64(bytes, pos, count_f)
      call get_f64(bytes, pos, meta)
      call get_f64(bytes, pos, lmeta)
      table%params = params_from(int(head(4)), p)
      table%params%flow_pressure = flow(1)
      if ((head(1) == cap_version .or. map_layout .or. &
         & head(1) == ratio_version) .and. .not. flow(1) > 0.0_dp) then
         call bad(error, path, "format version "//int_str(int(head(1)))// &
            & " with flow_pressure = "//format_real(flow(1))//" (versions 2, 4, 5 and 6 "// &
            & "are the flow-pressure cap's, > 0)")
         return
      end if
      if (head(1) == log_version .and. .not. flow(1) >= 0.0_dp) then
         call bad(error, path, "format version 3 with flow_pressure = "// &
            & format_real(flow(1))//" (must be >= 0)")
         return
      end if
      table%mapped = map_layout
      table%ratio_on_map = head(1) == mapped_ratio_version
      table%force_ratio = head(1) == ratio_version
      table%tail_length = tail(1)
      table%reversible = head(5) /= 0
      table%log_ratio = head(1) == log_version
      table%rel_tol = meta(1)
      table%delta_max = meta(2)
      table%max_error = meta(3)
      table%s_max = meta(4)
      table%loading%params = table%params
      table%loading%n_log = head(7)
      call set_table_meta(table%loading, lmeta)
      call get_nodes(bytes, pos, n_load, table%loading)
      allocate (table%m(n_m), table%length(n_m), table%s(n_s), table%gap(n_s, n_m), &
         & table%slope(n_s, n_m))
      call get_f64(bytes, pos, table%m)
      call get_f64(bytes, pos, table%length)
      if (table%mapped) then
         allocate (table%knee(n_m))
         call get_f64(bytes, pos, table%knee)
      end if
      if (table%force_ratio) then
         allocate (table%fine_m(n_f), table%fine_length(n_f))
         call get_f64(bytes, pos, table%fine_m)
         call get_f64(bytes, pos, table%fine_length)
      end if
      call get_f64(bytes, pos, table%s)
      call get_matrix(bytes, pos, table%gap)
      call get_matrix(bytes, pos, table%slope)
   end subroutine parse_binary

   ! ---------------------------------------------------------------------------- CSV

   subroutine write_csv(table, path, error)
      type(hysteresis_table), intent(in) :: table
      character(len=*), intent(in) :: path
      type(egw_error), allocatable, intent(out) :: error
      character(len=:), allocatable :: head
      integer :: i, j, n_m, n_s
      type(text_buffer) :: out
      call grid_sizes(table, n_m, n_s)
      associate (l => table%loading)
         ! the column header first and the metadata as '#' lines, as the 1-D tables:
         ! pandas.read_csv(path, comment="#") reads the unloading rows as they are
         if (table%log_ratio) then
            head = csv_columns_log//new_line("a")//csv_title_log//new_line("a")
         else if (table%force_ratio .and. .not. table%reversible) then
            head = csv_columns_ratio//new_line("a")//csv_title_ratio//new_line("a")
         else if (table%mapped .and. table%ratio_on_map .and. .not. table%reversible) then
            head = csv_columns_ratio//new_line("a")//csv_title_mapped_ratio//new_line("a")
         else if (table%mapped .and. .not. table%reversible) then
            head = csv_columns//new_line("a")//csv_title_mapped//new_line("a")
         else
            head = csv_columns//new_line("a")//merge(csv_title_cap, csv_title, &
               & table%params%flow_pressure /= 0.0_dp)//new_line("a")
         end if
         head = head// &
            & "# egw_version = "//egw_version_string//new_line("a")// &
            & "# model = "//int_str(table%params%model)//" ("// &
            & model_name(table%params%model)//")"//new_line("a")
         call add_reals(head, ["radius        ", "modulus       ", "sigma         ", &
            & "mu            ", "psi           ", "hardness_coeff", "plastic_ratio "], &
            & params_array(table%params))
         ! the cap's only: files without it stay as before
         if (table%params%flow_pressure /= 0.0_dp) call add_reals(head, ["flow_pressure"], &
            & [table%params%flow_pressure])
         call add_reals(head, ["rel_tol  ", "delta_max", "max_error", "s_max    "], &
            & [table%rel_tol, table%delta_max, table%max_error, table%s_max])
         if (table%mapped .and. .not. table%reversible) call add_reals(head, &
            & ["tail_length"], [table%tail_length])
         head = head//"# reversible = "//int_str(merge(1, 0, table%reversible))// &
            & new_line("a")//"# n_delta_max = "//int_str(n_m)//new_line("a")//"# n_s = "// &
            & int_str(n_s)//new_line("a")
         call add_reals(head, ["loading.rel_tol            ", "loading.cutoff             ", &
            & "loading.delta_max          ", "loading.reference_force    ", &
            & "loading.max_force_error    ", "loading.max_stiffness_error", &
            & "loading.radius_sum         "], table_meta(l))
         head = head//"# loading.n_nodes = "//int_str(size(l%delta))//new_line("a")// &
            & "# loading.n_log = "//int_str(l%n_log)//new_line("a")// &
            & "# units = delta, delta_max, contact_radius [length]; force [modulus*length^2]; "// &
            & "stiffness [modulus*length]; energy [modulus*length^3]; s, gap [1]"// &
            & new_line("a")
         call add_rows_note(head, table%log_ratio, table%force_ratio, &
            & table%mapped .and. table%ratio_on_map .and. .not. table%reversible)
         head = head//new_line("a")//"# loading columns = delta,force,stiffness,energy,"// &
            & "contact_radius"
         if (table%mapped .and. .not. table%reversible) then
            head = head//new_line("a")//"# the two-piece s map: each curve's knee (in "// &
               & "delta_max order) at s = 1/2, delta = 0 at s = 3/4, -tail_length at s = 1; "// &
               & trim(merge("dforce_ratio_ds", "dgap_ds        ", table%ratio_on_map))// &
               & ": the first piece's (doc/formats.md)"
            do j = 1, n_m
               head = head//new_line("a")//"# knee = "//fmt(table%knee(j))
            end do
         end if
         if (table%force_ratio .and. .not. table%reversible) then
            head = head//new_line("a")//"# 1/length interpolated on the fine delta_max grid "// &
               & "(cubic Lagrange on four neighbouring nodes): its nodes as delta_max, "// &
               & "length (doc/formats.md)"//new_line("a")//"# n_fine = "// &
               & int_str(size(table%fine_m))
            do j = 1, size(table%fine_m)
               head = head//new_line("a")//"# fine = "//csv_row([table%fine_m(j), &
                  & table%fine_length(j)])
            end do
         end if
         call put_line(head)
         do i = 1, size(l%delta)
            call put_line("# loading = "//csv_row([l%delta(i), l%force(i), l%stiffness(i), &
               & l%energy(i), l%contact_radius(i)]))
         end do
      end associate
      do j = 1, n_m
         do i = 1, n_s
            call put_line(csv_row([table%m(j), table%length(j), table%s(i), &
               & table%gap(i, j), table%slope(i, j)]))
         end do
      end do
      call put_line("# end of table, "//int_str(n_m*n_s)//" rows")
      ! the checksum line of the force tables' CSV (read back by read_hysteresis)
      call out%add(checksum_line(out%text(1:out%n)))
      ! built in memory, then written atomically with every step checked (egw_io)
      call out%write(path, error)
   contains
      subroutine put_line(line)
         character(len=*), intent(in) :: line
         call out%add(line)
      end subroutine put_line
   end subroutine write_csv

   !> Appends the '# rows:' line of a hysteresis CSV (what a row's numbers are) to head
   !> (a subroutine: the library has no deferred-length function results).
   pure subroutine add_rows_note(head, log_ratio, force_ratio, ratio_on_map)
      character(len=:), allocatable, intent(inout) :: head   !< the header so far
      logical, intent(in) :: log_ratio   !< a log-ratio table (format 3), else gap rows
      logical, intent(in) :: force_ratio   !< a force-ratio table (format 5)
      logical, intent(in) :: ratio_on_map   !< u on the two-piece map (format 6)
      if (ratio_on_map) then
         head = head//"# rows: unloading force = P_load(delta_max)*force_ratio at s of "// &
            & "the two-piece map (knee lines), cubic Hermite in s (slope dforce_ratio_ds "// &
            & "as the map line says), cubic Lagrange in delta_max over four neighbouring "// &
            & "curves, the knee too; below s = 1 the loading tail scaled (doc/formats.md)"
      else if (force_ratio) then
         head = head//"# rows: unloading force = P_load(delta_max)*force_ratio at s = "// &
            & "(delta_max - delta)/length, 0 from s = 1 on, cubic Hermite in s (slope "// &
            & "dforce_ratio_ds), cubic Lagrange in delta_max over four neighbouring "// &
            & "curves, 1/length on the fine grid of the fine_length lines (doc/formats.md)"
      else if (log_ratio) then
         head = head//"# rows: unloading force = P_load(delta)*exp(-log_ratio) at s of "// &
            & "the edge map of length and sigma (s piecewise linear in delta_max - delta, "// &
            & "doc/formats.md), cubic Hermite in s (slope dlog_ratio_dxi per "// &
            & "delta_max - delta), Lagrange in delta_max over six neighbouring curves "// &
            & "(four where fewer), 1/length too (doc/formats.md)"
      else
         head = head//"# rows: unloading force = P_load(delta) - P_load(delta_max)*gap at "// &
            & "s = (delta_max - delta)/(s_max*length), cubic Hermite in s (slope dgap_ds), "// &
            & "cubic Lagrange in delta_max over four neighbouring curves, length too "// &
            & "(doc/formats.md)"
      end if
   end subroutine add_rows_note

   !> Read the CSV form (doc/formats.md §6): the checksum line, then line by line the
   !> metadata and loading nodes ('#' lines, read_csv_meta) and the unloading rows
   !> (read_csv_row), then whether all were there (finish_csv).
   subroutine parse_csv(path, text, table, error)
      character(len=*), intent(in) :: path, text
      type(hysteresis_table), intent(inout) :: table
      type(egw_error), allocatable, intent(out) :: error
      type(csv_reading) :: reading
      integer :: start, eol, sum_at
      logical :: missing
      ! the checksum line covers every byte before it; unlike a force table, a hysteresis
      ! table without one is refused (nobody edits its grid by hand)
      call split_checksum(path, text, sum_at, missing, error)
      if (allocated(error)) return
      if (missing) then
         call bad(error, path, "no '# fnv1a32' checksum line (a hysteresis CSV must be "// &
            & "written by egw)")
         return
      end if
      if (starts_with(text, csv_columns//new_line("a")//csv_title_cap)) reading%format = 2
      if (starts_with(text, csv_columns//new_line("a")//csv_title_mapped)) reading%format = 4
      if (starts_with(text, csv_columns_ratio//new_line("a")//csv_title_ratio)) &
         & reading%format = 5
      if (starts_with(text, csv_columns_ratio//new_line("a")//csv_title_mapped_ratio)) &
         & reading%format = 6
      reading%log = starts_with(text, csv_columns_log//new_line("a"))
      start = 1
      do while (start <= sum_at)
         eol = index(text(start:), new_line("a"))
         if (eol == 0) exit
         eol = start + eol - 2
         reading%line = reading%line + 1
         if (reading%line == 1 .or. eol < start) then
            start = eol + 2
            cycle
         end if
         if (text(start:start) == "#") then
            call read_csv_meta(path, text(start:eol), table, reading, error)
         else
            call read_csv_row(path, text(start:eol), table, reading, error)
         end if
         if (allocated(error)) return
         start = eol + 2
      end do
      call finish_csv(path, table, reading, error)
   end subroutine parse_csv

   !> One '#' line of a hysteresis CSV: a metadata value (model, parameters, grid sizes,
   !> the loading table's metadata) or a loading node, into table and reading.
   subroutine read_csv_meta(path, line, table, reading, error)
      character(len=*), intent(in) :: path, line
      type(hysteresis_table), intent(inout) :: table
      type(csv_reading), intent(inout) :: reading
      type(egw_error), allocatable, intent(out) :: error
      character(len=:), allocatable :: key, value
      integer :: ios
      call split_key(line, key, value)
      associate (p => reading%p, lmeta => reading%lmeta, l => table%loading)
         select case (key)
         case ("model")
            read (value, *, iostat=ios) reading%model
         case ("radius"); call get_real(value, p(1), ios)
         case ("modulus"); call get_real(value, p(2), ios)
         case ("sigma"); call get_real(value, p(3), ios)
         case ("mu"); call get_real(value, p(4), ios)
         case ("psi"); call get_real(value, p(5), ios)
         case ("hardness_coeff"); call get_real(value, p(6), ios)
         case ("plastic_ratio"); call get_real(value, p(7), ios)
         case ("flow_pressure"); call get_real(value, reading%flow_pressure, ios)
         case ("rel_tol"); call get_real(value, table%rel_tol, ios)
         case ("delta_max"); call get_real(value, table%delta_max, ios)
         case ("max_error"); call get_real(value, table%max_error, ios)
         case ("s_max"); call get_real(value, table%s_max, ios)
         case ("tail_length"); call get_real(value, table%tail_length, ios)
         case ("knee")
            call read_knee(path, value, table, reading, ios, error)
            if (allocated(error)) return
         case ("n_fine")
            read (value, *, iostat=ios) reading%n_f
            if (ios == 0 .and. (reading%format /= 5 .or. reading%n_f < 4 .or. &
               & reading%n_f > max_rows .or. allocated(table%fine_m))) then
               call bad(error, path, "line "//int_str(reading%line)//": n_fine outside "// &
                  & "CSV format 5, repeated, or not in [4, "//int_str(max_rows)//"]")
               return
            end if
            if (ios == 0) allocate (table%fine_m(reading%n_f), &
               & table%fine_length(reading%n_f))
         case ("fine")
            call read_fine(path, value, table, reading, ios, error)
            if (allocated(error)) return
         case ("reversible"); read (value, *, iostat=ios) reading%rev
         case ("n_delta_max"); read (value, *, iostat=ios) reading%n_m
         case ("n_s"); read (value, *, iostat=ios) reading%n_s
         case ("loading.rel_tol"); call get_real(value, lmeta(1), ios)
         case ("loading.cutoff"); call get_real(value, lmeta(2), ios)
         case ("loading.delta_max"); call get_real(value, lmeta(3), ios)
         case ("loading.reference_force"); call get_real(value, lmeta(4), ios)
         case ("loading.max_force_error"); call get_real(value, lmeta(5), ios)
         case ("loading.max_stiffness_error"); call get_real(value, lmeta(6), ios)
         case ("loading.radius_sum"); call get_real(value, lmeta(7), ios)
         case ("loading.n_log"); read (value, *, iostat=ios) reading%n_log
         case ("loading.n_nodes")
            read (value, *, iostat=ios) reading%n_load
            if (ios == 0 .and. reading%n_load >= 2 .and. reading%n_load <= max_rows) &
               & allocate (l%delta(reading%n_load), l%force(reading%n_load), &
               & l%stiffness(reading%n_load), l%energy(reading%n_load), &
               & l%contact_radius(reading%n_load))
         case ("loading")
            call read_loading_node(path, value, table, reading, ios, error)
            if (allocated(error)) return
         case default
            ios = 0
         end select
      end associate
      if (ios /= 0) then
         call bad(error, path, "line "//int_str(reading%line)//": cannot read '"//key//"'")
         return
      end if
   end subroutine read_csv_meta

   !> A '# knee = ' line of format 4 or 6: the next curve's knee (ios: of its number).
   subroutine read_knee(path, value, table, reading, ios, error)
      character(len=*), intent(in) :: path, value
      type(hysteresis_table), intent(inout) :: table
      type(csv_reading), intent(inout) :: reading
      integer, intent(out) :: ios
      type(egw_error), allocatable, intent(out) :: error
      ios = 0
      if (.not. (reading%format == 4 .or. reading%format == 6) .or. reading%n_m < 0 .or. &
         & reading%n_m > max_rows) then
         call bad(error, path, "line "//int_str(reading%line)//": knee before a valid "// &
            & "n_delta_max, or outside CSV formats 4 and 6")
         return
      end if
      if (.not. allocated(table%knee)) allocate (table%knee(reading%n_m))
      reading%k_knee = reading%k_knee + 1
      if (reading%k_knee > reading%n_m) then
         call bad(error, path, "more knee lines than n_delta_max")
         return
      end if
      call get_real(value, table%knee(reading%k_knee), ios)
   end subroutine read_knee

   !> A '# fine = ' line of format 5: the next node of the fine grid, delta_max and its
   !> length (ios: of its numbers).
   subroutine read_fine(path, value, table, reading, ios, error)
      character(len=*), intent(in) :: path, value
      type(hysteresis_table), intent(inout) :: table
      type(csv_reading), intent(inout) :: reading
      integer, intent(out) :: ios
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: v(2)
      ios = 0
      if (.not. allocated(table%fine_m)) then
         call bad(error, path, "line "//int_str(reading%line)//": fine before n_fine")
         return
      end if
      reading%k_fine = reading%k_fine + 1
      if (reading%k_fine > size(table%fine_m)) then
         call bad(error, path, "more fine lines than n_fine")
         return
      end if
      read (value, *, iostat=ios) v
      table%fine_m(reading%k_fine) = v(1)
      table%fine_length(reading%k_fine) = v(2)
   end subroutine read_fine

   !> A '# loading = ' line: the next node of the loading table (ios: of its numbers).
   subroutine read_loading_node(path, value, table, reading, ios, error)
      character(len=*), intent(in) :: path, value
      type(hysteresis_table), intent(inout) :: table
      type(csv_reading), intent(inout) :: reading
      integer, intent(out) :: ios
      type(egw_error), allocatable, intent(out) :: error
      ios = 0
      reading%k_load = reading%k_load + 1
      if (.not. allocated(table%loading%delta)) then
         call bad(error, path, "line "//int_str(reading%line)//": loading node before "// &
            & "loading.n_nodes")
         return
      end if
      if (reading%k_load > reading%n_load) then
         call bad(error, path, "more loading nodes than loading.n_nodes")
         return
      end if
      associate (v => reading%v, k => reading%k_load, l => table%loading)
         read (value, *, iostat=ios) v
         l%delta(k) = v(1)
         l%force(k) = v(2)
         l%stiffness(k) = v(3)
         l%energy(k) = v(4)
         l%contact_radius(k) = v(5)
      end associate
   end subroutine read_loading_node

   !> One row of a hysteresis CSV: (delta_max, length, s, gap, dgap_ds) at the next point
   !> of the unloading grid, which the rows must fill in order (doc/formats.md §6).
   subroutine read_csv_row(path, line, table, reading, error)
      character(len=*), intent(in) :: path, line
      type(hysteresis_table), intent(inout) :: table
      type(csv_reading), intent(inout) :: reading
      type(egw_error), allocatable, intent(out) :: error
      integer :: ios
      associate (n_m => reading%n_m, n_s => reading%n_s, v => reading%v)
         if (.not. allocated(table%m)) then
            if (n_m < 0 .or. n_s < 0 .or. n_m > max_rows .or. n_s > max_rows .or. &
               & int(n_m, int64)*n_s > max_rows) then
               call bad(error, path, "line "//int_str(reading%line)//": row before valid "// &
                  & "n_delta_max and n_s")
               return
            end if
            allocate (table%m(n_m), table%length(n_m), table%s(n_s), &
               & table%gap(n_s, n_m), table%slope(n_s, n_m))
         end if
         reading%k_row = reading%k_row + 1
         read (line, *, iostat=ios) v(1:5)
         if (ios /= 0 .or. reading%k_row > n_m*n_s) then
            call bad(error, path, "line "//int_str(reading%line)//": not a row of 5 "// &
               & "numbers, or more rows than n_delta_max*n_s")
            return
         end if
         associate (j => (reading%k_row - 1)/n_s + 1, i => mod(reading%k_row - 1, n_s) + 1)
            if (i == 1) table%m(j) = v(1)
            if (i == 1) table%length(j) = v(2)
            if (j == 1) table%s(i) = v(3)
            if (v(1) /= table%m(j) .or. v(2) /= table%length(j) .or. &
               & v(3) /= table%s(i)) then
               call bad(error, path, "line "//int_str(reading%line)//": delta_max, length "// &
                  & "or s differs from the grid of the rows before")
               return
            end if
            table%gap(i, j) = v(4)
            table%slope(i, j) = v(5)
         end associate
      end associate
   end subroutine read_csv_row

   !> After the last line of a hysteresis CSV: every metadata value, loading node and row
   !> present; the parameters and the loading table's metadata set from them.
   subroutine finish_csv(path, table, reading, error)
      character(len=*), intent(in) :: path
      type(hysteresis_table), intent(inout) :: table
      type(csv_reading), intent(in) :: reading
      type(egw_error), allocatable, intent(out) :: error
      if (reading%model < 0 .or. reading%rev < 0 .or. reading%n_log < 0 .or. &
         & reading%n_load < 2 .or. reading%k_load /= reading%n_load .or. &
         & any(reading%p == -huge(1.0_dp)) .or. any(reading%lmeta == -huge(1.0_dp))) then
         call bad(error, path, "metadata or loading nodes incomplete")
         return
      end if
      if (.not. allocated(table%m)) allocate (table%m(0), table%length(0), table%s(0), &
         & table%gap(0, 0), table%slope(0, 0))
      if (reading%k_row /= size(table%m)*size(table%s)) then
         call bad(error, path, int_str(reading%k_row)//" rows, n_delta_max*n_s = "// &
            & int_str(size(table%m)*size(table%s)))
         return
      end if
      table%params = params_from(reading%model, reading%p)
      table%params%flow_pressure = reading%flow_pressure
      table%reversible = reading%rev /= 0
      table%mapped = reading%format == 4 .or. reading%format == 6
      table%ratio_on_map = reading%format == 6
      table%force_ratio = reading%format == 5
      if (table%force_ratio .and. (table%reversible .or. reading%n_f < 0 .or. &
         & reading%k_fine /= reading%n_f)) then
         call bad(error, path, "CSV format 5: "//int_str(reading%k_fine)//" fine lines, "// &
            & "n_fine = "//int_str(reading%n_f)//" (and a table with curves)")
         return
      end if
      if (table%mapped .and. (reading%k_knee /= size(table%m) .or. table%reversible)) then
         call bad(error, path, "CSV format "//int_str(reading%format)//": "// &
            & int_str(reading%k_knee)//" knee lines, "// &
            & "n_delta_max = "//int_str(size(table%m))//" (and a table with curves)")
         return
      end if
      ! formats 2 and 4 are the cap's: a flow_pressure line that is not > 0 is named (as
      ! the binary reader does), not taken for a format-1 file of the gap curves
      if (reading%format >= 4 .or. reading%format == 2) then
         if (.not. reading%flow_pressure > 0.0_dp) then
            call bad(error, path, "CSV format "//int_str(reading%format)// &
               & " with flow_pressure = "//format_real(reading%flow_pressure)// &
               & " (formats 2, 4, 5 and 6 are the flow-pressure cap's, > 0)")
            return
         end if
      end if
      if (.not. reading%log .and. .not. table%reversible .and. &
         & .not. reading%flow_pressure > 0.0_dp) then
         call bad(error, path, "CSV format 1 with curves"//rebuild_note)
         return
      end if
      if (reading%log .and. reading%flow_pressure < 0.0_dp) then
         call bad(error, path, "CSV format 3 with flow_pressure = "// &
            & format_real(reading%flow_pressure)//" (must be >= 0)")
         return
      end if
      if (reading%log .and. table%reversible) then
         call bad(error, path, "CSV format 3 of a reversible table (format 3 is the "// &
            & "log-ratio curves')")
         return
      end if
      table%log_ratio = reading%log
      table%loading%params = table%params
      table%loading%n_log = reading%n_log
      call set_table_meta(table%loading, reading%lmeta)
   end subroutine finish_csv

   ! ---------------------------------------------------------------------------- helpers

   !> delta_max nodes and s nodes of the stored curves (0, 0 for a reversible table).
   pure subroutine grid_sizes(table, n_m, n_s)
      type(hysteresis_table), intent(in) :: table
      integer, intent(out) :: n_m, n_s
      n_m = 0
      n_s = 0
      if (table%reversible) return
      n_m = size(table%m)
      n_s = size(table%s)
   end subroutine grid_sizes

   pure function params_array(p) result(a)
      type(contact_params), intent(in) :: p
      real(dp) :: a(7)
      a = [p%radius, p%modulus, p%sigma, p%mu, p%psi, p%hardness_coeff, p%plastic_ratio]
   end function params_array

   pure function params_from(model, a) result(p)
      integer, intent(in) :: model
      real(dp), intent(in) :: a(7)
      type(contact_params) :: p
      p = contact_params(model=model, radius=a(1), modulus=a(2), sigma=a(3), mu=a(4), &
         & psi=a(5), hardness_coeff=a(6), plastic_ratio=a(7))
   end function params_from

   subroutine clear(t)
      type(hysteresis_table), intent(out) :: t
   end subroutine clear

   subroutine read_bytes(path, bytes, error)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: bytes
      type(egw_error), allocatable, intent(out) :: error
      call read_file(path, bytes, error)
   end subroutine read_bytes

   pure subroutine put_i32(buf, pos, v)
      character(len=*), intent(inout) :: buf
      integer, intent(inout) :: pos
      integer(int32), intent(in) :: v(:)
      buf(pos:pos + 4*size(v) - 1) = transfer(v, buf(pos:pos + 4*size(v) - 1))
      pos = pos + 4*size(v)
   end subroutine put_i32

   pure subroutine get_i32(buf, pos, v)
      character(len=*), intent(in) :: buf
      integer, intent(inout) :: pos
      integer(int32), intent(out) :: v(:)
      v = transfer(buf(pos:pos + 4*size(v) - 1), v, size(v))
      pos = pos + 4*size(v)
   end subroutine get_i32

   pure subroutine get_matrix(buf, pos, a)
      character(len=*), intent(in) :: buf
      integer, intent(inout) :: pos
      real(dp), intent(out) :: a(:, :)
      real(dp) :: flat(size(a))
      call get_f64(buf, pos, flat)
      a = reshape(flat, shape(a))
   end subroutine get_matrix

   !> "# key = value" -> key, value (key "" for other comment lines).
   subroutine split_key(line, key, value)
      character(len=*), intent(in) :: line
      character(len=:), allocatable, intent(out) :: key, value
      integer :: eq
      eq = index(line, " = ")
      if (eq < 3) then
         key = ""
         value = ""
         return
      end if
      key = trim(adjustl(line(2:eq - 1)))
      value = trim(adjustl(line(eq + 3:)))
   end subroutine split_key

   subroutine get_real(value, x, ios)
      character(len=*), intent(in) :: value
      real(dp), intent(out) :: x
      integer, intent(out) :: ios
      read (value, *, iostat=ios) x
   end subroutine get_real

   subroutine add_reals(text, keys, values)
      character(len=:), allocatable, intent(inout) :: text
      character(len=*), intent(in) :: keys(:)
      real(dp), intent(in) :: values(:)
      integer :: i
      do i = 1, size(keys)
         text = text//"# "//trim(keys(i))//" = "//fmt(values(i))//new_line("a")
      end do
   end subroutine add_reals

   ! (results of lengths known before the call, not deferred: gfortran 12 keeps a
   ! deferred result length in a static variable, which threads share; see egw_text)


   !> 17 significant digits (ES25.17E3): every double reads back bit-for-bit.
   pure function fmt(x) result(str)
      real(dp), intent(in) :: x
      character(len=real_text_len(x, 17, 3)) :: str
      str = real_text(x, 17, 3)
   end function fmt

   pure logical function starts_with(str, prefix)
      character(len=*), intent(in) :: str, prefix
      starts_with = .false.
      if (len(str) >= len(prefix)) starts_with = str(1:len(prefix)) == prefix
   end function starts_with

end module egw_hysteresis_format
