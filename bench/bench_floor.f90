!> egw-bench --hysteresis, the floor of a one-double hysteresis evaluation: stripped-down
!> kernels with hysteresis_eval's argument list, each on a uniform grid of synthetic cells
!> in (delta_max, s), with no table structure, no range or NaN checks and no loading-table
!> lookup. They say what any tabulated one-double evaluation costs at least as a ratio to
!> the Hertz force on the same machine and build: the state update and the call alone, one
!> bilinear cell, one cell linear in delta_max and cubic in s, one bicubic cell (a
!> representation accurate to 1e-4 in a few MB needs cubic cells in at least one
!> direction; doc/benchmarks.md).
!> Compiled apart from the timing loop, as the library is, so that no call is inlined.
module bench_floor
   use egw, only: dp
   implicit none
   private
   public :: floor_grid, floor_grid_init, floor_kernel, floor_state_only, floor_bilinear, &
      & floor_linear_cubic, floor_bicubic

   !> n_m x n_s cells over delta_max in [m0, m0 + n_m/m_scale], s = (m - delta)(a + b m)
   !> in [0, 1] (one multiply-add: no division, no lookup of the span)
   type :: floor_grid
      integer :: n_m = 0, n_s = 0
      real(dp) :: m0 = 0.0_dp, m_scale = 1.0_dp, a = 1.0_dp, b = 0.0_dp
      real(dp), allocatable :: cell(:, :, :)   !< (16, n_s, n_m): coefficients
   end type floor_grid

   abstract interface
      !> hysteresis_eval's argument list on a floor grid
      pure subroutine kernel_call(g, delta, state, force, stiffness, stat)
         import :: dp, floor_grid
         type(floor_grid), intent(in) :: g
         real(dp), intent(in) :: delta
         real(dp), intent(inout) :: state
         real(dp), intent(out) :: force, stiffness
         integer, intent(out) :: stat
      end subroutine kernel_call
   end interface

   !> One of the kernels below, called through a pointer (as the library's procedures, it
   !> is never inlined into the timing loop)
   type :: floor_kernel
      procedure(kernel_call), pointer, nopass :: run => null()
   end type floor_kernel

contains

   !> A grid of n_m x n_s cells over delta_max in [lo, hi] with synthetic coefficients in
   !> [0, 1) (their values do not change the time; no subnormals).
   subroutine floor_grid_init(g, n_m, n_s, lo, hi)
      type(floor_grid), intent(out) :: g
      integer, intent(in) :: n_m, n_s
      real(dp), intent(in) :: lo, hi
      g%n_m = n_m
      g%n_s = n_s
      g%m0 = lo
      g%m_scale = n_m/(hi - lo)
      g%a = 1.0_dp/(hi - lo)
      g%b = 0.0_dp
      allocate (g%cell(16, n_s, n_m))
      call random_number(g%cell)
   end subroutine floor_grid_init

   !> The state update and the call: max(state, delta), nothing looked up.
   pure subroutine floor_state_only(g, delta, state, force, stiffness, stat)
      type(floor_grid), intent(in) :: g
      real(dp), intent(in) :: delta
      real(dp), intent(inout) :: state
      real(dp), intent(out) :: force, stiffness
      integer, intent(out) :: stat
      state = max(state, delta)
      force = state*g%a
      stiffness = delta
      stat = 0
   end subroutine floor_state_only

   !> The cell of (delta_max, s) and the local coordinates u, v in [0, 1], branch-free.
   pure subroutine floor_cell(g, delta, state, j, i, u, v, ds)
      type(floor_grid), intent(in) :: g
      real(dp), intent(in) :: delta
      real(dp), intent(inout) :: state
      integer, intent(out) :: j, i
      real(dp), intent(out) :: u, v, ds
      real(dp) :: m, x, y
      m = max(state, delta)
      state = m
      x = (m - g%m0)*g%m_scale
      j = min(max(int(x), 0), g%n_m - 1)
      u = x - j
      ds = (g%a + g%b*m)*g%n_s   ! dv/d(m - delta)
      y = (m - delta)*ds
      i = min(max(int(y), 0), g%n_s - 1)
      v = y - i
      i = i + 1
      j = j + 1
   end subroutine floor_cell

   !> One bilinear cell (4 coefficients).
   pure subroutine floor_bilinear(g, delta, state, force, stiffness, stat)
      type(floor_grid), intent(in) :: g
      real(dp), intent(in) :: delta
      real(dp), intent(inout) :: state
      real(dp), intent(out) :: force, stiffness
      integer, intent(out) :: stat
      real(dp) :: u, v, ds
      integer :: i, j
      call floor_cell(g, delta, state, j, i, u, v, ds)
      associate (c => g%cell(:, i, j))
         force = max((c(1) + u*c(2)) + v*(c(3) + u*c(4)), 0.0_dp)
         stiffness = -(c(3) + u*c(4))*ds
      end associate
      stat = 0
   end subroutine floor_bilinear

   !> One cell linear in delta_max and cubic in s (8 coefficients, Estrin's scheme).
   pure subroutine floor_linear_cubic(g, delta, state, force, stiffness, stat)
      type(floor_grid), intent(in) :: g
      real(dp), intent(in) :: delta
      real(dp), intent(inout) :: state
      real(dp), intent(out) :: force, stiffness
      integer, intent(out) :: stat
      real(dp) :: u, v, v2, ds, r(4)
      integer :: i, j
      call floor_cell(g, delta, state, j, i, u, v, ds)
      associate (c => g%cell(:, i, j))
         r = c(1:7:2) + u*c(2:8:2)
      end associate
      v2 = v*v
      force = max((r(1) + v*r(2)) + v2*(r(3) + v*r(4)), 0.0_dp)
      stiffness = -((r(2) + 2*v*r(3)) + 3*v2*r(4))*ds
      stat = 0
   end subroutine floor_linear_cubic

   !> One bicubic cell (16 coefficients, Estrin's scheme in both directions).
   pure subroutine floor_bicubic(g, delta, state, force, stiffness, stat)
      type(floor_grid), intent(in) :: g
      real(dp), intent(in) :: delta
      real(dp), intent(inout) :: state
      real(dp), intent(out) :: force, stiffness
      integer, intent(out) :: stat
      real(dp) :: u, u2, v, v2, ds, r(4)
      integer :: i, j
      call floor_cell(g, delta, state, j, i, u, v, ds)
      u2 = u*u
      associate (c => g%cell(:, i, j))
         r = (c(1:13:4) + u*c(2:14:4)) + u2*(c(3:15:4) + u*c(4:16:4))
      end associate
      v2 = v*v
      force = max((r(1) + v*r(2)) + v2*(r(3) + v*r(4)), 0.0_dp)
      stiffness = -((r(2) + 2*v*r(3)) + 3*v2*r(4))*ds
      stat = 0
   end subroutine floor_bicubic

end module bench_floor
