/* isolines.c - exact isolines of a distance field: the curves where the exact geodesic distance
 * equals given levels, from the windows one run records near them (field/record.c).
 * Based on: J. S. B. Mitchell, D. M. Mount and C. H. Papadimitriou, "The discrete geodesic
 *   problem", SIAM J. Comput. 16(4), 1987, §4 (inside a face the distance is the least of the
 *   windows' sigma + |p - s| over the wedges they light, the corners' d(c) + |cp| and the sources
 *   in the face: a lower envelope of cones, so its level sets are arcs of circles about the
 *   source images, of radius level - sigma).
 *
 * Edges: {x : D(x) <= L} is the union over the pieces of {x in wedge : sigma + |x - s| <= L}, each
 * an interval in closed form (a line against a disc and two half-planes), so the crossings are
 * the ends of the union's parts inside the edge: exact to rounding, shared by the faces at the
 * edge (every face's pieces are taken), and an interior minimum gives two crossings.
 * Faces: from each crossing where the curve enters a face, the curve is walked counterclockwise
 * about the active centre (the nearer side on the left: the gradient of D is the unit vector from
 * that centre), one arc step at a time (looked at inside too where it passes over another circle's
 * disc), each point projected back on the level (Newton on D,
 * exact in one step while the centre stays), the two circles' intersection inserted where the
 * centre changes, until the arc meets a side of the face: the exit snaps to the nearest crossing
 * of that side. The pieces are joined at their crossings into polylines. A vertex whose distance
 * is the level is a crossing too: walks end there, and start there into each face where the
 * circle through it that rules beyond it enters the face (or one passing within NEAR_REL of it,
 * where crossings are its node); such vertices joined by edges that short (coincident vertices)
 * are one node. A face whose distance the record proves
 * below the level everywhere (field/record.c: some of its windows were then left out, so its
 * pieces do not give its distance) is not walked, and its sides have no crossing. Nor is a
 * zero-area face (its sides lie on one segment): it joins the crossings at one place of two of
 * its sides.
 * Curves (tg_geodesic_curve_isolines): two more kinds of piece, linear: a line window's
 * sigma + n . p over the strip of its parallel rays, and in a face holding a segment each side's
 * distance to it, over the strip where the foot of the perpendicular falls inside it (its ends
 * are point sources). Their level sets are straight: the walk goes along n turned by +90 degrees
 * (the nearer side on the left, as about a centre), in one step to the side it leaves by, and
 * the curve's corners where the piece changes are the exact crossings of a line with a circle or
 * another line. Edges, nodes and chaining are the same. */
#include "geodesic/workspace.h"

#include <stdlib.h>
#include <string.h>

/* ---- one face's distance: its pieces ---- */

/* A piece of the distance in a face: sigma + |p - c| for p in its wedge (k < 3: a window in the
 * frame of side k, its image (sx, sy) and interval [b0, b1]; k == 3: everywhere, a corner or a
 * source in the face, `source` then set). (cx, cy): the centre in the face's frame.
 * A line piece (`line` set: a line window, or one side of a curve's segment in its face) is
 * linear instead: off + n . p (face frame) over the strip of its parallel rays. Its frame: origin
 * o, unit axis t (the window's side, or the segment), y along t turned by +90 degrees; the rays
 * have the direction (sx, sy) there (sy > 0) and leave the axis within [b0, b1] (x), at y >= ylo
 * (a segment: its own side only, to rounding; a window: -inf, its face lies on its side). Its
 * level sets are straight lines across the strip, walked along n turned by +90 degrees (the
 * nearer side on the left, as for arcs). */
typedef struct piece {
    uint32_t k, source;
    uint32_t circle; /* the first piece with the same centre and offset (one distance function,
                        split among wedges: a bundle entering through two sides, a corner); for
                        a line, the same linear function */
    uint32_t line;
    double sx, sy, b0, b1;
    double cx, cy, sigma;
    double ox, oy, tx, ty, ylo; /* line: its frame */
    double nx, ny, off;         /* line: the gradient n and the value at the face frame's origin */
    double lo;                  /* the least value over the face (less a margin: lines), the sort key:
                                   sigma for a circle */
} piece;

/* A face in its own frame (that of halfedge 3f): corners c[i], sides i = c[i] -> c[i + 1] of
 * length len[i] and direction u[i] (the face on their left). */
typedef struct face_geo {
    uint32_t f;
    double c[3][2], u[3][2], len[3];
    double span; /* longest side */
} face_geo;

/* A crossing of one level: on the edge of halfedge e (the lowest of its ring) at x from tri[e];
 * or a vertex whose distance is the level (e == TG_NONE, the vertex v): the curve passes through
 * it, from one face at it into another. Crossings within NEAR_REL of the same vertex (the
 * curve passes that close to it) are one node: rep, the first of them, stands for all. */
typedef struct crossing {
    uint32_t e, v, rep;
    double x;
} crossing;

/* A vertex lies on a level when its distance is the level to this relative margin (the rounding
 * of distances: the curve then passes within it of the vertex, and is taken through it). */
#define VERTEX_LEVEL_REL 1e-12
/* Nearness at an edge, relative to the longest side of the faces at it: an edge crossing this
 * close to a vertex on the level is that vertex; to another vertex, it is one node with the
 * other crossings that close to it, and so is one this close to the edge's previous crossing; a
 * walk's exit joins the crossing (or vertex) of its side this close (both ways agree; in a
 * sliver, a curve passing close to a vertex crosses the short sides far from it relative to
 * their own length). */
#define NEAR_REL 1e-6
/* A walk leaves through a side it starts on only beyond this angle about its centre: a circle
 * tangent to the side there meets it twice within about the square root of the rounding. */
#define START_ANGLE 1e-7
/* A walk starts on a circle off the level at its crossing by at most this much of the face (the
 * windows' rounding; walk_on snaps onto the next arc within it too). */
#define START_SNAP 1e-9

/* A walked piece of curve in one face: from crossing a to crossing b (indices of the level's
 * crossings; TG_NONE: the walk stopped there), through the face points [p0, p1) of `pts`; or a
 * closed curve about a source in the face (a == b == TG_NONE, loop set). */
typedef struct segment {
    uint32_t a, b, face, loop;
    size_t p0, p1;
} segment;

/* Every buffer of one call, made with the call's allocator. */
typedef struct iso_state {
    const tg_geodesic* g;
    const tg_allocator* alloc;
    const double* dist;          /* the run's vertex distances (solver numbering and frame) */
    const tg__field_scratch* fs; /* the run's: its record (tg__field_record_below) */
    const tg__rec_window* rec;   /* recorded windows, by face through rec_start / rec_order */
    size_t* rec_start;           /* F + 1 */
    uint32_t* rec_order;
    uint32_t* edge_first;        /* 3F, by the ring's lowest halfedge: its first crossing, TG_NONE
                                    while not computed for this level */
    uint32_t* edge_count;
    tg__vec edges_done;          /* uint32_t: halfedges set in edge_first this level */
    uint32_t* vertex_node;       /* V, this level: the vertex's own crossing when it is on the level,
                                    else the first crossing near it (its node's rep); TG_NONE while
                                    not looked at, TG_NONE - 1 when neither (yet) */
    tg__vec vertices_done;       /* uint32_t: vertices set in vertex_node this level */
    tg__vec pieces, pieces2;     /* piece: the face walked, a face at an edge */
    tg__vec spans;               /* double[2]: intervals of one edge */
    tg__vec cross;               /* crossing: this level's */
    tg__vec segs;                /* segment: this level's */
    tg__vec pts;                 /* tg__node: face points of this level's segments */
    /* the result, all levels */
    tg__vec out_nodes;           /* tg__node */
    tg__vec out_faces;           /* uint32_t (solver numbering) */
    tg__vec out_pstart;          /* size_t */
    tg__vec out_closed;          /* uint8_t */
    tg__vec adj_start, adj, used; /* chaining: uint32_t */
    /* progress while the levels are traced (the caller's options, NULL: none) */
    const tg_field_options* options;
    double next_report_s;
    double level;                /* the level being traced (solver frame) */
    size_t levels_done, level_count;
    bool cancelled;              /* the callback asked to stop: the false returned is not memory */
} iso_state;

/* Between faces and levels: the caller's callback once per progress period (tracing 1000 levels
 * on igl_armadillo takes about 10 s after a propagation of 0.1 s), told front_distance the level,
 * rows_done the levels traced of row_count. False when it asks to stop (st->cancelled). */
static bool keep_tracing(iso_state* st)
{
    const tg_field_options* o = st->options;
    if (!o || !o->progress || !tg__progress_due(&st->next_report_s)) return true;
    tg_field_progress p = {st->level * st->g->unscale, (double)st->levels_done / (double)st->level_count,
                           st->levels_done, st->level_count};
    st->cancelled = o->progress(o->progress_user, &p) != 0;
    return !st->cancelled;
}

static void face_geo_of(const tg_geodesic* g, uint32_t f, face_geo* fg)
{
    const tg__frame* fr = &g->frame[3 * (size_t)f];
    fg->f = f;
    fg->c[0][0] = 0.0, fg->c[0][1] = 0.0;
    fg->c[1][0] = fr->len, fg->c[1][1] = 0.0;
    fg->c[2][0] = fr->cx, fg->c[2][1] = fr->cy;
    fg->span = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double* a = fg->c[i];
        const double* b = fg->c[(i + 1) % 3];
        double len = g->frame[3 * (size_t)f + (size_t)i].len;
        fg->len[i] = len;
        fg->u[i][0] = len > 0.0 ? (b[0] - a[0]) / len : 0.0;
        fg->u[i][1] = len > 0.0 ? (b[1] - a[1]) / len : 0.0;
        if (len > fg->span) fg->span = len;
    }
}

/* p (face frame) in the frame of side k. */
static void to_side(const face_geo* fg, int k, const double p[2], double out[2])
{
    double qx = p[0] - fg->c[k][0], qy = p[1] - fg->c[k][1];
    out[0] = qx * fg->u[k][0] + qy * fg->u[k][1];
    out[1] = fg->u[k][0] * qy - fg->u[k][1] * qx;
}

static bool push(const tg_allocator* a, tg__vec* v, const void* item)
{
    if (!tg__vec_reserve(a, v, 1)) return false;
    memcpy((char*)v->data + v->count * v->elem, item, v->elem);
    v->count++;
    return true;
}

static int cmp_piece(const void* x, const void* y)
{
    const piece *a = x, *b = y;
    if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
    if (a->line != b->line) return a->line < b->line ? -1 : 1;
    if (a->cx != b->cx) return a->cx < b->cx ? -1 : 1;
    if (a->cy != b->cy) return a->cy < b->cy ? -1 : 1;
    if (a->nx != b->nx) return a->nx < b->nx ? -1 : 1;
    if (a->ny != b->ny) return a->ny < b->ny ? -1 : 1;
    if (a->off != b->off) return a->off < b->off ? -1 : 1;
    if (a->k != b->k) return a->k < b->k ? -1 : 1;
    return (a->b0 > b->b0) - (a->b0 < b->b0);
}

/* A line piece's value at p (face frame), its strip not looked at. */
static double line_value(const piece* pc, const double p[2])
{
    return pc->off + pc->nx * p[0] + pc->ny * p[1];
}

/* Do two pieces give the same distance function, to tol? Circles: the same centre and offset;
 * lines: the same values at the face's corners (a linear function is fixed by them). */
