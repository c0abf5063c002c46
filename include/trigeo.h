/* trigeo.h - the public API of trigeo: distances and shortest paths on triangle meshes.
 *
 * This header is the API reference. Every declaration has a doc block stating its behaviour,
 * return values, parameter contracts (sizes, NULL-ability, units), complexity and thread-safety.
 *
 * Conventions:
 *  - Every fallible function returns tg_status (TG_OK == 0). On failure, *out is NULL, nothing
 *    leaks and the caller's state is unchanged.
 *  - Built objects (tg_mesh, tg_bvh, ...) are opaque and immutable after creation; queries on them
 *    are thread-safe. tg_x_destroy(NULL) is a no-op.
 *  - Options structs: a NULL pointer or a zero-initialised struct means "defaults". Every member
 *    is either honoured or refused by every call taking the struct (the table at
 *    tg_field_options).
 *  - Indices are 0-based uint32_t in file order; TG_NONE (0xFFFFFFFF) means "no such element".
 *  - Coordinates and lengths are double. The library never prints, exits, aborts or keeps mutable
 *    globals.
 *  - Supported coordinate range: every coordinate within +-1e150 (so that squared distances stay
 *    finite). Meshes beyond it load, report and write, but the distance entry points refuse them
 *    (tg_bvh_create, tg_geodesic_create: TG_ERR_UNSUPPORTED; the CLI names the range) rather
 *    than answer wrongly; query points beyond it are refused (TG_ERR_INVALID_ARGUMENT). Within
 *    it, distances, fields, paths, signs and winding numbers do not depend on the unit or the
 *    position of the coordinates (they are computed in frames scaled by powers of two): a mesh
 *    scaled by any factor and moved anywhere in range gives the same results times the factor,
 *    to rounding (bit for bit under powers of two), down to coordinate differences of normal
 *    doubles (about 1e-307; subnormal ones have fewer digits).
 *
 * One convention for every query (0.6):
 *    what                 rule
 *    parameter order      the built object (mesh, bvh, geodesic), the workspace, the inputs, the
 *                         options, `int threads` (batch calls only), the result object or the
 *                         main output array, the other outputs, out_stats last
 *    the solver           named `geodesic` in every prototype (`mesh`, `bvh` likewise)
 *    result objects       paths, traces, sparse matrices, Voronoi boundaries and isolines are all
 *                         created empty by tg_x_create(allocator, &x), filled by the query (which
 *                         replaces their content, reusing nothing the caller holds a view of),
 *                         read by tg_x_get_view and freed by tg_x_destroy; on error they are
 *                         left empty. No query returns a fresh object through `**out`.
 *    per-vertex outputs   out_vertex_distance, then out_vertex_label / out_vertex_angle; the
 *                         per-point ones out_point_distance; arrays the caller sizes; NULL where
 *                         the call says an output is optional
 *    single queries       take a workspace (NULL: a temporary one); tracing needs none (a walk's
 *                         state is a few locals, its polyline lives in the trace object)
 *    batch queries        (matrices, tg_geodesic_trace_batch, tg_bvh_*_batch) take `int threads`
 *                         after the options (0: the OpenMP default, 1: the calling thread only)
 *                         and make one scratch per thread themselves; no workspace
 *    empty inputs         a source list may be empty wherever sources are taken: no vertex is
 *                         reached (distance +inf, label TG_NONE, no isolines, a 0-row matrix)
 *    progress             every long call takes a progress callback in its options and stops
 *                         with TG_ERR_CANCELLED when it returns non-zero
 *
 * Compiles as C11 and as C++ (extern "C").
 */
#ifndef TRIGEO_H
#define TRIGEO_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* TG_API marks what libtrigeo exports: everything else in the library is hidden
 * (-fvisibility=hidden). On Windows it is dllexport while building the DLL (TG_BUILDING_DLL) and
 * dllimport for its users (unless TG_STATIC). */
#ifndef TG_API
#if defined(_WIN32) && !defined(TG_STATIC)
#if defined(TG_BUILDING_DLL)
#define TG_API __declspec(dllexport)
#else
#define TG_API __declspec(dllimport)
#endif
#elif defined(__GNUC__) || defined(__clang__)
#define TG_API __attribute__((visibility("default")))
#else
#define TG_API
#endif
#endif

/* ============================================================================================== */
/* Version                                                                                        */
/* ============================================================================================== */

#define TG_VERSION_MAJOR 0
#define TG_VERSION_MINOR 6
#define TG_VERSION_PATCH 9
/** Single integer for comparisons: major * 10000 + minor * 100 + patch. */
#define TG_VERSION (TG_VERSION_MAJOR * 10000 + TG_VERSION_MINOR * 100 + TG_VERSION_PATCH)

/* Changes in 0.6.9 (ABI-compatible with 0.6.0: same soname, no interface change):
 *  - Exact fields and paths on large meshes: the tables of the vertex most likely to be taken
 *    next (the front's next, a round's next, a thread's next item) are asked for from memory
 *    while the current one is worked on: armadillo_1m (1.38M faces) 0.97-0.98x the time of a
 *    field on one thread, about 0.98x on two, near exact paths 0.96x. The same results, bit for
 *    bit, as 0.6.8.
 *  - The test suite: make test within 5 minutes on a slow two-core machine (shorter waits before
 *    the Ctrl-C tests' signals, the sanitized tree with line tables only). */

/* Changes in 0.6.8 (ABI-compatible with 0.6.0: same soname, no interface change):
 *  - One field on several threads: each thread writes the windows it makes to its own free
 *    slots (those of the windows it crossed), so that thread 0's merge of a wave only adds
 *    each to its list (8 bytes read where a window is 64): 2-6% faster on two threads. Still the
 *    same bits for every thread count >= 2 (every corpus mesh on 2, 3 and 7 threads).
 *  - Fields may differ from 0.6.7's by rounding (within 3.4e-15 relative on the corpus): two
 *    windows of a list that start at the same point are trimmed in the order of their places in
 *    the list, no longer of their slots in the pool (which on several threads depend on which
 *    thread made them).
 *  - Exact paths (A*): the straight way from a window on to the target is computed only once the
 *    target has a distance to compare it with (the same runs, about 6% faster on near pairs). */

/* Changes in 0.6.7 (ABI-compatible with 0.6.0: same soname, no interface change):
 *  - One field on several threads: thread 0 merges each list of a wave as soon as it and those
 *    before it have crossed, crossing lists itself while the next is not done, instead of
 *    after the whole wave; the corner distances follow the wave. The same bits as 0.6.6 for
 *    every thread count (every corpus mesh on 2, 3 and 7 threads), a few percent faster on two
 *    threads. tg_field_stats.lead_seconds no longer holds the merges of the waves' lists, and
 *    wave_seconds does (the threads' busy time in the waves).
 *  - Fixed: an exact path across non-manifold edges could fail with TG_ERR_INTERNAL (its walk
 *    back, guided by the distances of a run ordered toward the target, found no way); such a
 *    path is now followed back on the whole field. */

/* Changes in 0.6.6 (ABI-compatible with 0.6.0: same soname, no interface change):
 *  - Exact fields are a little faster, exact as before, not the same bits as 0.6.5's (within
 *    4.6e-15): where an end of two overlapping windows' common part belongs to one of them, the
 *    distance it was made with decides the run next to that end (no square root); a child window
 *    is found dominated before its end distances are computed; a pair's crossings are not
 *    solved for when the quadratic that holds them shows none inside their overlap; a list's
 *    newest block keeps its count in the list's head, 15 ids a block (fcpw_kitten 5%,
 *    openfoam_DTC-scaled 5%, openfoam_terrain 2-3%, armadillo_1m 2% faster on one thread). A
 *    workspace takes about 72 bytes per window slot.
 *  - Seams zipped between coincident vertices (zero-area slivers with an edge of length 0): a
 *    source inside such a sliver lights the faces on both sides (its field could come out a few
 *    percent long, proven); an edge point of an edge of length 0 is taken as the vertex at its
 *    position (the exact path to one could fail with TG_ERR_INTERNAL). */

/* Changes in 0.6.5 (ABI-compatible with 0.6.0: same soname, no interface change):
 *  - Exact fields are faster, exact as before, not the same bits as 0.6.4's (within rounding):
 *    the windows of one edge are each trimmed against the next 3 by start, not every window they
 *    overlap (1.7-3% more windows cross; openfoam_terrain 7%, openfoam_DTC-scaled 5%, fcpw_kitten
 *    4% faster), with the ends' test compared squared; a list's windows are held in blocks of 14
 *    ids, walked a cache line at a time (the icosphere of level 8: 15.4 s -> 13.8 s on one
 *    thread, 11.5 -> 10.5 s on two). A workspace takes about 73 bytes per window slot. */

/* Changes in 0.6.4 (ABI-compatible with 0.6.0: same soname, no interface change):
 *  - Exact fields are faster with the same results (the same bits on every mesh tried): a pair
 *    of windows of one edge whose overlap's ends are each won by the window ending there is left
 *    as it is without solving for their crossings (fcpw_kitten, openfoam_DTC-scaled and
 *    openfoam_terrain 10-12% faster); a list's links are walked without reading its windows and
 *    the windows fetched together, the pool aligned to the 64-byte window (the icosphere of level
 *    8, 245M windows: 2x faster). A workspace takes 72 bytes per window slot (4 more). */

/* Changes in 0.6.3 (ABI-compatible with 0.6.0: same soname, no interface change):
 *  - One field on several threads (tg_field_options.threads > 1): the vertices a round takes off
 *    the front are processed on every thread too (their emissions, their neighbours relaxed
 *    along the edges, the lists they release), not only the lists; a round takes vertices only
 *    within the shortest edge at any of them, so none lowers another. Every N >= 2 still gives the
 *    same bits; tg_field_stats.waves and wave_lists count these waves too.
 *  - The field's front is an indexed heap (a vertex on it once, its key lowered in place): the
 *    same vertices leave it in the same order, so one-thread fields are bit-identical to 0.6.2's;
 *    tg_field_stats.max_queue counts vertices, no stale entries. A solver keeps each vertex's
 *    shortest edge (tg_geodesic_memory_bytes: 8 bytes more a vertex), a workspace each vertex's
 *    place on the front (4 bytes). */

/* Changes in 0.6.2 (ABI-compatible with 0.6.0: same soname, new entry points only):
 *  - Curves as sources of exact fields: tg_geodesic_curve_field (segments of polylines on the
 *    surface, mixed with point sources; exact: the insides of the segments are sources of
 *    parallel rays), tg_geodesic_boundary_segments (the mesh's boundary as segments),
 *    tg_surface_segment_validate, tg_surface_point_snap (a point within a tolerance of an edge or
 *    corner named by it: polylines given in coordinates), tg_geodesic_curve_path (the exact path
 *    from the nearest point of the curves), tg_geodesic_curve_voronoi (cells of curve sites),
 *    tg_geodesic_curve_distance_matrix (rows of curves). CLI: field --from curve:FILE and --from boundary,
 *    path --from curve:FILE|boundary; Python: Mesh.field(curve=, curves=, boundary=), field_at
 *    likewise, Mesh.curve_path, Mesh.boundary_segments().
 *  - tg_geodesic_centroidal_voronoi's cells are clipped at their boundaries inside the faces (a
 *    face split between the cells it meets; the energy integrated over the pieces) instead of
 *    lumped vertex areas: on a flat mesh its iterations are the continuous planar Lloyd's.
 *  - tg_geodesic_bezier_with: de Casteljau by exact shortest paths (tg_geodesic_bezier's method)
 *    or by the exact exp/log maps (TG_BEZIER_LOG_MAP); CLI path --bezier-method, Python
 *    Mesh.bezier(method=).
 *  - Exact isolines of curve fields (offset curves on the surface): tg_geodesic_curve_isolines
 *    (tg_geodesic_isolines is the same code with no segments). CLI: field --from curve:FILE|boundary
 *    --isolines/--isoline-count; Python: Mesh.isolines(curve=, curves=, boundary=).
 *  - A solver takes at most 536,870,909 vertices (one id fewer: it names a curve's windows). */

/* Changes in 0.6.1 (ABI-compatible with 0.6.0: same soname, new behaviour and entry points only):
 *  - Geometry on the exact maps: tg_geodesic_mean (the weighted Karcher mean, with a uniqueness
 *    certificate), tg_geodesic_centroidal_voronoi (geodesic Lloyd), tg_geodesic_bezier (de
 *    Casteljau on exact paths).
 *  - The certified distance between two meshes: tg_mesh_distance (one-sided Hausdorff as an
 *    interval within a tolerance, the realising point, mean and RMS as intervals).
 *  - The exact gradient of a field: tg_geodesic_field_gradient (per vertex and per face, nearest
 *    source, ties flagged).
 *  - Parallel transport: tg_geodesic_transport_field (from a source to every vertex, along the
 *    log map's exact paths), tg_path_transport and tg_polyline_transport (along a path).
 *  - tg_field_options.threads is honoured by every call on one field: tg_geodesic_field_at with
 *    points, tg_geodesic_log_map, tg_geodesic_voronoi (each source's run), tg_geodesic_isolines
 *    and tg_geodesic_farthest_point_sampling (each sample's run), which refused counts above 1;
 *    the matrices still refuse them (their rows are spread over their own `threads`).
 *  - tg_geodesic_log_map gives angle 0 at every vertex it does not reach, as documented (a
 *    vertex of another component could get an angle resolved from a previous run's records). */

/* Changes in 0.6 (ABI: soname libtrigeo.so.0.6; programs built against 0.5 must be rebuilt), one
 * convention for every query (the table above):
 *  - tg_geodesic_local_matrix, tg_geodesic_voronoi and tg_geodesic_isolines fill a result object
 *    the caller created (tg_sparse_matrix_create, tg_voronoi_boundaries_create,
 *    tg_isolines_create) and may reuse, as paths and traces are, instead of returning a fresh one
 *    through `**out`; on error the object is empty.
 *  - tg_geodesic_voronoi's outputs come in the common order: boundaries, out_vertex_distance,
 *    out_vertex_label (it was label, distance, boundaries).
 *  - tg_geodesic_local_matrix refuses options->limit = TG_FIELD_MAX_DISTANCE (it used to ignore
 *    it: the radius is its max_distance argument).
 *  - Every prototype names the solver `geodesic`; the log map's outputs are out_vertex_distance
 *    and out_vertex_angle (names only).
 *  - One field on several threads: tg_field_options.threads (and TG_THREADS_ALL) at the end of
 *    the struct, honoured by tg_geodesic_field and field_at without points, refused elsewhere;
 *    tg_field_stats gained the schedule's figures (rounds, waves, wave_lists, lead_seconds,
 *    wave_seconds) at its end.
 *  - Python and the CLI follow: one rule for isolines (a number is always a level; a count of
 *    evenly spaced levels is asked for by name) and for empty source lists (accepted, nothing
 *    reached). */

/* Changes in 0.5 (ABI: soname libtrigeo.so.0.5; programs built against 0.4 must be rebuilt):
 *  - tg_geodesic_path_through takes a const tg_path_options* (before the path): its progress
 *    callback can stop a route (TG_ERR_CANCELLED); the method must be TG_PATH_EXACT.
 *  - tg_trace_options gained progress / progress_user at its end: tg_geodesic_trace and
 *    tg_geodesic_trace_batch can be stopped (TG_ERR_CANCELLED).
 *  - Every call that takes a progress callback calls it about every 5 ms of work however the work
 *    is divided: the matrices also between rows (rows shorter than 5 ms never reported, so a batch
 *    of them could not be stopped), tg_geodesic_isolines while it traces the levels after the
 *    propagation, tg_geodesic_voronoi while it finds the boundaries, tg_render_png once more after
 *    its PNG encoding. A callback that asked to stop always gives TG_ERR_CANCELLED, even when the
 *    work had just finished. */

/** The library's version as "MAJOR.MINOR.PATCH". Static storage; never NULL; thread-safe. */
TG_API const char* tg_version(void);

/** The most threads a `threads` argument may ask for. The CLI (--threads) and the Python package
 *  (threads=) refuse larger counts with a clear error instead of letting the OpenMP runtime abort
 *  the process when it cannot start them all; 0 (one thread per core) is not limited. */
#define TG_MAX_THREADS 256

/* ============================================================================================== */
/* Status codes and diagnostics                                                                   */
/* ============================================================================================== */

/** The one list of status codes: X(enum name, short name, sentence). */
#define TG_STATUS_LIST(X)                                                                         \
    X(TG_OK, "ok", "success")                                                                     \
    X(TG_ERR_INVALID_ARGUMENT, "invalid_argument", "an argument is NULL, out of range or inconsistent") \
    X(TG_ERR_OUT_OF_MEMORY, "out_of_memory", "memory allocation failed or a size overflowed")     \
    X(TG_ERR_IO, "io", "a file could not be opened, read or written")                             \
    X(TG_ERR_PARSE, "parse", "the input is malformed")                                            \
    X(TG_ERR_INVALID_MESH, "invalid_mesh", "the data cannot describe a mesh (bad index, NaN or infinite coordinate)") \
    X(TG_ERR_UNSUPPORTED, "unsupported", "the format or feature is not supported")                \
    X(TG_ERR_CAPACITY, "capacity", "an output buffer is too small")                              \
    X(TG_ERR_CANCELLED, "cancelled", "the caller's progress callback asked to stop")                  \
    X(TG_ERR_INTERNAL, "internal", "a consistency check of the library failed (a bug: please report the input)")

/** Status returned by every fallible function. TG_OK is 0. */
typedef enum tg_status {
#define TG_STATUS_ENUM_(name, short_name, sentence) name,
    TG_STATUS_LIST(TG_STATUS_ENUM_)
#undef TG_STATUS_ENUM_
    TG_STATUS_COUNT_
} tg_status;

/** Short identifier of a status, e.g. "parse". Unknown values give "unknown". Never NULL. */
TG_API const char* tg_status_name(tg_status status);
/** One sentence describing a status. Unknown values give "unknown status". Never NULL. */
TG_API const char* tg_status_string(tg_status status);

/** Where and why input was rejected. Filled by parsers and validators when the caller passes a
 *  non-NULL tg_diag*; all strings are NUL-terminated (truncated if longer than their arrays).
 *  line and column are 1-based (0 = not applicable, e.g. for binary formats, where byte_offset is
 *  the offset of the offending byte). */
typedef struct tg_diag {
    char file[256];     /**< the path or name given to the reader ("" if none) */
    uint64_t line;      /**< 1-based line of the problem, 0 if not a text position */
    uint64_t column;    /**< 1-based column, 0 if unknown */
    uint64_t byte_offset; /**< offset from the start of the (decompressed) data */
    char message[256];  /**< one sentence, no trailing newline */
} tg_diag;

/* ============================================================================================== */
/* Allocator                                                                                      */
/* ============================================================================================== */

/** Memory hooks. Any NULL function pointer (or a NULL tg_allocator*) selects the C library's
 *  malloc/realloc/free for all three. The hooks must be thread-safe if objects are created from
 *  several threads. realloc(user, NULL, n) must behave as alloc; free(user, NULL) as a no-op. */
typedef struct tg_allocator {
    void* (*alloc)(void* user, size_t size);
    void* (*realloc)(void* user, void* ptr, size_t size);
    void (*free)(void* user, void* ptr);
    void* user;
} tg_allocator;

/* ============================================================================================== */
/* Mesh                                                                                           */
/* ============================================================================================== */

#define TG_NONE 0xFFFFFFFFu

/** An immutable triangle mesh with halfedge topology.
 *  Halfedge h = 3 * f + i runs from triangle corner i to corner (i + 1) % 3 of face f, so next is
 *  implicit. Its opposite is the halfedge of the other face on the same edge, running the other
 *  way; TG_NONE at boundary edges, at non-manifold edges (three or more faces), at edges whose two
 *  faces are oriented inconsistently, and on faces with a repeated vertex index. */
typedef struct tg_mesh tg_mesh;

typedef struct tg_mesh_options {
    const tg_allocator* allocator; /**< NULL: libc */
} tg_mesh_options;

/** Mesh file formats. TG_FORMAT_AUTO picks by file extension (before a trailing .gz), then by
 *  content sniffing. */
typedef enum tg_format {
    TG_FORMAT_AUTO = 0,
    TG_FORMAT_OBJ,
    TG_FORMAT_OFF,
    TG_FORMAT_PLY,
    TG_FORMAT_STL
} tg_format;

/** The validation report, computed once at creation. Edges are undirected vertex pairs used by
 *  at least one triangle, ignoring pairs (a, a) of triangles with a repeated index. */
typedef struct tg_mesh_report {
    uint64_t vertices;              /**< vertex records (file order) */
    uint64_t faces;                 /**< triangles (after fan triangulation) */
    uint64_t edges;                 /**< undirected edges */
    uint64_t components;            /**< components of triangles connected through shared vertices */
    uint64_t boundary_edges;        /**< edges used by exactly one triangle */
    uint64_t boundary_loops;        /**< connected components of the graph of boundary edges */
    uint64_t nonmanifold_edges;     /**< edges used by three or more triangles */
    uint64_t nonmanifold_vertices;  /**< vertices whose triangles form more than one fan (pinched) */
    uint64_t misoriented_edges;     /**< two-face edges whose faces run the same way along it */
    uint64_t degenerate_faces;      /**< repeated index, or cross product exactly zero in double */
    uint64_t duplicate_faces;       /**< faces beyond the first with the same vertex set */
    uint64_t unreferenced_vertices; /**< vertices used by no triangle */
    int64_t euler_characteristic;   /**< V_used - E + F */
    int64_t genus;                  /**< total genus when the mesh is a closed manifold, else -1 */
    int closed_manifold;            /**< 1 when no boundary, non-manifold edge or vertex, repeated index */
    double bbox_min[3];             /**< bounding box of all vertices (zeros for an empty mesh) */
    double bbox_max[3];
} tg_mesh_report;

/** Creates a mesh from caller arrays, which are copied (the caller keeps ownership).
 *  xyz: 3 * vertex_count finite doubles; triangles: 3 * face_count indices < vertex_count.
 *  vertex_count and face_count must be < 2^31 (halfedge ids are 32-bit).
 *  Returns TG_ERR_INVALID_MESH (with diag naming the element) for an out-of-range index or a
 *  non-finite coordinate, TG_ERR_INVALID_ARGUMENT for NULL arrays with non-zero counts.
 *  Complexity O(V + F) time and memory. Thread-safe (no shared state). */
TG_API tg_status tg_mesh_create(const double* xyz, size_t vertex_count, const uint32_t* triangles,
                         size_t face_count, const tg_mesh_options* options, tg_diag* diag,
                         tg_mesh** out_mesh);

