/* test_io_roundtrip.c - writers against readers: OBJ and PLY written by tg_mesh_write_obj /
 * tg_mesh_write_ply read back with bit-identical positions and identical triangles (tricky
 * doubles included); PLY scalars (inf and NaN included) round-trip through
 * tg_ply_read_vertex_scalar; writer and scalar-reader argument errors. */
#include "tg_test.h"

#include <trigeo.h>

static void temp_path(char* out, size_t cap, const char* file)
{
    const char* dir = getenv("TG_BUILD_DIR");
    snprintf(out, cap, "%s/%s", dir ? dir : ".", file);
}

/* Doubles that stress a text round trip: signed zero, subnormals, extremes, 17-digit values. */
static double tricky(tg_rng* r, size_t i)
{
    static const double special[] = {0.0, -0.0, 0.1, -1.0 / 3.0, 4.9406564584124654e-324, 2.2250738585072009e-308,
                                     1.7976931348623157e308, -1e-300, 123456789.123456789, 9007199254740993.0,
                                     1e22, 1e23, 5e-324, 0.30000000000000004};
    if (i < sizeof special / sizeof special[0]) return special[i];
    switch (tg_rng_next(r) % 3) {
    case 0: return tg_rng_range(r, -1, 1);
    case 1: return ldexp(tg_rng_range(r, -1, 1), (int)(tg_rng_next(r) % 2000) - 1000);
    default: { /* any finite bit pattern */
        for (;;) {
            uint64_t u = tg_rng_next(r);
            double v;
            memcpy(&v, &u, sizeof v);
            if (isfinite(v)) return v;
        }
    }
    }
}

static tg_mesh* random_mesh(size_t nv, size_t nf, uint64_t seed)
{
    tg_rng r = {seed};
    double* xyz = malloc(3 * nv * sizeof *xyz);
    uint32_t* tri = malloc(3 * nf * sizeof *tri);
    for (size_t i = 0; i < 3 * nv; ++i) xyz[i] = tricky(&r, i);
    for (size_t i = 0; i < 3 * nf; ++i) tri[i] = (uint32_t)(tg_rng_next(&r) % nv);
    tg_mesh* m = NULL;
    tg_diag d;
    tg_status st = tg_mesh_create(xyz, nv, tri, nf, NULL, &d, &m);
    CHECK_MSG(st == TG_OK, "tg_mesh_create: %s", d.message);
    free(xyz);
    free(tri);
    return m;
}

static void check_identical(const tg_mesh* a, const tg_mesh* b, const char* what)
{
    if (!a || !b) {
        TG_FAIL_("%s: missing mesh", what);
        return;
    }
    CHECK_EQ_INT(tg_mesh_vertex_count(b), tg_mesh_vertex_count(a));
    CHECK_EQ_INT(tg_mesh_face_count(b), tg_mesh_face_count(a));
    if (tg_mesh_vertex_count(a) != tg_mesh_vertex_count(b) || tg_mesh_face_count(a) != tg_mesh_face_count(b)) return;
    size_t nv = tg_mesh_vertex_count(a), nf = tg_mesh_face_count(a), bad = 0, first = SIZE_MAX;
    for (size_t i = 0; i < 3 * nv; ++i)
        if (memcmp(&tg_mesh_positions(a)[i], &tg_mesh_positions(b)[i], sizeof(double)) != 0) {
            if (first == SIZE_MAX) first = i;
            bad++;
        }
    CHECK_MSG(bad == 0, "%s: %zu coordinates differ, first %zu: %.17g vs %.17g", what, bad, first,
              first == SIZE_MAX ? 0.0 : tg_mesh_positions(a)[first], first == SIZE_MAX ? 0.0 : tg_mesh_positions(b)[first]);
    CHECK_MSG(memcmp(tg_mesh_triangles(a), tg_mesh_triangles(b), 3 * nf * sizeof(uint32_t)) == 0, "%s: triangles differ",
              what);
}

