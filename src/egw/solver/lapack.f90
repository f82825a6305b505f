!> Explicit interfaces to the reference LAPACK routines egw calls (the build forbids
!> implicit interfaces). Only double precision, only what the solver uses.
module egw_lapack
   use egw_kinds, only: dp
   implicit none
   private

   public :: dgetrf, dgetf2, dgetrs

   interface
      !> LU factorisation with partial pivoting of a general m x n matrix.
      pure subroutine dgetrf(m, n, a, lda, ipiv, info)
         import :: dp
         integer, intent(in) :: m, n, lda
         real(dp), intent(inout) :: a(lda, *)
         integer, intent(out) :: ipiv(*)
         integer, intent(out) :: info
      end subroutine dgetrf

      !> Unblocked LU factorisation with partial pivoting (same factors as dgetrf). For the
      !> solver's matrices (n ~ 30-300) it takes 3-4 times fewer instructions than the
      !> reference dgetrf, whose recursive panel code calls dgemm/dtrsm on tiny blocks.
      pure subroutine dgetf2(m, n, a, lda, ipiv, info)
         import :: dp
         integer, intent(in) :: m, n, lda
         real(dp), intent(inout) :: a(lda, *)
         integer, intent(out) :: ipiv(*)
         integer, intent(out) :: info
      end subroutine dgetf2

      !> Solve A X = B (trans = 'N') with the factors from dgetrf.
      pure subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
         import :: dp
         character(len=1), intent(in) :: trans
         integer, intent(in) :: n, nrhs, lda, ldb
         real(dp), intent(in) :: a(lda, *)
         integer, intent(in) :: ipiv(*)
         real(dp), intent(inout) :: b(ldb, *)
         integer, intent(out) :: info
      end subroutine dgetrs
   end interface

end module egw_lapack
