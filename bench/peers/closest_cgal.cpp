// closest_cgal.cpp - peer comparator for bench_closest: CGAL AABB_tree over a triangle soup
// (Simple_cartesian<double>, AABB_triangle_primitive), closest_point_and_primitive after build()
// and accelerate_distance_queries().
// usage: closest_cgal MESH REPS QFILE...   (output format of `bench_closest run`:
//   "cgal QFILE faces build_s bytes_per_face ns_1t ns_2t"; writes QFILE.cgal.d)
// Build time covers making the triangle vector, the tree and its distance-query accelerator;
// bytes are the growth of the C heap over that (mallinfo2), excluding the tg_mesh.
#include "peer_common.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <memory>

namespace {

typedef CGAL::Simple_cartesian<double> K;
typedef std::vector<K::Triangle_3>::const_iterator Iterator;
typedef CGAL::AABB_triangle_primitive<K, Iterator> Primitive;
typedef CGAL::AABB_traits<K, Primitive> Traits;
typedef CGAL::AABB_tree<Traits> Tree;

struct Built {
    std::vector<K::Triangle_3> tris;
    std::unique_ptr<Tree> tree;
};

} // namespace

int main(int argc, char** argv)
{
    if (argc < 4) peer::die("usage: closest_cgal MESH REPS QFILE...", "");
    tg_mesh* m = peer::load(argv[1]);
    int reps = std::max(1, std::atoi(argv[2]));
    const size_t nf = tg_mesh_face_count(m);
    const double* x = tg_mesh_positions(m);
    const uint32_t* t3 = tg_mesh_triangles(m);
    std::vector<double> t;
    double bytes = 0.0;
    std::unique_ptr<Built> b;
    for (int r = 0; r < reps; ++r) {
        b.reset();
        double before = peer::heap_bytes();
        double t0 = peer::now();
        b.reset(new Built);
        b->tris.reserve(nf);
        for (size_t f = 0; f < nf; ++f) {
            const double *p = x + 3 * (size_t)t3[3 * f], *q = x + 3 * (size_t)t3[3 * f + 1], *s = x + 3 * (size_t)t3[3 * f + 2];
            b->tris.emplace_back(K::Point_3(p[0], p[1], p[2]), K::Point_3(q[0], q[1], q[2]), K::Point_3(s[0], s[1], s[2]));
        }
        b->tree.reset(new Tree(b->tris.begin(), b->tris.end()));
        b->tree->build();
        b->tree->accelerate_distance_queries();
        b->tree->closest_point(K::Point_3(0, 0, 0)); // any lazy construction happens here, single-threaded
        t.push_back(peer::now() - t0);
        bytes = peer::heap_bytes() - before;
    }
    double build = peer::median(t);
    const Tree& tree = *b->tree;

    peer::run_query_files(argc, argv, 3, reps, "cgal", nf, build, bytes, [&tree](const double* x) {
        K::Point_3 p(x[0], x[1], x[2]);
        auto pp = tree.closest_point_and_primitive(p);
        return CGAL::squared_distance(p, pp.first);
    });
    b.reset();
    tg_mesh_destroy(m);
    return 0;
}
