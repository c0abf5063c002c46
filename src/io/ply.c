/* ply.c - PLY reader (ascii, binary_little_endian, binary_big_endian) and
 * tg_ply_read_vertex_scalar. Vertex x, y, z of any numeric type; the face list "vertex_indices"
 * or "vertex_index" (else the face element's first list) with any integer count and index
 * types; every other element and property (lists included) is skipped; polygons are
 * fan-triangulated. Every header count is checked against the bytes that follow the header
 * before anything is allocated from it.
 * Based on: G. Turk, "The PLY Polygon File Format" (1994), the format description distributed
 * with the original ply library (header grammar, the eight scalar types and their sizes, list
 * properties, the three encodings); the type aliases int8..float64 of later writers. */
#include "io/io_internal.h"
#include "io/numparse.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* ---- header model ---- */

enum ply_type { PLY_NONE = 0, PLY_I8, PLY_U8, PLY_I16, PLY_U16, PLY_I32, PLY_U32, PLY_F32, PLY_F64 };
static const uint8_t type_size[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};

enum ply_encoding { PLY_ASCII = 1, PLY_LE, PLY_BE };

typedef struct ply_prop {
    const char* name; /* points into the header text */
    size_t name_len;
    uint8_t type;       /* scalar type; for a list, the item type */
    uint8_t count_type; /* list count type; PLY_NONE for a scalar */
    size_t offset;      /* byte offset in a binary record (meaningful before the first list) */
} ply_prop;

typedef struct ply_element {
    const char* name;
    size_t name_len;
    uint64_t count;
    size_t first_prop, prop_count;
    size_t min_size;  /* binary: exact record size without lists, else its lower bound */
    bool has_list;
    size_t header_off; /* offset of the "element" line, for diagnostics */
} ply_element;

typedef struct ply_file {
    const char* data;
    size_t size;
    const char* name;
    tg_diag* diag;
    const tg_allocator* a;
    int encoding;
    size_t body; /* offset of the first byte after the header */
    tg__vec elems; /* ply_element */
    tg__vec props; /* ply_prop */
} ply_file;

/* What to keep while walking the records of one element: up to three scalar columns (prop
 * indices within the element) and one list of vertex indices. */
typedef struct ply_pick {
    size_t col_prop[3];
    int ncols;
    bool finite;        /* columns must be finite (mesh coordinates) */
    double* vals;       /* ncols values per record */
    size_t list_prop;   /* SIZE_MAX: none */
    size_t vertex_count; /* list items must be < vertex_count */
    tg__vec* poly;      /* receives the list as uint32 */
} ply_pick;

#define PLY_NO_PROP SIZE_MAX

static ply_element* elem_at(const ply_file* f, size_t i) { return (ply_element*)f->elems.data + i; }
static ply_prop* prop_at(const ply_file* f, size_t i) { return (ply_prop*)f->props.data + i; }

static bool word_is(const char* s, size_t n, const char* lit)
{
    return strlen(lit) == n && memcmp(s, lit, n) == 0;
}

static int type_from_word(const char* s, size_t n)
{
    static const struct { const char* name; int type; } names[] = {
        {"char", PLY_I8},    {"int8", PLY_I8},     {"uchar", PLY_U8},    {"uint8", PLY_U8},
        {"short", PLY_I16},  {"int16", PLY_I16},   {"ushort", PLY_U16},  {"uint16", PLY_U16},
        {"int", PLY_I32},    {"int32", PLY_I32},   {"uint", PLY_U32},    {"uint32", PLY_U32},
        {"float", PLY_F32},  {"float32", PLY_F32}, {"double", PLY_F64},  {"float64", PLY_F64},
    };
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i)
        if (word_is(s, n, names[i].name)) return names[i].type;
    return PLY_NONE;
}

static bool type_is_integer(int t) { return t >= PLY_I8 && t <= PLY_U32; }

/* ---- binary loads: explicit byte order, so the host's does not matter ---- */

static inline uint16_t ld16(const unsigned char* p, bool big)
{
    return big ? (uint16_t)(p[0] << 8 | p[1]) : (uint16_t)(p[1] << 8 | p[0]);
}

static inline uint32_t ld32(const unsigned char* p, bool big)
{
    return big ? (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3]
               : (uint32_t)p[3] << 24 | (uint32_t)p[2] << 16 | (uint32_t)p[1] << 8 | p[0];
}

static inline uint64_t ld64(const unsigned char* p, bool big)
{
    uint64_t hi = ld32(p, big), lo = ld32(p + 4, big);
    return big ? hi << 32 | lo : lo << 32 | hi;
}

static inline double ld_f32(const unsigned char* p, bool big)
{
    uint32_t u = ld32(p, big);
    float v;
    memcpy(&v, &u, sizeof v);
    return v;
}

static inline double ld_f64(const unsigned char* p, bool big)
{
    uint64_t u = ld64(p, big);
    double v;
    memcpy(&v, &u, sizeof v);
    return v;
}

static double scalar_value(const unsigned char* p, int type, bool big)
{
    switch (type) {
    case PLY_I8: return (int8_t)p[0];
    case PLY_U8: return p[0];
    case PLY_I16: return (int16_t)ld16(p, big);
    case PLY_U16: return ld16(p, big);
    case PLY_I32: return (int32_t)ld32(p, big);
    case PLY_U32: return ld32(p, big);
    case PLY_F32: return ld_f32(p, big);
    default: return ld_f64(p, big);
    }
}

