/* io_internal.h - the contract between the loader (load.c), the file reading (read_file.c), the
 * per-format readers and what they share (reader_util.c).
 * Based on: the project's STYLE.md (validate everything from outside; no allocation sized by an
 * untrusted count before it is checked against the data size). */
#ifndef TG_IO_INTERNAL_H
#define TG_IO_INTERNAL_H

#include "core/core.h"

/* What a reader produces: a triangle soup in file order. Arrays are allocated with the
 * allocator given to the reader; on failure the reader frees them and leaves NULL. */
typedef struct tg__soup {
    double* xyz;
    size_t vertex_count;
    uint32_t* tri;
    size_t face_count;
} tg__soup;

/* Every reader: data[size] is readable and is '\0' (the loader guarantees a terminator, so
 * strtod-style scanning can never run past the buffer). name is for diagnostics. */
typedef tg_status (*tg__reader_fn)(const char* data, size_t size, const char* name,
                                   const tg_allocator* a, tg_diag* diag, tg__soup* out);

tg_status tg__read_obj(const char* data, size_t size, const char* name, const tg_allocator* a,
                       tg_diag* diag, tg__soup* out);
tg_status tg__read_off(const char* data, size_t size, const char* name, const tg_allocator* a,
                       tg_diag* diag, tg__soup* out);
tg_status tg__read_ply(const char* data, size_t size, const char* name, const tg_allocator* a,
                       tg_diag* diag, tg__soup* out);
tg_status tg__read_stl(const char* data, size_t size, const char* name, const tg_allocator* a,
                       tg_diag* diag, tg__soup* out);

/* Reads a whole file (decompressing .gz / gzip magic with zlib) into a '\0'-terminated buffer
 * allocated with a. */
tg_status tg__read_file(const char* path, const tg_allocator* a, tg_diag* diag, char** out_data,
                        size_t* out_size);

/* Whether s ends with suffix, ignoring ASCII case. */
bool tg__ends_with_ci(const char* s, const char* suffix);
/* Whether data starts with the gzip magic bytes. */
bool tg__gzip_magic(const char* data, size_t size);
/* Inflates gzip data held in memory (one member or several concatenated) under the limits of
 * tg__read_file. *out_data: '\0'-terminated, allocated with a. */
tg_status tg__inflate_memory(const char* data, size_t size, const char* name, const tg_allocator* a,
                             tg_diag* diag, char** out_data, size_t* out_size);

/* Format from the name's extension (before .gz), else sniffed from the content. */
tg_format tg__detect_format(const char* name, const char* data, size_t size);

/* Appends triangles (a, p[k], p[k+1]) of a polygon fan to the soup's triangle vector. */
bool tg__fan_push(const tg_allocator* a, tg__vec* tris, const uint32_t* poly, size_t corners);

/* 1-based line and column of byte offset `off` in text data (for diagnostics on error paths). */
void tg__line_col(const char* data, size_t off, uint64_t* line, uint64_t* col);

/* Records a reader failure at byte offset `off` and returns `status`. With text != NULL the
 * offset is in text data and line/column are computed from it (O(off), error paths only); with
 * text == NULL the data is binary and only the byte offset is set. */
tg_status tg__io_fail(tg_diag* diag, const char* name, const char* text, size_t off, tg_status status,
                      const char* fmt, ...) TG_PRINTF(6, 7);
/* The same with a va_list, for the readers' own printf-style failure helpers. */
tg_status tg__io_vfail(tg_diag* diag, const char* name, const char* text, size_t off, tg_status status,
                       const char* fmt, va_list ap);

/* Whitespace of the token-based text formats (OFF, PLY ascii, STL ascii): blank, \t, \n, \v,
 * \f, \r. '\0' is not whitespace, so a terminator or embedded NUL ends every token scan. */
static inline bool tg__is_space(char c) { return c == ' ' || (unsigned)(c - '\t') <= 4u; }
static inline bool tg__is_eol(char c) { return c == '\n' || c == '\r'; }

#endif
