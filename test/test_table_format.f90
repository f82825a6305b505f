!> Tests of egw_table_format: round trips of the egw formats (bit-exact), rejection of
!> truncated, corrupted and wrong-version files, atomic writes, and the LAMMPS and
!> CalculiX exports parsed back by small readers written here.
module test_table_format
   use, intrinsic :: iso_fortran_env, only: int32, int64
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf
   use testdrive, only: new_unittest, unittest_type, error_type, check, to_string
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_bad_file, egw_io_error, egw_invalid_argument, &
      & egw_unsupported, format_real
   use egw_params, only: contact_params, model_hertz, model_egw, model_epgw
   use egw_rough_sphere, only: solver_options
   use egw_asperity, only: flat_pressure
   use egw_table
   use egw_table_universal
   use egw_table_format
   use egw_hysteresis, only: hysteresis_table, build_hysteresis
   use egw_hysteresis_format, only: write_hysteresis, read_hysteresis
   implicit none
   private
   public :: collect_table_format

   real(dp), parameter :: tol = 1.0e-6_dp
   character(len=*), parameter :: dir = "build/test_table_format"

contains

   subroutine collect_table_format(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      call execute_command_line("mkdir -p "//dir)
      testsuite = [ &
         & new_unittest("csv round trip", test_csv_round_trip), &
         & new_unittest("binary round trip", test_binary_round_trip), &
         & new_unittest("universal round trips", test_universal_round_trip), &
         & new_unittest("binary truncated", test_binary_truncated), &
         & new_unittest("binary corrupted", test_binary_corrupted), &
         & new_unittest("binary wrong version", test_binary_version), &
         & new_unittest("csv truncated or corrupted", test_csv_bad), &
         & new_unittest("csv checksum: bit flips, no line", test_csv_checksum), &
         & new_unittest("csv sanity on read", test_csv_sanity), &
         & new_unittest("binary sanity on read", test_binary_sanity), &
         & new_unittest("crafted values with a valid checksum", test_crafted_values), &
         & new_unittest("crafted tail (n_log lowered) and absurd node", test_crafted_tail), &
         & new_unittest("atomic writes", test_atomic), &
         & new_unittest("lammps export", test_lammps), &
         & new_unittest("lammps export, rough table", test_lammps_rough), &
         & new_unittest("lammps units tag", test_lammps_units), &
         & new_unittest("calculix sphere export", test_calculix_sphere), &
         & new_unittest("calculix rough flat export", test_calculix_flat), &
         & new_unittest("calculix limits and shift", test_calculix_limits), &
         & new_unittest("unsupported and missing", test_unsupported), &
         & new_unittest("universal table relabelled Hertz refused", test_universal_relabelled) &
         & ]
   end subroutine collect_table_format

   pure real(dp) function p_hertz(e, r, d)
      real(dp), intent(in) :: e, r, d
      p_hertz = 4.0_dp/3.0_dp*e*sqrt(r)*max(d, 0.0_dp)**1.5_dp
   end function p_hertz

   subroutine hertz_table(t, error)
      type(force_table), intent(out) :: t
      type(error_type), allocatable, intent(out) :: error
      type(egw_error), allocatable :: err
      call build_table(contact_params(model=model_hertz, radius=0.5_dp, modulus=2.0_dp), &
         & solver_options(), 0.0_dp, 1.0e-2_dp, tol, t, err)
      call check(error, .not. allocated(err), "Hertz table build failed")
   end subroutine hertz_table

   subroutine rough_table(t, error)
      type(force_table), intent(out) :: t
      type(error_type), allocatable, intent(out) :: error
      type(egw_error), allocatable :: err
      call build_table(contact_params(model=model_egw, sigma=1.0e-3_dp, mu=4.0_dp), &
         & solver_options(), -6.0e-3_dp, 5.0e-3_dp, 1.0e-4_dp, t, err)
      call check(error, .not. allocated(err), "E-GW table build failed")
   end subroutine rough_table

   !> Tables read back must be identical: 17 significant digits (CSV) and raw bytes
   !> (binary) reproduce every double, and the evaluation data are derived
   !> deterministically, so evaluation is bit-for-bit the same too.
   subroutine same_table(error, a, b)
      type(error_type), allocatable, intent(out) :: error
      type(force_table), intent(in) :: a, b
      integer :: i
      real(dp) :: d, fa, ka, fb, kb
      call check(error, size(a%delta) == size(b%delta), "node count differs")
      if (allocated(error)) return
      call check(error, all(a%delta == b%delta) .and. all(a%force == b%force) .and. &
         & all(a%stiffness == b%stiffness) .and. all(a%energy == b%energy) .and. &
         & all(a%contact_radius == b%contact_radius), "node data differ")
      if (allocated(error)) return
      call check(error, a%params%model == b%params%model .and. a%params%radius == &
         & b%params%radius .and. a%params%mu == b%params%mu .and. a%params%sigma == &
         & b%params%sigma .and. a%n_log == b%n_log .and. a%cutoff == b%cutoff .and. &
         & a%rel_tol == b%rel_tol .and. a%reference_force == b%reference_force .and. &
         & a%radius_sum == b%radius_sum .and. a%max_force_error == b%max_force_error, &
         & "metadata differ")
      if (allocated(error)) return
      do i = 0, 200
         d = a%cutoff + (a%delta_max - a%cutoff)*(i/200.0_dp)**1.5_dp
         call table_eval(a, d, fa, ka)
         call table_eval(b, d, fb, kb)
         call check(error, fa == fb .and. ka == kb, "evaluation differs at "//format_real(d))
         if (allocated(error)) return
      end do
   end subroutine same_table

   subroutine round_trip(error, t, path, format)
      type(error_type), allocatable, intent(out) :: error
      type(force_table), intent(in) :: t
      character(len=*), intent(in) :: path
      integer, intent(in) :: format
      type(force_table) :: back
      type(egw_error), allocatable :: err
      call write_table(t, path, format, err)
      call check(error, .not. allocated(err), "write failed")
      if (allocated(error)) return
      call read_table(path, back, err)
      if (allocated(err)) then
         call check(error, .false., "read failed: "//err%message)
         return
      end if
      call same_table(error, t, back)
   end subroutine round_trip

   subroutine test_csv_round_trip(error)
      type(error_type), allocatable, intent(out) :: error
      type(force_table) :: t
      type(egw_error), allocatable :: err
      call hertz_table(t, error)
      if (allocated(error)) return
      call table_set_radii(t, 1.0_dp, 1.0_dp, err)
      call round_trip(error, t, dir//"/hertz.csv", format_csv)
      if (allocated(error)) return
      call rough_table(t, error)
      if (allocated(error)) return
      call round_trip(error, t, dir//"/egw.csv", format_csv)
   end subroutine test_csv_round_trip

   subroutine test_binary_round_trip(error)
      type(error_type), allocatable, intent(out) :: error
      type(force_table) :: t
      call hertz_table(t, error)
      if (allocated(error)) return
      call round_trip(error, t, dir//"/hertz.egwt", format_binary)
      if (allocated(error)) return
      call rough_table(t, error)
      if (allocated(error)) return
      call round_trip(error, t, dir//"/egw.egwt", format_binary)
   end subroutine test_binary_round_trip

   subroutine test_universal_round_trip(error)
      type(error_type), allocatable, intent(out) :: error
      type(universal_table) :: u, back
      type(egw_error), allocatable :: err
      integer :: fmt_id, j, i, s1, s2
      real(dp) :: x, mu, f1, k1, f2, k2
      character(len=*), parameter :: names(0:1) = [character(len=14) :: "universal.csv", &
         & "universal.egwu"]
      call build_universal(model_egw, 0.0_dp, 0.6_dp, 54.0_dp, solver_options(), 2.0_dp, &
         & 8.0_dp, -6.0_dp, 20.0_dp, 1.0e-4_dp, u, err)
      call check(error, .not. allocated(err), "universal build failed")
      if (allocated(error)) return
      do fmt_id = format_csv, format_binary
         call write_universal(u, dir//"/"//trim(names(fmt_id)), fmt_id, err)
         call check(error, .not. allocated(err), "universal write failed")
         if (allocated(error)) return
         call read_universal(dir//"/"//trim(names(fmt_id)), back, err)
         if (allocated(err)) then
            call check(error, .false., "universal read failed: "//err%message)
            return
         end if
         call check(error, back%n_mu == u%n_mu .and. back%x_cut == u%x_cut .and. &
            & back%mu_max == u%mu_max, "universal header differs")
         if (allocated(error)) return
         do j = 1, u%n_mu
            call same_table(error, u%slices(j), back%slices(j))
            if (allocated(error)) return
         end do
         do i = 1, 50
            x = -2.0_dp + 22.0_dp*(i - 0.5_dp)/50
            mu = 2.0_dp*4.0_dp**((i - 0.5_dp)/50)
            call universal_eval(u, 2.0_dp, 3.0_dp, 1e-3_dp, mu, x*1e-3_dp, f1, k1, s1)
            call universal_eval(back, 2.0_dp, 3.0_dp, 1e-3_dp, mu, x*1e-3_dp, f2, k2, s2)
            call check(error, f1 == f2 .and. k1 == k2 .and. s1 == s2, "universal eval differs")
            if (allocated(error)) return
         end do
      end do
   end subroutine test_universal_round_trip

   ! ------------------------------------------------------------ bad files

   subroutine slurp(path, bytes)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: bytes
      integer :: unit
      integer(int64) :: n
      open (newunit=unit, file=path, access="stream", form="unformatted", status="old")
      inquire (unit=unit, size=n)
      allocate (character(len=int(n)) :: bytes)
      read (unit) bytes
      close (unit)
   end subroutine slurp

   subroutine spit(path, bytes)
      character(len=*), intent(in) :: path, bytes
      integer :: unit
      open (newunit=unit, file=path, access="stream", form="unformatted", status="replace")
      write (unit) bytes
      close (unit)
   end subroutine spit

   !> Reading must fail with egw_bad_file, a message containing `what`, and no table.
   subroutine expect_bad(error, path, what)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in) :: path, what
      type(force_table) :: t
      type(egw_error), allocatable :: err
      call read_table(path, t, err)
      call check(error, allocated(err), path//": bad file accepted")
      if (allocated(error)) return
      call check(error, err%stat == egw_bad_file, path//": status "//to_string(err%stat)// &
         & " ("//err%message//")")
      if (allocated(error)) return
      call check(error, index(err%message, what) > 0, "message '"//err%message// &
         & "' should mention '"//what//"'")
      if (allocated(error)) return
      call check(error, .not. allocated(t%delta) .and. .not. allocated(t%seg), &
         & "a partial table was returned")
   end subroutine expect_bad

   subroutine good_binary(error, bytes)
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable, intent(out) :: bytes
      type(force_table) :: t
      type(egw_error), allocatable :: err
      call hertz_table(t, error)
      if (allocated(error)) return
      call write_table(t, dir//"/good.egwt", format_binary, err)
      call check(error, .not. allocated(err), "write failed")
      if (allocated(error)) return
      call slurp(dir//"/good.egwt", bytes)
   end subroutine good_binary

   subroutine test_binary_truncated(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: b
      call good_binary(error, b)
      if (allocated(error)) return
      call spit(dir//"/trunc1.egwt", b(1:len(b) - 1))
      call expect_bad(error, dir//"/trunc1.egwt", "checksum")
      if (allocated(error)) return
      call spit(dir//"/trunc2.egwt", b(1:len(b)/2))
      call expect_bad(error, dir//"/trunc2.egwt", "")
      if (allocated(error)) return
      call spit(dir//"/trunc3.egwt", b(1:60))
      call expect_bad(error, dir//"/trunc3.egwt", "truncated")
      if (allocated(error)) return
      call spit(dir//"/trunc4.egwt", b(1:8))
      call expect_bad(error, dir//"/trunc4.egwt", "truncated")
   end subroutine test_binary_truncated

   subroutine test_binary_corrupted(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: b, c
      integer :: where
      call good_binary(error, b)
      if (allocated(error)) return
      ! one flipped bit in the arrays, in the header, in the checksum itself
      do where = 1, 3
         c = b
         select case (where)
         case (1); c(len(c)/2:len(c)/2) = achar(ieor(iachar(c(len(c)/2:len(c)/2)), 1))
         case (2); c(100:100) = achar(ieor(iachar(c(100:100)), 16))
         case (3); c(len(c):len(c)) = achar(ieor(iachar(c(len(c):len(c))), 128))
         end select
         call spit(dir//"/corrupt.egwt", c)
         call expect_bad(error, dir//"/corrupt.egwt", "checksum")
         if (allocated(error)) return
      end do
      ! the node count made inconsistent with the size, checksum recomputed
      c = b
      c(25:28) = transfer(7_int32, c(25:28))
      call reseal(c)
      call spit(dir//"/count.egwt", c)
      call expect_bad(error, dir//"/count.egwt", "n_nodes")
      if (allocated(error)) return
      ! a node made non-monotone, checksum recomputed: the content check catches it
      c = b
      c(145 + 8:152 + 8) = transfer(-1.0_dp, c(145:152))
      call reseal(c)
      call spit(dir//"/order.egwt", c)
      call expect_bad(error, dir//"/order.egwt", "increasing")
      if (allocated(error)) return
      c = b
      c(1:8) = "EGWTAB9X"
      call spit(dir//"/magic.egwt", c)
      call expect_bad(error, dir//"/magic.egwt", "not an egw table")
   end subroutine test_binary_corrupted

   !> Recompute the trailing FNV-1a checksum after an edit (as a writer of a newer or
   !> foreign file would).
   subroutine reseal(c)
      character(len=*), intent(inout) :: c
      integer(int64) :: h
      integer(int32) :: v
      h = fnv1a32(c(1:len(c) - 4))
      if (h >= 2147483648_int64) h = h - 4294967296_int64
      v = int(h, int32)
      c(len(c) - 3:len(c)) = transfer(v, c(1:4))
   end subroutine reseal

   subroutine test_binary_version(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: b, c
      call good_binary(error, b)
      if (allocated(error)) return
      c = b
      c(9:12) = transfer(2_int32, c(9:12))
      call reseal(c)
      call spit(dir//"/v2.egwt", c)
      call expect_bad(error, dir//"/v2.egwt", "version 2")
      if (allocated(error)) return
      c = b
      c(13:16) = transfer(int(z'04030201', int32), c(13:16))
      call reseal(c)
      call spit(dir//"/endian.egwt", c)
      call expect_bad(error, dir//"/endian.egwt", "byte order")
   end subroutine test_binary_version

   subroutine test_csv_bad(error)
      type(error_type), allocatable, intent(out) :: error
      type(force_table) :: t
      type(egw_error), allocatable :: err
      character(len=:), allocatable :: b, c
      integer :: p
      call hertz_table(t, error)
      if (allocated(error)) return
      call write_table(t, dir//"/good.csv", format_csv, err)
      call check(error, .not. allocated(err), "write failed")
      if (allocated(error)) return
      call slurp(dir//"/good.csv", b)
      ! any change under the checksum line (here a digit of the last row) is caught
      p = index(b, "# end of table") - 5
      c = b
      c(p:p) = merge("1", "2", c(p:p) /= "1")
      call spit(dir//"/edited.csv", c)
      call expect_bad(error, dir//"/edited.csv", "checksum mismatch")
      if (allocated(error)) return
      ! the other checks, on files without their checksum line (as edited by hand)
      b = b(1:index(b, "# fnv1a32") - 1)
      ! cut inside the last number of the last row: the end line is missing
      p = index(b, "# end of table") - 5
      call spit(dir//"/cut.csv", b(1:p))
      call expect_bad(error, dir//"/cut.csv", "truncated")
      if (allocated(error)) return
      ! drop a whole data row (the end line's count no longer matches)
      ! (the first data row follows the last metadata line, "# interpolation = ...")
      p = index(b, "# interpolation")
      p = p + index(b(p:), new_line("a"))
      c = b(1:p - 1)//b(p + index(b(p:), new_line("a")):)
      call spit(dir//"/row.csv", c)
      call expect_bad(error, dir//"/row.csv", "end line")
      if (allocated(error)) return
      ! a garbled number
      c = b
      c(p + 3:p + 3) = "x"
      call spit(dir//"/garbled.csv", c)
      call expect_bad(error, dir//"/garbled.csv", "cannot read")
      if (allocated(error)) return
      ! a missing header key
      p = index(b, "# rel_tol")
      c = b(1:p - 1)//"# rel_tel"//b(p + 9:)
      call spit(dir//"/key.csv", c)
      call expect_bad(error, dir//"/key.csv", "rel_tol")
   end subroutine test_csv_bad

   !> Every single-bit flip of a checksummed CSV file is refused (1000 of them, spread
   !> over the file); without its checksum line the file is still read, bit-identical,
   !> and flagged checksum_missing; a written or built table is not flagged.
   subroutine test_csv_checksum(error)
      type(error_type), allocatable, intent(out) :: error
      type(force_table) :: t, back
      type(egw_error), allocatable :: err
      character(len=:), allocatable :: b, c
      integer :: i, pos, bit, accepted
      call hertz_table(t, error)
      if (allocated(error)) return
      call write_table(t, dir//"/sum.csv", format_csv, err)
      call slurp(dir//"/sum.csv", b)
      accepted = 0
      do i = 1, 1000
         pos = 1 + mod(7919*i, len(b))
         bit = mod(i, 7)
         c = b
         c(pos:pos) = achar(ieor(iachar(c(pos:pos)), 2**bit))
         call spit(dir//"/flip.csv", c)
         call read_table(dir//"/flip.csv", back, err)
         if (.not. allocated(err)) accepted = accepted + 1
      end do
      call check(error, accepted, 0, "bit flips accepted")
      if (allocated(error)) return
      call read_table(dir//"/sum.csv", back, err)
      call check(error, .not. allocated(err) .and. .not. back%checksum_missing, &
         & "a checksummed file is flagged or refused")
      if (allocated(error)) return
      call spit(dir//"/nosum.csv", b(1:index(b, "# fnv1a32") - 1))
      call read_table(dir//"/nosum.csv", back, err)
      call check(error, .not. allocated(err), "a file without checksum line is refused")
      if (allocated(error)) return
      call check(error, back%checksum_missing, "a file without checksum line is not flagged")
      if (allocated(error)) return
      call check(error, all(back%force == t%force) .and. all(back%stiffness == t%stiffness), &
         & "a file without checksum line reads different numbers")
      if (allocated(error)) return
      call check(error, .not. t%checksum_missing, "a built table is flagged")
   end subroutine test_csv_checksum

   !> Hand-edited CSV files (no checksum line) with insane values are refused, naming
   !> what is wrong: a negative force, a negative stiffness, a force spike (1e300, the
   !> next node then lies below it), an infinite stiffness, NaN or out-of-range metadata.
   subroutine test_csv_sanity(error)
      type(error_type), allocatable, intent(out) :: error
      type(force_table) :: t
      type(egw_error), allocatable :: err
      character(len=:), allocatable :: b
      call hertz_table(t, error)
      if (allocated(error)) return
      call write_table(t, dir//"/sane.csv", format_csv, err)
      call slurp(dir//"/sane.csv", b)
      b = b(1:index(b, "# fnv1a32") - 1)
      call edited_row(error, b, 5, 2, "-1.0E-003", "negative force")
      if (allocated(error)) return
      call edited_row(error, b, 5, 3, "-1.0E+010", "negative stiffness")
      if (allocated(error)) return
      call edited_row(error, b, 5, 2, "1.0E+300", "must not decrease")
      if (allocated(error)) return
      call edited_row(error, b, 5, 3, "Infinity", "not finite")
      if (allocated(error)) return
      call edited_row(error, b, 5, 4, "-2.0E-012", "negative energy")
      if (allocated(error)) return
      call edited_row(error, b, 5, 5, "-1.0E-003", "negative contact radius")
      if (allocated(error)) return
      call edited_row(error, b, 5, 1, "1.0E+000", "strictly increasing")
      if (allocated(error)) return
      call edited_key(error, b, "rel_tol", "NaN", "not a finite number")
      if (allocated(error)) return
      call edited_key(error, b, "rel_tol", "0.5", "must lie in (0, 0.1]")
      if (allocated(error)) return
      call edited_key(error, b, "reference_force", "-1.0", "reference_force")
      if (allocated(error)) return
      call edited_key(error, b, "max_force_error", "-1.0", "max_force_error")
   end subroutine test_csv_sanity

   !> Data row `row` of CSV text b with field `field` replaced by value: refused, the
   !> message mentioning what.
   subroutine edited_row(error, b, row, field, value, what)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in) :: b, value, what
      integer, intent(in) :: row, field
      character(len=:), allocatable :: c, line
      integer :: start, stop, i, f0, f1
      start = index(b, "# interpolation")
      start = start + index(b(start:), new_line("a"))
      do i = 2, row
         start = start + index(b(start:), new_line("a"))
      end do
      stop = start + index(b(start:), new_line("a")) - 2
      line = b(start:stop)//","
      f0 = 1
      do i = 2, field
         f0 = f0 + index(line(f0:), ",")
      end do
      f1 = f0 + index(line(f0:), ",") - 2
      line = line(1:f0 - 1)//value//line(f1 + 1:len(line) - 1)
      c = b(1:start - 1)//line//b(stop + 1:)
      call spit(dir//"/edited_row.csv", c)
      call expect_bad(error, dir//"/edited_row.csv", what)
   end subroutine edited_row

   subroutine edited_key(error, b, key, value, what)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in) :: b, key, value, what
      integer :: start, stop
      start = index(b, "# "//key//" = ")
      stop = start + index(b(start:), new_line("a")) - 2
      call spit(dir//"/edited_key.csv", b(1:start - 1)//"# "//key//" = "//value// &
         & b(stop + 1:))
      call expect_bad(error, dir//"/edited_key.csv", what)
   end subroutine edited_key

   !> Binary files with a valid checksum but insane numbers are refused: a negative
   !> force, an infinite stiffness, a NaN rel_tol, a negative energy or contact radius.
   subroutine test_binary_sanity(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=:), allocatable :: b
      integer :: n
      call good_binary(error, b)
      if (allocated(error)) return
      n = (len(b) - 144 - 4)/40
      ! layout (doc/formats.md): 144 header bytes (rel_tol at byte 89), then the arrays
      ! delta, force, stiffness, energy, contact_radius of n doubles each
      call patched(error, b, 145 + 8*n + 8*(n/2), -1.0_dp, "negative force")
      if (allocated(error)) return
      call patched(error, b, 145 + 16*n + 8*(n/2), ieee_value(1.0_dp, ieee_positive_inf), &
         & "not finite")
      if (allocated(error)) return
      call patched(error, b, 89, ieee_value(1.0_dp, ieee_quiet_nan), "rel_tol")
      if (allocated(error)) return
      call patched(error, b, 145 + 24*n + 8*(n/2), -1.0_dp, "negative energy")
      if (allocated(error)) return
      call patched(error, b, 145 + 32*n + 8*(n/2), -1.0_dp, "negative contact radius")
   end subroutine test_binary_sanity

   !> Files whose checksum is valid (written by the writer itself, which computes it) but
   !> whose values break what a table must satisfy are refused, naming what is wrong
   !> (issue 22: a universal slice with stiffness 1e300 evaluated to a force of -2.4e297
   !> with status OK): a stiffness far above the force differences (1-D, universal slice,
   !> a hysteresis loading curve in its ln P tail), energies that do not integrate the
   !> forces, a hysteresis gap slope that would carry a curve far outside [0, 1]. Built
   !> tables keep end slopes within 1.43 times the secant's (measured, bound 10) and gap
   !> rises within 0.36 (bound 2): exact refusals, no tolerance involved.
   subroutine test_crafted_values(error)
      type(error_type), allocatable, intent(out) :: error
      type(force_table) :: good, t
      type(universal_table) :: u
      type(hysteresis_table) :: h, hc
      type(egw_error), allocatable :: err
      integer :: n, fmt_id
      character(len=*), parameter :: ext(0:1) = [".csv ", ".egwt"]
      call hertz_table(good, error)
      if (allocated(error)) return
      n = size(good%delta)
      do fmt_id = format_csv, format_binary
         t = good
         t%stiffness(n/2) = 1.0e300_dp
         call crafted(t, "stiff"//trim(ext(fmt_id)), fmt_id, "inconsistent with the forces")
         if (allocated(error)) return
         t = good
         t%energy(n/2) = t%energy(n/2 + 1)   ! non-decreasing, but not the forces' integral
         call crafted(t, "energy"//trim(ext(fmt_id)), fmt_id, "energy rise")
         if (allocated(error)) return
         t = good
         t%energy = t%energy + 1.0_dp
         call crafted(t, "energy1"//trim(ext(fmt_id)), fmt_id, "energy at the cut-off")
         if (allocated(error)) return
      end do
      ! a universal slice
      call build_universal(model_hertz, 0.0_dp, 0.6_dp, 54.0_dp, solver_options(), 1.0_dp, &
         & 2.0_dp, -1.0_dp, 10.0_dp, 1e-4_dp, u, err)
      call check(error, .not. allocated(err), "universal build")
      if (allocated(error)) return
      n = size(u%slices(2)%delta)
      u%slices(2)%stiffness(n/2) = 1.0e300_dp
      call write_universal(u, dir//"/crafted.egwu", format_binary, err)
      call check(error, .not. allocated(err), "crafted universal write")
      if (allocated(error)) return
      block
         type(universal_table) :: back
         call read_universal(dir//"/crafted.egwu", back, err)
         call check(error, allocated(err), "crafted universal slice accepted")
         if (allocated(error)) return
         call check(error, err%stat == egw_bad_file .and. index(err%message, "slice 2: ") &
            & > 0 .and. index(err%message, "stiffness") > 0, "message: "//err%message)
         if (allocated(error)) return
      end block
      ! a hysteresis table: its loading curve in the ln P tail (interval 1), a gap slope
      call build_hysteresis(contact_params(model=model_epgw, sigma=1.0_dp, mu=4.0_dp, &
         & psi=2.0_dp), solver_options(), -2.0_dp, 4.0_dp, 1.0e-2_dp, h, err)
      call check(error, .not. allocated(err), "hysteresis build")
      if (allocated(error)) return
      call check(error, h%loading%n_log > 0, "the loading curve has ln P intervals")
      if (allocated(error)) return
      hc = h
      hc%loading%stiffness(2) = 1.0e300_dp
      call crafted_hysteresis(hc, "loading curve: nodes 1, 2")
      if (allocated(error)) return
      hc = h
      hc%slope(2, 2) = 1.0e300_dp
      call crafted_hysteresis(hc, "slope")
      if (allocated(error)) return
      ! audit22: the loading curve's last force x1e6 (increasing, slopes below 10x the
      ! secant's, energy within the bounds that grow with the jump) was accepted; with its
      ! stiffness set to twice the new secant's the slopes fit, but the cubic's integral is
      ! not the stored energy
      n = size(h%loading%delta)
      hc = h
      hc%loading%force(n) = 1.0e6_dp*hc%loading%force(n)
      call crafted_hysteresis(hc, "loading curve: nodes "//to_string(n - 1)//", "// &
         & to_string(n)//": the forces")
      if (allocated(error)) return
      hc%loading%stiffness(n) = 2*(hc%loading%force(n) - hc%loading%force(n - 1))/ &
         & (hc%loading%delta(n) - hc%loading%delta(n - 1))
      call crafted_hysteresis(hc, "loading curve: nodes "//to_string(n - 1)//", "// &
         & to_string(n)//": energy rise")
   contains
      !> t written (the writer's checksum) as name in format fmt_id: refused, naming what.
      subroutine crafted(t, name, fmt_id, what)
         type(force_table), intent(in) :: t   !< its nodes (the writer reads only these)
         character(len=*), intent(in) :: name, what
         integer, intent(in) :: fmt_id
         call write_table(t, dir//"/crafted_"//name, fmt_id, err)
         if (allocated(err)) then
            call check(error, .false., "crafted write "//name//": "//err%message)
            return
         end if
         call expect_bad(error, dir//"/crafted_"//name, what)
      end subroutine crafted
      !> hc written as CSV and binary: both refused, naming what.
      subroutine crafted_hysteresis(hc, what)
         type(hysteresis_table), intent(in) :: hc
         character(len=*), intent(in) :: what
         type(hysteresis_table) :: back
         integer :: f
         do f = format_csv, format_binary
            call write_hysteresis(hc, dir//"/crafted_hyst"//trim(ext(f)), f, err)
            call check(error, .not. allocated(err), "crafted hysteresis write")
            if (allocated(error)) return
            call read_hysteresis(dir//"/crafted_hyst"//trim(ext(f)), back, err)
            call check(error, allocated(err), "crafted hysteresis accepted ("//what//")")
            if (allocated(error)) return
            call check(error, err%stat == egw_bad_file .and. index(err%message, what) > 0, &
               & "message '"//err%message//"' should mention '"//what//"'")
            if (allocated(error)) return
         end do
      end subroutine crafted_hysteresis
   end subroutine test_crafted_values

   !> Issue 33's crafted files: a valid E-GW binary table (doc/formats.md §3) with n_log
   !> (int32 at offset 28) lowered to 0, 1 and 2, so that separated-tail intervals are
   !> read as P instead of ln P, and one with the last node's force (offset 144 + 8 n +
   !> 8 (n - 1)) set to 1e300 (still increasing, so the older checks passed it; since
   !> audit23 with its stiffness and energy made to match, as the slope and energy checks
   !> refuse the force alone, as they refuse audit22's force x1e6 below); each
   !> with its FNV-1a checksum recomputed here from the documented rule (not the
   !> writer's code). Each is refused with egw_bad_file naming what is wrong: a negative
   !> interpolated force between two named nodes, and the node's force above 1e200.
   !> The unpatched bytes, re-checksummed the same way, still read (the checksum code
   !> here is right, and the new checks pass a built table).
   subroutine test_crafted_tail(error)
      type(error_type), allocatable, intent(out) :: error
      type(force_table) :: t, back
      type(egw_error), allocatable :: err
      character(len=:), allocatable :: b, c
      integer :: n, n_log
      real(dp) :: h, k_n
      call rough_table(t, error)
      if (allocated(error)) return
      call check(error, t%n_log > 3, "the E-GW table has more than 3 ln P intervals")
      if (allocated(error)) return
      call write_table(t, dir//"/tail.egwt", format_binary, err)
      call check(error, .not. allocated(err), "write")
      if (allocated(error)) return
      call slurp(dir//"/tail.egwt", b)
      n = size(t%delta)
      c = b
      call resum(c)
      call spit(dir//"/tail_resum.egwt", c)
      call read_table(dir//"/tail_resum.egwt", back, err)
      call check(error, .not. allocated(err), "the re-checksummed valid table is refused")
      if (allocated(error)) return
      do n_log = 0, 2
         c = b
         c(29:32) = transfer(int(n_log, int32), c(29:32))
         call resum(c)
         call spit(dir//"/tail_nlog.egwt", c)
         call expect_bad(error, dir//"/tail_nlog.egwt", "the force interpolated between them "// &
            & "falls to -")
         if (allocated(error)) return
      end do
      ! the last force 1e300 with a stiffness (twice the secant's) and an energy (the
      ! cubic's integral) to match: only the 1e200 bound refuses it (the slope and energy
      ! checks refuse the force alone)
      h = t%delta(n) - t%delta(n - 1)
      k_n = 2*(1.0e300_dp - t%force(n - 1))/h
      c = b
      c(145 + 16*n - 8:145 + 16*n - 1) = transfer(1.0e300_dp, c(1:8))
      c(145 + 24*n - 8:145 + 24*n - 1) = transfer(k_n, c(1:8))
      c(145 + 32*n - 8:145 + 32*n - 1) = transfer(t%energy(n - 1) + h*(t%force(n - 1) + &
         & 1.0e300_dp)/2 + h*h*(t%stiffness(n - 1) - k_n)/12, c(1:8))
      call resum(c)
      call spit(dir//"/tail_absurd.egwt", c)
      call expect_bad(error, dir//"/tail_absurd.egwt", "node "//to_string(n)//": force "// &
         & format_real(1.0e300_dp)//" above")
      if (allocated(error)) return
      ! audit22's forged jump: the last force x1e6 (8 bytes at 145 + 16 n - 8), still
      ! increasing and far below 1e200: a loading force has no stiffness peak inside an
      ! interval (built tables: larger end slope >= 1.000 secant, bound 1/10); with the
      ! last stiffness twice the new secant (at 145 + 24 n - 8) the slopes fit, but the energy
      ! is not the integral of the force between the nodes (built: < 6e-12 of h P off,
      ! bound rel_tol = 1e-4). Both were read on main.
      c = b
      c(145 + 16*n - 8:145 + 16*n - 1) = transfer(1.0e6_dp*t%force(n), c(1:8))
      call resum(c)
      call spit(dir//"/tail_jump.egwt", c)
      call expect_bad(error, dir//"/tail_jump.egwt", "nodes "//to_string(n - 1)//", "// &
         & to_string(n)//": the forces")
      if (allocated(error)) return
      c(145 + 24*n - 8:145 + 24*n - 1) = transfer(2*(1.0e6_dp*t%force(n) - t%force(n - 1))/ &
         & (t%delta(n) - t%delta(n - 1)), c(1:8))
      call resum(c)
      call spit(dir//"/tail_jump2.egwt", c)
      call expect_bad(error, dir//"/tail_jump2.egwt", "nodes "//to_string(n - 1)//", "// &
         & to_string(n)//": energy rise")
   contains
      !> The checksum of doc/formats.md §3: FNV-1a 32 over every byte before it, stored as
      !> a little-endian uint32 in the last 4 bytes.
      subroutine resum(bytes)
         character(len=*), intent(inout) :: bytes
         integer(int64) :: h
         integer :: k, j
         h = 2166136261_int64
         do k = 1, len(bytes) - 4
            h = ieor(h, int(ichar(bytes(k:k)), int64))
            h = iand(h*16777619_int64, 4294967295_int64)
         end do
         do j = 0, 3
            bytes(len(bytes) - 3 + j:len(bytes) - 3 + j) = achar(int(iand(shiftr(h, 8*j), &
               & 255_int64)))
         end do
      end subroutine resum
   end subroutine test_crafted_tail

   !> b with the double at byte pos set to x and the checksum recomputed: refused.
   subroutine patched(error, b, pos, x, what)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in) :: b, what
      integer, intent(in) :: pos
      real(dp), intent(in) :: x
      character(len=:), allocatable :: c
      integer(int64) :: h
      integer(int32) :: sum32
      c = b
      c(pos:pos + 7) = transfer(x, c(pos:pos + 7))
      h = fnv1a32(c(1:len(c) - 4))
      if (h >= 2147483648_int64) h = h - 4294967296_int64
      sum32 = int(h, int32)
      c(len(c) - 3:) = transfer(sum32, c(1:4))
      call spit(dir//"/patched.egwt", c)
      call expect_bad(error, dir//"/patched.egwt", what)
   end subroutine patched

   !> A write that fails halfway (a NaN found while writing rows) or cannot start (no such
   !> directory) leaves the existing file byte-for-byte intact and no temporary behind.
   subroutine test_atomic(error)
      type(error_type), allocatable, intent(out) :: error
      type(force_table) :: t
      type(egw_error), allocatable :: err
      character(len=:), allocatable :: before, after
      logical :: exists
      integer :: fmt_id
      character(len=*), parameter :: path = dir//"/atomic.out"
      call hertz_table(t, error)
      if (allocated(error)) return
      do fmt_id = format_csv, format_calculix
         call write_table(t, path, fmt_id, err)
         call check(error, .not. allocated(err), "first write failed")
         if (allocated(error)) return
         call slurp(path, before)
         block
            type(force_table) :: broken
            broken = t
            broken%force(size(broken%force)/2) = ieee_value(1.0_dp, ieee_quiet_nan)
            call table_prepare(broken)
            call write_table(broken, path, fmt_id, err)
         end block
         call check(error, allocated(err), "writing a NaN must fail (format "// &
            & to_string(fmt_id)//")")
         if (allocated(error)) return
         call slurp(path, after)
         call check(error, before == after, "old file changed by a failed write (format "// &
            & to_string(fmt_id)//")")
         if (allocated(error)) return
         inquire (file=path//".egw-tmp", exist=exists)
         call check(error, .not. exists, "temporary file left behind")
         if (allocated(error)) return
      end do
      call write_table(t, dir//"/no/such/dir/t.csv", format_csv, err)
      call check(error, allocated(err), "write into a missing directory must fail")
      if (allocated(error)) return
      call check(error, err%stat == egw_io_error, "status of a failed open: "//err%message)
   end subroutine test_atomic

   ! ------------------------------------------------------------ LAMMPS

   !> Parse section `keyword` of a LAMMPS table file: N, rlo, rhi and the rows.
   subroutine read_lammps_section(path, keyword, n, rlo, rhi, r, e, f, comments, ok)
      character(len=*), intent(in) :: path, keyword
      integer, intent(out) :: n
      real(dp), intent(out) :: rlo, rhi
      real(dp), allocatable, intent(out) :: r(:), e(:), f(:)
      character(len=:), allocatable, intent(out) :: comments
      logical, intent(out) :: ok
      integer :: unit, ios, i, idx
      character(len=512) :: line
      character(len=8) :: nkey, rkey
      ok = .false.
      comments = ""
      open (newunit=unit, file=path, status="old", action="read")
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) then
            close (unit)
            return
         end if
         if (line(1:1) == "#") then
            comments = comments//trim(line)//new_line("a")
         else if (trim(line) == keyword) then
            exit
         end if
      end do
      read (unit, *) nkey, n, rkey, rlo, rhi
      read (unit, '(a)') line
      if (nkey /= "N" .or. rkey /= "R" .or. len_trim(line) /= 0) then
         close (unit)
         return
      end if
      allocate (r(n), e(n), f(n))
      do i = 1, n
         read (unit, *, iostat=ios) idx, r(i), e(i), f(i)
         if (ios /= 0 .or. idx /= i) then
            close (unit)
            return
         end if
      end do
      close (unit)
      ok = .true.
   end subroutine read_lammps_section

   !> Two sections: one built from particle radii R1 = R2 = 1 (R1 + R2 = 2), one from R
   !> alone (distances for R1 = R2 = 2R, sum 4R = 2 too: R = 0.5). Checks:
   !> r uniform from rlo to rhi; force = P_Hertz(R1 + R2 - r) within 1.5 rel_tol (table
   !> accuracy; the last point, at the cut-off, within 1.5 rel_tol * P_ref);
   !> F = -dE/dr: E(r_i) - E(r_i+1) equals the trapezoid of F within h^3/12 max|F''|
   !> (F'' = E sqrt(R)/sqrt(delta) for Hertz, largest at the smaller overlap, or the
   !> interpolant's own, 1.5x its second differences, where larger: E integrates the
   !> table's cubics) plus the rounding of E (17 digits).
   subroutine test_lammps(error)
      type(error_type), allocatable, intent(out) :: error
      type(force_table) :: t1, t2
      type(egw_error), allocatable :: err
      integer :: n, i, s
      real(dp) :: rlo, rhi, h, dlo, bound, pref, curv
      real(dp), allocatable :: r(:), e(:), f(:)
      character(len=:), allocatable :: comments
      logical :: ok
      character(len=*), parameter :: path = dir//"/hertz.table"
      call hertz_table(t1, error)
      if (allocated(error)) return
      call table_set_radii(t1, 1.0_dp, 1.0_dp, err)
      call check(error, .not. allocated(err), "set radii")
      if (allocated(error)) return
      t2 = t1
      t2%radius_sum = 0
      call write_lammps([t1, t2], path, err)
      call check(error, .not. allocated(err), "LAMMPS write failed")
      if (allocated(error)) return
      pref = t1%reference_force
      do s = 1, 2
         call read_lammps_section(path, "EGW_"//to_string(s), n, rlo, rhi, r, e, f, &
            & comments, ok)
         call check(error, ok, "section EGW_"//to_string(s)//" not parsed")
         if (allocated(error)) return
         if (s == 2) then
            call check(error, index(comments, "two equal spheres") > 0, &
               & "equivalent-radius section must say so")
            if (allocated(error)) return
         end if
         call check(error, rlo, 2.0_dp - t1%delta_max, "rlo", thr=1e-15_dp, rel=.true.)
         if (allocated(error)) return
         call check(error, rhi, 2.0_dp - t1%cutoff, "rhi", thr=1e-15_dp, rel=.true.)
         if (allocated(error)) return
         h = (rhi - rlo)/(n - 1)
         do i = 1, n
            call check(error, r(i), rlo + (i - 1)*h, "r uniform", thr=4e-16_dp*2, rel=.true.)
            if (allocated(error)) return
            call check(error, abs(f(i) - p_hertz(2.0_dp, 0.5_dp, 2.0_dp - r(i))) <= &
               & 1.5_dp*tol*max(p_hertz(2.0_dp, 0.5_dp, 2.0_dp - r(i)), &
               & merge(pref, 0.0_dp, i == n)) + 4*epsilon(1.0_dp)*pref, &
               & "force at r = "//format_real(r(i)))
            if (allocated(error)) return
         end do
         do i = 1, n - 1
            dlo = 2.0_dp - r(i + 1)
            ! F'' of Hertz, or of the table's cubics where they bend more (the energy is
            ! the exact integral of the interpolant; its F'' from second differences)
            curv = 2.0_dp*sqrt(0.5_dp)/sqrt(dlo)*1.01_dp
            if (i > 1 .and. i < n - 1) curv = max(curv, 1.5_dp*max(abs(f(i - 1) - 2*f(i) + &
               & f(i + 1)), abs(f(i) - 2*f(i + 1) + f(i + 2)))/h**2)
            bound = h**3/12*curv + 4*epsilon(1.0_dp)*e(1)
            call check(error, abs((e(i) - e(i + 1)) - h*(f(i) + f(i + 1))/2) <= bound, &
               & "F = -dE/dr violated between r = "//format_real(r(i))//" and "// &
               & format_real(r(i + 1)))
            if (allocated(error)) return
         end do
         call check(error, e(n) == 0.0_dp, "energy is zero at the cut-off")
         if (allocated(error)) return
      end do
   end subroutine test_lammps

   !> E-GW (contract only: any table): F = -dE/dr across the log tail and the contact
   !> onset. The energy column is the exact integral of the interpolated force, so the
   !> trapezoid rule of the force column matches the energy difference to h^3/12 |F''|;
   !> |F''| is bounded by twice the largest second difference of F around the interval
   !> (divided by h^2), plus the 17-digit rounding of E.
   subroutine test_lammps_rough(error)
      type(error_type), allocatable, intent(out) :: error
      type(force_table) :: t
      type(egw_error), allocatable :: err
      integer :: n, i
      real(dp) :: rlo, rhi, h, f2, bound
      real(dp), allocatable :: r(:), e(:), f(:)
      character(len=:), allocatable :: comments
      logical :: ok
      character(len=*), parameter :: path = dir//"/egw.table"
      call rough_table(t, error)
      if (allocated(error)) return
      call write_lammps([t], path, err)
      call check(error, .not. allocated(err), "LAMMPS write failed")
      if (allocated(error)) return
      call read_lammps_section(path, "EGW_1", n, rlo, rhi, r, e, f, comments, ok)
      call check(error, ok, "section not parsed")
      if (allocated(error)) return
      call check(error, index(comments, "two equal spheres") > 0, "equal-spheres note")
      if (allocated(error)) return
      call check(error, .not. has_units_tag(path), "no UNITS: tag unless requested "// &
         & "(LAMMPS takes it as a unit style)")
      if (allocated(error)) return
      h = (rhi - rlo)/(n - 1)
      do i = 2, n - 2
         f2 = 2*max(abs(f(i + 1) - 2*f(i) + f(i - 1)), abs(f(i + 2) - 2*f(i + 1) + f(i)))/h**2
         bound = h**3/12*f2 + 4*epsilon(1.0_dp)*e(1)
         call check(error, abs((e(i) - e(i + 1)) - h*(f(i) + f(i + 1))/2) <= bound, &
            & "F = -dE/dr violated at r = "//format_real(r(i)))
         if (allocated(error)) return
      end do
   end subroutine test_lammps_rough

   !> Does any line of the file carry LAMMPS's "UNITS:" tag (case-sensitive, as LAMMPS)?
   logical function has_units_tag(path) result(found)
      character(len=*), intent(in) :: path
      integer :: unit, ios
      character(len=512) :: line
      found = .false.
      open (newunit=unit, file=path, status="old", action="read")
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         found = found .or. index(line, "UNITS:") > 0
      end do
      close (unit)
   end function has_units_tag

   !> Requested units: the first line is "# DATE: ... UNITS: si ..." (what LAMMPS reads);
   !> a units string that is no LAMMPS style is refused and nothing written.
   subroutine test_lammps_units(error)
      type(error_type), allocatable, intent(out) :: error
      type(force_table) :: t
      type(egw_error), allocatable :: err
      integer :: unit
      character(len=512) :: line
      logical :: exists
      character(len=*), parameter :: path = dir//"/units.table"
      call hertz_table(t, error)
      if (allocated(error)) return
      call write_lammps([t], path, err, units="si")
      call check(error, .not. allocated(err), "LAMMPS write with units failed")
      if (allocated(error)) return
      open (newunit=unit, file=path, status="old", action="read")
      read (unit, '(a)') line
      close (unit)
      call check(error, line(1:8) == "# DATE: " .and. index(line, " UNITS: si ") > 0, &
         & "first line must carry UNITS: si, got: "//trim(line))
      if (allocated(error)) return
      call write_lammps([t], dir//"/units_bad.table", err, units="S I")
      inquire (file=dir//"/units_bad.table", exist=exists)
      call check(error, allocated(err) .and. .not. exists, "bad units must be refused")
   end subroutine test_lammps_units

   ! ------------------------------------------------------------ CalculiX

   subroutine read_calculix(path, p, x, comments, ok)
      character(len=*), intent(in) :: path
      real(dp), allocatable, intent(out) :: p(:), x(:)
      character(len=:), allocatable, intent(out) :: comments
      logical, intent(out) :: ok
      integer :: unit, ios, n
      character(len=256) :: line
      real(dp) :: a, b
      ok = .false.
      comments = ""
      allocate (p(0), x(0))
      open (newunit=unit, file=path, status="old", action="read")
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) then
            close (unit)
            return
         end if
         if (line(1:2) == "**") comments = comments//trim(line)//new_line("a")
         if (trim(line) == "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR") exit
      end do
      n = 0
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         read (line, *, iostat=ios) a, b
         if (ios /= 0) then
            close (unit)
            return
         end if
         p = [p, a]
         x = [x, b]
         n = n + 1
      end do
      close (unit)
      ok = n >= 2
   end subroutine read_calculix

   !> Force vs overclosure = delta: first pair at zero force at the cut-off, overclosure
   !> strictly increasing, at most 200 pairs (CalculiX's limit). A Hertz table at
   !> rel_tol = 1e-6 over four decades of delta cannot be followed that closely by 200
   !> linear pieces: the writer reports the error achieved, and linear interpolation
   !> between pairs must be within that + 1.5 rel_tol (table accuracy) of the Hertz force.
   !> The achieved error must be near the optimum: for P ~ delta^1.5 the best 199
   !> intervals are geometric with ratio q = (delta_max/delta_c)^(1/199), midpoint error
   !> (3/32) ln(q)^2 (leading order); 10 % slack for the discrete placement. Positions
   !> have 13 significant digits (CalculiX's 20-character fields): 1e-12 relative.
   !> A 1e-3 table fits in 200 pairs and must be followed within 2.5 rel_tol.
   subroutine test_calculix_sphere(error)
      type(error_type), allocatable, intent(out) :: error
      type(force_table) :: t
      type(egw_error), allocatable :: err
      real(dp), allocatable :: p(:), x(:)
      character(len=:), allocatable :: comments
      logical :: ok
      integer :: i
      real(dp) :: xm, pm, achieved, optimum
      call hertz_table(t, error)
      if (allocated(error)) return
      call write_table(t, dir//"/hertz.inp", format_calculix, err)
      call check(error, .not. allocated(err), "CalculiX write failed")
      if (allocated(error)) return
      call write_calculix_sphere(t, dir//"/hertz2.inp", err, max_error=achieved)
      call check(error, .not. allocated(err), "CalculiX write failed")
      if (allocated(error)) return
      call read_calculix(dir//"/hertz.inp", p, x, comments, ok)
      call check(error, ok, "CalculiX file not parsed")
      if (allocated(error)) return
      call check(error, size(x) <= 200, "more than 200 pairs: "//to_string(size(x)))
      if (allocated(error)) return
      call check(error, index(comments, "max error achieved = ") > 0 .and. &
         & index(comments, "WARNING") > 0, "header must give the error and warn")
      if (allocated(error)) return
      call check(error, p(1) == 0.0_dp .and. abs(x(1) - t%cutoff) <= 1e-12_dp*t%cutoff, &
         & "first pair (0, delta_c)")
      if (allocated(error)) return
      call check(error, all(x(2:) > x(:size(x) - 1)), "overclosure not increasing")
      if (allocated(error)) return
      call check(error, abs(x(size(x)) - t%delta_max) <= 1e-12_dp*t%delta_max, "last overclosure")
      if (allocated(error)) return
      optimum = 3.0_dp/32*(log(t%delta_max/t%cutoff)/199)**2
      call check(error, achieved <= 1.1_dp*optimum, "achieved error "// &
         & format_real(achieved)//" far above the optimum "//format_real(optimum))
      if (allocated(error)) return
      do i = 2, size(x) - 1
         xm = 0.5_dp*(x(i) + x(i + 1))
         pm = 0.5_dp*(p(i) + p(i + 1))
         ! the achieved error is relative to max(P, rel_tol P_ref) (the writer's metric)
         call check(error, abs(pm - p_hertz(2.0_dp, 0.5_dp, xm)) <= (achieved + &
            & 1.5_dp*tol + 1e-11_dp)*max(p_hertz(2.0_dp, 0.5_dp, xm), tol*t%reference_force), &
            & "interpolated force at "//format_real(xm))
         if (allocated(error)) return
      end do
      call build_table(contact_params(model=model_hertz, radius=0.5_dp, modulus=2.0_dp), &
         & solver_options(), 0.0_dp, 1.0e-2_dp, 1.0e-3_dp, t, err)
      call check(error, .not. allocated(err), "Hertz 1e-3 table build failed")
      if (allocated(error)) return
      call write_calculix_sphere(t, dir//"/hertz3.inp", err, max_error=achieved)
      call read_calculix(dir//"/hertz3.inp", p, x, comments, ok)
      call check(error, ok .and. size(x) <= 200 .and. achieved <= 1.0e-3_dp .and. &
         & index(comments, "WARNING") == 0, "1e-3 curve must fit in 200 pairs")
      if (allocated(error)) return
      do i = 2, size(x) - 1
         xm = 0.5_dp*(x(i) + x(i + 1))
         pm = 0.5_dp*(p(i) + p(i + 1))
         call check(error, pm, p_hertz(2.0_dp, 0.5_dp, xm), "interpolated force at "// &
            & format_real(xm), thr=2.5_dp*1.0e-3_dp, rel=.true.)
         if (allocated(error)) return
      end do
   end subroutine test_calculix_sphere

   !> Rough flat (contract of flat_pressure only): pairs are p_G(-overclosure) to 13
   !> digits (CalculiX's 20-character fields: 5e-13 each for p and the overclosure,
   !> which moves p_G by up to |d ln p_G/dd| |d| 5e-13 <~ 1e-11 here), the first at zero pressure where p_G <= rel_tol p_G(0), overclosure
   !> increasing, linear interpolation within rel_tol of p_G at the midpoints.
   subroutine test_calculix_flat(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: params
      type(egw_error), allocatable :: err
      real(dp), allocatable :: p(:), x(:)
      character(len=:), allocatable :: comments
      logical :: ok
      integer :: i
      real(dp) :: pg, dpg, p0
      real(dp), parameter :: ftol = 1.0e-5_dp
      real(dp) :: achieved
      params = contact_params(model=model_egw, radius=1.0_dp, modulus=2.0_dp, &
         & sigma=1.0e-3_dp, mu=4.0_dp)
      call write_calculix_flat(params, 3.0e-3_dp, ftol, dir//"/flat.inp", err, &
         & max_error=achieved)
      call check(error, .not. allocated(err), "CalculiX flat write failed")
      if (allocated(error)) return
      call read_calculix(dir//"/flat.inp", p, x, comments, ok)
      call check(error, ok, "CalculiX flat file not parsed")
      if (allocated(error)) return
      call flat_pressure(params, 0.0_dp, p0, dpg, err)
      call flat_pressure(params, -x(1), pg, dpg, err)
      call check(error, p(1) == 0.0_dp .and. pg <= ftol*p0, "first pair at zero pressure")
      if (allocated(error)) return
      call check(error, all(x(2:) > x(:size(x) - 1)), "overclosure not increasing")
      if (allocated(error)) return
      do i = 2, size(x)
         call flat_pressure(params, -x(i), pg, dpg, err)
         call check(error, p(i), pg, "pair "//to_string(i), thr=2e-11_dp, rel=.true.)
         if (allocated(error)) return
      end do
      do i = 2, size(x) - 1
         call flat_pressure(params, -0.5_dp*(x(i) + x(i + 1)), pg, dpg, err)
         ! ftol (1e-5) needs more than CalculiX's 200 pairs here: within the error the
         ! writer achieved (relative to max(p_G, ftol p_G(0)), its metric), which must be
         ! a few ftol at most (the sqrt(error) equidistribution: 200 instead of ~600
         ! bisection points costs a factor ~9)
         call check(error, abs(0.5_dp*(p(i) + p(i + 1)) - pg) <= (achieved*1.0001_dp + &
            & 4e-11_dp)*max(pg, ftol*p0), "interpolated p_G at pair "//to_string(i))
         if (allocated(error)) return
      end do
      call write_calculix_flat(contact_params(model=model_hertz), 1.0_dp, ftol, &
         & dir//"/flat2.inp", err)
      call check(error, allocated(err), "smooth flat must be refused")
   end subroutine test_calculix_flat

   !> What CalculiX can read (checked on the text, as CalculiX reads it): every number
   !> field of the pairs at most 20 characters, at most 200 pairs (a flat at rel_tol 1e-8
   !> needs more: the header then warns and states the error achieved, which must match
   !> the max_error output), and with shift the curve starts at (0, 0) and is the
   !> unshifted one moved by d_c (the same pressures; overclosures differ by the
   !> first unshifted overclosure -d_c, to the 13-digit rounding).
   subroutine test_calculix_limits(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: params
      type(egw_error), allocatable :: err
      real(dp), allocatable :: p(:), x(:), ps(:), xs(:)
      character(len=:), allocatable :: comments
      logical :: ok, shifted
      integer :: i, k
      real(dp) :: achieved, achieved_s
      params = contact_params(model=model_egw, radius=1.0_dp, modulus=2.0_dp, &
         & sigma=1.0e-3_dp, mu=4.0_dp)
      do k = 1, 2
         shifted = k == 2
         call write_calculix_flat(params, 3.0e-3_dp, 1.0e-8_dp, dir//"/flat_lim"// &
            & to_string(k)//".inp", err, shift=shifted, max_error=achieved)
         call check(error, .not. allocated(err), "CalculiX flat write failed")
         if (allocated(error)) return
         call check(error, fields_ok(dir//"/flat_lim"//to_string(k)//".inp"), &
            & "a number field is longer than 20 characters")
         if (allocated(error)) return
         if (shifted) then
            call read_calculix(dir//"/flat_lim2.inp", ps, xs, comments, ok)
            achieved_s = achieved
         else
            call read_calculix(dir//"/flat_lim1.inp", p, x, comments, ok)
         end if
         call check(error, ok, "file not parsed")
         if (allocated(error)) return
         call check(error, index(comments, "WARNING") > 0 .and. achieved > 1.0e-8_dp .and. &
            & index(comments, "max error achieved = ") > 0, "1e-8 must warn about 200 pairs")
         if (allocated(error)) return
      end do
      call check(error, size(x) == 200 .and. size(xs) == 200, "200 pairs expected")
      if (allocated(error)) return
      call check(error, achieved == achieved_s, "shift changes the error")
      if (allocated(error)) return
      call check(error, xs(1) == 0.0_dp .and. ps(1) == 0.0_dp, "shifted curve starts at 0")
      if (allocated(error)) return
      do i = 1, size(x)
         call check(error, ps(i) == p(i) .and. abs(xs(i) - (x(i) - x(1))) <= &
            & 1.0e-12_dp*(abs(x(i)) + abs(x(1))), "shifted pair "//to_string(i))
         if (allocated(error)) return
      end do
   end subroutine test_calculix_limits

   !> Every comma-separated field after the *SURFACE BEHAVIOR line: <= 20 characters.
   logical function fields_ok(path) result(ok)
      character(len=*), intent(in) :: path
      integer :: unit, ios, c
      character(len=512) :: line, rest
      logical :: data
      ok = .true.
      data = .false.
      open (newunit=unit, file=path, status="old", action="read")
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (data) then
            rest = line
            do
               c = index(rest, ",")
               if (c == 0) then
                  ok = ok .and. len_trim(adjustl(rest)) <= 20
                  exit
               end if
               ok = ok .and. len_trim(adjustl(rest(:c - 1))) <= 20
               rest = rest(c + 1:)
            end do
         end if
         if (line(1:9) == "*SURFACE ") data = .true.
      end do
      close (unit)
   end function fields_ok

   !> An E-GW universal table whose model field is set to 0 (Hertz), written with a valid
   !> checksum, was read and served E-GW forces (tail below delta = 0 included) to Hertz
   !> contacts (Stop 50 audit16). The reader refuses it naming the model field, in both
   !> formats; a Hertz table (n_log 0, no force at x <= 0, slices equal) still reads back.
   subroutine test_universal_relabelled(error)
      type(error_type), allocatable, intent(out) :: error
      type(universal_table) :: u, back
      type(egw_error), allocatable :: err
      integer :: k
      integer, parameter :: fmts(2) = [format_csv, format_binary]
      character(len=5), parameter :: ext(2) = [".csv ", ".egwu"]
      call build_universal(model_egw, 0.0_dp, 0.6_dp, 54.0_dp, solver_options(), 2.0_dp, &
         & 8.0_dp, -3.0_dp, 10.0_dp, 1e-3_dp, u, err)
      call check(error, .not. allocated(err), "E-GW universal build")
      if (allocated(error)) return
      call check(error, u%n_log > 0 .and. u%x_cut < 0.0_dp, "E-GW table has a tail")
      if (allocated(error)) return
      u%model = model_hertz
      do k = 1, 2
         call write_universal(u, dir//"/relabelled"//trim(ext(k)), fmts(k), err)
         call check(error, .not. allocated(err), "relabelled write")
         if (allocated(error)) return
         call read_universal(dir//"/relabelled"//trim(ext(k)), back, err)
         call check(error, allocated(err), "E-GW table relabelled Hertz accepted ("// &
            & trim(ext(k))//")")
         if (allocated(error)) return
         call check(error, err%stat == egw_bad_file .and. index(err%message, "model = 0") &
            & > 0, "message: "//err%message)
         if (allocated(error)) return
      end do
      call build_universal(model_hertz, 0.0_dp, 0.6_dp, 54.0_dp, solver_options(), 1.0_dp, &
         & 2.0_dp, -1.0_dp, 10.0_dp, 1e-4_dp, u, err)
      call check(error, .not. allocated(err), "Hertz universal build")
      if (allocated(error)) return
      do k = 1, 2
         call write_universal(u, dir//"/hertz_u"//trim(ext(k)), fmts(k), err)
         call check(error, .not. allocated(err), "Hertz write")
         if (allocated(error)) return
         call read_universal(dir//"/hertz_u"//trim(ext(k)), back, err)
         call check(error, .not. allocated(err), "Hertz universal table refused ("// &
            & trim(ext(k))//")")
         if (allocated(error)) return
      end do
   end subroutine test_universal_relabelled

   subroutine test_unsupported(error)
      type(error_type), allocatable, intent(out) :: error
      type(universal_table) :: u
      type(force_table) :: t
      type(egw_error), allocatable :: err
      call build_universal(model_hertz, 0.0_dp, 0.6_dp, 54.0_dp, solver_options(), 1.0_dp, &
         & 2.0_dp, -1.0_dp, 10.0_dp, 1e-4_dp, u, err)
      call check(error, .not. allocated(err), "universal build")
      if (allocated(error)) return
      call write_universal(u, dir//"/u.table", format_lammps, err)
      call check(error, allocated(err), "universal LAMMPS must be refused")
      if (allocated(error)) return
      call check(error, err%stat == egw_unsupported, "status of refused format")
      if (allocated(error)) return
      call write_universal(u, dir//"/u.egwu", format_binary, err)
      call read_table(dir//"/u.egwu", t, err)
      call check(error, allocated(err), "a universal file is not a 1-D table")
      if (allocated(error)) return
      call check(error, err%stat == egw_bad_file, "status for the wrong kind of file")
      if (allocated(error)) return
      call read_table(dir//"/does-not-exist", t, err)
      call check(error, allocated(err), "missing file")
      if (allocated(error)) return
      call check(error, err%stat == egw_io_error, "status for a missing file")
      if (allocated(error)) return
      call hertz_table(t, error)
      if (allocated(error)) return
      call write_table(t, dir//"/x", 7, err)
      call check(error, allocated(err), "unknown format")
      if (allocated(error)) return
      call check(error, err%stat == egw_invalid_argument, "status of an unknown format")
   end subroutine test_unsupported

end module test_table_format
