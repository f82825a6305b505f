!> Explicit interfaces to the reference LAPACK routines egw calls (the build forbids
!> implicit interfaces). Only double precision, only what the solver uses.
module egw_lapack
   use egw_kinds, only: dp
   implicit none
   private

   public :: dgetrf, dgetrs

   interface
      !> LU factorisation with partial pivoting of a general m x n matrix.
      pure subroutine dgetrf(m, n, a, lda, ipiv, info)
         import :: dp
         integer, intent(in) :: m, n, lda
         real(dp), intent(inout) :: a(lda, *)
         integer, intent(out) :: ipiv(*)
         integer, intent(out) :: info
      end subroutine dgetrf

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
