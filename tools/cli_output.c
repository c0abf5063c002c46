/* cli_output.c - CLI outputs that never destroy data: written into a private temporary directory
 * beside the target and renamed into place only when complete (devices and FIFOs written
 * directly, an output that is one of the inputs refused); Ctrl-C and SIGTERM end the work with
 * exit 130 and no temporary left behind; a progress line on a terminal.
 * Based on: the CLI contract of the project's DESIGN.md; rename(2) being atomic within one file
 * system and mkdtemp(3) creating a new directory exclusively (POSIX 2008); the async-signal-safe
 * functions of POSIX (unlink, rmdir, write, _exit). */
#define _POSIX_C_SOURCE 200809L
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* ---- Ctrl-C ---- */

/* Temporaries to remove when a signal ends the process: the file being written and its private
 * directory. Strings are written before the slot is marked used (and unmarked before they
 * change), so the handler, which may run on any thread, only reads complete names. */
#define MAX_TEMPORARIES 4
static char temp_file[MAX_TEMPORARIES][4096], temp_dir[MAX_TEMPORARIES][4096];
static volatile sig_atomic_t temp_used[MAX_TEMPORARIES];
static volatile sig_atomic_t interrupted, polling;
/* While the outputs of a run are renamed into place (cli_output_set_commit), a signal waits until
 * they all are: held_signal, raised again after. */
static volatile sig_atomic_t committing, held_signal;

static void remove_temporaries(void)
{
    for (int i = 0; i < MAX_TEMPORARIES; ++i)
        if (temp_used[i]) {
            unlink(temp_file[i]); /* async-signal-safe, as are rmdir, write and _exit */
            rmdir(temp_dir[i]);
        }
}

static void on_signal(int sig)
{
    if (committing) {
        held_signal = sig;
        return;
    }
    if (polling && !interrupted) { /* the work looks at the flag soon and ends cleanly */
        interrupted = 1;
        return;
    }
    /* a call that cannot look (a library call without a progress hook), or a second Ctrl-C */
    remove_temporaries();
    static const char msg[] = "trigeo: interrupted\n";
    ssize_t w = write(STDERR_FILENO, msg, sizeof msg - 1);
    (void)w;
    _exit(130);
}

void cli_interrupt_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

void cli_interrupt_polling(bool on)
{
    polling = on;
}

bool cli_interrupted(void)
{
    return interrupted != 0;
}

static int temp_register(const char* file, const char* dir)
{
    for (int i = 0; i < MAX_TEMPORARIES; ++i)
        if (!temp_used[i] && strlen(file) < sizeof temp_file[i] && strlen(dir) < sizeof temp_dir[i]) {
            strcpy(temp_file[i], file);
            strcpy(temp_dir[i], dir);
            atomic_signal_fence(memory_order_seq_cst);
            temp_used[i] = 1;
            return i;
        }
    return -1; /* not registered: a signal then leaves this temporary behind */
}

static void temp_unregister(int slot)
{
    if (slot >= 0) temp_used[slot] = 0;
    atomic_signal_fence(memory_order_seq_cst);
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

/* The kind of an existing path (following links); NULL for a regular file or none. */
static const char* special_kind(const struct stat* st)
{
    return S_ISDIR(st->st_mode)    ? "a directory"
         : S_ISCHR(st->st_mode)    ? "a character device"
         : S_ISBLK(st->st_mode)    ? "a block device"
         : S_ISFIFO(st->st_mode)   ? "a FIFO"
         : S_ISSOCK(st->st_mode)   ? "a socket"
                                   : NULL;
}

bool cli_output_is_direct(const char* path)
{
    struct stat st;
    return stat(path, &st) == 0 && (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode));
}

