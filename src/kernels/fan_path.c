/* fan_path.c - the shortest path across a fan of triangles around a vertex V.
 * Based on: seed 002 §3.1 and §4 (eq. 12-13, 54-55: the path P0 -> M_0 -> ... -> M_{m-1} -> P1,
 *   M_i = V + t_i D_i, and its length L(t)), eq. (14)-(15)/(56) (the partial derivatives),
 *   eq. (57)-(58) (the tridiagonal Hessian), §3.2/§4.2 (L is convex), §3.4.1 and §4.1 (eq. 41-87:
 *   whether the path through V can be shortened at all, ComputeLargestInitialDecrease, recursive in
 *   dimension), §3.4.2 (ClampToDomain, and the three search strategies: coordinate directions,
 *   Powell's direction set, conjugate gradient), §3.5/§4.3-4.5 (GetPath, Search, GetLRoot,
 *   GetFRoot, the convergence tests on the gradient and on the change of t).
 *
 * Departures from the seed's pseudocode, each for robustness:
 *  - The seed starts at t = 0 and assumes the only place where L is not differentiable is t = 0.
 *    L is also non-differentiable wherever two or more consecutive t are 0 (the path touches V
 *    between two edge points), and the coordinate search can stop there although a shorter path
 *    exists (each coordinate alone cannot leave V, only several together). After the search
 *    converges, every run of consecutive zeros is therefore tested with the same
 *    ComputeLargestInitialDecrease (with the run's neighbours as P0 and P1) and, on a decrease,
 *    left along ClampToDomain's ray, after which the search resumes. With this, a converged
 *    result satisfies the optimality conditions of the convex problem on [0, 1]^m.
 *  - The gradient test uses the projected gradient (components pushing against t = 0 or t = 1
 *    do not count): at a minimum on the boundary of [0, 1]^m the gradient does not vanish
 *    (Example 3.3, whose minimum has t0 = 1).
 *  - Derivatives are one-sided where a segment has zero length, so no 0/0 occurs; a step is
 *    kept only if it does not lengthen the path beyond rounding.
 *  - Consecutive edges on one ray (a zero-area triangle between them) are merged into one
 *    variable before the search: the length has a kink along them that stalls every strategy.
 *  - A fourth strategy, projected Newton with the seed's own tridiagonal Hessian (eq. 57-58),
 *    converges quadratically where the seed's linear-rate strategies need O(m^2) sweeps.
 *  - The 1D roots may also come from safeguarded Newton steps or, for the two-point problems of
 *    the coordinate search, from the unfolding closed form (edge_path.c). */
#include "kernels/fan_path.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "core/core.h"
#include "core/predicates.h"
#include "core/vec3.h"

/* Fans with at most this many interior edges keep their scratch on the stack (no allocation). */
#define FAN_STACK_EDGES 64
/* Doubles of scratch per interior edge (D: 3; |D|, t, u, g, dprev, tsave, aux1, aux2, flags: 9)
 * and per segment (line-search x and y: 6; cached length: 1). */
#define FAN_SCRATCH_PER_EDGE 12
#define FAN_SCRATCH_PER_SEGMENT 7

/* The closed form (eq. 50 ff.) divides by 1 - g^2 (g = -E . xi for the last edge, g_i(r_i)
 * after); its relative error grows like eps / (1 - g^2). Below sqrt(eps) it would lose more than
 * half the digits, and the seed (§3.4.1) recommends bisection instead. */
#define FAN_CLOSED_FORM_MIN_SIN2 1.4901161193847656e-08 /* sqrt(2^-52) */
/* A root from the closed form is accepted when the scaled derivative (r - c) + g |E' - r E|
 * vanishes to this relative accuracy; the correct root's residual is below eps / (1 - g^2) <=
 * sqrt(eps), an extraneous root (produced by squaring) has a residual of order |g|. */
#define FAN_ROOT_RESIDUAL 9.5367431640625e-07 /* 2^-20 */
/* The bisection fallback brackets r in [0, 2^FAN_R_MAX_EXP]. When g'(r) < 0 still holds there,
 * the remaining decrease of g beyond is below (1 - c^2) / 2^(FAN_R_MAX_EXP + 1) (g' ~ -(1 - c^2) /
 * 2 r^2), far below rounding. */
#define FAN_R_MAX_EXP 60
/* Direction components are rescaled when they exceed 2^FAN_U_RESCALE_EXP, keeping the products
 * of up to m roots far from overflow. */
#define FAN_U_RESCALE_EXP 200

typedef struct fan {
    size_t m;
    double q0[3], q1[3]; /* P0 - V, P1 - V */
    double* d;           /* 3m: D_i = W_i - V */
    double* dlen;        /* m: |D_i| */
    double* t;           /* m: the current edge parameters */
    double* u;           /* m: a direction (initial decrease, search direction) */
    double* g;           /* m: projected gradient */
    double* dprev;       /* m: previous conjugate-gradient direction */
    double* tsave;       /* m: t at the start of a Powell sweep; previous CG gradient */
    double* aux1;        /* m: Newton: Thomas modified super-diagonal */
    double* aux2;        /* m: Newton: Thomas modified right-hand side */
    double* flags;       /* m: Newton: 1 for a free variable, 0 for one held at a bound */
    double* lx;          /* 3 (m + 1): line-search data x_k; Newton: segment vectors */
    double* ly;          /* 3 (m + 1): line-search data y_k */
    double* seglen;      /* m + 1: Newton: segment lengths */
    tg__root_opts ro;
    int strategy;
    double grad_tol; /* on |dL/dt_j| / |D_j| (a difference of two cosines) */
    double step_tol; /* on max |change of t_j| over one sweep or step */
    long budget;     /* outer iterations left */
} fan;

/* M_i for i in -1 .. m: P0 - V, t_i D_i, P1 - V. */
static inline tg_vec3 fan_point(const fan* F, long i)
{
    if (i < 0) return tg_v3_load(F->q0);
    if ((size_t)i >= F->m) return tg_v3_load(F->q1);
    const double* di = F->d + 3 * (size_t)i;
    double ti = F->t[i];
    return tg_v3(ti * di[0], ti * di[1], ti * di[2]);
}

