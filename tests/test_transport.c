/* test_transport.c - parallel transport (tg_path_transport, tg_geodesic_transport_field) against
 * independent answers: the identity on a plane; Gauss-Bonnet on an icosahedron (a loop of exact
 * paths around one vertex turns a vector by that vertex's angle defect, pi / 3); the transport
 * field equal to the transport along each vertex's own exact path on a curved corpus mesh (two
 * computations: one from the log map's angle records, one from the path's segments); bad input. */
#include "tg_test.h"
#include "tg_test_geodesic.h"

#include <string.h>

static double vlen(const double* v)
{
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* On a plane both transports are the identity (the vector's projection onto the plane). */
static void test_flat(void)
{
    nv = nf = 0;
    grid(8, 0.0, 0.0, 1.0, 0.0, NULL);
    ctx c = open_ctx();
    size_t n = tg_mesh_vertex_count(c.mesh);
    double vec[3] = {0.6, -0.8, 0.0}, *out = malloc(3 * n * sizeof *out), *d = malloc(n * sizeof *d);
    tg_surface_point srcs[2] = {tg_surface_face(40, 0.2, 0.3, 0.5), tg_surface_vertex(30)};
    for (int k = 0; k < 2; ++k) {
        CHECK_STATUS(tg_geodesic_transport_field(c.geo, c.ws, &srcs[k], vec, NULL, out, NULL, d, NULL), TG_OK);
        double worst = 0.0;
        for (size_t v = 0; v < n; ++v)
            for (int i = 0; i < 3; ++i) worst = fmax(worst, fabs(out[3 * v + i] - vec[i]));
        CHECK_MSG(worst <= 1e-12, "flat, source %d: transport field off the identity by %.3g", k, worst);
    }
    /* a path across the grid */
    tg_surface_point a = tg_surface_face(3, 0.3, 0.3, 0.4), b = tg_surface_face(120, 0.5, 0.25, 0.25);
    CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &b, NULL, c.path), TG_OK);
    tg_path_view pv;
    tg_path_get_view(c.path, &pv);
    double* pt = malloc(3 * pv.point_count * sizeof *pt);
    double tilted[3] = {0.6, -0.8, 0.7}; /* its projection is vec, its length the result's */
    CHECK_STATUS(tg_path_transport(c.mesh, c.path, tilted, pt), TG_OK);
    double worst = 0.0, scale = vlen(tilted) / vlen(vec);
    for (size_t i = 0; i < pv.point_count; ++i)
        for (int k = 0; k < 3; ++k) worst = fmax(worst, fabs(pt[3 * i + k] - vec[k] * scale));
    CHECK_MSG(pv.point_count > 3 && worst <= 1e-12, "flat path of %zu points: off the identity by %.3g",
              pv.point_count, worst);
    /* bad input: nothing written */
    double zero[3] = {0, 0, 0}, up[3] = {0, 0, 1}, nan3[3] = {NAN, 0, 0};
    pt[0] = -7.0;
    CHECK_STATUS(tg_path_transport(c.mesh, c.path, zero, pt), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_path_transport(c.mesh, c.path, up, pt), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_path_transport(c.mesh, c.path, nan3, pt), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_path_transport(NULL, c.path, vec, pt), TG_ERR_INVALID_ARGUMENT);
    CHECK(pt[0] == -7.0);
    out[0] = -7.0;
    CHECK_STATUS(tg_geodesic_transport_field(c.geo, c.ws, &srcs[0], up, NULL, out, NULL, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_transport_field(c.geo, c.ws, &srcs[0], zero, NULL, out, NULL, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_transport_field(c.geo, c.ws, &srcs[0], NULL, NULL, out, NULL, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK(out[0] == -7.0);
    free(pt), free(out), free(d);
    close_sheet(&c);
}

/* A regular icosahedron: a loop of exact paths through the centroids of the five faces around
 * vertex 0 (each path crosses one edge of the fan) encloses that vertex alone, so transport
 * around it turns a vector by its angle defect 2 pi - 5 pi / 3 = pi / 3, counterclockwise
 * (positive curvature) for a counterclockwise loop. */
static void test_gauss_bonnet(void)
{
    nv = nf = 0;
    const double p = (1.0 + sqrt(5.0)) / 2.0;
    const double v[12][3] = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                             {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
    const uint32_t f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                               {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                               {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int i = 0; i < 12; ++i) add_v(v[i][0], v[i][1], v[i][2]);
    for (int i = 0; i < 20; ++i) add_f(f[i][0], f[i][1], f[i][2]);
    ctx c = open_ctx();
    double third = 1.0 / 3.0, vec[3], start[3];
    /* the vector at the first centroid: along the face's first edge */
    for (int k = 0; k < 3; ++k) vec[k] = start[k] = v[11][k] - v[0][k];
    for (int i = 0; i < 5; ++i) {
        tg_surface_point a = tg_surface_face((uint32_t)i, third, third, third);
        tg_surface_point b = tg_surface_face((uint32_t)((i + 1) % 5), third, third, third);
        CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &b, NULL, c.path), TG_OK);
        tg_path_view pv;
        tg_path_get_view(c.path, &pv);
        CHECK_MSG(pv.point_count == 3, "centroid %d -> %d: %zu points (one edge crossing expected)", i, (i + 1) % 5,
                  pv.point_count);
        double* out = malloc(3 * pv.point_count * sizeof *out);
        CHECK_STATUS(tg_path_transport(c.mesh, c.path, vec, out), TG_OK);
        memcpy(vec, out + 3 * (pv.point_count - 1), sizeof vec);
        free(out);
    }
    /* the turn about face 0's outward normal */
    double n[3], e1[3], e2[3];
    for (int k = 0; k < 3; ++k) e1[k] = v[11][k] - v[0][k], e2[k] = v[5][k] - v[0][k];
    n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double cx = start[1] * vec[2] - start[2] * vec[1], cy = start[2] * vec[0] - start[0] * vec[2];
    double cz = start[0] * vec[1] - start[1] * vec[0];
    double turn = atan2((cx * n[0] + cy * n[1] + cz * n[2]) / vlen(n), start[0] * vec[0] + start[1] * vec[1] +
                                                                          start[2] * vec[2]);
    CHECK_MSG(fabs(turn - TG_PI_ / 3.0) <= 1e-12 && fabs(vlen(vec) - vlen(start)) <= 1e-12 * vlen(start),
              "around vertex 0: turned by %.17g (angle defect pi/3 = %.17g), length %.17g -> %.17g", turn,
              TG_PI_ / 3.0, vlen(start), vlen(vec));
    close_sheet(&c);
}

/* On a curved corpus mesh: the transport field at vertex v equals the transport along v's own
 * exact path from the source (where that path arrives along the segment the field's record
 * names, compared by the angle to the arriving direction in both frames). */
static void test_field_against_paths(void)
{
    ctx c;
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "nvd_spot.obj");
    if (!m) return;
    c = open_ctx_for(m);
    size_t n = tg_mesh_vertex_count(m);
    double vec[3] = {0.3, 1.0, -0.2}, *field = malloc(3 * n * sizeof *field), *d = malloc(n * sizeof *d);
    tg_surface_point src = tg_surface_face(100, 0.2, 0.3, 0.5);
    CHECK_STATUS(tg_geodesic_transport_field(c.geo, c.ws, &src, vec, NULL, field, NULL, d, NULL), TG_OK);
    size_t checked = 0, agree = 0;
    double worst = 0.0;
    for (size_t v = 7; v < n; v += 53) {
        tg_surface_point t = tg_surface_vertex((uint32_t)v);
        CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &src, &t, NULL, c.path), TG_OK);
        tg_path_view pv;
        tg_path_get_view(c.path, &pv);
        double* out = malloc(3 * pv.point_count * sizeof *out);
        CHECK_STATUS(tg_path_transport(c.mesh, c.path, vec, out), TG_OK);
        const double* a = out + 3 * (pv.point_count - 1);
        const double* b = field + 3 * v;
        /* the same length, the same angle to the arriving segment (each in its face's plane) */
        const double* q = pv.xyz + 3 * (pv.point_count - 2);
        double s[3] = {pv.xyz[3 * (pv.point_count - 1)] - q[0], pv.xyz[3 * (pv.point_count - 1) + 1] - q[1],
                       pv.xyz[3 * (pv.point_count - 1) + 2] - q[2]};
        double sl = vlen(s);
        if (!(sl > 0.0)) {
            free(out);
            continue;
        }
        double ca = (a[0] * s[0] + a[1] * s[1] + a[2] * s[2]) / (vlen(a) * sl);
        double cb = (b[0] * s[0] + b[1] * s[1] + b[2] * s[2]) / (vlen(b) * sl);
        double e = fmax(fabs(ca - cb), fabs(vlen(a) - vlen(b)) / vlen(vec));
        checked++;
        if (e <= 1e-9) agree++;
        else if (e > worst) worst = e;
        free(out);
    }
    printf("nvd_spot: the transport field and the transport along each vertex's exact path agree at %zu of %zu "
           "vertices (worst other %.3g)\n", agree, checked, worst);
    CHECK_MSG(checked >= 50 && agree * 100 >= checked * 95, "the transport field agrees with the paths' at %zu of %zu",
              agree, checked);
    free(field), free(d);
    close_ctx(&c);
}

/* Every allocation failing in turn, on 1 and 2 threads: TG_ERR_OUT_OF_MEMORY with nothing written
 * and nothing leaked, until the first that succeeds gives the reference's bits. */
static void test_out_of_memory(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "nvd_spot.obj");
    if (!m) return;
    ctx c = open_ctx_for(m);
    size_t n = tg_mesh_vertex_count(m);
    double vec[3] = {0.3, 1.0, -0.2}, *ref = malloc(3 * n * sizeof *ref), *out = malloc(3 * n * sizeof *out);
    tg_surface_point src = tg_surface_vertex(17);
    int points = 0;
    for (int threads = 1; threads <= 2; ++threads) {
        tg_field_options plain;
        memset(&plain, 0, sizeof plain);
        plain.threads = threads; /* the bits of 2 threads may differ from one's by rounding */
        CHECK_STATUS(tg_geodesic_transport_field(c.geo, NULL, &src, vec, &plain, ref, NULL, NULL, NULL), TG_OK);
        for (long k = 0;; ++k) {
            tg_test_counting cnt = {0, 0, k, 0};
            tg_allocator a = tg_test_failing_allocator(&cnt);
            tg_field_options o;
            memset(&o, 0, sizeof o);
            o.allocator = &a, o.threads = threads;
            out[0] = -3.0;
            tg_status r = tg_geodesic_transport_field(c.geo, NULL, &src, vec, &o, out, NULL, NULL, NULL);
            CHECK_MSG(r == TG_OK || (r == TG_ERR_OUT_OF_MEMORY && out[0] == -3.0), "%d threads, allocation %ld "
                      "failing: %s, out[0] %g", threads, k, tg_status_name(r), out[0]);
            CHECK_MSG(cnt.allocs == cnt.frees, "allocation %ld failing: %ld allocations, %ld frees", k, cnt.allocs,
                      cnt.frees);
            if (r == TG_OK) {
                CHECK_MSG(memcmp(out, ref, 3 * n * sizeof *out) == 0, "%d threads: a different transport", threads);
                break;
            }
            if (++points > 10000) break;
        }
    }
    CHECK(points > 10);
    free(ref), free(out);
    close_ctx(&c);
}

