!> The flow-pressure cap for a smooth elastic sphere (doc/theory.md §12): frictionless
!> axisymmetric contact with an elastic-perfectly-plastic half-space whose contact pressure
!> may not exceed p_y (Thornton 1997). Loading to delta_max, elastic unloading/reloading from
!> the deformed shape, and the restitution of a head-on impact.
!>
!> Universal units: delta_y = (pi p_y/(2 E*))**2 R (Hertz p_max = p_y), a_y = sqrt(R delta_y),
!> P_y = (4/3) E* sqrt(R) delta_y**1.5, pressures in p_y. Then gap = rho**2/2 - Delta + w,
!> w(rho) = (2/pi) int 4/pi t/(rho+t) K(k) p(t) dt and P/P_y = 3 int rho p drho.
!>
!> Method: uniform rings of constant pressure on [0, L], L = 1.05 sqrt(2 Delta_max) (the
!> contact radius is below sqrt(2 Delta): w > 0), collocated at the ring midpoints with the
!> influence coefficients of egw_halfspace (one Gauss point per element). The collocation
!> matrix H is not symmetric; the rings' area weights D make D H symmetric up to the
!> discretisation error, and egw solves the box complementarity problem of A = sym(D H)
!> (a consistent Galerkin-like symmetrisation): 0 <= p <= p_cap, y = A p + D q, y >= 0
!> where p = 0, y = 0 where 0 < p < p_cap, y <= 0 where p = p_cap. A primal-dual active
!> set (semismooth Newton) iteration solves it; every active set it visits is kept, and a
!> repeated set (a cycle) or more than max_active iterations switches to projected SOR,
!> which converges for a symmetric positive definite A (Cryer 1971), then the active set
!> iteration restarts from the PSOR point. Both phases are capped: egw_not_converged.
!> Accuracy: levels of n, 2n, 4n rings; the finest is returned with the difference to the
!> level before as its error estimate. Once the capped zone reaches the contact edge (from
!> ~5 delta_y) the edge is a boundary layer (theory section 12, trap iv) that uniform rings
!> resolve to one ring only, an error of up to 3e-3 in P that oscillates with the edge's
!> place in the mesh; there every level after the first is graded toward the contact edge
!> the level before found (rings 16 times finer within one coarse ring of it): measured
!> within 3.1e-4 of the reference from 1 to 100 delta_y at n = 100, 2 levels.
!>
!> Limits: half-space theory; from ~50 v_y (Delta_max of several hundred) a/R > 0.24, where
!> a sphere is no longer a half-space. u_pl is the deformation-theory field at delta_max
!> (the box problem at delta_max); for a smooth sphere the capped zone grows with delta,
!> so it equals the accumulated plastic displacement of a monotone loading.
module egw_cap_sphere
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, fatal_error, format_real, int_str, &
      & egw_invalid_argument, egw_not_converged
   use egw_halfspace, only: radial_mesh, build_mesh, assemble_influence
   use egw_lapack, only: dgetrf, dgetrs
   implicit none
   private

   public :: cap_options, cap_result, cap_history
   public :: cap_load, cap_unload, cap_restitution, cap_units
   public :: cap_load_scaled_work, cap_unload_scaled_work

   !> Mesh and iteration options of the cap solver.
   type :: cap_options
      integer :: n_rings = 100      !< rings of the coarsest level (>= 8)
      integer :: n_levels = 3       !< levels n, 2n, 4n ... (>= 2)
      integer :: max_active = 60    !< active-set iterations before PSOR
      integer :: max_sweeps = 200000 !< PSOR sweeps
      integer :: n_quad = 16        !< Gauss points of the work integrals
   end type cap_options

   !> A solve's result in the caller's units.
   type :: cap_result
      real(dp) :: force = 0.0_dp           !< P
      real(dp) :: stiffness = 0.0_dp       !< dP/d delta (at fixed plastic field)
      real(dp) :: contact_radius = 0.0_dp  !< a
      real(dp) :: cap_radius = 0.0_dp      !< radius of the capped (plastic) zone
      real(dp) :: max_pressure = 0.0_dp    !< max p (<= p_y)
      real(dp) :: force_error = 0.0_dp     !< estimate: |P(finest) - P(level before)|
   end type cap_result

   !> What unloading needs of a loading to delta_max, per level (scaled units).
   type :: cap_history
      real(dp) :: radius = 0, modulus = 0, flow_pressure = 0
      real(dp) :: delta_y = 0, a_y = 0, force_y = 0
      real(dp) :: delta_max = 0            !< scaled Delta_max
      real(dp) :: residual = 0             !< scaled residual overlap Delta_res
      real(dp) :: outer = 0                !< L, the mesh's outer radius (scaled)
      logical :: elastic = .true.          !< Delta_max <= 1: Hertz, reversible
      integer :: n_levels = 0
      integer, allocatable :: n(:)         !< uniform rings per level (before grading)
      real(dp), allocatable :: centre(:)   !< per level: graded toward this radius (0: uniform)
      real(dp), allocatable :: u_pl(:, :) !< (max n, level) plastic displacement
      real(dp), allocatable :: residual_level(:)
      type(cap_options) :: options
   end type cap_history

   !> One level: rings and the symmetrised influence matrix.
   type :: cap_level
      integer :: n = 0
      real(dp) :: outer = 0
      real(dp), allocatable :: rho(:), width(:), area(:), a(:, :)
   end type cap_level

   !> The edge-graded mesh (doc/theory.md section 12, trap iv): rings refined by 2**edge_levels
   !> within edge_zone coarse rings of the contact edge, growing by edge_growth per ring.
   integer, parameter :: edge_levels = 4
   real(dp), parameter :: edge_zone = 1.0_dp, edge_growth = 0.3_dp

