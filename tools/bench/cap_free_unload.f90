!> The unloading solves of EP-GW + cap histories below the cap's first yield, by the
!> cap-free route (loading_history%cap_free, stop 52) or on the cap's routes (cap_free set
!> false on the same history): the README's rough + cap pair with --model EP-GW --psi 1
!> (R = 810569.469138702/2 per pair, E* = 1, sigma = 1, mu 4, p_y = 0.01, first yield
!> ~98 sigma), 41 histories from -6.7 to 93.75 sigma (the table's range below yield) at
!> the table's solve tolerance 1e-5, 18 unloading solves each down to 8 sigma below 0
!> with one unload_start per history, as a table curve. Prints the route, how many
!> histories were cap-free and the sum of the forces (equal for both routes: bit for bit).
!> Count instructions (doc/benchmarks.md "Stop 52 (free18)"):
!>
!>   B=$(dirname $(find build -path '*/egw_rough_sphere.mod' | head -1))
!>   gfortran -O2 -fopenmp -I$B tools/bench/cap_free_unload.f90 \
!>      $(find build -name libegw.a | head -1) -lfftw3_omp -lfftw3 -llapack -lblas \
!>      -o /tmp/cap_free_unload
!>   for r in free cap; do OMP_NUM_THREADS=1 valgrind --tool=cachegrind --cache-sim=no \
!>      /tmp/cap_free_unload $r; done
program cap_free_unload
   use egw_kinds, only: dp
   use egw_params, only: contact_params, model_epgw
   use egw_status, only: egw_error
   use egw_rough_sphere, only: solver_options, solve_result, loading_history, unload_start, &
      & load_history, solve_unload
   implicit none
   type(contact_params) :: p
   type(solver_options) :: o
   type(loading_history) :: h
   type(solve_result) :: top, res
   type(unload_start) :: start
   type(egw_error), allocatable :: err
   real(dp) :: m, total
   integer :: i, k, n_free
   character(len=8) :: route
   call get_command_argument(1, route)
   if (route /= "cap") route = "free"
   p = contact_params(model=model_epgw, radius=810569.469138702_dp/2, modulus=1.0_dp, &
      & sigma=1.0_dp, mu=4.0_dp, psi=1.0_dp, flow_pressure=0.01_dp)
   o%rel_tol = 1.0e-5_dp
   o%n_threads = 1
   total = 0.0_dp
   n_free = 0
   do i = 0, 40
      m = -6.7_dp + (93.75_dp + 6.7_dp)*real(i, dp)/40.0_dp
      call load_history(p, o, m, h, top, err)
      if (allocated(err)) error stop "history failed"
      if (h%cap_free) n_free = n_free + 1
      if (route == "cap") h%cap_free = .false.
      do k = 1, 18
         call solve_unload(h, m - (m + 8.0_dp)*real(k, dp)/18.0_dp, res, err, start)
         if (allocated(err)) error stop "unloading failed"
         total = total + res%force
      end do
   end do
   print '(a, a, i3, a, es24.16)', trim(route), ": cap-free histories ", n_free, &
      & " of 41, sum of forces ", total
end program cap_free_unload
