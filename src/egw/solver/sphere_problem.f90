!> The scaled problem of a rough sphere (doc/theory.md §5, §7): the options of a solve,
!> the problem in scaled variables (the loading law as a flat_law object, the base gap, the
!> unloading's closest-approach field), a discrete solution and what is read off it
!> (pressure, force, contact radius). Shared by the solver's meshes (egw_sphere_mesh),
!> iterations (egw_sphere_iteration) and levels (egw_sphere_solver).
module egw_sphere_problem
   use egw_kinds, only: dp, pi, sqrt2
   use egw_params, only: contact_params, model_egw, model_epgw, pressure_unit
   use egw_smooth_sphere, only: hertz_gap, hertz_pressure, hertz_force, hertz_stiffness
   use egw_flat_law, only: flat_law, gw_flat_law
   use egw_law_pieces, only: law_pieces
   use egw_zmc_table_law, only: zmc_table_law
   use egw_flow_cap, only: flow_cap
   use egw_unloading, only: unloading_law, unloading_law_of, unloading_pressure, &
      & tabulate_unloading
   use egw_halfspace, only: radial_mesh, node_index, influence_row, &
      & interpolate_nodal_walk
   implicit none
   private

   integer, parameter, public :: method_auto = 0    !< Newton (the robust choice)
   integer, parameter, public :: method_newton = 1  !< Newton + backtracking line search
   integer, parameter, public :: method_picard = 2  !< damped fixed point (Picard)

   !> Options of a solve. Field order and meaning match the C struct egw_options.
   type, public :: solver_options
      integer :: n_radial = 0          !< mesh nodes; 0 = chosen from rel_tol
      real(dp) :: rel_tol = 1.0e-6_dp  !< target relative accuracy of the force
      integer :: max_iter = 0          !< nonlinear iterations; 0 = default
      integer :: method = method_auto  !< method_auto, method_newton or method_picard
      integer :: n_threads = 0         !< threads of the assembly; 0 = OpenMP default
   end type solver_options

   !> Largest mesh (nodes) of a solve: its dense influence matrix (nodes x 1.5 nodes) and
   !> Jacobian take ~0.5 GB and an LU ~10 s; the automatic meshes of the solver's range
   !> (delta/sigma up to 1e15, rel_tol down to 1e-10) stay well below. Bounds every solve's
   !> time and memory (n_radial larger: egw_invalid_argument).
   integer, parameter, public :: max_mesh_nodes = 4097
   !> Scaled force below which a solve returns 0 (as negligible() does before solving).
   real(dp), parameter :: tiny_force = 1.0e-250_dp

   public :: tiny_force

   !> Degree of the deflection elements and pressure points per element: quartic elements
   !> with 6 Gauss points were the cheapest per digit of the pairs tried (degree 2-4,
   !> 4-8 points); the force error then falls like step**5 to step**6.
   integer, parameter, public :: deflection_degree = 4, pressure_points = 6
   !> On [-1, 1] the Lagrange basis of the degree-4 Chebyshev-Lobatto element nodes sums its
   !> negative parts to at most 0.3994 (half its Lebesgue constant 1.7988, less 1/2): an
   !> element's interpolant stays above its smallest nodal value less that times the nodal
   !> range. Taken as 0.5 (test rough_cap 'cap_never_acts: the element bound').
   real(dp), parameter, public :: lagrange_undershoot = 0.5_dp

   !> Separation field of the loading solve at delta_max (scaled): d_max(r) = z_max(r) +
   !> w_max(r) with z_max the base gap at delta_max and w_max the nodal rough deflection
   !> interpolated on its mesh (beyond the mesh it falls like 1/r, the far field of a load).
   type :: separation_field
      logical :: extended = .false.   !< z_max is the Hertz gap (else the rigid gap)
      real(dp) :: delta = 0.0_dp      !< delta_max/sigma
      !> The flow-pressure cap acted on the loading at delta_max (sums_total, force_floor)
      logical :: capped = .false.
      real(dp) :: force = 0.0_dp      !< the loading force at delta_max (scaled)
      type(radial_mesh) :: mesh
      real(dp), allocatable :: w(:)
   end type separation_field

   !> The scaled problem.
   type :: scaled_problem
      integer :: model = model_egw
      real(dp) :: delta = 0.0_dp       !< delta/sigma
      logical :: extended = .false.    !< base gap is the Hertz gap (E-GW/EP-GW, delta > 0)
      real(dp) :: a = 0.0_dp           !< Hertz radius sqrt(delta/sigma) (0 if delta <= 0)
      !> The rough-flat law of loading, in scaled units (GW's, or a law the caller gave).
      class(flat_law), allocatable :: law
      !> EP-GW unloading: mu/(2 sqrt 2), p = scale Z_u(h, h_min), and the ZMC parameters.
      real(dp) :: scale = 0.0_dp
      real(dp) :: psi = 0.0_dp, hardness = 0.6_dp, plastic_ratio = 54.0_dp
      !> Unloading: the closest approach so far (allocated), else the loading law.
      type(separation_field), allocatable :: closest
      !> Unloading: Z_u of psi, K, rho_p prepared once per solve (unloading_law_of).
      type(unloading_law) :: unload
      !> Unloading: radii where d crosses d_max (the law switches branch; the first
      !> n_branch) and where d - d_max crosses a kink of Z_u in Delta: element edges.
      real(dp), allocatable :: branch(:)
      integer :: n_branch = 0
      !> Unloading: an element edge at the loading Hertz edge sqrt(delta_max) (the onset of
      !> d_max); dropped where the locating solve's pressure there is negligible.
      logical :: amax_edge = .true.
      !> The flow-pressure cap (params%flow_pressure > 0; doc/theory.md §12 "Rough spheres
      !> with the cap"), applied to the law in one place: rough_pressure.
      type(flow_cap), allocatable :: cap
      !> Loading with the cap on the guided route (egw_sphere_solver's guided_cap_solve,
      !> small sigma/delta_y): geometric layers on both sides of each cap edge (branch)
      !> down to this width; 0: none (the default route).
      real(dp) :: kink_width = 0.0_dp
      !> Unloading after a capped loading, deep in the cap: the history's outermost
      !> plastic-zone edge (the rim, where the unloading contact ends in a layer), an
      !> element edge with geometric layers down to rim_width (first_unloading_level);
      !> 0: none.
      real(dp) :: rim = 0.0_dp, rim_width = 0.0_dp
      !> Unloading after a capped loading, the central-disc route (egw_sphere_solver's
      !> disc_cap_unload): the elements inside the innermost kink edge shrink with the
      !> level's step relative to that radius (sphere_mesh's disc_refined); .false.: the
      !> default route.
      logical :: refine_disc = .false.
      !> Unloading after a capped loading, the history-edges route (egw_sphere_solver's
      !> history_cap_unload): the element edges of the history's mesh (closest%mesh) are
      !> element edges of every level (sphere_mesh's with_history_edges).
      logical :: history_edges = .false.
      !> Unloading after a capped loading whose contact is a central disc far inside the
      !> Hertz radius (egw_sphere_refine's central_disc): its radius, about which the
      !> elements inside it are graded on every level (sphere_mesh's disc_graded); 0: none.
      real(dp) :: disc = 0.0_dp
      !> Scaled residual at which Newton stops (looser only for the unloading's locating
      !> solve, see first_unloading_level).
      real(dp) :: residual_tol = 1.0e-11_dp
   end type scaled_problem


   !> A converged discrete solution and what is derived from it (scaled units, rough part).
   type :: discrete_solution
      type(radial_mesh) :: mesh
      real(dp), allocatable :: infl(:, :)        !< nodes x Gauss points
      real(dp), allocatable :: w(:)              !< nodal rough deflection
      real(dp), allocatable :: base(:), dbase(:) !< base gap and d(base)/d(delta) at Gauss pts
      real(dp), allocatable :: gap(:), p(:), dpdh(:)  !< at the Gauss points
      real(dp), allocatable :: gap_min(:)  !< closest-approach gap at the Gauss points (unloading)
      !> With the cap (allocated then, at the Gauss points): smooth pressure p_s and its
      !> delta-derivative, the plastic gap shift and pressure offset (unloading), and
      !> dp/d(delta) of the rough part at fixed gap.
      real(dp), allocatable :: p_smooth(:), dps(:), shift(:), offset(:), dpdd(:)
      !> Unloading with the cap (else not allocated), for cap_excess_points: the loading
      !> law at gap_min (cap_fields; flow_cap's not_evaluated, above p_y, deep in the
      !> plastic zone where the kink scan needs no value), and the total unloading pressure
      !> before its floor at the gaps of the last evaluation (rough_pressure's unfloored,
      !> as gap).
      real(dp), allocatable :: law_min(:), unfloored(:)
      real(dp) :: force = 0.0_dp, dforce = 0.0_dp, moment0 = 0.0_dp, moment1 = 0.0_dp
      real(dp) :: residual = 0.0_dp, tail = 0.0_dp
      integer :: iterations = 0
      !> LU factors (lu_factor) of the last Jacobian Newton factored, near the solution; not
      !> allocated after Picard.
      real(dp), allocatable :: lu(:, :)
      integer, allocatable :: pivots(:)
   end type discrete_solution

   public :: separation_field, scaled_problem, discrete_solution
   public :: scaled, deep_unloading, normal, negligible, base_gap, base_gap_rate, closest_gap, law_at, &
      & estimated_gap, law_inverse, gauss_values, gauss_gap, effective_radius, total_pressure, &
      & smooth_force, smooth_stiffness, rough_pressure, cap_fields, cap_excess, &
      & cap_excess_points, sums_total, force_floor, cap_never_acts

contains

   !> Gap at the closest approach, d_max(r)/sigma, at scaled radii r >= 0.
   pure function closest_gap(field, r) result(gap)
      type(separation_field), intent(in) :: field   !< the closest approach's deflection
      real(dp), intent(in) :: r(:)   !< scaled radii, >= 0
      real(dp) :: gap(size(r))
      real(dp) :: r_out, w_out
      integer :: i
      r_out = field%mesh%edge(field%mesh%n_elem)
      w_out = field%w(size(field%w))
      ! (a value beyond r_out is replaced below)
      call interpolate_nodal_walk(field%mesh, field%w, min(r, r_out), gap)
      do i = 1, size(r)
         ! Beyond the loading mesh the pressure was negligible: the deflection is that
         ! of a point load there, continued from the outer radius.
         if (r(i) > r_out) gap(i) = w_out*r_out/r(i)
         if (field%extended) then
            gap(i) = gap(i) + hertz_gap(r(i), field%delta, 1.0_dp)
         else
            gap(i) = gap(i) + 0.5_dp*r(i)*r(i) - field%delta
         end if
      end do
   end function closest_gap

   !> The scaled problem of params at overlap delta (sigma > 0). loading: GW's ZMC law of
   !> params tabulated once (zmc_law_pieces), the problem's law where its parameters are
   !> params' (else GW's law as without it).
   pure function scaled(params, delta, loading) result(prob)
      type(contact_params), intent(in) :: params   !< validated, sigma > 0
      real(dp), intent(in) :: delta   !< overlap [length]
      type(law_pieces), intent(in), optional :: loading   !< the tabulated loading law
      type(scaled_problem) :: prob
      prob%model = params%model
      prob%delta = delta/params%sigma
      ! A subnormal delta/sigma is 0 to the solver's precision (the Hertz part, ~x**1.5,
      ! underflows), and its Hertz edge at sqrt(x) would put elements of subnormal size
      ! into the mesh: solve at 0 (continuous: at x = 1e-300 the force equals P(0)).
      if (abs(prob%delta) < tiny(1.0_dp)) prob%delta = 0.0_dp
      prob%a = sqrt(max(prob%delta, 0.0_dp))
      prob%extended = (params%model == model_egw .or. params%model == model_epgw) .and. &
         & prob%delta > 0.0_dp
      prob%scale = params%mu/(2.0_dp*sqrt2)
      prob%psi = 0.0_dp
      if (params%model == model_epgw) prob%psi = params%psi
      prob%hardness = params%hardness_coeff
      prob%plastic_ratio = params%plastic_ratio
      if (tabulated(prob, loading)) then
         allocate (prob%law, source=zmc_table_law(scale=prob%scale, pieces=loading))
      else
         allocate (prob%law, source=gw_flat_law(scale=prob%scale, psi=prob%psi, &
            & hardness_coeff=prob%hardness, plastic_ratio=prob%plastic_ratio))
      end if
      if (params%flow_pressure > 0.0_dp) then
         prob%cap = flow_cap(p_y=params%flow_pressure/pressure_unit(params))
         call prob%cap%prepare(prob%law)
      end if
   end function scaled

   !> loading (params' tabulated ZMC law, zmc_law_pieces) with its unloading law at the
   !> deep plastic zone's closest approach (egw_unloading's tabulate_unloading): h_y, the
   !> root of the cap prepared on the tabulated law, as every unloading problem of params
   !> made with loading prepares it (scaled), so that their deep points' shifted h_min is
   !> h_y to rounding. Unchanged without a cap, a root, or a tabulated law.
   pure subroutine deep_unloading(params, loading)
      type(contact_params), intent(in) :: params   !< validated, sigma > 0
      type(law_pieces), intent(inout) :: loading   !< from zmc_law_pieces for params
      type(scaled_problem) :: prob
      if (.not. params%flow_pressure > 0.0_dp) return
      prob = scaled(params, params%sigma, loading)
      if (.not. tabulated(prob, loading)) return
      if (.not. prob%cap%yield_known) return
      call tabulate_unloading(loading, prob%cap%h_yield)
   end subroutine deep_unloading

   !> Whether loading is present, tabulated, and the ZMC law of prob's psi (> 0), K, rho_p.
   pure logical function tabulated(prob, loading)
      type(scaled_problem), intent(in) :: prob
      type(law_pieces), intent(in), optional :: loading
      tabulated = .false.
      if (.not. present(loading)) return
      tabulated = prob%psi > 0.0_dp .and. loading%n > 0 .and. &
         & abs(loading%psi - prob%psi) <= 0.0_dp .and. &
         & abs(loading%hardness_coeff - prob%hardness) <= 0.0_dp .and. &
         & abs(loading%plastic_ratio - prob%plastic_ratio) <= 0.0_dp
   end function tabulated

   !> Scaled pressure of the loading law at one scaled separation h, and its derivative.
   pure subroutine law_at(prob, h, p, dpdh)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      real(dp), intent(in) :: h   !< scaled separation
      real(dp), intent(out) :: p, dpdh   !< scaled pressure and dp/dh
      real(dp) :: pa(1), da(1)
      call prob%law%pressure([h], pa, da)
      p = pa(1)
      dpdh = da(1)
   end subroutine law_at

   !> Whether x is a normal double (finite, nonzero, not subnormal).
   elemental logical function normal(x)
      real(dp), intent(in) :: x   !< any double
      normal = abs(x) >= tiny(1.0_dp) .and. abs(x) <= huge(1.0_dp)
   end function normal

   !> True when the spheres are so far apart that the summit pressure underflows.
   elemental logical function negligible(prob)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      real(dp) :: f, dfdh
      negligible = .false.
      if (prob%delta >= 0.0_dp) return
      call law_at(prob, -prob%delta, f, dfdh)
      negligible = f < tiny_force
   end function negligible

   !> Base gap z(r): the Hertz gap of eq. (28) (zero inside a) for the extended models at
   !> delta > 0, else the rigid gap r**2/2 - delta (classic GW, eq. 10).
   elemental real(dp) function base_gap(prob, r) result(z)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      real(dp), intent(in) :: r   !< scaled radius, >= 0
      if (prob%extended) then
         z = hertz_gap(r, prob%delta, 1.0_dp)
      else
         z = 0.5_dp*r*r - prob%delta
      end if
   end function base_gap

   !> d z / d delta at fixed r: Hertz gives d w_H/d delta = 1 inside a and
   !> (2/pi) asin(a/r) outside (the flat-punch field), so dz/d delta = 0 inside.
   elemental real(dp) function base_gap_rate(prob, r) result(dz)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      real(dp), intent(in) :: r   !< scaled radius, >= 0
      if (prob%extended) then
         if (r <= prob%a) then
            dz = 0.0_dp
         else
            dz = 2.0_dp/pi*asin(prob%a/r) - 1.0_dp
         end if
      else
         dz = -1.0_dp
      end if
   end function base_gap_rate

   !> Gap estimate before solving: the Hertz gap (extended models, and classic GW at
   !> delta > 0 whose gap is close to it) or the rigid gap.
   elemental real(dp) function estimated_gap(prob, r) result(z)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      real(dp), intent(in) :: r   !< scaled radius, >= 0
      if (prob%delta > 0.0_dp) then
         z = hertz_gap(r, prob%delta, 1.0_dp)
      else
         z = 0.5_dp*r*r - prob%delta
      end if
   end function estimated_gap

   !> h with p(h) = target (the scaled law, decreasing) by bisection: a bracket about
   !> [-2, 40] (GW's law underflows at 40), widened until it holds the target.
   pure real(dp) function law_inverse(prob, target) result(h)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      real(dp), intent(in) :: target   !< scaled pressure, > 0
      real(dp) :: lo, hi, f, dfdh
      integer :: i
      lo = -2.0_dp
      hi = 40.0_dp
      do i = 1, 60
         call law_at(prob, lo, f, dfdh)
         if (f > target) exit
         lo = 2.0_dp*lo
      end do
      do i = 1, 60
         call law_at(prob, hi, f, dfdh)
         if (.not. f > target) exit
         hi = 2.0_dp*hi
      end do
      do i = 1, 200
         h = 0.5_dp*(lo + hi)
         if (.not. (h > lo .and. h < hi)) exit
         call law_at(prob, h, f, dfdh)
         if (f > target) then
            lo = h
         else
            hi = h
         end if
      end do
   end function law_inverse

   !> Nodal field -> values at the Gauss points (element-wise Lagrange interpolation).
   pure function gauss_values(mesh, v) result(vg)
      type(radial_mesh), intent(in) :: mesh   !< a built mesh
      real(dp), intent(in) :: v(:)   !< nodal values, one per mesh node
      real(dp) :: vg(size(mesh%gauss_r))
      integer :: e, q, i0, j0
      do e = 1, mesh%n_elem
         i0 = (e - 1)*mesh%n_gauss
         j0 = node_index(mesh, e, 0)
         do q = 1, mesh%n_gauss
            vg(i0 + q) = dot_product(mesh%interp(:, q), v(j0:j0 + mesh%degree))
         end do
      end do
   end function gauss_values

   !> gap = base + gauss_values(mesh, v), the same arithmetic without gauss_values's
   !> temporary (a heap array: the Newton evaluations' malloc/free were ~5 % of a
   !> hysteresis build).
   pure subroutine gauss_gap(mesh, v, base, gap)
      type(radial_mesh), intent(in) :: mesh   !< a built mesh
      !> nodal deflection, and the base gap at the Gauss points
      real(dp), intent(in) :: v(:), base(:)
      real(dp), intent(out) :: gap(:)   !< size(mesh%gauss_r)
      integer :: e, q, i0, j0
      do e = 1, mesh%n_elem
         i0 = (e - 1)*mesh%n_gauss
         j0 = node_index(mesh, e, 0)
         do q = 1, mesh%n_gauss
            gap(i0 + q) = base(i0 + q) + dot_product(mesh%interp(:, q), &
               & v(j0:j0 + mesh%degree))
         end do
      end do
   end subroutine gauss_gap

   !> Effective contact radius a* = (3 pi/4) int r p dr / int p dr of the total pressure
   !> (scaled); the Hertz part has int r p_H dr = P_H/(2 pi), int p_H dr = a**2/2.
   pure real(dp) function effective_radius(prob, sol) result(a_eff)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(discrete_solution), intent(in) :: sol   !< its solution
      real(dp) :: m0, m1
      m0 = sol%moment0
      m1 = sol%moment1
      if (prob%extended) then
         m0 = m0 + 0.5_dp*prob%a**2
         m1 = m1 + hertz_force(prob%delta, 1.0_dp, 1.0_dp)/(2.0_dp*pi)
      end if
      a_eff = 0.0_dp
      if (m0 > 0.0_dp) a_eff = 0.75_dp*pi*m1/m0
   end function effective_radius

   !> Total scaled pressure at r from the solved deflection (influence row, exact for the
   !> discrete pressure).
   pure real(dp) function total_pressure(prob, sol, r) result(p)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(discrete_solution), intent(in) :: sol   !< its solution
      real(dp), intent(in) :: r   !< scaled radius, >= 0
      real(dp) :: row(size(sol%p)), gap_min(1), pr(1), dpdh(1), dpdd(1)
      real(dp), allocatable :: p_smooth(:), dps(:), shift(:), offset(:)
      call influence_row(sol%mesh, r, row)
      gap_min = 0.0_dp
      if (allocated(prob%closest)) gap_min = closest_gap(prob%closest, [r])
      if (allocated(prob%cap)) call cap_fields(prob, [r], gap_min, p_smooth, dps, shift, &
         & offset)
      call rough_pressure(prob, [base_gap(prob, r) + dot_product(row, sol%p)], gap_min, &
         & p_smooth, dps, shift, offset, pr, dpdh, dpdd)
      p = pr(1)
      if (prob%extended) p = p + hertz_pressure(r, prob%delta, 1.0_dp, 1.0_dp)
   end function total_pressure

   !> The rough part of the pressure and dp/dh at gaps h: the loading law, or (prob%closest
   !> allocated) the unloading law at the closest-approach gaps h_min; with the cap
   !> (prob%cap) the loading law capped (flow_cap%apply) or the unloading law at the
   !> shifted gaps h + shift, h_min + shift less the offset, the total kept >= 0
   !> (doc/theory.md §12 "Rough spheres with the cap"). dpdd: dp/d(delta) at fixed h (0
   !> without the cap). The one place the solver evaluates its pressure law. The cap
   !> fields (p_smooth .. offset, from cap_fields) are only read when prob%cap is allocated.
   pure subroutine rough_pressure(prob, h, h_min, p_smooth, dps, shift, offset, p, dpdh, dpdd, &
      & unfloored)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      real(dp), intent(in) :: h(:), h_min(:)   !< gaps and closest-approach gaps (scaled)
      !> the cap's fields at the same points (cap_fields)
      real(dp), allocatable, intent(in) :: p_smooth(:), dps(:), shift(:), offset(:)
      !> the rough pressure, dp/dh and dp/d(delta), scaled
      real(dp), intent(out) :: p(:), dpdh(:), dpdd(:)
      !> unloading with the cap: p_s + the rough pressure before the floor (cap_excess's
      !> kind 1, the same expression), else left as it is
      real(dp), intent(inout), optional :: unfloored(:)
      dpdd = 0.0_dp
      if (allocated(prob%closest)) then
         if (allocated(prob%cap)) then
            call unloading_pressure(prob%unload, h + shift, h_min + shift, p, dpdh)
            if (present(unfloored)) unfloored = p_smooth + prob%scale*p - offset
            p = prob%scale*p - offset
            dpdh = prob%scale*dpdh
            call prob%cap%unload_floor(p_smooth, dps, p, dpdh, dpdd)
         else
            call unloading_pressure(prob%unload, h, h_min, p, dpdh)
            p = prob%scale*p
            dpdh = prob%scale*dpdh
         end if
      else
         call prob%law%pressure(h, p, dpdh)
         if (allocated(prob%cap)) call prob%cap%apply(p_smooth, dps, p, dpdh, dpdd)
      end if
   end subroutine rough_pressure

   !> The cap's fields at radii r (prob%cap allocated): the smooth pressure p_s at delta
   !> and its delta-derivative (Hertz for the extended models, else 0); unloading (gap_min:
   !> the closest-approach gaps at r) the plastic gap shift and pressure offset from the
   !> loading at delta_max (flow_cap%plastic_shift), else 0.
   pure subroutine cap_fields(prob, r, gap_min, p_smooth, dps, shift, offset, law_min, known)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem, with the cap
      real(dp), intent(in) :: r(:), gap_min(:)   !< scaled radii and the closest-approach gaps there
      !> p_s, dp_s/d(delta), gap shift and pressure offset at r
      real(dp), allocatable, intent(out) :: p_smooth(:), dps(:), shift(:), offset(:)
      !> unloading: the loading law at gap_min (not allocated when loading; not_evaluated
      !> deep in the plastic zone, flow_cap's plastic_shifts); in: its values where known
      !> (from an earlier mesh's same points)
      real(dp), allocatable, intent(inout), optional :: law_min(:)
      logical, intent(in), optional :: known(:)   !< where law_min is given (size(r))
      real(dp), allocatable :: ps_max(:)
      p_smooth = 0.0_dp*r
      dps = 0.0_dp*r
      shift = 0.0_dp*r
      offset = 0.0_dp*r
      if (prob%extended) then
         p_smooth = hertz_pressure(r, prob%delta, 1.0_dp, 1.0_dp)
         ! p_s = (2/pi) sqrt(delta - r**2): d p_s/d delta = (1/pi)/sqrt(delta - r**2)
         where (p_smooth > 0.0_dp) dps = 2.0_dp/(pi*pi*p_smooth)
      end if
      if (.not. allocated(prob%closest)) then
         if (present(law_min)) then
            if (allocated(law_min)) deallocate (law_min)
         end if
         return
      end if
      ps_max = 0.0_dp*r
      if (prob%closest%extended) ps_max = hertz_pressure(r, prob%closest%delta, 1.0_dp, &
         & 1.0_dp)
      if (present(law_min)) then
         if (allocated(law_min)) then
            if (size(law_min) /= size(r)) deallocate (law_min)
         end if
         if (.not. allocated(law_min)) then
            allocate (law_min(size(r)))
            call prob%cap%plastic_shifts(prob%law, ps_max, gap_min, shift, offset, law_min)
         else if (present(known)) then
            call prob%cap%plastic_shifts(prob%law, ps_max, gap_min, shift, offset, law_min, &
               & known)
         else
            call prob%cap%plastic_shifts(prob%law, ps_max, gap_min, shift, offset, law_min)
         end if
      else
         call prob%cap%plastic_shifts(prob%law, ps_max, gap_min, shift, offset)
      end if
   end subroutine cap_fields

   !> Whether the cap never acts on an unloading from field (its loading uncapped there): at
   !> every r the unloading's cap fields (cap_fields) would be 0, since the loading total
   !> p_s(delta_max, r) + law(d_max(r)) stays at or below p_y, so that cap_plastic_shifts
   !> gives no shift and no offset, the rough part (Z_u >= 0) never meets the floor, and
   !> the unloading with the cap solves the cap-free equations. Decided from a bound, not
   !> from points: on each element of the field's mesh d_max >= its smallest nodal w less
   !> lagrange_undershoot times the nodal range, plus the base gap at the element's inner
   !> edge (increasing in r), p_s at most its value there (decreasing), and the law
   !> decreasing in the gap; beyond the mesh d_max >= min(w_out, 0) + the base gap at its
   !> edge. False if any bound reaches p_y (less a rounding margin), the cap is absent
   !> or the field was capped.
   pure logical function cap_never_acts(prob, field) result(free)
      type(scaled_problem), intent(in) :: prob   !< a problem of the field's params, with the cap
      type(separation_field), intent(in) :: field   !< a loading's field at delta_max
      real(dp), allocatable :: gap_low(:), ps_max(:), r0(:), p(:), dpdh(:)
      real(dp), allocatable :: v(:)
      integer :: e, n
      free = .false.
      if (.not. allocated(prob%cap) .or. field%capped .or. .not. allocated(field%w)) return
      if (field%mesh%degree /= deflection_degree .or. field%mesh%n_elem < 1) return
      n = field%mesh%n_elem
      allocate (gap_low(n + 1), r0(n + 1))
      do e = 1, n
         v = field%w(node_index(field%mesh, e, 0):node_index(field%mesh, e, &
            & field%mesh%degree))
         gap_low(e) = minval(v) - lagrange_undershoot*(maxval(v) - minval(v))
         r0(e) = field%mesh%edge(e - 1)
      end do
      gap_low(n + 1) = min(field%w(size(field%w)), 0.0_dp)
      r0(n + 1) = field%mesh%edge(n)
      if (field%extended) then
         gap_low = gap_low + hertz_gap(r0, field%delta, 1.0_dp)
         ps_max = hertz_pressure(r0, field%delta, 1.0_dp, 1.0_dp)
      else
         gap_low = gap_low + 0.5_dp*r0*r0 - field%delta
         ps_max = 0.0_dp*r0
      end if
      allocate (p(n + 1), dpdh(n + 1))
      call prob%law%pressure(gap_low, p, dpdh)
      ! (a margin for the rounding of p_s and of the law between the bound and the points)
      free = all(p + ps_max <= (1.0_dp - 1.0e-12_dp)*prob%cap%p_y)
   end function cap_never_acts

   !> Where p(r) has a kink from the cap, the sign of this changes (prob%cap allocated;
   !> gap: the solution's gap at r): loading (kind 1) p_s + law(gap) - p_y, the cap edge;
   !> unloading kind 1, the total unloading pressure before its floor at 0, kind 2,
   !> law(d_max) - (p_y - p_s(delta_max)), the cap edge at delta_max where the offset
   !> starts, and kind 3, law(d_max) - p_y, where the gap shift starts (flow_cap's
   !> plastic_shift: t = min(p_y, law(d_max))). 1 where a kind does not apply.
   pure real(dp) function cap_excess(prob, r, gap, kind) result(excess)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem, with the cap
      real(dp), intent(in) :: r, gap   !< scaled radius and the solution's gap there
      integer, intent(in) :: kind   !< 1, 2 or 3, as above
      real(dp) :: gm(1), p(1), dpdh(1), ps_max
      real(dp), allocatable :: p_smooth(:), dps(:), shift(:), offset(:)
      excess = 1.0_dp
      if (.not. allocated(prob%closest)) then
         if (kind /= 1) return
         call prob%law%pressure([gap], p, dpdh)
         ps_max = 0.0_dp   ! (here: p_s at delta)
         if (prob%extended) ps_max = hertz_pressure(r, prob%delta, 1.0_dp, 1.0_dp)
         excess = ps_max + p(1) - prob%cap%p_y
         return
      end if
      gm = closest_gap(prob%closest, [r])
      ! (the plastic shift, a root of the law, only where kind 1 needs it)
      if (kind == 1) call cap_fields(prob, [r], gm, p_smooth, dps, shift, offset)
      if (kind == 1) then
         call unloading_pressure(prob%unload, gap + shift(1), gm(1) + shift(1), p(1), dpdh(1))
         excess = p_smooth(1) + prob%scale*p(1) - offset(1)
      else
         ps_max = 0.0_dp
         if (prob%closest%extended .and. kind == 2) ps_max = hertz_pressure(r, &
            & prob%closest%delta, 1.0_dp, 1.0_dp)
         call prob%law%pressure(gm, p, dpdh)
         excess = p(1) - (prob%cap%p_y - ps_max)
      end if
   end function cap_excess

   !> cap_excess of the kinds 1 to 3 at every Gauss point of sol, at sol's gaps: from the
   !> cap fields the solve keeps there (gap_min, p_smooth, shift, offset: the plastic shift
   !> is a root of the law, and closest_gap an interpolation on the history's mesh, which
   !> the point-by-point cap_excess repeated for each kind at every level of a solve), the
   !> law at gap_min once for kinds 2 and 3; else point by point. The same formulas as
   !> cap_excess. A solve's unloading mesh keeps both (law_min from cap_fields, unfloored
   !> from its last evaluation), so that this evaluates no law at all.
   pure subroutine cap_excess_points(prob, sol, excess)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem, with the cap
      type(discrete_solution), intent(in) :: sol   !< a solution
      real(dp), intent(out) :: excess(:, :)   !< (Gauss points of sol, kind 1:3)
      real(dp) :: p(size(excess, 1)), dpdh(size(excess, 1)), ps_max(size(excess, 1))
      integer :: g, n, kind
      logical :: kept
      n = size(excess, 1)
      kept = allocated(prob%closest) .and. allocated(sol%gap_min) .and. &
         & allocated(sol%shift) .and. allocated(sol%offset) .and. allocated(sol%p_smooth)
      if (kept) kept = size(sol%gap_min) == n .and. size(sol%shift) == n .and. &
         & size(sol%offset) == n .and. size(sol%p_smooth) == n .and. size(sol%gap) == n
      if (kept .and. allocated(sol%unfloored) .and. allocated(sol%law_min)) then
         if (size(sol%unfloored) == n .and. size(sol%law_min) == n) then
            ! both kept by the solve (evaluate, cap_fields): no law evaluation here
            excess(:, 1) = sol%unfloored
            ps_max = 0.0_dp
            if (prob%closest%extended) ps_max = hertz_pressure(sol%mesh%gauss_r, &
               & prob%closest%delta, 1.0_dp, 1.0_dp)
            excess(:, 2) = sol%law_min - (prob%cap%p_y - ps_max)
            excess(:, 3) = sol%law_min - prob%cap%p_y
            return
         end if
      end if
      if (.not. kept) then
         do kind = 1, 3
            do g = 1, n
               excess(g, kind) = cap_excess(prob, sol%mesh%gauss_r(g), sol%gap(g), kind)
            end do
         end do
         return
      end if
      call unloading_pressure(prob%unload, sol%gap + sol%shift, sol%gap_min + sol%shift, &
         & p, dpdh)
      excess(:, 1) = sol%p_smooth + prob%scale*p - sol%offset
      ps_max = 0.0_dp
      if (prob%closest%extended) ps_max = hertz_pressure(sol%mesh%gauss_r, &
         & prob%closest%delta, 1.0_dp, 1.0_dp)
      call prob%law%pressure(sol%gap_min, p, dpdh)
      excess(:, 2) = p - (prob%cap%p_y - ps_max)
      excess(:, 3) = p - prob%cap%p_y
   end subroutine cap_excess_points

   !> Scaled Hertz force of the smooth part (extended models only; 0 where the solution's
   !> force holds it, sums_total).
   pure real(dp) function smooth_force(prob) result(force)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      force = 0.0_dp
      if (prob%extended .and. .not. sums_total(prob)) force = hertz_force(prob%delta, &
         & 1.0_dp, 1.0_dp)
   end function smooth_force

   !> Unloading of an extended model after a capped loading: the force is the Gauss sum
   !> of the total pressure p_s + p (discrete_solution%force holds the Hertz part too).
   !> Where the total sits at its floor 0 the rough part is -p_s, and near the residual
   !> overlap the force would be the small difference of the Hertz force and that sum:
   !> summed as the total pressure (0 there) neither the force nor the levels' difference
   !> carries the cancellation. Elsewhere the Hertz part's closed form is kept (more
   !> accurate than its Gauss sum, and the cap-free results stay bit for bit).
   elemental logical function sums_total(prob)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      sums_total = .false.
      if (.not. (allocated(prob%cap) .and. allocated(prob%closest))) return
      sums_total = prob%extended .and. prob%closest%capped
   end function sums_total

   !> The force below which an unloading solve after a capped loading bounds
   !> its error absolutely, by rel_tol times this: 1e-6 of the loading force at
   !> delta_max. Near and below the residual overlap the force falls to 1e-10 .. 1e-80 of
   !> it (the unloaded summits' Gaussian tail) where its relative error cannot be resolved
   !> (a sum of the total pressure whose terms are 1e6 times larger); an impact's work
   !> integrals need it to rel_tol of their whole. 0 (relative errors) elsewhere.
   elemental real(dp) function force_floor(prob) result(floor)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      floor = 0.0_dp
      if (.not. (allocated(prob%cap) .and. allocated(prob%closest))) return
      if (prob%closest%capped) floor = 1.0e-6_dp*abs(prob%closest%force)
   end function force_floor

   !> Scaled Hertz stiffness of the smooth part (extended models only).
   pure real(dp) function smooth_stiffness(prob) result(stiffness)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      stiffness = 0.0_dp
      if (prob%extended) stiffness = hertz_stiffness(prob%delta, 1.0_dp, 1.0_dp)
   end function smooth_stiffness

end module egw_sphere_problem
