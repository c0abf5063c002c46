/* cmd_compare.c - `trigeo compare A B [--tolerance T] [--mean-tolerance T] [--symmetric]
 * [--threads N] [-o A_DIST.ply|.csv] [--json]`: the certified distance from mesh A to mesh B
 * (tg_mesh_distance): the one-sided Hausdorff distance as an interval, the point realising its
 * lower bound, the mean and RMS distance over A's area as intervals; with --symmetric also B to A
 * and the symmetric Hausdorff interval.
 * Based on: the CLI contract of the project's DESIGN.md. */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct compare_args {
    const char *a_path, *b_path, *out;
    double tolerance, mean_tolerance;
    unsigned long long threads;
    bool symmetric, json, quiet;
} compare_args;

typedef struct progress_ctx {
    cli_progress* bar;
    int pass, passes;
} progress_ctx;

static int on_progress(void* user, const tg_mesh_distance_progress* p)
{
    const progress_ctx* c = user;
    char detail[96];
    if (isfinite(p->upper))
        snprintf(detail, sizeof detail, "[%s, %s]", cli_num(p->lower).s, cli_num(p->upper).s);
    else
        snprintf(detail, sizeof detail, "first pass");
    cli_progress_update(c->bar, ((double)c->pass + p->fraction) / c->passes, detail);
    return cli_interrupted();
}

/* The answer of one direction as a JSON object. */
static void json_direction(FILE* f, const char* indent, const tg_mesh_distance_result* r)
{
    fprintf(f, "{\n%s  \"lower\": %s,\n%s  \"upper\": %s,\n", indent, cli_num(r->lower).s, indent, cli_num(r->upper).s);
    fprintf(f, "%s  \"tolerance\": %s,\n%s  \"converged\": %s,\n", indent, cli_num(r->tolerance).s, indent,
            r->converged ? "true" : "false");
    fprintf(f, "%s  \"distance\": %s,\n", indent, cli_num(r->distance).s);
    fprintf(f, "%s  \"face\": %u,\n%s  \"bary\": [%s, %s, %s],\n", indent, r->face, indent, cli_num(r->bary[0]).s,
            cli_num(r->bary[1]).s, cli_num(r->bary[2]).s);
    fprintf(f, "%s  \"point\": [%s, %s, %s],\n", indent, cli_num(r->point[0]).s, cli_num(r->point[1]).s,
            cli_num(r->point[2]).s);
    fprintf(f, "%s  \"closest_face\": %u,\n%s  \"closest_bary\": [%s, %s, %s],\n", indent, r->closest_face, indent,
            cli_num(r->closest_bary[0]).s, cli_num(r->closest_bary[1]).s, cli_num(r->closest_bary[2]).s);
    fprintf(f, "%s  \"closest_point\": [%s, %s, %s],\n", indent, cli_num(r->closest_point[0]).s,
            cli_num(r->closest_point[1]).s, cli_num(r->closest_point[2]).s);
    fprintf(f, "%s  \"area\": %s,\n", indent, cli_num(r->area).s);
    fprintf(f, "%s  \"mean\": [%s, %s],\n%s  \"rms\": [%s, %s],\n", indent, cli_num(r->mean_lower).s,
            cli_num(r->mean_upper).s, indent, cli_num(r->rms_lower).s, cli_num(r->rms_upper).s);
    fprintf(f, "%s  \"pieces\": %llu,\n%s  \"queries\": %llu\n%s}", indent, (unsigned long long)r->pieces, indent,
            (unsigned long long)r->queries, indent);
}

static void print_json(const compare_args* ca, const tg_mesh_distance_result* r, double secs)
{
    printf("{\n  \"a\": ");
    cli_json_string(stdout, ca->a_path);
    printf(",\n  \"b\": ");
    cli_json_string(stdout, ca->b_path);
    printf(",\n  \"a_to_b\": ");
    json_direction(stdout, "  ", &r[0]);
    if (ca->symmetric) {
        printf(",\n  \"b_to_a\": ");
        json_direction(stdout, "  ", &r[1]);
        printf(",\n  \"symmetric\": {\"lower\": %s, \"upper\": %s}", cli_num(fmax(r[0].lower, r[1].lower)).s,
               cli_num(fmax(r[0].upper, r[1].upper)).s);
    }
    printf(",\n  \"seconds\": %.3f\n}\n", secs);
}

