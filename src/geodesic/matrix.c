/* matrix.c - distance matrices of many exact fields, one field per row, rows in parallel: the
 * dense matrix (sources x vertices), the sparse local matrix (every vertex within a radius of each
 * source, compressed sparse rows) and the matrix between sources and selected surface points
 * (each row's field stopped once its points are settled).
 * Based on: the exact engine of field/engine.h (Qin et al. 2016), whose run bounded by a distance
 *   explores only the disc within it and notes every vertex it wrote, so a row of the local
 *   matrix costs its disc, not the mesh; compressed sparse rows (W. F. Tinney and J. W. Walker,
 *   "Direct solutions of sparse network equations by optimally ordered triangular
 *   factorization", Proc. IEEE 55(11), 1967; the layout SciPy's csr_matrix reads). */
#include "geodesic/field.h"
#include "geodesic/field/scratch.h"

#include <stdlib.h>
#include <string.h>
#ifdef TG_HAVE_OPENMP
#include <omp.h>
#endif

struct tg_sparse_matrix {
    tg_allocator allocator;
    size_t row_count, col_count, entry_count;
    uint64_t* row_start;
    uint32_t* col;
    double* value;
};

/* ---- assembling rows in order ---- */

/* Entries go into blocks that grow from BLOCK_FIRST to BLOCK_MAX entries, and are copied block by
 * block into the final arrays (each freed once copied), so the peak is the result plus one block,
 * and no block is larger than a few megabytes. */
#define BLOCK_FIRST 4096u
#define BLOCK_MAX ((size_t)1 << 20)

typedef struct csr_block {
    uint32_t* col;
    double* value;
    size_t count, capacity;
} csr_block;

/* A row finished before an earlier one: one allocation, its count, then the values, then the
 * columns (the count's 8 bytes keep the values aligned). */
typedef struct pending_row {
    size_t count;
} pending_row;

static double* pending_values(pending_row* p)
{
    return (double*)(p + 1);
}

static uint32_t* pending_cols(pending_row* p)
{
    return (uint32_t*)(pending_values(p) + p->count);
}

/* The matrix being assembled: rows [0, next) are appended to the blocks, later finished rows
 * wait in pending[] (under the batch's lock). */
typedef struct csr_build {
    uint64_t* row_start; /* rows + 1 */
    pending_row** pending; /* rows; NULL: not finished, or appended */
    size_t next;
    tg__vec blocks;      /* csr_block */
    size_t entries;
} csr_build;

static bool csr_append(const tg_allocator* a, csr_build* c, const uint32_t* col, const double* value, size_t n)
{
    while (n) {
        csr_block* last = c->blocks.count ? (csr_block*)c->blocks.data + c->blocks.count - 1 : NULL;
        if (!last || last->count == last->capacity) {
            size_t cap = last ? 2 * last->capacity : BLOCK_FIRST;
            if (cap > BLOCK_MAX) cap = BLOCK_MAX;
            if (!tg__vec_reserve(a, &c->blocks, 1)) return false;
            csr_block b = {tg__alloc_array(a, cap, sizeof(uint32_t)), tg__alloc_array(a, cap, sizeof(double)), 0, cap};
            if (!b.col || !b.value) {
                tg__free(a, b.col), tg__free(a, b.value);
                return false;
            }
            ((csr_block*)c->blocks.data)[c->blocks.count++] = b;
            last = (csr_block*)c->blocks.data + c->blocks.count - 1;
        }
        size_t k = last->capacity - last->count;
        if (k > n) k = n;
        memcpy(last->col + last->count, col, k * sizeof *col);
        memcpy(last->value + last->count, value, k * sizeof *value);
        last->count += k, c->entries += k;
        col += k, value += k, n -= k;
    }
    return true;
}

static void csr_build_free(const tg_allocator* a, const tg_allocator* ma, csr_build* c, size_t rows)
{
    for (size_t i = 0; i < c->blocks.count; ++i) {
        csr_block* b = (csr_block*)c->blocks.data + i;
        tg__free(a, b->col), tg__free(a, b->value);
    }
    tg__vec_free(a, &c->blocks);
    for (size_t i = 0; c->pending && i < rows; ++i) tg__free(a, c->pending[i]);
    tg__free(a, c->pending);
    tg__free(ma, c->row_start);
    memset(c, 0, sizeof *c);
}

