/* test_io_counts.c - readers trust no count, and every refusal names its real cause: a binary
 * STL declaring fewer facets than it holds, an OFF declaring fewer faces or vertices than it
 * holds, a PLY with records after its declared ones or a value too many on a line, an OBJ 'f' or
 * 'v' with nothing after it are errors naming both numbers; padding after
 * a binary STL or PLY loads with a warning in diag; gzip data in memory is inflated (a .gz piped
 * in), truncated gzip says so; devices are refused, /proc files and pipes are read to their end,
 * and data that is no mesh says so; a vertex only a repeated-index face uses is named as such. */
#define _POSIX_C_SOURCE 200809L
#include "tg_test.h"

#include <pthread.h>
#include <sys/stat.h>
#include <trigeo.h>
#include <unistd.h>
#include <zlib.h>

typedef struct buf {
    unsigned char d[4096];
    size_t n;
} buf;

static void put(buf* b, const void* p, size_t n)
{
    memcpy(b->d + b->n, p, n);
    b->n += n;
}
static void put_f32(buf* b, float v) { put(b, &v, 4); } /* the tests run on little-endian hosts */
static void put_u32(buf* b, uint32_t v) { put(b, &v, 4); }

/* A binary STL declaring `declared` facets, holding `facets` (two triangles alternating), then
 * `pad` zero bytes. */
static void stl(buf* b, uint32_t declared, int facets, int pad)
{
    b->n = 0;
    char header[80];
    memset(header, ' ', sizeof header);
    memcpy(header, "binary", 6);
    put(b, header, 80);
    put_u32(b, declared);
    static const float tri[2][9] = {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {1, 0, 0, 1, 1, 0, 0, 1, 0}};
    for (int f = 0; f < facets; ++f) {
        for (int k = 0; k < 3; ++k) put_f32(b, k == 2 ? 1.0f : 0.0f);
        for (int k = 0; k < 9; ++k) put_f32(b, tri[f % 2][k]);
        put(b, "\0\0", 2);
    }
    for (int i = 0; i < pad; ++i) put(b, "", 1);
}

/* Loads from memory; returns the status, the message in msg (the mesh is freed). */
static tg_status load_mem(const void* data, size_t n, const char* name, tg_diag* d, size_t* out_faces)
{
    tg_mesh* m = NULL;
    memset(d, 0, sizeof *d);
    tg_status st = tg_mesh_load_memory(data, n, name, TG_FORMAT_AUTO, NULL, d, &m);
    if (out_faces) *out_faces = m ? tg_mesh_face_count(m) : 0;
    tg_mesh_destroy(m);
    return st;
}

/* The status and message must be as expected: every `needles` substring in the message. */
static void expect(const char* what, tg_status st, const tg_diag* d, tg_status want, const char* const* needles)
{
    bool ok = st == want;
    for (; ok && *needles; ++needles) ok = strstr(d->message, *needles) != NULL;
    CHECK_MSG(ok, "%s: status %s (want %s), message '%s'", what, tg_status_name(st), tg_status_name(want), d->message);
}

static void text_case(const char* what, const char* text, const char* name, tg_status want, const char* n0,
                      const char* n1, const char* n2)
{
    tg_diag d;
    const char* needles[4] = {n0, n1, n2, NULL};
    expect(what, load_mem(text, strlen(text), name, &d, NULL), &d, want, needles);
}