/* One-sided partial derivatives of L in t_j (eq. 56): D_j . (M_j - M_{j-1}) / |M_j - M_{j-1}|
 * - D_j . (M_{j+1} - M_j) / |M_{j+1} - M_j|; a zero-length segment contributes +|D_j| to the
 * right derivative and -|D_j| to the left one. */
static void fan_partial(const fan* F, size_t j, double* out_right, double* out_left)
{
    tg_vec3 dj = tg_v3_load(F->d + 3 * j);
    tg_vec3 mj = fan_point(F, (long)j);
    tg_vec3 a = tg_v3_sub(mj, fan_point(F, (long)j - 1));
    tg_vec3 b = tg_v3_sub(fan_point(F, (long)j + 1), mj);
    double la = tg_v3_len(a), lb = tg_v3_len(b);
    double smooth = 0.0, kinks = 0.0;
    if (la > 0.0) smooth += tg_v3_dot(dj, a) / la;
    else kinks += F->dlen[j];
    if (lb > 0.0) smooth -= tg_v3_dot(dj, b) / lb;
    else kinks += F->dlen[j];
    *out_right = smooth + kinks;
    *out_left = smooth - kinks;
}

/* The projected gradient into F->g (a component is 0 when t_j sits on a bound it is pushed
 * against, or when 0 lies between the one-sided derivatives); returns max_j |g_j| / |D_j|. */
static double fan_projected_gradient(fan* F)
{
    double worst = 0.0;
    for (size_t j = 0; j < F->m; j++) {
        double gr, gl, g = 0.0;
        fan_partial(F, j, &gr, &gl);
        if (gr < 0.0 && F->t[j] < 1.0) g = gr;
        else if (gl > 0.0 && F->t[j] > 0.0) g = gl;
        F->g[j] = g;
        if (g != 0.0) {
            double rel = fabs(g) / F->dlen[j];
            if (rel > worst) worst = rel;
        }
    }
    return worst;
}

/* ---- line searches ---- */

/* A step is kept when the new length is not longer than the old one beyond the rounding of a sum
 * of `terms` norms (each within ~2 eps): near the minimum L is flat to second order, so the
 * 1D minimizer's (derivative-based, accurate) step can change L by less than its rounding, and a
 * strict comparison would freeze t while the gradient is still far from zero. */
static inline int not_longer(double new_len, double old_len, size_t terms)
{
    return new_len <= old_len + 4.0 * DBL_EPSILON * (double)terms * old_len;
}

/* The seed's Search(j) with GetLRoot: minimize L over t_j alone, the others fixed, on [t_j, 1]
 * when L decreases to the right and on [0, t_j] when it decreases to the left. As a function of
 * t_j, L is the two-triangle function of §2: |t D_j - M_{j-1}| + |t D_j - M_{j+1}|.
 * Returns |change of t_j|. */
static double fan_search(fan* F, size_t j)
{
    if (!(F->dlen[j] > 0.0)) return 0.0;
    double gr, gl;
    fan_partial(F, j, &gr, &gl);
    double tj = F->t[j], s;
    const double* dj = F->d + 3 * j;
    tg_vec3 a = fan_point(F, (long)j - 1), b = fan_point(F, (long)j + 1);
    double x[6] = {-a.x, -a.y, -a.z, -b.x, -b.y, -b.z};
    double y[6] = {dj[0], dj[1], dj[2], dj[0], dj[1], dj[2]};
    tg__norm_sum f = {x, y, 2};
    double pa[3] = {a.x, a.y, a.z}, pb[3] = {b.x, b.y, b.z};
    if (gr < 0.0 && tj < 1.0) {
        if (F->ro.method == TG_ROOT_UNFOLD) s = tg__two_point_unfold(dj, pa, pb, tj, 1.0);
        else if (tg__norm_sum_slope(&f, 1.0, -1) <= 0.0) s = 1.0;
        else tg__norm_sum_root(&f, tj, 1.0, &F->ro, &s);
    } else if (gl > 0.0 && tj > 0.0) {
        if (F->ro.method == TG_ROOT_UNFOLD) s = tg__two_point_unfold(dj, pa, pb, 0.0, tj);
        else if (tg__norm_sum_slope(&f, 0.0, +1) >= 0.0) s = 0.0;
        else tg__norm_sum_root(&f, 0.0, tj, &F->ro, &s);
    } else {
        return 0.0;
    }
    if (s == tj || !not_longer(tg__norm_sum_value(&f, s), tg__norm_sum_value(&f, tj), 2)) return 0.0;
    F->t[j] = s;
    return fabs(s - tj);
}

/* One coordinate sweep (seed §3.5: for each j with a non-zero derivative, Search(j)).
 * Returns the largest change of any t_j. */
static double fan_sweep(fan* F)
{
    double moved = 0.0;
    for (size_t j = 0; j < F->m; j++) {
        double dt = fan_search(F, j);
        if (dt > moved) moved = dt;
    }
    return moved;
}

/* Root finder of line searches along general directions (many terms): the closed forms exist
 * only for two-term functions, so TG_ROOT_UNFOLD uses Newton there and TG_ROOT_QUADRATIC (the
 * two-triangle kernel's eq. 6) bisection. */
static tg__root_opts fan_line_root_opts(const fan* F)
{
    tg__root_opts ro = F->ro;
    if (ro.method == TG_ROOT_UNFOLD) ro.method = TG_ROOT_NEWTON;
    else if (ro.method != TG_ROOT_NEWTON) ro.method = TG_ROOT_BISECTION;
    return ro;
}

/* Minimizes L along t + s dir, s in [0, s_max] where s_max keeps t in [0, 1]^m: L restricted to
 * a line is a sum of norms of affine functions (tg__norm_sum), convex in s. Segment i runs from
 * M_{i-1} to M_i, so x_i = M_i - M_{i-1} and y_i = dir_i D_i - dir_{i-1} D_{i-1} (dir_{-1} =
 * dir_m = 0). Only the segments touched by non-zero dir components enter (first .. last + 1).
 * Returns the largest change of any t_j; *out_hit_bound is set when the step stopped at s_max. */
