#!/bin/sh
# Command-line behaviour of egw-table (issue: a newcomer's path; reliability): every
# refusal is one line "egw-table: <message>" on stderr with exit status 2, no runtime
# "ERROR STOP" or backtrace, no files; unknown options are named as such; --sigma 0 gives
# the Hertz model; progress in a log is plain lines (no carriage returns).
# Usage: egw_table_cli.sh PATH/TO/egw-table   (prints failures; exit status = their number)
exe=$1
[ -x "$exe" ] || { echo "    egw-table not found at '$exe'"; exit 1; }
work=$(mktemp -d)
trap 'umount "$work/full" 2>/dev/null; rm -rf "$work"' EXIT
fails=0
fail() { echo "    CLI check failed: $*"; fails=$((fails + 1)); }

# refuse NAME EXPECTED_SUBSTRING ARGS...: exit 2, one stderr line starting "egw-table: "
# that contains EXPECTED_SUBSTRING, nothing written to the output directory
refuse() {
  name=$1 expect=$2
  shift 2
  out="$work/out_$name"
  "$exe" --out "$out" "$@" >"$work/stdout" 2>"$work/stderr"
  rc=$?
  [ "$rc" -eq 2 ] || fail "$name: exit status $rc, expected 2"
  lines=$(wc -l <"$work/stderr")
  [ "$lines" -eq 1 ] || fail "$name: $lines stderr lines, expected 1: $(cat "$work/stderr")"
  grep -q "^egw-table: " "$work/stderr" || fail "$name: stderr does not start 'egw-table: '"
  grep -qF -- "$expect" "$work/stderr" || fail "$name: stderr lacks '$expect': $(cat "$work/stderr")"
  if grep -qiE "error stop|backtrace|#0 " "$work/stderr"; then fail "$name: runtime trace"; fi
  if [ -d "$out" ] && [ -n "$(ls -A "$out")" ]; then fail "$name: files written: $(ls "$out")"; fi
}

refuse unknown "egw-table: unknown option --x (see --help)" --x
refuse unknown_with_value "unknown option --bogus" --bogus 3
refuse missing_value "--tol needs a value" --tol
refuse value_is_option "--flow-pressure needs a value, got the option --model" --flow-pressure --model E-GW
refuse not_a_number "--radius = 'abc': not a number" --radius abc
refuse bad_radius "radius" --radius -1e-3
refuse bad_tol "tol" --tol 2
refuse no_scene_file "nonexistent.nml" "$work/nonexistent.nml"
printf '&scene\n  no_such_variable = 1\n/\n' >"$work/bad.nml"
refuse bad_scene_variable "bad.nml" "$work/bad.nml"
printf '&scene\n  radius = -1.0\n/\n' >"$work/neg.nml"
refuse bad_scene_value "radius" "$work/neg.nml"
# the scene-file path refuses in one line too: a directory, an empty file, binary junk
mkdir -p "$work/scene_dir"
refuse scene_is_directory "scene_dir" "$work/scene_dir"
: >"$work/empty.nml"
refuse empty_scene "empty.nml" "$work/empty.nml"
printf 'PK\003\004\377\376&scene \001\002 = /\n\000\000' >"$work/junk.nml"
refuse junk_scene "junk.nml" "$work/junk.nml"

# a flat-law scene (--flat-law FILE, or flat_law = 'FILE' in a scene file): the law's
# table and the law itself written; its sigma is the law's length; refusals name the cause
printf 'u,pressure\n# length = 1e-6\n0,1e7\n3e-6,4.978706836786394e5\n' >"$work/law.csv"
"$exe" --flat-law "$work/law.csv" --out "$work/flat" >"$work/stdout" 2>"$work/stderr"
rc=$?
[ "$rc" -eq 0 ] || fail "--flat-law: exit status $rc: $(cat "$work/stderr")"
grep -q "model = 4 (flat law)" "$work/flat/scene_table.csv" ||
  fail "--flat-law: scene_table.csv is not the flat law's table"
[ -s "$work/flat/scene_flat_law.csv" ] || fail "--flat-law: scene_flat_law.csv not written"
grep -q "sigma = 1.0000E-06" "$work/stdout" || fail "--flat-law: sigma is not the law's length"
printf "&scene\n  flat_law = '%s'\n  radius = 2e-3\n/\n" "$work/law.csv" >"$work/flat.nml"
"$exe" "$work/flat.nml" --quiet --choose-only >"$work/stdout" 2>"$work/stderr" ||
  fail "flat_law in a scene file: $(cat "$work/stderr")"
