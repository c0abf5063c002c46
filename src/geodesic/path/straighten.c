/* straighten.c - the fast shortening method (TG_PATH_STRAIGHTEN): funnel straightening of
 * triangle strips, with vertex passages re-routed through the fan on their sharper side, until
 * every passage is locally shortest.
 * Based on: Xin & Wang, "Efficiently determining a locally exact shortest path on polyhedral
 *   surfaces", Computer-Aided Design 39 (2007), §3-4 (alternate: shortest path inside the current
 *   face sequence by a funnel; where it passes a vertex at an angle below pi, add that side's
 *   faces to the sequence; the length decreases strictly, so the loop ends at a locally exact
 *   geodesic); seed 002 §5 and Figure 5.1 (the two fans at a path vertex); Mitchell, Mount &
 *   Papadimitriou (1987), Lemma 3.4 (the vertex condition: both angles >= pi). */
#include "geodesic/path/stages.h"

#include <string.h>

typedef tg__straighten_decision decision;

/* One straightening: the solver, the allocator and the scratch of the stage and of the funnel. */
typedef struct straightener {
    const tg_geodesic* g;
    const tg_allocator* a;
    tg__straighten_scratch* st;
    tg__sleeve_scratch* ss;
} straightener;

static uint32_t sleeve_last_face(const tg_geodesic* g, const tg__sleeve* s, const uint32_t* portals)
{
    if (s->portal_end == s->portal_begin) return s->face0;
    return g->opp[portals[s->portal_end - 1]] / 3;
}

/* Decides, for every interior vertex passage, whether and how to re-route it. Returns the count. */
static size_t decide_all(const straightener* sr, size_t np, double limit, bool single, decision* dec)
{
    const tg_geodesic* g = sr->g;
    const tg__node* piv = sr->st->now.pivots.data;
    const tg__sleeve* slv = sr->st->now.sleeves.data;
    const uint32_t* portals = sr->st->now.portals.data;
    size_t count = 0;
    for (size_t i = 0; i < np; ++i) dec[i].side = -1;
    for (size_t i = 1; i + 1 < np; ++i) {
        if (piv[i].kind != TG__NODE_VERTEX) continue;
        /* both sleeves unchanged since the last check, which found nothing to do here (or its
         * re-routing was rejected, which would happen again) */
        if (!slv[i - 1].fresh && !slv[i].fresh) continue;
        const tg__sleeve *in = &slv[i - 1], *out = &slv[i];
        uint32_t f_in = sleeve_last_face(g, in, portals), f_out = out->face0;
        uint32_t fi, fo;
        int side;
        double a = tg__vertex_best_side(g, piv[i].id, &in->near_b, f_in, in->ang_b, &out->near_a, f_out,
                                             out->ang_a, &fi, &fo, &side);
        if (a < 0.0 || !(a < limit)) continue;
        if ((fi != f_in && in->portal_end != in->portal_begin) || (fo != f_out && out->portal_end != out->portal_begin))
            continue;
        dec[i].side = side, dec[i].f_in = fi, dec[i].f_out = fo;
        count++;
    }
    /* after a rejected run: passages one at a time, never two adjacent ones */
    for (size_t i = 1; single && i + 2 < np; ++i) {
        if (dec[i].side >= 0 && dec[i + 1].side >= 0) {
            dec[i + 1].side = -1;
            count--;
        }
    }
    /* a portal-less sleeve between two re-routed passages can take only one face */
    for (size_t i = 1; i + 2 < np; ++i) {
        if (dec[i].side >= 0 && dec[i + 1].side >= 0 && slv[i].portal_end == slv[i].portal_begin &&
            dec[i].f_out != dec[i + 1].f_in) {
            dec[i + 1].side = -1;
            count--;
        }
    }
    return count;
}

/* Appends a portal to a sleeve, cancelling it against the previous one when it crosses the same
 * edge back (a fold f -> f' -> f: the segment between two passages runs along an edge, and the
 * fans on both sides cross that edge). The reduced face sequence still holds the old path, which
 * lies on the edge, and a funnel needs a sleeve without folds. */
static void push_portal(const tg_geodesic* g, uint32_t* mp, size_t* m, uint32_t p)
{
    if (*m > 0 && g->opp[mp[*m - 1]] == p)
        (*m)--;
    else
        mp[(*m)++] = p;
}

/* Writes to the merged portals: sleeves i..j-1 of the current state joined by the fans of the re-routed
 * pivots i+1..j-1. Returns false when a fan walk fails (the run is then left unchanged). */
