!> The route floor's premise measured (issue 32 item 3; doc/stability.md "The route
!> floor's premise"): route_floor (src/egw/solver/small_sigma_route.f90) bounds the error of a
!> loading solve at the probe's rel_tol 1e-7 by probe_margin = 10 times 1e-7 of its force.
!> Here E-GW + cap loading solves (mu 4, R = E* = 1, p_y = 2/pi, so delta_y = 1) at
!> sigma/delta_y in {2e-4, 1e-4, 2e-5, 1e-5} (the route's wide sigmas) and 1e-6, at several
!> delta, at rel_tol 1e-7 against the same solve at rel_tol 1e-10 (1e-9 where 1e-10 does
!> not converge): the ratio |P(1e-7) - P(ref)|/(1e-7 P(ref)) must stay below 10. An
!> independent check of the discretisation error, not of the model: the reference is the
!> same discrete model refined. Prints sigma, delta, P(1e-7), its est_rel_err, P(ref),
!> the reference's rel_tol and the ratio; "failed" where a solve does not converge.
!>
!>     OMP_NUM_THREADS=1 fpm run --profile release --example route-floor-premise
program route_floor_premise
   use egw, only: dp, contact_params, model_egw, solver_options, solve_result, &
      & solve_contact, egw_error
   implicit none
   real(dp), parameter :: pi = acos(-1.0_dp)
   real(dp), parameter :: sigmas(5) = [2.0e-4_dp, 1.0e-4_dp, 2.0e-5_dp, 1.0e-5_dp, 1.0e-6_dp]
   real(dp), parameter :: deltas(5) = [1.1_dp, 2.0_dp, 2.44_dp, 5.0_dp, 20.0_dp]
   real(dp), parameter :: ref_tols(2) = [1.0e-10_dp, 1.0e-9_dp]
   type(contact_params) :: p
   type(solve_result) :: probe, ref
   type(egw_error), allocatable :: err
   real(dp) :: t0, t1, worst
   integer :: i, j, k
   logical :: ok
   worst = 0.0_dp
   print '(a)', 'sigma,delta,P_probe,est_probe,P_ref,ref_tol,ratio,cpu_s'
   do i = 1, size(sigmas)
      do j = 1, size(deltas)
         p = contact_params(model=model_egw, radius=1.0_dp, modulus=1.0_dp, &
            & sigma=sigmas(i), mu=4.0_dp, flow_pressure=2.0_dp/pi)
         call cpu_time(t0)
         call solve_contact(p, solver_options(rel_tol=1.0e-7_dp, n_threads=1), deltas(j), &
            & probe, err)
         if (allocated(err)) then
            print '(es9.2,",",f6.2,",failed at 1e-7: ",a)', sigmas(i), deltas(j), err%message
            deallocate (err)
            cycle
         end if
         ok = .false.
         do k = 1, size(ref_tols)
            call solve_contact(p, solver_options(rel_tol=ref_tols(k), n_threads=1), &
               & deltas(j), ref, err)
            ok = .not. allocated(err)
            if (ok) exit
            deallocate (err)
         end do
         call cpu_time(t1)
         if (.not. ok) then
            print '(es9.2,",",f6.2,",",es22.15,",",es9.2,",reference failed")', sigmas(i), &
               & deltas(j), probe%force, probe%est_rel_err
            cycle
         end if
         worst = max(worst, abs(probe%force - ref%force)/(1.0e-7_dp*ref%force))
         print '(es9.2,",",f6.2,",",es22.15,",",es9.2,",",es22.15,",",es8.1,",",f8.3,",",f7.1)', &
            & sigmas(i), deltas(j), probe%force, probe%est_rel_err, ref%force, ref_tols(k), &
            & abs(probe%force - ref%force)/(1.0e-7_dp*ref%force), t1 - t0
      end do
   end do
   print '("# largest ratio: ",f8.3," (route_floor assumes <= 10)")', worst
end program route_floor_premise
