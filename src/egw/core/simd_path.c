/*
 * Which of the library's SIMD paths runs (module egw_simd_path; issue 32): the 4-lane
 * AVX2 + FMA kernels (solver/simd_kernels.c: the half-space assembly and the dense LU;
 * kernels/unloading_simd.c: the EP-GW unloading integral's nodes) where the CPU has both,
 * else the baseline x86-64 code gfortran generated. One switch for every layer, decided
 * once when the library loads: the callers ask egw_simd_level() before each call, so
 * that the library, built for any x86-64, runs on any x86-64.
 *
 * EGW_SIMD=sse2 (or off, 0) in the environment keeps the baseline path.
 *
 * Not an API: no declaration in egw.h.
 */
#include <stdlib.h>
#include <string.h>

/* 1: the AVX2 path is used; 0: the baseline. Set once at load time (a constructor),
 * before any thread of the library runs; egw_simd_set changes it (tests). */
static int simd_level = 0;

static int simd_hardware(void)
{
#if defined(__x86_64__) && defined(__GNUC__) && !defined(EGW_NO_SIMD)
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
    return 0;
#endif
}

__attribute__((constructor)) static void simd_init(void)
{
    const char *env = getenv("EGW_SIMD");
    int off = env != NULL && (strcmp(env, "sse2") == 0 || strcmp(env, "off") == 0 ||
                              strcmp(env, "0") == 0);
    simd_level = off ? 0 : simd_hardware();
}

/* The path in use: 1 AVX2, 0 the baseline. */
int egw_simd_level(void)
{
    return simd_level;
}

/* Ask for a path (1 AVX2, 0 the baseline); AVX2 only where the CPU has it. Returns the
 * path now in use. For tests and benchmarks: not while other threads compute. */
int egw_simd_set(int level)
{
    simd_level = level != 0 ? simd_hardware() : 0;
    return simd_level;
}