static void print_direction(const char* name, const tg_mesh_distance_result* r)
{
    printf("hausdorff %s  [%s, %s]  width %s (tolerance %s%s)\n", name, cli_num(r->lower).s, cli_num(r->upper).s,
           cli_num(r->upper - r->lower).s, cli_num(r->tolerance).s, r->converged ? "" : "; NOT reached: --max-pieces");
    printf("  at               f:%u:%s,%s,%s  (%s, %s, %s)  distance %s\n", r->face, cli_num(r->bary[0]).s,
           cli_num(r->bary[1]).s, cli_num(r->bary[2]).s, cli_num(r->point[0]).s, cli_num(r->point[1]).s,
           cli_num(r->point[2]).s, cli_num(r->distance).s);
    printf("  closest          f:%u:%s,%s,%s  (%s, %s, %s)\n", r->closest_face, cli_num(r->closest_bary[0]).s,
           cli_num(r->closest_bary[1]).s, cli_num(r->closest_bary[2]).s, cli_num(r->closest_point[0]).s,
           cli_num(r->closest_point[1]).s, cli_num(r->closest_point[2]).s);
    printf("  mean             [%s, %s]\n", cli_num(r->mean_lower).s, cli_num(r->mean_upper).s);
    printf("  rms              [%s, %s]\n", cli_num(r->rms_lower).s, cli_num(r->rms_upper).s);
    printf("  area             %s\n", cli_num(r->area).s);
    printf("  work             %llu pieces, %llu closest-point queries\n", (unsigned long long)r->pieces,
           (unsigned long long)r->queries);
}

/* Per vertex of A its distance to B: .ply (A with the vertex property `distance`, which trigeo
 * render --field draws) or .csv rows vertex,distance. */
static int write_distances(cli_output_set* set, const char* path, const tg_mesh* a, const double* dist)
{
    size_t n = tg_mesh_vertex_count(a);
    if (strcmp(path, "-") != 0 && cli_ext_is(path, ".ply")) {
        tg_vertex_scalar sc = {"distance", dist};
        tg_diag d;
        memset(&d, 0, sizeof d);
        cli_output* out = cli_output_set_reserve(set, path);
        return out ? cli_output_library_done(out, tg_mesh_write_ply(a, out->tmp, &sc, 1, &d), &d) : CLI_INPUT;
    }
    FILE* f = cli_output_set_open(set, path);
    if (!f) return CLI_INPUT;
    bool ok = fprintf(f, "vertex,distance\n") > 0;
    for (size_t v = 0; ok && v < n; ++v) ok = fprintf(f, "%zu,%s\n", v, cli_num(dist[v]).s) > 0;
    if (!ok) {
        cli_error(path, 0, "write failed: %s", strerror(errno));
        return CLI_INPUT;
    }
    return CLI_OK;
}

/* One direction; CLI_OK or the exit code after printing why. */
static int measure(const char* a_path, const tg_mesh* a, const char* b_path, const tg_mesh* b,
                   const tg_mesh_distance_options* o, double* dist, tg_mesh_distance_result* r)
{
    if (tg_mesh_face_count(a) == 0 || tg_mesh_face_count(b) == 0) {
        const char* which = tg_mesh_face_count(a) == 0 ? a_path : b_path;
        cli_error(which, 0, "the mesh has no faces: no surface to measure a distance %s", which == a_path ? "from" : "to");
        return CLI_INPUT;
    }
    tg_bvh_options bo;
    memset(&bo, 0, sizeof bo);
    bo.threads = o->threads;
    tg_bvh* bvh = NULL;
    tg_status st = tg_bvh_create(b, &bo, &bvh);
    if (st == TG_OK) st = tg_mesh_distance(a, bvh, o, dist, r);
    tg_bvh_destroy(bvh);
    if (st == TG_OK) return CLI_OK;
    if (st == TG_ERR_CANCELLED) {
        cli_error(a_path, 0, "interrupted: nothing written");
        return 130;
    }
    cli_error(st == TG_ERR_UNSUPPORTED ? b_path : a_path, 0, "%s", tg_status_string(st));
    return CLI_INPUT;
}