bool cli_output_reserve(cli_output* o, const char* path)
{
    memset(o, 0, sizeof *o);
    o->path = path;
    o->slot = -1;
    struct stat st;
    if (stat(path, &st) == 0 && special_kind(&st)) {
        /* a character device or a FIFO (/dev/null, a named pipe) is written to directly:
         * renaming a file over it would replace the node; anything else is refused */
        if (!S_ISCHR(st.st_mode) && !S_ISFIFO(st.st_mode)) {
            cli_error(path, 0, "is %s: give a file name (or a character device or FIFO, written directly)",
                      special_kind(&st));
            return false;
        }
        o->tmp = strdup(path);
        if (!o->tmp) cli_error(path, 0, "out of memory");
        return o->tmp != NULL;
    }
    /* a private directory beside the target (so the final rename stays within one file
     * system), made with mkdtemp: an unpredictable name, created exclusively with mode 0700, so
     * no one else can place a link where the file will be written */
    size_t n = strlen(path);
    const char* slash = strrchr(path, '/');
    size_t dir_len = slash ? (size_t)(slash - path) + 1 : 0;
    const char* base = slash ? slash + 1 : path;
    o->dir = malloc(dir_len + 32);
    o->tmp = malloc(dir_len + 32 + n + 2);
    if (!o->dir || !o->tmp) {
        cli_error(path, 0, "out of memory");
        free(o->dir), free(o->tmp);
        o->dir = o->tmp = NULL;
        return false;
    }
    memcpy(o->dir, path, dir_len);
    strcpy(o->dir + dir_len, ".trigeo-XXXXXX");
    if (!mkdtemp(o->dir)) {
        cli_error(path, 0, "cannot create a temporary directory beside it: %s", strerror(errno));
        free(o->dir), free(o->tmp);
        o->dir = o->tmp = NULL;
        return false;
    }
    sprintf(o->tmp, "%s/%s", o->dir, base);
    o->slot = temp_register(o->tmp, o->dir);
    return true;
}

FILE* cli_output_open(cli_output* o, const char* path)
{
    memset(o, 0, sizeof *o);
    o->path = path;
    o->slot = -1;
    if (!strcmp(path, "-")) {
        o->f = stdout;
        return o->f;
    }
    if (!cli_output_reserve(o, path)) return NULL;
    o->f = fopen(o->tmp, "wb");
    if (!o->f) {
        cli_error(path, 0, "cannot open for writing: %s", strerror(errno));
        cli_output_abort(o);
        return NULL;
    }
    return o->f;
}

/* Forgets the temporary names (after the rename or the removal). */
static void release(cli_output* o)
{
    temp_unregister(o->slot);
    o->slot = -1;
    if (o->dir) rmdir(o->dir);
    free(o->dir), free(o->tmp);
    o->dir = o->tmp = NULL;
}

int cli_output_close(cli_output* o)
{
    if (!o->f) return CLI_OK;
    bool bad = ferror(o->f) != 0;
    if (o->f == stdout)
        bad = fflush(stdout) != 0 || bad;
    else
        bad = fclose(o->f) != 0 || bad;
    o->f = NULL;
    if (!bad) return CLI_OK;
    cli_error(o->path, 0, "write failed: %s", strerror(errno));
    cli_output_abort(o);
    return CLI_INPUT;
}

/* Renames the complete temporary into place (nothing to do for stdout or a direct output). */
static int rename_into_place(cli_output* o)
{
    int rc = CLI_OK;
    if (o->dir && rename(o->tmp, o->path) != 0) {
        cli_error(o->path, 0, "cannot rename the finished output into place: %s", strerror(errno));
        unlink(o->tmp);
        rc = CLI_INPUT;
    }
    release(o);
    return rc;
}

int cli_output_commit(cli_output* o)
{
    if (interrupted) { /* Ctrl-C while polling, during work that finished without looking: honoured here */
        cli_error(o->path, 0, "interrupted: nothing written");
        cli_output_abort(o);
        return 130;
    }
    int rc = cli_output_close(o);
    return rc == CLI_OK ? rename_into_place(o) : rc;
}

