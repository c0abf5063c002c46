/* cmd_field.c - `trigeo field MESH --from SPEC[;SPEC...] [-o FIELD.ply | --csv OUT.csv]
 * [--max-distance D]`: the exact geodesic distance from one or more surface points to every
 * vertex (tg_geodesic_field), written as a PLY vertex property `distance` (which `trigeo render
 * --field` draws) or as CSV rows vertex,distance.
 * Based on: the CLI contract of the project's DESIGN.md. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define MAX_SOURCES 4096

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Splits the ';'-separated list in place; returns the count, or 0 for an empty item or too many. */
static size_t split_specs(char* list, char** items, size_t cap)
{
    size_t n = 0;
    for (char* s = list;;) {
        char* semi = strchr(s, ';');
        if (semi) *semi = '\0';
        if (!*s || n == cap) return 0;
        items[n++] = s;
        if (!semi) return n;
        s = semi + 1;
    }
}

static int write_csv(const char* out_path, const double* d, size_t n)
{
    bool to_stdout = !strcmp(out_path, "-");
    FILE* f = to_stdout ? stdout : fopen(out_path, "w");
    if (!f) {
        cli_error(out_path, 0, "cannot open for writing: %s", strerror(errno));
        return CLI_INPUT;
    }
    fprintf(f, "vertex,distance\n");
    for (size_t v = 0; v < n; ++v) fprintf(f, "%zu,%.17g\n", v, d[v]);
    int bad = to_stdout ? fflush(f) != 0 : fclose(f) != 0;
    if (bad) {
        cli_error(out_path, 0, "write failed");
        return CLI_INPUT;
    }
    return CLI_OK;
}

static void print_summary(size_t sources, const double* d, size_t n, double secs, const tg_field_stats* st)
{
    size_t reached = 0;
    double far = 0;
    for (size_t v = 0; v < n; ++v)
        if (isfinite(d[v])) reached++, far = fmax(far, d[v]);
    printf("sources            %zu\n", sources);
    printf("vertices           %zu (%zu reached)\n", n, reached);
    printf("max distance       %.17g\n", far);
    printf("windows            %llu propagated, %llu created\n", (unsigned long long)st->windows_propagated,
           (unsigned long long)st->windows_created);
    printf("seconds            %.3f\n", secs);
}

static int run_field(const char* mesh_path, char* from, const char* ply_path, const char* csv_path, double max_dist)
{
    char* items[MAX_SOURCES];
    size_t count = split_specs(from, items, MAX_SOURCES);
    if (!count) return cli_usage("field", "bad --from list (SPEC[;SPEC...], at most %d)", MAX_SOURCES);
    cli_spec* specs = malloc(count * sizeof *specs);
    tg_surface_point* pts = malloc(count * sizeof *pts);
    if (!specs || !pts) {
        free(specs), free(pts);
        cli_error(NULL, 0, "out of memory");
        return CLI_INPUT;
    }
    for (size_t i = 0; i < count; ++i) {
        if (!cli_parse_spec(items[i], &specs[i])) {
            free(specs), free(pts);
            return cli_usage("field", "bad source '%s' (v:IDX, f:FACE:b0,b1,b2, e:HALFEDGE:t or p:x,y,z)", items[i]);
        }
    }
    int rc = CLI_INPUT;
    tg_bvh* bvh = NULL;
    tg_geodesic* geo = NULL;
    double* dist = NULL;
    tg_mesh* mesh = cli_load_mesh(mesh_path);
    if (!mesh) goto done;
    if (tg_mesh_face_count(mesh) == 0) {
        cli_error(mesh_path, 0, "the mesh has no faces");
        goto done;
    }
    for (size_t i = 0; i < count; ++i)
        if (!cli_resolve_spec(mesh_path, mesh, &bvh, items[i], &specs[i], &pts[i])) goto done;
    size_t n = tg_mesh_vertex_count(mesh);
    dist = malloc((n ? n : 1) * sizeof *dist);
    tg_status st = dist ? tg_geodesic_create(mesh, NULL, &geo) : TG_ERR_OUT_OF_MEMORY;
    tg_field_options o;
    memset(&o, 0, sizeof o);
    if (max_dist > 0) o.limit = TG_FIELD_MAX_DISTANCE, o.max_distance = max_dist;
    tg_field_stats stats;
    double t0 = now_s();
    if (st == TG_OK) st = tg_geodesic_field(geo, pts, count, &o, dist, &stats);
    double secs = now_s() - t0;
    if (st != TG_OK) {
        cli_error(mesh_path, 0, "%s", tg_status_string(st));
        goto done;
    }
    if (ply_path) {
        tg_diag d;
        memset(&d, 0, sizeof d);
        tg_vertex_scalar sc = {"distance", dist};
        st = tg_mesh_write_ply(mesh, ply_path, &sc, 1, &d);
        if (st != TG_OK) {
            cli_error_diag(&d, st);
            goto done;
        }
    }
    if (csv_path && (rc = write_csv(csv_path, dist, n)) != CLI_OK) goto done;
    if (!csv_path || strcmp(csv_path, "-")) print_summary(count, dist, n, secs, &stats);
    rc = fflush(stdout) == 0 ? CLI_OK : CLI_INPUT;
done:
    free(specs), free(pts), free(dist);
    tg_geodesic_destroy(geo);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(mesh);
    return rc;
}

