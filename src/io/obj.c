/* obj.c - Wavefront OBJ reader: v and f statements (v, v/vt, v//vn, v/vt/vn, negative indices),
 * polygons fan-triangulated, '\' line continuations, every other statement ignored.
 * Based on: the Wavefront OBJ specification (Appendix B1 of the Advanced Visualizer manual). */
#include "io/io_internal.h"
#include "io/numparse.h"

#include <math.h>
#include <string.h>

typedef struct obj_cursor {
    const char* p;
    const char* end;
    const char* data;
    uint64_t line;
} obj_cursor;

/* Skips blanks and '\'-newline continuations within a statement. */
static void skip_blanks(obj_cursor* c)
{
    for (;;) {
        while (c->p < c->end && tg__is_blank(*c->p)) c->p++;
        if (c->p + 1 < c->end && c->p[0] == '\\' && (c->p[1] == '\n' || c->p[1] == '\r')) {
            c->p += (c->p[1] == '\r' && c->p + 2 < c->end && c->p[2] == '\n') ? 3 : 2;
            c->line++;
            continue;
        }
        return;
    }
}

static bool at_line_end(const obj_cursor* c)
{
    return c->p >= c->end || *c->p == '\n' || *c->p == '\r' || *c->p == '#';
}

/* Advances past the current line (its terminator: \n, \r\n or a lone \r). */
static void next_line(obj_cursor* c)
{
    const char* p = c->p;
    const char* nl = memchr(p, '\n', (size_t)(c->end - p));
    const char* cr = memchr(p, '\r', (size_t)((nl ? nl : c->end) - p));
    if (cr && !(cr + 1 < c->end && cr[1] == '\n')) { /* lone \r (old Mac) ends this line */
        c->p = cr + 1;
    } else if (nl) {
        /* a backslash right before the newline continues the statement; skipped lines count */
        c->p = nl + 1;
    } else {
        c->p = c->end;
    }
    c->line++;
}

static tg_status fail_status(obj_cursor* c, const char* name, tg_diag* diag, tg_status st, const char* msg,
                             long long value)
{
    uint64_t line, col;
    size_t off = (size_t)(c->p - c->data);
    tg__line_col(c->data, off, &line, &col);
    (void)line;
    tg__diag_set(diag, name, c->line, col, off, msg, value);
    return st;
}

static tg_status fail(obj_cursor* c, const char* name, tg_diag* diag, const char* msg, long long value)
{
    return fail_status(c, name, diag, TG_ERR_PARSE, msg, value);
}

static tg_status parse_vertex(obj_cursor* c, const char* name, const tg_allocator* a, tg_diag* diag,
                              tg__vec* xyz)
{
    if (!tg__vec_reserve(a, xyz, 3)) return TG_ERR_OUT_OF_MEMORY;
    double* out = (double*)xyz->data + xyz->count;
    for (int k = 0; k < 3; ++k) {
        skip_blanks(c);
        const char* q = at_line_end(c) ? NULL : tg__parse_double(c->p, &out[k]);
        if (!q || q > c->end) return fail(c, name, diag, "vertex needs 3 numeric coordinates (got %lld)", k);
        if (!isfinite(out[k])) return fail_status(c, name, diag, TG_ERR_INVALID_MESH, "non-finite vertex coordinate (coordinate %lld)", k);
        c->p = q;
    }
    xyz->count += 3;
    return TG_OK;
}

static tg_status parse_face(obj_cursor* c, const char* name, const tg_allocator* a, tg_diag* diag,
                            size_t vertex_count, tg__vec* poly, tg__vec* tris)
{
    poly->count = 0;
    for (;;) {
        skip_blanks(c);
        if (at_line_end(c)) break;
        int64_t idx;
        const char* q = tg__parse_int(c->p, &idx);
        if (!q) return fail(c, name, diag, "face corner is not a vertex index%.0lld", 0);
        int64_t v = idx > 0 ? idx - 1 : (int64_t)vertex_count + idx;
        if (idx == 0 || v < 0 || v >= (int64_t)vertex_count)
            return fail_status(c, name, diag, TG_ERR_INVALID_MESH, "face index %lld out of range", (long long)idx);
        /* skip /vt/vn */
        while (q < c->end && *q != ' ' && *q != '\t' && *q != '\n' && *q != '\r' && *q != '#') {
            if (*q != '/' && *q != '-' && *q != '+' && !tg__is_digit(*q))
                return fail(c, name, diag, "unexpected character in face corner%.0lld", 0);
            q++;
        }
        c->p = q;
        if (!tg__vec_reserve(a, poly, 1)) return TG_ERR_OUT_OF_MEMORY;
        ((uint32_t*)poly->data)[poly->count++] = (uint32_t)v;
    }
    if (poly->count < 3) return fail(c, name, diag, "face has %lld corners (at least 3 needed)", (long long)poly->count);
    if (!tg__fan_push(a, tris, poly->data, poly->count)) return TG_ERR_OUT_OF_MEMORY;
    return TG_OK;
}

tg_status tg__read_obj(const char* data, size_t size, const char* name, const tg_allocator* a,
                       tg_diag* diag, tg__soup* out)
{
    obj_cursor c = {data, data + size, data, 1};
    tg__vec xyz = {NULL, 0, 0, sizeof(double), 0, 0};
    tg__vec tris = {NULL, 0, 0, sizeof(uint32_t), 0, 0};
    tg__vec poly = {NULL, 0, 0, sizeof(uint32_t), 0, 0};
    tg_status st = TG_OK;
    while (c.p < c.end && st == TG_OK) {
        skip_blanks(&c);
        /* "v" and "f" end at a blank or at the end of the line ("f" alone is an empty face, an
         * error; "vt", "vn", "fo" are other statements) */
        if (c.p < c.end && (c.p[0] == 'v' || c.p[0] == 'f')) {
            const char* after = c.p + 1;
            bool ends = after >= c.end || tg__is_blank(*after) || *after == '\n' || *after == '\r' || *after == '#';
            if (ends && c.p[0] == 'v') {
                c.p = after;
                st = parse_vertex(&c, name, a, diag, &xyz);
            } else if (ends) {
                c.p = after;
                st = parse_face(&c, name, a, diag, xyz.count / 3, &poly, &tris);
            }
        }
        if (st == TG_OK) next_line(&c);
    }
    tg__vec_free(a, &poly);
    if (st == TG_OK && xyz.count / 3 >= (1u << 31)) st = TG_ERR_UNSUPPORTED;
    if (st != TG_OK) {
        if (st == TG_ERR_OUT_OF_MEMORY) tg__diag_set(diag, name, c.line, 0, 0, "out of memory");
        if (st == TG_ERR_UNSUPPORTED) tg__diag_set(diag, name, 0, 0, 0, "too many vertices for 32-bit indices");
        tg__vec_free(a, &xyz);
        tg__vec_free(a, &tris);
        return st;
    }
    out->xyz = xyz.data;
    out->vertex_count = xyz.count / 3;
    out->tri = tris.data;
    out->face_count = tris.count / 3;
    return TG_OK;
}
