/* cmd_mean.c - `trigeo mean MESH --points FILE [--weights FILE] [--start SPEC] [--tolerance T]
 * [--max-iterations N] [--json] [-o OUT.json] [--quiet]`: the weighted geodesic (Karcher) mean of
 * surface points, as a summary or a JSON document.
 * Based on: the CLI contract of the project's DESIGN.md (SPEC, exit codes, outputs written
 *   whole, Ctrl-C, progress); tg_geodesic_mean (include/trigeo.h). */
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct mean_args {
    const char *mesh_path, *points_path, *weights_path, *start_text, *out_path;
    tg_mean_options options;
    bool json, quiet;
} mean_args;

/* A file's items: its lines without blanks around them, blank lines and '#' comments skipped,
 * each with its line number (text: the file read whole, split in place). */
typedef struct lines {
    char* text;
    char** item;
    unsigned long long* line;
    size_t count;
} lines;

static void lines_free(lines* l)
{
    free(l->text), free(l->item), free(l->line);
    memset(l, 0, sizeof *l);
}

/* Reads `path`'s items; false after printing why (the file, or it has none). */
static bool read_items(const char* path, const char* what, const char* form, lines* out)
{
    memset(out, 0, sizeof *out);
    size_t size = 0;
    out->text = cli_read_text(path, what, &size);
    if (!out->text) return false;
    size_t cap = 1;
    for (size_t i = 0; i < size; ++i) cap += out->text[i] == '\n';
    out->item = malloc(cap * sizeof *out->item);
    out->line = malloc(cap * sizeof *out->line);
    if (!out->item || !out->line) {
        cli_error(path, 0, "out of memory");
        lines_free(out);
        return false;
    }
    char* cursor = out->text;
    unsigned long long lineno = 0;
    for (char* s; (s = cli_next_line(&cursor, &lineno));) {
        s += strspn(s, " \t");
        size_t l = strlen(s);
        while (l && (s[l - 1] == ' ' || s[l - 1] == '\t')) s[--l] = '\0';
        if (!l || s[0] == '#') continue;
        out->item[out->count] = s, out->line[out->count++] = lineno;
    }
    if (out->count == 0) {
        cli_error(path, 0, "no %s (%s)", what, form);
        lines_free(out);
        return false;
    }
    return true;
}

#define POINT_FORMS "one SPEC a line: v:IDX, f:FACE:b0,b1,b2, e:HALFEDGE:t or p:x,y,z, or x y z"

/* The points file resolved on the mesh: CLI_OK or CLI_INPUT (error printed, naming the line). */
static int resolve_points(const char* path, const lines* l, tg_mesh* mesh, tg_bvh** bvh, tg_surface_point* out)
{
    for (size_t i = 0; i < l->count; ++i) {
        cli_spec sp;
        if (!cli_parse_spec(l->item[i], &sp) && !cli_parse_xyz(l->item[i], &sp)) {
            cli_error(path, l->line[i], "bad point '%s' (%s)", l->item[i], POINT_FORMS);
            return CLI_INPUT;
        }
        char where[4096];
        snprintf(where, sizeof where, "%s:%llu", path, l->line[i]);
        if (!cli_resolve_spec(where, mesh, bvh, l->item[i], &sp, &out[i])) return CLI_INPUT;
    }
    return CLI_OK;
}

/* The weights file: one number >= 0 a line, as many as the points, not all 0. */
static int read_weights(const char* path, size_t count, double** out)
{
    lines l;
    if (!read_items(path, "weights", "one number >= 0 a line, one per point", &l)) return CLI_INPUT;
    int rc = CLI_OK;
    double* w = malloc(l.count * sizeof *w);
    if (!w) cli_error(path, 0, "out of memory"), rc = CLI_INPUT;
    double sum = 0.0;
    for (size_t i = 0; rc == CLI_OK && i < l.count; ++i) {
        if (!cli_parse_double(l.item[i], &w[i]) || !(w[i] >= 0.0)) {
            cli_error(path, l.line[i], "bad weight '%s' (a number >= 0)", l.item[i]);
            rc = CLI_INPUT;
        }
        sum += rc == CLI_OK ? w[i] : 0.0;
    }
    if (rc == CLI_OK && l.count != count) {
        cli_error(path, l.line[l.count - 1], "%zu weights for %zu points (one a line, in the points' order)", l.count, count);
        rc = CLI_INPUT;
    }
    if (rc == CLI_OK && !(sum > 0.0 && sum < INFINITY)) {
        cli_error(path, 0, sum > 0.0 ? "the weights' sum is not finite" : "every weight is 0 (at least one must be positive)");
        rc = CLI_INPUT;
    }
    lines_free(&l);
    if (rc != CLI_OK) free(w), w = NULL;
    *out = w;
    return rc;
}

