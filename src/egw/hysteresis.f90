!> Hysteresis tables for DEM (issue 10 item 4): the EP-GW force over (delta, delta_max) of
!> one parameter set, built adaptively to rel_tol, evaluated with a history (the largest
!> overlap so far) that the caller owns.
!>
!> Layout: the loading curve is a 1-D force_table (egw_table). Unloading curves are stored
!> at peak nodes delta_max = peak(j) as the ratio r(s) = P_unload(delta; peak)/P_load(peak)
!> over the normalised unloading coordinate s = (delta - delta_c)/(peak - delta_c) in
!> [0, 1] (delta_c the loading table's cut-off), on one s grid shared by all peaks, with
!> dr/ds from the solver's stiffness: cubic Hermite in s, linear in peak. r(1) = 1 at every
!> peak, so the force is continuous where unloading leaves the loading curve. The error
!> criterion of the unloading part is |P_table - P_solve| <= rel_tol*P_load(delta_max)
!> (the scale of the curve that the history selects); each direction gets rel_tol/2.
module egw_hysteresis
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_invalid_argument, egw_not_converged, fatal_error, &
      & format_real
   use egw_params, only: contact_params
   use egw_rough_sphere, only: solver_options, solve_result, loading_history, &
      & load_history, solve_unload
   use egw_table, only: force_table, build_table, table_eval
   implicit none
   private

   public :: build_hysteresis, build_hysteresis_with, hysteresis_eval, hysteresis_sampler

   !> Unloading ratios of one peak: r(s_i) = P_unload(delta_c + s_i (peak - delta_c); peak)
   !> / P_load(peak) and dr/ds at the given s (0 <= s <= 1).
   abstract interface
      subroutine hysteresis_sampler(peak, s, r, drds, error)
         import :: dp, egw_error
         real(dp), intent(in) :: peak        !< largest overlap of the history
         real(dp), intent(in) :: s(:)        !< normalised unloading coordinates
         real(dp), intent(out) :: r(:)       !< force ratio to the loading force at peak
         real(dp), intent(out) :: drds(:)    !< dr/ds
         type(egw_error), allocatable, intent(out) :: error
      end subroutine hysteresis_sampler
   end interface

   !> Hysteresis table of one parameter set. Evaluation (hysteresis_eval) reads it only.
   type, public :: hysteresis_table
      type(force_table) :: loading                !< the loading curve (1-D table)
      real(dp) :: rel_tol = 0.0_dp                !< requested tolerance
      real(dp) :: cutoff = 0.0_dp                 !< delta_c: force 0 below
      real(dp) :: delta_max = 0.0_dp              !< last overlap and peak covered
      real(dp) :: max_unload_error = 0.0_dp       !< max |dP|/P_load(peak) at the checks
      real(dp), allocatable :: s(:)               !< (n_s) unloading coordinate, 0 .. 1
      real(dp), allocatable :: peak(:)            !< (n_peak) delta_max nodes, ascending
      real(dp), allocatable :: ratio(:, :)        !< (n_s, n_peak) P_unload/P_load(peak)
      real(dp), allocatable :: dratio(:, :)       !< (n_s, n_peak) d ratio/ds
   end type hysteresis_table

   integer, parameter :: max_rounds = 40, max_s = 400, max_peaks = 400

contains

   !> Build the EP-GW (or any model's) hysteresis table over [delta_min, delta_max] to
   !> rel_tol: the loading table as build_table (same cut-off rule and errors), unloading
   !> curves from load_history/solve_unload at adaptively placed peaks and unloading
   !> coordinates, checked by solves midway between nodes in s and in delta_max. The
   !> solver runs with one thread inside an OpenMP loop over peaks.
   subroutine build_hysteresis(params, options, delta_min, delta_max, rel_tol, table, error)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta_min            !< smallest overlap (separation < 0)
      real(dp), intent(in) :: delta_max            !< largest overlap and history
      real(dp), intent(in) :: rel_tol              !< interpolation tolerance, (0, 0.1]
      type(hysteresis_table), intent(inout) :: table  !< untouched on error
      type(egw_error), allocatable, intent(out) :: error
      type(force_table) :: loading
      type(solver_options) :: opts

      call build_table(params, options, delta_min, delta_max, rel_tol, loading, error)
      if (allocated(error)) return
      opts = options
      opts%n_threads = 1
      opts%rel_tol = min(options%rel_tol, rel_tol/10)
      call build_hysteresis_with(loading, solved_ratios, table, error)
   contains
      subroutine solved_ratios(peak, s, r, drds, error)
         real(dp), intent(in) :: peak, s(:)
         real(dp), intent(out) :: r(:), drds(:)
         type(egw_error), allocatable, intent(out) :: error
         type(loading_history) :: history
         type(solve_result) :: res, top
         real(dp) :: span
         integer :: i
         call load_history(params, opts, peak, history, top, error)
         if (allocated(error)) return
         span = peak - loading%cutoff
         do i = 1, size(s)
            if (s(i) >= 1.0_dp) then
               res = top
            else
               call solve_unload(history, loading%cutoff + s(i)*span, res, error)
               if (allocated(error)) return
            end if
            r(i) = 0.0_dp
            drds(i) = 0.0_dp
            if (top%force > 0.0_dp) then
               r(i) = res%force/top%force
               drds(i) = res%stiffness*span/top%force
            end if
         end do
      end subroutine solved_ratios
   end subroutine build_hysteresis

   !> The adaptive build on a given loading table with unloading ratios from sampler
   !> (build_hysteresis passes the solver; tests pass an analytic family). rel_tol is
   !> the loading table's.
   subroutine build_hysteresis_with(loading, sampler, table, error)
      type(force_table), intent(in) :: loading
      procedure(hysteresis_sampler) :: sampler
      type(hysteresis_table), intent(inout) :: table   !< untouched on error
      type(egw_error), allocatable, intent(out) :: error
      real(dp), allocatable :: s(:), peak(:), r(:, :), dr(:, :), sm(:), rm(:, :), drm(:, :)
      real(dp), allocatable :: pm(:), rp(:, :), drp(:, :)
      logical, allocatable :: split(:)
      real(dp) :: tol, lo, err, max_err, ri, di, w
      integer :: round, i, j, n_s, n_p
      type(hysteresis_table) :: t

      tol = 0.5_dp*loading%rel_tol
      lo = loading%cutoff
      ! initial peaks: the loading table's nodes above the cut-off (they follow the force)
      peak = loading%delta(2:)
      s = [(real(i, dp)/8, i=0, 8)]
      call sample_grid(sampler, peak, s, r, dr, error)
      if (allocated(error)) return
      max_err = 0.0_dp

      do round = 1, max_rounds
         n_s = size(s)
         n_p = size(peak)
         if (round == max_rounds .or. n_s > max_s .or. n_p > max_peaks) then
            call fatal_error(error, egw_not_converged, "rel_tol = "// &
               & format_real(loading%rel_tol)//": hysteresis table did not converge "// &
               & "within the node limit")
            return
         end if
         ! 1. unloading coordinate: midpoints of every s interval at every peak
         sm = 0.5_dp*(s(1:n_s - 1) + s(2:n_s))
         call sample_grid(sampler, peak, sm, rm, drm, error)
         if (allocated(error)) return
         allocate (split(n_s - 1))
         split = .false.
         do j = 1, n_p
            do i = 1, n_s - 1
               call hermite(s(i), s(i + 1), r(i, j), r(i + 1, j), dr(i, j), dr(i + 1, j), &
                  & sm(i), ri, di)
               err = abs(ri - rm(i, j))
               max_err = max(max_err, err)
               split(i) = split(i) .or. err > tol
            end do
         end do
         if (any(split)) then
            call insert_s(s, r, dr, sm, rm, drm, split)
            deallocate (split)
            cycle
         end if
         deallocate (split)
         ! 2. peaks: a column midway between neighbouring peaks, against the linear
         !    combination of its neighbours at the s nodes and the s midpoints
         pm = 0.5_dp*(peak(1:n_p - 1) + peak(2:n_p))
         call sample_grid(sampler, pm, s, rp, drp, error)
         if (allocated(error)) return
         allocate (split(n_p - 1))
         split = .false.
         do j = 1, n_p - 1
            w = 0.5_dp
            do i = 1, n_s
               err = abs((1 - w)*r(i, j) + w*r(i, j + 1) - rp(i, j))
               max_err = max(max_err, err)
               split(j) = split(j) .or. err > tol
            end do
         end do
         if (.not. any(split)) exit
         call insert_peaks(peak, r, dr, pm, rp, drp, split)
         deallocate (split)
      end do
      t%loading = loading
      t%rel_tol = loading%rel_tol
      t%cutoff = lo
      t%delta_max = loading%delta_max
      t%max_unload_error = max_err
      call move_alloc(s, t%s)
      call move_alloc(peak, t%peak)
      call move_alloc(r, t%ratio)
      call move_alloc(dr, t%dratio)
      table = t
   end subroutine build_hysteresis_with

   !> Ratios at every (s, peak) pair; OpenMP over peaks.
   subroutine sample_grid(sampler, peak, s, r, dr, error)
      procedure(hysteresis_sampler) :: sampler
      real(dp), intent(in) :: peak(:), s(:)
      real(dp), allocatable, intent(out) :: r(:, :), dr(:, :)
      type(egw_error), allocatable, intent(out) :: error
      type(egw_error), allocatable :: err_j
      integer :: j, bad
      allocate (r(size(s), size(peak)), dr(size(s), size(peak)))
      bad = 0
      !$omp parallel do schedule(dynamic) private(err_j) reduction(max:bad)
      do j = 1, size(peak)
         call sampler(peak(j), s, r(:, j), dr(:, j), err_j)
         if (allocated(err_j)) bad = max(bad, j)
      end do
      !$omp end parallel do
      if (bad > 0) call sampler(peak(bad), s, r(:, bad), dr(:, bad), error)
   end subroutine sample_grid

   !> Insert the midpoints sm(i) (rows rm, drm) where split(i).
   pure subroutine insert_s(s, r, dr, sm, rm, drm, split)
      real(dp), allocatable, intent(inout) :: s(:), r(:, :), dr(:, :)
      real(dp), intent(in) :: sm(:), rm(:, :), drm(:, :)
      logical, intent(in) :: split(:)
      real(dp), allocatable :: s2(:), r2(:, :), d2(:, :)
      integer :: i, k
      k = size(s) + count(split)
      allocate (s2(k), r2(k, size(r, 2)), d2(k, size(r, 2)))
      k = 0
      do i = 1, size(s)
         k = k + 1
         s2(k) = s(i)
         r2(k, :) = r(i, :)
         d2(k, :) = dr(i, :)
         if (i < size(s)) then
            if (split(i)) then
               k = k + 1
               s2(k) = sm(i)
               r2(k, :) = rm(i, :)
               d2(k, :) = drm(i, :)
            end if
         end if
      end do
      call move_alloc(s2, s)
      call move_alloc(r2, r)
      call move_alloc(d2, dr)
   end subroutine insert_s

   !> Insert the middle peaks pm(j) (columns rp, drp) where split(j).
   pure subroutine insert_peaks(peak, r, dr, pm, rp, drp, split)
      real(dp), allocatable, intent(inout) :: peak(:), r(:, :), dr(:, :)
      real(dp), intent(in) :: pm(:), rp(:, :), drp(:, :)
      logical, intent(in) :: split(:)
      real(dp), allocatable :: p2(:), r2(:, :), d2(:, :)
      integer :: j, k
      k = size(peak) + count(split)
      allocate (p2(k), r2(size(r, 1), k), d2(size(r, 1), k))
      k = 0
      do j = 1, size(peak)
         k = k + 1
         p2(k) = peak(j)
         r2(:, k) = r(:, j)
         d2(:, k) = dr(:, j)
         if (j < size(peak)) then
            if (split(j)) then
               k = k + 1
               p2(k) = pm(j)
               r2(:, k) = rp(:, j)
               d2(:, k) = drp(:, j)
            end if
         end if
      end do
      call move_alloc(p2, peak)
      call move_alloc(r2, r)
      call move_alloc(d2, dr)
   end subroutine insert_peaks

   !> Cubic Hermite value and slope at x in [xa, xb].
   pure subroutine hermite(xa, xb, fa, fb, da, db, x, f, d)
      real(dp), intent(in) :: xa, xb, fa, fb, da, db, x
      real(dp), intent(out) :: f, d
      real(dp) :: h, t, h00, h10, h01, h11
      h = xb - xa
      t = (x - xa)/h
      h00 = (1 + 2*t)*(1 - t)**2
      h10 = t*(1 - t)**2
      h01 = t*t*(3 - 2*t)
      h11 = t*t*(t - 1)
      f = h00*fa + h10*h*da + h01*fb + h11*h*db
      d = (6*t*t - 6*t)*(fa - fb)/h + (3*t*t - 4*t + 1)*da + (3*t*t - 2*t)*db
   end subroutine hermite

   !> Index i with x(i) <= v < x(i+1), clamped to 1 .. size(x) - 1 (bisection, no
   !> allocation).
   pure integer function interval(x, v) result(i)
      real(dp), intent(in) :: x(:), v
      integer :: lo, hi, mid
      lo = 1
      hi = size(x)
      do while (hi - lo > 1)
         mid = (lo + hi)/2
         if (x(mid) <= v) then
            lo = mid
         else
            hi = mid
         end if
      end do
      i = lo
   end function interval

   !> Force and stiffness at overlap delta with the history state = the largest overlap
   !> so far (-huge or -inf for a new contact); state <- max(state, delta). delta >= the
   !> old state: the loading curve; below it: the unloading curve of peak = state (0
   !> below the cut-off, and where it has fallen to rel_tol*P_ref). Above the table's
   !> delta_max the loading curve continues linearly and the last peak's ratios are used
   !> (the C layer reports EGW_OUT_OF_RANGE). No allocation, read-only table.
   pure subroutine hysteresis_eval(table, delta, state, force, stiffness)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: delta                !< overlap (> 0), separation (< 0)
      real(dp), intent(inout) :: state             !< largest overlap so far
      real(dp), intent(out) :: force              !< contact force
      real(dp), intent(out) :: stiffness          !< dP/d(delta) at fixed history
      real(dp) :: s, span, w, ra, rb, da, db, r, dr, p_top, k_top
      integer :: i, j, np

      if (.not. (delta < state)) then
         state = delta
         call table_eval(table%loading, delta, force, stiffness)
         return
      end if
      force = 0.0_dp
      stiffness = 0.0_dp
      if (state <= table%cutoff .or. delta <= table%cutoff) return
      span = state - table%cutoff
      s = (delta - table%cutoff)/span
      np = size(table%peak)
      i = interval(table%s, s)
      if (state <= table%peak(1) .or. np == 1) then
         j = 1
         w = 0.0_dp
      else if (state >= table%peak(np)) then
         j = np - 1
         w = 1.0_dp
      else
         j = interval(table%peak, state)
         w = (state - table%peak(j))/(table%peak(j + 1) - table%peak(j))
      end if
      call hermite(table%s(i), table%s(i + 1), table%ratio(i, j), table%ratio(i + 1, j), &
         & table%dratio(i, j), table%dratio(i + 1, j), s, ra, da)
      if (w > 0.0_dp) then
         call hermite(table%s(i), table%s(i + 1), table%ratio(i, j + 1), &
            & table%ratio(i + 1, j + 1), table%dratio(i, j + 1), table%dratio(i + 1, j + 1), &
            & s, rb, db)
         r = (1 - w)*ra + w*rb
         dr = (1 - w)*da + w*db
      else
         r = ra
         dr = da
      end if
      call table_eval(table%loading, state, p_top, k_top)
      force = r*p_top
      if (force <= table%rel_tol*table%loading%reference_force) then
         force = 0.0_dp
         return
      end if
      stiffness = max(0.0_dp, dr*p_top/span)
   end subroutine hysteresis_eval

end module egw_hysteresis
