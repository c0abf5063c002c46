/* render.c - a small software rasterizer that draws a mesh, an optional per-vertex scalar field
 * (colour map + isolines) and an optional polyline (a geodesic path) into a PNG.
 * Based on: Pineda, "A Parallel Algorithm for Polygon Rasterization" (SIGGRAPH 1988), edge
 *   functions with barycentric interpolation; z-buffering (Catmull 1974); Gouraud-style normal
 *   interpolation with area-weighted vertex normals; box-filter supersampling; libpng's
 *   simplified write API (png_image_write_to_memory, libpng 1.6), which reports errors by return
 *   value, so this file never sees libpng's longjmp. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "mesh/mesh_internal.h"
#include "core/vec3.h"

#include <math.h>
#include <png.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#define MAX_SIDE 8192
/* Bytes per supersample (float depth + float rgb) and per pixel (the 8-bit image and the PNG
 * buffer, which a few rows of filter bytes and zlib's stored-block overhead can make larger than
 * the image): what TG_RENDER_MAX_BYTES bounds. */
#define SAMPLE_BYTES 16u
#define PIXEL_BYTES 7u
/* The clock is read every this many faces or rows, and the progress callback asked when
 * PROGRESS_PERIOD_S has passed (a face can cover millions of samples in a large picture). */
#define CHECK_EVERY 16u
#define PROGRESS_PERIOD_S 0.005

typedef struct camera {
    tg_vec3 right, up, fwd; /* orthonormal; fwd points into the screen */
    double scale, off_x, off_y; /* screen = (x * scale + off_x, off_y - y * scale) */
    /* depth = world depth times zscale, a power of two bringing the largest |depth| into
     * [0.5, 1): exact, so a float holds the depths of a mesh at any scale (1e100 overflowed a
     * float, 1e-100 underflowed to 0) and a mesh scaled by 2^k draws the same picture */
    double zscale;
    double depth_bias;          /* lift of the polyline toward the camera (in depth units) */
} camera;

typedef struct canvas {
    int w, h;      /* supersampled size */
    float* depth;  /* w * h, +inf = empty */
    float* rgb;    /* 3 * w * h, linear-ish 0..1 */
} canvas;

/* v's direction; scaled by a power of two first (exact), so that no square overflows or
 * underflows at any scale of the mesh */
static tg_vec3 normalize_or(tg_vec3 v, tg_vec3 fallback)
{
    v = tg_v3_pow2_unit(v);
    double len = tg_v3_len(v);
    return len > 0.0 && isfinite(len) ? tg_v3_scale(v, 1.0 / len) : fallback;
}

static void camera_basis(const tg_render_options* o, camera* cam)
{
    tg_vec3 f = tg_v3_load(o->view_dir);
    f = normalize_or(f, normalize_or(tg_v3(0.55, -0.35, 1.0), tg_v3(0, 0, 1)));
    tg_vec3 up = normalize_or(tg_v3_load(o->up), tg_v3(0, 1, 0));
    if (fabs(tg_v3_dot(up, f)) > 0.99) up = fabs(f.z) < 0.9 ? tg_v3(0, 0, 1) : tg_v3(1, 0, 0);
    cam->fwd = f;
    cam->right = normalize_or(tg_v3_cross(f, up), tg_v3(1, 0, 0));
    cam->up = tg_v3_cross(cam->right, f);
}

static tg_vec3 project(const camera* c, tg_vec3 p)
{
    double x = tg_v3_dot(p, c->right), y = tg_v3_dot(p, c->up), z = tg_v3_dot(p, c->fwd);
    return tg_v3(x * c->scale + c->off_x, c->off_y - y * c->scale, z * c->zscale);
}