/* Empties a matrix: its arrays freed, no rows. */
static void sparse_clear(tg_sparse_matrix* m)
{
    tg__free(&m->allocator, m->row_start);
    tg__free(&m->allocator, m->col);
    tg__free(&m->allocator, m->value);
    m->row_start = NULL, m->col = NULL, m->value = NULL;
    m->row_count = m->col_count = m->entry_count = 0;
}

/* The blocks copied into the final arrays, made with the matrix's allocator (each block freed once
 * copied), the row starts (made with it too) handed over; the matrix's old content freed. */
static tg_status csr_finish(const tg_allocator* a, csr_build* c, size_t rows, size_t cols, tg_sparse_matrix* m)
{
    const tg_allocator* ma = &m->allocator;
    uint32_t* col = NULL;
    double* value = NULL;
    if (c->entries) {
        col = tg__alloc_array(ma, c->entries, sizeof(uint32_t));
        value = tg__alloc_array(ma, c->entries, sizeof(double));
        if (!col || !value) {
            tg__free(ma, col), tg__free(ma, value);
            return TG_ERR_OUT_OF_MEMORY;
        }
    }
    size_t at = 0;
    for (size_t i = 0; i < c->blocks.count; ++i) {
        csr_block* b = (csr_block*)c->blocks.data + i;
        memcpy(col + at, b->col, b->count * sizeof(uint32_t));
        memcpy(value + at, b->value, b->count * sizeof(double));
        at += b->count;
        tg__free(a, b->col), tg__free(a, b->value);
        b->col = NULL, b->value = NULL;
    }
    sparse_clear(m);
    m->row_count = rows, m->col_count = cols, m->entry_count = c->entries;
    m->col = col, m->value = value;
    m->row_start = c->row_start;
    c->row_start = NULL;
    return TG_OK;
}

/* ---- the batch: rows in parallel, one engine scratch per thread ---- */

typedef struct batch batch;

/* One thread's share: its engine scratch, its counters, and the row it is building. */
typedef struct worker {
    batch* b;
    tg__field_scratch fs;
    tg_field_stats stats;
    tg__vec cols;   /* uint32_t: the row's columns (mesh vertices), sorted */
    tg__vec spare;  /* uint32_t: the sort's other buffer */
    tg__vec values; /* double: the row's distances, by column */
} worker;

struct batch {
    const tg_geodesic* g;
    const tg_field_options* opt; /* the caller's progress callback */
    tg_allocator alloc;
    size_t rows, done;
    volatile int stop; /* set on cancellation or failure: the other threads stop too */
    int cancelled;     /* the progress callback asked to stop (under the lock) */
    double next_report_s; /* when the next report between rows is due (tg__progress_due) */
#ifdef TG_HAVE_OPENMP
    omp_lock_t lock;   /* one thread at a time in the callback, the counters and the assembly (a
                          lock, not a named critical section: those are exported symbols) */
#endif
    tg_status (*row)(worker* w, size_t i);
    uint32_t* order;                 /* the rows in the order they are run (see row_order) */
    const tg_surface_point* sources; /* the caller's; NULL: row i is vertex i (local matrix) */
    const tg__curve_sites* sites;    /* curve rows: row i is site i (sources NULL) */
    tg_surface_point* targets;       /* the columns of the matrix at points, in the solver's form
                                        (field.h), converted once for every row */
    size_t target_count;
    double limit;                    /* in the solver's frame; +inf: none */
    double* dense;                   /* rows x target_count, or rows x vertices without targets */
    csr_build csr;
};

static void batch_lock(batch* b)
{
#ifdef TG_HAVE_OPENMP
    omp_set_lock(&b->lock);
#else
    (void)b;
#endif
}

static void batch_unlock(batch* b)
{
#ifdef TG_HAVE_OPENMP
    omp_unset_lock(&b->lock);
#else
    (void)b;
#endif
}

static int report_row(void* user, const tg__field_run* run)
{
    batch* b = ((worker*)user)->b;
    int stop;
    batch_lock(b);
    {
        tg_field_progress p;
        tg__field_progress_rows(run, b->done, b->rows, &p);
        stop = b->opt->progress(b->opt->progress_user, &p) != 0;
        if (stop) b->stop = 1, b->cancelled = 1;
    }
    batch_unlock(b);
    return stop;
}

