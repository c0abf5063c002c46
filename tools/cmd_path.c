/* cmd_path.c - `trigeo path MESH --from SPEC --to SPEC [-o PATH.obj] [--json] [--method M]`,
 * `trigeo path MESH --through "SPEC;SPEC;..." [--closed]` and
 * `trigeo path MESH --pairs PAIRS [-o OUT.csv] [--threads N] [--method M]`: geodesic paths between
 * surface points (one, or one through waypoints, written as an OBJ polyline or JSON; or a batch,
 * shared out among threads, as CSV with timings). */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* ---- output ---- */

/* JSON has no infinity: an unreachable path's lengths are null. */
static void json_number(FILE* f, double x)
{
    if (isfinite(x))
        fputs(cli_num(x).s, f);
    else
        fputs("null", f);
}

/* --through: the waypoints, where they are in the path's points (count + 1 entries when closed),
 * and whether the route is a loop. */
typedef struct waypoints {
    cli_spec_list list;
    size_t* at;
    bool closed;
} waypoints;

/* w: the waypoints of --through, NULL for --from/--to. */
static void print_json(FILE* f, const char* mesh_path, const char* method, const tg_path_view* v, const waypoints* w)
{
    fprintf(f, "{\n  \"mesh\": ");
    cli_json_string(f, mesh_path);
    fprintf(f, ",\n  \"method\": \"%s\",\n  \"status\": \"%s\",\n  \"global\": \"%s\",\n  \"length\": ", method,
            tg_path_status_name(v->status), tg_path_global_name(v->global));
    json_number(f, v->length);
    fprintf(f, ",\n  \"initial_length\": ");
    json_number(f, v->initial_length);
    fprintf(f, ",\n  \"max_angle_defect\": ");
    json_number(f, v->max_angle_defect);
    fprintf(f, ",\n  \"iterations\": %u,\n  \"point_count\": %zu,\n  \"points\": [", v->iterations, v->point_count);
    for (size_t i = 0; i < v->point_count; ++i) {
        fputs(i ? ",\n    " : "\n    ", f);
        cli_json_point(f, &v->points[i]);
    }
    fprintf(f, "%s],\n  \"xyz\": [", v->point_count ? "\n  " : "");
    for (size_t i = 0; i < v->point_count; ++i)
        fprintf(f, "%s[%s, %s, %s]", i ? ",\n    " : "\n    ", cli_num(v->xyz[3 * i]).s, cli_num(v->xyz[3 * i + 1]).s,
                cli_num(v->xyz[3 * i + 2]).s);
    fprintf(f, "%s],\n  \"faces\": [", v->point_count ? "\n  " : "");
    for (size_t i = 0; i + 1 < v->point_count; ++i) fprintf(f, "%s%u", i ? ", " : "", v->faces[i]);
    fprintf(f, "]");
    if (w && v->point_count) {
        fprintf(f, ",\n  \"closed\": %s,\n  \"waypoint_points\": [", w->closed ? "true" : "false");
        for (size_t i = 0; i < w->list.count + (w->closed ? 1 : 0); ++i) fprintf(f, "%s%zu", i ? ", " : "", w->at[i]);
        fprintf(f, "]");
    }
    fprintf(f, "\n}\n");
}

/* The OBJ polyline in tg_path_write_obj's layout (a comment, v records, one l record; only the
 * comment for an unreachable path), its numbers as the CLI writes every number (shortest that
 * reads back; the certificate %.3g as in the summary). */
static bool write_obj(FILE* f, const tg_path_view* v)
{
    bool ok = fprintf(f, "# trigeo geodesic path: %zu points, length %s, status %s, max angle defect %.3g rad\n",
                      v->point_count, cli_num(v->length).s, tg_path_status_name(v->status), v->max_angle_defect) > 0;
    ok = ok && cli_obj_vertices(f, v->xyz, v->point_count);
    return ok && (v->point_count < 2 || cli_obj_line(f, 0, v->point_count, false));
}

static void print_summary(FILE* f, tg_path_method method, const tg_path_view* v, const waypoints* w)
{
    int crossings = 0, vertices = 0;
    for (size_t i = 1; i + 1 < v->point_count; ++i) {
        crossings += v->points[i].kind == TG_SURFACE_EDGE;
        vertices += v->points[i].kind == TG_SURFACE_VERTEX;
    }
    /* endpoints (or consecutive waypoints) in different components: there is no path at all, proven
     * by the components, whatever the method (the view's global stays the library's "unproven") */
    bool none = v->status == TG_PATH_UNREACHABLE;
    fprintf(f, "status             %s\n", tg_path_status_name(v->status));
    fprintf(f, "global             %s\n",
            none ? (w ? "no path exists (two consecutive waypoints lie in different components)"
                      : "no path exists (the two points lie in different components)")
            : v->global == TG_PATH_PROVEN ? "proven shortest (exact check)"
            : method == TG_PATH_EXACT     ? "unproven (the exact method found no straight path here: see status)"
                                          : "unproven (locally shortest only; --certify or --method exact proves)");
    fprintf(f, "length             %s\n", cli_num(v->length).s);
    /* the exact method traces its path through the field: no edge path (the view repeats length) */
    if (none)
        fprintf(f, "edge path length   none (no path exists)\n");
    else if (method == TG_PATH_EXACT && v->edge_path_vertices == 0 && v->initial_length == v->length)
        fprintf(f, "edge path length   none (the exact method computes no edge path)\n");
    else
        fprintf(f, "edge path length   %s\n", cli_num(v->initial_length).s);
    fprintf(f, "points             %zu (%d edge crossings, %d vertex passages)\n", v->point_count, crossings, vertices);
    if (w && v->point_count)
        fprintf(f, "waypoints          %zu%s (the path bends there)\n", w->list.count, w->closed ? ", closed" : "");
    fprintf(f, "max angle defect   %.3g rad\n", v->max_angle_defect);
    fprintf(f, "iterations         %u\n", v->iterations);
}

