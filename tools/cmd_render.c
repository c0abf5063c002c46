/* cmd_render.c - `trigeo render MESH [--path PATH.obj] [--field FIELD.ply] -o OUT.png`: a picture
 * of the mesh with an optional geodesic path (an OBJ polyline as `trigeo path -o` writes it) and
 * an optional per-vertex scalar field (a PLY vertex property as `trigeo field -o` writes it). */
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static bool is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r';
}

/* A `v` record's numbers (p just past the `v`): x y z, then numbers only (w, a colour). false
 * after printing "FILE:LINE: why". */
static bool read_v_record(const char* path, unsigned long long lineno, const char* p, double out[3])
{
    for (int k = 0;; ++k) {
        while (is_blank(*p)) p++;
        if (!*p && k >= 3) return true;
        char* q;
        double x = strtod(p, &q);
        if (q == p || (*q && !is_blank(*q)) || !isfinite(x)) {
            cli_error(path, lineno, "a 'v' record needs 3 finite coordinates (and numbers only after them)");
            return false;
        }
        if (k < 3) out[k] = x;
        p = q;
    }
}

/* Parses the indices of an `l` record (p just past the `l` of `line`): each "I" or "I/VT",
 * 1-based or negative (from the end of the `v` records so far), appended to *order. false after
 * printing "FILE:LINE: why". */
static bool read_l_record(const char* path, unsigned long long lineno, const char* line, const char* p, size_t nv,
                          size_t** order, size_t* nl, size_t* lcap)
{
    for (;;) {
        while (is_blank(*p)) p++;
        if (!*p) return true;
        const char* tok = p;
        char* e;
        long long idx = strtoll(p, &e, 10);
        p = e;
        bool vt_ok = true;
        if (e != tok && *p == '/') { /* the texture index of "I/VT": digits */
            const char* vt = ++p;
            while (*p >= '0' && *p <= '9') p++;
            vt_ok = p > vt;
        }
        if (e == tok || !vt_ok || (*p && !is_blank(*p))) {
            size_t len = strcspn(tok, " \t\r");
            cli_error(path, lineno, "bad index '%.*s%s' in an 'l' record (column %zu): a vertex number expected",
                      (int)(len > 40 ? 40 : len), tok, len > 40 ? "..." : "", (size_t)(tok - line) + 1);
            return false;
        }
        long long k = idx > 0 ? idx - 1 : (long long)nv + idx;
        if (idx == 0 || k < 0 || k >= (long long)nv) {
            cli_error(path, lineno, "line index %lld out of range (%zu 'v' records before it)", idx, nv);
            return false;
        }
        if (!cli_grow((void**)order, lcap, *nl + 1, sizeof **order)) {
            cli_error(path, lineno, "out of memory");
            return false;
        }
        (*order)[(*nl)++] = (size_t)k;
    }
}

/* Reads the polyline of an OBJ file: its `v` records in the order its `l` records visit them
 * (all `l` records concatenated), or in file order when there are none. With out_starts, each
 * `l` record is a part: *out_starts gets *out_parts + 1 offsets (malloc'd). Lines of any length
 * (trigeo writes `l` records of hundreds of thousands of characters); every token of a `v` or `l`
 * record is checked, so a cut or corrupt record is refused with its line, never drawn wrong. */
