!> Contact parameters of a rough-sphere pair (doc/theory.md §1) and their validation.
!> Units are any consistent set; the defaults are the dimensionless E-GW case.
module egw_params
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, egw_invalid_parameter, fatal_error, format_real
   use egw_text, only: int_text, int_text_len
   implicit none
   private

   integer, parameter, public :: model_hertz = 0  !< smooth spheres, closed form
   integer, parameter, public :: model_gw = 1     !< classic GW (Greenwood-Tripp)
   integer, parameter, public :: model_egw = 2    !< extended elastic GW
   integer, parameter, public :: model_epgw = 3   !< extended elasto-plastic GW (ZMC asperities)

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
   end type contact_params

   public :: validate_params, model_name, mu_from_summits, psi_from_hardness, &
      & rough_flat_coefficient

contains

   !> Check every field, whatever the model (fields a model ignores must still be sane,
   !> so that switching model never turns garbage into physics). On failure the message
   !> names the parameter and its value.
   pure subroutine validate_params(params, error)
      type(contact_params), intent(in) :: params
      type(egw_error), allocatable, intent(out) :: error

      if (params%model < model_hertz .or. params%model > model_epgw) then
         call fatal_error(error, egw_invalid_parameter, "model = "//int_str(params%model) &
            & //": unknown model (0 Hertz, 1 GW, 2 E-GW, 3 EP-GW)")
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
   end subroutine validate_params

   !> Greenwood-Tripp mu = (8/3) eta sigma sqrt(2 R beta) from the summit density eta
   !> (per unit area), summit radius beta, roughness sigma and equivalent radius R.
   elemental function mu_from_summits(summit_density, summit_radius, sigma, radius) result(mu)
      real(dp), intent(in) :: summit_density, summit_radius, sigma, radius
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
      type(contact_params), intent(in) :: params
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
      case default;       name = "unknown"
      end select
   end function model_label

   !> Name of a model, for messages and file headers.
   pure function model_name(model) result(name)
      integer, intent(in) :: model
      ! not a deferred length: gfortran 12 keeps those in a static variable (egw_text)
      character(len=len_trim(model_label(model))) :: name
      name = model_label(model)
   end function model_name

   elemental logical function positive_finite(x)
      real(dp), intent(in) :: x
      positive_finite = ieee_is_finite(x) .and. x > 0.0_dp
   end function positive_finite

   pure subroutine bad(error, name, value, reason)
      type(egw_error), allocatable, intent(out) :: error
      character(len=*), intent(in) :: name, reason
      real(dp), intent(in) :: value
      call fatal_error(error, egw_invalid_parameter, name//" = "//format_real(value)//": "//reason)
   end subroutine bad

   pure function int_str(i) result(str)
      integer, intent(in) :: i
      character(len=int_text_len(i)) :: str  ! not deferred, not a WRITE: see egw_text
      str = int_text(i)
   end function int_str

end module egw_params
