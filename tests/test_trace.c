/* test_trace.c - geodesic tracing (tg_geodesic_trace, tg_geodesic_trace_batch): known answers on
 * flat meshes (the straight line), on a prism (helices of known length and pitch) and on a cube
 * (geodesics unfolded by hand, through a corner as the straightest geodesic), zero-area faces
 * (slits, caps), a non-manifold book, angles, scaling, the step and stall bounds, errors; on
 * corpus meshes: a trace followed by the exact path back is never longer, a trace from a vertex
 * along its exact path's first segment ends at the path's other end, and the batch equals single
 * calls bit for bit on any number of threads. Every polyline is checked against the mesh. */
#include "tg_test.h"
#include "tg_test_geodesic.h"
#include "tg_test_path.h"

#include <float.h>

/* ---- the contract of every trace ---- */

/* Every point valid and at its xyz, both ends of each segment in the segment's face, the walked
 * length the sum of the segments (to 1e-12), the end the last point, a unit end direction, the
 * branch points non-manifold crossings. Returns the number of problems (the first in why). */
static int trace_problems(const tg_mesh* m, const tg_trace_view* v, const tg_surface_point* start, char* why, size_t size)
{
    int bad = 0;
#define BAD_(...)                                           \
    do {                                                    \
        if (bad++ == 0) snprintf(why, size, __VA_ARGS__);   \
    } while (0)
    why[0] = '\0';
    size_t n = v->point_count;
    if (n < 2) {
        BAD_("%zu points", n);
        return bad;
    }
    double centre[3], diag = tg_test_mesh_box(m, centre), mag = 0.0;
    const tg_mesh_report* rep = tg_mesh_get_report(m);
    for (int k = 0; k < 3; ++k) mag = fmax(mag, fmax(fabs(rep->bbox_min[k]), fabs(rep->bbox_max[k])));
    double pos_tol = 16.0 * DBL_EPSILON * mag + 1e-13 * diag;
    double sum = tg_test_polyline_problems(m, n, v->points, v->xyz, v->faces, pos_tol, &bad, why, size);
    double s0[3];
    tg_test_point_position(m, start, s0);
    if (tg_test_dist3(s0, v->xyz) > pos_tol) BAD_("starts %.3g from the start point", tg_test_dist3(s0, v->xyz));
    if (!(fabs(sum - v->end.length) <= 1e-12 * sum + 4.0 * (double)n * DBL_EPSILON * mag))
        BAD_("walked %.17g, its segments sum to %.17g", v->end.length, sum);
    if (memcmp(&v->end.point, &v->points[n - 1], sizeof v->end.point) != 0 ||
        memcmp(v->end.xyz, v->xyz + 3 * (n - 1), sizeof v->end.xyz) != 0)
        BAD_("the end is not the last point");
    if (v->end.face != v->faces[n - 2]) BAD_("end face %u, last segment's %u", v->end.face, v->faces[n - 2]);
    double dl = sqrt(v->end.direction[0] * v->end.direction[0] + v->end.direction[1] * v->end.direction[1] +
                     v->end.direction[2] * v->end.direction[2]);
    if (!(fabs(dl - 1.0) <= 1e-12)) BAD_("end direction of length %.17g", dl);
    if (v->branch_count != v->end.branches) BAD_("%zu branch points, %u branches", v->branch_count, v->end.branches);
    for (size_t i = 0; i < v->branch_count; ++i)
        if (v->branch_points[i] == 0 || v->branch_points[i] + 1 >= n || v->points[v->branch_points[i]].kind != TG_SURFACE_EDGE)
            BAD_("branch point %zu (%zu) is not a crossing", i, v->branch_points[i]);
#undef BAD_
    return bad;
}

static int check_trace(const char* what, const tg_mesh* m, const tg_trace_view* v, const tg_surface_point* start)
{
    char why[256];
    int bad = trace_problems(m, v, start, why, sizeof why);
    CHECK_MSG(bad == 0, "%s: %d problems, first: %s", what, bad, why);
    return bad;
}

static tg_trace_direction vec(double x, double y, double z)
{
    tg_trace_direction d = {TG_TRACE_VECTOR, {x, y, z}, 0.0};
    return d;
}
static tg_trace_direction ang(double a)
{
    tg_trace_direction d = {TG_TRACE_ANGLE, {0.0, 0.0, 0.0}, a};
    return d;
}

/* Traces into t and returns its view (a failed check when the call fails). */
static tg_trace_view trace_view(const tg_geodesic* g, tg_trace* t, tg_surface_point s, tg_trace_direction d, double len)
{
    tg_trace_view v;
    CHECK_STATUS(tg_geodesic_trace(g, &s, &d, len, NULL, t), TG_OK);
    tg_trace_get_view(t, &v);
    return v;
}

/* ---- flat: the straight line ---- */

static void test_flat(void)
{
    tg_mesh* m = flat_square(12, 5);
    ctx c = open_ctx_for(m);
    tg_trace* t = NULL;
    CHECK_STATUS(tg_trace_create(NULL, &t), TG_OK);
    tg_rng r = {77};
    int checked = 0, worst_line = 0;
    double worst = 0.0;
    for (int i = 0; i < 400; ++i) {
        uint32_t f;
        tg_surface_point s = tg_test_random_surface_point(&r, m, &f);
        double p0[3], a = tg_rng_range(&r, 0.0, 2.0 * TG_PI_);
        tg_surface_point_position(m, &s, p0);
        double dx = cos(a), dy = sin(a);
        /* a length that ends inside [0.01, 0.99]^2 */
        double lim = INFINITY;
        for (int k = 0; k < 2; ++k) {
            double d = k ? dy : dx, p = p0[k];
            if (d > 1e-9) lim = fmin(lim, (0.99 - p) / d);
            if (d < -1e-9) lim = fmin(lim, (0.01 - p) / d);
        }
        if (!(lim > 0.05)) continue;
        double len = tg_rng_range(&r, 0.0, lim);
        tg_trace_view v = trace_view(c.geo, t, s, vec(3 * dx, 3 * dy, 0.0), len);
        if (check_trace("flat", m, &v, &s)) break;
        CHECK_EQ_INT(v.end.status, TG_TRACE_COMPLETE);
        CHECK(v.end.length == len);
        double ex = p0[0] + len * dx, ey = p0[1] + len * dy;
        double err = hypot(v.end.xyz[0] - ex, v.end.xyz[1] - ey) + fabs(v.end.xyz[2]);
        if (err > worst) worst = err;
        CHECK_MSG(err <= 1e-12, "flat trace %d: end (%.17g, %.17g), the line's (%.17g, %.17g)", i, v.end.xyz[0],
                  v.end.xyz[1], ex, ey);
        CHECK_NEAR(v.end.direction[0], dx, 1e-12);
        CHECK_NEAR(v.end.direction[1], dy, 1e-12);
        /* every point of the polyline is on the line */
        for (size_t k = 0; k < v.point_count; ++k) {
            const double* p = v.xyz + 3 * k;
            double off = fabs((p[0] - p0[0]) * dy - (p[1] - p0[1]) * dx);
            if (off > 1e-12) worst_line++;
        }
        /* the exact path back is the same segment: its length is the trace's */
        tg_surface_point e = v.end.point;
        CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &s, &e, NULL, c.path), TG_OK);
        tg_path_view pv;
        tg_path_get_view(c.path, &pv);
        CHECK_MSG(fabs(pv.length - len) <= 1e-12, "flat trace %d: length %.17g, the exact path back %.17g", i, len,
                  pv.length);
        checked++;
    }
    CHECK_EQ_INT(worst_line, 0);
    CHECK(checked > 300);
    printf("flat: %d traces, worst end error %.3g\n", checked, worst);

    /* leaving the square: stops on the boundary, having walked to it */
    tg_surface_point s = locate(m, 0.3, 0.4, 0.0);
    tg_trace_view v = trace_view(c.geo, t, s, vec(1, 0, 0), 5.0);
    check_trace("flat to the boundary", m, &v, &s);
    CHECK_EQ_INT(v.end.status, TG_TRACE_BOUNDARY);
    CHECK_NEAR(v.end.length, 0.7, 1e-12);
    CHECK_NEAR(v.end.xyz[0], 1.0, 1e-12);
    CHECK_NEAR(v.end.xyz[1], 0.4, 1e-12);
    CHECK_EQ_INT(v.end.point.kind, TG_SURFACE_EDGE);
    /* length 0: the start twice */
    v = trace_view(c.geo, t, s, vec(1, 0, 0), 0.0);
    CHECK_EQ_INT(v.point_count, 2);
    CHECK_EQ_INT(v.end.status, TG_TRACE_COMPLETE);
    CHECK(v.end.length == 0.0 && v.xyz[0] == v.xyz[3] && v.xyz[1] == v.xyz[4]);
    /* a vector with a component along the normal is projected */
    v = trace_view(c.geo, t, s, vec(0, 2, 5), 0.5);
    CHECK_NEAR(v.end.xyz[0], 0.3, 1e-12);
    CHECK_NEAR(v.end.xyz[1], 0.9, 1e-12);
    tg_trace_destroy(t);
    close_ctx(&c);
}

/* Rays through vertices and along edges of a regular grid: on a flat mesh the straightest
 * geodesic through a vertex is straight on, and a ray along edges runs vertex to vertex. */
