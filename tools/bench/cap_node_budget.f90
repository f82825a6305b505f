!> Stop 53 (doubt19): which Hertz + cap hysteresis tables reach their tolerance within the
!> build's delta_max node limit. R = E* = 1, p_y = 2/pi (delta_y = 1; the cap model is
!> universal in delta/delta_y), a table over [-0.8567, TOP] delta_y at TOL: its delta_max
!> nodes, the s nodes of its longest curve, max_error, the smallest delta_max interval and
!> where the grid is densest, the build's CPU time; or the build's message.
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/cap_node_budget.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/cap_node_budget
!>   OMP_NUM_THREADS=1 EGW_CACHE_DIR=off /tmp/cap_node_budget TOL TOP
program cap_node_budget
   use egw_all
   implicit none
   type(contact_params) :: p
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   real(dp) :: tol, topm, t0, t1, dm
   integer :: j, jmin, nbelow(4)
   character(len=32) :: arg
   call get_command_argument(1, arg); read (arg, *) tol
   call get_command_argument(2, arg); read (arg, *) topm
   p = contact_params(model=model_hertz, radius=1.0_dp, modulus=1.0_dp, &
      & flow_pressure=2/acos(-1.0_dp))
   call cpu_time(t0)
   call build_hysteresis(p, solver_options(n_threads=1), -0.8567_dp, topm, tol, t, err)
   call cpu_time(t1)
   if (allocated(err)) then
      print '(a,es9.2,a,f8.1,a,f8.2,a,a)', 'tol ', tol, ' top ', topm, ' cpu ', t1 - t0, &
         & ' s FAILED: ', err%message
      stop
   end if
   jmin = 1
   do j = 1, size(t%m) - 1
      if (t%m(j + 1) - t%m(j) < t%m(jmin + 1) - t%m(jmin)) jmin = j
   end do
   dm = t%m(jmin + 1) - t%m(jmin)
   ! nodes in (1, 1.01], (1.01, 1.1], (1.1, 2], above 2 delta_y
   nbelow(1) = count(t%m > 1.0_dp .and. t%m <= 1.01_dp)
   nbelow(2) = count(t%m > 1.01_dp .and. t%m <= 1.1_dp)
   nbelow(3) = count(t%m > 1.1_dp .and. t%m <= 2.0_dp)
   nbelow(4) = count(t%m > 2.0_dp)
   print '(a,es9.2,a,f8.1,a,f8.2,a,i4,a,es10.3,a,es10.3,a,es12.5,a,4i4)', 'tol ', tol, &
      & ' top ', topm, ' cpu ', t1 - t0, ' s m nodes ', size(t%m), ' max_error ', &
      & t%max_error, ' min dm/range ', dm/(t%m(size(t%m)) - t%m(1)), ' at m ', t%m(jmin), &
      & ' in (1,1.01],(1.01,1.1],(1.1,2],>2: ', nbelow
end program cap_node_budget
