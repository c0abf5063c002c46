/* load.c - tg_mesh_load / tg_mesh_load_memory: read the file (read_file.c), inflate gzip data
 * given in memory, pick the reader, hand the soup to tg_mesh.
 * Based on: the project's STYLE.md (a clear error naming the file, line and reason). */
#include "io/io_internal.h"
#include "mesh/mesh_internal.h"

#include <ctype.h>
#include <string.h>

static bool starts_with_ci(const char* p, const char* end, const char* word)
{
    for (; *word; ++word, ++p)
        if (p >= end || tolower((unsigned char)*p) != *word) return false;
    return true;
}

/* Do the first n bytes of s end with the 4-character extension ext (".obj"), any case? */
static bool ext_before(const char* s, size_t n, const char* ext)
{
    return n >= 4 && starts_with_ci(s + n - 4, s + n, ext);
}

/* The format a name's extension (before .gz) says; TG_FORMAT_AUTO when it says none. Names of
 * any length (a copy into a fixed buffer once cut long names before their extension). */
static tg_format format_from_name(const char* name)
{
    if (name && *name) {
        size_t n = strlen(name);
        if (tg__ends_with_ci(name, ".gz")) n -= 3;
        if (ext_before(name, n, ".obj")) return TG_FORMAT_OBJ;
        if (ext_before(name, n, ".off")) return TG_FORMAT_OFF;
        if (ext_before(name, n, ".ply")) return TG_FORMAT_PLY;
        if (ext_before(name, n, ".stl")) return TG_FORMAT_STL;
    }
    return TG_FORMAT_AUTO;
}

tg_format tg__detect_format(const char* name, const char* data, size_t size)
{
    tg_format by_name = format_from_name(name);
    if (by_name != TG_FORMAT_AUTO) return by_name;
    const char* p = data;
    const char* end = data + (size < 256 ? size : 256);
    while (p < end && isspace((unsigned char)*p)) p++;
    if (starts_with_ci(p, end, "ply")) return TG_FORMAT_PLY;
    if (starts_with_ci(p, end, "solid")) return TG_FORMAT_STL;
    const char* q = p;
    while (q < end && isalpha((unsigned char)*q)) q++;
    if (q - p >= 3 && starts_with_ci(q - 3, end, "off")) return TG_FORMAT_OFF;
    if (size >= 84) {
        uint32_t n = (uint32_t)(unsigned char)data[80] | (uint32_t)(unsigned char)data[81] << 8 |
                     (uint32_t)(unsigned char)data[82] << 16 | (uint32_t)(unsigned char)data[83] << 24;
        if ((uint64_t)84 + 50 * (uint64_t)n == size) return TG_FORMAT_STL;
    }
    return TG_FORMAT_OBJ;
}

static const char* format_name(tg_format f)
{
    switch (f) {
    case TG_FORMAT_OBJ: return "OBJ";
    case TG_FORMAT_OFF: return "OFF";
    case TG_FORMAT_PLY: return "PLY";
    case TG_FORMAT_STL: return "STL";
    default: return "unknown";
    }
}

/* A UTF-8 byte-order mark (Windows tools write one before text): skipped before a text format,
 * so that the first record is read like any other. A binary STL keeps its 80-byte header whole. */
static bool has_bom(const char* data, size_t size)
{
    return size >= 3 && (unsigned char)data[0] == 0xEF && (unsigned char)data[1] == 0xBB &&
           (unsigned char)data[2] == 0xBF;
}