static void test_grid_lines(void)
{
    nv = nf = 0;
    grid(8, 0.0, 0.0, 1.0, 0.0, NULL);
    ctx c = open_ctx();
    tg_trace* t = NULL;
    CHECK_STATUS(tg_trace_create(NULL, &t), TG_OK);
    /* along the row y = 0.5 from vertex (0.125, 0.5): through vertices only */
    tg_surface_point s = tg_surface_vertex(4 * 9 + 1);
    tg_trace_view v = trace_view(c.geo, t, s, vec(1, 0, 0), 0.8);
    check_trace("grid row", c.mesh, &v, &s);
    CHECK_EQ_INT(v.end.status, TG_TRACE_COMPLETE);
    CHECK_NEAR(v.end.xyz[0], 0.925, 1e-12);
    CHECK_NEAR(v.end.xyz[1], 0.5, 1e-14);
    CHECK_EQ_INT(v.end.vertices, 6);
    /* along the diagonal through (0, 0): every other cell's diagonal edge, the rest across
     * cells through their corners */
    s = tg_surface_vertex(0);
    v = trace_view(c.geo, t, s, vec(1, 1, 0), 1.2);
    check_trace("grid diagonal", c.mesh, &v, &s);
    CHECK_NEAR(v.end.xyz[0], 1.2 / sqrt(2.0), 1e-12);
    CHECK_NEAR(v.end.xyz[1], 1.2 / sqrt(2.0), 1e-12);
    CHECK_EQ_INT(v.end.vertices, 6);
    /* to the corner (1, 1): a boundary vertex */
    v = trace_view(c.geo, t, s, vec(1, 1, 0), 2.0);
    CHECK_EQ_INT(v.end.status, TG_TRACE_BOUNDARY);
    CHECK_NEAR(v.end.length, sqrt(2.0), 1e-12);
    CHECK_EQ_INT(v.end.point.kind, TG_SURFACE_VERTEX);
    CHECK_EQ_INT(v.end.point.index, 80);
    /* along the boundary from a corner: a walk on the boundary stops at its next vertex */
    v = trace_view(c.geo, t, s, vec(1, 0, 0), 3.0);
    check_trace("grid boundary", c.mesh, &v, &s);
    CHECK_EQ_INT(v.end.status, TG_TRACE_BOUNDARY);
    CHECK_NEAR(v.end.length, 0.125, 1e-15);
    CHECK_EQ_INT(v.end.point.index, 1);
    /* a boundary vector pointing off the surface: the nearest direction of the surface is along
     * the boundary */
    s = tg_surface_vertex(4);
    v = trace_view(c.geo, t, s, vec(0.3, -1, 0), 0.25);
    check_trace("grid off the boundary", c.mesh, &v, &s);
    CHECK_EQ_INT(v.end.status, TG_TRACE_BOUNDARY);
    CHECK_NEAR(v.end.xyz[0], 0.625, 1e-15);
    CHECK_NEAR(v.end.xyz[1], 0.0, 1e-15);
    tg_trace_destroy(t);
    close_sheet(&c);
}

/* ---- the prism: helices ---- */

/* The position along the perimeter (unrolled) of a point on the prism's side. */
static double prism_u(int n, const double* p)
{
    double a = atan2(p[1], p[0]);
    if (a < 0) a += 2 * TG_PI_;
    int k = (int)floor(a / (2 * TG_PI_ / n));
    if (k >= n) k = n - 1;
    double x0 = cos(2 * TG_PI_ * k / n), y0 = sin(2 * TG_PI_ * k / n);
    double side = 2 * sin(TG_PI_ / n);
    return k * side + hypot(p[0] - x0, p[1] - y0);
}

static void test_prism(void)
{
    const int n = 12;
    const double h = 10.0, side = 2 * sin(TG_PI_ / n), width = n * side;
    tg_mesh* m = prism(n, 20, h);
    ctx c = open_ctx_for(m);
    tg_trace* t = NULL;
    CHECK_STATUS(tg_trace_create(NULL, &t), TG_OK);
    const double alphas[3] = {0.1, 0.37, -0.2};
    for (int ia = 0; ia < 3; ++ia) {
        double alpha = alphas[ia], z0 = alpha < 0 ? 9.3 : 0.3, u0 = 0.4 * side;
        /* on side 0 (vertices 0 -> 1), u0 along it, at height z0 */
        double p0[3] = {1 + (cos(2 * TG_PI_ / n) - 1) * 0.4, sin(2 * TG_PI_ / n) * 0.4, z0};
        tg_surface_point s = locate(m, p0[0], p0[1], p0[2]);
        double tx = (cos(2 * TG_PI_ / n) - 1) / side, ty = sin(2 * TG_PI_ / n) / side;
        double len = 3.2 * width / cos(alpha); /* a bit more than three turns */
        tg_trace_view v = trace_view(c.geo, t, s, vec(cos(alpha) * tx, cos(alpha) * ty, sin(alpha)), len);
        check_trace("prism helix", m, &v, &s);
        CHECK_EQ_INT(v.end.status, TG_TRACE_COMPLETE);
        /* the end unrolled: u0 + len cos(alpha) along the perimeter, z0 + len sin(alpha) up */
        double u = fmod(u0 + len * cos(alpha), width), z = z0 + len * sin(alpha);
        int k = (int)floor(u / side);
        double f = (u - k * side) / side;
        double ex = cos(2 * TG_PI_ * k / n) + f * (cos(2 * TG_PI_ * (k + 1) / n) - cos(2 * TG_PI_ * k / n));
        double ey = sin(2 * TG_PI_ * k / n) + f * (sin(2 * TG_PI_ * (k + 1) / n) - sin(2 * TG_PI_ * k / n));
        double err = hypot(hypot(v.end.xyz[0] - ex, v.end.xyz[1] - ey), v.end.xyz[2] - z);
        CHECK_MSG(err <= 1e-11, "helix %g: end (%.17g %.17g %.17g), expected (%.17g %.17g %.17g)", alpha, v.end.xyz[0],
                  v.end.xyz[1], v.end.xyz[2], ex, ey, z);
        CHECK_NEAR(v.end.direction[2], sin(alpha), 1e-12);
        /* the pitch: every point rises tan(alpha) per unit of unrolled turn */
        double prev = u0, turns = 0.0, worst = 0.0;
        for (size_t i = 0; i < v.point_count; ++i) {
            double ui = prism_u(n, v.xyz + 3 * i);
            if (ui + turns < prev - 0.5 * width) turns += width;
            prev = ui + turns;
            worst = fmax(worst, fabs(v.xyz[3 * i + 2] - z0 - (prev - u0) * tan(alpha)));
        }
        CHECK_MSG(worst <= 1e-11, "helix %g: a point is %.3g off the pitch %.17g per turn", alpha, worst,
                  width * tan(alpha));
        CHECK_NEAR(prev - u0, len * cos(alpha), 1e-10);
    }
    /* a steeper helix reaches the top rim: stopped there, having walked (h - z0) / sin(alpha) */
    tg_surface_point s = locate(m, 1 + (cos(2 * TG_PI_ / n) - 1) * 0.5, sin(2 * TG_PI_ / n) * 0.5, 1.0);
    double tx = (cos(2 * TG_PI_ / n) - 1) / side, ty = sin(2 * TG_PI_ / n) / side, alpha = 0.3;
    tg_trace_view v = trace_view(c.geo, t, s, vec(cos(alpha) * tx, cos(alpha) * ty, sin(alpha)), 100.0);
    check_trace("prism to the rim", m, &v, &s);
    CHECK_EQ_INT(v.end.status, TG_TRACE_BOUNDARY);
    CHECK_NEAR(v.end.length, (h - 1.0) / sin(alpha), 1e-11);
    CHECK_NEAR(v.end.xyz[2], h, 1e-12);
    tg_trace_destroy(t);
    close_ctx(&c);
}

/* ---- the cube: geodesics unfolded by hand ---- */

static void check_end(const char* what, const tg_trace_view* v, double x, double y, double z, double tol)
{
    double err = hypot(hypot(v->end.xyz[0] - x, v->end.xyz[1] - y), v->end.xyz[2] - z);
    CHECK_MSG(err <= tol, "%s: end (%.17g, %.17g, %.17g), expected (%.17g, %.17g, %.17g)", what, v->end.xyz[0],
              v->end.xyz[1], v->end.xyz[2], x, y, z);
}

static void check_dir(const char* what, const tg_trace_view* v, double x, double y, double z, double tol)
{
    double l = sqrt(x * x + y * y + z * z);
    double err = hypot(hypot(v->end.direction[0] - x / l, v->end.direction[1] - y / l), v->end.direction[2] - z / l);
    CHECK_MSG(err <= tol, "%s: end direction (%.17g, %.17g, %.17g), expected (%.17g, %.17g, %.17g)", what,
              v->end.direction[0], v->end.direction[1], v->end.direction[2], x / l, y / l, z / l);
}

/* Directions at the cube's corner (1, 1, 0): its edges e_x = (-1, 0, 0), e_z = (0, 0, 1),
 * e_y = (0, -1, 0) lie counterclockwise (seen from outside) at fan angles 0, pi / 2, pi, and
 * e_x again at 3 pi / 2: the direction at fan angle phi, and the fan angle of a direction. */