/* Integer types only (list counts and indices; the header refuses float ones). */
static int64_t int_value(const unsigned char* p, int type, bool big)
{
    switch (type) {
    case PLY_I8: return (int8_t)p[0];
    case PLY_U8: return p[0];
    case PLY_I16: return (int16_t)ld16(p, big);
    case PLY_U16: return ld16(p, big);
    case PLY_I32: return (int32_t)ld32(p, big);
    default: return ld32(p, big);
    }
}

/* ---- header ---- */

typedef struct ply_word {
    const char* s;
    size_t n;
} ply_word;

/* Splits [s, e) at blanks into at most max words; returns the total number of words. */
static size_t split_words(const char* s, const char* e, ply_word* w, size_t max)
{
    size_t count = 0;
    while (s < e) {
        while (s < e && (tg__is_blank(*s) || *s == '\v' || *s == '\f')) s++;
        if (s >= e) break;
        const char* t = s;
        while (s < e && !(tg__is_blank(*s) || *s == '\v' || *s == '\f')) s++;
        if (count < max) w[count] = (ply_word){t, (size_t)(s - t)};
        count++;
    }
    return count;
}

static tg_status header_fail(ply_file* f, size_t off, tg_status st, const char* fmt, ...) TG_PRINTF(4, 5);
static tg_status header_fail(ply_file* f, size_t off, tg_status st, const char* fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    tg__io_vfail(f->diag, f->name, f->data, off, st, fmt, ap);
    va_end(ap);
    return st;
}

#define W_ARGS(w) (int)((w).n < 40 ? (w).n : 40), (w).s

static tg_status header_element(ply_file* f, size_t off, const ply_word* w, size_t nw)
{
    if (nw != 3) return header_fail(f, off, TG_ERR_PARSE, "'element' needs a name and a count");
    int64_t count;
    const char* q = tg__parse_int(w[2].s, &count);
    if (!q || q != w[2].s + w[2].n)
        return header_fail(f, off, TG_ERR_PARSE, "element '%.*s': count '%.*s' is not an integer", W_ARGS(w[1]), W_ARGS(w[2]));
    if (count < 0)
        return header_fail(f, off, TG_ERR_PARSE, "element '%.*s': negative count %lld", W_ARGS(w[1]), (long long)count);
    if (!tg__vec_reserve(f->a, &f->elems, 1)) return TG_ERR_OUT_OF_MEMORY;
    ply_element* e = elem_at(f, f->elems.count++);
    memset(e, 0, sizeof *e);
    e->name = w[1].s;
    e->name_len = w[1].n;
    e->count = (uint64_t)count;
    e->first_prop = f->props.count;
    e->header_off = off;
    return TG_OK;
}

static tg_status header_property(ply_file* f, size_t off, const ply_word* w, size_t nw)
{
    if (f->elems.count == 0) return header_fail(f, off, TG_ERR_PARSE, "'property' before any 'element'");
    ply_prop p = {NULL, 0, PLY_NONE, PLY_NONE, 0};
    if (nw >= 2 && word_is(w[1].s, w[1].n, "list")) {
        if (nw != 5) return header_fail(f, off, TG_ERR_PARSE, "'property list' needs a count type, an item type and a name");
        p.count_type = (uint8_t)type_from_word(w[2].s, w[2].n);
        p.type = (uint8_t)type_from_word(w[3].s, w[3].n);
        if (!p.count_type || !p.type)
            return header_fail(f, off, TG_ERR_PARSE, "unknown list type in '%.*s %.*s'", W_ARGS(w[2]), W_ARGS(w[3]));
        if (!type_is_integer(p.count_type))
            return header_fail(f, off, TG_ERR_PARSE, "list count type '%.*s' is not an integer type", W_ARGS(w[2]));
        p.name = w[4].s;
        p.name_len = w[4].n;
    } else {
        if (nw != 3) return header_fail(f, off, TG_ERR_PARSE, "'property' needs a type and a name");
        p.type = (uint8_t)type_from_word(w[1].s, w[1].n);
        if (!p.type) return header_fail(f, off, TG_ERR_PARSE, "unknown property type '%.*s'", W_ARGS(w[1]));
        p.name = w[2].s;
        p.name_len = w[2].n;
    }
    if (!tg__vec_reserve(f->a, &f->props, 1)) return TG_ERR_OUT_OF_MEMORY;
    ply_element* e = elem_at(f, f->elems.count - 1);
    if (!e->has_list) p.offset = e->min_size;
    e->min_size += p.count_type ? type_size[p.count_type] : type_size[p.type];
    e->has_list |= p.count_type != PLY_NONE;
    e->prop_count++;
    *prop_at(f, f->props.count++) = p;
    return TG_OK;
}

/* Element counts against the bytes after the header: binary records need at least their fixed
 * part (list counts included), ascii records at least two bytes per property. */
