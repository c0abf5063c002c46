/* read_file.c - the bytes of a mesh file: whole files (zlib for .gz; pipes and files whose size
 * the system does not know, such as /proc's, to their end; devices refused) and gzip data held
 * in memory, under limits that refuse gzip bombs early.
 * Based on: zlib's gzread interface (reads plain files too) and its inflate interface with
 * windowBits 15 + 32 (zlib or gzip header detected; RFC 1952 members may be concatenated). */
#define _POSIX_C_SOURCE 200809L /* fileno, fstat, S_ISSOCK */
#include "io/io_internal.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <zlib.h>

/* Decompressed inputs larger than this are refused: halfedge ids are 32-bit, so no usable mesh
 * needs more than a few GiB of text, and a gzip bomb must not exhaust memory. */
#define TG_MAX_INPUT_BYTES ((size_t)8 << 30)
/* A gzip stream that expands more than this many times (beyond the first 64 MiB) is refused as
 * it is read: mesh files compress 3-12x (the corpus's .gz files: 3.4-11.4x), while runs of zeros,
 * what a gzip bomb is made of, expand about 1000x. So a bomb is refused after ~100 KB of input
 * and ~70 MB of output, not after 8 GiB. */
#define TG_MAX_GZIP_RATIO 200
#define TG_GZIP_RATIO_SLACK ((size_t)64 << 20)

bool tg__ends_with_ci(const char* s, const char* suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    if (k > n) return false;
    for (size_t i = 0; i < k; ++i)
        if (tolower((unsigned char)s[n - k + i]) != tolower((unsigned char)suffix[i])) return false;
    return true;
}

static tg_status read_gz(const char* path, const tg_allocator* a, tg_diag* diag, char** out_data,
                         size_t* out_size)
{
    gzFile gz = gzopen(path, "rb");
    if (!gz) {
        tg__diag_set(diag, path, 0, 0, 0, "cannot open: %s", strerror(errno));
        return TG_ERR_IO;
    }
    tg__vec buf = {NULL, 0, 0, 1, 0, 0};
    tg_status st = TG_OK;
    for (;;) {
        if (!tg__vec_reserve(a, &buf, (size_t)1 << 20)) {
            st = TG_ERR_OUT_OF_MEMORY;
            break;
        }
        size_t room = buf.capacity - buf.count - 1;
        if (room > (16u << 20)) room = 16u << 20; /* small steps: the ratio is checked between them */
        int n = gzread(gz, (char*)buf.data + buf.count, (unsigned)room);
        if (n < 0) {
            int zerr;
            const char* msg = gzerror(gz, &zerr);
            tg__diag_set(diag, path, 0, 0, buf.count, "corrupt gzip data: %s", msg ? msg : "unknown error");
            st = TG_ERR_PARSE;
            break;
        }
        if (n == 0) {
            int zerr = Z_OK;
            gzerror(gz, &zerr);
            if (zerr == Z_BUF_ERROR) { /* the input ended inside a gzip stream */
                tg__diag_set(diag, path, 0, 0, buf.count,
                             "truncated gzip data: the file ends inside the compressed stream (after %zu bytes)",
                             buf.count);
                st = TG_ERR_PARSE;
            }
            break;
        }
        buf.count += (size_t)n;
        z_off_t in = gzoffset(gz);
        if (in >= 0 && buf.count > TG_GZIP_RATIO_SLACK &&
            buf.count / TG_MAX_GZIP_RATIO > (size_t)in) {
            tg__diag_set(diag, path, 0, 0, buf.count,
                         "gzip data expands more than %dx (%zu bytes from %lld): not a mesh (a gzip bomb?)",
                         TG_MAX_GZIP_RATIO, buf.count, (long long)in);
            st = TG_ERR_UNSUPPORTED;
            break;
        }
        if (buf.count > TG_MAX_INPUT_BYTES) {
            tg__diag_set(diag, path, 0, 0, buf.count, "decompressed data exceeds %zu bytes", TG_MAX_INPUT_BYTES);
            st = TG_ERR_UNSUPPORTED;
            break;
        }
    }
    gzclose(gz);
    if (st != TG_OK) {
        tg__vec_free(a, &buf);
        return st;
    }
    if (!tg__vec_reserve(a, &buf, 1)) {
        tg__vec_free(a, &buf);
        return TG_ERR_OUT_OF_MEMORY;
    }
    ((char*)buf.data)[buf.count] = '\0';
    *out_data = buf.data;
    *out_size = buf.count;
    return TG_OK;
}

