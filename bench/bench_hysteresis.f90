!> egw-bench --hysteresis: the EP-GW hysteresis table's build time (2 threads, rel_tol 1e-4
!> and 1e-5, delta in [-3, 30] sigma, turning points from its tail), as a ratio to its
!> loading table's build, its bytes in memory, its error against unloading solves at
!> rel_tol 1e-7 between its nodes, and its evaluation cost as a ratio to the Hertz force,
!> timed interleaved round by round in one run (issues 10 and 22). Rows go to
!> out/bench/hysteresis.csv (doc/bench/ with --update-docs) for the speed-accuracy chart.
module bench_hysteresis
   use, intrinsic :: iso_fortran_env, only: output_unit, int64
   use egw, only: dp, contact_params, model_epgw, solver_options, solve_result, egw_error, &
      & force_table, build_table, &
      & hertz_force, hysteresis_table, build_hysteresis, hysteresis_eval, &
      & hysteresis_eval_state, hysteresis_state_init, hysteresis_state_size, &
      & hysteresis_energy, hysteresis_energy_walk, solve_contact_unload, solve_contact
   use bench_common, only: frac, open_csv, write_row, close_csv, fmt_e
   use bench_floor, only: floor_grid, floor_grid_init, floor_kernel, floor_state_only, &
      & floor_bilinear, floor_linear_cubic, floor_bicubic
   implicit none
   private
   public :: run_hysteresis

