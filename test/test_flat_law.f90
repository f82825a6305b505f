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
         & new_unittest("table law: a table with flow_pressure refused", test_law_table_cap), &
         & new_unittest("table law: steep given slopes stay monotone", test_steep_slopes), &
         & new_unittest("tabulated GW law = classic GW solve", test_tabulated_gw), &
         & new_unittest("C egw_flat_law_*, egw_solve_flat_law", test_c), &
         & new_unittest("ZMC law from pieces = the integral at random h", test_zmc_pieces), &
         & new_unittest("Persson: u(p) vs independent quadrature", test_persson_reference), &
         & new_unittest("Persson: small-load area, large-u asymptote", test_persson_limits), &
         & new_unittest("Persson: scale invariance, bad input", test_persson_scaling)]
   end subroutine collect_flat_law

   !> An exponential is reproduced exactly (ln p linear: every Hermite piece and both
   !> continuations are the same line), to rounding (1e-14); a curved table is exact at
   !> its nodes and continuous with a continuous slope across them (C1: one-sided
   !> differences at 1e-7 of the spacing agree to 1e-5 of the slope).
   !> build_table_law refuses flow_pressure > 0 naming it (force tables have no cap; before
   !> audit25 it was dropped and the uncapped table built), as egw_table_build_flat_law.
   subroutine test_law_table_cap(error)
      use egw_flat_law, only: table_flat_law, new_table_law
      use egw_table, only: build_table_law, force_table
      use egw_rough_sphere, only: solver_options
      use egw_status, only: egw_invalid_parameter
      type(error_type), allocatable, intent(out) :: error
      type(table_flat_law) :: law
      type(force_table) :: table
      type(contact_params) :: pair
      type(egw_error), allocatable :: e
      real(dp) :: u(3)
      u = [0.0_dp, 1.0e-6_dp, 3.0e-6_dp]
      call new_table_law(u, exp(-u/1.0e-6_dp), law, e)
      call check(error, .not. allocated(e))
      if (allocated(error)) return
      pair%radius = 1.0e-2_dp
      pair%modulus = 1.0e12_dp
      pair%flow_pressure = 1.0e9_dp
      call build_table_law(pair, law, solver_options(), -8.0e-6_dp, 4.0e-6_dp, 1.0e-4_dp, &
         & table, e)
      call check(error, allocated(e), "a law's table with flow_pressure was built")
      if (allocated(error)) return
      call check(error, e%stat == egw_invalid_parameter .and. &
         & index(e%message, "flow_pressure") == 1, e%message)
   end subroutine test_law_table_cap

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

   !> Given slopes far steeper than their interval's secant (a BEM law near full contact:
   !> ln p falls 0.23 over 4.7e-12 m with d ln p/du 13x the secant at one end): the cubic
   !> would overshoot (a pressure below the next node's, so no longer decreasing); with
   !> Fritsch and Carlson's bound it decreases everywhere (checked at 2001 points) and is
   !> still exact at the nodes (1e-14). Slopes within the bound are kept as given (1e-14).
   subroutine test_steep_slopes(error)
      use egw_flat_law, only: table_flat_law, new_table_law
      type(error_type), allocatable, intent(out) :: error
      type(table_flat_law) :: law
      type(egw_error), allocatable :: e
      real(dp) :: u(3), p(3), k(3), x(2001), px(2001), dx(2001), pn(3), dn(3)
      integer :: i
      u = [1.98e-14_dp, 4.71e-12_dp, 1.0e-9_dp]
      p = [3.162e7_dp, 2.512e7_dp, 1.088e7_dp]
      k = [-2.017e19_dp, -3.667e17_dp, -2.6e15_dp]
      call new_table_law(u, p, law, e, dpdu=k)
      call check(error, .not. allocated(e))
      if (allocated(error)) return
      x = [(u(1) + (u(2) - u(1))*real(i, dp)/2000.0_dp, i = 0, 2000)]
      call law%pressure(x, px, dx)
      call check(error, all(px(2:) < px(:2000)) .and. all(dx <= 0.0_dp), &
         & "not decreasing on the steep interval: min p "//format_real(minval(px)))
      if (allocated(error)) return
      call law%pressure(u, pn, dn)
      call check(error, maxval(abs(pn/p - 1.0_dp)) < 1.0e-14_dp, "exact at the nodes")
      if (allocated(error)) return
      ! within the bound (an exponential's own slopes): kept
      p = 3.0_dp*exp(-u/1.0e-9_dp)
      call new_table_law(u, p, law, e, dpdu=-p/1.0e-9_dp)
      call law%pressure(u, pn, dn)
      call check(error, maxval(abs(dn*(-1.0e-9_dp)/p - 1.0_dp)) < 1.0e-14_dp, &
         & "slopes within the bound changed")
   end subroutine test_steep_slopes

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

   !> The tabulated ZMC law (egw_law_pieces, egw_zmc_table_law) against the integral it
   !> was built from (rough_flat_law; itself checked against 40-digit quadrature in
   !> suite gauss) at 4000 random h per law over and beyond the table's range, for
   !> psi 0.2 .. 20 and two (K, rho_p). Tolerances: the pieces' acceptance, checked at
   !> 49 points a piece when built, with a factor 5 for points between those (the
   !> interpolation error of a degree-24 series varies by less between the check points
   !> and anywhere else on a piece: its error curve is near-equioscillating, and its
   !> maximum on the 49 points is within a few x of its maximum on the piece): p to
   !> 5 ln_tol (1 + |ln p|/64) relative, dp/dh to 5 slope_tol; outside the range the exact
   !> law itself (bit-equal). The table must cover h in [-40, 30] (where a build's
   !> gaps lie) and be built at width 1 or 1/2 (its cost).
   subroutine test_zmc_pieces(error)
      use egw_flat_law, only: gw_flat_law
      use egw_law_pieces, only: law_pieces, zmc_law_pieces, ln_tol, slope_tol
      use egw_zmc_table_law, only: zmc_table_law
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: psis(5) = [0.2_dp, 0.7_dp, 1.0_dp, 3.0_dp, 20.0_dp]
      real(dp), parameter :: ks(2) = [0.6_dp, 0.4_dp], rhos(2) = [54.0_dp, 10.0_dp]
      integer, parameter :: n = 4000
      type(zmc_table_law) :: tab
      type(gw_flat_law) :: exact
      real(dp) :: h(n), pt(n), dt(n), pe(n), de(n), worst_p, worst_d, r(n)
      integer :: i, j
      logical :: inside(n)
      call random_seed(put=[(7919*i, i=1, 64)])
      do j = 1, size(psis)*size(ks)
         associate (psi => psis(1 + mod(j - 1, size(psis))), &
            & k => ks(1 + (j - 1)/size(psis)), rho => rhos(1 + (j - 1)/size(psis)))
            tab%scale = 0.7_dp
            tab%pieces = zmc_law_pieces(psi, k, rho)
            exact = gw_flat_law(scale=0.7_dp, psi=psi, hardness_coeff=k, plastic_ratio=rho)
            call check(error, tab%pieces%n > 0 .and. tab%pieces%h_lo <= -40.0_dp .and. &
               & tab%pieces%h_hi >= 30.0_dp .and. tab%pieces%width >= 0.5_dp, &
               & "psi "//format_real(psi)//": no table over [-40, 30] at width >= 1/2 (n " &
               & //to_string(tab%pieces%n)//", width "//format_real(tab%pieces%width)//")")
            if (allocated(error)) return
            call random_number(r)
            h = -45.0_dp + r*(tab%pieces%h_hi + 10.0_dp)
            call tab%pressure(h, pt, dt)
            call exact%pressure(h, pe, de)
            inside = h >= tab%pieces%h_lo .and. h < tab%pieces%h_hi
            worst_p = maxval(abs(pt/pe - 1.0_dp)/(1.0_dp + abs(log(pe/0.7_dp))/64.0_dp), &
               & mask=inside)
            worst_d = maxval(abs(dt/de - 1.0_dp), mask=inside)
            call check(error, worst_p <= 5.0_dp*ln_tol .and. worst_d <= 5.0_dp*slope_tol, &
               & "psi "//format_real(psi)//", K "//format_real(k)//": p off by " &
               & //format_real(worst_p)//", dp/dh by "//format_real(worst_d))
            if (allocated(error)) return
            call check(error, all(pack(pt, .not. inside) == pack(pe, .not. inside)) .and. &
               & all(pack(dt, .not. inside) == pack(de, .not. inside)), &
               & "outside the range: not the exact law")
            if (allocated(error)) return
            print '(a, es9.2, a, es9.2, a, es9.2, a, es9.2, a, f6.3, a, f7.2, a, i4)', &
               & "   zmc pieces psi ", psi, " K ", k, ": p ", worst_p, ", dp/dh ", &
               & worst_d, ", width ", tab%pieces%width, ", h_hi ", tab%pieces%h_hi, &
               & ", n ", tab%pieces%n
         end associate
      end do
      ! bad input: no table (every value from the integral)
      tab%pieces = zmc_law_pieces(0.0_dp, 0.6_dp, 54.0_dp)
      call check(error, tab%pieces%n == 0, "psi 0 tabulated")
      if (allocated(error)) return
      tab%pieces = zmc_law_pieces(1.0_dp, 0.6_dp, 54.0_dp, h_lo=0.5_dp)
      call check(error, tab%pieces%n == 0, "h_lo 0.5 tabulated")
   end subroutine test_zmc_pieces

   subroutine test_c(error)
      type(error_type), allocatable, intent(out) :: error
      integer(c_int) :: failed
      failed = c_flat_law()
      call check(error, failed == 0, to_string(int(failed))//" C check(s) failed")
   end subroutine test_c

   !> The self-affine spectrum of tools/reference/persson_reference.py.
   subroutine reference_psd(q, c)
      use egw_flat_persson, only: self_affine_psd
      real(dp), allocatable, intent(out) :: q(:), c(:)
      type(egw_error), allocatable :: e
      real(dp), parameter :: two_pi = 6.283185307179586_dp
      call self_affine_psd(0.8_dp, 1.0e-6_dp, two_pi/1.0e-3_dp, two_pi/1.0e-4_dp, &
         & two_pi/1.0e-6_dp, q, c, e)
   end subroutine reference_psd

   !> Persson's u(p) against test/data/persson_reference.csv (the published double
   !> integral by nested adaptive quadrature, its error <= 2e-12): egw within 1e-9 (its
   !> tabulated J ~1e-11, Gauss-Legendre panels ~1e-12; measured 1e-11), p/E* 1e-7..5e-2.
   subroutine test_persson_reference(error)
      use egw_flat_persson, only: persson_flat_curve, persson_options
      type(error_type), allocatable, intent(out) :: error
      real(dp), allocatable :: q(:), c(:), u(:), p(:), area(:), dpdu(:)
      type(egw_error), allocatable :: e
      real(dp) :: pr, uref, err
      integer :: unit, ios
      character(len=256) :: line
      call reference_psd(q, c)
      open (newunit=unit, file="test/data/persson_reference.csv", status="old", &
         & action="read", iostat=ios)
      call check(error, ios == 0, "test/data/persson_reference.csv not found")
      if (allocated(error)) return
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:1) == "#" .or. line(1:1) == "p") cycle
         read (line, *) pr, uref, err
         call persson_flat_curve(q, c, 1.0e9_dp, pr*1.0e9_dp, 2.0_dp*pr*1.0e9_dp, 1, &
            & persson_options(), u, p, area, dpdu, e)
         if (allocated(e)) then
            call check(error, .false., e%message)
            exit
         end if
         call check(error, abs(u(1)/uref - 1.0_dp) < 1.0e-9_dp, "p/E* = " &
            & //format_real(pr)//": u = "//format_real(u(1))//", reference " &
            & //format_real(uref))
         if (allocated(error)) exit
      end do
      close (unit)
   end subroutine test_persson_reference

   !> The theory's limits, in closed form: at small load A/A0 -> sqrt(8/pi) p/(E*
   !> sqrt(m2)) (erf's linear term: relative deviation (2/3) x^2 ~ 1e-17 at p/E* = 1e-9),
   !> m2 = 2 pi int q^3 C of the self-affine spectrum; far apart, p ~ exp(-u/u0):
   !> -du/d ln p between p/E* = 1e-10 and 1e-9 within 1e-4 of u0 = 5.1758891e-7 m
   !> (persson_reference.py; the corrections are O((w p/E*)^2) and from the few q near the
   !> longest wavelength where w p/E* is not small). And dp/du = the curve's slope:
   !> the exact dp/du against centred differences of u(ln p) (1e-6).
   subroutine test_persson_limits(error)
      use egw_flat_persson, only: persson_flat_curve, persson_options
      type(error_type), allocatable, intent(out) :: error
      real(dp), allocatable :: q(:), c(:), u(:), p(:), area(:), dpdu(:)
      type(egw_error), allocatable :: e
      real(dp) :: m2, kappa_law, slope, fd
      real(dp), parameter :: e_star = 1.0e9_dp, h = 0.8_dp, u0 = 5.1758891046980315e-7_dp
      integer :: k
      call reference_psd(q, c)
      m2 = 6.283185307179586_dp*(c(1)*(q(2)**4 - q(1)**4)/4.0_dp + c(1)*q(2)**4* &
         & ((q(3)/q(2))**(2.0_dp - 2.0_dp*h) - 1.0_dp)/(2.0_dp - 2.0_dp*h))
      call persson_flat_curve(q, c, e_star, 1.0e-10_dp*e_star, 1.0e-9_dp*e_star, 1, &
         & persson_options(), u, p, area, dpdu, e)
      call check(error, .not. allocated(e))
      if (allocated(error)) return
      kappa_law = area(2)/(p(2)/(e_star*sqrt(m2)))
      call check(error, abs(kappa_law/sqrt(8.0_dp/3.141592653589793_dp) - 1.0_dp) < 1.0e-10_dp, &
         & "small-load area: kappa = "//format_real(kappa_law))
      if (allocated(error)) return
      slope = -(u(2) - u(1))/log(p(2)/p(1))
      call check(error, abs(slope/u0 - 1.0_dp) < 1.0e-4_dp, "-du/dln p = " &
         & //format_real(slope)//", u0 = "//format_real(u0))
      if (allocated(error)) return
      call persson_flat_curve(q, c, e_star, 1.0e-4_dp*e_star, 1.0e-1_dp*e_star, 300, &
         & persson_options(), u, p, area, dpdu, e)
      do k = 3, size(u) - 2, 50
         ! fourth-order difference of u in ln p (uniform): error ~ (ln 10/300)**4 ~ 1e-9
         fd = p(k)*12.0_dp*log(p(k + 1)/p(k))/(-u(k + 2) + 8.0_dp*u(k + 1) &
            & - 8.0_dp*u(k - 1) + u(k - 2))
         call check(error, abs(dpdu(k)/fd - 1.0_dp) < 1.0e-7_dp, "dp/du at p/E* = " &
            & //format_real(p(k)/e_star)//": "//format_real(dpdu(k))//" vs " &
            & //format_real(fd))
         if (allocated(error)) return
      end do
   end subroutine test_persson_limits

   !> Heights times s (C -> s^2 C) give u(p) = s u_1(p/s) (slopes times s), and u depends
   !> on p/E* alone (E* and p times the same factor): to 1e-12; bad input names the
   !> argument.
   subroutine test_persson_scaling(error)
      use egw_flat_persson, only: persson_flat_curve, persson_options
      type(error_type), allocatable, intent(out) :: error
      real(dp), allocatable :: q(:), c(:), u(:), p(:), area(:), dpdu(:), u2(:)
      type(egw_error), allocatable :: e
      call reference_psd(q, c)
      call persson_flat_curve(q, c, 1.0e9_dp, 1.0e3_dp, 1.0e7_dp, 2, persson_options(), &
         & u, p, area, dpdu, e)
      call persson_flat_curve(q, 9.0_dp*c, 1.0e9_dp, 3.0e3_dp, 3.0e7_dp, 2, &
         & persson_options(), u2, p, area, dpdu, e)
      call check(error, maxval(abs(u2/(3.0_dp*u) - 1.0_dp)) < 1.0e-12_dp, "heights x 3")
      if (allocated(error)) return
      call persson_flat_curve(q, c, 7.0e9_dp, 7.0e3_dp, 7.0e7_dp, 2, persson_options(), &
         & u2, p, area, dpdu, e)
      call check(error, maxval(abs(u2/u - 1.0_dp)) < 1.0e-12_dp, "E*, p x 7")
      if (allocated(error)) return
      call persson_flat_curve(q(3:1:-1), c, 1.0e9_dp, 1.0e3_dp, 1.0e7_dp, 2, &
         & persson_options(), u2, p, area, dpdu, e)
      call check(error, allocated(e), "descending q accepted")
      if (allocated(error)) return
      call check(error, index(e%message, "q(2)") == 1, e%message)
      if (allocated(error)) return
      call persson_flat_curve(q, -c, 1.0e9_dp, 1.0e3_dp, 1.0e7_dp, 2, persson_options(), &
         & u2, p, area, dpdu, e)
      call check(error, allocated(e), "negative C accepted")
      if (allocated(error)) return
      call persson_flat_curve(q, c, 1.0e9_dp, 1.0e3_dp, 1.0e7_dp, 2, persson_options(2.0_dp), &
         & u2, p, area, dpdu, e)
      call check(error, allocated(e), "gamma = 2 accepted")
   end subroutine test_persson_scaling

end module test_flat_law
