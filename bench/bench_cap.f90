!> egw-bench --cap: the Hertz + cap hysteresis table's build time (doc/theory.md §12;
!> issue 32's goal: <= 2 s at rel_tol 1e-4 on 2 threads) for R = 1 mm, E* = 100 GPa,
!> p_y = 1 GPa over [0, 10 delta_y] at rel_tol 1e-3, 3e-4 and 1e-4 and over [0, 35 delta_y]
!> at 3e-4 and 1e-4, and each table's largest error against cap_unload solves (the public
!> solve_contact_unload) between its nodes, relative to the force at the turning point,
!> and relative to max(P, 1e-3 P(m)) down the curves to their residual overlap (issue 33
!> item 5; local_error).
module bench_cap
   use, intrinsic :: iso_fortran_env, only: output_unit, int64
   use egw, only: dp, contact_params, model_hertz, solver_options, solve_result, &
      & egw_error, hysteresis_table, build_hysteresis, hysteresis_eval, solve_contact, &
      & solve_contact_unload, loading_history, load_history, solve_unload
   implicit none
   private
   public :: run_cap

contains

   subroutine run_cap()
      real(dp), parameter :: radius = 1.0e-3_dp, modulus = 1.0e11_dp, py = 1.0e9_dp
      real(dp), parameter :: tols(5) = [1.0e-3_dp, 3.0e-4_dp, 1.0e-4_dp, 3.0e-4_dp, &
         & 1.0e-4_dp], ranges(5) = [10.0_dp, 10.0_dp, 10.0_dp, 35.0_dp, 35.0_dp]
      type(contact_params) :: p
      type(solver_options) :: opts
      type(hysteresis_table) :: t
      type(egw_error), allocatable :: err
      integer(int64) :: c0, c1, rate
      real(dp) :: delta_y, build_s
      integer :: i
      character(len=160) :: load
      integer :: u, ios
      p = contact_params(model=model_hertz, radius=radius, modulus=modulus, &
         & flow_pressure=py)
      delta_y = (acos(-1.0_dp)*py/(2.0_dp*modulus))**2*radius
      opts%n_threads = 2
      load = ""
      open (newunit=u, file="/proc/loadavg", action="read", iostat=ios)
      if (ios == 0) read (u, '(a)', iostat=ios) load
      if (ios == 0) close (u)
      write (output_unit, '(/a)') "== Hertz + cap hysteresis table (R = 1 mm, E* = 100 GPa, "// &
         & "p_y = 1 GPa; 2 threads; load "//trim(load)//")"
      do i = 1, size(tols)
         call system_clock(c0, rate)
         call build_hysteresis(p, opts, 0.0_dp, ranges(i)*delta_y, tols(i), t, err)
         call system_clock(c1)
         if (allocated(err)) then
            write (output_unit, '(a,es8.1,a,f5.1,a)') "  rel_tol ", tols(i), " to ", &
               & ranges(i), " delta_y: build failed: "//err%message
            deallocate (err)
            cycle
         end if
         build_s = real(c1 - c0, dp)/real(rate, dp)
         write (output_unit, '(a,es8.1,a,f5.1,a,f8.2,a,i0,a,i0,a,es9.2,a,es9.2)') &
            & "  rel_tol ", tols(i), " to ", ranges(i), " delta_y: ", build_s, " s, ", &
            & size(t%m), " turning points x ", size(t%s), " s nodes; worst error vs solves ", &
            & table_error(t, p, ranges(i)*delta_y), " of P(m), of max(P, 1e-3 P(m)) ", &
            & local_error(t, p, delta_y, ranges(i)*delta_y)
      end do
   end subroutine run_cap

   !> Largest |P_table - P_solve|/max(P_solve, 1e-3 P(m)) (issue 33 item 5: the
   !> tolerance relative to the local force down to 1e-3 of the turning point's) over 12
   !> turning points as table_error's and 33 overlaps on each unloading curve, graded
   !> toward its residual overlap delta_r (bisected on the solves): delta - delta_r from
   !> m - delta_r down to 1e-4 of it (P from P(m) down to ~1e-6 P(m)).
   real(dp) function local_error(t, p, delta_y, top) result(worst)
      type(hysteresis_table), intent(in) :: t
      type(contact_params), intent(in) :: p
      real(dp), intent(in) :: delta_y, top
      type(loading_history) :: hist
      type(solve_result) :: peak, res
      type(egw_error), allocatable :: err
      real(dp) :: m, d, f, k, state, lo, hi
      integer :: i, j, stat
      worst = -1.0_dp
      do j = 1, 12
         m = top*(0.05_dp + 0.95_dp*(real(j, dp) - 0.377_dp)/12.0_dp)
         if (.not. m > delta_y) cycle   ! (Hertz's: unloading retraces loading)
         call load_history(p, solver_options(), m, hist, peak, err)
         if (allocated(err)) return
         lo = 0.0_dp
         hi = m
         do i = 1, 50
            d = 0.5_dp*(lo + hi)
            call solve_unload(hist, d, res, err)
            if (allocated(err)) return
            if (res%force > 0.0_dp) then
               hi = d
            else
               lo = d
            end if
         end do
         worst = max(worst, 0.0_dp)
         do i = 0, 32
            d = hi + (m - hi)*10.0_dp**(-i/8.0_dp)
            call solve_unload(hist, d, res, err)
            if (allocated(err)) return
            state = m
            call hysteresis_eval(t, d, state, f, k, stat)
            worst = max(worst, abs(f - res%force)/max(res%force, 1.0e-3_dp*peak%force))
         end do
      end do
   end function local_error

   !> Largest |P_table - P_solve|/P(m) over 12 turning points between nodes (spread over
   !> (delta_y, delta_max]) and 6 overlaps on each unloading curve, solves on the public
   !> options (the cap solver's, ~3e-6 of the reference).
   real(dp) function table_error(t, p, top) result(worst)
      type(hysteresis_table), intent(in) :: t
      type(contact_params), intent(in) :: p
      real(dp), intent(in) :: top
      real(dp), parameter :: s_at(6) = [0.013_dp, 0.09_dp, 0.27_dp, 0.46_dp, 0.71_dp, 0.93_dp]
      type(solver_options) :: opts
      type(solve_result) :: peak, res
      type(egw_error), allocatable :: err
      real(dp) :: m, d, f, k, state
      integer :: i, j, stat
      worst = 0.0_dp
      do j = 1, 12
         m = top*(0.05_dp + 0.95_dp*(real(j, dp) - 0.377_dp)/12.0_dp)
         call solve_contact(p, opts, m, peak, err)
         if (allocated(err)) then
            worst = -1.0_dp
            return
         end if
         do i = 1, size(s_at)
            d = m*(1.0_dp - s_at(i))
            call solve_contact_unload(p, opts, d, m, res, err)
            if (allocated(err)) then
               worst = -1.0_dp
               return
            end if
            state = m
            call hysteresis_eval(t, d, state, f, k, stat)
            worst = max(worst, abs(f - res%force)/peak%force)
         end do
      end do
   end function table_error

end module bench_cap
