/*
 * The solver's hottest loops in 4-lane AVX2 + FMA, chosen at run time (module egw_simd;
 * issue 32): the half-space assembly's far-field kernel (egw_halfspace's far_kernel_run),
 * its near pieces' log-product weights (add_log_piece) and sums over the six-point
 * pressure basis (add_batch_six), and the rank-4
 * update of the dense LU (egw_lapack's panel_of_four).
 *
 * The library is built for the baseline x86-64 (SSE2): there gfortran vectorizes these
 * loops two lanes wide (the kernel with glibc's 2-lane vector log; the basis sums, a
 * reduction, one point at a time). On a CPU with AVX2
 * and FMA this file's routines do the same sums four lanes wide, the kernel with glibc's
 * 4-lane log (_ZGVdN4v_log, libmvec; the log is most of the kernel's cost). Only these
 * functions are compiled for AVX2 (GCC's target attribute); egw_simd_level (core/simd_path.c,
 * the one switch of every layer) tells the Fortran callers whether they may call them, so
 * that the library runs on any x86-64.
 *
 * The two paths differ in rounding only (the 4-lane log, the fused multiply-adds, the
 * sums' order): test_halfspace checks both against the exact uniform-disc deflection and
 * each other, test_rough_sphere the LU on both against reference LAPACK's dgetf2.
 * EGW_SIMD=sse2 (or off, 0) in the environment keeps the baseline path.
 *
 * Not an API: no declaration in egw.h.
 */
/* fpm compiles C without optimization flags: this file's kernel needs them. */
#if defined(__GNUC__) && !defined(__clang__) && !defined(__OPTIMIZE__)
#pragma GCC optimize("O2")
#endif

#include <stdlib.h>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(EGW_NO_SIMD)
#define EGW_HAVE_AVX2_PATH 1
#include <immintrin.h>
#endif

#ifdef EGW_HAVE_AVX2_PATH
/* glibc's 4-lane vector log (libmvec, which libm's linker script brings in). */
__attribute__((target("avx2,fma"))) __m256d _ZGVdN4v_log(__m256d x);

/* Estrin's scheme of c(0) + c(1) x + ... + c(9) x**9 as far_kernel_run writes it. */
__attribute__((target("avx2,fma"), always_inline)) static inline __m256d poly9(const double *c, __m256d x,
                                                                 __m256d x2, __m256d x4)
{
#define EGW_PAIR(i) _mm256_fmadd_pd(_mm256_set1_pd(c[(i) + 1]), x, _mm256_set1_pd(c[i]))
    __m256d a = _mm256_fmadd_pd(x2, EGW_PAIR(2), EGW_PAIR(0));
    __m256d b = _mm256_fmadd_pd(x2, EGW_PAIR(6), EGW_PAIR(4));
    b = _mm256_fmadd_pd(x4, EGW_PAIR(8), b);
    return _mm256_fmadd_pd(x4, b, a);
#undef EGW_PAIR
}

/* Four points of far_kernel_run. */
__attribute__((target("avx2,fma"), always_inline)) static inline __m256d far_four(__m256d t, __m256d w,
                                                                    __m256d r,
                                                                    const double *fp,
                                                                    const double *fq)
{
    const __m256d sign = _mm256_set1_pd(-0.0);
    const __m256d four_pi = _mm256_set1_pd(1.2732395447351628); /* 4/pi */
    __m256d inv_sum = _mm256_div_pd(_mm256_set1_pd(1.0), _mm256_add_pd(r, t));
    __m256d kc = _mm256_mul_pd(_mm256_andnot_pd(sign, _mm256_sub_pd(r, t)), inv_sum);
    __m256d eta = _mm256_mul_pd(kc, kc);
    __m256d e2 = _mm256_mul_pd(eta, eta);
    __m256d e4 = _mm256_mul_pd(e2, e2);
    __m256d p = poly9(fp, eta, e2, e4);
    __m256d q = poly9(fq, eta, e2, e4);
    __m256d lg = _ZGVdN4v_log(kc);
    __m256d k = _mm256_fnmadd_pd(_mm256_add_pd(lg, lg), q, p); /* p - 2 ln(kc) q */
    return _mm256_mul_pd(w, _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(four_pi, t), inv_sum), k));
}
#endif

