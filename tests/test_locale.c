/* test_locale.c - numbers in files are read and written with '.' whatever LC_NUMERIC a host
 * program sets. The test switches to a locale whose decimal separator is ',' (de_DE.UTF-8: the
 * system's, or one compiled with localedef into the build directory, as Debian's `locales` package
 * allows) and checks, first, that the hazard is real there (strtod stops at '.'), then that:
 * - the readers' slow path (more than 19 significant digits, large exponents) gives the C-locale
 *   value bit for bit, in OBJ, OFF and ASCII PLY;
 * - tg_mesh_write_obj and tg_path_write_obj write '.' and read back bit-identical.
 * Exit 77 (CTest: skipped) only when no such locale can be had on this machine. */
#define _POSIX_C_SOURCE 200809L
#include "tg_test.h"
#include "tg_test_geodesic.h"
#include "core/core.h"

#include <locale.h>
#include <unistd.h>

/* Coordinates that take the slow path, as text, and their values read in the C locale. */
static const char* const slow_text[] = {
    "0.10000000000000000000000000001", "1.2345678901234567890123", "-7.00000000000000000000000000000000001e-3",
    "123456789012345678901234567890", "2.5e-300",  "1e30",
    "0.333333333333333333333333",      "-4.5e+40", "9.8765432109876543210e-5",
};
#define SLOW_COUNT (sizeof slow_text / sizeof slow_text[0])

static bool tg__is_digit_(char c) { return c >= '0' && c <= '9'; }

static bool comma_locale(void)
{
    if (setlocale(LC_NUMERIC, "de_DE.UTF-8") && localeconv()->decimal_point[0] == ',') return true;
    const char* build = getenv("TG_BUILD_DIR");
    char dir[4096], cmd[8400];
    snprintf(dir, sizeof dir, "%s/locale", build && *build ? build : ".");
    snprintf(cmd, sizeof cmd, "mkdir -p '%s' && localedef -i de_DE -f UTF-8 '%s/de_DE.UTF-8' >/dev/null 2>&1", dir, dir);
    if (system(cmd) != 0) { /* localedef reports warnings with status 1 yet writes the locale */
        snprintf(cmd, sizeof cmd, "test -d '%s/de_DE.UTF-8'", dir);
        if (system(cmd) != 0) return false;
    }
    setenv("LOCPATH", dir, 1);
    return setlocale(LC_NUMERIC, "de_DE.UTF-8") && localeconv()->decimal_point[0] == ',';
}

static void check_mesh_coords(const char* what, const char* text, size_t len, const char* name, const double* want)
{
    tg_mesh* m = NULL;
    tg_diag d = {0};
    tg_status st = tg_mesh_load_memory(text, len, name, TG_FORMAT_AUTO, NULL, &d, &m);
    CHECK_MSG(st == TG_OK, "%s: load failed: %s %s", what, tg_status_name(st), d.message);
    if (st != TG_OK) return;
    CHECK_EQ_INT(tg_mesh_vertex_count(m), 3);
    const double* x = tg_mesh_positions(m);
    for (size_t i = 0; i < 9; ++i)
        CHECK_MSG(x[i] == want[i], "%s: coordinate %zu is %.17g, the C locale reads %.17g", what, i, x[i], want[i]);
    tg_mesh_destroy(m);
}

/* a ',' between two digits: a number written with the locale's separator */
static bool has_decimal_comma(const char* t)
{
    for (size_t i = 1; t[i] && t[i + 1]; ++i)
        if (t[i] == ',' && tg__is_digit_(t[i - 1]) && tg__is_digit_(t[i + 1])) return true;
    return false;
}

static char* read_file(const char* path, size_t* len)
{
    FILE* f = fopen(path, "rb");
    if (!f) return NULL;
    char* buf = malloc(1 << 20);
    *len = fread(buf, 1, (1 << 20) - 1, f);
    buf[*len] = '\0';
    fclose(f);
    return buf;
}

