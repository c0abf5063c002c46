/* cli_number.c - the CLI's numbers: read (the one rule of README.md "Numbers": decimal text, the
 * nearest double, subnormals included, then the option's range) and written (the shortest decimal
 * that reads back to the same double, for every number the CLI prints).
 * Based on: ISO C11 7.22.1.3 (strtod: correctly rounded in glibc, ERANGE also for a subnormal or
 * zero result of an underflow, which is not an error here); for the writer, Ulf Adams, "Ryu: fast
 * float-to-string conversion", PLDI 2018: §2 (the interval of decimals that round to the double:
 * halfway to each neighbour, bounds included when the significand is even, the lower one closer
 * for powers of two), §3.3 (the three interval points scaled by 10^-q, q one below the decimal
 * length so that one extra digit remains, computed exactly from 125-bit approximations of 2^k /
 * 5^q and 5^i / 2^k: the paper's Theorem and its table sizes), §3.4 (digits removed while the
 * scaled interval still holds a shorter number; the last removed digit rounds the result;
 * trailing-zero tracking only where the scaled values can be exact). The tables are computed here
 * at first use with exact multi-word arithmetic (5^i by repeated multiplication, 2^N / 5^q by
 * repeated division), not stored. */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ---- reading ---- */

static bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }
static bool is_digit(char c) { return c >= '0' && c <= '9'; }

static const char* skip_blanks(const char* s)
{
    while (is_blank(*s)) ++s;
    return s;
}

/* The length of the decimal number at s: [+-] digits [. [digits]] | [+-] . digits, then an
 * optional exponent (e|E) [+-] digits; 0 when s holds none. */
static size_t decimal_length(const char* s)
{
    size_t i = 0, digits = 0;
    if (s[i] == '+' || s[i] == '-') ++i;
    while (is_digit(s[i])) ++i, ++digits;
    if (s[i] == '.')
        for (++i; is_digit(s[i]); ++i) ++digits;
    if (!digits) return 0;
    if (s[i] == 'e' || s[i] == 'E') {
        size_t j = i + 1;
        if (s[j] == '+' || s[j] == '-') ++j;
        if (is_digit(s[j])) { /* "1e" is the number 1 followed by 'e' */
            while (is_digit(s[j])) ++j;
            i = j;
        }
    }
    return i;
}

cli_number_status cli_scan_double(const char* s, double* out, const char** end)
{
    s = skip_blanks(s);
    *end = s;
    size_t len = decimal_length(s);
    if (!len) return CLI_NUMBER_SYNTAX;
    char* after;
    errno = 0;
    double v = strtod(s, &after);
    /* strtod also reads hexadecimal, "inf" and "nan", which are no decimal text: when it reads
     * past the decimal, the text is not one */
    if (after != s + len) return CLI_NUMBER_SYNTAX;
    *end = after;
    if (!isfinite(v)) return CLI_NUMBER_INFINITE; /* an overflow (ERANGE, HUGE_VAL) */
    /* ERANGE with a finite result: an underflow, to a subnormal or to zero, the nearest double */
    *out = v;
    return CLI_NUMBER_OK;
}

bool cli_parse_double(const char* s, double* out)
{
    const char* end;
    double v;
    if (!s || cli_scan_double(s, &v, &end) != CLI_NUMBER_OK || *skip_blanks(end)) return false;
    *out = v;
    return true;
}

bool cli_parse_nonneg(const char* s, double* out)
{
    double v;
    if (!cli_parse_double(s, &v) || !(v >= 0.0)) return false;
    *out = v + 0.0; /* -0 (or a negative number that underflows to it) is 0 */
    return true;
}

bool cli_parse_doubles(const char* s, int n, double* out)
{
    double v[16];
    if (!s || n < 1 || n > 16) return false;
    for (int k = 0; k < n; ++k) {
        const char* end;
        if (cli_scan_double(s, &v[k], &end) != CLI_NUMBER_OK) return false;
        s = skip_blanks(end);
        if (k + 1 < n && *s++ != ',') return false;
    }
    if (*s) return false;
    memcpy(out, v, (size_t)n * sizeof *out);
    return true;
}