grep -q "flat law" "$work/stdout" || fail "flat_law in a scene file: not a flat-law scene"
refuse flat_law_pairs "one pair" -q --flat-law "$work/law.csv" --radii 1e-3,2e-3
refuse flat_law_missing "nope.csv" --flat-law "$work/nope.csv"
printf 'u,pressure\n0,1\n1e-6,2\n' >"$work/rising.csv"
refuse flat_law_rising "p(2)" --flat-law "$work/rising.csv"
refuse flat_law_calculix "calculix" -q --flat-law "$work/law.csv" --formats calculix

# smooth spheres: sigma = 0 is the Hertz model, not an error
"$exe" --sigma 0 --quiet --out "$work/smooth" >"$work/stdout" 2>"$work/stderr"
rc=$?
[ "$rc" -eq 0 ] || fail "--sigma 0: exit status $rc: $(cat "$work/stderr")"
grep -q "Hertz" "$work/stdout" || fail "--sigma 0: no Hertz model in the summary"

# progress into a log: plain lines, no carriage returns, every line 'egw-table: ...'
"$exe" --out "$work/log" --formats csv --tol 1e-3 >"$work/stdout" 2>"$work/stderr"
rc=$?
[ "$rc" -eq 0 ] || fail "build: exit status $rc: $(cat "$work/stderr")"
if tr -d '\n' <"$work/stderr" | grep -q "$(printf '\r')"; then
  fail "progress in a log contains carriage returns"
fi
if grep -v "^egw-table: " "$work/stderr" | grep -q .; then
  fail "progress lines in a log: $(grep -v '^egw-table: ' "$work/stderr" | head -2)"
fi
grep -q "building" "$work/stderr" || fail "no progress line in the log"
[ -s "$work/log/scene_table.csv" ] || fail "build: no scene_table.csv"
# EP-GW with plastic summits: the hysteresis tables beside the loading table, in the
# formats asked for, the summary saying so and the LAMMPS/CalculiX files' loading-only note
"$exe" --out "$work/ep" --model EP-GW --psi 2 --formats csv,binary,lammps --tol 1e-2 \
  >"$work/stdout" 2>"$work/stderr"
rc=$?
[ "$rc" -eq 0 ] || fail "EP-GW: exit status $rc: $(cat "$work/stderr")"
for f in scene_hysteresis.csv scene_hysteresis.bin; do
  [ -s "$work/ep/$f" ] || fail "EP-GW: no $f"
done
head -2 "$work/ep/scene_hysteresis.csv" | grep -q "^# egw hysteresis table" ||
  fail "EP-GW: scene_hysteresis.csv has no egw header"
grep -q "^# fnv1a32 = " "$work/ep/scene_hysteresis.csv" || fail "EP-GW: CSV without checksum"
grep -q "hysteresis  *1 EP-GW table" "$work/stdout" || fail "EP-GW: summary lacks the hysteresis line"
grep -q "loading curve only" "$work/stdout" || fail "EP-GW: summary lacks the loading-only note"
grep -q "loading curve only" "$work/ep/scene_table.lammps" ||
  fail "EP-GW: LAMMPS file lacks the loading-only note"
if ls "$work/ep" | grep -q "part$"; then fail "EP-GW: .part files left"; fi

# on a terminal (a pseudo-terminal from util-linux's script, where available): the bar,
# redrawn in place
if command -v script >/dev/null 2>&1; then
  script -qec "'$exe' --out '$work/tty' --formats csv --tol 1e-3 >/dev/null" "$work/tty.log" \
    >/dev/null 2>&1 </dev/null
  # the bar starts each redraw with a carriage return and "  building [" (the plain log
  # lines start "egw-table: building"; the terminal itself turns every newline into \r\n)
  grep -q "$(printf '\r')  building \[" "$work/tty.log" || fail "no progress bar on a terminal"
else
  echo "    (script(1) missing: the terminal bar is not checked)"
fi

# failed writes (issue 13): a file-size limit (ulimit -f) below the files' sizes, and
# (as root, where a small tmpfs can be mounted) a full file system: exit status 2, one
# line naming the reason, the files of an earlier run unchanged, no temporary or .part
# file left behind
good="$work/good"
"$exe" --out "$good" --formats csv,binary --tol 1e-3 -q >/dev/null 2>&1 ||
  fail "build for the failed-write checks: exit status $?"
