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

   !> cap_plastic_shifts' law_max where the law was not evaluated (deep inside the plastic
   !> zone: the law is above p_y there).
   real(dp), parameter, public :: not_evaluated = huge(1.0_dp)
   !> The band of h below the closest deep point where cap_plastic_shifts still evaluates
   !> the law, relative to 1 + |h|: the law rises by ~1e-3 |dlaw/dh| across it, far above
   !> its rounding, so no point deeper than the band can be at or below p_y.
   real(dp), parameter :: deep_band = 1.0e-3_dp

   !> The flow-pressure cap: p_y in the solver's pressure unit.
   type, public :: flow_cap
      real(dp) :: p_y = huge(1.0_dp)   !< scaled flow pressure (> 0)
      !> The root h_y of law(h) = p_y of the law the cap was prepared for (prepare), where
      !> yield_known: the deep plastic zone's shifted gap, the same for every point and
      !> every solve of one law (cap_plastic_shifts)
      real(dp) :: h_yield = 0.0_dp
      logical :: yield_known = .false.
   contains
      procedure :: prepare => cap_prepare
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

   !> cap_plastic_shift at many points (the Gauss points of a mesh). Where law(h_max) > p_y
   !> (t = p_y, the deep plastic zone) the shifted gap h_c is the one root h_y of
   !> law(h) = p_y whatever the point, so it is solved once (by prepare, for the cap's law:
   !> cap%h_yield; a cap not prepared solves it here, from the largest such h_max, the
   !> closest) and u_pl = h_y - h_max: point by point the same Newton from each h_max
   !> cost ~5 law evaluations a point (a third of an EP-GW + cap hysteresis build). The
   !> same root to rounding. Deep points need no law value either (their shift and offset
   !> follow from h_y and p_y): the law is evaluated from the largest h_max down (sorted)
   !> through the first point above p_y (the closest deep point) and a band of
   !> deep_band (1 + |h|) below it; the points below that band are deep because the law
   !> decreases, and are not evaluated unless law_max needs them (EP-GW + cap table of the
   !> README: 1.1 M of 1.9 M evaluations here skipped, at gaps of -5 to -90 sigma where one
   !> costs 0.4-1 us; doc/benchmarks.md "Stop 48 (rcost14)"). The same points are deep as
   !> with every point evaluated, the same root from the same closest point, the same
   !> shifts and offsets.
   !> With known (and law_max): law_max holds law(h_max) already where known (the solver's
   !> values from an earlier mesh's same Gauss points), and the law is evaluated at the
   !> other points only (point by point the same values).
   pure subroutine cap_plastic_shifts(cap, law, p_smooth_max, h_max, shift, offset, law_max, &
      & known)
      class(flow_cap), intent(in) :: cap
      class(flat_law), intent(in) :: law
      real(dp), intent(in) :: p_smooth_max(:), h_max(:)   !< as cap_plastic_shift's, per point
      real(dp), intent(out) :: shift(:), offset(:)   !< as cap_plastic_shift's, per point
      !> law(h_max) (optional: kept by the solver for the cap's kink scan), except at deep
      !> points whose neighbours (index +-1) are deep too: not_evaluated there (> p_y, as
      !> the law; the kink scan's brackets never end at such a point). In: where known.
      real(dp), intent(inout), optional :: law_max(:)
      logical, intent(in), optional :: known(:)   !< where law_max holds law(h_max) on entry
      real(dp) :: p(size(h_max)), dpdh(size(h_max)), c, t, h_y, p1(1), dpdh1(1), band
      integer :: order(size(h_max)), i, k, n, deepest, first_deep
      !> p(i) is law(h_max(i)) (from known, or evaluated here: then dpdh(i) is its slope)
      logical :: have(size(h_max)), fresh(size(h_max)), edge
      shift = 0.0_dp
      offset = 0.0_dp
      n = size(h_max)
      if (n == 0) return
      have = .false.
      if (present(known) .and. present(law_max)) then
         ! (a known not_evaluated is no value)
         have = known .and. law_max < not_evaluated
         where (have) p = law_max
      end if
      fresh = .false.
      dpdh = 0.0_dp
      call order_descending(h_max, order)
      deepest = 0
      band = 0.0_dp
      first_deep = n + 1
      do k = 1, n
         i = order(k)
         if (deepest > 0) then
            if (h_max(i) < h_max(deepest) - band) then
               first_deep = k
               exit
            end if
         end if
         if (.not. have(i)) then
            call law_point(law, h_max(i), p(i), dpdh(i))
            have(i) = .true.
            fresh(i) = .true.
         end if
         if (deepest == 0 .and. p(i) > cap%p_y) then
            deepest = i
            band = deep_band*(1.0_dp + abs(h_max(i)))
         end if
      end do
      ! order(k:) lie deeper than the band below the closest deep point: law > p_y there
      do k = first_deep, n
         i = order(k)
         if (.not. have(i)) p(i) = not_evaluated
      end do
      if (present(law_max)) then
         ! the kink scan brackets sign changes of law - p_y (and law - (p_y - p_s)) between
         ! neighbouring points: a deep point next to one that is not deep needs its value
         do i = 1, n
            if (have(i)) cycle
            edge = .false.
            if (i > 1) edge = .not. p(i - 1) > cap%p_y
            if (i < n) edge = edge .or. .not. p(i + 1) > cap%p_y
            if (.not. edge) cycle
            call law_point(law, h_max(i), p(i), dpdh(i))
            have(i) = .true.
            fresh(i) = .true.
         end do
         law_max = p
      end if
      h_y = 0.0_dp
      if (deepest > 0 .and. cap%yield_known) then
         h_y = cap%h_yield
      else if (deepest > 0) then
         if (.not. fresh(deepest)) then
            ! (known: law_root's start needs the slope too)
            call law_point(law, h_max(deepest), p1(1), dpdh(deepest))
         end if
         call law_root(law, cap%p_y, h_max(deepest), p(deepest), dpdh(deepest), h_y)
      end if
      do i = 1, n
         c = cap%p_y - p_smooth_max(i)
         if (.not. p(i) > c) cycle
         t = min(cap%p_y, p(i))
         offset(i) = t - c
         if (.not. p(i) > t) cycle
         shift(i) = h_y - h_max(i)
      end do
   end subroutine cap_plastic_shifts

   !> The cap for one law: its root h_y of law(h) = p_y, solved once here (from the first of
   !> h = 0, -1, -2, -4, ... where law(h) > p_y, by law_root) instead of once in every
   !> cap_plastic_shifts call from that call's closest deep point: 5-6 law evaluations a
   !> call, ~0.6 M evaluations of the ZMC law (~3 % of CPU) in the EP-GW + cap psi 1 table
   !> of issue 32 (doc/benchmarks.md "Stop 51 (psi17)"). The same root to its last bits
   !> (law_root stops at a step of 4 ulps). Not found (the law stays <= p_y down to
   !> h = -2^60, or is not finite): yield_known false, and cap_plastic_shifts solves as
   !> before.
   pure subroutine cap_prepare(cap, law)
      class(flow_cap), intent(inout) :: cap
      class(flat_law), intent(in) :: law   !< the loading law the cap acts on
      real(dp) :: h, p, dpdh, h_y
      integer :: i
      cap%yield_known = .false.
      cap%h_yield = 0.0_dp
      h = 0.0_dp
      do i = 0, 61
         call law_point(law, h, p, dpdh)
         if (p > cap%p_y) exit
         if (.not. abs(p) <= huge(p)) return
         h = -2.0_dp**i
      end do
      if (.not. (p > cap%p_y .and. p <= huge(p))) return
      call law_root(law, cap%p_y, h, p, dpdh, h_y)
      cap%h_yield = h_y
      cap%yield_known = .true.
   end subroutine cap_prepare

   !> The law and its slope at one point.
   pure subroutine law_point(law, h, p, dpdh)
      class(flat_law), intent(in) :: law
      real(dp), intent(in) :: h
      real(dp), intent(out) :: p, dpdh
      real(dp) :: p1(1), dpdh1(1)
      call law%pressure([h], p1, dpdh1)
      p = p1(1)
      dpdh = dpdh1(1)
   end subroutine law_point

   !> order: the indices of x by decreasing value, equal values by increasing index (a
   !> stable merge sort, bottom up).
   pure subroutine order_descending(x, order)
      real(dp), intent(in) :: x(:)
      integer, intent(out) :: order(:)
      integer :: work(size(x)), width, lo, mid, hi, a, b, k, n
      n = size(x)
      order = [(k, k=1, n)]
      width = 1
      do while (width < n)
         do lo = 1, n, 2*width
            mid = min(lo + width, n + 1)
            hi = min(lo + 2*width, n + 1)
            a = lo
            b = mid
            do k = lo, hi - 1
               if (a < mid .and. b < hi) then
                  if (x(order(b)) > x(order(a))) then
                     work(k) = order(b)
                     b = b + 1
                  else
                     work(k) = order(a)
                     a = a + 1
                  end if
               else if (a < mid) then
                  work(k) = order(a)
                  a = a + 1
               else
                  work(k) = order(b)
                  b = b + 1
               end if
            end do
         end do
         order = work
         width = 2*width
      end do
   end subroutine order_descending

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
