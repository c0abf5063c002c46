/* test_io_formats.c - every reader on hand-written in-memory files with known vertex and face
 * arrays: OBJ statement variants, OFF header variants, PLY in all three encodings with every
 * coordinate / count / index type, extra properties and unknown elements, STL ascii and binary
 * with welding order, line-ending variants, format sniffing, and .gz files through zlib. */
#include "tg_test.h"

#include <trigeo.h>
#include <zlib.h>

/* ---- helpers ---- */

static tg_mesh* load(const void* data, size_t size, const char* name, tg_format fmt)
{
    tg_mesh* m = NULL;
    tg_diag d;
    memset(&d, 0, sizeof d);
    tg_status st = tg_mesh_load_memory(data, size, name, fmt, NULL, &d, &m);
    CHECK_MSG(st == TG_OK, "%s: %s: %s (line %llu, offset %llu)", name, tg_status_name(st), d.message,
              (unsigned long long)d.line, (unsigned long long)d.byte_offset);
    return m;
}

static tg_mesh* load_text(const char* text, const char* name, tg_format fmt)
{
    return load(text, strlen(text), name, fmt);
}

/* The mesh has exactly these arrays (positions compared bit for bit). */
static void check_arrays(const tg_mesh* m, const char* what, const double* xyz, size_t nv, const uint32_t* tri, size_t nf)
{
    if (!m) {
        TG_FAIL_("%s: no mesh", what);
        return;
    }
    CHECK_MSG(tg_mesh_vertex_count(m) == nv, "%s: %zu vertices, expected %zu", what, tg_mesh_vertex_count(m), nv);
    CHECK_MSG(tg_mesh_face_count(m) == nf, "%s: %zu faces, expected %zu", what, tg_mesh_face_count(m), nf);
    if (tg_mesh_vertex_count(m) != nv || tg_mesh_face_count(m) != nf) return;
    const double* p = tg_mesh_positions(m);
    for (size_t i = 0; i < 3 * nv; ++i)
        CHECK_MSG(memcmp(&p[i], &xyz[i], sizeof(double)) == 0, "%s: coordinate %zu is %.17g, expected %.17g", what, i,
                  p[i], xyz[i]);
    const uint32_t* t = tg_mesh_triangles(m);
    for (size_t i = 0; i < 3 * nf; ++i)
        CHECK_MSG(t[i] == tri[i], "%s: triangle corner %zu is %u, expected %u", what, i, t[i], tri[i]);
}

/* Two meshes are identical (arrays bit for bit). */
static void check_same(const tg_mesh* a, const tg_mesh* b, const char* what)
{
    if (!a || !b) {
        TG_FAIL_("%s: missing mesh", what);
        return;
    }
    check_arrays(b, what, tg_mesh_positions(a), tg_mesh_vertex_count(a), tg_mesh_triangles(a), tg_mesh_face_count(a));
}

/* Replaces every "\n" of text by eol (a new string in buf). */
static const char* with_eol(const char* text, const char* eol, char* buf, size_t cap)
{
    size_t n = 0, k = strlen(eol);
    for (const char* s = text; *s && n + k + 1 < cap; ++s) {
        if (*s == '\n') {
            memcpy(buf + n, eol, k);
            n += k;
        } else {
            buf[n++] = *s;
        }
    }
    buf[n] = '\0';
    return buf;
}

/* Alternates \n, \r\n and \r line ends. */
static const char* with_mixed_eol(const char* text, char* buf, size_t cap)
{
    static const char* const eols[3] = {"\n", "\r\n", "\r"};
    size_t n = 0;
    int i = 0;
    for (const char* s = text; *s && n + 3 < cap; ++s) {
        if (*s == '\n') {
            const char* e = eols[i++ % 3];
            memcpy(buf + n, e, strlen(e));
            n += strlen(e);
        } else {
            buf[n++] = *s;
        }
    }
    buf[n] = '\0';
    return buf;
}

/* Every line-ending variant of text loads to the same arrays as text itself. */
static void check_line_endings(const char* text, const char* name, tg_format fmt)
{
    static char buf[16384];
    tg_mesh* ref = load_text(text, name, fmt);
    tg_mesh* m = load_text(with_eol(text, "\r\n", buf, sizeof buf), name, fmt);
    check_same(ref, m, "CRLF line ends");
    tg_mesh_destroy(m);
    m = load_text(with_eol(text, "\r", buf, sizeof buf), name, fmt);
    check_same(ref, m, "CR line ends");
    tg_mesh_destroy(m);
    m = load_text(with_mixed_eol(text, buf, sizeof buf), name, fmt);
    check_same(ref, m, "mixed line ends");
    tg_mesh_destroy(m);
    tg_mesh_destroy(ref);
}