/* A row is done: counted, and between rows the progress callback is called once per period.
 * A row shorter than the period never reports from inside its run (propagate.c reports at most
 * every period from a run's start), so without this a batch of short rows (a local matrix of
 * small discs) would not hear a caller asking to stop until its end. Under the lock. */
static void row_done(batch* b)
{
    b->done++;
    if (!b->opt || !b->opt->progress || b->stop || !tg__progress_due(&b->next_report_s)) return;
    tg_field_progress p = {0.0, (double)b->done / (double)b->rows, b->done, b->rows};
    if (b->opt->progress(b->opt->progress_user, &p) != 0) b->stop = 1, b->cancelled = 1;
}

/* The question of one row: its sources and curve segments (the solver's form), the targets, the
 * limit, the batch's progress and cancellation. Every row of every matrix is asked here, so an
 * engine option that applies to every row (such as stopping once the targets are settled) is set
 * here and nowhere else. */
static tg__field_query row_query(batch* b, worker* w, const tg_surface_point* sources, size_t source_count,
                                 const tg_surface_point* segments, size_t segment_count)
{
    tg__field_query q = {.sources = sources, .source_count = source_count, .segments = segments,
                         .segment_count = segment_count, .points = b->targets,
                         .point_count = b->target_count, .max_distance = b->limit,
                         .progress = b->opt && b->opt->progress ? report_row : NULL, .progress_user = w,
                         .cancel = &b->stop, .stop_at_points = b->target_count > 0};
    return q;
}

/* Runs every row on `threads` threads (0: the OpenMP default); each thread makes its scratch.
 * Returns the most telling error: out of memory before cancellation. */
static tg_status batch_run(batch* b, int threads, tg_field_stats* out_sum)
{
    tg_field_stats sum;
    memset(&sum, 0, sizeof sum);
    tg_status first_error = TG_OK;
    int nthreads = 1;
#ifdef TG_HAVE_OPENMP
    omp_init_lock(&b->lock);
    nthreads = threads > 0 ? threads : omp_get_max_threads();
    if ((size_t)nthreads > b->rows) nthreads = (int)b->rows;
#pragma omp parallel num_threads(nthreads)
#endif
    {
        worker w;
        memset(&w, 0, sizeof w);
        w.b = b;
        w.cols.elem = w.spare.elem = sizeof(uint32_t);
        w.values.elem = sizeof(double);
        tg_status mine = tg__field_scratch_init(&w.fs, b->g, &b->alloc) ? TG_OK : TG_ERR_OUT_OF_MEMORY;
        if (mine != TG_OK) b->stop = 1;
#ifdef TG_HAVE_OPENMP
#pragma omp for schedule(dynamic, 1)
#endif
        for (long long k = 0; k < (long long)b->rows; ++k) {
            if (b->stop || mine != TG_OK) continue;
            mine = b->row(&w, b->order[k]);
            if (mine != TG_OK) {
                b->stop = 1;
                continue;
            }
            batch_lock(b);
            row_done(b);
            batch_unlock(b);
        }
        batch_lock(b);
        {
            tg__field_stats_add(&sum, &w.stats);
            if (mine == TG_ERR_OUT_OF_MEMORY || (mine != TG_OK && first_error == TG_OK)) first_error = mine;
        }
        batch_unlock(b);
        tg__field_scratch_free(&w.fs);
        tg__vec_free(&b->alloc, &w.cols), tg__vec_free(&b->alloc, &w.spare), tg__vec_free(&b->alloc, &w.values);
    }
#ifdef TG_HAVE_OPENMP
    omp_destroy_lock(&b->lock);
#endif
    (void)threads, (void)nthreads;
    /* asked to stop: cancelled, even when the last rows were finished by then */
    if (first_error == TG_OK && (b->done != b->rows || b->cancelled)) first_error = TG_ERR_CANCELLED;
    if (first_error == TG_OK) *out_sum = sum;
    return first_error;
}

static int cmp_u64(const void* x, const void* y)
{
    uint64_t a = *(const uint64_t*)x, c = *(const uint64_t*)y;
    return (a > c) - (a < c);
}