/** Loads a mesh file (OBJ, OFF, PLY ascii/binary LE/BE, STL ascii/binary; gzip data, by the
 *  .gz extension or its magic bytes, is decompressed with zlib). Polygons are fan-triangulated;
 *  vertices keep file order (STL welds bit-identical positions in first-seen order). format:
 *  TG_FORMAT_AUTO or a forced format. Pipes and files whose size the system does not report
 *  (those of /proc) are read to their end; directories, devices and sockets are refused
 *  (TG_ERR_IO: /dev/urandom would never end).
 *  Counts are checked against the data: a binary STL whose facet count, an OFF whose vertex or
 *  face count, or a PLY whose element counts leave data unread (whole facet records, record
 *  lines, bytes) is refused with TG_ERR_PARSE naming both numbers, never loaded short; an ascii
 *  PLY line with more or fewer values than its record takes is named as such. Tolerated, with a
 *  warning: fewer bytes than a facet record after a binary STL's last facet, and blanks, line
 *  ends or NUL bytes after a binary PLY's last record (padding some writers add). Data that is
 *  none of the formats (no extension, no header, no OBJ statement) says so.
 *  Errors: TG_ERR_IO (cannot open/read), TG_ERR_PARSE (malformed), TG_ERR_INVALID_MESH,
 *  TG_ERR_UNSUPPORTED; diag (may be NULL) gets file, line or byte offset, and a sentence. On
 *  success diag->message is empty unless a warning was given: then it starts with "warning: "
 *  (the CLI prints it, Python issues a trigeo.LoadWarning). */
TG_API tg_status tg_mesh_load(const char* path, tg_format format, const tg_mesh_options* options,
                       tg_diag* diag, tg_mesh** out_mesh);

/** Parses a mesh from memory: the bytes of a mesh file, inflated first when they are gzip data
 *  (the gzip magic bytes 1f 8b; the same limits as files). name is used in diagnostics and, with
 *  TG_FORMAT_AUTO, for the extension; it may be NULL. Same errors and warnings as tg_mesh_load. */
TG_API tg_status tg_mesh_load_memory(const void* data, size_t size, const char* name, tg_format format,
                              const tg_mesh_options* options, tg_diag* diag, tg_mesh** out_mesh);

/** Frees a mesh. NULL is a no-op. */
TG_API void tg_mesh_destroy(tg_mesh* mesh);

/** Element counts. O(1). */
TG_API size_t tg_mesh_vertex_count(const tg_mesh* mesh);
TG_API size_t tg_mesh_face_count(const tg_mesh* mesh);
/** Array views valid for the mesh's lifetime: positions (3 doubles per vertex), triangles
 *  (3 indices per face), opposite halfedges (3 per face), one outgoing halfedge per vertex
 *  (TG_NONE for unreferenced vertices; a boundary halfedge where the vertex has one, so that a
 *  walk around the vertex covers its whole fan), and a component id per face (0-based, numbered
 *  in order of first face). */
TG_API const double* tg_mesh_positions(const tg_mesh* mesh);
TG_API const uint32_t* tg_mesh_triangles(const tg_mesh* mesh);
TG_API const uint32_t* tg_mesh_opposites(const tg_mesh* mesh);
TG_API const uint32_t* tg_mesh_vertex_halfedges(const tg_mesh* mesh);
TG_API const uint32_t* tg_mesh_face_components(const tg_mesh* mesh);
/** The report computed at creation. Never NULL for a valid mesh. */
TG_API const tg_mesh_report* tg_mesh_get_report(const tg_mesh* mesh);
/** Bytes owned by the mesh object (arrays and header). */
TG_API size_t tg_mesh_memory_bytes(const tg_mesh* mesh);

/** Halfedge helpers (inline): next and previous within a face, face of a halfedge. */
static inline uint32_t tg_halfedge_next(uint32_t h) { return h % 3 == 2 ? h - 2 : h + 1; }
static inline uint32_t tg_halfedge_prev(uint32_t h) { return h % 3 == 0 ? h + 2 : h - 1; }
static inline uint32_t tg_halfedge_face(uint32_t h) { return h / 3; }
/** Start and end vertex of halfedge h. h must be < 3 * face_count. */
TG_API uint32_t tg_mesh_halfedge_from(const tg_mesh* mesh, uint32_t h);
TG_API uint32_t tg_mesh_halfedge_to(const tg_mesh* mesh, uint32_t h);

/* ---- Writers ---- */

/** Writes the mesh as Wavefront OBJ ("v x y z" with %.17g, "f a b c" 1-based). */
TG_API tg_status tg_mesh_write_obj(const tg_mesh* mesh, const char* path, tg_diag* diag);

/** A named per-vertex scalar written as a PLY property (double). */
typedef struct tg_vertex_scalar {
    const char* name;     /**< property name: letters, digits, '_' */
    const double* values; /**< vertex_count values */
} tg_vertex_scalar;

/** Writes the mesh as binary little-endian PLY: vertex x,y,z (double) plus the given per-vertex
 *  scalar properties (double), face vertex_indices (uchar count, uint index). scalar_count may be
 *  0 (scalars NULL). */
TG_API tg_status tg_mesh_write_ply(const tg_mesh* mesh, const char* path, const tg_vertex_scalar* scalars,
                            size_t scalar_count, tg_diag* diag);

/** Reads the named per-vertex scalar property of a PLY file written by tg_mesh_write_ply (or any
 *  PLY whose vertex element has that numeric property). out_values: vertex_count doubles (NULL to
 *  ask for the count only); capacity: their number; *out_count receives the vertex count.
 *  TG_ERR_CAPACITY if capacity is too small; TG_ERR_PARSE if the property is absent. */
TG_API tg_status tg_ply_read_vertex_scalar(const char* path, const char* name, double* out_values,
                                    size_t capacity, size_t* out_count, tg_diag* diag);

/* ============================================================================================== */
/* Point-triangle distance (src/kernels) - section owned by the point-triangle kernels           */
/* ============================================================================================== */

/** The feature of a triangle on which a closest point lies. Derived from the final (s, t) (see
 *  tg_point_triangle): s == 0 && t == 0 -> VERTEX0; s == 1 -> VERTEX1; t == 1 -> VERTEX2;
 *  t == 0 -> EDGE01; s + t == 1 -> EDGE12; s == 0 -> EDGE20; otherwise FACE (the relative
 *  interior). Comparisons are exact, on the values returned in s and t. */
typedef enum tg_feature {
    TG_FEATURE_FACE = 0,
    TG_FEATURE_VERTEX0 = 1,
    TG_FEATURE_VERTEX1 = 2,
    TG_FEATURE_VERTEX2 = 3,
    TG_FEATURE_EDGE01 = 4,
    TG_FEATURE_EDGE12 = 5,
    TG_FEATURE_EDGE20 = 6
} tg_feature;

/** Result of a point-triangle distance query. The triangle is parametrised as
 *  T(s, t) = v0 + s (v1 - v0) + t (v2 - v0) over the domain s >= 0, t >= 0, s + t <= 1
 *  (seed 000 §1).
 *
 *  Invariants on every result (both variants, every dimension, every triangle):
 *   - all fields are finite (for finite inputs in the supported range, see below);
 *   - s, t in [0, 1] and the double sum s + t <= 1 (so (s, t) is in the domain);
 *   - bary = (1 - s - t, s, t): bary[0] is (1 - s) - t evaluated in doubles, except that it is
 *     exactly 0 when s + t == 1; it is > 0 otherwise, so the zero pattern of bary always agrees
 *     with `feature` (a vertex has s, t in {0, 1} exactly);
 *   - closest and T(s, t) agree up to rounding (a few units in the last place of the triangle's
 *     coordinates); sqdist is the squared distance from p to the computed closest point,
 *     evaluated from the displacement (closest - p) formed in coordinates local to the triangle,
 *     so it does not suffer from the rounding of closest itself when coordinates are large.
 *
 *  Degenerate triangles (robust variant): a zero-area triangle is the segment or point it spans.
 *  When v0 == v1, or v2 lies on the line v0 v1 as far as double arithmetic can tell (the computed
 *  height of v2 over that line is zero), the closest point is reported on the longest edge (the
 *  first of 01, 12, 20 on ties) or an endpoint of it, with the matching (s, t), bary and feature;
 *  when all three vertices coincide that is VERTEX0 with s = t = 0. A collinear triangle whose
 *  computed height is a rounding-level nonzero is handled as the sliver it then is: the closest
 *  point and distance are just as accurate, but (s, t) and the feature may name any edge or
 *  vertex that contains the point. */
typedef struct tg_point_triangle {
    double sqdist;     /**< squared distance from p to the triangle */
    double closest[3]; /**< closest point (3D; 2D entry points set closest[2] = 0; n-D entry points
                            write out_closest and store its first min(n, 3) coordinates here,
                            the rest 0) */
    double s, t;       /**< closest = v0 + s (v1 - v0) + t (v2 - v0) */
    double bary[3];    /**< (1 - s - t, s, t) */
    tg_feature feature; /**< the vertex, edge or face interior containing closest */
} tg_point_triangle;

/** Closest point of the triangle (v0, v1, v2) to p in 3D by the seed's region algorithm exactly
 *  as written (seed 000 §3, Listings 1-8: region classification of the unconstrained minimiser
 *  (be - cd, bd - ae) against det = |ac - b^2|, at most one division, deferred).
 *
 *  Accurate on well-shaped triangles: relative error of sqdist ~1e-14 away from the triangle,
 *  distance error below ~100 ulps of the local scale max_i |p - v_i| near it (measured by
 *  tests/test_point_triangle_gmp.c; the robust kernel stays below 5). Its premise
 *  ac - b^2 > 0 fails on zero-area triangles and rounding can misclassify needles and caps:
 *  there the result is still a valid point of the triangle (never NaN, (s, t) in the domain, so
 *  sqdist is never below the true squared distance by more than rounding) but not necessarily
 *  the closest one. In particular, when det evaluates to 0 (coincident or exactly collinear
 *  vertices) Listing 1 selects region 0 with s = t = 0 and the seed's 0/0 is taken as 0: the
 *  result is VERTEX0. Use tg_point_triangle_robust_3d unless you need the seed's exact
 *  behaviour.
 *
 *  p, v0, v1, v2: 3 doubles each, finite, with coordinate differences below 1e150 in magnitude
 *  (so squared lengths do not overflow). out: non-NULL. All pointers may alias each other
 *  except out. O(1), no allocation, thread-safe. */
TG_API void tg_point_triangle_3d(const double p[3], const double v0[3], const double v1[3], const double v2[3],
                          tg_point_triangle* out);

/** Closest point of the triangle (v0, v1, v2) to p in 3D, robust on every triangle: well-shaped,
 *  needles, caps, zero-area (repeated or collinear vertices), far from the origin.
 *
 *  Backward stable: the result is the exact answer for a triangle and point perturbed by a few
 *  units of roundoff times the local scale L = max_i |p - v_i|; since the distance is 1-Lipschitz
 *  in every input coordinate, the distance is accurate to a few ulps of L (and sqdist has a
 *  relative error of a few ulps once the distance is not tiny compared to L). Never divides by
 *  a quantity that can cancel to zero; never returns NaN or infinity for inputs in range.
 *  Degenerate triangles follow the convention documented at tg_point_triangle.
 *
 *  p, v0, v1, v2: 3 doubles each, finite, with coordinate differences below 1e150 in magnitude.
 *  out: non-NULL. Pointers may alias each other except out. O(1), no allocation, thread-safe. */
TG_API void tg_point_triangle_robust_3d(const double p[3], const double v0[3], const double v1[3],
                                 const double v2[3], tg_point_triangle* out);

/** 2D version of tg_point_triangle_3d (seed region algorithm): p and the vertices are 2 doubles;
 *  out->closest[2] is set to 0. Same contract and caveats. */
TG_API void tg_point_triangle_2d(const double p[2], const double v0[2], const double v1[2], const double v2[2],
                          tg_point_triangle* out);

/** 2D version of tg_point_triangle_robust_3d: p and the vertices are 2 doubles; out->closest[2] is
 *  set to 0. Same contract and guarantees. Results equal (==) those of the 3D kernel on the same
 *  triangle and point embedded at z = 0. */
TG_API void tg_point_triangle_robust_2d(const double p[2], const double v0[2], const double v1[2],
                                 const double v2[2], tg_point_triangle* out);

/** n-dimensional version of tg_point_triangle_3d (seed region algorithm; the seed notes that it
 *  holds for any n >= 2). p, v0, v1, v2: n doubles each. out_closest: n doubles receiving the
 *  closest point, or NULL; it must not overlap the inputs. out->closest receives its first
 *  min(n, 3) coordinates (the rest 0).
 *  n == 0 gives sqdist 0 and VERTEX0; n == 1 is accepted (a triangle on a line is a segment).
 *  O(n), no allocation, thread-safe. */
TG_API void tg_point_triangle_nd(size_t n, const double* p, const double* v0, const double* v1, const double* v2,
                          double* out_closest, tg_point_triangle* out);

/** n-dimensional version of tg_point_triangle_robust_3d; same arguments as tg_point_triangle_nd.
 *  For n == 3 the results equal (==, same operations in the same order) those of
 *  tg_point_triangle_robust_3d, for n == 2 those of tg_point_triangle_robust_2d, and likewise for
 *  the region variant. O(n), no allocation, thread-safe. */
TG_API void tg_point_triangle_robust_nd(size_t n, const double* p, const double* v0, const double* v1,
                                 const double* v2, double* out_closest, tg_point_triangle* out);


/* ============================================================================================== */
/* Surface points (src/mesh)                                                                      */
/* ============================================================================================== */

/** Kinds of surface point. */
typedef enum tg_surface_point_kind {
    TG_SURFACE_VERTEX = 0, /**< a mesh vertex: index = vertex id */
    TG_SURFACE_EDGE = 1,   /**< a point on an edge: index = halfedge id, t in [0, 1] from its start */
    TG_SURFACE_FACE = 2    /**< a point in a face: index = face id, bary = barycentric coordinates */
} tg_surface_point_kind;

/** A location on the mesh surface. Every API that takes a location takes one of these; tg_bvh
 *  turns any xyz into one (tg_bvh_locate). For TG_SURFACE_EDGE the point is
 *  (1 - t) * from(h) + t * to(h); for TG_SURFACE_FACE it is the barycentric combination of the
 *  face's corners 0, 1, 2 (bary sums to 1, each in [0, 1]). Unused fields are ignored. */
typedef struct tg_surface_point {
    tg_surface_point_kind kind;
    uint32_t index;
    double t;
    double bary[3];
} tg_surface_point;

/** Constructors (inline, no validation). */
static inline tg_surface_point tg_surface_vertex(uint32_t v)
{
    tg_surface_point p = {TG_SURFACE_VERTEX, v, 0.0, {0.0, 0.0, 0.0}};
    return p;
}
static inline tg_surface_point tg_surface_edge(uint32_t halfedge, double t)
{
    tg_surface_point p = {TG_SURFACE_EDGE, halfedge, t, {0.0, 0.0, 0.0}};
    return p;
}
static inline tg_surface_point tg_surface_face(uint32_t face, double b0, double b1, double b2)
{
    tg_surface_point p = {TG_SURFACE_FACE, face, 0.0, {b0, b1, b2}};
    return p;
}

/** Checks a surface point against a mesh: index in range, t in [0, 1], barycentrics finite, each
 *  in [-1e-12, 1 + 1e-12] and summing to 1 within 1e-9 (a tolerance for values read from text);
 *  a vertex must be referenced by some face. Returns TG_OK or TG_ERR_INVALID_ARGUMENT with a
 *  sentence in diag (may be NULL). O(1). Thread-safe. */
TG_API tg_status tg_surface_point_validate(const tg_mesh* mesh, const tg_surface_point* point, tg_diag* diag);

/** A valid surface point moved onto the edge or corner it lies within `tolerance` of: a face
 *  point's barycentrics at most tolerance become 0 (the others rescaled to sum to 1), an edge
 *  point's t within tolerance of 0 or 1 its end; then named by that feature (a face point with one
 *  zero weight an edge point, with two a vertex; an edge point at an end a vertex). For points
 *  located from coordinates that lie on an edge up to rounding (the crossings of a path written
 *  as xyz), so that they name the edge whose faces on both sides hold them (curves:
 *  tg_surface_segment_validate). An invalid point, a NULL mesh or a negative or NaN tolerance:
 *  the point unchanged. O(1). Thread-safe. (New in 0.6.2.) */
TG_API tg_surface_point tg_surface_point_snap(const tg_mesh* mesh, const tg_surface_point* point, double tolerance);

/** The 3D position of a (valid) surface point. O(1). Thread-safe. */
TG_API void tg_surface_point_position(const tg_mesh* mesh, const tg_surface_point* point, double out_xyz[3]);

/** The same location expressed canonically: a face point with a barycentric coordinate that is
 *  exactly 0 becomes an edge point, an edge point with t exactly 0 or 1 becomes a vertex; in a
 *  face with a repeated vertex index (a segment or a point) the repeated corner's weight goes to
 *  its first corner first, and an edge from a vertex to itself is that vertex. Never changes the
 *  position. O(1). */
TG_API tg_surface_point tg_surface_point_canonical(const tg_mesh* mesh, const tg_surface_point* point);


/* ============================================================================================== */
/* BVH, closest point, signed distance (src/spatial)                                              */
/* ============================================================================================== */

/** A bounding volume hierarchy over the triangles of a tg_mesh, for closest-point, signed-distance,
 *  winding-number and surface-location queries. Immutable after creation; every query is
 *  thread-safe given one workspace per thread. It keeps a pointer to the mesh (it does not copy
 *  the mesh), so the mesh must outlive the BVH.
 *
 *  Exactness: every closest-point answer is bit-identical to a linear scan of all faces with the
 *  project's robust point-triangle kernel (the tie rule below included). The tree only skips a
 *  face when its bounds (float, rounded outward, tested with error terms) prove that the kernel's
 *  value for it would exceed the best so far by more than the kernel's documented rounding error
 *  (taken as 2^-45 (d + D)^2 for distance d and mesh diagonal D; the kernel promises a few ulps).
 *  Ties: among faces at exactly the same squared distance, the lowest face index wins.
 *  Degenerate (zero-area) and duplicate faces are ordinary candidates. */
typedef struct tg_bvh tg_bvh;

/** Whether tg_bvh_create precomputes per-cluster dipole data for the fast (hierarchical)
 *  generalized winding number. */
typedef enum tg_bvh_winding_data {
    TG_BVH_WINDING_AUTO = 0,   /**< precompute exactly when TG_SIGN_AUTO would pick the winding number */
    TG_BVH_WINDING_ALWAYS = 1, /**< always precompute (512 bytes per BVH node, about 16 per face) */
    TG_BVH_WINDING_NEVER = 2   /**< never; winding numbers are then exact sums over all faces, O(F) */
} tg_bvh_winding_data;

/** Build options; a NULL pointer or a zero-initialised struct means defaults. */
typedef struct tg_bvh_options {
    const tg_allocator* allocator;    /**< NULL: libc. Also used by workspaces and batch queries. */
    uint32_t max_leaf_size;           /**< largest leaf, 1..15; 0: default (12) */
    tg_bvh_winding_data winding_data; /**< see tg_bvh_winding_data */
    /** threads for the build (OpenMP): 0 the OpenMP default, 1 this thread only (no thread is
     *  started), n at most n; negative: TG_ERR_INVALID_ARGUMENT. The tree is the same whatever. */
    int threads;
} tg_bvh_options;

/** Builds an 8-wide BVH over all faces of mesh: top levels split in Morton order, subtrees of at
 *  most 4096 faces by the binned surface area heuristic; 192-byte nodes holding axis-aligned and
 *  oriented boxes of their eight children; leaves store their triangles' vertices contiguously.
 *  With OpenMP the subtrees, leaves and boxes are built on options->threads threads (default:
 *  all cores); the tree is the same whatever the number of threads. With the default allocator on Linux the large arrays are
 *  advised as transparent huge pages.
 *
 *  Queries run kernels for the widest instruction set the processor offers, chosen here once:
 *  AVX-512 (F, VL, DQ, BW), AVX2, or portable C on any other processor (the library itself is
 *  built for the baseline of its target). Every level gives bit-identical answers. The
 *  environment variable TRIGEO_SIMD=portable|avx2|avx512, read by this call, lowers the level
 *  for the BVHs built while it is set (a level the processor lacks is not used; for testing and
 *  measuring).
 *
 *  Any valid mesh is accepted, including an empty one (every query then finds nothing).
 *  Returns TG_OK; TG_ERR_INVALID_ARGUMENT for a NULL mesh or out_bvh or an option out of range;
 *  TG_ERR_OUT_OF_MEMORY; TG_ERR_UNSUPPORTED beyond 2^31 faces or 32 GiB of leaf data, or for
 *  coordinates beyond +-1e150 (squared distances would overflow). On failure
 *  *out_bvh is NULL.
 *  Complexity: O(F log F) time, about 41 bytes per face (see tg_bvh_memory_bytes; nodes about 4,
 *  leaf blocks about 35 with the vertices they copy; more with winding data).
 *  Thread-safe (reads the mesh only). */
TG_API tg_status tg_bvh_create(const tg_mesh* mesh, const tg_bvh_options* options, tg_bvh** out_bvh);

/** Frees a BVH (not its mesh). NULL is a no-op. Workspaces created for it must not be used after. */
TG_API void tg_bvh_destroy(tg_bvh* bvh);

/** The mesh the BVH was built over. O(1). */
TG_API const tg_mesh* tg_bvh_mesh(const tg_bvh* bvh);

/** Bytes owned by the BVH (nodes, its copy of the triangles in tree order, winding data and
 *  header), excluding the tg_mesh. O(1). */
TG_API size_t tg_bvh_memory_bytes(const tg_bvh* bvh);

/** Per-thread query scratch (the traversal stack). A workspace may be used with the BVH it was
 *  created for, by one thread at a time. */
typedef struct tg_bvh_workspace tg_bvh_workspace;

/** Creates a workspace for bvh (a few kilobytes, allocated with the BVH's allocator).
 *  Returns TG_OK, TG_ERR_INVALID_ARGUMENT (NULL argument) or TG_ERR_OUT_OF_MEMORY. Thread-safe. */
TG_API tg_status tg_bvh_workspace_create(const tg_bvh* bvh, tg_bvh_workspace** out_workspace);

/** Frees a workspace. NULL is a no-op. */
TG_API void tg_bvh_workspace_destroy(tg_bvh_workspace* workspace);

/** The closest point of the mesh to a query point. */
typedef struct tg_closest_hit {
    uint32_t face;      /**< closest face (file order); TG_NONE when nothing was found */
    tg_feature feature; /**< face interior, edge or vertex of that face (kernel's classification) */
    double sqdist;      /**< squared distance; +infinity when nothing was found */
    double point[3];    /**< the closest point (zeros when nothing was found) */
    double bary[3];     /**< its barycentric coordinates on face (corners 0, 1, 2) */
} tg_closest_hit;

/** Finds the face closest to xyz with a squared distance <= max_dist_sq (pass INFINITY for no
 *  limit), with the kernel's closest point, barycentric coordinates and feature. When no face is
 *  that close (or the mesh is empty), returns TG_OK with out_hit->face == TG_NONE.
 *  Returns TG_ERR_INVALID_ARGUMENT for a NULL argument, an xyz not finite or beyond +-1e150, a NaN or negative
 *  max_dist_sq, or a workspace of another BVH.
 *  Complexity: O(log F) node visits for typical meshes, O(F) worst case. Thread-safe with one
 *  workspace per thread. */
