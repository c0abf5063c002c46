/* numparse.h - fast, correctly rounded decimal parsing for the text readers.
 * Based on: W. D. Clinger, "How to Read Floating Point Numbers Accurately" (PLDI 1990), the
 * fast path: a decimal mantissa m <= 2^53 and a power 10^k with |k| <= 22 are both exact
 * doubles, so one IEEE multiplication or division gives the correctly rounded result. Every
 * other input falls back to strtod in the "C" locale (tg__strtod_c, whatever LC_NUMERIC the host
 * program set), which is also correctly rounded on glibc.
 * Extended path (x86 80-bit long double, 64-bit significand): a mantissa below 10^19 < 2^64 and
 * 10^k with |k| <= 27 (5^27 < 2^64) are exact, so one long double operation has error at most
 * half an ulp of long double; rounding that to double is correct unless the true value may lie
 * on the other side of a double rounding boundary, which we detect by rounding both ends of the
 * error interval and falling back to strtod when they differ. This keeps 17-digit (%.17g) input
 * on the fast path. */
#ifndef TG_NUMPARSE_H
#define TG_NUMPARSE_H

#include <float.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>

#include "core/core.h"

static inline bool tg__is_digit(char c) { return (unsigned)(c - '0') < 10u; }
static inline bool tg__is_blank(char c) { return c == ' ' || c == '\t'; }

/* Parses a double at p (no leading blanks). Returns the end pointer, or NULL if p does not start
 * a number. The text must be '\0'-terminated somewhere after p. Accepts what strtod accepts
 * (including inf/nan, which callers reject as non-finite). */
static inline const char* tg__parse_double(const char* p, double* out)
{
    static const double pow10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                     1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                     1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    const char* s = p;
    bool neg = false;
    if (*s == '-' || *s == '+') neg = *s++ == '-';
    uint64_t m = 0;
    int digits = 0, frac = 0;
    bool any = false;
    while (*s == '0') s++, any = true; /* leading zeros are not significant */
    while (tg__is_digit(*s)) {
        if (digits < 19) m = m * 10 + (uint64_t)(*s - '0');
        else goto slow;
        digits++, any = true, s++;
    }
    if (*s == '.') {
        s++;
        if (!digits)
            while (*s == '0') s++, frac++, any = true;
        while (tg__is_digit(*s)) {
            if (digits < 19) m = m * 10 + (uint64_t)(*s - '0');
            else goto slow;
            digits++, frac++, any = true, s++;
        }
    }
    if (!any) goto slow; /* "inf", "nan", hex, or not a number at all */
    int e = 0;
    if (*s == 'e' || *s == 'E') {
        const char* t = s + 1;
        bool eneg = false;
        if (*t == '-' || *t == '+') eneg = *t++ == '-';
        if (!tg__is_digit(*t)) goto slow;
        while (tg__is_digit(*t)) {
            if (e < 100000) e = e * 10 + (*t - '0');
            t++;
        }
        if (eneg) e = -e;
        s = t;
    }
    if (*s == 'x' || *s == 'X' || *s == 'p' || *s == 'P') goto slow;
    e -= frac;
    if (m <= (1ull << 53) && e >= -22 && e <= 22) {
        double v = (double)m;
        v = e < 0 ? v / pow10[-e] : v * pow10[e];
        *out = neg ? -v : v;
        return s;
    }
#if LDBL_MANT_DIG == 64
    if (e >= -27 && e <= 27) {
        static const long double pow10l[28] = {
            1e0L,  1e1L,  1e2L,  1e3L,  1e4L,  1e5L,  1e6L,  1e7L,  1e8L,  1e9L,
            1e10L, 1e11L, 1e12L, 1e13L, 1e14L, 1e15L, 1e16L, 1e17L, 1e18L, 1e19L,
            1e20L, 1e21L, 1e22L, 1e23L, 1e24L, 1e25L, 1e26L, 1e27L};
        long double v = (long double)m;
        v = e < 0 ? v / pow10l[-e] : v * pow10l[e];
        /* the exact value lies within v * (1 +- 2^-64); widen to 2^-62 and require both ends
         * to round to the same double */
        long double slack = v * 0x1p-62L;
        double lo = (double)(v - slack), hi = (double)(v + slack);
        if (lo == hi && v != 0.0L) {
            *out = neg ? -lo : lo;
            return s;
        }
    }
#endif
    goto slow;
slow:
    {
        char* endp;
        double v = tg__strtod_c(p, &endp);
        if (endp == p) return NULL;
        *out = v;
        return endp;
    }
}

/* Parses a signed decimal integer into int64 (saturating check). NULL if no digits or overflow. */
static inline const char* tg__parse_int(const char* p, int64_t* out)
{
    const char* s = p;
    bool neg = false;
    if (*s == '-' || *s == '+') neg = *s++ == '-';
    if (!tg__is_digit(*s)) return NULL;
    uint64_t v = 0;
    while (tg__is_digit(*s)) {
        v = v * 10 + (uint64_t)(*s - '0');
        if (v > (uint64_t)INT64_MAX) return NULL;
        s++;
    }
    *out = neg ? -(int64_t)v : (int64_t)v;
    return s;
}

#endif
