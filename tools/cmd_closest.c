/* cmd_closest.c - `trigeo closest MESH QUERIES [--signed] [--sign M] [--threads N] [-o OUT]`:
 * closest points (and optionally signed distances) of query points (text or .npy), as CSV or as a
 * NumPy structured array. */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static const char* skip_blanks(const char* s)
{
    while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\v' || *s == '\f') ++s;
    return s;
}

/* Parses "x y z" lines; blank lines and lines starting with '#' are skipped, and a '#' after the
 * third number starts a comment. Returns the number of points (3 doubles each in *out), or
 * (size_t)-1 after printing "QUERIES:LINE: message". */
static size_t parse_queries(const char* name, char* text, double** out)
{
    size_t count = 0, cap = 1024;
    double* xyz = malloc(3 * cap * sizeof *xyz);
    unsigned long long line = 0;
    char* s = cli_skip_bom(text);
    while (xyz && *s) {
        char* end = strchr(s, '\n');
        if (end) *end = '\0';
        ++line;
        const char* p = skip_blanks(s);
        if (*p && *p != '#') {
            if (!cli_grow((void**)&xyz, &cap, count + 1, 3 * sizeof *xyz)) break;
            for (int k = 0; k < 3; ++k) {
                const char* after;
                double v = 0.0;
                cli_number_status ns = cli_scan_double(p, &v, &after);
                if (ns == CLI_NUMBER_SYNTAX ||
                    (*after && *after != ' ' && *after != '\t' && *after != '\r' && *after != '#')) {
                    cli_error(name, line, "expected three numbers \"x y z\", got \"%.40s\"", skip_blanks(s));
                    free(xyz);
                    return (size_t)-1;
                }
                if (ns == CLI_NUMBER_INFINITE) {
                    cli_error(name, line, "coordinate %d is not a finite number", k + 1);
                    free(xyz);
                    return (size_t)-1;
                }
                if (fabs(v) > 1e150) { /* the library's range: squared distances would overflow */
                    cli_error(name, line, "coordinate %d is %s, beyond the supported range of +-1e150", k + 1,
                              cli_num(v).s);
                    free(xyz);
                    return (size_t)-1;
                }
                xyz[3 * count + (size_t)k] = v;
                p = skip_blanks(after);
            }
            if (*p && *p != '#') {
                cli_error(name, line, "unexpected \"%.20s\" after the three coordinates", p);
                free(xyz);
                return (size_t)-1;
            }
            ++count;
        }
        if (!end) break;
        s = end + 1;
    }
    if (!xyz || (*s && count == cap)) {
        cli_error(name, 0, "out of memory");
        free(xyz);
        return (size_t)-1;
    }
    *out = xyz;
    return count;
}

/* Unsigned decimal at s; returns the length. */
static int format_uint(unsigned long long v, char* s)
{
    char r[24];
    int n = 0;
    do r[n++] = (char)('0' + v % 10), v /= 10;
    while (v);
    for (int i = 0; i < n; ++i) s[i] = r[n - 1 - i];
    return n;
}

/* CSV rows, numbers as the shortest decimals that read back to the same doubles (cli_format_double),
 * built in a buffer written in large blocks. Returns 0, 1 after Ctrl-C, -1 on a write error. */
static int write_csv(FILE* f, size_t n, const tg_closest_hit* hits, const tg_signed_hit* signed_hits)
{
    enum { BLOCK = 1 << 16, ROW_MAX = 20 + 11 + 7 * 26 + 4 };
    char* buf = malloc(BLOCK + ROW_MAX);
    if (!buf) return -1;
    size_t used = (size_t)sprintf(buf, "i,face,sqdist,cx,cy,cz,b0,b1,b2%s\n", signed_hits ? ",sign" : "");
    for (size_t i = 0; i < n; ++i) {
        const tg_closest_hit* h = signed_hits ? &signed_hits[i].hit : &hits[i];
        char* s = buf + used;
        s += format_uint(i, s);
        *s++ = ',';
        s += format_uint(h->face, s);
        const double v[7] = {h->sqdist, h->point[0], h->point[1], h->point[2], h->bary[0], h->bary[1], h->bary[2]};
        for (int k = 0; k < 7; ++k) {
            *s++ = ',';
            s += cli_format_double(v[k], s);
        }
        if (signed_hits) {
            int sign = signed_hits[i].sign;
            *s++ = ',';
            if (sign < 0) *s++ = '-';
            *s++ = sign ? '1' : '0';
        }
        *s++ = '\n';
        used = (size_t)(s - buf);
        if (used >= BLOCK) {
            if (fwrite(buf, 1, used, f) != used) break;
            used = 0;
            if (cli_interrupted()) { /* Ctrl-C: nothing is kept */
                free(buf);
                return 1;
            }
        }
    }
    if (used && fwrite(buf, 1, used, f) != used) used = 0;
    free(buf);
    return ferror(f) ? -1 : 0;
}

