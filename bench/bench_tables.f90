!> egw-bench table sections: evaluation cost of 1-D and universal tables against the
!> closed-form Hertz force (issue 4 item 3), table resolution and interpolation order
!> (cubic Hermite vs linear interpolation of the same nodes) against error (issue 5
!> item 1), and build times with 1 and 2 OpenMP threads (issue 5 item 5).
module bench_tables
   use, intrinsic :: iso_fortran_env, only: output_unit
   use omp_lib, only: omp_set_num_threads
   use egw_all, only: dp, contact_params, solver_options, solve_result, solve_contact, egw_error, &
      & model_hertz, model_egw, force_table, build_table, table_eval, table_interval, &
      & universal_table, build_universal, universal_eval, universal_slice, hertz_force, &
      & hertz_stiffness
   use bench_common, only: wall, frac, open_csv, write_row, close_csv, reference_force, &
      & fmt_e, fmt_i, fmt_s
   implicit none
   private

   public :: run_tables, run_universal, run_build_speedup

   integer, parameter :: n_eval = 4096   !< overlaps per sweep (fit in cache)
   integer, parameter :: repeats = 11    !< best of 11: sheds the noise of a shared machine

   !> Scene of the 1-D tables, scaled (R = E = sigma = 1): mu = 4, overlaps from 6 sigma
   !> apart to 50 sigma (a 1 mm sphere with 1 um roughness pressed 50 um).
   real(dp), parameter :: mu_scene = 4, d_lo = -6, d_hi = 50
   !> Tolerance of the table whose build is timed with 1 and 2 threads.
   real(dp), parameter :: speedup_tol = 1.0e-7_dp