/* Fits the referenced vertices and the polyline into the canvas with a 6% margin. */
static void camera_fit(const tg_mesh* m, const tg_render_options* o, const canvas* cv, camera* c)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    size_t n = m->vertex_count + o->polyline_count;
    for (size_t i = 0; i < n; ++i) {
        tg_vec3 p;
        if (i < m->vertex_count) {
            if (m->vhe[i] == TG_NONE) continue;
            p = tg_v3_load(m->xyz + 3 * i);
        } else {
            p = tg_v3_load(o->polyline + 3 * (i - m->vertex_count));
        }
        double q[3] = {tg_v3_dot(p, c->right), tg_v3_dot(p, c->up), tg_v3_dot(p, c->fwd)};
        for (int k = 0; k < 3; ++k) lo[k] = q[k] < lo[k] ? q[k] : lo[k], hi[k] = q[k] > hi[k] ? q[k] : hi[k];
    }
    if (!(lo[0] <= hi[0])) lo[0] = lo[1] = lo[2] = -1, hi[0] = hi[1] = hi[2] = 1;
    double sx = hi[0] - lo[0], sy = hi[1] - lo[1];
    double ext = sx > sy ? sx : sy;
    if (!(ext > 0.0)) ext = 1.0;
    double fit_x = sx > 0 ? 0.88 * cv->w / sx : INFINITY, fit_y = sy > 0 ? 0.88 * cv->h / sy : INFINITY;
    c->scale = fit_x < fit_y ? fit_x : fit_y;
    if (!isfinite(c->scale)) c->scale = 0.88 * (cv->w < cv->h ? cv->w : cv->h) / ext;
    c->off_x = 0.5 * cv->w - 0.5 * (lo[0] + hi[0]) * c->scale;
    c->off_y = 0.5 * cv->h + 0.5 * (lo[1] + hi[1]) * c->scale;
    /* the tube sits on the surface: lift it by a little more than a pixel's worth of depth and
     * 0.2% of the depth range so it wins the depth test against the faces it lies on */
    double zmax = fmax(fabs(lo[2]), fabs(hi[2]));
    int e = 0;
    if (zmax > 0.0 && isfinite(zmax)) (void)frexp(zmax, &e);
    c->zscale = ldexp(1.0, -e);
    c->depth_bias = (3.0 / c->scale + 0.002 * (hi[2] - lo[2])) * c->zscale;
}

/* A perceptual dark-blue -> teal -> green -> yellow ramp (control points chosen for monotone
 * lightness), linearly interpolated. */
static void colormap(double t, float out[3])
{
    static const float ramp[5][3] = {{0.17f, 0.06f, 0.35f}, {0.22f, 0.33f, 0.56f}, {0.13f, 0.57f, 0.55f},
                                     {0.37f, 0.78f, 0.38f}, {0.99f, 0.91f, 0.15f}};
    if (!(t > 0.0)) t = 0.0;
    if (t > 1.0) t = 1.0;
    double x = t * 4.0;
    int i = x >= 4.0 ? 3 : (int)x;
    float u = (float)(x - i);
    for (int k = 0; k < 3; ++k) out[k] = ramp[i][k] + u * (ramp[i + 1][k] - ramp[i][k]);
}

typedef struct shade_ctx {
    const tg_render_options* o;
    double smin, smax; /* finite range of the scalar */
    int isolines;
    double checker;    /* the checkerboard's square side (vertex_uv) */
} shade_ctx;

/* The checkerboard's two colours, and grey where (u, v) is not finite. */
static void checker_colour(double u, double v, double side, float out[3])
{
    static const float tone[2][3] = {{0.93f, 0.91f, 0.86f}, {0.80f, 0.25f, 0.20f}};
    if (!isfinite(u) || !isfinite(v)) {
        out[0] = out[1] = out[2] = 0.55f;
        return;
    }
    double k = floor(u / side) + floor(v / side);
    int odd = fmod(k, 2.0) != 0.0;
    for (int c = 0; c < 3; ++c) out[c] = tone[odd][c];
}

/* The colour of cell `label`: hues spaced by the golden ratio (neighbouring labels far apart on
 * the wheel), moderate saturation; TG_NONE grey. */
static void label_colour(uint32_t label, float out[3])
{
    if (label == TG_NONE) {
        out[0] = out[1] = out[2] = 0.55f;
        return;
    }
    double h = 6.0 * fmod(0.13 + 0.6180339887498949 * (double)label, 1.0), s = 0.55, v = 0.95;
    int i = (int)h;
    double f = h - i, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    double rgb[6][3] = {{v, t, p}, {q, v, p}, {p, v, t}, {p, q, v}, {t, p, v}, {v, p, q}};
    for (int c = 0; c < 3; ++c) out[c] = (float)rgb[i % 6][c];
}