/* The same records as a NumPy structured array of shape (n,), fields named as the CSV columns
 * (the row number is the index): face uint32, sqdist, cx, cy, cz, b0, b1, b2 float64[, sign int8],
 * packed, little-endian. */
static int write_npy(FILE* f, size_t n, const tg_closest_hit* hits, const tg_signed_hit* signed_hits)
{
    const char* descr = signed_hits ? "[('face', '<u4'), ('sqdist', '<f8'), ('cx', '<f8'), ('cy', '<f8'), ('cz', '<f8'), "
                                      "('b0', '<f8'), ('b1', '<f8'), ('b2', '<f8'), ('sign', 'i1')]"
                                    : "[('face', '<u4'), ('sqdist', '<f8'), ('cx', '<f8'), ('cy', '<f8'), ('cz', '<f8'), "
                                      "('b0', '<f8'), ('b1', '<f8'), ('b2', '<f8')]";
    const unsigned long long rows = n;
    if (!cli_npy_write_header(f, descr, 1, &rows)) return -1;
    enum { REC_MAX = 4 + 7 * 8 + 1, PER_BLOCK = 4096 };
    const size_t rec = signed_hits ? REC_MAX : REC_MAX - 1;
    unsigned char* buf = malloc(PER_BLOCK * REC_MAX);
    if (!buf) return -1;
    for (size_t i0 = 0; i0 < n; i0 += PER_BLOCK) {
        size_t m = n - i0 < PER_BLOCK ? n - i0 : PER_BLOCK;
        for (size_t j = 0; j < m; ++j) {
            const tg_closest_hit* h = signed_hits ? &signed_hits[i0 + j].hit : &hits[i0 + j];
            unsigned char* r = buf + j * rec;
            for (int b = 0; b < 4; ++b) r[b] = (unsigned char)(h->face >> (8 * b));
            const double v[7] = {h->sqdist, h->point[0], h->point[1], h->point[2], h->bary[0], h->bary[1], h->bary[2]};
            for (int k = 0; k < 7; ++k) {
                uint64_t bits;
                memcpy(&bits, &v[k], sizeof bits);
                for (int b = 0; b < 8; ++b) r[4 + 8 * k + b] = (unsigned char)(bits >> (8 * b));
            }
            if (signed_hits) r[REC_MAX - 1] = (unsigned char)(signed char)signed_hits[i0 + j].sign;
        }
        if (fwrite(buf, rec, m, f) != m) break;
        if (cli_interrupted()) {
            free(buf);
            return 1;
        }
    }
    free(buf);
    return ferror(f) ? -1 : 0;
}

/* The queries in chunks with Ctrl-C looked at between them (polling mode): the batch calls have
 * no progress callback, and their answers are per point, so chunking changes none. A chunk
 * grows (4x at most) toward 0.1 s of work, from 16 points, as one point can cost milliseconds
 * (an exact winding number over a million faces); the library's threads share each chunk.
 * TG_ERR_CANCELLED after Ctrl-C. */
static tg_status query_chunks(const tg_bvh* bvh, const double* xyz, size_t n, bool want_sign, tg_sign_method method,
                              int threads, tg_closest_hit* hits, tg_signed_hit* shits)
{
    tg_status st = TG_OK;
    cli_interrupt_polling(true);
    for (size_t lo = 0, size = 16; st == TG_OK && lo < n;) {
        if (cli_interrupted()) {
            st = TG_ERR_CANCELLED;
            break;
        }
        size_t m = n - lo < size ? n - lo : size;
        double t0 = cli_seconds();
        st = want_sign ? tg_bvh_signed_distance_batch(bvh, xyz + 3 * lo, m, method, threads, shits + lo)
                       : tg_bvh_closest_batch(bvh, xyz + 3 * lo, m, INFINITY, threads, hits + lo);
        double dt = cli_seconds() - t0;
        size_t grown = dt > 0.0 ? (size_t)((double)size * (0.1 / dt)) : 4 * size;
        size = grown > 4 * size ? 4 * size : grown < 16 ? 16 : grown;
        lo += m;
    }
    cli_interrupt_polling(false);
    return st;
}

