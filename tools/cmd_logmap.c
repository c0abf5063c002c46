/* cmd_logmap.c - `trigeo logmap MESH --from SPEC [--ref X,Y,Z] [--max-distance D] -o OUT.ply|.csv|.npy`:
 * the exact logarithmic map about a surface point, per vertex the distance, the angle and the 2D
 * coordinates (r cos a, r sin a).
 * Based on: the CLI contract of the project's DESIGN.md (SPEC, exit codes, outputs written
 *   whole, Ctrl-C); tg_geodesic_log_map (include/trigeo.h). */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct logmap_args {
    const char *mesh_path, *from, *out, *ref_text;
    double ref[3];
    bool has_ref, quiet;
    double max_dist; /* < 0: no limit */
    int threads;     /* tg_field_options.threads (cli_field_threads) */
    bool has_transport;
    double transport[3]; /* --transport: the vector carried to every vertex */
    const char* transport_text;
} logmap_args;

static int on_progress(void* user, const tg_field_progress* p)
{
    char detail[96];
    snprintf(detail, sizeof detail, "front at distance %.6g", p->front_distance);
    cli_progress_update(user, p->settled_fraction, detail);
    return cli_interrupted();
}

/* The 2D coordinates of the map: (r cos a, r sin a); +inf both where r is (unreached). */
static void planar(const double* r, const double* a, size_t n, double* u, double* v)
{
    for (size_t i = 0; i < n; ++i) {
        bool far = !(r[i] < INFINITY);
        u[i] = far ? INFINITY : r[i] * cos(a[i]);
        v[i] = far ? INFINITY : r[i] * sin(a[i]);
    }
}

/* The columns r, theta, u, v and, with --transport, tx, ty, tz (t: 3 a vertex, else NULL). */
static int write_output(const logmap_args* la, const tg_mesh* mesh, const double* r, const double* a, const double* u,
                        const double* v, const double* t, const uint8_t* tflag, size_t n)
{
    size_t cols = t ? 8 : 4;
    if (cli_ext_is(la->out, ".ply")) {
        double* tc = t ? malloc((n ? n : 1) * 4 * sizeof *tc) : NULL; /* one array a property */
        if (t && !tc) {
            cli_error(NULL, 0, "out of memory");
            return CLI_INPUT;
        }
        for (size_t i = 0; tc && i < n; ++i)
            tc[i] = t[3 * i], tc[n + i] = t[3 * i + 1], tc[2 * n + i] = t[3 * i + 2], tc[3 * n + i] = tflag[i];
        tg_vertex_scalar sc[8] = {{"distance", r}, {"angle", a}, {"u", u}, {"v", v}, {"tx", tc},
                                  {"ty", tc ? tc + n : NULL}, {"tz", tc ? tc + 2 * n : NULL},
                                  {"tflag", tc ? tc + 3 * n : NULL}};
        tg_diag d;
        memset(&d, 0, sizeof d);
        cli_output out;
        int rc = CLI_INPUT;
        if (cli_output_reserve(&out, la->out)) {
            out.f = NULL;
            rc = cli_output_finish_library(&out, tg_mesh_write_ply(mesh, out.tmp, sc, cols, &d), &d);
        }
        free(tc);
        return rc;
    }
    cli_output out;
    FILE* f = cli_output_open(&out, la->out);
    if (!f) return CLI_INPUT;
    bool ok;
    if (cli_ext_is(la->out, ".npy")) {
        double* rows = malloc((n ? n : 1) * cols * sizeof *rows);
        ok = rows != NULL;
        for (size_t i = 0; ok && i < n; ++i) {
            double* row = rows + cols * i;
            row[0] = r[i], row[1] = a[i], row[2] = u[i], row[3] = v[i];
            if (t) row[4] = t[3 * i], row[5] = t[3 * i + 1], row[6] = t[3 * i + 2], row[7] = tflag[i];
        }
        ok = ok && cli_write_npy_f64(f, rows, n, cols, true);
        free(rows);
    } else {
        ok = fprintf(f, t ? "vertex,r,theta,u,v,tx,ty,tz,tflag\n" : "vertex,r,theta,u,v\n") > 0;
        char b[7][32];
        for (size_t i = 0; ok && i < n; ++i) {
            cli_format_double(r[i], b[0]), cli_format_double(a[i], b[1]);
            cli_format_double(u[i], b[2]), cli_format_double(v[i], b[3]);
            if (t) {
                cli_format_double(t[3 * i], b[4]), cli_format_double(t[3 * i + 1], b[5]);
                cli_format_double(t[3 * i + 2], b[6]);
                ok = fprintf(f, "%zu,%s,%s,%s,%s,%s,%s,%s,%d\n", i, b[0], b[1], b[2], b[3], b[4], b[5], b[6],
                             tflag[i]) > 0;
            } else {
                ok = fprintf(f, "%zu,%s,%s,%s,%s\n", i, b[0], b[1], b[2], b[3]) > 0;
            }
        }
    }
    if (!ok) {
        cli_error(la->out, 0, "write failed: %s", strerror(errno));
        cli_output_abort(&out);
        return CLI_INPUT;
    }
    return cli_output_commit(&out);
}

