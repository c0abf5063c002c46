/* fan_path.h - internal: pieces of the fan minimizer exposed for tests and for the path solver.
 * Based on: seed 002 §3.4.1 (eq. 41-50: F'(0) along a direction, H(v) and its minimum), §4.1
 *   (eq. 59-87: the recursion in dimension), §4.5 (ComputeLargestInitialDecrease for N triangles). */
#ifndef TG_KERNELS_FAN_PATH_H
#define TG_KERNELS_FAN_PATH_H

#include <stddef.h>

#include "kernels/edge_path.h"

/* ComputeLargestInitialDecrease for a path Q0 -> V -> Q1 across n >= 1 edges V -> V + D_i
 * (coordinates relative to V): minimizes H(v) = G(1/|D_0|, v_1/|D_1|, ..., v_{n-1}/|D_{n-1}|),
 * where G(u) = F'(0) is the rate of change of the length when leaving V in direction u (eq. 61),
 * recursively from the last edge to the first (eq. 64-87), each level's root r_i of g_i'(r) = 0
 * taken from the closed form (eq. 50/68/72/81/84/87) and verified on the derivative, or by
 * bisection when the closed form is ill-conditioned (|E . xi| or |g| near 1, seed §3.4.1).
 * Returns the minimum of H when it is negative, with out_u (n doubles) the unit direction
 * (all components >= 0) along which the path leaves V; returns 0 with out_u all zero when no
 * direction shortens the path (then, by convexity, the path through V is the shortest, §4.2).
 * Also returns 0 when Q0 or Q1 is V, or some D_i is zero: the path must pass through V then. */
double tg__fan_initial_decrease(const double q0[3], const double q1[3], const double* d, size_t n,
                                const tg__root_opts* ro, double* out_u);

/* G(u) = F'(0) of eq. (61) for the same data: the right derivative at s = 0 of the length of
 * Q0 -> s u_0 D_0 -> ... -> s u_{n-1} D_{n-1} -> Q1. For tests of the decrease direction. */
double tg__fan_directional_slope(const double q0[3], const double q1[3], const double* d, size_t n, const double* u);

/* tg_fan_path_minimize with the scratch of fans over 64 edges taken from allocator a (NULL:
 * libc), so that the path solver's queries allocate only through the solver's allocator. */
tg_status tg__fan_path_minimize_with(const tg_allocator* a, const double p0[3], const double p1[3], const double v[3],
                                     const double* w, size_t m, const double* t_init,
                                     const tg_geodesic_kernel_options* opts, double* out_t, double* out_length,
                                     int* out_decreased);

#endif
