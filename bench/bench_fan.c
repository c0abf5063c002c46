/* bench_fan.c - the fan minimizer's search strategies side by side: microseconds per minimization
 * and the final length, on random 3-, 4-, 5- and 12-triangle fans.
 * Based on: seed 002 §3.4.2 (coordinate-direction search, Powell's direction set, conjugate
 *   gradient) plus the projected Newton strategy; §2.4 (bisection roots) vs. the faster roots.
 *
 * Usage: bench_fan [fans_per_row]   (default 2000). Every row uses the same fans for every column
 * (fixed seeds). Fans have total angle below pi at V, so every path can be shortened and the
 * search always runs; "flat" fans lie in a plane with random edge lengths (mostly non-convex:
 * the straight segment leaves the fan and the minimum has some t = 1), "curved" fans turn each
 * edge about a random axis. excess = (mean L - mean of the best L per fan) / mean best L. */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>

#include "trigeo.h"

#define MAX_EDGES 16

typedef struct rng { unsigned long long s; } rng;
static double unit(rng* r)
{
    r->s ^= r->s >> 12, r->s ^= r->s << 25, r->s ^= r->s >> 27;
    return (double)((r->s * 2685821657736338717ull) >> 11) * (1.0 / 9007199254740992.0);
}
static double range(rng* r, double lo, double hi) { return lo + (hi - lo) * unit(r); }

typedef struct fan_case { double p0[3], p1[3], v[3], w[3 * MAX_EDGES]; } fan_case;

static void make_fan(rng* r, int curved, size_t m, fan_case* f)
{
    const double pi = 3.14159265358979323846;
    double total = range(r, 0.3 * pi, 0.95 * pi);
    double dir[3] = {1, 0, 0}, pts[MAX_EDGES + 2][3];
    for (size_t i = 0; i <= m + 1; i++) {
        double rad = range(r, 0.3, 2.0);
        for (int k = 0; k < 3; k++) pts[i][k] = rad * dir[k];
        double ax[3] = {0, 0, 1};
        if (curved) {
            ax[0] = range(r, -1, 1), ax[1] = range(r, -1, 1), ax[2] = range(r, -1, 1);
            double dd = ax[0] * dir[0] + ax[1] * dir[1] + ax[2] * dir[2];
            for (int k = 0; k < 3; k++) ax[k] -= dd * dir[k];
            double al = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
            for (int k = 0; k < 3; k++) ax[k] /= al;
        }
        double ang = total / (double)(m + 1) * range(r, 0.6, 1.4);
        double c[3] = {ax[1] * dir[2] - ax[2] * dir[1], ax[2] * dir[0] - ax[0] * dir[2], ax[0] * dir[1] - ax[1] * dir[0]};
        for (int k = 0; k < 3; k++) dir[k] = cos(ang) * dir[k] + sin(ang) * c[k];
    }
    memset(f->v, 0, sizeof f->v);
    memcpy(f->p0, pts[0], sizeof f->p0);
    for (size_t i = 0; i < m; i++) memcpy(f->w + 3 * i, pts[i + 1], 3 * sizeof(double));
    memcpy(f->p1, pts[m + 1], sizeof f->p1);
}

static double now_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts); /* CPU time: steadier than wall time on a shared machine */
    return ts.tv_sec * 1e6 + ts.tv_nsec * 1e-3;
}

typedef struct column { const char* name; tg_fan_strategy strategy; tg_root_method root; } column;

int main(int argc, char** argv)
{
    int n = argc > 1 ? atoi(argv[1]) : 2000;
    if (n < 1) n = 1;
    const size_t sizes[4] = {2, 3, 4, 11}; /* interior edges: 3-, 4-, 5-, 12-triangle fans */
    const column cols[] = {
        {"coordinate", TG_FAN_COORDINATE, TG_ROOT_BISECTION}, {"powell", TG_FAN_POWELL, TG_ROOT_BISECTION},
        {"cg", TG_FAN_CG, TG_ROOT_BISECTION},                 {"newton", TG_FAN_NEWTON, TG_ROOT_BISECTION},
        {"coordinate", TG_FAN_COORDINATE, TG_ROOT_UNFOLD},    {"powell", TG_FAN_POWELL, TG_ROOT_UNFOLD},
        {"cg", TG_FAN_CG, TG_ROOT_NEWTON},                    {"newton", TG_FAN_NEWTON, TG_ROOT_NEWTON},
    };
    const int ncols = (int)(sizeof cols / sizeof cols[0]);
    fan_case* fans = (fan_case*)malloc((size_t)n * sizeof(fan_case));
    double* best = (double*)malloc((size_t)n * sizeof(double));
    double* lens = (double*)malloc((size_t)n * ncols * sizeof(double));
    if (!fans || !best || !lens) return 2;
    printf("bench_fan: %d fans per row; us = CPU microseconds per minimization (mean), L = mean final length,\n"
           "excess = relative excess of the mean L over the mean of the best L per fan\n\n", n);
    for (int table = 0; table < 2; table++) {
        printf("%s\n", table == 0 ? "1D roots: bisection, n = ceil(15 log2 10) = 50 steps (seed §2.4)"
                                  : "1D roots: unfolding closed form (coordinate, powell sweeps), safeguarded Newton (line searches)");
        printf("%-7s %-9s", "", "");
        for (int c = table * 4; c < table * 4 + 4; c++) printf(" | %-27s", cols[c].name);
        printf("\n%-7s %-9s", "fan", "kind");
        for (int c = table * 4; c < table * 4 + 4; c++) printf(" | %-10s %7s %8s", "L", "us", "excess");
        printf("\n");
        for (int kind = 0; kind < 2; kind++) {
            for (int si = 0; si < 4; si++) {
                size_t m = sizes[si];
                rng r = {0x5EED0000ull + 977 * m + (unsigned)kind};
                for (int i = 0; i < n; i++) make_fan(&r, kind, m, &fans[i]);
                double us[8] = {0}, mean_l[8] = {0}, mean_best = 0.0;
                for (int c = 0; c < ncols; c++) {
                    tg_geodesic_kernel_options o = {0};
                    o.strategy = cols[c].strategy;
                    o.root_method = cols[c].root;
                    double t[MAX_EDGES], len;
                    int dec;
                    double t0 = now_us();
                    for (int i = 0; i < n; i++) {
                        fan_case* f = &fans[i];
                        if (tg_fan_path_minimize(f->p0, f->p1, f->v, f->w, m, NULL, &o, t, &len, &dec) != TG_OK) return 3;
                        lens[(size_t)c * n + i] = len;
                    }
                    us[c] = (now_us() - t0) / n;
                }
                for (int i = 0; i < n; i++) {
                    best[i] = INFINITY;
                    for (int c = 0; c < ncols; c++) best[i] = fmin(best[i], lens[(size_t)c * n + i]);
                    mean_best += best[i] / n;
                }
                for (int c = 0; c < ncols; c++)
                    for (int i = 0; i < n; i++) mean_l[c] += lens[(size_t)c * n + i] / n;
                printf("%2zu tri   %-9s", m + 1, kind ? "curved" : "flat");
                for (int c = table * 4; c < table * 4 + 4; c++)
                    printf(" | %-10.8f %7.2f %8.1e", mean_l[c], us[c], (mean_l[c] - mean_best) / mean_best);
                printf("\n");
            }
        }
        printf("\n");
    }
    free(fans);
    free(best);
    free(lens);
    return 0;
}
