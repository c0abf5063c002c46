/* cmd_sample.c - `trigeo sample MESH --count K [--start SPEC | --seed N] [-o SAMPLES] [--field
 * FIELD.ply|.csv]`: farthest-point sampling in exact geodesic distance
 * (tg_geodesic_farthest_point_sampling): the samples in order, and optionally the distance to
 * the nearest sample and its position per vertex.
 * Based on: the CLI contract of the project's DESIGN.md. */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static int on_progress(void* user, const tg_field_progress* p)
{
    char detail[96];
    snprintf(detail, sizeof detail, "%zu/%zu samples", p->rows_done, p->row_count);
    cli_progress_update(user, p->settled_fraction, detail);
    return cli_interrupted();
}

/* The samples: .txt one `v:IDX` spec a line (a sources file for `trigeo field --sources`), .csv
 * rows i,vertex,x,y,z. */
static int write_samples(cli_output_set* set, const char* path, const tg_mesh* mesh, const uint32_t* s, size_t k)
{
    FILE* f = cli_output_set_open(set, path);
    if (!f) return CLI_INPUT;
    bool csv = strcmp(path, "-") != 0 && cli_ext_is(path, ".csv");
    const double* xyz = tg_mesh_positions(mesh);
    bool ok = !csv || fprintf(f, "i,vertex,x,y,z\n") > 0;
    for (size_t i = 0; ok && i < k; ++i) {
        const double* p = xyz + 3 * (size_t)s[i];
        ok = csv ? fprintf(f, "%zu,%u,%s,%s,%s\n", i, s[i], cli_num(p[0]).s, cli_num(p[1]).s, cli_num(p[2]).s) > 0
                 : fprintf(f, "v:%u\n", s[i]) > 0;
    }
    if (!ok) {
        cli_error(path, 0, "write failed: %s", strerror(errno));
        return CLI_INPUT;
    }
    return CLI_OK;
}


typedef struct sample_args {
    const char* mesh_path;
    const char *out, *field_out, *start;
    unsigned long long count, seed, iterations;
    bool quiet, cvt;
    int threads; /* tg_field_options.threads (cli_field_threads) */
} sample_args;

/* --cvt: the sites (surface points): .txt one SPEC a line, .csv rows i,site,x,y,z (the site a
 * quoted SPEC). */
static int write_sites(cli_output_set* set, const char* path, const tg_mesh* mesh, const tg_surface_point* s, size_t k)
{
    FILE* f = cli_output_set_open(set, path);
    if (!f) return CLI_INPUT;
    bool csv = strcmp(path, "-") != 0 && cli_ext_is(path, ".csv");
    bool ok = !csv || fprintf(f, "i,site,x,y,z\n") > 0;
    for (size_t i = 0; ok && i < k; ++i) {
        char spec[CLI_SPEC_TEXT_MAX];
        double p[3];
        cli_spec_text(&s[i], spec, sizeof spec);
        tg_surface_point_position(mesh, &s[i], p);
        /* the SPEC holds commas: quoted (RFC 4180) */
        ok = csv ? fprintf(f, "%zu,\"%s\",%s,%s,%s\n", i, spec, cli_num(p[0]).s, cli_num(p[1]).s, cli_num(p[2]).s) > 0
                 : fprintf(f, "%s\n", spec) > 0;
    }
    if (!ok) {
        cli_error(path, 0, "write failed: %s", strerror(errno));
        return CLI_INPUT;
    }
    return CLI_OK;
}

/* --cvt after the farthest-point samples: Lloyd's iteration from them, the sites written, the
 * final cells as --field, the energies in the summary. */
