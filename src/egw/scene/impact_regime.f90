!> Which physics an impact needs (issue 32; doc/restitution.md): the bulk's flow-pressure cap
!> once the impact speed exceeds the first-yield speed v_y, the roughness while the deepest
!> overlap is within a few sigma. Closed forms only (Hertz's deepest overlap), no solves.
module egw_impact_regime
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, fatal_error, format_real, egw_invalid_argument
   use egw_params, only: contact_params, validate_params
   implicit none
   private

   public :: impact_regime, classify_impact, first_yield_speed, first_yield_overlap, yield_speed

   !> Roughness matters for an impact whose deepest overlap is below this many sigma:
   !> beyond it EP-GW's e exceeds 0.998 for the steel beads of doc/restitution.md
   !> (psi = 1, mu = 4: e = 0.9978 at delta_m = 7 sigma, 0.9994 at 16 sigma, and the loss
   !> of the summit layer falls with delta_m/sigma for any psi, mu: its depth is a few sigma).
   real(dp), parameter, public :: rough_overlaps = 10.0_dp

   !> The answer of classify_impact.
   type :: impact_regime
      real(dp) :: yield_speed = 0.0_dp     !< v_y (0: no flow_pressure, never yields)
      real(dp) :: yield_overlap = 0.0_dp   !< delta_y (0: no flow_pressure)
      real(dp) :: max_overlap = 0.0_dp     !< Hertz's deepest overlap at the speed
      !> max_overlap/sigma (huge for a smooth sphere)
      real(dp) :: overlap_in_sigma = huge(1.0_dp)
      logical :: cap_matters = .false.       !< speed > v_y: the bulk yields
      logical :: roughness_matters = .false. !< max_overlap < rough_overlaps sigma
      character(len=:), allocatable :: reason
   end type impact_regime

contains

   !> First-yield overlap of a sphere R, E* with the flow pressure p_y: Hertz's peak
   !> pressure 2 E* a/(pi R) reaches p_y at delta_y = (pi p_y/(2 E*))**2 R; huge (never)
   !> for p_y = 0, as C's egw_first_yield (DBL_MAX). A closed form without checks: R, E* of
   !> valid parameters (validate_params); egw_first_yield and classify_impact check them.
   pure real(dp) function first_yield_overlap(params) result(delta_y)
      type(contact_params), intent(in) :: params   !< R, E* and flow_pressure of valid parameters
      if (.not. (params%flow_pressure > 0.0_dp)) then
         delta_y = huge(1.0_dp)
         return
      end if
      delta_y = (pi*params%flow_pressure/(2.0_dp*params%modulus))**2*params%radius
   end function first_yield_overlap

   !> First-yield speed of a head-on impact of effective mass m*: Hertz's deepest overlap
   !> reaches delta_y, v_y = sqrt((16/15) (pi/2)**5 p_y**5 R**3/(m* E***4)); huge (never)
   !> for p_y = 0, as C's egw_first_yield. A mass that is not finite and > 0, or one for
   !> which v_y is not a positive double, is refused with egw_invalid_argument naming the
   !> mass (v_y is then 0), as egw_first_yield and classify_impact refuse it.
   function first_yield_speed(params, mass, error) result(v_y)
      type(contact_params), intent(in) :: params   !< R, E* and flow_pressure of valid parameters
      real(dp), intent(in) :: mass   !< effective mass m* > 0
      !> egw_invalid_argument naming the mass refused
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: v_y
      v_y = 0.0_dp
      if (.not. (ieee_is_finite(mass) .and. mass > 0.0_dp)) then
         call fatal_error(error, egw_invalid_argument, "mass = "//format_real(mass) &
            & //": must be finite and > 0")
         return
      end if
      v_y = yield_speed(params, mass)
      if (.not. (ieee_is_finite(v_y) .and. v_y > 0.0_dp)) then
         call fatal_error(error, egw_invalid_argument, "mass = "//format_real(mass) &
            & //": with flow_pressure, radius and modulus the first-yield speed is not " &
            & //"a positive double")
         v_y = 0.0_dp
      end if
   end function first_yield_speed

   !> first_yield_speed's closed form, unchecked (mass finite and > 0: its callers check)
   pure real(dp) function yield_speed(params, mass) result(v_y)
      type(contact_params), intent(in) :: params   !< R, E* and flow_pressure of valid parameters
      real(dp), intent(in) :: mass   !< effective mass m*, finite and > 0 (not checked)
      if (.not. (params%flow_pressure > 0.0_dp)) then
         v_y = huge(1.0_dp)
         return
      end if
      v_y = sqrt(16.0_dp/15.0_dp*(pi/2.0_dp)**5*params%flow_pressure**5*params%radius**3 &
         & /(mass*params%modulus**4))
   end function yield_speed

   !> Classify a head-on impact at speed v of effective mass m*: the cap matters when
   !> flow_pressure > 0 and v > v_y; the roughness when sigma > 0 and Hertz's deepest
   !> overlap (15 m* v**2/(16 E* sqrt(R)))**(2/5) is below rough_overlaps sigma.
   pure subroutine classify_impact(params, mass, speed, regime, error)
      type(contact_params), intent(in) :: params   !< radius, modulus, sigma, flow_pressure
      real(dp), intent(in) :: mass                 !< effective mass m* > 0
      real(dp), intent(in) :: speed                !< impact speed v > 0
      type(impact_regime), intent(out) :: regime   !< which of cap and roughness matter, and why
      !> egw_invalid_argument naming the value refused
      type(egw_error), allocatable, intent(out) :: error
      character(len=:), allocatable :: cap, rough
      if (.not. (ieee_is_finite(mass) .and. mass > 0.0_dp)) then
         call fatal_error(error, egw_invalid_argument, "mass = "//format_real(mass) &
            & //": must be finite and > 0")
         return
      end if
      if (.not. (ieee_is_finite(speed) .and. speed > 0.0_dp)) then
         call fatal_error(error, egw_invalid_argument, "speed = "//format_real(speed) &
            & //": must be finite and > 0")
         return
      end if
      ! The whole validation (an Inf radius or modulus, p_y >= E* gave v_y = Inf or 0 and
      ! an answer; audit25), and closed forms that are positive doubles.
      call validate_params(params, error)
      if (allocated(error)) return
      regime%max_overlap = (15.0_dp*mass*speed**2/(16.0_dp*params%modulus &
         & *sqrt(params%radius)))**0.4_dp
      if (.not. (ieee_is_finite(regime%max_overlap) .and. regime%max_overlap > 0.0_dp)) then
         call fatal_error(error, egw_invalid_argument, "speed = "//format_real(speed) &
            & //", mass = "//format_real(mass)//": Hertz's deepest overlap (15 m* v**2/" &
            & //"(16 E* sqrt(R)))**(2/5) = "//format_real(regime%max_overlap) &
            & //" is not a positive double")
         regime%max_overlap = 0.0_dp
         return
      end if
      if (params%flow_pressure > 0.0_dp) then
         regime%yield_speed = yield_speed(params, mass)
         if (.not. (ieee_is_finite(regime%yield_speed) .and. regime%yield_speed > 0.0_dp)) then
            call fatal_error(error, egw_invalid_argument, "mass = "//format_real(mass) &
               & //": with flow_pressure, radius and modulus the first-yield speed is not " &
               & //"a positive double")
            regime%yield_speed = 0.0_dp
            regime%max_overlap = 0.0_dp
            return
         end if
         regime%yield_overlap = first_yield_overlap(params)
         regime%cap_matters = speed > regime%yield_speed
         cap = merge("above", "below", regime%cap_matters)//" the first-yield speed v_y = " &
            & //format_real(regime%yield_speed)//" (v/v_y = "// &
            & format_real(speed/regime%yield_speed)//"): the cap " &
            & //merge("matters    ", "never acts ", regime%cap_matters)
      else
         cap = "no flow_pressure: no bulk yield"
      end if
      if (params%sigma > 0.0_dp) then
         regime%overlap_in_sigma = regime%max_overlap/params%sigma
         regime%roughness_matters = regime%overlap_in_sigma < rough_overlaps
         rough = "delta_max ~ "//format_real(regime%overlap_in_sigma)//" sigma: roughness " &
            & //merge("matters                    ", "negligible (>= 10 sigma)   ", &
            & regime%roughness_matters)
      else
         rough = "smooth (sigma = 0)"
      end if
      regime%reason = trim(cap)//"; "//trim(rough)
   end subroutine classify_impact

end module egw_impact_regime
