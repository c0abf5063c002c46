/* off.c - OFF reader: [ST][C][N]OFF header (or none), "V F [E]" counts, vertex lines whose first
 * three numbers are x y z (colors, normals, texture coordinates after them are ignored), polygon
 * faces "n i0 .. in-1 [color]" that may wrap across lines, '#' comments anywhere.
 * Based on: the Geomview OFF file format description (Geomview manual, "OFF Files"); the
 * header-less variant and the "rest of the line after the last index is color" rule follow
 * shared/tools/meshstats.py, which defines the corpus counts. */
#include "io/io_internal.h"
#include "io/numparse.h"

#include <math.h>
#include <string.h>

typedef struct off_cursor {
    const char* data;
    const char* p;
    const char* end;
    const char* name;
    tg_diag* diag;
} off_cursor;

static tg_status fail_at(off_cursor* c, const char* at, tg_status st, const char* msg, ...) TG_PRINTF(4, 5);
static tg_status fail_at(off_cursor* c, const char* at, tg_status st, const char* msg, ...)
{
    va_list ap;
    va_start(ap, msg);
    tg__io_vfail(c->diag, c->name, c->data, (size_t)(at - c->data), st, msg, ap);
    va_end(ap);
    return st;
}

/* Skips to the end of the current line (the terminator itself is left as whitespace). */
static void skip_line(off_cursor* c)
{
    while (c->p < c->end && !tg__is_eol(*c->p)) c->p++;
}

/* Skips whitespace, line ends and '#' comments: positions at the next token or at the end. */
static void skip_space(off_cursor* c)
{
    for (;;) {
        while (c->p < c->end && tg__is_space(*c->p)) c->p++;
        if (c->p < c->end && *c->p == '#') {
            skip_line(c);
            continue;
        }
        return;
    }
}

/* Skips blanks within the line; true if a token follows on the same line. */
static bool skip_blanks_in_line(off_cursor* c)
{
    while (c->p < c->end && tg__is_blank(*c->p)) c->p++;
    return c->p < c->end && !tg__is_eol(*c->p) && *c->p != '#' && *c->p != '\v' && *c->p != '\f';
}

static bool token_ends(const off_cursor* c, const char* q)
{
    return q == c->end || tg__is_space(*q) || *q == '#';
}

/* Parses an integer token at c->p (which must start a token); NULL-safe on garbage. */
static bool parse_int_token(off_cursor* c, int64_t* out)
{
    const char* q = c->p < c->end ? tg__parse_int(c->p, out) : NULL;
    if (!q || q > c->end || !token_ends(c, q)) return false;
    c->p = q;
    return true;
}

static bool parse_double_token(off_cursor* c, double* out)
{
    const char* q = c->p < c->end ? tg__parse_double(c->p, out) : NULL;
    if (!q || q > c->end || !token_ends(c, q)) return false;
    c->p = q;
    return true;
}

/* The header keyword: [ST][C][N]OFF accepted (coordinates come first), 4OFF / nOFF / BINARY
 * refused. No keyword at all (the data starts with a number) is accepted too. */
static tg_status parse_keyword(off_cursor* c)
{
    skip_space(c);
    if (c->p >= c->end) return fail_at(c, c->p, TG_ERR_PARSE, "no OFF header or counts (only comments and blanks)");
    const char* kw = c->p;
    const char* q = kw;
    while (q < c->end && !tg__is_space(*q) && *q != '#') q++;
    size_t n = (size_t)(q - kw);
    bool keyword = n >= 3 && memcmp(q - 3, "OFF", 3) == 0;
    if (!keyword && (tg__is_digit(*kw) || *kw == '+' || *kw == '-')) return TG_OK; /* counts first */
    c->p = q;
    if (n < 3 || memcmp(kw + n - 3, "OFF", 3) != 0)
        return fail_at(c, kw, TG_ERR_PARSE, "not an OFF file: expected the OFF keyword or vertex/face counts, found '%.*s'",
                       (int)(n < 40 ? n : 40), kw);
    for (size_t i = 0; i + 3 < n; ++i) {
        if (kw[i] == '4' || kw[i] == 'n')
            return fail_at(c, kw, TG_ERR_UNSUPPORTED, "'%.*s' (homogeneous or n-dimensional coordinates) is not supported",
                           (int)(n < 40 ? n : 40), kw);
        if (!strchr("STCN", kw[i]))
            return fail_at(c, kw, TG_ERR_PARSE, "unknown OFF header keyword '%.*s'", (int)(n < 40 ? n : 40), kw);
    }
    if (skip_blanks_in_line(c)) {
        const char* t = c->p;
        if (c->end - t >= 6 && (memcmp(t, "BINARY", 6) == 0 || memcmp(t, "binary", 6) == 0) &&
            token_ends(c, t + 6))
            return fail_at(c, t, TG_ERR_UNSUPPORTED, "binary OFF is not supported (convert it to text OFF)");
    }
    return TG_OK;
}

