!> The first level of the sphere solver's routes (egw_sphere_solver), before its
!> refinement levels (egw_sphere_refine): an unloading's locating solve and kink edges,
!> the cap's edges on loading, classic GW refocused deep in contact, and the
!> continuation in delta of a cold start that failed.
module egw_sphere_first_level
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error
   use egw_halfspace, only: influence_cache
   use egw_sphere_problem, only: solver_options, scaled_problem, discrete_solution, law_inverse, &
      & sums_total
   use egw_sphere_mesh, only: mesh_family, trim_to_unloading_decay, gap_edge, kink_radii, &
      & negligible_at, mesh_geometry, plastic_rim, edge_layer_width, step_for_nodes, coarsen, &
      & focus_beyond, innermost_kink
   use egw_sphere_regime, only: yield_overlap, stall_fallbacks
   use egw_sphere_level, only: solve_with_tail, move_solution
   use egw_sphere_refine, only: relocate_kinks, central_disc
   implicit none
   private

   public :: first_unloading_level, first_cap_level, refocus_classic_gw, continuation

   !> The default route's levels refine the central disc [0, c] with the step (as the
   !> central-disc route does, disc_refined) where the innermost kink c of an unloading
   !> after a capped loading is below this fraction of the Hertz radius
   !> (first_unloading_level; branch mesh13's disc_split, doc/benchmarks.md "Stop 47
   !> (mesh13)", "Stop 49 (rcost15)") ...
   real(dp), parameter :: disc_split = 0.5_dp
   !> ... and only at sigma/delta_y at least this (measured at 1e-2 and 0.0105; at 1e-6
   !> a rough_cap solve came out 1.7e-5 off under an estimate of 3.6e-6)
   real(dp), parameter :: disc_split_sigma = 1.0e-3_dp

contains

   !> The first level of an unloading solve (doc/theory.md §8 "Sphere"): a locating solve
   !> on a coarser mesh places the element edges at the kinks of p(r) (prob%branch) and
   !> trims the mesh to where the unloading pressure has died (trim_to_unloading_decay);
   !> then the first level itself, whose kink edges are relocated (relocate_kinks).
   subroutine first_unloading_level(prob, options, method, mesh, coarse, error, start, cache, &
      & warm)
      !> the scaled problem, its edges and disc set here
      type(scaled_problem), intent(inout) :: prob
      type(solver_options), intent(in) :: options   !< the solver's options
      integer, intent(in) :: method   !< method_newton or method_picard
      !> the route's mesh family, trimmed and grown past the rim
      type(mesh_family), intent(inout) :: mesh
      type(discrete_solution), intent(out) :: coarse   !< the first level
      type(egw_error), allocatable, intent(out) :: error   !< egw_not_converged or the failure met
      type(influence_cache), intent(inout), optional :: cache   !< of the route's levels
      !> start of the locating solve (the cap's guided route; else the initial deflection)
      type(discrete_solution), intent(in), optional :: start
      !> a solution of another solve of the same history: the locating solve's start
      !> where start is absent (if that locating solve fails, it is solved again from
      !> the initial deflection)
      type(discrete_solution), intent(in), optional :: warm
      type(discrete_solution) :: first
      type(scaled_problem) :: locate
      real(dp) :: reach   !< past the plastic rim: the least outer radius of every level
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
      ! Nor, after a capped loading, the layers at a_max, at the rim and inside a (the
      ! first level has them, and relocate_kinks moves its kink edges again; solve_with_tail's
      ! locating): README's E-GW + cap build spent ~70 % less CPU in its locating solves.
      ! After a capped loading deep in the cap the unloading contact ends near the rim of
      ! the history's plastic zone, far outside the Hertz edge (the focus), in a layer as
      ! thin as the loading's there (first_cap_level): there the graded elements are
      ! ~ step (rim - focus) long, and the levels' forces are not yet asymptotic (EP-GW,
      ! sigma = delta_y/100, psi 1, from 18.9 delta_y, delta = 17.65 delta_y, rel_tol 1e-5:
      ! the contact ends within 53.0 .. 53.5 of the rim 53.8, elements 2.6 long there; the
      ! levels agreed to 1.3e-6 while 6.6e-5 off, and a hysteresis table at 1e-4 to 20
      ! delta_y did not build). The rim becomes an element edge with geometric layers on
      ! both sides, of the loading's layer width there (a property of the history: the same
      ! edges on every level).
      ! A fixed mesh (n_radial) gets no layers but reaches past the rim as well, its step
      ! set again for n_radial nodes: the contact can end in an annulus at the rim beyond
      ! a band where the pressure is exactly 0, which the tail check cannot see (its
      ! pressure at the outer radius is 0). E-GW + cap, steel beads (sigma 42 nm, R 0.5 mm,
      ! p_y 3.2 GPa) from 5.51 delta_y: the outer radius 10.7 .. 10.9 sqrt(R sigma) lay
      ! inside the rim 12.08, and from 0.58 to 0.67 delta_max every n_radial from 257 to
      ! 2049 gave the same force up to 2.7e-3 low (estimates ~1e-9), and P(delta) jumped
      ! by 0.33 % at 0.67 delta_max (doc/stability.md).
      ! Every mesh reaches past the rim, also where the rim lies within four layer widths
      ! of the focus (no layers of its own there): the outer radius from the law's decay
      ! can end inside it, and the annulus with it (E-GW + cap, R/sigma = 70711, p_y =
      ! 0.01 E*, from 68.14 sigma = 3.9 delta_y: at 44.3 sigma, rim 8.30, focus 6.66 +
      ! 4 x 0.47, outer 8.17 at rel_tol 1e-6, 8.30 at 1e-8; the force 2.1e-3 low under an
      ! estimate of 2.8e-8, at every n_radial, and a hysteresis table at 1e-3 to 20
      ! delta_y did not build; audit9).
      reach = 0.0_dp
      if (sums_total(prob)) then
         prob%rim = plastic_rim(prob)
         if (prob%rim > 0.0_dp) reach = prob%rim + 4.0_dp*edge_layer_width(prob%rim)
         if (prob%rim > mesh%focus + 4.0_dp*mesh%width .and. options%n_radial == 0) then
            prob%rim_width = edge_layer_width(prob%rim)
         else
            prob%rim = 0.0_dp
         end if
         if (reach > mesh%outer) then
            mesh%outer = reach
            if (options%n_radial > 0) then
               mesh%step = step_for_nodes(prob%extended, mesh%focus, mesh%width, &
                  & mesh%outer, options%n_radial)
               mesh%step_prev = coarsen*mesh%step
            end if
         end if
      end if
      locate = prob
      locate%residual_tol = 1.0e-6_dp
      ! The locating solve from the deflection of the history's last solve (a table's
      ! curve at the neighbouring s): the rough deflection after a capped loading is far
      ! from the initial deflection's (the shift and offset), and Newton took 5.6
      ! iterations from it, 3.3 from a warm start (E-GW + cap, the table of
      ! doc/benchmarks.md "Stop 44"). Only edges and the next start come from this solve.
      if (present(warm) .and. .not. present(start)) then
         call solve_with_tail(locate, options, method, .false., mesh%focus, mesh%width, &
            & 2.0_dp*mesh%step_prev, mesh%outer, first, error, warm, cache=cache, &
            & locating=.true.)
         if (allocated(error)) then
            deallocate (error)
            call solve_with_tail(locate, options, method, .false., mesh%focus, mesh%width, &
               & 2.0_dp*mesh%step_prev, mesh%outer, first, error, cache=cache, &
               & locating=.true.)
         end if
      else
         call solve_with_tail(locate, options, method, .false., mesh%focus, mesh%width, &
            & 2.0_dp*mesh%step_prev, mesh%outer, first, error, start, cache=cache, &
            & locating=.true.)
      end if
      ! (after a capped loading, a locating solve that failed from its start again by
      ! continuation in delta from the history's deflection at delta_max: unloading_descent)
      if (allocated(error) .and. options%n_radial == 0 .and. prob%closest%capped .and. &
         & stall_fallbacks(prob)) then
         deallocate (error)
         call unloading_descent(locate, options, method, mesh, first, error, cache)
      end if
      if (allocated(error)) then
         deallocate (error)
         call solve_with_tail(prob, options, method, mesh%layered, mesh%focus, mesh%width, &
            & mesh%step_prev, mesh%outer, coarse, error, start, cache=cache)
         return
      end if
      ! Edges only where the pressure is not negligible: a kink where r p is below
      ! 1e-4 rel_tol of its peak cannot move the force by rel_tol even if its elements
      ! were wholly wrong, and such edges (seen: r p at 1e-45 of the peak, in the far
      ! tail) cost a level of elements 4 nodes each.
      prob%branch = kink_radii(prob, first, 1.0e-4_dp*options%rel_tol, prob%n_branch)
      if (prob%closest%extended) prob%amax_edge = .not. negligible_at(first, &
         & sqrt(prob%closest%delta), 1.0e-4_dp*options%rel_tol)
      if (options%n_radial == 0) call trim_to_unloading_decay(prob, options, first, mesh)
      if (options%n_radial == 0) prob%disc = central_disc(prob, first)
      ! After a capped loading (sums_total) the innermost kink c can lie well inside the
      ! Hertz radius a the family is graded about: [0, c] is then one graded element on
      ! the first levels (between the fixed edges 0 and c), whose forces agree while both
      ! are off; the bisection check (now halved_levels) found it, and the levels then
      ! refined the whole mesh by
      ! a global step until the graded edges split [0, c] (E-GW + cap, sigma =
      ! delta_y/100 to 6 delta_y at 1e-4: 110 of 1444 checks found the disc off by 1e-7
      ! .. 2.9e-4 at c/a 0.05 .. 0.4, and the levels after them held 300-550 nodes, 47 %
      ! of the build's LU work). Below disc_split a the disc's elements shrink with the
      ! step from the first level on (disc_refined, as on the central-disc route; it
      ! takes the place of central_disc's grading there). Only at sigma/delta_y >=
      ! disc_split_sigma (delta_y/sigma = (pi p_y/2)**2 in these units), where it was
      ! measured: at 1e-6 (rough_cap's "solve_contact_unload near the residual", c =
      ! 0.21 a) the split disc came out 1.7e-5 off under an estimate of 3.6e-6.
      if (sums_total(prob) .and. options%n_radial == 0) then
         if (yield_overlap(prob) <= 1.0_dp/disc_split_sigma) prob%refine_disc = &
            & prob%refine_disc .or. innermost_kink(prob) <= disc_split*prob%a
      end if
      ! (the trimmed mesh still reaches past the rim: the contact can end just inside it)
      mesh%outer = max(mesh%outer, reach)
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
         & mesh%step_prev, mesh%outer, coarse, error, first, cache=cache)
      ! The locating solve (twice the step, no kink edges) places the kinks 3e-4..3e-3
      ! off (psi 10 after delta_max 2: at delta 0 the edges were 2.3e-3 off, an error
      ! of 9e-7 that every level shared, so rel_tol 1e-8 was never reached and the
      ! rel_tol 1e-7 answer was 2e-7 off the reference under an estimate of 5e-8).
      ! Relocated from the first level (kink edges in place, a finer mesh) and that
      ! level solved again until the offset costs less than a tenth of rel_tol.
      if (.not. allocated(error)) call relocate_kinks(prob, options, method, mesh%layered, &
         & mesh%focus, mesh%width, mesh%step_prev, mesh%outer, coarse, error, cache=cache)
   end subroutine first_unloading_level

   !> Unloading after a capped loading, the locating solve (locate, on the coarse mesh
   !> of first_unloading_level) where it failed from its start: continuation in delta
   !> from the history's own deflection at delta_max (the unloading solution there), at
   !> descent_stages overlaps evenly from delta_max down to locate%delta, each solved from
   !> the one before. Newton stalled from the initial and the neighbouring curve's
   !> deflections on every route (E-GW + cap, sigma/delta_y = 1e-4, 71049 sigma after
   !> 116562: residual 7.6e-3, issue 32); from here it converged (at sigma/delta_y = 2e-5
   !> and 1e-5, 0.5 and 0.65 delta_max, the first level stalls after it, unresolved).
   subroutine unloading_descent(locate, options, method, mesh, sol, error, cache)
      type(scaled_problem), intent(in) :: locate
      type(solver_options), intent(in) :: options
      integer, intent(in) :: method
      type(mesh_family), intent(inout) :: mesh
      type(discrete_solution), intent(out) :: sol
      type(egw_error), allocatable, intent(out) :: error
      type(influence_cache), intent(inout), optional :: cache
      integer, parameter :: descent_stages = 8
      type(scaled_problem) :: stage
      type(discrete_solution) :: previous
      integer :: k
      previous%mesh = locate%closest%mesh
      previous%w = locate%closest%w
      stage = locate
      do k = 1, descent_stages
         stage%delta = locate%closest%delta + (locate%delta - locate%closest%delta)* &
            & real(k, dp)/real(descent_stages, dp)
         if (k == descent_stages) stage%delta = locate%delta
         stage%a = sqrt(max(stage%delta, 0.0_dp))
         ! (as scaled(): the extended models' Hertz part only at delta > 0)
         stage%extended = locate%closest%extended .and. stage%delta > 0.0_dp
         call solve_with_tail(stage, options, method, .false., mesh%focus, mesh%width, &
            & 2.0_dp*mesh%step_prev, mesh%outer, sol, error, previous, cache=cache, &
            & locating=.true.)
         if (allocated(error)) return
         previous = sol
      end do
   end subroutine unloading_descent

   !> Loading with the cap (doc/theory.md §12 "Rough spheres with the cap"): the cap edges
   !> of the first level's solution (coarse) become element edges (prob%branch: where
   !> p_s + p reaches p_y, dp/dr jumps), the first level is solved again with them and
   !> they are relocated on it (relocate_kinks), as for the unloading's kinks.
   subroutine first_cap_level(prob, options, method, mesh, coarse, error, cache)
      type(scaled_problem), intent(inout) :: prob   !< the scaled problem, the cap edges set here
      type(solver_options), intent(in) :: options   !< the solver's options
      integer, intent(in) :: method   !< method_newton or method_picard
      !> the route's mesh family, refocused at an outer cap edge
      type(mesh_family), intent(inout) :: mesh
      !> the first level, solved again with the cap edges
      type(discrete_solution), intent(inout) :: coarse
      type(egw_error), allocatable, intent(out) :: error   !< egw_not_converged or the failure met
      type(influence_cache), intent(inout), optional :: cache   !< of the route's levels
      type(discrete_solution) :: first
      real(dp) :: edge
      prob%branch = kink_radii(prob, coarse, 1.0e-4_dp*options%rel_tol, prob%n_branch)
      if (size(prob%branch) == 0) then
         deallocate (prob%branch)
         return
      end if
      ! Beyond ~2 delta_y the capped contact outgrows the Hertz radius and ends, just past
      ! its outermost cap edge, in a layer as thin as the Hertz edge's (the smooth cap's
      ! pressure jumps from p_y to 0 there, trap iv): the family is refocused there (the
      ! Hertz edge, where the base gap has its onset, stays an element edge).
      edge = maxval(prob%branch)
      call focus_beyond(mesh, edge)
      call move_solution(coarse, first)
      call solve_with_tail(prob, options, method, mesh%layered, mesh%focus, mesh%width, &
         & mesh%step_prev, mesh%outer, coarse, error, first, cache=cache)
      if (.not. allocated(error)) call relocate_kinks(prob, options, method, mesh%layered, &
         & mesh%focus, mesh%width, mesh%step_prev, mesh%outer, coarse, error, cache=cache)
   end subroutine first_cap_level

   !> Classic GW deep in contact (doc/theory.md §5 "Useful facts", §7): with
   !> p_H(0) >> C sigma**1.5 (centre gap below -3 sigma) the solution ends in a thin layer
   !> around d = 0 whose place is only known from a solution (near, not at, the Hertz
   !> edge): the mesh family is refocused there and the first level (coarse) solved again.
   subroutine refocus_classic_gw(prob, options, method, mesh, coarse, error, cache)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(solver_options), intent(in) :: options   !< the solver's options
      integer, intent(in) :: method   !< method_newton or method_picard
      !> the route's mesh family, refocused at the gap's zero
      type(mesh_family), intent(inout) :: mesh
      !> the first level, solved again on the refocused family
      type(discrete_solution), intent(inout) :: coarse
      type(egw_error), allocatable, intent(out) :: error   !< egw_not_converged or the failure met
      type(influence_cache), intent(inout), optional :: cache   !< of the route's levels
      type(discrete_solution) :: first
      if (.not. law_inverse(prob, 2.0_dp*prob%a/pi) < -3.0_dp) return
      call gap_edge(coarse, mesh%focus, mesh%width)
      mesh%layered = .true.
      ! The first level again, on the refocused mesh family: two levels of different
      ! families can agree by accident (seen: both 1.3e-7 off at mu = 0.1,
      ! delta/sigma = 100, their difference 1.5e-8), so Richardson needs one family.
      call move_solution(coarse, first)
      call solve_with_tail(prob, options, method, mesh%layered, mesh%focus, mesh%width, &
         & mesh%step_prev, mesh%outer, coarse, error, first, cache=cache)
   end subroutine refocus_classic_gw

   !> Continuation in delta: solve at delta/sigma = 1 from a cold start, then at delta
   !> values growing by at most a factor 4 up to prob%delta, each started from the previous
   !> solution stretched by the Hertz similarity (r ~ sqrt(delta), w ~ delta).
   subroutine continuation(prob, options, method, focus, width, step, outer, sol, error, cache)
      type(scaled_problem), intent(in) :: prob   !< the scaled problem
      type(solver_options), intent(in) :: options   !< the solver's options
      integer, intent(in) :: method   !< method_newton or method_picard
      real(dp), intent(in) :: focus, width, step   !< the family's focus, layer width and step
      real(dp), intent(inout) :: outer   !< the problem's outer radius, its last stage's on return
      type(discrete_solution), intent(out) :: sol   !< the solution at prob%delta
      type(egw_error), allocatable, intent(out) :: error   !< egw_not_converged or the failure met
      type(influence_cache), intent(inout), optional :: cache   !< of the route's levels
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
               & stage_width, step, stage_outer, sol, error, cache=cache)
         else
            ratio = stage%delta/delta_prev
            previous%mesh%edge = previous%mesh%edge*sqrt(ratio)
            previous%w = previous%w*ratio
            call solve_with_tail(stage, options, method, stage%extended, stage_focus, &
               & stage_width, step, stage_outer, sol, error, previous, cache=cache)
         end if
         if (allocated(error)) return
         previous = sol
         delta_prev = stage%delta
      end do
      outer = stage_outer
   end subroutine continuation

end module egw_sphere_first_level
