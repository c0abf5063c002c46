/* write.c - mesh writers: Wavefront OBJ (%.17g, so every double reads back bit-identical) and
 * binary little-endian PLY with optional per-vertex double scalars.
 * Based on: the Wavefront OBJ specification (v / f statements, 1-based indices); G. Turk, "The
 * PLY Polygon File Format" (header grammar, binary_little_endian records); C11 7.21.6.1 (%.17g
 * prints DBL_DECIMAL_DIG significant digits, enough to round-trip any double). */
#include "io/io_internal.h"
#include "mesh/mesh_internal.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

/* Buffered output with sticky error state: one check at the end instead of one per value. */
typedef struct out_file {
    FILE* f;
    const char* path;
    char buf[1 << 16];
    size_t len;
    bool failed;
    int err; /* errno of the first failure */
} out_file;

static void out_flush(out_file* o)
{
    if (o->len && !o->failed && fwrite(o->buf, 1, o->len, o->f) != o->len) {
        o->failed = true;
        o->err = errno;
    }
    o->len = 0;
}

static void out_bytes(out_file* o, const void* p, size_t n)
{
    if (o->len + n > sizeof o->buf) out_flush(o);
    memcpy(o->buf + o->len, p, n);
    o->len += n;
}

/* Room for one formatted item (a few hundred bytes at most). */
static char* out_room(out_file* o, size_t n)
{
    if (o->len + n > sizeof o->buf) out_flush(o);
    return o->buf + o->len;
}

static tg_status out_open(out_file* o, const char* path, tg_diag* diag)
{
    o->path = path;
    o->len = 0;
    o->failed = false;
    o->err = 0;
    o->f = fopen(path, "wb");
    if (!o->f) {
        tg__diag_set(diag, path, 0, 0, 0, "cannot open for writing: %s", strerror(errno));
        return TG_ERR_IO;
    }
    return TG_OK;
}

static tg_status out_close(out_file* o, tg_diag* diag)
{
    out_flush(o);
    if (fclose(o->f) != 0 && !o->failed) {
        o->failed = true;
        o->err = errno;
    }
    if (o->failed) {
        tg__diag_set(diag, o->path, 0, 0, 0, "write failed: %s", strerror(o->err));
        return TG_ERR_IO;
    }
    return TG_OK;
}

/* %.17g; the caller runs in the "C" locale (tg__c_locale_enter), so the separator is '.'. */
static size_t format_double(char* s, size_t cap, double v)
{
    int n = snprintf(s, cap, "%.17g", v);
    if (n < 0) n = 0;
    if ((size_t)n >= cap) n = (int)cap - 1;
    return (size_t)n;
}

static size_t format_u32(char* s, uint64_t v)
{
    char tmp[24];
    size_t n = 0;
    do {
        tmp[n++] = (char)('0' + v % 10);
        v /= 10;
    } while (v);
    for (size_t i = 0; i < n; ++i) s[i] = tmp[n - 1 - i];
    return n;
}

static bool valid_property_name(const char* s)
{
    if (!s || !*s) return false;
    for (; *s; ++s)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9') || *s == '_'))
            return false;
    return true;
}

static tg_status check_scalars(const tg_vertex_scalar* scalars, size_t count, const char* path, tg_diag* diag)
{
    if (count && !scalars) {
        tg__diag_set(diag, path, 0, 0, 0, "scalar_count is %zu but scalars is NULL", count);
        return TG_ERR_INVALID_ARGUMENT;
    }
    for (size_t i = 0; i < count; ++i) {
        const char* nm = scalars[i].name;
        if (!valid_property_name(nm) || strlen(nm) > 64) {
            tg__diag_set(diag, path, 0, 0, 0, "scalar %zu: property name must be 1-64 letters, digits or '_'", i);
            return TG_ERR_INVALID_ARGUMENT;
        }
        if (!scalars[i].values) {
            tg__diag_set(diag, path, 0, 0, 0, "scalar '%s' has NULL values", nm);
            return TG_ERR_INVALID_ARGUMENT;
        }
        bool clash = strcmp(nm, "x") == 0 || strcmp(nm, "y") == 0 || strcmp(nm, "z") == 0;
        for (size_t j = 0; j < i && !clash; ++j) clash = strcmp(nm, scalars[j].name) == 0;
        if (clash) {
            tg__diag_set(diag, path, 0, 0, 0, "scalar name '%s' is used twice (x, y, z are taken)", nm);
            return TG_ERR_INVALID_ARGUMENT;
        }
    }
    return TG_OK;
}