static int run_compare(const compare_args* ca, size_t max_pieces)
{
    int rc = CLI_INPUT;
    double* dist = NULL;
    tg_mesh* a = cli_load_mesh_for_distances(ca->a_path);
    tg_mesh* b = a ? cli_load_mesh_for_distances(ca->b_path) : NULL;
    if (!a || !b) goto done;
    if (ca->out && !(dist = malloc((tg_mesh_vertex_count(a) ? tg_mesh_vertex_count(a) : 1) * sizeof *dist))) {
        cli_error(NULL, 0, "out of memory");
        goto done;
    }
    cli_progress bar;
    cli_progress_start(&bar, "compare", ca->quiet);
    progress_ctx pc = {&bar, 0, ca->symmetric ? 2 : 1};
    tg_mesh_distance_options o;
    memset(&o, 0, sizeof o);
    o.tolerance = ca->tolerance;
    o.mean_tolerance = ca->mean_tolerance;
    o.max_pieces = max_pieces;
    o.threads = (int)ca->threads;
    o.progress = on_progress;
    o.progress_user = &pc;
    tg_mesh_distance_result r[2];
    memset(r, 0, sizeof r);
    cli_interrupt_polling(true);
    double t0 = cli_seconds();
    rc = measure(ca->a_path, a, ca->b_path, b, &o, dist, &r[0]);
    if (rc == CLI_OK && ca->symmetric) {
        pc.pass = 1;
        rc = measure(ca->b_path, b, ca->a_path, a, &o, NULL, &r[1]);
    }
    double secs = cli_seconds() - t0;
    cli_interrupt_polling(false);
    cli_progress_end(&bar);
    if (rc != CLI_OK) goto done;
    if (ca->out) {
        cli_output_set outs = {0};
        rc = write_distances(&outs, ca->out, a, dist);
        if (rc == CLI_OK) rc = cli_output_set_commit(&outs);
        cli_output_set_abort(&outs);
        if (rc != CLI_OK) goto done;
    }
    if (ca->json) {
        print_json(ca, r, secs);
    } else if (!ca->quiet && (!ca->out || strcmp(ca->out, "-"))) {
        print_direction("A->B", &r[0]);
        if (ca->symmetric) {
            print_direction("B->A", &r[1]);
            printf("hausdorff sym.   [%s, %s]\n", cli_num(fmax(r[0].lower, r[1].lower)).s,
                   cli_num(fmax(r[0].upper, r[1].upper)).s);
        }
        printf("seconds            %.3f\n", secs);
    }
    rc = fflush(stdout) == 0 ? CLI_OK : CLI_INPUT;
done:
    free(dist);
    tg_mesh_destroy(a);
    tg_mesh_destroy(b);
    return rc;
}

