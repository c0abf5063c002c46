/* test_oom_sweep.c - allocation failures through every public entry point that allocates: mesh
 * creation, every reader (OBJ, OFF, binary and ASCII PLY, binary and ASCII STL, gzip) from files
 * and memory, the writers, the BVH build, workspaces and batch queries, the
 * geodesic solver, paths by every method with and without the certificate, exact fields (single,
 * at points, batch on 1 and 2 threads, with and without a distance limit), curves as sources
 * (the field, the path from them, their Voronoi cells, curve rows of a matrix), Voronoi labels,
 * farthest-point sampling and the renderer.
 *
 * Each entry point runs once per allocation point k (every one up to a few hundred, a sample
 * after, and always the last), with an allocator that fails its k-th request and every one after.
 * Every run must end in TG_OK or TG_ERR_OUT_OF_MEMORY, without a crash, with *out NULL on failure
 * where the header says so, outputs untouched (fields) or empty (paths) as documented, and with
 * as many blocks freed as allocated once everything is destroyed. The first run that succeeds
 * must give the same result, bit for bit, as the same call with the default allocator.
 * Meshes: data/nvd_spot.obj (5856 faces; paths between its far ends grow every buffer), written
 * into a temporary directory in every format; a grid of polygons (fan triangulation); spot with
 * misoriented, repeated-index and non-manifold faces; a disk with a 200-spoke vertex. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <zlib.h>

#include <trigeo.h>

#include "tg_test.h"

/* ---- the sweep driver ---- */

/* One run: the counting allocator, and the window of allocations that belong to the call under
 * test (objects it needs are made before arm() and destroyed after disarm(), never failing). */
typedef struct sweep {
    tg_test_counting c;
    tg_allocator a;
    long k;    /* the call's allocation that fails (0-based), with every one after it */
    long base; /* allocations before the call */
    long used; /* allocations the call made */
    const char* name;
} sweep;

static void arm(sweep* s)
{
    s->base = s->c.allocs;
    s->c.fail_after = s->base + s->k;
}

static void disarm(sweep* s)
{
    s->used = s->c.allocs - s->base;
    s->c.fail_after = -1;
}

typedef tg_status (*attempt_fn)(sweep* s, void* ctx);

static double seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Runs fn at k = 0, 1, ... until it succeeds: every k up to `dense`, then every `stride`-th, and
 * the last allocation point (used - 1) if the sample stepped over it. Prints the count and the
 * time; returns the allocations of the successful run. The fast suite thins every sweep: every
 * point up to `dense` / 16 (the first 9 to 25), then every (4 * stride)-th, and the last; the full
 * suite (TG_FULL=1) runs them as given. */
static long sweep_run(const char* name, attempt_fn fn, void* ctx, long dense, long stride)
{
    if (!tg_test_full()) dense /= 16, stride *= 4;
    double start = seconds();
    long used = -1, runs = 0, last_failed = -1, bad = 0;
    for (long k = 0;;) {
        sweep s;
        memset(&s, 0, sizeof s);
        s.c.fail_after = -1;
        s.a = (tg_allocator)tg_test_failing_allocator(&s.c);
        s.k = k;
        s.name = name;
        tg_status st = fn(&s, ctx);
        runs++;
        if (s.c.allocs != s.c.frees) {
            bad++;
            TG_FAIL_("%s, allocation %ld failing: %ld allocations, %ld frees", name, k, s.c.allocs, s.c.frees);
        } else {
            tg_test_passed_++;
        }
        if (st == TG_OK) {
            used = s.used;
            if (used - 1 > last_failed && used - 1 < k) {
                k = used - 1; /* the last point, stepped over by the sample */
                continue;
            }
            break;
        }
        if (st != TG_ERR_OUT_OF_MEMORY) {
            bad++;
            TG_FAIL_("%s, allocation %ld failing: status %s, expected out_of_memory", name, k, tg_status_name(st));
        }
        last_failed = k;
        if (bad > 10 || k > 1000000) {
            TG_FAIL_("%s: giving up at allocation %ld", name, k);
            break;
        }
        k += k < dense ? 1 : stride;
        if (used >= 0 && k >= used) break; /* only after the revisit of the last point */
    }
    printf("%-64s %4ld allocation points, %4ld runs, %6.2f s\n", name, used, runs, seconds() - start);
    fflush(stdout);
    return used;
}

/* A non-NULL pointer no call may leave behind on failure. */
static char not_null_;
#define NOT_NULL ((void*)&not_null_)

