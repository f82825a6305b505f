!> Tests of egw_search: bracket_interval against a linear scan of the nodes (the plain
!> definition, independent of the bisection) on graded, uniform and two-node arrays, at
!> every node, between nodes, outside both ends and at NaN.
module test_search
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   use testdrive, only: new_unittest, unittest_type, error_type, check, to_string
   use egw_kinds, only: dp
   use egw_search, only: bracket_interval
   implicit none
   private
   public :: collect_search

contains

   subroutine collect_search(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("bracket_interval: as a linear scan", test_linear_scan), &
         & new_unittest("bracket_interval: ends, NaN, short arrays", test_edges) &
         & ]
   end subroutine collect_search

   !> The largest i in 1..n-1 with nodes(i) <= x, else 1: the definition, read off by a scan.
   pure integer function scan_interval(nodes, x) result(i)
      real(dp), intent(in) :: nodes(:), x
      integer :: k
      i = 1
      do k = 2, size(nodes) - 1
         if (nodes(k) <= x) i = k
      end do
   end function scan_interval

   !> Every node, the midpoints and quarter points between nodes, and points beyond both
   !> ends, on arrays of 2 to 40 nodes (uniform and geometrically graded, as the tables'
   !> tails are): exactly the scan's interval (integers: no tolerance).
   subroutine test_linear_scan(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), allocatable :: nodes(:), points(:)
      integer :: n, k, j, graded
      do graded = 0, 1
         do n = 2, 40
            if (graded == 1) then
               nodes = [(-1.0_dp + 1.3_dp**k, k=1, n)]
            else
               nodes = [(0.25_dp*k - 3.0_dp, k=1, n)]
            end if
            points = [nodes(1) - 1.0_dp, nodes(n) + 1.0_dp, nodes, &
               & (nodes(k) + 0.5_dp*(nodes(k + 1) - nodes(k)), k=1, n - 1), &
               & (nodes(k) + 0.25_dp*(nodes(k + 1) - nodes(k)), k=1, n - 1), &
               & (nodes(k + 1) - spacing(nodes(k + 1)), k=1, n - 1)]
            do j = 1, size(points)
               call check(error, bracket_interval(nodes, points(j)), &
                  & scan_interval(nodes, points(j)), "n = "//to_string(n)//", point " &
                  & //to_string(j)//", graded = "//to_string(graded))
               if (allocated(error)) return
            end do
         end do
      end do
   end subroutine test_linear_scan

   !> The ends as the laws and tables rely on them: below the nodes 1, at and beyond the
   !> last n - 1 (the last interval, closed), NaN 1 (every comparison false), one node 1.
   subroutine test_edges(error)
      type(error_type), allocatable, intent(out) :: error
      real(dp), parameter :: nodes(5) = [0.0_dp, 1.0_dp, 2.0_dp, 4.0_dp, 8.0_dp]
      real(dp) :: nan
      nan = ieee_value(0.0_dp, ieee_quiet_nan)
      call check(error, bracket_interval(nodes, -5.0_dp), 1, "below the first node")
      if (allocated(error)) return
      call check(error, bracket_interval(nodes, 8.0_dp), 4, "at the last node")
      if (allocated(error)) return
      call check(error, bracket_interval(nodes, 1.0e300_dp), 4, "beyond the last node")
      if (allocated(error)) return
      call check(error, bracket_interval(nodes, 4.0_dp), 4, "at an inner node")
      if (allocated(error)) return
      call check(error, bracket_interval(nodes, nan), 1, "NaN")
      if (allocated(error)) return
      call check(error, bracket_interval(nodes(1:1), 3.0_dp), 1, "one node")
   end subroutine test_edges

end module test_search