static bool same_function(const face_geo* fg, const piece* a, const piece* b, double tol)
{
    if (a->line != b->line) return false;
    if (!a->line) return fabs(a->cx - b->cx) <= tol && fabs(a->cy - b->cy) <= tol;
    for (int i = 0; i < 3; ++i)
        if (!(fabs(line_value(a, fg->c[i]) - line_value(b, fg->c[i])) <= tol)) return false;
    return true;
}

/* Sorts the pieces by their least value and names each one's circle: the first piece with the
 * same distance function to a relative 1e-12 of the face (the same image reached through
 * different sides differs by the rounding of two unfoldings). */
static void group_circles(const face_geo* fg, piece* pcs, size_t n, double scale)
{
    if (n > 1) qsort(pcs, n, sizeof *pcs, cmp_piece);
    double tol = 1e-12 * scale;
    for (size_t i = 0; i < n; ++i) {
        pcs[i].circle = (uint32_t)i;
        for (size_t j = i; j-- > 0 && pcs[i].lo - pcs[j].lo <= tol;)
            if (same_function(fg, &pcs[i], &pcs[j], tol)) {
                pcs[i].circle = pcs[j].circle;
                break;
            }
    }
}

/* The line piece of a recorded line window (side k's frame) or segment side (face frame). False
 * for a segment of no length (none). */
static bool line_piece(const face_geo* fg, const tg__rec_window* r, piece* p)
{
    p->line = 1, p->sigma = r->sigma;
    if (r->kind == TG__REC_SEGMENT) {
        double dx = r->b0 - r->sx, dy = r->b1 - r->sy, len = sqrt(dx * dx + dy * dy);
        if (!(len > 0.0)) return false;
        /* rays at right angles from the segment, on its left; the strip's ends snapped as a line
         * window's (query.c), the side to rounding (a segment along an edge lies on it) */
        double snap = tg__window_snap(len, 0.0, 0.0);
        p->k = 3, p->ox = r->sx, p->oy = r->sy, p->tx = dx / len, p->ty = dy / len;
        p->sx = 0.0, p->sy = 1.0, p->b0 = -snap, p->b1 = len + snap, p->ylo = -1e-12 * fg->span;
    } else {
        uint32_t k = r->h % 3;
        double snap = tg__window_snap(fg->len[k], 0.0, 0.0);
        p->k = k, p->ox = fg->c[k][0], p->oy = fg->c[k][1], p->tx = fg->u[k][0], p->ty = fg->u[k][1];
        p->sx = r->sx, p->sy = r->sy, p->b0 = r->b0 - snap, p->b1 = r->b1 + snap, p->ylo = -INFINITY;
    }
    p->nx = p->sx * p->tx - p->sy * p->ty, p->ny = p->sx * p->ty + p->sy * p->tx;
    p->off = p->sigma - (p->nx * p->ox + p->ny * p->oy);
    double least = INFINITY;
    for (int i = 0; i < 3; ++i) least = fmin(least, line_value(p, fg->c[i]));
    /* points looked at lie in the face to 1e-9 of it: far within this margin */
    p->lo = least - 1e-6 * fg->span;
    return true;
}

/* The pieces of face f into v (cleared first): its recorded windows, its corners, its sources. */
static bool pieces_of(iso_state* st, const face_geo* fg, tg__vec* v)
{
    const tg_geodesic* g = st->g;
    uint32_t f = fg->f;
    v->count = 0;
    for (size_t i = st->rec_start[f]; i < st->rec_start[f + 1]; ++i) {
        const tg__rec_window* r = &st->rec[st->rec_order[i]];
        piece p;
        memset(&p, 0, sizeof p);
        p.sigma = r->sigma;
        if (r->kind != TG__REC_POINT) {
            if (!line_piece(fg, r, &p)) continue;
        } else if (!(r->b0 < r->b1)) { /* a point source, in the face's frame */
            p.k = 3, p.source = 1, p.cx = r->sx, p.cy = r->sy;
        } else {
            uint32_t k = r->h % 3;
            /* the snap of query.c: rays that close beyond an end still count */
            double snap = tg__window_snap(fg->len[k], r->sx, r->sy);
            p.k = k, p.sx = r->sx, p.sy = r->sy, p.b0 = r->b0 - snap, p.b1 = r->b1 + snap;
            double vx = -fg->u[k][1], vy = fg->u[k][0];
            p.cx = fg->c[k][0] + r->sx * fg->u[k][0] + r->sy * vx;
            p.cy = fg->c[k][1] + r->sx * fg->u[k][1] + r->sy * vy;
        }
        if (!p.line) p.lo = p.sigma;
        if (!push(st->alloc, v, &p)) return false;
    }
    for (int i = 0; i < 3; ++i) {
        double d = st->dist[g->tri[3 * (size_t)f + (size_t)i]];
        if (!(d < INFINITY)) continue;
        piece p;
        memset(&p, 0, sizeof p);
        p.k = 3, p.cx = fg->c[i][0], p.cy = fg->c[i][1], p.sigma = p.lo = d;
        if (!push(st->alloc, v, &p)) return false;
    }
    group_circles(fg, v->data, v->count, fg->span + (v->count ? ((piece*)v->data)[v->count - 1].sigma : 0.0));
    return true;
}

/* Does the piece's wedge hold p (face frame)? As query.c decides it: where the ray from the image
 * to p crosses the window's edge. */
static bool piece_holds(const face_geo* fg, const piece* pc, const double p[2])
{
    if (pc->line) { /* where its ray through p leaves the axis, as query.c decides it */
        double qx = p[0] - pc->ox, qy = p[1] - pc->oy;
        double x = qx * pc->tx + qy * pc->ty, y = pc->tx * qy - pc->ty * qx;
        double xs = x - y * pc->sx / pc->sy;
        return y >= pc->ylo && xs >= pc->b0 && xs <= pc->b1;
    }
    if (pc->k == 3) return true;
    double q[2];
    to_side(fg, (int)pc->k, p, q);
    double xs = pc->sx + (q[0] - pc->sx) * (-pc->sy) / (q[1] - pc->sy);
    return xs >= pc->b0 && xs <= pc->b1;
}

/* The angle counterclockwise about the piece's centre from p (in its wedge) to the end of its
 * wedge: the ray from the image through the window's start b0 (rays through the edge turn from
 * b1 towards b0 counterclockwise, the face on the edge's left); +inf for a corner or a source.
 * A line: the length along its level line to the strip's ray through b0. */
static double wedge_left(const face_geo* fg, const piece* pc, const double p[2])
{
    if (pc->line) { /* along the level line the rays' foot moves towards b0 at 1 / sy per unit */
        double qx = p[0] - pc->ox, qy = p[1] - pc->oy;
        double x = qx * pc->tx + qy * pc->ty, y = pc->tx * qy - pc->ty * qx;
        return (x - y * pc->sx / pc->sy - pc->b0) * pc->sy;
    }
    if (pc->k == 3) return INFINITY;
    double q[2];
    to_side(fg, (int)pc->k, p, q);
    double vx = q[0] - pc->sx, vy = q[1] - pc->sy, dx = pc->b0 - pc->sx, dy = -pc->sy;
    return atan2(vx * dy - vy * dx, vx * dx + vy * dy);
}

/* The piece's value at p (face frame), its wedge or strip not looked at. */
static double piece_value(const piece* pc, const double p[2])
{
    if (pc->line) return line_value(pc, p);
    double dx = p[0] - pc->cx, dy = p[1] - pc->cy;
    return pc->sigma + sqrt(dx * dx + dy * dy);
}

/* ---- the walk along a piece's level set: an arc about its centre, parametrised by the angle
 * counterclockwise; a line, by the length along its direction n turned by +90 degrees (the
 * nearer side on the left in both) ---- */

/* The length walked per unit of the parameter at p: the radius (arcs), 1 (lines). */
static double arc_scale(const piece* pc, const double p[2])
{
    if (pc->line) return 1.0;
    double vx = p[0] - pc->cx, vy = p[1] - pc->cy;
    return sqrt(vx * vx + vy * vy);
}

/* The least parameter of a start's first step through its own side: START_ANGLE, for a line the
 * same length as on a circle of the face's size. */
static double start_param(const face_geo* fg, const piece* pc)
{
    return pc->line ? START_ANGLE * fg->span : START_ANGLE;
}

/* The unit tangent of the walk at p (p not an arc's centre). */
static void tangent_at(const piece* pc, const double p[2], double t[2])
{
    if (pc->line) {
        t[0] = -pc->ny, t[1] = pc->nx;
        return;
    }
    double gx = p[0] - pc->cx, gy = p[1] - pc->cy, r = sqrt(gx * gx + gy * gy);
    t[0] = -gy / r, t[1] = gx / r;
}

/* p moved along the walk of piece pc by the parameter a. */
static void advance(const piece* pc, const double p[2], double a, double out[2])
{
    if (pc->line) {
        out[0] = p[0] - a * pc->ny, out[1] = p[1] + a * pc->nx;
        return;
    }
    double vx = p[0] - pc->cx, vy = p[1] - pc->cy, cs = cos(a), sn = sin(a);
    out[0] = pc->cx + cs * vx - sn * vy, out[1] = pc->cy + sn * vx + cs * vy;
}

/* When p lies within `snap` of piece pc's level set L (an arc's point beyond min_r of its centre),
 * its nearest point of it into out (out may be p). */
static bool snap_onto(const piece* pc, const double p[2], double L, double snap, double min_r, double out[2])
{
    if (pc->line) {
        double e = line_value(pc, p) - L;
        if (!(fabs(e) <= snap)) return false;
        out[0] = p[0] - e * pc->nx, out[1] = p[1] - e * pc->ny;
        return true;
    }
    double gx = p[0] - pc->cx, gy = p[1] - pc->cy, r = sqrt(gx * gx + gy * gy), want = L - pc->sigma;
    if (!(r > min_r) || !(fabs(r - want) <= snap)) return false;
    out[0] = pc->cx + gx * want / r, out[1] = pc->cy + gy * want / r;
    return true;
}

/* The distance at p (face frame) and its piece (*out_arg, TG_NONE when none holds p). */
static double eval_at(const face_geo* fg, const piece* pcs, size_t n, const double p[2], uint32_t* out_arg)
{
    double best = INFINITY;
    uint32_t arg = TG_NONE;
    for (size_t i = 0; i < n; ++i) {
        const piece* pc = &pcs[i];
        if (!(pc->lo < best)) continue;
        double d = piece_value(pc, p);
        if (d < best && piece_holds(fg, pc, p)) best = d, arg = (uint32_t)i;
    }
    *out_arg = arg;
    return best;
}

/* [x0, x1] cut to where alpha + beta x <= 0; false when nothing is left of the line. */
static bool clip_linear(double alpha, double beta, double* x0, double* x1)
{
    if (beta > 0.0) {
        double t = -alpha / beta;
        if (t < *x1) *x1 = t;
    } else if (beta < 0.0) {
        double t = -alpha / beta;
        if (t > *x0) *x0 = t;
    } else if (alpha > 0.0) {
        return false;
    }
    return true;
}

/* side_interval for a line piece: along the side its value, the foot of its ray and its height
 * above its axis are linear in x, so each condition cuts a half-line. */
