/* path_camera.h — the path tracer's primary samples: where in the pixel a sample lies, from a
 * low-discrepancy sequence decorrelated per pixel, and the thin lens.
 *
 * Sequence: the first two dimensions of Sobol's sequence (Sobol 1967): x_i = the bits of the
 * index i reversed (van der Corput in base 2), y_i = the same with the generator matrix of
 * Sobol's second dimension (the Pascal matrix mod 2: the direction numbers v_k = v_{k-1} xor
 * (v_{k-1} >> 1) from v_0 = 2^31). Every prefix of 2^k points is a (0, k, 2)-net: each
 * elementary interval of area 2^-k holds exactly one point, so a pixel's first 2^k samples
 * are stratified in every such grid at once. Decorrelation: each pixel gets its own nested
 * uniform (Owen) scrambling of each dimension, which keeps the net property and makes the
 * points of different pixels independent (Owen 1995). It is applied as a hash-based
 * permutation of the bit-reversed value that only propagates information from lower to higher
 * bits (Laine and Karras 2011, "Stratified sampling for stochastic transparency"; the
 * multiply-xor constants are those of Burley 2020, "Practical hash-based Owen scrambling",
 * JCGT 9(4)), keyed by rng_hash(seed, pixel, dimension). The index is the sample's own number,
 * so a sample's position depends only on (seed, pixel, sample): counter-based like rng.h.
 * path.sampler = random uses rng.h's hash instead (for the convergence comparison).
 *
 * Pixel filter: a Gaussian of standard deviation sigma truncated at radius R (pixels), sampled
 * by inverting its radial distribution: with u1, u2 in [0, 1),
 *     r = sigma sqrt(-2 ln(1 - u1 (1 - e^{-R^2 / (2 sigma^2)}))),  phi = 2 pi u2,
 * so (r cos phi, r sin phi) has density exp(-r^2 / (2 sigma^2)) / (2 pi sigma^2 (1 -
 * e^{-R^2/(2 sigma^2)})) inside the disc: each sample carries weight 1 and the image is the
 * filtered one (filter importance sampling; pbrt-v4 sec. 8.8). Defaults sigma = 0.5 px,
 * R = 1.5 px.
 * Thin lens (path.aperture_m > 0): the ray starts at a point of the aperture disc (radius
 * aperture_m, concentric in the camera's right/up plane, from two numbers of the stream) and
 * passes through the pinhole ray's point on the plane in focus at distance focus_m along
 * forward (pbrt-v4 sec. 5.2.3). */
#ifndef ATMO_RENDER_PATH_CAMERA_H
#define ATMO_RENDER_PATH_CAMERA_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/rng.h"
#include "common/camera.h"
#include "atmo/gpu_types.h"
#endif

ATMO_FN uint path_reverse_bits(uint x)
{
    x = (x << 16) | (x >> 16);
    x = ((x & 0x00ff00ffu) << 8) | ((x & 0xff00ff00u) >> 8);
    x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
    x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
    x = ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
    return x;
}

/* Sobol dimension 0 and 1 of index i, as 32-bit fractions. */
ATMO_FN uint path_sobol0(uint i) { return path_reverse_bits(i); }
ATMO_FN uint path_sobol1(uint i)
{
    uint y = 0u;
    for (uint v = 0x80000000u; i != 0u; i >>= 1, v ^= v >> 1)
        if (i & 1u)
            y ^= v;
    return y;
}

/* Nested uniform scrambling of a 32-bit fraction x keyed by seed: bit k of the result depends
 * only on bits above it, so intervals of every dyadic size map onto intervals of that size. */
ATMO_FN uint path_owen(uint x, uint seed)
{
    x = path_reverse_bits(x);
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return path_reverse_bits(x);
}

ATMO_FN float path_fraction(uint x) { return (float)(x >> 8) * (1.0f / 16777216.0f); }

/* The scrambled point (u, v) of sample `sample` of pixel `pixel`. */
ATMO_FN void path_sobol_2d(uint seed, uint pixel, uint sample, float *u, float *v)
{
    *u = path_fraction(path_owen(path_sobol0(sample), rng_hash(seed, pixel, 0x50b01u, 0u)));
    *v = path_fraction(path_owen(path_sobol1(sample), rng_hash(seed, pixel, 0x50b01u, 1u)));
}

/* The filter's offset from the pixel centre (pixels) for (u1, u2). */
ATMO_FN void path_filter_offset(float sigma, float radius, float u1, float u2, float *dx,
                                float *dy)
{
    float tail = -expm1f(-radius * radius / (2.0f * sigma * sigma)); /* 1 - e^{-R^2/2s^2} */
    float r = sigma * sqrtf(fmaxf(-2.0f * log1pf(-u1 * tail), 0.0f));
    float phi = 2.0f * ATMO_PI * u2;
    *dx = r * cosf(phi);
    *dy = r * sinf(phi);
}

/* The pinhole's ray at (u1, u2) in [0, 1)^2 of pixel (x, y) under the pixel filter, the
 * samples' own mapping (the denoiser's guides: the slot `pixel_ray`). */
ATMO_FN vec3 path_camera_pixel_ray(ATMO_GLOBAL const atmo_gpu_scene *s, int x, int y, float u1,
                                   float u2)
{
    float dx, dy;
    path_filter_offset(s->path.filter_sigma, s->path.filter_radius, u1, u2, &dx, &dy);
    return camera_ray(&s->camera, (float)x + 0.5f + dx, (float)y + 0.5f + dy);
}

/* The primary ray of a sample: camera-relative origin and unit direction (zero where the camera
 * sees nothing). The pixel position comes from the sequence, the lens from the stream g. */
ATMO_FN vec3 path_camera_sample(ATMO_GLOBAL const atmo_gpu_scene *s, int x, int y, uint pixel,
                                uint sample, rng_stream *g, vec3 *origin)
{
    ATMO_GLOBAL const atmo_gpu_camera *c = &s->camera;
    float u1, u2;
    if (s->path.sampler == ATMO_SAMPLER_SOBOL) {
        path_sobol_2d(s->seed, pixel, sample, &u1, &u2);
    } else {
        u1 = rng_next(g);
        u2 = rng_next(g);
    }
    float dx, dy;
    path_filter_offset(s->path.filter_sigma, s->path.filter_radius, u1, u2, &dx, &dy);
    vec3 d = camera_ray(c, (float)x + 0.5f + dx, (float)y + 0.5f + dy);
    *origin = v3(0.0f, 0.0f, 0.0f);
    float l1 = rng_next(g), l2 = rng_next(g); /* drawn always: streams stay aligned */
    if (s->path.aperture_m > 0.0f && c->kind == ATMO_CAMERA_PERSPECTIVE) {
        vec3 forward = v3_from4(c->forward);
        vec3 focus = v3_scale(d, s->path.focus_m / v3_dot(d, forward));
        float rl = s->path.aperture_m * sqrtf(l1), al = 2.0f * ATMO_PI * l2;
        *origin = v3_add(v3_scale(v3_from4(c->right), rl * cosf(al)),
                         v3_scale(v3_from4(c->up), rl * sinf(al)));
        d = v3_normalize(v3_sub(focus, *origin));
    }
    return d;
}

#endif
