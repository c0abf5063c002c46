/* stl.c - STL reader, binary and ascii, with welding of bit-identical positions (-0.0 == 0.0)
 * into vertices numbered in first-seen order (open-addressing hash table, O(n) expected).
 * Binary vs ascii follows shared/tools/meshstats.py, which defines the corpus counts: binary when
 * 84 + 50 n equals the size or the data does not start with "solid"; a "solid"-headed file whose
 * ascii parse finds no vertex but whose size fits 84 + 50 n bytes is binary too.
 * Based on: the StereoLithography Interface Specification (3D Systems, 1989): the 80-byte header,
 * uint32 facet count and 50-byte facet records (normal, three vertices as little-endian float32,
 * uint16 attribute); the ascii grammar solid / facet normal / outer loop / vertex / endloop /
 * endfacet / endsolid. */
#include "io/io_internal.h"
#include "io/numparse.h"

#include <math.h>
#include <string.h>

/* ---- welding ---- */

static uint64_t bits_of(double v)
{
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    return u;
}

static uint64_t position_hash(const double* p)
{
    /* multiply-xorshift mixing of the three bit patterns (constants: odd 64-bit multipliers
     * from splitmix64 / Murmur3's finalizer) */
    uint64_t h = bits_of(p[0]) * 0x9E3779B97F4A7C15ull;
    h ^= bits_of(p[1]) + 0xBF58476D1CE4E5B9ull + (h << 6) + (h >> 2);
    h *= 0x94D049BB133111EBull;
    h ^= bits_of(p[2]) + 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= h >> 31;
    h *= 0xFF51AFD7ED558CCDull;
    h ^= h >> 33;
    return h;
}

/* Welds corner positions in place: corner i's vertex is the first corner with the same
 * position, vertices are numbered in first-seen order and compacted to the front of xyz (a
 * vertex is written at index <= the corner it comes from, so reads never see overwritten
 * data). Positions must be finite; -0.0 is stored as 0.0. */
static tg_status weld(const tg_allocator* a, double* xyz, size_t corner_count, uint32_t* tri, size_t* out_vertex_count)
{
    size_t cap = 16;
    while (cap < 2 * corner_count) cap *= 2;
    uint32_t* table = tg__alloc_array(a, cap, sizeof(uint32_t));
    if (!table) return TG_ERR_OUT_OF_MEMORY;
    memset(table, 0xFF, cap * sizeof(uint32_t));
    size_t nv = 0;
    for (size_t i = 0; i < corner_count; ++i) {
        double p[3] = {xyz[3 * i] + 0.0, xyz[3 * i + 1] + 0.0, xyz[3 * i + 2] + 0.0}; /* -0.0 + 0.0 == +0.0 */
        size_t slot = (size_t)position_hash(p) & (cap - 1);
        for (;;) {
            uint32_t v = table[slot];
            if (v == TG_NONE) {
                table[slot] = (uint32_t)nv;
                memcpy(xyz + 3 * nv, p, sizeof p);
                tri[i] = (uint32_t)nv++;
                break;
            }
            const double* q = xyz + 3 * (size_t)v;
            if (q[0] == p[0] && q[1] == p[1] && q[2] == p[2]) {
                tri[i] = v;
                break;
            }
            slot = (slot + 1) & (cap - 1);
        }
    }
    tg__free(a, table);
    *out_vertex_count = nv;
    return TG_OK;
}

/* Welds the corner soup into the output (shrinking xyz to the vertices found). Takes ownership
 * of corners. */