#define CHECK_NULL_ON_FAILURE(s, st, ptr)                                                              \
    CHECK_MSG((st) == TG_OK || (ptr) == NULL, "%s, allocation %ld failing: %s is not NULL after %s", (s)->name, \
              (s)->k, #ptr, tg_status_name(st))

static bool same_bytes(const void* a, const void* b, size_t n) { return n == 0 || memcmp(a, b, n) == 0; }

static bool same_double(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* ---- fixtures ---- */

static char tmp_dir[4096];
static tg_mesh* spot;       /* default allocator */
static tg_geodesic* spot_g; /* default allocator */
static tg_surface_point far_a, far_b, near_b; /* far-apart face points, and one near far_a */

static void tmp_path(char* out, size_t cap, const char* file) { snprintf(out, cap, "%s/%s", tmp_dir, file); }

/* data/nvd_spot.obj of the source tree (env TG_SOURCE_DIR, set by CTest), else the corpus's copy. */
static void spot_path(char* out, size_t cap)
{
    const char* src = getenv("TG_SOURCE_DIR");
    if (src) snprintf(out, cap, "%s/data/nvd_spot.obj", src);
    else snprintf(out, cap, "%s/nvd_spot.obj", tg_test_meshes_dir());
}

static char* read_whole(const char* path, size_t* out_size)
{
    FILE* f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char* d = malloc((size_t)n + 1);
    if (d && fread(d, 1, (size_t)n, f) != (size_t)n) {
        free(d);
        d = NULL;
    }
    fclose(f);
    *out_size = (size_t)n;
    return d;
}

static bool write_gz(const char* dst, const char* src)
{
    size_t n = 0;
    char* d = read_whole(src, &n);
    gzFile g = d ? gzopen(dst, "wb") : NULL;
    bool ok = g && gzwrite(g, d, (unsigned)n) == (int)n;
    if (g) ok = gzclose(g) == Z_OK && ok;
    free(d);
    return ok;
}

static void put_f32(FILE* f, double v)
{
    float x = (float)v;
    fwrite(&x, sizeof x, 1, f); /* little-endian hosts only, like every binary test here */
}

/* The mesh as binary and ASCII STL, OFF, ASCII PLY; the readers' other inputs. */
static bool write_fixture_files(const tg_mesh* m)
{
    const double* p = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    size_t nv = tg_mesh_vertex_count(m), nf = tg_mesh_face_count(m);
    char path[4200];
    tmp_path(path, sizeof path, "spot.stl");
    FILE* f = fopen(path, "wb");
    if (!f) return false;
    char header[80] = "trigeo oom sweep";
    uint32_t count = (uint32_t)nf;
    fwrite(header, 1, sizeof header, f);
    fwrite(&count, sizeof count, 1, f);
    for (size_t i = 0; i < nf; ++i) {
        uint16_t attr = 0;
        for (int j = 0; j < 3; ++j) put_f32(f, 0.0);
        for (int c = 0; c < 3; ++c)
            for (int j = 0; j < 3; ++j) put_f32(f, p[3 * t[3 * i + c] + j]);
        fwrite(&attr, sizeof attr, 1, f);
    }
    if (fclose(f) != 0) return false;

    tmp_path(path, sizeof path, "spot_ascii.stl");
    if (!(f = fopen(path, "w"))) return false;
    fprintf(f, "solid spot\n");
    for (size_t i = 0; i < nf; ++i) {
        fprintf(f, "  facet normal 0 0 0\n    outer loop\n");
        for (int c = 0; c < 3; ++c) {
            const double* v = p + 3 * t[3 * i + c];
            fprintf(f, "      vertex %.17g %.17g %.17g\n", v[0], v[1], v[2]);
        }
        fprintf(f, "    endloop\n  endfacet\n");
    }
    fprintf(f, "endsolid spot\n");
    if (fclose(f) != 0) return false;

    tmp_path(path, sizeof path, "spot.off");
    if (!(f = fopen(path, "w"))) return false;
    fprintf(f, "OFF\n%zu %zu 0\n", nv, nf);
    for (size_t i = 0; i < nv; ++i) fprintf(f, "%.17g %.17g %.17g\n", p[3 * i], p[3 * i + 1], p[3 * i + 2]);
    for (size_t i = 0; i < nf; ++i) fprintf(f, "3 %u %u %u\n", t[3 * i], t[3 * i + 1], t[3 * i + 2]);
    if (fclose(f) != 0) return false;

    tmp_path(path, sizeof path, "spot_ascii.ply");
    if (!(f = fopen(path, "w"))) return false;
    fprintf(f, "ply\nformat ascii 1.0\nelement vertex %zu\nproperty double x\nproperty double y\n"
               "property double z\nelement face %zu\nproperty list uchar int vertex_indices\nend_header\n",
            nv, nf);
    for (size_t i = 0; i < nv; ++i) fprintf(f, "%.17g %.17g %.17g\n", p[3 * i], p[3 * i + 1], p[3 * i + 2]);
    for (size_t i = 0; i < nf; ++i) fprintf(f, "3 %u %u %u\n", t[3 * i], t[3 * i + 1], t[3 * i + 2]);
    if (fclose(f) != 0) return false;

    /* binary PLY by the library's writer, with a scalar */
    double* s = malloc(nv * sizeof *s);
    for (size_t i = 0; i < nv; ++i) s[i] = p[3 * i] - p[3 * i + 2];
    tg_vertex_scalar sc = {"height", s};
    tmp_path(path, sizeof path, "spot.ply");
    tg_status st = tg_mesh_write_ply(m, path, &sc, 1, NULL);
    free(s);
    if (st != TG_OK) return false;

    char src[4200];
    spot_path(src, sizeof src);
    tmp_path(path, sizeof path, "spot.obj.gz");
    if (!write_gz(path, src)) return false;
    /* over 1 MiB decompressed: the gzip reader's buffer grows */
    tmp_path(src, sizeof src, "spot_ascii.stl");
    tmp_path(path, sizeof path, "spot_ascii.stl.gz");
    return write_gz(path, src);
}

/* A mesh of polygons: quads, triangles, hexagons over two cells and one 42-gon (a fan over the
 * first row from an apex), for the readers' polygon paths (fan triangulation, growth of the
 * polygon and triangle buffers beyond what a triangle-only file reserves). Written as OBJ (with
 * every corner syntax and negative indices), OFF, ASCII PLY and binary PLY (with properties to
 * skip). */
enum { POLY_COLS = 40, POLY_ROWS = 30 };


/* The body of a text OFF or ASCII PLY file: vertex rows (each followed by `vertex_tail`), then
 * one "n i0 i1 ..." row per polygon; closes f. false on a write error. */
static bool write_text_polygons(FILE* f, const double* xyz, uint32_t nv, const uint32_t* start, const uint32_t* idx,
                                size_t faces, const char* vertex_tail)
{
    for (uint32_t v = 0; v < nv; ++v)
        fprintf(f, "%.17g %.17g %.17g%s\n", xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2], vertex_tail);
    for (size_t k = 0; k < faces; ++k) {
        fprintf(f, "%u", start[k + 1] - start[k]);
        for (uint32_t c = start[k]; c < start[k + 1]; ++c) fprintf(f, " %u", idx[c]);
        fprintf(f, "\n");
    }
    return fclose(f) == 0;
}

static bool write_polygon_files(void)
{
    const uint32_t w = POLY_COLS + 1, apex = (POLY_ROWS + 1) * w, nv = apex + 1;
    uint32_t* idx = malloc(16 * (size_t)POLY_COLS * POLY_ROWS * sizeof *idx + 64 * sizeof *idx);
    uint32_t* start = malloc((2 * (size_t)POLY_COLS * POLY_ROWS + 2) * sizeof *start);
    size_t n = 0, faces = 0;
    for (uint32_t i = 0; i < POLY_ROWS; ++i)
        for (uint32_t j = 0; j < POLY_COLS; ++j) {
            uint32_t a = i * w + j, b = a + 1, c = a + w + 1, d = a + w;
            if ((i + j) % 5 == 0) {
                start[faces++] = (uint32_t)n, idx[n++] = a, idx[n++] = b, idx[n++] = c;
                start[faces++] = (uint32_t)n, idx[n++] = a, idx[n++] = c, idx[n++] = d;
            } else if (j % 7 == 3 && j + 1 < POLY_COLS) { /* a hexagon over this cell and the next */
                start[faces++] = (uint32_t)n;
                idx[n++] = a, idx[n++] = b, idx[n++] = b + 1, idx[n++] = c + 1, idx[n++] = c, idx[n++] = d;
                j++;
            } else {
                start[faces++] = (uint32_t)n, idx[n++] = a, idx[n++] = b, idx[n++] = c, idx[n++] = d;
            }
        }
    start[faces++] = (uint32_t)n;
    idx[n++] = apex;
    for (uint32_t j = w; j-- > 0;) idx[n++] = j;
    start[faces] = (uint32_t)n;
    double* xyz = malloc(3 * (size_t)nv * sizeof *xyz);
    for (uint32_t v = 0; v < apex; ++v)
        xyz[3 * v] = (double)(v % w), xyz[3 * v + 1] = (double)(v / w), xyz[3 * v + 2] = 0.05 * (double)((v * 7) % 11);
    xyz[3 * apex] = 0.5 * POLY_COLS, xyz[3 * apex + 1] = -3.0, xyz[3 * apex + 2] = 1.0;

    char path[4200];
    bool ok = true;
    tmp_path(path, sizeof path, "poly.obj");
    FILE* f = fopen(path, "w");
    if (f) {
        for (uint32_t v = 0; v < nv; ++v) fprintf(f, "v %.17g %.17g %.17g\n", xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
        fprintf(f, "vt 0 0\nvn 0 0 1\n");
        for (size_t k = 0; k < faces; ++k) {
            fprintf(f, "f");
            for (uint32_t c = start[k]; c < start[k + 1]; ++c) {
                if (k == faces - 1) fprintf(f, " %ld", (long)idx[c] - (long)nv); /* negative: relative */
                else if (k % 4 == 0) fprintf(f, " %u", idx[c] + 1);
                else if (k % 4 == 1) fprintf(f, " %u/1", idx[c] + 1);
                else if (k % 4 == 2) fprintf(f, " %u//1", idx[c] + 1);
                else fprintf(f, " %u/1/1", idx[c] + 1);
            }
            fprintf(f, "\n");
        }
        ok = fclose(f) == 0 && ok;
    } else {
        ok = false;
    }
    tmp_path(path, sizeof path, "poly.off");
    if ((f = fopen(path, "w"))) {
        fprintf(f, "OFF\n%u %zu 0\n", nv, faces);
        ok = write_text_polygons(f, xyz, nv, start, idx, faces, "") && ok;
    } else {
        ok = false;
    }
    tmp_path(path, sizeof path, "poly_ascii.ply");
    if ((f = fopen(path, "w"))) {
        fprintf(f, "ply\nformat ascii 1.0\ncomment polygons\nelement vertex %u\nproperty double x\nproperty double y\n"
                   "property double z\nproperty float confidence\nelement face %zu\nproperty list uchar int vertex_indices\n"
                   "end_header\n",
                nv, faces);
        ok = write_text_polygons(f, xyz, nv, start, idx, faces, " 0.5") && ok;
    } else {
        ok = false;
    }
    tmp_path(path, sizeof path, "poly.ply");
    if ((f = fopen(path, "wb"))) {
        fprintf(f, "ply\nformat binary_little_endian 1.0\nelement vertex %u\nproperty float x\nproperty float y\n"
                   "property float z\nproperty uchar quality\nelement face %zu\nproperty uchar flags\n"
                   "property list uchar int vertex_indices\nproperty list uchar float texcoord\nend_header\n",
                nv, faces);
        for (uint32_t v = 0; v < nv; ++v) {
            unsigned char q = (unsigned char)v;
            for (int j = 0; j < 3; ++j) put_f32(f, xyz[3 * v + j]);
            fwrite(&q, 1, 1, f);
        }
        for (size_t k = 0; k < faces; ++k) {
            unsigned char flags = 7, count = (unsigned char)(start[k + 1] - start[k]), tc = 2;
            fwrite(&flags, 1, 1, f);
            fwrite(&count, 1, 1, f);
            for (uint32_t c = start[k]; c < start[k + 1]; ++c) {
                int32_t v = (int32_t)idx[c];
                fwrite(&v, sizeof v, 1, f);
            }
            fwrite(&tc, 1, 1, f);
            put_f32(f, 0.25), put_f32(f, 0.75);
        }
        ok = fclose(f) == 0 && ok;
    } else {
        ok = false;
    }
    free(idx), free(start), free(xyz);
    return ok;
}

static const char* fixture_files[] = {"spot.stl",    "spot_ascii.stl", "spot.off",       "spot_ascii.ply",
                                      "spot.ply",    "spot.obj.gz",    "spot_ascii.stl.gz", "poly.obj",
                                      "poly.off",    "poly_ascii.ply", "poly.ply"};

/* Two meshes are the same: counts, positions, triangles, topology and report. */
static bool same_mesh(const tg_mesh* a, const tg_mesh* b)
{
    size_t nv = tg_mesh_vertex_count(a), nf = tg_mesh_face_count(a);
    if (nv != tg_mesh_vertex_count(b) || nf != tg_mesh_face_count(b)) return false;
    if (!same_bytes(tg_mesh_positions(a), tg_mesh_positions(b), 3 * nv * sizeof(double))) return false;
    if (!same_bytes(tg_mesh_triangles(a), tg_mesh_triangles(b), 3 * nf * sizeof(uint32_t))) return false;
    if (!same_bytes(tg_mesh_opposites(a), tg_mesh_opposites(b), 3 * nf * sizeof(uint32_t))) return false;
    if (!same_bytes(tg_mesh_vertex_halfedges(a), tg_mesh_vertex_halfedges(b), nv * sizeof(uint32_t))) return false;
    if (!same_bytes(tg_mesh_face_components(a), tg_mesh_face_components(b), nf * sizeof(uint32_t))) return false;
    const tg_mesh_report *ra = tg_mesh_get_report(a), *rb = tg_mesh_get_report(b);
    return ra->edges == rb->edges && ra->components == rb->components && ra->boundary_edges == rb->boundary_edges &&
           ra->boundary_loops == rb->boundary_loops && ra->nonmanifold_edges == rb->nonmanifold_edges &&
           ra->nonmanifold_vertices == rb->nonmanifold_vertices && ra->misoriented_edges == rb->misoriented_edges &&
           ra->degenerate_faces == rb->degenerate_faces && ra->duplicate_faces == rb->duplicate_faces &&
           ra->genus == rb->genus && ra->closed_manifold == rb->closed_manifold &&
           same_bytes(ra->bbox_min, rb->bbox_min, sizeof ra->bbox_min) &&
           same_bytes(ra->bbox_max, rb->bbox_max, sizeof ra->bbox_max) &&
           tg_mesh_memory_bytes(a) == tg_mesh_memory_bytes(b);
}

/* A mesh made with the sweep's allocator, before arm(). */
static tg_mesh* failing_mesh(sweep* s)
{
    tg_mesh_options o = {&s->a};
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(tg_mesh_positions(spot), tg_mesh_vertex_count(spot), tg_mesh_triangles(spot),
                                tg_mesh_face_count(spot), &o, NULL, &m),
                 TG_OK);
    return m;
}

/* ---- meshes: create, load, write ---- */

/* Caller arrays for tg_mesh_create, and the mesh the default allocator makes of them. */
typedef struct create_ctx {
    const double* xyz;
    size_t nv;
    const uint32_t* tri;
    size_t nf;
    tg_mesh* reference;
} create_ctx;

static tg_status try_mesh_create(sweep* s, void* ctx)
{
    const create_ctx* cc = ctx;
    tg_mesh_options o = {&s->a};
    tg_mesh* m = NOT_NULL;
    arm(s);
    tg_status st = tg_mesh_create(cc->xyz, cc->nv, cc->tri, cc->nf, &o, NULL, &m);
    disarm(s);
    CHECK_NULL_ON_FAILURE(s, st, m);
    if (st == TG_OK) CHECK_MSG(same_mesh(m, cc->reference), "%s: the mesh differs from the default allocator's", s->name);
    if (st == TG_OK || m == NULL) tg_mesh_destroy(m);
    return st;
}

static void sweep_mesh_create(const double* xyz, size_t nv, const uint32_t* tri, size_t nf, const char* name)
{
    create_ctx cc = {xyz, nv, tri, nf, NULL};
    CHECK_STATUS(tg_mesh_create(xyz, nv, tri, nf, NULL, NULL, &cc.reference), TG_OK);
    if (cc.reference) sweep_run(name, try_mesh_create, &cc, 400, 1);
    tg_mesh_destroy(cc.reference);
}

/* spot with every 7th face wound the other way, two faces with a repeated index (a duplicate
 * pair) and a third face on the edge of face 0 (non-manifold) with a new vertex: the topology
 * pass's and the solver's paths for troubled meshes (corner linking, duplicate counting, the
 * solver's own rewound triangles). Faces keep their indices; the extras come last. */
static tg_mesh* troubled_spot(void)
{
    size_t nv = tg_mesh_vertex_count(spot), nf = tg_mesh_face_count(spot);
    double* xyz = malloc(3 * (nv + 1) * sizeof *xyz);
    uint32_t* t = malloc(3 * (nf + 3) * sizeof *t);
    memcpy(xyz, tg_mesh_positions(spot), 3 * nv * sizeof *xyz);
    memcpy(t, tg_mesh_triangles(spot), 3 * nf * sizeof *t);
    for (size_t f = 0; f < nf; f += 7) {
        uint32_t x = t[3 * f + 1];
        t[3 * f + 1] = t[3 * f + 2], t[3 * f + 2] = x;
    }
    const double* a = xyz + 3 * t[0];
    for (int j = 0; j < 3; ++j) xyz[3 * nv + j] = a[j] + 0.01 * (j + 1);
    uint32_t extra[9] = {t[0], t[0], t[1], t[1], t[0], t[0], t[0], t[1], (uint32_t)nv};
    memcpy(t + 3 * nf, extra, sizeof extra);
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(xyz, nv + 1, t, nf + 3, NULL, NULL, &m), TG_OK);
    const tg_mesh_report* r = m ? tg_mesh_get_report(m) : NULL;
    CHECK(r && r->misoriented_edges > 0 && r->nonmanifold_edges > 0 && r->duplicate_faces > 0);
    if (m) sweep_mesh_create(xyz, nv + 1, t, nf + 3, "tg_mesh_create (misoriented, repeated-index, non-manifold faces)");
    free(xyz);
    free(t);
    return m;
}

