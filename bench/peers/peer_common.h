// peer_common.h - shared plumbing of the peer comparators: query/distance files (the formats of
// bench/bench_closest.c), timing, medians, heap usage. Header-only; C++17.
#ifndef TG_PEER_COMMON_H
#define TG_PEER_COMMON_H

#include <malloc.h>
#include <trigeo.h>

#include "../bench_common.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace peer {

[[noreturn]] inline void die(const char* msg, const std::string& arg)
{
    std::fprintf(stderr, "peer: %s %s\n", msg, arg.c_str());
    std::exit(2);
}

inline double now() { return bench_wall(); }

inline double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// Bytes currently allocated from the C heap (small blocks plus mmapped ones).
inline double heap_bytes()
{
    struct mallinfo2 mi = mallinfo2();
    return (double)mi.uordblks + (double)mi.hblkhd;
}

inline std::vector<double> read_array(const std::string& path, const char* magic, int per)
{
    FILE* f = std::fopen(path.c_str(), "rb");
    char m[8];
    uint64_t n = 0;
    if (!f) die("cannot read", path);
    if (std::fread(m, 1, 8, f) != 8 || std::memcmp(m, magic, 8) || std::fread(&n, sizeof n, 1, f) != 1)
        die("bad file", path);
    std::vector<double> v((size_t)n * (size_t)per);
    if (std::fread(v.data(), sizeof(double), v.size(), f) != v.size()) die("bad file", path);
    std::fclose(f);
    return v;
}

inline void write_distances(const std::string& path, const std::vector<double>& d)
{
    FILE* f = std::fopen(path.c_str(), "wb");
    uint64_t n = d.size();
    if (!f) die("cannot write", path);
    std::fwrite("TGDIST01", 1, 8, f);
    std::fwrite(&n, sizeof n, 1, f);
    std::fwrite(d.data(), sizeof(double), d.size(), f);
    if (std::fclose(f)) die("cannot write", path);
}

inline tg_mesh* load(const char* path)
{
    tg_mesh* m = nullptr;
    tg_diag d;
    if (tg_mesh_load(path, TG_FORMAT_AUTO, nullptr, &d, &m) != TG_OK) die("cannot load", path);
    return m;
}

// Times the query files argv[first..argc) with 1 and 2 threads (OpenMP over the points in file
// order; medians of reps passes), writes the squared distances to FILE.<name>.d and prints
// "<name> FILE faces build_s bytes_per_face ns_1t ns_2t". query(p) returns the squared distance
// from the point p[0..2] to the mesh and must be safe to call from several threads.
// With TG_BENCH_THREADS=1 in the environment only the 1-thread passes run (ns_2t prints as nan):
// for timing a whole process that answers the queries on one thread. TG_BENCH_CLOCK=thread times
// the 1-thread passes by thread CPU time (bench_pass_clock in bench/bench_common.h).
template <class Query>
inline void run_query_files(int argc, char** argv, int first, int reps, const char* name, size_t nf, double build,
                            double bytes, Query query)
{
    for (int a = first; a < argc; ++a) {
        std::vector<double> q = read_array(argv[a], "TGQUERY1", 3);
        const long n = (long)(q.size() / 3);
        std::vector<double> d(n);
        double ns[2] = {NAN, NAN};
        const int max_threads = bench_max_threads();
        for (int threads = 1; threads <= max_threads; ++threads) {
            std::vector<double> tt;
            for (int r = 0; r < reps; ++r) {
                double t0 = bench_pass_clock(threads);
#ifdef _OPENMP
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1024)
#endif
                for (long i = 0; i < n; ++i) d[i] = query(&q[3 * i]);
                tt.push_back(bench_pass_clock(threads) - t0);
            }
            ns[threads - 1] = 1e9 * median(tt) / (double)n;
        }
        write_distances(std::string(argv[a]) + "." + name + ".d", d);
        std::printf("%s %s %zu %.4f %.1f %.0f %.0f\n", name, argv[a], nf, build, bytes / (double)nf, ns[0], ns[1]);
        std::fflush(stdout);
    }
}

} // namespace peer

#endif
