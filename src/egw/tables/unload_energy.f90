!> The elastic energy a hysteresis-table contact returns if it separates now (the
!> integral of its unloading curve, clipped at 0 as the evaluation is), in O(1) from
!> per-table samples of the clipped dips (energy_prepare, called by
!> hysteresis_prepare), and the walk over the whole span that those samples are
!> tested against.
module egw_unload_energy
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_is_finite
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_invalid_argument, egw_out_of_range, fatal_error, &
      & format_real
   use egw_table, only: table_eval, gl_x, gl_w, table_energy, table_interval, beyond_status
   use egw_hysteresis_data, only: hysteresis_table, unload_curve, nan_error, gap_cubic, &
      & turning_point, gap_combination, unload_tail_ratio, locate, map_s, map_x, s_knee, &
      & s_zero, map_lengths, log_unload, edge_breaks, edge_s, edge_xi, edge_segment, &
      & stencil_sum, unload_floor, stores_ratio
   implicit none
   private

   public :: hysteresis_energy, hysteresis_energy_walk, energy_prepare, log_energy_prepare

   !> Turning points sampled per delta_max interval for the energy's clipped dips
   !> (energy_prepare): dip_samples + 1 evenly spaced, each gap bisected (to a width of
   !> 1/dip_samples_max of the interval) until linear interpolation meets the walk at its
   !> midpoint to dip_tol of the span's (unclipped) integral.
   integer, parameter :: dip_samples = 16, dip_samples_max = 1024
   real(dp), parameter :: dip_tol = 1.0e-9_dp

   !> One delta_max interval's dip samples (energy_prepare), numbered from its first.
   type :: interval_dips
      real(dp), allocatable :: store(:, :)   !< (u, q, low) per sample
      integer :: used = 0   !< samples in store
      integer :: base(dip_samples) = 0   !< u0's sample of each part (dip_base less the offset)
      real(dp) :: band = 0.0_dp   !< dip_band
   end type interval_dips