int main(void)
{
    double want[SLOW_COUNT];
    for (size_t i = 0; i < SLOW_COUNT; ++i) want[i] = strtod(slow_text[i], NULL); /* still the C locale */
    if (!comma_locale()) {
        printf("SKIP: no locale with ',' as decimal separator (install Debian's locales package)\n");
        return 77;
    }
    char* end;
    double hazard = strtod("1.5", &end);
    CHECK_MSG(hazard == 1.0 && *end == '.', "the ',' locale should stop strtod at '.': got %g", hazard);

    /* readers: three vertices carrying the nine slow-path numbers */
    char obj[2048], off[2048], ply[2048];
    int n = 0;
    for (int v = 0; v < 3; ++v)
        n += snprintf(obj + n, sizeof obj - (size_t)n, "v %s %s %s\n", slow_text[3 * v], slow_text[3 * v + 1], slow_text[3 * v + 2]);
    n += snprintf(obj + n, sizeof obj - (size_t)n, "f 1 2 3\n");
    check_mesh_coords("OBJ", obj, (size_t)n, "slow.obj", want);
    n = snprintf(off, sizeof off, "OFF\n3 1 0\n");
    for (int v = 0; v < 3; ++v)
        n += snprintf(off + n, sizeof off - (size_t)n, "%s %s %s\n", slow_text[3 * v], slow_text[3 * v + 1], slow_text[3 * v + 2]);
    n += snprintf(off + n, sizeof off - (size_t)n, "3 0 1 2\n");
    check_mesh_coords("OFF", off, (size_t)n, "slow.off", want);
    n = snprintf(ply, sizeof ply,
                 "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
                 "element face 1\nproperty list uchar int vertex_indices\nend_header\n");
    for (int v = 0; v < 3; ++v)
        n += snprintf(ply + n, sizeof ply - (size_t)n, "%s %s %s\n", slow_text[3 * v], slow_text[3 * v + 1], slow_text[3 * v + 2]);
    n += snprintf(ply + n, sizeof ply - (size_t)n, "3 0 1 2\n");
    check_mesh_coords("PLY", ply, (size_t)n, "slow.ply", want);

    /* writers: a mesh and a path with non-integer coordinates */
    nv = nf = 0;
    add_v(0.1, 0.2, 0.3), add_v(1.7, 0.25, -0.5), add_v(0.45, 1.3, 0.125), add_v(1.1, 1.9, 0.75);
    add_f(0, 1, 2), add_f(2, 1, 3);
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(xyz, nv, tri, nf, NULL, NULL, &m), TG_OK);
    const char* build = getenv("TG_BUILD_DIR");
    char mesh_path[4096], path_path[4096];
    snprintf(mesh_path, sizeof mesh_path, "%s/test_locale_mesh.obj", build && *build ? build : ".");
    snprintf(path_path, sizeof path_path, "%s/test_locale_path.obj", build && *build ? build : ".");
    CHECK_STATUS(tg_mesh_write_obj(m, mesh_path, NULL), TG_OK);
    size_t len = 0;
    char* text = read_file(mesh_path, &len);
    CHECK(text != NULL);
    if (text) {
        CHECK_MSG(!has_decimal_comma(text), "mesh OBJ written with ',':\n%s", text);
        tg_mesh* back = NULL;
        CHECK_STATUS(tg_mesh_load(mesh_path, TG_FORMAT_AUTO, NULL, NULL, &back), TG_OK);
        if (back) {
            CHECK(memcmp(tg_mesh_positions(back), xyz, 3 * nv * sizeof(double)) == 0);
            tg_mesh_destroy(back);
        }
        free(text);
    }
    ctx c = open_ctx_for(m);
    tg_surface_point from = tg_surface_face(0, 0.2, 0.3, 0.5), to = tg_surface_face(1, 0.1, 0.3, 0.6);
    CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &from, &to, NULL, c.path), TG_OK);
    CHECK_STATUS(tg_path_write_obj(c.path, path_path, NULL), TG_OK);
    text = read_file(path_path, &len);
    CHECK(text != NULL);
    if (text) {
        CHECK_MSG(!has_decimal_comma(text), "path OBJ written with ',':\n%s", text);
        /* the polyline's first point reads back (in the C locale) as the path's first point */
        const char* v = strstr(text, "\nv ");
        CHECK(v != NULL);
        if (v) {
            double p[3];
            const char* s = v + 3;
            for (int k = 0; k < 3; ++k) {
                char* e;
                p[k] = tg__strtod_c(s, &e);
                s = e;
            }
            tg_path_view pv;
            tg_path_get_view(c.path, &pv);
            for (int k = 0; k < 3; ++k) CHECK_MSG(p[k] == pv.xyz[k], "path point %d: %.17g vs %.17g", k, p[k], pv.xyz[k]);
        }
        free(text);
    }
    close_ctx(&c);
    setlocale(LC_NUMERIC, "C");
    return tg_test_finish();
}