/* Why the library chose `used` (tg_bvh_sign_method decides; this only words it). */
static const char* method_reason(tg_sign_method requested, tg_sign_method used)
{
    if (requested != TG_SIGN_AUTO) return "as requested";
    return used == TG_SIGN_PSEUDONORMAL
               ? "auto: a closed, consistently oriented manifold without degenerate faces"
               : "auto: not a closed, consistently oriented manifold without degenerate faces (see trigeo info)";
}

static int run(int argc, char** argv)
{
    const char *mesh_path = NULL, *query_path = NULL, *out_path = NULL;
    bool want_sign = false;
    tg_sign_method method = TG_SIGN_AUTO;
    unsigned long long threads = 0;
    for (int i = 1; i < argc; ++i) {
        const char* a = argv[i];
        if (!strcmp(a, "--signed")) {
            want_sign = true;
        } else if (!strcmp(a, "--sign")) {
            if (++i >= argc) return cli_usage("closest", "--sign needs pseudonormal or winding");
            if (!strcmp(argv[i], "pseudonormal"))
                method = TG_SIGN_PSEUDONORMAL;
            else if (!strcmp(argv[i], "winding"))
                method = TG_SIGN_WINDING;
            else
                return cli_usage("closest", "--sign must be pseudonormal or winding, not '%s'", argv[i]);
            want_sign = true;
        } else if (!strcmp(a, "--threads")) {
            if (++i >= argc || !cli_parse_uint(argv[i], &threads) || threads > TG_MAX_THREADS)
                return cli_usage("closest", "--threads needs a count in 0..%d (0 = all cores), not '%s'", TG_MAX_THREADS,
                                 i < argc ? argv[i] : "");
        } else if (!strcmp(a, "-o")) {
            if (++i >= argc) return cli_usage("closest", "-o needs a file name");
            out_path = argv[i];
        } else if (a[0] == '-' && a[1]) {
            return cli_usage("closest", "unknown option '%s'", a);
        } else if (!mesh_path) {
            mesh_path = a;
        } else if (!query_path) {
            query_path = a;
        } else {
            return cli_usage("closest", "unexpected argument '%s'", a);
        }
    }
    if (!mesh_path || !query_path) return cli_usage("closest", "missing %s", mesh_path ? "QUERIES" : "MESH");

    const cli_file_role inputs[2] = {{mesh_path, "mesh"}, {query_path, "queries file"}};
    const cli_file_role outputs[1] = {{out_path, "-o"}};
    int rc = cli_check_outputs(outputs, 1, inputs, 2);
    if (rc != CLI_OK) return rc;
    if (out_path && strcmp(out_path, "-") && !cli_ext_is(out_path, ".csv") && !cli_ext_is(out_path, ".npy"))
        return cli_usage("closest", "-o %s: the extension must be .csv or .npy ('-': CSV on stdout)", out_path);
    if (!cli_threads_available((int)threads, "closest")) return CLI_INPUT;
    size_t size = 0;
    char* text = cli_read_all(query_path, &size);
    if (!text) return CLI_INPUT;
    double* xyz = NULL;
    size_t n = cli_is_npy(text, size) ? cli_read_npy_points(query_path, text, size, &xyz) : parse_queries(query_path, text, &xyz);
    free(text);
    if (n == (size_t)-1) return CLI_INPUT;

    rc = CLI_INPUT;
    tg_mesh* mesh = cli_load_mesh_for_distances(mesh_path);
    tg_bvh* bvh = NULL;
    tg_closest_hit* hits = NULL;
    tg_signed_hit* shits = NULL;
    if (!mesh) goto done;
    if (tg_mesh_face_count(mesh) == 0) {
        cli_error(mesh_path, 0, "the mesh has no faces");
        goto done;
    }
    tg_bvh_options o = {0};
    o.winding_data = !want_sign ? TG_BVH_WINDING_NEVER : method == TG_SIGN_WINDING ? TG_BVH_WINDING_ALWAYS : TG_BVH_WINDING_AUTO;
    o.threads = (int)threads; /* the build too, not only the queries */
    tg_status st = tg_bvh_create(mesh, &o, &bvh);
    if (st == TG_OK && want_sign) {
        tg_sign_method used = tg_bvh_sign_method(bvh, method);
        fprintf(stderr, "trigeo: closest: sign from %s (%s)\n",
                used == TG_SIGN_PSEUDONORMAL ? "angle-weighted pseudonormals" : "the generalized winding number",
                method_reason(method, used));
        shits = malloc((n ? n : 1) * sizeof *shits);
        st = shits ? query_chunks(bvh, xyz, n, true, method, (int)threads, NULL, shits) : TG_ERR_OUT_OF_MEMORY;
    } else if (st == TG_OK) {
        hits = malloc((n ? n : 1) * sizeof *hits);
        st = hits ? query_chunks(bvh, xyz, n, false, method, (int)threads, hits, NULL) : TG_ERR_OUT_OF_MEMORY;
    }
    if (st == TG_ERR_CANCELLED) {
        cli_error(mesh_path, 0, "interrupted: nothing written");
        rc = 130;
        goto done;
    }
    if (st != TG_OK) {
        cli_error(mesh_path, 0, "%s", tg_status_string(st));
        goto done;
    }
    /* to a temporary name renamed when complete: an error or Ctrl-C leaves no partial file */
    cli_output out;
    FILE* f = cli_output_open(&out, out_path ? out_path : "-");
    if (!f) goto done;
    (void)cli_format_double(0.0, (char[32]){0}); /* its tables, before any thread could ask */
    int werr = out_path && cli_ext_is(out_path, ".npy") ? write_npy(f, n, hits, shits) : write_csv(f, n, hits, shits);
    if (werr) {
        if (werr > 0) {
            cli_error(out_path ? out_path : "-", 0, "interrupted: nothing written");
            rc = 130;
        } else {
            cli_error(out_path ? out_path : "-", 0, "write error: %s", strerror(errno));
        }
        cli_output_abort(&out);
        goto done;
    }
    rc = cli_output_commit(&out);
done:
    free(shits);
    free(hits);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(mesh);
    free(xyz);
    return rc;
}

