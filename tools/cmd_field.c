/* cmd_field.c - `trigeo field MESH --from SPEC[;SPEC...] | --sources FILE|all [-o OUT.ply|.csv|
 * .npy|.npz] [--max-distance D] [--to POINTS]`: the exact geodesic distance from surface points
 * to every vertex (tg_geodesic_field), or one field per source as a matrix: dense over the
 * vertices (tg_geodesic_distance_matrix) or over selected points (tg_geodesic_distance_matrix_at),
 * or sparse within a radius (tg_geodesic_local_matrix); written as a PLY vertex property
 * `distance` (which `trigeo render --field` draws), CSV, NumPy .npy or SciPy's sparse .npz.
 * Based on: the CLI contract of the project's DESIGN.md. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define MAX_SOURCES 4096

/* The output format, from the file name's extension. */
enum { OUT_NONE, OUT_PLY, OUT_CSV, OUT_NPY, OUT_NPZ };

static int format_of(const char* path)
{
    const char* dot = strrchr(path, '.');
    if (!dot) return OUT_NONE;
    if (!strcmp(dot, ".ply")) return OUT_PLY;
    if (!strcmp(dot, ".csv")) return OUT_CSV;
    if (!strcmp(dot, ".npy")) return OUT_NPY;
    if (!strcmp(dot, ".npz")) return OUT_NPZ;
    return OUT_NONE;
}

/* Writes the field (rows == 1, not matrix: CSV rows vertex,distance) or the matrix (CSV: one
 * row of vertex_count distances per source) to path in `format`. */
static int write_table(const char* path, int format, const double* d, size_t rows, size_t n, bool matrix)
{
    cli_output out;
    FILE* f = cli_output_open(&out, path);
    if (!f) return CLI_INPUT;
    bool ok = true;
    if (format == OUT_NPY) {
        ok = cli_write_npy_f64(f, d, rows, n, matrix);
    } else if (!matrix) {
        ok = fprintf(f, "vertex,distance\n") > 0;
        for (size_t v = 0; ok && v < n; ++v) ok = fprintf(f, "%zu,%s\n", v, cli_num(d[v]).s) > 0;
    } else {
        for (size_t r = 0; ok && r < rows; ++r)
            for (size_t v = 0; ok && v < n; ++v)
                ok = fprintf(f, v + 1 < n ? "%s," : "%s\n", cli_num(d[r * n + v]).s) > 0;
    }
    if (!ok) {
        cli_error(path, 0, "write failed: %s", strerror(errno));
        cli_output_abort(&out);
        return CLI_INPUT;
    }
    return cli_output_commit(&out);
}

/* Progress of the field: the terminal line, and Ctrl-C as cancellation. */
static int on_progress(void* user, const tg_field_progress* p)
{
    char detail[96];
    if (p->row_count > 1)
        snprintf(detail, sizeof detail, "%zu/%zu fields", p->rows_done, p->row_count);
    else
        snprintf(detail, sizeof detail, "front at distance %.6g", p->front_distance);
    cli_progress_update(user, p->settled_fraction, detail);
    return cli_interrupted();
}

static void print_summary(size_t sources, size_t segments, bool matrix, const char* columns, const double* d,
                          size_t rows, size_t n, double secs, const tg_field_stats* st)
{
    size_t reached = 0;
    double far = 0;
    for (size_t v = 0; v < n * rows; ++v)
        if (isfinite(d[v])) reached++, far = fmax(far, d[v]);
    printf("sources            %zu%s\n", sources, matrix ? " (one field each)" : "");
    if (segments) printf("curve segments     %zu\n", segments);
    if (matrix)
        printf("%-18s %zu (%zu of %zu matrix entries reached)\n", columns, n, reached, n * rows);
    else
        printf("%-18s %zu (%zu reached)\n", columns, n, reached);
    printf("largest distance   %s\n", cli_num(far).s);
    cli_print_work(st, secs);
}

typedef struct field_args {
    const char* mesh_path;
    const char* out;      /* -o / --csv */
    int format;
    double max_dist;      /* < 0: no limit */
    int threads;          /* --threads: 0 = all cores; --sources: the rows, --from: one field */
    int field_threads;    /* tg_field_options.threads of one field (--from): 1 without --threads */
    bool quiet;           /* --quiet: no progress line, no summary */
    bool matrix;          /* --sources: one row per source */
    bool all;             /* --sources all: every vertex a row */
    bool sparse;          /* the matrix within the radius, sparse (.npz, or .csv triplets) */
    bool labels;          /* --labels: the nearest source's index per vertex (Voronoi) */
    const char* boundaries; /* --boundaries: the cells' boundaries (.obj or .json) */
    const char* isolines; /* --isolines: the levels (a list); -o is then ISO.obj|.json */
    const char* isoline_count; /* --isoline-count: that many levels below the largest distance */
    bool gradient;        /* --gradient: the field's gradient per vertex to -o */
    const char* face_gradient; /* --face-gradient: per face (at the centroid) to this file */
    const char* sources_path;
    const char* at_path;  /* --at (--from) or --to (--sources): distances at these points */
    char** at_items;
    unsigned long long* at_lines;
    size_t at_count;
    cli_curves curves;    /* curve sources in the --from list: curve:FILE items and `boundary` */
    size_t segments;
    /* --labels with curves: each item of the --from list a site, numbered in the list's order: the
     * point sources', the curve files' and the boundary's */
    uint32_t* point_site;
    uint32_t curve_site[CLI_CURVES_MAX], boundary_site;
    size_t site_count;      /* the segments they made (for the summary) */
} field_args;

/* The options of the computation (the limit, progress on a terminal, Ctrl-C as cancellation). */
static void start_work(const field_args* fa, tg_field_options* o, cli_progress* prog, tg_field_stats* stats)
{
    memset(o, 0, sizeof *o);
    if (fa->max_dist >= 0) o->limit = TG_FIELD_MAX_DISTANCE, o->max_distance = fa->max_dist;
    /* one field on field_threads; a matrix's rows spread over fa->threads instead */
    if (!fa->matrix) o->threads = fa->field_threads;
    cli_progress_start(prog, "field", fa->quiet);
    o->progress = on_progress;
    o->progress_user = prog;
    cli_interrupt_polling(true); /* the progress callback looks at the flag */
    memset(stats, 0, sizeof *stats);
}

/* The exit code of the computation: CLI_OK, 130 after Ctrl-C, CLI_INPUT on an error (printed). */
static int finished(const field_args* fa, tg_status st)
{
    if (st == TG_ERR_CANCELLED) {
        cli_error(fa->mesh_path, 0, "interrupted: nothing written");
        return 130;
    }
    if (st != TG_OK) {
        cli_error(fa->mesh_path, 0, "%s", tg_status_string(st));
        return CLI_INPUT;
    }
    return CLI_OK;
}

