!> Stop 65 (psi31): Z_u and dZ_u/dh of one library, written as float64 rows for an A/B
!> comparison (psi31_zu_panels.py compare). Two modes:
!>   replay PAIRS OUT [LEVEL]: the (Delta, h_min) pairs of a build's unload_integral calls
!>     (PAIRS as tools/bench/psi30_zu_replay.f90's header captures them), each through
!>     unloading_pressure on the psi 1 law (K 0.6, rho_p 54); rows (Z_u, dZ_u/dh);
!>   sweep N OUT [LEVEL]: N random (psi in [0.1, 100], K in [0.05, 0.95], rho_p in [1.5,
!>     1000], h_min in [-8, 8], Delta in [1e-8, 400] log-uniform; fixed seed) through
!>     rough_flat_unload_law; rows (psi, K, rho_p, h_min, h, Z_u, dZ_u/dh).
!> LEVEL 0 takes the baseline path (egw_simd_path's simd_set(0)), else the CPU's own.
!> Build against the library under test (its modules and libegw.a), e.g.
!>   B=$(dirname $(find build -path '*/egw_unloading.mod' | head -1))
!>   gfortran -O2 -I$B tools/bench/psi31_zu_values.f90 LIBEGW.a -lfftw3_omp -lfftw3 \
!>      -llapack -lblas -fopenmp -o /tmp/zu_values
!> (main's modules serve for main's libegw.a: the public interface is the same).
program psi31_zu_values
   use egw_kinds, only: dp
   use egw_unloading, only: unloading_law, unloading_law_of, unloading_pressure, &
      & rough_flat_unload_law
   use egw_simd_path, only: simd_set
   implicit none
   character(len=512) :: mode, arg, outp
   character(len=8) :: level
   integer :: n, i, u, got
   integer(8) :: sz
   real(dp), allocatable :: pairs(:, :), rows(:, :)
   type(unloading_law) :: law
   real(dp) :: r(5)
   call get_command_argument(1, mode)
   call get_command_argument(2, arg)
   call get_command_argument(3, outp)
   call get_command_argument(4, level)
   if (level == '0') got = simd_set(0)
   if (mode == 'replay') then
      open (newunit=u, file=trim(arg), access='stream', form='unformatted', status='old')
      inquire (unit=u, size=sz)
      n = int(sz/16)
      allocate (pairs(2, n), rows(2, n))
      read (u) pairs
      close (u)
      law = unloading_law_of(1.0_dp, 0.6_dp, 54.0_dp)
      do i = 1, n
         call unloading_pressure(law, pairs(1, i) + pairs(2, i), pairs(2, i), rows(1, i), &
            & rows(2, i))
      end do
   else
      read (arg, *) n
      allocate (rows(7, n))
      call random_seed(put=[(31 + i, i=1, 64)])
      do i = 1, n
         call random_number(r)
         rows(1, i) = 0.1_dp*1000.0_dp**r(1)
         rows(2, i) = 0.05_dp + 0.9_dp*r(2)
         rows(3, i) = 1.5_dp*(1000.0_dp/1.5_dp)**r(3)
         rows(4, i) = -8.0_dp + 16.0_dp*r(4)
         rows(5, i) = rows(4, i) + 1.0e-8_dp*(400.0_dp/1.0e-8_dp)**r(5)
         call rough_flat_unload_law(rows(5, i), rows(4, i), rows(1, i), rows(2, i), &
            & rows(3, i), rows(6, i), rows(7, i))
      end do
   end if
   open (newunit=u, file=trim(outp), access='stream', form='unformatted', status='replace')
   write (u) rows
   close (u)
end program psi31_zu_values