static double* read_polyline(const char* path, const char* what, size_t* out_count, size_t** out_starts,
                             size_t* out_parts)
{
    size_t *starts = NULL, parts = 0, scap = 0;
    char* text = cli_read_text(path, what, NULL);
    if (!text) return NULL;
    size_t nv = 0, cap = 64, nl = 0, lcap = 64;
    double* v = malloc(cap * 3 * sizeof *v);
    size_t* order = malloc(lcap * sizeof *order);
    unsigned long long lineno = 0;
    bool ok = v && order;
    if (!ok) cli_error(path, 0, "out of memory");
    char* cursor = text;
    for (char* line; ok && (line = cli_next_line(&cursor, &lineno));) {
        char* p = line;
        while (*p == ' ' || *p == '\t') p++;
        if (p[0] == 'v' && (p[1] == ' ' || p[1] == '\t')) {
            if (!cli_grow((void**)&v, &cap, nv + 1, 3 * sizeof *v)) {
                cli_error(path, lineno, "out of memory");
                ok = false;
                break;
            }
            ok = read_v_record(path, lineno, p + 1, v + 3 * nv);
            nv++;
        } else if (p[0] == 'l' && (p[1] == ' ' || p[1] == '\t')) {
            if (out_starts && !cli_grow((void**)&starts, &scap, parts + 2, sizeof *starts)) {
                cli_error(path, lineno, "out of memory");
                ok = false;
                break;
            }
            if (out_starts) starts[parts++] = nl;
            ok = read_l_record(path, lineno, line, p + 1, nv, &order, &nl, &lcap);
        }
    }
    free(text);
    double* pts = NULL;
    size_t n = nl ? nl : nv;
    if (ok && n < 2) cli_error(path, 0, "the %s holds fewer than 2 points", what);
    if (ok && n >= 2 && !(pts = malloc(3 * n * sizeof *pts))) cli_error(path, 0, "out of memory");
    if (pts)
        for (size_t i = 0; i < n; ++i) memcpy(pts + 3 * i, v + 3 * (nl ? order[i] : i), 3 * sizeof *pts);
    free(v);
    free(order);
    *out_count = n;
    if (out_starts) {
        if (pts && starts) starts[parts] = nl;
        if (!pts) free(starts), starts = NULL, parts = 0;
        *out_starts = starts, *out_parts = parts;
    }
    return pts;
}

/* Ctrl-C while the picture is drawn: the render's progress callback stops it (polling mode). */
static int on_progress(void* user, double fraction)
{
    (void)user, (void)fraction;
    return cli_interrupted();
}

/* Ctrl-C while the field of --from and its isolines are computed (polling mode). */
static int on_field_progress(void* user, const tg_field_progress* p)
{
    (void)user, (void)p;
    return cli_interrupted();
}

/* --from: the field of the sources and its exact isolines at 16 levels max * k / 17 (where the
 * colour bands were), each polyline's level for its colour. */
typedef struct exact_isolines {
    double* dist;
    tg_isolines* iso;
    double* level_of; /* per polyline */
} exact_isolines;

static int isolines_of_sources(const char* mesh_path, tg_mesh* mesh, cli_spec_list* srcs, exact_isolines* ex)
{
    tg_bvh* bvh = NULL;
    tg_geodesic* geo = NULL;
    size_t nv = tg_mesh_vertex_count(mesh);
    if (!cli_spec_list_resolve(mesh_path, mesh, &bvh, srcs)) {
        tg_bvh_destroy(bvh);
        return CLI_INPUT;
    }
    double levels[16];
    ex->dist = malloc((nv ? nv : 1) * sizeof *ex->dist);
    tg_status st = ex->dist ? tg_geodesic_create(mesh, NULL, &geo) : TG_ERR_OUT_OF_MEMORY;
    tg_field_options o;
    memset(&o, 0, sizeof o);
    o.progress = on_field_progress;
    cli_interrupt_polling(true);
    if (st == TG_OK) st = tg_geodesic_field(geo, NULL, srcs->point, srcs->count, &o, ex->dist, NULL);
    if (st == TG_OK) {
        cli_auto_levels(ex->dist, nv, 16, levels);
        st = tg_isolines_create(NULL, &ex->iso);
        if (st == TG_OK) st = tg_geodesic_isolines(geo, NULL, srcs->point, srcs->count, levels, 16, &o, ex->iso, NULL, NULL);
    }
    cli_interrupt_polling(false);
    if (st == TG_OK) {
        tg_isolines_view v;
        tg_isolines_get_view(ex->iso, &v);
        ex->level_of = malloc((v.polyline_count ? v.polyline_count : 1) * sizeof *ex->level_of);
        if (!ex->level_of) st = TG_ERR_OUT_OF_MEMORY;
        for (size_t l = 0; st == TG_OK && l < v.level_count; ++l)
            for (size_t p = v.level_start[l]; p < v.level_start[l + 1]; ++p) ex->level_of[p] = v.levels[l];
    }
    tg_geodesic_destroy(geo);
    tg_bvh_destroy(bvh);
    if (st == TG_ERR_CANCELLED) {
        cli_error(mesh_path, 0, "interrupted: nothing written");
        return 130;
    }
    if (st != TG_OK) {
        cli_error(mesh_path, 0, "%s", tg_status_string(st));
        return CLI_INPUT;
    }
    return CLI_OK;
}

