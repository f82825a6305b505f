!> Tests of egw_unloading: the ZMC summit on unloading and the rough flat's Z_u(h, h_min),
!> against 40-digit values (tools/reference/unload_refs.py, two independent forms of the
!> integral) and the law's own identities.
module test_unloading
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_invalid_argument, egw_invalid_parameter, format_real
   use egw_params, only: contact_params, model_epgw, model_egw
   use egw_asperity, only: rough_flat_law
   use egw_unloading, only: asperity_load_force, asperity_contact_area, &
      & asperity_residual_interference, asperity_unload_force, rough_flat_unload_law, &
      & flat_pressure_unload, unloading_law, unloading_law_of, unloading_pressure, &
      & unloading_kinks, tabulate_unloading, unload_slope_tol
   use egw_simd_path, only: simd_level, simd_set
   use testdrive, only: new_unittest, unittest_type, error_type, check, test_failed, to_string
   implicit none
   private
   public :: collect_unloading

contains

   subroutine collect_unloading(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("asperity: elastic summits recover fully", test_elastic_summit), &
         & new_unittest("asperity: law continuous, unloading below loading", test_summit), &
         & new_unittest("Z_u against 40-digit references", test_references), &
         & new_unittest("Z_u: AVX2 and baseline paths", test_simd_paths), &
         & new_unittest("Z_u: graded tail panels, 40-digit references", test_tail_references), &
         & new_unittest("Z_u(h, h) = Z(h), Z_u <= Z, monotone", test_identities), &
         & new_unittest("Z_u continuous at the kinks", test_continuity), &
         & new_unittest("dZ_u/dh against differences", test_derivative), &
         & new_unittest("prepared law: same Z_u, its kinks in Delta", test_prepared_law), &
         & new_unittest("prepared law with the loading table: same Z_u", test_loading_table), &
         & new_unittest("unloading table at one h_min: 40-digit references", &
         & test_unloading_table_references), &
         & new_unittest("unloading table at one h_min: the integral's Z_u", test_unloading_table), &
         & new_unittest("flat_pressure_unload: units and bad input", test_dimensional) &
         & ]
   end subroutine collect_unloading

   !> u_r = 0 and f_u = f for elastic summits (u_m <= e, or psi = 0): f = u^(3/2) exactly
   !> and A = u, so u_m - f/sqrt(A) = 0 up to rounding of u^(3/2)/u^(1/2).
   subroutine test_elastic_summit(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: u(4) = [0.01_dp, 0.2_dp, 0.24_dp, 3.0_dp]
      integer :: i
      do i = 1, 3  ! psi = 2: e = 0.25
         call check(error, asperity_residual_interference(u(i), 2.0_dp, 0.6_dp, 54.0_dp), &
            & 0.0_dp, "u_r(elastic u_m = "//format_real(u(i))//")")
         if (allocated(error)) return
      end do
      call check(error, asperity_residual_interference(u(4), 0.0_dp, 0.6_dp, 54.0_dp), &
         & 0.0_dp, "u_r(psi = 0)")
      if (allocated(error)) return
      call check(error, asperity_unload_force(1.0_dp, 3.0_dp, 0.0_dp, 0.6_dp, 54.0_dp), &
         & 1.0_dp, "psi = 0: f_u(1; 3) = 1^(3/2)", rel=.true., thr=4.0e-16_dp)
      if (allocated(error)) return
      call check(error, asperity_contact_area(0.1_dp, 2.0_dp, 54.0_dp), 0.1_dp, "A(0.1) = 0.1")
   end subroutine test_elastic_summit

   !> The loading law is continuous at e and q (values to 1e-15); a plastic summit keeps a
   !> residual interference; unloading forces lie below loading and vanish at u_r; the
   !> unloading curve starts with the elastic stiffness of the contact radius:
   !> d f_u/du at u_m = (3/2) f(u_m)/(u_m - u_r) = (3/2) sqrt(A(u_m)) (= 2 E a_m in units).
   subroutine test_summit(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: psi = 2.0_dp, k = 0.6_dp, rho = 54.0_dp, e = 0.25_dp
      real(dp) :: q, um, ur, fm, slope, h
      integer :: i
      q = rho*e
      call check(error, asperity_load_force(e*(1 + 1.0e-15_dp), psi, k, rho), &
         & asperity_load_force(e, psi, k, rho), "f continuous at e", rel=.true., thr=1.0e-14_dp)
      if (allocated(error)) return
      call check(error, asperity_load_force(q*(1 + 1.0e-15_dp), psi, k, rho), &
         & asperity_load_force(q, psi, k, rho), "f continuous at q", rel=.true., thr=1.0e-14_dp)
      if (allocated(error)) return
      um = 4.0_dp
      ur = asperity_residual_interference(um, psi, k, rho)
      call check(error, ur > 0.0_dp .and. ur < um, "plastic summit: 0 < u_r < u_m")
      if (allocated(error)) return
      call check(error, asperity_unload_force(ur, um, psi, k, rho), 0.0_dp, "f_u(u_r) = 0")
      if (allocated(error)) return
      fm = asperity_load_force(um, psi, k, rho)
      call check(error, asperity_unload_force(um, um, psi, k, rho), fm, "f_u(u_m) = f(u_m)")
      if (allocated(error)) return
      do i = 1, 9
         h = ur + (um - ur)*i/10.0_dp
         call check(error, asperity_unload_force(h, um, psi, k, rho) < &
            & asperity_load_force(h, psi, k, rho), "f_u < f at u = "//format_real(h))
         if (allocated(error)) return
      end do
      h = 1.0e-7_dp*um
      slope = (fm - asperity_unload_force(um - h, um, psi, k, rho))/h
      ! backward difference: error ~ f'' h / 2 relative ~ 1e-7
      call check(error, slope, 1.5_dp*sqrt(asperity_contact_area(um, psi, rho)), &
         & "initial unloading stiffness = elastic stiffness of a_m", rel=.true., thr=1.0e-6_dp)
   end subroutine test_summit

   !> Every row of test/data/unload_reference.csv: psi in [0.1, 100], K in [0.05, 0.95],
   !> rho_p in [1.5, 1000], h_min from -8 to 5, h - h_min from 0 to beyond q. The fixed rule
   !> must reach 1e-12 relative (the issue's accuracy; the rule's panels are sized for
   !> ~1e-15, the rest is rounding of the Gaussian factor far in the tail); dZ_u/dh the same.
   subroutine test_references(error)
      type(error_type), allocatable, intent(out) :: error
      call check_reference_file(error, "test/data/unload_reference.csv", 1.0e-12_dp, &
         & 0.0_dp, 300, "")
   end subroutine test_references

   !> Every row (psi, K, rho_p, h, h_min, Z_u, dZ_u/dh) of a 40-digit reference file against
   !> rough_flat_unload_law, Z_u and dZ_u/dh within tol_floor + tol_per_log |ln Z_u|
   !> relative; at least min_rows rows; label heads the failure's message.
   subroutine check_reference_file(error, path, tol_floor, tol_per_log, min_rows, label)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), intent(in) :: path, label
      real(dp), intent(in) :: tol_floor, tol_per_log
      integer, intent(in) :: min_rows
      character(len=512) :: line
      real(dp) :: psi, k, rho, h, h_min, z, dz, p, dp_, tol
      integer :: unit, ios, rows
      open (newunit=unit, file=path, status="old", action="read", iostat=ios)
      if (ios /= 0) then
         call test_failed(error, "cannot open "//path//" (run the tests from the project root)")
         return
      end if
      rows = 0
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:1) == "#" .or. line(1:4) == "psi,") cycle
         read (line, *) psi, k, rho, h, h_min, z, dz
         call rough_flat_unload_law(h, h_min, psi, k, rho, p, dp_)
         rows = rows + 1
         tol = tol_floor + tol_per_log*abs(log(z))
         call check(error, p, z, label//trim(line)//": Z_u", rel=.true., thr=tol)
         if (allocated(error)) exit
         call check(error, dp_, dz, label//trim(line)//": dZ_u/dh", rel=.true., thr=tol)
         if (allocated(error)) exit
      end do
      close (unit)
      if (allocated(error)) return
      call check(error, rows >= min_rows, to_string(rows)//" rows read from "//path)
   end subroutine check_reference_file

   !> Z_u where the integral's panels in the Gaussian's tail are graded (egw_unloading's
   !> tail_width): test/data/unload_tail_reference.csv (tools/reference/unload_refs.py
   !> --tail, 40 digits), on both paths. The edge left of the Gaussian's peak with small K,
   !> where a grading too strong shows first (tail_grade 1, 7x this one: 2.7e-13 .. 4.5e-13
   !> at the first four rows), and README's psi 1 + cap build's calls (K 0.6, rho_p 54).
   !> Within 2e-14 (1 + |ln Z_u|) relative: the rule's panels sized for ~1e-15, plus the
   !> rounding of the Gaussian's exponent, which grows with it (measured: 2.8e-16 .. 7.8e-15
   !> where Z_u ~ 1e-4 .. 4, 7.2e-14 at Z_u = 2e-71, dZ_u/dh alike).
   subroutine test_tail_references(error)
      type(error_type), allocatable, intent(out) :: error
      integer :: level0, got, level
      level0 = simd_level()
      do level = 0, 1
         if (simd_set(level) /= level) cycle  ! no AVX2 + FMA here: the baseline path only
         call check_reference_file(error, "test/data/unload_tail_reference.csv", 2.0e-14_dp, &
            & 2.0e-14_dp, 8, "path "//to_string(level)//", ")
         if (allocated(error)) exit
      end do
      got = simd_set(level0)
   end subroutine test_tail_references

   !> The integral's two paths (egw_simd_path: the nodes four lanes wide in AVX2 + FMA,
   !> unloading_simd.c; the baseline's two lanes): each against every 40-digit reference
   !> of test_references at its 1e-12 relative (measured: both paths 7.4e-14 on Z_u,
   !> 9.4e-14 on dZ_u/dh), and each other on 20000 random (psi in [0.1, 100], K, rho_p in
   !> [1.5, 1000], h_min in [-8, 5], Delta in [1e-8, 30]) wherever Z_u is above 1e4 tiny:
   !> within 1e-12 relative, the references' own bound, as each path sits within ~1e-13
   !> of the exact value (measured apart: 1.9e-13 on Z_u, 1.6e-13 on dZ_u/dh; the paths
   !> differ in rounding only: glibc's 4- and 2-lane log and exp, fused multiply-adds, the
   !> Gaussian's split). A wrong lane, branch or constant of the AVX2 kernel moves Z_u by
   !> far more (the area's cubic 3 made 3 + 3e-8: 8.3e-8 from the references). Skipped
   !> (passes) on a CPU without AVX2 and FMA.
   subroutine test_simd_paths(error)
      type(error_type), allocatable, intent(out) :: error
      character(len=*), parameter :: path = "test/data/unload_reference.csv"
      character(len=512) :: line
      real(dp) :: psi, k, rho, h, h_min, z, dz, p(0:1), dp_(0:1), u(5), worst(0:1, 2), &
         & apart(2)
      integer :: unit, ios, rows, level0, got, level, i
      level0 = simd_level()
      if (simd_set(1) /= 1) then
         got = simd_set(level0)
         return
      end if
      open (newunit=unit, file=path, status="old", action="read", iostat=ios)
      if (ios /= 0) then
         got = simd_set(level0)
         call test_failed(error, "cannot open "//path//" (run the tests from the project root)")
         return
      end if
      worst = 0.0_dp
      rows = 0
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:1) == "#" .or. line(1:4) == "psi,") cycle
         read (line, *) psi, k, rho, h, h_min, z, dz
         rows = rows + 1
         do level = 0, 1
            got = simd_set(level)
            call rough_flat_unload_law(h, h_min, psi, k, rho, p(level), dp_(level))
            worst(level, 1) = max(worst(level, 1), abs(p(level) - z)/abs(z))
            worst(level, 2) = max(worst(level, 2), abs(dp_(level) - dz)/max(abs(dz), tiny(1.0_dp)))
         end do
      end do
      close (unit)
      apart = 0.0_dp
      call random_seed(put=[(20261201 + i, i=1, 64)])
      do i = 1, 20000
         call random_number(u)
         psi = 0.1_dp*1000.0_dp**u(1)
         k = 0.05_dp + 0.9_dp*u(2)
         rho = 1.5_dp*(1000.0_dp/1.5_dp)**u(3)
         h_min = -8.0_dp + 13.0_dp*u(4)
         h = h_min + 1.0e-8_dp*(30.0_dp/1.0e-8_dp)**u(5)
         do level = 0, 1
            got = simd_set(level)
            call rough_flat_unload_law(h, h_min, psi, k, rho, p(level), dp_(level))
         end do
         if (.not. p(0) > 1.0e4_dp*tiny(1.0_dp)) cycle
         apart(1) = max(apart(1), abs(p(1) - p(0))/p(0))
         apart(2) = max(apart(2), abs(dp_(1) - dp_(0))/abs(dp_(0)))
      end do
      got = simd_set(level0)
      call check(error, rows >= 300, to_string(rows)//" rows read from "//path)
      if (allocated(error)) return
      call check(error, maxval(worst) <= 1.0e-12_dp, "Z_u, dZ_u/dh against the references: "// &
         & "baseline "//format_real(maxval(worst(0, :)))//", AVX2 "//format_real(maxval(worst(1, :))))
      if (allocated(error)) return
      call check(error, maxval(apart) <= 1.0e-12_dp, "AVX2 and baseline apart by "// &
         & format_real(apart(1))//" (Z_u), "//format_real(apart(2))//" (dZ_u/dh)")
   end subroutine test_simd_paths

   !> Z_u(h_min, h_min) = Z(h_min) exactly (the loading value); h < h_min is the loading law;
   !> Z_u <= Z and Z_u decreases in h (unloading); psi = 0 is the loading law everywhere.
   subroutine test_identities(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: p, dp_, z, dz, prev
      integer :: i
      call rough_flat_law(-0.7_dp, 3.0_dp, 0.6_dp, 54.0_dp, z, dz)
      call rough_flat_unload_law(-0.7_dp, -0.7_dp, 3.0_dp, 0.6_dp, 54.0_dp, p, dp_)
      call check(error, p, z, "Z_u(h, h) = Z(h)")
      if (allocated(error)) return
      call check(error, dp_ < dz, "unloading slope steeper than loading at h = h_min")
      if (allocated(error)) return
      call rough_flat_unload_law(-1.0_dp, -0.7_dp, 3.0_dp, 0.6_dp, 54.0_dp, p, dp_)
      call rough_flat_law(-1.0_dp, 3.0_dp, 0.6_dp, 54.0_dp, z, dz)
      call check(error, p == z .and. dp_ == dz, "h < h_min: the loading law")
      if (allocated(error)) return
      call rough_flat_unload_law(0.3_dp, -2.0_dp, 0.0_dp, 0.6_dp, 54.0_dp, p, dp_)
      call rough_flat_law(0.3_dp, 0.0_dp, 0.6_dp, 54.0_dp, z, dz)
      call check(error, p == z .and. dp_ == dz, "psi = 0: reversible")
      if (allocated(error)) return
      prev = huge(1.0_dp)
      do i = 0, 40
         call rough_flat_unload_law(-2.0_dp + 0.1_dp*i, -2.0_dp, 3.0_dp, 0.6_dp, 54.0_dp, &
            & p, dp_)
         call rough_flat_law(-2.0_dp + 0.1_dp*i, 3.0_dp, 0.6_dp, 54.0_dp, z, dz)
         call check(error, p <= z*(1 + 1.0e-14_dp), "Z_u <= Z at step "//to_string(i))
         if (allocated(error)) return
         call check(error, p <= prev .and. dp_ <= 0.0_dp, "Z_u decreasing, step "//to_string(i))
         if (allocated(error)) return
         prev = p
      end do
   end subroutine test_identities

   !> Continuity where the unloading branch changes form: h - h_min crossing e (contact edge
   !> moves from the elastic to the elasto-plastic summits) and the recovery's maximum at q;
   !> the value just below and above agree to 1e-12 + the change of the smooth function over
   !> the step (|dZ/dh| * 2e-12, bounded by the first-order term).
   subroutine test_continuity(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: psi = 2.0_dp, k = 0.6_dp, rho = 54.0_dp, h_min = -1.5_dp
      real(dp) :: kinks(2), lo, hi, dlo, dhi, d, eps
      integer :: i
      kinks = [0.25_dp, 0.0_dp]  ! Delta = e, and Delta = r(q) = sqrt(e)/K sqrt(2 q)
      kinks(2) = sqrt(0.25_dp)/k*sqrt(2.0_dp*rho*0.25_dp)
      do i = 1, 2
         eps = 1.0e-12_dp*kinks(i)
         call rough_flat_unload_law(h_min + kinks(i) - eps, h_min, psi, k, rho, lo, dlo)
         call rough_flat_unload_law(h_min + kinks(i) + eps, h_min, psi, k, rho, hi, dhi)
         d = abs(hi - lo) - 2.0_dp*eps*max(abs(dlo), abs(dhi))
         call check(error, d <= 1.0e-12_dp*abs(lo), "Z_u continuous at kink "//to_string(i)// &
            & ": jump "//format_real(d)//", values "//format_real(lo)//" "//format_real(hi))
         if (allocated(error)) return
      end do
   end subroutine test_continuity

   !> dZ_u/dh against a central difference of Z_u (step 1e-5: truncation ~1e-10, rounding
   !> 1e-16/1e-5 ~ 1e-11 relative; tolerance 1e-8).
   subroutine test_derivative(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: hs(4) = [-1.2_dp, -0.4_dp, 0.5_dp, 2.0_dp]
      real(dp) :: p, dp_, pl, pr, dl, dr, step
      integer :: i
      step = 1.0e-5_dp
      do i = 1, 4
         call rough_flat_unload_law(hs(i), -1.5_dp, 1.5_dp, 0.4_dp, 54.0_dp, p, dp_)
         call rough_flat_unload_law(hs(i) - step, -1.5_dp, 1.5_dp, 0.4_dp, 54.0_dp, pl, dl)
         call rough_flat_unload_law(hs(i) + step, -1.5_dp, 1.5_dp, 0.4_dp, 54.0_dp, pr, dr)
         call check(error, dp_, (pr - pl)/(2*step), "dZ_u/dh at h = "//format_real(hs(i)), &
            & rel=.true., thr=1.0e-8_dp)
         if (allocated(error)) return
      end do
   end subroutine test_derivative

   !> A law prepared once (unloading_law_of, as the sphere solver uses it) gives the values of
   !> rough_flat_unload_law bit for bit, on both branches. Its kinks in Delta are e = 1/psi^2,
   !> min(q, r(q)) with r(q) = sqrt(e)/K sqrt(2 q) (ZMC beyond q: f^ = 2 c u, A^ = 2u) and
   !> the switches of the recovery, where the residual interference (asperity_residual_
   !> interference, an independent path) turns from 0 to positive or back: checked on both
   !> sides at 1e-9 relative (K = 0.3: r(t) - t changes sign inside (e, q)). And d^2 Z_u/dh^2
   !> does jump there: at K = 0.6 the recovery is partial just above e (r'(e) = 1/2 + (1 -
   !> K)/(K ln rho_p) = 0.67 < 1), so D' jumps under the integral's edge at Delta = e; second
   !> differences (step 1e-4) 3e-4 either side of e differ by 4.6e-3 relative, against
   !> 2.2e-4 for the same pair at Delta = e/2 (bounds 2e-3 and 1e-3). A kink inside an
   !> element costs the sphere solver its order: those radii become element edges.
   subroutine test_prepared_law(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: psi = 2.0_dp, rho = 54.0_dp, h_min = -0.5_dp
      type(unloading_law) :: law
      real(dp), allocatable :: kinks(:)
      real(dp) :: p, dp_, pr, dpr, e, q, s, lo, hi, k, jump(2)
      integer :: i
      k = 0.3_dp
      law = unloading_law_of(psi, k, rho)
      do i = 0, 30
         call unloading_pressure(law, h_min - 1.0_dp + 0.1_dp*i, h_min, p, dp_)
         call rough_flat_unload_law(h_min - 1.0_dp + 0.1_dp*i, h_min, psi, k, rho, pr, dpr)
         call check(error, p == pr .and. dp_ == dpr, "prepared law at step "//to_string(i))
         if (allocated(error)) return
      end do
      e = 1.0_dp/psi**2
      q = rho*e
      kinks = unloading_kinks(law)
      call check(error, size(kinks) >= 3, to_string(size(kinks))//" kinks: e, D(q) and a switch")
      if (allocated(error)) return
      call check(error, kinks(1), e, "kink at Delta = e", rel=.true., thr=1.0e-15_dp)
      if (allocated(error)) return
      call check(error, kinks(2), min(q, sqrt(e)/k*sqrt(2.0_dp*q)), "kink at D(q)", &
         & rel=.true., thr=1.0e-14_dp)
      if (allocated(error)) return
      do i = 3, size(kinks)
         s = kinks(i)
         lo = asperity_residual_interference(s*(1.0_dp - 1.0e-9_dp), psi, k, rho)
         hi = asperity_residual_interference(s*(1.0_dp + 1.0e-9_dp), psi, k, rho)
         call check(error, (lo == 0.0_dp) .neqv. (hi == 0.0_dp), "switch "//to_string(i - 2) &
            & //" at "//format_real(s)//": u_r "//format_real(lo)//", "//format_real(hi))
         if (allocated(error)) return
      end do
      k = 0.6_dp
      jump(1) = d2_change(e)
      jump(2) = d2_change(0.5_dp*e)
      call check(error, jump(1) > 2.0e-3_dp .and. jump(2) < 1.0e-3_dp, "d2Z_u/dh2 change " &
         & //"across Delta = e: "//format_real(jump(1))//", across e/2: "//format_real(jump(2)))
   contains
      !> relative change of the second difference of Z_u (step 1e-4) from 3e-4 below to
      !> 3e-4 above Delta = x
      real(dp) function d2_change(x) result(c)
         real(dp), intent(in) :: x
         real(dp), parameter :: step = 1.0e-4_dp
         real(dp) :: z(-1:1), dz, d2(2)
         integer :: i, j
         do j = 1, 2
            do i = -1, 1
               call rough_flat_unload_law(h_min + x + (2*j - 3)*3.0_dp*step + i*step, &
                  & h_min, psi, k, rho, z(i), dz)
            end do
            d2(j) = (z(1) - 2.0_dp*z(0) + z(-1))/step**2
         end do
         c = abs(d2(2)/d2(1) - 1.0_dp)
      end function d2_change
   end subroutine test_prepared_law

   !> Z_u tabulated at one h_min (tabulate_unloading) against the 40-digit references of
   !> every row with h > h_min whose Delta the table covers: a table per (psi, K, rho_p,
   !> h_min) of the file, evaluated through unloading_pressure. Tolerance: the integral's
   !> 1e-12 (test_references) plus 5x the table's acceptance against the integral (ln_tol
   !> on ln Z_u, scaled as there; unload_slope_tol on dZ_u/dh), the check's points lying between
   !> the series' nodes as these rows do.
   subroutine test_unloading_table_references(error)
      use egw_law_pieces, only: law_pieces, zmc_law_pieces, ln_tol
      type(error_type), allocatable, intent(out) :: error
      character(len=*), parameter :: path = "test/data/unload_reference.csv"
      character(len=512) :: line
      real(dp) :: psi, k, rho, h, h_min, z, dz, p, dp_, last(4), bound
      type(law_pieces) :: pieces
      type(unloading_law) :: law
      integer :: unit, ios, rows
      open (newunit=unit, file=path, status="old", action="read", iostat=ios)
      if (ios /= 0) then
         call test_failed(error, "cannot open "//path//" (run the tests from the project root)")
         return
      end if
      rows = 0
      last = -1.0_dp
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:1) == "#" .or. line(1:4) == "psi,") cycle
         read (line, *) psi, k, rho, h, h_min, z, dz
         if (.not. (psi > 0.0_dp .and. h > h_min)) cycle
         if (any([psi, k, rho, h_min] /= last)) then
            pieces = zmc_law_pieces(psi, k, rho)
            call tabulate_unloading(pieces, h_min)
            law = unloading_law_of(psi, k, rho, pieces)
            last = [psi, k, rho, h_min]
         end if
         if (pieces%unload%n == 0) cycle
         if (.not. h - h_min < pieces%unload%edges(pieces%unload%n)) cycle
         call unloading_pressure(law, h, h_min, p, dp_)
         rows = rows + 1
         bound = 1.0e-12_dp + 5.0_dp*ln_tol*(1.0_dp + abs(log(z))/64.0_dp)
         call check(error, p, z, trim(line)//": Z_u from the table", rel=.true., thr=bound)
         if (allocated(error)) exit
         call check(error, dp_, dz, trim(line)//": dZ_u/dh from the table", rel=.true., &
            & thr=1.0e-12_dp + 5.0_dp*unload_slope_tol)
         if (allocated(error)) exit
      end do
      close (unit)
      if (allocated(error)) return
      call check(error, rows >= 150, to_string(rows)//" rows answered by tables")
   end subroutine test_unloading_table_references

   !> The table at one h_min against the integral on 4000 random Delta over its range (psi
   !> 1 and 0.3, h_min -3.7 and 0.8, K 0.6, rho_p 54): within 5x the acceptance; the
   !> table used (values differ from the integral's somewhere), its acceptance met as
   !> recorded; at an h_min beyond the slack, and on [d_end, d_end + 1), the integral bit
   !> for bit; from d_end + 1 on 0, where the integral is below 1e-280; no table for an
   !> empty loading law.
   subroutine test_unloading_table(error)
      use egw_law_pieces, only: law_pieces, zmc_law_pieces, ln_tol
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: n = 4000
      real(dp) :: h(n), hm(n), p0(n), d0(n), p1(n), d1(n), r(n), psi, h_min, d_end
      type(unloading_law) :: plain, tabled
      type(law_pieces) :: pieces
      integer :: i, k
      call random_seed(put=[(7919*i, i=1, 64)])
      do k = 1, 4
         psi = merge(1.0_dp, 0.3_dp, k <= 2)
         h_min = merge(-3.7_dp, 0.8_dp, mod(k, 2) == 1)
         pieces = zmc_law_pieces(psi, 0.6_dp, 54.0_dp)
         call tabulate_unloading(pieces, h_min)
         call check(error, pieces%unload%n > 0, "psi "//format_real(psi)//", h_min "// &
            & format_real(h_min)//": no table")
         if (allocated(error)) return
         call check(error, pieces%unload%ln_error <= ln_tol .and. &
            & pieces%unload%slope_error <= unload_slope_tol, "acceptance not met as recorded")
         if (allocated(error)) return
         d_end = pieces%unload%edges(pieces%unload%n)
         plain = unloading_law_of(psi, 0.6_dp, 54.0_dp)
         tabled = unloading_law_of(psi, 0.6_dp, 54.0_dp, pieces)
         call random_number(r)
         hm = h_min
         h = h_min + d_end*r
         call unloading_pressure(plain, h, hm, p0, d0)
         call unloading_pressure(tabled, h, hm, p1, d1)
         call check(error, any(p1 /= p0), "the table was not used")
         if (allocated(error)) return
         call check(error, maxval(abs(log(p1/p0))/(1.0_dp + abs(log(p0))/64.0_dp)) <= &
            & 5.0_dp*ln_tol, "Z_u off by "//format_real(maxval(abs(p1/p0 - 1.0_dp))))
         if (allocated(error)) return
         call check(error, maxval(abs(d1/d0 - 1.0_dp)) <= 5.0_dp*unload_slope_tol, &
            & "dZ_u/dh off by "//format_real(maxval(abs(d1/d0 - 1.0_dp))))
         if (allocated(error)) return
         ! another h_min (beyond the slack), and Delta beyond the range: the integral's
         hm = h_min + 1.0e-9_dp
         call unloading_pressure(plain, h, hm, p0, d0)
         call unloading_pressure(tabled, h, hm, p1, d1)
         call check(error, all(p1 == p0) .and. all(d1 == d0), "table used at another h_min")
         if (allocated(error)) return
         hm = h_min
         h = h_min + d_end + r
         call unloading_pressure(plain, h, hm, p0, d0)
         call unloading_pressure(tabled, h, hm, p1, d1)
         call check(error, all(p1 == p0) .and. all(d1 == d0), "table used beyond its range")
         if (allocated(error)) return
         ! from d_end + 1 on: 0, where the integral is below 1e-280 (p_floor)
         h = h_min + d_end + 1.0_dp + 30.0_dp*r
         call unloading_pressure(plain, h, hm, p0, d0)
         call unloading_pressure(tabled, h, hm, p1, d1)
         call check(error, all(p1 == 0.0_dp) .and. all(d1 == 0.0_dp) .and. &
            & all(p0 < 1.0e-280_dp), "beyond d_end + 1: not 0, or the integral above 1e-280")
         if (allocated(error)) return
      end do
      pieces = law_pieces()
      call tabulate_unloading(pieces, -3.7_dp)
      call check(error, pieces%unload%n == 0, "a table without a loading law")
   end subroutine test_unloading_table

   !> A prepared law given the tabulated loading law (zmc_law_pieces) answers as the law
   !> without it: the loading branch (h < h_min, and h = h_min's value) from the table, to
   !> the table's acceptance (p to 5 ln_tol (1 + |ln p|/64) relative, dp/dh to 5 slope_tol:
   !> test flat_law's factor for points between the checked ones), the unloading branch
   !> (h > h_min) bit-equal (the same integral); a table of other parameters is ignored
   !> (bit-equal everywhere). 3000 random (h, h_min) in [-30, 8]^2, psi 1 and 0.3.
   subroutine test_loading_table(error)
      use egw_law_pieces, only: law_pieces, zmc_law_pieces, ln_tol, slope_tol
      type(error_type), allocatable, intent(out) :: error
      integer, parameter :: n = 3000
      real(dp) :: h(n), hm(n), p0(n), d0(n), p1(n), d1(n), r(n), psi
      type(unloading_law) :: plain, tabled, other
      type(law_pieces) :: pieces
      integer :: i, k
      call random_seed(put=[(104729*i, i=1, 64)])
      do k = 1, 2
         psi = merge(1.0_dp, 0.3_dp, k == 1)
         pieces = zmc_law_pieces(psi, 0.6_dp, 54.0_dp)
         plain = unloading_law_of(psi, 0.6_dp, 54.0_dp)
         tabled = unloading_law_of(psi, 0.6_dp, 54.0_dp, pieces)
         other = unloading_law_of(psi, 0.6_dp, 40.0_dp, pieces)
         call random_number(r)
         h = -30.0_dp + 38.0_dp*r
         call random_number(r)
         hm = -30.0_dp + 38.0_dp*r
         hm(:50) = h(:50)   ! h = h_min
         call unloading_pressure(plain, h, hm, p0, d0)
         call unloading_pressure(tabled, h, hm, p1, d1)
         call check(error, all(pack(p1, h > hm) == pack(p0, h > hm)) .and. &
            & all(pack(d1, h > hm) == pack(d0, h > hm)), "unloading branch not the same")
         if (allocated(error)) return
         call check(error, maxval(abs(p1/p0 - 1.0_dp)/(1.0_dp + abs(log(p0))/64.0_dp), &
            & mask=h <= hm) <= 5.0_dp*ln_tol, "loading branch: p off by "// &
            & format_real(maxval(abs(p1/p0 - 1.0_dp), mask=h <= hm)))
         if (allocated(error)) return
         call check(error, maxval(abs(d1/d0 - 1.0_dp), mask=h < hm) <= 5.0_dp*slope_tol, &
            & "loading branch: dp/dh off by "//format_real(maxval(abs(d1/d0 - 1.0_dp), &
            & mask=h < hm)))
         if (allocated(error)) return
         call check(error, any(p1 /= p0 .and. h < hm), "the table was not used")
         if (allocated(error)) return
         call unloading_pressure(unloading_law_of(psi, 0.6_dp, 40.0_dp), h, hm, p0, d0)
         call unloading_pressure(other, h, hm, p1, d1)
         call check(error, all(p1 == p0) .and. all(d1 == d0), &
            & "a table of other parameters was used")
         if (allocated(error)) return
      end do
   end subroutine test_loading_table

   !> p_G,u = C sigma^(3/2) Z_u with C = mu E/(2 sigma sqrt(2R)); bad input gives a status
   !> naming the argument and leaves the outputs as they were.
   subroutine test_dimensional(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: p
      type(egw_error), allocatable :: err
      real(dp) :: pres, dpres, z, dz, c, nan
      p = contact_params(model=model_epgw, radius=2.0_dp, modulus=3.0_dp, sigma=0.01_dp, &
         & mu=4.0_dp, psi=2.0_dp, hardness_coeff=0.6_dp, plastic_ratio=54.0_dp)
      call flat_pressure_unload(p, 0.002_dp, -0.01_dp, pres, dpres, err)
      call check(error, .not. allocated(err), "valid call")
      if (allocated(error)) return
      call rough_flat_unload_law(0.2_dp, -1.0_dp, 2.0_dp, 0.6_dp, 54.0_dp, z, dz)
      c = 4.0_dp*3.0_dp/(2.0_dp*0.01_dp*sqrt(4.0_dp))
      call check(error, pres, c*0.01_dp**1.5_dp*z, "p = C sigma^1.5 Z_u", rel=.true., &
         & thr=1.0e-15_dp)
      if (allocated(error)) return
      call check(error, dpres, c*sqrt(0.01_dp)*dz, "dp/dd", rel=.true., thr=1.0e-15_dp)
      if (allocated(error)) return
      nan = ieee_nan()
      pres = 7.0_dp
      call flat_pressure_unload(p, nan, -0.01_dp, pres, dpres, err)
      call check(error, allocated(err) .and. pres == 7.0_dp, "NaN separation refused")
      if (allocated(error)) return
      call check(error, err%stat, egw_invalid_argument, "NaN separation: status")
      if (allocated(error)) return
      call check(error, index(err%message, "separation") == 1, "message names separation")
      if (allocated(error)) return
      call flat_pressure_unload(p, 0.0_dp, ieee_inf(), pres, dpres, err)
      call check(error, allocated(err) .and. index(err%message, "separation_min") == 1, &
         & "infinite separation_min refused")
      if (allocated(error)) return
      p%sigma = 0.0_dp
      call flat_pressure_unload(p, 0.0_dp, 0.0_dp, pres, dpres, err)
      call check(error, allocated(err), "sigma = 0 refused")
      if (allocated(error)) return
      call check(error, err%stat, egw_invalid_parameter, "sigma = 0: status")
      if (allocated(error)) return
      ! E-GW: elastic summits, the loading law
      p%sigma = 0.01_dp
      p%model = model_egw
      call flat_pressure_unload(p, 0.002_dp, -0.01_dp, pres, dpres, err)
      call rough_flat_law(0.2_dp, 0.0_dp, 0.6_dp, 54.0_dp, z, dz)
      call check(error, pres, c*0.01_dp**1.5_dp*z, "E-GW: loading law", rel=.true., &
         & thr=1.0e-15_dp)
   end subroutine test_dimensional

   real(dp) function ieee_inf()
      use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_positive_inf
      ieee_inf = ieee_value(1.0_dp, ieee_positive_inf)
   end function ieee_inf

   real(dp) function ieee_nan()
      use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
      ieee_nan = ieee_value(1.0_dp, ieee_quiet_nan)
   end function ieee_nan

end module test_unloading
