!> The universal table: P/(E sqrt(R) sigma^(3/2)) depends only on x = delta/sigma and mu
!> for the elastic models (and on psi, K, rho_p for EP-GW, fixed per table; doc/theory.md §5).
!> It holds one 1-D table ("slice", built with R = E = sigma = 1) per mu on a grid uniform
!> in ln mu, all with one common cut-off x_c and one set of x nodes. Like a 1-D table
!> (egw_table), a slice interpolates ln p in the separated tail (intervals ending at
!> x <= 0, rough models) and p itself in the contact range; the flag depends on x only,
!> so it is the same for every slice. Across mu the slices' cubics are combined per
!> interval with the 4-point Lagrange cubic in ln mu: in ln p in the tail (exact where p
!> is a power of mu, as in the far tail where p is proportional to mu) and in p in the
!> contact range (exact where p does not depend on mu, as for Hertz). Evaluating the
!> contact range then needs no exp, and neither does the exact per-contact slice
!> (universal_slice), which costs what a 1-D table costs.
!> Error budget: the slices are built to rel_tol/2 in x; the mu grid is refined (to the
!> size the h^4 law of the measured error asks for) until the whole interpolant agrees
!> with solves at mid-grid mu (where the Lagrange error in mu peaks) to rel_tol.
module egw_table_universal
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_invalid_argument, egw_invalid_parameter, &
      & egw_not_converged, egw_out_of_range, fatal_error, format_real, int_str
   use egw_params, only: contact_params, validate_params, overlap_ratio_max, product4, &
      & force_unit, stiffness_unit, length_unit, refuse_flow_pressure
   use egw_rough_sphere, only: solver_options, solve_result, solve_contact
   use egw_table_ends, only: deep_force
   use egw_table, only: force_table, build_tables_shared, table_find_cutoff, deep_law_floor_x, &
      & below_cutoff, &
      & table_interval, table_prepare, table_eval, table_progress, deep_coefficient
   implicit none
   private

   public :: build_universal, universal_eval, universal_prepare, universal_slice_params, &
      & universal_nodes_shared, universal_slice, move_universal

   !> At most this many mu nodes (a grid that needs more is not converging).
   integer, parameter :: max_mu_nodes = 257
   !> Check points in x per mu interval when testing the mu interpolation.
   integer, parameter :: n_check_x = 16

   !> Universal (dimensionless) table over x = delta/sigma and mu.
   type, public :: universal_table
      integer :: model = 0
      real(dp) :: psi = 0.0_dp, hardness_coeff = 0.6_dp, plastic_ratio = 54.0_dp
      real(dp) :: rel_tol = 0.0_dp
      real(dp) :: x_cut = 0.0_dp          !< common cut-off in x: rough models 0 below
      real(dp) :: x_max = 0.0_dp          !< upper end in x
      real(dp) :: mu_min = 0.0_dp, mu_max = 0.0_dp
      integer :: n_mu = 0                  !< mu_j = mu_min (mu_max/mu_min)^((j-1)/(n_mu-1))
      real(dp) :: max_mu_error = 0.0_dp   !< max rel. error at the mid-grid check solves
      real(dp) :: log_mu_min = 0.0_dp, inv_dlog_mu = 0.0_dp
      !> intervals 1..n_log interpolate ln p, the others p (the slices' common n_log;
      !> n - 1 in tables written before the contact range was interpolated in p)
      integer :: n_log = 0
      type(force_table), allocatable :: slices(:)
      !> (0:3, n_mu, n-1): cubic of ln p (intervals <= n_log) or p in t = x - x_i for
      !> every slice and interval, the 4 slices of a stencil contiguous (derived by
      !> universal_prepare)
      real(dp), allocatable :: coef(:, :, :)
   end type universal_table

