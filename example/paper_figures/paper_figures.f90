!> Data of the figures of Zhao & Feng (2018) that egw can recompute, with the corrected
!> equations (doc/theory.md §6): Fig. 3 (P/P_H against sigma, GW and E-GW), Figs. 4 and 5
!> (pressure and deflection profiles and their differences from Hertz), Fig. 7 (EP-GW
!> pressure profiles) and Fig. 8 (EP-GW force against overlap). R = E = 1 as in the paper.
!>
!> Usage: fpm run --example paper-figures -- [output-folder [rel_tol]]
!> (default out/figures, 1e-6). Writes one CSV per figure; tools/plot_figures.py draws them.
program paper_figures
   use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
   use egw, only: dp, contact_params, egw_error, model_gw, model_egw, model_epgw, &
      & model_name, hertz_force, hertz_pressure, hertz_deflection, egw_version_string
   use egw_rough_sphere, only: solver_options, solve_result, solve_contact
   use egw_rough_profile, only: contact_profile
   implicit none

   real(dp), parameter :: overlap = 0.01_dp        !< the paper's delta for Figs. 3, 4, 5, 7
   real(dp), parameter :: fig7_sigma = 1.0e-3_dp, fig7_mu = 4.0_dp
   !> Fig. 7 (a) psi = 2, 4, 10 at K = 0.6 and (b) K = 0.4, 0.6, 0.8 at psi = 4.
   real(dp), parameter :: ep_psi(6) = [2.0_dp, 4.0_dp, 10.0_dp, 4.0_dp, 4.0_dp, 4.0_dp]
   real(dp), parameter :: ep_hardness(6) = [0.6_dp, 0.6_dp, 0.6_dp, 0.4_dp, 0.6_dp, 0.8_dp]
   character(len=1), parameter :: ep_panel(6) = ["a", "a", "a", "b", "b", "b"]

   character(len=:), allocatable :: out_dir
   type(solver_options) :: options
   integer :: n_failed, n_solved

   call read_arguments(out_dir, options)
   call execute_command_line('mkdir -p "'//out_dir//'"')
   n_failed = 0
   n_solved = 0

   call figure3()
   call figures4and5()
   call figure7()
   call figure8()

   write (output_unit, '(a,i0,a,i0,a)') "paper-figures: ", n_solved, " solves, ", n_failed, &
      & " failed"
   if (n_failed > 0) error stop 1

contains

   !> Fig. 3: P* = P/P_H at delta = 0.01 against sigma in (0, 0.01] for mu = 1, 4, 10,
   !> classic GW and E-GW. Sigma is sampled both logarithmically (to show sigma -> 0,
   !> where GW tends to Hertz from below, eq. 27) and linearly (the paper's axis).
   subroutine figure3()
      real(dp), parameter :: mus(3) = [1.0_dp, 4.0_dp, 10.0_dp]
      integer, parameter :: models(2) = [model_gw, model_egw]
      character(len=*), parameter :: fig3_columns = "model,mu,sigma,delta_over_sigma," &
         & //"force,force_hertz,force_ratio,est_rel_err,iterations"
      real(dp) :: sigmas(45), p_hertz
      integer :: unit, i

      do i = 1, 25
         sigmas(i) = 10.0_dp**(-6.0_dp + 4.0_dp*real(i - 1, dp)/24.0_dp)
      end do
      do i = 1, 20
         sigmas(25 + i) = 5.0e-4_dp*real(i, dp)
      end do
      call sort(sigmas)
      p_hertz = hertz_force(overlap, 1.0_dp, 1.0_dp)

      call open_csv(unit, "fig3_force_ratio.csv", &
         & "Fig. 3: P* = P/P_H against sigma; R = E = 1, delta = 0.01", fig3_columns)
      call fig3_rows(unit, models, mus, 1.0_dp, sigmas, p_hertz)
      close (unit)
      ! The printed eq. (5) has 3/4 where eqs. (9) and (42) have 4/3 (doc/theory.md §6,
      ! misprint 1). p_G is proportional to C, hence to mu, so that misprint is exactly
      ! the corrected model at mu' = (9/16) mu; the rows keep the nominal mu.
      call open_csv(unit, "fig3_misprint1.csv", "Fig. 3 with the asperity force factor " &
         & //"3/4 of the printed eq. 5 (solved as mu' = 9 mu/16; mu column is nominal)", &
         & fig3_columns)
      call fig3_rows(unit, models, [4.0_dp], 9.0_dp/16.0_dp, sigmas, p_hertz)
      close (unit)
   end subroutine figure3

   !> One Fig. 3 row per model, mu and sigma; the solve uses mu_factor * mu.
   subroutine fig3_rows(unit, models, mus, mu_factor, sigmas, p_hertz)
      integer, intent(in) :: unit, models(:)
      real(dp), intent(in) :: mus(:), mu_factor, sigmas(:), p_hertz
      type(contact_params) :: params
      type(solve_result) :: res
      logical :: ok
      integer :: i, j, m
      do m = 1, size(models)
         do j = 1, size(mus)
            do i = 1, size(sigmas)
               ! the two samplings share 1e-3 and 1e-2
               if (i > 1) then
                  if (sigmas(i) <= sigmas(i - 1)*(1.0_dp + 1.0e-9_dp)) cycle
               end if
               params = scene(models(m), sigmas(i), mu_factor*mus(j))
               call solve(params, overlap, res, ok)
               if (.not. ok) cycle
               write (unit, '(a)') model_name(models(m))//","//num(mus(j))//"," &
                  & //num(sigmas(i))//","//num(overlap/sigmas(i))//","//num(res%force)//"," &
                  & //num(p_hertz)//","//num(res%force/p_hertz)//","//num(res%est_rel_err) &
                  & //","//int_str(res%iterations)
            end do
         end do
      end do
   end subroutine fig3_rows

   !> Figs. 4 and 5: p(r) and w(r) at delta = 0.01, mu = 4, sigma = 1e-5, 1e-4, 1e-3 for
   !> GW and E-GW, with the Hertz solution and the differences from it.
   subroutine figures4and5()
      real(dp), parameter :: sigmas(3) = [1.0e-5_dp, 1.0e-4_dp, 1.0e-3_dp]
      integer, parameter :: models(2) = [model_gw, model_egw]
      real(dp) :: r(801), pressure(801), deflection(801), p_h(801), w_h(801)
      type(contact_params) :: params
      logical :: ok
      integer :: unit_p, unit_w, i, j, m

      r = radii(size(r), 0.2_dp)
      p_h = hertz_pressure(r, overlap, 1.0_dp, 1.0_dp)
      w_h = hertz_deflection(r, overlap, 1.0_dp)
      call open_csv(unit_p, "fig4_pressure.csv", "Fig. 4: pressure p(r) and p - p_H; " &
         & //"R = E = 1, delta = 0.01, mu = 4", &
         & "model,sigma,r,pressure,pressure_hertz,pressure_difference")
      call open_csv(unit_w, "fig5_deflection.csv", "Fig. 5: deflection w(r) and w - w_H; " &
         & //"R = E = 1, delta = 0.01, mu = 4 (w_H by eq. 15 corrected)", &
         & "model,sigma,r,deflection,deflection_hertz,deflection_difference")
      do i = 1, size(r)
         write (unit_p, '(a)') "Hertz,0,"//num(r(i))//","//num(p_h(i))//","//num(p_h(i))//",0"
         write (unit_w, '(a)') "Hertz,0,"//num(r(i))//","//num(w_h(i))//","//num(w_h(i))//",0"
      end do
      do m = 1, size(models)
         do j = 1, size(sigmas)
            params = scene(models(m), sigmas(j), 4.0_dp)
            call profile(params, overlap, r, pressure, deflection, ok)
            if (.not. ok) cycle
            do i = 1, size(r)
               write (unit_p, '(a)') model_name(models(m))//","//num(sigmas(j))//"," &
                  & //num(r(i))//","//num(pressure(i))//","//num(p_h(i))//"," &
                  & //num(pressure(i) - p_h(i))
               write (unit_w, '(a)') model_name(models(m))//","//num(sigmas(j))//"," &
                  & //num(r(i))//","//num(deflection(i))//","//num(w_h(i))//"," &
                  & //num(deflection(i) - w_h(i))
            end do
         end do
      end do
      close (unit_p)
      close (unit_w)
   end subroutine figures4and5

   !> Fig. 7: pressure at delta = 0.01, sigma = 1e-3, mu = 4 for EP-GW (panel a:
   !> psi = 2, 4, 10 at K = 0.6; panel b: K = 0.4, 0.6, 0.8 at psi = 4), E-GW and Hertz.
   subroutine figure7()
      real(dp) :: r(641), pressure(641), deflection(641), p_h(641)
      type(contact_params) :: params
      logical :: ok
      integer :: unit, i, c

      r = radii(size(r), 0.16_dp)
      p_h = hertz_pressure(r, overlap, 1.0_dp, 1.0_dp)
      call open_csv(unit, "fig7_pressure.csv", "Fig. 7: EP-GW pressure p(r); R = E = 1, " &
         & //"delta = 0.01, sigma = 1e-3, mu = 4, plastic_ratio = 54 (eq. 45 per doc/theory.md " &
         & //"misprint 4)", "panel,model,psi,hardness_coeff,r,pressure")
      do i = 1, size(r)
         write (unit, '(a)') "ab,Hertz,0,0,"//num(r(i))//","//num(p_h(i))
      end do
      params = scene(model_egw, fig7_sigma, fig7_mu)
      call profile(params, overlap, r, pressure, deflection, ok)
      if (ok) then
         do i = 1, size(r)
            write (unit, '(a)') "ab,E-GW,0,0,"//num(r(i))//","//num(pressure(i))
         end do
      end if
      do c = 1, size(ep_psi)
         params = scene(model_epgw, fig7_sigma, fig7_mu)
         params%psi = ep_psi(c)
         params%hardness_coeff = ep_hardness(c)
         call profile(params, overlap, r, pressure, deflection, ok)
         if (.not. ok) cycle
         do i = 1, size(r)
            write (unit, '(a)') ep_panel(c)//",EP-GW,"//num(ep_psi(c))//"," &
               & //num(ep_hardness(c))//","//num(r(i))//","//num(pressure(i))
         end do
      end do
      close (unit)
   end subroutine figure7

   !> Fig. 8: force against overlap for the cases of Fig. 7, E-GW and Hertz, from
   !> delta = -4 sigma (separated; only the asperities carry load) to 0.01.
   subroutine figure8()
      integer, parameter :: n = 57
      real(dp) :: deltas(n)
      type(contact_params) :: params
      type(solve_result) :: res
      logical :: ok
      integer :: unit, i, c

      do i = 1, n
         deltas(i) = -4.0_dp*fig7_sigma + (overlap + 4.0_dp*fig7_sigma)*real(i - 1, dp) &
            & /real(n - 1, dp)
      end do
      call open_csv(unit, "fig8_force.csv", "Fig. 8: force against overlap; R = E = 1, " &
         & //"sigma = 1e-3, mu = 4, plastic_ratio = 54", &
         & "panel,model,psi,hardness_coeff,delta,force,est_rel_err")
      do i = 1, n
         write (unit, '(a)') "ab,Hertz,0,0,"//num(deltas(i))//"," &
            & //num(hertz_force(deltas(i), 1.0_dp, 1.0_dp))//",0"
      end do
      params = scene(model_egw, fig7_sigma, fig7_mu)
      do i = 1, n
         call solve(params, deltas(i), res, ok)
         if (ok) write (unit, '(a)') "ab,E-GW,0,0,"//num(deltas(i))//","//num(res%force) &
            & //","//num(res%est_rel_err)
      end do
      do c = 1, size(ep_psi)
         params = scene(model_epgw, fig7_sigma, fig7_mu)
         params%psi = ep_psi(c)
         params%hardness_coeff = ep_hardness(c)
         do i = 1, n
            call solve(params, deltas(i), res, ok)
            if (ok) write (unit, '(a)') ep_panel(c)//",EP-GW,"//num(ep_psi(c))//"," &
               & //num(ep_hardness(c))//","//num(deltas(i))//","//num(res%force)//"," &
               & //num(res%est_rel_err)
         end do
      end do
      close (unit)
   end subroutine figure8

   !> The paper's scene: R = E = 1, the given model, sigma and mu, elastic asperities.
   function scene(model, sigma, mu) result(params)
      integer, intent(in) :: model
      real(dp), intent(in) :: sigma, mu
      type(contact_params) :: params
      params%model = model
      params%radius = 1.0_dp
      params%modulus = 1.0_dp
      params%sigma = sigma
      params%mu = mu
   end function scene

   subroutine solve(params, delta, res, ok)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: delta
      type(solve_result), intent(out) :: res
      logical, intent(out) :: ok
      type(egw_error), allocatable :: error
      call solve_contact(params, options, delta, res, error)
      call account(error, params, delta, ok)
   end subroutine solve

   subroutine profile(params, delta, r, pressure, deflection, ok)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: delta, r(:)
      real(dp), intent(out) :: pressure(:), deflection(:)
      logical, intent(out) :: ok
      type(egw_error), allocatable :: error
      call contact_profile(params, options, delta, r, pressure, deflection, error)
      call account(error, params, delta, ok)
   end subroutine profile

   !> Count the solve; report a failure (and go on: one bad point must not cost a figure).
   subroutine account(error, params, delta, ok)
      type(egw_error), allocatable, intent(in) :: error
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: delta
      logical, intent(out) :: ok
      n_solved = n_solved + 1
      ok = .not. allocated(error)
      if (ok) return
      n_failed = n_failed + 1
      write (error_unit, '(a)') "paper-figures: "//model_name(params%model)//" sigma = " &
         & //num(params%sigma)//" mu = "//num(params%mu)//" psi = "//num(params%psi) &
         & //" K = "//num(params%hardness_coeff)//" delta = "//num(delta)//": " &
         & //error%message
   end subroutine account

   !> n radii on [0, r_max], evenly spaced.
   pure function radii(n, r_max) result(r)
      integer, intent(in) :: n
      real(dp), intent(in) :: r_max
      real(dp) :: r(n)
      integer :: i
      r = [(r_max*real(i, dp)/real(n - 1, dp), i = 0, n - 1)]
   end function radii

   subroutine open_csv(unit, name, title, columns)
      integer, intent(out) :: unit
      character(len=*), intent(in) :: name, title, columns
      open (newunit=unit, file=out_dir//"/"//name, status="replace", action="write")
      write (unit, '(a)') "# "//title
      write (unit, '(a)') "# egw "//egw_version_string//", example paper-figures, rel_tol = " &
         & //num(options%rel_tol)
      write (unit, '(a)') columns
      write (output_unit, '(a)') "writing "//out_dir//"/"//name
   end subroutine open_csv

   subroutine read_arguments(out_dir, options)
      character(len=:), allocatable, intent(out) :: out_dir
      type(solver_options), intent(inout) :: options
      character(len=256) :: buf
      integer :: stat
      out_dir = "out/figures"
      if (command_argument_count() >= 1) then
         call get_command_argument(1, buf)
         out_dir = trim(buf)
      end if
      if (command_argument_count() >= 2) then
         call get_command_argument(2, buf)
         read (buf, *, iostat=stat) options%rel_tol
         if (stat /= 0) then
            write (error_unit, '(a)') "paper-figures: cannot read rel_tol from '"//trim(buf)//"'"
            error stop 2
         end if
      end if
   end subroutine read_arguments

   !> Insertion sort (a handful of values).
   pure subroutine sort(x)
      real(dp), intent(inout) :: x(:)
      real(dp) :: v
      integer :: i, j
      do i = 2, size(x)
         v = x(i)
         j = i - 1
         do while (j >= 1)
            if (x(j) <= v) exit
            x(j + 1) = x(j)
            j = j - 1
         end do
         x(j + 1) = v
      end do
   end subroutine sort

   !> A real as a short CSV field that reads back to the same double.
   pure function num(x) result(str)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: str
      character(len=32) :: buf
      write (buf, '(es24.16e3)') x
      str = trim(adjustl(buf))
   end function num

   pure function int_str(i) result(str)
      integer, intent(in) :: i
      character(len=:), allocatable :: str
      character(len=16) :: buf
      write (buf, '(i0)') i
      str = trim(buf)
   end function int_str

end program paper_figures
