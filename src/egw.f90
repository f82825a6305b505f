!> egw: extended Greenwood-Williamson contact of rough spheres (Zhao & Feng 2018).
!> `use egw` gives a Fortran user the public API: parameters, options and results, model
!> and status constants with egw_error, the solves, restitution, force and hysteresis
!> tables with their files, scenes, rough-flat laws (tabulated, Persson's, the BEM's),
!> and dp. Internals (mesh, kernels, pi, unset, ...) stay in their modules and in egw_all
!> (src/egw_all.f90); the C API is include/egw.h.
module egw
   use egw_kinds, only: dp
   use egw_version, only: egw_version_string, egw_version_number, get_egw_version
   use egw_status, only: egw_error, status_message, egw_ok, egw_invalid_argument, &
      & egw_invalid_parameter, egw_not_converged, egw_io_error, egw_bad_file, &
      & egw_out_of_memory, egw_null_pointer, egw_out_of_range, egw_unsupported
   use egw_params, only: contact_params, model_hertz, model_gw, model_egw, model_epgw, &
      & model_flat_law, validate_params, model_name, mu_from_summits, psi_from_hardness
   use egw_flat_law, only: flat_law, table_flat_law, new_table_law
   use egw_flat_persson, only: persson_options, self_affine_psd, persson_flat_curve
   use egw_flat_bem, only: bem_options, bem_state, bem_result, bem_solve_load, &
      & bem_solve_gap, bem_flat_curve, bem_state_release
   use egw_gauss, only: gauss_integral, gauss_integral_deriv, get_gauss_integral, &
      & get_gauss_integral_deriv, zmc_integrals
   use egw_ellip, only: ellipk, ellipe, ellipk_comp, ellipe_comp, get_ellipk, get_ellipe
   use egw_asperity, only: hertz_asperity_force, zmc_asperity_force, rough_flat_law, &
      & flat_pressure
   use egw_unloading, only: asperity_load_force, asperity_contact_area, &
      & asperity_residual_interference, asperity_unload_force, rough_flat_unload_law, &
      & flat_pressure_unload
   use egw_smooth_sphere, only: hertz_contact, hertz_force, hertz_stiffness, &
      & hertz_contact_radius, hertz_energy, hertz_pressure, hertz_deflection, hertz_gap
   use egw_rough_sphere, only: solver_options, solve_result, method_auto, method_newton, &
      & method_picard, validate_options, solve_contact, loading_history, &
      & load_history, solve_unload, solve_contact_unload, solve_contact_law, &
      & unload_start
   use egw_rough_profile, only: contact_profile, contact_profile_unload, unload_profile
   use egw_impact, only: restitution, time_step
   use egw_progress, only: progress_hook, set_progress, progress_count
   use egw_table, only: force_table, build_table, build_table_law, table_eval, &
      & table_eval_all, table_covers, table_energy, table_contact_radius, table_set_radii
   use egw_table_universal, only: universal_table, build_universal, universal_eval, &
      & universal_slice
   use egw_table_format, only: format_csv, format_binary, format_lammps, format_calculix, &
      & write_table, read_table, write_universal, read_universal, write_lammps, &
      & write_calculix_flat, write_calculix_sphere
   use egw_hysteresis, only: hysteresis_table, hysteresis_state_size, build_hysteresis, &
      & hysteresis_eval, hysteresis_eval_state, hysteresis_state_init, hysteresis_energy, &
      & hysteresis_energy_walk
   use egw_hysteresis_format, only: write_hysteresis, read_hysteresis
   use egw_flat_law_format, only: write_flat_law, read_flat_law
   use egw_scene, only: scene_input, scene_overrides, contact_scene, model_choice, &
      & scene_tables, max_types, choice_hertz, choice_table, choice_universal, choice_name, &
      & default_scene_input, read_scene_file, apply_scene_overrides, validate_scene_input, &
      & resolve_scene, choose_model, build_scene_tables
   use egw_impact_regime, only: impact_regime, classify_impact, first_yield_overlap, &
      & first_yield_speed
   use egw_io, only: write_file, open_temporary, commit_temporary, discard_temporary
   use egw_cache, only: cache_directory, build_table_cached, build_universal_cached, &
      & build_hysteresis_cached
   implicit none
   public
end module egw
