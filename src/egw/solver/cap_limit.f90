!> The smooth cap's unloading as the small-sigma route's sigma -> 0 limit (egw_rough_sphere's
!> asymptotic_unloading; doc/theory.md section 12 "Small sigma: the cap's limit"): cap_load's
!> histories at three ring counts and Richardson's extrapolation over them, with an error
!> estimate that includes the plastic field's. A single cap history cannot give that:
!> its force_error compares two unloading meshes on the same plastic field, while near the
!> residual overlap the field's own error dominates (E-GW's limit, 2 delta_y, 0.145 ..
!> 0.2 delta_max: 200 rings 1.1e-6 off the independent reference under an estimate of
!> 9.8e-8; doc/stability.md "Stop 53 (small19)").
module egw_cap_limit
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_cap_sphere, only: cap_options, cap_result, cap_history, cap_load, cap_unload
   implicit none
   private

   public :: cap_limit, limit_load, limit_unload

   !> cap_options%n_rings of the three histories (n_levels 2: finest 200, 400, 800 rings).
   !> Their unloading forces near the residual overlap converge with order 1.61 .. 1.64
   !> (E-GW's limit above); from 50 rings on (finest 100) the order was 0.67 .. 0.85,
   !> not yet the asymptotic one. Loading the three: ~1 s at 2 delta_y (the 800-ring
   !> finest level 0.84 s).
   integer, parameter :: limit_rings(3) = [100, 200, 400]
   !> Richardson's extrapolation only where d2/d1, the ratio of successive differences, is
   !> in (0, shrink_max): they shrink with one sign (tools/reference/cap_reference.py's
   !> richardson, the same bound).
   real(dp), parameter :: shrink_max = 0.9_dp

   !> The smooth cap's loading to delta_max at limit_rings.
   type :: cap_limit
      type(cap_history) :: levels(3)
   end type cap_limit

contains

   !> cap_load's histories at delta_max on limit_rings (their force the finest's).
   subroutine limit_load(radius, modulus, flow_pressure, delta_max, limit, result, error)
      real(dp), intent(in) :: radius          !< equivalent radius R > 0
      real(dp), intent(in) :: modulus         !< effective modulus E* > 0
      real(dp), intent(in) :: flow_pressure   !< p_y, 0 < p_y < E*
      real(dp), intent(in) :: delta_max       !< overlap >= 0
      type(cap_limit), intent(out) :: limit   !< the three histories
      type(cap_result), intent(out) :: result   !< the finest history's loading
      !> cap_load's failure (input named as delta_max)
      type(egw_error), allocatable, intent(out) :: error
      integer :: l
      do l = 1, size(limit_rings)
         call cap_load(radius, modulus, flow_pressure, delta_max, cap_options( &
            & n_rings=limit_rings(l), n_levels=2), limit%levels(l), result, error, &
            & "delta_max")
         if (allocated(error)) return
      end do
   end subroutine limit_load

   !> The smooth cap's unloading at delta after limit_load: the force extrapolated over
   !> the three histories (q1, q2, q3 from the coarsest: q3 + d2/(2**p - 1), d1 = q2 - q1,
   !> d2 = q3 - q2, p = log2(d1/d2)) where 0 < d2/d1 < shrink_max, force_error |d2/(2**p -
   !> 1)| (the finest's estimated error, which bounds the extrapolated force's: measured
   !> 1.1e-7 .. 1.2e-7 of P over 2.1e-8 .. 2.4e-8 off the reference); elsewhere the
   !> finest's force, force_error |d2|. Stiffness, radii and peak pressure: the finest's.
   subroutine limit_unload(limit, delta, result, error)
      type(cap_limit), intent(in) :: limit   !< from limit_load
      real(dp), intent(in) :: delta          !< overlap <= delta_max
      type(cap_result), intent(out) :: result   !< as cap_unload's, force extrapolated
      !> cap_unload's failure
      type(egw_error), allocatable, intent(out) :: error
      type(cap_result) :: coarser
      real(dp) :: q(3), d1, d2, ratio, step
      integer :: l
      do l = 1, 3
         call cap_unload(limit%levels(l), delta, coarser, error)
         if (allocated(error)) return
         q(l) = coarser%force
         if (l == 3) result = coarser
      end do
      d1 = q(2) - q(1)
      d2 = q(3) - q(2)
      result%force_error = abs(d2)
      if (d1 == 0.0_dp .or. d2 == 0.0_dp) return
      ratio = d2/d1
      if (.not. (ratio > 0.0_dp .and. ratio < shrink_max)) return
      ! (2**p - 1 = 1/ratio - 1)
      step = d2*ratio/(1.0_dp - ratio)
      result%force = q(3) + step
      result%force_error = abs(step)
   end subroutine limit_unload

end module egw_cap_limit