/* The order the rows are run in. Given sources: along the solver's Morton curve of their
 * positions (a source's key is its vertex, or the first corner of its face), so that consecutive
 * rows explore neighbouring discs and find the mesh's tables in cache: 4,000 random vertices of
 * fcpw_kitten.obj within 5% of the diagonal, 4.3 s -> 2.9-4.0 s on one thread (BENCHMARKS.md
 * "Rows in Morton order"). Every vertex (sources NULL): in the mesh's order, whose files usually
 * list neighbours together already: the Morton order gained 4% there, and cost 75% more peak
 * memory in the local matrix, whose rows finished out of order wait in the assembly. Every row's
 * result is the same in any order. */
static bool row_order(batch* b)
{
    const tg_geodesic* g = b->g;
    if (b->rows > UINT32_MAX) return false;
    b->order = tg__alloc_array(&b->alloc, b->rows ? b->rows : 1, sizeof(uint32_t));
    if (!b->order) return false;
    if (!b->sources) {
        for (size_t k = 0; k < b->rows; ++k) b->order[k] = (uint32_t)k;
        return true;
    }
    uint64_t* kv = tg__alloc_array(&b->alloc, b->rows ? b->rows : 1, sizeof(uint64_t));
    if (!kv) return false;
    for (size_t i = 0; i < b->rows; ++i) {
        const tg_surface_point* s = &b->sources[i];
        uint32_t key = s->kind == TG_SURFACE_VERTEX ? g->solver_vertex[s->index]
                       : s->kind == TG_SURFACE_EDGE ? g->tri[3 * (size_t)g->solver_face[s->index / 3]]
                                                    : g->tri[3 * (size_t)g->solver_face[s->index]];
        kv[i] = (uint64_t)key << 32 | (uint64_t)i;
    }
    qsort(kv, b->rows, sizeof *kv, cmp_u64);
    for (size_t k = 0; k < b->rows; ++k) b->order[k] = (uint32_t)kv[k];
    tg__free(&b->alloc, kv);
    return true;
}

/* Sets up the batch (sources NULL: row i is vertex i; targets: the columns at points, if any,
 * converted here to the solver's form, once for every row) and its row order; false: out of
 * memory (batch_free then frees it). */
static bool batch_init(batch* b, const tg_geodesic* g, const tg_field_options* options,
                       const tg_surface_point* sources, size_t rows, const tg_surface_point* targets,
                       size_t target_count)
{
    memset(b, 0, sizeof *b);
    b->g = g;
    b->sources = sources;
    b->opt = options;
    b->alloc = options && options->allocator ? *options->allocator : g->allocator;
    b->rows = rows;
    b->target_count = target_count;
    b->next_report_s = tg__seconds() + TG__PROGRESS_PERIOD_S;
    if (target_count) {
        b->targets = tg__alloc_array(&b->alloc, target_count, sizeof *b->targets);
        if (!b->targets) return false;
        tg__field_points_in(g, targets, target_count, b->targets);
    }
    return row_order(b);
}

static void batch_free(batch* b)
{
    tg__free(&b->alloc, b->order);
    tg__free(&b->alloc, b->targets);
    b->order = NULL, b->targets = NULL;
}

/* ---- dense rows: sources x vertices, or sources x selected points ---- */

static tg_status dense_row(worker* w, size_t i)
{
    batch* b = w->b;
    tg_surface_point src;
    tg__field_query q;
    if (b->sites) { /* a curve row: its site's sources and segments */
        const tg__curve_sites* s = b->sites;
        q = row_query(b, w, s->src + s->src_start[i], s->src_start[i + 1] - s->src_start[i], s->seg + 2 * s->seg_start[i],
                      s->seg_start[i + 1] - s->seg_start[i]);
    } else {
        src = tg__surface_in(b->g, &b->sources[i]); /* the solver's form, once (field.h) */
        q = row_query(b, w, &src, 1, NULL, 0);
    }
    tg__field_run run;
    tg_status st = tg__field_execute(&w->fs, &q, &run);
    if (st != TG_OK) return st;
    if (b->target_count) {
        double* out = b->dense + i * b->target_count;
        for (size_t j = 0; j < b->target_count; ++j) out[j] = run.qdist[j] * b->g->unscale;
    } else {
        tg__field_copy_out(&run, b->dense + i * b->g->vertex_count);
    }
    tg__field_stats_add(&w->stats, &run.stats);
    return TG_OK;
}