static const double cube_edges[4][3] = {{-1, 0, 0}, {0, 0, 1}, {0, -1, 0}, {-1, 0, 0}};
static void corner_direction(double phi, double out[3])
{
    phi = fmod(phi, 1.5 * TG_PI_);
    if (phi < 0) phi += 1.5 * TG_PI_;
    int i = (int)(phi / (0.5 * TG_PI_));
    if (i > 2) i = 2;
    double psi = phi - i * 0.5 * TG_PI_;
    for (int k = 0; k < 3; ++k) out[k] = cos(psi) * cube_edges[i][k] + sin(psi) * cube_edges[i + 1][k];
}
static double corner_angle_of(const double d[3])
{
    for (int i = 0; i < 3; ++i) {
        const double *a = cube_edges[i], *b = cube_edges[i + 1];
        double da = d[0] * a[0] + d[1] * a[1] + d[2] * a[2], db = d[0] * b[0] + d[1] * b[1] + d[2] * b[2];
        double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (da >= -1e-15 && db >= -1e-15 && fabs(hypot(da, db) - l) <= 1e-12 * l) return i * 0.5 * TG_PI_ + atan2(db, da);
    }
    CHECK_MSG(0, "direction (%g, %g, %g) is not in the corner's fan", d[0], d[1], d[2]);
    return 0;
}

static void test_cube(void)
{
    tg_mesh* m = cube(3);
    ctx c = open_ctx_for(m);
    tg_trace* t = NULL;
    CHECK_STATUS(tg_trace_create(NULL, &t), TG_OK);
    const double r2 = sqrt(2.0);
    /* around the cube along y = 0.25: back to the start after 4 */
    tg_surface_point s = locate(m, 0.5, 0.25, 0.0);
    tg_trace_view v = trace_view(c.geo, t, s, vec(1, 0, 0), 4.0);
    check_trace("cube belt", m, &v, &s);
    check_end("cube belt", &v, 0.5, 0.25, 0.0, 1e-12);
    check_dir("cube belt", &v, 1, 0, 0, 1e-12);
    /* half way: on the top, heading -x */
    v = trace_view(c.geo, t, s, vec(1, 0, 0), 2.0);
    check_end("cube half belt", &v, 0.5, 0.25, 1.0, 1e-12);
    check_dir("cube half belt", &v, -1, 0, 0, 1e-12);
    /* at 45 degrees over two cube edges: bottom to x = 1 at y = 0.75, up to y = 1 at z = 0.25,
     * then across the side y = 1 heading -x and up */
    v = trace_view(c.geo, t, s, vec(1, 1, 0), 1.25 * r2);
    check_trace("cube diagonal", m, &v, &s);
    check_end("cube diagonal", &v, 0.5, 1.0, 0.75, 1e-12);
    check_dir("cube diagonal", &v, -1, 0, 1, 1e-12);
    /* through the corner (1, 1, 0), of angle 3 pi / 2: the straightest geodesic leaves with
     * 3 pi / 4 on each side, up the cube's vertical edge (through the vertex at z = 1/3) */
    s = locate(m, 0.5, 0.5, 0.0);
    v = trace_view(c.geo, t, s, vec(1, 1, 0), r2 / 2 + 0.5);
    check_trace("cube corner", m, &v, &s);
    CHECK_EQ_INT(v.end.status, TG_TRACE_COMPLETE);
    check_end("cube corner", &v, 1.0, 1.0, 0.5, 1e-12);
    check_dir("cube corner", &v, 0, 0, 1, 1e-12);
    CHECK_EQ_INT(v.end.vertices, 3); /* (2/3, 2/3, 0), the corner, (1, 1, 1/3) */
    /* on, over the top corner (1, 1, 1) the same way: down the diagonal of the top face */
    v = trace_view(c.geo, t, s, vec(1, 1, 0), r2 / 2 + 1.0 + r2 / 4);
    check_end("cube two corners", &v, 0.75, 0.75, 1.0, 1e-12);
    check_dir("cube two corners", &v, -1, -1, 0, 1e-12);
    /* angles at a corner: the vertex (1, 1, 0) has angle 3 pi / 2, normalised to 2 pi: a quarter
     * turn is 3 pi / 8 of the fan, counterclockwise seen from outside (the faces' winding) */
    uint32_t corner = cube_index[3][3][0];
    const uint32_t* vh = tg_mesh_vertex_halfedges(m);
    const double* x = tg_mesh_positions(m);
    uint32_t to = tg_mesh_halfedge_to(m, vh[corner]);
    double ref[3] = {x[3 * to] - 1.0, x[3 * to + 1] - 1.0, x[3 * to + 2]};
    double ref_phi = corner_angle_of(ref);
    for (int q = -1; q < 6; ++q) {
        tg_surface_point cs = tg_surface_vertex(corner);
        v = trace_view(c.geo, t, cs, ang(q * 0.5 * TG_PI_), 0.2);
        check_trace("cube corner angle", m, &v, &cs);
        double d[3];
        corner_direction(ref_phi + q * 3 * TG_PI_ / 8, d);
        check_end("cube corner angle", &v, 1.0 + 0.2 * d[0], 1.0 + 0.2 * d[1], 0.2 * d[2], 1e-12);
    }
    /* a face point's angle: from corner 0 towards corner 1, counterclockwise seen from outside */
    s = locate(m, 0.6, 0.2, 0.0);
    const uint32_t* tri3 = tg_mesh_triangles(m) + 3 * (size_t)s.index;
    double e01[3], nrm[3] = {0, 0, -1}, side[3];
    for (int k = 0; k < 3; ++k) e01[k] = x[3 * tri3[1] + k] - x[3 * tri3[0] + k];
    double el = sqrt(e01[0] * e01[0] + e01[1] * e01[1] + e01[2] * e01[2]);
    for (int k = 0; k < 3; ++k) e01[k] /= el;
    side[0] = nrm[1] * e01[2] - nrm[2] * e01[1], side[1] = nrm[2] * e01[0] - nrm[0] * e01[2],
    side[2] = nrm[0] * e01[1] - nrm[1] * e01[0];
    v = trace_view(c.geo, t, s, ang(1.0), 0.1);
    check_end("cube face angle", &v, 0.6 + 0.1 * (cos(1.0) * e01[0] + sin(1.0) * side[0]),
              0.2 + 0.1 * (cos(1.0) * e01[1] + sin(1.0) * side[1]), 0.0, 1e-13);
    tg_trace_destroy(t);
    close_ctx(&c);
}

/* ---- zero-area faces ---- */

/* A flat strip [0, 1] x [0, 1] cut along x = 0.5: the right half has its own copies of the seam
 * vertices, joined to the left half by slits (zero-area faces with a zero-length edge). */
static void seam_strip(int n)
{
    nv = nf = 0;
    uint32_t left[32][32], right[32];
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) left[j][i] = add_v((double)i / n, (double)j / n, 0.0);
    for (int j = 0; j <= n; ++j) right[j] = add_v(0.5, (double)j / n, 0.0);
    int half = n / 2;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            uint32_t a = left[j][i], b = left[j][i + 1], cc = left[j + 1][i], d = left[j + 1][i + 1];
            if (i == half) a = right[j], cc = right[j + 1]; /* the right half's own seam */
            add_f(a, b, d), add_f(a, d, cc);
        }
    for (int j = 0; j < n; ++j) { /* the slits, between the seam's two copies */
        add_f(left[j + 1][half], left[j][half], right[j]);
        add_f(left[j + 1][half], right[j], right[j + 1]);
    }
}

/* A diamond split along y = 0.5 with a T-junction: one face below the line A B, two above it
 * meeting at M on it, and the cap (A, B, M) of zero area between. Returns the cap's face. */
static uint32_t capped_diamond(void)
{
    nv = nf = 0;
    uint32_t a = add_v(0, 0.5, 0), b = add_v(1, 0.5, 0), m = add_v(0.4, 0.5, 0), top = add_v(0.5, 1, 0),
             bottom = add_v(0.5, 0, 0);
    add_f(a, bottom, b);
    add_f(a, m, top);
    add_f(m, b, top);
    add_f(a, b, m);
    return 3;
}