int cli_output_library_done(cli_output* o, tg_status st, const tg_diag* d)
{
    if (st == TG_OK && interrupted) st = TG_ERR_CANCELLED; /* the library finished without looking */
    if (st == TG_OK) return CLI_OK;
    if (st == TG_ERR_CANCELLED) {
        cli_error(o->path, 0, "interrupted: nothing written");
        cli_output_abort(o);
        return 130;
    }
    /* the library named the temporary file: name the one the user asked for */
    cli_error(o->path, 0, "%s", d && d->message[0] ? d->message : tg_status_string(st));
    cli_output_abort(o);
    return st == TG_ERR_INVALID_ARGUMENT ? CLI_USAGE : CLI_INPUT;
}

int cli_output_finish_library(cli_output* o, tg_status st, const tg_diag* d)
{
    int rc = cli_output_library_done(o, st, d);
    return rc == CLI_OK ? cli_output_commit(o) : rc;
}

void cli_output_abort(cli_output* o)
{
    if (o->f && o->f != stdout) fclose(o->f);
    o->f = NULL;
    if (o->dir) unlink(o->tmp);
    release(o);
}

/* ---- a run's outputs as one transaction ---- */

cli_output* cli_output_set_add(cli_output_set* s)
{
    if (s->count == CLI_OUTPUT_SET_MAX) return NULL; /* a command declares at most this many */
    cli_output* o = &s->item[s->count++];
    memset(o, 0, sizeof *o);
    o->slot = -1;
    return o;
}

FILE* cli_output_set_open(cli_output_set* s, const char* path)
{
    cli_output* o = cli_output_set_add(s);
    return o ? cli_output_open(o, path) : NULL;
}

cli_output* cli_output_set_reserve(cli_output_set* s, const char* path)
{
    cli_output* o = cli_output_set_add(s);
    return o && cli_output_reserve(o, path) ? o : NULL;
}

int cli_output_set_commit(cli_output_set* s)
{
    if (interrupted) { /* Ctrl-C while polling, during work that finished without looking */
        cli_error(s->count ? s->item[0].path : NULL, 0, "interrupted: nothing written");
        cli_output_set_abort(s);
        return 130;
    }
    int rc = CLI_OK;
    for (size_t i = 0; i < s->count && rc == CLI_OK; ++i) rc = cli_output_close(&s->item[i]);
    /* every temporary complete and still there (a library writer wrote it by name), before any
     * rename: otherwise none is renamed */
    for (size_t i = 0; i < s->count && rc == CLI_OK; ++i) {
        const cli_output* o = &s->item[i];
        struct stat st;
        if (o->dir && (lstat(o->tmp, &st) != 0 || !S_ISREG(st.st_mode))) {
            cli_error(o->path, 0, "the finished output is missing from its temporary folder: nothing written");
            rc = CLI_INPUT;
        }
    }
    if (rc != CLI_OK) {
        cli_output_set_abort(s);
        return rc;
    }
    /* the renames, with a signal held back until they are all done (one rename cannot be
     * undone, so all of them or none; they take microseconds) */
    committing = 1;
    atomic_signal_fence(memory_order_seq_cst);
    for (size_t i = 0; i < s->count; ++i) {
        int r = rename_into_place(&s->item[i]);
        if (rc == CLI_OK) rc = r;
    }
    s->count = 0;
    atomic_signal_fence(memory_order_seq_cst);
    committing = 0;
    int held = held_signal;
    held_signal = 0;
    if (held) raise(held); /* the outputs are complete; now the signal ends the run */
    return rc;
}

void cli_output_set_abort(cli_output_set* s)
{
    for (size_t i = 0; i < s->count; ++i) cli_output_abort(&s->item[i]);
    s->count = 0;
}

/* ---- outputs checked against the inputs and each other ---- */

/* What an output path names: the existing file (following links), or for a new one its folder
 * (device and inode) and its name in it. */
typedef struct output_id {
    bool exists, to_stdout;
    struct stat st, dir;
    const char* base;
} output_id;