/* A flat disk whose centre has 200 spokes (a vertex bucket too big for the small sort). */
static tg_mesh* spoke_disk(void)
{
    enum { SPOKES = 200 };
    double xyz[3 * (SPOKES + 1)] = {0, 0, 0};
    uint32_t tri[3 * SPOKES];
    for (int i = 0; i < SPOKES; ++i) {
        double a = 2.0 * 3.14159265358979323846 * i / SPOKES;
        xyz[3 * (i + 1)] = cos(a), xyz[3 * (i + 1) + 1] = sin(a), xyz[3 * (i + 1) + 2] = 0.0;
        tri[3 * i] = 0, tri[3 * i + 1] = (uint32_t)(i + 1), tri[3 * i + 2] = (uint32_t)((i + 1) % SPOKES + 1);
    }
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(xyz, SPOKES + 1, tri, SPOKES, NULL, NULL, &m), TG_OK);
    if (m) sweep_mesh_create(xyz, SPOKES + 1, tri, SPOKES, "tg_mesh_create (a vertex of valence 200)");
    return m;
}

typedef struct load_ctx {
    const char* path;  /* file to load, or NULL for memory */
    const char* data;  /* bytes for tg_mesh_load_memory */
    size_t size;
    const char* name;
    const tg_mesh* reference;
} load_ctx;

static tg_status try_mesh_load(sweep* s, void* ctx)
{
    load_ctx* l = ctx;
    tg_mesh_options o = {&s->a};
    tg_mesh* m = NOT_NULL;
    tg_diag d;
    arm(s);
    tg_status st = l->path ? tg_mesh_load(l->path, TG_FORMAT_AUTO, &o, &d, &m)
                           : tg_mesh_load_memory(l->data, l->size, l->name, TG_FORMAT_AUTO, &o, &d, &m);
    disarm(s);
    CHECK_NULL_ON_FAILURE(s, st, m);
    if (st == TG_OK) CHECK_MSG(same_mesh(m, l->reference), "%s: the mesh differs from the default allocator's", s->name);
    if (st == TG_OK || m == NULL) tg_mesh_destroy(m);
    return st;
}

static void sweep_loads(void)
{
    char path[4200], name[4300];
    spot_path(path, sizeof path);
    const long dense = TG_TEST_WORK(400, 150), stride = TG_TEST_WORK(3, 11);
    for (size_t i = 0; i <= sizeof fixture_files / sizeof fixture_files[0]; ++i) {
        char file[4200];
        if (i == 0) snprintf(file, sizeof file, "%s", path);
        else tmp_path(file, sizeof file, fixture_files[i - 1]);
        tg_mesh* ref = NULL;
        CHECK_STATUS(tg_mesh_load(file, TG_FORMAT_AUTO, NULL, NULL, &ref), TG_OK);
        if (!ref) continue;
        const char* base = strrchr(file, '/') ? strrchr(file, '/') + 1 : file;
        load_ctx l = {file, NULL, 0, base, ref};
        snprintf(name, sizeof name, "tg_mesh_load %s (%zu faces)", base, tg_mesh_face_count(ref));
        sweep_run(name, try_mesh_load, &l, dense, stride);
        if (!strstr(base, ".gz")) {
            size_t n = 0;
            char* bytes = read_whole(file, &n);
            CHECK(bytes != NULL);
            load_ctx lm = {NULL, bytes, n, base, ref};
            snprintf(name, sizeof name, "tg_mesh_load_memory %s (%zu faces)", base, tg_mesh_face_count(ref));
            if (bytes) sweep_run(name, try_mesh_load, &lm, dense, stride);
            free(bytes);
        }
        tg_mesh_destroy(ref);
    }
}

typedef struct write_ctx {
    bool ply;
    const char* reference; /* bytes written from the default-allocator mesh */
    size_t size;
} write_ctx;

static const double* ply_scalar(void)
{
    static double* s;
    if (!s) {
        size_t nv = tg_mesh_vertex_count(spot);
        s = malloc(nv * sizeof *s);
        for (size_t i = 0; i < nv; ++i) s[i] = tg_mesh_positions(spot)[3 * i + 1] * 0.5;
    }
    return s;
}

static tg_status write_one(const tg_mesh* m, bool ply, const char* path)
{
    tg_vertex_scalar sc = {"half_y", ply_scalar()};
    return ply ? tg_mesh_write_ply(m, path, &sc, 1, NULL) : tg_mesh_write_obj(m, path, NULL);
}


/* The file at path holds exactly the reference bytes (what the default allocator's run wrote). */
static void check_file_is(const char* path, const char* reference, size_t size, const char* what)
{
    size_t n = 0;
    char* d = read_whole(path, &n);
    CHECK_MSG(d && n == size && same_bytes(d, reference, n), "%s: %s differs from the default allocator's", what, path);
    free(d);
}

static tg_status try_write(sweep* s, void* ctx)
{
    write_ctx* w = ctx;
    tg_mesh* m = failing_mesh(s);
    char path[4200];
    tmp_path(path, sizeof path, w->ply ? "written.ply" : "written.obj");
    remove(path);
    arm(s);
    tg_status st = write_one(m, w->ply, path);
    disarm(s);
    if (st == TG_OK) check_file_is(path, w->reference, w->size, s->name);
    tg_mesh_destroy(m);
    return st;
}

static void sweep_writers(void)
{
    for (int ply = 0; ply < 2; ++ply) {
        char path[4200];
        tmp_path(path, sizeof path, ply ? "reference.ply" : "reference.obj");
        CHECK_STATUS(write_one(spot, ply, path), TG_OK);
        write_ctx w = {ply != 0, NULL, 0};
        char* d = read_whole(path, &w.size);
        w.reference = d;
        CHECK(d != NULL);
        if (d) sweep_run(ply ? "tg_mesh_write_ply" : "tg_mesh_write_obj", try_write, &w, 100, 1);
        free(d);
    }
}

/* ---- BVH ---- */

enum { QUERY_COUNT = 600 };
static double queries[3 * QUERY_COUNT];

static void make_queries(void)
{
    const tg_mesh_report* r = tg_mesh_get_report(spot);
    tg_rng rng = {0x5eed0011};
    for (int i = 0; i < QUERY_COUNT; ++i)
        for (int j = 0; j < 3; ++j) {
            double lo = r->bbox_min[j], hi = r->bbox_max[j], pad = 0.2 * (hi - lo);
            queries[3 * i + j] = tg_rng_range(&rng, lo - pad, hi + pad);
        }
}

static tg_bvh_options bvh_options(const tg_allocator* a, int threads)
{
    tg_bvh_options o;
    memset(&o, 0, sizeof o);
    o.allocator = a;
    o.winding_data = TG_BVH_WINDING_ALWAYS;
    o.threads = threads;
    return o;
}

/* The answers of one BVH: closest, signed (both methods), winding numbers, locations. */
typedef struct bvh_answers {
    tg_closest_hit closest[QUERY_COUNT];
    tg_signed_hit pseudo[QUERY_COUNT], winding[QUERY_COUNT];
    double wn[QUERY_COUNT];
    tg_surface_point located[QUERY_COUNT];
} bvh_answers;

static tg_status bvh_answer(const tg_bvh* bvh, tg_bvh_workspace* ws, bvh_answers* out)
{
    tg_status st = tg_bvh_closest_batch(bvh, queries, QUERY_COUNT, INFINITY, 1, out->closest);
    if (st == TG_OK) st = tg_bvh_signed_distance_batch(bvh, queries, QUERY_COUNT, TG_SIGN_PSEUDONORMAL, 1, out->pseudo);
    if (st == TG_OK) st = tg_bvh_signed_distance_batch(bvh, queries, QUERY_COUNT, TG_SIGN_WINDING, 1, out->winding);
    for (int i = 0; i < QUERY_COUNT && st == TG_OK; ++i) st = tg_bvh_winding_number(bvh, ws, queries + 3 * i, out->wn + i);
    for (int i = 0; i < QUERY_COUNT && st == TG_OK; ++i)
        st = tg_bvh_locate(bvh, ws, queries + 3 * i, out->located + i, NULL);
    return st;
}

static bvh_answers bvh_reference;

static bool same_answers(const bvh_answers* a, const bvh_answers* b) { return memcmp(a, b, sizeof *a) == 0; }

static tg_status try_bvh_create(sweep* s, void* ctx)
{
    int threads = *(const int*)ctx;
    tg_bvh_options o = bvh_options(&s->a, threads);
    tg_bvh* bvh = NOT_NULL;
    arm(s);
    tg_status st = tg_bvh_create(spot, &o, &bvh);
    disarm(s);
    CHECK_NULL_ON_FAILURE(s, st, bvh);
    if (st == TG_OK) {
        static bvh_answers got;
        tg_bvh_workspace* ws = NULL;
        CHECK_STATUS(tg_bvh_workspace_create(bvh, &ws), TG_OK);
        memset(&got, 0, sizeof got);
        CHECK_STATUS(bvh_answer(bvh, ws, &got), TG_OK);
        CHECK_MSG(same_answers(&got, &bvh_reference), "%s: answers differ from the default allocator's", s->name);
        tg_bvh_workspace_destroy(ws);
    }
    if (st == TG_OK || bvh == NULL) tg_bvh_destroy(bvh);
    return st;
}

