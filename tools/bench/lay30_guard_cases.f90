!> The unloading guards' own cases after a capped loading (doc/benchmarks.md "Stop 64:
!> lay30"), each solved at the rel_tol given: the rim's layers (EP-GW psi 1 + cap, sigma
!> = delta_y/100, 17.65375 delta_y after 18.90625 delta_y), the a_max layers (sigma =
!> delta_y, seven overlaps after 6 delta_y), the layers inside a (E-GW + cap steel beads,
!> 0.017419 delta_y after 1.2971 delta_y), the confirming level (sigma = delta_y/100,
!> 0.8837, 0.8357 of 9.375 delta_y). One line a solve: case, delta/delta_y, force (or
!> FAIL and the message), est_rel_err, P(delta_max).
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/lay30_guard_cases.f90 \
!>      $(find build -name libegw.a | head -1) -lfftw3_omp -lfftw3 -llapack -lblas -o /tmp/g
!>   OMP_NUM_THREADS=1 /tmp/g 1e-5   # rel_tol of the unloading solves
program guard_cases
   use egw, only: dp, contact_params, model_egw, model_epgw, solver_options, egw_error, &
      & solve_result, loading_history, load_history, solve_unload
   implicit none
   real(dp), parameter :: pi = acos(-1.0_dp), py = 0.01_dp
   real(dp) :: tol, dy
   character(len=32) :: arg
   type(contact_params) :: p
   call get_command_argument(1, arg); read (arg, *) tol
   dy = (0.5_dp*pi*py)**2
   ! the rim (test_rim_unloading)
   p = contact_params(model=model_epgw, radius=1.0_dp, modulus=1.0_dp, sigma=0.01_dp*dy, &
      & mu=4.0_dp, psi=1.0_dp, flow_pressure=py)
   call run("rim", p, dy, 18.90625_dp, 1.0e-6_dp, [17.65375_dp])
   ! the confirming level (test_deep_unloading_loose)
   call run("deep9", p, dy, 9.375_dp, 1.0e-6_dp, [0.8837_dp, 0.8357_dp]*9.375_dp)
   ! a_max (test_deep_unloading)
   p%sigma = dy
   call run("amax", p, dy, 6.0_dp, 1.0e-9_dp, [2.5714_dp, 3.9429_dp, 4.2857_dp, 4.6286_dp, &
      & 4.9714_dp, 5.3143_dp, 5.6571_dp, 0.5_dp, 1.5_dp, 5.9_dp])
   ! inside a (test_residual_overlap_beads)
   p = contact_params(model=model_egw, radius=0.5e-3_dp, modulus=210.0e9_dp/(2.0_dp*(1.0_dp &
      & - 0.29_dp**2)), sigma=1.41e-8_dp, mu=4.0_dp, flow_pressure=1.6e9_dp)
   call run("beads", p, 2.403074547673163e-7_dp, 1.2970813472435374_dp, 1.0e-10_dp, &
      & [0.01741909132221112_dp, 0.05_dp, 0.3_dp])
contains
   subroutine run(name, p, dy, m, htol, deltas)
      character(len=*), intent(in) :: name
      type(contact_params), intent(in) :: p
      real(dp), intent(in) :: dy, m, htol, deltas(:)
      type(loading_history) :: h
      type(solve_result) :: top, res
      type(egw_error), allocatable :: err
      integer :: i
      call load_history(p, solver_options(rel_tol=htol), m*dy, h, top, err)
      if (allocated(err)) then
         print '(a,1x,a,1x,a)', name, "history FAIL", trim(err%message)
         return
      end if
      h%options%rel_tol = tol
      do i = 1, size(deltas)
         call solve_unload(h, deltas(i)*dy, res, err)
         if (allocated(err)) then
            print '(a,1x,f12.8,1x,a,1x,a)', name, deltas(i), "FAIL", trim(err%message)
            deallocate (err)
         else
            print '(a,1x,f12.8,1x,es24.16,1x,es10.3,1x,es24.16)', name, deltas(i), res%force, &
               & res%est_rel_err, top%force
         end if
         flush (6)
      end do
   end subroutine run
end program guard_cases