static bool build_run(const straightener* sr, size_t i, size_t j, const decision* dec, uint32_t* out_face0,
                      size_t* out_m, tg_status* st)
{
    const tg_geodesic* g = sr->g;
    const tg__node* piv = sr->st->now.pivots.data;
    const tg__sleeve* slv = sr->st->now.sleeves.data;
    const uint32_t* portals = sr->st->now.portals.data;
    size_t m = 0;
    *st = TG_OK;
    *out_face0 = slv[i].face0;
    if (slv[i].portal_end == slv[i].portal_begin) *out_face0 = dec[i + 1].f_in;
    for (size_t r = i; r < j; ++r) {
        const tg__sleeve* s = &slv[r];
        size_t k = s->portal_end - s->portal_begin;
        /* room for this sleeve's portals and the fan after it (at most one per corner of v) */
        size_t fan_cap = 0;
        if (r + 1 < j) {
            uint32_t v = piv[r + 1].id;
            fan_cap = (size_t)(g->corner_start[v + 1] - g->corner_start[v]) + 2;
        }
        if (!tg__vec_fit(sr->a, &sr->st->merged, m + k + fan_cap)) {
            *st = TG_ERR_OUT_OF_MEMORY;
            return false;
        }
        uint32_t* mp = sr->st->merged.data;
        if (r > i && k > 0 && s->face0 != dec[r].f_out) return false;
        for (size_t q = 0; q < k; ++q) push_portal(g, mp, &m, portals[s->portal_begin + q]);
        if (r + 1 == j) break;
        const decision* d = &dec[r + 1];
        uint32_t f_last = m ? g->opp[mp[m - 1]] / 3 : *out_face0;
        if (f_last != d->f_in) return false;
        /* the fan is written past the end, then pushed one portal at a time */
        double a_in = d->f_in == sleeve_last_face(g, s, portals) ? s->ang_b : -1.0;
        double a_out = d->f_out == slv[r + 1].face0 ? slv[r + 1].ang_a : -1.0;
        size_t n = tg__fan_portals(g, piv[r + 1].id, d->f_in, &s->near_b, a_in, d->f_out, &slv[r + 1].near_a,
                                        a_out, d->side, mp + m, fan_cap);
        if (n == SIZE_MAX) return false;
        size_t at = m;
        for (size_t q = 0; q < n; ++q) push_portal(g, mp, &m, mp[at + q]);
    }
    *out_m = m;
    return true;
}

/* Appends pivot i+1 and sleeve i of the current state to the next one. */
static bool copy_step(const straightener* sr, size_t i)
{
    tg__pivot_path *now = &sr->st->now, *next = &sr->st->next;
    const tg__sleeve* s = (const tg__sleeve*)now->sleeves.data + i;
    size_t k = s->portal_end - s->portal_begin, np = next->pivots.count, nq = next->portals.count;
    if (!tg__vec_fit(sr->a, &next->pivots, np + 1) || !tg__vec_fit(sr->a, &next->sleeves, np + 1) ||
        !tg__vec_fit(sr->a, &next->portals, nq + k))
        return false;
    tg__sleeve* d = (tg__sleeve*)next->sleeves.data + (np - 1);
    *d = *s;
    d->fresh = 0;
    if (k) /* no portals: the arrays may still be NULL */
        memcpy((uint32_t*)next->portals.data + nq, (const uint32_t*)now->portals.data + s->portal_begin,
               k * sizeof(uint32_t));
    d->portal_begin = (uint32_t)nq;
    d->portal_end = (uint32_t)(nq + k);
    next->portals.count = nq + k;
    ((tg__node*)next->pivots.data)[np] = ((const tg__node*)now->pivots.data)[i + 1];
    next->pivots.count = np + 1;
    next->sleeves.count = np;
    return true;
}

/* One sweep from `now` into `next`: re-routes the decided passages run by run. *accepted counts
 * the passages re-routed; *out_retry asks for a sweep of single passages after a rejected run. */
