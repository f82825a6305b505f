!> Contact parameters of a rough-sphere pair (doc/theory.md §1) and their validation.
!> Units are any consistent set; the defaults are the dimensionless E-GW case.
module egw_params
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, egw_invalid_parameter, egw_invalid_argument, fatal_error, &
      & format_real, format_real_len, int_str, bad => parameter_error
   implicit none
   private

   integer, parameter, public :: model_hertz = 0  !< smooth spheres, closed form
   integer, parameter, public :: model_gw = 1     !< classic GW (Greenwood-Tripp)
   integer, parameter, public :: model_egw = 2    !< extended elastic GW
   integer, parameter, public :: model_epgw = 3   !< extended elasto-plastic GW (ZMC asperities)
   !> a rough-flat law of the caller's (egw_flat_law: tabulated, Persson, BEM); its
   !> parameters are R, E* and sigma = the law's length. Only the solves and tables
   !> that take a law accept it (validate_params' allow_flat_law).
   integer, parameter, public :: model_flat_law = 4

   !> Parameters of one contact. Field order and meaning match the C struct egw_params.
   type, public :: contact_params
      integer :: model = model_egw
      real(dp) :: radius = 1.0_dp          !< equivalent radius R, 1/R = 1/R1 + 1/R2
      real(dp) :: modulus = 1.0_dp         !< effective modulus E*
      real(dp) :: sigma = 0.0_dp           !< std of summit heights (0 = smooth)
      real(dp) :: mu = 1.0_dp              !< Greenwood-Tripp mu = (8/3) eta sigma sqrt(2 R beta)
      real(dp) :: psi = 0.0_dp             !< plasticity index of the paper (0 = elastic)
      real(dp) :: hardness_coeff = 0.6_dp  !< ZMC K in (0, 1)
      real(dp) :: plastic_ratio = 54.0_dp  !< ZMC delta_p/delta_ep > 1
      !> bulk flow pressure p_y of the elastic-perfectly-plastic half-space (doc/theory.md
      !> section 12): the contact pressure is capped at p_y; 0 = no bulk yield. Every
      !> model (rough ones cap the total pressure: theory.md section 12).
      real(dp) :: flow_pressure = 0.0_dp
   end type contact_params

   public :: validate_params, model_name, mu_from_summits, psi_from_hardness, &
      & rough_flat_coefficient, check_scaled_overlap, range_str, product4, length_unit, &
      & pressure_unit, force_unit, stiffness_unit, refuse_flow_pressure, positive_finite, &
      & is_rough

   !> What the numerics represent (doc/parameters.md "Valid ranges"): every positive field
   !> a normal double (no subnormals: they carry fewer digits and their reciprocals
   !> overflow); for rough spheres (sigma > 0) the scales of the solver's variables
   !> (length sqrt(R sigma), pressure E sqrt(sigma/R), force E sqrt(R) sigma**1.5)
   !> normal doubles with scale_margin decades to spare for the scaled solution, and the
   !> dimensionless parameters in the ranges below, where the scaled law and its
   !> Jacobian stay normal doubles.
   real(dp), parameter, public :: scale_margin = 1.0e-30_dp
   !> Greenwood-Tripp mu: the rough-flat law's Jacobian grows like mu (mu/K for EP-GW)
   !> against the elastic part; a measured bound, not a derived one: EP-GW solves converge
   !> at mu = 1e20 and ran for minutes at 1e50 (E-GW and GW were fine to 1e300).
   real(dp), parameter, public :: mu_min = 1.0e-20_dp, mu_max = 1.0e20_dp
   !> Plasticity index: e = 1/psi**2 and q = rho_p e (the scaled yield and plastic onsets)
   !> and their 3/2 powers must be normal doubles.
   real(dp), parameter, public :: psi_min = 1.0e-50_dp, psi_max = 1.0e50_dp
   !> ZMC K: the law's plastic coefficient sqrt(e)/K, limited like mu (measured: K = 1e-20
   !> converges, 1e-50 no longer does, 1e-100 ran for minutes).
   real(dp), parameter, public :: hardness_coeff_min = 1.0e-20_dp
   real(dp), parameter, public :: plastic_ratio_max = 1.0e50_dp
   !> Scaled overlap delta/sigma: the Hertz edge layer of relative width (delta/sigma)**(-2/3)
   !> must hold many doubles (1e15: 1e-10 of the contact radius, 6 digits inside it).
   real(dp), parameter, public :: overlap_ratio_max = 1.0e15_dp

