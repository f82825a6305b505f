!> C API of the force tables (include/egw.h): opaque handles to Fortran table
!> objects (c_loc of an allocated object, released by egw_table_free /
!> egw_universal_free), build, evaluation, file output and input. Errors go through
!> egw_capi_utils' per-thread last-error message and argument checks.
module egw_capi_table
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_null_ptr, &
      & c_associated, c_f_pointer, c_loc
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
   use egw_progress, only: progress_begin, progress_end, progress_count
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_ok, egw_invalid_parameter, egw_out_of_range, &
      & egw_out_of_memory, format_real, int_str, tolerance_context
   use egw_params, only: contact_params, is_rough, model_flat_law
   use egw_rough_sphere, only: solver_options
   use egw_cache, only: build_table_cached, build_universal_cached
   use egw_table, only: force_table, table_eval, table_covers, table_energy, &
      & table_contact_radius, table_set_radii, table_is_ready
   use egw_table_tail, only: tail_last_node, resample_tails, tail_resample_tol, max_fine
   use egw_table_universal, only: universal_table, universal_eval, &
      & universal_slice
   use egw_table_format, only: write_table, read_table, write_universal, read_universal, &
      & write_calculix_flat, write_lammps, write_calculix_sphere
   use egw_capi_utils, only: egw_params_c, settle, require, invalid, failure, check_number, &
      & check_count, read_params, read_contact, put, put_settled, put_handle_settled, &
      & take_handle, double_array, c_path, above_delta_max, refuse_cap
   implicit none
   private

   !> Mirror of the C struct egw_table_info.
   type, bind(C) :: egw_table_info_c
      integer(c_int) :: model, n_nodes
      real(c_double) :: cutoff, delta_max, reference_force, rel_tol, max_force_error, &
         & max_stiffness_error
      integer(c_int) :: checksum_missing
   end type egw_table_info_c

   public :: egw_table_info_c

