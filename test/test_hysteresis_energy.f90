!> Tests of hysteresis_energy: the energy against an independent quadrature of the force
!> hysteresis_eval returns, and against hysteresis_energy_walk, on EP-GW tables built at
!> rel_tol 1e-3, 1e-4 and 1e-5 and read back from both formats. EP-GW tables store
!> ln(P_load/P): their energy is E_load e^-eta with eta = ln(E_load/E) interpolated as h
!> (log_energy_prepare; the walk, a Gauss-Legendre sum per piece, is the reference); the
!> sampled dips (energy_prepare) belong to the gap tables where the cap acts (suites
!> cap_hysteresis, rough_cap_hysteresis).
module test_hysteresis_energy
   use egw_kinds, only: dp
   use egw_status, only: egw_error, format_real
   use egw_params, only: contact_params, model_epgw
   use egw_rough_sphere, only: solver_options
   use egw_hysteresis, only: hysteresis_table, build_hysteresis, hysteresis_eval, &
      & hysteresis_energy, hysteresis_energy_walk
   use egw_hysteresis_format, only: write_hysteresis, read_hysteresis
   use egw_table_format, only: format_csv, format_binary
   use testdrive, only: new_unittest, unittest_type, error_type, check, test_failed
   implicit none
   private
   public :: collect_hysteresis_energy

   !> Overlaps per unloading curve, from the cut-off to the turning point.
   integer, parameter :: n_ends = 9

