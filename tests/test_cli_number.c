/* test_cli_number.c - the CLI's numbers (tools/cli_number.c). Reading (the rule of README.md
 * "Numbers"): cli_parse_double is strtod's correctly rounded double on decimal text, subnormals
 * included (strtod's ERANGE on an underflow is no error), 0 below them, refused beyond the largest
 * double, refused for text that is no decimal (hexadecimal, inf, nan, junk); the range-checked
 * forms (>= 0, "X,Y,Z", integers) on their edges.
 * Writing: the shortest round-trip printer: every output reads
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

#include "cli.h"

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

/* ---- reading ---- */

static bool same_bits(double a, double b) { return !memcmp(&a, &b, sizeof a); }

/* text reads as `want` (bit for bit) */
static void expect_read(const char* text, double want)
{
    double got = -12345.0;
    bool ok = cli_parse_double(text, &got);
    CHECK_MSG(ok && same_bits(got, want), "'%s' read as %s %a, expected %a", text, ok ? "" : "(refused)", got, want);
}

static void expect_refused(const char* text)
{
    double got = -12345.0;
    bool ok = cli_parse_double(text, &got);
    CHECK_MSG(!ok && got == -12345.0, "'%s' should be refused, read as %a", text, got);
}

/* every decimal text strtod reads whole: the same double, or refused exactly when not finite */
static void expect_strtod(const char* text)
{
    char* end;
    double want = strtod(text, &end);
    CHECK_MSG(*end == '\0', "strtod stops in '%s'", text);
    double got = -12345.0;
    bool ok = cli_parse_double(text, &got);
    if (isfinite(want))
        CHECK_MSG(ok && same_bits(got, want), "'%s': %a (%s), strtod %a", text, got, ok ? "read" : "refused", want);
    else
        CHECK_MSG(!ok, "'%s' overflows (strtod %a) but was read as %a", text, want, got);
}

