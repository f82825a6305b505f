!> A reference for one unloading solve after a capped loading (doc/benchmarks.md
!> "Stop 62: acc28"): README's E-GW + cap pair (R = 810569.469138702, E* = sigma = 1,
!> mu 4, p_y = 0.01: delta_y = 200 sigma), delta = 2.1221 sigma after 209 sigma. Two
!> routes on the same history (loaded at rel_tol 1e-10, as solve_contact_unload loads it
!> for every rel_tol <= 1e-6): the automatic levels (solve_contact_unload) at rel_tol
!> 1e-8 .. 1e-10, and fixed meshes of N nodes (n_radial: one level, no error estimate,
!> none of refine_levels' acceptance) at N = 257 .. 4097, whose forces converge with N.
!> One line a solve: route, rel_tol or N, force, est_rel_err (automatic) or status, CPU s.
!>
!>   B=build/gfortran_28C1B7C106A83FFE   # the directory of egw.mod
!>   gfortran -O2 -fopenmp -I$B -J/tmp tools/bench/acc28_unload_reference.f90 \
!>      $(find build -name libegw.a | head -1) -lfftw3_omp -lfftw3 -llapack -lblas -o /tmp/ref
!>   OMP_NUM_THREADS=1 /tmp/ref
program unload_reference
   use egw, only: dp, contact_params, model_egw, solver_options, egw_error, solve_result, &
      & solve_contact_unload, loading_history, load_history, solve_unload
   implicit none
   type(contact_params) :: p
   type(egw_error), allocatable :: err
   type(solve_result) :: res, loaded
   type(loading_history) :: hist
   real(dp), parameter :: delta = 2.1221_dp, delta_max = 209.0_dp
   real(dp), parameter :: tols(3) = [1.0e-8_dp, 1.0e-9_dp, 1.0e-10_dp]
   integer, parameter :: nodes(5) = [257, 513, 1025, 2049, 4097]
   real(dp) :: t0, t1
   integer :: k
   p = contact_params(model=model_egw, radius=810569.469138702_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   do k = 1, size(tols)
      call cpu_time(t0)
      call solve_contact_unload(p, solver_options(rel_tol=tols(k), n_threads=1), delta, &
         & delta_max, res, err)
      call cpu_time(t1)
      if (allocated(err)) then
         print '(a,es8.1,1x,a)', "levels ", tols(k), "FAIL "//trim(err%message)
         deallocate (err)
      else
         print '(a,es8.1,1x,es24.16,1x,es10.3,1x,f7.2)', "levels ", tols(k), res%force, &
            & res%est_rel_err, t1 - t0
      end if
   end do
   call load_history(p, solver_options(rel_tol=1.0e-10_dp, n_threads=1), delta_max, hist, &
      & loaded, err)
   if (allocated(err)) error stop "history: "//err%message
   do k = 1, size(nodes)
      hist%options%n_radial = nodes(k)
      call cpu_time(t0)
      call solve_unload(hist, delta, res, err)
      call cpu_time(t1)
      if (allocated(err)) then
         print '(a,i8,1x,a)', "fixed  ", nodes(k), "FAIL "//trim(err%message)
         deallocate (err)
      else
         print '(a,i8,1x,es24.16,1x,a,1x,f7.2)', "fixed  ", nodes(k), res%force, "ok", t1 - t0
      end if
   end do
end program unload_reference
