!> Closed forms for two smooth elastic spheres (Hertz; paper eqs. 13-16, doc/theory.md §5):
!> contact radius, force, stiffness, energy, pressure, surface deflection and the gap
!> z(r) of the E-GW model (eq. 28). Eq. (15) is implemented in its corrected form
!> (doc/theory.md §6, misprint 2: sqrt(r**2/a**2 - 1), not r**2/a**2 - 1).
!>
!> Conventions: delta is the overlap (> 0 compression), radius the equivalent radius R,
!> modulus the effective modulus E*. For delta <= 0 the spheres do not touch: force,
!> pressure and deflection are 0 and the gap is the undeformed r**2/(2R) - delta.
!> (Not called egw_hertz: gfortran 12 rejects a module whose name equals the binding
!> label of a bind(C) routine, and the C API has egw_hertz.)
module egw_smooth_sphere
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, egw_invalid_argument, fatal_error, format_real
   use egw_params, only: contact_params, validate_params, product4
   implicit none
   private

   public :: hertz_contact_radius, hertz_force, hertz_stiffness, hertz_energy
   public :: hertz_pressure, hertz_deflection, hertz_gap, hertz_contact

contains

   !> Contact radius a = sqrt(R delta) (eq. 13); 0 for delta <= 0.
   elemental real(dp) function hertz_contact_radius(delta, radius) result(a)
      real(dp), intent(in) :: delta, radius   !< overlap and sphere radius R [length]
      real(dp) :: rd
      if (delta > 0.0_dp) then
         rd = radius*delta
         if (rd >= tiny(1.0_dp) .and. rd <= huge(1.0_dp)) then
            a = sqrt(rd)
         else
            ! R delta would underflow or overflow where a itself is representable
            a = sqrt(radius)*sqrt(delta)
         end if
      else
         a = 0.0_dp
      end if
   end function hertz_contact_radius

   !> Force P_H = (4/3) E sqrt(R) delta**(3/2) = (4/3) E a delta (eq. 16); 0 for delta <= 0.
   !> +Inf when the force itself exceeds the doubles (never from an intermediate overflow).
   elemental real(dp) function hertz_force(delta, radius, modulus) result(force)
      real(dp), intent(in) :: delta, radius, modulus   !< overlap, R [length], E* [pressure]
      real(dp) :: a, t
      a = hertz_contact_radius(delta, radius)
      t = (4.0_dp/3.0_dp)*modulus*a
      force = t*max(delta, 0.0_dp)
      ! a subnormal or infinite intermediate (or result): redo without losing digits
      if (delta > 0.0_dp .and. .not. (t >= tiny(1.0_dp) .and. t <= huge(1.0_dp) .and. &
         & force >= tiny(1.0_dp) .and. force <= huge(1.0_dp))) &
         & force = product4(4.0_dp/3.0_dp, modulus, a, delta)
   end function hertz_force

   !> Stiffness dP_H/d delta = 2 E a; 0 for delta <= 0.
   elemental real(dp) function hertz_stiffness(delta, radius, modulus) result(stiffness)
      real(dp), intent(in) :: delta, radius, modulus   !< overlap, R [length], E* [pressure]
      stiffness = 2.0_dp*modulus*hertz_contact_radius(delta, radius)
   end function hertz_stiffness


   !> Elastic energy stored at overlap delta, the integral of P_H from 0 to delta:
   !> (8/15) E sqrt(R) delta**(5/2); 0 for delta <= 0.
   elemental real(dp) function hertz_energy(delta, radius, modulus) result(energy)
      real(dp), intent(in) :: delta, radius, modulus   !< overlap, R [length], E* [pressure]
      energy = (8.0_dp/15.0_dp)*modulus*hertz_contact_radius(delta, radius) &
         & *max(delta, 0.0_dp)**2
   end function hertz_energy

   !> Contact pressure p_H(r) = p0 sqrt(1 - r**2/a**2), p0 = 2 E a/(pi R) (eq. 14), at
   !> radius r (|r| is used); 0 outside the contact and for delta <= 0.
   elemental real(dp) function hertz_pressure(r, delta, radius, modulus) result(pressure)
      !> radial position, overlap, R [length], E* [pressure]
      real(dp), intent(in) :: r, delta, radius, modulus
      real(dp) :: a, x
      a = hertz_contact_radius(delta, radius)
      x = abs(r)
      if (x < a) then
         ! p0 sqrt(1 - x**2/a**2) = (2E/(pi R)) sqrt((a - x)(a + x)): exact near the edge
         pressure = (2.0_dp*modulus/(pi*radius))*sqrt((a - x)*(a + x))
      else
         pressure = 0.0_dp
      end if
   end function hertz_pressure

   !> Normal surface deflection w_H(r) (eq. 15 corrected, doc/theory.md §6 misprint 2):
   !> delta - r**2/(2R) for r <= a, and for r > a
   !> w_H = a**2/(pi R) [sqrt(r**2/a**2 - 1) + (2 - r**2/a**2) asin(a/r)],
   !> evaluated without the cancellation that form suffers far out (it decays like
   !> P/(pi E r) while its terms grow like r). 0 for delta <= 0.
   elemental real(dp) function hertz_deflection(r, delta, radius) result(w)
      real(dp), intent(in) :: r, delta, radius   !< radial position, overlap, R [length]
      real(dp) :: a, x, s, t, u
      a = hertz_contact_radius(delta, radius)
      x = abs(r)
      if (a <= 0.0_dp) then
         w = 0.0_dp
      else if (x <= a) then
         w = delta - x*x/(2.0_dp*radius)
      else
         s = sqrt(x - a)*sqrt(x + a)     ! sqrt(r**2 - a**2), exact near r = a
         t = s/a
         if (t <= 1.0_dp) then
            ! every term is >= 0 here; asin(a/r) = atan2(a, s)
            w = t + (1.0_dp - t)*(1.0_dp + t)*atan2(a, s)
         else
            ! With u = 1/t = a/s: t + (1 - t**2) atan(u) = atan(u) + (u - atan u)/u**2,
            ! a sum of two positive terms (the bracket cancels as u**3 otherwise).
            u = a/s
            w = atan(u) + u*u_minus_atan_over_cube(u)
         end if
         w = w*(a*a/(pi*radius))
      end if
   end function hertz_deflection

   !> Gap between the Hertz-deformed sphere and the flat, z = w_H + r**2/(2R) - delta
   !> (eq. 28, the E-GW z(r)): 0 for r <= a; for r > a with t = sqrt(r**2/a**2 - 1)
   !> z = a**2/(pi R) [(t - atan t) + t**2 atan t], evaluated without cancellation.
   !> For delta <= 0 the undeformed gap r**2/(2R) - delta.
   elemental real(dp) function hertz_gap(r, delta, radius) result(z)
      real(dp), intent(in) :: r, delta, radius   !< radial position, overlap, R [length]
      real(dp) :: a, x, t
      x = abs(r)
      if (.not. delta > 0.0_dp) then
         z = x*x/(2.0_dp*radius) - delta
         return
      end if
      a = hertz_contact_radius(delta, radius)
      if (x <= a) then
         z = 0.0_dp
         return
      end if
      t = sqrt(x - a)*sqrt(x + a)/a
      if (t <= 0.5_dp) then
         ! t - atan t = t**3 (1/3 - t**2/5 + ...) cancels for small t: use the series.
         z = t*t*(t*u_minus_atan_over_cube(t) + atan(t))
      else
         ! t - atan t >= 0.036 t here, at most a factor ~14 lost on the smaller term
         z = (t - atan(t)) + t*t*atan(t)
      end if
      z = z*(a*a/(pi*radius))
   end function hertz_gap

   !> Force, stiffness and contact radius of smooth spheres with the R and E of params
   !> (other fields are validated but not used). Invalid params -> egw_invalid_parameter;
   !> NaN or infinite delta -> egw_invalid_argument naming delta. Outputs are NaN on error.
   pure subroutine hertz_contact(params, delta, force, stiffness, contact_radius, error)
      type(contact_params), intent(in) :: params   !< R and E* are used
      real(dp), intent(in) :: delta   !< overlap [length] (force 0 for delta <= 0)
      real(dp), intent(out) :: force   !< (4/3) E* sqrt(R) delta^(3/2) [force]
      real(dp), intent(out) :: stiffness   !< dP/ddelta [force/length]
      real(dp), intent(out) :: contact_radius   !< sqrt(R delta) [length]
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      force = ieee_value(1.0_dp, ieee_quiet_nan)
      stiffness = force
      contact_radius = force
      call validate_params(params, error)
      if (allocated(error)) return
      if (.not. ieee_is_finite(delta)) then
         call fatal_error(error, egw_invalid_argument, "delta = "//format_real(delta) &
            & //": the overlap must be finite")
         return
      end if
      force = hertz_force(delta, params%radius, params%modulus)
      stiffness = hertz_stiffness(delta, params%radius, params%modulus)
      contact_radius = hertz_contact_radius(delta, params%radius)
      if (.not. (ieee_is_finite(force) .and. ieee_is_finite(stiffness))) then
         call fatal_error(error, egw_invalid_argument, "delta = "//format_real(delta) &
            & //": the Hertz force (4/3) E sqrt(R) delta**1.5 or stiffness 2 E sqrt(R delta)" &
            & //" exceeds the largest double")
         force = ieee_value(1.0_dp, ieee_quiet_nan)
         stiffness = force
         contact_radius = force
      end if
   end subroutine hertz_contact

   !> (u - atan u)/u**3 for 0 <= u <= 1 without cancellation: the alternating series
   !> sum_j (-1)**j u**(2j)/(2j + 3) for u <= 1/2 (ratio <= 1/4), direct above, where
   !> u - atan u >= 0.07 u and at most ~14x rounding is lost on a term that callers add
   !> to a larger positive one.
   elemental real(dp) function u_minus_atan_over_cube(u) result(g)
      real(dp), intent(in) :: u
      real(dp) :: x, power, term
      integer :: j
      if (u > 0.5_dp) then
         g = (u - atan(u))/(u*u*u)
         return
      end if
      x = u*u
      g = 1.0_dp/3.0_dp
      power = 1.0_dp
      do j = 1, 30
         power = -power*x
         term = power/real(2*j + 3, dp)
         g = g + term
         if (abs(term) < 0.1_dp*epsilon(1.0_dp)) exit
      end do
   end function u_minus_atan_over_cube

end module egw_smooth_sphere
