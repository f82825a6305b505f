!> The flow-pressure cap as an object the rough sphere solver takes (doc/theory.md §12,
!> "Rough spheres with the cap"): the bulk flow pressure p_y caps the TOTAL pressure
!> p_s + p (p_s the smooth part of the extended models, p the rough-flat law's), so the
!> rough part is capped at p_y - p_s; and after a capped loading the plastic displacement
!> that unloading starts from. All in the solver's scaled units.
module egw_flow_cap
   use egw_kinds, only: dp
   use egw_flat_law, only: flat_law
   implicit none
   private

   !> The flow-pressure cap: p_y in the solver's pressure unit.
   type, public :: flow_cap
      real(dp) :: p_y = huge(1.0_dp)   !< scaled flow pressure (> 0)
   contains
      procedure :: apply => cap_apply
      procedure :: unload_floor => cap_unload_floor
      procedure :: plastic_shift => cap_plastic_shift
      procedure :: plastic_shifts => cap_plastic_shifts
   end type flow_cap

contains

   !> Loading: the rough part p (and dp/dh) at smooth pressures p_smooth capped so that
   !> p_smooth + p <= p_y; where capped p = p_y - p_smooth (negative where p_smooth > p_y),
   !> dp/dh = 0 and dp/d(delta) = -d(p_smooth)/d(delta), else dp/d(delta) = 0 (at fixed h).
   elemental subroutine cap_apply(cap, p_smooth, dps_ddelta, p, dpdh, dpdd)
      class(flow_cap), intent(in) :: cap
      real(dp), intent(in) :: p_smooth     !< smooth (Hertz) pressure, 0 for classic GW
      real(dp), intent(in) :: dps_ddelta   !< its delta-derivative at fixed r
      real(dp), intent(inout) :: p         !< rough part: the law's in, the capped out
      real(dp), intent(inout) :: dpdh      !< dp/dh: the law's in, 0 where capped
      real(dp), intent(out) :: dpdd        !< dp/d(delta) at fixed h
      dpdd = 0.0_dp
      if (p_smooth + p > cap%p_y) then
         p = cap%p_y - p_smooth
         dpdh = 0.0_dp
         dpdd = -dps_ddelta
      end if
   end subroutine cap_apply

   !> Unloading: the total pressure never falls below 0 (the rough part at least
   !> -p_smooth; only a shifted rough part with an offset, plastic_shift, can go below).
   elemental subroutine cap_unload_floor(cap, p_smooth, dps_ddelta, p, dpdh, dpdd)
      class(flow_cap), intent(in) :: cap
      real(dp), intent(in) :: p_smooth, dps_ddelta
      real(dp), intent(inout) :: p, dpdh
      real(dp), intent(out) :: dpdd
      dpdd = 0.0_dp
      if (p_smooth + p < 0.0_dp) then
         p = -p_smooth
         dpdh = 0.0_dp
         dpdd = -dps_ddelta
      end if
   end subroutine cap_unload_floor

   !> The plastic displacement at delta_max of a point at gap h_max with smooth pressure
   !> p_smooth_max there, for the loading law: where the law was capped (law(h_max) > c,
   !> c = p_y - p_smooth_max) the gap shift u_pl = h_c - h_max with law(h_c) = t,
   !> t = min(p_y, law(h_max)), and the pressure offset t - c; 0 and 0 elsewhere. Unloading
   !> uses the law at h + u_pl less the offset: at delta_max that is c again (continuous),
   !> and u_pl, offset are continuous in r (at the cap edge law(h_max) = c: t = c). Where
   !> law(h_max) >= p_y the unloading total is law(h + u_pl) + p_s(delta) - p_s(delta_max):
   !> the law carries the capped p_y from the shifted gap, the smooth part only its change
   !> (doc/theory.md §12 "Rough spheres with the cap").
   elemental subroutine cap_plastic_shift(cap, law, p_smooth_max, h_max, shift, offset)
      class(flow_cap), intent(in) :: cap
      class(flat_law), intent(in) :: law
      real(dp), intent(in) :: p_smooth_max, h_max
      real(dp), intent(out) :: shift, offset
      real(dp) :: c, t, h, p(1), dpdh(1)
      shift = 0.0_dp
      offset = 0.0_dp
      c = cap%p_y - p_smooth_max
      call law%pressure([h_max], p, dpdh)
      if (.not. p(1) > c) return
      t = min(cap%p_y, p(1))
      offset = t - c
      if (.not. p(1) > t) return
      ! law(h) = t for h > h_max (law decreasing). Newton from h_max: the laws are convex
      ! where they fall, so the tangent steps stay below the root and converge from the
      ! left in ~5 evaluations (bisection took ~60: it was 60 % of a rough + cap
      ! hysteresis build); a step that overshoots (law < t) bounds the root from above,
      ! and a step outside the bracket, or a flat law, falls back to doubling / bisection.
      call law_root(law, t, h_max, p(1), dpdh(1), h)
      shift = h - h_max
   end subroutine cap_plastic_shift

   !> cap_plastic_shift at many points (the Gauss points of a mesh), the law evaluated at
   !> all h_max in one call. Where law(h_max) > p_y (t = p_y, the deep plastic zone) the
   !> shifted gap h_c is the one root h_y of law(h) = p_y whatever the point, so it is
   !> solved once (from the largest such h_max, the closest) and u_pl = h_y - h_max:
   !> point by point the same Newton from each h_max cost ~5 law evaluations a point
   !> (a third of an EP-GW + cap hysteresis build). The same root to rounding.
   !> With known (and law_max): law_max holds law(h_max) already where known (the solver's
   !> values from an earlier mesh's same Gauss points), and the law is evaluated at the
   !> other points only (point by point the same values).
   pure subroutine cap_plastic_shifts(cap, law, p_smooth_max, h_max, shift, offset, law_max, &
      & known)
      class(flow_cap), intent(in) :: cap
      class(flat_law), intent(in) :: law
      real(dp), intent(in) :: p_smooth_max(:), h_max(:)   !< as cap_plastic_shift's, per point
      real(dp), intent(out) :: shift(:), offset(:)   !< as cap_plastic_shift's, per point
      !> law(h_max) (optional: kept by the solver for the cap's kink scan); in: where known
      real(dp), intent(inout), optional :: law_max(:)
      logical, intent(in), optional :: known(:)   !< where law_max holds law(h_max) on entry
      real(dp) :: p(size(h_max)), dpdh(size(h_max)), c, t, h_y, p1(1), dpdh1(1)
      real(dp), allocatable :: p_at(:), dpdh_at(:)
      integer, allocatable :: at(:)
      integer :: i, deepest
      logical :: reuse
      shift = 0.0_dp
      offset = 0.0_dp
      if (size(h_max) == 0) return
      reuse = .false.
      if (present(known) .and. present(law_max)) reuse = any(known)
      if (reuse) then
         at = pack([(i, i=1, size(h_max))], .not. known)
         allocate (p_at(size(at)), dpdh_at(size(at)))
         if (size(at) > 0) call law%pressure(h_max(at), p_at, dpdh_at)
         p = law_max
         dpdh = 0.0_dp   ! (not used where known: law_root's start is evaluated again)
         p(at) = p_at
         dpdh(at) = dpdh_at
      else
         call law%pressure(h_max, p, dpdh)
      end if
      if (present(law_max)) law_max = p
      deepest = 0
      do i = 1, size(h_max)
         if (.not. p(i) > cap%p_y) cycle
         if (deepest == 0) then
            deepest = i
         else if (h_max(i) > h_max(deepest)) then
            deepest = i
         end if
      end do
      h_y = 0.0_dp
      if (deepest > 0 .and. reuse) then
         if (known(deepest)) then
            call law%pressure(h_max(deepest:deepest), p1, dpdh1)
            dpdh(deepest) = dpdh1(1)
         end if
      end if
      if (deepest > 0) call law_root(law, cap%p_y, h_max(deepest), p(deepest), &
         & dpdh(deepest), h_y)
      do i = 1, size(h_max)
         c = cap%p_y - p_smooth_max(i)
         if (.not. p(i) > c) cycle
         t = min(cap%p_y, p(i))
         offset(i) = t - c
         if (.not. p(i) > t) cycle
         shift(i) = h_y - h_max(i)
      end do
   end subroutine cap_plastic_shifts

   !> The root h >= h_start of law(h) = t (law decreasing, law(h_start) = p_start > t,
   !> dlaw/dh = dpdh_start there).
   pure subroutine law_root(law, t, h_start, p_start, dpdh_start, h)
      class(flat_law), intent(in) :: law
      real(dp), intent(in) :: t, h_start, p_start, dpdh_start
      real(dp), intent(out) :: h
      real(dp) :: lo, hi, h_new, step, p(1), dpdh(1)
      integer :: i
      p(1) = p_start
      dpdh(1) = dpdh_start
      lo = h_start
      hi = huge(1.0_dp)
      h = h_start
      do i = 1, 400
         if (p(1) > t) then
            lo = h
         else
            hi = h
         end if
         if (p(1) == t) exit
         step = -1.0_dp
         if (dpdh(1) < 0.0_dp) step = (p(1) - t)/(-dpdh(1))
         h_new = h + step
         if (.not. (h_new > lo .and. h_new < hi)) then
            if (hi < huge(1.0_dp)) then
               h_new = 0.5_dp*(lo + hi)
            else
               h_new = h_start + 2.0_dp*max(lo - h_start, 0.5_dp)
            end if
         end if
         if (.not. (h_new > lo .and. h_new < hi)) exit
         if (abs(h_new - h) <= 4.0_dp*epsilon(1.0_dp)*abs(h_new)) then
            h = h_new
            exit
         end if
         h = h_new
         call law%pressure([h], p, dpdh)
      end do
   end subroutine law_root

end module egw_flow_cap
