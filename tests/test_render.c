/* test_render.c - tg_render_png: the PNG decodes to the requested size; background where no face
 * projects, shaded mesh where one does; a polyline adds red pixels; a scalar field colours the
 * low and high ends differently; identical inputs give identical bytes; bad arguments fail; a mesh
 * scaled by 2^k gives the same bytes (1e+-100: the same pixels to rounding). */
#include "tg_test.h"

#include <png.h>
#include <trigeo.h>

static unsigned char* decode(const char* path, int* w, int* h)
{
    png_image pi;
    memset(&pi, 0, sizeof pi);
    pi.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&pi, path)) return NULL;
    pi.format = PNG_FORMAT_RGB;
    unsigned char* buf = malloc(PNG_IMAGE_SIZE(pi));
    if (!buf || !png_image_finish_read(&pi, NULL, buf, 0, NULL)) {
        free(buf);
        png_image_free(&pi);
        return NULL;
    }
    *w = (int)pi.width, *h = (int)pi.height;
    return buf;
}

static const unsigned char* px(const unsigned char* img, int w, int x, int y) { return img + 3 * (y * w + x); }

static int count_red(const unsigned char* img, int w, int h)
{
    int n = 0;
    for (int i = 0; i < w * h; ++i) n += img[3 * i] > 150 && img[3 * i + 1] < 110 && img[3 * i + 2] < 110;
    return n;
}

static long file_bytes(const char* path, unsigned char** out)
{
    FILE* f = fopen(path, "rb");
    if (!f) return -1;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    *out = malloc((size_t)n);
    if (fread(*out, 1, (size_t)n, f) != (size_t)n) n = -1;
    fclose(f);
    return n;
}

/* Scale: a float depth buffer held the world depths and the normals were normalised
 * from squares of unscaled cross products, so that a mesh scaled by 1e100 (or 2^330) overflowed
 * (the depth test kept the wrong faces: the far side drawn over the near one) and by 1e-100 lost
 * its shading. An octahedron seen obliquely, coloured by a scalar field, with a polyline over it,
 * scaled by 2^k: the same bytes as unscaled; by 1e100 and 1e-100: the same pixels but for
 * rounding (at most 0.1% of them). */
