!> Complete elliptic integrals K and E of MODULUS k (not the parameter m = k**2), as
!> functions of k or of the complementary modulus kc = sqrt(1 - k**2), and the split of
!> K into a smooth part and the coefficient of its logarithmic singularity at k -> 1,
!> which product integration of the half-space kernel needs (DESIGN.md §4).
!>
!> Method: the arithmetic-geometric mean (AGM). With a0 = 1, b0 = kc, c0 = k,
!> K(k) = pi / (2 AGM(1, kc)) and E(k) = K(k) (1 - sum_n 2**(n-1) c_n**2). Every step
!> adds, multiplies or takes square roots of positive numbers, so K is good to a few ulp
!> for every kc in (0, 1], kc = 1e-300 included. The Legendre sum for E cancels as
!> k -> 1 (E/K -> 0), so for k > 1/sqrt(2) E comes from Legendre's relation instead:
!> E(k) = AGM(1, k) + K(k) S', where S' = sum_n 2**(n-1) c'_n**2 is the sum of the AGM
!> started at (1, k) with c'_0 = kc; both terms are positive and nothing cancels.
module egw_ellip
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, &
      & ieee_is_nan
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, egw_invalid_argument, fatal_error, format_real
   implicit none
   private

   public :: ellipk, ellipe, ellipk_comp, ellipe_comp
   public :: get_ellipk, get_ellipe, ellipk_log_split

   !> 1/sqrt(2): below it (in k) the Legendre sum for E has no cancellation worth naming
   !> (E/K >= 0.73), above it the complementary AGM converges in a few steps.
   real(dp), parameter :: inv_sqrt2 = 0.707106781186547524400844362104849039_dp
   real(dp), parameter :: ln2 = 0.693147180559945309417232121458176568_dp
   !> Below this kc the log split is summed as its power series in kc**2 (ratio <= 1/4);
   !> above it K - klog ln(1/kc) loses at most a factor 1.5 to cancellation.
   real(dp), parameter :: split_series_max = 0.5_dp
   !> Below this kc, K = ln(4/kc) to within kc**2 ln(4/kc)/4 < 2**-62 relative: one log
   !> is more accurate than fifteen AGM steps.
   real(dp), parameter :: kc_log_only = 2.0_dp**(-31)