/* Ctrl-C while a path is computed: the query's progress callback stops it (polling mode). */
static int on_progress(void* user, const tg_field_progress* p)
{
    (void)user, (void)p;
    return cli_interrupted();
}

/* The options with the callback, and polling on for the computation. */
static tg_path_options interruptible(const tg_path_options* o)
{
    tg_path_options c = *o;
    c.progress = on_progress;
    c.progress_user = NULL;
    return c;
}

/* ---- batch ---- */

/* Parses one PAIRS line into two surface points: "v SRC TGT" (vertices), "f F0 b0 b1 b2 F1 c0 c1
 * c2" (face points; the older "p" with these nine fields is read the same), "p x0 y0 z0 x1 y1 z1"
 * (positions, located on the surface); false after printing "PAIRS:LINE: message". */
static bool parse_pair(const char* name, unsigned long long line, char* s, tg_mesh* mesh, tg_bvh** bvh, int threads,
                       tg_surface_point* a, tg_surface_point* b)
{
    char* tok[9];
    int n = 0;
    bool extra = false; /* a tenth field, counted (not dropped) */
    for (char* t = strtok(s, " \t\r"); t && !extra; t = strtok(NULL, " \t\r")) {
        if (n == 9)
            extra = true;
        else
            tok[n++] = t;
    }
    unsigned long long i0, i1;
    double c[6];
    /* the six numbers: tokens 2-4 and 6-8 of the face form, 1-6 of the position form */
    static const int face_tok[6] = {2, 3, 4, 6, 7, 8}, pos_tok[6] = {1, 2, 3, 4, 5, 6};
    bool nums = (n == 9 || n == 7) && !extra;
    for (int k = 0; nums && k < 6; ++k) nums = cli_parse_double(tok[n == 9 ? face_tok[k] : pos_tok[k]], &c[k]);
    if (n == 3 && !extra && !strcmp(tok[0], "v") && cli_parse_uint(tok[1], &i0) && cli_parse_uint(tok[2], &i1)) {
        if (i0 > UINT32_MAX || i1 > UINT32_MAX) {
            cli_error(name, line, "vertex index out of range");
            return false;
        }
        *a = tg_surface_vertex((uint32_t)i0);
        *b = tg_surface_vertex((uint32_t)i1);
    } else if (n == 9 && nums && (!strcmp(tok[0], "f") || !strcmp(tok[0], "p")) && cli_parse_uint(tok[1], &i0) &&
               cli_parse_uint(tok[5], &i1)) {
        if (i0 > UINT32_MAX || i1 > UINT32_MAX) {
            cli_error(name, line, "face index out of range");
            return false;
        }
        *a = cli_face_point((uint32_t)i0, c);
        *b = cli_face_point((uint32_t)i1, c + 3);
    } else if (n == 7 && nums && !strcmp(tok[0], "p")) {
        for (int k = 0; k < 6; ++k)
            if (fabs(c[k]) > 1e150) {
                cli_error(name, line, "coordinate %s is beyond the supported range of +-1e150 (squared distances "
                          "would overflow)", cli_num(c[k]).s);
                return false;
            }
        const char* why = NULL;
        /* the BVH on the command's threads, as the paths (--threads 1: this thread only) */
        tg_bvh_options bo;
        memset(&bo, 0, sizeof bo);
        bo.threads = threads;
        tg_status st = *bvh || tg_mesh_face_count(mesh) == 0 ? TG_OK : tg_bvh_create(mesh, &bo, bvh);
        if (st != TG_OK) why = tg_status_string(st);
        if (st != TG_OK || !cli_locate(mesh, bvh, c, a, &why) || !cli_locate(mesh, bvh, c + 3, b, &why)) {
            cli_error(name, line, "cannot locate the positions on the surface: %s", why);
            return false;
        }
    } else {
        /* the number of fields, when the form is known and they are too many or too few */
        bool v = !strcmp(tok[0], "v"), f = !strcmp(tok[0], "f"), p = !strcmp(tok[0], "p");
        if (extra || (v && n != 3) || (f && n != 9) || (p && n != 7 && n != 9))
            cli_error(name, line, "%s%d fields, %s (\"v SRC TGT\", \"f F0 b0 b1 b2 F1 c0 c1 c2\" or \"p x0 y0 z0 x1 y1 z1\")",
                      extra ? "more than " : "", n, v ? "a \"v\" line has 3" : f ? "an \"f\" line has 9" : p ? "a \"p\" line has 7 or 9"
                      : "at most 9");
        else
            cli_error(name, line, "expected \"v SRC TGT\", \"f F0 b0 b1 b2 F1 c0 c1 c2\" or \"p x0 y0 z0 x1 y1 z1\"");
        return false;
    }
    tg_diag d;
    for (int e = 0; e < 2; ++e) {
        memset(&d, 0, sizeof d);
        if (tg_surface_point_validate(mesh, e ? b : a, &d) != TG_OK) {
            cli_error(name, line, "%s point: %s", e ? "second" : "first", d.message[0] ? d.message : "invalid");
            return false;
        }
    }
    return true;
}

