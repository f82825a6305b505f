!> Tests of egw_ellip: K and E of modulus k and of the complementary modulus against
!> mpmath (test/ref_ellip.f90), the log split of K, Legendre's relation, and the status
!> returned for moduli outside [0, 1).
module test_ellip
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_nan
   use testdrive, only: new_unittest, unittest_type, error_type, check, test_failed
   use egw_kinds, only: pi
   use egw_all, only: dp, egw_error, egw_invalid_argument, ellipk, ellipe, ellipk_comp, &
      & ellipe_comp, get_ellipk, get_ellipe, ellipk_log_split, ellipk_comp_fast, &
      & ellipk_split_a, ellipk_split_b
   use ref_ellip, only: k_arg, k_ellipk, k_ellipe, kc_arg, kc_ellipk, kc_ellipe, kc_kreg, &
      & kc_klog
   implicit none
   private
   public :: collect_ellip

   !> Accuracy promised by egw_ellip: a few ulp. The reference is the correctly rounded
   !> double of a 40-digit value, so 4 ulp here means at most 4.5 ulp from the truth.
   real(dp), parameter :: max_ulp = 4.0_dp

contains

   subroutine collect_ellip(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("K(k) against mpmath", test_k_modulus), &
         & new_unittest("E(k) against mpmath", test_e_modulus), &
         & new_unittest("K(kc) against mpmath", test_k_comp), &
         & new_unittest("E(kc) against mpmath", test_e_comp), &
         & new_unittest("fast K(kc) against mpmath and the AGM", test_k_fast), &
         & new_unittest("log split of K against mpmath", test_log_split), &
         & new_unittest("log split's series near k = 1 against mpmath", test_split_series), &
         & new_unittest("Legendre relation", test_legendre), &
         & new_unittest("special values and limits", test_special), &
         & new_unittest("invalid modulus gives a status", test_invalid) &
         & ]
   end subroutine collect_ellip

   !> Error of x in units of the spacing of doubles at the reference value.
   elemental real(dp) function ulps(x, ref)
      real(dp), intent(in) :: x, ref
      ulps = abs(x - ref)/spacing(ref)
   end function ulps

   !> Fails with the worst argument when any error exceeds max_ulp.
   subroutine check_ulps(error, what, args, values, refs)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in) :: what
      real(dp), intent(in) :: args(:), values(:), refs(:)
      real(dp) :: err(size(args))
      character(len=120) :: msg
      integer :: worst
      err = ulps(values, refs)
      worst = maxloc(err, 1)
      if (any(ieee_is_nan(values)) .or. err(worst) > max_ulp) then
         write (msg, '(a,es24.16,a,f0.2,a)') what//": argument ", args(worst), " is off by ", &
            & err(worst), " ulp"
         call test_failed(error, trim(msg))
      end if
   end subroutine check_ulps

   subroutine test_k_modulus(error)
      type(error_type), allocatable, intent(out) :: error
      call check_ulps(error, "ellipk", k_arg, ellipk(k_arg), k_ellipk)
   end subroutine test_k_modulus

   subroutine test_e_modulus(error)
      type(error_type), allocatable, intent(out) :: error
      call check_ulps(error, "ellipe", k_arg, ellipe(k_arg), k_ellipe)
   end subroutine test_e_modulus

   subroutine test_k_comp(error)
      type(error_type), allocatable, intent(out) :: error
      call check_ulps(error, "ellipk_comp", kc_arg, ellipk_comp(kc_arg), kc_ellipk)
   end subroutine test_k_comp

   !> The polynomial K of the kernel: a few ulp against mpmath on the reference grid
   !> (kc from 1 down to the smallest normal), and on 2000 points of kc in (0, 1] (uniform
   !> and logarithmic) within 8 ulp of the AGM's ellipk_comp (each is within ~4 ulp of the
   !> truth, the AGM by the test above); +Inf at kc = 0 and NaN outside [0, 1].
   subroutine test_k_fast(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: kc
      integer :: i
      call check_ulps(error, "ellipk_comp_fast", kc_arg, ellipk_comp_fast(kc_arg), kc_ellipk)
      if (allocated(error)) return
      do i = 1, 2000
         if (i <= 1000) then
            kc = real(i, dp)/1000.0_dp
         else
            kc = 10.0_dp**(-0.3_dp*real(i - 1000, dp))
         end if
         call check(error, ulps(ellipk_comp_fast(kc), ellipk_comp(kc)) <= 8.0_dp, &
            & "fast K and AGM K differ by more than 8 ulp")
         if (allocated(error)) return
      end do
      call check(error, ellipk_comp_fast(0.0_dp) > huge(1.0_dp), "fast K(kc = 0) = +Inf")
      if (allocated(error)) return
      call check(error, ieee_is_nan(ellipk_comp_fast(1.5_dp)), "fast K(kc = 1.5) is NaN")
   end subroutine test_k_fast

   subroutine test_e_comp(error)
      type(error_type), allocatable, intent(out) :: error
      call check_ulps(error, "ellipe_comp", kc_arg, ellipe_comp(kc_arg), kc_ellipe)
   end subroutine test_e_comp

   !> Both pieces to a few ulp (klog = 0 at kc = 1 is compared exactly), and the pieces
   !> reassemble K: kreg + klog ln(1/kc) agrees with K(kc) to rounding of the sum.
   subroutine test_log_split(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: kreg(size(kc_arg)), klog(size(kc_arg))
      integer :: i
      call ellipk_log_split(kc_arg, kreg, klog)
      call check_ulps(error, "kreg", kc_arg, kreg, kc_kreg)
      if (allocated(error)) return
      do i = 1, size(kc_arg)
         if (kc_klog(i) == 0.0_dp) then
            call check(error, klog(i), 0.0_dp, "klog at kc = 1 must be 0")
         else
            call check(error, ulps(klog(i), kc_klog(i)) <= max_ulp, "klog off by more than " &
               & //"4 ulp")
         end if
         if (allocated(error)) return
         ! Each of kreg, klog, ln is good to ~4 ulp; their combination to ~1e-15.
         call check(error, kreg(i) + klog(i)*log(1.0_dp/kc_arg(i)), kc_ellipk(i), &
            & "kreg + klog ln(1/kc) must equal K", thr=1.0e-15_dp, rel=.true.)
         if (allocated(error)) return
      end do
   end subroutine test_log_split

   !> The truncated series of the split (ellipk_split_a, _b, which the half-space's product
   !> integration evaluates for kc <= 1/3), summed here by Horner, against the same
   !> mpmath references at every kc_arg in (0, 1/3]: both pieces to a few ulp.
   subroutine test_split_series(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: x, kreg, klog
      integer :: i, n, tested
      tested = 0
      do i = 1, size(kc_arg)
         if (.not. (kc_arg(i) > 0.0_dp .and. kc_arg(i) <= 1.0_dp/3.0_dp)) cycle
         x = kc_arg(i)**2
         kreg = 0.0_dp
         klog = 0.0_dp
         do n = ubound(ellipk_split_a, 1), 0, -1
            kreg = kreg*x + ellipk_split_a(n)
            klog = klog*x + ellipk_split_b(n)
         end do
         call check(error, ulps(kreg, kc_kreg(i)) <= max_ulp .and. &
            & ulps(klog, kc_klog(i)) <= max_ulp, "split series off by more than 4 ulp")
         if (allocated(error)) return
         tested = tested + 1
      end do
      ! the references must reach into the range, else this tests nothing
      call check(error, tested >= 5, "fewer than 5 references with kc <= 1/3")
   end subroutine test_split_series

   !> E K' + E' K - K K' = pi/2 (DLMF 19.7.1) on 1999 moduli across both branches of E.
   !> The three products are O(1) to O(40) and nearly cancel near k = 0 and 1, so the
   !> tolerance scales with the largest product: 8 eps times it.
   subroutine test_legendre(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: n = 2000
      real(dp) :: k, kc, kk, ee, kkc, eec, big
      integer :: i
      do i = 1, n - 1
         ! k in (0, 1), crowded at both ends (K' = K(kc) is infinite at k = 0)
         k = 0.5_dp*(1.0_dp - cos(pi*real(i, dp)/real(n, dp)))
         kc = sqrt((1.0_dp - k)*(1.0_dp + k))
         kk = ellipk(k)
         ee = ellipe(k)
         kkc = ellipk(kc)
         eec = ellipe(kc)
         big = max(ee*kkc, eec*kk, kk*kkc)
         call check(error, ee*kkc + eec*kk - kk*kkc, 0.5_dp*pi, "Legendre relation", &
            & thr=8.0_dp*epsilon(1.0_dp)*big)
         if (allocated(error)) return
      end do
   end subroutine test_legendre

   subroutine test_special(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: kreg, klog
      ! K(0) = E(0) = pi/2 exactly to rounding.
      call check(error, ellipk(0.0_dp), 0.5_dp*pi, "K(0)", thr=epsilon(1.0_dp), rel=.true.)
      if (allocated(error)) return
      call check(error, ellipe(0.0_dp), 0.5_dp*pi, "E(0)", thr=epsilon(1.0_dp), rel=.true.)
      if (allocated(error)) return
      ! kc -> 0: K = ln(4/kc) + O(kc**2 ln kc), E = 1 + O(kc**2 ln kc); exact in double
      ! below kc = 1e-20 (the correction is below 1e-38).
      call check(error, ellipk_comp(1.0e-250_dp), log(4.0_dp) + 250.0_dp*log(10.0_dp), &
         & "K near kc = 0", thr=4.0_dp*epsilon(1.0_dp), rel=.true.)
      if (allocated(error)) return
      call check(error, ellipe_comp(1.0e-250_dp), 1.0_dp, "E near kc = 0")
      if (allocated(error)) return
      ! The limits the elemental functions give at the edge of the domain.
      call check(error, ellipk_comp(0.0_dp) > huge(1.0_dp), "K(kc = 0) must be +Inf")
      if (allocated(error)) return
      call check(error, ellipe_comp(0.0_dp), 1.0_dp, "E(kc = 0) must be 1")
      if (allocated(error)) return
      call check(error, ieee_is_nan(ellipk(1.5_dp)), "K(1.5) must be NaN")
      if (allocated(error)) return
      ! Symmetry in k: K and E are even functions.
      call check(error, ellipk(-0.3_dp), ellipk(0.3_dp), "K(-k) = K(k)")
      if (allocated(error)) return
      ! The split at kc = 1 is (pi/2, 0) by convention.
      call ellipk_log_split(1.0_dp, kreg, klog)
      call check(error, kreg == 0.5_dp*pi .and. klog == 0.0_dp, "split at kc = 1")
   end subroutine test_special

   subroutine test_invalid(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: bad(5), value
      type(egw_error), allocatable :: err
      integer :: i
      bad = [-0.1_dp, -tiny(1.0_dp), 1.0_dp, 1.5_dp, ieee_value(1.0_dp, ieee_quiet_nan)]
      do i = 1, size(bad)
         call get_ellipk(bad(i), value, err)
         call expect_error("get_ellipk")
         if (allocated(error)) return
         call get_ellipe(bad(i), value, err)
         call expect_error("get_ellipe")
         if (allocated(error)) return
      end do
      call get_ellipk(0.5_dp, value, err)
      call check(error, .not. allocated(err), "get_ellipk(0.5) must succeed")
      if (allocated(error)) return
      call check(error, value, ellipk(0.5_dp), "get_ellipk(0.5) value")
      if (allocated(error)) return
      call get_ellipe(0.5_dp, value, err)
      call check(error, .not. allocated(err), "get_ellipe(0.5) must succeed")
      if (allocated(error)) return
      call check(error, value, ellipe(0.5_dp), "get_ellipe(0.5) value")
   contains
      subroutine expect_error(what)
         character(len=*), intent(in) :: what
         if (.not. allocated(err)) then
            call test_failed(error, what//" accepted an invalid modulus")
            return
         end if
         call check(error, err%stat, egw_invalid_argument, what//": status")
         if (allocated(error)) return
         call check(error, index(err%message, "k = ") == 1, what//": message must name k", &
            & more=err%message)
         if (allocated(error)) return
         call check(error, ieee_is_nan(value), what//": value must be NaN on error")
      end subroutine expect_error
   end subroutine test_invalid

end module test_ellip
