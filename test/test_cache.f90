!> Tests of egw_cache: a second build of the same request is read from the cache and is
!> the same table to the bit (the binary files store every double; the evaluation data
!> are derived deterministically); a changed request, a corrupt entry, a directory that
!> cannot be written and EGW_CACHE_DIR=off all give a fresh build. The cache directory is
!> set with setenv(3) for these tests only (build/test_cache, emptied first).
module test_cache
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
   use, intrinsic :: iso_fortran_env, only: int64
   use testdrive, only: new_unittest, unittest_type, error_type, check, test_failed, skip_test
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_egw, model_epgw
   use egw_rough_sphere, only: solver_options
   use egw_table, only: force_table, table_eval, build_table
   use egw_simd, only: simd_level, simd_set
   use egw_hysteresis, only: hysteresis_table, hysteresis_eval
   use egw_cache, only: cache_directory, build_table_cached, build_hysteresis_cached, &
      & fnv1a_mix
   implicit none
   private
   public :: collect_cache

   interface
      function c_setenv(name, value, overwrite) result(stat) bind(C, name="setenv")
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: name(*), value(*)
         integer(c_int), value :: overwrite
         integer(c_int) :: stat
      end function c_setenv
   end interface

   character(len=*), parameter :: dir = "build/test_cache"
   type(contact_params), parameter :: ep = contact_params(model=model_epgw, radius=1.0_dp, &
      & modulus=1.0_dp, sigma=1.0_dp, mu=4.0_dp, psi=2.0_dp, hardness_coeff=0.6_dp)