bool tg__gzip_magic(const char* data, size_t size)
{
    return size >= 2 && (unsigned char)data[0] == 0x1f && (unsigned char)data[1] == 0x8b;
}

/* Inflates gzip data held in memory (one member or several concatenated, as gzread reads them;
 * bytes after the last member that do not start another are ignored, as gzread does) under the
 * same limits as read_gz. *out_data: '\0'-terminated, allocated with a. */
tg_status tg__inflate_memory(const char* data, size_t size, const char* name, const tg_allocator* a,
                             tg_diag* diag, char** out_data, size_t* out_size)
{
    z_stream z;
    memset(&z, 0, sizeof z);
    if (inflateInit2(&z, 15 + 32) != Z_OK) {
        tg__diag_set(diag, name, 0, 0, 0, "out of memory for gzip decompression");
        return TG_ERR_OUT_OF_MEMORY;
    }
    tg__vec buf = {NULL, 0, 0, 1, 0, 0};
    size_t in = 0; /* input bytes consumed */
    tg_status st = TG_OK;
    for (;;) {
        if (!tg__vec_reserve(a, &buf, (size_t)1 << 20)) {
            st = TG_ERR_OUT_OF_MEMORY;
            break;
        }
        size_t room = buf.capacity - buf.count - 1, left = size - in;
        z.next_in = (Bytef*)(uintptr_t)(data + in);
        z.avail_in = (uInt)(left < (1u << 30) ? left : (1u << 30));
        z.next_out = (Bytef*)buf.data + buf.count;
        z.avail_out = (uInt)(room < (16u << 20) ? room : (16u << 20));
        uInt avail_in = z.avail_in, avail_out = z.avail_out;
        int ret = inflate(&z, Z_NO_FLUSH);
        in += avail_in - z.avail_in;
        buf.count += avail_out - z.avail_out;
        if (ret == Z_STREAM_END) {
            if (!tg__gzip_magic(data + in, size - in)) break; /* the end, or trailing bytes gzread skips too */
            inflateReset(&z);                              /* another member follows */
            continue;
        }
        if (ret == Z_BUF_ERROR && in == size) {
            tg__diag_set(diag, name, 0, 0, buf.count,
                         "truncated gzip data: the data ends inside the compressed stream (after %zu bytes)", buf.count);
            st = TG_ERR_PARSE;
            break;
        }
        if (ret != Z_OK && ret != Z_BUF_ERROR) {
            tg__diag_set(diag, name, 0, 0, buf.count, "corrupt gzip data: %s", z.msg ? z.msg : "unknown error");
            st = ret == Z_MEM_ERROR ? TG_ERR_OUT_OF_MEMORY : TG_ERR_PARSE;
            break;
        }
        if (buf.count > TG_GZIP_RATIO_SLACK && buf.count / TG_MAX_GZIP_RATIO > in) {
            tg__diag_set(diag, name, 0, 0, buf.count,
                         "gzip data expands more than %dx (%zu bytes from %zu): not a mesh (a gzip bomb?)",
                         TG_MAX_GZIP_RATIO, buf.count, in);
            st = TG_ERR_UNSUPPORTED;
            break;
        }
        if (buf.count > TG_MAX_INPUT_BYTES) {
            tg__diag_set(diag, name, 0, 0, buf.count, "decompressed data exceeds %zu bytes", TG_MAX_INPUT_BYTES);
            st = TG_ERR_UNSUPPORTED;
            break;
        }
    }
    inflateEnd(&z);
    if (st == TG_OK && !tg__vec_reserve(a, &buf, 1)) st = TG_ERR_OUT_OF_MEMORY;
    if (st != TG_OK) {
        if (st == TG_ERR_OUT_OF_MEMORY) tg__diag_set(diag, name, 0, 0, buf.count, "out of memory decompressing gzip data");
        tg__vec_free(a, &buf);
        return st;
    }
    ((char*)buf.data)[buf.count] = '\0';
    *out_data = buf.data;
    *out_size = buf.count;
    return TG_OK;
}

/* Reads an open stream to its end (a pipe, or a file whose size the system reports as 0, like
 * those of /proc), then inflates it if it is gzip data. */