/* --boundaries: OBJ (a `v` per point, an `l` per polyline, a comment naming its two cells) or JSON
 * ({"polylines": [{"cells": [a, b], "points": [[x, y, z], ...], "surface": ["e:H:t", ...]}]}). */
static int write_boundaries(cli_output_set* set, const char* path, const tg_voronoi_boundaries* b)
{
    tg_voronoi_boundaries_view v;
    tg_voronoi_boundaries_get_view(b, &v);
    FILE* f = cli_output_set_open(set, path);
    if (!f) return CLI_INPUT;
    bool json = cli_ext_is(path, ".json"), ok = true;
    char spec[CLI_SPEC_TEXT_MAX];
    if (!json) {
        ok = fprintf(f, "# trigeo Voronoi boundaries: %zu polylines\n", v.polyline_count) > 0;
        ok = ok && cli_obj_vertices(f, v.xyz, v.point_count);
        for (size_t p = 0; ok && p < v.polyline_count; ++p)
            ok = fprintf(f, "# cells %u %u\n", v.polyline_cells[2 * p], v.polyline_cells[2 * p + 1]) > 0 &&
                 cli_obj_line(f, v.polyline_start[p], v.polyline_start[p + 1] - v.polyline_start[p], false);
    } else {
        ok = fprintf(f, "{\"polylines\": [") > 0;
        for (size_t p = 0; ok && p < v.polyline_count; ++p) {
            ok = fprintf(f, "%s\n  {\"cells\": [%u, %u], \"points\": [", p ? "," : "", v.polyline_cells[2 * p],
                         v.polyline_cells[2 * p + 1]) > 0;
            for (size_t i = v.polyline_start[p]; ok && i < v.polyline_start[p + 1]; ++i)
                ok = fprintf(f, "%s[%s, %s, %s]", i > v.polyline_start[p] ? ", " : "", cli_num(v.xyz[3 * i]).s,
                             cli_num(v.xyz[3 * i + 1]).s, cli_num(v.xyz[3 * i + 2]).s) > 0;
            ok = ok && fprintf(f, "], \"surface\": [") > 0;
            for (size_t i = v.polyline_start[p]; ok && i < v.polyline_start[p + 1]; ++i) {
                cli_spec_text(&v.points[i], spec, sizeof spec);
                ok = fprintf(f, "%s\"%s\"", i > v.polyline_start[p] ? ", " : "", spec) > 0;
            }
            ok = ok && fprintf(f, "]}") > 0;
        }
        ok = ok && fprintf(f, "\n]}\n") > 0;
    }
    if (!ok) {
        cli_error(path, 0, "write failed: %s", strerror(errno));
        return CLI_INPUT;
    }
    return CLI_OK;
}

/* The distances' array (n doubles) and the mesh's solver; TG_OK or the reason. */
static tg_status make_solver(tg_mesh* mesh, size_t n, double** out_dist, tg_geodesic** out_geo)
{
    *out_dist = malloc((n ? n : 1) * sizeof **out_dist);
    return *out_dist ? tg_geodesic_create(mesh, NULL, out_geo) : TG_ERR_OUT_OF_MEMORY;
}