static void shade(const shade_ctx* sc, const camera* cam, tg_vec3 n, double scalar, bool has_scalar,
                  const float* cell, float out[3])
{
    float base[3] = {0.72f, 0.74f, 0.78f};
    if (cell) {
        base[0] = cell[0], base[1] = cell[1], base[2] = cell[2];
    } else if (has_scalar) {
        if (!isfinite(scalar)) {
            base[0] = base[1] = base[2] = 0.55f;
        } else {
            double range = sc->smax - sc->smin;
            double t = range > 0 ? (scalar - sc->smin) / range : 0.0;
            colormap(t, base);
            if (sc->isolines > 0 && range > 0) {
                double f = t * sc->isolines;
                double frac = f - floor(f);
                if (frac < 0.06 || frac > 0.94) base[0] *= 0.35f, base[1] *= 0.35f, base[2] *= 0.35f;
            }
        }
    }
    /* headlight, two-sided: the light comes from the camera */
    double d = fabs(tg_v3_dot(n, cam->fwd));
    double spec = pow(d, 40.0) * 0.12; /* kept low: a face seen head-on must stay darker than the background */
    float k = (float)(0.28 + 0.72 * d);
    for (int c = 0; c < 3; ++c) {
        float v = base[c] * k + (float)spec;
        out[c] = v > 1.0f ? 1.0f : v;
    }
}

/* The exact isolines' arrays: present, offsets in order, points finite. */
static bool isolines_valid(const tg_render_options* o, const char* png_path, tg_diag* diag)
{
    if (!o->isoline_parts) return true;
    if (!o->isoline_xyz || !o->isoline_start) return false;
    for (size_t p = 0; p < o->isoline_parts; ++p)
        if (o->isoline_start[p] > o->isoline_start[p + 1]) {
            tg__diag_set(diag, png_path, 0, 0, 0, "isoline %zu: offsets out of order", p);
            return false;
        }
    for (size_t i = 3 * o->isoline_start[0]; i < 3 * o->isoline_start[o->isoline_parts]; ++i)
        if (!isfinite(o->isoline_xyz[i])) {
            tg__diag_set(diag, png_path, 0, 0, 0, "isoline point %zu is not finite", i / 3);
            return false;
        }
    return true;
}

static void raster_segment(tg_vec3 a, tg_vec3 b, double radius, const camera* cam, canvas* cv, bool dark,
                           const float* flat);

/* The exact isolines, each in the colour map's colour of its level darkened as the bands were. */
static void draw_isolines(const tg_render_options* o, const shade_ctx* sc, const camera* cam, double radius,
                          canvas* cv)
{
    for (size_t p = 0; p < o->isoline_parts; ++p) {
        float c[3] = {0.25f, 0.25f, 0.27f};
        double range = sc->smax - sc->smin;
        if (o->isoline_level && o->vertex_scalar && range > 0) {
            colormap((o->isoline_level[p] - sc->smin) / range, c);
            for (int k = 0; k < 3; ++k) c[k] *= 0.35f;
        }
        for (size_t i = o->isoline_start[p]; i + 1 < o->isoline_start[p + 1]; ++i)
            raster_segment(project(cam, tg_v3_load(o->isoline_xyz + 3 * i)),
                           project(cam, tg_v3_load(o->isoline_xyz + 3 * i + 3)), radius, cam, cv, false, c);
    }
}

