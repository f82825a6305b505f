!> A one-line text progress bar on stderr for the table builds of egw-table, fed by the
!> library's progress hook (egw_table's table_progress). The bar's state is module data:
!> this is the application's own single-threaded state (the library calls the hook only
!> from the serial part of a build), not library state. A module procedure rather than
!> an internal procedure of the program, because passing an internal procedure that
!> uses host variables needs a trampoline (an executable stack with gfortran).
module egw_progress_bar
   use, intrinsic :: iso_fortran_env, only: error_unit, int64
   implicit none
   private

   public :: bar_start, bar_update, bar_finish

   !> width of the bar in characters, and the least time between redraws (s); in a log
   !> (stderr not a terminal) a plain line at most every log_interval seconds
   integer, parameter :: bar_width = 30
   real, parameter :: min_interval = 0.1, log_interval = 5.0

   character(len=:), allocatable :: label
   !> what the counts count ("solves" unless bar_start says otherwise)
   character(len=:), allocatable :: unit_name
   integer :: last_done = 0, last_total = 0, last_len = 0
   integer(int64) :: last_draw = 0, clock_rate = 1
   logical :: active = .false., drawn = .false., stale = .false., plain = .false.

contains

   !> Start a bar named name (drawn at the first update). terminal: stderr is a terminal
   !> (a bar redrawn in place); otherwise plain progress lines, one every log_interval s.
   subroutine bar_start(name, terminal, counts)
      character(len=*), intent(in) :: name
      logical, intent(in) :: terminal
      character(len=*), intent(in), optional :: counts
      plain = .not. terminal
      label = name
      unit_name = "solves"
      if (present(counts)) unit_name = counts
      last_done = 0
      last_total = 0
      last_len = 0
      drawn = .false.
      stale = .false.
      active = .true.
      call system_clock(last_draw, clock_rate)
   end subroutine bar_start

   !> Progress hook (interface table_progress): remember the state and redraw at most
   !> every min_interval seconds, so that a fast build does not flood the terminal.
   subroutine bar_update(done, total)
      integer, intent(in) :: done, total
      integer(int64) :: now
      if (.not. active) return
      last_done = done
      last_total = total
      call system_clock(now)
      stale = drawn .and. real(now - last_draw)/real(clock_rate) < &
         & merge(log_interval, min_interval, plain)
      if (stale) return
      last_draw = now
      call draw(.false.)
      drawn = .true.
   end subroutine bar_update

   !> Draw the last state (unless it is on screen) and end the line (only if a bar was
   !> started and drawn).
   subroutine bar_finish()
      if (.not. active) return
      active = .false.
      if (stale .or. (plain .and. .not. drawn .and. last_total > 0)) then
         call draw(.true.)
      else if (drawn .and. .not. plain) then
         write (error_unit, '(a)') ""
         flush (error_unit)
      end if
   end subroutine bar_finish

   subroutine draw(final)
      logical, intent(in) :: final
      character(len=:), allocatable :: line
      character(len=16) :: pct, solves
      integer :: filled, percent
      percent = 0
      if (last_total > 0) percent = int(100.0*real(last_done)/real(last_total))
      percent = max(0, min(100, percent))
      filled = (percent*bar_width)/100
      write (pct, '(i3,a)') percent, "%"
      write (solves, '(i0)') last_done
      line = "  "//label//" ["//repeat("#", filled)//repeat(".", bar_width - filled)// &
         & "] "//trim(pct)//"  ("//trim(solves)//" "//unit_name//")"
      ! blank out what is left of a longer previous line
      if (len(line) < last_len) line = line//repeat(" ", last_len - len(line))
      last_len = len(line)
      if (plain) then
         write (error_unit, '(a)') "egw-table: "//trim(adjustl(line))
      else if (final) then
         write (error_unit, '(a)') achar(13)//line
      else
         write (error_unit, '(a)', advance='no') achar(13)//line
      end if
      flush (error_unit)
   end subroutine draw

end module egw_progress_bar