static int run(int argc, char** argv)
{
    const char *mesh_path = NULL, *from = NULL, *ply = NULL, *csv = NULL, *maxd = NULL;
    for (int i = 1; i < argc; ++i) {
        const char* a = argv[i];
        if (!strcmp(a, "--from") || !strcmp(a, "-o") || !strcmp(a, "--csv") || !strcmp(a, "--max-distance")) {
            if (i + 1 >= argc) return cli_usage("field", "%s needs a value", a);
            const char* val = argv[++i];
            if (!strcmp(a, "--from"))
                from = val;
            else if (!strcmp(a, "-o"))
                ply = val;
            else if (!strcmp(a, "--csv"))
                csv = val;
            else
                maxd = val;
        } else if (a[0] == '-' && a[1]) {
            return cli_usage("field", "unknown option '%s'", a);
        } else if (!mesh_path) {
            mesh_path = a;
        } else {
            return cli_usage("field", "unexpected argument '%s'", a);
        }
    }
    if (!mesh_path) return cli_usage("field", "missing MESH");
    if (!from) return cli_usage("field", "missing --from SPEC[;SPEC...]");
    if (ply && csv) return cli_usage("field", "-o and --csv exclude each other");
    double max_dist = 0;
    if (maxd && (!cli_parse_double(maxd, &max_dist) || max_dist < 0))
        return cli_usage("field", "--max-distance needs a non-negative number, not '%s'", maxd);
    size_t len = strlen(from);
    char* list = malloc(len + 1);
    if (!list) {
        cli_error(NULL, 0, "out of memory");
        return CLI_INPUT;
    }
    memcpy(list, from, len + 1);
    int rc = run_field(mesh_path, list, ply, csv, max_dist);
    free(list);
    return rc;
}

const cli_command cli_cmd_field = {
    "field",
    "field MESH --from SPEC[;SPEC...] [-o FIELD.ply | --csv OUT.csv] [--max-distance D]",
    "The exact geodesic distance from one or more surface points to every vertex (window\n"
    "propagation, Xin & Wang's improved Chen-Han algorithm); with several sources, the distance to\n"
    "the nearest.\n\n"
    "  --from SPEC[;SPEC...]  sources:  v:IDX            a vertex\n"
    "                                   f:FACE:b0,b1,b2  a point of a face (barycentric)\n"
    "                                   e:HALFEDGE:t     a point of an edge (halfedge 3*face+corner)\n"
    "                                   p:x,y,z          the surface point closest to x,y,z\n"
    "  -o FIELD.ply           write the mesh as binary PLY with a per-vertex double property\n"
    "                         'distance' (draw it with: trigeo render MESH --field FIELD.ply -o OUT.png)\n"
    "  --csv OUT.csv          write CSV rows vertex,distance (%.17g; '-' for stdout)\n"
    "  --max-distance D       stop at distance D: farther vertices get inf\n\n"
    "Unreachable vertices (other components, unused vertices) get inf. Without --csv - a summary\n"
    "(vertices reached, largest distance, windows, seconds) goes to stdout. Quote the list: ';' is\n"
    "special to the shell.\n",
    run,
};
