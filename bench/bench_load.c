/* bench_load.c - mesh loading speed and memory: trigeo's readers + topology against a plain
 * fgets/strtod and a fscanf OBJ baseline, measured in the same run on the same files.
 * usage: bench_load MESH... (PLY/OBJ/...; for each mesh its OBJ form is written to a temp file
 * and parsed by all three). Prints one table row per mesh. Single-threaded. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <trigeo.h>

#include "bench_common.h"

#include "io/io_internal.h"




#define REPS 5

/* Baseline 1: fgets + strtod/strtol, the way a quick hand-written loader reads OBJ. */
static size_t baseline_fgets(const char* path, size_t* out_faces)
{
    FILE* f = fopen(path, "rb");
    if (!f) return 0;
    char line[4096];
    size_t nv = 0, nf = 0, cap = 1 << 20;
    double* v = malloc(cap * sizeof *v);
    while (fgets(line, sizeof line, f)) {
        if (line[0] == 'v' && line[1] == ' ') {
            char* p = line + 2;
            if (nv * 3 + 3 > cap) v = realloc(v, (cap *= 2) * sizeof *v);
            for (int k = 0; k < 3; ++k) v[nv * 3 + k] = strtod(p, &p);
            nv++;
        } else if (line[0] == 'f' && line[1] == ' ') {
            char* p = line + 2;
            long a = strtol(p, &p, 10), b = strtol(p, &p, 10), c = strtol(p, &p, 10);
            nf += (a && b && c);
        }
    }
    fclose(f);
    free(v);
    *out_faces = nf;
    return nv;
}

/* Baseline 2: fscanf tokens. */
static size_t baseline_fscanf(const char* path, size_t* out_faces)
{
    FILE* f = fopen(path, "rb");
    if (!f) return 0;
    char tok[256];
    size_t nv = 0, nf = 0;
    double x, y, z;
    long a, b, c;
    while (fscanf(f, "%255s", tok) == 1) {
        if (!strcmp(tok, "v") && fscanf(f, "%lf %lf %lf", &x, &y, &z) == 3)
            nv++;
        else if (!strcmp(tok, "f") && fscanf(f, "%ld %ld %ld", &a, &b, &c) == 3)
            nf++;
    }
    fclose(f);
    *out_faces = nf;
    return nv;
}


int main(int argc, char** argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: bench_load MESH...\n");
        return 1;
    }
    printf("| mesh | faces | load (parse+topology) CPU s | wall s | bytes/face | OBJ MB | trigeo OBJ parse MB/s | trigeo OBJ load CPU s | fgets+strtod MB/s | fscanf MB/s |\n");
    printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (int i = 1; i < argc; ++i) {
        const char* path = argv[i];
        double t[REPS], c[REPS];
        tg_mesh* m = NULL;
        tg_diag d;
        for (int r = 0; r < REPS; ++r) {
            tg_mesh_destroy(m);
            m = NULL;
            double t0 = bench_wall(), c0 = bench_cpu_process();
            tg_status st = tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &m);
            t[r] = bench_wall() - t0;
            c[r] = bench_cpu_process() - c0;
            if (st != TG_OK) {
                fprintf(stderr, "%s: %s\n", path, d.message);
                return 2;
            }
        }
        double load_s = bench_median(t, REPS), load_cpu = bench_median(c, REPS);
        size_t nf = tg_mesh_face_count(m);
        double bpf = (double)tg_mesh_memory_bytes(m) / (double)nf;

        char obj[512];
        snprintf(obj, sizeof obj, "/tmp/bench_load_%d.obj", (int)i);
        if (tg_mesh_write_obj(m, obj, &d) != TG_OK) {
            fprintf(stderr, "%s: %s\n", obj, d.message);
            return 2;
        }
        tg_mesh_destroy(m);
        char* data;
        size_t size;
        if (tg__read_file(obj, NULL, &d, &data, &size) != TG_OK) return 2;
        for (int r = 0; r < REPS; ++r) {
            tg__soup soup;
            double c0 = bench_cpu_process();
            tg_status st = tg__read_obj(data, size, obj, NULL, &d, &soup);
            t[r] = bench_cpu_process() - c0;
            if (st != TG_OK) return 2;
            free(soup.xyz);
            free(soup.tri);
        }
        double parse_s = bench_median(t, REPS);
        free(data);
        for (int r = 0; r < REPS; ++r) {
            double c0 = bench_cpu_process();
            tg_mesh_load(obj, TG_FORMAT_AUTO, NULL, &d, &m);
            t[r] = bench_cpu_process() - c0;
            tg_mesh_destroy(m);
        }
        double objload_s = bench_median(t, REPS);
        size_t bf = 0;
        double c0 = bench_cpu_process();
        baseline_fgets(obj, &bf);
        double fgets_s = bench_cpu_process() - c0;
        c0 = bench_cpu_process();
        baseline_fscanf(obj, &bf);
        double fscanf_s = bench_cpu_process() - c0;
        double mb = (double)size / 1e6;
        const char* base = strrchr(path, '/');
        printf("| %s | %zu | %.3f | %.3f | %.1f | %.1f | %.0f | %.3f | %.0f | %.0f |\n", base ? base + 1 : path, nf,
               load_cpu, load_s, bpf, mb, mb / parse_s, objload_s, mb / fgets_s, mb / fscanf_s);
        remove(obj);
    }
    printf("\nCPU s = process CPU time (user + sys; equals wall time on an idle core); MB/s from CPU time.\n");
    printf("peak RSS %.1f MiB; median of %d runs for trigeo, 1 run for the baselines; 1 thread\n",
           bench_peak_rss_kib() / 1024.0, REPS);
    return 0;
}