static tg_status read_stream(FILE* f, const char* path, const tg_allocator* a, tg_diag* diag, char** out_data,
                             size_t* out_size)
{
    tg__vec buf = {NULL, 0, 0, 1, 0, 0};
    tg_status st = TG_OK;
    for (;;) {
        if (!tg__vec_reserve(a, &buf, (size_t)1 << 16)) {
            st = TG_ERR_OUT_OF_MEMORY;
            tg__diag_set(diag, path, 0, 0, buf.count, "out of memory reading the data (%zu bytes so far)", buf.count);
            break;
        }
        size_t got = fread((char*)buf.data + buf.count, 1, buf.capacity - buf.count - 1, f);
        buf.count += got;
        if (got == 0) {
            if (ferror(f)) {
                tg__diag_set(diag, path, 0, 0, buf.count, "read error after %zu bytes: %s", buf.count, strerror(errno));
                st = TG_ERR_IO;
            }
            break;
        }
        if (buf.count > TG_MAX_INPUT_BYTES) {
            tg__diag_set(diag, path, 0, 0, buf.count, "the data exceeds %zu bytes: not a mesh file", TG_MAX_INPUT_BYTES);
            st = TG_ERR_UNSUPPORTED;
            break;
        }
    }
    fclose(f);
    if (st != TG_OK) {
        tg__vec_free(a, &buf);
        return st;
    }
    if (tg__gzip_magic(buf.data, buf.count)) {
        st = tg__inflate_memory(buf.data, buf.count, path, a, diag, out_data, out_size);
        tg__vec_free(a, &buf);
        return st;
    }
    ((char*)buf.data)[buf.count] = '\0'; /* the first reserve left room for it */
    *out_data = buf.data;
    *out_size = buf.count;
    return TG_OK;
}

tg_status tg__read_file(const char* path, const tg_allocator* a, tg_diag* diag, char** out_data,
                        size_t* out_size)
{
    *out_data = NULL;
    *out_size = 0;
    FILE* f = fopen(path, "rb");
    if (!f) {
        tg__diag_set(diag, path, 0, 0, 0, "cannot open: %s", strerror(errno));
        return TG_ERR_IO;
    }
    struct stat sb;
    if (fstat(fileno(f), &sb) == 0) {
        const char* kind = S_ISDIR(sb.st_mode) ? "a directory" : S_ISCHR(sb.st_mode) ? "a character device"
                         : S_ISBLK(sb.st_mode) ? "a block device" : S_ISSOCK(sb.st_mode) ? "a socket" : NULL;
        if (kind) { /* /dev/urandom would be read forever, /dev/null is no mesh either */
            fclose(f);
            tg__diag_set(diag, path, 0, 0, 0, "is %s, not a mesh file", kind);
            return TG_ERR_IO;
        }
        if (!S_ISREG(sb.st_mode) || sb.st_size == 0) return read_stream(f, path, a, diag, out_data, out_size);
    }
    unsigned char magic[2] = {0, 0};
    size_t got = fread(magic, 1, 2, f);
    if (tg__ends_with_ci(path, ".gz") || (got == 2 && magic[0] == 0x1f && magic[1] == 0x8b)) {
        fclose(f);
        return read_gz(path, a, diag, out_data, out_size);
    }
    long size = -1;
    if (fseek(f, 0, SEEK_END) == 0) size = ftell(f);
    if (size < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        tg__diag_set(diag, path, 0, 0, 0, "cannot determine the file size (not a regular file?)");
        return TG_ERR_IO;
    }
    char* data = tg__alloc(a, (size_t)size + 1);
    if (!data) {
        fclose(f);
        tg__diag_set(diag, path, 0, 0, 0, "out of memory reading %ld bytes", size);
        return TG_ERR_OUT_OF_MEMORY;
    }
    size_t n = size ? fread(data, 1, (size_t)size, f) : 0;
    int err = ferror(f);
    fclose(f);
    if (n != (size_t)size || err) {
        tg__free(a, data);
        tg__diag_set(diag, path, 0, 0, n, "read error after %zu of %ld bytes", n, size);
        return TG_ERR_IO;
    }
    data[size] = '\0';
    *out_data = data;
    *out_size = (size_t)size;
    return TG_OK;
}
