# Two entry points: `make run` (the table generator) and `make test`.
# Both install missing tools first (tools/setup.sh).
FPM_FLAGS ?= --profile release
ARGS ?=

.PHONY: run test bench setup clean python
run: setup
	@fpm run egw-table $(FPM_FLAGS) -- $(ARGS)

# fpm test, then the Python and LAMMPS suites where installed; ends "total: N passed, N failed"
test: setup
	@OMP_NUM_THREADS=$${OMP_NUM_THREADS:-2} FPM_FLAGS="$(FPM_FLAGS)" sh tools/run_tests.sh

bench: setup
	@fpm run egw-bench $(FPM_FLAGS)

setup:
	@sh tools/setup.sh

# The Python package (python/) in the project venv .venv/, with numpy and pytest.
python: setup
	@[ -x .venv/bin/python ] || python3 -m venv .venv
	@.venv/bin/python -m pip install --quiet --disable-pip-version-check numpy pytest ./python
	@echo "python: egw $$(.venv/bin/python -c 'import egw; print(egw.version())') in .venv (.venv/bin/python, .venv/bin/egw-topo)"

clean:
	rm -rf build
