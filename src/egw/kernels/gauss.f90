!> Gaussian asperity integrals F_n(h) = int_h^inf (s-h)^n phi(s) ds (doc/theory.md §2), their
!> h-derivatives, and the three truncated integrals of the ZMC asperity law (eqs. 42-45).
!> Hot orders (n = -1/2, 0, 1/2, 1, 3/2, 5/2) use piecewise polynomial fits made offline by
!> tools/reference/gauss_fits.py; other orders and the truncated integrals use a fixed
!> composite 16-point Gauss-Legendre rule whose panels are placed from the Gaussian peak
!> (a deterministic rule, no error estimates, no adaptivity).
module egw_gauss
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_is_finite
   use egw_kinds, only: dp, inv_sqrt2pi
   use egw_status, only: egw_error, egw_invalid_argument, fatal_error, format_real
   use egw_gauss_fits, only: fit_pos, fit_neg, fit_deg_pos, fit_deg_neg, fit_pos_breaks, &
      & fit_store
   implicit none
   private

   public :: gauss_integral, gauss_integral_deriv, get_gauss_integral, get_gauss_integral_deriv
   public :: gauss_fm12, gauss_f0, gauss_f12, gauss_f1, gauss_f32, gauss_f52
   public :: normal_density, shifted_density, zmc_integrals, zmc_flat_integral
   public :: gl_x, gl_w

   ! Order index of the fitted kernels in egw_gauss_fits.
   integer, parameter :: ord_m12 = 1, ord_0 = 2, ord_12 = 3, ord_1 = 4, ord_32 = 5, ord_52 = 6

   ! Integrand kinds of the panel quadrature.
   integer, parameter :: kind_power = 1    ! g1 = x^p
   integer, parameter :: kind_power32 = 2  ! g1 = x^(3/2), g2 = x^(1/2)
   integer, parameter :: kind_ep = 3       ! g1 = ZMC elasto-plastic law, g2 = its x-derivative

   !> Largest loss of the Gaussian factor (e-folds below its peak on the interval) that the
   !> quadrature keeps: e^-50 ~ 2e-22 of the peak, plus 3 e-folds per power of x in the
   !> integrand, whose growth moves the integrand's peak away from the Gaussian's.
   real(dp), parameter :: loss_max = 50.0_dp
   !> A panel's Gaussian exponent may change by 12 e-folds near the peak (16-point GL
   !> integrates exp over such a span to ~1e-15) and by more where the Gaussian is already
   !> small, because there the absolute error is scaled down by e^-loss.
   real(dp), parameter :: dloss_peak = 12.0_dp, dloss_cap = 40.0_dp
   !> Width/left-end ratio of panels when the integrand has a branch point at x = 0
   !> (x^p, log x): the singularity then lies 5/3 half-widths from the panel's centre
   !> (Bernstein ellipse rho = 3, 16-point error ~ rho^-32 ~ 5e-16 of the panel).
   real(dp), parameter :: panel_ratio = 3.0_dp
   !> Exponent span of the Taylor-series panel at x = 0 (terms then stay below e^2 so the
   !> alternating sum loses at most ~1.5 digits).
   real(dp), parameter :: series_span = 2.0_dp
   !> For the general order x^p with large p: the power may grow by at most 6 e-folds over
   !> one panel (ratio limited to e^(6/p) - 1).
   real(dp), parameter :: power_span = 6.0_dp
   integer, parameter :: max_panels = 200
   !> Largest order of the checked F_n (get_gauss_integral): the quadrature's intermediates
   !> grow like Gamma((n+1)/2) and overflow past n ~ 170 (F_150(0) ~ 3e130, tested to 1e-13).
   real(dp), parameter, public :: max_order = 150.0_dp
   !> Below this order dF_n/dh = -n F_{n-1}(h) loses ~1e-17/n relatively (n - 1 rounds):
   !> small_order_deriv takes over.
   real(dp), parameter :: small_order = 1.0e-4_dp

   !> 16-point Gauss-Legendre nodes (positive half) and weights on [-1, 1].
   real(dp), parameter :: gl_x(8) = [0.095012509837637440185_dp, 0.28160355077925891323_dp, &
      & 0.45801677765722738634_dp, 0.61787624440264374845_dp, 0.7554044083550030339_dp, &
      & 0.86563120238783174388_dp, 0.94457502307323257608_dp, 0.9894009349916499326_dp]
   real(dp), parameter :: gl_w(8) = [0.18945061045506849629_dp, 0.18260341504492358887_dp, &
      & 0.16915651939500253819_dp, 0.14959598881657673208_dp, 0.12462897125553387205_dp, &
      & 0.09515851168249278481_dp, 0.062253523938647892863_dp, 0.027152459411754094852_dp]
   !> The 16 nodes mapped to [0, 2] and their weights.
   real(dp), parameter :: gl_u(16) = [1.0_dp - gl_x, 1.0_dp + gl_x]
   real(dp), parameter :: gl_w16(16) = [gl_w, gl_w]

   !> exp(-704): scale used to land subnormal results with a single rounding.
   real(dp), parameter :: exp_m704 = 1.80586275135226673053904237717e-306_dp
   real(dp), parameter :: shift704 = 704.0_dp
   !> Dekker's splitter 2^27 + 1: hi keeps 26 significant bits, so hi*hi is exact.
   real(dp), parameter :: splitter = 134217729.0_dp
   real(dp), parameter :: sixth = 1.0_dp/6.0_dp

