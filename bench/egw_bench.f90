!> egw-bench: speed against accuracy of every egw method, timed in one run (doc/benchmarks.md).
!>   fpm run egw-bench --profile release [-- sections] [--quick]
!> Sections (default: all but --universal-1thread and --peer):
!>   --kernels     ns per call of the kernels, as ratios to libm erfc and the Hertz force
!>   --fn          F_3/2 evaluation paths vs error          -> out/bench/fn.csv
!>   --solver      time per force point vs error, meshes, tolerances, Newton vs Picard
!>                                                           -> out/bench/solver.csv
!>   --assembly    OpenMP speed-up of assemble_influence     -> out/bench/speedup.csv
!>   --tables      1-D table eval vs Hertz, resolutions, Hermite vs linear, build speed-up
!>                                                           -> out/bench/tables.csv
!>   --universal   universal E-GW table (mu 0.1-100, delta/sigma -6..1e3): 1e-4 built with 1
!>                 and 2 threads (speed-up), 1e-6 with 2 threads -> out/bench/universal.csv
!>   --unloading   unloading solve vs loading solve at the same overlap (issue 10)
!>                                                           -> out/bench/unloading.csv
!>   --unloading-sweep  accuracy of solve_contact_unload on 100 cases (92 with a force above
!>                 1e-12) at rel_tol 1e-6, 1e-7
!>                 (not in the default set; ~20 s)
!>   --universal-1thread  also build the 1e-6 universal table with 1 thread
!>   --peer FILE   egw side of the peer comparison (tools/bench/peer_greenwood_tripp.py)
!>   --speedup     only the 1-vs-2-thread measurements: assembly, 1-D table build (best of
!>                 5), universal 1e-4 build -> out/bench/speedup.csv, universal_speedup.csv
!>   --universal-tol X  only the universal table at rel_tol X (2 threads)
!>                 -> out/bench/universal_tol.csv
!>   --cap         Hertz + cap hysteresis table: build time (1e-3 .. 1e-4, 10 and 35 delta_y)
!>                 and its error against unloading solves (2 threads)
!>   --hysteresis  EP-GW hysteresis table: build time (1e-3, 1e-4) and eval / Hertz force
!>                 (and the floor of a one-double evaluation: bench/bench_floor.f90)
!>   --separated   separated contacts (issue 33): egw_table_eval, egw_table_eval_array and
!>                 table_eval of a 1-D E-GW table beyond the cut-off, in the tail and in
!>                 contact, as ratios to an inline Hertz force; not in the default set
!>   --bem         periodic BEM flat law (bem_flat_curve) on the 512^2 and 576^2 maps of
!>                 tools/bench/bem_contactmechanics_time.py (which times ContactMechanics
!>                 and takes the ratio in one run); not in the default set
!>   --quick       fewer cases and shorter timings (a smoke run)
!>   --out DIR     write the CSVs to DIR/ (default out/bench/)
!>   --update-docs write the CSVs to doc/bench/, replacing the committed results that
!>                 doc/benchmarks.md quotes (only when regenerating those on purpose)
!> Run from the project root (reads test/data/sphere_reference.csv, writes out/bench/).
program egw_bench
   use, intrinsic :: iso_fortran_env, only: output_unit, error_unit, int64
   use omp_lib, only: omp_set_num_threads
   use egw, only: dp, gauss_integral, ellipk, rough_flat_law, hertz_force
   use bench_common, only: load_reference, open_csv, close_csv, frac, out_dir
   use bench_fn, only: run_fn
   use bench_solver, only: run_solver, run_assembly, run_peer_cases
   use bench_tables, only: run_tables, run_universal, run_build_speedup
   use bench_hysteresis, only: run_hysteresis
   use bench_cap, only: run_cap
   use bench_unloading, only: run_unloading, run_unloading_sweep
   use bench_bem, only: run_bem
   use bench_separated, only: run_separated
   implicit none

   integer, parameter :: n = 4096        ! inputs per sweep (fit in L1/L2 cache)
   integer, parameter :: repeats = 7     ! best of 7 runs, to shed noise of a shared machine
   real(dp) :: h(n), k(n), delta(n), sink
   real(dp) :: t_erfc, t_hertz, t_f32, t_ellipk, t_pg, t_pg_zmc
   integer :: i, sweeps
   logical :: do_kernels, do_fn, do_solver, do_assembly, do_tables, do_universal, quick
   logical :: universal_1thread, any_section, ok, do_speedup, do_unloading, do_hysteresis, &
      & do_cap, &
      & do_sweep, do_bem, do_separated
   real(dp) :: universal_tol
   character(len=512) :: arg, peer_file
   integer :: unit_speedup, unit_csv

   call parse_arguments()
   call load_reference("test/data/sphere_reference.csv", ok)
   if (.not. ok) write (output_unit, '(a)') "warning: test/data/sphere_reference.csv not"// &
      & " found (run from the project root): solver errors will be -1"
   if (len_trim(peer_file) > 0) then
      call run_peer_cases(trim(peer_file))
      if (.not. any_section) stop
   end if
   if (do_speedup) then
      call open_csv("speedup.csv", unit_speedup, &
         & "what,size,time_1thread_s,time_2threads_s,speedup")
      call run_assembly(unit_speedup)
      call run_build_speedup(5, unit_speedup)
      call open_csv("universal_speedup.csv", unit_csv)
      call run_universal(1.0e-4_dp, .true., unit_speedup, unit_csv)
      call close_csv(unit_csv)
      call close_csv(unit_speedup)
   end if
   if (universal_tol > 0) then
      call open_csv("universal_tol.csv", unit_csv)
      call open_csv("universal_tol_speedup.csv", unit_speedup, &
         & "what,size,time_1thread_s,time_2threads_s,speedup")
      call run_universal(universal_tol, .false., unit_speedup, unit_csv)
      call close_csv(unit_speedup)
      call close_csv(unit_csv)
   end if
   if (do_kernels) call run_kernels()
   if (do_bem) call run_bem()
   if (do_separated) call run_separated()
   if (do_hysteresis) call run_hysteresis()
   if (do_cap) call run_cap()
   if (do_fn) then
      call open_csv("fn.csv", unit_csv)
      call run_fn(unit_csv)
      call close_csv(unit_csv)
   end if
   if (do_solver) call run_solver(quick)
   if (do_unloading) call run_unloading(quick)
   if (do_sweep) call run_unloading_sweep()
   if (do_assembly .or. do_tables .or. do_universal) then
      ! one speed-up CSV for the sections that measure 1 thread against 2
      call open_csv("speedup.csv", unit_speedup, &
         & "what,size,time_1thread_s,time_2threads_s,speedup")
      if (do_assembly) call run_assembly(unit_speedup)
      if (do_tables) call run_tables(quick, unit_speedup)
      if (do_universal) then
         call open_csv("universal.csv", unit_csv)
         ! 1e-4 with 1 and 2 threads (the build speed-up), then the target 1e-6 (2 threads)
         call run_universal(1.0e-4_dp, .not. quick, unit_speedup, unit_csv)
         if (.not. quick) call run_universal(1.0e-6_dp, universal_1thread, unit_speedup, &
            & unit_csv)
         call close_csv(unit_csv)
      end if
      call close_csv(unit_speedup)
   end if

