/* cli_curve.c - curves on the command line: the files of surface points the commands read (one
 * point a line), and curve sources (`curve:FILE` and `boundary` items of a --from list) made into
 * segments for tg_geodesic_curve_field and tg_geodesic_curve_path. */
#include "cli.h"

#include <stdlib.h>
#include <string.h>

/* Reads a sources, points or curve file: one item a line; a leading BOM, blank lines and '#'
 * comments skipped. Returns the number of items (texts copied into *out_text, pointers into it in
 * *out_items, their line numbers in *out_lines; out_breaks: NULL, or per item 1 where a blank line
 * comes between it and the item before, which ends a polyline of a curve file), or -1 after
 * printing the error. */
long cli_read_lines(const char* path, const char* what, char** out_text, char*** out_items,
                    unsigned long long** out_lines, unsigned char** out_breaks)
{
    size_t len = 0;
    char* text = cli_read_all(path, &len);
    if (!text) return -1;
    if (memchr(text, 0, len)) {
        cli_error(path, 0, "binary data (a NUL byte): not a %s file", what);
        free(text);
        return -1;
    }
    size_t lines = 1;
    for (size_t i = 0; i < len; ++i) lines += text[i] == '\n';
    char** items = malloc(lines * sizeof *items);
    unsigned long long* at = malloc(lines * sizeof *at);
    unsigned char* breaks = out_breaks ? calloc(lines, 1) : NULL;
    if (!items || !at || (out_breaks && !breaks)) {
        free(text), free(items), free(at), free(breaks);
        cli_error(path, 0, "out of memory");
        return -1;
    }
    long n = 0;
    bool blank = false;
    char* s = cli_skip_bom(text);
    for (unsigned long long line = 1; *s || line == 1; ++line) {
        char* end = strchr(s, '\n');
        char* next = end ? end + 1 : s + strlen(s);
        if (end) *end = '\0';
        while (*s == ' ' || *s == '\t') ++s;
        size_t l = strlen(s);
        while (l && (s[l - 1] == ' ' || s[l - 1] == '\t' || s[l - 1] == '\r')) s[--l] = '\0';
        if (l && s[0] != '#') {
            items[n] = s;
            at[n] = line;
            if (breaks) breaks[n] = blank && n > 0;
            blank = false;
            n++;
        } else if (!l) {
            blank = true;
        }
        s = next;
        if (!end) break;
    }
    if (n == 0) {
        cli_error(path, 0, "no %s (one SPEC a line: v:IDX, f:FACE:b0,b1,b2, e:HALFEDGE:t or p:x,y,z%s)", what,
                  strcmp(what, "points") ? "" : ", or x y z");
        free(text), free(items), free(at), free(breaks);
        return -1;
    }
    *out_text = text, *out_items = items, *out_lines = at;
    if (out_breaks) *out_breaks = breaks;
    return n;
}

int cli_resolve_items(const char* cmd, const char* mesh_path, const char* file, bool allow_xyz, tg_mesh* mesh,
                      tg_bvh** bvh, char** items, const unsigned long long* lines, size_t count, tg_surface_point* pts)
{
    for (size_t i = 0; i < count; ++i) {
        cli_spec sp;
        if (!cli_parse_spec(items[i], &sp) && !(allow_xyz && cli_parse_xyz(items[i], &sp))) {
            if (lines)
                cli_error(file, lines[i], "bad %s '%s' (v:IDX, f:FACE:b0,b1,b2, e:HALFEDGE:t or p:x,y,z%s)",
                          allow_xyz ? "point" : "source", items[i], allow_xyz ? " or x y z" : "");
            else
                cli_usage(cmd, "bad source '%s' (v:IDX, f:FACE:b0,b1,b2, e:HALFEDGE:t or p:x,y,z)", items[i]);
            return lines ? CLI_INPUT : CLI_USAGE;
        }
        char where[4096];
        if (lines)
            snprintf(where, sizeof where, "%s:%llu", file, lines[i]);
        else
            snprintf(where, sizeof where, "%s", mesh_path);
        if (!cli_resolve_spec(where, mesh, bvh, items[i], &sp, &pts[i])) return CLI_INPUT;
    }
    return CLI_OK;
}

/* A curve's points given in coordinates (a path's .obj) lie on the edges they cross up to
 * rounding: within this share of an edge (barycentric, or t along an edge) they are taken on it
 * (tg_surface_point_snap), whose faces on both sides hold them. */
#define ON_EDGE_REL 1e-9

/* Appends the polylines of curve file `path` (one point a line as a SPEC, "x y z" or an OBJ
 * "v x y z"; a blank line between polylines; a polyline of one point is that point; OBJ "l", "o"
 * and "g" lines are ignored, so a path's .obj is a curve) to *seg as segments, each checked on
 * the solver (tg_surface_segment_validate). CLI_OK, or CLI_INPUT after the error (file, line). */
