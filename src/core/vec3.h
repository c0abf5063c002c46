/* vec3.h - inline double-precision 3-vector math used by every geometric layer.
 * Based on: standard vector algebra; no fused multiply-add (the build uses -ffp-contract=off). */
#ifndef TG_VEC3_H
#define TG_VEC3_H

#include <math.h>

typedef struct tg_vec3 {
    double x, y, z;
} tg_vec3;

static inline tg_vec3 tg_v3(double x, double y, double z) { tg_vec3 r = {x, y, z}; return r; }
static inline tg_vec3 tg_v3_load(const double* p) { tg_vec3 r = {p[0], p[1], p[2]}; return r; }
static inline tg_vec3 tg_v3_add(tg_vec3 a, tg_vec3 b) { return tg_v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline tg_vec3 tg_v3_sub(tg_vec3 a, tg_vec3 b) { return tg_v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline tg_vec3 tg_v3_scale(tg_vec3 a, double s) { return tg_v3(a.x * s, a.y * s, a.z * s); }
static inline double tg_v3_dot(tg_vec3 a, tg_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline tg_vec3 tg_v3_cross(tg_vec3 a, tg_vec3 b)
{
    return tg_v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double tg_v3_len_sq(tg_vec3 a) { return tg_v3_dot(a, a); }
static inline double tg_v3_len(tg_vec3 a) { return sqrt(tg_v3_dot(a, a)); }
static inline double tg_v3_dist(tg_vec3 a, tg_vec3 b) { return tg_v3_len(tg_v3_sub(a, b)); }
static inline double tg_v3_dist_sq(tg_vec3 a, tg_vec3 b) { return tg_v3_len_sq(tg_v3_sub(a, b)); }
/* a times the power of two that brings its largest |component| into [0.5, 1) (a itself when it is
 * zero or not finite): exact unless a component falls below the normal range (then it is below
 * 2^-1022 of the largest and rounds as any subnormal does), so that a vector and the same vector
 * times any power of two give the same bits, and products of the result neither overflow nor
 * underflow. Directions given by callers pass through it before any product. */
static inline tg_vec3 tg_v3_pow2_unit(tg_vec3 a)
{
    double m = fmax(fabs(a.x), fmax(fabs(a.y), fabs(a.z)));
    if (!(m > 0.0) || !isfinite(m)) return a;
    int e;
    (void)frexp(m, &e);
    return tg_v3(ldexp(a.x, -e), ldexp(a.y, -e), ldexp(a.z, -e));
}
/* a + t (b - a) */
static inline tg_vec3 tg_v3_lerp(tg_vec3 a, tg_vec3 b, double t)
{
    return tg_v3(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z));
}
/* The same on plain double[3] arrays (r must not alias a or b for cross). */
static inline void tg_a3_sub(const double* a, const double* b, double* r)
{
    r[0] = a[0] - b[0], r[1] = a[1] - b[1], r[2] = a[2] - b[2];
}
static inline void tg_a3_cross(const double* a, const double* b, double* r)
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}
static inline double tg_a3_dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline void tg_v3_store(tg_vec3 a, double* p) { p[0] = a.x; p[1] = a.y; p[2] = a.z; }

#endif