static tg_status sweep(const straightener* sr, const decision* dec, size_t* accepted, bool* out_retry)
{
    tg__pivot_path *now = &sr->st->now, *next = &sr->st->next;
    size_t np = now->pivots.count;
    *out_retry = false;
    next->pivots.count = next->sleeves.count = next->portals.count = 0;
    if (!tg__vec_fit(sr->a, &next->pivots, 1) || !tg__vec_fit(sr->a, &next->sleeves, 1)) return TG_ERR_OUT_OF_MEMORY;
    ((tg__node*)next->pivots.data)[0] = ((const tg__node*)now->pivots.data)[0];
    next->pivots.count = 1;
    *accepted = 0;
    size_t i = 0;
    while (i + 1 < np) {
        size_t j = i + 1;
        while (j + 1 < np && dec[j].side >= 0) j++;
        if (j == i + 1) {
            if (!copy_step(sr, i)) return TG_ERR_OUT_OF_MEMORY;
            i = j;
            continue;
        }
        uint32_t face0;
        size_t m = 0;
        tg_status st;
        bool ok = build_run(sr, i, j, dec, &face0, &m, &st);
        if (st != TG_OK) return st;
        size_t save_np = next->pivots.count, save_nq = next->portals.count;
        if (ok) {
            const tg__node* piv = now->pivots.data;
            const tg__sleeve* slv = now->sleeves.data;
            double old_len = 0.0, new_len = 0.0;
            for (size_t r = i; r < j; ++r) old_len += slv[r].len;
            st = tg__funnel(sr->g, sr->a, sr->ss, &piv[i], &piv[j], face0, sr->st->merged.data, m, next);
            if (st == TG_ERR_OUT_OF_MEMORY) return st;
            const tg__sleeve* ns = next->sleeves.data;
            for (size_t r = save_np - 1; st == TG_OK && r + 1 < next->pivots.count; ++r) new_len += ns[r].len;
            /* the old path lies in the merged sleeve, so the funnel's path cannot be longer; a
             * longer one would be a numerical accident in a degenerate strip: keep the old run.
             * 1e-12 relative is far above the rounding of two unfoldings of the same strip. */
            ok = st == TG_OK && new_len <= old_len * (1.0 + 1e-12);
        }
        if (ok) {
            *accepted += j - i - 1;
        } else {
            /* keep the old run; when it joined several passages, retry them one at a time in
             * the next sweep (their sleeves stay fresh so that they are decided again) */
            next->pivots.count = save_np, next->sleeves.count = save_np - 1, next->portals.count = save_nq;
            for (size_t r = i; r < j; ++r) {
                if (!copy_step(sr, r)) return TG_ERR_OUT_OF_MEMORY;
                if (j - i > 2) ((tg__sleeve*)next->sleeves.data)[next->pivots.count - 2].fresh = 1;
            }
            if (j - i > 2) *out_retry = true; /* a single passage that cannot be re-routed stays (the
                                                  caller's certificate then tells it is not straight) */
        }
        i = j;
    }
    return TG_OK;
}

/* Expands the pivot path `now` into the route's nodes, with every edge crossing. */
static tg_status expand(const straightener* sr, tg__route* route)
{
    const tg__pivot_path* now = &sr->st->now;
    size_t np = now->pivots.count;
    const tg__sleeve* slv = now->sleeves.data;
    size_t total = 1;
    for (size_t i = 0; i + 1 < np; ++i) total += slv[i].portal_end - slv[i].portal_begin + 1;
    if (!tg__route_fit(sr->a, route, total)) return TG_ERR_OUT_OF_MEMORY;
    const tg__node* piv = now->pivots.data;
    const uint32_t* portals = now->portals.data;
    tg__node* nodes = tg__route_nodes(route);
    uint32_t* faces = tg__route_faces(route);
    size_t n = 0;
    nodes[n++] = piv[0];
    for (size_t i = 0; i + 1 < np; ++i) {
        const tg__sleeve* s = &slv[i];
        n += tg__sleeve_crossings(sr->g, sr->a, sr->ss, &piv[i], &piv[i + 1], s->face0, portals + s->portal_begin,
                                  s->portal_end - s->portal_begin, nodes + n, faces + n - 1);
    }
    route->nodes.count = n;
    route->faces.count = n - 1;
    return TG_OK;
}

/* The crossing of edge node x with the straight line from p (in face fa) to n (in face fb), in the
 * unfolding of the two faces about x's edge, measured from the end `from_a` (1: the halfedge's
 * start) so that the result is precise when small. Returns false when p or n is not in its face,
 * the faces are not the two sides of the edge, or the line misses the edge's interior. */
static bool local_crossing(const tg_geodesic* g, const tg__node* x, const tg__node* p, uint32_t fa, const tg__node* n,
                           uint32_t fb, int from_a, double* out)
{
    uint32_t h = x->id;
    uint32_t va = g->tri[h], vb = g->tri[tg_halfedge_next(h)];
    uint32_t o = from_a ? va : vb, other = from_a ? vb : va;
    int ka = tg__corner_of(g, fa, o), kb = tg__corner_of(g, fb, o);
    tg_vec3 dp, dn;
    if (ka < 0 || kb < 0 || !tg__node_offset(g, p, fa, ka, &dp) || !tg__node_offset(g, n, fb, kb, &dn)) return false;
    tg_vec3 e = tg_v3_sub(tg__gpos(g, other), tg__gpos(g, o));
    double el = tg_v3_len(e);
    if (!(el > 0.0)) return false;
    tg_vec3 u = tg_v3_scale(e, 1.0 / el);
    double px = tg_v3_dot(dp, u), py = tg_v3_len(tg_v3_cross(dp, u));
    double nx = tg_v3_dot(dn, u), ny = -tg_v3_len(tg_v3_cross(dn, u));
    double den = py - ny;
    if (!(den > 0.0)) return false;
    double x0 = px + (nx - px) * (py / den);
    double lam = x0 / el;
    if (!(lam > 0.0 && lam < 1.0)) return false;
    *out = lam;
    return true;
}