static int run_field(field_args* fa, char** items, const unsigned long long* lines, size_t count)
{
    int rc = CLI_INPUT;
    tg_surface_segment* seg = NULL; /* curve sources */
    uint32_t* seg_site = NULL;      /* --labels: their sites */
    size_t nseg = 0;
    tg_bvh* bvh = NULL;
    tg_geodesic* geo = NULL;
    double *dist = NULL, *at_d = NULL;
    tg_surface_point* at_pts = NULL;
    uint32_t* label = NULL; /* --labels */
    tg_voronoi_boundaries* bounds = NULL;
    tg_surface_point* pts = malloc((count ? count : 1) * sizeof *pts);
    tg_mesh* mesh = pts ? cli_load_mesh_for_distances(fa->mesh_path) : NULL;
    if (!pts) cli_error(NULL, 0, "out of memory");
    if (!mesh) goto done;
    if (tg_mesh_face_count(mesh) == 0) {
        cli_error(fa->mesh_path, 0, "the mesh has no faces");
        goto done;
    }
    if ((rc = cli_resolve_items("field", fa->mesh_path, fa->sources_path, false, mesh, &bvh, items, lines, count, pts)) != CLI_OK) goto done;
    at_pts = fa->at_count ? malloc(fa->at_count * sizeof *at_pts) : NULL;
    at_d = fa->at_count ? malloc(fa->at_count * sizeof *at_d) : NULL;
    if (fa->at_count && (!at_pts || !at_d)) {
        cli_error(NULL, 0, "out of memory");
        goto done;
    }
    if (fa->at_count &&
        (rc = cli_resolve_items("field", fa->mesh_path, fa->at_path, true, mesh, &bvh, fa->at_items, fa->at_lines, fa->at_count, at_pts)) != CLI_OK)
        goto done;
    rc = CLI_INPUT;
    /* the columns: the vertices, or with --sources and --to the points; the rows: the sources, or
     * every item with curve rows */
    bool curves = fa->curves.count || fa->curves.boundary;
    size_t n = fa->matrix && fa->at_count ? fa->at_count : tg_mesh_vertex_count(mesh),
           rows = fa->matrix ? (curves ? fa->site_count : count) : 1;
    if (n && rows > SIZE_MAX / sizeof(double) / n) {
        cli_error(fa->sources_path, 0, "%zu sources x %zu vertices is too large", count, n);
        goto done;
    }
    tg_status st = make_solver(mesh, n * rows, &dist, &geo);
    if (st == TG_OK && (fa->curves.count || fa->curves.boundary)) {
        size_t ends[1 + CLI_CURVES_MAX];
        if ((rc = cli_curve_segments("field", fa->mesh_path, &fa->curves, mesh, &bvh, geo, &seg, &nseg, ends)) != CLI_OK)
            goto done;
        if (fa->labels && !(seg_site = malloc((nseg ? nseg : 1) * sizeof *seg_site))) {
            cli_error(NULL, 0, "out of memory");
            goto done;
        }
        for (size_t i = 0, k = 0; fa->labels && i < nseg; ++i) { /* the site of each segment */
            while (k <= fa->curves.count && i >= ends[k]) ++k;
            seg_site[i] = k == 0 ? fa->boundary_site : fa->curve_site[k - 1];
        }
        if (fa->matrix) { /* rows: the same numbering */
            if (!(seg_site = malloc((nseg ? nseg : 1) * sizeof *seg_site))) {
                cli_error(NULL, 0, "out of memory");
                goto done;
            }
            for (size_t i = 0, k = 0; i < nseg; ++i) {
                while (k <= fa->curves.count && i >= ends[k]) ++k;
                seg_site[i] = k == 0 ? fa->boundary_site : fa->curve_site[k - 1];
            }
        }
        rc = CLI_INPUT;
        fa->segments = nseg;
    }
    tg_field_options o;
    cli_progress prog;
    tg_field_stats stats;
    start_work(fa, &o, &prog, &stats);
    double t0 = cli_seconds();
    if (st == TG_OK && seg && fa->matrix) {
        st = tg_geodesic_curve_distance_matrix(geo, pts, count, fa->point_site, seg, nseg, seg_site, fa->site_count,
                                               at_pts, fa->at_count, &o, fa->threads, dist, &stats);
    } else if (st == TG_OK && seg && fa->labels) {
        label = malloc((n ? n : 1) * sizeof *label);
        st = !label ? TG_ERR_OUT_OF_MEMORY
                    : tg_geodesic_curve_voronoi(geo, NULL, pts, count, fa->point_site, seg, nseg, seg_site,
                                                fa->site_count, &o, dist, label, &stats);
    } else if (st == TG_OK && seg) {
        st = tg_geodesic_curve_field(geo, NULL, pts, count, seg, nseg, at_pts, fa->at_count, &o, at_d, dist, &stats);
    } else if (st == TG_OK && fa->labels) {
        label = malloc((n ? n : 1) * sizeof *label);
        st = !label ? TG_ERR_OUT_OF_MEMORY : fa->boundaries ? tg_voronoi_boundaries_create(NULL, &bounds) : TG_OK;
        if (st == TG_OK) st = tg_geodesic_voronoi(geo, NULL, pts, count, &o, bounds, dist, label, &stats);
    } else if (st == TG_OK && fa->matrix && fa->at_count)
        st = tg_geodesic_distance_matrix_at(geo, pts, count, at_pts, fa->at_count, &o, fa->threads, dist, &stats);
    else if (st == TG_OK && fa->matrix)
        st = tg_geodesic_distance_matrix(geo, pts, count, &o, fa->threads, dist, &stats);
    else if (st == TG_OK)
        st = tg_geodesic_field_at(geo, NULL, pts, count, at_pts, fa->at_count, &o, at_d, dist, &stats);
    double secs = cli_seconds() - t0;
    cli_interrupt_polling(false);
    cli_progress_end(&prog);
    if ((rc = finished(fa, st)) != CLI_OK) goto done;
    rc = CLI_INPUT; /* for the failures below */
    if (fa->at_count && !fa->matrix) { /* one distance a line (or a .npy vector), to -o or stdout */
        const char* path = fa->out ? fa->out : "-";
        if (fa->format == OUT_NPY) {
            rc = write_table(path, OUT_NPY, at_d, 1, fa->at_count, false);
        } else {
            cli_output out;
            FILE* f = cli_output_open(&out, path);
            bool ok = f != NULL;
            for (size_t i = 0; ok && i < fa->at_count; ++i) ok = fprintf(f, "%s\n", cli_num(at_d[i]).s) > 0;
            if (!f) {
                rc = CLI_INPUT;
            } else if (!ok) {
                cli_error(path, 0, "write failed: %s", strerror(errno));
                cli_output_abort(&out);
                rc = CLI_INPUT;
            } else {
                rc = cli_output_commit(&out);
            }
        }
        if (rc != CLI_OK) goto done;
        if (!fa->quiet && strcmp(path, "-")) print_summary(count, fa->segments, false, "vertices", dist, rows, n, secs, &stats);
        rc = fflush(stdout) == 0 ? CLI_OK : CLI_INPUT;
        goto done;
    }
    if (fa->labels) { /* the labels and the boundaries: both files or neither */
        cli_output_set outs = {0};
        rc = fa->out ? cli_write_labels(&outs, fa->out, mesh, label, dist, n) : CLI_OK;
        if (rc == CLI_OK && fa->boundaries) rc = write_boundaries(&outs, fa->boundaries, bounds);
        if (rc == CLI_OK) rc = cli_output_set_commit(&outs);
        cli_output_set_abort(&outs);
        if (rc != CLI_OK) goto done;
        if (!fa->quiet && (!fa->out || strcmp(fa->out, "-")))
            print_summary(count, fa->segments, false, "vertices", dist, rows, n, secs, &stats);
        rc = fflush(stdout) == 0 ? CLI_OK : CLI_INPUT;
        goto done;
    }
    if (fa->out && fa->format == OUT_PLY) {
        tg_diag d;
        memset(&d, 0, sizeof d);
        tg_vertex_scalar sc = {"distance", dist};
        cli_output out;
        if (!cli_output_reserve(&out, fa->out)) goto done;
        out.f = NULL;
        st = tg_mesh_write_ply(mesh, out.tmp, &sc, 1, &d);
        if ((rc = cli_output_finish_library(&out, st, &d)) != CLI_OK) goto done;
    } else if (fa->out && (rc = write_table(fa->out, fa->format, dist, rows, n, fa->matrix)) != CLI_OK) {
        goto done;
    }
    if (!fa->quiet && (!fa->out || strcmp(fa->out, "-")))
        print_summary(rows > 1 ? rows : count, fa->segments, fa->matrix, fa->matrix && fa->at_count ? "points" : "vertices", dist, rows, n, secs, &stats);
    rc = fflush(stdout) == 0 ? CLI_OK : CLI_INPUT;
done:
    free(pts), free(dist), free(at_pts), free(at_d), free(label), free(seg), free(seg_site);
    tg_voronoi_boundaries_destroy(bounds);
    tg_geodesic_destroy(geo);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(mesh);
    return rc;
}

/* --isolines / --isoline-count: the exact isolines of the field of the sources (the nearest of
 * them, curves included: their offset curves), to -o. A count of levels runs the field first for
 * its largest distance. */
