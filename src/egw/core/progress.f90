!> Progress reports of long calls (issue 32): a hook the caller sets (set_progress; C
!> egw_set_progress, Python egw.set_progress) that long solves, restitution and table
!> builds call with the fraction done and a short stage name. Nothing is reported, and
!> nothing printed, while no hook is set (the default).
!>
!> The hook is per thread, like the last-error message: set on a thread, it hears only the
!> calls made on that thread, so threads never share it and need no lock. Calls inside an
!> active OpenMP parallel region (a table build's solves, the C array entries of more than
!> one point, the caller's own regions) never report: a build reports for its solves, from
!> its own thread.
!>
!> done is monotone within one outermost call: 0 at its start, 1 at its end, never
!> decreasing between (a report below the last is raised to it). A call nested in another
!> (load_history inside restitution) reports inside the share its caller gave it
!> (progress_part), or not at all where none was given; so one hook sees one sequence per
!> outermost call, whatever calls what.
module egw_progress
   !$ use omp_lib, only: omp_in_parallel
   use egw_kinds, only: dp
   implicit none
   private

   public :: progress_hook, set_progress, progress_on, progress_begin, progress_end, &
      & progress_part, progress_report, progress_count, progress_note

   abstract interface
      !> A progress hook: done in [0, 1], monotone within one outermost call; stage names
      !> what is being done ("history", "small-sigma route: unloading", "table build" ...).
      subroutine progress_hook(done, stage)
         import :: dp
         real(dp), intent(in) :: done
         character(len=*), intent(in) :: stage
      end subroutine progress_hook
   end interface

   !> Depth of nested calls that are tracked (deeper ones report nothing).
   integer, parameter :: max_depth = 16

   !> This thread's hook and the spans of its nested calls (span(:, 0) = [0, 1]).
   type :: progress_state
      procedure(progress_hook), pointer, nopass :: hook => null()
      integer :: depth = 0
      !> the span of the global [0, 1] each open call covers (hi = lo: silent)
      real(dp) :: lo(0:max_depth) = 0.0_dp, hi(0:max_depth) = 1.0_dp
      !> the share given to the next call opened inside each open one
      real(dp) :: next_lo(0:max_depth) = 0.0_dp, next_hi(0:max_depth) = 0.0_dp
      real(dp) :: last = 0.0_dp   !< the last done reported
      logical :: calling = .false.   !< inside the hook (it may call egw: not reported)
      integer(8) :: last_call = 0   !< system_clock count of the last hook call
   end type progress_state
   type(progress_state), save :: state
   !$omp threadprivate(state)

contains

   !> Set this thread's hook, or switch reports off (hook absent or not associated).
   !> Called from inside the hook (the only way a call can be open on this thread), it
   !> swaps the hook only: the new one hears the rest of the open call, done going on from
   !> where it was (resetting the open calls there made each nested call of the rest an
   !> outermost one, 0 .. 1 again and again); outside, it also forgets any open call (one
   !> a hook switched off from inside left open).
   subroutine set_progress(hook)
      procedure(progress_hook), optional :: hook   !< the new hook (absent: reports off)
      state%hook => null()
      if (present(hook)) state%hook => hook
      if (state%calling) return
      state%depth = 0
      state%last = 0.0_dp
   end subroutine set_progress

   !> Whether reports are heard here: a hook set on this thread, outside an OpenMP
   !> parallel region, outside the hook itself.
   logical function progress_on()
      progress_on = associated(state%hook) .and. .not. state%calling
      !$ if (progress_on) progress_on = .not. omp_in_parallel()
   end function progress_on

   !> A long call starts (pair with progress_end on every return). Outermost: its span is
   !> [0, 1] and it reports 0; nested: the share its caller gave (progress_part), else none.
   subroutine progress_begin(stage)
      character(len=*), intent(in) :: stage   !< what the call does, as the hook hears it
      integer :: d
      if (.not. progress_on()) return
      d = state%depth
      state%depth = d + 1
      if (d + 1 > max_depth) return
      if (d == 0) then
         state%lo(1) = 0.0_dp
         state%hi(1) = 1.0_dp
         state%last = 0.0_dp
      else if (d <= max_depth) then
         state%lo(d + 1) = state%next_lo(d)
         state%hi(d + 1) = state%next_hi(d)
         ! (the share is used once)
         state%next_lo(d) = state%last
         state%next_hi(d) = state%last
      end if
      state%next_lo(d + 1) = state%lo(d + 1)
      state%next_hi(d + 1) = state%lo(d + 1)
      call progress_report(0.0_dp, stage)
   end subroutine progress_begin

   !> The long call opened last ends: it reports 1 (done at the end of its span).
   subroutine progress_end(stage)
      character(len=*), intent(in) :: stage   !< the stage its progress_begin named
      if (.not. progress_on() .or. state%depth == 0) return
      call progress_report(1.0_dp, stage)
      state%depth = state%depth - 1
   end subroutine progress_end

   !> The share [lo, hi] (fractions of the current call's span, 0 <= lo <= hi <= 1) that
   !> the next long call opened inside it reports in.
   subroutine progress_part(lo, hi)
      real(dp), intent(in) :: lo, hi   !< the share's ends, fractions of the current span
      integer :: d
      if (.not. progress_on()) return
      d = state%depth
      if (d < 1 .or. d > max_depth) return
      state%next_lo(d) = place(d, lo)
      state%next_hi(d) = place(d, max(lo, hi))
   end subroutine progress_part

   !> Report the fraction done of the current call (0 .. 1 of its span), with its stage.
   subroutine progress_report(fraction, stage)
      real(dp), intent(in) :: fraction   !< done, 0 .. 1 of the current call's span
      character(len=*), intent(in) :: stage   !< what is being done, as the hook hears it
      real(dp) :: done
      integer :: d
      if (.not. progress_on()) return
      d = state%depth
      if (d < 1 .or. d > max_depth) return
      if (state%hi(d) <= state%lo(d)) return   ! (a silent call: no share given)
      done = max(state%last, place(d, fraction))
      state%last = done
      call system_clock(state%last_call)
      state%calling = .true.
      call state%hook(done, stage)
      state%calling = .false.
   end subroutine progress_report

   !> A sign of life inside the current call (a mesh level, a Newton step): the hook is
   !> called with the last done again and stage, where a long step has no fraction of its
   !> own; at most one every note_interval seconds after the last call of the hook (the
   !> notes of a small-sigma first call came ~170 a second).
   subroutine progress_note(stage)
      character(len=*), intent(in) :: stage   !< what is being done, as the hook hears it
      real(dp), parameter :: note_interval = 0.5_dp
      integer(8) :: now, rate
      if (.not. progress_on()) return
      if (state%depth < 1 .or. state%depth > max_depth) return
      if (state%hi(state%depth) <= state%lo(state%depth)) return   ! (a silent call)
      call system_clock(now, rate)
      if (rate > 0 .and. real(now - state%last_call, dp) < note_interval*real(rate, dp)) return
      state%last_call = now
      state%calling = .true.
      call state%hook(state%last, stage)
      state%calling = .false.
   end subroutine progress_note

   !> A table build's hook (egw_table's table_progress: solves done of total so far)
   !> reporting through this thread's hook, stage "table build": pass it as a build's
   !> progress argument (the C entries do). total grows as a build refines; done stays
   !> monotone (progress_report), and the build's last report (done = total) is 1.
   subroutine progress_count(done, total)
      integer, intent(in) :: done, total   !< solves done, and of how many so far
      real(dp) :: fraction
      if (.not. progress_on() .or. total <= 0) return
      fraction = min(1.0_dp, max(0.0_dp, real(done, dp)/real(total, dp)))
      if (state%depth > 0) then
         call progress_report(fraction, "table build")
         return
      end if
      ! (outside any open call, a build of the caller's own: reported as one call whose
      ! end is the build's last report, done = total)
      state%depth = 1
      state%lo(1) = 0.0_dp
      state%hi(1) = 1.0_dp
      call progress_report(fraction, "table build")
      state%depth = 0
      if (fraction >= 1.0_dp) state%last = 0.0_dp
   end subroutine progress_count

   !> The global done of fraction x of open call d's span.
   pure real(dp) function place(d, x)
      integer, intent(in) :: d
      real(dp), intent(in) :: x
      place = state%lo(d) + min(1.0_dp, max(0.0_dp, x))*(state%hi(d) - state%lo(d))
   end function place
end module egw_progress
