!> Explicit interfaces to the reference LAPACK routines egw calls (the build forbids
!> implicit interfaces). Only double precision, only what the solver uses. And the
!> sphere solver's own dense LU (lu_factor, lu_solve): dgetf2/dgetrs's algorithm with
!> the same operations, compiled with egw's flags instead of called through the
!> reference BLAS (a dger/dtrsm call a column): 1.6x faster on the solver's n ~ 50-70.
module egw_lapack
   use egw_kinds, only: dp
   use egw_simd, only: simd_level, simd_rank4
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
   !> the k-th pivot is exactly zero (the factorisation stops there), else 0. The same
   !> pivots and operations as dgetf2 but for the order of the trailing updates: two
   !> columns are eliminated per sweep of the trailing matrix (a rank-2 update), which
   !> halves the passes over it (the solver's n ~ 100-400 fit in L2 and the rank-1
   !> sweeps were bound by its bandwidth). Four columns at a time (panel_of_four): the
   !> two rank-2 updates of a trailing column in one sweep, each entry still updated by
   !> the same two expressions in the same order, so the factors are the same to the bit.
   pure subroutine lu_factor(n, a, ipiv, info)
      integer, intent(in) :: n   !< order of the matrix
      real(dp), intent(inout) :: a(n, n)   !< in: A; out: its L and U factors
      integer, intent(out) :: ipiv(n)   !< row k swapped with row ipiv(k)
      integer, intent(out) :: info   !< 0, or the first zero pivot's k
      integer :: k, j
      real(dp) :: u1, u2
      info = 0
      k = 1
      do while (k + 3 < n)
         call panel_of_four(n, a, k, ipiv, info)
         if (info /= 0) return
         k = k + 4
      end do
      do while (k <= n)
         call pivot_column(n, a, k, ipiv, info)
         if (info /= 0 .or. k == n) return
         ! column k + 1 from column k alone, then its pivot
         u1 = a(k, k + 1)
         if (u1 /= 0.0_dp) a(k + 1:n, k + 1) = a(k + 1:n, k + 1) - u1*a(k + 1:n, k)
         call pivot_column(n, a, k + 1, ipiv, info)
         if (info /= 0) return
         ! the trailing columns: U's two entries, then one rank-2 sweep of the column
         do j = k + 2, n
            u1 = a(k, j)
            u2 = a(k + 1, j) - a(k + 1, k)*u1
            a(k + 1, j) = u2
            if (u1 /= 0.0_dp .or. u2 /= 0.0_dp) a(k + 2:n, j) = a(k + 2:n, j) &
               & - (u1*a(k + 2:n, k) + u2*a(k + 2:n, k + 1))
         end do
         k = k + 2
      end do
   end subroutine lu_factor

   !> lu_factor's two steps k and k + 2 (k + 3 < n): the panel k .. k + 3 as there (pivot
   !> rows swapped across the whole matrix), then each trailing column j > k + 3 once: U's
   !> entries of rows k, k + 1, the first rank-2 update of rows k + 2, k + 3, U's entries
   !> there, and both rank-2 updates of rows k + 4 .. n in one pass, in lu_factor's order.
   !> Row swaps and these row-wise updates commute, so every entry gets the operations of
   !> the two separate sweeps.
   pure subroutine panel_of_four(n, a, k, ipiv, info)
      integer, intent(in) :: n, k
      real(dp), intent(inout) :: a(n, n)
      integer, intent(inout) :: ipiv(n)
      integer, intent(inout) :: info
      integer :: j, i, m
      real(dp) :: u1, u2, u3, u4
      do m = k, k + 2, 2
         call pivot_column(n, a, m, ipiv, info)
         if (info /= 0) return
         u1 = a(m, m + 1)
         if (u1 /= 0.0_dp) a(m + 1:n, m + 1) = a(m + 1:n, m + 1) - u1*a(m + 1:n, m)
         call pivot_column(n, a, m + 1, ipiv, info)
         if (info /= 0) return
         if (m == k + 2) exit
         do j = k + 2, k + 3
            u1 = a(k, j)
            u2 = a(k + 1, j) - a(k + 1, k)*u1
            a(k + 1, j) = u2
            if (u1 /= 0.0_dp .or. u2 /= 0.0_dp) a(k + 2:n, j) = a(k + 2:n, j) &
               & - (u1*a(k + 2:n, k) + u2*a(k + 2:n, k + 1))
         end do
      end do
      do j = k + 4, n
         u1 = a(k, j)
         u2 = a(k + 1, j) - a(k + 1, k)*u1
         a(k + 1, j) = u2
         if (u1 /= 0.0_dp .or. u2 /= 0.0_dp) a(k + 2:k + 3, j) = a(k + 2:k + 3, j) &
            & - (u1*a(k + 2:k + 3, k) + u2*a(k + 2:k + 3, k + 1))
         u3 = a(k + 2, j)
         u4 = a(k + 3, j) - a(k + 3, k + 2)*u3
         a(k + 3, j) = u4
         if (u1 /= 0.0_dp .or. u2 /= 0.0_dp) then
            if ((u3 /= 0.0_dp .or. u4 /= 0.0_dp) .and. simd_level() == 1) then
               if (k + 4 <= n) call simd_rank4(n - k - 3, a(k + 4, j), a(k + 4, k), &
                  & a(k + 4, k + 1), a(k + 4, k + 2), a(k + 4, k + 3), u1, u2, u3, u4)
            else if (u3 /= 0.0_dp .or. u4 /= 0.0_dp) then
               do i = k + 4, n
                  a(i, j) = (a(i, j) - (u1*a(i, k) + u2*a(i, k + 1))) &
                     & - (u3*a(i, k + 2) + u4*a(i, k + 3))
               end do
            else
               a(k + 4:n, j) = a(k + 4:n, j) - (u1*a(k + 4:n, k) + u2*a(k + 4:n, k + 1))
            end if
         else if (u3 /= 0.0_dp .or. u4 /= 0.0_dp) then
            a(k + 4:n, j) = a(k + 4:n, j) - (u3*a(k + 4:n, k + 2) + u4*a(k + 4:n, k + 3))
         end if
      end do
   end subroutine panel_of_four

   !> lu_factor's step at column c: its pivot (rows c..n, ipiv(c)), the rows swapped
   !> across the whole matrix, the multipliers below it; info = c on an exactly zero
   !> pivot.
   pure subroutine pivot_column(n, a, c, ipiv, info)
      integer, intent(in) :: n, c
      real(dp), intent(inout) :: a(n, n)
      integer, intent(inout) :: ipiv(n)
      integer, intent(inout) :: info
      integer :: p
      real(dp) :: swap(n), pivot_inv
      p = c - 1 + maxloc(abs(a(c:n, c)), 1)
      ipiv(c) = p
      if (a(p, c) == 0.0_dp) then
         info = c
         return
      end if
      if (p /= c) then
         swap = a(c, :)
         a(c, :) = a(p, :)
         a(p, :) = swap
      end if
      if (c == n) return
      if (abs(a(c, c)) >= tiny(1.0_dp)) then
         pivot_inv = 1.0_dp/a(c, c)
         a(c + 1:n, c) = pivot_inv*a(c + 1:n, c)
      else
         a(c + 1:n, c) = a(c + 1:n, c)/a(c, c)
      end if
   end subroutine pivot_column

   !> Solve A x = b with the factors of lu_factor (b overwritten by x).
   pure subroutine lu_solve(n, a, ipiv, b)
      integer, intent(in) :: n   !< order of the matrix
      real(dp), intent(in) :: a(n, n)   !< L and U from lu_factor
      integer, intent(in) :: ipiv(n)   !< pivots from lu_factor
      real(dp), intent(inout) :: b(n)   !< in: b; out: x
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
