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
      & model_epgw, model_flat_law, mu_from_summits, check_scaled_overlap, positive_finite
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
      !> egw-table writes hysteresis tables with it: Hertz + cap for smooth spheres, the
      !> rough model's with the cap for sigma > 0 (doc/scenes.md). From yield_stress Y:
      !> p_y = 1.6 Y.
      real(dp) :: flow_pressure = 0.0_dp
      !> The yield stress Y that flow_pressure came from (0: flow_pressure given itself):
      !> a refusal of p_y then names the parameter the user gave.
      real(dp) :: yield_stress = 0.0_dp
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
      !> rel_tol = min(options%rel_tol, tol/10); EP-GW sets with psi > 0 on their ZMC law
      !> tabulated once (zmc_law_pieces, as a hysteresis build's solves). A set with a
      !> flow_pressure is measured against the smooth sphere with the same cap (Hertz + cap
      !> solves), not Hertz's closed form: the measure is the roughness's, not the cap's.
      module subroutine scene_hertz_error(scene, options, worst, n_solves, error)
         type(contact_scene), intent(in) :: scene   !< a resolved scene
         type(solver_options), intent(in) :: options   !< the solver's options (rel_tol as above)
         real(dp), intent(out) :: worst   !< the error measure above
         integer, intent(out) :: n_solves   !< full solves it took
         type(egw_error), allocatable, intent(out) :: error   !< the first solve's failure
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
         type(contact_scene), intent(in) :: scene   !< a resolved scene with discrete types
         type(solver_options), intent(in) :: options   !< the solver's options of every build
         !> one per type pair, in the order above
         type(force_table), allocatable, intent(out) :: tables(:)
         !> egw_unsupported as above, or a build's failure
         type(egw_error), allocatable, intent(out) :: error
         procedure(table_progress), optional :: progress   !< called by every build_table
      end subroutine build_pair_tables

      !> Read the namelist group &scene of a file into input: the variables given replace
      !> those of input, the rest keep their values (so a file may change only sigma of the
      !> default scene). Variables (doc/scenes.md): model, radius(1:8) or radius_min and
      !> radius_max, modulus(1:8), poisson(1:8) or effective_modulus, sigma or sigma_min and
      !> sigma_max, mu or summit_density and summit_radius, psi, K, plastic_ratio,
      !> delta_min and delta_max or delta_min_sigma and delta_max_sigma, tol, flat_law,
      !> flow_pressure or yield_stress (the bulk cap: doc/theory.md §12). The result is
      !> validated; on any error input is unchanged and the message names the variable.
      !> Thread-safe, also on one file from many threads at once: the file is read whole
      !> through C stdio (egw_io) and the namelist parsed from memory (a Fortran open of a
      !> file another thread has open fails: "File already opened in another unit").
      module subroutine read_scene_file(path, input, error)
         character(len=*), intent(in) :: path   !< a scene file (doc/scenes.md)
         !> the variables given replace its own; unchanged on error
         type(scene_input), intent(inout) :: input
         !> allocated on failure, naming the line
         type(egw_error), allocatable, intent(out) :: error
      end subroutine read_scene_file

      !> Replace the fields of input that ov gives (see scene_overrides), then validate.
      !> On any error input is unchanged and the message names the variable.
      pure module subroutine apply_scene_overrides(input, ov, error)
         type(scene_input), intent(inout) :: input   !< the scene to change
         type(scene_overrides), intent(in) :: ov !< the fields given replace those of input
         type(egw_error), allocatable, intent(out) :: error   !< allocated on failure
      end subroutine apply_scene_overrides
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
      character(len=*), intent(in) :: name   !< the model's name or number
      integer, intent(out) :: model   !< model_* constant (-1 if unknown)
      type(egw_error), allocatable, intent(out) :: error   !< egw_invalid_parameter naming the text
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
         if (.not. positive_finite(s%radius_min)) then
            call bad(error, "radius_min", s%radius_min, "must be finite and > 0"); return
         end if
         if (.not. (positive_finite(s%radius_max) .and. s%radius_max >= s%radius_min)) then
            call bad(error, "radius_max", s%radius_max, "must be finite and >= radius_min")
            return
         end if
      end if
      do i = 1, s%n_types
         if (.not. positive_finite(s%radius(i))) then
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
         if (.not. positive_finite(s%effective_modulus)) then
            call bad(error, "effective_modulus", s%effective_modulus, &
               & "must be finite and > 0 (or 0: from modulus and poisson)")
            return
         end if
      else
         do i = 1, max(1, s%n_types)
            if (i > 1 .and. s%modulus(i) == 0.0_dp) cycle  ! same material as type 1
            if (.not. positive_finite(s%modulus(i))) then
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
            if (.not. positive_finite(s%mu)) then
               call bad(error, "mu", s%mu, "must be finite and > 0"); return
            end if
         else if (s%summit_density == 0.0_dp .and. s%summit_radius == 0.0_dp) then
            ! no summit data either: mu is what is missing (e.g. --mu 0), not the summits
            call bad(error, "mu", s%mu, "must be finite and > 0 (or give summit_density "// &
               & "and summit_radius)")
            return
         else
            if (.not. positive_finite(s%summit_density)) then
               call bad(error, "summit_density", s%summit_density, &
                  & "must be finite and > 0 (or give mu)")
               return
            end if
            if (.not. positive_finite(s%summit_radius)) then
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
         call bad(error, "K (hardness_coeff)", s%hardness_coeff, "must lie in (0, 1)"); return
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

   !> resolve_scene: a pair's refusal of p_y = 1.6 Y (validate_params names flow_pressure)
   !> restated in the yield stress the user gave (egw-table --yield-stress, a scene's
   !> yield_stress), with the bound in Y where p_y is not below the pair's E*.
   pure subroutine name_yield_stress(yield_stress, p, error)
      real(dp), intent(in) :: yield_stress   !< Y, > 0
      type(contact_params), intent(in) :: p   !< the pair's parameters (p_y = 1.6 Y)
      type(egw_error), intent(inout) :: error   !< validate_params' refusal of flow_pressure
      character(len=:), allocatable :: named
      named = "yield_stress = "//format_real(yield_stress)
      if (p%flow_pressure >= p%modulus) then
         error%message = named//": must lie below E*/1.6 = "// &
            & format_real(p%modulus/flow_pressure_per_yield_stress)//" (flow_pressure = "// &
            & "1.6 yield_stress = "//format_real(p%flow_pressure)//" must lie below the "// &
            & "pair's effective modulus E* = "//format_real(p%modulus)//": a small-strain cap)"
      else
         error%message = named//" (flow_pressure = 1.6 yield_stress): "//error%message
      end if
   end subroutine name_yield_stress

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
                  if (input%yield_stress > 0.0_dp .and. &
                     & index(error%message, "flow_pressure = ") == 1) &
                     & call name_yield_stress(input%yield_stress, p, error)
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

end module egw_scene
