/* cli_npy.c - the NumPy .npy framing, written and read in one place: the magic string, the format
 * version, the header length, the header dict ('descr', 'fortran_order', 'shape') padded so that the
 * data starts at a multiple of 64 bytes. The CLI's .npy outputs (field, logmap, closest), the arrays
 * inside a .npz matrix (cli_npz.c) and the .npy query points of `trigeo closest` all go through it.
 * Based on: the NPY format versions 1.0, 2.0 and 3.0 (NumPy Enhancement Proposal 1 and
 * numpy.lib.format: version 1.0 has a 2-byte little-endian header length, 2.0 and 3.0 a 4-byte one;
 * the header ends with '\n' and is padded with blanks to a multiple of 64 bytes). */
#include "cli.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ---- writing ---- */

size_t cli_npy_header(char* out, size_t cap, const char* descr, int ndim, const unsigned long long* dims)
{
    /* the shape as NumPy writes a tuple: (), (n,), (a, b), ... */
    char shape[8 + 22 * CLI_NPY_DIMS_MAX];
    size_t s = 0;
    if (ndim < 0 || ndim > CLI_NPY_DIMS_MAX) return 0;
    shape[s++] = '(';
    for (int i = 0; i < ndim; ++i)
        s += (size_t)snprintf(shape + s, sizeof shape - s, i ? ", %llu" : "%llu", dims[i]);
    if (ndim == 1) shape[s++] = ',';
    shape[s++] = ')';
    shape[s] = '\0';
    /* magic (6) + version 1.0 (2) + header length (2) + the dict padded with blanks and a newline
     * to a multiple of 64 bytes, so that the data is aligned */
    if (cap < 11) return 0;
    int n = snprintf(out + 10, cap - 10, "{'descr': %s, 'fortran_order': False, 'shape': %s, }", descr, shape);
    if (n < 0 || (size_t)n >= cap - 10) return 0;
    size_t len = (size_t)n, pad = (64 - (10 + len + 1) % 64) % 64, hlen = len + pad + 1;
    if (hlen > 65535 || 10 + hlen > cap) return 0;
    static const unsigned char pre[8] = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0};
    memcpy(out, pre, 8);
    ((unsigned char*)out)[8] = (unsigned char)(hlen & 0xFF);
    ((unsigned char*)out)[9] = (unsigned char)(hlen >> 8);
    memset(out + 10 + len, ' ', pad);
    out[10 + len + pad] = '\n';
    return 10 + hlen;
}

bool cli_npy_write_header(FILE* f, const char* descr, int ndim, const unsigned long long* dims)
{
    char h[CLI_NPY_HEADER_MAX];
    size_t n = cli_npy_header(h, sizeof h, descr, ndim, dims);
    return n && fwrite(h, 1, n, f) == n;
}

bool cli_write_npy_f64(FILE* f, const double* data, size_t rows, size_t cols, bool matrix)
{
    const unsigned long long dims[2] = {matrix ? rows : cols, cols};
    if (!cli_npy_write_header(f, "'<f8'", matrix ? 2 : 1, dims)) return false;
    size_t n = rows * cols;
    for (size_t i = 0; i < n; ++i) {
        uint64_t bits;
        memcpy(&bits, &data[i], sizeof bits);
        unsigned char b[8];
        for (int k = 0; k < 8; ++k) b[k] = (unsigned char)(bits >> (8 * k)); /* little endian */
        if (fwrite(b, 1, 8, f) != 8) return false;
    }
    return true;
}

/* ---- reading ---- */

bool cli_is_npy(const char* data, size_t size) { return size >= 6 && !memcmp(data, "\x93NUMPY", 6); }

/* The value of key `key` in a .npy header dict (text of `len` bytes): a pointer just past
 * "'key':" and blanks, or NULL. */
static const char* npy_value(const char* dict, size_t len, const char* key)
{
    size_t k = strlen(key);
    for (size_t i = 0; i + k + 2 < len; ++i) {
        if (dict[i] != '\'' || memcmp(dict + i + 1, key, k) || dict[i + 1 + k] != '\'') continue;
        const char* p = dict + i + k + 2;
        while (p < dict + len && *p == ' ') ++p;
        if (p >= dict + len || *p != ':') return NULL;
        ++p;
        while (p < dict + len && *p == ' ') ++p;
        return p;
    }
    return NULL;
}

/* The shape tuple at info->shape, "(a, b, ...)" with blanks and a trailing comma allowed, into
 * info->ndim and info->dims; ndim -1 when it is not a tuple of at most CLI_NPY_DIMS_MAX
 * non-negative integers. */
static void npy_shape(cli_npy_info* info)
{
    const char* p = info->shape;
    const char* close = memchr(p, ')', (size_t)(info->dict + info->dict_len - p));
    info->shape_len = close ? (size_t)(close - p + 1) : 0;
    info->ndim = -1;
    if (*p != '(' || !close) return;
    ++p;
    int ndim = 0;
    while (*p == ' ') ++p;
    while (p != close) {
        if (ndim == CLI_NPY_DIMS_MAX || !(*p >= '0' && *p <= '9')) return;
        char* e;
        info->dims[ndim++] = strtoull(p, &e, 10);
        p = e;
        while (*p == ' ') ++p;
        if (p == close) break;
        if (*p != ',') return;
        ++p;
        while (*p == ' ') ++p;
    }
    info->ndim = ndim;
}

