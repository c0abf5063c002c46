/* cli.h - shared pieces of the trigeo command-line tool (uses only the public API). */
#ifndef TG_CLI_H
#define TG_CLI_H

#include <stdbool.h>
#include <stdio.h>
#include <trigeo.h>

/* Exit codes of the CLI contract (DESIGN.md). */
enum { CLI_OK = 0, CLI_USAGE = 1, CLI_INPUT = 2 };

typedef struct cli_command {
    const char* name;
    const char* synopsis; /* one line: "info MESH [--json]" */
    const char* help;     /* full help text */
    int (*run)(int argc, char** argv); /* argv[0] is the command name */
} cli_command;

/* "trigeo: FILE:LINE: message" (FILE/LINE omitted when unknown) on stderr. */
void cli_error(const char* file, unsigned long long line, const char* fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* Prints a tg_diag in the CLI error format. */
void cli_error_diag(const tg_diag* d, tg_status st);
/* Loads a mesh, printing the error and returning NULL on failure. */
tg_mesh* cli_load_mesh(const char* path);
/* The same for commands that compute distances: also refuses coordinates beyond +-1e150, where
 * squared distances overflow double, naming the limit. */
tg_mesh* cli_load_mesh_for_distances(const char* path);
/* Usage error: message plus "see trigeo help CMD"; returns CLI_USAGE. */
int cli_usage(const char* cmd, const char* fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Parses a non-negative integer / a double option value; false on junk. */
bool cli_parse_uint(const char* s, unsigned long long* out);
bool cli_parse_double(const char* s, double* out);
/* Parses a comma-separated list of exactly n finite doubles ("X,Y,Z"); false on junk. */
bool cli_parse_doubles(const char* s, int n, double* out);
/* Seconds on the monotonic clock (for durations). */
double cli_seconds(void);

/* A surface point as written on the command line (cli_spec.c). */
typedef struct cli_spec {
    int kind; /* 'v', 'f', 'e' or 'p' */
    unsigned long long index;
    double v[3];
} cli_spec;
/* Parses v:IDX | f:FACE:b0,b1,b2 | e:HALFEDGE:t | p:x,y,z; false on a syntax error. */
bool cli_parse_spec(const char* s, cli_spec* out);
/* Barycentric coordinates read from text that sum to 1 within this are rescaled to sum to 1
 * (the library itself accepts 1e-9); farther off, they are refused. */
#define CLI_BARY_RENORMALIZE 1e-6
/* A face point from barycentrics as read from text (renormalized within CLI_BARY_RENORMALIZE). */
tg_surface_point cli_face_point(uint32_t face, const double b[3]);
/* The surface point closest to xyz (through the BVH *bvh, built on first use); false for an
 * empty mesh or out of memory. */
bool cli_locate(tg_mesh* mesh, tg_bvh** bvh, const double xyz[3], tg_surface_point* out);
/* Resolves a spec on the mesh (p: through the BVH *bvh, built on first use; the caller destroys
 * it). Prints the error and returns false when the location is invalid. */
bool cli_resolve_spec(const char* mesh_path, tg_mesh* mesh, tg_bvh** bvh, const char* text, const cli_spec* sp,
                      tg_surface_point* out);

/* ---- inputs (cli_output.c) ---- */

/* The CLI's one growth rule: makes *p (an array of *cap elements of elem bytes, realloc'd) hold
 * at least `need` elements, doubling; false (nothing changed) on overflow or out of memory. */
bool cli_grow(void** p, size_t* cap, size_t need, size_t elem);
/* The whole of a file (standard input for "-") as a NUL-terminated buffer of *out_size bytes;
 * NULL after printing why. */
char* cli_read_all(const char* path, size_t* out_size);

/* ---- outputs, Ctrl-C and progress (cli_output.c) ---- */

/* A file output written to a temporary name beside `path` and renamed into place by
 * cli_output_commit, so that an error or Ctrl-C never leaves a partial file. "-" is stdout. */
typedef struct cli_output {
    const char* path;
    char* tmp; /* the temporary name, NULL for stdout */
    FILE* f;
} cli_output;
/* Opens the temporary file (or stdout for "-"); prints the error and returns NULL on failure. */
FILE* cli_output_open(cli_output* o, const char* path);
/* Only picks the temporary name, for a library writer that takes a file name (o->tmp). */
bool cli_output_reserve(cli_output* o, const char* path);
/* Closes (checking every write) and renames into place; CLI_OK or CLI_INPUT (error printed,
 * temporary removed). */
int cli_output_commit(cli_output* o);
/* Closes and removes the temporary file. */
void cli_output_abort(cli_output* o);
/* After a library writer wrote o->tmp (cli_output_reserve) with status st: renames it into place,
 * or prints the error under the user's file name and removes it. CLI_OK, CLI_USAGE (invalid
 * argument) or CLI_INPUT. */
int cli_output_finish_library(cli_output* o, tg_status st, const tg_diag* d);
/* Does `path` end with `ext` (".json", ".csv", ...; case-insensitive)? The CLI's -o picks the
 * output format by extension. */
bool cli_ext_is(const char* path, const char* ext);
/* Writes a float64 array as NumPy .npy: (rows, cols) when matrix, else (cols,). */
bool cli_write_npy_f64(FILE* f, const double* data, size_t rows, size_t cols, bool matrix);

/* Voronoi labels (trigeo field --labels, trigeo sample --field): per vertex the index of the nearest
 * source (-1 where none reaches) and its distance, as PLY vertex properties `label` and
 * `distance` (a .ply path) or CSV rows vertex,label,distance (anything else; '-' is stdout).
 * Written to a temporary name and renamed; CLI_OK or CLI_INPUT (error printed). */
int cli_write_labels(const char* path, const tg_mesh* mesh, const uint32_t* label, const double* dist, size_t n);

/* Can `threads` threads (0: one per core) be started? Prints why not (naming `what`): OpenMP's
 * runtime would end the process instead of failing. */
bool cli_threads_available(int threads, const char* what);

/* Past a leading UTF-8 byte-order mark, if any (text written by Windows tools). */
char* cli_skip_bom(char* text);

/* SIGINT and SIGTERM set a flag that long work polls (a second Ctrl-C exits at once). */
void cli_interrupt_install(void);
bool cli_interrupted(void);

/* A progress line on stderr, drawn only when it is a terminal, not quiet, and the work has
 * passed about a second. */
typedef struct cli_progress {
    const char* what;
    bool enabled, drawn;
    double t0, next;
} cli_progress;
void cli_progress_start(cli_progress* p, const char* what, bool quiet);
void cli_progress_update(cli_progress* p, double fraction, const char* detail);
void cli_progress_end(cli_progress* p);

/* Commands (one file each). */
extern const cli_command cli_cmd_info;
extern const cli_command cli_cmd_closest;
extern const cli_command cli_cmd_render;
extern const cli_command cli_cmd_path;
extern const cli_command cli_cmd_field;
extern const cli_command cli_cmd_sample;

#endif