contains

   subroutine run_hysteresis()
      type(contact_params) :: p
      type(solver_options) :: opts
      type(hysteresis_table) :: t
      type(force_table) :: loading
      type(egw_error), allocatable :: err
      integer, parameter :: n = 4096, rounds = 11, sweeps = 200
      real(dp) :: delta(n), state(n), tols(2), sink, f, k, m, t_h, t_y, best_h, best_y, &
         & build_s, max_err, t_c, best_c, t_w, best_w, wobble(0:63), t_e, best_e, t_v, &
         & best_v, u
      real(dp), allocatable :: states(:, :), moving(:, :)
      integer(int64) :: c0, c1, rate
      integer :: i, r, s, stat, it, unit
      character(len=8) :: label
      p = contact_params(model=model_epgw, radius=1.0_dp, modulus=1.0_dp, sigma=1.0_dp, &
         & mu=4.0_dp, psi=2.0_dp, hardness_coeff=0.6_dp, plastic_ratio=54.0_dp)
      tols = [1.0e-4_dp, 1.0e-5_dp]
      write (output_unit, '(/a)') "== hysteresis table (EP-GW, psi = 2, mu = 4; delta in "// &
         & "[-3, 30] sigma; OpenMP over the delta_max nodes)"
      ! contacts in all states: loading and unloading from delta_max within the range
      do i = 1, n
         state(i) = -3.0_dp + 33.0_dp*frac(0.7548776662466927_dp*i)
         delta(i) = state(i) - (state(i) + 3.0_dp)*frac(0.5698402909980532_dp*i)
         if (mod(i, 4) == 0) delta(i) = state(i) + 0.1_dp  ! a quarter loading
      end do
      call open_csv("hysteresis.csv", unit)
      do it = 1, 2
         call system_clock(c0, rate)
         call build_hysteresis(p, opts, -3.0_dp, 30.0_dp, tols(it), t, err)
         call system_clock(c1)
         if (allocated(err)) then
            write (output_unit, '(a)') "  build failed: "//err%message
            call close_csv(unit)
            return
         end if
         build_s = real(c1 - c0, dp)/real(rate, dp)
         ! the loading table alone, as build_hysteresis builds it first
         call system_clock(c0, rate)
         call build_table(p, opts, -3.0_dp, 30.0_dp, tols(it), loading, err)
         call system_clock(c1)
         write (output_unit, '(a,es8.1,a,f8.2,a,i0,a,i0,a,es9.2)') "  build rel_tol ", &
            & tols(it), ": ", build_s, " s, ", size(t%m), " delta_max nodes x ", size(t%s), &
            & " s nodes, max error at checks ", t%max_error
         write (output_unit, '(a,f9.1,a,f8.3,a,f8.3,a)') "  build / loading table's build: ", &
            & build_s/(real(c1 - c0, dp)/real(rate, dp)), " (", &
            & real(c1 - c0, dp)/real(rate, dp), " s); table in memory ", &
            & table_bytes(t)/1.0e6_dp, " MB"
         max_err = table_error(t, p)
         best_h = huge(1.0_dp)
         best_y = huge(1.0_dp)
         best_c = huge(1.0_dp)
         best_w = huge(1.0_dp)
         best_e = huge(1.0_dp)
         best_v = huge(1.0_dp)
         ! the contacts' states with the turning point's cache (hysteresis_eval_state):
         ! filled by the first sweep, kept with the contacts as a DEM code keeps them
         allocate (states(hysteresis_state_size, n), moving(hysteresis_state_size, n))
         do i = 1, n
            ! loaded to its turning point state(i) (a state egw did not fill is a new contact)
            call hysteresis_state_init(states(:, i))
            call hysteresis_eval_state(t, state(i), states(:, i), f, k, stat)
         end do
         moving = states
         ! DEM-like contacts: each overlap moves by up to 0.02 sigma from sweep to sweep
         ! (a 64-sweep cycle of amplitude 0.2 sigma), so that contacts cross table intervals
         ! and load past their turning points now and then
         wobble = [(0.2_dp*sin(2*acos(-1.0_dp)*i/64.0_dp), i = 0, 63)]
         sink = 0
         do r = 1, rounds
            call system_clock(c0, rate)
            do s = 1, sweeps
               do i = 1, n
                  sink = sink + hertz_force(abs(delta(i)), 1.0_dp, 1.0_dp)
               end do
            end do
            call system_clock(c1)
            t_h = real(c1 - c0, dp)/real(rate, dp)/(sweeps*n)
            call system_clock(c0, rate)
            do s = 1, sweeps
               do i = 1, n
                  m = state(i)
                  call hysteresis_eval(t, delta(i), m, f, k, stat)
                  sink = sink + f
               end do
            end do
            call system_clock(c1)
            t_y = real(c1 - c0, dp)/real(rate, dp)/(sweeps*n)
            call system_clock(c0, rate)
            do s = 1, sweeps
               do i = 1, n
                  call hysteresis_eval_state(t, delta(i), states(:, i), f, k, stat)
                  sink = sink + f
               end do
            end do
            call system_clock(c1)
            t_c = real(c1 - c0, dp)/real(rate, dp)/(sweeps*n)
            call system_clock(c0, rate)
            do s = 1, sweeps
               do i = 1, n
                  call hysteresis_eval_state(t, delta(i) + wobble(iand(s + i, 63)), &
                     & moving(:, i), f, k, stat)
                  sink = sink + f
               end do
            end do
            call system_clock(c1)
            t_w = real(c1 - c0, dp)/real(rate, dp)/(sweeps*n)
            ! the energy each contact returns if it separates now (LAMMPS tallies it on
            ! energy steps): the dips from the table's samples, and the walk over the span
            ! (the evaluation before the samples; 1/50 of the sweeps)
            call system_clock(c0, rate)
            do s = 1, sweeps
               do i = 1, n
                  call hysteresis_energy(t, delta(i), state(i), u, stat)
                  sink = sink + u
               end do
            end do
            call system_clock(c1)
            t_e = real(c1 - c0, dp)/real(rate, dp)/(sweeps*n)
            call system_clock(c0, rate)
            do s = 1, sweeps/50
               do i = 1, n
                  call hysteresis_energy_walk(t, delta(i), state(i), u, stat)
                  sink = sink + u
               end do
            end do
            call system_clock(c1)
            t_v = real(c1 - c0, dp)/real(rate, dp)/((sweeps/50)*n)
            best_e = min(best_e, t_e)
            best_v = min(best_v, t_v)
            best_w = min(best_w, t_w)
            best_h = min(best_h, t_h)
            best_y = min(best_y, t_y)
            best_c = min(best_c, t_c)
         end do
         deallocate (states, moving)
         write (output_unit, '(a,f7.2,a,f7.2,a,f6.2,a,es9.2)') "  eval: ", best_y*1e9, &
            & " ns/call (F and K), Hertz force ", best_h*1e9, " ns/call: ratio ", &
            & best_y/best_h, " (goal <= 3); max error vs solves ", max_err
         write (output_unit, '(a,f7.2,a,f6.2)') "  eval with a state (hysteresis_eval_state), "// &
            & "contacts at rest: ", best_c*1e9, " ns/call: ratio ", best_c/best_h
         write (output_unit, '(a,f7.2,a,f6.2)') "  eval with a state, contacts moving "// &
            & "(DEM-like steps):   ", best_w*1e9, " ns/call: ratio ", best_w/best_h
         write (output_unit, '(a,f8.1,a,f6.2,a,f9.1,a,f8.1,a)') "  energy (hysteresis_energy): ", &
            & best_e*1e9, " ns/call: / eval ", best_e/best_y, "; the walk over the span: ", &
            & best_v*1e9, " ns/call: / eval ", best_v/best_y, ""
         write (label, '(es7.1)') tols(it)
         call write_row(unit, "hysteresis", "hysteresis table", "EP-GW psi=2 mu=4 mix", &
            & "rel_tol="//trim(label), best_y, max_err, &
            & "solve_contact_unload rel_tol=1e-7", 0, "build_s="//fmt_e(build_s)// &
            & " hertz_s="//fmt_e(best_h)//" n_m="//itoa(size(t%m))//" n_s="// &
            & itoa(size(t%s)))
         call write_row(unit, "hysteresis", "hysteresis table state", &
            & "EP-GW psi=2 mu=4 mix", "rel_tol="//trim(label), best_c, max_err, &
            & "solve_contact_unload rel_tol=1e-7", 0, "hysteresis_eval_state at rest "// &
            & "hertz_s="//fmt_e(best_h))
         call write_row(unit, "hysteresis", "hysteresis table state moving", &
            & "EP-GW psi=2 mu=4 mix", "rel_tol="//trim(label), best_w, max_err, &
            & "solve_contact_unload rel_tol=1e-7", 0, "hysteresis_eval_state DEM-like "// &
            & "hertz_s="//fmt_e(best_h))
         write (output_unit, '(a,es10.3)') "  (checksum, ignore) ", sink
         if (it == size(tols)) call time_floor(t, delta, state)
      end do
      call close_csv(unit)
   end subroutine run_hysteresis

   !> The floor of a one-double evaluation (bench_floor's kernels on a uniform grid with as
   !> many cells as table t, the same contacts), timed round by round with the Hertz force
   !> and hysteresis_eval: ratios from one run.
   subroutine time_floor(t, delta, state)
      type(hysteresis_table), intent(in) :: t
      real(dp), intent(in) :: delta(:), state(:)
      integer, parameter :: rounds = 11, sweeps = 200, n_kernel = 6
      character(len=*), parameter :: names(n_kernel) = [character(len=40) :: &
         & "Hertz force", "hysteresis_eval", "floor: state update and call only", &
         & "floor: one bilinear cell", "floor: one linear x cubic cell", &
         & "floor: one bicubic cell"]
      type(floor_grid) :: g
      type(floor_kernel) :: kernels(n_kernel)
      real(dp) :: best(n_kernel), sink, f, k, m, dt
      integer(int64) :: c0, c1, rate
      integer :: r, s, i, kernel, stat
      call floor_grid_init(g, size(t%m) - 1, size(t%s) - 1, t%m(1), t%m(size(t%m)))
      kernels(3)%run => floor_state_only
      kernels(4)%run => floor_bilinear
      kernels(5)%run => floor_linear_cubic
      kernels(6)%run => floor_bicubic
      best = huge(1.0_dp)
      sink = 0
      do r = 1, rounds
         do kernel = 1, n_kernel
            call system_clock(c0, rate)
            do s = 1, sweeps
               select case (kernel)
               case (1)
                  do i = 1, size(delta)
                     sink = sink + hertz_force(abs(delta(i)), 1.0_dp, 1.0_dp)
                  end do
               case (2)
                  do i = 1, size(delta)
                     m = state(i)
                     call hysteresis_eval(t, delta(i), m, f, k, stat)
                     sink = sink + f
                  end do
               case default
                  do i = 1, size(delta)
                     m = state(i)
                     call kernels(kernel)%run(g, delta(i), m, f, k, stat)
                     sink = sink + f
                  end do
               end select
            end do
            call system_clock(c1)
            dt = real(c1 - c0, dp)/real(rate, dp)/(sweeps*size(delta))
            best(kernel) = min(best(kernel), dt)
         end do
      end do
      write (output_unit, '(a,i0,a,i0,a)') "  the floor of a one-double evaluation (bench_floor: "// &
         & "uniform grid of ", g%n_m, " x ", g%n_s, " synthetic cells, no checks, the same "// &
         & "contacts, best of 11 rounds):"
      do kernel = 1, n_kernel
         write (output_unit, '(4x,a,f7.2,a,f6.2)') names(kernel), best(kernel)*1e9, &
            & " ns/call: ratio ", best(kernel)/best(1)
      end do
      write (output_unit, '(a,es10.3)') "  (checksum, ignore) ", sink
   end subroutine time_floor

   !> Largest |P_table - P_solve| relative to the force at the turning point, over five
   !> delta_max between nodes and six overlaps on each of their unloading curves (solves at
   !> rel_tol 1e-7, independent of the table's nodes).
   real(dp) function table_error(t, p) result(worst)
      type(hysteresis_table), intent(in) :: t
      type(contact_params), intent(in) :: p
      real(dp), parameter :: m_at(5) = [-1.3_dp, 0.7_dp, 3.1_dp, 11.9_dp, 27.3_dp], &
         & s_at(6) = [0.013_dp, 0.09_dp, 0.27_dp, 0.46_dp, 0.71_dp, 0.93_dp]
      type(solver_options) :: fine
      type(solve_result) :: top, res
      type(egw_error), allocatable :: err
      real(dp) :: d, f, k, state
      integer :: i, j, stat, n_checked
      fine%rel_tol = 1.0e-7_dp
      worst = 0.0_dp
      n_checked = 0
      do j = 1, size(m_at)
         call solve_contact(p, fine, m_at(j), top, err)
         if (allocated(err)) cycle
         do i = 1, size(s_at)
            d = m_at(j) - (m_at(j) - t%loading%cutoff)*s_at(i)
            call solve_contact_unload(p, fine, d, m_at(j), res, err)
            if (allocated(err)) cycle
            state = m_at(j)
            call hysteresis_eval(t, d, state, f, k, stat)
            worst = max(worst, abs(f - res%force)/top%force)
            n_checked = n_checked + 1
         end do
      end do
      if (n_checked < 20) worst = -1.0_dp   ! too few reference solves: no error reported
   end function table_error

   pure function itoa(i) result(s)
      integer, intent(in) :: i
      character(len=:), allocatable :: s
      character(len=12) :: buf
      write (buf, '(i0)') i
      s = trim(buf)
   end function itoa

   !> Bytes a hysteresis table holds in memory: its stored data, its evaluation data and
   !> its loading table's (nodes and cubics).
   pure real(dp) function table_bytes(t) result(bytes)
      type(hysteresis_table), intent(in) :: t
      bytes = 8.0_dp*(size(t%m) + size(t%length) + size(t%inv_span) + size(t%s) + &
         & size(t%gap) + size(t%slope) + size(t%coef) + size(t%inv_ds) + &
         & size(t%gap_integral) + size(t%lagrange)) + 4.0_dp*(size(t%run_first) + &
         & size(t%run_last) + size(t%m_lookup%bucket) + size(t%s_lookup%bucket)) + &
         & 8.0_dp*(6*size(t%loading%delta) + size(t%loading%seg)) + &
         & 4.0_dp*size(t%loading%bucket)
      ! (log-ratio tables: gap and slope side by side for the states' refills)
      if (allocated(t%gap_slope)) bytes = bytes + 8.0_dp*size(t%gap_slope)
   end function table_bytes

end module bench_hysteresis
