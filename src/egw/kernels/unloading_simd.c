/*
 * The EP-GW unloading integral's panels (egw_unloading's unload_integral: one panel's 16
 * nodes, the integrands of Z_u(h, h_min) and dZ_u/dh there and their weighted sums) in
 * 4-lane AVX2 + FMA, chosen at run time (issue 32). The library is built for the baseline x86-64, where gfortran evaluates the
 * nodes two lanes wide (glibc's 2-lane vector log and exp); with AVX2 and FMA this file
 * does four lanes with glibc's 4-lane log and exp (_ZGVdN4v_log, _ZGVdN4v_exp: libmvec,
 * part of glibc on x86-64, which the baseline code and solver/simd_kernels.c use already).
 * Only these functions are compiled for AVX2 (GCC's target attribute); the Fortran caller
 * takes them only where egw_simd_level() (core/simd_path.c) is 1, so that the library
 * runs on any x86-64.
 *
 * The two paths differ in rounding only (the vector log and exp, fused multiply-adds, and
 * the Gaussian's exact split taken by truncating z's mantissa instead of Dekker's split):
 * test_unloading checks both against the 40-digit references and against each other.
 *
 * Not an API: no declaration in egw.h.
 */
/* fpm compiles C without optimization flags: this file's kernel needs them. */
#if defined(__GNUC__) && !defined(__clang__) && !defined(__OPTIMIZE__)
#pragma GCC optimize("O2")
#endif

#include <stdint.h>
#include <stdlib.h>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(EGW_NO_SIMD)
#define EGW_HAVE_AVX2_PATH 1
#include <immintrin.h>
#endif

#ifdef EGW_HAVE_AVX2_PATH
/* glibc's 4-lane vector log and exp (libmvec, which libm's linker script brings in). */
__attribute__((target("avx2,fma"))) __m256d _ZGVdN4v_log(__m256d x);
__attribute__((target("avx2,fma"))) __m256d _ZGVdN4v_exp(__m256d x);

/* phi(z) = exp(-z^2/2)/sqrt(2 pi) to a few ulps, as egw_unloading's gaussian: a = |z|
 * (at most 40: phi underflows from 38.6 on) = hi + lo with hi of 26 significant bits
 * (a's mantissa truncated, so that hi^2/2 is exact), and small = (a - hi)(a + hi)/2
 * (< 5e-5 for a <= 40) through exp(-small)'s cubic (error small^4/24 < 3e-19). */
__attribute__((target("avx2,fma"), always_inline)) static inline __m256d gaussian4(__m256d z)
{
    const __m256d sign = _mm256_set1_pd(-0.0);
    const __m256d keep = _mm256_castsi256_pd(_mm256_set1_epi64x((int64_t)0xFFFFFFFFF8000000ULL));
    __m256d a = _mm256_min_pd(_mm256_andnot_pd(sign, z), _mm256_set1_pd(40.0));
    __m256d hi = _mm256_and_pd(a, keep);
    __m256d small = _mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(0.5), _mm256_sub_pd(a, hi)),
                                  _mm256_add_pd(a, hi));
    __m256d e = _ZGVdN4v_exp(_mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(-0.5), hi), hi));
    /* 1 - s (1 - s (1/2 - s/6)) */
    __m256d c = _mm256_fnmadd_pd(small, _mm256_set1_pd(1.0 / 6.0), _mm256_set1_pd(0.5));
    c = _mm256_fnmadd_pd(small, c, _mm256_set1_pd(1.0));
    c = _mm256_fnmadd_pd(small, c, _mm256_set1_pd(1.0));
    return _mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(0.3989422804014327), e), c);
}