static double fan_line_search(fan* F, const double* dir, int* out_hit_bound)
{
    size_t m = F->m, first = m, last = 0, limit_j = m;
    double s_max = INFINITY, dmax = 0.0;
    *out_hit_bound = 0;
    for (size_t j = 0; j < m; j++) {
        if (dir[j] == 0.0) continue;
        if (first == m) first = j;
        last = j;
        double room = dir[j] > 0.0 ? (1.0 - F->t[j]) / dir[j] : F->t[j] / -dir[j];
        if (room < s_max) s_max = room, limit_j = j;
        if (fabs(dir[j]) > dmax) dmax = fabs(dir[j]);
    }
    if (first == m || !(s_max > 0.0)) return 0.0;
    size_t count = 0;
    for (size_t i = first; i <= last + 1; i++, count++) {
        tg_vec3 xi = tg_v3_sub(fan_point(F, (long)i), fan_point(F, (long)i - 1));
        tg_vec3 yi = tg_v3(0, 0, 0);
        if (i < m) yi = tg_v3_scale(tg_v3_load(F->d + 3 * i), dir[i]);
        if (i > 0 && i - 1 < m) yi = tg_v3_sub(yi, tg_v3_scale(tg_v3_load(F->d + 3 * (i - 1)), dir[i - 1]));
        tg_v3_store(xi, F->lx + 3 * count);
        tg_v3_store(yi, F->ly + 3 * count);
    }
    tg__norm_sum f = {F->lx, F->ly, count};
    tg__root_opts ro = fan_line_root_opts(F);
    double s;
    double len = tg__norm_sum_minimize(&f, 0.0, s_max, &ro, &s);
    if (!(s > 0.0) || !not_longer(len, tg__norm_sum_value(&f, 0.0), count)) return 0.0;
    for (size_t j = first; j <= last; j++) {
        double tj = F->t[j] + s * dir[j];
        F->t[j] = tj < 0.0 ? 0.0 : (tj > 1.0 ? 1.0 : tj);
    }
    if (s == s_max) {
        /* Land exactly on the bound that limited the step. */
        F->t[limit_j] = dir[limit_j] > 0.0 ? 1.0 : 0.0;
        *out_hit_bound = 1;
    }
    return s * dmax;
}

/* ---- leaving V: ComputeLargestInitialDecrease and ClampToDomain ---- */

/* The scaled derivative (r - c) + g |E' - r E| of g_i(r) = |E' - r E| + g r (eq. 65-66, 76-77):
 * g_i'(r) times |E' - r E| > 0, so it has the sign of g_i'(r). */
static double level_slope(tg_vec3 eprev, tg_vec3 e, double c, double g, double r)
{
    return (r - c) + g * tg_v3_len(tg_v3_sub(eprev, tg_v3_scale(e, r)));
}

/* The root r > 0 of g_i'(r) = 0, given g_i'(0) = g - c < 0 and g > -1 (seed §4.1: g_i'(inf) =
 * 1 + g > 0). omc = 1 - c^2 and omg = 1 - g^2, both computed without cancellation. */
static double level_root(tg_vec3 eprev, tg_vec3 e, double c, double omc, double g, double omg, const tg__root_opts* ro)
{
    if (omg >= FAN_CLOSED_FORM_MIN_SIN2) {
        /* eq. (50)/(68)/(72)/(81)/(84)/(87): r = c -+ g sqrt((1 - c^2) / (1 - g^2)); squaring made
         * one of the two extraneous, so keep the positive one whose derivative is closest to 0,
         * as the seed does, and accept it only if that derivative really vanishes. */
        double sq = sqrt(omc / omg);
        double cand[2] = {c - g * sq, c + g * sq};
        double best = -1.0, best_res = INFINITY;
        for (int k = 0; k < 2; k++) {
            if (!(cand[k] > 0.0)) continue;
            double res = fabs(level_slope(eprev, e, c, g, cand[k]));
            if (res < best_res) best_res = res, best = cand[k];
        }
        if (best > 0.0 && best_res <= FAN_ROOT_RESIDUAL * (1.0 + best)) return best;
    }
    /* Bisection (seed §3.4.1's advice for nearly degenerate triangles): bracket by doubling. */
    double lo = 0.0, hi = 1.0;
    while (level_slope(eprev, e, c, g, hi) < 0.0) {
        if (hi >= ldexp(1.0, FAN_R_MAX_EXP)) return hi;
        lo = hi;
        hi *= 2.0;
    }
    double r = hi;
    for (int i = 0; i < ro->iterations; i++) {
        r = 0.5 * (lo + hi);
        double s = level_slope(eprev, e, c, g, r);
        if (s < 0.0) lo = r;
        else if (s > 0.0) hi = r;
        else break;
    }
    return r;
}

static void zero_u(double* u, size_t n)
{
    for (size_t i = 0; i < n; i++) u[i] = 0.0;
}