static int run(int argc, char** argv)
{
    const char *mesh_path = NULL, *path_obj = NULL, *field = NULL, *scalar = "distance", *out = NULL;
    const char *labels = NULL, *bounds = NULL, *logmap = NULL, *from = NULL, *iso_obj = NULL;
    tg_render_options o;
    memset(&o, 0, sizeof o);
    for (int i = 1; i < argc; ++i) {
        const char* a = argv[i];
        bool has_value = i + 1 < argc;
        if (!strcmp(a, "-o") && has_value) out = argv[++i];
        else if (!strcmp(a, "--path") && has_value) path_obj = argv[++i];
        else if (!strcmp(a, "--field") && has_value) field = argv[++i];
        else if (!strcmp(a, "--scalar") && has_value) scalar = argv[++i];
        else if (!strcmp(a, "--labels") && has_value) labels = argv[++i];
        else if (!strcmp(a, "--boundaries") && has_value) bounds = argv[++i];
        else if (!strcmp(a, "--logmap") && has_value) logmap = argv[++i];
        else if (!strcmp(a, "--checker") && has_value) {
            if (!cli_parse_double(argv[++i], &o.checker_size) || !(o.checker_size > 0.0))
                return cli_usage("render", "--checker needs a size > 0");
        }
        else if (!strcmp(a, "--from") && has_value) from = argv[++i];
        else if (!strcmp(a, "--isolines") && has_value) iso_obj = argv[++i];
        else if (!strcmp(a, "--view") && has_value) {
            if (!cli_parse_doubles(argv[++i], 3, o.view_dir)) return cli_usage("render", "--view needs X,Y,Z");
        } else if (!strcmp(a, "--up") && has_value) {
            if (!cli_parse_doubles(argv[++i], 3, o.up)) return cli_usage("render", "--up needs X,Y,Z");
        } else if (!strcmp(a, "--size") && has_value) {
            /* W x H, two integers and nothing else ("64x48.5" and "100x100abc" were read by sscanf) */
            const char* v = argv[++i];
            const char* x = strchr(v, 'x');
            char w_text[24];
            unsigned long long w = 0, h = 0;
            bool ok = x && (size_t)(x - v) < sizeof w_text;
            if (ok) {
                memcpy(w_text, v, (size_t)(x - v));
                w_text[x - v] = '\0';
                ok = cli_parse_uint(w_text, &w) && cli_parse_uint(x + 1, &h);
            }
            if (!ok || w < 16 || h < 16 || w > 8192 || h > 8192)
                return cli_usage("render", "--size needs WxH, each 16..8192, not '%s'", v);
            o.width = (int)w, o.height = (int)h;
        } else if (a[0] == '-' && a[1]) return cli_usage("render", "unknown option or missing value: '%s'", a);
        else if (!mesh_path) mesh_path = a;
        else return cli_usage("render", "unexpected argument '%s'", a);
    }
    if (!mesh_path) return cli_usage("render", "missing MESH");
    if (!out) return cli_usage("render", "missing -o OUT.png");
    if (path_obj && bounds) return cli_usage("render", "--path and --boundaries exclude each other");
    if ((field != NULL) + (labels != NULL) + (logmap != NULL) > 1)
        return cli_usage("render", "--field, --labels and --logmap exclude each other");
    if (o.checker_size > 0.0 && !logmap) return cli_usage("render", "--checker applies to --logmap");
    if (from && (field || labels || logmap || iso_obj))
        return cli_usage("render", "--from computes the field and its isolines: without --field, --labels, --logmap, --isolines");
    cli_spec_list srcs;
    memset(&srcs, 0, sizeof srcs);
    if (from) {
        int prc = cli_spec_list_parse("render", "--from", from, &srcs);
        if (prc != CLI_OK) {
            cli_spec_list_free(&srcs);
            return prc;
        }
    }
    const cli_file_role inputs[7] = {{mesh_path, "mesh"}, {path_obj, "path file (--path)"},
                                     {field, "field file (--field)"}, {labels, "labels file (--labels)"},
                                     {logmap, "log map file (--logmap)"}, {iso_obj, "isolines file (--isolines)"},
                                     {bounds, "boundaries file (--boundaries)"}};
    const cli_file_role outputs[1] = {{out, "-o"}};
    int check = cli_check_outputs(outputs, 1, inputs, 7);
    if (check == CLI_OK && !cli_ext_is(out, ".png") && !cli_output_is_direct(out))
        check = cli_usage("render", "-o %s: render writes PNG: the name must end in .png", out);
    tg_mesh* mesh = check == CLI_OK ? cli_load_mesh(mesh_path) : NULL;
    if (!mesh) {
        cli_spec_list_free(&srcs);
        return check == CLI_OK ? CLI_INPUT : check;
    }
    int rc = CLI_OK;
    double* values = NULL;
    if (field) {
        size_t n = 0;
        tg_diag d;
        size_t nv = tg_mesh_vertex_count(mesh);
        values = malloc((nv ? nv : 1) * sizeof *values);
        tg_status st = values ? tg_ply_read_vertex_scalar(field, scalar, values, nv, &n, &d) : TG_ERR_OUT_OF_MEMORY;
        if (st == TG_OK && n != nv) {
            cli_error(field, 0, "the field has %zu values but the mesh has %zu vertices", n, nv);
            rc = CLI_INPUT;
        } else if (st != TG_OK) {
            cli_error_diag(&d, st);
            rc = CLI_INPUT;
        }
        o.vertex_scalar = values;
    }
    uint32_t* cells = NULL;
    if (rc == CLI_OK && labels) { /* the `label` property: -1 none, else a non-negative integer */
        size_t n = 0, nv = tg_mesh_vertex_count(mesh);
        tg_diag d;
        double* lv = malloc((nv ? nv : 1) * sizeof *lv);
        cells = malloc((nv ? nv : 1) * sizeof *cells);
        tg_status st = lv && cells ? tg_ply_read_vertex_scalar(labels, "label", lv, nv, &n, &d) : TG_ERR_OUT_OF_MEMORY;
        if (st != TG_OK) {
            cli_error_diag(&d, st);
            rc = CLI_INPUT;
        } else if (n != nv) {
            cli_error(labels, 0, "the labels have %zu values but the mesh has %zu vertices", n, nv);
            rc = CLI_INPUT;
        }
        for (size_t v = 0; rc == CLI_OK && v < nv; ++v) {
            if (!(lv[v] == -1.0 || (lv[v] >= 0 && lv[v] < 4294967295.0 && lv[v] == floor(lv[v])))) {
                cli_error(labels, 0, "vertex %zu: label %s is not -1 or a cell index", v, cli_num(lv[v]).s);
                rc = CLI_INPUT;
            }
            cells[v] = lv[v] < 0 ? TG_NONE : (uint32_t)lv[v];
        }
        free(lv);
        o.vertex_label = cells;
    }
    double* uv = NULL;
    if (rc == CLI_OK && logmap) { /* the properties `u` and `v` of trigeo logmap -o LM.ply */
        size_t nv = tg_mesh_vertex_count(mesh), n[2] = {0, 0};
        double* col = malloc((nv ? nv : 1) * sizeof *col);
        uv = malloc((nv ? nv : 1) * 2 * sizeof *uv);
        static const char* const name[2] = {"u", "v"};
        for (int k = 0; rc == CLI_OK && k < 2; ++k) {
            tg_diag d;
            tg_status st = col && uv ? tg_ply_read_vertex_scalar(logmap, name[k], col, nv, &n[k], &d) : TG_ERR_OUT_OF_MEMORY;
            if (st != TG_OK) {
                cli_error_diag(&d, st);
                rc = CLI_INPUT;
            } else if (n[k] != nv) {
                cli_error(logmap, 0, "the log map has %zu values but the mesh has %zu vertices", n[k], nv);
                rc = CLI_INPUT;
            }
            for (size_t v = 0; rc == CLI_OK && v < nv; ++v) uv[2 * v + (size_t)k] = col[v];
        }
        free(col);
        o.vertex_uv = uv;
    }
    double* poly = NULL;
    size_t* parts = NULL;
    exact_isolines ex;
    memset(&ex, 0, sizeof ex);
    if (rc == CLI_OK && from) {
        rc = isolines_of_sources(mesh_path, mesh, &srcs, &ex);
        o.vertex_scalar = ex.dist;
    }
    double* iso_pts = NULL;
    size_t *iso_parts = NULL, iso_count = 0;
    if (rc == CLI_OK && iso_obj) { /* polylines of trigeo field --isolines: every 'l' record one */
        iso_pts = read_polyline(iso_obj, "isolines file", &iso_count, &iso_parts, &o.isoline_parts);
        if (!iso_pts) rc = CLI_INPUT;
        o.isoline_xyz = iso_pts, o.isoline_start = iso_parts;
    } else if (rc == CLI_OK && from) {
        tg_isolines_view v;
        tg_isolines_get_view(ex.iso, &v);
        o.isoline_xyz = v.xyz, o.isoline_start = v.polyline_start, o.isoline_parts = v.polyline_count;
        o.isoline_level = ex.level_of;
    }
    if (rc == CLI_OK && (path_obj || bounds)) {
        poly = read_polyline(path_obj ? path_obj : bounds, path_obj ? "path file" : "boundaries file", &o.polyline_count, bounds ? &parts : NULL, &o.polyline_parts);
        if (!poly) rc = CLI_INPUT;
        o.polyline = poly;
        o.polyline_start = parts;
    }
    if (rc == CLI_OK) { /* to a temporary name, renamed when complete */
        tg_diag d;
        memset(&d, 0, sizeof d);
        cli_output png;
        if (!cli_output_reserve(&png, out)) {
            rc = CLI_INPUT;
        } else {
            png.f = NULL;
            o.progress = on_progress;
            cli_interrupt_polling(true);
            tg_status st = tg_render_png(mesh, &o, png.tmp, &d);
            cli_interrupt_polling(false);
            rc = cli_output_finish_library(&png, st, &d);
        }
    }
    free(poly);
    free(parts);
    free(iso_pts);
    free(iso_parts);
    free(ex.dist), free(ex.level_of);
    tg_isolines_destroy(ex.iso);
    cli_spec_list_free(&srcs);
    free(cells);
    free(values);
    free(uv);
    tg_mesh_destroy(mesh);
    return rc;
}

