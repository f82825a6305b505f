!> Tests of the rough sphere with the flow-pressure cap (doc/theory.md §12 "Rough spheres
!> with the cap"; egw_flow_cap in the scaled problem of egw_sphere_problem): it is the
!> cap-free model where the pressure stays below p_y, and the smooth cap model
!> (test/data/cap_reference.csv, tools/reference/cap_reference.py) as sigma -> 0.
module test_rough_cap
   use testdrive, only: new_unittest, unittest_type, error_type, check
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error
   use egw_flat_law, only: gw_flat_law
   use egw_halfspace, only: gauss_legendre
   use egw, only: contact_params, model_gw, model_egw, model_epgw, solver_options, &
      & solve_result, solve_contact, solve_contact_law, loading_history, load_history, &
      & solve_unload, restitution, solve_contact_unload
   use egw_status, only: egw_not_converged
   use egw_table, only: force_table, build_table, table_eval
   use egw_sphere_mesh, only: disc_refined, disc_graded, edge_layer_width, with_history_edges, &
      & split_kept
   use egw_flow_cap, only: flow_cap, not_evaluated
   use egw_law_pieces, only: law_pieces, zmc_law_pieces
   use egw_sphere_problem, only: lagrange_undershoot, deflection_degree
   use egw_rough_profile, only: contact_profile_unload
   use egw_cap_sphere, only: cap_options, cap_history, cap_result, cap_load, u_plastic
   use egw_cap_profile, only: cap_unload_profile
   use data_rows, only: read_data_rows, row_length
   implicit none
   private
   public :: collect_rough_cap

   !> The pair of the sigma -> 0 checks: R = E* = 1, p_y = 0.01 (delta_y = (pi p_y/2)**2).
   real(dp), parameter :: py = 0.01_dp

contains

   subroutine collect_rough_cap(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("p_y above every pressure: the cap-free loading", test_no_cap_load), &
         & new_unittest("p_y above every pressure: the cap-free unloading", &
         & test_no_cap_unload), &
         & new_unittest("sigma -> 0: loading reduces to the smooth cap", test_smooth_limit), &
         & new_unittest("sigma -> 0: unloading reduces to the smooth cap", &
         & test_smooth_limit_unload), &
         & new_unittest("sigma/delta_y = 1e-6: loading converges to the smooth cap", &
         & test_small_sigma), &
         & new_unittest("sigma/delta_y = 1e-6: unloading at 0.95, 0.9 delta_max", &
         & test_small_sigma_unload), &
         & new_unittest("sigma/delta_y = 1e-7, 1e-8: loading by the asymptotic route", &
         & test_tiny_sigma), &
         & new_unittest("E-GW + cap at sigma/delta_y = 1e-10, 1e-8: converged solves checked", &
         & test_tiny_sigma_checked), &
         & new_unittest("sigma/delta_y = 1e-7: the route's contact radius is a*", &
         & test_route_contact_radius), &
         & new_unittest("sigma/delta_y = 1e-6: unloading at 0.99 delta_max", &
         & test_small_sigma_unload_top), &
         & new_unittest("EP-GW + cap unloading from 6 delta_y at rel_tol 1e-6", &
         & test_deep_unloading), &
         & new_unittest("EP-GW + cap unloading from 9.375 delta_y at rel_tol 1e-5", &
         & test_deep_unloading_loose), &
         & new_unittest("EP-GW + cap unloading from 18.9 delta_y: the contact's end", &
         & test_rim_unloading), &
         & new_unittest("impact: dissipated = closed integral of P d delta", test_energy), &
         & new_unittest("impact: e below the cap-free EP-GW's, and first yield", &
         & test_first_yield), &
         & new_unittest("E-GW + cap loading: smooth in delta (fourth differences)", &
         & test_smooth_in_delta), &
         & new_unittest("E-GW + cap loading: stiffness = quotient of 1e-8 forces", &
         & test_stiffness), &
         & new_unittest("E-GW + cap loading: stiffness within rel_tol at the nine points", &
         & test_stiffness_points), &
         & new_unittest("E-GW + cap loading: force within rel_tol at the Hertz edge's points", &
         & test_force_points), &
         & new_unittest("load_history(stiffness=.false.): the same history, bit for bit", &
         & test_history_stiffness), &
         & new_unittest("solve_contact(stiffness=.false.): force and peak pressure, bit for bit", &
         & test_contact_stiffness), &
         & new_unittest("E-GW + cap loading table at 1e-5 against solves", &
         & test_loading_table), &
         & new_unittest("EP-GW + cap loading table at 1e-4: quarter points", &
         & test_loading_table_quarters), &
         & new_unittest("E-GW + cap steel beads: unloading near the residual overlap", &
         & test_residual_overlap_beads), &
         & new_unittest("E-GW + cap steel beads, 10 nm: the central-disc route", &
         & test_residual_disc_beads), &
         & new_unittest("the two routes' meshes: disc_refined, with_history_edges", &
         & test_route_meshes), &
         & new_unittest("split_kept: the levels' kept elements halved, none coarsened", &
         & test_split_kept), &
         & new_unittest("E-GW + cap steel beads, 42 nm: mid-unloading reaches the rim", &
         & test_mid_unloading_rim), &
         & new_unittest("E-GW + cap, rim within the focus's layers: the mesh reaches it", &
         & test_rim_near_focus), &
         & new_unittest("E-GW + cap, sigma = delta_y/10: a rim within the focus's grading", &
         & test_rim_in_grading), &
         & new_unittest("sigma/delta_y = 1e-8, 1e-10: histories by the small-sigma route", &
         & test_tiny_sigma_history), &
         & new_unittest("sigma/delta_y = 1e-8: restitution at 3 v_y by the small-sigma route", &
         & test_tiny_sigma_restitution), &
         & new_unittest("sigma/delta_y = 1e-6: unloading near the residual overlap", &
         & test_small_sigma_residual), &
         & new_unittest("sigma/delta_y = 1e-10 from 10 delta_y: near the residual overlap", &
         & test_tiny_sigma_residual), &
         & new_unittest("sigma/delta_y = 1e-6: solve_contact_unload near the residual", &
         & test_small_sigma_contact_unload), &
         & new_unittest("sigma/delta_y = 1e-6: a converged unloading solve checked", &
         & test_small_sigma_unload_checked), &
         & new_unittest("sigma/delta_y = 1e-7, 1e-6: restitution at 3 v_y", &
         & test_small_sigma_restitution), &
         & new_unittest("sigma/delta_y = 1e-6: restitution at rel_tol 1e-5", &
         & test_small_sigma_restitution_tight), &
         & new_unittest("sigma/delta_y = 1e-7: a loading beyond the route's reach", &
         & test_route_floor), &
         & new_unittest("sigma/delta_y = 1e-7: solve_contact_unload near the residual", &
         & test_tiny_sigma_contact_unload), &
         & new_unittest("sigma/delta_y = 1e-6: 0.1446, 0.1443 delta_max against the shift", &
         & test_shift_references), &
         & new_unittest("sigma/delta_y = 1e-8: profile_unload after a history by the route", &
         & test_route_profile), &
         & new_unittest("sigma/delta_y = 2e-5 at 0.1442 delta_max: answers within their bounds", &
         & test_contact_in_one_element), &
         & new_unittest("est_rel_err below the force floor", test_floor_estimate), &
         & new_unittest("far beyond first yield: refused naming delta", test_far_beyond_yield), &
         & new_unittest("plastic_shifts: law(h_max + u_pl) = p_y, offsets, GW and ZMC", &
         & test_plastic_shifts), &
         & new_unittest("plastic_shifts: deep points unevaluated, law_max and reuse", &
         & test_plastic_shifts_deep), &
         & new_unittest("flow_cap prepare: the root of law = p_y once", test_cap_prepare), &
         & new_unittest("E-GW + cap, sigma = delta_y/100: unloading near the edge at 1e-6", &
         & test_edge_unload), &
         & new_unittest("EP-GW + cap below first yield: the cap-free unloading, bit for bit", &
         & test_cap_never_acts), &
         & new_unittest("cap_never_acts: the element bound", test_lagrange_undershoot), &
         & new_unittest("sigma/delta_y = 2e-6: unloading near the residual overlap, " &
         & //"within its estimate at rel_tol 1e-6", test_gap_sigma_residual), &
         & new_unittest("sigma/delta_y = 1.2e-6, 1.5e-6: loading from 2, 3 delta_y", &
         & test_gap_sigma_loading), &
         & new_unittest("E-GW + cap histories at 1e-7: unloading force continuous in delta_max", &
         & test_history_continuous), &
         & new_unittest("E-GW + cap, 2.1221 sigma after 212.7 sigma: rel_tol 1e-8 reached", &
         & test_unload_tight_tol), &
         & new_unittest("E-GW + cap, 2.1221 sigma after 209 sigma: within rel_tol 1e-8", &
         & test_unload_first_refinement), &
         & new_unittest("E-GW + cap near the bottom after 209, 212.7 sigma: stiffness", &
         & test_unload_bottom_stiffness), &
         & new_unittest("GW + cap, 128.0475 sigma after 399.04 sigma: the knee at 1e-5", &
         & test_gw_knee_unload) &
         & ]
   end subroutine collect_rough_cap

   !> README's rough + cap pair in sigma units (R = 810569.469138702, E* = sigma = 1, mu 4,
   !> p_y = 0.01: delta_y = 200 sigma), histories at rel_tol 1e-7 (a 1e-4 table's curve
   !> solves as local19's prototype had them), unloading at 1e-5 to delta = 2.1221 sigma
   !> (1.1e-3 of the turning point's force): the force is a smooth function of delta_max,
   !> so its second difference over delta_max = 209.3170, 209.3175, 209.3180 sigma is
   !> ~(5e-4)**2 f'' (3e-10 of the force by 1e-9/1e-8 solves); bound: the
   !> unloading solve's rel_tol, 1e-5 of the force. Before stop 56 the history's mesh
   !> switched between 209.3175 and 209.3180 (a cap edge moved onto an element edge or
   !> inserted, with_kink_edges' tenth of an element) and the force jumped by 1.3e-4 of
   !> itself (doc/benchmarks.md "Stop 56: kink22").
   subroutine test_history_continuous(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: p
      type(loading_history) :: hist
      type(solve_result) :: peak, res
      type(egw_error), allocatable :: err
      real(dp) :: u(3), second
      integer :: j
      p = contact_params(model=model_egw, radius=810569.469138702_dp, modulus=1.0_dp, &
         & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
      do j = 1, 3
         call load_history(p, solver_options(rel_tol=1.0e-7_dp, n_threads=1), &
            & 209.3170_dp + 5.0e-4_dp*(j - 1), hist, peak, err, stiffness=.false.)
         if (allocated(err)) then
            call check(error, .false., "load_history: "//err%message)
            return
         end if
         hist%options%rel_tol = 1.0e-5_dp
         call solve_unload(hist, 2.1221_dp, res, err)
         if (allocated(err)) then
            call check(error, .false., "solve_unload: "//err%message)
            return
         end if
         u(j) = res%force
      end do
      second = abs(u(1) - 2.0_dp*u(2) + u(3))/u(2)
      call check(error, second <= 1.0e-5_dp, "second difference in delta_max of the "// &
         & "unloading force / force above 1e-5")
   end subroutine test_history_continuous

   !> README's E-GW + cap pair in sigma units (R = 810569.469138702, E* = sigma = 1, mu 4,
   !> p_y = 0.01: delta_y = 200 sigma), solve_contact_unload at 2.1221 sigma after
   !> 212.7 sigma at rel_tol 1e-8 (the floor kink 4e-6 inside the Hertz radius a): before,
   !> egw_not_converged (the finest mesh's estimate 5.13e-9 > rel_tol/2: the Gauss sum of
   !> p_s's sqrt(a - r) edge in the element ending at that kink, 4.7e-9 of the force;
   !> doc/benchmarks.md "Stop 61: acc27"). Reference: this solve at rel_tol 1e-10
   !> (estimate 3.1e-12; the same history, at 1e-10), corroborated by main 87a8984's
   !> finest level (step 0.01, 972 elements) with its Gauss sum of p_s replaced by the
   !> closed form: 8.4e-12 apart. Bound rel_tol (measured 7.8e-10, estimate 2.5e-9). The
   !> history's own error is shared by both solves and not tested here.
   subroutine test_unload_tight_tol(error)
      type(error_type), allocatable, intent(out) :: error
      call check_tight_unload(error, 2.1221_dp, 212.7_dp, 3431.4860803496281_dp)
   end subroutine test_unload_tight_tol

   !> README's E-GW + cap pair as test_unload_tight_tol, 2.1221 sigma after 209 sigma at
   !> rel_tol 1e-8: before, the first refinement level (step 0.275) was accepted against
   !> the locating level (0.413) with an estimate of 3.8e-9 while 1.32e-8 off (its halved
   !> kept elements stood for the confirming level rel_tol < 1e-6 asks for;
   !> doc/benchmarks.md "Stop 62: acc28"). Reference: this solve at rel_tol 1e-10
   !> (estimate 4.2e-12, the same history at 1e-10), corroborated by the fixed meshes of
   !> 257, 513, 1025, 2049 nodes (n_radial: one level, none of the levels' acceptance),
   !> which converge to it: the 2049-node force is 3.5e-13 from it, their extrapolation
   !> (differences 3.8e-7, 7.8e-8, 2.9e-8 of the force unit, ratio 2.7) 4.5e-12
   !> (tools/bench/acc28_unload_reference.f90). Bound rel_tol, ~2000 times the
   !> reference's error (measured 4.9e-10, estimate 2.3e-10; before 1.32e-8).
   subroutine test_unload_first_refinement(error)
      type(error_type), allocatable, intent(out) :: error
      call check_tight_unload(error, 2.1221_dp, 209.0_dp, 4246.8545221924160_dp)
   end subroutine test_unload_first_refinement

   !> README's E-GW + cap pair as test_unload_tight_tol: the implicit stiffness of the
   !> unloading solves at rel_tol 1e-8 near the bottom, where the floor's kink sits near
   !> the Hertz radius (1 and 2.1221 sigma after 209 sigma, 2.1221 after 212.7 sigma).
   !> Before, -1.0e-6, -3.2e-6 and +6.4e-6 off (the sliver between the floor's kink and
   !> its element edge, 2.5e-6 wide at 209/1, and the Gauss sums of -d(p_s)/d(delta)'s
   !> 1/sqrt(a - r) edge on the floored elements ending at a; egw_sphere_iteration's
   !> floor_stiffness, doc/benchmarks.md "Stop 63: stiffb29"); now 4.3e-8, 1.1e-7,
   !> 3.7e-7. Reference: the difference quotient of rel_tol 1e-10 forces (the same
   !> history at 1e-10), central with h = 0.01 and 0.02 sigma, extrapolated (4 D(h) -
   !> D(2h))/3 (tools/bench/acc28_unload_stiffness.f90 E-GW 1e-8 209 212.7, main 51be045;
   !> the forces are this branch's bit for bit), its error ~1e-8 (truncation h**4,
   !> rounding 1e-10 P/(h S)); the solves at rel_tol 1e-10 come within 6e-9, 3e-9, 3.4e-8
   !> of it. Bound 5e-7: the derivative of a rel_tol 1e-8 mesh converges like
   !> rel_tol**(1/2) at 212.7/2.1221 (3.7e-7, 1.2e-7, 3.4e-8 at 1e-8, 1e-9, 1e-10), where
   !> a kink 3.9e-6 inside a ends an element 1500 times longer.
   subroutine test_unload_bottom_stiffness(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: delta(3) = [1.0_dp, 2.1221_dp, 2.1221_dp], &
         & delta_max(3) = [209.0_dp, 209.0_dp, 212.7_dp], &
         & quotient(3) = [2021.13462570751_dp, 2863.83317859118_dp, 2620.38247663553_dp]
      type(contact_params) :: p
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      integer :: i
      p = contact_params(model=model_egw, radius=810569.469138702_dp, modulus=1.0_dp, &
         & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
      do i = 1, 3
         call solve_contact_unload(p, solver_options(rel_tol=1.0e-8_dp, n_threads=1), &
            & delta(i), delta_max(i), res, err)
         if (allocated(err)) then
            call check(error, .false., "solve_contact_unload: "//err%message)
            return
         end if
         call check(error, abs(res%stiffness - quotient(i)) <= 5.0e-7_dp*quotient(i), &
            & "delta = "//str(delta(i))//" after "//str(delta_max(i))//": K = " &
            & //str(res%stiffness)//", quotient "//str(quotient(i)))
         if (allocated(error)) return
      end do
   end subroutine test_unload_bottom_stiffness

   !> README's GW + cap scene in sigma units (R = 405284.734569351 effective, E* = sigma =
   !> 1, mu 4, p_y = 0.01: delta_y = 100 sigma), the history at rel_tol 1e-6 and the
   !> unloading solve at 1e-5 (a 1e-4 table's curve solves) at 128.0475 sigma after
   !> 399.0373536808676 sigma, just below the unloading curve's knee, where the force is
   !> 1.2e-3 of the turning point's. Before, the first refinement level (13 elements) was
   !> accepted against the locating level with an estimate of 1.3e-6 while 3.6e-4 of the
   !> force off (egw_sphere_refine: classic GW after a capped loading now confirms it;
   !> doc/benchmarks.md "Stop 68: gw34"). Reference: history and solve at rel_tol 1e-9
   !> (estimate 8.9e-13; a 1e-6 history with 1e-6 solves comes within 1.8e-7, "Stop 67:
   !> front33"). Bound rel_tol of the force, the 1e-6 history's own error (1.8e-7)
   !> included (measured 1.8e-7).
   subroutine test_gw_knee_unload(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: delta = 128.0475_dp, delta_max = 399.0373536808676_dp, &
         & ref = 6915.4330454023730_dp, tol = 1.0e-5_dp
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      p = contact_params(model=model_gw, radius=405284.734569351_dp, modulus=1.0_dp, &
         & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
      call load_history(p, solver_options(rel_tol=1.0e-6_dp, n_threads=1), delta_max, h, &
         & res, err)
      if (allocated(err)) then
         call check(error, .false., "load_history: "//err%message)
         return
      end if
      h%options%rel_tol = tol
      call solve_unload(h, delta, res, err)
      if (allocated(err)) then
         call check(error, .false., "solve_unload: "//err%message)
         return
      end if
      call check(error, abs(res%force - ref) <= tol*ref, "P = "//str(res%force)// &
         & ", reference "//str(ref)//": off by "//str(abs(res%force - ref)/ref)// &
         & " of it (estimate "//str(res%est_rel_err)//")")
   end subroutine test_gw_knee_unload

   !> README's E-GW + cap pair in sigma units (as test_unload_tight_tol): the unloading
   !> solve at delta after delta_max at rel_tol 1e-8 within rel_tol of ref.
   subroutine check_tight_unload(error, delta, delta_max, ref)
      type(error_type), allocatable, intent(out) :: error
      real(dp), intent(in) :: delta, delta_max, ref
      type(contact_params) :: p
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      p = contact_params(model=model_egw, radius=810569.469138702_dp, modulus=1.0_dp, &
         & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
      call solve_contact_unload(p, solver_options(rel_tol=1.0e-8_dp, n_threads=1), &
         & delta, delta_max, res, err)
      if (allocated(err)) then
         call check(error, .false., "solve_contact_unload: "//err%message)
         return
      end if
      call check(error, abs(res%force - ref) <= 1.0e-8_dp*ref, "P = "//str(res%force) &
         & //", reference "//str(ref))
   end subroutine check_tight_unload

   !> Polished steel beads (R = 0.5 mm, E* = 210 GPa/(2 (1 - 0.29**2)), sigma = 14.1 nm,
   !> mu 4, p_y = 1.6 GPa: sigma = 0.0587 delta_y), E-GW + cap unloading from 1.2971
   !> delta_y at 0.017419 delta_y, just above the residual overlap, at rel_tol 1e-6:
   !> before, egw_not_converged (the estimate 9.6e-7 on the finest mesh: the Hertz edge's
   !> sqrt in the floored total pressure, converging like h**1.5). Reference: this
   !> solve at rel_tol 2e-8 with 8 layers inside the Hertz edge (commit 1877970; estimate
   !> 4.7e-9), corroborated by the levels before the fix (steps 0.0183, 0.0103)
   !> extrapolated for h**1.5: 1e-8 apart. Within rel_tol (measured 6.9e-8, estimate
   !> 2.8e-7).
   subroutine test_residual_overlap_beads(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: radius = 0.5e-3_dp, p_y = 1.6e9_dp
      real(dp), parameter :: ref = 8.982700861461e-7_dp   ! N
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      ! (the overlaps in units of this pair's first yield, egw_first_yield)
      real(dp), parameter :: delta_y = 2.403074547673163e-7_dp
      real(dp) :: modulus
      modulus = 210.0e9_dp/(2.0_dp*(1.0_dp - 0.29_dp**2))
      p = contact_params(model=model_egw, radius=radius, modulus=modulus, sigma=1.41e-8_dp, &
         & mu=4.0_dp, flow_pressure=p_y)
      ! (the history at 1e-4 rel_tol, as solve_contact_unload loads it)
      call load_history(p, solver_options(rel_tol=1.0e-10_dp), 1.2970813472435374_dp* &
         & delta_y, h, res, err)
      call check(error, .not. allocated(err), "history at 1.297 delta_y failed")
      if (allocated(error)) return
      h%options%rel_tol = 1.0e-6_dp
      call solve_unload(h, 0.01741909132221112_dp*delta_y, res, err)
      if (allocated(err)) then
         call check(error, .false., "unloading at 0.0174 delta_y: "//err%message)
         return
      end if
      call check(error, abs(res%force - ref) <= 1.0e-6_dp*ref, "P = "//str(res%force) &
         & //" N, reference "//str(ref))
   end subroutine test_residual_overlap_beads

   !> Steel beads of example cap-bead-grid (R* = 0.5 mm, E = 210 GPa, nu 0.3, pair sigma
   !> 10 nm = 0.0105 delta_y, mu 4, p_y = 3.2 GPa), E-GW + cap unloading from 5.5141
   !> delta_y (the turning point at 3 m/s) at 2.1972 delta_y, where the force has fallen
   !> to 3.4e-6 of P(delta_max) and lives on a central disc of radius ~0.03 a, at rel_tol
   !> 1e-6: before, egw_not_converged (the finest mesh's estimate 6.0e-7; the disc's
   !> 1-5 elements kept between levels). Reference: this solve at rel_tol 1e-8 (the
   !> central-disc route, estimate 3.8e-9), corroborated by the default route's level at
   !> step 0.156 with its disc split into 2, 4, 8, 16 equal elements, extrapolated for
   !> their order 3 (errors 4.9e-7, 7.4e-8, 9.6e-9 apart): 8e-8 apart. Within rel_tol
   !> (measured 1.2e-7, estimate 2.8e-7).
   subroutine test_residual_disc_beads(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: ref = 1.02877858952745e-4_dp   ! N
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      p = contact_params(model=model_egw, radius=0.5e-3_dp, modulus=210.0e9_dp/(2.0_dp* &
         & (1.0_dp - 0.3_dp**2)), sigma=1.0e-8_dp, mu=4.0_dp, flow_pressure=3.2e9_dp)
      ! (the history at 1e-4 rel_tol, as solve_contact_unload loads it)
      call load_history(p, solver_options(rel_tol=1.0e-10_dp), 5.2323e-6_dp, h, res, err)
      call check(error, .not. allocated(err), "history at 5.51 delta_y failed")
      if (allocated(error)) return
      h%options%rel_tol = 1.0e-6_dp
      call solve_unload(h, 2.084897e-6_dp, res, err)
      if (allocated(err)) then
         call check(error, .false., "unloading at 2.20 delta_y: "//err%message)
         return
      end if
      call check(error, abs(res%force - ref) <= 1.0e-6_dp*ref, "P = "//str(res%force) &
         & //" N, reference "//str(ref))
   end subroutine test_residual_disc_beads

   !> The meshes of the central-disc and history-edges routes (egw_sphere_mesh), on
   !> hand-made edges: disc_refined splits each element inside the innermost positive
   !> radius c into equal parts no longer than c step/2 and leaves the others;
   !> with_history_edges keeps every edge of its own, adds the radii inside (0, outer)
   !> that are not within 1e-9 of an edge, increasing. Exact (equal parts of exact
   !> decimal edges to 1e-15; the edges themselves copied). disc_graded replaces the
   !> edges inside c by edges graded about c: increasing from 0, c an edge, the edges
   !> beyond c kept, the graded ones their closed form c - w sinh(xi_c (n - i)/n),
   !> xi_c = asinh(c/w), n = ceiling(2 xi_c/step) (to 1e-13 relative: rounding), and
   !> half the step gives twice the elements (to 10 %: the ceiling).
   subroutine test_route_meshes(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: edge(0:4) = [0.0_dp, 0.5_dp, 1.0_dp, 3.0_dp, 6.0_dp]
      real(dp), allocatable :: out(:)
      real(dp) :: w, xi
      integer :: i, n
      ! c = 1 (the 0 and the negative radius ignored), step 0.5: at most 0.25 long, so
      ! [0, 0.5] and [0.5, 1] in 2 parts each; [1, 3] and [3, 6] untouched
      out = disc_refined(edge, [2.0_dp, 0.0_dp, 1.0_dp, -1.0_dp], 0.5_dp)
      call check(error, size(out) == 7, "disc_refined: "//str(real(size(out), dp))//" edges")
      if (allocated(error)) return
      call check(error, all(abs(out - [0.0_dp, 0.25_dp, 0.5_dp, 0.75_dp, 1.0_dp, 3.0_dp, &
         & 6.0_dp]) <= 1.0e-15_dp), "disc_refined: the edges")
      if (allocated(error)) return
      ! 0.5 + 1e-12 and 3 - 1e-10 within 1e-9 of an edge (dropped), 0 and 7 outside
      out = with_history_edges(edge, [0.0_dp, 0.25_dp, 0.5_dp + 1.0e-12_dp, 2.0_dp, &
         & 3.0_dp - 1.0e-10_dp, 5.0_dp, 7.0_dp])
      call check(error, size(out) == 8, "with_history_edges: "//str(real(size(out), dp)) &
         & //" edges")
      if (allocated(error)) return
      call check(error, all(out == [0.0_dp, 0.25_dp, 0.5_dp, 1.0_dp, 2.0_dp, 3.0_dp, &
         & 5.0_dp, 6.0_dp]), "with_history_edges: the edges")
      if (allocated(error)) return
      call check(error, all([(out(i) < out(i + 1), i=1, size(out) - 1)]), &
         & "with_history_edges: not increasing")
      if (allocated(error)) return
      ! c = 2 in [1, 3]: 0.5 and 1 replaced, 3 and 6 kept
      out = disc_graded(edge, 2.0_dp, 0.5_dp)
      w = edge_layer_width(2.0_dp)
      xi = asinh(2.0_dp/w)
      n = ceiling(2.0_dp*xi/0.5_dp)
      call check(error, size(out) == n + 3, "disc_graded: "//str(real(size(out), dp)) &
         & //" edges, expected "//str(real(n + 3, dp)))
      if (allocated(error)) return
      call check(error, out(1) == 0.0_dp .and. all(abs(out(2:n + 1) - [(2.0_dp - w*sinh(xi &
         & *real(n - i, dp)/real(n, dp)), i=1, n)]) <= 1.0e-13_dp*2.0_dp) .and. &
         & all(out(n + 2:) == [3.0_dp, 6.0_dp]), "disc_graded: the edges")
      if (allocated(error)) return
      call check(error, all([(out(i) < out(i + 1), i=1, size(out) - 1)]), &
         & "disc_graded: not increasing")
      if (allocated(error)) return
      i = size(disc_graded(edge, 2.0_dp, 0.25_dp)) - 3
      call check(error, abs(real(i, dp)/real(n, dp) - 2.0_dp) <= 0.2_dp, &
         & "disc_graded: elements at half the step "//str(real(i, dp)))
   end subroutine test_route_meshes

   !> The unloading levels after a capped loading (egw_sphere_regime's halved_levels):
   !> split_kept halves each element of a level that is an element of the level before,
   !> cuts one that spans several of them (both its ends theirs) at their edges and halves
   !> those, and leaves the rest; with 3 parts, thirds. On hand-made edges against the list
   !> worked out by hand: exact (midpoints of dyadic edges, the others copied; thirds to
   !> 1e-15, their rounding); a mesh none of whose elements
   !> has both ends among the level before's edges comes back bit for bit, and a mesh
   !> against itself has every element halved.
   subroutine test_split_kept(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: level(0:5) = [0.0_dp, 1.0_dp, 2.0_dp, 3.0_dp, 5.0_dp, 8.0_dp]
      real(dp), parameter :: before(0:6) = [0.0_dp, 1.0_dp, 2.5_dp, 3.0_dp, 4.0_dp, 5.0_dp, &
         & 6.0_dp]
      real(dp), allocatable :: out(:)
      integer :: i
      ! [0, 1] kept: halved; [1, 2], [2, 3] and [5, 8] end off the level before's edges:
      ! as they are; [3, 5] spans [3, 4] and [4, 5]: cut at 4, each half halved
      out = split_kept(level, before, 2)
      call check(error, size(out) == 10, "split_kept: "//str(real(size(out), dp))//" edges")
      if (allocated(error)) return
      call check(error, all(out == [0.0_dp, 0.5_dp, 1.0_dp, 2.0_dp, 3.0_dp, 3.5_dp, 4.0_dp, &
         & 4.5_dp, 5.0_dp, 8.0_dp]), "split_kept: the edges")
      if (allocated(error)) return
      ! no element has both ends among the level before's edges: unchanged
      out = split_kept(level, [0.0_dp, 0.75_dp, 1.5_dp, 2.5_dp, 3.0_dp, 4.0_dp, 7.0_dp], 2)
      call check(error, size(out) == size(level), "split_kept: a mesh sharing no element")
      if (allocated(error)) return
      call check(error, all(out == level), "split_kept: a mesh sharing no element, edges")
      if (allocated(error)) return
      ! the same mesh: every element halved
      out = split_kept(before, before, 2)
      call check(error, size(out) == 2*size(before) - 1, "split_kept: the same mesh, " &
         & //str(real(size(out), dp))//" edges")
      if (allocated(error)) return
      call check(error, all(out(1::2) == before) .and. all([(out(2*i) == 0.5_dp*(before(i - &
         & 1) + before(i)), i=1, size(before) - 1)]), "split_kept: the same mesh, edges")
      if (allocated(error)) return
      ! 3 parts (a level 3 times finer): [0, 1] in thirds, [3, 5] cut at 4, each in thirds
      out = split_kept(level, before, 3)
      call check(error, size(out) == 13, "split_kept in thirds: "//str(real(size(out), dp)) &
         & //" edges")
      if (allocated(error)) return
      call check(error, all(abs(out - [0.0_dp, 1.0_dp/3, 2.0_dp/3, 1.0_dp, 2.0_dp, 3.0_dp, &
         & 10.0_dp/3, 11.0_dp/3, 4.0_dp, 13.0_dp/3, 14.0_dp/3, 5.0_dp, 8.0_dp]) <= 1.0e-15_dp &
         & *max(1.0_dp, out)), "split_kept in thirds: the edges")
   end subroutine test_split_kept

   !> Steel beads of example cap-bead-grid (R* = 0.5 mm, E = 210 GPa, nu 0.3, pair sigma
   !> 42 nm = 0.0443 delta_y, mu 4, p_y = 3.2 GPa), E-GW + cap unloading from the turning
   !> point of the 3 m/s impact (5.2304e-6 m = 5.51 delta_y) at 0.66 delta_max. There the
   !> contact ends in an annulus at the rim of the history's plastic zone (scaled radius
   !> 12.08), beyond a band of zero pressure, outside the outer radius (10.90) that a
   !> fixed mesh (n_radial) had: every n_radial from 257 to 2049 gave 458.95984 (scaled),
   !> 2.7e-3 low under estimates of ~1e-9, and P(delta) jumped by 0.33 % at 0.67
   !> delta_max (the history-edges route of stop 42's steel6 branch too: its e 0.7633088
   !> against 0.763344). Reference (scaled force P/(E* sqrt(R) sigma**1.5), the history at
   !> rel_tol 1e-9): fixed meshes reaching past the rim, n_radial 1025, 1537, 2049:
   !> 460.1819248, 460.1819250, 460.1819253; the default route at rel_tol 1e-8
   !> 460.1819251 (example steel-mid-unload, doc/stability.md). Bounds: the default route
   !> at rel_tol 1e-6 its tolerance (measured 1.4e-8); n_radial 513 1e-7 (measured 1.3e-8;
   !> the reference is good to ~1e-9; the failure was 2.7e-3).
   subroutine test_mid_unloading_rim(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: ref_scaled = 460.1819252_dp, delta_max = 5.2304422987839924e-6_dp
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: ref
      p = contact_params(model=model_egw, radius=0.5e-3_dp, modulus=210.0e9_dp/(2.0_dp* &
         & (1.0_dp - 0.3_dp**2)), sigma=4.2e-8_dp, mu=4.0_dp, flow_pressure=3.2e9_dp)
      ref = ref_scaled*p%modulus*sqrt(p%radius)*p%sigma**1.5_dp
      call load_history(p, solver_options(rel_tol=1.0e-9_dp, n_threads=1), delta_max, h, &
         & res, err)
      call check(error, .not. allocated(err), "history at 5.51 delta_y failed")
      if (allocated(error)) return
      h%options%rel_tol = 1.0e-6_dp
      call solve_unload(h, 0.66_dp*delta_max, res, err)
      if (allocated(err)) then
         call check(error, .false., "unloading at 0.66 delta_max: "//err%message)
         return
      end if
      call check(error, abs(res%force - ref) <= 1.0e-6_dp*ref, "rel_tol 1e-6: P = " &
         & //str(res%force)//" N, reference "//str(ref))
      if (allocated(error)) return
      h%options%n_radial = 513
      call solve_unload(h, 0.66_dp*delta_max, res, err)
      if (allocated(err)) then
         call check(error, .false., "unloading at 0.66 delta_max, n_radial 513: " &
            & //err%message)
         return
      end if
      call check(error, abs(res%force - ref) <= 1.0e-7_dp*ref, "n_radial 513: P = " &
         & //str(res%force)//" N, reference "//str(ref))
   end subroutine test_mid_unloading_rim

   !> E-GW + cap (mu 4, R/sigma = 70710.68, p_y = 0.01 E*: delta_y = 17.45 sigma; the wall
   !> contact of a 1 mm glass bead with sigma = 1.41e-8 m in LAMMPS), unloading from 68.136
   !> sigma (3.9 delta_y) through solve_contact_unload (egw_solve_unload) at rel_tol 1e-6.
   !> The history's plastic rim (scaled r 8.30) lies within four layer widths of the Hertz
   !> edge at 44.3 sigma (6.66 + 4 x 0.47), so it got no layers, and the outer radius
   !> from the law's decay (8.17) ended inside it: the contact's annulus at the rim was
   !> cut off, 2.1e-3 and 2.3e-3 low at 44.3 and 44.65 sigma under estimates of 2.8e-8 and
   !> 1.0e-8, at every n_radial (257 .. 2049), only from rel_tol 1e-7 on right; the
   !> hysteresis table at 1e-3 to 20 delta_y did not build (audit9). References (the
   !> force itself, E* = sigma = 1): rel_tol 1e-9 solves before the fix (whose outer
   !> radius reached the rim there), 63150.51553907, 64598.41961722 (at 1e-7 63150.51518,
   !> 64598.41960: good to ~1e-8). Bound: rel_tol 1e-6, the solves' own tolerance, also
   !> for a fixed mesh of 1025 nodes.
   subroutine test_rim_near_focus(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: delta_max = 68.13586736546107_dp, deltas(2) = [44.3_dp, &
         & 44.65_dp], refs(2) = [63150.51553907_dp, 64598.41961722_dp]
      type(contact_params) :: p
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      integer :: i, k
      integer, parameter :: n_radial(2) = [0, 1025]
      p = contact_params(model=model_egw, radius=70710.67811865475_dp, modulus=1.0_dp, &
         & sigma=1.0_dp, mu=4.0_dp, flow_pressure=py)
      do k = 1, size(n_radial)
         do i = 1, size(deltas)
            call solve_contact_unload(p, solver_options(rel_tol=1.0e-6_dp, n_threads=1, &
               & n_radial=n_radial(k)), deltas(i), delta_max, res, err)
            if (allocated(err)) then
               call check(error, .false., "unloading at "//str(deltas(i))//": " &
                  & //err%message)
               return
            end if
            call check(error, abs(res%force - refs(i)) <= 1.0e-6_dp*refs(i), "n_radial " &
               & //str(real(n_radial(k), dp))//", delta "//str(deltas(i))//": P = " &
               & //str(res%force)//", reference "//str(refs(i)))
            if (allocated(error)) return
         end do
      end do
   end subroutine test_rim_near_focus

   !> E-GW + cap, R = 4.05e5 sigma, p_y = 0.01 E*, sigma = delta_y/10 (the table of
   !> doc/benchmarks.md "Stop 43", its sigma = delta_y/10 row, to 20 delta_y at 1e-3,
   !> which did not build: its curve at delta_max = 454.13 = 4.54 delta_y). The history's
   !> plastic rim (scaled radius 6.93) lies within the Hertz edge's grading (5.21 + 4 x
   !> 0.51), so it had no layers, and the outer radius (6.74) stopped inside it; from
   !> delta = m - 182.5893544822179 on (a jump within 2e-11 of it) every level missed the
   !> contact's annulus at the rim: at rel_tol 1e-4 the force was 6.3e-3 low (1.6e-3 of
   !> P(m)) under an estimate of 9.2e-6. Reference: rel_tol 1e-9 solves of a rel_tol 1e-9
   !> history on the code before the fix (whose tight solves were right there; the 1e-8
   !> ones agree to 4e-9, and the fixed code's 1e-9 ones to 3e-11). Bound: the solves'
   !> rel_tol 1e-4 (measured 6e-8 with the fix).
   subroutine test_rim_in_grading(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: m = 454.1306018557710_dp
      real(dp), parameter :: offset(3) = [182.5893544822179_dp, 182.59_dp, 182.6_dp]
      real(dp), parameter :: ref(3) = [1.7244559632596434e6_dp, 1.7244406157879801e6_dp, &
         & 1.7242028680744793e6_dp]
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      integer :: i
      p = contact_params(model=model_egw, radius=405284.734569351_dp, modulus=1.0_dp, &
         & sigma=10.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
      call load_history(p, solver_options(rel_tol=1.0e-4_dp, n_threads=1), m, h, res, err)
      call check(error, .not. allocated(err), "history at 4.54 delta_y failed")
      if (allocated(error)) return
      do i = 1, size(offset)
         call solve_unload(h, m - offset(i), res, err)
         if (allocated(err)) then
            call check(error, .false., "unloading at m - "//str(offset(i))//": " &
               & //err%message)
            return
         end if
         call check(error, abs(res%force - ref(i)) <= 1.0e-4_dp*ref(i), "m - " &
            & //str(offset(i))//": P = "//str(res%force)//", reference "//str(ref(i)))
         if (allocated(error)) return
      end do
   end subroutine test_rim_in_grading

   !> Histories of E-GW with the cap at tiny sigma (rel_tol 1e-6) against the smooth cap
   !> (test/data/cap_reference.csv, the sigma -> 0 limit). sigma/delta_y = 1e-8 from
   !> 2 delta_y: the loading does not converge, and load_history failed before; now the
   !> small-sigma route loads it and answers its unloading solves. 1e-10 from 10 delta_y:
   !> the loading converges 1.28e-5 above the reference (estimate 1.5e-8), which
   !> solve_contact's check caught but load_history kept (and unloaded from); now checked
   !> as well (the route's history). Bounds as test_tiny_sigma: the rough layer lowers the
   !> force by at most 0.3 (sigma/delta_y)**(2/3) (1.4e-6 at 1e-8; measured 5.2e-7 on
   !> loading, 4.5e-7 at 0.95 delta_max), within [ref (1 - 0.3 r**(2/3)), ref] widened by
   !> rel_tol/2 and the reference's own error (its unloading rows at 10 delta_y: 1.8e-7)
   !> at 1e-10; and below the smooth cap's residual overlap (0.5245 delta_max from
   !> 10 delta_y) the force is 0.
   subroutine test_tiny_sigma_history(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: ratios(2) = [1.0e-8_dp, 1.0e-10_dp], x(2) = [2.0_dp, 10.0_dp]
      real(dp), parameter :: ref_load(2) = [2.720383972669_dp, 20.91895411785_dp], &
         & ref_unload(2) = [2.507170193550_dp, 18.12329882330_dp]   ! P/P_y, 0.95 delta_max
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, got, slack, low
      integer :: i
      call yield_units(delta_y, force_y)
      do i = 1, size(ratios)
         p = egw_cap(ratios(i))
         call load_history(p, solver_options(rel_tol=1.0e-6_dp), x(i)*delta_y, h, res, err)
         if (allocated(err)) then
            call check(error, .false., "sigma/delta_y = "//str(ratios(i))//": history: " &
               & //err%message)
            return
         end if
         low = 0.3_dp*ratios(i)**(2.0_dp/3.0_dp)
         slack = 5.0e-7_dp
         got = res%force/force_y
         call check(error, got <= ref_load(i)*(1.0_dp + slack) .and. got >= ref_load(i)* &
            & (1.0_dp - low - slack), "sigma/delta_y = "//str(ratios(i))//", loading: " &
            & //"P/P_y = "//str(got)//", smooth cap "//str(ref_load(i)))
         if (allocated(error)) return
         call solve_unload(h, 0.95_dp*x(i)*delta_y, res, err)
         if (allocated(err)) then
            call check(error, .false., "sigma/delta_y = "//str(ratios(i))//", 0.95 " &
               & //"delta_max: "//err%message)
            return
         end if
         got = res%force/force_y
         slack = 5.0e-7_dp + 2.0e-7_dp
         call check(error, got <= ref_unload(i)*(1.0_dp + slack) .and. got >= &
            & ref_unload(i)*(1.0_dp - low - slack), "sigma/delta_y = "//str(ratios(i)) &
            & //", 0.95 delta_max: P/P_y = "//str(got)//", smooth cap "//str(ref_unload(i)))
         if (allocated(error)) return
      end do
      call solve_unload(h, 0.5_dp*10.0_dp*delta_y, res, err)
      if (allocated(err)) then
         call check(error, .false., "sigma/delta_y = 1e-10, 0.5 delta_max: "//err%message)
         return
      end if
      call check(error, res%force == 0.0_dp, "sigma/delta_y = 1e-10, 0.5 delta_max: " &
         & //"P = "//str(res%force)//", below the residual overlap")
   end subroutine test_tiny_sigma_history

   !> restitution of E-GW + cap at sigma/delta_y = 1e-8 (mu 4, 3 v_y, rel_tol 1e-4), whose
   !> loading and unloading solves are the small-sigma route's (doc/theory.md section 12),
   !> against the smooth cap's e (restitution at sigma = 0: cap_restitution, an independent
   !> closed solve on the cap model, within 3.4e-6 of test/data/cap_reference.csv). Before,
   !> every unloading solve reloaded the route's two wide histories (minutes per impact, or
   !> egw_not_converged). Tolerance 1e-4: restitution's own (rel_tol, the work integrals'
   !> tolerance on e), plus the smooth cap's 3.4e-6 and the rough layer's effect on the
   !> forces, at most 0.3 (sigma/delta_y)**(2/3) = 1.4e-6 (test_tiny_sigma_history).
   subroutine test_tiny_sigma_restitution(error)
      type(error_type), allocatable, intent(out) :: error
      call check_restitution_near_cap([1.0e-8_dp], 1.0e-4_dp, error)
   end subroutine test_tiny_sigma_restitution

   !> E-GW + cap at sigma/delta_y = 1e-6 (mu 4) from 2 delta_y (history at rel_tol 1e-7),
   !> unloading at rel_tol 1e-5 just above the residual overlap (0.14407 delta_max), where
   !> the force is 4e-5 .. 1e-2 of P(delta_max): at 0.145, 0.16 and 0.18 delta_max (on main
   !> egw_not_converged: the discrete solves stall, the route's estimates 3.9e-4, 1.4e-5,
   !> 5.3e-6 against 5e-6). Reference: the smooth cap's force (tools/reference/
   !> cap_near_residual.py --m 40, an independent solve; its Richardson errors 3.7e-7,
   !> 3.8e-8, 2.7e-8 relative) times 1 + the rough layer's correction from the rough
   !> model's own discrete solves at sigma/delta_y = 5e-5, 1e-4, 2e-4, 5e-4 less
   !> egw_cap_limit's smooth cap (rel_tol 1e-8, not the route; example small-sigma-residual,
   !> stop 53; fitted in sigma**(2/3) to fourth order: -4.6e-3, -3.5e-4, -1.8e-4 relative,
   !> the fits of third and fourth order apart by 2.7e-7, 2.7e-8, 5.8e-9 of the force;
   !> until stop 53 -4.601825e-3, -3.541831e-4, -1.816596e-4 from the solves of stop 44
   !> and a 64-ring smooth cap). Tolerance: rel_tol plus those (1e-5 + 3e-6). Measured
   !> against the old values: 1.4e-6, 7.6e-7, 1.2e-6 off (estimates 2.1e-6, 7.6e-7,
   !> 8.4e-7), 12 s.
   subroutine test_small_sigma_residual(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: fractions(3) = [0.145_dp, 0.16_dp, 0.18_dp]
      ! P/P_y of the smooth cap and the rough correction relative to it
      real(dp), parameter :: smooth(3) = [1.162796266339e-4_dp, 8.226717030518e-3_dp, &
         & 2.776761469579e-2_dp]
      real(dp), parameter :: correction(3) = [-4.603500e-3_dp, -3.539259e-4_dp, -1.813434e-4_dp]
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, ref
      integer :: i
      call yield_units(delta_y, force_y)
      p = egw_cap(1.0e-6_dp)
      call load_history(p, solver_options(rel_tol=1.0e-7_dp), 2.0_dp*delta_y, h, res, err)
      if (allocated(err)) then
         call check(error, .false., "history from 2 delta_y: "//err%message)
         return
      end if
      h%options%rel_tol = 1.0e-5_dp
      do i = 1, size(fractions)
         call solve_unload(h, fractions(i)*2.0_dp*delta_y, res, err)
         if (allocated(err)) then
            call check(error, .false., "unloading at "//str(fractions(i))//" delta_max: " &
               & //err%message)
            return
         end if
         ref = smooth(i)*(1.0_dp + correction(i))
         call check(error, abs(res%force/force_y - ref) <= 1.3e-5_dp*ref, "unloading at " &
            & //str(fractions(i))//" delta_max: P/P_y = "//str(res%force/force_y) &
            & //", reference "//str(ref))
         if (allocated(error)) return
         call check(error, res%est_rel_err <= 0.5e-5_dp, "estimate "//str(res%est_rel_err))
         if (allocated(error)) return
      end do
   end subroutine test_small_sigma_residual

   !> E-GW + cap at sigma/delta_y = 2e-6 (mu 4) from 2 delta_y (history at rel_tol 1e-7),
   !> unloading near the residual overlap (0.14407 delta_max). At rel_tol 1e-5 at 0.145,
   !> 0.15, 0.16, 0.18 and 0.2 delta_max (on 5d99b29 egw_not_converged at every one,
   !> Newton's residual 8e-4 .. 1.3e-3 on the first level: the stall fallbacks apply only
   !> above 2e-6 and the small-sigma route only at 1e-6 and below; since stop 52 the route
   !> answers). At rel_tol 1e-6 at 0.16, 0.18, 0.2: each answer within rel_tol and within
   !> its own estimate (+ spread), or refused (557b1ba's route answered 7.8e-7, 7.1e-7,
   !> 6.5e-7 off under estimates of 4.1e-7, 3.4e-7, 3.6e-7, its smooth cap 1.1e-6 off:
   !> fails here; now 1.3e-7, 0.8e-7 off under
   !> 4.4e-7, 4.3e-7 at 0.18, 0.2, and 0.16 refused, estimate 5.2e-7; doc/stability.md
   !> "Stop 53 (small19)"). Reference as test_small_sigma_residual's: the smooth cap
   !> (tools/reference/cap_near_residual.py --m 40; its Richardson errors 3.7e-7, 7.3e-8,
   !> 3.8e-8, 2.7e-8, 2.4e-8 relative) times 1 + the rough layer's correction at 2e-6
   !> fitted from the rough model's own discrete solves at sigma/delta_y = 5e-5, 1e-4, 2e-4,
   !> 5e-4 less egw_cap_limit's smooth cap (rel_tol 1e-8; example small-sigma-residual --
   !> 2e-6; not the route): -7.3e-3 .. -2.0e-4 relative, the fits of third and fourth
   !> order 3.8e-7, 1.1e-7, 4.0e-8, 8.4e-9, 5.7e-9 apart. spread: the sum of those two
   !> uncertainties. Tolerance rel_tol + spread (rel_tol 1e-5: measured 7.1e-6, 1.6e-6,
   !> 1.6e-6, 1.2e-6, 1.3e-6 off against stop 52's reference, estimates 1.7e-6, 8.5e-7,
   !> 1.2e-6, 1.1e-6, 5.9e-7), ~20 s CPU. The discrete solves with the stall fallbacks let
   !> down to 2e-6 (tried in stop 52, not kept) were 4.7e-7 .. 5.8e-7 from stop 52's
   !> references at rel_tol 1e-5: two independent answers.
   subroutine test_gap_sigma_residual(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: fractions(5) = [0.145_dp, 0.15_dp, 0.16_dp, 0.18_dp, 0.2_dp]
      ! P/P_y of the smooth cap and the rough correction relative to it
      real(dp), parameter :: smooth(5) = [1.162796266246e-4_dp, 1.871674134534e-3_dp, &
         & 8.226717030492e-3_dp, 2.776761469578e-2_dp, 5.373404469003e-2_dp]
      real(dp), parameter :: correction(5) = [-7.294156e-3_dp, -1.323236e-3_dp, &
         & -5.612505e-4_dp, -2.876139e-4_dp, -2.034764e-4_dp]
      real(dp), parameter :: spread(5) = [7.6e-7_dp, 1.8e-7_dp, 7.8e-8_dp, &
         & 3.6e-8_dp, 3.0e-8_dp]
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, ref, off
      integer :: i
      call yield_units(delta_y, force_y)
      p = egw_cap(2.0e-6_dp)
      call load_history(p, solver_options(rel_tol=1.0e-7_dp), 2.0_dp*delta_y, h, res, err)
      if (allocated(err)) then
         call check(error, .false., "history from 2 delta_y: "//err%message)
         return
      end if
      h%options%rel_tol = 1.0e-5_dp
      do i = 1, size(fractions)
         call solve_unload(h, fractions(i)*2.0_dp*delta_y, res, err)
         if (allocated(err)) then
            call check(error, .false., "unloading at "//str(fractions(i))//" delta_max: " &
               & //err%message)
            return
         end if
         ref = smooth(i)*(1.0_dp + correction(i))
         call check(error, abs(res%force/force_y - ref) <= (1.0e-5_dp + spread(i))*ref, &
            & "unloading at "//str(fractions(i))//" delta_max: P/P_y = " &
            & //str(res%force/force_y)//", reference "//str(ref))
         if (allocated(error)) return
      end do
      h%options%rel_tol = 1.0e-6_dp
      do i = 3, size(fractions)
         call solve_unload(h, fractions(i)*2.0_dp*delta_y, res, err)
         if (allocated(err)) then
            ! (a refusal is honest; the two farthest points must answer)
            call check(error, i < 4 .and. err%stat == egw_not_converged, "rel_tol 1e-6 at " &
               & //str(fractions(i))//" delta_max: "//err%message)
            if (allocated(error)) return
            deallocate (err)
            cycle
         end if
         ref = smooth(i)*(1.0_dp + correction(i))
         off = abs(res%force/force_y/ref - 1.0_dp)
         call check(error, off <= 1.0e-6_dp + spread(i) .and. off <= res%est_rel_err + &
            & spread(i), "rel_tol 1e-6 at "//str(fractions(i))//" delta_max: "//str(off) &
            & //" off the reference, estimate "//str(res%est_rel_err))
         if (allocated(error)) return
      end do
   end subroutine test_gap_sigma_residual

   !> E-GW + cap (mu 4) between the small-sigma route's old reach (sigma/delta_y <= 1e-6)
   !> and the stall fallbacks (> 2e-6), where neither applied: loading at rel_tol 1e-6 at
   !> 1.2e-6 and 1.5e-6 from 2 and 3 delta_y (on main egw_not_converged, Newton's
   !> residual 2e-3 .. 1.2e-2; now the route answers). Reference: the smooth cap's loading (test_small_sigma's values,
   !> tools/reference/cap_reference.py) and the rough layer's law: (P/P_cap - 1)/
   !> (sigma/delta_y)**(2/3) = -0.110 at 2 delta_y and -0.146 .. -0.147 at 3 delta_y in the
   !> discrete solves at 2e-6 .. 5e-6 (rel_tol 1e-6, doc/stability.md "Stop 52 (small18)"),
   !> e_ref here. Tolerance: 1e-6 (rel_tol) + 0.01 (sigma/delta_y)**(2/3) (the law's
   !> spread, 1.3e-6 at 1.5e-6); measured 0.8e-7 .. 4.1e-7 off. A solve that stalled at
   !> Hertz + cap (e = 0) would be 1.5e-5 .. 2e-5 off.
   subroutine test_gap_sigma_loading(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: ratios(2) = [1.2e-6_dp, 1.5e-6_dp]
      real(dp), parameter :: x(2) = [2.0_dp, 3.0_dp]
      real(dp), parameter :: smooth(2) = [2.720383972669_dp, 4.696156337776_dp]
      real(dp), parameter :: law(2) = [-0.110_dp, -0.1465_dp]
      type(contact_params) :: p
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, s, ref
      integer :: i, j
      call yield_units(delta_y, force_y)
      do j = 1, size(ratios)
         p = egw_cap(ratios(j))
         s = ratios(j)**(2.0_dp/3.0_dp)
         do i = 1, size(x)
            call solve_contact(p, solver_options(rel_tol=1.0e-6_dp), x(i)*delta_y, res, err)
            if (allocated(err)) then
               call check(error, .false., "sigma/delta_y = "//str(ratios(j))// &
                  & ", delta/delta_y = "//str(x(i))//": "//err%message)
               return
            end if
            ref = smooth(i)*(1.0_dp + law(i)*s)
            call check(error, abs(res%force/force_y - ref) <= (1.0e-6_dp + 0.01_dp*s)*ref, &
               & "sigma/delta_y = "//str(ratios(j))//", delta/delta_y = "//str(x(i)) &
               & //": P/P_y = "//str(res%force/force_y)//", reference "//str(ref))
            if (allocated(error)) return
         end do
      end do
   end subroutine test_gap_sigma_loading

   !> E-GW + cap at sigma/delta_y = 1e-10 (mu 4) from 10 delta_y (history at rel_tol
   !> 1e-7), unloading at rel_tol 1e-6 at 0.53 delta_max, 0.0055 delta_max above the
   !> residual overlap (on main egw_not_converged: the route's solves at 1e-5 and 2e-5
   !> delta_y fail there, so neither pair answered). Reference as
   !> test_small_sigma_residual's: the smooth cap (cap_near_residual.py, 1.8e-8 relative)
   !> and the rough correction from sigma/delta_y = 1e-4 .. 1e-3 (-4.0e-7 relative, the
   !> fits apart by 4e-15 of the force). Tolerance: the answer's own estimate plus 3e-8,
   !> the reference's uncertainty (1.8e-8; the route's smooth cap, egw_cap_limit, is
   !> 2.4e-8 from it). Stop 44 measured this 4.6e-7 off under an estimate of 1.0e-7 (the
   !> wide pair 1e-4/2e-4, per-call histories); on 5d14490 (the route's wide histories
   !> and egw_cap_limit) 1.93e-8 off, estimate 1.27e-8 (AVX2 path; baseline 1.86e-8,
   !> 1.24e-8; doc/stability.md "Stop 54 (doubt20)"): the old tolerance, rel_tol + 1e-7,
   !> let an answer 50x its estimate pass.
   subroutine test_tiny_sigma_residual(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: smooth = 3.103690750064e-2_dp, correction = -4.003284e-7_dp
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, ref
      call yield_units(delta_y, force_y)
      p = egw_cap(1.0e-10_dp)
      call load_history(p, solver_options(rel_tol=1.0e-7_dp), 10.0_dp*delta_y, h, res, err)
      if (allocated(err)) then
         call check(error, .false., "history from 10 delta_y: "//err%message)
         return
      end if
      h%options%rel_tol = 1.0e-6_dp
      call solve_unload(h, 5.3_dp*delta_y, res, err)
      if (allocated(err)) then
         call check(error, .false., "unloading at 0.53 delta_max: "//err%message)
         return
      end if
      ref = smooth*(1.0_dp + correction)
      call check(error, res%est_rel_err <= 0.5e-6_dp .and. abs(res%force/force_y - ref) <= &
         & (res%est_rel_err + 3.0e-8_dp)*ref, "P/P_y = "//str(res%force/force_y)// &
         & ", reference "//str(ref)//", estimate "//str(res%est_rel_err))
   end subroutine test_tiny_sigma_residual

   !> solve_contact_unload (C egw_solve_unload) of E-GW + cap at sigma/delta_y = 1e-6 (mu 4)
   !> from 2 delta_y at 0.15 delta_max, rel_tol 1e-5: its history at 1e-4 rel_tol (1e-9)
   !> does not converge, and on main the fallback history at rel_tol gave 8.9e-5 off under
   !> an estimate of 4.8e-7 (audit8); now the history 10 times looser (1e-8) answers.
   !> Reference as test_small_sigma_residual's: the smooth cap (cap_near_residual.py
   !> --m 20, 1.8716741e-3 P_y, Richardson error ~1e-7 relative) times the rough correction
   !> 1 - 8.346386e-4 (example small-sigma-residual, from direct solves at 5e-5 .. 1e-3
   !> delta_y). Tolerance rel_tol + 3e-6 (the reference's uncertainty, as there).
   subroutine test_small_sigma_contact_unload(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: smooth = 1.8716741e-3_dp, correction = -8.346386e-4_dp
      type(contact_params) :: p
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, ref
      call yield_units(delta_y, force_y)
      p = egw_cap(1.0e-6_dp)
      call solve_contact_unload(p, solver_options(rel_tol=1.0e-5_dp), 0.3_dp*delta_y, &
         & 2.0_dp*delta_y, res, err)
      if (allocated(err)) then
         call check(error, .false., "unloading at 0.15 delta_max: "//err%message)
         return
      end if
      ref = smooth*(1.0_dp + correction)
      call check(error, abs(res%force/force_y - ref) <= 1.3e-5_dp*ref, "P/P_y = " &
         & //str(res%force/force_y)//", reference "//str(ref)//", estimate " &
         & //str(res%est_rel_err))
      if (allocated(error)) return
      ! 0.145 delta_max, 0.0019 delta_y above the residual overlap, from the same history
      ! (kept per thread): within its estimate plus the reference's uncertainty (2.5e-6,
      ! test_small_sigma_residual's reference, fits of third and fourth order apart).
      ! With the route's wide histories at 1e-8 (before wide_history_floor) 8.8e-6 off
      ! under an estimate of 4.1e-6; measured now 1.4e-6 off, estimate 2.1e-6.
      call solve_contact_unload(p, solver_options(rel_tol=1.0e-5_dp), 0.29_dp*delta_y, &
         & 2.0_dp*delta_y, res, err)
      if (allocated(err)) then
         call check(error, .false., "unloading at 0.145 delta_max: "//err%message)
         return
      end if
      ref = 1.162796266339e-4_dp*(1.0_dp - 4.601825e-3_dp)
      call check(error, res%est_rel_err <= 0.5e-5_dp .and. abs(res%force/force_y - ref) <= &
         & res%est_rel_err*res%force/force_y + 2.5e-6_dp*ref, "0.145 delta_max: P/P_y = " &
         & //str(res%force/force_y)//", reference "//str(ref)//", estimate " &
         & //str(res%est_rel_err))
   end subroutine test_small_sigma_contact_unload

   !> E-GW + cap at sigma/delta_y = 1e-6 (mu 4) from 2 delta_y (history at rel_tol 1e-7, as
   !> test_small_sigma_residual), unloading at 0.15 delta_max at rel_tol 2e-5: the discrete
   !> solve converges (0.01 s) and on main answered 1.870099e-3 P_y, 6.9e-6 below the
   !> reference under an estimate of 1.3e-6 (doc/stability.md "Stop 48 (sigma14)", "Stop
   !> 49 (resid15)"); now checked against the small-sigma route (unload_check_limit), which
   !> answers. Reference test_small_sigma_contact_unload's (the smooth cap,
   !> cap_near_residual.py, times the rough correction from direct solves at 5e-5 .. 1e-3
   !> delta_y; sigma14's shift reference agrees within 2e-7). Tolerance: the answer's
   !> estimate plus the reference's uncertainty 3e-6 (as there). Measured 1.0e-6 off,
   !> estimate 1.4e-6.
   subroutine test_small_sigma_unload_checked(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: smooth = 1.8716741e-3_dp, correction = -8.346386e-4_dp
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, ref
      call yield_units(delta_y, force_y)
      p = egw_cap(1.0e-6_dp)
      call load_history(p, solver_options(rel_tol=1.0e-7_dp), 2.0_dp*delta_y, h, res, err)
      if (allocated(err)) then
         call check(error, .false., "history from 2 delta_y: "//err%message)
         return
      end if
      h%options%rel_tol = 2.0e-5_dp
      call solve_unload(h, 0.3_dp*delta_y, res, err)
      if (allocated(err)) then
         call check(error, .false., "unloading at 0.15 delta_max: "//err%message)
         return
      end if
      ref = smooth*(1.0_dp + correction)
      call check(error, res%est_rel_err <= 1.0e-5_dp .and. abs(res%force/force_y - ref) <= &
         & res%est_rel_err*res%force/force_y + 3.0e-6_dp*ref, "P/P_y = " &
         & //str(res%force/force_y)//", reference "//str(ref)//", estimate " &
         & //str(res%est_rel_err))
   end subroutine test_small_sigma_unload_checked

   !> restitution of E-GW + cap at sigma/delta_y = 1e-7 and 1e-6 (mu 4, 3 v_y, rel_tol
   !> 1e-4), as test_tiny_sigma_restitution at 1e-8: on main egw_not_converged (an
   !> unloading solve near 0.2 delta_max, near the residual overlap: the route's
   !> estimates 6.2e-5, 1.4e-4 against 5e-5). Against the smooth cap's e (cap_restitution):
   !> tolerance 1e-4 (restitution's) + 3.4e-6 (the smooth cap's) + 0.3 (sigma/delta_y)**(2/3)
   !> (the rough layer's effect on the forces, 3e-5 at 1e-6: test_tiny_sigma's bound; measured
   !> on e: 1.6e-6, -9.7e-6).
   subroutine test_small_sigma_restitution(error)
      type(error_type), allocatable, intent(out) :: error
      call check_restitution_near_cap([1.0e-7_dp, 1.0e-6_dp], 1.0e-4_dp, error)
   end subroutine test_small_sigma_restitution

   !> As test_small_sigma_restitution at 1e-6, rel_tol 1e-5: before, egw_not_converged
   !> (the unloading solve at 0.197 delta_m, force 1.5e-2 of P(delta_m): the route's
   !> estimate 1.6e-5 against 5e-6, where its absolute error adds ~1e-9 of W_load to the
   !> work integral). Now restitution's solves take half the work density as the route's
   !> force floor (impact.f90, unload_force_floor: e within (rel_tol/4)(1 + 0.5/e**2)).
   !> Tolerance as there with rel_tol 1e-5 (4.3e-5; measured 8.3e-6 below the smooth cap).
   subroutine test_small_sigma_restitution_tight(error)
      type(error_type), allocatable, intent(out) :: error
      call check_restitution_near_cap([1.0e-6_dp], 1.0e-5_dp, error)
   end subroutine test_small_sigma_restitution_tight

   !> E-GW + cap at sigma/delta_y = 1e-7 (mu 4) loaded to 2 delta_y at rel_tol 1e-8: the
   !> discrete solve stalls and the small-sigma route's estimate is ~6.4e-8 at every
   !> rel_tol (the next order in sigma, not the solves' tolerance), so the answer is a
   !> refusal (egw_not_converged). It now comes from the route's probe at 1e-7
   !> (route_floor), its message naming the lower bound; before, from the route's four
   !> wide solves at 1e-8 (8 s; at 1e-9 24 s). (At rel_tol 1e-6, above the probe, the
   !> route answers as before: test_tiny_sigma.)
   subroutine test_route_floor(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: p
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y
      call yield_units(delta_y, force_y)
      p = egw_cap(1.0e-7_dp)
      call solve_contact(p, solver_options(rel_tol=1.0e-8_dp), 2.0_dp*delta_y, res, err)
      call check(error, allocated(err), "rel_tol 1e-8: answered, P = "//str(res%force))
      if (allocated(error)) return
      call check(error, err%stat == egw_not_converged .and. index(err%message, &
         & "lower bound") > 0, "rel_tol 1e-8: "//err%message)
   end subroutine test_route_floor

   !> solve_contact_unload of E-GW + cap at sigma/delta_y = 1e-7 (mu 4) from 2 delta_y at
   !> 0.15 and 0.145 delta_max, rel_tol 1e-5: its history loads only at rel_tol (by the
   !> small-sigma route: its estimate ~6.4e-8 misses 5e-8 at 1e-7), and the route's wide
   !> histories were then at 1e-6: both refused (estimates 6.8e-6, 7.9e-6). A route-loaded
   !> history's wide histories are now at wide_history_floor (1e-7). Reference: the
   !> smooth cap (cap_near_residual.py, as test_small_sigma_contact_unload's and
   !> test_small_sigma_residual's) times 1 + the rough correction at 1e-6 scaled by
   !> (1e-7/1e-6)**(2/3). That scaling is exact for the first order A s (s = sigma**(2/3))
   !> and misplaces the next, B s**2, by 0.17 of it; at 1e-6 B s**2 was 0.3 % of the
   !> correction at 0.145 (doc/theory.md section 12 "near the residual overlap": e_j from
   !> -5.25e-3 to -4.80e-3 P_y between 2e-5 and 2e-4 delta_y), so the reference is within
   !> 2.4e-6 of the force at 0.145, far less at 0.15. Tolerance rel_tol + 3e-6, as
   !> test_small_sigma_residual's (measured 7.3e-7, -1.9e-6).
   subroutine test_tiny_sigma_contact_unload(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: fractions(2) = [0.15_dp, 0.145_dp]
      real(dp), parameter :: smooth(2) = [1.8716741e-3_dp, 1.162796266339e-4_dp]
      real(dp), parameter :: correction(2) = [-8.346386e-4_dp, -4.601825e-3_dp]
      type(contact_params) :: p
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, ref
      integer :: i
      call yield_units(delta_y, force_y)
      p = egw_cap(1.0e-7_dp)
      do i = 1, size(fractions)
         call solve_contact_unload(p, solver_options(rel_tol=1.0e-5_dp), fractions(i)* &
            & 2.0_dp*delta_y, 2.0_dp*delta_y, res, err)
         if (allocated(err)) then
            call check(error, .false., str(fractions(i))//" delta_max: "//err%message)
            return
         end if
         ref = smooth(i)*(1.0_dp + correction(i)*0.1_dp**(2.0_dp/3.0_dp))
         call check(error, abs(res%force/force_y - ref) <= 1.3e-5_dp*ref, str(fractions(i)) &
            & //" delta_max: P/P_y = "//str(res%force/force_y)//", reference "//str(ref))
         if (allocated(error)) return
      end do
   end subroutine test_tiny_sigma_contact_unload

   !> E-GW + cap at sigma/delta_y = 1e-6 (mu 4) from 2 delta_y (history at rel_tol 1e-7),
   !> unloading at 0.1446 and 0.1443 delta_max, 5.3e-4 and 2.3e-4 delta_max above the
   !> residual overlap (0.14407 delta_max), where no test had a reference: test_small_sigma_
   !> residual's (the force's correction fitted in sigma**(2/3)) does not converge there
   !> (its ratio D/(delta - delta_r) passes 0.5 at its direct solves' sigma, to 1e-3). Reference:
   !> the rough layer as a shift of the smooth cap's unloading curve, P = P_cap(delta + D)
   !> (doc/stability.md "Stop 47 (sigma13)"): D at 1e-6 from a least-squares fit
   !> of degree 2 in x = (sigma_j/sigma)**(2/3) of D_j/x_j, D_j the shifts of the rough model's
   !> own discrete solves at sigma_j/delta_y = 1e-5 .. 2e-4 (histories at rel_tol 1e-8, each
   !> solve at the tightest of 1e-5, 1e-6, 1e-7 that converged; example small-sigma-shift,
   !> tools/reference/shift_reference.py): -5.5641e-6, -5.4079e-6 delta_y; P_cap at delta + D
   !> by tools/reference/cap_near_residual.py --m 40 --at (an independent solve, Richardson
   !> error 6e-7, 1.5e-6 relative). The reference's uncertainty is that of D: the fits of
   !> degree 1 and 3 are 1.3e-8, 2.8e-8 delta_y apart, 1.8e-5 and 9.4e-5 of the force
   !> (P_cap ~ (delta - delta_r)**(3/2): 1.5 dD/(delta + D - delta_r)); the discrete solves
   !> scatter about the fits by ~4e-9 delta_y in D_j/x_j (their hidden errors, doc/stability.md
   !> "Stop 47 (sigma13)"). At rel_tol 2e-5 both answer (the force's extrapolation, as on
   !> main: measured 8.5e-6 and 1.6e-5 above the references, estimates 6.7e-6, 8.4e-6):
   !> tolerance rel_tol + the reference's uncertainty + its Richardson error. At rel_tol
   !> 1e-5 0.1446 is refused (the route's estimate 6.0e-4): either
   !> answer must be within that tolerance at rel_tol 1e-5, or the call must say
   !> egw_not_converged.
   subroutine test_shift_references(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: fractions(2) = [0.1446_dp, 0.1443_dp]
      real(dp), parameter :: refs(2) = [4.960942012208e-5_dp, 1.402116596395e-5_dp]
      real(dp), parameter :: uncertainty(2) = [1.9e-5_dp, 9.6e-5_dp]
      real(dp), parameter :: rel_tols(2) = [2.0e-5_dp, 1.0e-5_dp]
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y
      integer :: i, j
      call yield_units(delta_y, force_y)
      p = egw_cap(1.0e-6_dp)
      call load_history(p, solver_options(rel_tol=1.0e-7_dp), 2.0_dp*delta_y, h, res, err)
      if (allocated(err)) then
         call check(error, .false., "history from 2 delta_y: "//err%message)
         return
      end if
      do j = 1, size(rel_tols)
         h%options%rel_tol = rel_tols(j)
         do i = 1, size(fractions)
            if (j == 2 .and. i == 2) exit
            call solve_unload(h, fractions(i)*2.0_dp*delta_y, res, err)
            if (allocated(err)) then
               call check(error, j == 2 .and. err%stat == egw_not_converged, "rel_tol " &
                  & //str(rel_tols(j))//", "//str(fractions(i))//" delta_max: "//err%message)
               if (allocated(error)) return
               deallocate (err)
               cycle
            end if
            call check(error, abs(res%force/force_y - refs(i)) <= (rel_tols(j) + &
               & uncertainty(i))*refs(i) .and. res%est_rel_err <= 0.5_dp*rel_tols(j), &
               & "rel_tol "//str(rel_tols(j))//", "//str(fractions(i))//" delta_max: P/P_y = " &
               & //str(res%force/force_y)//", reference "//str(refs(i))//", estimate " &
               & //str(res%est_rel_err))
            if (allocated(error)) return
         end do
      end do
   end subroutine test_shift_references

   !> contact_profile_unload (C egw_profile_unload) of E-GW + cap at sigma/delta_y = 1e-8
   !> (mu 4) from 2 delta_y, whose history the small-sigma route loads (no rough field; on
   !> main egw_unsupported), at 0.5 delta_max, against the sigma -> 0 limit: the smooth
   !> cap's unloading profile (cap_unload_profile on 256 rings, its own references in
   !> test_cap_sphere's test_cap_profile_unload) at the same delta, its w less the plastic
   !> crater u_pl (the rough solver's profiles give the elastic deflection). The served
   !> profile is the smooth cap's at delta + D, D the rough layer's shift of the force,
   !> O((sigma/delta_y)**(2/3) delta_y) = O(4.6e-6 delta_y) (D/((sigma/delta_y)**(2/3)
   !> delta_y) = -0.066 at 1e-6, 0.15 delta_max, doc/stability.md Stop 47), moving w by D
   !> on the contact and p by about D p_y/delta_y: tolerance 1e-5 p_y and 1e-5 delta_y
   !> (measured 2.4e-7 p_y, 5.1e-7 delta_y at r = 0), at radii away from the contact's
   !> edge (0.9 a_y, whose sqrt(b - r) would amplify D). A wrong convention (w with the
   !> crater, u_pl(0) = 0.29 delta_y) fails by far. Below the residual overlap (0.1
   !> delta_max): p = 0, w = 0.
   subroutine test_route_profile(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: rho(5) = [0.0_dp, 0.3_dp, 0.6_dp, 1.2_dp, 1.6_dp]
      type(contact_params) :: p
      type(cap_history) :: cap
      type(cap_result) :: at_max
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, a_y, r(5), pr(5), w(5), pc(5), wc(5), u, du
      integer :: i
      call yield_units(delta_y, force_y)
      a_y = sqrt(delta_y)
      r = rho*a_y
      p = egw_cap(1.0e-8_dp)
      call contact_profile_unload(p, solver_options(rel_tol=1.0e-3_dp), delta_y, &
         & 2.0_dp*delta_y, r, pr, w, err)
      if (allocated(err)) then
         call check(error, .false., "profile_unload at 0.5 delta_max: "//err%message)
         return
      end if
      call cap_load(1.0_dp, 1.0_dp, py, 2.0_dp*delta_y, cap_options(n_rings=128, &
         & n_levels=2), cap, at_max, err, "delta_max")
      if (.not. allocated(err)) call cap_unload_profile(cap, 256, delta_y, r, pc, wc, err)
      if (allocated(err)) then
         call check(error, .false., "smooth cap: "//err%message)
         return
      end if
      do i = 1, size(r)
         call u_plastic(cap, rho(i), u, du)
         wc(i) = wc(i) - delta_y*u
         call check(error, abs(pr(i) - pc(i)) <= 1.0e-5_dp*py .and. abs(w(i) - wc(i)) <= &
            & 1.0e-5_dp*delta_y, "r/a_y = "//str(rho(i))//": p/p_y = "//str(pr(i)/py)// &
            & ", smooth cap "//str(pc(i)/py)//"; w/delta_y = "//str(w(i)/delta_y)// &
            & ", smooth cap "//str(wc(i)/delta_y))
         if (allocated(error)) return
      end do
      call contact_profile_unload(p, solver_options(rel_tol=1.0e-3_dp), 0.2_dp*delta_y, &
         & 2.0_dp*delta_y, r, pr, w, err)
      if (allocated(err)) then
         call check(error, .false., "profile_unload at 0.1 delta_max: "//err%message)
         return
      end if
      call check(error, all(pr == 0.0_dp) .and. all(w == 0.0_dp), "0.1 delta_max, below " &
         & //"the residual overlap: p/p_y = "//str(maxval(abs(pr))/py))
      if (allocated(error)) return
      ! sigma/delta_y = 1e-7 at rel_tol 1e-4, 0.9 delta_max: the history at 1e-8 does not
      ! converge (the route's loading estimate 7.2e-9 misses 5e-9; egw_not_converged on
      ! main, doc/stability.md Stop 48 (audit14)); a looser one serves, as in
      ! solve_contact_unload. Against the smooth cap at 0.9 delta_max, within 1e-5 p_y and
      ! (1e-7)**(2/3) = 2.2e-5 delta_y (|D| measured 0.11 .. 0.15 of that scale: 3.3e-6
      ! delta_y here, p 1.2e-6 p_y apart).
      p = egw_cap(1.0e-7_dp)
      call contact_profile_unload(p, solver_options(rel_tol=1.0e-4_dp), 1.8_dp*delta_y, &
         & 2.0_dp*delta_y, r(1:3), pr(1:3), w(1:3), err)
      if (allocated(err)) then
         call check(error, .false., "1e-7, profile_unload at 0.9 delta_max: "//err%message)
         return
      end if
      call cap_unload_profile(cap, 256, 1.8_dp*delta_y, r(1:3), pc(1:3), wc(1:3), err)
      if (allocated(err)) then
         call check(error, .false., "smooth cap at 0.9 delta_max: "//err%message)
         return
      end if
      do i = 1, 3
         call u_plastic(cap, rho(i), u, du)
         wc(i) = wc(i) - delta_y*u
         call check(error, abs(pr(i) - pc(i)) <= 1.0e-5_dp*py .and. abs(w(i) - wc(i)) <= &
            & 2.2e-5_dp*delta_y, "1e-7, 0.9 delta_max, r/a_y = "//str(rho(i))//": p/p_y = " &
            & //str(pr(i)/py)//", smooth cap "//str(pc(i)/py)//"; w/delta_y = " &
            & //str(w(i)/delta_y)//", smooth cap "//str(wc(i)/delta_y))
         if (allocated(error)) return
      end do
   end subroutine test_route_profile

   !> E-GW + cap, mu 4, R = E* = 1, p_y = 2/pi (delta_y = 1), history to 2 delta_y at
   !> rel_tol 1e-8 (from one at 1e-7 main refuses rel_tol 1e-6 there), the discrete
   !> unloading solve at sigma = 2e-5 delta_y, 0.1442 delta_max (near the residual overlap
   !> 0.14407 delta_max: the contact a disc of ~4.9 in scaled radius, the mesh graded to
   !> the loading's edge at 120): at rel_tol 1e-5 and 1e-6 each
   !> answer's estimate must be below rel_tol/2 and bound its error, so two accepted answers
   !> differ by at most the sum of their rel_tols (the triangle inequality; no reference
   !> from the code is needed). Main answered 6.335328e-6 (estimate 2.1e-6, the
   !> central-disc route, 117 elements in the contact) and 6.331779e-6 (estimate 1.1e-7):
   !> 5.6e-4 apart, the second's levels all holding the whole contact in the one element
   !> from r = 0 to the kink edge, which Richardson cannot see (doc/stability.md, Stop 47
   !> resid13). With the disc graded (sphere_refine's central_disc): 6.335328e-6 and
   !> 6.335331e-6 (estimates 2.1e-6, 1.6e-7; Stop 48 resid14). A refusal
   !> (egw_not_converged) passes.
   subroutine test_contact_in_one_element(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: rel_tols(2) = [1.0e-5_dp, 1.0e-6_dp]
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: forces(2)
      logical :: answered(2)
      integer :: j
      p = contact_params(model=model_egw, radius=1.0_dp, modulus=1.0_dp, sigma=2.0e-5_dp, &
         & mu=4.0_dp, flow_pressure=2.0_dp/pi)
      call load_history(p, solver_options(rel_tol=1.0e-8_dp), 2.0_dp, h, res, err)
      if (allocated(err)) then
         call check(error, .false., "history from 2 delta_y: "//err%message)
         return
      end if
      answered = .false.
      forces = 0.0_dp
      do j = 1, size(rel_tols)
         h%options%rel_tol = rel_tols(j)
         call solve_unload(h, 0.1442_dp*2.0_dp, res, err)
         if (allocated(err)) then
            call check(error, err%stat == egw_not_converged, "rel_tol "//str(rel_tols(j)) &
               & //": "//err%message)
            if (allocated(error)) return
            deallocate (err)
            cycle
         end if
         call check(error, res%force > 0.0_dp .and. res%est_rel_err <= 0.5_dp*rel_tols(j), &
            & "rel_tol "//str(rel_tols(j))//": P = "//str(res%force)//", estimate " &
            & //str(res%est_rel_err))
         if (allocated(error)) return
         answered(j) = .true.
         forces(j) = res%force
      end do
      if (all(answered)) call check(error, abs(forces(1) - forces(2)) <= &
         & sum(rel_tols)*forces(1), "P at rel_tol 1e-5, 1e-6: "//str(forces(1))//", " &
         & //str(forces(2))//": further apart than the sum of their rel_tols")
   end subroutine test_contact_in_one_element

   !> E-GW + cap (mu 4) restitution at 3 v_y, rel_tol, at each sigma/delta_y of ratios
   !> against the smooth cap's e (sigma = 0), within rel_tol + 3.4e-6 +
   !> 0.3 (sigma/delta_y)**(2/3) (the tests above say why).
   subroutine check_restitution_near_cap(ratios, rel_tol, error)
      real(dp), intent(in) :: ratios(:)
      real(dp), intent(in) :: rel_tol
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: p
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, v, e_cap, e_rough, dissipated, tol
      integer :: i
      call yield_units(delta_y, force_y)
      v = 3.0_dp*first_yield_speed()
      p = contact_params(model=model_egw, radius=1.0_dp, modulus=1.0_dp, sigma=0.0_dp, &
         & mu=4.0_dp, flow_pressure=py)
      call restitution(p, solver_options(rel_tol=rel_tol), 1.0_dp, v, e_cap, dissipated, err)
      if (allocated(err)) then
         call check(error, .false., "smooth cap restitution: "//err%message)
         return
      end if
      do i = 1, size(ratios)
         p%sigma = ratios(i)*delta_y
         call restitution(p, solver_options(rel_tol=rel_tol), 1.0_dp, v, e_rough, &
            & dissipated, err)
         if (allocated(err)) then
            call check(error, .false., "sigma/delta_y = "//str(ratios(i))//": restitution: " &
               & //err%message)
            return
         end if
         tol = rel_tol + 3.4e-6_dp + 0.3_dp*ratios(i)**(2.0_dp/3.0_dp)
         call check(error, abs(e_rough - e_cap) <= tol*e_cap, "sigma/delta_y = " &
            & //str(ratios(i))//": e = "//str(e_rough)//", smooth cap "//str(e_cap))
         if (allocated(error)) return
      end do
   end subroutine check_restitution_near_cap

   !> The rough + cap table of issue 32 (the README's command with --model EP-GW --psi 1:
   !> mu 4, sigma = 1, R = 810569.469138702/2, E* = 1, p_y = 0.01, first yield ~98 sigma):
   !> histories whose loading never reaches p_y anywhere (cap_never_acts) unload by the
   !> cap-free route, which solves the same equations (shift, offset 0, the floor never
   !> acts on Z_u >= 0): against the cap's routes (cap_free set false on the same history)
   !> force and stiffness bit for bit (measured so: the kink scans find no kink, the meshes
   !> are the same). Such a history's loading peak is below p_y (the solve's max_pressure,
   !> an independent read of the same loading); one loaded beyond first yield (99 sigma,
   !> the loading's peak at p_y) keeps the cap's routes.
   subroutine test_cap_never_acts(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: tops(4) = [-3.0_dp, 0.0_dp, 50.0_dp, 93.0_dp]
      real(dp), parameter :: fractions(3) = [0.05_dp, 0.4_dp, 0.9_dp]
      type(contact_params) :: p
      type(solver_options) :: o
      type(loading_history) :: h
      type(solve_result) :: top, free, capped
      type(egw_error), allocatable :: err
      real(dp) :: delta
      integer :: i, k
      p = contact_params(model=model_epgw, radius=810569.469138702_dp/2, modulus=1.0_dp, &
         & sigma=1.0_dp, mu=4.0_dp, psi=1.0_dp, flow_pressure=0.01_dp)
      o%rel_tol = 1.0e-5_dp
      o%n_threads = 1
      do i = 1, size(tops)
         call load_history(p, o, tops(i), h, top, err)
         call check(error, .not. allocated(err), "history at "//str(tops(i))//" failed")
         if (allocated(error)) return
         call check(error, h%cap_free .and. top%max_pressure < p%flow_pressure, &
            & "delta_max = "//str(tops(i))//": not cap-free, or its peak "// &
            & str(top%max_pressure)//" at p_y")
         if (allocated(error)) return
         do k = 1, size(fractions)
            delta = tops(i) - fractions(k)*(tops(i) + 8.0_dp)
            h%cap_free = .true.
            call solve_unload(h, delta, free, err)
            call check(error, .not. allocated(err), "cap-free unloading failed")
            if (allocated(error)) return
            h%cap_free = .false.
            call solve_unload(h, delta, capped, err)
            call check(error, .not. allocated(err), "unloading on the cap's routes failed")
            if (allocated(error)) return
            call check(error, free%force == capped%force .and. &
               & free%stiffness == capped%stiffness, "delta_max "//str(tops(i))// &
               & ", delta "//str(delta)//": "//str(free%force)//" /= "//str(capped%force))
            if (allocated(error)) return
         end do
      end do
      call load_history(p, o, 99.0_dp, h, top, err)
      call check(error, .not. allocated(err), "history at 99 sigma failed")
      if (allocated(error)) return
      call check(error, .not. h%cap_free .and. top%max_pressure >= 0.999_dp*p%flow_pressure, &
         & "99 sigma (beyond first yield): cap-free, or its peak "//str(top%max_pressure))
   end subroutine test_cap_never_acts

   !> lagrange_undershoot bounds the negative parts of the degree-4 Chebyshev-Lobatto
   !> Lagrange basis on [-1, 1] (the solver's deflection elements): their sum sampled at
   !> 200 001 points is 0.39938 (numpy, the same nodes: 0.3993809), and between samples
   !> it moves by at most its slope bound max sum |l_k'| = 16 (numpy) times 5e-6: 8e-5.
   subroutine test_lagrange_undershoot(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: n = 200000
      real(dp) :: s(0:4), l(0:4), x, worst
      integer :: i, j, k
      call check(error, deflection_degree == 4, "the bound is the degree-4 elements'")
      if (allocated(error)) return
      s = [(-cos(pi*real(j, dp)/4.0_dp), j = 0, 4)]
      s(0) = -1.0_dp
      s(4) = 1.0_dp
      worst = 0.0_dp
      do i = 0, n
         x = -1.0_dp + 2.0_dp*real(i, dp)/real(n, dp)
         do k = 0, 4
            l(k) = product([((x - s(j))/(s(k) - s(j)), j = 0, k - 1), &
               & ((x - s(j))/(s(k) - s(j)), j = k + 1, 4)])
         end do
         worst = max(worst, -sum(min(l, 0.0_dp)))
      end do
      call check(error, abs(worst - 0.3993809_dp) < 1.0e-6_dp .and. &
         & worst + 2.0e-4_dp < lagrange_undershoot, "negative parts "//str(worst))
   end subroutine test_lagrange_undershoot

   function str(x) result(s)
      real(dp), intent(in) :: x
      character(len=24) :: s
      write (s, '(es24.16)') x
   end function str

   !> Equal to 1e-12 relative: the cap-free solve's own values (the flat law's stiffness
   !> differs by 1 ulp, 6e-16, the other cases are bit for bit).
   pure logical function same(a, b)
      real(dp), intent(in) :: a, b
      same = abs(a - b) <= 1.0e-12_dp*abs(b)
   end function same

   !> The E-GW + cap contact of the small-sigma tests: mu 4, E* = R = 1, p_y = py, sigma =
   !> ratio delta_y.
   !> est_rel_err is the error relative to |P| (issue 32 item 4), also where an unloading
   !> solve after a capped loading is accepted against its absolute floor (1e-6
   !> P(delta_max)): E-GW + cap (mu 4) at sigma = 0.1 delta_y from 2 delta_y (history at
   !> rel_tol 1e-8), unloading at rel_tol 1e-6 at 0.25, 0.1, 0.05 delta_y, where P falls
   !> to 1e-8 .. 1.6e-14 P(delta_max), against the same solves at rel_tol 1e-9 (their
   !> absolute error ~1e-9 of the floor, 1e3 below the tested one's). Bound: |P - P_ref| <=
   !> 10 (est |P| + est_ref |P_ref|), 10 as the estimate is no bound (the true error up to
   !> 7.4 times it over the stability map, doc/stability.md). On main est_rel_err was
   !> relative to the floor: 0.05 delta_y 79 % off under 9.7e-8, 0.25 7.7e-6 off under
   !> 4.1e-7 (fails); now 6.1 and 3.7e-5.
   subroutine test_floor_estimate(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: overlaps(3) = [0.25_dp, 0.1_dp, 0.05_dp]
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: loaded, res, ref
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y
      integer :: i
      call yield_units(delta_y, force_y)
      p = egw_cap(0.1_dp)
      call load_history(p, solver_options(rel_tol=1.0e-8_dp, n_threads=1), 2.0_dp*delta_y, h, &
         & loaded, err)
      if (allocated(err)) then
         call check(error, .false., "history: "//err%message)
         return
      end if
      do i = 1, size(overlaps)
         h%options%rel_tol = 1.0e-6_dp
         call solve_unload(h, overlaps(i)*delta_y, res, err)
         if (.not. allocated(err)) then
            h%options%rel_tol = 1.0e-9_dp
            call solve_unload(h, overlaps(i)*delta_y, ref, err)
         end if
         if (allocated(err)) then
            call check(error, .false., str(overlaps(i))//" delta_y: "//err%message)
            return
         end if
         call check(error, res%force < 1.0e-6_dp*loaded%force .and. abs(res%force - &
            & ref%force) <= 10.0_dp*(res%est_rel_err*res%force + ref%est_rel_err*ref%force), &
            & str(overlaps(i))//" delta_y: P/P(delta_max) = "//str(res%force/loaded%force)// &
            & ", "//str(abs(res%force/ref%force - 1.0_dp))//" off under est_rel_err "// &
            & str(res%est_rel_err))
         if (allocated(error)) return
      end do
   end subroutine test_floor_estimate

   !> E-GW + cap at delta = 200 sigma: at 2e11 delta_y the solve converges, max_pressure <= p_y
   !> to 1e-9 as egw-fuzz checks (1.7e-12 above from the scaled units here; audit10 measured
   !> convergence up to 2e13 delta_y at 200 sigma, doc/stability.md "Rough + cap far beyond
   !> first yield"); at 2e13 delta_y (beyond the range 1e12 delta_y) solve_contact refuses
   !> naming delta and solve_contact_unload naming delta_max, with egw_invalid_argument
   !> (before: EGW_NOT_CONVERGED one decade further, with a message naming neither).
   subroutine test_far_beyond_yield(error)
      use egw_status, only: egw_invalid_argument
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: p
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      type(solver_options) :: o
      real(dp) :: delta_y, force_y
      call yield_units(delta_y, force_y)
      o = solver_options(rel_tol=1.0e-4_dp, n_threads=1)
      p = egw_cap(1.0e9_dp)
      call solve_contact(p, o, 200.0_dp*p%sigma, res, err)
      if (allocated(err)) then
         call check(error, .false., "2e11 delta_y: "//err%message)
         return
      end if
      call check(error, res%force > 0.0_dp .and. res%max_pressure <= py*(1.0_dp + 1.0e-9_dp), &
         & "2e11 delta_y: force "//str(res%force)//", max_pressure/p_y "//str(res%max_pressure/py))
      if (allocated(error)) return
      p = egw_cap(1.0e11_dp)
      call solve_contact(p, o, 200.0_dp*p%sigma, res, err)
      call check(error, allocated(err), "2e13 delta_y: accepted")
      if (allocated(error)) return
      call check(error, err%stat == egw_invalid_argument .and. index(err%message, "delta =") == 1 &
         & .and. index(err%message, "1e12 delta_y") > 0, "2e13 delta_y: "//err%message)
      if (allocated(error)) return
      deallocate (err)
      call solve_contact_unload(p, o, 0.0_dp, 200.0_dp*p%sigma, res, err)
      call check(error, allocated(err), "delta_max at 2e13 delta_y: accepted")
      if (allocated(error)) return
      call check(error, err%stat == egw_invalid_argument .and. index(err%message, &
         & "delta_max =") > 0, "delta_max at 2e13 delta_y: "//err%message)
   end subroutine test_far_beyond_yield

   pure type(contact_params) function egw_cap(ratio) result(p)
      real(dp), intent(in) :: ratio
      real(dp) :: delta_y, force_y
      call yield_units(delta_y, force_y)
      p = contact_params(model=model_egw, radius=1.0_dp, modulus=1.0_dp, &
         & sigma=ratio*delta_y, mu=4.0_dp, flow_pressure=py)
   end function egw_cap

   !> First yield delta_y and force P_y of the smooth sphere (R = E* = 1) at p_y.
   pure subroutine yield_units(delta_y, force_y)
      real(dp), intent(out) :: delta_y, force_y
      delta_y = (0.5_dp*pi*py)**2
      force_y = 4.0_dp/3.0_dp*delta_y**1.5_dp
   end subroutine yield_units

   !> With p_y above the largest total pressure the cap never acts, and every loading solve
   !> is the cap-free one (GW, E-GW, EP-GW, and a caller's flat law: GW's own through
   !> solve_contact_law), to 1e-12 (same): the cap only enters through rough_pressure,
   !> which then returns the law's values, and the mesh gets no cap edges. p_y = 2 x the
   !> cap-free max_pressure.
   subroutine test_no_cap_load(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: models(3) = [model_gw, model_egw, model_epgw]
      real(dp), parameter :: deltas(3) = [-1.0e-3_dp, 2.0e-3_dp, 2.0e-2_dp]
      type(contact_params) :: p
      type(solve_result) :: free, capped
      type(egw_error), allocatable :: err
      integer :: m, k
      do m = 1, size(models)
         do k = 1, size(deltas)
            p = contact_params(model=models(m), radius=1.0_dp, modulus=1.0_dp, &
               & sigma=1.0e-3_dp, mu=4.0_dp, psi=2.0_dp)
            call solve_contact(p, solver_options(), deltas(k), free, err)
            call check(error, .not. allocated(err), "cap-free solve failed")
            if (allocated(error)) return
            p%flow_pressure = min(0.5_dp, 2.0_dp*free%max_pressure)
            call solve_contact(p, solver_options(), deltas(k), capped, err)
            call check(error, .not. allocated(err), "solve with the cap failed")
            if (allocated(error)) return
            call check(error, same(capped%force, free%force) .and. &
               & same(capped%stiffness, free%stiffness), &
               & "model "//str(real(models(m), dp))//" delta "//str(deltas(k)) &
               & //": "//str(capped%force)//" /= "//str(free%force))
            if (allocated(error)) return
         end do
      end do
      ! a rough-flat law of the caller's (GW's of mu 4, in its own units: sigma = 1)
      block
         type(gw_flat_law) :: law
         law = gw_flat_law(scale=4.0_dp/(2.0_dp*sqrt(2.0_dp)), psi=0.0_dp, &
            & hardness_coeff=0.6_dp, plastic_ratio=54.0_dp)
         ! R = 1e4 sigma: pressures ~1e-2 E*, so that p_y < E* as validate_params asks
         p = contact_params(radius=1.0e4_dp, modulus=1.0_dp)
         call solve_contact_law(p, law, solver_options(), 2.0_dp, free, err)
         call check(error, .not. allocated(err), "flat-law solve failed")
         if (allocated(error)) return
         p%flow_pressure = 2.0_dp*free%max_pressure
         call solve_contact_law(p, law, solver_options(), 2.0_dp, capped, err)
         call check(error, .not. allocated(err), "flat-law solve with the cap failed")
         if (allocated(error)) return
         call check(error, same(capped%force, free%force) .and. &
            & same(capped%stiffness, free%stiffness), "flat law: "//str(capped%force) &
            & //" /= "//str(free%force)//" or stiffness "//str(capped%stiffness)//" /= " &
            & //str(free%stiffness))
      end block
   end subroutine test_no_cap_load

   !> Unloading with p_y above every pressure of the loading at delta_max: no plastic
   !> shift, no offset, the floor never reached: the cap-free unloading bit for bit.
   subroutine test_no_cap_unload(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: models(3) = [model_gw, model_egw, model_epgw]
      type(contact_params) :: p
      type(loading_history) :: h_free, h_cap
      type(solve_result) :: top, free, capped
      type(egw_error), allocatable :: err
      integer :: m
      do m = 1, size(models)
         p = contact_params(model=models(m), radius=1.0_dp, modulus=1.0_dp, &
            & sigma=1.0e-3_dp, mu=4.0_dp, psi=2.0_dp)
         call load_history(p, solver_options(), 3.0e-3_dp, h_free, top, err)
         call check(error, .not. allocated(err), "cap-free history failed")
         if (allocated(error)) return
         call solve_unload(h_free, 1.0e-3_dp, free, err)
         call check(error, .not. allocated(err), "cap-free unloading failed")
         if (allocated(error)) return
         p%flow_pressure = 2.0_dp*top%max_pressure
         call load_history(p, solver_options(), 3.0e-3_dp, h_cap, top, err)
         call check(error, .not. allocated(err), "history with the cap failed")
         if (allocated(error)) return
         call solve_unload(h_cap, 1.0e-3_dp, capped, err)
         call check(error, .not. allocated(err), "unloading with the cap failed")
         if (allocated(error)) return
         call check(error, same(capped%force, free%force) .and. &
            & same(capped%stiffness, free%stiffness), "model "//str(real(models(m), dp)) &
            & //": "//str(capped%force)//" /= "//str(free%force))
         if (allocated(error)) return
      end do
   end subroutine test_no_cap_unload

   !> E-GW with the cap at sigma/delta_y = 1e-4 and 1e-5 against the smooth cap model's
   !> independent reference (its error column <= 5e-8 on these rows): the rough model's
   !> rough layer adds a compliance whose gap is ~ sigma (p/(mu E* sqrt(sigma/R)))**(2/3),
   !> so it differs from the smooth cap by O((sigma/delta_y)**(2/3)) (measured: 1.2e-4 ..
   !> 3.2e-4 at 1e-4, 1.3e-5 .. 6.9e-5 at 1e-5, the ratio ~10**(2/3)). Checked: at 1e-5
   !> within 1e-4 (3 x (1e-5)**(2/3) x 0.7, the largest seen x 1.5), and the Richardson
   !> extrapolation of the two in (sigma/delta_y)**(2/3) within 1e-5 of the reference
   !> (seen: 3e-7 .. 5.4e-6; each solve at rel_tol 1e-6, estimates <= 4e-7).
   subroutine test_smooth_limit(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: x(6) = [1.5_dp, 2.0_dp, 3.0_dp, 5.0_dp, 10.0_dp, 20.0_dp]
      real(dp), parameter :: ref(6) = [1.815256521822_dp, 2.720383972669_dp, &
         & 4.696156337776_dp, 9.032667181270_dp, 2.091895411785e+01_dp, &
         & 4.646580037371e+01_dp]
      real(dp), parameter :: ratios(2) = [1.0e-4_dp, 1.0e-5_dp]
      type(contact_params) :: p
      type(solver_options) :: o
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, got(2), extrapolated, q
      integer :: i, j
      call yield_units(delta_y, force_y)
      o%rel_tol = 1.0e-6_dp
      q = 10.0_dp**(2.0_dp/3.0_dp)
      do i = 1, size(x)
         do j = 1, 2
            p = egw_cap(ratios(j))
            call solve_contact(p, o, x(i)*delta_y, res, err)
            if (allocated(err)) then
               call check(error, .false., "delta/delta_y = "//str(x(i))//": " &
                  & //err%message)
               return
            end if
            if (allocated(error)) return
            got(j) = res%force/force_y
         end do
         call check(error, abs(got(2) - ref(i)) <= 1.0e-4_dp*ref(i), "delta/delta_y = " &
            & //str(x(i))//", sigma/delta_y 1e-5: P/P_y = "//str(got(2))//", reference " &
            & //str(ref(i)))
         if (allocated(error)) return
         extrapolated = (q*got(2) - got(1))/(q - 1.0_dp)
         call check(error, abs(extrapolated - ref(i)) <= 1.0e-5_dp*ref(i), &
            & "delta/delta_y = "//str(x(i))//": extrapolated P/P_y = "//str(extrapolated) &
            & //", reference "//str(ref(i)))
         if (allocated(error)) return
      end do
   end subroutine test_smooth_limit

   !> E-GW with the cap at sigma/delta_y = 1e-6 from 1.5 to 20 delta_y (before, Newton
   !> did not converge at 1.5 and 2 delta_y: the plastic zone's edge, a layer ~ a
   !> (sigma/delta)**(2/3) thin, sat inside elements ~100 layers long; now the solver's
   !> guided route, sphere_solver's guided_cap_solve) against the reference (as
   !> test_smooth_limit): the rough layer's O((sigma/delta_y)**(2/3)) difference, at
   !> 1e-5 up to 6.9e-5, is 10**(-2/3) of that, 1.5e-5, at 1e-6 (measured 2.5e-6 ..
   !> 1.5e-5; the solves at rel_tol 1e-6, error <= 5e-7): within 3e-5, twice that.
   !> Differences above 3e-5 mean the solve is wrong or the layer's law is not the one
   !> measured (a limit that stalled at 1e-5's values would be 6.9e-5 off).
   subroutine test_small_sigma(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: x(6) = [1.5_dp, 2.0_dp, 3.0_dp, 5.0_dp, 10.0_dp, 20.0_dp]
      real(dp), parameter :: ref(6) = [1.815256521822_dp, 2.720383972669_dp, &
         & 4.696156337776_dp, 9.032667181270_dp, 2.091895411785e+01_dp, &
         & 4.646580037371e+01_dp]
      type(contact_params) :: p
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, got
      integer :: i
      call yield_units(delta_y, force_y)
      p = egw_cap(1.0e-6_dp)
      do i = 1, size(x)
         call solve_contact(p, solver_options(rel_tol=1.0e-6_dp), x(i)*delta_y, res, err)
         if (allocated(err)) then
            call check(error, .false., "delta/delta_y = "//str(x(i))//": "//err%message)
            return
         end if
         got = res%force/force_y
         call check(error, abs(got - ref(i)) <= 3.0e-5_dp*ref(i), "delta/delta_y = " &
            & //str(x(i))//", sigma/delta_y 1e-6: P/P_y = "//str(got)//", reference " &
            & //str(ref(i)))
         if (allocated(error)) return
      end do
   end subroutine test_small_sigma

   !> E-GW with the cap at sigma/delta_y = 1e-7 (2, 3 delta_y) and 1e-8 (2, 3, 5 delta_y),
   !> where the discrete solve does not converge (before: egw_not_converged) and the
   !> asymptotic route answers (rough_sphere's small_sigma_loading: the smooth cap plus the
   !> rough layer's correction scaled in sigma**(2/3) from solves at 1e-5 and 1e-4
   !> delta_y), against the reference (as test_small_sigma). The rough layer's difference,
   !> up to 1.5e-5 = 0.15 (1e-6)**(2/3) at 1e-6, is at most 0.15 (sigma/delta_y)**(2/3):
   !> 3.2e-6 at 1e-7, 7e-7 at 1e-8 (measured 2.4e-6, 3.2e-6 and 4.0e-7 .. 6.9e-7); within
   !> 0.3 (sigma/delta_y)**(2/3), twice that: 6.5e-6 and 1.4e-6. rel_tol 1e-6 (the
   !> route's estimates 7e-9 .. 8.7e-8).
   subroutine test_tiny_sigma(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: ratios(5) = [1.0e-7_dp, 1.0e-7_dp, 1.0e-8_dp, 1.0e-8_dp, &
         & 1.0e-8_dp]
      real(dp), parameter :: x(5) = [2.0_dp, 3.0_dp, 2.0_dp, 3.0_dp, 5.0_dp]
      real(dp), parameter :: ref(5) = [2.720383972669_dp, 4.696156337776_dp, &
         & 2.720383972669_dp, 4.696156337776_dp, 9.032667181270_dp]
      type(contact_params) :: p
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, got
      integer :: i
      call yield_units(delta_y, force_y)
      do i = 1, size(x)
         p = egw_cap(ratios(i))
         call solve_contact(p, solver_options(rel_tol=1.0e-6_dp), x(i)*delta_y, res, err)
         if (allocated(err)) then
            call check(error, .false., "sigma/delta_y = "//str(ratios(i))//", delta/delta_y = " &
               & //str(x(i))//": "//err%message)
            return
         end if
         got = res%force/force_y
         call check(error, abs(got - ref(i)) <= 0.3_dp*ratios(i)**(2.0_dp/3.0_dp)*ref(i), &
            & "sigma/delta_y = "//str(ratios(i))//", delta/delta_y = "//str(x(i)) &
            & //": P/P_y = "//str(got)//", reference "//str(ref(i)))
         if (allocated(error)) return
      end do
   end subroutine test_tiny_sigma

   !> The contact radius every rough solve reports is a* = (3 pi/4) int r p dr / int p dr,
   !> which for a capped contact is well above its edge a (3 pi a/8 once fully capped). The
   !> small-sigma route (sigma/delta_y <= ~1e-6) extrapolated it towards the smooth cap's
   !> edge a instead (audit17: E-GW + cap at 3 delta_y gave a = 2.0849 at sigma/delta_y =
   !> 1e-6, the discrete solve, and 1.8271 at 1e-7, the route, 12 % apart; at 10 delta_y
   !> 4.3995 and 3.7661). Reference: the discrete rough solve at sigma/delta_y = 1e-6
   !> (another algorithm), whose a* differs from the sigma -> 0 limit by O((sigma/
   !> delta_y)**(2/3)) (measured: 8e-6 between 1e-5 and 1e-6 at 10 delta_y): within 1e-4.
   !> Unloading at 0.95 delta_max after 3 delta_y likewise (the route's unloading; rel_tol
   !> 1e-5: at 1e-6 the route's unloading there refuses, its estimate 8.2e-7).
   subroutine test_route_contact_radius(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: x(2) = [3.0_dp, 10.0_dp]
      type(solve_result) :: route, discrete
      type(loading_history) :: hist
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y
      integer :: i
      call yield_units(delta_y, force_y)
      do i = 1, size(x)
         call solve_contact(egw_cap(1.0e-7_dp), solver_options(rel_tol=1.0e-6_dp), &
            & x(i)*delta_y, route, err)
         if (.not. allocated(err)) call solve_contact(egw_cap(1.0e-6_dp), &
            & solver_options(rel_tol=1.0e-6_dp), x(i)*delta_y, discrete, err)
         if (allocated(err)) then
            call check(error, .false., "delta/delta_y = "//str(x(i))//": "//err%message)
            return
         end if
         call check(error, abs(route%contact_radius/discrete%contact_radius - 1.0_dp) <= &
            & 1.0e-4_dp, "loading at "//str(x(i))//" delta_y: a* = " &
            & //str(route%contact_radius)//" (sigma/delta_y = 1e-7), " &
            & //str(discrete%contact_radius)//" (1e-6)")
         if (allocated(error)) return
      end do
      call load_history(egw_cap(1.0e-7_dp), solver_options(rel_tol=1.0e-5_dp), &
         & 3.0_dp*delta_y, hist, route, err)
      if (.not. allocated(err)) call solve_unload(hist, 2.85_dp*delta_y, route, err)
      if (.not. allocated(err)) call load_history(egw_cap(1.0e-6_dp), &
         & solver_options(rel_tol=1.0e-5_dp), 3.0_dp*delta_y, hist, discrete, err)
      if (.not. allocated(err)) call solve_unload(hist, 2.85_dp*delta_y, discrete, err)
      if (allocated(err)) then
         call check(error, .false., "unloading: "//err%message)
         return
      end if
      call check(error, abs(route%contact_radius/discrete%contact_radius - 1.0_dp) <= &
         & 1.0e-4_dp, "unloading at 2.85 after 3 delta_y: a* = "//str(route%contact_radius) &
         & //" (sigma/delta_y = 1e-7), "//str(discrete%contact_radius)//" (1e-6)")
   end subroutine test_route_contact_radius

   !> E-GW with the cap at sigma/delta_y = 1e-10 and 1e-8, 10 delta_y, rel_tol 1e-6, where
   !> the discrete solve converges (rough_sphere's small_sigma_check_loading checks it
   !> against the asymptotic route; before, 1e-10 converged 1.28e-5 ABOVE the reference
   !> under an estimate of 1.5e-8) against the smooth cap's loading row at 10 delta_y
   !> (test/data/cap_reference.csv, the sigma -> 0 limit): the rough layer's compliance
   !> can only lower the force, by at most 0.3 (sigma/delta_y)**(2/3) (test_tiny_sigma),
   !> so P/P_y within [ref (1 - 0.3 r**(2/3)), ref] widened by rel_tol/2 (5e-7).
   subroutine test_tiny_sigma_checked(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: ratios(2) = [1.0e-10_dp, 1.0e-8_dp]
      real(dp), parameter :: ref = 20.91895411785_dp   ! P/P_y at 10 delta_y
      type(contact_params) :: p
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, got, slack
      integer :: i
      call yield_units(delta_y, force_y)
      do i = 1, size(ratios)
         p = egw_cap(ratios(i))
         call solve_contact(p, solver_options(rel_tol=1.0e-6_dp), 10.0_dp*delta_y, res, err)
         if (allocated(err)) then
            call check(error, .false., "sigma/delta_y = "//str(ratios(i))//": "//err%message)
            return
         end if
         got = res%force/force_y
         slack = 5.0e-7_dp*ref
         call check(error, got <= ref + slack .and. got >= ref*(1.0_dp - 0.3_dp* &
            & ratios(i)**(2.0_dp/3.0_dp)) - slack, "sigma/delta_y = "//str(ratios(i)) &
            & //", 10 delta_y: P/P_y = "//str(got)//", smooth cap "//str(ref))
         if (allocated(error)) return
      end do
   end subroutine test_tiny_sigma_checked

   !> Unloading of E-GW with the cap at sigma/delta_y = 1e-6 from 2 delta_y (history at
   !> rel_tol 1e-7, as test_small_sigma_unload) at 0.99 delta_max, rel_tol 1e-6, where
   !> the discrete solve does not converge (before: egw_not_converged; Newton diverges)
   !> and the asymptotic route answers (rough_sphere's small_sigma_unload: the smooth cap's
   !> unloading plus the rough layer's correction from histories at 1e-5 and 1e-4
   !> delta_y), against the reference's unloading row: within 3e-5 as
   !> test_small_sigma_unload (the rough layer's 0.15 (1e-6)**(2/3) = 1.5e-5, twice;
   !> measured 1.1e-5; the route's estimate 3.6e-7).
   subroutine test_small_sigma_unload_top(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: ref = 2.677343788024_dp  ! P/P_y at 0.99 delta_max
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, got
      call yield_units(delta_y, force_y)
      p = egw_cap(1.0e-6_dp)
      call load_history(p, solver_options(rel_tol=1.0e-7_dp), 2.0_dp*delta_y, h, res, err)
      call check(error, .not. allocated(err), "history at 2 delta_y failed")
      if (allocated(error)) return
      h%options%rel_tol = 1.0e-6_dp
      call solve_unload(h, 0.99_dp*2.0_dp*delta_y, res, err)
      if (allocated(err)) then
         call check(error, .false., "unloading at 0.99 delta_max: "//err%message)
         return
      end if
      got = res%force/force_y
      call check(error, abs(got - ref) <= 3.0e-5_dp*ref, "delta/delta_max = 0.99: P/P_y = " &
         & //str(got)//", reference "//str(ref))
   end subroutine test_small_sigma_unload_top

   !> Unloading of E-GW with the cap at sigma/delta_y = 1e-6 from 2 delta_y at 0.95 and
   !> 0.9 delta_max (the guided route: sphere_solver's guided_cap_unload; 0.8 converges
   !> too, in 27 s, 0.99 not yet, doc/theory.md §12 "Small sigma") against the reference's
   !> unloading rows (test_smooth_limit_unload): the rough layer's difference, 2.6e-4 ..
   !> 2.8e-4 at 1e-4, scales like (sigma/delta_y)**(2/3) to 1.3e-5 at 1e-6 (measured
   !> 1.22e-5, 1.34e-5); within 3e-5 (2.3 x that; the solves at rel_tol 1e-7).
   subroutine test_small_sigma_unload(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: y(2) = [0.95_dp, 0.9_dp]
      real(dp), parameter :: ref(2) = [2.507170193550_dp, 2.298961418756_dp]  ! P/P_y
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, got
      integer :: i
      call yield_units(delta_y, force_y)
      p = egw_cap(1.0e-6_dp)
      call load_history(p, solver_options(rel_tol=1.0e-7_dp), 2.0_dp*delta_y, h, res, err)
      call check(error, .not. allocated(err), "history at 2 delta_y failed")
      if (allocated(error)) return
      do i = 1, size(y)
         call solve_unload(h, y(i)*2.0_dp*delta_y, res, err)
         if (allocated(err)) then
            call check(error, .false., "unloading at "//str(y(i))//" delta_max: " &
               & //err%message)
            return
         end if
         got = res%force/force_y
         call check(error, abs(got - ref(i)) <= 3.0e-5_dp*ref(i), "delta/delta_max = " &
            & //str(y(i))//": P/P_y = "//str(got)//", reference "//str(ref(i)))
         if (allocated(error)) return
      end do
   end subroutine test_small_sigma_unload

   !> Unloading of E-GW with the cap at sigma/delta_y = 1e-4 from delta_max = 2 delta_y
   !> against the reference's unloading rows and residual overlap (error column <= 1.7e-7):
   !> forces within 1e-3
   !> (measured 2.4e-4 .. 3.4e-4: the O((sigma/delta_y)**(2/3)) = 2e-3 x 0.2 of the rough
   !> layer, as on loading). History and unloading at rel_tol 1e-7.
   subroutine test_smooth_limit_unload(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: y(4) = [0.99_dp, 0.95_dp, 0.9_dp, 0.8_dp]
      real(dp), parameter :: ref(4) = [2.677343788024_dp, 2.507170193550_dp, &
         & 2.298961418756_dp, 1.897742567134_dp]
      real(dp), parameter :: residual = 1.440704322244e-01_dp  ! delta_r/delta_max
      type(contact_params) :: p
      type(solver_options) :: o
      type(loading_history) :: h
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, got
      integer :: i
      call yield_units(delta_y, force_y)
      o%rel_tol = 1.0e-7_dp
      p = egw_cap(1.0e-4_dp)
      call load_history(p, o, 2.0_dp*delta_y, h, res, err)
      call check(error, .not. allocated(err), "history failed")
      if (allocated(error)) return
      do i = 1, size(y)
         call solve_unload(h, y(i)*2.0_dp*delta_y, res, err)
         call check(error, .not. allocated(err), "y = "//str(y(i))//": unloading failed")
         if (allocated(error)) return
         got = res%force/force_y
         call check(error, abs(got - ref(i)) <= 1.0e-3_dp*ref(i), "delta/delta_max = " &
            & //str(y(i))//": P/P_y = "//str(got)//", reference "//str(ref(i)))
         if (allocated(error)) return
      end do
      ! The residual overlap within 1e-3 delta_max of the reference's (0.14407 delta_max;
      ! issue 32's goal for the smooth cap): a force 1e-3 delta_max above it, none below
      ! (measured: P/P_y = 1.1e-4 at 0.145 delta_max, 0 at 0.144). The sign of the force is
      ! all that counts: these solves at rel_tol 1e-5 (near the residual 1e-7 is not
      ! reached: the force is 1e-4 of the Hertz part it is the difference of).
      h%options%rel_tol = 1.0e-5_dp
      call solve_unload(h, (residual + 1.0e-3_dp)*2.0_dp*delta_y, res, err)
      if (allocated(err)) then
         call check(error, .false., "unloading above the residual: "//err%message)
         return
      end if
      if (allocated(error)) return
      call check(error, res%force > 0.0_dp, "no force 1e-3 delta_max above the residual")
      if (allocated(error)) return
      call solve_unload(h, (residual - 1.0e-3_dp)*2.0_dp*delta_y, res, err)
      if (allocated(err)) then
         call check(error, .false., "unloading below the residual: "//err%message)
         return
      end if
      if (allocated(error)) return
      call check(error, res%force == 0.0_dp, "force "//str(res%force/force_y) &
         & //" P_y 1e-3 delta_max below the residual")
   end subroutine test_smooth_limit_unload

   !> Unloading after a deep capped loading (EP-GW, psi 1, mu 4, sigma = delta_y, history
   !> at 6 delta_y, rel_tol 1e-9): every one of 70 unloading solves at rel_tol 1e-6 from
   !> 0.3 to 5.97 delta_y converges (before a_max was an element edge with halving layers
   !> inside it, sphere_level's solve_with_tail, 7 of them did not reach 1e-6: the
   !> offset's sqrt(a_max - r) edge, where the total steps from its floor to ~p_s, made
   !> the levels' forces alternate by 1.2e-3), and at 7 overlaps they agree with rel_tol
   !> 1e-8 solves (error <= 5e-9) within 5e-6 (5 rel_tol; measured 2.8e-6 at 2.57 delta_y,
   !> <= 1e-6 at 3.9 .. 5.7: the estimate is not a bound there, doc/theory.md §12 Limits),
   !> relative to max(|P|, 1e-6 P(delta_max)) (force_floor).
   subroutine test_deep_unloading(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: checked(7) = [2.5714_dp, 3.9429_dp, 4.2857_dp, 4.6286_dp, &
         & 4.9714_dp, 5.3143_dp, 5.6571_dp]
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: top, res, ref
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, d
      integer :: i
      call yield_units(delta_y, force_y)
      p = impact_pair()
      call load_history(p, solver_options(rel_tol=1.0e-9_dp), 6.0_dp*delta_y, h, top, err)
      call check(error, .not. allocated(err), "history at 6 delta_y failed")
      if (allocated(error)) return
      h%options%rel_tol = 1.0e-6_dp
      do i = 0, 69
         d = 6.0_dp*delta_y*(0.05_dp + 0.95_dp*i/70.0_dp)
         call solve_unload(h, d, res, err)
         if (allocated(err)) then
            call check(error, .false., "unloading at "//str(d/delta_y)//" delta_y: " &
               & //err%message)
            return
         end if
      end do
      do i = 1, size(checked)
         d = checked(i)*delta_y
         call unload_at_tols(h, d, 1.0e-6_dp, 1.0e-8_dp, res, ref, err)
         if (allocated(err)) then
            call check(error, .false., "unloading at "//str(checked(i))//" delta_y: " &
               & //err%message)
            return
         end if
         call check(error, abs(res%force - ref%force) <= 5.0e-6_dp*max(abs(ref%force), &
            & 1.0e-6_dp*top%force), "at "//str(checked(i))//" delta_y: "//str(res%force) &
            & //" vs rel_tol 1e-8 "//str(ref%force))
         if (allocated(error)) return
      end do
   end subroutine test_deep_unloading

   !> Unloading solves at rel_tol 1e-5 after a capped loading (EP-GW, mu 4, psi 1, sigma =
   !> delta_y/100, R/sigma = 4.05e5: the hysteresis table at 1e-4 to 10 delta_y of issue 32,
   !> whose curves are solved at 1e-5) against rel_tol 1e-7 solves of the same history, at
   !> delta = 0.8837 and 0.8357 delta_max = 9.375 delta_y. Their first two levels agreed
   !> by accident while both were off: 1.1e-4 and 9.3e-5 of P(delta_max) under estimates
   !> of 1.3e-6 (a confirming level, as below rel_tol 1e-6, now checks them). Bound:
   !> rel_tol 1e-5 of P(delta_max), the solve's own tolerance (its force is below P there);
   !> the references' own error is ~1e-10 (rel_tol 1e-8 solves).
   subroutine test_deep_unloading_loose(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: fractions(2) = [0.8837_dp, 0.8357_dp]
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: top, res, ref
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, d, dm
      integer :: i
      call yield_units(delta_y, force_y)
      p = impact_pair()
      p%sigma = 0.01_dp*delta_y
      dm = 9.375_dp*delta_y
      call load_history(p, solver_options(rel_tol=1.0e-6_dp), dm, h, top, err)
      call check(error, .not. allocated(err), "history at 9.375 delta_y failed")
      if (allocated(error)) return
      do i = 1, size(fractions)
         d = fractions(i)*dm
         call unload_at_tols(h, d, 1.0e-5_dp, 1.0e-7_dp, res, ref, err)
         if (allocated(err)) then
            call check(error, .false., "unloading at "//str(fractions(i))//" delta_max: " &
               & //err%message)
            return
         end if
         call check(error, abs(res%force - ref%force) <= 1.0e-5_dp*top%force, "at " &
            & //str(fractions(i))//" delta_max: "//str(res%force)//" vs rel_tol 1e-7 " &
            & //str(ref%force)//", P(delta_max) "//str(top%force))
         if (allocated(error)) return
      end do
   end subroutine test_deep_unloading_loose

   !> The unloading solve at rel_tol 1e-5 after the capped loading to 18.90625 delta_y
   !> (the pair of test_deep_unloading_loose: a delta_max node of the hysteresis table at
   !> 1e-4 to 20 delta_y) at 17.65375 delta_y, where the unloading contact ends ~0.5 inside
   !> the rim of the history's plastic zone (scaled r 53.8, the Hertz edge 42): on graded
   !> elements 2.6 long there its levels agreed to 1.3e-6 while 5.1e-5 of P(delta_max)
   !> off (6.6e-5 of its own force), and the table's curve at that node needed more than
   !> 400 s nodes. Against a rel_tol 1e-7 solve of the same history (its estimate 2e-8;
   !> rel_tol 3e-8 and 2e-6 solves agree with it to 2.1e-8 of its force). Bound: rel_tol
   !> 1e-5 of P(delta_max), the solve's own tolerance (its force is below P there).
   subroutine test_rim_unloading(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: p
      type(loading_history) :: h
      type(solve_result) :: top, res, ref
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y
      call yield_units(delta_y, force_y)
      p = impact_pair()
      p%sigma = 0.01_dp*delta_y
      call load_history(p, solver_options(rel_tol=1.0e-6_dp), 18.90625_dp*delta_y, h, top, &
         & err)
      call check(error, .not. allocated(err), "history at 18.9 delta_y failed")
      if (allocated(error)) return
      call unload_at_tols(h, 17.65375_dp*delta_y, 1.0e-5_dp, 1.0e-7_dp, res, ref, err)
      call check(error, .not. allocated(err), "unloading at 17.65 delta_y failed")
      if (allocated(error)) return
      call check(error, abs(res%force - ref%force) <= 1.0e-5_dp*top%force, "at 17.65 " &
         & //"delta_y: "//str(res%force)//" vs rel_tol 1e-7 "//str(ref%force) &
         & //", P(delta_max) "//str(top%force))
   end subroutine test_rim_unloading

   !> Unloading solves of the history h at d at rel_tol tol (res) and at the reference's
   !> ref_tol (ref); err allocated when either fails (h's tolerance left at ref_tol).
   subroutine unload_at_tols(h, d, tol, ref_tol, res, ref, err)
      type(loading_history), intent(inout) :: h
      real(dp), intent(in) :: d, tol, ref_tol
      type(solve_result), intent(inout) :: res, ref
      type(egw_error), allocatable, intent(out) :: err
      h%options%rel_tol = tol
      call solve_unload(h, d, res, err)
      if (allocated(err)) return
      h%options%rel_tol = ref_tol
      call solve_unload(h, d, ref, err)
   end subroutine unload_at_tols

   !> The pair of the impact checks: EP-GW (psi 1, mu 4) with sigma = delta_y, p_y = 0.01,
   !> R = E* = m* = 1; v_y the smooth sphere's first-yield speed.
   pure function impact_pair() result(p)
      type(contact_params) :: p
      real(dp) :: delta_y, force_y
      call yield_units(delta_y, force_y)
      p = contact_params(model=model_epgw, radius=1.0_dp, modulus=1.0_dp, sigma=delta_y, &
         & mu=4.0_dp, psi=1.0_dp, flow_pressure=py)
   end function impact_pair

   pure real(dp) function first_yield_speed() result(v_y)
      v_y = sqrt(16.0_dp/15.0_dp*(0.5_dp*pi)**5*py**5)
   end function first_yield_speed

   !> Energy balance of an impact at 3 v_y: restitution's dissipated energy (its integrals
   !> to rel_tol 1e-5 of the energy each) against the closed integral of P d(delta) by a
   !> composite Gauss-Legendre rule of this test (8 panels x 12 points from -8 sigma, where
   !> the force is ~1e-14 of its peak, to delta_m, on the loading solves and on the
   !> unloading solves of a history at delta_m; the curves are smooth on the scale of sigma,
   !> the panels 0.3 sigma wide). Within 1e-4 of the impact energy (about 1e-3 of what is
   !> dissipated, 10 x the integrals' tolerance); W_load within 1e-4 of m v**2/2.
   subroutine test_energy(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: p
      type(solver_options) :: o
      type(loading_history) :: h
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: e, dissipated, dm, energy, w_load, w_unload, v
      p = impact_pair()
      o%rel_tol = 1.0e-5_dp
      v = 3.0_dp*first_yield_speed()
      energy = 0.5_dp*v*v
      call restitution(p, o, 1.0_dp, v, e, dissipated, err, max_overlap=dm)
      if (allocated(err)) then
         call check(error, .false., "restitution: "//err%message)
         return
      end if
      call load_history(p, o, dm, h, res, err)
      call check(error, .not. allocated(err), "load_history failed")
      if (allocated(error)) return
      w_load = integral(.false.)
      if (allocated(error)) return
      w_unload = integral(.true.)
      if (allocated(error)) return
      call check(error, abs(w_load - energy) <= 1.0e-4_dp*energy, "W_load "//str(w_load) &
         & //" vs m v**2/2 = "//str(energy))
      if (allocated(error)) return
      call check(error, abs((w_load - w_unload) - dissipated) <= 1.0e-4_dp*energy, &
         & "closed integral "//str(w_load - w_unload)//" vs dissipated "//str(dissipated))
      if (allocated(error)) return
      call check(error, abs(e - sqrt(w_unload/w_load)) <= 1.0e-4_dp, "e = "//str(e) &
         & //" vs "//str(sqrt(w_unload/w_load)))
   contains
      real(dp) function integral(unloading) result(total)
         logical, intent(in) :: unloading
         integer, parameter :: panels = 8, points = 12
         real(dp) :: x(points), w(points), a, b, lo
         integer :: i, k
         call gauss_legendre(points, x, w)
         lo = -8.0_dp*p%sigma
         total = 0.0_dp
         do k = 1, panels
            a = lo + (dm - lo)*real(k - 1, dp)/panels
            b = lo + (dm - lo)*real(k, dp)/panels
            do i = 1, points
               if (unloading) then
                  call solve_unload(h, a + 0.5_dp*(b - a)*(x(i) + 1.0_dp), res, err)
               else
                  call solve_contact(p, o, a + 0.5_dp*(b - a)*(x(i) + 1.0_dp), res, err)
               end if
               if (allocated(err)) then
                  call check(error, .false., "solve: "//err%message)
                  return
               end if
               total = total + 0.5_dp*(b - a)*w(i)*res%force
            end do
         end do
      end function integral
   end subroutine test_energy

   !> Beyond v_y the cap dissipates: at 3 v_y e is below the cap-free EP-GW's (measured
   !> 0.879 vs 0.984 at rel_tol 1e-4; the smooth cap model's is 0.92..0.83 from 2 to 5 v_y).
   !> First yield of the rough sphere: with p_y 1 % above the largest total pressure of the
   !> cap-free impact (at delta_m) the cap never acts, e is the cap-free one (1e-12);
   !> 10 % below it the cap acts and e falls below the cap-free e by more than the
   !> integrals' tolerance (2 x 1e-4).
   subroutine test_first_yield(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: p
      type(solver_options) :: o
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: e_cap, e_free, e_above, e_below, dissipated, dm, v
      p = impact_pair()
      o%rel_tol = 1.0e-4_dp
      v = 3.0_dp*first_yield_speed()
      call restitution(p, o, 1.0_dp, v, e_cap, dissipated, err)
      call check(error, .not. allocated(err), "restitution with the cap failed")
      if (allocated(error)) return
      p%flow_pressure = 0.0_dp
      call restitution(p, o, 1.0_dp, v, e_free, dissipated, err, max_overlap=dm)
      call check(error, .not. allocated(err), "cap-free restitution failed")
      if (allocated(error)) return
      call check(error, e_cap < e_free - 0.05_dp, "e with the cap "//str(e_cap) &
         & //" not below the cap-free "//str(e_free))
      if (allocated(error)) return
      ! a slow impact: first yield of the rough sphere
      v = 0.5_dp*first_yield_speed()
      call restitution(p, o, 1.0_dp, v, e_free, dissipated, err, max_overlap=dm)
      call check(error, .not. allocated(err), "slow cap-free restitution failed")
      if (allocated(error)) return
      call solve_contact(p, o, dm, res, err)
      call check(error, .not. allocated(err), "solve at delta_m failed")
      if (allocated(error)) return
      p%flow_pressure = 1.01_dp*res%max_pressure
      call restitution(p, o, 1.0_dp, v, e_above, dissipated, err)
      call check(error, .not. allocated(err), "restitution, p_y above failed")
      if (allocated(error)) return
      call check(error, abs(e_above - e_free) <= 1.0e-12_dp, "p_y above the peak: e = " &
         & //str(e_above)//" vs cap-free "//str(e_free))
      if (allocated(error)) return
      p%flow_pressure = 0.9_dp*res%max_pressure
      call restitution(p, o, 1.0_dp, v, e_below, dissipated, err)
      call check(error, .not. allocated(err), "restitution, p_y below failed")
      if (allocated(error)) return
      call check(error, e_below < e_free - 2.0e-4_dp, "p_y below the peak: e = " &
         & //str(e_below)//" vs cap-free "//str(e_free))
   end subroutine test_first_yield

   !> The steel-like pair of the rough + cap hysteresis tables (test_rough_cap_hysteresis):
   !> R = 1 mm, E* = 100 GPa, p_y = 1 GPa, E-GW, mu = 4, sigma = delta_y/100.
   pure function steel_pair() result(p)
      type(contact_params) :: p
      real(dp), parameter :: radius = 1.0e-3_dp, modulus = 1.0e11_dp, p_y = 1.0e9_dp
      p = contact_params(model=model_egw, radius=radius, modulus=modulus, &
         & sigma=1.0e-2_dp*steel_delta_y(), mu=4.0_dp, flow_pressure=p_y)
   end function steel_pair

   pure real(dp) function steel_delta_y() result(delta_y)
      delta_y = (pi*1.0e9_dp/(2*1.0e11_dp))**2*1.0e-3_dp
   end function steel_delta_y

   !> The capped loading force is smooth in delta (what a table at 1e-4 needs of its
   !> solves): on 13 overlaps 0.01 delta_y apart from 5 and from 9.6 delta_y, solved at
   !> rel_tol 1e-6, every fourth difference within 8e-6 of P (16 x rel_tol/2: four
   !> differences of errors each within the solver's rel_tol/2; the smooth force's own
   !> is ~(0.01/5)**4 P, 1e-11). Measured 2.2e-6 and 5e-13; before the Hertz edge was
   !> always an element edge with its layers (sphere_level's solve_with_tail) the
   !> Hertz edge fell inside an element on some levels and the force near 9.68 delta_y
   !> was 8.5e-5 off under an estimate of 5e-7: fourth differences 2.6e-4.
   subroutine test_smooth_in_delta(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: starts(2) = [5.0_dp, 9.6_dp]
      type(contact_params) :: p
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: f(0:12), d4
      integer :: k, i
      p = steel_pair()
      do k = 1, size(starts)
         do i = 0, 12
            call solve_contact(p, solver_options(rel_tol=1.0e-6_dp), (starts(k) + 0.01_dp*i) &
               & *steel_delta_y(), res, err)
            if (allocated(err)) then
               call check(error, .false., "solve at "//str(starts(k) + 0.01_dp*i) &
                  & //" delta_y: "//err%message)
               return
            end if
            f(i) = res%force
         end do
         do i = 0, 8
            d4 = abs(f(i) - 4*f(i + 1) + 6*f(i + 2) - 4*f(i + 3) + f(i + 4))/f(i + 2)
            call check(error, d4 <= 8.0e-6_dp, "fourth difference "//str(d4)//" of P at " &
               & //str(starts(k) + 0.01_dp*(i + 2))//" delta_y")
            if (allocated(error)) return
         end do
      end do
   end subroutine test_smooth_in_delta

   !> The loading stiffness at rel_tol 1e-6 against the central difference quotient of
   !> forces solved at rel_tol 1e-8, delta (1 +- 1e-3) (an independent, more accurate
   !> computation: its truncation ~(1e-3)**2/6 of K; the quotient moved by <= 4e-7 with
   !> h = 1e-4 or rel_tol 1e-7 but at 20 delta_y, sigma/delta_y = 1e-4, by 7e-6). E-GW +
   !> cap, R = 1/ratio, E* = sigma = 1, p_y = 2/pi (delta_y = R). Within 5e-6 (5 rel_tol:
   !> the quotient's error plus the accepted level's) at sigma/delta_y = 1e-2 from 1.5 to
   !> 20 delta_y, 1e-4 at 1.5, 6 and 20 delta_y and 1e-5 at 1.5 delta_y (measured <=
   !> 1.7e-6); within 5e-6 at 1e-4, 10 delta_y too since stop 57 (its quotient here is
   !> 1.7e-6 below the fourth-order one of test_stiffness_points; before, -1.22e-5: the
   !> layer past the cap's edge unresolved on the derivative's mesh). The stiffness is
   !> the derivative of the converged answer
   !> on the accepted mesh moved with its kinks at their rate (egw_sphere_moving_mesh);
   !> stop 53's kinks re-found on a solve at delta (1 + 1e-6) were 8.7e-5, 2.9e-5 and
   !> -3.2e-5 off at 1e-4 (1.5, 10, 20 delta_y), 3.7e-5 at 1e-5, 1.5 delta_y; the
   !> implicit derivative on the fixed mesh (main before stop 53) 2.6e-5 .. 1.3e-3 off at
   !> 1e-2, 2.3e-4 and 3.9e-2 at 1e-4, 6 and 20 delta_y. None of these solves falls back
   !> to the implicit derivative (implicit_stiffness .false.).
   subroutine test_stiffness(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: n = 10
      real(dp), parameter :: ratio(n) = [1e-2_dp, 1e-2_dp, 1e-2_dp, 1e-2_dp, 1e-2_dp, &
         & 1e-4_dp, 1e-4_dp, 1e-4_dp, 1e-4_dp, 1e-5_dp], x(n) = [1.5_dp, 3.0_dp, 6.0_dp, &
         & 10.0_dp, 20.0_dp, 1.5_dp, 6.0_dp, 10.0_dp, 20.0_dp, 1.5_dp], tol(n) = [5e-6_dp, &
         & 5e-6_dp, 5e-6_dp, 5e-6_dp, 5e-6_dp, 5e-6_dp, 5e-6_dp, 5e-6_dp, 5e-6_dp, 5e-6_dp]
      real(dp), parameter :: h = 1.0e-3_dp
      type(contact_params) :: p
      type(solve_result) :: res, up, down
      type(egw_error), allocatable :: err
      real(dp) :: d, quotient
      integer :: i
      do i = 1, n
         p = contact_params(model=model_egw, radius=1.0_dp/ratio(i), modulus=1.0_dp, &
            & sigma=1.0_dp, mu=4.0_dp, flow_pressure=2.0_dp/pi)
         d = x(i)*p%radius
         call solve_contact(p, solver_options(rel_tol=1.0e-6_dp), d, res, err)
         if (.not. allocated(err)) call solve_contact(p, solver_options(rel_tol=1.0e-8_dp), &
            & d*(1 + h), up, err)
         if (.not. allocated(err)) call solve_contact(p, solver_options(rel_tol=1.0e-8_dp), &
            & d*(1 - h), down, err)
         if (allocated(err)) then
            call check(error, .false., "solve at "//str(x(i))//" delta_y: "//err%message)
            return
         end if
         quotient = (up%force - down%force)/(2*h*d)
         ! (the moved-mesh derivative, not the implicit fallback)
         call check(error, .not. res%implicit_stiffness, "sigma/delta_y "//str(ratio(i)) &
            & //" at "//str(x(i))//" delta_y: implicit_stiffness set")
         if (allocated(error)) return
         call check(error, abs(res%stiffness - quotient) <= tol(i)*quotient, &
            & "sigma/delta_y "//str(ratio(i))//" at "//str(x(i))//" delta_y: stiffness " &
            & //str(res%stiffness)//" vs difference quotient "//str(quotient))
         if (allocated(error)) return
      end do
   end subroutine test_stiffness

   !> The loading stiffness at rel_tol 1e-6 within rel_tol of fourth-order quotients of
   !> rel_tol 1e-8 forces (test/data/rough_cap_stiffness_reference.csv, written by
   !> tools/bench/rough_cap_stiffness_reference.f90: forces only, never the stiffness
   !> path), E-GW + cap at sigma/delta_y 1e-2, 1e-4, 1e-5 x 1.5, 10, 20 delta_y (1e-5 at
   !> 20 delta_y has no row: its 1e-8 forces need more than 4097 nodes). The h = 1e-2
   !> quotient is the reference (its forces' errors enter as ~1.5 eps P/(h delta K), 3.3x
   !> less than at h = 3e-3; its truncation h**4/30 of ~10 K, ~3e-9); the h = 3e-3 one
   !> checks it: they agree within 4.9e-7 (checked here to 1e-6).
   !> Bound: 1e-6, the solve's rel_tol; measured <= 3.0e-7. Before stop 57 (main 8214e0f)
   !> -1.72e-5 at 1e-4, 10 delta_y (the layer past the cap's edge, one element of the
   !> accepted mesh, sliding through its Gauss points), 1.75e-6 at 1e-4, 20 delta_y and
   !> 1.14e-6 at 1e-5, 10 delta_y: this test fails there (egw_sphere_moving_mesh's
   !> steep_split and step; doc/benchmarks.md "Stop 57: stiff23").
   subroutine test_stiffness_points(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), parameter :: path = "test/data/rough_cap_stiffness_reference.csv"
      character(len=row_length), allocatable :: rows(:)
      type(solve_result) :: res
      real(dp) :: ratio, x, k_ref, k_check, est
      integer :: i, comma
      call read_data_rows(path, rows, error)
      if (allocated(error)) return
      call check(error, size(rows) == 8, path//": "//str(real(size(rows), dp))//" rows, not 8")
      if (allocated(error)) return
      do i = 1, size(rows)
         comma = index(rows(i), ",")
         read (rows(i)(comma + 1:), *) ratio, x, k_ref, k_check, est
         ! (the reference's own spread, far inside the bound)
         call check(error, abs(k_check - k_ref) <= 1.0e-6_dp*k_ref, path//": row " &
            & //str(real(i, dp))//": the two quotients differ by more than 1e-6")
         if (allocated(error)) return
         call edge_point_solve(ratio, x, res, error)
         if (allocated(error)) return
         call check(error, .not. res%implicit_stiffness, "sigma/delta_y "//str(ratio) &
            & //" at "//str(x)//" delta_y: implicit_stiffness set")
         if (allocated(error)) return
         call check(error, abs(res%stiffness - k_ref) <= 1.0e-6_dp*k_ref, "sigma/delta_y " &
            & //str(ratio)//" at "//str(x)//" delta_y: stiffness "//str(res%stiffness) &
            & //" vs reference "//str(k_ref)//" (relative "//str(res%stiffness/k_ref - 1) &
            & //")")
         if (allocated(error)) return
      end do
   end subroutine test_stiffness_points

   !> The loading force at rel_tol 1e-6 within rel_tol of rel_tol 1e-9 forces
   !> (test/data/rough_cap_force_reference.csv, written by
   !> tools/bench/rough_cap_force_error.f90; main 114b9b2's rel_tol 1e-9 forces, on other
   !> meshes inside a, agree with them within 3.5e-10, checked here to 1e-8), E-GW + cap at
   !> five points where the capped zone holds the Hertz edge a (the error's ratio to the
   !> estimate: doc/benchmarks.md "Stop 58: edge24"). Bound: 1e-6, the solve's rel_tol;
   !> measured <= 3.0e-7. Before stop 58 (main 114b9b2): -4.84e-6 at 1e-2, 20
   !> delta_y (under an estimate of 4.4e-8), -1.30e-6 at 1e-3, 20, -1.07e-6 at 1e-5, 10
   !> and -1.91e-5 at 1e-5, 40 delta_y: this test fails there (egw_sphere_mesh's
   !> graded_inside and egw_sphere_refine's confirming level of capped loading).
   subroutine test_force_points(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), parameter :: path = "test/data/rough_cap_force_reference.csv"
      character(len=row_length), allocatable :: rows(:)
      type(solve_result) :: res
      real(dp) :: ratio, x, f_ref, est, f_main
      integer :: i, comma
      call read_data_rows(path, rows, error)
      if (allocated(error)) return
      call check(error, size(rows) == 5, path//": "//str(real(size(rows), dp))//" rows, not 5")
      if (allocated(error)) return
      do i = 1, size(rows)
         comma = index(rows(i), ",")
         read (rows(i)(comma + 1:), *) ratio, x, f_ref, est, f_main
         ! (the reference's own spread, far inside the bound)
         call check(error, abs(f_main - f_ref) <= 1.0e-8_dp*f_ref, path//": row " &
            & //str(real(i, dp))//": the two references differ by more than 1e-8")
         if (allocated(error)) return
         call edge_point_solve(ratio, x, res, error)
         if (allocated(error)) return
         call check(error, abs(res%force - f_ref) <= 1.0e-6_dp*f_ref, "sigma/delta_y " &
            & //str(ratio)//" at "//str(x)//" delta_y: force "//str(res%force) &
            & //" vs reference "//str(f_ref)//" (relative "//str(res%force/f_ref - 1) &
            & //", estimate "//str(res%est_rel_err)//")")
         if (allocated(error)) return
      end do
   end subroutine test_force_points

   !> test_stiffness_points' and test_force_points' solve: E-GW + cap, sigma = E* = 1,
   !> R = 1/ratio, p_y = 2/pi (delta_y = R), mu 4, at x delta_y and rel_tol 1e-6; a failed
   !> solve is the test's error, naming the point.
   subroutine edge_point_solve(ratio, x, res, error)
      real(dp), intent(in) :: ratio, x
      type(solve_result), intent(out) :: res
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: p
      type(egw_error), allocatable :: err
      p = contact_params(model=model_egw, radius=1.0_dp/ratio, modulus=1.0_dp, &
         & sigma=1.0_dp, mu=4.0_dp, flow_pressure=2.0_dp/pi)
      call solve_contact(p, solver_options(rel_tol=1.0e-6_dp), x*p%radius, res, err)
      if (allocated(err)) call check(error, .false., "sigma/delta_y "//str(ratio)//" at " &
         & //str(x)//" delta_y: "//err%message)
   end subroutine edge_point_solve

   !> solve_contact with stiffness=.false. (what the scene's Hertz check and cap_reached
   !> ask: they read the force, resp. the peak pressure only) skips the moved-mesh
   !> stiffness: force, peak pressure and contact radius the default solve's to the bit,
   !> the stiffness the implicit derivative, said by implicit_stiffness (the default
   !> solve's not), within 1e-2 of the default's (test_history_stiffness's bound). E-GW +
   !> cap, sigma/delta_y = 1e-2, mu 4 (README's scene's) at 3.5 and 10 delta_y, rel_tol
   !> 1e-5; and EP-GW psi 1 + cap at 10 delta_y on its tabulated law.
   subroutine test_contact_stiffness(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: at(3) = [3.5_dp, 10.0_dp, 10.0_dp]
      type(contact_params) :: p
      type(solve_result) :: res, res_fast
      type(egw_error), allocatable :: err
      type(law_pieces) :: law
      real(dp) :: d
      integer :: k
      do k = 1, size(at)
         p = contact_params(model=model_egw, radius=100.0_dp, modulus=1.0_dp, sigma=1.0_dp, &
            & mu=4.0_dp, flow_pressure=2.0_dp/pi)
         if (k == 3) then
            p%model = model_epgw
            p%psi = 1.0_dp
            law = zmc_law_pieces(p%psi, p%hardness_coeff, p%plastic_ratio)
         end if
         d = at(k)*p%radius   ! (delta_y = R here: pi p_y/(2 E*) = 1)
         call solve_contact(p, solver_options(rel_tol=1.0e-5_dp), d, res, err, law)
         if (.not. allocated(err)) call solve_contact(p, solver_options(rel_tol=1.0e-5_dp), &
            & d, res_fast, err, law, stiffness=.false.)
         if (allocated(err)) then
            call check(error, .false., "solve at "//str(at(k))//" delta_y: "//err%message)
            return
         end if
         call check(error, res_fast%force == res%force .and. res_fast%max_pressure == &
            & res%max_pressure .and. res_fast%contact_radius == res%contact_radius, &
            & "at "//str(at(k))//" delta_y: force "//str(res_fast%force)//" vs " &
            & //str(res%force)//", peak pressure "//str(res_fast%max_pressure)//" vs " &
            & //str(res%max_pressure))
         if (allocated(error)) return
         call check(error, res_fast%implicit_stiffness .and. .not. res%implicit_stiffness, &
            & "at "//str(at(k))//" delta_y: implicit_stiffness: stiffness=.false. "// &
            & merge("T", "F", res_fast%implicit_stiffness)//", default "// &
            & merge("T", "F", res%implicit_stiffness))
         if (allocated(error)) return
         call check(error, abs(res_fast%stiffness - res%stiffness) <= 1.0e-2_dp* &
            & res%stiffness, "at "//str(at(k))//" delta_y: stiffness "// &
            & str(res_fast%stiffness)//" vs the default's "//str(res%stiffness))
         if (allocated(error)) return
      end do
   end subroutine test_contact_stiffness

   !> load_history with stiffness=.false. (what a hysteresis build's curves load: they read
   !> the history's force only) skips the moved-mesh stiffness: the history's force and
   !> every unloading solve from it are the default history's to the bit, its loading
   !> stiffness the implicit derivative, said by implicit_stiffness (the default
   !> history's not), within 1e-2 of the quotient of 1e-8 forces (as
   !> test_stiffness; measured 1.26e-3 at rel_tol 1e-6 before stop 53), where the default
   !> history's is within 5e-6 (test_stiffness's bound). E-GW + cap, sigma/delta_y = 1e-2,
   !> 10 delta_y, rel_tol 1e-5 (the history's field at 1e-6).
   subroutine test_history_stiffness(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: h = 1.0e-3_dp, at(2) = [0.9_dp, 0.5_dp]
      type(contact_params) :: p
      type(loading_history) :: exact, fast
      type(solve_result) :: top, top_fast, up, down, res, res_fast
      type(egw_error), allocatable :: err
      real(dp) :: d, quotient
      integer :: k
      p = contact_params(model=model_egw, radius=100.0_dp, modulus=1.0_dp, sigma=1.0_dp, &
         & mu=4.0_dp, flow_pressure=2.0_dp/pi)
      d = 10.0_dp*p%radius
      call load_history(p, solver_options(rel_tol=1.0e-5_dp), d, exact, top, err)
      if (.not. allocated(err)) call load_history(p, solver_options(rel_tol=1.0e-5_dp), d, &
         & fast, top_fast, err, stiffness=.false.)
      if (.not. allocated(err)) call solve_contact(p, solver_options(rel_tol=1.0e-8_dp), &
         & d*(1 + h), up, err)
      if (.not. allocated(err)) call solve_contact(p, solver_options(rel_tol=1.0e-8_dp), &
         & d*(1 - h), down, err)
      if (allocated(err)) then
         call check(error, .false., "load or solve: "//err%message)
         return
      end if
      quotient = (up%force - down%force)/(2*h*d)
      call check(error, top_fast%force == top%force, "loading force "//str(top_fast%force) &
         & //" vs the default history's "//str(top%force))
      if (allocated(error)) return
      call check(error, abs(top%stiffness - quotient) <= 5.0e-6_dp*quotient, "default " &
         & //"history: stiffness "//str(top%stiffness)//" vs quotient "//str(quotient))
      if (allocated(error)) return
      call check(error, top_fast%implicit_stiffness .and. .not. top%implicit_stiffness, &
         & "implicit_stiffness: stiffness=.false. "//merge("T", "F", &
         & top_fast%implicit_stiffness)//", default "//merge("T", "F", top%implicit_stiffness))
      if (allocated(error)) return
      call check(error, abs(top_fast%stiffness - quotient) <= 1.0e-2_dp*quotient, &
         & "stiffness=.false.: stiffness "//str(top_fast%stiffness)//" vs quotient " &
         & //str(quotient))
      if (allocated(error)) return
      do k = 1, size(at)
         call solve_unload(exact, at(k)*d, res, err)
         if (.not. allocated(err)) call solve_unload(fast, at(k)*d, res_fast, err)
         if (allocated(err)) then
            call check(error, .false., "unloading at "//str(at(k))//" delta_max: " &
               & //err%message)
            return
         end if
         call check(error, res_fast%force == res%force .and. res_fast%stiffness == &
            & res%stiffness, "unloading at "//str(at(k))//" delta_max: "// &
            & str(res_fast%force)//", "//str(res_fast%stiffness)//" vs "//str(res%force) &
            & //", "//str(res%stiffness))
         if (allocated(error)) return
      end do
   end subroutine test_history_stiffness

   !> A loading table (the capped loading curve of a hysteresis table, build_table with
   !> loading_curve) at rel_tol 1e-5 from -3 sigma to 10 delta_y builds (before the
   !> solver was smooth in delta it stopped at 3e-5 with its node spacing at round-off)
   !> and its force at the midpoint of every interval from delta_y on agrees with solves
   !> at rel_tol 1e-8 within 1e-5 (the table's tolerance; the build checks its midpoints
   !> against its own solves at 1e-6).
   subroutine test_loading_table(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: p
      type(force_table) :: t
      type(egw_error), allocatable :: err
      real(dp) :: worst
      integer :: first, n
      p = steel_pair()
      call build_table(p, solver_options(), -3*p%sigma, 10*steel_delta_y(), 1.0e-5_dp, t, &
         & err, loading_curve=.true.)
      if (allocated(err)) then
         call check(error, .false., "loading table at 1e-5: "//err%message)
         return
      end if
      first = findloc(t%delta >= steel_delta_y(), .true., dim=1)
      n = size(t%delta)
      call check(error, first > 0 .and. n - first >= 5, "too few nodes above delta_y")
      if (allocated(error)) return
      call check_table_points(error, p, t, first, [0.5_dp], 1.0e-5_dp, steel_delta_y(), &
         & worst)
   end subroutine test_loading_table

   !> The loading table of the EP-GW + cap hysteresis table of issue 32 (mu 4, psi 1, sigma
   !> = delta_y/100, R/sigma = 4.05e5; build_table with loading_curve, rel_tol 1e-4, from 0
   !> to 10 delta_y) against rel_tol 1e-8 solves at the quarter points and midpoints of its
   !> intervals from delta_y on, within rel_tol 1e-4 (the table's tolerance; the solves'
   !> own error is ~1e-8). Its curvature changes at ~3 delta_y (where the capped zone
   !> outgrows the Hertz radius): before the build checked the slope at its midpoints too,
   !> the interval 2.46 .. 3.69 delta_y met its midpoint solve (8.1e-5) while the table was
   !> 2.2e-4 off at 3.35 delta_y.
   subroutine test_loading_table_quarters(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: p
      type(force_table) :: t
      type(egw_error), allocatable :: err
      real(dp) :: delta_y, force_y, worst
      integer :: first
      call yield_units(delta_y, force_y)
      p = impact_pair()
      p%sigma = 0.01_dp*delta_y
      call build_table(p, solver_options(), 0.0_dp, 10*delta_y, 1.0e-4_dp, t, err, &
         & loading_curve=.true.)
      if (allocated(err)) then
         call check(error, .false., "loading table at 1e-4: "//err%message)
         return
      end if
      first = findloc(t%delta >= delta_y, .true., dim=1)
      call check(error, first > 1, "no node above delta_y")
      if (allocated(error)) return
      call check_table_points(error, p, t, first - 1, [0.25_dp, 0.5_dp, 0.75_dp], &
         & 1.0e-4_dp, delta_y, worst)
      print '(4x, a, es9.2)', "largest |P_table - P_solve|/P: ", worst
   end subroutine test_loading_table_quarters

   !> The force table t of p against solves at rel_tol 1e-8 at the fractions u of each of
   !> its intervals from node first on: within tol of the solve's force (error on the
   !> first miss); worst the largest relative difference seen; delta_y the messages' unit.
   subroutine check_table_points(error, p, t, first, u, tol, delta_y, worst)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params), intent(in) :: p
      type(force_table), intent(in) :: t
      integer, intent(in) :: first
      real(dp), intent(in) :: u(:), tol, delta_y
      real(dp), intent(out) :: worst
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      real(dp) :: d, f, k
      integer :: i, j
      worst = 0
      do i = first, size(t%delta) - 1
         do j = 1, size(u)
            d = t%delta(i) + u(j)*(t%delta(i + 1) - t%delta(i))
            call table_eval(t, d, f, k)
            call solve_contact(p, solver_options(rel_tol=1.0e-8_dp), d, res, err)
            if (allocated(err)) then
               call check(error, .false., "solve at "//str(d/delta_y)//" delta_y: " &
                  & //err%message)
               return
            end if
            worst = max(worst, abs(f - res%force)/res%force)
            call check(error, abs(f - res%force) <= tol*res%force, "table "//str(f) &
               & //" vs solve "//str(res%force)//" at "//str(d/delta_y)//" delta_y")
            if (allocated(error)) return
         end do
      end do
   end subroutine check_table_points

   !> flow_cap's plastic_shifts at many points (the deep zone's root solved once) against
   !> the definition (doc/theory.md §12): with c = p_y - p_s,max and t = min(p_y, law(h_max)),
   !> where law(h_max) > c the offset is t - c, and where law(h_max) > p_y the shifted gap
   !> solves law(h_max + u_pl) = p_y (else u_pl = 0); elsewhere both 0. Laws: GW (psi 0)
   !> and ZMC summits (psi 1), p_y = law(1); points on both sides of h = 1, with p_s,max
   !> putting some between c and p_y. Tolerance 1e-12 of p_y on law(h_max + u_pl): the
   !> root is converged to a few ulp of h (|d ln law/d h| h <= ~10 here), and one taken
   !> from another point's Newton, or a shift off by 1e-11 sigma, misses it.
   subroutine test_plastic_shifts(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: h_max(8) = [-1.5_dp, -0.3_dp, 0.2_dp, 0.7_dp, 0.95_dp, &
         & 1.1_dp, 1.4_dp, 2.5_dp]
      real(dp), parameter :: ps_frac(8) = [0.0_dp, 0.4_dp, 0.9_dp, 0.0_dp, 0.2_dp, 0.6_dp, &
         & 0.3_dp, 0.1_dp]
      type(gw_flat_law) :: law
      type(flow_cap) :: cap
      real(dp) :: p(8), dpdh(8), shift(8), offset(8), ps_max(8), p1(1), d1(1), c, t
      integer :: k, i, cases(3), pass
      real(dp), parameter :: psi(2) = [0.0_dp, 1.0_dp]
      ! pass 1: the root solved in the call; pass 2: by prepare, once for the cap
      do pass = 1, 2
      do k = 1, 2
         law%scale = 1.0_dp
         law%psi = psi(k)
         call law%pressure([1.0_dp], p1, d1)
         cap = flow_cap(p_y=p1(1))
         if (pass == 2) call cap%prepare(law)
         call check(error, cap%yield_known .eqv. pass == 2, "psi "//str(psi(k)) &
            & //": the cap's root known after prepare only")
         if (allocated(error)) return
         ps_max = ps_frac*cap%p_y
         call cap%plastic_shifts(law, ps_max, h_max, shift, offset)
         call law%pressure(h_max, p, dpdh)
         cases = 0
         do i = 1, size(h_max)
            c = cap%p_y - ps_max(i)
            if (.not. p(i) > c) then
               cases(1) = cases(1) + 1
               call check(error, shift(i) == 0.0_dp .and. offset(i) == 0.0_dp, "psi " &
                  & //str(psi(k))//", h_max "//str(h_max(i))//": below the cap, shift " &
                  & //str(shift(i))//", offset "//str(offset(i)))
               if (allocated(error)) return
               cycle
            end if
            t = min(cap%p_y, p(i))
            call check(error, abs(offset(i) - (t - c)) <= 1.0e-15_dp*cap%p_y, "psi " &
               & //str(psi(k))//", h_max "//str(h_max(i))//": offset "//str(offset(i)) &
               & //", t - c = "//str(t - c))
            if (allocated(error)) return
            if (.not. p(i) > cap%p_y) then
               cases(2) = cases(2) + 1
               call check(error, shift(i) == 0.0_dp, "psi "//str(psi(k))//", h_max " &
                  & //str(h_max(i))//": law below p_y, shift "//str(shift(i)))
               if (allocated(error)) return
               cycle
            end if
            cases(3) = cases(3) + 1
            call law%pressure([h_max(i) + shift(i)], p1, d1)
            call check(error, shift(i) > 0.0_dp .and. &
               & abs(p1(1) - cap%p_y) <= 1.0e-12_dp*cap%p_y, "psi "//str(psi(k)) &
               & //", h_max "//str(h_max(i))//": law(h_max + shift) = "//str(p1(1)) &
               & //", p_y "//str(cap%p_y))
            if (allocated(error)) return
         end do
         ! every branch met (the points were chosen so)
         call check(error, all(cases > 0), "psi "//str(psi(k))//": cases " &
            & //str(real(cases(1), dp))//" "//str(real(cases(2), dp))//" " &
            & //str(real(cases(3), dp)))
         if (allocated(error)) return
      end do
      end do
   end subroutine test_plastic_shifts

   !> flow_cap's prepare: the root h_y of law(h) = p_y, solved once for a cap. p_y =
   !> law(h0) at h0 from -200 to 4 (GW and ZMC summits), so the root is h0 itself: h_y
   !> within 1e-12 (1 + |h0|) of h0 (law_root stops at a step of 4 ulps, and rounding of
   !> p_y moves the root by |ulp(p)/p'| <= ~1e-14 (1 + |h0|) here; the start h = 0, -1,
   !> -2, -4, ... itself misses h0 by 0.5 to 56 here). A p_y the law never reaches
   !> down to h = -2^60 (1e300): not known, and plastic_shifts then solves as before (the
   !> GW law at h = -2^60 is ~1e27).
   subroutine test_cap_prepare(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: h0(5) = [-200.0_dp, -7.5_dp, -0.4_dp, 1.0_dp, 4.0_dp]
      real(dp), parameter :: psi(2) = [0.0_dp, 1.0_dp]
      type(gw_flat_law) :: law
      type(flow_cap) :: cap
      real(dp) :: p1(1), d1(1)
      integer :: k, i
      law%scale = 1.0_dp
      do k = 1, 2
         law%psi = psi(k)
         do i = 1, size(h0)
            call law%pressure([h0(i)], p1, d1)
            cap = flow_cap(p_y=p1(1))
            call cap%prepare(law)
            call check(error, cap%yield_known, "psi "//str(psi(k))//", h0 "//str(h0(i)) &
               & //": no root found")
            if (allocated(error)) return
            call check(error, abs(cap%h_yield - h0(i)) <= 1.0e-12_dp*(1.0_dp + abs(h0(i))), &
               & "psi "//str(psi(k))//": root "//str(cap%h_yield)//", expected "//str(h0(i)))
            if (allocated(error)) return
         end do
         cap = flow_cap(p_y=1.0e300_dp)
         call cap%prepare(law)
         call check(error, .not. cap%yield_known, "psi "//str(psi(k)) &
            & //": a root of law = 1e300 reported")
         if (allocated(error)) return
      end do
   end subroutine test_cap_prepare

   !> flow_cap's plastic_shifts on a mesh-like field with a deep plastic zone (h_max from
   !> -40 to 3, not in order, a ring that is not deep inside it; 61 points): the law is not evaluated at deep points whose
   !> neighbours are deep (law_max = not_evaluated there), and every output is what the
   !> definition gives with the law evaluated everywhere (here, by the test): law_max equal
   !> to the law bit for bit where given (the same evaluation), not_evaluated only where the
   !> point and both neighbours have law > p_y; offsets t - c to 1e-15 p_y and
   !> law(h_max + u_pl) = p_y to 1e-12 p_y (as test_plastic_shifts); and some points
   !> skipped. Then the solver's reuse: law_max from that call known at every other point
   !> (not_evaluated ones included, which are no value) gives the same shifts and offsets
   !> bit for bit and the same law_max. GW (psi 0) and ZMC summits (psi 1), p_y = law(-2).
   subroutine test_plastic_shifts_deep(error)
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: n = 61
      type(gw_flat_law) :: law
      type(flow_cap) :: cap
      real(dp) :: h_max(n), ps_max(n), p(n), dpdh(n), shift(n), offset(n), law_max(n), &
         & shift2(n), offset2(n), law_max2(n), p1(1), d1(1), c, t
      logical :: known(n), deep_row
      integer :: k, i, skipped
      real(dp), parameter :: psi(2) = [0.0_dp, 1.0_dp]
      do i = 1, n
         ! a gap rising from -40 at the centre to 3 at the rim, wavy (not monotone in i),
         ! with a bump above p_y's gap inside the deep zone: deep points next to points
         ! that are not deep lie on three edges, two of them far below the closest deep point
         h_max(i) = -40.0_dp + 43.0_dp*(real(i - 1, dp)/(n - 1))**2 &
            & + 2.0_dp*sin(0.7_dp*real(i, dp)) + 40.0_dp*exp(-((i - 20)/3.0_dp)**2)
         ps_max(i) = 0.3_dp*max(0.0_dp, 1.0_dp - real(i - 1, dp)/40.0_dp)
      end do
      do k = 1, 2
         law%scale = 1.0_dp
         law%psi = psi(k)
         call law%pressure([-2.0_dp], p1, d1)
         cap%p_y = p1(1)
         ps_max = ps_max*cap%p_y/maxval(ps_max)*0.3_dp
         call law%pressure(h_max, p, dpdh)
         call cap%plastic_shifts(law, ps_max, h_max, shift, offset, law_max)
         skipped = 0
         do i = 1, n
            deep_row = p(i) > cap%p_y
            if (i > 1) deep_row = deep_row .and. p(i - 1) > cap%p_y
            if (i < n) deep_row = deep_row .and. p(i + 1) > cap%p_y
            if (law_max(i) >= not_evaluated) then
               skipped = skipped + 1
               call check(error, deep_row, "psi "//str(psi(k))//", h_max "//str(h_max(i)) &
                  & //": not evaluated outside the deep zone's interior")
            else
               call check(error, law_max(i) == p(i), "psi "//str(psi(k))//", h_max " &
                  & //str(h_max(i))//": law_max "//str(law_max(i))//", law "//str(p(i)))
            end if
            if (allocated(error)) return
            c = cap%p_y - ps_max(i)
            if (.not. p(i) > c) then
               call check(error, shift(i) == 0.0_dp .and. offset(i) == 0.0_dp, "psi " &
                  & //str(psi(k))//", h_max "//str(h_max(i))//": below the cap, shift " &
                  & //str(shift(i))//", offset "//str(offset(i)))
               if (allocated(error)) return
               cycle
            end if
            t = min(cap%p_y, p(i))
            call check(error, abs(offset(i) - (t - c)) <= 1.0e-15_dp*cap%p_y, "psi " &
               & //str(psi(k))//", h_max "//str(h_max(i))//": offset "//str(offset(i)) &
               & //", t - c = "//str(t - c))
            if (allocated(error)) return
            if (.not. p(i) > cap%p_y) then
               call check(error, shift(i) == 0.0_dp, "psi "//str(psi(k))//", h_max " &
                  & //str(h_max(i))//": law below p_y, shift "//str(shift(i)))
               if (allocated(error)) return
               cycle
            end if
            call law%pressure([h_max(i) + shift(i)], p1, d1)
            call check(error, shift(i) > 0.0_dp .and. &
               & abs(p1(1) - cap%p_y) <= 1.0e-12_dp*cap%p_y, "psi "//str(psi(k)) &
               & //", h_max "//str(h_max(i))//": law(h_max + shift) = "//str(p1(1)) &
               & //", p_y "//str(cap%p_y))
            if (allocated(error)) return
         end do
         call check(error, skipped >= 10, "psi "//str(psi(k))//": only " &
            & //str(real(skipped, dp))//" deep points skipped")
         if (allocated(error)) return
         ! the solver's reuse: every other point known from the first call
         known = [(mod(i, 2) == 0, i=1, n)]
         law_max2 = law_max
         call cap%plastic_shifts(law, ps_max, h_max, shift2, offset2, law_max2, known)
         call check(error, all(shift2 == shift) .and. all(offset2 == offset) .and. &
            & all(law_max2 == law_max), "psi "//str(psi(k))//": reuse changed the results")
         if (allocated(error)) return
      end do
   end subroutine test_plastic_shifts_deep

   !> README's rough + cap contact (E-GW + cap, mu 4, sigma = delta_y/100) unloaded from
   !> 2.3 delta_y to 4.92 sigma, where the force is 9.5e-4 P(m) (~2 sigma above its front,
   !> where it rises as Hertz's (delta - delta_f)^(3/2) from a Gaussian foot; doc/benchmarks.md
   !> "Stop 51 (ratio17)", "Stop 52 (local18)"): a history and
   !> unloading solve at rel_tol 1e-6 within 1e-6 P(m) (rel_tol of the turning point's
   !> force, README's meaning of an unloading solve's rel_tol) of a history and solve at
   !> rel_tol 1e-9. The reference shares the code but not its error: its field and mesh
   !> are solved 1000 times tighter, and it moves by 8e-12 P(m) from 1e-8 to 1e-9
   !> (doc/stability.md "Stop 51 (edge17)"). Main's history field at rel_tol 1e-6 put
   !> this solve 2.4e-6 P(m) off, whatever the unloading rel_tol; with the field at
   !> 0.1 rel_tol it is 3.0e-8 off, so the bound 1e-6 separates the two by 30x each way.
   subroutine test_edge_unload(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: p
      type(loading_history) :: hist
      type(solve_result) :: peak, res, ref
      type(egw_error), allocatable :: err
      real(dp), parameter :: m = 230.0_dp, d = 4.92_dp
      character(len=80) :: text
      p = contact_params(model=model_egw, radius=810569.469138702_dp, modulus=1.0_dp, &
         & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
      call load_history(p, solver_options(rel_tol=1.0e-9_dp), m, hist, peak, err)
      call check(error, .not. allocated(err), "reference history")
      if (allocated(error)) return
      call solve_unload(hist, d, ref, err)
      call check(error, .not. allocated(err), "reference unloading")
      if (allocated(error)) return
      call load_history(p, solver_options(rel_tol=1.0e-6_dp), m, hist, peak, err)
      call check(error, .not. allocated(err), "history at 1e-6")
      if (allocated(error)) return
      call solve_unload(hist, d, res, err)
      call check(error, .not. allocated(err), "unloading at 1e-6")
      if (allocated(error)) return
      ! (the force here: between 5e-4 and 2e-3 P(m), near the edge)
      write (text, '(a,es10.3,a,es10.3,a)') "P/P(m) = ", ref%force/peak%force, &
         & ", off by ", (res%force - ref%force)/peak%force, " P(m)"
      call check(error, ref%force > 5.0e-4_dp*peak%force .and. &
         & ref%force < 2.0e-3_dp*peak%force, text)
      if (allocated(error)) return
      call check(error, abs(res%force - ref%force) <= 1.0e-6_dp*peak%force, text)
   end subroutine test_edge_unload

end module test_rough_cap
