/* cmd_trace.c - `trigeo trace MESH --from SPEC (--dir X,Y,Z | --angle A) --length L [-o OUT.obj|.json]
 * [--json]` and `trigeo trace MESH --batch TRACES [-o OUT.csv] [--threads N]`: geodesics walked
 * straight from surface points (the exponential map), as a summary, an OBJ polyline or a JSON
 * document; or many, as a CSV of their ends.
 * Based on: the CLI contract of the project's DESIGN.md (SPEC, exit codes, outputs written
 *   whole); tg_geodesic_trace (include/trigeo.h). */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* What the command line asked for. */
typedef struct trace_args {
    const char *mesh_path, *from, *dir_text, *out_path, *batch_path;
    tg_trace_direction dir;
    double length;
    tg_trace_options options;
    int threads;
    bool json;
} trace_args;

/* Ctrl-C while traces are walked: the walk's progress callback stops it (polling mode). */
static int on_progress(void* user, const tg_field_progress* p)
{
    (void)user, (void)p;
    return cli_interrupted();
}

/* The options with Ctrl-C as cancellation, and polling on for the walks (interrupted() ends it). */
static tg_trace_options interruptible(const trace_args* ta)
{
    tg_trace_options o = ta->options;
    o.progress = on_progress;
    o.progress_user = NULL;
    cli_interrupt_polling(true);
    return o;
}

/* Polling off; true (after saying so) when the walks were interrupted. */
static bool interrupted(const trace_args* ta, tg_status st)
{
    cli_interrupt_polling(false);
    if (st != TG_ERR_CANCELLED) return false;
    cli_error(ta->mesh_path, 0, "interrupted: nothing written");
    return true;
}

/* ---- output ---- */

static void json_xyz(FILE* f, const double* p)
{
    fprintf(f, "[%s, %s, %s]", cli_num(p[0]).s, cli_num(p[1]).s, cli_num(p[2]).s);
}

static void print_json(FILE* f, const trace_args* ta, const tg_trace_view* v)
{
    const tg_trace_end* e = &v->end;
    fprintf(f, "{\n  \"mesh\": ");
    cli_json_string(f, ta->mesh_path);
    fprintf(f, ",\n  \"status\": \"%s\",\n  \"length\": %s,\n  \"requested_length\": %s,\n  \"end\": {\"point\": ",
            tg_trace_status_name(e->status), cli_num(e->length).s, cli_num(ta->length).s);
    cli_json_point(f, &e->point);
    fprintf(f, ", \"xyz\": ");
    json_xyz(f, e->xyz);
    fprintf(f, ", \"direction\": ");
    json_xyz(f, e->direction);
    fprintf(f, ", \"face\": %u},\n  \"crossings\": %llu,\n  \"vertices\": %u,\n  \"branches\": %u,\n  \"branch_points\": [",
            e->face, (unsigned long long)e->crossings, e->vertices, e->branches);
    for (size_t i = 0; i < v->branch_count; ++i) fprintf(f, "%s%zu", i ? ", " : "", v->branch_points[i]);
    fprintf(f, "],\n  \"point_count\": %zu,\n  \"points\": [", v->point_count);
    for (size_t i = 0; i < v->point_count; ++i) {
        fputs(i ? ",\n    " : "\n    ", f);
        cli_json_point(f, &v->points[i]);
    }
    fprintf(f, "\n  ],\n  \"xyz\": [");
    for (size_t i = 0; i < v->point_count; ++i) {
        fputs(i ? ",\n    " : "\n    ", f);
        json_xyz(f, v->xyz + 3 * i);
    }
    fprintf(f, "\n  ],\n  \"faces\": [");
    for (size_t i = 0; i + 1 < v->point_count; ++i) fprintf(f, "%s%u", i ? ", " : "", v->faces[i]);
    fprintf(f, "]\n}\n");
}

