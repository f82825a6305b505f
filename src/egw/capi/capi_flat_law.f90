!> The C API of rough-flat laws (include/egw.h, "Rough-flat laws"): the opaque handle
!> egw_flat_law (c_loc of an allocated table_flat_law, released by egw_flat_law_free),
!> made from a table of (u, p); evaluated; a sphere solve that takes one.
module egw_capi_flat_law
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_associated, c_f_pointer, &
      & c_loc
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_ok, egw_unsupported, egw_invalid_parameter, &
      & fatal_error, format_real, int_str
   use egw_params, only: contact_params
   use egw_flat_law, only: flat_law, table_flat_law, new_table_law
   use egw_rough_sphere, only: solver_options, solve_result, solve_contact_law
   use egw_table, only: force_table, build_table_law
   use egw_flat_law_format, only: write_flat_law, read_flat_law
   use egw_flat_persson, only: persson_flat_curve, persson_options, psd_rms_height
   use egw_flat_bem, only: bem_flat_curve, bem_options
   use egw_capi_utils, only: settle, require, invalid, failure, check_number, &
      & double_array, read_contact, put, put_handle_settled, take_handle, put_result, c_path, &
      & read_options
   implicit none
   private

   !> Mean pressures a decade of the laws made from a PSD or a map.
   integer, parameter :: per_decade = 10

   public :: egw_flat_law_from_table, egw_flat_law_pressure, egw_flat_law_contact_area, &
      & egw_flat_law_info, egw_flat_law_free, egw_solve_flat_law, egw_table_build_flat_law, &
      & egw_flat_law_write, egw_flat_law_read, egw_flat_law_from_psd, &
      & egw_flat_law_from_heights, egw_flat_law_rescale