TG_API tg_status tg_bvh_closest(const tg_bvh* bvh, tg_bvh_workspace* workspace, const double xyz[3],
                         double max_dist_sq, tg_closest_hit* out_hit);

/** tg_bvh_closest for count points (xyz: 3 * count doubles; out_hits: count entries, in input
 *  order). Queries are processed in Morton (Z-curve) order so that consecutive queries share cache
 *  lines, each seeded with the answer of its predecessor as an upper bound when that answer was
 *  far (a near one is soon matched by the search itself); the answers are identical to calling
 *  tg_bvh_closest on each point. threads: 0 = all cores (OpenMP), 1 = the
 *  calling thread only. Allocates O(count) scratch with the BVH's allocator.
 *  Returns TG_ERR_INVALID_ARGUMENT (NULL with count > 0, a non-finite point, a NaN or negative
 *  max_dist_sq, threads < 0; out_hits is then unspecified) or TG_ERR_OUT_OF_MEMORY.
 *  Thread-safe. */
TG_API tg_status tg_bvh_closest_batch(const tg_bvh* bvh, const double* xyz, size_t count,
                               double max_dist_sq, int threads, tg_closest_hit* out_hits);

/** How the inside/outside sign of a distance is decided. */
typedef enum tg_sign_method {
    TG_SIGN_AUTO = 0,         /**< pseudonormal for a consistently oriented closed manifold without
                                   degenerate faces (tg_mesh_report: closed_manifold, no misoriented
                                   edges, no degenerate faces), else winding */
    TG_SIGN_PSEUDONORMAL = 1, /**< angle-weighted pseudonormal at the closest feature (Baerentzen
                                   and Aanaes 2005); exact for closed manifolds */
    TG_SIGN_WINDING = 2       /**< generalized winding number >= 1/2 means inside (Jacobson et al.
                                   2013; far clusters by dipoles, Barill et al. 2018) */
} tg_sign_method;

/** The method TG_SIGN_AUTO resolves to for this BVH's mesh (other values are returned as is). */
TG_API tg_sign_method tg_bvh_sign_method(const tg_bvh* bvh, tg_sign_method method);

/** A closest point with an inside/outside sign. Faces are taken counter-clockwise seen from
 *  outside (right-hand normals point out): inside a closed, so oriented mesh is negative. */
typedef struct tg_signed_hit {
    tg_closest_hit hit;         /**< as tg_bvh_closest with no distance limit */
    double distance;            /**< sign * sqrt(hit.sqdist) */
    int sign;                   /**< -1 inside, +1 outside, 0 exactly on the surface */
    tg_sign_method method;      /**< the method used (never TG_SIGN_AUTO) */
    double winding_number;      /**< with TG_SIGN_WINDING: the generalized winding number, as it is
                                     (fractional on open meshes); otherwise 0 */
} tg_signed_hit;

/** Signed distance from xyz to the mesh. Signs and winding numbers do not depend on the unit of
 *  the coordinates: every intermediate is computed in a frame scaled by powers of two, so a mesh
 *  and its queries scaled uniformly (anywhere within +-1e150, down to meshes whose edges are
 *  normal doubles) or translated get the same signs, and winding numbers equal up to rounding
 *  (bit-identical under scaling by a power of two). With TG_SIGN_PSEUDONORMAL the sign is that of
 *  (xyz - closest point) . pseudonormal of the closest feature (face normal; sum of the two face
 *  normals of an edge; angle-weighted sum around a vertex); if that dot product is exactly 0 with
 *  a non-zero distance (degenerate normals), the winding number decides. With TG_SIGN_WINDING
 *  the point is inside when the winding number is >= 1/2. sign is 0 when hit.sqdist == 0.
 *  An empty mesh gives hit.face == TG_NONE, sign +1 and distance +infinity.
 *  Returns TG_ERR_INVALID_ARGUMENT for a NULL argument, a non-finite xyz, an unknown method or a
 *  workspace of another BVH. Complexity: one closest-point query, plus one winding-number
 *  evaluation for TG_SIGN_WINDING. Thread-safe with one workspace per thread. */
TG_API tg_status tg_bvh_signed_distance(const tg_bvh* bvh, tg_bvh_workspace* workspace,
                                 const double xyz[3], tg_sign_method method,
                                 tg_signed_hit* out_hit);

/** tg_bvh_signed_distance for count points (same ordering and threads as tg_bvh_closest_batch;
 *  answers identical to the single-point call). */
TG_API tg_status tg_bvh_signed_distance_batch(const tg_bvh* bvh, const double* xyz, size_t count,
                                       tg_sign_method method, int threads,
                                       tg_signed_hit* out_hits);

/** The generalized winding number of the mesh at xyz: (1/4pi) * sum of the signed solid angles
 *  of its triangles (Van Oosterom and Strackee 1983), scale-invariant as tg_bvh_signed_distance
 *  says (never NaN for coordinates within +-1e150). 1 inside and 0 outside a closed,
 *  consistently oriented mesh; fractional near holes. Evaluated hierarchically: clusters far from
 *  xyz (distance > 3 * their radius) contribute their dipole term, near ones the exact sum (the
 *  approximation is typically within 1e-2 of the exact value); without dipole data
 *  (TG_BVH_WINDING_NEVER) the exact sum over all faces. Finite everywhere (on the surface itself
 *  the value is one of the one-sided limits or in between).
 *  Returns TG_ERR_INVALID_ARGUMENT for a NULL argument, a non-finite xyz or a foreign workspace.
 *  Complexity: O(log F) clusters plus the triangles near xyz; O(F) without dipole data.
 *  Thread-safe with one workspace per thread. */
TG_API tg_status tg_bvh_winding_number(const tg_bvh* bvh, tg_bvh_workspace* workspace, const double xyz[3],
                                double* out_winding_number);

/** tg_bvh_winding_number for count points (xyz: 3 * count doubles; out_winding_numbers: count
 *  values in input order, identical to the single-point call), in Morton order on `threads`
 *  threads as tg_bvh_closest_batch. Errors: TG_ERR_INVALID_ARGUMENT (NULL with count > 0, a
 *  non-finite point, threads < 0), TG_ERR_OUT_OF_MEMORY. Thread-safe. */
TG_API tg_status tg_bvh_winding_number_batch(const tg_bvh* bvh, const double* xyz, size_t count, int threads,
                                             double* out_winding_numbers);

/** The surface point closest to xyz, canonical (tg_surface_point_canonical: a barycentric
 *  coordinate that is exactly 0 makes it an edge point, t exactly 0 or 1 a vertex). out_hit (may
 *  be NULL) receives the closest-point answer it came from. Returns TG_ERR_INVALID_ARGUMENT as
 *  tg_bvh_closest, and for an empty mesh (no surface point exists). Thread-safe with one
 *  workspace per thread. */
TG_API tg_status tg_bvh_locate(const tg_bvh* bvh, tg_bvh_workspace* workspace, const double xyz[3],
                        tg_surface_point* out_point, tg_closest_hit* out_hit);

/* ============================================================================================== */
/* Distance between two meshes (src/spatial/mesh_distance.c)                                      */
/* ============================================================================================== */

/** What the progress callback of tg_mesh_distance is told. */
typedef struct tg_mesh_distance_progress {
    double fraction; /**< rough share of the work done, in [0, 1]: A's vertices up to 0.25, its
                          faces (in chunks of 8192) up to 0.5, then the refinement, measured by
                          the interval's width against the tolerance on a log scale */
    double lower;    /**< the Hausdorff lower bound so far (0 until A's vertices are measured) */
    double upper;    /**< the largest upper bound still queued (+inf during the first pass, NaN
                          while the mean is refined) */
} tg_mesh_distance_progress;

/** Progress callback of tg_mesh_distance, called about every 5 ms of work from the calling
 *  thread: return 0 to go on, anything else to stop (TG_ERR_CANCELLED). */
typedef int (*tg_mesh_distance_progress_fn)(void* user, const tg_mesh_distance_progress* progress);

/** Options of tg_mesh_distance; NULL or all-zero means defaults. */
typedef struct tg_mesh_distance_options {
    const tg_allocator* allocator; /**< the call's scratch; NULL: mesh a's allocator */
    /** absolute width the Hausdorff interval is refined to (same unit as the coordinates, finite,
     *  >= 0); 0: 1e-9 of the larger bounding-box diagonal of the two meshes. Widths below
     *  4 * 2^-40 * (largest coordinate magnitude + diagonal) are raised to it (the rounding of
     *  the distances themselves; reported in tg_mesh_distance_result.tolerance). */
    double tolerance;
    /** absolute width the mean's and the RMS's intervals are refined to (finite, >= 0); 0: no
     *  refinement for them beyond what the Hausdorff interval needed (their intervals are then
     *  what A's own triangles give: of the order of the edge length where d varies) */
    double mean_tolerance;
    /** the most triangle pieces kept, A's faces included (memory: about 160 bytes each, A's
     *  faces and vertices included); 0: A's faces + 2^21 (about 330 MB of refinement); never
     *  fewer than A's faces. When reached, the refinement stops and the intervals, still valid,
     *  are wider than asked (the Hausdorff's: tg_mesh_distance_result.converged = 0). */
    size_t max_pieces;
    /** threads of the first pass (OpenMP; 0 all cores, 1 this thread, n at most n; negative or
     *  beyond TG_MAX_THREADS: TG_ERR_INVALID_ARGUMENT). The refinement runs on the calling
     *  thread. Every count gives the same bits. */
    int threads;
    tg_mesh_distance_progress_fn progress; /**< NULL: none */
    void* progress_user;                   /**< passed to progress */
} tg_mesh_distance_options;

/** The certified distance from mesh A to mesh B (every number in the coordinates' unit). */
typedef struct tg_mesh_distance_result {
    /** the one-sided Hausdorff distance h(A, B) = max over x on A of d(x, B) lies in
     *  [lower, upper]; upper - lower <= tolerance when converged */
    double lower, upper;
    double tolerance; /**< the absolute tolerance used (see tg_mesh_distance_options.tolerance) */
    int converged;    /**< 1: upper - lower <= tolerance; 0: max_pieces stopped the refinement */
    /** the point of A where the lower bound was realised: d(point, B) = distance, and
     *  lower = distance - 2^-40 * (magnitude + diagonal) (clamped at 0) */
    double distance;
    uint32_t face;      /**< A's face (file order) holding the point */
    double bary[3];     /**< the point's barycentrics on that face */
    double point[3];    /**< the point */
    uint32_t closest_face;    /**< B's face closest to the point (tg_bvh_closest's answer) */
    double closest_bary[3];   /**< the closest point's barycentrics on it */
    double closest_point[3];  /**< the closest point of B */
    double area;              /**< A's total area */
    /** the mean of d(x, B) over A's area lies in [mean_lower, mean_upper], the root mean square
     *  in [rms_lower, rms_upper] (0 when A's area is 0) */
    double mean_lower, mean_upper;
    double rms_lower, rms_upper;
    uint64_t pieces;  /**< triangle pieces made (A's faces and their subdivisions) */
    uint64_t queries; /**< closest-point queries on B */
} tg_mesh_distance_result;

/** The distance from mesh A to mesh B, certified: the one-sided Hausdorff distance
 *  h(A, B) = max over points x of A's faces of the distance d(x, B) to B's faces, as an interval
 *  [lower, upper] refined until upper - lower <= tolerance; the point of A realising the lower
 *  bound and its closest point on B; the mean and the RMS of d(x, B) over A's area as
 *  intervals; and the exact distance of every vertex of A. The symmetric Hausdorff distance is
 *  max(h(A, B), h(B, A)): two calls (the CLI's compare --symmetric and Python's
 *  distance_to(symmetric=True) make them), the interval [max of lowers, max of uppers].
 *
 *  Method (Tang, Lee, Kim 2009): every vertex of A is queried exactly (tg_bvh_closest); the
 *  lower bound is the largest distance realised at a point evaluated. Upper bounds per triangle
 *  T of A (and per piece of one), the least of:
 *   - interpolants: d(x, t) to one triangle t of B is convex, so it lies below the linear
 *     interpolant of its corner values, and d(x, B) <= the least of those interpolants over the
 *     corners' closest faces; its maximum over T is a two-variable linear program, bounded
 *     through its dual so that rounding cannot lower it;
 *   - edge split: two of those faces sharing an edge cut T by the bisector plane of their
 *     dihedral angle, each side bounded by its face at the polygon's vertices (convexity);
 *   - prisms (only for pieces that would otherwise be refined): T cut into the parts inside the
 *     prisms of nearby faces of B, where d(x, t) is the distance to t's plane, and the rest,
 *     bounded by convexity, each part only as tightly as it takes to spare T its refinement:
 *     exact where A lies on or near B across B's edges and vertices, and where B is convex
 *     under T; so a triangle of A over many of B's faces (B much finer than A) is mostly
 *     certified whole, its cost growing with the number of B's faces under it.
 *  Pieces whose bound exceeds lower + tolerance are taken worst first: the point where the
 *  interpolants peak is queried, then they are split in four at their edge midpoints (each
 *  queried). Where d is the distance to one or two planes of B the bounds are exact, so little
 *  is refined. The integrals of d and d^2 over each piece are bounded from above by the same
 *  interpolants (integrated exactly over the regions where each is least) and plane bounds, and
 *  from below by the concavity of d^2(x) - |x|^2 (for the distance to any set), the 1-Lipschitz
 *  bound, and the tangent planes at the piece's centroid of d(., t) for every face t of B within
 *  the piece's upper bound (a box query on the BVH): their least is concave, integrated exactly.
 *  These widths shrink quadratically with the pieces' size where d is the distance to planes,
 *  linearly elsewhere; options->mean_tolerance refines the widest pieces further.
 *
 *  The bounds are rigorous in real arithmetic; the computed distances carry rounding of a few
 *  ulps of the coordinates' magnitude, which every bound absorbs with a margin of 2^-40 *
 *  (largest coordinate magnitude + diagonal).
 *
 *  a: mesh A, with at least one face. b: a BVH over mesh B (tg_bvh_create), whose mesh has at
 *  least one face. Faces of either mesh may be degenerate (a zero-area face of A counts for the
 *  Hausdorff distance, not for the area; B's are ordinary candidates as in tg_bvh_closest);
 *  unreferenced vertices of A are not on its surface (they get a distance in
 *  out_vertex_distance but do not count). options: NULL for defaults.
 *  out_vertex_distance: NULL, or vertex_count(a) doubles: d(vertex, B), exactly as
 *  tg_bvh_closest. out_result: the numbers above.
 *
 *  Returns TG_OK (also when max_pieces stopped the refinement: converged = 0);
 *  TG_ERR_INVALID_ARGUMENT for a NULL a, b or out_result, a mesh without faces, a coordinate of A
 *  beyond +-1e150, a tolerance or mean_tolerance negative, NaN or infinite, a thread count out of
 *  range; TG_ERR_OUT_OF_MEMORY; TG_ERR_CANCELLED. On error out_result and out_vertex_distance are
 *  untouched (out_vertex_distance may be partly written when cancelled) and nothing leaks.
 *  Complexity: one closest-point query per vertex of A (on `threads` threads), then per face
 *  of A (on the same threads) some ten point-triangle distances and one box query on B's BVH,
 *  then 4 queries per refined piece (one thread): the pieces refined are those near the points
 *  where d comes within the tolerance of its maximum, typically a few per level of subdivision
 *  (log(edge / tolerance) levels). About 7x the vertices' closest-point pass on armadillo_1m
 *  against igl_armadillo at 1e-6 of the diagonal (BENCHMARKS.md). A much coarser than B costs
 *  more than that pass, which is then tiny: each face of A lies over many faces of B, which its
 *  corners do not see; the prisms of B's faces under it bound it, at a cost growing with their
 *  number (some 1-2 microseconds a face of B under A; tens of microseconds a face of A over 16
 *  of B's), so the whole takes about as long as the other direction, B to A (BENCHMARKS.md).
 *  Memory O(V + F + pieces). Thread-safe: the meshes and the BVH are only read (concurrent calls need distinct
 *  output arrays). (New in 0.6.1.) */
TG_API tg_status tg_mesh_distance(const tg_mesh* a, const tg_bvh* b, const tg_mesh_distance_options* options,
                                  double* out_vertex_distance, tg_mesh_distance_result* out_result);


/* ============================================================================================== */
/* Geodesic kernels: two-triangle and fan minimizers (src/kernels, seed 002 §2-4)                 */
/* ============================================================================================== */

/** Search strategies of the fan minimizer after its initial descent step (seed 002 §3.4.2). */
typedef enum tg_fan_strategy {
    TG_FAN_DEFAULT = 0,    /**< the default: TG_FAN_CG (the same minima as the seed's coordinate search,
                                which stalls into its iteration cap on strongly coupled spokes) */
    TG_FAN_COORDINATE = 1, /**< coordinate-direction search with Search/GetLRoot (seed §3.5, §4.3-4.5) */
    TG_FAN_POWELL = 2,     /**< Powell-style (seed §3.4.2 item 2): each coordinate sweep is followed by a
                                line search along the sweep's net displacement, the "approximate
                                conjugate direction"; no full direction set is kept */
    TG_FAN_CG = 3,         /**< conjugate gradient (seed §3.4.2 item 3): each direction conjugate to the
                                previous one with respect to the exact (tridiagonal) Hessian, eq. (57)-(58),
                                restarted by Powell's test */
    TG_FAN_NEWTON = 4      /**< projected Newton with that Hessian and exact line searches (not in the
                                seed): quadratic convergence, the fastest and most accurate; recommended
                                together with TG_ROOT_NEWTON or TG_ROOT_UNFOLD (bench/bench_fan.c) */
} tg_fan_strategy;

/** One-dimensional root finders for L'(t) = 0 (the derivative of a convex length function). */
typedef enum tg_root_method {
    TG_ROOT_BISECTION = 0, /**< n = ceil(digits * log2(10)) bisection steps, no early exit (seed §2.4); default */
    TG_ROOT_NEWTON = 1,    /**< Newton steps safeguarded by the bracket (bisection when a step leaves it or
                                shrinks too slowly), stopping when a step is below the width n bisection
                                steps would leave: the same resolution, usually 3-5 evaluations */
    TG_ROOT_QUADRATIC = 2, /**< two-triangle kernel: the closed-form roots of eq. (6), with its degenerate
                                case t = b0 / a (Example 2.2); the fan treats it as BISECTION */
    TG_ROOT_UNFOLD = 3     /**< closed form by unfolding the two triangles into a plane (not in the seed):
                                t = (a_par b_perp + b_par a_perp) / ((a_perp + b_perp) |B - A|), clamped,
                                for the two-triangle kernel and the fan's coordinate searches, O(1) each;
                                the fan's other line searches then use NEWTON */
} tg_root_method;

/** Options of the geodesic kernels. A NULL pointer or a zero-initialised struct means defaults. */
typedef struct tg_geodesic_kernel_options {
    int digits;         /**< decimal digits of accuracy of each 1D root (seed §2.4); 0: 15; at most 17 */
    int max_iterations; /**< cap on the fan search's outer iterations (one sweep over all coordinates,
                             or one CG / Newton step); 0: 100 + 50 (m + 1)^2 for COORDINATE and
                             POWELL (linear convergence), 100 + 20 (m + 1) for CG and NEWTON */
    tg_fan_strategy strategy;   /**< 0: TG_FAN_DEFAULT (conjugate gradient) */
    tg_root_method root_method; /**< 0: TG_ROOT_BISECTION (the seed's choice) */
} tg_geodesic_kernel_options;
/* Options out of range (digits < 0 or > 17, max_iterations < 0, an unknown strategy or root
 * method) make every function taking them return TG_ERR_INVALID_ARGUMENT. */

/** Two triangles sharing the edge AB (seed 002 §2): the shortest path P0 -> M -> P1 with
 *  M = A + t (B - A), t in [0, 1], minimizing L(t) = |M - P0| + |P1 - M| (eq. 2). L is convex
 *  (eq. 7-8), so: L'(0) >= 0 gives t = 0; else L'(1) <= 0 gives t = 1; else the unique root of
 *  L' in (0, 1) by bisection (or the method chosen in opts). Works in 3D directly: P0 and P1 need
 *  not be coplanar with AB (each leg lies in its own triangle); no unfolding is needed.
 *  p0, a, b, p1: 3 doubles each, finite. opts: NULL for defaults. out_length: receives L(t)
 *  (>= 0); out_t: receives t in [0, 1] (may be NULL). Degenerate input is handled without NaN:
 *  A == B gives t = 0; P0 or P1 on the line AB uses one-sided derivatives; data of extreme
 *  magnitude is rescaled by a power of two. Returns TG_OK; TG_ERR_INVALID_ARGUMENT for a NULL
 *  pointer (out_t excepted), non-finite input, finite input whose differences overflow, or
 *  options out of range (outputs then untouched). Cost: O(digits) square roots (O(1) with
 *  TG_ROOT_UNFOLD). Thread-safe, no allocation. */
TG_API tg_status tg_edge_path_minimize(const double p0[3], const double a[3], const double b[3], const double p1[3],
                                       const tg_geodesic_kernel_options* opts, double* out_length, double* out_t);

/** A fan of m + 1 triangles around vertex V (seed 002 §3-4): the path enters at P0 (a point of
 *  the first triangle, usually its far vertex or a point on its outer edge), crosses the m interior
 *  edges V -> W_i at M_i = V + t_i (W_i - V), t_i in [0, 1], in order, and leaves at P1 (a point of
 *  the last triangle). Minimizes L(t) = |M_0 - P0| + sum |M_{i+1} - M_i| + |P1 - M_{m-1}| (eq. 55),
 *  a convex function (§4.2), by the seed's method: ComputeLargestInitialDecrease (recursive in
 *  dimension, eq. 50/68/72/81/84/87) decides whether the path through V (all t = 0) can be
 *  shortened at all; if so ClampToDomain steps along the steepest ray, then the search strategy in
 *  opts runs to convergence. When the search stalls where the path touches V again (two or more
 *  consecutive t = 0), the same initial-decrease test is applied to that sub-fan, so the result is
 *  the minimum over [0, 1]^m up to the 1D root accuracy, not only a coordinate-wise one.
 *  To shorten a path through a mesh vertex V, call this once per side of V (the two fans between
 *  the incoming and outgoing path edges; on a boundary vertex only the interior side) and keep the
 *  shorter result.
 *  p0, p1, v: 3 doubles each. w: 3 * m doubles, W_0 .. W_{m-1} in fan order from the P0 side to the
 *  P1 side. m: number of interior edges (triangles - 1); m == 0 means a single triangle, whose
 *  shortest path is the segment P0P1 (*out_length = |P1 - P0|). t_init: m start values (clamped to
 *  [0, 1]) or NULL for the seed's start at all t = 0. opts: NULL for defaults.
 *  out_t: m doubles in [0, 1] (may be NULL only when m == 0). out_length: the length of the path
 *  given by out_t, never larger than the length through V (|P0 - V| + |P1 - V|), and, from a
 *  t_init, not larger than L(t_init) beyond rounding.
 *  out_decreased (may be NULL): 1 when *out_length is shorter than the path through V by more than
 *  the rounding noise of evaluating it (4 ulps of the length per segment); else 0, and then out_t
 *  is all 0 and *out_length is the length through V.
 *  Degenerate fans never produce NaN: a zero-length edge (W_i == V) pins the path to V; consecutive
 *  edges on one ray (a zero-area triangle, detected exactly with orient2d) are crossed at one
 *  point; P0 or P1 at V, collinear points and extreme magnitudes are handled. The search always
 *  terminates (iteration caps); the strategies reach the minimum to ~1e-12 relative with their
 *  default caps (COORDINATE: ~1e-10 on long, badly scaled fans; its rate is linear).
 *  Returns TG_OK; TG_ERR_INVALID_ARGUMENT for NULL pointers, non-finite input, finite input
 *  whose differences overflow or options out of range; TG_ERR_OUT_OF_MEMORY if m > 64 and scratch allocation fails
 *  (m <= 64 uses the stack only, about 12 KB). Cost per iteration: O(m) square roots times the
 *  1D root cost (O(digits) for bisection, a few for NEWTON, 1 for UNFOLD in sweeps).
 *  Thread-safe. */