static bool vertex_normals(const tg_mesh* m, tg_vec3* vn)
{
    /* sides scaled by one power of two (the bounding box's): exact, and their cross products
     * neither overflow nor underflow at any scale of the mesh */
    const double *lo = m->report.bbox_min, *hi = m->report.bbox_max;
    double ext = 0.0;
    for (int k = 0; k < 3; ++k) ext = fmax(ext, fmax(fabs(lo[k]), fabs(hi[k])));
    int e = 0;
    if (ext > 0.0 && isfinite(ext)) (void)frexp(ext, &e);
    double s = ldexp(1.0, -e);
    for (size_t v = 0; v < m->vertex_count; ++v) vn[v] = tg_v3(0, 0, 0);
    for (size_t f = 0; f < m->face_count; ++f) {
        const uint32_t* t = m->tri + 3 * f;
        tg_vec3 a = tg_v3_load(m->xyz + 3 * (size_t)t[0]), b = tg_v3_load(m->xyz + 3 * (size_t)t[1]);
        tg_vec3 c = tg_v3_load(m->xyz + 3 * (size_t)t[2]);
        tg_vec3 n = tg_v3_cross(tg_v3_scale(tg_v3_sub(b, a), s), tg_v3_scale(tg_v3_sub(c, a), s)); /* 2 area: weights */
        for (int k = 0; k < 3; ++k) vn[t[k]] = tg_v3_add(vn[t[k]], n);
    }
    for (size_t v = 0; v < m->vertex_count; ++v) vn[v] = normalize_or(vn[v], tg_v3(0, 0, 0));
    return true;
}

static void raster_face(const tg_mesh* m, size_t f, const tg_vec3* sp, const tg_vec3* vn, const shade_ctx* sc,
                        const camera* cam, canvas* cv)
{
    const uint32_t* t = m->tri + 3 * f;
    tg_vec3 p0 = sp[t[0]], p1 = sp[t[1]], p2 = sp[t[2]];
    double area = (p1.x - p0.x) * (p2.y - p0.y) - (p1.y - p0.y) * (p2.x - p0.x);
    if (!(fabs(area) > 0.0)) return; /* zero-area in screen space (edge-on or degenerate) */
    tg_vec3 a = tg_v3_load(m->xyz + 3 * (size_t)t[0]), b = tg_v3_load(m->xyz + 3 * (size_t)t[1]);
    tg_vec3 c = tg_v3_load(m->xyz + 3 * (size_t)t[2]);
    tg_vec3 fn = normalize_or(tg_v3_cross(tg_v3_sub(b, a), tg_v3_sub(c, a)), tg_v3(0, 0, 1));
    double xmin = fmin(p0.x, fmin(p1.x, p2.x)), xmax = fmax(p0.x, fmax(p1.x, p2.x));
    double ymin = fmin(p0.y, fmin(p1.y, p2.y)), ymax = fmax(p0.y, fmax(p1.y, p2.y));
    int x0 = (int)floor(xmin), x1 = (int)ceil(xmax), y0 = (int)floor(ymin), y1 = (int)ceil(ymax);
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > cv->w - 1) x1 = cv->w - 1;
    if (y1 > cv->h - 1) y1 = cv->h - 1;
    double inv = 1.0 / area;
    const double* sv = sc->o->vertex_scalar;
    const uint32_t* lv = sc->o->vertex_label;
    const double* uv = sc->o->vertex_uv;
    float cells[3][3], square[3];
    if (lv)
        for (int k = 0; k < 3; ++k) label_colour(lv[t[k]], cells[k]);
    for (int y = y0; y <= y1; ++y) {
        double py = y + 0.5;
        for (int x = x0; x <= x1; ++x) {
            double px = x + 0.5;
            /* barycentric weights from edge functions, sign-normalised by the area */
            double w0 = ((p1.x - px) * (p2.y - py) - (p1.y - py) * (p2.x - px)) * inv;
            double w1 = ((p2.x - px) * (p0.y - py) - (p2.y - py) * (p0.x - px)) * inv;
            double w2 = 1.0 - w0 - w1;
            if (w0 < 0 || w1 < 0 || w2 < 0) continue;
            double z = w0 * p0.z + w1 * p1.z + w2 * p2.z;
            size_t idx = (size_t)y * (size_t)cv->w + (size_t)x;
            if (!(z < cv->depth[idx])) continue;
            cv->depth[idx] = (float)z;
            tg_vec3 n = tg_v3_add(tg_v3_add(tg_v3_scale(vn[t[0]], w0), tg_v3_scale(vn[t[1]], w1)), tg_v3_scale(vn[t[2]], w2));
            n = normalize_or(n, fn);
            double s = 0.0;
            if (sv) {
                double s0 = sv[t[0]], s1 = sv[t[1]], s2 = sv[t[2]];
                s = (isfinite(s0) && isfinite(s1) && isfinite(s2)) ? w0 * s0 + w1 * s1 + w2 * s2 : INFINITY;
            }
            /* cells: the nearest corner's label (ties to the lower corner) */
            int near = w0 >= w1 && w0 >= w2 ? 0 : w1 >= w2 ? 1 : 2;
            const float* base = lv ? cells[near] : NULL;
            if (uv) {
                const double *q0 = uv + 2 * (size_t)t[0], *q1 = uv + 2 * (size_t)t[1], *q2 = uv + 2 * (size_t)t[2];
                checker_colour(w0 * q0[0] + w1 * q1[0] + w2 * q2[0], w0 * q0[1] + w1 * q1[1] + w2 * q2[1], sc->checker,
                               square);
                base = square;
            }
            shade(sc, cam, n, s, sv != NULL, base, cv->rgb + 3 * idx);
        }
    }
}

