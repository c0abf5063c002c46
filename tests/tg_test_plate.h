/* tg_test_plate.h - the closed holed plate of the geodesic tests, the flat-CAD case (rows of
 * collinear vertices, holes with walls). It is the one ../shared/tools/plate.py writes (same
 * vertex and face numbering): N x N unit cells 400 wide, every HOLE_EVERY-th cell in both
 * directions a square hole, top and bottom triangulated on the grid with alternating diagonals,
 * walls around the holes and the rim. */
#ifndef TG_TEST_PLATE_H
#define TG_TEST_PLATE_H

#include <stdbool.h>
#include <stdlib.h>
#include <trigeo.h>

#include "tg_test.h"

typedef struct plate {
    double* xyz;
    uint32_t* tri;
    size_t nv, nf;
    int32_t* vid; /* (n + 1)^2 * 2 */
    int n;
} plate;

static bool is_hole(int n, int every, int i, int j)
{
    return i % every == every / 2 && j % every == every / 2 && 0 < i && i < n - 1 && 0 < j && j < n - 1;
}

static uint32_t pv(plate* p, double s, double thick, int x, int y, int z)
{
    int32_t* id = &p->vid[((size_t)x * (size_t)(p->n + 1) + (size_t)y) * 2 + (size_t)z];
    if (*id < 0) {
        *id = (int32_t)p->nv;
        p->xyz[3 * p->nv] = x * s, p->xyz[3 * p->nv + 1] = y * s, p->xyz[3 * p->nv + 2] = z * thick;
        p->nv++;
    }
    return (uint32_t)*id;
}

static void pf(plate* p, uint32_t a, uint32_t b, uint32_t c)
{
    p->tri[3 * p->nf] = a, p->tri[3 * p->nf + 1] = b, p->tri[3 * p->nf + 2] = c;
    p->nf++;
}

static tg_mesh* make_plate(int n, int every, double thick)
{
    plate p = {0};
    p.n = n;
    size_t cap_v = (size_t)(n + 1) * (size_t)(n + 1) * 2, cap_f = (size_t)n * (size_t)n * 12;
    p.xyz = malloc(3 * cap_v * sizeof(double));
    p.tri = malloc(3 * cap_f * sizeof(uint32_t));
    p.vid = malloc(cap_v * sizeof(int32_t));
    for (size_t i = 0; i < cap_v; ++i) p.vid[i] = -1;
    double s = 400.0 / n;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            if (is_hole(n, every, i, j)) continue;
            bool even = (i + j) % 2 == 0;
            uint32_t a = pv(&p, s, thick, i, j, 1), b = pv(&p, s, thick, i + 1, j, 1);
            uint32_t c = pv(&p, s, thick, i + 1, j + 1, 1), d = pv(&p, s, thick, i, j + 1, 1);
            if (even) pf(&p, a, b, c), pf(&p, a, c, d);
            else pf(&p, a, b, d), pf(&p, b, c, d);
            a = pv(&p, s, thick, i, j, 0), b = pv(&p, s, thick, i + 1, j, 0);
            c = pv(&p, s, thick, i + 1, j + 1, 0), d = pv(&p, s, thick, i, j + 1, 0);
            if (even) pf(&p, a, c, b), pf(&p, a, d, c);
            else pf(&p, a, d, b), pf(&p, b, d, c);
            static const int side[4][6] = {{0, -1, 0, 0, 1, 0}, {1, 0, 1, 0, 1, 1}, {0, 1, 1, 1, 0, 1}, {-1, 0, 0, 1, 0, 0}};
            for (int k = 0; k < 4; ++k) {
                int ni = i + side[k][0], nj = j + side[k][1];
                bool cell = ni >= 0 && ni < n && nj >= 0 && nj < n && !is_hole(n, every, ni, nj);
                if (cell) continue; /* a wall on this side, facing out of the cell */
                int px = i + side[k][2], py = j + side[k][3], qx = i + side[k][4], qy = j + side[k][5];
                uint32_t p0 = pv(&p, s, thick, px, py, 0), p1 = pv(&p, s, thick, qx, qy, 0);
                uint32_t t0 = pv(&p, s, thick, px, py, 1), t1 = pv(&p, s, thick, qx, qy, 1);
                pf(&p, p0, p1, t1), pf(&p, p0, t1, t0);
            }
        }
    }
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(p.xyz, p.nv, p.tri, p.nf, NULL, NULL, &m), TG_OK);
    free(p.xyz), free(p.tri), free(p.vid);
    return m;
}

#endif
