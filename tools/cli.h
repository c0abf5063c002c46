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
/* Usage error: message plus "see trigeo help CMD"; returns CLI_USAGE. */
int cli_usage(const char* cmd, const char* fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Parses a non-negative integer / a double option value; false on junk. */
bool cli_parse_uint(const char* s, unsigned long long* out);
bool cli_parse_double(const char* s, double* out);

/* A surface point as written on the command line (cli_spec.c). */
typedef struct cli_spec {
    int kind; /* 'v', 'f', 'e' or 'p' */
    unsigned long long index;
    double v[3];
} cli_spec;
/* Parses v:IDX | f:FACE:b0,b1,b2 | e:HALFEDGE:t | p:x,y,z; false on a syntax error. */
bool cli_parse_spec(const char* s, cli_spec* out);
/* Resolves a spec on the mesh (p: through the BVH *bvh, built on first use; the caller destroys
 * it). Prints the error and returns false when the location is invalid. */
bool cli_resolve_spec(const char* mesh_path, tg_mesh* mesh, tg_bvh** bvh, const char* text, const cli_spec* sp,
                      tg_surface_point* out);

/* Commands (one file each). */
extern const cli_command cli_cmd_info;
extern const cli_command cli_cmd_closest;
extern const cli_command cli_cmd_render;
extern const cli_command cli_cmd_path;
extern const cli_command cli_cmd_field;

#endif
