!> egw-bench F_n section: the cost and error of the evaluation paths of the asperity
!> integral F_{3/2}(h) = int_h^inf (s-h)^{3/2} phi(s) ds (issue 5 item 1):
!>   - egw's fitted kernel (gauss_integral(1.5, h), the path every solve uses);
!>   - egw's general-order path (fixed composite Gauss-Legendre), reached with the order
!>     n = nearest(1.5, 2) = 1.5 + 2.2e-16 (the fits are keyed on the exact order); the
!>     order shift changes F by ~1e-16 relative, far below what is measured;
!>   - a naive adaptive Simpson quadrature of the definition written here, at several
!>     tolerances (the baseline a user would write first).
!> Error against 40-digit mpmath values, doc/bench/fn_reference.csv
!> (tools/bench/fn_reference.py).
module bench_fn
   use, intrinsic :: iso_fortran_env, only: output_unit
   use egw, only: dp, gauss_integral
   use bench_common, only: wall, write_row, fmt_e, fmt_s
   implicit none
   private

   public :: run_fn

   real(dp), parameter :: inv_sqrt2pi = 0.39894228040143267794_dp

contains

   subroutine run_fn(unit)
      integer, intent(in) :: unit
      real(dp), allocatable :: h(:), ref(:)
      real(dp), parameter :: tols(6) = [1e-3_dp, 1e-5_dp, 1e-7_dp, 1e-9_dp, 1e-11_dp, &
         & 1e-13_dp]
      real(dp) :: t, e
      integer :: it
      logical :: ok
      call read_reference("doc/bench/fn_reference.csv", h, ref, ok)
      if (.not. ok) then
         write (output_unit, '(a)') "F_n section skipped: doc/bench/fn_reference.csv missing"// &
            & " (python3 tools/bench/fn_reference.py)"
         return
      end if
      write (output_unit, '(/a)') "== F_3/2(h): time per call vs error (64 h in [-6, 8];"// &
         & " error vs 40-digit mpmath)"
      call time_path(1, 0.0_dp, h, ref, t, e)
      call write_row(unit, "F_n", "fitted kernel", "F_3/2 h in [-6:8]", "-", t, e, &
         & "mpmath 40 digits", 0, "")
      call time_path(2, 0.0_dp, h, ref, t, e)
      call write_row(unit, "F_n", "general-order quadrature", "F_3/2 h in [-6:8]", "-", t, e, &
         & "mpmath 40 digits", 0, "")
      do it = 1, size(tols)
         call time_path(3, tols(it), h, ref, t, e)
         call write_row(unit, "F_n", "naive adaptive Simpson", "F_3/2 h in [-6:8]", &
            & "tol="//fmt_s(tols(it)), t, e, "mpmath 40 digits", 0, "")
      end do
   end subroutine run_fn

   subroutine read_reference(path, h, ref, ok)
      character(len=*), intent(in) :: path
      real(dp), allocatable, intent(out) :: h(:), ref(:)
      logical, intent(out) :: ok
      integer :: unit, ios
      character(len=256) :: line
      real(dp) :: a, b
      allocate (h(0), ref(0))
      ok = .false.
      open (newunit=unit, file=path, status="old", action="read", iostat=ios)
      if (ios /= 0) return
      do
         read (unit, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:1) == "#" .or. line(1:1) == "h") cycle
         read (line, *) a, b
         h = [h, a]
         ref = [ref, b]
      end do
      close (unit)
      ok = size(h) > 0
   end subroutine read_reference

   !> Mean time per call (best of 5 passes over all h, enough sweeps for >= 20 ms) and the
   !> max relative error of path `which`.
   subroutine time_path(which, tol, h, ref, t, e)
      integer, intent(in) :: which
      real(dp), intent(in) :: tol, h(:), ref(:)
      real(dp), intent(out) :: t, e
      real(dp) :: acc, t0, el, v(size(h))
      integer :: r, s, j, sweeps
      do j = 1, size(h)
         v(j) = eval(which, tol, h(j))
      end do
      e = maxval(abs(v/ref - 1))
      ! calibrate the sweeps to ~20 ms
      sweeps = 1
      do
         t0 = wall()
         acc = sweep(sweeps)
         el = wall() - t0
         if (el > 0.02_dp .or. sweeps > 1000000) exit
         sweeps = sweeps*4
      end do
      t = huge(1.0_dp)
      do r = 1, 5
         t0 = wall()
         acc = acc + sweep(sweeps)
         t = min(t, (wall() - t0)/real(sweeps*size(h), dp))
      end do
      if (acc == -1.0_dp) write (output_unit, *) acc
   contains
      real(dp) function sweep(n) result(a)
         integer, intent(in) :: n
         a = 0
         do s = 1, n
            do j = 1, size(h)
               a = a + eval(which, tol, h(j))
            end do
         end do
      end function sweep
   end subroutine time_path

   real(dp) function eval(which, tol, h) result(f)
      integer, intent(in) :: which
      real(dp), intent(in) :: tol, h
      select case (which)
      case (1)
         f = gauss_integral(1.5_dp, h)
      case (2)
         f = gauss_integral(nearest(1.5_dp, 2.0_dp), h)
      case default
         f = simpson_fn(h, tol)
      end select
   end function eval

   !> Naive baseline: adaptive Simpson of int_0^L x^1.5 phi(x + h) dx with L = max(0,-h)
   !> + 12 (phi beyond 12 is < 1e-31 of the peak); the absolute tolerance is tol times a
   !> first 16-panel estimate of the integral.
   real(dp) function simpson_fn(h, tol) result(f)
      real(dp), intent(in) :: h, tol
      real(dp) :: upper, coarse, a, b, fa, fm, fb
      integer :: i
      integer, parameter :: n0 = 16
      upper = max(0.0_dp, -h) + 12
      coarse = 0
      do i = 0, n0 - 1
         a = upper*i/n0
         b = upper*(i + 1)/n0
         coarse = coarse + (b - a)/6*(g(a) + 4*g(0.5_dp*(a + b)) + g(b))
      end do
      f = 0
      do i = 0, n0 - 1
         a = upper*i/n0
         b = upper*(i + 1)/n0
         fa = g(a)
         fm = g(0.5_dp*(a + b))
         fb = g(b)
         f = f + adapt(a, b, fa, fm, fb, (b - a)/6*(fa + 4*fm + fb), &
            & tol*abs(coarse)/n0, 0)
      end do
   contains
      real(dp) function g(x)
         real(dp), intent(in) :: x
         g = x*sqrt(x)*inv_sqrt2pi*exp(-0.5_dp*(x + h)**2)
      end function g
      recursive real(dp) function adapt(a, b, fa, fm, fb, whole, eps, depth) result(s)
         real(dp), intent(in) :: a, b, fa, fm, fb, whole, eps
         integer, intent(in) :: depth
         real(dp) :: m, lm, rm, flm, frm, left, right
         m = 0.5_dp*(a + b)
         lm = 0.5_dp*(a + m)
         rm = 0.5_dp*(m + b)
         flm = g(lm)
         frm = g(rm)
         left = (m - a)/6*(fa + 4*flm + fm)
         right = (b - m)/6*(fm + 4*frm + fb)
         if (depth >= 40 .or. abs(left + right - whole) <= 15*eps) then
            s = left + right + (left + right - whole)/15
         else
            s = adapt(a, m, fa, flm, fm, left, 0.5_dp*eps, depth + 1) + &
               & adapt(m, b, fm, frm, fb, right, 0.5_dp*eps, depth + 1)
         end if
      end function adapt
   end function simpson_fn

end module bench_fn