/* The unit square split in two, and a square pyramid whose base is one quad. */
static const double square_xyz[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
static const uint32_t square_tri[] = {0, 1, 2, 0, 2, 3};

static const double pyramid_xyz[] = {0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0, 1, 1, 3};
/* base quad 0 3 2 1 fans to (0 3 2) (0 2 1); then the four sides */
static const uint32_t pyramid_tri[] = {0, 3, 2, 0, 2, 1, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};

/* ---- OBJ ---- */

static void test_obj(void)
{
    const char* plain = "# square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
    tg_mesh* m = load_text(plain, "plain.obj", TG_FORMAT_OBJ);
    check_arrays(m, "obj plain", square_xyz, 4, square_tri, 2);
    tg_mesh_destroy(m);

    const char* variants[] = {
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1//1 3//1 4//1\n",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\nf 1/1/1 3/1/1 4/1/1\n",
        /* negative (relative) indices */
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3 -2\nf -4 -2 -1\n",
        /* a quad fans to the same two triangles */
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
        /* other statements, blank lines, comments after values, a continuation */
        "mtllib a.mtl\no sq\ng grp\n\nv 0 0 0 # origin\nv 1 0 0\nv 1.0e0 1 0\nv 0 1 0 1.0\nusemtl m\ns 1\nf 1 2 \\\n 3\nl 1 2\nf 1 3 4\n",
    };
    for (size_t i = 0; i < sizeof variants / sizeof variants[0]; ++i) {
        char what[32];
        snprintf(what, sizeof what, "obj variant %zu", i);
        m = load_text(variants[i], "v.obj", TG_FORMAT_OBJ);
        check_arrays(m, what, square_xyz, 4, square_tri, 2);
        tg_mesh_destroy(m);
    }
    /* negative indices count back from the vertices read so far, not from the file's end */
    const char* rel = "v 0 0 0\nv 1 0 0\nv 1 1 0\nf -3 -2 -1\nv 0 1 0\nf -4 -2 -1\n";
    m = load_text(rel, "rel.obj", TG_FORMAT_OBJ);
    check_arrays(m, "obj relative", square_xyz, 4, square_tri, 2);
    tg_mesh_destroy(m);
    /* a hexagon fans from its first corner */
    const char* hex = "v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 2 0\nv -1 1 0\nf 1 2 3 4 5 6\n";
    static const double hex_xyz[] = {0, 0, 0, 1, 0, 0, 2, 1, 0, 1, 2, 0, 0, 2, 0, -1, 1, 0};
    static const uint32_t hex_tri[] = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5};
    m = load_text(hex, "hex.obj", TG_FORMAT_OBJ);
    check_arrays(m, "obj hexagon", hex_xyz, 6, hex_tri, 4);
    tg_mesh_destroy(m);
    check_line_endings(variants[5], "v.obj", TG_FORMAT_OBJ);
    /* imperfect but valid: a repeated index, a duplicate face, a zero-area face, an unused vertex */
    const char* imperfect = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nv 5 5 5\nf 1 1 2\nf 1 2 3\nf 3 2 1\nf 1 2 4\n";
    static const double imp_xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0, 5, 5, 5};
    static const uint32_t imp_tri[] = {0, 0, 1, 0, 1, 2, 2, 1, 0, 0, 1, 3};
    m = load_text(imperfect, "imperfect.obj", TG_FORMAT_OBJ);
    check_arrays(m, "obj imperfect", imp_xyz, 5, imp_tri, 4);
    if (m) {
        CHECK_EQ_INT(tg_mesh_get_report(m)->degenerate_faces, 2);
        CHECK_EQ_INT(tg_mesh_get_report(m)->unreferenced_vertices, 1);
    }
    tg_mesh_destroy(m);
}

/* ---- OFF ---- */

