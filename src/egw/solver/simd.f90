!> The solver's AVX2 + FMA kernels (simd_kernels.c), chosen at run time (issue 32): the
!> library is built for any x86-64; where the CPU has AVX2 and FMA (simd_level() == 1)
!> the half-space's far-field kernel, its near pieces' log-product weights and basis sums
!> (egw_halfspace) and
!> the dense LU's rank-4 update (egw_lapack) take the 4-lane routines, else gfortran's
!> loops.
!> EGW_SIMD=sse2 in the environment keeps the baseline (the switch: core's egw_simd_path,
!> shared with egw_unloading's kernel). The two paths differ in rounding
!> only (test_halfspace, test_rough_sphere's dense LU).
module egw_simd
   use egw_simd_path, only: simd_level, simd_set
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   implicit none
   private

   public :: simd_level, simd_set, simd_far_kernel, simd_log_piece, simd_batch6, simd_rank4

   interface
      !> egw_halfspace's far_kernel_run four lanes wide (fp, fq: ellipk_fast_p, _q).
      pure subroutine simd_far_kernel(n, t, w, r, fp, fq, row) &
         & bind(C, name="egw_simd_far_kernel")
         import :: c_int, c_double
         integer(c_int), value :: n
         real(c_double), intent(in) :: t(*), w(*), fp(*), fq(*)
         real(c_double), value :: r
         real(c_double), intent(out) :: row(*)
      end subroutine simd_far_kernel
      !> egw_halfspace's add_log_piece weights (split_near's range) four lanes wide (a, b:
      !> ellipk_split_a, _b).
      pure subroutine simd_log_piece(n, x, lw, llw, r, len, direction, a, b, wt) &
         & bind(C, name="egw_simd_log_piece")
         import :: c_int, c_double
         integer(c_int), value :: n
         real(c_double), intent(in) :: x(*), lw(*), llw(*), a(*), b(*)
         real(c_double), value :: r, len, direction
         real(c_double), intent(out) :: wt(*)
      end subroutine simd_log_piece
      !> egw_halfspace's add_batch_six over m points, four at a time.
      pure subroutine simd_batch6(m, ls, bary, s, wt, acc) bind(C, name="egw_simd_batch6")
         import :: c_int, c_double
         integer(c_int), value :: m
         real(c_double), intent(in) :: ls(*), bary(*), s(*), wt(*)
         real(c_double), intent(inout) :: acc(*)
      end subroutine simd_batch6
      !> a = (a - (u1 c1 + u2 c2)) - (u3 c3 + u4 c4) over m entries.
      pure subroutine simd_rank4(m, a, c1, c2, c3, c4, u1, u2, u3, u4) &
         & bind(C, name="egw_simd_rank4")
         import :: c_int, c_double
         integer(c_int), value :: m
         real(c_double), intent(inout) :: a(*)
         real(c_double), intent(in) :: c1(*), c2(*), c3(*), c4(*)
         real(c_double), value :: u1, u2, u3, u4
      end subroutine simd_rank4
   end interface
end module egw_simd