/* One pair of the PAIRS file, parsed before any path is computed. */
typedef struct pair_in {
    tg_surface_point a, b;
    unsigned long long line;
} pair_in;

/* Reads and validates every pair (a leading BOM, blank lines and '#' comments skipped; the BVH
 * that locates positions built on the first "p" pair, on `threads` threads); returns the count,
 * or -1 after printing "PAIRS:LINE: message". */
static long read_pairs(const char* pairs_path, tg_mesh* mesh, tg_bvh** bvh, int threads, pair_in** out)
{
    char* all = cli_read_text(pairs_path, "pairs file", NULL);
    if (!all) return -1;
    size_t n = 0, cap = 256;
    pair_in* pairs = malloc(cap * sizeof *pairs);
    unsigned long long lineno = 0;
    long result = -1;
    char* cursor = all;
    bool oom = !pairs;
    for (char* text; !oom && (text = cli_next_line(&cursor, &lineno));) {
        const char* p = text + strspn(text, " \t\r");
        if (!*p || *p == '#') continue;
        if ((oom = !cli_grow((void**)&pairs, &cap, n + 1, sizeof *pairs))) break;
        if (!parse_pair(pairs_path, lineno, text, mesh, bvh, threads, &pairs[n].a, &pairs[n].b)) goto done;
        pairs[n++].line = lineno;
    }
    if (oom) /* (a file of exactly 256, 512, ... pairs was once refused here too) */
        cli_error(pairs_path, lineno, "out of memory");
    else
        result = (long)n;
done:
    free(all);
    if (result < 0) free(pairs), pairs = NULL;
    *out = pairs;
    return result;
}

/* One pair's row of the CSV, kept until the rows before it are written (the pairs finish in any
 * order on several threads; the rows go out in input order). */
typedef struct pair_out {
    double length, max_angle_defect, microseconds;
    size_t point_count;
    tg_path_status status;
    tg_path_global global;
    bool done;
} pair_out;

/* The batch shared by the threads: the pairs, their rows, the output, and the first pair that
 * failed (n when none): pairs after it are skipped, the ones before it still computed and
 * written, so that the rows written and the pair named by the error are the serial run's. */
typedef struct pairs_batch {
    const tg_geodesic* geo;
    const pair_in* pairs;
    long n;
    tg_path_options options;
    pair_out* out;
    FILE* f;
    long written;      /* rows written, in input order (under the lock) */
    atomic_long stop;  /* the lowest failing pair, n when none */
    tg_status* status; /* per pair, the error of a failing one */
#ifdef _OPENMP
    omp_lock_t lock; /* held while a row is stored and the rows ready are written */
#endif
} pairs_batch;

/* Writes the rows finished in a row from b->written on (called under b->lock). */
static void write_ready_rows(pairs_batch* b)
{
    long stop = atomic_load(&b->stop);
    for (; b->written < stop && b->out[b->written].done; ++b->written) {
        const pair_out* r = &b->out[b->written];
        fprintf(b->f, "%ld,%s,%zu,%s,%s,%.3f,%s\n", b->written, cli_num(r->length).s, r->point_count,
                tg_path_status_name(r->status), cli_num(r->max_angle_defect).s, r->microseconds,
                tg_path_global_name(r->global));
    }
}

/* Pair i on the calling thread's workspace and path; a failure lowers b->stop to i. */
static void compute_pair(pairs_batch* b, long i, tg_geodesic_workspace* ws, tg_path* path)
{
    double t0 = cli_seconds();
    tg_status st = cli_interrupted() ? TG_ERR_CANCELLED
                                     : tg_geodesic_path(b->geo, ws, &b->pairs[i].a, &b->pairs[i].b, &b->options, path);
    double us = 1e6 * (cli_seconds() - t0);
    if (st != TG_OK) {
        b->status[i] = st;
        for (long s = atomic_load(&b->stop); i < s && !atomic_compare_exchange_weak(&b->stop, &s, i);) {
        }
        return;
    }
    tg_path_view v;
    tg_path_get_view(path, &v);
#ifdef _OPENMP
    omp_set_lock(&b->lock);
#endif
    b->out[i] = (pair_out){v.length, v.max_angle_defect, us, v.point_count, v.status, v.global, true};
    write_ready_rows(b);
#ifdef _OPENMP
    omp_unset_lock(&b->lock);
#endif
}

