/* cpu.h - which vector instruction set the running processor offers, for kernels compiled for
 * several (gcc/clang target attributes) and chosen at run time.
 * Based on: the gcc/clang built-ins __builtin_cpu_init and __builtin_cpu_supports (CPUID feature
 * bits, with the operating system's XSAVE support of the wider registers checked through XGETBV). */
#ifndef TG_CPU_H
#define TG_CPU_H

/* Levels, each including the one below. AVX512 means F, VL, DQ and BW together (x86-64-v4). */
typedef enum tg__simd_level {
    TG__SIMD_PORTABLE = 0, /* plain C (and SSE2, the x86-64 baseline) */
    TG__SIMD_AVX2 = 1,
    TG__SIMD_AVX512 = 2
} tg__simd_level;

/* Kernels for the wider levels exist only where the compiler can target them. */
#if (defined(__x86_64__) || defined(_M_X64)) && (defined(__GNUC__) || defined(__clang__)) && !defined(TG_NO_SIMD)
#define TG_HAVE_X86_KERNELS 1
#define TG_TARGET_AVX2 __attribute__((target("avx2")))
#define TG_TARGET_AVX512 __attribute__((target("avx2,avx512f,avx512vl,avx512dq,avx512bw")))
#endif

/* The highest level the processor and the build support, lowered to the level named by the
 * environment variable TRIGEO_SIMD if set ("portable", "avx2" or "avx512"; a level above what the
 * processor offers is not raised to; anything else is ignored). Read each time it is called: the
 * library stores the result in the objects it builds, so that there is no global state. */
tg__simd_level tg__simd_level_detect(void);

/* The name of a level, as TRIGEO_SIMD spells it. */
const char* tg__simd_level_name(tg__simd_level level);

#endif
