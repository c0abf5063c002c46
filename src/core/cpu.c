/* cpu.c - the vector instruction set the running processor offers (see cpu.h).
 * Based on: the gcc/clang built-ins __builtin_cpu_init and __builtin_cpu_supports. */
#include "core/cpu.h"

#include <stdlib.h>
#include <string.h>

static tg__simd_level hardware_level(void)
{
#ifdef TG_HAVE_X86_KERNELS
    __builtin_cpu_init(); /* needed before constructors have run; cheap and idempotent otherwise */
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq") &&
        __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx2"))
        return TG__SIMD_AVX512;
    if (__builtin_cpu_supports("avx2")) return TG__SIMD_AVX2;
#endif
    return TG__SIMD_PORTABLE;
}

tg__simd_level tg__simd_level_detect(void)
{
    tg__simd_level level = hardware_level();
    const char* want = getenv("TRIGEO_SIMD");
    if (want) {
        for (int l = TG__SIMD_PORTABLE; l <= TG__SIMD_AVX512; ++l)
            if (!strcmp(want, tg__simd_level_name((tg__simd_level)l)) && (tg__simd_level)l < level)
                level = (tg__simd_level)l;
    }
    return level;
}

const char* tg__simd_level_name(tg__simd_level level)
{
    switch (level) {
    case TG__SIMD_AVX2: return "avx2";
    case TG__SIMD_AVX512: return "avx512";
    default: return "portable";
    }
}