static void test_zero_area(void)
{
    tg_trace* t = NULL;
    CHECK_STATUS(tg_trace_create(NULL, &t), TG_OK);
    seam_strip(8);
    ctx c = open_ctx();
    tg_rng r = {3};
    for (int i = 0; i < 50; ++i) { /* across the seam: the straight line, through two slits */
        double y0 = tg_rng_range(&r, 0.3, 0.7), a = tg_rng_range(&r, -0.5, 0.5), len = 0.35 / cos(a);
        tg_surface_point s = locate(c.mesh, 0.2, y0, 0.0);
        tg_trace_view v = trace_view(c.geo, t, s, vec(cos(a), sin(a), 0), len);
        if (check_trace("seam", c.mesh, &v, &s)) break;
        CHECK_EQ_INT(v.end.status, TG_TRACE_COMPLETE);
        check_end("seam", &v, 0.2 + len * cos(a), y0 + len * sin(a), 0.0, 1e-12);
    }
    /* a start on the seam itself (a point of a slit): the same line */
    tg_surface_point s = tg_surface_face((uint32_t)(nf - 3), 0.25, 0.25, 0.5);
    double p0[3];
    tg_surface_point_position(c.mesh, &s, p0);
    tg_trace_view v = trace_view(c.geo, t, s, vec(1, 0.2, 0), 0.3);
    check_trace("seam start", c.mesh, &v, &s);
    check_end("seam start", &v, p0[0] + 0.3 / sqrt(1.04), p0[1] + 0.06 / sqrt(1.04), 0.0, 1e-12);
    close_sheet(&c);

    uint32_t cap = capped_diamond();
    c = open_ctx();
    s = locate(c.mesh, 0.5, 0.2, 0.0);
    v = trace_view(c.geo, t, s, vec(0.1, 1, 0), 0.5);
    check_trace("cap", c.mesh, &v, &s);
    check_end("cap", &v, 0.5 + 0.05 / sqrt(1.01), 0.2 + 0.5 / sqrt(1.01), 0.0, 1e-12);
    /* from a point of the cap, up or down */
    s = tg_surface_face(cap, 0.3, 0.3, 0.4);
    tg_surface_point_position(c.mesh, &s, p0);
    v = trace_view(c.geo, t, s, vec(0, 1, 0), 0.2);
    check_trace("from the cap up", c.mesh, &v, &s);
    check_end("from the cap up", &v, p0[0], 0.7, 0.0, 1e-12);
    v = trace_view(c.geo, t, s, vec(0.1, -1, 0), 0.2);
    check_end("from the cap down", &v, p0[0] + 0.02 / sqrt(1.01), 0.5 - 0.2 / sqrt(1.01), 0.0, 1e-12);
    close_sheet(&c);

    /* more than 1000 nested caps in a row at one point: the walk stops rather than loop */
    nv = nf = 0;
    uint32_t a0 = add_v(0, 0, 0), s0 = add_v(0.5, -1, 0), b0 = add_v(1, 0, 0), prev = b0;
    add_f(a0, s0, b0);
    for (int k = 1; k <= 1200; ++k) {
        uint32_t mk = add_v(1.0 - k / 2000.0, 0, 0);
        add_f(a0, prev, mk);
        prev = mk;
    }
    add_f(a0, prev, add_v(0.2, 1, 0));
    c = open_ctx();
    s = tg_surface_face(0, 0.65, 0.05, 0.3); /* at x = 0.325: inside every cap's long side */
    v = trace_view(c.geo, t, s, vec(0, 1, 0), 1.0);
    check_trace("nested caps", c.mesh, &v, &s);
    CHECK_EQ_INT(v.end.status, TG_TRACE_STALLED);
    CHECK_MSG(v.end.crossings > 1000 && v.end.crossings < 1100, "stalled after %llu crossings",
              (unsigned long long)v.end.crossings);
    close_sheet(&c);
    tg_trace_destroy(t);
}

/* ---- non-manifold edges: the straightest page ---- */

/* A book of three pages on the spine x = z = 0, y in [0, 1]: page A flat at x < 0, pages B and C
 * leaving the spine at angles tb and tc (radians, from +x towards +z). */
static void book(double tb, double tc)
{
    nv = nf = 0;
    uint32_t spine[3], pa[3], pb[3], pc[3];
    for (int j = 0; j < 3; ++j) {
        double y = 0.5 * j;
        spine[j] = add_v(0, y, 0);
        pa[j] = add_v(-1, y, 0);
        pb[j] = add_v(cos(tb), y, sin(tb));
        pc[j] = add_v(cos(tc), y, sin(tc));
    }
    for (int j = 0; j < 2; ++j) {
        add_f(pa[j], spine[j], spine[j + 1]), add_f(pa[j], spine[j + 1], pa[j + 1]);
        add_f(spine[j], pb[j], pb[j + 1]), add_f(spine[j], pb[j + 1], spine[j + 1]);
        add_f(spine[j], pc[j + 1], pc[j]), add_f(spine[j], spine[j + 1], pc[j + 1]);
    }
}

static void test_book(void)
{
    tg_trace* t = NULL;
    CHECK_STATUS(tg_trace_create(NULL, &t), TG_OK);
    const double deg = TG_PI_ / 180;
    const double pages[2][2] = {{0.0, 90 * deg}, {-80 * deg, 45 * deg}}; /* B flat; then C straighter */
    for (int i = 0; i < 2; ++i) {
        book(pages[i][0], pages[i][1]);
        ctx c = open_ctx();
        tg_surface_point s = locate(c.mesh, -0.5, 0.3, 0.0);
        double a = 0.2, len = 0.5 / cos(a) + 0.3;
        tg_trace_view v = trace_view(c.geo, t, s, vec(cos(a), sin(a), 0), len);
        check_trace("book", c.mesh, &v, &s);
        CHECK_EQ_INT(v.end.status, TG_TRACE_COMPLETE);
        CHECK_EQ_INT(v.end.branches, 1);
        double tp = i == 0 ? pages[i][0] : pages[i][1], y = 0.3 + len * sin(a);
        check_end("book", &v, 0.3 * cos(a) * cos(tp), y, 0.3 * cos(a) * sin(tp), 1e-12);
        if (v.branch_count == 1) { /* the face taken: one of the page's (faces 2, 3, 8, 9: B; 4, 5, 10, 11: C) */
            uint32_t f = v.faces[v.branch_points[0]];
            int page = (f % 6) / 2;
            CHECK_EQ_INT(page, i == 0 ? 1 : 2);
        }
        close_sheet(&c);
    }
    tg_trace_destroy(t);
}

/* ---- scale, step limit, errors ---- */

static tg_mesh* load_data_mesh(const char* name)
{
    const char* src = getenv("TG_SOURCE_DIR");
    char path[4096];
    snprintf(path, sizeof path, "%s/data/%s", src ? src : ".", name);
    tg_mesh* m = NULL;
    tg_diag d;
    CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &m), TG_OK);
    return m;
}

/* The mesh's vertices times s plus (dx, dy, dz). */
static tg_mesh* transformed(const tg_mesh* m, double s, double dx, double dy, double dz)
{
    size_t n = tg_mesh_vertex_count(m);
    double* x = malloc(3 * n * sizeof *x);
    const double* p = tg_mesh_positions(m);
    for (size_t i = 0; i < n; ++i) x[3 * i] = p[3 * i] * s + dx, x[3 * i + 1] = p[3 * i + 1] * s + dy, x[3 * i + 2] = p[3 * i + 2] * s + dz;
    tg_mesh* out = NULL;
    CHECK_STATUS(tg_mesh_create(x, n, tg_mesh_triangles(m), tg_mesh_face_count(m), NULL, NULL, &out), TG_OK);
    free(x);
    return out;
}

static void test_scale(void)
{
    tg_mesh* m = load_data_mesh("nvd_spot.obj");
    if (!m) return;
    tg_mesh* big = transformed(m, 1024.0, 0, 0, 0);
    tg_mesh* odd = transformed(m, 3.7, 10.0, -5.0, 2.0);
    tg_geodesic *g = NULL, *gb = NULL, *go = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    CHECK_STATUS(tg_geodesic_create(big, NULL, &gb), TG_OK);
    CHECK_STATUS(tg_geodesic_create(odd, NULL, &go), TG_OK);
    tg_trace *t = NULL, *tb = NULL;
    CHECK_STATUS(tg_trace_create(NULL, &t), TG_OK);
    CHECK_STATUS(tg_trace_create(NULL, &tb), TG_OK);
    double centre[3], diag = tg_test_mesh_box(m, centre), worst = 0.0;
    tg_rng r = {11};
    int same = 0, near = 0, traced = 0, n = 200;
    for (int i = 0; i < n; ++i) {
        tg_surface_point s = tg_test_random_surface_point(&r, m, NULL);
        tg_trace_direction d = i % 2 ? vec(tg_rng_range(&r, -1, 1), tg_rng_range(&r, -1, 1), tg_rng_range(&r, -1, 1))
                                     : ang(tg_rng_range(&r, -7, 7));
        double len = tg_rng_range(&r, 0.0, 0.3) * diag;
        tg_status st = tg_geodesic_trace(g, &s, &d, len, NULL, t);
        if (st == TG_ERR_INVALID_ARGUMENT) continue; /* a random vector perpendicular to the surface */
        CHECK_STATUS(st, TG_OK);
        traced++;
        CHECK_STATUS(tg_geodesic_trace(gb, &s, &d, len * 1024.0, NULL, tb), TG_OK);
        tg_trace_view a, b;
        tg_trace_get_view(t, &a);
        tg_trace_get_view(tb, &b);
        bool ok = a.point_count == b.point_count && a.end.status == b.end.status &&
                  b.end.length == a.end.length * 1024.0 && !memcmp(a.end.direction, b.end.direction, sizeof a.end.direction) &&
                  !memcmp(a.points, b.points, a.point_count * sizeof *a.points) &&
                  !memcmp(a.faces, b.faces, (a.point_count - 1) * sizeof *a.faces);
        for (size_t k = 0; ok && k < 3 * a.point_count; ++k) ok = b.xyz[k] == a.xyz[k] * 1024.0;
        same += ok;
        CHECK_STATUS(tg_geodesic_trace(go, &s, &d, len * 3.7, NULL, tb), TG_OK);
        tg_trace_get_view(tb, &b);
        double e[3] = {(b.end.xyz[0] - 10.0) / 3.7, (b.end.xyz[1] + 5.0) / 3.7, (b.end.xyz[2] - 2.0) / 3.7};
        double err = tg_test_dist3(e, a.end.xyz) / diag;
        if (err > worst) worst = err;
        near += err <= 1e-9 && b.end.status == a.end.status;
    }
    printf("scale: %d of %d traces bit-identical at 1024x, %d within 1e-9 of the diagonal at 3.7x (worst %.3g)\n",
           same, traced, near, worst);
    CHECK(traced > n / 2);
    CHECK_EQ_INT(same, traced);
    CHECK_EQ_INT(near, traced);
    tg_trace_destroy(t);
    tg_trace_destroy(tb);
    tg_geodesic_destroy(g);
    tg_geodesic_destroy(gb);
    tg_geodesic_destroy(go);
    tg_mesh_destroy(m);
    tg_mesh_destroy(big);
    tg_mesh_destroy(odd);
}