bool cli_parse_uint(const char* s, unsigned long long* out)
{
    if (!s) return false;
    s = skip_blanks(s);
    if (!is_digit(*s)) return false; /* no sign: strtoull would negate "-5" silently */
    char* end;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    if (errno || *skip_blanks(end)) return false;
    *out = v;
    return true;
}

/* ---- writing: the tables ---- */

#define POW5_BITS 125         /* bits kept of 5^i and of 2^k / 5^q (Ryu §3.3 for doubles) */
#define POW5_COUNT 326        /* 5^i for i <= 325: -e2 - q over all subnormal and normal doubles */
#define POW5_INV_COUNT 342    /* 2^k / 5^q for q <= 341 (q <= 291 is used) */

typedef struct u128 {
    uint64_t lo, hi;
} u128;

static u128 pow5_split[POW5_COUNT];        /* the top POW5_BITS bits of 5^i */
static u128 pow5_inv_split[POW5_INV_COUNT]; /* floor(2^(bitlen(5^q) - 1 + POW5_BITS) / 5^q) + 1 */
static bool tables_ready;

/* Little-endian multi-word integers of at most BIG_WORDS 32-bit words. */
#define BIG_WORDS 40 /* 1280 bits: 5^341 < 2^793, and 2^N with N = 1216 */
typedef struct big {
    uint32_t w[BIG_WORDS];
    int n; /* words in use (the top one non-zero, or n == 0 for zero) */
} big;

static int big_bitlen(const big* b)
{
    if (!b->n) return 0;
    uint32_t top = b->w[b->n - 1];
    int bits = 0;
    while (top) ++bits, top >>= 1;
    return 32 * (b->n - 1) + bits;
}

static void big_mul_small(big* b, uint32_t m)
{
    uint64_t carry = 0;
    for (int i = 0; i < b->n; ++i) {
        uint64_t t = (uint64_t)b->w[i] * m + carry;
        b->w[i] = (uint32_t)t;
        carry = t >> 32;
    }
    if (carry) b->w[b->n++] = (uint32_t)carry;
}

/* b = floor(b / d) */
static void big_div_small(big* b, uint32_t d)
{
    uint64_t rem = 0;
    for (int i = b->n - 1; i >= 0; --i) {
        uint64_t t = rem << 32 | b->w[i];
        b->w[i] = (uint32_t)(t / d);
        rem = t % d;
    }
    while (b->n && !b->w[b->n - 1]) --b->n;
}

/* floor(b / 2^s) * 2^t's low 128 bits, for a result below 2^128 (s, t >= 0, one of them 0). */
static u128 big_bits(const big* b, int s, int t)
{
    uint64_t word[4] = {0, 0, 0, 0}; /* 128 bits after the shifts */
    for (int k = 0; k < 128; ++k) {
        int src = k - t + s; /* bit k of the result is bit src of b */
        if (src < 0 || src >= 32 * b->n) continue;
        if (b->w[src / 32] >> (src % 32) & 1) word[k / 64] |= (uint64_t)1 << (k % 64);
    }
    u128 r = {word[0], word[1]};
    return r;
}

static void make_tables(void)
{
    big p = {{1}, 1};
    for (int i = 0; i < POW5_COUNT; ++i) {
        int len = big_bitlen(&p);
        pow5_split[i] = len >= POW5_BITS ? big_bits(&p, len - POW5_BITS, 0) : big_bits(&p, 0, POW5_BITS - len);
        big_mul_small(&p, 5);
    }
    /* d = floor(2^N / 5^q), kept exact by dividing by 5 step by step (floor(floor(x / a) / b) ==
     * floor(x / (a b))); the wanted floor(2^K / 5^q) is then d shifted right by N - K */
    const int N = 32 * BIG_WORDS - 64;
    big d = {{0}, N / 32 + 1};
    d.w[N / 32] = (uint32_t)1 << (N % 32);
    big p5 = {{1}, 1};
    for (int q = 0; q < POW5_INV_COUNT; ++q) {
        int K = big_bitlen(&p5) - 1 + POW5_BITS;
        u128 v = big_bits(&d, N - K, 0);
        v.lo += 1;
        if (!v.lo) v.hi += 1;
        pow5_inv_split[q] = v;
        big_div_small(&d, 5);
        big_mul_small(&p5, 5);
    }
    tables_ready = true;
}