/* fz(i) = f^ ((D - Delta)_+/D)^(3/2) phi(z(i)) and gz(i) = f^ (D - Delta)_+^(1/2) / D^(3/2)
 * phi(z(i)), i = 1..16, at t = max(z - h_min, tiny) on one branch of the ZMC law: 0 below
 * e (f^ = t^(3/2), D = t), 1 between e and q, 2 beyond q. e, inv_qe = 1/(q - e), slope =
 * (1 - K)/ln rho_p, lnq = ln q and c = sqrt(e)/K as egw_unloading's zmc_law. Kept a
 * function of its own (noinline) so that its code, and so its rounding, is the one the
 * Fortran caller called before the panel moved here (stop 65, psi31). */
__attribute__((target("avx2,fma"), noinline)) static void integrands(int branch, const double *z,
                                                                  double h_min, double delta,
                                                                  double e, double inv_qe,
                                                                  double slope, double lnq,
                                                                  double c, double *fz,
                                                                  double *gz)
{
    const __m256d zero = _mm256_setzero_pd();
    const __m256d one = _mm256_set1_pd(1.0);
    const __m256d dv = _mm256_set1_pd(delta);
    const __m256d cv = _mm256_set1_pd(c);
    int i;
    for (i = 0; i < 16; i += 4) {
        __m256d zi = _mm256_loadu_pd(z + i);
        __m256d t = _mm256_max_pd(_mm256_sub_pd(zi, _mm256_set1_pd(h_min)),
                                  _mm256_set1_pd(2.2250738585072014e-308));
        __m256d phi = gaussian4(zi);
        __m256d f, d, x, g;
        if (branch == 0) {
            x = _mm256_max_pd(_mm256_sub_pd(t, dv), zero);
            g = _mm256_mul_pd(_mm256_sqrt_pd(x), phi);
        } else {
            if (branch == 1) {
                __m256d l = _mm256_mul_pd(_mm256_sub_pd(t, _mm256_set1_pd(e)),
                                          _mm256_set1_pd(inv_qe));
                /* 1 + l^2 (3 - 2 l) */
                __m256d area = _mm256_fnmadd_pd(_mm256_set1_pd(2.0), l, _mm256_set1_pd(3.0));
                area = _mm256_fmadd_pd(_mm256_mul_pd(l, l), area, one);
                /* 1 - slope (ln q - ln t) */
                __m256d pres = _mm256_fnmadd_pd(
                    _mm256_set1_pd(slope),
                    _mm256_sub_pd(_mm256_set1_pd(lnq), _ZGVdN4v_log(t)), one);
                __m256d cp = _mm256_mul_pd(cv, pres);
                __m256d at = _mm256_mul_pd(area, t);
                f = _mm256_mul_pd(cp, at);
                d = _mm256_min_pd(t, _mm256_mul_pd(cp, _mm256_sqrt_pd(at)));
            } else {
                f = _mm256_mul_pd(_mm256_add_pd(cv, cv), t);
                d = _mm256_min_pd(t, _mm256_mul_pd(cv, _mm256_sqrt_pd(_mm256_add_pd(t, t))));
            }
            __m256d inv_d = _mm256_div_pd(one, d);
            x = _mm256_max_pd(_mm256_sub_pd(d, dv), zero);
            g = _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(f, inv_d),
                                            _mm256_sqrt_pd(_mm256_mul_pd(x, inv_d))), phi);
        }
        _mm256_storeu_pd(gz + i, g);
        _mm256_storeu_pd(fz + i, _mm256_mul_pd(g, x));
    }
}

/* Sum of four vectors' 16 lanes in egw_unloading's sum16 order: with x(1:16) = x0..x3,
 * h8 = x(1:8) + x(9:16), h4 = h8(1:4) + h8(5:8), then (h4(1) + h4(3)) + (h4(2) + h4(4)). */
__attribute__((target("avx2,fma"), always_inline)) static inline double sum16(__m256d x0,
                                                                              __m256d x1,
                                                                              __m256d x2,
                                                                              __m256d x3)
{
    double h[4];
    _mm256_storeu_pd(h, _mm256_add_pd(_mm256_add_pd(x0, x2), _mm256_add_pd(x1, x3)));
    return (h[0] + h[2]) + (h[1] + h[3]);
}