contains

   !> Build the universal table of a model over mu in [mu_min, mu_max] (mu_max > mu_min)
   !> and x = delta/sigma up to x_max (or egw_table's deep_law_floor_x, if higher), starting where the force has fallen to rel_tol times
   !> its reference (see egw_table) for every grid mu, or at x_min if that is lower.
   !> The optional progress hook (egw_table's table_progress) counts solves of the slice
   !> builds and their mu checks over all rounds of mu refinement as one monotone
   !> sequence (the cut-off searches are not counted: they run in parallel); the total
   !> grows when a round rebuilds on a finer mu grid.
   subroutine build_universal(model, psi, hardness_coeff, plastic_ratio, options, mu_min, &
      & mu_max, x_min, x_max, rel_tol, table, error, progress)
      integer, intent(in) :: model   !< model_gw, model_egw or model_epgw
      real(dp), intent(in) :: psi   !< plasticity index (EP-GW; 0 elastic)
      real(dp), intent(in) :: hardness_coeff   !< ZMC K, in (0, 1)
      real(dp), intent(in) :: plastic_ratio   !< ZMC rho_p = delta_p/delta_ep, > 1
      type(solver_options), intent(in) :: options   !< of the solves
      real(dp), intent(in) :: mu_min   !< smallest mu tabulated
      real(dp), intent(in) :: mu_max   !< largest mu tabulated (> mu_min)
      real(dp), intent(in) :: x_min   !< smallest delta/sigma of interest
      real(dp), intent(in) :: x_max   !< largest delta/sigma tabulated
      real(dp), intent(in) :: rel_tol   !< interpolation tolerance of the force, relative
      type(universal_table), intent(out) :: table   !< the table; empty on error
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      procedure(table_progress), optional :: progress   !< optional hook (table_progress)
      type(universal_table) :: u
      type(solver_options) :: opts
      real(dp), allocatable :: mus(:)
      real(dp) :: worst
      integer :: n_solves

      call check_universal_request(model, psi, hardness_coeff, plastic_ratio, mu_min, &
         & mu_max, x_min, x_max, error)
      if (allocated(error)) return
      opts = options
      opts%n_threads = 1
      opts%rel_tol = min(options%rel_tol, 0.1_dp*rel_tol)

      u%model = model
      u%psi = psi
      u%hardness_coeff = hardness_coeff
      u%plastic_ratio = plastic_ratio
      u%rel_tol = rel_tol
      ! at least up to where the deep-overlap law above the last node holds its 1 %
      u%x_max = max(x_max, deep_law_floor_x(model))
      u%mu_min = mu_min
      u%mu_max = mu_max
      ! 4 nodes per decade to start (and at least 4 for the cubic stencil)
      u%n_mu = max(4, ceiling(4*log10(mu_max/mu_min)) + 1)
      mus = grid(mu_min, mu_max, u%n_mu)
      call common_cutoff(u, mus, opts, x_min, error)
      if (allocated(error)) return

      n_solves = 0
      do
         call build_mu_grid(u, mus, opts, worst, n_solves, error, progress)
         if (allocated(error)) return
         u%max_mu_error = worst
         if (worst <= rel_tol) exit
         if (u%n_mu >= max_mu_nodes) then
            call fatal_error(error, egw_not_converged, "rel_tol = "//format_real(rel_tol)// &
               & " not reached: the mu interpolation error is still "//format_real(worst)// &
               & " with the maximum number of mu nodes ("//int_str(u%n_mu)//")")
            return
         end if
         ! rebuild on a finer grid (shared nodes must be re-chosen for all slices). The
         ! 4-point Lagrange error in ln mu falls like h^4: jump straight to the grid
         ! that should bring it to 0.4 rel_tol (the slices' own x error is <= 0.5
         ! rel_tol), with 10 % margin, instead of doubling (doubling built 13 + 25 + 49
         ! + 97 slices where ~75 suffice for mu in [0.1, 100] at 1e-6)
         u%n_mu = min(max_mu_nodes, max(u%n_mu + 2, 1 + ceiling(1.1_dp*(u%n_mu - 1)* &
            & sqrt(sqrt(worst/(0.4_dp*rel_tol))))))
         mus = grid(mu_min, mu_max, u%n_mu)
      end do
      call move_universal(u, table)
   end subroutine build_universal

   !> The arguments of build_universal that its solves cannot check: the mu range, the
   !> summit laws at both ends of it, and the x range (the solver's, doc/theory.md §5).
   subroutine check_universal_request(model, psi, hardness_coeff, plastic_ratio, mu_min, &
      & mu_max, x_min, x_max, error)
      integer, intent(in) :: model
      real(dp), intent(in) :: psi, hardness_coeff, plastic_ratio, mu_min, mu_max, x_min, x_max
      type(egw_error), allocatable, intent(out) :: error
      if (.not. (ieee_is_finite(mu_min) .and. mu_min > 0.0_dp)) then
         call fatal_error(error, egw_invalid_argument, "mu_min = "//format_real(mu_min)// &
            & ": must be finite and > 0")
         return
      end if
      if (.not. (ieee_is_finite(mu_max) .and. mu_max > mu_min)) then
         call fatal_error(error, egw_invalid_argument, "mu_max = "//format_real(mu_max)// &
            & ": must be finite and > mu_min")
         return
      end if
      call validate_params(universal_slice_params(model, psi, hardness_coeff, &
         & plastic_ratio, mu_min), error)
      if (allocated(error)) return
      call validate_params(universal_slice_params(model, psi, hardness_coeff, &
         & plastic_ratio, mu_max), error)
      if (allocated(error)) return
      if (.not. ieee_is_finite(x_min)) then
         call fatal_error(error, egw_invalid_argument, "x_min = "//format_real(x_min)// &
            & ": must be finite")
         return
      end if
      if (.not. (ieee_is_finite(x_max) .and. x_max > x_min .and. &
         & x_max <= overlap_ratio_max)) then
         call fatal_error(error, egw_invalid_argument, "x_max = "//format_real(x_max)// &
            & ": must be > x_min and <= "//format_real(overlap_ratio_max)// &
            & " (the solver's range of delta/sigma)")
         return
      end if
   end subroutine check_universal_request

   !> The common cut-off u%x_cut (doc/theory.md §7 "Tables"): the lowest of the cut-offs of
   !> the slices at mus (where the force has fallen to rel_tol of its reference), or x_min.
   subroutine common_cutoff(u, mus, opts, x_min, error)
      type(universal_table), intent(inout) :: u
      real(dp), intent(in) :: mus(:)
      type(solver_options), intent(in) :: opts
      real(dp), intent(in) :: x_min
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: xc(size(mus)), pref(size(mus))
      integer :: stat(size(mus)), j
      ! the searches are serial chains of solves: run the mu nodes in parallel
      !$omp parallel do schedule(dynamic)
      do j = 1, size(mus)
         call find_cutoff_quiet(universal_slice_params(u%model, u%psi, u%hardness_coeff, &
            & u%plastic_ratio, mus(j)), opts, x_min, u%x_max, u%rel_tol, xc(j), pref(j), &
            & stat(j))
      end do
      !$omp end parallel do
      do j = 1, size(mus)
         if (stat(j) /= 0) then
            ! redo the first failure serially to recover its message
            call table_find_cutoff(universal_slice_params(u%model, u%psi, u%hardness_coeff, &
               & u%plastic_ratio, mus(j)), opts, x_min, u%x_max, u%rel_tol, xc(j), pref(j), &
               & error)
            if (.not. allocated(error)) call fatal_error(error, stat(j), "mu = "// &
               & format_real(mus(j))//": cut-off search failed")
            return
         end if
      end do
      u%x_cut = minval(xc)
   end subroutine common_cutoff

   !> One round of the universal table on the mu grid mus (doc/theory.md §7 "Tables"): the
   !> slices on one set of x nodes, then the mu interpolation checked against solves at
   !> mid-grid mu (worst: its largest relative error). n_solves counts the solves.
   subroutine build_mu_grid(u, mus, opts, worst, n_solves, error, progress)
      type(universal_table), intent(inout) :: u
      real(dp), intent(in) :: mus(:)
      type(solver_options), intent(in) :: opts
      real(dp), intent(out) :: worst
      integer, intent(inout) :: n_solves
      type(egw_error), allocatable, intent(out) :: error
      procedure(table_progress), optional :: progress
      type(contact_params), allocatable :: params(:)
      real(dp), allocatable :: xs(:)
      integer :: j, n_before
      ! all slices on one set of x nodes (one lookup serves all mu at evaluation)
      n_before = n_solves  ! (not the same actual for solves_before and solves)
      if (allocated(u%slices)) deallocate (u%slices)
      allocate (u%slices(u%n_mu))
      params = [(universal_slice_params(u%model, u%psi, u%hardness_coeff, u%plastic_ratio, &
         & mus(j)), j=1, u%n_mu)]
      ! log_space = .false.: ln p in the tail, p in the contact range (as build_table)
      call build_tables_shared(params, opts, u%x_cut, u%x_max, 0.5_dp*u%rel_tol, .false., &
         & u%slices, error, progress, n_before, n_solves)
      if (allocated(error)) return
      call universal_prepare(u)
      ! check the mu interpolation at mid-grid mu against solves
      xs = check_points(u%x_cut, u%x_max, u%slices(1)%delta)
      call mid_grid_error(u, opts, xs, worst, error)
      if (allocated(error)) return
      ! the mu check: one solve per mid-grid mu and check point
      n_solves = n_solves + (u%n_mu - 1)*size(xs)
      if (present(progress)) call progress(n_solves, n_solves)
   end subroutine build_mu_grid

   !> table_find_cutoff with the status only (for use inside a parallel loop).
   subroutine find_cutoff_quiet(params, opts, x_min, x_max, rel_tol, cutoff, p_ref, stat)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: opts
      real(dp), intent(in) :: x_min, x_max, rel_tol
      real(dp), intent(out) :: cutoff, p_ref
      integer, intent(out) :: stat
      type(egw_error), allocatable :: error
      call table_find_cutoff(params, opts, x_min, x_max, rel_tol, cutoff, p_ref, error)
      stat = 0
      if (allocated(error)) stat = error%stat
   end subroutine find_cutoff_quiet

   !> Parameters of the slice at mu (R = E = sigma = 1, so P = p, delta = x).
   pure function universal_slice_params(model, psi, hardness_coeff, plastic_ratio, mu) &
      & result(params)
      integer, intent(in) :: model   !< model_* constant
      !> the model's psi, K, plastic ratio and the slice's mu
      real(dp), intent(in) :: psi, hardness_coeff, plastic_ratio, mu
      type(contact_params) :: params
      params = contact_params(model=model, radius=1.0_dp, modulus=1.0_dp, sigma=1.0_dp, &
         & mu=mu, psi=psi, hardness_coeff=hardness_coeff, plastic_ratio=plastic_ratio)
   end function universal_slice_params

   !> Derived evaluation data (after build or read): mu lookup constants and the
   !> slices' cubics gathered per interval. Needs universal_nodes_shared(u).
   pure subroutine universal_prepare(u)
      type(universal_table), intent(inout) :: u   !< built or read, universal_nodes_shared
      integer :: j, n
      u%log_mu_min = log(u%mu_min)
      u%inv_dlog_mu = (u%n_mu - 1)/(log(u%mu_max) - u%log_mu_min)
      n = size(u%slices(1)%delta)
      u%n_log = u%slices(1)%n_log
      if (allocated(u%coef)) deallocate (u%coef)
      allocate (u%coef(0:3, u%n_mu, n - 1))
      do j = 1, u%n_mu
         u%coef(:, j, :) = u%slices(j)%seg(1:4, 1:n - 1)
      end do
   end subroutine universal_prepare

   !> Force and stiffness of a contact (R, E, sigma > 0, mu) at overlap delta:
   !> P = E sqrt(R) sigma^1.5 p(delta/sigma, mu), K = E sqrt(R) sigma^0.5 dp/dx.
   !> In interval i the 4 slices' nodal data are combined with the Lagrange weights in
   !> the interval's variable (ln p, d ln p/dx for i <= n_log; p, dp/dx above), which,
   !> the Hermite cubic being linear in them, is the weighted sum of the slices' cubics.
   !> A node is combined in p as soon as it bounds a p interval (see combined_node), so
   !> the last log interval (n_log, ending at the first p node) has its right end ln of
   !> the combined p and its cubic is formed from the combined nodal data (boundary_cubic).
   !> stat (egw_universal_eval's statuses; the optional error says the same with a message
   !> naming the argument): 0; egw_invalid_parameter for sigma, R or E not > 0 and
   !> egw_invalid_argument for a NaN delta (force, stiffness 0); egw_out_of_range for mu
   !> outside [mu_min, mu_max] (force, stiffness 0) or x above x_max (the deep-overlap
   !> asymptote of the combined last node, deep_force, as in the 1-D table, so that
   !> universal_slice reproduces it); egw_invalid_parameter where the force or stiffness
   !> is not finite (R, E or sigma infinite, or a force beyond the doubles; the values as
   !> computed). At the cut-off the combined first node, below it 0 (rough models: the
   !> force there is below 1e-12 P_ref; below_cutoff, as the 1-D table).
   !> No allocation; thread-safe.
   pure subroutine universal_eval(u, radius, modulus, sigma, mu, delta, force, stiffness, &
      & stat, error)
      type(universal_table), intent(in) :: u   !< built or read
      real(dp), intent(in) :: radius   !< equivalent radius R [length], > 0
      real(dp), intent(in) :: modulus   !< effective modulus E* [force/length^2], > 0
      real(dp), intent(in) :: sigma   !< summit height deviation [length], > 0
      real(dp), intent(in) :: mu   !< Greenwood-Tripp mu, in the table's range
      real(dp), intent(in) :: delta   !< overlap [length]
      real(dp), intent(out) :: force   !< normal force [force], >= 0
      real(dp), intent(out) :: stiffness   !< dP/ddelta [force/length]
      integer, intent(out) :: stat   !< 0 or an egw status (above)
      !> allocated when stat is not 0, with a message naming the argument
      type(egw_error), allocatable, intent(out), optional :: error

      force = 0.0_dp
      stiffness = 0.0_dp
      stat = 0
      if (.not. (sigma > 0.0_dp .and. radius > 0.0_dp .and. modulus > 0.0_dp)) then
         stat = egw_invalid_parameter
      else if (ieee_is_nan(delta)) then
         stat = egw_invalid_argument
      else if (.not. mu_in_range(u, mu)) then
         stat = egw_out_of_range
      else
         call universal_values(u, radius, modulus, sigma, mu, delta, force, stiffness)
         if (.not. (ieee_is_finite(force) .and. ieee_is_finite(stiffness))) then
            stat = egw_invalid_parameter
         else if (delta/sigma > u%x_max) then
            stat = egw_out_of_range
         end if
      end if
      if (stat /= 0 .and. present(error)) call universal_error(u, radius, modulus, sigma, &
         & mu, delta, stat, error)
   end subroutine universal_eval

   !> universal_eval's error of status stat, with its message (egw_universal_eval's).
   pure subroutine universal_error(u, radius, modulus, sigma, mu, delta, stat, error)
      type(universal_table), intent(in) :: u
      real(dp), intent(in) :: radius, modulus, sigma, mu, delta
      integer, intent(in) :: stat
      type(egw_error), allocatable, intent(out) :: error
      character(len=:), allocatable :: text
      if (stat == egw_invalid_argument) then
         text = "delta = NaN: must be a number"
      else if (stat == egw_out_of_range .and. .not. mu_in_range(u, mu)) then
         text = "mu = "//format_real(mu)//": outside the table's ["//format_real(u%mu_min)// &
            & ", "//format_real(u%mu_max)//"]"
      else if (stat == egw_out_of_range) then
         text = "delta = "//format_real(delta)//": above the table's delta_max = x_max sigma"// &
            & " = "//format_real(u%x_max*sigma)//" (values extrapolated)"
      else if (.not. (sigma > 0.0_dp .and. radius > 0.0_dp .and. modulus > 0.0_dp)) then
         text = "sigma = "//format_real(sigma)//", radius = "//format_real(radius)// &
            & ", modulus = "//format_real(modulus)//": universal tables need all three > 0"
      else
         text = "sigma = "//format_real(sigma)//", radius = "//format_real(radius)// &
            & ", modulus = "//format_real(modulus)//", delta = "//format_real(delta)// &
            & ": the force E sqrt(R) sigma**1.5 p(delta/sigma) exceeds the largest double" &
            & //" (R, E, sigma must be finite)"
      end if
      call fatal_error(error, stat, text)
   end subroutine universal_error

   !> universal_eval's force and stiffness for valid arguments (sigma, R, E > 0, mu in
   !> range, delta a number).
   pure subroutine universal_values(u, radius, modulus, sigma, mu, delta, force, stiffness)
      type(universal_table), intent(in) :: u
      real(dp), intent(in) :: radius, modulus, sigma, mu, delta
      real(dp), intent(out) :: force, stiffness
      real(dp) :: x, t, w(0:3), v, dv, scale, c(0:3)
      integer :: j0, i, n

      force = 0.0_dp
      stiffness = 0.0_dp
      x = delta/sigma
      if (ieee_is_nan(x)) return   ! (Inf/Inf)
      call mu_stencil(u, mu, j0, w)
      scale = modulus*sqrt(radius)
      ! (sqrt(sigma) >= 1.5e-154 for a normal sigma: only the first two factors can leave
      ! the normal range on the way; redo those products without losing digits)
      if (scale >= tiny(1.0_dp) .and. scale <= huge(1.0_dp)) then
         scale = scale*sigma*sqrt(sigma)
         if (.not. scale >= tiny(1.0_dp)) scale = product4(modulus, sqrt(radius), sigma, &
            & sqrt(sigma))
      else
         scale = product4(modulus, sqrt(radius), sigma, sqrt(sigma))
      end if
      n = size(u%slices(1)%delta)
      if (.not. x > u%x_cut) then
         ! at the cut-off its combined node, below it below_cutoff (0 for rough models;
         ! in x, sigma = 1: what universal_slice's table gives)
         call combined_node(u, j0, w, 1, v, dv)
         if (x == u%x_cut) then
            force = v
            stiffness = dv
         else
            call below_cutoff(u%slices(1)%params, u%x_cut, v, dv, x, force, stiffness)
         end if
         force = scale*force
         stiffness = scale*stiffness/sigma
      else if (x < u%x_max) then
         ! one lookup for all slices (shared nodes), then one cubic of the combination
         i = table_interval(u%slices(1), x)
         t = x - u%slices(1)%seg(0, i)
         c = w(0)*u%coef(:, j0 + 1, i) + w(1)*u%coef(:, j0 + 2, i) + &
            & w(2)*u%coef(:, j0 + 3, i) + w(3)*u%coef(:, j0 + 4, i)
         if (i == u%n_log .and. i < n - 1) call boundary_cubic(u, j0, w, i, c)
         v = c(0) + t*(c(1) + t*(c(2) + t*c(3)))
         dv = c(1) + t*(2*c(2) + 3*t*c(3))
         if (i <= u%n_log) then
            force = scale*exp(v)
            stiffness = force*dv/sigma
         else
            force = scale*v
            stiffness = scale*dv/sigma
         end if
      else
         ! above x_max: the combined p and dp/dx at the last node, continued by the
         ! deep-overlap asymptote (deep_force in x, c = 4/3: universal_slice's table, in
         ! physical units, gives the same)
         call combined_node(u, j0, w, n, v, dv)
         call deep_force(u%x_max, v, dv, deep_coefficient(u%slices(1)%params), x, force, &
            & stiffness)
         force = scale*force
         stiffness = scale*stiffness/sigma
      end if
   end subroutine universal_values

   !> Combined p and dp/dx at node i (x = x_i) of mu's stencil: in ln p (exp of the
   !> weighted ln p) at nodes bounding only ln p intervals (i <= n_log, or all nodes when
   !> every interval is in ln p), linearly in p at the others.
   pure subroutine combined_node(u, j0, w, i, p, dp_dx)
      type(universal_table), intent(in) :: u
      integer, intent(in) :: j0, i
      real(dp), intent(in) :: w(0:3)
      real(dp), intent(out) :: p, dp_dx
      real(dp) :: lp, dlp
      integer :: m
      lp = 0.0_dp
      dlp = 0.0_dp
      if (i <= u%n_log .or. u%n_log >= size(u%slices(1)%delta) - 1) then
         do m = 0, 3
            associate (sl => u%slices(j0 + m + 1))
               lp = lp + w(m)*log(sl%force(i))
               dlp = dlp + w(m)*(sl%stiffness(i)/sl%force(i))
            end associate
         end do
         p = exp(lp)
         dp_dx = p*dlp
      else
         p = 0.0_dp
         dp_dx = 0.0_dp
         do m = 0, 3
            p = p + w(m)*u%slices(j0 + m + 1)%force(i)
            dp_dx = dp_dx + w(m)*u%slices(j0 + m + 1)%stiffness(i)
         end do
      end if
   end subroutine combined_node

   !> Cubic of ln p on the last log interval i = n_log, whose right node is combined in
   !> p: Hermite from ln p, d ln p/dx at both ends (left: c(0:1) as combined; right: from
   !> combined_node), the formula of egw_table's table_prepare, so that the slice table
   !> built from the combined nodes has the same cubic.
   pure subroutine boundary_cubic(u, j0, w, i, c)
      type(universal_table), intent(in) :: u
      integer, intent(in) :: j0, i
      real(dp), intent(in) :: w(0:3)
      real(dp), intent(inout) :: c(0:3)
      real(dp) :: p1, k1, v1, d1, h, s
      call combined_node(u, j0, w, i + 1, p1, k1)
      v1 = log(p1)
      d1 = k1/p1
      h = u%slices(1)%delta(i + 1) - u%slices(1)%delta(i)
      s = (v1 - c(0))/h
      c(2) = (3*s - 2*c(1) - d1)/h
      c(3) = (c(1) + d1 - 2*s)/h**2
   end subroutine boundary_cubic

   !> The 1-D force table of one contact (R, E, sigma > 0 and mu of params; model, psi,
   !> K, rho_p must equal the table's) cut out of the universal table: table_eval of it
   !> equals universal_eval at these parameters to rounding, at the cost of a 1-D table
   !> (no log, no mu interpolation, no exp outside the separated tail).
   !> Why it is exact: the slices share their x nodes and their per-interval choice of
   !> ln p or p, and the cubic Hermite in x is linear in the nodal data of its interval's
   !> variable. The nodes of the slice carry the combination universal_eval uses
   !> (combined_node: in ln p at nodes bounding only ln p intervals, in p at the others),
   !> so table_prepare forms the same cubic per interval (the weighted sum of the
   !> slices' cubics, or boundary_cubic's on the last ln p interval); scaling
   !> delta = sigma x, P = E sqrt(R) sigma^1.5 p, dP/ddelta = E sqrt(R) sigma^0.5 dp/dx
   !> turns it into a table in physical units with the slices' n_log, the same cut-off
   !> and the same deep-overlap asymptote above delta_max. Being an ordinary table of
   !> nodes, it survives write_table/read_table bit for bit. The contact radius
   !> a* = sqrt(R sigma) a*_x is combined with the same weights (not error-controlled,
   !> as in every table).
   !> rel_tol is the universal table's; max_force_error its measured error (mid-grid mu
   !> checks and the slices' x checks); reference_force the combined P_ref.
   !> Errors: egw_invalid_parameter (params invalid, sigma = 0), egw_invalid_argument
   !> (model, psi, K, rho_p differ from the table's; table not built; forces not
   !> representable), egw_out_of_range (mu outside [mu_min, mu_max]).
   !> linear_contact: accepted for compatibility and ignored. It used to re-interpolate
   !> P instead of ln P above delta = 0 (for speed, at the price of differing from
   !> universal_eval); the universal table itself now interpolates P there, so the
   !> exact slice is already as fast.
   pure subroutine universal_slice(u, params, table, error, linear_contact, delta_max)
      type(universal_table), intent(in) :: u   !< built or read
      !> one contact within the table's model and mu range
      type(contact_params), intent(in) :: params
      type(force_table), intent(out) :: table   !< its 1-D table; empty on error
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      logical, intent(in), optional :: linear_contact   !< ignored (compatibility)
      !> Largest overlap the caller will evaluate (optional): the slice keeps the nodes up
      !> to the first one at or above it, so its values below are unchanged and its lookup
      !> buckets are spent where the contacts are (a DEM mix over a table reaching
      !> delta/sigma = 1e3 otherwise crowds its buckets). Above it the table extrapolates.
      real(dp), intent(in), optional :: delta_max
      real(dp) :: w(0:3), scale, p, dp_dx, a, lref
      integer :: j0, m, i, n

      call validate_params(params, error)
      if (allocated(error)) return
      call refuse_flow_pressure(params, "a force table", error)
      if (allocated(error)) return
      if (.not. allocated(u%slices) .or. .not. allocated(u%coef)) then
         call fatal_error(error, egw_invalid_argument, "u: not a built or read table")
         return
      end if
      if (.not. params%sigma > 0.0_dp) then
         call fatal_error(error, egw_invalid_parameter, "sigma = "// &
            & format_real(params%sigma)//": universal tables need sigma > 0")
         return
      end if
      if (params%model /= u%model) then
         call fatal_error(error, egw_invalid_argument, "model = "// &
            & int_str(params%model)//": table is for model "//int_str(u%model))
         return
      end if
      if (params%psi /= u%psi .or. params%hardness_coeff /= u%hardness_coeff .or. &
         & params%plastic_ratio /= u%plastic_ratio) then
         call fatal_error(error, egw_invalid_argument, "psi = "//format_real(params%psi)// &
            & ": psi, K, rho_p differ from the table's")
         return
      end if
      if (.not. mu_in_range(u, params%mu)) then
         call fatal_error(error, egw_out_of_range, "mu = "//format_real(params%mu)// &
            & ": outside the table's ["//format_real(u%mu_min)//", "// &
            & format_real(u%mu_max)//"]")
         return
      end if
      call mu_stencil(u, params%mu, j0, w)
      scale = force_unit(params)
      n = size(u%slices(1)%delta)
      if (present(delta_max)) then
         if (.not. (ieee_is_finite(delta_max) .and. delta_max > params%sigma*u%x_cut)) then
            call fatal_error(error, egw_invalid_argument, "delta_max = "// &
               & format_real(delta_max)//": must be finite and above the cut-off "// &
               & format_real(params%sigma*u%x_cut))
            return
         end if
         do i = 2, n
            if (params%sigma*u%slices(1)%delta(i) >= delta_max) then
               ! keep every ln P interval and one P interval: the intervals kept are
               ! then exactly those of the full slice
               n = max(i, min(n, u%n_log + 2))
               exit
            end if
         end do
      end if
      allocate (table%delta(n), table%force(n), table%stiffness(n), &
         & table%contact_radius(n))
      do i = 1, n
         ! the nodal data of universal_eval's cubics
         call combined_node(u, j0, w, i, p, dp_dx)
         a = 0.0_dp
         do m = 0, 3
            a = a + w(m)*u%slices(j0 + m + 1)%contact_radius(i)
         end do
         table%delta(i) = params%sigma*u%slices(1)%delta(i)
         table%force(i) = scale*p
         table%stiffness(i) = stiffness_unit(params)*dp_dx
         table%contact_radius(i) = length_unit(params)*max(a, 0.0_dp)
      end do
      if (.not. all(ieee_is_finite(table%force) .and. table%force > 0.0_dp .and. &
         & ieee_is_finite(table%stiffness))) then
         call fatal_error(error, egw_invalid_argument, "modulus = "// &
            & format_real(params%modulus)//": with radius, sigma the forces are not "// &
            & "representable (overflow or underflow)")
         deallocate (table%delta, table%force, table%stiffness, table%contact_radius)
         return
      end if
      table%params = params
      table%rel_tol = u%rel_tol
      table%cutoff = table%delta(1)
      table%delta_max = table%delta(n)
      lref = 0.0_dp
      table%max_force_error = u%max_mu_error
      table%max_stiffness_error = 0.0_dp
      do m = 0, 3
         lref = lref + w(m)*log(u%slices(j0 + m + 1)%reference_force)
      end do
      table%reference_force = scale*exp(lref)
      do m = 1, u%n_mu
         table%max_force_error = max(table%max_force_error, u%slices(m)%max_force_error)
         table%max_stiffness_error = max(table%max_stiffness_error, &
            & u%slices(m)%max_stiffness_error)
      end do
      table%radius_sum = 0.0_dp
      ! ln P where the slices interpolate ln p (force > 0 from the cut-off on)
      table%n_log = u%n_log
      call table_prepare(table)
      if (present(linear_contact)) continue  ! no-op, see above
   end subroutine universal_slice

   !> True when every slice has the nodes and the ln p intervals (n_log) of the first,
   !> as the builder makes them; readers check it before universal_prepare.
   pure logical function universal_nodes_shared(u)
      type(universal_table), intent(in) :: u   !< built or read
      integer :: j
      universal_nodes_shared = .false.
      do j = 1, u%n_mu
         if (size(u%slices(j)%delta) /= size(u%slices(1)%delta)) return
         if (any(u%slices(j)%delta /= u%slices(1)%delta)) return
         if (u%slices(j)%n_log /= u%slices(1)%n_log) return
      end do
      universal_nodes_shared = .true.
   end function universal_nodes_shared

   ! ------------------------------------------------------------------ internals

   !> mu inside [mu_min, mu_max] (1e-12: mu at the ends of the range after a round trip
   !> through ln); false for NaN.
   pure logical function mu_in_range(u, mu)
      type(universal_table), intent(in) :: u
      real(dp), intent(in) :: mu
      mu_in_range = mu >= u%mu_min*(1 - 1.0e-12_dp) .and. mu <= u%mu_max*(1 + 1.0e-12_dp)
   end function mu_in_range

   !> First slice j0 + 1 of mu's 4-point stencil and its Lagrange weights in ln mu
   !> (one code path for universal_eval and universal_slice: the same weights bit for bit).
   pure subroutine mu_stencil(u, mu, j0, w)
      type(universal_table), intent(in) :: u
      real(dp), intent(in) :: mu
      integer, intent(out) :: j0
      real(dp), intent(out) :: w(0:3)
      real(dp) :: s, t
      s = (log(mu) - u%log_mu_min)*u%inv_dlog_mu
      j0 = min(max(int(s) - 1, 0), u%n_mu - 4)
      t = s - j0
      w(0) = -(t - 1)*(t - 2)*(t - 3)/6
      w(1) = t*(t - 2)*(t - 3)/2
      w(2) = -t*(t - 1)*(t - 3)/2
      w(3) = t*(t - 1)*(t - 2)/6
   end subroutine mu_stencil

   pure function grid(mu_min, mu_max, n) result(mus)
      real(dp), intent(in) :: mu_min, mu_max
      integer, intent(in) :: n
      real(dp) :: mus(n)
      integer :: j
      do j = 1, n
         mus(j) = exp(log(mu_min) + (log(mu_max) - log(mu_min))*(j - 1)/(n - 1))
      end do
      mus(1) = mu_min
      mus(n) = mu_max
   end function grid

   !> x check points: the midpoints of every k-th interval of a slice's nodes, so that
   !> they sample the tail, the contact onset and the Hertz range as densely as the
   !> x-table itself needs.
   pure function check_points(x_cut, x_max, nodes) result(xs)
      real(dp), intent(in) :: x_cut, x_max
      real(dp), intent(in) :: nodes(:)
      real(dp), allocatable :: xs(:)
      integer :: n, stride, i
      n = size(nodes)
      stride = max(1, (n - 1)/n_check_x)
      xs = [(0.5_dp*(nodes(i) + nodes(i + 1)), i=1, n - 1, stride)]
      xs = pack(xs, xs > x_cut .and. xs < x_max)
   end function check_points

   !> Max relative error of the mu interpolation at the mid-grid mu of every interval.
   subroutine mid_grid_error(u, opts, xs, worst, error)
      type(universal_table), intent(in) :: u
      type(solver_options), intent(in) :: opts
      real(dp), intent(in) :: xs(:)
      real(dp), intent(out) :: worst
      type(egw_error), allocatable, intent(out) :: error
      integer :: n, nx, idx, jm, ix
      real(dp), allocatable :: err(:)
      integer, allocatable :: stat(:)
      nx = size(xs)
      n = (u%n_mu - 1)*nx
      allocate (err(n), stat(n))
      !$omp parallel do schedule(dynamic) private(jm, ix)
      do idx = 1, n
         jm = (idx - 1)/nx + 1
         ix = idx - (jm - 1)*nx
         call one_check(u, opts, jm, xs(ix), err(idx), stat(idx))
      end do
      !$omp end parallel do
      worst = 0.0_dp
      if (n > 0) worst = maxval(err)
      if (any(stat /= 0)) then
         call fatal_error(error, stat(findloc(stat /= 0, .true., dim=1)), &
            & "mu check solve failed while building the universal table")
      end if
   end subroutine mid_grid_error

   subroutine one_check(u, opts, jm, x, err, stat)
      type(universal_table), intent(in) :: u
      type(solver_options), intent(in) :: opts
      integer, intent(in) :: jm
      real(dp), intent(in) :: x
      real(dp), intent(out) :: err
      integer, intent(out) :: stat
      type(egw_error), allocatable :: e
      type(solve_result) :: res
      real(dp) :: mu, f, k
      integer :: st
      mu = exp(u%log_mu_min + (jm - 0.5_dp)/u%inv_dlog_mu)
      call solve_contact(universal_slice_params(u%model, u%psi, u%hardness_coeff, &
         & u%plastic_ratio, mu), opts, x, res, e)
      err = 0.0_dp
      stat = 0
      if (allocated(e)) then
         stat = e%stat
         return
      end if
      call universal_eval(u, 1.0_dp, 1.0_dp, 1.0_dp, mu, x, f, k, st)
      if (res%force > 0.0_dp) err = abs(f/res%force - 1)
   end subroutine one_check

   !> Move a built universal table into `to` (allocations moved, not copied) and prepare
   !> it for evaluation.
   subroutine move_universal(from, to)
      type(universal_table), intent(inout) :: from   !< the built table (deallocated after)
      type(universal_table), intent(out) :: to   !< the same table, prepared
      to%model = from%model
      to%psi = from%psi
      to%hardness_coeff = from%hardness_coeff
      to%plastic_ratio = from%plastic_ratio
      to%rel_tol = from%rel_tol
      to%x_cut = from%x_cut
      to%x_max = from%x_max
      to%mu_min = from%mu_min
      to%mu_max = from%mu_max
      to%n_mu = from%n_mu
      to%max_mu_error = from%max_mu_error
      call move_alloc(from%slices, to%slices)
      call move_alloc(from%coef, to%coef)
      call universal_prepare(to)
   end subroutine move_universal

end module egw_table_universal