/* ---- output ---- */

static const char* uniqueness_text(tg_mean_uniqueness u)
{
    return u == TG_MEAN_UNIQUE ? "unique (certified: the faces within 4R form a disc without cone vertices)"
         : u == TG_MEAN_NOT_CHECKED ? "not checked"
                                    : "not certified (a cone vertex, a hole or a handle within 4R: maybe unique, maybe not)";
}

static void print_summary(FILE* f, const tg_mean_result* r, size_t count, double secs)
{
    char spec[CLI_SPEC_TEXT_MAX];
    cli_spec_text(&r->point, spec, sizeof spec);
    fprintf(f, "mean               %s\n", spec);
    fprintf(f, "xyz                %s %s %s\n", cli_num(r->xyz[0]).s, cli_num(r->xyz[1]).s, cli_num(r->xyz[2]).s);
    fprintf(f, "points             %zu\n", count);
    fprintf(f, "status             %s\n", tg_mean_status_name(r->status));
    fprintf(f, "iterations         %u (%u halved)\n", r->iterations, r->halvings);
    fprintf(f, "gradient norm      %s\n", cli_num(r->gradient_norm).s);
    fprintf(f, "energy             %s (weighted mean squared distance)\n", cli_num(r->energy).s);
    fprintf(f, "radius             %s (farthest point)\n", cli_num(r->radius).s);
    fprintf(f, "uniqueness         %s\n", uniqueness_text(r->uniqueness));
    fprintf(f, "fields             %u\n", r->fields);
    fprintf(f, "seconds            %.3f\n", secs);
}

static void print_json(FILE* f, const char* mesh_path, const tg_mean_result* r, size_t count)
{
    fprintf(f, "{\n  \"mesh\": ");
    cli_json_string(f, mesh_path);
    fprintf(f, ",\n  \"points\": %zu,\n  \"mean\": ", count);
    cli_json_point(f, &r->point);
    fprintf(f, ",\n  \"xyz\": [%s, %s, %s],\n  \"status\": \"%s\",\n  \"iterations\": %u,\n  \"halvings\": %u,\n",
            cli_num(r->xyz[0]).s, cli_num(r->xyz[1]).s, cli_num(r->xyz[2]).s, tg_mean_status_name(r->status),
            r->iterations, r->halvings);
    fprintf(f, "  \"gradient_norm\": %s,\n  \"energy\": %s,\n  \"radius\": %s,\n  \"uniqueness\": \"%s\",\n  \"fields\": %u\n}\n",
            cli_num(r->gradient_norm).s, cli_num(r->energy).s, cli_num(r->radius).s,
            tg_mean_uniqueness_name(r->uniqueness), r->fields);
}

static int on_progress(void* user, const tg_field_progress* p)
{
    char detail[96];
    snprintf(detail, sizeof detail, "step %zu, front at distance %.6g", p->rows_done, p->front_distance);
    cli_progress_update(user, p->settled_fraction, detail);
    return cli_interrupted();
}

