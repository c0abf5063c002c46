/* morton.h - Morton (Z-order) codes for spatial ordering of points and primitives.
 * Based on: G. M. Morton, "A computer oriented geodetic data base and a new technique in file
 * sequencing" (IBM, 1966); bit interleaving by shift-and-mask ("magic numbers"). */
#ifndef TG_MORTON_H
#define TG_MORTON_H

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

#endif