static tg_status try_bvh_workspace(sweep* s, void* ctx)
{
    (void)ctx;
    tg_bvh_options o = bvh_options(&s->a, 1);
    tg_bvh* bvh = NULL;
    CHECK_STATUS(tg_bvh_create(spot, &o, &bvh), TG_OK);
    tg_bvh_workspace* ws = NOT_NULL;
    arm(s);
    tg_status st = tg_bvh_workspace_create(bvh, &ws);
    disarm(s);
    CHECK_NULL_ON_FAILURE(s, st, ws);
    if (st == TG_OK) {
        tg_closest_hit h;
        CHECK_STATUS(tg_bvh_closest(bvh, ws, queries, INFINITY, &h), TG_OK);
        CHECK(memcmp(&h, &bvh_reference.closest[0], sizeof h) == 0);
    }
    if (st == TG_OK || ws == NULL) tg_bvh_workspace_destroy(ws);
    tg_bvh_destroy(bvh);
    return st;
}

/* A batch or single query on a BVH made with the sweep's allocator. */
typedef enum bvh_call {
    CLOSEST_BATCH,
    SIGNED_PSEUDO_BATCH,
    SIGNED_WINDING_BATCH,
    CLOSEST,
    SIGNED_PSEUDO,
    SIGNED_WINDING,
    WINDING_NUMBER,
    LOCATE
} bvh_call;
typedef struct bvh_query_ctx {
    bvh_call call;
    int threads;
} bvh_query_ctx;

static tg_status try_bvh_query(sweep* s, void* ctx)
{
    const bvh_query_ctx* q = ctx;
    tg_bvh_options o = bvh_options(&s->a, 1);
    tg_bvh* bvh = NULL;
    tg_bvh_workspace* ws = NULL;
    CHECK_STATUS(tg_bvh_create(spot, &o, &bvh), TG_OK);
    CHECK_STATUS(tg_bvh_workspace_create(bvh, &ws), TG_OK);
    static bvh_answers got;
    memset(&got, 0, sizeof got);
    tg_status st = TG_OK;
    bool same = false;
    arm(s);
    switch (q->call) {
    case CLOSEST_BATCH:
        st = tg_bvh_closest_batch(bvh, queries, QUERY_COUNT, INFINITY, q->threads, got.closest);
        same = st == TG_OK && memcmp(got.closest, bvh_reference.closest, sizeof got.closest) == 0;
        break;
    case SIGNED_PSEUDO_BATCH:
        st = tg_bvh_signed_distance_batch(bvh, queries, QUERY_COUNT, TG_SIGN_PSEUDONORMAL, q->threads, got.pseudo);
        same = st == TG_OK && memcmp(got.pseudo, bvh_reference.pseudo, sizeof got.pseudo) == 0;
        break;
    case SIGNED_WINDING_BATCH:
        st = tg_bvh_signed_distance_batch(bvh, queries, QUERY_COUNT, TG_SIGN_WINDING, q->threads, got.winding);
        same = st == TG_OK && memcmp(got.winding, bvh_reference.winding, sizeof got.winding) == 0;
        break;
    case CLOSEST:
        for (int i = 0; i < QUERY_COUNT && st == TG_OK; ++i)
            st = tg_bvh_closest(bvh, ws, queries + 3 * i, INFINITY, got.closest + i);
        same = st == TG_OK && memcmp(got.closest, bvh_reference.closest, sizeof got.closest) == 0;
        break;
    case SIGNED_PSEUDO:
    case SIGNED_WINDING: {
        tg_sign_method method = q->call == SIGNED_PSEUDO ? TG_SIGN_PSEUDONORMAL : TG_SIGN_WINDING;
        tg_signed_hit* out = q->call == SIGNED_PSEUDO ? got.pseudo : got.winding;
        for (int i = 0; i < QUERY_COUNT && st == TG_OK; ++i)
            st = tg_bvh_signed_distance(bvh, ws, queries + 3 * i, method, out + i);
        same = st == TG_OK &&
               memcmp(out, q->call == SIGNED_PSEUDO ? bvh_reference.pseudo : bvh_reference.winding, sizeof got.pseudo) == 0;
        break;
    }
    case WINDING_NUMBER:
        for (int i = 0; i < QUERY_COUNT && st == TG_OK; ++i) st = tg_bvh_winding_number(bvh, ws, queries + 3 * i, got.wn + i);
        same = st == TG_OK && memcmp(got.wn, bvh_reference.wn, sizeof got.wn) == 0;
        break;
    case LOCATE:
        for (int i = 0; i < QUERY_COUNT && st == TG_OK; ++i)
            st = tg_bvh_locate(bvh, ws, queries + 3 * i, got.located + i, NULL);
        same = st == TG_OK && memcmp(got.located, bvh_reference.located, sizeof got.located) == 0;
        break;
    }
    disarm(s);
    if (st == TG_OK) CHECK_MSG(same, "%s: answers differ from the default allocator's", s->name);
    tg_bvh_workspace_destroy(ws);
    tg_bvh_destroy(bvh);
    return st;
}

static void sweep_bvh(void)
{
    tg_bvh_options o = bvh_options(NULL, 1);
    tg_bvh* bvh = NULL;
    tg_bvh_workspace* ws = NULL;
    CHECK_STATUS(tg_bvh_create(spot, &o, &bvh), TG_OK);
    CHECK_STATUS(tg_bvh_workspace_create(bvh, &ws), TG_OK);
    CHECK_STATUS(bvh_answer(bvh, ws, &bvh_reference), TG_OK);
    tg_bvh_workspace_destroy(ws);
    tg_bvh_destroy(bvh);

    const long dense = TG_TEST_WORK(400, 100), stride = TG_TEST_WORK(1, 5);
    static const int one = 1, two = 2;
    sweep_run("tg_bvh_create (winding data, 1 thread)", try_bvh_create, (void*)&one, dense, stride);
    sweep_run("tg_bvh_create (winding data, 2 threads)", try_bvh_create, (void*)&two, dense, stride);
    sweep_run("tg_bvh_workspace_create", try_bvh_workspace, NULL, dense, stride);
    static const struct {
        const char* name;
        bvh_query_ctx q;
    } calls[] = {
        {"tg_bvh_closest_batch (1 thread)", {CLOSEST_BATCH, 1}},
        {"tg_bvh_closest_batch (2 threads)", {CLOSEST_BATCH, 2}},
        {"tg_bvh_signed_distance_batch pseudonormal (1 thread)", {SIGNED_PSEUDO_BATCH, 1}},
        {"tg_bvh_signed_distance_batch pseudonormal (2 threads)", {SIGNED_PSEUDO_BATCH, 2}},
        {"tg_bvh_signed_distance_batch winding (1 thread)", {SIGNED_WINDING_BATCH, 1}},
        {"tg_bvh_signed_distance_batch winding (2 threads)", {SIGNED_WINDING_BATCH, 2}},
        {"tg_bvh_closest", {CLOSEST, 1}},
        {"tg_bvh_signed_distance pseudonormal", {SIGNED_PSEUDO, 1}},
        {"tg_bvh_signed_distance winding", {SIGNED_WINDING, 1}},
        {"tg_bvh_winding_number", {WINDING_NUMBER, 1}},
        {"tg_bvh_locate", {LOCATE, 1}},
    };
    for (size_t i = 0; i < sizeof calls / sizeof calls[0]; ++i)
        sweep_run(calls[i].name, try_bvh_query, (void*)&calls[i].q, dense, stride);
}

/* ---- geodesic solver and paths ---- */

typedef struct path_copy {
    size_t n;
    tg_surface_point* points;
    double* xyz;
    uint32_t* faces;
    tg_path_view v;
} path_copy;

static path_copy copy_path(const tg_path* p)
{
    path_copy c;
    tg_path_get_view(p, &c.v);
    c.n = c.v.point_count;
    c.points = malloc((c.n + 1) * sizeof *c.points);
    c.xyz = malloc((3 * c.n + 1) * sizeof *c.xyz);
    c.faces = malloc((c.n + 1) * sizeof *c.faces);
    if (c.n) {
        memcpy(c.points, c.v.points, c.n * sizeof *c.points);
        memcpy(c.xyz, c.v.xyz, 3 * c.n * sizeof *c.xyz);
        memcpy(c.faces, c.v.faces, (c.n - 1) * sizeof *c.faces);
    }
    c.v.points = c.points, c.v.xyz = c.xyz, c.v.faces = c.faces;
    return c;
}

static void free_path_copy(path_copy* c) { free(c->points), free(c->xyz), free(c->faces); }

static bool same_path(const tg_path* p, const path_copy* ref)
{
    tg_path_view v;
    tg_path_get_view(p, &v);
    return v.point_count == ref->n && same_bytes(v.points, ref->points, ref->n * sizeof *ref->points) &&
           same_bytes(v.xyz, ref->xyz, 3 * ref->n * sizeof *ref->xyz) &&
           same_bytes(v.faces, ref->faces, (ref->n ? ref->n - 1 : 0) * sizeof *ref->faces) &&
           same_double(v.length, ref->v.length) && same_double(v.initial_length, ref->v.initial_length) &&
           same_double(v.max_angle_defect, ref->v.max_angle_defect) && v.status == ref->v.status &&
           v.global == ref->v.global && v.iterations == ref->v.iterations &&
           v.edge_path_vertices == ref->v.edge_path_vertices;
}

static path_copy short_path_reference; /* far_a to near_b, STRAIGHTEN, default allocator */
/* the straightener, asked for by name: the default method is EXACT, swept with the others below */
static const tg_path_options straighten = {TG_PATH_STRAIGHTEN, 0, 0.0, NULL, TG_PATH_CERTIFY_OFF, NULL, NULL};

/* A solver for a mesh, checked by its size and one short path against the default allocator's. */
typedef struct geodesic_ctx {
    const tg_mesh* mesh;
    size_t bytes;
    const path_copy* reference; /* far_a to near_b, STRAIGHTEN */
} geodesic_ctx;

