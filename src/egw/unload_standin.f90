!> TEMPORARY stand-in for egw_unloading (branch unloadflat), to be deleted when that
!> branch is merged: the DESIGN §8 rough-flat unloading law Z_u(h, h_min) by plain
!> Gauss-Legendre quadrature (pieces split at the kinks of the summit law and of D, found
!> by scanning; t = t* + x**2 at the contact edge). Slow (~10 us per call), ~1e-10 accurate.
module egw_unload_standin
   use egw_kinds, only: dp, pi
   use egw_asperity, only: rough_flat_law
   use egw_halfspace, only: gauss_legendre
   implicit none
   private
   public :: rough_flat_unload_law
   integer, parameter :: n_gl = 16, n_sub = 6
contains

   !> Z_u(h, h_min) and dZ_u/dh at fixed h_min; h < h_min or psi = 0: the loading law.
   elemental subroutine rough_flat_unload_law(h, h_min, psi, hardness_coeff, plastic_ratio, p, dp_)
      real(dp), intent(in) :: h, h_min, psi, hardness_coeff, plastic_ratio
      real(dp), intent(out) :: p, dp_
      real(dp) :: e, q, k, delta, ts, lo, hi, b(8), x(n_gl), w(n_gl), a0, a1, xs, x0, x1, t, &
         & jac, dt, gap, f, ph, mid, tl, th, gl, gh
      integer :: nb, j, s, i, it
      logical :: sub
      if (h < h_min .or. psi == 0.0_dp) then
         call rough_flat_law(h, psi, hardness_coeff, plastic_ratio, p, dp_)
         return
      end if
      e = 1.0_dp/psi**2
      q = plastic_ratio*e
      k = hardness_coeff
      delta = h - h_min
      ! t* = D^-1(delta)
      lo = 0.0_dp
      hi = max(2.0_dp*delta, 1.0_dp)
      do while (dd(hi) < delta)
         hi = 2.0_dp*hi
      end do
      do it = 1, 60
         mid = 0.5_dp*(lo + hi)
         if (dd(mid) >= delta) then
            hi = mid
         else
            lo = mid
         end if
      end do
      ts = hi
      lo = max(ts, -h_min - 10.0_dp)
      hi = max(lo, -h_min) + 12.0_dp
      nb = 1
      b(1) = lo
      call add_b(e, lo, hi, b, nb)
      call add_b(q, lo, hi, b, nb)
      ! branch points of D in (e, q): scan
      do i = 1, 16
         tl = e + (q - e)*real(i - 1, dp)/16.0_dp
         th = e + (q - e)*real(i, dp)/16.0_dp
         gl = g(tl + 1.0e-12_dp*e)
         gh = g(th)
         if (gl*gh < 0.0_dp) then
            do it = 1, 52
               mid = 0.5_dp*(tl + th)
               if (g(mid)*gl > 0.0_dp) then
                  tl = mid
               else
                  th = mid
               end if
            end do
            call add_b(0.5_dp*(tl + th), lo, hi, b, nb)
         end if
      end do
      if (2.0_dp*e/k**2 > q) call add_b(2.0_dp*e/k**2, lo, hi, b, nb)
      call add_b(hi, lo, hi, b, nb)
      call sort(b(1:nb))
      call gauss_legendre(n_gl, x, w)
      p = 0.0_dp
      dp_ = 0.0_dp
      do j = 1, nb - 1
         a0 = b(j)
         a1 = b(j + 1)
         if (a1 <= a0) cycle
         sub = a0 <= lo .and. ts >= lo
         xs = a1 - a0
         if (sub) xs = sqrt(a1 - a0)
         do s = 1, n_sub
            x0 = xs*real(s - 1, dp)/n_sub
            x1 = xs*real(s, dp)/n_sub
            do i = 1, n_gl
               t = 0.5_dp*(x0 + x1) + 0.5_dp*(x1 - x0)*x(i)
               jac = 1.0_dp
               if (sub) then
                  jac = 2.0_dp*t
                  t = a0 + t*t
               else
                  t = a0 + t
               end if
               dt = dd(t)
               if (dt <= delta) cycle
               gap = dt - delta
               f = fhat(t)
               ph = exp(-0.5_dp*(t + h_min)**2)/sqrt(2.0_dp*pi)
               p = p + 0.5_dp*(x1 - x0)*w(i)*jac*f*(gap/dt)**1.5_dp*ph
               dp_ = dp_ - 1.5_dp*0.5_dp*(x1 - x0)*w(i)*jac*f*sqrt(gap/dt)/dt*ph
            end do
         end do
      end do
   contains
      pure subroutine add_b(v, lo, hi, b, nb)
         real(dp), intent(in) :: v, lo, hi
         real(dp), intent(inout) :: b(:)
         integer, intent(inout) :: nb
         if (v > lo .and. v < hi) then
            nb = nb + 1
            b(nb) = v
         else if (v >= hi .and. nb < 8 .and. b(nb) < hi) then
            nb = nb + 1
            b(nb) = hi
         end if
      end subroutine add_b
      pure subroutine sort(v)
         real(dp), intent(inout) :: v(:)
         integer :: a, c
         real(dp) :: tmp
         do a = 1, size(v)
            do c = a + 1, size(v)
               if (v(c) < v(a)) then
                  tmp = v(a); v(a) = v(c); v(c) = tmp
               end if
            end do
         end do
      end subroutine sort
      pure real(dp) function fhat(t)
         real(dp), intent(in) :: t
         real(dp) :: l, c, m
         if (t <= 0.0_dp) then
            fhat = 0.0_dp
         else if (t <= e) then
            fhat = t**1.5_dp
         else if (t <= q) then
            l = (t - e)/(q - e)
            c = 1.0_dp + 3.0_dp*l*l - 2.0_dp*l**3
            m = 1.0_dp - (1.0_dp - k)*log(q/t)/log(q/e)
            fhat = sqrt(e)*t*m*c/k
         else
            fhat = 2.0_dp*sqrt(e)*t/k
         end if
      end function fhat
      pure real(dp) function ahat(t)
         real(dp), intent(in) :: t
         real(dp) :: l
         if (t <= e) then
            ahat = t
         else if (t <= q) then
            l = (t - e)/(q - e)
            ahat = t*(1.0_dp + 3.0_dp*l*l - 2.0_dp*l**3)
         else
            ahat = 2.0_dp*t
         end if
      end function ahat
      pure real(dp) function dd(t)
         real(dp), intent(in) :: t
         if (t <= 0.0_dp) then
            dd = 0.0_dp
         else
            dd = min(t, fhat(t)/sqrt(ahat(t)))
         end if
      end function dd
      pure real(dp) function g(t)
         real(dp), intent(in) :: t
         g = t - fhat(t)/sqrt(ahat(t))
      end function g
   end subroutine rough_flat_unload_law

end module egw_unload_standin