static bool line_side_interval(const face_geo* fg, const piece* pc, int m, double L, double* lo, double* hi)
{
    double x0 = 0.0, x1 = fg->len[m], ux = fg->u[m][0], uy = fg->u[m][1];
    double qx = fg->c[m][0] - pc->ox, qy = fg->c[m][1] - pc->oy;
    double y0 = pc->tx * qy - pc->ty * qx, dy = pc->tx * uy - pc->ty * ux;
    double xs0 = qx * pc->tx + qy * pc->ty - y0 * pc->sx / pc->sy;
    double dxs = ux * pc->tx + uy * pc->ty - dy * pc->sx / pc->sy;
    bool ok = clip_linear(line_value(pc, fg->c[m]) - L, pc->nx * ux + pc->ny * uy, &x0, &x1) &&
              clip_linear(pc->b0 - xs0, -dxs, &x0, &x1) && clip_linear(xs0 - pc->b1, dxs, &x0, &x1) &&
              (pc->ylo == -INFINITY || clip_linear(pc->ylo - y0, -dy, &x0, &x1));
    if (!ok || !(x0 <= x1)) return false;
    *lo = x0, *hi = x1;
    return true;
}

/* The part of side m (x from c[m], in [0, len]) where the piece is at most L: [*lo, *hi];
 * false when empty. */
static bool side_interval(const face_geo* fg, const piece* pc, int m, double L, double* lo, double* hi)
{
    if (pc->line) return line_side_interval(fg, pc, m, L, lo, hi);
    double r = L - pc->sigma;
    if (!(r >= 0.0)) return false;
    double qx = fg->c[m][0] - pc->cx, qy = fg->c[m][1] - pc->cy, ux = fg->u[m][0], uy = fg->u[m][1];
    double a = -(qx * ux + qy * uy), b = fabs(ux * qy - uy * qx);
    if (b > r) return false;
    double w = sqrt((r - b) * (r + b));
    double x0 = a - w, x1 = a + w;
    if (pc->k < 3) { /* the wedge: two half-planes, each linear in x (see piece_holds) */
        double o[2], du[2], s[2] = {pc->sx, pc->sy};
        to_side(fg, (int)pc->k, fg->c[m], o);
        int k = (int)pc->k;
        du[0] = ux * fg->u[k][0] + uy * fg->u[k][1];
        du[1] = fg->u[k][0] * uy - fg->u[k][1] * ux;
        for (int side = 0; side < 2; ++side) {
            double dx = (side ? pc->b1 : pc->b0) - s[0], dy = -s[1];
            /* cross(d, P(x) - s) = alpha + beta x; xs >= b0 <=> <= 0, xs <= b1 <=> >= 0 */
            double alpha = dx * (o[1] - s[1]) - dy * (o[0] - s[0]);
            double beta = dx * du[1] - dy * du[0];
            if (side) alpha = -alpha, beta = -beta; /* both as alpha + beta x <= 0 */
            if (beta > 0.0) {
                double t = -alpha / beta;
                if (t < x1) x1 = t;
            } else if (beta < 0.0) {
                double t = -alpha / beta;
                if (t > x0) x0 = t;
            } else if (alpha > 0.0) {
                return false;
            }
        }
    }
    if (x0 < 0.0) x0 = 0.0;
    if (x1 > fg->len[m]) x1 = fg->len[m];
    if (!(x0 <= x1)) return false;
    *lo = x0, *hi = x1;
    return true;
}

static int cmp_span(const void* x, const void* y)
{
    const double *a = x, *b = y;
    return (a[0] > b[0]) - (a[0] < b[0]);
}

/* The lowest halfedge of h's edge (the edge's name). */
static uint32_t edge_name(const tg_geodesic* g, uint32_t h)
{
    uint32_t e = h;
    for (uint32_t o = g->ring[h]; o != h; o = g->ring[o])
        if (o < e) e = o;
    return e;
}

static bool face_traced(const tg_geodesic* g, uint32_t f)
{
    return !(g->fflags[f] & (TG__F_SKIP | TG__F_FLAT));
}

/* Is the distance below L over the whole of face f (the record's bound: the face's recorded
 * windows are then incomplete for L, and the level does not meet the face, its sides or its
 * corners)? */
static bool face_below(const iso_state* st, uint32_t f, double L)
{
    return tg__field_record_below(st->fs, f, L); /* never for a face not traced: none recorded */
}

#define NOT_ON_LEVEL (TG_NONE - 1u)

/* NEAR_REL times the longest side of the faces at the edge of h. */
static double near_dist(const tg_geodesic* g, uint32_t h)
{
    double span = 0.0;
    uint32_t o = h;
    do {
        for (uint32_t k = 0; k < 3; ++k) span = fmax(span, g->frame[3 * (o / 3) + k].len);
        o = g->ring[o];
    } while (o != h);
    return NEAR_REL * span;
}

/* Looks at vertex v for level L (once per level): its own crossing when its distance is L, with
 * rep as its node (TG_NONE: a node of its own). */
static bool look_at_vertex(iso_state* st, uint32_t v, double L, uint32_t rep)
{
    if (!push(st->alloc, &st->vertices_done, &v)) return false;
    st->vertex_node[v] = NOT_ON_LEVEL;
    if (!(fabs(st->dist[v] - L) <= VERTEX_LEVEL_REL * L)) return true;
    uint32_t id = (uint32_t)st->cross.count;
    crossing c = {TG_NONE, v, rep != TG_NONE ? rep : id, 0.0};
    st->vertex_node[v] = id;
    return push(st->alloc, &st->cross, &c);
}

/* The crossing of vertex v when its distance is the level L (made once per level), else
 * TG_NONE; false when out of memory. Vertices on the level joined by edges within NEAR_REL of
 * their faces (zero-length edges: a mesh with one point split into several coincident vertices,
 * zero-area faces between them) are one node, as the edge crossings that near a vertex are: the
 * curve enters that point at one of them and leaves at another. */
static bool vertex_crossing(iso_state* st, uint32_t v, double L, uint32_t* out)
{
    const tg_geodesic* g = st->g;
    uint32_t* vn = &st->vertex_node[v];
    if (*vn == TG_NONE) {
        size_t i = st->vertices_done.count;
        if (!look_at_vertex(st, v, L, TG_NONE)) return false;
        uint32_t rep = *vn;
        for (; rep != NOT_ON_LEVEL && i < st->vertices_done.count; ++i) { /* its node, breadth first */
            uint32_t u = ((const uint32_t*)st->vertices_done.data)[i];
            if (st->vertex_node[u] == NOT_ON_LEVEL) continue;
            for (uint32_t j = g->corner_start[u]; j < g->corner_start[u + 1]; ++j) {
                uint32_t h = g->corners[j], sides[2] = {h, 3 * (h / 3) + (h % 3 + 2) % 3};
                for (int k = 0; k < 2; ++k) {
                    uint32_t w = g->tri[k ? sides[1] : tg_halfedge_next(h)];
                    if (st->vertex_node[w] == TG_NONE && g->frame[sides[k]].len <= near_dist(g, sides[k]) &&
                        !look_at_vertex(st, w, L, rep))
                        return false;
                }
            }
        }
    }
    *out = *vn != NOT_ON_LEVEL && ((const crossing*)st->cross.data)[*vn].e == TG_NONE ? *vn : TG_NONE;
    return true;
}

/* Adds the crossing at x on the edge named e (of length len; its crossings come in ascending x):
 * one near an end joins that end vertex's node, one near the edge's previous crossing joins that
 * one's (the level touches the edge there, or crosses it twice within the distance at which a
 * walk's exit joins a crossing). */
static bool add_crossing(iso_state* st, uint32_t e, double x, double len, double near)
{
    const tg_geodesic* g = st->g;
    uint32_t id = (uint32_t)st->cross.count;
    crossing c = {e, TG_NONE, id, x};
    const crossing* prev = st->edge_count[e] ? &((const crossing*)st->cross.data)[id - 1] : NULL;
    if (prev && x - prev->x <= near) c.rep = prev->rep;
    uint32_t v = x <= near ? g->tri[e] : x >= len - near ? g->tri[tg_halfedge_next(e)] : TG_NONE;
    if (v != TG_NONE) { /* looked at by the caller: NOT_ON_LEVEL or a node's rep */
        if (st->vertex_node[v] == NOT_ON_LEVEL) st->vertex_node[v] = c.rep;
        else c.rep = st->vertex_node[v];
    }
    if (!push(st->alloc, &st->cross, &c)) return false;
    st->edge_count[e]++;
    return true;
}

/* The crossings of level L on the edge named e, computed once per level from every face at it
 * (none within NEAR_REL of an end on the level: that end is the crossing). */
static bool edge_crossings(iso_state* st, uint32_t e, double L)
{
    const tg_geodesic* g = st->g;
    if (st->edge_first[e] != TG_NONE) return true;
    uint32_t n0, n1;
    if (!vertex_crossing(st, g->tri[e], L, &n0) || !vertex_crossing(st, g->tri[tg_halfedge_next(e)], L, &n1))
        return false;
    st->edge_first[e] = (uint32_t)st->cross.count, st->edge_count[e] = 0;
    if (!push(st->alloc, &st->edges_done, &e)) return false;
    double len = g->frame[e].len;
    if (!(len > 0.0)) return true;
    uint32_t o = e;
    do { /* a face at the edge wholly below the level: the edge too, no crossing */
        if (face_below(st, o / 3, L)) return true;
        o = g->ring[o];
    } while (o != e);
    st->spans.count = 0;
    do {
        uint32_t f = o / 3;
        if (face_traced(g, f)) {
            face_geo fg;
            face_geo_of(g, f, &fg);
            if (!pieces_of(st, &fg, &st->pieces2)) return false;
            const piece* pcs = st->pieces2.data;
            int m = (int)(o % 3);
            bool same = g->tri[o] == g->tri[e];
            for (size_t i = 0; i < st->pieces2.count; ++i) {
                double lo, hi;
                if (!side_interval(&fg, &pcs[i], m, L, &lo, &hi)) continue;
                double iv[2] = {same ? lo : len - hi, same ? hi : len - lo};
                if (!tg__vec_reserve(st->alloc, &st->spans, 1)) return false;
                memcpy((double*)st->spans.data + 2 * st->spans.count++, iv, sizeof iv);
            }
        }
        o = g->ring[o];
    } while (o != e);
    double* iv = st->spans.data;
    size_t n = st->spans.count;
    if (n > 1) qsort(iv, n, 2 * sizeof(double), cmp_span);
    /* parts of the union; gaps of rounding size (pieces meeting at a wedge's edge) are no gaps;
     * their ends strictly inside the edge are the crossings, but none near an end on the level */
    double gap = 1e-12 * len, near = near_dist(g, e), lo_ok = n0 != TG_NONE ? near : 0.0;
    double hi_ok = len - (n1 != TG_NONE ? near : 0.0);
    for (size_t i = 0; i < n;) {
        double lo = iv[2 * i], hi = iv[2 * i + 1];
        size_t j = i + 1;
        for (; j < n && iv[2 * j] <= hi + gap; ++j)
            if (iv[2 * j + 1] > hi) hi = iv[2 * j + 1];
        /* a part of one point (the level touches the edge there) is one crossing */
        double ends[2] = {lo, hi};
        for (int k = 0; k < (hi - lo > gap ? 2 : 1); ++k)
            if (ends[k] > lo_ok && ends[k] < hi_ok && !add_crossing(st, e, ends[k], len, near)) return false;
        i = j;
    }
    return true;
}

/* ---- walking the curve through one face ---- */

#define MAX_STEPS 20000

/* Where crossing c lies on side m of the face (x from c[m]). */
static double crossing_on_side(const tg_geodesic* g, const crossing* c, uint32_t h)
{
    return g->tri[h] == g->tri[c->e] ? c->x : g->frame[c->e].len - c->x;
}