static tg_status check_counts(ply_file* f)
{
    uint64_t avail = f->size - f->body, need = 0;
    for (size_t i = 0; i < f->elems.count; ++i) {
        const ply_element* e = elem_at(f, i);
        uint64_t per = f->encoding == PLY_ASCII ? 2 * (uint64_t)e->prop_count : e->min_size;
        uint64_t slack = f->encoding == PLY_ASCII ? 1 : 0; /* the last value needs no separator */
        if (per && (e->count > (avail + slack) / per || need + e->count * per > avail + slack))
            return header_fail(f, e->header_off, TG_ERR_PARSE,
                               "element '%.*s' declares %llu records of at least %llu bytes, more than the %llu bytes "
                               "after the header", (int)(e->name_len < 40 ? e->name_len : 40), e->name,
                               (unsigned long long)e->count, (unsigned long long)per, (unsigned long long)avail);
        need += e->count * per;
    }
    return TG_OK;
}

static tg_status parse_header(ply_file* f)
{
    const char* d = f->data;
    size_t n = f->size, pos = 0;
    bool first = true, have_format = false;
    for (;;) {
        if (pos >= n) return header_fail(f, pos, TG_ERR_PARSE, "missing 'end_header' (truncated header?)");
        size_t e = pos;
        while (e < n && !tg__is_eol(d[e])) e++;
        /* \n, \r\n or a lone \r; a binary body after "end_header\r" that starts with byte 0x0A
         * is read as if the header ended in \r\n (the format says \n; no writer emits a lone \r) */
        size_t next = e >= n ? n : (d[e] == '\r' && e + 1 < n && d[e + 1] == '\n') ? e + 2 : e + 1;
        ply_word w[6];
        size_t nw = split_words(d + pos, d + e, w, 6);
        tg_status st = TG_OK;
        if (first) {
            if (nw != 1 || !word_is(w[0].s, w[0].n, "ply"))
                return header_fail(f, pos, TG_ERR_PARSE, "not a PLY file: the first line must be 'ply'");
            first = false;
        } else if (nw == 0) {
            /* blank header line: tolerated */
        } else if (word_is(w[0].s, w[0].n, "format")) {
            if (nw < 2) return header_fail(f, pos, TG_ERR_PARSE, "'format' needs an encoding");
            f->encoding = word_is(w[1].s, w[1].n, "ascii")                  ? PLY_ASCII
                        : word_is(w[1].s, w[1].n, "binary_little_endian") ? PLY_LE
                        : word_is(w[1].s, w[1].n, "binary_big_endian")    ? PLY_BE
                                                                           : 0;
            if (!f->encoding) return header_fail(f, pos, TG_ERR_PARSE, "unknown PLY encoding '%.*s'", W_ARGS(w[1]));
            have_format = true;
        } else if (word_is(w[0].s, w[0].n, "comment") || word_is(w[0].s, w[0].n, "obj_info")) {
            /* free text */
        } else if (word_is(w[0].s, w[0].n, "element")) {
            st = header_element(f, pos, w, nw);
        } else if (word_is(w[0].s, w[0].n, "property")) {
            st = header_property(f, pos, w, nw);
        } else if (word_is(w[0].s, w[0].n, "end_header")) {
            if (!have_format) return header_fail(f, pos, TG_ERR_PARSE, "PLY header has no 'format' line");
            f->body = next;
            return check_counts(f);
        } else {
            return header_fail(f, pos, TG_ERR_PARSE, "unknown PLY header line starting with '%.*s'", W_ARGS(w[0]));
        }
        if (st != TG_OK) {
            if (st == TG_ERR_OUT_OF_MEMORY) header_fail(f, pos, st, "out of memory reading the PLY header");
            return st;
        }
        pos = next;
    }
}

static size_t find_element(const ply_file* f, const char* name)
{
    for (size_t i = 0; i < f->elems.count; ++i)
        if (word_is(elem_at(f, i)->name, elem_at(f, i)->name_len, name)) return i;
    return PLY_NO_PROP;
}

/* Index of the property named `name` within element e (scalar only), or PLY_NO_PROP. */
static size_t find_scalar(const ply_file* f, const ply_element* e, const char* name)
{
    for (size_t k = 0; k < e->prop_count; ++k) {
        const ply_prop* p = prop_at(f, e->first_prop + k);
        if (!p->count_type && word_is(p->name, p->name_len, name)) return k;
    }
    return PLY_NO_PROP;
}

static size_t find_face_list(const ply_file* f, const ply_element* e)
{
    size_t first_list = PLY_NO_PROP;
    for (size_t k = 0; k < e->prop_count; ++k) {
        const ply_prop* p = prop_at(f, e->first_prop + k);
        if (!p->count_type) continue;
        if (word_is(p->name, p->name_len, "vertex_indices") || word_is(p->name, p->name_len, "vertex_index")) return k;
        if (first_list == PLY_NO_PROP) first_list = k;
    }
    return first_list;
}

/* ---- body: shared diagnostics ---- */

static tg_status body_fail(ply_file* f, size_t off, tg_status st, const char* fmt, ...) TG_PRINTF(4, 5);
static tg_status body_fail(ply_file* f, size_t off, tg_status st, const char* fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    tg__io_vfail(f->diag, f->name, f->encoding == PLY_ASCII ? f->data : NULL, off, st, fmt, ap);
    va_end(ap);
    return st;
}

#define E_ARGS(e) (int)((e)->name_len < 40 ? (e)->name_len : 40), (e)->name

