/* cli_npz.c - a sparse matrix as the .npz file scipy.sparse.load_npz reads: a zip archive of five
 * NumPy arrays (format 'csr', shape, indptr, indices, data), stored without compression; each
 * array's .npy header from cli_npy.c.
 * Based on: the .ZIP File Format Specification (PKWARE APPNOTE 6.3.x: local headers, central
 *   directory, Zip64 extra fields and end records, §4.3-4.5); SciPy's save_npz layout (the names
 *   and dtypes of the five arrays). */
#include "cli.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

/* One array of the archive: its .npy header, then `count` elements of `size` bytes from `at`
 * (widened or copied to little-endian by `put`). */
typedef struct npz_entry {
    const char* name;
    char header[256];
    size_t header_len;
    const void* at;
    uint64_t count;
    unsigned size;
    void (*put)(const void* at, uint64_t i, unsigned char* out);
    uint32_t crc;
    uint64_t offset; /* of its local header */
} npz_entry;

static void put_le(unsigned char* out, uint64_t v, unsigned bytes)
{
    for (unsigned k = 0; k < bytes; ++k) out[k] = (unsigned char)(v >> (8 * k));
}

static void put_u64(const void* at, uint64_t i, unsigned char* out)
{
    put_le(out, ((const uint64_t*)at)[i], 8);
}

static void put_u32_as_i32(const void* at, uint64_t i, unsigned char* out)
{
    put_le(out, ((const uint32_t*)at)[i], 4);
}

static void put_u32_as_i64(const void* at, uint64_t i, unsigned char* out)
{
    put_le(out, ((const uint32_t*)at)[i], 8);
}

static void put_f64(const void* at, uint64_t i, unsigned char* out)
{
    uint64_t bits;
    memcpy(&bits, (const double*)at + i, 8);
    put_le(out, bits, 8);
}

static void put_bytes(const void* at, uint64_t i, unsigned char* out)
{
    out[0] = ((const unsigned char*)at)[i];
}

static uint64_t entry_size(const npz_entry* e)
{
    return e->header_len + e->count * e->size;
}

/* The entry's bytes, a buffer at a time: to f when f is set, always into the CRC. */
static bool entry_stream(npz_entry* e, FILE* f)
{
    unsigned char buf[1 << 16];
    uLong crc = crc32(0L, Z_NULL, 0);
    crc = crc32(crc, (const Bytef*)e->header, (uInt)e->header_len);
    if (f && fwrite(e->header, 1, e->header_len, f) != e->header_len) return false;
    uint64_t per = sizeof buf / e->size;
    for (uint64_t i = 0; i < e->count; i += per) {
        uint64_t n = e->count - i < per ? e->count - i : per;
        for (uint64_t k = 0; k < n; ++k) e->put(e->at, i + k, buf + k * e->size);
        size_t bytes = (size_t)(n * e->size);
        crc = crc32(crc, buf, (uInt)bytes);
        if (f && fwrite(buf, 1, bytes, f) != bytes) return false;
    }
    e->crc = (uint32_t)crc;
    return true;
}

/* The entry's .npy header (cli_npy_header) for `ndim` dimensions dims. */
static bool npy_header(npz_entry* e, const char* descr, int ndim, const unsigned long long* dims)
{
    e->header_len = cli_npy_header(e->header, sizeof e->header, descr, ndim, dims);
    return e->header_len != 0;
}

/* Every size and offset goes in Zip64 fields (the 32-bit ones say 0xFFFFFFFF), so one layout
 * serves archives of any size, and the path that large matrices take is the one every test
 * takes. Time and date: 1980-01-01 00:00, so the same matrix gives the same bytes. */
static bool local_header(FILE* f, const npz_entry* e)
{
    unsigned char h[30 + 16 + 20];
    size_t name_len = strlen(e->name);
    put_le(h, 0x04034b50u, 4);
    put_le(h + 4, 45, 2);   /* version needed: 4.5 (Zip64) */
    put_le(h + 6, 0, 2);    /* flags */
    put_le(h + 8, 0, 2);    /* stored */
    put_le(h + 10, 0, 2);   /* time */
    put_le(h + 12, 0x21, 2); /* date 1980-01-01 */
    put_le(h + 14, e->crc, 4);
    put_le(h + 18, 0xFFFFFFFFu, 4);
    put_le(h + 22, 0xFFFFFFFFu, 4);
    put_le(h + 26, name_len, 2);
    put_le(h + 28, 20, 2);  /* extra length */
    if (fwrite(h, 1, 30, f) != 30 || fwrite(e->name, 1, name_len, f) != name_len) return false;
    put_le(h, 0x0001, 2), put_le(h + 2, 16, 2);
    put_le(h + 4, entry_size(e), 8), put_le(h + 12, entry_size(e), 8);
    return fwrite(h, 1, 20, f) == 20;
}

