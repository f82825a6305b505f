!> egw binary: versioned, little-endian checked, FNV-1a checksummed (doc/formats.md).
!> The binary submodule of egw_table_format (src/egw/formats/table_format.f90), whose
!> interface block declares the entry points implemented here.
submodule (egw_table_format) egw_table_format_binary
   implicit none

   integer(int32), parameter :: byte_order_mark = int(z'01020304', int32)
   !> Fixed part of a 1-D table file before the arrays (doc/formats.md).
   integer, parameter :: table_header_bytes = 144
   integer, parameter :: universal_header_bytes = 104, slice_header_bytes = 64

contains

   module procedure write_table_binary
      character(len=:), allocatable :: buf
      integer :: n, pos
      n = size(table%delta)
      if (.not. (row_ok(table%delta) .and. row_ok(table%force) .and. row_ok(table%stiffness) &
         & .and. row_ok(table%energy) .and. row_ok(table%contact_radius))) then
         call fatal_error(error, egw_invalid_argument, "table: a node is not finite; "// &
            & "nothing written")
         return
      end if
      allocate (character(len=table_header_bytes + 40*n + 4) :: buf)
      buf(1:8) = magic_table
      pos = 9
      call put_i32(buf, pos, binary_version)
      call put_i32(buf, pos, byte_order_mark)
      call put_i32(buf, pos, int(egw_version_number, int32))
      call put_i32(buf, pos, int(table%params%model, int32))
      call put_i32(buf, pos, int(n, int32))
      call put_i32(buf, pos, int(table%n_log, int32))
      call put_f64(buf, pos, [table%params%radius, table%params%modulus, table%params%sigma, &
         & table%params%mu, table%params%psi, table%params%hardness_coeff, &
         & table%params%plastic_ratio])
      call put_f64(buf, pos, table_meta(table))
      call put_nodes(buf, pos, table)
      call write_checked(path, buf, pos, error)
   end procedure write_table_binary

   module procedure write_universal_binary
      character(len=:), allocatable :: buf
      integer :: nbytes, pos, j, n
      nbytes = universal_header_bytes + 4
      do j = 1, table%n_mu
         nbytes = nbytes + slice_header_bytes + 40*size(table%slices(j)%delta)
      end do
      allocate (character(len=nbytes) :: buf)
      buf(1:8) = magic_universal
      pos = 9
      call put_i32(buf, pos, binary_version)
      call put_i32(buf, pos, byte_order_mark)
      call put_i32(buf, pos, int(egw_version_number, int32))
      call put_i32(buf, pos, int(table%model, int32))
      call put_i32(buf, pos, int(table%n_mu, int32))
      call put_i32(buf, pos, 0_int32)
      call put_f64(buf, pos, [table%psi, table%hardness_coeff, table%plastic_ratio, &
         & table%rel_tol, table%x_cut, table%x_max, table%mu_min, table%mu_max, &
         & table%max_mu_error])
      do j = 1, table%n_mu
         associate (s => table%slices(j))
            n = size(s%delta)
            call put_i32(buf, pos, int(n, int32))
            call put_i32(buf, pos, int(s%n_log, int32))
            call put_f64(buf, pos, [s%rel_tol, s%cutoff, s%delta_max, s%reference_force, &
               & s%max_force_error, s%max_stiffness_error, s%params%mu])
            call put_nodes(buf, pos, s)
         end associate
      end do
      call write_checked(path, buf, pos, error)
   end procedure write_universal_binary

   module procedure parse_table_binary
      type(force_table) :: t
      integer :: pos, n
      integer(int32) :: model
      real(dp) :: p(7), meta(7)

      call check_binary_frame(path, bytes, table_header_bytes, error)
      if (allocated(error)) return
      pos = 21
      model = get_i32(bytes, pos)
      n = get_i32(bytes, pos)
      t%n_log = get_i32(bytes, pos)
      if (n < 2 .or. len(bytes) /= table_header_bytes + 40*int(n, int64) + 4) then
         call bad(error, path, "n_nodes = "//int_str(n)//" does not match the file size "// &
            & int_str(len(bytes)))
         return
      end if
      call get_f64(bytes, pos, p)
      call get_f64(bytes, pos, meta)
      t%params = contact_params(model=int(model), radius=p(1), modulus=p(2), sigma=p(3), &
         & mu=p(4), psi=p(5), hardness_coeff=p(6), plastic_ratio=p(7))
      call set_table_meta(t, meta)
      call get_nodes(bytes, pos, n, t)
      ! (a table of a flat law is a table like any other: its tail needs no law)
      call validate_params(t%params, error, allow_flat_law=.true.)
      if (allocated(error)) then
         call bad(error, path, "stored parameters invalid: "//error%message)
         return
      end if
      call check_table(path, "", t, error)
      if (allocated(error)) return
      call table_prepare(t)
      call move_table(t, table)
   end procedure parse_table_binary

   module procedure parse_universal_binary
      type(universal_table) :: u
      integer :: pos, j, n
      real(dp) :: h(9), meta(7)

      call check_binary_frame(path, bytes, universal_header_bytes, error)
      if (allocated(error)) return
      pos = 21
      u%model = get_i32(bytes, pos)
      u%n_mu = get_i32(bytes, pos)
      pos = pos + 4
      call get_f64(bytes, pos, h)
      u%psi = h(1); u%hardness_coeff = h(2); u%plastic_ratio = h(3); u%rel_tol = h(4)
      u%x_cut = h(5); u%x_max = h(6); u%mu_min = h(7); u%mu_max = h(8); u%max_mu_error = h(9)
      call check_universal_header(path, u, error)
      if (allocated(error)) return
      allocate (u%slices(u%n_mu))
      do j = 1, u%n_mu
         if (pos + slice_header_bytes > len(bytes) - 4) then
            call bad(error, path, "slice "//int_str(j)//": file too short")
            return
         end if
         n = get_i32(bytes, pos)
         u%slices(j)%n_log = get_i32(bytes, pos)
         call get_f64(bytes, pos, meta)
         if (n < 2 .or. pos - 1 + 40*int(n, int64) > len(bytes) - 4) then
            call bad(error, path, "slice "//int_str(j)//": n_nodes = "//int_str(n)// &
               & " does not fit the file size")
            return
         end if
         associate (s => u%slices(j))
            call set_table_meta(s, [meta(1:6), 0.0_dp])
            s%params = universal_slice_params(u%model, u%psi, u%hardness_coeff, &
               & u%plastic_ratio, meta(7))
            call get_nodes(bytes, pos, n, s)
            if (abs(meta(7) - slice_mu(u, j)) > 1.0e-12_dp*meta(7)) then
               call bad(error, path, "slice "//int_str(j)//": mu = "//format_real(meta(7))// &
                  & " is not on the grid")
               return
            end if
            call check_table(path, "slice "//int_str(j)//": ", s, error)
            if (allocated(error)) return
            call table_prepare(s)
         end associate
      end do
      if (pos /= len(bytes) - 3) then
         call bad(error, path, "file size does not match its slices")
         return
      end if
      call check_universal_slices(path, u, error)
      if (allocated(error)) return
      call move_universal(u, table)
   end procedure parse_universal_binary

   !> Append the checksum of buf(1:pos-1) and write buf atomically.
   subroutine write_checked(path, buf, pos, error)
      character(len=*), intent(in) :: path
      character(len=*), intent(inout) :: buf
      integer, intent(inout) :: pos
      type(egw_error), allocatable, intent(out) :: error
      call put_i32(buf, pos, checksum_i32(fnv1a32(buf(1:pos - 1))))
      call write_file(path, buf(1:pos - 1), error)
   end subroutine write_checked

   !> Magic, version, byte order, minimum size and checksum of a binary file.
   subroutine check_binary_frame(path, bytes, header_bytes, error)
      character(len=*), intent(in) :: path, bytes
      integer, intent(in) :: header_bytes
      type(egw_error), allocatable, intent(out) :: error
      integer :: pos
      integer(int32) :: version, bom, stored
      if (len(bytes) < header_bytes + 4) then
         call bad(error, path, "truncated: "//int_str(len(bytes))//" bytes, header needs "// &
            & int_str(header_bytes + 4))
         return
      end if
      pos = 9
      version = get_i32(bytes, pos)
      bom = get_i32(bytes, pos)
      if (bom /= byte_order_mark) then
         call bad(error, path, "byte order mark "//int_str(int(bom))//": written on a "// &
            & "machine of the other endianness, or corrupted")
         return
      end if
      if (version /= binary_version) then
         call bad(error, path, "format version "//int_str(int(version))// &
            & " is not supported (this egw reads version "//int_str(int(binary_version))//")")
         return
      end if
      pos = len(bytes) - 3
      stored = get_i32(bytes, pos)
      if (stored /= checksum_i32(fnv1a32(bytes(1:len(bytes) - 4)))) then
         call bad(error, path, "checksum mismatch: file is corrupted or truncated")
         return
      end if
   end subroutine check_binary_frame

   pure subroutine put_i32(buf, pos, v)
      character(len=*), intent(inout) :: buf
      integer, intent(inout) :: pos
      integer(int32), intent(in) :: v
      buf(pos:pos + 3) = transfer(v, buf(pos:pos + 3))
      pos = pos + 4
   end subroutine put_i32

   integer(int32) function get_i32(buf, pos) result(v)
      character(len=*), intent(in) :: buf
      integer, intent(inout) :: pos
      v = transfer(buf(pos:pos + 3), v)
      pos = pos + 4
   end function get_i32

end submodule egw_table_format_binary
