!> The scaled half-space problem of a rough sphere and its discrete solve (doc/theory.md
!> §5), behind egw_rough_sphere's solves: meshes, continuation, Newton and Picard, the
!> error estimate and the implicit stiffness.
!>
!> Everything is solved in scaled variables (doc/theory.md §5 "useful facts"): radii in units of
!> sqrt(R sigma), gaps and deflections in sigma, pressures in E sqrt(sigma/R), forces in
!> E sqrt(R) sigma**1.5. Then R = E = sigma = 1, the Hertz radius is sqrt(delta/sigma) and
!> the rough-flat law is p_G = mu/(2 sqrt 2) f(h) with f the dimensionless law of
!> egw_asperity (f = F_{3/2} for elastic summits). Scale invariance is thus exact.
!>
!> Unknown: the rough deflection w_G at the nodes of continuous Lagrange elements. The
!> gap at the Gauss points is d = z + w_G (z the base gap: Hertz gap of eq. 28 for the
!> extended models at delta > 0, else r**2/2 - delta), the pressure there is p_G(d) exactly
!> (never interpolated), and w_G = H p_G is imposed at the nodes (collocation) with the
!> influence matrix of egw_halfspace. Newton with a backtracking line search (Jacobian by
!> LAPACK dgetf2/dgetrs, factors reused while they contract), or damped Picard. The force
!> is the Gauss sum of p_G(d).
!>
!> Mesh: graded in asinh((r - focus)/width) (egw_halfspace graded_edges) about the Hertz
!> edge (boundary layer width ~ a (sigma/delta)**(2/3)) with two geometric layers at it for
!> the extended models, about the computed gap's zero for classic GW deep in contact, and
!> about r = 0 otherwise; the outer radius grows until the force left outside is below
!> 1 % of the tolerance. Levels of decreasing step, each warm-started from the previous,
!> until the Richardson estimate from the last two (plus the tail) is below rel_tol/2.
!>
!> Unloading (doc/theory.md §8): with a closest-approach field (scaled_problem%closest) the
!> law is p_G = scale Z_u(d/sigma, d_max/sigma) at fixed d_max (egw_unloading), on the same
!> meshes with the same Newton, error estimate and stiffness (h_min does not depend on
!> delta or w, so the Jacobian and the implicit derivative keep their form); the meshes
!> also get element edges where p(r) is less smooth (first_unloading_level), Newton takes
!> no chord steps, and Z_u's law-only work is done once (unloading_law_of).
module egw_sphere_solver
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp, pi, sqrt2
   use egw_status, only: egw_error, egw_invalid_argument, egw_not_converged, &
      & egw_out_of_memory, fatal_error, format_real, int_str
   use egw_params, only: contact_params, model_gw, model_egw, model_epgw
   use egw_smooth_sphere, only: hertz_gap, hertz_pressure, hertz_force, hertz_stiffness
   use egw_flat_law, only: flat_law, gw_flat_law
   use egw_unloading, only: unloading_law, unloading_law_of, unloading_pressure, unloading_kinks
   use egw_halfspace, only: radial_mesh, build_mesh, graded_edges, mesh_nodes, node_index, &
      & assemble_influence, influence_row, interpolate_nodal
   use egw_lapack, only: dgetf2, dgetrs
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

   !> Degree of the deflection elements and pressure points per element: quartic elements
   !> with 6 Gauss points were the cheapest per digit of the pairs tried (degree 2-4,
   !> 4-8 points); the force error then falls like step**5 to step**6.
   integer, parameter :: deflection_degree = 4, pressure_points = 6
   !> Step ratio of the first two levels, and the order assumed when extrapolating the
   !> difference of two levels to an error estimate: 3, the lowest seen on coarse meshes
   !> (5-6 asymptotically), so that the estimate errs on the safe side; 2 for unloading,
   !> whose (t - t*)**1.5 edges of Z_u inside elements slow it (with 3 the errors of
   !> egw-bench --unloading-sweep at rel_tol 1e-6 were up to 2-3 times their estimates,
   !> with 2 at most 1.8; the levels it accepts, and the bench times, did not change).
   real(dp), parameter :: coarsen = 1.5_dp, force_order = 3.0_dp, unload_order = 2.0_dp
   !> Geometric layers at the Hertz edge (number, size ratio).
   integer, parameter :: focus_layers = 2
   real(dp), parameter :: focus_ratio = 0.25_dp
   !> Step (in asinh units) of the first level, and the finest allowed.
   real(dp), parameter :: finest_step = 0.01_dp, coarsest_step = 0.6_dp
   integer, parameter :: min_elements = 8
   !> A kink of Z_u in Delta closer than this fraction of its element to a branch edge
   !> gets no edge of its own (with_kink_edges).
   real(dp), parameter :: near_kink = 0.3_dp
   integer, parameter :: newton_max_default = 100, picard_max_default = 3000
   !> Largest mesh (nodes) of a solve: its dense influence matrix (nodes x 1.5 nodes) and
   !> Jacobian take ~0.5 GB and an LU ~10 s; the automatic meshes of the solver's range
   !> (delta/sigma up to 1e15, rel_tol down to 1e-10) stay well below. Bounds every solve's
   !> time and memory (n_radial larger: egw_invalid_argument).
   integer, parameter, public :: max_mesh_nodes = 4097
   !> Scaled force below which a solve returns 0 (as negligible() does before solving).
   real(dp), parameter :: tiny_force = 1.0e-250_dp

   public :: tiny_force

   !> Separation field of the loading solve at delta_max (scaled): d_max(r) = z_max(r) +
   !> w_max(r) with z_max the base gap at delta_max and w_max the nodal rough deflection
   !> interpolated on its mesh (beyond the mesh it falls like 1/r, the far field of a load).
   type :: separation_field
      logical :: extended = .false.   !< z_max is the Hertz gap (else the rigid gap)
      real(dp) :: delta = 0.0_dp      !< delta_max/sigma
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
      real(dp) :: force = 0.0_dp, dforce = 0.0_dp, moment0 = 0.0_dp, moment1 = 0.0_dp
      real(dp) :: residual = 0.0_dp, tail = 0.0_dp
      integer :: iterations = 0
      !> LU factors (dgetf2) of the last Jacobian Newton factored, near the solution; not
      !> allocated after Picard.
      real(dp), allocatable :: lu(:, :)
      integer, allocatable :: pivots(:)
   end type discrete_solution

   !> The meshes of a solve's levels: one family (grading focus and width, outer radius,
   !> geometric layers at the focus) and the steps (asinh units) of the level being solved
   !> and of the one before. Passed from step to step of solve_scaled.
   type :: mesh_family
      real(dp) :: focus = 0.0_dp, width = 0.0_dp, outer = 0.0_dp
      real(dp) :: step = 0.0_dp, step_prev = 0.0_dp
      logical :: layered = .false.
   end type mesh_family

   public :: separation_field, scaled_problem, discrete_solution
   public :: scaled, normal, negligible, base_gap, closest_gap, solve_scaled, differentiate, &
      & effective_radius, total_pressure, smooth_force, smooth_stiffness

