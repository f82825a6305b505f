!> The flow-pressure cap for a smooth elastic sphere (doc/theory.md §12): frictionless
!> axisymmetric contact with an elastic-perfectly-plastic half-space whose contact pressure
!> may not exceed p_y (Thornton 1997). Loading to delta_max, elastic unloading/reloading from
!> the deformed shape, and the restitution of a head-on impact.
!>
!> Universal units: delta_y = (pi p_y/(2 E*))**2 R (Hertz p_max = p_y), a_y = sqrt(R delta_y),
!> P_y = (4/3) E* sqrt(R) delta_y**1.5, pressures in p_y. Then gap = rho**2/2 - Delta + w,
!> w(rho) = (2/pi) int 4/pi t/(rho+t) K(k) p(t) dt and P/P_y = 3 int rho p drho.
!>
!> Method: the edges are in the mesh, so that nothing jumps as Delta moves. Loading: p = 1
!> on the capped disc [0, c] (one element, its influence exact), unknown constant-pressure
!> rings on the elastic annulus [c, a] whose edges are fixed fractions of it (graded toward
!> both ends), collocated at their midpoints (gap = 0) with egw_halfspace's influence
!> coefficients (n_press Gauss points per element, summed: a constant pressure's far field
!> to ~1e-8). For given (c, a) the rings' pressure is linear in Delta, and the force
!> P(c, a; Delta) of the contact forced onto [c, a] is stationary at the solution in both:
!> dP/da = 0 is the edge's zero stress intensity (p ~ sqrt(a - rho)), dP/dc = 0 the
!> cap edge's (1 - p ~ sqrt(rho - c)), both linear in them (so single roots; the energy
!> would have double ones). At fixed gamma = c/a, dP/da = 0 is a quadratic in a (closed
!> form); in gamma a Newton iteration on finite differences of P*(gamma) (a minimum: the
!> cap takes pressure away). A stationary P
!> is second-order insensitive to gamma's error, and every quantity is a smooth function
!> of (gamma, a, Delta): P, a, c and the stiffness dP/dDelta = dP/dDelta at fixed
!> (gamma, a) (the envelope) are smooth in Delta. The plastic displacement u_pl = -gap on
!> [0, c] is kept as a Chebyshev series in s = sqrt(1 - rho/c) (u_pl ~ (c - rho)**1.5 at
!> the cap edge is smooth in s), made to vanish at c with zero slope.
!> Unloading from the deformed shape f(rho) = rho**2/2 + u_pl(rho) (f increases, so the
!> contact is a disc [0, b]): rings on [0, b] at fixed fractions of b (graded toward b),
!> whose influence matrix is b times one fixed matrix; collocation makes P(b; Delta) =
!> 3 b (Delta r1 - v.f(b x)) with v = H^-T area, and dP/db = 0 gives Delta(b) in closed
!> form: a root in b per solve, no matrix. The residual overlap is f(0) = u_pl(0).
!> The elastic edge a - c shrinks exponentially with Delta (1e-7 a at 32 delta_y); beyond
!> ~35 delta_y the solve is the fully capped limit in closed form (see t_cap), and up to
!> 1.0001 delta_y Hertz's (see elastic_margin).
!> Accuracy: levels of n, 2n ... rings; the finest is solved and the level before for the
!> error estimate (loading: at the finest's gamma). Measured at 32/64 rings (the public
!> doors' options): every row of test/data/cap_reference.csv (loading, residual,
!> unloading, restitution; 1 to 100 delta_y) within 3.3e-6; P, a, the residual and
!> the unloading force are smooth in delta and delta_max (test_cap_sphere).
!>
!> Limits: half-space theory; from ~50 v_y (Delta_max of several hundred) a/R > 0.24, where
!> a sphere is no longer a half-space. u_pl is the deformation-theory field at delta_max
!> (the cap problem at delta_max); for a smooth sphere the capped zone grows with delta,
!> so it equals the accumulated plastic displacement of a monotone loading.
!>
!> The profiles p(r), w(r) of these solves: egw_cap_profile (cap_profile.f90).
module egw_cap_sphere
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, fatal_error, format_real, int_str, &
      & egw_invalid_argument, egw_not_converged
   use egw_halfspace, only: radial_mesh, build_mesh, assemble_influence, influence_row
   use egw_lapack, only: dgetrf, dgetrs
   use egw_ellip, only: ellipe_comp, ellipk_comp
   use egw_cap_start, only: cap_start_logit
   implicit none
   private

   public :: cap_options, cap_result, cap_history
   public :: cap_load, cap_unload, cap_restitution, cap_units
   public :: cap_load_scaled_work, cap_unload_scaled_work, cap_residual
   ! for egw_cap_profile (the profiles of these solves: the rings of a loading solve, the
   ! plastic field and the unloading rings of a history)
   public :: n_press, elastic_margin, fitted_load, check_inputs, gamma_start, load_fitted, &
      & u_plastic, keep_unloading, toward_one

   !> Gauss points per element of the influence integrals of a constant pressure
   integer, parameter :: n_press = 4
   !> Chebyshev points per panel of u_pl's series, and most panels
   integer, parameter :: n_cheb = 16, max_panels = 12

   !> Mesh and iteration options of the cap solver.
   type :: cap_options
      integer :: n_rings = 100      !< rings of the coarsest level (>= 8)
      integer :: n_levels = 2       !< levels n, 2n, 4n ... (>= 2; the last two are used)
      integer :: max_active = 60    !< Newton iterations on the cap radius (>= 1)
      integer :: max_sweeps = 200000 !< (unused; kept for the interface)
      integer :: n_quad = 16        !< Gauss points of the work integrals
   end type cap_options

   !> A solve's result in the caller's units.
   type :: cap_result
      real(dp) :: force = 0.0_dp           !< P
      real(dp) :: stiffness = 0.0_dp       !< dP/d delta (loading: along the loading curve)
      real(dp) :: contact_radius = 0.0_dp  !< a, the contact's edge (p = 0 beyond)
      !> a* = (3 pi/4) int r p dr / int p dr, the rough solver's contact radius (= a for
      !> Hertz, 3 pi a/8 for the fully capped disc): the sigma -> 0 limit of a rough + cap
      !> solve's, which the small-sigma route extrapolates to
      real(dp) :: effective_radius = 0.0_dp
      real(dp) :: cap_radius = 0.0_dp      !< radius of the capped (plastic) zone
      real(dp) :: max_pressure = 0.0_dp    !< max p (<= p_y)
      real(dp) :: force_error = 0.0_dp     !< estimate: |P(finest) - P(level before)|
   end type cap_result

   !> What unloading needs of a loading to delta_max (scaled units).
   type :: cap_history
      real(dp) :: radius = 0, modulus = 0, flow_pressure = 0
      real(dp) :: delta_y = 0, a_y = 0, force_y = 0
      real(dp) :: delta_max = 0            !< scaled Delta_max
      real(dp) :: residual = 0             !< scaled residual overlap Delta_res
      real(dp) :: contact = 0              !< scaled contact radius a at delta_max
      real(dp) :: cap = 0                  !< scaled cap radius c at delta_max
      real(dp) :: disc = 0                 !< the radius of p = 1 of the same force, sqrt(2P/3)
      logical :: elastic = .true.          !< Delta_max <= 1: Hertz, reversible
      !> g's Chebyshev coefficients (see u_plastic) on the panels [s_break(j-1), s_break(j)]
      real(dp) :: u_cheb(0:n_cheb - 1, max_panels) = 0
      real(dp) :: s_break(0:max_panels) = 0
      integer :: n_panels = 0
      integer :: n_unload(2) = 0           !< unloading rings per level (before, finest)
      real(dp), allocatable :: x_unload(:, :)  !< (ring, level) unit midpoints
      real(dp), allocatable :: v_unload(:, :)  !< H^-T area (ring, level)
      real(dp) :: r_unload(2) = 0          !< sum(v) per level
      real(dp), allocatable :: lu_unload(:, :) !< finest level's LU of H (pressures)
      integer, allocatable :: piv_unload(:)
      type(cap_options) :: options
   end type cap_history


   !> Largest t = ln(c/(a - c)) of the loading solve. The elastic edge a - c shrinks
   !> exponentially with Delta (1e-7 a at 32 delta_y); once the solution's t is beyond
   !> t_cap (a - c < 1.5e-8 a, from ~35 delta_y) the solve is the fully capped limit: p = 1
   !> on [0, a], gap(a) = 0, i.e. Delta = a**2/2 + 8 a/pi**2 (the uniform disc's edge
   !> deflection 4 a/pi in E* = 1 units, times 2/pi), P = 3 a**2/2; the edge's share of P
   !> is of the order of its width, so the switch moves P by ~1e-8.
   real(dp), parameter :: t_cap = 18.0_dp

   !> Up to delta_y (1 + elastic_margin) the solve is Hertz's: there the cap's zone is
   !> ~0.03 a wide and its force differs from Hertz by ~1e-8 (measured at 1.0001 delta_y),
   !> its residual overlap is ~1e-6 delta_y, and the flat minimum in gamma is ill-posed.
   real(dp), parameter :: elastic_margin = 1.0e-4_dp

   !> One fitted loading mesh at gamma = c/a (unit contact radius) and its solution.
   type :: fitted_load
      integer :: m = 0   !< rings on the elastic annulus [gamma, 1]
      !> gamma = c/a, scaled Delta, contact radius a, force P, stiffness dP/dDelta
      real(dp) :: gamma = 0, delta = 0, a = 0, force = 0, stiffness = 0
      !> a*/a = (3 pi/4) int x p dx / int p dx on the unit contact (x = r/a)
      real(dp) :: effective = 0
      !> the capped disc (element 1) and the rings, n_press Gauss points each
      type(radial_mesh) :: mesh
      !> ring midpoints (unit a), the capped disc's deflection there, the rings' influence
      !> matrix H's LU, the rings' pressures (units p_y)
      real(dp), allocatable :: x(:), hc(:), lu(:, :), q(:)
      integer, allocatable :: piv(:)   !< H's pivots
   end type fitted_load

