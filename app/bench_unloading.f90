!> egw-bench unloading section (issue 10): time of an unloading solve (solve_unload from a
!> history loaded once, as a sweep or a hysteresis table uses it) against the loading solve
!> at the same overlap (goal <= 1.5), and of the one-shot solve_contact_unload (loading to
!> delta_max included); with the error of the unloading solve against the independent
!> references of test/data/sphere_unload_reference.csv. Rows go to out/bench/unloading.csv (doc/bench/ with --update-docs).
module bench_unloading
   use, intrinsic :: iso_fortran_env, only: output_unit
   use egw, only: dp, contact_params, solver_options, solve_result, solve_contact, egw_error, &
      & model_epgw, loading_history, load_history, solve_unload, solve_contact_unload
   use bench_common, only: wall, open_csv, write_row, close_csv, fmt_s, fmt_e
   implicit none
   private

   public :: run_unloading

contains

   !> Every reference row: best-of-repeats wall time of the three solves, their ratios.
   subroutine run_unloading(quick)
      logical, intent(in) :: quick
      character(len=*), parameter :: path = "test/data/sphere_unload_reference.csv"
      character(len=512) :: line
      character(len=8) :: model
      real(dp) :: delta, delta_max, mu, psi, hardness, force, force_err, stiffness, &
         & stiffness_err, force_max, t_load, t_unload, t_once, err
      type(contact_params) :: p
      type(solver_options) :: opts
      type(loading_history) :: hist
      type(solve_result) :: res, loaded
      type(egw_error), allocatable :: error
      integer :: unit_in, unit, ios, stat, repeats
      character(len=:), allocatable :: case_name
      repeats = 5
      if (quick) repeats = 2
      open (newunit=unit_in, file=path, status="old", action="read", iostat=ios)
      if (ios /= 0) then
         write (output_unit, '(a)') "egw-bench: cannot open "//path//" (run from the root)"
         return
      end if
      call open_csv("unloading.csv", unit)
      write (output_unit, '(a)') "unloading: time of one solve (best of "// &
         & trim(fmt_s(real(repeats, dp)))//"), unload/load ratio (goal <= 1.5)"
      do
         read (unit_in, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:1) == "#" .or. line(1:6) == "model,") cycle
         read (line, *) model, delta, delta_max, mu, psi, hardness, force, force_err, &
            & stiffness, stiffness_err, force_max
         p = contact_params(model=model_epgw, sigma=1.0_dp, mu=mu, psi=psi, &
            & hardness_coeff=hardness)
         call load_history(p, opts, delta_max, hist, loaded, error)
         if (allocated(error)) cycle
         t_load = best(1)
         t_unload = best(2)
         t_once = best(3)
         stat = 0
         if (allocated(error)) stat = error%stat
         err = abs(res%force/force - 1.0_dp)
         case_name = "EPGW d="//trim(fmt_s(delta))//" dmax="//trim(fmt_s(delta_max)) &
            & //" mu="//trim(fmt_s(mu))//" psi="//trim(fmt_s(psi))//" K="//trim(fmt_s(hardness))
         call write_row(unit, "unloading", "solve_contact", case_name, "rel_tol=1e-6", &
            & t_load, -1.0_dp, "", 0, "")
         call write_row(unit, "unloading", "solve_unload", case_name, "rel_tol=1e-6", &
            & t_unload, err, "sphere_unload_reference", stat, "ratio_to_load=" &
            & //fmt_e(t_unload/t_load))
         call write_row(unit, "unloading", "solve_contact_unload", case_name, "rel_tol=1e-6", &
            & t_once, err, "sphere_unload_reference", stat, "ratio_to_load=" &
            & //fmt_e(t_once/t_load))
      end do
      close (unit_in)
      call close_csv(unit)
   contains
      real(dp) function best(which) result(t)
         integer, intent(in) :: which
         real(dp) :: t0
         integer :: r
         t = huge(1.0_dp)
         do r = 1, repeats
            t0 = wall()
            select case (which)
            case (1)
               call solve_contact(p, opts, delta, res, error)
            case (2)
               call solve_unload(hist, delta, res, error)
            case default
               call solve_contact_unload(p, opts, delta, delta_max, res, error)
            end select
            t = min(t, wall() - t0)
         end do
      end function best
   end subroutine run_unloading

end module bench_unloading