static tg_status parse_count(off_cursor* c, const char* what, int64_t* out)
{
    skip_space(c);
    if (c->p >= c->end) return fail_at(c, c->p, TG_ERR_PARSE, "missing %s count (truncated header?)", what);
    const char* at = c->p;
    if (!parse_int_token(c, out)) return fail_at(c, at, TG_ERR_PARSE, "%s count is not an integer", what);
    if (*out < 0) return fail_at(c, at, TG_ERR_PARSE, "negative %s count %lld", what, (long long)*out);
    return TG_OK;
}

static tg_status parse_vertices(off_cursor* c, size_t vertex_count, double* xyz)
{
    for (size_t i = 0; i < vertex_count; ++i) {
        skip_space(c);
        if (c->p >= c->end)
            return fail_at(c, c->p, TG_ERR_PARSE, "data ends after %zu of %zu vertices (truncated file?)", i, vertex_count);
        for (int k = 0; k < 3; ++k) {
            if (k > 0 && !skip_blanks_in_line(c))
                return fail_at(c, c->p, TG_ERR_PARSE, "vertex %zu has %d coordinates on its line (3 needed)", i, k);
            const char* at = c->p;
            double v;
            if (!parse_double_token(c, &v))
                return fail_at(c, at, TG_ERR_PARSE, "vertex %zu: %c coordinate is not a number", i, "xyz"[k]);
            if (!isfinite(v))
                return fail_at(c, at, TG_ERR_INVALID_MESH, "vertex %zu: non-finite %c coordinate", i, "xyz"[k]);
            xyz[3 * i + (size_t)k] = v;
        }
        skip_line(c); /* colors, normals, texture coordinates */
    }
    return TG_OK;
}

/* Whether the line at p holds exactly three numbers that cannot start a face (one is not an
 * integer, or the first, a corner count, is below 3): a vertex line where a face was expected. */
static bool vertex_like(const off_cursor* c, const char* p)
{
    int n = 0;
    bool face_like = true;
    while (p < c->end && !tg__is_eol(*p) && *p != '#') {
        while (p < c->end && tg__is_blank(*p)) p++;
        if (p >= c->end || tg__is_eol(*p) || *p == '#') break;
        double x;
        const char* q = tg__parse_double(p, &x);
        if (!q || q > c->end || !token_ends(c, q)) return false;
        if (x != floor(x) || (n == 0 && x < 3)) face_like = false;
        n++, p = q;
    }
    return n == 3 && !face_like;
}

static tg_status parse_face_records(off_cursor* c, const tg_allocator* a, size_t vertex_count, size_t face_count,
                                    tg__vec* poly, tg__vec* tris);

/* The faces; a first face that fails to parse and looks like a vertex line is reported as what
 * it most likely is: a vertex the header's count left out. */
static tg_status parse_faces(off_cursor* c, const tg_allocator* a, size_t vertex_count, size_t face_count,
                             tg__vec* poly, tg__vec* tris)
{
    skip_space(c);
    const char* first = c->p;
    tg_status st = parse_face_records(c, a, vertex_count, face_count, poly, tris);
    if (st != TG_OK && st != TG_ERR_OUT_OF_MEMORY && tris->count == 0 && first < c->end && vertex_like(c, first)) {
        const char* eol = first;
        while (eol < c->end && !tg__is_eol(*eol)) eol++;
        return fail_at(c, first, TG_ERR_PARSE,
                       "face 0 ('%.*s') is a vertex line: the data holds more vertices than the %zu the header "
                       "declares (a wrong vertex count)",
                       (int)(eol - first < 40 ? eol - first : 40), first, vertex_count);
    }
    return st;
}

static tg_status parse_face_records(off_cursor* c, const tg_allocator* a, size_t vertex_count, size_t face_count,
                                    tg__vec* poly, tg__vec* tris)
{
    for (size_t f = 0; f < face_count; ++f) {
        skip_space(c);
        if (c->p >= c->end)
            return fail_at(c, c->p, TG_ERR_PARSE, "data ends after %zu of %zu faces (truncated file?)", f, face_count);
        const char* at = c->p;
        int64_t n;
        if (!parse_int_token(c, &n)) return fail_at(c, at, TG_ERR_PARSE, "face %zu: corner count is not an integer", f);
        if (n < 3) return fail_at(c, at, TG_ERR_PARSE, "face %zu has %lld corners (at least 3 needed)", f, (long long)n);
        /* every corner needs at least two bytes: refuse counts the remaining data cannot hold */
        if ((uint64_t)n > (uint64_t)(c->end - c->p) / 2)
            return fail_at(c, at, TG_ERR_PARSE, "face %zu has %lld corners, more than the remaining data can hold", f,
                           (long long)n);
        poly->count = 0;
        if (!tg__vec_reserve(a, poly, (size_t)n)) return TG_ERR_OUT_OF_MEMORY;
        uint32_t* corner = poly->data;
        for (int64_t k = 0; k < n; ++k) {
            skip_space(c);
            const char* ia = c->p;
            int64_t idx;
            if (c->p >= c->end)
                return fail_at(c, ia, TG_ERR_PARSE, "face %zu ends after %lld of %lld corners (truncated file?)", f,
                               (long long)k, (long long)n);
            if (!parse_int_token(c, &idx))
                return fail_at(c, ia, TG_ERR_PARSE, "face %zu: corner %lld is not an integer index", f, (long long)k);
            if (idx < 0 || (uint64_t)idx >= vertex_count)
                return fail_at(c, ia, TG_ERR_INVALID_MESH, "face %zu: vertex index %lld out of range (%zu vertices)", f,
                               (long long)idx, vertex_count);
            corner[k] = (uint32_t)idx;
        }
        poly->count = (size_t)n;
        skip_line(c); /* optional face color */
        if (!tg__fan_push(a, tris, corner, (size_t)n)) return TG_ERR_OUT_OF_MEMORY;
    }
    return TG_OK;
}

