!> Tests of egw_gauss against mpmath values (test/ref_gauss.f90, made by
!> tools/reference/gauss_refs.py from quadrature of the definitions at 50 digits).
module test_gauss
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, &
      & ieee_negative_inf, ieee_is_nan, ieee_is_finite
   use testdrive, only: new_unittest, unittest_type, error_type, check, test_failed
   use egw_all, only: dp, gauss_integral, gauss_integral_deriv, get_gauss_integral, gauss_f0, &
      & gauss_f12, gauss_f1, gauss_f32, gauss_f52, gauss_fm12, normal_density, zmc_integrals, &
      & egw_error, egw_invalid_argument
   use ref_gauss, only: ref_fn, ref_zmc
   implicit none
   private
   public :: collect_gauss

   !> Smallest normal double: below it a value can only be "correctly small".
   real(dp), parameter :: tiny_normal = tiny(1.0_dp)

contains

   subroutine collect_gauss(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("doc/theory.md check values of F_3/2", test_design_values), &
         & new_unittest("fitted orders to 1e-14", test_fitted_orders), &
         & new_unittest("other orders to 1e-12", test_general_orders), &
         & new_unittest("high orders where phi(h) is subnormal", test_high_orders_far), &
         & new_unittest("derivative dF_n/dh = -n F_(n-1)", test_derivative), &
         & new_unittest("named kernels equal gauss_integral", test_named_kernels), &
         & new_unittest("recurrence F_5/2 = 3/2 F_1/2 - h F_3/2", test_recurrence), &
         & new_unittest("infinite arguments and no NaN", test_limits), &
         & new_unittest("checked call rejects bad n and h", test_checked), &
         & new_unittest("ZMC integrals and derivatives", test_zmc) &
         & ]
   end subroutine collect_gauss

   !> |actual - expected| within rel*|expected| where expected is a normal double; in the
   !> subnormal range (and for 0) within 2 subnormal ulps ("correctly small"), which also
   !> covers the absolute 1e-300 floor.
   logical function close(actual, expected, rel)
      real(dp), intent(in) :: actual, expected, rel
      if (abs(expected) >= tiny_normal) then
         close = abs(actual - expected) <= rel*abs(expected)
      else
         close = abs(actual - expected) <= 2.0_dp*tiny(1.0_dp)*epsilon(1.0_dp)
      end if
      if (ieee_is_nan(actual)) close = .false.
   end function close

   !> Bitwise-different reals (written without == so -Wcompare-reals stays quiet).
   logical function differ(a, b)
      real(dp), intent(in) :: a, b
      differ = abs(a - b) > 0.0_dp
   end function differ

   character(len=80) function describe(n, h, actual, expected)
      real(dp), intent(in) :: n, h, actual, expected
      write (describe, '("n=",f5.2," h=",es12.5," got ",es23.16," want ",es23.16)') &
         & n, h, actual, expected
   end function describe

   !> doc/theory.md §2 values (15 digits given, so 1e-14 relative).
   subroutine test_design_values(error)
      type(error_type), allocatable, intent(out) :: error
      call check(error, gauss_f32(0.0_dp), 0.430019993662260_dp, rel=.true., thr=1e-14_dp)
      if (allocated(error)) return
      call check(error, gauss_f32(2.0_dp), 6.64817762358709e-3_dp, rel=.true., thr=1e-14_dp)
      if (allocated(error)) return
      call check(error, gauss_f32(6.0_dp), 8.20358058981517e-11_dp, rel=.true., thr=1e-14_dp)
      if (allocated(error)) return
      call check(error, gauss_f32(-5.0_dp), 11.3493877980066_dp, rel=.true., thr=1e-14_dp)
   end subroutine test_design_values

   !> n in {-1/2, 0, 1/2, 1, 3/2, 5/2}, h from -1000 to 45: the issue's 1e-14 target.
   subroutine test_fitted_orders(error)
      type(error_type), allocatable, intent(out) :: error
      call compare_orders(error, .true., 1.0e-14_dp)
   end subroutine test_fitted_orders

   !> n = 100 .. 150 at h = 37.2 .. 38.6, where phi(h) is subnormal (or nearly) but F_n(h)
   !> is a normal double (Gamma(n+1)/h^(n+1) > 1): the 1e-12 of other orders (egw.h).
   !> 50-digit values of tools/reference/gauss_high_order_refs.py. Before audit25 the
   !> quadrature's result was rounded through phi(h): 1.2e-11 off at (150, 38.0), 1.8e-3
   !> at (150, 38.5) and 0 for 1.55e-304 at (150, 38.6).
   subroutine test_high_orders_far(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: ref(3, 9) = reshape([ &
         & 150.0_dp, 37.5_dp, 1.2560252896818976e-284_dp, &
         & 150.0_dp, 37.9_dp, 8.2375254641585366e-292_dp, &
         & 150.0_dp, 38.0_dp, 1.2882948005357761e-293_dp, &
         & 150.0_dp, 38.3_dp, 4.6632999536882344e-299_dp, &
         & 150.0_dp, 38.5_dp, 1.04990572804025e-302_dp, &
         & 150.0_dp, 38.6_dp, 1.5537319444957278e-304_dp, &
         & 120.0_dp, 37.5_dp, 3.1606807981076504e-300_dp, &
         & 137.25_dp, 38.1_dp, 2.6295821920828703e-302_dp, &
         & 100.0_dp, 37.2_dp, 8.6967855149485654e-304_dp], [3, 9])
      real(dp) :: f
      character(len=100) :: msg
      integer :: i
      do i = 1, size(ref, 2)
         f = gauss_integral(ref(1, i), ref(2, i))
         if (.not. close(f, ref(3, i), 1.0e-12_dp)) then
            write (msg, '("n=",f7.2," h=",f6.2," got ",es23.16," want ",es23.16)') &
               & ref(1, i), ref(2, i), f, ref(3, i)
            call test_failed(error, "F_n beyond phi's underflow: "//trim(msg))
            return
         end if
      end do
   end subroutine test_high_orders_far

   !> n in {0.3, 2, 3.7, 7, -0.7}: the issue's 1e-12 target.
   subroutine test_general_orders(error)
      type(error_type), allocatable, intent(out) :: error
      call compare_orders(error, .false., 1.0e-12_dp)
   end subroutine test_general_orders

   subroutine compare_orders(error, fitted, rel)
      type(error_type), allocatable, intent(out) :: error
      logical, intent(in) :: fitted
      real(dp), intent(in) :: rel
      real(dp) :: n, h, f
      integer :: i, ncheck
      ncheck = 0
      do i = 1, size(ref_fn, 2)
         n = ref_fn(1, i)
         h = ref_fn(2, i)
         if (is_fitted(n) .neqv. fitted) cycle
         f = gauss_integral(n, h)
         ncheck = ncheck + 1
         if (.not. close(f, ref_fn(3, i), rel)) then
            call test_failed(error, "F_n(h) off: "//trim(describe(n, h, f, ref_fn(3, i))))
            return
         end if
      end do
      call check(error, ncheck > 100, "too few reference values")
   end subroutine compare_orders

   logical function is_fitted(n)
      real(dp), intent(in) :: n
      is_fitted = any(abs(n - [-0.5_dp, 0.0_dp, 0.5_dp, 1.0_dp, 1.5_dp, 2.5_dp]) <= 0.0_dp)
   end function is_fitted

   !> Against -n F_{n-1} from the parabolic-cylinder form (independent of the quadrature
   !> values above). The fitted derivative kernels share the 1e-14 target, others 1e-12.
   subroutine test_derivative(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: n, h, df, rel
      integer :: i
      do i = 1, size(ref_fn, 2)
         n = ref_fn(1, i)
         h = ref_fn(2, i)
         if (n < 0.0_dp) cycle
         rel = merge(1.0e-14_dp, 1.0e-12_dp, is_fitted(n))
         df = gauss_integral_deriv(n, h)
         if (.not. close(df, ref_fn(4, i), rel)) then
            call test_failed(error, "dF_n/dh off: "//trim(describe(n, h, df, ref_fn(4, i))))
            return
         end if
      end do
   end subroutine test_derivative

   !> The named hot kernels are the same functions (bit for bit) as the generic entry.
   subroutine test_named_kernels(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: h
      integer :: i
      do i = -40, 80
         h = 0.493_dp*i
         if (differ(gauss_fm12(h), gauss_integral(-0.5_dp, h)) .or. &
            & differ(gauss_f0(h), gauss_integral(0.0_dp, h)) .or. &
            & differ(gauss_f12(h), gauss_integral(0.5_dp, h)) .or. &
            & differ(gauss_f1(h), gauss_integral(1.0_dp, h)) .or. &
            & differ(gauss_f32(h), gauss_integral(1.5_dp, h)) .or. &
            & differ(gauss_f52(h), gauss_integral(2.5_dp, h))) then
            call test_failed(error, "a named kernel differs from gauss_integral")
            return
         end if
      end do
      ! phi(0) = 1/sqrt(2 pi) to an ulp
      call check(error, normal_density(0.0_dp), 0.398942280401432677939946059934_dp, &
         & rel=.true., thr=2e-16_dp)
      if (allocated(error)) return
      ! phi(37.3) (mpmath) to 1e-15: exp(-h*h/2) in double is 2.6e-14 off here, since exp
      ! amplifies the rounding of h*h/2 ~ 696 (ulp 1.1e-13); h^2/2 must be formed exactly
      call check(error, normal_density(37.3_dp), 3.06284629069566746729894e-303_dp, &
         & rel=.true., &
         & thr=1e-15_dp)
   end subroutine test_named_kernels

   !> F_{n+1} = n F_{n-1} - h F_n (doc/theory.md §2); for h <= 0 every term is positive, so
   !> the identity holds to a few ulp of the fitted values (3e-15 allowed).
   subroutine test_recurrence(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: h, lhs, rhs
      integer :: i
      do i = 0, 60
         h = -0.37_dp*i
         lhs = gauss_f52(h)
         rhs = 1.5_dp*gauss_f12(h) - h*gauss_f32(h)
         if (abs(lhs - rhs) > 3.0e-15_dp*lhs) then
            call test_failed(error, "recurrence fails", describe(2.5_dp, h, lhs, rhs))
            return
         end if
      end do
   end subroutine test_recurrence

   !> F_n(+Inf) = 0, F_0(-Inf) = 1, F_n(-Inf) = +Inf (n > 0), and a dense sweep from
   !> -1000 to 1000 never gives NaN, Inf (for finite h > -1000) or a negative value.
   subroutine test_limits(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: pinf, minf, h, f, orders(8)
      integer :: i, j
      pinf = ieee_value(pinf, ieee_positive_inf)
      minf = ieee_value(minf, ieee_negative_inf)
      orders = [-0.5_dp, 0.0_dp, 0.5_dp, 1.0_dp, 1.5_dp, 2.5_dp, 0.3_dp, 3.7_dp]
      do j = 1, size(orders)
         call check(error, gauss_integral(orders(j), pinf), 0.0_dp, "F_n(+Inf) must be 0")
         if (allocated(error)) return
      end do
      call check(error, gauss_integral(0.0_dp, minf), 1.0_dp, "F_0(-Inf) must be 1")
      if (allocated(error)) return
      call check(error, gauss_integral(1.5_dp, minf) > huge(1.0_dp), "F_3/2(-Inf) = +Inf")
      if (allocated(error)) return
      call check(error, gauss_integral(0.3_dp, minf) > huge(1.0_dp), "F_0.3(-Inf) = +Inf")
      if (allocated(error)) return
      do j = 1, size(orders)
         do i = -2000, 2000, 3
            h = 0.5_dp*i + 0.0137_dp
            f = gauss_integral(orders(j), h)
            if (.not. ieee_is_finite(f) .or. f < 0.0_dp) then
               call test_failed(error, "F_n not finite or negative", &
                  & describe(orders(j), h, f, 0.0_dp))
               return
            end if
         end do
      end do
   end subroutine test_limits

   !> The checked call names the offending argument and its value.
   subroutine test_checked(error)
      type(error_type), allocatable, intent(out) :: error
      type(egw_error), allocatable :: err
      real(dp) :: v, nan
      nan = ieee_value(nan, ieee_quiet_nan)
      call get_gauss_integral(-1.0_dp, 0.0_dp, v, err)
      call check(error, allocated(err), "n = -1 accepted")
      if (allocated(error)) return
      call check(error, err%stat, egw_invalid_argument, "status for n = -1")
      if (allocated(error)) return
      call check(error, index(err%message, "n = -1.0") == 1, "message: "//err%message)
      if (allocated(error)) return
      call get_gauss_integral(nan, 0.0_dp, v, err)
      call check(error, allocated(err), "n = NaN accepted")
      if (allocated(error)) return
      call check(error, index(err%message, "n = NaN") == 1, "message: "//err%message)
      if (allocated(error)) return
      call get_gauss_integral(1.5_dp, nan, v, err)
      call check(error, allocated(err), "h = NaN accepted")
      if (allocated(error)) return
      call check(error, err%stat, egw_invalid_argument, "status for h = NaN")
      if (allocated(error)) return
      call check(error, index(err%message, "h = NaN") == 1, "message: "//err%message)
      if (allocated(error)) return
      call get_gauss_integral(1.5_dp, 2.0_dp, v, err)
      call check(error, .not. allocated(err), "valid call rejected")
      if (allocated(error)) return
      call check(error, v, 6.64817762358709e-3_dp, rel=.true., thr=1e-14_dp)
   end subroutine test_checked

   !> I_e, I_ep, I_p and their h-derivatives for psi in [0.1, 100], rho_p from 1.01 to 1000,
   !> K from 0.1 to 0.95, h across every regime: the issue's 1e-12 relative (absolute
   !> 1e-300 where the value underflows).
   subroutine test_zmc(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), parameter :: names(6) = [character(len=8) :: "I_e", "I_ep", "I_p", &
         & "dI_e", "dI_ep", "dI_p"]
      real(dp) :: v(6), ref
      character(len=160) :: msg
      integer :: i, j
      do i = 1, size(ref_zmc, 2)
         call zmc_integrals(ref_zmc(1, i), ref_zmc(2, i), ref_zmc(3, i), ref_zmc(4, i), &
            & v(1), v(2), v(3), v(4), v(5), v(6))
         do j = 1, 6
            ref = ref_zmc(6 + j, i)
            if (.not. (abs(v(j) - ref) <= max(1.0e-12_dp*abs(ref), 1.0e-300_dp))) then
               write (msg, '(a," off at h=",es12.5," e=",es10.3," q=",es10.3," K=",f5.2, &
                  & ": got ",es23.16," want ",es23.16)') trim(names(j)), ref_zmc(1:4, i), &
                  & v(j), ref
               call test_failed(error, trim(msg))
               return
            end if
         end do
      end do
   end subroutine test_zmc

end module test_gauss