static void test_stl(void)
{
    buf b;
    tg_diag d;
    size_t faces;
    stl(&b, 1, 2, 0); /* the probe's file: 1 declared, 2 in the file: loaded 1 face, exit 0 */
    const char* lie[] = {"declares 1 facet", "holds 2 facet records", "wrong facet count", NULL};
    expect("STL count too small", load_mem(b.d, b.n, "lie.stl", &d, NULL), &d, TG_ERR_PARSE, lie);
    CHECK_EQ_INT(d.byte_offset, 80);
    stl(&b, 2, 2, 4); /* 4 padding bytes: loaded, with a warning */
    const char* pad[] = {"warning: ", "4 bytes after the last of the 2 declared facets", NULL};
    expect("STL padding", load_mem(b.d, b.n, "pad.stl", &d, &faces), &d, TG_OK, pad);
    CHECK_EQ_INT(faces, 2);
    stl(&b, 2, 2, 0); /* exact: no message */
    const char* none[] = {NULL};
    expect("STL exact", load_mem(b.d, b.n, "ok.stl", &d, &faces), &d, TG_OK, none);
    CHECK(faces == 2 && d.message[0] == '\0');
    stl(&b, 3, 2, 0);
    const char* trunc[] = {"declares 3 facets", "truncated", NULL};
    expect("STL count too large", load_mem(b.d, b.n, "short.stl", &d, NULL), &d, TG_ERR_PARSE, trunc);
}

static void test_off(void)
{
    text_case("OFF faces undercounted", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n", "a.off",
              TG_ERR_PARSE, "declares 1 face", "1 more record line", "wrong face count");
    text_case("OFF vertices undercounted", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n0.5 0.5 0\n3 0 1 2\n3 1 2 0\n", "b.off",
              TG_ERR_PARSE, "is a vertex line", "more vertices than the 3", "wrong vertex count");
    text_case("OFF trailing comment", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n# the end\n\n", "c.off", TG_OK, "", NULL,
              NULL);
}

static void test_ply(void)
{
    const char* h = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    char t[1024];
    snprintf(t, sizeof t, "%s0 0 0 5\n1 0 0\n0 1 0\n3 0 1 2\n", h); /* the probe: said "truncated file?" */
    text_case("PLY extra value", t, "a.ply", TG_ERR_PARSE, "vertex 0 has 4 values", "its 3 properties take 3",
              "does not declare");
    snprintf(t, sizeof t, "%s0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n", h);
    text_case("PLY records after the declared ones", t, "b.ply", TG_ERR_PARSE, "data continues after the last",
              "vertex 3, face 1", "wrong element count");
    snprintf(t, sizeof t, "%s0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n\n \n", h);
    text_case("PLY trailing blank lines", t, "c.ply", TG_OK, "", NULL, NULL);

    buf b;
    b.n = 0;
    const char* bh = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                     "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    put(&b, bh, strlen(bh));
    static const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    for (int k = 0; k < 9; ++k) put_f32(&b, v[k]);
    unsigned char face[13] = {3, 0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0};
    put(&b, face, 13);
    size_t exact = b.n;
    tg_diag d;
    put(&b, face, 13); /* a second face the header does not count */
    const char* extra[] = {"13 bytes follow the last declared record", "vertex 3, face 1", NULL};
    expect("binary PLY extra record", load_mem(b.d, b.n, "d.ply", &d, NULL), &d, TG_ERR_PARSE, extra);
    b.n = exact;
    put(&b, "\n", 1);
    const char* pad[] = {"warning: ", "1 padding bytes", NULL};
    expect("binary PLY padding", load_mem(b.d, b.n, "e.ply", &d, NULL), &d, TG_OK, pad);
}

static void test_obj(void)
{
    text_case("OBJ empty f", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf\n", "a.obj", TG_ERR_PARSE, "face has 0 corners", NULL,
              NULL);
    text_case("OBJ empty f at the end", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf", "b.obj", TG_ERR_PARSE,
              "face has 0 corners", NULL, NULL);
    text_case("OBJ empty v", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv\nf 1 2 3\n", "c.obj", TG_ERR_PARSE, "vertex needs 3", NULL,
              NULL);
    text_case("OBJ vt, vn, fo", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nfo x\nf 1 2 3\n", "d.obj", TG_OK, "",
              NULL, NULL);
    text_case("not a mesh", "Name:\tcat\nState:\tR (running)\n", "status", TG_ERR_PARSE, "not a mesh",
              "no OFF, PLY or STL header", NULL);
    text_case("OBJ without faces", "v 0 0 0\n", "e.obj", TG_ERR_PARSE, "1 vertices but no faces", NULL, NULL);
}