contains

   !> Units of the cap model: delta_y = (pi p_y/(2E))**2 R, a_y, P_y = (4/3)E sqrt(R) delta_y**1.5.
   pure subroutine cap_units(radius, modulus, flow_pressure, delta_y, a_y, force_y)
      !> R [length], E* and p_y [pressure], each > 0
      real(dp), intent(in) :: radius, modulus, flow_pressure
      !> first-yield overlap, its contact radius a_y [length], force P_y
      real(dp), intent(out) :: delta_y, a_y, force_y
      delta_y = (pi*flow_pressure/(2.0_dp*modulus))**2*radius
      a_y = sqrt(radius*delta_y)
      force_y = 4.0_dp/3.0_dp*modulus*sqrt(radius)*delta_y**1.5_dp
   end subroutine cap_units

   !> The checks of every cap solve's input: R, E*, p_y finite and > 0 with p_y < E*, and
   !> options in range (n_rings 8..4000, n_levels 2..5, at most 4000 rings on the finest).
   pure subroutine check_inputs(radius, modulus, flow_pressure, options, error)
      real(dp), intent(in) :: radius, modulus, flow_pressure   !< R [length], E*, p_y
      type(cap_options), intent(in) :: options   !< the cap solver's options
      !> egw_invalid_argument naming the value, when one is refused
      type(egw_error), allocatable, intent(out) :: error
      call positive(radius, "radius", error); if (allocated(error)) return
      call positive(modulus, "modulus", error); if (allocated(error)) return
      call positive(flow_pressure, "flow_pressure", error); if (allocated(error)) return
      if (flow_pressure >= modulus) then
         call fatal_error(error, egw_invalid_argument, "flow_pressure = " &
            & //format_real(flow_pressure)//": must be below the modulus " &
            & //format_real(modulus)//" (a small-strain cap)")
         return
      end if
      if (options%n_rings < 8 .or. options%n_rings > 4000) then
         call fatal_error(error, egw_invalid_argument, "n_rings = " &
            & //int_str(options%n_rings)//": must be in 8..4000")
      else if (options%n_levels < 2 .or. options%n_levels > 5) then
         call fatal_error(error, egw_invalid_argument, "n_levels = " &
            & //int_str(options%n_levels)//": must be in 2..5")
      else if (options%n_rings*2**(options%n_levels - 1) > 4000) then
         call fatal_error(error, egw_invalid_argument, "n_rings*2**(n_levels - 1) = " &
            & //int_str(options%n_rings*2**(options%n_levels - 1))//": must be <= 4000")
      else if (options%max_active < 1 .or. options%max_sweeps < 1) then
         call fatal_error(error, egw_invalid_argument, "max_active, max_sweeps must be >= 1")
      else if (options%n_quad < 4 .or. options%n_quad > 64) then
         call fatal_error(error, egw_invalid_argument, "n_quad = " &
            & //int_str(options%n_quad)//": must be in 4..64")
      end if
   end subroutine check_inputs

   pure subroutine positive(x, name, error)
      real(dp), intent(in) :: x
      character(len=*), intent(in) :: name
      type(egw_error), allocatable, intent(out) :: error
      if (.not. ieee_is_finite(x) .or. .not. x > 0.0_dp) then
         call fatal_error(error, egw_invalid_argument, name//" = "//format_real(x) &
            & //": must be finite and > 0")
      end if
   end subroutine positive

   !> Ring edges graded toward both ends of [0, 1] (spacing ~ 1/m**2 there).
   elemental real(dp) function both_ends(t) result(x)
      real(dp), intent(in) :: t
      x = t*t*(3.0_dp - 2.0_dp*t)
   end function both_ends

   !> Ring edges graded toward 1 (spacing ~ 1/m**2 there, 2/m at 0).
   elemental real(dp) function toward_one(t) result(x)
      real(dp), intent(in) :: t   !< the edge's fraction j/m in [0, 1]
      x = 1.0_dp - (1.0_dp - t)**2
   end function toward_one

   !> Scaled influence h(i, e) = w at x(i) of p = 1 on element e (elements on edges), and
   !> the mesh: n_press Gauss points per element, their coefficients summed.
   subroutine influence(edges, x, mesh, h, error)
      real(dp), intent(in) :: edges(0:), x(:)
      type(radial_mesh), intent(out) :: mesh
      real(dp), allocatable, intent(out) :: h(:, :)
      type(egw_error), allocatable, intent(out) :: error
      real(dp), allocatable :: infl(:, :)
      integer :: e, n, stat
      n = size(edges) - 1
      call build_mesh(edges, 1, n_press, mesh)
      allocate (infl(size(x), n*n_press), h(size(x), n), stat=stat)
      if (stat == 0) call assemble_influence(mesh, x, infl, 1, stat)
      if (stat /= 0) then
         call fatal_error(error, egw_not_converged, "cap solver: influence matrix of " &
            & //int_str(n)//" rings could not be allocated")
         return
      end if
      do e = 1, n
         h(:, e) = 2.0_dp/pi*sum(infl(:, (e - 1)*n_press + 1:e*n_press), dim=2)
      end do
   end subroutine influence

   !> The loading problem on the fitted mesh of m rings at gamma = c/a in (0, 1): p = 1 on
   !> [0, gamma], rings on [gamma, 1] (unit a; lengths scale with a, deflections too), gap = 0
   !> at their midpoints. q = H^-1 (Delta/a - a x**2/2 - hc), P = 3 a**2 (gamma**2/2 +
   !> area.q) = 3 (a**2 gamma**2/2 + a Delta r1 - a**3 r2 - a**2 r3), r = v.(1, x**2/2, hc),
   !> v = H^-T area; dP/da = 0 is 3 r2 a**2 - (gamma**2 - 2 r3) a - Delta r1 = 0.
   subroutine fitted_solve(m, gamma, delta, st, error)
      integer, intent(in) :: m
      real(dp), intent(in) :: gamma, delta
      type(fitted_load), intent(out) :: st
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: edges(0:m + 1), ar(m), v(m, 1), rhs(m, 1), r1, r2, r3, bq, a
      real(dp), allocatable :: h(:, :)
      integer :: j, info
      edges(0) = 0.0_dp
      edges(1) = gamma
      edges(2:m + 1) = gamma + (1.0_dp - gamma)*both_ends([(real(j, dp)/real(m, dp), j=1, m)])
      edges(m + 1) = 1.0_dp
      st%m = m
      st%gamma = gamma
      st%delta = delta
      st%x = 0.5_dp*(edges(1:m) + edges(2:m + 1))
      ar = 0.5_dp*(edges(2:m + 1)**2 - edges(1:m)**2)
      call influence(edges, st%x, st%mesh, h, error)
      if (allocated(error)) return
      st%hc = h(:, 1)
      st%lu = h(:, 2:m + 1)
      allocate (st%piv(m))
      call dgetrf(m, m, st%lu, m, st%piv, info)
      if (info == 0) then
         v(:, 1) = ar
         call dgetrs('T', m, 1, st%lu, m, st%piv, v, m, info)
      end if
      r1 = sum(v(:, 1))
      r2 = 0.5_dp*sum(v(:, 1)*st%x**2)
      r3 = sum(v(:, 1)*st%hc)
      if (info /= 0 .or. .not. (r1 > 0.0_dp .and. r2 > 0.0_dp)) then
         call fatal_error(error, egw_not_converged, "cap solver: the fitted mesh at c/a = " &
            & //format_real(gamma)//" is singular")
         return
      end if
      bq = gamma**2 - 2.0_dp*r3
      a = (bq + sqrt(bq**2 + 12.0_dp*r2*r1*delta))/(6.0_dp*r2)
      st%a = a
      st%force = 3.0_dp*(0.5_dp*a**2*gamma**2 + a*delta*r1 - a**3*r2 - a**2*r3)
      st%stiffness = 3.0_dp*a*r1
      rhs(:, 1) = delta/a - 0.5_dp*a*st%x**2 - st%hc
      call dgetrs('N', m, 1, st%lu, m, st%piv, rhs, m, info)
      st%q = rhs(:, 1)
      st%effective = 0.75_dp*pi*(0.5_dp*gamma**2 + sum(ar*st%q))/(gamma + &
         & sum((edges(2:m + 1) - edges(1:m))*st%q))
   end subroutine fitted_solve

   !> The loading solution at Delta on m rings: Newton on dP*/dt = 0, t = ln(gamma/(1 -
   !> gamma)), P*(t) = P at the stationary a, derivatives by central differences (step
   !> h_t: their truncation error ~1e-7 in t moves P* by ~1e-14, P* being stationary).
   !> gamma: in, the start; out, the solution. st: the solution's mesh and pressures.
   subroutine load_fitted(m, delta, max_iter, gamma, st, full, error)
      integer, intent(in) :: m          !< rings
      integer, intent(in) :: max_iter   !< most Newton iterations (cap_options%max_active)
      real(dp), intent(in) :: delta     !< scaled Delta (> 1)
      real(dp), intent(inout) :: gamma  !< c/a: in, the start; out, the solution
      type(fitted_load), intent(out) :: st   !< the solution's mesh and pressures
      logical, intent(out) :: full   !< the solution's edge is below exp(-t_cap) a
      !> egw_not_converged when the cap radius does not converge or a mesh is singular
      type(egw_error), allocatable, intent(out) :: error
      real(dp), parameter :: h_t = 1.0e-3_dp
      type(fitted_load) :: sm, sp
      real(dp) :: t, d1, d2, step
      integer :: it
      t = min(t_cap, log(gamma/(1.0_dp - gamma)))
      full = .false.
      step = huge(1.0_dp)
      do it = 1, max_iter
         call fitted_solve(m, logistic(t), delta, st, error)
         if (.not. allocated(error)) call fitted_solve(m, logistic(t - h_t), delta, sm, error)
         if (.not. allocated(error)) call fitted_solve(m, logistic(t + h_t), delta, sp, error)
         if (allocated(error)) return
         d1 = (sp%force - sm%force)/(2.0_dp*h_t)
         d2 = (sp%force - 2.0_dp*st%force + sm%force)/h_t**2
         if (.not. d2 > 0.0_dp) then
            ! P* is a minimum in gamma (the cap takes pressure away); away from it descend
            step = -sign(0.5_dp, d1)
         else
            step = max(-1.0_dp, min(1.0_dp, -d1/d2))
         end if
         if (t + step > t_cap) then
            ! the elastic edge is thinner than exp(-t_cap) a: the fully capped limit
            full = .true.
            return
         end if
         t = t + step
         if (abs(step) <= 1.0e-6_dp) exit
         ! a flat minimum (a small cap just above delta_y): P* settled to rounding
         if (abs(d1*step) <= 1.0e-15_dp*st%force .and. d2 > 0.0_dp .and. &
            & abs(step) <= 1.0e-3_dp) exit
      end do
      ! after max_iter: a flat minimum where the steps cycle on the differences' rounding
      ! (|step| ~1e-4, P* the same to 1e-14: 5 of 30000 overlaps in 1.0008 .. 1.0043
      ! delta_y, audit16) is settled too
      if (.not. (abs(step) <= 1.0e-3_dp .and. abs(d1*step) <= 1.0e-15_dp*st%force .or. &
         & abs(step) <= 1.0e-3_dp .and. abs(d1*step) <= 1.0e-13_dp*st%force .and. &
         & d2 > 0.0_dp .or. abs(step) <= 1.0e-6_dp) &
         & .or. .not. ieee_is_finite(t)) then
         call fatal_error(error, egw_not_converged, "cap solver: the cap radius at delta = " &
            & //format_real(delta)//" delta_y did not converge")
         return
      end if
      gamma = logistic(t)
      call fitted_solve(m, gamma, delta, st, error)
   end subroutine load_fitted

   elemental real(dp) function logistic(t) result(g)
      real(dp), intent(in) :: t
      g = 1.0_dp/(1.0_dp + exp(-t))
   end function logistic

   !> A start for gamma = c/a at Delta > 1: the tabulated ln(c/(a - c)) (egw_cap_start)
   !> below t_cap.
   pure real(dp) function gamma_start(delta) result(g)
      real(dp), intent(in) :: delta   !< scaled Delta = delta/delta_y (> 1)
      g = logistic(min(cap_start_logit(delta), t_cap))
   end function gamma_start

   !> Clenshaw sum of the Chebyshev series c at y in [-1, 1].
   pure real(dp) function cheb(c, y) result(s)
      real(dp), intent(in) :: c(0:), y
      real(dp) :: b0, b1, b2
      integer :: k
      b1 = 0.0_dp
      b2 = 0.0_dp
      do k = ubound(c, 1), 1, -1
         b0 = c(k) + 2.0_dp*y*b1 - b2
         b2 = b1
         b1 = b0
      end do
      s = c(0) + y*b1 - b2
   end function cheb

   !> The series of dU/dy of U = sum c_k T_k(y).
   pure function cheb_derivative(c) result(d)
      real(dp), intent(in) :: c(0:)
      real(dp) :: d(0:ubound(c, 1))
      integer :: n, k
      n = ubound(c, 1)
      d = 0.0_dp
      if (n >= 1) d(n - 1) = 2.0_dp*real(n, dp)*c(n)
      do k = n - 1, 1, -1
         d(k - 1) = merge(d(k + 1), 0.0_dp, k + 1 <= n) + 2.0_dp*real(k, dp)*c(k)
      end do
      d(0) = 0.5_dp*d(0)
   end function cheb_derivative

   !> The plastic displacement u_pl(rho) and its slope (scaled): 0 beyond the cap radius c;
   !> within, u_pl = D + g. D = Delta - rho**2/2 - (8 r/pi**2) E(rho/r), minus the gap of
   !> p = 1 on the disc [0, r] of the same force (r = sqrt(2P/3) in (c, a); exact, with the
   !> log-steep rim of the fully capped crater, where r = c = a), g the deflection of the
   !> rest, p - 1 on [c, r] and p on [r, a]: no net force and continuous at c, so it is
   !> small (~(a - c)**2 near a thin elastic edge) and smooth in s = sqrt(1 - rho/c) on
   !> [0, c), kept as a series
   !> less the Hermite cubics in s that set u_pl(c) = 0 and take out its s-slope at s = 0
   !> (the discrete solution's misfit there), so that u_pl and its slope stay bounded and
   !> nothing jumps as a collocation point crosses c.
   pure subroutine u_plastic(hist, rho, u, du)
      type(cap_history), intent(in) :: hist   !< from cap_load (u_pl = 0 if elastic)
      real(dp), intent(in) :: rho   !< scaled radius r/a_y >= 0
      real(dp), intent(out) :: u, du   !< u_pl/delta_y and its derivative in rho
      real(dp) :: s, y, d(0:n_cheb - 1), d1(0:n_cheb - 1), us, u0, us0, dd, dc, dummy, h
      integer :: j
      u = 0.0_dp
      du = 0.0_dp
      if (rho >= hist%cap) return
      call full_gap(hist%delta_max, hist%disc, rho, u, du)
      if (hist%cap >= hist%disc) return
      call full_gap(hist%delta_max, hist%disc, hist%cap, dc, dummy)
      s = sqrt(max(0.0_dp, 1.0_dp - rho/hist%cap))
      j = 1
      do while (j < hist%n_panels .and. s > hist%s_break(j))
         j = j + 1
      end do
      h = hist%s_break(j) - hist%s_break(j - 1)
      y = max(-1.0_dp, min(1.0_dp, 2.0_dp*(s - hist%s_break(j - 1))/h - 1.0_dp))
      d = cheb_derivative(hist%u_cheb(:, j))
      d1 = cheb_derivative(hist%u_cheb(:, 1))
      u0 = cheb(hist%u_cheb(:, 1), -1.0_dp) + dc
      us0 = 2.0_dp/hist%s_break(1)*cheb(d1, -1.0_dp)
      u = u + cheb(hist%u_cheb(:, j), y) - u0*(1.0_dp - s)**2*(1.0_dp + 2.0_dp*s) &
         & - us0*s*(1.0_dp - s)**2
      us = 2.0_dp/h*cheb(d, y) + u0*6.0_dp*s*(1.0_dp - s) &
         & - us0*(1.0_dp - s)*(1.0_dp - 3.0_dp*s)
      ! du/drho = us ds/drho, ds/drho = -1/(2 c s); us = O(s) at s = 0
      dd = -us/(2.0_dp*hist%cap*max(s, 1.0e-8_dp))
      du = du + dd
   end subroutine u_plastic

   !> D = Delta - rho**2/2 - (8 a/pi**2) E(rho/a) and dD/drho, 0 <= rho < a: minus the gap
   !> of p = 1 on [0, a] (uniform disc: w = 4 a/pi E(k) for E* = 1, times 2/pi).
   pure subroutine full_gap(delta, a, rho, d, dd)
      real(dp), intent(in) :: delta, a, rho
      real(dp), intent(out) :: d, dd
      real(dp) :: k, kc, e, dedk
      k = rho/a
      kc = sqrt(max(0.0_dp, (1.0_dp - k)*(1.0_dp + k)))
      e = ellipe_comp(kc)
      if (k < 1.0e-4_dp) then
         dedk = -0.25_dp*pi*k
      else
         dedk = (e - ellipk_comp(kc))/k
      end if
      d = delta - 0.5_dp*rho**2 - 8.0_dp*a/pi**2*e
      dd = -rho - 8.0_dp/pi**2*dedk
   end subroutine full_gap

   !> u_pl = -gap on [0, c] of the loading solution st at Delta, less D (see u_plastic),
   !> sampled at the Chebyshev points of max_panels panels in s whose breaks are geometric
   !> from sqrt((a - c)/c) to 1 (g varies on the scale a - c of the elastic edge next to c)
   !> and kept as their series (in hist).
   subroutine keep_plastic(st, hist)
      type(fitted_load), intent(in) :: st
      type(cap_history), intent(inout) :: hist
      real(dp) :: row(st%mesh%n_elem*n_press), hr(st%mesh%n_elem), u(0:n_cheb - 1), th, s
      real(dp) :: x, w, d, dd, eta
      integer :: k, e, j, n
      ! a fixed count of panels whose breaks move with eta: nothing jumps as Delta moves
      eta = sqrt(max(1.0e-300_dp, 1.0_dp - st%gamma))
      n = max_panels
      hist%n_panels = n
      hist%s_break(0) = 0.0_dp
      hist%s_break(1:n - 1) = eta**(real([(n - j, j=1, n - 1)], dp)/real(n - 1, dp))
      hist%s_break(n) = 1.0_dp
      do j = 1, n
         do k = 0, n_cheb - 1
            th = pi*(real(k, dp) + 0.5_dp)/real(n_cheb, dp)
            s = hist%s_break(j - 1) + 0.5_dp*(1.0_dp + cos(th))* &
               & (hist%s_break(j) - hist%s_break(j - 1))
            x = st%gamma*(1.0_dp - s*s)
            call influence_row(st%mesh, x, row)
            do e = 1, st%mesh%n_elem
               hr(e) = 2.0_dp/pi*sum(row((e - 1)*n_press + 1:e*n_press))
            end do
            w = st%a*(hr(1) + sum(hr(2:)*st%q))
            call full_gap(st%delta, hist%disc, st%a*x, d, dd)
            u(k) = st%delta - 0.5_dp*(st%a*x)**2 - w - d
         end do
         call keep_series(u, hist%u_cheb(:, j))
      end do
   end subroutine keep_plastic

   !> The Chebyshev series c of the values u at the points cos(pi (k + 1/2)/n_cheb).
   pure subroutine keep_series(u, c)
      real(dp), intent(in) :: u(0:n_cheb - 1)
      real(dp), intent(out) :: c(0:n_cheb - 1)
      integer :: j, k
      do j = 0, n_cheb - 1
         c(j) = 2.0_dp/real(n_cheb, dp)*sum(u*cos(real(j, dp)*pi* &
            & ([(real(k, dp), k=0, n_cheb - 1)] + 0.5_dp)/real(n_cheb, dp)))
      end do
      c(0) = 0.5_dp*c(0)
   end subroutine keep_series

   !> The unloading mesh of m rings on the unit disc (graded toward its edge): midpoints x,
   !> v = H^-T area and (lu, piv) = H's LU.
   subroutine unload_mesh(m, x, v, r1, lu, piv, error)
      integer, intent(in) :: m
      real(dp), intent(out) :: x(m), v(m), r1
      real(dp), allocatable, intent(out) :: lu(:, :)
      integer, allocatable, intent(out) :: piv(:)
      type(egw_error), allocatable, intent(out) :: error
      type(radial_mesh) :: mesh
      real(dp) :: edges(0:m), rhs(m, 1)
      integer :: j, info
      edges = toward_one([(real(j, dp)/real(m, dp), j=0, m)])
      edges(0) = 0.0_dp
      edges(m) = 1.0_dp
      x = 0.5_dp*(edges(0:m - 1) + edges(1:m))
      call influence(edges, x, mesh, lu, error)
      if (allocated(error)) return
      allocate (piv(m))
      call dgetrf(m, m, lu, m, piv, info)
      rhs(:, 1) = 0.5_dp*(edges(1:m)**2 - edges(0:m - 1)**2)
      if (info == 0) call dgetrs('T', m, 1, lu, m, piv, rhs, m, info)
      if (info /= 0) then
         call fatal_error(error, egw_not_converged, "cap solver: the unloading mesh of " &
            & //int_str(m)//" rings is singular")
         return
      end if
      v = rhs(:, 1)
      r1 = sum(v)
   end subroutine unload_mesh

   !> Unloading on level l at contact radius b: Delta(b) (dP/db = 0) and P there.
   pure subroutine unload_at(hist, l, b, delta, force)
      type(cap_history), intent(in) :: hist
      integer, intent(in) :: l
      real(dp), intent(in) :: b
      real(dp), intent(out) :: delta, force
      real(dp) :: rho, u, du, sf, sd
      integer :: i
      sf = 0.0_dp
      sd = 0.0_dp
      do i = 1, hist%n_unload(l)
         rho = b*hist%x_unload(i, l)
         call u_plastic(hist, rho, u, du)
         sf = sf + hist%v_unload(i, l)*(0.5_dp*rho**2 + u)
         sd = sd + hist%v_unload(i, l)*rho*(rho + du)
      end do
      delta = (sf + sd)/hist%r_unload(l)
      force = 3.0_dp*b*(delta*hist%r_unload(l) - sf)
   end subroutine unload_at

   !> The contact radius b of level l where Delta(b) = d (> residual): Illinois on
   !> [0, b_hi], Delta(0) = residual, b_hi from the loading contact radius outward.
   subroutine unload_radius(hist, l, d, b, error)
      type(cap_history), intent(in) :: hist
      integer, intent(in) :: l
      real(dp), intent(in) :: d
      real(dp), intent(out) :: b
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: lo, hi, flo, fhi, fb, force
      integer :: it, side
      lo = 0.0_dp
      flo = hist%residual - d
      hi = hist%contact
      do it = 1, 20
         call unload_at(hist, l, hi, fhi, force)
         fhi = fhi - d
         if (fhi >= 0.0_dp) exit
         lo = hi
         flo = fhi
         hi = 1.25_dp*hi
      end do
      b = hi
      if (fhi < 0.0_dp) then
         call fatal_error(error, egw_not_converged, "cap_unload: no contact radius for " &
            & //"delta = "//format_real(d)//" delta_y")
         return
      end if
      side = 0
      do it = 1, 200
         b = 0.5_dp*(lo + hi)
         if (fhi /= flo) b = (lo*fhi - hi*flo)/(fhi - flo)
         if (.not. (b > lo .and. b < hi)) b = 0.5_dp*(lo + hi)
         call unload_at(hist, l, b, fb, force)
         fb = fb - d
         if (fb == 0.0_dp .or. hi - lo <= 1.0e-15_dp*hi) exit
         if (sign(1.0_dp, fb) == sign(1.0_dp, fhi)) then
            hi = b
            fhi = fb
            if (side == 1) flo = 0.5_dp*flo
            side = 1
         else
            lo = b
            flo = fb
            if (side == -1) fhi = 0.5_dp*fhi
            side = -1
         end if
         if (abs(fb) <= 1.0e-15_dp*d) exit
      end do
   end subroutine unload_radius

   !> Loading solve at delta_max (>= 0) of a sphere R, E* against the cap p_y; keeps the
   !> plastic field in history for cap_unload. Below delta_y: Hertz (closed form).
   subroutine cap_load(radius, modulus, flow_pressure, delta_max, options, history, result, &
      & error, name)
      real(dp), intent(in) :: radius          !< equivalent radius R > 0
      real(dp), intent(in) :: modulus         !< effective modulus E* > 0
      real(dp), intent(in) :: flow_pressure   !< p_y, 0 < p_y < E*
      real(dp), intent(in) :: delta_max       !< overlap >= 0
      type(cap_options), intent(in) :: options   !< the cap solver's options (cap_options)
      type(cap_history), intent(out) :: history   !< the plastic field at delta_max, for cap_unload
      !> force, stiffness, radii, peak pressure at delta_max
      type(cap_result), intent(out) :: result
      !> egw_invalid_argument naming the value, or the solve's failure
      type(egw_error), allocatable, intent(out) :: error
      !> the overlap's name in messages (default "delta_max"; a loading solve's: "delta")
      character(len=*), intent(in), optional :: name
      character(len=:), allocatable :: label
      type(fitted_load) :: st, coarse
      real(dp) :: dm, f, k, a, pm, gamma, u, du
      integer :: m
      logical :: full
      label = "delta_max"
      if (present(name)) label = name
      call check_inputs(radius, modulus, flow_pressure, options, error)
      if (allocated(error)) return
      if (.not. ieee_is_finite(delta_max) .or. .not. delta_max >= 0.0_dp) then
         call fatal_error(error, egw_invalid_argument, label//" = "//format_real(delta_max) &
            & //": must be finite and >= 0")
         return
      end if
      history%radius = radius
      history%modulus = modulus
      history%flow_pressure = flow_pressure
      history%options = options
      call cap_units(radius, modulus, flow_pressure, history%delta_y, history%a_y, &
         & history%force_y)
      dm = delta_max/history%delta_y
      history%delta_max = dm
      if (dm > 1.0e6_dp) then
         call fatal_error(error, egw_invalid_argument, label//" = "//format_real(delta_max) &
            & //": beyond 1e6 delta_y (the cap model's range)")
         return
      end if
      if (dm <= 1.0_dp + elastic_margin) then
         history%elastic = .true.
         history%residual = 0.0_dp
         call hertz_scaled(dm, f, k, a, pm)
         call unscale(history, f, k, a, a, 0.0_dp, pm, 0.0_dp, result)
         return
      end if
      history%elastic = .false.
      m = options%n_rings*2**(options%n_levels - 1)
      gamma = gamma_start(dm)
      call load_fitted(m, dm, options%max_active, gamma, st, full, error)
      if (allocated(error)) return
      if (full) then
         call load_full(dm, history, result)
         call keep_unloading(history, m, error)
         return
      end if
      ! the level before at the same gamma: P is stationary in gamma, so this is its own
      ! solution's force to second order
      call fitted_solve(m/2, gamma, dm, coarse, error)
      if (allocated(error)) return
      history%contact = st%a
      history%cap = gamma*st%a
      history%disc = sqrt(2.0_dp*st%force/3.0_dp)
      call keep_plastic(st, history)
      call u_plastic(history, 0.0_dp, u, du)
      history%residual = max(0.0_dp, u)
      call keep_unloading(history, m, error)
      if (allocated(error)) return
      call unscale(history, st%force, st%stiffness, st%a, st%effective*st%a, gamma*st%a, &
         & 1.0_dp, abs(st%force - coarse%force)*history%force_y, result)
   end subroutine cap_load

   !> The residual overlap delta_r/delta_y of cap_load's history at delta_max, without
   !> what only its force and unloading need (the coarse level's solve, the unloading
   !> meshes): the same steps, the same value (the hysteresis build's fine L grid). The
   !> inputs as cap_load's (checked the same way); gamma, when present, is the start of
   !> the cap radius's search (c/a in (0, 1), e.g. a neighbouring turning point's, out:
   !> the solution's; 0 or absent: gamma_start's).
   subroutine cap_residual(radius, modulus, flow_pressure, delta_max, options, residual, &
      & error, gamma)
      real(dp), intent(in) :: radius          !< effective radius R [length]
      real(dp), intent(in) :: modulus         !< effective modulus E* [pressure]
      real(dp), intent(in) :: flow_pressure   !< p_y > 0 [pressure]
      real(dp), intent(in) :: delta_max       !< the loading's deepest overlap [length]
      type(cap_options), intent(in) :: options   !< rings and levels (cap_load's)
      real(dp), intent(out) :: residual   !< delta_r/delta_y (0 up to first yield)
      type(egw_error), allocatable, intent(out) :: error   !< bad input, no convergence
      !> in: a start for c/a in (0, 1) (else gamma_start's); out: the solution's c/a
      real(dp), intent(inout), optional :: gamma
      type(cap_history) :: history
      type(fitted_load) :: st
      real(dp) :: dm, g, du
      integer :: m
      logical :: full
      residual = 0.0_dp
      call check_inputs(radius, modulus, flow_pressure, options, error)
      if (allocated(error)) return
      if (.not. ieee_is_finite(delta_max) .or. .not. delta_max >= 0.0_dp) then
         call fatal_error(error, egw_invalid_argument, "delta_max = " &
            & //format_real(delta_max)//": must be finite and >= 0")
         return
      end if
      call cap_units(radius, modulus, flow_pressure, history%delta_y, history%a_y, &
         & history%force_y)
      dm = delta_max/history%delta_y
      if (dm > 1.0e6_dp) then
         call fatal_error(error, egw_invalid_argument, "delta_max = " &
            & //format_real(delta_max)//": beyond 1e6 delta_y (the cap model's range)")
         return
      end if
      if (dm <= 1.0_dp + elastic_margin) return
      history%delta_max = dm
      history%options = options
      m = options%n_rings*2**(options%n_levels - 1)
      g = gamma_start(dm)
      if (present(gamma)) then
         if (gamma > 0.0_dp .and. gamma < 1.0_dp) g = gamma
      end if
      call load_fitted(m, dm, options%max_active, g, st, full, error)
      if (allocated(error)) return
      if (present(gamma)) gamma = g
      if (full) then
         history%contact = -8.0_dp/pi**2 + sqrt(64.0_dp/pi**4 + 2.0_dp*dm)
         history%cap = history%contact
         history%disc = history%contact
         history%u_cheb = 0.0_dp
         history%n_panels = 1
         history%s_break(0:1) = [0.0_dp, 1.0_dp]
         call u_plastic(history, 0.0_dp, residual, du)
         return
      end if
      history%contact = st%a
      history%cap = g*st%a
      history%disc = sqrt(2.0_dp*st%force/3.0_dp)
      call keep_plastic(st, history)
      call u_plastic(history, 0.0_dp, residual, du)
      residual = max(0.0_dp, residual)
   end subroutine cap_residual

   !> The fully capped limit at Delta (see t_cap): a from Delta = a**2/2 + 8 a/pi**2,
   !> P = 3 a**2/2, dP/dDelta = 3 a/(a + 8/pi**2); u_pl = Delta - rho**2/2 - w of the
   !> uniform disc, w = (8 a/pi**2) E(rho/a); force_error: the limit's ~1e-8 of P.
   subroutine load_full(delta, history, result)
      real(dp), intent(in) :: delta
      type(cap_history), intent(inout) :: history
      type(cap_result), intent(out) :: result
      real(dp) :: a, dummy
      a = -8.0_dp/pi**2 + sqrt(64.0_dp/pi**4 + 2.0_dp*delta)
      history%contact = a
      history%cap = a
      history%disc = a
      history%u_cheb = 0.0_dp
      history%n_panels = 1
      history%s_break(0:1) = [0.0_dp, 1.0_dp]
      call u_plastic(history, 0.0_dp, history%residual, dummy)
      call unscale(history, 1.5_dp*a**2, 3.0_dp*a/(a + 8.0_dp/pi**2), a, 0.375_dp*pi*a, a, &
         & 1.0_dp, &
         & 1.0e-8_dp*1.5_dp*a**2*history%force_y, result)
   end subroutine load_full

   !> The unloading meshes of the last two levels (m/2 and m rings) into history.
   subroutine keep_unloading(history, m, error)
      !> a plastic loading's history, without unloading meshes (their arrays unallocated)
      type(cap_history), intent(inout) :: history
      integer, intent(in) :: m   !< the finest level's rings (even)
      !> egw_not_converged when an unloading mesh cannot be allocated or is singular
      type(egw_error), allocatable, intent(out) :: error
      integer :: l, n
      history%n_unload = [m/2, m]
      allocate (history%x_unload(m, 2), history%v_unload(m, 2))
      history%x_unload = 0.0_dp
      history%v_unload = 0.0_dp
      do l = 1, 2
         n = history%n_unload(l)
         call unload_mesh(n, history%x_unload(1:n, l), history%v_unload(1:n, l), &
            & history%r_unload(l), history%lu_unload, history%piv_unload, error)
         if (allocated(error)) return
      end do
   end subroutine keep_unloading

   pure subroutine hertz_scaled(d, f, k, a, pm)
      real(dp), intent(in) :: d
      real(dp), intent(out) :: f, k, a, pm
      f = max(d, 0.0_dp)**1.5_dp
      k = 1.5_dp*sqrt(max(d, 0.0_dp))
      a = sqrt(max(d, 0.0_dp))
      pm = a
   end subroutine hertz_scaled

   pure subroutine unscale(history, f, k, a, as, c, pm, ferr, result)
      type(cap_history), intent(in) :: history
      real(dp), intent(in) :: f, k, a, c, pm, ferr
      real(dp), intent(in) :: as   !< scaled a* (effective radius)
      type(cap_result), intent(inout) :: result
      result%force = f*history%force_y
      result%stiffness = k*history%force_y/history%delta_y
      result%contact_radius = a*history%a_y
      result%effective_radius = as*history%a_y
      result%cap_radius = c*history%a_y
      result%max_pressure = pm*history%flow_pressure
      result%force_error = ferr
   end subroutine unscale

   !> Unloading (or reloading) at delta <= delta_max after cap_load: elastic from the
   !> deformed shape (u_pl frozen); 0 once delta is at or below the residual overlap.
   !> Above delta_max loading continues: call cap_load at the new delta_max.
   subroutine cap_unload(history, delta, result, error)
      type(cap_history), intent(in) :: history   !< from cap_load
      real(dp), intent(in) :: delta              !< overlap <= delta_max
      type(cap_result), intent(out) :: result   !< force, stiffness, radii, peak pressure at delta
      !> egw_invalid_argument: no loaded history, or delta refused (named)
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: d, f, k, a, pm, b, dl, fc, u, du, as
      real(dp), allocatable :: q(:, :), edges(:)
      integer :: m, i, info
      if (history%delta_y <= 0.0_dp) then
         call fatal_error(error, egw_invalid_argument, "cap_unload: history not loaded")
         return
      end if
      if (.not. ieee_is_finite(delta)) then
         call fatal_error(error, egw_invalid_argument, "delta = "//format_real(delta) &
            & //": must be finite")
         return
      end if
      d = delta/history%delta_y
      if (d > history%delta_max*(1.0_dp + 1.0e-12_dp)) then
         call fatal_error(error, egw_invalid_argument, "delta = "//format_real(delta) &
            & //": above the history's delta_max "//format_real(history%delta_max* &
            & history%delta_y)//" (reloading beyond it is a new cap_load)")
         return
      end if
      if (history%elastic) then
         call hertz_scaled(d, f, k, a, pm)
         call unscale(history, f, k, a, a, 0.0_dp, pm, 0.0_dp, result)
         return
      end if
      if (d <= history%residual) then
         call unscale(history, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, result)
         return
      end if
      call unload_radius(history, 1, d, b, error)
      if (allocated(error)) return
      call unload_at(history, 1, b, dl, fc)
      fc = fc + 3.0_dp*b*history%r_unload(1)*(d - dl)
      call unload_radius(history, 2, d, b, error)
      if (allocated(error)) return
      call unload_at(history, 2, b, dl, f)
      ! the root's last misfit d - dl to first order (dP/dDelta = 3 b r1 at fixed b)
      f = f + 3.0_dp*b*history%r_unload(2)*(d - dl)
      k = 3.0_dp*b*history%r_unload(2)
      m = history%n_unload(2)
      allocate (q(m, 1), edges(0:m))
      do i = 1, m
         call u_plastic(history, b*history%x_unload(i, 2), u, du)
         q(i, 1) = (d - 0.5_dp*(b*history%x_unload(i, 2))**2 - u)/b
      end do
      call dgetrs('N', m, 1, history%lu_unload, m, history%piv_unload, q, m, info)
      pm = maxval(q(:, 1))
      ! a* from the rings' pressures (unit b; edges as unload_mesh's)
      edges = toward_one([(real(i, dp)/real(m, dp), i=0, m)])
      edges(0) = 0.0_dp
      edges(m) = 1.0_dp
      as = 0.75_dp*pi*b*sum(0.5_dp*(edges(1:m)**2 - edges(0:m - 1)**2)*q(:, 1))/ &
         & sum((edges(1:m) - edges(0:m - 1))*q(:, 1))
      call unscale(history, f, k, b, as, 0.0_dp, pm, abs(f - fc)*history%force_y, result)
   end subroutine cap_unload

   !> Scaled loading work W(Delta_m) = int_0^Delta_m P dDelta (units P_y delta_y):
   !> 2/5 up to first yield, then Gauss-Legendre in t, Delta = 1 + (Delta_m - 1) t**2.
   subroutine cap_load_scaled_work(dm, options, work, force_m, error)
      real(dp), intent(in) :: dm   !< Delta_m = delta_max/delta_y
      type(cap_options), intent(in) :: options   !< the cap solver's options (n_quad points)
      real(dp), intent(out) :: work, force_m   !< W and P(Delta_m), scaled
      type(egw_error), allocatable, intent(out) :: error   !< a loading solve's failure
      type(cap_history) :: hist
      type(cap_result) :: res
      real(dp) :: x(options%n_quad), w(options%n_quad), t, d
      integer :: i
      call gl(options%n_quad, x, w)
      work = 0.4_dp*min(dm, 1.0_dp)**2.5_dp
      if (dm > 1.0_dp) then
         do i = 1, options%n_quad
            t = 0.5_dp*(x(i) + 1.0_dp)
            d = 1.0_dp + (dm - 1.0_dp)*t*t
            ! unit problem: R = 1, E* = 1, p_y = 2/pi gives delta_y = 1, P_y = 4/3
            call cap_load(1.0_dp, 1.0_dp, 2.0_dp/pi, d, options, hist, res, error)
            if (allocated(error)) return
            work = work + 0.5_dp*w(i)*2.0_dp*t*(dm - 1.0_dp)*res%force*0.75_dp
         end do
      end if
      call cap_load(1.0_dp, 1.0_dp, 2.0_dp/pi, dm, options, hist, res, error)
      if (allocated(error)) return
      force_m = res%force*0.75_dp
   end subroutine cap_load_scaled_work

   !> Scaled unloading work int_{Delta_res}^{Delta_m} P_u dDelta after loading to Delta_m,
   !> Gauss-Legendre in t, Delta = Delta_res + (Delta_m - Delta_res) t**2 (P_u ~ t**3 at 0).
   subroutine cap_unload_scaled_work(dm, options, work, residual, error)
      real(dp), intent(in) :: dm   !< Delta_m = delta_max/delta_y
      type(cap_options), intent(in) :: options   !< the cap solver's options (n_quad points)
      !> the unloading work and the residual overlap Delta_res, scaled
      real(dp), intent(out) :: work, residual
      type(egw_error), allocatable, intent(out) :: error   !< a solve's failure
      type(cap_history) :: hist
      type(cap_result) :: res
      real(dp) :: x(options%n_quad), w(options%n_quad), t, d
      integer :: i
      call cap_load(1.0_dp, 1.0_dp, 2.0_dp/pi, dm, options, hist, res, error)
      if (allocated(error)) return
      residual = hist%residual
      work = 0.0_dp
      call gl(options%n_quad, x, w)
      do i = 1, options%n_quad
         t = 0.5_dp*(x(i) + 1.0_dp)
         d = residual + (dm - residual)*t*t
         call cap_unload(hist, d, res, error)
         if (allocated(error)) return
         work = work + 0.5_dp*w(i)*2.0_dp*t*(dm - residual)*res%force*0.75_dp
      end do
   end subroutine cap_unload_scaled_work

   subroutine gl(n, x, w)
      use egw_halfspace, only: gauss_legendre
      integer, intent(in) :: n
      real(dp), intent(out) :: x(n), w(n)
      call gauss_legendre(n, x, w)
   end subroutine gl

   !> Coefficient of restitution of a head-on impact of effective mass m* at speed v with
   !> the cap: (1/2) m* v**2 = W_load(delta_max), e**2 = W_unload/W_load. In units:
   !> v_y**2 = (16/15) (pi/2)**5 p_y**5 R**3/(m* E***4) (the speed that just reaches
   !> first yield), (v/v_y)**2 = W_load/(2/5) in units P_y delta_y; e = 1 for v <= v_y.
   subroutine cap_restitution(radius, modulus, flow_pressure, mass, velocity, options, e, &
      & error, max_overlap)
      !> R [length], E* and p_y [pressure], as cap_load
      real(dp), intent(in) :: radius, modulus, flow_pressure
      real(dp), intent(in) :: mass       !< effective mass m* > 0
      real(dp), intent(in) :: velocity   !< impact speed v > 0
      type(cap_options), intent(in) :: options   !< the cap solver's options (cap_options)
      real(dp), intent(out) :: e   !< coefficient of restitution in (0, 1]
      !> egw_invalid_argument naming the value, or a solve's failure
      type(egw_error), allocatable, intent(out) :: error
      !> the deepest overlap delta_max of the impact (Hertz's for v <= v_y)
      real(dp), intent(out), optional :: max_overlap
      real(dp) :: vy, target, dm, wl, fm, wu, res, step
      integer :: it
      e = 1.0_dp
      call check_inputs(radius, modulus, flow_pressure, options, error)
      if (allocated(error)) return
      call positive(mass, "mass", error); if (allocated(error)) return
      call positive(velocity, "velocity", error); if (allocated(error)) return
      ! factored so that no power of the inputs overflows or underflows on the way (the
      ! plain p**5 R**3/(m E**4) gave v_y = 0 for m* ~ 1e264 kg in SI)
      vy = sqrt(16.0_dp/15.0_dp*(pi/2.0_dp)**5)*(flow_pressure/modulus)**2* &
         & sqrt(flow_pressure/mass)*sqrt(radius)**3
      if (.not. (vy > 0.0_dp .and. ieee_is_finite(vy))) then
         call fatal_error(error, egw_invalid_argument, "mass = "//format_real(mass)// &
            & ": the first-yield speed v_y = "//format_real(vy)//" is not a positive " &
            & //"double (v_y**2 = (16/15) (pi/2)**5 p_y**5 R**3/(m* E***4))")
         return
      end if
      target = 0.4_dp*(velocity/vy)**2
      if (present(max_overlap)) max_overlap = (target/0.4_dp)**0.4_dp* &
         & (pi*flow_pressure/(2.0_dp*modulus))**2*radius
      if (velocity <= vy) return
      if (velocity > 1.0e4_dp*vy) then
         call fatal_error(error, egw_invalid_argument, "velocity = "//format_real(velocity) &
            & //": above 1e4 v_y (v_y = "//format_real(vy)//"), beyond the cap model")
         return
      end if
      ! Newton on W(Delta_m) = target (W' = P > 0, W convex: from below-target starts the
      ! iterates rise monotonically); start at the fully capped estimate W ~ pi/... <= .
      dm = max(1.0_dp, (target/0.4_dp)**0.4_dp)
      do it = 1, 60
         call cap_load_scaled_work(dm, options, wl, fm, error)
         if (allocated(error)) return
         step = (target - wl)/fm
         dm = max(0.5_dp*(dm + 1.0_dp), dm + step)
         if (abs(step) <= 1.0e-10_dp*dm) exit
      end do
      if (abs(step) > 1.0e-8_dp*dm) then
         call fatal_error(error, egw_not_converged, "cap_restitution: delta_max for v = " &
            & //format_real(velocity)//" not found")
         return
      end if
      call cap_unload_scaled_work(dm, options, wu, res, error)
      if (allocated(error)) return
      call cap_load_scaled_work(dm, options, wl, fm, error)
      if (allocated(error)) return
      ! the plastic displacement only takes energy (W_unload <= W_load): just above v_y,
      ! where 1 - e < 2e-6, the works' own error (~3e-7) would otherwise give e > 1
      e = min(1.0_dp, sqrt(wu/wl))
      if (present(max_overlap)) max_overlap = dm*(pi*flow_pressure/(2.0_dp*modulus))**2*radius
   end subroutine cap_restitution

end module egw_cap_sphere
