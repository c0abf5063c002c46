/* simd4.h - a minimal 4-lane float vector for the BVH (SSE2 on x86-64, plain C elsewhere).
 * Based on: IEEE 754 single precision; every operation is one correctly rounded lane-wise operation,
 * so the SSE and the plain C paths give bit-identical results (the build uses -ffp-contract=off). */
#ifndef TG_SIMD4_H
#define TG_SIMD4_H

#include <stdint.h>
#include <string.h>

#if defined(__SSE2__) && !defined(TG_NO_SIMD)
#include <emmintrin.h>
#define TG_SIMD4_SSE 1
typedef __m128 tg_v4;
static inline tg_v4 tg_v4_set1(float x) { return _mm_set1_ps(x); }
static inline tg_v4 tg_v4_set(float a, float b, float c, float d) { return _mm_setr_ps(a, b, c, d); }
static inline tg_v4 tg_v4_loadu(const float* p) { return _mm_loadu_ps(p); }
static inline void tg_v4_storeu(float* p, tg_v4 a) { _mm_storeu_ps(p, a); }
static inline tg_v4 tg_v4_add(tg_v4 a, tg_v4 b) { return _mm_add_ps(a, b); }
static inline tg_v4 tg_v4_sub(tg_v4 a, tg_v4 b) { return _mm_sub_ps(a, b); }
static inline tg_v4 tg_v4_mul(tg_v4 a, tg_v4 b) { return _mm_mul_ps(a, b); }
static inline tg_v4 tg_v4_div(tg_v4 a, tg_v4 b) { return _mm_div_ps(a, b); }
/* min/max return the second operand when either is NaN (as minps/maxps); callers never pass NaN. */
static inline tg_v4 tg_v4_min(tg_v4 a, tg_v4 b) { return _mm_min_ps(a, b); }
static inline tg_v4 tg_v4_max(tg_v4 a, tg_v4 b) { return _mm_max_ps(a, b); }
/* Four bytes as floats 0..255 (exact). */
static inline tg_v4 tg_v4_from_u8(const uint8_t* q)
{
    uint32_t w;
    memcpy(&w, q, sizeof w);
    __m128i z = _mm_setzero_si128();
    __m128i v = _mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128((int)w), z), z);
    return _mm_cvtepi32_ps(v);
}
/* Four signed bytes as floats -128..127 (exact). */
static inline tg_v4 tg_v4_from_i8(const int8_t* q)
{
    uint32_t w;
    memcpy(&w, q, sizeof w);
    __m128i v = _mm_cvtsi32_si128((int)w);
    v = _mm_unpacklo_epi8(v, v);
    v = _mm_srai_epi32(_mm_unpacklo_epi16(v, v), 24);
    return _mm_cvtepi32_ps(v);
}
static inline tg_v4 tg_v4_abs(tg_v4 a) { return _mm_and_ps(a, _mm_castsi128_ps(_mm_set1_epi32(0x7FFFFFFF))); }
/* Lanes converted to int32 with truncation (as a C cast), stored to out[4]. */
static inline void tg_v4_trunc_store(int32_t* out, tg_v4 a) { _mm_storeu_si128((__m128i*)(void*)out, _mm_cvttps_epi32(a)); }
/* Bit i set when lane i of a is <= lane i of b. */
static inline int tg_v4_le_mask(tg_v4 a, tg_v4 b) { return _mm_movemask_ps(_mm_cmple_ps(a, b)); }
#else
typedef struct tg_v4 {
    float v[4];
} tg_v4;
static inline tg_v4 tg_v4_set1(float x) { tg_v4 r = {{x, x, x, x}}; return r; }
static inline tg_v4 tg_v4_set(float a, float b, float c, float d) { tg_v4 r = {{a, b, c, d}}; return r; }
static inline tg_v4 tg_v4_loadu(const float* p) { tg_v4 r; memcpy(r.v, p, sizeof r.v); return r; }
static inline void tg_v4_storeu(float* p, tg_v4 a) { memcpy(p, a.v, sizeof a.v); }
#define TG_V4_LANES_(expr)                          \
    tg_v4 r;                                        \
    for (int i = 0; i < 4; ++i) r.v[i] = (expr);    \
    return r
static inline tg_v4 tg_v4_add(tg_v4 a, tg_v4 b) { TG_V4_LANES_(a.v[i] + b.v[i]); }
static inline tg_v4 tg_v4_sub(tg_v4 a, tg_v4 b) { TG_V4_LANES_(a.v[i] - b.v[i]); }
static inline tg_v4 tg_v4_mul(tg_v4 a, tg_v4 b) { TG_V4_LANES_(a.v[i] * b.v[i]); }
static inline tg_v4 tg_v4_div(tg_v4 a, tg_v4 b) { TG_V4_LANES_(a.v[i] / b.v[i]); }
static inline tg_v4 tg_v4_min(tg_v4 a, tg_v4 b) { TG_V4_LANES_(a.v[i] < b.v[i] ? a.v[i] : b.v[i]); }
static inline tg_v4 tg_v4_max(tg_v4 a, tg_v4 b) { TG_V4_LANES_(a.v[i] > b.v[i] ? a.v[i] : b.v[i]); }
static inline tg_v4 tg_v4_from_u8(const uint8_t* q) { TG_V4_LANES_((float)q[i]); }
static inline tg_v4 tg_v4_from_i8(const int8_t* q) { TG_V4_LANES_((float)q[i]); }
static inline tg_v4 tg_v4_abs(tg_v4 a) { TG_V4_LANES_(a.v[i] < 0.0f ? -a.v[i] : a.v[i]); }
static inline void tg_v4_trunc_store(int32_t* out, tg_v4 a)
{
    for (int i = 0; i < 4; ++i) out[i] = (int32_t)a.v[i];
}
#undef TG_V4_LANES_
static inline int tg_v4_le_mask(tg_v4 a, tg_v4 b)
{
    int m = 0;
    for (int i = 0; i < 4; ++i) m |= (a.v[i] <= b.v[i]) << i;
    return m;
}
#endif

#endif