static tg_status truncated(ply_file* f, size_t off, const ply_element* e, uint64_t rec)
{
    return body_fail(f, off, TG_ERR_PARSE, "data ends inside %.*s %llu of %llu (truncated file?)", E_ARGS(e),
                     (unsigned long long)rec, (unsigned long long)e->count);
}

static tg_status bad_index(ply_file* f, size_t off, const ply_element* e, uint64_t rec, int64_t idx, size_t nv)
{
    return body_fail(f, off, TG_ERR_INVALID_MESH, "%.*s %llu: vertex index %lld out of range (%zu vertices)", E_ARGS(e),
                     (unsigned long long)rec, (long long)idx, nv);
}

static tg_status short_face(ply_file* f, size_t off, const ply_element* e, uint64_t rec, int64_t n)
{
    return body_fail(f, off, TG_ERR_PARSE, "%.*s %llu has %lld vertices (at least 3 needed)", E_ARGS(e),
                     (unsigned long long)rec, (long long)n);
}

static tg_status non_finite(ply_file* f, size_t off, const ply_element* e, uint64_t rec, const ply_prop* p)
{
    return body_fail(f, off, TG_ERR_INVALID_MESH, "%.*s %llu: non-finite %.*s", E_ARGS(e), (unsigned long long)rec,
                     (int)(p->name_len < 40 ? p->name_len : 40), p->name);
}

static int pick_col(const ply_pick* pick, size_t k)
{
    for (int c = 0; c < pick->ncols; ++c)
        if (pick->col_prop[c] == k) return c;
    return -1;
}

/* ---- binary records ---- */

/* One record of any layout (the general path): keeps the picked columns and list. */
static tg_status binary_record(ply_file* f, const ply_element* e, uint64_t rec, size_t* pos, const ply_pick* pick)
{
    const unsigned char* d = (const unsigned char*)f->data;
    const bool big = f->encoding == PLY_BE;
    size_t p = *pos, n = f->size;
    for (size_t k = 0; k < e->prop_count; ++k) {
        const ply_prop* pr = prop_at(f, e->first_prop + k);
        if (!pr->count_type) {
            size_t s = type_size[pr->type];
            if (n - p < s) return truncated(f, p, e, rec);
            int c = pick_col(pick, k);
            if (c >= 0) {
                double v = scalar_value(d + p, pr->type, big);
                if (pick->finite && !isfinite(v)) return non_finite(f, p, e, rec, pr);
                pick->vals[(size_t)rec * (size_t)pick->ncols + (size_t)c] = v;
            }
            p += s;
            continue;
        }
        size_t cs = type_size[pr->count_type], is = type_size[pr->type];
        if (n - p < cs) return truncated(f, p, e, rec);
        int64_t items = int_value(d + p, pr->count_type, big);
        if (items < 0)
            return body_fail(f, p, TG_ERR_PARSE, "%.*s %llu: negative list length %lld", E_ARGS(e),
                             (unsigned long long)rec, (long long)items);
        size_t at = p;
        p += cs;
        if ((uint64_t)items > (n - p) / is) return truncated(f, at, e, rec);
        if (k == pick->list_prop) {
            if (items < 3) return short_face(f, at, e, rec, items);
            tg__vec* poly = pick->poly;
            poly->count = 0;
            if (!tg__vec_reserve(f->a, poly, (size_t)items)) return TG_ERR_OUT_OF_MEMORY;
            uint32_t* out = poly->data;
            for (size_t i = 0; i < (size_t)items; ++i) {
                int64_t v = int_value(d + p + i * is, pr->type, big);
                if (v < 0 || (uint64_t)v >= pick->vertex_count)
                    return bad_index(f, p + i * is, e, rec, v, pick->vertex_count);
                out[i] = (uint32_t)v;
            }
            poly->count = (size_t)items;
        }
        p += (size_t)items * is;
    }
    *pos = p;
    return TG_OK;
}

/* Vertex columns of a fixed-size record (the common layout): no per-property dispatch, and the
 * all-float / all-double cases get their own loops. */
static tg_status binary_columns_fixed(ply_file* f, const ply_element* e, size_t* pos, const ply_pick* pick)
{
    const bool big = f->encoding == PLY_BE;
    const size_t rs = e->min_size, nc = (size_t)pick->ncols;
    if (e->count > (f->size - *pos) / (rs ? rs : 1)) return truncated(f, f->size, e, (f->size - *pos) / rs);
    const unsigned char* base = (const unsigned char*)f->data + *pos;
    const ply_prop* pr[3];
    size_t off[3];
    int type = -1;
    for (size_t c = 0; c < nc; ++c) {
        pr[c] = prop_at(f, e->first_prop + pick->col_prop[c]);
        off[c] = pr[c]->offset;
        type = c == 0 ? pr[c]->type : (type == pr[c]->type ? type : -1);
    }
    double* out = pick->vals;
    const size_t count = (size_t)e->count;
    for (size_t i = 0; i < count; ++i) {
        const unsigned char* r = base + i * rs;
        for (size_t c = 0; c < nc; ++c) {
            double v = type == PLY_F32 ? ld_f32(r + off[c], big)
                     : type == PLY_F64 ? ld_f64(r + off[c], big)
                                       : scalar_value(r + off[c], pr[c]->type, big);
            out[i * nc + c] = v;
        }
    }
    if (pick->finite) {
        for (size_t i = 0; i < count * nc; ++i)
            if (!isfinite(out[i]))
                return non_finite(f, *pos + (i / nc) * rs + off[i % nc], e, i / nc, pr[i % nc]);
    }
    *pos += count * rs;
    return TG_OK;
}