static int run_cvt(const sample_args* sa, tg_mesh* mesh, tg_geodesic* geo, const uint32_t* samples, uint32_t* label,
                   double* dist, cli_progress* prog)
{
    size_t k = sa->count, n = tg_mesh_vertex_count(mesh), iters = sa->iterations ? sa->iterations : 10, done = 0;
    tg_surface_point* sites = malloc(k * sizeof *sites);
    double* energies = malloc((iters + 1) * sizeof *energies);
    int rc = CLI_INPUT;
    if (!sites || !energies) {
        cli_error(NULL, 0, "out of memory");
        goto done;
    }
    for (size_t i = 0; i < k; ++i) sites[i] = tg_surface_vertex(samples[i]);
    tg_centroidal_options co;
    memset(&co, 0, sizeof co);
    co.iterations = (uint32_t)iters;
    co.progress = on_progress;
    co.progress_user = prog;
    double t0 = cli_seconds();
    cli_interrupt_polling(true);
    tg_status st = tg_geodesic_centroidal_voronoi(geo, NULL, sites, 0, k, &co, sites, label, energies, &done);
    tg_field_options fo;
    memset(&fo, 0, sizeof fo);
    fo.progress = on_progress, fo.progress_user = prog;
    if (st == TG_OK && sa->field_out) st = tg_geodesic_voronoi(geo, NULL, sites, k, &fo, NULL, dist, label, NULL);
    cli_interrupt_polling(false);
    double secs = cli_seconds() - t0;
    cli_progress_end(prog);
    if (st == TG_ERR_CANCELLED) {
        cli_error(sa->mesh_path, 0, "interrupted: nothing written");
        rc = 130;
        goto done;
    }
    if (st != TG_OK) {
        cli_error(sa->mesh_path, 0, "%s", tg_status_string(st));
        goto done;
    }
    cli_output_set outs = {0};
    rc = sa->out ? write_sites(&outs, sa->out, mesh, sites, k) : CLI_OK;
    if (rc == CLI_OK && sa->field_out) rc = cli_write_labels(&outs, sa->field_out, mesh, label, dist, n);
    if (rc == CLI_OK) rc = cli_output_set_commit(&outs);
    cli_output_set_abort(&outs);
    if (rc != CLI_OK) goto done;
    if (!sa->quiet && (!sa->out || strcmp(sa->out, "-"))) {
        printf("sites              %zu (centroidal Voronoi from the farthest-point samples)\n", k);
        printf("iterations         %zu\n", done);
        printf("energies          ");
        for (size_t i = 0; i <= done; ++i) printf(" %s", cli_num(energies[i]).s);
        printf("\nseconds            %.3f\n", secs);
    }
    rc = fflush(stdout) == 0 ? CLI_OK : CLI_INPUT;
done:
    free(sites);
    free(energies);
    return rc;
}

