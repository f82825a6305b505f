#!/bin/sh
# The README's test command (`make test`) runs this: the Fortran and C suites (fpm test),
# the layer check of src/egw (tools/check_layers.py),
# then, when the project venv has them, the Python package's tests (pytest; `make test`
# installs the package first) and the LAMMPS plugin's tests (after `make lammps`). Each suite prints its
# own results; the last line adds them up as "total: N passed, N failed" (a suite that
# crashes counts as one failure). Exit status 0 only if every suite that ran passed.
# Environment: FPM (fpm command), FPM_FLAGS, VENV (default .venv).
VENV=${VENV:-.venv}
FPM=${FPM:-$VENV/bin/fpm}
FPM_FLAGS=${FPM_FLAGS:---profile release}
log=$(mktemp)
# the builds' on-disk cache (egw_cache) in a fresh directory of this run: no suite reads
# an entry of an earlier run or writes under $HOME
EGW_CACHE_DIR=$(mktemp -d)
export EGW_CACHE_DIR
trap 'rm -f "$log" "$log.rc"; rm -rf "$EGW_CACHE_DIR"' EXIT
passed=0
failed=0
status=0

# suite TITLE COMMAND...: run it, show its output, add its "N passed" / "N failed" /
# "N error(s)" counts (test-drive and pytest both print them)
suite() {
  echo "=== $1"
  shift
  { "$@" 2>&1; echo $? >"$log.rc"; } | tee "$log"
  p=$(grep -Eo '[0-9]+ passed' "$log" | tail -n 1 | grep -Eo '[0-9]+')
  f=$(grep -Eo '[0-9]+ failed' "$log" | tail -n 1 | grep -Eo '[0-9]+')
  e=$(grep -Eo '[0-9]+ errors?' "$log" | tail -n 1 | grep -Eo '[0-9]+')
  f=$((${f:-0} + ${e:-0}))
  passed=$((passed + ${p:-0}))
  failed=$((failed + f))
  if [ "$(cat "$log.rc")" -ne 0 ]; then
    status=1
    [ "$f" -gt 0 ] || failed=$((failed + 1))
  fi
}

# fpm 0.12 relinks a program only when its own sources change, not when the library
# it links did (built by an earlier fpm call): drop the linked programs so that they are
# linked again against the current library (seconds)
find build -type f -perm -u+x \( -path 'build/gfortran_*/app/*' -o \
  -path 'build/gfortran_*/test/*' -o -path 'build/gfortran_*/example/*' \) \
  -exec rm -f {} + 2>/dev/null
# the programs too: the cli suite runs the egw-table built beside the tester
# shellcheck disable=SC2086
$FPM build $FPM_FLAGS >/dev/null 2>&1 || $FPM build $FPM_FLAGS || status=1
# shellcheck disable=SC2086
suite "Fortran and C suites (fpm test)" $FPM test $FPM_FLAGS

# the use arrows between the layers of src/egw point one way (doc/architecture.md)
suite "Layers of src/egw (tools/check_layers.py)" python3 tools/check_layers.py --self-test

if [ -x "$VENV/bin/python" ] && "$VENV/bin/python" -c "import egw, pytest" 2>/dev/null; then
  suite "Python package (pytest python/tests)" \
    "$VENV/bin/python" -m pytest -q -p no:cacheprovider python/tests
else
  echo "=== Python package: skipped (run 'make python' to install it into $VENV)"
fi

if [ -x integrations/lammps/test/run_tests.sh ] && [ -f build/lammps/egwplugin.so ]; then
  suite "LAMMPS plugin (integrations/lammps/test/run_tests.sh)" \
    integrations/lammps/test/run_tests.sh
else
  echo "=== LAMMPS plugin: skipped (run 'make lammps' to build it)"
fi
[ "$failed" -eq 0 ] || status=1
echo "total: $passed passed, $failed failed"
exit $status