bool cli_npy_read_header(const char* name, const char* data, size_t size, cli_npy_info* info)
{
    const unsigned char* u = (const unsigned char*)data;
    if (!cli_is_npy(data, size) || size < 10) {
        cli_error(name, 0, ".npy: not a NumPy file (no \\x93NUMPY magic)");
        return false;
    }
    size_t hlen, start;
    if (u[6] == 1) {
        hlen = (size_t)u[8] | (size_t)u[9] << 8;
        start = 10;
    } else if ((u[6] == 2 || u[6] == 3) && size >= 12) {
        hlen = (size_t)u[8] | (size_t)u[9] << 8 | (size_t)u[10] << 16 | (size_t)u[11] << 24;
        start = 12;
    } else {
        cli_error(name, 0, ".npy: unsupported format version %u.%u (1.0, 2.0 and 3.0 are read)", u[6], size > 7 ? u[7] : 0);
        return false;
    }
    if (hlen > size - start) {
        cli_error(name, 0, ".npy: truncated header (%zu bytes announced, %zu in the file)", hlen, size - start);
        return false;
    }
    const char* dict = data + start;
    if (!hlen || dict[0] != '{' || !memchr(dict, '}', hlen)) {
        cli_error(name, 0, ".npy: the header is not a dictionary");
        return false;
    }
    info->dict = dict;
    info->dict_len = hlen;
    info->data_offset = start + hlen;
    info->descr = npy_value(dict, hlen, "descr");
    const char* order = npy_value(dict, hlen, "fortran_order");
    info->shape = npy_value(dict, hlen, "shape");
    if (!info->descr || !order || !info->shape) {
        cli_error(name, 0, ".npy: the header lacks '%s'", !info->descr ? "descr" : !order ? "fortran_order" : "shape");
        return false;
    }
    info->fortran_order = !strncmp(order, "True", 4);
    if (!info->fortran_order && strncmp(order, "False", 5)) {
        cli_error(name, 0, ".npy: fortran_order is neither True nor False");
        return false;
    }
    npy_shape(info);
    return true;
}

size_t cli_read_npy_points(const char* name, const char* data, size_t size, double** out)
{
    cli_npy_info h;
    if (!cli_npy_read_header(name, data, size, &h)) return (size_t)-1;
    /* float64 or float32, either byte order: converted exactly to double */
    const char* descr = h.descr;
    bool big = descr[0] == '\'' && descr[1] == '>';
    size_t item = !strncmp(descr + 1, big ? ">f8'" : "<f8'", 4)   ? 8
                  : !strncmp(descr + 1, big ? ">f4'" : "<f4'", 4) ? 4
                                                                  : 0;
    if (!item) {
        const char* end = memchr(descr, ',', (size_t)(h.dict + h.dict_len - descr));
        cli_error(name, 0, ".npy: dtype %.*s, expected float64 or float32 ('<f8', '>f8', '<f4' or '>f4')",
                  (int)(end ? end - descr : 20), descr);
        return (size_t)-1;
    }
    /* shape: (k, 3) with k a non-negative integer */
    if (h.ndim != 2 || h.dims[1] != 3) {
        cli_error(name, 0, ".npy: shape %.*s, expected (k, 3): one point (x, y, z) a row", h.shape_len ? (int)h.shape_len : 12,
                  h.shape);
        return (size_t)-1;
    }
    unsigned long long k = h.dims[0];
    size_t body = size - h.data_offset, row = 3 * item;
    if (k > (size_t)-1 / 24 / 2 || body != row * (size_t)k) {
        if (body < row * k)
            cli_error(name, 0, ".npy: truncated data: %zu bytes for shape (%llu, 3), expected %llu", body, k, row * k);
        else
            cli_error(name, 0, ".npy: %zu bytes after the data of shape (%llu, 3)", body - row * (size_t)k, k);
        return (size_t)-1;
    }
    double* xyz = malloc(24 * (size_t)k + 8);
    if (!xyz) {
        cli_error(name, 0, "out of memory");
        return (size_t)-1;
    }
    const unsigned char* b = (const unsigned char*)data + h.data_offset;
    for (size_t i = 0; i < 3 * (size_t)k; ++i) {
        /* point i / 3, coordinate i % 3: C order stores rows, Fortran order the three columns */
        size_t at = h.fortran_order ? (i % 3) * (size_t)k + i / 3 : i;
        uint64_t bits = 0;
        for (size_t j = 0; j < item; ++j) bits |= (uint64_t)b[item * at + (big ? item - 1 - j : j)] << (8 * j);
        if (item == 8) {
            memcpy(&xyz[i], &bits, sizeof bits);
        } else {
            uint32_t bits32 = (uint32_t)bits;
            float x32;
            memcpy(&x32, &bits32, sizeof x32);
            xyz[i] = (double)x32; /* exact: every float is a double */
        }
        if (!isfinite(xyz[i]) || fabs(xyz[i]) > 1e150) {
            cli_error(name, 0, ".npy: row %zu (from 0), %c is %s: not finite or beyond +-1e150", i / 3, "xyz"[i % 3],
                      cli_num(xyz[i]).s);
            free(xyz);
            return (size_t)-1;
        }
    }
    *out = xyz;
    return (size_t)k;
}