(cd "$good" && cksum ./* >"$work/good.sum")
# failed_write NAME EXPECTED_SUBSTRING DIR [ulimit -f BLOCKS]
failed_write() {
  name=$1 expect=$2 dir=$3 blocks=$4
  if [ -n "$blocks" ]; then
    (ulimit -f "$blocks" && exec "$exe" --out "$dir" --formats csv,binary --tol 1e-3 -q) \
      >"$work/stdout" 2>"$work/stderr"
  else
    "$exe" --out "$dir" --formats csv,binary --tol 1e-3 -q >"$work/stdout" 2>"$work/stderr"
  fi
  rc=$?
  [ "$rc" -eq 2 ] || fail "$name: exit status $rc, expected 2"
  [ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "$name: stderr is not one line: $(cat "$work/stderr")"
  grep -qF -- "$expect" "$work/stderr" || fail "$name: stderr lacks '$expect': $(cat "$work/stderr")"
  (cd "$dir" && cksum ./* | cmp -s - "$work/good.sum") || fail "$name: earlier files changed"
  if ls -a "$dir" | grep -qE 'egw-tmp|\.part$'; then fail "$name: left $(ls -a "$dir")"; fi
}
cp -r "$good" "$work/limited"
failed_write ulimit "ulimit -f" "$work/limited" 4
if [ "$(id -u)" -eq 0 ] && mkdir -p "$work/full" &&
  mount -t tmpfs -o size=64k tmpfs "$work/full" 2>/dev/null; then
  cp -r "$good" "$work/full/out"
  # fill the file system up (dd stops at ENOSPC)
  dd if=/dev/zero of="$work/full/filler" bs=1k count=64 2>/dev/null
  failed_write full_disk "No space left on device" "$work/full/out"
  umount "$work/full"
else
  echo "    (not root or no tmpfs mount: the full-disk check is skipped; ulimit -f checked)"
fi

# the flow-pressure cap (doc/theory.md 12): flow_pressure or yield_stress (p_y = 1.6 Y) for
# smooth spheres writes the Hertz + cap hysteresis table, for a rough model its hysteresis
# table with the cap; both given and negative values are refused naming the variable
smooth="--model Hertz --radius 1e-3 --modulus 200e9 --poisson 0.3 --delta-min 0 --delta-max 4e-7"
refuse cap_both "flow_pressure and yield_stress: give one" $smooth --flow-pressure 1e9 \
  --yield-stress 1e9
refuse cap_negative "flow_pressure = -1" $smooth --flow-pressure -1
refuse cap_negative_yield "yield_stress = -2" $smooth --yield-stress -2
# p_y = 1.6 Y above E* (115 GPa here) is refused naming the yield stress given, not p_y
refuse cap_yield_above_modulus "yield_stress = 1.000000000000000E+012: must lie below E*/1.6" \
  $smooth --yield-stress 1e12
printf '&scene\n  model = "Hertz"\n  yield_stress = 0.6e9\n  flow_pressure = 1e9\n/\n' \
  >"$work/cap_both.nml"
refuse cap_both_file "flow_pressure and yield_stress" "$work/cap_both.nml"
# two 1 mm steel beads, Y = 0.6 GPa: p_y = 0.96 GPa, delta_y = 9.4e-8 m; to 4 delta_y
printf '&scene\n  model = "Hertz"\n  radius = 1e-3\n  modulus = 200e9\n  poisson = 0.3\n%s\n/\n' \
  "  yield_stress = 0.6e9, delta_min = 0, delta_max = 4e-7, tol = 1e-2" >"$work/cap.nml"
"$exe" "$work/cap.nml" --out "$work/cap" -q >"$work/stdout" 2>"$work/stderr"
rc=$?
[ "$rc" -eq 0 ] || fail "cap scene: exit status $rc: $(cat "$work/stderr")"
grep -q "CSV format 5" "$work/cap/scene_hysteresis.csv" ||
  fail "cap scene: scene_hysteresis.csv is not a Hertz + cap table"
grep -q "^# flow_pressure = 9.600000000" "$work/cap/scene_hysteresis.csv" ||
  fail "cap scene: flow_pressure is not 1.6 yield_stress: $(grep flow "$work/cap/scene_hysteresis.csv")"
[ -s "$work/cap/scene_hysteresis.bin" ] || fail "cap scene: scene_hysteresis.bin not written"
grep -q "Hertz + cap" "$work/stdout" || fail "cap scene: summary does not name the cap"
# the summary gives the written table's tol and measured error, not only the Hertz choice's
# bound 0, which read as an exact table (audit29)
grep -q "^  error bound .*hysteresis table(s): tol = 1.0000E-02" "$work/stdout" ||
  fail "cap scene: the error bound does not give the table's tol: $(grep bound "$work/stdout")"
grep -q "^  measured error    [0-9].*Hertz + cap hysteresis build" "$work/stdout" ||
  fail "cap scene: no measured error of the hysteresis table: $(grep -c . "$work/stdout") lines"
# below first yield (delta_y ~ 100 sigma) an E-GW + cap table is reversible (max_error 0):
# the measured error printed is its loading table's, not 0 (lead, stop 63)
"$exe" --radius 810569.469138702 --effective-modulus 1 --sigma 1 --mu 4 --delta-min 0 \
  --delta-max 50 --tol 1e-2 -q --flow-pressure 0.01 --model E-GW --out "$work/rev" \
  >"$work/stdout" 2>"$work/stderr" || fail "reversible cap scene: $(cat "$work/stderr")"
grep -q "^# reversible = 1" "$work/rev/scene_hysteresis.csv" ||
  fail "reversible cap scene: the table is not reversible: $(grep reversible "$work/rev/scene_hysteresis.csv")"
if grep -q "^  measured error    0.0000E+00" "$work/stdout"; then
  fail "reversible cap scene: the measured error printed is 0"
fi
# --choose-only: no files, and the summary must not say the cap needs none
"$exe" "$work/cap.nml" --choose-only -q >"$work/stdout" 2>"$work/stderr" ||
  fail "cap scene --choose-only: $(cat "$work/stderr")"
if grep -q "no table needed" "$work/stdout"; then
  fail "cap scene --choose-only: says no table is needed: $(grep files "$work/stdout")"
fi
grep -q "Hertz + cap hysteresis table(s) not built" "$work/stdout" ||
  fail "cap scene --choose-only: the summary does not name the table a run would build"
# formats without the hysteresis table's (csv, binary): none written, and said why
"$exe" "$work/cap.nml" --formats lammps --out "$work/cap_lammps" -q >"$work/stdout" \
  2>"$work/stderr" || fail "cap scene --formats lammps: $(cat "$work/stderr")"
grep -q "hysteresis table(s) come in the csv and binary formats only" "$work/stdout" ||
  fail "cap scene --formats lammps: $(grep files "$work/stdout")"
# rough + cap at sigma/delta_y = 2e-5 (the normalised scene E* = 1, sigma = 1, mu 4, p_y =
# 0.01, two spheres of R 4.0528e8: delta_y = 5e4): to 12 delta_y (6e5 sigma, beyond the 2e5
# sigma such tables build to) refused before any solve, naming delta_max and the Hertz +
# cap route; GW + cap to 1e5 sigma fails in the model choice's solves, with their own
# message (doc/stability.md "Stop 51 (tiny17)"). The E-GW refusal needs tol 1e-5: the
# roughness changes the force by 2.5e-5 of P(delta_max) against Hertz + cap, so at 1e-3 the
# chooser takes Hertz and the Hertz + cap table is written (the route the refusal names)
tiny="--radius 4.0528473e8 --effective-modulus 1 --sigma 1 --mu 4 --flow-pressure 0.01 \
  --delta-min 0 -q"
refuse rough_cap_tiny_sigma "rough + cap tables beyond 2.000E+05 sigma at sigma/delta_y" \
  $tiny --tol 1e-5 --delta-max 6e5 --model E-GW
grep -qF "give sigma = 0 (or model Hertz) for the Hertz + cap table" "$work/stderr" ||
  fail "rough_cap_tiny_sigma: no Hertz + cap route: $(cat "$work/stderr")"
"$exe" $tiny --tol 1e-3 --delta-max 6e5 --model E-GW --out "$work/tiny_hertz" \
  >"$work/stdout" 2>"$work/stderr" ||
  fail "rough_cap_tiny_sigma at tol 1e-3: exit status $?: $(cat "$work/stderr")"
grep -q "CSV format 5" "$work/tiny_hertz/scene_hysteresis.csv" ||
  fail "rough_cap_tiny_sigma at tol 1e-3: not the Hertz + cap table"
refuse rough_cap_tiny_sigma_gw "Hertz check of parameter set 1 (delta = " $tiny \
  --tol 1e-3 --delta-max 1e5 --model GW
# the same beads, E-GW with sigma = 1 nm (delta_y/94), at tol 1e-3: the roughness changes
# the force by 3.0e-3 of P(delta_max) against Hertz + cap, so the rough model's table with
# the cap
"$exe" "$work/cap.nml" --model E-GW --sigma 1e-9 --mu 4 --delta-min -3e-9 --tol 1e-3 --out \
  "$work/rough_cap" -q >"$work/stdout" 2>"$work/stderr"
rc=$?
[ "$rc" -eq 0 ] || fail "rough cap scene: exit status $rc: $(cat "$work/stderr")"
# (E-GW + cap: elastic summits, turning points above 0: u on the two-piece s map, CSV
# format 6; format 4, the gap on it, before stop 66)
grep -q "CSV format 6" "$work/rough_cap/scene_hysteresis.csv" &&
  grep -q "^# sigma = 1.000000000" "$work/rough_cap/scene_hysteresis.csv" ||
  fail "rough cap scene: scene_hysteresis.csv is not a rough + cap table"
[ ! -e "$work/rough_cap/scene_table.csv" ] || fail "rough cap scene: a force table written"
grep -q "E-GW + cap" "$work/stdout" || fail "rough cap scene: summary does not name the cap"
# at the namelist's tol 1e-2 the chooser takes Hertz (3.0e-3 <= 1e-2): the Hertz + cap table,
# not the rough model's (a model no more than the scene needs; before stop 59 the E-GW +
# cap table was built whatever the choice, 4.6x the CPU)
"$exe" "$work/cap.nml" --model E-GW --sigma 1e-9 --mu 4 --delta-min -3e-9 --out \
  "$work/rough_cap_hertz" -q >"$work/stdout" 2>"$work/stderr" ||
  fail "rough cap scene, Hertz chosen: exit status $?: $(cat "$work/stderr")"
grep -q "model chosen *Hertz" "$work/stdout" ||
  fail "rough cap scene at tol 1e-2: Hertz not chosen: $(grep chosen "$work/stdout")"
grep -q "CSV format 5" "$work/rough_cap_hertz/scene_hysteresis.csv" ||
  fail "rough cap scene, Hertz chosen: scene_hysteresis.csv is not a Hertz + cap table"
grep -q "hysteresis *1 Hertz + cap" "$work/stdout" ||
  fail "rough cap scene, Hertz chosen: the summary does not name Hertz + cap: $(grep hysteresis "$work/stdout")"
# --help says so too (it said "(Hertz or sigma = 0)" while rough scenes take the cap)
"$exe" --help >"$work/help" 2>&1
grep -A2 -- "--flow-pressure" "$work/help" | grep -q "rough model + cap" ||
  fail "--help: --flow-pressure does not say rough models take the cap: $(grep -A1 -- "--flow-pressure" "$work/help")"

# psi with a model that ignores it: said (as Python's IgnoredParameterWarning, LAMMPS's
# WARNING), not silently dropped (before audit22 nothing was said)
"$exe" --psi 1 --choose-only -q >"$work/stdout" 2>"$work/stderr" ||
  fail "--psi 1 with E-GW: exit status $?: $(cat "$work/stderr")"
grep -qF "note: psi = 1.0000E+00 is EP-GW's plasticity index: model E-GW ignores it" \
  "$work/stdout" || fail "--psi 1 with E-GW: no note: $(cat "$work/stdout")"
"$exe" --psi 1 --model EP-GW --choose-only -q >"$work/stdout" 2>"$work/stderr"
if grep -q "note: psi" "$work/stdout"; then fail "EP-GW: psi noted as ignored"; fi

# the output directory is made without a shell: a quote in its name is a name (before
# audit22 "mkdir -p '...'" failed on it), and one that cannot be made is one line
"$exe" --out "$work/Bob's runs" --choose-only -q >/dev/null 2>"$work/stderr" &&
  "$exe" --out "$work/Bob's runs" --tol 1e-3 -q >/dev/null 2>>"$work/stderr" ||
  fail "--out with a quote: exit status $?: $(cat "$work/stderr")"
[ -s "$work/Bob's runs/scene_table.csv" ] || fail "--out with a quote: no scene_table.csv"
refuse out_not_creatable "cannot create the directory" -q --tol 1e-3 --out /proc/egw_no_such_dir

echo "    $fails CLI check(s) failed"
exit "$fails"
