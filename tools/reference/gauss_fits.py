#!/usr/bin/env python3
"""Generate src/egw/kernels/gauss_fits.f90: piecewise Chebyshev fits of the Gaussian asperity
integrals F_n(h) = int_h^inf (s-h)^n phi(s) ds for n in {-1/2, 0, 1/2, 1, 3/2, 5/2}.

h >= 0 : fit G_n(h) = F_n(h)/phi(h)  (smooth, ~ Gamma(n+1)/h^(n+1)); the caller multiplies
         by phi(h) formed without cancellation.
-12 <= h < 0 : fit F_n(h) itself (entire, grows like |h|^n).
Values come from mpmath at 50 digits through the parabolic cylinder function
F_n(h) = Gamma(n+1) exp(-h^2/4) D_{-n-1}(h) / sqrt(2 pi) (doc/theory.md section 2).
Each series is truncated where the remaining coefficients fall below 1e-18 of the
smallest function value on its interval, then converted (exactly, in mpmath) to powers of
the interval variable t in [-1, 1]: the coefficients still decay (the Chebyshev ones decay
faster than 2^-k), and Fortran evaluates them by Estrin's scheme (groups of four terms in
parallel, Horner in t^4), about three times faster than Clenshaw's serial recurrence.
Run:  python3 tools/reference/gauss_fits.py
"""
import os
import sys

try:
    import mpmath as mp
except ImportError:  # the script installs what it needs
    import subprocess
    subprocess.check_call([sys.executable, "-m", "pip", "install", "--quiet", "mpmath"])
    import mpmath as mp

mp.mp.dps = 50
ORDERS = [("m12", mp.mpf(-1) / 2), ("0", mp.mpf(0)), ("12", mp.mpf(1) / 2), ("1", mp.mpf(1)),
          ("32", mp.mpf(3) / 2), ("52", mp.mpf(5) / 2)]
