!> Scenes, the choice and the builds (the module egw_scene in src/egw/scene/scene.f90 holds the
!> input, its validation and resolution, and declares these procedures): the cheapest
!> model that meets a scene's tolerance, the Hertz check that decides it, and the
!> builds of the chosen tables.
submodule (egw_scene) egw_scene_choice
   use egw_status, only: egw_invalid_argument, egw_not_converged
   use egw_smooth_sphere, only: hertz_force
   use egw_rough_sphere, only: solve_result, solve_contact, validate_options
   use egw_table, only: build_table, build_table_law, table_set_radii
   use egw_table_universal, only: build_universal
   use egw_text, only: real_text, real_text_len
   use egw_impact_regime, only: first_yield_overlap
   use egw_law_pieces, only: law_pieces, zmc_law_pieces
   implicit none

contains

   ! choose_model: interface and documentation in egw_scene (src/egw/scene/scene.f90)
   module procedure choose_model
      real(dp) :: tol
      integer :: ns

      if (.not. allocated(scene%sets)) then
         call fatal_error(error, egw_invalid_argument, "scene: not resolved (resolve_scene)")
         return
      end if
      call validate_options(options, error)
      if (allocated(error)) return
      tol = scene%input%tol
      ns = size(scene%sets)
      choice%n_sets = ns
      choice%mu_min = minval(scene%sets%mu)
      choice%mu_max = maxval(scene%sets%mu)
      if (all(scene%sets%sigma > 0.0_dp)) then
         choice%x_min = minval(scene%delta_min/scene%sets%sigma)
         choice%x_max = maxval(scene%delta_max/scene%sets%sigma)
      end if
      call yield_check(scene, choice)
      if (scene%input%model == model_hertz .or. scene%input%sigma_max == 0.0_dp) then
         choice%kind = choice_hertz
         choice%error_bound = 0.0_dp
         if (choice%cap_matters) then
            choice%reason = "smooth spheres (model Hertz or sigma = 0) with flow_pressure: " &
               & //"delta_max reaches "//num(choice%yield_ratio)//" delta_y, beyond first " &
               & //"yield: Hertz + cap (the bulk yields and dissipates; the Hertz closed " &
               & //"form holds up to delta_y only)"
         else
            choice%reason = "smooth spheres (model Hertz or sigma = 0): Hertz is exact"
            if (choice%yield_ratio > 0.0_dp) choice%reason = choice%reason// &
               & " (delta_max <= delta_y: the flow-pressure cap never acts)"
         end if
         return
      end if
      if (scene%input%model == model_flat_law) then
         if (ns /= 1 .or. scene%continuous) then
            call fatal_error(error, egw_unsupported, "flat_law: a flat-law scene builds " &
               & //"the table of one pair (one particle type or one radius, one material)" &
               & //"; this one has "//int_str(ns)//" parameter sets (build each pair's " &
               & //"table with egw_table_build_flat_law, or run egw-table once per pair)")
            return
         end if
         choice%kind = choice_table
         choice%error_bound = tol
         choice%reason = "rough-flat law "//trim(scene%input%flat_law)//" in place of " &
            & //"the summit model: one 1-D table of the law (no Hertz check)"
         return
      end if

      call scene_hertz_error(scene, options, choice%hertz_error, choice%n_solves, error)
      if (allocated(error)) return
      choice%hertz_relative_to_max = scene%input%delta_min <= 0.0_dp
      if (choice%hertz_error <= tol) then
         choice%kind = choice_hertz
         choice%error_bound = choice%hertz_error
         choice%reason = "roughness changes the force by at most "// &
            & num(choice%hertz_error)//hertz_measure(choice)//" <= tol = "// &
            & num(tol)
      else if (ns == 1 .and. .not. scene%continuous) then
         choice%kind = choice_table
         choice%error_bound = tol
         choice%reason = "roughness changes the force by up to "// &
            & num(choice%hertz_error)//hertz_measure(choice)//" > tol; "// &
            & "one parameter set: one 1-D table"
      else
         choice%kind = choice_universal
         choice%error_bound = tol
         choice%reason = "roughness changes the force by up to "// &
            & num(choice%hertz_error)//hertz_measure(choice)//" > tol; "// &
            & int_str(ns)//" parameter sets"//merge(" (radius range)", "               ", &
            & scene%continuous)
         choice%reason = trim(choice%reason)//": the universal table over mu in ["// &
            & num(choice%mu_min)//", "//num(choice%mu_max)// &
            & "], delta/sigma in ["//num(choice%x_min)//", "// &
            & num(choice%x_max)//"]"
      end if
      if (choice%cap_matters) choice%reason = choice%reason//" (against Hertz + cap: "// &
         & "delta_max reaches "//num(choice%yield_ratio)//" delta_y, the bulk yields)"
   end procedure choose_model

   !> The flow-pressure cap (issue 32): largest delta_max/delta_y of the sets with a
   !> flow_pressure, delta_y = (pi p_y/(2 E*))**2 R (Hertz's peak pressure reaches p_y);
   !> beyond 1 the cap matters (for an impact: speed above v_y, egw_impact_regime).
   pure subroutine yield_check(scene, choice)
      type(contact_scene), intent(in) :: scene
      type(model_choice), intent(inout) :: choice
      integer :: s
      choice%yield_ratio = 0.0_dp
      do s = 1, size(scene%sets)
         if (scene%sets(s)%flow_pressure > 0.0_dp) choice%yield_ratio = max( &
            & choice%yield_ratio, scene%delta_max(s)/first_yield_overlap(scene%sets(s)))
      end do
      choice%cap_matters = choice%yield_ratio > 1.0_dp
   end subroutine yield_check

   pure function hertz_measure(choice) result(str)
      type(model_choice), intent(in) :: choice
      character(len=merge(16, 11, choice%hertz_relative_to_max)) :: str  ! not deferred
      if (choice%hertz_relative_to_max) then
         str = " of P(delta_max)"
      else
         str = " (relative)"
      end if
   end function hertz_measure

   ! scene_hertz_error: interface and documentation in egw_scene (src/egw/scene/scene.f90)
   module procedure scene_hertz_error
      type(solver_options) :: opts
      real(dp), allocatable :: deltas(:, :), force(:, :), p_ref(:), smooth(:, :)
      integer, allocatable :: stat(:, :, :), n_pts(:)
      !> the failed solves' own messages (what failed: Newton, the mesh's node limit, ...)
      character(len=400), allocatable :: why(:, :, :)
      integer :: ns, s, i, idx, np, nmax, i0, k
      real(dp) :: lo, hi, e
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      !> each set's ZMC law tabulated once (EP-GW, psi > 0; else empty): its solves then
      !> evaluate Chebyshev pieces (within 5e-13 of the law) instead of GW's integral
      !> (~0.55e9 instructions of a psi 1 + cap build's start; the table costs ~5 ms a set)
      type(law_pieces), allocatable :: laws(:)
      !> a set's smooth sphere with its cap (Hertz + cap): the reference of a set with a
      !> flow_pressure, so that the measure is the roughness's (against the closed form the
      !> capped rough force differed by the cap's own effect: 0.18 of P(delta_max) at 4
      !> delta_y where roughness alone is 5.5e-3; audit25)
      type(contact_params) :: capped

      worst = 0.0_dp
      n_solves = 0
      ns = size(scene%sets)
      opts = options
      opts%n_threads = 1
      opts%rel_tol = min(options%rel_tol, 0.1_dp*scene%input%tol)
      nmax = 0
      allocate (n_pts(ns))
      do s = 1, ns
         n_pts(s) = 0
         if (scene%delta_max(s) <= 0.0_dp) cycle  ! no overlap at all: see below
         call sample_range(scene, s, lo, hi)
         n_pts(s) = max(2, ceiling(samples_per_decade*log10(hi/lo)) + 1)
         if (scene%delta_min(s) <= 0.0_dp) n_pts(s) = n_pts(s) + 1
         nmax = max(nmax, n_pts(s))
      end do
      allocate (deltas(nmax, ns), force(nmax, ns), stat(nmax, ns, 2), p_ref(ns), &
         & why(nmax, ns, 2))
      allocate (smooth(nmax, ns))
      allocate (laws(ns))
      do s = 1, ns
         associate (p => scene%sets(s))
            if (n_pts(s) > 0 .and. p%model == model_epgw .and. p%psi > 0.0_dp) laws(s) = &
               & zmc_law_pieces(p%psi, p%hardness_coeff, p%plastic_ratio)
         end associate
      end do
      deltas = 0.0_dp
      force = 0.0_dp
      smooth = 0.0_dp
      stat = 0
      do s = 1, ns
         if (n_pts(s) == 0) cycle
         call sample_range(scene, s, lo, hi)
         ! geometric from lo to hi, after delta = 0 when the scene starts separated
         i0 = merge(1, 0, scene%delta_min(s) <= 0.0_dp)
         np = n_pts(s) - i0
         do i = 1, np
            deltas(i0 + i, s) = lo*(hi/lo)**(real(i - 1, dp)/real(np - 1, dp))
         end do
         deltas(n_pts(s), s) = hi
         n_solves = n_solves + n_pts(s)
      end do
      ! the deepest points first, a point's rough solve and its capped smooth one as
      ! separate iterations (a solve costs more the deeper its overlap: in increasing
      ! order, a point's pair on one thread, the dearest came last); each iteration
      ! writes only its own entries
      !$omp parallel do schedule(dynamic) private(s, i, k, res, err, capped)
      do idx = 2*nmax*ns, 1, -1
         k = mod(idx - 1, 2) + 1   ! 1: the rough solve, 2: its smooth reference
         i = (idx - 1)/(2*ns) + 1
         s = mod((idx - 1)/2, ns) + 1
         if (i <= n_pts(s)) then
            if (k == 1) then
               ! (the force only: no moved-mesh stiffness, the same force to the bit;
               ! README's E-GW + cap scene spent 0.33 s of the check's 0.41 s CPU in its
               ! solve at 346 sigma, where the capped zone holds the Hertz edge, 0.3 s of
               ! it in that stiffness: the check's wall was that one solve)
               call solve_contact(scene%sets(s), opts, deltas(i, s), res, err, laws(s), &
                  & stiffness=.false.)
               force(i, s) = res%force
            else if (scene%sets(s)%flow_pressure > 0.0_dp) then
               capped = scene%sets(s)
               capped%model = model_hertz
               capped%sigma = 0.0_dp
               call solve_contact(capped, opts, deltas(i, s), res, err)
               smooth(i, s) = res%force
            else
               smooth(i, s) = hertz_force(deltas(i, s), scene%sets(s)%radius, &
                  & scene%sets(s)%modulus)
            end if
            if (allocated(err)) then
               stat(i, s, k) = err%stat
               why(i, s, k) = err%message
            end if
         end if
      end do
      !$omp end parallel do
      do s = 1, ns
         if (n_pts(s) == 0) then
            ! delta_max <= 0: Hertz gives no force at all where the rough force is
            ! positive, an error of 1 in the measure relative to P(delta_max)
            worst = max(worst, 1.0_dp)
            cycle
         end if
         do i = 1, n_pts(s)
            if (any(stat(i, s, :) /= 0) .or. .not. (ieee_is_finite(force(i, s)) .and. &
               & force(i, s) >= 0.0_dp .and. ieee_is_finite(smooth(i, s)))) then
               call fatal_error(error, egw_not_converged, "delta = "// &
                  & format_real(deltas(i, s))//": full solve failed in the Hertz check "// &
                  & "of parameter set "//int_str(s))
               ! (the rough solve's message first, as when the pair ran in that order)
               k = merge(1, 2, stat(i, s, 1) /= 0)
               if (stat(i, s, k) /= 0) error%message = error%message//" ("// &
                  & trim(why(i, s, k))//")"
               return
            end if
         end do
         associate (p => scene%sets(s))
            if (scene%delta_min(s) <= 0.0_dp) then
               p_ref(s) = force(n_pts(s), s)
               do i = 1, n_pts(s)
                  e = abs(smooth(i, s) - force(i, s))/p_ref(s)
                  worst = max(worst, e)
               end do
            else
               do i = 1, n_pts(s)
                  e = abs(smooth(i, s)/force(i, s) - 1.0_dp)
                  worst = max(worst, e)
               end do
            end if
         end associate
      end do
   end procedure scene_hertz_error

   !> Positive overlaps sampled by the Hertz check of set s: [max(delta_min, 1e-12 sigma),
   !> delta_max] when delta_min > 0, else [min(sigma/100, delta_max/10), delta_max].
   pure subroutine sample_range(scene, s, lo, hi)
      type(contact_scene), intent(in) :: scene
      integer, intent(in) :: s
      real(dp), intent(out) :: lo, hi
      hi = scene%delta_max(s)
      if (scene%delta_min(s) > 0.0_dp) then
         ! below 1e-12 sigma the rough force is P(0) to ~1e-18 and the Hertz force ~1e-18
         ! of it: the Hertz error is that at 1e-12 sigma (bounds the samples: a
         ! delta_min = 1e-300 would ask for 1200 solves)
         lo = min(hi, max(scene%delta_min(s), 1.0e-12_dp*scene%sets(s)%sigma))
      else
         lo = min(0.01_dp*scene%sets(s)%sigma, 0.1_dp*hi)
      end if
   end subroutine sample_range

   ! build_scene_tables: interface and documentation in egw_scene (src/egw/scene/scene.f90)
   ! (a full header: gfortran 12 loses the interface of a procedure dummy in a
   ! `module procedure` body)
   module subroutine build_scene_tables(scene, choice, options, tables, error, progress, &
      & law)
      type(contact_scene), intent(in) :: scene
      type(model_choice), intent(in) :: choice
      type(solver_options), intent(in) :: options
      type(scene_tables), intent(out) :: tables
      type(egw_error), allocatable, intent(out) :: error
      !> called as the build goes (see egw_table's table_progress; not called for Hertz)
      procedure(table_progress), optional :: progress
      class(flat_law), intent(in), optional :: law   !< a flat-law scene's law
      real(dp) :: mu_lo, mu_hi
      integer :: j

      tables%kind = choice%kind
      select case (choice%kind)
      case (choice_hertz)
         tables%measured_error = choice%error_bound
      case (choice_table)
         if (scene%input%model == model_flat_law) then
            if (.not. present(law)) then
               call fatal_error(error, egw_invalid_argument, "law: a flat-law scene's " &
                  & //"table needs its law (read from "//trim(scene%input%flat_law)//")")
               return
            end if
            call build_table_law(scene%sets(1), law, options, scene%delta_min(1), &
               & scene%delta_max(1), scene%input%tol, tables%table, error, progress)
         else
            call build_table(scene%sets(1), options, scene%delta_min(1), &
               & scene%delta_max(1), scene%input%tol, tables%table, error, progress)
         end if
         if (allocated(error)) return
         call table_set_radii(tables%table, scene%radius1(1), scene%radius2(1), error)
         if (allocated(error)) return
         tables%measured_error = tables%table%max_force_error
         tables%n_nodes = size(tables%table%delta)
      case (choice_universal)
         mu_lo = choice%mu_min
         mu_hi = choice%mu_max
         if (mu_hi <= mu_lo*(1.0_dp + 1.0e-12_dp)) then
            mu_lo = mu_lo/1.05_dp
            mu_hi = mu_hi*1.05_dp
         end if
         call build_universal(scene%input%model, scene%input%psi, &
            & scene%input%hardness_coeff, scene%input%plastic_ratio, options, mu_lo, mu_hi, &
            & choice%x_min, choice%x_max, scene%input%tol, tables%universal, error, &
            & progress)
         if (allocated(error)) return
         tables%measured_error = tables%universal%max_mu_error
         do j = 1, tables%universal%n_mu
            tables%measured_error = max(tables%measured_error, &
               & tables%universal%slices(j)%max_force_error)
         end do
         tables%n_nodes = tables%universal%n_mu*size(tables%universal%slices(1)%delta)
      case default
         call fatal_error(error, egw_invalid_argument, "choice%kind = "// &
            & int_str(choice%kind)//": unknown")
      end select
   end subroutine build_scene_tables

   ! build_pair_tables: interface and documentation in egw_scene (src/egw/scene/scene.f90)
   ! (a full header: gfortran 12 loses the interface of a procedure dummy in a
   ! `module procedure` body)
   module subroutine build_pair_tables(scene, options, tables, error, progress)
      type(contact_scene), intent(in) :: scene
      type(solver_options), intent(in) :: options
      type(force_table), allocatable, intent(out) :: tables(:)
      type(egw_error), allocatable, intent(out) :: error
      procedure(table_progress), optional :: progress
      type(force_table), allocatable :: built(:)
      integer :: s, i, j, k, n
      if (.not. allocated(scene%sets)) then
         call fatal_error(error, egw_invalid_argument, "scene: not resolved (resolve_scene)")
         return
      end if
      if (scene%continuous .or. scene%input%sigma_min /= scene%input%sigma_max) then
         call fatal_error(error, egw_unsupported, "scene: a radius or sigma range has no "// &
            & "finite set of type pairs; per-pair tables need particle types and one sigma")
         return
      end if
      allocate (built(size(scene%sets)))
      do s = 1, size(scene%sets)
         call build_table(scene%sets(s), options, scene%delta_min(s), scene%delta_max(s), &
            & scene%input%tol, built(s), error, progress)
         if (allocated(error)) then
            error%message = "parameter set "//int_str(s)//": "//error%message
            return
         end if
      end do
      n = scene%input%n_types
      allocate (tables(size(scene%pair_set)))
      k = 0
      do i = 1, n
         do j = i, n
            k = k + 1
            tables(k) = built(scene%pair_set(k))
            call table_set_radii(tables(k), scene%input%radius(i), scene%input%radius(j), &
               & error)
            if (allocated(error)) return
         end do
      end do
   end subroutine build_pair_tables

   !> Short form of a number for messages (4 significant digits).
   pure function num(x) result(str)
      real(dp), intent(in) :: x
      character(len=real_text_len(x, 4, 2)) :: str  ! not deferred: see egw_text
      str = real_text(x, 4, 2)  ! as ES11.4, without an internal WRITE (egw_text)
   end function num

end submodule egw_scene_choice