/* The crossing of this level on side m of the face (an end vertex on the level included) nearest
 * to x (from c[m]), if within NEAR_REL of it (near_dist); else TG_NONE. */
static uint32_t nearest_crossing(iso_state* st, const face_geo* fg, int m, double x, double L, bool* ok)
{
    const tg_geodesic* g = st->g;
    uint32_t h = 3 * fg->f + (uint32_t)m, e = edge_name(g, h), ends[2];
    if (!edge_crossings(st, e, L) || !vertex_crossing(st, g->tri[h], L, &ends[0]) ||
        !vertex_crossing(st, g->tri[tg_halfedge_next(h)], L, &ends[1])) {
        *ok = false;
        return TG_NONE;
    }
    const crossing* cs = st->cross.data;
    uint32_t best = TG_NONE;
    double near = near_dist(g, h), bd = near;
    for (uint32_t i = st->edge_first[e]; i < st->edge_first[e] + st->edge_count[e]; ++i) {
        double d = fabs(crossing_on_side(g, &cs[i], h) - x);
        if (d <= bd) bd = d, best = i;
    }
    for (int k = 0; k < 2; ++k) {
        double d = fabs((k ? fg->len[m] : 0.0) - x);
        if (ends[k] != TG_NONE && d <= bd) bd = d, best = ends[k];
    }
    for (int k = 0; k < 2 && best == TG_NONE; ++k) {
        /* none on this side, but at an end: the node of crossings near that vertex on its other
         * edges (every edge at it looked at first) */
        uint32_t v = g->tri[k ? tg_halfedge_next(h) : h];
        if (!(fabs((k ? fg->len[m] : 0.0) - x) <= near)) continue;
        for (uint32_t i = g->corner_start[v]; i < g->corner_start[v + 1]; ++i) {
            uint32_t c = g->corners[i], f = c / 3, hp = 3 * f + (c % 3 + 2) % 3;
            if (!edge_crossings(st, edge_name(g, c), L) || !edge_crossings(st, edge_name(g, hp), L)) {
                *ok = false;
                return TG_NONE;
            }
        }
        if (st->vertex_node[v] != NOT_ON_LEVEL) best = st->vertex_node[v];
    }
    return best;
}

/* The angle step about a centre at distance r: the arc's sagitta within 0.9 of the tolerance
 * (1e-3 of the face's longest side), a chord at most that side, at most pi / 4. */
static double step_angle(double r, double span)
{
    double tol = 0.9e-3 * span;
    double a = TG__PI / 4.0;
    if (r > tol) {
        double s = 4.0 * asin(sqrt(tol / (2.0 * r)));
        if (s < a) a = s;
        double c = span / r;
        if (c < a) a = c;
    }
    return a;
}

/* The first parameter in (amin[m], amax] at which the line of piece pc through p meets a side m of
 * the face (first_exit's). */
static double first_exit_line(const face_geo* fg, const piece* pc, const double p[2], const double amin[3],
                              double amax, int* out_m, double* out_x)
{
    double t[2], best = INFINITY;
    tangent_at(pc, p, t);
    for (int m = 0; m < 3; ++m) {
        double ux = fg->u[m][0], uy = fg->u[m][1], den = t[0] * uy - t[1] * ux;
        if (!(den != 0.0)) continue; /* along the side: it leaves through another */
        double wx = fg->c[m][0] - p[0], wy = fg->c[m][1] - p[1];
        double a = (wx * uy - wy * ux) / den, x = (wx * t[1] - wy * t[0]) / den, slack = 1e-9 * fg->len[m];
        if (x < -slack || x > fg->len[m] + slack) continue; /* through a corner: either side */
        x = x < 0.0 ? 0.0 : x > fg->len[m] ? fg->len[m] : x;
        if (a > amin[m] && a <= amax && a < best) best = a, *out_m = m, *out_x = x;
    }
    return best;
}

/* The first parameter in (amin[m], amax] at which the walk of piece pc from p (an arc: the angle
 * counterclockwise about its centre) meets a side m of the face; its side in *out_m, its abscissa
 * along it in *out_x. */
static double first_exit(const face_geo* fg, const piece* pc, const double p[2], const double amin[3],
                         double amax, int* out_m, double* out_x)
{
    if (pc->line) return first_exit_line(fg, pc, p, amin, amax, out_m, out_x);
    const double c[2] = {pc->cx, pc->cy};
    double vx = p[0] - c[0], vy = p[1] - c[1], r = sqrt(vx * vx + vy * vy);
    double best = INFINITY;
    for (int m = 0; m < 3; ++m) {
        double qx = fg->c[m][0] - c[0], qy = fg->c[m][1] - c[1], ux = fg->u[m][0], uy = fg->u[m][1];
        double a = -(qx * ux + qy * uy), b = ux * qy - uy * qx;
        if (!(fabs(b) <= r)) continue;
        double w = sqrt((r - fabs(b)) * (r + fabs(b)));
        for (int s = -1; s <= 1; s += 2) {
            double x = a + s * w, slack = 1e-9 * fg->len[m];
            if (x < -slack || x > fg->len[m] + slack) continue; /* through a corner: either side */
            x = x < 0.0 ? 0.0 : x > fg->len[m] ? fg->len[m] : x;
            double ex = qx + x * ux, ey = qy + x * uy; /* from the centre */
            double ang = atan2(vx * ey - vy * ex, vx * ex + vy * ey);
            if (ang < 0.0) ang += 2.0 * TG__PI;
            if (ang > amin[m] && ang <= amax && ang < best) best = ang, *out_m = m, *out_x = x;
        }
    }
    return best;
}

/* Is p (face frame) in the face, to 1e-9 of its longest side? */
static bool inside_face(const face_geo* fg, const double p[2])
{
    for (int m = 0; m < 3; ++m) {
        double qx = p[0] - fg->c[m][0], qy = p[1] - fg->c[m][1];
        if (fg->u[m][0] * qy - fg->u[m][1] * qx < -1e-9 * fg->span) return false;
    }
    return true;
}