static void print_obj(FILE* f, const tg_trace_view* v)
{
    fprintf(f, "# trigeo geodesic trace: %zu points, length %s, status %s\n", v->point_count, cli_num(v->end.length).s,
            tg_trace_status_name(v->end.status));
    cli_obj_vertices(f, v->xyz, v->point_count); /* write errors: checked when the output is committed */
    cli_obj_line(f, 0, v->point_count, false);
}

static void print_summary(FILE* f, const tg_trace_view* v)
{
    const tg_trace_end* e = &v->end;
    fprintf(f, "status             %s\n", tg_trace_status_name(e->status));
    fprintf(f, "length             %s\n", cli_num(e->length).s);
    fprintf(f, "end                ");
    cli_print_spec(f, &e->point);
    fprintf(f, "\nend xyz            %s %s %s\n", cli_num(e->xyz[0]).s, cli_num(e->xyz[1]).s, cli_num(e->xyz[2]).s);
    fprintf(f, "end direction      %s %s %s\n", cli_num(e->direction[0]).s, cli_num(e->direction[1]).s,
            cli_num(e->direction[2]).s);
    fprintf(f, "end face           %u\n", e->face);
    fprintf(f, "points             %zu (%llu edge crossings, %u vertex passages)\n", v->point_count,
            (unsigned long long)e->crossings, e->vertices);
    fprintf(f, "non-manifold edges %u (the walk took the straightest face at each)\n", e->branches);
}

/* ---- the trace ---- */

/* Why the library refused a direction it was given (the arguments were checked before). */
static int refused(const trace_args* ta)
{
    if (ta->dir.kind == TG_TRACE_VECTOR)
        return cli_usage("trace", "--dir %s is perpendicular to the surface at --from %s (within 1e-9 radians of the "
                                  "normal there, or pointing off the surface at its boundary)", ta->dir_text, ta->from);
    return cli_usage("trace", "--angle is measured in the start point's reference face, which has zero area here: give "
                              "--dir X,Y,Z instead");
}

static int write_output(const trace_args* ta, const tg_trace_view* v)
{
    cli_output out;
    FILE* f = cli_output_open(&out, ta->out_path);
    if (!f) return CLI_INPUT;
    if (cli_ext_is(ta->out_path, ".json"))
        print_json(f, ta, v);
    else
        print_obj(f, v);
    return cli_output_commit(&out);
}

static int run_trace(const trace_args* ta)
{
    cli_spec sp;
    if (!cli_parse_spec(ta->from, &sp))
        return cli_usage("trace", "bad --from '%s' (v:IDX, f:FACE:b0,b1,b2, e:HALFEDGE:t or p:x,y,z)", ta->from);
    int rc = CLI_INPUT;
    tg_bvh* bvh = NULL;
    tg_geodesic* geo = NULL;
    tg_trace* trace = NULL;
    tg_surface_point start;
    tg_mesh* mesh = cli_load_mesh_for_distances(ta->mesh_path);
    if (!mesh) goto done;
    if (tg_mesh_face_count(mesh) == 0) {
        cli_error(ta->mesh_path, 0, "the mesh has no faces");
        goto done;
    }
    if (!cli_resolve_spec(ta->mesh_path, mesh, &bvh, ta->from, &sp, &start)) goto done;
    tg_status st = tg_geodesic_create(mesh, NULL, &geo);
    if (st == TG_OK) st = tg_trace_create(NULL, &trace);
    tg_trace_options o = interruptible(ta);
    if (st == TG_OK) st = tg_geodesic_trace(geo, &start, &ta->dir, ta->length, &o, trace);
    if (interrupted(ta, st)) {
        rc = 130;
        goto done;
    }
    if (st == TG_ERR_INVALID_ARGUMENT) {
        rc = refused(ta);
        goto done;
    }
    if (st != TG_OK) {
        cli_error(ta->mesh_path, 0, "%s", tg_status_string(st));
        goto done;
    }
    tg_trace_view v;
    tg_trace_get_view(trace, &v);
    if (ta->out_path && write_output(ta, &v) != CLI_OK) goto done;
    if (ta->json)
        print_json(stdout, ta, &v);
    else
        print_summary(stdout, &v);
    rc = fflush(stdout) == 0 ? CLI_OK : CLI_INPUT;
done:
    tg_trace_destroy(trace);
    tg_geodesic_destroy(geo);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(mesh);
    return rc;
}