/* One panel of egw_unloading's unload_integral: its 16 nodes, the integrands there and
 * their weighted sums (the Fortran plain_panel and edge_panel, which called the integrands
 * through a wrapper and formed the nodes and sums two lanes wide). edge = 0: [za, zb]
 * with z = za + (zb - za) u; edge = 1: z = z* + v^2, v from sqrt(za - z*) to
 * sqrt(zb - z*) (the contact edge made smooth), the weights times dz/dv = 2 v. rp, rdp:
 * the panel's integrals of F and G (as egw_unloading's integrands); gl_u, gl_w: the
 * 16-point Gauss-Legendre nodes on [0, 1] and weights summing to 1. The same operations
 * in the same order as the Fortran (no fused multiply-add: fp-contract off), so the same
 * bits. Only when egw_simd_level() is 1. */
__attribute__((target("avx2,fma"), optimize("O2", "fp-contract=off"))) void egw_unload_panel(
    int branch, int edge, double za, double zb, double z_star, double h_min, double delta,
    double e, double inv_qe, double slope, double lnq, double c, const double *gl_u,
    const double *gl_w, double *rp, double *rdp)
{
    double z[16], fz[16], gz[16];
    __m256d v[4], fs[4], gs[4];
    double width;
    int i;
    if (edge) {
        double va = __builtin_sqrt(za - z_star > 0.0 ? za - z_star : 0.0);
        double vb = __builtin_sqrt(zb - z_star > 0.0 ? zb - z_star : 0.0);
        for (i = 0; i < 4; i++) {
            v[i] = _mm256_add_pd(_mm256_set1_pd(va), _mm256_mul_pd(_mm256_set1_pd(vb - va),
                                                                  _mm256_loadu_pd(gl_u + 4 * i)));
            _mm256_storeu_pd(z + 4 * i, _mm256_add_pd(_mm256_set1_pd(z_star),
                                                      _mm256_mul_pd(v[i], v[i])));
        }
        width = vb - va;
    } else {
        for (i = 0; i < 4; i++) {
            __m256d u = _mm256_loadu_pd(gl_u + 4 * i);
            _mm256_storeu_pd(z + 4 * i, _mm256_add_pd(_mm256_set1_pd(za),
                                                      _mm256_mul_pd(_mm256_set1_pd(zb - za), u)));
        }
        width = zb - za;
    }
    integrands(branch, z, h_min, delta, e, inv_qe, slope, lnq, c, fz, gz);
    for (i = 0; i < 4; i++) {
        __m256d w = _mm256_loadu_pd(gl_w + 4 * i);
        fs[i] = _mm256_mul_pd(w, _mm256_loadu_pd(fz + 4 * i));
        gs[i] = _mm256_mul_pd(w, _mm256_loadu_pd(gz + 4 * i));
        if (edge) { /* (w f 2) v, as the Fortran's gl_w16*fz*2.0_dp*v */
            fs[i] = _mm256_mul_pd(_mm256_add_pd(fs[i], fs[i]), v[i]);
            gs[i] = _mm256_mul_pd(_mm256_add_pd(gs[i], gs[i]), v[i]);
        }
    }
    *rp = sum16(fs[0], fs[1], fs[2], fs[3]) * width;
    *rdp = sum16(gs[0], gs[1], gs[2], gs[3]) * width;
}
#else
void egw_unload_panel(int branch, int edge, double za, double zb, double z_star, double h_min,
                      double delta, double e, double inv_qe, double slope, double lnq, double c,
                      const double *gl_u, const double *gl_w, double *rp, double *rdp)
{
    (void)branch; (void)edge; (void)za; (void)zb; (void)z_star; (void)h_min; (void)delta;
    (void)e; (void)inv_qe; (void)slope; (void)lnq; (void)c; (void)gl_u; (void)gl_w;
    (void)rp; (void)rdp;
    abort(); /* unreachable: egw_simd_level() is 0 without the AVX2 path */
}
#endif