static tg_status try_geodesic_create(sweep* s, void* ctx)
{
    const geodesic_ctx* gc = ctx;
    tg_geodesic_options o = {&s->a};
    tg_geodesic* g = NOT_NULL;
    arm(s);
    tg_status st = tg_geodesic_create(gc->mesh, &o, &g);
    disarm(s);
    CHECK_NULL_ON_FAILURE(s, st, g);
    if (st == TG_OK) {
        CHECK_EQ_INT(tg_geodesic_memory_bytes(g), gc->bytes);
        tg_geodesic_workspace* ws = NULL;
        tg_path* p = NULL;
        CHECK_STATUS(tg_geodesic_workspace_create(g, &ws), TG_OK);
        CHECK_STATUS(tg_path_create(&s->a, &p), TG_OK);
        CHECK_STATUS(tg_geodesic_path(g, ws, &far_a, &near_b, &straighten, p), TG_OK);
        CHECK_MSG(same_path(p, gc->reference), "%s: path differs from the default allocator's", s->name);
        tg_path_destroy(p);
        tg_geodesic_workspace_destroy(ws);
    }
    if (st == TG_OK || g == NULL) tg_geodesic_destroy(g);
    return st;
}

static void sweep_geodesic_create(const tg_mesh* m, const char* name, long dense, long stride)
{
    tg_geodesic* g = NULL;
    tg_geodesic_workspace* ws = NULL;
    tg_path* p = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    CHECK_STATUS(tg_geodesic_workspace_create(g, &ws), TG_OK);
    CHECK_STATUS(tg_path_create(NULL, &p), TG_OK);
    CHECK_STATUS(tg_geodesic_path(g, ws, &far_a, &near_b, &straighten, p), TG_OK);
    path_copy ref = copy_path(p);
    geodesic_ctx gc = {m, tg_geodesic_memory_bytes(g), &ref};
    sweep_run(name, try_geodesic_create, &gc, dense, stride);
    free_path_copy(&ref);
    tg_path_destroy(p);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
}

static tg_status try_geodesic_workspace(sweep* s, void* ctx)
{
    (void)ctx;
    tg_geodesic_options o = {&s->a};
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(spot, &o, &g), TG_OK);
    tg_geodesic_workspace* ws = NOT_NULL;
    arm(s);
    tg_status st = tg_geodesic_workspace_create(g, &ws);
    disarm(s);
    CHECK_NULL_ON_FAILURE(s, st, ws);
    if (st == TG_OK) {
        tg_path* p = NULL;
        CHECK_STATUS(tg_path_create(NULL, &p), TG_OK);
        CHECK_STATUS(tg_geodesic_path(g, ws, &far_a, &near_b, &straighten, p), TG_OK);
        CHECK_MSG(same_path(p, &short_path_reference), "%s: path differs from the default allocator's", s->name);
        tg_path_destroy(p);
    }
    if (st == TG_OK || ws == NULL) tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
    return st;
}

static tg_status try_path_create(sweep* s, void* ctx)
{
    (void)ctx;
    tg_path* p = NOT_NULL;
    arm(s);
    tg_status st = tg_path_create(&s->a, &p);
    disarm(s);
    CHECK_NULL_ON_FAILURE(s, st, p);
    if (st == TG_OK) {
        tg_path_view v;
        tg_path_get_view(p, &v);
        CHECK(v.point_count == 0 && v.status == TG_PATH_UNREACHABLE);
    }
    if (st == TG_OK || p == NULL) tg_path_destroy(p);
    return st;
}

typedef struct path_ctx {
    const tg_mesh* mesh;
    tg_surface_point from, to;
    tg_path_options options;
    const tg_surface_point* warm_to; /* a query from `from` to it first, into the same workspace
                                        and path (not failing); NULL: fresh ones */
    path_copy reference;
} path_ctx;

static tg_status try_geodesic_path(sweep* s, void* ctx)
{
    path_ctx* pc = ctx;
    tg_geodesic_options o = {&s->a};
    tg_geodesic* g = NULL;
    tg_geodesic_workspace* ws = NULL;
    tg_path* p = NULL;
    CHECK_STATUS(tg_geodesic_create(pc->mesh, &o, &g), TG_OK);
    CHECK_STATUS(tg_geodesic_workspace_create(g, &ws), TG_OK);
    CHECK_STATUS(tg_path_create(&s->a, &p), TG_OK);
    if (pc->warm_to) CHECK_STATUS(tg_geodesic_path(g, ws, &pc->from, pc->warm_to, &pc->options, p), TG_OK);
    arm(s);
    tg_status st = tg_geodesic_path(g, ws, &pc->from, &pc->to, &pc->options, p);
    disarm(s);
    tg_path_view v;
    tg_path_get_view(p, &v);
    if (st == TG_OK) {
        CHECK_MSG(same_path(p, &pc->reference), "%s: path differs from the default allocator's (%zu points, length %.17g vs %zu, %.17g)",
                  s->name, v.point_count, v.length, pc->reference.n, pc->reference.v.length);
    } else {
        CHECK_MSG(v.point_count == 0 && v.status == TG_PATH_UNREACHABLE && v.length == INFINITY,
                  "%s, allocation %ld failing: the path is not empty after %s (%zu points)", s->name, s->k,
                  tg_status_name(st), v.point_count);
        /* the workspace and path still work after the failure */
        CHECK_STATUS(tg_geodesic_path(g, ws, &pc->from, &pc->to, &pc->options, p), TG_OK);
        CHECK_MSG(same_path(p, &pc->reference), "%s, allocation %ld failing: the next query differs", s->name, s->k);
    }
    tg_path_destroy(p);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
    return st;
}

/* Sweeps one query; returns the allocations it made. The reference comes from a fresh solver,
 * workspace and path with the default allocator. */
static long sweep_path(path_ctx* pc, const char* what, long dense, long stride)
{
    tg_geodesic* g = NULL;
    tg_geodesic_workspace* ws = NULL;
    tg_path* p = NULL;
    CHECK_STATUS(tg_geodesic_create(pc->mesh, NULL, &g), TG_OK);
    CHECK_STATUS(tg_geodesic_workspace_create(g, &ws), TG_OK);
    CHECK_STATUS(tg_path_create(NULL, &p), TG_OK);
    CHECK_STATUS(tg_geodesic_path(g, ws, &pc->from, &pc->to, &pc->options, p), TG_OK);
    pc->reference = copy_path(p);
    tg_path_destroy(p);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
    static const char* method_names[] = {[TG_PATH_EXACT] = "exact", [TG_PATH_STRAIGHTEN] = "straighten",
                                         [TG_PATH_RELAX] = "relax", [TG_PATH_EDGE] = "edge"};
    char name[160];
    snprintf(name, sizeof name, "tg_geodesic_path %s%s%s%s (%zu points, %u iterations, %s)",
             method_names[pc->options.method], pc->options.certify ? ", certified" : "",
             pc->warm_to ? ", grown workspace" : "", what, pc->reference.n, pc->reference.v.iterations,
             tg_path_status_name(pc->reference.v.status));
    long used = sweep_run(name, try_geodesic_path, pc, dense, stride);
    free_path_copy(&pc->reference);
    return used;
}

/* RELAX between two rim faces of the spoke disk 170 degrees apart: the edge path runs through the
 * centre, and RELAX minimizes over the 94 spokes of the narrower side, where the fan kernel's
 * scratch (over 64 edges) is on the heap: the solver's allocator, not libc's. */
static void sweep_geodesic(const tg_mesh* troubled, const tg_mesh* disk)
{
    tg_geodesic_workspace* ws = NULL;
    tg_path* p = NULL;
    CHECK_STATUS(tg_geodesic_workspace_create(spot_g, &ws), TG_OK);
    CHECK_STATUS(tg_path_create(NULL, &p), TG_OK);
    CHECK_STATUS(tg_geodesic_path(spot_g, ws, &far_a, &near_b, &straighten, p), TG_OK);
    short_path_reference = copy_path(p);
    tg_path_destroy(p);
    tg_geodesic_workspace_destroy(ws);

    const long dense = TG_TEST_WORK(400, 150), stride = TG_TEST_WORK(1, 3);
    sweep_geodesic_create(spot, "tg_geodesic_create", dense, stride);
    if (troubled) sweep_geodesic_create(troubled, "tg_geodesic_create (misoriented, repeated-index, non-manifold faces)", dense, stride);
    sweep_run("tg_geodesic_workspace_create", try_geodesic_workspace, NULL, dense, stride);
    sweep_run("tg_path_create", try_path_create, NULL, dense, stride);

    /* RELAX converges linearly (1181 passes here, half a second with the default kernels):
     * Newton fans with unfolded roots and 100 passes grow the path to its final size (every
     * allocation of the full run) in a tenth of the time */
    static const tg_geodesic_kernel_options fast = {0, 0, TG_FAN_NEWTON, TG_ROOT_UNFOLD};
    for (int certify = 0; certify < 2; ++certify)
        for (int method = 0; method < 4; ++method)
            for (int warm = 0; warm < 2; ++warm) {
                if (warm && certify) continue;
                path_ctx pc;
                memset(&pc, 0, sizeof pc);
                pc.mesh = spot, pc.from = far_a, pc.to = far_b;
                pc.options.method = (tg_path_method)method;
                pc.options.certify = certify ? TG_PATH_CERTIFY_ON : TG_PATH_CERTIFY_OFF;
                pc.warm_to = warm ? &near_b : NULL;
                if (method == TG_PATH_RELAX) pc.options.kernel = &fast, pc.options.max_iterations = 100;
                sweep_path(&pc, "", dense, stride);
            }

    if (!disk) return;
    path_ctx pc;
    memset(&pc, 0, sizeof pc);
    pc.mesh = disk;
    pc.from = tg_surface_face(0, 0.02, 0.49, 0.49);
    pc.to = tg_surface_face(85, 0.02, 0.49, 0.49);
    pc.options.method = TG_PATH_RELAX;
    pc.options.kernel = &fast;
    sweep_path(&pc, " through a 200-spoke vertex", dense, stride);
    /* the same query again: the workspace and path are grown, so what it allocates is the fan
     * kernel's scratch, which must come from the solver's allocator too */
    pc.warm_to = &pc.to;
    long used = sweep_path(&pc, " through a 200-spoke vertex", dense, stride);
    CHECK_MSG(used > 0, "RELAX across a fan of 94 spokes allocated nothing through the solver's allocator");
}

/* ---- exact fields ---- */

enum { FIELD_SOURCES = 3, FIELD_POINTS = 40 };
static tg_surface_point field_sources[FIELD_SOURCES];
static tg_surface_point field_points[FIELD_POINTS];
static double field_limit; /* a third of the largest distance */

typedef enum field_call { FIELD, FIELD_AT, FIELD_AT_POINTS_ONLY, FIELD_BATCH } field_call;

typedef struct field_ctx {
    field_call call;
    bool limited;
    int workspace; /* 0: a temporary one from options.allocator; 1: a fresh one; 2: one grown by a smaller field */
    int threads;   /* batch */
    size_t nv;
    double* ref_vertex; /* FIELD, FIELD_AT: nv; BATCH: FIELD_SOURCES * nv */
    double* ref_points;
    tg_field_stats ref_stats;
} field_ctx;

