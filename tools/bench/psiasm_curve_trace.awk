# Sums the per-curve lines of tools/bench/psiasm_curve_trace.patch (stderr "TRC curve
# CHECK m solves s_nodes cpu meshes lus evals sum_n sum_n*ng sum_n^3 sum_ng zu_pieces
# zu_integral", "TRC verify m ...") by kind (check, node, verify) and turning-point
# region (m < 0, 0 <= m < M_Y, m >= M_Y; M_Y defaults to 98.3, README's scene's first
# yield of the rough contact): curves, solves, CPU (one thread), meshes, LU factorizations
# and Newton evaluations a solve, nodes a mesh, n*ng and n^3 a solve, Z_u's calls a solve
# answered by the tabulated pieces and by the integral, microseconds a solve.
# usage: awk [-v M_Y=98.3] -f psiasm_curve_trace.awk trace.log
BEGIN { if (M_Y == "") M_Y = 98.3 }
/^TRC/ {
  if ($2 == "curve") { kind = ($3 == "T") ? "check" : "node"; o = 4 } else { kind = "verify"; o = 3 }
  mm = $(o); reg = (mm < 0) ? "a:m<0" : (mm < M_Y ? "b:0<=m<M_Y" : "c:m>=M_Y"); k = reg " " kind
  C[k]++; S[k] += $(o+1); T[k] += $(o+3); M[k] += $(o+4); L[k] += $(o+5); E[k] += $(o+6)
  N[k] += $(o+7); NNG[k] += $(o+8); N3[k] += $(o+9); ZP[k] += $(o+11); ZI[k] += $(o+12)
}
END {
  printf "%-18s %5s %6s %7s %6s %5s %6s %6s %8s %9s %7s %7s %8s\n", "group", "crv", "solves", \
    "cpu_s", "mesh/s", "lu/s", "ev/s", "n/mesh", "nng/s", "n3/s(1e6)", "zuP/s", "zuI/s", "us/solve"
  for (k in C) printf "%-18s %5d %6d %7.3f %6.2f %5.2f %6.2f %6.1f %8.0f %9.2f %7.0f %7.0f %8.0f\n", \
    k, C[k], S[k], T[k], M[k]/S[k], L[k]/S[k], E[k]/S[k], N[k]/M[k], NNG[k]/S[k], \
    N3[k]/S[k]/1e6, ZP[k]/S[k], ZI[k]/S[k], 1e6*T[k]/S[k]
}