contains

   !> F_n(h) = int_h^inf (s-h)^n phi(s) ds for real n > -1 and any h, including +-Inf
   !> (F_n(+Inf) = 0; F_n(-Inf) = +Inf for n > 0, 1 for n = 0, 0 for n < 0).
   !> Precondition (not checked here): n > -1 and neither argument NaN; a NaN h gives NaN.
   !> Use get_gauss_integral for a checked call. Relative error ~1e-15 (tested: <= 1e-14)
   !> for the fitted orders n = -1/2, 0, 1/2, 1, 3/2, 5/2, and ~2e-15 (tested: <= 1e-12)
   !> for other orders, checked for n up to 12; those cost ~1 us (quadrature).
   elemental real(dp) function gauss_integral(n, h) result(f)
      real(dp), intent(in) :: n, h   !< order n > -1, and h = separation/sigma
      if (same(n, 1.5_dp)) then
         f = fitted(ord_32, h)
      else if (same(n, 0.5_dp)) then
         f = fitted(ord_12, h)
      else if (same(n, 0.0_dp)) then
         f = fitted(ord_0, h)
      else if (same(n, 1.0_dp)) then
         f = fitted(ord_1, h)
      else if (same(n, 2.5_dp)) then
         f = fitted(ord_52, h)
      else if (same(n, -0.5_dp)) then
         f = fitted(ord_m12, h)
      else
         f = general_order(n, h)
      end if
   end function gauss_integral

   !> dF_n/dh = -n F_{n-1}(h) for n >= 0 (n = 0: -phi(h)). Same precondition as
   !> gauss_integral.
   elemental real(dp) function gauss_integral_deriv(n, h) result(df)
      real(dp), intent(in) :: n, h   !< order n >= 0, and h = separation/sigma
      if (same(n, 0.0_dp)) then
         df = -normal_density(h)
      else if (n < small_order) then
         df = -small_order_deriv(n, h)
      else
         df = -n*gauss_integral(n - 1.0_dp, h)
      end if
   end function gauss_integral_deriv

   !> n F_{n-1}(h) for 0 < n < small_order, where F_{n-1} nears its pole at order -1 and
   !> n - 1 keeps only log10(n/eps) digits of n (relative error ~1e-17/n). With
   !> n int_0^1 t^(n-1) dt = 1:
   !>   n F_{n-1}(h) = phi(h) + n [int_0^1 t^(n-1) (phi(h+t) - phi(h)) dt
   !>                              + int_1^inf t^(n-1) phi(h+t) dt],
   !> two smooth O(1) integrals needed to ~1e-12/(n ...) only: 16-point Gauss-Legendre on
   !> [0, 1] and on panels of width 1 over the Gaussian's support t in h+t in [-40, 40].
   elemental real(dp) function small_order_deriv(n, h) result(v)
      real(dp), intent(in) :: n, h
      real(dp) :: a, b, t, lo, hi, ph
      integer :: i, k, panels
      if (h < -1.0e8_dp) then
         ! every summit above h: F_m(h) = |h|**m (1 + m(m-1)/(2 h**2) + ...), exact here
         v = n*(-h)**(n - 1.0_dp)
         return
      end if
      ph = normal_density(h)
      a = 0.0_dp
      do i = 1, 16
         t = 0.5_dp*gl_u(i)
         a = a + 0.5_dp*gl_w16(i)*t**(n - 1.0_dp)*(normal_density(h + t) - ph)
      end do
      b = 0.0_dp
      lo = max(1.0_dp, -h - 40.0_dp)
      hi = max(1.0_dp, -h + 40.0_dp)
      panels = ceiling(hi - lo)
      do k = 0, panels - 1
         do i = 1, 16
            t = lo + (real(k, dp) + 0.5_dp*gl_u(i))*(hi - lo)/real(panels, dp)
            b = b + 0.5_dp*gl_w16(i)*(hi - lo)/real(panels, dp)*t**(n - 1.0_dp) &
               & *normal_density(h + t)
         end do
      end do
      v = ph + n*(a + b)
   end function small_order_deriv

   !> Checked F_n(h): NaN h, NaN n or n < 0 give egw_invalid_argument naming the argument.
   pure subroutine get_gauss_integral(n, h, value, error)
      real(dp), intent(in) :: n  !< order, n >= 0
      real(dp), intent(in) :: h  !< lower limit (separation in units of sigma)
      real(dp), intent(out) :: value   !< F_n(h)
      type(egw_error), allocatable, intent(out) :: error   !< allocated for invalid n or h
      value = 0.0_dp
      call check_gauss_args(n, h, error)
      if (allocated(error)) return
      value = gauss_integral(n, h)
      call check_gauss_value(n, h, value, error)
   end subroutine get_gauss_integral

   !> dF_n/dh with the checks of get_gauss_integral.
   pure subroutine get_gauss_integral_deriv(n, h, value, error)
      real(dp), intent(in) :: n  !< order, n >= 0
      real(dp), intent(in) :: h  !< lower limit (separation in units of sigma)
      real(dp), intent(out) :: value   !< dF_n/dh
      type(egw_error), allocatable, intent(out) :: error   !< allocated for invalid n or h
      value = 0.0_dp
      call check_gauss_args(n, h, error)
      if (allocated(error)) return
      value = gauss_integral_deriv(n, h)
      call check_gauss_value(n, h, value, error)
   end subroutine get_gauss_integral_deriv

   !> A value beyond the doubles (F_n(h) ~ |h|**n for h -> -Inf) is refused.
   pure subroutine check_gauss_value(n, h, value, error)
      real(dp), intent(in) :: n, h, value
      type(egw_error), allocatable, intent(out) :: error
      if (.not. ieee_is_finite(value)) call fatal_error(error, egw_invalid_argument, "h = " &
         & //format_real(h)//": F_n(h) or its derivative exceeds the largest double at n = " &
         & //format_real(n))
   end subroutine check_gauss_value

   pure subroutine check_gauss_args(n, h, error)
      real(dp), intent(in) :: n, h
      type(egw_error), allocatable, intent(out) :: error
      if (ieee_is_nan(n) .or. n < 0.0_dp .or. n > max_order) then
         call fatal_error(error, egw_invalid_argument, "n = "//format_real(n)// &
            & ": the order of the Gaussian integral must lie in [0, "// &
            & format_real(max_order)//"] (Gamma((n+1)/2)-sized intermediates overflow" &
            & //" beyond n ~ 170)")
      else if (ieee_is_nan(h)) then
         call fatal_error(error, egw_invalid_argument, "h = "//format_real(h)// &
            & ": the lower limit of the Gaussian integral must not be NaN")
      end if
   end subroutine check_gauss_args

   !> F_{-1/2}(h) (the derivative of F_{1/2} is -F_{-1/2}/2).
   elemental real(dp) function gauss_fm12(h)
      real(dp), intent(in) :: h   !< separation/sigma
      gauss_fm12 = fitted(ord_m12, h)
   end function gauss_fm12

   !> F_0(h) = erfc(h/sqrt 2)/2, accurate to a few ulp up to the underflow.
   elemental real(dp) function gauss_f0(h)
      real(dp), intent(in) :: h   !< separation/sigma
      gauss_f0 = fitted(ord_0, h)
   end function gauss_f0

   !> F_{1/2}(h).
   elemental real(dp) function gauss_f12(h)
      real(dp), intent(in) :: h   !< separation/sigma
      gauss_f12 = fitted(ord_12, h)
   end function gauss_f12

   !> F_1(h) = phi(h) - h F_0(h), without the cancellation of that formula for h > 0.
   elemental real(dp) function gauss_f1(h)
      real(dp), intent(in) :: h   !< separation/sigma
      gauss_f1 = fitted(ord_1, h)
   end function gauss_f1

   !> F_{3/2}(h), the elastic GW rough-flat pressure (eq. 9), the hot kernel.
   elemental real(dp) function gauss_f32(h)
      real(dp), intent(in) :: h   !< separation/sigma
      gauss_f32 = fitted(ord_32, h)
   end function gauss_f32

   !> F_{5/2}(h) (far-field force of a rigid rough sphere, doc/theory.md §5).
   elemental real(dp) function gauss_f52(h)
      real(dp), intent(in) :: h   !< separation/sigma
      gauss_f52 = fitted(ord_52, h)
   end function gauss_f52

   !> Standard normal density phi(h) with h^2/2 formed exactly, so that the relative
   !> error stays at an ulp or two right up to the underflow (h ~ 38.6).
   elemental real(dp) function normal_density(h) result(phi)
      real(dp), intent(in) :: h   !< any double
      phi = inv_sqrt2pi*exp_neg_half_square(h, 0.0_dp)
   end function normal_density

   !> Truncated ZMC integrals (doc/theory.md §2; x = s - h, lambda = (x-e)/(q-e)):
   !>   i_e  = int_0^e x^(3/2) phi(h+x) dx
   !>   i_ep = int_e^q [1 - (1-K) ln(q/x)/ln(q/e)] (1 + 3 lambda^2 - 2 lambda^3) x phi(h+x) dx
   !>   i_p  = int_q^inf x phi(h+x) dx = F_1(h+q) + q F_0(h+q)
   !> and their exact h-derivatives, boundary terms included (they cancel in the ZMC sum
   !> i_e + (i_ep + 2 i_p)/(K psi) because the law is continuous, see rough_flat_law).
   !> e = delta_ep/sigma = 1/psi^2 > 0, q = rho_p e > e, 0 < K < 1 (not checked).
   pure subroutine zmc_integrals(h, e, q, hardness_coeff, i_e, i_ep, i_p, di_e, di_ep, di_p)
      real(dp), intent(in) :: h               !< separation of the summit base plane / sigma
      real(dp), intent(in) :: e               !< delta_ep / sigma
      real(dp), intent(in) :: q               !< delta_p / sigma
      real(dp), intent(in) :: hardness_coeff  !< ZMC K
      real(dp), intent(out) :: i_e   !< elastic part int_0^e
      real(dp), intent(out) :: i_ep   !< elastic-plastic part int_e^q
      real(dp), intent(out) :: i_p   !< fully plastic part int_q^inf
      real(dp), intent(out) :: di_e   !< d i_e/dh
      real(dp), intent(out) :: di_ep   !< d i_ep/dh
      real(dp), intent(out) :: di_p   !< d i_p/dh
      real(dp) :: j_e, j_ep, m3, m4, f0, phi_e, phi_q, b1, b2
      ! Two exact forms of d/dh int_a^b g(x) phi(h+x) dx: under the integral sign,
      ! -int g(x) (h+x) phi(h+x) dx, which cancels when the Gaussian sits inside a long
      ! interval, and by parts, g(b) phi(h+b) - g(a) phi(h+a) - int g' phi, which cancels
      ! when the interval is short. Each is taken where its terms are smaller (|sum of
      ! magnitudes| is the rounding error bound of either).
      phi_e = shifted_density(h, e)
      phi_q = shifted_density(h, q)
      call gauss_moments(kind_power32, 1.5_dp, e, q, hardness_coeff, 0.0_dp, e, h, .true., &
         & i_e, j_e, m3, m4)
      b1 = e*sqrt(e)*phi_e
      b2 = 1.5_dp*j_e
      if (m4 <= b1 + b2) then
         di_e = -m3
      else
         di_e = b1 - b2
      end if
      call gauss_moments(kind_ep, 1.0_dp, e, q, hardness_coeff, e, q, h, .true., i_ep, j_ep, &
         & m3, m4)
      b1 = 2.0_dp*q*phi_q
      b2 = hardness_coeff*e*phi_e
      if (m4 <= b1 + b2 + abs(j_ep)) then
         di_ep = -m3
      else
         di_ep = (b1 - b2) - j_ep
      end if
      call plastic_part(h, q, i_p, di_p, f0)
   end subroutine zmc_integrals

   !> I_p = F_1(h+q) + q F_0(h+q) and dI_p/dh = -q phi(h+q) - F_0(h+q). The rounding error
   !> t of h + q = s + t would cost (h+q)^2 ulp (3e-14 at h+q = 16); it is put back by
   !> first-order Taylor terms, dF_1 = -F_0 t and dF_0 = -phi t. Also returns F_0(h+q).
   elemental subroutine plastic_part(h, q, i_p, di_p, f0)
      real(dp), intent(in) :: h, q
      real(dp), intent(out) :: i_p, di_p, f0
      real(dp) :: s, t, phi
      call two_sum(h, q, s, t)
      if (.not. abs(s) <= huge(s)) t = 0.0_dp  ! h = +-Inf: two_sum leaves t = NaN
      phi = inv_sqrt2pi*exp_neg_half_square(s, t)
      f0 = gauss_f0(s) - phi*t
      i_p = (gauss_f1(s) - f0*t) + q*f0
      di_p = -q*phi - f0
   end subroutine plastic_part

   !> The ZMC rough-flat integral p = I_e + (I_ep + 2 I_p) sqrt(e)/K (doc/theory.md §3 with
   !> 1/psi = sqrt(e); doc/theory.md §6 misprint 4) and dp/dh = -int f'(x) phi(h+x) dx, where f is
   !> the whole (continuous) ZMC law in units of sigma: the boundary terms of the pieces
   !> cancel, so they are left out rather than cancelled numerically.
   pure subroutine zmc_flat_integral(h, e, q, hardness_coeff, p, dpdh)
      real(dp), intent(in) :: h               !< separation of the summit base plane / sigma
      real(dp), intent(in) :: e               !< delta_ep / sigma = 1/psi^2
      real(dp), intent(in) :: q               !< delta_p / sigma = rho_p e
      real(dp), intent(in) :: hardness_coeff  !< ZMC K
      real(dp), intent(out) :: p     !< the integral p(h)
      real(dp), intent(out) :: dpdh  !< dp/dh
      real(dp) :: i_e, j_e, i_ep, j_ep, unused, unused4, i_p, di_p, f0, c
      call gauss_moments(kind_power32, 1.5_dp, e, q, hardness_coeff, 0.0_dp, e, h, .false., &
         & i_e, j_e, unused, unused4)
      call gauss_moments(kind_ep, 1.0_dp, e, q, hardness_coeff, e, q, h, .false., i_ep, j_ep, &
         & unused, unused4)
      call plastic_part(h, q, i_p, di_p, f0)
      c = sqrt(e)/hardness_coeff
      p = i_e + c*(i_ep + 2.0_dp*i_p)
      ! f' = (3/2) x^(1/2) below e, g_ep' between e and q, 2 sqrt(e)/K beyond q
      dpdh = -(1.5_dp*j_e + c*(j_ep + 2.0_dp*f0))
   end subroutine zmc_flat_integral

   ! ---------------------------------------------------------------------------------------

   !> Exact equality of reals, spelled so that -Wcompare-reals sees it is intended.
   elemental logical function same(a, b)
      real(dp), intent(in) :: a, b
      same = abs(a - b) <= 0.0_dp
   end function same

   !> phi(h + x) with the sum h + x carried exactly into the exponent.
   elemental real(dp) function shifted_density(h, x) result(phi)
      real(dp), intent(in) :: h, x   !< the two terms of the argument h + x
      real(dp) :: zh, zl
      call two_sum(h, x, zh, zl)
      phi = inv_sqrt2pi*exp_neg_half_square(zh, zl)
   end function shifted_density

   !> exp(-(zh + zl)^2/2) for a double-double argument (|zl| <= ulp(zh)): the big part
   !> hi^2/2 is exact (Dekker split), the rest is small and enters through a short series.
   elemental real(dp) function exp_neg_half_square(zh, zl) result(r)
      real(dp), intent(in) :: zh, zl
      real(dp) :: a, c, hi, lo, small
      a = abs(zh)
      if (a < 1.0_dp) then
         r = exp(-0.5_dp*zh*zh - zh*zl)
      else if (a > 40.0_dp) then  ! exp(-800) underflows; also catches Inf
         r = 0.0_dp
      else
         c = splitter*a
         hi = c - (c - a)
         lo = a - hi
         small = 0.5_dp*lo*(a + hi) + zh*zl
         ! |small| < 2e-5, so the cubic is exp(-small) to 1e-21
         r = exp(-0.5_dp*hi*hi)*(1.0_dp - small*(1.0_dp - small*(0.5_dp - small*sixth)))
      end if
   end function exp_neg_half_square

   !> exp(704 - h^2/2) for 37 <= |h| <= 40, formed like exp_neg_half_square; 704 - hi^2/2
   !> is exact there (Sterbenz), so a subnormal F_n needs one rounding only.
   elemental real(dp) function exp_neg_half_square_scaled(h) result(r)
      real(dp), intent(in) :: h
      real(dp) :: a, c, hi, lo, small
      a = abs(h)
      c = splitter*a
      hi = c - (c - a)
      lo = a - hi
      small = 0.5_dp*lo*(a + hi)
      r = exp(shift704 - 0.5_dp*hi*hi)*(1.0_dp - small*(1.0_dp - small*(0.5_dp - small*sixth)))
   end function exp_neg_half_square_scaled

   !> Knuth's two-sum: s + t = a + b exactly.
   elemental subroutine two_sum(a, b, s, t)
      real(dp), intent(in) :: a, b
      real(dp), intent(out) :: s, t
      real(dp) :: v
      s = a + b
      v = s - a
      t = (a - (s - v)) + (b - v)
   end subroutine two_sum

   !> Fitted F_n: G_n = F_n/phi by polynomial pieces for 0 <= h < 40 (F_n underflows beyond),
   !> F_n itself for -12 <= h < 0, the asymptotic expansion below -12.
   elemental real(dp) function fitted(iord, h) result(f)
      integer, intent(in) :: iord
      real(dp), intent(in) :: h
      real(dp), parameter :: order(6) = [-0.5_dp, 0.0_dp, 0.5_dp, 1.0_dp, 1.5_dp, 2.5_dp]
      real(dp) :: a, b, t, g, fl
      integer :: i
      if (h >= 0.0_dp) then
         if (h >= 40.0_dp) then
            f = 0.0_dp
            return
         end if
         if (h < 8.0_dp) then
            i = int(h) + 1
         else if (h < 10.0_dp) then
            i = 9
         else if (h < 12.0_dp) then
            i = 10
         else if (h < 16.0_dp) then
            i = 11
         else if (h < 24.0_dp) then
            i = 12
         else
            i = 13
         end if
         a = fit_pos_breaks(i - 1)
         b = fit_pos_breaks(i)
         t = (2.0_dp*h - (a + b))/(b - a)
         g = power_series(fit_pos(:, i, iord), fit_deg_pos(i, iord), t)
         if (h < 37.0_dp) then
            f = g*normal_density(h)
         else
            f = (g*inv_sqrt2pi*exp_neg_half_square_scaled(h))*exp_m704
         end if
      else if (h >= -12.0_dp) then
         fl = floor(h)
         i = int(fl) + 13
         t = 2.0_dp*(h - fl) - 1.0_dp
         f = power_series(fit_neg(:, i, iord), fit_deg_neg(i, iord), t)
      else if (h < 0.0_dp) then
         f = asymptotic_negative(order(iord), h)
      else  ! NaN
         f = h
      end if
   end function fitted

   !> Polynomial sum_k c_k t^k, k = 0..deg (c zero padded to whole groups of four), by
   !> Estrin's scheme: the groups c_4k + c_4k+1 t + (c_4k+2 + c_4k+3 t) t^2 are independent,
   !> so the serial chain is a Horner recurrence in t^4 of deg/4 steps only.
   pure real(dp) function power_series(c, deg, t) result(s)
      real(dp), intent(in) :: c(0:fit_store - 1)
      integer, intent(in) :: deg
      real(dp), intent(in) :: t
      real(dp) :: t2, t4
      integer :: k
      t2 = t*t
      t4 = t2*t2
      k = 4*(deg/4)
      s = (c(k) + c(k + 1)*t) + (c(k + 2) + c(k + 3)*t)*t2
      do k = 4*(deg/4) - 4, 0, -4
         s = s*t4 + ((c(k) + c(k + 1)*t) + (c(k + 2) + c(k + 3)*t)*t2)
      end do
   end function power_series

   !> h -> -inf: F_n = E[(X - h)_+^n] = |h|^n sum_k C(n,2k) (2k-1)!! h^(-2k) up to a term of
   !> order phi(h) (the mass of X below h), i.e. e^-72 relative at h = -12.
   elemental real(dp) function asymptotic_negative(n, h) result(f)
      real(dp), intent(in) :: n, h
      real(dp) :: x, term, s
      integer :: k
      x = 1.0_dp/(h*h)
      term = 1.0_dp
      s = 1.0_dp
      do k = 0, 80
         ! C(n,2k+2)(2k+1)!!/(C(n,2k)(2k-1)!!) = (n-2k)(n-2k-1)/(2k+2)
         term = term*((n - 2*k)*(n - 2*k - 1)/(2*k + 2))*x
         s = s + term
         if (abs(term) <= 1.0e-17_dp*abs(s)) exit
      end do
      f = abs(h)**n*s
   end function asymptotic_negative

   !> F_n for an order without a fit: asymptotic expansion far left, otherwise the panel
   !> quadrature of int_0^inf x^n phi(h + x) dx.
   elemental real(dp) function general_order(n, h) result(f)
      real(dp), intent(in) :: n, h
      real(dp) :: unused, unused3, unused4
      if (ieee_is_nan(h) .or. ieee_is_nan(n)) then
         f = h + n
      else if (h < -max(12.0_dp, 2.0_dp*n + 2.0_dp)) then
         f = asymptotic_negative(n, h)
      else
         call gauss_moments(kind_power, n, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, huge(1.0_dp), h, &
            & .false., f, unused, unused3, unused4)
      end if
   end function general_order

   !> m1 = int_a^b g1(x) phi(h + x) dx, m2 = int_a^b g2(x) phi(h + x) dx and
   !> m3 = int_a^b g1(x) (h + x) phi(h + x) dx, m4 = the same with |h + x| (the size of the
   !> terms that cancel in m3), 0 <= a < b, for the integrand kinds above,
   !> by composite 16-point Gauss-Legendre.
   !> Panels start at the peak x_m of the Gaussian factor on [a, b] and march outwards
   !> until the factor has lost loss_max e-folds; widths are set by the local exponent
   !> change (dloss) and, for x^p and log x, by the distance to x = 0 (panel_ratio). A panel
   !> touching x = 0 with a branch point there is done by its Taylor series instead.
   !> All node values are scaled by phi(h + x_m), formed exactly, so nothing overflows and
   !> nothing cancels in the exponent. with_m34 false: m3 and m4 are not wanted (the
   !> rough-flat law and F_n take m1, m2 only), and the panels skip their sums (a sixth
   !> of a panel's work; m1, m2 the same to the bit), so that m3 and m4 are meaningless.
   pure subroutine gauss_moments(kind, p, e, q, kc, a, b, h, with_m34, m1, m2, m3, m4)
      integer, intent(in) :: kind
      real(dp), intent(in) :: p, e, q, kc, a, b, h
      logical, intent(in) :: with_m34
      real(dp), intent(out) :: m1, m2, m3, m4
      real(dp) :: xm, zh, zl, lo_end, hi_end, x, w, s1, s2, s3, s4, loss, slope, dl, lnqe
      real(dp) :: r1, r2, r3, r4, ratio, pw, lmax, f
      integer :: ip
      m1 = 0.0_dp
      m2 = 0.0_dp
      m3 = 0.0_dp
      m4 = 0.0_dp
      xm = min(max(-h, a), b)
      call two_sum(h, xm, zh, zl)
      if (abs(zh) > 40.0_dp) return  ! phi(h + x) < e^-800 on all of [a, b]: underflow
      lnqe = 0.0_dp
      ! Polynomial factors are integrated exactly, but a high power x^p (general order)
      ! also grows by p ln(1 + ratio) e-folds over a panel: keep that below power_span.
      select case (kind)
      case (kind_ep)
         lnqe = log(q/e)
         pw = 4.0_dp  ! x (1 + 3 lambda^2 - 2 lambda^3) grows at most like x^4
      case (kind_power32)
         pw = 1.5_dp
      case default
         pw = max(abs(p), 1.0_dp)
      end select
      ratio = panel_ratio
      if (kind == kind_power) ratio = min(panel_ratio, exp(power_span/pw) - 1.0_dp)
      ! The integrand peaks up to p e-folds beyond the Gaussian's peak and the tail of
      ! x^p e^-loss beyond loss L is ~ e^-L L^p/p!: widen the kept region accordingly.
      lmax = loss_max + 3.0_dp*pw
      ! region where the Gaussian factor is above e^-loss_max of its peak
      lo_end = a
      hi_end = b
      if (xm > a) lo_end = max(a, xm - 2.0_dp*lmax/(-zh + sqrt(zh*zh + 2.0_dp*lmax)))
      if (xm < b) hi_end = min(b, xm + 2.0_dp*lmax/(zh + sqrt(zh*zh + 2.0_dp*lmax)))
      s1 = 0.0_dp
      s2 = 0.0_dp
      s3 = 0.0_dp
      s4 = 0.0_dp
      ! march right from the peak
      x = xm
      do ip = 1, max_panels
         if (x >= hi_end) exit
         if (.not. x > 0.0_dp .and. kind /= kind_ep) then
            w = min(series_width(h), hi_end)
            call series_panel(kind, p, h, w, r1, r2, r3, r4)
            f = loss_factor(0.0_dp)
            s1 = s1 + r1*f
            s2 = s2 + r2*f
            s3 = s3 + r3*f
            s4 = s4 + r4*f
         else
            loss = loss_at(x)
            slope = abs(zh + (x - xm))
            dl = min(dloss_peak + loss, dloss_cap)
            w = 2.0_dp*dl/(slope + sqrt(slope*slope + 2.0_dp*dl))
            w = min(w, ratio*x)
            w = min(w, hi_end - x)
            call gl_panel(x, x + w, r1, r2, r3, r4)
            s1 = s1 + r1
            s2 = s2 + r2
            s3 = s3 + r3
            s4 = s4 + r4
         end if
         x = x + w
      end do
      ! march left from the peak
      x = xm
      do ip = 1, max_panels
         if (x <= lo_end) exit
         if (.not. lo_end > 0.0_dp .and. kind /= kind_ep .and. x <= series_width(h)) then
            call series_panel(kind, p, h, x, r1, r2, r3, r4)
            f = loss_factor(0.0_dp)
            s1 = s1 + r1*f
            s2 = s2 + r2*f
            s3 = s3 + r3*f
            s4 = s4 + r4*f
            exit
         end if
         loss = loss_at(x)
         slope = abs(zh + (x - xm))
         dl = min(dloss_peak + loss, dloss_cap)
         w = 2.0_dp*dl/(slope + sqrt(slope*slope + 2.0_dp*dl))
         w = min(w, ratio*x/(1.0_dp + ratio))
         w = min(w, x - lo_end)
         call gl_panel(x - w, x, r1, r2, r3, r4)
         s1 = s1 + r1
         s2 = s2 + r2
         s3 = s3 + r3
         s4 = s4 + r4
         x = x - w
      end do
      if (kind == kind_power .and. zh > 37.0_dp) then
         ! phi(h) is subnormal from h ~ 37.6 on, where a high order's F_n is not (F_150(38.6)
         ! = 1.6e-304): scaled by e^704 and back, as `fitted` does (here x_m = 0, zl = 0).
         r1 = inv_sqrt2pi*exp_neg_half_square_scaled(zh)
         m1 = (s1*r1)*exp_m704
         m2 = (s2*r1)*exp_m704
      else
         r1 = inv_sqrt2pi*exp_neg_half_square(zh, zl)
         m1 = s1*r1
         m2 = s2*r1
         m3 = s3*r1
         m4 = s4*r1
      end if

   contains

      !> e-folds lost by the Gaussian factor between x_m and x: ((h+x)^2 - (h+x_m)^2)/2.
      pure real(dp) function loss_at(x) result(l)
         real(dp), intent(in) :: x
         l = 0.5_dp*(x - xm)*(2.0_dp*zh + (x - xm))
      end function loss_at

      pure real(dp) function loss_factor(x) result(f)
         real(dp), intent(in) :: x
         f = exp(-loss_at(x))
      end function loss_factor

      !> Widest [0, w] whose exponent change |h| w + w^2/2 is series_span.
      pure real(dp) function series_width(h) result(w)
         real(dp), intent(in) :: h
         w = 2.0_dp*series_span/(abs(h) + sqrt(h*h + 2.0_dp*series_span))
      end function series_width

      !> 16-point Gauss-Legendre on [x0, x1] of g * exp(-loss), relative to phi(h + x_m).
      pure subroutine gl_panel(x0, x1, r1, r2, r3, r4)
         real(dp), intent(in) :: x0, x1
         real(dp), intent(out) :: r1, r2, r3, r4
         real(dp) :: half, d0, off(16), dlt(16), fac(16), g1(16), g2(16), z(16)
         half = 0.5_dp*(x1 - x0)
         d0 = x0 - xm
         off = half*gl_u
         dlt = d0 + off
         ! weight times phi(h + x)/phi(h + x_m) at the 16 nodes
         fac = gl_w16*exp(-0.5_dp*dlt*(2.0_dp*zh + dlt))
         call integrand(kind, x0 + off, p, e, q, kc, lnqe, g1, g2)
         r1 = half*sum(fac*g1)
         r2 = half*sum(fac*g2)
         r3 = 0.0_dp
         r4 = 0.0_dp
         if (.not. with_m34) return
         ! h + x = (h + x_m) + (x - x_m), exact up to two roundings
         z = (zh + dlt) + zl
         r3 = half*sum(fac*g1*z)
         r4 = half*sum(fac*g1*abs(z))
      end subroutine gl_panel

   end subroutine gauss_moments

   !> The asperity-law integrands g1 (and g2 where needed) at the 16 nodes x > 0.
   pure subroutine integrand(kind, x, p, e, q, kc, lnqe, g1, g2)
      integer, intent(in) :: kind
      real(dp), intent(in) :: x(16), p, e, q, kc, lnqe
      real(dp), intent(out) :: g1(16), g2(16)
      real(dp) :: lam(16), area(16), pres(16), inv_width, slope
      select case (kind)
      case (kind_power32)
         g2 = sqrt(x)
         g1 = x*g2
      case (kind_ep)
         ! eqs. (40)-(43) in units of sigma: mean pressure ratio pres (eq. 40), area factor
         ! 1 + 3 lambda^2 - 2 lambda^3 (eq. 41); g1 = pres * area * x and g2 = d g1/dx
         inv_width = 1.0_dp/(q - e)
         slope = (1.0_dp - kc)/lnqe
         lam = (x - e)*inv_width
         area = 1.0_dp + lam*lam*(3.0_dp - 2.0_dp*lam)
         pres = 1.0_dp - slope*log(q/x)
         g1 = pres*area*x
         g2 = slope*area + pres*(6.0_dp*inv_width*lam*(1.0_dp - lam)*x + area)
      case default
         g1 = x**p
         g2 = 0.0_dp
      end select
   end subroutine integrand

   !> int_0^w x^p e^(-h x - x^2/2) dx (and the same with x^(p-1) for kind_power32) by the
   !> Taylor series of the exponential: with d_k the coefficients of (w x')^k,
   !> (k+1) d_(k+1) = -h w d_k - w^2 d_(k-1), the integral is w^(p+1) sum_k d_k/(p+k+1).
   !> kind_power32 (p = 3/2, the rough flat's elastic summits: every loading-law call whose
   !> kept region reaches x = 0) multiplies by the reciprocals 1/k and 1/(k + 1/2), constants
   !> rounded once at compile time, instead of dividing: four divisions an iteration, one
   !> of them in the recurrence's dependency chain, made this loop ~20 % of the ZMC
   !> loading law (perf, psi = 1); the sums move by an ulp or two (a product with a
   !> rounded reciprocal rounds twice).
   pure subroutine series_panel(kind, p, h, w, r1, r2, r3, r4)
      integer, intent(in) :: kind
      real(dp), intent(in) :: p, h, w
      real(dp), intent(out) :: r1, r2, r3, r4
      real(dp) :: hw, w2, dkm1, dk, dnext, sum1, sum2, sum3
      integer :: k
      !> 1/k and 1/(k + 1/2), k = 1 .. 85 (the loop's k runs to 80)
      real(dp), parameter :: inv_k(85) = [(1.0_dp/real(k, dp), k=1, 85)]
      real(dp), parameter :: inv_half(85) = [(1.0_dp/(real(k, dp) + 0.5_dp), k=1, 85)]
      hw = h*w
      w2 = w*w
      dkm1 = 0.0_dp
      dk = 1.0_dp
      sum1 = 1.0_dp/(p + 1.0_dp)
      sum2 = 0.0_dp
      sum3 = 1.0_dp/(p + 2.0_dp)
      if (kind == kind_power32) then
         ! 1/(p + 1), 1/p, 1/(p + 2) and, below, 1/(p + k + 2), 1/(p + k + 1),
         ! 1/(p + k + 3) with p = 3/2
         sum1 = inv_half(2)
         sum2 = inv_half(1)
         sum3 = inv_half(3)
         do k = 0, 80
            dnext = (-hw*dk - w2*dkm1)*inv_k(k + 1)
            dkm1 = dk
            dk = dnext
            sum1 = sum1 + dk*inv_half(k + 3)
            sum2 = sum2 + dk*inv_half(k + 2)
            sum3 = sum3 + dk*inv_half(k + 4)
            if (abs(dk) + abs(dkm1) <= 1.0e-17_dp*abs(sum1)) exit
         end do
      else
         do k = 0, 80
            dnext = (-hw*dk - w2*dkm1)/(k + 1)
            dkm1 = dk
            dk = dnext
            sum1 = sum1 + dk/(p + k + 2)
            sum2 = sum2 + dk/(p + k + 1)
            sum3 = sum3 + dk/(p + k + 3)
            if (abs(dk) + abs(dkm1) <= 1.0e-17_dp*abs(sum1)) exit
         end do
      end if
      if (kind == kind_power32) then
         r2 = w*sqrt(w)*sum2
         r1 = w*w*sqrt(w)*sum1
         ! int x^(3/2) (h + x) e^(...) = h r1 + int x^(5/2) e^(...)
         r3 = h*r1 + w*w*w*sqrt(w)*sum3
         ! a bound on int x^(3/2) |h + x| e^(...), enough to choose a derivative form
         r4 = abs(h)*r1 + w*w*w*sqrt(w)*abs(sum3)
      else
         r1 = w**(p + 1.0_dp)*sum1
         r2 = 0.0_dp
         r3 = 0.0_dp
         r4 = 0.0_dp
      end if
   end subroutine series_panel

end module egw_gauss