static bool central_header(FILE* f, const npz_entry* e)
{
    unsigned char h[46];
    size_t name_len = strlen(e->name);
    put_le(h, 0x02014b50u, 4);
    put_le(h + 4, 45, 2), put_le(h + 6, 45, 2);
    put_le(h + 8, 0, 2), put_le(h + 10, 0, 2), put_le(h + 12, 0, 2), put_le(h + 14, 0x21, 2);
    put_le(h + 16, e->crc, 4);
    put_le(h + 20, 0xFFFFFFFFu, 4), put_le(h + 24, 0xFFFFFFFFu, 4);
    put_le(h + 28, name_len, 2), put_le(h + 30, 28, 2), put_le(h + 32, 0, 2);
    put_le(h + 34, 0, 2), put_le(h + 36, 0, 2), put_le(h + 38, 0, 4);
    put_le(h + 42, 0xFFFFFFFFu, 4);
    if (fwrite(h, 1, 46, f) != 46 || fwrite(e->name, 1, name_len, f) != name_len) return false;
    unsigned char x[28];
    put_le(x, 0x0001, 2), put_le(x + 2, 24, 2);
    put_le(x + 4, entry_size(e), 8), put_le(x + 12, entry_size(e), 8), put_le(x + 20, e->offset, 8);
    return fwrite(x, 1, 28, f) == 28;
}

static bool end_records(FILE* f, uint64_t entries, uint64_t cd_offset, uint64_t cd_size)
{
    unsigned char z[56 + 20 + 22];
    put_le(z, 0x06064b50u, 4), put_le(z + 4, 44, 8);
    put_le(z + 12, 45, 2), put_le(z + 14, 45, 2), put_le(z + 16, 0, 4), put_le(z + 20, 0, 4);
    put_le(z + 24, entries, 8), put_le(z + 32, entries, 8), put_le(z + 40, cd_size, 8), put_le(z + 48, cd_offset, 8);
    unsigned char* l = z + 56; /* the Zip64 end record's locator */
    put_le(l, 0x07064b50u, 4), put_le(l + 4, 0, 4), put_le(l + 8, cd_offset + cd_size, 8), put_le(l + 16, 1, 4);
    unsigned char* e = l + 20;
    put_le(e, 0x06054b50u, 4), put_le(e + 4, 0, 2), put_le(e + 6, 0, 2);
    put_le(e + 8, 0xFFFF, 2), put_le(e + 10, 0xFFFF, 2);
    put_le(e + 12, 0xFFFFFFFFu, 4), put_le(e + 16, 0xFFFFFFFFu, 4), put_le(e + 20, 0, 2);
    return fwrite(z, 1, sizeof z, f) == sizeof z;
}

bool cli_write_npz_csr(FILE* f, const tg_sparse_matrix_view* v)
{
    static const char format[3] = {'c', 's', 'r'};
    uint64_t shape[2] = {v->row_count, v->col_count};
    bool wide = v->col_count > INT32_MAX; /* columns that int32 cannot hold */
    const unsigned long long two = 2, rows1 = (unsigned long long)v->row_count + 1, entries = v->entry_count;
    npz_entry e[5] = {
        {"format.npy", {0}, 0, format, 3, 1, put_bytes, 0, 0},
        {"shape.npy", {0}, 0, shape, 2, 8, put_u64, 0, 0},
        {"indptr.npy", {0}, 0, v->row_start, v->row_count + 1, 8, put_u64, 0, 0},
        {"indices.npy", {0}, 0, v->col, v->entry_count, wide ? 8 : 4, wide ? put_u32_as_i64 : put_u32_as_i32, 0, 0},
        {"data.npy", {0}, 0, v->value, v->entry_count, 8, put_f64, 0, 0},
    };
    if (!npy_header(&e[0], "'|S3'", 0, NULL) /* one 3-byte string, written as 3 single bytes */
        || !npy_header(&e[1], "'<i8'", 1, &two) || !npy_header(&e[2], "'<i8'", 1, &rows1)
        || !npy_header(&e[3], wide ? "'<i8'" : "'<i4'", 1, &entries) || !npy_header(&e[4], "'<f8'", 1, &entries))
        return false;
    uint64_t at = 0;
    for (int i = 0; i < 5; ++i) {
        if (!entry_stream(&e[i], NULL)) return false; /* the CRC first: it precedes the data */
        e[i].offset = at;
        if (!local_header(f, &e[i]) || !entry_stream(&e[i], f)) return false;
        at += 30 + strlen(e[i].name) + 20 + entry_size(&e[i]);
    }
    uint64_t cd = at;
    for (int i = 0; i < 5; ++i) {
        if (!central_header(f, &e[i])) return false;
        at += 46 + strlen(e[i].name) + 28;
    }
    return end_records(f, 5, cd, at - cd);
}
