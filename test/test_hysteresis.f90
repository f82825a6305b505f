!> Tests of egw_hysteresis (issue 10 item 4). The interpolation is tested on an analytic
!> hysteresis family with known values (exact references), the EP-GW build against
!> independent unloading solves (solve_unload) between nodes in delta and delta_max.
module test_hysteresis
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   use, intrinsic :: iso_c_binding, only: c_int
   use testdrive, only: new_unittest, unittest_type, error_type, check, to_string
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_invalid_argument, format_real
   use egw_params, only: contact_params, model_hertz, model_epgw
   use egw_rough_sphere, only: solver_options, solve_result, loading_history, &
      & load_history, solve_unload
   use egw_table, only: force_table, build_table, table_eval
   use egw_hysteresis
   implicit none
   private
   public :: collect_hysteresis

   interface
      integer(c_int) function c_hysteresis() bind(C, name="egw_capi_test_hysteresis")
         import :: c_int
      end function c_hysteresis
   end interface

contains

   subroutine collect_hysteresis(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("analytic family between nodes", test_analytic), &
         & new_unittest("history semantics", test_history), &
         & new_unittest("EP-GW table vs unloading solves", test_epgw), &
         & new_unittest("invalid requests", test_invalid), &
         & new_unittest("C API (test/hysteresis_checks.c)", test_c) &
         & ]
   end subroutine collect_hysteresis

   !> Exponent of the analytic family r(s; peak) = s**a(peak): varies with peak as the
   !> EP-GW curves do (steeper after deeper loading), smooth in both directions.
   pure real(dp) function expo(peak)
      real(dp), intent(in) :: peak
      expo = 1.5_dp + peak + 0.3_dp*sin(5*peak)
   end function expo

   subroutine analytic(peak, s, r, drds, error)
      real(dp), intent(in) :: peak, s(:)
      real(dp), intent(out) :: r(:), drds(:)
      type(egw_error), allocatable, intent(out) :: error
      real(dp) :: a
      a = expo(peak)
      r = s**a
      drds = a*s**(a - 1)
   end subroutine analytic

   !> Hertz loading (exact table) with the analytic unloading family, rel_tol 1e-5: at
   !> points midway between peaks and between s nodes (where the interpolation error is
   !> largest) |P - r_exact P_load(peak)| <= rel_tol P_load(peak) (the table's criterion).
   subroutine test_analytic(error)
      type(error_type), allocatable, intent(out) :: error
      type(force_table) :: loading
      type(hysteresis_table) :: h
      type(egw_error), allocatable :: err
      real(dp), parameter :: rel_tol = 1.0e-5_dp
      real(dp) :: peak, s, state, f, k, p_top, k_top, worst
      integer :: i, j
      call build_table(contact_params(model=model_hertz, radius=1.0_dp, modulus=1.0_dp, &
         & sigma=0.0_dp), solver_options(), 0.0_dp, 1.0_dp, rel_tol, loading, err)
      call check(error, .not. allocated(err), "loading table")
      if (allocated(error)) return
      call build_hysteresis_with(loading, analytic, h, err)
      call check(error, .not. allocated(err), "analytic build")
      if (allocated(error)) return
      worst = 0.0_dp
      do j = 1, size(h%peak) - 1
         peak = 0.5_dp*(h%peak(j) + h%peak(j + 1))
         call table_eval(h%loading, peak, p_top, k_top)
         do i = 1, size(h%s) - 1
            s = 0.5_dp*(h%s(i) + h%s(i + 1))
            state = peak
            call hysteresis_eval(h, h%cutoff + s*(peak - h%cutoff), state, f, k)
            if (f > 0.0_dp) worst = max(worst, abs(f/p_top - s**expo(peak)))
         end do
      end do
      call check(error, worst <= rel_tol, "max error "//format_real(worst)//" > rel_tol; "// &
         & to_string(size(h%peak))//" peaks, "//to_string(size(h%s))//" s nodes")
   end subroutine test_analytic

   !> A small EP-GW table (sigma = 1, rel_tol 1e-2 to keep the suite short).
   subroutine epgw_table(h, params, err)
      type(hysteresis_table), intent(out) :: h
      type(contact_params), intent(out) :: params
      type(egw_error), allocatable, intent(out) :: err
      params = contact_params(model=model_epgw, radius=100.0_dp, modulus=1.0_dp, &
         & sigma=1.0_dp, mu=4.0_dp, psi=1.0_dp)
      call build_hysteresis(params, solver_options(), -2.0_dp, 4.0_dp, 1.0e-2_dp, h, err)
   end subroutine epgw_table

   !> New contact (-huge) loads; the state follows the largest overlap; below it the
   !> force is the unloading curve (below loading), the same on reloading, continuous at
   !> delta = state (to the Hermite slope times the step), and loading resumes above.
   subroutine test_history(error)
      type(error_type), allocatable, intent(out) :: error
      type(hysteresis_table) :: h
      type(contact_params) :: params
      type(egw_error), allocatable :: err
      real(dp) :: state, f, k, fl, kl, fu, ku, fr, kr
      call epgw_table(h, params, err)
      call check(error, .not. allocated(err), "build")
      if (allocated(error)) return
      state = -huge(1.0_dp)
      call hysteresis_eval(h, 3.0_dp, state, f, k)
      call table_eval(h%loading, 3.0_dp, fl, kl)
      call check(error, f == fl .and. k == kl .and. state == 3.0_dp, "new contact loads")
      if (allocated(error)) return
      call hysteresis_eval(h, 2.0_dp, state, fu, ku)
      call table_eval(h%loading, 2.0_dp, fl, kl)
      call check(error, state == 3.0_dp .and. fu < fl .and. fu > 0.0_dp .and. ku > kl, &
         & "unloading below loading, stiffer")
      if (allocated(error)) return
      call hysteresis_eval(h, 1.0_dp, state, f, k)
      call hysteresis_eval(h, 2.0_dp, state, fr, kr)
      call check(error, fr == fu .and. kr == ku .and. state == 3.0_dp, &
         & "reloading follows the unloading curve")
      if (allocated(error)) return
      call hysteresis_eval(h, 3.0_dp - 1.0e-9_dp, state, fu, ku)
      call table_eval(h%loading, 3.0_dp, fl, kl)
      call check(error, abs(fu - fl) <= 2.0e-9_dp*ku, "continuous at delta = state")
      if (allocated(error)) return
      call hysteresis_eval(h, 3.5_dp, state, f, k)
      call table_eval(h%loading, 3.5_dp, fl, kl)
      call check(error, f == fl .and. state == 3.5_dp, "loading resumes above the state")
      if (allocated(error)) return
      call hysteresis_eval(h, -1.9_dp, state, f, k)
      call check(error, f == 0.0_dp .and. k == 0.0_dp, "zero far below the history")
   end subroutine test_history

   !> Table against solve_unload at (delta, delta_max) both between nodes: error <=
   !> rel_tol P_load(delta_max) (the build checks each direction to rel_tol/2); where the
   !> table gives 0 (cut-off rule) the solve's force is below ~rel_tol P_ref.
   subroutine test_epgw(error)
      type(error_type), allocatable, intent(out) :: error
      type(hysteresis_table) :: h
      type(contact_params) :: params
      type(egw_error), allocatable :: err
      type(loading_history) :: history
      type(solve_result) :: top, res
      real(dp) :: peak, s, state, f, k, worst
      integer :: i, j
      call epgw_table(h, params, err)
      call check(error, .not. allocated(err), "build")
      if (allocated(error)) return
      worst = 0.0_dp
      do j = 2, size(h%peak) - 1, 3
         peak = 0.5_dp*(h%peak(j) + h%peak(j + 1))
         call load_history(params, solver_options(rel_tol=1.0e-4_dp), peak, history, top, err)
         call check(error, .not. allocated(err), "history")
         if (allocated(error)) return
         do i = 2, size(h%s) - 1, 2
            s = 0.5_dp*(h%s(i) + h%s(i + 1))
            call solve_unload(history, h%cutoff + s*(peak - h%cutoff), res, err)
            call check(error, .not. allocated(err), "unloading solve")
            if (allocated(error)) return
            state = peak
            call hysteresis_eval(h, h%cutoff + s*(peak - h%cutoff), state, f, k)
            if (f == 0.0_dp) then
               ! the cut-off rule: zero where the force has fallen to rel_tol P_ref
               call check(error, res%force <= 2.0e-2_dp*h%loading%reference_force, &
                  & "zero force where the solve gives "//format_real(res%force))
               if (allocated(error)) return
            else
               worst = max(worst, abs(f - res%force)/top%force)
            end if
         end do
      end do
      call check(error, worst <= 1.0e-2_dp, "max error "//format_real(worst)// &
         & " of P_load(delta_max) > rel_tol 1e-2")
   end subroutine test_epgw

   !> delta_max < delta_min and NaN rel_tol: egw_invalid_argument, table untouched.
   subroutine test_invalid(error)
      type(error_type), allocatable, intent(out) :: error
      type(hysteresis_table) :: h
      type(egw_error), allocatable :: err
      type(contact_params) :: params
      params = contact_params(model=model_epgw, radius=100.0_dp, modulus=1.0_dp, &
         & sigma=1.0_dp, mu=4.0_dp, psi=1.0_dp)
      call build_hysteresis(params, solver_options(), 4.0_dp, -2.0_dp, 1.0e-2_dp, h, err)
      call check(error, allocated(err), "delta_max < delta_min refused")
      if (allocated(error)) return
      call check(error, err%stat == egw_invalid_argument, "stat "//to_string(err%stat))
      if (allocated(error)) return
      call build_hysteresis(params, solver_options(), -2.0_dp, 4.0_dp, &
         & ieee_value(1.0_dp, ieee_quiet_nan), h, err)
      call check(error, allocated(err), "NaN rel_tol refused")
      if (allocated(error)) return
      call check(error, .not. allocated(h%peak), "table untouched")
   end subroutine test_invalid

   subroutine test_c(error)
      type(error_type), allocatable, intent(out) :: error
      integer(c_int) :: nfail
      nfail = c_hysteresis()
      call check(error, int(nfail) == 0, to_string(int(nfail))//" C check(s) failed")
   end subroutine test_c

end module test_hysteresis