/* Local refinement of the crossings: each is moved onto the straight line between its neighbours
 * in the unfolding of its two faces (the seed's two-triangle minimum, §2, in closed form), in a
 * frame at its nearer vertex. Crossings computed in a long strip's unfolding carry an absolute
 * rounding error of the strip's size, which is a large angle across a very short segment (a path
 * through slivers); a few Gauss-Seidel sweeps remove that noise, each step never lengthening the
 * path. Vertex passages and endpoints stay fixed. */
#define POLISH_SWEEPS 4

static void polish(const tg_geodesic* g, tg__node* nodes, const uint32_t* faces, size_t n)
{
    for (int sweep = 0; sweep < POLISH_SWEEPS; ++sweep) {
        for (size_t i = 1; i + 1 < n; ++i) {
            tg__node* x = &nodes[i];
            if (x->kind != TG__NODE_EDGE || faces[i - 1] == faces[i]) continue;
            double ta, tb;
            if (!local_crossing(g, x, &nodes[i - 1], faces[i - 1], &nodes[i + 1], faces[i], 1, &ta) ||
                !local_crossing(g, x, &nodes[i - 1], faces[i - 1], &nodes[i + 1], faces[i], 0, &tb))
                continue;
            /* keep the one measured from the nearer end exact; the other is its complement */
            if (ta <= tb)
                x->t = ta, x->s = 1.0 - ta;
            else
                x->s = tb, x->t = 1.0 - tb;
        }
    }
}

tg_status tg__straighten(const tg_geodesic* g, const tg_allocator* a, tg__straighten_scratch* st,
                         tg__sleeve_scratch* ss, tg__route* route, uint32_t max_sweeps, double angle_tol,
                         const tg__path_progress* progress, tg__shorten_result* out)
{
    straightener sr = {g, a, st, ss};
    size_t count = route->nodes.count;
    memset(out, 0, sizeof *out);
    tg__pivot_path* now = &st->now;
    if (!tg__vec_fit(a, &now->pivots, count) || !tg__vec_fit(a, &now->sleeves, count) || !tg__vec_fit(a, &now->portals, 1))
        return TG_ERR_OUT_OF_MEMORY;
    const tg__node* nodes = tg__route_nodes(route);
    const uint32_t* faces = tg__route_faces(route);
    tg__node* piv = now->pivots.data;
    tg__sleeve* slv = now->sleeves.data;
    for (size_t i = 0; i < count; ++i) {
        piv[i] = nodes[i];
        if (i + 1 == count) break;
        slv[i].face0 = faces[i];
        slv[i].portal_begin = slv[i].portal_end = 0;
        slv[i].len = tg__node_dist(g, &nodes[i], &nodes[i + 1], faces[i]);
        slv[i].near_a = nodes[i + 1];
        slv[i].near_b = nodes[i];
        slv[i].ang_a = slv[i].ang_b = -1.0;
        slv[i].fresh = 1;
    }
    now->pivots.count = count, now->sleeves.count = count - 1, now->portals.count = 0;
    double limit = TG__PI - angle_tol;
    bool single = false;
    for (;;) {
        size_t np = now->pivots.count;
        if (!tg__vec_fit(a, &st->decisions, np)) return TG_ERR_OUT_OF_MEMORY;
        decision* dec = st->decisions.data;
        if (decide_all(&sr, np, limit, single, dec) == 0) break;
        if (out->iterations >= max_sweeps) {
            out->capped = true;
            break;
        }
        size_t accepted = 0;
        bool retry = false;
        tg_status s = sweep(&sr, dec, &accepted, &retry);
        if (s != TG_OK) return s;
        out->iterations++;
        if (tg__shorten_cancelled(progress, out->iterations)) return TG_ERR_CANCELLED;
        tg__pivot_path t = st->now;
        st->now = st->next, st->next = t;
        if (retry) single = true;
        if (accepted == 0 && !retry) {
            out->capped = true; /* every re-routing was rejected: stop rather than repeat it */
            break;
        }
    }
    tg_status s = expand(&sr, route);
    if (s == TG_OK) polish(g, tg__route_nodes(route), tg__route_faces(route), route->nodes.count);
    return s;
}
