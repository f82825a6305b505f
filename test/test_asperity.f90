!> Tests of egw_asperity: the asperity laws (continuity, limits) and the rough-flat law
!> against mpmath values (test/ref_gauss.f90, tools/reference/gauss_refs.py).
module test_asperity
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, &
      & ieee_negative_inf, ieee_is_nan
   use testdrive, only: new_unittest, unittest_type, error_type, check, test_failed
   use egw_kinds, only: pi
   use egw_all, only: dp, hertz_asperity_force, zmc_asperity_force, rough_flat_law, &
      & flat_pressure, contact_params, model_egw, model_epgw, egw_error, &
      & egw_invalid_argument, egw_invalid_parameter, gauss_f32, gauss_f12
   use ref_gauss, only: ref_fn, ref_zmc
   implicit none
   private
   public :: collect_asperity

   ! ZMC test material: E = 1, beta = 1, H = 0.5, K = 0.6, rho_p = 54
   real(dp), parameter :: e_mod = 1.0_dp, beta = 1.0_dp, hard = 0.5_dp, kc = 0.6_dp, &
      & rho = 54.0_dp

contains

   subroutine collect_asperity(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("Hertz asperity", test_hertz), &
         & new_unittest("ZMC law: regimes", test_zmc_regimes), &
         & new_unittest("ZMC law: continuous at delta_ep and delta_p", test_zmc_continuity), &
         & new_unittest("rough-flat law against mpmath", test_flat_law_refs), &
         & new_unittest("rough-flat law: elastic limit psi -> 0", test_elastic_limit), &
         & new_unittest("rough-flat law is decreasing", test_monotone), &
         & new_unittest("flat pressure: scaling and model choice", test_flat_pressure), &
         & new_unittest("flat pressure: bad input", test_flat_pressure_errors) &
         & ]
   end subroutine collect_asperity

   !> (4/3) E beta^(1/2) x^(3/2) with E = 3, beta = 4, x = 1/4 is exactly 1 (eq. 5 with the
   !> corrected 4/3, doc/theory.md §6 misprint 1); no force without overlap.
   subroutine test_hertz(error)
      type(error_type), allocatable, intent(out) :: error
      call check(error, hertz_asperity_force(0.25_dp, 3.0_dp, 4.0_dp), 1.0_dp, thr=4e-16_dp)
      if (allocated(error)) return
      call check(error, hertz_asperity_force(0.0_dp, 3.0_dp, 4.0_dp), 0.0_dp)
      if (allocated(error)) return
      call check(error, hertz_asperity_force(-1.0_dp, 3.0_dp, 4.0_dp), 0.0_dp)
   end subroutine test_hertz

   real(dp) function d_ep()
      d_ep = (3.0_dp*pi*kc*hard/(4.0_dp*e_mod))**2*beta  ! eq. (36)
   end function d_ep

   real(dp) function zmc(x)
      real(dp), intent(in) :: x
      zmc = zmc_asperity_force(x, e_mod, beta, hard, kc, rho)
   end function zmc

   !> Each regime of eq. (42): Hertz below delta_ep, 2 pi H beta x above delta_p, and the
   !> eqs. (40)-(43) blend at the geometric mean of delta_ep and delta_p, where
   !> ln(delta_p/x)/ln(delta_p/delta_ep) = 1/2 (values to a few ulp: 1e-15).
   subroutine test_zmc_regimes(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: x, lam, expected
      x = 0.5_dp*d_ep()
      call check(error, zmc(x), hertz_asperity_force(x, e_mod, beta), rel=.true., thr=1e-15_dp)
      if (allocated(error)) return
      x = 3.0_dp*rho*d_ep()
      call check(error, zmc(x), 2.0_dp*pi*hard*beta*x, rel=.true., thr=1e-15_dp)
      if (allocated(error)) return
      x = sqrt(rho)*d_ep()
      lam = (sqrt(rho) - 1.0_dp)/(rho - 1.0_dp)
      expected = pi*hard*beta*(1.0_dp - 0.5_dp*(1.0_dp - kc))*(1.0_dp + 3*lam**2 - 2*lam**3)*x
      call check(error, zmc(x), expected, rel=.true., thr=1e-14_dp)
      if (allocated(error)) return
      call check(error, zmc(0.0_dp), 0.0_dp)
   end subroutine test_zmc_regimes

   !> The force is continuous at delta_ep and delta_p: over [d(1-eps), d(1+eps)] with
   !> eps = 1e-10 it may change by slope * 2 eps d ~ 3e-10 relative, so 1e-8 separates
   !> continuity from any real jump (the paper's eq. 45 prefactor misprint gives 25 %).
   !> The slope is NOT continuous; from eqs. (40)-(43) it drops at both points: at delta_ep
   !> from (3/2) f/x to (1 + (1-K)/(K ln rho)) f/x, at delta_p from (1 + (1-K)/ln rho) f/x
   !> to f/x. One-sided difference quotients (step 1e-6, truncation error ~1e-6 relative)
   !> must match those slopes to 1e-5.
   subroutine test_zmc_continuity(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: eps = 1.0e-10_dp, h = 1.0e-6_dp
      real(dp) :: d, below, above, slope_lo, slope_hi, f
      d = d_ep()
      below = zmc(d*(1.0_dp - eps))
      above = zmc(d*(1.0_dp + eps))
      call check(error, abs(above - below) <= 1.0e-8_dp*below, "jump at delta_ep")
      if (allocated(error)) return
      f = zmc(d)
      slope_lo = (f - zmc(d*(1.0_dp - h)))/(d*h)
      slope_hi = (zmc(d*(1.0_dp + h)) - f)/(d*h)
      call check(error, slope_lo, 1.5_dp*f/d, rel=.true., thr=1e-5_dp, &
         & message="elastic slope at delta_ep")
      if (allocated(error)) return
      call check(error, slope_hi, (kc + (1.0_dp - kc)/log(rho))*f/(kc*d), rel=.true., &
         & thr=1e-5_dp, message="elasto-plastic slope at delta_ep")
      if (allocated(error)) return
      d = rho*d_ep()
      below = zmc(d*(1.0_dp - eps))
      above = zmc(d*(1.0_dp + eps))
      call check(error, abs(above - below) <= 1.0e-8_dp*below, "jump at delta_p")
      if (allocated(error)) return
      f = zmc(d)
      slope_lo = (f - zmc(d*(1.0_dp - h)))/(d*h)
      slope_hi = (zmc(d*(1.0_dp + h)) - f)/(d*h)
      call check(error, slope_lo, (1.0_dp + (1.0_dp - kc)/log(rho))*f/d, rel=.true., &
         & thr=1e-5_dp, message="elasto-plastic slope at delta_p")
      if (allocated(error)) return
      call check(error, slope_hi, f/d, rel=.true., thr=1e-5_dp, message="plastic slope")
   end subroutine test_zmc_continuity

   !> p and dp/dh against mpmath: psi > 0 rows of ref_zmc (p and dp/dh computed there at 50
   !> digits from the integrals and their exact derivatives, not by differencing) to the
   !> issue's 1e-12 (absolute 1e-300 where they underflow); psi = 0 against F_3/2 and
   !> -(3/2) F_1/2 to the kernel's 1e-14 (2 subnormal ulps where they are subnormal).
   subroutine test_flat_law_refs(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: p, dpdh
      character(len=160) :: msg
      integer :: i
      do i = 1, size(ref_zmc, 2)
         call rough_flat_law(ref_zmc(1, i), ref_zmc(5, i), ref_zmc(4, i), ref_zmc(6, i), &
            & p, dpdh)
         if (.not. (abs(p - ref_zmc(13, i)) <= max(1e-12_dp*abs(ref_zmc(13, i)), 1e-300_dp) &
            & .and. abs(dpdh - ref_zmc(14, i)) <= max(1e-12_dp*abs(ref_zmc(14, i)), &
            & 1e-300_dp))) then
            write (msg, '("h=",es12.5," psi=",es9.2," K=",f4.2," rho=",es9.2,": p ",2es23.15, &
               & " dp ",2es23.15)') ref_zmc(1, i), ref_zmc(5, i), ref_zmc(4, i), ref_zmc(6, i), &
               & p, ref_zmc(13, i), dpdh, ref_zmc(14, i)
            call test_failed(error, trim(msg))
            return
         end if
      end do
      do i = 1, size(ref_fn, 2)
         if (abs(ref_fn(1, i) - 1.5_dp) > 0.0_dp) cycle
         call rough_flat_law(ref_fn(2, i), 0.0_dp, kc, rho, p, dpdh)
         if (.not. (close(p, ref_fn(3, i)) .and. close(dpdh, ref_fn(4, i)))) then
            write (msg, '("psi = 0, h=",es12.5,": p ",2es23.15," dp ",2es23.15)') &
               & ref_fn(2, i), p, ref_fn(3, i), dpdh, ref_fn(4, i)
            call test_failed(error, trim(msg))
            return
         end if
      end do
   contains
      !> 1e-14 relative for normal values; 2 subnormal ulps ("correctly small") below.
      logical function close(actual, expected)
         real(dp), intent(in) :: actual, expected
         if (abs(expected) >= tiny(1.0_dp)) then
            close = abs(actual - expected) <= 1.0e-14_dp*abs(expected)
         else
            close = abs(actual - expected) <= 2.0_dp*tiny(1.0_dp)*epsilon(1.0_dp)
         end if
      end function close
   end subroutine test_flat_law_refs

   !> psi -> 0 sends delta_ep to infinity: at psi = 0.01 (e = 1e4) every summit that can
   !> touch is elastic, so p = F_3/2 and dp/dh = -(3/2) F_1/2 to rounding (1e-13); and the
   !> plastic reduction F_3/2 - p >= 0 shrinks monotonically as psi decreases.
   subroutine test_elastic_limit(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: psis(5) = [4.0_dp, 2.0_dp, 1.0_dp, 0.5_dp, 0.3_dp]
      real(dp) :: h, p, dpdh, gap, last, tol
      integer :: i, j
      do i = -6, 10
         h = 0.5_dp*i
         call rough_flat_law(h, 0.01_dp, kc, rho, p, dpdh)
         call check(error, p, gauss_f32(h), rel=.true., thr=1e-13_dp, message="p at psi=0.01")
         if (allocated(error)) return
         call check(error, dpdh, -1.5_dp*gauss_f12(h), rel=.true., thr=1e-13_dp, &
            & message="dp at psi=0.01")
         if (allocated(error)) return
      end do
      do i = -2, 2
         h = 1.0_dp*i
         last = huge(1.0_dp)
         do j = 1, size(psis)
            call rough_flat_law(h, psis(j), kc, rho, p, dpdh)
            ! at psi = 0.3 the true gap (~e^-60) is below rounding: 2e-15 relative allowed,
            ! the quadrature and the fit each being good to ~1e-15
            gap = gauss_f32(h) - p
            tol = 2.0e-15_dp*gauss_f32(h)
            call check(error, gap >= -tol .and. (gap < last .or. abs(gap) <= tol), &
               & "plastic reduction must shrink as psi decreases")
            if (allocated(error)) return
            last = gap
         end do
      end do
   end subroutine test_elastic_limit

   !> The law of increasing summit force integrated over a Gaussian: p decreases with h and
   !> dp/dh < 0 wherever p is not 0, for every plasticity index; at h = +Inf p = dp/dh = 0,
   !> at h = -Inf p = +Inf (no NaN either way).
   subroutine test_monotone(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: psis(5) = [0.0_dp, 0.1_dp, 1.0_dp, 10.0_dp, 100.0_dp]
      real(dp) :: h, p, dpdh, last
      integer :: i, j
      do j = 1, size(psis)
         last = huge(1.0_dp)
         do i = -400, 780
            h = 0.05_dp*i
            call rough_flat_law(h, psis(j), kc, rho, p, dpdh)
            if (p > last .or. (p > 0.0_dp .and. .not. dpdh < 0.0_dp)) then
               call test_failed(error, "p not decreasing or dp/dh >= 0")
               return
            end if
            last = p
         end do
         call rough_flat_law(ieee_value(h, ieee_positive_inf), psis(j), kc, rho, p, dpdh)
         call check(error, abs(p) + abs(dpdh) <= 0.0_dp, "p and dp/dh at h = +Inf must be 0")
         if (allocated(error)) return
         call rough_flat_law(ieee_value(h, ieee_negative_inf), psis(j), kc, rho, p, dpdh)
         call check(error, p > huge(p) .and. .not. ieee_is_nan(dpdh), "p(-Inf) = +Inf")
         if (allocated(error)) return
      end do
   end subroutine test_monotone

   !> p_G = C sigma^(3/2) p(d/sigma), dp_G/dd = C sigma^(1/2) dp/dh with
   !> C = mu E/(2 sigma sqrt(2R)) (eq. 9); ZMC only for EP-GW with psi > 0.
   subroutine test_flat_pressure(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: params
      type(egw_error), allocatable :: err
      real(dp) :: pg, dpg, c, p, dpdh, d, sigma
      sigma = 1.0e-3_dp
      d = 0.7_dp*sigma
      params = contact_params(model=model_egw, radius=2.0_dp, modulus=3.0_dp, sigma=sigma, &
         & mu=4.0_dp, psi=4.0_dp)
      c = 4.0_dp*3.0_dp/(2.0_dp*sigma*sqrt(4.0_dp))
      call flat_pressure(params, d, pg, dpg, err)
      call check(error, .not. allocated(err), "valid E-GW call rejected")
      if (allocated(error)) return
      call rough_flat_law(0.7_dp, 0.0_dp, kc, rho, p, dpdh)  ! E-GW ignores psi
      call check(error, pg, c*sigma**1.5_dp*p, rel=.true., thr=1e-14_dp, message="E-GW p_G")
      if (allocated(error)) return
      call check(error, dpg, c*sigma**0.5_dp*dpdh, rel=.true., thr=1e-14_dp, &
         & message="E-GW dp_G/dd")
      if (allocated(error)) return
      params%model = model_epgw
      call flat_pressure(params, d, pg, dpg, err)
      call check(error, .not. allocated(err), "valid EP-GW call rejected")
      if (allocated(error)) return
      call rough_flat_law(0.7_dp, 4.0_dp, params%hardness_coeff, params%plastic_ratio, p, dpdh)
      call check(error, pg, c*sigma**1.5_dp*p, rel=.true., thr=1e-14_dp, message="EP-GW p_G")
      if (allocated(error)) return
      call check(error, dpg, c*sigma**0.5_dp*dpdh, rel=.true., thr=1e-14_dp, &
         & message="EP-GW dp_G/dd")
      if (allocated(error)) return
      call check(error, pg < c*sigma**1.5_dp*gauss_f32(0.7_dp), "plasticity must lower p_G")
   end subroutine test_flat_pressure

   !> Bad parameters, sigma = 0 and a NaN separation give a status naming the culprit.
   subroutine test_flat_pressure_errors(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: params
      type(egw_error), allocatable :: err
      real(dp) :: pg, dpg, nan
      nan = ieee_value(nan, ieee_quiet_nan)
      params = contact_params(sigma=1.0e-3_dp, radius=-1.0_dp)
      call flat_pressure(params, 0.0_dp, pg, dpg, err)
      call expect(egw_invalid_parameter, "radius =")
      if (allocated(error)) return
      params = contact_params(sigma=1.0e-3_dp, model=model_epgw, hardness_coeff=1.5_dp)
      call flat_pressure(params, 0.0_dp, pg, dpg, err)
      call expect(egw_invalid_parameter, "hardness_coeff =")
      if (allocated(error)) return
      params = contact_params(sigma=0.0_dp)
      call flat_pressure(params, 0.0_dp, pg, dpg, err)
      call expect(egw_invalid_parameter, "sigma = 0")
      if (allocated(error)) return
      params = contact_params(sigma=1.0e-3_dp)
      call flat_pressure(params, nan, pg, dpg, err)
      call expect(egw_invalid_argument, "separation = NaN")
   contains
      subroutine expect(stat, prefix)
         integer, intent(in) :: stat
         character(len=*), intent(in) :: prefix
         call check(error, allocated(err), "bad input accepted: "//prefix)
         if (allocated(error)) return
         call check(error, err%stat, stat, "status for "//prefix)
         if (allocated(error)) return
         call check(error, index(err%message, prefix) == 1, "message: "//err%message)
      end subroutine expect
   end subroutine test_flat_pressure_errors

end module test_asperity