/* ---- any scale, any length of the direction, the tangent plane ---- */

/* Trace b, on the mesh scaled by s (a power of two), is trace a scaled, bit for bit: the same
 * points, faces, status and end direction; the positions and the length times s. */
static bool same_scaled(const tg_trace_view* a, const tg_trace_view* b, double s)
{
    bool ok = a->point_count == b->point_count && a->point_count >= 2 && a->end.status == b->end.status &&
              b->end.length == a->end.length * s && !memcmp(a->end.direction, b->end.direction, sizeof a->end.direction) &&
              !memcmp(a->points, b->points, a->point_count * sizeof *a->points) &&
              !memcmp(a->faces, b->faces, (a->point_count - 1) * sizeof *a->faces);
    for (size_t k = 0; ok && k < 3 * a->point_count; ++k) ok = b->xyz[k] == a->xyz[k] * s;
    return ok;
}

/* The angle reference's normal was computed from the mesh's coordinates unscaled: its square
 * overflowed or underflowed beyond about 1e+-78, and spot scaled by 1e100 or 1e-100 refused every
 * angle ("zero area"). Traces from vertices, edge points and face points, by angle and by vector,
 * on spot scaled by 2^k (k = +-330, +-490: within the solver's 1e150) are the unscaled ones bit
 * for bit, and at 1e100 and 1e-100 the same to rounding. */
static void test_any_scale(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "oded_spot_low_resolution.obj");
    if (!m) return;
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    tg_trace *t = NULL, *ts = NULL;
    CHECK_STATUS(tg_trace_create(NULL, &t), TG_OK);
    CHECK_STATUS(tg_trace_create(NULL, &ts), TG_OK);
    double centre[3], diag = tg_test_mesh_box(m, centre);
    const double scales[] = {ldexp(1.0, -490), ldexp(1.0, -330), ldexp(1.0, 330), ldexp(1.0, 490), 1e100, 1e-100};
    const int exponents[] = {-490, -330, 330, 490, 0, 0};
    for (size_t si = 0; si < sizeof scales / sizeof scales[0]; ++si) {
        double s = scales[si];
        tg_mesh* ms = transformed(m, s, 0, 0, 0);
        tg_geodesic* gs = NULL;
        CHECK_STATUS(tg_geodesic_create(ms, NULL, &gs), TG_OK);
        tg_rng r = {30};
        int n = TG_TEST_WORK(300, 60), same = 0, refused = 0, angles = 0;
        double worst = 0.0;
        for (int i = 0; i < n; ++i) {
            tg_surface_point p = tg_test_random_surface_point(&r, m, NULL);
            tg_trace_direction d = i % 2 ? vec(tg_rng_range(&r, -1, 1), tg_rng_range(&r, -1, 1), tg_rng_range(&r, -1, 1))
                                         : ang(tg_rng_range(&r, -7, 7));
            double len = tg_rng_range(&r, 0.0, 0.3) * diag;
            angles += d.kind == TG_TRACE_ANGLE;
            CHECK_STATUS(tg_geodesic_trace(g, &p, &d, len, NULL, t), TG_OK);
            if (tg_geodesic_trace(gs, &p, &d, len * s, NULL, ts) != TG_OK) {
                refused++;
                continue;
            }
            tg_trace_view a, b;
            tg_trace_get_view(t, &a);
            tg_trace_get_view(ts, &b);
            if (exponents[si] != 0) {
                same += same_scaled(&a, &b, s);
                continue;
            }
            double e[3] = {b.end.xyz[0] / s, b.end.xyz[1] / s, b.end.xyz[2] / s};
            double err = tg_test_dist3(e, a.end.xyz) / diag;
            if (err > worst) worst = err;
            same += err <= 1e-9 && a.end.status == b.end.status;
        }
        char what[64];
        if (exponents[si] != 0) snprintf(what, sizeof what, "x2^%d, bit for bit", exponents[si]);
        else snprintf(what, sizeof what, "x%g, worst end %.3g of the diagonal", s, worst);
        printf("scale: spot %s: %d of %d traces (%d by angle) the same, %d refused\n", what, same, n, angles, refused);
        CHECK_MSG(refused == 0 && same == n, "spot %s: %d of %d traces refused, %d of %d the same", what, refused, n,
                  same, n);
        tg_geodesic_destroy(gs);
        tg_mesh_destroy(ms);
    }
    tg_trace_destroy(t);
    tg_trace_destroy(ts);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
}

/* The direction's length was squared: --dir 1e-165,0,0 turned by -26.6 degrees at vertices of a
 * jittered grid (its square underflowed to 0, every cosine became infinite and the lowest face
 * won) and 1e160,0,0 was refused as perpendicular. A direction with integer components times
 * 2^k, for k from -1074 (subnormal components) to 1013, gives the same end bit for bit, from
 * every vertex, from edge points and from face points; on a flat mesh, a vector out of the plane
 * gives the end of its projection onto the plane, bit for bit. */
static void direction_powers(const char* name, tg_mesh* m, bool flat)
{
    ctx c = open_ctx_for(m);
    tg_trace* t = NULL;
    CHECK_STATUS(tg_trace_create(NULL, &t), TG_OK);
    double centre[3], diag = tg_test_mesh_box(m, centre);
    size_t nvert = tg_mesh_vertex_count(m), nface = tg_mesh_face_count(m);
    tg_rng r = {1074};
    int starts = 0, compared = 0, differ = 0, projected = 0;
    for (size_t i = 0; i < nvert + 200; ++i) {
        tg_surface_point p = i < nvert         ? tg_surface_vertex((uint32_t)i)
                             : i < nvert + 100 ? tg_surface_edge((uint32_t)(tg_rng_next(&r) % (3 * nface)), tg_rng_unit(&r))
                                               : random_face_point(&r, nface);
        double d[3];
        for (int k = 0; k < 3; ++k) d[k] = (double)(int)(tg_rng_next(&r) % 2001) - 1000.0;
        if (tg_surface_point_validate(m, &p, NULL) != TG_OK || (d[0] == 0.0 && d[1] == 0.0 && d[2] == 0.0)) continue;
        double len = 0.1 * diag;
        tg_trace_direction d0 = vec(d[0], d[1], d[2]);
        tg_status st = tg_geodesic_trace(c.geo, &p, &d0, len, NULL, t);
        if (st == TG_ERR_INVALID_ARGUMENT) continue; /* off an open fan */
        CHECK_STATUS(st, TG_OK);
        tg_trace_view v;
        tg_trace_get_view(t, &v);
        tg_trace_end e0 = v.end;
        starts++;
        for (int k = -1074;; k += 29) {
            if (k > 1013) k = 1013;
            tg_trace_direction dk = vec(ldexp(d[0], k), ldexp(d[1], k), ldexp(d[2], k));
            st = tg_geodesic_trace(c.geo, &p, &dk, len, NULL, t);
            tg_trace_get_view(t, &v);
            compared++;
            if (st != TG_OK || memcmp(&v.end, &e0, sizeof e0) != 0) {
                CHECK_MSG(differ > 0, "%s: from point %zu, (%.17g, %.17g, %.17g) x 2^%d: %s, end (%.17g, %.17g, %.17g); "
                          "x 1: (%.17g, %.17g, %.17g)", name, i, d[0], d[1], d[2], k, tg_status_name(st),
                          v.end.xyz[0], v.end.xyz[1], v.end.xyz[2], e0.xyz[0], e0.xyz[1], e0.xyz[2]);
                differ++;
            }
            if (k == 1013) break;
        }
        if (flat && (d[0] != 0.0 || d[1] != 0.0)) { /* the projection onto the plane z = 0 */
            tg_trace_direction dp = vec(d[0], d[1], 0.0);
            st = tg_geodesic_trace(c.geo, &p, &dp, len, NULL, t);
            tg_trace_get_view(t, &v);
            projected++;
            CHECK_MSG(st == TG_OK && memcmp(&v.end, &e0, sizeof e0) == 0,
                      "%s: from point %zu, (%.17g, %.17g, 0): %s, end (%.17g, %.17g); with z = %.17g: (%.17g, %.17g)",
                      name, i, d[0], d[1], tg_status_name(st), v.end.xyz[0], v.end.xyz[1], d[2], e0.xyz[0], e0.xyz[1]);
        }
    }
    printf("direction length: %s: %d starts x 73 powers of two: %d of %d ends differ; %d projections onto the plane\n",
           name, starts, differ, compared, projected);
    CHECK_EQ_INT(differ, 0);
    CHECK(starts > (int)nvert / 2);
    /* the vectors (not powers of two of each other): the same end as (1, 0, 0), to
     * rounding, from every vertex */
    const double xs[] = {1e-320, 4.9e-324, 1e-165, 1e-160, 1e160, 1e300, DBL_MAX};
    int agree = 0, tried = 0;
    for (uint32_t i = 0; i < nvert; ++i) {
        tg_surface_point p = tg_surface_vertex(i);
        tg_trace_direction d1 = vec(1, 0, 0);
        if (tg_geodesic_trace(c.geo, &p, &d1, 0.1 * diag, NULL, t) != TG_OK) continue;
        tg_trace_view v;
        tg_trace_get_view(t, &v);
        tg_trace_end e1 = v.end;
        for (size_t j = 0; j < sizeof xs / sizeof xs[0]; ++j) {
            tg_trace_direction dx = vec(xs[j], 0, 0);
            tg_status st = tg_geodesic_trace(c.geo, &p, &dx, 0.1 * diag, NULL, t);
            tg_trace_get_view(t, &v);
            tried++;
            bool ok = st == TG_OK && v.end.status == e1.status && tg_test_dist3(v.end.xyz, e1.xyz) <= 1e-12 * diag;
            CHECK_MSG(ok || agree < tried - 1, "%s: from v%u, (%.17g, 0, 0): %s, end (%.17g, %.17g, %.17g); (1, 0, 0): "
                      "(%.17g, %.17g, %.17g)", name, i, xs[j], tg_status_name(st), v.end.xyz[0], v.end.xyz[1],
                      v.end.xyz[2], e1.xyz[0], e1.xyz[1], e1.xyz[2]);
            agree += ok;
        }
    }
    printf("direction length: %s: %d of %d traces along (x, 0, 0), x from 4.9e-324 to DBL_MAX, end where (1, 0, 0) "
           "does\n", name, agree, tried);
    CHECK_EQ_INT(agree, tried);
    tg_trace_destroy(t);
    close_ctx(&c);
}

