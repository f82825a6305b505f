!> Atomic file output and whole-file input through the C library's stdio: a file is
!> built in memory, written to a fresh temporary file beside the target, flushed,
!> synced and closed with every return value checked, and only then renamed over the
!> target (rename(2) is atomic within a file system), so a full disk, a file-size
!> limit or an I/O error leaves an existing file untouched and no temporary behind.
!>
!> Why C stdio and not Fortran units: the system's reason for a failure (strerror of
!> errno: "No space left on device"), fsync before the rename, and an exclusive create
!> ("x") of a temporary file of this writer's own. The libc functions are reached
!> through interface blocks (system calls, not part of the C API).
module egw_io
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char, c_ptr, c_size_t, &
      & c_long, c_int64_t, c_associated, c_null_ptr, c_loc, c_f_pointer
   use, intrinsic :: iso_fortran_env, only: int64
   use egw_status, only: egw_error, egw_io_error, fatal_error
   use egw_text, only: int_text, int_text_len
   implicit none
   private

   public :: write_file, write_stream, read_file, rename_file, remove_file, text_buffer, &
      & file_size_limit
   ! Fortran-unit variants (kept for callers that write through a unit; prefer write_file)
   public :: open_temporary, commit_temporary, discard_temporary, make_directories

   !> A file's text built line by line in memory (capacity doubles as it grows).
   type :: text_buffer
      character(len=:), allocatable :: text
      integer :: n = 0
   contains
      procedure :: add => text_add
      procedure :: write => text_write
   end type text_buffer

   !> struct rlimit of getrlimit(2) (rlim_t is an unsigned long on Linux).
   type, bind(C) :: c_rlimit
      integer(c_long) :: cur, max
   end type c_rlimit

   !> RLIMIT_FSIZE (Linux, BSD, macOS: 1).
   integer(c_int), parameter :: rlimit_fsize = 1

   interface
      function c_rename(from, to) result(stat) bind(C, name="rename")
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: from(*), to(*)
         integer(c_int) :: stat
      end function c_rename
      function c_remove(path) result(stat) bind(C, name="remove")
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int) :: stat
      end function c_remove
      function c_mkdir(path, mode) result(stat) bind(C, name="mkdir")
         import :: c_int, c_char
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int), value :: mode
         integer(c_int) :: stat
      end function c_mkdir
      function c_fopen(path, mode) result(fp) bind(C, name="fopen")
         import :: c_ptr, c_char
         character(kind=c_char), intent(in) :: path(*), mode(*)
         type(c_ptr) :: fp
      end function c_fopen
      function c_fwrite(buf, size, n, fp) result(written) bind(C, name="fwrite")
         import :: c_ptr, c_size_t
         type(c_ptr), value, intent(in) :: buf, fp
         integer(c_size_t), value, intent(in) :: size, n
         integer(c_size_t) :: written
      end function c_fwrite
      function c_fread(buf, size, n, fp) result(got) bind(C, name="fread")
         import :: c_ptr, c_size_t
         type(c_ptr), value, intent(in) :: buf, fp
         integer(c_size_t), value, intent(in) :: size, n
         integer(c_size_t) :: got
      end function c_fread
      function c_fflush(fp) result(stat) bind(C, name="fflush")
         import :: c_ptr, c_int
         type(c_ptr), value, intent(in) :: fp
         integer(c_int) :: stat
      end function c_fflush
      function c_fclose(fp) result(stat) bind(C, name="fclose")
         import :: c_ptr, c_int
         type(c_ptr), value, intent(in) :: fp
         integer(c_int) :: stat
      end function c_fclose
      function c_fileno(fp) result(fd) bind(C, name="fileno")
         import :: c_ptr, c_int
         type(c_ptr), value, intent(in) :: fp
         integer(c_int) :: fd
      end function c_fileno
      function c_fsync(fd) result(stat) bind(C, name="fsync")
         import :: c_int
         integer(c_int), value, intent(in) :: fd
         integer(c_int) :: stat
      end function c_fsync
      function c_fseek(fp, offset, whence) result(stat) bind(C, name="fseek")
         import :: c_ptr, c_int, c_long
         type(c_ptr), value, intent(in) :: fp
         integer(c_long), value, intent(in) :: offset
         integer(c_int), value, intent(in) :: whence
         integer(c_int) :: stat
      end function c_fseek
      function c_ftell(fp) result(pos) bind(C, name="ftell")
         import :: c_ptr, c_long
         type(c_ptr), value, intent(in) :: fp
         integer(c_long) :: pos
      end function c_ftell
      function c_getpid() result(pid) bind(C, name="getpid")
         import :: c_int
         integer(c_int) :: pid
      end function c_getpid
      function c_getrlimit(resource, limit) result(stat) bind(C, name="getrlimit")
         import :: c_int, c_rlimit
         integer(c_int), value, intent(in) :: resource
         type(c_rlimit), intent(out) :: limit
         integer(c_int) :: stat
      end function c_getrlimit
      !> errno of the calling thread (glibc and musl).
      function c_errno_location() result(p) bind(C, name="__errno_location")
         import :: c_ptr
         type(c_ptr) :: p
      end function c_errno_location
      function c_strerror(errnum) result(p) bind(C, name="strerror")
         import :: c_ptr, c_int
         integer(c_int), value, intent(in) :: errnum
         type(c_ptr) :: p
      end function c_strerror
      pure function c_strlen(s) result(n) bind(C, name="strlen")
         import :: c_ptr, c_size_t
         type(c_ptr), value, intent(in) :: s
         integer(c_size_t) :: n
      end function c_strlen
   end interface

   integer(c_int), parameter :: seek_end = 2, seek_set = 0
   !> errno values (Linux) of an fsync that the file type does not support.
   integer(c_int), parameter :: errno_einval = 22, errno_erofs = 30, errno_enotsup = 95

