!> C API of the EP-GW hysteresis tables (include/egw.h): an opaque handle, a
!> hysteresis_handle (c_loc of an allocated one, released by egw_hysteresis_free) that
!> points to an allocated hysteresis_table. egw_hysteresis_eval_state is C
!> (capi_hysteresis_state.c): the steps its state answers alone there, the others here.
module egw_capi_hysteresis
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_associated, c_f_pointer, &
      & c_loc, c_null_ptr
   use, intrinsic :: ieee_arithmetic, only: ieee_is_nan, ieee_is_finite, ieee_value, &
      & ieee_negative_inf
   use, intrinsic :: iso_fortran_env, only: int64
   use egw_progress, only: progress_begin, progress_end, progress_count
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_ok, egw_out_of_range, egw_out_of_memory, format_real, &
      & int_str, tolerance_context
   use egw_params, only: contact_params
   use egw_rough_sphere, only: solver_options
   use egw_cache, only: build_hysteresis_cached
   use egw_hysteresis, only: hysteresis_table, hysteresis_eval, zero_lo, folded, &
      & hysteresis_eval_state, hysteresis_state_init, hysteresis_state_size, &
      & hysteresis_energy
   use egw_hysteresis_data, only: quiet_nan
   use egw_hysteresis_format, only: write_hysteresis, read_hysteresis
   use egw_capi_utils, only: settle, require, invalid, failure, check_number, check_count, &
      & read_contact, put, put_handle_settled, take_handle, double_array, from_params, &
      & egw_params_c, c_path, above_delta_max
   implicit none
   private

   !> C: egw_hysteresis_info (include/egw.h).
   type, bind(C) :: egw_hysteresis_info_c
      integer(c_int) :: model, reversible, n_delta_max, n_s, n_loading
      real(c_double) :: cutoff, delta_max, reference_force, rel_tol, max_error
      type(egw_params_c) :: params
   end type egw_hysteresis_info_c

   !> What the handle egw_hysteresis points to (C: capi_hysteresis_state.c's struct
   !> egw_hysteresis_s, the same layout): the table, and the three numbers of it that
   !> egw_hysteresis_eval_state's steps read in C (no Fortran descriptor there).
   type, bind(C) :: hysteresis_handle
      real(c_double) :: tag = 0   !< the table's tag (hysteresis_table%tag)
      !> min(delta_max, input_limit): a history or overlap above it takes the Fortran entry
      real(c_double) :: served_limit = 0
      real(c_double) :: cutoff = 0   !< the loading table's cut-off
      type(c_ptr) :: table   !< c_loc of the hysteresis_table
   end type hysteresis_handle

   public :: egw_hysteresis_info_c, hysteresis_handle, hysteresis_handle_for
   ! (public so that the compiler keeps it out of line: the steps
   ! egw_hysteresis_eval_state_general serves itself, which it inlines, then set up no
   ! frame for it)
   public :: eval_state_full