/* The face point of p (face frame). */
static tg__node face_node(const face_geo* fg, const double p[2])
{
    const double *a = fg->c[0], *b = fg->c[1], *c = fg->c[2];
    double det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    double l1 = ((p[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (p[1] - a[1])) / det;
    double l2 = ((b[0] - a[0]) * (p[1] - a[1]) - (p[0] - a[0]) * (b[1] - a[1])) / det;
    /* a point on a side may come out an ulp outside: clamped, as a valid face point */
    double w[3] = {1.0 - l1 - l2, l1, l2}, sum = 0.0;
    for (int i = 0; i < 3; ++i) {
        if (!(w[i] > 0.0)) w[i] = 0.0;
        sum += w[i];
    }
    tg__node nd = {TG__NODE_FACE, fg->f, 0.0, 0.0, {w[0] / sum, w[1] / sum, w[2] / sum}};
    return nd;
}

static bool add_point(iso_state* st, const face_geo* fg, const double p[2])
{
    tg__node nd = face_node(fg, p);
    return push(st->alloc, &st->pts, &nd);
}

/* Is piece k's circle the distance at q (a piece of it holds q, no piece is shorter there beyond
 * rounding)? */
static bool piece_rules(const face_geo* fg, const piece* pcs, size_t n, uint32_t k, const double q[2], double tol)
{
    double bar = piece_value(&pcs[k], q) - tol;
    bool held = false; /* by a piece of k's circle */
    for (size_t i = 0; i < n; ++i) {
        const piece* pc = &pcs[i];
        if (pc->circle == pcs[k].circle) {
            held = held || piece_holds(fg, pc, q);
            continue;
        }
        if (!(pc->lo < bar)) continue;
        if (piece_value(pc, q) < bar && piece_holds(fg, pc, q)) return false;
    }
    return held;
}

static bool walk_on(iso_state* st, const face_geo* fg, uint32_t ci, const double start[2], int m0, int m1,
                    uint32_t j, double L);

/* The point of out[0 .. n) nearest x, into out, when within near of x. */
static bool nearest_of(const double (*cand)[2], int n, const double x[2], double near, double out[2])
{
    double best = near;
    bool found = false;
    for (int i = 0; i < n; ++i) {
        double e = hypot(cand[i][0] - x[0], cand[i][1] - x[1]);
        if (e <= best) best = e, out[0] = cand[i][0], out[1] = cand[i][1], found = true;
    }
    return found;
}

/* The crossing of the circles about a's centre (radius ra) and b's (radius rb) nearest x, into
 * out, when within near of x; false when they do not cross there. */
static bool arcs_cross(const piece* a, double ra, const piece* b, double rb, const double x[2], double near,
                       double out[2])
{
    double dx = b->cx - a->cx, dy = b->cy - a->cy, d = sqrt(dx * dx + dy * dy);
    if (!(d > 0.0)) return false;
    double m = (d * d + ra * ra - rb * rb) / (2.0 * d), h2 = ra * ra - m * m;
    if (!(h2 >= 0.0)) return false;
    double h = sqrt(h2), mx = a->cx + m * dx / d, my = a->cy + m * dy / d, best = near;
    bool found = false;
    for (int s = -1; s <= 1; s += 2) {
        double px = mx - s * h * dy / d, py = my + s * h * dx / d, e = hypot(px - x[0], py - x[1]);
        if (e <= best) best = e, out[0] = px, out[1] = py, found = true;
    }
    return found;
}

/* The same for the circle of piece c (radius r) and the level L of line piece ln. */
static bool arc_line_cross(const piece* c, double r, const piece* ln, double L, const double x[2], double near,
                           double out[2])
{
    double at[2] = {c->cx, c->cy}, delta = L - line_value(ln, at); /* the line from the centre along n */
    double h2 = r * r - delta * delta;
    if (!(h2 >= 0.0)) return false;
    double h = sqrt(h2), fx = c->cx + delta * ln->nx, fy = c->cy + delta * ln->ny;
    double cand[2][2] = {{fx - h * ln->ny, fy + h * ln->nx}, {fx + h * ln->ny, fy - h * ln->nx}};
    return nearest_of(cand, 2, x, near, out);
}

/* The crossing of the level sets L of pieces a and b (a's arc through the walk: radius ra; b's:
 * rb) nearest x, into out, when within near of x. */
static bool levels_cross(const piece* a, double ra, const piece* b, double rb, double L, const double x[2],
                         double near, double out[2])
{
    if (!a->line && !b->line) return arcs_cross(a, ra, b, rb, x, near, out);
    if (!a->line) return arc_line_cross(a, ra, b, L, x, near, out);
    if (!b->line) return arc_line_cross(b, rb, a, L, x, near, out);
    /* two lines: from x onto a's, then along it to b's (each step exact to rounding on its line
     * whatever the angle between them: nearly parallel lines, one bundle unfolded two ways,
     * would make Cramer's rule miss both by the rounding over the sine of that angle) */
    double ea = line_value(a, x) - L, pa[2] = {x[0] - ea * a->nx, x[1] - ea * a->ny};
    double slope = b->nx * -a->ny + b->ny * a->nx; /* b's value along a's direction */
    if (!(slope != 0.0)) return false;            /* parallel: no corner between them */
    double s = (L - line_value(b, pa)) / slope;
    double cand[1][2] = {{pa[0] - s * a->ny, pa[1] + s * a->nx}};
    return nearest_of(cand, 1, x, near, out);
}

/* The stretch (*lo, *hi) of the walk of piece pj from p (arc: radius r, angles counterclockwise
 * from p, lo in [0, 2 pi); line: lengths, either end may be infinite) inside the part where the
 * circle or line of piece pc is below L, when it meets it crosswise within reach of p and reaches
 * deeper than shallow beyond pj's level set (first_dip). */
static bool stretch_below(const piece* pj, const double p[2], double r, const piece* pc, double L, double reach,
                          double shallow, double* lo, double* hi)
{
    if (!pj->line && !pc->line) { /* in the disc of pc's circle */
        double ri = L - pc->sigma, ex = pc->cx - p[0], ey = pc->cy - p[1];
        if (!(ri > 0.0) || !(ex * ex + ey * ey < (ri + reach) * (ri + reach))) return false;
        double vx = p[0] - pj->cx, vy = p[1] - pj->cy;
        double dx = pc->cx - pj->cx, dy = pc->cy - pj->cy, d = sqrt(dx * dx + dy * dy);
        if (!(d < r + ri) || !(d > fabs(r - ri)) || !(ri - r + d > shallow)) return false;
        double cs = (d * d + r * r - ri * ri) / (2.0 * d * r);
        double half = acos(cs < -1.0 ? -1.0 : cs > 1.0 ? 1.0 : cs);
        *lo = atan2(vx * dy - vy * dx, vx * dx + vy * dy) - half; /* from p, counterclockwise */
        *lo = fmod(*lo + 4.0 * TG__PI, 2.0 * TG__PI);
        *hi = *lo + 2.0 * half;
        return true;
    }
    if (!pj->line) { /* pj's circle in the half-plane below pc's line: about the direction -n */
        double at[2] = {pj->cx, pj->cy}, kappa = (L - line_value(pc, at)) / r;
        if (!(line_value(pc, p) - L < reach) || !(kappa < 1.0) || !(kappa > -1.0) || !(r * (kappa + 1.0) > shallow))
            return false;
        double vx = p[0] - pj->cx, vy = p[1] - pj->cy, dx = -pc->nx, dy = -pc->ny, half = acos(-kappa);
        *lo = atan2(vx * dy - vy * dx, vx * dx + vy * dy) - half;
        *lo = fmod(*lo + 4.0 * TG__PI, 2.0 * TG__PI);
        *hi = *lo + 2.0 * half;
        return true;
    }
    double t[2];
    tangent_at(pj, p, t);
    if (!pc->line) { /* pj's line through pc's disc: a chord */
        double ri = L - pc->sigma, wx = pc->cx - p[0], wy = pc->cy - p[1];
        if (!(ri > 0.0) || !(wx * wx + wy * wy < (ri + reach) * (ri + reach))) return false;
        double a0 = t[0] * wx + t[1] * wy, dist = fabs(t[0] * wy - t[1] * wx);
        if (!(ri - dist > shallow)) return false;
        double h = sqrt((ri - dist) * (ri + dist));
        *lo = a0 - h, *hi = a0 + h;
        return true;
    }
    /* two lines: pc's value along pj's line is linear */
    double v0 = line_value(pc, p) - L, slope = pc->nx * t[0] + pc->ny * t[1];
    if (!(slope != 0.0) || !(fmax(-v0, -(v0 + slope * reach)) > shallow)) return false;
    double root = -v0 / slope;
    *lo = slope > 0.0 ? -INFINITY : root, *hi = slope > 0.0 ? root : INFINITY;
    return true;
}

/* Does piece j stop ruling strictly inside the step (0, at] of its arc (at the level) from p,
 * where the step's end alone does not show it (a short stretch where a nearer image rules, a
 * small disc the step passes over)? The arc lies in the disc {sigma + |x - c| < L} of another
 * circle between two angles: where the arc enters or leaves such a disc within the step, j is
 * looked at in the middle of the stretch's part within the step (a disc the whole step lies in
 * shows at the step's end), when the disc reaches deeper than START_SNAP of the face inside the
 * circle (a shallower one moves the curve by less: one image unfolded two ways; the step's end
 * still sees it). Lines alike: a line's half-plane below L across an arc, a disc or a half-plane
 * across a line (stretch_below). The first parameter where j does not rule, else at. */
static double first_dip(const face_geo* fg, const piece* pcs, size_t n, uint32_t j, const double p[2], double at,
                        double L, double tol)
{
    const piece* pj = &pcs[j];
    double r = arc_scale(pj, p), best = at;
    double reach = r * at, shallow = START_SNAP * fg->span; /* the step lies within reach of p */
    for (size_t i = 0; i < n; ++i) {
        const piece* pc = &pcs[i];
        double lo, hi, a, b; /* the part (a, b) of the stretch within the step */
        if (pc->circle != i || pc->circle == pj->circle || !stretch_below(pj, p, r, pc, L, reach, shallow, &lo, &hi))
            continue;
        if (pj->line) {
            a = fmax(lo, 0.0), b = fmin(hi, best);
            if (!(a < b)) continue;
        } else if (lo < best) {
            a = lo, b = fmin(hi, best);
        } else if (hi - 2.0 * TG__PI > 0.0 && hi - 2.0 * TG__PI < best) {
            a = 0.0, b = hi - 2.0 * TG__PI;
        } else {
            continue;
        }
        double t[2];
        advance(pj, p, 0.5 * (a + b), t);
        if (!piece_rules(fg, pcs, n, j, t, tol)) best = 0.5 * (a + b);
    }
    return best;
}

/* q lies a little along the arc (at the level) of the circle ruling at p: does another piece
 * take over between them? The piece ruling at q is below the level there and its circle above it
 * at p: the two circles cross on the arc strictly between p and q. */
static bool taken_over(const face_geo* fg, const piece* pcs, size_t n, const double p[2], const double q[2], double L,
                       double tol)
{
    uint32_t k;
    if (!(eval_at(fg, pcs, n, q, &k) < L) || k == TG_NONE) return false;
    return piece_value(&pcs[k], p) > L + tol;
}

/* Does the circle of piece c leave p (face frame, on it) into the face: across side m, or inside
 * corner m's angle (along side m counts: the arc bends to its left, into the face; a curve through
 * a vertex of a grid leaves along an edge)? Then q: a point a little along the arc (before it
 * leaves the face: a curve may cross the corner of a sliver within far less; at most the angle
 * `most` about the centre), and *k: the piece of the circle that holds q (TG_NONE: none). False
 * when the arc does not enter, or q is not in the face. */
static bool look_along(const face_geo* fg, const piece* pcs, size_t n, uint32_t c, const double p[2], int m,
                       bool corner, double most, double q[2], uint32_t* k)
{
    const piece* pc = &pcs[c];
    const double* u_in = fg->u[m];             /* along side m, away from c[m] */
    const double* u_back = fg->u[(m + 2) % 3]; /* side m - 1 arrives at c[m] */
    double t[2], r = arc_scale(pc, p);
    tangent_at(pc, p, t);
    double tx = t[0], ty = t[1];
    if (corner ? !(u_in[0] * ty - u_in[1] * tx > -1e-12) || !(tx * -u_back[1] - ty * -u_back[0] > 1e-12)
               : !(u_in[0] * ty - u_in[1] * tx > 1e-12))
        return false;
    double amin[3] = {0.0, 0.0, 0.0}, ex;
    int em;
    amin[m] = start_param(fg, pc);
    if (corner) amin[(m + 2) % 3] = start_param(fg, pc);
    double a = fmin(1e-6 * fg->span / r, most);
    double ea = first_exit(fg, pc, p, amin, a, &em, &ex);
    advance(pc, p, ea < a ? 0.5 * ea : a, q);
    *k = TG_NONE;
    for (size_t i = 0; i < n && *k == TG_NONE; ++i)
        if (pcs[i].circle == c && piece_holds(fg, &pcs[i], q)) *k = (uint32_t)i;
    return inside_face(fg, q);
}

/* Does the circle of piece pc pass through p (face frame) at the level, to the rounding of a vertex
 * on it, p not its centre? (A line: its level line.) */
static bool through(const face_geo* fg, const piece* pc, const double p[2], double L, double tol)
{
    if (pc->line) return fabs(line_value(pc, p) - L) <= VERTEX_LEVEL_REL * L + tol;
    double gx = p[0] - pc->cx, gy = p[1] - pc->cy, r = sqrt(gx * gx + gy * gy);
    return r > 1e-9 * fg->span && fabs(pc->sigma + r - L) <= VERTEX_LEVEL_REL * L + tol;
}

/* Where the level set L of piece pc meets the line of side m (x from c[m]): into xs, their count. */
static int side_levels(const face_geo* fg, const piece* pc, int m, double L, double xs[2])
{
    double ux = fg->u[m][0], uy = fg->u[m][1];
    if (pc->line) {
        double slope = pc->nx * ux + pc->ny * uy;
        if (!(slope != 0.0)) return 0;
        xs[0] = (L - line_value(pc, fg->c[m])) / slope;
        return 1;
    }
    double r = L - pc->sigma;
    if (!(r > 0.0)) return 0;
    double qx = fg->c[m][0] - pc->cx, qy = fg->c[m][1] - pc->cy;
    double a = -(qx * ux + qy * uy), b = fabs(ux * qy - uy * qx);
    if (!(b <= r)) return 0;
    double w = sqrt((r - b) * (r + b));
    xs[0] = a - w, xs[1] = a + w;
    return 2;
}

/* At corner m, a vertex on the level (crossing ci) that no circle through it leaves into the face:
 * the curve may still enter the face within NEAR_REL of the vertex (edge crossings that close
 * are the vertex's node, none of their own) on a circle off the level at the vertex by up to that
 * much (unfoldings of the source tying at the vertex to 3e-8 of the face: one passes through it
 * into the faces beyond, another beside it takes over within 5e-8 of it and crosses this face).
 * The curve starts where such a circle crosses a side at the corner within that distance of it,
 * when it enters the face there and rules a little along its arc; a walk that comes back to the
 * vertex's node (a piece of curve within the node) is dropped and the next one tried. */
static bool walk_from_near(iso_state* st, const face_geo* fg, uint32_t ci, int m, double L, double tol)
{
    const piece* pcs = st->pieces.data;
    size_t n = st->pieces.count;
    for (int t = 0; t < 2; ++t) {
        int s = t ? (m + 2) % 3 : m; /* side m leaves the corner at x = 0, side m - 1 arrives at len */
        double near = near_dist(st->g, 3 * fg->f + (uint32_t)s), at = t ? fg->len[s] : 0.0;
        for (uint32_t c = 0; c < n; ++c) {
            const piece* pc = &pcs[c];
            double xs[2], ux = fg->u[s][0], uy = fg->u[s][1];
            if (pc->circle != c || through(fg, pc, fg->c[m], L, tol)) continue;
            int nx = side_levels(fg, pc, s, L, xs);
            for (int i = 0; i < nx; ++i) {
                double x = xs[i], p[2], q[2];
                uint32_t k;
                if (!(fabs(x - at) <= near) || !(x > 0.0 && x < fg->len[s])) continue;
                p[0] = fg->c[s][0] + x * ux, p[1] = fg->c[s][1] + x * uy;
                if (!look_along(fg, pcs, n, c, p, s, false, INFINITY, q, &k) || k == TG_NONE ||
                    !piece_rules(fg, pcs, n, k, q, tol))
                    continue;
                size_t ns = st->segs.count, np = st->pts.count;
                if (!walk_on(st, fg, ci, p, s, -1, k, L)) return false;
                const segment* last = st->segs.count > ns ? &((const segment*)st->segs.data)[ns] : NULL;
                if (last && last->a != last->b) return true;
                st->segs.count = ns, st->pts.count = np; /* back at the vertex's node: within it */
            }
        }
    }
    return true;
}

/* Starts the curve of level L into face fg from p, the crossing ci: on side m (at x from c[m]),
 * or at corner m, a vertex on the level (corner set). The curve leaves p along the circle of a
 * piece through p, counterclockwise (the nearer side on the left: the gradient of D is the unit
 * vector from that centre), into the face (look_along); where pieces of several circles tie at p
 * (the curve has a corner there) the one that rules just beyond p along its arc is taken. When
 * none does at an edge crossing, but another circle takes over from the one ruling at p strictly
 * beyond p (their crossing, a corner of the curve, lies within that look beyond p), the curve runs
 * along the first and walk_on switches at the corner. When no circle within the rounding of the
 * level at p does either, the one that rules beyond p may be off the level at p by the rounding of
 * the windows (up to START_SNAP of the face: a window's wedge ending at p, next to a corner's
 * circle; one image unfolded two ways): the curve starts on it, at its point nearest p. Last, the
 * wedge of the piece holding p may end before the point looked at, where a circle inside its own
 * touches it: the curve starts along it when it rules half-way to that end; or another's wedge
 * may begin there (a vertex passed closer than the look): along it when it rules at a shorter
 * look. At a vertex, last, a circle passing beside it (walk_from_near). */
static bool walk_from(iso_state* st, const face_geo* fg, uint32_t ci, int m, double x, bool corner, double L)
{
    const piece* pcs = st->pieces.data;
    size_t n = st->pieces.count;
    double p[2] = {fg->c[m][0] + x * fg->u[m][0], fg->c[m][1] + x * fg->u[m][1]};
    if (corner) p[0] = fg->c[m][0], p[1] = fg->c[m][1];
    double tol = 1e-14 * (L + fg->span);
    uint32_t first, taken = TG_NONE, k;
    eval_at(fg, pcs, n, p, &first);
    if (first == TG_NONE) return true;
    double q[2];
    for (size_t t = 0; t <= n; ++t) {
        /* the circle of the piece that holds p first, then every other circle once */
        uint32_t c = t == 0 ? pcs[first].circle : (uint32_t)(t - 1);
        if (t > 0 && (pcs[c].circle != c || c == pcs[first].circle)) continue;
        if (!through(fg, &pcs[c], p, L, tol)) continue;
        if (!look_along(fg, pcs, n, c, p, m, corner, INFINITY, q, &k)) continue;
        if (k != TG_NONE && piece_rules(fg, pcs, n, k, q, tol))
            return walk_on(st, fg, ci, p, m, corner ? (m + 2) % 3 : -1, k, L);
        if (t == 0 && !corner && taken_over(fg, pcs, n, p, q, L, tol)) taken = k != TG_NONE ? k : first;
    }
    /* none rules beyond p, but the circle holding p enters the face and another takes over
     * before the point looked at (their crossing within 1e-6 of the face from an edge crossing):
     * the curve runs along the first to it, and walk_on switches there */
    if (taken != TG_NONE) return walk_on(st, fg, ci, p, m, -1, taken, L);
    for (uint32_t c = 0; c < n && !corner; ++c) {
        const piece* pc = &pcs[c];
        double gx = p[0] - pc->cx, gy = p[1] - pc->cy, r = sqrt(gx * gx + gy * gy), s[2];
        if (pc->circle != c) continue;
        if (pc->line) {
            if (!snap_onto(pc, p, L, START_SNAP * fg->span, 0.0, s)) continue;
        } else {
            if (!(r > 1e-9 * fg->span) || !(fabs(pc->sigma + r - L) <= START_SNAP * fg->span)) continue;
            s[0] = pc->cx + gx * (L - pc->sigma) / r, s[1] = pc->cy + gy * (L - pc->sigma) / r;
        }
        if (look_along(fg, pcs, n, c, s, m, false, INFINITY, q, &k) && k != TG_NONE &&
            piece_rules(fg, pcs, n, k, q, tol))
            return walk_on(st, fg, ci, s, m, -1, k, L);
    }
    /* the wedge of the piece holding p may end nearer than the look: where a circle inside its
     * own takes over, tangent to it (a pseudo-source vertex's, the curve passing close to it and
     * into its shadow), the arc looked along runs outside that circle beyond the wedge, so no
     * piece is below the level there and the tests above see nothing. The curve starts along it
     * when it rules half-way to its wedge's end; walk_on switches at the end. Not when the end
     * lies within twice START_ANGLE (a crossing that close to a wedge's end, below what a start
     * resolves: looked along, a crossing 8e-9 from a vertex drew a loop of rounding there). */
    double end = corner ? 0.0 : wedge_left(fg, &pcs[first], p);
    if (end > 2.0 * start_param(fg, &pcs[first]) && end < INFINITY && through(fg, &pcs[first], p, L, tol) &&
        look_along(fg, pcs, n, pcs[first].circle, p, m, false, 0.5 * end, q, &k) && k != TG_NONE &&
        piece_rules(fg, pcs, n, k, q, tol))
        return walk_on(st, fg, ci, p, m, -1, k, L);
    /* the circle holding p may give way, beyond p, to a window's wedge whose disc holds it,
     * tangent to it on that wedge's edge (the curve passing a vertex closer than the look, 1e-6
     * of the face: a large angle about it; beyond the wedge's edge, the window's circle): the
     * curve starts along it when it rules at a shorter look, halved down to twice START_ANGLE;
     * walk_on switches at the wedge's edge */
    if (!corner && through(fg, &pcs[first], p, L, tol)) {
        double r = arc_scale(&pcs[first], p);
        for (double most = 0.5e-6 * fg->span / r; most > 2.0 * start_param(fg, &pcs[first]); most *= 0.5)
            if (look_along(fg, pcs, n, pcs[first].circle, p, m, false, most, q, &k) && k != TG_NONE &&
                piece_rules(fg, pcs, n, k, q, tol))
                return walk_on(st, fg, ci, p, m, -1, k, L);
    }
    return corner ? walk_from_near(st, fg, ci, m, L, tol) : true;
}

/* Walks from p (on the level, piece j ruling), which lies on side m0 (and m1 >= 0: on that side
 * too, at their corner), and appends the segment. Along the arc of the ruling piece until it stops
 * ruling (another piece shorter, or its wedge ends): the angle where it stops is found by
 * bisection, and the walk goes on from there along the arc of the piece that rules beyond. The
 * first step leaves through sides m0, m1 only beyond START_ANGLE, through the others at any angle
 * (a start near a corner may leave through the side beyond the corner at once). */
static bool walk_on(iso_state* st, const face_geo* fg, uint32_t ci, const double start[2], int m0, int m1,
                    uint32_t j, double L)
{
    const piece* pcs = st->pieces.data;
    size_t n = st->pieces.count;
    double tol = 1e-14 * (L + fg->span);
    double p[2] = {start[0], start[1]};
    segment sg = {ci, TG_NONE, fg->f, 0, st->pts.count, 0};
    bool ok = true;
    /* the last two places where the piece changed: a walk back at the one before the last goes
     * to and fro between two pieces (a level within rounding of a curve, where both sides' pieces
     * hold to rounding: nearer side on no side) and stops there */
    double turns[2][2] = {{INFINITY, INFINITY}, {INFINITY, INFINITY}};
    for (int step = 0; step < MAX_STEPS; ++step) {
        const piece* pc = &pcs[j];
        double r = arc_scale(pc, p);
        if (!(r > 0.0)) break;
        /* a line is straight: one step to where it leaves the face (no chord is longer) */
        double da = pc->line ? fg->span : step_angle(r, fg->span);
        int em = -1;
        double ex = 0.0;
        double amin[3] = {0.0, 0.0, 0.0};
        if (step == 0) {
            amin[m0] = start_param(fg, pc);
            if (m1 >= 0) amin[m1] = start_param(fg, pc);
        }
        double ea = first_exit(fg, pc, p, amin, da, &em, &ex);
        double at = ea <= da ? ea : da, q[2];
        advance(pc, p, at, q);
        bool rules = piece_rules(fg, pcs, n, j, q, tol);
        if (rules) { /* and nowhere in between it stops ruling */
            double dip = first_dip(fg, pcs, n, j, p, at, L, tol);
            if (dip < at) at = dip, rules = false, advance(pc, p, at, q);
        }
        if (rules) {
            if (ea <= da) { /* the arc leaves the face: at a crossing of that side, or its end */
                sg.b = nearest_crossing(st, fg, em, ex, L, &ok);
                if (!ok) return false;
                /* none there (a zero-area face beyond): the walk ends on the side, the polyline
                 * open */
                if (sg.b == TG_NONE && !add_point(st, fg, q)) return false;
                break;
            }
            if (!inside_face(fg, q)) break; /* past a side unseen (rounding at a corner): stop open */
            if (!add_point(st, fg, q)) return false;
            p[0] = q[0], p[1] = q[1];
            continue;
        }
        /* the piece stops ruling within (0, at]: where, by bisection on the angle, to 1e-11 of the
         * face (far below the snap onto the next arc below) */
        double lo = 0.0, hi = at;
        for (int it = 0; it < 60 && (hi - lo) * r > 1e-11 * fg->span; ++it) {
            double mid = 0.5 * (lo + hi), t[2];
            advance(pc, p, mid, t);
            if (piece_rules(fg, pcs, n, j, t, tol)) lo = mid;
            else hi = mid;
        }
        double xk[2], beyond[2];
        advance(pc, p, lo, xk);
        advance(pc, p, hi, beyond);
        uint32_t next;
        eval_at(fg, pcs, n, beyond, &next);
        if (next == TG_NONE || next == j) break; /* nothing rules beyond: the walk stops */
        /* onto the next arc (D is continuous: it passes within rounding of xk): at the two arcs'
         * crossing nearest xk when that is within START_SNAP of the face (the corner of the curve,
         * exact to rounding), else at the next circle's point nearest xk (lines alike) */
        double cx[2] = {0.0, 0.0};
        if (levels_cross(pc, r, &pcs[next], L - pcs[next].sigma, L, xk, START_SNAP * fg->span, cx))
            xk[0] = cx[0], xk[1] = cx[1];
        else
            snap_onto(&pcs[next], xk, L, START_SNAP * fg->span, 0.0, xk);
        if (hypot(xk[0] - turns[0][0], xk[1] - turns[0][1]) <= START_SNAP * fg->span) break;
        turns[0][0] = turns[1][0], turns[0][1] = turns[1][1], turns[1][0] = xk[0], turns[1][1] = xk[1];
        if (lo > 0.0 && !add_point(st, fg, xk)) return false;
        p[0] = xk[0], p[1] = xk[1], j = next;
    }
    sg.p1 = st->pts.count;
    /* crossings near one vertex are one node; a piece of curve between two of them is dropped */
    const crossing* cs = st->cross.data;
    sg.a = cs[sg.a].rep;
    if (sg.b != TG_NONE) sg.b = cs[sg.b].rep;
    if (sg.a == sg.b && sg.p1 == sg.p0) return true;
    return push(st->alloc, &st->segs, &sg);
}

/* A closed curve about a source inside the face that meets no side: sampled whole when every
 * sample is on the level (no other piece below it). */
static bool source_loop(iso_state* st, const face_geo* fg, const piece* pc, double L)
{
    const piece* pcs = st->pieces.data;
    double r = L - pc->sigma;
    if (!(r > 0.0)) return true;
    for (int m = 0; m < 3; ++m) { /* the circle must clear every side */
        double qx = pc->cx - fg->c[m][0], qy = pc->cy - fg->c[m][1];
        if (!(fg->u[m][0] * qy - fg->u[m][1] * qx > r)) return true;
    }
    double da = step_angle(r, fg->span);
    int count = (int)ceil(2.0 * TG__PI / da);
    if (count < 8) count = 8;
    size_t p0 = st->pts.count;
    for (int i = 0; i < count; ++i) {
        double a = 2.0 * TG__PI * i / count, q[2] = {pc->cx + r * cos(a), pc->cy + r * sin(a)};
        uint32_t arg;
        if (fabs(eval_at(fg, pcs, st->pieces.count, q, &arg) - L) > 1e-12 * (L + fg->span)) {
            st->pts.count = p0;
            return true;
        }
        if (!add_point(st, fg, q)) return false;
    }
    segment sg = {TG_NONE, TG_NONE, fg->f, 1, p0, st->pts.count};
    return push(st->alloc, &st->segs, &sg);
}

/* Can level L meet face f? D is 1-Lipschitz: within the face it lies in
 * [max d(c) - span, min d(c) + span] over its reached corners. */
static bool face_meets(const iso_state* st, uint32_t f, double L, double span)
{
    double lo = -INFINITY, hi = INFINITY;
    for (int i = 0; i < 3; ++i) {
        double d = st->dist[st->g->tri[3 * (size_t)f + (size_t)i]];
        if (!(d < INFINITY)) continue;
        if (d - span > lo) lo = d - span;
        if (d + span < hi) hi = d + span;
    }
    double m = 1e-12 * (L + span);
    return hi < INFINITY && L >= lo - m && L <= hi + m;
}

/* A crossing as a node: its vertex, or its point of the edge. */
static tg__node crossing_node(const tg_geodesic* g, const crossing* c)
{
    if (c->e == TG_NONE) return tg__node_vertex(c->v);
    double len = g->frame[c->e].len;
    return tg__node_edge(c->e, c->x / len, (len - c->x) / len);
}

/* A zero-area face (not walked: its sides lie on one segment) carries the curve from a crossing
 * of one side to the crossing at the same place on another, or to the corner inside its longest
 * side when that corner is on the level and there: each such pair (within NEAR_REL of the faces
 * at its sides, each crossing in one pair) becomes a segment of no points. */
static bool link_flat(iso_state* st, uint32_t f, double L)
{
    const tg_geodesic* g = st->g;
    enum { MAX_LINKED = 64 };
    uint32_t ids[MAX_LINKED], side[MAX_LINKED];
    tg_vec3 at[MAX_LINKED];
    size_t n = 0;
    double near = 0.0;
    for (uint32_t m = 0; m < 3; ++m) {
        uint32_t e = edge_name(g, 3 * f + m);
        if (!edge_crossings(st, e, L)) return false;
        near = fmax(near, near_dist(g, e));
        for (uint32_t i = st->edge_first[e]; i < st->edge_first[e] + st->edge_count[e]; ++i) {
            if (n == MAX_LINKED) return true; /* left open */
            tg__node nd = crossing_node(g, &((const crossing*)st->cross.data)[i]);
            ids[n] = i, side[n] = m, at[n++] = tg__node_pos(g, &nd);
        }
    }
    /* the corner inside the longest side, when on the level: a side of its own */
    uint32_t lm = 0;
    for (uint32_t m = 1; m < 3; ++m)
        if (g->frame[3 * f + m].len > g->frame[3 * f + lm].len) lm = m;
    uint32_t mid = g->tri[3 * f + (lm + 2) % 3], vc;
    if (!vertex_crossing(st, mid, L, &vc)) return false;
    if (vc != TG_NONE) {
        if (n == MAX_LINKED) return true;
        ids[n] = vc, side[n] = 3, at[n++] = tg__gpos(g, mid);
    }
    bool linked[MAX_LINKED] = {false};
    const crossing* cs = st->cross.data;
    for (size_t i = 0; i < n; ++i) {
        size_t best = n;
        double bd = near;
        for (size_t j = i + 1; j < n && !linked[i]; ++j) {
            double d = tg_v3_dist(at[i], at[j]);
            if (!linked[j] && side[j] != side[i] && d <= bd) bd = d, best = j;
        }
        if (best == n || cs[ids[i]].rep == cs[ids[best]].rep) continue;
        linked[i] = linked[best] = true;
        segment sg = {cs[ids[i]].rep, cs[ids[best]].rep, f, 0, st->pts.count, st->pts.count};
        if (!push(st->alloc, &st->segs, &sg)) return false;
    }
    return true;
}

/* Every segment of level L. */
static bool trace_level(iso_state* st, double L)
{
    const tg_geodesic* g = st->g;
    st->cross.count = st->segs.count = st->pts.count = 0;
    st->level = L;
    for (uint32_t f = 0; f < g->face_count; ++f) {
        if ((f & 1023u) == 0 && !keep_tracing(st)) return false; /* a level can take long too */
        if ((g->fflags[f] & (TG__F_SKIP | TG__F_FLAT)) == TG__F_FLAT) {
            if (!link_flat(st, f, L)) return false;
            continue;
        }
        if (!face_traced(g, f) || face_below(st, f, L)) continue;
        face_geo fg;
        face_geo_of(g, f, &fg);
        if (!face_meets(st, f, L, fg.span)) continue;
        if (!pieces_of(st, &fg, &st->pieces)) return false;
        for (int m = 0; m < 3; ++m) {
            uint32_t h = 3 * f + (uint32_t)m, e = edge_name(g, h);
            if (!edge_crossings(st, e, L)) return false;
            for (uint32_t i = st->edge_first[e]; i < st->edge_first[e] + st->edge_count[e]; ++i) {
                double x = crossing_on_side(g, &((const crossing*)st->cross.data)[i], h);
                if (!walk_from(st, &fg, i, m, x, false, L)) return false;
            }
            uint32_t vc;
            if (!vertex_crossing(st, g->tri[h], L, &vc)) return false;
            if (vc != TG_NONE && !walk_from(st, &fg, vc, m, 0.0, true, L)) return false;
        }
        for (size_t i = 0; i < st->pieces.count; ++i) {
            piece pc = ((const piece*)st->pieces.data)[i];
            if (pc.source && !source_loop(st, &fg, &pc, L)) return false;
        }
    }
    const uint32_t* done = st->edges_done.data;
    for (size_t i = 0; i < st->edges_done.count; ++i) st->edge_first[done[i]] = TG_NONE;
    st->edges_done.count = 0;
    done = st->vertices_done.data;
    for (size_t i = 0; i < st->vertices_done.count; ++i) st->vertex_node[done[i]] = TG_NONE;
    st->vertices_done.count = 0;
    return true;
}

/* ---- joining the segments into polylines ---- */

static bool out_node(iso_state* st, const tg__node* nd, uint32_t face)
{
    return push(st->alloc, &st->out_nodes, nd) && push(st->alloc, &st->out_faces, &face);
}

static bool out_crossing(iso_state* st, uint32_t ci, uint32_t face)
{
    tg__node nd = crossing_node(st->g, &((const crossing*)st->cross.data)[ci]);
    return out_node(st, &nd, face);
}

/* Appends segment s walked from end `from` (its a or b), its far crossing included. */
static bool out_segment(iso_state* st, const segment* s, uint32_t from)
{
    const tg__node* pts = st->pts.data;
    bool fwd = from == s->a;
    for (size_t i = 0; i < s->p1 - s->p0; ++i)
        if (!out_node(st, &pts[fwd ? s->p0 + i : s->p1 - 1 - i], s->face)) return false;
    uint32_t to = fwd ? s->b : s->a;
    return to == TG_NONE || out_crossing(st, to, s->face);
}

static bool close_polyline(iso_state* st, size_t first, uint8_t closed)
{
    size_t end = st->out_nodes.count;
    if (end - first < 2) { /* a lone point: dropped */
        st->out_nodes.count = st->out_faces.count = first;
        return true;
    }
    return push(st->alloc, &st->out_pstart, &end) && push(st->alloc, &st->out_closed, &closed);
}

/* The segments of this level chained at their crossings: first from the crossings where a curve
 * ends (one segment: the mesh boundary, a walk that stopped), then the closed curves. */
static bool chain_level(iso_state* st)
{
    const tg_allocator* a = st->alloc;
    size_t nc = st->cross.count, ns = st->segs.count;
    const segment* segs = st->segs.data;
    if (!tg__vec_fit(a, &st->adj_start, nc + 1) || !tg__vec_fit(a, &st->adj, 2 * ns + 1) ||
        !tg__vec_fit(a, &st->used, ns + 1))
        return false;
    uint32_t *start = st->adj_start.data, *adj = st->adj.data, *used = st->used.data;
    memset(start, 0, (nc + 1) * sizeof *start);
    for (size_t i = 0; i < ns; ++i) {
        if (segs[i].a != TG_NONE) start[segs[i].a + 1]++;
        if (segs[i].b != TG_NONE) start[segs[i].b + 1]++;
    }
    for (size_t v = 0; v < nc; ++v) start[v + 1] += start[v];
    for (size_t i = 0; i < ns; ++i) {
        if (segs[i].a != TG_NONE) adj[start[segs[i].a]++] = (uint32_t)i;
        if (segs[i].b != TG_NONE) adj[start[segs[i].b]++] = (uint32_t)i;
    }
    for (size_t v = nc; v > 0; --v) start[v] = start[v - 1];
    start[0] = 0;
    memset(used, 0, (ns + 1) * sizeof *used);
    for (int pass = 0; pass < 2; ++pass) {
        for (size_t s0 = 0; s0 < ns; ++s0) {
            const segment* s = &segs[s0];
            if (used[s0]) continue;
            size_t first = st->out_nodes.count;
            if (s->loop) {
                if (pass == 0) continue;
                used[s0] = 1;
                if (!out_segment(st, s, s->a)) return false;
                tg__node nd = ((const tg__node*)st->pts.data)[s->p0];
                if (!out_node(st, &nd, s->face) || !close_polyline(st, first, 1)) return false;
                continue;
            }
            /* pass 0: only from an end of a curve (a crossing with one segment, or none) */
            uint32_t v0 = s->a;
            bool a_end = v0 == TG_NONE || start[v0 + 1] - start[v0] == 1;
            bool b_end = s->b == TG_NONE || start[s->b + 1] - start[s->b] == 1;
            if (pass == 0 && !a_end && !b_end) continue;
            if (pass == 0 && !a_end) v0 = s->b;
            uint32_t sg = (uint32_t)s0, cur = v0;
            if (cur != TG_NONE && !out_crossing(st, cur, s->face)) return false;
            bool closed = false;
            while (sg != TG_NONE) {
                used[sg] = 1;
                if (!out_segment(st, &segs[sg], cur)) return false;
                cur = segs[sg].a == cur ? segs[sg].b : segs[sg].a;
                sg = TG_NONE;
                if (cur == TG_NONE) break;
                if (cur == v0) {
                    closed = true;
                    break;
                }
                for (uint32_t q = start[cur]; q < start[cur + 1]; ++q)
                    if (!used[adj[q]]) {
                        sg = adj[q];
                        break;
                    }
            }
            if (!close_polyline(st, first, closed)) return false;
        }
    }
    return true;
}

/* ---- the result ---- */

struct tg_isolines {
    tg_allocator allocator;
    size_t level_count, polyline_count, point_count;
    double* levels;
    size_t *level_start, *polyline_start;
    uint8_t* closed;
    tg_surface_point* points;
    uint32_t* faces;
    double* xyz;
};

/* Empties a result: its arrays freed, no levels. */
static void isolines_clear(tg_isolines* r)
{
    tg_allocator a = r->allocator;
    void* arrays[] = {r->levels, r->level_start, r->polyline_start, r->closed, r->points, r->faces, r->xyz};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; ++i) tg__free(&a, arrays[i]);
    memset(r, 0, sizeof *r);
    r->allocator = a;
}

tg_status tg_isolines_create(const tg_allocator* allocator, tg_isolines** out_isolines)
{
    if (!out_isolines) return TG_ERR_INVALID_ARGUMENT;
    *out_isolines = NULL;
    tg_isolines* r = tg__alloc(allocator, sizeof *r);
    if (!r) return TG_ERR_OUT_OF_MEMORY;
    memset(r, 0, sizeof *r);
    if (allocator) r->allocator = *allocator;
    *out_isolines = r;
    return TG_OK;
}

void tg_isolines_destroy(tg_isolines* r)
{
    if (!r) return;
    isolines_clear(r);
    tg_allocator a = r->allocator;
    tg__free(&a, r);
}

void tg_isolines_get_view(const tg_isolines* r, tg_isolines_view* out)
{
    memset(out, 0, sizeof *out);
    if (!r) return;
    out->level_count = r->level_count, out->levels = r->levels, out->level_start = r->level_start;
    out->polyline_count = r->polyline_count, out->polyline_start = r->polyline_start;
    out->polyline_closed = r->closed, out->point_count = r->point_count, out->points = r->points;
    out->faces = r->faces, out->xyz = r->xyz;
}

/* The result into r (emptied first), its arrays made with r's allocator. */
static bool make_result(const iso_state* st, tg_isolines* r, const double* levels, size_t nl,
                        const size_t* level_start)
{
    const tg_geodesic* g = st->g;
    isolines_clear(r);
    const tg_allocator* a = &r->allocator;
    size_t np = st->out_nodes.count, npl = st->out_closed.count;
    r->level_count = nl, r->polyline_count = npl, r->point_count = np;
    r->levels = tg__alloc_array(a, nl, sizeof(double));
    r->level_start = tg__alloc_array(a, nl + 1, sizeof(size_t));
    r->polyline_start = tg__alloc_array(a, npl + 1, sizeof(size_t));
    r->closed = tg__alloc_array(a, npl ? npl : 1, 1);
    r->points = tg__alloc_array(a, np ? np : 1, sizeof(tg_surface_point));
    r->faces = tg__alloc_array(a, np ? np : 1, sizeof(uint32_t));
    r->xyz = tg__alloc_array(a, np ? 3 * np : 1, sizeof(double));
    if (!r->levels || !r->level_start || !r->polyline_start || !r->closed || !r->points || !r->faces || !r->xyz) {
        isolines_clear(r);
        return false;
    }
    memcpy(r->levels, levels, nl * sizeof(double));
    memcpy(r->level_start, level_start, (nl + 1) * sizeof(size_t));
    r->polyline_start[0] = 0;
    if (npl) memcpy(r->polyline_start + 1, st->out_pstart.data, npl * sizeof(size_t));
    if (npl) memcpy(r->closed, st->out_closed.data, npl);
    const tg__node* nodes = st->out_nodes.data;
    const uint32_t* faces = st->out_faces.data;
    for (size_t i = 0; i < np; ++i) {
        r->points[i] = tg__surface_out(g, &nodes[i]);
        r->faces[i] = tg__face_out(g, faces[i]);
        tg_surface_point_position(g->mesh, &r->points[i], r->xyz + 3 * i);
    }
    return true;
}

static void state_free(iso_state* st)
{
    const tg_allocator* a = st->alloc;
    tg__free(a, st->rec_start);
    tg__free(a, st->rec_order);
    tg__free(a, st->edge_first);
    tg__free(a, st->edge_count);
    tg__free(a, st->vertex_node);
    tg__vec* vs[] = {&st->vertices_done, &st->edges_done, &st->pieces,    &st->pieces2,    &st->spans,
                     &st->cross,         &st->segs,       &st->pts,       &st->out_nodes,  &st->out_faces,
                     &st->out_pstart,    &st->out_closed, &st->adj_start, &st->adj,        &st->used};
    for (size_t i = 0; i < sizeof vs / sizeof vs[0]; ++i) tg__vec_free(a, vs[i]);
}

/* The recorded windows grouped by face (a counting sort: the order within a face is the
 * recording's, so the result is deterministic). */
static bool group_records(iso_state* st, const tg__field_scratch* fs)
{
    const tg_geodesic* g = st->g;
    size_t nr = fs->rec.count, nf = g->face_count;
    st->fs = fs;
    st->rec = fs->rec.data;
    st->rec_start = tg__calloc_array(st->alloc, nf + 2, sizeof(size_t));
    st->rec_order = tg__alloc_array(st->alloc, nr ? nr : 1, sizeof(uint32_t));
    if (!st->rec_start || !st->rec_order || nr > (size_t)UINT32_MAX) return false;
    for (size_t i = 0; i < nr; ++i) st->rec_start[st->rec[i].h / 3 + 2]++;
    for (size_t f = 0; f < nf; ++f) st->rec_start[f + 2] += st->rec_start[f + 1];
    for (size_t i = 0; i < nr; ++i) st->rec_order[st->rec_start[st->rec[i].h / 3 + 1]++] = (uint32_t)i;
    return true;
}

static void vec_init(iso_state* st)
{
    st->edges_done.elem = st->vertices_done.elem = sizeof(uint32_t);
    st->pieces.elem = st->pieces2.elem = sizeof(piece);
    st->spans.elem = 2 * sizeof(double);
    st->cross.elem = sizeof(crossing);
    st->segs.elem = sizeof(segment);
    st->pts.elem = st->out_nodes.elem = sizeof(tg__node);
    st->out_faces.elem = sizeof(uint32_t);
    st->out_pstart.elem = sizeof(size_t);
    st->out_closed.elem = 1;
    st->adj_start.elem = st->adj.elem = st->used.elem = sizeof(uint32_t);
}

/* The run from the sources and segments (the solver's form, field.h; segment_count pairs), then
 * every level traced and chained (solver frame: levels times scale). */
static tg_status isolines_of(const tg_geodesic* g, tg__field_scratch* fs, const tg_surface_point* sources,
                             size_t source_count, const tg_surface_point* segments, size_t segment_count,
                             const double* levels, size_t nl, const tg_field_options* options,
                             const tg_allocator* a, tg_isolines* out, double* out_vertex_distance,
                             tg_field_stats* out_stats)
{
    double* sorted = tg__alloc_array(a, nl, sizeof(double));
    size_t* level_start = tg__alloc_array(a, nl + 1, sizeof(size_t));
    iso_state st;
    memset(&st, 0, sizeof st);
    st.g = g, st.alloc = a;
    vec_init(&st);
    tg_status status = sorted && level_start ? TG_OK : TG_ERR_OUT_OF_MEMORY;
    tg__field_run run;
    double limit = tg__field_limit(g, options);
    if (status == TG_OK) {
        for (size_t i = 0; i < nl; ++i) sorted[i] = levels[i] * g->scale;
        qsort(sorted, nl, sizeof *sorted, tg__cmp_double);
        bool progress = options && options->progress;
        tg__field_query q = {.sources = sources, .source_count = source_count, .segments = segments,
                             .segment_count = segment_count, .max_distance = limit,
                             .progress = progress ? tg__field_report_single : NULL, .progress_user = (void*)options,
                             .record_levels = sorted, .record_level_count = nl,
                             .threads = tg__field_threads(options)};
        status = tg__field_execute(fs, &q, &run);
    }
    if (status == TG_OK) {
        st.dist = run.vertex_dist;
        size_t nh = 3 * (size_t)g->face_count;
        st.edge_first = tg__alloc_array(a, nh ? nh : 1, sizeof(uint32_t));
        st.edge_count = tg__alloc_array(a, nh ? nh : 1, sizeof(uint32_t));
        st.vertex_node = tg__alloc_array(a, g->vertex_count ? g->vertex_count : 1, sizeof(uint32_t));
        if (!st.edge_first || !st.edge_count || !st.vertex_node || !group_records(&st, fs))
            status = TG_ERR_OUT_OF_MEMORY;
        for (size_t h = 0; status == TG_OK && h < nh; ++h) st.edge_first[h] = TG_NONE;
        for (size_t v = 0; status == TG_OK && v < g->vertex_count; ++v) st.vertex_node[v] = TG_NONE;
    }
    st.options = options, st.level_count = nl;
    st.next_report_s = tg__seconds() + TG__PROGRESS_PERIOD_S;
    for (size_t li = 0; status == TG_OK && li < nl; ++li, st.levels_done = li) {
        level_start[li] = st.out_closed.count;
        double L = levels[li] * g->scale;
        if (!(L <= limit)) continue;
        if (!trace_level(&st, L) || !chain_level(&st)) status = st.cancelled ? TG_ERR_CANCELLED : TG_ERR_OUT_OF_MEMORY;
    }
    if (status == TG_OK) {
        level_start[nl] = st.out_closed.count;
        if (!make_result(&st, out, levels, nl, level_start)) status = TG_ERR_OUT_OF_MEMORY;
    }
    if (status == TG_OK) {
        if (out_vertex_distance) tg__field_copy_out(&run, out_vertex_distance);
        if (out_stats) *out_stats = run.stats;
    }
    state_free(&st);
    tg__free(a, sorted);
    tg__free(a, level_start);
    return status;
}

tg_status tg_geodesic_curve_isolines(const tg_geodesic* g, tg_geodesic_workspace* ws,
                                     const tg_surface_point* sources, size_t source_count,
                                     const tg_surface_segment* segments, size_t segment_count, const double* levels,
                                     size_t level_count, const tg_field_options* options, tg_isolines* isolines,
                                     double* out_vertex_distance, tg_field_stats* out_stats)
{
    if (!isolines) return TG_ERR_INVALID_ARGUMENT;
    tg_status st = levels && level_count && (segments || !segment_count) ? TG_OK : TG_ERR_INVALID_ARGUMENT;
    for (size_t i = 0; st == TG_OK && i < level_count; ++i)
        if (!(levels[i] >= 0.0 && levels[i] < INFINITY)) st = TG_ERR_INVALID_ARGUMENT;
    if (st == TG_OK) st = tg__field_check(g, sources, source_count, options);
    tg_geodesic_workspace* own = NULL;
    if (st == TG_OK) st = tg__workspace_acquire(g, options ? options->allocator : NULL, &ws, &own);
    if (st == TG_OK) {
        const tg_allocator* a = options && options->allocator ? options->allocator : &g->allocator;
        tg__field_points_ws in;
        st = tg__field_points_in_workspace(ws, sources, source_count, segments, segment_count, NULL, 0, &in);
        if (st == TG_OK)
            st = isolines_of(g, &ws->field, in.sources, source_count, in.segments, segment_count, levels, level_count,
                             options, a, isolines, out_vertex_distance, out_stats);
        tg__workspace_release(own);
    }
    if (st != TG_OK) isolines_clear(isolines);
    return st;
}

tg_status tg_geodesic_isolines(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* sources,
                               size_t source_count, const double* levels, size_t level_count,
                               const tg_field_options* options, tg_isolines* isolines,
                               double* out_vertex_distance, tg_field_stats* out_stats)
{
    return tg_geodesic_curve_isolines(g, ws, sources, source_count, NULL, 0, levels, level_count, options, isolines,
                                      out_vertex_distance, out_stats);
}
