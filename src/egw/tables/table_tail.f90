!> The separated tail of a rough force table resampled for evaluation without exp: its
!> ln P intervals below 0 as equal pieces of cubic Hermite in P (force_table%fine_seg,
!> which table_eval evaluates; egw_table_get_tail hands them to C). The rule works on
!> node arrays, of one table or of several that share their nodes (the slices of a
!> universal table, which a DEM code blends piece by piece), so both share one code.
module egw_table_tail
   use egw_kinds, only: dp
   use egw_search, only: bracket_interval
   implicit none
   private

   public :: tail_last_node, resample_tails

   !> The resampled tail's relative distance to the ln P cubic it replaces, as a fraction
   !> of the table's rel_tol (so the table keeps its tolerance to within 5 %), and its most
   !> pieces (320 kB; an E-GW tail over 28 e-folds takes ~270 at rel_tol 1e-4, ~1200 at
   !> 1e-6, ~6000 at 1e-8: beyond, exp as before).
   real(dp), parameter, public :: tail_resample_tol = 5.0e-2_dp
   integer, parameter, public :: max_fine = 8192
   !> The fewest pieces a resampling starts from (then 20 % more at a time).
   integer, parameter, public :: min_fine = 16

contains

   !> The last node of a tail's ln P intervals 1..n_log that is <= 0 (the separated part
   !> only: tables of earlier versions have ln P intervals above 0), or 0 where there is
   !> none (no ln P interval, or the second node above 0).
   pure integer function tail_last_node(delta, n_log) result(last)
      real(dp), intent(in) :: delta(:)   !< the table's nodes, ascending
      integer, intent(in) :: n_log       !< intervals 1..n_log interpolate ln P
      last = 0
      if (n_log < 1) return
      last = n_log + 1
      do while (delta(last) > 0.0_dp .and. last > 2)
         last = last - 1
      end do
      if (.not. delta(last) <= 0.0_dp) last = 0
   end function tail_last_node

   !> The ln P tail [delta(1), delta(last)] of ns tables on the nodes delta as n_fine equal
   !> pieces, on each every table's cubic Hermite in P through its ln P interpolant's
   !> values and slopes at the piece's ends (exact at the nodes delta(1), delta(last)).
   !> n_fine is the first of n_start, ceiling(1.2 n_start), ... (n_start from min_fine on
   !> that sequence) on which every table k's pieces, checked at 8 points of each, lie
   !> within tol(k)/2 of its interpolant, relative to it, and their slopes within
   !> 10 tol(k) of its slope; 0 (pieces empty) beyond max_fine pieces. pieces(0:4, j) for
   !> j = (q - 1) ns + k: the start of piece q and table k's cubic c1..c4 in
   !> t = delta - start (force_table%seg's layout; for ns = 1 fine_seg's). Deterministic.
   pure subroutine resample_tails(n, ns, delta, force, stiffness, seg, n_log, last, tol, &
      & n_start, pieces, n_fine)
      integer, intent(in) :: n       !< nodes
      integer, intent(in) :: ns      !< tables
      real(dp), intent(in) :: delta(n)   !< the nodes they share [length]
      real(dp), intent(in) :: force(n, ns)       !< each table's force at the nodes
      real(dp), intent(in) :: stiffness(n, ns)   !< and its stiffness
      real(dp), intent(in) :: seg(0:4, n, ns)    !< and its cubics (force_table%seg)
      integer, intent(in) :: n_log   !< intervals 1..n_log interpolate ln P (all tables)
      integer, intent(in) :: last    !< tail_last_node(delta, n_log), >= 2
      real(dp), intent(in) :: tol(ns)   !< each table's tail_resample_tol rel_tol
      integer, intent(in) :: n_start   !< the first piece count tried (min_fine's sequence)
      real(dp), allocatable, intent(out) :: pieces(:, :)   !< (0:4, ns n_fine), as above
      integer, intent(out) :: n_fine   !< pieces of each table; 0: beyond max_fine
      integer :: k, q
      real(dp) :: lo, hi
      real(dp), allocatable :: x(:)
      lo = delta(1)
      hi = delta(last)
      n_fine = n_start
      do
         x = [(lo + (hi - lo)*q/n_fine, q=0, n_fine)]
         x(n_fine + 1) = hi
         if (all_fit()) exit
         n_fine = ceiling(1.2_dp*n_fine)
         if (n_fine > max_fine) then
            n_fine = 0
            allocate (pieces(0:4, 0))
            return
         end if
      end do
      allocate (pieces(0:4, ns*n_fine))
      do q = 1, n_fine
         do k = 1, ns
            pieces(:, (q - 1)*ns + k) = hermite_piece(n, delta, force(:, k), &
               & stiffness(:, k), seg(:, :, k), n_log, x(q), x(q + 1))
         end do
      end do
   contains
      pure logical function all_fit()
         integer :: j
         all_fit = .false.
         do j = 1, ns
            if (.not. pieces_fit(n, delta, force(:, j), stiffness(:, j), seg(:, :, j), &
               & n_log, x, tol(j))) return
         end do
         all_fit = .true.
      end function all_fit
   end subroutine resample_tails

   !> A table's ln P interpolant (P, dP/ddelta) at delta in [delta(1), delta(n_log + 1)]:
   !> its nodes' values where delta is one, else exp of its interval's cubic.
   pure subroutine tail_value(n, delta, force, stiffness, seg, n_log, x, p, dpdx)
      integer, intent(in) :: n, n_log
      real(dp), intent(in) :: delta(n), force(n), stiffness(n), seg(0:4, n), x
      real(dp), intent(out) :: p, dpdx
      integer :: i
      real(dp) :: t
      i = bracket_interval(delta(1:n_log + 1), x)
      if (x == delta(i) .or. x == delta(i + 1)) then
         if (x == delta(i + 1)) i = i + 1
         p = force(i)
         dpdx = stiffness(i)
         return
      end if
      t = x - seg(0, i)
      p = exp(seg(1, i) + t*(seg(2, i) + t*(seg(3, i) + t*seg(4, i))))
      dpdx = p*(seg(2, i) + t*(2*seg(3, i) + 3*t*seg(4, i)))
   end subroutine tail_value

   !> The cubic Hermite in P on [x0, x1] through a table's tail values and slopes there:
   !> start, value, slope and the two coefficients (seg's layout).
   pure function hermite_piece(n, delta, force, stiffness, seg, n_log, x0, x1) result(c)
      integer, intent(in) :: n, n_log
      real(dp), intent(in) :: delta(n), force(n), stiffness(n), seg(0:4, n), x0, x1
      real(dp) :: c(0:4)
      real(dp) :: p0, p1, d0, d1, s, h
      call tail_value(n, delta, force, stiffness, seg, n_log, x0, p0, d0)
      call tail_value(n, delta, force, stiffness, seg, n_log, x1, p1, d1)
      h = x1 - x0
      s = (p1 - p0)/h
      c = [x0, p0, d0, (3*s - 2*d0 - d1)/h, (d0 + d1 - 2*s)/h**2]
   end function hermite_piece

   !> Whether a table's Hermite pieces in P on the grid x stay within tol/2 of its ln P
   !> interpolant (relative) and their slopes within 10 tol of its slope, checked at 8
   !> points of every piece (1/16, 3/16, ... 15/16; the half is a margin for the maxima
   !> between them, where a piece spans a node and the interpolant is only C1).
   pure logical function pieces_fit(n, delta, force, stiffness, seg, n_log, x, tol) &
      & result(fit)
      integer, intent(in) :: n, n_log
      real(dp), intent(in) :: delta(n), force(n), stiffness(n), seg(0:4, n), x(:), tol
      integer :: k, j
      real(dp) :: c(0:4), u, exact, dexact, approx
      fit = .false.
      do k = 1, size(x) - 1
         c = hermite_piece(n, delta, force, stiffness, seg, n_log, x(k), x(k + 1))
         do j = 1, 15, 2
            u = (x(k + 1) - x(k))*j/16.0_dp
            call tail_value(n, delta, force, stiffness, seg, n_log, x(k) + u, exact, dexact)
            approx = c(1) + u*(c(2) + u*(c(3) + u*c(4)))
            if (.not. abs(approx - exact) <= 0.5_dp*tol*exact) return
            approx = c(2) + u*(2*c(3) + 3*u*c(4))
            if (.not. abs(approx - dexact) <= 10*tol*abs(dexact)) return
         end do
      end do
      fit = .true.
   end function pieces_fit

end module egw_table_tail