static void test_direction_length(void)
{
    direction_powers("flat jittered grid", flat_square(10, 165), true);
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "oded_spot_low_resolution.obj");
    if (m) direction_powers("spot", m, false);
}

/* The angle-weighted normal of every vertex, by the file's winding (Thürmer & Wüthrich 1998,
 * computed here on the mesh's coordinates), into n (3 per vertex; zero where a face at the vertex
 * has zero area); closed[v]: its faces make one fan, closed by edges of two faces each. */
static void vertex_normals(const tg_mesh* m, double* n, bool* closed)
{
    size_t nvert = tg_mesh_vertex_count(m), nface = tg_mesh_face_count(m);
    const double* x = tg_mesh_positions(m);
    const uint32_t* tr = tg_mesh_triangles(m);
    const uint32_t* op = tg_mesh_opposites(m);
    const uint32_t* vh = tg_mesh_vertex_halfedges(m);
    uint32_t* count = calloc(nvert, sizeof *count);
    bool* degenerate = calloc(nvert, sizeof *degenerate);
    memset(n, 0, 3 * nvert * sizeof *n);
    for (size_t f = 0; f < nface; ++f)
        for (int k = 0; k < 3; ++k) {
            uint32_t v = tr[3 * f + (size_t)k], a = tr[3 * f + (size_t)(k + 1) % 3], b = tr[3 * f + (size_t)(k + 2) % 3];
            double e1[3], e2[3], cr[3];
            for (int j = 0; j < 3; ++j) e1[j] = x[3 * a + j] - x[3 * v + j], e2[j] = x[3 * b + j] - x[3 * v + j];
            cr[0] = e1[1] * e2[2] - e1[2] * e2[1], cr[1] = e1[2] * e2[0] - e1[0] * e2[2], cr[2] = e1[0] * e2[1] - e1[1] * e2[0];
            double cl = sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
            double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]), l2 = sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
            count[v]++;
            if (!(cl > 1e-9 * l1 * l2)) {
                degenerate[v] = true;
                continue;
            }
            double ang = atan2(cl, e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]);
            for (int j = 0; j < 3; ++j) n[3 * v + j] += ang * cr[j] / cl;
        }
    for (size_t v = 0; v < nvert; ++v) {
        double l = sqrt(n[3 * v] * n[3 * v] + n[3 * v + 1] * n[3 * v + 1] + n[3 * v + 2] * n[3 * v + 2]);
        if (degenerate[v] || !(l > 1e-6)) l = INFINITY;
        for (int j = 0; j < 3; ++j) n[3 * v + j] /= l;
        /* once round the fan: from an outgoing halfedge, across the edge coming in */
        uint32_t h = vh[v], steps = 0;
        closed[v] = h != TG_NONE && l < INFINITY;
        while (closed[v]) {
            uint32_t in = h - h % 3 + (h % 3 + 2) % 3, o = op[in];
            if (o == TG_NONE || tg_mesh_halfedge_from(m, o) != v) closed[v] = false;
            else if (++steps, h = o, h == vh[v]) break;
            if (steps > count[v]) closed[v] = false;
        }
        if (closed[v] && steps != count[v]) closed[v] = false; /* a pinch: more than one fan */
    }
    free(count);
    free(degenerate);
}

static double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* A vector at a vertex was refused as perpendicular when no face of its fan had a direction within
 * a right angle of it: on cgal_mpi.off, v:81 refused (1.387, -1.317, -2.283), 92-107 degrees
 * from every direction of the surface there, and about 6% of random vectors at its vertices.
 * Now its projection onto the tangent plane counts: at every vertex whose fan closes, random
 * vectors are never refused and the direction taken has a positive cosine with the projection;
 * the normal itself is refused, the normal tilted by 1e-7 radians is not. At edge points of two
 * faces the same with the faces' mean normal. */
