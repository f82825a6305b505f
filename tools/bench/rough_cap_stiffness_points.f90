!> Stop 55 (dcap21): the rough + cap loading stiffness at chosen points against central
!> quotients of rel_tol 1e-8 forces, in two runs (the references change only with the
!> forces, which stay bit-identical across the stiffness's changes). E-GW + cap, sigma = 1,
!> R = 1/RATIO, E* = 1, p_y = 2/pi (delta_y = R, sigma/delta_y = RATIO), mu 4; X in delta_y.
!>   ref: (P(delta (1 + 1e-3)) - P(delta (1 - 1e-3)))/(2e-3 delta), the forces at rel_tol 1e-8
!>   k:   the force and stiffness at rel_tol 1e-6, implicit_stiffness, CPU seconds
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/rough_cap_stiffness_points.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/kq
!>   OMP_NUM_THREADS=1 /tmp/kq RATIO ref X...  >  ref_RATIO.txt
!>   OMP_NUM_THREADS=1 /tmp/kq RATIO k X...     (stiffness / ref's quotient - 1 by hand)
program rough_cap_stiffness_points
   use egw_all
   implicit none
   type(contact_params) :: p
   type(egw_error), allocatable :: err
   type(solve_result) :: r0, rp, rm
   real(dp) :: ratio, d, x, q, t0, t1
   real(dp), parameter :: h = 1e-3_dp
   character(len=32) :: arg, mode
   integer :: i
   call get_command_argument(1, arg); read (arg, *) ratio
   call get_command_argument(2, mode)
   p = contact_params(model=model_egw, radius=1.0_dp/ratio, modulus=1.0_dp, sigma=1.0_dp, &
      & mu=4.0_dp, flow_pressure=2/acos(-1.0_dp))
   do i = 3, command_argument_count()
      call get_command_argument(i, arg); read (arg, *) x
      d = x*p%radius
      if (mode == 'ref') then
         call solve_contact(p, solver_options(rel_tol=1e-8_dp, n_threads=1), d*(1 + h), rp, &
            & err)
         if (.not. allocated(err)) call solve_contact(p, solver_options(rel_tol=1e-8_dp, &
            & n_threads=1), d*(1 - h), rm, err)
         if (allocated(err)) then
            print '(a)', err%message; cycle
         end if
         q = (rp%force - rm%force)/(2*h*d)
         print '(es10.2,f6.1,es24.16)', ratio, x, q
      else
         call cpu_time(t0)
         call solve_contact(p, solver_options(rel_tol=1e-6_dp, n_threads=1), d, r0, err)
         call cpu_time(t1)
         if (allocated(err)) then
            print '(a)', err%message; cycle
         end if
         print '(es10.2,f6.1,2es24.16,l2,f8.3)', ratio, x, r0%force, r0%stiffness, &
            & r0%implicit_stiffness, t1 - t0
      end if
   end do
end program rough_cap_stiffness_points