contains

   !> K(k), complete elliptic integral of the first kind of modulus k, 0 <= k < 1.
   !> Returns +Inf at |k| = 1 and NaN for |k| > 1 or NaN (use get_ellipk for a status).
   !> Near k = 1 prefer ellipk_comp(kc), since forming kc from k costs digits of kc.
   elemental real(dp) function ellipk(k)
      real(dp), intent(in) :: k
      if (.not. abs(k) < 1.0_dp) then
         ellipk = out_of_domain_k(k)
         return
      end if
      ! 1 - k and 1 + k are exact or nearly so; 1 - k*k would lose digits near k = 1.
      ellipk = ellipk_comp(sqrt((1.0_dp - k)*(1.0_dp + k)))
   end function ellipk

   !> E(k), complete elliptic integral of the second kind of modulus k, 0 <= k < 1.
   !> Returns 1 at |k| = 1 and NaN for |k| > 1 or NaN (use get_ellipe for a status).
   elemental real(dp) function ellipe(k)
      real(dp), intent(in) :: k
      if (.not. abs(k) < 1.0_dp) then
         if (abs(k) == 1.0_dp) then
            ellipe = 1.0_dp
         else
            ellipe = ieee_value(1.0_dp, ieee_quiet_nan)
         end if
         return
      end if
      ellipe = ellipe_both(abs(k), sqrt((1.0_dp - k)*(1.0_dp + k)))
   end function ellipe

   !> K as a function of the complementary modulus kc = sqrt(1 - k**2), 0 < kc <= 1.
   !> Accurate to a few ulp down to the smallest normal kc; +Inf at kc = 0, NaN outside
   !> [0, 1]. The half-space kernel has kc = |r - t|/(r + t) exactly.
   elemental real(dp) function ellipk_comp(kc)
      real(dp), intent(in) :: kc
      if (.not. (kc > 0.0_dp .and. kc <= 1.0_dp)) then
         if (kc == 0.0_dp) then
            ellipk_comp = ieee_value(1.0_dp, ieee_positive_inf)
         else
            ellipk_comp = ieee_value(1.0_dp, ieee_quiet_nan)
         end if
         return
      end if
      if (kc < kc_log_only) then
         ellipk_comp = log(4.0_dp) - log(kc)
      else
         ellipk_comp = 0.5_dp*pi/agm(1.0_dp, kc)
      end if
   end function ellipk_comp

   !> E as a function of the complementary modulus kc = sqrt(1 - k**2), 0 <= kc <= 1
   !> (E = 1 at kc = 0); NaN outside [0, 1].
   elemental real(dp) function ellipe_comp(kc)
      real(dp), intent(in) :: kc
      if (.not. (kc >= 0.0_dp .and. kc <= 1.0_dp)) then
         ellipe_comp = ieee_value(1.0_dp, ieee_quiet_nan)
         return
      end if
      ellipe_comp = ellipe_both(sqrt((1.0_dp - kc)*(1.0_dp + kc)), kc)
   end function ellipe_comp

   !> K(k) with argument checking: k < 0, k >= 1 or NaN give egw_invalid_argument and a
   !> NaN value; otherwise value = ellipk(k) and error stays unallocated.
   pure subroutine get_ellipk(k, value, error)
      real(dp), intent(in) :: k
      real(dp), intent(out) :: value
      type(egw_error), allocatable, intent(out) :: error
      call check_modulus(k, value, error)
      if (allocated(error)) return
      value = ellipk(k)
   end subroutine get_ellipk

   !> E(k) with argument checking: k < 0, k >= 1 or NaN give egw_invalid_argument and a
   !> NaN value; otherwise value = ellipe(k) and error stays unallocated.
   pure subroutine get_ellipe(k, value, error)
      real(dp), intent(in) :: k
      real(dp), intent(out) :: value
      type(egw_error), allocatable, intent(out) :: error
      call check_modulus(k, value, error)
      if (allocated(error)) return
      value = ellipe(k)
   end subroutine get_ellipe

   !> Split of K near k = 1 for product integration of the log-singular kernel:
   !>
   !>   K(k) = kreg + klog * ln(1/kc),   kc = sqrt(1 - k**2) in (0, 1),
   !>
   !> with kreg = sum_n a_n kc**(2n) and klog = sum_n b_n kc**(2n), b_n = ((1/2)_n/n!)**2,
   !> a_n = 2 b_n (ln 2 - sum_{j<=n} 1/((2j-1) 2j)); a_0 = ln 4, b_0 = 1 (DLMF 19.12.1).
   !> Both pieces are analytic in kc**2 on kc < 1, positive, and klog = (2/pi) K(kc)
   !> = 1/AGM(1, k). So near t = r the kernel is (smooth) + (smooth) * ln|r - t| plus the
   !> smooth ln(r + t). As kc -> 1 (k -> 0) klog grows like ln(4/k)/pi while the product
   !> klog ln(1/kc) -> 0; at kc = 1 exactly the split degenerates and this routine returns
   !> kreg = pi/2, klog = 0 so that the identity still holds. NaN outside (0, 1].
   !> Accuracy: a few ulp for both pieces (tested against mpmath).
   elemental subroutine ellipk_log_split(kc, kreg, klog)
      real(dp), intent(in) :: kc
      real(dp), intent(out) :: kreg, klog
      real(dp) :: x, term_b, rest_ln2, power, a_sum, b_sum, k
      integer :: n

      if (.not. (kc > 0.0_dp .and. kc <= 1.0_dp)) then
         kreg = ieee_value(1.0_dp, ieee_quiet_nan)
         klog = kreg
         return
      end if
      if (kc == 1.0_dp) then
         kreg = 0.5_dp*pi
         klog = 0.0_dp
         return
      end if
      if (kc >= split_series_max) then
         k = sqrt((1.0_dp - kc)*(1.0_dp + kc))
         ! ln(1/kc) <= ln 2 here, so K and klog ln(1/kc) differ by a factor >= 3.
         klog = 1.0_dp/agm(1.0_dp, k)
         kreg = 0.5_dp*pi/agm(1.0_dp, kc) - klog*log(1.0_dp/kc)
         return
      end if
      ! Power series in x = kc**2 < 1/4: terms fall at least 4-fold per step.
      x = kc*kc
      term_b = 1.0_dp
      rest_ln2 = ln2          ! ln 2 - sum_{j<=n} 1/((2j-1) 2j) > 0, ~ 1/(4n)
      power = 1.0_dp
      a_sum = 2.0_dp*ln2
      b_sum = 1.0_dp
      do n = 1, 60
         term_b = term_b*(real(2*n - 1, dp)/real(2*n, dp))**2
         rest_ln2 = rest_ln2 - 1.0_dp/(real(2*n - 1, dp)*real(2*n, dp))
         power = power*x
         b_sum = b_sum + term_b*power
         a_sum = a_sum + 2.0_dp*term_b*rest_ln2*power
         if (term_b*power < 0.25_dp*epsilon(1.0_dp)) exit
      end do
      kreg = a_sum
      klog = b_sum
   end subroutine ellipk_log_split

   !> E from both moduli (k, kc >= 0, k**2 + kc**2 = 1), choosing the AGM that does not
   !> cancel (see the module header).
   elemental real(dp) function ellipe_both(k, kc) result(e)
      real(dp), intent(in) :: k, kc
      real(dp) :: mean, csum, mean_c, csum_c
      if (k <= inv_sqrt2) then
         ! E/K = 1 - S with S <= 0.27: at most a factor 1.4 lost to cancellation.
         call agm_sum(1.0_dp, kc, k, mean, csum)
         e = (0.5_dp*pi/mean)*(1.0_dp - csum)
      else
         ! Legendre: E K' + E' K - K K' = pi/2 with K' = pi/(2 mean_c), E' = K'(1 - S').
         call agm_sum(1.0_dp, k, kc, mean_c, csum_c)
         e = mean_c + (0.5_dp*pi/agm(1.0_dp, kc))*csum_c
      end if
   end function ellipe_both

   !> AGM(a, b) of two positive numbers.
   elemental real(dp) function agm(a0, b0) result(mean)
      real(dp), intent(in) :: a0, b0
      real(dp) :: csum
      call agm_sum(a0, b0, sqrt(abs((a0 - b0)*(a0 + b0))), mean, csum)
   end function agm

   !> AGM of a0 >= b0 > 0 and the sum S = sum_{n>=0} 2**(n-1) c_n**2, given
   !> c0 = sqrt(a0**2 - b0**2) by the caller (who knows it without cancellation).
   !> c_{n+1} = c_n**2 / (4 a_{n+1}) replaces (a_n - b_n)/2, which would cancel.
   !> Convergence is quadratic once c_n < a_n; from b0/a0 = 1e-300 it takes ~15 steps.
   pure subroutine agm_sum(a0, b0, c0, mean, csum)
      real(dp), intent(in) :: a0, b0, c0
      real(dp), intent(out) :: mean, csum
      ! Once c_n <= 2**-27 a_n, c_{n+1} <= 2**-56 a_n: (a_n + b_n)/2 is the mean to
      ! rounding and the remaining terms of S are below 2**-110 relative.
      real(dp), parameter :: tol = 2.0_dp**(-27)
      real(dp) :: a, b, c, a_next, weight
      integer :: n
      a = a0
      b = b0
      c = c0
      weight = 0.5_dp
      csum = weight*c*c
      do n = 1, 64
         if (c <= tol*a) exit
         a_next = 0.5_dp*(a + b)
         b = sqrt(a*b)
         c = (c/a_next)*(0.25_dp*c)
         a = a_next
         weight = 2.0_dp*weight
         csum = csum + weight*c*c
      end do
      mean = 0.5_dp*(a + b)
   end subroutine agm_sum

   elemental real(dp) function out_of_domain_k(k) result(value)
      real(dp), intent(in) :: k
      if (abs(k) == 1.0_dp) then
         value = ieee_value(1.0_dp, ieee_positive_inf)
      else
         value = ieee_value(1.0_dp, ieee_quiet_nan)
      end if
   end function out_of_domain_k

   pure subroutine check_modulus(k, value, error)
      real(dp), intent(in) :: k
      real(dp), intent(out) :: value
      type(egw_error), allocatable, intent(out) :: error
      value = ieee_value(1.0_dp, ieee_quiet_nan)
      if (ieee_is_nan(k) .or. k < 0.0_dp .or. k >= 1.0_dp) then
         call fatal_error(error, egw_invalid_argument, "k = "//format_real(k) &
            & //": the elliptic modulus must lie in [0, 1)")
      end if
   end subroutine check_modulus

end module egw_ellip
