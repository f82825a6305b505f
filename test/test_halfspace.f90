!> Tests of egw_halfspace against exact half-space solutions (Johnson 1985, §3.2 and §4.2):
!> uniform pressure on a disc and the Hertz pressure.
module test_halfspace
   use testdrive, only: new_unittest, unittest_type, error_type, check, test_failed
   use egw_kinds, only: dp, pi
   use egw_ellip, only: ellipk, ellipe
   use egw_halfspace, only: radial_mesh, build_mesh, graded_edges, influence_row, &
      & assemble_influence, interpolate_nodal, mesh_nodes, influence_cache, &
      & assemble_influence_cached, cached_point_values, keep_point_values, clear_cache, &
      & interpolate_nodal_walk
   use egw_simd, only: simd_level, simd_set
   implicit none
   private
   public :: collect_halfspace

contains

   subroutine collect_halfspace(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("uniform pressure on a disc is exact", test_uniform_disc), &
         & new_unittest("the far kernel's AVX2 path: exact disc, baseline's rows", &
         & test_simd_paths), &
         & new_unittest("Hertz pressure converges at order 1.5", test_hertz_order), &
         & new_unittest("deflection at r = 0 is 2 int p dt", test_centre), &
         & new_unittest("parallel assembly equals the rows", test_assembly), &
         & new_unittest("cached assembly equals the plain one", test_cached_assembly), &
         & new_unittest("point values kept with the cache", test_cached_point_values), &
         & new_unittest("a cleared cache is a new one with its storage", test_cleared_cache), &
         & new_unittest("a mesh built with another's rules is the same", test_mesh_rules), &
         & new_unittest("nodal interpolation reproduces polynomials", test_interpolation), &
         & new_unittest("the walk interpolates as the bisection", test_interpolation_walk) &
         & ]
   end subroutine collect_halfspace

   !> egw_simd's two paths of the far-field kernel and of the near pieces' log-product
   !> weights (AVX2 + FMA, four lanes, glibc's 4-lane log; the baseline, two lanes; the
   !> rows hold both: the log-piece weights scaled by 1 + 1e-13 put the rows 1.1e-13
   !> apart, asm21): the uniform disc exact on each (test_uniform_disc's
   !> 1e-13, so a wrong coefficient, lane or tail of the AVX2 routine fails), and their
   !> rows within rounding of each other: a coefficient is ~20 roundings (the log's few
   !> ulp among them) from its value on either path, 1e-14 of the row's largest allows
   !> a hundred ulp. Runs of far points of every length mod 4 (the 4-lane routine's
   !> tail) arise on these meshes (6 and 8 Gauss points an element, runs of 1..n
   !> elements). Skipped (passes) on a CPU without AVX2 and FMA.
   subroutine test_simd_paths(error)
      type(error_type), allocatable, intent(out) :: error
      type(radial_mesh) :: mesh
      real(dp), allocatable :: row(:), base(:)
      real(dp) :: r, w, exact, worst, apart
      integer :: i, imesh, level0, got

      level0 = simd_level()
      if (simd_set(1) /= 1) then
         got = simd_set(level0)
         return
      end if
      do imesh = 1, 3
         select case (imesh)
         case (1)
            call build_mesh([(real(i, dp)/7.0_dp, i=0, 7)], 2, 8, mesh)
         case (2)
            call build_mesh(graded_edges(0.999_dp, 0.01_dp, 1.0_dp, 0.4_dp), 3, 6, mesh)
         case default
            call build_mesh([(real(i, dp)/13.0_dp, i=0, 13)], 2, 6, mesh)
         end select
         allocate (row(mesh%n_elem*mesh%n_gauss), base(mesh%n_elem*mesh%n_gauss))
         worst = 0.0_dp
         apart = 0.0_dp
         do i = 0, 161
            r = 2.0_dp*real(i, dp)/161.0_dp
            if (i == 161) r = mesh%node(2)
            got = simd_set(0)
            call influence_row(mesh, r, base)
            got = simd_set(1)
            call influence_row(mesh, r, row)
            w = sum(row)
            if (r <= 1.0_dp) then
               exact = 4.0_dp/pi*ellipe(r)
            else
               exact = 4.0_dp*r/pi*(ellipe(1.0_dp/r) - (1.0_dp - 1.0_dp/r**2)*ellipk(1.0_dp/r))
            end if
            worst = max(worst, abs(w - exact))
            apart = max(apart, maxval(abs(row - base))/maxval(abs(base)))
         end do
         deallocate (row, base)
         got = simd_set(level0)
         call check(error, worst < 1.0e-13_dp, "AVX2 path, uniform disc: max |w - exact| = " &
            & //real_str(worst))
         if (allocated(error)) return
         call check(error, apart <= 1.0e-14_dp, "AVX2 and baseline rows apart by " &
            & //real_str(apart)//" of the row's largest")
         if (allocated(error)) return
         got = simd_set(1)
      end do
      got = simd_set(level0)
   end subroutine test_simd_paths

   !> Uniform pressure p = 1 on the unit disc (E = 1): w = (4/pi) E(r) inside and
   !> w = (4 r/pi) [E(1/r) - (1 - 1/r**2) K(1/r)] outside. The pressure is a polynomial on
   !> every element, so only quadrature error remains: 1e-13 (a hundred ulp of w ~ 1)
   !> proves the log singularity is integrated exactly, on node and off node.
   subroutine test_uniform_disc(error)
      type(error_type), allocatable, intent(out) :: error
      type(radial_mesh) :: mesh
      real(dp), allocatable :: row(:)
      real(dp) :: r, w, exact, worst
      integer :: i, imesh

      do imesh = 1, 2
         if (imesh == 1) then
            call build_mesh([(real(i, dp)/7.0_dp, i=0, 7)], 2, 8, mesh)
         else
            call build_mesh(graded_edges(0.999_dp, 0.01_dp, 1.0_dp, 0.4_dp), 3, 6, mesh)
         end if
         allocate (row(mesh%n_elem*mesh%n_gauss))
         worst = 0.0_dp
         do i = 0, 161
            r = 2.0_dp*real(i, dp)/161.0_dp
            if (i == 161) r = mesh%node(2)     ! a node close to r = 0
            call influence_row(mesh, r, row)
            w = sum(row)
            if (r <= 1.0_dp) then
               exact = 4.0_dp/pi*ellipe(r)
            else
               exact = 4.0_dp*r/pi*(ellipe(1.0_dp/r) - (1.0_dp - 1.0_dp/r**2)*ellipk(1.0_dp/r))
            end if
            worst = max(worst, abs(w - exact))
         end do
         deallocate (row)
         call check(error, worst < 1.0e-13_dp, "uniform disc: max |w - exact| = " &
            & //real_str(worst))
         if (allocated(error)) return
      end do
   end subroutine test_uniform_disc

   !> Hertz pressure p = sqrt(1 - r**2) (a = 1, E = 1, so R = 2/pi): w = (pi/4)(2 - r**2)
   !> inside and (1/2)[sqrt(r**2-1) + (2 - r**2) asin(1/r)] outside. On uniform meshes the
   !> square-root edge limits the pressure interpolation on the last element to h**1.5, so
   !> the max error must fall at order 1.5; the asymptotic regime is reached slowly from
   !> below (log corrections), hence the band [1.35, 1.65] on the h = 1/16 -> 1/64 steps.
   subroutine test_hertz_order(error)
      type(error_type), allocatable, intent(out) :: error
      type(radial_mesh) :: mesh
      real(dp), allocatable :: row(:), p(:)
      real(dp) :: r, w, exact, err(3), order
      integer :: i, k, n

      do k = 1, 3
         n = 8*2**k
         call build_mesh([(real(i, dp)/real(n, dp), i=0, n)], 2, 8, mesh)
         allocate (row(mesh%n_elem*mesh%n_gauss))
         p = sqrt(max(0.0_dp, 1.0_dp - mesh%gauss_r**2))
         err(k) = 0.0_dp
         do i = 0, 60
            r = 1.5_dp*real(i, dp)/60.0_dp
            call influence_row(mesh, r, row)
            w = sum(row*p)
            if (r <= 1.0_dp) then
               exact = 0.25_dp*pi*(2.0_dp - r*r)
            else
               exact = 0.5_dp*(sqrt(r*r - 1.0_dp) + (2.0_dp - r*r)*asin(1.0_dp/r))
            end if
            err(k) = max(err(k), abs(w - exact))
         end do
         deallocate (row)
      end do
      do k = 2, 3
         order = log(err(k - 1)/err(k))/log(2.0_dp)
         call check(error, order > 1.35_dp .and. order < 1.65_dp, &
            & "Hertz on uniform meshes: observed order "//real_str(order)//" not ~1.5")
         if (allocated(error)) return
      end do
   end subroutine test_hertz_order

   !> At r = 0 the kernel is 4/pi * pi/2 = 2: w(0) = 2 int p dt, exact for the pressure
   !> polynomials, so the row must equal twice the Gauss weights to rounding.
   subroutine test_centre(error)
      type(error_type), allocatable, intent(out) :: error
      type(radial_mesh) :: mesh
      real(dp), allocatable :: row(:)
      call build_mesh(graded_edges(0.0_dp, 0.3_dp, 3.0_dp, 0.5_dp), 2, 8, mesh)
      allocate (row(mesh%n_elem*mesh%n_gauss))
      call influence_row(mesh, 0.0_dp, row)
      call check(error, maxval(abs(row - 2.0_dp*mesh%gauss_w)) < 1.0e-15_dp, &
         & "w(0) row differs from 2 * weights")
   end subroutine test_centre

   !> The OpenMP assembly must give the serial rows bit for bit (rows are independent).
   subroutine test_assembly(error)
      type(error_type), allocatable, intent(out) :: error
      type(radial_mesh) :: mesh
      real(dp), allocatable :: infl(:, :), row(:)
      integer :: i
      call build_mesh(graded_edges(3.0_dp, 0.2_dp, 5.0_dp, 0.5_dp), 2, 8, mesh)
      allocate (infl(mesh_nodes(mesh), mesh%n_elem*mesh%n_gauss))
      allocate (row(size(infl, 2)))
      call assemble_influence(mesh, mesh%node, infl, 2)
      do i = 1, mesh_nodes(mesh)
         call influence_row(mesh, mesh%node(i), row)
         if (any(row /= infl(i, :))) then
            call test_failed(error, "assembled row differs from influence_row")
            return
         end if
      end do
   end subroutine test_assembly

   !> assemble_influence_cached against assemble_influence, bit for bit, on the solver's
   !> element kinds (degree 4, 6 points) over a sequence of meshes as one solve's levels
   !> make them: a graded mesh; it with three elements halved (a bisection check); its
   !> inner part with a grown outer radius; another step (shares r = 0 and little else).
   !> A coefficient depends only on the node and the element's edges, so the reused ones
   !> are the same numbers. That reuse happens at all is checked with a poisoned cache
   !> (its stored matrix set to -1: the entries taken from it show).
   subroutine test_cached_assembly(error)
      type(error_type), allocatable, intent(out) :: error
      type(radial_mesh) :: mesh
      type(influence_cache) :: cache, poisoned
      real(dp), allocatable :: infl(:, :), plain(:, :), edges(:), base(:)
      integer :: k, n_reused
      base = graded_edges(3.0_dp, 0.2_dp, 5.0_dp, 0.25_dp)
      do k = 1, 4
         select case (k)
         case (1)
            edges = base
         case (2)
            edges = [base(1:4), 0.5_dp*(base(4) + base(5)), base(5:9), &
               & 0.5_dp*(base(9) + base(10)), base(10:size(base) - 1), &
               & 0.5_dp*(base(size(base) - 1) + base(size(base))), base(size(base))]
         case (3)
            edges = [base(1:size(base) - 3), graded_edges(3.0_dp, 0.2_dp, 7.0_dp, &
               & 0.25_dp)]
            edges = [base(1:size(base) - 3), pack(edges(size(base) - 2:), &
               & edges(size(base) - 2:) > base(size(base) - 3))]
         case (4)
            edges = graded_edges(3.0_dp, 0.2_dp, 5.0_dp, 0.2_dp)
         end select
         call build_mesh(edges, 4, 6, mesh)
         allocate (infl(mesh_nodes(mesh), mesh%n_elem*mesh%n_gauss))
         allocate (plain(mesh_nodes(mesh), mesh%n_elem*mesh%n_gauss))
         call assemble_influence(mesh, mesh%node, plain, 1)
         if (k == 2) then
            poisoned = cache
            poisoned%slot(poisoned%last)%rows = -1.0_dp
            call assemble_influence_cached(mesh, infl, 1, poisoned)
            n_reused = count(infl == -1.0_dp)
            ! (the three halved elements' columns and the new nodes' rows are computed)
            call check(error, n_reused > size(infl)/2, "mesh 2: only "// &
               & "some coefficients reused from the cache")
            if (allocated(error)) return
            call check(error, all(infl == plain .or. infl == -1.0_dp), &
               & "mesh 2: a computed coefficient differs from the plain assembly's")
            if (allocated(error)) return
         end if
         call assemble_influence_cached(mesh, infl, 1, cache)
         call check(error, all(infl == plain), "mesh "//char(48 + k)// &
            & ": the cached assembly differs from the plain one")
         if (allocated(error)) return
         deallocate (infl, plain)
      end do
   end subroutine test_cached_assembly

   !> keep_point_values / cached_point_values (the solver's law at gap_min across a solve's
   !> levels): values f(r) = 1 + r**2 kept at a graded mesh's Gauss points come back, bit
   !> for bit f at the same radii, at exactly the Gauss points of the elements a second
   !> mesh shares (it halves three of them: 6 of its elements are new); none under another
   !> key, and none kept for a mesh that was not the one stored last.
   subroutine test_cached_point_values(error)
      type(error_type), allocatable, intent(out) :: error
      type(radial_mesh) :: mesh1, mesh2
      type(influence_cache) :: cache
      real(dp), allocatable :: infl(:, :), base(:), edges(:), values(:)
      logical, allocatable :: known(:)
      base = graded_edges(3.0_dp, 0.2_dp, 5.0_dp, 0.25_dp)
      edges = [base(1:4), 0.5_dp*(base(4) + base(5)), base(5:9), &
         & 0.5_dp*(base(9) + base(10)), base(10:size(base) - 1), &
         & 0.5_dp*(base(size(base) - 1) + base(size(base))), base(size(base))]
      call build_mesh(base, 4, 6, mesh1)
      call build_mesh(edges, 4, 6, mesh2)
      allocate (infl(mesh_nodes(mesh1), mesh1%n_elem*mesh1%n_gauss))
      call assemble_influence_cached(mesh1, infl, 1, cache)
      ! not the mesh stored last: ignored
      call keep_point_values(cache, mesh2, 2.0_dp, 1.0_dp + mesh2%gauss_r**2)
      allocate (values(size(mesh2%gauss_r)), known(size(mesh2%gauss_r)))
      call cached_point_values(cache, mesh2, 2.0_dp, values, known)
      call check(error, .not. any(known), "values kept for a mesh the cache did not store")
      if (allocated(error)) return
      call keep_point_values(cache, mesh1, 2.0_dp, 1.0_dp + mesh1%gauss_r**2)
      call cached_point_values(cache, mesh2, 3.0_dp, values, known)
      call check(error, .not. any(known), "values served under another key")
      if (allocated(error)) return
      call cached_point_values(cache, mesh2, 2.0_dp, values, known)
      call check(error, count(known), (mesh2%n_elem - 6)*mesh2%n_gauss, &
         & "Gauss points served: not those of the shared elements")
      if (allocated(error)) return
      call check(error, all(pack(values, known) == pack(1.0_dp + mesh2%gauss_r**2, known)), &
         & "a served value is not the one kept at the same radius")
   end subroutine test_cached_point_values

   !> clear_cache (a solver_workspace's cache, reused by the routes of many solves): after
   !> it nothing of before is served, neither coefficients (the storage of before poisoned
   !> with -1: none shows up, and every matrix equals the plain assembly bit for bit) nor
   !> point values; the storage is kept (meshes smaller than the first one reuse it: the
   !> buffers are not reallocated, so their lengths stay those of the first mesh's), and a
   !> mesh that shares elements with one assembled after the clear still takes them from
   !> it (-1 from a poisoned copy shows).
   subroutine test_cleared_cache(error)
      type(error_type), allocatable, intent(out) :: error
      type(radial_mesh) :: big, mesh, halved
      type(influence_cache) :: cache, poisoned
      real(dp), allocatable :: infl(:, :), plain(:, :), base(:), edges(:), values(:)
      logical, allocatable :: known(:)
      integer :: j, k, storage, n_reused
      call build_mesh(graded_edges(3.0_dp, 0.2_dp, 9.0_dp, 0.15_dp), 4, 6, big)
      allocate (infl(mesh_nodes(big), big%n_elem*big%n_gauss))
      ! (four times: every slot and the spare then hold storage for the big mesh)
      do k = 1, 4
         call assemble_influence_cached(big, infl, 1, cache)
      end do
      call keep_point_values(cache, big, 2.0_dp, 1.0_dp + big%gauss_r**2)
      deallocate (infl)
      call clear_cache(cache)
      storage = 0
      do j = 1, size(cache%slot)
         cache%slot(j)%rows = -1.0_dp
         storage = storage + size(cache%slot(j)%rows)
      end do
      cache%spare = -1.0_dp
      storage = storage + size(cache%spare)
      allocate (values(size(big%gauss_r)), known(size(big%gauss_r)))
      call cached_point_values(cache, big, 2.0_dp, values, known)
      call check(error, .not. any(known), "point values served after clear_cache")
      if (allocated(error)) return
      base = graded_edges(3.0_dp, 0.2_dp, 5.0_dp, 0.25_dp)
      do k = 1, 3
         select case (k)
         case (1)
            edges = base
         case (2)
            edges = graded_edges(2.0_dp, 0.3_dp, 5.0_dp, 0.3_dp)
         case (3)
            edges = graded_edges(3.0_dp, 0.2_dp, 9.0_dp, 0.15_dp)
         end select
         call build_mesh(edges, 4, 6, mesh)
         allocate (infl(mesh_nodes(mesh), mesh%n_elem*mesh%n_gauss))
         allocate (plain(mesh_nodes(mesh), mesh%n_elem*mesh%n_gauss))
         call assemble_influence(mesh, mesh%node, plain, 1)
         call assemble_influence_cached(mesh, infl, 1, cache)
         call check(error, all(infl == plain), "mesh "//char(48 + k)// &
            & " after clear_cache: the cached assembly differs from the plain one")
         if (allocated(error)) return
         deallocate (infl, plain)
      end do
      ! (the largest of these meshes is the big one: no buffer grew)
      call check(error, size(cache%spare) + sum([(size(cache%slot(j)%rows), j = 1, &
         & size(cache%slot))]), storage, "clear_cache: the storage was reallocated for " &
         & //"meshes no larger than the one before")
      if (allocated(error)) return
      ! the cache still serves what was assembled after the clear: the last mesh with
      ! three elements halved
      edges = [mesh%edge(0:3), 0.5_dp*(mesh%edge(3) + mesh%edge(4)), mesh%edge(4:)]
      call build_mesh(edges, 4, 6, halved)
      poisoned = cache
      poisoned%slot(poisoned%last)%rows = -1.0_dp
      allocate (infl(mesh_nodes(halved), halved%n_elem*halved%n_gauss))
      call assemble_influence_cached(halved, infl, 1, poisoned)
      n_reused = count(infl == -1.0_dp)
      call check(error, n_reused > size(infl)/2, "after clear_cache: the meshes assembled " &
         & //"since are not reused")
   end subroutine test_cleared_cache

   !> build_mesh with rules (the solver's meshes take those of the first mesh its cache
   !> kept): the same mesh, bit for bit, as built alone, where the rules' degree and
   !> n_gauss are the mesh's; rules of another degree or n_gauss are not taken.
   subroutine test_mesh_rules(error)
      type(error_type), allocatable, intent(out) :: error
      type(radial_mesh) :: rules, other, alone, with
      real(dp), allocatable :: edges(:)
      integer :: k
      call build_mesh(graded_edges(1.0_dp, 0.3_dp, 4.0_dp, 0.5_dp), 2, 6, rules)
      call build_mesh(graded_edges(1.0_dp, 0.3_dp, 4.0_dp, 0.5_dp), 3, 5, other)
      edges = graded_edges(3.0_dp, 0.2_dp, 5.0_dp, 0.25_dp)
      do k = 1, 3
         select case (k)
         case (1)
            call build_mesh(edges, 2, 6, alone)
            call build_mesh(edges, 2, 6, with, rules)
         case (2)
            call build_mesh(edges, 2, 6, with, other)
         case (3)
            call build_mesh(edges, 3, 5, alone)
            call build_mesh(edges, 3, 5, with, rules)
         end select
         call check(error, same_mesh(alone, with), "case "//char(48 + k)// &
            & ": the mesh built with rules differs from the one built alone")
         if (allocated(error)) return
      end do
   contains
      logical function same_mesh(a, b)
         type(radial_mesh), intent(in) :: a, b
         same_mesh = a%n_elem == b%n_elem .and. a%degree == b%degree .and. &
            & a%n_gauss == b%n_gauss .and. lbound(b%node_s, 1) == 0 .and. &
            & lbound(b%interp, 1) == 0 .and. all(shape(a%interp) == shape(b%interp))
         if (.not. same_mesh) return
         same_mesh = all(a%edge == b%edge) .and. all(a%node == b%node) .and. &
            & all(a%gauss_r == b%gauss_r) .and. all(a%gauss_w == b%gauss_w) .and. &
            & all(a%local_s == b%local_s) .and. all(a%local_w == b%local_w) .and. &
            & all(a%local_bary == b%local_bary) .and. all(a%node_s == b%node_s) .and. &
            & all(a%interp == b%interp) .and. all(a%fine_s == b%fine_s) .and. &
            & all(a%fine_w == b%fine_w) .and. all(a%log_x == b%log_x) .and. &
            & all(a%log_w == b%log_w) .and. all(a%log_lw == b%log_lw)
      end function same_mesh
   end subroutine test_mesh_rules

   !> Continuous Lagrange elements of degree 3 reproduce a cubic to rounding (1e-13 for
   !> values ~ 30), at nodes and between them.
   subroutine test_interpolation(error)
      type(error_type), allocatable, intent(out) :: error
      type(radial_mesh) :: mesh
      real(dp), allocatable :: v(:)
      real(dp) :: r, worst
      integer :: i
      call build_mesh(graded_edges(1.0_dp, 0.1_dp, 3.0_dp, 0.7_dp), 3, 4, mesh)
      v = cubic(mesh%node)
      worst = 0.0_dp
      do i = 0, 100
         r = 3.0_dp*real(i, dp)/100.0_dp
         worst = max(worst, abs(interpolate_nodal(mesh, v, r) - cubic(r)))
      end do
      call check(error, worst < 1.0e-13_dp, "cubic not reproduced: "//real_str(worst))
   end subroutine test_interpolation

   !> interpolate_nodal_walk against interpolate_nodal point by point (its bisection is
   !> the reference): the same element and expression, so equal to the bit (another
   !> element's quadratic through sin(3 r) is off by far more than rounding inside an
   !> element; a walk that does not start again after a decreasing radius failed here).
   !> The radii: increasing, with element edges and nodes exactly (the walk's stop
   !> test; there either element gives the node's value), points beyond the outer edge
   !> (the last element's polynomial), then a decreasing run (the walk starts again).
   subroutine test_interpolation_walk(error)
      type(error_type), allocatable, intent(out) :: error
      type(radial_mesh) :: mesh
      real(dp), allocatable :: v(:), r(:), val(:)
      integer :: i, bad
      call build_mesh(graded_edges(1.0_dp, 0.1_dp, 3.0_dp, 0.7_dp), 2, 6, mesh)
      v = sin(3.0_dp*mesh%node)
      r = [(3.3_dp*real(i, dp)/97.0_dp, i=0, 97)]
      r = [r(1:40), mesh%edge(1:3), mesh%node(7:9), r(41:)]
      ! (ordered again: the edges and nodes above fall between r(40) and r(41))
      call sort_increasing(r)
      r = [r, 2.9_dp, 1.0_dp, mesh%edge(2), 0.0_dp, 0.5_dp]
      allocate (val(size(r)))
      call interpolate_nodal_walk(mesh, v, r, val)
      bad = 0
      do i = 1, size(r)
         if (val(i) /= interpolate_nodal(mesh, v, r(i))) bad = bad + 1
      end do
      call check(error, bad == 0, int_str(bad)//" of "//int_str(size(r)) &
         & //" values differ from interpolate_nodal's")
   end subroutine test_interpolation_walk

   pure subroutine sort_increasing(x)
      real(dp), intent(inout) :: x(:)
      integer :: i, j
      real(dp) :: t
      do i = 2, size(x)
         t = x(i)
         j = i - 1
         do while (j >= 1)
            if (x(j) <= t) exit
            x(j + 1) = x(j)
            j = j - 1
         end do
         x(j + 1) = t
      end do
   end subroutine sort_increasing

   function int_str(k) result(s)
      integer, intent(in) :: k
      character(len=:), allocatable :: s
      character(len=16) :: buf
      write (buf, '(i0)') k
      s = trim(buf)
   end function int_str

   elemental real(dp) function cubic(r)
      real(dp), intent(in) :: r
      cubic = 1.0_dp - 2.0_dp*r + 0.5_dp*r**2 + r**3
   end function cubic

   function real_str(x) result(s)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: s
      character(len=32) :: buf
      write (buf, '(es12.4)') x
      s = trim(adjustl(buf))
   end function real_str

end module test_halfspace