contains

   !> Elastic energy [force*length] that a contact at overlap delta returns if it
   !> separates now: the integral of its unloading curve from the loading cut-off to delta,
   !> int_{delta_c}^{delta} P_unload(x; m) dx with m = max(delta_max_state, delta), of the
   !> force hysteresis_eval returns (clipped at 0 where the interpolated curve dips below
   !> it within rel_tol, and 0 below the cut-off; those dips from samples per delta_max
   !> interval made by hysteresis_prepare, so that the cost is of the order of
   !> hysteresis_eval's). On the loading curve (delta = m) it is
   !> the part of the loading work that comes back; what the turning point leaves behind
   !> is dissipated. Reversible tables: the loading table's energy. The state is not
   !> changed. Statuses as hysteresis_eval (egw_hysteresis_energy's): NaN delta or state
   !> egw_invalid_argument (energy 0); max(delta, state) above delta_max egw_out_of_range
   !> (value written); an energy beyond the doubles egw_invalid_argument. The optional
   !> error says the same with a message naming the argument.
   pure subroutine hysteresis_energy(table, delta, delta_max_state, energy, stat, error)
      type(hysteresis_table), intent(in) :: table   !< built or read
      real(dp), intent(in) :: delta             !< overlap [length]
      real(dp), intent(in) :: delta_max_state   !< the contact's largest overlap so far
      real(dp), intent(out) :: energy           !< [force*length], >= 0
      integer, intent(out) :: stat              !< 0 or an egw status
      !> allocated when stat is not 0, with a message naming the argument
      type(egw_error), allocatable, intent(out), optional :: error
      call energy_value(table, delta, delta_max_state, energy, stat, .false.)
      if (stat == egw_invalid_argument) then
         if (present(error)) call nan_error(delta, "delta_max_state", "-huge(1.0_dp)", error)
      else if (.not. ieee_is_finite(energy)) then
         stat = egw_invalid_argument
         if (present(error)) call fatal_error(error, stat, "delta = "//format_real(delta)// &
            & ", delta_max_state = "//format_real(delta_max_state)// &
            & ": the energy there exceeds the doubles")
      else if (stat /= 0 .and. present(error)) then
         call beyond_status(table%delta_max, "max(delta, delta_max_state)", &
            & max(delta, delta_max_state), [energy], error)
      end if
   end subroutine hysteresis_energy

   !> hysteresis_energy by one walk over the whole span for the dips the evaluation clips
   !> (its cost grows with the pieces of the span, ~100x hysteresis_eval's): the reference
   !> that hysteresis_energy's samples are tested against. Same arguments and statuses
   !> (no error message).
   pure subroutine hysteresis_energy_walk(table, delta, delta_max_state, energy, stat)
      type(hysteresis_table), intent(in) :: table   !< built or read
      real(dp), intent(in) :: delta             !< overlap [length]
      real(dp), intent(in) :: delta_max_state   !< the contact's largest overlap so far
      real(dp), intent(out) :: energy           !< [force*length], >= 0
      integer, intent(out) :: stat              !< 0 or an egw status
      call energy_value(table, delta, delta_max_state, energy, stat, .true.)
      if (stat /= egw_invalid_argument .and. .not. ieee_is_finite(energy)) &
         & stat = egw_invalid_argument
   end subroutine hysteresis_energy_walk

   !> hysteresis_energy's value and status (NaN input, above delta_max); walk (the
   !> reference, hysteresis_energy_walk): the clipped dips from one walk over the span.
   pure subroutine energy_value(table, delta, delta_max_state, energy, stat, walk)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: delta, delta_max_state
      real(dp), intent(out) :: energy
      integer, intent(out) :: stat
      logical, intent(in) :: walk
      type(unload_curve) :: cv
      real(dp) :: m, d_1, lo, ratio, dips, x_top
      stat = 0
      energy = 0.0_dp
      if (ieee_is_nan(delta) .or. ieee_is_nan(delta_max_state)) then
         stat = egw_invalid_argument
         return
      end if
      m = max(delta_max_state, delta)
      if (m > table%delta_max) stat = egw_out_of_range
      if (.not. delta > unload_floor(table)) return
      energy = table_energy(table%loading, delta)
      if (table%reversible .or. .not. m > table%elastic_limit) then
         if (.not. delta > table%loading%cutoff) energy = 0.0_dp   ! (force_ratio)
         return
      end if
      cv%m = m
      call turning_point(table, m, cv%first, cv%w, cv%inv_span, cv%f_m, cv%knee)
      if (table%log_ratio) then   ! (no dips; the walk: the reference)
         if (walk .or. .not. allocated(table%energy_coef)) then
            energy = log_energy(table, cv, delta)
         else if (m < table%delta_max .and. table%energy_walk(locate(table%m_lookup, &
            & table%m, m))) then
            energy = log_energy(table, cv, delta)
         else
            energy = log_energy_ratio(table, cv, delta)
         end if
         return
      end if
      ! below the span's end d_1 the force is ratio P_load (unload_branch), above it
      ! P_load - f_m g(s), clipped at 0: int g(s(x)) dx over (lo, delta) with s = (m -
      ! x)/(s_max L) is (1/(s_max L)) times the integral of g over s from s(delta) to
      ! s(lo) (gap_work; the two-piece map: piece by piece); the span starts at the
      ! cut-off if d_1 is below it (no force there)
      d_1 = curve_x(table, cv, 1.0_dp)
      ratio = unload_tail_ratio(table, d_1, cv%f_m, stencil_sum(table%n_w, cv%w, &
         & table%gap(size(table%s), cv%first:cv%first + table%n_w - 1)))
      if (.not. delta > d_1) then
         energy = ratio*energy
         return
      end if
      lo = max(d_1, unload_floor(table))
      if (walk) then
         call span_dips(table, cv, lo, delta, dips, x_top)
      else
         dips = dips_below(table, cv, lo, delta)
      end if
      if (stores_ratio(table)) then
         ! (the force is f_m u: its integral, on the loading tail's below d_1 scaled by
         ! ratio; Hertz + cap: ratio 0, apart below the residual overlap)
         energy = ratio*table_energy(table%loading, lo) + gap_term(table, cv, lo, delta) - &
            & dips
      else
         energy = ratio*table_energy(table%loading, lo) + (energy - &
            & table_energy(table%loading, lo)) - gap_term(table, cv, lo, delta) - dips
      end if
      energy = max(energy, 0.0_dp)
   end subroutine energy_value

   !> int_lo^delta min(F, 0) dx (F the span force of curve cv, lo its span's start): the
   !> dips that the evaluation clips, from the table's samples (energy_prepare) in O(1):
   !> over the whole span, interpolated linearly in m between the samples of m's interval
   !> (at an overlap in the stretch from lo that both samples around m clipped, dip_low:
   !> the integral of F from lo, all of it clipped), less the dips between delta and the
   !> band (dip_band: a short walk, only for an overlap in or below it; from lo instead
   !> where that is shorter). Above the band the span force at delta is looked at: a dip
   !> there that no sample saw (between them) gets the walk from lo, as a turning point
   !> above the table's delta_max (no samples).
   pure real(dp) function dips_below(table, cv, lo, delta) result(total)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: lo, delta
      real(dp) :: u, x_band, f, slope, x_top, above
      integer :: i, j, n, k
      if (.not. allocated(table%dip) .or. cv%m > table%delta_max) then
         call span_dips(table, cv, lo, delta, total, x_top)
         return
      end if
      j = locate(table%m_lookup, table%m, cv%m)
      u = min(max((cv%m - table%m(j))/(table%m(j + 1) - table%m(j)), 0.0_dp), 1.0_dp)
      ! the samples' gap around u: its equal part, then bisection (few samples in a part)
      i = min(int(u*dip_samples), dip_samples - 1) + 1
      k = table%dip_base(i, j)
      n = table%dip_first(j + 1) - 1
      if (i < dip_samples) n = table%dip_base(i + 1, j)
      do while (n - k > 1)
         i = (k + n)/2
         if (table%dip_u(i) <= u) then
            k = i
         else
            n = i
         end if
      end do
      if (delta - lo <= 0.95_dp*min(table%dip_low(k), table%dip_low(k + 1))*(cv%m - lo)) then
         ! in the stretch from lo that every sample clipped: all of it clipped (F(delta)
         ! looked at: a positive force there was not seen by the samples)
         call span_eval(table, cv, delta, f, slope)
         if (.not. f > 0.0_dp) then
            total = span_integral(table, cv, lo, delta)
            return
         end if
      end if
      u = (u - table%dip_u(k))/(table%dip_u(k + 1) - table%dip_u(k))
      if (table%mapped) then   ! (dips in f_m tail_length units there)
         total = ((1.0_dp - u)*table%dip(k) + u*table%dip(k + 1))*cv%f_m*table%tail_length
      else
         total = ((1.0_dp - u)*table%dip(k) + u*table%dip(k + 1))*cv%f_m/cv%inv_span
      end if
      x_band = curve_x(table, cv, min(table%dip_band(j), 1.0_dp))
      if (delta > x_band) then
         call span_eval(table, cv, delta, f, slope)
         if (.not. f > 0.0_dp) call span_dips(table, cv, lo, delta, total, x_top)
      else if (delta - lo < x_band - delta) then   ! the shorter walk: from lo
         call span_dips(table, cv, lo, delta, total, x_top)
      else
         call span_dips(table, cv, delta, x_band, above, x_top)
         total = min(total - above, 0.0_dp)
      end if
   end function dips_below

   !> The energy of a log-ratio table (P = P_load e^-h, never below 0: nothing clipped) at
   !> delta below the turning point of cv: below the span's end d_1 (s = 1) the loading
   !> table's energy times e^-h(1), above it that at d_1 plus the force's integral from d_1,
   !> by 8-point Gauss-Legendre on each smooth piece (between the loading table's nodes
   !> and the s nodes): O(pieces between d_1 and delta).
   pure real(dp) function log_energy(table, cv, delta) result(energy)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: delta
      real(dp) :: length, xi_b(3), d_1, ratio, lo, x_a, x_b, s_a, ds, next, f, k, part
      integer :: i, q, it, n_s
      n_s = size(table%s)
      length = 1.0_dp/cv%inv_span
      call edge_breaks(length, table%params%sigma, xi_b)
      d_1 = cv%m - xi_b(3)
      ratio = exp(-stencil_sum(table%n_w, cv%w, table%gap(n_s, cv%first:cv%first + &
         & table%n_w - 1)))
      if (.not. delta > d_1) then
         energy = ratio*table_energy(table%loading, delta)
         return
      end if
      lo = max(d_1, table%loading%cutoff)
      energy = ratio*table_energy(table%loading, lo)
      x_a = lo
      do it = 1, 4*(size(table%loading%delta) + n_s) + 8
         if (.not. x_a < delta) exit
         x_b = delta
         if (x_a < table%loading%delta_max) then
            i = table_interval(table%loading, x_a)
            x_b = min(x_b, table%loading%delta(i + 1))
         end if
         ! the next s node below s(x_a) (s falls as x grows)
         call edge_s(xi_b, cv%m - x_a, s_a, ds)
         i = locate(table%s_lookup, table%s, min(s_a, 1.0_dp))
         call edge_xi(xi_b, table%s(i), next)
         next = cv%m - next
         if (.not. next > x_a .and. i > 1) then
            call edge_xi(xi_b, table%s(i - 1), next)
            next = cv%m - next
         end if
         if (next > x_a) x_b = min(x_b, next)
         if (.not. x_b > x_a) exit   ! round-off at a break
         part = 0.0_dp
         do q = 1, size(gl_x)
            call log_unload(table, cv%first, cv%w, length, cv%m, x_a + (x_b - x_a)*gl_x(q), &
               & f, k)
            part = part + gl_w(q)*f
         end do
         energy = energy + part*(x_b - x_a)
         x_a = x_b
      end do
   end function log_energy

   !> The energy of a log-ratio table at delta below the turning point of cv in O(1):
   !> E_load(delta) e^-eta with eta = ln(E_load/E) interpolated as h is (the stencil's
   !> weights on energy_coef's cubics at s of the edge map of the interpolated L); below
   !> the span's end (s >= 1) E_load(delta) e^-h(1), as log_energy. eta's error is a
   !> relative error of the energy, as h's is of the force (doc/theory.md section 8).
   pure real(dp) function log_energy_ratio(table, cv, delta) result(energy)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: delta
      real(dp) :: xi_b(3), s, ds, c(4), t, eta
      integer :: i, f
      f = cv%first
      call edge_breaks(1.0_dp/cv%inv_span, table%params%sigma, xi_b)
      call edge_s(xi_b, cv%m - delta, s, ds)
      if (s >= 1.0_dp) then
         eta = stencil_sum(table%n_w, cv%w, table%gap(size(table%s), f:f + table%n_w - 1))
      else
         i = locate(table%s_lookup, table%s, s)
         ! (the window's curves that are the stencil's: weight not 0)
         if (i + 1 >= minval(table%energy_cut(f:f + table%n_w - 1), &
            & mask=cv%w(1:table%n_w) /= 0.0_dp)) then
            ! the stencil's curves reach the cut-off by this interval's end: eta has a layer
            ! there (E/E_load runs from e^-h at the cut-off to its value within a few
            ! 1/(d ln P_load/d delta)): the short walk from the cut-off
            energy = log_energy(table, cv, delta)
            return
         end if
         if (table%n_w == 4) then
            c = cv%w(1)*table%energy_coef(:, f, i) + cv%w(2)*table%energy_coef(:, f + 1, i) + &
               & cv%w(3)*table%energy_coef(:, f + 2, i) + cv%w(4)*table%energy_coef(:, f + 3, i)
         else
            associate (ec => table%energy_coef(:, f:f + 5, i))
               c = ((cv%w(1)*ec(:, 1) + cv%w(2)*ec(:, 2)) + (cv%w(3)*ec(:, 3) + &
                  & cv%w(4)*ec(:, 4))) + (cv%w(5)*ec(:, 5) + cv%w(6)*ec(:, 6))
            end associate
         end if
         t = (s - table%s(i))*table%inv_ds(i)
         eta = (c(1) + t*c(2)) + t*t*(c(3) + t*c(4))
      end if
      energy = table_energy(table%loading, delta)*exp(-eta)
   end function log_energy_ratio

   !> energy_coef of a log-ratio table: on each curve (its own force, from the loading
   !> table's cut-off or the span's end s = 1, whichever is higher) the energy E at every s
   !> node by a walk up the curve (curve_energies), eta = ln(E_load/E) there and its exact
   !> slope d eta/d xi = P/E - P_load/E_load (xi = m - delta), joined by Hermite cubics on
   !> the s intervals. Where a node lies at or below the cut-off (both energies 0) eta is
   !> continued by h and its slope (the limit of E/E_load at the cut-off is P/P_load =
   !> e^-h), and energy_cut marks the curve's first such node: log_energy_ratio walks
   !> from the cut-off on the s intervals that reach it (eta's layer there). Then
   !> energy_walk: three turning points of each delta_max interval (a quarter, a half and
   !> three quarters in), walked, at their own s nodes and the nodes' midpoints; an
   !> interval where log_energy_ratio misses one by more than rel_tol/2 of max(E, 1e-3
   !> E_m) (the force's local tolerance) takes the walk (turning points near the
   !> cut-off, where ln P_load bends hard). Cost: four walks per curve (8-point
   !> Gauss-Legendre, two panels per piece).
   pure subroutine log_energy_prepare(table)
      !> a log-ratio table prepared but for this (hysteresis_prepare): energy_coef,
      !> energy_walk and energy_cut set
      type(hysteresis_table), intent(inout) :: table
      type(unload_curve) :: cv
      real(dp) :: xi_b(3), d(3), length, x_i, xi, e_l, p_l, k_l, p_u, h, d0, d1, e_m
      real(dp), allocatable :: eta(:), deta(:), x(:), e(:)
      integer :: i, j, k, l, n_s, n_m
      n_s = size(table%s)
      n_m = size(table%m)
      if (allocated(table%energy_coef)) deallocate (table%energy_coef)
      if (allocated(table%energy_walk)) deallocate (table%energy_walk)
      if (allocated(table%energy_cut)) deallocate (table%energy_cut)
      allocate (table%energy_coef(4, n_m, n_s - 1), eta(n_s), deta(n_s), x(2*n_s - 1), &
         & e(2*n_s - 1), table%energy_walk(n_m - 1), table%energy_cut(n_m))
      table%energy_walk = .false.
      table%energy_cut = n_s + 1
      do j = 1, n_m
         cv%m = table%m(j)
         call turning_point(table, cv%m, cv%first, cv%w, cv%inv_span, cv%f_m, cv%knee)
         length = 1.0_dp/cv%inv_span
         call edge_breaks(length, table%params%sigma, xi_b)
         d = [2*xi_b(1), 4*(xi_b(2) - xi_b(1)), 4*(xi_b(3) - xi_b(2))]
         do i = 1, n_s
            call edge_xi(xi_b, table%s(n_s + 1 - i), xi)
            x(i) = cv%m - xi
         end do
         x(n_s) = cv%m
         call curve_energies(table, cv, xi_b, x(1:n_s), e(1:n_s))
         do i = 1, n_s
            x_i = x(n_s + 1 - i)
            e_l = table_energy(table%loading, x_i)
            if (x_i > table%loading%cutoff .and. e(n_s + 1 - i) > 0.0_dp .and. &
               & e_l > 0.0_dp) then
               call table_eval(table%loading, x_i, p_l, k_l)
               call log_unload(table, cv%first, cv%w, length, cv%m, x_i, p_u, k_l)
               eta(i) = log(e_l/e(n_s + 1 - i))
               deta(i) = p_u/e(n_s + 1 - i) - p_l/e_l
            else
               eta(i) = table%gap(i, j)
               deta(i) = table%slope(i, j)
               table%energy_cut(j) = min(table%energy_cut(j), i)
            end if
         end do
         do i = 1, n_s - 1
            k = edge_segment(table%s(i), table%s(i + 1))
            h = table%s(i + 1) - table%s(i)
            d0 = h*d(k)*deta(i)
            d1 = h*d(k)*deta(i + 1)
            table%energy_coef(:, j, i) = [eta(i), d0, 3*(eta(i + 1) - eta(i)) - 2*d0 - d1, &
               & 2*(eta(i) - eta(i + 1)) + d0 + d1]
         end do
      end do
      do l = 1, 3*(n_m - 1)
         j = (l - 1)/3 + 1
         if (table%energy_walk(j)) cycle
         cv%m = table%m(j) + 0.25_dp*(mod(l - 1, 3) + 1)*(table%m(j + 1) - table%m(j))
         if (.not. cv%m > table%elastic_limit) cycle
         call turning_point(table, cv%m, cv%first, cv%w, cv%inv_span, cv%f_m, cv%knee)
         call edge_breaks(1.0_dp/cv%inv_span, table%params%sigma, xi_b)
         do i = 1, 2*n_s - 1   ! nodes and midpoints, s falling
            k = n_s - i/2
            if (mod(i, 2) == 1) then
               call edge_xi(xi_b, table%s(k), xi)
            else
               call edge_xi(xi_b, 0.5_dp*(table%s(k) + table%s(k + 1)), xi)
            end if
            x(i) = cv%m - xi
         end do
         x(2*n_s - 1) = cv%m
         call curve_energies(table, cv, xi_b, x, e)
         e_m = e(2*n_s - 1)
         do i = 1, 2*n_s - 1
            if (.not. x(i) > table%loading%cutoff) cycle
            if (abs(log_energy_ratio(table, cv, x(i)) - e(i)) > 0.5_dp*table%rel_tol* &
               & max(e(i), 1.0e-3_dp*e_m)) table%energy_walk(j) = .true.
         end do
      end do
   end subroutine log_energy_prepare

   !> The energies e(i) at the overlaps x(i) (increasing, at most cv%m) of the log-ratio
   !> curve cv (edge map xi_b): one walk up the curve from its start (the cut-off or the
   !> span's end s = 1, whichever is higher), log_integral between consecutive overlaps.
   pure subroutine curve_energies(table, cv, xi_b, x, e)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: xi_b(3), x(:)
      real(dp), intent(out) :: e(:)
      real(dp) :: x_lo, total
      integer :: i
      x_lo = max(cv%m - xi_b(3), table%loading%cutoff)
      total = exp(-stencil_sum(table%n_w, cv%w, table%gap(size(table%s), &
         & cv%first:cv%first + table%n_w - 1)))* &
         & table_energy(table%loading, x_lo)
      do i = 1, size(x)
         if (x(i) > x_lo) then
            total = total + log_integral(table, cv, 1.0_dp/cv%inv_span, x_lo, x(i))
            x_lo = x(i)
         end if
         e(i) = total
         if (.not. x(i) > table%loading%cutoff) e(i) = 0.0_dp
      end do
   end subroutine curve_energies

   !> int_{x0}^{x1} of the force of log-ratio curve cv (unloading length length), x0 < x1
   !> within one of its s intervals: 8-point Gauss-Legendre on two panels of each piece
   !> between the loading table's nodes.
   pure real(dp) function log_integral(table, cv, length, x0, x1) result(total)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: length, x0, x1
      real(dp) :: x_a, x_b, f, k
      integer :: i, p, q, it
      total = 0.0_dp
      x_a = x0
      do it = 1, size(table%loading%delta) + 2
         if (.not. x_a < x1) exit
         x_b = x1
         if (x_a < table%loading%delta_max) then
            i = table_interval(table%loading, x_a)
            x_b = min(x_b, table%loading%delta(i + 1))
         end if
         if (.not. x_b > x_a) exit   ! round-off at a node
         do p = 0, 1
            do q = 1, size(gl_x)
               call log_unload(table, cv%first, cv%w, length, cv%m, x_a + 0.5_dp*(x_b - &
                  & x_a)*(p + gl_x(q)), f, k)
               total = total + 0.5_dp*gl_w(q)*f*(x_b - x_a)
            end do
         end do
         x_a = x_b
      end do
   end function log_integral

   !> int_0^s g(s', m) ds' of curve cv, s <= 1.
   pure real(dp) function gap_primitive(table, cv, s) result(total)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: s
      real(dp) :: t, h, x
      integer :: i, k
      x = min(s, 1.0_dp)
      i = locate(table%s_lookup, table%s, x)
      h = table%s(i + 1) - table%s(i)
      t = (x - table%s(i))/h
      total = 0.0_dp
      do k = 1, table%n_w
         associate (c => table%coef(:, cv%first + k - 1, i))
            total = total + cv%w(k)*(table%gap_integral(cv%first + k - 1, i) + h*t*(c(1) + &
               & t*(c(2)/2 + t*(c(3)/3 + t*c(4)/4))))
         end associate
      end do
   end function gap_primitive

   !> P_load(m) int_a^b g(s(x)) dx over overlaps a < b of curve cv's span: the gap's part
   !> of the span force's integral (the linear map: f_m/(s_max L) times the integral of g
   !> over s; the two-piece map: gap_work).
   pure real(dp) function gap_term(table, cv, a, b) result(total)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: a, b
      if (.not. table%mapped) then
         total = cv%f_m/cv%inv_span*(gap_primitive(table, cv, (cv%m - a)*cv%inv_span) - &
            & gap_primitive(table, cv, (cv%m - b)*cv%inv_span))
      else
         total = cv%f_m*(gap_work(table, cv, curve_s(table, cv, a)) - &
            & gap_work(table, cv, curve_s(table, cv, b)))
      end if
   end function gap_term

   !> int g(s(x)) dx from the turning point down to where s(x) = s <= 1 on a mapped
   !> table's curve: int_0^s g ds' times dx/ds, piece by piece of the two-piece map.
   pure real(dp) function gap_work(table, cv, s) result(total)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: s
      real(dp) :: dxds(3)
      dxds = map_lengths(table, cv%m, cv%knee)
      total = gap_primitive(table, cv, min(s, s_knee))*dxds(1)
      if (.not. s > s_knee) return
      total = total + (gap_primitive(table, cv, min(s, s_zero)) - gap_primitive(table, cv, &
         & s_knee))*dxds(2)
      if (.not. s > s_zero) return
      total = total + (gap_primitive(table, cv, s) - gap_primitive(table, cv, s_zero))*dxds(3)
   end function gap_work

   !> s (at most 1) at overlap x on the unloading curve cv (map_s).
   pure real(dp) function curve_s(table, cv, x) result(s)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: x
      real(dp) :: dsdx
      s = (cv%m - x)*cv%inv_span
      if (table%mapped) call map_s(table, cv%m, cv%knee, cv%inv_span, cv%m - x, s, dsdx)
      s = min(s, 1.0_dp)
   end function curve_s

   !> The overlap at s on the unloading curve cv (map_x).
   pure real(dp) function curve_x(table, cv, s) result(x)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: s
      real(dp) :: dsdx
      x = cv%m - s/cv%inv_span   ! (unless mapped: the linear map's arithmetic as before)
      if (.not. table%mapped) return
      call map_x(table, cv%m, cv%knee, cv%inv_span, s, x, dsdx)
      x = cv%m - x
   end function curve_x

   !> The unclipped span force P_load(x) - f_m g(s(x)) (tables of u, stores_ratio:
   !> f_m u(s(x)))
   !> of curve cv and its slope dF/dx (unload_branch before its clip).
   pure subroutine span_eval(table, cv, x, f, k)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: x
      real(dp), intent(out) :: f, k
      real(dp) :: s, c(4), g, dg, f_d, k_d, dsdx
      integer :: i
      s = (cv%m - x)*cv%inv_span
      dsdx = cv%inv_span
      if (table%mapped) call map_s(table, cv%m, cv%knee, cv%inv_span, cv%m - x, s, dsdx)
      s = min(s, 1.0_dp)
      i = locate(table%s_lookup, table%s, s)
      call gap_combination(table, cv%first, cv%w, i, c)
      call gap_cubic(c, (s - table%s(i))*table%inv_ds(i), table%inv_ds(i), g, dg)
      if (stores_ratio(table)) then   ! f_m u(s)
         f = cv%f_m*g
         k = -cv%f_m*dg*dsdx
         return
      end if
      call table_eval(table%loading, x, f_d, k_d)
      f = f_d - cv%f_m*g
      k = k_d + cv%f_m*dg*dsdx
   end subroutine span_eval

   !> span_eval's force only.
   pure real(dp) function span_force(table, cv, x) result(f)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: x
      real(dp) :: k
      call span_eval(table, cv, x, f, k)
   end function span_force

   !> int_a^b min(F, 0) over the span force F of curve cv (total), the part of the closed
   !> form that the evaluation clips, and an x_top above which no sample was <= 0 (-huge:
   !> none was). F is smooth between the breaks of the loading intervals and of the s
   !> intervals (x = m - s_i/(s_max L)); a piece whose cubic Hermite of its end values and
   !> slopes stays positive is skipped (F is that cubic where the loading interval is
   !> linear, and close to it on ln P intervals); others are sampled at 9 points: where
   !> none is positive the piece's integral is the closed form's (span_integral), and
   !> where some are not the negative runs between their neighbours (roots by
   !> regula falsi) are integrated by 8-point Gauss-Legendre (exact for the cubic F of a
   !> linear loading interval). Dips narrower than an eighth of a piece go unseen: they are
   !> of the order of the interpolation noise times their width cubed. Every piece of
   !> [a, b] is looked at: stopping above 10 rel_tol f_m (the unloading force increases
   !> with delta) missed dips of LAMMPS's EP-GW tables (test energy_epgw: the unloading
   !> energy drift 1.7e-4 instead of 1.6e-5). Cost: the pieces of [a, b] (the reference
   !> walk, and energy_prepare's samples; dips_below walks only short stretches).
   pure subroutine span_dips(table, cv, a, b, total, x_top, x_low)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: a, b
      real(dp), intent(out) :: total, x_top
      !> the end of the run from a on which every sample was <= 0 (a: none)
      real(dp), intent(out), optional :: x_low
      real(dp) :: x_a, x_b, next, s_a, xs(0:8), fs(0:8), f_a, k_a, f_b, k_b
      integer :: i, k, it, n_load
      logical :: low_open
      total = 0.0_dp
      x_top = -huge(1.0_dp)
      call span_eval(table, cv, a, f_a, k_a)
      low_open = .not. f_a > 0.0_dp
      if (present(x_low)) x_low = a
      n_load = size(table%loading%delta)
      x_a = a
      do it = 1, 4*(n_load + size(table%s)) + 8
         if (.not. x_a < b) exit
         ! the next break above x_a: a loading node or an s node (s falls as x grows)
         x_b = b
         if (x_a < table%loading%delta_max) then
            i = table_interval(table%loading, x_a)
            x_b = min(x_b, table%loading%delta(i + 1))
         end if
         s_a = curve_s(table, cv, x_a)
         i = locate(table%s_lookup, table%s, s_a)
         next = curve_x(table, cv, table%s(i))
         if (.not. next > x_a .and. i > 1) next = curve_x(table, cv, table%s(i - 1))
         if (next > x_a) x_b = min(x_b, next)
         if (.not. x_b > x_a) exit   ! round-off at a break
         call span_eval(table, cv, x_b, f_b, k_b)
         if (hermite_positive(x_b - x_a, f_a, f_b, k_a, k_b)) then
            low_open = .false.
         else
            xs = x_a + (x_b - x_a)*[(real(k, dp), k=0, 8)]/8
            fs(0) = f_a
            do k = 1, 7
               fs(k) = span_force(table, cv, xs(k))
            end do
            fs(8) = f_b
            if (all(.not. fs > 0.0_dp)) then
               ! a piece below 0 at every sample: min(F, 0) = F, the closed form
               total = total + span_integral(table, cv, x_a, x_b)
               x_top = x_b
               if (low_open .and. present(x_low)) x_low = x_b
            else if (any(.not. fs > 0.0_dp)) then
               if (low_open .and. present(x_low)) then
                  k = findloc(fs > 0.0_dp, .true., dim=1) - 1   ! the first positive sample
                  x_low = xs(k - 1)
               end if
               low_open = .false.
               do k = 0, 7
                  total = total + negative_part(table, cv, xs(k), xs(k + 1), fs(k), &
                     & fs(k + 1))
                  if (.not. (fs(k) > 0.0_dp .and. fs(k + 1) > 0.0_dp)) x_top = xs(k + 1)
               end do
            else
               low_open = .false.
            end if
         end if
         x_a = x_b
         f_a = f_b
         k_a = k_b
      end do
   end subroutine span_dips

   !> int_a^b F dx of the span force of curve cv, a < b in its span (s <= 1), from the
   !> primitives: the loading table's energy less f_m/(s_max L) times the gap's integral
   !> (tables of u, stores_ratio: f_m times the integral of u(s(x)), gap_term).
   pure real(dp) function span_integral(table, cv, a, b) result(total)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: a, b
      if (stores_ratio(table)) then   ! (f_m u: the curves' integral alone)
         total = gap_term(table, cv, a, b)
         return
      end if
      total = table_energy(table%loading, b) - table_energy(table%loading, a) - &
         & gap_term(table, cv, a, b)
   end function span_integral

   !> True when the cubic Hermite of (f0, k0) and (f1, k1) over a width h is positive
   !> on it: both ends positive and no interior minimum at or below 0.
   pure logical function hermite_positive(h, f0, f1, k0, k1) result(ok)
      real(dp), intent(in) :: h, f0, f1, k0, k1
      real(dp) :: c1, c2, c3, disc, t, r(2)
      integer :: j
      ok = f0 > 0.0_dp .and. f1 > 0.0_dp
      if (.not. ok) return
      ! p(t) = f0 + c1 t + c2 t^2 + c3 t^3 on [0, 1]; p'(t) = c1 + 2 c2 t + 3 c3 t^2
      c1 = h*k0
      c2 = 3*(f1 - f0) - h*(2*k0 + k1)
      c3 = 2*(f0 - f1) + h*(k0 + k1)
      if (abs(c3) > 0.0_dp) then
         disc = c2*c2 - 3*c3*c1
         if (disc < 0.0_dp) return   ! monotone
         r = [(-c2 - sqrt(disc))/(3*c3), (-c2 + sqrt(disc))/(3*c3)]
      else if (abs(c2) > 0.0_dp) then
         r = -c1/(2*c2)
      else
         return   ! linear
      end if
      do j = 1, 2
         t = r(j)
         if (t > 0.0_dp .and. t < 1.0_dp) ok = ok .and. f0 + t*(c1 + t*(c2 + t*c3)) > 0.0_dp
      end do
   end function hermite_positive

   !> int_x0^x1 min(F, 0) where F(x0) = f0, F(x1) = f1 and F changes sign at most once
   !> (the root to 1e-12 of the width: what remains is ~1e-24 of its slope times width^2).
   pure real(dp) function negative_part(table, cv, x0, x1, f0, f1) result(total)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: x0, x1, f0, f1
      real(dp) :: lo_x, hi_x, r, f_lo, f_hi, f_r
      integer :: j, side
      total = 0.0_dp
      if (f0 > 0.0_dp .and. f1 > 0.0_dp) return
      if (.not. f0 > 0.0_dp .and. .not. f1 > 0.0_dp) then
         total = min(gauss_integral(table, cv, x0, x1), 0.0_dp)
         return
      end if
      ! one end positive: the root by regula falsi (Illinois: a few evaluations, the
      ! bracket kept), then the negative side
      lo_x = x0
      hi_x = x1
      f_lo = f0
      f_hi = f1
      side = 0
      r = x0
      do j = 1, 60
         r = (lo_x*f_hi - hi_x*f_lo)/(f_hi - f_lo)
         if (.not. (r > lo_x .and. r < hi_x)) r = 0.5_dp*(lo_x + hi_x)
         if (.not. (r > lo_x .and. r < hi_x)) exit
         f_r = span_force(table, cv, r)
         if (abs(f_r) <= 1.0e-14_dp*max(abs(f0), abs(f1))) exit   ! at the root
         if ((f_r > 0.0_dp) .eqv. (f_lo > 0.0_dp)) then
            lo_x = r
            f_lo = f_r
            if (side == -1) f_hi = 0.5_dp*f_hi
            side = -1
         else
            hi_x = r
            f_hi = f_r
            if (side == 1) f_lo = 0.5_dp*f_lo
            side = 1
         end if
         if (hi_x - lo_x <= 1.0e-12_dp*(x1 - x0)) exit
      end do
      if (f0 > 0.0_dp) then
         total = min(gauss_integral(table, cv, r, x1), 0.0_dp)
      else
         total = min(gauss_integral(table, cv, x0, r), 0.0_dp)
      end if
   end function negative_part

   !> 8-point Gauss-Legendre integral of the span force of curve cv over [x0, x1].
   pure real(dp) function gauss_integral(table, cv, x0, x1) result(total)
      type(hysteresis_table), intent(in) :: table
      type(unload_curve), intent(in) :: cv
      real(dp), intent(in) :: x0, x1
      integer :: q
      total = 0.0_dp
      do q = 1, size(gl_x)
         total = total + gl_w(q)*span_force(table, cv, x0 + (x1 - x0)*gl_x(q))
      end do
      total = total*(x1 - x0)
   end function gauss_integral

   !> The dips' samples (dip, dip_u, dip_first, dip_band): at turning points of each
   !> delta_max interval, the walk over the whole span (span_dips), normalised by
   !> P_load(m)/(s_max L(m)) (the scale of the span's force and of its width in s), so
   !> that a sample is a number of order rel_tol; dip_samples + 1 evenly spaced, then each
   !> gap bisected until linear interpolation meets the walk at its midpoint to dip_tol of
   !> the span's (unclipped) integral in the same units, or the gap is 1/dip_samples_max
   !> of the interval (dips come and go with m: bumps of a few hundredths of an interval
   !> were seen, and the walk's own jumps where it first sees a dip). dip_band: the
   !> smallest s above which a sample clipped anything, less a margin of a twentieth
   !> (dips move with m between samples); dip_low: per sample, the fraction of the span
   !> from its start over which it clipped everything. Called by hysteresis_prepare
   !> (cost: a walk per
   !> sample, 33 per interval where the dips are smooth in m, more where they are not).
   subroutine energy_prepare(table)
      !> a gap table prepared but for this (hysteresis_prepare): its dip samples set
      type(hysteresis_table), intent(inout) :: table
      type(interval_dips), allocatable :: parts(:)
      integer :: j, n_m, used
      n_m = size(table%m)
      if (allocated(table%dip)) deallocate (table%dip)
      if (allocated(table%dip_u)) deallocate (table%dip_u)
      if (allocated(table%dip_first)) deallocate (table%dip_first)
      if (allocated(table%dip_band)) deallocate (table%dip_band)
      if (allocated(table%dip_low)) deallocate (table%dip_low)
      if (allocated(table%dip_base)) deallocate (table%dip_base)
      allocate (parts(n_m - 1))
      ! the intervals in parallel, each into its own samples, joined in order below: the
      ! same samples on any thread count (~1 % of README's rough + cap builds' CPU, serial
      ! before: doc/benchmarks.md "Stop 56: par22")
      !$omp parallel do schedule(dynamic) default(shared) private(j)
      do j = 1, n_m - 1
         call sample_interval(table, j, parts(j))
      end do
      !$omp end parallel do
      allocate (table%dip_first(n_m), table%dip_band(n_m - 1), &
         & table%dip_base(dip_samples, n_m - 1))
      used = 0
      do j = 1, n_m - 1
         table%dip_first(j) = used + 1
         table%dip_base(:, j) = used + parts(j)%base
         table%dip_band(j) = parts(j)%band
         used = used + parts(j)%used
      end do
      table%dip_first(n_m) = used + 1
      allocate (table%dip_u(used), table%dip(used), table%dip_low(used))
      used = 0
      do j = 1, n_m - 1
         associate (n => parts(j)%used)
            table%dip_u(used + 1:used + n) = parts(j)%store(1, 1:n)
            table%dip(used + 1:used + n) = parts(j)%store(2, 1:n)
            table%dip_low(used + 1:used + n) = parts(j)%store(3, 1:n)
            used = used + n
         end associate
      end do
   end subroutine energy_prepare

   !> energy_prepare's samples of delta_max interval j (numbered from its first), its
   !> dip_base (u0's sample of each of the dip_samples parts) and dip_band.
   pure subroutine sample_interval(table, j, part)
      type(hysteresis_table), intent(in) :: table   !< as energy_prepare's
      integer, intent(in) :: j   !< the interval
      type(interval_dips), intent(out) :: part   !< its samples
      real(dp) :: band, scale, u0, u1, q0, q1, top, low0, low1
      integer :: k
      allocate (part%store(3, 64))
      part%used = 0
      band = huge(1.0_dp)
      u0 = 0.0_dp
      call dip_sample(table, j, u0, q0, top, scale, low0)
      band = min(band, top)
      call dip_push(part%store, part%used, [u0, q0, low0])
      do k = 1, dip_samples
         u1 = real(k, dp)/dip_samples
         call dip_sample(table, j, u1, q1, top, scale, low1)
         band = min(band, top)
         part%base(k) = part%used   ! u0's sample
         call refine(table, j, u0, u1, q0, q1, low1, band, part%store, part%used)
         u0 = u1
         q0 = q1
      end do
      part%band = max(0.95_dp*band, 0.0_dp)
   end subroutine sample_interval

   !> Append the samples of (u0, u1] of delta_max interval j (q0, q1 the samples at its
   !> ends, low1 u1's dip_low; u0's already stored): its midpoint's, then each half
   !> refined where linear interpolation misses the midpoint by more than dip_tol of the
   !> span's integral.
   pure recursive subroutine refine(table, j, u0, u1, q0, q1, low1, band, store, used)
      type(hysteresis_table), intent(in) :: table
      integer, intent(in) :: j
      real(dp), intent(in) :: u0, u1, q0, q1, low1
      real(dp), intent(inout) :: band
      real(dp), allocatable, intent(inout) :: store(:, :)
      integer, intent(inout) :: used
      real(dp) :: u_mid, q_mid, top, scale, low_mid
      u_mid = 0.5_dp*(u0 + u1)
      call dip_sample(table, j, u_mid, q_mid, top, scale, low_mid)
      band = min(band, top)
      if (abs(q_mid - 0.5_dp*(q0 + q1)) <= dip_tol*scale .or. &
         & u1 - u0 <= 2.0_dp/dip_samples_max) then
         call dip_push(store, used, [u_mid, q_mid, low_mid])
         call dip_push(store, used, [u1, q1, low1])
      else
         call refine(table, j, u0, u_mid, q0, q_mid, low_mid, band, store, used)
         call refine(table, j, u_mid, u1, q_mid, q1, low1, band, store, used)
      end if
   end subroutine refine

   !> Append a sample (u, q, low) to store (grown by doubling).
   pure subroutine dip_push(store, used, sample)
      real(dp), allocatable, intent(inout) :: store(:, :)
      integer, intent(inout) :: used
      real(dp), intent(in) :: sample(3)
      real(dp), allocatable :: grown(:, :)
      if (used == size(store, 2)) then
         allocate (grown(3, 2*used + 16))
         grown(:, 1:used) = store(:, 1:used)
         call move_alloc(grown, store)
      end if
      used = used + 1
      store(:, used) = sample
   end subroutine dip_push

   !> One sample of energy_prepare at fraction u of delta_max interval j: the normalised
   !> dips q, the s above which none was clipped (top; huge where none was) and the span's
   !> unclipped integral in the same units (scale, > 0), and the fraction of the span from
   !> its start over which every sample was clipped (low).
   pure subroutine dip_sample(table, j, u, q, top, scale, low)
      type(hysteresis_table), intent(in) :: table
      integer, intent(in) :: j
      real(dp), intent(in) :: u
      real(dp), intent(out) :: q, top, scale
      real(dp), intent(out) :: low   !< (x_low - lo)/(m - lo) of span_dips
      type(unload_curve) :: cv
      real(dp) :: lo, total, x_top, x_low
      q = 0.0_dp
      top = huge(1.0_dp)
      scale = tiny(1.0_dp)
      low = 0.0_dp
      cv%m = table%m(j) + (table%m(j + 1) - table%m(j))*u
      if (u >= 1.0_dp) cv%m = table%m(j + 1)
      if (.not. cv%m > table%elastic_limit) return
      call turning_point(table, cv%m, cv%first, cv%w, cv%inv_span, cv%f_m, cv%knee)
      if (.not. cv%f_m > 0.0_dp) return
      lo = max(curve_x(table, cv, 1.0_dp), unload_floor(table))
      if (.not. lo < cv%m) return
      call span_dips(table, cv, lo, cv%m, total, x_top, x_low)
      q = total*cv%inv_span/cv%f_m
      ! (the two-piece map: in f_m tail_length, as its first piece vanishes at m = 0)
      if (table%mapped) q = total/(cv%f_m*table%tail_length)
      low = (x_low - lo)/(cv%m - lo)
      if (x_top > -huge(1.0_dp)) top = curve_s(table, cv, x_top)
      scale = max(abs(span_integral(table, cv, lo, cv%m))*cv%inv_span/cv%f_m, tiny(1.0_dp))
      ! (the two-piece map: in f_m tail_length, as its first piece vanishes at m = 0)
      if (table%mapped) scale = max(abs(span_integral(table, cv, lo, cv%m))/(cv%f_m* &
         & table%tail_length), tiny(1.0_dp))
   end subroutine dip_sample

end module egw_unload_energy
