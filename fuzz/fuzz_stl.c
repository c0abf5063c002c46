/* fuzz_stl.c - libFuzzer target: arbitrary bytes through the STL reader (forced format), then the
 * mesh build. Invariants: no crash or sanitizer report; a failure returns NULL and a diagnostic
 * with a message and a position; a success returns a mesh. */
#include <trigeo.h>

#include <stdint.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    tg_mesh* mesh = NULL;
    tg_diag diag;
    tg_status st = tg_mesh_load_memory(data, size, "fuzz.stl", TG_FORMAT_STL, NULL, &diag, &mesh);
    if (st == TG_OK && !mesh) abort();
    if (st != TG_OK && (mesh || diag.message[0] == '\0' || (diag.line == 0 && diag.byte_offset == 0 && size))) abort();
    tg_mesh_destroy(mesh);
    return 0;
}