/* X,Y,Z: three finite numbers, not all zero. */
static bool parse_vector(const char* s, double out[3])
{
    return cli_parse_doubles(s, 3, out) && (out[0] != 0.0 || out[1] != 0.0 || out[2] != 0.0);
}

/* ---- the batch ---- */

/* One line of a TRACES file, parsed before any walk. */
typedef struct trace_in {
    tg_surface_point start;
    tg_trace_direction dir;
    double length;
} trace_in;

/* Parses "SPEC DIRECTION LENGTH" (DIRECTION: X,Y,Z or an angle in radians); false after printing
 * "TRACES:LINE: message". */
static bool parse_trace_line(const char* name, unsigned long long line, char* s, tg_mesh* mesh, tg_bvh** bvh,
                             trace_in* out)
{
    char* tok[3];
    int n = 0;
    /* every field counted: a fourth one is refused, not dropped */
    for (char* t = strtok(s, " \t\r"); t; t = strtok(NULL, " \t\r")) {
        if (n == 3) {
            cli_error(name, line, "unexpected '%s' after the length (\"SPEC X,Y,Z LENGTH\" or \"SPEC ANGLE LENGTH\": three "
                      "fields)", t);
            return false;
        }
        tok[n++] = t;
    }
    if (n != 3) {
        cli_error(name, line, "expected \"SPEC X,Y,Z LENGTH\" or \"SPEC ANGLE LENGTH\" (three fields, not %d)", n);
        return false;
    }
    cli_spec sp;
    if (!cli_parse_spec(tok[0], &sp)) {
        cli_error(name, line, "bad start '%s' (v:IDX, f:FACE:b0,b1,b2, e:HALFEDGE:t or p:x,y,z)", tok[0]);
        return false;
    }
    memset(&out->dir, 0, sizeof out->dir);
    if (strchr(tok[1], ',')) {
        out->dir.kind = TG_TRACE_VECTOR;
        if (!parse_vector(tok[1], out->dir.vector)) {
            cli_error(name, line, "bad direction '%s' (X,Y,Z: three finite numbers, not all zero)", tok[1]);
            return false;
        }
    } else {
        out->dir.kind = TG_TRACE_ANGLE;
        if (!cli_parse_double(tok[1], &out->dir.angle)) {
            cli_error(name, line, "bad direction '%s' (X,Y,Z or an angle: finite radians)", tok[1]);
            return false;
        }
    }
    if (!cli_parse_nonneg(tok[2], &out->length)) {
        cli_error(name, line, "bad length '%s' (a finite number >= 0)", tok[2]);
        return false;
    }
    char where[4096]; /* the start's errors (a vertex out of range, ...) name the line too */
    snprintf(where, sizeof where, "%s:%llu", name, line);
    return cli_resolve_spec(where, mesh, bvh, tok[0], &sp, &out->start);
}

/* Reads every line of TRACES (a leading BOM, blank lines and '#' comments skipped) into *out and
 * their line numbers into *out_lines; returns the count, or -1 after printing the error. */
static long read_traces(const char* path, tg_mesh* mesh, tg_bvh** bvh, trace_in** out, unsigned long long** out_lines)
{
    char* all = cli_read_text(path, "traces file", NULL);
    if (!all) return -1;
    size_t n = 0, cap = 256, lcap = 256;
    trace_in* items = malloc(cap * sizeof *items);
    unsigned long long* lines = malloc(lcap * sizeof *lines);
    unsigned long long lineno = 0;
    long result = -1;
    char* cursor = all;
    bool oom = !items || !lines;
    for (char* text; !oom && (text = cli_next_line(&cursor, &lineno));) {
        const char* p = text + strspn(text, " \t\r");
        if (!*p || *p == '#') continue;
        if ((oom = !cli_grow((void**)&items, &cap, n + 1, sizeof *items) || !cli_grow((void**)&lines, &lcap, n + 1, sizeof *lines)))
            break;
        if (!parse_trace_line(path, lineno, text, mesh, bvh, &items[n])) goto done;
        lines[n++] = lineno;
    }
    if (oom) /* (a file of exactly 256, 512, ... traces was once refused here too) */
        cli_error(path, lineno, "out of memory");
    else
        result = (long)n;
done:
    free(all);
    if (result < 0) free(items), free(lines), items = NULL, lines = NULL;
    *out = items;
    *out_lines = lines;
    return result;
}

