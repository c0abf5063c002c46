/* cmd_info.c - `trigeo info MESH [--json]`: the mesh validation report. */
#include "cli.h"

#include <string.h>

static void print_json(FILE* f, const char* path, const tg_mesh_report* r)
{
    fprintf(f, "{\n  \"file\": ");
    cli_json_string(f, path);
    fprintf(f, ",\n");
    fprintf(f, "  \"vertices\": %llu,\n", (unsigned long long)r->vertices);
    fprintf(f, "  \"faces\": %llu,\n", (unsigned long long)r->faces);
    fprintf(f, "  \"edges\": %llu,\n", (unsigned long long)r->edges);
    fprintf(f, "  \"components\": %llu,\n", (unsigned long long)r->components);
    fprintf(f, "  \"boundary_edges\": %llu,\n", (unsigned long long)r->boundary_edges);
    fprintf(f, "  \"boundary_loops\": %llu,\n", (unsigned long long)r->boundary_loops);
    fprintf(f, "  \"nonmanifold_edges\": %llu,\n", (unsigned long long)r->nonmanifold_edges);
    fprintf(f, "  \"nonmanifold_vertices\": %llu,\n", (unsigned long long)r->nonmanifold_vertices);
    fprintf(f, "  \"misoriented_edges\": %llu,\n", (unsigned long long)r->misoriented_edges);
    fprintf(f, "  \"degenerate_faces\": %llu,\n", (unsigned long long)r->degenerate_faces);
    fprintf(f, "  \"duplicate_faces\": %llu,\n", (unsigned long long)r->duplicate_faces);
    fprintf(f, "  \"unreferenced_vertices\": %llu,\n", (unsigned long long)r->unreferenced_vertices);
    fprintf(f, "  \"euler_characteristic\": %lld,\n", (long long)r->euler_characteristic);
    fprintf(f, "  \"closed_manifold\": %s,\n", r->closed_manifold ? "true" : "false");
    if (r->genus >= 0)
        fprintf(f, "  \"genus\": %lld,\n", (long long)r->genus);
    else
        fprintf(f, "  \"genus\": null,\n");
    fprintf(f, "  \"bbox_min\": [%s, %s, %s],\n", cli_num(r->bbox_min[0]).s, cli_num(r->bbox_min[1]).s,
            cli_num(r->bbox_min[2]).s);
    fprintf(f, "  \"bbox_max\": [%s, %s, %s]\n}\n", cli_num(r->bbox_max[0]).s, cli_num(r->bbox_max[1]).s,
            cli_num(r->bbox_max[2]).s);
}

static void print_text(FILE* f, const char* path, const tg_mesh_report* r, size_t bytes)
{
    fprintf(f, "%s\n", path);
    fprintf(f, "  vertices               %llu\n", (unsigned long long)r->vertices);
    fprintf(f, "  faces                  %llu\n", (unsigned long long)r->faces);
    fprintf(f, "  edges                  %llu\n", (unsigned long long)r->edges);
    fprintf(f, "  components             %llu\n", (unsigned long long)r->components);
    fprintf(f, "  boundary edges         %llu in %llu loop(s)\n", (unsigned long long)r->boundary_edges,
           (unsigned long long)r->boundary_loops);
    fprintf(f, "  non-manifold edges     %llu\n", (unsigned long long)r->nonmanifold_edges);
    fprintf(f, "  non-manifold vertices  %llu\n", (unsigned long long)r->nonmanifold_vertices);
    fprintf(f, "  misoriented edges      %llu\n", (unsigned long long)r->misoriented_edges);
    fprintf(f, "  degenerate faces       %llu\n", (unsigned long long)r->degenerate_faces);
    fprintf(f, "  duplicate faces        %llu\n", (unsigned long long)r->duplicate_faces);
    fprintf(f, "  unreferenced vertices  %llu\n", (unsigned long long)r->unreferenced_vertices);
    fprintf(f, "  Euler characteristic   %lld\n", (long long)r->euler_characteristic);
    if (r->genus >= 0)
        fprintf(f, "  genus                  %lld (closed manifold)\n", (long long)r->genus);
    else
        fprintf(f, "  genus                  n/a (%s)\n", r->closed_manifold ? "non-orientable" : "not a closed manifold");
    fprintf(f, "  bounding box           [%s, %s, %s] - [%s, %s, %s]\n", cli_num(r->bbox_min[0]).s,
            cli_num(r->bbox_min[1]).s, cli_num(r->bbox_min[2]).s, cli_num(r->bbox_max[0]).s, cli_num(r->bbox_max[1]).s,
            cli_num(r->bbox_max[2]).s);
    fprintf(f, "  memory                 %.1f MiB (%.1f bytes/face)\n", bytes / 1048576.0,
           r->faces ? (double)bytes / (double)r->faces : 0.0);
}

static int run(int argc, char** argv)
{
    const char *path = NULL, *out_path = NULL;
    bool json = false;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--json"))
            json = true;
        else if (!strcmp(argv[i], "-o")) {
            if (++i >= argc) return cli_usage("info", "-o needs a file name");
            out_path = argv[i];
        }
        else if (argv[i][0] == '-' && argv[i][1])
            return cli_usage("info", "unknown option '%s'", argv[i]);
        else if (!path)
            path = argv[i];
        else
            return cli_usage("info", "unexpected argument '%s'", argv[i]);
    }
    if (!path) return cli_usage("info", "missing MESH");
    const cli_file_role inputs[1] = {{path, "mesh"}}, outputs[1] = {{out_path, "-o"}};
    int check = cli_check_outputs(outputs, 1, inputs, 1);
    if (check != CLI_OK) return check;
    if (out_path && strcmp(out_path, "-") && !cli_ext_is(out_path, ".txt") && !cli_ext_is(out_path, ".json"))
        return cli_usage("info", "-o %s: the extension must be .txt or .json ('-': stdout)", out_path);
    tg_mesh* mesh = cli_load_mesh(path);
    if (!mesh) return CLI_INPUT;
    const tg_mesh_report* r = tg_mesh_get_report(mesh);
    if (out_path && cli_ext_is(out_path, ".json")) json = true; /* the extension picks the format */
    cli_output out;
    FILE* f = cli_output_open(&out, out_path ? out_path : "-");
    int rc = CLI_INPUT;
    if (f) {
        if (json)
            print_json(f, path, r);
        else
            print_text(f, path, r, tg_mesh_memory_bytes(mesh));
        rc = cli_output_commit(&out);
    }
    tg_mesh_destroy(mesh);
    return rc;
}

const cli_command cli_cmd_info = {
    "info", "info MESH [--json] [-o OUT.json|OUT.txt]",
    "Loads MESH and prints its validation report: counts of vertices, faces, edges, components,\n"
    "boundary edges and loops, non-manifold edges and (pinched) vertices, inconsistently oriented\n"
    "edges, degenerate (zero-area) and duplicate faces, unreferenced vertices, the Euler\n"
    "characteristic, the genus when the mesh is a closed manifold, and the bounding box.\n\n"
    "  --json   machine-readable output; genus is null when not a closed manifold\n"
    "  -o OUT   write the report to OUT.txt (OUT.json: the JSON form; other extensions are\n"
    "           refused), complete or not at all\n",
    run,
};
