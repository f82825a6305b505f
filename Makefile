# Two entry points: `make run` (the table generator) and `make test`.
# Both install missing tools first (tools/setup.sh): gfortran and LAPACK from Debian, fpm
# into the project venv .venv/ (VENV), which other targets (python, lammps, docs) share.
FPM_FLAGS ?= --profile release
ARGS ?=
VENV ?= .venv
FPM := $(VENV)/bin/fpm
export VENV

.PHONY: run test bench setup clean
run: setup
	@$(FPM) run egw-table $(FPM_FLAGS) -- $(ARGS)

test: setup
	@OMP_NUM_THREADS=$${OMP_NUM_THREADS:-2} $(FPM) test $(FPM_FLAGS)

bench: setup
	@$(FPM) run egw-bench $(FPM_FLAGS)

setup:
	@sh tools/setup.sh

clean:
	rm -rf build
