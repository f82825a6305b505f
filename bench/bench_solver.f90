!> egw-bench solver sections: time per force point and its error against the independent
!> references (test/data/sphere_reference.csv) for each tolerance and mesh size, Newton
!> against Picard (issue 3 item 5); the OpenMP speed-up of assemble_influence; and the
!> egw side of the peer comparison (issue 5 item 2).
module bench_solver
   use, intrinsic :: iso_fortran_env, only: output_unit
   use omp_lib, only: omp_set_num_threads
   use egw_all, only: dp, contact_params, solver_options, solve_result, solve_contact, egw_error, &
      & model_gw, model_egw, model_epgw, method_newton, method_picard, radial_mesh, &
      & build_mesh, graded_edges, assemble_influence
   use bench_common, only: wall, open_csv, write_row, close_csv, reference_force, fmt_e, &
      & fmt_i, fmt_s, out_dir
   implicit none
   private

   public :: run_solver, run_assembly, run_peer_cases

   !> One benchmark case (scaled: R = E = sigma = 1, so P = P_scaled).
   type :: solve_case
      character(len=8) :: model = "EGW"
      real(dp) :: delta = 0, mu = 1, psi = 0, k = 0.6
   end type solve_case

contains

   function case_params(c) result(p)
      type(solve_case), intent(in) :: c
      type(contact_params) :: p
      select case (trim(c%model))
      case ("GW")
         p%model = model_gw
      case ("EPGW")
         p%model = model_epgw
      case default
         p%model = model_egw
      end select
      p%radius = 1
      p%modulus = 1
      p%sigma = 1
      p%mu = c%mu
      p%psi = c%psi
      if (c%psi > 0) p%hardness_coeff = c%k
   end function case_params

   function case_name(c) result(s)
      type(solve_case), intent(in) :: c
      character(len=:), allocatable :: s
      s = trim(c%model)//" d="//trim(short(c%delta))//" mu="//trim(short(c%mu))
      if (c%psi > 0) s = s//" psi="//trim(short(c%psi))//" K="//trim(short(c%k))
   end function case_name

   function short(x) result(s)
      real(dp), intent(in) :: x
      character(len=16) :: s
      write (s, '(g0.4)') x
      s = adjustl(s)
   end function short

   !> Best (minimum) wall time of one solve over repeats that fit in `budget` seconds
   !> (at least 2 runs: the first also warms caches). stat = error status (0 ok).
   subroutine time_solve(params, opts, delta, budget, t_best, res, stat)
      type(contact_params), intent(in) :: params
      type(solver_options), intent(in) :: opts
      real(dp), intent(in) :: delta, budget
      real(dp), intent(out) :: t_best
      type(solve_result), intent(out) :: res
      integer, intent(out) :: stat
      type(egw_error), allocatable :: error
      real(dp) :: t0, t1, start
      integer :: r
      t_best = huge(1.0_dp)
      start = wall()
      stat = 0
      do r = 1, 50
         t0 = wall()
         call solve_contact(params, opts, delta, res, error)
         t1 = wall()
         t_best = min(t_best, t1 - t0)
         if (allocated(error)) then
            stat = error%stat
            return
         end if
         if (r >= 2 .and. t1 - start > budget) exit
      end do
   end subroutine time_solve

   !> Issue 3 item 5 / issue 5 item 1: tolerance and mesh sweeps, Newton vs Picard.
   !> Writes <out>/solver.csv; one thread per solve (n_threads = 1).
   subroutine run_solver(quick)
      logical, intent(in) :: quick
      type(solve_case), allocatable :: cases(:)
      real(dp), parameter :: tols(8) = [1e-2_dp, 1e-3_dp, 1e-4_dp, 1e-5_dp, 1e-6_dp, &
         & 1e-7_dp, 1e-8_dp, 1e-9_dp]
      integer, parameter :: meshes(6) = [16, 32, 64, 128, 256, 512]
      integer :: unit, ic, it, im, m, stat, unit_t
      real(dp) :: t, pref, err, budget
      type(solver_options) :: opts
      type(solve_result) :: res
      character(len=8) :: mname

      cases = [solve_case("EGW", -1.0_dp, 1.0_dp), solve_case("EGW", 1.0_dp, 1.0_dp), &
         & solve_case("EGW", 10.0_dp, 10.0_dp), solve_case("EGW", 100.0_dp, 1.0_dp), &
         & solve_case("EGW", 1000.0_dp, 100.0_dp), solve_case("GW", 1.0_dp, 1.0_dp), &
         & solve_case("GW", 100.0_dp, 10.0_dp), &
         & solve_case("EPGW", 10.0_dp, 1.0_dp, 2.0_dp, 0.6_dp)]
      if (quick) cases = cases([2, 3, 6])
      budget = merge(0.02_dp, 0.1_dp, quick)
      call omp_set_num_threads(1)
      call open_csv("solver.csv", unit)
      ! the compact target table: E-GW at rel_tol 1e-6, Newton, one core
      call open_csv("solver_target.csv", unit_t, &
         & "case,time_s,rel_err,est_rel_err,iterations,status")
      write (output_unit, '(/a)') "== solver: time per force point vs error (n_threads = 1);"// &
         & " error vs test/data/sphere_reference.csv"
      do ic = 1, size(cases)
         pref = reference_force(cases(ic)%model, cases(ic)%delta, cases(ic)%mu, &
            & cases(ic)%psi, merge(cases(ic)%k, 0.0_dp, cases(ic)%psi > 0))
         do m = method_newton, method_picard
            mname = merge("newton", "picard", m == method_newton)
            do it = 1, size(tols)
               opts = solver_options(rel_tol=tols(it), method=m, n_threads=1)
               call time_solve(case_params(cases(ic)), opts, cases(ic)%delta, budget, t, &
                  & res, stat)
               err = rel_error(res%force, pref, stat)
               call write_row(unit, "solver", trim(mname)//" auto-mesh", case_name(cases(ic)), &
                  & "rel_tol="//fmt_s(tols(it)), t, err, "sphere_reference.csv", stat, &
                  & "iter="//fmt_i(res%iterations)//" est="//fmt_e(res%est_rel_err))
               if (m == method_newton .and. it == 5 .and. cases(ic)%model == "EGW") &
                  & write (unit_t, '(a)') case_name(cases(ic))//","//fmt_e(t)//","// &
                  & fmt_e(err)//","//fmt_e(res%est_rel_err)//","//fmt_i(res%iterations) &
                  & //","//fmt_i(stat)
            end do
         end do
         do im = 1, size(meshes)
            if (quick .and. meshes(im) > 128) cycle
            do m = method_newton, method_picard
               mname = merge("newton", "picard", m == method_newton)
               opts = solver_options(n_radial=meshes(im), method=m, n_threads=1)
               call time_solve(case_params(cases(ic)), opts, cases(ic)%delta, budget, t, &
                  & res, stat)
               err = rel_error(res%force, pref, stat)
               call write_row(unit, "solver", trim(mname)//" fixed-mesh", &
                  & case_name(cases(ic)), "n_radial="//fmt_i(meshes(im)), t, err, &
                  & "sphere_reference.csv", stat, "iter="//fmt_i(res%iterations))
            end do
         end do
      end do
      call close_csv(unit)
      call close_csv(unit_t)
      call omp_set_num_threads(2)
   end subroutine run_solver

   real(dp) function rel_error(p, pref, stat)
      real(dp), intent(in) :: p, pref
      integer, intent(in) :: stat
      if (stat /= 0 .or. pref <= 0) then
         rel_error = -1.0_dp
      else
         rel_error = abs(p/pref - 1.0_dp)
      end if
   end function rel_error

   !> OpenMP speed-up of assemble_influence: 1 thread vs 2 threads, same run, on a
   !> graded quartic mesh like the solver's fine levels. Writes <out>/speedup.csv
   !> rows (appended by the table section too).
   subroutine run_assembly(unit)
      integer, intent(in) :: unit
      type(radial_mesh) :: mesh
      real(dp), allocatable :: infl(:, :)
      real(dp) :: t(2), t0
      integer :: nt, r
      call build_mesh(graded_edges(3.0_dp, 0.05_dp, 12.0_dp, 0.06_dp), 4, 6, mesh)
      allocate (infl(size(mesh%node), mesh%n_elem*mesh%n_gauss))
      ! 1 and 2 threads interleaved, best of 21 each: load from other processes on the
      ! shared machine then hits both alike
      t = huge(1.0_dp)
      do r = 1, 21
         do nt = 1, 2
            t0 = wall()
            call assemble_influence(mesh, mesh%node, infl, nt)
            t(nt) = min(t(nt), wall() - t0)
         end do
      end do
      write (output_unit, '(/a,i0,a,i0,a)') "== assemble_influence: ", size(mesh%node), &
         & " nodes x ", mesh%n_elem*mesh%n_gauss, " Gauss points (best of 21)"
      write (output_unit, '(a,f9.4,a,f9.4,a,f6.3)') "   1 thread ", t(1), " s, 2 threads ", &
         & t(2), " s, speed-up ", t(1)/t(2)
      write (unit, '(a)') "assemble_influence,"//fmt_i(size(mesh%node))//" nodes x "// &
         & fmt_i(mesh%n_elem*mesh%n_gauss)//" points,"//fmt_e(t(1))//","//fmt_e(t(2))// &
         & ","//fmt_e(t(1)/t(2))
   end subroutine run_assembly

   !> egw side of the peer comparison: for each (delta/sigma, mu) line of `path`, classic
   !> GW at the default options (rel_tol 1e-6, one thread) timed, and a reference solve at
   !> rel_tol 1e-9. Writes <out>/peer_egw.csv.
   subroutine run_peer_cases(path)
      character(len=*), intent(in) :: path
      integer :: in, unit, ios, stat, stat_ref
      real(dp) :: delta, mu, t, t_ref
      type(solve_case) :: c
      type(solve_result) :: res, ref
      call omp_set_num_threads(1)
      open (newunit=in, file=path, status="old", action="read", iostat=ios)
      if (ios /= 0) then
         write (output_unit, '(a)') "cannot open peer case file "//path
         return
      end if
      call open_csv("peer_egw.csv", unit, &
         & "delta_over_sigma,mu,time_s,P_scaled,est_rel_err,status,P_ref,ref_time_s,ref_status")
      do
         read (in, *, iostat=ios) delta, mu
         if (ios /= 0) exit
         c = solve_case("GW", delta, mu)
         call time_solve(case_params(c), solver_options(rel_tol=1.0e-6_dp, n_threads=1), &
            & delta, 0.1_dp, t, res, stat)
         call time_solve(case_params(c), solver_options(rel_tol=1.0e-9_dp, n_threads=1), &
            & delta, 0.0_dp, t_ref, ref, stat_ref)
         write (unit, '(a)') fmt_e(delta)//","//fmt_e(mu)//","//fmt_e(t)//","// &
            & fmt_e(res%force)//","//fmt_e(res%est_rel_err)//","//fmt_i(stat)//","// &
            & fmt_e(ref%force)//","//fmt_e(t_ref)//","//fmt_i(stat_ref)
      end do
      close (in)
      call close_csv(unit)
      write (output_unit, '(a)') "wrote "//out_dir//"peer_egw.csv"
      call omp_set_num_threads(2)
   end subroutine run_peer_cases

end module bench_solver
