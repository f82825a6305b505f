!> Where the unloading force of an E-GW + cap contact vanishes, against the two-piece
!> map's knee (the smooth cap's residual overlap), and how accurate the solves are near
!> that edge by rel_tol (doc/benchmarks.md "Stop 51 (ratio17)"). README's rough + cap
!> numbers: R = 810569.469138702, E* = 1, sigma = 1, mu 4, p_y = 0.01 (delta_y = 100).
!>
!>   B=$(dirname $(find build -path '*/egw_hysteresis.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/rough_cap_edge.f90 \
!>      $(find build -name libegw.a | head -1) -llapack -lblas -o /tmp/rough_cap_edge
!>   OMP_NUM_THREADS=1 /tmp/rough_cap_edge
!>
!> Part 1: the 1e-3 table to 6 delta_y; at each of its nodes the edge delta_e bisected
!> (40 steps on [-5 sigma, m]) on rel_tol 1e-7 solves, its distance from the node's knee
!> in sigma, and P/P(m) at 0.01, 0.1, 1, 10 sigma above it. Part 2: at m = 2.3 and 4
!> delta_y, three overlaps above the edge, the history and unloading solved at rel_tol
!> 1e-4 .. 1e-7 against 1e-8: the local error |P - P_ref|/P_ref.
!> (Part 1's bisection on P > 0 finds the asperity heights' Gaussian foot -- P/P(m) ~1e-57
!> at 0.01 sigma for m = 2.23 delta_y -- not the force's 3/2-law front:
!> tools/bench/rough_cap_front.f90, doc/benchmarks.md "Stop 52 (local18)".)
program rough_cap_edge
   use egw, only: dp, contact_params, model_egw, solver_options, solve_result, egw_error, &
      & hysteresis_table, build_hysteresis, loading_history, load_history, solve_unload
   implicit none
   type(contact_params) :: p
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   type(loading_history) :: hist
   type(solve_result) :: peak, res, ref
   real(dp) :: m, lo, hi, d, pr(4), tol, ms(2), ds(3, 2)
   integer :: j, it, i, k, q
   p = contact_params(model=model_egw, radius=810569.469138702_dp, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, flow_pressure=0.01_dp)
   call build_hysteresis(p, solver_options(), 0.0_dp, 600.0_dp, 1.0e-3_dp, t, err)
   if (allocated(err)) stop 1
   do j = 2, size(t%m)
      m = t%m(j)
      call load_history(p, solver_options(rel_tol=1.0e-7_dp, n_threads=1), m, hist, peak, err)
      if (allocated(err)) stop 1
      lo = -5.0_dp
      hi = m
      do it = 1, 40
         d = 0.5_dp*(lo + hi)
         call solve_unload(hist, d, res, err)
         if (allocated(err)) stop 1
         if (res%force > 0.0_dp) then
            hi = d
         else
            lo = d
         end if
      end do
      do i = 1, 4
         call solve_unload(hist, hi + 10.0_dp**(i - 3), res, err)
         if (allocated(err)) stop 1
         pr(i) = res%force/peak%force
      end do
      print '(a,f6.3,a,f8.4,a,f8.4,a,f7.2,a,4es9.2)', "m/dy ", m/100, "  knee/dy ", &
         & t%knee(j)/100, "  edge/dy ", hi/100, "  (edge - knee)/sigma ", hi - t%knee(j), &
         & "  P/P(m) at edge + 0.01, 0.1, 1, 10 sigma ", pr
   end do
   ms = [230.0_dp, 400.0_dp]
   ds(:, 1) = [4.92_dp, 10.0_dp, 20.0_dp]    ! (the edge at 0)
   ds(:, 2) = [61.0_dp, 65.0_dp, 80.0_dp]    ! (the edge at 57.3)
   do q = 1, 2
      do i = 1, 3
         call load_history(p, solver_options(rel_tol=1.0e-8_dp, n_threads=1), ms(q), hist, &
            & peak, err)
         if (allocated(err)) stop 1
         call solve_unload(hist, ds(i, q), ref, err)
         if (allocated(err)) stop 1
         do k = 4, 7
            tol = 10.0_dp**(-k)
            call load_history(p, solver_options(rel_tol=tol, n_threads=1), ms(q), hist, &
               & peak, err)
            if (allocated(err)) stop 1
            call solve_unload(hist, ds(i, q), res, err)
            if (allocated(err)) stop 1
            print '(a,f6.2,a,f6.2,a,es8.1,a,es10.3,a,es9.2)', "m/dy ", ms(q)/100, &
               & "  delta/sigma ", ds(i, q), "  rel_tol ", tol, "  P/P(m) ", &
               & ref%force/peak%force, "  local error ", abs(res%force - ref%force)/ref%force
         end do
      end do
   end do
end program rough_cap_edge