/* The dense matrix of sources x columns: the targets (at_points), or every vertex; sites: NULL,
 * or the curve rows (then sources NULL and source_count their number). */
static tg_status dense_matrix(const tg_geodesic* g, const tg_surface_point* sources, size_t source_count,
                              const tg__curve_sites* sites, bool at_points, const tg_surface_point* targets,
                              size_t columns, const tg_field_options* options, int threads, double* out_matrix,
                              tg_field_stats* out_stats)
{
    /* rows spread over `threads`; one field each on one thread */
    if (threads < 0 || (options && options->threads != 0 && options->threads != 1)) return TG_ERR_INVALID_ARGUMENT;
    tg_status st = tg__field_check(g, sources, sites ? 0 : source_count, options);
    if (st == TG_OK && at_points) st = tg__field_check(g, targets, columns, NULL);
    if (st != TG_OK) return st;
    size_t cells;
    if (tg__mul_overflows(source_count, columns, &cells) || cells > SIZE_MAX / sizeof(double))
        return TG_ERR_INVALID_ARGUMENT;
    if (cells > 0 && !out_matrix) return TG_ERR_INVALID_ARGUMENT;
    tg_field_stats sum;
    memset(&sum, 0, sizeof sum);
    if (cells > 0) {
        batch b;
        if (!batch_init(&b, g, options, sources, source_count, targets, at_points ? columns : 0)) {
            batch_free(&b);
            return TG_ERR_OUT_OF_MEMORY;
        }
        b.row = dense_row;
        b.sites = sites;
        b.limit = tg__field_limit(g, options);
        b.dense = out_matrix;
        st = batch_run(&b, threads, &sum);
        batch_free(&b);
        if (st != TG_OK) return st;
    }
    if (out_stats) *out_stats = sum;
    return TG_OK;
}

/* ---- the local matrix ---- */

/* Sorts keys[0 .. n) ascending: insertion for a few, else least significant digit first, 8 bits
 * a pass (a pass whose digit is the same in every key is skipped); tmp holds n. Returns the
 * buffer holding the result (keys or tmp). */
static uint32_t* sort_u32(uint32_t* keys, uint32_t* tmp, size_t n)
{
    if (n < 48) {
        for (size_t i = 1; i < n; ++i) {
            uint32_t k = keys[i];
            size_t j = i;
            for (; j > 0 && keys[j - 1] > k; --j) keys[j] = keys[j - 1];
            keys[j] = k;
        }
        return keys;
    }
    for (unsigned shift = 0; shift < 32; shift += 8) {
        size_t count[256];
        memset(count, 0, sizeof count);
        for (size_t i = 0; i < n; ++i) count[(keys[i] >> shift) & 255u]++;
        if (count[(keys[0] >> shift) & 255u] == n) continue;
        size_t sum = 0;
        for (unsigned d = 0; d < 256; ++d) {
            size_t c = count[d];
            count[d] = sum, sum += c;
        }
        for (size_t i = 0; i < n; ++i) tmp[count[(keys[i] >> shift) & 255u]++] = keys[i];
        uint32_t* t = keys;
        keys = tmp, tmp = t;
    }
    return keys;
}

/* The finished run's vertices within the limit, in the mesh's numbering, ascending, with their
 * distances converted exactly as tg_geodesic_field converts them. Only the vertices the run
 * wrote are read (the scratch's list of them); should a run ever keep no list, every vertex. */
static bool gather_row(worker* w, const tg__field_run* run)
{
    const tg_geodesic* g = w->b->g;
    const tg__field_scratch* fs = &w->fs;
    const uint32_t* list = fs->touched_v.data;
    size_t n = fs->touched_all ? g->vertex_count : fs->touched_v.count;
    const tg_allocator* a = &w->b->alloc;
    w->cols.count = w->values.count = 0;
    if (!tg__vec_fit(a, &w->cols, n) || !tg__vec_fit(a, &w->spare, n)) return false;
    uint32_t* cols = w->cols.data;
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
        uint32_t u = fs->touched_all ? (uint32_t)i : list[i];
        double d = run->vertex_dist[u];
        if (d <= run->max_dist && d < INFINITY) cols[k++] = g->mesh_vertex[u];
    }
    uint32_t* sorted = sort_u32(cols, w->spare.data, k);
    if (sorted != cols) { /* keep the sorted keys in cols */
        tg__vec t = w->cols;
        w->cols = w->spare, w->spare = t;
    }
    w->cols.count = k;
    if (!tg__vec_fit(a, &w->values, k)) return false;
    const uint32_t* c = w->cols.data;
    double* value = w->values.data;
    for (size_t i = 0; i < k; ++i) value[i] = run->vertex_dist[g->solver_vertex[c[i]]] * g->unscale;
    w->values.count = k;
    return true;
}

