/* morton.h - Morton (Z-order) codes for spatial ordering of points and primitives.
 * Based on: G. M. Morton, "A computer oriented geodetic data base and a new technique in file
 * sequencing" (IBM, 1966); bit interleaving by shift-and-mask ("magic numbers"). */
#ifndef TG_MORTON_H
#define TG_MORTON_H

#include <stddef.h>
#include <stdint.h>

/* Spreads the low 10 bits of x to every third bit (bit i goes to bit 3i). */
static inline uint32_t tg__morton_spread3(uint32_t x)
{
    x &= 0x3FF;
    x = (x | x << 16) & 0x030000FF;
    x = (x | x << 8) & 0x0300F00F;
    x = (x | x << 4) & 0x030C30C3;
    x = (x | x << 2) & 0x09249249;
    return x;
}

/* Sorts the pairs kv[0..n) by their key in bits 32..61 (a 30-bit Morton code above a 32-bit
 * payload), stably: LSD radix sort, 3 passes of 10 bits, alternating between kv and tmp (n entries
 * each); hist is scratch for 1024 counters. Returns the array that holds the result (tmp, after an
 * odd number of passes). */
static inline uint64_t* tg__morton_sort_pairs(uint64_t* kv, uint64_t* tmp, size_t n, uint32_t* hist)
{
    for (int pass = 0; pass < 3; ++pass) {
        int shift = 32 + 10 * pass;
        for (int b = 0; b < 1024; ++b) hist[b] = 0;
        for (size_t i = 0; i < n; ++i) hist[kv[i] >> shift & 1023]++;
        uint32_t sum = 0;
        for (int b = 0; b < 1024; ++b) {
            uint32_t h = hist[b];
            hist[b] = sum;
            sum += h;
        }
        for (size_t i = 0; i < n; ++i) tmp[hist[kv[i] >> shift & 1023]++] = kv[i];
        uint64_t* t = kv;
        kv = tmp;
        tmp = t;
    }
    return kv;
}

#endif