static bool push_poly(ply_file* f, tg__vec* tris, const tg__vec* poly)
{
    return tg__fan_push(f->a, tris, poly->data, poly->count);
}

/* Faces whose record is just "uchar/char count, int/uint items" (what nearly every writer
 * emits): triangles are decoded in place. */
static tg_status binary_faces_fast(ply_file* f, const ply_element* e, size_t* pos, const ply_pick* pick, tg__vec* tris)
{
    const unsigned char* d = (const unsigned char*)f->data;
    const bool big = f->encoding == PLY_BE;
    const ply_prop* pr = prop_at(f, e->first_prop);
    const bool signed_count = pr->count_type == PLY_I8, signed_items = pr->type == PLY_I32;
    const uint32_t nv = (uint32_t)pick->vertex_count; /* < 2^31, so a negative int32 is >= nv too */
    size_t p = *pos, n = f->size;
    for (uint64_t rec = 0; rec < e->count; ++rec) {
        if (p >= n) return truncated(f, p, e, rec);
        int items = signed_count ? (int8_t)d[p] : d[p];
        if (items == 3 && n - p >= 13) {
            uint32_t a = ld32(d + p + 1, big), b = ld32(d + p + 5, big), c = ld32(d + p + 9, big);
            if (TG_UNLIKELY(a >= nv || b >= nv || c >= nv)) {
                uint32_t bad = a >= nv ? a : b >= nv ? b : c;
                size_t at = p + 1 + 4 * (size_t)(a >= nv ? 0 : b >= nv ? 1 : 2);
                return bad_index(f, at, e, rec, signed_items ? (int64_t)(int32_t)bad : (int64_t)bad, nv);
            }
            if (TG_UNLIKELY(tris->capacity - tris->count < 3) && !tg__vec_reserve(f->a, tris, 3))
                return TG_ERR_OUT_OF_MEMORY;
            uint32_t* t = (uint32_t*)tris->data + tris->count;
            t[0] = a, t[1] = b, t[2] = c;
            tris->count += 3;
            p += 13;
            continue;
        }
        tg_status st = binary_record(f, e, rec, &p, pick);
        if (st != TG_OK) return st;
        if (!push_poly(f, tris, pick->poly)) return TG_ERR_OUT_OF_MEMORY;
    }
    *pos = p;
    return TG_OK;
}

/* ---- ascii records ---- */

static size_t skip_space(const char* d, size_t p, size_t n)
{
    while (p < n && tg__is_space(d[p])) p++;
    return p;
}

static bool token_end(const ply_file* f, size_t q)
{
    return q >= f->size || tg__is_space(f->data[q]);
}

static tg_status ascii_record(ply_file* f, const ply_element* e, uint64_t rec, size_t* pos, const ply_pick* pick)
{
    const char* d = f->data;
    size_t p = *pos, n = f->size;
    for (size_t k = 0; k < e->prop_count; ++k) {
        const ply_prop* pr = prop_at(f, e->first_prop + k);
        p = skip_space(d, p, n);
        if (p >= n) return truncated(f, p, e, rec);
        if (!pr->count_type) {
            double v;
            const char* q = tg__parse_double(d + p, &v);
            if (!q || !token_end(f, (size_t)(q - d)))
                return body_fail(f, p, TG_ERR_PARSE, "%.*s %llu: property '%.*s' is not a number", E_ARGS(e),
                                 (unsigned long long)rec, (int)(pr->name_len < 40 ? pr->name_len : 40), pr->name);
            int c = pick_col(pick, k);
            if (c >= 0) {
                if (pick->finite && !isfinite(v)) return non_finite(f, p, e, rec, pr);
                pick->vals[(size_t)rec * (size_t)pick->ncols + (size_t)c] = v;
            }
            p = (size_t)(q - d);
            continue;
        }
        int64_t items;
        const char* q = tg__parse_int(d + p, &items);
        if (!q || !token_end(f, (size_t)(q - d)))
            return body_fail(f, p, TG_ERR_PARSE, "%.*s %llu: list length is not an integer", E_ARGS(e), (unsigned long long)rec);
        if (items < 0)
            return body_fail(f, p, TG_ERR_PARSE, "%.*s %llu: negative list length %lld", E_ARGS(e),
                             (unsigned long long)rec, (long long)items);
        size_t at = p;
        p = (size_t)(q - d);
        if ((uint64_t)items > (n - p) / 2) /* each item takes a separator and a digit */
            return truncated(f, at, e, rec);
        bool keep = k == pick->list_prop;
        if (keep) {
            if (items < 3) return short_face(f, at, e, rec, items);
            pick->poly->count = 0;
            if (!tg__vec_reserve(f->a, pick->poly, (size_t)items)) return TG_ERR_OUT_OF_MEMORY;
        }
        for (int64_t i = 0; i < items; ++i) {
            p = skip_space(d, p, n);
            if (p >= n) return truncated(f, p, e, rec);
            if (keep) {
                int64_t v;
                q = tg__parse_int(d + p, &v);
                if (!q || !token_end(f, (size_t)(q - d)))
                    return body_fail(f, p, TG_ERR_PARSE, "%.*s %llu: list item %lld is not an integer", E_ARGS(e),
                                     (unsigned long long)rec, (long long)i);
                if (v < 0 || (uint64_t)v >= pick->vertex_count) return bad_index(f, p, e, rec, v, pick->vertex_count);
                ((uint32_t*)pick->poly->data)[pick->poly->count++] = (uint32_t)v;
            } else {
                double v;
                q = tg__parse_double(d + p, &v);
                if (!q || !token_end(f, (size_t)(q - d)))
                    return body_fail(f, p, TG_ERR_PARSE, "%.*s %llu: list item %lld is not a number", E_ARGS(e),
                                     (unsigned long long)rec, (long long)i);
            }
            p = (size_t)(q - d);
        }
    }
    *pos = p;
    return TG_OK;
}

