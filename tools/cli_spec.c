/* cli_spec.c - surface point specifications of the CLI (v:IDX | f:FACE:b0,b1,b2 | e:HALFEDGE:t |
 * p:x,y,z) and ';'-separated lists of them, shared by `trigeo path`, `trigeo field` and
 * `trigeo trace`.
 * Based on: the CLI contract of the project's DESIGN.md (SPEC). */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void cli_spec_text(const tg_surface_point* p, char* buf, size_t cap)
{
    if (p->kind == TG_SURFACE_EDGE)
        snprintf(buf, cap, "e:%u:%s", p->index, cli_num(p->t).s);
    else if (p->kind == TG_SURFACE_FACE)
        snprintf(buf, cap, "f:%u:%s,%s,%s", p->index, cli_num(p->bary[0]).s, cli_num(p->bary[1]).s,
                 cli_num(p->bary[2]).s);
    else
        snprintf(buf, cap, "v:%u", p->index);
}

void cli_print_spec(FILE* f, const tg_surface_point* p)
{
    char buf[CLI_SPEC_TEXT_MAX];
    cli_spec_text(p, buf, sizeof buf);
    fputs(buf, f);
}

tg_surface_point cli_face_point(uint32_t face, const double b[3])
{
    double sum = b[0] + b[1] + b[2];
    if (isfinite(sum) && fabs(sum - 1.0) <= CLI_BARY_RENORMALIZE && sum != 1.0)
        return tg_surface_face(face, b[0] / sum, b[1] / sum, b[2] / sum);
    return tg_surface_face(face, b[0], b[1], b[2]);
}

bool cli_locate(tg_mesh* mesh, tg_bvh** bvh, const double xyz[3], tg_surface_point* out, const char** why)
{
    for (int k = 0; k < 3; ++k)
        if (!(fabs(xyz[k]) <= 1e150)) {
            *why = "a coordinate is beyond the supported range of +-1e150 (squared distances would overflow)";
            return false;
        }
    if (tg_mesh_face_count(mesh) == 0) {
        *why = "the mesh has no faces";
        return false;
    }
    tg_status st = TG_OK;
    tg_bvh_workspace* ws = NULL;
    if (!*bvh) st = tg_bvh_create(mesh, NULL, bvh);
    if (st == TG_OK) st = tg_bvh_workspace_create(*bvh, &ws);
    if (st == TG_OK) st = tg_bvh_locate(*bvh, ws, xyz, out, NULL);
    tg_bvh_workspace_destroy(ws);
    *why = tg_status_string(st);
    return st == TG_OK;
}

/* v:IDX | f:FACE:b0,b1,b2 | e:HALFEDGE:t | p:x,y,z. false on a syntax error. */
bool cli_parse_spec(const char* s, cli_spec* out)
{
    memset(out, 0, sizeof *out);
    s += strspn(s, " \t\r\n"); /* blanks around a spec are allowed (the numbers take trailing ones) */
    if (!s[0] || s[1] != ':') return false;
    out->kind = s[0];
    const char* rest = s + 2;
    if (out->kind == 'v') return cli_parse_uint(rest, &out->index);
    if (out->kind == 'p') return cli_parse_doubles(rest, 3, out->v);
    if (out->kind != 'f' && out->kind != 'e') return false;
    const char* colon = strchr(rest, ':');
    if (!colon || colon == rest || colon - rest > 20) return false;
    char num[24];
    memcpy(num, rest, (size_t)(colon - rest));
    num[colon - rest] = '\0';
    if (!cli_parse_uint(num, &out->index)) return false;
    return cli_parse_doubles(colon + 1, out->kind == 'f' ? 3 : 1, out->v);
}

size_t cli_split_list(char* list, char** items, size_t cap)
{
    size_t n = 0;
    for (char* s = list;;) {
        char* semi = strchr(s, ';');
        if (semi) *semi = '\0';
        s += strspn(s, " \t\r\n"); /* "v:0; v:5": blanks around an item are no part of it */
        size_t len = strlen(s);
        while (len && strchr(" \t\r\n", s[len - 1])) s[--len] = '\0';
        if (!*s || n == cap) return 0;
        items[n++] = s;
        if (!semi) return n;
        s = semi + 1;
    }
}