/* row(i) = w(i) 4/pi t(i)/(r + t(i)) K, K = P(kc**2) - ln(kc**2) Q(kc**2),
 * kc = |r - t(i)|/(r + t(i)), i = 1..n: far_kernel_run's sums (fp, fq: ellipk_fast_p,
 * ellipk_fast_q, ten each). Points t(i) > 0 off r (kc in (0, 1]). Only when
 * egw_simd_level() is 1. */
#ifdef EGW_HAVE_AVX2_PATH
__attribute__((target("avx2,fma"))) void egw_simd_far_kernel(int n, const double *t,
                                                             const double *w, double r,
                                                             const double *fp,
                                                             const double *fq, double *row)
{
    const __m256d rv = _mm256_set1_pd(r);
    int i = 0;
    for (; i + 4 <= n; i += 4)
        _mm256_storeu_pd(row + i, far_four(_mm256_loadu_pd(t + i), _mm256_loadu_pd(w + i),
                                           rv, fp, fq));
    if (i < n) {
        /* the last one to three points, the unused lanes at t = r + 1 (kc > 0) */
        double tt[4], ww[4], out[4];
        int m = n - i, j;
        for (j = 0; j < 4; j++) {
            tt[j] = j < m ? t[i + j] : r + 1.0;
            ww[j] = j < m ? w[i + j] : 0.0;
        }
        _mm256_storeu_pd(out, far_four(_mm256_loadu_pd(tt), _mm256_loadu_pd(ww), rv, fp, fq));
        for (j = 0; j < m; j++)
            row[i + j] = out[j];
    }
}
/* Estrin's scheme of c(0) + c(1) x + ... + c(17) x**17 as split_near writes it. */
__attribute__((target("avx2,fma"), always_inline)) static inline __m256d poly17(const double *c, __m256d x,
                                                                  __m256d x2, __m256d x4,
                                                                  __m256d x8, __m256d x16)
{
#define EGW_PAIR(i) _mm256_fmadd_pd(_mm256_set1_pd(c[(i) + 1]), x, _mm256_set1_pd(c[i]))
    __m256d lo = _mm256_fmadd_pd(x4, _mm256_fmadd_pd(x2, EGW_PAIR(6), EGW_PAIR(4)),
                                 _mm256_fmadd_pd(x2, EGW_PAIR(2), EGW_PAIR(0)));
    __m256d hi = _mm256_fmadd_pd(x4, _mm256_fmadd_pd(x2, EGW_PAIR(14), EGW_PAIR(12)),
                                 _mm256_fmadd_pd(x2, EGW_PAIR(10), EGW_PAIR(8)));
    return _mm256_fmadd_pd(x16, EGW_PAIR(16), _mm256_fmadd_pd(x8, hi, lo));
#undef EGW_PAIR
}

/* Four points of add_log_piece's weights (split_near's kc <= 1/3). */
__attribute__((target("avx2,fma"), always_inline)) static inline __m256d log_four(
    __m256d x, __m256d lw, __m256d llw, __m256d r, __m256d len, __m256d dir,
    __m256d inv_len, const double *a, const double *b)
{
    const __m256d four_pi = _mm256_set1_pd(1.2732395447351628); /* 4/pi */
    __m256d t = _mm256_fmadd_pd(_mm256_mul_pd(dir, len), x, r);
    __m256d sum = _mm256_add_pd(r, t);
    __m256d inv_sum = _mm256_div_pd(_mm256_set1_pd(1.0), sum);
    __m256d kc = _mm256_mul_pd(_mm256_mul_pd(len, x), inv_sum);
    __m256d e = _mm256_mul_pd(kc, kc);
    __m256d e2 = _mm256_mul_pd(e, e);
    __m256d e4 = _mm256_mul_pd(e2, e2);
    __m256d e8 = _mm256_mul_pd(e4, e4);
    __m256d e16 = _mm256_mul_pd(e8, e8);
    __m256d kreg = poly17(a, e, e2, e4, e8, e16);
    __m256d klog = poly17(b, e, e2, e4, e8, e16);
    __m256d lg = _ZGVdN4v_log(_mm256_mul_pd(sum, inv_len));
    __m256d inner = _mm256_fmsub_pd(lw, _mm256_fmadd_pd(klog, lg, kreg), _mm256_mul_pd(llw, klog));
    return _mm256_mul_pd(_mm256_mul_pd(len, _mm256_mul_pd(_mm256_mul_pd(four_pi, t), inv_sum)),
                         inner);
}