contains

   !> C: egw_flat_law_from_table: a tabulated law from n nodes (u, p), optional dp/du and
   !> contact-area fraction (NULL: none), its length (0: from the table) and E* (0: not
   !> known).
   function egw_flat_law_from_table(u, p, dpdu, area, n, length, modulus, out) result(stat) &
      & bind(C, name="egw_flat_law_from_table")
      !> C: `const double *u`; `const double *p`; `const double *dpdu`; `const double
      !> *area`; `egw_flat_law *out` (the new handle)
      type(c_ptr), value, intent(in) :: u, p, dpdu, area, out
      integer(c_int), value, intent(in) :: n   !< C: `int n`
      real(c_double), value, intent(in) :: length, modulus   !< C: `double length`; `double modulus`
      integer(c_int) :: stat
      type(table_flat_law), pointer :: law
      type(egw_error), allocatable :: error
      real(c_double), pointer :: uu(:), pp(:), dd(:), aa(:)
      stat = require(out, "out")
      if (stat == egw_ok) stat = require(u, "u")
      if (stat == egw_ok) stat = require(p, "p")
      if (stat /= egw_ok) return
      if (n < 2) then
         stat = invalid("n = "//int_str(int(n))//": a tabulated flat law needs n >= 2 nodes")
         return
      end if
      uu => double_array(u, n)
      pp => double_array(p, n)
      dd => double_array(dpdu, n)
      aa => double_array(area, n)
      allocate (law)
      ! (a disassociated pointer is an absent optional argument, Fortran 2008)
      call new_table_law(uu, pp, law, error, dpdu=dd, area=aa, length=length, &
         & modulus=modulus)
      stat = put_handle_settled(out, c_loc(law), error)
      if (stat /= egw_ok) deallocate (law)
   end function egw_flat_law_from_table

   !> C: egw_flat_law_rescale: the same law in other units (separations divided by
   !> unit_length, pressures by pressure_unit; its length and E* with them).
   function egw_flat_law_rescale(h, unit_length, pressure_unit, out) result(stat) &
      & bind(C, name="egw_flat_law_rescale")
      !> C: `egw_flat_law law`; `egw_flat_law *out` (the new handle)
      type(c_ptr), value, intent(in) :: h, out
      !> C: `double unit_length`; `double pressure_unit`
      real(c_double), value, intent(in) :: unit_length, pressure_unit
      integer(c_int) :: stat
      type(table_flat_law), pointer :: law, scaled
      class(flat_law), allocatable :: s
      type(egw_error), allocatable :: error
      stat = require(out, "out")
      if (stat == egw_ok) stat = require(h, "law")
      if (stat /= egw_ok) return
      ! (units the law's numbers survive: beyond them ln p or u would overflow)
      if (.not. (unit_length >= 1.0e-100_dp .and. unit_length <= 1.0e100_dp)) then
         stat = invalid("unit_length = "//format_real(unit_length)//": must lie in " &
            & //"[1e-100, 1e100]")
      else if (.not. (pressure_unit >= 1.0e-100_dp .and. pressure_unit <= 1.0e100_dp)) then
         stat = invalid("pressure_unit = "//format_real(pressure_unit)//": must lie in " &
            & //"[1e-100, 1e100]")
      end if
      if (stat /= egw_ok) return
      call c_f_pointer(h, law)
      call law%rescaled(unit_length, pressure_unit, s)
      allocate (scaled)
      select type (s)
      type is (table_flat_law)
         scaled = s
      end select
      stat = put_handle_settled(out, c_loc(scaled), error)
      if (stat /= egw_ok) deallocate (scaled)
   end function egw_flat_law_rescale

   !> C: egw_flat_law_from_psd: Persson's law of an isotropic PSD (q, C).
   function egw_flat_law_from_psd(q, c, n, modulus, p_min, p_max, out) result(stat) &
      & bind(C, name="egw_flat_law_from_psd")
      !> C: `const double *q`; `const double *C`; `egw_flat_law *out` (the new handle)
      type(c_ptr), value, intent(in) :: q, c, out
      integer(c_int), value, intent(in) :: n   !< C: `int n`
      !> C: `double modulus`; `double p_min`; `double p_max`
      real(c_double), value, intent(in) :: modulus, p_min, p_max
      integer(c_int) :: stat
      type(egw_error), allocatable :: error
      real(c_double), pointer :: qq(:), cc(:)
      real(dp), allocatable :: u(:), p(:), area(:), dpdu(:)
      real(dp) :: lo, hi
      stat = require(out, "out")
      if (stat == egw_ok) stat = require(q, "q")
      if (stat == egw_ok) stat = require(c, "C")
      if (stat /= egw_ok) return
      if (n < 2) then
         stat = invalid("n = "//int_str(int(n))//": a PSD needs n >= 2 nodes (q, C)")
         return
      end if
      qq => double_array(q, n)
      cc => double_array(c, n)
      call pressure_range(modulus, p_min, p_max, lo, hi)
      call persson_flat_curve(qq, cc, modulus, lo, hi, per_decade, persson_options(), u, p, &
         & area, dpdu, error)
      if (.not. allocated(error)) stat = made(u, p, dpdu, area, psd_rms_height(qq, cc), &
         & modulus, out, error)
      if (allocated(error)) stat = settle(error)
   end function egw_flat_law_from_psd

   !> C: egw_flat_law_from_heights: egw's periodic BEM law of a height map.
   function egw_flat_law_from_heights(heights, nx, ny, pixel, modulus, p_min, p_max, o, out) &
      & result(stat) bind(C, name="egw_flat_law_from_heights")
      !> C: `const double *heights`; `const egw_options *o` (solver options, NULL: the
      !> defaults); `egw_flat_law *out` (the new handle)
      type(c_ptr), value, intent(in) :: heights, o, out
      integer(c_int), value, intent(in) :: nx, ny   !< C: `int nx`; `int ny`
      !> C: `double pixel`; `double modulus`; `double p_min`; `double p_max`
      real(c_double), value, intent(in) :: pixel, modulus, p_min, p_max
      integer(c_int) :: stat
      type(egw_error), allocatable :: error
      real(c_double), pointer :: h(:, :)
      type(bem_options) :: opts
      type(solver_options) :: options
      real(dp), allocatable :: u(:), p(:), area(:), k(:)
      real(dp) :: lo, hi, rms
      stat = require(out, "out")
      if (stat == egw_ok) stat = require(heights, "heights")
      if (stat /= egw_ok) return
      if (nx < 2 .or. ny < 2) then
         stat = invalid("nx = "//int_str(int(nx))//", ny = "//int_str(int(ny)) &
            & //": a height map needs at least 2 x 2 pixels")
         return
      end if
      call read_options(o, options)
      opts%n_threads = options%n_threads
      call c_f_pointer(heights, h, [nx, ny])
      call pressure_range(modulus, p_min, p_max, lo, hi)
      ! scales the solver's pressures, compliances and sweep represent (beyond them it
      ! would overflow or sweep for ever: a range of 1e300 is 3000 loads)
      if (.not. (pixel >= 1.0e-100_dp .and. pixel <= 1.0e100_dp)) then
         stat = invalid("pixel = "//format_real(pixel)//": must lie in [1e-100, 1e100]")
      else if (.not. (modulus >= 1.0e-100_dp .and. modulus <= 1.0e100_dp)) then
         stat = invalid("modulus = "//format_real(modulus)//": must lie in [1e-100, 1e100]")
      else if (.not. (lo >= 1.0e-12_dp*modulus .and. hi <= modulus .and. hi > lo)) then
         stat = invalid("p_min = "//format_real(lo)//", p_max = "//format_real(hi) &
            & //": the pressures must lie in [1e-12 E*, E*] with p_min < p_max")
      end if
      if (stat /= egw_ok) return
      call bem_flat_curve(h, pixel, modulus, lo, hi, per_decade, opts, u, p, area, k, error)
      if (.not. allocated(error)) then
         if (size(u) < 2) then
            stat = failure(egw_unsupported, "heights: the map is in full contact at " &
               & //"p_min = "//format_real(lo)//" already: no law (lower p_min)")
            return
         end if
         rms = sqrt(sum((h - sum(h)/size(h))**2)/size(h))
         stat = made(u, p, -k, area, rms, modulus, out, error)
      end if
      if (allocated(error)) stat = settle(error)
   end function egw_flat_law_from_heights

   !> The default range p/E* in [1e-6, 1e-1] where p_min or p_max is 0.
   pure subroutine pressure_range(modulus, p_min, p_max, lo, hi)
      real(dp), intent(in) :: modulus, p_min, p_max
      real(dp), intent(out) :: lo, hi
      lo = p_min
      hi = p_max
      if (lo == 0.0_dp) lo = 1.0e-6_dp*modulus
      if (hi == 0.0_dp) hi = 1.0e-1_dp*modulus
   end subroutine pressure_range

   !> A law from a curve of decreasing u (Persson, BEM): nodes reversed to ascending u;
   !> the handle at *out (status), or error set.
   integer(c_int) function made(u, p, dpdu, area, length, modulus, out, error) result(stat)
      real(dp), intent(in) :: u(:), p(:), dpdu(:), area(:), length, modulus
      type(c_ptr), intent(in) :: out
      type(egw_error), allocatable, intent(out) :: error
      type(table_flat_law), pointer :: law
      integer :: n
      n = size(u)
      allocate (law)
      call new_table_law(u(n:1:-1), p(n:1:-1), law, error, dpdu=dpdu(n:1:-1), &
         & area=area(n:1:-1), length=length, modulus=modulus)
      stat = put_handle_settled(out, c_loc(law), error)
      if (stat /= egw_ok) deallocate (law)
   end function made

   !> C: egw_flat_law_pressure: p and dp/du at the mean separation u.
   function egw_flat_law_pressure(h, u, pressure, dpdu) result(stat) &
      & bind(C, name="egw_flat_law_pressure")
      !> C: `egw_flat_law law`; `double *pressure` (out); `double *dpdu` (out)
      type(c_ptr), value, intent(in) :: h, pressure, dpdu
      real(c_double), value, intent(in) :: u   !< C: `double u`
      integer(c_int) :: stat
      type(table_flat_law), pointer :: law
      real(dp) :: p(1), d(1)
      stat = require(h, "law")
      if (stat == egw_ok) stat = check_number("u", u)
      if (stat /= egw_ok) return
      call c_f_pointer(h, law)
      call law%pressure([u], p, d)
      if (p(1) >= huge(1.0_dp) .or. d(1) <= -huge(1.0_dp)) then
         stat = invalid("u = "//format_real(u)//": the law's pressure or its derivative " &
            & //"there is beyond the doubles")
         return
      end if
      call put(pressure, p(1))
      call put(dpdu, d(1))
   end function egw_flat_law_pressure

   !> C: egw_flat_law_contact_area: the contact-area fraction at u (laws that carry one).
   function egw_flat_law_contact_area(h, u, area) result(stat) &
      & bind(C, name="egw_flat_law_contact_area")
      type(c_ptr), value, intent(in) :: h, area   !< C: `egw_flat_law law`; `double *area` (out)
      real(c_double), value, intent(in) :: u   !< C: `double u`
      integer(c_int) :: stat
      type(table_flat_law), pointer :: law
      real(dp) :: a
      stat = require(h, "law")
      if (stat == egw_ok) stat = check_number("u", u)
      if (stat /= egw_ok) return
      call c_f_pointer(h, law)
      a = law%contact_area(u)
      if (ieee_is_nan(a)) then
         stat = failure(egw_unsupported, "law: made without contact-area data (a table " &
            & //"without area): no contact area to give")
         return
      end if
      call put(area, a)
   end function egw_flat_law_contact_area

   !> C: egw_flat_law_info: nodes, length, E*, separation range and whether it has areas.
   function egw_flat_law_info(h, n_nodes, length, modulus, u_min, u_max, has_area) &
      & result(stat) bind(C, name="egw_flat_law_info")
      !> C: `egw_flat_law law`; `int *n_nodes` (out); `double *length` (out); `double
      !> *modulus` (out); `double *u_min` (out); `double *u_max` (out); `int *has_area`
      !> (out)
      type(c_ptr), value, intent(in) :: h, n_nodes, length, modulus, u_min, u_max, has_area
      integer(c_int) :: stat
      type(table_flat_law), pointer :: law
      integer(c_int), pointer :: ip
      stat = require(h, "law")
      if (stat /= egw_ok) return
      call c_f_pointer(h, law)
      if (c_associated(n_nodes)) then
         call c_f_pointer(n_nodes, ip)
         ip = int(size(law%u), c_int)
      end if
      if (c_associated(has_area)) then
         call c_f_pointer(has_area, ip)
         ip = merge(1_c_int, 0_c_int, allocated(law%area))
      end if
      call put(length, law%length())
      call put(modulus, law%modulus())
      call put(u_min, law%u(1))
      call put(u_max, law%u(size(law%u)))
   end function egw_flat_law_info

   !> C: egw_flat_law_free(egw_flat_law *law): releases the law, sets *law = NULL.
   subroutine egw_flat_law_free(h) bind(C, name="egw_flat_law_free")
      !> C: `egw_flat_law *law` (released, then set to NULL; NULL is fine)
      type(c_ptr), value, intent(in) :: h
      type(c_ptr) :: object
      type(table_flat_law), pointer :: law
      object = take_handle(h)
      if (.not. c_associated(object)) return
      call c_f_pointer(object, law)
      deallocate (law)
   end subroutine egw_flat_law_free

   !> C: egw_solve_flat_law: the sphere solve (R, E* of p) with the rough-flat law.
   function egw_solve_flat_law(p, h, o, delta, res) result(stat) &
      & bind(C, name="egw_solve_flat_law")
      !> C: `const egw_params *p` (the contact's parameters); `egw_flat_law law`; `const
      !> egw_options *o` (solver options, NULL: the defaults); `egw_result *res` (out)
      type(c_ptr), value, intent(in) :: p, h, o, res
      real(c_double), value, intent(in) :: delta   !< C: `double delta`
      integer(c_int) :: stat
      type(contact_params) :: params
      type(solver_options) :: options
      type(solve_result) :: result
      type(table_flat_law), pointer :: law
      type(egw_error), allocatable :: error
      stat = require(res, "res")
      if (stat == egw_ok) stat = require(h, "law")
      if (stat == egw_ok) stat = read_contact(p, o, params, options, allow_flat_law=.true.)
      if (stat /= egw_ok) return
      call c_f_pointer(h, law)
      call solve_contact_law(params, law, options, delta, result, error)
      stat = settle(error)
      if (stat == egw_ok) call put_result(res, result)
   end function egw_solve_flat_law

   !> C: egw_table_build_flat_law: a 1-D force table of the sphere pair with the law.
   function egw_table_build_flat_law(p, h, o, delta_min, delta_max, rel_tol, out) &
      & result(stat) bind(C, name="egw_table_build_flat_law")
      !> C: `const egw_params *p` (the contact's parameters); `egw_flat_law law`; `const
      !> egw_options *o` (solver options, NULL: the defaults); `egw_table *out` (the new
      !> handle)
      type(c_ptr), value, intent(in) :: p, h, o, out
      !> C: `double delta_min`; `double delta_max`; `double rel_tol`
      real(c_double), value, intent(in) :: delta_min, delta_max, rel_tol
      integer(c_int) :: stat
      type(contact_params) :: params
      type(solver_options) :: options
      type(table_flat_law), pointer :: law
      type(force_table), pointer :: t
      type(egw_error), allocatable :: error
      stat = require(out, "out")
      if (stat == egw_ok) stat = require(h, "law")
      if (stat == egw_ok) stat = read_contact(p, o, params, options, allow_flat_law=.true.)
      if (stat == egw_ok) stat = no_cap(params)
      if (stat /= egw_ok) return
      call c_f_pointer(h, law)
      allocate (t)
      call build_table_law(params, law, options, delta_min, delta_max, rel_tol, t, error)
      stat = put_handle_settled(out, c_loc(t), error)
      if (stat /= egw_ok) deallocate (t)
   end function egw_table_build_flat_law

   !> A law's force table has no flow-pressure cap (as egw_table_build's: a capped contact
   !> is a hysteresis table's): p%flow_pressure > 0 is refused naming it (the build dropped
   !> it, the uncapped law's table with EGW_OK; audit25). A law's solve takes the cap.
   integer(c_int) function no_cap(params) result(stat)
      type(contact_params), intent(in) :: params
      type(egw_error), allocatable :: error
      if (params%flow_pressure > 0.0_dp) call fatal_error(error, egw_invalid_parameter, &
         & "flow_pressure = "//format_real(params%flow_pressure)//": a rough-flat law's " &
         & //"force table has no flow-pressure cap (force tables refuse it; the law's " &
         & //"solve, egw_solve_flat_law, takes it): 0 for a table")
      stat = settle(error)
   end function no_cap

   !> C: egw_flat_law_write: the law as egw CSV (atomic).
   function egw_flat_law_write(h, path) result(stat) bind(C, name="egw_flat_law_write")
      !> C: `egw_flat_law law`; `const char *path` (NUL-terminated)
      type(c_ptr), value, intent(in) :: h, path
      integer(c_int) :: stat
      type(table_flat_law), pointer :: law
      character(len=:), allocatable :: fpath
      type(egw_error), allocatable :: error
      stat = require(h, "law")
      if (stat == egw_ok) stat = c_path(path, fpath)
      if (stat /= egw_ok) return
      call c_f_pointer(h, law)
      call write_flat_law(law, fpath, error)
      stat = settle(error)
   end function egw_flat_law_write

   !> C: egw_flat_law_read: a law from egw's CSV or a user's (u, pressure) CSV.
   function egw_flat_law_read(path, out) result(stat) bind(C, name="egw_flat_law_read")
      !> C: `const char *path` (NUL-terminated); `egw_flat_law *out` (the new handle)
      type(c_ptr), value, intent(in) :: path, out
      integer(c_int) :: stat
      character(len=:), allocatable :: fpath
      type(table_flat_law), pointer :: law
      type(egw_error), allocatable :: error
      stat = require(out, "out")
      if (stat == egw_ok) stat = c_path(path, fpath)
      if (stat /= egw_ok) return
      allocate (law)
      call read_flat_law(fpath, law, error)
      stat = put_handle_settled(out, c_loc(law), error)
      if (stat /= egw_ok) deallocate (law)
   end function egw_flat_law_read

end module egw_capi_flat_law