contains

   subroutine parse_arguments()
      integer :: k
      do_kernels = .false.; do_fn = .false.; do_solver = .false.; do_assembly = .false.
      do_tables = .false.; do_universal = .false.; quick = .false.; do_speedup = .false.
      do_hysteresis = .false.
      do_cap = .false.
      do_unloading = .false.
      do_sweep = .false.
      do_bem = .false.
      do_separated = .false.
      universal_tol = 0
      universal_1thread = .false.; peer_file = ""
      out_dir = "out/bench/"
      k = 0
      do while (k < command_argument_count())
         k = k + 1
         call get_command_argument(k, arg)
         select case (trim(arg))
         case ("--kernels"); do_kernels = .true.
         case ("--fn"); do_fn = .true.
         case ("--solver"); do_solver = .true.
         case ("--assembly"); do_assembly = .true.
         case ("--tables"); do_tables = .true.
         case ("--universal"); do_universal = .true.
         case ("--universal-1thread"); do_universal = .true.; universal_1thread = .true.
         case ("--quick"); quick = .true.
         case ("--hysteresis"); do_hysteresis = .true.
         case ("--cap"); do_cap = .true.
         case ("--speedup"); do_speedup = .true.
         case ("--unloading"); do_unloading = .true.
         case ("--unloading-sweep"); do_sweep = .true.
         case ("--bem"); do_bem = .true.
         case ("--separated"); do_separated = .true.
         case ("--universal-tol")
            k = k + 1
            call get_command_argument(k, arg)
            read (arg, *) universal_tol
         case ("--out")
            k = k + 1
            call get_command_argument(k, arg)
            out_dir = trim(arg)//"/"
         case ("--update-docs")
            out_dir = "doc/bench/"
         case ("--peer")
            k = k + 1
            call get_command_argument(k, peer_file)
         case default
            write (error_unit, '(a)') "egw-bench: unknown option "//trim(arg)// &
               & " (see the header of bench/egw_bench.f90)"
            stop 2, quiet=.true.  ! exit status 2, no "STOP" line
         end select
      end do
      any_section = do_kernels .or. do_fn .or. do_solver .or. do_assembly .or. do_tables &
         & .or. do_universal .or. do_speedup .or. universal_tol > 0 .or. do_hysteresis &
         & .or. do_cap &
         & .or. do_unloading .or. do_sweep .or. do_bem .or. do_separated
      if (.not. any_section .and. len_trim(peer_file) == 0) then
         do_kernels = .true.; do_fn = .true.; do_solver = .true.; do_assembly = .true.
         do_tables = .true.; do_universal = .true.; do_unloading = .true.
      end if
   end subroutine parse_arguments

   !> The issue-2 kernel benchmark: ns per call, ratios to erfc and Hertz.
   subroutine run_kernels()
      do i = 1, n
         ! inputs spread over the ranges a solver visits; irregular so nothing is hoisted
         h(i) = -6.0_dp + 14.0_dp*frac(0.6180339887498949_dp*i)
         k(i) = 0.999_dp*frac(0.7548776662466927_dp*i)
         delta(i) = 1.0e-2_dp*frac(0.5698402909980532_dp*i)
      end do
      sweeps = 500
      sink = 0

      t_erfc = best_time(1)
      t_hertz = best_time(2)
      t_f32 = best_time(3)
      t_ellipk = best_time(4)
      t_pg = best_time(5)
      t_pg_zmc = best_time(6)

      write (output_unit, '(a)') "egw-bench: ns per call (best of 7), ratios in one run"
      write (output_unit, '(a)') "kernel                         ns/call   / erfc   / Hertz"
      call row("libm erfc(x)", t_erfc)
      call row("Hertz force (closed form)", t_hertz)
      call row("F_3/2(h)  gauss_integral", t_f32)
      call row("K(k)      ellipk", t_ellipk)
      call row("p_G(h)    elastic + deriv", t_pg)
      call row("p_G(h)    ZMC psi=4 + deriv", t_pg_zmc)
      write (output_unit, '(a,es10.3)') "(checksum, ignore) ", sink
   end subroutine run_kernels

   !> Best time per call, in ns, of kernel `which` over `repeats` runs.
   function best_time(which) result(t)
      integer, intent(in) :: which
      real(dp) :: t
      integer(int64) :: c0, c1, rate
      integer :: r, s, j
      real(dp) :: acc, p, dp_
      t = huge(1.0_dp)
      do r = 1, repeats
         acc = 0
         call system_clock(c0, rate)
         do s = 1, sweeps
            select case (which)
            case (1)
               do j = 1, n
                  acc = acc + erfc(h(j))
               end do
            case (2)
               do j = 1, n
                  acc = acc + hertz_force(delta(j), 1.0_dp, 1.0_dp)
               end do
            case (3)
               do j = 1, n
                  acc = acc + gauss_integral(1.5_dp, h(j))
               end do
            case (4)
               do j = 1, n
                  acc = acc + ellipk(k(j))
               end do
            case (5)
               do j = 1, n
                  call rough_flat_law(h(j), 0.0_dp, 0.6_dp, 54.0_dp, p, dp_)
                  acc = acc + p + dp_
               end do
            case (6)
               do j = 1, n
                  call rough_flat_law(h(j), 4.0_dp, 0.6_dp, 54.0_dp, p, dp_)
                  acc = acc + p + dp_
               end do
            end select
         end do
         call system_clock(c1)
         sink = sink + acc
         t = min(t, real(c1 - c0, dp)/real(rate, dp)*1.0e9_dp/real(n*sweeps, dp))
      end do
   end function best_time

   subroutine row(name, t)
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: t
      write (output_unit, '(a30,f9.2,2f9.2)') name, t, t/t_erfc, t/t_hertz
   end subroutine row

end program egw_bench