static tg_status parse_buffer(const char* data, size_t size, const char* name, tg_format format,
                              const tg_allocator* a, tg_diag* diag, tg_mesh** out_mesh)
{
    if (has_bom(data, size)) {
        tg_format text = format == TG_FORMAT_AUTO ? tg__detect_format(name, data + 3, size - 3) : format;
        bool binary_stl = text == TG_FORMAT_STL && size >= 84 &&
                          tg__detect_format(NULL, data, size) == TG_FORMAT_STL &&
                          !(size - 3 >= 5 && !strncmp(data + 3, "solid", 5));
        if (!binary_stl) data += 3, size -= 3, format = text;
    }
    /* OBJ chosen for want of anything recognisable (no extension, no header) */
    bool detected = format == TG_FORMAT_AUTO && format_from_name(name) == TG_FORMAT_AUTO;
    if (format == TG_FORMAT_AUTO) format = tg__detect_format(name, data, size);
    tg__reader_fn reader = format == TG_FORMAT_OBJ ? tg__read_obj
                         : format == TG_FORMAT_OFF ? tg__read_off
                         : format == TG_FORMAT_PLY ? tg__read_ply
                         : format == TG_FORMAT_STL ? tg__read_stl
                                                   : NULL;
    if (!reader) {
        tg__diag_set(diag, name, 0, 0, 0, "unknown mesh format");
        return TG_ERR_UNSUPPORTED;
    }
    if (size == 0) {
        tg__diag_set(diag, name, 1, 1, 0, "empty file (expected %s)", format_name(format));
        return TG_ERR_PARSE;
    }
    tg__soup soup = {NULL, 0, NULL, 0};
    tg_status st = reader(data, size, name, a, diag, &soup);
    if (st != TG_OK) return st;
    if (soup.face_count == 0) {
        tg__free(a, soup.xyz);
        tg__free(a, soup.tri);
        /* text formats get the line of the end of the data; binary ones only the offset */
        bool text = format == TG_FORMAT_OBJ || format == TG_FORMAT_OFF;
        if (format == TG_FORMAT_OBJ && soup.vertex_count == 0) /* OBJ is also what unrecognised data is read as */
            return tg__io_fail(diag, name, data, size, TG_ERR_PARSE,
                               "not a mesh: no 'v' or 'f' statement of OBJ%s",
                               detected ? ", and no OFF, PLY or STL header either" : "");
        return tg__io_fail(diag, name, text ? data : NULL, size, TG_ERR_PARSE, "%s data has %zu vertices but no faces",
                           format_name(format), soup.vertex_count);
    }
    return tg__mesh_create_owned(soup.xyz, soup.vertex_count, soup.tri, soup.face_count, a, name,
                                 diag, out_mesh);
}

tg_status tg_mesh_load(const char* path, tg_format format, const tg_mesh_options* options,
                       tg_diag* diag, tg_mesh** out_mesh)
{
    if (!out_mesh) return TG_ERR_INVALID_ARGUMENT;
    *out_mesh = NULL;
    if (!path) return TG_ERR_INVALID_ARGUMENT;
    tg__diag_clear(diag, path);
    const tg_allocator* a = options ? options->allocator : NULL;
    char* data;
    size_t size;
    tg_status st = tg__read_file(path, a, diag, &data, &size);
    if (st != TG_OK) return st;
    st = parse_buffer(data, size, path, format, a, diag, out_mesh);
    tg__free(a, data);
    return st;
}

tg_status tg_mesh_load_memory(const void* data, size_t size, const char* name, tg_format format,
                              const tg_mesh_options* options, tg_diag* diag, tg_mesh** out_mesh)
{
    if (!out_mesh) return TG_ERR_INVALID_ARGUMENT;
    *out_mesh = NULL;
    if (!data && size) return TG_ERR_INVALID_ARGUMENT;
    if (!name) name = "";
    tg__diag_clear(diag, name);
    const tg_allocator* a = options ? options->allocator : NULL;
    char* buf = NULL;
    tg_status st = TG_OK;
    if (tg__gzip_magic(data, size)) { /* gzip data (a .gz file piped in): inflated first */
        st = tg__inflate_memory(data, size, name, a, diag, &buf, &size);
        if (st != TG_OK) return st;
    } else { /* copy to guarantee the '\0' terminator every reader relies on */
        buf = tg__alloc(a, size + 1);
        if (!buf) return TG_ERR_OUT_OF_MEMORY;
        if (size) memcpy(buf, data, size);
        buf[size] = '\0';
    }
    st = parse_buffer(buf, size, name, format, a, diag, out_mesh);
    tg__free(a, buf);
    return st;
}