static int run_sample(const sample_args* sa)
{
    int rc = CLI_INPUT;
    tg_bvh* bvh = NULL;
    tg_geodesic* geo = NULL;
    uint32_t *samples = NULL, *label = NULL;
    double* dist = NULL;
    tg_mesh* mesh = cli_load_mesh_for_distances(sa->mesh_path);
    if (!mesh) goto done;
    size_t n = tg_mesh_vertex_count(mesh);
    uint32_t start = TG_NONE;
    if (sa->start) {
        cli_spec sp;
        tg_surface_point p;
        if (!cli_parse_spec(sa->start, &sp) || sp.kind != 'v') {
            rc = cli_usage("sample", "--start needs a vertex, v:IDX, not '%s'", sa->start);
            goto done;
        }
        if (!cli_resolve_spec(sa->mesh_path, mesh, &bvh, sa->start, &sp, &p)) goto done;
        start = p.index;
    }
    if (tg_geodesic_create(mesh, NULL, &geo) != TG_OK) {
        cli_error(sa->mesh_path, 0, "out of memory");
        goto done;
    }
    samples = malloc(sa->count * sizeof *samples);
    label = malloc((n ? n : 1) * sizeof *label);
    dist = malloc((n ? n : 1) * sizeof *dist);
    if (!samples || !label || !dist) {
        cli_error(NULL, 0, "out of memory");
        goto done;
    }
    tg_field_options o;
    memset(&o, 0, sizeof o);
    o.threads = sa->threads;
    cli_progress prog;
    cli_progress_start(&prog, "sample", sa->quiet);
    o.progress = on_progress;
    o.progress_user = &prog;
    cli_interrupt_polling(true); /* the progress callback looks at the flag */
    tg_field_stats stats;
    double t0 = cli_seconds();
    tg_status st = tg_geodesic_farthest_point_sampling(geo, NULL, start, sa->seed, sa->count, &o, samples, dist, label,
                                                       &stats);
    double secs = cli_seconds() - t0;
    cli_interrupt_polling(false);
    if (!sa->cvt || st != TG_OK) cli_progress_end(&prog);
    if (st == TG_ERR_CANCELLED) {
        cli_error(sa->mesh_path, 0, "interrupted: nothing written");
        rc = 130;
        goto done;
    }
    if (st == TG_ERR_INVALID_ARGUMENT) { /* the count (the start was validated above) */
        const tg_mesh_report* r = tg_mesh_get_report(mesh);
        cli_error(sa->mesh_path, 0, "--count %llu: the mesh has only %llu vertices used by faces", sa->count,
                  (unsigned long long)(r->vertices - r->unreferenced_vertices));
        goto done;
    }
    if (st != TG_OK) {
        cli_error(sa->mesh_path, 0, "%s", tg_status_string(st));
        goto done;
    }
    if (sa->cvt) {
        rc = run_cvt(sa, mesh, geo, samples, label, dist, &prog);
        goto done;
    }
    /* the samples and the field: both files or neither */
    cli_output_set outs = {0};
    rc = sa->out ? write_samples(&outs, sa->out, mesh, samples, sa->count) : CLI_OK;
    if (rc == CLI_OK && sa->field_out) rc = cli_write_labels(&outs, sa->field_out, mesh, label, dist, n);
    if (rc == CLI_OK) rc = cli_output_set_commit(&outs);
    cli_output_set_abort(&outs);
    if (rc != CLI_OK) goto done;
    if (!sa->quiet && (!sa->out || strcmp(sa->out, "-"))) {
        double far = 0;
        for (size_t v = 0; v < n; ++v)
            if (isfinite(dist[v]) && dist[v] > far) far = dist[v];
        printf("samples            %llu (first v:%u)\n", sa->count, samples[0]);
        printf("vertices           %zu\n", n);
        printf("covering radius    %s\n", cli_num(far).s);
        cli_print_work(&stats, secs);
    }
    rc = fflush(stdout) == 0 ? CLI_OK : CLI_INPUT;
done:
    free(samples), free(label), free(dist);
    tg_geodesic_destroy(geo);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(mesh);
    return rc;
}

static int run(int argc, char** argv)
{
    sample_args sa;
    memset(&sa, 0, sizeof sa);
    const char *count = NULL, *seed = NULL, *threads = NULL, *iterations = NULL;
    for (int i = 1; i < argc; ++i) {
        const char* a = argv[i];
        if (!strcmp(a, "--quiet")) {
            sa.quiet = true;
        } else if (!strcmp(a, "--cvt")) {
            sa.cvt = true;
        } else if (!strcmp(a, "--count") || !strcmp(a, "--start") || !strcmp(a, "--seed") || !strcmp(a, "-o") ||
                   !strcmp(a, "--field") || !strcmp(a, "--threads") || !strcmp(a, "--iterations")) {
            if (i + 1 >= argc) return cli_usage("sample", "%s needs a value", a);
            const char* val = argv[++i];
            if (!strcmp(a, "--iterations")) iterations = val;
            else if (!strcmp(a, "--count")) count = val;
            else if (!strcmp(a, "--start")) sa.start = val;
            else if (!strcmp(a, "--seed")) seed = val;
            else if (!strcmp(a, "-o")) sa.out = val;
            else if (!strcmp(a, "--threads")) threads = val;
            else sa.field_out = val;
        } else if (a[0] == '-' && a[1]) {
            return cli_usage("sample", "unknown option '%s'", a);
        } else if (!sa.mesh_path) {
            sa.mesh_path = a;
        } else {
            return cli_usage("sample", "unexpected argument '%s'", a);
        }
    }
    if (!sa.mesh_path) return cli_usage("sample", "missing MESH");
    if (!count || !cli_parse_uint(count, &sa.count) || sa.count == 0 || sa.count > 0xFFFFFFFEull)
        return cli_usage("sample", "--count needs a positive number of samples%s%s%s", count ? ", not '" : "",
                         count ? count : "", count ? "'" : "");
    if (sa.start && seed) return cli_usage("sample", "--start and --seed exclude each other");
    if (iterations && !sa.cvt) return cli_usage("sample", "--iterations applies to --cvt");
    if (iterations && (!cli_parse_uint(iterations, &sa.iterations) || sa.iterations < 1 || sa.iterations > 100000))
        return cli_usage("sample", "--iterations needs a number in 1..100000, not '%s'", iterations);
    if (seed && !cli_parse_uint(seed, &sa.seed)) return cli_usage("sample", "--seed needs a non-negative integer, not '%s'", seed);
    if (sa.out && strcmp(sa.out, "-") && !cli_ext_is(sa.out, ".txt") && !cli_ext_is(sa.out, ".csv"))
        return cli_usage("sample", "-o %s: the extension must be .txt or .csv", sa.out);
    if (sa.field_out && !cli_ext_is(sa.field_out, ".ply") && !cli_ext_is(sa.field_out, ".csv"))
        return cli_usage("sample", "--field %s: the extension must be .ply or .csv", sa.field_out);
    const cli_file_role inputs[1] = {{sa.mesh_path, "mesh"}}, outputs[2] = {{sa.out, "-o"}, {sa.field_out, "--field"}};
    int check = cli_check_outputs(outputs, 2, inputs, 1);
    if (check == CLI_OK) check = cli_field_threads("sample", threads, &sa.threads);
    return check != CLI_OK ? check : run_sample(&sa);
}