/* ---- writing: the algorithm ---- */

/* floor(log10(2^e)) for 0 <= e <= 1650; floor(log10(5^e)) for 0 <= e <= 2620; bitlen(5^e). The
 * constants are the fixed-point logarithms, checked over those ranges by the test. */
static uint32_t log10_pow2(int e) { return ((uint32_t)e * 78913) >> 18; }
static uint32_t log10_pow5(int e) { return ((uint32_t)e * 732923) >> 20; }
static int pow5_bits(int e) { return (int)(((uint32_t)e * 1217359) >> 19) + 1; }

static uint32_t pow5_factor(uint64_t v)
{
    uint32_t n = 0;
    while (v % 5 == 0) v /= 5, ++n;
    return n;
}
static bool multiple_of_pow5(uint64_t v, uint32_t p) { return pow5_factor(v) >= p; }
static bool multiple_of_pow2(uint64_t v, uint32_t p) { return (v & (((uint64_t)1 << p) - 1)) == 0; }

/* floor(m * mul / 2^j) for m < 2^62 and a result below 2^64 (j > 64). */
static uint64_t mul_shift(uint64_t m, u128 mul, int j)
{
    unsigned __int128 lo = (unsigned __int128)m * mul.lo, hi = (unsigned __int128)m * mul.hi;
    unsigned __int128 sum = (lo >> 64) + hi;
    return (uint64_t)(sum >> (j - 64));
}

/* The shortest decimal digits and exponent of a finite non-zero |x|: value = digits * 10^exp. */
static void shortest(uint64_t ieee_mantissa, int ieee_exponent, uint64_t* out_digits, int* out_exp)
{
    int e2;
    uint64_t m2;
    if (ieee_exponent == 0) {
        e2 = 1 - 1023 - 52 - 2;
        m2 = ieee_mantissa;
    } else {
        e2 = ieee_exponent - 1023 - 52 - 2;
        m2 = ieee_mantissa | (uint64_t)1 << 52;
    }
    const bool even = (m2 & 1) == 0, accept_bounds = even;
    /* the interval: (mm, mp) * 2^e2 around mv * 2^e2; the lower half-gap is half as wide below a
     * power of two (except at the smallest normal exponent) */
    const uint64_t mv = 4 * m2;
    const uint32_t mm_shift = ieee_mantissa != 0 || ieee_exponent <= 1;
    uint64_t vr, vp, vm;
    int e10;
    bool vm_trailing_zeros = false, vr_trailing_zeros = false;
    if (e2 >= 0) {
        const uint32_t q = log10_pow2(e2) - (e2 > 3);
        e10 = (int)q;
        const int k = POW5_BITS + pow5_bits((int)q) - 1;
        const int i = -e2 + (int)q + k;
        vr = mul_shift(4 * m2, pow5_inv_split[q], i);
        vp = mul_shift(4 * m2 + 2, pow5_inv_split[q], i);
        vm = mul_shift(4 * m2 - 1 - mm_shift, pow5_inv_split[q], i);
        if (q <= 21) {
            /* only one of mv, mv + 2, mv - 1 - mm_shift can be a multiple of 5 */
            if (mv % 5 == 0)
                vr_trailing_zeros = multiple_of_pow5(mv, q);
            else if (accept_bounds)
                vm_trailing_zeros = multiple_of_pow5(mv - 1 - mm_shift, q);
            else
                vp -= multiple_of_pow5(mv + 2, q);
        }
    } else {
        const uint32_t q = log10_pow5(-e2) - (-e2 > 1);
        e10 = (int)q + e2;
        const int i = -e2 - (int)q;
        const int k = pow5_bits(i) - POW5_BITS;
        const int j = (int)q - k;
        vr = mul_shift(4 * m2, pow5_split[i], j);
        vp = mul_shift(4 * m2 + 2, pow5_split[i], j);
        vm = mul_shift(4 * m2 - 1 - mm_shift, pow5_split[i], j);
        if (q <= 1) {
            /* mv * 2^e2 / 10^q has q trailing zeros in its scaled form: mv is a multiple of 4 */
            vr_trailing_zeros = true;
            if (accept_bounds)
                vm_trailing_zeros = mm_shift == 1;
            else
                --vp;
        } else if (q < 63) {
            vr_trailing_zeros = multiple_of_pow2(mv, q);
        }
    }
    /* remove digits while a shorter number stays inside the interval */
    int removed = 0;
    uint32_t last_removed = 0;
    uint64_t output;
    if (vm_trailing_zeros || vr_trailing_zeros) {
        while (vp / 10 > vm / 10) {
            vm_trailing_zeros &= vm % 10 == 0;
            vr_trailing_zeros &= last_removed == 0;
            last_removed = (uint32_t)(vr % 10);
            vr /= 10, vp /= 10, vm /= 10, ++removed;
        }
        if (vm_trailing_zeros)
            while (vm % 10 == 0) {
                vr_trailing_zeros &= last_removed == 0;
                last_removed = (uint32_t)(vr % 10);
                vr /= 10, vp /= 10, vm /= 10, ++removed;
            }
        if (vr_trailing_zeros && last_removed == 5 && vr % 2 == 0) last_removed = 4; /* exactly halfway: even */
        output = vr + ((vr == vm && (!accept_bounds || !vm_trailing_zeros)) || last_removed >= 5);
    } else {
        bool round_up = false;
        while (vp / 10 > vm / 10) {
            round_up = vr % 10 >= 5;
            vr /= 10, vp /= 10, vm /= 10, ++removed;
        }
        output = vr + (vr == vm || round_up);
    }
    *out_digits = output;
    *out_exp = e10 + removed;
}

