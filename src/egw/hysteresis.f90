!> Hysteresis tables for DEM (EP-GW loading, unloading and reloading, doc/theory.md §8):
!> the force of one parameter set over (delta, delta_max), with a per-contact history that
!> the caller owns (the largest overlap so far; -huge for a contact that never touched).
!>
!> Layout: the loading curve is a 1-D force table (egw_table). Each node m_j of the
!> delta_max grid carries its unloading curve as the hysteresis gap relative to the force
!> at the turning point, g_j(xi) = [P_load(m_j - xi) - P_unload(m_j - xi; m_j)]/P_load(m_j),
!> xi = m_j - delta >= 0, on cubic Hermite nodes in xi (slopes from the solver's
!> stiffnesses; the solves run at rel_tol/10). Between m nodes g is interpolated linearly
!> in m at the same xi, and the force is P = max(0, P_load(delta) - P_load(m) g): g = 0 at
!> xi = 0 for every m, so the force is continuous where unloading starts, and the loading
!> table is used as it is. Both grids are refined
!> until solves at the midpoints (xi midpoints of every curve; nine xi of the curve of
!> every m midpoint) agree with the table to rel_tol of the force at the turning point.
!> Evaluation allocates nothing and changes only the caller's history.
module egw_hysteresis
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_invalid_argument, egw_invalid_parameter, &
      & egw_not_converged, egw_out_of_range, fatal_error, format_real
   use egw_params, only: contact_params, validate_params, model_epgw
   use egw_rough_sphere, only: solver_options, solve_result, loading_history, load_history, &
      & solve_unload
   use egw_table, only: force_table, build_table, table_eval
   implicit none
   private

   public :: hysteresis_table, build_hysteresis, hysteresis_eval

   !> Nodes in xi of one unloading curve (at most), and of the delta_max grid.
   integer, parameter :: max_xi_nodes = 400, max_m_nodes = 400

   !> The unloading curve of one delta_max node: the gap D(xi) and dD/dxi at nodes xi.
   type :: unloading_curve
      real(dp), allocatable :: xi(:), gap(:), slope(:)
   end type unloading_curve

   !> A hysteresis table of one parameter set (build_hysteresis).
   type :: hysteresis_table
      type(contact_params) :: params           !< parameters the table was built for
      real(dp) :: rel_tol = 0.0_dp             !< requested tolerance
      real(dp) :: delta_max = 0.0_dp           !< last delta_max node (table range)
      real(dp) :: max_error = 0.0_dp           !< largest mismatch found at check solves
      type(force_table) :: loading             !< the loading curve
      real(dp), allocatable :: m(:)            !< delta_max nodes, increasing
      type(unloading_curve), allocatable :: curves(:)  !< one per delta_max node
   end type hysteresis_table

