!> Explicit interfaces to the few FFTW3 routines egw's boundary-element solver calls
!> (double precision, threaded with OpenMP: link -lfftw3_omp -lfftw3). Only what
!> egw_flat_bem uses; the constants are FFTW's own (fftw3.h).
module egw_fftw
   use, intrinsic :: iso_c_binding, only: c_int, c_ptr, c_double, c_double_complex
   implicit none
   private

   public :: fftw_plan_dft_r2c_2d, fftw_plan_dft_c2r_2d, fftw_execute, fftw_destroy_plan
   public :: fftw_init_threads, fftw_plan_with_nthreads

   !> Planner flags of fftw3.h: a plan from a heuristic (no measurement, so the same
   !> plan, hence the same rounding, on every run), and a c2r transform that may
   !> overwrite its input (its default).
   integer(c_int), parameter, public :: fftw_estimate_flag = 64      ! 1U << 6
   integer(c_int), parameter, public :: fftw_destroy_input_flag = 1  ! 1U << 0

   interface
      !> Plan of the real-to-complex 2-D transform of a row-major n0 x n1 array (a
      !> column-major Fortran array (n1, n0)); out holds (n1/2 + 1) x n0 values.
      function fftw_plan_dft_r2c_2d(n0, n1, in, out, flags) result(plan) &
         & bind(C, name="fftw_plan_dft_r2c_2d")
         import :: c_int, c_ptr, c_double, c_double_complex
         integer(c_int), value :: n0, n1
         real(c_double), intent(inout) :: in(*)
         complex(c_double_complex), intent(inout) :: out(*)
         integer(c_int), value :: flags
         type(c_ptr) :: plan
      end function fftw_plan_dft_r2c_2d

      !> Plan of the complex-to-real 2-D transform, the (unnormalised) inverse of the above.
      function fftw_plan_dft_c2r_2d(n0, n1, in, out, flags) result(plan) &
         & bind(C, name="fftw_plan_dft_c2r_2d")
         import :: c_int, c_ptr, c_double, c_double_complex
         integer(c_int), value :: n0, n1
         complex(c_double_complex), intent(inout) :: in(*)
         real(c_double), intent(inout) :: out(*)
         integer(c_int), value :: flags
         type(c_ptr) :: plan
      end function fftw_plan_dft_c2r_2d

      !> Run a plan on the arrays it was made for (thread-safe).
      subroutine fftw_execute(plan) bind(C, name="fftw_execute")
         import :: c_ptr
         type(c_ptr), value :: plan
      end subroutine fftw_execute

      !> Free a plan (planner call: not thread-safe).
      subroutine fftw_destroy_plan(plan) bind(C, name="fftw_destroy_plan")
         import :: c_ptr
         type(c_ptr), value :: plan
      end subroutine fftw_destroy_plan

      !> Set up FFTW's threads (once per process; 0 on failure).
      function fftw_init_threads() result(ok) bind(C, name="fftw_init_threads")
         import :: c_int
         integer(c_int) :: ok
      end function fftw_init_threads

      !> Number of threads of the plans made from now on (global planner state).
      subroutine fftw_plan_with_nthreads(n) bind(C, name="fftw_plan_with_nthreads")
         import :: c_int
         integer(c_int), value :: n
      end subroutine fftw_plan_with_nthreads
   end interface

end module egw_fftw
