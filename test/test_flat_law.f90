!> Rough-flat laws as objects (egw_flat_law) and the sphere solve that takes one
!> (solve_contact_law); the C half is test/flat_law_checks.c.
module test_flat_law
   use, intrinsic :: iso_c_binding, only: c_int
   use testdrive, only: new_unittest, unittest_type, error_type, check, to_string
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_invalid_argument, format_real
   use egw_params, only: contact_params, model_gw
   use egw_asperity, only: flat_pressure
   implicit none
   private
   public :: collect_flat_law

   interface
      integer(c_int) function c_flat_law() bind(C, name="egw_capi_test_flat_law")
         import :: c_int
      end function
   end interface

contains

   subroutine collect_flat_law(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("table law: nodes, slopes, C1, ends", test_table_law), &
         & new_unittest("table law: bad tables", test_bad_tables), &
         & new_unittest("tabulated GW law = classic GW solve", test_tabulated_gw), &
         & new_unittest("C egw_flat_law_*, egw_solve_flat_law", test_c)]
   end subroutine collect_flat_law

   !> An exponential is reproduced exactly (ln p linear: every Hermite piece and both
   !> continuations are the same line), to rounding (1e-14); a curved table is exact at
   !> its nodes and continuous with a continuous slope across them (C1: one-sided
   !> differences at 1e-7 of the spacing agree to 1e-5 of the slope).
   subroutine test_table_law(error)
      ! (egw_flat_law used here, not by the module: gfortran 12 writes the abstract type
      ! into this module's .mod in a form it then cannot read)
      use egw_flat_law, only: table_flat_law, new_table_law
      type(error_type), allocatable, intent(out) :: error
      type(table_flat_law) :: law
      type(egw_error), allocatable :: e
      real(dp) :: u(5), p(5), pu(7), du(7), pl(1), dl(1), pr(1), dr(1), h
      integer :: i
      u = [0.0_dp, 0.5_dp, 1.0_dp, 2.0_dp, 4.0_dp]
      p = 3.0_dp*exp(-u/0.7_dp)
      call new_table_law(u, p, law, e)
      call check(error, .not. allocated(e))
      if (allocated(error)) return
      call check(error, abs(law%length() - 0.7_dp) < 1.0e-14_dp, "length " &
         & //format_real(law%length()))
      if (allocated(error)) return
      call law%pressure([-1.0_dp, 0.0_dp, 0.3_dp, 1.7_dp, 3.0_dp, 4.0_dp, 9.0_dp], pu, du)
      call check(error, maxval(abs(pu/(3.0_dp*exp(-[-1.0_dp, 0.0_dp, 0.3_dp, 1.7_dp, &
         & 3.0_dp, 4.0_dp, 9.0_dp]/0.7_dp)) - 1.0_dp)) < 1.0e-14_dp, "exponential values")
      if (allocated(error)) return
      call check(error, maxval(abs(du*(-0.7_dp)/pu - 1.0_dp)) < 1.0e-13_dp, "slopes")
      if (allocated(error)) return
      ! a curved table: p = 1/(1 + u)**3
      p = 1.0_dp/(1.0_dp + u)**3
      call new_table_law(u, p, law, e)
      call law%pressure(u, pu(:5), du(:5))
      call check(error, maxval(abs(pu(:5)/p - 1.0_dp)) < 1.0e-14_dp, "exact at the nodes")
      if (allocated(error)) return
      do i = 2, 4
         h = 1.0e-7_dp*(u(i + 1) - u(i))
         call law%pressure([u(i) - h], pl, dl)
         call law%pressure([u(i) + h], pr, dr)
         call check(error, abs(dl(1) - dr(1)) <= 1.0e-5_dp*abs(du(i)), "C1 at node " &
            & //to_string(i))
         if (allocated(error)) return
         call check(error, dl(1) < 0.0_dp .and. dr(1) < 0.0_dp, "decreasing")
         if (allocated(error)) return
      end do
   end subroutine test_table_law

   subroutine test_bad_tables(error)
      use egw_flat_law, only: table_flat_law, new_table_law
      type(error_type), allocatable, intent(out) :: error
      type(table_flat_law) :: law
      type(egw_error), allocatable :: e
      call new_table_law([0.0_dp, 1.0_dp, 1.0_dp], [3.0_dp, 2.0_dp, 1.0_dp], law, e)
      call check(error, allocated(e), "equal u accepted")
      if (allocated(error)) return
      call check(error, e%stat == egw_invalid_argument .and. index(e%message, "u(3)") == 1, &
         & e%message)
      if (allocated(error)) return
      call new_table_law([0.0_dp, 1.0_dp], [3.0_dp, -2.0_dp], law, e)
      call check(error, allocated(e), "negative p accepted")
      if (allocated(error)) return
      call check(error, index(e%message, "p(2)") == 1, e%message)
      if (allocated(error)) return
      call new_table_law([0.0_dp, 1.0_dp], [3.0_dp, 2.0_dp], law, e, area=[0.5_dp, 1.5_dp])
      call check(error, allocated(e), "area 1.5 accepted")
      if (allocated(error)) return
      call new_table_law([0.0_dp, 1.0_dp], [3.0_dp, 2.0_dp], law, e, dpdu=[-1.0_dp, 1.0_dp])
      call check(error, allocated(e), "dp/du > 0 accepted")
   end subroutine test_bad_tables

   !> GW's own law p_G(d) tabulated in the caller's units (nodes 0.02 sigma apart from
   !> -4 sigma to 14 sigma, exact slopes: the Hermite error in ln p is ~ (0.02)**4/384
   !> times ln p's fourth derivative, O(1) here: ~1e-9) gives the classic-GW sphere of the
   !> same pair: forces within 2e-7 (both solves at rel_tol 1e-8, their error estimates
   !> below 5e-9), stiffness within 1e-6, at separations and overlaps whose gaps stay on
   !> the table.
   subroutine test_tabulated_gw(error)
      use egw_flat_law, only: table_flat_law, new_table_law
      use egw_rough_sphere, only: solver_options, solve_result, solve_contact, &
         & solve_contact_law
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: params
      type(table_flat_law) :: law
      type(solver_options) :: options
      type(solve_result) :: ref, res
      type(egw_error), allocatable :: e
      real(dp), allocatable :: u(:), p(:), d(:)
      real(dp) :: deltas(4)
      integer :: i, n
      params = contact_params(model=model_gw, radius=1.0e-3_dp, modulus=1.0e9_dp, &
         & sigma=1.0e-6_dp, mu=4.0_dp)
      n = 901
      allocate (u(n), p(n), d(n))
      do i = 1, n
         u(i) = params%sigma*(-4.0_dp + 0.02_dp*real(i - 1, dp))
         call flat_pressure(params, u(i), p(i), d(i), e)
      end do
      call new_table_law(u, p, law, e, dpdu=d, length=params%sigma, modulus=params%modulus)
      call check(error, .not. allocated(e))
      if (allocated(error)) return
      options%rel_tol = 1.0e-8_dp
      deltas = params%sigma*[-2.0_dp, 0.0_dp, 1.0_dp, 5.0_dp]
      do i = 1, size(deltas)
         call solve_contact(params, options, deltas(i), ref, e)
         call check(error, .not. allocated(e), "GW solve")
         if (allocated(error)) return
         call solve_contact_law(params, law, options, deltas(i), res, e)
         if (allocated(e)) then
            call check(error, .false., e%message)
            return
         end if
         call check(error, abs(res%force/ref%force - 1.0_dp) < 2.0e-7_dp, "force at delta/" &
            & //"sigma = "//format_real(deltas(i)/params%sigma)//": "//format_real(res%force) &
            & //" vs GW "//format_real(ref%force))
         if (allocated(error)) return
         call check(error, abs(res%stiffness/ref%stiffness - 1.0_dp) < 1.0e-6_dp, &
            & "stiffness at delta/sigma = "//format_real(deltas(i)/params%sigma))
         if (allocated(error)) return
         call check(error, abs(res%contact_radius/ref%contact_radius - 1.0_dp) < 1.0e-6_dp, &
            & "contact radius at delta/sigma = "//format_real(deltas(i)/params%sigma))
         if (allocated(error)) return
      end do
      ! another E* than the law's
      params%modulus = 2.0e9_dp
      call solve_contact_law(params, law, options, 0.0_dp, res, e)
      call check(error, allocated(e), "a law of another E* was accepted")
   end subroutine test_tabulated_gw

   subroutine test_c(error)
      type(error_type), allocatable, intent(out) :: error
      integer(c_int) :: failed
      failed = c_flat_law()
      call check(error, failed == 0, to_string(int(failed))//" C check(s) failed")
   end subroutine test_c

end module test_flat_law