const cli_command cli_cmd_sample = {
    "sample",
    "sample MESH --count K [--start v:IDX | --seed N] [--cvt [--iterations N]] [-o SAMPLES.txt|.csv]\n"
    "       [--field FIELD.ply|.csv] [--threads N] [--quiet]",
    "Farthest-point sampling in exact geodesic distance: the first sample is --start (or the vertex\n"
    "the seed picks, default seed 0), each next one the vertex farthest from all earlier ones (a\n"
    "component no sample reaches yet counts as farthest; ties to the lowest index). Each sample's\n"
    "field propagates only where it gets below the earlier samples' distance.\n\n"
    "  --count K              the number of samples (at most the vertices used by faces)\n"
    "  --start v:IDX          the first sample\n"
    "  --seed N               the first sample is the (SplitMix64(N) mod R)-th of the R vertices\n"
    "                         used by faces (Python's Mesh.farthest_point_sampling(seed=N) agrees)\n"
    "  -o SAMPLES             .txt: one v:IDX a line (a --sources file for trigeo field);\n"
    "                         .csv: rows i,vertex,x,y,z; '-': .txt to stdout\n"
    "  --field FIELD          per vertex the position of the nearest sample in the order (-1:\n"
    "                         none) and the distance to it: .ply properties 'label' and\n"
    "                         'distance' (trigeo render --labels), .csv rows vertex,label,distance\n"
    "  --threads N            each sample's field on N threads (at most 256, 0 = all cores;\n"
    "                         default 1): every N > 1 gives the same samples; one thread's\n"
    "                         only where two candidates tie within rounding (1e-14 relative)\n"
    "  --cvt                  then a centroidal Voronoi tessellation from those samples (geodesic\n"
    "                         Lloyd): each site moved to the geodesic mean of its exact Voronoi\n"
    "                         cell (clipped inside the faces at its boundaries), the cells\n"
    "                         made again, until no site moves more than 1e-7 of the diagonal;\n"
    "                         the summary lists the energy (the integral over the cells of the\n"
    "                         squared distance) before and after each iteration, never\n"
    "                         increasing. -o\n"
    "                         then writes the sites as SPECs (.txt) or rows i,site,x,y,z (.csv,\n"
    "                         the site a quoted SPEC),\n"
    "                         --field their final cells\n"
    "  --iterations N         with --cvt: at most N iterations (default 10)\n"
    "  --quiet                no progress line and no summary (errors are still printed, -o -\n"
    "                         still writes the samples)\n\n"
    "Outputs are written to a temporary name and renamed when complete. Without -o - and --quiet a\n"
    "summary (covering radius: the largest distance to the nearest sample) goes to stdout.\n",
    run,
};
