!> Persson's theory of the contact of an elastic half-space (effective modulus E*) with a
!> randomly rough, isotropic surface: the mean separation u (from the mean plane of the
!> heights) and the relative contact area against the mean pressure p, from the surface's
!> power spectrum C(q). doc/theory.md §11.
!>
!> **Spectrum.** Isotropic 2-D PSD with <h^2> = int d^2q C(q) = 2 pi int q C(q) dq,
!> tabulated at wavenumbers q_1 < ... < q_n [rad/length] and taken as a power law between
!> neighbouring nodes (exact for self-affine spectra; `self_affine_psd` gives one), zero
!> outside [q_1, q_n]. m2(q) = 2 pi int_{q_1}^q q'^3 C dq' is the mean square slope of the
!> wavelengths longer than 2 pi/q.
!>
!> **Formulas** (B. N. J. Persson, PRL 99, 125502 (2007), eq. (3) with the elastic-energy
!> factor of C. Yang & B. N. J. Persson, J. Phys.: Condens. Matter 20, 215214 (2008)):
!>   P(q, p) = erf(1/(2 sqrt G)),  G(q) = (pi/4)(E*/p)^2 int_{q_1}^q q'^3 C dq',
!>   u(p) = sqrt(pi) int_{q_1}^{q_n} dq q^2 C(q) w(q) int_p^inf (dp'/p')
!>          [gamma + 3(1 - gamma) P(q, p')^2] exp(-(w(q) p'/E*)^2),
!>   w(q) = (pi int_{q_1}^q q'^3 C dq')^(-1/2) = (m2(q)/2)^(-1/2).
!> With s = w(q) p'/E*, 1/(2 sqrt G) = s, so the inner integral is
!>   I(s0) = int_{s0}^inf (ds/s) [gamma + 3(1 - gamma) erf(s)^2] exp(-s^2)
!>         = (gamma/2) E1(s0^2) + 3(1 - gamma) J(s0),  J(s0) = int_{s0}^inf erf^2 e^{-s^2} ds/s,
!> s0 = w(q) p/E*; du/dp follows from dI/ds0 = -(1/s0)[gamma + 3(1 - gamma) erf(s0)^2]
!> exp(-s0^2) in closed form. Contact area A/A0 = P(q_n, p) = erf(w(q_n) p/E*).
!> gamma: the empirical factor for the elastic energy stored near the contact edges;
!> Persson proposes gamma of about 0.4-0.5; egw's default 0.42 (a parameter).
!> Limits (tests): A/A0 -> sqrt(8/pi) p/(E* sqrt(m2(q_n))) at small p; at large u,
!> p ~ exp(-u/u0) with u0 = sqrt(pi) gamma int q^2 C w dq (the E1 term's -ln s0^2).
!>
!> **Numerics.** J is tabulated once per call on s in [0, 8] (cubic Hermite with the exact
!> derivative, error ~1e-11) from composite 16-point Gauss-Legendre integrals; the outer
!> integral in ln q by 8-point Gauss-Legendre panels (at most 0.1 wide), with
!> t = sqrt(ln(q/q_1)) and geometric panels on the first interval, where w ~ (q - q_1)^-1/2.
module egw_flat_persson
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, egw_invalid_argument, fatal_error, format_real, int_str, &
      & parameter_error
   implicit none
   private

   public :: self_affine_psd, persson_flat_curve, psd_rms_height, psd_slope_squared

   !> Options of Persson's law.
   type, public :: persson_options
      real(dp) :: gamma = 0.42_dp   !< elastic-energy factor gamma in (0, 1]
   end type persson_options

   real(dp), parameter :: euler_gamma = 0.57721566490153286_dp
   !> 8- and 16-point Gauss-Legendre nodes and weights on [0, 1].
   real(dp), parameter :: x8(4) = [0.1834346424956498_dp, 0.5255324099163290_dp, &
      & 0.7966664774136267_dp, 0.9602898564975363_dp]
   real(dp), parameter :: w8(4) = [0.3626837833783620_dp, 0.3137066458778873_dp, &
      & 0.2223810344533745_dp, 0.1012285362903763_dp]
   real(dp), parameter :: j_top = 8.0_dp   !< J(s) = 0 beyond (e^-64)
   integer, parameter :: j_nodes = 1601     !< J's table on [0, j_top]

contains

   !> The self-affine PSD with a roll-off: C = C0 for q_long <= q < q_roll, C0
   !> (q/q_roll)^(-2(1 + hurst)) for q_roll <= q <= q_short, C0 fixed by the rms height
   !> (<h^2> = 2 pi int q C dq). q_long = q_roll: no plateau. Returned as the nodes of the
   !> tabulated form (power law between nodes: exact).
   subroutine self_affine_psd(hurst, rms_height, q_long, q_roll, q_short, q, c, error)
      real(dp), intent(in) :: hurst        !< Hurst exponent in (0, 1]
      real(dp), intent(in) :: rms_height   !< rms height [length] > 0
      real(dp), intent(in) :: q_long, q_roll, q_short   !< 0 < q_long <= q_roll < q_short
      real(dp), allocatable, intent(out) :: q(:), c(:)  !< [rad/length], [length^4]
      !> egw_invalid_argument naming the argument out of range
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: c0, tail
      if (.not. (hurst > 0.0_dp .and. hurst <= 1.0_dp)) then
         call parameter_error(error, "hurst", hurst, "must lie in (0, 1]"); return
      end if
      if (.not. (ieee_is_finite(rms_height) .and. rms_height > 0.0_dp)) then
         call parameter_error(error, "rms_height", rms_height, "must be finite and > 0")
         return
      end if
      if (.not. (ieee_is_finite(q_long) .and. q_long > 0.0_dp)) then
         call parameter_error(error, "q_long", q_long, "must be finite and > 0"); return
      end if
      if (.not. (ieee_is_finite(q_roll) .and. q_roll >= q_long)) then
         call parameter_error(error, "q_roll", q_roll, "must be finite and >= q_long")
         return
      end if
      if (.not. (ieee_is_finite(q_short) .and. q_short > q_roll)) then
         call parameter_error(error, "q_short", q_short, "must be finite and > q_roll")
         return
      end if
      tail = q_roll**2*(1.0_dp - (q_short/q_roll)**(-2.0_dp*hurst))/(2.0_dp*hurst)
      c0 = rms_height**2/(2.0_dp*pi*(0.5_dp*(q_roll**2 - q_long**2) + tail))
      if (q_roll > q_long) then
         q = [q_long, q_roll, q_short]
         c = [c0, c0, c0*(q_short/q_roll)**(-2.0_dp*(1.0_dp + hurst))]
      else
         q = [q_roll, q_short]
         c = [c0, c0*(q_short/q_roll)**(-2.0_dp*(1.0_dp + hurst))]
      end if
   end subroutine self_affine_psd

   !> rms height sqrt(2 pi int q C dq) of a tabulated PSD (power law between nodes).
   pure real(dp) function psd_rms_height(q, c) result(h)
      !> wavenumbers [rad/length] ascending, and C(q) [length^4]
      real(dp), intent(in) :: q(:), c(:)
      h = sqrt(2.0_dp*pi*moment(q, c, 1.0_dp, size(q)))
   end function psd_rms_height

   !> Mean square slope m2 = 2 pi int q^3 C dq of a tabulated PSD.
   pure real(dp) function psd_slope_squared(q, c) result(m2)
      !> wavenumbers [rad/length] ascending, and C(q) [length^4]
      real(dp), intent(in) :: q(:), c(:)
      m2 = 2.0_dp*pi*moment(q, c, 3.0_dp, size(q))
   end function psd_slope_squared

   !> Persson's curve at mean pressures geometric from p_min to p_max (per_decade a decade,
   !> both ends): u(:) [length] (decreasing), p(:), the area fraction and dp/du (< 0);
   !> it ends before (nearly) full contact, where u underflows (so it may be shorter).
   !> Errors (egw_invalid_argument, naming the argument): fewer than 2 nodes, q not
   !> finite, > 0 and ascending, C not finite or < 0, all of C zero, a pressure range or
   !> modulus that is not finite and positive, gamma outside (0, 1].
   subroutine persson_flat_curve(q, c, modulus, p_min, p_max, per_decade, options, u, p, &
      & area, dpdu, error)
      real(dp), intent(in) :: q(:), c(:)     !< the PSD's nodes
      real(dp), intent(in) :: modulus        !< E* [pressure]
      real(dp), intent(in) :: p_min, p_max   !< mean-pressure range [pressure]
      integer, intent(in) :: per_decade      !< pressures per decade (1 .. 1000)
      type(persson_options), intent(in) :: options   !< the theory's choices (persson_options)
      !> mean separation [length], pressure, area fraction, dp/du
      real(dp), allocatable, intent(out) :: u(:), p(:), area(:), dpdu(:)
      type(egw_error), allocatable, intent(out) :: error   !< egw_invalid_argument, as above
      real(dp), allocatable :: qq(:), wq(:), fq(:), ww(:), jt(:), dj(:)
      real(dp) :: s0, dudp
      integer :: n, k, i, last

      call check_curve(q, c, modulus, p_min, p_max, per_decade, options, error)
      if (allocated(error)) return
      call outer_rule(q, c, qq, wq, fq, ww)
      call tabulate_j(jt, dj)
      n = max(2, ceiling(real(per_decade, dp)*log10(p_max/p_min) - 1.0e-9_dp) + 1)
      allocate (u(n), p(n), area(n), dpdu(n))
      do k = 1, n
         p(k) = p_min*(p_max/p_min)**(real(k - 1, dp)/real(n - 1, dp))
      end do
      p(n) = p_max
      last = 0
      do k = 1, n
         u(k) = 0.0_dp
         dudp = 0.0_dp
         do i = 1, size(qq)
            if (.not. ww(i) < huge(1.0_dp)) cycle   ! w infinite: s0 infinite, I = 0
            s0 = ww(i)*p(k)/modulus
            u(k) = u(k) + wq(i)*fq(i)*inner(s0, options%gamma, jt, dj)
            dudp = dudp + wq(i)*fq(i)*(ww(i)/modulus)*inner_rate(s0, options%gamma)
         end do
         u(k) = sqrt(pi)*u(k)
         area(k) = erf(p(k)/modulus*sqrt(2.0_dp/psd_slope_squared(q, c)))
         ! (nearly) full contact: u and du/dp underflow, the law ends (as the BEM's)
         if (.not. (dudp < 0.0_dp .and. u(k) > 0.0_dp .and. area(k) < 1.0_dp)) exit
         dpdu(k) = 1.0_dp/(sqrt(pi)*dudp)
         last = k
      end do
      if (last < 2) then
         call fatal_error(error, egw_invalid_argument, "p_min = "//format_real(p_min) &
            & //": the surface is in full contact there already (Persson's u vanishes): " &
            & //"lower p_min")
         return
      end if
      u = u(:last)
      p = p(:last)
      area = area(:last)
      dpdu = dpdu(:last)
   end subroutine persson_flat_curve

   subroutine check_curve(q, c, modulus, p_min, p_max, per_decade, options, error)
      real(dp), intent(in) :: q(:), c(:), modulus, p_min, p_max
      integer, intent(in) :: per_decade
      type(persson_options), intent(in) :: options
      type(egw_error), allocatable, intent(out) :: error
      integer :: i
      if (size(q) < 2 .or. size(c) /= size(q)) then
         call fatal_error(error, egw_invalid_argument, "n = "//int_str(size(q))// &
            & ", size(C) = "//int_str(size(c))//": a PSD needs n >= 2 nodes (q, C)")
         return
      end if
      do i = 1, size(q)
         if (.not. (ieee_is_finite(q(i)) .and. q(i) > 0.0_dp) .or. &
            & (i > 1 .and. .not. q(i) > q(max(i - 1, 1)))) then
            call fatal_error(error, egw_invalid_argument, "q("//int_str(i)//") = " &
               & //format_real(q(i))//": wavenumbers must be finite, > 0 and ascending")
            return
         end if
         if (.not. (ieee_is_finite(c(i)) .and. c(i) >= 0.0_dp)) then
            call fatal_error(error, egw_invalid_argument, "C("//int_str(i)//") = " &
               & //format_real(c(i))//": the PSD must be finite and >= 0")
            return
         end if
      end do
      if (.not. psd_slope_squared(q, c) > 0.0_dp) then
         call fatal_error(error, egw_invalid_argument, "C: the PSD is zero everywhere")
      else if (.not. (ieee_is_finite(modulus) .and. modulus > 0.0_dp)) then
         call parameter_error(error, "modulus", modulus, "must be finite and > 0")
      else if (.not. (ieee_is_finite(p_min) .and. p_min > 0.0_dp)) then
         call parameter_error(error, "p_min", p_min, "must be finite and > 0")
      else if (.not. (ieee_is_finite(p_max) .and. p_max > p_min)) then
         call parameter_error(error, "p_max", p_max, "must be finite and > p_min")
      else if (per_decade < 1 .or. per_decade > 1000) then
         call fatal_error(error, egw_invalid_argument, "per_decade = "//int_str(per_decade) &
            & //": must lie in [1, 1000]")
      else if (.not. (options%gamma > 0.0_dp .and. options%gamma <= 1.0_dp)) then
         call parameter_error(error, "gamma", options%gamma, "must lie in (0, 1]")
      end if
   end subroutine check_curve

   !> int_{q_1}^{q_x} q^m C(q) dq over the first k intervals (power law on each), with
   !> q_x = q(k+1) for k < n, and the partial integral up to x in the interval k+1
   !> when x is given.
   pure real(dp) function moment(q, c, m, k, x) result(s)
      real(dp), intent(in) :: q(:), c(:), m
      integer, intent(in) :: k
      real(dp), intent(in), optional :: x
      integer :: i
      s = 0.0_dp
      do i = 1, min(k, size(q)) - 1
         s = s + piece(i, q(i + 1))
      end do
      if (present(x) .and. k < size(q)) s = s + piece(k, x)
   contains
      pure real(dp) function piece(i, qe) result(v)
         integer, intent(in) :: i
         real(dp), intent(in) :: qe
         real(dp) :: a, e
         v = 0.0_dp
         if (c(i) <= 0.0_dp .or. c(i + 1) <= 0.0_dp) then
            ! a zero end: linear in q between the nodes (a power law has no zero)
            v = int_linear(q(i), q(i + 1), c(i), c(i + 1), m, qe)
            return
         end if
         a = log(c(i + 1)/c(i))/log(q(i + 1)/q(i))
         e = m + 1.0_dp + a
         if (abs(e) < 1.0e-12_dp) then
            v = c(i)*q(i)**(m + 1.0_dp)*log(qe/q(i))
         else
            v = c(i)*q(i)**(m + 1.0_dp)*((qe/q(i))**e - 1.0_dp)/e
         end if
      end function piece
   end function moment

   !> int_{q0}^{qe} q^m (c0 + (c1 - c0)(q - q0)/(q1 - q0)) dq.
   pure real(dp) function int_linear(q0, q1, c0, c1, m, qe) result(v)
      real(dp), intent(in) :: q0, q1, c0, c1, m, qe
      real(dp) :: b
      b = (c1 - c0)/(q1 - q0)
      v = (c0 - b*q0)*(qe**(m + 1.0_dp) - q0**(m + 1.0_dp))/(m + 1.0_dp) &
         & + b*(qe**(m + 2.0_dp) - q0**(m + 2.0_dp))/(m + 2.0_dp)
   end function int_linear

   !> C at q (power law between the nodes, linear where a node is zero).
   pure real(dp) function psd_at(q, c, k, x) result(v)
      real(dp), intent(in) :: q(:), c(:), x
      integer, intent(in) :: k   !< the interval holding x
      if (c(k) <= 0.0_dp .or. c(k + 1) <= 0.0_dp) then
         v = c(k) + (c(k + 1) - c(k))*(x - q(k))/(q(k + 1) - q(k))
      else
         v = c(k)*(x/q(k))**(log(c(k + 1)/c(k))/log(q(k + 1)/q(k)))
      end if
   end function psd_at

   !> The outer rule: points qq, weights wq (of dq), w(q) = (pi int q^3 C)^-1/2 (huge
   !> where that integral is 0) and f = q^2 C w at them.
   subroutine outer_rule(q, c, qq, wq, fq, ww)
      real(dp), intent(in) :: q(:), c(:)
      real(dp), allocatable, intent(out) :: qq(:), wq(:), fq(:), ww(:)
      real(dp), allocatable :: a(:), b(:)
      real(dp) :: lo, hi, t_hi, x, dx, m3
      integer :: k, j, np, i, g, n
      ! panels: in t = sqrt(ln(q/q_1)) on the first interval (geometric towards t = 0),
      ! in ln q on the others (at most 0.1 wide)
      allocate (a(0), b(0))
      t_hi = sqrt(log(q(2)/q(1)))
      ! uniform panels at most 0.05 wide down to the first, then halving towards t = 0
      np = max(1, ceiling(t_hi/0.05_dp))
      do j = np, 2, -1
         a = [a, t_hi*real(j - 1, dp)/real(np, dp)]
         b = [b, t_hi*real(j, dp)/real(np, dp)]
      end do
      hi = t_hi/real(np, dp)
      do j = 1, 40
         a = [a, 0.5_dp*hi]
         b = [b, hi]
         hi = 0.5_dp*hi
      end do
      n = size(a)
      allocate (qq(8*n), wq(8*n), fq(8*n))
      do j = 1, n
         do g = 1, 8
            i = 8*(j - 1) + g
            x = merge(0.5_dp*(1.0_dp - x8(min(g, 9 - g))), 0.5_dp*(1.0_dp + x8(min(g, &
               & 9 - g))), g <= 4)
            x = a(j) + (b(j) - a(j))*x
            dx = (b(j) - a(j))*0.5_dp*w8(min(g, 9 - g))
            qq(i) = q(1)*exp(x*x)
            wq(i) = dx*2.0_dp*x*qq(i)
         end do
      end do
      do k = 2, size(q) - 1
         lo = log(q(k))
         hi = log(q(k + 1))
         np = max(1, ceiling((hi - lo)/0.1_dp))
         do j = 1, np
            do g = 1, 8
               x = merge(0.5_dp*(1.0_dp - x8(min(g, 9 - g))), 0.5_dp*(1.0_dp + x8(min(g, &
                  & 9 - g))), g <= 4)
               x = lo + (hi - lo)*(real(j - 1, dp) + x)/real(np, dp)
               dx = (hi - lo)/real(np, dp)*0.5_dp*w8(min(g, 9 - g))
               qq = [qq, exp(x)]
               wq = [wq, dx*exp(x)]
            end do
         end do
      end do
      deallocate (fq)
      allocate (fq(size(qq)), ww(size(qq)))
      do i = 1, size(qq)
         k = 1
         do while (k < size(q) - 1 .and. qq(i) > q(k + 1))
            k = k + 1
         end do
         m3 = moment(q, c, 3.0_dp, k, qq(i))
         if (m3 > 0.0_dp) then
            ww(i) = 1.0_dp/sqrt(pi*m3)
            fq(i) = qq(i)**2*psd_at(q, c, k, qq(i))*ww(i)
         else
            ww(i) = huge(1.0_dp)
            fq(i) = 0.0_dp
         end if
      end do
   end subroutine outer_rule

   !> J(s) = int_s^inf erf(t)^2 exp(-t^2) dt/t on a uniform grid of [0, j_top], from the
   !> top down (16-point Gauss-Legendre on every step), and its derivative.
   subroutine tabulate_j(jt, dj)
      real(dp), allocatable, intent(out) :: jt(:), dj(:)
      real(dp) :: h, s, t, acc
      integer :: i, g
      allocate (jt(j_nodes), dj(j_nodes))
      h = j_top/real(j_nodes - 1, dp)
      jt(j_nodes) = 0.0_dp
      do i = j_nodes - 1, 1, -1
         s = h*real(i - 1, dp)
         acc = 0.0_dp
         do g = 1, 4
            t = s + h*0.5_dp*(1.0_dp - x8(g))
            acc = acc + w8(g)*j_integrand(t)
            t = s + h*0.5_dp*(1.0_dp + x8(g))
            acc = acc + w8(g)*j_integrand(t)
         end do
         jt(i) = jt(i + 1) + 0.5_dp*h*acc
      end do
      do i = 1, j_nodes
         dj(i) = -j_integrand(h*real(i - 1, dp))
      end do
   end subroutine tabulate_j

   elemental real(dp) function j_integrand(t) result(f)
      real(dp), intent(in) :: t
      if (t < 1.0e-8_dp) then
         f = (4.0_dp/pi)*t*exp(-t*t)   ! erf(t)^2/t ~ (4/pi) t
      else
         f = erf(t)**2*exp(-t*t)/t
      end if
   end function j_integrand

   !> I(s0) = (gamma/2) E1(s0^2) + 3(1 - gamma) J(s0).
   pure real(dp) function inner(s0, gamma, jt, dj) result(v)
      real(dp), intent(in) :: s0, gamma, jt(:), dj(:)
      real(dp) :: h, t, x
      integer :: i
      if (s0 >= j_top) then
         v = 0.5_dp*gamma*expint_e1(s0*s0)
         return
      end if
      h = j_top/real(j_nodes - 1, dp)
      i = min(j_nodes - 1, int(s0/h) + 1)
      x = s0 - h*real(i - 1, dp)
      t = x/h
      v = (1.0_dp + 2.0_dp*t)*(1.0_dp - t)**2*jt(i) + t*(1.0_dp - t)**2*h*dj(i) &
         & + t*t*(3.0_dp - 2.0_dp*t)*jt(i + 1) + t*t*(t - 1.0_dp)*h*dj(i + 1)
      v = 0.5_dp*gamma*expint_e1(s0*s0) + 3.0_dp*(1.0_dp - gamma)*v
   end function inner

   !> dI/ds0 = -(1/s0) [gamma + 3(1 - gamma) erf(s0)^2] exp(-s0^2).
   elemental real(dp) function inner_rate(s0, gamma) result(v)
      real(dp), intent(in) :: s0, gamma
      v = -(gamma + 3.0_dp*(1.0_dp - gamma)*erf(s0)**2)*exp(-s0*s0)/s0
   end function inner_rate

   !> The exponential integral E1(x), x > 0: its series below 1, a continued fraction
   !> above (modified Lentz), to ~1e-15 relative.
   elemental real(dp) function expint_e1(x) result(e1)
      real(dp), intent(in) :: x
      real(dp) :: term, b, c, d, h, del, an
      integer :: k
      if (x > 700.0_dp) then
         e1 = 0.0_dp
      else if (x <= 1.0_dp) then
         e1 = -euler_gamma - log(x)
         term = 1.0_dp
         do k = 1, 60
            term = -term*x/real(k, dp)
            e1 = e1 - term/real(k, dp)
            if (abs(term) < 1.0e-17_dp*abs(e1)) exit
         end do
      else
         b = x + 1.0_dp
         c = 1.0_dp/tiny(1.0_dp)
         d = 1.0_dp/b
         h = d
         do k = 1, 200
            an = -real(k, dp)**2
            b = b + 2.0_dp
            d = 1.0_dp/(an*d + b)
            c = b + an/c
            del = c*d
            h = h*del
            if (abs(del - 1.0_dp) < 1.0e-16_dp) exit
         end do
         e1 = h*exp(-x)
      end if
   end function expint_e1

end module egw_flat_persson
