/* cloud_noise.h — the noise of the fBm cloud layer (cloud_layer.h): lattice value noise from an
 * integer hash, its fractal sum (fBm) and a domain warp.
 *
 * Value noise (Perlin 1985's lattice form with values instead of gradients): at the integer
 * lattice point k = (i, j, l) the value v_k = hash(i, j, l, seed) / 2^24 in [0, 1), the hash
 * being rng.h's full-avalanche permutation of the coordinates spread by odd multipliers (as in
 * Teschner et al. 2003's spatial hash), then of the seed; between lattice
 * points the eight values are blended trilinearly with the quintic fade
 *     s(f) = f^3 (f (6 f - 15) + 10)   (Perlin 2002, "Improving noise", eq. 2)
 * so the noise is C2 and, a convex combination of values in [0, 1), stays in [0, 1).
 * fBm (Musgrave, in Ebert et al., "Texturing and Modeling", ch. 16) over turned octaves:
 *     fbm(x) = sum_{i<N} 2^-i v((2 R)^i R x + o_i) / sum_{i<N} 2^-i,  in [0, 1)
 * with a lattice offset o_i per octave that keeps the octaves' lattices apart and the octave
 * rotation R, the rotation by the unit quaternion (4, 3, 4, 0) / sqrt(41) (102.7 degrees about
 * the axis (3, 4, 0) / 5), whose entries are k / 41:
 *     R = [[9, 24, 32], [24, 23, -24], [-32, 24, -9]] / 41.
 * Value noise is a tensor product: where one axis' lattice values dominate a cell, its
 * contours are planes parallel to a lattice plane, and the fBm's low tail (the cloud, where
 * fbm < c <= 0.3) follows such a contour of the first octave over much of a cell. Unturned,
 * those planes are the world's axis planes (straight vertical walls of cloud, thesis-8). R's
 * rows (the first octave's lattice axes in x's frame) all rise 34-36 degrees above the
 * horizontal (the most three orthogonal axes can: 35.3), so every lattice plane of the first
 * octave leans 54-56 degrees from the horizontal in lattice units and 35-36 degrees in the
 * world (the layer's frequencies are (1, 2, 1) times f, twice as fine vertically), none steep;
 * the normals of R's planes lie at least 34 degrees, and those of R^2 .. R^6 (the default 6
 * octaves) at least 12 degrees, from the world's axes, and R has no zero entry, so none of
 * those octaves' lattice planes is vertical or contains a world axis
 * (tests/test_cloud_isotropy.c measures the contours' normals; docs/notes/clouds-lod.md).
 * R^7 turns by 7 x 102.7 = 719 degrees, within 1 degree of the lattice's own axes: a seventh
 * octave (clouds.octaves > 6; weight 2^-6) is nearly unturned, R^8 .. R^12 again at least 12.
 * The octaves turn one after another (as the terrain's 2-D octaves do, kernels/terrain/noise.h)
 * so that each has its own orientation.
 * Its level of detail (noise_fbm_lod) leaves out the octaves finer than a footprint and puts
 * their mean in their place (frequency clamping, Lagae et al. 2010, "A survey of procedural
 * noise functions", sec. 4).
 * The domain warp (Quilez 2002, "domain warping") samples a field at x + A (2 w(x) - 1), w a
 * vector of three value noises.
 *
 * Bitwise the same on every device: the lattice values are integer arithmetic, floor and the
 * float operations are correctly rounded (+, -, *; the factors 2^i are exact; R's entries are
 * decimal literals that every compiler rounds to the same floats), and contraction
 * into fused multiply-adds is switched off for this file, so a GPU and PoCL compute the same
 * bits (tests/test_cloud_noise.c compares the device with the host). */
#ifndef ATMO_CLOUDS_CLOUD_NOISE_H
#define ATMO_CLOUDS_CLOUD_NOISE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/rng.h"
#endif

/* no fused multiply-adds in this file's functions (the compilers' default, on, returns at its
 * end) */
#ifdef __OPENCL_VERSION__
#pragma OPENCL FP_CONTRACT OFF
#endif

/* The lattice value at (i, j, l), in [0, 1). */
ATMO_FN float noise_lattice(int i, int j, int l, uint seed)
{
    /* one avalanche over the coordinates spread by odd constants (a lattice point's value
     * only has to look independent of its neighbours'), a second over the seed */
    uint h = rng_permute(((uint)i * 0x8da6b343u ^ (uint)j * 0xd8163841u ^
                          (uint)l * 0xcb1ab31fu) + 0x9e3779b9u); /* off permute's fixed point 0 */
    h = rng_permute(h ^ seed);
    return (float)(h >> 8) * (1.0f / 16777216.0f);
}

