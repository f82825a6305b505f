!> Searches in ascending node arrays shared by the laws and tables: the interval of a
!> point by bisection, so that every piecewise interpolant finds its piece one way.
module egw_search
   use egw_kinds, only: dp
   implicit none
   private

   public :: bracket_interval

contains

   !> The interval i of x in the ascending nodes: the largest i in 1..size(nodes) - 1
   !> with nodes(i) <= x (so nodes(i) <= x < nodes(i + 1) inside), 1 where x lies below
   !> nodes(2) or is NaN, size(nodes) - 1 at or beyond the last node; 1 for fewer than
   !> two nodes. Bisection: ceiling(log2(size(nodes) - 1)) comparisons.
   pure integer function bracket_interval(nodes, x) result(i)
      real(dp), intent(in) :: nodes(:)   !< ascending
      real(dp), intent(in) :: x          !< the point
      integer :: hi, mid
      i = 1
      hi = size(nodes)
      do while (hi - i > 1)
         mid = (i + hi)/2
         if (nodes(mid) <= x) then
            i = mid
         else
            hi = mid
         end if
      end do
   end function bracket_interval

end module egw_search
