/* rng.h — counter-based random numbers: a pure function of (seed, pixel, sample, dimension).
 *
 * Nothing is carried between launches, so an image is bitwise identical whatever the tile size,
 * the samples per launch or the order of tiles. Each of the four counters is folded in by
 * xor followed by a full-avalanche 32-bit permutation (the "lowbias32" constants found by
 * C. Wellons' hash prospector; bias about 0.17 of the ideal avalanche). Because every step is a
 * bijection of the running state, distinct counters never share a state before the last mix.
 * Uniform floats keep the top 24 bits, so they lie on the float grid k * 2^-24 in [0, 1).
 * Tested by chi-square for uniformity of each dimension and independence of pairs
 * (tests/test_rng.c).
 *
 * Streams: a sample's dimensions are handed out by rng_stream, not from fixed bases. Stage k of
 * a sample (k = 0: the camera and the primary ray's integrator, which continues where the camera
 * stops; k >= 1: bounce k of a path, or any later stage that asks for one) owns the block of
 * dimensions [k 2^RNG_STAGE_BITS, (k + 1) 2^RNG_STAGE_BITS), and draws from it in order with
 * rng_next. A stage never needs to know how many numbers another one drew, so a path tracer can
 * call the medium integrator at every bounce with its own stream. 2^24 numbers per stage is
 * more than any walk draws (a Monte Carlo path draws a few per tentative collision). */
#ifndef ATMO_RNG_H
#define ATMO_RNG_H
#ifndef __OPENCL_VERSION__
#include <string.h>
#include "common/compat.h"
#endif

ATMO_FN uint rng_permute(uint x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

ATMO_FN uint rng_hash(uint seed, uint pixel, uint sample, uint dimension)
{
    uint h = rng_permute(seed ^ 0x9e3779b9u); /* golden-ratio offset keeps seed 0 off the fixed point 0 */
    h = rng_permute(h ^ pixel);
    h = rng_permute(h ^ sample);
    return rng_permute(h ^ dimension);
}

/* Uniform in [0, 1). */
ATMO_FN float rng_uniform(uint seed, uint pixel, uint sample, uint dimension)
{
    return (float)(rng_hash(seed, pixel, sample, dimension) >> 8) * (1.0f / 16777216.0f);
}

#define RNG_STAGE_BITS 24u

typedef struct rng_stream {
    uint seed, pixel, sample, dim; /* dim: the next dimension to draw */
} rng_stream;

/* The stream of stage `stage` of sample `sample` of pixel `pixel`. */
ATMO_FN rng_stream rng_stream_stage(uint seed, uint pixel, uint sample, uint stage)
{
    rng_stream g;
    g.seed = seed;
    g.pixel = pixel;
    g.sample = sample;
    g.dim = stage << RNG_STAGE_BITS;
    return g;
}

/* The stream of the stage after the one g belongs to (bounce k + 1 after bounce k). */
ATMO_FN rng_stream rng_stream_next_stage(const rng_stream *g)
{
    return rng_stream_stage(g->seed, g->pixel, g->sample, (g->dim >> RNG_STAGE_BITS) + 1u);
}

/* The next number of the stream, uniform in [0, 1). */
ATMO_FN float rng_next(rng_stream *g)
{
    return rng_uniform(g->seed, g->pixel, g->sample, g->dim++);
}

/* The bits of a float, as an unsigned integer. */
ATMO_FN uint rng_float_bits(float x)
{
#ifdef __OPENCL_VERSION__
    return as_uint(x);
#else
    uint u;
    memcpy(&u, &x, sizeof u);
    return u;
#endif
}

/* A 32-bit hash of the point p's bits and seed (the same permutation folds in each
 * coordinate): a counter for streams and offsets that are a function of a point, the same
 * in any tile and launch. */
ATMO_FN uint rng_point_hash(vec3 p, uint seed)
{
    uint h = rng_permute(seed ^ 0x2545f491u ^ rng_float_bits(p.x));
    h = rng_permute(h ^ rng_float_bits(p.y));
    return rng_permute(h ^ rng_float_bits(p.z));
}

#endif