/* Identifies an output; CLI_OK, or CLI_INPUT after printing why it cannot be written (a folder
 * that does not exist or cannot be written into, a directory, a block device or socket). */
static int identify_output(const char* path, const char* option, output_id* id)
{
    memset(id, 0, sizeof *id);
    if (!strcmp(path, "-")) {
        id->to_stdout = true;
        return CLI_OK;
    }
    size_t n = strlen(path);
    if (!n || path[n - 1] == '/') {
        cli_error(path, 0, "%s needs a file name, not a folder", option);
        return CLI_INPUT;
    }
    if (stat(path, &id->st) == 0) {
        id->exists = true;
        const char* kind = special_kind(&id->st);
        if (kind && !S_ISCHR(id->st.st_mode) && !S_ISFIFO(id->st.st_mode)) {
            cli_error(path, 0, "is %s: %s needs a file name (or a character device or FIFO, written directly)", kind, option);
            return CLI_INPUT;
        }
        if (kind) return CLI_OK; /* written directly: its folder does not matter */
    }
    const char* slash = strrchr(path, '/');
    id->base = slash ? slash + 1 : path;
    char* dir = slash ? strndup(path, slash == path ? 1 : (size_t)(slash - path)) : strdup(".");
    if (!dir) {
        cli_error(path, 0, "out of memory");
        return CLI_INPUT;
    }
    int rc = CLI_OK;
    if (stat(dir, &id->dir) != 0) {
        cli_error(path, 0, "cannot write %s: the folder %s: %s; nothing written", option, dir, strerror(errno));
        rc = CLI_INPUT;
    } else if (!S_ISDIR(id->dir.st_mode)) {
        cli_error(path, 0, "cannot write %s: %s is not a folder; nothing written", option, dir);
        rc = CLI_INPUT;
    } else if (access(dir, W_OK | X_OK) != 0) {
        cli_error(path, 0, "cannot write %s into the folder %s: %s; nothing written", option, dir, strerror(errno));
        rc = CLI_INPUT;
    }
    free(dir);
    return rc;
}

static bool same_output(const output_id* a, const output_id* b)
{
    if (a->to_stdout || b->to_stdout) return a->to_stdout && b->to_stdout;
    if (a->exists || b->exists) /* one new file is never an existing one */
        return a->exists && b->exists && a->st.st_dev == b->st.st_dev && a->st.st_ino == b->st.st_ino;
    return a->dir.st_dev == b->dir.st_dev && a->dir.st_ino == b->dir.st_ino && !strcmp(a->base, b->base);
}

int cli_check_outputs(const cli_file_role* outputs, size_t output_count, const cli_file_role* inputs, size_t input_count)
{
    output_id id[CLI_OUTPUT_SET_MAX];
    if (output_count > CLI_OUTPUT_SET_MAX) output_count = CLI_OUTPUT_SET_MAX;
    for (size_t k = 0; k < output_count; ++k) {
        const char* out = outputs[k].path;
        memset(&id[k], 0, sizeof id[k]);
        if (!out) continue; /* an option not given */
        int rc = identify_output(out, outputs[k].what, &id[k]);
        if (rc != CLI_OK) return rc;
        for (size_t i = 0; id[k].exists && i < input_count; ++i) {
            struct stat si;
            const char* in = inputs[i].path;
            if (!in || !strcmp(in, "-") || stat(in, &si) != 0) continue; /* stdin, or a read error later */
            if (si.st_dev == id[k].st.st_dev && si.st_ino == id[k].st.st_ino) { /* by any name or link */
                cli_error(out, 0, "%s is the same file as the %s %s: writing it would destroy the input; choose "
                                  "another output", outputs[k].what, inputs[i].what, in);
                return CLI_USAGE;
            }
        }
        for (size_t j = 0; j < k; ++j)
            if (outputs[j].path && same_output(&id[j], &id[k])) {
                cli_error(out, 0, "%s is the same file as %s %s: one run writes each output to its own file; choose "
                                  "another name", outputs[k].what, outputs[j].what, outputs[j].path);
                return CLI_USAGE;
            }
    }
    return CLI_OK;
}

