!> egw-bench: cost per call of egw's kernels, as ratios to a libm erfc call and to the
!> closed-form Hertz force, all timed in one run. Run: fpm run egw-bench --profile release
program egw_bench
   use, intrinsic :: iso_fortran_env, only: output_unit, int64
   use egw, only: dp, gauss_integral, ellipk, rough_flat_law, hertz_force
   implicit none

   integer, parameter :: n = 4096        ! inputs per sweep (fit in L1/L2 cache)
   integer, parameter :: repeats = 7     ! best of 7 runs, to shed noise of a shared machine
   real(dp) :: h(n), k(n), delta(n), sink
   real(dp) :: t_erfc, t_hertz, t_f32, t_ellipk, t_pg, t_pg_zmc
   integer :: i, sweeps

   do i = 1, n
      ! inputs spread over the ranges a solver visits; irregular so nothing is hoisted
      h(i) = -6.0_dp + 14.0_dp*frac(0.6180339887498949_dp*i)
      k(i) = 0.999_dp*frac(0.7548776662466927_dp*i)
      delta(i) = 1.0e-2_dp*frac(0.5698402909980532_dp*i)
   end do
   sweeps = 500
   sink = 0

   t_erfc = best_time(1)
   t_hertz = best_time(2)
   t_f32 = best_time(3)
   t_ellipk = best_time(4)
   t_pg = best_time(5)
   t_pg_zmc = best_time(6)

   write (output_unit, '(a)') "egw-bench: ns per call (best of 7), ratios in one run"
   write (output_unit, '(a)') "kernel                         ns/call   / erfc   / Hertz"
   call row("libm erfc(x)", t_erfc)
   call row("Hertz force (closed form)", t_hertz)
   call row("F_3/2(h)  gauss_integral", t_f32)
   call row("K(k)      ellipk", t_ellipk)
   call row("p_G(h)    elastic + deriv", t_pg)
   call row("p_G(h)    ZMC psi=4 + deriv", t_pg_zmc)
   write (output_unit, '(a,es10.3)') "(checksum, ignore) ", sink

contains

   !> Best time per call, in ns, of kernel `which` over `repeats` runs.
   function best_time(which) result(t)
      integer, intent(in) :: which
      real(dp) :: t
      integer(int64) :: c0, c1, rate
      integer :: r, s, j
      real(dp) :: acc, p, dp_
      t = huge(1.0_dp)
      do r = 1, repeats
         acc = 0
         call system_clock(c0, rate)
         do s = 1, sweeps
            select case (which)
            case (1)
               do j = 1, n
                  acc = acc + erfc(h(j))
               end do
            case (2)
               do j = 1, n
                  acc = acc + hertz_force(delta(j), 1.0_dp, 1.0_dp)
               end do
            case (3)
               do j = 1, n
                  acc = acc + gauss_integral(1.5_dp, h(j))
               end do
            case (4)
               do j = 1, n
                  acc = acc + ellipk(k(j))
               end do
            case (5)
               do j = 1, n
                  call rough_flat_law(h(j), 0.0_dp, 0.6_dp, 54.0_dp, p, dp_)
                  acc = acc + p + dp_
               end do
            case (6)
               do j = 1, n
                  call rough_flat_law(h(j), 4.0_dp, 0.6_dp, 54.0_dp, p, dp_)
                  acc = acc + p + dp_
               end do
            end select
         end do
         call system_clock(c1)
         sink = sink + acc
         t = min(t, real(c1 - c0, dp)/real(rate, dp)*1.0e9_dp/real(n*sweeps, dp))
      end do
   end function best_time

   subroutine row(name, t)
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: t
      write (output_unit, '(a30,f9.2,2f9.2)') name, t, t/t_erfc, t/t_hertz
   end subroutine row

   elemental real(dp) function frac(x)
      real(dp), intent(in) :: x
      frac = x - aint(x)
   end function frac

end program egw_bench