/* Resolves a spec on the mesh (p: through the BVH, built on first use). Prints the error and
 * returns false when the location is invalid. */
bool cli_resolve_spec(const char* mesh_path, tg_mesh* mesh, tg_bvh** bvh, const char* text, const cli_spec* sp,
                      tg_surface_point* out)
{
    if (sp->kind == 'p') {
        const char* why = NULL;
        if (!cli_locate(mesh, bvh, sp->v, out, &why)) {
            cli_error(mesh_path, 0, "cannot locate '%s' on the surface: %s", text, why);
            return false;
        }
        return true;
    }
    if (sp->index > UINT32_MAX) {
        cli_error(mesh_path, 0, "index in '%s' is out of range", text);
        return false;
    }
    uint32_t i = (uint32_t)sp->index;
    if (sp->kind == 'v')
        *out = tg_surface_vertex(i);
    else if (sp->kind == 'e')
        *out = tg_surface_edge(i, sp->v[0]);
    else
        *out = cli_face_point(i, sp->v);
    tg_diag d;
    memset(&d, 0, sizeof d);
    if (tg_surface_point_validate(mesh, out, &d) != TG_OK) {
        cli_error(mesh_path, 0, "'%s': %s", text, d.message[0] ? d.message : "invalid surface point");
        return false;
    }
    return true;
}

int cli_spec_list_parse(const char* cmd, const char* option, const char* list, cli_spec_list* out)
{
    memset(out, 0, sizeof *out);
    size_t len = strlen(list);
    out->buffer = malloc(len + 1);
    out->text = malloc(CLI_SPEC_LIST_MAX * sizeof *out->text);
    if (!out->buffer || !out->text) {
        cli_error(NULL, 0, "out of memory");
        return CLI_INPUT;
    }
    memcpy(out->buffer, list, len + 1);
    out->count = cli_split_list(out->buffer, out->text, CLI_SPEC_LIST_MAX);
    if (!out->count)
        return cli_usage(cmd, "bad %s list \"%s\" (SPEC;SPEC;..., no empty item, at most %d)", option, list,
                         CLI_SPEC_LIST_MAX);
    out->spec = malloc(out->count * sizeof *out->spec);
    out->point = malloc(out->count * sizeof *out->point);
    if (!out->spec || !out->point) {
        cli_error(NULL, 0, "out of memory");
        return CLI_INPUT;
    }
    for (size_t i = 0; i < out->count; ++i)
        if (!cli_parse_spec(out->text[i], &out->spec[i]))
            return cli_usage(cmd, "bad %s item %zu '%s' (v:IDX, f:FACE:b0,b1,b2, e:HALFEDGE:t or p:x,y,z)", option, i + 1,
                             out->text[i]);
    return CLI_OK;
}

bool cli_spec_list_resolve(const char* mesh_path, tg_mesh* mesh, tg_bvh** bvh, cli_spec_list* l)
{
    for (size_t i = 0; i < l->count; ++i)
        if (!cli_resolve_spec(mesh_path, mesh, bvh, l->text[i], &l->spec[i], &l->point[i])) return false;
    return true;
}

void cli_spec_list_free(cli_spec_list* l)
{
    free(l->buffer), free(l->text), free(l->spec), free(l->point);
    memset(l, 0, sizeof *l);
}

bool cli_parse_xyz(const char* s, cli_spec* out)
{
    memset(out, 0, sizeof *out);
    out->kind = 'p';
    for (int k = 0; k < 3; ++k) {
        const char* end;
        if (cli_scan_double(s, &out->v[k], &end) != CLI_NUMBER_OK) return false;
        s = end + strspn(end, " \t");
        if (k < 2 && *s == ',') s += 1 + strspn(s + 1, " \t");
        else if (k < 2 && s == end) return false; /* "1-2 3": no separator */
    }
    return *s == '\0';
}
