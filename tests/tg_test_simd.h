/* tg_test_simd.h - runs a check once per instruction-set level of the closest-point kernels that
 * this machine supports (portable, AVX2, AVX-512; src/core/cpu.h): the level is forced through
 * the TRIGEO_SIMD environment variable, read when a BVH is built. Include before any system
 * header (it asks for setenv). */
#ifndef TG_TEST_SIMD_H
#define TG_TEST_SIMD_H

#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <stdlib.h>

#include "core/cpu.h"

/* The levels this machine runs, lowest first (TRIGEO_SIMD as the caller's environment has it
 * still lowers the highest); returns their count. */
static inline int tg_test_simd_levels(tg__simd_level out[3])
{
    int n = 0;
    tg__simd_level top = tg__simd_level_detect();
    for (int l = TG__SIMD_PORTABLE; l <= (int)top; ++l) out[n++] = (tg__simd_level)l;
    return n;
}

/* Makes BVHs built from now on use `level`; unsetenv("TRIGEO_SIMD") undoes it. */
static inline void tg_test_simd_force(tg__simd_level level) { setenv("TRIGEO_SIMD", tg__simd_level_name(level), 1); }

#endif