/* After the declared faces only blanks and comments may follow: more records mean the header's
 * face count is wrong, and reading only the declared ones would drop data silently. */
static tg_status check_end(off_cursor* c, size_t face_count)
{
    skip_space(c);
    if (c->p >= c->end) return TG_OK;
    const char* first = c->p;
    size_t records = 0;
    while (c->p < c->end) { /* one record a line, as the faces are written */
        records++;
        skip_line(c);
        skip_space(c);
    }
    const char* eol = first;
    while (eol < c->end && !tg__is_eol(*eol)) eol++;
    return fail_at(c, first, TG_ERR_PARSE,
                   "the header declares %zu face%s but %zu more record line%s follow%s the last of them ('%.*s'): a "
                   "wrong face count",
                   face_count, face_count == 1 ? "" : "s", records, records == 1 ? "" : "s", records == 1 ? "s" : "",
                   (int)(eol - first < 40 ? eol - first : 40), first);
}

tg_status tg__read_off(const char* data, size_t size, const char* name, const tg_allocator* a,
                       tg_diag* diag, tg__soup* out)
{
    off_cursor c = {data, data, data + size, name, diag};
    /* a UTF-8 byte order mark is not part of the header */
    if (size >= 3 && memcmp(data, "\xEF\xBB\xBF", 3) == 0) c.p += 3;
    tg_status st = parse_keyword(&c);
    int64_t nv = 0, nf = 0;
    if (st == TG_OK) st = parse_count(&c, "vertex", &nv);
    if (st == TG_OK) st = parse_count(&c, "face", &nf);
    if (st != TG_OK) return st;
    /* the edge count is optional and ignored; anything else on the counts line too */
    skip_line(&c);
    /* A vertex line is at least "x y z\n" (6 bytes), a face at least "3 a b c\n" (8 bytes): counts
     * the data cannot hold are refused before anything is allocated. */
    uint64_t room = (uint64_t)(c.end - c.p) + 1;
    if ((uint64_t)nv > room || (uint64_t)nf > room || 6 * (uint64_t)nv + 8 * (uint64_t)nf > room)
        return fail_at(&c, c.p, TG_ERR_PARSE, "counts %lld vertices, %lld faces need more than the %zu remaining bytes",
                       (long long)nv, (long long)nf, (size_t)(c.end - c.p));
    if ((uint64_t)nv >= (1u << 31))
        return fail_at(&c, c.p, TG_ERR_UNSUPPORTED, "%lld vertices exceed the 32-bit index limit", (long long)nv);
    tg__vec xyz = {NULL, 0, 0, sizeof(double), 0, 0};
    tg__vec tris = {NULL, 0, 0, sizeof(uint32_t), 0, 0};
    tg__vec poly = {NULL, 0, 0, sizeof(uint32_t), 0, 0};
    if (!tg__vec_reserve(a, &xyz, 3 * (size_t)nv + 1) || !tg__vec_reserve(a, &tris, 3 * (size_t)nf + 3))
        st = TG_ERR_OUT_OF_MEMORY;
    if (st == TG_OK) st = parse_vertices(&c, (size_t)nv, xyz.data);
    if (st == TG_OK) st = parse_faces(&c, a, (size_t)nv, (size_t)nf, &poly, &tris);
    if (st == TG_OK) st = check_end(&c, (size_t)nf);
    tg__vec_free(a, &poly);
    if (st != TG_OK) {
        if (st == TG_ERR_OUT_OF_MEMORY) fail_at(&c, c.p, st, "out of memory");
        tg__vec_free(a, &xyz);
        tg__vec_free(a, &tris);
        return st;
    }
    out->xyz = xyz.data;
    out->vertex_count = (size_t)nv;
    out->tri = tris.data;
    out->face_count = tris.count / 3;
    return TG_OK;
}
