!> Scenes: what a DEM or FE user knows about their contacts (particle radii, materials,
!> roughness, overlap range, force tolerance), resolved into the contact parameter sets
!> of its particle pairs, and the rule that picks the cheapest model meeting the
!> tolerance: Hertz closed form, one 1-D table, or the universal 2-D table (doc/scenes.md).
module egw_scene
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use egw_kinds, only: dp
   use egw_status, only: egw_error, egw_invalid_parameter, egw_bad_file, &
      & egw_unsupported, fatal_error, format_real, int_str, bad => parameter_error
   use egw_params, only: contact_params, validate_params, model_hertz, model_gw, model_egw, &
      & model_epgw, model_flat_law, mu_from_summits, check_scaled_overlap
   use egw_flat_law, only: flat_law
   use egw_rough_sphere, only: solver_options
   use egw_table, only: force_table, table_progress
   use egw_table_universal, only: universal_table
   use egw_io, only: read_file
   implicit none
   private

   public :: default_scene_input, read_scene_file, apply_scene_overrides, &
      & validate_scene_input, resolve_scene, choose_model, build_scene_tables, &
      & build_pair_tables, model_from_name, choice_name, scene_hertz_error

   !> Most particle types (and materials) a scene lists.
   integer, parameter, public :: max_types = 8

   !> The ASCII control characters a text file does not hold (all but tab 9, LF 10, form
   !> feed 12 and CR 13; DEL 127).
   character(len=*), parameter :: control_bytes = achar(0)//achar(1)//achar(2)// &
      & achar(3)//achar(4)//achar(5)//achar(6)//achar(7)//achar(8)//achar(11)//achar(14)// &
      & achar(15)//achar(16)//achar(17)//achar(18)//achar(19)//achar(20)//achar(21)// &
      & achar(22)//achar(23)//achar(24)//achar(25)//achar(26)//achar(27)//achar(28)// &
      & achar(29)//achar(30)//achar(31)//achar(127)

   integer, parameter, public :: choice_hertz = 0      !< Hertz closed form, no table
   integer, parameter, public :: choice_table = 1      !< one 1-D force table
   integer, parameter, public :: choice_universal = 2  !< the universal 2-D table

   !> Tolerances a scene may ask for (the table builders' range is [1e-10, 0.1]; below
   !> 1e-8 the builds take minutes and the solver's own accuracy is the limit).
   real(dp), parameter :: tol_min = 1.0e-8_dp, tol_max = 0.1_dp

   !> A scene as the user states it (any consistent units). Field order matches the C
   !> struct egw_scene. Particle types: radius(1:n_types); n_types = 0 means a continuous
   !> radius range [radius_min, radius_max] of one material. Materials: E* of every pair
   !> directly (effective_modulus > 0), or E and nu per type (modulus(i) = 0 for i >= 2:
   !> same material as type 1). Roughness: combined summit-height std of a pair in
   !> [sigma_min, sigma_max]; mu directly (mu > 0) or from the summit density and radius
   !> (then mu = (8/3) eta sigma sqrt(2 R beta) differs between pairs). Overlaps
   !> [delta_min, delta_max], in length units or (delta_in_sigma = 1) in units of sigma.
   type, public :: scene_input
      integer :: model = model_egw
      integer :: n_types = 0
      real(dp) :: radius(max_types) = 0.0_dp
      real(dp) :: radius_min = 0.0_dp, radius_max = 0.0_dp
      real(dp) :: modulus(max_types) = 0.0_dp, poisson(max_types) = 0.0_dp
      real(dp) :: effective_modulus = 0.0_dp
      real(dp) :: sigma_min = 0.0_dp, sigma_max = 0.0_dp
      real(dp) :: mu = 0.0_dp, summit_density = 0.0_dp, summit_radius = 0.0_dp
      real(dp) :: psi = 0.0_dp, hardness_coeff = 0.6_dp, plastic_ratio = 54.0_dp
      real(dp) :: delta_min = 0.0_dp, delta_max = 0.0_dp
      integer :: delta_in_sigma = 0
      real(dp) :: tol = 1.0e-3_dp
      !> A rough-flat law file (doc/formats.md §7) in place of the summit model (model
      !> flat law; Fortran only: not in the C struct). Its caller reads the law and gives
      !> sigma = the law's length (egw-table does); blank: none.
      character(len=512) :: flat_law = ""
      !> The bulk flow pressure p_y of the flow-pressure cap (doc/theory.md §12; 0: none;
      !> Fortran only, not in the C struct: egw_scene_read refuses a file that sets it).
      !> Smooth spheres only (model Hertz or sigma = 0): egw-table writes their hysteresis
      !> tables. From yield_stress Y: p_y = 1.6 Y.
      real(dp) :: flow_pressure = 0.0_dp
   end type scene_input

   !> "Not given" marker of scene_overrides (a value no scene uses).
   real(dp), parameter, public :: unset = huge(1.0_dp)

   !> Values that replace those of a scene_input (from a namelist file or command-line
   !> flags); fields left at unset (model: blank) are not given. Names as in the
   !> namelist; sigma and delta_*_sigma are the one-value / units-of-sigma forms.
   type, public :: scene_overrides
      character(len=32) :: model = ""
      real(dp) :: radius(max_types) = unset
      real(dp) :: radius_min = unset, radius_max = unset
      real(dp) :: modulus(max_types) = unset, poisson(max_types) = unset
      real(dp) :: effective_modulus = unset
      real(dp) :: sigma = unset, sigma_min = unset, sigma_max = unset
      real(dp) :: mu = unset, summit_density = unset, summit_radius = unset
      real(dp) :: psi = unset, hardness_coeff = unset, plastic_ratio = unset
      real(dp) :: delta_min = unset, delta_max = unset
      real(dp) :: delta_min_sigma = unset, delta_max_sigma = unset
      real(dp) :: tol = unset
      character(len=512) :: flat_law = ""   !< a rough-flat law file (blank: not given)
      !> the cap's p_y, or the yield stress Y it follows from (p_y = 1.6 Y): one of them
      real(dp) :: flow_pressure = unset, yield_stress = unset
   end type scene_overrides

   !> p_y = flow_pressure_per_yield_stress Y: the Hertz peak pressure at first yield of
   !> the sphere (Johnson 1985, §6.2; doc/theory.md §12 says why egw takes 1.6).
   real(dp), parameter, public :: flow_pressure_per_yield_stress = 1.6_dp

   !> A validated scene resolved into the distinct parameter sets of its pairs (for a
   !> continuous radius range: the pairs of the range's ends, whose R and mu bound those
   !> of every pair), each with its overlap range in length units.
   type, public :: contact_scene
      type(scene_input) :: input
      logical :: continuous = .false.             !< radius range: sets are its corners
      type(contact_params), allocatable :: sets(:)
      real(dp), allocatable :: radius1(:), radius2(:)  !< particle radii of each set's pair
      real(dp), allocatable :: delta_min(:), delta_max(:)
      !> set of each (type pair, sigma) in the order (1,1), (1,2), .., (1,n), (2,2), ..,
      !> (n,n), sigma_min before sigma_max (identical sets are stored once)
      integer, allocatable :: pair_set(:)
   end type contact_scene

   !> The cheapest model meeting the scene's tolerance, and why.
   type, public :: model_choice
      integer :: kind = choice_hertz
      !> bound on the force error of the choice: for Hertz the measured maximum of the
      !> Hertz error measure (see scene_hertz_error) over the sampled overlaps; for the
      !> tables the tolerance they are built to (their measured error is reported by
      !> build_scene_tables)
      real(dp) :: error_bound = 0.0_dp
      real(dp) :: hertz_error = 0.0_dp   !< Hertz error measure (0 when not computed)
      logical :: hertz_relative_to_max = .false.  !< measure relative to P(delta_max)
      integer :: n_sets = 0              !< distinct pair parameter sets
      integer :: n_solves = 0            !< full solves spent on the choice
      real(dp) :: mu_min = 0.0_dp, mu_max = 0.0_dp   !< mu range of the scene
      real(dp) :: x_min = 0.0_dp, x_max = 0.0_dp     !< delta/sigma range of the scene
      !> largest delta_max/delta_y over the sets with a flow_pressure (0: none has one);
      !> above 1 the bulk yields (issue 32): cap_matters, and the reason says so
      real(dp) :: yield_ratio = 0.0_dp
      logical :: cap_matters = .false.
      character(len=:), allocatable :: reason
   end type model_choice

   !> The tables of a choice (none for Hertz).
   type, public :: scene_tables
      integer :: kind = choice_hertz
      type(force_table) :: table          !< choice_table
      type(universal_table) :: universal  !< choice_universal
      real(dp) :: measured_error = 0.0_dp !< max rel. force error at the builds' check solves
      integer :: n_nodes = 0              !< nodes (universal: x nodes times mu nodes)
   end type scene_tables

   !> Hertz samples per decade of overlap (the Hertz error varies slowly and smoothly
   !> in ln delta: 4 per decade resolve its maximum to a few per cent of itself).
   integer, parameter :: samples_per_decade = 4

   interface
      !> The cheapest model that meets the scene's tolerance (doc/scenes.md):
      !> 1. Hertz, exactly, for smooth spheres (model Hertz or sigma = 0);
      !> 2. Hertz when the Hertz error measure (scene_hertz_error) is <= tol for every set;
      !> 3. one 1-D table when the scene has a single parameter set (one pair, one sigma);
      !> 4. the universal 2-D table otherwise (radius range, several types or materials,
      !>    sigma range), over the scene's mu and delta/sigma ranges.
      !> Full solves (options) are spent only on the Hertz check; tables are built by
      !> build_scene_tables.
      module subroutine choose_model(scene, options, choice, error)
         type(contact_scene), intent(in) :: scene   !< resolved (resolve_scene)
         type(solver_options), intent(in) :: options   !< of the Hertz check's solves
         type(model_choice), intent(out) :: choice   !< the cheapest model meeting the tolerance
         type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      end subroutine choose_model

      !> The Hertz error measure of a scene, the maximum over its parameter sets of:
      !> - delta_min > 0: max |P_Hertz(delta)/P(delta) - 1| over the overlaps (pointwise
      !>   relative error, P from full solves);
      !> - delta_min <= 0: max |P_Hertz(delta) - P(delta)| / P(delta_max) (relative to the
      !>   scene's largest force): Hertz gives 0 for delta <= 0 where the rough force is not,
      !>   and a pointwise relative error would be 1 there whatever the scene.
      !> Sampled at delta = 0 (for delta_min <= 0: P increases with delta, so P(0) bounds
      !> the missing force of all separations) and at 4 overlaps per decade from the
      !> smallest positive overlap of interest (delta_min, or sigma/100) to delta_max, where
      !> roughness matters most relative to Hertz at the small end. Solves in parallel at
      !> rel_tol = min(options%rel_tol, tol/10).
      module subroutine scene_hertz_error(scene, options, worst, n_solves, error)
         type(contact_scene), intent(in) :: scene
         type(solver_options), intent(in) :: options
         real(dp), intent(out) :: worst
         integer, intent(out) :: n_solves
         type(egw_error), allocatable, intent(out) :: error
      end subroutine scene_hertz_error

      !> Build the tables of a choice at the scene's tolerance (nothing for Hertz): the 1-D
      !> table over the set's overlap range (with the pair's particle radii recorded for
      !> LAMMPS), or the universal table over the scene's mu range (widened to +-5 % when
      !> mu is one value: the table needs a range) and delta/sigma range. measured_error is
      !> the largest relative force error the builds measured at their check solves.
      module subroutine build_scene_tables(scene, choice, options, tables, error, progress, &
         & law)
         type(contact_scene), intent(in) :: scene   !< resolved (resolve_scene)
         type(model_choice), intent(in) :: choice   !< from choose_model
         type(solver_options), intent(in) :: options   !< of the builds' solves
         type(scene_tables), intent(out) :: tables   !< the chosen tables (none for Hertz)
         type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
         !> called as the build goes (see egw_table's table_progress; not called for Hertz)
         procedure(table_progress), optional :: progress
         !> the law of a flat-law scene (model flat law: required)
         class(flat_law), intent(in), optional :: law
      end subroutine build_scene_tables

      !> One 1-D table per particle-type pair (1,1), (1,2), .., (1,n), (2,2), .., (n,n) of a
      !> scene with discrete types and one sigma (for LAMMPS, whose pair_style table needs
      !> one section per type pair), each over its pair's overlap range at the scene's
      !> tolerance with the pair's particle radii recorded; pairs with the same parameter
      !> set share one build. egw_unsupported for a radius or sigma range (no finite set
      !> of type pairs). The optional progress hook is passed to every build_table: one
      !> sequence (done from 0 to total) per distinct parameter set, one set after another.
      module subroutine build_pair_tables(scene, options, tables, error, progress)
         type(contact_scene), intent(in) :: scene
         type(solver_options), intent(in) :: options
         type(force_table), allocatable, intent(out) :: tables(:)
         type(egw_error), allocatable, intent(out) :: error
         procedure(table_progress), optional :: progress
      end subroutine build_pair_tables
   end interface

contains

   !> The embedded default scene: two 1 mm glass beads (E = 70 GPa, nu = 0.22 each),
   !> combined summit-height std 1 um, mu = 4, E-GW, overlaps -2 sigma .. 20 sigma
   !> (first summit contacts to several times the roughness), force tolerance 1e-4.
   pure function default_scene_input() result(s)
      type(scene_input) :: s
      s%model = model_egw
      s%n_types = 1
      s%radius(1) = 1.0e-3_dp
      s%modulus(1) = 70.0e9_dp
      s%poisson(1) = 0.22_dp
      s%sigma_min = 1.0e-6_dp
      s%sigma_max = 1.0e-6_dp
      s%mu = 4.0_dp
      s%delta_min = -2.0_dp
      s%delta_max = 20.0_dp
      s%delta_in_sigma = 1
      s%tol = 1.0e-4_dp
   end function default_scene_input

   !> Model constant from a name: Hertz, GW, E-GW, EP-GW (case and '-' ignored) or 0..3.
   pure subroutine model_from_name(name, model, error)
      character(len=*), intent(in) :: name
      integer, intent(out) :: model
      type(egw_error), allocatable, intent(out) :: error
      character(len=:), allocatable :: key
      integer :: i
      key = ""
      do i = 1, len_trim(name)
         select case (name(i:i))
         case ("-", "_", " ")
         case ("A":"Z"); key = key//achar(iachar(name(i:i)) + 32)
         case default; key = key//name(i:i)
         end select
      end do
      select case (key)
      case ("hertz", "0"); model = model_hertz
      case ("gw", "1"); model = model_gw
      case ("egw", "2"); model = model_egw
      case ("epgw", "3"); model = model_epgw
      case ("flatlaw", "4"); model = model_flat_law
      case default
         model = -1
         call fatal_error(error, egw_invalid_parameter, "model = '"//trim(name)// &
            & "': unknown (Hertz, GW, E-GW, EP-GW or flat law)")
      end select
   end subroutine model_from_name

   pure function choice_label(kind) result(name)
      integer, intent(in) :: kind
      character(len=24) :: name
      select case (kind)
      case (choice_hertz); name = "Hertz closed form"
      case (choice_table); name = "1-D table"
      case (choice_universal); name = "universal 2-D table"
      case default; name = "unknown"
      end select
   end function choice_label

   !> Name of a choice for messages.
   pure function choice_name(kind) result(name)
      integer, intent(in) :: kind   !< choice_hertz, choice_table or choice_universal
      ! not a deferred length: gfortran 12 keeps those in a static variable (egw_text)
      character(len=len_trim(choice_label(kind))) :: name
      name = choice_label(kind)
   end function choice_name

   !> Read the namelist group &scene of a file into input: the variables given replace
   !> those of input, the rest keep their values (so a file may change only sigma of the
   !> default scene). Variables (doc/scenes.md): model, radius(1:8) or radius_min and
   !> radius_max, modulus(1:8), poisson(1:8) or effective_modulus, sigma or sigma_min and
   !> sigma_max, mu or summit_density and summit_radius, psi, K, plastic_ratio,
   !> delta_min and delta_max or delta_min_sigma and delta_max_sigma, tol, flat_law,
   !> flow_pressure or yield_stress (smooth spheres; doc/theory.md §12). The result is
   !> validated; on any error input is unchanged and the message names the variable.
   !> Thread-safe, also on one file from many threads at once: the file is read whole
   !> through C stdio (egw_io) and the namelist parsed from memory (a Fortran open of a
   !> file another thread has open fails: "File already opened in another unit").
   subroutine read_scene_file(path, input, error)
      character(len=*), intent(in) :: path   !< a scene file (doc/scenes.md)
      !> the variables given replace its own; unchanged on error
      type(scene_input), intent(inout) :: input
      !> allocated on failure, naming the line
      type(egw_error), allocatable, intent(out) :: error
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
   end subroutine read_scene_file

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

   pure function to_lower(str) result(lower)
      character(len=*), intent(in) :: str
      character(len=len(str)) :: lower
      integer :: i
      lower = str
      do i = 1, len(str)
         if (str(i:i) >= "A" .and. str(i:i) <= "Z") lower(i:i) = achar(iachar(str(i:i)) + 32)
      end do
   end function to_lower

   !> Replace the fields of input that ov gives (see scene_overrides), then validate.
   !> On any error input is unchanged and the message names the variable.
   pure subroutine apply_scene_overrides(input, ov, error)
      type(scene_input), intent(inout) :: input   !< the scene to change
      type(scene_overrides), intent(in) :: ov !< the fields given replace those of input
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
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
   end subroutine apply_scene_overrides

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
         if (.not. positive(ov%yield_stress)) then
            call bad(error, "yield_stress", ov%yield_stress, "must be finite and > 0 "// &
               & "(flow_pressure = 1.6 yield_stress; flow_pressure = 0 for no bulk yield)")
            return
         end if
         s%flow_pressure = flow_pressure_per_yield_stress*ov%yield_stress
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

   !> Check a scene; the message names the first offending field and its value.
   pure subroutine validate_scene_input(s, error)
      type(scene_input), intent(in) :: s   !< the scene to check
      !> allocated, naming the entry, when one is invalid
      type(egw_error), allocatable, intent(out) :: error
      if (s%model < model_hertz .or. s%model > model_flat_law) then
         call fatal_error(error, egw_invalid_parameter, "model = "//int_str(s%model)// &
            & ": unknown (0 Hertz, 1 GW, 2 E-GW, 3 EP-GW, 4 flat law)")
         return
      end if
      if ((s%model == model_flat_law) .neqv. (len_trim(s%flat_law) > 0)) then
         call fatal_error(error, egw_invalid_parameter, "model = flat law and flat_law: " &
            & //"a flat-law scene names its law file (flat_law = 'path', egw-table " &
            & //"--flat-law FILE), and a law file makes the model flat law")
         return
      end if
      call check_particles(s, error)
      if (allocated(error)) return
      call check_materials(s, error)
      if (allocated(error)) return
      call check_roughness(s, error)
      if (allocated(error)) return
      call check_summit_law(s, error)
      if (allocated(error)) return
      call check_overlaps(s, error)
      if (allocated(error)) return
      call check_cap(s, error)
      if (allocated(error)) return
      if (.not. (s%tol >= tol_min .and. s%tol <= tol_max)) then
         call bad(error, "tol", s%tol, "must lie in ["//format_real(tol_min)//", "// &
            & format_real(tol_max)//"]")
         return
      end if
   end subroutine validate_scene_input

   !> validate_scene_input: the particle types and their radii (a list or a range).
   pure subroutine check_particles(s, error)
      type(scene_input), intent(in) :: s
      type(egw_error), allocatable, intent(out) :: error
      integer :: i
      if (s%n_types < 0 .or. s%n_types > max_types) then
         call fatal_error(error, egw_invalid_parameter, "n_types = "//int_str(s%n_types)// &
            & ": must lie in [0, "//int_str(max_types)//"] (0: radius range)")
         return
      end if
      if (s%n_types == 0) then
         if (.not. positive(s%radius_min)) then
            call bad(error, "radius_min", s%radius_min, "must be finite and > 0"); return
         end if
         if (.not. (positive(s%radius_max) .and. s%radius_max >= s%radius_min)) then
            call bad(error, "radius_max", s%radius_max, "must be finite and >= radius_min")
            return
         end if
      end if
      do i = 1, s%n_types
         if (.not. positive(s%radius(i))) then
            call bad(error, "radius("//int_str(i)//")", s%radius(i), "must be finite and > 0")
            return
         end if
      end do
   end subroutine check_particles

   !> validate_scene_input: E* of every pair, or E and nu per type (doc/theory.md §1).
   pure subroutine check_materials(s, error)
      type(scene_input), intent(in) :: s
      type(egw_error), allocatable, intent(out) :: error
      integer :: i
      if (s%effective_modulus /= 0.0_dp) then
         if (.not. positive(s%effective_modulus)) then
            call bad(error, "effective_modulus", s%effective_modulus, &
               & "must be finite and > 0 (or 0: from modulus and poisson)")
            return
         end if
      else
         do i = 1, max(1, s%n_types)
            if (i > 1 .and. s%modulus(i) == 0.0_dp) cycle  ! same material as type 1
            if (.not. positive(s%modulus(i))) then
               call bad(error, "modulus("//int_str(i)//")", s%modulus(i), &
                  & "must be finite and > 0")
               return
            end if
            if (.not. (s%poisson(i) > -1.0_dp .and. s%poisson(i) <= 0.5_dp)) then
               call bad(error, "poisson("//int_str(i)//")", s%poisson(i), &
                  & "must lie in (-1, 0.5]")
               return
            end if
         end do
         if (s%n_types == 0 .and. any(s%modulus(2:) /= 0.0_dp)) then
            call fatal_error(error, egw_invalid_parameter, "modulus(2): a radius range "// &
               & "has one material (give a list of types for several)")
            return
         end if
      end if
   end subroutine check_materials

   !> validate_scene_input: the roughness (sigma range) and, for a rough model, mu or the
   !> summits it follows from (doc/theory.md §1).
   pure subroutine check_roughness(s, error)
      type(scene_input), intent(in) :: s
      type(egw_error), allocatable, intent(out) :: error
      if (.not. (ieee_is_finite(s%sigma_min) .and. s%sigma_min >= 0.0_dp)) then
         call bad(error, "sigma_min", s%sigma_min, "must be finite and >= 0"); return
      end if
      if (.not. (ieee_is_finite(s%sigma_max) .and. s%sigma_max >= s%sigma_min)) then
         call bad(error, "sigma_max", s%sigma_max, "must be finite and >= sigma_min"); return
      end if
      if (s%sigma_min == 0.0_dp .and. s%sigma_max > 0.0_dp) then
         call bad(error, "sigma_min", s%sigma_min, "a roughness range must be > 0 "// &
            & "(sigma = 0 alone means smooth spheres)")
         return
      end if
      if (s%model == model_flat_law .and. .not. (s%sigma_min == s%sigma_max .and. &
         & s%sigma_max > 0.0_dp)) then
         call bad(error, "sigma", s%sigma_max, "a flat-law scene's sigma is its law's " &
            & //"length: one value > 0 (egw-table sets it from the law)")
         return
      end if
      if (s%sigma_max > 0.0_dp .and. s%model /= model_hertz .and. &
         & s%model /= model_flat_law) then
         if (s%mu /= 0.0_dp) then
            if (.not. positive(s%mu)) then
               call bad(error, "mu", s%mu, "must be finite and > 0"); return
            end if
         else
            if (.not. positive(s%summit_density)) then
               call bad(error, "summit_density", s%summit_density, &
                  & "must be finite and > 0 (or give mu)")
               return
            end if
            if (.not. positive(s%summit_radius)) then
               call bad(error, "summit_radius", s%summit_radius, &
                  & "must be finite and > 0 (or give mu)")
               return
            end if
         end if
      end if
   end subroutine check_roughness

   !> validate_scene_input: psi and the ZMC constants K, rho_p (doc/theory.md §3).
   pure subroutine check_summit_law(s, error)
      type(scene_input), intent(in) :: s
      type(egw_error), allocatable, intent(out) :: error
      if (.not. (ieee_is_finite(s%psi) .and. s%psi >= 0.0_dp)) then
         call bad(error, "psi", s%psi, "must be finite and >= 0"); return
      end if
      if (.not. (s%hardness_coeff > 0.0_dp .and. s%hardness_coeff < 1.0_dp)) then
         call bad(error, "K", s%hardness_coeff, "must lie in (0, 1)"); return
      end if
      if (.not. (ieee_is_finite(s%plastic_ratio) .and. s%plastic_ratio > 1.0_dp)) then
         call bad(error, "plastic_ratio", s%plastic_ratio, "must be finite and > 1"); return
      end if
   end subroutine check_summit_law

   !> validate_scene_input: the flow-pressure cap, 0 or > 0 (Hertz, GW, E-GW, EP-GW; not a
   !> flat law; each pair's p_y < E* is checked with its parameters).
   pure subroutine check_cap(s, error)
      type(scene_input), intent(in) :: s
      type(egw_error), allocatable, intent(out) :: error
      if (.not. (ieee_is_finite(s%flow_pressure) .and. s%flow_pressure >= 0.0_dp)) then
         call bad(error, "flow_pressure", s%flow_pressure, "must be finite and >= 0 "// &
            & "(0: no bulk yield)")
         return
      end if
      if (s%flow_pressure > 0.0_dp .and. s%model == model_flat_law) then
         call bad(error, "flow_pressure", s%flow_pressure, "the flow-pressure cap with a "// &
            & "flat law is not available in scenes (no hysteresis table takes a flat law; "// &
            & "egw_solve_flat_law takes the cap)")
      end if
   end subroutine check_cap

   !> validate_scene_input: the overlap range and its unit (length or sigma).
   pure subroutine check_overlaps(s, error)
      type(scene_input), intent(in) :: s
      type(egw_error), allocatable, intent(out) :: error
      if (s%delta_in_sigma /= 0 .and. s%delta_in_sigma /= 1) then
         call fatal_error(error, egw_invalid_parameter, "delta_in_sigma = "// &
            & int_str(s%delta_in_sigma)//": must be 0 (length) or 1 (units of sigma)")
         return
      end if
      if (s%delta_in_sigma == 1 .and. s%sigma_max == 0.0_dp) then
         call fatal_error(error, egw_invalid_parameter, "delta_min_sigma/delta_max_sigma:"// &
            & " overlaps in units of sigma need sigma > 0")
         return
      end if
      if (.not. ieee_is_finite(s%delta_min)) then
         call bad(error, delta_name(s, "min"), s%delta_min, "must be finite"); return
      end if
      if (.not. (ieee_is_finite(s%delta_max) .and. s%delta_max > s%delta_min)) then
         call bad(error, delta_name(s, "max"), s%delta_max, "must be finite and > "// &
            & delta_name(s, "min"))
         return
      end if
      if ((s%model == model_hertz .or. s%sigma_max == 0.0_dp) .and. s%delta_max <= 0.0_dp) then
         call bad(error, delta_name(s, "max"), s%delta_max, "smooth spheres need overlaps > 0")
         return
      end if
   end subroutine check_overlaps

   !> Validate a scene and resolve it into the distinct parameter sets of its pairs.
   !> Pairs (i <= j) of types combine as 1/R = 1/R_i + 1/R_j and
   !> 1/E* = (1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j; each at sigma_min and sigma_max (mu from
   !> the summits is increasing in R and sigma, so the ends bound it).
   pure subroutine resolve_scene(input, scene, error)
      type(scene_input), intent(in) :: input   !< a valid scene (validate_scene_input)
      type(contact_scene), intent(out) :: scene   !< its parameter sets and pairs
      type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      real(dp) :: radii(max_types), e_star, r, sig(2)
      integer :: n, i, j, is, ns, nsig, np, match
      integer, allocatable :: pset(:)
      type(contact_params) :: p
      type(contact_params), allocatable :: sets(:)
      real(dp), allocatable :: r1(:), r2(:)

      call validate_scene_input(input, error)
      if (allocated(error)) return
      scene%input = input
      scene%continuous = input%n_types == 0
      if (scene%continuous) then
         n = 2
         radii(1:2) = [input%radius_min, input%radius_max]
      else
         n = input%n_types
         radii(1:n) = input%radius(1:n)
      end if
      sig = [input%sigma_min, input%sigma_max]
      nsig = merge(1, 2, input%sigma_min == input%sigma_max)
      allocate (sets(n*(n + 1)/2*nsig), r1(n*(n + 1)/2*nsig), r2(n*(n + 1)/2*nsig))
      allocate (pset(n*(n + 1)/2*nsig))
      ns = 0
      np = 0
      do i = 1, n
         do j = i, n
            r = radii(i)*radii(j)/(radii(i) + radii(j))
            ! the product over- or underflows where R itself is a double (radii 1e+-200)
            if (.not. (r >= tiny(1.0_dp) .and. r <= huge(1.0_dp))) &
               & r = 1.0_dp/(1.0_dp/radii(i) + 1.0_dp/radii(j))
            if (input%effective_modulus > 0.0_dp) then
               e_star = input%effective_modulus
            else
               e_star = 1.0_dp/(compliance(input, i) + compliance(input, j))
            end if
            do is = 1, nsig
               p = contact_params(model=input%model, radius=r, modulus=e_star, &
                  & sigma=sig(is), mu=1.0_dp, psi=input%psi, &
                  & hardness_coeff=input%hardness_coeff, plastic_ratio=input%plastic_ratio, &
                  & flow_pressure=input%flow_pressure)
               ! (mu stays 1 for smooth spheres and Hertz scenes without roughness data)
               if (input%mu > 0.0_dp) then
                  p%mu = input%mu
               else if (input%summit_density > 0.0_dp .and. sig(is) > 0.0_dp) then
                  p%mu = mu_from_summits(input%summit_density, input%summit_radius, &
                     & sig(is), r)
               end if
               np = np + 1
               match = findloc(same_params(sets(1:ns), p), .true., dim=1)
               if (match > 0) then
                  pset(np) = match
                  cycle
               end if
               call validate_params(p, error, input%model == model_flat_law)
               if (allocated(error)) then
                  error%message = "pair of types "//int_str(i)//", "//int_str(j)//": "// &
                     & error%message
                  return
               end if
               ns = ns + 1
               sets(ns) = p
               r1(ns) = radii(i)
               r2(ns) = radii(j)
               pset(np) = ns
            end do
         end do
      end do
      scene%sets = sets(1:ns)
      scene%pair_set = pset(1:np)
      scene%radius1 = r1(1:ns)
      scene%radius2 = r2(1:ns)
      allocate (scene%delta_min(ns), scene%delta_max(ns))
      do is = 1, ns
         if (input%delta_in_sigma == 1) then
            scene%delta_min(is) = input%delta_min*scene%sets(is)%sigma
            scene%delta_max(is) = input%delta_max*scene%sets(is)%sigma
         else
            scene%delta_min(is) = input%delta_min
            scene%delta_max(is) = input%delta_max
         end if
         ! the solver's range (doc/parameters.md section 5), named before any solve
         if (scene%sets(is)%model /= model_hertz) call check_scaled_overlap("delta_max", &
            & scene%delta_max(is), scene%sets(is)%sigma, error)
         if (allocated(error)) then
            error%message = "parameter set "//int_str(is)//": "//error%message
            return
         end if
      end do
   end subroutine resolve_scene

   ! ------------------------------------------------------------------ helpers

   !> (1 - nu^2)/E of type i (types without a material of their own use type 1's).
   pure real(dp) function compliance(s, i)
      type(scene_input), intent(in) :: s
      integer, intent(in) :: i
      integer :: m
      m = i
      if (s%modulus(m) == 0.0_dp) m = 1
      compliance = (1.0_dp - s%poisson(m)**2)/s%modulus(m)
   end function compliance

   elemental logical function same_params(a, b)
      type(contact_params), intent(in) :: a, b
      same_params = a%model == b%model .and. a%radius == b%radius .and. &
         & a%modulus == b%modulus .and. a%sigma == b%sigma .and. a%mu == b%mu
   end function same_params

   pure function delta_name(s, which) result(name)
      type(scene_input), intent(in) :: s
      character(len=*), intent(in) :: which
      ! not a deferred length: gfortran 12 keeps those in a static variable (egw_text)
      character(len=6 + len(which) + merge(6, 0, s%delta_in_sigma == 1)) :: name
      name = "delta_"//which
      if (s%delta_in_sigma == 1) name = "delta_"//which//"_sigma"
   end function delta_name

   elemental logical function positive(x)
      real(dp), intent(in) :: x
      positive = ieee_is_finite(x) .and. x > 0.0_dp
   end function positive

end module egw_scene
