/* test_cli_number.c - the CLI's shortest round-trip printer (tools/cli_number.c): every output reads
 * back (strtod) to the same double, on millions of random bit patterns, all powers of two and
 * their neighbours, subnormals, powers of ten and their neighbours, the extremes and short
 * decimals; it is never longer than the shortest "%.*e" that reads back, and when that one has as
 * many digits, it has the same digits (the nearest). Notation: fixed for decimal exponents -4 to
 * 15, else d.ddd e+-XX, as Python's repr.
 *
 * COUNT random patterns (4 million in the full suite, 400 thousand under AddressSanitizer; 1 million
 * and 100 thousand in the fast one; TG_NUMBER_COUNT overrides); the shortest-digits check, which
 * calls snprintf up to 17 times, runs on every 16th. */
#include "tg_test.h"

#include <float.h>

int cli_format_double(double x, char* out);

#define COUNT TG_TEST_DEPTH(TG_TEST_WORK(4000000, 400000), TG_TEST_WORK(1000000, 100000))

static long checked, failures;

/* The significant digits of a decimal string (no sign, point, exponent or trailing zeros). */
static int digits_of(const char* s, char* out)
{
    int n = 0;
    bool seen = false;
    for (; *s && *s != 'e'; ++s)
        if (*s >= '0' && *s <= '9') {
            seen = seen || *s != '0';
            if (seen) out[n++] = *s;
        }
    while (n > 1 && out[n - 1] == '0') --n;
    if (!n) out[n++] = '0';
    out[n] = '\0';
    return n;
}

static void check(double x, bool shortest)
{
    char s[64];
    int len = cli_format_double(x, s);
    double y = strtod(s, NULL);
    ++checked;
    if (len != (int)strlen(s) || len > 24 || memcmp(&x, &y, sizeof x)) {
        if (failures++ < 10) TG_FAIL_("%a (%.17g) printed as \"%s\" (length %d) reads back as %a", x, x, s, len, y);
        return;
    }
    if (!shortest || x == 0.0) return;
    char mine[32], theirs[32];
    int n = digits_of(s, mine);
    for (int p = 1; p <= 17; ++p) {
        char c[64];
        snprintf(c, sizeof c, "%.*e", p - 1, x);
        if (strtod(c, NULL) != x) continue;
        int m = digits_of(c, theirs);
        if (n > m || (n == m && strcmp(mine, theirs)))
            if (failures++ < 10) TG_FAIL_("%a: \"%s\" but \"%s\" reads back too", x, s, c);
        break;
    }
}

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static uint64_t next(void)
{
    rng_state ^= rng_state << 13, rng_state ^= rng_state >> 7, rng_state ^= rng_state << 17;
    return rng_state;
}
static double from_bits(uint64_t u)
{
    double x;
    memcpy(&x, &u, sizeof x);
    return x;
}

static void expect(double x, const char* want)
{
    char s[64];
    cli_format_double(x, s);
    CHECK_MSG(!strcmp(s, want), "%.17g printed as \"%s\", expected \"%s\"", x, s, want);
}

int main(void)
{
    long count = COUNT;
    const char* env = getenv("TG_NUMBER_COUNT");
    if (env && atol(env) > 0) count = atol(env);
    /* notation and known shortest forms */
    expect(0.0, "0"), expect(-0.0, "-0"), expect(1.0, "1"), expect(-2.5, "-2.5"), expect(0.1, "0.1");
    expect(0.3, "0.3"), expect(1.0 / 3.0, "0.3333333333333333"), expect(2.0 / 3.0, "0.6666666666666666");
    expect(0.0001, "0.0001"), expect(0.00001, "1e-05"), expect(1.5e-4, "0.00015"), expect(3.9e-5, "3.9e-05");
    expect(1e15, "1000000000000000"), expect(1e16, "1e+16"), expect(123456789012345.6, "123456789012345.6");
    expect(1e23, "1e+23"), expect(5e-324, "5e-324"), expect(DBL_MAX, "1.7976931348623157e+308");
    expect(DBL_MIN, "2.2250738585072014e-308"), expect(9007199254740993.0, "9007199254740992");
    expect(1e100, "1e+100"), expect(-1.25e-200, "-1.25e-200");
    /* every power of two and its neighbours (the interval is asymmetric below them) */
    for (int e = -1074; e <= 1023; ++e) {
        double x = ldexp(1.0, e);
        check(x, true), check(nextafter(x, 0.0), true), check(nextafter(x, INFINITY), true), check(-x, false);
    }
    /* powers of ten and their neighbours */
    for (int k = -323; k <= 308; ++k) {
        char t[16];
        snprintf(t, sizeof t, "1e%d", k);
        double x = strtod(t, NULL);
        check(x, true), check(nextafter(x, 0.0), true), check(nextafter(x, INFINITY), true);
    }
    /* the smallest subnormals, the largest ones, the largest normals */
    for (uint64_t m = 1; m < 20000; ++m) check(from_bits(m), m % 16 == 0);
    for (uint64_t m = 1; m < 20000; ++m) check(from_bits(0x0010000000000000ull - m), m % 16 == 0);
    for (uint64_t m = 1; m < 20000; ++m) check(from_bits(0x7FF0000000000000ull - m), m % 16 == 0);
    /* random bit patterns (finite), random subnormals, short decimals, [0, 1) */
    for (long i = 0; i < count; ++i) {
        double x = from_bits(next());
        if (isfinite(x)) check(x, i % 16 == 0);
    }
    for (long i = 0; i < count / 8; ++i) check(from_bits(next() & 0x000FFFFFFFFFFFFFull), i % 16 == 0);
    for (long i = 0; i < count / 8; ++i) {
        check((double)(next() % 100000000) / 1e4, i % 16 == 0);
        check((double)(next() >> 11) * 0x1p-53, i % 16 == 0);
    }
    CHECK_MSG(failures == 0, "%ld of %ld numbers failed", failures, checked);
    printf("%ld numbers checked\n", checked);
    return tg_test_finish();
}
