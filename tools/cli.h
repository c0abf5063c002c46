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

/* ---- messages (cli_report.c) ---- */

/* "trigeo: FILE:LINE: message" (FILE/LINE omitted when unknown) on stderr. */
void cli_error(const char* file, unsigned long long line, const char* fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* Prints a tg_diag in the CLI error format. */
void cli_error_diag(const tg_diag* d, tg_status st);
/* Usage error: message plus "see trigeo help CMD"; returns CLI_USAGE. */
int cli_usage(const char* cmd, const char* fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* The last lines of every field-based summary (field, logmap, sample), in one wording:
 * "windows            N created, M propagated" and "seconds            S.SSS", on stdout. */
void cli_print_work(const tg_field_stats* st, double secs);

/* ---- files of surface points and curves (cli_curve.c) ---- */

/* Reads a sources, points or curve file: one item a line; a leading BOM, blank lines and '#'
 * comments skipped. Returns the number of items (texts copied into *out_text, pointers into it in
 * *out_items, their line numbers in *out_lines; out_breaks: NULL, or per item 1 where a blank line
 * comes between it and the item before, which ends a polyline of a curve file), or -1 after
 * printing the error. */
long cli_read_lines(const char* path, const char* what, char** out_text, char*** out_items,
                    unsigned long long** out_lines, unsigned char** out_breaks);
/* Resolves the spec texts items[0..count) on the mesh into pts (lines: from `file`, named in
 * errors; NULL: command-line items of command cmd, errors naming mesh_path; allow_xyz: "x y z"
 * too). CLI_OK, CLI_USAGE (a command-line item that does not parse) or CLI_INPUT (printed). */
int cli_resolve_items(const char* cmd, const char* mesh_path, const char* file, bool allow_xyz, tg_mesh* mesh,
                      tg_bvh** bvh, char** items, const unsigned long long* lines, size_t count, tg_surface_point* pts);

/* The curve sources of a --from list: `curve:FILE` items and `boundary`. */
#define CLI_CURVES_MAX 64
typedef struct cli_curves {
    const char* files[CLI_CURVES_MAX];
    size_t count; /* may exceed CLI_CURVES_MAX: too many (the caller refuses) */
    bool boundary;
} cli_curves;
/* Is item a curve source (`boundary`, `curve:FILE`)? Then it is noted in *c. */
bool cli_curve_item(const char* item, cli_curves* c);
/* The segments of the curve sources c into *out (malloc'd, NULL when none) and *out_count: the
 * boundary's (an error when the mesh has none), then each file's polylines (one point a line as a
 * SPEC, "x y z" or an OBJ "v x y z"; a blank line between polylines; a point within 1e-9 of an
 * edge or corner taken on it), each segment checked (tg_surface_segment_validate, errors naming
 * file and line). out_ends: NULL, or room for 1 + c->count: where the boundary's segments end,
 * then where each file's end. CLI_OK, or CLI_INPUT after the error. */
int cli_curve_segments(const char* cmd, const char* mesh_path, const cli_curves* c, tg_mesh* mesh, tg_bvh** bvh,
                       const tg_geodesic* geo, tg_surface_segment** out, size_t* out_count, size_t* out_ends);

/* ---- the mesh (cli_mesh.c) ---- */

/* The format every later cli_load_mesh reads (--format of the command line; TG_FORMAT_AUTO, the
 * default: from the file's extension, or the content for standard input). */
void cli_set_mesh_format(tg_format format);
/* Loads a mesh, printing the error and returning NULL on failure. */
tg_mesh* cli_load_mesh(const char* path);
/* The same for commands that compute distances: also refuses coordinates beyond +-1e150, where
 * squared distances overflow double, naming the limit. */
tg_mesh* cli_load_mesh_for_distances(const char* path);

/* ---- surface points (cli_spec.c) ---- */

/* A surface point as written on the command line (cli_spec.c). */
typedef struct cli_spec {
    int kind; /* 'v', 'f', 'e' or 'p' */
    unsigned long long index;
    double v[3];
} cli_spec;
/* Parses v:IDX | f:FACE:b0,b1,b2 | e:HALFEDGE:t | p:x,y,z (blanks around it allowed); false on a
 * syntax error. */
bool cli_parse_spec(const char* s, cli_spec* out);
/* Parses "x y z" (three numbers separated by blanks or by one comma) as a p: spec; false
 * otherwise ("1-2 3": no separator). */
bool cli_parse_xyz(const char* s, cli_spec* out);
/* Splits the ';'-separated list in place into items (at most cap), blanks around each item
 * removed ("v:0; v:5"); returns the count, or 0 for an empty item or more than cap. */
size_t cli_split_list(char* list, char** items, size_t cap);
/* A ';'-separated list of specs given to an option ("SPEC;SPEC;..."): its items, parsed, and
 * their surface points once resolved on a mesh. */
#define CLI_SPEC_LIST_MAX 4096
typedef struct cli_spec_list {
    char* buffer;            /* the list, split in place */
    char** text;             /* each item's text */
    cli_spec* spec;
    tg_surface_point* point; /* filled by cli_spec_list_resolve */
    size_t count;
} cli_spec_list;
/* Parses `list` (at most CLI_SPEC_LIST_MAX items): CLI_OK, or CLI_USAGE after naming `option` of
 * command `cmd` and the bad item (CLI_INPUT out of memory). cli_spec_list_free afterwards in any
 * case. */
int cli_spec_list_parse(const char* cmd, const char* option, const char* list, cli_spec_list* out);
/* Resolves every item on the mesh (cli_resolve_spec); false after printing the error. */
bool cli_spec_list_resolve(const char* mesh_path, tg_mesh* mesh, tg_bvh** bvh, cli_spec_list* l);
void cli_spec_list_free(cli_spec_list* l);
/* Barycentric coordinates read from text that sum to 1 within this are rescaled to sum to 1
 * (the library itself accepts 1e-9); farther off, they are refused. */
#define CLI_BARY_RENORMALIZE 1e-6
/* Prints a surface point as a SPEC (v:IDX | e:HALFEDGE:t | f:FACE:b0,b1,b2, the numbers as
 * cli_format_double writes them). */
void cli_print_spec(FILE* f, const tg_surface_point* p);
/* A face point from barycentrics as read from text (renormalized within CLI_BARY_RENORMALIZE). */
tg_surface_point cli_face_point(uint32_t face, const double b[3]);
/* The surface point closest to xyz (through the BVH *bvh, built on first use); false, with the
 * reason in *why (a coordinate beyond +-1e150, a mesh without faces, out of memory), when there
 * is none. */
bool cli_locate(tg_mesh* mesh, tg_bvh** bvh, const double xyz[3], tg_surface_point* out, const char** why);
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
/* cli_read_all for a text file: a NUL byte is refused ("FILE:LINE: binary data (a NUL byte): not
 * a WHAT"); *out_size (may be NULL) gets the size. NULL after printing why. */
char* cli_read_text(const char* path, const char* what, size_t* out_size);
/* The lines of a text read whole, of any length: the next line from *cursor, cut in place at its
 * '\n' (and a '\r' before it), a UTF-8 byte-order mark removed from line 1; NULL after the
 * last. *lineno (start it at 0) counts the lines returned. */
char* cli_next_line(char** cursor, unsigned long long* lineno);

/* ---- outputs, Ctrl-C and progress (cli_output.c) ---- */

/* A file output written into a private temporary directory beside `path` (mkdtemp) and renamed
 * into place by cli_output_commit, so that an error or Ctrl-C never leaves a partial file and no
 * link planted beside the target is followed. "-" is stdout; an existing character device or
 * FIFO is written directly (no rename could keep it); directories, block devices and sockets
 * are refused. */
typedef struct cli_output {
    const char* path;
    char* tmp; /* the name written: inside dir, or path itself when direct; NULL for stdout */
    char* dir; /* the private temporary directory, NULL when direct or stdout */
    FILE* f;
    int slot;  /* registration for removal on a signal, -1 if none */
} cli_output;
/* Opens the temporary file (or stdout for "-"); prints the error and returns NULL on failure. */
FILE* cli_output_open(cli_output* o, const char* path);
/* Is path an existing character device or FIFO (written directly, its name picking no format)? */
bool cli_output_is_direct(const char* path);
/* Only makes the temporary name, for a library writer that takes a file name (o->tmp). */
bool cli_output_reserve(cli_output* o, const char* path);
/* Closes the output (checking every write) without renaming it: the complete temporary stays for
 * cli_output_set_commit. CLI_OK, or CLI_INPUT (error printed, temporary removed). */
int cli_output_close(cli_output* o);
/* Closes (checking every write) and renames into place; CLI_OK or CLI_INPUT (error printed,
 * temporary removed), or 130 when Ctrl-C came while polling and the work ended without looking
 * (the output is then removed, not renamed). */
int cli_output_commit(cli_output* o);
/* Closes and removes the temporary file. */
void cli_output_abort(cli_output* o);
/* After a library writer wrote o->tmp (cli_output_reserve) with status st: CLI_OK (the complete
 * temporary stays, not renamed), or the error printed under the user's file name, the temporary
 * removed and CLI_USAGE (invalid argument), CLI_INPUT, or 130 (TG_ERR_CANCELLED: interrupted). */
int cli_output_library_done(cli_output* o, tg_status st, const tg_diag* d);
/* After a library writer wrote o->tmp (cli_output_reserve) with status st: renames it into place,
 * or prints the error under the user's file name and removes it. CLI_OK, CLI_USAGE (invalid
 * argument), CLI_INPUT, or 130 (TG_ERR_CANCELLED: interrupted). */
int cli_output_finish_library(cli_output* o, tg_status st, const tg_diag* d);

/* A file every run checks before any work (cli_check_outputs): its path (NULL: the option was not
 * given; "-": stdin or stdout) and what it is, for messages ("mesh", "--boundaries"). */
typedef struct cli_file_role {
    const char* path;
    const char* what;
} cli_file_role;
/* The check every command makes before it reads or computes anything: each output is refused when
 * it is the same file as an input (device and inode, through symbolic and hard links: CLI_USAGE)
 * or as another output of the run (the same existing file, or the same name in the same folder,
 * or both "-": CLI_USAGE), when it is a directory, a block device or a socket, or when its folder
 * does not exist or cannot be written into (CLI_INPUT). CLI_OK, or the exit code after printing
 * why. At most CLI_OUTPUT_SET_MAX outputs. */
int cli_check_outputs(const cli_file_role* outputs, size_t output_count, const cli_file_role* inputs, size_t input_count);

/* The outputs of one run as one transaction: each written to its temporary name (the set's
 * open/reserve), then cli_output_set_commit renames them all into place only when every one was
 * written completely and every temporary is still there, holding Ctrl-C back during the renames;
 * on any failure none is renamed and every temporary is removed. Start from {0}. */
#define CLI_OUTPUT_SET_MAX 4
typedef struct cli_output_set {
    cli_output item[CLI_OUTPUT_SET_MAX];
    size_t count;
} cli_output_set;
/* A new member (NULL when the set is full). */
cli_output* cli_output_set_add(cli_output_set* s);
/* A new member opened for writing (cli_output_open); NULL after printing why. */
FILE* cli_output_set_open(cli_output_set* s, const char* path);
/* A new member with only its temporary name, for a library writer (cli_output_reserve, then
 * cli_output_library_done); NULL after printing why. */
cli_output* cli_output_set_reserve(cli_output_set* s, const char* path);
/* Closes every member, checks it, and renames all into place: CLI_OK, or CLI_INPUT after printing
 * why, nothing renamed (a failed rename, rare after the checks, is reported and the others kept). */
int cli_output_set_commit(cli_output_set* s);
/* Removes every member's temporary (after an error or Ctrl-C); the set is empty after. */
void cli_output_set_abort(cli_output_set* s);
/* OBJ polylines (path, trace, isolines, Voronoi boundaries): `v` records of count points (xyz:
 * 3 * count doubles, shortest decimals); an `l` record of the points first .. first + count - 1
 * (1-based in the file), the last replaced by the first when closed (a closed polyline ends on
 * its first vertex). false on a write error. */
bool cli_obj_vertices(FILE* f, const double* xyz, size_t count);
bool cli_obj_line(FILE* f, size_t first, size_t count, bool closed);
/* Does `path` end with `ext` (".json", ".csv", ...; case-insensitive)? The CLI's -o picks the
 * output format by extension. */
bool cli_ext_is(const char* path, const char* ext);
/* A surface point as JSON: {"kind": ..., ...} (strings: cli_json_string below). */
void cli_json_point(FILE* f, const tg_surface_point* p);

/* ---- NumPy .npy and .npz (cli_npy.c, cli_npz.c) ---- */

/* The longest .npy header cli_npy_write_header writes, and the most dimensions of a shape. */
#define CLI_NPY_HEADER_MAX 1024
#define CLI_NPY_DIMS_MAX 4
/* The .npy header of an array into out[0..cap): format version 1.0 (magic, version, header
 * length), the dict {'descr': DESCR, 'fortran_order': False, 'shape': (d0, d1, ...), } padded with
 * blanks and a newline so that the data starts at a multiple of 64 bytes. descr is a NumPy descr
 * literal ('<f8', or [('face', '<u4'), ...]); the shape is dims[0..ndim), ndim 0..CLI_NPY_DIMS_MAX
 * (written as NumPy writes a tuple: (), (n,), (a, b)). Returns the header's length, or 0 when it
 * does not fit in cap bytes. */
size_t cli_npy_header(char* out, size_t cap, const char* descr, int ndim, const unsigned long long* dims);
/* The same header written to f (at most CLI_NPY_HEADER_MAX bytes); false on a write error. */
bool cli_npy_write_header(FILE* f, const char* descr, int ndim, const unsigned long long* dims);
/* Writes a float64 array as NumPy .npy: (rows, cols) when matrix, else (cols,). */
bool cli_write_npy_f64(FILE* f, const double* data, size_t rows, size_t cols, bool matrix);
/* Is this file content a NumPy .npy file (its magic string)? */
bool cli_is_npy(const char* data, size_t size);
/* The header of .npy content, as read by cli_npy_read_header (pointers into the content). */
typedef struct cli_npy_info {
    const char* dict;  /* the header dict's text ... */
    size_t dict_len;   /* ... of this many bytes */
    size_t data_offset; /* where the data starts */
    const char* descr; /* the value of 'descr' as written ('<f8', [(...)], ...), in dict */
    bool fortran_order;
    const char* shape; /* the value of 'shape' as written, in dict ... */
    size_t shape_len;  /* ... through its ')' (0 when there is none) */
    int ndim;          /* the shape's length, -1 when it is not a tuple of at most CLI_NPY_DIMS_MAX integers */
    unsigned long long dims[CLI_NPY_DIMS_MAX];
} cli_npy_info;
/* Reads the framing of .npy content (format version 1.0, 2.0 or 3.0): the magic, the header length
 * within the content, a dict holding 'descr', 'fortran_order' (True or False) and 'shape'. What the
 * dtype and shape must be is the caller's to check. false after printing why ("NAME: .npy: ..."). */
bool cli_npy_read_header(const char* name, const char* data, size_t size, cli_npy_info* out);
/* The (k, 3) array of a .npy file's content, as k points: float64 or float32 (converted exactly),
 * little- or big-endian ('<f8', '>f8', '<f4', '>f4'), C or Fortran order; every other dtype or
 * shape, a bad header, truncated or excess data, a coordinate not finite or beyond +-1e150 is
 * refused with the file name and the reason (printed). Returns the count, or (size_t)-1 after
 * printing the error; *out is malloc'd (at least one element). */
size_t cli_read_npy_points(const char* name, const char* data, size_t size, double** out);
/* Writes a sparse matrix as the .npz archive scipy.sparse.load_npz reads (cli_npz.c). */
bool cli_write_npz_csr(FILE* f, const tg_sparse_matrix_view* v);

/* ---- numbers (cli_number.c) ---- */

/* Reading, the CLI's one rule for numbers (README.md "Numbers", as Python's float()): a number is
 * decimal text, [+-] digits [. digits] [(e|E) [+-] digits] (no hexadecimal, "inf" or "nan"), read
 * as the double nearest to it (strtod's correctly rounded result), subnormals included: text that
 * underflows is the subnormal or the 0 nearest to it, text beyond the largest double is refused
 * as not finite. Then each option checks its range. Blanks around a number are allowed. */
typedef enum cli_number_status {
    CLI_NUMBER_OK = 0,
    CLI_NUMBER_SYNTAX,   /* no decimal number at the start of the text */
    CLI_NUMBER_INFINITE  /* beyond +-1.7976931348623157e+308: not finite */
} cli_number_status;
/* The number at the start of s (blanks skipped); *end past it on success (at the number's start,
 * past the blanks, on a syntax error). */
cli_number_status cli_scan_double(const char* s, double* out, const char** end);
/* The whole of s is one number (blanks around allowed); false otherwise, *out untouched. */
bool cli_parse_double(const char* s, double* out);
/* The same, and >= 0 (an option's distance or length): -0, and negatives that underflow to it,
 * are read as 0. */
bool cli_parse_nonneg(const char* s, double* out);
/* Exactly n (1..16) numbers separated by commas ("X,Y,Z"; blanks around each allowed). */
bool cli_parse_doubles(const char* s, int n, double* out);
/* A non-negative decimal integer (digits only, no sign; blanks around allowed) within 64 bits. */
bool cli_parse_uint(const char* s, unsigned long long* out);

/* Writing: every number the CLI prints (CSV, JSON, OBJ, summaries) is the shortest decimal that
 * reads back (strtod) to exactly x, '\0'-terminated; at most 25 bytes with the terminator. Fixed
 * notation for decimal exponents -4 to 15 (as Python's repr), else d.ddde+XX / d.ddde-XX; "inf",
 * "-inf" and "nan" for the others. Returns the length. Thread-compatible: the first call fills
 * static tables (call it once before starting threads). */
int cli_format_double(double x, char* out);
/* The same in a value whose buffer lives to the end of the full expression that calls it (C11
 * 6.2.4p8), for printf: printf("%s,%s\n", cli_num(a).s, cli_num(b).s). */
typedef struct cli_num_text {
    char s[32];
} cli_num_text;
cli_num_text cli_num(double x);

/* Voronoi labels (trigeo field --labels, trigeo sample --field): per vertex the index of the nearest
 * source (-1 where none reaches) and its distance, as PLY vertex properties `label` and
 * `distance` (a .ply path) or CSV rows vertex,label,distance (anything else; '-' is stdout).
 * Written to a temporary name, a member of `set` (renamed by cli_output_set_commit); CLI_OK or
 * CLI_INPUT (error printed; the caller aborts the set). */
/* Named columns of n rows each (cols[c][i]) to path, a member of `set`: .ply the mesh with a
 * per-vertex double property a column (at most 16), .npy an (n, ncols) float64 array, else CSV
 * (and '-': stdout) with a header `index_name,names...` and the row index first. CLI_OK or
 * CLI_INPUT (error printed). */
int cli_write_columns(cli_output_set* set, const char* path, const tg_mesh* mesh, const char* index_name,
                      const char* const* names, const double* const* cols, size_t ncols, size_t n);
int cli_write_labels(cli_output_set* set, const char* path, const tg_mesh* mesh, const uint32_t* label, const double* dist,
                     size_t n);

/* ---- isolines (cli_isolines.c: trigeo field --isolines, trigeo render) ---- */

/* --isolines VALUE: a comma-separated list of levels (finite, >= 0; a number is always a level, so
 * "3" is the level 3). On success *out_levels (malloc'd) and *out_count. Prints the error (naming
 * `option`) and returns CLI_INPUT on a bad value. */
int cli_parse_levels(const char* option, const char* text, double** out_levels, size_t* out_count);
/* --isoline-count N: N (1..4096) levels equally spaced below the largest finite distance, filled
 * in later by cli_auto_levels; *out_levels (malloc'd, N zeros) and *out_count. Errors as above. */
int cli_parse_level_count(const char* option, const char* text, double** out_levels, size_t* out_count);
/* N levels max * k / (N + 1), k = 1..N, max the largest finite value of dist[0..n) (all 0 when
 * none is finite). */
void cli_auto_levels(const double* dist, size_t n, size_t count, double* out_levels);
/* Writes isolines to path: .obj ('v' records, a group 'g level_I' with a '# level L' comment per
 * level, an 'l' record per polyline, closed ones ending on their first vertex) or .json
 * ({"levels": [...], "polylines": [{"level": I, "value": L, "closed": B, "points": [[x, y, z],
 * ...], "faces": [...], "surface": ["e:H:t" | "f:F:b0,b1,b2", ...]}]}). Written to a temporary
 * name and renamed; CLI_OK or CLI_INPUT (error printed). */
int cli_write_isolines(const char* path, const tg_isolines* iso);
/* A surface point as a spec (cli_spec.c's syntax: v:I, e:H:t, f:F:b0,b1,b2; numbers as
 * cli_format_double writes them), at most CLI_SPEC_TEXT_MAX bytes with the terminator. */
#define CLI_SPEC_TEXT_MAX 112
void cli_spec_text(const tg_surface_point* p, char* buf, size_t cap);

/* Can `threads` threads (0: one per core) be started? Prints why not (naming `what`): OpenMP's
 * runtime would end the process instead of failing. */
bool cli_threads_available(int threads, const char* what);
/* --threads N of a command that runs one field (logmap, sample): NULL (not given) is 1, the
 * serial engine; 0 every core (TG_THREADS_ALL); at most TG_MAX_THREADS. CLI_OK with the count
 * for tg_field_options.threads in *out, else the exit code (usage printed, or the threads could
 * not be started). */
int cli_field_threads(const char* cmd, const char* text, int* out);

/* s as a JSON string: quotes and backslashes escaped, control characters as \u00XX, and bytes
 * that are not UTF-8 (a file name in another encoding) as U+FFFD, so the document stays valid. */
void cli_json_string(FILE* f, const char* s);

/* Past a leading UTF-8 byte-order mark, if any (text written by Windows tools). */
char* cli_skip_bom(char* text);

/* SIGINT and SIGTERM end the process with exit 130, removing the temporaries of the outputs
 * being written (installed for every command). While polling is on (work whose library call has
 * a progress hook that returns cli_interrupted()), the first signal only sets the flag and the
 * work ends itself, with exit 130; a second one ends the process at once. */
void cli_interrupt_install(void);
void cli_interrupt_polling(bool on);
bool cli_interrupted(void);

/* Seconds on the monotonic clock (for durations). */
double cli_seconds(void);
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
extern const cli_command cli_cmd_trace;
extern const cli_command cli_cmd_logmap;
extern const cli_command cli_cmd_sample;
extern const cli_command cli_cmd_compare;
extern const cli_command cli_cmd_mean;

#endif
