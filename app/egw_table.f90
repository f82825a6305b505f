!> egw-table: the table generator. A scene (the embedded default, a namelist file, and/or
!> command-line flags) goes in; egw_scene picks the cheapest model that meets the
!> scene's force tolerance, builds its tables and this program writes them (the minimal
!> set: none for Hertz, one 1-D table, or the universal table) and a summary.
!> Parsing and printing only; the logic lives in src/egw/scene/scene.f90.
program egw_table_app
   use, intrinsic :: iso_fortran_env, only: output_unit, error_unit, int64
   use egw_all, only: dp, egw_version_string, egw_error, format_real, int_str, model_name, &
      & scene_input, scene_overrides, contact_scene, model_choice, scene_tables, &
      & default_scene_input, read_scene_file, apply_scene_overrides, resolve_scene, &
      & choose_model, build_scene_tables, choice_name, choice_hertz, choice_table, &
      & choice_universal, max_types, solver_options, write_table, write_universal, &
      & write_calculix_flat, write_lammps, force_table, build_pair_tables, format_csv, &
      & format_binary, format_lammps, format_calculix, contact_params, flat_pressure, &
      & hertz_force, hertz_stiffness, hertz_contact_radius, rename_file, model_epgw, &
      & text_buffer, remove_file, hysteresis_table, build_hysteresis, write_hysteresis, &
      & table_flat_law, read_flat_law, write_flat_law, model_flat_law, model_hertz, &
      & make_directories
   use egw_progress_bar, only: bar_start, bar_update, bar_finish
   use egw_terminal, only: stderr_is_terminal, exit_process
   implicit none

   type(scene_input) :: input
   type(scene_overrides) :: ov, ov_law
   !> the rough-flat law of a flat-law scene (flat_law = 'FILE', --flat-law FILE)
   type(table_flat_law) :: law
   type(contact_scene) :: scene
   type(model_choice) :: choice
   type(scene_tables) :: tables
   type(solver_options) :: options
   type(egw_error), allocatable :: error
   character(len=:), allocatable :: out_dir, arg, val, scene_file, format_list
   character(len=:), allocatable :: written(:)
   type(force_table), allocatable :: pair_tables(:)
   logical :: want(0:3), formats_given, quiet, choose_only, pair_lammps
   integer :: iarg, n_written
   integer(int64) :: t0, t1, rate
   real(dp) :: elapsed
   !> deepest overlap the LAMMPS sections reach (0: default, twice the scene's delta_max)
   real(dp) :: lammps_reach = 0.0_dp
   logical :: lammps_written = .false.
   !> EP-GW hysteresis tables written (one per parameter set), or why none
   integer :: n_hysteresis = 0
   character(len=:), allocatable :: hysteresis_note
   !> the largest max_error of the hysteresis tables written (the summary's measured error
   !> of a cap scene, whose choice's own bound is the cap-free models')
   real(dp) :: hysteresis_error = 0.0_dp

   call system_clock(t0, rate)
   out_dir = "out"
   scene_file = ""
   format_list = ""
   formats_given = .false.
   quiet = .false.
   choose_only = .false.
   iarg = 1
   do while (iarg <= command_argument_count())
      call get_arg(iarg, arg)
      if (arg(1:min(2, len(arg))) /= "--" .and. arg /= "-h" .and. arg /= "-o" &
         & .and. arg /= "-q") then
         if (len(scene_file) > 0) call die("two scene files given: '"//scene_file// &
            & "' and '"//arg//"'")
         scene_file = arg
         iarg = iarg + 1
         cycle
      end if
      select case (arg)
      case ("-h", "--help")
         call usage()
         stop
      case ("-q", "--quiet")
         quiet = .true.
      case ("--choose-only")
         choose_only = .true.
      case default
         if (.not. takes_value(arg)) call die("unknown option "//arg//" (see --help)")
         call next_value(iarg, arg, val)
         select case (arg)
         case ("-o", "--out"); out_dir = val
         case ("--formats"); format_list = val; formats_given = .true.
         case ("--model"); ov%model = val
         case ("--flat-law"); ov%flat_law = val
         case ("--radius"); ov%radius(1) = real_value(arg, val)
         case ("--radii"); call real_list(arg, val, ov%radius)
         case ("--radius-range"); call real_pair(arg, val, ov%radius_min, ov%radius_max)
         case ("--modulus"); call real_list(arg, val, ov%modulus)
         case ("--poisson"); call real_list(arg, val, ov%poisson)
         case ("--effective-modulus"); ov%effective_modulus = real_value(arg, val)
         case ("--sigma"); ov%sigma = real_value(arg, val)
         case ("--sigma-range"); call real_pair(arg, val, ov%sigma_min, ov%sigma_max)
         case ("--mu"); ov%mu = real_value(arg, val)
         case ("--summit-density"); ov%summit_density = real_value(arg, val)
         case ("--summit-radius"); ov%summit_radius = real_value(arg, val)
         case ("--psi"); ov%psi = real_value(arg, val)
         case ("--K", "--k"); ov%hardness_coeff = real_value(arg, val)
         case ("--plastic-ratio"); ov%plastic_ratio = real_value(arg, val)
         case ("--delta-min"); ov%delta_min = real_value(arg, val)
         case ("--delta-max"); ov%delta_max = real_value(arg, val)
         case ("--delta-min-sigma"); ov%delta_min_sigma = real_value(arg, val)
         case ("--delta-max-sigma"); ov%delta_max_sigma = real_value(arg, val)
         case ("--tol"); ov%tol = real_value(arg, val)
         case ("--flow-pressure"); ov%flow_pressure = real_value(arg, val)
         case ("--yield-stress"); ov%yield_stress = real_value(arg, val)
         case ("--lammps-delta-max"); lammps_reach = real_value(arg, val)
         case default
            call die("unknown option "//arg//" (see --help)")
         end select
      end select
      iarg = iarg + 1
   end do

   ! --- everything is validated before anything is built or written
   input = default_scene_input()
   if (len(scene_file) > 0) then
      call read_scene_file(scene_file, input, error)
      if (allocated(error)) call die(error%message)
   end if
   call apply_scene_overrides(input, ov, error)
   if (allocated(error)) call die("command line: "//error%message)
   if (input%model == model_flat_law) then
      ! the law's length is the scene's sigma (overlaps given in sigma are in it)
      call read_flat_law(trim(input%flat_law), law, error)
      if (allocated(error)) call die(error%message)
      ov_law%sigma = law%length()
      call apply_scene_overrides(input, ov_law, error)
      if (allocated(error)) call die("flat_law: "//error%message)
   end if
   call resolve_scene(input, scene, error)
   if (allocated(error)) call die(error%message)
   call parse_formats(format_list, formats_given, want)
   if (lammps_reach == 0.0_dp) then
      lammps_reach = 2.0_dp*maxval(scene%delta_max)
   else if (.not. (lammps_reach >= maxval(scene%delta_max) .and. lammps_reach < huge(1.0_dp))) &
      & then
      call die("--lammps-delta-max = "//num(lammps_reach)//": must be finite and >= "// &
         & "the scene's delta_max = "//num(maxval(scene%delta_max))//" [length]")
   end if

   call print_scene()
   call progress("choosing the model (Hertz check by full solves) ...")
   call choose_model(scene, options, choice, error)
   if (allocated(error)) call die(error%message)
   ! LAMMPS beside a universal table: one 1-D table per particle-type pair (possible for
   ! discrete types with one sigma); CalculiX files hold one parameter set
   pair_lammps = choice%kind == choice_universal .and. formats_given .and. &
      & want(format_lammps)
   if (choice%kind == choice_universal .and. formats_given .and. want(format_calculix)) &
      & call die("--formats: CalculiX files hold one parameter set; this scene needs "// &
      & "the universal table (csv, binary; lammps for particle types)")
   if (pair_lammps .and. (input%n_types == 0 .or. input%sigma_min /= input%sigma_max)) &
      & call die("--formats: a LAMMPS file needs one table per particle-type pair: "// &
      & "list the types (--radii) and give one sigma")
   if (.not. formats_given) want = [.true., .true., choice%kind == choice_table, &
      & choice%kind == choice_table .and. input%model /= model_flat_law]
   if (input%model == model_flat_law .and. want(format_calculix)) call die("--formats " &
      & //"calculix: the CalculiX curves are GW's rough flat; a flat-law scene has csv, " &
      & //"binary and lammps")
   write (output_unit, '(a)') "model: "//choice_name(choice%kind)//" ("// &
      & model_name(merge(0, input%model, choice%kind == choice_hertz))//")"
   write (output_unit, '(a)') "  why: "//choice%reason
   ! as Python's IgnoredParameterWarning and LAMMPS's WARNING: a psi the model ignores
   if (input%psi > 0.0_dp .and. input%model /= model_epgw) write (output_unit, '(a)') &
      & "  note: psi = "//num(input%psi)//" is EP-GW's plasticity index: model "// &
      & trim(model_name(input%model))//" ignores it"
   if (input%flow_pressure > 0.0_dp .and. choice%kind == choice_hertz) write (output_unit, &
      & '(a)') "  note: flow_pressure = "// &
      & num(input%flow_pressure)//": Hertz holds up to first yield only, (pi p_y/(2 E*))^2 R;"// &
      & " the hysteresis table(s) hold the cap's loading and unloading beyond it"
   if (input%flow_pressure > 0.0_dp .and. choice%kind /= choice_hertz) write (output_unit, &
      & '(a)') "  note: flow_pressure = "//num(input%flow_pressure)//": with the cap no "// &
      & "force table is written (a capped loading curve unloads otherwise); the "// &
      & "hysteresis table(s) of the rough model + cap hold loading and unloading"

   n_written = 0
   ! every output: at most 10 tables and curves, and a hysteresis table in two formats
   ! per parameter set
   allocate (character(len=1024) :: written(10 + 2*max_types*(max_types + 1)/2))
   ! the output directory before any build (one that cannot be made stops at once), and
   ! without a shell: "mkdir -p '...'" broke on a quote in the path and printed the
   ! shell's own error beside egw-table's
   if (.not. choose_only .and. (input%flow_pressure > 0.0_dp .or. &
      & choice%kind /= choice_hertz)) then
      if (.not. make_directories(out_dir)) call die("--out "//out_dir// &
         & ": cannot create the directory (nothing written)")
   end if
   if (.not. choose_only .and. input%flow_pressure > 0.0_dp) then
      ! the flow-pressure cap: no force table (the closed form holds up to first yield
      ! only; a rough capped loading curve is no reversible law), the hysteresis tables
      call write_all()
   else if (.not. choose_only .and. choice%kind /= choice_hertz) then
      call progress("building the "//choice_name(choice%kind)//" at tol = "// &
         & num(input%tol)//" (full solves, OpenMP over points) ...")
      if (quiet) then
         call build_scene_tables(scene, choice, options, tables, error, law=law)
      else
         call bar_start("building", stderr_is_terminal())
         call build_scene_tables(scene, choice, options, tables, error, bar_update, law=law)
         call bar_finish()
      end if
      if (allocated(error)) call die(error%message)
      if (pair_lammps) then
         call progress("LAMMPS: building one 1-D table per particle-type pair ...")
         if (quiet) then
            call build_pair_tables(scene, options, pair_tables, error)
         else
            ! the bar restarts for every distinct parameter set (so does the count)
            call bar_start("building", stderr_is_terminal())
            call build_pair_tables(scene, options, pair_tables, error, bar_update)
            call bar_finish()
         end if
         if (allocated(error)) call die(error%message)
      end if
      call write_all()
   end if

   call system_clock(t1)
   elapsed = real(t1 - t0, dp)/real(rate, dp)
   call summary()

contains

   !> Write every wanted format of the tables under out_dir: first each to a
   !> '.part' file (itself written atomically), then all renamed, so that a failure
   !> leaves no partial set of files behind.
   subroutine write_all()
      character(len=:), allocatable :: base
      integer :: i
      select case (tables%kind)
      case (choice_table)
         base = out_dir//"/scene_table"
         if (want(format_csv)) then
            call put(base//".csv", format_csv)
            call put_curves(scene%sets(1), scene%delta_min(1), scene%delta_max(1))
         end if
         if (want(format_binary)) call put(base//".bin", format_binary)
         if (want(format_lammps)) then
            call write_lammps([tables%table], base//".lammps.part", error, &
               & delta_reach=lammps_reach)
            if (allocated(error)) call fail_write(error%message)
            n_written = n_written + 1
            written(n_written) = base//".lammps"
            lammps_written = .true.
         end if
         ! CalculiX: the rough flat's pressure-overclosure law (a contact law between
         ! surfaces). The sphere's force-overlap curve is not one: CalculiX multiplies a
         ! pressure-overclosure curve by each slave node's area, so it is not written here
         ! (the library's write_calculix_sphere documents what it is for).
         if (want(format_calculix)) call put_flat(out_dir//"/scene_flat.inp")
      case (choice_universal)
         base = out_dir//"/scene_universal"
         if (want(format_csv)) call put(base//".csv", format_csv)
         if (want(format_binary)) call put(base//".bin", format_binary)
         if (pair_lammps) then
            call write_lammps(pair_tables, out_dir//"/scene_pairs.lammps.part", error, &
               & delta_reach=lammps_reach)
            lammps_written = .true.
            if (allocated(error)) call fail_write(error%message)
            n_written = n_written + 1
            written(n_written) = out_dir//"/scene_pairs.lammps"
         end if
      end select
      call put_hysteresis()
      do i = 1, n_written
         call rename_file(trim(written(i))//".part", trim(written(i)), error)
         if (allocated(error)) call fail_write(error%message)
      end do
   end subroutine write_all

   !> EP-GW with plastic summits, or any model but a flat law with the flow-pressure cap: the
   !> hysteresis table (loading, unloading, reloading) of every parameter set in the
   !> wanted egw formats, built to the scene's tolerance, for DEM codes that carry a
   !> per-contact history. A continuous radius or sigma range has no finite set of them
   !> (only discrete particle types do).
   subroutine put_hysteresis()
      type(hysteresis_table) :: h
      type(contact_params) :: set
      character(len=:), allocatable :: base
      integer :: i, n_sets
      if (.not. ((input%model == model_epgw .and. input%psi > 0.0_dp) .or. &
         & input%flow_pressure > 0.0_dp)) return
      if (.not. (want(format_csv) .or. want(format_binary))) return
      if (input%n_types == 0 .and. (tables%kind == choice_universal .or. &
         & input%flow_pressure > 0.0_dp)) then
         hysteresis_note = "not written: a radius or sigma range has no finite set of "// &
            & "parameter sets (list the particle types with --radii, or build one with "// &
            & "egw_hysteresis_build)"
         return
      end if
      n_sets = size(scene%sets)
      do i = 1, n_sets
         call progress("building the "//either(input%flow_pressure > 0.0_dp, &
            & cap_label(), "EP-GW")//" hysteresis table of parameter set "// &
            & int_str(i)//" at tol = "//num(input%tol)//" ...")
         set = scene%sets(i)
         ! the chooser found the roughness within tol of Hertz + cap: the smooth sphere's
         ! table (a model no more than the scene needs; it was the rough model's + cap)
         if (hertz_cap()) set = contact_params(model=model_hertz, radius=set%radius, &
            & modulus=set%modulus, flow_pressure=set%flow_pressure)
         if (quiet) then
            call build_hysteresis(set, options, scene%delta_min(i), &
               & scene%delta_max(i), input%tol, h, error)
         else
            call bar_start("hysteresis", stderr_is_terminal(), "unloading curves")
            call build_hysteresis(set, options, scene%delta_min(i), &
               & scene%delta_max(i), input%tol, h, error, bar_update)
            call bar_finish()
         end if
         if (allocated(error)) call fail_write("hysteresis table: "//error%message)
         ! (a reversible table's error is its loading table's: max_error is 0 there)
         hysteresis_error = max(hysteresis_error, h%max_error, h%loading%max_force_error)
         base = out_dir//"/scene_hysteresis"
         if (n_sets > 1) base = base//"_"//int_str(i)
         if (want(format_csv)) call put_hysteresis_file(h, base//".csv", format_csv)
         if (want(format_binary)) call put_hysteresis_file(h, base//".bin", format_binary)
         n_hysteresis = n_hysteresis + 1
      end do
   end subroutine put_hysteresis

   !> "Hertz + cap", or the rough model's name + cap.
   function cap_label() result(label)
      character(len=:), allocatable :: label
      label = "Hertz + cap"
      if (input%model /= model_hertz .and. input%sigma_max > 0.0_dp .and. .not. &
         & hertz_cap()) label = model_name(input%model)//" + cap"
   end function cap_label

   !> With the cap, the chooser took Hertz for a rough scene: Hertz + cap's tables.
   logical function hertz_cap()
      hertz_cap = input%flow_pressure > 0.0_dp .and. choice%kind == choice_hertz
   end function hertz_cap

   subroutine put_hysteresis_file(h, path, format)
      type(hysteresis_table), intent(in) :: h
      character(len=*), intent(in) :: path
      integer, intent(in) :: format
      call write_hysteresis(h, path//".part", format, error)
      if (allocated(error)) call fail_write(error%message)
      n_written = n_written + 1
      written(n_written) = path
   end subroutine put_hysteresis_file

   subroutine put(path, format)
      character(len=*), intent(in) :: path
      integer, intent(in) :: format
      if (tables%kind == choice_table) then
         call write_table(tables%table, path//".part", format, error)
      else
         call write_universal(tables%universal, path//".part", format, error)
      end if
      if (allocated(error)) call fail_write(error%message)
      n_written = n_written + 1
      written(n_written) = path
   end subroutine put

   !> CalculiX pressure-overclosure curve of the rough flat of the scene's pair, up to
   !> an overclosure of delta_max.
   subroutine put_flat(path)
      character(len=*), intent(in) :: path
      ! shifted: CalculiX only reaches overclosures >= 0 (node-to-surface contact springs
      ! exist only where the surfaces touch or penetrate), so the curve starts at (0, 0)
      ! at the separation d_c where p_G has fallen to tol p_G(0): the model's surfaces
      ! stand for the summit base planes at separation d_c (doc/formats.md section 5)
      call write_calculix_flat(scene%sets(1), scene%delta_max(1), input%tol, &
         & path//".part", error, shift=.true.)
      if (allocated(error)) call fail_write(error%message)
      n_written = n_written + 1
      written(n_written) = path
   end subroutine put_flat

   !> Reference curves of a parameter set as CSV with a metadata header: the smooth
   !> spheres' Hertz force-overlap curve (doc/theory.md §5) and the rough flat's
   !> pressure-separation law p_G(d) (doc/theory.md §3), 201 points each.
   subroutine put_curves(p, delta_lo, delta_hi)
      type(contact_params), intent(in) :: p
      real(dp), intent(in) :: delta_lo, delta_hi
      integer, parameter :: n = 201
      character(len=:), allocatable :: path
      real(dp) :: x, lo, hi, pg, dpg
      integer :: i
      type(text_buffer) :: out
      character(len=128) :: line
      path = out_dir//"/hertz_force.csv"
      ! column header first, metadata as '#' lines (read as is by pandas.read_csv(path,
      ! comment="#") and numpy.loadtxt(path, delimiter=",", skiprows=1))
      call out%add("delta,force,stiffness,contact_radius")
      call curve_header(out, p, "Hertz force-overlap curve of the smooth spheres (doc/theory.md §5)")
      hi = max(delta_hi, 0.0_dp)
      do i = 0, n - 1
         x = hi*real(i, dp)/real(n - 1, dp)
         write (line, '(3(g0.17,","),g0.17)') x, hertz_force(x, p%radius, p%modulus), &
            & hertz_stiffness(x, p%radius, p%modulus), hertz_contact_radius(x, p%radius)
         call out%add(trim(line))
      end do
      call put_text(out, path)
      if (p%model == model_flat_law) then
         ! the scene's own law, as egw CSV (the rough flat's pressure-separation law)
         path = out_dir//"/scene_flat_law.csv"
         call write_flat_law(law, path//".part", error, source="scene")
         if (allocated(error)) call fail_write(error%message)
         n_written = n_written + 1
         written(n_written) = path
         return
      end if
      if (p%sigma <= 0.0_dp) return
      path = out_dir//"/rough_flat_pressure.csv"
      out = text_buffer()
      call out%add("separation,pressure,dpressure_dseparation")
      call curve_header(out, p, "rough-flat pressure-separation law p_G(d) and dp_G/dd "// &
         & "(doc/theory.md §3); separation d = -overlap")
      lo = -max(delta_hi, 4.0_dp*p%sigma)
      hi = max(-delta_lo, 6.0_dp*p%sigma)
      do i = 0, n - 1
         x = lo + (hi - lo)*real(i, dp)/real(n - 1, dp)
         call flat_pressure(p, x, pg, dpg, error)
         if (allocated(error)) call fail_write(error%message)
         write (line, '(2(g0.17,","),g0.17)') x, pg, dpg
         call out%add(trim(line))
      end do
      call put_text(out, path)
   end subroutine put_curves

   !> Write a text as path//".part" (atomically, every write checked: egw_io).
   subroutine put_text(out, path)
      type(text_buffer), intent(in) :: out
      character(len=*), intent(in) :: path
      call out%write(path//".part", error)
      if (allocated(error)) call fail_write(error%message)
      n_written = n_written + 1
      written(n_written) = path
   end subroutine put_text

   subroutine curve_header(out, p, title)
      type(text_buffer), intent(inout) :: out
      type(contact_params), intent(in) :: p
      character(len=*), intent(in) :: title
      call out%add("# egw "//egw_version_string//": "//title)
      call out%add("# units: those of the scene (SI suggested: m, Pa, N)")
      call out%add("# model = "//model_name(p%model))
      call out%add("# radius = "//format_real(p%radius))
      call out%add("# modulus = "//format_real(p%modulus))
      call out%add("# sigma = "//format_real(p%sigma))
      call out%add("# mu = "//format_real(p%mu))
      call out%add("# psi = "//format_real(p%psi))
      call out%add("# hardness_coeff = "//format_real(p%hardness_coeff))
      call out%add("# plastic_ratio = "//format_real(p%plastic_ratio))
   end subroutine curve_header

   !> Remove the '.part' files written so far, then stop with the message (exit status 2).
   subroutine fail_write(message)
      character(len=*), intent(in) :: message
      integer :: i
      do i = 1, n_written
         call remove_file(trim(written(i))//".part")
      end do
      call die(message//" (no files written)")
   end subroutine fail_write

   subroutine print_scene()
      character(len=:), allocatable :: line
      integer :: i
      if (quiet) return
      write (output_unit, '(a)') "egw-table "//egw_version_string//": scene "// &
         & either(len(scene_file) > 0, scene_file, "(default"// &
         & either(command_argument_count() > 0, " + options)", ")"))
      if (input%n_types == 0) then
         line = "  radius range ["//num(input%radius_min)//", "// &
            & num(input%radius_max)//"]"
      else
         line = "  particle radii"
         do i = 1, input%n_types
            line = line//" "//num(input%radius(i))
         end do
      end if
      write (output_unit, '(a)') line//", model "//model_name(input%model)
      if (input%sigma_min == input%sigma_max) then
         line = "  sigma = "//num(input%sigma_min)
      else
         line = "  sigma in ["//num(input%sigma_min)//", "// &
            & num(input%sigma_max)//"]"
      end if
      if (input%flow_pressure > 0.0_dp) line = line//", flow_pressure = "// &
         & num(input%flow_pressure)
      write (output_unit, '(a)') line//", overlaps ["//num(input%delta_min)//", "// &
         & num(input%delta_max)//"]"//either(input%delta_in_sigma == 1, &
         & " sigma", "")//", tol = "//num(input%tol)
      do i = 1, size(scene%sets)
         associate (p => scene%sets(i))
            write (output_unit, '(a)') "  "//either(input%n_types == 0, "range corner ", &
               & "parameter set ")//int_str(i)//": R = "// &
               & num(p%radius)//", E* = "//num(p%modulus)//", sigma = "// &
               & num(p%sigma)//", mu = "//num(p%mu)//", delta in ["// &
               & num(scene%delta_min(i))//", "//num(scene%delta_max(i))//"]"
         end associate
      end do
   end subroutine print_scene

   subroutine summary()
      integer :: i
      write (output_unit, '(a)') "summary:"
      write (output_unit, '(a)') "  model chosen      "//choice_name(choice%kind)
      if (input%model == model_flat_law) then
         write (output_unit, '(a)') "  Hertz error       not measured (flat-law scene)"
      else
         write (output_unit, '(a)') "  Hertz error       "//num(choice%hertz_error)// &
            & either(choice%hertz_relative_to_max, " of P(delta_max)", " (relative)")// &
            & " (" //int_str(choice%n_solves)//" full solves)"
      end if
      ! a cap scene writes hysteresis tables at tol whatever the choice: "error bound 0"
      ! of a Hertz choice alone read as an exact table (audit29)
      write (output_unit, '(a)') "  error bound       "//num(choice%error_bound)// &
         & either(input%flow_pressure > 0.0_dp, " (the model choice's; the "// &
         & cap_label()//" hysteresis table(s): tol = "//num(input%tol)//")", "")
      if (input%flow_pressure > 0.0_dp .and. n_hysteresis > 0) write (output_unit, '(a)') &
         & "  measured error    "//num(hysteresis_error)//" (max at the "//cap_label()// &
         & " hysteresis build's check solves)"
      if (.not. choose_only .and. choice%kind /= choice_hertz .and. &
         & input%flow_pressure == 0.0_dp) then
         write (output_unit, '(a)') "  measured error    "// &
            & num(tables%measured_error)//" (max at the build's check solves)"
         write (output_unit, '(a)') "  nodes             "//int_str(tables%n_nodes)// &
            & either(tables%kind == choice_universal, &
            & " (x nodes * mu nodes)", "")
      end if
      write (output_unit, '(a,f7.3,a)') "  time           ", elapsed, " s"
      if (n_written == 0) then
         if (input%flow_pressure > 0.0_dp) then
            ! the cap needs its hysteresis table even where the choice is Hertz (below δ_y)
            write (output_unit, '(a)') "  files             none ("//either(choose_only, &
               & "--choose-only: the "//cap_label()//" hysteresis table(s) not built)", &
               & "the "//cap_label()//" hysteresis table(s) come in the csv and binary"// &
               & " formats only: --formats)")
         else
            write (output_unit, '(a)') "  files             none"// &
               & either(choice%kind == choice_hertz, " (Hertz closed form: no table needed)", &
               & "")
         end if
      end if
      do i = 1, n_written
         write (output_unit, '(a)') "  wrote             "//trim(written(i))
      end do
      if (allocated(pair_tables)) call pair_sections()
      if (input%model == model_epgw .and. input%psi > 0.0_dp .and. n_written > 0 .and. &
         & (want(format_lammps) .or. want(format_calculix))) write (output_unit, '(a)') &
         & "  WARNING           EP-GW: the LAMMPS and CalculiX files carry the loading"// &
         & " curve only (no unloading hysteresis, no plastic dissipation)"
      if (n_hysteresis > 0) write (output_unit, '(a)') "  hysteresis        "// &
         & int_str(n_hysteresis)//either(input%flow_pressure > 0.0_dp, " "// &
         & cap_label()//" (flow_pressure "//num(input%flow_pressure)//")", " EP-GW")// &
         & " table(s) scene_hysteresis*: loading, unloading"// &
         & " and reloading over (delta, delta_max) for a per-contact history"// &
         & " (egw_hysteresis_read, egw_hysteresis_eval)"
      if (allocated(hysteresis_note)) write (output_unit, '(a)') &
         & "  hysteresis        "//hysteresis_note
      if (lammps_written) then
         write (output_unit, '(a)') "  LAMMPS reach      delta <= "//num(lammps_reach)// &
            & " (--lammps-delta-max; default 2 x delta_max): deeper overlaps stop LAMMPS"// &
            & " with 'Pair distance < table inner cutoff'; above delta_max the force"// &
            & " follows the deep-overlap asymptote"
      end if
   end subroutine summary

   !> Which particle types each LAMMPS section of scene_pairs.lammps is for.
   subroutine pair_sections()
      integer :: i, j, k
      k = 0
      do i = 1, input%n_types
         do j = i, input%n_types
            k = k + 1
            write (output_unit, '(a)') "    section EGW_"//int_str(k)//": types "// &
               & int_str(i)//" "//int_str(j)//" (pair_coeff "//int_str(i)//" "// &
               & int_str(j)//" scene_pairs.lammps EGW_"//int_str(k)//")"
         end do
      end do
   end subroutine pair_sections

   subroutine parse_formats(list, given_list, want)
      character(len=*), intent(in) :: list
      logical, intent(in) :: given_list
      logical, intent(out) :: want(0:3)
      integer :: i0, i
      character(len=:), allocatable :: item
      want = .false.
      if (.not. given_list) return
      i0 = 1
      do i = 1, len(list) + 1
         if (i <= len(list)) then
            if (list(i:i) /= ",") cycle
         end if
         item = list(i0:i - 1)
         select case (item)
         case ("csv"); want(format_csv) = .true.
         case ("binary", "bin"); want(format_binary) = .true.
         case ("lammps"); want(format_lammps) = .true.
         case ("calculix", "ccx"); want(format_calculix) = .true.
         case default
            call die("--formats: '"//item//"' is not one of csv, binary, lammps, calculix")
         end select
         i0 = i + 1
      end do
   end subroutine parse_formats

   subroutine progress(message)
      character(len=*), intent(in) :: message
      if (.not. quiet) write (error_unit, '(a)') "egw-table: "//message
      flush (error_unit)
   end subroutine progress

   subroutine next_value(i, name, val)
      integer, intent(inout) :: i
      character(len=*), intent(in) :: name
      character(len=:), allocatable, intent(out) :: val
      if (i + 1 > command_argument_count()) call die(name//" needs a value (see --help)")
      i = i + 1
      call get_arg(i, val)
      ! another option where the value should be ("--flow-pressure --out d" said "'--out':
      ! not a number"); no number or path a user means starts with "--"
      if (len(val) >= 2) then
         if (val(1:2) == "--") call die(name//" needs a value, got the option "//val// &
            & " (see --help)")
      end if
   end subroutine next_value

   real(dp) function real_value(name, text) result(x)
      character(len=*), intent(in) :: name, text
      integer :: stat
      read (text, *, iostat=stat) x
      if (stat /= 0 .or. len_trim(text) == 0 .or. index(text, ",") > 0 .or. &
         & index(text, "/") > 0) call die(name//" = '"//text//"': not a number")
   end function real_value

   subroutine real_list(name, text, x)
      character(len=*), intent(in) :: name, text
      real(dp), intent(inout) :: x(:)
      integer :: i0, i, n
      n = 0
      i0 = 1
      do i = 1, len(text) + 1
         if (i <= len(text)) then
            if (text(i:i) /= ",") cycle
         end if
         n = n + 1
         if (n > size(x)) call die(name//": at most "//int_str(size(x))//" values")
         x(n) = real_value(name, text(i0:i - 1))
         i0 = i + 1
      end do
   end subroutine real_list

   subroutine real_pair(name, text, lo, hi)
      character(len=*), intent(in) :: name, text
      real(dp), intent(out) :: lo, hi
      real(dp) :: x(max_types)
      x = huge(1.0_dp)
      call real_list(name, text, x)
      if (x(2) == huge(1.0_dp) .or. x(3) /= huge(1.0_dp)) &
         & call die(name//" = '"//text//"': give two values MIN,MAX")
      lo = x(1)
      hi = x(2)
   end subroutine real_pair

   subroutine usage()
      character(len=*), parameter :: lines(*) = [character(len=92) :: &
         & "usage: egw-table [SCENE.nml] [options]", &
         & "", &
         & "Picks the cheapest model that meets the scene's force tolerance (Hertz closed", &
         & "form, one 1-D table, or the universal 2-D table) and writes its tables.", &
         & "Without arguments: the default scene, two 1 mm glass beads (E = 70 GPa,", &
         & "nu = 0.22), sigma = 1 um, mu = 4, E-GW, overlaps -2..20 sigma, tol = 1e-4.", &
         & "A namelist file (&scene ... /, see doc/scenes.md) changes the default scene;", &
         & "options override the file. Units: any consistent set (SI suggested: m, Pa,", &
         & "N); eta is per unit area, so eta*sigma*sqrt(R*beta) is dimensionless.", &
         & "", &
         & "Scene:", &
         & "  --model NAME            Hertz, GW, E-GW (default) or EP-GW", &
         & "  --flat-law FILE         a rough-flat law file (egw-topo, doc/formats.md 7) in", &
         & "                          place of the summit model: sigma = the law's length,", &
         & "                          one particle pair; writes its 1-D table", &
         & "  --radius R              one particle type of radius R [length]", &
         & "  --radii R1,R2,...       particle types (all type pairs are contacts; <= 8)", &
         & "  --radius-range MIN,MAX  continuous radius range (polydisperse, one material)", &
         & "  --modulus E1[,E2..]     Young's modulus per type [pressure]", &
         & "  --poisson NU1[,NU2..]   Poisson's ratio per type (a missing type: type 1's)", &
         & "  --effective-modulus E*  E* of every pair instead of modulus/poisson", &
         & "  --sigma S               combined summit-height std of a pair [length]", &
         & "  --sigma-range MIN,MAX   range of the combined sigma", &
         & "  --mu MU                 Greenwood-Tripp mu = (8/3) eta sigma sqrt(2 R beta)", &
         & "  --summit-density ETA    summits per area [1/length^2] (with --summit-radius:", &
         & "  --summit-radius BETA    mu per pair from eta, beta [length], sigma and R)", &
         & "  --psi PSI               plasticity index (EP-GW)", &
         & "  --K K                   ZMC hardness coefficient in (0, 1) (EP-GW)", &
         & "  --plastic-ratio RHO     ZMC delta_p/delta_ep > 1 (EP-GW)", &
         & "  --flow-pressure PY      bulk flow pressure p_y [pressure] of the cap, every", &
         & "                          model: writes the hysteresis table(s) (Hertz + cap, or", &
         & "                          the rough model + cap), no force table", &
         & "  --yield-stress Y        the same from the yield stress: p_y = 1.6 Y", &
         & "  --delta-min D, --delta-max D            overlap range [length]", &
         & "  --delta-min-sigma X, --delta-max-sigma X  overlap range in units of sigma", &
         & "  --tol TOL               force tolerance (relative), 1e-8 .. 0.1", &
         & "  --lammps-delta-max D    deepest overlap the LAMMPS table reaches [length]", &
         & "                          (default 2 x delta_max; LAMMPS stops beyond it)", &
         & "", &
         & "Output:", &
         & "  --formats LIST          of csv,binary,lammps,calculix (default: all that apply:", &
         & "                          CSV + binary for every table; LAMMPS pair_style table", &
         & "                          and CalculiX sphere + rough-flat curves for a 1-D table;", &
         & "                          with the universal table, lammps writes one section", &
         & "                          per particle-type pair from 1-D tables)", &
         & "  -o, --out DIR           output directory (default: out)", &
         & "  --choose-only           report the model choice, build and write nothing", &
         & "  -q, --quiet             no progress lines or bar on stderr", &
         & "  -h, --help              this text", &
         & "", &
         & "Invalid input: a message naming the parameter, exit status 2, no files."]
      integer :: i
      do i = 1, size(lines)
         write (output_unit, '(a)') trim(lines(i))
      end do
   end subroutine usage

   !> One line "egw-table: <message>" on stderr and exit status 2 (no runtime backtrace).
   subroutine die(message)
      character(len=*), intent(in) :: message
      write (error_unit, '(a)') "egw-table: "//message
      call exit_process(2)
   end subroutine die

   !> The options that take a value (the others are --help, --quiet, --choose-only).
   pure logical function takes_value(name)
      character(len=*), intent(in) :: name
      select case (name)
      case ("-o", "--out", "--formats", "--model", "--flat-law", "--radius", "--radii", &
         & "--radius-range", &
         & "--modulus", "--poisson", "--effective-modulus", "--sigma", "--sigma-range", &
         & "--mu", "--summit-density", "--summit-radius", "--psi", "--K", "--k", &
         & "--plastic-ratio", "--delta-min", "--delta-max", "--delta-min-sigma", &
         & "--delta-max-sigma", "--tol", "--lammps-delta-max", "--flow-pressure", &
         & "--yield-stress")
         takes_value = .true.
      case default
         takes_value = .false.
      end select
   end function takes_value

   subroutine get_arg(i, val)
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: val
      integer :: n
      call get_command_argument(i, length=n)
      allocate (character(len=n) :: val)
      call get_command_argument(i, val)
   end subroutine get_arg

   pure function either(cond, a, b) result(str)
      logical, intent(in) :: cond
      character(len=*), intent(in) :: a, b
      character(len=:), allocatable :: str
      if (cond) then
         str = a
      else
         str = b
      end if
   end function either

   !> Short form of a number for messages (4 significant digits).
   pure function num(x) result(str)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: str
      character(len=16) :: buf
      write (buf, '(es11.4)') x
      str = trim(adjustl(buf))
   end function num

end program egw_table_app