TG_API tg_status tg_fan_path_minimize(const double p0[3], const double p1[3], const double v[3], const double* w,
                               size_t m, const double* t_init, const tg_geodesic_kernel_options* opts,
                               double* out_t, double* out_length, int* out_decreased);


/* ============================================================================================== */
/* Geodesic paths (src/geodesic)                                                                  */
/* ============================================================================================== */

/** A geodesic path and distance field solver over one mesh (seed 002 §5, the straightener
 *  beyond it, and the exact field engine). Built once per mesh by tg_geodesic_create: it keeps a
 *  pointer to the mesh (which must outlive it and is never modified) plus its own view of the
 *  mesh: vertices and faces renumbered along a Morton curve, so that a query over a region touches
 *  nearby memory whatever the file's order (surface points, faces and vertex distances are given
 *  and returned in the mesh's numbering), each component's faces wound consistently, halfedge
 *  frames (every unfolding is made from them), edge rings, neighbour and corner tables, and the
 *  vertices where geodesics may bend. Memory: about 65 bytes per vertex plus 133 per face
 *  (tg_geodesic_memory_bytes). Immutable after creation; any number of threads may query it at
 *  once, each with its own tg_geodesic_workspace. */
typedef struct tg_geodesic tg_geodesic;

typedef struct tg_geodesic_options {
    const tg_allocator* allocator; /**< NULL: libc; also used by workspaces created from it */
} tg_geodesic_options;

/** Builds the solver for mesh (not copied; must stay alive and unchanged until
 *  tg_geodesic_destroy). options may be NULL. Errors: TG_ERR_UNSUPPORTED (coordinates beyond
 *  +-1e150: squared lengths would overflow; 536,870,910 vertices or more: the exact engine numbers
 *  vertices in 29 bits), TG_ERR_INVALID_ARGUMENT (NULL mesh or out),
 *  TG_ERR_OUT_OF_MEMORY. On failure *out_geodesic is NULL. O(V + F log(valence)) time, O(V + F)
 *  memory. Thread-safe (no shared state). */
TG_API tg_status tg_geodesic_create(const tg_mesh* mesh, const tg_geodesic_options* options,
                             tg_geodesic** out_geodesic);

/** Frees the solver. NULL is a no-op. Workspaces created from it must be destroyed first or at
 *  least never used again. */
TG_API void tg_geodesic_destroy(tg_geodesic* geodesic);

/** Bytes owned by the solver (tables and header, not the mesh). O(1). NULL gives 0. */
TG_API size_t tg_geodesic_memory_bytes(const tg_geodesic* geodesic);

/** Per-thread scratch for every query on one solver: paths (tg_geodesic_path) and fields
 *  (tg_geodesic_field, tg_geodesic_field_at). Its tables sized for the mesh are allocated when it
 *  is created, from the solver's allocator: about 61 bytes per vertex plus 64 per face (the exact
 *  engine's distances, predecessors, window lists and splits; A*'s records); its buffers (window
 *  pool, front, path nodes, sleeves) grow to the largest query seen and are kept, so repeated
 *  queries do not allocate (except TG_PATH_RELAX across a fan of over 64 edges: the fan kernel's
 *  scratch). A query touches only the entries of the region it explores. Every call taking a
 *  workspace also accepts NULL and then makes and frees a temporary one (that costs O(V + F)
 *  per call). Not thread-safe: one workspace per thread. */
typedef struct tg_geodesic_workspace tg_geodesic_workspace;

/** Creates a workspace for queries on geodesic. Errors: TG_ERR_INVALID_ARGUMENT,
 *  TG_ERR_OUT_OF_MEMORY (then *out_workspace is NULL). O(V + F) time and memory. */
TG_API tg_status tg_geodesic_workspace_create(const tg_geodesic* geodesic,
                                       tg_geodesic_workspace** out_workspace);

/** Frees a workspace. NULL is a no-op. */
TG_API void tg_geodesic_workspace_destroy(tg_geodesic_workspace* workspace);

/** Bytes currently owned by the workspace (its tables plus grown buffers). NULL gives 0. */
TG_API size_t tg_geodesic_workspace_memory_bytes(const tg_geodesic_workspace* workspace);

/** How a path is found. TG_PATH_EXACT, the default, is the globally shortest path; the others
 *  shorten the shortest edge path (A*) into a locally shortest one, faster but unproven. */
typedef enum tg_path_method {
    /** Default. The globally shortest path, proven: an exact window propagation from `from`
     *  (tg_geodesic_field's engine) ordered toward `to` (A*: a window's distance plus the
     *  Euclidean distance from it to `to`) and bounded by the best distance to `to` found so far
     *  (windows reaching it, the corners of its face), then the path traced back from `to` along
     *  the ray of the window that reached it, through the faces it crossed, to the pseudo-source
     *  vertex it came from, and on through the windows and pseudo-source vertices to `from`. No
     *  edge path is computed, so in its view initial_length equals length and edge_path_vertices
     *  and iterations are 0; global is TG_PATH_PROVEN. Cost: see BENCHMARKS.md (near pairs cost a
     *  small region of the field's work, far pairs a few times TG_PATH_STRAIGHTEN's). The trace
     *  back reproduces the exact distance on every pair of the project's sweep; should it ever
     *  fail, the call returns TG_ERR_INTERNAL rather than an unproven path. */
    TG_PATH_EXACT = 0,
    /** The fast locally shortest path: unfolds every run of edge crossings of the edge path (a
     *  triangle strip) into the plane and straightens it in one pass with a funnel (Lee &
     *  Preparata 1984); vertex passages whose smaller side angle is below pi are re-routed through
     *  the fan on that side and the strip is straightened again, until every vertex passage is
     *  locally shortest (Xin & Wang 2007). A geodesic, not always the globally shortest one:
     *  global is TG_PATH_UNPROVEN unless certify proves it. */
    TG_PATH_STRAIGHTEN = 1,
    /** The seed's relaxation (seed 002 §5): passes over consecutive triples, two-triangle
     *  minimization at edge points (§2) and fan minimization on each side of a mesh vertex (§3-4),
     *  until a pass shortens the path by at most tolerance * length. Unproven unless certify. */
    TG_PATH_RELAX = 2,
    /** No shortening: the initial shortest edge path (Dijkstra/A*) only. Unproven unless certify. */
    TG_PATH_EDGE = 3
} tg_path_method;

/** Whether a path is proven globally shortest. */
typedef enum tg_path_global {
    TG_PATH_UNPROVEN = 0, /**< locally shortest (certificate), not shown to be globally shortest */
    TG_PATH_PROVEN = 1    /**< an exact computation showed no path shorter by 1e-9 relative exists */
} tg_path_global;

/** "proven", "unproven"; "unknown" for other values. Never NULL. */
TG_API const char* tg_path_global_name(tg_path_global global);

/** Whether tg_geodesic_path checks its result against the exact distance. */
typedef enum tg_path_certify {
    /** default: no check (the default method, TG_PATH_EXACT, is proven without it; the other
     *  methods' paths are TG_PATH_UNPROVEN) */
    TG_PATH_CERTIFY_OFF = 0,
    /** After STRAIGHTEN, RELAX or EDGE: the exact distance within the path's length; a path
     *  within 1e-9 of it becomes TG_PATH_PROVEN, and a longer one is replaced by the exact path
     *  (TG_PATH_EXACT's). Redundant with TG_PATH_EXACT, whose path is proven already. */
    TG_PATH_CERTIFY_ON = 1
} tg_path_certify;

/** The outcome of a query, stored in the path. */
typedef enum tg_path_status {
    TG_PATH_CONVERGED = 0,     /**< the method's stopping criterion was met */
    TG_PATH_ITERATION_CAP = 1, /**< max_iterations was reached; the path is valid but may be longer */
    TG_PATH_UNREACHABLE = 2,   /**< the endpoints lie in different components: no points, length +inf */
    /** STRAIGHTEN stopped, yet its path is not straight: the certificate exceeds 1e-8 rad (a mesh
     *  whose scale makes angles unmeasurable, e.g. coordinates near 1e-300); never "converged" */
    TG_PATH_STALLED = 3
} tg_path_status;

/** "converged", "iteration_cap", "unreachable", "stalled"; "unknown" for other values. Never NULL. */
TG_API const char* tg_path_status_name(tg_path_status status);

/** What a progress callback of a field or a path is told (defined here, before the paths, which
 *  take the same callback). */
typedef struct tg_field_progress {
    double front_distance;   /**< distance of the wavefront: the last vertex settled */
    double settled_fraction; /**< share of the mesh's vertices settled (in [0, 1]; vertices no
                                  source reaches are never settled); for a batch, the share of all
                                  rows' work: (rows done + this row's share) / rows */
    size_t rows_done;        /**< batch: rows finished so far (0 for a single field) */
    size_t row_count;        /**< batch: number of rows (1 for a single field) */
} tg_field_progress;

/** Progress callback: called every few milliseconds of work (about every 5 ms, from the thread
 *  doing the work; in a batch, from one thread at a time), however the work is divided (a batch
 *  of pieces each shorter than that reports between them too), so that a caller can stop any
 *  call that takes one within a few milliseconds (Ctrl-C). Return 0 to go on, anything else to
 *  cancel: the call then returns TG_ERR_CANCELLED (even when its work had just finished), with
 *  the outputs as its documentation says for errors. */
typedef int (*tg_field_progress_fn)(void* user, const tg_field_progress* progress);

/** Query options. NULL or all-zero means defaults. */
typedef struct tg_path_options {
    tg_path_method method;   /**< TG_PATH_EXACT (0) by default */
    /** cap on straightening sweeps or relaxation passes (not used by EXACT); 0: 10000 */
    uint32_t max_iterations;
    /** Stopping tolerance, dimensionless; 0: default. STRAIGHTEN: a vertex passage is re-routed
     *  when its smaller side angle is below pi - tolerance radians (default 1e-12). RELAX: stop
     *  when a pass shortens the path by at most tolerance * length (default 1e-13). EXACT: not
     *  used. Negative, NaN or infinite: TG_ERR_INVALID_ARGUMENT (whatever the method). */
    double tolerance;
    /** RELAX: options of the seed's kernels (tg_edge_path_minimize, tg_fan_path_minimize). NULL
     *  or zero: their defaults, 15 digits by bisection (§2.4) and the conjugate-gradient fan
     *  search (§3.4.2). */
    const tg_geodesic_kernel_options* kernel; /**< out of range: TG_ERR_INVALID_ARGUMENT */
    tg_path_certify certify; /**< TG_PATH_CERTIFY_OFF by default */
    /** Called from the querying thread while the query works, so that a caller can stop it
     *  (Ctrl-C): during an exact propagation (TG_PATH_EXACT, certify) every few milliseconds with
     *  the field's figures (settled_fraction of the component; an A*-bounded run stops well
     *  before 1), and after every straightening sweep (STRAIGHTEN) or relaxation pass (RELAX)
     *  with front_distance 0, settled_fraction 0, rows_done the sweeps or passes done and
     *  row_count 0. Returning non-zero stops the query: TG_ERR_CANCELLED, the path empty.
     *  NULL: none. (New in 0.3.) */
    tg_field_progress_fn progress;
    void* progress_user; /**< passed to progress */
} tg_path_options;

/** A geodesic path: a caller-owned result object reused across queries (its buffers grow to the
 *  longest path and are kept). Read it through tg_path_get_view. */
typedef struct tg_path tg_path;

/** Read-only view of a path, valid until the next query into the same tg_path or its
 *  destruction. Consecutive points are joined by straight segments, segment i (between points i
 *  and i + 1) lying in face faces[i]; a segment along a mesh edge names one of the edge's faces
 *  (the same one for the same query). */
typedef struct tg_path_view {
    size_t point_count;              /**< >= 2 unless unreachable (then 0) */
    const tg_surface_point* points;  /**< from, every vertex passage and edge crossing, to */
    const double* xyz;               /**< 3 * point_count positions */
    const uint32_t* faces;           /**< point_count - 1 faces, one per segment */
    double length;                   /**< sum of 3D segment lengths; +inf when unreachable */
    /** length of the initial shortest edge path; TG_PATH_EXACT computes none: there it equals
     *  length; +inf when unreachable */
    double initial_length;
    /** The certificate, radians: the largest straightness defect over edge crossings
     *  (|pi - unfolded angle|) and vertex passages (max(0, pi - smaller side angle), taking only
     *  the interior side at a boundary; 0 where the path passes between two fans of a pinched or
     *  non-manifold vertex, or through coincident vertices). Crossings closer together than
     *  1e-5 of the local edge length are measured as one, between the points beyond them (a
     *  crossing stored as edge + t is only resolved to about 1e-16 of its edge's length).
     *  0 for a path with no interior point. Angles inside zero-area faces mean nothing: a path
     *  through them (e.g. across a pole of coincident vertices) can show a large defect, and a
     *  path whose global is TG_PATH_PROVEN is the shortest by its length whatever its certificate. */
    double max_angle_defect;
    tg_path_status status;
    /** TG_PATH_PROVEN only when an exact computation showed that no path shorter by more than
     *  1e-9 relative exists (method TG_PATH_EXACT, or certify); else TG_PATH_UNPROVEN. */
    tg_path_global global;
    uint32_t iterations;             /**< sweeps (STRAIGHTEN) or passes (RELAX) performed; 0 for EXACT */
    uint32_t edge_path_vertices;     /**< mesh vertices on the initial edge path; 0 for EXACT */
} tg_path_view;

/** Creates an empty path object. allocator may be NULL (libc). Errors: TG_ERR_INVALID_ARGUMENT,
 *  TG_ERR_OUT_OF_MEMORY. */
TG_API tg_status tg_path_create(const tg_allocator* allocator, tg_path** out_path);

/** Frees a path object. NULL is a no-op. */
TG_API void tg_path_destroy(tg_path* path);

/** Fills *out_view with the path's current content (an empty, unreachable path before the first
 *  query). O(1). */
TG_API void tg_path_get_view(const tg_path* path, tg_path_view* out_view);

/** Computes a geodesic path from `from` to `to` (any surface points: vertex, edge point, face
 *  point; never snapped to a vertex) into `path`.
 *  By default (TG_PATH_EXACT) the path is the globally shortest one, proven (global
 *  TG_PATH_PROVEN): an exact window propagation from `from` toward `to`, traced back (see
 *  tg_path_method). The other methods insert the endpoints virtually (the mesh is not modified),
 *  find the shortest path in the edge graph plus the endpoints' virtual edges by A* with the
 *  Euclidean lower bound (binary heap, stopping at the target, work proportional to the explored
 *  region), then shorten it by options->method. Their result is a locally shortest path (a
 *  geodesic) in the homotopy class the edge path leads to; where several geodesics join the
 *  endpoints (around a cone point, a handle) it need not be the globally shortest one
 *  (TG_PATH_UNPROVEN unless certify).
 *  Surface semantics: exact paths cross every edge the exact fields cross (any winding, every
 *  other face at a non-manifold edge: the surface as a 2-complex); the other methods cross every
 *  edge shared by exactly two faces (non-zero length) whatever the faces' winding (the solver
 *  winds each component consistently once; a non-orientable component keeps one wall per
 *  conflict) and pass non-manifold edges, pinched vertices and coincident vertices through
 *  vertices. A duplicate face counts once.
 *  Endpoints in different components give status TG_PATH_UNREACHABLE, length +inf and TG_OK.
 *  Every returned path lies on the surface and its length never exceeds initial_length; exact
 *  and straightened converged paths have max_angle_defect <= 1e-10 in practice (reported, not
 *  assumed). The output endpoints are the canonical forms of from and to.
 *  workspace: one of this solver's, or NULL for a temporary one (see tg_geodesic_workspace).
 *  options: NULL or zero for the defaults.
 *  Errors: TG_ERR_INVALID_ARGUMENT (NULL geodesic, from, to or path, a workspace of another
 *  solver, an invalid surface point, out-of-range options), TG_ERR_OUT_OF_MEMORY,
 *  TG_ERR_INTERNAL (see TG_PATH_EXACT), TG_ERR_CANCELLED (options->progress asked to stop); on
 *  error the path is empty (unreachable).
 *  Complexity: EXACT is the field's (tg_geodesic_field) over the region its A* order and bound
 *  explore; A* is O(n log n) in the n explored vertices; straightening is O(k) per sweep in the
 *  k faces of the path's strips (figures in BENCHMARKS.md). Thread-safe for distinct workspaces
 *  and paths. */
TG_API tg_status tg_geodesic_path(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                           const tg_surface_point* from, const tg_surface_point* to,
                           const tg_path_options* options, tg_path* path);

/** Writes the path as a Wavefront OBJ polyline: one "v x y z" (%.17g) per point and one
 *  "l 1 2 ... n" record (nothing but a comment for an unreachable path). Errors: TG_ERR_IO with
 *  diag (may be NULL), TG_ERR_INVALID_ARGUMENT. */
TG_API tg_status tg_path_write_obj(const tg_path* path, const char* filename, tg_diag* diag);

/** Parallel transport along a path: the tangent vector `vector` at the path's start carried to
 *  every point of it. Across an edge the two faces unfold into one plane, where transport is the
 *  identity, so along a path straight in the unfolding (an exact path: TG_PATH_EXACT, or proven)
 *  the vector keeps its angle to the path; that angle is kept at every point, vertex passages
 *  included (where the path, and the vector with it, turns into the next face's plane). Point i
 *  gets the vector in the plane of the face of segment i (the last point: of the last segment).
 *  vector: 3 finite doubles, not zero; its projection onto the first segment's face plane is the
 *  direction (TG_TRACE_VECTOR's rule), its length the result's. Angles turn counterclockwise about
 *  each face's normal by its file winding (on a surface that is not orientable the sense flips
 *  where the winding does). Segments of length 0 and faces of zero area keep the frame before.
 *  mesh: the mesh the path was computed on. out_vectors: 3 doubles a point.
 *  Errors: TG_ERR_INVALID_ARGUMENT (NULL arguments; a zero, NaN or infinite vector; a vector
 *  perpendicular to the first face (projection at most 1e-9 of its length); a path with fewer than
 *  two points, of length 0 or naming faces the mesh has not); out_vectors is then untouched.
 *  O(points). Thread-safe. Python: Path.transport(vector). (New in 0.6.1.) */
TG_API tg_status tg_path_transport(const tg_mesh* mesh, const tg_path* path, const double vector[3],
                                   double* out_vectors);
/** tg_path_transport on any polyline of the surface given as arrays: point_count points xyz
 *  (3 each, finite), segment i lying in face faces[i] (point_count - 1 faces of `mesh`), e.g. a
 *  tg_trace_view's points and faces. The same errors (point_count < 2, NULL arrays). (New in
 *  0.6.1.) */
TG_API tg_status tg_polyline_transport(const tg_mesh* mesh, size_t point_count, const double* xyz,
                                       const uint32_t* faces, const double vector[3], double* out_vectors);

/* ============================================================================================== */
/* Paths through waypoints (src/geodesic/waypoints.c)                                             */
/* ============================================================================================== */

/** Whether a route through waypoints returns to its first point. */
typedef enum tg_path_closure {
    TG_PATH_OPEN = 0,  /**< from the first point to the last */
    TG_PATH_CLOSED = 1 /**< a loop: from the last point back to the first as well */
} tg_path_closure;

/** The shortest route visiting `points` in the given order (and back to the first with
 *  TG_PATH_CLOSED), as one path: the exact shortest path (tg_geodesic_path with the default
 *  method, TG_PATH_EXACT) between each pair of consecutive points, joined end to end. Each piece
 *  is globally shortest and proven, so the route is the shortest one through the points in that
 *  order; its length is the sum of the pieces' lengths (added in order) and its global flag is
 *  TG_PATH_PROVEN. The path bends at the waypoints, which are not part of its certificate:
 *  max_angle_defect is the largest over the pieces. Each waypoint appears once in the points
 *  (a piece's first point is the previous piece's last); consecutive equal waypoints give an
 *  empty segment. initial_length equals length, iterations and edge_path_vertices are 0.
 *  points: point_count >= 1 valid surface points (one point: the path from it to itself, two
 *  equal points and length 0). closure: TG_PATH_OPEN or TG_PATH_CLOSED.
 *  options: NULL for the defaults, or tg_geodesic_path's options with method TG_PATH_EXACT (the
 *  others are refused); each piece is computed with them, and their progress callback is told
 *  the pieces finished (rows_done of row_count = the pieces; settled_fraction the route's share
 *  done), from inside each piece's propagation and between pieces, about every 5 ms. Returning
 *  non-zero stops the route: TG_ERR_CANCELLED. (New in 0.5.)
 *  workspace: one of this solver's, or NULL for a temporary one. path: the result (its
 *  allocator also serves the pieces' scratch path).
 *  out_waypoint_points: NULL, or point_count (+ 1 when closed) entries receiving the index in
 *  the path's points of each waypoint in visiting order (the last entry of a closed route is the
 *  point where it returns to the first waypoint, which is the path's last point).
 *  When two consecutive waypoints lie in different components the route does not exist: the
 *  path is empty with status TG_PATH_UNREACHABLE and length +inf, out_waypoint_points is
 *  untouched, and the call returns TG_OK.
 *  Errors: TG_ERR_INVALID_ARGUMENT (NULL geodesic, points or path, point_count 0, an invalid
 *  point, an unknown closure, a method other than TG_PATH_EXACT or options tg_geodesic_path
 *  refuses, a workspace of another solver), TG_ERR_OUT_OF_MEMORY, TG_ERR_INTERNAL (as
 *  tg_geodesic_path), TG_ERR_CANCELLED (the progress callback asked to stop); on error the path
 *  is empty and out_waypoint_points untouched. Every point is validated before any path is
 *  computed.
 *  Complexity: the sum of the pieces' tg_geodesic_path calls. Thread-safe for distinct
 *  workspaces and paths. */