/* The library refused the batch: find the first entry it refuses alone, to name its line. */
static void name_refused_line(const tg_geodesic* geo, const char* path, const trace_in* items,
                              const unsigned long long* lines, long n)
{
    for (long i = 0; i < n; ++i) {
        tg_trace_end e;
        if (tg_geodesic_trace_batch(geo, &items[i].start, &items[i].dir, &items[i].length, 1, NULL, 1, &e) != TG_OK) {
            cli_error(path, lines[i], items[i].dir.kind == TG_TRACE_VECTOR
                                          ? "the direction is perpendicular to the surface at the start"
                                          : "the angle is measured in the start's reference face, which has zero area: "
                                            "give X,Y,Z instead");
            return;
        }
    }
    cli_error(path, 0, "the traces were refused");
}

static void csv_spec(FILE* f, const tg_surface_point* p)
{
    fputc('"', f); /* f: and e: specs hold commas */
    cli_print_spec(f, p);
    fputc('"', f);
}

static int run_batch(const trace_args* ta)
{
    int rc = CLI_INPUT;
    tg_bvh* bvh = NULL;
    tg_geodesic* geo = NULL;
    trace_in* items = NULL;
    unsigned long long* lines = NULL;
    tg_surface_point* starts = NULL;
    tg_trace_direction* dirs = NULL;
    double* lengths = NULL;
    tg_trace_end* ends = NULL;
    tg_mesh* mesh = cli_load_mesh_for_distances(ta->mesh_path);
    if (!mesh) goto done;
    long n = read_traces(ta->batch_path, mesh, &bvh, &items, &lines);
    if (n < 0) goto done;
    size_t k = (size_t)n;
    starts = malloc((k + 1) * sizeof *starts), dirs = malloc((k + 1) * sizeof *dirs);
    lengths = malloc((k + 1) * sizeof *lengths), ends = malloc((k + 1) * sizeof *ends);
    if (!starts || !dirs || !lengths || !ends) {
        cli_error(NULL, 0, "out of memory");
        goto done;
    }
    for (size_t i = 0; i < k; ++i) starts[i] = items[i].start, dirs[i] = items[i].dir, lengths[i] = items[i].length;
    tg_status st = tg_geodesic_create(mesh, NULL, &geo);
    tg_trace_options o = interruptible(ta);
    if (st == TG_OK) st = tg_geodesic_trace_batch(geo, starts, dirs, lengths, k, &o, ta->threads, ends);
    if (interrupted(ta, st)) {
        rc = 130;
        goto done;
    }
    if (st == TG_ERR_INVALID_ARGUMENT && geo) {
        name_refused_line(geo, ta->batch_path, items, lines, n);
        goto done;
    }
    if (st != TG_OK) {
        cli_error(ta->mesh_path, 0, "%s", tg_status_string(st));
        goto done;
    }
    cli_output out;
    FILE* f = cli_output_open(&out, ta->out_path ? ta->out_path : "-");
    if (!f) goto done;
    fprintf(f, "i,status,length,crossings,vertices,branches,face,x,y,z,dx,dy,dz,end\n");
    for (size_t i = 0; i < k; ++i) {
        const tg_trace_end* e = &ends[i];
        fprintf(f, "%zu,%s,%s,%llu,%u,%u,%u,%s,%s,%s,%s,%s,%s,", i, tg_trace_status_name(e->status), cli_num(e->length).s,
                (unsigned long long)e->crossings, e->vertices, e->branches, e->face, cli_num(e->xyz[0]).s,
                cli_num(e->xyz[1]).s, cli_num(e->xyz[2]).s, cli_num(e->direction[0]).s, cli_num(e->direction[1]).s,
                cli_num(e->direction[2]).s);
        csv_spec(f, &e->point);
        fputc('\n', f);
    }
    rc = cli_output_commit(&out);
done:
    free(items), free(lines), free(starts), free(dirs), free(lengths), free(ends);
    tg_geodesic_destroy(geo);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(mesh);
    return rc;
}