static void put_le_double(out_file* o, double v)
{
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    unsigned char b[8];
    for (int i = 0; i < 8; ++i) b[i] = (unsigned char)(u >> (8 * i));
    out_bytes(o, b, 8);
}

tg_status tg_mesh_write_obj(const tg_mesh* mesh, const char* path, tg_diag* diag)
{
    if (!mesh || !path) {
        tg__diag_set(diag, path ? path : "", 0, 0, 0, "NULL mesh or path");
        return TG_ERR_INVALID_ARGUMENT;
    }
    out_file* o = tg__alloc(&mesh->allocator, sizeof *o);
    if (!o) return TG_ERR_OUT_OF_MEMORY;
    tg_status st = out_open(o, path, diag);
    if (st != TG_OK) {
        tg__free(&mesh->allocator, o);
        return st;
    }
    static const char head[] = "# written by trigeo\n";
    out_bytes(o, head, sizeof head - 1);
    tg__c_locale loc = tg__c_locale_enter();
    for (size_t v = 0; v < mesh->vertex_count; ++v) {
        char* s = out_room(o, 128);
        size_t n = 0;
        s[n++] = 'v';
        for (int k = 0; k < 3; ++k) {
            s[n++] = ' ';
            n += format_double(s + n, 40, mesh->xyz[3 * v + (size_t)k]);
        }
        s[n++] = '\n';
        o->len += n;
    }
    tg__c_locale_leave(loc);
    for (size_t f = 0; f < mesh->face_count; ++f) {
        char* s = out_room(o, 80);
        size_t n = 0;
        s[n++] = 'f';
        for (int k = 0; k < 3; ++k) {
            s[n++] = ' ';
            n += format_u32(s + n, (uint64_t)mesh->tri[3 * f + (size_t)k] + 1);
        }
        s[n++] = '\n';
        o->len += n;
    }
    st = out_close(o, diag);
    tg__free(&mesh->allocator, o);
    return st;
}

tg_status tg_mesh_write_ply(const tg_mesh* mesh, const char* path, const tg_vertex_scalar* scalars,
                            size_t scalar_count, tg_diag* diag)
{
    if (!mesh || !path) {
        tg__diag_set(diag, path ? path : "", 0, 0, 0, "NULL mesh or path");
        return TG_ERR_INVALID_ARGUMENT;
    }
    tg_status st = check_scalars(scalars, scalar_count, path, diag);
    if (st != TG_OK) return st;
    out_file* o = tg__alloc(&mesh->allocator, sizeof *o);
    if (!o) return TG_ERR_OUT_OF_MEMORY;
    st = out_open(o, path, diag);
    if (st != TG_OK) {
        tg__free(&mesh->allocator, o);
        return st;
    }
    char line[160];
    int n = snprintf(line, sizeof line,
                     "ply\nformat binary_little_endian 1.0\ncomment written by trigeo %s\nelement vertex %zu\n"
                     "property double x\nproperty double y\nproperty double z\n",
                     tg_version(), mesh->vertex_count);
    out_bytes(o, line, (size_t)n);
    for (size_t i = 0; i < scalar_count; ++i) {
        n = snprintf(line, sizeof line, "property double %s\n", scalars[i].name);
        out_bytes(o, line, (size_t)n);
    }
    n = snprintf(line, sizeof line, "element face %zu\nproperty list uchar uint vertex_indices\nend_header\n",
                 mesh->face_count);
    out_bytes(o, line, (size_t)n);
    for (size_t v = 0; v < mesh->vertex_count; ++v) {
        for (int k = 0; k < 3; ++k) put_le_double(o, mesh->xyz[3 * v + (size_t)k]);
        for (size_t i = 0; i < scalar_count; ++i) put_le_double(o, scalars[i].values[v]);
    }
    for (size_t f = 0; f < mesh->face_count; ++f) {
        unsigned char rec[13];
        rec[0] = 3;
        for (int k = 0; k < 3; ++k) {
            uint32_t idx = mesh->tri[3 * f + (size_t)k];
            for (int b = 0; b < 4; ++b) rec[1 + 4 * k + b] = (unsigned char)(idx >> (8 * b));
        }
        out_bytes(o, rec, sizeof rec);
    }
    st = out_close(o, diag);
    tg__free(&mesh->allocator, o);
    return st;
}