contains

   !> Gap at the closest approach, d_max(r)/sigma, at scaled radii r >= 0.
   pure function closest_gap(field, r) result(gap)
      type(separation_field), intent(in) :: field
      real(dp), intent(in) :: r(:)
      real(dp) :: gap(size(r))
      real(dp) :: r_out, w_out
      integer :: i
      r_out = field%mesh%edge(field%mesh%n_elem)
      w_out = field%w(size(field%w))
      do i = 1, size(r)
         if (r(i) <= r_out) then
            gap(i) = interpolate_nodal(field%mesh, field%w, r(i))
         else
            ! Beyond the loading mesh the pressure was negligible: the deflection is that
            ! of a point load there, continued from the outer radius.
            gap(i) = w_out*r_out/r(i)
         end if
         if (field%extended) then
            gap(i) = gap(i) + hertz_gap(r(i), field%delta, 1.0_dp)
         else
            gap(i) = gap(i) + 0.5_dp*r(i)*r(i) - field%delta
         end if
      end do
   end function closest_gap

   !> The scaled problem of params at overlap delta (sigma > 0).
   pure function scaled(params, delta) result(prob)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: delta
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
      allocate (prob%law, source=gw_flat_law(scale=prob%scale, psi=prob%psi, &
         & hardness_coeff=prob%hardness, plastic_ratio=prob%plastic_ratio))
   end function scaled

   !> Scaled pressure of the loading law at one scaled separation h, and its derivative.
   pure subroutine law_at(prob, h, p, dpdh)
      type(scaled_problem), intent(in) :: prob
      real(dp), intent(in) :: h
      real(dp), intent(out) :: p, dpdh
      real(dp) :: pa(1), da(1)
      call prob%law%pressure([h], pa, da)
      p = pa(1)
      dpdh = da(1)
   end subroutine law_at

   elemental logical function normal(x)
      real(dp), intent(in) :: x
      normal = abs(x) >= tiny(1.0_dp) .and. abs(x) <= huge(1.0_dp)
   end function normal

   !> True when the spheres are so far apart that the summit pressure underflows.
   elemental logical function negligible(prob)
      type(scaled_problem), intent(in) :: prob
      real(dp) :: f, dfdh
      negligible = .false.
      if (prob%delta >= 0.0_dp) return
      call law_at(prob, -prob%delta, f, dfdh)
      negligible = f < tiny_force
   end function negligible

   !> Base gap z(r): the Hertz gap of eq. (28) (zero inside a) for the extended models at
   !> delta > 0, else the rigid gap r**2/2 - delta (classic GW, eq. 10).
   elemental real(dp) function base_gap(prob, r) result(z)
      type(scaled_problem), intent(in) :: prob
      real(dp), intent(in) :: r
      if (prob%extended) then
         z = hertz_gap(r, prob%delta, 1.0_dp)
      else
         z = 0.5_dp*r*r - prob%delta
      end if
   end function base_gap

   !> d z / d delta at fixed r: Hertz gives d w_H/d delta = 1 inside a and
   !> (2/pi) asin(a/r) outside (the flat-punch field), so dz/d delta = 0 inside.
   elemental real(dp) function base_gap_rate(prob, r) result(dz)
      type(scaled_problem), intent(in) :: prob
      real(dp), intent(in) :: r
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

   !> Solve on meshes of decreasing step until the estimated force error is below rel_tol/2
   !> (or on the mesh fixed by n_radial), doc/theory.md §7 "Error control": the first
   !> level's mesh (first_mesh), the first level (first_unloading_level for unloading;
   !> continuation if a cold start fails; refocus_classic_gw), then the refinement levels
   !> (refine_levels).
   subroutine solve_scaled(problem, options, sol, est, method_used, error)
      type(scaled_problem), intent(in) :: problem
      type(solver_options), intent(in) :: options
      type(discrete_solution), intent(out) :: sol
      real(dp), intent(out) :: est
      integer, intent(out) :: method_used
      type(egw_error), allocatable, intent(out) :: error
      type(discrete_solution) :: coarse
      type(scaled_problem) :: prob
      type(mesh_family) :: mesh
      real(dp) :: order

      prob = problem
      order = force_order
      if (allocated(prob%closest)) order = unload_order
      method_used = options%method
      if (method_used == method_auto) method_used = method_newton
      ! Unloading: Newton to a scaled residual of 1e-4 rel_tol (at most 1e-10, 1e-11 from
      ! rel_tol 1e-7 down), which moves the force by ~1e-4 rel_tol times the Jacobian's
      ! condition, far inside the tolerance and the Richardson margin; a level whose last
      ! step lands between 1e-11 and that (seen: 2.8e-11, 4.0e-11 on the reference cases)
      ! is spared an evaluation of Z_u over the mesh and an LU.
      if (allocated(prob%closest)) prob%residual_tol = &
         & max(prob%residual_tol, min(1.0e-10_dp, 1.0e-4_dp*options%rel_tol))
      call first_mesh(prob, options, mesh)
      if (allocated(prob%closest)) then
         call first_unloading_level(prob, options, method_used, mesh, coarse, error)
      else
         call solve_with_tail(prob, options, method_used, mesh%layered, mesh%focus, &
            & mesh%width, mesh%step_prev, mesh%outer, coarse, error)
      end if
      if (allocated(error)) then
         ! A cold start that fails (classic GW deep in contact is the stiff case) is retried
         ! by continuation in delta from a shallow contact.
         if (error%stat /= egw_not_converged .or. prob%delta <= 1.0_dp) return
         call continuation(prob, options, method_used, mesh%focus, mesh%width, &
            & mesh%step_prev, mesh%outer, coarse, error)
         if (allocated(error)) return
      end if
      if (.not. prob%extended .and. prob%delta > 1.0_dp) then
         call refocus_classic_gw(prob, options, method_used, mesh, coarse, error)
         if (allocated(error)) return
      end if
      call refine_levels(prob, options, method_used, order, mesh, coarse, sol, est, error)
   end subroutine solve_scaled

   !> The mesh family of the first level (doc/theory.md §7 "Unknowns and discretisation"):
   !> grading focus, width and outer radius (mesh_geometry), and the steps of the first
   !> level (step_prev) and of the next (step).
   pure subroutine first_mesh(prob, options, mesh)
      type(scaled_problem), intent(in) :: prob
      type(solver_options), intent(in) :: options
      type(mesh_family), intent(out) :: mesh
      call mesh_geometry(prob, options%rel_tol, mesh%focus, mesh%width, mesh%outer)
      mesh%layered = prob%extended
      if (options%n_radial > 0) then
         mesh%step = step_for_nodes(prob%extended, mesh%focus, mesh%width, mesh%outer, &
            & options%n_radial)
         mesh%step_prev = coarsen*mesh%step
      else
         mesh%step_prev = coarsest_level_step(prob, mesh)
         mesh%step = mesh%step_prev/coarsen
      end if
   end subroutine first_mesh

   !> Step of the first level of an automatic mesh family.
   pure real(dp) function coarsest_level_step(prob, mesh) result(step)
      type(scaled_problem), intent(in) :: prob
      type(mesh_family), intent(in) :: mesh
      ! Deep contacts resolve the same relative error on coarser steps (the rough part,
      ! where the error lives, weighs less): start coarser there ...
      step = coarsest_step*max(1.0_dp, prob%delta)**0.1_dp
      ! ... but never fewer than min_elements graded elements: on fewer, two levels can
      ! agree by accident (not yet asymptotic) and the estimate would be worthless.
      step = min(step, (asinh(mesh%focus/mesh%width) &
         & + asinh((mesh%outer - mesh%focus)/mesh%width))/real(min_elements, dp))
   end function coarsest_level_step

   !> The first level of an unloading solve (doc/theory.md §8 "Sphere"): a locating solve
   !> on a coarser mesh places the element edges at the kinks of p(r) (prob%branch) and
   !> trims the mesh to where the unloading pressure has died (trim_to_unloading_decay);
   !> then the first level itself, whose kink edges are relocated (relocate_kinks).
   subroutine first_unloading_level(prob, options, method, mesh, coarse, error)
      type(scaled_problem), intent(inout) :: prob
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      type(mesh_family), intent(inout) :: mesh
      type(discrete_solution), intent(out) :: coarse
      type(egw_error), allocatable, intent(out) :: error
      type(discrete_solution) :: first
      type(scaled_problem) :: locate
      ! Unloading: where d crosses d_max the law switches branch and p(r) has a kink
      ! (dp/dh jumps), which costs an element holding it its order (and the Richardson
      ! estimate its meaning); so do, more weakly (d2p/dh2 jumps), the radii where
      ! d - d_max crosses a kink of Z_u in Delta (unloading_kinks). Without those (seen:
      ! errors 10-35x the estimate) or with one edge off its kink, both levels carry the
      ! same kink error, which their difference cannot see. The crossings, from a solve
      ! on a mesh of twice the step (a quarter of a level's cost), become element edges
      ! of every level. (Three times the step was cheaper, but placed an edge far enough
      ! off to leave an error of 4.8e-7 under an estimate of 3e-9.)
      ! That solve only places edges and starts the next: Newton stops at a residual of
      ! 1e-6, whose error in the gap is below that mesh's own (the next level starts
      ! from an interpolation error of 1e-4..1e-6 anyway): one evaluation of Z_u over the
      ! mesh and an LU fewer in most cases; on the 12 reference cases the edges, forces
      ! and estimates are those of a fully converged locating solve to 3 digits.
      ! Nor does it need the geometric layers at the Hertz edge (16 of its ~41 nodes):
      ! without them the 12 reference cases keep their errors (<= 1.2e-7) and a sweep
      ! of 40 random unloading solves agrees with rel_tol 1e-9 solves as well as with
      ! the layers (worst 5e-7, the same case either way).
      locate = prob
      locate%residual_tol = 1.0e-6_dp
      call solve_with_tail(locate, options, method, .false., mesh%focus, mesh%width, &
         & 2.0_dp*mesh%step_prev, mesh%outer, first, error)
      if (allocated(error)) then
         deallocate (error)
         call solve_with_tail(prob, options, method, mesh%layered, mesh%focus, mesh%width, &
            & mesh%step_prev, mesh%outer, coarse, error)
         return
      end if
      ! Edges only where the pressure is not negligible: a kink where r p is below
      ! 1e-4 rel_tol of its peak cannot move the force by rel_tol even if its elements
      ! were wholly wrong, and such edges (seen: r p at 1e-45 of the peak, in the far
      ! tail) cost a level of elements 4 nodes each.
      prob%branch = branch_radii(prob, first, [0.0_dp, unloading_kinks(prob%unload)], &
         & 1.0e-4_dp*options%rel_tol, prob%n_branch)
      if (prob%closest%extended) prob%amax_edge = .not. negligible_at(first, &
         & sqrt(prob%closest%delta), 1.0e-4_dp*options%rel_tol)
      if (options%n_radial == 0) call trim_to_unloading_decay(prob, options, first, mesh)
      ! The first level only enters the estimate through its difference to the next
      ! (divided by 2.4) and places the kinks again: Newton to a scaled residual of
      ! 1e-2 rel_tol (at most 1e-8) moves its force by far less than the estimate's
      ! margin and its kinks by ~1e-8 sigma, and takes one step fewer (psi 10, delta 0.5
      ! after delta_max 1: 1.59 -> 1.47 ms; the 16 references and a 100-solve sweep
      ! unchanged to 3 digits at rel_tol 1e-6..1e-8).
      locate = prob
      locate%residual_tol = max(prob%residual_tol, min(1.0e-8_dp, &
         & 1.0e-2_dp*options%rel_tol))
      call solve_with_tail(locate, options, method, mesh%layered, mesh%focus, mesh%width, &
         & mesh%step_prev, mesh%outer, coarse, error, first)
      ! The locating solve (twice the step, no kink edges) places the kinks 3e-4..3e-3
      ! off (psi 10 after delta_max 2: at delta 0 the edges were 2.3e-3 off, an error
      ! of 9e-7 that every level shared, so rel_tol 1e-8 was never reached and the
      ! rel_tol 1e-7 answer was 2e-7 off the reference under an estimate of 5e-8).
      ! Relocated from the first level (kink edges in place, a finer mesh) and that
      ! level solved again until the offset costs less than a tenth of rel_tol.
      if (.not. allocated(error)) call relocate_kinks(prob, options, method, mesh%layered, &
         & mesh%focus, mesh%width, mesh%step_prev, mesh%outer, coarse, error)
   end subroutine first_unloading_level

   !> The outer radius (and the steps) of an unloading solve from where the unloading
   !> pressure of the locating solve (first) has died (doc/theory.md §8).
   pure subroutine trim_to_unloading_decay(prob, options, first, mesh)
      type(scaled_problem), intent(in) :: prob
      type(solver_options), intent(in) :: options
      type(discrete_solution), intent(in) :: first
      type(mesh_family), intent(inout) :: mesh
      real(dp) :: trimmed
      ! mesh_geometry sizes the mesh for the loading law, whose Gaussian tail reaches
      ! far out, but Z_u vanishes once the summits it holds have recovered, so r p
      ! falls far faster (seen: 1e-19 of the loading tail at the same radius). A mesh
      ! trimmed to where r p is below 1e-6 rel_tol of its peak (the force beyond is
      ! then ~1e-6 rel_tol, and the tail check of solve_with_tail still guards it)
      ! puts the same number of elements where the force is. At delta -1 after
      ! delta_max 1, psi 10 (a force of 1.4e-18 from a peak at r ~ 0.1 that has fallen
      ! by 1e-12 at r ~ 0.5, on a mesh out to 3.2) this spares a third level. On a
      ! sweep of 120 unloading solves (psi 1-10, delta_max -0.5..20) the 14 trimmed
      ! ones moved by at most 4e-8, except psi 10, delta 0 after delta_max 2, where
      ! the untrimmed solve was 9.7e-6 off its own rel_tol 1e-7 answer and the
      ! trimmed one is 2.1e-7 off.
      trimmed = decayed_radius(first, 1.0e-6_dp*options%rel_tol)
      ! Only a mesh that shrinks by half: a slight trim gains little and moves the
      ! edges, which can cost a level (seen: outer 3.59 -> 3.36 at delta 0.5 after
      ! delta_max 1, psi 10, a third level).
      ! (trimmed is 0 where the pressure is 0 throughout: nothing to trim to.)
      if (trimmed > 0.0_dp .and. trimmed <= 0.5_dp*mesh%outer) then
         ! At the centre focus the grading width must fit inside the trimmed mesh.
         if (mesh%focus == 0.0_dp) mesh%width = min(mesh%width, 0.5_dp*trimmed)
         mesh%outer = max(trimmed, mesh%focus + 2.0_dp*mesh%width)
         mesh%step_prev = coarsest_level_step(prob, mesh)
         mesh%step = mesh%step_prev/coarsen
      end if
   end subroutine trim_to_unloading_decay

   !> Classic GW deep in contact (doc/theory.md §5 "Useful facts", §7): with
   !> p_H(0) >> C sigma**1.5 (centre gap below -3 sigma) the solution ends in a thin layer
   !> around d = 0 whose place is only known from a solution (near, not at, the Hertz
   !> edge): the mesh family is refocused there and the first level (coarse) solved again.
   subroutine refocus_classic_gw(prob, options, method, mesh, coarse, error)
      type(scaled_problem), intent(in) :: prob
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      type(mesh_family), intent(inout) :: mesh
      type(discrete_solution), intent(inout) :: coarse
      type(egw_error), allocatable, intent(out) :: error
      type(discrete_solution) :: first
      if (.not. law_inverse(prob, 2.0_dp*prob%a/pi) < -3.0_dp) return
      call gap_edge(coarse, mesh%focus, mesh%width)
      mesh%layered = .true.
      ! The first level again, on the refocused mesh family: two levels of different
      ! families can agree by accident (seen: both 1.3e-7 off at mu = 0.1,
      ! delta/sigma = 100, their difference 1.5e-8), so Richardson needs one family.
      first = coarse
      call solve_with_tail(prob, options, method, mesh%layered, mesh%focus, mesh%width, &
         & mesh%step_prev, mesh%outer, coarse, error, first)
   end subroutine refocus_classic_gw

   !> Levels of decreasing step (doc/theory.md §7 "Error control"), each warm-started from
   !> the last (coarse): the force of each and of the one before give the Richardson
   !> estimate |P_h - P_H|/((H/h)**order - 1) of the error of P_h, plus the tail and (for
   !> unloading) the kink offsets (add_kink_error); below rel_tol/2 the level is accepted,
   !> else the next step is predicted from the estimate.
   subroutine refine_levels(prob, options, method, order, mesh, coarse, sol, est, error)
      type(scaled_problem), intent(inout) :: prob
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      real(dp), intent(in) :: order   !< order assumed by the Richardson estimate
      type(mesh_family), intent(inout) :: mesh
      type(discrete_solution), intent(inout) :: coarse   !< the previous level
      type(discrete_solution), intent(out) :: sol
      real(dp), intent(out) :: est
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: total
      integer :: level
      logical :: confirm, confirming, vanished

      confirm = .false.
      confirming = .false.
      do level = 1, 12
         ! The previous level's solution is the initial guess: 2-3 Newton steps instead of 5-8.
         call solve_with_tail(prob, options, method, mesh%layered, mesh%focus, mesh%width, &
            & mesh%step, mesh%outer, sol, error, coarse)
         if (allocated(error)) return
         total = abs(smooth_force(prob) + sol%force)
         est = 0.0_dp
         if (total < tiny_force) then
            ! Unloading far apart: the force has fallen to the underflow range, where
            ! relative differences are rounding noise. As for negligible(): 0, error 1.
            sol%p = 0.0_dp
            sol%force = 0.0_dp
            est = 1.0_dp
            return
         end if
         ! Discretisation (Richardson) plus the force estimated beyond the outer radius,
         ! which both levels share and their difference cannot see.
         if (total > 0.0_dp) est = discretisation_error(sol%force, coarse%force, total, &
            & mesh%step_prev/mesh%step, confirming, order) + sol%tail/total
         if (allocated(prob%branch) .and. total > 0.0_dp) then
            call add_kink_error(prob, options, method, order, confirming, mesh, coarse, sol, &
               & total, est, vanished, error)
            if (allocated(error)) return
            if (vanished) cycle
         end if
         ! Half the tolerance: a margin for the estimate itself.
         if (options%n_radial > 0) return
         if (est <= 0.5_dp*options%rel_tol) then
            ! Below rel_tol 1e-6 the two levels of an unloading solve can agree by accident
            ! while both are off (the elements beside a d = d_max edge: psi 10, delta 0.3
            ! after delta_max 1, rel_tol 1e-7: 1.6e-7 off under an estimate of 2.4e-9; 4 of
            ! the 92 solves of egw-bench --unloading-sweep at 1e-7, up to 2.7e-7): one level
            ! more, at half the step, whose estimate is the whole difference to the
            ! accepted level, not its Richardson fraction (later levels, if that fails, are
            ! estimated as before). The sweep then has none above rel_tol.
            if (confirm .or. .not. (allocated(prob%branch) .and. &
               & options%rel_tol < 1.0e-6_dp) .or. mesh%step <= finest_step) return
            confirm = .true.
            confirming = .true.
            mesh%step_prev = mesh%step
            mesh%step = max(finest_step, 0.5_dp*mesh%step)
            coarse = sol
            cycle
         end if
         confirming = .false.
         if (mesh%step <= finest_step) exit
         mesh%step_prev = mesh%step
         mesh%step = max(finest_step, 0.25_dp*mesh%step, min(mesh%step/1.25_dp, &
            & mesh%step*(0.25_dp*options%rel_tol/est)**(1.0_dp/force_order)))
         coarse = sol
      end do
      call fatal_error(error, egw_not_converged, "rel_tol = "//format_real(options%rel_tol) &
         & //" not reached: the finest mesh's force error estimate is "//format_real(est) &
         & //", above rel_tol/2 = "//format_real(0.5_dp*options%rel_tol) &
         & //" (half: a margin for the estimate); this solve reaches rel_tol >= " &
         & //format_real(2.0_dp*est))
   end subroutine refine_levels

   !> Unloading (doc/theory.md §8): adds to est what the kink edges still miss by (both
   !> levels share it). Edges off by more than a tenth of rel_tol are moved and both levels
   !> (coarse, sol) solved again; vanished when the force has then fallen to the underflow
   !> range (est is then left as it was).
   subroutine add_kink_error(prob, options, method, order, confirming, mesh, coarse, sol, &
      & total, est, vanished, error)
      type(scaled_problem), intent(inout) :: prob
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      real(dp), intent(in) :: order
      logical, intent(in) :: confirming   !< est is the whole difference of the levels
      type(mesh_family), intent(inout) :: mesh
      type(discrete_solution), intent(inout) :: coarse, sol
      real(dp), intent(in) :: total   !< |force| of the level (sol)
      real(dp), intent(inout) :: est
      logical, intent(out) :: vanished
      type(egw_error), allocatable, intent(out) :: error
      real(dp), allocatable :: moved(:)
      real(dp) :: kink_err, total_again
      integer :: n_moved
      type(discrete_solution) :: guess

      vanished = .false.
      kink_err = kink_offset_error(prob, sol, options%rel_tol, moved, n_moved)/total
      if (kink_err > 0.1_dp*options%rel_tol .and. options%n_radial == 0) then
         prob%branch = moved
         prob%n_branch = n_moved
         ! each level restarts from its own solution: a copy, since the result (intent out)
         ! may not be the guess too
         guess = coarse
         call solve_with_tail(prob, options, method, mesh%layered, mesh%focus, mesh%width, &
            & mesh%step_prev, mesh%outer, coarse, error, guess)
         if (allocated(error)) return
         guess = sol
         call solve_with_tail(prob, options, method, mesh%layered, mesh%focus, mesh%width, &
            & mesh%step, mesh%outer, sol, error, guess)
         if (allocated(error)) return
         total_again = abs(smooth_force(prob) + sol%force)
         vanished = total_again < tiny_force
         if (vanished) return
         kink_err = kink_offset_error(prob, sol, options%rel_tol, moved, n_moved)/total_again
         est = discretisation_error(sol%force, coarse%force, total_again, &
            & mesh%step_prev/mesh%step, confirming, order) + sol%tail/total_again
      end if
      est = est + kink_err
   end subroutine add_kink_error

   !> The relative discretisation error of the finer of two levels (forces fine, coarse,
   !> step ratio) out of their difference: its Richardson fraction for the order assumed,
   !> or the whole difference where the fraction is not trusted (conservative).
   pure real(dp) function discretisation_error(fine, coarse, total, ratio, whole, order) &
      & result(e)
      real(dp), intent(in) :: fine, coarse, total, ratio, order
      logical, intent(in) :: whole
      e = abs(fine - coarse)/total
      if (.not. whole) e = e/(ratio**order - 1.0_dp)
   end function discretisation_error

   !> Continuation in delta: solve at delta/sigma = 1 from a cold start, then at delta
   !> values growing by at most a factor 4 up to prob%delta, each started from the previous
   !> solution stretched by the Hertz similarity (r ~ sqrt(delta), w ~ delta).
   subroutine continuation(prob, options, method, focus, width, step, outer, sol, error)
      type(scaled_problem), intent(in) :: prob
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      real(dp), intent(in) :: focus, width, step
      real(dp), intent(inout) :: outer
      type(discrete_solution), intent(out) :: sol
      type(egw_error), allocatable, intent(out) :: error
      type(scaled_problem) :: stage
      type(discrete_solution) :: previous
      real(dp) :: stage_focus, stage_width, stage_outer, ratio, delta_prev
      integer :: k, n_stages

      n_stages = ceiling(log(prob%delta)/log(4.0_dp))
      stage = prob
      do k = 0, n_stages
         stage%delta = prob%delta**(real(k, dp)/real(n_stages, dp))
         stage%a = sqrt(stage%delta)
         if (k == n_stages) then
            ! The last stage is the problem itself, on its own mesh.
            stage = prob
            stage_focus = focus
            stage_width = width
            stage_outer = outer
         else
            call mesh_geometry(stage, options%rel_tol, stage_focus, stage_width, stage_outer)
         end if
         if (k == 0) then
            call solve_with_tail(stage, options, method, stage%extended, stage_focus, &
               & stage_width, step, stage_outer, sol, error)
         else
            ratio = stage%delta/delta_prev
            previous%mesh%edge = previous%mesh%edge*sqrt(ratio)
            previous%w = previous%w*ratio
            call solve_with_tail(stage, options, method, stage%extended, stage_focus, &
               & stage_width, step, stage_outer, sol, error, previous)
         end if
         if (allocated(error)) return
         previous = sol
         delta_prev = stage%delta
      end do
      outer = stage_outer
   end subroutine continuation

   !> Solve on the mesh of the given step, growing the outer radius (kept for the next
   !> levels) until the force estimated beyond it is below 1 % of the tolerance.
   subroutine solve_with_tail(prob, options, method, layered, focus, width, step, outer, sol, &
      & error, guess)
      type(scaled_problem), intent(in) :: prob
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      logical, intent(in) :: layered   !< geometric layers at the focus
      real(dp), intent(in) :: focus, width, step
      real(dp), intent(inout) :: outer
      type(discrete_solution), intent(out) :: sol
      type(egw_error), allocatable, intent(out) :: error
      type(discrete_solution), intent(in), optional :: guess  !< solution on another mesh
      real(dp) :: total, keep
      integer :: attempt
      real(dp), allocatable :: edges(:)

      do attempt = 1, 8
         edges = graded_edges(focus, width, outer, step)
         if (layered) edges = focus_refined(edges, focus)
         ! Unloading after an extended loading: d_max has its (r - a_max)**1.5 onset at
         ! the loading Hertz edge; an element edge there keeps the elements smooth.
         if (allocated(prob%closest)) then
            ! The (r - a_max)**1.5 onset is milder than a kink: moving a graded edge onto it
            ! (as for the kinks) made the elements beside it uneven and cost accuracy (delta
            ! 0.5, delta_max 1, psi 10: error 7e-8 -> 2e-7, one level more); it keeps the
            ! insertion unless within a tenth of an element of an edge.
            if (prob%closest%extended .and. prob%amax_edge) edges = with_edge(edges, &
               & sqrt(prob%closest%delta))
            if (allocated(prob%branch)) then
               keep = 0.0_dp
               if (prob%closest%extended .and. prob%amax_edge) keep = sqrt(prob%closest%delta)
               edges = with_kink_edges(edges, prob%branch, focus, prob%n_branch, keep)
            end if
         end if
         call solve_mesh(prob, options, method, edges, sol, error, guess)
         if (allocated(error)) return
         total = abs(smooth_force(prob) + sol%force)
         if (sol%tail <= 0.01_dp*options%rel_tol*total .or. total == 0.0_dp) return
         outer = grown_outer(prob, sol, options%rel_tol*total, outer)
      end do
      call fatal_error(error, egw_not_converged, "delta = "//format_real(prob%delta) &
         & //" (in units of sigma): the pressure does not decay within the outer radius " &
         & //format_real(outer))
   end subroutine solve_with_tail

   !> Kink edges of an unloading solve placed from a solution with them in place (sol, the
   !> first level): while what the edges still miss by (kink_offset_error) exceeds a tenth
   !> of rel_tol, move them and solve that level again (at most 3 times).
   subroutine relocate_kinks(prob, options, method, layered, focus, width, step, outer, sol, &
      & error)
      type(scaled_problem), intent(inout) :: prob
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      logical, intent(in) :: layered
      real(dp), intent(in) :: focus, width, step
      real(dp), intent(inout) :: outer
      type(discrete_solution), intent(inout) :: sol
      type(egw_error), allocatable, intent(out) :: error
      type(discrete_solution) :: guess
      real(dp), allocatable :: moved(:)
      real(dp) :: total
      integer :: pass, n_moved
      if (options%n_radial > 0) return
      do pass = 1, 3
         total = abs(smooth_force(prob) + sol%force)
         if (.not. total > 0.0_dp) return
         if (kink_offset_error(prob, sol, options%rel_tol, moved, n_moved) &
            & <= 0.1_dp*options%rel_tol*total) return
         prob%branch = moved
         prob%n_branch = n_moved
         call move_solution(sol, guess)
         call solve_with_tail(prob, options, method, layered, focus, width, step, outer, sol, &
            & error, guess)
         if (allocated(error)) return
      end do
   end subroutine relocate_kinks

   !> to <- from (the arrays moved, not copied).
   pure subroutine move_solution(from, to)
      type(discrete_solution), intent(inout) :: from
      type(discrete_solution), intent(out) :: to
      to%mesh = from%mesh
      call move_alloc(from%w, to%w)
   end subroutine move_solution

   !> Force an unloading solution misses because its kink edges (prob%branch) are off the
   !> kinks of its own field (moved: the kinks located again on sol, branch_radii): at a
   !> kink where dp/dr jumps by J, an edge e off it leaves a wedge of pressure J e**2/2 that
   !> no element polynomial holds, 2 pi r J e**2/2 of force (both levels share it: the
   !> Richardson estimate cannot see it). J by one-sided differences of p on the solution's
   !> field. The kinks of Z_u in Delta (d2p jumps) give J ~ 0: their wedges are e**3.
   !> A kink with no edge near it counts at the distance to the nearest edge of any kind.
   function kink_offset_error(prob, sol, rel_tol, moved, n_moved) result(err)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(in) :: sol
      real(dp), intent(in) :: rel_tol
      real(dp), allocatable, intent(out) :: moved(:)
      integer, intent(out) :: n_moved     !< how many of moved are d = d_max crossings
      real(dp) :: err
      real(dp) :: r, off, s, gapr, jump, pm(-2:2)
      integer :: k, i
      moved = branch_radii(prob, sol, [0.0_dp, unloading_kinks(prob%unload)], &
         & 1.0e-4_dp*rel_tol, n_moved)
      err = 0.0_dp
      do k = 1, size(moved)
         r = moved(k)
         off = huge(1.0_dp)
         if (size(prob%branch) > 0) off = minval(abs(prob%branch - r))
         off = min(off, minval(abs(sol%mesh%edge(0:sol%mesh%n_elem) - r)))
         if (off == 0.0_dp) cycle
         ! difference step: well inside the gap to the neighbouring kinks
         gapr = r
         do i = 1, size(moved)
            if (i /= k) gapr = min(gapr, abs(moved(i) - r))
         end do
         s = 1.0e-3_dp*gapr
         do i = -2, 2
            if (i /= 0) pm(i) = pressure_at(r + real(i, dp)*s)
         end do
         jump = ((pm(2) - pm(1)) - (pm(-1) - pm(-2)))/s
         err = err + pi*r*abs(jump)*off**2
      end do
   contains
      real(dp) function pressure_at(x) result(p)
         real(dp), intent(in) :: x
         real(dp) :: gm(1), f, dfdh
         gm = closest_gap(prob%closest, [x])
         call unloading_pressure(prob%unload, base_gap(prob, x) &
            & + interpolate_nodal(sol%mesh, sol%w, x), gm(1), f, dfdh)
         p = prob%scale*f
      end function pressure_at
   end function kink_offset_error

   !> Where the gap of a solution last crosses 0 (linear between Gauss points), and the
   !> distance over which it grows by one sigma there; focus and width unchanged if the
   !> gap never crosses 0.
   pure subroutine gap_edge(sol, focus, width)
      type(discrete_solution), intent(in) :: sol
      real(dp), intent(inout) :: focus, width
      real(dp) :: slope
      integer :: g
      do g = size(sol%gap) - 1, 1, -1
         if (sol%gap(g) < 0.0_dp .and. sol%gap(g + 1) >= 0.0_dp) then
            slope = (sol%gap(g + 1) - sol%gap(g))/(sol%mesh%gauss_r(g + 1) - sol%mesh%gauss_r(g))
            focus = sol%mesh%gauss_r(g) - sol%gap(g)/slope
            width = min(width, 1.0_dp/slope)
            return
         end if
      end do
   end subroutine gap_edge

   !> Radii where the gap of a solution crosses its closest-approach gap plus one of the
   !> levels (0: the branch; the kinks of Z_u in Delta), at most 16. Bracketed by the Gauss
   !> points where gap - gap_min - level changes sign, then bisected on the solution's own
   !> field (nodal interpolation of w, the history's d_max): an edge placed off the kink by
   !> the linear interpolation's error (~ spacing^2 x curvature) left both levels with the
   !> same error, which their difference (the Richardson estimate) cannot see.
   function branch_radii(prob, sol, levels, negligible_weight, n_first) result(radii)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(in) :: sol
      real(dp), intent(in) :: levels(:)
      real(dp), intent(in) :: negligible_weight  !< skip radii where negligible_at says so
      integer, intent(out) :: n_first            !< how many radii (the first) are of levels(1)
      real(dp), allocatable :: radii(:)
      real(dp) :: f0, f1, lo, hi, mid, f_lo, f_hi, f_mid
      integer :: g, k, i, side
      allocate (radii(0))
      n_first = 0
      do k = 1, size(levels)
         do g = 1, size(sol%gap) - 1
            f0 = sol%gap(g) - sol%gap_min(g) - levels(k)
            f1 = sol%gap(g + 1) - sol%gap_min(g + 1) - levels(k)
            if ((f0 < 0.0_dp .eqv. f1 < 0.0_dp) .or. size(radii) >= 16) cycle
            if (negligible_at(sol, 0.5_dp*(sol%mesh%gauss_r(g) + sol%mesh%gauss_r(g + 1)), &
               & negligible_weight)) cycle
            lo = sol%mesh%gauss_r(g)
            hi = sol%mesh%gauss_r(g + 1)
            mid = lo + f0/(f0 - f1)*(hi - lo)
            f_lo = excess(lo)
            f_hi = excess(hi)
            if ((f_lo < 0.0_dp) .neqv. (f_hi < 0.0_dp)) then
               ! Illinois (regula falsi that halves the value kept twice): ~8 evaluations
               ! of the field to full precision where bisection took 40-50.
               side = 0
               do i = 1, 60
                  mid = (lo*f_hi - hi*f_lo)/(f_hi - f_lo)
                  if (.not. (mid > lo .and. mid < hi)) mid = 0.5_dp*(lo + hi)
                  if (.not. (mid > lo .and. mid < hi)) exit
                  f_mid = excess(mid)
                  if (f_mid == 0.0_dp) exit
                  if ((f_mid < 0.0_dp) .eqv. (f_lo < 0.0_dp)) then
                     lo = mid
                     f_lo = f_mid
                     if (side == 1) f_hi = 0.5_dp*f_hi
                     side = 1
                  else
                     hi = mid
                     f_hi = f_mid
                     if (side == -1) f_lo = 0.5_dp*f_lo
                     side = -1
                  end if
                  if (hi - lo <= 8.0_dp*epsilon(1.0_dp)*hi) exit
               end do
            end if
            radii = [radii, mid]
         end do
         if (k == 1) n_first = size(radii)
      end do
   contains
      !> gap - gap_min - level at r from the nodal field
      pure real(dp) function excess(r)
         real(dp), intent(in) :: r
         real(dp) :: gm(1)
         gm = closest_gap(prob%closest, [r])
         excess = base_gap(prob, r) + interpolate_nodal(sol%mesh, sol%w, r) - gm(1) - levels(k)
      end function excess
   end function branch_radii

   !> True when r p(r) of a solution, at the two Gauss points around r (or the last one),
   !> is at most weight times its largest value over the mesh.
   pure logical function negligible_at(sol, r, weight)
      type(discrete_solution), intent(in) :: sol
      real(dp), intent(in) :: r, weight
      real(dp) :: peak, local
      integer :: g, ng
      ng = size(sol%p)
      peak = maxval(abs(sol%p*sol%mesh%gauss_r))
      g = 1
      do while (g < ng)
         if (sol%mesh%gauss_r(g + 1) >= r) exit
         g = g + 1
      end do
      local = abs(sol%p(g)*sol%mesh%gauss_r(g))
      if (g < ng) local = max(local, abs(sol%p(g + 1)*sol%mesh%gauss_r(g + 1)))
      negligible_at = local <= weight*peak
   end function negligible_at

   !> The Gauss radius just past the last one where r p of a solution exceeds weight times
   !> its peak (the last Gauss radius if that is the last point; 0 if p is 0 throughout).
   pure real(dp) function decayed_radius(sol, weight) result(r)
      type(discrete_solution), intent(in) :: sol
      real(dp), intent(in) :: weight
      real(dp) :: peak
      integer :: g, ng
      ng = size(sol%p)
      peak = maxval(abs(sol%p*sol%mesh%gauss_r))
      r = 0.0_dp
      if (.not. peak > 0.0_dp) return
      do g = ng, 1, -1
         if (abs(sol%p(g)*sol%mesh%gauss_r(g)) > weight*peak) exit
      end do
      r = sol%mesh%gauss_r(min(g + 1, ng))
   end function decayed_radius

   !> Geometric layers on both sides of the focus (the Hertz edge of the extended models),
   !> where the pressure has its one-sided (r - a)**1.5 onset: a polynomial on an element
   !> touching a converges only algebraically, on geometric layers exponentially.
   pure function focus_refined(edge, focus) result(refined)
      real(dp), intent(in) :: edge(0:), focus
      real(dp), allocatable :: refined(:)
      real(dp) :: left, right
      integer :: i, k, n
      n = size(edge) - 1
      k = -1
      if (focus > 0.0_dp) k = findloc(edge, focus, dim=1) - 1
      if (k <= 0 .or. k >= n .or. focus_layers == 0) then
         refined = edge
         return
      end if
      left = focus - edge(k - 1)
      right = edge(k + 1) - focus
      refined = [edge(0:k - 1), (focus - left*focus_ratio**i, i=1, focus_layers), focus, &
         & (focus + right*focus_ratio**i, i=focus_layers, 1, -1), edge(k + 1:n)]
   end function focus_refined

   !> edge with r added as an element edge (the element holding r split in two) unless r
   !> is outside (0, outer) or within a tenth of its element's length of an edge already.
   pure function with_edge(edge, r) result(out)
      real(dp), intent(in) :: edge(0:), r
      real(dp), allocatable :: out(:)
      integer :: k, n
      n = size(edge) - 1
      out = edge
      if (.not. (r > 0.0_dp .and. r < edge(n))) return
      k = 1
      do while (edge(k) < r)
         k = k + 1
      end do
      if (min(edge(k) - r, r - edge(k - 1)) <= 0.1_dp*(edge(k) - edge(k - 1))) return
      out = [edge(0:k - 1), r, edge(k:n)]
   end function with_edge

   !> edge with each of the radii r (kinks of the unloading pressure) made an element edge:
   !> the edge nearest r is moved onto it when that is at most a tenth of both elements
   !> beside it away (and is not 0, the outer radius, the focus or an edge placed for an
   !> earlier r), else r is inserted (the element holding it split in two). Formerly an r
   !> within a tenth of an element of an edge was skipped, which left the kink inside the
   !> element on one level and not on the other: the Richardson estimate then measured
   !> the kink, not the discretisation (seen: 3.8e-7 for an error of 2e-9). The a_max edge
   !> (keep) and the focus layers are never moved onto a kink (without the a_max edge the
   !> unloading forces of psi 10 after delta_max 1, 2 were off by up to 1.3e-6).
   pure function with_kink_edges(edge, radii, focus, n_strong, keep) result(out)
      real(dp), intent(in) :: edge(:), radii(:), focus
      integer, intent(in) :: n_strong   !< radii(:n_strong): d = d_max crossings
      real(dp), intent(in) :: keep      !< an edge never moved (the a_max edge; 0: none)
      real(dp), allocatable :: out(:)   ! indices 1..m (the edges' 0..n)
      logical, allocatable :: fixed(:)
      real(dp) :: r, room
      integer :: i, j, k, m, kf
      allocate (out(size(edge)))
      out(:) = edge
      fixed = out == focus .or. out == keep
      ! nor the focus layers
      if (focus > 0.0_dp .and. any(out == focus)) then
         kf = findloc(out, focus, dim=1)
         fixed(max(1, kf - focus_layers):min(size(out), kf + focus_layers)) = .true.
      end if
      do i = 1, size(radii)
         r = radii(i)
         m = size(out)
         if (.not. (r > 0.0_dp .and. r < out(m))) cycle
         k = 2
         do while (out(k) < r)
            k = k + 1
         end do
         ! A kink of Z_u in Delta (d2p jumps) within near_kink of its element of a branch
         ! edge (dp jumps) gets no edge of its own: the element that short between them
         ! cost 6 % of the solve (psi 10, delta 0.5 after delta_max 1: Delta reaches e
         ! 0.016 past the branch edge) for an error of order its length cubed (on the 16
         ! references the forces moved by at most 7.5e-8 at rel_tol 1e-7, within the
         ! tolerance and the estimate).
         if (i > n_strong .and. n_strong > 0) then
            if (minval(abs(radii(:n_strong) - r)) < near_kink*(out(k) - out(k - 1))) cycle
         end if
         ! nearest edge j of the element (out(k-1), out(k)] holding r
         j = k
         if (r - out(k - 1) < out(k) - r) j = k - 1
         if (abs(out(j) - r) <= 4.0_dp*epsilon(1.0_dp)*r) then
            fixed(j) = .true.
            cycle
         end if
         if (j > 1 .and. j < m) then
            room = 0.1_dp*min(out(j) - out(j - 1), out(j + 1) - out(j))
            if (.not. fixed(j) .and. abs(out(j) - r) <= room) then
               out(j) = r
               fixed(j) = .true.
               cycle
            end if
         end if
         out = [out(:k - 1), r, out(k:)]
         fixed = [fixed(:k - 1), .true., fixed(k:)]
      end do
   end function with_kink_edges

   !> Focus of the mesh grading (Hertz edge or 0), its width, and the first outer radius.
   !> Outside the Hertz edge the gap grows like (4/3)(a**2/pi)(2 s/a)**1.5 (s = r - a), so
   !> it reaches one sigma at s_b = (a/2)(3 pi/(4 a**2))**(2/3): the boundary layer whose
   !> relative width is ~ (sigma/delta)**(2/3).
   pure subroutine mesh_geometry(prob, rel_tol, focus, width, outer)
      type(scaled_problem), intent(in) :: prob
      real(dp), intent(in) :: rel_tol
      real(dp), intent(out) :: focus, width, outer
      real(dp) :: h_ref, f_ref, h_cut, f, dfdh, lo, hi, mid
      integer :: i

      if (prob%a > 1.0_dp .or. (prob%extended .and. prob%a > 0.0_dp)) then
         ! The extended models need a node at a, where z has its (r - a)**1.5 onset.
         focus = prob%a
         width = min(1.0_dp, 0.5_dp*prob%a*(0.75_dp*pi/prob%a**2)**(2.0_dp/3.0_dp))
      else
         focus = 0.0_dp
         width = min(1.0_dp, 1.0_dp/sqrt(max(1.0_dp, -prob%delta)))
      end if
      ! Gap where the law has fallen by 1e-3 rel_tol from its value at the closest point.
      h_ref = max(0.0_dp, -prob%delta)
      if (.not. prob%extended .and. prob%delta > 0.0_dp) h_ref = 0.0_dp
      call law_at(prob, h_ref, f_ref, dfdh)
      h_cut = h_ref
      do i = 1, 400
         h_cut = h_cut + 0.25_dp
         call law_at(prob, h_cut, f, dfdh)
         if (f <= 1.0e-3_dp*rel_tol*f_ref) exit
      end do
      ! Classic GW at delta > 0 has its gap below the Hertz gap by up to the centre value
      ! -h(p_H(0)) (eq. 19; ~15 sigma at sigma/delta = 1e-5): reach that much further out.
      if (.not. prob%extended .and. prob%delta > 0.0_dp) h_cut = h_cut &
         & + max(0.0_dp, -law_inverse(prob, 2.0_dp*prob%a/pi))
      ! Radius where the Hertz (or rigid) gap reaches h_cut: bisection, the gap grows with r.
      lo = prob%a
      hi = prob%a + sqrt(2.0_dp*(h_cut + abs(prob%delta))) + 10.0_dp
      do i = 1, 100
         mid = 0.5_dp*(lo + hi)
         if (estimated_gap(prob, mid) < h_cut) then
            lo = mid
         else
            hi = mid
         end if
      end do
      outer = max(hi, focus + 2.0_dp*width)
   end subroutine mesh_geometry

   !> Gap estimate before solving: the Hertz gap (extended models, and classic GW at
   !> delta > 0 whose gap is close to it) or the rigid gap.
   elemental real(dp) function estimated_gap(prob, r) result(z)
      type(scaled_problem), intent(in) :: prob
      real(dp), intent(in) :: r
      if (prob%delta > 0.0_dp) then
         z = hertz_gap(r, prob%delta, 1.0_dp)
      else
         z = 0.5_dp*r*r - prob%delta
      end if
   end function estimated_gap

   !> Step that gives about n_nodes nodes with graded_edges.
   pure real(dp) function step_for_nodes(extended, focus, width, outer, n_nodes) result(step)
      logical, intent(in) :: extended
      real(dp), intent(in) :: focus, width, outer
      integer, intent(in) :: n_nodes
      real(dp) :: xi_total
      integer :: graded_nodes
      xi_total = asinh(focus/width) + asinh((outer - focus)/width)
      ! The focus layers add 2 focus_layers elements when the focus is inside the mesh.
      graded_nodes = n_nodes - 1
      if (extended .and. focus > 0.0_dp) graded_nodes = graded_nodes &
         & - 2*focus_layers*deflection_degree
      step = xi_total*real(deflection_degree, dp) &
         & /real(max(graded_nodes, 2*deflection_degree), dp)
   end function step_for_nodes

   !> New outer radius when the pressure at the old one leaves too much force outside:
   !> the pressure falls at least like exp(-kappa (r - outer)) with kappa from the last
   !> two Gauss points.
   pure real(dp) function grown_outer(prob, sol, allowed, outer) result(new_outer)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(in) :: sol
      real(dp), intent(in) :: allowed, outer
      real(dp) :: kappa
      integer :: n
      n = size(sol%p)
      kappa = 0.0_dp
      if (sol%p(n) > 0.0_dp .and. sol%p(n - 1) > sol%p(n)) kappa = log(sol%p(n - 1)/sol%p(n)) &
         & /(sol%mesh%gauss_r(n) - sol%mesh%gauss_r(n - 1))
      if (kappa > 0.0_dp) then
         new_outer = outer + max(0.25_dp*(outer - prob%a), &
            & log(max(sol%tail/(0.001_dp*allowed), 2.0_dp))/kappa)
      else
         new_outer = outer + 0.5_dp*(outer - prob%a)
      end if
      if (prob%a > 0.0_dp) new_outer = max(new_outer, prob%a*1.05_dp)
   end function grown_outer

   !> Build the mesh on edges, assemble, and solve the discrete equations; then the force,
   !> its delta-derivative (implicit differentiation), moments and the tail estimate.
   subroutine solve_mesh(prob, options, method, edges, sol, error, guess)
      type(scaled_problem), intent(in) :: prob
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      real(dp), intent(in) :: edges(0:)
      type(discrete_solution), intent(out) :: sol
      type(egw_error), allocatable, intent(out) :: error
      type(discrete_solution), intent(in), optional :: guess  !< solution on another mesh
      integer :: n, ng, max_iter, i, stat
      real(dp) :: kappa, rn

      if ((size(edges) - 1)*deflection_degree + 1 > max_mesh_nodes) then
         call fatal_error(error, egw_not_converged, "delta = "//format_real(prob%delta) &
            & //" (in units of sigma): the mesh would need " &
            & //int_str((size(edges) - 1)*deflection_degree + 1)//" nodes, more than " &
            & //int_str(max_mesh_nodes))
         return
      end if
      call build_mesh(edges, deflection_degree, pressure_points, sol%mesh)
      n = mesh_nodes(sol%mesh)
      ng = size(sol%mesh%gauss_r)
      allocate (sol%infl(n, ng), stat=stat)
      if (stat == 0) call assemble_influence(sol%mesh, sol%mesh%node, sol%infl, &
         & options%n_threads, stat)
      if (stat /= 0) then
         call fatal_error(error, egw_out_of_memory, "the influence matrix of " &
            & //int_str(n)//" nodes could not be allocated")
         return
      end if
      sol%base = base_gap(prob, sol%mesh%gauss_r)
      sol%dbase = base_gap_rate(prob, sol%mesh%gauss_r)
      if (allocated(prob%closest)) sol%gap_min = closest_gap(prob%closest, sol%mesh%gauss_r)
      if (present(guess)) then
         ! Interpolated; beyond the guess's mesh its outermost value (w_G varies slowly there).
         allocate (sol%w(n))
         do i = 1, n
            sol%w(i) = interpolate_nodal(guess%mesh, guess%w, &
               & min(sol%mesh%node(i), guess%mesh%edge(guess%mesh%n_elem)))
         end do
      else
         call initial_deflection(prob, sol)
      end if

      max_iter = options%max_iter
      if (method == method_picard) then
         if (max_iter == 0) max_iter = picard_max_default
         call picard(prob, sol, max_iter, error)
      else
         if (max_iter == 0) max_iter = newton_max_default
         call newton(prob, sol, max_iter, error)
      end if
      if (allocated(error)) return

      sol%force = 2.0_dp*pi*sum(sol%mesh%gauss_w*sol%mesh%gauss_r*sol%p)
      sol%moment0 = sum(sol%mesh%gauss_w*sol%p)
      sol%moment1 = sum(sol%mesh%gauss_w*sol%mesh%gauss_r*sol%p)
      ! Force beyond the outer radius if p keeps falling like at the last two Gauss points.
      rn = sol%mesh%gauss_r(ng)
      kappa = 0.0_dp
      if (sol%p(ng) > 0.0_dp .and. sol%p(ng - 1) > sol%p(ng)) &
         & kappa = log(sol%p(ng - 1)/sol%p(ng))/(rn - sol%mesh%gauss_r(ng - 1))
      if (kappa > 0.0_dp) then
         sol%tail = 2.0_dp*pi*rn*sol%p(ng)*(1.0_dp/kappa + 1.0_dp/(rn*kappa**2))
      else
         sol%tail = huge(1.0_dp)
         if (sol%p(ng) == 0.0_dp) sol%tail = 0.0_dp
      end if
   end subroutine solve_mesh

   !> d(force)/d(delta) of the converged discrete solution by implicit differentiation:
   !> J dw/d(delta) = infl (p' dz/d(delta)) with J the Jacobian at the solution. Newton's
   !> last factors belong to an iterate near the solution: iterative refinement with them
   !> (residuals with the exact J) contracts by |J_old**-1 (J - J_old)| << 1 per sweep
   !> and spares an LU; without them, or if refinement stalls, J itself is factored.
   subroutine differentiate(prob, sol, error)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(inout) :: sol
      type(egw_error), allocatable, intent(out) :: error
      integer, parameter :: max_sweeps = 6
      real(dp), allocatable :: jac(:, :), rhs(:), x(:, :), corr(:, :), rate(:)
      integer, allocatable :: ipiv(:)
      integer :: n, info, sweep
      logical :: refined
      n = size(sol%w)
      allocate (jac(n, n), x(n, 1), corr(n, 1), stat=info)
      if (info /= 0) then
         call fatal_error(error, egw_out_of_memory, "the Jacobian of " &
            & //int_str(n)//" nodes could not be allocated")
         return
      end if
      call evaluate(prob, sol)
      call jacobian(sol, jac)
      rhs = matmul(sol%infl, sol%dpdh*sol%dbase)
      refined = .false.
      if (allocated(sol%lu)) then
         if (size(sol%lu, 1) == n) then
            x(:, 1) = rhs
            call dgetrs('N', n, 1, sol%lu, n, sol%pivots, x, n, info)
            do sweep = 1, max_sweeps
               corr(:, 1) = rhs - matmul(jac, x(:, 1))
               call dgetrs('N', n, 1, sol%lu, n, sol%pivots, corr, n, info)
               x = x + corr
               if (maxval(abs(corr)) <= 1.0e-14_dp*maxval(abs(x))) then
                  refined = .true.
                  exit
               end if
            end do
         end if
      end if
      if (.not. refined) then
         allocate (ipiv(n))
         call dgetf2(n, n, jac, n, ipiv, info)
         if (info /= 0) then
            call fatal_error(error, egw_not_converged, "delta = "//format_real(prob%delta) &
               & //" (in units of sigma): singular Jacobian at the solution")
            return
         end if
         x(:, 1) = rhs
         call dgetrs('N', n, 1, jac, n, ipiv, x, n, info)
      end if
      rate = sol%dbase + gauss_values(sol%mesh, x(:, 1))
      sol%dforce = 2.0_dp*pi*sum(sol%mesh%gauss_w*sol%mesh%gauss_r*sol%dpdh*rate)
   end subroutine differentiate

   !> Initial rough deflection. Separated spheres: 0 (the base gap is already close).
   !> Extended models: inside the Hertz radius the gap is w_G itself, and a disc of radius a
   !> under uniform pressure p sags by 2 p a at its centre (E = 1), so w_G ~ w_c with
   !> w_c = 2 a p_G(w_c), flat inside a and falling like the flat-punch field (2/pi)
   !> asin(a/r) outside. From w = 0 Newton needs 7 LUs at delta/sigma = 1e4, from this 3.
   !> Classic GW at delta > 0: the deflection whose gap gives the Hertz pressure through
   !> the law (capped near the edge), so that w ~ w_H: the stiff case starts close to its
   !> solution.
   pure subroutine initial_deflection(prob, sol)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(inout) :: sol
      integer :: i
      real(dp) :: r, h, target, lo, hi, f, dfdh
      real(dp), parameter :: h_cap = 1.5_dp
      allocate (sol%w(mesh_nodes(sol%mesh)))
      sol%w = 0.0_dp
      if (prob%delta <= 0.0_dp) return
      if (prob%extended) then
         ! Bisection for w_c - 2 a p_G(w_c) = 0 (increasing in w_c; p_G(40) underflows).
         lo = 0.0_dp
         hi = 40.0_dp
         do i = 1, 50
            h = 0.5_dp*(lo + hi)
            call law_at(prob, h, f, dfdh)
            if (h < 2.0_dp*prob%a*f) then
               lo = h
            else
               hi = h
            end if
         end do
         where (sol%mesh%node <= prob%a)
            sol%w = h
         elsewhere
            sol%w = h*2.0_dp/pi*asin(prob%a/sol%mesh%node)
         end where
         return
      end if
      do i = 1, size(sol%w)
         r = sol%mesh%node(i)
         target = hertz_pressure(r, prob%delta, 1.0_dp, 1.0_dp)
         h = h_cap
         if (target > 0.0_dp) h = min(h_cap, law_inverse(prob, target))
         sol%w(i) = hertz_gap(r, prob%delta, 1.0_dp) + h - base_gap(prob, r)
      end do
   end subroutine initial_deflection

   !> h with p(h) = target (the scaled law, decreasing) by bisection: a bracket about
   !> [-2, 40] (GW's law underflows at 40), widened until it holds the target.
   pure real(dp) function law_inverse(prob, target) result(h)
      type(scaled_problem), intent(in) :: prob
      real(dp), intent(in) :: target
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
      type(radial_mesh), intent(in) :: mesh
      real(dp), intent(in) :: v(:)
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

   !> Gap, pressure and its derivative at the Gauss points for the current w (the
   !> unloading law at the closest-approach gaps when unloading).
   pure subroutine evaluate(prob, sol)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(inout) :: sol
      real(dp), allocatable :: f(:), dfdh(:)
      sol%gap = sol%base + gauss_values(sol%mesh, sol%w)
      if (allocated(sol%gap_min)) then
         allocate (f(size(sol%gap)), dfdh(size(sol%gap)))
         call unloading_pressure(prob%unload, sol%gap, sol%gap_min, f, dfdh)
         sol%p = prob%scale*f
         sol%dpdh = prob%scale*dfdh
      else
         sol%p = sol%gap       ! (sized as the gap)
         sol%dpdh = sol%gap
         call prob%law%pressure(sol%gap, sol%p, sol%dpdh)
      end if
   end subroutine evaluate

   !> Residual F = w - H p_G(z + w) (at the current evaluate()) and its scaled max norm.
   pure subroutine residual(sol, res, norm)
      type(discrete_solution), intent(in) :: sol
      real(dp), intent(out) :: res(:)
      real(dp), intent(out) :: norm
      res = sol%w - matmul(sol%infl, sol%p)
      norm = maxval(abs(res))/max(1.0_dp, maxval(abs(sol%w)))
   end subroutine residual

   !> Jacobian J = I - infl diag(p') interp.
   pure subroutine jacobian(sol, jac)
      type(discrete_solution), intent(in) :: sol
      real(dp), intent(out) :: jac(:, :)
      integer :: e, q, j, g, col
      jac = 0.0_dp
      do j = 1, size(jac, 1)
         jac(j, j) = 1.0_dp
      end do
      do e = 1, sol%mesh%n_elem
         do q = 1, sol%mesh%n_gauss
            g = (e - 1)*sol%mesh%n_gauss + q
            do j = 0, sol%mesh%degree
               col = node_index(sol%mesh, e, j)
               jac(:, col) = jac(:, col) - sol%infl(:, g)*(sol%dpdh(g)*sol%mesh%interp(j, q))
            end do
         end do
      end do
   end subroutine jacobian

   !> Newton with backtracking (Armijo on |F|_2). Converged when the scaled residual is
   !> below prob%residual_tol: 1e-11 (the rounding floor of H p is ~1e-12 for w ~ 1e6;
   !> looser for unloading, see solve_scaled), or the step is at rounding level with a
   !> residual below 1e-9.
   !> The LU factors are kept once Newton is in its quadratic regime (the last full step
   !> cut |F|_2 at least chord_start-fold): a full step with the old factors (chord step) is
   !> accepted when it cuts |F|_2 at least chord_gain-fold, else the Jacobian is refactored
   !> at the same iterate and the Newton step with line search taken. Near the solution a
   !> chord step contracts like |w - w*|, so the fallback only costs one evaluation, while
   !> the LU (n**3) is most of an iteration's cost on the solver's meshes. Far from the
   !> solution chord steps would cost iterations: max_iter counts both kinds alike.
   !> Unloading solves take no chord steps (see below).
   subroutine newton(prob, sol, max_iter, error)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(inout) :: sol
      integer, intent(in) :: max_iter
      type(egw_error), allocatable, intent(out) :: error
      real(dp), parameter :: chord_gain = 10.0_dp, chord_start = 100.0_dp
      real(dp), allocatable :: jac(:, :), res(:), step(:, :), w0(:), res_try(:)
      integer, allocatable :: ipiv(:)
      integer :: n, it, info, k
      real(dp) :: norm, norm_try, lambda, f2, f2_try
      logical :: factored, have_lu, converged

      n = size(sol%w)
      allocate (jac(n, n), res(n), step(n, 1), ipiv(n), res_try(n), stat=info)
      if (info /= 0) then
         call fatal_error(error, egw_out_of_memory, "the Jacobian of " &
            & //int_str(n)//" nodes could not be allocated")
         return
      end if
      call evaluate(prob, sol)
      call residual(sol, res, norm)
      factored = .false.
      have_lu = .false.
      converged = .false.
      do it = 1, max_iter + 1
         sol%iterations = it - 1
         sol%residual = norm
         converged = norm <= prob%residual_tol
         if (converged .or. it > max_iter) exit
         w0 = sol%w
         f2 = sum(res**2)
         lambda = 1.0_dp
         if (factored) then
            step(:, 1) = -res
            call dgetrs('N', n, 1, jac, n, ipiv, step, n, info)
            sol%w = w0 + step(:, 1)
            call evaluate(prob, sol)
            call residual(sol, res_try, norm_try)
            f2_try = sum(res_try**2)
            factored = f2_try <= f2/chord_gain**2 .and. ieee_is_finite(f2_try)
            if (.not. factored) then
               sol%w = w0
               call evaluate(prob, sol)
            end if
         end if
         if (.not. factored) then
            call jacobian(sol, jac)
            call dgetf2(n, n, jac, n, ipiv, info)
            have_lu = info == 0
            if (.not. have_lu) exit
            factored = .true.
            step(:, 1) = -res
            call dgetrs('N', n, 1, jac, n, ipiv, step, n, info)
            do k = 1, 40
               sol%w = w0 + lambda*step(:, 1)
               call evaluate(prob, sol)
               call residual(sol, res_try, norm_try)
               f2_try = sum(res_try**2)
               if (f2_try <= (1.0_dp - 1.0e-4_dp*lambda)*f2) exit
               lambda = 0.5_dp*lambda
            end do
            ! Factors from far away (damped, or slow) are not worth reusing. Unloading never
            ! reuses them: an evaluation of Z_u costs ~1.5x the loading law's, so on the
            ! solver's meshes the LU costs less than the evaluation a chord step adds, and
            ! the law's kink at d = d_max (dp/dh jumps) slows chord steps to a 20-50-fold
            ! gain each (seen: 5 chord steps from 1e-4 to 1e-11 where Newton takes 2).
            factored = lambda == 1.0_dp .and. f2_try <= f2/chord_start**2 .and. &
               & .not. allocated(prob%closest)
         end if
         res = res_try
         norm = norm_try
         if (maxval(abs(lambda*step(:, 1))) <= 1.0e-14_dp*max(1.0_dp, maxval(abs(sol%w))) &
            & .and. norm <= 1.0e-9_dp) then
            sol%iterations = it
            sol%residual = norm
            converged = .true.
            exit
         end if
      end do
      if (converged) then
         ! Keep the last factors for differentiate.
         if (have_lu) then
            call move_alloc(jac, sol%lu)
            call move_alloc(ipiv, sol%pivots)
         end if
         return
      end if
      sol%iterations = max_iter
      sol%residual = norm
      call fatal_error(error, egw_not_converged, "delta = "//format_real(prob%delta) &
         & //" (in units of sigma): Newton did not converge in "//int_str(max_iter) &
         & //" iterations, residual "//format_real(norm))
   end subroutine newton

   !> Damped fixed point w <- w - omega (w - H p_G(z + w)); omega halves when the residual
   !> grows and recovers slowly while it falls. Converged at a scaled residual of 1e-11.
   !> Where the spectral radius of H |dp/dw| is large (classic GW at small sigma/delta)
   !> omega must become tiny and the iteration runs out of max_iter: not converged.
   subroutine picard(prob, sol, max_iter, error)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(inout) :: sol
      integer, intent(in) :: max_iter
      type(egw_error), allocatable, intent(out) :: error
      real(dp), allocatable :: res(:), w0(:)
      real(dp) :: norm, norm_old, omega
      integer :: it
      allocate (res(size(sol%w)))
      omega = 0.5_dp
      call evaluate(prob, sol)
      call residual(sol, res, norm)
      do it = 1, max_iter + 1
         sol%iterations = it - 1
         sol%residual = norm
         if (norm <= 1.0e-11_dp) return
         if (it > max_iter) exit
         w0 = sol%w
         norm_old = norm
         sol%w = w0 - omega*res
         call evaluate(prob, sol)
         call residual(sol, res, norm)
         if (norm > norm_old) then
            omega = 0.5_dp*omega
         else
            omega = min(1.0_dp, 1.05_dp*omega)
         end if
      end do
      sol%iterations = max_iter
      sol%residual = norm
      call fatal_error(error, egw_not_converged, "delta = "//format_real(prob%delta) &
         & //" (in units of sigma): Picard did not converge in "//int_str(max_iter) &
         & //" iterations, residual "//format_real(norm))
   end subroutine picard

   !> Effective contact radius a* = (3 pi/4) int r p dr / int p dr of the total pressure
   !> (scaled); the Hertz part has int r p_H dr = P_H/(2 pi), int p_H dr = a**2/2.
   pure real(dp) function effective_radius(prob, sol) result(a_eff)
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(in) :: sol
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
      type(scaled_problem), intent(in) :: prob
      type(discrete_solution), intent(in) :: sol
      real(dp), intent(in) :: r
      real(dp) :: row(size(sol%p)), f, dfdh, gap_min(1)
      call influence_row(sol%mesh, r, row)
      if (allocated(prob%closest)) then
         gap_min = closest_gap(prob%closest, [r])
         call unloading_pressure(prob%unload, base_gap(prob, r) + dot_product(row, sol%p), &
            & gap_min(1), f, dfdh)
         p = prob%scale*f
      else
         call law_at(prob, base_gap(prob, r) + dot_product(row, sol%p), p, dfdh)
      end if
      if (prob%extended) p = p + hertz_pressure(r, prob%delta, 1.0_dp, 1.0_dp)
   end function total_pressure

   !> Scaled Hertz force of the smooth part (extended models only).
   pure real(dp) function smooth_force(prob) result(force)
      type(scaled_problem), intent(in) :: prob
      force = 0.0_dp
      if (prob%extended) force = hertz_force(prob%delta, 1.0_dp, 1.0_dp)
   end function smooth_force

   !> Scaled Hertz stiffness of the smooth part (extended models only).
   pure real(dp) function smooth_stiffness(prob) result(stiffness)
      type(scaled_problem), intent(in) :: prob
      stiffness = 0.0_dp
      if (prob%extended) stiffness = hertz_stiffness(prob%delta, 1.0_dp, 1.0_dp)
   end function smooth_stiffness

end module egw_sphere_solver