double tg__fan_initial_decrease(const double q0[3], const double q1[3], const double* d, size_t n,
                                const tg__root_opts* ro, double* out_u)
{
    zero_u(out_u, n);
    tg_vec3 Q0 = tg_v3_load(q0), Q1 = tg_v3_load(q1);
    double l0 = tg_v3_len(Q0), l1 = tg_v3_len(Q1);
    /* P0 or P1 at V: the path through V is already straight from V on. */
    if (n == 0 || !(l0 > 0.0) || !(l1 > 0.0)) return 0.0;
    for (size_t i = 0; i < n; i++) {
        double len = tg_v3_len(tg_v3_load(d + 3 * i));
        if (!(len > 0.0)) return 0.0; /* a zero edge pins the path to V */
        out_u[i] = 1.0 / len;         /* u_i = v_i / |D_i| with v_i built up below (eq. 62) */
    }
    tg_vec3 xi0 = tg_v3_scale(Q0, 1.0 / l0), xi1 = tg_v3_scale(Q1, 1.0 / l1);
    tg_vec3 dlast = tg_v3_load(d + 3 * (n - 1));
    tg_vec3 e = tg_v3_scale(dlast, 1.0 / tg_v3_len(dlast));
    /* g = -E_{n-1} . xi1 (the last level's constant term); 1 - g^2 = |E x xi|^2 exactly. */
    double g = -tg_v3_dot(e, xi1);
    double omg = tg_v3_len_sq(tg_v3_cross(e, xi1));
    for (size_t i = n - 1; i >= 1; i--) {
        tg_vec3 dprev = tg_v3_load(d + 3 * (i - 1));
        tg_vec3 eprev = tg_v3_scale(dprev, 1.0 / tg_v3_len(dprev));
        double c = tg_v3_dot(eprev, e);
        /* g_i'(0) = -E_{i-1} . E_i + g (§4.1 "Necessity of g'(0) < 0"): if it is >= 0, g_i, and with
         * it H, cannot become negative. */
        if (!(g - c < 0.0)) {
            zero_u(out_u, n);
            return 0.0;
        }
        double omc = tg_v3_len_sq(tg_v3_cross(eprev, e));
        double r = level_root(eprev, e, c, omc, g, omg, ro);
        /* hat g_i(r_i) = |E_{i-1} - r_i E_i| + g r_i becomes the next level's g (eq. 74, 85). */
        double gnext = tg_v3_len(tg_v3_sub(eprev, tg_v3_scale(e, r))) + g * r;
        double umax = 0.0;
        for (size_t l = i; l < n; l++) out_u[l] *= r;
        for (size_t l = 0; l < n; l++) umax = fmax(umax, out_u[l]);
        if (umax > ldexp(1.0, FAN_U_RESCALE_EXP)) {
            for (size_t l = 0; l < n; l++) out_u[l] /= umax; /* H is homogeneous: only u's direction matters */
        }
        g = gnext;
        omg = (1.0 - g) * (1.0 + g);
        e = eprev;
    }
    /* min H = hat g_1(r_1) + ... = g - E_0 . xi0 (seed §4.5). */
    double hmin = g - tg_v3_dot(e, xi0);
    double norm = 0.0;
    for (size_t l = 0; l < n; l++) norm += out_u[l] * out_u[l];
    norm = sqrt(norm);
    if (!(hmin < 0.0) || !(norm > 0.0) || !isfinite(norm)) {
        zero_u(out_u, n);
        return 0.0;
    }
    for (size_t l = 0; l < n; l++) out_u[l] /= norm;
    return hmin;
}

double tg__fan_directional_slope(const double q0[3], const double q1[3], const double* d, size_t n, const double* u)
{
    /* eq. (61): -b0 u0 / |Delta0| + sum |u_i D_i - u_{i+1} D_{i+1}| - b1 u_{n-1} / |Delta1|. */
    if (n == 0) return 0.0;
    tg_vec3 Q0 = tg_v3_load(q0), Q1 = tg_v3_load(q1);
    double l0 = tg_v3_len(Q0), l1 = tg_v3_len(Q1);
    tg_vec3 first = tg_v3_scale(tg_v3_load(d), u[0]);
    tg_vec3 last = tg_v3_scale(tg_v3_load(d + 3 * (n - 1)), u[n - 1]);
    double s = 0.0;
    s += l0 > 0.0 ? -tg_v3_dot(first, Q0) / l0 : tg_v3_len(first);
    s += l1 > 0.0 ? -tg_v3_dot(last, Q1) / l1 : tg_v3_len(last);
    for (size_t i = 0; i + 1 < n; i++) {
        tg_vec3 a = tg_v3_scale(tg_v3_load(d + 3 * i), u[i]);
        tg_vec3 b = tg_v3_scale(tg_v3_load(d + 3 * (i + 1)), u[i + 1]);
        s += tg_v3_dist(a, b);
    }
    return s;
}

/* ClampToDomain (seed §3.4.2, §3.5): minimize L along the ray t = s u from the run [j, k]
 * (all t there 0) for s in [0, 1 / max u], the part of the ray inside [0, 1]^m; at the far end
 * the largest component is exactly 1. Returns 1 when the path got shorter. */
static int fan_clamp_to_domain(fan* F, size_t j, size_t k, const double* u)
{
    size_t imax = j;
    for (size_t l = j; l <= k; l++)
        if (u[l] > u[imax]) imax = l;
    if (!(u[imax] > 0.0)) return 0;
    double s_max = 1.0 / u[imax];
    size_t count = 0;
    for (size_t i = j; i <= k + 1; i++, count++) {
        tg_vec3 xi = tg_v3_sub(fan_point(F, (long)i), fan_point(F, (long)i - 1));
        tg_vec3 yi = tg_v3(0, 0, 0);
        if (i <= k) yi = tg_v3_scale(tg_v3_load(F->d + 3 * i), u[i]);
        if (i > j) yi = tg_v3_sub(yi, tg_v3_scale(tg_v3_load(F->d + 3 * (i - 1)), u[i - 1]));
        tg_v3_store(xi, F->lx + 3 * count);
        tg_v3_store(yi, F->ly + 3 * count);
    }
    tg__norm_sum f = {F->lx, F->ly, count};
    tg__root_opts ro = fan_line_root_opts(F);
    double s;
    double len = tg__norm_sum_minimize(&f, 0.0, s_max, &ro, &s);
    if (!(s > 0.0) || !(len < tg__norm_sum_value(&f, 0.0))) return 0;
    for (size_t l = j; l <= k; l++) {
        double tl = s * u[l];
        F->t[l] = tl > 1.0 ? 1.0 : tl;
    }
    if (s == s_max) F->t[imax] = 1.0;
    return 1;
}

/* Tests every maximal run of consecutive t == 0 (the path touches V there) for an initial
 * decrease, with the run's neighbours as the end points, and leaves V along the best ray.
 * Returns the number of runs that got shorter. */
