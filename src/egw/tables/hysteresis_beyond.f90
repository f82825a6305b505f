!> Hysteresis tables beyond their delta_max: the fully capped continuation of a Hertz +
!> cap table whose delta_max reaches cap_full_reach delta_y (doc/theory.md section 12,
!> "Beyond a table"), and of a rough + cap table there, the same law matched to its top
!> up to the reach where its measured error is within the table's tolerance ("Beyond a
!> rough + cap table"), for the stateless evaluation, the state's piece and the energy;
!> egw_hysteresis serves every evaluation through it above delta_max.
module egw_hysteresis_beyond
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_is_finite
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, egw_invalid_argument, fatal_error, format_real
   use egw_params, only: model_gw
   use egw_cap_sphere, only: cap_units
   use egw_hysteresis_data, only: hysteresis_table, hysteresis_state_size, turning_point, &
      & gap_combination, locate, quiet_nan, map_s, unload_floor, max_stencil
   use egw_hysteresis_piece, only: piece_force, make_piece, unload_branch
   use egw_table, only: table_eval
   use egw_unload_energy, only: curve_energy => hysteresis_energy
   implicit none
   private

   public :: cap_continues, cap_continue, continue_state, hysteresis_energy, rough_reach

   !> The turning point, in first-yield overlaps delta_y, from which a Hertz + cap contact is
   !> fully capped (doc/theory.md section 12, trap iv: its elastic edge ring below 1e-7 a
   !> from 32 delta_y): a Hertz + cap table whose delta_max reaches it continues beyond it
   !> by the fully capped continuation (cap_continues; LAMMPS's CAP_FULL_MIN, the same).
   real(dp), parameter, public :: cap_full_reach = 35.0_dp

   !> k = 8/pi^2 of the fully capped contact: delta/delta_y = alpha^2/2 + k alpha
   !> (cap_continue, cap_ratio).
   real(dp), parameter :: capped_k = 8.0_dp/pi**2

   !> The rough + cap continuation's measured error (doc/theory.md section 12, "Beyond a
   !> rough + cap table"), relative to the force at the turning point, is within
   !> C (sigma/delta_y)**0.75 ln(m/X) for histories m from X (the table's delta_max) to
   !> rough_limit X, sigma/delta_y in [rough_sigma_min, 1], C = rough_error_gw for GW,
   !> rough_error_egw for E-GW and EP-GW: envelopes, 1.21x and 1.41x above the largest
   !> error/ln(m/X) measured against rough + cap solves at 1.02 to 5 X, X = 35 delta_y
   !> (tools/bench/beyond31_rough_continuation.f90; doc/benchmarks.md "Stop 65: beyond31").
   real(dp), parameter :: rough_error_gw = 0.05_dp, rough_error_egw = 0.02_dp
   real(dp), parameter :: rough_error_power = 0.75_dp
   real(dp), parameter :: rough_sigma_min = 0.01_dp
   !> The farthest measured: rough + cap tables never continue past 5 X.
   real(dp), parameter :: rough_limit = 5.0_dp

contains

   !> Whether table continues beyond its delta_max to the history (or overlap) x: a Hertz +
   !> cap table (force_ratio curves of the cap solver) whose last turning point is fully
   !> capped, delta_max >= cap_full_reach delta_y, at any x (the fully capped continuation,
   !> exact in the cap model); a rough + cap table up to its rough_reach. (Others, and
   !> farther: egw_out_of_range there.)
   pure logical function cap_continues(table, x)
      type(hysteresis_table), intent(in) :: table   !< built or read
      real(dp), intent(in) :: x   !< the history, or the overlap loading past it [length]
      if (.not. table%capped) then
         cap_continues = x <= rough_reach(table)
         return
      end if
      cap_continues = .not. table%reversible
      ! (a hair below: a table built to 35 delta_y in units where delta_y rounds above 1
      ! continues, as LAMMPS's test of its x_max >= 35 says)
      ! (delta_yield: hysteresis_prepare's first_yield of the table's parameters)
      if (cap_continues) cap_continues = table%delta_yield > 0.0_dp .and. &
         & table%delta_max >= (cap_full_reach - 1.0e-9_dp)*table%delta_yield
   end function cap_continues

   !> The largest history [length] to which a rough + cap table (sigma > 0 with the
   !> flow-pressure cap, gap curves) continues beyond its delta_max X: where X >=
   !> cap_full_reach delta_y (the contact fully capped but for its rough rim) and
   !> sigma/delta_y in [rough_sigma_min, 1] (measured), the m where the error bound
   !> C (sigma/delta_y)**rough_error_power ln(m/X) reaches the table's rel_tol, at most
   !> rough_limit X; else X (no continuation; Hertz + cap: X too).
   pure real(dp) function rough_reach(table) result(reach)
      type(hysteresis_table), intent(in) :: table   !< built or read
      real(dp) :: ratio, coeff
      reach = table%delta_max
      if (table%capped .or. table%reversible .or. table%log_ratio .or. &
         & table%force_ratio .or. .not. table%delta_yield > 0.0_dp .or. &
         & .not. table%params%sigma > 0.0_dp) return
      if (.not. table%delta_max >= (cap_full_reach - 1.0e-9_dp)*table%delta_yield) return
      ratio = table%params%sigma/table%delta_yield
      if (.not. (ratio >= rough_sigma_min .and. ratio <= 1.0_dp)) return
      coeff = rough_error_egw
      if (table%params%model == model_gw) coeff = rough_error_gw
      reach = table%delta_max*min(rough_limit, &
         & exp(table%rel_tol/(coeff*ratio**rough_error_power)))
   end function rough_reach

   !> The smooth fully capped law matched to a rough + cap table's top X (its loading
   !> force P_X and stiffness K_X there): P = c 2 alpha(delta + s)^2 P_u, alpha_top from
   !> the law's P/(dP/ddelta) = alpha (alpha + k) delta_y/2 = P_X/K_X, the shift s =
   !> delta(alpha_top) - X and the scale c = P_X/(2 alpha_top^2 P_u).
   pure subroutine rough_match(table, alpha_top, shift, scale)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(out) :: alpha_top, shift, scale
      real(dp), parameter :: k = capped_k
      real(dp) :: delta_y, a_y, force_y, f_x, k_x
      call cap_units(table%params%radius, table%params%modulus, &
         & table%params%flow_pressure, delta_y, a_y, force_y)
      call table_eval(table%loading, table%delta_max, f_x, k_x)
      alpha_top = 0.5_dp*(sqrt(k*k + 8*(f_x/k_x)/delta_y) - k)
      shift = delta_y*(0.5_dp*alpha_top**2 + k*alpha_top) - table%delta_max
      scale = f_x/(2*alpha_top**2*(0.75_dp*force_y))
   end subroutine rough_match

   !> The fully capped continuation of a Hertz + cap table beyond its delta_max X
   !> (doc/theory.md section 12, "Beyond a table"; cap_continues): with alpha = a/a_y,
   !> delta/delta_y = alpha^2/2 + k alpha (k = 8/pi^2) and P_u = E* sqrt(R) delta_y^1.5,
   !> loading (delta >= the history, which moves to delta) P = 2 alpha^2 P_u, dP/ddelta =
   !> 4 alpha/(alpha + k) P_u/delta_y; unloading and reloading below a history m > X the
   !> table's last curve scaled by r = alpha(m)/alpha(X): P = r^2 P_X(X - (m - delta)/r),
   !> dP/ddelta = r P_X' there (exact in the cap model: the capped disk's deformed shape,
   !> so its elastic unloading, is a_m times one function of rho/a_m). A rough + cap table
   !> (to its rough_reach): the same law matched to its top, c P(delta + s) (rough_match),
   !> and r = alpha(m + s)/alpha(X + s).
   pure subroutine cap_continue(table, delta, history, force, stiffness)
      type(hysteresis_table), intent(in) :: table   !< a table that continues there
      real(dp), intent(in) :: delta          !< the overlap [length]
      real(dp), intent(inout) :: history     !< the contact's largest overlap so far
      !> [force] and [force/length] at delta
      real(dp), intent(out) :: force, stiffness
      real(dp), parameter :: k = capped_k
      real(dp) :: delta_y, a_y, force_y, a, r, alpha_top, shift, scale
      call cap_units(table%params%radius, table%params%modulus, &
         & table%params%flow_pressure, delta_y, a_y, force_y)
      if (.not. delta < history .and. .not. table%capped) then
         ! (a rough + cap table: the law matched to its top, shifted and scaled)
         call rough_match(table, alpha_top, shift, scale)
         history = delta
         a = sqrt(k*k + 2*((delta + shift)/delta_y)) - k
         force = scale*(2*a*a*(0.75_dp*force_y))
         stiffness = scale*(4*a/(a + k)*(0.75_dp*force_y/delta_y))
         return
      end if
      if (.not. delta < history) then
         history = delta
         a = sqrt(k*k + 2*(delta/delta_y)) - k
         force = 2*a*a*(0.75_dp*force_y)
         stiffness = 4*a/(a + k)*(0.75_dp*force_y/delta_y)
         return
      end if
      r = cap_ratio(table, history)
      call last_curve(table, table%delta_max - (history - delta)/r, force, stiffness)
      force = r*r*force
      stiffness = r*stiffness
   end subroutine cap_continue

   !> r = alpha(m)/alpha(X) of cap_continue: the contact radius at the history m over the
   !> one at the table's delta_max X (fully capped: m/delta_y = alpha^2/2 + k alpha).
   pure real(dp) function cap_ratio(table, m) result(r)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: m   !< the history, above delta_max
      real(dp), parameter :: k = capped_k
      real(dp) :: delta_y, alpha_top, shift, scale
      delta_y = table%delta_yield
      if (.not. table%capped) then   ! (rough + cap: alpha(m + s)/alpha_top, rough_match)
         call rough_match(table, alpha_top, shift, scale)
         r = (sqrt(k*k + 2*((m + shift)/delta_y)) - k)/alpha_top
         return
      end if
      r = (sqrt(k*k + 2*(m/delta_y)) - k)/(sqrt(k*k + 2*(table%delta_max/delta_y)) - k)
   end function cap_ratio

   !> hysteresis_eval_state's step below a history m above the delta_max X of a capped
   !> table that continues (cap_continues): the piece of the last curve around x = X - (m -
   !> delta)/r (make_piece, r = cap_ratio), moved to the contact (x - x_lo = (delta - lo)/r,
   !> the force r^2 times the curve's: the cubic's coefficients times r^2, r, 1, 1/r), kept
   !> as the state's piece with a zero linear loading interval over the same overlaps (the
   !> piece's force needs none; egw.h's inline and this routine's top read it as any
   !> piece: the contact's next steps inside it read only the state). Where no piece (the
   !> clamp, an end, a ln P loading interval) cap_continue's values. The turning-point caches
   !> marked stale (state(4) = 0: they would be X's, not the history's).
   pure subroutine continue_state(table, delta, state, force, stiffness)
      type(hysteresis_table), intent(in) :: table   !< a table that continues there
      real(dp), intent(in) :: delta   !< the overlap [length], below the history state(1)
      !> the contact's state (its history above delta_max), given the piece
      real(dp), intent(inout) :: state(hysteresis_state_size)
      !> [force] and [force/length] at delta
      real(dp), intent(out) :: force, stiffness
      real(dp) :: r, x, x_top, w(max_stencil), inv_span, f_m, knee, s, dsdx, c(4), ends(2), &
         & seg(7)
      integer :: first, i
      logical :: found
      x_top = table%delta_max
      r = cap_ratio(table, state(1))
      x = x_top - (state(1) - delta)/r
      state(2) = state(1)
      state(4) = 0.0_dp
      state(11:12) = quiet_nan
      state(18:19) = quiet_nan
      found = .false.
      if (x > unload_floor(table)) then
         call last_curve_point(table, x, first, w, inv_span, f_m, knee, s, dsdx, i)
         seg = quiet_nan
         call make_piece(table, w, first, i, s, x_top, x, inv_span, knee, f_m, seg, ends, c, &
            & found)
         found = found .and. .not. seg(7) > 0.0_dp
      end if
      if (.not. found) then
         call cap_continue(table, delta, state(1), force, stiffness)
         return
      end if
      state(11) = state(1) - (x_top - ends(1))*r
      state(12) = state(1) - (x_top - ends(2))*r
      state(14:17) = [r*r*c(1), r*c(2), c(3), c(4)/r]
      state(18:19) = state(11:12)
      state(20:24) = 0.0_dp
      call piece_force(state(11), state(14:17), state(18:24), delta, force, stiffness)
   end subroutine continue_state

   !> The force and stiffness at delta on the unloading curve of the table's last turning
   !> point delta_max: hysteresis_eval's unloading branch (not log-ratio: a Hertz + cap
   !> table's), written out for cap_continue alone, so that hysteresis_eval's own stays
   !> inline on its hot path.
   pure subroutine last_curve(table, delta, force, stiffness)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: delta
      real(dp), intent(out) :: force, stiffness
      real(dp) :: w(max_stencil), inv_span, f_m, c(4), s, knee, dsdx, m
      integer :: first, i
      force = 0.0_dp
      stiffness = 0.0_dp
      m = table%delta_max
      if (.not. delta > unload_floor(table)) return
      call last_curve_point(table, delta, first, w, inv_span, f_m, knee, s, dsdx, i)
      call gap_combination(table, first, w, i, c)
      call unload_branch(table, c, i, s, m, f_m, inv_span, knee, dsdx, delta, force, &
         & stiffness)
   end subroutine last_curve

   !> Where overlap x lies on the unloading curve of the table's last turning point
   !> delta_max (continue_state, last_curve): its stencil, the curve's s and ds/dx, and the
   !> s interval i.
   pure subroutine last_curve_point(table, x, first, w, inv_span, f_m, knee, s, dsdx, i)
      type(hysteresis_table), intent(in) :: table
      real(dp), intent(in) :: x
      integer, intent(out) :: first, i
      real(dp), intent(out) :: w(max_stencil), inv_span, f_m, knee, s, dsdx
      real(dp) :: m
      m = table%delta_max
      call turning_point(table, m, first, w, inv_span, f_m, knee)
      s = (m - x)*inv_span
      dsdx = inv_span
      if (table%mapped) call map_s(table, m, knee, inv_span, m - x, s, dsdx)
      s = min(s, 1.0_dp)
      i = locate(table%s_lookup, table%s, s)
   end subroutine last_curve_point

   !> hysteresis_energy (egw_unload_energy's: the elastic energy a contact at delta returns
   !> if it separates now, turning point max(delta, delta_max_state)), continued beyond a
   !> table that continues there (cap_continues, cap_continue): the energy of the
   !> last curve at X - (m - delta)/r times r^3 (the force scales by r^2, the overlaps by
   !> r), stat 0. Statuses and error as egw_unload_energy's hysteresis_energy.
   pure subroutine hysteresis_energy(table, delta, delta_max_state, energy, stat, error)
      type(hysteresis_table), intent(in) :: table   !< built or read
      real(dp), intent(in) :: delta             !< overlap [length]
      real(dp), intent(in) :: delta_max_state   !< the contact's largest overlap so far
      real(dp), intent(out) :: energy           !< [force*length], >= 0
      integer, intent(out) :: stat              !< 0 or an egw status
      !> allocated when stat is not 0, with a message naming the argument
      type(egw_error), allocatable, intent(out), optional :: error
      real(dp) :: m, r
      m = delta_max_state
      if (delta > m) m = delta
      if (m > table%delta_max .and. .not. ieee_is_nan(delta)) then
         if (cap_continues(table, m)) then
            r = cap_ratio(table, m)
            call curve_energy(table, table%delta_max - (m - delta)/r, table%delta_max, &
               & energy, stat, error)
            energy = r**3*energy
            if (stat == 0 .and. .not. ieee_is_finite(energy)) then
               stat = egw_invalid_argument
               if (present(error)) call fatal_error(error, stat, "delta = "// &
                  & format_real(delta)//", delta_max_state = "// &
                  & format_real(delta_max_state)//": the energy there exceeds the doubles")
            end if
            return
         end if
      end if
      call curve_energy(table, delta, delta_max_state, energy, stat, error)
   end subroutine hysteresis_energy

end module egw_hysteresis_beyond