/* A depth-tested disc-swept segment (the tube), coloured red with a lighter core (dark grey when
 * `dark`: cell boundaries). */
/* dark: a dark tube (boundaries); flat: one colour, no relief (isolines); neither: the red path. */
static void raster_segment(tg_vec3 a, tg_vec3 b, double radius, const camera* cam, canvas* cv, bool dark,
                           const float* flat)
{
    int x0 = (int)floor(fmin(a.x, b.x) - radius), x1 = (int)ceil(fmax(a.x, b.x) + radius);
    int y0 = (int)floor(fmin(a.y, b.y) - radius), y1 = (int)ceil(fmax(a.y, b.y) + radius);
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > cv->w - 1) x1 = cv->w - 1;
    if (y1 > cv->h - 1) y1 = cv->h - 1;
    double dx = b.x - a.x, dy = b.y - a.y, len_sq = dx * dx + dy * dy;
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            double px = x + 0.5 - a.x, py = y + 0.5 - a.y;
            double u = len_sq > 0 ? (px * dx + py * dy) / len_sq : 0.0;
            u = u < 0 ? 0 : u > 1 ? 1 : u;
            double ex = px - u * dx, ey = py - u * dy, d_sq = ex * ex + ey * ey;
            if (d_sq > radius * radius) continue;
            double z = a.z + u * (b.z - a.z) - cam->depth_bias;
            size_t idx = (size_t)y * (size_t)cv->w + (size_t)x;
            if (!(z < cv->depth[idx])) continue;
            float core = (float)(1.0 - sqrt(d_sq) / radius); /* 1 at the centre line */
            if (flat) {
                for (int k = 0; k < 3; ++k) cv->rgb[3 * idx + (size_t)k] = flat[k];
                continue;
            }
            if (dark) {
                cv->rgb[3 * idx + 0] = cv->rgb[3 * idx + 1] = 0.08f + 0.22f * core * core;
                cv->rgb[3 * idx + 2] = 0.10f + 0.22f * core * core;
                continue;
            }
            cv->rgb[3 * idx + 0] = 0.75f + 0.25f * core;
            cv->rgb[3 * idx + 1] = 0.08f + 0.30f * core * core;
            cv->rgb[3 * idx + 2] = 0.06f + 0.20f * core * core;
        }
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The caller's progress callback, asked every PROGRESS_PERIOD_S; true to stop. */
typedef struct progress_ctx {
    const tg_render_options* o;
    double total, done, next_s;
    unsigned since;
} progress_ctx;

static bool stop_requested(progress_ctx* pc, double steps)
{
    pc->done += steps;
    if (!pc->o->progress || ++pc->since < CHECK_EVERY) return false;
    pc->since = 0;
    double t = now_s();
    if (t < pc->next_s) return false;
    pc->next_s = t + PROGRESS_PERIOD_S;
    double fraction = pc->total > 0.0 && pc->done < pc->total ? pc->done / pc->total : 1.0;
    return pc->o->progress(pc->o->progress_user, fraction) != 0;
}