contains

   ! ============================================================ whole files

   !> Write bytes to path atomically: a fresh temporary file beside path is written,
   !> flushed, synced (fsync) and closed, each step checked; then it is renamed over
   !> path. On any failure the temporary file is removed, an existing file at path is
   !> left as it was, and error gets egw_io_error with the path and the system's
   !> reason. A file larger than the process's file-size limit (ulimit -f) is refused
   !> before anything is written (writing it would raise SIGXFSZ, which kills the
   !> process and leaves the temporary file behind).
   subroutine write_file(path, bytes, error)
      character(len=*), intent(in) :: path   !< the file to replace atomically
      character(len=*), intent(in), target :: bytes   !< its whole content
      !> allocated on failure (path unchanged)
      type(egw_error), allocatable, intent(out) :: error
      character(len=:), allocatable :: tmp, why
      type(c_ptr) :: fp
      integer(int64) :: limit
      if (len(path) == 0) then
         call fatal_error(error, egw_io_error, "path: empty")
         return
      end if
      limit = file_size_limit()
      if (limit >= 0 .and. len(bytes, int64) > limit) then
         call fatal_error(error, egw_io_error, "path = "//path//": the file needs "// &
            & int_text(len(bytes, int64))//" bytes, above the file size limit of "// &
            & int_text(limit)//" bytes (ulimit -f); nothing written")
         return
      end if
      call create_temporary(path, fp, tmp, why)
      if (.not. c_associated(fp)) then
         call fatal_error(error, egw_io_error, "path = "//path//": cannot create the "// &
            & "temporary file "//tmp//" ("//why//"); nothing written")
         return
      end if
      call write_and_close(fp, bytes, why)
      if (len(why) > 0) then
         call remove_file(tmp)
         call fatal_error(error, egw_io_error, "path = "//path//": writing failed ("// &
            & why//"); the temporary file is removed and an existing file is unchanged")
         return
      end if
      call rename_file(tmp, path, error)
      if (allocated(error)) call remove_file(tmp)
   end subroutine write_file

   !> Write bytes into the file or device at path in place (no temporary file, no
   !> rename: for devices and pipes, or where atomicity is not wanted), with the checks
   !> of write_file: egw_io_error with the system's reason if any step fails.
   subroutine write_stream(path, bytes, error)
      character(len=*), intent(in) :: path   !< the file or device to write
      character(len=*), intent(in) :: bytes   !< what to write, as it is
      !> egw_io_error naming path and the system's reason
      type(egw_error), allocatable, intent(out) :: error
      character(len=:), allocatable :: why
      type(c_ptr) :: fp
      call open_file(path, "wb", fp, error)
      if (allocated(error)) return
      call write_and_close(fp, bytes, why)
      if (len(why) > 0) call fatal_error(error, egw_io_error, "path = "//path// &
         & ": writing failed ("//why//")")
   end subroutine write_stream

   !> fopen(path, mode) of write_stream and read_file: fp, or egw_io_error naming path and
   !> the system's reason (fp then null).
   subroutine open_file(path, mode, fp, error)
      character(len=*), intent(in) :: path   !< the file to open
      character(len=*), intent(in) :: mode   !< fopen's mode ("rb", "wb")
      type(c_ptr), intent(out) :: fp   !< the open stream (null on failure)
      !> egw_io_error naming path and the system's reason
      type(egw_error), allocatable, intent(out) :: error
      character(len=:), allocatable :: why
      fp = c_fopen(path//c_null_char, mode//c_null_char)
      if (c_associated(fp)) return
      call system_reason(why)
      call fatal_error(error, egw_io_error, "path = "//path//": cannot open ("//why//")")
   end subroutine open_file

   !> fwrite, fflush, fsync and fclose, each checked; why: "" or what failed and why.
   !> fsync refused by a device or pipe (EINVAL, EROFS, ENOTSUP) is not a failure.
   subroutine write_and_close(fp, bytes, why)
      type(c_ptr), intent(in) :: fp
      character(len=*), intent(in), target :: bytes
      character(len=:), allocatable, intent(out) :: why
      integer(c_int), pointer :: errno
      why = ""
      if (len(bytes) > 0) then
         if (c_fwrite(c_loc(bytes), 1_c_size_t, int(len(bytes), c_size_t), fp) /= &
            & int(len(bytes), c_size_t)) call failed("write", why)
      end if
      if (len(why) == 0) then
         if (c_fflush(fp) /= 0) call failed("flush", why)
      end if
      if (len(why) == 0) then
         if (c_fsync(c_fileno(fp)) /= 0) then
            call c_f_pointer(c_errno_location(), errno)
            if (all(errno /= [errno_einval, errno_erofs, errno_enotsup])) &
               & call failed("fsync", why)
         end if
      end if
      if (c_fclose(fp) /= 0 .and. len(why) == 0) call failed("close", why)
   end subroutine write_and_close

   !> The whole file at path as bytes. egw_io_error if it cannot be opened or read.
   subroutine read_file(path, bytes, error)
      character(len=*), intent(in) :: path   !< the file to read
      character(len=:), allocatable, target, intent(out) :: bytes   !< its whole content
      !> egw_io_error naming path and the system's reason
      type(egw_error), allocatable, intent(out) :: error
      type(c_ptr) :: fp
      integer(c_long) :: size
      integer(c_size_t) :: got
      character(len=:), allocatable :: why
      character(len=1), target :: first
      integer(c_int), pointer :: errno
      if (len(path) == 0) then
         call fatal_error(error, egw_io_error, "path: empty")
         return
      end if
      call open_file(path, "rb", fp, error)
      if (allocated(error)) return
      why = ""
      size = -1
      ! a directory opens and seeks (to a huge "size" on ext4): one byte read says what it is
      call c_f_pointer(c_errno_location(), errno)
      errno = 0
      got = c_fread(c_loc(first), 1_c_size_t, 1_c_size_t, fp)
      if (got == 0 .and. errno /= 0) then
         call failed("read", why)
      else if (c_fseek(fp, 0_c_long, seek_end) == 0) then
         size = c_ftell(fp)
      end if
      if (len(why) > 0) then
         ! the reason is given
      else if (size < 0) then
         why = "not a regular file, or its size is unknown"
      else if (size > huge(1)) then
         why = "larger than "//int_text(int(huge(1), int64))//" bytes"
      else if (c_fseek(fp, 0_c_long, seek_set) /= 0) then
         call failed("seek", why)
      else
         allocate (character(len=int(size)) :: bytes)
         if (size > 0) then
            got = c_fread(c_loc(bytes), 1_c_size_t, int(size, c_size_t), fp)
            if (got /= int(size, c_size_t)) call failed("read", why)
         end if
      end if
      if (c_fclose(fp) /= 0 .and. len(why) == 0) call failed("close", why)
      if (len(why) > 0) then
         if (allocated(bytes)) deallocate (bytes)
         call fatal_error(error, egw_io_error, "path = "//path//": cannot read ("// &
            & why//")")
      end if
   end subroutine read_file

   !> Rename a file onto path (atomic within a file system; replaces an existing path).
   subroutine rename_file(from, path, error)
      character(len=*), intent(in) :: from, path   !< the file renamed, and the path it takes
      !> egw_io_error naming both and the system's reason
      type(egw_error), allocatable, intent(out) :: error
      character(len=:), allocatable :: why
      if (c_rename(from//c_null_char, path//c_null_char) /= 0) then
         call system_reason(why)
         call fatal_error(error, egw_io_error, "path = "//path//": cannot rename "// &
            & from//" onto it ("//why//")")
      end if
   end subroutine rename_file

   !> Remove a file if it exists (errors ignored: used to clean up after a failure).
   subroutine remove_file(path)
      character(len=*), intent(in) :: path   !< the file to remove
      integer(c_int) :: ignored
      ignored = c_remove(path//c_null_char)
   end subroutine remove_file

   !> mkdir -p: every missing directory of path (0777 before the umask); true when path is
   !> a directory at the end (whoever made it: concurrent callers are fine).
   logical function make_directories(path) result(ok)
      character(len=*), intent(in) :: path   !< the directory
      integer :: k
      integer(c_int) :: ignored
      do k = 2, len(path)
         if (path(k:k) == "/") ignored = c_mkdir(path(:k - 1)//c_null_char, int(o'777', c_int))
      end do
      ignored = c_mkdir(path//c_null_char, int(o'777', c_int))
      inquire (file=path//"/.", exist=ok)
   end function make_directories

   !> The soft file-size limit of this process in bytes (ulimit -f), -1 if unlimited.
   function file_size_limit() result(limit)
      integer(int64) :: limit
      type(c_rlimit) :: rl
      limit = -1
      if (c_getrlimit(rlimit_fsize, rl) /= 0) return
      ! RLIM_INFINITY is all bits set on Linux (-1 here) and 2^63 - 1 on BSD and macOS
      if (rl%cur >= 0 .and. rl%cur < huge(rl%cur)) limit = int(rl%cur, int64)
   end function file_size_limit

   ! ============================================================ text buffer

   !> Append line and a newline.
   pure subroutine text_add(self, line)
      class(text_buffer), intent(inout) :: self
      character(len=*), intent(in) :: line
      character(len=:), allocatable :: grown
      integer :: need
      need = self%n + len(line) + 1
      if (.not. allocated(self%text)) allocate (character(len=max(4096, 2*need)) :: self%text)
      if (need > len(self%text)) then
         allocate (character(len=max(2*len(self%text), need)) :: grown)
         grown(1:self%n) = self%text(1:self%n)
         call move_alloc(grown, self%text)
      end if
      self%text(self%n + 1:need - 1) = line
      self%text(need:need) = new_line("a")
      self%n = need
   end subroutine text_add

   !> Write the text added so far to path (write_file: atomic, every step checked).
   subroutine text_write(self, path, error)
      class(text_buffer), intent(in) :: self
      character(len=*), intent(in) :: path
      type(egw_error), allocatable, intent(out) :: error
      if (allocated(self%text)) then
         call write_file(path, self%text(1:self%n), error)
      else
         call write_file(path, "", error)
      end if
   end subroutine text_write

   ! ============================================================ Fortran units

   !> Open a fresh temporary file for path; tmp_path receives its name.
   !> binary (default false): unformatted stream access, for byte-exact binary formats.
   !> Prefer write_file: this temporary's name is not unique to the writer (two threads
   !> writing the same path share it) and a unit gives no fsync.
   subroutine open_temporary(path, unit, tmp_path, error, binary)
      character(len=*), intent(in) :: path   !< the file the temporary will replace
      integer, intent(out) :: unit   !< the open unit
      character(len=:), allocatable, intent(out) :: tmp_path   !< the temporary's name
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      logical, intent(in), optional :: binary   !< optional, default false: unformatted stream
      integer :: ios
      character(len=256) :: msg
      logical :: stream
      stream = .false.
      if (present(binary)) stream = binary
      tmp_path = path//".egw-tmp"
      if (stream) then
         open (newunit=unit, file=tmp_path, status="replace", action="write", &
            & form="unformatted", access="stream", iostat=ios, iomsg=msg)
      else
         open (newunit=unit, file=tmp_path, status="replace", action="write", &
            & form="formatted", iostat=ios, iomsg=msg)
      end if
      if (ios /= 0) then
         call fatal_error(error, egw_io_error, "path = "//path//": cannot create "// &
            & tmp_path//" ("//trim(msg)//")")
      end if
   end subroutine open_temporary

   !> Flush and close the temporary file (both checked), then rename it over path; on
   !> failure the temporary file is removed.
   subroutine commit_temporary(unit, tmp_path, path, error)
      integer, intent(in) :: unit   !< from open_temporary
      character(len=*), intent(in) :: tmp_path   !< from open_temporary
      character(len=*), intent(in) :: path   !< the file to replace
      !> allocated on failure (path unchanged)
      type(egw_error), allocatable, intent(out) :: error
      integer :: ios
      character(len=256) :: msg
      msg = ""
      flush (unit, iostat=ios, iomsg=msg)
      if (ios == 0) then
         close (unit, iostat=ios, iomsg=msg)
      else
         call discard_temporary(unit, tmp_path)
      end if
      if (ios /= 0) then
         call remove_file(tmp_path)
         call fatal_error(error, egw_io_error, "path = "//path//": cannot write "// &
            & tmp_path//" ("//trim(msg)//"); an existing file is unchanged")
         return
      end if
      call rename_file(tmp_path, path, error)
      if (allocated(error)) call remove_file(tmp_path)
   end subroutine commit_temporary

   !> Abandon a temporary file (after a failure while writing it).
   subroutine discard_temporary(unit, tmp_path)
      integer, intent(in) :: unit   !< from open_temporary
      character(len=*), intent(in) :: tmp_path   !< from open_temporary
      integer :: ios
      close (unit, status="delete", iostat=ios)
      if (ios /= 0) call remove_file(tmp_path)
   end subroutine discard_temporary

   ! ============================================================ helpers

   !> Create a temporary file beside path that no other writer uses: the name carries
   !> the process id and an address on this thread's stack (distinct between threads
   !> running at the same time), and fopen's "x" mode refuses an existing file (then
   !> the next of a few numbered names is tried). why: the reason of a failure.
   subroutine create_temporary(path, fp, tmp, why)
      character(len=*), intent(in) :: path
      type(c_ptr), intent(out) :: fp
      character(len=:), allocatable, intent(out) :: tmp, why
      integer, target :: marker
      integer(c_int64_t) :: address
      integer :: attempt
      address = transfer(c_loc(marker), address)
      fp = c_null_ptr
      why = ""
      do attempt = 0, 7
         tmp = path//".egw-tmp-"//int_text(int(c_getpid(), int64))//"-"// &
            & int_text(address)//"-"//int_text(attempt)
         fp = c_fopen(tmp//c_null_char, "wbx"//c_null_char)
         if (c_associated(fp)) return
         call system_reason(why)
      end do
   end subroutine create_temporary

   !> The text of errno (strerror) and its number.
   subroutine system_reason(text)
      character(len=:), allocatable, intent(out) :: text
      integer(c_int), pointer :: errno
      integer(c_int) :: code
      type(c_ptr) :: msg
      character(kind=c_char), pointer :: chars(:)
      integer :: n, i
      call c_f_pointer(c_errno_location(), errno)
      code = errno
      msg = c_strerror(code)
      n = 0
      if (c_associated(msg)) n = int(c_strlen(msg))
      allocate (character(len=n) :: text)
      if (n > 0) call c_f_pointer(msg, chars, [n])
      do i = 1, n
         text(i:i) = chars(i)
      end do
      text = text//", errno "//int_text(int(code))
   end subroutine system_reason

   !> why = what//": "//errno's text.
   subroutine failed(what, why)
      character(len=*), intent(in) :: what
      character(len=:), allocatable, intent(inout) :: why
      character(len=:), allocatable :: reason
      call system_reason(reason)
      why = what//": "//reason
   end subroutine failed

end module egw_io