static int fan_leave_vertex(fan* F)
{
    /* t below the 1D resolution is V for the search: a search that drives t towards V converges
     * to such values without reaching 0 exactly, and must not hide a run from this test. */
    const double at_v = F->step_tol;
    int changed = 0;
    size_t j = 0;
    while (j < F->m) {
        if (F->t[j] > at_v) {
            j++;
            continue;
        }
        size_t k = j;
        while (k + 1 < F->m && F->t[k + 1] <= at_v) k++;
        double q0[3], q1[3];
        tg_v3_store(fan_point(F, (long)j - 1), q0);
        tg_v3_store(fan_point(F, (long)k + 1), q1);
        for (size_t l = j; l <= k; l++) F->t[l] = 0.0; /* ClampToDomain starts from V */
        double hmin = tg__fan_initial_decrease(q0, q1, F->d + 3 * j, k - j + 1, &F->ro, F->u + j);
        if (hmin < 0.0 && fan_clamp_to_domain(F, j, k, F->u)) changed++;
        j = k + 1;
    }
    return changed;
}

/* ---- search strategies (seed §3.4.2) ---- */

/* 1. Coordinate-direction search (the seed's GetPath loop): sweeps until the projected gradient
 * or the change of t is negligible. */
static void strategy_coordinate(fan* F)
{
    while (F->budget > 0) {
        F->budget--;
        if (fan_projected_gradient(F) <= F->grad_tol) return;
        if (fan_sweep(F) <= F->step_tol) return;
    }
}

/* 2. Powell-style: after each coordinate sweep, a line search along the sweep's net displacement
 * (the seed's "approximate conjugate direction, the unit-length vector from the initial location
 * to the final location"), which follows the long valleys that make coordinate search zig-zag. */
static void strategy_powell(fan* F)
{
    while (F->budget > 0) {
        F->budget--;
        if (fan_projected_gradient(F) <= F->grad_tol) return;
        memcpy(F->tsave, F->t, F->m * sizeof(double));
        if (fan_sweep(F) <= F->step_tol) return;
        for (size_t j = 0; j < F->m; j++) F->u[j] = F->t[j] - F->tsave[j];
        int hit;
        fan_line_search(F, F->u, &hit);
    }
}

/* a^T H b with H the Hessian of L (eq. 57-58), written per segment: the Hessian of |X| for X
 * linear in t is J^T (I - n n^T) J / |X|, n = X / |X|. Returns +inf at a zero-length segment
 * that a or b moves (H is unbounded there). */
static double fan_hessian_form(const fan* F, const double* a, const double* b)
{
    double sum = 0.0;
    tg_vec3 prev = fan_point(F, -1);
    for (size_t i = 0; i <= F->m; i++) {
        tg_vec3 cur = fan_point(F, (long)i);
        tg_vec3 x = tg_v3_sub(cur, prev);
        prev = cur;
        tg_vec3 ya = tg_v3(0, 0, 0), yb = tg_v3(0, 0, 0);
        if (i < F->m) {
            tg_vec3 di = tg_v3_load(F->d + 3 * i);
            ya = tg_v3_scale(di, a[i]);
            yb = tg_v3_scale(di, b[i]);
        }
        if (i > 0) {
            tg_vec3 dp = tg_v3_load(F->d + 3 * (i - 1));
            ya = tg_v3_sub(ya, tg_v3_scale(dp, a[i - 1]));
            yb = tg_v3_sub(yb, tg_v3_scale(dp, b[i - 1]));
        }
        double len = tg_v3_len(x);
        if (!(len > 0.0)) {
            if (tg_v3_len_sq(ya) > 0.0 || tg_v3_len_sq(yb) > 0.0) return INFINITY;
            continue;
        }
        tg_vec3 n = tg_v3_scale(x, 1.0 / len);
        tg_vec3 pa = tg_v3_sub(ya, tg_v3_scale(n, tg_v3_dot(ya, n)));
        tg_vec3 pb = tg_v3_sub(yb, tg_v3_scale(n, tg_v3_dot(yb, n)));
        sum += tg_v3_dot(pa, pb) / len;
    }
    return sum;
}

/* 3. Conjugate gradient (seed §3.4.2 item 3): the next direction is C = -grad + beta V with
 * C^T H V = 0 for the previous direction V and the Hessian H at the current point (Daniel's
 * choice beta = grad^T H V / V^T H V). Components that would leave [0, 1]^m are dropped; after a
 * step that stops on a bound (the active set changed), at a kink, or when C is not a descent
 * direction, the search restarts from the steepest descent direction. */
static void strategy_cg(fan* F)
{
    int restart = 1;
    double* gprev = F->tsave; /* the previous projected gradient */
    while (F->budget > 0) {
        F->budget--;
        if (fan_projected_gradient(F) <= F->grad_tol) return;
        /* Powell's restart test: on a quadratic successive gradients are orthogonal; when they
         * are far from it, L is not quadratic enough here for conjugacy to help. */
        double gg = 0.0, ggp = 0.0;
        for (size_t j = 0; j < F->m; j++) gg += F->g[j] * F->g[j], ggp += F->g[j] * gprev[j];
        if (!restart && fabs(ggp) >= 0.2 * gg) restart = 1;
        memcpy(gprev, F->g, F->m * sizeof(double));
        double beta = 0.0;
        if (!restart) {
            double vhv = fan_hessian_form(F, F->dprev, F->dprev);
            double ghv = fan_hessian_form(F, F->g, F->dprev);
            if (vhv > 0.0 && isfinite(vhv) && isfinite(ghv)) beta = ghv / vhv;
            else restart = 1;
        }
        double slope = 0.0;
        for (size_t j = 0; j < F->m; j++) {
            double c = -F->g[j] + beta * F->dprev[j];
            if ((F->t[j] <= 0.0 && c < 0.0) || (F->t[j] >= 1.0 && c > 0.0) || F->dlen[j] == 0.0) c = 0.0;
            F->u[j] = c;
            slope += c * F->g[j];
        }
        if (!(slope < 0.0)) {
            for (size_t j = 0; j < F->m; j++) F->u[j] = -F->g[j];
            restart = 1;
        }
        int hit;
        double moved = fan_line_search(F, F->u, &hit);
        if (moved <= F->step_tol) {
            /* Steepest descent can stall on a badly scaled L with the gradient far from 0; a
             * coordinate sweep (exact 1D minima) then decides whether anything can still move. */
            if (restart && fan_sweep(F) <= F->step_tol) return;
            restart = 1;
            continue;
        }
        memcpy(F->dprev, F->u, F->m * sizeof(double));
        restart = hit;
    }
}

