!> Single-asperity contact laws (Hertz, eq. 5; ZMC elasto-plastic, eqs. 36-43) and the
!> nominal pressure of a rough flat on a smooth rigid flat, p_G(d) (eqs. 8, 9, 44;
!> doc/theory.md §3), which is also the pressure-overclosure law an FE code wants.
module egw_asperity
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_is_finite
   ! The kind is imported as wp because the rough-flat law's derivative argument is dp.
   use egw_kinds, only: wp => dp, pi
   use egw_status, only: egw_error, egw_invalid_argument, egw_invalid_parameter, fatal_error, &
      & format_real
   use egw_params, only: contact_params, validate_params, model_epgw
   use egw_gauss, only: gauss_f32, gauss_f12, zmc_flat_integral
   implicit none
   private

   public :: hertz_asperity_force, zmc_asperity_force, rough_flat_law, flat_pressure
   public :: check_flat_input, flat_psi, flat_scaled_to_units

contains

   !> Hertz force of one spherical summit of radius beta pressed by x into a rigid flat:
   !> f = (4/3) E beta^(1/2) x^(3/2) (eq. 5 with 4/3, doc/theory.md §6 misprint 1); 0 for x <= 0.
   elemental real(wp) function hertz_asperity_force(overlap, modulus, summit_radius) result(f)
      real(wp), intent(in) :: overlap        !< x, the summit's overlap (> 0 in contact)
      real(wp), intent(in) :: modulus        !< effective modulus E
      real(wp), intent(in) :: summit_radius  !< beta
      if (overlap > 0.0_wp) then
         f = (4.0_wp/3.0_wp)*modulus*sqrt(summit_radius)*overlap*sqrt(overlap)
      else if (ieee_is_nan(overlap)) then
         f = overlap
      else
         f = 0.0_wp
      end if
   end function hertz_asperity_force

   !> ZMC elasto-plastic asperity force, eq. (42): Hertz up to delta_ep = (3 pi K H/(4E))^2
   !> beta (eq. 36); then pi H beta [1 - (1-K) ln(delta_p/x)/ln(delta_p/delta_ep)]
   !> (1 + 3 lambda^2 - 2 lambda^3) x (eqs. 40, 41, 43) up to delta_p = rho_p delta_ep;
   !> then fully plastic, 2 pi H beta x (eq. 39). Continuous at delta_ep and delta_p; the
   !> slope is not: it drops at both, from (3/2) f/x to (1 + (1-K)/(K ln rho_p)) f/x at
   !> delta_ep and from (1 + (1-K)/ln rho_p) f/x to f/x at delta_p.
   elemental real(wp) function zmc_asperity_force(overlap, modulus, summit_radius, hardness, &
         & hardness_coeff, plastic_ratio) result(f)
      real(wp), intent(in) :: overlap         !< x, the summit's overlap (> 0 in contact)
      real(wp), intent(in) :: modulus         !< effective modulus E
      real(wp), intent(in) :: summit_radius   !< beta
      real(wp), intent(in) :: hardness        !< H
      real(wp), intent(in) :: hardness_coeff  !< K in (0, 1): mean pressure K H at yield
      real(wp), intent(in) :: plastic_ratio   !< rho_p = delta_p/delta_ep > 1 (ZMC: 54)
      real(wp) :: d_ep, d_p, lam, mean_pressure
      if (ieee_is_nan(overlap)) then
         f = overlap
         return
      end if
      d_ep = (3.0_wp*pi*hardness_coeff*hardness/(4.0_wp*modulus))**2*summit_radius
      d_p = plastic_ratio*d_ep
      if (overlap <= 0.0_wp) then
         f = 0.0_wp
      else if (overlap <= d_ep) then
         f = hertz_asperity_force(overlap, modulus, summit_radius)
      else if (overlap <= d_p) then
         lam = (overlap - d_ep)/(d_p - d_ep)
         mean_pressure = 1.0_wp - (1.0_wp - hardness_coeff)*log(d_p/overlap)/log(plastic_ratio)
         f = pi*hardness*summit_radius*mean_pressure*(1.0_wp + lam*lam*(3.0_wp - 2.0_wp*lam)) &
            & *overlap
      else
         f = 2.0_wp*pi*hardness*summit_radius*overlap
      end if
   end function zmc_asperity_force

   !> Dimensionless rough-flat pressure p = p_G/(C sigma^(3/2)) at h = d/sigma, and dp/dh.
   !> psi = 0 (elastic asperities): p = F_{3/2}(h), dp/dh = -(3/2) F_{1/2}(h) (eq. 9).
   !> psi > 0 (ZMC asperities, eq. 44 with eq. 42 and H from eq. 36, e = 1/psi^2,
   !> q = rho_p e): p = I_e + (I_ep + 2 I_p)/(K psi) (doc/theory.md §6 misprint 4: the paper's
   !> common prefactor 3/(2 K psi) in eq. 45 is wrong). Preconditions (not checked):
   !> psi >= 0, 0 < K < 1, rho_p > 1, h not NaN.
   elemental subroutine rough_flat_law(h, psi, hardness_coeff, plastic_ratio, p, dp)
      real(wp), intent(in) :: h               !< separation / sigma
      real(wp), intent(in) :: psi             !< plasticity index of the paper (0 = elastic)
      real(wp), intent(in) :: hardness_coeff  !< ZMC K
      real(wp), intent(in) :: plastic_ratio   !< ZMC rho_p
      real(wp), intent(out) :: p              !< p_G/(C sigma^(3/2))
      real(wp), intent(out) :: dp             !< dp/dh
      real(wp) :: e
      if (psi > 0.0_wp) then
         e = 1.0_wp/(psi*psi)
         call zmc_flat_integral(h, e, plastic_ratio*e, hardness_coeff, p, dp)
      else
         p = gauss_f32(h)
         dp = -1.5_wp*gauss_f12(h)
      end if
   end subroutine rough_flat_law

   !> Nominal pressure p_G(d) = C sigma^(3/2) p(d/sigma) of a rough flat whose summit base
   !> plane is at separation d from a smooth rigid flat, and dp_G/dd, with
   !> C = mu E/(2 sigma sqrt(2R)) (eq. 9). ZMC asperities iff model is EP-GW and psi > 0,
   !> elastic asperities otherwise. Errors: invalid params (egw_invalid_parameter, from
   !> validate_params), sigma = 0 (egw_invalid_parameter), NaN separation
   !> (egw_invalid_argument).
   pure subroutine flat_pressure(params, separation, pressure, dpressure, error)
      type(contact_params), intent(in) :: params   !< the rough flat (sigma > 0)
      real(wp), intent(in) :: separation   !< d, same length unit as sigma
      real(wp), intent(out) :: pressure    !< p_G(d)
      real(wp), intent(out) :: dpressure   !< dp_G/dd (<= 0)
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      real(wp) :: sigma, p, dpdh, psi
      pressure = 0.0_wp
      dpressure = 0.0_wp
      call check_flat_input(params, separation, error)
      if (allocated(error)) return
      sigma = params%sigma
      psi = flat_psi(params)
      call rough_flat_law(separation/sigma, psi, params%hardness_coeff, params%plastic_ratio, &
         & p, dpdh)
      call flat_scaled_to_units(params, separation, p, dpdh, pressure, dpressure, error)
   end subroutine flat_pressure

   !> p_G = C sigma^(3/2) p and dp_G/dd = C sigma^(1/2) dp/dh with C sigma^(3/2) =
   !> (mu/(2 sqrt 2)) E sqrt(sigma/R), formed from the scales validate_params keeps normal
   !> (C alone may overflow). A pressure beyond the doubles (deep overlap, d/sigma ->
   !> -Inf) is refused: egw_invalid_argument naming the separation.
   pure subroutine flat_scaled_to_units(params, separation, p, dpdh, pressure, dpressure, error)
      type(contact_params), intent(in) :: params   !< validated, sigma > 0
      !> d [length] (named in the message), p and dp/dh scaled
      real(wp), intent(in) :: separation, p, dpdh
      real(wp), intent(out) :: pressure, dpressure   !< p_G [pressure] and dp_G/dd [pressure/length]
      !> egw_invalid_argument where p_G exceeds the doubles
      type(egw_error), allocatable, intent(out) :: error
      real(wp) :: scale
      scale = params%mu/(2.0_wp*sqrt(2.0_wp))*params%modulus
      pressure = scale*(sqrt(params%sigma)/sqrt(params%radius))*p
      dpressure = scale/(sqrt(params%sigma)*sqrt(params%radius))*dpdh
      if (.not. (ieee_is_finite(pressure) .and. ieee_is_finite(dpressure))) then
         call fatal_error(error, egw_invalid_argument, "separation = "// &
            & format_real(separation)//": the pressure there overflows (deeper than the " &
            & //"doubles reach; separation/sigma = "//format_real(separation/params%sigma)//")")
      end if
   end subroutine flat_scaled_to_units

   !> The checks of the rough-flat laws' input (flat_pressure, flat_pressure_unload): valid
   !> params, sigma > 0 (a flat needs roughness), a separation that is a number.
   pure subroutine check_flat_input(params, separation, error)
      type(contact_params), intent(in) :: params   !< the contact's parameters
      real(wp), intent(in) :: separation   !< d, same length unit as sigma
      !> the first check that fails, naming its value
      type(egw_error), allocatable, intent(out) :: error
      call validate_params(params, error)
      if (allocated(error)) return
      if (ieee_is_nan(separation)) then
         call fatal_error(error, egw_invalid_argument, "separation = "// &
            & format_real(separation)//": the separation must be a number")
      else if (.not. params%sigma > 0.0_wp) then
         call fatal_error(error, egw_invalid_parameter, &
            & "sigma = 0: the rough-flat law needs sigma > 0")
      end if
   end subroutine check_flat_input

   !> The plasticity index the rough-flat law uses: psi for EP-GW, 0 (elastic summits)
   !> for every other model.
   elemental real(wp) function flat_psi(params) result(psi)
      type(contact_params), intent(in) :: params   !< the contact's parameters
      psi = 0.0_wp
      if (params%model == model_epgw) psi = params%psi
   end function flat_psi

end module egw_asperity
