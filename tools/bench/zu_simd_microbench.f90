!> Stop 56 (psi22): the CPU time (cpu_time, one thread) of Z_u's integral on its two SIMD
!> paths (egw_simd_path: 0 the baseline, 1 AVX2 + FMA), alternated in one run: N random
!> (h, h_min) of psi PSI (K 0.6, rho_p 54; h_min in [-4, 8], Delta = h - h_min in [1e-6,
!> 30] log-uniform: the points of a rough + cap build outside the deep plastic zone, as
!> stop 55's psi21 measured), each round timing both paths; prints per round the ns per
!> call of each path and their ratio, and the largest relative difference of Z_u, dZ_u/dh.
!>   B=$(dirname $(find build -path '*/egw_unloading.mod' | head -1))
!>   gfortran -O2 -I$B tools/bench/zu_simd_microbench.f90 LIBEGW.a -llapack -lblas \
!>      -fopenmp -o /tmp/zu_simd_microbench
!>   OMP_NUM_THREADS=1 /tmp/zu_simd_microbench [PSI [N [ROUNDS]]]     (default 1 20000 5)
program zu_simd_microbench
   use egw_kinds, only: dp
   use egw_unloading, only: unloading_law, unloading_law_of, unloading_pressure
   use egw_simd_path, only: simd_set
   implicit none
   type(unloading_law) :: law
   real(dp), allocatable :: h(:), h_min(:), p(:, :), dp_(:, :)
   real(dp) :: psi, u(2), t0, t1, t(0:1), apart(2)
   integer :: n, rounds, i, round, level, got
   character(len=32) :: arg
   psi = 1.0_dp
   n = 20000
   rounds = 5
   if (command_argument_count() >= 1) then
      call get_command_argument(1, arg); read (arg, *) psi
   end if
   if (command_argument_count() >= 2) then
      call get_command_argument(2, arg); read (arg, *) n
   end if
   if (command_argument_count() >= 3) then
      call get_command_argument(3, arg); read (arg, *) rounds
   end if
   allocate (h(n), h_min(n), p(n, 0:1), dp_(n, 0:1))
   call random_seed(put=[(56 + i, i=1, 64)])
   do i = 1, n
      call random_number(u)
      h_min(i) = -4.0_dp + 12.0_dp*u(1)
      h(i) = h_min(i) + 1.0e-6_dp*(30.0_dp/1.0e-6_dp)**u(2)
   end do
   law = unloading_law_of(psi, 0.6_dp, 54.0_dp)
   if (simd_set(1) /= 1) then
      print '(a)', "no AVX2 + FMA on this CPU: nothing to compare"
      stop
   end if
   do round = 1, rounds
      do level = 0, 1
         got = simd_set(level)
         call cpu_time(t0)
         do i = 1, n
            call unloading_pressure(law, h(i), h_min(i), p(i, level), dp_(i, level))
         end do
         call cpu_time(t1)
         t(level) = (t1 - t0)/n*1.0e9_dp
      end do
      apart(1) = maxval(abs(p(:, 1) - p(:, 0))/max(abs(p(:, 0)), tiny(1.0_dp)))
      apart(2) = maxval(abs(dp_(:, 1) - dp_(:, 0))/max(abs(dp_(:, 0)), tiny(1.0_dp)))
      print '(a, i0, a, f8.1, a, f8.1, a, f6.3, a, 2es9.2)', "round ", round, &
         & ": baseline ", t(0), " ns, AVX2 ", t(1), " ns, AVX2/baseline ", t(1)/t(0), &
         & ", apart (Z_u, dZ_u/dh) ", apart
   end do
end program zu_simd_microbench