/* Length of the valid UTF-8 sequence at s (1-4), or 0 (RFC 3629: no overlong forms, no
 * surrogates, nothing above U+10FFFF). */
static int utf8_length(const unsigned char* s)
{
    unsigned c = s[0];
    if (c < 0x80) return 1;
    int n = c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3 : c >= 0xF0 && c <= 0xF4 ? 4 : 0;
    for (int i = 1; i < n; ++i)
        if ((s[i] & 0xC0) != 0x80) return 0;
    if (n == 3 && ((c == 0xE0 && s[1] < 0xA0) || (c == 0xED && s[1] > 0x9F))) return 0;
    if (n == 4 && ((c == 0xF0 && s[1] < 0x90) || (c == 0xF4 && s[1] > 0x8F))) return 0;
    return n;
}

void cli_json_string(FILE* f, const char* s)
{
    const unsigned char* u = (const unsigned char*)s;
    fputc('"', f);
    while (*u) {
        if (*u == '"' || *u == '\\') {
            fputc('\\', f);
            fputc(*u++, f);
        } else if (*u < 0x20 || *u == 0x7F) {
            fprintf(f, "\\u%04x", *u++);
        } else {
            int n = utf8_length(u);
            if (n) {
                fwrite(u, 1, (size_t)n, f);
                u += n;
            } else {
                fputs("\\ufffd", f);
                u++;
            }
        }
    }
    fputc('"', f);
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

int cli_field_threads(const char* cmd, const char* text, int* out)
{
    unsigned long long n = 1;
    if (text && (!cli_parse_uint(text, &n) || n > TG_MAX_THREADS))
        return cli_usage(cmd, "--threads needs a number in 0..%d (0 = all cores), not '%s'", TG_MAX_THREADS, text);
    *out = n == 0 ? TG_THREADS_ALL : (int)n;
    if (n != 1 && !cli_threads_available((int)n, cmd)) return CLI_INPUT;
    return CLI_OK;
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

char* cli_read_text(const char* path, const char* what, size_t* out_size)
{
    size_t size = 0;
    char* text = cli_read_all(path, &size);
    const char* nul = text ? memchr(text, 0, size) : NULL;
    if (nul) {
        unsigned long long line = 1;
        for (const char* p = text; p < nul; ++p) line += *p == '\n';
        cli_error(path, line, "binary data (a NUL byte): not a %s", what);
        free(text);
        return NULL;
    }
    if (text && out_size) *out_size = size;
    return text;
}

char* cli_next_line(char** cursor, unsigned long long* lineno)
{
    char* s = *cursor;
    if (!s || !*s) return NULL;
    char* end = strchr(s, '\n');
    *cursor = end ? end + 1 : s + strlen(s);
    if (end) {
        if (end > s && end[-1] == '\r') end[-1] = '\0';
        *end = '\0';
    } else if (*cursor > s && (*cursor)[-1] == '\r') {
        (*cursor)[-1] = '\0';
    }
    if (++*lineno == 1) s = cli_skip_bom(s);
    return s;
}

bool cli_ext_is(const char* path, const char* ext)
{
    size_t n = strlen(path), e = strlen(ext);
    return n >= e && !strcasecmp(path + n - e, ext);
}

/* ---- JSON ---- */

void cli_json_point(FILE* f, const tg_surface_point* p)
{
    if (p->kind == TG_SURFACE_VERTEX)
        fprintf(f, "{\"kind\": \"vertex\", \"vertex\": %u}", p->index);
    else if (p->kind == TG_SURFACE_EDGE)
        fprintf(f, "{\"kind\": \"edge\", \"halfedge\": %u, \"t\": %s}", p->index, cli_num(p->t).s);
    else
        fprintf(f, "{\"kind\": \"face\", \"face\": %u, \"bary\": [%s, %s, %s]}", p->index, cli_num(p->bary[0]).s,
                cli_num(p->bary[1]).s, cli_num(p->bary[2]).s);
}

int cli_write_labels(cli_output_set* set, const char* path, const tg_mesh* mesh, const uint32_t* label, const double* dist,
                     size_t n)
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
        cli_output* out = cli_output_set_reserve(set, path);
        int rc = out ? cli_output_library_done(out, tg_mesh_write_ply(mesh, out->tmp, sc, 2, &d), &d) : CLI_INPUT;
        free(as_double);
        return rc;
    }
    FILE* f = cli_output_set_open(set, path);
    if (!f) return CLI_INPUT;
    bool ok = fprintf(f, "vertex,label,distance\n") > 0;
    for (size_t v = 0; ok && v < n; ++v)
        ok = fprintf(f, "%zu,%lld,%s\n", v, label[v] == TG_NONE ? -1LL : (long long)label[v], cli_num(dist[v]).s) > 0;
    if (!ok) {
        cli_error(path, 0, "write failed: %s", strerror(errno));
        return CLI_INPUT;
    }
    return CLI_OK;
}