static tg_status finish(const tg_allocator* a, const char* name, tg_diag* diag, double* corners, size_t corner_count,
                        tg__soup* out)
{
    if (corner_count / 3 >= (1u << 31) / 3) {
        tg__free(a, corners);
        tg__diag_set(diag, name, 0, 0, 0, "%zu facets exceed the 32-bit index limit", corner_count / 3);
        return TG_ERR_UNSUPPORTED;
    }
    uint32_t* tri = tg__alloc_array(a, corner_count + 1, sizeof(uint32_t));
    size_t nv = 0;
    tg_status st = tri ? weld(a, corners, corner_count, tri, &nv) : TG_ERR_OUT_OF_MEMORY;
    if (st != TG_OK) {
        tg__free(a, corners);
        tg__free(a, tri);
        tg__diag_set(diag, name, 0, 0, 0, "out of memory welding %zu corners", corner_count);
        return st;
    }
    double* xyz = tg__realloc(a, corners, (3 * nv + 1) * sizeof(double));
    out->xyz = xyz ? xyz : corners;
    out->vertex_count = nv;
    out->tri = tri;
    out->face_count = corner_count / 3;
    return TG_OK;
}

/* ---- binary ---- */

static uint32_t ld32le(const unsigned char* p)
{
    return (uint32_t)p[3] << 24 | (uint32_t)p[2] << 16 | (uint32_t)p[1] << 8 | p[0];
}

static tg_status read_binary(const char* data, size_t size, const char* name, const tg_allocator* a, tg_diag* diag,
                             tg__soup* out)
{
    const unsigned char* d = (const unsigned char*)data;
    if (size < 84)
        return tg__io_fail(diag, name, NULL, size, TG_ERR_PARSE,
                           "binary STL needs an 84-byte header, the data has %zu bytes", size);
    uint64_t n = ld32le(d + 80);
    if (84 + 50 * n > size)
        return tg__io_fail(diag, name, NULL, 80, TG_ERR_PARSE,
                           "binary STL declares %llu facets (%llu bytes) but the data has %zu bytes (truncated file?)",
                           (unsigned long long)n, (unsigned long long)(84 + 50 * n), size);
    /* The count must account for the data: whole facet records after the declared ones mean a
     * wrong count, and reading only the declared ones would drop faces silently. Fewer bytes
     * than a record are padding some exporters add (the corpus's reference reader,
     * meshstats.py, skips them too): a warning, not an error. */
    uint64_t records = (size - 84) / 50, extra = size - 84 - 50 * n;
    if (records > n)
        return tg__io_fail(diag, name, NULL, 80, TG_ERR_PARSE,
                           "binary STL declares %llu facet%s but the data holds %llu facet records (%zu bytes): "
                           "a wrong facet count",
                           (unsigned long long)n, n == 1 ? "" : "s", (unsigned long long)records, size);
    double* xyz = tg__alloc_array(a, 9 * (size_t)n + 1, sizeof(double));
    if (!xyz) return tg__io_fail(diag, name, NULL, 80, TG_ERR_OUT_OF_MEMORY, "out of memory for %llu facets", (unsigned long long)n);
    for (size_t f = 0; f < (size_t)n; ++f) {
        const unsigned char* r = d + 84 + 50 * f + 12; /* skip the normal */
        for (int k = 0; k < 9; ++k) {
            uint32_t u = ld32le(r + 4 * k);
            float v;
            memcpy(&v, &u, sizeof v);
            if (!isfinite(v)) {
                tg__free(a, xyz);
                return tg__io_fail(diag, name, NULL, 84 + 50 * f + 12 + 4 * (size_t)k, TG_ERR_INVALID_MESH,
                                   "facet %zu: non-finite vertex coordinate", f);
            }
            xyz[9 * f + (size_t)k] = v;
        }
    }
    tg_status st = finish(a, name, diag, xyz, 3 * (size_t)n, out);
    if (st == TG_OK && extra)
        tg__io_fail(diag, name, NULL, 84 + 50 * (size_t)n, TG_OK,
                    "warning: %llu bytes after the last of the %llu declared facets ignored (less than a facet record)",
                    (unsigned long long)extra, (unsigned long long)n);
    return st;
}

/* ---- ascii ---- */

