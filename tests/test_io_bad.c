/* test_io_bad.c - malformed input: every case returns TG_ERR_PARSE / TG_ERR_INVALID_MESH /
 * TG_ERR_UNSUPPORTED with a diagnostic naming the file, a position (line for text, byte offset
 * for binary) and a message; every prefix of a valid file of each format and flavour fails
 * cleanly or loads (hand-written files, and prefixes of real corpus files); absurd header counts
 * allocate nothing large; failures leak nothing. */
#include "tg_test.h"

#include <trigeo.h>


/* ---- the case runner ---- */

typedef struct bad_case {
    const char* what;
    tg_format format;
    const char* text; /* NUL-terminated unless size is given */
    size_t size;      /* 0: strlen(text) */
    tg_status expected;
    uint64_t line;        /* expected diag.line (0: only "line or offset set" is checked) */
    uint64_t byte_offset; /* expected diag.byte_offset for binary cases (0: not checked) */
} bad_case;

static void run_case(const bad_case* bc)
{
    size_t size = bc->size ? bc->size : strlen(bc->text);
    tg_test_counting cnt = {0, 0, -1, 0};
    tg_allocator alloc = tg_test_failing_allocator(&cnt);
    tg_mesh_options opt = {&alloc};
    tg_diag d;
    memset(&d, 0x55, sizeof d); /* garbage in: the loader must fill it */
    tg_mesh* m = (tg_mesh*)&cnt;
    tg_status st = tg_mesh_load_memory(bc->text, size, "bad.input", bc->format, &opt, &d, &m);
    CHECK_MSG(st == bc->expected, "%s: status %s, expected %s (%s)", bc->what, tg_status_name(st),
              tg_status_name(bc->expected), st == TG_OK ? "loaded" : d.message);
    CHECK_MSG(m == NULL, "%s: *out_mesh not NULL on failure", bc->what);
    if (st == TG_OK) tg_mesh_destroy(m);
    CHECK_MSG(cnt.allocs == cnt.frees, "%s: %ld blocks leaked", bc->what, cnt.allocs - cnt.frees);
    CHECK_MSG(strcmp(d.file, "bad.input") == 0, "%s: diag.file is '%.40s'", bc->what, d.file);
    CHECK_MSG(d.message[0] != '\0' && strlen(d.message) < sizeof d.message, "%s: empty diag message", bc->what);
    CHECK_MSG(d.line > 0 || d.byte_offset > 0, "%s: neither line nor byte offset set (%s)", bc->what, d.message);
    if (bc->line) CHECK_MSG(d.line == bc->line, "%s: diag.line %llu, expected %llu (%s)", bc->what,
                            (unsigned long long)d.line, (unsigned long long)bc->line, d.message);
    if (bc->byte_offset)
        CHECK_MSG(d.byte_offset == bc->byte_offset, "%s: diag.byte_offset %llu, expected %llu (%s)", bc->what,
                  (unsigned long long)d.byte_offset, (unsigned long long)bc->byte_offset, d.message);
    /* nothing is allocated from an untrusted count: no request beyond a small multiple of the
     * input (the loader's own copy is size + 1) */
    CHECK_MSG(cnt.largest <= 64 * size + 65536, "%s: allocated %zu bytes for %zu bytes of input", bc->what, cnt.largest,
              size);
}

#define PARSE TG_ERR_PARSE
#define INVALID TG_ERR_INVALID_MESH
#define UNSUPP TG_ERR_UNSUPPORTED