static int run_pairs(const char* mesh_path, const char* pairs_path, const char* out_path, const tg_path_options* o,
                     int threads)
{
    int rc = CLI_INPUT;
    tg_geodesic* geo = NULL;
    tg_geodesic_workspace** ws = NULL;
    tg_path** path = NULL;
    pair_in* pairs = NULL;
    pairs_batch b;
    memset(&b, 0, sizeof b);
    tg_bvh* bvh = NULL; /* for "p" position pairs, built on first use */
    cli_output out;
    bool opened = false;
    int nt = 1; /* threads: --threads, 0 the OpenMP default (one per core), at most one per pair */
#ifdef _OPENMP
    nt = threads > 0 ? threads : omp_get_max_threads();
#endif
    tg_mesh* mesh = cli_load_mesh_for_distances(mesh_path);
    if (!mesh) goto done;
    /* every pair is checked before any output exists */
    long n = read_pairs(pairs_path, mesh, &bvh, threads, &pairs);
    if (n < 0) goto done;
    if (nt > n) nt = n > 0 ? (int)n : 1;
    b.out = calloc((size_t)(n ? n : 1), sizeof *b.out); /* none done */
    b.status = malloc((size_t)(n ? n : 1) * sizeof *b.status);
    ws = calloc((size_t)nt, sizeof *ws);
    path = calloc((size_t)nt, sizeof *path);
    tg_status st = b.out && b.status && ws && path ? TG_OK : TG_ERR_OUT_OF_MEMORY;
    if (st == TG_OK) st = tg_geodesic_create(mesh, NULL, &geo);
    for (int t = 0; t < nt && st == TG_OK; ++t) {
        st = tg_geodesic_workspace_create(geo, &ws[t]);
        if (st == TG_OK) st = tg_path_create(NULL, &path[t]);
    }
    if (st != TG_OK) {
        cli_error(mesh_path, 0, "%s", tg_status_string(st));
        goto done;
    }
    FILE* f = cli_output_open(&out, out_path ? out_path : "-");
    if (!f) goto done;
    opened = true;
    fprintf(f, "i,length,points,status,max_angle_defect,microseconds,global\n");
    b.geo = geo, b.pairs = pairs, b.n = n, b.options = interruptible(o), b.f = f;
    atomic_init(&b.stop, n);
    cli_interrupt_polling(true);
#ifdef _OPENMP
    omp_init_lock(&b.lock);
#pragma omp parallel num_threads(nt)
#endif
    {
        int t = 0;
#ifdef _OPENMP
        t = omp_get_thread_num();
#pragma omp for schedule(dynamic, 1)
#endif
        for (long i = 0; i < n; ++i)
            if (i < atomic_load(&b.stop)) compute_pair(&b, i, ws[t], path[t]);
    }
#ifdef _OPENMP
    omp_destroy_lock(&b.lock);
#endif
    long stop = atomic_load(&b.stop);
    if (stop < n && b.status[stop] == TG_ERR_CANCELLED) {
        cli_error(pairs_path, pairs[stop].line, "interrupted: nothing written");
        rc = 130;
        goto done;
    }
    if (stop < n) {
        cli_error(pairs_path, pairs[stop].line, "%s", tg_status_string(b.status[stop]));
        goto done;
    }
    cli_interrupt_polling(false);
    opened = false;
    rc = cli_output_commit(&out);
done:
    cli_interrupt_polling(false);
    if (opened) cli_output_abort(&out);
    free(pairs);
    free(b.out);
    free(b.status);
    tg_bvh_destroy(bvh);
    for (int t = 0; path && t < nt; ++t) tg_path_destroy(path[t]);
    for (int t = 0; ws && t < nt; ++t) tg_geodesic_workspace_destroy(ws[t]);
    free(path);
    free(ws);
    tg_geodesic_destroy(geo);
    tg_mesh_destroy(mesh);
    return rc;
}

/* --from with curve sources (`curve:FILE`, `boundary`, and point SPECs beside them): the exact path
 * from the nearest of them to --to (tg_geodesic_curve_path). */
typedef struct curve_from {
    cli_curves curves;
    char** items; /* the point SPECs of the list */
    size_t count;
} curve_from;

static int run_single(const char* mesh_path, const char* from, const char* to, waypoints* through,
                      const curve_from* cf, const char* out_path, bool json, const char* method_name,
                      const tg_path_options* o)
{
    cli_spec sa, sb;
    if (!through && !cf && !cli_parse_spec(from, &sa)) return cli_usage("path", "bad --from '%s' (v:IDX, f:FACE:b0,b1,b2, e:HALFEDGE:t or p:x,y,z)", from);
    if (!through && !cli_parse_spec(to, &sb)) return cli_usage("path", "bad --to '%s' (v:IDX, f:FACE:b0,b1,b2, e:HALFEDGE:t or p:x,y,z)", to);
    int rc = CLI_INPUT;
    tg_bvh* bvh = NULL;
    tg_geodesic* geo = NULL;
    tg_geodesic_workspace* ws = NULL;
    tg_path* path = NULL;
    tg_surface_segment* seg = NULL; /* cf: the curves' segments and the point sources */
    tg_surface_point* cpts = NULL;
    size_t nseg = 0;
    tg_mesh* mesh = cli_load_mesh_for_distances(mesh_path);
    tg_surface_point a, b;
    if (!mesh) goto done;
    if (tg_mesh_face_count(mesh) == 0) {
        cli_error(mesh_path, 0, "the mesh has no faces");
        goto done;
    }
    if (through ? !cli_spec_list_resolve(mesh_path, mesh, &bvh, &through->list)
                : (!cf && !cli_resolve_spec(mesh_path, mesh, &bvh, from, &sa, &a)) ||
                      !cli_resolve_spec(mesh_path, mesh, &bvh, to, &sb, &b))
        goto done;
    tg_status st = tg_geodesic_create(mesh, NULL, &geo);
    if (st == TG_OK && cf) {
        cpts = malloc((cf->count ? cf->count : 1) * sizeof *cpts);
        if (!cpts) {
            cli_error(NULL, 0, "out of memory");
            goto done;
        }
        if ((rc = cli_resolve_items("path", mesh_path, NULL, false, mesh, &bvh, cf->items, NULL, cf->count, cpts)) !=
                CLI_OK ||
            (rc = cli_curve_segments("path", mesh_path, &cf->curves, mesh, &bvh, geo, &seg, &nseg, NULL)) != CLI_OK)
            goto done;
        rc = CLI_INPUT;
    }
    if (st == TG_OK) st = tg_geodesic_workspace_create(geo, &ws);
    if (st == TG_OK) st = tg_path_create(NULL, &path);
    tg_path_options oi = interruptible(o);
    cli_interrupt_polling(true);
    if (st == TG_OK && through) {
        size_t n = through->list.count;
        st = tg_geodesic_path_through(geo, ws, through->list.point, n, through->closed ? TG_PATH_CLOSED : TG_PATH_OPEN,
                                      &oi, path, through->at);
    } else if (st == TG_OK && cf) {
        st = tg_geodesic_curve_path(geo, ws, cpts, cf->count, seg, nseg, &b, &oi, path);
    } else if (st == TG_OK) {
        st = tg_geodesic_path(geo, ws, &a, &b, &oi, path);
    }
    cli_interrupt_polling(false);
    if (st == TG_ERR_CANCELLED) {
        cli_error(mesh_path, 0, "interrupted: nothing written");
        rc = 130;
        goto done;
    }
    if (st != TG_OK) {
        cli_error(mesh_path, 0, "%s", tg_status_string(st));
        goto done;
    }
    tg_path_view v;
    tg_path_get_view(path, &v);
    if (out_path && cli_ext_is(out_path, ".json")) { /* the JSON document to a file */
        cli_output out;
        FILE* f = cli_output_open(&out, out_path);
        if (!f) goto done;
        print_json(f, mesh_path, method_name, &v, through);
        if (cli_output_commit(&out) != CLI_OK) goto done;
    } else if (out_path) { /* the OBJ polyline, to a temporary name renamed when complete */
        cli_output out;
        FILE* f = cli_output_open(&out, out_path);
        if (!f) goto done;
        if (!write_obj(f, &v)) {
            cli_error(out_path, 0, "write failed: %s", strerror(errno));
            cli_output_abort(&out);
            goto done;
        }
        if (cli_output_commit(&out) != CLI_OK) goto done;
    }
    if (json)
        print_json(stdout, mesh_path, method_name, &v, through);
    else
        print_summary(stdout, o->method, &v, through);
    rc = fflush(stdout) == 0 ? CLI_OK : CLI_INPUT;
done:
    free(seg), free(cpts);
    tg_path_destroy(path);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(geo);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(mesh);
    return rc;
}

