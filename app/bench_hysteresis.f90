!> egw-bench --hysteresis: the EP-GW hysteresis table's build time (2 threads, rel_tol 1e-4
!> and 1e-3, delta in [-3, 30] sigma) and its evaluation cost as a ratio to the Hertz force,
!> timed interleaved round by round in one run (issue 10's bench items).
module bench_hysteresis
   use, intrinsic :: iso_fortran_env, only: output_unit, int64
   use egw, only: dp, contact_params, model_epgw, solver_options, egw_error, hertz_force, &
      & hysteresis_table, build_hysteresis, hysteresis_eval
   use bench_common, only: frac
   implicit none
   private
   public :: run_hysteresis

contains

   subroutine run_hysteresis()
      type(contact_params) :: p
      type(solver_options) :: opts
      type(hysteresis_table) :: t
      type(egw_error), allocatable :: err
      integer, parameter :: n = 4096, rounds = 11, sweeps = 200
      real(dp) :: delta(n), state(n), tols(2), sink, f, k, m, t_h, t_y, best_h, best_y
      integer(int64) :: c0, c1, rate
      integer :: i, r, s, stat, it
      p = contact_params(model=model_epgw, radius=1.0_dp, modulus=1.0_dp, sigma=1.0_dp, &
         & mu=4.0_dp, psi=2.0_dp, hardness_coeff=0.6_dp, plastic_ratio=54.0_dp)
      tols = [1.0e-3_dp, 1.0e-4_dp]
      write (output_unit, '(/a)') "== hysteresis table (EP-GW, psi = 2, mu = 4; delta in "// &
         & "[-3, 30] sigma; OpenMP over the delta_max nodes)"
      do it = 1, 2
         call system_clock(c0, rate)
         call build_hysteresis(p, opts, -3.0_dp, 30.0_dp, tols(it), t, err)
         call system_clock(c1)
         if (allocated(err)) then
            write (output_unit, '(a)') "  build failed: "//err%message
            return
         end if
         write (output_unit, '(a,es8.1,a,f8.2,a,i0,a,es9.2)') "  build rel_tol ", tols(it), &
            & ": ", real(c1 - c0, dp)/real(rate, dp), " s, ", size(t%m), &
            & " delta_max nodes, max error at checks ", t%max_error
         write (output_unit, '(a,i0,a,f8.2,a)') "    s nodes ", size(t%s), ", evaluation data ", &
            & real(storage_size(t%coef)/8*size(t%coef), dp)/2.0_dp**20, " MiB"
         write (output_unit, '(10f8.3)') t%m
      end do
      ! contacts in all states: loading and unloading from delta_max within the range
      do i = 1, n
         state(i) = -3.0_dp + 33.0_dp*frac(0.7548776662466927_dp*i)
         delta(i) = state(i) - (state(i) + 3.0_dp)*frac(0.5698402909980532_dp*i)
         if (mod(i, 4) == 0) delta(i) = state(i) + 0.1_dp  ! a quarter loading
      end do
      best_h = huge(1.0_dp)
      best_y = huge(1.0_dp)
      sink = 0
      do r = 1, rounds
         call system_clock(c0, rate)
         do s = 1, sweeps
            do i = 1, n
               sink = sink + hertz_force(abs(delta(i)), 1.0_dp, 1.0_dp)
            end do
         end do
         call system_clock(c1)
         t_h = real(c1 - c0, dp)/real(rate, dp)/(sweeps*n)*1.0e9_dp
         call system_clock(c0, rate)
         do s = 1, sweeps
            do i = 1, n
               m = state(i)
               call hysteresis_eval(t, delta(i), m, f, k, stat)
               sink = sink + f
            end do
         end do
         call system_clock(c1)
         t_y = real(c1 - c0, dp)/real(rate, dp)/(sweeps*n)*1.0e9_dp
         best_h = min(best_h, t_h)
         best_y = min(best_y, t_y)
      end do
      write (output_unit, '(a,f7.2,a,f7.2,a,f6.2,a)') "  eval (rel_tol 1e-4 table): ", &
         & best_y, " ns/call, Hertz force ", best_h, " ns/call: ratio ", best_y/best_h, &
         & " (goal <= 3)"
      write (output_unit, '(a,es10.3)') "  (checksum, ignore) ", sink
   end subroutine run_hysteresis

end module bench_hysteresis