/* ---- ascii diagnosis: records that do not fill their lines ---- */

/* Values are read as a stream of tokens, so records may wrap across lines. When reading fails
 * on a file that has one line per record (as most writers, and Turk's ply library, which reads a
 * line per record, make them), the first line whose value count is not what its record takes is
 * the real cause (an undeclared property, a wrong list length), not the end of data the stream
 * reader met far later. Returns false when the file is not laid out that way or every line fits. */
static bool ascii_line_mismatch(ply_file* f)
{
    const char* d = f->data;
    size_t n = f->size, lines = 0, records = 0;
    for (size_t i = 0; i < f->elems.count; ++i) records += (size_t)elem_at(f, i)->count;
    for (size_t p = f->body; p < n;) { /* non-blank lines of the body */
        size_t e = p;
        bool blank = true;
        while (e < n && !tg__is_eol(d[e])) blank &= tg__is_space(d[e]), e++;
        lines += !blank;
        p = e + 1;
    }
    if (lines != records) return false;
    size_t p = f->body;
    for (size_t i = 0; i < f->elems.count; ++i) {
        const ply_element* e = elem_at(f, i);
        for (uint64_t rec = 0; rec < e->count; ++rec) {
            while (p < n && tg__is_space(d[p])) p++; /* to the next non-blank line */
            size_t line_start = p, end = p;
            while (end < n && !tg__is_eol(d[end])) end++;
            size_t tokens = 0, need = 0, k = 0;
            int64_t items = -1;
            for (size_t q = line_start; q < end;) { /* count the values; the record's need as they come */
                while (q < end && tg__is_space(d[q])) q++;
                if (q >= end) break;
                tokens++;
                if (k < e->prop_count && items < 0) {
                    const ply_prop* pr = prop_at(f, e->first_prop + k);
                    if (pr->count_type) {
                        if (!tg__parse_int(d + q, &items) || items < 0) return false;
                        need += 1 + (size_t)items;
                        if (items == 0) items = -1, k++;
                    } else {
                        need++, k++;
                    }
                } else if (items > 0 && --items == 0) {
                    items = -1, k++;
                }
                while (q < end && !tg__is_space(d[q])) q++;
            }
            for (; k < e->prop_count && items < 0; ++k) need++; /* properties the line lacks */
            if (tokens != need) {
                body_fail(f, line_start, TG_ERR_PARSE,
                          "%.*s %llu has %zu values on its line, its %zu propert%s take%s %zu: %s", E_ARGS(e),
                          (unsigned long long)rec, tokens, e->prop_count, e->prop_count == 1 ? "y" : "ies",
                          e->prop_count == 1 ? "s" : "", need,
                          tokens > need ? "a value the header does not declare" : "values missing");
                return true;
            }
            p = end;
        }
    }
    return false;
}

/* ---- elements ---- */

static tg_status read_records(ply_file* f, const ply_element* e, size_t* pos, const ply_pick* pick, tg__vec* tris)
{
    if (f->encoding != PLY_ASCII) {
        if (!e->has_list && pick->list_prop == PLY_NO_PROP) {
            if (pick->ncols) return binary_columns_fixed(f, e, pos, pick);
            /* skipped fixed-size element: one bounds check, no loop */
            if (e->min_size && e->count > (f->size - *pos) / e->min_size)
                return truncated(f, f->size, e, (f->size - *pos) / e->min_size);
            *pos += (size_t)e->count * e->min_size;
            return TG_OK;
        }
        const ply_prop* first = prop_at(f, e->first_prop);
        if (tris && e->prop_count == 1 && pick->list_prop == 0 && type_size[first->count_type] == 1 &&
            type_size[first->type] == 4)
            return binary_faces_fast(f, e, pos, pick, tris);
    } else if (e->prop_count == 0) {
        return TG_OK;
    }
    for (uint64_t rec = 0; rec < e->count; ++rec) {
        tg_status st = f->encoding == PLY_ASCII ? ascii_record(f, e, rec, pos, pick) : binary_record(f, e, rec, pos, pick);
        if (st != TG_OK) return st;
        if (tris && !push_poly(f, tris, pick->poly)) return TG_ERR_OUT_OF_MEMORY;
    }
    return TG_OK;
}

/* "vertex 4, face 2" (the declared counts, for messages). */
static void declared_counts(const ply_file* f, char* buf, size_t cap)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < f->elems.count && used + 1 < cap; ++i) {
        const ply_element* e = elem_at(f, i);
        int w = snprintf(buf + used, cap - used, "%s%.*s %llu", i ? ", " : "", E_ARGS(e), (unsigned long long)e->count);
        if (w < 0) break;
        used += (size_t)w;
    }
}