static void test_text_cases(void)
{
    static const bad_case cases[] = {
        /* ---- OBJ ---- */
        {"obj empty", TG_FORMAT_OBJ, "", 0, PARSE, 1, 0},
        {"obj only comments", TG_FORMAT_OBJ, "# nothing\n# here\n", 0, PARSE, 3, 0},
        {"obj vertex with 2 coordinates", TG_FORMAT_OBJ, "v 0 0 0\nv 1 2\n", 0, PARSE, 2, 0},
        {"obj nan coordinate", TG_FORMAT_OBJ, "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n", 0, INVALID, 3, 0},
        {"obj inf coordinate", TG_FORMAT_OBJ, "v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n", 0, INVALID, 2, 0},
        {"obj huge coordinate overflows to inf", TG_FORMAT_OBJ, "v 0 0 1e999\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 0, INVALID, 1, 0},
        {"obj face index out of range", TG_FORMAT_OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n", 0, INVALID, 5, 0},
        {"obj face index 0", TG_FORMAT_OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 0, INVALID, 4, 0},
        {"obj negative index too far back", TG_FORMAT_OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", 0, INVALID, 4, 0},
        {"obj face with 2 corners", TG_FORMAT_OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", 0, PARSE, 4, 0},
        {"obj garbage corner", TG_FORMAT_OBJ, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", 0, PARSE, 4, 0},
        {"obj CR line ends count lines", TG_FORMAT_OBJ, "v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 9\r", 0, INVALID, 4, 0},
        {"obj CRLF line ends count lines", TG_FORMAT_OBJ, "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 9\r\n", 0, INVALID, 4, 0},
        /* ---- OFF ---- */
        {"off empty", TG_FORMAT_OFF, "", 0, PARSE, 1, 0},
        {"off keyword only", TG_FORMAT_OFF, "OFF\n", 0, PARSE, 2, 0},
        {"off only comments", TG_FORMAT_OFF, "# a\n# b\n", 0, PARSE, 3, 0},
        {"off not an off keyword", TG_FORMAT_OFF, "PLY\n3 1 0\n", 0, PARSE, 1, 0},
        {"off negative vertex count", TG_FORMAT_OFF, "OFF\n-3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 0, PARSE, 2, 0},
        {"off negative face count", TG_FORMAT_OFF, "OFF\n3 -1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 0, PARSE, 2, 0},
        {"off count not integer", TG_FORMAT_OFF, "OFF\n3.5 1 0\n", 0, PARSE, 2, 0},
        {"off absurd counts", TG_FORMAT_OFF, "OFF\n4000000000 4000000000 0\n0 0 0\n", 0, PARSE, 2, 0},
        {"off absurd face count", TG_FORMAT_OFF, "OFF\n3 99999999999 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 0, PARSE, 2, 0},
        {"off count overflowing int64", TG_FORMAT_OFF, "OFF\n99999999999999999999 1 0\n", 0, PARSE, 2, 0},
        {"off truncated vertices", TG_FORMAT_OFF, "OFF\n3 1 0\n0 0 0\n1 0 0\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n", 0, PARSE, 0, 0},
        {"off truncated faces", TG_FORMAT_OFF, "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n", 0, PARSE, 0, 0},
        {"off truncated inside a face", TG_FORMAT_OFF, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n", 0, PARSE, 0, 0},
        {"off vertex with 2 coordinates", TG_FORMAT_OFF, "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", 0, PARSE, 4, 0},
        {"off nan coordinate", TG_FORMAT_OFF, "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", 0, INVALID, 4, 0},
        {"off inf coordinate", TG_FORMAT_OFF, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 -inf\n3 0 1 2\n", 0, INVALID, 5, 0},
        {"off garbage coordinate", TG_FORMAT_OFF, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 z\n3 0 1 2\n", 0, PARSE, 5, 0},
        {"off index out of range", TG_FORMAT_OFF, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", 0, INVALID, 6, 0},
        {"off negative index", TG_FORMAT_OFF, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", 0, INVALID, 6, 0},
        {"off face with 2 corners", TG_FORMAT_OFF, "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n2 0 1\n", 0, PARSE, 7, 0},
        {"off face with 0 corners", TG_FORMAT_OFF, "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n0\n3 0 1 2\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n\n", 0, PARSE, 6, 0},
        {"off face with negative corners", TG_FORMAT_OFF, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n", 0, PARSE, 6, 0},
        {"off absurd corner count", TG_FORMAT_OFF, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n", 0, PARSE, 6, 0},
        {"off no faces", TG_FORMAT_OFF, "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", 0, PARSE, 0, 0},
        {"off binary", TG_FORMAT_OFF, "OFF BINARY\n\x00\x00\x00\x03", 15, UNSUPP, 1, 0},
        {"off 4OFF", TG_FORMAT_OFF, "4OFF\n3 1 0\n0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2\n", 0, UNSUPP, 1, 0},
        {"off nOFF", TG_FORMAT_OFF, "nOFF\n3\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 0, UNSUPP, 1, 0},
        {"off CR lines", TG_FORMAT_OFF, "OFF\r3 1 0\r0 0 0\r1 0 0\r0 1 0\r3 0 1 7\r", 0, INVALID, 6, 0},
        {"off mixed lines", TG_FORMAT_OFF, "OFF\r\n3 1 0\r0 0 0\n1 0 0\r\n0 1 0\r3 0 1 7\n", 0, INVALID, 6, 0},
        /* ---- PLY header ---- */
        {"ply empty", TG_FORMAT_PLY, "", 0, PARSE, 1, 0},
        {"ply magic only", TG_FORMAT_PLY, "ply\n", 0, PARSE, 2, 0},
        {"ply not ply", TG_FORMAT_PLY, "plyx\nformat ascii 1.0\nend_header\n", 0, PARSE, 1, 0},
        {"ply no end_header", TG_FORMAT_PLY, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n", 0, PARSE, 5, 0},
        {"ply no format", TG_FORMAT_PLY, "ply\nelement vertex 0\nend_header\n", 0, PARSE, 3, 0},
        {"ply unknown encoding", TG_FORMAT_PLY, "ply\nformat binary_middle_endian 1.0\nend_header\n", 0, PARSE, 2, 0},
        {"ply unknown keyword", TG_FORMAT_PLY, "ply\nformat ascii 1.0\nelemental vertex 3\nend_header\n", 0, PARSE, 3, 0},
        {"ply unknown type", TG_FORMAT_PLY, "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n", 0, PARSE, 4, 0},
        {"ply property before element", TG_FORMAT_PLY, "ply\nformat ascii 1.0\nproperty float x\nend_header\n", 0, PARSE, 3, 0},
        {"ply element without count", TG_FORMAT_PLY, "ply\nformat ascii 1.0\nelement vertex\nend_header\n", 0, PARSE, 3, 0},
        {"ply negative count", TG_FORMAT_PLY, "ply\nformat ascii 1.0\nelement vertex -3\nproperty float x\nend_header\n", 0, PARSE, 3, 0},
        {"ply count not integer", TG_FORMAT_PLY, "ply\nformat ascii 1.0\nelement vertex 3x\nend_header\n", 0, PARSE, 3, 0},
        {"ply float list count", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty list float int l\nend_header\n", 0, PARSE, 5, 0},
        {"ply absurd vertex count ascii", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 0, PARSE, 3, 0},
        {"ply absurd vertex count binary", TG_FORMAT_PLY,
         "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
         "property float z\nend_header\n0123456789012345678901234567890123456789", 0, PARSE, 3, 0},
        {"ply count beyond int64", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement vertex 99999999999999999999\nproperty float x\nend_header\n", 0, PARSE, 3, 0},
        {"ply absurd face count", TG_FORMAT_PLY,
         "ply\nformat binary_big_endian 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1000000000\nproperty list uchar int vertex_indices\nend_header\n\x03", 0, PARSE, 7, 0},
        {"ply absurd counts summed", TG_FORMAT_PLY,
         "ply\nformat binary_little_endian 1.0\nelement a 6\nproperty uchar v\nelement b 6\nproperty uchar v\n"
         "end_header\n0123456789", 0, PARSE, 5, 0},
        {"ply no vertex element", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n3 0 1 2\n", 0, PARSE, 0, 0},
        {"ply vertex without z", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nend_header\n0 0\n1 0\n0 1\n", 0, PARSE, 3, 0},
        {"ply face without list", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty int a\nend_header\n0 0 0\n1 0 0\n0 1 0\n3\n", 0, PARSE, 7, 0},
        {"ply float face indices", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar float vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 0, PARSE, 7, 0},
        {"ply no faces", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "end_header\n0 0 0\n1 0 0\n0 1 0\n", 0, PARSE, 0, 0},
        /* ---- PLY ascii body ---- */
        {"ply ascii truncated vertices", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 0\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1          ", 0, PARSE, 12, 0},
        {"ply ascii truncated face", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1     ", 0, PARSE, 13, 0},
        {"ply ascii index out of range", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 3\n", 0,
         INVALID, 14, 0},
        {"ply ascii negative index", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", 0, INVALID, 13, 0},
        {"ply ascii nan", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 NaN 0\n0 1 0\n3 0 1 2\n", 0, INVALID, 11, 0},
        {"ply ascii garbage value", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0x\n3 0 1 2\n", 0, PARSE, 12, 0},
        {"ply ascii face with 2 vertices", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", 0, PARSE, 13, 0},
        {"ply ascii negative list length", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n", 0, PARSE, 13, 0},
        {"ply ascii absurd list length", TG_FORMAT_PLY,
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uint int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n", 0,
         PARSE, 13, 0},
        /* ---- STL ascii ---- */
        {"stl empty", TG_FORMAT_STL, "", 0, PARSE, 1, 0},
        {"stl solid only", TG_FORMAT_STL, "solid x\n", 0, PARSE, 2, 0},
        {"stl no facets", TG_FORMAT_STL, "solid x\nendsolid x\n", 0, PARSE, 0, 0},
        {"stl truncated in loop", TG_FORMAT_STL, "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n", 0,
         PARSE, 6, 0},
        {"stl truncated in vertex", TG_FORMAT_STL, "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0", 0, PARSE,
         5, 0},
        {"stl missing endsolid", TG_FORMAT_STL,
         "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n", 0, PARSE, 9, 0},
        {"stl 2 vertices", TG_FORMAT_STL,
         "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid t\n", 0, PARSE, 0, 0},
        {"stl 4 vertices", TG_FORMAT_STL,
         "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 1 1 0\nendloop\n"
         "endfacet\nendsolid t\n", 0, PARSE, 7, 0},
        {"stl missing outer loop", TG_FORMAT_STL,
         "solid t\nfacet normal 0 0 1\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendfacet\nendsolid t\n", 0, PARSE, 3, 0},
        {"stl bad keyword", TG_FORMAT_STL,
         "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertx 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n", 0,
         PARSE, 5, 0},
        {"stl nan vertex", TG_FORMAT_STL,
         "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 nan 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n", 0,
         INVALID, 5, 0},
        {"stl garbage number", TG_FORMAT_STL,
         "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0,5\nendloop\nendfacet\nendsolid\n", 0,
         PARSE, 6, 0},
        {"stl text after endsolid", TG_FORMAT_STL,
         "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\njunk\n",
         0, PARSE, 10, 0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) run_case(&cases[i]);
}

/* ---- binary cases, built byte by byte ---- */

typedef struct bytes {
    unsigned char d[4096];
    size_t n;
} bytes;

static void put(bytes* b, const void* p, size_t n)
{
    memcpy(b->d + b->n, p, n);
    b->n += n;
}

static void put_str(bytes* b, const char* s) { put(b, s, strlen(s)); }

static void put_u32le(bytes* b, uint32_t v)
{
    unsigned char x[4] = {(unsigned char)v, (unsigned char)(v >> 8), (unsigned char)(v >> 16), (unsigned char)(v >> 24)};
    put(b, x, 4);
}

static void put_f32le(bytes* b, float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    put_u32le(b, u);
}

static void put_u8(bytes* b, unsigned v)
{
    unsigned char x = (unsigned char)v;
    put(b, &x, 1);
}

static const char* ply_le_head = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                 "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";

/* Three vertices and two faces (the second given by face2[0..n]) after ply_le_head. */
static void ply_le(bytes* b, float bad_y, const unsigned* face2, size_t n)
{
    b->n = 0;
    put_str(b, ply_le_head);
    const float v[9] = {0, 0, 0, 1, bad_y, 0, 0, 1, 0};
    for (int i = 0; i < 9; ++i) put_f32le(b, v[i]);
    put_u8(b, 3);
    for (unsigned k = 0; k < 3; ++k) put_u32le(b, k);
    for (size_t k = 0; k < n; ++k) k == 0 ? put_u8(b, face2[0]) : put_u32le(b, face2[k]);
}

static void run_bytes(const char* what, tg_format fmt, const bytes* b, tg_status expected, uint64_t offset)
{
    bad_case bc = {what, fmt, (const char*)b->d, b->n, expected, 0, offset};
    run_case(&bc);
}

static void test_binary_cases(void)
{
    static bytes b;
    size_t head = strlen(ply_le_head);
    const size_t face2_at = head + 36 + 13; /* offset of the second face record */

    static const unsigned ok_face[] = {3, 2, 1, 0};
    ply_le(&b, 0.0f, ok_face, 4);
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_load_memory(b.d, b.n, "good.ply", TG_FORMAT_PLY, NULL, NULL, &m), TG_OK);
    tg_mesh_destroy(m);

    static const unsigned out_of_range[] = {3, 0, 1, 3};
    ply_le(&b, 0.0f, out_of_range, 4);
    run_bytes("ply binary index out of range (fast path)", TG_FORMAT_PLY, &b, INVALID, face2_at + 1 + 8);
    static const unsigned negative[] = {3, 0, 0xFFFFFFFFu, 2};
    ply_le(&b, 0.0f, negative, 4);
    run_bytes("ply binary negative index (fast path)", TG_FORMAT_PLY, &b, INVALID, face2_at + 1 + 4);
    static const unsigned quad_bad[] = {4, 0, 1, 2, 7};
    ply_le(&b, 0.0f, quad_bad, 5);
    run_bytes("ply binary quad index out of range (general path)", TG_FORMAT_PLY, &b, INVALID, face2_at + 1 + 12);
    static const unsigned two[] = {2, 0, 1};
    ply_le(&b, 0.0f, two, 3);
    run_bytes("ply binary face with 2 vertices", TG_FORMAT_PLY, &b, PARSE, face2_at);
    static const unsigned zero[] = {0};
    ply_le(&b, 0.0f, zero, 1);
    run_bytes("ply binary face with 0 vertices", TG_FORMAT_PLY, &b, PARSE, face2_at);
    static const unsigned truncated[] = {3, 0, 1};
    ply_le(&b, 0.0f, truncated, 3);
    run_bytes("ply binary truncated face", TG_FORMAT_PLY, &b, PARSE, face2_at);
    ply_le(&b, 0.0f, ok_face, 1);
    b.n--;
    run_bytes("ply binary missing face", TG_FORMAT_PLY, &b, PARSE, face2_at);
    ply_le(&b, NAN, ok_face, 4);
    run_bytes("ply binary nan", TG_FORMAT_PLY, &b, INVALID, head + 16);
    ply_le(&b, INFINITY, ok_face, 4);
    run_bytes("ply binary inf", TG_FORMAT_PLY, &b, INVALID, head + 16);
    static const unsigned huge[] = {255, 0, 1, 2};
    ply_le(&b, 0.0f, huge, 4);
    run_bytes("ply binary list longer than the data", TG_FORMAT_PLY, &b, PARSE, face2_at);

    /* a signed count type with a negative count, in a generic (two-property) face element */
    b.n = 0;
    put_str(&b, "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty uchar x\nproperty uchar y\n"
                "property uchar z\nelement face 1\nproperty list char uchar vertex_indices\nproperty uchar red\nend_header\n");
    size_t body = b.n;
    const unsigned char v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    put(&b, v, 9);
    put_u8(&b, 0xFD); /* -3 */
    put_u8(&b, 0);
    put_u8(&b, 1);
    put_u8(&b, 2);
    put_u8(&b, 9);
    run_bytes("ply binary negative list count", TG_FORMAT_PLY, &b, PARSE, body + 9);
    /* a uint list count of 4e9 in a skipped element */
    b.n = 0;
    put_str(&b, "ply\nformat binary_little_endian 1.0\nelement junk 1\nproperty list uint int stuff\nelement vertex 3\n"
                "property float x\nproperty float y\nproperty float z\nend_header\n");
    body = b.n;
    put_u32le(&b, 4000000000u);
    for (int i = 0; i < 12; ++i) put_u32le(&b, 0);
    run_bytes("ply binary absurd list count in skipped element", TG_FORMAT_PLY, &b, PARSE, body);

    /* ---- STL binary ---- */
    b.n = 0;
    put_str(&b, "binary header");
    while (b.n < 80) put_u8(&b, 0);
    put_u32le(&b, 10); /* 10 facets declared, 1 present */
    for (int i = 0; i < 12; ++i) put_f32le(&b, (float)(i % 3));
    put_u8(&b, 0);
    put_u8(&b, 0);
    run_bytes("stl binary truncated", TG_FORMAT_STL, &b, PARSE, 80);
    b.n = 0;
    put_str(&b, "binary header");
    while (b.n < 80) put_u8(&b, 0);
    put_u32le(&b, 0xFFFFFFFFu);
    run_bytes("stl binary absurd facet count", TG_FORMAT_STL, &b, PARSE, 80);
    b.n = 0;
    put_str(&b, "binary header");
    while (b.n < 80) put_u8(&b, 0);
    put_u32le(&b, 1);
    for (int i = 0; i < 12; ++i) put_f32le(&b, i == 7 ? NAN : (float)(i % 3));
    put_u8(&b, 0);
    put_u8(&b, 0);
    run_bytes("stl binary nan", TG_FORMAT_STL, &b, INVALID, 84 + 28);
    b.n = 0;
    put_str(&b, "\x01\x02garbage that is not ascii STL");
    run_bytes("stl binary too short", TG_FORMAT_STL, &b, PARSE, b.n);
    b.n = 0;
    put_str(&b, "binary header");
    while (b.n < 80) put_u8(&b, 0);
    put_u32le(&b, 0);
    run_bytes("stl binary zero facets", TG_FORMAT_STL, &b, PARSE, 84);

    /* binary garbage through every reader */
    b.n = 0;
    for (unsigned i = 0; i < 2000; ++i) put_u8(&b, (i * 2654435761u) >> 13);
    const tg_format all[] = {TG_FORMAT_OBJ, TG_FORMAT_OFF, TG_FORMAT_PLY, TG_FORMAT_STL};
    for (int f = 0; f < 4; ++f) {
        tg_diag d;
        m = NULL;
        tg_status st = tg_mesh_load_memory(b.d, b.n, "garbage", all[f], NULL, &d, &m);
        CHECK_MSG(st != TG_OK && m == NULL && d.message[0], "garbage as format %d: %s", f, tg_status_name(st));
        tg_mesh_destroy(m);
    }
}

/* ---- every prefix of a valid file fails cleanly or loads ---- */

static void check_prefixes(const char* what, tg_format fmt, const unsigned char* data, size_t size)
{
    int loaded = 0, failed = 0, bad = 0;
    for (size_t n = 0; n <= size; ++n) {
        tg_test_counting cnt = {0, 0, -1, 0};
        tg_allocator alloc = tg_test_failing_allocator(&cnt);
        tg_mesh_options opt = {&alloc};
        tg_diag d;
        tg_mesh* m = NULL;
        tg_status st = tg_mesh_load_memory(data, n, "prefix", fmt, &opt, &d, &m);
        if (st == TG_OK) {
            loaded++;
            bad += m == NULL;
            tg_mesh_destroy(m);
        } else {
            failed++;
            bad += m != NULL || d.message[0] == '\0' || (d.line == 0 && d.byte_offset == 0) ||
                   (st != TG_ERR_PARSE && st != TG_ERR_INVALID_MESH);
        }
        bad += cnt.allocs != cnt.frees;
    }
    CHECK_MSG(bad == 0, "%s: %d of %zu prefixes misbehaved", what, bad, size + 1);
    /* the whole file loads; the empty prefix fails */
    CHECK_MSG(loaded >= 1 && failed >= 1, "%s: %d loaded, %d failed", what, loaded, failed);
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_load_memory(data, size, "whole", fmt, NULL, NULL, &m), TG_OK);
    tg_mesh_destroy(m);
}

static void test_prefixes(void)
{
    const char* obj = "# tetra\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvn 0 0 1\nf 1/1/1 3/1/1 2/1/1\nf 1 2 4\nf 2 3 4 \\\n\nf -4 -1 -2\n";
    const char* off = "OFF\n# c\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1 # x\n3 0 2 1\n3 0 1 3 255 0 0\n3 1\n 2 3\n3 0 3 2\n";
    const char* ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                      "3 0 1 2\n4 0 2 3 1\n";
    const char* stl = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
                      "facet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
    check_prefixes("obj", TG_FORMAT_OBJ, (const unsigned char*)obj, strlen(obj));
    check_prefixes("off", TG_FORMAT_OFF, (const unsigned char*)off, strlen(off));
    check_prefixes("ply ascii", TG_FORMAT_PLY, (const unsigned char*)ply, strlen(ply));
    check_prefixes("stl ascii", TG_FORMAT_STL, (const unsigned char*)stl, strlen(stl));

    static bytes b;
    static const unsigned quad[] = {4, 0, 1, 2, 0};
    ply_le(&b, 0.0f, quad, 5);
    check_prefixes("ply binary le", TG_FORMAT_PLY, b.d, b.n);
    /* the same mesh big-endian, with an extra element and a generic face layout */
    b.n = 0;
    put_str(&b, "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
                "property double z\nelement face 2\nproperty list ushort short vertex_indices\nproperty uchar red\n"
                "element extra 2\nproperty list uchar uchar l\nend_header\n");
    const double v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    for (int i = 0; i < 9; ++i) {
        uint64_t u;
        memcpy(&u, &v[i], 8);
        for (int k = 7; k >= 0; --k) put_u8(&b, (unsigned)(u >> (8 * k)) & 0xFF);
    }
    for (int f = 0; f < 2; ++f) {
        put_u8(&b, 0);
        put_u8(&b, 3);
        for (int k = 0; k < 3; ++k) {
            put_u8(&b, 0);
            put_u8(&b, (unsigned)(f ? 2 - k : k));
        }
        put_u8(&b, 200);
    }
    put_u8(&b, 1);
    put_u8(&b, 5);
    put_u8(&b, 0);
    check_prefixes("ply binary be", TG_FORMAT_PLY, b.d, b.n);

    b.n = 0;
    put_str(&b, "prefix test");
    while (b.n < 80) put_u8(&b, ' ');
    put_u32le(&b, 2);
    for (int f = 0; f < 2; ++f) {
        for (int i = 0; i < 12; ++i) put_f32le(&b, (float)((i + f) % 4));
        put_u8(&b, 0);
        put_u8(&b, 0);
    }
    check_prefixes("stl binary", TG_FORMAT_STL, b.d, b.n);
}

/* Prefixes of real corpus files of each flavour, cut at 97 evenly spaced lengths and next to
 * the header / first record boundaries (every cut of a small prefix region, then a stride). */
static void test_corpus_prefixes(void)
{
    static const struct { const char* file; tg_format fmt; } files[] = {
        {"cgal_mpi.off", TG_FORMAT_OFF},          {"igl_camelhead.off", TG_FORMAT_OFF},
        {"gc_lego.ply", TG_FORMAT_PLY},           {"tm_bunny.ply", TG_FORMAT_PLY},
        {"tm_cycloidal.ply", TG_FORMAT_PLY},      {"tm_soup.stl", TG_FORMAT_STL},
        {"tm_1002_tray_bottom.STL", TG_FORMAT_STL}, {"c3d_suzanne.obj", TG_FORMAT_OBJ},
    };
    for (size_t i = 0; i < sizeof files / sizeof files[0]; ++i) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", tg_test_meshes_dir(), files[i].file);
        FILE* f = fopen(path, "rb");
        CHECK_MSG(f != NULL, "cannot open corpus file %s", path);
        if (!f) continue;
        fseek(f, 0, SEEK_END);
        long len = ftell(f);
        fseek(f, 0, SEEK_SET);
        unsigned char* data = malloc((size_t)len);
        size_t got = fread(data, 1, (size_t)len, f);
        fclose(f);
        CHECK_EQ_INT(got, len);
        int bad = 0, failed = 0;
        for (size_t k = 0; k < 97 + 600; ++k) {
            size_t n = k < 600 ? k : (size_t)len * (k - 600) / 97;
            if (n > got) break;
            tg_diag d;
            tg_mesh* m = NULL;
            tg_status st = tg_mesh_load_memory(data, n, files[i].file, files[i].fmt, NULL, &d, &m);
            if (st == TG_OK) {
                bad += m == NULL;
            } else {
                failed++;
                bad += m != NULL || d.message[0] == '\0' || (d.line == 0 && d.byte_offset == 0) ||
                       (st != TG_ERR_PARSE && st != TG_ERR_INVALID_MESH);
            }
            tg_mesh_destroy(m);
        }
        CHECK_MSG(bad == 0, "%s: %d prefixes misbehaved", files[i].file, bad);
        CHECK_MSG(failed > 0, "%s: no prefix failed", files[i].file);
        free(data);
    }
}

int main(void)
{
    test_text_cases();
    test_binary_cases();
    test_prefixes();
    test_corpus_prefixes();
    return tg_test_finish();
}