contains

   !> C: egw_hysteresis_build (include/egw.h).
   function egw_hysteresis_build(p, o, delta_min, delta_max, rel_tol, out) result(stat) &
      & bind(C, name="egw_hysteresis_build")
      !> C: `const egw_params *p` (the contact's parameters); `const egw_options *o` (solver
      !> options, NULL: the defaults); `egw_hysteresis *out` (the new handle)
      type(c_ptr), value, intent(in) :: p, o, out
      !> C: `double delta_min`; `double delta_max`; `double rel_tol`
      real(c_double), value, intent(in) :: delta_min, delta_max, rel_tol
      integer(c_int) :: stat
      type(contact_params) :: params
      type(solver_options) :: options
      type(hysteresis_table), pointer :: h
      type(egw_error), allocatable :: error
      stat = require(out, "out")
      if (stat == egw_ok) stat = read_contact(p, o, params, options)
      if (stat /= egw_ok) return
      stat = new_table(h)
      if (stat /= egw_ok) return
      call progress_begin("table build")
      call build_hysteresis_cached(params, options, delta_min, delta_max, rel_tol, h, error, &
         & progress_count)
      call progress_end("table build")
      ! in the caller's terms (its curves are solved at a tenth of rel_tol)
      if (allocated(error)) call tolerance_context(error, "hysteresis table", rel_tol, &
         & min(options%rel_tol, 0.1_dp*rel_tol))
      stat = put_table_handle(out, h, error)
   end function egw_hysteresis_build

   !> C: egw_hysteresis_eval: the per-contact hot path (no allocation, no lock).
   function egw_hysteresis_eval(hp, delta, state, force, stiffness) result(stat) &
      & bind(C, name="egw_hysteresis_eval")
      !> C: `egw_hysteresis h`; `double *delta_max_state` (out); `double *force` (out);
      !> `double *stiffness` (out)
      type(c_ptr), value, intent(in) :: hp, state, force, stiffness
      real(c_double), value, intent(in) :: delta   !< C: `double delta`
      integer(c_int) :: stat
      type(hysteresis_table), pointer :: h
      real(c_double), pointer :: s
      real(dp) :: f, k, m
      integer :: st
      ! good arguments pass an inline test, not the checks' calls (the hot path)
      if (.not. (c_associated(hp) .and. c_associated(state)) .or. ieee_is_nan(delta)) then
         stat = require(hp, "h")
         if (stat == egw_ok) stat = require(state, "delta_max_state")
         if (stat == egw_ok) stat = check_number("delta", delta)
         return
      end if
      call handle_table(hp, h)
      call c_f_pointer(state, s)
      if (ieee_is_nan(s)) then
         stat = invalid("delta_max_state = NaN: a new contact starts from -HUGE_VAL")
         return
      end if
      m = s
      call hysteresis_eval(h, delta, m, f, k, st)
      if (.not. (ieee_is_finite(f) .and. ieee_is_finite(k))) then  ! input guard (issue 13)
         stat = invalid("delta = "//format_real(delta)//", delta_max_state = "// &
            & format_real(s)//": the force there exceeds the doubles")
         return
      end if
      s = m
      call put(force, f)
      call put(stiffness, k)
      stat = int(st, c_int)
      if (stat == egw_out_of_range) stat = above_table(h, "delta_max_state", m)
   end function egw_hysteresis_eval

   !> C: egw_hysteresis_eval_state (capi_hysteresis_state.c) but for the steps it answers
   !> in C (zero, folded, log-ratio on a linear interval, loading; both outputs given):
   !> egw_hysteresis_eval with the turning point's data kept in the caller's state
   !> (EGW_HYSTERESIS_STATE_SIZE doubles; state[0] the history). The steps that read
   !> nothing but the state (eval_state_served: what egw.h's inline
   !> egw_hysteresis_eval_cached serves) are answered here, before the argument checks,
   !> which the call that filled the state passed; every other step takes eval_state_full.
   function egw_hysteresis_eval_state_general(hp, delta, state_p, force, stiffness) &
      & result(stat) bind(C, name="egw_hysteresis_eval_state_general")
      !> C: `void *table` (the handle's hysteresis_table, NULL for a NULL handle); `double
      !> state[EGW_HYSTERESIS_STATE_SIZE]`; `double *force` (out); `double *stiffness` (out)
      type(c_ptr), value, intent(in) :: hp, state_p, force, stiffness
      real(c_double), value, intent(in) :: delta   !< C: `double delta`
      integer(c_int) :: stat
      type(hysteresis_table), pointer :: h
      real(c_double), pointer, contiguous :: state(:)   ! no packing on the hot path
      real(c_double), pointer :: out
      real(dp) :: f, k
      logical :: served
      if (c_associated(hp) .and. c_associated(state_p)) then
         call c_f_pointer(hp, h)
         call c_f_pointer(state_p, state, [hysteresis_state_size])
         call eval_state_served(h, delta, state, f, k, served)
         if (served) then
            if (c_associated(force)) then
               call c_f_pointer(force, out)
               out = f
            end if
            if (c_associated(stiffness)) then
               call c_f_pointer(stiffness, out)
               out = k
            end if
            stat = egw_ok
            return
         end if
      end if
      stat = eval_state_full(hp, delta, state_p, force, stiffness)
   end function egw_hysteresis_eval_state_general

   !> The steps of egw_hysteresis_eval_state that its state answers alone (egw.h's inline
   !> egw_hysteresis_eval_cached serves the same): a state this table filled (its tag)
   !> whose piece covers delta with the loading interval beside it (hysteresis_eval_state's
   !> first test; a zero piece: 0), or a step loading further (delta >= state(1)) inside
   !> the loading interval the state holds (above the loading table's cut-off, or in a zero
   !> interval below it; a zero piece and a folded piece up to its end, as
   !> hysteresis_eval_state). The values
   !> are hysteresis_eval_state's (piece_force's and
   !> segment_eval's arithmetic in the same order; a log-ratio piece's exp piece_exp, the
   !> others' exp from the same libm: bit for bit, test hysteresis), and so is the state
   !> it leaves; a step whose status would not be EGW_OK (a history above the table's
   !> delta_max, values that are not finite: a garbled state) is not served (served
   !> .false., the state unchanged), nor a log-ratio piece's whose force is 0 (the full
   !> call gives it the same zeros: its served step keeps one test). One of the served
   !> arithmetic's four copies (src/egw/capi/README.md: a change goes into all four).
   pure subroutine eval_state_served(h, delta, state, force, stiffness, served)
      type(hysteresis_table), intent(in) :: h
      real(dp), intent(in) :: delta
      real(dp), intent(inout) :: state(hysteresis_state_size)
      real(dp), intent(out) :: force, stiffness
      logical, intent(out) :: served
      real(dp) :: x, x2, t, t2, v, d, p, q
      logical :: lnp
      served = .false.
      force = 0.0_dp
      stiffness = 0.0_dp
      if (.not. state(3) == h%tag) return
      if (state(11) == zero_lo .and. state(11) < delta .and. delta <= state(12) .and. &
         & state(2) == state(1)) then
         ! a zero piece (separated, no force; hysteresis_eval_state's exit there, tested
         ! first as there: its zero interval need not be read)
         served = state(1) <= h%input_limit
         return
      end if
      if (state(24) == folded .and. state(11) < delta .and. delta <= state(12) .and. &
         & state(2) == state(1)) then
         ! a folded log-ratio piece (the separated tail: exp of the one cubic ln P - h;
         ! make_log_piece cut it inside its loading interval, which is not read), its end
         ! included (the step back at the history, as hysteresis_eval_state)
         if (.not. (state(1) <= h%delta_max .and. state(1) <= h%input_limit)) return
         x = delta - state(11)
         x2 = x*x
         force = (state(14) + x*state(15)) + x2*(state(16) + x*state(17))
         stiffness = (state(15) + 2*x*state(16)) + 3*x2*state(17)
         ! (below: exp(force + 0), p (-0 + stiffness): exp(force), p stiffness bit for bit)
         v = 0.0_dp
         d = -0.0_dp
      else if (state(2) == state(1) .and. state(11) < delta .and. delta < state(12) .and. &
         & state(18) <= delta .and. delta < state(19)) then
         if (.not. (state(1) <= h%delta_max .and. state(1) <= h%input_limit)) return
         x = delta - state(11)
         x2 = x*x
         force = (state(14) + x*state(15)) + x2*(state(16) + x*state(17))
         stiffness = (state(15) + 2*x*state(16)) + 3*x2*state(17)
         if (state(24) > 1.0_dp .or. state(24) < 0.0_dp) then
            t = delta - state(18)
            t2 = t*t
            v = (state(20) + t*state(21)) + t2*(state(22) + t*state(23))
            d = (state(21) + 2*t*state(22)) + 3*t2*state(23)
         else
            if (state(24) > 0.0_dp) then
               ! a gap piece on a ln P interval: the cubic plus P
               t = delta - state(18)
               t2 = t*t
               v = (state(20) + t*state(21)) + t2*(state(22) + t*state(23))
               d = (state(21) + 2*t*state(22)) + 3*t2*state(23)
               p = exp(v)
               force = force + p
               stiffness = stiffness + p*d
            end if
            if (.not. force > 0.0_dp) then
               force = 0.0_dp
               stiffness = 0.0_dp
            end if
            served = ieee_is_finite(force) .and. ieee_is_finite(stiffness)
            return
         end if
      else if (delta >= state(1) .and. state(18) <= delta .and. delta < state(19) .and. &
         & delta <= h%delta_max .and. delta <= h%input_limit) then
         ! loading further (or back at the history) inside the loading interval
         if (state(18) == zero_lo) then
            ! the zero interval below the cut-off (a contact that has not touched)
            if (.not. delta < h%loading%cutoff) return
         else
            if (.not. delta > h%loading%cutoff) return
            t = delta - state(18)
            t2 = t*t
            v = (state(20) + t*state(21)) + t2*(state(22) + t*state(23))
            d = (state(21) + 2*t*state(22)) + 3*t2*state(23)
            if (state(24) > 0.0_dp) then
               force = exp(v)
               stiffness = force*d
            else
               force = v
               stiffness = d
            end if
         end if
         if (.not. (ieee_is_finite(force) .and. ieee_is_finite(stiffness))) return
         if (.not. delta == state(1)) state(11:12) = quiet_nan
         state(1) = delta
         served = .true.
         return
      else
         return
      end if
      ! a log-ratio piece (one piece_exp call for the folded and the other log-ratio
      ! pieces: gfortran inlines a single call site, two it calls out of line): on a ln P
      ! interval (the separated tail) exp(ln P - h), on a linear one P e^-h. Written as
      ! one with q = 1 or P (1 times a double is that double, and force + 0 differs from
      ! force only at -0, whose exp is 1 as +0's: the same bits): gcc then tests state(24)
      ! once where the two branches took three tests (stop 53, tail19)
      lnp = state(24) > 1.0_dp
      q = merge(1.0_dp, v, lnp)
      p = piece_exp(force + merge(v, 0.0_dp, lnp))
      stiffness = p*(d + q*stiffness)
      force = q*p
      ! (served only with a positive force and finite values, one test for both: a force
      ! 0 (exp 0, P <= 0) or values beyond the doubles take the full call, which gives
      ! them the same bits, as it does the rare finite pair whose sum would overflow)
      served = force > 0.0_dp .and. abs(stiffness) + force <= huge(1.0_dp)
   end subroutine eval_state_served

   include "../tables/piece_exp.inc"

   !> egw_hysteresis_eval_state's checks and hysteresis_eval_state: the steps eval_state_served
   !> does not serve. (Kept out of line: the served steps then need no stack frame of it.)
   function eval_state_full(hp, delta, state_p, force, stiffness) result(stat)
      type(c_ptr), value, intent(in) :: hp, state_p, force, stiffness   !< as the C entry's
      real(c_double), value, intent(in) :: delta   !< as the C entry's
      integer(c_int) :: stat
      type(hysteresis_table), pointer :: h
      real(c_double), pointer, contiguous :: state(:)   ! no packing on the hot path
      real(c_double), pointer :: out
      real(dp) :: f, k, kept, limit
      integer :: st
      if (.not. (c_associated(hp) .and. c_associated(state_p)) .or. ieee_is_nan(delta)) then
         stat = require(hp, "h")
         if (stat == egw_ok) stat = require(state_p, "state")
         if (stat == egw_ok) stat = check_number("delta", delta)
         return
      end if
      call c_f_pointer(hp, h)
      call c_f_pointer(state_p, state, [hysteresis_state_size])
      if (ieee_is_nan(state(1))) then
         stat = invalid("state[0] = NaN: a new contact starts from "// &
            & "egw_hysteresis_state_init (state[0] = -HUGE_VAL)")
         return
      end if
      limit = h%input_limit   ! (stored: the DEM hot path)
      if (delta > limit .or. state(1) > limit) then
         stat = invalid("delta = "//format_real(delta)//", state[0] = "// &
            & format_real(state(1))//": must be <= "//format_real(limit)// &
            & " (the force there exceeds the doubles)")
         return
      end if
      kept = state(1)
      call hysteresis_eval_state(h, delta, state, f, k, st)
      if (.not. (ieee_is_finite(f) .and. ieee_is_finite(k))) then  ! input guard (issue 13)
         state(1) = kept
         stat = invalid("delta = "//format_real(delta)//", state[0] = "// &
            & format_real(kept)//": the force there exceeds the doubles")
         return
      end if
      ! put's steps written out (a call each on the DEM hot path)
      if (c_associated(force)) then
         call c_f_pointer(force, out)
         out = f
      end if
      if (c_associated(stiffness)) then
         call c_f_pointer(stiffness, out)
         out = k
      end if
      stat = int(st, c_int)
      if (stat == egw_out_of_range) stat = above_table(h, "state[0]", state(1))
   end function eval_state_full

   !> C: egw_hysteresis_state_tag: the tag egw writes into the states h fills (state[2]),
   !> for egw.h's inline egw_hysteresis_eval_cached.
   function egw_hysteresis_state_tag(hp, tag) result(stat) &
      & bind(C, name="egw_hysteresis_state_tag")
      type(c_ptr), value, intent(in) :: hp, tag   !< C: `egw_hysteresis h`; `double *tag` (out)
      integer(c_int) :: stat
      type(hysteresis_table), pointer :: h
      stat = get_table(hp, h)
      if (stat == egw_ok) stat = require(tag, "tag")
      if (stat /= egw_ok) return
      call put(tag, h%tag)
   end function egw_hysteresis_state_tag

   !> C: egw_hysteresis_energy: the elastic energy a contact returns if it separates now.
   function egw_hysteresis_energy(hp, delta, state, energy) result(stat) &
      & bind(C, name="egw_hysteresis_energy")
      !> C: `egw_hysteresis h`; `double *energy` (out)
      type(c_ptr), value, intent(in) :: hp, energy
      !> C: `double delta`; `double delta_max_state`
      real(c_double), value, intent(in) :: delta, state
      integer(c_int) :: stat
      type(hysteresis_table), pointer :: h
      real(dp) :: u
      integer :: st
      character(len=:), allocatable :: message
      stat = get_table(hp, h)
      if (stat == egw_ok) stat = require(energy, "energy")
      if (stat /= egw_ok) return
      if (ieee_is_nan(delta) .or. ieee_is_nan(state) .or. delta > h%input_limit .or. &
         & state > h%input_limit) then
         call history_message("delta", delta, "delta_max_state", state, h%input_limit, &
            & message)
         stat = invalid(message)
         return
      end if
      call hysteresis_energy(h, delta, state, u, st)
      if (.not. ieee_is_finite(u)) then   ! input guard (issue 13)
         stat = invalid("delta = "//format_real(delta)//": the energy there exceeds the doubles")
         return
      end if
      call put(energy, u)
      stat = int(st, c_int)
      if (stat == egw_out_of_range) &
         & stat = above_table(h, "max(delta, delta_max_state)", max(delta, state))
   end function egw_hysteresis_energy

   !> C: egw_hysteresis_state_init: a new contact's state (state[0] = -HUGE_VAL, no cache).
   subroutine egw_hysteresis_state_init(state_p) bind(C, name="egw_hysteresis_state_init")
      type(c_ptr), value, intent(in) :: state_p   !< C: `double state[EGW_HYSTERESIS_STATE_SIZE]`
      real(c_double), pointer :: state(:)
      if (.not. c_associated(state_p)) return
      call c_f_pointer(state_p, state, [hysteresis_state_size])
      call hysteresis_state_init(state)
      state(1) = ieee_value(state(1), ieee_negative_inf)   ! C's -HUGE_VAL
   end subroutine egw_hysteresis_state_init

   !> C: egw_hysteresis_eval_array: n independent contacts in one call. Every input is
   !> checked before anything is written: overlaps and states must be numbers, and at most
   !> where the loading table's deep-overlap asymptote stays well inside the doubles.
   function egw_hysteresis_eval_array(hp, n, delta_p, state_p, force, stiffness) &
      & result(stat) bind(C, name="egw_hysteresis_eval_array")
      type(c_ptr), value, intent(in) :: hp   !< C: `egw_hysteresis h`
      integer(c_int), value, intent(in) :: n   !< C: `int n`
      !> C: `const double *delta`; `double *delta_max_state` (out); `double *force` (out);
      !> `double *stiffness` (out)
      type(c_ptr), value, intent(in) :: delta_p, state_p, force, stiffness
      integer(c_int) :: stat
      type(hysteresis_table), pointer :: h
      real(c_double), pointer :: delta(:), state(:), f(:), k(:)
      real(dp), allocatable :: fa(:), ka(:), ma(:)
      integer :: i, st, first_out, alloc_stat
      stat = get_table(hp, h)
      if (stat == egw_ok) stat = check_count(n)
      if (stat /= egw_ok .or. n == 0) return
      stat = require(delta_p, "delta")
      if (stat == egw_ok) stat = require(state_p, "delta_max_state")
      if (stat /= egw_ok) return
      delta => double_array(delta_p, n)
      state => double_array(state_p, n)
      stat = check_histories(h, delta, state)
      if (stat /= egw_ok) return
      f => double_array(force, n)
      k => double_array(stiffness, n)
      ! evaluated into copies first: a value that leaves the doubles (a state inside the
      ! input limit on a curve stretched beyond them, as egw_hysteresis_eval refuses) is
      ! refused before anything is written, as egw.h says
      allocate (fa(n), ka(n), ma(n), stat=alloc_stat)
      if (alloc_stat /= 0) then
         stat = failure(egw_out_of_memory, "hysteresis_eval_array: out of memory")
         return
      end if
      ma = state
      first_out = 0
      do i = 1, n
         call hysteresis_eval(h, delta(i), ma(i), fa(i), ka(i), st)
         if (.not. (ieee_is_finite(fa(i)) .and. ieee_is_finite(ka(i)))) then
            stat = invalid("delta["//int_str(i - 1)//"] = "//format_real(delta(i))// &
               & ", delta_max_state["//int_str(i - 1)//"] = "//format_real(state(i))// &
               & ": the force there exceeds the doubles")
            return
         end if
         if (st /= egw_ok .and. first_out == 0) first_out = i
      end do
      state = ma
      if (associated(f)) f = fa
      if (associated(k)) k = ka
      if (first_out > 0) stat = failure(egw_out_of_range, "delta["//int_str(first_out - 1)// &
         & "] or its state above the table's delta_max = "//format_real(h%delta_max)// &
         & " (values extrapolated)")
   end function egw_hysteresis_eval_array

   !> C: egw_hysteresis_free: release a table; sets *h to NULL (NULL is fine).
   subroutine egw_hysteresis_free(hp) bind(C, name="egw_hysteresis_free")
      !> C: `egw_hysteresis *h` (released, then set to NULL; NULL is fine)
      type(c_ptr), value, intent(in) :: hp
      type(c_ptr) :: object
      type(hysteresis_handle), pointer :: handle
      type(hysteresis_table), pointer :: h
      object = take_handle(hp)
      if (.not. c_associated(object)) return
      call c_f_pointer(object, handle)
      call c_f_pointer(handle%table, h)
      deallocate (h)
      deallocate (handle)
   end subroutine egw_hysteresis_free

   !> C: egw_hysteresis_write: CSV or binary, atomically.
   function egw_hysteresis_write(hp, path, format) result(stat) &
      & bind(C, name="egw_hysteresis_write")
      !> C: `egw_hysteresis h`; `const char *path` (NUL-terminated)
      type(c_ptr), value, intent(in) :: hp, path
      integer(c_int), value, intent(in) :: format   !< C: `int format`
      integer(c_int) :: stat
      type(hysteresis_table), pointer :: h
      character(len=:), allocatable :: fpath
      type(egw_error), allocatable :: error
      stat = get_table(hp, h)
      if (stat == egw_ok) stat = c_path(path, fpath)
      if (stat /= egw_ok) return
      call write_hysteresis(h, fpath, int(format), error)
      stat = settle(error)
   end function egw_hysteresis_write

   !> C: egw_hysteresis_read: a handle only for a file that passed every check.
   function egw_hysteresis_read(path, out) result(stat) bind(C, name="egw_hysteresis_read")
      !> C: `const char *path` (NUL-terminated); `egw_hysteresis *out` (the new handle)
      type(c_ptr), value, intent(in) :: path, out
      integer(c_int) :: stat
      character(len=:), allocatable :: fpath
      type(hysteresis_table), pointer :: h
      type(egw_error), allocatable :: error
      stat = require(out, "out")
      if (stat == egw_ok) stat = c_path(path, fpath)
      if (stat == egw_ok) stat = new_table(h)
      if (stat /= egw_ok) return
      call read_hysteresis(fpath, h, error)
      stat = put_table_handle(out, h, error)
   end function egw_hysteresis_read

   !> C: egw_hysteresis_get_info.
   function egw_hysteresis_get_info(hp, info) result(stat) &
      & bind(C, name="egw_hysteresis_get_info")
      !> C: `egw_hysteresis h`; `egw_hysteresis_info *info` (out)
      type(c_ptr), value, intent(in) :: hp, info
      integer(c_int) :: stat
      type(hysteresis_table), pointer :: h
      type(egw_hysteresis_info_c), pointer :: out
      stat = get_table(hp, h)
      if (stat == egw_ok) stat = require(info, "info")
      if (stat /= egw_ok) return
      call c_f_pointer(info, out)
      out%model = int(h%params%model, c_int)
      out%reversible = merge(1_c_int, 0_c_int, h%reversible)
      out%n_delta_max = 0
      out%n_s = 0
      if (allocated(h%m)) out%n_delta_max = int(size(h%m), c_int)
      if (allocated(h%s)) out%n_s = int(size(h%s), c_int)
      out%n_loading = int(size(h%loading%delta), c_int)
      out%cutoff = h%loading%cutoff
      out%delta_max = h%delta_max
      out%reference_force = h%loading%reference_force
      out%rel_tol = h%rel_tol
      out%max_error = h%max_error
      out%params = from_params(h%params)
   end function egw_hysteresis_get_info

   ! ---------------------------------------------------------------- helpers

   !> The table of a handle egw_hysteresis (not NULL; a handle only comes from build or
   !> read, so there is nothing more to check).
   integer(c_int) function get_table(hp, h) result(stat)
      type(c_ptr), intent(in) :: hp
      type(hysteresis_table), pointer, intent(out) :: h
      h => null()
      stat = require(hp, "h")
      if (stat == egw_ok) call handle_table(hp, h)
   end function get_table

   !> The table of a handle (not NULL: the entries' hot paths, which test it themselves).
   subroutine handle_table(hp, h)
      type(c_ptr), intent(in) :: hp
      type(hysteresis_table), pointer, intent(out) :: h
      type(hysteresis_handle), pointer :: handle
      call c_f_pointer(hp, handle)
      call c_f_pointer(handle%table, h)
   end subroutine handle_table

   !> The handle of a table (its address and the numbers egw_hysteresis_eval_state reads
   !> in C): build's and read's, and the tests' for a table of their own.
   function hysteresis_handle_for(table) result(handle)
      type(hysteresis_table), target, intent(in) :: table   !< built or read
      type(hysteresis_handle) :: handle
      handle%tag = table%tag
      handle%served_limit = min(table%delta_max, table%input_limit)
      handle%cutoff = table%loading%cutoff
      handle%table = c_loc(table)
   end function hysteresis_handle_for

   !> Status of the build or read that made h (put_handle_settled): on success a new
   !> handle of h at *out; on failure (that status, or no memory for the handle) h is
   !> released and *out untouched.
   integer(c_int) function put_table_handle(out, h, error) result(stat)
      type(c_ptr), intent(in) :: out   !< egw_hysteresis* (not NULL)
      type(hysteresis_table), pointer, intent(inout) :: h   !< the new table
      !> the build's or read's error, unallocated on success
      type(egw_error), allocatable, intent(in) :: error
      type(hysteresis_handle), pointer :: handle
      integer :: alloc_stat
      stat = egw_ok
      if (.not. allocated(error)) then
         allocate (handle, stat=alloc_stat)
         if (alloc_stat /= 0) then
            deallocate (h)
            stat = failure(egw_out_of_memory, "hysteresis table: out of memory")
            return
         end if
         handle = hysteresis_handle_for(h)
         stat = put_handle_settled(out, c_loc(handle), error)
         if (stat == egw_ok) return
         deallocate (handle)
      else
         stat = put_handle_settled(out, c_null_ptr, error)
      end if
      deallocate (h)
   end function put_table_handle

   !> A new, empty table at h, or EGW_OUT_OF_MEMORY (a fine table is large: no abort).
   integer(c_int) function new_table(h) result(stat)
      type(hysteresis_table), pointer, intent(out) :: h
      integer :: alloc_stat
      stat = egw_ok
      allocate (h, stat=alloc_stat)
      if (alloc_stat /= 0) stat = failure(egw_out_of_memory, "hysteresis table: out of memory")
   end function new_table

   !> The refusal of an overlap and its history: the one that is NaN, or above limit (the
   !> force there leaves the doubles), named with its value. (A subroutine: deferred-length
   !> function results are not thread-safe under gfortran 12, test_text_io.)
   subroutine history_message(dname, d, sname, st, limit, msg)
      character(len=*), intent(in) :: dname, sname
      real(dp), intent(in) :: d, st, limit
      character(len=:), allocatable, intent(out) :: msg
      if (ieee_is_nan(d)) then
         msg = dname//" = NaN: must be a number"
      else if (ieee_is_nan(st)) then
         msg = sname//" = NaN: must be a number (a new contact starts at -HUGE_VAL)"
      else if (d > limit) then
         msg = dname//" = "//format_real(d)//": must be <= "//format_real(limit)// &
            & " (the force there exceeds the doubles)"
      else
         msg = sname//" = "//format_real(st)//": must be <= "//format_real(limit)// &
            & " (the force there exceeds the doubles)"
      end if
   end subroutine history_message

   !> EGW_OK if every overlap and its state are numbers <= h%input_limit, else
   !> EGW_INVALID_ARGUMENT naming the first other pair (delta[i], delta_max_state[i]).
   integer(c_int) function check_histories(h, delta, state) result(stat)
      type(hysteresis_table), intent(in) :: h
      real(dp), intent(in) :: delta(:), state(:)
      real(dp) :: limit
      integer :: i
      character(len=:), allocatable :: message
      stat = egw_ok
      limit = h%input_limit
      do i = 1, size(delta)
         if (ieee_is_nan(delta(i)) .or. ieee_is_nan(state(i)) .or. delta(i) > limit .or. &
            & state(i) > limit) then
            call history_message("delta["//int_str(i - 1)//"]", delta(i), &
               & "delta_max_state["//int_str(i - 1)//"]", state(i), limit, message)
            stat = invalid(message)
            return
         end if
      end do
   end function check_histories

   !> EGW_OUT_OF_RANGE for a history x (called name) above the table's delta_max: the
   !> values are written, extrapolated.
   integer(c_int) function above_table(h, name, x) result(stat)
      type(hysteresis_table), intent(in) :: h
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: x
      stat = above_delta_max(name, x, h%delta_max)
   end function above_table

end module egw_capi_hysteresis
