!> egw CSV: the metadata header, the data rows and the checksum line (doc/formats.md).
!> The CSV submodule of egw_table_format (src/egw/formats/table_format.f90), whose
!> interface block declares the entry points implemented here.
submodule (egw_table_format) egw_table_format_csv
   implicit none

   !> key = value pairs of a CSV header.
   type :: header_dict
      character(len=64), allocatable :: keys(:)
      character(len=256), allocatable :: values(:)
      integer :: n = 0
   end type header_dict

contains

   module procedure write_table_csv
      integer :: i
      type(text_buffer) :: out
      ! the column header first and the metadata as '#' lines: pandas.read_csv(path,
      ! comment="#"), numpy.loadtxt(path, delimiter=",", skiprows=1) and
      ! numpy.genfromtxt(path, delimiter=",", names=True) read it as it is
      call out%add(csv_columns_table)
      call out%add("# egw force table, CSV format 3")
      call out%add("# egw_version = "//egw_version_string)
      call write_params_csv(out, table%params)
      call write_table_meta_csv(out, "", table)
      call out%add("# units = consistent set of the parameters: delta, "// &
         & "contact_radius [length]; force [modulus*length^2]; stiffness [modulus*length]; "// &
         & "energy [modulus*length^3]")
      call out%add("# interpolation = cubic Hermite in delta with stiffness as slope; "// &
         & "ln(force) in intervals 1..n_log; below cutoff and above delta_max the rules "// &
         & "of doc/formats.md (rough models: 0 below cutoff); energy = int of force from "// &
         & "cutoff")
      do i = 1, size(table%delta)
         if (.not. row_ok([table%delta(i), table%force(i), table%stiffness(i), &
            & table%energy(i), table%contact_radius(i)])) then
            call fatal_error(error, egw_invalid_argument, "table: node "//int_str(i)// &
               & " is not finite; nothing written")
            return
         end if
         call out%add(csv_row([table%delta(i), table%force(i), table%stiffness(i), &
            & table%energy(i), table%contact_radius(i)]))
      end do
      call out%add("# end of table, "//int_str(size(table%delta))//" rows")
      call add_checksum(out)
      call out%write(path, error)
   end procedure write_table_csv

   module procedure write_universal_csv
      integer :: i, j, nrows
      type(text_buffer) :: out
      call out%add(csv_columns_universal)  ! first: see write_table_csv
      call out%add("# egw universal table, CSV format 3")
      call out%add("# egw_version = "//egw_version_string)
      call out%add("# model = "//int_str(table%model)//" ("//model_name(table%model)//")")
      call kv(out, "psi", table%psi)
      call kv(out, "hardness_coeff", table%hardness_coeff)
      call kv(out, "plastic_ratio", table%plastic_ratio)
      call kv(out, "rel_tol", table%rel_tol)
      call kv(out, "x_cut", table%x_cut)
      call kv(out, "x_max", table%x_max)
      call kv(out, "mu_min", table%mu_min)
      call kv(out, "mu_max", table%mu_max)
      call kv(out, "max_mu_error", table%max_mu_error)
      call out%add("# n_mu = "//int_str(table%n_mu))
      call out%add("# units = dimensionless: x = delta/sigma; p = P/(E sqrt(R) "// &
         & "sigma^1.5); dp_dx; energy = W/(E sqrt(R) sigma^2.5); contact_radius = "// &
         & "a/sqrt(R sigma); mu_j = mu_min (mu_max/mu_min)^((j-1)/(n_mu-1))")
      do j = 1, table%n_mu
         call kv(out, "slice."//int_str(j)//".mu", table%slices(j)%params%mu)
         call write_table_meta_csv(out, "slice."//int_str(j)//".", table%slices(j))
      end do
      nrows = 0
      do j = 1, table%n_mu
         associate (s => table%slices(j))
            do i = 1, size(s%delta)
               if (.not. row_ok([s%delta(i), s%force(i), s%stiffness(i), s%energy(i), &
                  & s%contact_radius(i)])) then
                  call fatal_error(error, egw_invalid_argument, "table: slice "// &
                     & int_str(j)//" node "//int_str(i)//" is not finite; nothing written")
                  return
               end if
               call out%add(int_str(j)//","//csv_row([s%delta(i), s%force(i), &
                  & s%stiffness(i), s%energy(i), s%contact_radius(i)]))
               nrows = nrows + 1
            end do
         end associate
      end do
      call out%add("# end of table, "//int_str(nrows)//" rows")
      call add_checksum(out)
      call out%write(path, error)
   end procedure write_universal_csv

   module procedure parse_table_csv
      type(header_dict) :: dict
      type(force_table) :: t
      real(dp), allocatable :: rows(:, :)
      integer, allocatable :: idx(:)
      integer :: n

      call parse_csv(path, text, 5, csv_columns_table, dict, rows, idx, error, &
         & t%checksum_missing)
      if (allocated(error)) return
      call get_params(path, dict, t%params, error)
      if (allocated(error)) return
      call get_table_meta(path, dict, "", t, n, error)
      if (allocated(error)) return
      if (size(rows, 2) /= n) then
         call bad(error, path, "n_nodes = "//int_str(n)//" but "//int_str(size(rows, 2))// &
            & " data rows")
         return
      end if
      call set_nodes(t, rows)
      call check_table(path, "", t, error)
      if (allocated(error)) return
      call table_prepare(t)
      call move_table(t, table)
   end procedure parse_table_csv

   module procedure parse_universal_csv
      type(header_dict) :: dict
      type(universal_table) :: u
      real(dp), allocatable :: rows(:, :)
      integer, allocatable :: idx(:)
      integer :: j, n, first
      real(dp) :: mu
      character(len=:), allocatable :: prefix
      logical :: missing

      call parse_csv(path, text, 5, csv_columns_universal, dict, rows, &
         & idx, error, missing)
      if (allocated(error)) return
      call get_int(path, dict, "model", u%model, error)
      if (.not. allocated(error)) call get_real(path, dict, "psi", u%psi, error)
      if (.not. allocated(error)) call get_real(path, dict, "hardness_coeff", &
         & u%hardness_coeff, error)
      if (.not. allocated(error)) call get_real(path, dict, "plastic_ratio", &
         & u%plastic_ratio, error)
      if (.not. allocated(error)) call get_real(path, dict, "rel_tol", u%rel_tol, error)
      if (.not. allocated(error)) call get_real(path, dict, "x_cut", u%x_cut, error)
      if (.not. allocated(error)) call get_real(path, dict, "x_max", u%x_max, error)
      if (.not. allocated(error)) call get_real(path, dict, "mu_min", u%mu_min, error)
      if (.not. allocated(error)) call get_real(path, dict, "mu_max", u%mu_max, error)
      if (.not. allocated(error)) call get_real(path, dict, "max_mu_error", u%max_mu_error, error)
      if (.not. allocated(error)) call get_int(path, dict, "n_mu", u%n_mu, error)
      if (allocated(error)) return
      call check_universal_header(path, u, error)
      if (allocated(error)) return
      allocate (u%slices(u%n_mu))
      first = 1
      do j = 1, u%n_mu
         prefix = "slice."//int_str(j)//"."
         call get_table_meta(path, dict, prefix, u%slices(j), n, error)
         if (.not. allocated(error)) call get_real(path, dict, prefix//"mu", mu, error)
         if (allocated(error)) return
         if (abs(mu - slice_mu(u, j)) > 1.0e-12_dp*mu) then
            call bad(error, path, "slice "//int_str(j)//": mu = "//format_real(mu)// &
               & " is not on the grid")
            return
         end if
         if (first + n - 1 > size(rows, 2)) then
            call bad(error, path, "slice "//int_str(j)//": fewer data rows than n_nodes")
            return
         end if
         if (any(idx(first:first + n - 1) /= j)) then
            call bad(error, path, "slice "//int_str(j)//": rows out of order or missing")
            return
         end if
         u%slices(j)%params = universal_slice_params(u%model, u%psi, u%hardness_coeff, &
            & u%plastic_ratio, mu)
         call set_nodes(u%slices(j), rows(:, first:first + n - 1))
         call check_table(path, "slice "//int_str(j)//": ", u%slices(j), error)
         if (allocated(error)) return
         call table_prepare(u%slices(j))
         first = first + n
      end do
      if (first - 1 /= size(rows, 2)) then
         call bad(error, path, "more data rows than the slices' n_nodes")
         return
      end if
      call check_universal_slices(path, u, error)
      if (allocated(error)) return
      call move_universal(u, table)
   end procedure parse_universal_csv

   subroutine write_params_csv(out, p)
      type(text_buffer), intent(inout) :: out
      type(contact_params), intent(in) :: p
      call out%add("# model = "//int_str(p%model)//" ("//model_name(p%model)//")")
      call kv(out, "radius", p%radius)
      call kv(out, "modulus", p%modulus)
      call kv(out, "sigma", p%sigma)
      call kv(out, "mu", p%mu)
      call kv(out, "psi", p%psi)
      call kv(out, "hardness_coeff", p%hardness_coeff)
      call kv(out, "plastic_ratio", p%plastic_ratio)
   end subroutine write_params_csv

   subroutine write_table_meta_csv(out, prefix, t)
      type(text_buffer), intent(inout) :: out
      character(len=*), intent(in) :: prefix
      type(force_table), intent(in) :: t
      call kv(out, prefix//"rel_tol", t%rel_tol)
      call kv(out, prefix//"cutoff", t%cutoff)
      call kv(out, prefix//"delta_max", t%delta_max)
      call kv(out, prefix//"reference_force", t%reference_force)
      call kv(out, prefix//"max_force_error", t%max_force_error)
      call kv(out, prefix//"max_stiffness_error", t%max_stiffness_error)
      call kv(out, prefix//"radius_sum", t%radius_sum)
      call out%add("# "//prefix//"n_nodes = "//int_str(size(t%delta)))
      call out%add("# "//prefix//"n_log = "//int_str(t%n_log))
   end subroutine write_table_meta_csv

   !> Split a CSV file into its "# key = value" header, check the column header line,
   !> read ncol reals per data row (after an integer index when the columns start with
   !> "mu_index") and require the "# end of table, N rows" trailer (so that a file cut
   !> inside its last number is detected). A last line "# fnv1a32 = ..." (CSV format
   !> 3) must match the checksum of the bytes above it; checksum_missing tells whether
   !> it was absent (a format 1 or 2 file, or a hand-edited one).
   subroutine parse_csv(path, file_text, ncol, columns, dict, rows, idx, error, &
      & checksum_missing)
      character(len=*), intent(in) :: path, file_text, columns
      logical, intent(out) :: checksum_missing
      integer, intent(in) :: ncol
      type(header_dict), intent(out) :: dict
      real(dp), allocatable, intent(out) :: rows(:, :)
      integer, allocatable, intent(out) :: idx(:)
      type(egw_error), allocatable, intent(out) :: error
      integer :: pos, eol, nrow, line_no, eq, cap, n_end
      logical :: in_data, ended, indexed, ok
      character(len=:), allocatable :: line
      real(dp) :: vals(ncol)
      integer :: j, body

      call split_checksum(path, file_text, body, checksum_missing, error)
      if (allocated(error)) return
      associate (text => file_text(1:body))
      indexed = starts_with(columns, "mu_index")
      cap = 1024
      allocate (rows(ncol, cap), idx(cap), dict%keys(64), dict%values(64))
      nrow = 0
      pos = 1
      line_no = 0
      in_data = .false.
      ended = .false.
      do while (pos <= len(text))
         eol = index(text(pos:), new_line("a"))
         if (eol == 0) then
            ! a complete file ends with a newline: a missing one means truncation
            call bad(error, path, "truncated (last line has no end of line)")
            return
         end if
         line = text(pos:pos + eol - 2)
         pos = pos + eol
         line_no = line_no + 1
         if (len(line) > 0) then
            if (line(len(line):len(line)) == achar(13)) line = line(1:len(line) - 1)
         end if
         if (ended) then
            if (len_trim(line) > 0) then
               call bad(error, path, "line "//int_str(line_no)//": text after the end line")
               return
            end if
            cycle
         end if
         if (starts_with(line, "# end of table,")) then
            call parse_int(first_token(line(16:)), n_end, ok)
            if (.not. ok .or. n_end /= nrow .or. .not. in_data) then
               call bad(error, path, "line "//int_str(line_no)//": end line does not match "// &
                  & int_str(nrow)//" data rows")
               return
            end if
            ended = .true.
         else if (starts_with(line, "#")) then
            if (nrow > 0) then
               call bad(error, path, "line "//int_str(line_no)//": comment inside the data")
               return
            end if
            eq = index(line, "=")
            if (eq > 0) call dict_add(dict, adjustl(trim(line(2:eq - 1))), &
               & adjustl(trim(line(eq + 1:))))
         else if (.not. in_data) then
            if (trim(line) /= columns) then
               call bad(error, path, "line "//int_str(line_no)//": expected column header '"// &
                  & columns//"'")
               return
            end if
            in_data = .true.
         else
            call split_row(line, indexed, j, vals, ok)
            if (.not. ok) then
               call bad(error, path, "line "//int_str(line_no)//": cannot read "// &
                  & int_str(ncol)//" numbers")
               return
            end if
            if (nrow == cap) then
               cap = 2*cap
               call grow(rows, idx, cap)
            end if
            nrow = nrow + 1
            rows(:, nrow) = vals
            idx(nrow) = j
         end if
      end do
      if (.not. ended) then
         call bad(error, path, "truncated (no '# end of table' line)")
         return
      end if
      rows = rows(:, 1:nrow)
      idx = idx(1:nrow)
      end associate
   end subroutine parse_csv

   !> Append the checksum line of CSV format 3: the FNV-1a hash of all bytes above it.
   subroutine add_checksum(out)
      type(text_buffer), intent(inout) :: out
      call out%add(checksum_line(out%text(1:out%n)))
   end subroutine add_checksum

   subroutine set_nodes(t, rows)
      type(force_table), intent(inout) :: t
      real(dp), intent(in) :: rows(:, :)
      t%delta = rows(1, :)
      t%force = rows(2, :)
      t%stiffness = rows(3, :)
      t%energy = rows(4, :)
      t%contact_radius = rows(5, :)
   end subroutine set_nodes

   subroutine get_params(path, dict, p, error)
      character(len=*), intent(in) :: path
      type(header_dict), intent(in) :: dict
      type(contact_params), intent(out) :: p
      type(egw_error), allocatable, intent(out) :: error
      call get_int(path, dict, "model", p%model, error)
      if (.not. allocated(error)) call get_real(path, dict, "radius", p%radius, error)
      if (.not. allocated(error)) call get_real(path, dict, "modulus", p%modulus, error)
      if (.not. allocated(error)) call get_real(path, dict, "sigma", p%sigma, error)
      if (.not. allocated(error)) call get_real(path, dict, "mu", p%mu, error)
      if (.not. allocated(error)) call get_real(path, dict, "psi", p%psi, error)
      if (.not. allocated(error)) call get_real(path, dict, "hardness_coeff", &
         & p%hardness_coeff, error)
      if (.not. allocated(error)) call get_real(path, dict, "plastic_ratio", &
         & p%plastic_ratio, error)
      if (allocated(error)) return
      call validate_params(p, error, allow_flat_law=.true.)   ! a flat law's table too
      if (allocated(error)) call bad(error, path, "stored parameters invalid: "//error%message)
   end subroutine get_params

   subroutine get_table_meta(path, dict, prefix, t, n, error)
      character(len=*), intent(in) :: path, prefix
      type(header_dict), intent(in) :: dict
      type(force_table), intent(inout) :: t
      integer, intent(out) :: n
      type(egw_error), allocatable, intent(out) :: error
      call get_real(path, dict, prefix//"rel_tol", t%rel_tol, error)
      if (.not. allocated(error)) call get_real(path, dict, prefix//"cutoff", t%cutoff, error)
      if (.not. allocated(error)) call get_real(path, dict, prefix//"delta_max", &
         & t%delta_max, error)
      if (.not. allocated(error)) call get_real(path, dict, prefix//"reference_force", &
         & t%reference_force, error)
      if (.not. allocated(error)) call get_real(path, dict, prefix//"max_force_error", &
         & t%max_force_error, error)
      if (.not. allocated(error)) call get_real(path, dict, prefix//"max_stiffness_error", &
         & t%max_stiffness_error, error)
      if (.not. allocated(error)) call get_real(path, dict, prefix//"radius_sum", &
         & t%radius_sum, error)
      if (.not. allocated(error)) call get_int(path, dict, prefix//"n_nodes", n, error)
      if (.not. allocated(error)) call get_int(path, dict, prefix//"n_log", t%n_log, error)
   end subroutine get_table_meta

   subroutine get_real(path, dict, key, x, error)
      character(len=*), intent(in) :: path, key
      type(header_dict), intent(in) :: dict
      real(dp), intent(out) :: x
      type(egw_error), allocatable, intent(out) :: error
      integer :: i
      logical :: ok
      i = dict_find(dict, key)
      x = 0.0_dp
      if (i == 0) then
         call bad(error, path, "header key '"//key//"' missing")
         return
      end if
      call parse_real(first_token(dict%values(i)), x, ok)
      if (.not. ok .or. .not. ieee_is_finite(x)) then
         call bad(error, path, "header key '"//key//"' = '"//trim(dict%values(i))// &
            & "' is not a finite number")
      end if
   end subroutine get_real

   subroutine get_int(path, dict, key, k, error)
      character(len=*), intent(in) :: path, key
      type(header_dict), intent(in) :: dict
      integer, intent(out) :: k
      type(egw_error), allocatable, intent(out) :: error
      integer :: i
      logical :: ok
      i = dict_find(dict, key)
      k = 0
      if (i == 0) then
         call bad(error, path, "header key '"//key//"' missing")
         return
      end if
      call parse_int(first_token(dict%values(i)), k, ok)
      if (.not. ok) call bad(error, path, "header key '"//key//"' = '"// &
         & trim(dict%values(i))//"' is not an integer")
   end subroutine get_int

   pure integer function dict_find(dict, key) result(i)
      type(header_dict), intent(in) :: dict
      character(len=*), intent(in) :: key
      do i = 1, dict%n
         if (trim(dict%keys(i)) == key) return
      end do
      i = 0
   end function dict_find

   pure subroutine dict_add(dict, key, value)
      type(header_dict), intent(inout) :: dict
      character(len=*), intent(in) :: key, value
      character(len=64), allocatable :: k2(:)
      character(len=256), allocatable :: v2(:)
      if (dict%n == size(dict%keys)) then
         allocate (k2(2*dict%n), v2(2*dict%n))
         k2(1:dict%n) = dict%keys
         v2(1:dict%n) = dict%values
         call move_alloc(k2, dict%keys)
         call move_alloc(v2, dict%values)
      end if
      dict%n = dict%n + 1
      dict%keys(dict%n) = key
      dict%values(dict%n) = value
   end subroutine dict_add

   pure subroutine grow(rows, idx, cap)
      real(dp), allocatable, intent(inout) :: rows(:, :)
      integer, allocatable, intent(inout) :: idx(:)
      integer, intent(in) :: cap
      real(dp), allocatable :: r2(:, :)
      integer, allocatable :: i2(:)
      allocate (r2(size(rows, 1), cap), i2(cap))
      r2(:, 1:size(rows, 2)) = rows
      i2(1:size(idx)) = idx
      call move_alloc(r2, rows)
      call move_alloc(i2, idx)
   end subroutine grow

   subroutine kv(out, key, x)
      type(text_buffer), intent(inout) :: out
      character(len=*), intent(in) :: key
      real(dp), intent(in) :: x
      call out%add("# "//key//" = "//fmt(x))
   end subroutine kv



   pure integer function first_token_len(text) result(n)
      character(len=*), intent(in) :: text
      n = index(trim(adjustl(text))//" ", " ") - 1
   end function first_token_len

   !> The text up to the first blank (after leading blanks).
   pure function first_token(text) result(token)
      character(len=*), intent(in) :: text
      character(len=first_token_len(text)) :: token  ! not deferred: see egw_text
      token = adjustl(text)
   end function first_token

   !> A data row: an integer index (if indexed) and size(vals) reals, separated by
   !> commas; blanks around fields allowed, nothing else.
   pure subroutine split_row(line, indexed, j, vals, ok)
      character(len=*), intent(in) :: line
      logical, intent(in) :: indexed
      integer, intent(out) :: j
      real(dp), intent(out) :: vals(:)
      logical, intent(out) :: ok
      integer :: start, comma, k, nfield
      j = 0
      vals = 0.0_dp
      nfield = size(vals)
      if (indexed) nfield = nfield + 1
      start = 1
      do k = 1, nfield
         comma = index(line(start:), ",")
         if (k < nfield) then
            ok = comma > 0
            if (.not. ok) return
            comma = start + comma - 1
         else
            ok = comma == 0
            if (.not. ok) return
            comma = len(line) + 1
         end if
         if (indexed .and. k == 1) then
            call parse_int(line(start:comma - 1), j, ok)
         else
            call parse_real(line(start:comma - 1), vals(k - merge(1, 0, indexed)), ok)
         end if
         if (.not. ok) return
         start = comma + 1
      end do
   end subroutine split_row

end submodule egw_table_format_csv
