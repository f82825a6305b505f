!> Stop 64 (psi30): Z_u's integral calls of a build, replayed. Reads (Delta, h_min) pairs
!> (float64, little-endian, Delta first) captured from a build's unload_integral calls,
!> evaluates each with unloading_pressure on the psi 1 law (K 0.6, rho_p 54, no table:
!> every call by the integral, as in the build), and prints per round the calls and CPU
!> (cpu_time, one thread) of five classes of the result: Z_u = 0, (0, 1e-60), [1e-60,
!> 1e-30), [1e-30, 1e-16), >= 1e-16.
!> Capture (root; uprobes; the arguments by reference, rsi = Delta, rdx = h_min):
!>   perf probe -x EGW_TABLE --add 'zu=__egw_unloading_MOD_unload_integral \
!>      delta=+0(%si):u64 hmin=+0(%dx):u64'
!>   EGW_CACHE_DIR=off OMP_NUM_THREADS=1 perf record -e probe_egw:zu -o zu.data EGW_TABLE \
!>      <README's psi 1 + cap command>
!>   perf script -i zu.data -F trace | awk '{print $(NF-1), $NF}' | sed 's/[a-z]*=//g' \
!>      > zu.txt   (then the u64 pairs as float64 into zu.bin, e.g. numpy's view)
!> Build and run:
!>   B=$(dirname $(find build -path '*/egw_unloading.mod' | head -1))
!>   gfortran -O2 -I$B tools/bench/psi30_zu_replay.f90 LIBEGW.a -lfftw3_omp -lfftw3 \
!>      -llapack -lblas -fopenmp -o /tmp/psi30_zu_replay
!>   OMP_NUM_THREADS=1 /tmp/psi30_zu_replay zu.bin
program psi30_zu_replay
   use egw_kinds, only: dp
   use egw_unloading, only: unloading_law, unloading_law_of, unloading_pressure
   implicit none
   type(unloading_law) :: law
   real(dp), allocatable :: a(:, :), p(:), dpdh(:)
   integer, allocatable :: cls(:)
   integer :: n, i, u, round, c, ncls(5)
   integer(8) :: sz
   real(dp) :: t0, t1, tcls(5), s
   character(len=512) :: path
   path = 'zu.bin'
   if (command_argument_count() >= 1) call get_command_argument(1, path)
   open (newunit=u, file=trim(path), access='stream', form='unformatted', status='old')
   inquire (unit=u, size=sz)
   n = int(sz/16)
   allocate (a(2, n), p(n), dpdh(n), cls(n))
   read (u) a
   close (u)
   law = unloading_law_of(1.0_dp, 0.6_dp, 54.0_dp)
   do i = 1, n
      call unloading_pressure(law, a(1, i) + a(2, i), a(2, i), p(i), dpdh(i))
      if (p(i) <= 0.0_dp) then
         cls(i) = 1
      else if (p(i) < 1.0e-60_dp) then
         cls(i) = 2
      else if (p(i) < 1.0e-30_dp) then
         cls(i) = 3
      else if (p(i) < 1.0e-16_dp) then
         cls(i) = 4
      else
         cls(i) = 5
      end if
   end do
   do c = 1, 5
      ncls(c) = count(cls == c)
   end do
   s = 0.0_dp
   do round = 1, 3
      do c = 1, 5
         call cpu_time(t0)
         do i = 1, n
            if (cls(i) /= c) cycle
            call unloading_pressure(law, a(1, i) + a(2, i), a(2, i), p(i), dpdh(i))
            s = s + p(i)
         end do
         call cpu_time(t1)
         tcls(c) = t1 - t0
      end do
      print '(a, i0, 5(2x, i0, 1x, f7.3, " s"))', 'round ', round, &
         & (ncls(c), tcls(c), c = 1, 5)
   end do
   if (.not. s >= 0.0_dp) print '(a)', 'negative sum'
end program psi30_zu_replay