const cli_command cli_cmd_closest = {
    "closest", "closest MESH QUERIES [--signed] [--sign pseudonormal|winding] [--threads N] [-o OUT.csv|OUT.npy]",
    "For each query point, the closest point of MESH: face (0-based, file order), squared distance,\n"
    "closest point and its barycentric coordinates on that face. Ties go to the lowest face index;\n"
    "the answers equal a linear scan over all faces.\n\n"
    "  QUERIES     text, one \"x y z\" per line ('-' = stdin); blank lines and '#' comments allowed;\n"
    "              or a NumPy .npy file (recognized by its content) holding a (k, 3) array of\n"
    "              float64 or float32 (converted exactly), either byte order, C or Fortran\n"
    "              order, e.g. numpy.save(\"q.npy\", points)\n"
    "  --signed    add a sign column: -1 inside, +1 outside, 0 on the surface. Angle-weighted\n"
    "              pseudonormals for closed, consistently oriented manifolds, else the generalized\n"
    "              winding number (>= 1/2 is inside); the choice is reported on stderr\n"
    "  --sign M    force the method: pseudonormal or winding (implies --signed)\n"
    "  --threads N worker threads, at most 256 (default 0 = all cores)\n"
    "  -o OUT      write there instead of stdout: OUT.csv, or OUT.npy, a NumPy structured\n"
    "              array of shape (k,) with the CSV's columns as fields: face (uint32), sqdist, cx,\n"
    "              cy, cz, b0, b1, b2 (float64)[, sign (int8)] - numpy.load(OUT)[\"sqdist\"]\n\n"
    "Output: CSV with header i,face,sqdist,cx,cy,cz,b0,b1,b2[,sign]; each number is the shortest\n"
    "decimal that reads back to exactly the computed double.\n"
    "A malformed or non-finite query line is reported as QUERIES:LINE, a malformed .npy file with\n"
    "the reason (dtype, shape, truncation, a coordinate), and nothing is written.\n",
    run,
};
