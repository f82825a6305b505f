!> Microbenchmark of the evaluation paths on a Hertz + cap hysteresis table (R = 1 mm,
!> E* = 100 GPa, p_y = 1 GPa, [0, 10 delta_y] at 1e-4; doc/stability.md "Stop 50
!> (capu16)"): ns per call of hysteresis_eval, hysteresis_eval_state at rest and moving,
!> hysteresis_energy, best of 7 rounds, over 4096 contacts with turning points in
!> [1.05, 9.95] delta_y, each unloaded to a fraction of its turning point (a quarter of
!> them loading). Each binary builds its own table (main's gap curves, version 2; the
!> force-ratio curves, version 5), so that two libraries can be alternated in one script.
!> Build as tools/bench/cap_local_error.f90; OMP_NUM_THREADS=1 ./cap_eval_microbench
program cap_eval_microbench
   use, intrinsic :: iso_fortran_env, only: int64
   use egw, only: dp, contact_params, model_hertz, solver_options, egw_error, &
      & hysteresis_table, build_hysteresis, hysteresis_eval
   use egw_hysteresis, only: hysteresis_eval_state, hysteresis_state_init, &
      & hysteresis_energy, hysteresis_state_size
   implicit none
   integer, parameter :: n = 4096, sweeps = 100, rounds = 7
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   real(dp) :: delta(n), state(n), wobble(0:63), f, k, m, u, sink, best(4), tt, dy
   real(dp), allocatable :: states(:, :), moving(:, :)
   integer(int64) :: c0, c1, rate
   integer :: i, r, s, stat, j
   dy = (acos(-1.0_dp)*1.0e9_dp/(2*1.0e11_dp))**2*1.0e-3_dp
   call build_hysteresis(contact_params(model=model_hertz, radius=1.0e-3_dp, &
      & modulus=1.0e11_dp, flow_pressure=1.0e9_dp), solver_options(n_threads=1), 0.0_dp, &
      & 10*dy, 1.0e-4_dp, t, err)
   if (allocated(err)) error stop 1
   do i = 1, n
      state(i) = dy*(1.05_dp + 8.9_dp*modulo(0.7548776662466927_dp*i, 1.0_dp))
      delta(i) = state(i)*(1 - 0.8_dp*modulo(0.5698402909980532_dp*i, 1.0_dp))
      if (mod(i, 4) == 0) delta(i) = state(i) + 0.01_dp*dy
   end do
   allocate (states(hysteresis_state_size, n), moving(hysteresis_state_size, n))
   do i = 1, n
      call hysteresis_state_init(states(:, i))
      call hysteresis_eval_state(t, state(i), states(:, i), f, k, stat)
   end do
   moving = states
   wobble = [(0.02_dp*dy*sin(2*acos(-1.0_dp)*i/64.0_dp), i = 0, 63)]
   best = huge(1.0_dp)
   sink = 0
   do r = 1, rounds
      do j = 1, 4
         call system_clock(c0, rate)
         do s = 1, sweeps
            do i = 1, n
               select case (j)
               case (1)
                  m = state(i)
                  call hysteresis_eval(t, delta(i), m, f, k, stat)
                  sink = sink + f
               case (2)
                  call hysteresis_eval_state(t, delta(i), states(:, i), f, k, stat)
                  sink = sink + f
               case (3)
                  call hysteresis_eval_state(t, delta(i) + wobble(iand(s + i, 63)), &
                     & moving(:, i), f, k, stat)
                  sink = sink + f
               case (4)
                  call hysteresis_energy(t, delta(i), state(i), u, stat)
                  sink = sink + u
               end select
            end do
         end do
         call system_clock(c1)
         tt = real(c1 - c0, dp)/real(rate, dp)/(sweeps*n)
         best(j) = min(best(j), tt)
      end do
   end do
   print '(a,i0,a,i0,a,4f9.2,a,es10.3)', 'nodes ', size(t%m), ' x ', size(t%s), &
      & ' ns: eval rest moving energy ', best*1e9, ' sum ', sink
end program cap_eval_microbench
