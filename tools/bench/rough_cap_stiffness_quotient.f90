!> Stop 52 (doubt18): the rough + cap loading stiffness against central difference quotients
!> of forces. E-GW + cap, sigma = 1, R = 1/RATIO, E* = 1, p_y = 2/pi (delta_y = R, sigma/delta_y
!> = RATIO), mu 4; at 3, 6, 10 delta_y the solve's stiffness at rel_tol 1e-6, 1e-7, 1e-8
!> against (P(delta (1 + H)) - P(delta (1 - H)))/(2 H delta), the forces at RTOL.
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/rough_cap_stiffness_quotient.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/rough_cap_stiffness_quotient
!>   OMP_NUM_THREADS=1 /tmp/rough_cap_stiffness_quotient RATIO RTOL H    (e.g. 1e-2 1e-9 1e-4)
program rough_cap_stiffness_quotient
   use egw_all
   implicit none
   type(contact_params) :: p
   type(egw_error), allocatable :: err
   type(solve_result) :: r0, rp, rm
   real(dp) :: ratio, d, h, rtol, q
   real(dp), parameter :: ds(3) = [3.0_dp, 6.0_dp, 10.0_dp], tols(3) = [1e-6_dp, 1e-7_dp, &
      & 1e-8_dp]
   integer :: i, k
   character(len=32) :: arg
   call get_command_argument(1, arg); read (arg, *) ratio
   call get_command_argument(2, arg); read (arg, *) rtol
   call get_command_argument(3, arg); read (arg, *) h
   p = contact_params(model=model_egw, radius=1.0_dp/ratio, modulus=1.0_dp, sigma=1.0_dp, &
      & mu=4.0_dp, flow_pressure=2/acos(-1.0_dp))
   do i = 1, size(ds)
      d = ds(i)*p%radius
      call solve_contact(p, solver_options(rel_tol=rtol, n_threads=1), d*(1 + h), rp, err)
      if (allocated(err)) then
         print '(a)', 'reference + '//err%message
         cycle
      end if
      call solve_contact(p, solver_options(rel_tol=rtol, n_threads=1), d*(1 - h), rm, err)
      if (allocated(err)) then
         print '(a)', 'reference - '//err%message
         cycle
      end if
      q = (rp%force - rm%force)/(2*h*d)
      do k = 1, size(tols)
         call solve_contact(p, solver_options(rel_tol=tols(k), n_threads=1), d, r0, err)
         if (allocated(err)) then
            print '(es10.2,1x,a)', tols(k), err%message
            cycle
         end if
         print '(f6.1,es10.2,3es20.12,es11.3)', ds(i), tols(k), r0%force, r0%stiffness, q, &
            & r0%stiffness/q - 1
      end do
   end do
end program rough_cap_stiffness_quotient