static void tangent_case(const char* file, int per_vertex)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), file);
    if (!m) return;
    ctx c = open_ctx_for(m);
    tg_trace* t = NULL;
    CHECK_STATUS(tg_trace_create(NULL, &t), TG_OK);
    size_t nvert = tg_mesh_vertex_count(m), nface = tg_mesh_face_count(m);
    double* nrm = malloc(3 * nvert * sizeof *nrm);
    bool* closed = malloc(nvert * sizeof *closed);
    vertex_normals(m, nrm, closed);
    tg_rng r = {81};
    int vertices = 0, tried = 0, refused = 0, backwards = 0, normal_kept = 0, tilted_refused = 0;
    for (uint32_t i = 0; i < nvert; ++i) {
        if (!closed[i]) continue;
        const double* n = nrm + 3 * i;
        vertices++;
        tg_surface_point p = tg_surface_vertex(i);
        for (int k = 0; k < per_vertex; ++k) {
            double d[3], l;
            do {
                for (int j = 0; j < 3; ++j) d[j] = tg_rng_range(&r, -1, 1);
                l = dot3(d, d);
            } while (l > 1.0 || l < 1e-6);
            tg_trace_direction dv = vec(d[0], d[1], d[2]);
            tried++;
            if (tg_geodesic_trace(c.geo, &p, &dv, 0.0, NULL, t) != TG_OK) {
                CHECK_MSG(refused > 0, "%s: v%u refused (%.17g, %.17g, %.17g), %.3g rad from the normal", file, i, d[0],
                          d[1], d[2], acos(fabs(dot3(d, n)) / sqrt(l)));
                refused++;
                continue;
            }
            tg_trace_view v;
            tg_trace_get_view(t, &v);
            double dn = dot3(d, n), vt[3] = {d[0] - dn * n[0], d[1] - dn * n[1], d[2] - dn * n[2]};
            if (!(dot3(v.end.direction, vt) > 0.0)) {
                CHECK_MSG(backwards > 0, "%s: v%u, (%.17g, %.17g, %.17g): the direction taken (%.17g, %.17g, %.17g) is "
                          "not within a right angle of its projection", file, i, d[0], d[1], d[2], v.end.direction[0],
                          v.end.direction[1], v.end.direction[2]);
                backwards++;
            }
        }
        /* the normal: refused; tilted by 1e-7 towards a tangent t: taken, on t's side */
        tg_trace_direction dn = vec(n[0], n[1], n[2]);
        if (tg_geodesic_trace(c.geo, &p, &dn, 0.0, NULL, t) != TG_ERR_INVALID_ARGUMENT) normal_kept++;
        double a[3] = {fabs(n[0]) < 0.5 ? 1.0 : 0.0, fabs(n[0]) < 0.5 ? 0.0 : 1.0, 0.0}, tt[3];
        tt[0] = n[1] * a[2] - n[2] * a[1], tt[1] = n[2] * a[0] - n[0] * a[2], tt[2] = n[0] * a[1] - n[1] * a[0];
        double tl = sqrt(dot3(tt, tt));
        tg_trace_direction dt = vec(n[0] + 1e-7 * tt[0] / tl, n[1] + 1e-7 * tt[1] / tl, n[2] + 1e-7 * tt[2] / tl);
        tg_trace_view v;
        if (tg_geodesic_trace(c.geo, &p, &dt, 0.0, NULL, t) != TG_OK) tilted_refused++;
        else if (tg_trace_get_view(t, &v), !(dot3(v.end.direction, tt) > 0.0)) backwards++;
    }
    /* edge points of two faces: the tangent plane of the faces' mean normal */
    const double* x = tg_mesh_positions(m);
    const uint32_t* tr = tg_mesh_triangles(m);
    const uint32_t* op = tg_mesh_opposites(m);
    int edges = 0, edge_refused = 0, edge_normal_kept = 0, edge_tilted_refused = 0;
    for (int k = 0; k < 20 * per_vertex && nface; ++k) {
        uint32_t h = (uint32_t)(tg_rng_next(&r) % (3 * nface)), o = op[h];
        if (o == TG_NONE) continue;
        double en[3] = {0, 0, 0};
        bool ok = true;
        for (int s = 0; s < 2; ++s) {
            uint32_t f = (s ? o : h) / 3;
            const double *a = x + 3 * tr[3 * f], *b = x + 3 * tr[3 * f + 1], *cc = x + 3 * tr[3 * f + 2];
            double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {cc[0] - a[0], cc[1] - a[1], cc[2] - a[2]};
            double cr[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
            double cl = sqrt(dot3(cr, cr));
            ok = ok && cl > 1e-9 * dot3(e1, e1) + 1e-9 * dot3(e2, e2);
            for (int j = 0; j < 3 && ok; ++j) en[j] += cr[j] / cl;
        }
        /* where the faces fold back onto each other (cgal_mpi.off has fins: normals 3e-5 from
         * opposite), their mean normal is known only to the rounding of a face's normal over its
         * length, beyond 1e-9: such edges are left out */
        double el = sqrt(dot3(en, en));
        if (!ok || !(el > 1e-3)) continue;
        tg_surface_point p = tg_surface_edge(h, tg_rng_range(&r, 0.05, 0.95));
        double d[3] = {tg_rng_range(&r, -1, 1), tg_rng_range(&r, -1, 1), tg_rng_range(&r, -1, 1)};
        tg_trace_direction dv = vec(d[0], d[1], d[2]);
        edges++;
        if (tg_geodesic_trace(c.geo, &p, &dv, 0.0, NULL, t) != TG_OK) {
            CHECK_MSG(edge_refused > 0, "%s: e:%u refused (%.17g, %.17g, %.17g)", file, h, d[0], d[1], d[2]);
            edge_refused++;
            continue;
        }
        tg_trace_view v;
        tg_trace_get_view(t, &v);
        double dn = dot3(d, en) / (el * el), vt[3] = {d[0] - dn * en[0], d[1] - dn * en[1], d[2] - dn * en[2]};
        if (!(dot3(v.end.direction, vt) > 0.0)) backwards++;
        /* the normal, and the normal tilted by 1e-7 across the edge (off both faces at a ridge) */
        double u[3], ux[3], n1[3] = {en[0] / el, en[1] / el, en[2] / el};
        const double *ea = x + 3 * tr[h], *eb = x + 3 * tg_mesh_halfedge_to(m, h);
        for (int j = 0; j < 3; ++j) u[j] = eb[j] - ea[j];
        ux[0] = n1[1] * u[2] - n1[2] * u[1], ux[1] = n1[2] * u[0] - n1[0] * u[2], ux[2] = n1[0] * u[1] - n1[1] * u[0];
        double ul = sqrt(dot3(ux, ux));
        tg_trace_direction dnn = vec(n1[0], n1[1], n1[2]);
        if (tg_geodesic_trace(c.geo, &p, &dnn, 0.0, NULL, t) != TG_ERR_INVALID_ARGUMENT) edge_normal_kept++;
        for (int side = -1; side <= 1; side += 2) {
            double tilt = side * 1e-7 / ul;
            tg_trace_direction dt = vec(n1[0] + tilt * ux[0], n1[1] + tilt * ux[1], n1[2] + tilt * ux[2]);
            if (tg_geodesic_trace(c.geo, &p, &dt, 0.0, NULL, t) != TG_OK) edge_tilted_refused++;
            else if (tg_trace_get_view(t, &v), !(side * dot3(v.end.direction, ux) > 0.0)) backwards++;
        }
    }
    printf("tangent plane: %-18s %5d closed fans: %d of %d random vectors refused, normal refused at %d, tilted by "
           "1e-7 taken at %d; at %d edge points: %d random vectors refused, normal refused at %d, tilted by 1e-7 "
           "either way taken %d times; %d directions taken not within a right angle of the projection\n", file,
           vertices, refused, tried, vertices - normal_kept, vertices - tilted_refused, edges, edge_refused,
           edges - edge_normal_kept, 2 * edges - edge_tilted_refused, backwards);
    CHECK_EQ_INT(refused, 0);
    CHECK_EQ_INT(edge_refused, 0);
    CHECK_EQ_INT(edge_normal_kept, 0);
    CHECK_EQ_INT(edge_tilted_refused, 0);
    CHECK_EQ_INT(backwards, 0);
    CHECK_EQ_INT(normal_kept, 0);
    CHECK_EQ_INT(tilted_refused, 0);
    CHECK(vertices > (int)nvert / 2 && edges > 10 * per_vertex);
    free(nrm);
    free(closed);
    tg_trace_destroy(t);
    close_ctx(&c);
}

static void test_tangent_plane(void)
{
    /* the case */
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "cgal_mpi.off");
    if (m) {
        ctx c = open_ctx_for(m);
        tg_trace* t = NULL;
        CHECK_STATUS(tg_trace_create(NULL, &t), TG_OK);
        tg_surface_point p = tg_surface_vertex(81);
        tg_trace_view v = trace_view(c.geo, t, p, vec(1.387, -1.317, -2.283), 0.1);
        check_trace("cgal_mpi v:81", c.mesh, &v, &p);
        CHECK_EQ_INT(v.end.status, TG_TRACE_COMPLETE);
        tg_trace_destroy(t);
        close_ctx(&c);
    }
    tangent_case("cgal_mpi.off", TG_TEST_WORK(200, 20));
    tangent_case("cgal_pinion.off", TG_TEST_WORK(40, 4));
    tangent_case("fcpw_kitten.obj", TG_TEST_WORK(2, 1));
}