static int run_isolines(const field_args* fa, char** items, const unsigned long long* lines, size_t count)
{
    int rc = CLI_INPUT;
    tg_bvh* bvh = NULL;
    tg_geodesic* geo = NULL;
    tg_isolines* iso = NULL;
    tg_surface_segment* seg = NULL; /* curve sources */
    size_t nseg = 0;
    double *levels = NULL, *dist = NULL;
    size_t nl = 0;
    bool autolv = fa->isoline_count != NULL;
    tg_surface_point* pts = malloc((count ? count : 1) * sizeof *pts);
    if (!pts) cli_error(NULL, 0, "out of memory");
    if (!pts) goto done;
    rc = autolv ? cli_parse_level_count("--isoline-count", fa->isoline_count, &levels, &nl)
                : cli_parse_levels("--isolines", fa->isolines, &levels, &nl);
    if (rc != CLI_OK) goto done;
    rc = CLI_INPUT;
    tg_mesh* mesh = cli_load_mesh_for_distances(fa->mesh_path);
    if (!mesh) goto done;
    size_t nv = tg_mesh_vertex_count(mesh);
    if (tg_mesh_face_count(mesh) == 0) {
        cli_error(fa->mesh_path, 0, "the mesh has no faces");
    } else if ((rc = cli_resolve_items("field", fa->mesh_path, fa->sources_path, false, mesh, &bvh, items, lines, count, pts)) == CLI_OK) {
        rc = CLI_INPUT;
        tg_status st = make_solver(mesh, nv, &dist, &geo);
        if (st == TG_OK && (fa->curves.count || fa->curves.boundary) &&
            cli_curve_segments("field", fa->mesh_path, &fa->curves, mesh, &bvh, geo, &seg, &nseg, NULL) != CLI_OK)
            goto close;
        tg_field_options o;
        cli_progress prog;
        tg_field_stats stats;
        start_work(fa, &o, &prog, &stats);
        double t0 = cli_seconds();
        if (st == TG_OK && autolv) {
            st = tg_geodesic_curve_field(geo, NULL, pts, count, seg, nseg, NULL, 0, &o, NULL, dist, NULL);
            if (st == TG_OK) cli_auto_levels(dist, nv, nl, levels);
        }
        if (st == TG_OK) st = tg_isolines_create(NULL, &iso);
        if (st == TG_OK)
            st = tg_geodesic_curve_isolines(geo, NULL, pts, count, seg, nseg, levels, nl, &o, iso, dist, &stats);
        double secs = cli_seconds() - t0;
        cli_interrupt_polling(false);
        cli_progress_end(&prog);
        if ((rc = finished(fa, st)) == CLI_OK && (rc = cli_write_isolines(fa->out, iso)) == CLI_OK && !fa->quiet &&
            strcmp(fa->out, "-")) {
            tg_isolines_view v;
            tg_isolines_get_view(iso, &v);
            size_t closed = 0;
            for (size_t p = 0; p < v.polyline_count; ++p) closed += v.polyline_closed[p];
            printf("sources            %zu\n", count);
            if (nseg) printf("curve segments     %zu\n", nseg);
            printf("levels             %zu (%s .. %s)\n", nl, cli_num(levels[0]).s, cli_num(levels[nl - 1]).s);
            printf("polylines          %zu (%zu closed), %zu points\n", v.polyline_count, closed, v.point_count);
            cli_print_work(&stats, secs);
            rc = fflush(stdout) == 0 ? CLI_OK : CLI_INPUT;
        }
    }
close:
    tg_mesh_destroy(mesh);
done:
    free(pts), free(levels), free(dist), free(seg);
    tg_isolines_destroy(iso);
    tg_geodesic_destroy(geo);
    tg_bvh_destroy(bvh);
    return rc;
}

/* --gradient: per vertex the distance, the unit direction of steepest ascent (the shortest path's
 * arriving direction), its flag and the nearest source, to -o; with --face-gradient per face the
 * same at its centroid. Both files or neither. */
static int run_gradient(const field_args* fa, char** items, const unsigned long long* lines, size_t count)
{
    int rc = CLI_INPUT;
    tg_bvh* bvh = NULL;
    tg_geodesic* geo = NULL;
    double *dist = NULL, *cols = NULL;
    uint8_t *vflag = NULL, *fflag = NULL;
    uint32_t* label = NULL;
    tg_surface_point* pts = malloc((count ? count : 1) * sizeof *pts);
    tg_mesh* mesh = pts ? cli_load_mesh_for_distances(fa->mesh_path) : NULL;
    if (!pts) cli_error(NULL, 0, "out of memory");
    if (!mesh) goto done;
    size_t nv = tg_mesh_vertex_count(mesh), F = tg_mesh_face_count(mesh);
    if (F == 0) {
        cli_error(fa->mesh_path, 0, "the mesh has no faces");
        goto done;
    }
    if ((rc = cli_resolve_items("field", fa->mesh_path, fa->sources_path, false, mesh, &bvh, items, lines, count, pts)) != CLI_OK) goto done;
    rc = CLI_INPUT;
    /* columns: distance, gx, gy, gz, flag, label per vertex; gx, gy, gz, flag per face */
    cols = malloc((6 * nv + 4 * F + 1) * sizeof *cols);
    double* grad = malloc((3 * (nv > F ? nv : F) + 1) * sizeof *grad);
    vflag = malloc(nv + 1), fflag = malloc(F + 1), label = malloc((nv + 1) * sizeof *label);
    tg_status st = cols && grad && vflag && fflag && label ? make_solver(mesh, nv, &dist, &geo) : TG_ERR_OUT_OF_MEMORY;
    tg_field_options o;
    cli_progress prog;
    tg_field_stats stats;
    start_work(fa, &o, &prog, &stats);
    double t0 = cli_seconds();
    double* fgrad = cols + 6 * nv; /* 3 a face, then copied into columns below */
    if (st == TG_OK)
        st = tg_geodesic_field_gradient(geo, NULL, pts, count, &o, grad, vflag, label, dist,
                                        fa->face_gradient ? fgrad : NULL, fa->face_gradient ? fflag : NULL, &stats);
    double secs = cli_seconds() - t0;
    cli_interrupt_polling(false);
    cli_progress_end(&prog);
    if ((rc = finished(fa, st)) == CLI_OK) {
        double* c = cols; /* vertex columns */
        for (size_t v = 0; v < nv; ++v) {
            c[v] = dist[v], c[nv + v] = grad[3 * v], c[2 * nv + v] = grad[3 * v + 1], c[3 * nv + v] = grad[3 * v + 2];
            c[4 * nv + v] = vflag[v], c[5 * nv + v] = label[v] == TG_NONE ? -1.0 : (double)label[v];
        }
        static const char* const vnames[6] = {"distance", "gx", "gy", "gz", "flag", "label"};
        static const char* const fnames[4] = {"gx", "gy", "gz", "flag"};
        const double* vcols[6] = {c, c + nv, c + 2 * nv, c + 3 * nv, c + 4 * nv, c + 5 * nv};
        cli_output_set outs = {0};
        rc = cli_write_columns(&outs, fa->out, mesh, "vertex", vnames, vcols, 6, nv);
        if (rc == CLI_OK && fa->face_gradient) {
            memcpy(grad, fgrad, 3 * F * sizeof *grad); /* the face rows, as columns */
            double* fc = cols + 6 * nv;
            for (size_t f = 0; f < F; ++f)
                fc[f] = grad[3 * f], fc[F + f] = grad[3 * f + 1], fc[2 * F + f] = grad[3 * f + 2], fc[3 * F + f] = fflag[f];
            const double* fcols[4] = {fc, fc + F, fc + 2 * F, fc + 3 * F};
            rc = cli_write_columns(&outs, fa->face_gradient, NULL, "face", fnames, fcols, 4, F);
        }
        if (rc == CLI_OK) rc = cli_output_set_commit(&outs);
        cli_output_set_abort(&outs);
        if (rc == CLI_OK && !fa->quiet && strcmp(fa->out, "-")) {
            size_t counts[4] = {0, 0, 0, 0};
            for (size_t v = 0; v < nv; ++v) counts[vflag[v] & 3]++;
            printf("sources            %zu\n", count);
            printf("vertices           %zu: %zu with a gradient, %zu ties, %zu sources, %zu unreached\n", nv,
                   counts[TG_GRADIENT_DEFINED], counts[TG_GRADIENT_TIE], counts[TG_GRADIENT_SOURCE],
                   counts[TG_GRADIENT_UNREACHED]);
            cli_print_work(&stats, secs);
            rc = fflush(stdout) == 0 ? CLI_OK : CLI_INPUT;
        }
    }
    free(grad);
done:
    free(pts), free(dist), free(cols), free(vflag), free(fflag), free(label);
    tg_geodesic_destroy(geo);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(mesh);
    return rc;
}