typedef struct stl_cursor {
    const char* data;
    size_t p, n;
    const char* name;
    tg_diag* diag;
    size_t corners; /* vertices read so far */
} stl_cursor;

typedef struct stl_token {
    size_t at, len;
} stl_token;

static stl_token next_token(stl_cursor* c)
{
    while (c->p < c->n && tg__is_space(c->data[c->p])) c->p++;
    stl_token t = {c->p, 0};
    while (c->p < c->n && !tg__is_space(c->data[c->p])) c->p++;
    t.len = c->p - t.at;
    return t;
}

static void skip_line(stl_cursor* c)
{
    while (c->p < c->n && !tg__is_eol(c->data[c->p])) c->p++;
}

/* Case-insensitive keyword match (writers differ: "facet" / "FACET"). */
static bool token_is(const stl_cursor* c, stl_token t, const char* kw)
{
    size_t k = strlen(kw);
    if (t.len != k) return false;
    for (size_t i = 0; i < k; ++i) {
        char ch = c->data[t.at + i];
        if (ch >= 'A' && ch <= 'Z') ch = (char)(ch - 'A' + 'a');
        if (ch != kw[i]) return false;
    }
    return true;
}

static tg_status fail_token(stl_cursor* c, stl_token t, size_t facet, const char* expected)
{
    if (t.len == 0)
        return tg__io_fail(c->diag, c->name, c->data, t.at, TG_ERR_PARSE,
                           "data ends in facet %zu, expected '%s' (truncated file?)", facet, expected);
    return tg__io_fail(c->diag, c->name, c->data, t.at, TG_ERR_PARSE, "facet %zu: expected '%s', found '%.*s'", facet,
                       expected, (int)(t.len < 40 ? t.len : 40), c->data + t.at);
}

static tg_status expect(stl_cursor* c, size_t facet, const char* kw)
{
    stl_token t = next_token(c);
    return token_is(c, t, kw) ? TG_OK : fail_token(c, t, facet, kw);
}

static tg_status parse_vertex(stl_cursor* c, size_t facet, const tg_allocator* a, tg__vec* xyz)
{
    if (!tg__vec_reserve(a, xyz, 3)) return TG_ERR_OUT_OF_MEMORY;
    double* out = (double*)xyz->data + xyz->count;
    for (int k = 0; k < 3; ++k) {
        stl_token t = next_token(c);
        const char* q = t.len ? tg__parse_double(c->data + t.at, &out[k]) : NULL;
        if (!q || q != c->data + t.at + t.len)
            return t.len ? tg__io_fail(c->diag, c->name, c->data, t.at, TG_ERR_PARSE,
                                       "facet %zu: vertex coordinate '%.*s' is not a number", facet,
                                       (int)(t.len < 40 ? t.len : 40), c->data + t.at)
                         : fail_token(c, t, facet, "coordinate");
        if (!isfinite(out[k]))
            return tg__io_fail(c->diag, c->name, c->data, t.at, TG_ERR_INVALID_MESH,
                               "facet %zu: non-finite vertex coordinate", facet);
    }
    xyz->count += 3;
    c->corners++;
    return TG_OK;
}

/* facet normal nx ny nz / outer loop / vertex x3 / endloop / endfacet ("facet" already read). */
static tg_status parse_facet(stl_cursor* c, size_t facet, const tg_allocator* a, tg__vec* xyz)
{
    skip_line(c); /* the normal is recomputed by whoever needs it */
    tg_status st = expect(c, facet, "outer");
    if (st == TG_OK) st = expect(c, facet, "loop");
    int k = 0;
    while (st == TG_OK) {
        stl_token t = next_token(c);
        if (token_is(c, t, "endloop")) break;
        if (!token_is(c, t, "vertex")) return fail_token(c, t, facet, k < 3 ? "vertex" : "endloop");
        if (k == 3)
            return tg__io_fail(c->diag, c->name, c->data, t.at, TG_ERR_PARSE, "facet %zu has more than 3 vertices", facet);
        st = parse_vertex(c, facet, a, xyz);
        k++;
    }
    if (st == TG_OK && k < 3)
        return tg__io_fail(c->diag, c->name, c->data, c->p, TG_ERR_PARSE, "facet %zu has %d vertices (3 needed)", facet, k);
    if (st == TG_OK) st = expect(c, facet, "endfacet");
    return st;
}