static void test_off(void)
{
    const char* plain = "OFF\n5 5 8\n0 0 0\n2 0 0\n2 2 0\n0 2 0\n1 1 3\n4 0 3 2 1\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n";
    tg_mesh* m = load_text(plain, "p.off", TG_FORMAT_OFF);
    check_arrays(m, "off plain", pyramid_xyz, 5, pyramid_tri, 6);
    tg_mesh_destroy(m);

    const char* variants[] = {
        /* header-less: the counts come first (as meshstats.py accepts) */
        "5 5 8\n0 0 0\n2 0 0\n2 2 0\n0 2 0\n1 1 3\n4 0 3 2 1\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n",
        /* counts on the keyword line, no edge count */
        "OFF 5 5\n0 0 0\n2 0 0\n2 2 0\n0 2 0\n1 1 3\n4 0 3 2 1\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n",
        /* COFF: per-vertex RGBA and per-face colors are ignored */
        "COFF\n5 5 0\n0 0 0 255 0 0 255\n2 0 0 0 255 0 255\n2 2 0 0 0 255 255\n0 2 0 1 1 1 1\n1 1 3 0.5 0.5 0.5 1\n"
        "4 0 3 2 1 255 0 0\n3 0 1 4 0.1 0.2 0.3 1\n3 1 2 4\n3 2 3 4 7\n3 3 0 4\n",
        /* NOFF: normals after the coordinates */
        "NOFF\n5 5 0\n0 0 0 0 0 -1\n2 0 0 0 0 -1\n2 2 0 0 0 -1\n0 2 0 0 0 -1\n1 1 3 0 0 1\n"
        "4 0 3 2 1\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n",
        /* STCNOFF, comments everywhere, blank lines, tabs, faces wrapping across lines */
        "# leading comment\n\nSTCNOFF # keyword comment\n# between\n5\t5 0 # counts\n"
        "0 0 0 0 0 1 0.1 0.2 0.3 0 0\n2 0 0 0 0 1 0 0 0 0 0 # c\n#\n2 2 0 0 0 1 0 0 0 0 0\n"
        "0 2 0 0 0 1 0 0 0 0 0\n1 1 3 0 0 1 0 0 0 0 0\n"
        "4\n0 3\n2 1\n3 0 # wrapped\n 1 4\n3 1 2 4\n\n3 2 3 4\n3 3 0 4",
        /* number spellings */
        "OFF\n5 5 0\n0.0 -0e0 +0\n2. 0 0\n2e0 0.2e1 0\n0 20e-1 0\n1 1 3.000\n4 0 3 2 1\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n",
    };
    for (size_t i = 0; i < sizeof variants / sizeof variants[0]; ++i) {
        char what[32];
        snprintf(what, sizeof what, "off variant %zu", i);
        m = load_text(variants[i], "v.off", TG_FORMAT_OFF);
        if (i == 5) {
            /* "-0e0" is -0.0: positions keep their sign bit (OFF does not weld) */
            double xyz[15];
            memcpy(xyz, pyramid_xyz, sizeof xyz);
            xyz[1] = -0.0;
            check_arrays(m, what, xyz, 5, pyramid_tri, 6);
        } else {
            check_arrays(m, what, pyramid_xyz, 5, pyramid_tri, 6);
        }
        tg_mesh_destroy(m);
    }
    check_line_endings(variants[4], "v.off", TG_FORMAT_OFF);
    check_line_endings(plain, "p.off", TG_FORMAT_OFF);
    /* unreferenced vertices are kept in file order */
    m = load_text("OFF\n4 1 0\n9 9 9\n0 0 0\n1 0 0\n0 1 0\n3 1 2 3\n", "u.off", TG_FORMAT_OFF);
    static const double u_xyz[] = {9, 9, 9, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const uint32_t u_tri[] = {1, 2, 3};
    check_arrays(m, "off unreferenced", u_xyz, 4, u_tri, 1);
    tg_mesh_destroy(m);
}

/* ---- PLY: one generator for every encoding and type combination ---- */

typedef struct bytes {
    unsigned char d[8192];
    size_t n;
} bytes;

static void put_text(bytes* b, const char* s)
{
    size_t k = strlen(s);
    if (b->n + k > sizeof b->d) return;
    memcpy(b->d + b->n, s, k);
    b->n += k;
}

static int type_size(const char* t)
{
    if (!strcmp(t, "char") || !strcmp(t, "uchar") || !strcmp(t, "int8") || !strcmp(t, "uint8")) return 1;
    if (!strcmp(t, "short") || !strcmp(t, "ushort") || !strcmp(t, "int16") || !strcmp(t, "uint16")) return 2;
    if (!strcmp(t, "double") || !strcmp(t, "float64")) return 8;
    return 4;
}

static int type_is_float(const char* t)
{
    return !strcmp(t, "float") || !strcmp(t, "float32") || !strcmp(t, "double") || !strcmp(t, "float64");
}

/* Appends value v as type t: text for ascii, else bytes in the given byte order. */
static void put_value(bytes* b, const char* enc, const char* t, double v)
{
    if (!strcmp(enc, "ascii")) {
        char s[48];
        if (type_is_float(t))
            snprintf(s, sizeof s, "%.17g ", v);
        else
            snprintf(s, sizeof s, "%lld ", (long long)v);
        put_text(b, s);
        return;
    }
    int big = !strcmp(enc, "binary_big_endian");
    int size = type_size(t);
    unsigned char raw[8];
    if (type_is_float(t) && size == 4) {
        float f = (float)v;
        memcpy(raw, &f, 4);
    } else if (type_is_float(t)) {
        memcpy(raw, &v, 8);
    } else {
        uint64_t u = (uint64_t)(int64_t)v;
        for (int i = 0; i < size; ++i) raw[i] = (unsigned char)(u >> (8 * i));
        /* integer bytes are built little-endian above, independently of the host */
        for (int i = 0; i < size; ++i) b->d[b->n + (size_t)(big ? size - 1 - i : i)] = raw[i];
        b->n += (size_t)size;
        return;
    }
    /* float bytes are in host order: host order to little-endian, then to the wanted order */
    const uint16_t probe = 1;
    int host_big = *(const unsigned char*)&probe == 0;
    for (int i = 0; i < size; ++i) b->d[b->n + (size_t)i] = raw[(big != host_big) ? size - 1 - i : i];
    b->n += (size_t)size;
}

static void end_record(bytes* b, const char* enc)
{
    if (!strcmp(enc, "ascii")) {
        b->n--; /* drop the trailing space */
        put_text(b, "\n");
    }
}

typedef struct ply_spec {
    const char* enc;
    const char* coord;  /* x, y, z type */
    const char* count;  /* face list count type */
    const char* index;  /* face list index type */
    int extras;         /* 0: none; 1: extra scalars and unknown elements; 2: also lists everywhere */
    const char* list_name;
    int vertex_last;    /* the face element comes before the vertex element */
} ply_spec;

static const int pyramid_faces[5][5] = {{4, 0, 3, 2, 1}, {3, 0, 1, 4}, {3, 1, 2, 4}, {3, 2, 3, 4}, {3, 3, 0, 4}};

static void put_vertices(bytes* b, const ply_spec* s)
{
    for (int v = 0; v < 5; ++v) {
        if (s->extras) put_value(b, s->enc, "uchar", 7 + v);
        if (s->extras == 2) {
            put_value(b, s->enc, "uchar", 2);
            put_value(b, s->enc, "float", 0.25);
            put_value(b, s->enc, "float", 0.75);
        }
        for (int k = 0; k < 3; ++k) put_value(b, s->enc, s->coord, pyramid_xyz[3 * v + k]);
        if (s->extras) put_value(b, s->enc, "double", -1.5 * v);
        end_record(b, s->enc);
    }
}

static void put_faces(bytes* b, const ply_spec* s)
{
    for (int f = 0; f < 5; ++f) {
        if (s->extras == 2) {
            put_value(b, s->enc, "uchar", 1);
            put_value(b, s->enc, "ushort", 99); /* a list of out-of-range "indices": never used */
        }
        put_value(b, s->enc, s->count, pyramid_faces[f][0]);
        for (int k = 1; k <= pyramid_faces[f][0]; ++k) put_value(b, s->enc, s->index, pyramid_faces[f][k]);
        if (s->extras) {
            put_value(b, s->enc, "uchar", 255);
            put_value(b, s->enc, "short", -3);
        }
        end_record(b, s->enc);
    }
}

static void build_ply(bytes* b, const ply_spec* s)
{
    char h[1024];
    b->n = 0;
    snprintf(h, sizeof h, "ply\nformat %s 1.0\ncomment generated by test_io_formats\nobj_info none\n", s->enc);
    put_text(b, h);
    if (s->extras) put_text(b, "element camera 1\nproperty float view_x\nproperty int flags\n");
    const char* vhead_extra1 = s->extras ? "property uchar flags\n" : "";
    const char* vhead_extra2 = s->extras == 2 ? "property list uchar float uv\n" : "";
    char vhead[512], fhead[512];
    snprintf(vhead, sizeof vhead, "element vertex 5\n%s%sproperty %s x\nproperty %s y\nproperty %s z\n%s", vhead_extra1,
             vhead_extra2, s->coord, s->coord, s->coord, s->extras ? "property double quality\n" : "");
    snprintf(fhead, sizeof fhead, "element face 5\n%sproperty list %s %s %s\n%s",
             s->extras == 2 ? "property list uchar ushort texture_ids\n" : "", s->count, s->index,
             s->list_name ? s->list_name : "vertex_indices",
             s->extras ? "property uchar red\nproperty short material\n" : "");
    put_text(b, s->vertex_last ? fhead : vhead);
    put_text(b, s->vertex_last ? vhead : fhead);
    if (s->extras) put_text(b, "element edge 2\nproperty int vertex1\nproperty list int int path\n");
    put_text(b, "end_header\n");
    if (s->extras) {
        put_value(b, s->enc, "float", 1.0);
        put_value(b, s->enc, "int", -7);
        end_record(b, s->enc);
    }
    if (s->vertex_last) {
        put_faces(b, s);
        put_vertices(b, s);
    } else {
        put_vertices(b, s);
        put_faces(b, s);
    }
    if (s->extras) {
        for (int e = 0; e < 2; ++e) {
            put_value(b, s->enc, "int", e);
            put_value(b, s->enc, "int", 2);
            put_value(b, s->enc, "int", 10);
            put_value(b, s->enc, "int", -10);
            end_record(b, s->enc);
        }
    }
}

static void test_ply_generated(void)
{
    static const char* const encs[] = {"ascii", "binary_little_endian", "binary_big_endian"};
    static const char* const coords[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double",
                                         "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
    static const char* const counts[] = {"uchar", "char", "ushort", "short", "int", "uint", "uint8", "int32"};
    static const char* const indices[] = {"int", "uint", "uchar", "char", "short", "ushort", "int32", "uint16"};
    static bytes b;
    int cases = 0;
    for (size_t e = 0; e < 3; ++e) {
        for (size_t c = 0; c < sizeof coords / sizeof coords[0]; ++c) {
            for (int extras = 0; extras <= 2; ++extras) {
                /* cycle the count/index types with the coordinate type so all pairs meet */
                for (size_t li = 0; li < 2; ++li) {
                    ply_spec s = {encs[e], coords[c], counts[(c + li) % 8], indices[(c + 3 * li + (size_t)extras) % 8],
                                  extras, li ? "vertex_index" : NULL, (int)((c + (size_t)extras) % 2)};
                    build_ply(&b, &s);
                    char what[160];
                    snprintf(what, sizeof what, "ply %s coord %s list %s %s extras %d vertex_last %d", s.enc, s.coord,
                             s.count, s.index, s.extras, s.vertex_last);
                    tg_mesh* m = load(b.d, b.n, what, TG_FORMAT_PLY);
                    check_arrays(m, what, pyramid_xyz, 5, pyramid_tri, 6);
                    tg_mesh_destroy(m);
                    cases++;
                }
            }
        }
    }
    CHECK_EQ_INT(cases, 3 * 16 * 3 * 2);
    /* fractional float and double coordinates, and a list found as the first list property */
    static const double frac_xyz[] = {0.5, -1.25, 3.75, 1e-3, 2.5e10, -0.0, 1.0 / 3.0, 2, 1, -7.125, 0, 1e-300, 6, 7, 8};
    for (size_t e = 0; e < 3; ++e) {
        ply_spec s = {encs[e], "double", "uchar", "int", 0, "corners", 0};
        b.n = 0;
        char h[512];
        snprintf(h, sizeof h, "ply\nformat %s 1.0\nelement vertex 5\nproperty double x\nproperty double y\n"
                              "property double z\nelement face 5\nproperty list uchar int corners\nend_header\n", s.enc);
        put_text(&b, h);
        for (int v = 0; v < 5; ++v) {
            for (int k = 0; k < 3; ++k) put_value(&b, s.enc, "double", frac_xyz[3 * v + k]);
            end_record(&b, s.enc);
        }
        put_faces(&b, &s);
        tg_mesh* m = load(b.d, b.n, "frac.ply", TG_FORMAT_PLY);
        check_arrays(m, encs[e], frac_xyz, 5, pyramid_tri, 6);
        tg_mesh_destroy(m);
    }
}

static void test_ply_text(void)
{
    /* the classic cube from the PLY format description, with an unknown element and comments */
    const char* cube = "ply\nformat ascii 1.0\ncomment made by Greg Turk\ncomment this file is a cube\n"
                       "element vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
                       "element face 6\nproperty list uchar int vertex_index\nend_header\n"
                       "0 0 0\n0 0 1\n0 1 1\n0 1 0\n1 0 0\n1 0 1\n1 1 1\n1 1 0\n"
                       "4 0 1 2 3\n4 7 6 5 4\n4 0 4 5 1\n4 1 5 6 2\n4 2 6 7 3\n4 3 7 4 0\n";
    static const double cube_xyz[] = {0, 0, 0, 0, 0, 1, 0, 1, 1, 0, 1, 0, 1, 0, 0, 1, 0, 1, 1, 1, 1, 1, 1, 0};
    static const uint32_t cube_tri[] = {0, 1, 2, 0, 2, 3, 7, 6, 5, 7, 5, 4, 0, 4, 5, 0, 5, 1,
                                        1, 5, 6, 1, 6, 2, 2, 6, 7, 2, 7, 3, 3, 7, 4, 3, 4, 0};
    tg_mesh* m = load_text(cube, "cube.ply", TG_FORMAT_PLY);
    check_arrays(m, "ply cube", cube_xyz, 8, cube_tri, 12);
    const tg_mesh_report* r = m ? tg_mesh_get_report(m) : NULL;
    if (r) CHECK_EQ_INT(r->genus, 0);
    tg_mesh_destroy(m);
    check_line_endings(cube, "cube.ply", TG_FORMAT_PLY);
    /* ascii records may wrap or share lines: the body is a token stream */
    const char* wrapped = "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
                          "property double z\nelement face 2\nproperty list uchar uint vertex_indices\nend_header\n"
                          "0 0\n0 1 0 0 1 1 0\n0 1 0\n3\n0 1 2 3 0 2 3\n";
    m = load_text(wrapped, "wrapped.ply", TG_FORMAT_PLY);
    check_arrays(m, "ply wrapped ascii", square_xyz, 4, square_tri, 2);
    tg_mesh_destroy(m);
    /* binary body right after "end_header\r\n" */
    static bytes b;
    b.n = 0;
    put_text(&b, "ply\r\nformat binary_little_endian 1.0\r\nelement vertex 4\r\nproperty float x\r\nproperty float y\r\n"
                 "property float z\r\nelement face 2\r\nproperty list uchar int vertex_indices\r\nend_header\r\n");
    for (int v = 0; v < 4; ++v)
        for (int k = 0; k < 3; ++k) put_value(&b, "binary_little_endian", "float", square_xyz[3 * v + k]);
    for (int f = 0; f < 2; ++f) {
        put_value(&b, "binary_little_endian", "uchar", 3);
        for (int k = 0; k < 3; ++k) put_value(&b, "binary_little_endian", "int", square_tri[3 * f + k]);
    }
    m = load(b.d, b.n, "crlf.ply", TG_FORMAT_PLY);
    check_arrays(m, "ply binary after CRLF header", square_xyz, 4, square_tri, 2);
    tg_mesh_destroy(m);
}

/* ---- STL ---- */

/* two triangles sharing an edge, written as a soup: corners 0 1 2 / 2 1 3 in first-seen order */
static const char* stl_ascii =
    "solid square\n"
    "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 1 1 0\n"
    "    endloop\n  endfacet\n"
    "  facet normal 0 0 1\n    outer loop\n      vertex 1 1 0\n      vertex 1 0 0\n      vertex 0 1 0\n"
    "    endloop\n  endfacet\n"
    "endsolid square\n";
static const double stl_xyz[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
static const uint32_t stl_tri[] = {0, 1, 2, 2, 1, 3};

static void put_stl_binary(bytes* b, const char* header80, const double* corners, size_t facets)
{
    b->n = 0;
    memset(b->d, ' ', 80);
    memcpy(b->d, header80, strlen(header80) < 80 ? strlen(header80) : 80);
    b->n = 80;
    put_value(b, "binary_little_endian", "uint", (double)facets);
    for (size_t f = 0; f < facets; ++f) {
        for (int k = 0; k < 3; ++k) put_value(b, "binary_little_endian", "float", k == 2 ? 1.0 : 0.0);
        for (int k = 0; k < 9; ++k) put_value(b, "binary_little_endian", "float", corners[9 * f + (size_t)k]);
        put_value(b, "binary_little_endian", "ushort", 0);
    }
}

static void test_stl(void)
{
    tg_mesh* m = load_text(stl_ascii, "sq.stl", TG_FORMAT_STL);
    check_arrays(m, "stl ascii", stl_xyz, 4, stl_tri, 2);
    tg_mesh_destroy(m);
    check_line_endings(stl_ascii, "sq.stl", TG_FORMAT_STL);

    /* uppercase keywords, two solids, no names, exponents, -0.0 welded to 0.0 */
    const char* upper =
        "SOLID\nFACET NORMAL 0 0 1\nOUTER LOOP\nVERTEX 0 0 0\nVERTEX 1E0 0 0\nVERTEX 1 1 0\nENDLOOP\nENDFACET\nENDSOLID\n"
        "solid second\nfacet normal 0 0 1\nouter loop\nvertex 1 1 -0\nvertex 1.0 -0.0 0\nvertex 0 1 0\nendloop\n"
        "endfacet\nendsolid second\n";
    m = load_text(upper, "up.stl", TG_FORMAT_STL);
    check_arrays(m, "stl ascii upper/two solids/-0", stl_xyz, 4, stl_tri, 2);
    if (m) {
        const double* p = tg_mesh_positions(m);
        int negative_zeros = 0;
        for (size_t i = 0; i < 12; ++i) negative_zeros += p[i] == 0.0 && signbit(p[i]);
        CHECK_EQ_INT(negative_zeros, 0);
    }
    tg_mesh_destroy(m);

    /* NUL padding after the last endsolid is tolerated */
    {
        static char padded[1024];
        size_t n = strlen(stl_ascii);
        memcpy(padded, stl_ascii, n);
        memset(padded + n, 0, 16);
        m = load(padded, n + 16, "pad.stl", TG_FORMAT_STL);
        check_arrays(m, "stl ascii with NUL padding", stl_xyz, 4, stl_tri, 2);
        tg_mesh_destroy(m);
    }

    /* binary: same soup; welding order is first-seen, not sorted */
    static const double corners[] = {1, 1, 0, 1, 0, 0, 0, 0, 0, /* */ 0, 0, 0, 1, 0, 0, 0, 1, 0,
                                     /* */ 0, 1, 0, 1, 1, 0, 0, 0, 0};
    static const double w_xyz[] = {1, 1, 0, 1, 0, 0, 0, 0, 0, 0, 1, 0};
    static const uint32_t w_tri[] = {0, 1, 2, 2, 1, 3, 3, 0, 2};
    static bytes b;
    put_stl_binary(&b, "binary header", corners, 3);
    CHECK_EQ_INT(b.n, 84 + 3 * 50);
    m = load(b.d, b.n, "w.stl", TG_FORMAT_STL);
    check_arrays(m, "stl binary first-seen order", w_xyz, 4, w_tri, 3);
    tg_mesh_destroy(m);
    /* a binary file whose header starts with "solid": detected by its exact size */
    put_stl_binary(&b, "solid but binary", corners, 3);
    m = load(b.d, b.n, "sb.stl", TG_FORMAT_STL);
    check_arrays(m, "stl binary with solid header", w_xyz, 4, w_tri, 3);
    tg_mesh_destroy(m);
    /* ... and with trailing bytes: the ascii parse finds no vertex, so it is binary */
    put_stl_binary(&b, "solid exporter", corners, 3);
    memcpy(b.d + b.n, "\0\0\0\0\0\0\0", 7);
    b.n += 7;
    m = load(b.d, b.n, "sbt.stl", TG_FORMAT_STL);
    check_arrays(m, "stl binary with solid header and trailing bytes", w_xyz, 4, w_tri, 3);
    tg_mesh_destroy(m);
    /* float32 precision: 0.1f is what a binary file stores */
    static const double tenth[] = {0.1, 0, 0, 1, 0, 0, 0, 1, 0};
    put_stl_binary(&b, "", tenth, 1);
    m = load(b.d, b.n, "t.stl", TG_FORMAT_STL);
    if (m) CHECK_MSG(tg_mesh_positions(m)[0] == (double)0.1f, "binary STL keeps float32 values: %.17g", tg_mesh_positions(m)[0]);
    tg_mesh_destroy(m);
}

/* ---- detection and files ---- */

static void test_sniffing(void)
{
    const char* off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const char* ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const char* stl = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
                      "endfacet\nendsolid t\n";
    const char* obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    static const double tri_xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const uint32_t tri_tri[] = {0, 1, 2};
    const char* texts[] = {off, ply, stl, obj};
    for (int i = 0; i < 4; ++i) {
        /* no name: sniffed from the content; a misleading extension is overridden by a forced format */
        tg_mesh* m = load_text(texts[i], NULL, TG_FORMAT_AUTO);
        check_arrays(m, "sniffed", tri_xyz, 3, tri_tri, 1);
        tg_mesh_destroy(m);
        m = load_text(texts[i], "noext", TG_FORMAT_AUTO);
        check_arrays(m, "sniffed, no extension", tri_xyz, 3, tri_tri, 1);
        tg_mesh_destroy(m);
        static const tg_format forced[] = {TG_FORMAT_OFF, TG_FORMAT_PLY, TG_FORMAT_STL, TG_FORMAT_OBJ};
        m = load_text(texts[i], "wrong.obj", forced[i]);
        check_arrays(m, "forced", tri_xyz, 3, tri_tri, 1);
        tg_mesh_destroy(m);
    }
    static bytes b;
    static const double corners[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    put_stl_binary(&b, "", corners, 1);
    tg_mesh* m = load(b.d, b.n, NULL, TG_FORMAT_AUTO);
    check_arrays(m, "sniffed binary STL", tri_xyz, 3, tri_tri, 1);
    tg_mesh_destroy(m);
}

static void temp_path(char* out, size_t cap, const char* file)
{
    const char* dir = getenv("TG_BUILD_DIR");
    snprintf(out, cap, "%s/%s", dir ? dir : ".", file);
}

static int write_gz(const char* path, const void* data, size_t size)
{
    gzFile g = gzopen(path, "wb");
    if (!g) return 0;
    int ok = gzwrite(g, data, (unsigned)size) == (int)size;
    return gzclose(g) == Z_OK && ok;
}

static void test_gz_files(void)
{
    char path[1024];
    const char* plain = "OFF\n5 5 8\n0 0 0\n2 0 0\n2 2 0\n0 2 0\n1 1 3\n4 0 3 2 1\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n";
    temp_path(path, sizeof path, "test_io_formats_pyramid.off.gz");
    CHECK(write_gz(path, plain, strlen(plain)));
    tg_mesh* m = NULL;
    tg_diag d;
    CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &m), TG_OK);
    check_arrays(m, "off.gz", pyramid_xyz, 5, pyramid_tri, 6);
    tg_mesh_destroy(m);
    remove(path);
    /* binary PLY, gzipped, under a name without .gz: recognised by the gzip magic */
    static bytes b;
    ply_spec s = {"binary_big_endian", "float", "uchar", "int", 1, NULL, 0};
    build_ply(&b, &s);
    temp_path(path, sizeof path, "test_io_formats_pyramid_gz.ply");
    CHECK(write_gz(path, b.d, b.n));
    m = NULL;
    CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &m), TG_OK);
    check_arrays(m, "gzipped ply without .gz", pyramid_xyz, 5, pyramid_tri, 6);
    tg_mesh_destroy(m);
    remove(path);
    /* a plain file too */
    temp_path(path, sizeof path, "test_io_formats_plain.stl");
    FILE* f = fopen(path, "wb");
    CHECK(f != NULL);
    if (f) {
        fwrite(stl_ascii, 1, strlen(stl_ascii), f);
        fclose(f);
        m = NULL;
        CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &m), TG_OK);
        check_arrays(m, "stl file", stl_xyz, 4, stl_tri, 2);
        tg_mesh_destroy(m);
        remove(path);
    }
    /* a truncated .gz (its trailer cut, or cut mid-stream) is an error naming the file, never a
     * silently shorter mesh */
    temp_path(path, sizeof path, "test_io_formats_pyramid_full.off.gz");
    CHECK(write_gz(path, plain, strlen(plain)));
    f = fopen(path, "rb");
    unsigned char gzb[512];
    size_t gzn = f ? fread(gzb, 1, sizeof gzb, f) : 0;
    if (f) fclose(f);
    remove(path);
    for (size_t cut = 1; cut <= 9; cut += 4) {
        temp_path(path, sizeof path, "test_io_formats_truncated.off.gz");
        f = fopen(path, "wb");
        CHECK(f && gzn > cut);
        if (!f) break;
        fwrite(gzb, 1, gzn - cut, f);
        fclose(f);
        m = NULL;
        memset(&d, 0, sizeof d);
        CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &m), TG_ERR_PARSE);
        CHECK(m == NULL && strstr(d.message, "truncated") != NULL);
        CHECK_EQ_STR(d.file, path);
        remove(path);
    }
    /* a missing file is an I/O error naming the path */
    temp_path(path, sizeof path, "test_io_formats_does_not_exist.obj");
    m = NULL;
    CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &m), TG_ERR_IO);
    CHECK(m == NULL);
    CHECK_EQ_STR(d.file, path);
}

int main(void)
{
    test_obj();
    test_off();
    test_ply_generated();
    test_ply_text();
    test_stl();
    test_sniffing();
    test_gz_files();
    return tg_test_finish();
}