/* ---- --bezier ---- */

#define BEZIER_DEFAULT_SAMPLES 101u
#define BEZIER_MAX_SAMPLES 10000000u

static void print_bezier_json(FILE* f, const char* mesh_path, const cli_spec_list* ctrl, const tg_surface_point* pts,
                              const double* xyz, size_t n)
{
    fprintf(f, "{\n  \"mesh\": ");
    cli_json_string(f, mesh_path);
    fprintf(f, ",\n  \"controls\": [");
    for (size_t i = 0; i < ctrl->count; ++i) {
        fputs(i ? ", " : "", f);
        cli_json_point(f, &ctrl->point[i]);
    }
    fprintf(f, "],\n  \"samples\": %zu,\n  \"points\": [", n);
    for (size_t i = 0; i < n; ++i) {
        fputs(i ? ",\n    " : "\n    ", f);
        cli_json_point(f, &pts[i]);
    }
    fprintf(f, "\n  ],\n  \"xyz\": [");
    for (size_t i = 0; i < n; ++i)
        fprintf(f, "%s[%s, %s, %s]", i ? ",\n    " : "\n    ", cli_num(xyz[3 * i]).s, cli_num(xyz[3 * i + 1]).s,
                cli_num(xyz[3 * i + 2]).s);
    fprintf(f, "\n  ]\n}\n");
}

/* `--bezier "SPEC;...": the geodesic Bezier curve of the control points, sampled. */
static int run_bezier(const char* mesh_path, cli_spec_list* ctrl, size_t samples, tg_bezier_method method,
                      const char* out_path, bool json)
{
    int rc = CLI_INPUT;
    tg_bvh* bvh = NULL;
    tg_geodesic* geo = NULL;
    tg_surface_point* pts = malloc(samples * sizeof *pts);
    double* xyz = malloc(3 * samples * sizeof *xyz);
    tg_mesh* mesh = pts && xyz ? cli_load_mesh_for_distances(mesh_path) : NULL;
    if (!pts || !xyz) cli_error(NULL, 0, "out of memory");
    if (!mesh) goto done;
    if (tg_mesh_face_count(mesh) == 0) {
        cli_error(mesh_path, 0, "the mesh has no faces");
        goto done;
    }
    if (!cli_spec_list_resolve(mesh_path, mesh, &bvh, ctrl)) goto done;
    tg_status st = tg_geodesic_create(mesh, NULL, &geo);
    tg_path_options o;
    memset(&o, 0, sizeof o);
    o = interruptible(&o);
    cli_interrupt_polling(true);
    if (st == TG_OK) st = tg_geodesic_bezier_with(geo, NULL, ctrl->point, ctrl->count, samples, method, &o, pts, xyz);
    cli_interrupt_polling(false);
    if (st == TG_ERR_CANCELLED) {
        cli_error(mesh_path, 0, "interrupted: nothing written");
        rc = 130;
        goto done;
    }
    if (st == TG_ERR_INVALID_ARGUMENT) { /* every point was resolved: what is left is where they lie */
        cli_error(mesh_path, 0, "the control points lie in different components of the mesh: no path joins them");
        goto done;
    }
    if (st != TG_OK) {
        cli_error(mesh_path, 0, "%s", tg_status_string(st));
        goto done;
    }
    if (out_path) {
        cli_output out;
        FILE* f = cli_output_open(&out, out_path);
        if (!f) goto done;
        bool ok = true;
        if (cli_ext_is(out_path, ".json")) {
            print_bezier_json(f, mesh_path, ctrl, pts, xyz, samples);
        } else {
            ok = fprintf(f, "# trigeo geodesic Bezier curve: %zu control points, %zu samples\n", ctrl->count, samples) > 0;
            ok = ok && cli_obj_vertices(f, xyz, samples) && cli_obj_line(f, 0, samples, false);
        }
        if (!ok) {
            cli_error(out_path, 0, "write failed: %s", strerror(errno));
            cli_output_abort(&out);
            goto done;
        }
        if (cli_output_commit(&out) != CLI_OK) goto done;
    }
    if (json) {
        print_bezier_json(stdout, mesh_path, ctrl, pts, xyz, samples);
    } else if (!(out_path && !strcmp(out_path, "-"))) {
        double len = 0.0;
        for (size_t i = 0; i + 1 < samples; ++i) {
            const double *a = xyz + 3 * i, *b = a + 3;
            len += sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
        }
        printf("control points     %zu (degree %zu)\n", ctrl->count, ctrl->count - 1);
        printf("samples            %zu\n", samples);
        printf("polyline length    %s\n", cli_num(len).s);
    }
    rc = fflush(stdout) == 0 ? CLI_OK : CLI_INPUT;
done:
    free(pts);
    free(xyz);
    tg_geodesic_destroy(geo);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(mesh);
    return rc;
}