static tg_field_options field_options(const field_ctx* fc, const tg_allocator* a)
{
    tg_field_options o;
    memset(&o, 0, sizeof o);
    o.allocator = a;
    if (fc->limited) {
        o.limit = TG_FIELD_MAX_DISTANCE;
        o.max_distance = field_limit;
    }
    return o;
}

static tg_status run_field(const field_ctx* fc, const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_field_options* o,
                           double* vertex, double* points, tg_field_stats* stats)
{
    switch (fc->call) {
    case FIELD: return tg_geodesic_field(g, ws, field_sources, 2, o, vertex, stats);
    case FIELD_AT: return tg_geodesic_field_at(g, ws, field_sources, 2, field_points, FIELD_POINTS, o, points, vertex, stats);
    case FIELD_AT_POINTS_ONLY:
        return tg_geodesic_field_at(g, ws, field_sources, 2, field_points, FIELD_POINTS, o, points, NULL, stats);
    case FIELD_BATCH: return tg_geodesic_distance_matrix(g, field_sources, FIELD_SOURCES, o, fc->threads, vertex, stats);
    }
    return TG_ERR_INVALID_ARGUMENT;
}

static bool same_stats(const tg_field_stats* a, const tg_field_stats* b)
{
    return a->windows_created == b->windows_created && a->windows_propagated == b->windows_propagated &&
           a->windows_filtered == b->windows_filtered && a->pseudo_source_events == b->pseudo_source_events &&
           a->pseudo_source_vertices == b->pseudo_source_vertices && a->max_queue == b->max_queue &&
           a->peak_windows == b->peak_windows && a->peak_bytes == b->peak_bytes;
}

static bool all_bytes(const void* p, size_t n, unsigned char byte)
{
    const unsigned char* b = p;
    for (size_t i = 0; i < n; ++i)
        if (b[i] != byte) return false;
    return true;
}

static tg_status try_field(sweep* s, void* ctx)
{
    field_ctx* fc = ctx;
    size_t nv = fc->nv, rows = fc->call == FIELD_BATCH ? FIELD_SOURCES : 1;
    const tg_geodesic* g = spot_g;
    tg_geodesic* own_g = NULL;
    tg_geodesic_workspace* ws = NULL;
    if (fc->workspace) {
        tg_geodesic_options go = {&s->a};
        CHECK_STATUS(tg_geodesic_create(spot, &go, &own_g), TG_OK);
        g = own_g;
        CHECK_STATUS(tg_geodesic_workspace_create(g, &ws), TG_OK);
        if (fc->workspace == 2) {
            tg_field_options small = field_options(fc, NULL);
            small.limit = TG_FIELD_MAX_DISTANCE;
            small.max_distance = field_limit * 0.25;
            double* tmp = malloc(nv * sizeof *tmp);
            CHECK_STATUS(tg_geodesic_field(g, ws, field_sources, 1, &small, tmp, NULL), TG_OK);
            free(tmp);
        }
    }
    tg_field_options o = field_options(fc, &s->a);
    double* vertex = malloc(rows * nv * sizeof *vertex);
    double* points = malloc(FIELD_POINTS * sizeof *points);
    memset(vertex, 0xA5, rows * nv * sizeof *vertex);
    memset(points, 0xA5, FIELD_POINTS * sizeof *points);
    tg_field_stats stats;
    memset(&stats, 0xA5, sizeof stats);
    arm(s);
    tg_status st = run_field(fc, g, ws, &o, vertex, points, &stats);
    disarm(s);
    bool has_vertex = fc->call != FIELD_AT_POINTS_ONLY, has_points = fc->call == FIELD_AT || fc->call == FIELD_AT_POINTS_ONLY;
    if (st == TG_OK) {
        CHECK_MSG(!has_vertex || same_bytes(vertex, fc->ref_vertex, rows * nv * sizeof *vertex),
                  "%s: vertex distances differ from the default allocator's", s->name);
        CHECK_MSG(!has_points || same_bytes(points, fc->ref_points, FIELD_POINTS * sizeof *points),
                  "%s: point distances differ from the default allocator's", s->name);
        CHECK_MSG(same_stats(&stats, &fc->ref_stats),
                  "%s: stats differ from the default allocator's: windows %llu %llu %llu, pseudo-sources %llu %llu, queue %llu, "
                  "peak windows %llu, peak bytes %zu; reference %llu %llu %llu, %llu %llu, %llu, %llu, %zu",
                  s->name, (unsigned long long)stats.windows_created, (unsigned long long)stats.windows_propagated,
                  (unsigned long long)stats.windows_filtered, (unsigned long long)stats.pseudo_source_events,
                  (unsigned long long)stats.pseudo_source_vertices, (unsigned long long)stats.max_queue,
                  (unsigned long long)stats.peak_windows, stats.peak_bytes, (unsigned long long)fc->ref_stats.windows_created,
                  (unsigned long long)fc->ref_stats.windows_propagated, (unsigned long long)fc->ref_stats.windows_filtered,
                  (unsigned long long)fc->ref_stats.pseudo_source_events,
                  (unsigned long long)fc->ref_stats.pseudo_source_vertices, (unsigned long long)fc->ref_stats.max_queue,
                  (unsigned long long)fc->ref_stats.peak_windows, fc->ref_stats.peak_bytes);
    } else if (fc->call == FIELD_BATCH) {
        /* complete rows or untouched ones */
        for (size_t r = 0; r < rows; ++r) {
            const double* row = vertex + r * nv;
            CHECK_MSG(all_bytes(row, nv * sizeof *row, 0xA5) || same_bytes(row, fc->ref_vertex + r * nv, nv * sizeof *row),
                      "%s, allocation %ld failing: row %zu is partial after %s", s->name, s->k, r, tg_status_name(st));
        }
        CHECK_MSG(all_bytes(&stats, sizeof stats, 0xA5), "%s, allocation %ld failing: stats written after %s", s->name,
                  s->k, tg_status_name(st));
    } else {
        CHECK_MSG(all_bytes(vertex, nv * sizeof *vertex, 0xA5) && all_bytes(points, FIELD_POINTS * sizeof *points, 0xA5) &&
                      all_bytes(&stats, sizeof stats, 0xA5),
                  "%s, allocation %ld failing: outputs written after %s", s->name, s->k, tg_status_name(st));
    }
    /* a workspace that saw a failure still gives the right field */
    if (st != TG_OK && ws) {
        CHECK_STATUS(run_field(fc, g, ws, &o, vertex, points, &stats), TG_OK);
        CHECK_MSG((!has_vertex || same_bytes(vertex, fc->ref_vertex, rows * nv * sizeof *vertex)) &&
                      (!has_points || same_bytes(points, fc->ref_points, FIELD_POINTS * sizeof *points)),
                  "%s, allocation %ld failing: the next field on the workspace differs", s->name, s->k);
    }
    free(vertex);
    free(points);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(own_g);
    return st;
}

static tg_status try_field_workspace(sweep* s, void* ctx)
{
    field_ctx* fc = ctx;
    tg_geodesic_options go = {&s->a};
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(spot, &go, &g), TG_OK);
    tg_geodesic_workspace* ws = NOT_NULL;
    arm(s);
    tg_status st = tg_geodesic_workspace_create(g, &ws);
    disarm(s);
    CHECK_NULL_ON_FAILURE(s, st, ws);
    if (st == TG_OK) {
        tg_field_options o = field_options(fc, NULL);
        double* d = malloc(fc->nv * sizeof *d);
        CHECK_STATUS(tg_geodesic_field(g, ws, field_sources, 2, &o, d, NULL), TG_OK);
        CHECK_MSG(same_bytes(d, fc->ref_vertex, fc->nv * sizeof *d), "%s: field differs from the default allocator's",
                  s->name);
        free(d);
    }
    if (st == TG_OK || ws == NULL) tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
    return st;
}

static void sweep_fields(void)
{
    size_t nv = tg_mesh_vertex_count(spot);
    tg_rng rng = {0xf1e1d};
    field_sources[0] = far_a;
    field_sources[1] = tg_surface_vertex(tg_mesh_triangles(spot)[3 * 1000 + 1]);
    field_sources[2] = far_b;
    for (int i = 0; i < FIELD_POINTS; ++i) field_points[i] = tg_test_random_surface_point(&rng, spot, NULL);
    double* d = malloc(nv * sizeof *d);
    CHECK_STATUS(tg_geodesic_field(spot_g, NULL, field_sources, 2, NULL, d, NULL), TG_OK);
    double max = 0;
    for (size_t i = 0; i < nv; ++i)
        if (isfinite(d[i]) && d[i] > max) max = d[i];
    field_limit = max / 3;
    free(d);

    const long dense = TG_TEST_WORK(300, 60), stride = TG_TEST_WORK(2, 7);
    static const char* call_names[] = {"tg_geodesic_field", "tg_geodesic_field_at", "tg_geodesic_field_at (points only)",
                                       "tg_geodesic_distance_matrix"};
    static const char* ws_names[] = {"temporary workspace", "fresh workspace", "grown workspace"};
    for (int call = 0; call <= FIELD_BATCH; ++call)
        for (int limited = 0; limited < 2; ++limited)
            for (int workspace = 0; workspace < 3; ++workspace)
                for (int threads = 1; threads <= 2; ++threads) {
                    if (call == FIELD_BATCH ? workspace != 0 : threads != 1) continue;
                    if (call != FIELD && workspace == 2) continue;
                    field_ctx fc;
                    memset(&fc, 0, sizeof fc);
                    fc.call = (field_call)call;
                    fc.limited = limited != 0;
                    fc.workspace = workspace;
                    fc.threads = threads;
                    fc.nv = nv;
                    size_t rows = call == FIELD_BATCH ? FIELD_SOURCES : 1;
                    fc.ref_vertex = malloc(rows * nv * sizeof *fc.ref_vertex);
                    fc.ref_points = malloc(FIELD_POINTS * sizeof *fc.ref_points);
                    tg_field_options o = field_options(&fc, NULL);
                    CHECK_STATUS(run_field(&fc, spot_g, NULL, &o, fc.ref_vertex, fc.ref_points, &fc.ref_stats), TG_OK);
                    char name[160];
                    if (call == FIELD_BATCH)
                        snprintf(name, sizeof name, "%s%s (%d thread%s)", call_names[call], limited ? " limited" : "",
                                 threads, threads > 1 ? "s" : "");
                    else
                        snprintf(name, sizeof name, "%s%s (%s)", call_names[call], limited ? " limited" : "",
                                 ws_names[workspace]);
                    sweep_run(name, try_field, &fc, dense, stride);
                    if (call == FIELD && workspace == 0)
                        sweep_run(limited ? "tg_geodesic_workspace_create (then a limited field)" : "tg_geodesic_workspace_create",
                                  try_field_workspace, &fc, dense, stride);
                    free(fc.ref_vertex);
                    free(fc.ref_points);
                }
}