/* Row i is finished in w: appended now if every earlier row is, else kept aside until they are;
 * every row it was holding up follows it. Under the batch's lock. */
static bool deposit_row(worker* w, size_t i)
{
    batch* b = w->b;
    csr_build* c = &b->csr;
    const tg_allocator* a = &b->alloc;
    if (i != c->next) {
        size_t n = w->cols.count;
        pending_row* p = tg__alloc(a, sizeof *p + n * (sizeof(double) + sizeof(uint32_t)));
        if (!p) return false;
        p->count = n;
        if (n) { /* an empty row's buffers may never have been allocated */
            memcpy(pending_values(p), w->values.data, n * sizeof(double));
            memcpy(pending_cols(p), w->cols.data, n * sizeof(uint32_t));
        }
        c->pending[i] = p;
        return true;
    }
    if (!csr_append(a, c, w->cols.data, w->values.data, w->cols.count)) return false;
    c->row_start[++c->next] = c->entries;
    while (c->next < b->rows && c->pending[c->next]) {
        pending_row* p = c->pending[c->next];
        if (!csr_append(a, c, pending_cols(p), pending_values(p), p->count)) return false;
        tg__free(a, p);
        c->pending[c->next] = NULL;
        c->row_start[++c->next] = c->entries;
    }
    return true;
}

static tg_status local_row(worker* w, size_t i)
{
    batch* b = w->b;
    tg_surface_point vertex = tg_surface_vertex((uint32_t)i);
    w->cols.count = w->values.count = 0;
    /* every vertex: one that no face uses is not on the surface, and its row is empty */
    if (b->sources || tg_surface_point_validate(b->g->mesh, &vertex, NULL) == TG_OK) {
        /* the solver's form, once (field.h; a vertex's is its solver index) */
        tg_surface_point src =
            b->sources ? tg__surface_in(b->g, &b->sources[i]) : tg_surface_vertex(b->g->solver_vertex[i]);
        tg__field_query q = row_query(b, w, &src, 1, NULL, 0);
        tg__field_run run;
        tg_status st = tg__field_execute(&w->fs, &q, &run);
        if (st != TG_OK) return st;
        tg__field_stats_add(&w->stats, &run.stats);
        if (!gather_row(w, &run)) return TG_ERR_OUT_OF_MEMORY;
    }
    batch_lock(b);
    bool ok = deposit_row(w, i);
    batch_unlock(b);
    return ok ? TG_OK : TG_ERR_OUT_OF_MEMORY;
}

/* ---- public entry points ---- */

tg_status tg_geodesic_distance_matrix(const tg_geodesic* g, const tg_surface_point* sources, size_t source_count,
                                      const tg_field_options* options, int threads, double* out_matrix,
                                      tg_field_stats* out_stats)
{
    if (!out_matrix || !g) return TG_ERR_INVALID_ARGUMENT;
    return dense_matrix(g, sources, source_count, NULL, false, NULL, g->vertex_count, options, threads, out_matrix,
                        out_stats);
}

tg_status tg_geodesic_distance_matrix_at(const tg_geodesic* g, const tg_surface_point* sources, size_t source_count,
                                         const tg_surface_point* targets, size_t target_count,
                                         const tg_field_options* options, int threads, double* out_matrix,
                                         tg_field_stats* out_stats)
{
    return dense_matrix(g, sources, source_count, NULL, true, targets, target_count, options, threads, out_matrix,
                        out_stats);
}

