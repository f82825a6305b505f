!> The axisymmetric elastic half-space on a radial mesh (doc/theory.md §4):
!>
!>   w(r) = 4/(pi E) int_0^abar t/(r+t) p(t) K(k) dt,   k = 2 sqrt(r t)/(r+t),
!>
!> in units where E = 1. This module owns the mesh (elements, collocation nodes, Gauss
!> points) and the influence coefficients that map pressure at the Gauss points to the
!> deflection at any radius.
!>
!> Discretisation. On each element the pressure is the polynomial of degree n_gauss - 1
!> through its values at the element's n_gauss Gauss-Legendre points (no continuity
!> imposed, so a pressure known pointwise is represented to O(h**n_gauss)). The
!> deflection (the solver's unknown) lives on the nodes of continuous Lagrange elements
!> of degree `degree` (Chebyshev-Lobatto nodes). Influence coefficients integrate the
!> kernel times each pressure basis polynomial:
!> - far from r (distance >= 2 element lengths) by the element's own Gauss rule, which
!>   then is exact to ~rho**(-2 n_gauss), rho >= 9.9 (Bernstein ellipse);
!> - near r by bisection into pieces whose distance from r is at least their length
!>   (8-point Gauss), and, on pieces no longer than r/2 that end at r (there kc <= 1/3),
!>   by 14-point product integration: with
!>   kc = |r-t|/(r+t), K = kreg + klog ln(r+t) - klog ln|r-t| (egw_ellip), the smooth
!>   parts by Gauss and the ln|r-t| part by Gauss weights modified to integrate
!>   ln(x) times a polynomial exactly (moments of shifted Legendre polynomials). The
!>   kernel is never sampled near its singularity. The rule sizes were chosen so that the
!>   uniform-disc test (exact pressure representation) holds to 1e-15.
module egw_halfspace
   !$ use omp_lib, only: omp_get_num_procs
   use egw_kinds, only: dp, pi
   use egw_simd, only: simd_level, simd_far_kernel, simd_log_piece, simd_batch6
   use egw_ellip, only: ellipk_comp_fast, ellipk_log_split, ellipk_fast_p, ellipk_fast_q, &
      & ellipk_split_a, ellipk_split_b
   implicit none
   private

   public :: radial_mesh, build_mesh, graded_edges, mesh_nodes, node_index
   public :: influence_row, assemble_influence, interpolate_nodal, interpolate_nodal_walk, &
      & halfspace_kernel
   public :: influence_cache, assemble_influence_cached, cached_point_values, keep_point_values, &
      & clear_cache
   public :: gauss_legendre

   !> Points of the plain rule on near pieces and of the log-product rule. Max error on the
   !> uniform disc (test_halfspace) with n_log = 14: 9e-16 for n_fine = 10 or 12, 9e-15 for
   !> 8, 1.5e-11 for 6; 8 is 1e-14 relative to w, far below any force tolerance, and the near
   !> pieces are most of the assembly's kernel evaluations. n_log = 12 lost a digit.
   integer, parameter :: n_fine = 8, n_log = 14
   !> Recursion guard for the bisection of near pieces (r is never closer than
   !> 2**(-max_depth) element lengths to a piece without being on its end).
   integer, parameter :: max_depth = 60

   !> Points queued for add_batch: this many at most (a near element takes 30-100).
   integer, parameter :: max_batch = 128

   !> Quadrature points of a near element's pieces not yet summed into its coefficients:
   !> local coordinates s on [-1, 1] and weights wt (kernel included).
   type :: point_batch
      integer :: m = 0
      real(dp) :: s(max_batch), wt(max_batch)
   end type point_batch

   !> Radial mesh: elements [edge(e-1), edge(e)], e = 1..n_elem, edge(0) = 0.
   type :: radial_mesh
      integer :: n_elem = 0
      !> Degree of the continuous Lagrange elements of the deflection.
      integer :: degree = 2
      !> Gauss points per element, the pressure nodes.
      integer :: n_gauss = 8
      real(dp), allocatable :: edge(:)        !< (0:n_elem) element boundaries
      real(dp), allocatable :: node(:)        !< (n_elem*degree + 1) deflection nodes
      real(dp), allocatable :: gauss_r(:)     !< (n_elem*n_gauss) pressure points
      real(dp), allocatable :: gauss_w(:)     !< their weights for int dr
      real(dp), allocatable :: local_s(:)     !< (n_gauss) Gauss points on [-1, 1]
      real(dp), allocatable :: local_w(:)     !< (n_gauss) their weights
      real(dp), allocatable :: local_bary(:)  !< (n_gauss) barycentric weights of local_s
      real(dp), allocatable :: node_s(:)      !< (0:degree) element nodes on [-1, 1]
      !> interp(j, q): weight of local node j in the deflection at Gauss point q.
      real(dp), allocatable :: interp(:, :)
      real(dp), allocatable :: fine_s(:), fine_w(:)  !< n_fine-point rule on [-1, 1]
      real(dp), allocatable :: log_x(:), log_w(:)    !< n_log-point rule on [0, 1]
      !> log_lw: weights with sum log_lw f(x) = int_0^1 f(x) ln(x) dx for degree < n_log.
      real(dp), allocatable :: log_lw(:)
   end type radial_mesh

   !> Meshes an influence_cache keeps, and the largest matrix it keeps (entries; 16 MB).
   integer, parameter :: cache_meshes = 3, cache_max_entries = 2*1024*1024

   !> One mesh's influence matrix as assemble_influence_cached stored it.
   type :: cached_matrix
      logical :: filled = .false.   !< holds a mesh (else its storage is free)
      real(dp), allocatable :: edge(:)       !< (0:n_elem) its element edges
      real(dp), allocatable :: node(:)       !< its deflection nodes
      integer :: n_row = 0   !< n_elem*n_gauss: the length of a node's row
      !> the matrix transposed, a node's row contiguous: node k's row is
      !> rows((k - 1)*n_row + 1:k*n_row) (storage kept when the slot is emptied or
      !> refilled, so that it may be longer)
      real(dp), allocatable :: rows(:)
      !> values its caller keeps at the mesh's Gauss points (keep_point_values), and the
      !> caller's key for them (values under another key are not served)
      logical :: has_values = .false.
      real(dp), allocatable :: point_values(:)
      real(dp) :: key = 0.0_dp
   end type cached_matrix

   !> The influence matrices of the last few meshes of one caller (one solve's levels),
   !> for assemble_influence_cached. A coefficient depends only on the node's radius and
   !> the element's two edges (and the rules, fixed by n_gauss), so a mesh that shares
   !> nodes and elements with a stored one takes those coefficients from it: the same
   !> numbers, computed the same way. Owned by one caller (a solve's route, or a
   !> solver_workspace that its routes reuse one after another): no sharing between
   !> threads. clear_cache empties it as a new one but keeps its storage, which the next
   !> meshes reuse (a slot's rows and the spare grow only; issue 32: fresh matrices a
   !> mesh were ~8 % of a rough + cap hysteresis build's CPU in page faults).
   type :: influence_cache
      integer :: last = 0   !< the slot stored last (0: none)
      integer :: n_gauss = 0
      type(cached_matrix) :: slot(cache_meshes)
      !> the next mesh's rows (as a slot's), swapped with the slot that stores it
      real(dp), allocatable :: spare(:)
      !> a mesh whose rules build_mesh copies (the first its owner built: rules depend
      !> only on the degree and n_gauss; kept by clear_cache)
      type(radial_mesh) :: rules
   end type influence_cache

contains

   !> Gauss-Legendre rule of n points on [-1, 1] (Newton on P_n from the asymptotic
   !> guesses; converged to rounding).
   pure subroutine gauss_legendre(n, x, w)
      integer, intent(in) :: n   !< points, >= 1
      real(dp), intent(out) :: x(n), w(n)   !< the nodes (ascending) and weights
      integer :: i, it
      real(dp) :: z, p, dpn
      do i = 1, (n + 1)/2
         z = cos(pi*(real(i, dp) - 0.25_dp)/(real(n, dp) + 0.5_dp))
         do it = 1, 100
            call legendre_p(n, z, p, dpn)
            z = z - p/dpn
            if (abs(p/dpn) < 1.0e-16_dp) exit
         end do
         call legendre_p(n, z, p, dpn)
         x(i) = -z
         x(n + 1 - i) = z
         w(i) = 2.0_dp/((1.0_dp - z*z)*dpn*dpn)
         w(n + 1 - i) = w(i)
      end do
   end subroutine gauss_legendre

   !> P_n(z) and P_n'(z) by the three-term recurrence.
   pure subroutine legendre_p(n, z, p, dpn)
      integer, intent(in) :: n
      real(dp), intent(in) :: z
      real(dp), intent(out) :: p, dpn
      real(dp) :: p0, p1
      integer :: k
      p0 = 1.0_dp
      p1 = z
      if (n == 0) then
         p = 1.0_dp; dpn = 0.0_dp; return
      end if
      do k = 2, n
         p = (real(2*k - 1, dp)*z*p1 - real(k - 1, dp)*p0)/real(k, dp)
         p0 = p1
         p1 = p
      end do
      p = p1
      dpn = real(n, dp)*(z*p1 - p0)/(z*z - 1.0_dp)
   end subroutine legendre_p

   !> Element boundaries graded about a focus radius r_focus >= 0 (the Hertz edge, or 0):
   !> uniform in xi = asinh((r - r_focus)/width), so elements are ~width*step long at the
   !> focus and grow geometrically (ratio ~ 1 + step) away from it. r_focus is an edge.
   pure function graded_edges(r_focus, width, r_outer, step) result(edge)
      real(dp), intent(in) :: r_focus   !< focus radius, 0 <= r_focus < r_outer
      real(dp), intent(in) :: width     !< length scale of the finest elements (> 0)
      real(dp), intent(in) :: r_outer   !< outer radius of the mesh
      real(dp), intent(in) :: step      !< element size in xi (> 0)
      real(dp), allocatable :: edge(:)
      real(dp) :: xi_in, xi_out
      integer :: n_in, n_out, i
      xi_in = asinh(r_focus/width)
      xi_out = asinh((r_outer - r_focus)/width)
      n_in = 0
      if (r_focus > 0.0_dp) n_in = max(1, ceiling(xi_in/step))
      n_out = max(1, ceiling(xi_out/step))
      allocate (edge(0:n_in + n_out))
      do i = 0, n_in
         edge(i) = r_focus - width*sinh(xi_in*real(n_in - i, dp)/real(max(n_in, 1), dp))
      end do
      do i = 1, n_out
         edge(n_in + i) = r_focus + width*sinh(xi_out*real(i, dp)/real(n_out, dp))
      end do
      edge(0) = 0.0_dp
      edge(n_in + n_out) = r_outer
   end function graded_edges

   !> Build the mesh on the element boundaries edge(0:n) (edge(0) = 0, increasing).
   !> rules (optional): a built mesh whose quadrature rules and element interpolation are
   !> taken where its degree and n_gauss are these (they depend on nothing else: the same
   !> numbers as computed here), instead of computing them again.
   pure subroutine build_mesh(edge, degree, n_gauss, mesh, rules)
      real(dp), intent(in) :: edge(0:)   !< element boundaries, edge(0) = 0, increasing
      integer, intent(in) :: degree    !< deflection element degree >= 1
      integer, intent(in) :: n_gauss   !< pressure points per element >= 1
      type(radial_mesh), intent(out) :: mesh   !< the mesh, nodes and Gauss points filled
      type(radial_mesh), intent(in), optional :: rules   !< a built mesh (its rules taken)
      integer :: e, j, q, n
      real(dp) :: x0, x1
      logical :: copied

      n = size(edge) - 1
      mesh%n_elem = n
      mesh%degree = degree
      mesh%n_gauss = n_gauss
      mesh%edge = edge
      copied = .false.
      if (present(rules)) copied = rules%degree == degree .and. rules%n_gauss == n_gauss &
         & .and. allocated(rules%log_lw)
      if (copied) then
         mesh%local_s = rules%local_s
         mesh%local_w = rules%local_w
         mesh%local_bary = rules%local_bary
         mesh%node_s = rules%node_s
         mesh%interp = rules%interp
         mesh%fine_s = rules%fine_s
         mesh%fine_w = rules%fine_w
         mesh%log_x = rules%log_x
         mesh%log_w = rules%log_w
         mesh%log_lw = rules%log_lw
      else
         call build_rules(mesh)
      end if
      allocate (mesh%node(n*degree + 1), mesh%gauss_r(n*n_gauss), mesh%gauss_w(n*n_gauss))
      do e = 1, n
         x0 = edge(e - 1)
         x1 = edge(e)
         do j = 0, degree
            mesh%node(node_index(mesh, e, j)) = 0.5_dp*(x0 + x1) + 0.5_dp*(x1 - x0)*mesh%node_s(j)
         end do
         ! Ends exactly equal to the edges, so collocation at an edge is recognised as such.
         mesh%node(node_index(mesh, e, 0)) = x0
         mesh%node(node_index(mesh, e, degree)) = x1
         do q = 1, n_gauss
            mesh%gauss_r((e - 1)*n_gauss + q) = 0.5_dp*(x0 + x1) + 0.5_dp*(x1 - x0)*mesh%local_s(q)
            mesh%gauss_w((e - 1)*n_gauss + q) = 0.5_dp*(x1 - x0)*mesh%local_w(q)
         end do
      end do
   end subroutine build_mesh

   !> build_mesh's rules for mesh%degree and mesh%n_gauss: the Gauss points and weights,
   !> barycentric weights, element nodes and interpolation, the near pieces' and the
   !> log-product rules.
   pure subroutine build_rules(mesh)
      type(radial_mesh), intent(inout) :: mesh
      integer :: j, q, k, degree, n_gauss
      real(dp) :: pk, pkm1, pkm2
      degree = mesh%degree
      n_gauss = mesh%n_gauss
      allocate (mesh%local_s(n_gauss), mesh%local_w(n_gauss))
      call gauss_legendre(n_gauss, mesh%local_s, mesh%local_w)
      allocate (mesh%local_bary(n_gauss))
      do q = 1, n_gauss
         mesh%local_bary(q) = 1.0_dp/product(mesh%local_s(q) - mesh%local_s, &
            & mask=[(k /= q, k=1, n_gauss)])
      end do
      allocate (mesh%node_s(0:degree))
      do j = 0, degree
         mesh%node_s(j) = -cos(pi*real(j, dp)/real(degree, dp))
      end do
      mesh%node_s(0) = -1.0_dp
      mesh%node_s(degree) = 1.0_dp
      allocate (mesh%interp(0:degree, n_gauss))
      do q = 1, n_gauss
         mesh%interp(:, q) = lagrange_weights(mesh%node_s, mesh%local_s(q))
      end do
      allocate (mesh%fine_s(n_fine), mesh%fine_w(n_fine))
      call gauss_legendre(n_fine, mesh%fine_s, mesh%fine_w)
      allocate (mesh%log_x(n_log), mesh%log_w(n_log), mesh%log_lw(n_log))
      call gauss_legendre(n_log, mesh%log_x, mesh%log_w)
      mesh%log_x = 0.5_dp*(mesh%log_x + 1.0_dp)
      mesh%log_w = 0.5_dp*mesh%log_w
      ! Product weights: f = sum_k c_k P*_k (shifted Legendre), c_k = (2k+1) int f P*_k,
      ! and int_0^1 P*_k ln x dx = -1 (k = 0), (-1)**(k+1)/(k(k+1)) (k >= 1).
      do j = 1, n_log
         pkm2 = 1.0_dp
         pkm1 = 2.0_dp*mesh%log_x(j) - 1.0_dp
         mesh%log_lw(j) = -1.0_dp + 3.0_dp*pkm1*0.5_dp
         do k = 2, n_log - 1
            pk = (real(2*k - 1, dp)*(2.0_dp*mesh%log_x(j) - 1.0_dp)*pkm1 &
               & - real(k - 1, dp)*pkm2)/real(k, dp)
            mesh%log_lw(j) = mesh%log_lw(j) + real(2*k + 1, dp)*pk &
               & *real((-1)**(k + 1), dp)/real(k*(k + 1), dp)
            pkm2 = pkm1
            pkm1 = pk
         end do
         mesh%log_lw(j) = mesh%log_lw(j)*mesh%log_w(j)
      end do
   end subroutine build_rules

   !> Number of deflection nodes.
   pure integer function mesh_nodes(mesh)
      type(radial_mesh), intent(in) :: mesh   !< a built mesh
      mesh_nodes = mesh%n_elem*mesh%degree + 1
   end function mesh_nodes

   !> Global index of local node j (0..degree) of element e.
   pure integer function node_index(mesh, e, j)
      type(radial_mesh), intent(in) :: mesh   !< a built mesh
      integer, intent(in) :: e, j   !< element (1..n_elem) and local node (0..degree)
      node_index = (e - 1)*mesh%degree + j + 1
   end function node_index

   !> Lagrange basis weights at s for the nodes xs.
   pure function lagrange_weights(xs, s) result(l)
      real(dp), intent(in) :: xs(:), s
      real(dp) :: l(size(xs))
      integer :: i, k
      do i = 1, size(xs)
         l(i) = 1.0_dp
         do k = 1, size(xs)
            if (k /= i) l(i) = l(i)*(s - xs(k))/(xs(i) - xs(k))
         end do
      end do
   end function lagrange_weights

   !> Kernel 4/pi t/(r+t) K(k) of w = int kernel p dt (E = 1), r, t >= 0, r /= t.
   elemental real(dp) function halfspace_kernel(r, t) result(g)
      real(dp), intent(in) :: r, t   !< field and source radii, >= 0, r /= t
      if (r + t <= 0.0_dp) then
         g = 0.0_dp
         return
      end if
      g = 4.0_dp/pi*t/(r + t)*ellipk_comp_fast(abs(r - t)/(r + t))
   end function halfspace_kernel

   !> Influence row at radius r >= 0: w(r) = sum_i row(i) p(gauss_r(i)) (E = 1).
   pure subroutine influence_row(mesh, r, row, known)
      type(radial_mesh), intent(in) :: mesh   !< a built mesh
      real(dp), intent(in) :: r   !< radius of the row, >= 0
      !> size n_elem*n_gauss (contiguous: its runs go to far_kernel_run without a copy)
      real(dp), intent(inout), contiguous :: row(:)
      !> elements whose coefficients row holds already (left as they are)
      logical, intent(in), optional :: known(:)
      integer :: e, i0, first_far
      real(dp) :: x0, x1, dist
      type(point_batch) :: pts

      ! Far elements in runs of consecutive ones, each run's points in one loop
      ! (far_kernel_run), which the compiler vectorizes, log included.
      first_far = 0
      do e = 1, mesh%n_elem
         if (present(known)) then
            if (known(e)) then
               i0 = (e - 1)*mesh%n_gauss
               if (first_far > 0) call far_kernel_run(mesh%gauss_r(first_far:i0), &
                  & mesh%gauss_w(first_far:i0), r, row(first_far:i0))
               first_far = 0
               cycle
            end if
         end if
         x0 = mesh%edge(e - 1)
         x1 = mesh%edge(e)
         i0 = (e - 1)*mesh%n_gauss
         dist = max(0.0_dp, x0 - r, r - x1)
         if (r <= 0.0_dp .or. dist >= 2.0_dp*(x1 - x0)) then
            ! Smooth kernel on this element (at r = 0, K = pi/2 and the kernel is 2).
            if (first_far == 0) first_far = i0 + 1
         else
            if (first_far > 0) call far_kernel_run(mesh%gauss_r(first_far:i0), &
               & mesh%gauss_w(first_far:i0), r, row(first_far:i0))
            first_far = 0
            ! Accumulated in place: a local buffer of run-time size would be a heap array.
            row(i0 + 1:i0 + mesh%n_gauss) = 0.0_dp
            call add_piece(mesh, x0, x1, x0, x1, r, 0, pts, row(i0 + 1:i0 + mesh%n_gauss))
            call add_batch(mesh, pts, row(i0 + 1:i0 + mesh%n_gauss))
         end if
      end do
      i0 = mesh%n_elem*mesh%n_gauss
      if (first_far > 0) call far_kernel_run(mesh%gauss_r(first_far:i0), &
         & mesh%gauss_w(first_far:i0), r, row(first_far:i0))
   end subroutine influence_row

   !> row(i) = w(i) halfspace_kernel(r, t(i)) for points t(i) > 0 off r (kc in (0, 1]),
   !> with ellipk_comp_fast's formula written out so that the loop has no branch and no
   !> call but log (the compiler's vector log): the far field is most of the kernel
   !> evaluations of an assembly. On CPUs with AVX2 and FMA, egw_simd's 4-lane routine.
   pure subroutine far_kernel_run(t, w, r, row)
      real(dp), intent(in), contiguous :: t(:), w(:)
      real(dp), intent(in) :: r
      real(dp), intent(out), contiguous :: row(:)
      integer :: i
      real(dp) :: kc, eta, e2, e4, p, q, inv_sum
      if (size(t) == 0) return
      if (simd_level() == 1) then
         call simd_far_kernel(size(t), t, w, r, ellipk_fast_p, ellipk_fast_q, row)
         return
      end if
      do i = 1, size(t)
         inv_sum = 1.0_dp/(r + t(i))  ! one division a point
         kc = abs(r - t(i))*inv_sum
         eta = kc*kc
         e2 = eta*eta
         e4 = e2*e2
         associate (fp => ellipk_fast_p, fq => ellipk_fast_q)
            p = (fp(0) + fp(1)*eta) + e2*(fp(2) + fp(3)*eta) &
               & + e4*((fp(4) + fp(5)*eta) + e2*(fp(6) + fp(7)*eta) &
               & + e4*(fp(8) + fp(9)*eta))
            q = (fq(0) + fq(1)*eta) + e2*(fq(2) + fq(3)*eta) &
               & + e4*((fq(4) + fq(5)*eta) + e2*(fq(6) + fq(7)*eta) &
               & + e4*(fq(8) + fq(9)*eta))
         end associate
         row(i) = w(i)*(4.0_dp/pi*t(i)*inv_sum*(p - 2.0_dp*log(kc)*q))
      end do
   end subroutine far_kernel_run

   !> Add int_alpha^beta kernel(r, t) L_q(t) dt to acc(q) for the pressure basis L_q of the
   !> element [x0, x1]; bisects until r is far from the piece or at its end. The pieces'
   !> quadrature points go to pts and are summed into acc in batches (add_batch).
   pure recursive subroutine add_piece(mesh, x0, x1, alpha, beta, r, depth, pts, acc)
      type(radial_mesh), intent(in) :: mesh
      real(dp), intent(in) :: x0, x1, alpha, beta, r
      integer, intent(in) :: depth
      type(point_batch), intent(inout) :: pts
      real(dp), intent(inout) :: acc(:)
      real(dp) :: len, dist, mid

      len = beta - alpha
      if (len <= 0.0_dp) return
      if (r > alpha .and. r < beta) then
         call add_piece(mesh, x0, x1, alpha, r, r, depth + 1, pts, acc)
         call add_piece(mesh, x0, x1, r, beta, r, depth + 1, pts, acc)
         return
      end if
      mid = alpha + 0.5_dp*len
      if (r == alpha .or. r == beta) then
         ! kc <= 1/3 on a piece no longer than r/2 touching r: the log split is analytic there.
         if (len <= 0.5_dp*r .or. depth >= max_depth) then
            call add_log_piece(mesh, x0, x1, alpha, beta, r, pts, acc)
         else
            call add_piece(mesh, x0, x1, alpha, mid, r, depth + 1, pts, acc)
            call add_piece(mesh, x0, x1, mid, beta, r, depth + 1, pts, acc)
         end if
         return
      end if
      dist = min(abs(r - alpha), abs(r - beta))
      if (dist >= len .or. depth >= max_depth) then
         call add_gauss_piece(mesh, x0, x1, alpha, beta, r, pts, acc)
      else
         call add_piece(mesh, x0, x1, alpha, mid, r, depth + 1, pts, acc)
         call add_piece(mesh, x0, x1, mid, beta, r, depth + 1, pts, acc)
      end if
   end subroutine add_piece

   !> Plain n_fine-point Gauss on a piece at distance >= its length from r (t /= r, so
   !> the branch-free far_kernel_run applies).
   pure subroutine add_gauss_piece(mesh, x0, x1, alpha, beta, r, pts, acc)
      type(radial_mesh), intent(in) :: mesh
      real(dp), intent(in) :: x0, x1, alpha, beta, r
      type(point_batch), intent(inout) :: pts
      real(dp), intent(inout) :: acc(:)
      integer :: i
      real(dp) :: t(n_fine), w(n_fine), wt(n_fine)
      do i = 1, n_fine
         t(i) = 0.5_dp*(alpha + beta) + 0.5_dp*(beta - alpha)*mesh%fine_s(i)
         w(i) = 0.5_dp*(beta - alpha)*mesh%fine_w(i)
      end do
      call far_kernel_run(t, w, r, wt)
      call add_points(mesh, (2.0_dp*t - (x0 + x1))*(1.0_dp/(x1 - x0)), wt, pts, acc)
   end subroutine add_gauss_piece

   !> Product integration on a piece with r at one end (length <= r/2):
   !> kernel = 4/pi t/(r+t) [kreg + klog ln(r+t) - klog ln|t-r|], |t - r| = len x,
   !> so that len (log_w (g1 - g2 ln len) - log_lw g2) = len c (log_w (kreg + klog
   !> ln((r+t)/len)) - log_lw klog), c = 4/pi t/(r+t): one log a point. The n_log points
   !> as arrays (the loops vectorize, log included); kc <= 1/3 there, where the split is
   !> two fixed polynomials (split_near) instead of ellipk_log_split's series.
   pure subroutine add_log_piece(mesh, x0, x1, alpha, beta, r, pts, acc)
      type(radial_mesh), intent(in) :: mesh
      real(dp), intent(in) :: x0, x1, alpha, beta, r
      type(point_batch), intent(inout) :: pts
      real(dp), intent(inout) :: acc(:)
      real(dp) :: len, direction
      real(dp) :: t(n_log), inv_sum(n_log), kreg(n_log), klog(n_log), wt(n_log)
      len = beta - alpha
      direction = 1.0_dp
      if (r == beta) direction = -1.0_dp
      t = r + direction*len*mesh%log_x
      ! (on AVX2 + FMA the weights four lanes wide, egw_simd: ~a fifth of the assembly's
      ! instructions were these weights' two-lane polynomials and log)
      if (len <= 0.5_dp*r .and. simd_level() == 1) then
         call simd_log_piece(n_log, mesh%log_x, mesh%log_w, mesh%log_lw, r, len, direction, &
            & ellipk_split_a, ellipk_split_b, wt)
         call add_points(mesh, (2.0_dp*t - (x0 + x1))*(1.0_dp/(x1 - x0)), wt, pts, acc)
         return
      end if
      inv_sum = 1.0_dp/(r + t)
      ! |t - r|/(r + t) <= (r/2)/(3r/2) = 1/3 when len <= r/2 (add_piece's rule; only the
      ! recursion guard max_depth can leave a longer piece)
      if (len <= 0.5_dp*r) then
         call split_near(len*mesh%log_x*inv_sum, kreg, klog)
      else
         call ellipk_log_split(len*mesh%log_x*inv_sum, kreg, klog)
      end if
      wt = len*(4.0_dp/pi*t*inv_sum)*(mesh%log_w*(kreg + klog*log((r + t)*(1.0_dp/len))) &
         & - mesh%log_lw*klog)
      call add_points(mesh, (2.0_dp*t - (x0 + x1))*(1.0_dp/(x1 - x0)), wt, pts, acc)
   end subroutine add_log_piece

   !> ellipk_log_split for kc <= 1/3: kreg and klog as their power series in x = kc**2
   !> truncated after x**17 (egw_ellip's ellipk_split_a, _b; the truncation is below
   !> 1e-18 relative there), by Estrin's scheme; no branch, no division, so that the
   !> points of a piece vectorize.
   pure subroutine split_near(kc, kreg, klog)
      real(dp), intent(in) :: kc(:)
      real(dp), intent(out) :: kreg(:), klog(:)
      integer :: i
      real(dp) :: x, x2, x4, x8, x16
      do i = 1, size(kc)
         x = kc(i)*kc(i)
         x2 = x*x
         x4 = x2*x2
         x8 = x4*x4
         x16 = x8*x8
         associate (a => ellipk_split_a, b => ellipk_split_b)
            kreg(i) = ((a(0) + a(1)*x) + x2*(a(2) + a(3)*x) &
               & + x4*((a(4) + a(5)*x) + x2*(a(6) + a(7)*x))) &
               & + x8*((a(8) + a(9)*x) + x2*(a(10) + a(11)*x) &
               & + x4*((a(12) + a(13)*x) + x2*(a(14) + a(15)*x))) &
               & + x16*(a(16) + a(17)*x)
            klog(i) = ((b(0) + b(1)*x) + x2*(b(2) + b(3)*x) &
               & + x4*((b(4) + b(5)*x) + x2*(b(6) + b(7)*x))) &
               & + x8*((b(8) + b(9)*x) + x2*(b(10) + b(11)*x) &
               & + x4*((b(12) + b(13)*x) + x2*(b(14) + b(15)*x))) &
               & + x16*(b(16) + b(17)*x)
         end associate
      end do
   end subroutine split_near

   !> Queue the points (s(:), wt(:)) of the element's pressure basis (local coordinates,
   !> weights with the kernel); a batch that would overflow is summed first.
   pure subroutine add_points(mesh, s, wt, pts, acc)
      type(radial_mesh), intent(in) :: mesh
      real(dp), intent(in) :: s(:), wt(:)
      type(point_batch), intent(inout) :: pts
      real(dp), intent(inout) :: acc(:)
      integer :: m
      if (pts%m + size(s) > max_batch) call add_batch(mesh, pts, acc)
      m = pts%m
      pts%s(m + 1:m + size(s)) = s
      pts%wt(m + 1:m + size(s)) = wt
      pts%m = m + size(s)
   end subroutine add_points

   !> acc(q) += sum_p wt_p L_q(s_p), q = 1..n_gauss, over the queued points (then
   !> emptied), L_q(s) = bary_q prod_{k /= q} (s - s_k), by prefix and suffix products
   !> across the batch: no divisions, and no chain of dependent products from one point
   !> to the next (this is the innermost work of the assembly; the loops over points
   !> vectorize). Rules beyond max_basis points (never used by the solver) take the
   !> barycentric form with one division per point.
   pure subroutine add_batch(mesh, pts, acc)
      type(radial_mesh), intent(in) :: mesh
      type(point_batch), intent(inout) :: pts
      real(dp), intent(inout) :: acc(:)
      integer, parameter :: max_basis = 32
      real(dp) :: prefix(max_batch, max_basis), suffix(max_batch), prod
      integer :: q, n, m, i
      n = mesh%n_gauss
      m = pts%m
      pts%m = 0
      if (m == 0) return
      if (n == 6 .and. simd_level() == 1) then
         call simd_batch6(m, mesh%local_s, mesh%local_bary, pts%s, pts%wt, acc)
         return
      else if (n == 6) then
         call add_batch_six(mesh%local_s, mesh%local_bary, pts%s(1:m), pts%wt(1:m), acc)
         return
      end if
      if (n > max_basis) then
         do i = 1, m
            prod = pts%wt(i)
            do q = 1, n
               if (pts%s(i) == mesh%local_s(q)) exit
               prod = prod*(pts%s(i) - mesh%local_s(q))
            end do
            if (q <= n) then
               acc(q) = acc(q) + pts%wt(i)
               cycle
            end if
            do q = 1, n
               acc(q) = acc(q) + prod*mesh%local_bary(q)/(pts%s(i) - mesh%local_s(q))
            end do
         end do
         return
      end if
      prefix(1:m, 1) = pts%wt(1:m)
      do q = 2, n
         prefix(1:m, q) = prefix(1:m, q - 1)*(pts%s(1:m) - mesh%local_s(q - 1))
      end do
      suffix(1:m) = 1.0_dp
      do q = n, 1, -1
         acc(q) = acc(q) + mesh%local_bary(q)*sum(prefix(1:m, q)*suffix(1:m))
         suffix(1:m) = suffix(1:m)*(pts%s(1:m) - mesh%local_s(q))
      end do
   end subroutine add_batch

   !> add_batch for the sphere solver's six-point pressure basis (pressure_points): the
   !> same products point by point in registers, the six sums interleaved (the general
   !> form sums one basis function at a time over the batch, a chain of dependent adds
   !> each; without reassociation the compiler cannot vectorize such sums).
   pure subroutine add_batch_six(ls, bary, s, wt, acc)
      real(dp), intent(in) :: ls(6), bary(6), s(:), wt(:)
      real(dp), intent(inout) :: acc(:)
      real(dp) :: d1, d2, d3, d4, d5, d6, p2, p3, p4, p5, p6, q1, q2, q3, q4, q5
      real(dp) :: a1, a2, a3, a4, a5, a6
      integer :: i
      a1 = 0.0_dp; a2 = 0.0_dp; a3 = 0.0_dp; a4 = 0.0_dp; a5 = 0.0_dp; a6 = 0.0_dp
      do i = 1, size(s)
         d1 = s(i) - ls(1)
         d2 = s(i) - ls(2)
         d3 = s(i) - ls(3)
         d4 = s(i) - ls(4)
         d5 = s(i) - ls(5)
         d6 = s(i) - ls(6)
         ! prefix wt prod_{k<q} d_k, suffix prod_{k>q} d_k
         p2 = wt(i)*d1
         p3 = p2*d2
         p4 = p3*d3
         p5 = p4*d4
         p6 = p5*d5
         q5 = d6
         q4 = q5*d5
         q3 = q4*d4
         q2 = q3*d3
         q1 = q2*d2
         a1 = a1 + wt(i)*q1
         a2 = a2 + p2*q2
         a3 = a3 + p3*q3
         a4 = a4 + p4*q4
         a5 = a5 + p5*q5
         a6 = a6 + p6
      end do
      acc(1) = acc(1) + bary(1)*a1
      acc(2) = acc(2) + bary(2)*a2
      acc(3) = acc(3) + bary(3)*a3
      acc(4) = acc(4) + bary(4)*a4
      acc(5) = acc(5) + bary(5)*a5
      acc(6) = acc(6) + bary(6)*a6
   end subroutine add_batch_six

   elemental real(dp) function local_coord(x0, x1, t) result(s)
      real(dp), intent(in) :: x0, x1, t
      s = (2.0_dp*t - x0 - x1)/(x1 - x0)
   end function local_coord

   !> Influence matrix infl(i, :) = influence_row(mesh, r(i)), rows in parallel (OpenMP);
   !> n_threads = 0 leaves the team size to OpenMP. Each thread fills whole columns of a
   !> transposed buffer (contiguous, no cache line shared between threads), transposed
   !> after the parallel region.
   !> n_threads above the processor count is capped to it (more threads than processors
   !> only cost; libgomp aborts when it cannot create them). stat (optional): nonzero if
   !> the buffer could not be allocated (infl then unset), else the buffer's failure stops.
   subroutine assemble_influence(mesh, r, infl, n_threads, stat)
      type(radial_mesh), intent(in) :: mesh   !< a built mesh
      real(dp), intent(in) :: r(:)   !< the rows' radii, >= 0
      real(dp), intent(out) :: infl(:, :)   !< (size(r), n_elem*n_gauss)
      integer, intent(in) :: n_threads   !< OpenMP threads (0: OpenMP's choice)
      integer, intent(out), optional :: stat   !< nonzero: the buffer could not be allocated
      integer :: i, threads, ios
      real(dp), allocatable :: rows(:, :)
      if (present(stat)) then
         allocate (rows(mesh%n_elem*mesh%n_gauss, size(r)), stat=ios)
         stat = ios
         if (ios /= 0) return
      else
         allocate (rows(mesh%n_elem*mesh%n_gauss, size(r)))
      end if
      threads = n_threads
      !$ threads = min(n_threads, omp_get_num_procs())
      if (threads > 0) then
         !$omp parallel do schedule(dynamic, 4) num_threads(threads)
         do i = 1, size(r)
            call influence_row(mesh, r(i), rows(:, i))
         end do
         !$omp end parallel do
      else
         !$omp parallel do schedule(dynamic, 4)
         do i = 1, size(r)
            call influence_row(mesh, r(i), rows(:, i))
         end do
         !$omp end parallel do
      end if
      infl = transpose(rows)
   end subroutine assemble_influence

   !> assemble_influence at the mesh's own nodes (infl(i, :) the row of mesh%node(i)),
   !> with the coefficients of every (node, element) pair that a mesh in cache has too
   !> (the same node radius, the same two edges) taken from it; then the mesh is stored
   !> in the cache in place of the oldest (not a matrix of more than cache_max_entries).
   !> Levels of a solve share elements and nodes where edges are fixed (r = 0, kinks,
   !> layers, the inner part when only the outer radius grows); a kink relocation or a
   !> level after a capped loading (halved elements) keeps most of its mesh.
   subroutine assemble_influence_cached(mesh, infl, n_threads, cache, stat)
      type(radial_mesh), intent(in) :: mesh   !< a built mesh
      real(dp), intent(out) :: infl(:, :)   !< (nodes, n_elem*n_gauss)
      integer, intent(in) :: n_threads   !< OpenMP threads (0: OpenMP's choice)
      !> earlier meshes' coefficients; this mesh's stored
      type(influence_cache), intent(inout) :: cache
      integer, intent(out), optional :: stat   !< nonzero: a buffer could not be allocated
      integer :: i, j, k, e, c, ng, n, nr, threads, ios, slot, src
      integer, allocatable :: node_at(:, :), elem_at(:, :), row_slot(:)
      real(dp), allocatable :: swap(:)
      ! known(e, slot): element e's coefficients come from that slot's mesh (the same for
      ! every row taken from it: a column a slot, not a column a row)
      logical, allocatable :: known(:, :)
      logical :: shares(cache_meshes)
      n = size(mesh%node)
      ng = mesh%n_gauss
      nr = mesh%n_elem*ng
      if (cache%n_gauss /= ng) then
         call clear_cache(cache)
         cache%n_gauss = ng
      end if
      ! (the rows in the spare, node i's at (i - 1)*nr + 1: grown only, by a quarter more
      ! than needed (at most cache_max_entries more), so that a build's slowly growing
      ! meshes reallocate it rarely)
      ios = 0
      if (allocated(cache%spare)) then
         if (size(cache%spare, kind=8) < int(nr, 8)*n) deallocate (cache%spare)
      end if
      if (.not. allocated(cache%spare)) allocate (cache%spare(nr*n + min(nr*n/4, &
         & cache_max_entries)), stat=ios)
      if (ios == 0) allocate (node_at(n, cache_meshes), elem_at(mesh%n_elem, cache_meshes), &
         & row_slot(n), known(mesh%n_elem, cache_meshes), stat=ios)
      if (present(stat)) stat = ios
      if (ios /= 0) return
      node_at = 0
      elem_at = 0
      shares = .false.
      do j = 1, cache_meshes
         if (.not. cache%slot(j)%filled) cycle
         call match_elements(mesh%edge, cache%slot(j)%edge, elem_at(:, j))
         shares(j) = any(elem_at(:, j) > 0)
         if (shares(j)) call match_sorted(mesh%node, cache%slot(j)%node, node_at(:, j))
      end do
      known = elem_at > 0
      ! each row from the most recent mesh that has its node (and shares elements)
      row_slot = 0
      do i = 1, n
         do k = 0, cache_meshes - 1
            slot = modulo(cache%last - 1 - k, cache_meshes) + 1
            if (node_at(i, slot) > 0 .and. shares(slot)) then
               row_slot(i) = slot
               exit
            end if
         end do
         if (row_slot(i) == 0) cycle
         slot = row_slot(i)
         src = (node_at(i, slot) - 1)*cache%slot(slot)%n_row
         do e = 1, mesh%n_elem
            c = elem_at(e, slot)
            if (c == 0) cycle
            cache%spare((i - 1)*nr + (e - 1)*ng + 1:(i - 1)*nr + e*ng) = &
               & cache%slot(slot)%rows(src + (c - 1)*ng + 1:src + c*ng)
         end do
      end do
      threads = n_threads
      !$ threads = min(n_threads, omp_get_num_procs())
      if (threads > 0) then
         !$omp parallel do schedule(dynamic, 4) num_threads(threads)
         do i = 1, n
            call row_of(i)
         end do
         !$omp end parallel do
      else
         !$omp parallel do schedule(dynamic, 4)
         do i = 1, n
            call row_of(i)
         end do
         !$omp end parallel do
      end if
      call transpose_rows(nr, n, cache%spare, infl)
      if (size(infl, kind=8) > int(cache_max_entries, 8)) return
      ! stored in place of the oldest: the spare becomes its rows, its storage the spare
      slot = modulo(cache%last, cache_meshes) + 1
      cache%slot(slot)%has_values = .false.
      cache%slot(slot)%edge = mesh%edge
      cache%slot(slot)%node = mesh%node
      cache%slot(slot)%n_row = nr
      if (allocated(cache%slot(slot)%rows)) call move_alloc(cache%slot(slot)%rows, swap)
      call move_alloc(cache%spare, cache%slot(slot)%rows)
      if (allocated(swap)) call move_alloc(swap, cache%spare)
      cache%slot(slot)%filled = .true.
      cache%last = slot
   contains
      subroutine row_of(i)
         integer, intent(in) :: i
         if (row_slot(i) > 0) then
            call influence_row(mesh, mesh%node(i), cache%spare((i - 1)*nr + 1:i*nr), &
               & known(:, row_slot(i)))
         else
            call influence_row(mesh, mesh%node(i), cache%spare((i - 1)*nr + 1:i*nr))
         end if
      end subroutine row_of
   end subroutine assemble_influence_cached

   !> infl = the transpose of the first nr*n entries of rows read as an nr x n matrix.
   pure subroutine transpose_rows(nr, n, rows, infl)
      integer, intent(in) :: nr, n
      real(dp), intent(in) :: rows(nr, n)
      real(dp), intent(out) :: infl(:, :)   !< (n, nr)
      infl = transpose(rows)
   end subroutine transpose_rows

   !> Empty the cache as a new one (no mesh, no values) but keep its storage for the
   !> meshes to come.
   pure subroutine clear_cache(cache)
      type(influence_cache), intent(inout) :: cache   !< emptied, its storage kept
      integer :: j
      cache%last = 0
      cache%n_gauss = 0
      do j = 1, cache_meshes
         cache%slot(j)%filled = .false.
         cache%slot(j)%has_values = .false.
      end do
   end subroutine clear_cache

   !> Values a caller kept (keep_point_values, under the same key) at the Gauss points of
   !> the cached meshes' elements that mesh shares (the same two edges, so the same Gauss
   !> radii): values(i) and known(i) = .true. there, the most recent mesh first; known
   !> .false. elsewhere (values(i) then unset).
   pure subroutine cached_point_values(cache, mesh, key, values, known)
      type(influence_cache), intent(in) :: cache   !< a solve's cache
      type(radial_mesh), intent(in) :: mesh   !< a built mesh
      real(dp), intent(in) :: key   !< as keep_point_values'
      real(dp), intent(out) :: values(:)   !< (n_elem*n_gauss)
      logical, intent(out) :: known(:)   !< (n_elem*n_gauss)
      integer :: k, slot, e, c, ng, elem_at(mesh%n_elem)
      known = .false.
      values = 0.0_dp
      ng = mesh%n_gauss
      if (cache%n_gauss /= ng) return
      do k = 0, cache_meshes - 1
         slot = modulo(cache%last - 1 - k, cache_meshes) + 1
         if (.not. (cache%slot(slot)%filled .and. cache%slot(slot)%has_values)) cycle
         if (cache%slot(slot)%key /= key) cycle
         call match_elements(mesh%edge, cache%slot(slot)%edge, elem_at)
         do e = 1, mesh%n_elem
            c = elem_at(e)
            if (c == 0) cycle
            if (known((e - 1)*ng + 1)) cycle
            values((e - 1)*ng + 1:e*ng) = cache%slot(slot)%point_values((c - 1)*ng + 1:c*ng)
            known((e - 1)*ng + 1:e*ng) = .true.
         end do
      end do
   end subroutine cached_point_values

   !> Keep values at mesh's Gauss points under key with the cache's entry of mesh (the one
   !> assemble_influence_cached stored last; nothing if it did not store mesh).
   pure subroutine keep_point_values(cache, mesh, key, values)
      type(influence_cache), intent(inout) :: cache   !< a solve's cache
      type(radial_mesh), intent(in) :: mesh   !< the mesh assemble_influence_cached took last
      real(dp), intent(in) :: key   !< the caller's key
      real(dp), intent(in) :: values(:)   !< (n_elem*n_gauss)
      integer :: slot
      slot = cache%last
      if (slot == 0) return
      if (.not. cache%slot(slot)%filled) return
      if (size(cache%slot(slot)%edge) /= size(mesh%edge)) return
      if (any(cache%slot(slot)%edge /= mesh%edge)) return
      if (size(values) /= mesh%n_elem*mesh%n_gauss) return
      cache%slot(slot)%point_values = values
      cache%slot(slot)%has_values = .true.
      cache%slot(slot)%key = key
   end subroutine keep_point_values

   !> at(i) = k where b(k) == a(i) exactly, else 0 (a and b increasing).
   pure subroutine match_sorted(a, b, at)
      real(dp), intent(in) :: a(:), b(:)
      integer, intent(out) :: at(:)
      integer :: i, k
      at = 0
      k = 1
      do i = 1, size(a)
         do while (k <= size(b))
            if (b(k) >= a(i)) exit
            k = k + 1
         end do
         if (k > size(b)) exit
         if (b(k) == a(i)) at(i) = k
      end do
   end subroutine match_sorted

   !> at(e) = c where element c of the edges b(0:) ([b(c - 1), b(c)]) is element e of
   !> a(0:) (both edges exactly equal), else 0.
   pure subroutine match_elements(a, b, at)
      real(dp), intent(in) :: a(0:), b(0:)
      integer, intent(out) :: at(:)
      integer :: edge_at(0:size(a) - 1), e
      call match_sorted(a, b, edge_at)
      at = 0
      do e = 1, size(a) - 1
         if (edge_at(e - 1) > 0 .and. edge_at(e) > 0) then
            ! (positions in b counted from 1: b(edge_at(e) - 1) is a(e))
            if (edge_at(e) == edge_at(e - 1) + 1) at(e) = edge_at(e) - 1
         end if
      end do
   end subroutine match_elements

   !> Value at r of the continuous piecewise-Lagrange field with nodal values v; r beyond
   !> the mesh takes the last element's polynomial (callers keep r inside).
   pure real(dp) function interpolate_nodal(mesh, v, r) result(val)
      type(radial_mesh), intent(in) :: mesh   !< a built mesh
      real(dp), intent(in) :: v(:), r   !< nodal values, one per mesh node, and the radius r
      integer :: e, lo, hi
      real(dp) :: l(0:mesh%degree)
      ! Bisection for the element holding r.
      lo = 1
      hi = mesh%n_elem
      do while (lo < hi)
         e = (lo + hi)/2
         if (r > mesh%edge(e)) then
            lo = e + 1
         else
            hi = e
         end if
      end do
      e = lo
      l = lagrange_weights(mesh%node_s, local_coord(mesh%edge(e - 1), mesh%edge(e), r))
      val = dot_product(l, v(node_index(mesh, e, 0):node_index(mesh, e, mesh%degree)))
   end function interpolate_nodal

   !> interpolate_nodal at many radii, val(i) at r(i): the element of each found by a walk
   !> from the last one's (forward while r > its right edge), which for increasing r (a
   !> mesh's nodes or Gauss points, the solver's calls) visits each element once instead
   !> of a bisection a point; a smaller r starts the walk again from the first element.
   !> The element is the one bisection finds (the first e with r <= edge(e), else the
   !> last) and the value the same expression: the same numbers to the bit.
   pure subroutine interpolate_nodal_walk(mesh, v, r, val)
      type(radial_mesh), intent(in) :: mesh   !< a built mesh
      real(dp), intent(in) :: v(:)   !< nodal values, one per mesh node
      real(dp), intent(in) :: r(:)   !< the radii (increasing: one pass)
      real(dp), intent(out) :: val(:)   !< (size(r)) the values
      integer :: i, e
      real(dp) :: l(0:mesh%degree)
      e = 1
      do i = 1, size(r)
         if (i > 1) then
            if (r(i) < r(i - 1)) e = 1
         end if
         do while (e < mesh%n_elem)
            if (.not. r(i) > mesh%edge(e)) exit
            e = e + 1
         end do
         l = lagrange_weights(mesh%node_s, local_coord(mesh%edge(e - 1), mesh%edge(e), r(i)))
         val(i) = dot_product(l, v(node_index(mesh, e, 0):node_index(mesh, e, mesh%degree)))
      end do
   end subroutine interpolate_nodal_walk

end module egw_halfspace