static int run_mean(const mean_args* ma)
{
    int rc = CLI_INPUT;
    tg_bvh* bvh = NULL;
    tg_geodesic* geo = NULL;
    tg_surface_point* pts = NULL;
    double* w = NULL;
    lines pl = {0};
    tg_mesh* mesh = cli_load_mesh_for_distances(ma->mesh_path);
    if (!mesh) goto done;
    if (tg_mesh_face_count(mesh) == 0) {
        cli_error(ma->mesh_path, 0, "the mesh has no faces");
        goto done;
    }
    if (!read_items(ma->points_path, "points", POINT_FORMS, &pl)) goto done;
    if (!(pts = malloc(pl.count * sizeof *pts))) {
        cli_error(NULL, 0, "out of memory");
        goto done;
    }
    if (resolve_points(ma->points_path, &pl, mesh, &bvh, pts) != CLI_OK) goto done;
    if (ma->weights_path && read_weights(ma->weights_path, pl.count, &w) != CLI_OK) goto done;
    tg_mean_options o = ma->options;
    tg_surface_point start;
    if (ma->start_text) {
        cli_spec sp;
        if (!cli_parse_spec(ma->start_text, &sp)) { /* (checked before the mesh was read) */
            rc = CLI_USAGE;
            goto done;
        }
        if (!cli_resolve_spec(ma->mesh_path, mesh, &bvh, ma->start_text, &sp, &start)) goto done;
        o.start = &start;
    }
    tg_status st = tg_geodesic_create(mesh, NULL, &geo);
    if (st != TG_OK) {
        cli_error(ma->mesh_path, 0, "%s", tg_status_string(st));
        goto done;
    }
    cli_progress prog;
    cli_progress_start(&prog, "mean", ma->quiet);
    o.progress = on_progress;
    o.progress_user = &prog;
    tg_mean_result r;
    double t0 = cli_seconds();
    cli_interrupt_polling(true);
    st = tg_geodesic_mean(geo, NULL, pts, w, pl.count, &o, &r);
    cli_interrupt_polling(false);
    cli_progress_end(&prog);
    double secs = cli_seconds() - t0;
    if (st == TG_ERR_CANCELLED) {
        cli_error(ma->mesh_path, 0, "interrupted: nothing written");
        rc = 130;
        goto done;
    }
    if (st == TG_ERR_INVALID_ARGUMENT) {
        /* every point and weight was read and resolved: what is left is where they lie */
        cli_error(ma->points_path, 0, "the points%s lie in different components of the mesh: no path joins them",
                  ma->start_text ? " (and --start)" : "");
        goto done;
    }
    if (st != TG_OK) {
        cli_error(ma->mesh_path, 0, "%s", tg_status_string(st));
        goto done;
    }
    if (ma->out_path) {
        cli_output out;
        FILE* f = cli_output_open(&out, ma->out_path);
        if (!f) goto done;
        print_json(f, ma->mesh_path, &r, pl.count);
        if (cli_output_commit(&out) != CLI_OK) goto done;
    }
    if (ma->json)
        print_json(stdout, ma->mesh_path, &r, pl.count);
    else if (!ma->quiet && !(ma->out_path && !strcmp(ma->out_path, "-")))
        print_summary(stdout, &r, pl.count, secs);
    rc = fflush(stdout) == 0 ? CLI_OK : CLI_INPUT;
done:
    lines_free(&pl);
    free(pts);
    free(w);
    tg_geodesic_destroy(geo);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(mesh);
    return rc;
}