static void test_reading(long count)
{
    /* the smallest subnormal, written as the issue wrote it and as Python repr writes it */
    expect_read("4.9e-324", 0x1p-1074), expect_read("5e-324", 0x1p-1074), expect_read("-5e-324", -0x1p-1074);
    expect_read("1e-320", strtod("1e-320", NULL)), expect_read("2.2250738585072009e-308", 0x0.fffffffffffffp-1022);
    /* half the smallest subnormal, 2^-1075 = 2.4703282292062327208...e-324: above it rounds up,
     * below it (and exactly at it, to even) to 0 */
    expect_read("2.4703282292062328e-324", 0x1p-1074), expect_read("2.4703282292062327e-324", 0.0);
    expect_read("1e-400", 0.0), expect_read("-1e-400", -0.0), expect_read("0e999999", 0.0);
    /* the largest double, and text that still rounds to it; beyond the halfway point: infinite */
    expect_read("1.7976931348623157e308", DBL_MAX), expect_read("1.7976931348623158e308", DBL_MAX);
    expect_read("179769313486231580793728971405303415079934132710037826936173778980444968292764750946649017977587207096330286416692887910946555547851940402630657488671505820681908902000708383676273854845817711531764475730270069855571366959622842914819860834936475292719074168444365510704342711559699508093042880177904174497791.9999", DBL_MAX);
    expect_refused("1.797693134862315808e308"), expect_refused("1e309"), expect_refused("-1e999");
    /* decimal forms, blanks around */
    expect_read("0", 0.0), expect_read("-0", -0.0), expect_read("+1.5", 1.5), expect_read("1.", 1.0);
    expect_read(".5", 0.5), expect_read("-.5e-3", -0.0005), expect_read("1E2", 100.0), expect_read(" 7 ", 7.0);
    expect_read("\t0.1\n", 0.1), expect_read("0.30000000000000004", 0.30000000000000004);
    expect_read("9007199254740993", 9007199254740992.0), expect_read("00000000000000000000001.5", 1.5);
    /* not decimal text, or not only one number */
    static const char* const bad[] = {"", " ", "+", "-", ".", "e5", "1e", "1e+", "1.5x", "--1", "+-1", "1,2", "1 2",
                                      "0x1p3", "0x10", "inf", "-inf", "infinity", "nan", "NAN", "1_000", "1e5.5",
                                      "1d5", "١"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) expect_refused(bad[i]);
    /* agreement with strtod on random decimals: %.17g of random bit patterns (subnormals among
     * them), short %.*e forms, and decimal exponents over the whole range and beyond */
    uint64_t st = 0x2545F4914F6CDD1Dull;
    char t[64];
    for (long i = 0; i < count / 16; ++i) {
        st ^= st << 13, st ^= st >> 7, st ^= st << 17;
        double x = from_bits(i % 3 == 0 ? st & 0x000FFFFFFFFFFFFFull : st);
        if (!isfinite(x)) continue;
        if (i % 2)
            snprintf(t, sizeof t, "%.17g", x);
        else
            snprintf(t, sizeof t, "%.*e", (int)(st >> 59), x);
        expect_strtod(t);
        snprintf(t, sizeof t, "%u.%03ue%d", (unsigned)(st >> 40 & 0xFFFF) % 10, (unsigned)(st >> 20 & 0xFFFF) % 1000,
                 (int)(st % 1400) - 700);
        expect_strtod(t);
    }
    /* >= 0: -0 and negative underflows are 0 (positive zero); a subnormal is kept */
    double v = -1.0;
    CHECK_MSG(cli_parse_nonneg("-0", &v) && same_bits(v, 0.0), "nonneg '-0' -> %a", v);
    CHECK_MSG(cli_parse_nonneg("-1e-400", &v) && same_bits(v, 0.0), "nonneg '-1e-400' -> %a", v);
    CHECK_MSG(cli_parse_nonneg("4.9e-324", &v) && same_bits(v, 0x1p-1074), "nonneg '4.9e-324' -> %a", v);
    CHECK_MSG(!cli_parse_nonneg("-5e-324", &v) && !cli_parse_nonneg("-1", &v) && !cli_parse_nonneg("1e400", &v),
              "nonneg refuses negatives and overflow");
    /* X,Y,Z */
    double w[3] = {9, 9, 9};
    CHECK_MSG(cli_parse_doubles("1e-320,0,-0", 3, w) && same_bits(w[0], strtod("1e-320", NULL)) && w[1] == 0 &&
                  same_bits(w[2], -0.0), "'1e-320,0,-0' -> %a %a %a", w[0], w[1], w[2]);
    CHECK_MSG(cli_parse_doubles(" 1 , 2 ,3 ", 3, w) && w[0] == 1 && w[1] == 2 && w[2] == 3, "' 1 , 2 ,3 ' -> %g %g %g",
              w[0], w[1], w[2]);
    static const char* const bad3[] = {"1,2", "1,2,3,4", "1,2,3,", ",1,2,3", "1,,2,3", "1 2 3", "1,2,1e999", "1,nan,2",
                                       "1,2,3x", ""};
    for (size_t i = 0; i < sizeof bad3 / sizeof bad3[0]; ++i) {
        double u[3] = {9, 9, 9};
        CHECK_MSG(!cli_parse_doubles(bad3[i], 3, u) && u[0] == 9 && u[1] == 9 && u[2] == 9, "X,Y,Z '%s' should be refused",
                  bad3[i]);
    }
    /* integers: digits only, within 64 bits (" -5" was read as 2^64 - 5 by strtoull) */
    unsigned long long n = 7;
    CHECK_MSG(cli_parse_uint("18446744073709551615", &n) && n == 18446744073709551615ull, "uint max -> %llu", n);
    CHECK_MSG(cli_parse_uint(" 42 ", &n) && n == 42, "uint ' 42 ' -> %llu", n);
    static const char* const badu[] = {"", "-5", " -5", "+5", "18446744073709551616", "1e3", "5x", "0x10", "1 2"};
    for (size_t i = 0; i < sizeof badu / sizeof badu[0]; ++i) {
        n = 7;
        CHECK_MSG(!cli_parse_uint(badu[i], &n) && n == 7, "uint '%s' should be refused, read as %llu", badu[i], n);
    }
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
    int before = tg_test_failed_;
    test_reading(count);
    printf("reading: %d failures\n", tg_test_failed_ - before);
    printf("%ld numbers checked\n", checked);
    return tg_test_finish();
}
