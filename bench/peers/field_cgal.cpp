// field_cgal.cpp - exact geodesic distance fields: trigeo's tg_geodesic_field against CGAL's
// Surface_mesh_shortest_path (an exact window propagation too, Xin and Wang 2009), on the same
// mesh (loaded through trigeo, so both see identical vertices) from the same source vertices.
//
// usage: field_cgal MESH [--sources N] [--seed S] [--vertex V] [--no-cgal]
//   the sources are bench_field's (same generator and seed), or the vertex V. Per source prints:
//   | mesh | faces | source | trigeo s | trigeo windows | trigeo MiB | CGAL s | CGAL peak heap MiB | max rel diff |
//   (--no-cgal: trigeo only, for meshes where CGAL would need tens of GB)
//   times are CPU seconds of the calling thread (CGAL: build_sequence_tree plus one distance query
//   per vertex; trigeo: tg_geodesic_field); "max rel diff" is max |d_cgal - d_trigeo| / max(d, 1e-12
//   diagonal) over the vertices. CGAL needs a manifold surface: meshes it cannot take are reported.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <cmath>
#include <ctime>

#include "peer_common.h"

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef CGAL::Surface_mesh_shortest_path_traits<K, Mesh> Traits;
typedef CGAL::Surface_mesh_shortest_path<Traits> Shortest;

static double thread_cpu()
{
    timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(int argc, char** argv)
{
    if (argc < 2) peer::die("usage: field_cgal MESH [--sources N] [--seed S] [--vertex V] [--no-cgal]", "");
    int sources = 3;
    long vertex = -1;
    bool cgal = true;
    unsigned long long seed = 1;
    for (int i = 2; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--sources" && i + 1 < argc)
            sources = std::atoi(argv[++i]);
        else if (a == "--seed" && i + 1 < argc)
            seed = std::strtoull(argv[++i], nullptr, 10);
        else if (a == "--vertex" && i + 1 < argc)
            vertex = std::atol(argv[++i]), sources = 1;
        else if (a == "--no-cgal")
            cgal = false;
        else
            peer::die("unknown argument", a);
    }
    tg_mesh* m = peer::load(argv[1]);
    const size_t nv = tg_mesh_vertex_count(m), nf = tg_mesh_face_count(m);
    const double* xyz = tg_mesh_positions(m);
    const uint32_t* tri = tg_mesh_triangles(m);
    std::string name = argv[1];
    name = name.substr(name.find_last_of('/') + 1);

    Mesh mesh;
    std::vector<Mesh::Vertex_index> vid(nv);
    for (size_t v = 0; v < nv; ++v) vid[v] = mesh.add_vertex(K::Point_3(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]));
    for (size_t f = 0; cgal && f < nf; ++f)
        if (mesh.add_face(vid[tri[3 * f]], vid[tri[3 * f + 1]], vid[tri[3 * f + 2]]) == Mesh::null_face()) {
            std::printf("| %s | %zu | - | - | - | - | CGAL's Surface_mesh refuses face %zu (non-manifold) |\n", name.c_str(), nf, f);
            return 0;
        }

    tg_geodesic* g = nullptr;
    if (tg_geodesic_create(m, nullptr, &g) != TG_OK) peer::die("solver", argv[1]);
    std::vector<double> ours(nv);
    double diag = 0;
    {
        const tg_mesh_report* r = tg_mesh_get_report(m);
        for (int k = 0; k < 3; ++k) diag += (r->bbox_max[k] - r->bbox_min[k]) * (r->bbox_max[k] - r->bbox_min[k]);
        diag = std::sqrt(diag);
    }
    uint64_t s = seed * 0x9E3779B97F4A7C15ull + 1; // bench_field's source generator
    for (int q = 0; q < sources; ++q) {
        s ^= s >> 12, s ^= s << 25, s ^= s >> 27;
        uint32_t v = vertex >= 0 ? (uint32_t)vertex : tri[(s * 2685821657736338717ull) % (3 * nf)];
        tg_surface_point src = tg_surface_vertex(v);
        tg_field_stats st;
        double t0 = thread_cpu();
        if (tg_geodesic_field(g, &src, 1, nullptr, ours.data(), &st) != TG_OK) peer::die("field failed", argv[1]);
        double t_ours = thread_cpu() - t0;
        if (!cgal) {
            std::printf("| %s | %zu | v:%u | %.3f | %.2fM | %.1f | - | - | - |\n", name.c_str(), nf, v, t_ours,
                        (double)st.windows_propagated * 1e-6, (double)st.peak_bytes / (1024.0 * 1024.0));
            continue;
        }

        double heap0 = peer::heap_bytes(), peak = heap0;
        t0 = thread_cpu();
        std::vector<double> theirs(nv);
        {
            Shortest sp(mesh);
            sp.add_source_point(vid[v]);
            sp.build_sequence_tree();
            peak = std::max(peak, peer::heap_bytes());
            for (size_t w = 0; w < nv; ++w) theirs[w] = sp.shortest_distance_to_source_points(vid[w]).first;
        }
        double t_cgal = thread_cpu() - t0;
        double worst = 0, worst_abs = 0, far = 0;
        size_t at = 0;
        for (size_t w = 0; w < nv; ++w) {
            if (!std::isfinite(ours[w]) || theirs[w] < 0) continue; // unreachable in both
            double den = std::max(ours[w], 1e-12 * diag);
            worst = std::max(worst, std::fabs(theirs[w] - ours[w]) / den);
            if (std::fabs(theirs[w] - ours[w]) > worst_abs) worst_abs = std::fabs(theirs[w] - ours[w]), at = w;
            far = std::max(far, ours[w]);
        }
        std::fprintf(stderr,
                     "field_cgal: %s v:%u: largest |difference| %.3g = %.2g of the largest distance %.17g (vertex %zu: "
                     "trigeo %.17g, CGAL %.17g)\n",
                     name.c_str(), v, worst_abs, far > 0 ? worst_abs / far : 0.0, far, at, ours[at], theirs[at]);
        std::printf("| %s | %zu | v:%u | %.3f | %.2fM | %.1f | %.3f | %.1f | %.1e |\n", name.c_str(), nf, v, t_ours,
                    (double)st.windows_propagated * 1e-6, (double)st.peak_bytes / (1024.0 * 1024.0), t_cgal,
                    (peak - heap0) / (1024.0 * 1024.0), worst);
        std::fflush(stdout);
    }
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
    return 0;
}
