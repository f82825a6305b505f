!> Tests of egw_smooth_sphere (Hertz): identities of the smooth-sphere closed forms, the deflection and
!> gap against mpmath (test/ref_hertz.f90), the misprinted eq. (15) against the corrected
!> one (doc/theory.md §6 misprint 2), and the statuses of hertz_contact.
module test_hertz
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, &
      & ieee_is_nan
   use testdrive, only: new_unittest, unittest_type, error_type, check, test_failed
   use egw_kinds, only: pi
   use egw, only: dp, egw_error, egw_invalid_argument, egw_invalid_parameter, &
      & contact_params, hertz_contact_radius, hertz_force, hertz_stiffness, hertz_energy, &
      & hertz_pressure, hertz_deflection, hertz_gap, hertz_contact
   use ref_hertz, only: hz_radius, hz_delta, hz_r, hz_deflection, hz_gap
   implicit none
   private
   public :: collect_hertz

   real(dp), parameter :: radius = 2.5_dp, modulus = 3.0_dp, delta = 4.0e-3_dp

contains

   subroutine collect_hertz(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("force is the integral of the pressure", test_force_integral), &
         & new_unittest("stiffness is dP/d delta = 2 E a", test_stiffness), &
         & new_unittest("energy integrates the force", test_energy), &
         & new_unittest("deflection: w(0), continuity, far field", test_deflection_limits), &
         & new_unittest("deflection and gap against mpmath", test_against_mpmath), &
         & new_unittest("misprinted eq. 15 fails, corrected passes", test_misprint), &
         & new_unittest("separated spheres", test_separated), &
         & new_unittest("hertz_contact and its statuses", test_contact) &
         & ]
   end subroutine collect_hertz

   !> 2 pi int_0^a r p(r) dr = P_H by composite Simpson in r = a sin(theta), where the
   !> integrand a**2 p0 sin cos**2 is smooth. With 2000 panels the Simpson bound
   !> (pi/2) h**4 max|f''''|/180 is below 1e-13 of the integral; tolerance 1e-12.
   subroutine test_force_integral(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: n = 2000
      real(dp) :: a, h, theta, total, weight
      integer :: i
      a = hertz_contact_radius(delta, radius)
      h = 0.5_dp*pi/real(n, dp)
      total = 0.0_dp
      do i = 0, n
         theta = h*real(i, dp)
         weight = merge(1.0_dp, merge(4.0_dp, 2.0_dp, mod(i, 2) == 1), i == 0 .or. i == n)
         total = total + weight*hertz_pressure(a*sin(theta), delta, radius, modulus) &
            & *a*sin(theta)*a*cos(theta)
      end do
      total = 2.0_dp*pi*total*h/3.0_dp
      call check(error, total, hertz_force(delta, radius, modulus), &
         & "2 pi int r p dr must equal P_H", thr=1.0e-12_dp, rel=.true.)
      if (allocated(error)) return
      ! and P_H = (4/3) E sqrt(R) delta**1.5 as printed in eq. (16)
      call check(error, hertz_force(delta, radius, modulus), &
         & 4.0_dp/3.0_dp*modulus*sqrt(radius)*delta**1.5_dp, "eq. (16)", &
         & thr=4.0_dp*epsilon(1.0_dp), rel=.true.)
      if (allocated(error)) return
      ! p(0) = p0 = 2 E a/(pi R)
      call check(error, hertz_pressure(0.0_dp, delta, radius, modulus), &
         & 2.0_dp*modulus*hertz_contact_radius(delta, radius)/(pi*radius), "p0", &
         & thr=4.0_dp*epsilon(1.0_dp), rel=.true.)
   end subroutine test_force_integral

   !> Central difference of the closed-form force with h = 1e-4 delta: truncation
   !> P''' h**2/6 is 2e-10 of P', rounding eps P/h ~ 1e-12; tolerance 1e-9.
   subroutine test_stiffness(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: h, slope, d
      integer :: i
      do i = 1, 3
         d = delta*10.0_dp**(i - 2)
         h = 1.0e-4_dp*d
         slope = (hertz_force(d + h, radius, modulus) - hertz_force(d - h, radius, modulus)) &
            & /(2.0_dp*h)
         call check(error, hertz_stiffness(d, radius, modulus), slope, "dP/d delta", &
            & thr=1.0e-9_dp, rel=.true.)
         if (allocated(error)) return
         call check(error, hertz_stiffness(d, radius, modulus), &
            & 2.0_dp*modulus*sqrt(radius*d), "2 E a", thr=2.0_dp*epsilon(1.0_dp), rel=.true.)
         if (allocated(error)) return
      end do
   end subroutine test_stiffness

   !> Energy = int_0^delta P d delta'. In s = sqrt(delta') the integrand 2 s P(s**2) is
   !> c s**4, for which composite Simpson with n panels overestimates by exactly
   !> (2/3)/n**4 relative (its error term has a constant fourth derivative); dividing
   !> that out leaves rounding only: tolerance 1e-14.
   subroutine test_energy(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: n = 20
      real(dp) :: h, s, total, weight
      integer :: i
      h = sqrt(delta)/real(n, dp)
      total = 0.0_dp
      do i = 0, n
         s = h*real(i, dp)
         weight = merge(1.0_dp, merge(4.0_dp, 2.0_dp, mod(i, 2) == 1), i == 0 .or. i == n)
         total = total + weight*2.0_dp*s*hertz_force(s*s, radius, modulus)
      end do
      total = total*h/3.0_dp/(1.0_dp + 2.0_dp/(3.0_dp*real(n, dp)**4))
      call check(error, hertz_energy(delta, radius, modulus), total, &
         & "energy = int P d delta", thr=1.0e-14_dp, rel=.true.)
   end subroutine test_energy

   subroutine test_deflection_limits(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: a, w_in, w_out, slope_in, slope_out, r, far, eps
      integer :: i
      a = hertz_contact_radius(delta, radius)
      ! w(0) = delta: the centre moves by the overlap (eq. 15, w_H0 = delta)
      call check(error, hertz_deflection(0.0_dp, delta, radius), delta, "w(0) = delta")
      if (allocated(error)) return
      ! Value continuity at r = a: both sides are delta/2 up to the slope a/R times the
      ! 1e-12 a offset, so |jump| <= 1e-12 delta plus rounding.
      eps = 1.0e-12_dp
      w_in = hertz_deflection(a*(1.0_dp - eps), delta, radius)
      w_out = hertz_deflection(a*(1.0_dp + eps), delta, radius)
      call check(error, w_out, w_in, "w continuous at r = a", thr=4.0e-12_dp*delta)
      if (allocated(error)) return
      ! Slope continuity at r = a (eq. 15 is C1): one-sided differences over 1e-6 a agree
      ! with -a/R to O(1e-3) (the outer slope has a sqrt(r - a) correction).
      slope_in = (w_in - hertz_deflection(a*(1.0_dp - 1.0e-6_dp), delta, radius)) &
         & /(a*(1.0e-6_dp - eps))
      slope_out = (hertz_deflection(a*(1.0_dp + 1.0e-6_dp), delta, radius) - w_out) &
         & /(a*(1.0e-6_dp - eps))
      call check(error, slope_in, -a/radius, "slope inside", thr=1.0e-3_dp, rel=.true.)
      if (allocated(error)) return
      call check(error, slope_out, -a/radius, "slope outside", thr=1.0e-2_dp, rel=.true.)
      if (allocated(error)) return
      ! Far field: w -> P/(pi E r) (1 + x**2/10 + 9 x**4/280 + O(x**6)), x = a/r (expand
      ! eq. 15). The printed form would lose all digits by r = 1e8 a; ours keeps them:
      ! 1e-14 (the O(x**6) rest is < 1e-18 from r = 1e3 a on).
      do i = 3, 12
         r = a*10.0_dp**i
         far = hertz_force(delta, radius, modulus)/(pi*modulus*r) &
            & *(1.0_dp + (a/r)**2/10.0_dp + 9.0_dp*(a/r)**4/280.0_dp)
         call check(error, hertz_deflection(r, delta, radius), far, "far field", &
            & thr=1.0e-14_dp, rel=.true.)
         if (allocated(error)) return
      end do
   end subroutine test_deflection_limits

   !> Deflection and gap against 60-digit mpmath values of the defining formulas. Where
   !> a = sqrt(R delta) is exact (first two cases) the only error is egw's rounding; in
   !> the third the rounding of a enters z with the factor a/(r - a) <= 10. So 1e-14.
   subroutine test_against_mpmath(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: w, z
      integer :: i
      do i = 1, size(hz_r)
         w = hertz_deflection(hz_r(i), hz_delta(i), hz_radius(i))
         z = hertz_gap(hz_r(i), hz_delta(i), hz_radius(i))
         call check(error, w, hz_deflection(i), "deflection vs mpmath", thr=1.0e-14_dp, &
            & rel=.true., more=point(i))
         if (allocated(error)) return
         if (hz_gap(i) == 0.0_dp) then
            call check(error, z, 0.0_dp, "gap inside the contact", more=point(i))
         else
            call check(error, z, hz_gap(i), "gap vs mpmath", thr=1.0e-14_dp, rel=.true., &
               & more=point(i))
         end if
         if (allocated(error)) return
      end do
   end subroutine test_against_mpmath

   !> Printed eq. (15) for r > a: a**2/(pi R) [r**2/a**2 - 1 + (2 - r**2/a**2) asin(a/r)].
   !> Its value at r = a matches (delta/2), but its slope does not: just outside it drops
   !> with slope ~ -1/sqrt(r - a), so the gap z goes negative (the sphere would pass
   !> through the flat), and far out it grows like r**2 instead of decaying like 1/r.
   !> The corrected form has z >= 0 and w -> 0.
   subroutine test_misprint(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: a, r, w_printed, z_printed
      a = hertz_contact_radius(delta, radius)
      r = a*(1.0_dp + 1.0e-4_dp)
      w_printed = printed_eq15(r, a)
      z_printed = w_printed + r*r/(2.0_dp*radius) - delta
      ! z_printed ~ -(2 sqrt 2/pi) delta sqrt(1e-4)/... clearly negative: < -1e-3 delta
      call check(error, z_printed < -1.0e-3_dp*delta, "printed eq. 15 should give a "// &
         & "negative gap just outside r = a")
      if (allocated(error)) return
      call check(error, hertz_gap(r, delta, radius) >= 0.0_dp, "corrected gap must be >= 0")
      if (allocated(error)) return
      ! the same corrected gap from w_H directly (cancels, hence the loose tolerance)
      call check(error, hertz_deflection(r, delta, radius) + r*r/(2.0_dp*radius) - delta, &
         & hertz_gap(r, delta, radius), "gap = w + r**2/2R - delta", thr=1.0e-15_dp)
      if (allocated(error)) return
      r = 10.0_dp*a
      call check(error, printed_eq15(r, a) > delta, "printed eq. 15 grows far out")
      if (allocated(error)) return
      call check(error, hertz_deflection(r, delta, radius) < 0.1_dp*delta, &
         & "corrected eq. 15 decays far out")
   contains
      pure real(dp) function printed_eq15(r, a) result(w)
         real(dp), intent(in) :: r, a
         w = a*a/(pi*radius)*(r*r/(a*a) - 1.0_dp + (2.0_dp - r*r/(a*a))*asin(a/r))
      end function printed_eq15
   end subroutine test_misprint

   subroutine test_separated(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: gap0 = -1.0e-3_dp
      call check(error, hertz_force(gap0, radius, modulus), 0.0_dp, "force")
      if (allocated(error)) return
      call check(error, hertz_stiffness(gap0, radius, modulus), 0.0_dp, "stiffness")
      if (allocated(error)) return
      call check(error, hertz_energy(gap0, radius, modulus), 0.0_dp, "energy")
      if (allocated(error)) return
      call check(error, hertz_contact_radius(gap0, radius), 0.0_dp, "contact radius")
      if (allocated(error)) return
      call check(error, hertz_pressure(0.0_dp, gap0, radius, modulus), 0.0_dp, "pressure")
      if (allocated(error)) return
      call check(error, hertz_deflection(0.0_dp, gap0, radius), 0.0_dp, "deflection")
      if (allocated(error)) return
      ! undeformed gap r**2/(2R) - delta, exact in this arithmetic
      call check(error, hertz_gap(0.1_dp, gap0, radius), 0.01_dp/(2.0_dp*radius) - gap0, &
         & "undeformed gap", thr=2.0_dp*epsilon(1.0_dp), rel=.true.)
   end subroutine test_separated

   subroutine test_contact(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: params
      type(egw_error), allocatable :: err
      real(dp) :: force, stiffness, a
      params%radius = radius
      params%modulus = modulus
      call hertz_contact(params, delta, force, stiffness, a, err)
      call check(error, .not. allocated(err), "valid call must succeed")
      if (allocated(error)) return
      call check(error, force == hertz_force(delta, radius, modulus) .and. &
         & stiffness == hertz_stiffness(delta, radius, modulus) .and. &
         & a == hertz_contact_radius(delta, radius), "outputs equal the closed forms")
      if (allocated(error)) return
      call hertz_contact(params, ieee_value(1.0_dp, ieee_quiet_nan), force, stiffness, a, err)
      call expect(egw_invalid_argument, "delta = NaN")
      if (allocated(error)) return
      call hertz_contact(params, ieee_value(1.0_dp, ieee_positive_inf), force, stiffness, &
         & a, err)
      call expect(egw_invalid_argument, "delta = +Inf")
      if (allocated(error)) return
      params%radius = -1.0_dp
      call hertz_contact(params, delta, force, stiffness, a, err)
      call expect(egw_invalid_parameter, "radius = ")
   contains
      subroutine expect(stat, prefix)
         integer, intent(in) :: stat
         character(len=*), intent(in) :: prefix
         if (.not. allocated(err)) then
            call test_failed(error, "invalid input accepted", prefix)
            return
         end if
         call check(error, err%stat, stat, "status", more=prefix)
         if (allocated(error)) return
         call check(error, index(err%message, prefix) == 1, "message must start '"//prefix &
            & //"'", more=err%message)
         if (allocated(error)) return
         call check(error, ieee_is_nan(force), "force must be NaN on error")
      end subroutine expect
   end subroutine test_contact

   function point(i) result(str)
      integer, intent(in) :: i
      character(len=:), allocatable :: str
      character(len=80) :: buf
      write (buf, '(a,es10.3,a,es10.3,a,es22.15)') "R = ", hz_radius(i), ", delta = ", &
         & hz_delta(i), ", r = ", hz_r(i)
      str = trim(buf)
   end function point

end module test_hertz
