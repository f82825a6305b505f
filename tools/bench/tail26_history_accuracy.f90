! Stop 60 (tail26): a separated contact back at its history exactly on a folded piece of
! the separated tail (doc/benchmarks.md "Stop 60: tail26"): the value hysteresis_eval_state
! gives there against the loading table's (table_eval) and a loading solve at rel_tol 1e-7,
! the loading route at the next double up, the piece's own value at the next double down
! (test hysteresis "served steps: ...": top_off), over test_served_copies's walks of the
! suite's EP-GW table (1e-3 over [-2, 6] sigma).
! The walk (the loop over n below) repeats test_hysteresis's walk_start/walk_overlap: a
! standalone program cannot link the test module; change both together.
! Build (fpm's release objects): gfortran -O2 -Ibuild/gfortran_<mods> \
!   tools/bench/tail26_history_accuracy.f90 LIB -lfftw3_omp -lfftw3 -llapack -lblas -fopenmp
program tail26_history_accuracy
   use egw_kinds, only: dp
   use egw_params, only: contact_params, model_epgw
   use egw_rough_sphere, only: solver_options, solve_result, solve_contact
   use egw_table, only: table_eval
   use egw_status, only: egw_error
   use egw_hysteresis, only: hysteresis_table, build_hysteresis, hysteresis_eval, &
      & hysteresis_eval_state, hysteresis_state_init, hysteresis_state_size, folded
   implicit none
   type(contact_params), parameter :: ep = contact_params(model=model_epgw, radius=1.0_dp, &
      & modulus=1.0_dp, sigma=1.0_dp, mu=4.0_dp, psi=2.0_dp, hardness_coeff=0.6_dp, &
      & plastic_ratio=54.0_dp)
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   type(solve_result) :: res
   real(dp) :: sf(hysteresis_state_size), s0(hysteresis_state_size), x0, d, cut, ff, kf, &
      & fl, kl, worst, worst_k, up, fu, ku, wc, wck, worst_s, su(hysteresis_state_size)
   integer :: j, n, stat, nh, ns, noff = 0
   real(dp) :: sb(hysteresis_state_size), fb, kb
   real(dp) :: rmin = huge(1.0_dp), rmax = -huge(1.0_dp)
   call build_hysteresis(ep, solver_options(), -2.0_dp, 6.0_dp, 1.0e-3_dp, t, err)
   if (allocated(err)) error stop "build"
   cut = t%loading%cutoff
   worst = 0; worst_k = 0; wc = 0; wck = 0; nh = 0; worst_s = 0; ns = 0
   do j = 1, 800
      if (j <= 400) then
         x0 = cut*(1.0_dp - (j - 0.5_dp)/400)
      else
         x0 = 6.2_dp*(j - 400.5_dp)/400
      end if
      call hysteresis_state_init(sf)
      do n = 0, 160
         if (n == 0) then
            d = merge(1.0_dp, x0 - 1.0_dp, mod(j, 2) == 0)
         else if (n <= 20) then
            d = x0 - 1.0_dp + n/20.0_dp
         else if (n <= 60) then
            d = x0 + 0.02_dp*(modulo(5*n, 8)/7.0_dp - 0.5_dp) + 1.0e-4_dp*sin(0.1_dp*n)
         else if (n <= 100) then
            d = x0 + 0.02_dp + 0.01_dp*modulo(7*n, 16)/15.0_dp
         else if (n <= 130) then
            d = x0 - 3.0_dp*(n - 100)/30.0_dp
         else
            d = x0 - 3.0_dp + 3.0_dp*(n - 130)/30.0_dp
         end if
         s0 = sf
         call hysteresis_eval_state(t, d, sf, ff, kf, stat)
         if (d == s0(1) .and. s0(24) == folded .and. s0(2) == s0(1) .and. s0(11) < d .and. &
            & d == s0(12) .and. stat == 0) then
            nh = nh + 1
            call table_eval(t%loading, d, fl, kl)
            worst = max(worst, abs(ff - fl)/fl)
            worst_k = max(worst_k, abs(kf - kl)/abs(kl))
            rmin = min(rmin, kf/kl); rmax = max(rmax, kf/kl)
            ! the loading route just above the history (the state's loading interval)
            up = nearest(d, 1.0_dp)
            su = s0
            call hysteresis_eval_state(t, up, su, fu, ku, stat)
            wc = max(wc, abs(ff - fu)/fl)
            sb = s0
            call hysteresis_eval_state(t, nearest(d, -1.0_dp), sb, fb, kb, stat)
            if (abs(ff - fl) > 1.0e-12_dp*fl .or. stat /= 0 .or. abs(ff - fb) > 1.0e-12_dp*fl &
               & .or. abs(kf - kb) > 1.0e-12_dp*abs(kb)) noff = noff + 1
            wck = max(wck, abs(kf - ku)/abs(kl))
            if (mod(nh, 40) == 1 .and. ns < 12) then
               call solve_contact(ep, solver_options(rel_tol=1.0e-7_dp), d, res, err)
               if (.not. allocated(err)) then
                  ns = ns + 1
                  worst_s = max(worst_s, abs(ff - res%force)/res%force)
                  print '(a,es12.4,a,es12.4,a,es12.4,a,es12.4)', "d ", d, " piece ", ff, &
                     & " loading table ", fl, " solve 1e-7 ", res%force
               end if
            end if
         end if
      end do
   end do
   print *, "history steps on a folded piece:", nh
   print *, "max |piece - loading table|/loading (force):", worst
   print *, "max |piece - loading table| (stiffness) rel:", worst_k
   print *, "max |piece(m) - loading(next double)|/P(m):", wc, " stiffness:", wck
   print *, "stiffness piece/loading at the history: min", rmin, " max", rmax
   print *, "test_served_copies check: top_off =", noff, " of", nh
   print *, "solves:", ns, " max |piece - solve|/solve:", worst_s
end program tail26_history_accuracy
