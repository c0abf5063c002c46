/* record.c - recording, while a run propagates, the windows that may matter for given distance
 * levels: each list's windows as they cross their face (with the point sources inside faces,
 * and the sides of the curves' segments in the faces holding them), so that the exact distance
 * inside a face can be rebuilt after the run (isolines.c).
 * Based on: J. S. B. Mitchell, D. M. Mount and C. H. Papadimitriou, "The discrete geodesic
 *   problem", SIAM J. Comput. 16(4), 1987, §4 (the distance at a point of a face is the least over
 *   the windows whose rays reach it, the face's corners, and the sources in the face; query.c).
 *
 * Which windows: the distance D is 1-Lipschitz, so over a face of longest side delta it spans at
 * most delta; a level L meets the face only if L <= D <= every window's distance there, hence
 * L >= the least distance wmin of every window crossing it over the face within delta (each
 * window's values over the face lie in [wmin, ...]). A window whose wmin has no level in
 * [wmin, wmin + delta] is therefore above every level that meets the face (it can neither carry
 * the level set nor hide it) and is not needed. Recording is off unless a run asks for it, so
 * plain fields pay one test per list.
 *
 * A window is left out for level L in two ways: L < wmin (harmless: above L it hides nothing), or
 * L > wmin + delta, and then the level does not meet the face at all: D <= wmin + delta < L over
 * the whole face, edges and corners included. The face's other windows are then incomplete for L
 * (some were left out), so the isolines must know it: each face keeps the least wmin of the
 * windows that crossed it (fs->rec_floor), and tg__field_record_below tells, by the same
 * arithmetic as the filter, the levels for which a window of the face may be missing. */
#include "geodesic/field/record.h"

#include "geodesic/field/scratch.h"

/* Is there a level in [lo, hi]? (levels ascending) */
static bool level_within(const tg__field_query* q, double lo, double hi)
{
    size_t a = 0, b = q->record_level_count;
    while (a < b) { /* the first level >= lo */
        size_t m = a + (b - a) / 2;
        if (q->record_levels[m] < lo) a = m + 1;
        else b = m;
    }
    return a < q->record_level_count && q->record_levels[a] <= hi;
}

/* The longest side of face f, with a relative margin for the rounding of the distances compared
 * with it. */
static double face_span(const tg_geodesic* g, uint32_t f)
{
    const tg__frame* fr = &g->frame[3 * (size_t)f];
    double a = fr->len, b = g->frame[3 * (size_t)f + 1].len, c = g->frame[3 * (size_t)f + 2].len;
    double m = a > b ? a : b;
    return (m > c ? m : c) * (1.0 + 1e-9);
}

bool tg__field_record_setup(tg__field_run* run)
{
    tg__field_scratch* fs = run->fs;
    size_t nf = run->g->face_count;
    fs->rec.count = 0;
    fs->rec_floor.count = 0;
    if (!run->q->record_levels) return true;
    if (!tg__field_grow(fs, &fs->rec_floor, nf)) return false;
    double* least = fs->rec_floor.data;
    for (size_t f = 0; f < nf; ++f) least[f] = INFINITY;
    fs->rec_floor.count = nf;
    return true;
}

bool tg__field_record_below(const tg__field_scratch* fs, uint32_t f, double level)
{
    const double* least = fs->rec_floor.data;
    return level > least[f] + face_span(fs->g, f);
}

static bool append(tg__field_scratch* fs, const tg__rec_window* r)
{
    if (!tg__field_grow(fs, &fs->rec, 1)) return false;
    ((tg__rec_window*)fs->rec.data)[fs->rec.count++] = *r;
    return true;
}

bool tg__field_record_cross(tg__field_run* run, uint32_t h, const tg__window* pool, const uint32_t* ids, size_t n)
{
    const tg_geodesic* g = run->g;
    uint32_t f = h / 3;
    if (g->fflags[f] & (TG__F_SKIP | TG__F_FLAT)) return true;
    double span = face_span(g, f), *least = (double*)run->fs->rec_floor.data + f;
    for (size_t i = 0; i < n; ++i) {
        const tg__window* w = &pool[ids[i]];
        if (!(w->b0 < w->b1)) continue;
        /* the least distance over the interval: at the foot of the image when inside, else an end
         * (rays only grow beyond the edge, so this bounds the face's part too); a line window's is
         * linear along the edge: an end */
        bool line = tg__win_is_line(w);
        double wmin = (!line && w->sx > w->b0 && w->sx < w->b1)
                          ? w->sigma - w->sy
                          : fmin(tg__win_dist(w, w->b0), tg__win_dist(w, w->b1));
        double lo = wmin * (1.0 - 1e-12);
        if (lo < *least) *least = lo;
        if (!level_within(run->q, lo, lo + span)) continue;
        tg__rec_window r = {h, line ? TG__REC_LINE : TG__REC_POINT, w->sx, w->sy, w->sigma, w->b0, w->b1};
        if (!append(run->fs, &r)) return false;
    }
    return true;
}

bool tg__field_record_source(tg__field_run* run, const double src[3], double sigma, uint32_t f)
{
    const tg_geodesic* g = run->g;
    if (g->fflags[f] & (TG__F_SKIP | TG__F_FLAT)) return true;
    double xy[2];
    tg__frame_point(g, 3 * f, tg_v3_load(src), xy);
    tg__rec_window r = {3 * f, TG__REC_POINT, xy[0], xy[1], sigma, 1.0, 0.0};
    return append(run->fs, &r);
}

bool tg__field_record_segment(tg__field_run* run, uint32_t f, const double o[2], const double e[2])
{
    if (run->g->fflags[f] & (TG__F_SKIP | TG__F_FLAT)) return true;
    tg__rec_window r = {3 * f, TG__REC_SEGMENT, o[0], o[1], 0.0, e[0], e[1]};
    return append(run->fs, &r);
}
