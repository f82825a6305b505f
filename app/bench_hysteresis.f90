!> egw-bench hysteresis section (issue 10 item 4): build time of an EP-GW hysteresis table
!> at rel_tol 1e-4 over delta in [-3 sigma, 30 sigma] on 2 OpenMP threads (goal <= 30 s),
!> and the cost of hysteresis_eval against the closed-form Hertz force (goal <= 3x) over
!> the overlaps and histories of DEM impacts (loading and unloading mixed). Rows go to
!> out/bench/hysteresis.csv (doc/bench/ with --update-docs).
module bench_hysteresis
   use, intrinsic :: iso_fortran_env, only: output_unit
   use omp_lib, only: omp_set_num_threads
   use egw, only: dp, contact_params, solver_options, egw_error, model_epgw, hertz_force, &
      & hysteresis_table, build_hysteresis, hysteresis_eval
   use bench_common, only: wall, frac, open_csv, write_row, close_csv, fmt_e, fmt_i
   implicit none
   private

   public :: run_hysteresis

   integer, parameter :: n_eval = 4096   !< contacts per sweep (fit in cache)

contains

   !> Build (2 threads, timed once) and evaluation ratio (best of repeats, interleaved).
   subroutine run_hysteresis(quick)
      logical, intent(in) :: quick
      type(contact_params) :: p
      type(hysteresis_table) :: h
      type(egw_error), allocatable :: error
      real(dp) :: t0, t_build, d(n_eval), peak(n_eval), t_hertz, t_hyst, acc, f, k, st, tol
      integer :: unit, r, s, j, repeats, sweeps, stat
      real(dp), parameter :: lo = -3, hi = 30
      character(len=8) :: tol_str
      tol = 1.0e-4_dp
      if (quick) tol = 1.0e-2_dp
      write (tol_str, '(es8.1)') tol
      p = contact_params(model=model_epgw, radius=1.0_dp, modulus=1.0_dp, sigma=1.0_dp, &
         & mu=4.0_dp, psi=1.0_dp)
      call omp_set_num_threads(2)
      t0 = wall()
      call build_hysteresis(p, solver_options(), lo, hi, tol, h, error)
      t_build = wall() - t0
      call open_csv("hysteresis.csv", unit)
      if (allocated(error)) then
         write (output_unit, '(a)') "hysteresis: build failed: "//error%message
         call write_row(unit, "hysteresis", "build", "EP-GW mu=4 psi=1", "rel_tol="// &
            & trim(tol_str), t_build, -1.0_dp, "-", error%stat, "")
         call close_csv(unit)
         return
      end if
      ! impacts: overlap d(j) and history peak(j) >= d(j) (a third of them loading)
      do j = 1, n_eval
         peak(j) = lo + (hi - lo)*frac(0.6180339887498949_dp*j)
         d(j) = lo + (peak(j) - lo)*frac(0.7548776662466927_dp*j)
         if (mod(j, 3) == 0) d(j) = peak(j)
      end do
      repeats = 11
      if (quick) repeats = 3
      sweeps = 200
      t_hertz = huge(1.0_dp)
      t_hyst = huge(1.0_dp)
      acc = 0
      do r = 1, repeats
         t0 = wall()
         do s = 1, sweeps
            do j = 1, n_eval
               acc = acc + hertz_force(d(j), 1.0_dp, 1.0_dp)
            end do
         end do
         t_hertz = min(t_hertz, (wall() - t0)/real(n_eval*sweeps, dp)*1.0e9_dp)
         t0 = wall()
         do s = 1, sweeps
            do j = 1, n_eval
               st = peak(j)
               call hysteresis_eval(h, d(j), st, f, k, stat)
               acc = acc + f + k
            end do
         end do
         t_hyst = min(t_hyst, (wall() - t0)/real(n_eval*sweeps, dp)*1.0e9_dp)
      end do
      write (output_unit, '(a)') "hysteresis table (EP-GW, mu = 4, psi = 1, delta in "// &
         & "[-3, 30] sigma, rel_tol "//trim(tol_str)//", 2 threads)"
      write (output_unit, '(a,f8.2,a)') "   build                    ", t_build, " s (goal <= 30)"
      write (output_unit, '(a,i0,a,es9.2)') "   nodes                    ", &
         & size(h%m), " histories; max check error ", h%max_error
      write (output_unit, '(a,f8.2,a)') "   Hertz force              ", t_hertz, " ns"
      write (output_unit, '(a,f8.2,a,f6.2,a)') "   hysteresis_eval (F+K)    ", t_hyst, &
         & " ns  ratio ", t_hyst/t_hertz, " x Hertz F (goal <= 3)"
      if (acc == 0.5_dp) write (output_unit, '(a)') ""  ! keep acc alive
      call write_row(unit, "hysteresis", "build", "EP-GW mu=4 psi=1 d=-3..30 sigma", &
         & "rel_tol="//trim(tol_str)//" threads=2", t_build, h%max_error, &
         & "unloading solves at midpoints", 0, "peaks="//fmt_i(size(h%m)))
      call write_row(unit, "hysteresis", "eval F+K", "impact mix", "rel_tol="//trim(tol_str), &
         & t_hyst*1e-9_dp, 0.0_dp, "-", 0, "ratio_F="//fmt_e(t_hyst/t_hertz)//" hertz_F_ns="// &
         & fmt_e(t_hertz))
      call close_csv(unit)
   end subroutine run_hysteresis

end module bench_hysteresis