int cli_format_double(double x, char* out)
{
    if (!tables_ready) make_tables();
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    char* s = out;
    if (bits >> 63) *s++ = '-';
    const uint64_t mantissa = bits & (((uint64_t)1 << 52) - 1);
    const int exponent = (int)(bits >> 52 & 0x7FF);
    if (exponent == 0x7FF) { /* not produced by the library; written as C does */
        memcpy(s, mantissa ? "nan" : "inf", 4);
        return (int)(s - out) + 3;
    }
    if (exponent == 0 && mantissa == 0) {
        *s++ = '0';
        *s = '\0';
        return (int)(s - out);
    }
    uint64_t digits;
    int e;
    shortest(mantissa, exponent, &digits, &e);
    char buf[24];
    int n = 0;
    for (uint64_t d = digits; d; d /= 10) buf[n++] = (char)('0' + d % 10); /* reversed */
    const int point = n + e; /* the decimal point's place after the first `point` digits */
    /* fixed notation for decimal exponents -4 .. 15, as Python's repr (and %g's lower limit) */
    if (point > 0 && point <= 16) {
        /* 1234.5, 12300 */
        for (int i = 0; i < point; ++i) *s++ = i < n ? buf[n - 1 - i] : '0';
        if (n > point) {
            *s++ = '.';
            for (int i = point; i < n; ++i) *s++ = buf[n - 1 - i];
        }
    } else if (point <= 0 && point > -4) {
        /* 0.00123 */
        *s++ = '0', *s++ = '.';
        for (int i = point; i < 0; ++i) *s++ = '0';
        for (int i = 0; i < n; ++i) *s++ = buf[n - 1 - i];
    } else {
        /* 1.234e-07, 5e+22: as %g writes exponents, at least two digits */
        *s++ = buf[n - 1];
        if (n > 1) {
            *s++ = '.';
            for (int i = 1; i < n; ++i) *s++ = buf[n - 1 - i];
        }
        int x10 = point - 1;
        *s++ = 'e';
        *s++ = x10 < 0 ? '-' : '+';
        if (x10 < 0) x10 = -x10;
        if (x10 >= 100) *s++ = (char)('0' + x10 / 100);
        *s++ = (char)('0' + x10 / 10 % 10);
        *s++ = (char)('0' + x10 % 10);
    }
    *s = '\0';
    return (int)(s - out);
}

cli_num_text cli_num(double x)
{
    cli_num_text t;
    cli_format_double(x, t.s);
    return t;
}
