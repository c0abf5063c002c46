/* test_bvh_oom.c - allocation failures through the BVH build on a mesh large enough to reach its
 * large-build paths (more than 64 top-level subtree tasks of at most 4096 faces: a 409,600-face
 * grid), at each allocation (all of the top levels', a dense sample after): each run ends in TG_OK or TG_ERR_OUT_OF_MEMORY with every block
 * freed (the task stack's growth used to lose the old block when realloc failed). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>

#include "tg_test.h"

int main(void)
{
    enum { N = 452 }; /* (N - 1)^2 * 2 = 406,802 faces */
    double* xyz = malloc((size_t)N * N * 3 * sizeof *xyz);
    uint32_t* tri = malloc((size_t)(N - 1) * (N - 1) * 6 * sizeof *tri);
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) {
            double* p = xyz + 3 * ((size_t)i * N + (size_t)j);
            p[0] = i, p[1] = j, p[2] = 0.01 * ((i * 7 + j * 13) % 5);
        }
    size_t f = 0;
    for (int i = 0; i + 1 < N; ++i)
        for (int j = 0; j + 1 < N; ++j) {
            uint32_t a = (uint32_t)(i * N + j), b = a + 1, c = a + N, d = c + 1;
            uint32_t* t = tri + 6 * f++;
            t[0] = a, t[1] = b, t[2] = d, t[3] = a, t[4] = d, t[5] = c;
        }
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(xyz, (size_t)N * N, tri, f * 2, NULL, NULL, &m), TG_OK);
    free(xyz), free(tri);
    if (!m) return tg_test_finish();
    long total = -1;
    /* every allocation point of the top levels, where the task stack grows, then a sample of the
     * subtree and leaf builds: every 5th in the full suite (25th under the sanitizers), every
     * 25th (100th) in the fast one */
    const long stride = TG_TEST_DEPTH(TG_TEST_WORK(5, 25), TG_TEST_WORK(25, 100));
    for (long k = 0;; k += k < 120 ? 1 : stride) {
        tg_test_counting c = {0, 0, k, 0};
        tg_allocator a = tg_test_failing_allocator(&c);
        tg_bvh_options o;
        memset(&o, 0, sizeof o);
        o.allocator = &a;
        o.threads = 2;
        tg_bvh* bvh = NULL;
        tg_status st = tg_bvh_create(m, &o, &bvh);
        tg_bvh_destroy(bvh);
        CHECK_MSG(c.allocs == c.frees, "fail at %ld: %ld allocations, %ld frees", k, c.allocs, c.frees);
        if (st == TG_OK) {
            total = k;
            break;
        }
        CHECK_MSG(st == TG_ERR_OUT_OF_MEMORY, "fail at %ld: %s", k, tg_status_name(st));
        if (k > 5000) break;
    }
    printf("BVH build of %zu faces: %ld allocation points, failed at every one up to 120, then every %ldth\n",
           tg_mesh_face_count(m), total, stride);
    CHECK(total > 64);
    tg_mesh_destroy(m);
    return tg_test_finish();
}
