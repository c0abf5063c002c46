/* reader_util.c - what the format readers share: polygon fans and failures named by file, line,
 * column or byte offset.
 * Based on: the project's STYLE.md (parsers fill tg_diag with file, line, column and a sentence). */
#include "io/io_internal.h"

void tg__line_col(const char* data, size_t off, uint64_t* line, uint64_t* col)
{
    uint64_t l = 1;
    size_t start = 0;
    for (size_t i = 0; i < off; ++i) {
        if (data[i] == '\n' || (data[i] == '\r' && data[i + 1] != '\n')) {
            l++;
            start = i + 1;
        }
    }
    *line = l;
    *col = off - start + 1;
}

tg_status tg__io_vfail(tg_diag* diag, const char* name, const char* text, size_t off, tg_status status,
                       const char* fmt, va_list ap)
{
    uint64_t line = 0, col = 0;
    if (text) tg__line_col(text, off, &line, &col);
    tg__diag_vset(diag, name, line, col, off, fmt, ap);
    return status;
}

tg_status tg__io_fail(tg_diag* diag, const char* name, const char* text, size_t off, tg_status status,
                      const char* fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    tg__io_vfail(diag, name, text, off, status, fmt, ap);
    va_end(ap);
    return status;
}

bool tg__fan_push(const tg_allocator* a, tg__vec* tris, const uint32_t* poly, size_t corners)
{
    if (corners < 3) return true;
    if (!tg__vec_reserve(a, tris, 3 * (corners - 2))) return false;
    uint32_t* t = (uint32_t*)tris->data + tris->count;
    for (size_t k = 1; k + 1 < corners; ++k) {
        *t++ = poly[0];
        *t++ = poly[k];
        *t++ = poly[k + 1];
    }
    tris->count += 3 * (corners - 2);
    return true;
}
