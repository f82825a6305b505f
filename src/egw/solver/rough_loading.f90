!> The loading solves behind the public doors, in the caller's units: solve_contact (Hertz
!> in closed form, the smooth sphere's flow-pressure cap, the rough models' discrete solve
!> with the small-sigma route) and solve_contact_law (a rough-flat law of the caller's).
!> doc/theory.md §5, §11, §12.
module egw_rough_loading
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp, pi
   use egw_status, only: egw_error, egw_invalid_argument, egw_invalid_parameter, fatal_error, &
      & format_real
   use egw_params, only: contact_params, model_hertz, model_flat_law, pressure_unit, product4
   use egw_progress, only: progress_begin, progress_end, progress_report
   use egw_smooth_sphere, only: hertz_pressure, hertz_force, hertz_stiffness, &
      & hertz_contact_radius
   use egw_flat_law, only: flat_law
   use egw_law_pieces, only: law_pieces
   use egw_cap_sphere, only: cap_history
   use egw_sphere_solver, only: solver_options, scaled_problem, discrete_solution, scaled, &
      & normal, negligible
   use egw_rough_solve, only: solve_result, check_input, smooth_capped, cap_loading, solve_rough
   use egw_small_sigma_route, only: small_sigma_loading
   implicit none
   private

   public :: solve_contact, solve_contact_law

contains

   !> Force, stiffness, effective contact radius and maximum pressure at overlap delta
   !> (> 0 overlap, < 0 separation) for any model of params. Hertz (and sigma = 0) in
   !> closed form; the rough models by the discrete solve, refined until the two-level
   !> estimate of the force error is below options%rel_tol/2 (n_radial = 0) or on the mesh
   !> of about n_radial nodes. Fails with egw_not_converged rather than return a doubtful
   !> answer. E-GW (EP-GW at psi = 0) with the cap at sigma/delta_y <= 2e-6 whose
   !> discrete solve does not converge: the asymptotic route (small_sigma_loading,
   !> doc/theory.md §12), if its estimate meets rel_tol; at sigma/delta_y <= 1e-7 a
   !> converged solve of those models is checked against that route
   !> (small_sigma_loading).
   !> Reports progress (egw_progress) as one long call, stage "solve".
   subroutine solve_contact(params, options, delta, result, error, loading, stiffness)
      !> the contact (model, R, E*, sigma, mu, psi, K, rho_p)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options   !< mesh, tolerance, method and threads
      real(dp), intent(in) :: delta   !< overlap [length]: > 0 pressed together, < 0 apart
      !> force [force] >= 0, stiffness [force/length], contact radius [length], ...
      type(solve_result), intent(out) :: result
      !> allocated on failure (result is then not defined)
      type(egw_error), allocatable, intent(out) :: error
      !> GW's ZMC law of params tabulated once (zmc_law_pieces): the law where its
      !> parameters are params' (a hysteresis build's loading table), else ignored
      type(law_pieces), intent(in), optional :: loading
      !> .false.: a rough model's stiffness with the cap may be the implicit one (~1e-3
      !> off; saves solve_rough's moved-mesh solves, up to 0.9 of a loading solve where the
      !> capped zone holds the Hertz edge), for callers that read the force only (the
      !> scene's Hertz check); absent: .true.
      logical, intent(in), optional :: stiffness
      if ((params%model == model_hertz .or. params%sigma == 0.0_dp) .and. .not. &
         & params%flow_pressure > 0.0_dp) then
         ! (the closed form, ~80 ns: no progress to report, and no 5 ns spent on it)
         call contact_solve(params, options, delta, result, error, loading)
         return
      end if
      call progress_begin("solve")
      call contact_solve(params, options, delta, result, error, loading, stiffness)
      call progress_end("solve")
   end subroutine solve_contact

   !> solve_contact's work.
   subroutine contact_solve(params, options, delta, result, error, loading, stiffness)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta
      type(solve_result), intent(out) :: result
      type(egw_error), allocatable, intent(out) :: error
      type(law_pieces), intent(in), optional :: loading
      logical, intent(in), optional :: stiffness
      type(scaled_problem) :: prob
      type(discrete_solution) :: sol
      type(cap_history) :: cap

      call check_input(params, options, delta, error)
      if (allocated(error)) return
      if (smooth_capped(params, delta)) then
         call cap_loading(params, options, delta, cap, result, error, "delta")
         return
      end if
      if (params%model == model_hertz .or. params%sigma == 0.0_dp) then
         result%force = hertz_force(delta, params%radius, params%modulus)
         result%stiffness = hertz_stiffness(delta, params%radius, params%modulus)
         result%contact_radius = hertz_contact_radius(delta, params%radius)
         result%max_pressure = hertz_pressure(0.0_dp, delta, params%radius, params%modulus)
         ! p0 = (2/pi) E sqrt(delta/R): 2E/(pi R) alone may overflow where p0 does not
         if (delta > 0.0_dp .and. .not. normal(result%max_pressure)) result%max_pressure = &
            & product4(2.0_dp/pi, params%modulus, sqrt(delta), 1.0_dp/sqrt(params%radius))
         result%method_used = options%method
         if (.not. ieee_is_finite(result%max_pressure)) call fatal_error(error, &
            & egw_invalid_argument, "delta = "//format_real(delta)//": the Hertz peak " &
            & //"pressure (2/pi) E sqrt(delta/R) exceeds the largest double")
         return
      end if

      prob = scaled(params, delta, loading)
      if (negligible(prob)) then
         ! Beyond ~37 sigma apart the summit pressure underflows: the force is below
         ! 1e-250 E sqrt(R) sigma**1.5 and is returned as 0 with est_rel_err = 1 (honest:
         ! zero has relative error 1).
         result%method_used = options%method
         result%est_rel_err = 1.0_dp
         return
      end if
      call solve_rough(params, options, prob, sol, result, error, moved_rate=stiffness)
      call progress_report(0.2_dp, "solve")
      call small_sigma_loading(params, options, delta, prob, result, error)
   end subroutine contact_solve

   !> Loading solve of a sphere whose local pressure is a rough-flat law of the caller's
   !> (a tabulated, Persson or BEM law; doc/theory.md §11): the law gives the whole
   !> pressure p(u) at the local mean separation u(r) = r**2/(2R) - delta + w(r), w the
   !> half-space deflection, so delta is the overlap with the law's reference plane (the
   !> mean plane of the heights for those laws). Of params only radius and modulus are
   !> used (R and E* of the pair); the solve is scaled by the law's length. Result and
   !> errors as solve_contact; also egw_invalid_parameter when the law was made with
   !> another E* than params%modulus.
   subroutine solve_contact_law(params, law, options, delta, result, error)
      type(contact_params), intent(in) :: params   !< radius R and modulus E*
      class(flat_law), intent(in) :: law           !< the rough-flat law p(u)
      type(solver_options), intent(in) :: options  !< mesh, tolerance, method and threads
      real(dp), intent(in) :: delta   !< overlap [length] with the law's reference plane
      type(solve_result), intent(out) :: result   !< force, stiffness, radius ... at delta
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      type(contact_params) :: lp
      type(scaled_problem) :: prob
      type(discrete_solution) :: sol

      lp = contact_params(model=model_flat_law, radius=params%radius, &
         & modulus=params%modulus, sigma=law%length(), flow_pressure=params%flow_pressure)
      call check_input(lp, options, delta, error, allow_flat_law=.true.)
      if (allocated(error)) then
         error%message = "flat law of length "//format_real(law%length())//": " &
            & //error%message
         return
      end if
      if (law%modulus() > 0.0_dp .and. abs(params%modulus - law%modulus()) > &
         & 1.0e-12_dp*law%modulus()) then
         call fatal_error(error, egw_invalid_parameter, "modulus = " &
            & //format_real(params%modulus)//": the flat law was made with E* = " &
            & //format_real(law%modulus())//"; the sphere must have the same")
         return
      end if
      prob = scaled(lp, delta)
      call law%rescaled(law%length(), pressure_unit(lp), prob%law)
      ! (the cap's root is the given law's)
      if (allocated(prob%cap)) call prob%cap%prepare(prob%law)
      if (negligible(prob)) then
         result%method_used = options%method
         result%est_rel_err = 1.0_dp
         return
      end if
      call solve_rough(lp, options, prob, sol, result, error)
   end subroutine solve_contact_law

end module egw_rough_loading