/* The sparse matrix as "i,j,d" lines (a header, then one line per stored entry, rows in order). */
static bool write_triplets(FILE* f, const tg_sparse_matrix_view* v)
{
    bool ok = fprintf(f, "i,j,d\n") > 0;
    for (size_t r = 0; ok && r < v->row_count; ++r)
        for (uint64_t e = v->row_start[r]; ok && e < v->row_start[r + 1]; ++e)
            ok = fprintf(f, "%zu,%u,%s\n", r, (unsigned)v->col[e], cli_num(v->value[e]).s) > 0;
    return ok;
}

/* --sources FILE|all with a sparse output: every vertex within the radius of each source. */
static int run_sparse(const field_args* fa, char** items, const unsigned long long* lines, size_t count)
{
    int rc = CLI_INPUT;
    tg_bvh* bvh = NULL;
    tg_geodesic* geo = NULL;
    tg_sparse_matrix* mat = NULL;
    tg_surface_point* pts = NULL;
    tg_mesh* mesh = cli_load_mesh_for_distances(fa->mesh_path);
    if (!mesh) goto done;
    if (tg_mesh_face_count(mesh) == 0) {
        cli_error(fa->mesh_path, 0, "the mesh has no faces");
        goto done;
    }
    if (fa->all) {
        count = tg_mesh_vertex_count(mesh);
    } else {
        pts = malloc(count * sizeof *pts);
        if (!pts) {
            cli_error(NULL, 0, "out of memory");
            goto done;
        }
        if ((rc = cli_resolve_items("field", fa->mesh_path, fa->sources_path, false, mesh, &bvh, items, lines, count, pts)) != CLI_OK) goto done;
        rc = CLI_INPUT;
    }
    tg_status st = tg_geodesic_create(mesh, NULL, &geo);
    tg_field_options o;
    cli_progress prog;
    tg_field_stats stats;
    start_work(fa, &o, &prog, &stats);
    o.limit = TG_FIELD_UNLIMITED; /* the radius is the call's own argument */
    double t0 = cli_seconds();
    if (st == TG_OK) st = tg_sparse_matrix_create(NULL, &mat);
    if (st == TG_OK)
        st = tg_geodesic_local_matrix(geo, pts, count, fa->max_dist >= 0 ? fa->max_dist : INFINITY, &o, fa->threads,
                                      mat, &stats);
    double secs = cli_seconds() - t0;
    cli_interrupt_polling(false);
    cli_progress_end(&prog);
    if ((rc = finished(fa, st)) != CLI_OK) goto done;
    rc = CLI_INPUT; /* for the failures below */
    tg_sparse_matrix_view v;
    tg_sparse_matrix_get_view(mat, &v);
    cli_output out;
    FILE* f = cli_output_open(&out, fa->out);
    if (!f) goto done;
    if (!(fa->format == OUT_NPZ ? cli_write_npz_csr(f, &v) : write_triplets(f, &v))) {
        cli_error(fa->out, 0, "write failed: %s", strerror(errno));
        cli_output_abort(&out);
        goto done;
    }
    if ((rc = cli_output_commit(&out)) != CLI_OK) goto done;
    if (!fa->quiet && strcmp(fa->out, "-")) {
        printf("sources            %zu (one field each%s)\n", count, fa->all ? ", every vertex" : "");
        printf("radius             %s\n", cli_num(fa->max_dist >= 0 ? fa->max_dist : INFINITY).s);
        printf("entries            %zu (%.1f a row, %.1f MiB as CSR)\n", v.entry_count,
               count ? (double)v.entry_count / (double)count : 0.0,
               (double)tg_sparse_matrix_memory_bytes(mat) / 1048576.0);
        cli_print_work(&stats, secs);
    }
    rc = fflush(stdout) == 0 ? CLI_OK : CLI_INPUT;
done:
    free(pts);
    tg_sparse_matrix_destroy(mat);
    tg_geodesic_destroy(geo);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(mesh);
    return rc;
}

/* Sets the curve items (curve:FILE, boundary) of a --from list or a sources file apart from the
 * point SPECs: items (and lines, when not NULL) keep the points, *out_count their number; every
 * item is a site (--labels) or a row (--sources) in the order given (fa->point_site,
 * curve_site, boundary_site, site_count). CLI_OK, or CLI_INPUT when out of memory (printed). */
static int split_curves(field_args* fa, char** items, unsigned long long* lines, size_t all, size_t* out_count)
{
    size_t count = 0;
    fa->point_site = malloc((all ? all : 1) * sizeof *fa->point_site);
    if (!fa->point_site) {
        cli_error(NULL, 0, "out of memory");
        return CLI_INPUT;
    }
    for (size_t i = 0; i < all; ++i) {
        size_t files = fa->curves.count;
        bool had_boundary = fa->curves.boundary;
        if (!cli_curve_item(items[i], &fa->curves)) {
            fa->point_site[count] = (uint32_t)i;
            if (lines) lines[count] = lines[i];
            items[count++] = items[i];
        } else if (fa->curves.count > files) {
            if (files < CLI_CURVES_MAX) fa->curve_site[files] = (uint32_t)i;
        } else if (!had_boundary) {
            fa->boundary_site = (uint32_t)i;
        }
    }
    fa->site_count = all;
    *out_count = count;
    return CLI_OK;
}

/* The files a run reads, with the curve files of fa->curves, checked against its outputs
 * (cli_check_outputs). */
static int check_files(const field_args* fa, const char* at_opt, const char* csv)
{
    cli_file_role* inputs = malloc((3 + fa->curves.count) * sizeof *inputs);
    if (!inputs) {
        cli_error(NULL, 0, "out of memory");
        return CLI_INPUT;
    }
    inputs[0] = (cli_file_role){fa->mesh_path, "mesh"};
    inputs[1] = (cli_file_role){fa->sources_path && strcmp(fa->sources_path, "all") ? fa->sources_path : NULL,
                                "sources file (--sources)"};
    inputs[2] = (cli_file_role){fa->at_path, at_opt && !strcmp(at_opt, "--to") ? "points file (--to)" : "points file (--at)"};
    for (size_t i = 0; i < fa->curves.count && i < CLI_CURVES_MAX; ++i)
        inputs[3 + i] = (cli_file_role){fa->curves.files[i], "curve file (curve:)"};
    const cli_file_role outputs[3] = {{fa->out, csv ? "--csv" : "-o"}, {fa->boundaries, "--boundaries"},
                                      {fa->face_gradient, "--face-gradient"}};
    int check = cli_check_outputs(outputs, 3, inputs, 3 + (fa->curves.count < CLI_CURVES_MAX ? fa->curves.count : CLI_CURVES_MAX));
    free(inputs);
    return check;
}

