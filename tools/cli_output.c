/* cli_output.c - CLI outputs that never leave a partial file (written to a temporary name beside
 * the target and renamed into place only when complete), Ctrl-C as a polite request to stop, a
 * progress line on a terminal, and the NumPy .npy format.
 * Based on: the CLI contract of the project's DESIGN.md; rename(2) being atomic within one file
 * system (POSIX); the NPY format version 1.0 (NumPy Enhancement Proposal 1). */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"

#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>
#include <unistd.h>

/* ---- Ctrl-C ---- */

static volatile sig_atomic_t interrupted;

static void on_sigint(int sig)
{
    (void)sig;
    if (interrupted) _exit(130); /* a second Ctrl-C: stop at once (temporary files may remain) */
    interrupted = 1;
}

void cli_interrupt_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_sigint;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

bool cli_interrupted(void)
{
    return interrupted != 0;
}

/* ---- progress line ---- */

double cli_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void cli_progress_start(cli_progress* p, const char* what, bool quiet)
{
    memset(p, 0, sizeof *p);
    p->what = what;
    p->enabled = !quiet && isatty(STDERR_FILENO);
    p->t0 = cli_seconds();
    p->next = p->t0 + 1.0; /* only work that passes about a second draws a line */
}

void cli_progress_update(cli_progress* p, double fraction, const char* detail)
{
    if (!p->enabled) return;
    double t = cli_seconds();
    if (t < p->next) return;
    p->next = t + 0.1;
    p->drawn = true;
    fprintf(stderr, "\r%s: %5.1f%%  %s  %.1f s   ", p->what, 100.0 * fraction, detail ? detail : "", t - p->t0);
    fflush(stderr);
}

void cli_progress_end(cli_progress* p)
{
    if (p->drawn) {
        fprintf(stderr, "\r%*s\r", 78, "");
        fflush(stderr);
    }
    p->drawn = false;
}

/* ---- outputs ---- */

FILE* cli_output_open(cli_output* o, const char* path)
{
    memset(o, 0, sizeof *o);
    o->path = path;
    if (!strcmp(path, "-")) {
        o->f = stdout;
        return o->f;
    }
    if (!cli_output_reserve(o, path)) return NULL;
    o->f = fopen(o->tmp, "wb");
    if (!o->f) {
        cli_error(path, 0, "cannot open for writing: %s", strerror(errno));
        free(o->tmp);
        o->tmp = NULL;
        return NULL;
    }
    return o->f;
}

bool cli_output_reserve(cli_output* o, const char* path)
{
    o->path = path;
    size_t n = strlen(path);
    o->tmp = malloc(n + 32);
    if (!o->tmp) {
        cli_error(path, 0, "out of memory");
        return false;
    }
    /* beside the target (same directory, so the rename stays within one file system) */
    snprintf(o->tmp, n + 32, "%s.tmp-%ld", path, (long)getpid());
    return true;
}

int cli_output_commit(cli_output* o)
{
    int rc = CLI_OK;
    if (o->f) {
        bool bad = ferror(o->f) != 0;
        if (o->f == stdout)
            bad = fflush(stdout) != 0 || bad;
        else
            bad = fclose(o->f) != 0 || bad;
        o->f = NULL;
        if (bad) {
            cli_error(o->path, 0, "write failed: %s", strerror(errno));
            rc = CLI_INPUT;
        }
    }
    if (o->tmp) {
        if (rc == CLI_OK && rename(o->tmp, o->path) != 0) {
            cli_error(o->path, 0, "cannot rename the finished output into place: %s", strerror(errno));
            rc = CLI_INPUT;
        }
        if (rc != CLI_OK) remove(o->tmp);
        free(o->tmp);
        o->tmp = NULL;
    }
    return rc;
}

int cli_output_finish_library(cli_output* o, tg_status st, const tg_diag* d)
{
    if (st == TG_OK) return cli_output_commit(o);
    /* the library named the temporary file: name the one the user asked for */
    cli_error(o->path, 0, "%s", d && d->message[0] ? d->message : tg_status_string(st));
    cli_output_abort(o);
    return st == TG_ERR_INVALID_ARGUMENT ? CLI_USAGE : CLI_INPUT;
}

void cli_output_abort(cli_output* o)
{
    if (o->f && o->f != stdout) fclose(o->f);
    o->f = NULL;
    if (o->tmp) {
        remove(o->tmp);
        free(o->tmp);
        o->tmp = NULL;
    }
}

char* cli_skip_bom(char* text)
{
    const unsigned char* u = (const unsigned char*)text;
    return u[0] == 0xEF && u[1] == 0xBB && u[2] == 0xBF ? text + 3 : text;
}

/* ---- threads ---- */

static void* idle_thread(void* arg)
{
    return arg;
}

