!> Stop 57 (stiff23): reference loading stiffnesses of E-GW + cap for
!> test/data/rough_cap_stiffness_reference.csv (test_rough_cap's "stiffness at the nine
!> points"): fourth-order central quotients of forces solved at RTOL,
!>   K = (8 (P(d(1+h)) - P(d(1-h))) - (P(d(1+2h)) - P(d(1-2h))))/(12 h d),
!> at h = H1 and H2 (the data's two columns: their difference bounds the quotients' error;
!> the forces' errors enter as ~1.5 eps P/(h d K), the truncation as h**4 d**4 P^(5)/(30 K)).
!> sigma = 1, R = 1/RATIO, E* = 1, p_y = 2/pi (delta_y = R, sigma/delta_y = RATIO), mu 4;
!> X in delta_y. Forces never come from the stiffness path (solve_result%force only).
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/rough_cap_stiffness_reference.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/kref
!>   OMP_NUM_THREADS=1 /tmp/kref RATIO RTOL H1 H2 X...   (e.g. 1e-4 1e-8 1e-2 3e-3 1.5 10 20)
!> prints one CSV row per X: ratio,x,K(H1),K(H2),largest est_rel_err of the forces.
program rough_cap_stiffness_reference
   use egw_all
   implicit none
   type(contact_params) :: p
   type(egw_error), allocatable :: err
   type(solve_result) :: r
   real(dp) :: ratio, rtol, hs(2), x, d, f(-2:2), q(2), worst
   character(len=32) :: arg
   integer :: i, j, k
   logical :: failed
   call get_command_argument(1, arg); read (arg, *) ratio
   call get_command_argument(2, arg); read (arg, *) rtol
   call get_command_argument(3, arg); read (arg, *) hs(1)
   call get_command_argument(4, arg); read (arg, *) hs(2)
   p = contact_params(model=model_egw, radius=1.0_dp/ratio, modulus=1.0_dp, sigma=1.0_dp, &
      & mu=4.0_dp, flow_pressure=2/acos(-1.0_dp))
   do i = 5, command_argument_count()
      call get_command_argument(i, arg); read (arg, *) x
      d = x*p%radius
      worst = 0
      failed = .false.
      do k = 1, 2
         do j = -2, 2
            if (j == 0) cycle
            call solve_contact(p, solver_options(rel_tol=rtol, n_threads=1), &
               & d*(1 + j*hs(k)), r, err)
            if (allocated(err)) then
               print '(a)', '# x = '//trim(arg)//': '//err%message
               failed = .true.
               exit
            end if
            f(j) = r%force
            worst = max(worst, r%est_rel_err)
         end do
         if (failed) exit
         q(k) = (8*(f(1) - f(-1)) - (f(2) - f(-2)))/(12*hs(k)*d)
      end do
      if (failed) cycle
      print '(es8.1,",",f5.1,",",es23.16,",",es23.16,",",es9.2)', ratio, x, q, worst
   end do
end program rough_cap_stiffness_reference