contains

   subroutine collect_hysteresis_energy(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("LAMMPS's EP-GW table (1e-4): energy = quadrature of the force", &
         & test_lammps_table), &
         & new_unittest("EP-GW psi = 2 at 1e-3: energy = quadrature of the force", &
         & test_coarse), &
         & new_unittest("EP-GW at 1e-5: energy = quadrature of the force", test_fine), &
         & new_unittest("tables read back (CSV, binary): the same energies", test_read_back) &
         & ]
   end subroutine collect_hysteresis_energy

   !> The normalised table LAMMPS builds for in.pour.heat's EP-GW grains (R = E* = sigma =
   !> 1, mu = 4, psi = 1, delta_max to 140 sigma, rel_tol 1e-4), whose unloading curves
   !> dip below 0 from the cut-off up to the residual overlap at most turning points.
   subroutine test_lammps_table(error)
      type(error_type), allocatable, intent(out) :: error
      type(hysteresis_table) :: t
      type(hysteresis_table) :: back
      type(egw_error), allocatable :: err
      call build(contact_params(model=model_epgw, radius=1.0_dp, modulus=1.0_dp, &
         & sigma=1.0_dp, mu=4.0_dp, psi=1.0_dp), 0.0_dp, 140.0_dp, 1.0e-4_dp, t, error)
      if (allocated(error)) return
      call check_table(t, error)
      if (allocated(error)) return
      ! the file the plugin sends between ranks reads back (its log ratios below the
      ! cut-off reach below 0: the reader's bound once refused LAMMPS's pour tables)
      call write_hysteresis(t, "build/hyst_lammps.bin", format_binary, err)
      if (.not. allocated(err)) call read_hysteresis("build/hyst_lammps.bin", back, err)
      if (allocated(err)) call test_failed(error, "write/read: "//err%message)
   end subroutine test_lammps_table

   !> test_hysteresis's EP-GW contact (psi = 2, mu = 4) at 1e-3 over [-2, 6] sigma.
   subroutine test_coarse(error)
      type(error_type), allocatable, intent(out) :: error
      type(hysteresis_table) :: t
      call build(contact_params(model=model_epgw, radius=1.0_dp, modulus=1.0_dp, &
         & sigma=1.0_dp, mu=4.0_dp, psi=2.0_dp), -2.0_dp, 6.0_dp, 1.0e-3_dp, t, error)
      if (allocated(error)) return
      call check_table(t, error)
   end subroutine test_coarse

   !> mu = 4, psi = 1 at 1e-5 over [0, 5] sigma (the finest tolerance LAMMPS decks use).
   subroutine test_fine(error)
      type(error_type), allocatable, intent(out) :: error
      type(hysteresis_table) :: t
      call build(contact_params(model=model_epgw, radius=1.0_dp, modulus=1.0_dp, &
         & sigma=1.0_dp, mu=4.0_dp, psi=1.0_dp), 0.0_dp, 5.0_dp, 1.0e-5_dp, t, error)
      if (allocated(error)) return
      call check_table(t, error)
   end subroutine test_fine

   !> A table written and read back (CSV and binary) samples its dips again from the
   !> stored data: its energies equal the built table's (bit for bit where the stored
   !> data are: both formats keep every double; 200 points across the table).
   subroutine test_read_back(error)
      type(error_type), allocatable, intent(out) :: error
      type(hysteresis_table) :: t, back
      type(egw_error), allocatable :: err
      character(len=*), parameter :: names(2) = ["build/hyst_energy.csv", &
         & "build/hyst_energy.bin"]
      integer :: formats(2), i, it, stat, stat2
      real(dp) :: d, m, u, u2
      call build(contact_params(model=model_epgw, radius=1.0_dp, modulus=1.0_dp, &
         & sigma=1.0_dp, mu=4.0_dp, psi=2.0_dp), -2.0_dp, 6.0_dp, 1.0e-3_dp, t, error)
      if (allocated(error)) return
      formats = [format_csv, format_binary]
      do it = 1, 2
         call write_hysteresis(t, names(it), formats(it), err)
         if (.not. allocated(err)) call read_hysteresis(names(it), back, err)
         if (allocated(err)) then
            call test_failed(error, names(it)//": "//err%message)
            return
         end if
         do i = 1, 200
            m = -2.0_dp + 8.0_dp*modulo(0.618034_dp*i, 1.0_dp)
            d = m - (m - t%loading%cutoff)*modulo(0.7548777_dp*i, 1.0_dp)
            call hysteresis_energy(t, d, m, u, stat)
            call hysteresis_energy(back, d, m, u2, stat2)
            if (u /= u2 .or. stat /= stat2) then
               call test_failed(error, names(it)//": read-back energy "//format_real(u2)// &
                  & " differs from "//format_real(u)//" at delta = "//format_real(d)// &
                  & ", delta_max_state "//format_real(m))
               return
            end if
         end do
      end do
   end subroutine test_read_back

   subroutine build(params, delta_min, delta_max, rel_tol, table, error)
      type(contact_params), intent(in) :: params
      real(dp), intent(in) :: delta_min, delta_max, rel_tol
      type(hysteresis_table), intent(out) :: table
      type(error_type), allocatable, intent(out) :: error
      type(egw_error), allocatable :: err
      call build_hysteresis(params, solver_options(), delta_min, delta_max, rel_tol, table, err)
      if (allocated(err)) call test_failed(error, "build: "//err%message)
   end subroutine build

   !> At 14 turning points (m nodes, midpoints between nodes, points in between; 7 from
   !> the lower half of the table, where dips come and go with m, and 7 from the upper)
   !> and n_ends overlaps on each unloading curve (the cut-off region, the dips, the
   !> top of the dips where the force first leaves 0 and just above it, up the curve and
   !> the turning point itself), hysteresis_energy against
   !> - the force that hysteresis_eval returns integrated from the cut-off by 3-point
   !>   Gauss-Legendre on 60000 panels (cumulative along the curve): that force is smooth
   !>   between the table's breaks and kinks where it is clipped at 0; each kink costs the
   !>   rule ~h^2 times the slope jump, so the quadrature is good to ~1e-9 of the energy
   !>   at the turning point E_m (the walk below meets it to 2.8e-12); 2e-7 E_m is
   !>   allowed for the sampled dips (linear in m between 17 samples per delta_max
   !>   interval: measured 3e-10, 4.1e-8 and 6.5e-9 E_m on the 1e-4, 1e-3 and 1e-5
   !>   tables; the dips left out, as an integral of the unclipped curve, miss by 6.6e-6,
   !>   4.3e-5 and 8.6e-7 E_m: each test then fails);
   !> - hysteresis_energy_walk (the walk over the span, exact but for its root
   !>   finding): the same 2e-7 E_m, and the walk against the quadrature to 1e-10 E_m.
   !> Log-ratio tables (EP-GW: all of this suite's): the walk against the quadrature to
   !> 1e-10 E_m as above; hysteresis_energy (eta interpolated) against the quadrature to
   !> rel_tol of max(E, 1e-3 E_m), the force's own local tolerance (the table's force is
   !> within rel_tol of the solves' down to 1e-3 P(m), so its energy can claim no more):
   !> measured (tools/bench/log_energy_ratio_check.f90: 1997 turning points from the
   !> cut-off to delta_max, 12 overlaps each, against the walk) 0.19, 0.26 and 0.39 rel_tol
   !> on the 1e-3, 1e-4 and 1e-5 tables. Without the walks near the cut-off (eta's layer
   !> there, energy_cut and energy_walk) the 1e-3 table errs by 0.38 of max(E, 1e-3 E_m)
   !> at m = -6.3 sigma (380 rel_tol), and
   !> the node curves' integrals combined as the curves (local10's proposal) by 0.1-0.3
   !> rel_tol of E_m inside and 0.5-1 E_m below delta_min.
   subroutine check_table(t, error)
      type(hysteresis_table), intent(in) :: t
      type(error_type), allocatable, intent(out) :: error
      real(dp) :: ms(14), ends(n_ends), quad(n_ends), u, u_walk, e_m, top, bound
      integer :: i, j, stat, jm
      do i = 1, 7
         jm = 1 + (size(t%m) - 1)*i/16
         ms(i) = t%m(jm) + modulo(0.381966_dp*i, 1.0_dp)*(t%m(jm + 1) - t%m(jm))
         jm = 1 + (size(t%m) - 1)*(7 + i)/16
         ms(7 + i) = t%m(jm)
         if (mod(i, 2) == 0) ms(7 + i) = 0.5_dp*(t%m(jm) + t%m(jm + 1))
      end do
      do i = 1, size(ms)
         if (.not. ms(i) > t%elastic_limit) cycle
         top = dip_top(t, ms(i))
         ends = [t%loading%cutoff + 1.0e-3_dp*(ms(i) - t%loading%cutoff), &
            & t%loading%cutoff + 0.5_dp*(top - t%loading%cutoff), top, &
            & top + 1.0e-3_dp*(ms(i) - top), top + 1.0e-2_dp*(ms(i) - top), &
            & top + 0.1_dp*(ms(i) - top), top + 0.5_dp*(ms(i) - top), &
            & top + 0.9_dp*(ms(i) - top), ms(i)]
         call quadrature(t, ms(i), ends, quad)
         call hysteresis_energy(t, ms(i), ms(i), e_m, stat)
         do j = 1, n_ends
            call hysteresis_energy(t, ends(j), ms(i), u, stat)
            call hysteresis_energy_walk(t, ends(j), ms(i), u_walk, stat)
            if (t%log_ratio) then
               bound = t%rel_tol*max(quad(j), 1.0e-3_dp*e_m)
            else
               bound = 2.0e-7_dp*e_m
            end if
            call check(error, abs(u - quad(j)) <= bound .and. &
               & abs(u - u_walk) <= bound .and. abs(u_walk - quad(j)) <= &
               & 1.0e-10_dp*e_m, "turning point "//format_real(ms(i))//", delta "// &
               & format_real(ends(j))//": energy "//format_real(u)//", walk "// &
               & format_real(u_walk)//", quadrature of the force "//format_real(quad(j))// &
               & " (energy at the turning point "//format_real(e_m)//")")
            if (allocated(error)) return
         end do
      end do
   end subroutine check_table

   !> The largest overlap on m's unloading curve (1000 steps from the cut-off) where the
   !> force is still 0: the top of its dips (the cut-off where there are none).
   real(dp) function dip_top(t, m) result(top)
      type(hysteresis_table), intent(in) :: t
      real(dp), intent(in) :: m
      real(dp) :: x, state, f, k
      integer :: i, stat
      top = t%loading%cutoff
      do i = 1, 999
         x = t%loading%cutoff + (m - t%loading%cutoff)*i/1000.0_dp
         state = m
         call hysteresis_eval(t, x, state, f, k, stat)
         if (f == 0.0_dp) top = x
      end do
   end function dip_top

   !> int_{cut-off}^{ends(j)} of the force hysteresis_eval returns below turning point m,
   !> for increasing ends: 3-point Gauss-Legendre on panels as equal as the ends allow
   !> (60000 from the cut-off to m).
   subroutine quadrature(t, m, ends, total)
      type(hysteresis_table), intent(in) :: t
      real(dp), intent(in) :: m, ends(:)
      real(dp), intent(out) :: total(:)
      real(dp), parameter :: node(3) = [-sqrt(0.6_dp), 0.0_dp, sqrt(0.6_dp)], &
         & weight(3) = [5.0_dp, 8.0_dp, 5.0_dp]/9.0_dp
      real(dp) :: a, b, h, c, x, state, f, k, sum
      integer :: j, n, p, q, stat
      sum = 0.0_dp
      a = t%loading%cutoff
      do j = 1, size(ends)
         b = ends(j)
         n = max(1, nint(60000*(b - a)/(m - t%loading%cutoff)))
         h = (b - a)/n
         do p = 1, n
            c = a + (p - 0.5_dp)*h
            do q = 1, 3
               x = c + 0.5_dp*h*node(q)
               state = m
               call hysteresis_eval(t, x, state, f, k, stat)
               sum = sum + 0.5_dp*h*weight(q)*f
            end do
         end do
         total(j) = sum
         a = b
      end do
   end subroutine quadrature

end module test_hysteresis_energy
