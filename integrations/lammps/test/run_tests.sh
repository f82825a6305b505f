#!/bin/sh
# The LAMMPS plugin's tests (after `make lammps`); `make test` runs this when
# build/lammps/egwplugin.so exists. Ends with "N passed, N failed"; non-zero exit on failure.
cd "$(dirname "$0")" || exit 1
exec python3 run_tests.py "$@"
