# Two entry points: `make run` (the table generator) and `make test`.
# Both install missing tools first (tools/setup.sh).
FPM_FLAGS ?= --profile release
ARGS ?=

.PHONY: run test bench setup clean
run: setup
	@fpm run egw-table $(FPM_FLAGS) -- $(ARGS)

test: setup
	@OMP_NUM_THREADS=$${OMP_NUM_THREADS:-2} fpm test $(FPM_FLAGS)

bench: setup
	@fpm run egw-bench $(FPM_FLAGS)

setup:
	@sh tools/setup.sh

clean:
	rm -rf build