static int run_logmap(const logmap_args* la, const cli_spec* sp)
{
    int rc = CLI_INPUT;
    tg_bvh* bvh = NULL;
    tg_geodesic* geo = NULL;
    double *r = NULL, *a = NULL, *u = NULL, *v = NULL, *t = NULL;
    uint8_t* tflag = NULL;
    tg_surface_point source;
    tg_mesh* mesh = cli_load_mesh_for_distances(la->mesh_path);
    if (!mesh) goto done;
    if (tg_mesh_face_count(mesh) == 0) {
        cli_error(la->mesh_path, 0, "the mesh has no faces");
        goto done;
    }
    if (!cli_resolve_spec(la->mesh_path, mesh, &bvh, la->from, sp, &source)) goto done;
    size_t n = tg_mesh_vertex_count(mesh);
    r = malloc((n ? n : 1) * sizeof *r), a = malloc((n ? n : 1) * sizeof *a);
    u = malloc((n ? n : 1) * sizeof *u), v = malloc((n ? n : 1) * sizeof *v);
    if (la->has_transport) t = malloc((n ? n : 1) * 3 * sizeof *t), tflag = malloc(n ? n : 1);
    if (!r || !a || !u || !v || (la->has_transport && (!t || !tflag))) {
        cli_error(NULL, 0, "out of memory");
        goto done;
    }
    tg_status st = tg_geodesic_create(mesh, NULL, &geo);
    tg_field_options o;
    memset(&o, 0, sizeof o);
    if (la->max_dist >= 0) o.limit = TG_FIELD_MAX_DISTANCE, o.max_distance = la->max_dist;
    o.threads = la->threads;
    cli_progress prog;
    cli_progress_start(&prog, "logmap", la->quiet);
    o.progress = on_progress;
    o.progress_user = &prog;
    cli_interrupt_polling(true);
    tg_field_stats stats;
    double t0 = cli_seconds();
    if (st == TG_OK) st = tg_geodesic_log_map(geo, NULL, &source, la->has_ref ? la->ref : NULL, &o, r, a, &stats);
    bool transport_refused = false;
    if (st == TG_OK && t) { /* a second propagation: the vector's own angles */
        st = tg_geodesic_transport_field(geo, NULL, &source, la->transport, &o, t, tflag, NULL, NULL);
        transport_refused = st == TG_ERR_INVALID_ARGUMENT;
    }
    double secs = cli_seconds() - t0;
    cli_interrupt_polling(false);
    cli_progress_end(&prog);
    if (st == TG_ERR_CANCELLED) {
        cli_error(la->mesh_path, 0, "interrupted: nothing written");
        rc = 130;
        goto done;
    }
    if (transport_refused) {
        cli_error(la->mesh_path, 0, "--transport %s is perpendicular to the surface at %s (within 1e-9 radians of "
                  "the normal there)", la->transport_text, la->from);
        goto done;
    }
    if (st == TG_ERR_INVALID_ARGUMENT && geo) {
        if (la->has_ref)
            cli_error(la->mesh_path, 0, "--ref %s is perpendicular to the surface at %s (within 1e-9 radians of the "
                      "normal there; or the reference face has zero area)", la->ref_text, la->from);
        else
            cli_error(la->mesh_path, 0, "the reference face at %s has zero area: give --ref X,Y,Z", la->from);
        goto done;
    }
    if (st != TG_OK) {
        cli_error(la->mesh_path, 0, "%s", tg_status_string(st));
        goto done;
    }
    planar(r, a, n, u, v);
    if ((rc = write_output(la, mesh, r, a, u, v, t, tflag, n)) != CLI_OK) goto done;
    if (!la->quiet && strcmp(la->out, "-")) {
        size_t reached = 0;
        double far = 0.0;
        for (size_t i = 0; i < n; ++i)
            if (r[i] < INFINITY) reached++, far = r[i] > far ? r[i] : far;
        printf("vertices           %zu (%zu reached)\n", n, reached);
        printf("largest distance   %s\n", cli_num(far).s);
        cli_print_work(&stats, secs);
    }
    rc = fflush(stdout) == 0 ? CLI_OK : CLI_INPUT;
done:
    free(r), free(a), free(u), free(v), free(t), free(tflag);
    tg_geodesic_destroy(geo);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(mesh);
    return rc;
}