/* Segment vectors X_i = M_i - M_{i-1} into F->lx and their lengths into F->seglen, i = 0..m. */
static void fan_segments(fan* F)
{
    tg_vec3 prev = fan_point(F, -1);
    for (size_t i = 0; i <= F->m; i++) {
        tg_vec3 cur = fan_point(F, (long)i);
        tg_vec3 x = tg_v3_sub(cur, prev);
        tg_v3_store(x, F->lx + 3 * i);
        F->seglen[i] = tg_v3_len(x);
        prev = cur;
    }
}

/* From the cached segments: the projected gradient (eq. 56, one-sided at zero-length segments)
 * into F->g and the free-variable flags into F->flags (a variable is held when it sits on a
 * bound its gradient pushes against). Returns max_j |g_j| / |D_j|. */
static double fan_newton_gradient(fan* F)
{
    double worst = 0.0;
    for (size_t j = 0; j < F->m; j++) {
        tg_vec3 dj = tg_v3_load(F->d + 3 * j);
        double la = F->seglen[j], lb = F->seglen[j + 1], smooth = 0.0, kinks = 0.0;
        if (la > 0.0) smooth += tg_v3_dot(dj, tg_v3_load(F->lx + 3 * j)) / la;
        else kinks += F->dlen[j];
        if (lb > 0.0) smooth -= tg_v3_dot(dj, tg_v3_load(F->lx + 3 * (j + 1))) / lb;
        else kinks += F->dlen[j];
        double gr = smooth + kinks, gl = smooth - kinks, g = 0.0;
        int held = F->dlen[j] == 0.0 || (F->t[j] <= 0.0 && gr >= 0.0) || (F->t[j] >= 1.0 && gl <= 0.0);
        if (!held) g = gr < 0.0 ? gr : (gl > 0.0 ? gl : 0.0);
        F->flags[j] = held ? 0.0 : 1.0;
        F->g[j] = g;
        if (g != 0.0 && fabs(g) / F->dlen[j] > worst) worst = fabs(g) / F->dlen[j];
    }
    return worst;
}

/* The projected-Newton direction: H delta = -g on the free variables, with H the tridiagonal
 * Hessian of eq. (57)-(58), positive definite there (§4.2), assembled from the cached segments
 * as in fan_hessian_form and solved by the Thomas algorithm (no pivoting needed for a symmetric
 * positive definite matrix). Writes delta to F->u; returns 0 when H is unbounded (a zero-length
 * segment next to a free variable) or not numerically positive definite. */
static int fan_newton_direction(fan* F)
{
    size_t m = F->m;
    double* diag = F->dprev; /* this strategy uses neither dprev nor tsave otherwise */
    double* off = F->tsave;  /* off[j] = H[j][j + 1] */
    double* cp = F->aux1;
    double* dp = F->aux2;
    for (size_t j = 0; j < m; j++) diag[j] = off[j] = 0.0;
    for (size_t i = 0; i <= m; i++) {
        int has_right = i < m && F->flags[i] != 0.0, has_left = i > 0 && F->flags[i - 1] != 0.0;
        if (!has_right && !has_left) continue;
        double len = F->seglen[i];
        if (!(len > 0.0)) return 0;
        tg_vec3 n = tg_v3_scale(tg_v3_load(F->lx + 3 * i), 1.0 / len);
        /* D^T (I - n n^T) D' = (D x n) . (D' x n) (Lagrange's identity), no cancellation */
        tg_vec3 cr = has_right ? tg_v3_cross(tg_v3_load(F->d + 3 * i), n) : tg_v3(0, 0, 0);
        tg_vec3 cl = has_left ? tg_v3_cross(tg_v3_load(F->d + 3 * (i - 1)), n) : tg_v3(0, 0, 0);
        if (has_right) diag[i] += tg_v3_len_sq(cr) / len;
        if (has_left) diag[i - 1] += tg_v3_len_sq(cl) / len;
        if (has_right && has_left) off[i - 1] -= tg_v3_dot(cl, cr) / len;
    }
    /* forward elimination over each run of free variables (held ones decouple the runs) */
    for (size_t j = 0; j < m; j++) {
        if (F->flags[j] == 0.0) {
            cp[j] = dp[j] = 0.0;
            continue;
        }
        int linked = j > 0 && F->flags[j - 1] != 0.0;
        double sub = linked ? off[j - 1] : 0.0;
        double den = diag[j] - (linked ? sub * cp[j - 1] : 0.0);
        if (!(den > 0.0) || !isfinite(den)) return 0;
        cp[j] = (j + 1 < m && F->flags[j + 1] != 0.0) ? off[j] / den : 0.0;
        dp[j] = (-F->g[j] - (linked ? sub * dp[j - 1] : 0.0)) / den;
    }
    double next = 0.0;
    for (size_t j = m; j-- > 0;) {
        if (F->flags[j] == 0.0) {
            F->u[j] = next = 0.0;
            continue;
        }
        F->u[j] = next = dp[j] - cp[j] * next;
        if (!isfinite(next)) return 0;
    }
    return 1;
}

/* 4. Projected Newton (not in the seed; its Hessian is): Newton directions on the free
 * variables with an exact line search, quadratic convergence near the minimum. Converged when
 * the Newton step itself is below the 1D resolution. Where the Hessian is unbounded it falls back
 * to a coordinate sweep. */
static void strategy_newton(fan* F)
{
    while (F->budget > 0) {
        F->budget--;
        fan_segments(F);
        if (fan_newton_gradient(F) <= F->grad_tol) return;
        if (!fan_newton_direction(F)) {
            if (fan_sweep(F) <= F->step_tol) return;
            continue;
        }
        double step = 0.0;
        for (size_t j = 0; j < F->m; j++) step = fmax(step, fabs(F->u[j]));
        if (step <= F->step_tol) return;
        int hit;
        if (fan_line_search(F, F->u, &hit) <= F->step_tol && fan_sweep(F) <= F->step_tol) return;
    }
}

