!> The loading curve of a smooth sphere with the flow-pressure cap (doc/theory.md §12) as a
!> force table (egw_table's force_table), for the hysteresis tables of Hertz + cap: Hertz's
!> closed form up to first yield delta_y (a node there: the curvature jumps), the cap's
!> loading solves above it.
!>
!> Slopes: the derivative of the quadratic through each node and its two neighbours
!> (through the last three at the last node), Hertz's exact one at delta_y (the loading
!> stiffness is continuous there). (The cap solver's stiffness is the loading tangent now,
!> egw_cap_sphere's envelope; the quadratic slopes are kept: the checks below see them.) The
!> intervals are bisected until the cubic Hermite with those slopes meets a solve at every
!> midpoint to rel_tol of the force there, and its slope there the chord's (the parabola
!> through the three solves) to rel_tol of the force over 16/h (all intervals are checked
!> again after each round: a split changes its neighbours' slopes).
module egw_cap_loading
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_not_converged, fatal_error, format_real, int_str, &
      & first_failure
   use egw_params, only: contact_params
   use egw_rough_sphere, only: solver_options, solve_result, solve_contact
   use egw_cap_sphere, only: cap_units
   use egw_table, only: force_table, build_table, table_prepare
   implicit none
   private

   public :: build_cap_loading

   !> Most nodes above delta_y (a smooth curve needs far fewer).
   integer, parameter :: max_cap_nodes = 2000

contains

   !> The loading table of params (smooth, flow_pressure > 0) from below delta_min (Hertz's
   !> cut-off, as build_table's) to delta_max, to rel_tol. delta_max <= delta_y: Hertz's
   !> table (the cap never acts). Errors: as build_table; a failed cap solve; rel_tol not
   !> reached within max_cap_nodes nodes (egw_not_converged).
   subroutine build_cap_loading(params, options, delta_min, delta_max, rel_tol, table, &
      & error)
      type(contact_params), intent(in) :: params   !< validated, smooth, flow_pressure > 0
      type(solver_options), intent(in) :: options  !< of the Hertz part (closed form)
      real(dp), intent(in) :: delta_min, delta_max, rel_tol   !< as build_table
      type(force_table), intent(out) :: table   !< the table; empty on error
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      type(contact_params) :: hertz
      type(force_table) :: elastic
      real(dp) :: delta_y, a_y, force_y, worst
      real(dp), allocatable :: x(:), f(:), k(:), a(:)
      integer :: n_e

      call cap_units(params%radius, params%modulus, params%flow_pressure, delta_y, a_y, &
         & force_y)
      hertz = params
      hertz%flow_pressure = 0.0_dp
      if (.not. delta_max > delta_y) then
         call build_table(hertz, options, delta_min, delta_max, rel_tol, table, error)
         if (allocated(error)) return
         table%params = params
         call table_prepare(table)
         return
      end if
      call build_table(hertz, options, min(delta_min, 0.5_dp*delta_y), delta_y, rel_tol, &
         & elastic, error)
      if (allocated(error)) return
      n_e = size(elastic%delta)
      call cap_nodes(params, delta_y, elastic%stiffness(n_e), delta_max, rel_tol, x, f, k, &
         & a, worst, error)
      if (allocated(error)) return
      table%params = params
      table%rel_tol = rel_tol
      table%cutoff = elastic%cutoff
      table%delta_max = x(size(x))
      table%reference_force = f(size(f))
      table%max_force_error = max(elastic%max_force_error, worst)
      table%max_stiffness_error = elastic%max_stiffness_error
      table%radius_sum = 0.0_dp
      table%n_log = 0
      ! the Hertz nodes up to delta_y (exclusive: the cap's first node is delta_y itself)
      table%delta = [elastic%delta(1:n_e - 1), x]
      table%force = [elastic%force(1:n_e - 1), f]
      table%stiffness = [elastic%stiffness(1:n_e - 1), k]
      table%contact_radius = [elastic%contact_radius(1:n_e - 1), a]
      call table_prepare(table)
   end subroutine build_cap_loading

   !> The nodes x from delta_y to delta_max with forces f, slopes k and contact radii a:
   !> 9 nodes graded towards delta_y (quadratically), bisected as the module header says;
   !> worst is the largest relative midpoint error left.
   subroutine cap_nodes(params, delta_y, k_y, delta_max, rel_tol, x, f, k, a, worst, error)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: delta_y, k_y, delta_max, rel_tol
      real(dp), allocatable, intent(out) :: x(:), f(:), k(:), a(:)
      real(dp), intent(out) :: worst
      type(egw_error), allocatable, intent(out) :: error
      real(dp), allocatable :: xm(:), fm(:), am(:), err(:), nx(:), nf(:), na(:), nxm(:), &
         & nfm(:), nam(:), ft(:), at(:)
      logical, allocatable :: have(:), nhave(:)
      integer, allocatable :: todo(:)
      integer :: j, n, i, c, round
      real(dp) :: h, mid_value

      n = 9
      x = delta_y + (delta_max - delta_y)*([(real(j, dp), j=0, n - 1)]/real(n - 1, dp))**2
      x(n) = delta_max
      allocate (f(n), a(n), xm(n - 1), fm(n - 1), am(n - 1), have(n - 1))
      call solve_points(params, x, f, a, error)
      if (allocated(error)) return
      have = .false.
      do round = 1, 60
         todo = pack([(i, i=1, size(x) - 1)], .not. have)
         if (size(todo) > 0) then
            xm(todo) = 0.5_dp*(x(todo) + x(todo + 1))
            allocate (ft(size(todo)), at(size(todo)))
            call solve_points(params, xm(todo), ft, at, error)
            if (allocated(error)) return
            fm(todo) = ft
            am(todo) = at
            deallocate (ft, at)
            have = .true.
         end if
         call quadratic_slopes(x, f, k_y, k)
         allocate (err(size(x) - 1))
         do i = 1, size(x) - 1
            h = x(i + 1) - x(i)
            mid_value = 0.5_dp*(f(i) + f(i + 1)) + h*(k(i) - k(i + 1))/8
            ! and the Hermite slope at the midpoint against the chord, which is the slope
            ! of the parabola through the three solves there: the midpoint value alone
            ! is blind to equal slope errors at both ends (they cancel at t = 1/2, not
            ! at t = 1/4; measured 5e-3 between nodes that passed a 1e-3 value check)
            err(i) = max(abs(mid_value - fm(i)), abs(2*(f(i + 1) - f(i)) - h*(k(i) + &
               & k(i + 1)))/16)/fm(i)
         end do
         worst = maxval(err)
         if (worst <= rel_tol) return
         n = size(x) + count(err > rel_tol)
         if (n > max_cap_nodes) then
            call fatal_error(error, egw_not_converged, "flow_pressure = "// &
               & format_real(params%flow_pressure)//": the cap's loading curve needs more "// &
               & "than "//int_str(max_cap_nodes)//" nodes for rel_tol = "// &
               & format_real(rel_tol)//" (its largest midpoint error still "// &
               & format_real(worst)//")")
            return
         end if
         ! split: a failed interval's midpoint becomes a node, its halves unchecked
         allocate (nx(n), nf(n), na(n), nxm(n - 1), nfm(n - 1), nam(n - 1), nhave(n - 1))
         nhave = .false.
         c = 1
         nx(1) = x(1)
         nf(1) = f(1)
         na(1) = a(1)
         do i = 1, size(x) - 1
            if (err(i) > rel_tol) then
               c = c + 1
               nx(c) = xm(i)
               nf(c) = fm(i)
               na(c) = am(i)
            else
               nxm(c) = xm(i)
               nfm(c) = fm(i)
               nam(c) = am(i)
               nhave(c) = .true.
            end if
            c = c + 1
            nx(c) = x(i + 1)
            nf(c) = f(i + 1)
            na(c) = a(i + 1)
         end do
         call move_alloc(nx, x)
         call move_alloc(nf, f)
         call move_alloc(na, a)
         call move_alloc(nxm, xm)
         call move_alloc(nfm, fm)
         call move_alloc(nam, am)
         call move_alloc(nhave, have)
         deallocate (err)
      end do
      call fatal_error(error, egw_not_converged, "flow_pressure = "// &
         & format_real(params%flow_pressure)//": the cap's loading curve did not settle to "// &
         & "rel_tol = "//format_real(rel_tol)//" after 60 bisections")
   end subroutine cap_nodes

   !> Slopes of the quadratic through each node and its neighbours (the last three at the
   !> end), k(1) = k_first; none negative (the loading force rises).
   pure subroutine quadratic_slopes(x, f, k_first, k)
      real(dp), intent(in) :: x(:), f(:), k_first
      real(dp), allocatable, intent(out) :: k(:)
      real(dp) :: d(size(x) - 1), h(size(x) - 1)
      integer :: n, i
      n = size(x)
      h = x(2:n) - x(1:n - 1)
      d = (f(2:n) - f(1:n - 1))/h
      allocate (k(n))
      k(1) = k_first
      do i = 2, n - 1
         k(i) = (h(i)*d(i - 1) + h(i - 1)*d(i))/(h(i - 1) + h(i))
      end do
      if (n >= 3) then
         k(n) = d(n - 1) + (d(n - 1) - d(n - 2))*h(n - 1)/(h(n - 2) + h(n - 1))
      else
         k(n) = d(n - 1)
      end if
      k = max(k, 0.0_dp)
   end subroutine quadratic_slopes

   !> Loading solves (solve_contact: the cap's above delta_y) at x, in parallel; the first
   !> failure (lowest index) is the error.
   subroutine solve_points(params, x, f, a, error)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: x(:)
      real(dp), intent(out) :: f(:), a(:)
      type(egw_error), allocatable, intent(out) :: error
      type(solver_options) :: serial
      integer :: stats(size(x)), i
      character(len=512) :: messages(size(x))
      serial = solver_options(n_threads=1)
      stats = 0
      !$omp parallel do schedule(dynamic) default(shared) private(i)
      do i = 1, size(x)
         call one_point(i)
      end do
      !$omp end parallel do
      call first_failure(stats, messages, error, "the capped loading solve at delta", x)
   contains
      subroutine one_point(i)
         integer, intent(in) :: i
         type(egw_error), allocatable :: err
         type(solve_result) :: res
         call solve_contact(params, serial, x(i), res, err)
         if (allocated(err)) then
            stats(i) = err%stat
            messages(i) = err%message
            return
         end if
         f(i) = res%force
         a(i) = res%contact_radius
      end subroutine one_point
   end subroutine solve_points

end module egw_cap_loading