TG_API tg_status tg_geodesic_path_through(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                                   const tg_surface_point* points, size_t point_count, tg_path_closure closure,
                                   const tg_path_options* options, tg_path* path, size_t* out_waypoint_points);


/* ============================================================================================== */
/* Geodesic tracing, the exponential map (src/geodesic/walk.c)                                    */
/* ============================================================================================== */

/** How the direction of a trace is given. */
typedef enum tg_trace_direction_kind {
    /** A 3D vector, finite and not zero, of any length: the vector and the vector times any
     *  power of two (subnormal components included) give the same trace bit for bit, and its
     *  length never overflows or underflows anything. It is taken as a direction of the surface
     *  at the start point:
     *  - inside a face: its projection onto the face's plane; refused (TG_ERR_INVALID_ARGUMENT)
     *    when that projection is at most 1e-9 of the vector's length;
     *  - at a vertex or at a point of an edge: its projection onto the point's tangent plane.
     *    The plane's normal is the mean of the unit normals of the faces of non-zero area at the
     *    point (oriented alike around it, whatever the file's winding), each weighted by its
     *    angle at the point (Thürmer & Wüthrich 1998; the two faces of an edge weigh the same). Each face's corner
     *    at the vertex (its half-plane at the edge) projects along the normal onto a wedge of the
     *    tangent plane; among the faces whose wedge holds the projection (sides included), each
     *    has one direction whose projection runs along the vector's, and the trace takes the one
     *    of these nearest to the vector in space (largest dot product; several faces qualify only
     *    where the fan folds over its tangent plane), the face of lowest index on exact ties. So
     *    a vector lying in a face of the fan is taken as it is (to rounding), the direction taken
     *    always has a positive cosine with the projection, and it turns continuously with the
     *    vector wherever the fan does not fold. Where the fan's projection goes round the point
     *    (at the closed-fan vertices of 21 corpus meshes, all but one where a face folds back
     *    over its neighbours), a wedge holds every projection: the vector is refused only when
     *    it is parallel to the normal, its projection at most 1e-9 of its length (within about
     *    1e-9 radians).
     *    Where no wedge holds the projection (off the open fan of a boundary vertex, or a fan
     *    whose projection does not go round), the direction of the faces nearest to the
     *    projection is taken (largest cosine: a corner's nearer side when the projection is
     *    outside it, along the edge when it points out of a face at an edge), refused when that
     *    cosine is at most 1e-9. Where the point has no tangent plane (an edge of more than two
     *    faces, or normals that cancel to within 1e-9 of their weights, as at a pinch of two
     *    opposite cones), the same nearest direction to the vector itself. */
    TG_TRACE_VECTOR = 0,
    /** An angle in radians from a reference direction, counterclockwise about the normal of the
     *  reference face (its corners 0, 1, 2 in the file's order are counterclockwise), measured as
     *  the surface unfolds (intrinsically), by the start point's kind as given by the caller:
     *  - a face point of face f: from f's corner 0 towards its corner 1;
     *  - an edge point of halfedge h: from h's start towards its end, counterclockwise in h's face;
     *    angles in (pi, 2 pi) point across the edge, into the face beyond it unfolded;
     *  - a vertex v: from the halfedge tg_mesh_vertex_halfedges gives for v, counterclockwise in
     *    its face and on around v, with the vertex's angle sum scaled to 2 pi (to pi where the
     *    fan of faces around v is not closed: a boundary vertex), as geometry-central's vertex
     *    tangent spaces: 0.5 pi is a quarter of the way round whatever the cone angle.
     *  The reference face must have a non-zero area (its normal and side are measured with
     *  their vectors scaled by powers of two first: at any scale of the mesh). */
    TG_TRACE_ANGLE = 1
} tg_trace_direction_kind;

/** The direction of a trace: kind, then vector (TG_TRACE_VECTOR, 3 finite doubles, not all zero,
 *  in any unit and of any length) or angle (TG_TRACE_ANGLE, finite radians; any value, taken
 *  modulo 2 pi where the fan is closed). The unused member is ignored. */
typedef struct tg_trace_direction {
    tg_trace_direction_kind kind;
    double vector[3];
    double angle;
} tg_trace_direction;

/** Why a trace ended. */
typedef enum tg_trace_status {
    TG_TRACE_COMPLETE = 0, /**< the whole length was walked */
    /** stopped on the boundary: the walk reached a boundary edge, or a vertex whose fan of faces
     *  is not closed by crossable edges because it meets a boundary edge (a boundary vertex), or
     *  an angle pointed off the surface at the start */
    TG_TRACE_BOUNDARY = 1,
    /** stopped at a vertex where no straightest continuation is defined: its fan of faces is not
     *  closed for another reason (a non-manifold edge, a pinch, a misoriented seam or a zero-length
     *  edge at it), or the start point lies in zero-area faces only */
    TG_TRACE_SINGULAR = 2,
    TG_TRACE_STEP_LIMIT = 3, /**< options->max_steps faces were entered before the length was used */
    /** more than 1000 faces in a row were entered without advancing (zero-area faces around one
     *  point): the walk stopped there rather than loop */
    TG_TRACE_STALLED = 4
} tg_trace_status;

/** "complete", "boundary", "singular", "step_limit", "stalled"; "unknown" for other values.
 *  Never NULL. (New in 0.4.) */
TG_API const char* tg_trace_status_name(tg_trace_status status);

/** Options of tg_geodesic_trace and tg_geodesic_trace_batch. NULL or all-zero means defaults. */
typedef struct tg_trace_options {
    /** the most faces one walk may enter (each edge crossing and each face entered at a vertex
     *  counts one); 0: 16 times the face count plus 65536. A walk that reaches it stops with
     *  TG_TRACE_STEP_LIMIT: raise it for walks many times around a mesh. */
    uint64_t max_steps;
    /** Called while the walks work, so that a caller can stop them (Ctrl-C), about every 5 ms
     *  (the flag and the clock are looked at every 4096 faces of a walk and after each trace of a
     *  batch), from a walking thread (in a batch from one thread at a time): front_distance the
     *  length the current walk has gone (after a trace of a batch: its whole length), rows_done the traces of a batch finished of row_count (0 of 1 for tg_geodesic_trace),
     *  settled_fraction the share done. Returning non-zero stops the call: TG_ERR_CANCELLED.
     *  NULL: none. (New in 0.5.) */
    tg_field_progress_fn progress;
    void* progress_user; /**< passed to progress */
} tg_trace_options;

/** Where a trace ended, and how. */
typedef struct tg_trace_end {
    tg_surface_point point; /**< the end point (canonical form; the start point when nothing was walked) */
    double xyz[3];          /**< its position (tg_surface_point_position) */
    /** the unit direction of the walk at the end (3D, in the mesh's frame), in the plane of the
     *  last face of non-zero area it was in (`face`, unless that is a zero-area face): the start
     *  direction when nothing was walked */
    double direction[3];
    uint32_t face;          /**< the face of the last segment (of the start direction when nothing was walked) */
    tg_trace_status status;
    /** the length walked: exactly the requested length when status is TG_TRACE_COMPLETE, the
     *  distance along the walk to where it stopped otherwise */
    double length;
    uint64_t crossings;     /**< edges crossed (zero-area faces included) */
    uint32_t vertices;      /**< vertices passed through (straightest continuations) */
    /** non-manifold edges crossed: at each the walk took, of the other faces at the edge, the one
     *  where it continues straightest in space (the largest cosine between the 3D directions
     *  before and after; the lowest face index on ties); tg_trace_view lists where */
    uint32_t branches;
} tg_trace_end;

/** A geodesic trace: a caller-owned result object reused across calls (its buffers grow to the
 *  longest trace and are kept). Read it through tg_trace_get_view. */
typedef struct tg_trace tg_trace;

/** Read-only view of a trace, valid until the next call into the same tg_trace or its
 *  destruction. Consecutive points are joined by straight segments, segment i lying in face
 *  faces[i]; a segment across a zero-area face has length 0. */
typedef struct tg_trace_view {
    size_t point_count;             /**< >= 2 after a trace: start, every edge crossing and vertex
                                         passage, end (the end is not repeated when it is the last
                                         crossing or vertex); 0 before the first */
    const tg_surface_point* points; /**< the surface points (canonical forms) */
    const double* xyz;              /**< 3 * point_count positions */
    const uint32_t* faces;          /**< point_count - 1 faces */
    size_t branch_count;            /**< == end.branches */
    /** the index in points of each non-manifold crossing; the face taken there is
     *  faces[branch_points[i]] */
    const size_t* branch_points;
    tg_trace_end end;
} tg_trace_view;

/** Creates an empty trace object. allocator may be NULL (libc). Errors:
 *  TG_ERR_INVALID_ARGUMENT, TG_ERR_OUT_OF_MEMORY. (New in 0.4.) */
TG_API tg_status tg_trace_create(const tg_allocator* allocator, tg_trace** out_trace);

/** Frees a trace object. NULL is a no-op. (New in 0.4.) */
TG_API void tg_trace_destroy(tg_trace* trace);

/** Fills *out_view with the trace's current content (no points before the first call). O(1).
 *  (New in 0.4.) */
TG_API void tg_trace_get_view(const tg_trace* trace, tg_trace_view* out_view);

/** The exponential map: walks from `start` in `direction` straight across the faces for `length`
 *  (the same unit as the coordinates), in double precision, into `trace`: the polyline (surface
 *  points, positions, faces), the end point and the direction there.
 *
 *  Method: the walk unfolds each face it enters into the plane of the one before (the solver's
 *  halfedge frames), so that it is a straight line of the unfolding, and decides which edge it
 *  leaves by through exact orientation tests. A walk passing a vertex within 1e-11 of the face's
 *  longest edge goes through the vertex (on which side of it a ray passes is rounding noise
 *  below that) and leaves it as the straightest geodesic of Polthier and Schmies (1998): with
 *  the same angle sum on both sides, half the vertex's total angle, so that it goes on straight
 *  through a flat vertex and along the unique bisecting direction at a cone or saddle vertex.
 *  A walk along an edge goes through the vertex at its end. Zero-area faces with a zero-length
 *  edge (slits) are crossed straight through to their other side; other zero-area faces are
 *  crossed where the walk meets them. At a non-manifold edge the walk continues into the face
 *  where it runs straightest in space (see tg_trace_end.branches). The walk stops at the
 *  boundary (TG_TRACE_BOUNDARY), at a vertex with no straightest continuation
 *  (TG_TRACE_SINGULAR), after options->max_steps faces (TG_TRACE_STEP_LIMIT) or after 1000
 *  faces in a row without advancing (TG_TRACE_STALLED); these are statuses of the result, not
 *  errors. The results are the same, bit for bit, for a mesh scaled by a power of two (and to
 *  rounding at any scale and position), and the same whatever other calls run.
 *
 *  start: a valid surface point (vertex, edge point or face point). direction: see
 *  tg_trace_direction. length: finite and >= 0 (0 gives the start point, two equal points).
 *  options: NULL for defaults. trace: the result.
 *  Errors: TG_ERR_INVALID_ARGUMENT (NULL geodesic, start, direction or trace; an invalid start
 *  point; a negative, NaN or infinite length; a zero, NaN or infinite vector, or one
 *  perpendicular to the surface at the start (along the normal: see TG_TRACE_VECTOR); a NaN or infinite angle, or
 *  one measured in a zero-area reference face; an unknown direction kind), TG_ERR_OUT_OF_MEMORY,
 *  TG_ERR_CANCELLED (options->progress asked to stop); on error the trace is empty (no points).
 *  Complexity: O(k) in the k faces crossed, a small constant per face (figures in
 *  BENCHMARKS.md), plus the vertices' fans at vertex passages; no allocation once the trace's
 *  buffers hold k points. Thread-safe for distinct trace objects. (New in 0.4.) */
TG_API tg_status tg_geodesic_trace(const tg_geodesic* geodesic, const tg_surface_point* start,
                            const tg_trace_direction* direction, double length, const tg_trace_options* options,
                            tg_trace* trace);

/** Many traces at once: out_ends[i] is the end of tg_geodesic_trace(starts[i], directions[i],
 *  lengths[i]), bit for bit (the walk records no polyline here, so it allocates nothing). The
 *  traces run in parallel with OpenMP on `threads` threads (0: the OpenMP default; 1: this thread
 *  only); each walk keeps its state in a few local variables, so the results do not depend on
 *  the number of threads or the order in which they run.
 *  starts, directions, lengths: count entries each (NULL allowed when count is 0); every entry is
 *  validated before any walk, as tg_geodesic_trace does. out_ends: count entries.
 *  Errors: TG_ERR_INVALID_ARGUMENT (as tg_geodesic_trace for any entry, NULL arrays with a
 *  non-zero count, a negative thread count); out_ends is then untouched. TG_ERR_CANCELLED
 *  (options->progress asked to stop): every walk ends at its next look, out_ends holds the
 *  entries of the traces finished before (each complete) and leaves the others untouched.
 *  Complexity: the sum of the walks', divided among the threads. Thread-safe. (New in 0.4.) */
TG_API tg_status tg_geodesic_trace_batch(const tg_geodesic* geodesic, const tg_surface_point* starts,
                                  const tg_trace_direction* directions, const double* lengths, size_t count,
                                  const tg_trace_options* options, int threads, tg_trace_end* out_ends);


/* ============================================================================================== */
/* Exact geodesic distance fields (src/geodesic/field)                                             */
/* ============================================================================================== */

/** Whether max_distance applies. */
typedef enum tg_field_limit {
    TG_FIELD_UNLIMITED = 0,   /**< default: the whole surface reachable from the sources */
    TG_FIELD_MAX_DISTANCE = 1 /**< stop at max_distance (0 is allowed and means distance 0) */
} tg_field_limit;

/** Options of the field calls. NULL or all-zero means defaults. Every call that takes them
 *  honours each member or refuses it (TG_ERR_INVALID_ARGUMENT); none ignores one:
 *
 *    call                                 allocator  limit / max_distance    progress  threads
 *    tg_geodesic_field, tg_geodesic_field_at   honoured   honoured           honoured  honoured
 *    tg_geodesic_log_map, _transport_field  honoured  honoured              honoured  honoured
 *    tg_geodesic_field_gradient           honoured   honoured                honoured  honoured
 *    tg_geodesic_voronoi                  honoured   honoured                honoured  honoured
 *    tg_geodesic_isolines                 honoured   honoured                honoured  honoured
 *    tg_geodesic_farthest_point_sampling  honoured   refused (samples need   honoured  honoured
 *                                                    the whole field)
 *    tg_geodesic_distance_matrix, _at     honoured   honoured (every row)    honoured  0/1 only
 *    tg_geodesic_local_matrix             honoured   refused: the radius is  honoured  0/1 only
 *                                                    its max_distance
 *
 *  ("0/1 only": any other thread count is refused; the matrices spread their rows with their own
 *  `threads` argument, one field a row on one thread.)
 *  The allocator serves the call's scratch (a temporary workspace, per-thread scratch); result
 *  objects use their own allocator, given when they were created. */
typedef struct tg_field_options {
    /** the memory of a temporary workspace (and of the distance matrix's per-thread scratch);
     *  NULL: the solver's allocator */
    const tg_allocator* allocator;
    tg_field_limit limit; /**< TG_FIELD_UNLIMITED by default */
    /** With TG_FIELD_MAX_DISTANCE: the distance limit (same unit as the coordinates, >= 0).
     *  Vertices within it get their exact distance, every vertex beyond it +inf, and the work
     *  stays within it. Ignored with TG_FIELD_UNLIMITED. */
    double max_distance;
    tg_field_progress_fn progress; /**< NULL: none */
    void* progress_user;           /**< passed to progress */
    /** Threads for one field: 0 or 1 (the default) the serial engine; N >= 2 the same exact
     *  propagation in rounds whose lists cross their faces on N threads at once, merged in a
     *  fixed order, so every N >= 2 (and TG_THREADS_ALL: every core) gives the same bits, within
     *  rounding (about 1e-15 relative) of the serial engine's; no more threads than the machine's
     *  processors are started (the bits do not change). What a call computes from its field
     *  follows: where two paths tie within that rounding, a log map angle, a Voronoi label or a
     *  farthest sample may be the other path's (the same for every N >= 2, run to run), and
     *  isolines may cut a curve at other points of the same level set (each on its level to
     *  rounding). Honoured by every call on one field (table above); the matrices refuse
     *  anything but 0 or 1 (TG_ERR_INVALID_ARGUMENT), and every call a count below
     *  TG_THREADS_ALL. (New in 0.6; every call on one field since 0.6.1, field and field_at
     *  without points before.) */
    int threads;
} tg_field_options;

/** tg_field_options.threads: every core (the OpenMP default). */
#define TG_THREADS_ALL (-1)

/** Counters of one tg_geodesic_field run, or summed over a batch (for benchmarks and tests). */
typedef struct tg_field_stats {
    uint64_t windows_created;        /**< windows put on an edge side's list */
    uint64_t windows_propagated;     /**< windows carried across a face */
    uint64_t windows_filtered;       /**< windows or children dropped by the filters (or empty) */
    uint64_t pseudo_source_events;   /**< emissions from sources and pseudo-source vertices */
    uint64_t pseudo_source_vertices; /**< vertices classified as pseudo-sources */
    uint64_t max_queue;              /**< largest number of entries on the vertex front */
    uint64_t peak_windows;           /**< largest number of windows alive at once */
    size_t peak_bytes;               /**< largest workspace memory in use (bytes) */
    /* One field on several threads (tg_field_options.threads > 1; zero otherwise): its schedule,
     * from which a speed-up on more threads can be planned (BENCHMARKS.md, "Every core"). */
    uint64_t rounds;     /**< rounds: vertices taken off the front together */
    uint64_t waves;      /**< waves of lists (or of a round's vertices) crossed on all threads at once */
    uint64_t wave_lists; /**< the lists and vertices those waves took (the rest on thread 0) */
    double lead_seconds; /**< thread 0's time outside the waves: the front, the merges of the vertex
                              rounds and the corner distances after each wave, small waves */
    double wave_seconds; /**< the threads' busy time in the waves, summed over the threads: lists
                              crossed, and thread 0's merges of a wave's lists while later ones cross */
} tg_field_stats;

/** The exact geodesic distance from a set of surface points to every vertex: the length of the
 *  shortest path on the surface to the nearest source.
 *
 *  Method: windows (intervals of edges lit by one unfolded source image, plus a distance offset
 *  for paths bending at a vertex; Chen & Han 1990) are kept in one list per edge side and moved
 *  across one face at a time, in FIFO order, behind a front of vertices taken in order of
 *  distance (Qin et al. 2016, "VTP"). Before a list crosses its face its windows are checked
 *  against the distances of the edge's end vertices (Xin & Wang 2009) and trimmed against each
 *  other where one is shorter (Mitchell, Mount & Papadimitriou 1987); the window that reaches the
 *  face's opposite corner most shortly cuts the rays of the others that cross its own ray inside
 *  the face (one angle, one split). Paths bend only at pseudo-sources: vertices whose total angle
 *  exceeds 2 pi by more than 1e-9 relative, boundary vertices and the vertices listed below.
 *  Windows are dropped or cut only where another real path is shorter, so the result is exact up
 *  to rounding (about 1e-15 relative per unfolded face), never below the geodesic distance beyond
 *  rounding, and never above the shortest edge-graph distance beyond rounding.
 *
 *  Surface semantics: distance is intrinsic, so the winding of faces does not matter: windows
 *  cross every edge shared by exactly two faces whatever their orientation. At a non-manifold
 *  edge (three or more faces) windows continue into every other face at the edge (the shortest
 *  path on the surface as a 2-complex). A face with the same three vertices as a lower-indexed
 *  face counts once; a face with a repeated vertex index is ignored. Boundary edges are walls
 *  passed only through their end vertices. Vertices of degenerate faces (a zero-length edge or a
 *  corner thinner than 1e-12 relative) are pseudo-sources; windows cross a zero-area face at most
 *  once in a row, otherwise the distance there is the one through its vertices (a real path).
 *
 *  workspace: one of this solver's (tg_geodesic_workspace), or NULL for a temporary one.
 *  sources: source_count valid surface points (tg_surface_point_validate; vertex, edge point or
 *  face point; NULL allowed when source_count is 0). With several sources each vertex gets the
 *  distance to the nearest; with none, every vertex gets +inf.
 *  options: NULL for defaults. out_vertex_distance: vertex_count doubles; vertices that no path
 *  reaches (another component, unreferenced vertices, beyond max_distance) get +inf; never NaN.
 *  out_stats: may be NULL; filled on success.
 *
 *  Errors: TG_ERR_INVALID_ARGUMENT (NULL geodesic or out_vertex_distance, NULL sources with a non-zero
 *  count, an invalid source point, a negative or NaN max_distance with TG_FIELD_MAX_DISTANCE, an
 *  unknown limit, a workspace of another solver), TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED (the
 *  progress callback returned non-zero). On any error out_vertex_distance and out_stats are
 *  untouched and nothing leaks.
 *  Complexity: typically a small multiple of n^1.5 window crossings for n vertices (O(n^2 log n)
 *  worst case); memory: the workspace plus about 72 bytes per window slot (as many as were live at
 *  once: the window, its place on the free list and in its list's block of 14).
 *  Thread-safe: geodesic is only read; concurrent calls need distinct workspaces and output arrays. */
TG_API tg_status tg_geodesic_field(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                            const tg_surface_point* sources, size_t source_count,
                            const tg_field_options* options, double* out_vertex_distance, tg_field_stats* out_stats);

/** The exact geodesic distance from the sources to arbitrary surface points (inside faces, on
 *  edges, vertices), and optionally to every vertex, in one propagation: each point's distance is
 *  the least over the windows whose rays reach it while they cross its face, the paths through
 *  the face's corners, and the sources in the face (so it is exact like the vertex distances).
 *  points: point_count valid surface points (NULL when 0); out_point_distance: point_count
 *  doubles (+inf where unreachable or beyond the limit); out_vertex_distance: vertex_count
 *  doubles, or NULL when only the points are wanted: then the propagation stops as soon as
 *  every point is settled (as tg_geodesic_distance_matrix_at's rows; the points' distances are
 *  the same bit for bit). Everything else as tg_geodesic_field (which is this call without
 *  points). Errors: as tg_geodesic_field, and
 *  TG_ERR_INVALID_ARGUMENT for an invalid point or NULL points / out_point_distance with a
 *  non-zero point_count; on error the outputs are untouched. Cost: the field's, plus the windows
 *  crossing the points' faces times the points in them. */
TG_API tg_status tg_geodesic_field_at(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                               const tg_surface_point* sources, size_t source_count,
                               const tg_surface_point* points, size_t point_count, const tg_field_options* options,
                               double* out_point_distance, double* out_vertex_distance, tg_field_stats* out_stats);

/** A segment of a curve on the surface: two surface points with a face in common (consecutive
 *  points of a polyline inside one face or along one edge); a and b the same point: a point. */