/* The cut locus is flagged: on a regular octahedron four paths of one length join the source vertex
 * to the opposite vertex (flag TG_GRADIENT_TIE), one reaches each other vertex (defined), and the
 * source itself is flagged; on 1, 2 and 3 threads alike. On the flat grid nothing ties. */
static void test_cut_locus(void)
{
    nv = nf = 0;
    const double v[6][3] = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
    const uint32_t f[8][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}, {5, 2, 1}, {5, 3, 2}, {5, 4, 3}, {5, 1, 4}};
    for (int i = 0; i < 6; ++i) add_v(v[i][0], v[i][1], v[i][2]);
    for (int i = 0; i < 8; ++i) add_f(f[i][0], f[i][1], f[i][2]);
    ctx c = open_ctx();
    double vec[3] = {1, 0, 0}, out[18];
    uint8_t flag[6];
    tg_surface_point s = tg_surface_vertex(0);
    for (int threads = 1; threads <= 3; ++threads) {
        tg_field_options o;
        memset(&o, 0, sizeof o);
        o.threads = threads;
        CHECK_STATUS(tg_geodesic_transport_field(c.geo, c.ws, &s, vec, &o, out, flag, NULL, NULL), TG_OK);
        CHECK_MSG(flag[0] == TG_GRADIENT_SOURCE && flag[5] == TG_GRADIENT_TIE, "%d threads: source flag %d, opposite %d",
                  threads, flag[0], flag[5]);
        for (int k = 1; k < 5; ++k)
            CHECK_MSG(flag[k] == TG_GRADIENT_DEFINED, "%d threads: v%d flag %d", threads, k, flag[k]);
    }
    close_sheet(&c);
    /* the octahedron divided 4 times onto the sphere (2048 faces: the waves of lists are large
     * enough to cross on the lanes of several threads): its poles still join by four paths */
    nv = nf = 0;
    for (int i = 0; i < 6; ++i) add_v(v[i][0], v[i][1], v[i][2]);
    static uint32_t tri0[3 * 2048], edges[2 * 4096], mids[4096];
    size_t nt = 8, ne = 0;
    for (int i = 0; i < 8; ++i) tri0[3 * i] = f[i][0], tri0[3 * i + 1] = f[i][1], tri0[3 * i + 2] = f[i][2];
    for (int level = 0; level < 4; ++level) {
        static uint32_t next[3 * 2048];
        size_t nn = 0;
        ne = 0;
        for (size_t t = 0; t < nt; ++t) {
            uint32_t m[3];
            for (int k = 0; k < 3; ++k) {
                uint32_t a = tri0[3 * t + (size_t)k], b = tri0[3 * t + (size_t)(k + 1) % 3], lo = a < b ? a : b,
                         hi = a < b ? b : a;
                size_t e = 0;
                while (e < ne && !(edges[2 * e] == lo && edges[2 * e + 1] == hi)) ++e;
                if (e == ne) {
                    double p[3], l = 0.0;
                    for (int j = 0; j < 3; ++j) p[j] = xyz[3 * a + (size_t)j] + xyz[3 * b + (size_t)j], l += p[j] * p[j];
                    l = sqrt(l);
                    edges[2 * ne] = lo, edges[2 * ne + 1] = hi, mids[ne++] = add_v(p[0] / l, p[1] / l, p[2] / l);
                }
                m[k] = mids[e];
            }
            uint32_t a = tri0[3 * t], b = tri0[3 * t + 1], cc = tri0[3 * t + 2];
            uint32_t quad[4][3] = {{a, m[0], m[2]}, {m[0], b, m[1]}, {m[2], m[1], cc}, {m[0], m[1], m[2]}};
            for (int q = 0; q < 4; ++q, ++nn)
                for (int j = 0; j < 3; ++j) next[3 * nn + (size_t)j] = quad[q][j];
        }
        nt = nn;
        memcpy(tri0, next, 3 * nt * sizeof *tri0);
    }
    for (size_t t = 0; t < nt; ++t) add_f(tri0[3 * t], tri0[3 * t + 1], tri0[3 * t + 2]);
    c = open_ctx();
    for (int threads = 1; threads <= 2; ++threads) {
        size_t nvs = tg_mesh_vertex_count(c.mesh);
        double* o3 = malloc(3 * nvs * sizeof *o3);
        uint8_t* fl = malloc(nvs);
        tg_field_options o;
        memset(&o, 0, sizeof o);
        o.threads = threads;
        tg_field_stats st;
        CHECK_STATUS(tg_geodesic_transport_field(c.geo, c.ws, &s, vec, &o, o3, fl, NULL, &st), TG_OK);
        CHECK_MSG(fl[5] == TG_GRADIENT_TIE, "divided octahedron, %d threads: the opposite pole's flag %d (waves %llu)",
                  threads, fl[5], (unsigned long long)st.waves);
        free(o3), free(fl);
    }
    close_sheet(&c);
    nv = nf = 0;
    grid(8, 0.0, 0.0, 1.0, 0.0, NULL);
    c = open_ctx();
    size_t n = tg_mesh_vertex_count(c.mesh);
    double* o3 = malloc(3 * n * sizeof *o3);
    uint8_t* fl = malloc(n);
    tg_surface_point fp = tg_surface_face(40, 0.2, 0.3, 0.5);
    CHECK_STATUS(tg_geodesic_transport_field(c.geo, c.ws, &fp, vec, NULL, o3, fl, NULL, NULL), TG_OK);
    size_t ties = 0;
    for (size_t k = 0; k < n; ++k) ties += fl[k] == TG_GRADIENT_TIE;
    CHECK_MSG(ties == 0, "flat grid: %zu vertices flagged as cut locus", ties);
    free(o3), free(fl);
    close_sheet(&c);
}

int main(void)
{
    test_flat();
    test_gauss_bonnet();
    test_field_against_paths();
    test_out_of_memory();
    test_cut_locus();
    return tg_test_finish();
}