/* ---- curves as sources: the field (at points too), the path from them, Voronoi cells of curve
 * sites, curve rows of a matrix (1 and 2 threads) ---- */

enum { CURVE_SEGMENTS = 24 };
static tg_surface_segment curve_segments[CURVE_SEGMENTS]; /* chords of faces and an edge */
static uint32_t curve_site[CURVE_SEGMENTS];               /* 3 sites */

typedef struct curve_ctx {
    int call; /* 0 field (and points), 1 path, 2 Voronoi, 3 matrix, 4 isolines (their field as out) */
    int threads;
    size_t nv;
    double *ref, *out;
    uint32_t *ref_label, *label;
    path_copy ref_path;
} curve_ctx;

static tg_status curve_call(curve_ctx* cc, const tg_allocator* a, double* out, double* out_points, uint32_t* label,
                            tg_path* p)
{
    tg_field_options o;
    memset(&o, 0, sizeof o);
    o.allocator = a;
    switch (cc->call) {
    case 0:
        return tg_geodesic_curve_field(spot_g, NULL, field_sources, 1, curve_segments, CURVE_SEGMENTS, field_points,
                                       FIELD_POINTS, &o, out_points, out, NULL);
    case 1: return tg_geodesic_curve_path(spot_g, NULL, NULL, 0, curve_segments, CURVE_SEGMENTS, &far_b, NULL, p);
    case 2:
        return tg_geodesic_curve_voronoi(spot_g, NULL, NULL, 0, NULL, curve_segments, CURVE_SEGMENTS, curve_site, 3, &o,
                                         out, label, NULL);
    case 3:
        return tg_geodesic_curve_distance_matrix(spot_g, NULL, 0, NULL, curve_segments, CURVE_SEGMENTS, curve_site, 3,
                                                 NULL, 0, &o, cc->threads, out, NULL);
    default: {
        static const double levels[2] = {0.05, 0.2};
        tg_isolines* iso = NULL;
        if (tg_isolines_create(NULL, &iso) != TG_OK) return TG_ERR_OUT_OF_MEMORY; /* not under test: never fails */
        tg_status st = tg_geodesic_curve_isolines(spot_g, NULL, NULL, 0, curve_segments, CURVE_SEGMENTS, levels, 2, &o,
                                                  iso, out, NULL);
        tg_isolines_view v;
        tg_isolines_get_view(iso, &v);
        if (st == TG_OK && out_points) out_points[0] = (double)v.point_count, out_points[1] = v.point_count ? v.xyz[0] : 0.0;
        if (st != TG_OK) CHECK_MSG(v.polyline_count == 0, "curve isolines: not empty after %s", tg_status_name(st));
        tg_isolines_destroy(iso);
        return st;
    }
    }
}

static tg_status try_curve(sweep* s, void* ctx)
{
    curve_ctx* cc = ctx;
    size_t n = (cc->call == 3 ? 3 : 1) * cc->nv + FIELD_POINTS;
    for (size_t i = 0; i < n; ++i) cc->out[i] = -7.0;
    tg_path* p = NULL;
    if (cc->call == 1) CHECK_STATUS(tg_path_create(NULL, &p), TG_OK);
    /* the path's workspace is a temporary one from the solver's allocator: a solver with s->a */
    tg_geodesic* g = spot_g;
    tg_geodesic_options go = {&s->a};
    if (cc->call == 1) {
        CHECK_STATUS(tg_geodesic_create(spot, &go, &g), TG_OK);
        tg_geodesic* keep = spot_g;
        spot_g = g;
        arm(s);
        tg_status st = curve_call(cc, NULL, NULL, NULL, NULL, p);
        disarm(s);
        spot_g = keep;
        tg_path_view v;
        tg_path_get_view(p, &v);
        if (st == TG_OK)
            CHECK_MSG(same_path(p, &cc->ref_path), "%s: the path differs from the default allocator's", s->name);
        else
            CHECK_MSG(v.point_count == 0, "%s, allocation %ld failing: the path is not empty", s->name, s->k);
        tg_path_destroy(p);
        tg_geodesic_destroy(g);
        return st;
    }
    arm(s);
    tg_status st = curve_call(cc, &s->a, cc->out, cc->out + n - FIELD_POINTS, cc->label, NULL);
    disarm(s);
    /* the points' distances: the field's only; the isolines' point count and first coordinate there */
    size_t written = cc->call == 0 ? n : cc->call == 4 ? n - FIELD_POINTS + 2 : n - FIELD_POINTS;
    if (st == TG_OK) {
        CHECK_MSG(same_bytes(cc->out, cc->ref, written * sizeof *cc->out) &&
                      (!cc->label || same_bytes(cc->label, cc->ref_label, cc->nv * sizeof *cc->label)),
                  "%s: the result differs from the default allocator's", s->name);
    } else {
        bool untouched = true;
        for (size_t i = 0; i < (cc->call == 3 ? 0 : n); ++i) untouched = untouched && cc->out[i] == -7.0;
        CHECK_MSG(untouched, "%s, allocation %ld failing: the outputs were written", s->name, s->k);
    }
    return st;
}

static void sweep_curves(void)
{
    size_t nv = tg_mesh_vertex_count(spot);
    const uint32_t* t = tg_mesh_triangles(spot);
    tg_rng rng = {0xc0e5};
    for (int i = 0; i < CURVE_SEGMENTS; ++i) {
        uint32_t f = (uint32_t)(tg_rng_next(&rng) % tg_mesh_face_count(spot));
        double u = tg_rng_unit(&rng) * 0.5, w = tg_rng_unit(&rng) * 0.5;
        curve_segments[i].a = tg_surface_face(f, 1 - u - w, u, w);
        curve_segments[i].b = i % 4 ? tg_surface_edge(3 * f + (uint32_t)(i % 3), tg_rng_unit(&rng))
                                    : tg_surface_vertex(t[3 * f + 2]);
        curve_site[i] = (uint32_t)(i % 3);
    }
    const long dense = TG_TEST_WORK(300, 60), stride = TG_TEST_WORK(2, 7);
    static const char* names[] = {"tg_geodesic_curve_field (and points)", "tg_geodesic_curve_path",
                                  "tg_geodesic_curve_voronoi", "tg_geodesic_curve_distance_matrix",
                                  "tg_geodesic_curve_isolines"};
    for (int call = 0; call < 5; ++call)
        for (int threads = 1; threads <= (call == 3 ? 2 : 1); ++threads) {
            curve_ctx cc;
            memset(&cc, 0, sizeof cc);
            cc.call = call, cc.threads = threads, cc.nv = nv;
            size_t n = 3 * nv + FIELD_POINTS;
            cc.ref = malloc(n * sizeof *cc.ref), cc.out = malloc(n * sizeof *cc.out);
            if (call == 2) cc.ref_label = malloc(nv * sizeof *cc.ref_label), cc.label = malloc(nv * sizeof *cc.label);
            size_t used = (call == 3 ? 3 : 1) * nv + FIELD_POINTS;
            tg_path* p = NULL;
            CHECK_STATUS(tg_path_create(NULL, &p), TG_OK);
            CHECK_STATUS(curve_call(&cc, NULL, cc.ref, cc.ref + used - FIELD_POINTS, cc.ref_label, p), TG_OK);
            if (call == 1) cc.ref_path = copy_path(p);
            tg_path_destroy(p);
            char name[160];
            snprintf(name, sizeof name, "%s (%d thread%s)", names[call], threads, threads > 1 ? "s" : "");
            sweep_run(name, try_curve, &cc, dense, stride);
            if (call == 1) free_path_copy(&cc.ref_path);
            free(cc.ref), free(cc.out), free(cc.ref_label), free(cc.label);
        }
}

/* ---- Voronoi labels and farthest-point sampling ---- */

typedef struct nearest_ctx {
    int fps;       /* 0: tg_geodesic_voronoi of field_sources; 1: 12 farthest points from field_sources[1], a
                      vertex; 2: the Voronoi cells with their boundaries */
    int workspace; /* 0: a temporary one from options.allocator; 1: a fresh one */
    size_t nv;
    uint32_t *ref_label, ref_samples[12];
    double* ref_dist;
    double* ref_xyz; /* the boundaries' points */
    size_t ref_points;
} nearest_ctx;

/* The boundaries' point count and positions equal the reference's. */
static bool same_boundaries(const nearest_ctx* nc, const tg_voronoi_boundaries* b)
{
    tg_voronoi_boundaries_view v;
    tg_voronoi_boundaries_get_view(b, &v);
    return v.point_count == nc->ref_points && same_bytes(v.xyz, nc->ref_xyz, 3 * v.point_count * sizeof(double));
}

/* An object left empty (as after a failure). */
static bool no_boundaries(const tg_voronoi_boundaries* b)
{
    tg_voronoi_boundaries_view v;
    tg_voronoi_boundaries_get_view(b, &v);
    return v.polyline_count == 0 && v.point_count == 0 && !v.points && !v.xyz;
}

static tg_status run_nearest(const nearest_ctx* nc, const tg_geodesic* g, tg_geodesic_workspace* ws,
                             const tg_field_options* o, uint32_t* label, double* dist, uint32_t* samples,
                             tg_voronoi_boundaries* bounds)
{
    if (nc->fps == 1)
        return tg_geodesic_farthest_point_sampling(g, ws, field_sources[1].index, 0, 12, o, samples, dist, label, NULL);
    return tg_geodesic_voronoi(g, ws, field_sources, FIELD_SOURCES, o, nc->fps == 2 ? bounds : NULL, dist, label, NULL);
}

