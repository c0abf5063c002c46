// field_cgal.cpp - exact geodesic distance fields: trigeo's tg_geodesic_field against CGAL's
// Surface_mesh_shortest_path (an exact window propagation too, Xin and Wang 2009), on the same
// mesh (loaded through trigeo, so both see identical vertices) from the same source vertices.
//
// usage: field_cgal MESH [--sources N] [--seed S] [--vertex V] [--no-cgal]
//   the sources are bench_field's (same generator and seed), or the vertex V. Per source prints:
//   | mesh | faces | source | trigeo s | trigeo windows | trigeo MiB | CGAL s | CGAL peak heap MiB | max rel diff |
//   (--no-cgal: trigeo only, for meshes where CGAL would need tens of GB)
// or:    field_cgal MESH --ref OUT.ref [--seed S] [--sample M]
//   writes reference distances for tests/test_field_cgal_ref.c: three sources (a vertex, an edge
//   point, a face point, picked from the seed) in trigeo's spec syntax, and for each CGAL's
//   distance at M sampled vertices (all of them when the mesh has fewer; default 300).
//   times are CPU seconds of the calling thread (CGAL: build_sequence_tree plus one distance query
//   per vertex; trigeo: tg_geodesic_field); "max rel diff" is max |d_cgal - d_trigeo| / max(d, 1e-12
//   diagonal) over the vertices. CGAL needs a manifold surface: meshes it cannot take are reported.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <cmath>
#include <ctime>

#include "peer_common.h"

#include <cstdio>
#include <vector>

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

/* CGAL's barycentric coordinates of face f follow its own corner order: which trigeo corner is
 * CGAL's coordinate k, found by evaluating the corner points. */
static void cgal_corner_order(const Shortest& sp, Mesh::Face_index f, const double* xyz, const uint32_t* tri, size_t tf,
                              int out[3])
{
    for (int k = 0; k < 3; ++k) {
        Shortest::Barycentric_coordinates b = {{k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0}};
        K::Point_3 p = sp.point(f, b);
        out[k] = -1;
        for (int c = 0; c < 3; ++c) {
            const double* q = xyz + 3 * (size_t)tri[3 * tf + (size_t)c];
            if (p.x() == q[0] && p.y() == q[1] && p.z() == q[2]) out[k] = c;
        }
    }
}

static int write_refs(const char* mesh_path, const char* out_path, unsigned long long seed, size_t sample)
{
    tg_mesh* m = peer::load(mesh_path);
    const size_t nv = tg_mesh_vertex_count(m), nf = tg_mesh_face_count(m);
    const double* xyz = tg_mesh_positions(m);
    const uint32_t* tri = tg_mesh_triangles(m);
    Mesh mesh;
    std::vector<Mesh::Vertex_index> vid(nv);
    for (size_t v = 0; v < nv; ++v) vid[v] = mesh.add_vertex(K::Point_3(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]));
    std::vector<Mesh::Face_index> fid(nf);
    for (size_t f = 0; f < nf; ++f) {
        fid[f] = mesh.add_face(vid[tri[3 * f]], vid[tri[3 * f + 1]], vid[tri[3 * f + 2]]);
        if (fid[f] == Mesh::null_face()) {
            std::fprintf(stderr, "field_cgal: %s: CGAL refuses face %zu (non-manifold): no reference\n", mesh_path, f);
            return 3;
        }
    }
    std::FILE* out = std::fopen(out_path, "w");
    if (!out) peer::die("cannot write", out_path);
    std::string name = mesh_path;
    name = name.substr(name.find_last_of('/') + 1);
    std::fprintf(out, "# CGAL %d.%d Surface_mesh_shortest_path distances for tests/test_field_cgal_ref.c\n",
                 CGAL_VERSION_MAJOR, CGAL_VERSION_MINOR);
    std::fprintf(out, "mesh %s\n", name.c_str());
    uint64_t s = seed * 0x9E3779B97F4A7C15ull + 7;
    auto next = [&s]() {
        s ^= s >> 12, s ^= s << 25, s ^= s >> 27;
        return s * 2685821657736338717ull;
    };
    auto unit = [&next]() { return (double)(next() >> 11) * (1.0 / 9007199254740992.0); };
    std::vector<uint32_t> verts;
    if (nv <= sample) {
        for (size_t v = 0; v < nv; ++v) verts.push_back((uint32_t)v);
    } else {
        for (size_t i = 0; i < sample; ++i) verts.push_back((uint32_t)(next() % nv));
    }
    for (int kind = 0; kind < 3; ++kind) {
        Shortest sp(mesh);
        uint32_t f = (uint32_t)(next() % nf);
        double bary[3] = {0, 0, 0}; /* trigeo corner order */
        char spec[160];
        if (kind == 0) {
            uint32_t v = tri[3 * (size_t)f + next() % 3];
            sp.add_source_point(vid[v]);
            std::snprintf(spec, sizeof spec, "v:%u", v);
        } else {
            if (kind == 1) {
                /* a point close to an edge (CGAL 5.5 misplaces sources exactly on an edge: the
                 * distance it gives to an end vertex of that very edge is below the Euclidean
                 * one; trigeo's edge sources are checked by symmetry and known answers instead) */
                uint32_t k = (uint32_t)(next() % 3);
                double t = 0.1 + 0.8 * unit();
                bary[k] = (1 - t) * (1 - 1e-3), bary[(k + 1) % 3] = t * (1 - 1e-3), bary[(k + 2) % 3] = 1e-3;
                std::snprintf(spec, sizeof spec, "f:%u:%.17g,%.17g,%.17g", f, bary[0], bary[1], bary[2]);
            } else {
                double u = 0.05 + 0.45 * unit(), w = 0.05 + 0.45 * unit();
                bary[0] = 1 - u - w, bary[1] = u, bary[2] = w;
                std::snprintf(spec, sizeof spec, "f:%u:%.17g,%.17g,%.17g", f, bary[0], bary[1], bary[2]);
            }
            {
                int order[3];
                cgal_corner_order(sp, fid[f], xyz, tri, f, order);
                if (order[0] < 0 || order[1] < 0 || order[2] < 0) peer::die("cannot map CGAL's corners", name);
                Shortest::Barycentric_coordinates b = {{bary[order[0]], bary[order[1]], bary[order[2]]}};
                sp.add_source_point(fid[f], b);
            }
        }
        sp.build_sequence_tree();
        std::fprintf(out, "source %s\n", spec);
        for (uint32_t v : verts) {
            double d = sp.shortest_distance_to_source_points(vid[v]).first;
            if (d < 0) std::fprintf(out, "%u inf\n", v);
            else std::fprintf(out, "%u %.17g\n", v, d);
        }
    }
    if (std::fclose(out) != 0) peer::die("write failed", out_path);
    tg_mesh_destroy(m);
    return 0;
}

int main(int argc, char** argv)
{
    if (argc >= 4 && std::string(argv[2]) == "--ref") {
        unsigned long long seed = 1;
        size_t sample = 300;
        for (int i = 4; i + 1 < argc; i += 2) {
            std::string a = argv[i];
            if (a == "--seed") seed = std::strtoull(argv[i + 1], nullptr, 10);
            else if (a == "--sample") sample = (size_t)std::strtoull(argv[i + 1], nullptr, 10);
            else peer::die("unknown argument", a);
        }
        return write_refs(argv[1], argv[3], seed, sample);
    }
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
        if (tg_geodesic_field(g, NULL, &src, 1, nullptr, ours.data(), &st) != TG_OK) peer::die("field failed", argv[1]);
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