contains

   subroutine collect_cache(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("1-D table: second build read back, same values", test_table), &
         & new_unittest("hysteresis: second build read back, same values", test_hysteresis), &
         & new_unittest("changed request, corrupt entry: rebuilt", test_miss), &
         & new_unittest("off, or a directory that cannot be written", test_off), &
         & new_unittest("one entry per SIMD path, each path's own bits", test_simd_path), &
         & new_unittest("the key's hash is FNV-1a 64, wrapping", test_fnv1a) &
         & ]
   end subroutine collect_cache

   subroutine set_dir(value)
      character(len=*), intent(in) :: value
      integer(c_int) :: stat
      stat = c_setenv("EGW_CACHE_DIR"//c_null_char, value//c_null_char, 1_c_int)
   end subroutine set_dir

   subroutine fresh_dir()
      call execute_command_line("rm -rf "//dir)
      call set_dir(dir)
   end subroutine fresh_dir

   subroutine test_table(error)
      type(error_type), allocatable, intent(out) :: error
      type(force_table) :: a, b
      type(egw_error), allocatable :: err
      type(contact_params) :: p
      logical :: hit1, hit2
      integer :: i
      real(dp) :: d, fa, ka, fb, kb
      character(len=:), allocatable :: got
      call fresh_dir()
      call cache_directory(got)
      call check(error, got == dir, "EGW_CACHE_DIR names the directory: got '"//got//"'")
      if (allocated(error)) return
      p = contact_params(model=model_egw, sigma=1.0e-3_dp, mu=4.0_dp)
      call build_table_cached(p, solver_options(), -3.0e-3_dp, 5.0e-3_dp, 1.0e-4_dp, a, err, &
         & hit1)
      if (.not. allocated(err)) call build_table_cached(p, solver_options(), -3.0e-3_dp, &
         & 5.0e-3_dp, 1.0e-4_dp, b, err, hit2)
      if (allocated(err)) then
         call test_failed(error, err%message)
         return
      end if
      call check(error, .not. hit1 .and. hit2, "first a build, then a cache hit")
      if (allocated(error)) return
      call check(error, all(a%delta == b%delta) .and. all(a%force == b%force) .and. &
         & all(a%stiffness == b%stiffness) .and. a%cutoff == b%cutoff, "the same nodes")
      if (allocated(error)) return
      do i = 0, 200
         d = -1.0e-2_dp + 2.0e-2_dp*i/200.0_dp
         call table_eval(a, d, fa, ka)
         call table_eval(b, d, fb, kb)
         call check(error, fa == fb .and. ka == kb, "the same values")
         if (allocated(error)) return
      end do
   end subroutine test_table

   subroutine test_hysteresis(error)
      type(error_type), allocatable, intent(out) :: error
      type(hysteresis_table) :: a, b
      type(egw_error), allocatable :: err
      logical :: hit1, hit2
      integer :: i, sa, sb
      real(dp) :: d, ma, mb, fa, ka, fb, kb
      call fresh_dir()
      call build_hysteresis_cached(ep, solver_options(), -2.0_dp, 4.0_dp, 1.0e-2_dp, a, err, &
         & hit=hit1)
      if (.not. allocated(err)) call build_hysteresis_cached(ep, solver_options(), -2.0_dp, &
         & 4.0_dp, 1.0e-2_dp, b, err, hit=hit2)
      if (allocated(err)) then
         call test_failed(error, err%message)
         return
      end if
      call check(error, .not. hit1 .and. hit2 .and. a%tag == b%tag, &
         & "first a build, then a cache hit with the same data tag")
      if (allocated(error)) return
      ma = -huge(1.0_dp)
      mb = ma
      do i = 0, 300
         d = 3.0_dp*sin(0.05_dp*i) + 0.003_dp*i
         call hysteresis_eval(a, d, ma, fa, ka, sa)
         call hysteresis_eval(b, d, mb, fb, kb, sb)
         call check(error, fa == fb .and. ka == kb .and. ma == mb .and. sa == sb, &
            & "the same forces along a history")
         if (allocated(error)) return
      end do
   end subroutine test_hysteresis

   subroutine test_miss(error)
      type(error_type), allocatable, intent(out) :: error
      type(hysteresis_table) :: a, b
      type(egw_error), allocatable :: err
      type(contact_params) :: p
      logical :: hit
      integer :: stat
      call fresh_dir()
      call build_hysteresis_cached(ep, solver_options(), -2.0_dp, 4.0_dp, 1.0e-2_dp, a, err)
      p = ep
      p%psi = 2.5_dp
      if (.not. allocated(err)) call build_hysteresis_cached(p, solver_options(), -2.0_dp, &
         & 4.0_dp, 1.0e-2_dp, b, err, hit=hit)
      if (allocated(err)) then
         call test_failed(error, err%message)
         return
      end if
      call check(error, .not. hit .and. b%params%psi == 2.5_dp, "another psi: a build")
      if (allocated(error)) return
      ! corrupt every entry in the middle (the checksum no longer matches)
      call execute_command_line("for f in "//dir//"/*.bin; do printf 'XXXX' | dd of=$f "// &
         & "bs=1 seek=200 conv=notrunc 2>/dev/null; done", exitstat=stat)
      call build_hysteresis_cached(ep, solver_options(), -2.0_dp, 4.0_dp, 1.0e-2_dp, b, err, &
         & hit=hit)
      call check(error, stat == 0 .and. .not. allocated(err) .and. .not. hit .and. &
         & b%tag == a%tag, "a corrupt entry is rebuilt, to the same table")
      if (allocated(error)) return
      call build_hysteresis_cached(ep, solver_options(), -2.0_dp, 4.0_dp, 1.0e-2_dp, b, err, &
         & hit=hit)
      call check(error, .not. allocated(err) .and. hit, "and written again")
   end subroutine test_miss

   subroutine test_off(error)
      type(error_type), allocatable, intent(out) :: error
      type(force_table) :: t
      type(egw_error), allocatable :: err
      type(contact_params) :: p
      logical :: hit
      integer :: stat
      character(len=:), allocatable :: got
      p = contact_params(model=model_egw, sigma=1.0e-3_dp, mu=4.0_dp)
      call execute_command_line("rm -rf "//dir)
      call set_dir("off")
      call cache_directory(got)
      call check(error, len(got) == 0, "EGW_CACHE_DIR=off: no directory")
      if (allocated(error)) return
      call build_table_cached(p, solver_options(), -3.0e-3_dp, 5.0e-3_dp, 1.0e-4_dp, t, err, hit)
      call build_table_cached(p, solver_options(), -3.0e-3_dp, 5.0e-3_dp, 1.0e-4_dp, t, err, hit)
      call check(error, .not. allocated(err) .and. .not. hit, "off: every call builds")
      if (allocated(error)) return
      call execute_command_line("test -e "//dir, exitstat=stat)
      call check(error, stat /= 0, "off: nothing written")
      if (allocated(error)) return
      ! /proc cannot take directories: the build still succeeds, uncached
      call set_dir("/proc/egw-no-such-cache")
      call build_table_cached(p, solver_options(), -3.0e-3_dp, 5.0e-3_dp, 1.0e-4_dp, t, err, hit)
      call check(error, .not. allocated(err) .and. .not. hit .and. allocated(t%delta), &
         & "an unwritable directory: built, not cached")
      call set_dir(dir)
   end subroutine test_off

   !> The AVX2 + FMA path's tables differ from the baseline's in their last digits, so the
   !> key holds the path: a build on one path is not read back on the other (on main it
   !> was: the second path's build was a hit with the first path's bits), each path gets
   !> back its own fresh build bit for bit, and the directory holds two entries. Skipped on
   !> a CPU without AVX2 and FMA (one path only).
   subroutine test_simd_path(error)
      type(error_type), allocatable, intent(out) :: error
      type(force_table) :: a(0:1), fresh(0:1)
      type(egw_error), allocatable :: err
      type(contact_params) :: p
      logical :: hit(0:1), again(0:1)
      integer :: level, level0, got, stat, unit, n
      level0 = simd_level()
      if (simd_set(1) /= 1) then
         got = simd_set(level0)
         call skip_test(error, "the CPU has no AVX2 + FMA: one SIMD path only")
         return
      end if
      p = contact_params(model=model_egw, sigma=1.0e-3_dp, mu=4.0_dp)
      call fresh_dir()
      ! path 1, then path 0, each a first build; then each again (hits)
      do level = 1, 0, -1
         got = simd_set(level)
         call build_table_cached(p, solver_options(), -3.0e-3_dp, 5.0e-3_dp, 1.0e-4_dp, &
            & a(level), err, hit(level))
         if (.not. allocated(err)) call build_table(p, solver_options(), -3.0e-3_dp, &
            & 5.0e-3_dp, 1.0e-4_dp, fresh(level), err)
         if (allocated(err)) exit
      end do
      do level = 1, 0, -1
         if (allocated(err)) exit
         got = simd_set(level)
         call build_table_cached(p, solver_options(), -3.0e-3_dp, 5.0e-3_dp, 1.0e-4_dp, &
            & a(level), err, again(level))
         if (allocated(err)) exit
         call check(error, again(level), "a second build on the same path is a cache hit")
         if (allocated(error)) exit
         call check(error, same_table(a(level), fresh(level)), &
            & "the hit is the path's own fresh build, bit for bit")
         if (allocated(error)) exit
      end do
      got = simd_set(level0)
      if (allocated(err)) then
         call test_failed(error, err%message)
         return
      end if
      if (allocated(error)) return
      call check(error, .not. hit(1) .and. .not. hit(0), &
         & "a build on the other path is not read from the first path's entry")
      if (allocated(error)) return
      ! the case the key guards: the two paths' tables are not the same bits
      call check(error, .not. same_table(fresh(0), fresh(1)), &
         & "the paths' tables differ (else this test shows nothing)")
      if (allocated(error)) return
      call execute_command_line("ls "//dir//"/*.bin | wc -l > "//dir//"_count.txt", &
         & exitstat=stat)
      open (newunit=unit, file=dir//"_count.txt", status="old", action="read")
      read (unit, *) n
      close (unit, status="delete")
      call check(error, stat == 0 .and. n == 2, "two entries, one per path")
   end subroutine test_simd_path

   !> fnv1a_mix against FNV-1a 64 computed with Python's unbounded integers:
   !>   h = 14695981039346656037; for b in bytes: h = ((h ^ b)*1099511628211) % 2**64
   !> over the word's 8 bytes, low byte first. Words with zero bytes are the case gfortran
   !> -O3 folded to huge(h) where the overflowing int64 multiply of main's mix was inlined
   !> with such a word (entry_path's SIMD level: test_simd_path); called across modules,
   !> as here, main's mix gave these values too: this test guards the arithmetic.
   subroutine test_fnv1a(error)
      type(error_type), allocatable, intent(out) :: error
      integer(int64), parameter :: basis = -3750763034362895579_int64
      integer(int64) :: h
      character(len=16) :: got
      h = basis
      call fnv1a_mix(h, 0_int64)
      write (got, "(z16.16)") h
      call check(error, got == "A8C7F832281A39C5", "word 0: got "//got)
      if (allocated(error)) return
      h = basis
      call fnv1a_mix(h, 1_int64)
      write (got, "(z16.16)") h
      call check(error, got == "89CD31291D2AEFA4", "word 1: got "//got)
      if (allocated(error)) return
      ! "foobar" and two NUL bytes as one word, then the word 2**63 (seven zero bytes, 128)
      h = basis
      call fnv1a_mix(h, transfer("foobar"//achar(0)//achar(0), h))
      call fnv1a_mix(h, shiftl(1_int64, 63))
      write (got, "(z16.16)") h
      call check(error, got == "91B10E294FAC4AA8", "'foobar', 2**63: got "//got)
   end subroutine test_fnv1a

   !> Two 1-D tables with the same nodes, forces and stiffnesses, bit for bit.
   logical function same_table(a, b)
      type(force_table), intent(in) :: a, b
      same_table = size(a%delta) == size(b%delta)
      if (same_table) same_table = all(a%delta == b%delta) .and. all(a%force == b%force) &
         & .and. all(a%stiffness == b%stiffness) .and. a%cutoff == b%cutoff
   end function same_table

end module test_cache