static tg_status try_nearest(sweep* s, void* ctx)
{
    nearest_ctx* nc = ctx;
    size_t nv = nc->nv;
    const tg_geodesic* g = spot_g;
    tg_geodesic* own_g = NULL;
    tg_geodesic_workspace* ws = NULL;
    if (nc->workspace) {
        tg_geodesic_options go = {&s->a};
        CHECK_STATUS(tg_geodesic_create(spot, &go, &own_g), TG_OK);
        g = own_g;
        CHECK_STATUS(tg_geodesic_workspace_create(g, &ws), TG_OK);
    }
    tg_field_options o;
    memset(&o, 0, sizeof o);
    o.allocator = &s->a;
    uint32_t* label = malloc(nv * sizeof *label);
    double* dist = malloc(nv * sizeof *dist);
    uint32_t samples[12];
    memset(label, 0xA5, nv * sizeof *label);
    memset(dist, 0xA5, nv * sizeof *dist);
    memset(samples, 0xA5, sizeof samples);
    /* the result object made with the failing allocator (its arrays are part of the sweep), and
     * holding an earlier result that a failure must clear */
    tg_voronoi_boundaries* bounds = NULL;
    CHECK_STATUS(tg_voronoi_boundaries_create(&s->a, &bounds), TG_OK);
    if (nc->fps == 2) CHECK_STATUS(run_nearest(nc, g, ws, NULL, NULL, dist, samples, bounds), TG_OK);
    memset(dist, 0xA5, nv * sizeof *dist);
    arm(s);
    tg_status st = run_nearest(nc, g, ws, &o, label, dist, samples, bounds);
    disarm(s);
    if (nc->fps == 2 && st != TG_OK)
        CHECK_MSG(no_boundaries(bounds), "%s, allocation %ld failing: boundaries left after %s", s->name, s->k,
                  tg_status_name(st));
    if (st == TG_OK) {
        CHECK_MSG(same_bytes(label, nc->ref_label, nv * sizeof *label) && same_bytes(dist, nc->ref_dist, nv * sizeof *dist) &&
                      (nc->fps != 1 || same_bytes(samples, nc->ref_samples, sizeof samples)) &&
                      (nc->fps != 2 || same_boundaries(nc, bounds)),
                  "%s: results differ from the default allocator's", s->name);
    } else {
        CHECK_MSG(all_bytes(label, nv * sizeof *label, 0xA5) && all_bytes(dist, nv * sizeof *dist, 0xA5) &&
                      all_bytes(samples, sizeof samples, 0xA5),
                  "%s, allocation %ld failing: outputs written after %s", s->name, s->k, tg_status_name(st));
    }
    if (st != TG_OK && ws) { /* the workspace still gives the right result */
        CHECK_STATUS(run_nearest(nc, g, ws, &o, label, dist, samples, bounds), TG_OK);
        if (nc->fps == 2) CHECK_MSG(same_boundaries(nc, bounds), "%s: boundaries differ after a failure", s->name);
        CHECK_MSG(same_bytes(label, nc->ref_label, nv * sizeof *label) && same_bytes(dist, nc->ref_dist, nv * sizeof *dist),
                  "%s, allocation %ld failing: the next call on the workspace differs", s->name, s->k);
    }
    free(label);
    free(dist);
    tg_voronoi_boundaries_destroy(bounds);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(own_g);
    return st;
}

static void sweep_nearest(void)
{
    const long dense = TG_TEST_WORK(300, 60), stride = TG_TEST_WORK(2, 7);
    static const char* names[3][2] = {{"tg_geodesic_voronoi (temporary workspace)", "tg_geodesic_voronoi (fresh workspace)"},
                                      {"tg_geodesic_farthest_point_sampling (temporary workspace)",
                                       "tg_geodesic_farthest_point_sampling (fresh workspace)"},
                                      {"tg_geodesic_voronoi with boundaries (temporary workspace)",
                                       "tg_geodesic_voronoi with boundaries (fresh workspace)"}};
    for (int fps = 0; fps < 3; ++fps)
        for (int workspace = 0; workspace < 2; ++workspace) {
            nearest_ctx nc;
            memset(&nc, 0, sizeof nc);
            nc.fps = fps, nc.workspace = workspace;
            nc.nv = tg_mesh_vertex_count(spot);
            nc.ref_label = malloc(nc.nv * sizeof *nc.ref_label);
            nc.ref_dist = malloc(nc.nv * sizeof *nc.ref_dist);
            tg_voronoi_boundaries* ref = NULL;
            CHECK_STATUS(tg_voronoi_boundaries_create(NULL, &ref), TG_OK);
            CHECK_STATUS(run_nearest(&nc, spot_g, NULL, NULL, nc.ref_label, nc.ref_dist, nc.ref_samples, ref), TG_OK);
            tg_voronoi_boundaries_view v;
            tg_voronoi_boundaries_get_view(ref, &v);
            nc.ref_points = v.point_count;
            nc.ref_xyz = malloc((3 * v.point_count + 1) * sizeof *nc.ref_xyz);
            if (v.point_count) memcpy(nc.ref_xyz, v.xyz, 3 * v.point_count * sizeof *nc.ref_xyz);
            tg_voronoi_boundaries_destroy(ref);
            sweep_run(names[fps][workspace], try_nearest, &nc, dense, stride);
            free(nc.ref_label);
            free(nc.ref_dist);
            free(nc.ref_xyz);
        }
}

/* ---- pictures ---- */

typedef struct render_ctx {
    tg_render_options options;
    char* reference;
    size_t size;
} render_ctx;

static tg_status try_render(sweep* s, void* ctx)
{
    render_ctx* rc = ctx;
    tg_mesh* m = failing_mesh(s);
    char path[4200];
    tmp_path(path, sizeof path, "render.png");
    remove(path);
    arm(s);
    tg_status st = tg_render_png(m, &rc->options, path, NULL);
    disarm(s);
    if (st == TG_OK) check_file_is(path, rc->reference, rc->size, s->name);
    tg_mesh_destroy(m);
    return st;
}

static void sweep_render(void)
{
    size_t nv = tg_mesh_vertex_count(spot);
    double* field = malloc(nv * sizeof *field);
    CHECK_STATUS(tg_geodesic_field(spot_g, NULL, &far_a, 1, NULL, field, NULL), TG_OK);
    tg_geodesic_workspace* ws = NULL;
    tg_path* p = NULL;
    CHECK_STATUS(tg_geodesic_workspace_create(spot_g, &ws), TG_OK);
    CHECK_STATUS(tg_path_create(NULL, &p), TG_OK);
    CHECK_STATUS(tg_geodesic_path(spot_g, ws, &far_a, &far_b, NULL, p), TG_OK);
    tg_path_view v;
    tg_path_get_view(p, &v);
    render_ctx rc;
    memset(&rc, 0, sizeof rc);
    rc.options.width = 160, rc.options.height = 120, rc.options.supersample = 2;
    rc.options.vertex_scalar = field;
    rc.options.polyline = v.xyz, rc.options.polyline_count = v.point_count;
    char path[4200];
    tmp_path(path, sizeof path, "render_reference.png");
    CHECK_STATUS(tg_render_png(spot, &rc.options, path, NULL), TG_OK);
    rc.reference = read_whole(path, &rc.size);
    CHECK(rc.reference != NULL);
    if (rc.reference) sweep_run("tg_render_png (scalar field and polyline)", try_render, &rc, 100, 1);
    free(rc.reference);
    tg_path_destroy(p);
    tg_geodesic_workspace_destroy(ws);
    free(field);
}

/* ---- main ---- */

/* Face points near the two ends of the mesh along its longest bounding-box axis, and one near the
 * first. */
static void pick_endpoints(void)
{
    const double* p = tg_mesh_positions(spot);
    const uint32_t* t = tg_mesh_triangles(spot);
    const tg_mesh_report* r = tg_mesh_get_report(spot);
    int axis = 0;
    for (int j = 1; j < 3; ++j)
        if (r->bbox_max[j] - r->bbox_min[j] > r->bbox_max[axis] - r->bbox_min[axis]) axis = j;
    size_t nf = tg_mesh_face_count(spot), lo = 0, hi = 0;
    double clo = INFINITY, chi = -INFINITY, c0[3] = {0, 0, 0};
    for (size_t f = 0; f < nf; ++f) {
        double c = p[3 * t[3 * f] + axis] + p[3 * t[3 * f + 1] + axis] + p[3 * t[3 * f + 2] + axis];
        if (c < clo) clo = c, lo = f;
        if (c > chi) chi = c, hi = f;
    }
    far_a = tg_surface_face((uint32_t)lo, 0.2, 0.3, 0.5);
    far_b = tg_surface_face((uint32_t)hi, 0.6, 0.1, 0.3);
    tg_surface_point_position(spot, &far_a, c0);
    /* the nearest other face centroid at least a few edge lengths away: a short path */
    double best = INFINITY, span = r->bbox_max[axis] - r->bbox_min[axis];
    size_t near = lo;
    for (size_t f = 0; f < nf; ++f) {
        double d2 = 0;
        for (int j = 0; j < 3; ++j) {
            double c = (p[3 * t[3 * f] + j] + p[3 * t[3 * f + 1] + j] + p[3 * t[3 * f + 2] + j]) / 3 - c0[j];
            d2 += c * c;
        }
        if (d2 > (0.1 * span) * (0.1 * span) && d2 < best) best = d2, near = f;
    }
    near_b = tg_surface_face((uint32_t)near, 1.0 / 3, 1.0 / 3, 1.0 / 3);
}

static void remove_fixture_files(void)
{
    static const char* more[] = {"written.obj", "written.ply", "reference.obj", "reference.ply", "render.png",
                                 "render_reference.png"};
    char path[4200];
    for (size_t i = 0; i < sizeof fixture_files / sizeof fixture_files[0]; ++i) {
        tmp_path(path, sizeof path, fixture_files[i]);
        remove(path);
    }
    for (size_t i = 0; i < sizeof more / sizeof more[0]; ++i) {
        tmp_path(path, sizeof path, more[i]);
        remove(path);
    }
    rmdir(tmp_dir);
}

int main(void)
{
    const char* tmp = getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp";
    snprintf(tmp_dir, sizeof tmp_dir, "%s/tg_oom_sweep_XXXXXX", tmp);
    if (!mkdtemp(tmp_dir)) {
        TG_FAIL_("cannot make a directory under %s", tmp);
        return tg_test_finish();
    }
    char path[4200];
    spot_path(path, sizeof path);
    tg_diag d;
    CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &spot), TG_OK);
    if (!spot) {
        rmdir(tmp_dir);
        return tg_test_finish();
    }
    CHECK_STATUS(tg_geodesic_create(spot, NULL, &spot_g), TG_OK);
    CHECK(write_fixture_files(spot));
    CHECK(write_polygon_files());
    pick_endpoints();
    make_queries();

    sweep_mesh_create(tg_mesh_positions(spot), tg_mesh_vertex_count(spot), tg_mesh_triangles(spot),
                      tg_mesh_face_count(spot), "tg_mesh_create");
    tg_mesh* troubled = troubled_spot();
    tg_mesh* disk = spoke_disk();
    sweep_loads();
    sweep_writers();
    sweep_bvh();
    sweep_geodesic(troubled, disk);
    sweep_fields();
    sweep_curves();
    sweep_nearest();
    sweep_render();

    tg_mesh_destroy(troubled);
    tg_mesh_destroy(disk);
    free((void*)ply_scalar());
    free_path_copy(&short_path_reference);
    tg_geodesic_destroy(spot_g);
    tg_mesh_destroy(spot);
    remove_fixture_files();
    return tg_test_finish();
}