ATMO_FN float noise_fade(float f)
{
    return f * f * f * (f * (f * 6.0f - 15.0f) + 10.0f);
}

ATMO_FN float noise_lerp(float a, float b, float t)
{
    return a + (b - a) * t;
}

/* Value noise at x (lattice units), in [0, 1). */
ATMO_FN float noise_value(vec3 x, uint seed)
{
    float fx = floorf(x.x), fy = floorf(x.y), fz = floorf(x.z);
    int i = (int)fx, j = (int)fy, l = (int)fz;
    float u = noise_fade(x.x - fx), v = noise_fade(x.y - fy), w = noise_fade(x.z - fz);
    float c000 = noise_lattice(i, j, l, seed), c100 = noise_lattice(i + 1, j, l, seed);
    float c010 = noise_lattice(i, j + 1, l, seed), c110 = noise_lattice(i + 1, j + 1, l, seed);
    float c001 = noise_lattice(i, j, l + 1, seed), c101 = noise_lattice(i + 1, j, l + 1, seed);
    float c011 = noise_lattice(i, j + 1, l + 1, seed);
    float c111 = noise_lattice(i + 1, j + 1, l + 1, seed);
    float a = noise_lerp(noise_lerp(c000, c100, u), noise_lerp(c010, c110, u), v);
    float b = noise_lerp(noise_lerp(c001, c101, u), noise_lerp(c011, c111, u), v);
    return noise_lerp(a, b, w);
}

/* x turned by the octave rotation R (see the top of the file): R x, its entries k / 41. */
ATMO_FN vec3 noise_rotate(vec3 x)
{
    return v3(0.219512195f * x.x + 0.585365854f * x.y + 0.780487805f * x.z,
              0.585365854f * x.x + 0.560975610f * x.y - 0.585365854f * x.z,
              -0.780487805f * x.x + 0.585365854f * x.y - 0.219512195f * x.z);
}

/* The point of octave i's lattice for the octave's turned point y = (2 R)^i R x: y + o_i with
 * o_i = (o, -o, o / 2), o = 37 i + (i mod 4) / 4 (multiples of 1/4 cell, exact in float). */
ATMO_FN vec3 noise_octave_point(vec3 y, int i)
{
    float o = (float)(i * 37) + 0.25f * (float)(i & 3);
    return v3(y.x + o, y.y - o, y.z + 0.5f * o);
}

/* fBm of `octaves` octaves at x (lattice units of the first octave) filtered to a footprint of
 * `footprint` lattice units of the first octave (level of detail), in [0, 1): octave i, whose
 * cells are 2^-i wide, has k_i = footprint 2^i of its cells in a footprint (the rotation keeps
 * lengths); it is evaluated in full where a cell spans two footprints or more (k_i <= 1/2),
 * replaced by its mean 1/2 where it spans one or less (k_i >= 1; not evaluated), and blended
 * linearly between, with the evaluated share e_i = clamp(2 - 2 k_i, 0, 1). With footprint 0 it
 * is the plain fBm. */
ATMO_FN float noise_fbm_lod(vec3 x, int octaves, float footprint, uint seed)
{
    float sum = 0.0f, norm = 0.0f, amp = 1.0f, k = footprint;
    vec3 y = noise_rotate(x); /* (2 R)^i R x, octave by octave */
    for (int i = 0; i < octaves; i++) {
        float e = clamp(2.0f - 2.0f * k, 0.0f, 1.0f), v = 0.5f;
        if (e > 0.0f) {
            float n = noise_value(noise_octave_point(y, i), seed + (uint)i);
            v = e < 1.0f ? noise_lerp(0.5f, n, e) : n;
        }
        sum += amp * v;
        norm += amp;
        amp *= 0.5f;
        y = noise_rotate(v3_scale(y, 2.0f));
        k *= 2.0f;
    }
    return sum / norm;
}

/* fBm of `octaves` octaves at x (lattice units of the first octave), in [0, 1). */
ATMO_FN float noise_fbm(vec3 x, int octaves, uint seed)
{
    return noise_fbm_lod(x, octaves, 0.0f, seed);
}

/* The domain-warp displacement at x (lattice units): 2 w - 1 per axis, in (-1, 1). */
ATMO_FN vec3 noise_warp(vec3 x, uint seed)
{
    return v3(2.0f * noise_value(x, seed ^ 0x1b873593u) - 1.0f,
              2.0f * noise_value(v3(x.x + 17.0f, x.y, x.z), seed ^ 0xcc9e2d51u) - 1.0f,
              2.0f * noise_value(v3(x.x, x.y + 31.0f, x.z), seed ^ 0xe6546b64u) - 1.0f);
}

#ifdef __OPENCL_VERSION__
#pragma OPENCL FP_CONTRACT ON
#endif

#endif
