/* test_io_bom.c - text meshes that start with a UTF-8 byte-order mark (written by Windows tools)
 * load exactly like the same text without it (OBJ, OFF, ascii PLY, ascii STL; plain and through
 * a file), a binary STL whose header happens to start with the mark keeps its header whole, and a
 * directory given as a mesh is named as one. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>

#include "tg_test.h"

static tg_mesh* load_mem(const char* text, size_t n, const char* name)
{
    tg_mesh* m = NULL;
    tg_diag d;
    tg_status st = tg_mesh_load_memory(text, n, name, TG_FORMAT_AUTO, NULL, &d, &m);
    CHECK_MSG(st == TG_OK, "%s: %s", name, st == TG_OK ? "" : d.message);
    return m;
}

static void same_mesh(const char* what, const tg_mesh* a, const tg_mesh* b)
{
    if (!a || !b) return;
    CHECK_MSG(tg_mesh_vertex_count(a) == tg_mesh_vertex_count(b) && tg_mesh_face_count(a) == tg_mesh_face_count(b),
              "%s: %zu/%zu vertices, %zu/%zu faces", what, tg_mesh_vertex_count(a), tg_mesh_vertex_count(b),
              tg_mesh_face_count(a), tg_mesh_face_count(b));
    if (tg_mesh_vertex_count(a) != tg_mesh_vertex_count(b) || tg_mesh_face_count(a) != tg_mesh_face_count(b)) return;
    CHECK_MSG(!memcmp(tg_mesh_positions(a), tg_mesh_positions(b), 3 * tg_mesh_vertex_count(a) * sizeof(double)) &&
                  !memcmp(tg_mesh_triangles(a), tg_mesh_triangles(b), 3 * tg_mesh_face_count(a) * sizeof(uint32_t)),
              "%s: different positions or triangles", what);
}

static void check_text(const char* name, const char* text)
{
    size_t n = strlen(text);
    char* bom = malloc(n + 3);
    memcpy(bom, "\xEF\xBB\xBF", 3);
    memcpy(bom + 3, text, n);
    tg_mesh* plain = load_mem(text, n, name);
    tg_mesh* with = load_mem(bom, n + 3, name);
    same_mesh(name, plain, with);
    /* without the extension: detected from the content after the mark */
    tg_mesh* anon = load_mem(bom, n + 3, "");
    same_mesh(name, plain, anon);
    /* through a file */
    char path[64];
    snprintf(path, sizeof path, "/tmp/tg_bom_%d_%s", (int)n, name);
    FILE* f = fopen(path, "wb");
    fwrite(bom, 1, n + 3, f);
    fclose(f);
    tg_mesh* file = NULL;
    tg_diag d;
    CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &file), TG_OK);
    same_mesh(name, plain, file);
    remove(path);
    tg_mesh_destroy(plain), tg_mesh_destroy(with), tg_mesh_destroy(anon), tg_mesh_destroy(file);
    free(bom);
}

int main(void)
{
    /* the example: 5 vertices, the first one at the origin */
    check_text("bom.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 9 9 9\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
    check_text("bom.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n");
    check_text("bom.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                          "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    check_text("bom.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                          "endloop\nendfacet\nendsolid t\n");
    /* the example's first vertex is the origin and index 1 is vertex 0: nothing shifted */
    const char* obj = "\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 9 9 9\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    tg_mesh* m = load_mem(obj, strlen(obj), "x.obj");
    if (m) {
        CHECK_EQ_INT(tg_mesh_vertex_count(m), 5);
        CHECK(tg_mesh_positions(m)[0] == 0 && tg_mesh_positions(m)[3] == 1 && tg_mesh_triangles(m)[1] == 2);
        tg_mesh_destroy(m);
    }
    /* a binary STL whose 80-byte header starts with the mark: read as binary, header untouched */
    unsigned char stl[84 + 50];
    memset(stl, 0, sizeof stl);
    memcpy(stl, "\xEF\xBB\xBF binary header", 17);
    stl[80] = 1;
    float tri[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    memcpy(stl + 84, tri, sizeof tri);
    m = load_mem((const char*)stl, sizeof stl, "b.stl");
    if (m) {
        CHECK_EQ_INT(tg_mesh_face_count(m), 1);
        CHECK(tg_mesh_positions(m)[3] == 1.0);
        tg_mesh_destroy(m);
    }
    /* coordinates beyond +-1e150: no distances computed there, never wrong ones;
     * the query point bound likewise */
    {
        double big[9] = {0, 0, 0, 1e300, 0, 0, 0, 1, 0}, small[9] = {0, 0, 0, 1e-300, 0, 0, 0, 1e-300, 0};
        double fine[9] = {0, 0, 0, 1e140, 0, 0, 0, 1e140, 0};
        uint32_t t3[3] = {0, 1, 2};
        tg_mesh* mm = NULL;
        tg_diag dd;
        /* such a mesh loads (any finite coordinate round-trips), but no distance structure takes it */
        CHECK_STATUS(tg_mesh_create(big, 3, t3, 1, NULL, &dd, &mm), TG_OK);
        tg_bvh* bb = NULL;
        tg_geodesic* gg = NULL;
        CHECK_STATUS(tg_bvh_create(mm, NULL, &bb), TG_ERR_UNSUPPORTED);
        CHECK_STATUS(tg_geodesic_create(mm, NULL, &gg), TG_ERR_UNSUPPORTED);
        tg_mesh_destroy(mm);
        mm = NULL;
        CHECK_STATUS(tg_mesh_create(small, 3, t3, 1, NULL, &dd, &mm), TG_OK); /* tiny is fine */
        tg_mesh_destroy(mm);
        mm = NULL;
        CHECK_STATUS(tg_mesh_create(fine, 3, t3, 1, NULL, &dd, &mm), TG_OK);
        tg_bvh* bvh = NULL;
        tg_bvh_workspace* bw = NULL;
        CHECK_STATUS(tg_bvh_create(mm, NULL, &bvh), TG_OK);
        CHECK_STATUS(tg_bvh_workspace_create(bvh, &bw), TG_OK);
        tg_closest_hit h;
        double far[3] = {0, 0, 1e200}, near[3] = {0, 0, 1e149};
        CHECK_STATUS(tg_bvh_closest(bvh, bw, far, INFINITY, &h), TG_ERR_INVALID_ARGUMENT);
        CHECK_STATUS(tg_bvh_closest(bvh, bw, near, INFINITY, &h), TG_OK);
        CHECK(isfinite(h.sqdist) && h.sqdist > 1e297);
        tg_bvh_workspace_destroy(bw);
        tg_bvh_destroy(bvh);
        tg_mesh_destroy(mm);
    }
    /* a directory */
    tg_mesh* dir = NULL;
    tg_diag d;
    CHECK_STATUS(tg_mesh_load("/tmp", TG_FORMAT_AUTO, NULL, &d, &dir), TG_ERR_IO);
    CHECK_MSG(strstr(d.message, "directory") != NULL, "directory: %s", d.message);
    return tg_test_finish();
}