static void fan_run_strategy(fan* F)
{
    if (F->strategy == TG_FAN_NEWTON) strategy_newton(F);
    else if (F->strategy == TG_FAN_CG) strategy_cg(F);
    else if (F->strategy == TG_FAN_POWELL) strategy_powell(F);
    else strategy_coordinate(F);
}

/* ---- entry point ---- */

static int all_finite(const double* p, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(p[i])) return 0;
    return 1;
}

/* The search: leave V where the path touches it, search, and repeat while leaving V helps. Each
 * round spends at least one outer iteration of the budget, so this terminates. */
static void fan_minimize(fan* F)
{
    for (int round = 0; F->budget > 0; round++) {
        int left = fan_leave_vertex(F);
        if (round > 0 && !left) return;
        int any = 0;
        for (size_t j = 0; j < F->m; j++) any |= F->t[j] != 0.0;
        if (!any) return; /* still the path through V: it is the shortest */
        F->budget--;
        fan_run_strategy(F);
    }
}

/* Edges V -> W_{i-1} and V -> W_i on the same ray (a zero-area triangle between them; exact test
 * with orient2d on the three coordinate projections of V, W_{i-1}, W_i). The points are first
 * scaled by the kernel's power-of-two factor (exact), which brings tiny or huge fans into the
 * predicate's exact range. */
static int same_ray(const double* v, const double* a, const double* b, const double* da, const double* db,
                    double scale)
{
    for (int k = 0; k < 3; k++) {
        int k1 = (k + 1) % 3;
        double pv[2] = {v[k] * scale, v[k1] * scale}, pa[2] = {a[k] * scale, a[k1] * scale};
        double pb[2] = {b[k] * scale, b[k1] * scale};
        if (tg__orient2d_sign(pv, pa, pb) != 0) return 0;
    }
    return tg_v3_dot(tg_v3_load(da), tg_v3_load(db)) > 0.0;
}

/* Consecutive edges on one ray: an optimal path crosses them at one point (moving the crossing of
 * the longer edge onto the other's is never longer, by the triangle inequality), so they become
 * one variable of the reduced fan F, with the shorter edge. Without this the length has a kink
 * along t_{i-1} |D_{i-1}| = t_i |D_i| that stalls every search. Fills F->d, F->dlen, F->m and the
 * start values F->t (from t_init, clamped, mapped to the same points on the ray), lfull (|D_i| of
 * the input's edges) and group (input edge -> reduced edge). Returns the reduced count. */
static size_t fan_merge_collinear(fan* F, const double* v, const double* w, const double* dfull, double* lfull,
                                  size_t m, double scale, const double* t_init, size_t* group)
{
    size_t mr = 0;
    for (size_t i = 0; i < m; i++) {
        lfull[i] = tg_v3_len(tg_v3_load(dfull + 3 * i));
        int merge = i > 0 && lfull[i] > 0.0 && lfull[i - 1] > 0.0 &&
                    same_ray(v, w + 3 * (i - 1), w + 3 * i, dfull + 3 * (i - 1), dfull + 3 * i, scale);
        if (!merge) {
            memcpy(F->d + 3 * mr, dfull + 3 * i, 3 * sizeof(double));
            F->dlen[mr] = lfull[i];
            F->t[mr] = INFINITY;
            mr++;
        } else if (lfull[i] < F->dlen[mr - 1]) {
            memcpy(F->d + 3 * (mr - 1), dfull + 3 * i, 3 * sizeof(double));
            F->dlen[mr - 1] = lfull[i];
        }
        group[i] = mr - 1;
    }
    F->m = mr;
    for (size_t i = 0; i < m; i++) {
        double ti = t_init ? t_init[i] : 0.0;
        ti = ti < 0.0 ? 0.0 : (ti > 1.0 ? 1.0 : ti);
        size_t gi = group[i];
        double tr = F->dlen[gi] > 0.0 ? ti * lfull[i] / F->dlen[gi] : ti; /* the same point on the ray */
        if (tr < F->t[gi]) F->t[gi] = tr > 1.0 ? 1.0 : tr;
    }
    return mr;
}

/* L(t) of eq. (55) for the input's own edges: the sum of the m + 1 segment lengths. */
static double full_length(const double* q0, const double* q1, const double* d, size_t m, const double* t)
{
    double sum = 0.0;
    tg_vec3 prev = tg_v3_load(q0);
    for (size_t i = 0; i < m; i++) {
        tg_vec3 cur = tg_v3_scale(tg_v3_load(d + 3 * i), t[i]);
        sum += tg_v3_dist(cur, prev);
        prev = cur;
    }
    return sum + tg_v3_dist(tg_v3_load(q1), prev);
}

