#!/usr/bin/env python3
"""Tests of pair_style egw (the LAMMPS plugin), run through build/lammps/lmp.

Each test runs small LAMMPS decks (collision.in, pile.in) and checks a number against an
independent reference: the library's egw_restitution (build/lammps/egw-restitution),
LAMMPS's own pair_style granular (hertz/material, coeff_restitution, mindlin), energy
conservation, or the same deck on another rank count / after a restart.  Prints one line
per test and ends with "N passed, N failed"; exit status 1 if any failed.
Usage: run_tests.py [NAME ...]  (default: all)
"""
import sys

from lmp_common import *  # noqa: F401,F403
from suite_pair import *  # noqa: F401,F403
from suite_walls import *  # noqa: F401,F403
from suite_decks import *  # noqa: F401,F403
from suite_laws import *  # noqa: F401,F403
from suite_cap import *  # noqa: F401,F403


TESTS = [test_energy_elastic, test_flat_law_file, test_epgw_restitution, test_restitution_tool_args, test_slow_impacts, test_energy_epgw, test_single_pair_local, test_summit_data_restitution, test_unequal_radii_summit, test_hertz_damping_vs_granular,
         test_oblique_friction_vs_granular, test_sigma_to_zero_vs_granular,
         test_submodels_vs_granular, test_twisting_pair_vs_granular, test_submodels_ranks_agree, test_pair_local_granular_columns, test_heat_vs_granular,
         test_heat_flow_needs_model, test_pair_write, test_overlap_beyond_tables, test_not_finite_force,
         test_rmin_rmax_strict, test_pour_uses_both_ranks, test_wall_restitution, test_wall_material_contact, test_wall_sink_through, test_wall_bounces_start_afresh,
         test_wall_rolling_vs_wall_gran, test_wall_restart_and_ranks,
         test_bad_wall, test_wall_region, test_drum_example,
         test_wall_heat_vs_wall_gran, test_wall_temperature_variable, test_default_damping_vs_granular,
         test_ignored_keywords_warn, test_collision_example, test_wall_curvature_vs_wall_gran,
         test_wall_curvature_summit, test_wall_contacts_vs_wall_gran, test_granular_decks, test_lammps_decks_converted,
         test_column_vs_granular, test_peratom_energy_virial, test_pile_vs_granular, test_ranks_agree,
         test_reneighbor_keeps_history, test_size_list_reaches_tail, test_restart_keeps_history, test_bad_coeff,
         test_flat_law_vs_solve, test_flat_law_energy, test_flat_law_mixing, test_lnmu_error_estimate, test_inline_law, test_normalised_table_scaling, test_pour_tables_shared,
         test_cap_pair_restitution, test_cap_pair_beyond_40, test_cap_continuation, test_cap_wall_restitution, test_cap_wall_material_contact,
         test_bad_flow_pressure, test_rough_cap_tiny_sigma,
         test_cap_restart, test_cap_energy, test_rough_cap_pair_restitution,
         test_rough_cap_wall_restitution, test_rough_cap_wall_rim, test_rough_cap_restart,
         test_rough_cap_polydisperse]


def main():
    want = sys.argv[1:]
    passed = failed = 0
    for t in TESTS:
        name = t.__name__[5:]
        if want and name not in want:
            continue
        try:
            ok, msg = t()
        except Exception as exc:    # a crash of a deck or a missing RESULT is a failure
            ok, msg = False, f"exception: {exc}"
        print(f"{'PASS' if ok else 'FAIL'} {name}: {msg}", flush=True)
        passed += ok
        failed += not ok
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
