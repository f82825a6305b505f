! The O(1) energy proposed for log-ratio hysteresis tables (issue 33 item 5, task local10
! step 1), measured before it is built: each node curve's force integrated over s on its own
! edge map, phi_k(s) = P_k(s)/P_load(m_k), combined with the stencil's weights as the
! curves are, F(s; m) ~ P_load(m) sum_k w_k phi_k(s), times m's own dxi/ds per edge
! segment (here integrated by 8-point Gauss-Legendre on 400 panels per segment: the stored
! integrals' exact values), against hysteresis_energy_walk (the integral of the force
! hysteresis_eval returns). Prints the worst |E_comb - E_walk|/E_m over 997 turning points
! in [delta_min, delta_max] and 9 overlaps each, for the tables of test
! hysteresis_energy (1: psi 2, -2..6 sigma, 1e-3; 2: psi 1, 0..140 sigma, 1e-4; 3: psi 1,
! 0..5 sigma, 1e-5); 4 prints the nodes of test hysteresis far_errors' 1e-4 table over
! [-3, 30] sigma. Build (B: an fpm build directory with the .mod files, L: its libegw.a,
! A: the other libraries of that build):
!   gfortran -O2 -ffree-line-length-none -fopenmp -I$B log_energy_combination.f90 $L $A \
!      -lfftw3_omp -lfftw3 -llapack -lblas -o comb
program energy_interp
   use egw_kinds, only: dp
   use egw_params, only: contact_params, model_epgw
   use egw_rough_sphere, only: solver_options
   use egw_status, only: egw_error
   use egw_hysteresis, only: hysteresis_table, build_hysteresis, hysteresis_energy_walk
   use egw_hysteresis_data, only: turning_point, edge_breaks, edge_s, edge_xi, log_unload
   use egw_table, only: table_eval, table_energy, gl_x, gl_w
   implicit none
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   character(len=32) :: arg
   real(dp) :: rel_tol, dmin, dmax, psi
   integer :: which
   call get_command_argument(1, arg); read (arg, *) which
   select case (which)
   case (1); psi = 2; dmin = -2; dmax = 6; rel_tol = 1e-3_dp
   case (2); psi = 1; dmin = 0; dmax = 140; rel_tol = 1e-4_dp
   case (4); psi = 2; dmin = -3; dmax = 30; rel_tol = 1e-4_dp
   case default; psi = 1; dmin = 0; dmax = 5; rel_tol = 1e-5_dp
   end select
   call build_hysteresis(contact_params(model=model_epgw, radius=1.0_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, psi=psi), solver_options(), dmin, dmax, rel_tol, t, err)
   if (allocated(err)) error stop 1
   if (which == 4) then
      print '(a,i0,a,i0)', 'nodes ', size(t%m), ' x ', size(t%s)
      print '(8f10.5)', t%m
      stop
   end if
   call sweep(t, rel_tol, dmin)
contains
   subroutine sweep(t, rel_tol, dmin)
      type(hysteresis_table), intent(in) :: t
      real(dp), intent(in) :: rel_tol, dmin
      real(dp) :: m, e_m, worst, worst_m, x, frac, e, e_w, lo
      integer :: i, j, stat
      real(dp), parameter :: fracs(9) = [1e-3_dp, 1e-2_dp, 0.05_dp, 0.1_dp, 0.3_dp, 0.5_dp, 0.7_dp, 0.9_dp, 1.0_dp]
      worst = 0; worst_m = 0
      do i = 1, 997
         m = t%m(1) + (t%m(size(t%m)) - t%m(1))*modulo(0.381966_dp*i, 1.0_dp)
         if (.not. m > t%elastic_limit .or. .not. m > t%loading%cutoff .or. m < dmin) cycle
         call hysteresis_energy_walk(t, m, m, e_m, stat)
         if (.not. e_m > 0) cycle
         do j = 1, 9
            frac = fracs(j)
            x = t%loading%cutoff + frac*(m - t%loading%cutoff)
            call hysteresis_energy_walk(t, x, m, e_w, stat)
            e = approx(t, m, x)
            if (abs(e - e_w)/e_m > worst) then
               worst = abs(e - e_w)/e_m; worst_m = m
            end if
         end do
      end do
      print '(a,es9.2,a,i0,a,i0,a,es9.2,a,es10.3)', 'rel_tol ', rel_tol, ' nodes ', size(t%m), &
         & ' x ', size(t%s), ': max |E_interp - E_walk|/E_m = ', worst, ' at m = ', worst_m
   end subroutine sweep

   real(dp) function approx(t, m, x) result(e)
      type(hysteresis_table), intent(in) :: t
      real(dp), intent(in) :: m, x
      integer :: first, k, fk, seg, p, q, np
      real(dp) :: w(4), inv, f_m, knee, xi_b(3), ratio, lo, s_d, s_lo, a, b, d(3)
      real(dp) :: wk(4), invk(4), fmk(4), kneek, lk(4), xib_k(3, 4), pl(4), sq, phi, xi, f, st, pm, sl
      real(dp) :: bounds(0:3)
      call turning_point(t, m, first, w, inv, f_m, knee)
      call edge_breaks(1/inv, t%params%sigma, xi_b)
      d = [2*xi_b(1), 4*(xi_b(2) - xi_b(1)), 4*(xi_b(3) - xi_b(2))]
      ratio = exp(-dot_product(w, t%gap(size(t%s), first:first + 3)))
      lo = max(m - xi_b(3), t%loading%cutoff)
      if (.not. x > m - xi_b(3)) then
         e = ratio*table_energy(t%loading, x); return
      end if
      e = ratio*table_energy(t%loading, lo)
      do k = 1, 4
         call turning_point(t, t%m(first + k - 1), fk, wk, invk(k), fmk(k), kneek)
         call edge_breaks(1/invk(k), t%params%sigma, xib_k(:, k))
         call table_eval(t%loading, t%m(first + k - 1), pl(k), st)
      end do
      call table_eval(t%loading, m, pm, st)
      call edge_s(xi_b, m - x, s_d, sl); s_d = min(s_d, 1.0_dp)
      call edge_s(xi_b, m - lo, s_lo, sl); s_lo = min(s_lo, 1.0_dp)
      bounds = [0.0_dp, 0.5_dp, 0.75_dp, 1.0_dp]
      np = 400
      do seg = 1, 3
         a = max(bounds(seg - 1), s_d); b = min(bounds(seg), s_lo)
         if (.not. b > a) cycle
         do p = 1, np
            do q = 1, 8
               sq = a + (b - a)*(p - 1 + gl_x(q))/np
               phi = 0
               do k = 1, 4
                  call edge_xi(xib_k(:, k), sq, xi)
                  if (t%m(first + k - 1) - xi > t%loading%cutoff) then
                     call log_unload(t, first, unit(k), 1/invk(k), t%m(first + k - 1), &
                        & t%m(first + k - 1) - xi, f, st)
                  else
                     f = 0
                  end if
                  phi = phi + w(k)*f/pl(k)
               end do
               e = e + pm*phi*d(seg)*gl_w(q)*(b - a)/np
            end do
         end do
      end do
   end function approx

   function unit(k) result(u)
      integer, intent(in) :: k
      real(dp) :: u(4)
      u = 0; u(k) = 1
   end function unit
end program energy_interp