static void test_scale(const char* a, const char* b)
{
    const double x[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
    const uint32_t t[] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    const double field[] = {0, 1, 2, 3, 4, 5};
    const double line[] = {1, 0, 0, 0.5, 0.5, 0, 0, 1, 0, 0, 0.5, 0.5, 0, 0, 1};
    const double scales[] = {ldexp(1.0, -490), ldexp(1.0, -330), ldexp(1.0, 330), ldexp(1.0, 490), 1e100, 1e-100};
    unsigned char *ref = NULL, *got = NULL;
    int w = 0, h = 0, rw = 0, rh = 0;
    for (int i = -1; i < 6; ++i) {
        double s = i < 0 ? 1.0 : scales[i], xs[18], ls[15];
        for (int k = 0; k < 18; ++k) xs[k] = x[k] * s;
        for (int k = 0; k < 15; ++k) ls[k] = line[k] * s;
        tg_mesh* m = NULL;
        CHECK_STATUS(tg_mesh_create(xs, 6, t, 8, NULL, NULL, &m), TG_OK);
        if (!m) return;
        tg_render_options o;
        memset(&o, 0, sizeof o);
        o.width = 160, o.height = 120, o.view_dir[0] = 0.3, o.view_dir[1] = -0.5, o.view_dir[2] = -1.0;
        o.vertex_scalar = field, o.polyline = ls, o.polyline_count = 5;
        CHECK_STATUS(tg_render_png(m, &o, i < 0 ? a : b, NULL), TG_OK);
        tg_mesh_destroy(m);
        if (i < 0) {
            ref = decode(a, &rw, &rh);
            CHECK(ref != NULL);
            continue;
        }
        unsigned char *ba = NULL, *bb = NULL;
        long na = file_bytes(a, &ba), nb = file_bytes(b, &bb);
        bool same = na > 0 && na == nb && memcmp(ba, bb, (size_t)na) == 0;
        free(ba), free(bb);
        got = decode(b, &w, &h);
        int differ = 0;
        for (int k = 0; got && ref && w == rw && h == rh && k < w * h; ++k) differ += memcmp(got + 3 * k, ref + 3 * k, 3) != 0;
        if (i < 4)
            CHECK_MSG(same, "octahedron x 2^%d: the PNG differs from the unscaled one (%d of %d pixels)",
                      (int)ilogb(s), differ, w * h);
        else
            CHECK_MSG(got && w == rw && h == rh && differ <= w * h / 1000, "octahedron x %g: %d of %d pixels differ", s,
                      differ, w * h);
        free(got);
    }
    free(ref);
}

int main(void)
{
    /* a unit square in the xy plane (two triangles), viewed straight along -z */
    const double x[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const uint32_t t[] = {0, 1, 2, 0, 2, 3};
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(x, 4, t, 2, NULL, NULL, &m), TG_OK);
    if (!m) return tg_test_finish();
    char a[256], b[256];
    snprintf(a, sizeof a, "%s/tg_render_a.png", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    snprintf(b, sizeof b, "%s/tg_render_b.png", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    tg_render_options o;
    memset(&o, 0, sizeof o);
    o.width = 200, o.height = 100, o.view_dir[2] = -1.0;
    CHECK_STATUS(tg_render_png(m, &o, a, NULL), TG_OK);
    int w = 0, h = 0;
    unsigned char* img = decode(a, &w, &h);
    CHECK(img != NULL);
    if (img) {
        CHECK_EQ_INT(w, 200);
        CHECK_EQ_INT(h, 100);
        /* the square is fitted to 88% of the height, centred: x in ~[56, 144] */
        const unsigned char *corner = px(img, w, 2, 2), *centre = px(img, w, 100, 50), *left = px(img, w, 30, 50);
        CHECK_MSG(corner[0] > 200 && corner[0] == corner[1], "background pixel (%d,%d,%d)", corner[0], corner[1], corner[2]);
        CHECK_MSG(left[0] > 200, "left of the square is background (%d)", left[0]);
        CHECK_MSG(centre[0] < 230 && abs(centre[0] - corner[0]) > 10, "centre shaded (%d) vs background (%d)", centre[0], corner[0]);
        CHECK_EQ_INT(count_red(img, w, h), 0);
        free(img);
    }
    /* identical inputs, identical bytes */
    CHECK_STATUS(tg_render_png(m, &o, b, NULL), TG_OK);
    unsigned char *ba = NULL, *bb = NULL;
    long na = file_bytes(a, &ba), nb = file_bytes(b, &bb);
    CHECK(na > 0 && na == nb && memcmp(ba, bb, (size_t)na) == 0);
    free(ba);
    free(bb);
    /* a diagonal polyline over the square */
    const double line[] = {0.1, 0.1, 0, 0.5, 0.5, 0, 0.9, 0.9, 0};
    o.polyline = line, o.polyline_count = 3;
    CHECK_STATUS(tg_render_png(m, &o, a, NULL), TG_OK);
    img = decode(a, &w, &h);
    if (img) {
        int red = count_red(img, w, h);
        CHECK_MSG(red > 60, "polyline pixels: %d", red);
        const unsigned char* mid = px(img, w, 100, 50);
        CHECK_MSG(mid[0] > 150 && mid[1] < 110, "the path's middle is red (%d,%d,%d)", mid[0], mid[1], mid[2]);
        free(img);
    }
    /* a scalar field: low end dark blue, high end yellow */
    const double field[] = {0, 1, 2, 1};
    o.polyline = NULL, o.polyline_count = 0, o.vertex_scalar = field, o.isolines = -1;
    CHECK_STATUS(tg_render_png(m, &o, a, NULL), TG_OK);
    img = decode(a, &w, &h);
    if (img) {
        const unsigned char *lo = px(img, w, 60, 92), *hi = px(img, w, 140, 8); /* near (0,0) and (1,1) */
        CHECK_MSG(lo[2] > lo[0] && hi[0] > hi[2] && hi[1] > lo[1], "low (%d,%d,%d) high (%d,%d,%d)", lo[0], lo[1],
                  lo[2], hi[0], hi[1], hi[2]);
        free(img);
    }
    /* exact isolines instead of the bands: a line at level 1 (the diagonal x + y = 1) in the colour
     * map's colour of 1, darkened; the bands are gone (isolines 16 would draw some) */
    const double diag_line[] = {0.05, 0.95, 0, 0.5, 0.5, 0, 0.95, 0.05, 0};
    const size_t diag_parts[] = {0, 3};
    const double diag_level = 1.0;
    o.isolines = 0, o.isoline_xyz = diag_line, o.isoline_start = diag_parts, o.isoline_parts = 1;
    o.isoline_level = &diag_level;
    CHECK_STATUS(tg_render_png(m, &o, a, NULL), TG_OK);
    img = decode(a, &w, &h);
    if (img) {
        const unsigned char *on = px(img, w, 100, 50), *off = px(img, w, 75, 70);
        CHECK_MSG(on[0] < 60 && on[1] < 60 && on[2] < 60 && off[1] > on[1] + 40, "isoline (%d,%d,%d) beside (%d,%d,%d)",
                  on[0], on[1], on[2], off[0], off[1], off[2]);
        free(img);
    }
    const size_t diag_backwards[] = {3, 0};
    o.isoline_start = diag_backwards;
    CHECK_STATUS(tg_render_png(m, &o, a, NULL), TG_ERR_INVALID_ARGUMENT);
    const double diag_nan[] = {0.05, 0.95, 0, NAN, 0.5, 0, 0.95, 0.05, 0};
    o.isoline_start = diag_parts, o.isoline_xyz = diag_nan;
    CHECK_STATUS(tg_render_png(m, &o, a, NULL), TG_ERR_INVALID_ARGUMENT);
    o.isoline_xyz = NULL;
    CHECK_STATUS(tg_render_png(m, &o, a, NULL), TG_ERR_INVALID_ARGUMENT);
    o.isoline_parts = 0, o.isoline_start = NULL, o.isoline_level = NULL, o.isolines = -1;
    /* Voronoi cells: corner 0 (0,0) in cell 0, corner 2 (1,1) in cell 1, the others in no cell:
     * two distinct colours and grey; two boundary parts drawn dark, with no red end dots */
    const uint32_t cells[] = {0, TG_NONE, 1, TG_NONE};
    o.vertex_scalar = NULL, o.vertex_label = cells;
    const double two[] = {0.2, 0.8, 0, 0.4, 0.6, 0, 0.6, 0.4, 0, 0.8, 0.2, 0};
    const size_t parts[] = {0, 2, 4};
    o.polyline = two, o.polyline_count = 4, o.polyline_start = parts, o.polyline_parts = 2;
    CHECK_STATUS(tg_render_png(m, &o, a, NULL), TG_OK);
    img = decode(a, &w, &h);
    if (img) {
        const unsigned char *c0 = px(img, w, 60, 92), *c1 = px(img, w, 140, 8), *none = px(img, w, 140, 92);
        CHECK_MSG(memcmp(c0, c1, 3) != 0 && abs(none[0] - none[1]) < 8 && abs(none[1] - none[2]) < 8 &&
                      (abs(c0[0] - c0[1]) > 20 || abs(c0[1] - c0[2]) > 20),
                  "cells (%d,%d,%d) (%d,%d,%d), none (%d,%d,%d)", c0[0], c0[1], c0[2], c1[0], c1[1], c1[2], none[0],
                  none[1], none[2]);
        int dark = 0; /* the boundary tubes: two segments of 0.28 across 90 pixels per unit */
        for (int i = 0; i < w * h; ++i) dark += img[3 * i] < 90 && img[3 * i + 1] < 90 && img[3 * i + 2] < 90;
        CHECK_MSG(dark > 60, "boundary pixels: %d", dark);
        CHECK_MSG(count_red(img, w, h) == 0, "no red: %d", count_red(img, w, h));
        free(img);
    }
    const size_t backwards[] = {0, 3, 2};
    o.polyline_start = backwards;
    CHECK_STATUS(tg_render_png(m, &o, a, NULL), TG_ERR_INVALID_ARGUMENT);
    o.polyline_start = NULL;
    CHECK_STATUS(tg_render_png(m, &o, a, NULL), TG_ERR_INVALID_ARGUMENT);
    o.vertex_label = NULL, o.polyline = NULL, o.polyline_count = 0, o.polyline_parts = 0;
    /* bad arguments */
    tg_diag d;
    o.vertex_scalar = NULL;
    o.width = 0, o.height = -5;
    CHECK_STATUS(tg_render_png(m, &o, a, &d), TG_ERR_INVALID_ARGUMENT);
    o.width = 10, o.height = 10, o.polyline_count = 2;
    CHECK_STATUS(tg_render_png(m, &o, a, NULL), TG_ERR_INVALID_ARGUMENT);
    const double nan_line[] = {0, 0, 0, NAN, 0, 0};
    o.polyline = nan_line;
    CHECK_STATUS(tg_render_png(m, &o, a, &d), TG_ERR_INVALID_ARGUMENT);
    o.polyline_count = 0;
    CHECK_STATUS(tg_render_png(m, &o, "/nonexistent-dir/x.png", &d), TG_ERR_IO);
    CHECK(strlen(d.message) > 0);
    CHECK_STATUS(tg_render_png(NULL, &o, a, NULL), TG_ERR_INVALID_ARGUMENT);
    test_scale(a, b);
    remove(a);
    remove(b);
    tg_mesh_destroy(m);
    return tg_test_finish();
}