/* Some exporters pad the file after the last endsolid with NUL bytes. */
static bool only_padding(const stl_cursor* c, size_t from)
{
    for (size_t i = from; i < c->n; ++i)
        if (c->data[i] != '\0' && !tg__is_space(c->data[i])) return false;
    return true;
}

static tg_status parse_ascii(stl_cursor* c, const tg_allocator* a, tg__vec* xyz)
{
    size_t facet = 0;
    bool any_solid = false;
    for (;;) {
        stl_token t = next_token(c);
        if (t.len == 0 && any_solid) return TG_OK;
        if (any_solid && only_padding(c, t.at)) return TG_OK;
        if (!token_is(c, t, "solid")) {
            if (t.len == 0) return tg__io_fail(c->diag, c->name, c->data, t.at, TG_ERR_PARSE, "ascii STL has no 'solid'");
            return tg__io_fail(c->diag, c->name, c->data, t.at, TG_ERR_PARSE, "expected 'solid', found '%.*s'",
                               (int)(t.len < 40 ? t.len : 40), c->data + t.at);
        }
        any_solid = true;
        skip_line(c); /* the solid's name */
        for (;;) {
            t = next_token(c);
            if (token_is(c, t, "endsolid")) {
                skip_line(c);
                break;
            }
            if (t.len == 0)
                return tg__io_fail(c->diag, c->name, c->data, t.at, TG_ERR_PARSE,
                                   "data ends after facet %zu without 'endsolid' (truncated file?)", facet);
            if (!token_is(c, t, "facet")) return fail_token(c, t, facet, "facet' or 'endsolid");
            tg_status st = parse_facet(c, facet, a, xyz);
            if (st != TG_OK) return st;
            facet++;
        }
    }
}

tg_status tg__read_stl(const char* data, size_t size, const char* name, const tg_allocator* a,
                       tg_diag* diag, tg__soup* out)
{
    bool binary = size >= 84 && 84 + 50 * (uint64_t)ld32le((const unsigned char*)data + 80) == size;
    if (!binary) {
        size_t p = 0;
        while (p < size && tg__is_space(data[p])) p++;
        stl_cursor probe = {data, p, size, name, diag, 0};
        binary = !token_is(&probe, (stl_token){p, size - p < 5 ? size - p : 5}, "solid");
    }
    if (binary) return read_binary(data, size, name, a, diag, out);
    stl_cursor c = {data, 0, size, name, diag, 0};
    tg__vec xyz = {NULL, 0, 0, sizeof(double), 0, 0};
    tg_status st = parse_ascii(&c, a, &xyz);
    if (c.corners == 0 && size >= 84 && 84 + 50 * (uint64_t)ld32le((const unsigned char*)data + 80) <= size) {
        /* a binary file whose 80-byte header happens to start with "solid" */
        tg__vec_free(a, &xyz);
        return read_binary(data, size, name, a, diag, out);
    }
    if (st != TG_OK) {
        if (st == TG_ERR_OUT_OF_MEMORY) tg__io_fail(diag, name, data, c.p, st, "out of memory");
        tg__vec_free(a, &xyz);
        return st;
    }
    if (c.corners == 0) {
        tg__vec_free(a, &xyz);
        return tg__io_fail(diag, name, data, size, TG_ERR_PARSE, "ascii STL has no facets");
    }
    return finish(a, name, diag, xyz.data, c.corners, out);
}