/* gzip data in memory (a .gz file piped to the CLI said "OBJ data has no faces") */
static void test_gzip(void)
{
    const char* obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n";
    unsigned char z[1024];
    size_t zn = 0;
    for (int member = 0; member < 2; ++member) { /* two gzip members, as `cat a.gz b.gz` makes */
        z_stream s;
        memset(&s, 0, sizeof s);
        CHECK(deflateInit2(&s, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) == Z_OK);
        const char* part = member ? obj + 24 : obj; /* "v 0 0 0\nv 1 0 0\nv 0 1 0\n" is 24 bytes */
        s.next_in = (Bytef*)(uintptr_t)part;
        s.avail_in = (uInt)(member ? strlen(obj) - 24 : 24);
        s.next_out = z + zn;
        s.avail_out = (uInt)(sizeof z - zn);
        CHECK(deflate(&s, Z_FINISH) == Z_STREAM_END);
        zn = sizeof z - s.avail_out;
        deflateEnd(&s);
    }
    tg_diag d;
    size_t faces = 0;
    const char* none[] = {NULL};
    expect("gzip in memory", load_mem(z, zn, "-", &d, &faces), &d, TG_OK, none);
    CHECK_EQ_INT(faces, 2);
    const char* trunc[] = {"truncated gzip data", NULL};
    expect("truncated gzip in memory", load_mem(z, zn / 2, "-", &d, NULL), &d, TG_ERR_PARSE, trunc);
}

static void* fifo_writer(void* path)
{
    FILE* f = fopen(path, "w");
    if (f) {
        fputs("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", f);
        fclose(f);
    }
    return NULL;
}

static void test_files(void)
{
    tg_mesh* m = NULL;
    tg_diag d;
    memset(&d, 0, sizeof d);
    CHECK_STATUS(tg_mesh_load("/dev/urandom", TG_FORMAT_AUTO, NULL, &d, &m), TG_ERR_IO);
    CHECK_MSG(strstr(d.message, "character device"), "/dev/urandom: '%s'", d.message);
    if (access("/proc/self/status", R_OK) == 0) { /* size 0 to stat, text when read */
        CHECK_STATUS(tg_mesh_load("/proc/self/status", TG_FORMAT_AUTO, NULL, &d, &m), TG_ERR_PARSE);
        CHECK_MSG(strstr(d.message, "not a mesh"), "/proc/self/status: '%s'", d.message);
    }
    char fifo[64];
    snprintf(fifo, sizeof fifo, "test_io_counts_fifo_%ld.obj", (long)getpid());
    remove(fifo);
    if (mkfifo(fifo, 0600) == 0) { /* a pipe is read to its end */
        pthread_t t;
        pthread_create(&t, NULL, fifo_writer, fifo);
        CHECK_STATUS(tg_mesh_load(fifo, TG_FORMAT_AUTO, NULL, &d, &m), TG_OK);
        CHECK(m && tg_mesh_face_count(m) == 1);
        tg_mesh_destroy(m);
        pthread_join(t, NULL);
        remove(fifo);
    }
}

/* A vertex only "f 4 4 4" names is not on the surface: the message says why. */
static void test_degenerate_only_vertex(void)
{
    const char* obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\nf 4 4 4\n";
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_load_memory(obj, strlen(obj), "x.obj", TG_FORMAT_AUTO, NULL, NULL, &m), TG_OK);
    if (!m) return;
    tg_diag d;
    memset(&d, 0, sizeof d);
    tg_surface_point v = tg_surface_vertex(3);
    CHECK_STATUS(tg_surface_point_validate(m, &v, &d), TG_ERR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(d.message, "only by faces with a repeated vertex index (face 1: 3 3 3)"), "message '%s'",
              d.message);
    tg_mesh_destroy(m);
}

int main(void)
{
    test_stl();
    test_off();
    test_ply();
    test_obj();
    test_gzip();
    test_files();
    test_degenerate_only_vertex();
    return tg_test_finish();
}
