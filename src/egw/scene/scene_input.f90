!> Reading a scene: the namelist file (read_scene_file) and the fields given as overrides
!> (apply_scene_overrides: egw-table's flags); the module egw_scene in
!> src/egw/scene/scene.f90 declares them and holds the checks and the resolution.
submodule (egw_scene) egw_scene_input
   use egw_text, only: to_lower
   implicit none

contains

   ! read_scene_file: interface and documentation in egw_scene (scene.f90)
   module procedure read_scene_file
      character(len=:), allocatable :: bytes, lines(:)
      integer :: at
      call read_file(path, bytes, error)
      if (allocated(error)) return
      ! a namelist is text: control bytes (but tab, CR, LF, form feed) mean another kind
      ! of file, which gfortran's namelist parser of internal files would partly accept
      at = scan(bytes, control_bytes)
      if (at > 0) then
         call fatal_error(error, egw_bad_file, "path = "//path//": not a text file (byte "// &
            & int_str(at)//" is the control character "//int_str(iachar(bytes(at:at)))// &
            & "): not a namelist &scene")
         return
      end if
      call split_lines(bytes, lines)
      call read_scene_lines(lines, input, error)
      if (allocated(error)) error%message = "path = "//path//": "//error%message
   end procedure read_scene_file

   !> The lines of a text (LF or CRLF ends; at least one, blank for an empty text) as the
   !> records of an internal file, blank-padded to the longest.
   pure subroutine split_lines(text, lines)
      character(len=*), intent(in) :: text
      character(len=:), allocatable, intent(out) :: lines(:)
      integer :: n, i, first, last, width, k
      n = 1
      width = 0
      first = 1
      do i = 1, len(text) + 1
         if (i <= len(text)) then
            if (text(i:i) /= achar(10)) cycle
         end if
         width = max(width, line_end(i) - first + 1)
         if (i <= len(text)) n = n + 1
         first = i + 1
      end do
      if (len(text) > 0) then
         if (text(len(text):) == achar(10)) n = n - 1   ! a final LF ends, not starts, a line
      end if
      allocate (character(len=max(width, 1)) :: lines(max(n, 1)))
      lines = ""
      k = 0
      first = 1
      do i = 1, len(text) + 1
         if (i <= len(text)) then
            if (text(i:i) /= achar(10)) cycle
         end if
         k = k + 1
         if (k > size(lines)) exit
         last = line_end(i)
         if (last >= first) lines(k) = text(first:last)
         first = i + 1
      end do
   contains
      !> The last character of the line that ends before position i (a CR dropped).
      pure integer function line_end(i) result(last)
         integer, intent(in) :: i
         last = i - 1
         if (last >= 1) then
            if (text(last:last) == achar(13)) last = last - 1
         end if
      end function line_end
   end subroutine split_lines

   !> read_scene_file on the file's lines (the records of an internal file); the message
   !> of an error does not name the file (the caller adds it).
   subroutine read_scene_lines(lines, input, error)
      character(len=*), intent(in) :: lines(:)   !< the file's lines
      type(scene_input), intent(inout) :: input  !< as read_scene_file
      type(egw_error), allocatable, intent(out) :: error
      type(scene_overrides) :: ov
      character(len=32) :: model
      real(dp) :: radius(max_types), radius_min, radius_max, modulus(max_types), &
         & poisson(max_types), effective_modulus, sigma, sigma_min, sigma_max, mu, &
         & summit_density, summit_radius, psi, k, plastic_ratio, delta_min, delta_max, &
         & delta_min_sigma, delta_max_sigma, tol, flow_pressure, yield_stress
      character(len=512) :: flat_law
      namelist /scene/ model, radius, radius_min, radius_max, modulus, poisson, &
         & effective_modulus, sigma, sigma_min, sigma_max, mu, summit_density, summit_radius, &
         & psi, k, plastic_ratio, delta_min, delta_max, delta_min_sigma, delta_max_sigma, tol, &
         & flat_law, flow_pressure, yield_stress
      integer :: stat
      character(len=512) :: msg

      model = ov%model
      radius = ov%radius; radius_min = ov%radius_min; radius_max = ov%radius_max
      modulus = ov%modulus; poisson = ov%poisson; effective_modulus = ov%effective_modulus
      sigma = ov%sigma; sigma_min = ov%sigma_min; sigma_max = ov%sigma_max
      mu = ov%mu; summit_density = ov%summit_density; summit_radius = ov%summit_radius
      psi = ov%psi; k = ov%hardness_coeff; plastic_ratio = ov%plastic_ratio
      delta_min = ov%delta_min; delta_max = ov%delta_max
      delta_min_sigma = ov%delta_min_sigma; delta_max_sigma = ov%delta_max_sigma
      tol = ov%tol
      flat_law = ov%flat_law
      flow_pressure = ov%flow_pressure; yield_stress = ov%yield_stress

      msg = ""
      ! gfortran 12 reads an internal file without the group as a success: look first
      stat = 0
      if (.not. any(has_group(lines))) stat = -1
      if (stat == 0) read (lines, nml=scene, iostat=stat, iomsg=msg)
      if (stat /= 0) then
         ! gfortran reports most malformed groups as end of file: find the entry at fault
         call diagnose(msg)
         call fatal_error(error, egw_bad_file, trim(msg))
         return
      end if
      ov = scene_overrides(model=model, radius=radius, radius_min=radius_min, &
         & radius_max=radius_max, modulus=modulus, poisson=poisson, &
         & effective_modulus=effective_modulus, sigma=sigma, sigma_min=sigma_min, &
         & sigma_max=sigma_max, mu=mu, summit_density=summit_density, &
         & summit_radius=summit_radius, psi=psi, hardness_coeff=k, &
         & plastic_ratio=plastic_ratio, delta_min=delta_min, delta_max=delta_max, &
         & delta_min_sigma=delta_min_sigma, delta_max_sigma=delta_max_sigma, tol=tol, &
         & flat_law=flat_law, flow_pressure=flow_pressure, yield_stress=yield_stress)
      call apply_scene_overrides(input, ov, error)

   contains

      !> Why the group could not be read: no group, no closing '/', or the first entry
      !> (a line starting "name =" with its continuation lines) that fails on its own.
      subroutine diagnose(why)
         character(len=*), intent(inout) :: why
         character(len=:), allocatable :: line, entry, lower
         character(len=512) :: entry_msg
         logical :: in_group, closed
         integer :: at, i
         in_group = .false.
         closed = .false.
         entry = ""
         do i = 1, size(lines)
            line = trim(lines(i))
            at = index(line, "!")
            if (at > 0) line = line(:at - 1)
            if (.not. in_group) then
               lower = to_lower(line)
               at = index(lower, "&scene")
               if (at == 0) cycle
               in_group = .true.
               line = line(at + 6:)
            end if
            at = index(line, "/")
            if (at > 0) then
               closed = .true.
               line = line(:at - 1)
            end if
            if (starts_entry(line) .and. len_trim(entry) > 0) then
               if (.not. entry_ok(entry, entry_msg)) exit
               entry = ""
            end if
            entry = entry//" "//trim(line)
            if (closed) exit
         end do
         if (.not. in_group) then
            why = "no namelist group &scene found"
         else if (len_trim(entry) > 0 .and. .not. entry_ok(entry, entry_msg)) then
            why = "'"//trim(adjustl(entry))//"': "//trim(entry_msg)
         else if (.not. closed) then
            why = "the &scene group has no closing '/'"
         end if
      end subroutine diagnose

      logical function entry_ok(entry, why)
         character(len=*), intent(in) :: entry
         character(len=*), intent(out) :: why
         character(len=:), allocatable :: text
         integer :: ios
         why = ""
         text = "&scene "//entry//" /"
         read (text, nml=scene, iostat=ios, iomsg=why)
         entry_ok = ios == 0
      end function entry_ok

   end subroutine read_scene_lines

   !> Whether a line (its part before a comment '!') opens the group &scene (any case).
   elemental logical function has_group(line)
      character(len=*), intent(in) :: line
      character(len=len(line)) :: lower
      integer :: at, next
      lower = to_lower(line)
      at = index(lower, "!")
      if (at > 0) lower(at:) = ""
      at = index(lower, "&scene")
      has_group = at > 0
      if (.not. has_group) return
      next = at + 6
      if (next <= len(lower)) has_group = verify(lower(next:next), &
         & "abcdefghijklmnopqrstuvwxyz0123456789_") > 0
   end function has_group

   !> Whether a namelist line starts an entry: a name (optionally indexed) then '='.
   pure logical function starts_entry(line)
      character(len=*), intent(in) :: line
      integer :: i, eq
      character :: c
      starts_entry = .false.
      eq = index(line, "=")
      if (eq == 0) return
      do i = 1, eq - 1
         c = line(i:i)
         if (.not. (c == " " .or. c == "_" .or. c == "(" .or. c == ")" .or. c == ":" &
            & .or. c == "," .or. (c >= "a" .and. c <= "z") .or. (c >= "A" .and. c <= "Z") &
            & .or. (c >= "0" .and. c <= "9"))) return
      end do
      starts_entry = len_trim(line(:eq - 1)) > 0
   end function starts_entry

   ! apply_scene_overrides: interface and documentation in egw_scene (scene.f90)
   module procedure apply_scene_overrides
      type(scene_input) :: s

      s = input
      if (len_trim(ov%model) > 0) then
         call model_from_name(ov%model, s%model, error)
         if (allocated(error)) return
      end if
      call override_radii(s, ov, error)
      if (allocated(error)) return
      call override_materials(s, ov, error)
      if (allocated(error)) return
      call override_roughness(s, ov, error)
      if (allocated(error)) return
      call override_summits(s, ov, error)
      if (allocated(error)) return
      if (given(ov%psi)) s%psi = ov%psi
      if (given(ov%hardness_coeff)) s%hardness_coeff = ov%hardness_coeff
      if (given(ov%plastic_ratio)) s%plastic_ratio = ov%plastic_ratio
      call override_overlaps(s, ov, input%sigma_max, error)
      if (allocated(error)) return
      if (given(ov%tol)) s%tol = ov%tol
      if (len_trim(ov%flat_law) > 0) then
         s%flat_law = ov%flat_law
         s%model = model_flat_law
      end if
      call override_cap(s, ov, error)
      if (allocated(error)) return

      call validate_scene_input(s, error)
      if (allocated(error)) return
      input = s
   end procedure apply_scene_overrides

   !> The flow-pressure cap of ov, if given: flow_pressure itself, or yield_stress Y
   !> (p_y = 1.6 Y; doc/theory.md §12), not both.
   pure subroutine override_cap(s, ov, error)
      type(scene_input), intent(inout) :: s
      type(scene_overrides), intent(in) :: ov
      type(egw_error), allocatable, intent(out) :: error
      if (given(ov%flow_pressure) .and. given(ov%yield_stress)) then
         call fatal_error(error, egw_invalid_parameter, "flow_pressure and yield_stress: "// &
            & "give one (flow_pressure = 1.6 yield_stress, doc/theory.md section 12)")
         return
      end if
      if (given(ov%flow_pressure)) s%flow_pressure = ov%flow_pressure
      if (given(ov%yield_stress)) then
         if (.not. positive_finite(ov%yield_stress)) then
            call bad(error, "yield_stress", ov%yield_stress, "must be finite and > 0 "// &
               & "(flow_pressure = 1.6 yield_stress; flow_pressure = 0 for no bulk yield)")
            return
         end if
         s%flow_pressure = flow_pressure_per_yield_stress*ov%yield_stress
         s%yield_stress = ov%yield_stress
      else if (given(ov%flow_pressure)) then
         s%yield_stress = 0.0_dp
      end if
   end subroutine override_cap

   !> The particles of ov, if given: a list of the types' radii or a radius range.
   pure subroutine override_radii(s, ov, error)
      type(scene_input), intent(inout) :: s
      type(scene_overrides), intent(in) :: ov
      type(egw_error), allocatable, intent(out) :: error
      integer :: n
      n = count(given(ov%radius))
      if (n > 0 .and. .not. all(given(ov%radius(1:n)))) then
         call fatal_error(error, egw_invalid_parameter, "radius: give the types' radii "// &
            & "as radius = R1, R2, ... without gaps")
         return
      end if
      if (n > 0 .and. (given(ov%radius_min) .or. given(ov%radius_max))) then
         call fatal_error(error, egw_invalid_parameter, "radius and radius_min/radius_max: "// &
            & "give a list of radii or a range, not both")
         return
      end if
      if (n > 0) then
         s%n_types = n
         s%radius = 0.0_dp
         s%radius(1:n) = ov%radius(1:n)
      else if (given(ov%radius_min) .or. given(ov%radius_max)) then
         if (.not. (given(ov%radius_min) .and. given(ov%radius_max))) then
            call fatal_error(error, egw_invalid_parameter, "radius_min, radius_max: "// &
               & "a radius range needs both")
            return
         end if
         s%n_types = 0
         s%radius = 0.0_dp
         s%radius_min = ov%radius_min
         s%radius_max = ov%radius_max
      end if
   end subroutine override_radii

   !> The materials of ov, if given: E* of every pair, or E and nu per type (doc/theory.md
   !> §1).
   pure subroutine override_materials(s, ov, error)
      type(scene_input), intent(inout) :: s
      type(scene_overrides), intent(in) :: ov
      type(egw_error), allocatable, intent(out) :: error
      if (given(ov%effective_modulus)) then
         if (any(given(ov%modulus)) .or. any(given(ov%poisson))) then
            call fatal_error(error, egw_invalid_parameter, "effective_modulus and "// &
               & "modulus/poisson: give E* or the materials, not both")
            return
         end if
         s%effective_modulus = ov%effective_modulus
      else if (any(given(ov%modulus)) .or. any(given(ov%poisson))) then
         s%effective_modulus = 0.0_dp
         where (given(ov%modulus)) s%modulus = ov%modulus
         where (given(ov%poisson)) s%poisson = ov%poisson
      end if
   end subroutine override_materials

   !> The roughness of ov, if given: the combined sigma of a pair (doc/theory.md §1), one
   !> value or a range.
   pure subroutine override_roughness(s, ov, error)
      type(scene_input), intent(inout) :: s
      type(scene_overrides), intent(in) :: ov
      type(egw_error), allocatable, intent(out) :: error
      if (given(ov%sigma)) then
         if (given(ov%sigma_min) .or. given(ov%sigma_max)) then
            call fatal_error(error, egw_invalid_parameter, "sigma and sigma_min/sigma_max: "// &
               & "give one sigma or a range, not both")
            return
         end if
         ! (named here: validation would name sigma_min)
         if (.not. (ieee_is_finite(ov%sigma) .and. ov%sigma >= 0.0_dp)) then
            call bad(error, "sigma", ov%sigma, "must be finite and >= 0"); return
         end if
         s%sigma_min = ov%sigma
         s%sigma_max = ov%sigma
      else if (given(ov%sigma_min) .or. given(ov%sigma_max)) then
         if (.not. (given(ov%sigma_min) .and. given(ov%sigma_max))) then
            call fatal_error(error, egw_invalid_parameter, "sigma_min, sigma_max: "// &
               & "a roughness range needs both")
            return
         end if
         s%sigma_min = ov%sigma_min
         s%sigma_max = ov%sigma_max
      end if
   end subroutine override_roughness

   !> The summits of ov, if given: the Greenwood-Tripp mu directly, or the summit density
   !> and radius it follows from per pair (doc/theory.md §1).
   pure subroutine override_summits(s, ov, error)
      type(scene_input), intent(inout) :: s
      type(scene_overrides), intent(in) :: ov
      type(egw_error), allocatable, intent(out) :: error
      if (given(ov%mu)) then
         if (given(ov%summit_density) .or. given(ov%summit_radius)) then
            call fatal_error(error, egw_invalid_parameter, "mu and summit_density/"// &
               & "summit_radius: give mu or the summits, not both")
            return
         end if
         s%mu = ov%mu
         s%summit_density = 0.0_dp
         s%summit_radius = 0.0_dp
      else if (given(ov%summit_density) .or. given(ov%summit_radius)) then
         if (.not. (given(ov%summit_density) .and. given(ov%summit_radius))) then
            call fatal_error(error, egw_invalid_parameter, "summit_density, summit_radius: "// &
               & "mu from the summits needs both")
            return
         end if
         s%mu = 0.0_dp
         s%summit_density = ov%summit_density
         s%summit_radius = ov%summit_radius
      end if
   end subroutine override_summits

   !> The overlap range of ov, if given: both ends in one unit, or one end in the scene's
   !> current unit. A scene made smooth keeps its range (in units of old_sigma_max, the
   !> scene's sigma_max before the overrides).
   pure subroutine override_overlaps(s, ov, old_sigma_max, error)
      type(scene_input), intent(inout) :: s
      type(scene_overrides), intent(in) :: ov
      real(dp), intent(in) :: old_sigma_max
      type(egw_error), allocatable, intent(out) :: error
      if (given(ov%delta_min_sigma) .or. given(ov%delta_max_sigma)) then
         if (given(ov%delta_min) .or. given(ov%delta_max)) then
            call fatal_error(error, egw_invalid_parameter, "delta_min/delta_max and "// &
               & "delta_min_sigma/delta_max_sigma: give the range in one unit")
            return
         end if
         call set_range(s, ov%delta_min_sigma, ov%delta_max_sigma, 1, "delta_min_sigma", &
            & "delta_max_sigma", error)
      else
         ! a scene made smooth (sigma = 0) keeps its overlaps: a range in units of the
         ! old sigma becomes that range in length (the only unit left)
         if (s%delta_in_sigma == 1 .and. s%sigma_max == 0.0_dp .and. &
            & old_sigma_max > 0.0_dp) then
            s%delta_min = s%delta_min*old_sigma_max
            s%delta_max = s%delta_max*old_sigma_max
            s%delta_in_sigma = 0
         end if
         call set_range(s, ov%delta_min, ov%delta_max, 0, "delta_min", "delta_max", error)
      end if
   end subroutine override_overlaps

   !> Whether a scene_overrides value was given.
   elemental logical function given(x)
      real(dp), intent(in) :: x
      given = x /= unset
   end function given

   !> Set the overlap range in the given unit (0 length, 1 sigma); a single end is
   !> accepted only when the scene's range is already in that unit.
   pure subroutine set_range(s, lo, hi, unit_kind, name_lo, name_hi, error)
      type(scene_input), intent(inout) :: s
      real(dp), intent(in) :: lo, hi
      integer, intent(in) :: unit_kind
      character(len=*), intent(in) :: name_lo, name_hi
      type(egw_error), allocatable, intent(out) :: error
      if (.not. (given(lo) .or. given(hi))) return
      if (.not. (given(lo) .and. given(hi)) .and. s%delta_in_sigma /= unit_kind) then
         call fatal_error(error, egw_invalid_parameter, name_lo//", "//name_hi// &
            & ": the scene's range is in other units; give both ends")
         return
      end if
      s%delta_in_sigma = unit_kind
      if (given(lo)) s%delta_min = lo
      if (given(hi)) s%delta_max = hi
   end subroutine set_range

end submodule egw_scene_input
