// closest_embree.cpp - peer comparator for bench_closest: Embree 3 rtcPointQuery over a triangle
// geometry, with a closest-point callback that evaluates each candidate triangle in double with
// trigeo's public robust point-triangle kernel (tg_point_triangle_robust_3d) on the double mesh,
// and shrinks the (float) query radius to the best distance so far, rounded up.
// usage: closest_embree MESH REPS QFILE...   (output format of `bench_closest run`:
//   "embree QFILE faces build_s bytes_per_face ns_1t ns_2t"; writes QFILE.embree.d)
// Build: the device is created with "threads=1" so that the build time is single-threaded like
// trigeo's; bytes are those Embree reports through its memory monitor (BVH plus its float copy
// of the vertices and indices), excluding the tg_mesh.
#include "peer_common.h"

#include <embree3/rtcore.h>

#include <atomic>
#include <cmath>

namespace {

std::atomic<long long> g_embree_bytes{0}; // memory monitor total (Embree's callback has no state per device here)

bool monitor(void*, ssize_t bytes, bool)
{
    g_embree_bytes += (long long)bytes;
    return true;
}

struct Query {
    const double* xyz;
    const uint32_t* tri;
    double p[3];
    double best;
    uint32_t face;
};

bool closest_callback(RTCPointQueryFunctionArguments* args)
{
    Query* q = static_cast<Query*>(args->userPtr);
    const uint32_t* t = q->tri + 3 * (size_t)args->primID;
    tg_point_triangle r;
    tg_point_triangle_robust_3d(q->p, q->xyz + 3 * (size_t)t[0], q->xyz + 3 * (size_t)t[1], q->xyz + 3 * (size_t)t[2], &r);
    if (r.sqdist < q->best || (r.sqdist == q->best && args->primID < q->face)) {
        q->best = r.sqdist;
        q->face = args->primID;
        float rad = (float)std::sqrt(r.sqdist);
        args->query->radius = std::nextafter(rad, INFINITY);
        return true;
    }
    return false;
}

} // namespace

int main(int argc, char** argv)
{
    if (argc < 4) peer::die("usage: closest_embree MESH REPS QFILE...", "");
    tg_mesh* m = peer::load(argv[1]);
    int reps = std::max(1, std::atoi(argv[2]));
    const size_t nv = tg_mesh_vertex_count(m), nf = tg_mesh_face_count(m);
    const double* xyz = tg_mesh_positions(m);
    const uint32_t* tri = tg_mesh_triangles(m);

    RTCDevice device = rtcNewDevice("threads=1");
    if (!device) peer::die("rtcNewDevice failed", "");
    rtcSetDeviceMemoryMonitorFunction(device, monitor, nullptr);
    RTCScene scene = nullptr;
    std::vector<double> t;
    double bytes = 0.0;
    for (int r = 0; r < reps; ++r) {
        if (scene) rtcReleaseScene(scene);
        long long before = g_embree_bytes.load();
        double t0 = peer::now();
        scene = rtcNewScene(device);
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        float* v = (float*)rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv);
        unsigned* ix = (unsigned*)rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), nf);
        for (size_t i = 0; i < 3 * nv; ++i) v[i] = (float)xyz[i];
        std::memcpy(ix, tri, 3 * nf * sizeof(unsigned));
        rtcCommitGeometry(geom);
        rtcAttachGeometry(scene, geom);
        rtcReleaseGeometry(geom);
        rtcCommitScene(scene);
        t.push_back(peer::now() - t0);
        bytes = (double)(g_embree_bytes.load() - before);
    }
    double build = peer::median(t);

    peer::run_query_files(argc, argv, 3, reps, "embree", nf, build, bytes, [&](const double* x) {
        Query u{xyz, tri, {x[0], x[1], x[2]}, INFINITY, 0xFFFFFFFFu};
        RTCPointQuery pq;
        pq.x = (float)u.p[0], pq.y = (float)u.p[1], pq.z = (float)u.p[2];
        pq.time = 0.0f;
        pq.radius = INFINITY;
        RTCPointQueryContext ctx;
        rtcInitPointQueryContext(&ctx);
        rtcPointQuery(scene, &pq, &ctx, closest_callback, &u);
        return u.best;
    });
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
    tg_mesh_destroy(m);
    return 0;
}