static int run(int argc, char** argv)
{
    mean_args ma;
    memset(&ma, 0, sizeof ma);
    const char *tol = NULL, *iters = NULL;
    for (int i = 1; i < argc; ++i) {
        const char* a = argv[i];
        if (!strcmp(a, "--points") || !strcmp(a, "--weights") || !strcmp(a, "--start") || !strcmp(a, "-o") ||
            !strcmp(a, "--tolerance") || !strcmp(a, "--max-iterations")) {
            if (i + 1 >= argc) return cli_usage("mean", "%s needs a value", a);
            const char* val = argv[++i];
            if (!strcmp(a, "--points")) ma.points_path = val;
            else if (!strcmp(a, "--weights")) ma.weights_path = val;
            else if (!strcmp(a, "--start")) ma.start_text = val;
            else if (!strcmp(a, "-o")) ma.out_path = val;
            else if (!strcmp(a, "--tolerance")) tol = val;
            else iters = val;
        } else if (!strcmp(a, "--json")) {
            ma.json = true;
        } else if (!strcmp(a, "--no-uniqueness")) {
            ma.options.skip_uniqueness = 1;
        } else if (!strcmp(a, "--quiet")) {
            ma.quiet = true;
        } else if (a[0] == '-' && a[1]) {
            return cli_usage("mean", "unknown option '%s'", a);
        } else if (!ma.mesh_path) {
            ma.mesh_path = a;
        } else {
            return cli_usage("mean", "unexpected argument '%s'", a);
        }
    }
    if (!ma.mesh_path) return cli_usage("mean", "missing MESH");
    if (!ma.points_path) return cli_usage("mean", "missing --points FILE");
    if (tol && (!cli_parse_double(tol, &ma.options.tolerance) || !(ma.options.tolerance > 0.0)))
        return cli_usage("mean", "--tolerance needs a number > 0 (relative to the bounding box's diagonal), not '%s'", tol);
    unsigned long long n = 0;
    if (iters && (!cli_parse_uint(iters, &n) || n < 1 || n > 1000000))
        return cli_usage("mean", "--max-iterations needs a number in 1..1000000, not '%s'", iters);
    ma.options.max_iterations = (uint32_t)n;
    cli_spec sp;
    if (ma.start_text && !cli_parse_spec(ma.start_text, &sp))
        return cli_usage("mean", "bad --start '%s' (v:IDX, f:FACE:b0,b1,b2, e:HALFEDGE:t or p:x,y,z)", ma.start_text);
    if (ma.out_path && strcmp(ma.out_path, "-") && !cli_ext_is(ma.out_path, ".json"))
        return cli_usage("mean", "-o writes the JSON document: OUT.json ('-': stdout), not '%s'", ma.out_path);
    if (ma.json && ma.out_path && !strcmp(ma.out_path, "-")) return cli_usage("mean", "--json and -o - both write to stdout");
    if (!strcmp(ma.points_path, "-") && ma.weights_path && !strcmp(ma.weights_path, "-"))
        return cli_usage("mean", "--points and --weights cannot both be read from standard input");
    const cli_file_role inputs[3] = {{ma.mesh_path, "mesh"}, {ma.points_path, "points file (--points)"},
                                     {ma.weights_path, "weights file (--weights)"}};
    const cli_file_role outputs[1] = {{ma.out_path, "-o"}};
    int rc = cli_check_outputs(outputs, 1, inputs, 3);
    if (rc != CLI_OK) return rc;
    return run_mean(&ma);
}

const cli_command cli_cmd_mean = {
    "mean",
    "mean MESH --points FILE [--weights FILE] [--start SPEC] [--tolerance T] [--max-iterations N]\n"
    "       [--no-uniqueness] [--json] [-o OUT.json] [--quiet]",
    "The weighted geodesic (Karcher / Frechet) mean of surface points: the surface point minimising\n"
    "the weighted sum of squared exact geodesic distances to them. It iterates p <- exp_p(sum w log_p(x)\n"
    "/ sum w) with exact paths (their distance and direction at p) and the exact trace, until a step is\n"
    "below the tolerance; a step that raises the energy is walked again at half length.\n\n"
    "  --points FILE      the points, one a line: v:IDX | f:FACE:b0,b1,b2 | e:HALFEDGE:t | p:x,y,z, or\n"
    "                     \"x y z\" (p: and x y z are the closest surface point); '#' comments and\n"
    "                     blank lines skipped; '-' reads standard input. All in one component.\n"
    "  --weights FILE     one weight a line, >= 0, one per point in the same order, not all 0\n"
    "                     (default: all 1)\n"
    "  --start SPEC       where the iteration starts (default: the point of largest weight, the first\n"
    "                     on ties): the iteration finds a mean near its start\n"
    "  --tolerance T      stop when a step is below T times the bounding box's diagonal (default 1e-10)\n"
    "  --max-iterations N at most N steps (default 100)\n"
    "  --no-uniqueness    skip the uniqueness test (one bounded field)\n"
    "  --json             print the result as JSON (mean, xyz, status, iterations, halvings,\n"
    "                     gradient_norm, energy, radius, uniqueness, fields)\n"
    "  -o OUT.json        write that JSON document (written whole, or not at all)\n"
    "  --quiet            no progress line and no summary\n\n"
    "The summary: the mean as a SPEC and its position, status (converged, iteration_cap: the last\n"
    "point; stalled: a step could not be walked), the steps, the gradient norm |sum w log_p(x)| / sum w\n"
    "at the mean, the energy (sum w d^2 / sum w), the radius (the farthest point), and uniqueness:\n"
    "unique when the faces within 4 radii of the mean form a disc with no vertex of angle sum below\n"
    "2 pi inside (then the minimiser is unique: a CAT(0) region); not certified otherwise, which says\n"
    "nothing either way (every closed convex surface lands here). Bad points or weights name the file\n"
    "and line (exit 2). Ctrl-C stops the computation (exit 130, nothing written).\n",
    run,
};
