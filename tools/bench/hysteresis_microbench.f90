! Microbenchmark of the hysteresis evaluation paths on egw-bench --hysteresis's 1e-4 table
! (EP-GW mu 4, psi 2, [-3, 30] sigma; bench/bench_hysteresis.f90's contacts and loops),
! built once and written to FILE, then read (the read prepares it) by every run, so that
! two libraries' binaries can be alternated in short runs: best of 7 rounds, ns per call
! of the Hertz force, hysteresis_eval (one double), hysteresis_eval_state at rest and
! moving, hysteresis_energy. Build against an fpm build (B: the .mod directory, L:
! libegw.a, A: the build's other libraries):
!   gfortran -O2 -ffree-line-length-none -fopenmp -I$B hysteresis_microbench.f90 $L $A \
!      -lfftw3_omp -lfftw3 -llapack -lblas -o mb
!   OMP_NUM_THREADS=1 ./mb FILE [CASE]
! CASE (1-5: Hertz, eval, rest, moving, energy) times that loop alone (for perf record);
! the others print huge.
program mb
   use, intrinsic :: iso_fortran_env, only: int64
   use egw_kinds, only: dp
   use egw_params, only: contact_params, model_epgw
   use egw_rough_sphere, only: solver_options
   use egw_status, only: egw_error
   use egw_hysteresis, only: hysteresis_table, build_hysteresis, hysteresis_eval, hysteresis_eval_state, &
      & hysteresis_state_init, hysteresis_energy, hysteresis_state_size
   use egw_hysteresis_format, only: write_hysteresis, read_hysteresis
   use egw_table_format, only: format_binary
   use egw_smooth_sphere, only: hertz_force
   implicit none
   integer, parameter :: n = 4096, sweeps = 200, rounds = 7
   type(hysteresis_table) :: t
   type(egw_error), allocatable :: err
   character(len=256) :: file
   real(dp) :: delta(n), state(n), wobble(0:63), f, k, m, u, sink, best(5), tt
   real(dp), allocatable :: states(:, :), moving(:, :)
   integer(int64) :: c0, c1, rate
   integer :: i, r, s, stat, j, only
   logical :: there
   call get_command_argument(1, file)
   only = 0
   if (command_argument_count() >= 2) then
      call get_command_argument(2, file)
      read (file, *) only
      call get_command_argument(1, file)
   end if
   inquire (file=trim(file), exist=there)
   if (.not. there) then
      call build_hysteresis(contact_params(model=model_epgw, radius=1.0_dp, modulus=1.0_dp, sigma=1.0_dp, &
         & mu=4.0_dp, psi=2.0_dp, hardness_coeff=0.6_dp, plastic_ratio=54.0_dp), solver_options(), &
         & -3.0_dp, 30.0_dp, 1.0e-4_dp, t, err)
      if (allocated(err)) error stop 1
      call write_hysteresis(t, trim(file), format_binary, err)
      if (allocated(err)) print *, "write: ", err%message
   end if
   call read_hysteresis(trim(file), t, err)
   if (allocated(err)) then
      print *, err%message
      error stop 2
   end if
   do i = 1, n
      state(i) = -3.0_dp + 33.0_dp*modulo(0.7548776662466927_dp*i, 1.0_dp)
      delta(i) = state(i) - (state(i) + 3.0_dp)*modulo(0.5698402909980532_dp*i, 1.0_dp)
      if (mod(i, 4) == 0) delta(i) = state(i) + 0.1_dp
   end do
   allocate (states(hysteresis_state_size, n), moving(hysteresis_state_size, n))
   do i = 1, n
      call hysteresis_state_init(states(:, i))
      call hysteresis_eval_state(t, state(i), states(:, i), f, k, stat)
   end do
   moving = states
   wobble = [(0.2_dp*sin(2*acos(-1.0_dp)*i/64.0_dp), i = 0, 63)]
   best = huge(1.0_dp)
   sink = 0
   do r = 1, rounds
      do j = 1, 5
         if (only > 0 .and. j /= only) cycle
         call system_clock(c0, rate)
         do s = 1, sweeps
            do i = 1, n
               select case (j)
               case (1)
                  sink = sink + hertz_force(abs(delta(i)), 1.0_dp, 1.0_dp)
               case (2)
                  m = state(i)
                  call hysteresis_eval(t, delta(i), m, f, k, stat); sink = sink + f
               case (3)
                  call hysteresis_eval_state(t, delta(i), states(:, i), f, k, stat); sink = sink + f
               case (4)
                  call hysteresis_eval_state(t, delta(i) + wobble(iand(s + i, 63)), moving(:, i), f, k, stat)
                  sink = sink + f
               case (5)
                  call hysteresis_energy(t, delta(i), state(i), u, stat); sink = sink + u
               end select
            end do
         end do
         call system_clock(c1)
         tt = real(c1 - c0, dp)/real(rate, dp)/(sweeps*n)
         best(j) = min(best(j), tt)
      end do
   end do
   print '(a,i0,a,i0,a,5f9.2,a,es10.3)', 'nodes ', size(t%m), ' x ', size(t%s), &
      & ' ns: hertz eval rest moving energy ', best*1e9, ' sum ', sink
end program mb
