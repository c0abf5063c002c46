// header_cxx.cpp - include/trigeo.h must compile and link as C++ (extern "C", no C-only syntax).
#include <trigeo.h>

#include <cstdio>
#include <cstring>

int main()
{
    const char* v = tg_version();
    if (std::strlen(v) < 5) {
        std::printf("FAIL tg_version() = '%s'\n", v);
        std::printf("0 passed, 1 failed\n");
        return 1;
    }
    if (std::strcmp(tg_status_name(TG_OK), "ok") != 0) {
        std::printf("FAIL tg_status_name(TG_OK) = '%s'\n", tg_status_name(TG_OK));
        std::printf("0 passed, 1 failed\n");
        return 1;
    }
    std::printf("2 passed, 0 failed\n");
    return 0;
}
