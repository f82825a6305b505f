!> egw-bench unloading section (issue 10): time of an unloading solve (solve_unload from a
!> history loaded once, as a sweep or a hysteresis table uses it) against the loading solve
!> at the same overlap (goal <= 1.5), and of solve_contact_unload (egw_solve_unload):
!> one-shot (loading to delta_max at 1e-4 rel_tol included) and in a sweep after one
!> delta_max (its history kept, loaded once); with the error of the unloading solve
!> against the independent references of test/data/sphere_unload_reference.csv. Rows go to
!> out/bench/unloading.csv (doc/bench/ with --update-docs).
module bench_unloading
   use, intrinsic :: iso_fortran_env, only: output_unit
   use egw, only: dp, contact_params, solver_options, solve_result, solve_contact, egw_error, &
      & model_epgw, loading_history, load_history, solve_unload, solve_contact_unload
   use bench_common, only: wall, open_csv, write_row, close_csv, fmt_s, fmt_e
   implicit none
   private

   public :: run_unloading, run_unloading_sweep

contains

   !> Every reference row: best-of-repeats wall time of the four solves, their ratios.
   subroutine run_unloading(quick)
      logical, intent(in) :: quick
      character(len=*), parameter :: path = "test/data/sphere_unload_reference.csv"
      character(len=512) :: line
      character(len=8) :: model
      real(dp) :: delta, delta_max, mu, psi, hardness, force, force_err, stiffness, &
         & stiffness_err, force_max, t_load, t_unload, t_once, t_kept, err
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
         t_kept = best(4)
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
         call write_row(unit, "unloading", "solve_contact_unload kept", case_name, &
            & "rel_tol=1e-6", t_kept, err, "sphere_unload_reference", stat, "ratio_to_load=" &
            & //fmt_e(t_kept/t_load))
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
            case (3)
               ! one-shot: another turning point first (untimed), so that the history
               ! this thread keeps is not the one needed
               call solve_contact_unload(p, opts, delta - 0.5_dp, delta_max + 0.5_dp, res, &
                  & error)
               t0 = wall()
               call solve_contact_unload(p, opts, delta, delta_max, res, error)
            case default
               ! a sweep after one delta_max: the history kept from the call before
               call solve_contact_unload(p, opts, delta, delta_max, res, error)
            end select
            t = min(t, wall() - t0)
         end do
      end function best
   end subroutine run_unloading

   !> The accuracy sweep of solve_contact_unload (the C API's egw_solve_unload): EP-GW mu 4,
   !> K 0.6, rho_p 54, psi 1, 2, 5, 10, delta_max 0.5, 1, 2, 5, 10 sigma, delta at 0.1..0.9
   !> of the way from delta_max down to -2 sigma, at rel_tol 1e-6 and 1e-7, against
   !> solve_unload at rel_tol 1e-9 (1e-8 where 1e-9 does not converge) from a history loaded
   !> at 1e-10 (a consistency check of the same code, not independent: the independent
   !> references are the test's 19 points). Prints the solves above rel_tol and, per
   !> rel_tol, the count, the worst error and the worst error/estimate where the error
   !> exceeds rel_tol/10 (how far the estimate can be too low).
   subroutine run_unloading_sweep()
      real(dp), parameter :: psis(4) = [1.0_dp, 2.0_dp, 5.0_dp, 10.0_dp], &
         & tops(5) = [0.5_dp, 1.0_dp, 2.0_dp, 5.0_dp, 10.0_dp], &
         & fractions(5) = [0.1_dp, 0.3_dp, 0.5_dp, 0.7_dp, 0.9_dp]
      type(contact_params) :: p
      type(solver_options) :: opts
      type(loading_history) :: reference_history
      type(solve_result) :: res, ref, loaded
      type(egw_error), allocatable :: error
      real(dp) :: tol, delta, e, worst, worst_ratio
      integer :: k, a, b, c, n, n_over, n_failed
      write (output_unit, '(/a)') "== unloading accuracy sweep (solve_contact_unload against "// &
         & "rel_tol 1e-9 solves on 1e-10 histories; EP-GW mu 4, K 0.6)"
      do k = 6, 7
         tol = 10.0_dp**(-k)
         n = 0
         n_over = 0
         n_failed = 0
         worst = 0.0_dp
         worst_ratio = 0.0_dp
         do a = 1, size(psis)
            p = contact_params(model=model_epgw, radius=1.0_dp, modulus=1.0_dp, &
               & sigma=1.0_dp, mu=4.0_dp, psi=psis(a), hardness_coeff=0.6_dp, &
               & plastic_ratio=54.0_dp)
            do b = 1, size(tops)
               opts%rel_tol = 1.0e-10_dp
               call load_history(p, opts, tops(b), reference_history, loaded, error)
               if (allocated(error)) then
                  deallocate (error)
                  cycle
               end if
               do c = 1, size(fractions)
                  delta = tops(b) - fractions(c)*(tops(b) + 2.0_dp)
                  reference_history%options%rel_tol = 1.0e-9_dp
                  call solve_unload(reference_history, delta, ref, error)
                  if (allocated(error)) then
                     deallocate (error)
                     reference_history%options%rel_tol = 1.0e-8_dp
                     call solve_unload(reference_history, delta, ref, error)
                     if (allocated(error)) then
                        deallocate (error)
                        cycle
                     end if
                  end if
                  if (.not. ref%force > 1.0e-12_dp) cycle   ! rounding noise relative
                  opts%rel_tol = tol
                  call solve_contact_unload(p, opts, delta, tops(b), res, error)
                  n = n + 1
                  if (allocated(error)) then
                     n_failed = n_failed + 1
                     deallocate (error)
                     cycle
                  end if
                  e = abs(res%force/ref%force - 1.0_dp)
                  worst = max(worst, e)
                  if (e > 0.1_dp*tol) worst_ratio = max(worst_ratio, e/max(res%est_rel_err, &
                     & tiny(1.0_dp)))
                  if (e > tol) then
                     n_over = n_over + 1
                     write (output_unit, '(a,3f7.2,2es10.2)') "  above rel_tol: psi, "// &
                        & "delta_max, delta, error, estimate", psis(a), tops(b), delta, e, &
                        & res%est_rel_err
                  end if
               end do
            end do
         end do
         write (output_unit, '(a,es8.1,a,i0,a,i0,a,i0,a,es9.2,a,f8.1)') "  rel_tol ", tol, &
            & ": ", n, " solves, ", n_over, " above rel_tol, ", n_failed, &
            & " not converged; worst error ", worst, ", worst error/estimate ", worst_ratio
      end do
   end subroutine run_unloading_sweep

end module bench_unloading