const cli_command cli_cmd_render = {
    "render",
    "render MESH [--path PATH.obj | --boundaries B.obj] [--field FIELD.ply [--scalar NAME] [--isolines ISO.obj] |\n"
    "       --from SPEC[;SPEC...] | --labels L.ply | --logmap LM.ply [--checker S]] -o OUT.png",
    "Draws MESH into a PNG (software rasterizer: orthographic view, smooth headlight shading,\n"
    "3x3 supersampling). Optional overlays:\n"
    "  --path PATH.obj    a polyline (OBJ 'v' + 'l' records, as 'trigeo path -o' writes) drawn as a\n"
    "                     red tube with dots at its ends\n"
    "  --field FIELD.ply  a per-vertex scalar (PLY vertex property NAME, default 'distance') drawn\n"
    "                     with a dark-blue-to-yellow colour map and 16 isolines drawn as colour bands\n"
    "                     of the per-vertex values (exact lines: --from, or --isolines); +inf (unreachable)\n"
    "                     is grey\n"
    "  --from SPEC[;...]  the exact distance field of these sources (trigeo field --from), drawn with\n"
    "                     the colour map and its 16 exact isolines (trigeo field --isolines 16): lines\n"
    "                     along the true level curves, not colour bands\n"
    "  --isolines ISO.obj these polylines (trigeo field --isolines -o ISO.obj) drawn as the\n"
    "                     isolines: with --field instead of its colour bands, else dark grey\n"
    "                     (on the plain mesh, the cells of --labels or a --logmap)\n"
    "  --labels L.ply     Voronoi cells: the PLY vertex property 'label' (trigeo field --labels,\n"
    "                     trigeo sample --field) drawn one colour per cell, -1 grey\n"
    "  --boundaries B.obj polylines (every 'l' record one; trigeo field --boundaries) drawn as\n"
    "                     dark tubes\n"
    "  --logmap LM.ply    a log map (the PLY vertex properties 'u' and 'v' of trigeo logmap -o)\n"
    "                     drawn as the checkerboard of its 2D coordinates: squares of side S\n"
    "                     (--checker S, default the bounding box diagonal / 40) coloured by the\n"
    "                     parity of floor(u / S) + floor(v / S); unreached vertices grey\n"
    "  --view X,Y,Z       direction the camera looks along (default 0.55,-0.35,1)\n"
    "  --up X,Y,Z         camera up (default +y)\n"
    "  --size WxH         image size in pixels, each side 16..8192 (default 960x720); the memory\n"
    "                     budget is 2 GiB (16 bytes per sample, 7 per pixel): 3x3 supersampling up\n"
    "                     to about 3770x3770, 2x2 up to 5500x5500, none beyond\n"
    "OUT must end in .png (or be a character device or FIFO, written directly); an OUT that is\n"
    "one of the files read is refused. The PNG appears only when complete; Ctrl-C stops the\n"
    "drawing (exit 130, no file written).\n",
    run,
};
