/* sky_method.h — the interface between the sky kernels and the atmosphere methods.
 *
 * Every method (single scattering, ray marching with a multiple-scattering term, precomputed
 * LUTs, the Monte Carlo reference) is one fragment that defines
 *
 *   ATMO_FN void sky_radiance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
 *                             float r, float mu, float mu_s, float nu,
 *                             uint pixel, uint sample, vec3 *sky, vec3 *sun);
 *
 * the radiance reaching a camera at radius r along a ray with view cosine mu, sun cosine mu_s
 * and view-sun cosine nu (spherical symmetry makes these four numbers enough): `sky` gets the
 * scattered light and the lit ground, `sun` the sun disc seen through the atmosphere. Random
 * numbers come from rng_uniform(s->seed, pixel, sample, d) with d >= ATMO_RNG_METHOD_DIM
 * (dimensions below it belong to the camera). Every method also defines
 *
 *   ATMO_FN void sky_segment(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
 *                            float r, float mu, float mu_s, float nu, float d,
 *                            uint pixel, uint sample, vec3 *inscatter, vec3 *transmittance);
 *
 * aerial perspective: the same ray ending at a black (absorbing) surface at distance d > 0
 * from the camera (metres), as terrain and clouds will need: `inscatter` gets the light that
 * the air between the camera and the surface scatters toward the camera (all the orders the
 * method models; no sun disc), `transmittance` T(0, d) through the atmosphere (1 outside it).
 * Where the ray reaches the ground or leaves the atmosphere before d, the segment is the whole
 * ray: `inscatter` is sky_radiance's `sky` (with the lit ground, which hides the surface) and
 * T is to the ground or to the top. Every method gets the same four LUT buffers
 * (the transmittance LUT and three of its own; the plan binds a 16-byte dummy to any it does
 * not use), and every precompute kernel has the signature
 *
 *   __kernel void NAME(__global const atmo_gpu_scene *s, ATMO_LUT_OUT_PARAMS, int arg)
 *
 * so the host runs them from the plan's list of passes without knowing the method. */
#ifndef ATMO_SKY_METHOD_H
#define ATMO_SKY_METHOD_H

#define ATMO_RNG_METHOD_DIM 2u

#define ATMO_LUT_PARAMS                                                                            \
    ATMO_GLOBAL const float4 *lut_transmittance, ATMO_GLOBAL const float4 *lut_a,                 \
        ATMO_GLOBAL const float4 *lut_b, ATMO_GLOBAL const float4 *lut_c
#define ATMO_LUT_OUT_PARAMS                                                                        \
    ATMO_GLOBAL float4 *lut_transmittance, ATMO_GLOBAL float4 *lut_a, ATMO_GLOBAL float4 *lut_b,  \
        ATMO_GLOBAL float4 *lut_c
#define ATMO_LUT_ARGS lut_transmittance, lut_a, lut_b, lut_c

#endif