tg_status tg_geodesic_curve_distance_matrix(const tg_geodesic* g, const tg_surface_point* sources, size_t source_count,
                                            const uint32_t* source_row, const tg_surface_segment* segments,
                                            size_t segment_count, const uint32_t* segment_row, size_t row_count,
                                            const tg_surface_point* targets, size_t target_count,
                                            const tg_field_options* options, int threads, double* out_matrix,
                                            tg_field_stats* out_stats)
{
    if (!g || (target_count && !targets)) return TG_ERR_INVALID_ARGUMENT;
    const tg_allocator* a = options && options->allocator ? options->allocator : &g->allocator;
    tg__curve_sites sites;
    tg_status st = tg__curve_sites_make(g, a, sources, source_count, source_row, segments, segment_count, segment_row,
                                        row_count, &sites);
    if (st != TG_OK) return st;
    st = dense_matrix(g, NULL, row_count, &sites, target_count > 0, targets, target_count ? target_count : g->vertex_count,
                      options, threads, out_matrix, out_stats);
    tg__curve_sites_free(a, &sites);
    return st;
}

tg_status tg_geodesic_local_matrix(const tg_geodesic* g, const tg_surface_point* sources, size_t source_count,
                                   double max_distance, const tg_field_options* options, int threads,
                                   tg_sparse_matrix* matrix, tg_field_stats* out_stats)
{
    if (!matrix) return TG_ERR_INVALID_ARGUMENT;
    tg_status st = TG_OK;
    if (!g || threads < 0 || !(max_distance >= 0.0) || (options && options->limit != TG_FIELD_UNLIMITED) ||
        (options && options->threads != 0 && options->threads != 1))
        st = TG_ERR_INVALID_ARGUMENT;
    else if (!sources && source_count != g->vertex_count)
        st = TG_ERR_INVALID_ARGUMENT;
    else if (sources)
        st = tg__field_check(g, sources, source_count, NULL);
    if (st == TG_OK && source_count >= SIZE_MAX / sizeof(uint64_t) - 1) st = TG_ERR_OUT_OF_MEMORY;
    if (st != TG_OK) {
        sparse_clear(matrix);
        return st;
    }
    batch b;
    bool ordered = batch_init(&b, g, options, sources, source_count, NULL, 0);
    b.row = local_row;
    b.limit = max_distance * g->scale;
    const tg_allocator* a = &b.alloc;
    b.csr.blocks.elem = sizeof(csr_block);
    b.csr.row_start = tg__calloc_array(&matrix->allocator, source_count + 1, sizeof(uint64_t));
    b.csr.pending = tg__calloc_array(a, source_count ? source_count : 1, sizeof(pending_row*));
    tg_field_stats sum;
    memset(&sum, 0, sizeof sum);
    st = ordered && b.csr.row_start && b.csr.pending ? TG_OK : TG_ERR_OUT_OF_MEMORY;
    if (st == TG_OK && source_count > 0) st = batch_run(&b, threads, &sum);
    if (st == TG_OK) st = csr_finish(a, &b.csr, source_count, g->vertex_count, matrix);
    csr_build_free(a, &matrix->allocator, &b.csr, source_count);
    batch_free(&b);
    if (st != TG_OK) {
        sparse_clear(matrix);
        return st;
    }
    if (out_stats) *out_stats = sum;
    return TG_OK;
}

tg_status tg_sparse_matrix_create(const tg_allocator* allocator, tg_sparse_matrix** out_matrix)
{
    if (!out_matrix) return TG_ERR_INVALID_ARGUMENT;
    *out_matrix = NULL;
    tg_sparse_matrix* m = tg__alloc(allocator, sizeof *m);
    if (!m) return TG_ERR_OUT_OF_MEMORY;
    memset(m, 0, sizeof *m);
    if (allocator) m->allocator = *allocator;
    *out_matrix = m;
    return TG_OK;
}

void tg_sparse_matrix_get_view(const tg_sparse_matrix* m, tg_sparse_matrix_view* out)
{
    if (!out) return;
    memset(out, 0, sizeof *out);
    if (!m) return;
    out->row_count = m->row_count;
    out->col_count = m->col_count;
    out->entry_count = m->entry_count;
    out->row_start = m->row_start;
    out->col = m->col;
    out->value = m->value;
}

size_t tg_sparse_matrix_memory_bytes(const tg_sparse_matrix* m)
{
    if (!m) return 0;
    return sizeof *m + (m->row_count + 1) * sizeof(uint64_t) + m->entry_count * (sizeof(uint32_t) + sizeof(double));
}

void tg_sparse_matrix_destroy(tg_sparse_matrix* m)
{
    if (!m) return;
    sparse_clear(m);
    tg_allocator a = m->allocator;
    tg__free(&a, m);
}