typedef struct tg_surface_segment {
    tg_surface_point a, b;
} tg_surface_segment;

/** Checks a segment against the solver's mesh: both ends valid surface points
 *  (tg_surface_point_validate) lying in one kept face (a vertex of it, a point of its edges or
 *  inside it; the same point twice is a point). TG_OK or TG_ERR_INVALID_ARGUMENT with a sentence
 *  in diag (may be NULL). O(valence). Thread-safe. (New in 0.6.2.) */
TG_API tg_status tg_surface_segment_validate(const tg_geodesic* geodesic, const tg_surface_segment* segment,
                                             tg_diag* diag);

/** The exact geodesic distance from curves on the surface (and points), at every vertex and at
 *  surface points: each vertex's distance is the length of the shortest path on the surface to
 *  the nearest point of any segment or source.
 *
 *  Method: a shortest path from a curve leaves it at an end of a segment or at right angles from
 *  its inside. The ends are point sources; the inside of a segment is a source of parallel rays,
 *  a window whose distance is the distance to the segment's line, unfolded across faces like a
 *  point's windows (and trimmed, split and filtered by the same rules), so the result is exact
 *  like tg_geodesic_field's (rounding about 1e-15 relative per unfolded face). In the faces that
 *  hold a segment the distance is the Euclidean distance to it. A segment along an edge lights
 *  the faces on both sides (a boundary edge: its one face); a segment whose only common faces
 *  have zero area lights nothing beyond its ends.
 *
 *  sources: source_count point sources as in tg_geodesic_field (may be 0). segments:
 *  segment_count segments (NULL when 0), each end a valid surface point, the two ends in one kept
 *  face (or the same point); a polyline of K points is K - 1 segments; the mesh's boundary is
 *  tg_geodesic_boundary_segments. points, out_point_distance, out_vertex_distance, options,
 *  out_stats: as tg_geodesic_field_at (out_vertex_distance may be NULL only with points: the run
 *  then stops once the points are settled). With neither sources nor segments every distance is
 *  +inf. options->threads: as tg_geodesic_field (the same bits for every count >= 2).
 *  Errors: TG_ERR_INVALID_ARGUMENT (as tg_geodesic_field_at; an invalid segment end, ends with no
 *  face in common, NULL segments with a non-zero count, no output), TG_ERR_OUT_OF_MEMORY,
 *  TG_ERR_CANCELLED; on error the outputs are untouched. Complexity: as a field from as many
 *  sources; the windows of a long curve are many but short-lived (each is dominated a few faces
 *  away by its neighbours). Thread-safe as tg_geodesic_field. (New in 0.6.2.) */
TG_API tg_status tg_geodesic_curve_field(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                                         const tg_surface_point* sources, size_t source_count,
                                         const tg_surface_segment* segments, size_t segment_count,
                                         const tg_surface_point* points, size_t point_count,
                                         const tg_field_options* options, double* out_point_distance,
                                         double* out_vertex_distance, tg_field_stats* out_stats);

/** The exact shortest path from the nearest point of the sources and curves to `to`: the path
 *  starts at that point (a source, an end of a segment, or a point inside a segment, where the
 *  path leaves the segment at right angles), ends at `to`, and its length is
 *  tg_geodesic_curve_field's distance at `to` (proven: global TG_PATH_PROVEN, as
 *  tg_geodesic_path's exact paths). Method: an exact propagation from all of them ordered toward
 *  `to` (A*, one thread), then the path followed back through the windows to the point it comes
 *  from. sources, segments: as tg_geodesic_curve_field (at least one of either, else the path is
 *  unreachable). options: NULL or with method TG_PATH_EXACT (the default) and certify off (the
 *  path is exact); progress as tg_geodesic_path's. path: the result (points from the curve to
 *  `to`; unreachable when no source or curve lies in `to`'s component: 0 points, length +inf).
 *  Errors: TG_ERR_INVALID_ARGUMENT (NULL geodesic, to or path; NULL sources or segments with a
 *  non-zero count; an invalid point or segment; another method or certify on),
 *  TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED; on error the path is empty. Thread-safe as
 *  tg_geodesic_path. (New in 0.6.2.) */
TG_API tg_status tg_geodesic_curve_path(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                                        const tg_surface_point* sources, size_t source_count,
                                        const tg_surface_segment* segments, size_t segment_count,
                                        const tg_surface_point* to, const tg_path_options* options, tg_path* path);

/** Geodesic Voronoi cells of sites made of curves and points: per vertex the site nearest to it
 *  (the exact distance to the nearest point of each site's sources and segments, as
 *  tg_geodesic_curve_field computes it) and that distance. Ties go to the lowest site.
 *  Method: one field of every site, then one run per site bounded by it (each explores its own
 *  cell), as tg_geodesic_voronoi. sources, segments: as tg_geodesic_curve_field. source_site,
 *  segment_site: the site of each (< site_count); NULL: source i is site i, segment i is site
 *  source_count + i. site_count: the sites (a site with nothing in it labels nothing).
 *  out_vertex_distance, out_vertex_label: vertex_count values (either may be NULL, not both):
 *  +inf and TG_NONE where no site reaches. Errors: TG_ERR_INVALID_ARGUMENT (as
 *  tg_geodesic_curve_field; a site out of range; site_count >= TG_NONE; no output),
 *  TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED; on error the outputs are untouched. Cell boundaries:
 *  tg_geodesic_voronoi's, for point sites only. Complexity: about two fields.
 *  Thread-safe as tg_geodesic_field. (New in 0.6.2.) */
TG_API tg_status tg_geodesic_curve_voronoi(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                                           const tg_surface_point* sources, size_t source_count,
                                           const uint32_t* source_site, const tg_surface_segment* segments,
                                           size_t segment_count, const uint32_t* segment_site, size_t site_count,
                                           const tg_field_options* options, double* out_vertex_distance,
                                           uint32_t* out_vertex_label, tg_field_stats* out_stats);

/** The distance matrix of rows made of curves and points: row k is tg_geodesic_curve_field of
 *  row k's sources and segments (bit for bit), at every vertex (targets NULL, target_count 0:
 *  row_count x vertex_count) or at the targets (row_count x target_count, each row's run stopped
 *  once its targets are settled, as tg_geodesic_distance_matrix_at). source_row, segment_row:
 *  the row of each source and segment (< row_count); NULL: source i is row i, segment i is row
 *  source_count + i (a row with nothing in it is +inf). Rows run in parallel on `threads`
 *  threads (0: the OpenMP default), each on one thread (options->threads must be 0 or 1).
 *  out_matrix: row-major doubles, +inf where unreachable or beyond the options' limit.
 *  Errors: TG_ERR_INVALID_ARGUMENT (as tg_geodesic_curve_field and tg_geodesic_distance_matrix;
 *  a row out of range, row_count >= TG_NONE), TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED; each row
 *  is written only once complete, as tg_geodesic_distance_matrix's. Thread-safe: geodesic is
 *  only read.
 *  (New in 0.6.2.) */
TG_API tg_status tg_geodesic_curve_distance_matrix(const tg_geodesic* geodesic, const tg_surface_point* sources,
                                                   size_t source_count, const uint32_t* source_row,
                                                   const tg_surface_segment* segments, size_t segment_count,
                                                   const uint32_t* segment_row, size_t row_count,
                                                   const tg_surface_point* targets, size_t target_count,
                                                   const tg_field_options* options, int threads, double* out_matrix,
                                                   tg_field_stats* out_stats);

/** The mesh's boundary as segments: every edge of exactly one kept face (duplicate faces and faces
 *  with a repeated vertex do not count; non-manifold edges are not boundary), from vertex to
 *  vertex, in the order of the faces and their corners in the file. out: room for capacity
 *  segments, or NULL to ask for the count; *out_count: the number of boundary edges.
 *  Errors: TG_ERR_INVALID_ARGUMENT (NULL geodesic or out_count), TG_ERR_CAPACITY (out too small;
 *  *out_count still set). O(F). Thread-safe. (New in 0.6.2.) */
TG_API tg_status tg_geodesic_boundary_segments(const tg_geodesic* geodesic, tg_surface_segment* out, size_t capacity,
                                               size_t* out_count);

/** The exact logarithmic map (polar coordinates about a point): for every vertex its exact
 *  geodesic distance from `source` (out_vertex_distance, bit-identical to tg_geodesic_field's for this
 *  source) and the angle at which its shortest path leaves the source (out_vertex_angle, radians).
 *  The 2D coordinates of the map are (r cos a, r sin a).
 *
 *  Method: the field's window propagation, in which every window lit by the source carries the
 *  rotation from its frame to the source's (one record per window, made only here, so plain
 *  fields do not slow down): a vertex lit by a window of the source takes the angle of its ray
 *  there; a vertex in a face holding the source, the angle of the segment to it; a vertex whose
 *  shortest path passes through another vertex w (a saddle or boundary vertex, or along an edge),
 *  w's angle. No approximation beyond rounding (about 1e-15 radians per face unfolded), unlike
 *  the vector heat method's.
 *
 *  Angles: counterclockwise, measured as TG_TRACE_ANGLE measures them at the source's canonical
 *  form (tg_surface_point_canonical), so that tg_geodesic_trace from the source along angle
 *  out_vertex_angle[v] for length out_vertex_distance[v] ends at v wherever its shortest path is unique and
 *  meets no vertex on the way: at a face point from its face's corner 0 towards corner 1, in
 *  [0, 2 pi); at an edge point from its halfedge's start towards its end, in [0, pi] in the
 *  halfedge's face and (pi, 2 pi) beyond the edge; at a vertex from tg_mesh_vertex_halfedges'
 *  halfedge, scaled so the turn around the vertex is 2 pi (in [0, 2 pi)), or pi where the fan of
 *  faces around it is not closed (a boundary vertex: angles in [0, pi] from the boundary side;
 *  at a vertex where several fans meet, a pinch or non-manifold vertex, only the reference fan is
 *  scaled: directions into the other fans measure from their corners' sides, not meaningfully).
 *  reference: NULL, or a 3D vector (finite, not zero, of any length: times any power of two it
 *  gives the same angles bit for bit) taken as the direction of the surface at the source by
 *  the rule of TG_TRACE_VECTOR (a face point: its projection onto the face's plane; a vertex or
 *  an edge point: the direction of the faces there whose projection onto the tangent plane runs
 *  along the vector's), which becomes angle 0: every angle is then the one above minus that
 *  direction's angle (measured as above), taken into [0, 2 pi) except around a boundary vertex.
 *  So a trace from the source with the reference as its TG_TRACE_VECTOR leaves along the log
 *  map's angle 0, and the log map's angle a is TG_TRACE_ANGLE's a + alpha, alpha the angle of
 *  the reference's direction (at a vertex, on the scaled turn).
 *  Ties: where two paths are equally long to the last bit (the cut locus), the angle is the one
 *  of the path the propagation found first; the result is deterministic (the same for the same
 *  input, on any thread count).
 *  Vertices not reached (another component, unreferenced, beyond options' max_distance): distance
 *  +inf and angle 0 (never NaN). The source vertex itself: distance 0, angle 0.
 *
 *  workspace: NULL or one of this solver's. source: a valid surface point. options: as
 *  tg_geodesic_field's (limit, allocator, progress, threads). out_vertex_distance,
 *  out_vertex_angle: vertex_count doubles each. out_stats: may be NULL.
 *  Errors: TG_ERR_INVALID_ARGUMENT (NULL geodesic, source or outputs; an invalid source; bad options;
 *  a reference vector that is zero, NaN or infinite, or that TG_TRACE_VECTOR refuses at the
 *  source (parallel to the normal there: its projection at most 1e-9 of its length); a
 *  reference face of zero area),
 *  TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED. On error the outputs are untouched.
 *  Complexity: the field's, plus O(V) for the angles (BENCHMARKS.md: within 1.2x of the
 *  field's time); memory: the field's plus 24 bytes per window slot and about 40 bytes per
 *  vertex (how each got its distance, the angles, a stack).
 *  Thread-safe as tg_geodesic_field. (New in 0.4.) */
TG_API tg_status tg_geodesic_log_map(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                              const tg_surface_point* source, const double* reference,
                              const tg_field_options* options, double* out_vertex_distance,
                              double* out_vertex_angle, tg_field_stats* out_stats);

/** Parallel transport from a source to every vertex: the tangent vector `vector` at the source
 *  carried along each vertex's exact shortest path (the log map's). Along a path straight in the
 *  unfolding of the faces it crosses, transport keeps the angle between the vector and the path,
 *  so at vertex v the result is the vector at the angle from the path's arriving direction that
 *  it had from the leaving direction at the source (the log map with `vector` as its reference
 *  gives that angle), in the plane of the face holding the path's last segment, with the length
 *  of `vector`. Exact up to rounding, as the log map; no smoothing, unlike the vector heat
 *  method's transport.
 *  vector: 3 finite doubles, not zero, taken as the direction of the surface at the source by the
 *  rule of TG_TRACE_VECTOR (as tg_geodesic_log_map's reference, refused likewise when it is
 *  perpendicular to the surface there). At a vertex source the angles are the fan's own (not scaled
 *  to a turn of 2 pi), measured counterclockwise from the vector, so around a cone vertex the
 *  result depends on which way round the path leaves (the cone's holonomy).
 *  out_vertex_vector: 3 doubles a vertex (x, y, z): 0 where not reached (another component,
 *  beyond options' max_distance; never NaN), `vector` itself at the source vertex and where the
 *  last segment has length 0. out_vertex_flag: NULL or one tg_gradient_flag a vertex:
 *  TG_GRADIENT_DEFINED, TG_GRADIENT_SOURCE (the source, or a last segment of length 0),
 *  TG_GRADIENT_UNREACHED, or TG_GRADIENT_TIE where a second path as short (within 1e-12
 *  relative) arrives from another direction: the cut locus, where transport is undefined (the
 *  vector given there follows the path the log map's angle follows, the one found first).
 *  out_vertex_distance: NULL or vertex_count doubles, the log map's distances. On a surface that
 *  is not orientable the sense of the angles is the solver's orientation of each face.
 *  options: as tg_geodesic_field's (limit, allocator, progress, threads).
 *  Errors: as tg_geodesic_log_map's (a NULL vector or out_vertex_vector too); the outputs are then
 *  untouched. Complexity: the log map's plus O(V) (BENCHMARKS.md). Thread-safe as
 *  tg_geodesic_field. (New in 0.6.1.) */
TG_API tg_status tg_geodesic_transport_field(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                                             const tg_surface_point* source, const double vector[3],
                                             const tg_field_options* options, double* out_vertex_vector,
                                             uint8_t* out_vertex_flag, double* out_vertex_distance,
                                             tg_field_stats* out_stats);

/** What a gradient is at a vertex or face (tg_geodesic_field_gradient). */
typedef enum tg_gradient_flag {
    TG_GRADIENT_DEFINED = 0,   /**< the direction of steepest ascent: the shortest path's arriving direction */
    TG_GRADIENT_SOURCE = 1,    /**< a source (distance 0): no direction; the gradient is (0, 0, 0) */
    TG_GRADIENT_UNREACHED = 2, /**< no path (another component, beyond max_distance): (0, 0, 0) */
    /** (vertices) two sources reach it as shortly (within 1e-12 relative): the field has no
     *  gradient there; the direction given is the labelled source's path's */
    TG_GRADIENT_TIE = 3
} tg_gradient_flag;

/** The gradient of the exact distance field from the sources: at every vertex the unit direction in
 *  which its shortest path arrives (the last segment's, in space, in the plane of the face holding
 *  it: the direction of steepest ascent of the field there, never averaged), the nearest source
 *  and the distance; at every face the same at its centroid, where the field is
 *  sigma + |p - s| for the window (source image s) that reaches it most shortly, so the gradient is
 *  exactly (p - s) / |p - s| in the face's plane. Exact up to rounding, unlike the heat method's
 *  normalised gradient of a smoothed field.
 *  Method: the nearest-source field of tg_geodesic_voronoi with each vertex's record kept (labels
 *  and ties: a vertex two sources reach within 1e-12 relative is TG_GRADIENT_TIE), then, for the
 *  faces, one run of all the sources with the faces' centroids as query points.
 *  Not flagged: where two paths from one source tie (its cut locus) the direction is the path the
 *  propagation found first, as the log map's angle; a face's centroid on a cut locus likewise.
 *  sources: source_count valid surface points (none: everything unreached). Outputs (each may be
 *  NULL, not all): out_vertex_gradient 3 doubles a vertex, out_vertex_flag (tg_gradient_flag)
 *  and out_vertex_label (the index of the nearest source, TG_NONE where unreached) one a vertex,
 *  out_vertex_distance vertex_count doubles (as tg_geodesic_voronoi's); out_face_gradient 3
 *  doubles a face, out_face_flag one a face (DEFINED, SOURCE: a source at the centroid, or
 *  UNREACHED, also for the duplicate faces the solver skips). options: allocator, limit, progress,
 *  threads (each run's).
 *  Errors: TG_ERR_INVALID_ARGUMENT (NULL geodesic, every output NULL, invalid sources or options),
 *  TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED; the outputs are then untouched.
 *  Complexity: tg_geodesic_voronoi's, plus one field with the centroids as points when a face
 *  output is asked. Thread-safe as tg_geodesic_field. (New in 0.6.1.) */
TG_API tg_status tg_geodesic_field_gradient(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                                            const tg_surface_point* sources, size_t source_count,
                                            const tg_field_options* options, double* out_vertex_gradient,
                                            uint8_t* out_vertex_flag, uint32_t* out_vertex_label,
                                            double* out_vertex_distance, double* out_face_gradient,
                                            uint8_t* out_face_flag, tg_field_stats* out_stats);

/** The distance matrix: row i of out_matrix (row-major, source_count x vertex_count doubles) is
 *  the field of sources[i] alone, exactly as tg_geodesic_field computes it (bit-identical). The
 *  same operation is `trigeo field --sources` in the CLI and Mesh.distance_matrix in Python. Rows
 *  are computed in parallel with OpenMP on `threads` threads (0: the OpenMP default; 1: this
 *  thread only), each with the exact engine's scratch of a workspace, made and freed by the call;
 *  the limit, allocator and progress apply to every row (progress is called from one thread at a
 *  time with rows_done / row_count, inside long rows and between rows, about every 5 ms). out_stats (may be NULL): counters summed over the rows,
 *  peak_bytes the largest of one thread's scratch.
 *  Errors: as tg_geodesic_field (every source is validated before any work), and
 *  TG_ERR_INVALID_ARGUMENT for a negative thread count or a matrix size that overflows. Each row
 *  is written only once complete, so on error (or cancellation) out_matrix holds some complete
 *  rows and leaves the others untouched, never a partial row; out_stats is untouched.
 *  Thread-safe as tg_geodesic_field. */
TG_API tg_status tg_geodesic_distance_matrix(const tg_geodesic* geodesic, const tg_surface_point* sources, size_t source_count,
                                  const tg_field_options* options, int threads, double* out_matrix,
                                  tg_field_stats* out_stats);

/** The distance matrix between sources and selected surface points: row i of out_matrix
 *  (row-major, source_count x target_count doubles) holds the distances from sources[i] alone to
 *  targets[0 .. target_count), exactly as tg_geodesic_field_at computes them for that one source
 *  and these points (bit-identical; +inf where unreachable or beyond the limit). Targets may be
 *  vertices, edge points or face points. The same operation is `trigeo field --sources FILE --to
 *  FILE` in the CLI and Mesh.distance_matrix(sources, targets=...) in Python.
 *  Rows run in parallel as in tg_geodesic_distance_matrix (threads: 0 the OpenMP default, 1 this
 *  thread only; one exact-engine scratch per thread, made and freed by the call); options (limit,
 *  allocator, progress) apply to every row (progress as tg_geodesic_distance_matrix's). Each row's field stops as soon as its targets are
 *  settled: once every target has a finite upper bound (a window reaching it, or a reached
 *  vertex of its face plus the segment to it), the row's limit drops to the largest bound, so
 *  near targets cost a disc around the source, not the mesh (a target in another component
 *  keeps the whole component running). The entries are still those of the whole field.
 *  Errors: TG_ERR_INVALID_ARGUMENT (NULL geodesic or out_matrix with a non-zero size, NULL sources or
 *  targets with a non-zero count, an invalid source or target point, bad options, a negative
 *  thread count, a matrix size that overflows); every point is validated before any work.
 *  TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED. Each row is written only once complete, so on error
 *  out_matrix holds some complete rows and leaves the others untouched; out_stats (may be NULL;
 *  counters summed over the rows) is filled only on success.
 *  Complexity: source_count fields, each only as far as its farthest target, plus the targets'
 *  evaluation, divided among the threads; memory: one workspace's engine scratch per thread. Thread-safe as
 *  tg_geodesic_field. (New in 0.4.) */
TG_API tg_status tg_geodesic_distance_matrix_at(const tg_geodesic* geodesic, const tg_surface_point* sources,
                                         size_t source_count, const tg_surface_point* targets, size_t target_count,
                                         const tg_field_options* options, int threads, double* out_matrix,
                                         tg_field_stats* out_stats);

/** A sparse matrix in compressed sparse row form (CSR): a result object (see "Conventions"),
 *  created empty by tg_sparse_matrix_create, filled by tg_geodesic_local_matrix (each call
 *  replaces its content), read through tg_sparse_matrix_get_view, freed by
 *  tg_sparse_matrix_destroy. */
typedef struct tg_sparse_matrix tg_sparse_matrix;

/** Creates an empty matrix (no rows). allocator: the memory of its arrays (NULL: libc); it must
 *  outlive the matrix. Errors: TG_ERR_INVALID_ARGUMENT (NULL out_matrix), TG_ERR_OUT_OF_MEMORY
 *  (*out_matrix NULL). (New in 0.6.) */
TG_API tg_status tg_sparse_matrix_create(const tg_allocator* allocator, tg_sparse_matrix** out_matrix);

/** Read-only view of a sparse matrix, valid until the matrix is filled again or destroyed. Row r holds the
 *  entries row_start[r] .. row_start[r + 1] - 1: column col[k] has the value value[k]; columns
 *  ascend strictly within a row. Absent entries are not zeros: in a local distance matrix they are
 *  the pairs farther apart than the radius (or unreachable); a stored 0.0 is a distance of 0 (the
 *  source vertex itself). These are the arrays scipy.sparse.csr_matrix((value, col, row_start))
 *  takes (SciPy's own layout). */
typedef struct tg_sparse_matrix_view {
    size_t row_count;          /**< rows (the sources) */
    size_t col_count;          /**< columns (the mesh's vertices) */
    size_t entry_count;        /**< stored entries, row_start[row_count] */
    const uint64_t* row_start; /**< row_count + 1 offsets, row_start[0] = 0 */
    const uint32_t* col;       /**< entry_count column indices (NULL when entry_count is 0) */
    const double* value;       /**< entry_count values (NULL when entry_count is 0) */
} tg_sparse_matrix_view;

/** Fills *out_view with the matrix's arrays (all zero for a NULL matrix). O(1). Thread-safe.
 *  (New in 0.4.) */