static int run(int argc, char** argv)
{
    const char *mesh_path = NULL, *from = NULL, *to = NULL, *pairs = NULL, *out_path = NULL, *method = NULL;
    const char *through = NULL, *threads = NULL, *bezier = NULL, *samples = NULL, *bezier_method = NULL;
    bool json = false, certify = false, closed = false;
    tg_path_options o;
    memset(&o, 0, sizeof o);
    for (int i = 1; i < argc; ++i) {
        const char* a = argv[i];
        if (!strcmp(a, "--from") || !strcmp(a, "--to") || !strcmp(a, "--pairs") || !strcmp(a, "-o") ||
            !strcmp(a, "--method") || !strcmp(a, "--through") || !strcmp(a, "--threads") || !strcmp(a, "--bezier") ||
            !strcmp(a, "--samples") || !strcmp(a, "--bezier-method")) {
            if (i + 1 >= argc) return cli_usage("path", "%s needs a value", a);
            const char* val = argv[++i];
            if (!strcmp(a, "--from"))
                from = val;
            else if (!strcmp(a, "--to"))
                to = val;
            else if (!strcmp(a, "--pairs"))
                pairs = val;
            else if (!strcmp(a, "-o"))
                out_path = val;
            else if (!strcmp(a, "--through"))
                through = val;
            else if (!strcmp(a, "--threads"))
                threads = val;
            else if (!strcmp(a, "--bezier"))
                bezier = val;
            else if (!strcmp(a, "--samples"))
                samples = val;
            else if (!strcmp(a, "--bezier-method"))
                bezier_method = val;
            else
                method = val;
        } else if (!strcmp(a, "--json")) {
            json = true;
        } else if (!strcmp(a, "--certify")) {
            certify = true;
        } else if (!strcmp(a, "--closed")) {
            closed = true;
        } else if (a[0] == '-' && a[1]) {
            return cli_usage("path", "unknown option '%s'", a);
        } else if (!mesh_path) {
            mesh_path = a;
        } else {
            return cli_usage("path", "unexpected argument '%s'", a);
        }
    }
    if (samples && !bezier) return cli_usage("path", "--samples applies to --bezier");
    if (bezier_method && !bezier) return cli_usage("path", "--bezier-method applies to --bezier");
    if (bezier) {
        if (from || to || pairs || through || closed || threads)
            return cli_usage("path", "--bezier excludes --from, --to, --pairs, --through, --closed and --threads");
        if ((method && strcmp(method, "exact")) || certify)
            return cli_usage("path", "--bezier interpolates along exact paths (proven): --method and --certify do not apply");
        unsigned long long ns = BEZIER_DEFAULT_SAMPLES;
        if (samples && (!cli_parse_uint(samples, &ns) || ns < 2 || ns > BEZIER_MAX_SAMPLES))
            return cli_usage("path", "--samples needs a number in 2..%u, not '%s'", BEZIER_MAX_SAMPLES, samples);
        tg_bezier_method bm = TG_BEZIER_PATHS;
        if (bezier_method && !strcmp(bezier_method, "logmap"))
            bm = TG_BEZIER_LOG_MAP;
        else if (bezier_method && strcmp(bezier_method, "paths"))
            return cli_usage("path", "--bezier-method takes paths or logmap, not '%s'", bezier_method);
        if (!mesh_path) return cli_usage("path", "missing MESH");
        if (out_path && !cli_ext_is(out_path, ".obj") && !cli_ext_is(out_path, ".json"))
            return cli_usage("path", "-o takes B.obj (the polyline) or B.json (the surface points too)");
        if (json && out_path && !strcmp(out_path, "-")) return cli_usage("path", "--json and -o - both write to stdout");
        const cli_file_role inputs[1] = {{mesh_path, "mesh"}};
        const cli_file_role outputs[1] = {{out_path, "-o"}};
        int rc = cli_check_outputs(outputs, 1, inputs, 1);
        if (rc != CLI_OK) return rc;
        cli_spec_list ctrl = {NULL, NULL, NULL, NULL, 0};
        rc = cli_spec_list_parse("path", "--bezier", bezier, &ctrl);
        if (rc == CLI_OK) rc = run_bezier(mesh_path, &ctrl, (size_t)ns, bm, out_path, json);
        cli_spec_list_free(&ctrl);
        return rc;
    }
    if (through) {
        if (from || to || pairs) return cli_usage("path", "--through excludes --from, --to and --pairs");
        if ((method && strcmp(method, "exact")) || certify)
            return cli_usage("path", "--through joins exact paths (proven): --method and --certify do not apply");
    } else if (closed) {
        return cli_usage("path", "--closed applies to --through");
    }
    if (!method) method = "exact";
    if (!strcmp(method, "exact"))
        o.method = TG_PATH_EXACT;
    else if (!strcmp(method, "straighten"))
        o.method = TG_PATH_STRAIGHTEN;
    else if (!strcmp(method, "relax"))
        o.method = TG_PATH_RELAX;
    else if (!strcmp(method, "edge"))
        o.method = TG_PATH_EDGE;
    else
        return cli_usage("path", "--method must be exact, straighten, relax or edge, not '%s'", method);
    if (certify) o.certify = TG_PATH_CERTIFY_ON;
    if (!mesh_path) return cli_usage("path", "missing MESH");
    const cli_file_role inputs[2] = {{mesh_path, "mesh"}, {pairs, "pairs file (--pairs)"}};
    const cli_file_role outputs[1] = {{out_path, "-o"}};
    if (pairs) {
        if (from || to) return cli_usage("path", "--pairs excludes --from and --to");
        if (json) return cli_usage("path", "--json applies to a single path (--from/--to)");
        unsigned long long nt = 0;
        if (threads && (!cli_parse_uint(threads, &nt) || nt > TG_MAX_THREADS))
            return cli_usage("path", "--threads needs a number in 0..%d (0 = all cores), not '%s'", TG_MAX_THREADS, threads);
        int rc = cli_check_outputs(outputs, 1, inputs, 2);
        if (rc != CLI_OK) return rc;
        if (out_path && strcmp(out_path, "-") && !cli_ext_is(out_path, ".csv"))
            return cli_usage("path", "--pairs writes CSV: -o OUT.csv ('-': stdout), not '%s'", out_path);
        if (!cli_threads_available((int)nt, "path")) return CLI_INPUT;
        return run_pairs(mesh_path, pairs, out_path, &o, (int)nt);
    }
    if (threads) return cli_usage("path", "--threads applies to --pairs");
    if (!through && (!from || !to)) return cli_usage("path", "missing %s (or --pairs FILE)", from ? "--to" : "--from");
    if (out_path && !cli_ext_is(out_path, ".obj") && !cli_ext_is(out_path, ".json"))
        return cli_usage("path", "-o takes PATH.obj (the polyline) or PATH.json (the whole answer)");
    int rc = cli_check_outputs(outputs, 1, inputs, 1);
    if (rc != CLI_OK) return rc;
    if (!through && from && (strchr(from, ';') || !strcmp(from, "boundary") || !strncmp(from, "curve:", 6))) {
        /* curve sources: `curve:FILE`, `boundary`, with point SPECs beside them */
        char* list = strdup(from);
        curve_from cf;
        memset(&cf, 0, sizeof cf);
        cf.items = malloc(CLI_SPEC_LIST_MAX * sizeof *cf.items);
        if (!list || !cf.items) {
            free(list), free(cf.items);
            cli_error(NULL, 0, "out of memory");
            return CLI_INPUT;
        }
        size_t all = cli_split_list(list, cf.items, CLI_SPEC_LIST_MAX);
        for (size_t i = 0; i < all; ++i)
            if (!cli_curve_item(cf.items[i], &cf.curves)) cf.items[cf.count++] = cf.items[i];
        cli_file_role roles[1 + CLI_CURVES_MAX];
        roles[0] = inputs[0];
        for (size_t i = 0; i < cf.curves.count && i < CLI_CURVES_MAX; ++i)
            roles[1 + i] = (cli_file_role){cf.curves.files[i], "curve file (--from curve:)"};
        if (!all || (!cf.curves.count && !cf.curves.boundary))
            rc = cli_usage("path", "bad --from list \"%s\": one SPEC, or curves (curve:FILE, boundary) with SPECs", from);
        else if (cf.curves.count > CLI_CURVES_MAX)
            rc = cli_usage("path", "at most %d curve files", CLI_CURVES_MAX);
        else if (o.method != TG_PATH_EXACT || o.certify)
            rc = cli_usage("path", "a path from curves is exact (proven): --method and --certify do not apply");
        else
            rc = cli_check_outputs(outputs, 1, roles, 1 + cf.curves.count);
        if (rc == CLI_OK) rc = run_single(mesh_path, from, to, NULL, &cf, out_path, json, method, &o);
        free(list), free(cf.items);
        return rc;
    }
    if (!through) return run_single(mesh_path, from, to, NULL, NULL, out_path, json, method, &o);
    waypoints w = {{NULL, NULL, NULL, NULL, 0}, NULL, closed};
    rc = cli_spec_list_parse("path", "--through", through, &w.list);
    if (rc == CLI_OK && !(w.at = malloc((w.list.count + 1) * sizeof *w.at))) {
        cli_error(NULL, 0, "out of memory");
        rc = CLI_INPUT;
    }
    if (rc == CLI_OK) rc = run_single(mesh_path, NULL, NULL, &w, NULL, out_path, json, method, &o);
    cli_spec_list_free(&w.list);
    free(w.at);
    return rc;
}