/* wt(i) = len c(t) (log_w(i) (kreg + klog ln((r + t)/len)) - log_lw(i) klog),
 * t = r + direction len x(i), c = 4/pi t/(r + t), kreg and klog the power series of
 * split_near at kc = len x(i)/(r + t) (a, b: ellipk_split_a, _b, 18 each), i = 1..n:
 * add_log_piece's weights on a piece no longer than r/2 touching r. Only when
 * egw_simd_level() is 1. */
__attribute__((target("avx2,fma"))) void egw_simd_log_piece(int n, const double *x,
                                                            const double *lw,
                                                            const double *llw, double r,
                                                            double len, double direction,
                                                            const double *a,
                                                            const double *b, double *wt)
{
    const __m256d rv = _mm256_set1_pd(r), lv = _mm256_set1_pd(len);
    const __m256d dv = _mm256_set1_pd(direction), il = _mm256_set1_pd(1.0 / len);
    int i = 0;
    for (; i + 4 <= n; i += 4)
        _mm256_storeu_pd(wt + i, log_four(_mm256_loadu_pd(x + i), _mm256_loadu_pd(lw + i),
                                          _mm256_loadu_pd(llw + i), rv, lv, dv, il, a, b));
    if (i < n) {
        /* the last one to three points, the unused lanes at x = 1/2 (inside the piece) */
        double xx[4], ww[4], ll[4], out[4];
        int m = n - i, j;
        for (j = 0; j < 4; j++) {
            xx[j] = j < m ? x[i + j] : 0.5;
            ww[j] = j < m ? lw[i + j] : 0.0;
            ll[j] = j < m ? llw[i + j] : 0.0;
        }
        _mm256_storeu_pd(out, log_four(_mm256_loadu_pd(xx), _mm256_loadu_pd(ww),
                                       _mm256_loadu_pd(ll), rv, lv, dv, il, a, b));
        for (j = 0; j < m; j++)
            wt[i + j] = out[j];
    }
}
/* a(i) = (a(i) - (u1 c1(i) + u2 c2(i))) - (u3 c3(i) + u4 c4(i)), i = 1..m: the rank-4
 * update of one column below a panel of four (panel_of_four). Only when
 * egw_simd_level() is 1. */
__attribute__((target("avx2,fma"))) void egw_simd_rank4(int m, double *a, const double *c1,
                                                        const double *c2, const double *c3,
                                                        const double *c4, double u1,
                                                        double u2, double u3, double u4)
{
    const __m256d v1 = _mm256_set1_pd(u1), v2 = _mm256_set1_pd(u2);
    const __m256d v3 = _mm256_set1_pd(u3), v4 = _mm256_set1_pd(u4);
    int i = 0;
    for (; i + 4 <= m; i += 4) {
        __m256d s = _mm256_fmadd_pd(v2, _mm256_loadu_pd(c2 + i),
                                    _mm256_mul_pd(v1, _mm256_loadu_pd(c1 + i)));
        __m256d t = _mm256_fmadd_pd(v4, _mm256_loadu_pd(c4 + i),
                                    _mm256_mul_pd(v3, _mm256_loadu_pd(c3 + i)));
        _mm256_storeu_pd(a + i, _mm256_sub_pd(_mm256_sub_pd(_mm256_loadu_pd(a + i), s), t));
    }
    for (; i < m; i++)
        a[i] = (a[i] - __builtin_fma(u2, c2[i], u1 * c1[i])) - __builtin_fma(u4, c4[i], u3 * c3[i]);
}
/* acc(q) += bary(q) sum_p wt(p) prod_{k /= q} (s(p) - ls(k)), q = 1..6, over m points:
 * egw_halfspace's add_batch_six four points at a time (its six sums in four lanes each,
 * added up at the end). Only when egw_simd_level() is 1. */
