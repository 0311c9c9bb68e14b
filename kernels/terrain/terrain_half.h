/* terrain_half.h — the half-float heightmap's texels (ATMO_TERRAIN_FORMAT_HALF): IEEE 754
 * binary16, 1 sign bit, 5 exponent bits (bias 15), 10 fraction bits.
 *
 * On the device the heightmap pass stores with vstore_half and the lookups load with vload_half
 * (OpenCL C 1.2, section 6.12.7: core, no cl_khr_fp16 needed); vstore_half rounds to nearest,
 * ties to even. The host has the same two conversions in bits, for the kernels' lookups compiled
 * as C and for the tests and benchmark:
 *   terrain_half_to_float: exact (every binary16 value is a float): a normal h with exponent
 *     field E and fraction m is (-1)^s (1 + m 2^-10) 2^(E - 15), a subnormal (E = 0)
 *     (-1)^s m 2^-24, E = 31 infinity (m = 0) or NaN;
 *   terrain_half_from_float: round to nearest, ties to even (vstore_half's rounding), overflow
 *     to infinity (|x| >= 65520, the midpoint above the largest half 65504), subnormals kept
 *     (spacing 2^-24), NaN kept as a quiet NaN.
 * A height h stored as half is off by at most 2^-11 |h| (the unit roundoff of 11 significant
 * bits) for |h| >= 2^-14 and by at most 2^-25 below that: about 1 m at 2048..4096 m. */
#ifndef ATMO_TERRAIN_HALF_H
#define ATMO_TERRAIN_HALF_H
#ifndef __OPENCL_VERSION__
#include <string.h>
#include "common/compat.h"

ATMO_FN float terrain_half_to_float(unsigned short h)
{
    unsigned sign = (unsigned)(h & 0x8000u) << 16, e = (h >> 10) & 0x1fu, m = h & 0x3ffu, bits;
    if (e == 0) { /* zero and subnormals: m 2^-24 exactly */
        float x = ldexpf((float)m, -24);
        return sign ? -x : x;
    }
    if (e == 31)
        bits = sign | 0x7f800000u | (m << 13);
    else
        bits = sign | ((e + 112u) << 23) | (m << 13); /* exponent e - 15 + 127 */
    float x;
    memcpy(&x, &bits, sizeof x);
    return x;
}

ATMO_FN unsigned short terrain_half_from_float(float x)
{
    unsigned bits;
    memcpy(&bits, &x, sizeof bits);
    unsigned sign = (bits >> 16) & 0x8000u, exp = (bits >> 23) & 0xffu, mant = bits & 0x7fffffu;
    if (exp == 0xffu) /* infinity, NaN (quiet) */
        return (unsigned short)(sign | 0x7c00u | (mant ? 0x200u : 0u));
    int e = (int)exp - 127 + 15; /* the half's exponent field */
    if (e <= 0) {                /* a half subnormal (or zero): units of 2^-24 */
        if (e < -10)             /* |x| < 2^-25: nearer 0 than the smallest subnormal */
            return (unsigned short)sign;
        mant |= 0x800000u;
        int shift = 14 - e;
        unsigned q = mant >> shift, rem = mant & ((1u << shift) - 1u), half = 1u << (shift - 1);
        if (rem > half || (rem == half && (q & 1u)))
            q++; /* a carry into bit 10 is the smallest normal, as it should be */
        return (unsigned short)(sign | q);
    }
    unsigned h = ((unsigned)e << 10) | (mant >> 13), rem = mant & 0x1fffu;
    if (rem > 0x1000u || (rem == 0x1000u && (h & 1u)))
        h++; /* a carry into the exponent is the next binade */
    if (h >= 0x7c00u)
        return (unsigned short)(sign | 0x7c00u);
    return (unsigned short)(sign | h);
}
#endif

/* Texel k of a half heightmap (hm: the buffer as the kernels receive it). */
#ifdef __OPENCL_VERSION__
#define TERRAIN_LOAD_HALF(hm, k) vload_half((size_t)(k), (ATMO_GLOBAL const half *)(hm))
#else
#define TERRAIN_LOAD_HALF(hm, k) terrain_half_to_float(((const unsigned short *)(hm))[k])
#endif

#endif