/* The memory of a w x h picture at ss x ss samples per pixel (SAMPLE_BYTES, PIXEL_BYTES). */
static double render_bytes(int w, int h, int ss)
{
    double px = (double)w * (double)h;
    return px * (double)ss * (double)ss * SAMPLE_BYTES + px * PIXEL_BYTES;
}

static tg_status write_png(const tg_allocator* a, const canvas* cv, int ss, const char* path, progress_ctx* pc,
                           tg_diag* diag)
{
    int w = cv->w / ss, h = cv->h / ss;
    unsigned char* img = tg__alloc_array(a, (size_t)w * (size_t)h, 3);
    if (!img) return TG_ERR_OUT_OF_MEMORY;
    for (int y = 0; y < h; ++y) {
        if (stop_requested(pc, 16.0)) {
            tg__free(a, img);
            return TG_ERR_CANCELLED;
        }
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                float acc = 0.0f;
                for (int j = 0; j < ss; ++j)
                    for (int i = 0; i < ss; ++i)
                        acc += cv->rgb[3 * ((size_t)(y * ss + j) * (size_t)cv->w + (size_t)(x * ss + i)) + c];
                int v = (int)lrintf(255.0f * acc / (float)(ss * ss));
                img[3 * ((size_t)y * (size_t)w + (size_t)x) + c] = (unsigned char)(v < 0 ? 0 : v > 255 ? 255 : v);
            }
    }
    png_image pi;
    memset(&pi, 0, sizeof pi);
    pi.version = PNG_IMAGE_VERSION;
    pi.width = (png_uint_32)w;
    pi.height = (png_uint_32)h;
    pi.format = PNG_FORMAT_RGB;
    /* one compression pass into a buffer the PNG of this image all but certainly fits (the raw
     * image, a filter byte per row, zlib's 5 bytes per stored 16 KiB block, headers); libpng
     * says the size it needs when it does not fit, and then a second pass is made */
    png_alloc_size_t size = (png_alloc_size_t)w * (png_alloc_size_t)h * 3u + (png_alloc_size_t)h +
                            ((png_alloc_size_t)w * (png_alloc_size_t)h * 3u >> 12) + 4096u;
    tg_status st = TG_OK;
    void* mem = tg__alloc(a, size);
    png_alloc_size_t capacity = size;
    bool ok = mem && png_image_write_to_memory(&pi, mem, &size, 0, img, 0, NULL);
    if (mem && !ok && size > capacity) { /* too small: libpng said how large */
        tg__free(a, mem);
        png_image_free(&pi);
        memset(&pi, 0, sizeof pi);
        pi.version = PNG_IMAGE_VERSION;
        pi.width = (png_uint_32)w;
        pi.height = (png_uint_32)h;
        pi.format = PNG_FORMAT_RGB;
        mem = tg__alloc(a, size);
        ok = mem && png_image_write_to_memory(&pi, mem, &size, 0, img, 0, NULL);
    }
    if (!ok) {
        tg__diag_set(diag, path, 0, 0, 0, "PNG encoding failed: %s", pi.message[0] ? pi.message : "out of memory");
        st = mem ? TG_ERR_IO : TG_ERR_OUT_OF_MEMORY;
    }
    png_image_free(&pi);
    /* the encoding (one libpng call, about 0.2 s for 4000 x 4000 pixels) does not report: a
     * caller that asked to stop meanwhile is heard here, before the file is opened */
    if (st == TG_OK && pc->o->progress && pc->o->progress(pc->o->progress_user, 1.0) != 0) st = TG_ERR_CANCELLED;
    if (st == TG_OK) {
        FILE* f = fopen(path, "wb");
        if (!f || fwrite(mem, 1, size, f) != size) {
            tg__diag_set(diag, path, 0, 0, 0, "cannot write the PNG file");
            st = TG_ERR_IO;
        }
        if (f && fclose(f) != 0 && st == TG_OK) {
            tg__diag_set(diag, path, 0, 0, 0, "cannot write the PNG file");
            st = TG_ERR_IO;
        }
    }
    tg__free(a, mem);
    tg__free(a, img);
    return st;
}