contains

   !> Build the hysteresis table of params over overlaps [delta_min, delta_max] to rel_tol
   !> (relative to the force at the turning point). Errors: invalid params or range,
   !> solves that fail (egw_not_converged), node limits reached.
   subroutine build_hysteresis(params, options, delta_min, delta_max, rel_tol, table, error)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta_min      !< smallest overlap of interest (< 0: separation)
      real(dp), intent(in) :: delta_max      !< largest overlap (and delta_max) tabulated
      real(dp), intent(in) :: rel_tol        !< tolerance, in [1e-8, 0.1]
      type(hysteresis_table), intent(out) :: table
      type(egw_error), allocatable, intent(out) :: error
      type(unloading_curve), allocatable :: curves(:), merged(:), mid_curves(:)
      real(dp), allocatable :: m(:), m_new(:)
      real(dp) :: err_mid
      integer, allocatable :: idx(:)
      integer :: j, n, k, pass, i
      logical, allocatable :: split(:), checked(:), checked_new(:)

      call validate_params(params, error)
      if (allocated(error)) return
      if (.not. (rel_tol >= 1.0e-8_dp .and. rel_tol <= 0.1_dp)) then
         call fatal_error(error, egw_invalid_argument, "rel_tol = "//format_real(rel_tol)// &
            & ": must lie in [1e-8, 0.1]")
         return
      end if
      if (ieee_is_nan(delta_min) .or. .not. (delta_max > delta_min .and. &
         & delta_max < huge(1.0_dp))) then
         call fatal_error(error, egw_invalid_argument, "delta_min, delta_max = "// &
            & format_real(delta_min)//", "//format_real(delta_max)// &
            & ": need finite delta_min < delta_max")
         return
      end if
      call build_table(params, options, delta_min, delta_max, rel_tol, table%loading, error)
      if (allocated(error)) return
      table%params = params
      table%rel_tol = rel_tol
      table%delta_max = delta_max
      ! delta_max grid: from the loading cut-off (nothing to unload below) to delta_max
      n = 9
      allocate (m(n))
      m = table%loading%cutoff + (delta_max - table%loading%cutoff)*[(real(j, dp), j = 0, n - 1)] &
         & /real(n - 1, dp)
      allocate (curves(n))
      call build_curves(table, options, m, curves, error)
      if (allocated(error)) return
      ! refine the delta_max grid where a curve at the midpoint differs from the
      ! interpolation of its neighbours (intervals already checked are not checked again)
      allocate (checked(n - 1))
      checked = .false.
      do pass = 1, 20
         ! the midpoint curves of the unchecked intervals, built in parallel
         idx = pack([(j, j = 1, size(m) - 1)], .not. checked)
         allocate (split(size(m) - 1), mid_curves(size(idx)))
         split = .false.
         call build_curves(table, options, 0.5_dp*(m(idx) + m(idx + 1)), mid_curves, error)
         if (allocated(error)) return
         do i = 1, size(idx)
            j = idx(i)
            err_mid = curve_mismatch(table, curves(j), curves(j + 1), m(j), m(j + 1), &
               & mid_curves(i), 0.5_dp*(m(j) + m(j + 1)))
            split(j) = err_mid > rel_tol
            if (.not. split(j)) table%max_error = max(table%max_error, err_mid)
         end do
         if (.not. any(split)) exit
         if (size(m) + count(split) > max_m_nodes) then
            call fatal_error(error, egw_not_converged, "hysteresis table: more than "// &
               & format_real(real(max_m_nodes, dp))//" delta_max nodes needed for rel_tol = " &
               & //format_real(rel_tol))
            return
         end if
         allocate (m_new(size(m) + count(split)), merged(size(m) + count(split)), &
            & checked_new(size(m) + count(split) - 1))
         k = 0
         do j = 1, size(m)
            k = k + 1
            m_new(k) = m(j)
            call move_curve(curves(j), merged(k))
            if (j < size(m)) then
               if (split(j)) then
                  checked_new(k) = .false.
                  k = k + 1
                  m_new(k) = 0.5_dp*(m(j) + m(j + 1))
                  ! the midpoint's curve was built for the check: it becomes a node
                  call move_curve(mid_curves(findloc(idx, j, dim=1)), merged(k))
                  checked_new(k) = .false.
               else
                  checked_new(k) = .true.
               end if
            end if
         end do
         call move_alloc(m_new, m)
         call move_alloc(merged, curves)
         call move_alloc(checked_new, checked)
         deallocate (split, mid_curves)
      end do
      call move_alloc(m, table%m)
      call move_alloc(curves, table%curves)
   end subroutine build_hysteresis

   !> Force [force] and stiffness dP/ddelta [force/length] at overlap delta for a contact
   !> whose history is delta_max_state (the largest overlap so far; -huge(1.0) for a new
   !> contact), which is updated to max(state, delta). Loading (delta >= state) follows the
   !> loading table; unloading and reloading below the state the unloading curve of the
   !> state. A state above the table's delta_max uses the last curve and returns
   !> egw_out_of_range (values written). NaN delta: egw_invalid_argument, nothing changed.
   subroutine hysteresis_eval(table, delta, delta_max_state, force, stiffness, stat)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: delta
      real(dp), intent(inout) :: delta_max_state
      real(dp), intent(out) :: force, stiffness
      integer, intent(out) :: stat
      real(dp) :: f_load, k_load, gap, slope, w, g1, s1, g2, s2, m, scale
      integer :: j
      stat = 0
      if (ieee_is_nan(delta)) then
         stat = egw_invalid_argument
         force = 0.0_dp
         stiffness = 0.0_dp
         return
      end if
      call table_eval(table%loading, delta, f_load, k_load)
      if (.not. delta < delta_max_state) then
         delta_max_state = delta
         force = f_load
         stiffness = k_load
         if (delta > table%delta_max) stat = egw_out_of_range
         return
      end if
      m = delta_max_state
      if (m >= table%m(size(table%m))) then
         j = size(table%m) - 1
         w = 1.0_dp
         if (m > table%delta_max) stat = egw_out_of_range
      else if (m <= table%m(1)) then
         j = 1
         w = 0.0_dp
      else
         j = find_node(table%m, m)
         w = (m - table%m(j))/(table%m(j + 1) - table%m(j))
      end if
      call curve_eval(table%curves(j), m - delta, g1, s1)
      call curve_eval(table%curves(j + 1), m - delta, g2, s2)
      scale = turning_force(table, m)
      gap = scale*((1.0_dp - w)*g1 + w*g2)
      slope = scale*((1.0_dp - w)*s1 + w*s2)
      force = f_load - gap
      stiffness = k_load + slope
      if (force <= 0.0_dp) then
         force = 0.0_dp
         stiffness = 0.0_dp
      end if
   end subroutine hysteresis_eval

   ! ---------------------------------------------------------------------------------------

   !> The unloading curves of the delta_max values m(:), in parallel (OpenMP; every curve
   !> is independent: its own loading history and solves); the first error wins.
   subroutine build_curves(table, options, m, curves, error)
      type(hysteresis_table), intent(inout) :: table
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: m(:)
      type(unloading_curve), intent(inout) :: curves(:)
      type(egw_error), allocatable, intent(out) :: error
      type(solver_options) :: serial
      real(dp) :: worst(size(m))
      integer :: stats(size(m)), j
      character(len=256) :: messages(size(m))
      serial = options
      serial%n_threads = 1  ! the parallelism is over the curves
      ! the unloading solves run a decade finer than the table's tolerance
      serial%rel_tol = table%rel_tol/10.0_dp
      stats = 0
      worst = 0.0_dp
      !$omp parallel do schedule(dynamic) default(shared) private(j)
      do j = 1, size(m)
         call one_curve(j)
      end do
      !$omp end parallel do
      do j = 1, size(m)
         if (stats(j) /= 0) then
            call fatal_error(error, stats(j), trim(messages(j)))
            return
         end if
      end do
      table%max_error = max(table%max_error, maxval(worst))
   contains
      subroutine one_curve(j)
         integer, intent(in) :: j
         type(egw_error), allocatable :: err
         call build_curve(table, serial, m(j), curves(j), worst(j), err)
         if (allocated(err)) then
            stats(j) = err%stat
            messages(j) = err%message
         end if
      end subroutine one_curve
   end subroutine build_curves

   !> The unloading curve of delta_max = m: xi nodes from 0 to m - cutoff, bisected until the
   !> Hermite gap agrees with the solves at every midpoint to rel_tol P_load(m).
   subroutine build_curve(table, options, m, curve, worst, error)
      type(hysteresis_table), intent(in) :: table
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: m
      type(unloading_curve), intent(out) :: curve
      real(dp), intent(out) :: worst
      type(egw_error), allocatable, intent(out) :: error
      type(loading_history) :: hist
      type(solve_result) :: res
      real(dp) :: xi(max_xi_nodes), gap(max_xi_nodes), slope(max_xi_nodes), scale, span, &
         & g_mid, s_mid, g_int, s_int, x_mid
      integer :: n, i, k
      logical :: refined
      type(unloading_curve) :: probe
      worst = 0.0_dp
      span = m - table%loading%cutoff
      call load_history(table%params, options, m, hist, res, error)
      if (allocated(error)) return
      scale = turning_force(table, m)
      n = 5
      xi(1:n) = span*[0.0_dp, 0.0625_dp, 0.25_dp, 0.5_dp, 1.0_dp]
      if (.not. span > 0.0_dp) then
         allocate (curve%xi(1), curve%gap(1), curve%slope(1))
         curve%xi = 0.0_dp
         curve%gap = 0.0_dp
         curve%slope = 0.0_dp
         return
      end if
      do i = 1, n
         call gap_at(xi(i), gap(i), slope(i))
         if (allocated(error)) return
      end do
      do
         refined = .false.
         i = 1
         do while (i < n)
            x_mid = 0.5_dp*(xi(i) + xi(i + 1))
            call gap_at(x_mid, g_mid, s_mid)
            if (allocated(error)) return
            probe%xi = xi(i:i + 1)
            probe%gap = gap(i:i + 1)
            probe%slope = slope(i:i + 1)
            call curve_eval(probe, x_mid, g_int, s_int)
            if (abs(g_int - g_mid) > table%rel_tol*scale) then
               if (n == max_xi_nodes) then
                  call fatal_error(error, egw_not_converged, "hysteresis table: an unloading"// &
                     & " curve needs more than 400 nodes at delta_max = "//format_real(m))
                  return
               end if
               do k = n, i + 1, -1
                  xi(k + 1) = xi(k)
                  gap(k + 1) = gap(k)
                  slope(k + 1) = slope(k)
               end do
               xi(i + 1) = x_mid
               gap(i + 1) = g_mid
               slope(i + 1) = s_mid
               n = n + 1
               refined = .true.
            else
               worst = max(worst, abs(g_int - g_mid)/scale)
            end if
            i = i + 1
         end do
         if (.not. refined) exit
      end do
      ! stored relative to the force at the turning point: the gaps of neighbouring
      ! delta_max then differ smoothly also where forces change by orders of magnitude
      curve%xi = xi(1:n)
      curve%gap = gap(1:n)/scale
      curve%slope = slope(1:n)/scale

   contains

      !> D(xi) = P_load(table) - P_unload(solve) and dD/dxi = k_unload - k_load at delta = m - xi
      subroutine gap_at(x, g, s)
         real(dp), intent(in) :: x
         real(dp), intent(out) :: g, s
         real(dp) :: f_load, k_load
         g = 0.0_dp
         s = 0.0_dp
         if (.not. x > 0.0_dp) return
         call table_eval(table%loading, m - x, f_load, k_load)
         call solve_unload(hist, m - x, res, error)
         if (allocated(error)) return
         g = f_load - res%force
         s = res%stiffness - k_load
      end subroutine gap_at

   end subroutine build_curve

   !> Largest |g_interp - g_mid| at nine xi across the midpoint curve (gaps relative to the
   !> turning-point force), denser near the turning point where the gap changes fastest.
   function curve_mismatch(table, c1, c2, m1, m2, mid, m_mid) result(err)
      type(hysteresis_table), intent(in) :: table
      type(unloading_curve), intent(in) :: c1, c2, mid
      real(dp), intent(in) :: m1, m2, m_mid
      real(dp), parameter :: probe_xi(9) = [0.01_dp, 0.03_dp, 0.07_dp, 0.15_dp, 0.3_dp, 0.45_dp, &
         & 0.6_dp, 0.75_dp, 0.9_dp]
      real(dp) :: err, x, g1, s1, g2, s2, gm, sm, w
      integer :: i
      ! (the curves hold gaps relative to the turning-point force: so is the mismatch)
      w = (m_mid - m1)/(m2 - m1)
      err = 0.0_dp
      do i = 1, size(probe_xi)
         x = (m_mid - table%loading%cutoff)*probe_xi(i)
         call curve_eval(c1, x, g1, s1)
         call curve_eval(c2, x, g2, s2)
         call curve_eval(mid, x, gm, sm)
         err = max(err, abs((1.0_dp - w)*g1 + w*g2 - gm))
      end do
   end function curve_mismatch

   !> The force at the turning point delta_max = m from the loading table, floored at the
   !> cut-off's force (the scale of the stored gaps and of the tolerance).
   pure real(dp) function turning_force(table, m) result(f)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: m
      real(dp) :: k
      call table_eval(table%loading, m, f, k)
      f = max(f, table%loading%reference_force*table%rel_tol)
   end function turning_force

   !> Cubic Hermite gap and its xi-derivative at xi; 0 outside [0, last node].
   pure subroutine curve_eval(curve, xi, gap, slope)
      type(unloading_curve), intent(in) :: curve
      real(dp), intent(in) :: xi
      real(dp), intent(out) :: gap, slope
      real(dp) :: h, t, h00, h10, h01, h11, d00, d10, d01, d11
      integer :: i, n
      n = size(curve%xi)
      gap = 0.0_dp
      slope = 0.0_dp
      if (n < 2 .or. .not. xi > 0.0_dp .or. xi > curve%xi(n)) return
      i = find_node(curve%xi, xi)
      h = curve%xi(i + 1) - curve%xi(i)
      t = (xi - curve%xi(i))/h
      h00 = (1 + 2*t)*(1 - t)**2
      h10 = t*(1 - t)**2
      h01 = t*t*(3 - 2*t)
      h11 = t*t*(t - 1)
      gap = h00*curve%gap(i) + h10*h*curve%slope(i) + h01*curve%gap(i + 1) &
         & + h11*h*curve%slope(i + 1)
      d00 = 6*t*(t - 1)/h
      d10 = (1 - t)*(1 - 3*t)
      d01 = -d00
      d11 = t*(3*t - 2)
      slope = d00*curve%gap(i) + d10*curve%slope(i) + d01*curve%gap(i + 1) &
         & + d11*curve%slope(i + 1)
   end subroutine curve_eval

   !> i with x(i) <= v < x(i+1) (x increasing, x(1) <= v < x(n)), by bisection.
   pure integer function find_node(x, v) result(i)
      real(dp), intent(in) :: x(:), v
      integer :: lo, hi, mid
      lo = 1
      hi = size(x)
      ! branch-free halving (conditional moves): the history and the overlap of DEM
      ! contacts are unpredictable, and mispredicted branches dominated the evaluation
      do while (hi - lo > 1)
         mid = (lo + hi)/2
         lo = merge(mid, lo, x(mid) <= v)
         hi = merge(hi, mid, x(mid) <= v)
      end do
      i = lo
   end function find_node

   pure subroutine move_curve(from, to)
      type(unloading_curve), intent(inout) :: from
      type(unloading_curve), intent(out) :: to
      call move_alloc(from%xi, to%xi)
      call move_alloc(from%gap, to%gap)
      call move_alloc(from%slope, to%slope)
   end subroutine move_curve

end module egw_hysteresis
