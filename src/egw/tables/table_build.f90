!> The builds of force tables (module egw_table): the cut-off search, the adaptive
!> placement of nodes checked by solves at interval midpoints (OpenMP over points), and
!> the shared nodes of several parameter sets. The table type, its evaluation and the
!> interfaces of the public builds are in egw_table (table.f90).
submodule (egw_table) egw_table_build
   use egw_status, only: egw_invalid_parameter
   implicit none

contains

   ! build_table: interface and documentation in egw_table (table.f90)
   module procedure build_table
      call build_1d(params, options, delta_min, delta_max, rel_tol, table, error, progress, &
         & loading_curve=loading_curve, loading=loading)
   end procedure build_table

   ! build_table_law: interface and documentation in egw_table (table.f90)
   module procedure build_table_law
      type(contact_params) :: lp
      ! force tables refuse the cap (a capped contact is a hysteresis table's), a law's as
      ! build_table's; it was dropped here (audit25). solve_contact_law takes it.
      if (params%flow_pressure > 0.0_dp) then
         call fatal_error(error, egw_invalid_parameter, "flow_pressure = " &
            & //format_real(params%flow_pressure)//": a rough-flat law's force table has no " &
            & //"flow-pressure cap (force tables refuse it; the law's solve takes it): 0 " &
            & //"for a table")
         return
      end if
      lp = contact_params(model=model_flat_law, radius=params%radius, &
         & modulus=params%modulus, sigma=law%length())
      call build_1d(lp, options, delta_min, delta_max, rel_tol, table, error, progress, law)
   end procedure build_table_law

   ! build_table_fixed_cutoff: interface and documentation in egw_table (table.f90)
   module procedure build_table_fixed_cutoff
      type(solver_options) :: opts
      real(dp) :: p_ref, k, a

      call check_request(params, cutoff, delta_max, rel_tol, error)
      if (allocated(error)) return
      opts = point_options(options, rel_tol)
      call solve_point(params, opts, reference_overlap(params, delta_max), p_ref, k, a, error)
      if (allocated(error)) return
      call build_core(params, opts, cutoff, delta_max, rel_tol, p_ref, log_space, table, error)
   end procedure build_table_fixed_cutoff

   ! build_tables_shared: interface and documentation in egw_table (table.f90)
   module procedure build_tables_shared
      type(solver_options) :: opts
      real(dp) :: p_ref(size(params))
      real(dp) :: pk(1, size(params)), kk(1, size(params)), ak(1, size(params))
      integer :: s, n_solves
      n_solves = 0
      if (present(solves_before)) n_solves = solves_before
      if (present(solves)) solves = n_solves
      do s = 1, size(params)
         call check_request(params(s), cutoff, delta_max, rel_tol, error)
         if (allocated(error)) return
      end do
      opts = point_options(options, rel_tol)
      ! P_ref of every set, in parallel (the sets are slices of one model: one overlap)
      call solve_grid(params, opts, [reference_overlap(params(1), delta_max)], pk(1:1, :), &
         & kk(1:1, :), ak(1:1, :), error)
      if (allocated(error)) return
      p_ref = pk(1, :)
      n_solves = n_solves + size(params)
      call build_shared_nodes(params, opts, cutoff, delta_max, rel_tol, p_ref, log_space, &
         & tables, error, n_solves, progress)
      if (present(solves)) solves = n_solves
   end procedure build_tables_shared

   ! table_find_cutoff: interface and documentation in egw_table (table.f90)
   module procedure table_find_cutoff
      integer :: n_solves
      call find_cutoff(params, options, delta_min, delta_max, rel_tol, cutoff, p_ref, &
         & n_solves, error)
   end procedure table_find_cutoff

   !> The 1-D build of build_table and build_table_law (law present: solves with it).
   subroutine build_1d(params, options, delta_min, delta_max, rel_tol, table, error, &
      & progress, law, loading_curve, loading)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta_min, delta_max, rel_tol
      type(force_table), intent(out) :: table
      type(egw_error), allocatable, intent(out) :: error
      procedure(table_progress), optional :: progress
      class(flat_law), intent(in), optional :: law
      logical, intent(in), optional :: loading_curve   !< as build_table's
      type(law_pieces), intent(in), optional :: loading   !< as build_table's
      type(solver_options) :: opts
      real(dp) :: cutoff, p_ref
      type(force_table) :: tables(1)
      integer :: n_solves
      logical :: allow_cap

      allow_cap = .false.
      if (present(loading_curve)) allow_cap = loading_curve
      call check_request(params, delta_min, delta_max, rel_tol, error, present(law), allow_cap)
      if (allocated(error)) return
      opts = point_options(options, rel_tol)
      call find_cutoff(params, opts, delta_min, delta_max, rel_tol, cutoff, p_ref, n_solves, &
         & error, law, loading)
      ! nodes at least up to where the deep-overlap law above the last node holds its 1 %
      if (.not. allocated(error)) call build_shared_nodes([params], opts, cutoff, &
         & max(delta_max, deep_law_floor(params)), rel_tol, [p_ref], .false., tables, error, &
         & n_solves, progress, law, loading)
      if (allocated(error)) then
         call tolerance_context(error, "table", rel_tol, opts%rel_tol)   ! the caller's terms
         return
      end if
      table = tables(1)
   end subroutine build_1d

   !> table_find_cutoff, also counting its solves (n_solves, for progress reports).
   subroutine find_cutoff(params, options, delta_min, delta_max, rel_tol, cutoff, p_ref, &
      & n_solves, error, law, loading)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: delta_min, delta_max, rel_tol
      real(dp), intent(out) :: cutoff, p_ref
      integer, intent(out) :: n_solves
      type(egw_error), allocatable, intent(out) :: error
      class(flat_law), intent(in), optional :: law   !< solves with this law
      type(law_pieces), intent(in), optional :: loading   !< as build_table's
      real(dp) :: lo, hi, p_lo, k, a, target, step, d_ref, xs(2), ps(2, 1), ks(2, 1), &
         & as(2, 1)
      integer :: it, j, pass

      d_ref = reference_overlap(params, delta_max)
      hi = d_ref
      lo = min(delta_min, d_ref)
      ! P_ref and the force at delta_min together (solve_grid: in parallel)
      n_solves = 2
      call solve_grid([params], options, [d_ref, lo], ps, ks, as, error, law, loading)
      if (allocated(error)) return
      p_ref = ps(1, 1)
      p_lo = ps(2, 1)
      if (.not. p_ref > 0.0_dp) then
         call fatal_error(error, egw_invalid_argument, "delta_max = "// &
            & format_real(delta_max)//": the force there is zero, nothing to tabulate")
         return
      end if
      target = rel_tol*p_ref
      if (is_rough(params)) target = min(rel_tol, tail_floor)*p_ref
      step = length_scale(params, delta_max)
      ! extend below delta_min until the force is small enough (Gaussian tail: a few sigma)
      it = 0
      do while (p_lo > target)
         it = it + 1
         if (it > 60) then
            call fatal_error(error, egw_not_converged, "delta_min = "// &
               & format_real(delta_min)//": force does not fall to rel_tol*P_ref below it")
            return
         end if
         hi = lo
         lo = lo - step
         step = 2*step
         n_solves = n_solves + 1
         call solve_point(params, options, lo, p_lo, k, a, error, law, loading)
         if (allocated(error)) return
      end do
      ! trisection: two solves per step in parallel shrink the bracket 3x per solve
      ! time (bisection: 2x); a fixed two points, so the result does not depend on the
      ! number of threads
      do pass = 1, 2
         do it = 1, 200
            if (p_lo >= 0.5_dp*target) exit
            if (hi - lo <= 1.0e-14_dp*max(abs(lo), abs(hi), step)) exit
            xs = [lo + (hi - lo)/3, lo + 2*(hi - lo)/3]
            if (.not. (xs(1) > lo .and. xs(2) > xs(1) .and. hi > xs(2))) exit
            n_solves = n_solves + 2
            call solve_grid([params], options, xs, ps, ks, as, error, law, loading)
            if (allocated(error)) return
            do j = 2, 1, -1
               if (.not. ps(j, 1) > target) exit
               hi = xs(j)
            end do
            ! j = last point with force <= target (0: none)
            if (j >= 1) then
               lo = xs(j)
               p_lo = ps(j, 1)
            end if
         end do
         ! 3**200 did not bring a bracket from a delta_min far below the contact to its
         ! length scale (E-GW, sigma 1e-6, delta_min -1e100: a cut-off at -3.8e4 where the
         ! force is 0, 1020 nodes; Hertz at -1e100: a build failed at round-off): bracket
         ! it again from hi down, in steps of the length scale doubling
         if (it <= 200 .or. hi - lo <= length_scale(params, delta_max)) exit
         step = length_scale(params, delta_max)
         do it = 1, 61
            if (it > 60) then
               call fatal_error(error, egw_not_converged, "delta_min = "// &
                  & format_real(delta_min)//": no force below rel_tol*P_ref found below "// &
                  & format_real(hi))
               return
            end if
            lo = hi - step
            n_solves = n_solves + 1
            call solve_point(params, options, lo, p_lo, k, a, error, law, loading)
            if (allocated(error)) return
            if (.not. p_lo > target) exit
            hi = lo
            step = 2*step
         end do
      end do
      cutoff = lo
   end subroutine find_cutoff

   !> Adaptive build between a given cut-off and delta_max (one parameter set).
   subroutine build_core(params, opts, cutoff, delta_max, rel_tol, p_ref, log_all, table, error)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: opts
      real(dp), intent(in) :: cutoff, delta_max, rel_tol, p_ref
      logical, intent(in) :: log_all
      type(force_table), intent(out) :: table
      type(egw_error), allocatable, intent(out) :: error
      type(force_table) :: tables(1)
      integer :: n_solves
      n_solves = 0
      call build_shared_nodes([params], opts, cutoff, delta_max, rel_tol, [p_ref], log_all, &
         & tables, error, n_solves)
      if (allocated(error)) return
      table = tables(1)
   end subroutine build_core

   !> Tables of several parameter sets (the mu slices of a universal table) on one
   !> common set of nodes: an interval is accepted only when the check passes for every
   !> set (check_midpoints; doc/theory.md §7 "Tables": intervals bisected until solves at
   !> their midpoints agree). Solves run in parallel over all (node, set) pairs. A single
   !> set is the ordinary 1-D build. n_solves: solves done before (counted on in place, for
   !> the optional progress hook, which is called after every batch of solves).
   subroutine build_shared_nodes(params, opts, cutoff, delta_max, rel_tol, p_ref, log_all, &
      & tables, error, n_solves, progress, law, loading)
      type(contact_params), intent(in) :: params(:)
      type(solver_options), intent(in) :: opts
      real(dp), intent(in) :: cutoff, delta_max, rel_tol, p_ref(:)
      logical, intent(in) :: log_all
      type(force_table), intent(inout) :: tables(:)
      type(egw_error), allocatable, intent(out) :: error
      integer, intent(inout) :: n_solves
      procedure(table_progress), optional :: progress
      class(flat_law), intent(in), optional :: law   !< solves with this law (one set)
      type(law_pieces), intent(in), optional :: loading   !< as build_table's (one set)
      real(dp), allocatable :: x(:), f(:, :), k(:, :), a(:, :), xm(:), fm(:, :), km(:, :)
      real(dp), allocatable :: am(:, :), err_f(:), err_k(:)
      logical, allocatable :: accepted(:), split(:)
      integer, allocatable :: todo(:)
      integer :: round, n, i, m, ns

      ns = size(params)
      call initial_nodes(params(1), cutoff, delta_max, x)
      n = size(x)
      allocate (f(n, ns), k(n, ns), a(n, ns))
      call solve_grid(params, opts, x, f, k, a, error, law, loading)
      if (allocated(error)) return
      n_solves = n_solves + n*ns
      ! pending: one midpoint solve per set for each of the n - 1 unchecked intervals
      if (present(progress)) call progress(n_solves, n_solves + (n - 1)*ns)
      allocate (accepted(n - 1), err_f(n - 1), err_k(n - 1))
      accepted = .false.
      err_f = 0.0_dp
      err_k = 0.0_dp

      do round = 1, max_rounds
         todo = pack([(i, i=1, n - 1)], .not. accepted)
         m = size(todo)
         if (m == 0) exit
         if (n + m > max_nodes .or. round == max_rounds) then
            call fatal_error(error, egw_not_converged, "rel_tol = "//format_real(rel_tol)// &
               & " not reached: "//int_str(n)//" nodes and the largest interpolation error "// &
               & "at the check solves is still "//format_real(maxval(err_f))// &
               & " (node limit; the solver's noise at "//format_real(opts%rel_tol)// &
               & " above rel_tol?)")
            return
         end if
         xm = 0.5_dp*(x(todo) + x(todo + 1))
         if (any(xm <= x(todo) .or. xm >= x(todo + 1))) then
            call fatal_error(error, egw_not_converged, "rel_tol = "//format_real(rel_tol)// &
               & " not reached: the node spacing reached round-off with the largest "// &
               & "interpolation error at the check solves still "//format_real(maxval(err_f)))
            return
         end if
         allocate (fm(m, ns), km(m, ns), am(m, ns), split(m))
         call solve_grid(params, opts, xm, fm, km, am, error, law, loading)
         if (allocated(error)) return
         call check_midpoints(params, rel_tol, log_all, x, f, k, todo, xm, fm, km, split, &
            & err_f, err_k)
         call merge_nodes(x, f, k, a, accepted, err_f, err_k, todo, xm, fm, km, am, split)
         n = size(x)
         deallocate (fm, km, am, split)
         n_solves = n_solves + m*ns
         if (present(progress)) call progress(n_solves, n_solves + count(.not. accepted)*ns)
      end do
      call store_shared_tables(params, rel_tol, p_ref, log_all, x, f, k, a, err_f, err_k, &
         & tables)
   end subroutine build_shared_nodes

   !> The check of a table's intervals (doc/theory.md §7 "Tables"): the cubic Hermite
   !> interpolant of every set at the midpoints xm of the intervals todo against the solves
   !> there (fm, km). split(j): interval todo(j) fails for some set (force off by more than
   !> rel_tol, stiffness off, or not monotone); err_f, err_k: its largest errors.
   pure subroutine check_midpoints(params, rel_tol, log_all, x, f, k, todo, xm, fm, km, &
      & split, err_f, err_k)
      type(contact_params), intent(in) :: params(:)
      real(dp), intent(in) :: rel_tol
      logical, intent(in) :: log_all
      real(dp), intent(in) :: x(:), f(:, :), k(:, :)   !< nodes and their solves
      integer, intent(in) :: todo(:)
      real(dp), intent(in) :: xm(:), fm(:, :), km(:, :)   !< midpoints and their solves
      logical, intent(out) :: split(:)
      real(dp), intent(inout) :: err_f(:), err_k(:)
      real(dp) :: fi, ki, ef, ek, k_tol
      integer :: i, j, s
      logical :: rough, in_log, bad_interval, check_k
      rough = is_rough(params(1))
      check_k = .not. rough
      do j = 1, size(todo)
         i = todo(j)
         in_log = log_all .or. (rough .and. x(i + 1) <= 0.0_dp)
         split(j) = .false.
         err_f(i) = 0.0_dp
         err_k(i) = 0.0_dp
         do s = 1, size(params)
            call hermite_at(x(i), x(i + 1), f(i, s), f(i + 1, s), k(i, s), k(i + 1, s), &
               & in_log, xm(j), fi, ki)
            ef = rel_diff(fi, fm(j, s))
            ek = rel_diff(ki, km(j, s))
            ! the capped loading curve of a rough model (a hysteresis table's): its
            ! curvature changes where the capped zone outgrows the Hertz radius (~3 delta_y),
            ! and an interval across that change can meet the midpoint solve while its error
            ! peaks elsewhere (EP-GW + cap, sigma = delta_y/100, rel_tol 1e-4: 8.1e-5 at the
            ! midpoint of 2.46 .. 3.69 delta_y, 2.2e-4 at 3.35). The slope's mismatch too,
            ! in value units over a quarter interval (as the hysteresis curves' check): an
            ! error that is not symmetric about the midpoint has a slope there.
            if (rough .and. params(s)%flow_pressure > 0.0_dp .and. .not. in_log .and. &
               & fm(j, s) > 0.0_dp) ef = max(ef, 0.25_dp*(x(i + 1) - x(i))* &
               & abs(ki - km(j, s))/fm(j, s))
            ! the stiffness check (10 rel_tol) catches the sqrt(delta) singularity of
            ! the Hertz stiffness at delta = 0 that the force check misses; for smooth
            ! data the midpoint derivative error of cubic Hermite vanishes to leading
            ! order, so it adds no nodes there. Smooth spheres only: a rough sphere has
            ! P(0) > 0, so its delta^(3/2) onset term shows in the force check, and
            ! there the solver's stiffness just above delta = 0 (where the bulk
            ! contact patch a ~ sqrt(R delta) is far below the mesh) is not the
            ! derivative of its force to 1e-5: checking it made tables below
            ! rel_tol ~ 5e-6 split towards 0 without end. Only the interval starting
            ! at delta = 0 of a rough table is checked, to 1e-4 (its sqrt(delta)
            ! stiffness term gave errors ~1e-3 there; 1e-4 is reached at ~1e-5 sigma
            ! for mu = 4, where the solver's stiffness is still consistent to ~1e-6),
            ! and not below 1e-6 sigma (small mu, where the bulk sqrt(delta) term
            ! dominates K(0), would need intervals where it is not)
            k_tol = huge(1.0_dp)
            if (check_k) k_tol = 10*rel_tol
            if (rough .and. x(i) == 0.0_dp .and. x(i + 1) > 1.0e-6_dp*params(s)%sigma) &
               & k_tol = max(10*rel_tol, 1.0e-4_dp)
            bad_interval = ef > rel_tol .or. &
               & ek > k_tol + slope_roundoff(x(i), x(i + 1), f(i, s), f(i + 1, s), &
               & km(j, s), in_log) .or. &
               & .not. monotone_ok(x(i), x(i + 1), f(i, s), f(i + 1, s), k(i, s), &
               & k(i + 1, s), in_log)
            split(j) = split(j) .or. bad_interval
            err_f(i) = max(err_f(i), ef)
            err_k(i) = max(err_k(i), ek)
         end do
      end do
   end subroutine check_midpoints

   !> The finished tables of build_shared_nodes: every set's values at the common nodes x,
   !> with the build's metadata (the largest midpoint errors, n_log), prepared for
   !> evaluation.
   pure subroutine store_shared_tables(params, rel_tol, p_ref, log_all, x, f, k, a, err_f, &
      & err_k, tables)
      type(contact_params), intent(in) :: params(:)
      real(dp), intent(in) :: rel_tol, p_ref(:)
      logical, intent(in) :: log_all
      real(dp), intent(in) :: x(:), f(:, :), k(:, :), a(:, :), err_f(:), err_k(:)
      type(force_table), intent(inout) :: tables(:)
      integer :: n, s
      logical :: rough
      n = size(x)
      rough = is_rough(params(1))
      do s = 1, size(params)
         associate (table => tables(s))
            table%params = params(s)
            table%rel_tol = rel_tol
            table%cutoff = x(1)
            table%delta_max = x(n)
            table%reference_force = p_ref(s)
            table%max_force_error = maxval(err_f)
            table%max_stiffness_error = maxval(err_k)
            table%radius_sum = 0.0_dp
            table%n_log = 0
            if (rough) table%n_log = count(x(2:n) <= 0.0_dp)
            if (log_all) table%n_log = n - 1
            table%delta = x
            table%force = f(:, s)
            table%stiffness = k(:, s)
            table%contact_radius = a(:, s)
            call table_prepare(table)
         end associate
      end do
   end subroutine store_shared_tables

   !> Hermite interpolant of one interval at xq (log space if in_log).
   pure subroutine hermite_at(x0, x1, f0, f1, k0, k1, in_log, xq, f, k)
      real(dp), intent(in) :: x0, x1, f0, f1, k0, k1, xq
      logical, intent(in) :: in_log
      real(dp), intent(out) :: f, k
      real(dp) :: h, t, v0, v1, d0, d1, v, d
      h = x1 - x0
      t = (xq - x0)/h
      if (in_log) then
         v0 = log(f0)
         v1 = log(f1)
         d0 = k0/f0
         d1 = k1/f1
      else
         v0 = f0
         v1 = f1
         d0 = k0
         d1 = k1
      end if
      v = (1 + 2*t)*(1 - t)**2*v0 + t*(1 - t)**2*h*d0 + t**2*(3 - 2*t)*v1 + t**2*(t - 1)*h*d1
      d = 6*t*(t - 1)/h*(v0 - v1) + (1 - t)*(1 - 3*t)*d0 + t*(3*t - 2)*d1
      if (in_log) then
         f = exp(v)
         k = f*d
      else
         f = v
         k = d
      end if
   end subroutine hermite_at

   !> Insert the midpoints of split intervals as nodes, keep the others' verdicts.
   pure subroutine merge_nodes(x, f, k, a, accepted, err_f, err_k, todo, xm, fm, km, am, split)
      real(dp), allocatable, intent(inout) :: x(:), f(:, :), k(:, :), a(:, :), err_f(:), &
         & err_k(:)
      logical, allocatable, intent(inout) :: accepted(:)
      integer, intent(in) :: todo(:)
      real(dp), intent(in) :: xm(:), fm(:, :), km(:, :), am(:, :)
      logical, intent(in) :: split(:)
      real(dp), allocatable :: x2(:), f2(:, :), k2(:, :), a2(:, :), ef2(:), ek2(:)
      logical, allocatable :: acc2(:)
      integer, allocatable :: slot(:)
      integer :: n, n2, i, j, p, ns

      n = size(x)
      ns = size(f, 2)
      allocate (slot(n - 1))
      slot = 0
      do j = 1, size(todo)
         if (split(j)) then
            slot(todo(j)) = j
         else
            accepted(todo(j)) = .true.
         end if
      end do
      n2 = n + count(split)
      allocate (x2(n2), f2(n2, ns), k2(n2, ns), a2(n2, ns), acc2(n2 - 1), ef2(n2 - 1), &
         & ek2(n2 - 1))
      p = 1
      x2(1) = x(1); f2(1, :) = f(1, :); k2(1, :) = k(1, :); a2(1, :) = a(1, :)
      do i = 1, n - 1
         j = slot(i)
         if (j > 0) then
            acc2(p) = .false.; ef2(p) = 0.0_dp; ek2(p) = 0.0_dp
            p = p + 1
            x2(p) = xm(j); f2(p, :) = fm(j, :); k2(p, :) = km(j, :); a2(p, :) = am(j, :)
            acc2(p) = .false.; ef2(p) = 0.0_dp; ek2(p) = 0.0_dp
         else
            acc2(p) = accepted(i); ef2(p) = err_f(i); ek2(p) = err_k(i)
         end if
         p = p + 1
         x2(p) = x(i + 1); f2(p, :) = f(i + 1, :); k2(p, :) = k(i + 1, :); a2(p, :) = a(i + 1, :)
      end do
      call move_alloc(x2, x)
      call move_alloc(f2, f)
      call move_alloc(k2, k)
      call move_alloc(a2, a)
      call move_alloc(acc2, accepted)
      call move_alloc(ef2, err_f)
      call move_alloc(ek2, err_k)
   end subroutine merge_nodes

   !> Starting nodes: geometric in delta above 0 (delta^(3/2) and the E-GW curvature
   !> jump at 0 need grading), every sigma in the tail, 0 itself for rough models.
   pure subroutine initial_nodes(params, cutoff, delta_max, x)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: cutoff, delta_max
      real(dp), allocatable, intent(out) :: x(:)
      real(dp) :: buf(4000), step, d
      integer :: n
      n = 1
      buf(1) = cutoff
      if (is_rough(params)) then
         step = params%sigma
         d = cutoff + step
         do while (d < min(0.0_dp, delta_max) - 0.25_dp*step .and. n < 1000)
            n = n + 1
            buf(n) = d
            d = d + step
         end do
         if (cutoff < 0.0_dp .and. delta_max > 0.0_dp) then
            n = n + 1
            buf(n) = 0.0_dp
         end if
         d = max(cutoff, 0.0_dp)
         step = params%sigma/8
      else
         d = cutoff
         step = cutoff
      end if
      do while (d + step < delta_max*(1 - 1.0e-3_dp) .and. n < 3990)
         d = d + step
         n = n + 1
         buf(n) = d
         step = max(step, 0.5_dp*d)
      end do
      n = n + 1
      buf(n) = delta_max
      x = buf(1:n)
   end subroutine initial_nodes

   !> Solve every (point, parameter set) pair in parallel (solver threads off).
   subroutine solve_grid(params, opts, x, f, k, a, error, law, loading)
      type(contact_params), intent(in) :: params(:)
      type(solver_options), intent(in) :: opts
      real(dp), intent(in) :: x(:)
      real(dp), intent(out) :: f(:, :), k(:, :), a(:, :)
      type(egw_error), allocatable, intent(out) :: error
      class(flat_law), intent(in), optional :: law   !< solves with this law
      type(law_pieces), intent(in), optional :: loading   !< as build_table's
      integer, allocatable :: stat(:, :)
      integer :: i, s, idx, nx
      nx = size(x)
      allocate (stat(nx, size(params)))
      !$omp parallel do schedule(dynamic) private(i, s)
      do idx = 1, nx*size(params)
         i = mod(idx - 1, nx) + 1
         s = (idx - 1)/nx + 1
         call solve_quiet(params(s), opts, x(i), f(i, s), k(i, s), a(i, s), stat(i, s), law, &
            & loading)
      end do
      !$omp end parallel do
      do s = 1, size(params)
         do i = 1, nx
            if (stat(i, s) /= 0) then
               ! redo the first failure serially to recover its message
               call solve_point(params(s), opts, x(i), f(i, s), k(i, s), a(i, s), error, law, &
                  & loading)
               ! (the solve's message in its scaled units: which table node, in the user's)
               if (allocated(error)) error%message = "the table's solve at delta = "// &
                  & format_real(x(i))//": "//error%message
               if (.not. allocated(error)) call fatal_error(error, stat(i, s), "delta = "// &
                  & format_real(x(i))//": solve failed while building the table")
               return
            end if
         end do
      end do
   end subroutine solve_grid

   subroutine solve_quiet(params, opts, x, f, k, a, stat, law, loading)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: opts
      real(dp), intent(in) :: x
      real(dp), intent(out) :: f, k, a
      integer, intent(out) :: stat
      class(flat_law), intent(in), optional :: law
      type(law_pieces), intent(in), optional :: loading
      type(egw_error), allocatable :: error
      call solve_point(params, opts, x, f, k, a, error, law, loading)
      stat = 0
      if (allocated(error)) stat = error%stat
   end subroutine solve_quiet

   subroutine solve_point(params, opts, x, f, k, a, error, law, loading)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: opts
      real(dp), intent(in) :: x
      real(dp), intent(out) :: f, k, a
      type(egw_error), allocatable, intent(out) :: error
      class(flat_law), intent(in), optional :: law   !< (params: R, E* of the pair)
      !> GW's ZMC law tabulated (solve_contact's loading), where law is absent
      type(law_pieces), intent(in), optional :: loading
      type(solve_result) :: res
      if (present(law)) then
         call solve_contact_law(params, law, opts, x, res, error)
      else
         call solve_contact(params, opts, x, res, error, loading)
      end if
      f = res%force
      k = res%stiffness
      a = res%contact_radius
      if (allocated(error)) return
      if (.not. (ieee_is_finite(f) .and. f >= 0.0_dp .and. ieee_is_finite(k))) then
         call fatal_error(error, egw_not_converged, "delta = "//format_real(x)// &
            & ": solver returned force "//format_real(f)//", stiffness "//format_real(k))
      end if
   end subroutine solve_point

   pure subroutine check_request(params, delta_min, delta_max, rel_tol, error, with_law, &
      & allow_cap)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: delta_min, delta_max, rel_tol
      type(egw_error), allocatable, intent(out) :: error
      logical, intent(in), optional :: with_law   !< the build has the law (model_flat_law)
      !> a hysteresis table's loading curve: flow_pressure allowed
      logical, intent(in), optional :: allow_cap
      logical :: cap_ok
      call validate_params(params, error, with_law)
      if (allocated(error)) return
      ! the formats store a reversible loading curve: a capped one unloads otherwise
      cap_ok = .false.
      if (present(allow_cap)) cap_ok = allow_cap
      if (.not. cap_ok) call refuse_flow_pressure(params, "a force table", error)
      if (allocated(error)) return
      if (.not. ieee_is_finite(delta_min)) then
         call fatal_error(error, egw_invalid_argument, "delta_min = "// &
            & format_real(delta_min)//": must be finite")
      else if (.not. (ieee_is_finite(delta_max) .and. delta_max > delta_min)) then
         call fatal_error(error, egw_invalid_argument, "delta_max = "// &
            & format_real(delta_max)//": must be finite and > delta_min")
      else if (.not. (rel_tol >= 1.0e-10_dp .and. rel_tol <= 0.1_dp)) then
         ! below 1e-10 the solver's own accuracy is the limit; above 0.1 no table
         call fatal_error(error, egw_invalid_argument, "rel_tol = "//format_real(rel_tol)// &
            & ": must lie in [1e-10, 0.1]")
      else if (.not. is_rough(params) .and. .not. delta_max > 0.0_dp) then
         call fatal_error(error, egw_invalid_argument, "delta_max = "// &
            & format_real(delta_max)//": smooth spheres need delta_max > 0")
      else if (is_rough(params)) then
         call check_scaled_overlap("delta_max", delta_max, params%sigma, error)
      else if (.not. (ieee_is_finite(hertz_force(delta_max, params%radius, params%modulus)) &
         & .and. ieee_is_finite(hertz_stiffness(delta_max, params%radius, params%modulus)))) then
         call fatal_error(error, egw_invalid_argument, "delta_max = "//format_real(delta_max) &
            & //": the Hertz force (4/3) E sqrt(R) delta**1.5 or stiffness exceeds the " &
            & //"largest double")
      end if
   end subroutine check_request

   pure function point_options(options, rel_tol) result(opts)
      type(solver_options), intent(in) :: options
      real(dp), intent(in) :: rel_tol
      type(solver_options) :: opts
      opts = options
      opts%n_threads = 1
      opts%rel_tol = min(options%rel_tol, 0.1_dp*rel_tol)
   end function point_options

   pure real(dp) function reference_overlap(params, delta_max)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: delta_max
      if (is_rough(params)) then
         reference_overlap = min(0.0_dp, delta_max)
      else
         reference_overlap = delta_max
      end if
   end function reference_overlap

   !> Fritsch-Carlson: where the data are monotone (increasing values, non-negative
   !> slopes) the cubic is monotone if alpha^2 + beta^2 <= 9 (alpha, beta = end slopes
   !> over the secant). Otherwise the interval is split.
   pure logical function monotone_ok(x0, x1, f0, f1, k0, k1, in_log) result(ok)
      real(dp), intent(in) :: x0, x1, f0, f1, k0, k1
      logical, intent(in) :: in_log
      real(dp) :: s, d0, d1
      if (in_log) then
         s = (log(f1) - log(f0))/(x1 - x0)
         d0 = k0/f0
         d1 = k1/f1
      else
         s = (f1 - f0)/(x1 - x0)
         d0 = k0
         d1 = k1
      end if
      ok = .true.
      ! where the data differ by round-off only, the secant is noise: nothing to check
      if (abs(f1 - f0) <= 1.0e3_dp*epsilon(f1)*max(abs(f0), abs(f1))) return
      if (s > 0.0_dp .and. d0 >= 0.0_dp .and. d1 >= 0.0_dp) then
         ok = (d0/s)**2 + (d1/s)**2 <= 9.0_dp
      end if
   end function monotone_ok

   !> Relative round-off of the interpolant's slope on a tiny interval: the cubic's
   !> derivative contains (v1 - v0)/h, whose rounding error is ~eps |v|/h. Below this
   !> floor a stiffness mismatch is noise, not interpolation error.
   pure real(dp) function slope_roundoff(x0, x1, f0, f1, k, in_log) result(floor)
      real(dp), intent(in) :: x0, x1, f0, f1, k
      logical, intent(in) :: in_log
      real(dp) :: v
      if (in_log) then
         v = max(abs(log(f0)), abs(log(f1)))*max(f0, f1)
      else
         v = max(abs(f0), abs(f1))
      end if
      floor = huge(1.0_dp)
      if (abs(k) > 0.0_dp) floor = 100*epsilon(1.0_dp)*v/((x1 - x0)*abs(k))
   end function slope_roundoff

   pure real(dp) function rel_diff(a, b)
      real(dp), intent(in) :: a, b
      if (b /= 0.0_dp) then
         rel_diff = abs(a - b)/abs(b)
      else
         rel_diff = abs(a)
      end if
   end function rel_diff

   pure real(dp) function length_scale(params, delta_max)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: delta_max
      if (is_rough(params)) then
         length_scale = params%sigma
      else
         length_scale = abs(delta_max)
      end if
   end function length_scale

end submodule egw_table_build