static int run(int argc, char** argv)
{
    logmap_args la;
    memset(&la, 0, sizeof la);
    la.max_dist = -1.0;
    const char *ref = NULL, *maxd = NULL, *threads = NULL, *transport = NULL;
    for (int i = 1; i < argc; ++i) {
        const char* s = argv[i];
        const char** slot = !strcmp(s, "--from") ? &la.from : !strcmp(s, "--ref") ? &ref
                            : !strcmp(s, "-o") ? &la.out : !strcmp(s, "--max-distance") ? &maxd
                            : !strcmp(s, "--threads") ? &threads : !strcmp(s, "--transport") ? &transport : NULL;
        if (slot) {
            if (i + 1 >= argc) return cli_usage("logmap", "%s needs a value", s);
            *slot = argv[++i];
        } else if (!strcmp(s, "--quiet")) {
            la.quiet = true;
        } else if (s[0] == '-' && s[1]) {
            return cli_usage("logmap", "unknown option '%s'", s);
        } else if (!la.mesh_path) {
            la.mesh_path = s;
        } else {
            return cli_usage("logmap", "unexpected argument '%s'", s);
        }
    }
    if (!la.mesh_path) return cli_usage("logmap", "missing MESH");
    if (!la.from) return cli_usage("logmap", "missing --from SPEC");
    if (!la.out) return cli_usage("logmap", "missing -o OUT.ply|.csv|.npy");
    if (strcmp(la.out, "-") && !cli_ext_is(la.out, ".ply") && !cli_ext_is(la.out, ".csv") && !cli_ext_is(la.out, ".npy"))
        return cli_usage("logmap", "-o %s: the extension must be .ply, .csv or .npy ('-': CSV on stdout)", la.out);
    if (ref) {
        la.has_ref = true;
        la.ref_text = ref;
        if (!cli_parse_doubles(ref, 3, la.ref) || (la.ref[0] == 0.0 && la.ref[1] == 0.0 && la.ref[2] == 0.0))
            return cli_usage("logmap", "bad --ref '%s' (X,Y,Z: three finite numbers, not all zero)", ref);
    }
    if (transport) {
        la.has_transport = true;
        la.transport_text = transport;
        if (!cli_parse_doubles(transport, 3, la.transport) ||
            (la.transport[0] == 0.0 && la.transport[1] == 0.0 && la.transport[2] == 0.0))
            return cli_usage("logmap", "bad --transport '%s' (X,Y,Z: three finite numbers, not all zero)", transport);
    }
    if (maxd && !cli_parse_nonneg(maxd, &la.max_dist))
        return cli_usage("logmap", "bad --max-distance '%s' (a finite number >= 0)", maxd);
    cli_spec sp;
    if (!cli_parse_spec(la.from, &sp))
        return cli_usage("logmap", "bad --from '%s' (v:IDX, f:FACE:b0,b1,b2, e:HALFEDGE:t or p:x,y,z)", la.from);
    const cli_file_role inputs[1] = {{la.mesh_path, "mesh"}}, outputs[1] = {{la.out, "-o"}};
    int check = cli_check_outputs(outputs, 1, inputs, 1);
    if (check == CLI_OK) check = cli_field_threads("logmap", threads, &la.threads);
    if (check != CLI_OK) return check;
    return run_logmap(&la, &sp);
}