contains

   !> The overlaps a DEM collision visits: delta(t) = d_lo + (d_hi - d_lo) sin(pi u),
   !> u quasi-uniform in [0, 1] (a half-sine impact, approach and rebound included).
   function collision_mix(lo, hi) result(d)
      real(dp), intent(in) :: lo, hi
      real(dp) :: d(n_eval)
      integer :: i
      real(dp), parameter :: pi = acos(-1.0_dp)
      do i = 1, n_eval
         d(i) = lo + (hi - lo)*sin(pi*frac(0.6180339887498949_dp*i))
      end do
   end function collision_mix

   !> ns per call of each evaluation in `which` over the overlaps d: the evaluations are
   !> timed in turn within each of `repeats` rounds and the best round of each is kept, so
   !> that load from other processes on the shared machine hits all of them alike and
   !> their ratios stay meaningful. 1 Hertz force, 2 Hertz force + stiffness,
   !> 3 table_eval (Hermite), 4 linear interpolation of the nodes, 5 universal_eval with
   !> mu = mus(j).
   function eval_ns(which, d, table, u, mus) result(t)
      integer, intent(in) :: which(:)
      real(dp), intent(in) :: d(:)
      type(force_table), intent(in) :: table
      type(universal_table), intent(in), optional :: u
      real(dp), intent(in), optional :: mus(:)
      real(dp) :: t(size(which)), acc, f, k, t0
      integer :: r, s, j, w, sweeps, stat
      sweeps = 200
      t = huge(1.0_dp)
      do r = 1, repeats
         do w = 1, size(which)
            acc = 0
            t0 = wall()
            do s = 1, sweeps
               select case (which(w))
               case (1)
                  do j = 1, size(d)
                     acc = acc + hertz_force(d(j), 1.0_dp, 1.0_dp)
                  end do
               case (2)
                  do j = 1, size(d)
                     acc = acc + hertz_force(d(j), 1.0_dp, 1.0_dp) + &
                        & hertz_stiffness(d(j), 1.0_dp, 1.0_dp)
                  end do
               case (3)
                  do j = 1, size(d)
                     call table_eval(table, d(j), f, k)
                     acc = acc + f + k
                  end do
               case (4)
                  do j = 1, size(d)
                     call linear_eval(table, d(j), f, k)
                     acc = acc + f + k
                  end do
               case (5)
                  do j = 1, size(d)
                     call universal_eval(u, 1.0_dp, 1.0_dp, 1.0_dp, mus(j), d(j), f, k, stat)
                     acc = acc + f + k
                  end do
               end select
            end do
            t(w) = min(t(w), (wall() - t0)/real(size(d)*sweeps, dp)*1.0e9_dp)
            if (acc == -1.0_dp) write (output_unit, *) acc   ! keeps acc alive
         end do
      end do
   end function eval_ns

   !> Linear interpolation of the table's nodes (the comparison order): linear in P, and
   !> linear in ln P on the table's log-space tail intervals (as the Hermite cubic is).
   !> Same interval lookup as table_eval, so only the interpolation order differs.
   pure subroutine linear_eval(table, delta, force, stiffness)
      type(force_table), intent(in) :: table
      real(dp), intent(in) :: delta
      real(dp), intent(out) :: force, stiffness
      integer :: i
      real(dp) :: s, h
      force = 0
      stiffness = 0
      if (.not. (delta > table%cutoff .and. delta < table%delta_max)) then
         call table_eval(table, delta, force, stiffness)
         return
      end if
      i = table_interval(table, delta)
      h = table%delta(i + 1) - table%delta(i)
      s = (delta - table%delta(i))/h
      if (i > table%n_log) then
         force = table%force(i) + s*(table%force(i + 1) - table%force(i))
         stiffness = (table%force(i + 1) - table%force(i))/h
      else
         stiffness = log(table%force(i + 1)/table%force(i))/h
         force = table%force(i)*exp(s*h*stiffness)
         stiffness = force*stiffness
      end if
   end subroutine linear_eval

   !> Reference forces at check overlaps: solves at rel_tol 1e-9 (the solver is checked to
   !> 1e-6 or better against the independent references; its estimate at 1e-9 is below
   !> 5e-10, so this reference is ~1000x tighter than any table measured here).
   subroutine reference_solves(params, d, p)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: d(:)
      real(dp), intent(out) :: p(:)
      type(solve_result) :: res
      type(egw_error), allocatable :: error
      integer :: i
      p = -1
      !$omp parallel do private(res, error) schedule(dynamic)
      do i = 1, size(d)
         call solve_contact(params, solver_options(rel_tol=1.0e-9_dp, n_threads=1), d(i), &
            & res, error)
         if (.not. allocated(error)) p(i) = res%force
      end do
      !$omp end parallel do
   end subroutine reference_solves

   !> Max relative force error of a table (Hermite or linear) at check overlaps where the
   !> reference force is above 1e-3 of the tail's reference force scale (below the table's
   !> cut-off the force is set to 0 by design; that part is the cut-off's, not the
   !> interpolation's, error and is bounded separately by rel_tol * P_ref).
   real(dp) function table_error(table, d, p, linear) result(e)
      type(force_table), intent(in) :: table
      real(dp), intent(in) :: d(:), p(:)
      logical, intent(in) :: linear
      integer :: i
      real(dp) :: f, k
      e = 0
      do i = 1, size(d)
         if (p(i) <= 0 .or. d(i) <= table%cutoff) cycle
         if (linear) then
            call linear_eval(table, d(i), f, k)
         else
            call table_eval(table, d(i), f, k)
         end if
         e = max(e, abs(f/p(i) - 1))
      end do
   end function table_error

   !> The 1-D table sections. Writes <out>/tables.csv and appends build speed-up rows
   !> to the speed-up CSV (unit_speedup).
   subroutine run_tables(quick, unit_speedup)
      logical, intent(in) :: quick
      integer, intent(in) :: unit_speedup
      real(dp), allocatable :: tols(:)
      type(contact_params) :: hertz, rough
      type(force_table) :: table, table_h
      type(egw_error), allocatable :: error
      real(dp) :: d(n_eval), t_hertz, t_hertz_k, t_tab, t_lin, t_build, t0
      real(dp), allocatable :: dchk(:), pchk(:)
      real(dp) :: e_h, f_h, k_h, tt3(3), tt4(4)
      integer :: unit, it, i, n_chk
      type(solver_options) :: opts

      tols = [1e-3_dp, 1e-4_dp, 1e-5_dp, 1e-6_dp, 1e-7_dp]
      if (quick) tols = [1e-3_dp, 1e-5_dp]
      hertz = contact_params(model=model_hertz, radius=1.0_dp, modulus=1.0_dp, sigma=0.0_dp)
      rough = contact_params(model=model_egw, radius=1.0_dp, modulus=1.0_dp, sigma=1.0_dp, &
         & mu=mu_scene)
      opts = solver_options(n_threads=1)
      call omp_set_num_threads(2)
      call open_csv("tables.csv", unit)

      ! Hertz closed form and a Hertz table on the same overlaps (0..d_hi, sigma = 0)
      d = collision_mix(d_lo, d_hi)
      call build_table(hertz, opts, 0.0_dp, d_hi, 1.0e-6_dp, table_h, error)
      if (allocated(error)) then
         write (output_unit, '(a)') "Hertz table: "//error%message
         return
      end if
      tt3 = eval_ns([1, 2, 3], d, table_h)
      t_hertz = tt3(1)
      t_hertz_k = tt3(2)
      t_tab = tt3(3)
      e_h = 0
      do i = 1, n_eval
         call table_eval(table_h, d(i), f_h, k_h)
         if (d(i) > 0) e_h = max(e_h, abs(f_h/hertz_force(d(i), 1.0_dp, 1.0_dp) - 1))
      end do
      write (output_unit, '(/a)') "== table eval: ns per call (best of 11, interleaved),"// &
         & " DEM mix delta/sigma in [-6, 50]"
      write (output_unit, '(a,f8.2)') "   Hertz force (closed form)          ", t_hertz
      write (output_unit, '(a,f8.2)') "   Hertz force + stiffness (closed)   ", t_hertz_k
      write (output_unit, '(a,f8.2,a,f6.2,a,f6.2,a,i0,a,es8.1,a)') &
         & "   Hertz table 1e-6 (F and K)  ", &
         & t_tab, "  ratio ", t_tab/t_hertz, " x Hertz F, ", t_tab/t_hertz_k, &
         & " x Hertz F+K (", size(table_h%delta), " nodes, max error ", e_h, ")"
      call write_row(unit, "eval", "hertz closed form", "F only", "-", t_hertz*1e-9_dp, &
         & 0.0_dp, "exact", 0, "ns="//fmt_e(t_hertz))
      call write_row(unit, "eval", "hertz closed form", "F+K", "-", t_hertz_k*1e-9_dp, &
         & 0.0_dp, "exact", 0, "ns="//fmt_e(t_hertz_k))
      call write_row(unit, "eval", "hertz table", "F+K", "rel_tol=1e-6", t_tab*1e-9_dp, &
         & e_h, "hertz_force closed form", 0, "ratio_F="//fmt_e(t_tab/t_hertz)//" ratio_FK="// &
         & fmt_e(t_tab/t_hertz_k)//" nodes="//fmt_i(size(table_h%delta)))

      ! Check overlaps for the E-GW tables' errors: quasi-random over the scene
      n_chk = merge(24, 64, quick)
      allocate (dchk(n_chk), pchk(n_chk))
      do i = 1, n_chk
         dchk(i) = d_lo + (d_hi - d_lo)*frac(0.7548776662466927_dp*i + 0.1_dp)
      end do
      t0 = wall()
      call reference_solves(rough, dchk, pchk)
      write (output_unit, '(a,i0,a,f7.2,a)') "   (", n_chk, &
         & " reference solves at rel_tol 1e-9 in ", wall() - t0, " s)"

      do it = 1, size(tols)
         t0 = wall()
         call build_table(rough, opts, d_lo, d_hi, tols(it), table, error)
         t_build = wall() - t0
         if (allocated(error)) then
            write (output_unit, '(a)') "E-GW table: "//error%message
            deallocate (error)
            cycle
         end if
         ! Hertz again in the same rounds: the ratios of this row are of one moment
         tt4 = eval_ns([1, 2, 3, 4], d, table)
         t_hertz = tt4(1)
         t_hertz_k = tt4(2)
         t_tab = tt4(3)
         t_lin = tt4(4)
         call write_row(unit, "table", "E-GW table hermite", "mu=4 d in [-6:50]", &
            & "rel_tol="//fmt_s(tols(it)), t_tab*1e-9_dp, table_error(table, dchk, pchk, &
            & .false.), "solve rel_tol=1e-9", 0, "nodes="//fmt_i(size(table%delta))// &
            & " build_s="//fmt_e(t_build)//" ratio_F="//fmt_e(t_tab/t_hertz)// &
            & " ratio_FK="//fmt_e(t_tab/t_hertz_k))
         call write_row(unit, "table", "E-GW table linear", "mu=4 d in [-6:50]", &
            & "rel_tol="//fmt_s(tols(it)), t_lin*1e-9_dp, table_error(table, dchk, pchk, &
            & .true.), "solve rel_tol=1e-9", 0, "nodes="//fmt_i(size(table%delta))// &
            & " hertz_F_ns="//fmt_e(t_hertz)//" hertz_FK_ns="//fmt_e(t_hertz_k))
      end do
      call close_csv(unit)

      call run_build_speedup(merge(1, 3, quick), unit_speedup)
   end subroutine run_tables

   !> Build speed-up: the same E-GW table (mu = 4, delta/sigma in [-6, 50]) built with 1
   !> and with 2 OpenMP threads, interleaved, best of n_best each (other processes on the
   !> shared machine then slow both alike). rel_tol 1e-7: the 1e-6 build of this scene hits
   !> the node limit (see doc/benchmarks.md); 1e-7 builds and takes ~0.6 s, enough to time.
   subroutine run_build_speedup(n_best, unit_speedup)
      integer, intent(in) :: n_best, unit_speedup
      type(contact_params) :: rough
      type(force_table) :: table
      type(egw_error), allocatable :: error
      type(solver_options) :: opts
      real(dp) :: tb(2), t0
      integer :: i, nt
      rough = contact_params(model=model_egw, radius=1.0_dp, modulus=1.0_dp, sigma=1.0_dp, &
         & mu=mu_scene)
      opts = solver_options(n_threads=1)
      tb = huge(1.0_dp)
      do i = 1, n_best
         do nt = 1, 2
            call omp_set_num_threads(nt)
            t0 = wall()
            call build_table(rough, opts, d_lo, d_hi, speedup_tol, table, error)
            tb(nt) = min(tb(nt), wall() - t0)
            if (allocated(error)) then
               write (output_unit, '(a)') "   build failed: "//error%message
               deallocate (error)
               tb(nt) = -1
            end if
         end do
      end do
      call omp_set_num_threads(2)
      write (output_unit, '(a,es8.1,a,i0,a,f8.3,a,f8.3,a,f6.3)') "== E-GW table build ", &
         & speedup_tol, " (best of ", n_best, "): 1 thread ", tb(1), " s, 2 threads ", &
         & tb(2), " s, speed-up ", tb(1)/tb(2)
      write (unit_speedup, '(a)') "build_table E-GW mu=4 d -6..50 rel_tol="// &
         & fmt_s(speedup_tol)//","//fmt_i(size(table%delta))// &
         & " nodes,"//fmt_e(tb(1))//","//fmt_e(tb(2))//","//fmt_e(tb(1)/tb(2))
   end subroutine run_build_speedup

   !> The universal table over mu in [0.1, 100], delta/sigma in [-6, 1e3] at rel_tol:
   !> build time (2 threads; and 1 thread if both_threads), eval cost vs Hertz on a
   !> polydisperse mix, error against the independent references (E-GW rows in range).
   subroutine run_universal(rel_tol, both_threads, unit_speedup, unit_csv)
      real(dp), intent(in) :: rel_tol
      logical, intent(in) :: both_threads
      integer, intent(in) :: unit_speedup, unit_csv
      type(universal_table) :: u
      type(egw_error), allocatable :: error
      type(force_table) :: dummy
      real(dp) :: tb(2), t0, d(n_eval), mus(n_eval), t_u, t_hertz, t_hertz_k, f, k, tt3(3)
      real(dp) :: e, emax, pref, d_worst, mu_worst
      ! every E-GW reference row (grid and design sets) inside the table's range
      real(dp), parameter :: dgrid(11) = [-6.0_dp, -3.0_dp, -1.0_dp, 0.0_dp, 1.0_dp, &
         & 2.0_dp, 3.0_dp, 5.0_dp, 10.0_dp, 100.0_dp, 1000.0_dp]
      real(dp), parameter :: mgrid(5) = [0.1_dp, 1.0_dp, 4.0_dp, 10.0_dp, 100.0_dp]
      integer :: nt, j, stat, i, n_ref, n_below
      type(solver_options) :: opts

      opts = solver_options(n_threads=1)
      tb = -1
      do nt = 2, merge(1, 2, both_threads), -1
         call omp_set_num_threads(nt)
         t0 = wall()
         call build_universal(model_egw, 0.0_dp, 0.6_dp, 54.0_dp, opts, 0.1_dp, 100.0_dp, &
            & -6.0_dp, 1000.0_dp, rel_tol, u, error)
         tb(nt) = wall() - t0
         if (allocated(error)) then
            write (output_unit, '(a,i0,a,f8.2,a)') "== universal E-GW table FAILED with ", nt, &
               & " threads after ", tb(nt), " s: "//error%message
            call write_row(unit_csv, "universal", "universal table", &
               & "mu 0.1-100 d -6..1e3", "rel_tol="//fmt_s(rel_tol), tb(nt), -1.0_dp, &
               & "-", error%stat, "build FAILED after "//fmt_e(tb(nt))//" s with "// &
               & fmt_i(nt)//" threads: "//error%message)
            call omp_set_num_threads(2)
            return
         end if
         write (output_unit, '(a,es8.1,a,i0,a,f8.2,a,i0,a,i0,a)') &
            & "== universal E-GW table rel_tol ", rel_tol, " built with ", nt, &
            & " threads in ", tb(nt), " s (", u%n_mu, " mu slices x ", &
            & size(u%slices(1)%delta), " x nodes)"
      end do
      call omp_set_num_threads(2)
      if (both_threads) write (unit_speedup, '(a)') "build_universal E-GW "// &
         & fmt_e(rel_tol)//","//fmt_i(u%n_mu)//" slices,"//fmt_e(tb(1))//","//fmt_e(tb(2)) &
         & //","//fmt_e(tb(1)/tb(2))

      ! eval cost: a polydisperse mix, mu log-uniform in [0.1, 100], collision overlaps
      d = collision_mix(-6.0_dp, 50.0_dp)
      do j = 1, n_eval
         mus(j) = 0.1_dp*1000.0_dp**frac(0.7548776662466927_dp*j)
      end do
      tt3 = eval_ns([1, 2, 5], d, dummy, u, mus)
      t_hertz = tt3(1)
      t_hertz_k = tt3(2)
      t_u = tt3(3)

      ! error against the independent references inside the table's range
      emax = 0
      d_worst = 0
      mu_worst = 0
      n_ref = 0
      n_below = 0
      do i = 1, size(dgrid)
         do j = 1, size(mgrid)
            pref = reference_force("EGW", dgrid(i), mgrid(j), 0.0_dp, 0.0_dp)
            if (pref <= 0) cycle
            ! below the common cut-off the table returns 0 by design (P < rel_tol P_ref
            ! there: the cut-off's absolute error, not an interpolation error)
            if (dgrid(i) <= u%x_cut) then
               n_below = n_below + 1
               cycle
            end if
            call universal_eval(u, 1.0_dp, 1.0_dp, 1.0_dp, mgrid(j), dgrid(i), f, k, stat)
            e = abs(f/pref - 1)
            if (e > emax) then
               d_worst = dgrid(i)
               mu_worst = mgrid(j)
            end if
            emax = max(emax, e)
            n_ref = n_ref + 1
         end do
      end do
      write (output_unit, '(a,f8.2,a,f6.2,a,f6.2,a,es9.2,a,i0,a)') "   eval ", t_u, &
         & " ns = ", t_u/t_hertz, " x Hertz F, ", t_u/t_hertz_k, " x Hertz F+K; max error ", &
         & emax, " over ", n_ref, " reference points above the cut-off"
      write (output_unit, '(a,g0.4,a,g0.4,a,g0.4,a,i0,a)') "   worst at delta/sigma = ", &
         & d_worst, ", mu = ", mu_worst, "; x_cut = ", u%x_cut, " (", n_below, &
         & " reference points below it: force 0 by design)"
      ! the DEM path for a polydisperse scene: a 1-D table cut from the universal table
      ! once per particle pair (here mu = 4), timed interleaved with the Hertz force
      block
         type(force_table) :: slice
         type(egw_error), allocatable :: slice_error
         real(dp) :: ts(3)
         ! trimmed to the collision mix's overlaps (delta <= 50 sigma), as a DEM code would
         call universal_slice(u, contact_params(model=model_egw, radius=1.0_dp, &
            & modulus=1.0_dp, sigma=1.0_dp, mu=4.0_dp), slice, slice_error, delta_max=50.0_dp)
         if (allocated(slice_error)) then
            write (output_unit, '(a)') "   universal_slice failed: "//slice_error%message
         else
            ts = eval_ns([1, 2, 3], d, slice)
            write (output_unit, '(a,f8.2,a,f6.2,a,f6.2,a)') &
               & "   per-pair slice (mu = 4, delta <= 50 sigma) eval ", &
               & ts(3), " ns = ", ts(3)/ts(1), " x Hertz F, ", ts(3)/ts(2), " x Hertz F+K"
            call write_row(unit_csv, "universal", "universal per-pair slice", &
               & "mu=4 d -6..50", "rel_tol="//fmt_s(rel_tol), ts(3)*1e-9_dp, emax, &
               & "as the universal table", 0, "ratio_F="//fmt_e(ts(3)/ts(1))// &
               & " ratio_FK="//fmt_e(ts(3)/ts(2)))
         end if
      end block
      call write_row(unit_csv, "universal", "universal table", "mu 0.1-100 d -6..1e3", &
         & "rel_tol="//fmt_s(rel_tol), t_u*1e-9_dp, emax, "sphere_reference.csv", 0, &
         & "build_s_2thr="//fmt_e(tb(2))//" build_s_1thr="//fmt_e(tb(1))//" ratio_F="// &
         & fmt_e(t_u/t_hertz)//" ratio_FK="//fmt_e(t_u/t_hertz_k)//" n_mu="//fmt_i(u%n_mu) &
         & //" n_ref="//fmt_i(n_ref)//" worst_d="//fmt_e(d_worst)// &
         & " worst_mu="//fmt_e(mu_worst)//" x_cut="//fmt_e(u%x_cut)//" n_below_cut="// &
         & fmt_i(n_below))
   end subroutine run_universal

end module bench_tables