static void test_obj_roundtrip(void)
{
    char path[1024];
    temp_path(path, sizeof path, "test_io_roundtrip.obj");
    for (uint64_t seed = 1; seed <= 3; ++seed) {
        tg_mesh* m = random_mesh(500 * seed, 900 * seed, seed);
        tg_diag d;
        CHECK_STATUS(tg_mesh_write_obj(m, path, &d), TG_OK);
        tg_mesh* back = NULL;
        CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &back), TG_OK);
        check_identical(m, back, "obj");
        tg_mesh_destroy(back);
        tg_mesh_destroy(m);
    }
    remove(path);
}

static void test_ply_roundtrip(void)
{
    char path[1024];
    temp_path(path, sizeof path, "test_io_roundtrip.ply");
    const size_t nv = 700, nf = 1300;
    tg_mesh* m = random_mesh(nv, nf, 42);
    double* dist = malloc(nv * sizeof *dist);
    double* other = malloc(nv * sizeof *other);
    tg_rng r = {7};
    for (size_t i = 0; i < nv; ++i) {
        dist[i] = tricky(&r, i);
        other[i] = (double)i * 0.5;
    }
    dist[3] = INFINITY; /* unreachable vertices of a distance field */
    dist[4] = -INFINITY;
    dist[5] = NAN;
    const tg_vertex_scalar scalars[2] = {{"distance", dist}, {"other_1", other}};
    tg_diag d;
    CHECK_STATUS(tg_mesh_write_ply(m, path, scalars, 2, &d), TG_OK);
    tg_mesh* back = NULL;
    CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &back), TG_OK);
    check_identical(m, back, "ply");
    tg_mesh_destroy(back);

    /* scalars: count query, exact capacity, bit-identical values */
    size_t count = 12345;
    CHECK_STATUS(tg_ply_read_vertex_scalar(path, "distance", NULL, 0, &count, &d), TG_OK);
    CHECK_EQ_INT(count, nv);
    double* got = malloc((nv + 1) * sizeof *got);
    got[nv] = 99.0;
    CHECK_STATUS(tg_ply_read_vertex_scalar(path, "distance", got, nv, &count, &d), TG_OK);
    CHECK_EQ_INT(count, nv);
    CHECK_MSG(memcmp(got, dist, nv * sizeof *got) == 0, "distance scalars differ");
    CHECK(got[nv] == 99.0); /* nothing written past the count */
    CHECK_STATUS(tg_ply_read_vertex_scalar(path, "other_1", got, nv + 1, &count, &d), TG_OK);
    CHECK_MSG(memcmp(got, other, nv * sizeof *got) == 0, "other_1 scalars differ");
    /* x is a vertex scalar too */
    CHECK_STATUS(tg_ply_read_vertex_scalar(path, "x", got, nv, &count, &d), TG_OK);
    int xs_equal = 1;
    for (size_t i = 0; i < nv; ++i) xs_equal &= memcmp(&got[i], &tg_mesh_positions(m)[3 * i], sizeof(double)) == 0;
    CHECK(xs_equal);

    /* errors: capacity, missing property, missing file; the caller's array is untouched */
    got[0] = -5.0;
    count = 0;
    CHECK_STATUS(tg_ply_read_vertex_scalar(path, "distance", got, nv - 1, &count, &d), TG_ERR_CAPACITY);
    CHECK_EQ_INT(count, nv);
    CHECK(got[0] == -5.0);
    CHECK_STATUS(tg_ply_read_vertex_scalar(path, "missing", got, nv, &count, &d), TG_ERR_PARSE);
    CHECK(strstr(d.message, "missing") != NULL);
    CHECK(d.line > 0);
    CHECK_STATUS(tg_ply_read_vertex_scalar(path, NULL, got, nv, &count, &d), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_ply_read_vertex_scalar(path, "distance", got, nv, NULL, &d), TG_ERR_INVALID_ARGUMENT);
    char missing[1024];
    temp_path(missing, sizeof missing, "test_io_roundtrip_missing.ply");
    CHECK_STATUS(tg_ply_read_vertex_scalar(missing, "distance", got, nv, &count, &d), TG_ERR_IO);
    CHECK(got[0] == -5.0);

    /* no scalars at all */
    CHECK_STATUS(tg_mesh_write_ply(m, path, NULL, 0, &d), TG_OK);
    back = NULL;
    CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_PLY, NULL, &d, &back), TG_OK);
    check_identical(m, back, "ply without scalars");
    tg_mesh_destroy(back);
    CHECK_STATUS(tg_ply_read_vertex_scalar(path, "distance", got, nv, &count, &d), TG_ERR_PARSE);

    /* bad scalar arguments */
    const tg_vertex_scalar bad_name[1] = {{"has space", dist}};
    const tg_vertex_scalar empty_name[1] = {{"", dist}};
    const tg_vertex_scalar null_values[1] = {{"d", NULL}};
    const tg_vertex_scalar clash_x[1] = {{"x", dist}};
    const tg_vertex_scalar twice[2] = {{"d", dist}, {"d", other}};
    CHECK_STATUS(tg_mesh_write_ply(m, path, bad_name, 1, &d), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_mesh_write_ply(m, path, empty_name, 1, &d), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_mesh_write_ply(m, path, null_values, 1, &d), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_mesh_write_ply(m, path, clash_x, 1, &d), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_mesh_write_ply(m, path, twice, 2, &d), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_mesh_write_ply(m, path, NULL, 1, &d), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_mesh_write_ply(NULL, path, NULL, 0, &d), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_mesh_write_obj(NULL, path, &d), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_mesh_write_obj(m, NULL, &d), TG_ERR_INVALID_ARGUMENT);
    /* an unwritable path is an I/O error naming it */
    char nodir[1024];
    temp_path(nodir, sizeof nodir, "no_such_directory_for_trigeo/x.ply");
    CHECK_STATUS(tg_mesh_write_ply(m, nodir, NULL, 0, &d), TG_ERR_IO);
    CHECK_EQ_STR(d.file, nodir);
    CHECK_STATUS(tg_mesh_write_obj(m, nodir, &d), TG_ERR_IO);
    CHECK(d.message[0] != '\0');

    remove(path);
    free(got);
    free(dist);
    free(other);
    tg_mesh_destroy(m);
}