const cli_command cli_cmd_logmap = {
    "logmap",
    "logmap MESH --from SPEC [--ref X,Y,Z] [--transport X,Y,Z] [--max-distance D] [--threads N] -o OUT.ply|.csv|.npy "
    "[--quiet]",
    "The exact logarithmic map about a surface point: for every vertex the exact geodesic\n"
    "distance r (the same as trigeo field's, bit for bit), the angle theta at which its shortest\n"
    "path leaves the point, and the 2D coordinates u = r cos theta, v = r sin theta.\n\n"
    "  --from SPEC      the centre: v:IDX | f:FACE:b0,b1,b2 | e:HALFEDGE:t | p:x,y,z\n"
    "  --ref X,Y,Z      angle 0 along the direction trigeo trace --dir X,Y,Z takes from the\n"
    "                   centre (any length; at f: the projection onto the face); refused when\n"
    "                   perpendicular to the surface there. Default: as trigeo trace --angle,\n"
    "                   from corner 0 towards corner 1 of the face of f:, along the halfedge of\n"
    "                   e:, or along the vertex's first halfedge for v:\n"
    "  --transport X,Y,Z the vector at the centre (a direction of the surface there as --ref takes\n"
    "                   it, and a length) carried to every vertex along its exact shortest path\n"
    "                   (parallel transport: the angle to the path is kept): 4 more columns\n"
    "                   tx,ty,tz (0,0,0 where not reached) and tflag (0 transported, 1 the\n"
    "                   centre, 2 unreached, 3 the cut locus); one more propagation\n"
    "  --max-distance D only within D (beyond: r inf)\n"
    "  --threads N      the field's propagation on N threads (at most 256, 0 = all cores;\n"
    "                   default 1): every N > 1 gives the same bits, within 1e-14 relative of\n"
    "                   one thread's (an angle at a tie may be the other path's)\n"
    "  -o OUT           .csv   vertex,r,theta,u,v[,tx,ty,tz,tflag]  (one row a vertex; '-' = stdout)\n"
    "                   .npy   a (vertices, 4 or 8) float64 array, columns r, theta, u, v[, tx, ty, tz, tflag]\n"
    "                   .ply   the mesh as binary PLY with per-vertex double properties\n"
    "                          distance, angle, u, v[, tx, ty, tz, tflag] (trigeo render MESH --logmap OUT.ply)\n"
    "  --quiet          no progress line and no summary (errors are still printed, -o - still\n"
    "                   writes the CSV)\n\n"
    "Angles are counterclockwise about the reference face's normal (its file winding), in\n"
    "[0, 2 pi); at a vertex they are scaled so the turn around it is 2 pi (pi at a boundary\n"
    "vertex, angles in [0, pi]), as geometry-central's tangent spaces. `trigeo trace --from SPEC\n"
    "--angle theta --length r` walks back to the vertex wherever its shortest path is unique and\n"
    "passes no vertex. Where two paths are equally short (the cut locus) the angle is the one of\n"
    "the path found first (deterministic). Vertices not reached: r inf, theta 0, u and v inf.\n"
    "Without -o - and --quiet a summary (vertices reached, largest distance, windows, seconds) goes\n"
    "to stdout.\n",
    run,
};