contains

   ! ------------------------------------------------------------ 1-D tables

   !> C: egw_table_build (see include/egw.h for units and statuses).
   function egw_table_build(p, o, delta_min, delta_max, rel_tol, out) result(stat) &
      & bind(C, name="egw_table_build")
      !> C: `const egw_params *p` (the contact's parameters); `const egw_options *o` (solver
      !> options, NULL: the defaults); `egw_table *out` (the new handle)
      type(c_ptr), value, intent(in) :: p, o, out
      !> C: `double delta_min`; `double delta_max`; `double rel_tol`
      real(c_double), value, intent(in) :: delta_min, delta_max, rel_tol
      integer(c_int) :: stat
      type(contact_params) :: params
      type(solver_options) :: options
      type(force_table), pointer :: t
      type(egw_error), allocatable :: error
      stat = require(out, "out")
      if (stat == egw_ok) stat = read_contact(p, o, params, options)
      if (stat /= egw_ok) return
      allocate (t)
      ! (flow_pressure is refused by the build, before any cache lookup)
      call progress_begin("table build")
      call build_table_cached(params, options, delta_min, delta_max, rel_tol, t, error, &
         & progress=progress_count)
      call progress_end("table build")
      stat = put_handle_settled(out, c_loc(t), error)
      if (stat /= egw_ok) deallocate (t)
   end function egw_table_build

   !> C: egw_table_eval; above delta_max returns EGW_OUT_OF_RANGE with values written.
   function egw_table_eval(h, delta, force, stiffness) result(stat) &
      & bind(C, name="egw_table_eval")
      !> C: `egw_table t`; `double *force` (out); `double *stiffness` (out)
      type(c_ptr), value, intent(in) :: h, force, stiffness
      real(c_double), value, intent(in) :: delta   !< C: `double delta`
      integer(c_int) :: stat
      type(force_table), pointer :: t
      real(c_double), pointer :: out
      real(dp) :: f, k
      ! lean: this is the per-contact hot path (a handle only comes from build or read,
      ! so it always holds a prepared table: no get_table), and good arguments pass an
      ! inline test, not the checks' calls (~1 ns of ~8)
      if (c_associated(h)) then
         call c_f_pointer(h, t)
         ! below a rough table's cut-off (or a Hertz table's 0), where the force is exactly
         ! 0 (table_prepare's zero_below): one comparison, EGW_OK, zeros
         if (delta < t%zero_below) then
            ! the stores written out, as below (put is a call into another module)
            stat = egw_ok
            if (c_associated(force)) then
               call c_f_pointer(force, out)
               out = 0.0_dp
            end if
            if (c_associated(stiffness)) then
               call c_f_pointer(stiffness, out)
               out = 0.0_dp
            end if
            return
         end if
      end if
      if (.not. c_associated(h) .or. ieee_is_nan(delta)) then
         stat = require(h, "t")
         if (stat == egw_ok) stat = check_number("delta", delta)
         return
      end if
      stat = egw_ok
      call c_f_pointer(h, t)
      call table_eval(t, delta, f, k)
      if (delta > t%delta_max) then
         ! the deep-overlap asymptote: +Inf or far enough to overflow is refused, untouched
         if (.not. (ieee_is_finite(f) .and. ieee_is_finite(k))) then
            stat = beyond(t, delta)
            return
         end if
         stat = out_of_range(t, delta)
      end if
      if (c_associated(force)) then
         call c_f_pointer(force, out)
         out = f
      end if
      if (c_associated(stiffness)) then
         call c_f_pointer(stiffness, out)
         out = k
      end if
   end function egw_table_eval

   !> C: egw_table_eval_array: egw_table_eval at n overlaps in one call (for callers such
   !> as Python/numpy that pay a high price per call). NaN refuses the whole call before
   !> any output is written; above delta_max the values are written and EGW_OUT_OF_RANGE
   !> names the first such overlap.
   function egw_table_eval_array(h, n, delta_ptr, force, stiffness) result(stat) &
      & bind(C, name="egw_table_eval_array")
      type(c_ptr), value, intent(in) :: h   !< C: `egw_table t`
      integer(c_int), value, intent(in) :: n   !< C: `int n`
      type(c_ptr), value, intent(in) :: delta_ptr   !< C: `const double *delta`
      !> C: `double *force` (out); `double *stiffness` (out)
      type(c_ptr), value, intent(in) :: force, stiffness
      integer(c_int) :: stat
      type(force_table), pointer :: t
      real(c_double), pointer :: f(:), k(:), delta(:)
      real(dp) :: fi, ki
      integer :: i, first_out
      stat = get_table(h, t)
      if (stat == egw_ok) stat = check_count(n)
      if (stat /= egw_ok .or. n == 0) return
      stat = require(delta_ptr, "delta")
      if (stat /= egw_ok) return
      delta => double_array(delta_ptr, n)
      stat = check_overlaps(t, delta)
      if (stat /= egw_ok) return
      f => double_array(force, n)
      k => double_array(stiffness, n)
      first_out = 0
      do i = 1, n
         call table_eval(t, delta(i), fi, ki)
         if (associated(f)) f(i) = fi
         if (associated(k)) k(i) = ki
         if (first_out == 0 .and. delta(i) > t%delta_max) first_out = i
      end do
      if (first_out > 0) stat = out_of_range(t, delta(first_out))
   end function egw_table_eval_array

   !> C: egw_table_eval_all (force, stiffness, energy, contact radius).
   function egw_table_eval_all(h, delta, force, stiffness, energy, contact_radius) &
      & result(stat) bind(C, name="egw_table_eval_all")
      !> C: `egw_table t`; `double *force` (out); `double *stiffness` (out); `double
      !> *energy` (out); `double *contact_radius` (out)
      type(c_ptr), value, intent(in) :: h, force, stiffness, energy, contact_radius
      real(c_double), value, intent(in) :: delta   !< C: `double delta`
      integer(c_int) :: stat
      type(force_table), pointer :: t
      real(dp) :: f, k, e, a
      stat = get_table(h, t)
      if (stat == egw_ok) stat = check_number("delta", delta)
      if (stat /= egw_ok) return
      call table_eval(t, delta, f, k)
      e = table_energy(t, delta)
      a = table_contact_radius(t, delta)
      if (.not. (ieee_is_finite(f) .and. ieee_is_finite(k) .and. ieee_is_finite(e) .and. &
         & ieee_is_finite(a))) then
         stat = beyond(t, delta)
         return
      end if
      call put(force, f)
      call put(stiffness, k)
      call put(energy, e)
      call put(contact_radius, a)
      if (.not. table_covers(t, delta)) stat = out_of_range(t, delta)
   end function egw_table_eval_all

   !> C: egw_table_get_info.
   function egw_table_get_info(h, info) result(stat) bind(C, name="egw_table_get_info")
      type(c_ptr), value, intent(in) :: h, info   !< C: `egw_table t`; `egw_table_info *info` (out)
      integer(c_int) :: stat
      type(force_table), pointer :: t
      type(egw_table_info_c), pointer :: ci
      stat = get_table(h, t)
      if (stat == egw_ok) stat = require(info, "info")
      if (stat /= egw_ok) return
      call c_f_pointer(info, ci)
      ci = egw_table_info_c(model=int(t%params%model, c_int), &
         & n_nodes=int(size(t%delta), c_int), cutoff=t%cutoff, delta_max=t%delta_max, &
         & reference_force=t%reference_force, rel_tol=t%rel_tol, &
         & max_force_error=t%max_force_error, max_stiffness_error=t%max_stiffness_error, &
         & checksum_missing=merge(1_c_int, 0_c_int, t%checksum_missing))
   end function egw_table_get_info

   !> C: egw_table_get_interpolant: the nodes and each interval's cubic (table%seg's
   !> layout unpacked) for callers that evaluate the table in their own inner loop.
   function egw_table_get_interpolant(h, capacity, nodes, coeffs, n_log) result(stat) &
      & bind(C, name="egw_table_get_interpolant")
      !> C: `egw_table t`; `double *nodes` (out); `double *coeffs` (out); `int *n_log` (out)
      type(c_ptr), value, intent(in) :: h, nodes, coeffs, n_log
      integer(c_int), value, intent(in) :: capacity   !< C: `int capacity`
      integer(c_int) :: stat
      type(force_table), pointer :: t
      real(c_double), pointer :: x(:), c(:)
      integer(c_int), pointer :: nl
      integer :: n, i
      stat = get_table(h, t)
      if (stat == egw_ok) stat = require(nodes, "nodes")
      if (stat == egw_ok) stat = require(coeffs, "coeffs")
      if (stat == egw_ok) stat = require(n_log, "n_log")
      if (stat /= egw_ok) return
      n = size(t%delta)
      if (capacity < n) then
         stat = invalid("capacity = "//int_str(int(capacity))//": below the table's "// &
            & int_str(n)//" nodes (egw_table_info.n_nodes; coeffs needs 4*(n_nodes-1))")
         return
      end if
      x => double_array(nodes, int(n, c_int))
      c => double_array(coeffs, int(4*(n - 1), c_int))
      call c_f_pointer(n_log, nl)
      x = t%seg(0, 1:n)
      do i = 1, n - 1
         c(4*i - 3:4*i) = t%seg(1:4, i)
      end do
      nl = int(t%n_log, c_int)
   end function egw_table_get_interpolant

   !> C: egw_table_get_tail: the separated tail's resampled pieces of n tables sharing their
   !> nodes (one table: its fine_seg, what egw_table_eval evaluates; several: egw_table_tail's
   !> rule on one grid), for callers that evaluate the tail in their own inner loop.
   function egw_table_get_tail(n, tables, capacity, starts, coeffs, n_pieces) result(stat) &
      & bind(C, name="egw_table_get_tail")
      integer(c_int), value, intent(in) :: n, capacity   !< C: `int n`; `int capacity`
      !> C: `const egw_table *tables`; `double *starts` (out); `double *coeffs` (out); `int
      !> *n_pieces` (out)
      type(c_ptr), value, intent(in) :: tables, starts, coeffs, n_pieces
      integer(c_int) :: stat
      type(c_ptr), pointer :: handles(:)
      real(dp), allocatable :: pieces(:, :)
      real(dp) :: tail_end
      real(c_double), pointer :: x(:), c(:)
      integer(c_int), pointer :: count
      integer :: n_fine, j
      stat = egw_ok
      if (n < 1) stat = invalid("n = "//int_str(int(n))//": need at least one table")
      ! (4 n n_pieces coefficients must be an int)
      if (n > huge(n)/(4*max_fine)) stat = invalid("n = "//int_str(int(n))// &
         & ": at most "//int_str(huge(1)/(4*max_fine))//" tables")
      if (stat == egw_ok) stat = require(tables, "tables")
      if (stat == egw_ok) stat = require(n_pieces, "n_pieces")
      if (stat == egw_ok .and. capacity < 0) stat = invalid("capacity = "// &
         & int_str(int(capacity))//": must be >= 0 (0: a size query)")
      if (stat == egw_ok .and. capacity > 0) stat = require(starts, "starts")
      if (stat == egw_ok .and. capacity > 0) stat = require(coeffs, "coeffs")
      if (stat /= egw_ok) return
      call c_f_pointer(tables, handles, [n])
      stat = tail_pieces(handles, pieces, n_fine, tail_end)
      if (stat /= egw_ok) return
      if (capacity > 0 .and. capacity < n_fine) then
         stat = invalid("capacity = "//int_str(int(capacity))//": below the tail's "// &
            & int_str(n_fine)//" pieces (capacity = 0 asks their number; starts needs "// &
            & "n_pieces + 1 doubles, coeffs 4 n n_pieces)")
         return
      end if
      call c_f_pointer(n_pieces, count)
      count = int(n_fine, c_int)
      if (capacity == 0) return
      x => double_array(starts, int(n_fine + 1, c_int))
      c => double_array(coeffs, int(4*size(pieces, 2), c_int))
      x(1:n_fine) = pieces(0, 1:size(pieces, 2):n)
      x(n_fine + 1) = tail_end
      do j = 1, size(pieces, 2)
         c(4*j - 3:4*j) = pieces(1:4, j)
      end do
   end function egw_table_get_tail

   !> C: egw_table_set_radii (R1, R2 consistent with the table's R).
   function egw_table_set_radii(h, radius1, radius2) result(stat) &
      & bind(C, name="egw_table_set_radii")
      type(c_ptr), value, intent(in) :: h   !< C: `egw_table t`
      !> C: `double radius1`; `double radius2`
      real(c_double), value, intent(in) :: radius1, radius2
      integer(c_int) :: stat
      type(force_table), pointer :: t
      type(egw_error), allocatable :: error
      stat = get_table(h, t)
      if (stat /= egw_ok) return
      call table_set_radii(t, radius1, radius2, error)
      stat = settle(error)
   end function egw_table_set_radii

   !> C: egw_table_write (atomic; EGW_FORMAT_*).
   function egw_table_write(h, path, format) result(stat) bind(C, name="egw_table_write")
      !> C: `egw_table t`; `const char *path` (NUL-terminated)
      type(c_ptr), value, intent(in) :: h, path
      integer(c_int), value, intent(in) :: format   !< C: `int format`
      integer(c_int) :: stat
      type(force_table), pointer :: t
      character(len=:), allocatable :: fpath
      type(egw_error), allocatable :: error
      stat = get_table(h, t)
      if (stat == egw_ok) stat = c_path(path, fpath)
      if (stat /= egw_ok) return
      call write_table(t, fpath, int(format), error)
      stat = settle(error)
   end function egw_table_write

   !> C: egw_table_read (egw CSV or binary; no handle on a bad file).
   function egw_table_read(path, out) result(stat) bind(C, name="egw_table_read")
      !> C: `const char *path` (NUL-terminated); `egw_table *out` (the new handle)
      type(c_ptr), value, intent(in) :: path, out
      integer(c_int) :: stat
      character(len=:), allocatable :: fpath
      type(force_table), pointer :: t
      type(egw_error), allocatable :: error
      stat = require(out, "out")
      if (stat == egw_ok) stat = c_path(path, fpath)
      if (stat /= egw_ok) return
      allocate (t)
      call read_table(fpath, t, error)
      stat = put_handle_settled(out, c_loc(t), error)
      if (stat /= egw_ok) deallocate (t)
   end function egw_table_read

   !> C: egw_table_free(egw_table *t): releases the table, sets *t = NULL.
   subroutine egw_table_free(h) bind(C, name="egw_table_free")
      !> C: `egw_table *t` (released, then set to NULL; NULL is fine)
      type(c_ptr), value, intent(in) :: h
      type(c_ptr) :: object
      type(force_table), pointer :: t
      object = take_handle(h)
      if (.not. c_associated(object)) return
      call c_f_pointer(object, t)
      deallocate (t)
   end subroutine egw_table_free

   !> C: egw_tables_write_lammps: one pair_style table section (EGW_1..EGW_n) per table.
   function egw_tables_write_lammps(n, tables, path) result(stat) &
      & bind(C, name="egw_tables_write_lammps")
      integer(c_int), value, intent(in) :: n   !< C: `int n`
      !> C: `const egw_table *tables`; `const char *path` (NUL-terminated)
      type(c_ptr), value, intent(in) :: tables, path
      integer(c_int) :: stat
      stat = lammps_c(n, tables, path, .false., c_null_ptr)
   end function egw_tables_write_lammps

   !> C: egw_write_flat_calculix (rough-flat p_G for CalculiX).
   function egw_write_flat_calculix(p, overclosure_max, rel_tol, path) result(stat) &
      & bind(C, name="egw_write_flat_calculix")
      !> C: `const egw_params *p` (the contact's parameters); `const char *path`
      !> (NUL-terminated)
      type(c_ptr), value, intent(in) :: p, path
      !> C: `double overclosure_max`; `double rel_tol`
      real(c_double), value, intent(in) :: overclosure_max, rel_tol
      integer(c_int) :: stat
      type(contact_params) :: params
      character(len=:), allocatable :: fpath
      type(egw_error), allocatable :: error
      stat = read_params(p, params)
      if (stat == egw_ok) stat = c_path(path, fpath)
      if (stat /= egw_ok) return
      call write_calculix_flat(params, overclosure_max, rel_tol, fpath, error)
      stat = settle(error)
   end function egw_write_flat_calculix

   !> C: egw_table_write_calculix (sphere curve; shift: overclosure from the cut-off;
   !> max_error may be NULL).
   function egw_table_write_calculix(h, path, shift, max_error) result(stat) &
      & bind(C, name="egw_table_write_calculix")
      !> C: `egw_table t`; `const char *path` (NUL-terminated); `double *max_error` (out)
      type(c_ptr), value, intent(in) :: h, path, max_error
      integer(c_int), value, intent(in) :: shift   !< C: `int shift`
      integer(c_int) :: stat
      type(force_table), pointer :: t
      character(len=:), allocatable :: fpath
      type(egw_error), allocatable :: error
      real(dp) :: achieved
      stat = get_table(h, t)
      if (stat == egw_ok) stat = c_path(path, fpath)
      if (stat /= egw_ok) return
      call write_calculix_sphere(t, fpath, error, shift=shift /= 0, max_error=achieved)
      stat = put_settled(max_error, achieved, error)
   end function egw_table_write_calculix

   !> C: egw_write_flat_calculix_shifted (rough flat; shift: overclosure from d_c;
   !> max_error may be NULL).
   function egw_write_flat_calculix_shifted(p, overclosure_max, rel_tol, shift, path, &
      & max_error) result(stat) bind(C, name="egw_write_flat_calculix_shifted")
      !> C: `const egw_params *p` (the contact's parameters); `const char *path`
      !> (NUL-terminated); `double *max_error` (out)
      type(c_ptr), value, intent(in) :: p, path, max_error
      !> C: `double overclosure_max`; `double rel_tol`
      real(c_double), value, intent(in) :: overclosure_max, rel_tol
      integer(c_int), value, intent(in) :: shift   !< C: `int shift`
      integer(c_int) :: stat
      type(contact_params) :: params
      character(len=:), allocatable :: fpath
      type(egw_error), allocatable :: error
      real(dp) :: achieved
      stat = read_params(p, params)
      if (stat == egw_ok) stat = c_path(path, fpath)
      if (stat /= egw_ok) return
      call write_calculix_flat(params, overclosure_max, rel_tol, fpath, error, &
         & shift=shift /= 0, max_error=achieved)
      stat = put_settled(max_error, achieved, error)
   end function egw_write_flat_calculix_shifted

   !> C: egw_tables_write_lammps_units: as egw_tables_write_lammps with a LAMMPS units
   !> style written as the file's UNITS: tag.
   function egw_tables_write_lammps_units(n, tables, path, units) result(stat) &
      & bind(C, name="egw_tables_write_lammps_units")
      integer(c_int), value, intent(in) :: n   !< C: `int n`
      !> C: `const egw_table *tables`; `const char *path` (NUL-terminated); `const char
      !> *units`
      type(c_ptr), value, intent(in) :: tables, path, units
      integer(c_int) :: stat
      stat = lammps_c(n, tables, path, .true., units)
   end function egw_tables_write_lammps_units

   ! ------------------------------------------------------------ universal tables

   !> C: egw_universal_build.
   function egw_universal_build(p, o, mu_min, mu_max, x_min, x_max, rel_tol, out) &
      & result(stat) bind(C, name="egw_universal_build")
      !> C: `const egw_params *p` (the contact's parameters); `const egw_options *o` (solver
      !> options, NULL: the defaults); `egw_universal *out` (the new handle)
      type(c_ptr), value, intent(in) :: p, o, out
      !> C: `double mu_min`; `double mu_max`; `double x_min`; `double x_max`; `double
      !> rel_tol`
      real(c_double), value, intent(in) :: mu_min, mu_max, x_min, x_max, rel_tol
      integer(c_int) :: stat
      type(contact_params) :: params
      type(solver_options) :: options
      type(universal_table), pointer :: u
      type(egw_error), allocatable :: error
      stat = require(out, "out")
      if (stat == egw_ok) stat = read_contact(p, o, params, options)
      if (stat == egw_ok) stat = refuse_cap(params, "a universal table")
      if (stat /= egw_ok) return
      allocate (u)
      call progress_begin("table build")
      call build_universal_cached(params%model, params%psi, params%hardness_coeff, &
         & params%plastic_ratio, options, mu_min, mu_max, x_min, x_max, rel_tol, u, error, &
         & progress=progress_count)
      call progress_end("table build")
      ! in the caller's terms (its slices are solved at a tenth of rel_tol)
      if (allocated(error)) call tolerance_context(error, "universal table", rel_tol, &
         & min(options%rel_tol, 0.1_dp*rel_tol))
      stat = put_handle_settled(out, c_loc(u), error)
      if (stat /= egw_ok) deallocate (u)
   end function egw_universal_build

   !> C: egw_universal_eval (R, E, sigma, mu from p; model, psi, K, rho_p must match).
   function egw_universal_eval(h, p, delta, force, stiffness) result(stat) &
      & bind(C, name="egw_universal_eval")
      !> C: `egw_universal u`; `const egw_params *p` (the contact's parameters); `double
      !> *force` (out); `double *stiffness` (out)
      type(c_ptr), value, intent(in) :: h, p, force, stiffness
      real(c_double), value, intent(in) :: delta   !< C: `double delta`
      integer(c_int) :: stat
      type(universal_table), pointer :: u
      type(egw_params_c), pointer :: cp
      integer :: st
      real(dp) :: f, k
      stat = get_universal(h, u)
      if (stat == egw_ok) stat = require(p, "p")
      if (stat /= egw_ok) return
      call c_f_pointer(p, cp)
      ! cheap checks only: this is the per-contact hot path
      if (cp%model /= u%model) then
         stat = invalid("model = "//int_str(int(cp%model))//": table is for model "// &
            & int_str(u%model))
         return
      end if
      if (cp%psi /= u%psi .or. cp%hardness_coeff /= u%hardness_coeff .or. &
         & cp%plastic_ratio /= u%plastic_ratio) then
         stat = invalid("psi = "//format_real(cp%psi)//": psi, K, rho_p differ from the table's")
         return
      end if
      if (.not. (cp%sigma > 0.0_dp .and. cp%radius > 0.0_dp .and. cp%modulus > 0.0_dp)) then
         stat = failure(egw_invalid_parameter, "sigma = "//format_real(cp%sigma)// &
            & ": universal tables need sigma, radius, modulus > 0")
         return
      end if
      stat = check_number("delta", delta)
      if (stat /= egw_ok) return
      call universal_eval(u, cp%radius, cp%modulus, cp%sigma, cp%mu, delta, f, k, st)
      if (st /= egw_ok .and. .not. (cp%mu >= u%mu_min*(1 - 1.0e-12_dp) .and. &
         & cp%mu <= u%mu_max*(1 + 1.0e-12_dp))) then
         stat = failure(egw_out_of_range, "mu = "//format_real(cp%mu)// &
            & ": outside the table's ["//format_real(u%mu_min)//", "//format_real(u%mu_max)//"]")
         return
      end if
      if (.not. (ieee_is_finite(f) .and. ieee_is_finite(k))) then
         ! Inf R, E or sigma, or a force beyond the doubles: refused, outputs untouched
         stat = failure(egw_invalid_parameter, "sigma = "//format_real(cp%sigma)// &
            & ", radius = "//format_real(cp%radius)//", modulus = "//format_real(cp%modulus) &
            & //", delta = "//format_real(delta) &
            & //": the force E sqrt(R) sigma**1.5 p(delta/sigma) exceeds the largest double" &
            & //" (R, E, sigma must be finite)")
         return
      end if
      call put(force, f)
      call put(stiffness, k)
      if (st /= egw_ok) stat = failure(st, "delta = "//format_real(delta)// &
         & ": above the table's x_max*sigma = "//format_real(u%x_max*cp%sigma)// &
         & " (values extrapolated)")
   end function egw_universal_eval

   !> C: egw_universal_slice: the 1-D table of the contact p cut out of u.
   function egw_universal_slice(h, p, out) result(stat) bind(C, name="egw_universal_slice")
      !> C: `egw_universal u`; `const egw_params *p` (the contact's parameters); `egw_table
      !> *out` (the new handle)
      type(c_ptr), value, intent(in) :: h, p, out
      integer(c_int) :: stat
      stat = slice_c(h, p, out, .false., 0.0_dp)
   end function egw_universal_slice

   !> C: egw_universal_slice_range: the same, trimmed to overlaps up to delta_max.
   function egw_universal_slice_range(h, p, delta_max, out) result(stat) &
      & bind(C, name="egw_universal_slice_range")
      !> C: `egw_universal u`; `const egw_params *p` (the contact's parameters); `egw_table
      !> *out` (the new handle)
      type(c_ptr), value, intent(in) :: h, p, out
      real(c_double), value, intent(in) :: delta_max   !< C: `double delta_max`
      integer(c_int) :: stat
      stat = slice_c(h, p, out, .true., delta_max)
   end function egw_universal_slice_range

   !> The 1-D table of the contact p cut out of the universal table h into *out; trimmed
   !> to overlaps up to delta_max when trim.
   integer(c_int) function slice_c(h, p, out, trim, delta_max) result(stat)
      type(c_ptr), intent(in) :: h, p, out
      logical, intent(in) :: trim
      real(dp), intent(in) :: delta_max
      type(universal_table), pointer :: u
      type(contact_params) :: params
      type(force_table), pointer :: t
      type(egw_error), allocatable :: error
      stat = get_universal(h, u)
      if (stat == egw_ok) stat = require(out, "out")
      if (stat == egw_ok) stat = read_params(p, params)
      if (stat /= egw_ok) return
      allocate (t)
      if (trim) then
         call universal_slice(u, params, t, error, delta_max=delta_max)
      else
         call universal_slice(u, params, t, error)
      end if
      stat = put_handle_settled(out, c_loc(t), error)
      if (stat /= egw_ok) deallocate (t)
   end function slice_c

   !> C: egw_universal_write (CSV or binary).
   function egw_universal_write(h, path, format) result(stat) &
      & bind(C, name="egw_universal_write")
      !> C: `egw_universal u`; `const char *path` (NUL-terminated)
      type(c_ptr), value, intent(in) :: h, path
      integer(c_int), value, intent(in) :: format   !< C: `int format`
      integer(c_int) :: stat
      type(universal_table), pointer :: u
      character(len=:), allocatable :: fpath
      type(egw_error), allocatable :: error
      stat = get_universal(h, u)
      if (stat == egw_ok) stat = c_path(path, fpath)
      if (stat /= egw_ok) return
      call write_universal(u, fpath, int(format), error)
      stat = settle(error)
   end function egw_universal_write

   !> C: egw_universal_read.
   function egw_universal_read(path, out) result(stat) bind(C, name="egw_universal_read")
      !> C: `const char *path` (NUL-terminated); `egw_universal *out` (the new handle)
      type(c_ptr), value, intent(in) :: path, out
      integer(c_int) :: stat
      character(len=:), allocatable :: fpath
      type(universal_table), pointer :: u
      type(egw_error), allocatable :: error
      stat = require(out, "out")
      if (stat == egw_ok) stat = c_path(path, fpath)
      if (stat /= egw_ok) return
      allocate (u)
      call read_universal(fpath, u, error)
      stat = put_handle_settled(out, c_loc(u), error)
      if (stat /= egw_ok) deallocate (u)
   end function egw_universal_read

   !> C: egw_universal_free(egw_universal *u): releases, sets *u = NULL.
   subroutine egw_universal_free(h) bind(C, name="egw_universal_free")
      !> C: `egw_universal *u` (released, then set to NULL; NULL is fine)
      type(c_ptr), value, intent(in) :: h
      type(c_ptr) :: object
      type(universal_table), pointer :: u
      object = take_handle(h)
      if (.not. c_associated(object)) return
      call c_f_pointer(object, u)
      deallocate (u)
   end subroutine egw_universal_free

   ! ------------------------------------------------------------ helpers

   !> The LAMMPS file of n tables (egw_table*) at path; a UNITS: tag when with_units.
   integer(c_int) function lammps_c(n, tables, path, with_units, units) result(stat)
      integer(c_int), intent(in) :: n
      type(c_ptr), intent(in) :: tables, path, units
      logical, intent(in) :: with_units
      type(c_ptr), pointer :: handles(:)
      type(force_table), allocatable :: copies(:)
      type(force_table), pointer :: t
      character(len=:), allocatable :: fpath, funits
      type(egw_error), allocatable :: error
      integer :: i
      stat = egw_ok
      if (n < 1) stat = invalid("n = "//int_str(int(n))//": need at least one table")
      if (stat == egw_ok) stat = require(tables, "tables")
      if (stat == egw_ok) stat = c_path(path, fpath)
      if (stat == egw_ok .and. with_units) stat = c_path(units, funits, "units")
      if (stat /= egw_ok) return
      call c_f_pointer(tables, handles, [n])
      allocate (copies(n), stat=i)
      if (i /= 0) then
         stat = failure(egw_out_of_memory, "n = "//int_str(int(n))// &
            & ": no memory for that many tables")
         return
      end if
      do i = 1, n
         stat = get_table(handles(i), t)
         if (stat /= egw_ok) return
         copies(i) = t
      end do
      if (with_units) then
         call write_lammps(copies, fpath, error, units=funits)
      else
         call write_lammps(copies, fpath, error)
      end if
      stat = settle(error)
   end function lammps_c

   !> The table of a handle egw_table (not NULL, built or read), as get_universal.
   integer(c_int) function get_table(h, t) result(stat)
      type(c_ptr), intent(in) :: h
      type(force_table), pointer, intent(out) :: t
      t => null()
      stat = require(h, "t")
      if (stat /= egw_ok) return
      call c_f_pointer(h, t)
      if (.not. table_is_ready(t)) stat = invalid("t: not a built or read table")
   end function get_table

   !> egw_table_get_tail's pieces of the tables behind handles (checked: built or read, each
   !> with a resampled tail of its own, all on the first one's nodes and ln P intervals):
   !> the one table's fine_seg, or resample_tails over all from the most pieces any of them
   !> takes alone (each fails on every count below its own, so the first count on which
   !> all fit is the one a search from min_fine finds); the tail's end.
   integer(c_int) function tail_pieces(handles, pieces, n_fine, tail_end) result(stat)
      type(c_ptr), intent(in) :: handles(:)
      real(dp), allocatable, intent(out) :: pieces(:, :)
      integer, intent(out) :: n_fine
      real(dp), intent(out) :: tail_end
      type(force_table), pointer :: t, first
      real(dp), allocatable :: force(:, :), stiffness(:, :), seg(:, :, :), tol(:)
      integer :: i, nn, ns, n_start
      n_fine = 0
      tail_end = 0.0_dp
      ns = size(handles)
      n_start = 0
      do i = 1, ns
         stat = tail_table(handles(i), "tables["//int_str(i - 1)//"]", t)
         if (stat /= egw_ok) return
         if (i == 1) first => t
         if (size(t%delta) /= size(first%delta) .or. t%n_log /= first%n_log) then
            stat = invalid("tables["//int_str(i - 1)//"]: its nodes or ln P intervals "// &
               & "differ from tables[0]'s (one grid needs shared nodes)")
         else if (any(t%delta /= first%delta)) then
            stat = invalid("tables["//int_str(i - 1)//"]: its nodes differ from "// &
               & "tables[0]'s (one grid needs shared nodes)")
         end if
         if (stat /= egw_ok) return
         n_start = max(n_start, size(t%fine_seg, 2))
      end do
      tail_end = first%tail_end
      if (ns == 1) then
         pieces = first%fine_seg
         n_fine = size(pieces, 2)
         return
      end if
      nn = size(first%delta)
      allocate (force(nn, ns), stiffness(nn, ns), seg(0:4, nn, ns), tol(ns), stat=i)
      if (i /= 0) then
         stat = failure(egw_out_of_memory, "n = "//int_str(ns)//": no memory for that "// &
            & "many tables' nodes")
         return
      end if
      do i = 1, ns
         call c_f_pointer(handles(i), t)
         force(:, i) = t%force
         stiffness(:, i) = t%stiffness
         seg(:, :, i) = t%seg
         tol(i) = tail_resample_tol*t%rel_tol
      end do
      call resample_tails(nn, ns, first%delta, force, stiffness, seg, first%n_log, &
         & tail_last_node(first%delta, first%n_log), tol, n_start, pieces, n_fine)
      if (n_fine == 0) stat = invalid("n = "//int_str(ns)//": on one grid the tables' "// &
         & "tails need more than "//int_str(max_fine)//" pieces")
   end function tail_pieces

   !> The table of handle h (called name) if it has a resampled tail, else
   !> EGW_NULL_POINTER or EGW_INVALID_ARGUMENT saying why it has none.
   integer(c_int) function tail_table(h, name, t) result(stat)
      type(c_ptr), intent(in) :: h
      character(len=*), intent(in) :: name   !< e.g. "tables[2]"
      type(force_table), pointer, intent(out) :: t
      t => null()
      stat = require(h, name)
      if (stat /= egw_ok) return
      call c_f_pointer(h, t)
      if (.not. table_is_ready(t)) then
         stat = invalid(name//": not a built or read table")
      else if (size(t%fine_seg, 2) > 0) then
         return
      else if (.not. is_rough(t%params)) then
         stat = invalid(name//": a smooth-sphere table has no separated tail")
      else if (t%params%model == model_flat_law) then
         stat = invalid(name//": a flat-law table's tail is ln P throughout (not resampled)")
      else if (tail_last_node(t%delta, t%n_log) == 0) then
         stat = invalid(name//": no ln P interval below delta = 0 (no separated tail)")
      else
         stat = invalid(name//": its tail would take more than "//int_str(max_fine)// &
            & " pieces at rel_tol "//format_real(t%rel_tol)//" (egw_table_eval takes exp)")
      end if
   end function tail_table

   !> The table of a handle egw_universal (not NULL, built or read).
   integer(c_int) function get_universal(h, u) result(stat)
      type(c_ptr), intent(in) :: h
      type(universal_table), pointer, intent(out) :: u
      u => null()
      stat = require(h, "u")
      if (stat /= egw_ok) return
      call c_f_pointer(h, u)
      if (.not. allocated(u%slices)) stat = invalid("u: not a built or read table")
   end function get_universal

   !> EGW_OK if every overlap is a number whose deep-overlap asymptote above delta_max stays
   !> inside the doubles, else EGW_INVALID_ARGUMENT naming the first other (delta[i]).
   integer(c_int) function check_overlaps(t, delta) result(stat)
      type(force_table), intent(in) :: t
      real(dp), intent(in) :: delta(:)
      real(dp) :: f, k
      integer :: i
      stat = egw_ok
      do i = 1, size(delta)
         stat = check_number("delta", delta(i), i - 1)
         if (stat /= egw_ok) return
         if (delta(i) > t%delta_max) then
            call table_eval(t, delta(i), f, k)
            if (.not. (ieee_is_finite(f) .and. ieee_is_finite(k))) then
               stat = beyond(t, delta(i), "delta["//int_str(i - 1)//"]")
               return
            end if
         end if
      end do
   end function check_overlaps

   !> EGW_OUT_OF_RANGE for an overlap above delta_max (values written, extrapolated).
   integer(c_int) function out_of_range(t, delta) result(stat)
      type(force_table), intent(in) :: t
      real(dp), intent(in) :: delta
      stat = above_delta_max("delta", delta, t%delta_max)
   end function out_of_range

   !> An overlap whose deep-overlap asymptote above delta_max leaves the doubles (+Inf, or
   !> ~1e300): refused, outputs untouched.
   integer(c_int) function beyond(t, delta, name) result(stat)
      type(force_table), intent(in) :: t
      real(dp), intent(in) :: delta
      character(len=*), intent(in), optional :: name
      character(len=:), allocatable :: label
      label = "delta"
      if (present(name)) label = name
      stat = invalid(label//" = "//format_real(delta)//": the continuation above the table's" &
         & //" delta_max = "//format_real(t%delta_max)//" exceeds the largest double")
   end function beyond

end module egw_capi_table
