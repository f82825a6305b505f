!> Stiffness of unloading solves after a capped loading against quotients of tight forces
!> (doc/benchmarks.md "Stop 62: acc28"): README's E-GW + cap pair (or EP-GW, psi 1) in
!> sigma units (R = 810569.469138702, E* = sigma = 1, mu 4, p_y = 0.01: delta_y = 200
!> sigma). At each (delta_max, delta): the implicit stiffness of solve_contact_unload at
!> rel_tol TOL and the difference quotient of rel_tol 1e-10 forces (same history, loaded
!> at 1e-10), central with h = 0.01 and 0.02 sigma, extrapolated (4 D(h) - D(2h))/3 (its
!> truncation O(h**4); its rounding ~ e P/(h S) with e the forces' error). One line a
!> point: model, m, delta, P, S(TOL), S(1e-10), quotient, the two relative differences
!> (S - quotient)/quotient, D(h) - D(2h) relative (the truncation's size).
!>
!>   B=build/gfortran_28C1B7C106A83FFE   # the directory of egw.mod
!>   gfortran -O2 -fopenmp -I$B -J/tmp tools/bench/acc28_unload_stiffness.f90 \
!>      $(find build -name libegw.a | head -1) -lfftw3_omp -lfftw3 -llapack -lblas -o /tmp/stiff
!>   OMP_NUM_THREADS=1 /tmp/stiff E-GW 1e-8 209 212.7
program unload_stiffness
   use egw, only: dp, contact_params, model_egw, model_epgw, solver_options, egw_error, &
      & solve_result, solve_contact_unload
   implicit none
   type(contact_params) :: p
   real(dp), parameter :: frac(3) = [0.6_dp, 0.2_dp, 0.05_dp], fixed(3) = [5.0_dp, &
      & 2.1221_dp, 1.0_dp], h = 0.01_dp, shifts(4) = [-2.0_dp, -1.0_dp, 1.0_dp, 2.0_dp]
   real(dp) :: m, tol, deltas(6), s_tol, s_tight, f0, d1, d2, q, fp(4)
   character(len=32) :: arg, model
   integer :: k, j, i
   logical :: ok
   call get_command_argument(1, model)
   call get_command_argument(2, arg); read (arg, *) tol
   p = contact_params(model=model_egw, radius=810569.469138702_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   if (model == "EP-GW") then
      p%model = model_epgw
      p%psi = 1.0_dp
   end if
   do k = 3, command_argument_count()
      call get_command_argument(k, arg); read (arg, *) m
      deltas(1:3) = frac*m
      deltas(4:6) = fixed
      do j = 1, 6
         call solve(deltas(j), tol, f0, s_tol, ok)
         if (.not. ok) cycle
         call solve(deltas(j), 1.0e-10_dp, f0, s_tight, ok)
         if (.not. ok) cycle
         do i = 1, 4
            call solve(deltas(j) + h*shifts(i), 1.0e-10_dp, fp(i), q, ok)
            if (.not. ok) exit
         end do
         if (.not. ok) cycle
         d1 = (fp(3) - fp(2))/(2.0_dp*h)
         d2 = (fp(4) - fp(1))/(4.0_dp*h)
         q = (4.0_dp*d1 - d2)/3.0_dp
         print '(a,1x,f9.4,1x,f9.4,1x,es22.14,3(1x,es22.14),3(1x,es10.2))', trim(model), m, &
            & deltas(j), f0, s_tol, s_tight, q, (s_tol - q)/q, (s_tight - q)/q, (d1 - d2)/q
         flush (6)
      end do
   end do
contains
   subroutine solve(delta, rel_tol, force, stiffness, ok)
      real(dp), intent(in) :: delta, rel_tol
      real(dp), intent(out) :: force, stiffness
      logical, intent(out) :: ok
      type(solve_result) :: res
      type(egw_error), allocatable :: err
      call solve_contact_unload(p, solver_options(rel_tol=rel_tol, n_threads=1), delta, m, &
         & res, err)
      ok = .not. allocated(err)
      if (.not. ok) then
         print '(a,1x,f9.4,1x,f9.4,1x,es8.1,1x,a)', trim(model), m, delta, rel_tol, &
            & "FAIL "//trim(err%message)
         return
      end if
      force = res%force
      stiffness = res%stiffness
   end subroutine solve
end program unload_stiffness