/* ---- the command line ---- */

static int run(int argc, char** argv)
{
    trace_args ta;
    memset(&ta, 0, sizeof ta);
    const char *angle = NULL, *length = NULL, *steps = NULL, *threads = NULL;
    for (int i = 1; i < argc; ++i) {
        const char* a = argv[i];
        const char** slot = !strcmp(a, "--from") ? &ta.from : !strcmp(a, "--dir") ? &ta.dir_text
                            : !strcmp(a, "--angle") ? &angle : !strcmp(a, "--length") ? &length
                            : !strcmp(a, "-o") ? &ta.out_path : !strcmp(a, "--max-steps") ? &steps
                            : !strcmp(a, "--batch") ? &ta.batch_path : !strcmp(a, "--threads") ? &threads : NULL;
        if (slot) {
            if (i + 1 >= argc) return cli_usage("trace", "%s needs a value", a);
            *slot = argv[++i];
        } else if (!strcmp(a, "--json")) {
            ta.json = true;
        } else if (a[0] == '-' && a[1]) {
            return cli_usage("trace", "unknown option '%s'", a);
        } else if (!ta.mesh_path) {
            ta.mesh_path = a;
        } else {
            return cli_usage("trace", "unexpected argument '%s'", a);
        }
    }
    if (!ta.mesh_path) return cli_usage("trace", "missing MESH");
    unsigned long long ms = 0, nt = 0;
    if (steps && (!cli_parse_uint(steps, &ms) || ms == 0))
        return cli_usage("trace", "bad --max-steps '%s' (an integer >= 1)", steps);
    ta.options.max_steps = ms;
    if (ta.batch_path) {
        if (ta.from || ta.dir_text || angle || length || ta.json)
            return cli_usage("trace", "--batch TRACES excludes --from, --dir, --angle, --length and --json");
        if (threads && (!cli_parse_uint(threads, &nt) || nt > TG_MAX_THREADS))
            return cli_usage("trace", "--threads needs a number in 0..%d (0 = all cores), not '%s'", TG_MAX_THREADS,
                             threads);
        ta.threads = (int)nt;
        if (ta.out_path && !cli_ext_is(ta.out_path, ".csv")) return cli_usage("trace", "--batch writes OUT.csv");
        const cli_file_role inputs[2] = {{ta.mesh_path, "mesh"}, {ta.batch_path, "traces file (--batch)"}};
        const cli_file_role outputs[1] = {{ta.out_path, "-o"}};
        int check = cli_check_outputs(outputs, 1, inputs, 2);
        if (check != CLI_OK) return check;
        if (!cli_threads_available(ta.threads, "trace")) return CLI_INPUT;
        return run_batch(&ta);
    }
    if (threads) return cli_usage("trace", "--threads applies to --batch");
    if (!ta.from) return cli_usage("trace", "missing --from SPEC");
    if (!ta.dir_text == !angle) return cli_usage("trace", "give the direction as --dir X,Y,Z or as --angle RADIANS (one of them)");
    if (ta.dir_text) {
        ta.dir.kind = TG_TRACE_VECTOR;
        if (!parse_vector(ta.dir_text, ta.dir.vector))
            return cli_usage("trace", "bad --dir '%s' (X,Y,Z: three finite numbers, not all zero)", ta.dir_text);
    } else {
        ta.dir.kind = TG_TRACE_ANGLE;
        if (!cli_parse_double(angle, &ta.dir.angle)) return cli_usage("trace", "bad --angle '%s' (finite radians)", angle);
    }
    if (!length) return cli_usage("trace", "missing --length L");
    if (!cli_parse_nonneg(length, &ta.length))
        return cli_usage("trace", "bad --length '%s' (a finite number >= 0)", length);
    if (ta.out_path && !cli_ext_is(ta.out_path, ".obj") && !cli_ext_is(ta.out_path, ".json"))
        return cli_usage("trace", "-o takes OUT.obj (the polyline) or OUT.json (the whole answer)");
    const cli_file_role inputs[1] = {{ta.mesh_path, "mesh"}}, outputs[1] = {{ta.out_path, "-o"}};
    int check = cli_check_outputs(outputs, 1, inputs, 1);
    return check != CLI_OK ? check : run_trace(&ta);
}

