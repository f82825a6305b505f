! Unloading solves of the rough + cap tables of doc/benchmarks.md "Stop 44: rough + cap
! builds" at fixed (delta_max, delta): R = 405284.73 (the scene's radius 810569.47 halved),
! E* = 1, sigma = 1, mu = 4, p_y = 0.01 (delta_y = 100), E-GW (or EP-GW, psi 1, with the
! argument epgw), rel_tol 1e-5 (the 1e-4 table's curves), turning points 1.1 .. 5.9
! delta_y, 30 overlaps each down to 0.25 delta_max, in order (as a table's curve).
! Prints delta_max, delta, force, estimate, loading force; built against two libraries
! (main's and a branch's) the outputs are compared by unload_solves_compare.py.
! -DWARM: the solves of a history share an unload_start (stop 44's API; not in libraries
! before it). Build (B: an fpm build directory with the .mod files, L: its libegw.a):
!   gfortran -O2 -cpp [-DWARM] -fopenmp -I$B unload_solves_compare.f90 $L \
!      -llapack -lblas -lfftw3_omp -lfftw3 -o compare
program drv
   use egw_kinds, only: dp
   use egw_params, only: contact_params, model_egw, model_epgw
   use egw_status, only: egw_error
   use egw_rough_sphere
   implicit none
   type(contact_params) :: p
   type(solver_options) :: opt
   type(loading_history) :: h
   type(solve_result) :: res, top
   type(egw_error), allocatable :: err
#ifdef WARM
   type(unload_start) :: st
#endif
   real(dp) :: ms(5) = [110.0_dp, 180.0_dp, 300.0_dp, 450.0_dp, 590.0_dp], m, d
   integer :: i, k, model
   character(len=8) :: arg
   call get_command_argument(1, arg)
   p%radius = 810569.469138702_dp/2
   p%modulus = 1
   p%sigma = 1
   p%mu = 4
   p%flow_pressure = 0.01_dp
   p%model = model_egw
   if (arg == "epgw") then
      p%model = model_epgw
      p%psi = 1
   end if
   opt%rel_tol = 1.0e-5_dp
   opt%n_threads = 1
   do k = 1, size(ms)
      m = ms(k)
      call load_history(p, opt, m, h, top, err)
      if (allocated(err)) then
         print *, "load failed ", trim(err%message)
         stop 1
      end if
      do i = 1, 30
         d = m - real(i, dp)/31.0_dp*(0.75_dp*m)
#ifdef WARM
         call solve_unload(h, d, res, err, st)
#else
         call solve_unload(h, d, res, err)
#endif
         if (allocated(err)) then
            print '(a,2es24.16,a)', "FAIL ", m, d, trim(err%message)
            deallocate (err)
            cycle
         end if
         print '(5es24.16)', m, d, res%force, res%est_rel_err, top%force
      end do
   end do
end program drv