contains

   !> Units of the cap model: delta_y = (pi p_y/(2E))**2 R, a_y, P_y = (4/3)E sqrt(R) delta_y**1.5.
   pure subroutine cap_units(radius, modulus, flow_pressure, delta_y, a_y, force_y)
      real(dp), intent(in) :: radius, modulus, flow_pressure
      real(dp), intent(out) :: delta_y, a_y, force_y
      delta_y = (pi*flow_pressure/(2.0_dp*modulus))**2*radius
      a_y = sqrt(radius*delta_y)
      force_y = 4.0_dp/3.0_dp*modulus*sqrt(radius)*delta_y**1.5_dp
   end subroutine cap_units

   pure subroutine check_inputs(radius, modulus, flow_pressure, options, error)
      real(dp), intent(in) :: radius, modulus, flow_pressure
      type(cap_options), intent(in) :: options
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

   !> Build a level on [0, outer] (scaled units): n uniform rings, or (centre > 0) rings of
   !> the same width h = outer/n away from centre, refined to h/2**edge_levels within
   !> edge_zone*h of it and growing by the factor 1 + edge_growth per ring in between.
   subroutine make_level(n, outer, centre, lev, error)
      integer, intent(in) :: n
      real(dp), intent(in) :: outer, centre
      type(cap_level), intent(out) :: lev
      type(egw_error), allocatable, intent(out) :: error
      type(radial_mesh) :: mesh
      real(dp), allocatable :: h(:, :), edges(:)
      integer :: i, stat
      if (centre > 0.0_dp) then
         call graded_edges(n, outer, centre, edges)
      else
         edges = [(outer*real(i, dp)/real(n, dp), i=0, n)]
      end if
      lev%n = size(edges) - 1
      lev%outer = outer
      call build_mesh(edges, 1, 1, mesh)
      lev%rho = mesh%gauss_r
      lev%width = edges(2:lev%n + 1) - edges(1:lev%n)
      lev%area = lev%rho*lev%width
      allocate (h(lev%n, lev%n))
      call assemble_influence(mesh, lev%rho, h, 1, stat)
      if (stat /= 0) then
         call fatal_error(error, egw_not_converged, "cap solver: influence matrix of " &
            & //int_str(lev%n)//" rings could not be allocated")
         return
      end if
      ! Scaled deflection w = (2/pi) * (E = 1 deflection); A = sym(D H).
      do i = 1, lev%n
         h(i, :) = 2.0_dp/pi*lev%area(i)*h(i, :)
      end do
      lev%a = 0.5_dp*(h + transpose(h))
   end subroutine make_level

   !> Ring edges on [0, outer] graded toward centre (see make_level).
   pure subroutine graded_edges(n, outer, centre, edges)
      integer, intent(in) :: n
      real(dp), intent(in) :: outer, centre
      real(dp), allocatable, intent(out) :: edges(:)
      real(dp) :: coarse, fine, x, s, buf(max_graded_rings(n) + 1)
      integer :: k
      coarse = outer/real(n, dp)
      fine = coarse/2.0_dp**edge_levels
      buf(1) = 0.0_dp
      x = 0.0_dp
      k = 1
      do
         s = min(coarse, fine*(1.0_dp + max(0.0_dp, abs(x - centre) - edge_zone*coarse) &
            & *edge_growth/fine))
         ! approaching the centre: the ring may not overshoot into the fine zone
         if (x < centre) s = min(s, max(fine, fine + (centre - edge_zone*coarse - x) &
            & *edge_growth/(1.0_dp + edge_growth)))
         if (x + 1.5_dp*s >= outer .or. k == size(buf) - 1) exit
         x = x + s
         k = k + 1
         buf(k) = x
      end do
      k = k + 1
      buf(k) = outer
      edges = buf(1:k)
   end subroutine graded_edges

   !> An upper bound of the rings of a graded level of base n (sizes the history).
   pure integer function max_graded_rings(n) result(m)
      integer, intent(in) :: n
      m = n + 2*ceiling((edge_zone + 1.0_dp)*2.0_dp**edge_levels) &
         & + 2*ceiling(log(2.0_dp**edge_levels)/log(1.0_dp + edge_growth)) + 8
   end function max_graded_rings

   !> Box complementarity 0 <= p <= cap, y = A p + b (see the module header).
   subroutine solve_box(lev, b, cap, options, p, error)
      type(cap_level), intent(in) :: lev
      real(dp), intent(in) :: b(:), cap
      type(cap_options), intent(in) :: options
      real(dp), intent(inout) :: p(:)     !< in: start; out: solution
      type(egw_error), allocatable, intent(out) :: error
      integer :: round
      logical :: done
      do round = 1, 3
         call active_set(lev, b, cap, options%max_active, p, done)
         if (done) return
         call psor(lev, b, cap, options%max_sweeps, p, done)
         if (.not. done) exit
      end do
      call fatal_error(error, egw_not_converged, "cap solver: the box problem of " &
         & //int_str(lev%n)//" rings did not converge (active set cycled, PSOR after " &
         & //int_str(options%max_sweeps)//" sweeps)")
   end subroutine solve_box

   !> Primal-dual active set; done = .false. on a cycle or after max_iter.
   subroutine active_set(lev, b, cap, max_iter, p, done)
      type(cap_level), intent(in) :: lev
      real(dp), intent(in) :: b(:), cap
      integer, intent(in) :: max_iter
      real(dp), intent(inout) :: p(:)
      logical, intent(out) :: done
      integer :: state(lev%n), seen(lev%n, max_iter), it, k, m, info, i
      integer, allocatable :: idx(:), ipiv(:)
      real(dp), allocatable :: m_ii(:, :), rhs(:, :)
      real(dp) :: y(lev%n), c(lev%n), pn(lev%n)
      done = .false.
      c = 1.0_dp/[(lev%a(i, i), i=1, lev%n)]
      do it = 1, max_iter
         y = matmul(lev%a, p) + b
         ! -1 free (p = 0), 0 elastic, 1 capped (p = cap)
         state = 0
         where (p - c*y <= 0.0_dp) state = -1
         where (p - c*y >= cap) state = 1
         do k = 1, it - 1
            if (all(seen(:, k) == state)) return    ! a cycle: give up to PSOR
         end do
         seen(:, it) = state
         idx = pack([(i, i=1, lev%n)], state == 0)
         m = size(idx)
         pn = 0.0_dp
         where (state == 1) pn = cap
         if (m > 0) then
            m_ii = lev%a(idx, idx)
            allocate (rhs(m, 1), ipiv(m))
            rhs(:, 1) = -b(idx) - matmul(lev%a(idx, :), pn)
            call dgetrf(m, m, m_ii, m, ipiv, info)
            if (info /= 0) return
            call dgetrs('N', m, 1, m_ii, m, ipiv, rhs, m, info)
            pn(idx) = rhs(:, 1)
            deallocate (rhs, ipiv)
         end if
         p = pn
         y = matmul(lev%a, p) + b
         if (all(p >= 0.0_dp .and. p <= cap) .and. all(y >= -1.0e-13_dp*maxval(abs(b)) &
            & .or. state /= -1) .and. all(y <= 1.0e-13_dp*maxval(abs(b)) .or. state /= 1)) then
            done = .true.
            return
         end if
      end do
   end subroutine active_set

   !> Projected SOR (omega = 1.5) to 1e-13 of the cap in the largest change of a sweep.
   subroutine psor(lev, b, cap, max_sweeps, p, done)
      type(cap_level), intent(in) :: lev
      real(dp), intent(in) :: b(:), cap
      integer, intent(in) :: max_sweeps
      real(dp), intent(inout) :: p(:)
      logical, intent(out) :: done
      integer :: sweep, i
      real(dp) :: change, new
      done = .false.
      do sweep = 1, max_sweeps
         change = 0.0_dp
         do i = 1, lev%n
            new = p(i) - 1.5_dp*(dot_product(lev%a(:, i), p) + b(i))/lev%a(i, i)
            new = min(cap, max(0.0_dp, new))
            change = max(change, abs(new - p(i)))
            p(i) = new
         end do
         if (change <= 1.0e-13_dp*cap) then
            done = .true.
            return
         end if
      end do
   end subroutine psor

   !> Scaled force, stiffness, radii of a box solution.
   subroutine read_off(lev, p, cap, force, stiffness, contact, capped, pmax)
      type(cap_level), intent(in) :: lev
      real(dp), intent(in) :: p(:), cap
      real(dp), intent(out) :: force, stiffness, contact, capped, pmax
      integer, allocatable :: idx(:), ipiv(:)
      real(dp), allocatable :: m_ii(:, :), rhs(:, :)
      integer :: m, info, k, i
      force = 3.0_dp*sum(lev%area*p)
      pmax = maxval(p)
      ! tangent: elastic rings move, capped and free ones do not
      idx = pack([(i, i=1, lev%n)], p > 0.0_dp .and. p < cap)
      m = size(idx)
      stiffness = 0.0_dp
      if (m > 0) then
         m_ii = lev%a(idx, idx)
         allocate (rhs(m, 1), ipiv(m))
         rhs(:, 1) = lev%area(idx)
         call dgetrf(m, m, m_ii, m, ipiv, info)
         if (info == 0) call dgetrs('N', m, 1, m_ii, m, ipiv, rhs, m, info)
         stiffness = 3.0_dp*sum(lev%area(idx)*rhs(:, 1))
      end if
      ! contact edge: p**2 linear in rho over the last two loaded rings (p ~ sqrt(a - rho))
      k = 0
      do i = lev%n, 1, -1
         if (p(i) > 0.0_dp) then
            k = i
            exit
         end if
      end do
      contact = 0.0_dp
      if (k >= 2) then
         if (p(k - 1)**2 > p(k)**2) then
            contact = lev%rho(k) + p(k)**2*(lev%rho(k) - lev%rho(k - 1)) &
               & /(p(k - 1)**2 - p(k)**2)
            contact = min(contact, lev%rho(k) + lev%width(k))
         else
            contact = lev%rho(k) + 0.5_dp*lev%width(k)
         end if
      end if
      capped = 0.0_dp
      do i = lev%n, 1, -1
         if (p(i) >= cap) then
            capped = lev%rho(i) + 0.5_dp*lev%width(i)
            exit
         end if
      end do
   end subroutine read_off

   !> Scaled loading solve at Delta on one level: p (warm start in, solution out).
   subroutine load_level(lev, delta, options, p, error)
      type(cap_level), intent(in) :: lev
      real(dp), intent(in) :: delta
      type(cap_options), intent(in) :: options
      real(dp), intent(inout) :: p(:)
      type(egw_error), allocatable, intent(out) :: error
      call solve_box(lev, lev%area*(0.5_dp*lev%rho**2 - delta), 1.0_dp, options, p, error)
   end subroutine load_level

   !> Loading solve at delta_max (>= 0) of a sphere R, E* against the cap p_y; keeps the
   !> plastic field in history for cap_unload. Below delta_y: Hertz (closed form).
   subroutine cap_load(radius, modulus, flow_pressure, delta_max, options, history, result, &
      & error)
      real(dp), intent(in) :: radius          !< equivalent radius R > 0
      real(dp), intent(in) :: modulus         !< effective modulus E* > 0
      real(dp), intent(in) :: flow_pressure   !< p_y, 0 < p_y < E*
      real(dp), intent(in) :: delta_max       !< overlap >= 0
      type(cap_options), intent(in) :: options
      type(cap_history), intent(out) :: history
      type(cap_result), intent(out) :: result
      type(egw_error), allocatable, intent(out) :: error
      type(cap_level) :: lev
      real(dp), allocatable :: p(:), b(:)
      real(dp) :: dm, f, k, a, c, pm, f_prev
      integer :: l, nmax
      call check_inputs(radius, modulus, flow_pressure, options, error)
      if (allocated(error)) return
      if (.not. ieee_is_finite(delta_max) .or. .not. delta_max >= 0.0_dp) then
         call fatal_error(error, egw_invalid_argument, "delta_max = "//format_real(delta_max) &
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
         call fatal_error(error, egw_invalid_argument, "delta_max = "//format_real(delta_max) &
            & //": beyond 1e6 delta_y (the cap model's range)")
         return
      end if
      if (dm <= 1.0_dp) then
         history%elastic = .true.
         history%residual = 0.0_dp
         call hertz_scaled(dm, f, k, a, pm)
         call unscale(history, f, k, a, 0.0_dp, pm, 0.0_dp, result)
         return
      end if
      history%elastic = .false.
      history%outer = 1.05_dp*sqrt(2.0_dp*dm)
      history%n_levels = options%n_levels
      nmax = max_graded_rings(options%n_rings*2**(options%n_levels - 1))
      allocate (history%n(options%n_levels), history%u_pl(nmax, options%n_levels))
      allocate (history%residual_level(options%n_levels), history%centre(options%n_levels))
      history%u_pl = 0.0_dp
      history%centre = 0.0_dp
      f_prev = 0.0_dp
      a = 0.0_dp
      c = 0.0_dp
      do l = 1, options%n_levels
         ! level 1 uniform; once the capped zone reaches the contact edge (to within a
         ! ring of the level before: the boundary layer of trap iv) each finer level is
         ! graded toward the edge found before. (Graded meshes with a wide elastic ring,
         ! below ~5 delta_y, make the box problem fail to converge, and gain nothing there.)
         if (l > 1 .and. a >= c .and. a - c <= edge_zone*history%outer/history%n(l - 1) &
            & .and. a < 0.95_dp*history%outer) history%centre(l) = a
         history%n(l) = options%n_rings*2**(l - 1)
         call load_on_level(history%n(l), history%outer, dm, options, history%centre(l), &
            & lev, p, error)
         if (allocated(error)) return
         b = lev%area*(0.5_dp*lev%rho**2 - dm)
         call read_off(lev, p, 1.0_dp, f, k, a, c, pm)
         ! plastic displacement = interpenetration of the capped rings, -gap
         where (p >= 1.0_dp) history%u_pl(1:lev%n, l) = &
            & max(0.0_dp, -(matmul(lev%a, p) + b)/lev%area)
         history%residual_level(l) = minval(0.5_dp*lev%rho**2 + history%u_pl(1:lev%n, l))
         if (l == options%n_levels) result%force_error = abs(f - f_prev)*history%force_y
         f_prev = f
      end do
      history%residual = history%residual_level(options%n_levels)
      call unscale(history, f, k, a, c, pm, result%force_error, result)
   end subroutine cap_load

   !> Loading solve at Delta on a level of base n rings graded toward centre (0: uniform).
   !> A graded box problem that does not converge (its active set cycles; PSOR is slow on
   !> the fine rings, so it gets few sweeps) is retried with the fine zone shifted by
   !> a third of a coarse ring either way, then on the uniform mesh (centre returns 0).
   subroutine load_on_level(n, outer, delta, options, centre, lev, p, error)
      integer, intent(in) :: n
      real(dp), intent(in) :: outer, delta
      type(cap_options), intent(in) :: options
      real(dp), intent(inout) :: centre
      type(cap_level), intent(out) :: lev
      real(dp), allocatable, intent(out) :: p(:)
      type(egw_error), allocatable, intent(out) :: error
      type(cap_options) :: quick
      real(dp) :: shift(3), try
      integer :: i
      quick = options
      quick%max_sweeps = min(options%max_sweeps, 2000)
      shift = [0.0_dp, 1.0_dp, -1.0_dp]*outer/(3.0_dp*real(n, dp))
      if (centre > 0.0_dp) then
         do i = 1, size(shift)
            try = centre + shift(i)
            call make_level(n, outer, try, lev, error)
            if (allocated(error)) return
            p = min(1.0_dp, sqrt(max(0.0_dp, delta - lev%rho**2)))
            call load_level(lev, delta, quick, p, error)
            if (.not. allocated(error)) then
               centre = try
               return
            end if
         end do
      end if
      centre = 0.0_dp
      call make_level(n, outer, centre, lev, error)
      if (allocated(error)) return
      p = min(1.0_dp, sqrt(max(0.0_dp, delta - lev%rho**2)))
      call load_level(lev, delta, options, p, error)
   end subroutine load_on_level

   pure subroutine hertz_scaled(d, f, k, a, pm)
      real(dp), intent(in) :: d
      real(dp), intent(out) :: f, k, a, pm
      f = max(d, 0.0_dp)**1.5_dp
      k = 1.5_dp*sqrt(max(d, 0.0_dp))
      a = sqrt(max(d, 0.0_dp))
      pm = a
   end subroutine hertz_scaled

   pure subroutine unscale(history, f, k, a, c, pm, ferr, result)
      type(cap_history), intent(in) :: history
      real(dp), intent(in) :: f, k, a, c, pm, ferr
      type(cap_result), intent(inout) :: result
      result%force = f*history%force_y
      result%stiffness = k*history%force_y/history%delta_y
      result%contact_radius = a*history%a_y
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
      type(cap_result), intent(out) :: result
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: d, f, k, a, c, pm, f_prev, ferr
      integer :: l
      type(cap_level) :: lev
      real(dp), allocatable :: p(:)
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
         call unscale(history, f, k, a, 0.0_dp, pm, 0.0_dp, result)
         return
      end if
      if (d <= history%residual) then
         call unscale(history, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, result)
         return
      end if
      f_prev = 0.0_dp
      ferr = 0.0_dp
      do l = 1, history%n_levels
         call make_level(history%n(l), history%outer, history%centre(l), lev, error)
         if (allocated(error)) return
         call unload_level(lev, history%u_pl(1:lev%n, l), d, history%options, p, error)
         if (allocated(error)) return
         call read_off(lev, p, huge(1.0_dp), f, k, a, c, pm)
         if (l == history%n_levels) ferr = abs(f - f_prev)*history%force_y
         f_prev = f
      end do
      call unscale(history, f, k, a, 0.0_dp, pm, ferr, result)
   end subroutine cap_unload

   subroutine unload_level(lev, u_pl, d, options, p, error)
      type(cap_level), intent(in) :: lev
      real(dp), intent(in) :: u_pl(:), d
      type(cap_options), intent(in) :: options
      real(dp), allocatable, intent(out) :: p(:)
      type(egw_error), allocatable, intent(out) :: error
      p = min(1.0_dp, sqrt(max(0.0_dp, d - lev%rho**2 - u_pl)))
      call solve_box(lev, lev%area*(0.5_dp*lev%rho**2 + u_pl - d), huge(1.0_dp), options, &
         & p, error)
   end subroutine unload_level

   !> Scaled loading work W(Delta_m) = int_0^Delta_m P dDelta (units P_y delta_y):
   !> 2/5 up to first yield, then Gauss-Legendre in t, Delta = 1 + (Delta_m - 1) t**2.
   subroutine cap_load_scaled_work(dm, options, work, force_m, error)
      real(dp), intent(in) :: dm
      type(cap_options), intent(in) :: options
      real(dp), intent(out) :: work, force_m   !< W and P(Delta_m), scaled
      type(egw_error), allocatable, intent(out) :: error
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
      real(dp), intent(in) :: dm
      type(cap_options), intent(in) :: options
      real(dp), intent(out) :: work, residual
      type(egw_error), allocatable, intent(out) :: error
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
      real(dp), intent(in) :: radius, modulus, flow_pressure
      real(dp), intent(in) :: mass       !< effective mass m* > 0
      real(dp), intent(in) :: velocity   !< impact speed v > 0
      type(cap_options), intent(in) :: options
      real(dp), intent(out) :: e
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
      vy = sqrt(16.0_dp/15.0_dp*(pi/2.0_dp)**5*flow_pressure**5*radius**3 &
         & /(mass*modulus**4))
      target = 0.4_dp*(velocity/vy)**2
      if (present(max_overlap)) max_overlap = (target/0.4_dp)**0.4_dp* &
         & (pi*flow_pressure/(2.0_dp*modulus))**2*radius
      if (velocity <= vy) return
      if (target > 1.0e8_dp) then
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
      e = sqrt(wu/wl)
      if (present(max_overlap)) max_overlap = dm*(pi*flow_pressure/(2.0_dp*modulus))**2*radius
   end subroutine cap_restitution

end module egw_cap_sphere