const cli_command cli_cmd_trace = {
    "trace",
    "trace MESH (--from SPEC (--dir X,Y,Z | --angle A) --length L [-o OUT.obj|.json] [--json] |\n"
    "       --batch TRACES [-o OUT.csv] [--threads N]) [--max-steps N]",
    "The exponential map: a geodesic walked straight from a surface point for a given length,\n"
    "across the faces as they unfold, through a vertex as the straightest geodesic (half the\n"
    "vertex's angle on each side: straight on where the surface is flat), stopping at the\n"
    "boundary.\n\n"
    "  --from SPEC      the start:  v:IDX            a vertex\n"
    "                               f:FACE:b0,b1,b2  a point of a face (barycentric; within 1e-6\n"
    "                                                of summing to 1 they are rescaled)\n"
    "                               e:HALFEDGE:t     a point of an edge (halfedge 3*face+corner)\n"
    "                               p:x,y,z          the surface point closest to x,y,z\n"
    "  --dir X,Y,Z      the direction as a 3D vector of any length: its projection onto the start\n"
    "                   face, or at an edge or vertex onto the tangent plane there (the faces'\n"
    "                   angle-weighted normal), taken in the face it projects from; refused when\n"
    "                   it is perpendicular to the surface (within 1e-9 radians of the normal)\n"
    "  --angle A        or as an angle in radians, counterclockwise (in the face's winding) from\n"
    "                   corner 0 towards corner 1 of the face of f:, along the halfedge of e:, or\n"
    "                   from the vertex's first halfedge for v: (its angle sum scaled to 2 pi)\n"
    "  --length L       how far to walk (the mesh's unit, >= 0)\n"
    "  -o OUT.obj|.json the polyline as an OBJ (v and l records), or the JSON document of --json\n"
    "  --json           print the end (point, xyz, direction, face), the status, the length\n"
    "                   walked, the points (surface points and xyz) and the face of each segment\n"
    "  --max-steps N    stop after entering N faces (default: 16 times the faces, plus 65536)\n"
    "  --batch TRACES   many traces: one a line, \"SPEC X,Y,Z LENGTH\" or \"SPEC ANGLE LENGTH\" ('#'\n"
    "                   comments, blank lines skipped; '-' = stdin), every line checked before any\n"
    "                   walk; writes the CSV  i,status,length,crossings,vertices,branches,face,\n"
    "                   x,y,z,dx,dy,dz,end  (the end point and direction; end is its SPEC, quoted)\n"
    "                   to OUT.csv or stdout\n"
    "  --threads N      with --batch: walk on N threads, at most 256 (0: one per core, the default)\n\n"
    "Status: complete, boundary (the walk reached a boundary edge or boundary vertex), singular (a\n"
    "vertex with no straightest continuation: non-manifold, pinched, next to a zero-length edge),\n"
    "step_limit or stalled (over 1000 zero-area faces in a row). At a non-manifold edge the walk\n"
    "takes the face where it runs straightest in space (JSON: branch_points; the face taken is\n"
    "faces[i] at each). Indices are 0-based in file order.\n",
    run,
};
