#!/bin/sh
# Install what egw needs if it is missing: gfortran and LAPACK/BLAS from Debian,
# fpm 0.12 from PyPI. Silent and quick when everything is already there.
set -e
need_apt=""
command -v gfortran >/dev/null 2>&1 || need_apt="$need_apt gfortran"
have_lapack=no
for lib in /usr/lib/liblapack.so /usr/lib/*/liblapack.so; do
  [ -e "$lib" ] && have_lapack=yes
done
[ "$have_lapack" = yes ] || need_apt="$need_apt liblapack-dev"
if [ -n "$need_apt" ]; then
  echo "setup: installing$need_apt from Debian" >&2
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq >/dev/null
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $need_apt >/dev/null
fi
if ! command -v fpm >/dev/null 2>&1 || ! fpm --version 2>/dev/null | grep -q "0\.12\."; then
  echo "setup: installing fpm 0.12 from PyPI" >&2
  PY=python3
  command -v "$PY" >/dev/null 2>&1 || PY=python
  PIP_ROOT_USER_ACTION=ignore "$PY" -m pip install --quiet --disable-pip-version-check "fpm==0.12.*"
  hash -r 2>/dev/null || true
  if ! command -v fpm >/dev/null 2>&1; then
    echo "setup: fpm installed but not on PATH; add $("$PY" -m site --user-base)/bin" >&2
    exit 1
  fi
fi
