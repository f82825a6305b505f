#!/bin/sh
# The README's test command (`make test`) runs this: the Fortran and C suites (fpm test),
# then, when the project venv has them, the Python package's tests (pytest, after
# `make python`) and the LAMMPS plugin's tests (after `make lammps`). Each suite prints its
# own results; the last line adds them up as "total: N passed, N failed". Exit status 0
# only if every suite that ran passed.
# Environment: FPM (fpm command), FPM_FLAGS, VENV (default .venv).
FPM=${FPM:-${VENV:-.venv}/bin/fpm}
FPM_FLAGS=${FPM_FLAGS:---profile release}
VENV=${VENV:-.venv}
log=$(mktemp)
trap 'rm -f "$log"' EXIT
passed=0
failed=0
status=0

# add the "N passed, N failed" (test-drive) or pytest "N passed, N failed" counts of $log
count() {
  p=$(grep -Eo '[0-9]+ passed' "$log" | tail -n 1 | grep -Eo '[0-9]+')
  f=$(grep -Eo '[0-9]+ failed' "$log" | tail -n 1 | grep -Eo '[0-9]+')
  e=$(grep -Eo '[0-9]+ errors?' "$log" | tail -n 1 | grep -Eo '[0-9]+')
  passed=$((passed + ${p:-0}))
  failed=$((failed + ${f:-0} + ${e:-0}))
}

echo "=== Fortran and C suites (fpm test)"
# shellcheck disable=SC2086
{ $FPM test $FPM_FLAGS 2>&1; echo $? >"$log.rc"; } | tee "$log"
[ "$(cat "$log.rc")" -eq 0 ] || status=1
count

if [ -x "$VENV/bin/python" ] && "$VENV/bin/python" -c "import egw, pytest" 2>/dev/null; then
  echo "=== Python package (pytest python/tests)"
  { "$VENV/bin/python" -m pytest -q -p no:cacheprovider python/tests 2>&1; echo $? >"$log.rc"; } |
    tee "$log"
  [ "$(cat "$log.rc")" -eq 0 ] || status=1
  count
else
  echo "=== Python package: skipped (run 'make python' to install it into $VENV)"
fi

if [ -x integrations/lammps/test/run_tests.sh ] && [ -f build/lammps/egwplugin.so ]; then
  echo "=== LAMMPS plugin (integrations/lammps/test/run_tests.sh)"
  { integrations/lammps/test/run_tests.sh 2>&1; echo $? >"$log.rc"; } | tee "$log"
  [ "$(cat "$log.rc")" -eq 0 ] || status=1
  count
else
  echo "=== LAMMPS plugin: skipped (run 'make lammps' to build it)"
fi
rm -f "$log.rc"
[ "$failed" -eq 0 ] || status=1
echo "total: $passed passed, $failed failed"
exit $status
