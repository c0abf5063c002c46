/* test_render_limits.c - tg_render_png's bounded resources and cancellation:
 * a size whose samples would exceed TG_RENDER_MAX_BYTES is refused before anything is allocated,
 * with a message saying how much it needs; the default supersampling is lowered to fit (seen
 * through the first buffer it asks the allocator for); the progress callback is called with
 * growing fractions in [0, 1] and stops the call with TG_ERR_CANCELLED, no file written. */
#include "tg_test.h"

#include <trigeo.h>
#include <unistd.h>

typedef struct prog {
    int calls, stop_at;
    double last;
    int bad;
} prog;

static int on_progress(void* user, double fraction)
{
    prog* p = user;
    p->calls++;
    if (!(fraction >= p->last && fraction <= 1.0)) p->bad++;
    p->last = fraction;
    return p->stop_at && p->calls >= p->stop_at;
}

/* The largest request: the colour buffer, width * height * ss^2 * 3 floats (every request fails,
 * so nothing large is allocated). */
static size_t first_buffer(const tg_mesh* src, int w, int h, int ss, tg_status* out_status)
{
    tg_test_counting c = {0, 0, -1, 0};
    tg_allocator a = tg_test_failing_allocator(&c);
    tg_mesh_options mo = {&a};
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(tg_mesh_positions(src), tg_mesh_vertex_count(src), tg_mesh_triangles(src),
                                tg_mesh_face_count(src), &mo, NULL, &m),
                 TG_OK);
    c.fail_after = c.allocs; /* the render's requests fail: nothing big is allocated */
    c.largest = 0;
    tg_render_options o;
    memset(&o, 0, sizeof o);
    o.width = w, o.height = h, o.supersample = ss;
    tg_diag d;
    *out_status = tg_render_png(m, &o, "never-written.png", &d);
    size_t largest = c.largest;
    tg_mesh_destroy(m);
    return largest;
}

int main(void)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/nvd_spot.obj", tg_test_meshes_dir());
    tg_mesh* spot = NULL;
    CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_AUTO, NULL, NULL, &spot), TG_OK);
    if (!spot) return tg_test_finish();

    /* over the budget: refused at once, saying what it would need */
    tg_render_options o;
    memset(&o, 0, sizeof o);
    o.width = 8192, o.height = 8192, o.supersample = 3;
    tg_diag d;
    memset(&d, 0, sizeof d);
    CHECK_STATUS(tg_render_png(spot, &o, "never-written.png", &d), TG_ERR_INVALID_ARGUMENT);
    CHECK_MSG(strstr(d.message, "GiB") && strstr(d.message, "8192 x 8192"), "message: %s", d.message);
    CHECK(access("never-written.png", F_OK) != 0);

    /* the default supersampling: 3 where it fits, fewer where it does not, never over budget */
    struct { int w, h, ss; } cases[] = {{960, 720, 3}, {3700, 3700, 3}, {4000, 4000, 2}, {5400, 5400, 2},
                                        {6000, 6000, 1}, {8192, 8192, 1}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        tg_status st;
        size_t got = first_buffer(spot, cases[i].w, cases[i].h, 0, &st);
        size_t want = (size_t)cases[i].w * (size_t)cases[i].h * (size_t)(cases[i].ss * cases[i].ss) * 3 * sizeof(float);
        CHECK_MSG(st == TG_ERR_OUT_OF_MEMORY && got == want,
                  "%d x %d by default: colour buffer %zu bytes, expected %zu (%d x %d samples), status %s", cases[i].w,
                  cases[i].h, got, want, cases[i].ss, cases[i].ss, tg_status_name(st));
    }
    /* an explicit supersample within the budget is kept */
    tg_status st;
    CHECK_EQ_INT(first_buffer(spot, 2000, 1000, 4, &st), 2000 * 1000 * 16 * 3 * sizeof(float));

    /* progress and cancellation */
    const char* out = "test_render_limits.png";
    remove(out);
    memset(&o, 0, sizeof o);
    o.width = 1600, o.height = 1200; /* about 0.3 s: the callback is asked every 5 ms */
    prog p = {0, 0, 0.0, 0};
    o.progress = on_progress, o.progress_user = &p;
    CHECK_STATUS(tg_render_png(spot, &o, out, &d), TG_OK);
    CHECK_MSG(p.calls >= 2 && p.bad == 0, "%d progress calls, %d out of order", p.calls, p.bad);
    CHECK(access(out, F_OK) == 0);
    remove(out);
    for (int stop = 1; stop <= 2; ++stop) {
        prog s = {0, stop, 0.0, 0};
        o.progress_user = &s;
        CHECK_STATUS(tg_render_png(spot, &o, out, &d), TG_ERR_CANCELLED);
        CHECK_EQ_INT(s.calls, stop);
        CHECK_MSG(access(out, F_OK) != 0, "a cancelled render wrote %s", out);
    }
    tg_mesh_destroy(spot);
    return tg_test_finish();
}
