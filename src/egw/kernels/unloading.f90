!> EP-GW unloading and reloading (doc/theory.md §8, doc/theory.md): the single ZMC asperity
!> unloaded elastically from its contact at maximum interference, and the rough flat's
!> pressure after a closest approach, Z_u(h, h_min).
!>
!> Everything is in units of sigma: interference u, e = delta_ep/sigma = 1/psi^2,
!> q = rho_p e; forces f^ in units of (4/3) E beta^(1/2) sigma^(3/2) (so that the rough
!> flat's pressure is C sigma^(3/2) int f^ phi, as in egw_asperity's rough_flat_law) and
!> contact areas A^ = A/(pi beta sigma).
!>
!> Z_u(h, h_min) = int f^(t) ((D(t) - Delta)_+ / D(t))^(3/2) phi(t + h_min) dt with
!> t = s - h_min the summit's maximum interference, Delta = h - h_min >= 0 and
!> D(t) = t - u_r(t) = min(t, f^(t)/sqrt(A^(t))) its elastic recovery. D is continuous and
!> increasing, so the summits in contact are those beyond t* = D^-1(Delta). The integrand
!> has a (t - t*)^(3/2) edge at t* and kinks at e, q and where the recovery switches between
!> "complete" (D = t, u_r clamped at 0) and "partial" (D = f^/sqrt(A^)); the integral is a
!> fixed composite 16-point Gauss-Legendre rule on the pieces between those points, with
!> t = t* + w^2 on the first panel (the edge becomes smooth), panels sized by the Gaussian's
!> slope and by the distance to t = 0 (the law's branch point), wider in the Gaussian's
!> tail where they carry little of Z_u (tail_width), and the Gaussian factor evaluated at
!> exact node values z = t + h_min.
module egw_unloading
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp, inv_sqrt2pi, pi
   use egw_status, only: egw_error, egw_invalid_argument, fatal_error, format_real
   use egw_params, only: contact_params
   use egw_asperity, only: rough_flat_law, check_flat_input, flat_psi, flat_scaled_to_units
   use egw_gauss, only: gl_x, gl_w
   use egw_simd_path, only: simd_level
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use egw_law_pieces, only: law_pieces, law_pieces_at, unload_pieces, unload_pieces_at, &
      & chebyshev_fit, clenshaw, degree, ln_tol, max_halvings, p_floor
   implicit none
   private

   public :: asperity_load_force, asperity_contact_area, asperity_residual_interference, &
      & asperity_unload_force, rough_flat_unload_law, flat_pressure_unload
   public :: unloading_law, unloading_law_of, unloading_pressure, unloading_kinks, &
      & tabulate_unloading

   !> Gaussian factor kept down to e^-loss_max (2e-16) of its largest value on the domain,
   !> plus the growth of f^ (at most (t_hi/t_lo)^(3/2), a few e-folds) on top.
   real(dp), parameter :: loss_max = 36.0_dp
   !> Panel width: at most max_width in z, at most dloss/|z| where the Gaussian is steep
   !> (exponent change per panel ~ dloss e-folds: 16-point GL error ~1e-16 relative), at
   !> most ratio_max times the distance of the panel's left end to t = 0 (branch point of
   !> the law: Bernstein ellipse rho >= 3, error 3^-32).
   !> loss_max 36 and max_width 2.5 (were 46 and 1.5: a third fewer panels) change Z_u and
   !> dZ_u/dh by at most 5e-14 relative from the former rule on 200000 random (psi in
   !> [0.1, 100], K, rho_p in [1.5, 1000], h_min in [-8, 8], Delta in [1e-8, 30]) wherever
   !> Z_u > 1e-30 (and test_unloading's 40-digit references hold at 1e-12); width 4 or
   !> dloss 12 would not (2e-11, 8e-13).
   real(dp), parameter :: max_width = 2.5_dp, dloss = 10.0_dp, ratio_max = 2.0_dp
   !> Growth of the panels' exponent change per e-fold the Gaussian has lost (tail_width).
   real(dp), parameter :: tail_grade = 0.15_dp
   !> Samples of the clamp test t = f^/sqrt(A^) on (e, q): sign changes are located on this
   !> logarithmic grid, then refined by bisection to full precision.
   integer, parameter :: clamp_samples = 48
   integer, parameter :: max_panels = 400
   !> Halvings of a tabulated Z_u's pieces towards each kink (tabulate_unloading): the
   !> piece touching it 2^-12 of the segment's piece width. ln Z_u's series error there
   !> falls as (width)^(5/2), dZ_u/dh's as (width)^(3/2) (at 1/64: 1e-10 at psi 1, h_min
   !> -3.7, but 8e-8 at h_min 0.8, 9e-7 at psi 0.3), while the integral's last-bit noise
   !> in the series' derivative grows as 1/width: 12 halvings balance them (measured
   !> dZ_u/dh within 2e-9 .. 2e-8 at psi 0.3 .. 10, h_min -6 .. 0.8; ln Z_u 7e-14 ..
   !> 4e-13), hence the slope acceptance unload_slope_tol, looser than the loading
   !> law's (slope_tol): dZ_u/dh enters Newton's Jacobian and the stiffness only.
   integer, parameter :: kink_grades = 12
   real(dp), parameter, public :: unload_slope_tol = 1.0e-7_dp

   !> 16-point Gauss-Legendre nodes on [0, 1] and weights summing to 1 (from egw_gauss's).
   real(dp), parameter :: gl_u(16) = [0.5_dp*(1.0_dp - gl_x), 0.5_dp*(1.0_dp + gl_x)]
   real(dp), parameter :: gl_w16(16) = [0.5_dp*gl_w, 0.5_dp*gl_w]

   !> The ZMC law of one parameter set in units of sigma.
   type :: zmc_law
      real(dp) :: e = huge(1.0_dp)  !< delta_ep/sigma (huge: elastic)
      real(dp) :: q = huge(1.0_dp)  !< delta_p/sigma
      real(dp) :: k = 1.0_dp        !< hardness coefficient K
      real(dp) :: lnqe = 1.0_dp     !< ln(q/e) = ln rho_p
      real(dp) :: c = 1.0_dp        !< sqrt(e)/K, the prefactor of the ZMC pieces
      ! for unload_integral's nodes (no division there): ln q, 1/(q - e), (1 - K)/ln rho_p
      real(dp) :: lnq = 0.0_dp, inv_qe = 0.0_dp, slope = 0.0_dp
   end type zmc_law

   !> Z_u of one parameter set, with what depends on the law alone computed once: the
   !> points where the recovery switches between complete and partial (kinks of D, the
   !> breakpoints of every Z_u call), and r(q). A solver evaluating Z_u at many (h, h_min)
   !> builds it once (unloading_law_of) instead of once per call: the switch search (48
   !> samples of r plus bisections, each with a log) and the bisection for t* were about a
   !> third of a call (5.0 -> 3.2 us at psi = 2 with both moved out or made Newton).
   type, public :: unloading_law
      private
      type(zmc_law) :: zmc
      logical :: plastic = .false.      !< psi > 0 (else Z_u is the loading law)
      real(dp) :: psi = 0.0_dp, hardness_coeff = 0.6_dp, plastic_ratio = 54.0_dp
      integer :: n_sw = 0               !< switch points, ascending in sw(:n_sw)
      real(dp) :: sw(6) = 0.0_dp
      real(dp) :: r_q = 0.0_dp          !< recovery at q, r(q)
      !> The loading law of the same parameters tabulated (egw_law_pieces; empty: the
      !> integral), answering where h <= h_min (the loading branch).
      type(law_pieces) :: loading
   end type unloading_law

   interface
      !> One panel of unload_integral four lanes wide (unloading_simd.c), where simd_level()
      !> is 1: its nodes (edge 0: plain, 1: z = z* + v^2), the integrands there (branch 0
      !> below e, 1 on (e, q), 2 beyond q) and their weighted sums rp, rdp; e .. c:
      !> zmc_law's constants; gl_u, gl_w: the nodes and weights on [0, 1].
      pure subroutine simd_panel(branch, edge, za, zb, z_star, h_min, delta, e, inv_qe, &
         & slope, lnq, c, gl_u, gl_w, rp, rdp) bind(C, name="egw_unload_panel")
         import :: c_int, c_double
         integer(c_int), value :: branch, edge
         real(c_double), value :: za, zb, z_star, h_min, delta, e, inv_qe, slope, lnq, c
         real(c_double), intent(in) :: gl_u(16), gl_w(16)
         real(c_double), intent(out) :: rp, rdp
      end subroutine simd_panel
   end interface

contains

   !> Loading force f^(u) of one summit at interference u (units above): u^(3/2) up to e,
   !> (sqrt(e)/K) [1 - (1-K) ln(q/u)/ln(q/e)] (1 + 3 l^2 - 2 l^3) u up to q
   !> (l = (u-e)/(q-e)), (sqrt(e)/K) 2u beyond (ZMC, eqs. 36-43); 0 for u <= 0.
   !> psi = 0: elastic (u^(3/2) everywhere).
   elemental real(dp) function asperity_load_force(u, psi, hardness_coeff, plastic_ratio) &
      & result(f)
      real(dp), intent(in) :: u               !< interference / sigma
      real(dp), intent(in) :: psi             !< plasticity index of the paper (0: elastic)
      real(dp), intent(in) :: hardness_coeff  !< ZMC K in (0, 1)
      real(dp), intent(in) :: plastic_ratio   !< rho_p > 1
      real(dp) :: a, d
      call law_at(make_law(psi, hardness_coeff, plastic_ratio), u, f, a, d)
   end function asperity_load_force

   !> Contact area A^ = A/(pi beta sigma) of one summit at interference u: u up to e,
   !> u (1 + 3 l^2 - 2 l^3) up to q, 2u beyond (ZMC eq. 41); 0 for u <= 0.
   elemental real(dp) function asperity_contact_area(u, psi, plastic_ratio) result(a)
      real(dp), intent(in) :: u              !< interference / sigma
      real(dp), intent(in) :: psi            !< plasticity index of the paper (0: elastic)
      real(dp), intent(in) :: plastic_ratio  !< rho_p > 1
      real(dp) :: f, d
      call law_at(make_law(psi, 0.5_dp, plastic_ratio), u, f, a, d)
   end function asperity_contact_area

   !> Residual interference u_r = max(0, u_m - f^(u_m)/sqrt(A^(u_m))) after unloading from
   !> the maximum interference u_m: Hertzian unloading from the contact radius at u_m, whose
   !> initial stiffness is the elastic stiffness 2 E a_m. 0 for elastic summits (u_m <= e).
   elemental real(dp) function asperity_residual_interference(u_max, psi, hardness_coeff, &
      & plastic_ratio) result(u_r)
      real(dp), intent(in) :: u_max           !< maximum interference u_m / sigma
      real(dp), intent(in) :: psi             !< plasticity index of the paper (0: elastic)
      real(dp), intent(in) :: hardness_coeff  !< ZMC K in (0, 1)
      real(dp), intent(in) :: plastic_ratio   !< rho_p > 1
      real(dp) :: f, a, d
      call law_at(make_law(psi, hardness_coeff, plastic_ratio), u_max, f, a, d)
      u_r = max(0.0_dp, u_max - d)
   end function asperity_residual_interference

   !> Unloading/reloading force of one summit at interference u after the maximum u_m:
   !> f^(u_m) ((u - u_r)/(u_m - u_r))^(3/2) for u_r < u <= u_m, 0 for u <= u_r, and the
   !> loading law f^(u) above u_m (the history then moves up).
   elemental real(dp) function asperity_unload_force(u, u_max, psi, hardness_coeff, &
      & plastic_ratio) result(f)
      real(dp), intent(in) :: u               !< interference / sigma
      real(dp), intent(in) :: u_max           !< maximum interference so far / sigma
      real(dp), intent(in) :: psi             !< plasticity index of the paper (0: elastic)
      real(dp), intent(in) :: hardness_coeff  !< ZMC K in (0, 1)
      real(dp), intent(in) :: plastic_ratio   !< rho_p > 1
      type(zmc_law) :: law
      real(dp) :: fm, a, d, x
      law = make_law(psi, hardness_coeff, plastic_ratio)
      if (u >= u_max) then
         call law_at(law, u, f, a, d)
         return
      end if
      call law_at(law, u_max, fm, a, d)
      x = d - (u_max - u)  ! u - u_r
      if (x > 0.0_dp) then
         f = fm*(x/d)*sqrt(x/d)
      else
         f = 0.0_dp
      end if
   end function asperity_unload_force

   !> Dimensionless unloading/reloading pressure of the rough flat, Z_u(h, h_min)
   !> (doc/theory.md §8), in the units of rough_flat_law (p_G = C sigma^(3/2) Z_u), and dZ_u/dh
   !> at fixed h_min. h < h_min, or psi = 0 (elastic summits: reversible), is the loading
   !> law; at h = h_min the value is the loading law's and dp the unloading slope.
   !> Preconditions as rough_flat_law (psi >= 0, 0 < K < 1, rho_p > 1, no NaN).
   elemental subroutine rough_flat_unload_law(h, h_min, psi, hardness_coeff, plastic_ratio, &
      & p, dpdh)
      real(dp), intent(in) :: h               !< separation / sigma
      real(dp), intent(in) :: h_min           !< closest approach so far / sigma
      real(dp), intent(in) :: psi             !< plasticity index of the paper (0: elastic)
      real(dp), intent(in) :: hardness_coeff  !< ZMC K
      real(dp), intent(in) :: plastic_ratio   !< ZMC rho_p
      real(dp), intent(out) :: p              !< Z_u
      real(dp), intent(out) :: dpdh           !< dZ_u/dh at fixed h_min (<= 0)
      if (.not. psi > 0.0_dp .or. h < h_min) then
         call rough_flat_law(h, psi, hardness_coeff, plastic_ratio, p, dpdh)
         return
      end if
      call unloading_pressure(unloading_law_of(psi, hardness_coeff, plastic_ratio), h, h_min, &
         & p, dpdh)
   end subroutine rough_flat_unload_law

   !> The unloading law of one parameter set, prepared for many unloading_pressure calls
   !> (the switch points of the recovery found once). Preconditions as rough_flat_law.
   !> loading: the same parameters' loading law tabulated (zmc_law_pieces), taken for the
   !> loading branch (h <= h_min) where its parameters are these (else ignored).
   elemental function unloading_law_of(psi, hardness_coeff, plastic_ratio, loading) &
      & result(law)
      real(dp), intent(in) :: psi             !< plasticity index of the paper (0: elastic)
      real(dp), intent(in) :: hardness_coeff  !< ZMC K
      real(dp), intent(in) :: plastic_ratio   !< ZMC rho_p
      type(law_pieces), intent(in), optional :: loading   !< the tabulated loading law
      type(unloading_law) :: law
      law%psi = psi
      law%hardness_coeff = hardness_coeff
      law%plastic_ratio = plastic_ratio
      law%plastic = psi > 0.0_dp
      if (.not. law%plastic) return
      law%zmc = make_law(psi, hardness_coeff, plastic_ratio)
      call clamp_switches(law%zmc, 0.0_dp, huge(1.0_dp), law%sw, law%n_sw)
      law%r_q = recovery(law%zmc, law%zmc%q)
      if (present(loading)) then
         if (abs(loading%psi - psi) <= 0.0_dp .and. &
            & abs(loading%hardness_coeff - hardness_coeff) <= 0.0_dp .and. &
            & abs(loading%plastic_ratio - plastic_ratio) <= 0.0_dp) law%loading = loading
      end if
   end function unloading_law_of

   !> The Delta = h - h_min > 0 at which Z_u(h, h_min) is less smooth in h: where the
   !> contact edge t* = D^-1(Delta) crosses a kink of the recovery D (t = e, q and the
   !> switches between complete and partial recovery), i.e. Delta = D(e) = e, D(q) =
   !> min(q, r(q)) and D(switch) = switch. Where D' jumps there (at e when the recovery is
   !> partial just above it, at q, at the switches), d^2 Z_u/dh^2 jumps with it (under the
   !> integral's edge; a kink of f^ alone is weaker): small jumps (~0.5 %), but one inside a
   !> sphere solve's element costs it its order (seen: errors 10x the Richardson estimate),
   !> as Delta = 0 (the branch) does for dZ_u/dh. Empty for elastic summits.
   pure function unloading_kinks(law) result(deltas)
      type(unloading_law), intent(in) :: law   !< prepared by unloading_law_of
      real(dp), allocatable :: deltas(:)
      if (.not. law%plastic) then
         allocate (deltas(0))
         return
      end if
      deltas = [law%zmc%e, min(law%zmc%q, law%r_q), law%sw(:law%n_sw)]
   end function unloading_kinks

   !> Z_u(h, h_min) and dZ_u/dh of a prepared law: the same values as rough_flat_unload_law
   !> with the law's parameters.
   elemental subroutine unloading_pressure(law, h, h_min, p, dpdh)
      type(unloading_law), intent(in) :: law   !< prepared by unloading_law_of
      real(dp), intent(in) :: h               !< separation / sigma
      real(dp), intent(in) :: h_min           !< closest approach so far / sigma
      real(dp), intent(out) :: p              !< Z_u
      real(dp), intent(out) :: dpdh           !< dZ_u/dh at fixed h_min (<= 0)
      real(dp) :: p_load, dp_load
      logical :: inside
      if (.not. law%plastic .or. h < h_min) then
         call loading_pressure(law, h, p, dpdh)
         return
      end if
      call unload_pieces_at(law%loading%unload, h - h_min, h_min, p, dpdh, inside)
      if (.not. inside) call unload_integral(law, h - h_min, h_min, p, dpdh)
      if (.not. h > h_min) then  ! h = h_min: the loading value exactly
         call loading_pressure(law, h, p_load, dp_load)
         p = p_load
      end if
   end subroutine unloading_pressure

   !> The loading law of a prepared unloading law at h: its table where it has one and h
   !> is in its range, else the integral.
   elemental subroutine loading_pressure(law, h, p, dpdh)
      type(unloading_law), intent(in) :: law
      real(dp), intent(in) :: h
      real(dp), intent(out) :: p, dpdh
      logical :: inside
      call law_pieces_at(law%loading, h, p, dpdh, inside)
      if (.not. inside) call rough_flat_law(h, law%psi, law%hardness_coeff, &
         & law%plastic_ratio, p, dpdh)
   end subroutine loading_pressure

   !> Nominal pressure p_G,u(d, d_min) = C sigma^(3/2) Z_u(d/sigma, d_min/sigma) of the rough
   !> flat at separation d after the closest approach d_min (d_min <= d: unloading or
   !> reloading; d < d_min: the loading law, the approach then being new), and dp_G,u/dd at
   !> fixed d_min. ZMC summits iff model is EP-GW and psi > 0, else elastic (reversible).
   !> Errors: invalid params, sigma = 0 (egw_invalid_parameter); NaN separation or
   !> non-finite separation_min (egw_invalid_argument). Outputs unchanged on error.
   pure subroutine flat_pressure_unload(params, separation, separation_min, pressure, &
      & dpressure, error)
      type(contact_params), intent(in) :: params   !< the contact (sigma > 0)
      real(dp), intent(in) :: separation      !< d, same length unit as sigma
      real(dp), intent(in) :: separation_min  !< d_min, the closest approach so far
      real(dp), intent(inout) :: pressure     !< p_G,u
      real(dp), intent(inout) :: dpressure    !< dp_G,u/dd (<= 0)
      type(egw_error), allocatable, intent(out) :: error   !< allocated on bad input
      real(dp) :: sigma, p, dpdh, psi, pu, dpu
      call check_flat_input(params, separation, error)
      if (allocated(error)) return
      if (.not. ieee_is_finite(separation_min)) then
         call fatal_error(error, egw_invalid_argument, "separation_min = "// &
            & format_real(separation_min)//": the closest approach must be finite")
         return
      end if
      sigma = params%sigma
      psi = flat_psi(params)
      call rough_flat_unload_law(separation/sigma, separation_min/sigma, psi, &
         & params%hardness_coeff, params%plastic_ratio, p, dpdh)
      call flat_scaled_to_units(params, separation, p, dpdh, pu, dpu, error)
      if (allocated(error)) return
      pressure = pu
      dpressure = dpu
   end subroutine flat_pressure_unload

   !> Adds to loading (a tabulated ZMC law, zmc_law_pieces) its unloading law at one
   !> closest approach h_min: Z_u(Delta, h_min) in Delta (egw_law_pieces' unload_pieces),
   !> which unloading_pressure then answers at that h_min (within rounding: 1e-12 (1 +
   !> |h_min|)). A rough + cap build's unloading solves evaluate most of their Z_u at one
   !> h_min, the deep plastic zone's h_y (flow_cap's plastic_shifts: every deep point's
   !> shifted h_min is that root), ~3 us a call by the integral. The range: Delta from 0 to
   !> the last whole unit d_end where Z_u >= p_floor (Z_u < p_floor from d_end + 1 on:
   !> answered as 0); the pieces end at every unloading_kinks
   !> Delta (the series need Z_u smooth on each, graded towards them) and are at most 1
   !> wide. Accepted as zmc_law_pieces: at each piece's Chebyshev extrema and midpoints
   !> between them, ln Z_u within ln_tol (1 + |ln Z_u|/64) and dZ_u/dh within
   !> unload_slope_tol of the integral's (relative); a piece that fails halves the widths
   !> (max_halvings times), then the table stays empty (the integral answers). An empty or elastic loading is left as it is.
   pure subroutine tabulate_unloading(loading, h_min)
      type(law_pieces), intent(inout) :: loading   !< the tabulated loading law
      real(dp), intent(in) :: h_min   !< the closest approach / sigma (finite)
      type(unloading_law) :: law
      real(dp), allocatable :: kinks(:)
      real(dp) :: d_end, p, dpdh, w
      integer :: halving
      logical :: ok
      loading%unload = unload_pieces()
      if (loading%n == 0 .or. .not. loading%psi > 0.0_dp .or. &
         & .not. ieee_is_finite(h_min)) return
      law = unloading_law_of(loading%psi, loading%hardness_coeff, loading%plastic_ratio)
      ! the last whole unit of Delta where Z_u >= p_floor
      d_end = 0.0_dp
      do
         call unload_integral(law, d_end + 1.0_dp, h_min, p, dpdh)
         if (.not. p >= p_floor .or. d_end >= 1.0e3_dp) exit
         d_end = d_end + 1.0_dp
      end do
      if (.not. d_end > 0.0_dp) return
      kinks = unloading_kinks(law)
      kinks = pack(kinks, kinks > 0.0_dp .and. kinks < d_end)
      call sort(kinks)
      w = 1.0_dp
      do halving = 0, max_halvings
         call unloading_series(law, h_min, [0.0_dp, kinks, d_end], w, loading%unload, ok)
         if (ok) return
         w = 0.5_dp*w
      end do
      loading%unload = unload_pieces()
   end subroutine tabulate_unloading

   !> tabulate_unloading's pieces of width at most w between the breaks (ascending) and
   !> their check; ok when every piece passes.
   pure subroutine unloading_series(law, h_min, breaks, w, t, ok)
      type(unloading_law), intent(in) :: law
      real(dp), intent(in) :: h_min, breaks(:), w
      type(unload_pieces), intent(out) :: t
      logical, intent(out) :: ok
      integer, parameter :: m = degree + 1
      real(dp) :: x(m), xc(2*m - 1), lnp(m), d, p, dpdh, lt, dlt, a, b, lo, hi, err
      real(dp), allocatable :: edges(:)
      integer :: i, j, k, n
      call chebyshev_fit(x=x)
      do i = 1, 2*m - 1
         xc(i) = cos(0.5_dp*pi*real(i, dp)/m)
      end do
      ! every segment in equal pieces of width <= w, those next to a kink (an interior
      ! break) graded towards it: Z_u has a (Delta - kink)^(5/2)-type term there, whose
      ! series error on a piece of width h next to it falls as h^(5/2) (ln Z_u) and
      ! h^(3/2) (dZ_u/dh; 7e-8 at h = 1, psi 1, h_min -3.7): kink_grades halvings bring
      ! it below the acceptance
      edges = [breaks(1)]
      do i = 1, size(breaks) - 1
         a = breaks(i)
         b = breaks(i + 1)
         n = max(1, ceiling((b - a)/w - 1.0e-9_dp))
         do j = 1, n
            lo = a + (b - a)*real(j - 1, dp)/n
            hi = a + (b - a)*real(j, dp)/n
            if (j == n) hi = b
            if (i > 1 .and. j == 1) edges = [edges, [(lo + (hi - lo)*0.5_dp**k, &
               & k = kink_grades, 1, -1)]]
            ! (a piece graded at both ends has its midpoint once)
            if (i < size(breaks) - 1 .and. j == n) edges = [edges, [(hi - (hi - lo)* &
               & 0.5_dp**k, k = merge(2, 1, i > 1 .and. n == 1), kink_grades)]]
            edges = [edges, hi]
         end do
      end do
      n = size(edges) - 1
      t%h_min = h_min
      t%slack = 1.0e-12_dp*(1.0_dp + abs(h_min))
      t%n = n
      allocate (t%c(0:degree, n), t%edges(0:n))
      t%edges(:) = edges
      ok = .true.
      do k = 1, n
         a = t%edges(k - 1)
         b = t%edges(k)
         do j = 1, m
            d = 0.5_dp*(a + b) + 0.5_dp*(b - a)*x(j)
            call unload_integral(law, d, h_min, p, dpdh)
            if (.not. (p > 0.0_dp .and. ieee_is_finite(p))) then
               ok = .false.
               return
            end if
            lnp(j) = log(p)
         end do
         call chebyshev_fit(lnp, t%c(:, k))
         do j = 1, 2*m - 1
            d = 0.5_dp*(a + b) + 0.5_dp*(b - a)*xc(j)
            call unload_integral(law, d, h_min, p, dpdh)
            call clenshaw(t%c(:, k), xc(j), 2.0_dp/(b - a), lt, dlt)
            if (.not. (p > 0.0_dp .and. dpdh < 0.0_dp)) then
               ok = .false.
               return
            end if
            err = abs(lt - log(p))/(1.0_dp + abs(log(p))/64.0_dp)
            t%ln_error = max(t%ln_error, err)
            err = abs(exp(lt)*dlt - dpdh)/abs(dpdh)
            t%slope_error = max(t%slope_error, err)
         end do
         if (.not. (t%ln_error <= ln_tol .and. t%slope_error <= unload_slope_tol)) then
            ok = .false.
            return
         end if
      end do
   end subroutine unloading_series

   ! ---------------------------------------------------------------------------------------

   elemental function make_law(psi, hardness_coeff, plastic_ratio) result(law)
      real(dp), intent(in) :: psi, hardness_coeff, plastic_ratio
      type(zmc_law) :: law
      if (psi > 0.0_dp) then
         law%e = 1.0_dp/(psi*psi)
         law%q = plastic_ratio*law%e
         law%k = hardness_coeff
         law%lnqe = log(plastic_ratio)
         law%c = sqrt(law%e)/hardness_coeff
         law%lnq = log(law%q)
         law%inv_qe = 1.0_dp/(law%q - law%e)
         law%slope = (1.0_dp - hardness_coeff)/law%lnqe
      end if
   end function make_law

   !> f^(t), A^(t) and the elastic recovery r(t) = f^/sqrt(A^) (t above e; t below it, where
   !> they are equal), for t > 0; all 0 for t <= 0.
   elemental subroutine law_at(law, t, f, a, r)
      type(zmc_law), intent(in) :: law
      real(dp), intent(in) :: t
      real(dp), intent(out) :: f, a, r
      real(dp) :: l, area, pres
      if (.not. t > 0.0_dp) then
         f = 0.0_dp
         a = 0.0_dp
         r = 0.0_dp
      else if (t <= law%e) then
         f = t*sqrt(t)
         a = t
         r = t
      else if (t <= law%q) then
         l = (t - law%e)/(law%q - law%e)
         area = 1.0_dp + l*l*(3.0_dp - 2.0_dp*l)
         pres = 1.0_dp - (1.0_dp - law%k)*log(law%q/t)/law%lnqe
         f = law%c*pres*area*t
         a = area*t
         r = law%c*pres*sqrt(a)
      else
         f = 2.0_dp*law%c*t
         a = 2.0_dp*t
         r = law%c*sqrt(a)
      end if
      r = min(t, r)
   end subroutine law_at

   !> The partial recovery r(t) = f^/sqrt(A^) (not clamped at t).
   elemental real(dp) function recovery(law, t) result(r)
      type(zmc_law), intent(in) :: law
      real(dp), intent(in) :: t
      real(dp) :: l, area, pres
      if (t <= law%e) then
         r = t
      else if (t <= law%q) then
         l = (t - law%e)/(law%q - law%e)
         area = 1.0_dp + l*l*(3.0_dp - 2.0_dp*l)
         pres = 1.0_dp - (1.0_dp - law%k)*log(law%q/t)/law%lnqe
         r = law%c*pres*sqrt(area*t)
      else
         r = law%c*sqrt(2.0_dp*t)
      end if
   end function recovery

   !> t* = D^-1(Delta) = max(Delta, r^-1(Delta)) (both D = min(t, r) and r increase).
   !> On (e, q) r is smooth and increasing: Newton with the analytic r', kept inside a
   !> bracket (bisection when a step leaves it), to a step of a few ulps (5-6 iterations;
   !> a bisection to the last bit took 60 evaluations of r, each with a log).
   pure real(dp) function contact_start(ulaw, delta) result(t)
      type(unloading_law), intent(in) :: ulaw
      real(dp), intent(in) :: delta
      real(dp) :: lo, hi, g, dg, step, t_new
      integer :: i
      associate (law => ulaw%zmc)
         if (delta <= law%e) then
            t = delta
         else if (delta <= ulaw%r_q) then
            lo = law%e
            hi = law%q
            ! r(e) = e: start on the chord from (e, e) to (q, r(q))
            t = law%e + (law%q - law%e)*(delta - law%e)/(ulaw%r_q - law%e)
            do i = 1, 100
               call recovery_slope(law, t, g, dg)
               g = g - delta
               if (g < 0.0_dp) then
                  lo = t
               else
                  hi = t
               end if
               if (g == 0.0_dp) exit
               step = -g/dg
               t_new = t + step
               if (.not. (t_new > lo .and. t_new < hi)) then
                  t_new = 0.5_dp*(lo + hi)
                  step = t_new - t
               end if
               if (.not. (t_new > lo .and. t_new < hi)) exit  ! bracket at rounding level
               t = t_new
               if (abs(step) <= 4.0_dp*epsilon(1.0_dp)*t) exit
            end do
            t = max(delta, t)
         else
            t = max(delta, 0.5_dp*(delta/law%c)**2)
         end if
      end associate
   end function contact_start

   !> The partial recovery r(t) = c pres sqrt(A^) on (e, q] and its derivative
   !> r' = c (pres' sqrt(A^) + pres A^'/(2 sqrt(A^))), pres' = (1 - K)/(t ln rho_p),
   !> A^' = area + t area'(l)/(q - e).
   pure subroutine recovery_slope(law, t, r, drdt)
      type(zmc_law), intent(in) :: law
      real(dp), intent(in) :: t
      real(dp), intent(out) :: r, drdt
      real(dp) :: l, area, pres, a, sa, da
      l = (t - law%e)/(law%q - law%e)
      area = 1.0_dp + l*l*(3.0_dp - 2.0_dp*l)
      pres = 1.0_dp - (1.0_dp - law%k)*log(law%q/t)/law%lnqe
      a = area*t
      sa = sqrt(a)
      da = area + t*6.0_dp*l*(1.0_dp - l)/(law%q - law%e)
      r = law%c*pres*sa
      drdt = law%c*((1.0_dp - law%k)/(t*law%lnqe)*sa + pres*da/(2.0_dp*sa))
   end subroutine recovery_slope

   !> Points in (t_lo, t_hi) where the recovery switches between complete (r >= t) and
   !> partial (r < t): kinks of D. On (e, q) by sign changes of r - t on a log grid refined
   !> by bisection; beyond q at t = 2 e/K^2 (r = t there in closed form).
   pure subroutine clamp_switches(law, t_lo, t_hi, sw, n)
      type(zmc_law), intent(in) :: law
      real(dp), intent(in) :: t_lo, t_hi
      real(dp), intent(out) :: sw(:)
      integer, intent(out) :: n
      real(dp) :: lo, hi, g_lo, g_hi, ratio, root
      integer :: i
      n = 0
      if (max(law%e, t_lo) < min(law%q, t_hi)) then
         ratio = (law%q/law%e)**(1.0_dp/clamp_samples)
         lo = law%e*(1.0_dp + 1.0e-12_dp)  ! r = t at e itself
         g_lo = recovery(law, lo) - lo
         do i = 1, clamp_samples
            hi = law%e*ratio**i
            if (i == clamp_samples) hi = law%q
            g_hi = recovery(law, hi) - hi
            if ((g_lo < 0.0_dp .neqv. g_hi < 0.0_dp) .and. hi > t_lo .and. lo < t_hi) then
               root = switch_point(law, lo, hi, g_lo < 0.0_dp)
               if (root > t_lo .and. root < t_hi .and. n < size(sw)) then
                  n = n + 1
                  sw(n) = root
               end if
            end if
            if (hi >= t_hi) exit
            lo = hi
            g_lo = g_hi
         end do
      end if
      root = 2.0_dp*law%e/(law%k*law%k)
      if (root > law%q .and. root > t_lo .and. root < t_hi .and. n < size(sw)) then
         n = n + 1
         sw(n) = root
      end if
   end subroutine clamp_switches

   !> The zero of r(t) - t in (lo, hi), where it changes sign, by bisection to the last bit.
   pure real(dp) function switch_point(law, lo, hi, negative_at_lo) result(t)
      type(zmc_law), intent(in) :: law
      real(dp), intent(in) :: lo, hi
      logical, intent(in) :: negative_at_lo
      real(dp) :: a, b
      integer :: i
      a = lo
      b = hi
      t = 0.5_dp*(a + b)
      do i = 1, 200
         t = 0.5_dp*(a + b)
         if (.not. (t > a .and. t < b)) exit
         if ((recovery(law, t) - t < 0.0_dp) .eqv. negative_at_lo) then
            a = t
         else
            b = t
         end if
      end do
   end function switch_point

   !> Z_u and dZ_u/dh for Delta = h - h_min >= 0 by the piecewise rule described above.
   pure subroutine unload_integral(ulaw, delta, h_min, p, dpdh)
      type(unloading_law), intent(in) :: ulaw
      real(dp), intent(in) :: delta, h_min
      real(dp), intent(out) :: p, dpdh
      real(dp) :: t_star, z_star, z_lo, z_hi, z_peak, span, breaks(8), z0, z1, w
      real(dp) :: s_p, s_dp, r_p, r_dp, t0
      integer :: nb, i, ip
      logical :: wide
      p = 0.0_dp
      dpdh = 0.0_dp
      t_star = contact_start(ulaw, delta)
      z_star = t_star + h_min
      ! Gaussian window on [z_star, inf): from the peak z_peak of phi there, keep the
      ! region where phi has lost at most loss_max e-folds
      z_peak = max(z_star, 0.0_dp)
      if (z_peak > 38.7_dp) return  ! phi < 1e-325 everywhere: underflow, Z_u = 0
      span = loss_max + 6.0_dp
      z_hi = z_peak + 2.0_dp*span/(z_peak + sqrt(z_peak*z_peak + 2.0_dp*span))
      z_lo = z_star
      if (z_peak > z_star) z_lo = max(z_star, -sqrt(2.0_dp*span))
      ! breakpoints of the law inside the window, in z
      nb = 0
      call add_break(ulaw%zmc%e + h_min, z_lo, z_hi, breaks, nb)
      call add_break(ulaw%zmc%q + h_min, z_lo, z_hi, breaks, nb)
      do i = 1, ulaw%n_sw
         call add_break(ulaw%sw(i) + h_min, z_lo, z_hi, breaks, nb)
      end do
      call sort(breaks(:nb))
      ! AVX2 + FMA: each panel four lanes wide in unloading_simd.c (asked once a call)
      wide = simd_level() == 1
      s_p = 0.0_dp
      s_dp = 0.0_dp
      z0 = z_lo
      do i = 1, nb + 1
         if (i <= nb) then
            z1 = breaks(i)
         else
            z1 = z_hi
         end if
         if (z1 <= z0) cycle
         ! panels near the contact edge (the first, and any starting closer to it than their
         ! width, e.g. right after a breakpoint just beyond t*) in t = t* + v^2, which
         ! makes the (t - t*)^(3/2) edge smooth
         do ip = 1, max_panels
            if (z0 >= z1) exit
            w = min(z1 - z0, max_width)
            if (abs(z0) > 1.0_dp) w = min(w, dloss/abs(z0))
            ! beyond e the law has log t and sqrt t: keep t = 0 far from the panel
            t0 = max(z0 - h_min, t_star)
            if (t0 >= ulaw%zmc%e) w = min(w, ratio_max*t0)
            if (z0 - z_star < w) then
               ! a panel that starts just beyond the edge (after a breakpoint) sees the
               ! edge's branch point at v ~ +-i sqrt(z0 - z*): at most 3x that in v
               if (z0 > z_star) w = min(w, 8.0_dp*(z0 - z_star))
               call edge_panel(z0, z0 + w, r_p, r_dp)
            else
               if (z0 > z_peak) w = max(w, tail_width(z0, z1, z_peak, z_star, t0, &
                  & ulaw%zmc%e))
               call plain_panel(z0, z0 + w, r_p, r_dp)
            end if
            s_p = s_p + r_p
            s_dp = s_dp + r_dp
            z0 = z0 + w
         end do
         z0 = max(z0, z1)
      end do
      p = s_p
      dpdh = -1.5_dp*s_dp

   contains

      !> The integrands at the 16 nodes z(:) of one panel, F = f^ ((D - Delta)/D)^(3/2)
      !> phi(z) and G = f^ (D - Delta)^(1/2)/D^(3/2) phi(z) (dZ_u/dh = -(3/2) int G).
      !> Panels never straddle e, q or a switch of the recovery (they are breakpoints), so
      !> one branch of the law holds on the whole panel: it is chosen once, at the panel's
      !> middle t_mid, and the 16 nodes are evaluated as arrays, which the compiler turns
      !> into SIMD code (vector log, exp, sqrt; as egw_gauss's panels of the loading law).
      !> Evaluated node by node through law_at, this was ~70 % of Z_u's time. The law's
      !> constants are prepared (make_law) so that a node divides once (1/D); below e,
      !> where f^ = t^(3/2) and D = t, G is sqrt(t - Delta) phi outright. Where the CPU has
      !> AVX2 + FMA (egw_simd_path), wide_panel evaluates the same formulas four lanes wide
      !> in unloading_simd.c instead (the results differ in rounding only: test_unloading).
      pure subroutine integrands(t_mid, z, fz, gz)
         real(dp), intent(in) :: t_mid, z(16)
         real(dp), intent(out) :: fz(16), gz(16)
         real(dp) :: t(16), f(16), d(16), x(16), l(16), area(16), pres(16), phi(16), &
            & inv_d(16)
         t = max(z - h_min, tiny(1.0_dp))  ! nodes lie above t* >= 0
         phi = gaussian(z)
         associate (law => ulaw%zmc)
            if (t_mid <= law%e) then
               x = max(t - delta, 0.0_dp)
               gz = sqrt(x)*phi
               fz = gz*x
               return
            else if (t_mid <= law%q) then
               l = (t - law%e)*law%inv_qe
               area = 1.0_dp + l*l*(3.0_dp - 2.0_dp*l)
               pres = 1.0_dp - law%slope*(law%lnq - log(t))
               f = law%c*pres*area*t
               d = min(t, law%c*pres*sqrt(area*t))
            else
               f = 2.0_dp*law%c*t
               d = min(t, law%c*sqrt(2.0_dp*t))
            end if
         end associate
         x = max(d - delta, 0.0_dp)
         inv_d = 1.0_dp/d
         gz = f*inv_d*sqrt(x*inv_d)*phi
         fz = gz*x
      end subroutine integrands

      !> The whole panel in unloading_simd.c (AVX2 + FMA): the same nodes, integrands and
      !> sums as plain_panel and edge_panel, in the same order (the same bits), one call a
      !> panel instead of the integrands' wrapper and two-lane nodes and sums here.
      pure subroutine wide_panel(edge, za, zb, rp, rdp)
         integer(c_int), intent(in) :: edge
         real(dp), intent(in) :: za, zb
         real(dp), intent(out) :: rp, rdp
         real(dp) :: t_mid
         integer(c_int) :: branch
         t_mid = 0.5_dp*(za + zb) - h_min
         associate (law => ulaw%zmc)
            branch = merge(0_c_int, merge(1_c_int, 2_c_int, t_mid <= law%q), &
               & t_mid <= law%e)
            call simd_panel(branch, edge, za, zb, z_star, h_min, delta, law%e, law%inv_qe, &
               & law%slope, law%lnq, law%c, gl_u, gl_w16, rp, rdp)
         end associate
      end subroutine wide_panel

      pure subroutine plain_panel(za, zb, rp, rdp)
         real(dp), intent(in) :: za, zb
         real(dp), intent(out) :: rp, rdp
         real(dp) :: fz(16), gz(16)
         if (wide) then
            call wide_panel(0_c_int, za, zb, rp, rdp)
            return
         end if
         call integrands(0.5_dp*(za + zb) - h_min, za + (zb - za)*gl_u, fz, gz)
         rp = sum16(gl_w16*fz)*(zb - za)
         rdp = sum16(gl_w16*gz)*(zb - za)
      end subroutine plain_panel

      !> [za, zb] in z = z* + v^2, v from sqrt(za - z*) to sqrt(zb - z*)
      pure subroutine edge_panel(za, zb, rp, rdp)
         real(dp), intent(in) :: za, zb
         real(dp), intent(out) :: rp, rdp
         real(dp) :: fz(16), gz(16), va, vb, v(16)
         if (wide) then
            call wide_panel(1_c_int, za, zb, rp, rdp)
            return
         end if
         va = sqrt(max(za - z_star, 0.0_dp))
         vb = sqrt(max(zb - z_star, 0.0_dp))
         v = va + (vb - va)*gl_u
         call integrands(0.5_dp*(za + zb) - h_min, z_star + v*v, fz, gz)
         rp = sum16(gl_w16*fz*2.0_dp*v)*(vb - va)
         rdp = sum16(gl_w16*gz*2.0_dp*v)*(vb - va)
      end subroutine edge_panel

   end subroutine unload_integral

   !> The width of a plain panel starting at z0 > z_peak in the Gaussian's tail, where phi
   !> has lost L = (z0^2 - z_peak^2)/2 e-folds from its largest value on the window: the
   !> panel's share of Z_u is below e^-L, so its relative error may be e^L times larger
   !> and the exponent change it spans (dloss and max_width, the limits at L = 0) grows
   !> by the factor 1 + tail_grade L. The 16-point rule's relative error on e^-lambda x,
   !> x in [0, 1] (mpmath): 2e-15 at lambda 20, 3e-12 at 30, 8e-10 at 40, 6e-7 at 60;
   !> lambda = 10 + 1.5 L keeps e^-L times it below 2e-17 at every L (5e-18 at L 10, 2e-18
   !> at 20). Not graded: the distance to the law's branch point t = 0 (ratio_max t0) and
   !> to the contact edge (at most twice z0 - z*: the edge's (z - z*)^(3/2) then lies a
   !> Bernstein ellipse rho >= 3.7 away, 3.7^-32 = 6e-19). Stop 65 (psi31): 4.05 -> 2.53
   !> panels a call of README's psi 1 + cap build, Z_u and dZ_u/dh within 7e-16 of the
   !> ungraded rule there and on 200 000 random parameters (doc/benchmarks.md).
   pure real(dp) function tail_width(z0, z1, z_peak, z_star, t0, e) result(w)
      real(dp), intent(in) :: z0       !< the panel's start, beyond z_peak and the edge
      real(dp), intent(in) :: z1       !< the next breakpoint or the window's end
      real(dp), intent(in) :: z_peak   !< where phi is largest on the window
      real(dp), intent(in) :: z_star   !< the contact edge z* = t* + h_min
      real(dp), intent(in) :: t0       !< the summits' interference at z0
      real(dp), intent(in) :: e        !< delta_ep/sigma, where log t enters the law
      real(dp) :: g
      g = 1.0_dp + tail_grade*0.5_dp*(z0 - z_peak)*(z0 + z_peak)
      w = g*max_width
      if (abs(z0) > 1.0_dp) w = min(w, g*dloss/abs(z0))
      if (t0 >= e) w = min(w, ratio_max*t0)
      w = min(z1 - z0, w, 2.0_dp*(z0 - z_star))
   end function tail_width

   !> Sum of a panel's 16 terms as a tree of halves (vector adds; the sum intrinsic adds
   !> them one after the other, a chain of 15 dependent adds, since the compiler may not
   !> reorder them).
   pure real(dp) function sum16(x) result(total)
      real(dp), intent(in) :: x(16)
      real(dp) :: h8(8), h4(4)
      h8 = x(1:8) + x(9:16)
      h4 = h8(1:4) + h8(5:8)
      total = (h4(1) + h4(3)) + (h4(2) + h4(4))
   end function sum16

   !> Append z to breaks(1:nb) if it lies inside (z_lo, z_hi).
   pure subroutine add_break(z, z_lo, z_hi, breaks, nb)
      real(dp), intent(in) :: z, z_lo, z_hi
      real(dp), intent(inout) :: breaks(:)
      integer, intent(inout) :: nb
      if (z > z_lo .and. z < z_hi .and. nb < size(breaks)) then
         nb = nb + 1
         breaks(nb) = z
      end if
   end subroutine add_break

   !> phi(z) = exp(-z^2/2)/sqrt(2 pi) at the nodes of a panel, to a few ulps: with z = hi
   !> + lo, hi of 26 bits (Dekker split), hi^2/2 is exact and the rest, |small| < 2e-5 for
   !> the |z| < 40 of the windows, enters through a cubic (egw_gauss's exp_neg_half_square
   !> without its branches, so that the 16 nodes vectorise). |z| > 38.6: 0 (underflow).
   !> Of fixed size 16: with z(:) the result was a temporary of run-time size, which
   !> gfortran took from the heap (malloc and free on every panel, ~9 % of Z_u's time).
   pure function gaussian(z) result(phi)
      real(dp), intent(in) :: z(16)
      real(dp) :: phi(16)
      real(dp), parameter :: splitter = 134217729.0_dp  ! 2^27 + 1
      real(dp) :: a(16), c(16), hi(16), small(16)
      a = min(abs(z), 40.0_dp)
      c = splitter*a
      hi = c - (c - a)
      small = 0.5_dp*(a - hi)*(a + hi)
      phi = inv_sqrt2pi*exp(-0.5_dp*hi*hi)*(1.0_dp - small*(1.0_dp - small*(0.5_dp - &
         & small/6.0_dp)))
   end function gaussian

   pure subroutine sort(x)
      real(dp), intent(inout) :: x(:)
      real(dp) :: v
      integer :: i, j
      do i = 2, size(x)
         v = x(i)
         j = i - 1
         do while (j >= 1)
            if (x(j) <= v) exit
            x(j + 1) = x(j)
            j = j - 1
         end do
         x(j + 1) = v
      end do
   end subroutine sort

end module egw_unloading