const cli_command cli_cmd_path = {
    "path",
    "path MESH ((--from SPEC|curve:FILE|boundary --to SPEC | --through \"SPEC;SPEC;...\" [--closed]) [-o PATH.obj|.json] [--json] |\n"
    "       --pairs PAIRS [-o OUT.csv] [--threads N]) [--method M] [--certify] |\n"
    "       --bezier \"SPEC;SPEC;...\" [--bezier-method paths|logmap] [--samples N] [-o B.obj|.json] [--json]",
    "Geodesic paths on the surface between any two surface points (never snapped to a vertex): by\n"
    "default the globally shortest path, proven by an exact window propagation; or, faster, the\n"
    "shortest edge path (A*) with the endpoints inserted virtually, then shortened.\n\n"
    "  --from SPEC, --to SPEC   endpoints:  v:IDX            a vertex\n"
    "                                       f:FACE:b0,b1,b2  a point of a face (barycentric; within 1e-6\n"
    "                                                    of summing to 1 they are rescaled)\n"
    "                                       e:HALFEDGE:t     a point of an edge (halfedge 3*face+corner)\n"
    "                                       p:x,y,z          the surface point closest to x,y,z\n"
    "  --from \"curve:FILE;boundary;SPEC...\"  the exact path to --to from the nearest point of curves\n"
    "                           (a curve file as trigeo field --from curve:FILE reads it; boundary:\n"
    "                           the mesh's boundary) and of the SPECs; it starts where it leaves\n"
    "                           them (at right angles from a segment's inside)\n"
    "  --through \"SPEC;SPEC;...\" the shortest route through these points in this order: the exact\n"
    "                           paths between consecutive points, each proven, joined into one\n"
    "                           path (quote the list: ';' is special to the shell)\n"
    "  --closed                 with --through: back to the first point too (a loop)\n"
    "  --bezier \"SPEC;SPEC;...\"  the geodesic Bezier curve of these control points (degree: their\n"
    "                           count - 1): de Casteljau on the surface, each interpolation taken\n"
    "                           along the exact shortest path (proven) between two points; on a flat\n"
    "                           region the planar Bezier curve. Written as an OBJ polyline of the\n"
    "                           samples (-o B.obj) or JSON with their surface points (-o B.json,\n"
    "                           --json); from the first control point to the last\n"
    "  --bezier-method M        with --bezier: paths (default: the point at fraction t of the exact\n"
    "                           shortest path) or logmap (exp_a(t log_a(b)): the trace from a along\n"
    "                           the exact log map's direction to b for t times the distance; the\n"
    "                           same where the path passes no vertex)\n"
    "  --samples N              with --bezier: N points at t = 0, 1/(N-1), ..., 1 (default 101)\n"
    "  -o PATH.obj|PATH.json    write the path as an OBJ polyline (v and l records), or the\n"
    "                           JSON document of --json (the format follows the extension)\n"
    "  --json                   print surface points, faces, 3D points, length, status, certificate\n"
    "  --pairs PAIRS            batch: one pair a line: \"v SRC TGT\" (vertices), \"f F0 b0 b1 b2 F1 c0 c1 c2\"\n"
    "                           (face points; \"p\" with these nine fields is read the same) or\n"
    "                           \"p x0 y0 z0 x1 y1 z1\" (the surface points closest to two positions);\n"
    "                           CSV i,length,points,status,max_angle_defect,microseconds,global to\n"
    "                           stdout or -o OUT.csv (only .csv; '-' reads PAIRS from stdin)\n"
    "  --threads N              with --pairs: the pairs shared out among N threads, at most 256 (0:\n"
    "                           one per core, the default); the rows in input order, each the same\n"
    "                           for any N (but its microseconds)\n"
    "  --method M               exact (default: the globally shortest path, proven: an exact window\n"
    "                           propagation from the source ordered toward the target (A*) and\n"
    "                           bounded by the best distance to it found so far, traced back from\n"
    "                           the target through the windows and pseudo-source vertices),\n"
    "                           straighten (faster on far pairs, locally shortest, unproven: funnel\n"
    "                           over unfolded strips of the edge path, vertex re-routing),\n"
    "                           relax (the seed's relaxation), edge (the initial edge path only)\n"
    "  --certify                after straighten, relax or edge, check against the exact distance: a\n"
    "                           path within 1e-9 of it is proven, a longer one is replaced by the\n"
    "                           exact path (redundant with exact)\n\n"
    "global: proven when an exact computation showed no path shorter by 1e-9 relative exists\n"
    "(--method exact, the default, or --certify), else unproven (locally shortest, possibly not\n"
    "globally).\n"
    "Status is converged, iteration_cap, unreachable (endpoints in different components: no path\n"
    "exists, the summary says so; no points, length inf, JSON length null, global unproven) or\n"
    "stalled (straighten's certificate exceeds 1e-8 rad; never proven).\n"
    "Timings of the methods: BENCHMARKS.md. The certificate (max angle\n"
    "defect, radians) is the largest deviation from straightness over edge crossings and vertex\n"
    "passages. Indices are 0-based in file order. Ctrl-C stops the computation (exit 130, no\n"
    "file written).\n",
    run,
};