static void scalar_range(const tg_mesh* m, const double* s, double* lo, double* hi)
{
    *lo = INFINITY, *hi = -INFINITY;
    for (size_t v = 0; v < m->vertex_count; ++v)
        if (isfinite(s[v]) && m->vhe[v] != TG_NONE) *lo = fmin(*lo, s[v]), *hi = fmax(*hi, s[v]);
    if (!(*lo <= *hi)) *lo = *hi = 0.0;
}

tg_status tg_render_png(const tg_mesh* m, const tg_render_options* options, const char* png_path, tg_diag* diag)
{
    tg_render_options o;
    memset(&o, 0, sizeof o);
    if (options) o = *options;
    tg__diag_clear(diag, png_path);
    if (!m || !png_path || (o.polyline_count && !o.polyline)) return TG_ERR_INVALID_ARGUMENT;
    if (!o.width) o.width = 960;
    if (!o.height) o.height = 720;
    if (o.width < 1 || o.height < 1 || o.width > MAX_SIDE || o.height > MAX_SIDE || o.supersample < 0 ||
        o.supersample > 8) {
        tg__diag_set(diag, png_path, 0, 0, 0, "image size %d x %d (supersample %d) out of range", o.width,
                     o.height, o.supersample);
        return TG_ERR_INVALID_ARGUMENT;
    }
    if (!o.supersample) { /* the default 3 x 3, lowered as far as the memory budget needs */
        o.supersample = 3;
        while (o.supersample > 1 && render_bytes(o.width, o.height, o.supersample) > (double)TG_RENDER_MAX_BYTES)
            o.supersample--;
    }
    if (render_bytes(o.width, o.height, o.supersample) > (double)TG_RENDER_MAX_BYTES) {
        tg__diag_set(diag, png_path, 0, 0, 0,
                     "a %d x %d image with %d x %d samples per pixel needs %.2f GiB, over the budget of %.0f GiB "
                     "(TG_RENDER_MAX_BYTES): choose a smaller size or fewer samples",
                     o.width, o.height, o.supersample, o.supersample,
                     render_bytes(o.width, o.height, o.supersample) / 1073741824.0,
                     (double)TG_RENDER_MAX_BYTES / 1073741824.0);
        return TG_ERR_INVALID_ARGUMENT;
    }
    if (o.polyline_parts && !o.polyline_start) return TG_ERR_INVALID_ARGUMENT;
    for (size_t p = 0; p < o.polyline_parts; ++p)
        if (o.polyline_start[p] > o.polyline_start[p + 1] || o.polyline_start[p + 1] > o.polyline_count) {
            tg__diag_set(diag, png_path, 0, 0, 0, "polyline part %zu out of order or past the points", p);
            return TG_ERR_INVALID_ARGUMENT;
        }
    if (!isolines_valid(&o, png_path, diag)) return TG_ERR_INVALID_ARGUMENT;
    for (size_t i = 0; i < 3 * o.polyline_count; ++i)
        if (!isfinite(o.polyline[i])) {
            tg__diag_set(diag, png_path, 0, 0, 0, "polyline point %zu is not finite", i / 3);
            return TG_ERR_INVALID_ARGUMENT;
        }
    if (!(o.checker_size >= 0.0) || !isfinite(o.checker_size)) {
        tg__diag_set(diag, png_path, 0, 0, 0, "checker size %g is not a finite number >= 0", o.checker_size);
        return TG_ERR_INVALID_ARGUMENT;
    }
    canvas cv = {o.width * o.supersample, o.height * o.supersample, NULL, NULL};
    size_t px = (size_t)cv.w * (size_t)cv.h;
    cv.depth = tg__alloc_array(&m->allocator, px, sizeof(float));
    cv.rgb = tg__alloc_array(&m->allocator, px, 3 * sizeof(float));
    tg_vec3* sp = tg__alloc_array(&m->allocator, m->vertex_count, sizeof(tg_vec3));
    tg_vec3* vn = tg__alloc_array(&m->allocator, m->vertex_count, sizeof(tg_vec3));
    tg_status st = TG_OK;
    if (!cv.depth || !cv.rgb || !sp || !vn) {
        st = TG_ERR_OUT_OF_MEMORY;
        goto done;
    }
    /* progress: the canvas rows, the faces, the picture rows (a row about a face's cost) */
    progress_ctx pc = {&o, (double)cv.h + (double)m->face_count + 16.0 * o.height, 0.0, now_s() + PROGRESS_PERIOD_S, 0};
    for (int y = 0; y < cv.h; ++y) { /* first touch of the canvas: seconds for the largest */
        /* a soft vertical gradient keeps silhouettes readable on screen and paper */
        float g = 0.97f - 0.10f * (float)y / (float)cv.h;
        for (size_t i = (size_t)y * (size_t)cv.w, end = i + (size_t)cv.w; i < end; ++i) {
            cv.depth[i] = INFINITY;
            cv.rgb[3 * i] = cv.rgb[3 * i + 1] = g;
            cv.rgb[3 * i + 2] = g + 0.01f;
        }
        if (stop_requested(&pc, 1.0)) {
            st = TG_ERR_CANCELLED;
            goto done;
        }
    }
    camera cam;
    camera_basis(&o, &cam);
    camera_fit(m, &o, &cv, &cam);
    for (size_t v = 0; v < m->vertex_count; ++v) sp[v] = project(&cam, tg_v3_load(m->xyz + 3 * v));
    vertex_normals(m, vn);
    shade_ctx sc = {&o, 0, 0, o.isoline_parts ? -1 : o.isolines == 0 ? 16 : o.isolines, o.checker_size};
    if (!(sc.checker > 0.0)) {
        const double *lo = m->report.bbox_min, *hi = m->report.bbox_max;
        sc.checker = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                          (hi[2] - lo[2]) * (hi[2] - lo[2])) / 40.0;
        if (!(sc.checker > 0.0)) sc.checker = 1.0;
    }
    if (o.vertex_scalar) scalar_range(m, o.vertex_scalar, &sc.smin, &sc.smax);
    for (size_t f = 0; f < m->face_count; ++f) {
        raster_face(m, f, sp, vn, &sc, &cam, &cv);
        if (stop_requested(&pc, 1.0)) {
            st = TG_ERR_CANCELLED;
            goto done;
        }
    }
    double radius = 1.6 * o.supersample * (o.width > 1200 ? o.width / 1200.0 : 1.0);
    draw_isolines(&o, &sc, &cam, 0.8 * radius, &cv);
    bool parts = o.polyline_parts > 0;
    for (size_t p = 0, i = 0; parts ? p < o.polyline_parts : p < 1; ++p) {
        size_t end = parts ? o.polyline_start[p + 1] : o.polyline_count;
        for (i = parts ? o.polyline_start[p] : 0; i + 1 < end; ++i)
            raster_segment(project(&cam, tg_v3_load(o.polyline + 3 * i)),
                           project(&cam, tg_v3_load(o.polyline + 3 * i + 3)), parts ? 0.7 * radius : radius, &cam, &cv,
                           parts, NULL);
    }
    if (o.polyline_count && !parts) {
        tg_vec3 e0 = project(&cam, tg_v3_load(o.polyline));
        tg_vec3 e1 = project(&cam, tg_v3_load(o.polyline + 3 * (o.polyline_count - 1)));
        raster_segment(e0, e0, 2.6 * radius, &cam, &cv, false, NULL);
        raster_segment(e1, e1, 2.6 * radius, &cam, &cv, false, NULL);
    }
    st = write_png(&m->allocator, &cv, o.supersample, png_path, &pc, diag);
done:
    if (st == TG_ERR_OUT_OF_MEMORY) tg__diag_set(diag, png_path, 0, 0, 0, "out of memory for a %d x %d image", o.width, o.height);
    tg__free(&m->allocator, cv.depth);
    tg__free(&m->allocator, cv.rgb);
    tg__free(&m->allocator, sp);
    tg__free(&m->allocator, vn);
    return st;
}
