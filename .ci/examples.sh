#!/usr/bin/env bash
# CI: build and install egw with CMake, link the examples against the installed package
# (CMake find_package and pkg-config, shared and static) and run every example; each checks
# its own result. Installs what is missing (cmake, pkg-config, LAMMPS, CalculiX) with apt.
# Runs every step, prints a summary and exits non-zero if any step failed.
# Usage: .ci/examples.sh [work dir]   (default: a temporary directory, removed at the end)
set -uo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}
sh tools/setup.sh || exit 1
export PATH="$root/${VENV:-.venv}/bin:$PATH"  # fpm from the project venv
FPM_FLAGS=${FPM_FLAGS:---profile release}

# --- tools ------------------------------------------------------------------------------
missing=()
command -v cmake >/dev/null || missing+=(cmake)
command -v pkg-config >/dev/null || missing+=(pkg-config)
command -v lmp >/dev/null || missing+=(lammps)
command -v ccx >/dev/null || missing+=(calculix-ccx)
if ((${#missing[@]})); then
  echo "examples: installing ${missing[*]}"
  sudo=""
  if [ "$(id -u)" != 0 ] && command -v sudo >/dev/null; then sudo="sudo"; fi
  $sudo apt-get update -qq &&
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
      "${missing[@]}" >/dev/null || echo "examples: apt-get failed; steps needing it will fail"
fi

if [ $# -ge 1 ]; then
  work=$1
  mkdir -p "$work"
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
prefix=$work/prefix
failed=()
summary=()

# step NAME COMMAND...: run, time, record
step() {
  local name=$1 t0 rc
  shift
  echo "=== $name"
  t0=$(date +%s)
  "$@"
  rc=$?
  summary+=("$(printf '%-40s %s %4ss' "$name" "$([ $rc = 0 ] && echo ok || echo FAILED)" \
    $(($(date +%s) - t0)))")
  [ $rc = 0 ] || failed+=("$name")
  return 0
}

# --- the library: CMake build and install -----------------------------------------------
step "cmake: configure, build, install" sh -c "
  cmake -S '$root' -B '$work/build' -DCMAKE_INSTALL_PREFIX='$prefix' >'$work/cmake.log' &&
  cmake --build '$work/build' -j 2 >>'$work/cmake.log' &&
  cmake --install '$work/build' >>'$work/cmake.log' || { tail -40 '$work/cmake.log'; exit 1; }"

# a shared library that asks for an executable stack (gfortran's trampolines for an internal
# procedure passed as an argument) is refused by dlopen on newer glibc: LAMMPS could not load
# the plugin, Python not the package
step "libegw.so: no executable stack" sh -c "
  lib=\$(find '$prefix' -name 'libegw.so*' -type f | head -n 1) && test -n \"\$lib\" &&
  readelf -lW \"\$lib\" | grep GNU_STACK | grep -qv RWE"

step "egw-table: installed, runs from the prefix (rpath), no LD_LIBRARY_PATH" sh -c "
  env -i PATH=/usr/bin:/bin '$prefix/bin/egw-table' --quiet --formats csv --out '$work/installed_out' \
    >/dev/null && test -s '$work/installed_out/scene_table.csv'"

# --- C and Fortran DEM examples against the installed package ---------------------------
for lang in c fortran; do
  for st in OFF ON; do
    kind=$([ $st = ON ] && echo static || echo shared)
    step "dem_$lang: CMake find_package, $kind" sh -c "
      cmake -S '$root/example/dem_$lang' -B '$work/dem_${lang}_$kind' \
        -DCMAKE_PREFIX_PATH='$prefix' -DEGW_STATIC=$st >/dev/null &&
      cmake --build '$work/dem_${lang}_$kind' >/dev/null && '$work/dem_${lang}_$kind/dem_$lang'"
  done
done
export PKG_CONFIG_PATH=$prefix/lib/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}
libdir=$(pkg-config --variable=libdir egw 2>/dev/null)
step "dem_c: pkg-config egw (shared)" sh -c "
  cc -O2 -o '$work/dem_c_pc' '$root/example/dem_c/dem_c.c' \$(pkg-config --cflags --libs egw) \
    -lm -Wl,-rpath,'$libdir' && '$work/dem_c_pc'"
step "dem_c: pkg-config egw-static" sh -c "
  cc -O2 -o '$work/dem_c_pcs' '$root/example/dem_c/dem_c.c' \
    \$(pkg-config --cflags --libs egw-static) -lm && '$work/dem_c_pcs'"
if command -v c++ >/dev/null; then
  step "dem_c compiled as C++: pkg-config egw" sh -c "
    c++ -x c++ -O2 -o '$work/dem_cxx_pc' '$root/example/dem_c/dem_c.c' \
      \$(pkg-config --cflags --libs egw) -Wl,-rpath,'$libdir' && '$work/dem_cxx_pc'"
fi
step "dem_fortran: pkg-config egw (shared)" sh -c "
  gfortran -O2 -o '$work/dem_f_pc' '$root/example/dem_fortran/dem_fortran.f90' \
    \$(pkg-config --cflags --libs egw) -Wl,-rpath,'$libdir' && '$work/dem_f_pc'"
step "dem_fortran: pkg-config egw-static" sh -c "
  gfortran -O2 -o '$work/dem_f_pcs' '$root/example/dem_fortran/dem_fortran.f90' \
    \$(pkg-config --cflags --libs egw-static) && '$work/dem_f_pcs'"
step "dem_fortran: fpm example" fpm run --example dem-fortran $FPM_FLAGS

# --- LAMMPS and CalculiX ------------------------------------------------------------------
step "lammps: pair_style table, Hertz and E-GW" sh -c "
  fpm run --example lammps-tables $FPM_FLAGS -- '$work/egw_pair.table' &&
  python3 '$root/example/lammps/run.py' '$work/egw_pair.table' lmp"
step "calculix: rough flat, p_G" sh -c "
  fpm run --example calculix-flat $FPM_FLAGS -- '$work/flat.inc' &&
  python3 '$root/example/calculix/run.py' '$work/flat.inc' ccx"

# egw-table's own CalculiX output in a real ccx: the block of example/calculix on the
# scene_flat.inp that egw-table writes for the same surface (mm, N, MPa; E* of steel on a
# rigid base, eta = 500 /mm^2, beta = 0.05 mm, sigma = 1 um; R = 1 mm: p_G depends on
# mu/sqrt(R) only)
step "calculix: egw-table's scene_flat.inp in ccx" sh -c "
  fpm run egw-table $FPM_FLAGS -- --quiet --radius 2 --effective-modulus 230769.23076923077 \
    --sigma 1e-3 --summit-density 500 --summit-radius 0.05 --delta-min -0.002 \
    --delta-max 1e-3 --tol 1e-3 --formats calculix --out '$work/ccx_scene' >/dev/null &&
  python3 '$root/example/calculix/run.py' '$work/ccx_scene/scene_flat.inp' ccx"

# ... and a sphere on a plane: an elastic steel sphere (R = 2 mm) on a rigid plane through
# egw-table's scene_flat.inp; the contact force against egw-table's own classic-GW table
step "calculix: sphere on a plane, egw-table's outputs" sh -c "
  fpm run egw-table $FPM_FLAGS -- --quiet --model GW --radius 4 \
    --effective-modulus 230769.23076923077 --sigma 1e-3 --summit-density 500 \
    --summit-radius 0.05 --delta-min -0.003 --delta-max 0.006 --tol 1e-4 \
    --formats csv,calculix --out '$work/ccx_sphere' >/dev/null &&
  python3 '$root/example/calculix/sphere.py' '$work/ccx_sphere/scene_flat.inp' \
    '$work/ccx_sphere/scene_table.csv' ccx"

echo "=== examples summary"
printf '%s\n' "${summary[@]}"
if ((${#failed[@]})); then
  echo "examples: ${#failed[@]} FAILED: ${failed[*]}"
  exit 1
fi
echo "examples: all passed"
