!> CalculiX/Abaqus `*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR` curves (doc/formats.md).
!> The CalculiX submodule of egw_table_format (src/egw/formats/table_format.f90), whose
!> interface block declares the entry points implemented here.
submodule (egw_table_format) egw_table_format_calculix
   implicit none

   ! CalculiX reads only the first 20 characters of a field: numbers as ES20.12E3, 13
   ! significant digits (relative rounding <= 5e-13, below every rel_tol a curve can be
   ! asked for)

   !> What resample_linear samples: the force of a table against overlap, or the
   !> rough-flat pressure against overclosure (a type, not an internal procedure, so no
   !> trampoline / executable stack is needed).
   type :: sampler
      type(force_table), pointer :: table => null()
      type(contact_params) :: params
      logical :: flat = .false.
      integer :: stat = egw_ok
   end type sampler

contains

   module procedure write_calculix_sphere
      real(dp), allocatable :: x(:), y(:)
      real(dp) :: achieved, origin
      type(text_buffer) :: out
      type(sampler) :: smp
      logical :: shifted
      shifted = .false.
      if (present(shift)) shifted = shift
      smp%table => t
      call fit_pairs(smp, t%cutoff, t%delta_max, t%rel_tol, t%rel_tol*t%reference_force, &
         & x, y, achieved)
      if (present(max_error)) max_error = achieved
      if (smp%stat /= egw_ok) then
         call fatal_error(error, smp%stat, "table: force not finite; nothing written")
         return
      end if
      y(1) = 0.0_dp
      origin = 0.0_dp
      if (shifted) origin = t%cutoff
      call out%add("** egw "//egw_version_string//": rough-sphere contact, model "// &
         & model_name(t%params%model)//", R = "//fmt(t%params%radius)//", E = "// &
         & fmt(t%params%modulus)//", sigma = "//fmt(t%params%sigma)//", mu = "// &
         & fmt(t%params%mu))
      if (t%params%model == model_epgw) call out%add("** EP-GW: the LOADING curve "// &
         & "only (a pressure-overclosure curve has no history: no unloading hysteresis)")
      if (shifted) then
         call out%add("** node-to-surface contact: FORCE per node against "// &
            & "overclosure = delta - delta_c (shifted: overlap delta = overclosure + "// &
            & fmt(t%cutoff)//"); force 0 below overclosure 0")
      else
         call out%add("** node-to-surface contact: FORCE per node against "// &
            & "overclosure (= overlap delta); force 0 below overclosure "//fmt(t%cutoff))
      end if
      call write_error_comment(out, t%rel_tol, achieved, size(x))
      call write_pairs(out, x - origin, y, error)
      if (allocated(error)) return
      call out%write(path, error)
   end procedure write_calculix_sphere

   module procedure write_calculix_flat
      real(dp), allocatable :: x(:), y(:)
      real(dp) :: p0, dp0, pc, d_c, step, achieved, origin
      integer :: it
      type(text_buffer) :: out
      type(sampler) :: smp
      logical :: shifted

      shifted = .false.
      if (present(shift)) shifted = shift
      call validate_params(params, error)
      if (allocated(error)) return
      if (.not. params%sigma > 0.0_dp) then
         call fatal_error(error, egw_invalid_parameter, "sigma = "//format_real(params%sigma)// &
            & ": a rough flat needs sigma > 0")
         return
      end if
      ! A pressure-overclosure curve is reversible: it cannot carry the cap's plastic flow,
      ! and p_G beyond p_y written without a word misled (audit29); the FE model's material
      ! carries a bulk's yield.
      if (params%flow_pressure > 0.0_dp) then
         call fatal_error(error, egw_invalid_parameter, "flow_pressure = " &
            & //format_real(params%flow_pressure)//": a CalculiX pressure-overclosure " &
            & //"curve is the rough flat's reversible law p_G(d) and cannot hold the " &
            & //"flow-pressure cap (bulk yield belongs to the FE model's material); " &
            & //"flow_pressure = 0 for the curve")
         return
      end if
      if (.not. (rel_tol >= 1.0e-12_dp .and. rel_tol <= 0.1_dp)) then
         call fatal_error(error, egw_invalid_argument, "rel_tol = "//format_real(rel_tol)// &
            & ": must lie in [1e-12, 0.1]")
         return
      end if
      if (.not. (ieee_is_finite(overclosure_max) .and. overclosure_max > 0.0_dp)) then
         call fatal_error(error, egw_invalid_argument, "overclosure_max = "// &
            & format_real(overclosure_max)//": must be finite and > 0")
         return
      end if
      call flat_pressure(params, 0.0_dp, p0, dp0, error)
      if (allocated(error)) return
      ! separation where p_G falls below rel_tol * p_G(0): step out by sigma
      d_c = 0.0_dp
      step = params%sigma
      do it = 1, 200
         d_c = d_c + step
         call flat_pressure(params, d_c, pc, dp0, error)
         if (allocated(error)) return
         if (pc <= rel_tol*p0) exit
      end do
      smp%params = params
      smp%flat = .true.
      call fit_pairs(smp, -d_c, overclosure_max, rel_tol, rel_tol*p0, x, y, achieved)
      if (present(max_error)) max_error = achieved
      if (smp%stat /= egw_ok) then
         call fatal_error(error, smp%stat, "flat_pressure failed while sampling p_G")
         return
      end if
      y(1) = 0.0_dp
      origin = 0.0_dp
      if (shifted) origin = -d_c
      call out%add("** egw "//egw_version_string//": rough flat, GW nominal "// &
         & "pressure p_G (doc/theory.md section 3), model "//model_name(params%model)// &
         & ", E = "//fmt(params%modulus)//", sigma = "//fmt(params%sigma)//", mu = "// &
         & fmt(params%mu)//", R = "//fmt(params%radius)//", psi = "//fmt(params%psi))
      if (shifted) then
         call out%add("** PRESSURE against overclosure = d_c - separation of the "// &
            & "summit base plane, d_c = "//fmt(d_c)//" (shifted); pressure 0 for "// &
            & "overclosure < 0")
      else
         call out%add("** PRESSURE against overclosure = -separation of the summit "// &
            & "base plane; pressure 0 for overclosure < "//fmt(-d_c))
      end if
      call write_error_comment(out, rel_tol, achieved, size(x))
      call write_pairs(out, x - origin, y, error)
      if (allocated(error)) return
      call out%write(path, error)
   end procedure write_calculix_flat

   !> Header lines on the interpolation error achieved (and a warning if above rel_tol).
   subroutine write_error_comment(out, rel_tol, achieved, n)
      type(text_buffer), intent(inout) :: out
      integer, intent(in) :: n
      real(dp), intent(in) :: rel_tol, achieved
      call out%add("** linear interpolation between pairs within rel_tol = "// &
         & fmt(rel_tol)//" requested; max error achieved = "//fmt(achieved)// &
         & " (relative to max(|value|, rel_tol*reference)); "//int_str(n)//" pairs")
      if (achieved > rel_tol) call out%add("** WARNING: rel_tol not met within "// &
         & "CalculiX's limit of "//int_str(calculix_max_pairs)//" pairs per curve")
   end subroutine write_error_comment

   subroutine write_pairs(out, x, y, error)
      type(text_buffer), intent(inout) :: out
      real(dp), intent(in) :: x(:), y(:)
      type(egw_error), allocatable, intent(out) :: error
      integer :: i
      call out%add("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TABULAR")
      do i = 1, size(x)
         if (.not. row_ok([x(i), y(i)])) then
            call fatal_error(error, egw_invalid_argument, "value at overclosure "// &
               & format_real(x(i))//" is not finite; nothing written")
            return
         end if
         call out%add(fmt20(y(i))//", "//fmt20(x(i)))
      end do
   end subroutine write_pairs

   !> At most calculix_max_pairs points on [a, b] for linear interpolation of g. First
   !> the bisection of resample_linear at rel_tol; if that needs more points, they are
   !> placed by equidistributing the interpolation error: on the fine bisection grid
   !> interval j has midpoint error e_j ~ c h_j^2, so covering it with m_j intervals
   !> gives e_j/m_j^2, and the largest error over the curve is smallest when m_j is
   !> proportional to sqrt(e_j): the new points split the cumulative sum of sqrt(e_j)
   !> equally. achieved = the largest midpoint error of the result, relative to
   !> max(|g|, floor) (floor = rel_tol * the curve's reference value: the tail below it
   !> needs only absolute accuracy).
   subroutine fit_pairs(g, a, b, rel_tol, floor, x, y, achieved)
      type(sampler), intent(inout) :: g
      real(dp), intent(in) :: a, b, rel_tol, floor
      real(dp), allocatable, intent(out) :: x(:), y(:)
      real(dp), intent(out) :: achieved
      real(dp), allocatable :: xf(:), yf(:), w(:)
      real(dp) :: target, frac
      integer :: nf, j, k
      call resample_linear(g, a, b, rel_tol, xf, yf)
      nf = size(xf)
      if (g%stat /= egw_ok) return
      if (nf <= calculix_max_pairs) then
         call move_alloc(xf, x)
         call move_alloc(yf, y)
      else
         allocate (w(0:nf - 1))
         w(0) = 0.0_dp
         do j = 1, nf - 1
            w(j) = w(j - 1) + sqrt(midpoint_error(g, xf(j), xf(j + 1), yf(j), yf(j + 1), &
               & floor))
         end do
         allocate (x(calculix_max_pairs), y(calculix_max_pairs))
         x(1) = a
         x(calculix_max_pairs) = b
         j = 1
         do k = 2, calculix_max_pairs - 1
            target = w(nf - 1)*(k - 1)/(calculix_max_pairs - 1)
            do while (w(j) < target .and. j < nf - 1)
               j = j + 1
            end do
            ! target lies in fine interval j: w(j-1) <= target <= w(j)
            frac = 0.5_dp
            if (w(j) > w(j - 1)) frac = (target - w(j - 1))/(w(j) - w(j - 1))
            x(k) = xf(j) + frac*(xf(j + 1) - xf(j))
         end do
         ! keep the points strictly increasing (plateaus of w can stack them)
         do k = 2, calculix_max_pairs - 1
            x(k) = max(x(k), x(k - 1) + 1.0e-9_dp*(b - a))
         end do
         do k = 1, calculix_max_pairs
            y(k) = sample(g, x(k))
         end do
         call equalise_errors(g, floor, x, y)
      end if
      achieved = 0.0_dp
      do k = 1, size(x) - 1
         achieved = max(achieved, midpoint_error(g, x(k), x(k + 1), y(k), y(k + 1), floor))
      end do
   end subroutine fit_pairs

   !> A few passes of de Boor's equidistribution on the points themselves: interval k
   !> with midpoint error e_k would need sqrt(e_k/eps) intervals for error eps, so the
   !> points are moved to split the cumulative sum of sqrt(e_k) (linear within each
   !> interval) equally. The fine-grid estimate of fit_pairs is only a start (its
   !> errors are sampled once per fine interval); the best set of the passes is kept.
   subroutine equalise_errors(g, floor, x, y)
      type(sampler), intent(inout) :: g
      real(dp), intent(in) :: floor
      real(dp), intent(inout) :: x(:), y(:)
      real(dp) :: w(0:size(x) - 1), xn(size(x)), yn(size(x)), xo(size(x)), best, worst, e, &
         & target, frac
      integer :: n, pass, k, j
      n = size(x)
      best = huge(1.0_dp)
      xn = x
      yn = y
      do pass = 1, 8
         w(0) = 0.0_dp
         worst = 0.0_dp
         do k = 1, n - 1
            e = midpoint_error(g, xn(k), xn(k + 1), yn(k), yn(k + 1), floor)
            worst = max(worst, e)
            w(k) = w(k - 1) + sqrt(e)
         end do
         if (worst < best) then
            best = worst
            x = xn
            y = yn
         end if
         if (pass == 8 .or. .not. w(n - 1) > 0.0_dp) exit
         ! new points from the current set (the weights belong to it)
         xo = xn
         j = 1
         do k = 2, n - 1
            target = w(n - 1)*(k - 1)/(n - 1)
            do while (w(j) < target .and. j < n - 1)
               j = j + 1
            end do
            frac = 0.5_dp
            if (w(j) > w(j - 1)) frac = (target - w(j - 1))/(w(j) - w(j - 1))
            xn(k) = xo(j) + frac*(xo(j + 1) - xo(j))
         end do
         do k = 2, n - 1
            xn(k) = max(xn(k), xn(k - 1) + 1.0e-9_dp*(x(n) - x(1)))
         end do
         do k = 1, n
            yn(k) = sample(g, xn(k))
         end do
      end do
   end subroutine equalise_errors

   !> |linear interpolant - g| at the midpoint of [xl, xr], relative to max(|g|, floor).
   real(dp) function midpoint_error(g, xl, xr, yl, yr, floor) result(e)
      type(sampler), intent(inout) :: g
      real(dp), intent(in) :: xl, xr, yl, yr, floor
      real(dp) :: ym
      ym = sample(g, 0.5_dp*(xl + xr))
      e = abs(0.5_dp*(yl + yr) - ym)/max(abs(ym), floor, tiny(1.0_dp))
   end function midpoint_error

   !> Points on [a, b] such that linear interpolation of g has midpoint error
   !> <= rel_tol * |g(mid)| (bisection; at most max_export_points points).
   subroutine resample_linear(g, a, b, rel_tol, x, y)
      type(sampler), intent(inout) :: g
      real(dp), intent(in) :: a, b, rel_tol
      real(dp), allocatable, intent(out) :: x(:), y(:)
      real(dp), allocatable :: sx(:), sy(:)
      integer :: n, top
      real(dp) :: xl, yl, xr, yr, xm, ym
      ! depth-first bisection with an explicit stack of right ends
      allocate (x(1024), y(1024), sx(200), sy(200))
      n = 1
      x(1) = a
      y(1) = sample(g, a)
      top = 1
      sx(1) = b
      sy(1) = sample(g, b)
      do while (top > 0)
         xl = x(n); yl = y(n)
         xr = sx(top); yr = sy(top)
         xm = 0.5_dp*(xl + xr)
         ym = sample(g, xm)
         if (.not. ieee_is_finite(ym)) then
            if (g%stat == egw_ok) g%stat = egw_invalid_argument
            exit
         end if
         if (abs(0.5_dp*(yl + yr) - ym) > rel_tol*abs(ym) .and. top < size(sx) .and. &
            & n < max_export_points .and. xm > xl .and. xm < xr) then
            top = top + 1
            sx(top) = xm
            sy(top) = ym
         else
            if (n == size(x)) then
               x = [x, x]
               y = [y, y]
            end if
            n = n + 1
            x(n) = xr
            y(n) = yr
            top = top - 1
         end if
      end do
      x = x(1:n)
      y = y(1:n)
   end subroutine resample_linear

   !> Value of the sampled curve at x (records a failure of flat_pressure in g%stat).
   real(dp) function sample(g, x)
      type(sampler), intent(inout) :: g
      real(dp), intent(in) :: x
      real(dp) :: k
      type(egw_error), allocatable :: e
      if (g%flat) then
         call flat_pressure(g%params, -x, sample, k, e)
         if (allocated(e) .and. g%stat == egw_ok) g%stat = e%stat
      else
         call table_eval(g%table, x, sample, k)
      end if
   end function sample

   !> 20 characters at most (CalculiX fields), 13 significant digits.
   pure function fmt20(x) result(str)
      real(dp), intent(in) :: x
      character(len=real_text_len(x, 12, 3)) :: str
      str = real_text(x, 12, 3)  ! ES20.12E3
   end function fmt20

end submodule egw_table_format_calculix
