# Two entry points: `make run` (the table generator) and `make test`.
# Both install missing tools first (tools/setup.sh): gfortran and LAPACK from Debian, fpm
# into the project venv .venv/ (VENV), which other targets (python, lammps, docs) share.
FPM_FLAGS ?= --profile release
ARGS ?=
VENV ?= .venv
FPM := $(VENV)/bin/fpm
export VENV

.PHONY: run test bench setup clean python docs fuzz
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

# The C API fuzz harness in full (tools/fuzz/egw_fuzz.c, doc/fuzz.md): ~6600 forked calls
# with NaN, Inf, 0, +-1e300, 1e-300, subnormals and extreme integers (and pairs of
# extreme scales); prints the counts
# tried / refused / accepted / silent / clobbered / crashed / hung (a few minutes).
# FUZZ_ARGS: e.g. "-j 4 -t 20" or "-f egw_solve -v".
FUZZ_ARGS ?=
fuzz: setup
	@$(FPM) build $(FPM_FLAGS) >/dev/null
	@$(FPM) run egw-fuzz $(FPM_FLAGS) -- $(FUZZ_ARGS)
