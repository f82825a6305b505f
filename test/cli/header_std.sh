#!/bin/sh
# include/egw.h compiles without a warning as C89, C99, C11 (cc) and as C++98, C++11,
# C++17 (c++, where one is installed) under -pedantic -Wall -Wextra -Werror, in a unit
# that calls its inline (egw_hysteresis_eval_cached, C99 and C++ only) and a library
# function (audit23: g++ -std=c++98 -pedantic warned on long long in egw_piece_exp_).
# Usage: header_std.sh [INCLUDE_DIR]   (prints failures; exit status = their number)
inc=${1:-include}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
cat >"$work/use.c" <<'SRC'
#include "egw.h"
int main(void)
{
  double state[EGW_HYSTERESIS_STATE_SIZE] = {0.0};
  double force = 0.0, stiffness = 0.0;
  int served = 0;
  (void)state;
#if defined(__cplusplus) || (defined(__STDC_VERSION__) && __STDC_VERSION__ >= 199901L)
  served = egw_hysteresis_eval_cached(1.0, 0.5, state, &force, &stiffness);
#endif
  return served + (int)force + (int)stiffness + (int)sizeof(egw_params);
}
SRC
cp "$work/use.c" "$work/use.cpp"
# check COMPILER STD SOURCE: compile only (no library needed), every warning an error
check() {
  if ! "$1" -std="$2" -pedantic -Wall -Wextra -Werror -I"$inc" -c "$3" -o "$work/use.o" \
    >"$work/log" 2>&1; then
    echo "    egw.h check failed: $1 -std=$2 -pedantic -Wall -Wextra -Werror:"
    sed 's/^/      /' "$work/log" | head -n 8
    fails=$((fails + 1))
  fi
}
CC=${CC:-cc}
CXX=${CXX:-c++}
for std in c89 c99 c11; do check "$CC" "$std" "$work/use.c"; done
if command -v "$CXX" >/dev/null 2>&1; then
  for std in c++98 c++11 c++17; do check "$CXX" "$std" "$work/use.cpp"; done
else
  echo "    (no C++ compiler '$CXX': the C++ checks are skipped)"
fi
exit $fails
