!> Shared pieces of egw-bench: wall clock, result rows (CSV + console), the independent
!> reference data of test/data/sphere_reference.csv, and the DEM-like overlap mix.
!> Every CSV row of the speed-accuracy sections has the same columns, so that
!> tools/bench/plot_pareto.py can draw them all on one chart:
!>   section,method,case,setting,time_s,rel_err,reference,status,extra
module bench_common
   use, intrinsic :: iso_fortran_env, only: output_unit, int64
   use egw, only: dp
   implicit none
   private

   public :: wall, frac, open_csv, write_row, close_csv, load_reference, reference_force
   public :: fmt_e, fmt_i, fmt_s, csv_header, out_dir

   !> Directory the CSVs go to (relative to the project root, where fpm runs); set once
   !> by the driver's --out flag before any section runs.
   character(len=:), allocatable :: out_dir
   character(len=*), parameter :: csv_header = &
      & "section,method,case,setting,time_s,rel_err,reference,status,extra"

   !> The reference rows (model, delta/sigma, mu, psi, K, P_scaled), loaded once.
   type :: reference_row
      character(len=8) :: model = ""
      real(dp) :: delta = 0, mu = 0, psi = 0, k = 0, p = 0
   end type reference_row
   type(reference_row), allocatable :: refs(:)

contains

   !> Wall-clock seconds (system_clock, int64 resolution).
   real(dp) function wall()
      integer(int64) :: c, rate
      call system_clock(c, rate)
      wall = real(c, dp)/real(rate, dp)
   end function wall

   !> Fractional part (for quasi-random inputs that nothing can hoist).
   elemental real(dp) function frac(x)
      real(dp), intent(in) :: x
      frac = x - aint(x)
   end function frac

   !> Open out_dir//name for writing and put the header line.
   subroutine open_csv(name, unit, header)
      character(len=*), intent(in) :: name
      integer, intent(out) :: unit
      character(len=*), intent(in), optional :: header
      if (.not. allocated(out_dir)) out_dir = "out/bench/"
      call execute_command_line("mkdir -p "//out_dir)
      open (newunit=unit, file=out_dir//name, status="replace", action="write")
      if (present(header)) then
         write (unit, '(a)') header
      else
         write (unit, '(a)') csv_header
      end if
   end subroutine open_csv

   subroutine close_csv(unit)
      integer, intent(in) :: unit
      close (unit)
   end subroutine close_csv

   !> One speed-accuracy row to the CSV and a short echo to the console.
   subroutine write_row(unit, section, method, case, setting, time_s, rel_err, reference, &
      & status, extra)
      integer, intent(in) :: unit
      character(len=*), intent(in) :: section, method, case, setting, reference
      real(dp), intent(in) :: time_s, rel_err
      integer, intent(in) :: status
      character(len=*), intent(in) :: extra
      write (unit, '(a)') section//","//method//","//case//","//setting//","// &
         & fmt_e(time_s)//","//fmt_e(rel_err)//","//reference//","//fmt_i(status)//","//extra
      write (output_unit, '(a10,1x,a22,1x,a22,1x,a16,1x,es10.3," s",1x,es9.2,1x,i2,1x,a)') &
         & section, method, case, setting, time_s, rel_err, status, extra
      flush (output_unit)
   end subroutine write_row

   function fmt_e(x) result(s)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: s
      character(len=32) :: buf
      write (buf, '(es23.15e3)') x
      s = trim(adjustl(buf))
   end function fmt_e

   !> Short form (2 digits) for settings such as rel_tol=1.0e-06.
   function fmt_s(x) result(s)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: s
      character(len=32) :: buf
      write (buf, '(es8.1e2)') x
      s = trim(adjustl(buf))
   end function fmt_s

   function fmt_i(i) result(s)
      integer, intent(in) :: i
      character(len=:), allocatable :: s
      character(len=16) :: buf
      write (buf, '(i0)') i
      s = trim(buf)
   end function fmt_i

   !> Read test/data/sphere_reference.csv (independent Python solver, see
   !> tools/reference/README.md): P scaled by E sqrt(R) sigma^1.5.
   subroutine load_reference(path, ok)
      character(len=*), intent(in) :: path
      logical, intent(out) :: ok
      integer :: unit, ios, n, k, c
      character(len=512) :: line
      character(len=64) :: fields(14)
      type(reference_row) :: row
      type(reference_row), allocatable :: tmp(:)
      ok = .false.
      open (newunit=unit, file=path, status="old", action="read", iostat=ios)
      if (ios /= 0) return
      allocate (refs(0))
      n = 0
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:1) == "#" .or. line(1:5) == "model") cycle
         ! split on commas
         fields = ""
         c = 1
         do k = 1, len_trim(line)
            if (line(k:k) == ",") then
               c = c + 1
               if (c > 14) exit
            else
               fields(c) = trim(fields(c))//line(k:k)
            end if
         end do
         row%model = fields(1)
         read (fields(3), *) row%delta
         read (fields(4), *) row%mu
         read (fields(5), *) row%psi
         read (fields(6), *) row%k
         read (fields(8), *) row%p
         n = n + 1
         tmp = [refs, row]
         call move_alloc(tmp, refs)
      end do
      close (unit)
      ok = n > 0
   end subroutine load_reference

   !> Reference P_scaled for (model name GW/EGW/EPGW, delta/sigma, mu, psi, K); -1 if the
   !> reference file has no such row.
   real(dp) function reference_force(model, delta, mu, psi, k) result(p)
      character(len=*), intent(in) :: model
      real(dp), intent(in) :: delta, mu, psi, k
      integer :: i
      p = -1.0_dp
      if (.not. allocated(refs)) return
      do i = 1, size(refs)
         if (trim(refs(i)%model) == model .and. close_to(refs(i)%delta, delta) .and. &
            & close_to(refs(i)%mu, mu) .and. close_to(refs(i)%psi, psi) .and. &
            & close_to(refs(i)%k, k)) then
            p = refs(i)%p
            return
         end if
      end do
   end function reference_force

   elemental logical function close_to(a, b)
      real(dp), intent(in) :: a, b
      close_to = abs(a - b) <= 1.0e-9_dp*max(1.0_dp, abs(b))
   end function close_to

end module bench_common
