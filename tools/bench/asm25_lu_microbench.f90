! egw_lapack's lu_factor on dense matrices I - 0.8 U(0,1)/n of the solver's sizes (doc/benchmarks.md
! "Stop 59: asm25"): CPU ms a factorisation, and a checksum (equal checksums: the same bits).
! Build against a built library, e.g.
!   gfortran -O2 -Ibuild/gfortran_<mods> tools/bench/asm25_lu_microbench.f90 \
!     build/gfortran_<lib>/egw/libegw.a -fopenmp -llapack -lblas -o lub
program lub
   use egw_lapack, only: lu_factor
   implicit none
   integer, parameter :: dp = kind(1.0d0)
   integer :: sizes(5) = [50, 108, 200, 300, 500], reps(5) = [20000, 4000, 800, 250, 60]
   integer :: s, n, r, info
   real(dp), allocatable :: a0(:, :), a(:, :)
   integer, allocatable :: ipiv(:)
   real(dp) :: t0, t1, chk
   do s = 1, size(sizes)
      n = sizes(s)
      allocate (a0(n, n), a(n, n), ipiv(n))
      call random_seed(put=[(12345 + r, r=1, 64)])
      call random_number(a0)
      a0 = -0.8_dp*a0/real(n, dp)
      do r = 1, n
         a0(r, r) = a0(r, r) + 1.0_dp
      end do
      chk = 0.0_dp
      call cpu_time(t0)
      do r = 1, reps(s)
         a = a0
         call lu_factor(n, a, ipiv, info)
         chk = chk + a(n, n)
      end do
      call cpu_time(t1)
      write (*, '(i5, f10.4, a, es24.16)') n, (t1 - t0)/reps(s)*1e3, ' ms ', chk
      deallocate (a0, a, ipiv)
   end do
end program lub
