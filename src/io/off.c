/* off.c - placeholder until the off reader lands (same session). */
#include "io/io_internal.h"

tg_status tg__read_off(const char* data, size_t size, const char* name, const tg_allocator* a,
                       tg_diag* diag, tg__soup* out)
{
    (void)data; (void)size; (void)a; (void)out;
    tg__diag_set(diag, name, 0, 0, 0, "reader not built yet");
    return TG_ERR_UNSUPPORTED;
}