/* After the last element only line ends and blanks may follow (ascii), or nothing (binary):
 * more data means a count that is too small, and reading only the declared records would drop
 * data silently. Binary files padded with line ends, blanks or NUL bytes are read with a
 * warning (diag set, TG_OK). */
static tg_status check_end(ply_file* f, size_t pos)
{
    char counts[160];
    if (pos >= f->size) return TG_OK;
    size_t q = pos;
    if (f->encoding == PLY_ASCII) {
        q = skip_space(f->data, pos, f->size);
        if (q >= f->size) return TG_OK;
        size_t len = 0;
        while (q + len < f->size && !tg__is_space(f->data[q + len]) && len < 40) len++;
        declared_counts(f, counts, sizeof counts);
        return body_fail(f, q, TG_ERR_PARSE,
                         "data continues after the last declared record ('%.*s'; the header declares %s): a wrong "
                         "element count", (int)len, f->data + q, counts);
    }
    while (q < f->size && (f->data[q] == '\0' || tg__is_space(f->data[q]))) q++;
    declared_counts(f, counts, sizeof counts);
    if (q < f->size)
        return body_fail(f, pos, TG_ERR_PARSE,
                         "%zu bytes follow the last declared record (the header declares %s): a wrong element count",
                         f->size - pos, counts);
    body_fail(f, pos, TG_OK, "warning: %zu padding bytes after the last declared record ignored", f->size - pos);
    return TG_OK;
}

/* Walks the body element by element: vertex columns of element vidx go to vals, the face list
 * of element fidx (PLY_NO_PROP: none) to tris; others are skipped. Stops after the last
 * element it needs, or with to_end walks every element and checks that nothing follows. */
static tg_status read_body(ply_file* f, size_t vidx, const ply_pick* vpick, size_t fidx, const ply_pick* fpick,
                           tg__vec* tris, bool to_end)
{
    size_t pos = f->body, last = fidx != PLY_NO_PROP && fidx > vidx ? fidx : vidx;
    if (to_end) last = f->elems.count - 1;
    static const ply_pick skip = {{0, 0, 0}, 0, false, NULL, PLY_NO_PROP, 0, NULL};
    for (size_t i = 0; i <= last; ++i) {
        const ply_element* e = elem_at(f, i);
        tg_status st = i == vidx   ? read_records(f, e, &pos, vpick, NULL)
                     : i == fidx ? read_records(f, e, &pos, fpick, tris)
                                   : read_records(f, e, &pos, &skip, NULL);
        if (st != TG_OK) {
            if (st == TG_ERR_OUT_OF_MEMORY) body_fail(f, pos, st, "out of memory reading the PLY body");
            return st;
        }
    }
    return to_end ? check_end(f, pos) : TG_OK;
}

static void ply_free(ply_file* f)
{
    tg__vec_free(f->a, &f->elems);
    tg__vec_free(f->a, &f->props);
}

static void ply_init(ply_file* f, const char* data, size_t size, const char* name, const tg_allocator* a, tg_diag* diag)
{
    memset(f, 0, sizeof *f);
    f->data = data;
    f->size = size;
    f->name = name;
    f->diag = diag;
    f->a = a;
    f->elems.elem = sizeof(ply_element);
    f->props.elem = sizeof(ply_prop);
}

/* Checks the vertex element and finds x, y, z; vertex count below 2^31. */
static tg_status vertex_columns(ply_file* f, size_t* out_vidx, ply_pick* vpick)
{
    size_t vidx = find_element(f, "vertex");
    if (vidx == PLY_NO_PROP) return header_fail(f, f->body ? f->body - 1 : 0, TG_ERR_PARSE, "PLY header has no 'vertex' element");
    const ply_element* ve = elem_at(f, vidx);
    static const char* const xyz[3] = {"x", "y", "z"};
    for (int c = 0; c < 3; ++c) {
        vpick->col_prop[c] = find_scalar(f, ve, xyz[c]);
        if (vpick->col_prop[c] == PLY_NO_PROP)
            return header_fail(f, ve->header_off, TG_ERR_PARSE, "vertex element has no scalar property '%s'", xyz[c]);
    }
    if (ve->count >= (1u << 31))
        return header_fail(f, ve->header_off, TG_ERR_UNSUPPORTED, "%llu vertices exceed the 32-bit index limit",
                           (unsigned long long)ve->count);
    vpick->ncols = 3;
    vpick->finite = true;
    vpick->list_prop = PLY_NO_PROP;
    *out_vidx = vidx;
    return TG_OK;
}