static void test_limits_and_errors(void)
{
    nv = nf = 0;
    grid(8, 0.0, 0.0, 1.0, 0.0, NULL);
    ctx c = open_ctx();
    tg_trace* t = NULL;
    CHECK_STATUS(tg_trace_create(NULL, &t), TG_OK);
    tg_surface_point s = locate(c.mesh, 0.1, 0.13, 0.0), bad;
    tg_trace_direction d = vec(1, 0.3, 0), dz = vec(0, 0, 1);
    /* the step limit: the walk stops after entering that many faces */
    tg_trace_options o = {5, NULL, NULL};
    CHECK_STATUS(tg_geodesic_trace(c.geo, &s, &d, 0.8, &o, t), TG_OK);
    tg_trace_view v;
    tg_trace_get_view(t, &v);
    check_trace("step limit", c.mesh, &v, &s);
    CHECK_EQ_INT(v.end.status, TG_TRACE_STEP_LIMIT);
    CHECK_EQ_INT(v.end.crossings + v.end.vertices, 6); /* the sixth crossing could not enter its face */
    CHECK(v.end.length > 0.0 && v.end.length < 0.8);

    /* errors: the library says invalid argument and leaves the trace empty */
    const double nan = NAN, inf = INFINITY;
    tg_trace_direction zero = vec(0, 0, 0), vnan = vec(nan, 1, 0), vinf = vec(inf, 0, 0), anan = ang(nan),
                       ainf = ang(-inf), kind = d;
    kind.kind = (tg_trace_direction_kind)7;
    const tg_trace_direction* bad_dirs[] = {&zero, &vnan, &vinf, &anan, &ainf, &kind, &dz};
    for (size_t i = 0; i < sizeof bad_dirs / sizeof bad_dirs[0]; ++i) {
        CHECK_STATUS(tg_geodesic_trace(c.geo, &s, bad_dirs[i], 0.5, NULL, t), TG_ERR_INVALID_ARGUMENT);
        tg_trace_get_view(t, &v);
        CHECK_EQ_INT(v.point_count, 0);
    }
    const double bad_lengths[] = {-1.0, -0.0 - 1e-300, nan, inf};
    for (size_t i = 0; i < 4; ++i)
        CHECK_STATUS(tg_geodesic_trace(c.geo, &s, &d, bad_lengths[i], NULL, t), TG_ERR_INVALID_ARGUMENT);
    tg_surface_point bad_points[] = {tg_surface_vertex(100000), tg_surface_face((uint32_t)nf, 1, 0, 0),
                                     tg_surface_face(0, 0.5, 0.6, 0.1), tg_surface_edge(0, 1.5), tg_surface_edge(3 * (uint32_t)nf, 0.5)};
    for (size_t i = 0; i < 5; ++i)
        CHECK_STATUS(tg_geodesic_trace(c.geo, &bad_points[i], &d, 0.5, NULL, t), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_trace(NULL, &s, &d, 0.5, NULL, t), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_trace(c.geo, NULL, &d, 0.5, NULL, t), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_trace(c.geo, &s, NULL, 0.5, NULL, t), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_trace(c.geo, &s, &d, 0.5, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    /* perpendicular to the surface at a vertex and at an edge point too */
    bad = tg_surface_vertex(40);
    CHECK_STATUS(tg_geodesic_trace(c.geo, &bad, &dz, 0.5, NULL, t), TG_ERR_INVALID_ARGUMENT);
    bad = tg_surface_edge(7, 0.5);
    CHECK_STATUS(tg_geodesic_trace(c.geo, &bad, &dz, 0.5, NULL, t), TG_ERR_INVALID_ARGUMENT);
    /* nearly perpendicular, but not within 1e-9: accepted */
    tg_trace_direction steep = vec(1e-6, 0, 1);
    CHECK_STATUS(tg_geodesic_trace(c.geo, &s, &steep, 0.5, NULL, t), TG_OK);
    tg_trace_get_view(t, &v);
    CHECK_NEAR(v.end.xyz[0], 0.6, 1e-9);
    /* the batch: the same checks, before any walk; out_ends untouched */
    tg_surface_point starts[3] = {s, s, s};
    tg_trace_direction dirs[3] = {d, d, dz};
    double lens[3] = {0.1, 0.2, 0.3};
    tg_trace_end ends[3];
    memset(ends, 0xAB, sizeof ends);
    unsigned char pattern[sizeof ends];
    memset(pattern, 0xAB, sizeof pattern);
    CHECK_STATUS(tg_geodesic_trace_batch(c.geo, starts, dirs, lens, 3, NULL, 2, ends), TG_ERR_INVALID_ARGUMENT);
    CHECK(memcmp(ends, pattern, sizeof ends) == 0);
    dirs[2] = d, lens[1] = -1.0;
    CHECK_STATUS(tg_geodesic_trace_batch(c.geo, starts, dirs, lens, 3, NULL, 2, ends), TG_ERR_INVALID_ARGUMENT);
    CHECK(memcmp(ends, pattern, sizeof ends) == 0);
    lens[1] = 0.2;
    CHECK_STATUS(tg_geodesic_trace_batch(c.geo, starts, dirs, lens, 3, NULL, -1, ends), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_trace_batch(c.geo, NULL, dirs, lens, 3, NULL, 1, ends), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_trace_batch(c.geo, NULL, NULL, NULL, 0, NULL, 1, NULL), TG_OK);
    CHECK_STATUS(tg_geodesic_trace_batch(c.geo, starts, dirs, lens, 3, NULL, 2, ends), TG_OK);
    CHECK_EQ_INT(ends[2].status, TG_TRACE_COMPLETE);
    CHECK_EQ_STR(tg_trace_status_name(TG_TRACE_STALLED), "stalled");
    CHECK_EQ_STR(tg_trace_status_name((tg_trace_status)99), "unknown");
    tg_trace_destroy(t);
    close_sheet(&c);
}

/* ---- corpus meshes: properties ---- */

static const char* corpus[] = {"nvd_spot.obj", "oded_spot_low_resolution.obj", "c3d_woody.obj", "cgal_pinion.off",
                               "gc_moebius.obj", "assimp_Spider_binary.stl", "cgal_anchor.off", "c3d_suzanne.obj"};

/* A random direction: a random vector, or a random angle. */
static tg_trace_direction random_direction(tg_rng* r)
{
    if (tg_rng_next(r) & 1) return ang(tg_rng_range(r, -10, 10));
    return vec(tg_rng_range(r, -1, 1), tg_rng_range(r, -1, 1), tg_rng_range(r, -1, 1));
}

/* A trace of length L and the exact path back from its end: never longer than L. */
static void corpus_path_back(const char* name, ctx* c, double diag, int count)
{
    tg_trace* t = NULL;
    CHECK_STATUS(tg_trace_create(NULL, &t), TG_OK);
    tg_rng r = {2024};
    int done = 0, equal = 0;
    for (int i = 0; i < count; ++i) {
        tg_surface_point s = tg_test_random_surface_point(&r, c->mesh, NULL);
        tg_trace_direction d = random_direction(&r);
        double len = tg_rng_range(&r, 0.0, 0.2) * diag;
        tg_status st = tg_geodesic_trace(c->geo, &s, &d, len, NULL, t);
        if (st == TG_ERR_INVALID_ARGUMENT && d.kind == TG_TRACE_VECTOR) continue; /* perpendicular: rare */
        if (st == TG_ERR_INVALID_ARGUMENT) continue; /* an angle in a zero-area face */
        CHECK_STATUS(st, TG_OK);
        tg_trace_view v;
        tg_trace_get_view(t, &v);
        char what[128];
        snprintf(what, sizeof what, "%s trace %d", name, i);
        if (check_trace(what, c->mesh, &v, &s)) break;
        if (v.end.status == TG_TRACE_COMPLETE) CHECK(v.end.length == len);
        tg_surface_point e = v.end.point;
        CHECK_STATUS(tg_geodesic_path(c->geo, c->ws, &s, &e, NULL, c->path), TG_OK);
        tg_path_view pv;
        tg_path_get_view(c->path, &pv);
        CHECK_MSG(pv.length <= v.end.length * (1 + 1e-9) + 1e-12 * diag,
                  "%s: walked %.17g, the exact path back is longer: %.17g", what, v.end.length, pv.length);
        equal += fabs(pv.length - v.end.length) <= 1e-9 * diag;
        done++;
    }
    printf("%-32s %4d traces, %4d as long as the exact path back\n", name, done, equal);
    tg_trace_destroy(t);
}

/* From a vertex along the first segment of its exact path to another vertex, for that path's
 * length: the walk ends at that vertex where the path passes no vertex. */
static void corpus_vertex_paths(const char* name, ctx* c, double diag, int count)
{
    tg_trace* t = NULL;
    CHECK_STATUS(tg_trace_create(NULL, &t), TG_OK);
    tg_rng r = {99};
    size_t nv_ = tg_mesh_vertex_count(c->mesh);
    int tried = 0, used = 0;
    double worst = 0.0;
    for (int i = 0; i < count; ++i) {
        tg_surface_point a = tg_surface_vertex((uint32_t)(tg_rng_next(&r) % nv_));
        tg_surface_point b = tg_surface_vertex((uint32_t)(tg_rng_next(&r) % nv_));
        if (tg_surface_point_validate(c->mesh, &a, NULL) || tg_surface_point_validate(c->mesh, &b, NULL)) continue;
        CHECK_STATUS(tg_geodesic_path(c->geo, c->ws, &a, &b, NULL, c->path), TG_OK);
        tg_path_view pv;
        tg_path_get_view(c->path, &pv);
        if (pv.point_count < 3) continue; /* unreachable, or one segment along an edge */
        tried++;
        bool through = false;
        for (size_t k = 1; k + 1 < pv.point_count; ++k) through |= pv.points[k].kind != TG_SURFACE_EDGE;
        if (through) continue;
        const double* x = pv.xyz;
        tg_trace_direction d = vec(x[3] - x[0], x[4] - x[1], x[5] - x[2]);
        tg_status st = tg_geodesic_trace(c->geo, &a, &d, pv.length, NULL, t);
        if (st == TG_ERR_INVALID_ARGUMENT) continue; /* the first segment too short for a direction */
        CHECK_STATUS(st, TG_OK);
        tg_trace_view v;
        tg_trace_get_view(t, &v);
        double err = tg_test_dist3(v.end.xyz, x + 3 * (pv.point_count - 1)) / diag;
        if (err > worst) worst = err;
        CHECK_MSG(err <= 1e-9, "%s: trace from v:%u along its path to v:%u ends %.3g of the diagonal from it (%s)",
                  name, a.index, b.index, err, tg_trace_status_name(v.end.status));
        used++;
    }
    printf("%-32s %4d vertex paths, %4d through no vertex, traced to within %.3g of the diagonal\n", name, tried, used,
           worst);
    tg_trace_destroy(t);
}

/* The batch equals single calls, bit for bit, on 1, 2 and 3 threads. */
static void corpus_batch(const char* name, ctx* c, double diag, int count)
{
    tg_surface_point* s = malloc((size_t)count * sizeof *s);
    tg_trace_direction* d = malloc((size_t)count * sizeof *d);
    double* len = malloc((size_t)count * sizeof *len);
    tg_trace_end* single = malloc((size_t)count * sizeof *single);
    tg_trace_end* batch = malloc((size_t)count * sizeof *batch);
    tg_trace* t = NULL;
    CHECK_STATUS(tg_trace_create(NULL, &t), TG_OK);
    tg_rng r = {7};
    int n = 0;
    while (n < count) {
        s[n] = tg_test_random_surface_point(&r, c->mesh, NULL);
        d[n] = random_direction(&r);
        len[n] = tg_rng_range(&r, 0.0, 0.5) * diag;
        if (tg_geodesic_trace(c->geo, &s[n], &d[n], len[n], NULL, t) != TG_OK) continue;
        tg_trace_view v;
        tg_trace_get_view(t, &v);
        single[n++] = v.end;
    }
    for (int threads = 1; threads <= 3; ++threads) {
        memset(batch, 0, (size_t)count * sizeof *batch);
        CHECK_STATUS(tg_geodesic_trace_batch(c->geo, s, d, len, (size_t)count, NULL, threads, batch), TG_OK);
        int differ = 0;
        for (int i = 0; i < count; ++i) differ += memcmp(&single[i], &batch[i], sizeof single[i]) != 0;
        CHECK_MSG(differ == 0, "%s: %d of %d batch ends on %d threads differ from single calls", name, differ, count, threads);
    }
    tg_trace_destroy(t);
    free(s), free(d), free(len), free(single), free(batch);
}

static void test_corpus(void)
{
    for (size_t i = 0; i < sizeof corpus / sizeof corpus[0]; ++i) {
        tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), corpus[i]);
        if (!m) continue;
        ctx c = open_ctx_for(m);
        double centre[3], diag = tg_test_mesh_box(m, centre);
        corpus_path_back(corpus[i], &c, diag, TG_TEST_WORK(150, 25));
        corpus_vertex_paths(corpus[i], &c, diag, TG_TEST_WORK(60, 10));
        corpus_batch(corpus[i], &c, diag, TG_TEST_WORK(300, 60));
        close_ctx(&c);
    }
}

int main(void)
{
    test_flat();
    test_grid_lines();
    test_prism();
    test_cube();
    test_zero_area();
    test_book();
    test_scale();
    test_any_scale();
    test_direction_length();
    test_tangent_plane();
    test_limits_and_errors();
    test_corpus();
    return tg_test_finish();
}