static int run(int argc, char** argv)
{
    field_args fa;
    memset(&fa, 0, sizeof fa);
    fa.max_dist = -1;
    const char *from = NULL, *csv = NULL, *maxd = NULL, *threads = NULL, *at_opt = NULL;
    for (int i = 1; i < argc; ++i) {
        const char* a = argv[i];
        if (!strcmp(a, "--quiet")) {
            fa.quiet = true;
        } else if (!strcmp(a, "--sparse")) {
            fa.sparse = true;
        } else if (!strcmp(a, "--labels")) {
            fa.labels = true;
        } else if (!strcmp(a, "--gradient")) {
            fa.gradient = true;
        } else if (!strcmp(a, "--from") || !strcmp(a, "-o") || !strcmp(a, "--csv") || !strcmp(a, "--max-distance") ||
                   !strcmp(a, "--sources") || !strcmp(a, "--threads") || !strcmp(a, "--at") || !strcmp(a, "--to") ||
                   !strcmp(a, "--boundaries") || !strcmp(a, "--isolines") || !strcmp(a, "--isoline-count") ||
                   !strcmp(a, "--face-gradient")) {
            if (i + 1 >= argc) return cli_usage("field", "%s needs a value", a);
            const char* val = argv[++i];
            if (!strcmp(a, "--from"))
                from = val;
            else if (!strcmp(a, "-o"))
                fa.out = val;
            else if (!strcmp(a, "--csv"))
                csv = val;
            else if (!strcmp(a, "--sources"))
                fa.sources_path = val;
            else if (!strcmp(a, "--threads"))
                threads = val;
            else if (!strcmp(a, "--at"))
                fa.at_path = val, at_opt = "--at";
            else if (!strcmp(a, "--to"))
                fa.at_path = val, at_opt = "--to";
            else if (!strcmp(a, "--boundaries"))
                fa.boundaries = val;
            else if (!strcmp(a, "--isolines"))
                fa.isolines = val;
            else if (!strcmp(a, "--isoline-count"))
                fa.isoline_count = val;
            else if (!strcmp(a, "--face-gradient"))
                fa.face_gradient = val;
            else
                maxd = val;
        } else if (a[0] == '-' && a[1]) {
            return cli_usage("field", "unknown option '%s'", a);
        } else if (!fa.mesh_path) {
            fa.mesh_path = a;
        } else {
            return cli_usage("field", "unexpected argument '%s'", a);
        }
    }
    if (!fa.mesh_path) return cli_usage("field", "missing MESH");
    if (!from == !fa.sources_path) return cli_usage("field", "give either --from SPEC[;SPEC...] or --sources FILE");
    if (fa.out && csv) return cli_usage("field", "-o and --csv exclude each other");
    if (fa.isolines && fa.isoline_count)
        return cli_usage("field", "give the levels (--isolines L,L,...) or their count (--isoline-count N), not both");
    if (fa.face_gradient && !fa.gradient) return cli_usage("field", "--face-gradient goes with --gradient");
    if (fa.gradient) { /* the gradient of the field of the sources to -o (and --face-gradient) */
        bool ext = fa.out && (!strcmp(fa.out, "-") || cli_ext_is(fa.out, ".npy") || cli_ext_is(fa.out, ".csv") ||
                              cli_ext_is(fa.out, ".ply"));
        if (!ext) return cli_usage("field", "--gradient writes -o G.npy, G.csv or G.ply");
        if (fa.face_gradient && !cli_ext_is(fa.face_gradient, ".npy") && !cli_ext_is(fa.face_gradient, ".csv"))
            return cli_usage("field", "--face-gradient %s: the extension must be .npy or .csv", fa.face_gradient);
        if (csv || fa.labels || fa.at_path || fa.sparse || fa.isolines || fa.isoline_count ||
            (fa.sources_path && !strcmp(fa.sources_path, "all")))
            return cli_usage("field", "--gradient goes with --from or --sources FILE, -o, --face-gradient, "
                                      "--max-distance and --threads only");
    } else if (fa.isolines || fa.isoline_count) { /* one field of the sources, its isolines to -o */
        const char* opt = fa.isolines ? "--isolines" : "--isoline-count";
        if (!fa.out || !(cli_ext_is(fa.out, ".obj") || cli_ext_is(fa.out, ".json")))
            return cli_usage("field", "%s writes -o ISO.obj or ISO.json", opt);
        if (csv || fa.labels || fa.at_path || fa.sparse || (fa.sources_path && !strcmp(fa.sources_path, "all")))
            return cli_usage("field", "%s goes with --from or --sources FILE, -o and --max-distance only", opt);
    } else if (csv) {
        fa.out = csv;
        fa.format = OUT_CSV;
    } else if (fa.out) {
        fa.format = !strcmp(fa.out, "-") ? OUT_CSV : format_of(fa.out);
        if (fa.format == OUT_NONE && !(fa.at_path && strrchr(fa.out, '.') && !strcmp(strrchr(fa.out, '.'), ".txt")))
            return cli_usage("field", "-o %s: the extension must be .ply, .csv, .npy or .npz", fa.out);
    }
    fa.matrix = fa.sources_path != NULL && !fa.labels && !fa.isolines && !fa.isoline_count && !fa.gradient;
    if (fa.boundaries && !fa.labels) return cli_usage("field", "--boundaries goes with --labels");
    if (fa.boundaries && !cli_ext_is(fa.boundaries, ".obj") && !cli_ext_is(fa.boundaries, ".json"))
        return cli_usage("field", "--boundaries %s: the extension must be .obj or .json", fa.boundaries);
    if (fa.labels && fa.at_path) return cli_usage("field", "--labels and %s exclude each other", at_opt);
    if (fa.labels && (fa.format == OUT_NPY || fa.format == OUT_NPZ || fa.sparse))
        return cli_usage("field", "--labels writes -o OUT.ply or OUT.csv");
    if (fa.labels && fa.sources_path && !strcmp(fa.sources_path, "all"))
        return cli_usage("field", "--labels needs the sources listed in a FILE, not all");
    fa.all = fa.matrix && !strcmp(fa.sources_path, "all");
    if (at_opt && !strcmp(at_opt, "--at") && fa.matrix) return cli_usage("field", "--at goes with --from; with --sources, --to");
    if (at_opt && !strcmp(at_opt, "--to") && !fa.matrix) return cli_usage("field", "--to goes with --sources; with --from, --at");
    if (fa.at_path && fa.out && fa.format == OUT_PLY) return cli_usage("field", "%s writes distances: -o OUT.csv, .npy or .txt", at_opt);
    if (fa.matrix && !fa.out) return cli_usage("field", "--sources needs -o MATRIX.npz, .npy or .csv");
    if (fa.matrix && fa.format == OUT_PLY) return cli_usage("field", "--sources writes a matrix: -o MATRIX.npz, .npy or .csv");
    if (!fa.matrix && (fa.format == OUT_NPZ || fa.sparse))
        return cli_usage("field", "a sparse matrix (.npz, --sparse) needs --sources FILE|all");
    fa.sparse = fa.sparse || fa.format == OUT_NPZ || fa.all;
    if (fa.sparse && fa.format == OUT_NPY)
        return cli_usage("field", "the sparse matrix (--sources all, --sparse) is written as .npz or .csv, not .npy");
    if (fa.sparse && fa.at_path)
        return cli_usage("field", "--to writes the dense sources x points matrix: -o .npy or .csv, without --sparse");
    if (maxd && !cli_parse_nonneg(maxd, &fa.max_dist))
        return cli_usage("field", "--max-distance needs a finite number >= 0, not '%s'", maxd);
    unsigned long long nt = 0;
    if (threads && (!cli_parse_uint(threads, &nt) || nt > TG_MAX_THREADS))
        return cli_usage("field", "--threads needs a number in 0..%d (0 = all cores), not '%s'", TG_MAX_THREADS, threads);
    fa.threads = (int)nt;
    fa.field_threads = 1;
    if (threads && !fa.matrix) /* one field (--from, --labels' each source, --isolines) on several threads */
        fa.field_threads = nt == 0 ? TG_THREADS_ALL : (int)nt;
    /* the --from list: point SPECs, and curve sources (curve:FILE, boundary) set apart */
    char* list = NULL;
    char** items = NULL;
    size_t count = 0;
    if (from) {
        size_t len = strlen(from);
        list = malloc(len + 1);
        items = malloc(MAX_SOURCES * sizeof *items);
        if (!list || !items) {
            free(list), free(items), free(fa.point_site);
            cli_error(NULL, 0, "out of memory");
            return CLI_INPUT;
        }
        memcpy(list, from, len + 1);
        size_t all = cli_split_list(list, items, MAX_SOURCES);
        if (split_curves(&fa, items, NULL, all, &count) != CLI_OK) {
            free(list), free(items), free(fa.point_site);
            return CLI_INPUT;
        }
        int bad = all == 0 ? cli_usage("field", "bad --from list \"%s\" (SPEC;SPEC;..., no empty item, at most %d)",
                                       from, MAX_SOURCES)
                  : fa.curves.count > CLI_CURVES_MAX ? cli_usage("field", "at most %d curve files", CLI_CURVES_MAX)
                  : (fa.curves.boundary || fa.curves.count) && fa.gradient
                      ? cli_usage("field", "curve sources (curve:FILE, boundary) go with a field (-o, --at, --labels, "
                                           "--isolines, --max-distance, --threads), not yet with --gradient")
                  : (fa.curves.boundary || fa.curves.count) && fa.boundaries
                      ? cli_usage("field", "--boundaries draws the cells of point sources only, not of curves")
                      : CLI_OK;
        if (bad != CLI_OK) {
            free(list), free(items), free(fa.point_site);
            return bad;
        }
    }
    int check = check_files(&fa, at_opt, csv);
    if (check == CLI_OK && (fa.sources_path || fa.field_threads != 1) && !cli_threads_available(fa.threads, "field"))
        check = CLI_INPUT;
    if (check != CLI_OK) {
        free(list), free(items), free(fa.point_site);
        return check;
    }
    int rc;
    char* at_text = NULL;
    if (fa.at_path) {
        long na = cli_read_lines(fa.at_path, "points", &at_text, &fa.at_items, &fa.at_lines, NULL);
        if (na < 0) {
            free(list), free(items), free(fa.point_site);
            return CLI_INPUT;
        }
        fa.at_count = (size_t)na;
    }
    if (fa.sources_path) { /* a matrix, or the Voronoi cells of the listed sources */
        char* text = NULL;
        char** rows = NULL;
        unsigned long long* lines = NULL;
        long n = fa.all ? 0 : cli_read_lines(fa.sources_path, "sources", &text, &rows, &lines, NULL);
        size_t kept = 0;
        rc = n < 0 ? CLI_INPUT : split_curves(&fa, rows, lines, (size_t)n, &kept);
        if (rc == CLI_OK && (fa.curves.count || fa.curves.boundary)) { /* curve rows */
            rc = fa.curves.count > CLI_CURVES_MAX ? cli_usage("field", "at most %d curve files", CLI_CURVES_MAX)
                 : fa.sparse || fa.gradient || fa.boundaries
                     ? cli_usage("field", "curve rows (curve:FILE, boundary) in --sources go with the dense matrix "
                                          "(-o .npy, .csv; --to), --labels and --isolines")
                     : check_files(&fa, at_opt, csv);
            n = (long)kept;
        }
        if (rc == CLI_OK)
            rc = fa.gradient ? run_gradient(&fa, rows, lines, (size_t)n)
                 : fa.isolines || fa.isoline_count ? run_isolines(&fa, rows, lines, (size_t)n)
                 : fa.sparse ? run_sparse(&fa, rows, lines, (size_t)n)
                             : run_field(&fa, rows, lines, (size_t)n);
        free(text), free(rows), free(lines), free(fa.point_site);
        free(at_text), free(fa.at_items), free(fa.at_lines);
        return rc;
    }
    rc = fa.gradient ? run_gradient(&fa, items, NULL, count)
         : fa.isolines || fa.isoline_count ? run_isolines(&fa, items, NULL, count)
                                           : run_field(&fa, items, NULL, count);
    free(list), free(items), free(fa.point_site);
    free(at_text), free(fa.at_items), free(fa.at_lines);
    return rc;
}