TG_API void tg_sparse_matrix_get_view(const tg_sparse_matrix* matrix, tg_sparse_matrix_view* out_view);

/** Bytes owned by the matrix: 8 per row plus 12 per entry, and a header. NULL gives 0.
 *  (New in 0.4.) */
TG_API size_t tg_sparse_matrix_memory_bytes(const tg_sparse_matrix* matrix);

/** Frees a matrix (with the allocator it was created with). NULL is a no-op. (New in 0.4.) */
TG_API void tg_sparse_matrix_destroy(tg_sparse_matrix* matrix);

/** The local distance matrix: row i lists every vertex within max_distance of sources[i] (the
 *  geodesic distance along the surface), with that distance, as a sparse matrix of
 *  source_count rows and vertex_count columns. Its entries are bit-identical to the finite
 *  entries of tg_geodesic_field(sources[i]) with limit TG_FIELD_MAX_DISTANCE and this
 *  max_distance, and no vertex that field reaches is missing; each row's field only explores the
 *  disc of radius max_distance around its source. The same operation is `trigeo field --sources
 *  FILE|all --max-distance D -o M.npz` in the CLI and Mesh.distance_matrix(sources,
 *  max_distance=D, sparse=True) in Python.
 *  Symmetry: the distance from a to b and from b to a come from two propagations and agree to
 *  rounding only (measured on fcpw_kitten within 5% of its diagonal: at most 2.6e-15
 *  relative, 1.4e-16 absolute; BENCHMARKS.md), so the matrix of every vertex is
 *  symmetric to rounding, and a pair at distance D to rounding may be stored one way only.
 *
 *  sources: source_count valid surface points (tg_surface_point_validate); or NULL for every
 *  vertex in order (row i is vertex i; source_count must then equal the vertex count, and an
 *  unreferenced vertex, which is not on the surface, gets an empty row).
 *  max_distance: the radius, >= 0 (0 keeps only distance-0 entries), in the unit of the
 *  coordinates; +inf keeps every reachable vertex (the full matrix, stored sparse).
 *  options: allocator (of the call's scratch) and progress as for tg_geodesic_distance_matrix
 *  (inside long rows and between rows, so a matrix of many small discs stops within
 *  milliseconds); the radius is the max_distance argument, so options->limit must be
 *  TG_FIELD_UNLIMITED (TG_FIELD_MAX_DISTANCE is refused rather than ignored).
 *  threads: rows run in parallel with OpenMP (0: the OpenMP default, 1: this thread only), each
 *  thread with an exact-engine scratch made and freed by the call; rows are assembled in
 *  order, so the result is the same whatever the thread count.
 *  matrix: the result (tg_sparse_matrix_create; its old content is replaced, its arrays are made
 *  with its allocator); out_stats: may be NULL, counters summed over the rows, filled on success.
 *  Errors: TG_ERR_INVALID_ARGUMENT (NULL geodesic or matrix, NULL sources with a count other than
 *  the vertex count, an invalid source, a negative or NaN max_distance, options->limit set, a
 *  negative thread count), TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED (the progress callback asked to
 *  stop). On error the matrix is empty (no rows; as a path is) and nothing leaks.
 *  Complexity: one field bounded to the radius per row, divided among the threads; each row
 *  costs time in the windows of its disc and reads only the vertices its run reached (no pass
 *  over all vertices per row). Memory: the result (8 bytes per row, 12 per entry), the rows
 *  finished out of order and waiting for earlier ones, and one workspace's engine scratch per
 *  thread; the entries are gathered in blocks and copied into the final arrays block by block,
 *  each block freed once copied. Thread-safe as tg_geodesic_field. (New in 0.4.) */
TG_API tg_status tg_geodesic_local_matrix(const tg_geodesic* geodesic, const tg_surface_point* sources, size_t source_count,
                                   double max_distance, const tg_field_options* options, int threads,
                                   tg_sparse_matrix* matrix, tg_field_stats* out_stats);


/** The boundaries of geodesic Voronoi cells: a result object (see "Conventions"), created empty
 *  by tg_voronoi_boundaries_create, filled by tg_geodesic_voronoi, read through
 *  tg_voronoi_boundaries_get_view, freed by tg_voronoi_boundaries_destroy. */
typedef struct tg_voronoi_boundaries tg_voronoi_boundaries;

/** Creates an empty boundaries object (no polylines). allocator: the memory of its arrays (NULL:
 *  libc); it must outlive the object. Errors: TG_ERR_INVALID_ARGUMENT (NULL out_boundaries),
 *  TG_ERR_OUT_OF_MEMORY (*out_boundaries NULL). (New in 0.6.) */
TG_API tg_status tg_voronoi_boundaries_create(const tg_allocator* allocator,
                                              tg_voronoi_boundaries** out_boundaries);

/** Geodesic Voronoi labels: for every vertex, the index of its nearest source in exact geodesic
 *  distance, and that distance; optionally the cells' boundaries as polylines on the surface.
 *
 *  Method: the sources' fields are added one at a time, in index order, to a nearest-source
 *  field: each runs the exact engine (as tg_geodesic_field) but passes on only what can get below
 *  the distance of the sources before it (a vertex reached no more shortly starts nothing; a
 *  window is dropped when its least distance over its interval of an edge is at least the largest
 *  over that interval of min(d(a) + |ax|, d(b) + |bx|), d the earlier sources' distance at the
 *  edge's ends), so that each run covers about its own cell. A vertex takes the new source's
 *  distance and label only when strictly shorter, as doubles: a tie goes to the lowest index.
 *  The result is the argmin over the sources' separate fields (tg_geodesic_field of each source
 *  alone), ties to the lowest index, the distance their minimum (each run keeps the windows of
 *  every path that beats the earlier sources, so where it wins it finds the separate field's
 *  value; the tests compare both bit for bit on corpus meshes).
 *
 *  workspace: one of this solver's, or NULL for a temporary one. sources: source_count valid
 *  surface points (any kind; repeated points are allowed: the later one's cell is empty).
 *  options: NULL for defaults; with TG_FIELD_MAX_DISTANCE vertices farther than max_distance
 *  from every source get +inf and TG_NONE; progress (called while fields run and after each
 *  source) is told rows_done = sources done, row_count = source_count.
 *  boundaries: NULL, or a boundaries object (tg_voronoi_boundaries_create) that receives the
 *  cells' boundaries (its old content replaced, its arrays made with its allocator): on every
 *  edge whose end vertices have different labels (both reached, the edge of non-zero length),
 *  the crossing point where the two sources' exact distances are equal within 1e-10 relative
 *  (the search stops there, so crossings typically agree to just under 1e-10: 1.0e-10 at worst
 *  on five corpus meshes; the tests hold them to 1e-9; found by regula falsi, with points
 *  around the false position and the bracket's quarters evaluated together, on distances the
 *  engine evaluates at edge points, one round of runs bounded by the final field per step, at
 *  most 120 rounds; each evaluation is exact where its source is nearest and never below the
 *  true distance elsewhere, so the bracket's signs are exact). Inside each face whose
 *  corners lie in two cells the two crossings are joined by a segment; a face of three cells gets
 *  a junction at the mean of its three crossings (a face point; not itself equidistant). Faces
 *  with an unreached corner have no segments. Segments are chained into polylines between
 *  junctions and ends (the mesh boundary); closed loops repeat their first point at the end.
 *  While the boundaries are found progress is called inside the runs and between them (about
 *  every 5 ms), with rows_done = row_count = source_count.
 *  out_vertex_distance: vertex_count doubles (the distance to the nearest source), or NULL.
 *  out_vertex_label: vertex_count labels (source indices; TG_NONE where no source reaches: other
 *  components, unreferenced vertices, beyond the limit), or NULL.
 *  At least one of the three outputs. out_stats (may be NULL): counters summed over the runs.
 *  Errors: as tg_geodesic_field, and TG_ERR_INVALID_ARGUMENT when all outputs are NULL or
 *  source_count exceeds 0xFFFFFFFE; on error the arrays are untouched and the boundaries object
 *  is empty. Complexity: one run per source over about its cell and its boundary, plus
 *  O(vertex_count) memory for the running field (made with the options' or the solver's
 *  allocator); the boundaries add one such pass per round (each source's run evaluating its
 *  crossings). Thread-safe as tg_geodesic_field. (New in 0.4; in 0.6 the boundaries became a
 *  caller-created object and the distance comes before the label.) */
TG_API tg_status tg_geodesic_voronoi(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                                     const tg_surface_point* sources, size_t source_count,
                                     const tg_field_options* options, tg_voronoi_boundaries* boundaries,
                                     double* out_vertex_distance, uint32_t* out_vertex_label,
                                     tg_field_stats* out_stats);

/** The boundaries' polylines (valid until tg_voronoi_boundaries_destroy). */
typedef struct tg_voronoi_boundaries_view {
    size_t polyline_count;
    const size_t* polyline_start;   /**< polyline_count + 1 offsets: polyline p is points
                                         [polyline_start[p], polyline_start[p + 1]) (two or more) */
    const uint32_t* polyline_cells; /**< 2 per polyline: the labels of the cells on its two sides,
                                         lower first */
    size_t point_count;
    const tg_surface_point* points; /**< edge points (crossings) and face points (junctions) */
    const double* xyz;              /**< 3 per point: their positions */
} tg_voronoi_boundaries_view;

/** Fills *out_view with the boundaries' current content (all zero for NULL, and no polylines before
 *  the first tg_geodesic_voronoi that asked for them); the view's arrays stay valid until the
 *  object is filled again or destroyed. O(1). Thread-safe. (New in 0.4.) */
TG_API void tg_voronoi_boundaries_get_view(const tg_voronoi_boundaries* boundaries,
                                           tg_voronoi_boundaries_view* out_view);
/** Frees the object (with the allocator it was created with). NULL is a no-op. (New in 0.4.) */
TG_API void tg_voronoi_boundaries_destroy(tg_voronoi_boundaries* boundaries);

/** Isolines of an exact field: a result object (see "Conventions"), created empty by
 *  tg_isolines_create, filled by tg_geodesic_isolines, read through tg_isolines_get_view, freed by
 *  tg_isolines_destroy. */
typedef struct tg_isolines tg_isolines;

/** Creates an empty isolines object (no levels). allocator: the memory of its arrays (NULL:
 *  libc); it must outlive the object. Errors: TG_ERR_INVALID_ARGUMENT (NULL out_isolines),
 *  TG_ERR_OUT_OF_MEMORY (*out_isolines NULL). (New in 0.6.) */
TG_API tg_status tg_isolines_create(const tg_allocator* allocator, tg_isolines** out_isolines);

/** Exact isolines: for each level, the curves on the surface where the exact geodesic distance
 *  from the sources (as tg_geodesic_field measures it: the nearest of several sources) equals
 *  the level, as polylines of surface points.
 *
 *  Method: one propagation (tg_geodesic_field) that also records, for every face a level may
 *  meet, the windows crossing it whose distance comes within the face's longest side of a level
 *  (and the point sources in faces). The exact distance in a face is the least of those windows'
 *  distances sigma + |p - s| (each only inside the wedge of rays it lights), of the corners'
 *  distances plus the straight segment, and of the sources in the face. Along an edge the set
 *  where the distance is at most the level is a union of intervals solved in closed form (one
 *  square root per window, over every face at the edge), so crossings are exact to rounding, an
 *  interior minimum of the distance along an edge (a window from a saddle vertex, a hole) gives
 *  its two crossings, and the faces on both sides share them. Inside a face the curve is
 *  followed along the exact circular arcs (centre a window's source image, radius level -
 *  sigma), counterclockwise about the active centre (the nearer side on the left), with steps
 *  short enough that a chord stays within 1e-3 of the face's longest side of its arc; each
 *  point is projected back onto the level (Newton's step on the distance, whose gradient is the
 *  unit vector from the active centre), and where the active centre changes the two circles'
 *  intersection is inserted. The pieces of all faces are joined at their shared edge crossings
 *  and at vertices on the level (a vertex whose distance equals the level to 1e-12 relative: the
 *  curve passes through it, and leaves it into a face along the circle that rules there);
 *  crossings within 1e-6 of the faces' longest side of each other or of a vertex are one node.
 *
 *  Result: per level (in the order given), polylines of two or more points; a polyline is open
 *  where the curve meets the mesh boundary (or stops: see below) and closed when it comes back
 *  to its start (then its first point is repeated at its end and its closed flag is 1). Every
 *  point is a surface point (an edge point where the curve crosses an edge, a face point inside
 *  a face) with its 3D position and a face holding it.
 *  Not covered (documented limits): in faces thinner than about 1e-3 of their length (walls of
 *  thin plates) a curve passing within such a face's width of a vertex may still break into
 *  open polylines there; a closed curve inside one face that meets no edge is found only around
 *  a source in that face (not around a local maximum of the distance). A zero-area face is not
 *  walked: a curve crossing it goes on from its crossing of one side to the crossing (or the
 *  corner on the level) at the same place on another, so the polyline holds that place twice in
 *  a row, the second time with the zero-area face as its face.
 *
 *  workspace: one of this solver's, or NULL for a temporary one. sources, source_count: as
 *  tg_geodesic_field. levels: level_count >= 1 finite values >= 0 (any order, repeats allowed;
 *  the same unit as the coordinates); levels beyond the options' max_distance give no polylines.
 *  options: as tg_geodesic_field; progress is called during
 *  the propagation as for a field, then while the levels are traced (between faces and levels,
 *  about every 5 ms) with front_distance the level, rows_done the levels traced of row_count =
 *  level_count and settled_fraction their share. isolines: the result
 *  (tg_isolines_create; its old content replaced, its arrays made with its allocator).
 *  out_vertex_distance: NULL or vertex_count doubles, the field as
 *  tg_geodesic_field returns it (bit-identical). out_stats: may be NULL.
 *  Errors: as tg_geodesic_field, and TG_ERR_INVALID_ARGUMENT for NULL levels or isolines, a
 *  level_count of 0, a negative, NaN or infinite level. On error the isolines object is empty (no
 *  levels), out_vertex_distance and out_stats are untouched, nothing leaks. Complexity: the field's propagation plus, per level, the faces it meets times the
 *  windows recorded there (a run without levels records nothing: plain fields are not slowed).
 *  Thread-safe as tg_geodesic_field. (New in 0.4.) */
TG_API tg_status tg_geodesic_isolines(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                                      const tg_surface_point* sources, size_t source_count, const double* levels,
                                      size_t level_count, const tg_field_options* options,
                                      tg_isolines* isolines, double* out_vertex_distance,
                                      tg_field_stats* out_stats);

/** Exact isolines of the distance from curves (and points): the offset curves of polylines on
 *  the surface, or of the mesh's boundary, at the given levels. The same as tg_geodesic_isolines
 *  (one implementation: tg_geodesic_isolines is this call with no segments) for the field of
 *  tg_geodesic_curve_field: the run also records the line windows (the rays leaving a segment's
 *  inside at right angles, whose distance is linear: its level sets are straight) and, in the
 *  faces that hold a segment, each side of the segment (the Euclidean distance to it where the
 *  foot of the perpendicular falls inside it; its ends are point sources). Inside a face the curve
 *  is followed along the exact arcs and straight pieces of the lower envelope, and where the
 *  active piece changes (a circle meeting a line, two lines: the offset curve's corners, as at a
 *  reflex corner of the boundary) their exact intersection is inserted. Everything else (edge
 *  crossings solved in closed form, nodes at vertices on the level, chaining, open polylines at the
 *  mesh's boundary, the documented limits) as tg_geodesic_isolines. Levels within about 1e-9 of
 *  the faces' size of the curve are below what the tracing resolves (the two sides of a segment
 *  tie there to rounding) and give short pieces of curve only, as circles about a point source
 *  of radius 1e-7 of the mesh break into pieces; a level of 0 does not draw the curve (draw its
 *  own points).
 *
 *  sources, source_count, segments, segment_count: as tg_geodesic_curve_field (either count may be
 *  0; with neither, no polylines). levels, options, isolines, out_vertex_distance (then the field
 *  as tg_geodesic_curve_field returns it, bit-identical), out_stats: as tg_geodesic_isolines
 *  (options->threads: the same polylines, bit for bit, for every count >= 2).
 *  Errors: as tg_geodesic_isolines, and TG_ERR_INVALID_ARGUMENT for NULL segments with a non-zero
 *  count or an invalid segment (tg_surface_segment_validate). On error the isolines object is
 *  empty, out_vertex_distance and out_stats are untouched, nothing leaks. Complexity: as
 *  tg_geodesic_isolines for a field from as many sources. Thread-safe as tg_geodesic_field.
 *  (New in 0.6.2.) */
TG_API tg_status tg_geodesic_curve_isolines(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                                            const tg_surface_point* sources, size_t source_count,
                                            const tg_surface_segment* segments, size_t segment_count,
                                            const double* levels, size_t level_count,
                                            const tg_field_options* options, tg_isolines* isolines,
                                            double* out_vertex_distance, tg_field_stats* out_stats);

/** Read-only view of isolines (valid until the object is filled again or destroyed). Polylines are grouped by level:
 *  those of level i are level_start[i] .. level_start[i + 1] - 1; polyline p is points
 *  polyline_start[p] .. polyline_start[p + 1] - 1. */
typedef struct tg_isolines_view {
    size_t level_count;
    const double* levels;            /**< the levels, as given */
    const size_t* level_start;       /**< level_count + 1 offsets into the polylines */
    size_t polyline_count;
    const size_t* polyline_start;    /**< polyline_count + 1 offsets into the points */
    const uint8_t* polyline_closed;  /**< 1: a closed curve (its first point repeated at its end) */
    size_t point_count;
    const tg_surface_point* points;  /**< edge points (crossings) and face points */
    const uint32_t* faces;           /**< a face holding each point (the mesh's numbering) */
    const double* xyz;               /**< 3 per point */
} tg_isolines_view;

/** Fills *out_view (all zero for NULL). O(1). Thread-safe. (New in 0.4.) */
TG_API void tg_isolines_get_view(const tg_isolines* isolines, tg_isolines_view* out_view);
/** Frees the object (with the allocator it was created with). NULL is a no-op. (New in 0.4.) */
TG_API void tg_isolines_destroy(tg_isolines* isolines);

/** Farthest-point sampling in exact geodesic distance: sample 0 is start_vertex, and each next
 *  sample is the vertex farthest from all earlier ones (the largest distance to the nearest
 *  sample; +inf, a component no sample reaches yet, counts as farthest; ties to the lowest
 *  vertex index; vertices already sampled and unreferenced vertices are never chosen).
 *
 *  Method: the nearest-source field of tg_geodesic_voronoi, one sample added at a time, each
 *  run passing on only what gets below the earlier samples' distance; the farthest vertex is
 *  found by a scan of the vertices after each run. The result equals the brute-force loop over
 *  the samples' separate fields (tg_geodesic_field of each, their minimum, its argmax).
 *
 *  start_vertex: the first sample, a referenced vertex (used by some face); or TG_NONE to take it
 *  from `seed`: the (s mod R)-th referenced vertex in index order, R their number and s the
 *  SplitMix64 output of the seed (the CLI's --seed and Python's seed= use this). Ignored
 *  otherwise. sample_count: 1 .. the number of referenced vertices. options: NULL for
 *  defaults; the limit must be TG_FIELD_UNLIMITED; progress (while fields run and after each sample) is told rows_done = samples done,
 *  row_count = sample_count. out_samples: sample_count vertex indices in the order chosen.
 *  out_vertex_distance (may be NULL): vertex_count doubles, the distance to the nearest sample
 *  (+inf where none reaches). out_vertex_label (may be NULL): vertex_count labels, the position
 *  in out_samples of the nearest sample (ties to the earliest), TG_NONE where none reaches.
 *  out_stats (may be NULL): counters summed over the runs.
 *  Errors: TG_ERR_INVALID_ARGUMENT (NULL geodesic or out_samples, sample_count 0 or larger than the
 *  referenced vertices, start_vertex out of range or unreferenced, a limit, a workspace of
 *  another solver), TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED; on error the outputs are untouched.
 *  Complexity: one run per sample over about its cell, plus O(vertex_count) per sample for the
 *  scan. Thread-safe as tg_geodesic_field. (New in 0.4.) */
TG_API tg_status tg_geodesic_farthest_point_sampling(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                                                     uint32_t start_vertex, uint64_t seed, size_t sample_count,
                                                     const tg_field_options* options, uint32_t* out_samples,
                                                     double* out_vertex_distance, uint32_t* out_vertex_label,
                                                     tg_field_stats* out_stats);


/* ============================================================================================== */
/* Geodesic means (src/geodesic/mean.c)                                                           */
/* ============================================================================================== */

/** How a geodesic mean's iteration ended. */
typedef enum tg_mean_status {
    TG_MEAN_CONVERGED = 0,     /**< the last step was shorter than the tolerance */
    TG_MEAN_ITERATION_CAP = 1, /**< max_iterations steps were taken first; the point is the last one */
    /** the step could not be walked: the trace from the point went nowhere (a singular vertex,
     *  the boundary in the step's direction) while the step was above the tolerance, or it ended
     *  in zero-area faces only (no direction measurable there); the point is the step's start */
    TG_MEAN_STALLED = 2
} tg_mean_status;

/** "converged", "iteration_cap", "stalled"; "unknown" for other values. Never NULL. (New in 0.6.1.) */
TG_API const char* tg_mean_status_name(tg_mean_status status);

/** What is known of the minimiser's uniqueness (see tg_geodesic_mean, "Uniqueness"). */
typedef enum tg_mean_uniqueness {
    /** the test was made and did not pass: the minimiser may or may not be unique (every mesh
     *  with a vertex of angle sum below 2 pi near the points, e.g. any closed convex surface, or
     *  a hole or handle near them, lands here) */
    TG_MEAN_NOT_CERTIFIED = 0,
    TG_MEAN_UNIQUE = 1,       /**< certified: the mean is the only minimiser on the surface */
    TG_MEAN_NOT_CHECKED = 2   /**< options->skip_uniqueness was set */
} tg_mean_uniqueness;

/** "not_certified", "unique", "not_checked"; "unknown" for other values. Never NULL. (New in 0.6.1.) */
TG_API const char* tg_mean_uniqueness_name(tg_mean_uniqueness uniqueness);

/** Options of tg_geodesic_mean. NULL or all-zero means defaults. */
typedef struct tg_mean_options {
    /** stop when a step is at most tolerance times the diagonal of the bounding box of the
     *  mesh's referenced vertices; 0: 1e-10. Negative, NaN or infinite: TG_ERR_INVALID_ARGUMENT. */
    double tolerance;
    uint32_t max_iterations; /**< the most steps; 0: 100 */
    /** NULL, or the point the iteration starts from (a valid surface point in the points'
     *  component); NULL: the point of largest weight (the lowest index on ties) */
    const tg_surface_point* start;
    int skip_uniqueness; /**< non-zero: no uniqueness test (TG_MEAN_NOT_CHECKED; saves its field) */
    /** the memory of a temporary workspace and of the call's scratch; NULL: the solver's */
    const tg_allocator* allocator;
    /** Called while the fields run (about every 5 ms) and after each step: rows_done the steps
     *  taken, row_count max_iterations, front_distance the field's front, settled_fraction the
     *  share of the cap done. Non-zero stops the call: TG_ERR_CANCELLED. NULL: none. */
    tg_field_progress_fn progress;
    void* progress_user;
} tg_mean_options;

