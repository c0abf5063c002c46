/* result.c - tg_path, the caller-owned result of tg_geodesic_path: creation, growth, the
 * read-only view, names of its status and global flag, and the OBJ polyline writer.
 * Based on: the project's DESIGN.md (tg_path: points with every crossing and vertex passage, faces,
 *   length, status, certificate). */
#include "geodesic/path/stages.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

const char* tg_path_global_name(tg_path_global global)
{
    return global == TG_PATH_PROVEN ? "proven" : global == TG_PATH_UNPROVEN ? "unproven" : "unknown";
}

const char* tg_path_status_name(tg_path_status s)
{
    switch (s) {
    case TG_PATH_CONVERGED: return "converged";
    case TG_PATH_ITERATION_CAP: return "iteration_cap";
    case TG_PATH_UNREACHABLE: return "unreachable";
    case TG_PATH_STALLED: return "stalled";
    default: return "unknown";
    }
}

void tg__path_clear(tg_path* p)
{
    p->count = 0;
    p->length = p->initial_length = INFINITY;
    p->max_angle_defect = 0.0;
    p->status = TG_PATH_UNREACHABLE;
    p->global = TG_PATH_UNPROVEN;
    p->iterations = 0;
    p->edge_path_vertices = 0;
}

tg_status tg_path_create(const tg_allocator* a, tg_path** out)
{
    if (!out) return TG_ERR_INVALID_ARGUMENT;
    *out = NULL;
    tg_path* p = tg__alloc(a, sizeof *p);
    if (!p) return TG_ERR_OUT_OF_MEMORY;
    memset(p, 0, sizeof *p);
    if (a) p->allocator = *a;
    tg__path_clear(p);
    *out = p;
    return TG_OK;
}

void tg_path_destroy(tg_path* p)
{
    if (!p) return;
    tg_allocator a = p->allocator;
    tg__free(&a, p->points);
    tg__free(&a, p->xyz);
    tg__free(&a, p->faces);
    tg__free(&a, p);
}

void tg_path_get_view(const tg_path* p, tg_path_view* v)
{
    if (!v) return;
    memset(v, 0, sizeof *v);
    if (!p) {
        v->length = v->initial_length = INFINITY;
        v->status = TG_PATH_UNREACHABLE;
        return;
    }
    v->point_count = p->count;
    v->points = p->points;
    v->xyz = p->xyz;
    v->faces = p->faces;
    v->length = p->length;
    v->initial_length = p->initial_length;
    v->max_angle_defect = p->max_angle_defect;
    v->status = p->status;
    v->global = p->global;
    v->iterations = p->iterations;
    v->edge_path_vertices = p->edge_path_vertices;
}

bool tg__path_reserve(tg_path* p, size_t n)
{
    if (n <= p->capacity) return true;
    size_t cap = tg__grow_capacity(p->capacity, n, 16), bytes;
    if (tg__mul_overflows(cap, 3 * sizeof(double), &bytes)) return false;
    tg_surface_point* pts = tg__realloc(&p->allocator, p->points, cap * sizeof *pts);
    if (pts) p->points = pts;
    double* xyz = pts ? tg__realloc(&p->allocator, p->xyz, cap * 3 * sizeof *xyz) : NULL;
    if (xyz) p->xyz = xyz;
    uint32_t* faces = xyz ? tg__realloc(&p->allocator, p->faces, cap * sizeof *faces) : NULL;
    if (faces) p->faces = faces;
    if (!faces) return false;
    p->capacity = cap;
    return true;
}

tg_status tg_path_write_obj(const tg_path* p, const char* filename, tg_diag* diag)
{
    tg__diag_clear(diag, filename ? filename : "");
    if (!p || !filename) return TG_ERR_INVALID_ARGUMENT;
    FILE* f = fopen(filename, "w");
    if (!f) {
        tg__diag_set(diag, filename, 0, 0, 0, "cannot open for writing: %s", strerror(errno));
        return TG_ERR_IO;
    }
    tg__c_locale loc = tg__c_locale_enter(); /* '.' separators whatever the host's LC_NUMERIC */
    fprintf(f, "# trigeo geodesic path: %zu points, length %.17g, status %s, max angle defect %.3g rad\n",
            p->count, p->length, tg_path_status_name(p->status), p->max_angle_defect);
    for (size_t i = 0; i < p->count; ++i)
        fprintf(f, "v %.17g %.17g %.17g\n", p->xyz[3 * i], p->xyz[3 * i + 1], p->xyz[3 * i + 2]);
    tg__c_locale_leave(loc);
    if (p->count >= 2) {
        fputs("l", f);
        for (size_t i = 0; i < p->count; ++i) fprintf(f, " %zu", i + 1);
        fputc('\n', f);
    }
    bool bad = ferror(f) != 0;
    if (fclose(f) != 0) bad = true;
    if (bad) {
        tg__diag_set(diag, filename, 0, 0, 0, "write failed");
        return TG_ERR_IO;
    }
    return TG_OK;
}