POS_BREAKS = [0, 1, 2, 3, 4, 5, 6, 7, 8, 10, 12, 16, 24, 40]
NEG_BREAKS = list(range(-12, 1))
NODES = 40
MAXDEG = 24
NSTORE = 4 * (MAXDEG // 4 + 1)  # zero padded to whole groups of four for Estrin's scheme


def f_n(n, h):
    h = mp.mpf(h)
    return mp.gamma(n + 1) * mp.exp(-h * h / 4) * mp.pcfd(-n - 1, h) / mp.sqrt(2 * mp.pi)


def g_n(n, h):
    h = mp.mpf(h)
    return f_n(n, h) * mp.sqrt(2 * mp.pi) * mp.exp(h * h / 2)


def chebfit(func, a, b):
    a, b = mp.mpf(a), mp.mpf(b)
    xs = [mp.cos(mp.pi * (j + mp.mpf(1) / 2) / NODES) for j in range(NODES)]
    fs = [func((a + b) / 2 + (b - a) / 2 * x) for x in xs]
    c = [2 * mp.fsum(fs[j] * mp.cos(mp.pi * k * (j + mp.mpf(1) / 2) / NODES)
                     for j in range(NODES)) / NODES for k in range(NODES)]
    c[0] /= 2
    fmin = min(abs(v) for v in fs)
    deg = 0
    for d in range(NODES - 1, -1, -1):
        if abs(c[d]) > mp.mpf("1e-18") * fmin:
            deg = d
            break
    if deg > MAXDEG:
        raise SystemExit(f"degree {deg} > {MAXDEG} on [{a}, {b}]")
    power = cheb_to_power(c[:deg + 1])
    # rounding-error amplification of the power form relative to the function value
    amp = max(sum(abs(v) for v in power) / abs(f) for f in fs)
    if amp > 8:
        raise SystemExit(f"power form amplifies rounding by {amp} on [{a}, {b}]")
    return power


def cheb_to_power(c):
    """Coefficients of sum_k c_k T_k(t) in powers of t."""
    tkm1, tk = [mp.mpf(1)], [mp.mpf(0), mp.mpf(1)]
    out = [mp.mpf(0)] * len(c)
    out[0] += c[0]
    for k in range(1, len(c)):
        for i, v in enumerate(tk):
            out[i] += c[k] * v
        nxt = [mp.mpf(0)] + [2 * v for v in tk]
        for i, v in enumerate(tkm1):
            nxt[i] -= v
        tkm1, tk = tk, nxt
    return out


def wrap_list(items, per_line, indent="      & "):
    rows = [", ".join(items[i:i + per_line]) for i in range(0, len(items), per_line)]
    return (", &\n" + indent).join(rows)


def fortran_array(name, values, dims):
    lines = [f"   real(dp), parameter :: {name}{dims} = reshape([ &"]
    strs = [mp.nstr(v, 18, min_fixed=1, max_fixed=0) for v in values]
    strs = [s if "e" in s else s + "e0" for s in strs]
    strs = [s + "_dp" for s in strs]
    for i in range(0, len(strs), 3):
        chunk = ", ".join(strs[i:i + 3])
        end = ", &" if i + 3 < len(strs) else "], &"
        lines.append("      & " + chunk + end)
    lines.append(f"      & shape({name}))")
    return "\n".join(lines)


def main():
    out = os.path.join(os.path.dirname(__file__), "..", "..", "src", "egw", "gauss_fits.f90")
    body = []
    degs_pos, degs_neg = [], []
    for tag, n in ORDERS:
        pos, neg, dp_, dn_ = [], [], [], []
        for a, b in zip(POS_BREAKS[:-1], POS_BREAKS[1:]):
            c = chebfit(lambda h: g_n(n, h), a, b)
            dp_.append(len(c) - 1)
            pos += c + [mp.mpf(0)] * (NSTORE - len(c))
        for a, b in zip(NEG_BREAKS[:-1], NEG_BREAKS[1:]):
            c = chebfit(lambda h: f_n(n, h), a, b)
            dn_.append(len(c) - 1)
            neg += c + [mp.mpf(0)] * (NSTORE - len(c))
        degs_pos.append(dp_)
        degs_neg.append(dn_)
        npos, nneg = len(POS_BREAKS) - 1, len(NEG_BREAKS) - 1
        body.append(fortran_array(f"pos_{tag}", pos, f"(0:{NSTORE - 1}, {npos})"))
        body.append(fortran_array(f"neg_{tag}", neg, f"(0:{NSTORE - 1}, {nneg})"))
        print(tag, "degrees h>0:", dp_, "h<0:", dn_, file=sys.stderr)
    npos, nneg = len(POS_BREAKS) - 1, len(NEG_BREAKS) - 1
    tags = [t for t, _ in ORDERS]
    text = f"""!> GENERATED by tools/reference/gauss_fits.py -- do not edit by hand.
!> Piecewise polynomial fits (Chebyshev-truncated, stored in powers of t in [-1, 1] with a
!> zero pad to whole groups of four) of the Gaussian asperity integrals F_n, n in
!> {{-1/2, 0, 1/2, 1, 3/2, 5/2}} (order index 1..6): for h >= 0 of G_n = F_n/phi on the
!> intervals pos_breaks, for -12 <= h < 0 of F_n on unit intervals. See the script for how.
module egw_gauss_fits
   use egw_kinds, only: dp
   implicit none
   private

   integer, parameter, public :: fit_maxdeg = {MAXDEG}, fit_store = {NSTORE}
   integer, parameter, public :: fit_npos = {npos}, fit_nneg = {nneg}
   real(dp), parameter, public :: fit_pos_breaks(0:{npos}) = [ &
      & {wrap_list([f"{b}.0_dp" for b in POS_BREAKS], 8)}]
   integer, parameter, public :: fit_deg_pos({npos}, 6) = reshape([ &
      & {wrap_list([str(d) for row in degs_pos for d in row], 16)}], [{npos}, 6])
   integer, parameter, public :: fit_deg_neg({nneg}, 6) = reshape([ &
      & {wrap_list([str(d) for row in degs_neg for d in row], 16)}], [{nneg}, 6])

{chr(10).join(body)}

   !> Coefficients for h >= 0: fit_pos(k, interval, order).
   real(dp), parameter, public :: fit_pos(0:{NSTORE - 1}, {npos}, 6) = reshape([ &
      & {", ".join("pos_" + t for t in tags)}], [{NSTORE}, {npos}, 6])
   !> Coefficients for -12 <= h < 0: fit_neg(k, interval, order), interval i = [i-13, i-12].
   real(dp), parameter, public :: fit_neg(0:{NSTORE - 1}, {nneg}, 6) = reshape([ &
      & {", ".join("neg_" + t for t in tags)}], [{NSTORE}, {nneg}, 6])

end module egw_gauss_fits
"""
    with open(out, "w") as f:
        f.write(text)
    print("wrote", os.path.normpath(out), file=sys.stderr)


if __name__ == "__main__":
    main()