__attribute__((target("avx2,fma"))) void egw_simd_batch6(int m, const double *ls,
                                                         const double *bary, const double *s,
                                                         const double *wt, double *acc)
{
    const __m256d l1 = _mm256_set1_pd(ls[0]), l2 = _mm256_set1_pd(ls[1]);
    const __m256d l3 = _mm256_set1_pd(ls[2]), l4 = _mm256_set1_pd(ls[3]);
    const __m256d l5 = _mm256_set1_pd(ls[4]), l6 = _mm256_set1_pd(ls[5]);
    __m256d a1 = _mm256_setzero_pd(), a2 = a1, a3 = a1, a4 = a1, a5 = a1, a6 = a1;
    double lane[6][4];
    int i, j, q;
    for (i = 0; i < m; i += 4) {
        __m256d sv, wv, d1, d2, d3, d4, d5, d6, p, q1, q2, q3, q4, q5;
        if (i + 4 <= m) {
            sv = _mm256_loadu_pd(s + i);
            wv = _mm256_loadu_pd(wt + i);
        } else {
            /* the last one to three points; the unused lanes weigh 0: they add exact zeros */
            double ss[4] = {0.0, 0.0, 0.0, 0.0}, ww[4] = {0.0, 0.0, 0.0, 0.0};
            for (j = 0; i + j < m; j++) {
                ss[j] = s[i + j];
                ww[j] = wt[i + j];
            }
            sv = _mm256_loadu_pd(ss);
            wv = _mm256_loadu_pd(ww);
        }
        d1 = _mm256_sub_pd(sv, l1);
        d2 = _mm256_sub_pd(sv, l2);
        d3 = _mm256_sub_pd(sv, l3);
        d4 = _mm256_sub_pd(sv, l4);
        d5 = _mm256_sub_pd(sv, l5);
        d6 = _mm256_sub_pd(sv, l6);
        /* suffixes q(k) = prod_{j > k} d(j); prefixes wt prod_{j < k} d(j) */
        q5 = d6;
        q4 = _mm256_mul_pd(q5, d5);
        q3 = _mm256_mul_pd(q4, d4);
        q2 = _mm256_mul_pd(q3, d3);
        q1 = _mm256_mul_pd(q2, d2);
        a1 = _mm256_fmadd_pd(wv, q1, a1);
        p = _mm256_mul_pd(wv, d1);
        a2 = _mm256_fmadd_pd(p, q2, a2);
        p = _mm256_mul_pd(p, d2);
        a3 = _mm256_fmadd_pd(p, q3, a3);
        p = _mm256_mul_pd(p, d3);
        a4 = _mm256_fmadd_pd(p, q4, a4);
        p = _mm256_mul_pd(p, d4);
        a5 = _mm256_fmadd_pd(p, q5, a5);
        a6 = _mm256_add_pd(a6, _mm256_mul_pd(p, d5));
    }
    _mm256_storeu_pd(lane[0], a1);
    _mm256_storeu_pd(lane[1], a2);
    _mm256_storeu_pd(lane[2], a3);
    _mm256_storeu_pd(lane[3], a4);
    _mm256_storeu_pd(lane[4], a5);
    _mm256_storeu_pd(lane[5], a6);
    for (q = 0; q < 6; q++)
        acc[q] += bary[q] * ((lane[q][0] + lane[q][1]) + (lane[q][2] + lane[q][3]));
}
#else
void egw_simd_batch6(int m, const double *ls, const double *bary, const double *s,
                     const double *wt, double *acc)
{
    (void)m; (void)ls; (void)bary; (void)s; (void)wt; (void)acc;
    abort(); /* unreachable: egw_simd_level() is 0 without the AVX2 path */
}

void egw_simd_rank4(int m, double *a, const double *c1, const double *c2, const double *c3,
                    const double *c4, double u1, double u2, double u3, double u4)
{
    (void)m; (void)a; (void)c1; (void)c2; (void)c3; (void)c4;
    (void)u1; (void)u2; (void)u3; (void)u4;
    abort(); /* unreachable: egw_simd_level() is 0 without the AVX2 path */
}

void egw_simd_log_piece(int n, const double *x, const double *lw, const double *llw,
                        double r, double len, double direction, const double *a,
                        const double *b, double *wt)
{
    (void)n; (void)x; (void)lw; (void)llw; (void)r; (void)len; (void)direction;
    (void)a; (void)b; (void)wt;
    abort(); /* unreachable: egw_simd_level() is 0 without the AVX2 path */
}

void egw_simd_far_kernel(int n, const double *t, const double *w, double r,
                         const double *fp, const double *fq, double *row)
{
    (void)n; (void)t; (void)w; (void)r; (void)fp; (void)fq; (void)row;
    abort(); /* unreachable: egw_simd_level() is 0 without the AVX2 path */
}
#endif