tg_status tg__read_ply(const char* data, size_t size, const char* name, const tg_allocator* a,
                       tg_diag* diag, tg__soup* out)
{
    ply_file f;
    ply_init(&f, data, size, name, a, diag);
    ply_pick vpick = {{0, 0, 0}, 0, false, NULL, PLY_NO_PROP, 0, NULL};
    tg__vec poly = {NULL, 0, 0, sizeof(uint32_t), 0, 0};
    ply_pick fpick = {{0, 0, 0}, 0, false, NULL, PLY_NO_PROP, 0, &poly};
    tg__vec tris = {NULL, 0, 0, sizeof(uint32_t), 0, 0};
    size_t vidx = PLY_NO_PROP, fidx;
    double* xyz = NULL;
    tg_status st = parse_header(&f);
    if (st == TG_OK) st = vertex_columns(&f, &vidx, &vpick);
    if (st == TG_OK) {
        size_t nv = (size_t)elem_at(&f, vidx)->count;
        fidx = find_element(&f, "face");
        if (fidx != PLY_NO_PROP) {
            const ply_element* fe = elem_at(&f, fidx);
            fpick.list_prop = find_face_list(&f, fe);
            fpick.vertex_count = nv;
            if (fpick.list_prop == PLY_NO_PROP)
                st = header_fail(&f, fe->header_off, TG_ERR_PARSE, "face element has no list property");
            else if (!type_is_integer(prop_at(&f, fe->first_prop + fpick.list_prop)->type))
                st = header_fail(&f, fe->header_off, TG_ERR_PARSE, "face vertex list has a non-integer item type");
        }
        xyz = st == TG_OK ? tg__alloc_array(a, 3 * nv + 1, sizeof(double)) : NULL;
        if (st == TG_OK && !xyz) st = header_fail(&f, 0, TG_ERR_OUT_OF_MEMORY, "out of memory for %zu vertices", nv);
        vpick.vals = xyz;
        if (st == TG_OK && fidx != PLY_NO_PROP) {
            /* reserve the triangles the data can actually hold; polygons grow the vector */
            const ply_element* fe = elem_at(&f, fidx);
            const ply_prop* lp = prop_at(&f, fe->first_prop + fpick.list_prop);
            uint64_t per = f.encoding == PLY_ASCII ? 8 : (uint64_t)fe->min_size + 3u * type_size[lp->type];
            uint64_t cap = fe->count < (size - f.body) / per ? fe->count : (size - f.body) / per;
            if (!tg__vec_reserve(a, &tris, 3 * (size_t)cap + 3))
                st = header_fail(&f, 0, TG_ERR_OUT_OF_MEMORY, "out of memory for %llu faces", (unsigned long long)cap);
        }
        if (st == TG_OK) st = read_body(&f, vidx, &vpick, fidx, &fpick, &tris, true);
        if ((st == TG_ERR_PARSE || st == TG_ERR_INVALID_MESH) && f.encoding == PLY_ASCII && ascii_line_mismatch(&f))
            st = TG_ERR_PARSE;
        if (st == TG_OK) {
            out->xyz = xyz;
            out->vertex_count = nv;
            out->tri = tris.data;
            out->face_count = tris.count / 3;
        }
    }
    tg__vec_free(a, &poly);
    ply_free(&f);
    if (st != TG_OK) {
        tg__free(a, xyz);
        tg__vec_free(a, &tris);
    }
    return st;
}

tg_status tg_ply_read_vertex_scalar(const char* path, const char* name, double* out_values, size_t capacity,
                                    size_t* out_count, tg_diag* diag)
{
    if (out_count) *out_count = 0;
    if (!path || !name || !out_count) {
        tg__diag_set(diag, path ? path : "", 0, 0, 0, "NULL path, property name or out_count");
        return TG_ERR_INVALID_ARGUMENT;
    }
    tg__diag_clear(diag, path);
    char* data;
    size_t size;
    tg_status st = tg__read_file(path, NULL, diag, &data, &size);
    if (st != TG_OK) return st;
    ply_file f;
    ply_init(&f, data, size, path, NULL, diag);
    ply_pick vpick = {{0, 0, 0}, 1, false, NULL, PLY_NO_PROP, 0, NULL};
    double* vals = NULL;
    size_t vidx = PLY_NO_PROP, nv = 0;
    st = parse_header(&f);
    if (st == TG_OK) {
        vidx = find_element(&f, "vertex");
        if (vidx == PLY_NO_PROP) st = header_fail(&f, f.body ? f.body - 1 : 0, TG_ERR_PARSE, "PLY header has no 'vertex' element");
    }
    if (st == TG_OK) {
        const ply_element* ve = elem_at(&f, vidx);
        nv = (size_t)ve->count;
        vpick.col_prop[0] = find_scalar(&f, ve, name);
        if (vpick.col_prop[0] == PLY_NO_PROP)
            st = header_fail(&f, ve->header_off, TG_ERR_PARSE, "vertex element has no scalar property '%.64s'", name);
    }
    if (st == TG_OK && out_values && capacity < nv) {
        tg__diag_set(diag, path, 0, 0, 0, "%zu values needed, capacity is %zu", nv, capacity);
        st = TG_ERR_CAPACITY;
    }
    if (st == TG_OK && out_values) {
        /* read into scratch so that the caller's array is untouched on failure */
        vals = tg__alloc_array(NULL, nv + 1, sizeof(double));
        vpick.vals = vals;
        st = vals ? read_body(&f, vidx, &vpick, PLY_NO_PROP, NULL, NULL, false) : TG_ERR_OUT_OF_MEMORY;
        if (st == TG_OK) memcpy(out_values, vals, nv * sizeof(double));
    }
    if (st == TG_OK || st == TG_ERR_CAPACITY) *out_count = nv;
    tg__free(NULL, vals);
    ply_free(&f);
    tg__free(NULL, data);
    return st;
}
