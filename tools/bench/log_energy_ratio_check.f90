! The O(1) energy of log-ratio hysteresis tables (E_load e^-eta, eta = ln(E_load/E)
! interpolated as h; src/egw/tables/unload_energy.f90 log_energy_ratio) against the walk
! (hysteresis_energy_walk: the integral of the force hysteresis_eval returns) at 1997
! turning points from the loading cut-off to delta_max and 12 overlaps each (from 1e-6 of
! the span above the cut-off to the turning point): the worst |E - E_walk| relative to
! E_m and to max(E_walk, 1e-3 E_m) (the force's local tolerance), below and above
! delta_min, and the delta_max intervals that take the walk (energy_walk). Tables: 1 psi
! 2, -2..6 sigma, 1e-3; 2 psi 1, 0..140 sigma, 1e-4 (LAMMPS's); 3 psi 1, 0..5 sigma, 1e-5;
! 4 psi 2, -3..30 sigma, 1e-4 (test hysteresis far_errors'); a second argument switches
! energy_walk off. Build (B: an fpm build directory with the .mod files, L: its libegw.a,
! A: the other libraries of that build):
!   gfortran -O2 -ffree-line-length-none -fopenmp -I$B log_energy_ratio_check.f90 $L $A \
!      -lfftw3_omp -lfftw3 -llapack -lblas -o check
program echeck
   use egw_kinds, only: dp
   use egw_params, only: contact_params, model_epgw
   use egw_rough_sphere, only: solver_options
   use egw_status, only: egw_error
   use egw_hysteresis, only: hysteresis_table, build_hysteresis, hysteresis_energy, hysteresis_energy_walk
   implicit none
   type(hysteresis_table) :: t
   integer :: jj
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
   print '(a,i0,a,i0,a,2f9.3)', 'walk intervals ', count(t%energy_walk), ' of ', size(t%energy_walk), ' range ', t%m(1), t%m(size(t%m))
   if (count(t%energy_walk) > 0) print '(a,f9.3)', ' highest walked m ', t%m(maxval(findloc(t%energy_walk, .true., back=.true.)))
   do jj = 1, size(t%energy_walk)
      if (t%energy_walk(jj)) print '(a,2f10.4)', '  walked ', t%m(jj), t%m(jj+1)
   end do
   if (command_argument_count() > 1) t%energy_walk = .false.
   call sweep(t, rel_tol, -huge(1.0_dp), dmin)
   call sweep(t, rel_tol, dmin, huge(1.0_dp))
contains
   subroutine sweep(t, rel_tol, lo, hi)
      type(hysteresis_table), intent(in) :: t
      real(dp), intent(in) :: rel_tol, lo, hi
      real(dp) :: m, e_m, wm, wl, wlm, wlx, x, e, e_w, wmm, wlmm
      integer :: i, j, stat
      real(dp), parameter :: fracs(12) = [1e-6_dp, 1e-4_dp, 1e-3_dp, 1e-2_dp, 0.05_dp, 0.1_dp, 0.3_dp, 0.5_dp, 0.7_dp, 0.9_dp, 0.99_dp, 1.0_dp]
      wm = 0; wl = 0; wmm = 0; wlm = 0; wlx = 0; wlmm = 0
      do i = 1, 1997
         m = t%loading%cutoff + (t%m(size(t%m)) - t%loading%cutoff)*modulo(0.381966_dp*i, 1.0_dp)
         if (.not. m > t%elastic_limit .or. m < lo .or. m > hi) cycle
         call hysteresis_energy_walk(t, m, m, e_m, stat)
         if (.not. e_m > 0) cycle
         do j = 1, size(fracs)
            x = t%loading%cutoff + fracs(j)*(m - t%loading%cutoff)
            call hysteresis_energy_walk(t, x, m, e_w, stat)
            call hysteresis_energy(t, x, m, e, stat)
            if (abs(e - e_w)/e_m > wm) then
               wm = abs(e - e_w)/e_m; wmm = m
            end if
            if (e_w > 0) then
            if (abs(e - e_w)/max(e_w, 1e-3_dp*e_m) > wl) then
               wl = abs(e - e_w)/max(e_w, 1e-3_dp*e_m); wlm = m; wlx = x
            end if
            if (abs(e - e_w)/e_w > wlmm) wlmm = abs(e - e_w)/e_w
            end if
         end do
      end do
      print '(2f8.2)', max(lo,-99.0_dp), min(hi,999.0_dp)
      print '(a,es9.2,a,i0,a,i0,a,f8.3,a,es9.2,a,es9.2,a,es9.2,a,es9.2,a,es9.2)', 'rel_tol ', rel_tol, ' nodes ', size(t%m), &
         & ' x ', size(t%s), ' cutoff ', t%loading%cutoff, ': max |E-E_walk|/E_m ', wm, ' at m ', wmm, &
         & '; /max(E,1e-3E_m) ', wl, ' at m ', wlm, ' x ', wlx
      print '(a,es9.2)', '  max |E-E_walk|/E_walk (any E) ', wlmm
   end subroutine sweep
end program echeck