/* A mesh loaded from each format, written as OBJ and as PLY, reads back identical. */
static void test_cross_format(void)
{
    const char* off = "OFF\n5 5 0\n0 0 0\n2 0 0\n2 2 0\n0 2 0\n1 1 3.25\n4 0 3 2 1\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n";
    tg_mesh* m = NULL;
    tg_diag d;
    CHECK_STATUS(tg_mesh_load_memory(off, strlen(off), "p.off", TG_FORMAT_AUTO, NULL, &d, &m), TG_OK);
    char obj_path[1024], ply_path[1024];
    temp_path(obj_path, sizeof obj_path, "test_io_roundtrip_cross.obj");
    temp_path(ply_path, sizeof ply_path, "test_io_roundtrip_cross.ply");
    CHECK_STATUS(tg_mesh_write_obj(m, obj_path, &d), TG_OK);
    CHECK_STATUS(tg_mesh_write_ply(m, ply_path, NULL, 0, &d), TG_OK);
    tg_mesh *a = NULL, *b = NULL;
    CHECK_STATUS(tg_mesh_load(obj_path, TG_FORMAT_AUTO, NULL, &d, &a), TG_OK);
    CHECK_STATUS(tg_mesh_load(ply_path, TG_FORMAT_AUTO, NULL, &d, &b), TG_OK);
    check_identical(m, a, "off -> obj");
    check_identical(m, b, "off -> ply");
    if (a) CHECK_EQ_INT(tg_mesh_face_count(a), 6);
    tg_mesh_destroy(a);
    tg_mesh_destroy(b);
    tg_mesh_destroy(m);
    remove(obj_path);
    remove(ply_path);
}

int main(void)
{
    test_obj_roundtrip();
    test_ply_roundtrip();
    test_cross_format();
    return tg_test_finish();
}