/** The result of tg_geodesic_mean. Distances in the unit of the coordinates. */
typedef struct tg_mean_result {
    tg_surface_point point; /**< the mean (canonical form, tg_surface_point_canonical) */
    double xyz[3];          /**< its position */
    /** the weighted mean of the squared exact distances from the mean to the points,
     *  sum w_i d_i^2 / sum w_i: the function minimised (its gradient is -2 sum w_i log(x_i) /
     *  sum w_i) */
    double energy;
    /** |sum w_i log(x_i)| / sum w_i at the mean: the length of the step the iteration would take
     *  next (0 at an exact critical point; at most the tolerance when converged) */
    double gradient_norm;
    double radius;          /**< the largest exact distance from the mean to a point of positive weight */
    uint32_t iterations;    /**< steps taken (walked traces; a halved step counts once more) */
    uint32_t halvings;      /**< steps walked again at half length because the energy rose */
    uint32_t fields;        /**< exact field runs made (one per step and halving, one for the test) */
    tg_mean_status status;
    tg_mean_uniqueness uniqueness;
} tg_mean_result;

/** The weighted geodesic mean (Karcher / Fréchet mean) of surface points: the point m of the
 *  surface minimising sum w_i d(m, x_i)^2, d the exact geodesic distance.
 *
 *  Method: from the start point p, repeatedly p <- exp_p(v), v = sum w_i log_p(x_i) / sum w_i.
 *  log_p(x_i) is the vector at p of length d(p, x_i) along the direction in which the exact
 *  shortest path to x_i leaves p: one exact field from p with the x_i as query points (stopped
 *  once they are settled, tg_geodesic_field_at's engine), each path followed back through the
 *  windows (TG_PATH_EXACT's backtrack) and its straight first run (up to the first vertex it
 *  passes, or x_i) unfolded into p's face, so the direction is exact to rounding however short
 *  the path's first segment. The vectors are summed as TG_TRACE_ANGLE measures directions at p:
 *  in a face and at a point of an edge the plane of the face (the two faces of the edge unfolded
 *  into one plane), exact; at a vertex the fan's angles scaled so the turn is 2 pi (pi at a
 *  boundary vertex), as the log map's angles (tg_geodesic_log_map). exp_p(v) is
 *  tg_geodesic_trace from p along v's angle for v's length. On a flat region one step lands on
 *  the weighted average of the points (the exact answer there). Where the surface curves, the
 *  plain step over- or undershoots by a factor the iteration keeps repeating, so after the first
 *  step v's component along the direction in which the last step arrived is divided by the
 *  secant lambda = (that step's own component - v's) / its length, the energy's curvature along
 *  it relative to a flat one, when lambda is in [0.25, 4] (not after a step from a vertex, whose
 *  scaled angles measure no component; on fcpw_kitten this took 25 steps down to 14). When a
 *  step raises the energy (sum w_i d_i^2 / sum w_i) by more than 1e-12 relative, it is walked
 *  again from its start at half the length (halvings), after one try of the vertex nearest to
 *  the step's middle (taken when its energy is lower): where the points' paths bend at a
 *  saddle or boundary vertex the energy has a corner there, its minimum may be that vertex, and
 *  the gradient never vanishes (steps from a vertex are walked again at a sixteenth of their
 *  length until below the tolerance: the vertex is then the answer, gradient_norm its pull).
 *  The iteration stops when both the step
 *  and |v| are at most the tolerance (TG_MEAN_CONVERGED), after max_iterations steps, or when a
 *  trace cannot move.
 *  The iteration finds a critical point near its start: on data spread over a closed surface a
 *  mean may be a local minimiser only; give `start` to choose where to look. At a vertex of angle
 *  sum below 2 pi (a cone: every vertex of a closed convex mesh) the energy has a ridge, not a
 *  minimum: stepping off the vertex shortens the distances to the points on that side more than
 *  it lengthens the others' (their directions span less than 2 pi), so the minima of points
 *  placed symmetrically about such a vertex lie on a small ring around it (on an icosphere of
 *  level 3, 0.002 from the vertex for points 0.5 away; tests/test_mean.c); the vertex itself is
 *  returned only when the iteration starts there and the vectors cancel. Where the minimiser
 *  presses against the boundary or sits at a saddle vertex the paths bend at (points around a
 *  hole: its corner) it is no critical point: the vertex try above finds a minimum at a vertex
 *  (tests/test_mean.c, a flat annulus); one on a boundary edge is approached until the cap
 *  (TG_MEAN_ITERATION_CAP, gradient_norm the outward pull) or a stall (TG_MEAN_STALLED also when
 *  a step ends in zero-area faces only, where no direction can be measured: the step's start is
 *  returned). On 9 corpus meshes with
 *  boundaries, saddles and non-manifold edges, 6 random points each, 6 trials: 44 of 54 converged
 *  in 40 steps, the others at the cap, none failed.
 *
 *  Uniqueness (after the iteration, unless skip_uniqueness): with R the largest distance from
 *  the mean m to the points of positive weight, every minimiser lies within 2R of m and every
 *  shortest path that matters within 4R (triangle inequality). The test takes K, the faces with
 *  a vertex nearer to m than 4R plus the face's longest side (an exact field bounded there), and
 *  certifies TG_MEAN_UNIQUE when K is a topological disc (connected, every edge in at most two
 *  of its faces, at every vertex 0 or 2 of its edges on its border, Euler characteristic 1) and
 *  every vertex inside K has a closed fan of angle sum at least 2 pi (flat or saddle, within
 *  1e-13 relative). Then K with its own length metric is CAT(0) (Bridson & Haefliger 1999,
 *  II.5.6 and II.4.1: a simply connected polyhedral surface whose vertex links have no loop
 *  shorter than 2 pi), where the squared distance is strictly convex along geodesics, so the
 *  energy has one minimiser (R = 0 counts as unique). The test is sufficient, not necessary:
 *  TG_MEAN_NOT_CERTIFIED says nothing either way (points near a vertex of positive curvature,
 *  or around a hole, are never certified, though their mean is often unique).
 *
 *  points: count >= 1 valid surface points, all in one component of the mesh (points of weight 0
 *  are validated and then ignored). weights: NULL (all 1), or count finite values >= 0, not all
 *  0. workspace: NULL or one of this solver's. options: NULL for defaults. out: the result.
 *  Errors: TG_ERR_INVALID_ARGUMENT (NULL geodesic, points or out; count 0; an invalid point; points
 *  in different components (no path joins them); a negative, NaN or infinite weight or all
 *  weights 0; a bad tolerance; an invalid start or one in another component; a workspace of
 *  another solver), TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED, TG_ERR_INTERNAL (a path could not be
 *  followed back: a bug); on error *out is untouched.
 *  Complexity: per step one exact field from p as far as the farthest point (a few paths' work
 *  for near points, a field's for spread ones) plus the K backtracks; the uniqueness test one
 *  field bounded to about 4R. Figures in BENCHMARKS.md. Thread-safe as tg_geodesic_field.
 *  (New in 0.6.1.) */
TG_API tg_status tg_geodesic_mean(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                                  const tg_surface_point* points, const double* weights, size_t count,
                                  const tg_mean_options* options, tg_mean_result* out);


/* ============================================================================================== */
/* Geodesic Bézier curves (src/geodesic/bezier.c)                                                 */
/* ============================================================================================== */

/** How tg_geodesic_bezier_with interpolates between two points a and b at each level of de Casteljau's
 *  construction. */
typedef enum tg_bezier_method {
    /** the point at fraction t of the arclength of the exact shortest path from a to b (default) */
    TG_BEZIER_PATHS = 0,
    /** exp_a(t log_a(b)): the trace from a (tg_geodesic_trace) along the direction in which the
     *  exact shortest path to b leaves a (the exact log map at a, as tg_geodesic_mean measures it)
     *  for t d(a, b) */
    TG_BEZIER_LOG_MAP = 1,
} tg_bezier_method;

/** A geodesic Bézier curve: de Casteljau's construction on the surface with exact shortest
 *  paths or the exact exponential and log maps, sampled at sample_count parameters
 *  t = j / (sample_count - 1), j = 0 .. sample_count - 1.
 *
 *  Method: for each t, the control points P_0 .. P_n are replaced n times by the points at
 *  parameter t between consecutive points; the one point left is the curve's point at t.
 *  TG_BEZIER_PATHS: the point at fraction t of the arclength of the exact shortest path
 *  (tg_geodesic_path, TG_PATH_EXACT, proven) between the two; each path is computed once where t
 *  does not change it (the n paths between the control points are shared by every sample); a
 *  point at arclength s of a path is in the face of the segment holding it, its barycentric
 *  coordinates interpolated between the segment's ends. TG_BEZIER_LOG_MAP: exp_a(t log_a(b)),
 *  one exact field from a (stopped once b is settled) for the direction in which the shortest
 *  path to b leaves a, then the trace along it for t d(a, b). The two agree wherever the
 *  shortest path from a to b is one straight unfolding (it passes no vertex): then the trace
 *  follows it; where it bends round a saddle or boundary vertex, the trace goes straight on past
 *  the vertex instead (on an icosphere, whose vertices are all cones, with the control points
 *  within a quarter of the radius: within 1e-12 of the radius; tests/test_bezier.c). On a flat
 *  region both are the planar Bézier curve of the control points. Where a shortest path is not
 *  unique (the cut locus), the one the propagation finds is taken, so the curve may jump there.
 *  The curve starts at P_0 and ends at P_n (exactly those points).
 *
 *  controls: control_count >= 1 valid surface points (any kind), all in one component.
 *  sample_count: >= 2. method: a tg_bezier_method (others: TG_ERR_INVALID_ARGUMENT). options:
 *  NULL, or tg_geodesic_path's options with method TG_PATH_EXACT (others refused); their progress
 *  callback is told rows_done = samples done of row_count = sample_count, from inside the fields
 *  and between them. workspace: NULL or one of this solver's. out_points: sample_count surface
 *  points (canonical form); out_xyz: NULL or 3 * sample_count doubles, their positions.
 *  Errors: TG_ERR_INVALID_ARGUMENT (NULL geodesic, controls or out_points; control_count 0;
 *  sample_count below 2; an unknown method; an invalid control point; control points in
 *  different components; options tg_geodesic_path_through refuses), TG_ERR_OUT_OF_MEMORY,
 *  TG_ERR_INTERNAL (as tg_geodesic_path), TG_ERR_CANCELLED; on error the outputs are untouched.
 *  Complexity: TG_BEZIER_PATHS n exact paths, plus n (n - 1) / 2 per sample; TG_BEZIER_LOG_MAP
 *  n (n + 1) / 2 fields and traces per sample (between nearby points: a small region's
 *  propagation each). Thread-safe for distinct workspaces. (New in 0.6.2; tg_geodesic_bezier, new
 *  in 0.6.1, is this call with TG_BEZIER_PATHS.) */
TG_API tg_status tg_geodesic_bezier_with(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                                         const tg_surface_point* controls, size_t control_count, size_t sample_count,
                                         tg_bezier_method method, const tg_path_options* options,
                                         tg_surface_point* out_points, double* out_xyz);

/** tg_geodesic_bezier_with with TG_BEZIER_PATHS (exact shortest paths): the 0.6.1 entry point.
 *  (New in 0.6.1.) */
TG_API tg_status tg_geodesic_bezier(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                                    const tg_surface_point* controls, size_t control_count, size_t sample_count,
                                    const tg_path_options* options, tg_surface_point* out_points, double* out_xyz);

/* ============================================================================================== */
/* Centroidal Voronoi tessellations (src/geodesic/centroidal.c)                                   */
/* ============================================================================================== */

/** Options of tg_geodesic_centroidal_voronoi. NULL or all-zero means defaults. */
typedef struct tg_centroidal_options {
    uint32_t iterations; /**< the most Lloyd iterations; 0: 10 */
    /** stop when no site moved more than tolerance times the bounding box's diagonal (straight
     *  distance between its old and new positions); also each cell mean's tolerance
     *  (tg_mean_options); 0: 1e-7. Negative, NaN or infinite: TG_ERR_INVALID_ARGUMENT. */
    double tolerance;
    const tg_allocator* allocator; /**< the call's scratch and temporary workspace; NULL: the solver's */
    /** Called from inside the fields and means (about every 5 ms): rows_done the iterations
     *  done of row_count = iterations. Non-zero stops the call: TG_ERR_CANCELLED. NULL: none. */
    tg_field_progress_fn progress;
    void* progress_user;
} tg_centroidal_options;

/** A geodesic centroidal Voronoi tessellation (geodesic Lloyd): K sites, each moved to the
 *  geodesic mean of its exact Voronoi cell, repeatedly.
 *
 *  Method: Lloyd's iteration on the exact Voronoi cells, clipped inside the faces. The vertices
 *  are labelled as tg_geodesic_voronoi labels them (each to its nearest site in exact distance).
 *  Each face is then split between its candidate cells: those of its corners, of the vertices
 *  across its edges and of the sites in it, and every cell whose piece in a face next to it runs
 *  along the shared edge (repeated until no face gains one, at most 16 rounds and 8 cells a
 *  face, so the thin tip of a cell crossing faces that hold none of its vertices is found).
 *  For every candidate i the exact distances d_i from its site to the face's three corners are
 *  evaluated (one run per site, bounded by the labelling's field plus 4 times the longest edge).
 *  In the face's plane d_i^2 is taken as q_i = |y|^2 + the linear function through the three
 *  corner values; q_i - q_j is linear, so cell i's piece, where q_i is the least (ties to the
 *  lower index), is the triangle clipped by straight lines. q_i = d_i^2 exactly wherever the
 *  site's shortest paths into the face unfold straight (d_i = |y - s'| with s' the site's image:
 *  no bend at a vertex, no cut locus of the site in the face), so there the pieces are bounded by
 *  the exact bisectors and everything below is exact; elsewhere |q_i - d_i^2| <= 2 d h + 2 h^2 (h
 *  the face's longest side, d the distance; O(h^2) away from the bending vertex).
 *  Quadrature (stated exactly): E = sum over cells of the integral of q_i over the cell's pieces,
 *  computed in closed form as sum over cells i and vertices v of W_i(v) d_i(v)^2 minus sum over
 *  faces of A (a^2 + b^2 + c^2) / 12 (A the face's area, a, b, c its sides: the integral of the
 *  gap between |y|^2 and its linear interpolant), where W_i(v) is the integral over cell i's
 *  pieces of v's hat function (its barycentric coordinate). An iteration moves each site to the
 *  weighted geodesic mean of the vertices v with weights W_i(v) (tg_geodesic_mean from the site,
 *  at most 2 steps, no uniqueness test): the subtracted term does not depend on the site, so this
 *  minimises the cell's part of E (on a flat region: the exact centroid of the polygonal cell).
 *  The old site is kept when the mean does not lower that part; then the cells are made again.
 *  Both halves lower E (the mean by the check; the new pieces are where the q are least), so the
 *  energies never increase (to the rounding of the exact distances, ~1e-15 relative). Empty cells
 *  keep their site. It stops after `iterations` iterations or when no site moved more than the
 *  tolerance. On a flat region it is the planar Lloyd iteration of the continuous domain
 *  (tests/test_centroidal.c compares energies and sites to 1e-12 with cells clipped by the
 *  straight bisectors of all the sites; the lumped-area quadrature of earlier builds, each cell
 *  its vertices, was 1.2-1.5% off in energy there, its sites up to 0.7 of an edge away).
 *
 *  start_sites: NULL to start from farthest-point sampling (tg_geodesic_farthest_point_sampling
 *  with start_vertex TG_NONE and `seed`), or site_count valid surface points. site_count: >= 1;
 *  without start_sites at most the referenced vertices. options: NULL for defaults. workspace:
 *  NULL or one of this solver's. out_sites: site_count surface points, the final sites.
 *  out_vertex_label: NULL or vertex_count labels of the final cells (TG_NONE: unreferenced or
 *  unreached). out_energies: NULL or room for iterations + 1 values: E before the first
 *  iteration and after each (*out_iteration_count + 1 written). out_iteration_count: NULL or the
 *  iterations made.
 *  Errors: TG_ERR_INVALID_ARGUMENT (NULL geodesic or out_sites, site_count 0 or above the
 *  referenced vertices without start sites, an invalid start site, a bad tolerance),
 *  TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED, and the errors of the calls it makes; on error the
 *  outputs are untouched. Complexity: per iteration one Voronoi labelling (about one field), the
 *  corner distances (runs bounded to each cell and a margin: about one field) and K means over
 *  the cells (each a few fields bounded to its cell); figures in BENCHMARKS.md. Thread-safe as
 *  tg_geodesic_field. (New in 0.6.1.) */
TG_API tg_status tg_geodesic_centroidal_voronoi(const tg_geodesic* geodesic, tg_geodesic_workspace* workspace,
                                                const tg_surface_point* start_sites, uint64_t seed,
                                                size_t site_count, const tg_centroidal_options* options,
                                                tg_surface_point* out_sites, uint32_t* out_vertex_label,
                                                double* out_energies, size_t* out_iteration_count);

/* ============================================================================================== */
/* Pictures (src/render)                                                                          */
/* ============================================================================================== */

/** The memory budget of tg_render_png: 16 bytes per sample (width x height x supersample^2)
 *  plus 7 per pixel may not exceed it (2 GiB). The default supersampling (3 x 3) is lowered to
 *  2 x 2 or 1 x 1 for pictures that would not fit (beyond about 3770 x 3770 and 5500 x 5500
 *  pixels); an explicit supersample that does not fit is refused. */
#define TG_RENDER_MAX_BYTES ((size_t)2 << 30)

/** Render progress: fraction in [0, 1]; return non-zero to stop (TG_ERR_CANCELLED). */
typedef int (*tg_render_progress_fn)(void* user, double fraction);

/** What to draw and how. A zero-initialised struct (or NULL) means: 960 x 720 pixels, the default
 *  three-quarter view, the mesh in neutral grey, no overlay. */
typedef struct tg_render_options {
    int width, height;            /**< pixels; 0: 960 x 720; each at most 8192 */
    double view_dir[3];           /**< direction the camera looks along (world space); zero: the
                                       default view (0.55, -0.35, 1), i.e. from -z, slightly
                                       above and to the right. Orthographic projection. */
    double up[3];                 /**< world "up" for the camera; zero: +y (or +z if the view is
                                       along y) */
    const double* vertex_scalar;  /**< optional: one value per vertex, drawn with a perceptual
                                       colour map (dark blue = low, yellow = high) and isolines;
                                       non-finite values (e.g. +inf: unreachable) are drawn grey */
    int isolines;                 /**< number of isolines over the scalar's finite range; 0: 16;
                                       negative: none */
    const double* polyline;       /**< optional: 3 * polyline_count doubles, drawn as a red tube
                                       over the surface (depth-tested, slightly lifted toward the
                                       camera), endpoints as dots */
    size_t polyline_count;
    int supersample;              /**< samples per pixel side for anti-aliasing, 1..8; 0: 3, or
                                       fewer where TG_RENDER_MAX_BYTES needs; 1: none */
    /** Called every few thousand faces and picture rows from the rendering thread (NULL: none),
     *  and once more after the PNG encoding (which does not report; since 0.5); non-zero stops
     *  the call with TG_ERR_CANCELLED, before the file is opened. (New in 0.3.) */
    tg_render_progress_fn progress;
    void* progress_user;
    /** optional: one cell label per vertex (tg_geodesic_voronoi): each face is painted piecewise
     *  by the label of its nearest corner, every label in its own colour (hues spaced by the
     *  golden ratio), TG_NONE grey; drawn instead of vertex_scalar */
    const uint32_t* vertex_label;
    /** optional: split the polyline into polyline_parts polylines, part p being points
     *  [polyline_start[p], polyline_start[p + 1]) (polyline_parts + 1 non-decreasing offsets, the
     *  last at most polyline_count), drawn as dark tubes without end dots (cell boundaries);
     *  NULL / 0: one red polyline with its end dots */
    const size_t* polyline_start;
    size_t polyline_parts;
    /** optional: two coordinates (u, v) per vertex, such as a log map's (tg_geodesic_log_map:
     *  u = r cos a, v = r sin a), drawn as the standard checkerboard of texture maps: (u, v)
     *  interpolated linearly over each face, squares of side checker_size coloured by the parity
     *  of floor(u / s) + floor(v / s); a face with a non-finite corner grey; drawn instead of
     *  vertex_scalar and vertex_label (New in 0.4.) */
    const double* vertex_uv;
    /** the squares' side in the unit of (u, v); 0: the mesh's bounding box diagonal / 40 */
    double checker_size;
    /** optional: exact isolines (tg_geodesic_isolines) drawn instead of the colour bands of
     *  vertex_scalar's isolines: isoline_parts polylines, part p being the points
     *  [isoline_start[p], isoline_start[p + 1]) of isoline_xyz (3 doubles each; isoline_parts + 1
     *  non-decreasing offsets), drawn as thin depth-tested lines in the colour map's colour of
     *  their level, darkened (isoline_level: one value per part, in vertex_scalar's units; NULL,
     *  or no vertex_scalar: dark grey). With isoline_parts > 0 no bands are drawn. (New in 0.4.) */
    const double* isoline_xyz;
    const size_t* isoline_start;
    const double* isoline_level;
    size_t isoline_parts;
} tg_render_options;

/** Renders the mesh (software rasterizer, z-buffer, smooth two-sided headlight shading) with the
 *  optional scalar field and polyline, and writes an 8-bit RGB PNG (libpng) to png_path.
 *  Degenerate faces are skipped; an empty mesh gives a background-only image. Deterministic: the
 *  same inputs give the same bytes, and a mesh (with its polyline and isolines) scaled by a power
 *  of two gives the same bytes (depths and normals are measured scale-free; at other scales the
 *  same picture to rounding). Errors: TG_ERR_INVALID_ARGUMENT (NULL mesh/path, size out of
 *  range, over TG_RENDER_MAX_BYTES (diag says how much it would need), polyline_count > 0 with NULL
 *  polyline, polyline_parts > 0 with NULL or out-of-order polyline_start, isoline_parts > 0 with NULL or out-of-order
 *  arrays or a non-finite point), TG_ERR_OUT_OF_MEMORY, TG_ERR_IO (cannot write), TG_ERR_CANCELLED (progress said
 *  stop; no file is written). Cost: O(F + pixels * supersample^2), memory at most
 *  TG_RENDER_MAX_BYTES plus the mesh's projected vertices. Thread-safe (no shared state). */
TG_API tg_status tg_render_png(const tg_mesh* mesh, const tg_render_options* options, const char* png_path,
                        tg_diag* diag);


#ifdef __cplusplus
}
#endif

#endif /* TRIGEO_H */