static int run(int argc, char** argv)
{
    compare_args ca;
    memset(&ca, 0, sizeof ca);
    unsigned long long max_pieces = 0;
    for (int i = 1; i < argc; ++i) {
        const char* a = argv[i];
        if (!strcmp(a, "--symmetric")) {
            ca.symmetric = true;
        } else if (!strcmp(a, "--json")) {
            ca.json = true;
        } else if (!strcmp(a, "--quiet")) {
            ca.quiet = true;
        } else if (!strcmp(a, "--tolerance") || !strcmp(a, "--mean-tolerance") || !strcmp(a, "--threads") ||
                   !strcmp(a, "--max-pieces") || !strcmp(a, "-o")) {
            if (i + 1 >= argc) return cli_usage("compare", "%s needs a value", a);
            const char* val = argv[++i];
            if (!strcmp(a, "-o")) {
                ca.out = val;
            } else if (!strcmp(a, "--threads")) {
                if (!cli_parse_uint(val, &ca.threads) || ca.threads > TG_MAX_THREADS)
                    return cli_usage("compare", "--threads needs a count in 0..%d (0 = all cores), not '%s'",
                                     TG_MAX_THREADS, val);
            } else if (!strcmp(a, "--max-pieces")) {
                if (!cli_parse_uint(val, &max_pieces) || max_pieces == 0 || max_pieces > 0xFFFFFFF0ull)
                    return cli_usage("compare", "--max-pieces needs a positive count, not '%s'", val);
            } else {
                double* t = !strcmp(a, "--tolerance") ? &ca.tolerance : &ca.mean_tolerance;
                if (!cli_parse_nonneg(val, t) || !(*t > 0.0))
                    return cli_usage("compare", "%s needs a positive distance, not '%s'", a, val);
            }
        } else if (a[0] == '-' && a[1]) {
            return cli_usage("compare", "unknown option '%s'", a);
        } else if (!ca.a_path) {
            ca.a_path = a;
        } else if (!ca.b_path) {
            ca.b_path = a;
        } else {
            return cli_usage("compare", "unexpected argument '%s'", a);
        }
    }
    if (!ca.a_path || !ca.b_path) return cli_usage("compare", "needs two meshes, A and B");
    if (!strcmp(ca.a_path, "-") && !strcmp(ca.b_path, "-"))
        return cli_usage("compare", "only one mesh can come from standard input ('-')");
    if (ca.out && strcmp(ca.out, "-") && !cli_ext_is(ca.out, ".ply") && !cli_ext_is(ca.out, ".csv"))
        return cli_usage("compare", "-o %s: the extension must be .ply or .csv", ca.out);
    if (ca.out && ca.json && !strcmp(ca.out, "-"))
        return cli_usage("compare", "--json and -o - both write to standard output");
    const cli_file_role inputs[2] = {{ca.a_path, "mesh A"}, {ca.b_path, "mesh B"}}, outputs[1] = {{ca.out, "-o"}};
    int check = cli_check_outputs(outputs, 1, inputs, 2);
    if (check != CLI_OK) return check;
    if (!cli_threads_available((int)ca.threads, "compare")) return CLI_INPUT;
    return run_compare(&ca, (size_t)max_pieces);
}

const cli_command cli_cmd_compare = {
    "compare",
    "compare A B [--tolerance T] [--mean-tolerance T] [--symmetric] [--threads N] [--max-pieces N] [-o A_DIST.ply|.csv]\n"
    "        [--json] [--quiet]",
    "The certified distance from mesh A to mesh B: the one-sided Hausdorff distance h(A, B), the\n"
    "largest distance from a point of A's surface to B's surface, as an interval [lower, upper]\n"
    "whose width is at most the tolerance (lower: a point of A where the distance is realised;\n"
    "upper: a bound proven over every triangle of A, refined where needed), the point realising the\n"
    "lower bound and its closest point on B, and the mean and RMS distance over A's area as\n"
    "intervals. Sampling tools (MeshLab, libigl, metro) give a value below the true one.\n\n"
    "  --tolerance T       the Hausdorff interval's width (default 1e-9 of the larger bounding-box\n"
    "                      diagonal; never below the rounding of the distances themselves)\n"
    "  --mean-tolerance T  refine the mean's and the RMS's intervals to this width too (default:\n"
    "                      no more than the Hausdorff interval needs; they are then of the order of\n"
    "                      A's edge length where the distance varies)\n"
    "  --symmetric         also h(B, A), and the symmetric distance max(h(A, B), h(B, A))\n"
    "  --threads N         threads of the first pass, at most 256 (default 0 = all cores; the\n"
    "                      numbers are the same for every count)\n"
    "  --max-pieces N      the most triangle pieces kept, A's faces included (about 160 bytes\n"
    "                      each; default A's faces + 2097152); when reached the intervals, still\n"
    "                      valid, are wider\n"
    "  -o FILE             per vertex of A its exact distance to B: .ply (A with the vertex property\n"
    "                      'distance': trigeo render FILE --field FILE) or .csv rows vertex,distance\n"
    "  --json              the answer as JSON on stdout (a_to_b, with --symmetric b_to_a and\n"
    "                      symmetric)\n"
    "  --quiet             no progress line and no summary\n\n"
    "A mesh without faces is an input error (exit 2). -o is written to a temporary name and renamed\n"
    "when complete; it may not name A or B.\n",
    run,
};
