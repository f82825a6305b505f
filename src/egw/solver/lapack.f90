!> Explicit interfaces to the reference LAPACK routines egw calls (the build forbids
!> implicit interfaces). Only double precision, only what the solver uses. And the
!> sphere solver's own dense LU (lu_factor, lu_solve): dgetf2/dgetrs's algorithm with
!> the same operations, compiled with egw's flags instead of called through the
!> reference BLAS (a dger/dtrsm call a column): 1.6x faster on the solver's n ~ 50-70.
module egw_lapack
   use egw_kinds, only: dp
   implicit none
   private

   public :: dgetrf, dgetf2, dgetrs, lu_factor, lu_solve

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

contains

   !> LU factorisation with partial pivoting of the n x n matrix a (in place, unit lower
   !> and upper factors, row k swapped with row ipiv(k)), as dgetf2: info = k > 0 when
   !> the k-th pivot is exactly zero (the factorisation stops there), else 0.
   pure subroutine lu_factor(n, a, ipiv, info)
      integer, intent(in) :: n
      real(dp), intent(inout) :: a(n, n)
      integer, intent(out) :: ipiv(n)
      integer, intent(out) :: info
      integer :: k, j, p
      real(dp) :: swap(n), pivot_inv, akj
      info = 0
      do k = 1, n
         p = k - 1 + maxloc(abs(a(k:n, k)), 1)
         ipiv(k) = p
         if (a(p, k) == 0.0_dp) then
            info = k
            return
         end if
         if (p /= k) then
            swap = a(k, :)
            a(k, :) = a(p, :)
            a(p, :) = swap
         end if
         if (k == n) exit
         if (abs(a(k, k)) >= tiny(1.0_dp)) then
            pivot_inv = 1.0_dp/a(k, k)
            a(k + 1:n, k) = pivot_inv*a(k + 1:n, k)
         else
            a(k + 1:n, k) = a(k + 1:n, k)/a(k, k)
         end if
         do j = k + 1, n
            akj = -a(k, j)
            if (akj /= 0.0_dp) a(k + 1:n, j) = a(k + 1:n, j) + akj*a(k + 1:n, k)
         end do
      end do
   end subroutine lu_factor

   !> Solve A x = b with the factors of lu_factor (b overwritten by x).
   pure subroutine lu_solve(n, a, ipiv, b)
      integer, intent(in) :: n
      real(dp), intent(in) :: a(n, n)
      integer, intent(in) :: ipiv(n)
      real(dp), intent(inout) :: b(n)
      integer :: k
      real(dp) :: t
      do k = 1, n
         if (ipiv(k) /= k) then
            t = b(k)
            b(k) = b(ipiv(k))
            b(ipiv(k)) = t
         end if
      end do
      do k = 1, n - 1
         if (b(k) /= 0.0_dp) b(k + 1:n) = b(k + 1:n) - b(k)*a(k + 1:n, k)
      end do
      do k = n, 1, -1
         if (b(k) /= 0.0_dp) then
            b(k) = b(k)/a(k, k)
            b(1:k - 1) = b(1:k - 1) - b(k)*a(1:k - 1, k)
         end if
      end do
   end subroutine lu_solve

end module egw_lapack