contains

   !> Check every field, whatever the model (fields a model ignores must still be sane,
   !> so that switching model never turns garbage into physics). On failure the message
   !> names the parameter and its value.
   pure subroutine validate_params(params, error, allow_flat_law)
      type(contact_params), intent(in) :: params   !< the parameters to check
      !> allocated, naming the field, when one is invalid
      type(egw_error), allocatable, intent(out) :: error
      !> model_flat_law is valid here (a solve or table that has the law; a table file)
      logical, intent(in), optional :: allow_flat_law
      logical :: flat_ok

      flat_ok = .false.
      if (present(allow_flat_law)) flat_ok = allow_flat_law
      if (params%model == model_flat_law .and. .not. flat_ok) then
         call fatal_error(error, egw_invalid_parameter, "model = 4 (flat law): a rough-" &
            & //"flat law is solved with its law (solve_contact_law, egw_solve_flat_law, " &
            & //"egw_table_build_flat_law), not from parameters alone")
         return
      end if
      if (params%model < model_hertz .or. params%model > model_flat_law) then
         call fatal_error(error, egw_invalid_parameter, "model = "//int_str(params%model) &
            & //": unknown model (0 Hertz, 1 GW, 2 E-GW, 3 EP-GW, 4 flat law)")
         return
      end if
      if (.not. positive_finite(params%radius)) then
         call bad(error, "radius", params%radius, "must be finite and > 0"); return
      end if
      if (.not. positive_finite(params%modulus)) then
         call bad(error, "modulus", params%modulus, "must be finite and > 0"); return
      end if
      if (.not. ieee_is_finite(params%sigma) .or. params%sigma < 0.0_dp) then
         call bad(error, "sigma", params%sigma, "must be finite and >= 0"); return
      end if
      if (params%sigma > 0.0_dp .and. .not. positive_finite(params%mu)) then
         call bad(error, "mu", params%mu, "must be finite and > 0 when sigma > 0"); return
      end if
      if (.not. ieee_is_finite(params%psi) .or. params%psi < 0.0_dp) then
         call bad(error, "psi", params%psi, "must be finite and >= 0"); return
      end if
      if (ieee_is_nan(params%hardness_coeff) .or. .not. (params%hardness_coeff > 0.0_dp &
         & .and. params%hardness_coeff < 1.0_dp)) then
         call bad(error, "hardness_coeff", params%hardness_coeff, "K must lie in (0, 1)"); return
      end if
      if (.not. ieee_is_finite(params%plastic_ratio) .or. .not. params%plastic_ratio > 1.0_dp) then
         call bad(error, "plastic_ratio", params%plastic_ratio, "must be finite and > 1"); return
      end if
      call check_flow_pressure(params, error)
      if (allocated(error)) return
      call check_ranges(params, error)
   end subroutine validate_params

   !> flow_pressure: 0 (no bulk yield) or a normal double below the modulus (the cap
   !> model is a small-strain one: p_y << E*); every model takes it.
   pure subroutine check_flow_pressure(params, error)
      type(contact_params), intent(in) :: params
      type(egw_error), allocatable, intent(out) :: error
      if (.not. ieee_is_finite(params%flow_pressure) .or. params%flow_pressure < 0.0_dp) then
         call bad(error, "flow_pressure", params%flow_pressure, "must be finite and >= 0 " &
            & //"(0 = no bulk yield)"); return
      end if
      if (params%flow_pressure == 0.0_dp) return
      if (params%flow_pressure < tiny(1.0_dp) .or. .not. params%flow_pressure &
         & < params%modulus) then
         call bad(error, "flow_pressure", params%flow_pressure, "must be 0 or lie in [" &
            & //format_real(tiny(1.0_dp))//", modulus = "//format_real(params%modulus) &
            & //") (a small-strain cap: p_y < E*)"); return
      end if
   end subroutine check_flow_pressure

   !> egw_invalid_parameter when params have the flow-pressure cap, for a door that does
   !> not serve it yet (what: e.g. "a force table"; doc/theory.md section 12).
   pure subroutine refuse_flow_pressure(params, what, error)
      type(contact_params), intent(in) :: params   !< the contact
      character(len=*), intent(in) :: what         !< the refused request, for the message
      !> allocated when params%flow_pressure /= 0
      type(egw_error), allocatable, intent(out) :: error
      if (params%flow_pressure == 0.0_dp) return
      call fatal_error(error, egw_invalid_parameter, "flow_pressure = " &
         & //format_real(params%flow_pressure)//": "//what//" with the flow-pressure " &
         & //"cap is not available yet (solves and egw_restitution are; flow_pressure = 0 " &
         & //"for a table without bulk yield)")
   end subroutine refuse_flow_pressure

   !> The ranges the numerics represent (see scale_margin above; doc/parameters.md).
   pure subroutine check_ranges(params, error)
      type(contact_params), intent(in) :: params
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: lr, le, ls, la
      if (params%radius < tiny(1.0_dp)) then
         call bad(error, "radius", params%radius, "must be a normal double >= " &
            & //format_real(tiny(1.0_dp))//" (subnormal)"); return
      end if
      if (params%modulus < tiny(1.0_dp)) then
         call bad(error, "modulus", params%modulus, "must be a normal double >= " &
            & //format_real(tiny(1.0_dp))//" (subnormal)"); return
      end if
      if (params%sigma > 0.0_dp .and. params%sigma < tiny(1.0_dp)) then
         call bad(error, "sigma", params%sigma, "must be 0 or a normal double >= " &
            & //format_real(tiny(1.0_dp))//" (subnormal)"); return
      end if
      if (params%sigma > 0.0_dp) then
         if (params%mu < mu_min .or. params%mu > mu_max) then
            call bad(error, "mu", params%mu, "must lie in "//range_str(mu_min, mu_max) &
               & //" (where the rough-flat law and its Jacobian stay normal doubles)"); return
         end if
         ! the scales of the solver's variables, in logarithms (no overflow on the way)
         lr = log(params%radius)
         le = log(params%modulus)
         ls = log(params%sigma)
         if (.not. (in_scale(0.5_dp*(lr + ls)) .and. in_scale(le + 0.5_dp*(ls - lr)) .and. &
            & in_scale(le + 0.5_dp*lr + 1.5_dp*ls) .and. in_scale(le + 0.5_dp*(lr + ls)))) then
            call bad(error, "sigma", params%sigma, "with radius = "//format_real(params%radius) &
               & //" and modulus = "//format_real(params%modulus)//": the scales sqrt(R sigma)" &
               & //", E sqrt(sigma/R), E sqrt(R) sigma**1.5 must lie in " &
               & //range_str(tiny(1.0_dp)/scale_margin, huge(1.0_dp)*scale_margin)); return
         end if
      end if
      if (params%flow_pressure > 0.0_dp) then
         ! the cap's scales (doc/theory.md section 12): a_y = pi R p_y/(2 E*), delta_y =
         ! a_y**2/R and P_y = (4/3) E* a_y**3/R, in logarithms; p_y/E* = 1e-300 passed
         ! the field's own check while delta_y underflowed to 0
         lr = log(params%radius)
         le = log(params%modulus)
         la = log(0.5_dp*pi) + lr + log(params%flow_pressure) - le
         if (.not. (in_scale(la) .and. in_scale(2.0_dp*la - lr) .and. &
            & in_scale(log(4.0_dp/3.0_dp) + le + 3.0_dp*la - lr))) then
            call bad(error, "flow_pressure", params%flow_pressure, "with radius = " &
               & //format_real(params%radius)//" and modulus = " &
               & //format_real(params%modulus)//": the cap's first-yield scales a_y = " &
               & //"pi R p_y/(2 E*), delta_y = a_y**2/R, P_y = (4/3) E* a_y**3/R must " &
               & //"lie in "//range_str(tiny(1.0_dp)/scale_margin, &
               & huge(1.0_dp)*scale_margin)); return
         end if
      end if
      if (params%psi > 0.0_dp .and. (params%psi < psi_min .or. params%psi > psi_max)) then
         call bad(error, "psi", params%psi, "must be 0 or lie in "//range_str(psi_min, psi_max) &
            & //" (1/psi**2 and rho_p/psi**2 normal doubles)"); return
      end if
      if (params%hardness_coeff < hardness_coeff_min) then
         call bad(error, "hardness_coeff", params%hardness_coeff, "K must lie in [" &
            & //format_real(hardness_coeff_min)//", 1)"); return
      end if
      if (params%plastic_ratio > plastic_ratio_max) then
         call bad(error, "plastic_ratio", params%plastic_ratio, "must lie in (1, " &
            & //format_real(plastic_ratio_max)//"]"); return
      end if
   end subroutine check_ranges

   !> ln(x) of a scale x that is a normal double with scale_margin to spare both ways.
   elemental logical function in_scale(log_x)
      real(dp), intent(in) :: log_x
      in_scale = log_x >= log(tiny(1.0_dp)/scale_margin) .and. log_x <= log(huge(1.0_dp)*scale_margin)
   end function in_scale

   !> The scaled overlap delta/sigma of a rough contact (sigma > 0) within what the solver
   !> resolves: |delta/sigma| <= overlap_ratio_max on the overlap side (any separation is
   !> fine: far apart the force is 0). name names the argument in the message.
   pure subroutine check_scaled_overlap(name, delta, sigma, error)
      character(len=*), intent(in) :: name   !< the argument's name in the message
      real(dp), intent(in) :: delta, sigma   !< overlap and sigma [length]
      !> egw_invalid_argument naming name, if out of range
      type(egw_error), allocatable, intent(out) :: error
      if (.not. sigma > 0.0_dp) return
      if (delta > overlap_ratio_max*sigma) call fatal_error(error, egw_invalid_argument, &
         & name//" = "//format_real(delta)//": must be <= "//format_real(overlap_ratio_max) &
         & //" sigma = "//format_real(overlap_ratio_max*sigma) &
         & //" (the solver's range of delta/sigma)")
   end subroutine check_scaled_overlap

   !> w x y z of positive doubles without intermediate overflow or underflow: the
   !> significands multiply in [1/16, 1), the exponents add, and scale() rounds once more
   !> (to a subnormal, 0 or +Inf only if the product itself is out of range).
   elemental real(dp) function product4(w, x, y, z) result(p)
      real(dp), intent(in) :: w, x, y, z   !< the four factors, > 0
      p = scale(fraction(w)*fraction(x)*fraction(y)*fraction(z), &
         & exponent(w) + exponent(x) + exponent(y) + exponent(z))
   end function product4

   !> The units of the rough solver's scaled variables (doc/theory.md section 5) for
   !> validated params with sigma > 0: length sqrt(R sigma), pressure E sqrt(sigma/R),
   !> force E sqrt(R) sigma**1.5, stiffness E sqrt(R sigma). The plain expression where its
   !> intermediates stay normal (bit for bit as before), else product4 (sigma**1.5 alone
   !> underflows at sigma = 1e-300 while the force unit E sqrt(R) sigma**1.5 need not).
   elemental real(dp) function length_unit(params) result(u)
      type(contact_params), intent(in) :: params   !< validated, sigma > 0
      u = sqrt(params%radius*params%sigma)
      if (.not. normal(u) .or. .not. normal(params%radius*params%sigma)) &
         & u = sqrt(params%radius)*sqrt(params%sigma)
   end function length_unit

   !> The scaled pressure unit E sqrt(sigma/R) (as length_unit).
   elemental real(dp) function pressure_unit(params) result(u)
      type(contact_params), intent(in) :: params   !< validated, sigma > 0
      u = params%modulus*sqrt(params%sigma/params%radius)
      if (.not. normal(u) .or. .not. normal(params%sigma/params%radius)) &
         & u = product4(params%modulus, sqrt(params%sigma), 1.0_dp/sqrt(params%radius), 1.0_dp)
   end function pressure_unit

   !> The scaled force unit E sqrt(R) sigma**1.5 (as length_unit).
   elemental real(dp) function force_unit(params) result(u)
      type(contact_params), intent(in) :: params   !< validated, sigma > 0
      u = params%modulus*sqrt(params%radius)*params%sigma**1.5_dp
      if (.not. normal(u) .or. .not. normal(params%sigma**1.5_dp) .or. &
         & .not. normal(params%modulus*sqrt(params%radius))) &
         & u = product4(params%modulus, sqrt(params%radius), params%sigma, sqrt(params%sigma))
   end function force_unit

   !> The scaled stiffness unit E sqrt(R sigma) (as length_unit).
   elemental real(dp) function stiffness_unit(params) result(u)
      type(contact_params), intent(in) :: params   !< validated, sigma > 0
      u = product4(params%modulus, sqrt(params%radius), sqrt(params%sigma), 1.0_dp)
   end function stiffness_unit

   elemental logical function normal(x)
      real(dp), intent(in) :: x
      normal = abs(x) >= tiny(1.0_dp) .and. abs(x) <= huge(1.0_dp)
   end function normal

   !> "[lo, hi]" for messages.
   pure function range_str(lo, hi) result(str)
      real(dp), intent(in) :: lo, hi   !< the range's ends
      ! a length from a specification function, not a deferred one (egw_text: threads)
      character(len=format_real_len(lo) + format_real_len(hi) + 4) :: str
      str = "["//format_real(lo)//", "//format_real(hi)//"]"
   end function range_str

   !> Greenwood-Tripp mu = (8/3) eta sigma sqrt(2 R beta) from the summit density eta
   !> (per unit area), summit radius beta, roughness sigma and equivalent radius R.
   elemental function mu_from_summits(summit_density, summit_radius, sigma, radius) result(mu)
      real(dp), intent(in) :: summit_density   !< summits per unit area eta [1/length^2]
      real(dp), intent(in) :: summit_radius   !< summit radius beta [length]
      real(dp), intent(in) :: sigma   !< summit height deviation [length]
      real(dp), intent(in) :: radius   !< equivalent sphere radius R [length]
      real(dp) :: mu
      mu = (8.0_dp/3.0_dp)*summit_density*sigma*sqrt(2.0_dp*radius*summit_radius)
   end function mu_from_summits

   !> Plasticity index of the paper, psi = sqrt(sigma/delta_ep) (eq. 47) with the ZMC
   !> yield-onset interference delta_ep = (3 pi K H/(4 E))**2 beta (eq. 36):
   !> psi = 4 E/(3 pi K H) sqrt(sigma/beta), i.e. 4/(3 pi K) times the GW index
   !> (E/H) sqrt(sigma/beta) (doc/theory.md §6 misprint 6). Preconditions (not checked):
   !> modulus, hardness, summit_radius > 0, 0 < K < 1, sigma >= 0.
   elemental function psi_from_hardness(modulus, hardness, hardness_coeff, sigma, &
      & summit_radius) result(psi)
      real(dp), intent(in) :: modulus        !< effective modulus E*
      real(dp), intent(in) :: hardness       !< hardness H of the softer surface
      real(dp), intent(in) :: hardness_coeff !< ZMC K (mean pressure K H at yield onset)
      real(dp), intent(in) :: sigma          !< std of summit heights
      real(dp), intent(in) :: summit_radius  !< summit radius beta
      real(dp) :: psi
      psi = 4.0_dp*modulus/(3.0_dp*pi*hardness_coeff*hardness)*sqrt(sigma/summit_radius)
   end function psi_from_hardness

   !> C = (4/3) E eta beta^(1/2) = mu E / (2 sigma sqrt(2R)) of eq. (9) (sigma > 0).
   elemental function rough_flat_coefficient(params) result(c)
      type(contact_params), intent(in) :: params   !< validated, sigma > 0
      real(dp) :: c
      c = params%mu*params%modulus/(2.0_dp*params%sigma*sqrt(2.0_dp*params%radius))
   end function rough_flat_coefficient

   pure function model_label(model) result(name)
      integer, intent(in) :: model
      character(len=8) :: name
      select case (model)
      case (model_hertz); name = "Hertz"
      case (model_gw);    name = "GW"
      case (model_egw);   name = "E-GW"
      case (model_epgw);  name = "EP-GW"
      case (model_flat_law); name = "flat law"
      case default;       name = "unknown"
      end select
   end function model_label

   !> Name of a model, for messages and file headers.
   pure function model_name(model) result(name)
      integer, intent(in) :: model   !< model_hertz, model_gw, model_egw or model_epgw
      ! not a deferred length: gfortran 12 keeps those in a static variable (egw_text)
      character(len=len_trim(model_label(model))) :: name
      name = model_label(model)
   end function model_name

   !> Whether x is finite and > 0 (a NaN is not).
   elemental logical function positive_finite(x)
      real(dp), intent(in) :: x   !< any double
      positive_finite = ieee_is_finite(x) .and. x > 0.0_dp
   end function positive_finite

   !> True for a rough contact: a GW-family model (GW, E-GW, EP-GW, a flat law) with
   !> sigma > 0; Hertz, or any model with sigma = 0, is a smooth sphere.
   pure logical function is_rough(params)
      type(contact_params), intent(in) :: params   !< the contact's parameters
      is_rough = params%model /= model_hertz .and. params%sigma > 0.0_dp
   end function is_rough

end module egw_params
