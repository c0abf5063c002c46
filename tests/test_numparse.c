/* test_numparse.c - the readers' number parser (src/io/numparse.h) is bit-identical to strtod on
 * random doubles printed with %.17g, short %g, %e forms, plus hand-picked edge cases (halfway
 * cases, subnormals, huge exponents, 19+ digit mantissas, junk). */
#include "tg_test.h"

#include "io/numparse.h"

static void check_one(const char* text)
{
    double a = 0.0;
    char* endb;
    const char* enda = tg__parse_double(text, &a);
    double b = strtod(text, &endb);
    if (endb == text) {
        CHECK_MSG(enda == NULL, "'%s' should not parse", text);
        return;
    }
    CHECK_MSG(enda == endb, "'%s': end offset %td vs strtod %td", text, enda ? enda - text : -1, endb - text);
    CHECK_MSG(memcmp(&a, &b, sizeof a) == 0, "'%s': %.17g vs strtod %.17g", text, a, b);
}

int main(void)
{
    const char* fixed[] = {"0", "-0", "+1", "1.", ".5", "-.5e-3", "1e22", "1e23", "9007199254740993",
                           "9007199254740992.5", "0.1", "0.30000000000000004", "2.2250738585072011e-308",
                           "4.9e-324", "1.7976931348623157e308", "1e309", "123456789012345678901234",
                           "0.000000000000000000000000000001", "1e-27", "1e27", "1e28", "7.0e-10",
                           "89255.0e-22", "1.00000000000000011102230246251565404236316680908203125",
                           "0.1000000000000000055511151231257827021181583404541015625", "inf", "-nan",
                           "abc", "-", ".", "e5", "1e", "1e+", "0x1p3", "  7", "12abc", "00000000000000000000001.5"};
    for (size_t i = 0; i < sizeof fixed / sizeof fixed[0]; ++i) check_one(fixed[i]);
    tg_rng r = {0x9E3779B97F4A7C15ull};
    char buf[64];
    int before = tg_test_failed_;
    for (long i = 0; i < 2000000 && tg_test_failed_ - before < 10; ++i) {
        uint64_t bits = tg_rng_next(&r);
        double d;
        memcpy(&d, &bits, sizeof d);
        switch (i % 4) {
        case 0:
            if (!isfinite(d)) continue;
            snprintf(buf, sizeof buf, "%.17g", d);
            break;
        case 1: snprintf(buf, sizeof buf, "%.17g", tg_rng_range(&r, -1000, 1000)); break;
        case 2: snprintf(buf, sizeof buf, "%.*g", (int)(bits % 19) + 1, tg_rng_range(&r, -1, 1)); break;
        default: snprintf(buf, sizeof buf, "%.*e", (int)(bits % 19), tg_rng_range(&r, 0, 1e6)); break;
        }
        double a = 0.0, b = strtod(buf, NULL);
        const char* e = tg__parse_double(buf, &a);
        if (e && memcmp(&a, &b, sizeof a) == 0)
            tg_test_passed_++;
        else
            TG_FAIL_("'%s': %.17g vs strtod %.17g", buf, a, b);
    }
    return tg_test_finish();
}