int cli_write_columns(cli_output_set* set, const char* path, const tg_mesh* mesh, const char* index_name,
                      const char* const* names, const double* const* cols, size_t ncols, size_t n)
{
    bool stdout_ = strcmp(path, "-") == 0;
    if (!stdout_ && cli_ext_is(path, ".ply")) { /* the mesh with a property a column */
        tg_vertex_scalar sc[16];
        if (!mesh || ncols > 16) return CLI_INPUT;
        for (size_t c = 0; c < ncols; ++c) sc[c].name = names[c], sc[c].values = cols[c];
        tg_diag d;
        memset(&d, 0, sizeof d);
        cli_output* out = cli_output_set_reserve(set, path);
        return out ? cli_output_library_done(out, tg_mesh_write_ply(mesh, out->tmp, sc, ncols, &d), &d) : CLI_INPUT;
    }
    FILE* f = cli_output_set_open(set, path);
    if (!f) return CLI_INPUT;
    bool ok = true;
    if (!stdout_ && cli_ext_is(path, ".npy")) {
        double* rows = malloc((n ? n : 1) * ncols * sizeof *rows);
        ok = rows != NULL;
        for (size_t i = 0; ok && i < n; ++i)
            for (size_t c = 0; c < ncols; ++c) rows[i * ncols + c] = cols[c][i];
        ok = ok && cli_write_npy_f64(f, rows, n, ncols, true);
        free(rows);
    } else {
        ok = fprintf(f, "%s", index_name) > 0;
        for (size_t c = 0; ok && c < ncols; ++c) ok = fprintf(f, ",%s", names[c]) > 0;
        ok = ok && fputc('\n', f) != EOF;
        for (size_t i = 0; ok && i < n; ++i) {
            ok = fprintf(f, "%zu", i) > 0;
            for (size_t c = 0; ok && c < ncols; ++c) ok = fprintf(f, ",%s", cli_num(cols[c][i]).s) > 0;
            ok = ok && fputc('\n', f) != EOF;
        }
    }
    if (!ok) {
        cli_error(path, 0, "write failed: %s", strerror(errno));
        return CLI_INPUT;
    }
    return CLI_OK;
}

bool cli_obj_vertices(FILE* f, const double* xyz, size_t count)
{
    bool ok = true;
    for (size_t i = 0; ok && i < count; ++i)
        ok = fprintf(f, "v %s %s %s\n", cli_num(xyz[3 * i]).s, cli_num(xyz[3 * i + 1]).s, cli_num(xyz[3 * i + 2]).s) > 0;
    return ok;
}

bool cli_obj_line(FILE* f, size_t first, size_t count, bool closed)
{
    bool ok = fputc('l', f) != EOF;
    for (size_t i = 0; ok && i < count; ++i)
        ok = fprintf(f, " %zu", (closed && i + 1 == count ? first : first + i) + 1) > 0;
    return ok && fputc('\n', f) != EOF;
}