bool cli_threads_available(int threads, const char* what)
{
    long n = threads > 0 ? threads : sysconf(_SC_NPROCESSORS_ONLN);
    if (n > 256) n = 256;
    pthread_t t[256];
    long made = 0;
    int err = 0;
    /* the OpenMP runtime starts n - 1 threads with default attributes, and exits the process if it
     * cannot: start them once here, where a failure can be reported */
    for (; made < n - 1; ++made)
        if ((err = pthread_create(&t[made], NULL, idle_thread, NULL)) != 0) break;
    for (long i = 0; i < made; ++i) pthread_join(t[i], NULL);
    if (err) {
        cli_error(NULL, 0, "%s: cannot start %ld threads (%s); try --threads 1", what, n, strerror(err));
        return false;
    }
    return true;
}

/* ---- .npy ---- */

bool cli_write_npy_f64(FILE* f, const double* data, size_t rows, size_t cols, bool matrix)
{
    char dict[160];
    if (matrix)
        snprintf(dict, sizeof dict, "{'descr': '<f8', 'fortran_order': False, 'shape': (%zu, %zu), }", rows, cols);
    else
        snprintf(dict, sizeof dict, "{'descr': '<f8', 'fortran_order': False, 'shape': (%zu,), }", cols);
    /* magic (6) + version (2) + header length (2) + dict padded with spaces and a newline to a
     * multiple of 64 bytes, so that the data is aligned */
    size_t len = strlen(dict), total = 10 + len + 1;
    size_t pad = (64 - total % 64) % 64, hlen = len + pad + 1;
    unsigned char pre[10] = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0, (unsigned char)(hlen & 0xFF), (unsigned char)(hlen >> 8)};
    if (fwrite(pre, 1, 10, f) != 10 || fwrite(dict, 1, len, f) != len) return false;
    for (size_t i = 0; i < pad; ++i)
        if (fputc(' ', f) == EOF) return false;
    if (fputc('\n', f) == EOF) return false;
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

bool cli_grow(void** p, size_t* cap, size_t need, size_t elem)
{
    if (need <= *cap) return true;
    size_t c = *cap ? *cap : 16;
    while (c < need) {
        if (c > SIZE_MAX / 2) return false;
        c *= 2;
    }
    if (c > SIZE_MAX / elem) return false;
    void* grown = realloc(*p, c * elem);
    if (!grown) return false;
    *p = grown, *cap = c;
    return true;
}

char* cli_read_all(const char* path, size_t* out_size)
{
    FILE* f = strcmp(path, "-") ? fopen(path, "rb") : stdin;
    if (!f) {
        cli_error(path, 0, "cannot open: %s", strerror(errno));
        return NULL;
    }
    size_t cap = 0, n = 0;
    char* buf = NULL;
    bool ok = true;
    for (;;) {
        if (!cli_grow((void**)&buf, &cap, n + 65536, 1)) {
            ok = false;
            break;
        }
        size_t got = fread(buf + n, 1, cap - 1 - n, f);
        n += got;
        if (got == 0) break;
    }
    int bad = ferror(f);
    if (f != stdin) fclose(f);
    if (!ok || bad) {
        cli_error(path, 0, bad ? "read error: %s" : "out of memory%s", bad ? strerror(errno) : "");
        free(buf);
        return NULL;
    }
    buf[n] = '\0';
    *out_size = n;
    return buf;
}

bool cli_ext_is(const char* path, const char* ext)
{
    size_t n = strlen(path), e = strlen(ext);
    return n >= e && !strcasecmp(path + n - e, ext);
}

int cli_write_labels(const char* path, const tg_mesh* mesh, const uint32_t* label, const double* dist, size_t n)
{
    if (strcmp(path, "-") != 0 && cli_ext_is(path, ".ply")) {
        double* as_double = malloc((n ? n : 1) * sizeof *as_double);
        if (!as_double) {
            cli_error(NULL, 0, "out of memory");
            return CLI_INPUT;
        }
        for (size_t v = 0; v < n; ++v) as_double[v] = label[v] == TG_NONE ? -1.0 : (double)label[v];
        tg_vertex_scalar sc[2] = {{"label", as_double}, {"distance", dist}};
        tg_diag d;
        memset(&d, 0, sizeof d);
        cli_output out;
        int rc = CLI_INPUT;
        if (cli_output_reserve(&out, path)) {
            out.f = NULL;
            rc = cli_output_finish_library(&out, tg_mesh_write_ply(mesh, out.tmp, sc, 2, &d), &d);
        }
        free(as_double);
        return rc;
    }
    cli_output out;
    FILE* f = cli_output_open(&out, path);
    if (!f) return CLI_INPUT;
    bool ok = fprintf(f, "vertex,label,distance\n") > 0;
    for (size_t v = 0; ok && v < n; ++v)
        ok = fprintf(f, "%zu,%lld,%.17g\n", v, label[v] == TG_NONE ? -1LL : (long long)label[v], dist[v]) > 0;
    if (!ok) {
        cli_error(path, 0, "write failed: %s", strerror(errno));
        cli_output_abort(&out);
        return CLI_INPUT;
    }
    return cli_output_commit(&out);
}
