/* cli_isolines.c - the isolines' levels as the CLI takes them (a list, or a count by name) and their
 * writers (OBJ polylines, JSON), for `trigeo field --isolines` and `trigeo render`.
 * Based on: the CLI contract of the project's DESIGN.md (outputs renamed into place when
 * complete; bad input: exit 2, no file). */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_LEVELS 4096

int cli_parse_level_count(const char* option, const char* text, double** out_levels, size_t* out_count)
{
    *out_levels = NULL, *out_count = 0;
    unsigned long long n = 0;
    if (!cli_parse_uint(text, &n) || n < 1 || n > MAX_LEVELS) {
        cli_error(NULL, 0, "%s %s: a count of levels must be 1..%d", option, text, MAX_LEVELS);
        return CLI_INPUT;
    }
    *out_levels = calloc((size_t)n, sizeof(double));
    if (!*out_levels) {
        cli_error(NULL, 0, "out of memory");
        return CLI_INPUT;
    }
    *out_count = (size_t)n;
    return CLI_OK;
}

int cli_parse_levels(const char* option, const char* text, double** out_levels, size_t* out_count)
{
    *out_levels = NULL, *out_count = 0;
    size_t len = strlen(text);
    size_t n = 1;
    for (size_t i = 0; i < len; ++i) n += text[i] == ',';
    char* buf = malloc(len + 1);
    double* lv = malloc(n * sizeof *lv);
    if (!buf || !lv || n > MAX_LEVELS) {
        if (n > MAX_LEVELS) cli_error(NULL, 0, "%s: at most %d levels", option, MAX_LEVELS);
        else cli_error(NULL, 0, "out of memory");
        free(buf), free(lv);
        return CLI_INPUT;
    }
    memcpy(buf, text, len + 1);
    size_t k = 0;
    char* s = buf;
    for (;;) {
        char* comma = strchr(s, ',');
        if (comma) *comma = '\0';
        if (!cli_parse_nonneg(s, &lv[k])) {
            cli_error(NULL, 0, "%s: level %zu '%s' is not a finite number >= 0 (give LEVEL,LEVEL,...; a count is --isoline-count N)",
                      option, k + 1, s);
            free(buf), free(lv);
            return CLI_INPUT;
        }
        k++;
        if (!comma) break;
        s = comma + 1;
    }
    free(buf);
    *out_levels = lv, *out_count = k;
    return CLI_OK;
}

void cli_auto_levels(const double* dist, size_t n, size_t count, double* out_levels)
{
    double far = 0.0;
    for (size_t v = 0; v < n; ++v)
        if (isfinite(dist[v]) && dist[v] > far) far = dist[v];
    for (size_t k = 0; k < count; ++k) out_levels[k] = far * (double)(k + 1) / (double)(count + 1);
}


static bool write_obj(FILE* f, const tg_isolines_view* v)
{
    bool ok = fprintf(f, "# trigeo isolines: %zu levels, %zu polylines\n", v->level_count, v->polyline_count) > 0;
    ok = ok && cli_obj_vertices(f, v->xyz, v->point_count);
    for (size_t l = 0; ok && l < v->level_count; ++l) {
        ok = fprintf(f, "g level_%zu\n# level %s\n", l, cli_num(v->levels[l]).s) > 0;
        for (size_t p = v->level_start[l]; ok && p < v->level_start[l + 1]; ++p)
            ok = cli_obj_line(f, v->polyline_start[p], v->polyline_start[p + 1] - v->polyline_start[p],
                              v->polyline_closed[p]);
    }
    return ok;
}

static bool write_json(FILE* f, const tg_isolines_view* v)
{
    char spec[CLI_SPEC_TEXT_MAX];
    bool ok = fprintf(f, "{\"levels\": [") > 0;
    for (size_t l = 0; ok && l < v->level_count; ++l)
        ok = fprintf(f, "%s%s", l ? ", " : "", cli_num(v->levels[l]).s) > 0;
    ok = ok && fprintf(f, "],\n \"polylines\": [") > 0;
    size_t written = 0;
    for (size_t l = 0; ok && l < v->level_count; ++l)
        for (size_t p = v->level_start[l]; ok && p < v->level_start[l + 1]; ++p) {
            size_t a = v->polyline_start[p], b = v->polyline_start[p + 1];
            ok = fprintf(f, "%s\n  {\"level\": %zu, \"value\": %s, \"closed\": %s, \"points\": [", written++ ? "," : "",
                         l, cli_num(v->levels[l]).s, v->polyline_closed[p] ? "true" : "false") > 0;
            for (size_t i = a; ok && i < b; ++i)
                ok = fprintf(f, "%s[%s, %s, %s]", i > a ? ", " : "", cli_num(v->xyz[3 * i]).s,
                             cli_num(v->xyz[3 * i + 1]).s, cli_num(v->xyz[3 * i + 2]).s) > 0;
            ok = ok && fprintf(f, "], \"faces\": [") > 0;
            for (size_t i = a; ok && i < b; ++i) ok = fprintf(f, "%s%u", i > a ? ", " : "", v->faces[i]) > 0;
            ok = ok && fprintf(f, "], \"surface\": [") > 0;
            for (size_t i = a; ok && i < b; ++i) {
                cli_spec_text(&v->points[i], spec, sizeof spec);
                ok = fprintf(f, "%s\"%s\"", i > a ? ", " : "", spec) > 0;
            }
            ok = ok && fprintf(f, "]}") > 0;
        }
    return ok && fprintf(f, "\n]}\n") > 0;
}

int cli_write_isolines(const char* path, const tg_isolines* iso)
{
    tg_isolines_view v;
    tg_isolines_get_view(iso, &v);
    cli_output out;
    FILE* f = cli_output_open(&out, path);
    if (!f) return CLI_INPUT;
    if (!(cli_ext_is(path, ".json") ? write_json(f, &v) : write_obj(f, &v))) {
        cli_error(path, 0, "write failed: %s", strerror(errno));
        cli_output_abort(&out);
        return CLI_INPUT;
    }
    return cli_output_commit(&out);
}