static int read_curve(const char* cmd, const char* mesh_path, const char* path, tg_mesh* mesh, tg_bvh** bvh,
                      const tg_geodesic* geo, tg_surface_segment** seg, size_t* n)
{
    char* text = NULL;
    char** items = NULL;
    unsigned long long* lines = NULL;
    unsigned char* breaks = NULL;
    tg_surface_point* pts = NULL;
    long k = cli_read_lines(path, "curve points", &text, &items, &lines, &breaks);
    if (k < 0) return CLI_INPUT;
    long kept = 0; /* OBJ: "v x y z" is a point, "l", "o", "g" lines are not */
    for (long i = 0; i < k; ++i) {
        const char* it = items[i];
        if ((it[0] == 'l' || it[0] == 'o' || it[0] == 'g') && (it[1] == ' ' || it[1] == '\t')) {
            if (i + 1 < k) breaks[i + 1] |= breaks[i];
            continue;
        }
        items[kept] = it[0] == 'v' && (it[1] == ' ' || it[1] == '\t') ? items[i] + 2 : items[i];
        lines[kept] = lines[i], breaks[kept] = breaks[i];
        kept++;
    }
    k = kept;
    int rc = CLI_INPUT;
    if (k == 0) {
        cli_error(path, 0, "no curve points (one point a line: v:IDX, f:FACE:b0,b1,b2, e:HALFEDGE:t, p:x,y,z or x y z)");
        goto done;
    }
    tg_surface_segment* grown = realloc(*seg, (*n + (size_t)k) * sizeof *grown);
    pts = malloc((size_t)k * sizeof *pts);
    if (grown) *seg = grown;
    if (!grown || !pts) {
        cli_error(NULL, 0, "out of memory");
        goto done;
    }
    if ((rc = cli_resolve_items(cmd, mesh_path, path, true, mesh, bvh, items, lines, (size_t)k, pts)) != CLI_OK) goto done;
    rc = CLI_INPUT;
    for (long i = 0; i < k; ++i) pts[i] = tg_surface_point_snap(mesh, &pts[i], ON_EDGE_REL);
    for (long i = 0; i < k; ++i) {
        bool starts = i == 0 || breaks[i], alone = starts && (i + 1 == k || breaks[i + 1]);
        if (starts && !alone) continue; /* the first point of a polyline: its segment comes next */
        tg_surface_segment sg = {alone ? pts[i] : pts[i - 1], pts[i]};
        tg_diag d;
        memset(&d, 0, sizeof d);
        if (tg_surface_segment_validate(geo, &sg, &d) != TG_OK) {
            if (alone)
                cli_error(path, lines[i], "%s", d.message);
            else
                cli_error(path, lines[i], "the segment from line %llu: %s", lines[i - 1], d.message);
            goto done;
        }
        (*seg)[(*n)++] = sg;
    }
    rc = CLI_OK;
done:
    free(text), free(items), free(lines), free(breaks), free(pts);
    return rc;
}

bool cli_curve_item(const char* item, cli_curves* c)
{
    if (!strcmp(item, "boundary")) {
        c->boundary = true;
        return true;
    }
    if (strncmp(item, "curve:", 6) || !item[6]) return false;
    if (c->count < CLI_CURVES_MAX) c->files[c->count] = item + 6;
    c->count++; /* beyond the room: counted, refused by the caller */
    return true;
}

int cli_curve_segments(const char* cmd, const char* mesh_path, const cli_curves* c, tg_mesh* mesh, tg_bvh** bvh,
                       const tg_geodesic* geo, tg_surface_segment** out, size_t* out_count, size_t* out_ends)
{
    tg_surface_segment* seg = NULL;
    size_t n = 0;
    *out = NULL, *out_count = 0;
    if (c->boundary) {
        tg_geodesic_boundary_segments(geo, NULL, 0, &n);
        if (!n) {
            cli_error(mesh_path, 0, "the mesh has no boundary (--from boundary): every edge has two faces or more");
            return CLI_INPUT;
        }
        seg = malloc(n * sizeof *seg);
        if (!seg || tg_geodesic_boundary_segments(geo, seg, n, &n) != TG_OK) {
            free(seg);
            cli_error(NULL, 0, "out of memory");
            return CLI_INPUT;
        }
    }
    if (out_ends) out_ends[0] = n;
    for (size_t i = 0; i < c->count && i < CLI_CURVES_MAX; ++i) {
        if (read_curve(cmd, mesh_path, c->files[i], mesh, bvh, geo, &seg, &n) != CLI_OK) {
            free(seg);
            return CLI_INPUT;
        }
        if (out_ends) out_ends[1 + i] = n;
    }
    *out = seg, *out_count = n;
    return CLI_OK;
}