tg_status tg__fan_path_minimize_with(const tg_allocator* a, const double p0[3], const double p1[3], const double v[3],
                                     const double* w, size_t m, const double* t_init,
                                     const tg_geodesic_kernel_options* opts, double* out_t, double* out_length,
                                     int* out_decreased)
{
    if (out_decreased) *out_decreased = 0;
    if (!p0 || !p1 || !v || !out_length || (m > 0 && (!w || !out_t)) || !tg__kernel_options_valid(opts))
        return TG_ERR_INVALID_ARGUMENT;
    if (!all_finite(p0, 3) || !all_finite(p1, 3) || !all_finite(v, 3) || (m > 0 && !all_finite(w, 3 * m)) ||
        (t_init && !all_finite(t_init, m)))
        return TG_ERR_INVALID_ARGUMENT;
    /* Scratch: the reduced fan (FAN_SCRATCH_PER_EDGE and _PER_SEGMENT doubles per edge), the
     * input's own edges and lengths (4 per edge), and the edge -> group map. */
    size_t per_edge, doubles_count;
    const size_t per_edge_doubles = FAN_SCRATCH_PER_EDGE + FAN_SCRATCH_PER_SEGMENT + 4;
    if (tg__mul_overflows(m, per_edge_doubles, &per_edge) || per_edge > SIZE_MAX / 2 - 4 * FAN_SCRATCH_PER_SEGMENT ||
        m > SIZE_MAX / (2 * sizeof(size_t)))
        return TG_ERR_OUT_OF_MEMORY;
    doubles_count = per_edge + FAN_SCRATCH_PER_SEGMENT;
    double stack[FAN_STACK_EDGES * (FAN_SCRATCH_PER_EDGE + FAN_SCRATCH_PER_SEGMENT + 4) + FAN_SCRATCH_PER_SEGMENT];
    size_t stack_group[FAN_STACK_EDGES];
    double* heap = NULL;
    size_t* heap_group = NULL;
    double* buf = stack;
    size_t* group = stack_group;
    if (m > FAN_STACK_EDGES) {
        heap = (double*)tg__alloc_array(a, doubles_count, sizeof(double));
        heap_group = (size_t*)tg__alloc_array(a, m, sizeof(size_t));
        if (!heap || !heap_group) {
            tg__free(a, heap);
            tg__free(a, heap_group);
            return TG_ERR_OUT_OF_MEMORY;
        }
        buf = heap;
        group = heap_group;
    }
    fan F;
    memset(&F, 0, sizeof F);
    double* dfull = buf;             /* 3m: W_i - V */
    double* lfull = dfull + 3 * m;   /* m: |W_i - V| */
    F.d = lfull + m;
    F.dlen = F.d + 3 * m;
    F.t = F.dlen + m;
    F.u = F.t + m;
    F.g = F.u + m;
    F.dprev = F.g + m;
    F.tsave = F.dprev + m;
    F.aux1 = F.tsave + m;
    F.aux2 = F.aux1 + m;
    F.flags = F.aux2 + m;
    F.lx = F.flags + m;
    F.ly = F.lx + 3 * (m + 1);
    F.seglen = F.ly + 3 * (m + 1);
    for (int k = 0; k < 3; k++) {
        F.q0[k] = p0[k] - v[k];
        F.q1[k] = p1[k] - v[k];
    }
    for (size_t i = 0; i < 3 * m; i++) dfull[i] = w[i] - v[i % 3];
    tg_status status = TG_OK;
    if (!all_finite(F.q0, 3) || !all_finite(F.q1, 3) || !all_finite(dfull, 3 * m)) {
        status = TG_ERR_INVALID_ARGUMENT; /* differences of finite input overflowed */
        goto done;
    }
    {
        double q[6] = {F.q0[0], F.q0[1], F.q0[2], F.q1[0], F.q1[1], F.q1[2]};
        double scale = tg__kernel_rescale(q, 6, dfull, 3 * m);
        memcpy(F.q0, q, 3 * sizeof(double));
        memcpy(F.q1, q + 3, 3 * sizeof(double));
        double through_v = tg_v3_len(tg_v3_load(F.q0)) + tg_v3_len(tg_v3_load(F.q1));
        /* The length is a sum of m + 1 norms, each within ~2 eps of exact; a decrease below 4 eps
         * per term can be rounding alone, and must not count as a shorter path. */
        double noise = 4.0 * DBL_EPSILON * (double)(m + 2) * through_v;
        if (m == 0) {
            double direct = tg_v3_dist(tg_v3_load(F.q0), tg_v3_load(F.q1));
            *out_length = direct / scale;
            if (out_decreased) *out_decreased = direct < through_v - noise;
            goto done;
        }
        size_t mr = fan_merge_collinear(&F, v, w, dfull, lfull, m, scale, t_init, group);
        F.ro = tg__root_opts_make(opts);
        F.strategy = opts && opts->strategy != TG_FAN_DEFAULT ? (int)opts->strategy : TG_FAN_CG;
        /* Default caps: coordinate sweeps converge linearly, at a rate that degrades like 1 - c / m^2
         * on long fans (the Hessian is tridiagonal, like a 1D Laplacian), so they get O(m^2) sweeps;
         * Newton and conjugate gradient need O(m) steps. */
        long mm = (long)mr + 1;
        long cap = (opts && opts->max_iterations > 0) ? opts->max_iterations
                   : (F.strategy == TG_FAN_COORDINATE || F.strategy == TG_FAN_POWELL) ? 100 + 50 * mm * mm
                                                                                       : 100 + 20 * mm;
        F.budget = cap;
        /* Convergence thresholds: the 1D searches resolve t to 2^-n (n = ceil(digits log2 10));
         * a sweep or step that moves no t by more than a few of those has stalled. dL/dt_j / |D_j|
         * is a difference of cosines (of the path's angles with the edge on its two sides), so a
         * projected gradient below 10^-digits of |D_j| is zero to the requested digits; it is
         * never asked below 64 ulps, the rounding noise of those cosines (unit vectors of short,
         * cancelling differences M_i - M_{i-1}). */
        F.step_tol = ldexp(4.0, -F.ro.iterations);
        F.grad_tol = fmax(pow(10.0, -(double)(opts && opts->digits > 0 ? opts->digits : TG_KERNEL_DEFAULT_DIGITS)),
                          64.0 * DBL_EPSILON);
        fan_minimize(&F);
        for (size_t i = 0; i < m; i++) {
            size_t gi = group[i];
            double ti = lfull[i] > 0.0 ? F.t[gi] * (F.dlen[gi] / lfull[i]) : F.t[gi];
            out_t[i] = ti > 1.0 ? 1.0 : ti;
        }
        double len = full_length(F.q0, F.q1, dfull, m, out_t);
        if (len < through_v - noise) {
            *out_length = len / scale;
            if (out_decreased) *out_decreased = 1;
        } else {
            for (size_t j = 0; j < m; j++) out_t[j] = 0.0;
            *out_length = through_v / scale;
        }
    }
done:
    tg__free(a, heap);
    tg__free(a, heap_group);
    return status;
}

tg_status tg_fan_path_minimize(const double p0[3], const double p1[3], const double v[3], const double* w,
                               size_t m, const double* t_init, const tg_geodesic_kernel_options* opts,
                               double* out_t, double* out_length, int* out_decreased)
{
    return tg__fan_path_minimize_with(NULL, p0, p1, v, w, m, t_init, opts, out_t, out_length, out_decreased);
}