const cli_command cli_cmd_field = {
    "field",
    "field MESH --from SPEC[;SPEC...] [--at POINTS] | --sources FILE|all [--to POINTS] [-o OUT.ply|.csv|.npy|.npz]\n"
    "       [--max-distance D] [--sparse] [--labels [--boundaries B.obj|.json]] [--isolines L,L,... | --isoline-count N -o ISO.obj|.json]\n"
    "       [--gradient -o G.npy|.csv|.ply [--face-gradient FG.npy|.csv]]",
    "The exact geodesic distance from surface points to every vertex (window propagation: window\n"
    "lists crossing one face at a time behind a front of vertices, after Qin et al. 2016 and Xin &\n"
    "Wang 2009). Distance is intrinsic: faces' winding does not matter, and paths continue into\n"
    "every face at a non-manifold edge.\n\n"
    "  --from SPEC[;SPEC...]  one field, the distance to the nearest of these sources:\n"
    "                                   v:IDX            a vertex\n"
    "                                   f:FACE:b0,b1,b2  a point of a face (barycentric; within 1e-6\n"
    "                                                    of summing to 1 they are rescaled)\n"
    "                                   e:HALFEDGE:t     a point of an edge (halfedge 3*face+corner)\n"
    "                                   p:x,y,z          the surface point closest to x,y,z\n"
    "                                   curve:FILE       every point of a curve: FILE has one point\n"
    "                                                    a line (a SPEC, x y z, or an OBJ v line:\n"
    "                                                    a path's .obj is a curve), a blank line\n"
    "                                                    between polylines; consecutive points lie\n"
    "                                                    in one face or on one edge (a point within\n"
    "                                                    1e-9 of an edge or corner is taken on it)\n"
    "                                   boundary         every boundary edge of the mesh\n"
    "                         curves are exact sources (their segments' insides too), with -o,\n"
    "                         --at, --isolines (offset curves), --max-distance and --threads\n"
    "  --sources FILE|all     one field per source: FILE has one SPEC a line ('#' comments and\n"
    "                         blank lines skipped; '-' reads stdin), 'all' is every vertex in order\n"
    "                         (sparse outputs only); the fields are computed in parallel and\n"
    "                         written as the distance matrix, one row per source; a line\n"
    "                         curve:FILE or boundary is a row of that curve (dense matrix, --to,\n"
    "                         --labels, --isolines: the nearest row's)\n"
    "  --to POINTS            with --sources: the matrix of sources x these points (SPEC or \"x y z\"\n"
    "                         a line), each field stopped once its points are settled (.npy, .csv)\n"
    "  --sparse               with --sources: only the entries within --max-distance (every\n"
    "                         reachable one without it), as .csv triplets; implied by .npz and 'all'\n"
    "  -o OUT                 the format follows the extension:\n"
    "                           .ply  (--from) the mesh as binary PLY with a per-vertex double\n"
    "                                 property 'distance' (trigeo render MESH --field OUT.ply)\n"
    "                           .csv  --from: rows vertex,distance; --sources: one row of\n"
    "                                 vertex_count distances per source, no header\n"
    "                           .npy  NumPy float64: shape (vertices,) or (sources, vertices)\n"
    "                           .npz  (--sources) the sparse matrix as scipy.sparse.load_npz reads\n"
    "                                 it (CSR: format, shape, indptr, indices, data)\n"
    "                           .csv  sparse: a header i,j,d, then one line per entry (row i =\n"
    "                                 source, column j = vertex, d = distance)\n"
    "                         '-' writes CSV to stdout\n"
    "  --csv OUT              the same as -o with CSV whatever the extension\n"
    "  --at POINTS            with --from: the distance at these surface points instead of the\n"
    "                         vertices: POINTS has one SPEC or \"x y z\" a line (x y z: the closest\n"
    "                         surface point); one distance a line to -o (.txt, .csv or\n"
    "                         .npy) or stdout\n"
    "  --labels               Voronoi cells of the sources (--from or --sources): per vertex the\n"
    "                         index of the nearest source (0-based, in the order given; ties to\n"
    "                         the lowest; -1 where none reaches) and its distance, as PLY\n"
    "                         properties 'label' and 'distance' (trigeo render --labels) or CSV\n"
    "                         rows vertex,label,distance; equal to the argmin over the sources'\n"
    "                         separate fields; with curves in --from every item of the list is a\n"
    "                         site (a curve file all its polylines, boundary the whole boundary)\n"
    "  --boundaries B         with --labels: the cells' boundaries as polylines; on every edge\n"
    "                         between two cells the point where the two sources' distances are\n"
    "                         equal (to 1e-10 relative), joined inside faces (a face of three cells\n"
    "                         gets a junction at the mean of its crossings); .obj: 'v' and 'l'\n"
    "                         records (a '# cells A B' comment before each 'l'; trigeo render\n"
    "                         --path draws them); .json: {\"polylines\": [{\"cells\": [A, B],\n"
    "                         \"points\": [[x, y, z], ...], \"surface\": [\"e:H:t\" | \"f:F:b0,b1,b2\"]}]}\n"
    "  --isolines L,L,...     the exact isolines of the field (--from, or --sources FILE: the nearest\n"
    "                         source) at these levels (a number is always a level: 3 is the level\n"
    "                         3, as in Python's Mesh.isolines); crossings of edges exact, arcs\n"
    "                         inside faces within 1e-3 of the face; -o ISO.obj: 'v' records, a\n"
    "                         group 'g level_I' ('# level L') of 'l' polylines per level (closed\n"
    "                         ones end on their first vertex); -o ISO.json: {\"levels\": [...],\n"
    "                         \"polylines\": [{\"level\": I, \"value\": L, \"closed\": B, \"points\":\n"
    "                         [[x, y, z], ...], \"faces\": [...], \"surface\": [\"e:H:t\", ...]}]};\n"
    "                         negative, NaN or missing levels: exit 2, no file; from curve:FILE or\n"
    "                         boundary the curves' exact offset curves (straight beside a segment)\n"
    "  --gradient             the exact gradient to -o: per vertex distance, gx, gy, gz (the unit\n"
    "                         direction in which its shortest path arrives: steepest ascent), flag\n"
    "                         (0 defined, 1 a source, 2 unreached, 3 two sources tie) and label\n"
    "                         (the nearest source, -1 none): CSV vertex,distance,gx,gy,gz,flag,label,\n"
    "                         (n, 6) .npy or PLY properties; with --from or --sources FILE\n"
    "  --face-gradient FG     with --gradient: per face at its centroid gx, gy, gz, flag (.npy (F, 4)\n"
    "                         or CSV face,gx,gy,gz,flag); both files or neither\n"
    "  --isoline-count N      instead of --isolines: N levels equally spaced below the largest\n"
    "                         distance (max * k / (N + 1), k = 1..N; Python: isolines(count=N))\n"
    "  --max-distance D       stop at distance D (0 allowed): farther vertices get inf\n"
    "  --threads N            at most 256, 0 = all cores. --sources (a matrix): the rows spread\n"
    "                         over N threads (default 0). --from (with --at, --isolines) and\n"
    "                         --labels: one field's window propagation on N threads (default 1:\n"
    "                         the serial engine); every N > 1 gives the same bits, within\n"
    "                         1e-14 relative of one thread's (a label, at a tie, may differ)\n"
    "  --quiet                no progress line (else drawn on stderr when it is a terminal and\n"
    "                         the work passes about a second) and no summary; errors are still\n"
    "                         printed, and data sent to stdout (-o -, --at) still is\n\n"
    "Unreachable vertices (other components, unused vertices) get inf. Outputs are written into a\n"
    "private temporary directory beside the target and renamed when complete: an error or Ctrl-C\n"
    "(exit 130) leaves no partial file; an output that is one of the inputs is refused. Without\n"
    "-o - and --quiet a summary (vertices reached, largest distance, windows, seconds) goes to\n"
    "stdout. Quote the --from list: ';' is special to the shell.\n",
    run,
};
