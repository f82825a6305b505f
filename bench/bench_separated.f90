!> egw-bench --separated (issue 33 item 5): what a DEM loop pays per evaluation of a 1-D
!> E-GW table through the C API (egw_table_eval, egw_table_eval_array, as a C or Fortran
!> DEM calls them) and through Fortran's table_eval, as ratios to an inline Hertz force
!> F = (4/3) E* sqrt(R) |delta|^(3/2) evaluated on the same overlaps, in three regimes:
!> (i) beyond the tail's cut-off (delta < delta_c, the table's first node, where a rough
!> table gives 0), (ii) in the tail (delta_c < delta < 0, ln P interpolated), (iii) in
!> contact (delta > 0), (o) far apart (delta < -40 sigma), and (d) far above the table's
!> last node (20 sigma .. 2e13 sigma: the deep-overlap law, where every contact of a deck
!> converted from Hertz with sigma -> 0 sits).
module bench_separated
   use, intrinsic :: iso_fortran_env, only: output_unit
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_loc, c_null_ptr
   use egw_all, only: dp, contact_params, solver_options, egw_error, model_egw, force_table, &
      & build_table, table_eval
   use bench_common, only: wall, frac
   implicit none
   private

   public :: run_separated

   integer, parameter :: n_eval = 4096   !< overlaps per sweep (fit in L1/L2 cache)
   !> best of 101 rounds of 20 sweeps (~1 ms each): on a shared machine a round that long
   !> often runs without being descheduled (rounds of 200 sweeps, ~25 ms in the tail, were
   !> all preempted at load 7 on 2 cores and measured the load, not the evaluation)
   integer, parameter :: repeats = 101
   integer, parameter :: sweeps = 20

   interface
      !> include/egw.h: int egw_table_eval(egw_table t, double delta, double *force,
      !> double *stiffness)
      function c_table_eval(h, delta, force, stiffness) result(stat) &
         & bind(C, name="egw_table_eval")
         import :: c_int, c_double, c_ptr
         type(c_ptr), value, intent(in) :: h, force, stiffness
         real(c_double), value, intent(in) :: delta
         integer(c_int) :: stat
      end function c_table_eval
      !> include/egw.h: egw_table_eval_array
      function c_table_eval_array(h, n, delta, force, stiffness) result(stat) &
         & bind(C, name="egw_table_eval_array")
         import :: c_int, c_ptr
         type(c_ptr), value, intent(in) :: h, delta, force, stiffness
         integer(c_int), value, intent(in) :: n
         integer(c_int) :: stat
      end function c_table_eval_array
   end interface

contains

   !> Build the scene's table (R = E* = sigma = 1, mu = 4: the glass pair of the default
   !> scene, scaled; overlaps from -2 sigma to 20 sigma at rel_tol 1e-4, as `make run`)
   !> and print ns per evaluation and the ratios to the inline Hertz force per regime.
   subroutine run_separated()
      type(force_table), allocatable, target :: table
      type(contact_params) :: params
      type(egw_error), allocatable :: error
      real(dp), target :: d(n_eval, 5)
      real(dp) :: t(4), lo(4), hi(4), f, k
      character(len=*), parameter :: names(5) = [character(len=32) :: &
         & "(i) beyond the cut-off", "(ii) tail (cut-off < delta < 0)", "(iii) delta > 0", &
         & "(o) delta < -40 sigma (P = 0)", "(d) deep law, 20..2e13 sigma"]
      integer :: r, i
      allocate (table)
      params = contact_params(model=model_egw, radius=1.0_dp, modulus=1.0_dp, sigma=1.0_dp, &
         & mu=4.0_dp)
      call build_table(params, solver_options(n_threads=1), -2.0_dp, 20.0_dp, 1.0e-4_dp, &
         & table, error)
      if (allocated(error)) then
         write (output_unit, '(a)') "separated: table build failed: "//error%message
         return
      end if
      ! (i) from 2 sigma below the cut-off up to it (delta = -8 sigma is in there)
      lo = [table%cutoff - 2.0_dp, table%cutoff, 0.0_dp, -60.0_dp]
      hi = [table%cutoff, 0.0_dp, 20.0_dp, -41.0_dp]
      do r = 1, 4
         do i = 1, n_eval
            d(i, r) = lo(r) + (hi(r) - lo(r))*(0.001_dp + 0.998_dp*frac(0.6180339887498949_dp*i))
         end do
      end do
      do i = 1, n_eval
         d(i, 5) = table%delta_max*10.0_dp**(12*frac(0.6180339887498949_dp*i))
      end do
      write (output_unit, '(a)') "egw-bench --separated: 1-D E-GW table (mu = 4, R = E* = "// &
         & "sigma = 1), ns per evaluation (best of 101 rounds) and / inline Hertz F"
      write (output_unit, '(a,f8.3,a)') "  cut-off delta_c = ", table%cutoff, " sigma"
      call table_eval(table, -8.0_dp, f, k)
      write (output_unit, '(a,es12.4,a,es12.4)') "  P(-8 sigma) = ", f, &
         & "  P(delta_c) = ", table%force(1)
      write (output_unit, '(a)') "  regime                            Hertz  eval   "// &
         & "ratio  array  ratio  Fortran ratio"
      do r = 1, 5
         t = regime_ns(c_loc(table), table, d(:, r))
         write (output_unit, '(2x,a32,f7.2,3(f7.2,f7.1))') names(r), t(1), t(2), &
            & t(2)/t(1), t(3), t(3)/t(1), t(4), t(4)/t(1)
      end do
   end subroutine run_separated

   !> ns per evaluation over the overlaps d: 1 inline Hertz force, 2 egw_table_eval,
   !> 3 egw_table_eval_array (one call per sweep), 4 Fortran table_eval; timed in turn
   !> within each round, the best round of each kept. Every result goes to a volatile
   !> sink, so nothing is hoisted, vectorised away or left uncomputed.
   function regime_ns(h, table, d) result(t)
      type(c_ptr), intent(in) :: h
      type(force_table), intent(in) :: table
      real(dp), intent(in), target :: d(:)
      real(dp) :: t(4)
      real(dp), volatile :: sink
      real(dp), target :: f, k, fa(n_eval), ka(n_eval)
      real(dp) :: t0, c, a, fl, kl
      integer :: r, s, j, w, stat
      c = 4.0_dp/3   ! (4/3) E* sqrt(R) with E* = R = 1
      t = huge(1.0_dp)
      do r = 1, repeats
         do w = 1, 4
            t0 = wall()
            do s = 1, sweeps
               select case (w)
               case (1)
                  do j = 1, size(d)
                     a = abs(d(j))
                     sink = c*a*sqrt(a)
                  end do
               case (2)
                  do j = 1, size(d)
                     stat = c_table_eval(h, d(j), c_loc(f), c_loc(k))
                     sink = f
                  end do
               case (3)
                  stat = c_table_eval_array(h, int(size(d), c_int), c_loc(d), c_loc(fa), &
                     & c_loc(ka))
                  sink = fa(size(d))
               case (4)
                  do j = 1, size(d)
                     call table_eval(table, d(j), fl, kl)
                     sink = fl
                  end do
               end select
            end do
            t(w) = min(t(w), (wall() - t0)*1.0e9_dp/(sweeps*size(d)))
         end do
      end do
      if (stat < 0) sink = 0   ! the status is used: the calls cannot be dropped
   end function regime_ns

end module bench_separated
