/* sky_method.h — the interface between the sky kernels and the atmosphere methods.
 *
 * Every method (single scattering, ray marching with a multiple-scattering term, precomputed
 * LUTs, the Monte Carlo reference) is one fragment that defines
 *
 *   ATMO_FN void sky_trace(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
 *                          const medium_ray *ray, float t_max, rng_stream *rng,
 *                          vec3 *sky, vec3 *sun, vec3 *view_t);
 *
 * the radiance reaching the origin of a camera-relative ray (kernels/media/ray.h) from the
 * segment [0, t_max] of it: `sky` gets the scattered light and the lit ground, `sun` the sun
 * disc seen through the atmosphere, `view_t` the transmittance T(0, end). With t_max = INFINITY
 * the ray runs to the ground or out of the atmosphere. With t_max finite (aerial perspective, as
 * terrain and clouds need) the ray ends at a black (absorbing) surface at t_max metres:
 * `sky` is the light the air between scatters toward the origin (all the orders the method
 * models; no sun disc) and `view_t` T(0, t_max); where the ray reaches the ground or leaves the
 * atmosphere first, the segment is the whole ray. Random numbers come from the stream `rng`
 * (kernels/common/rng.h), drawn in order. single, march and fast are configurations of the
 * medium integrator (kernels/media/medium.h); lut and reference are their own estimators over
 * the same media and visibility interfaces.
 *
 * sky_cosines.h wraps it as sky_radiance(r, mu, mu_s, nu, pixel, sample, ...) and
 * sky_segment(..., d, ...) for the probes and the LUT precomputes. Every method gets the same
 * four LUT buffers (the transmittance LUT and three of its own; the plan binds a 16-byte dummy
 * to any it does not use), and every precompute kernel has the signature
 *
 *   __kernel void NAME(__global const atmo_gpu_scene *s, ATMO_LUT_OUT_PARAMS, int arg)
 *
 * so the host runs them from the plan's list of passes without knowing the method. */
#ifndef ATMO_SKY_METHOD_H
#define ATMO_SKY_METHOD_H

#define ATMO_LUT_PARAMS                                                                            \
    ATMO_GLOBAL const float4 *lut_transmittance, ATMO_GLOBAL const float4 *lut_a,                 \
        ATMO_GLOBAL const float4 *lut_b, ATMO_GLOBAL const float4 *lut_c
#define ATMO_LUT_OUT_PARAMS                                                                        \
    ATMO_GLOBAL float4 *lut_transmittance, ATMO_GLOBAL float4 *lut_a, ATMO_GLOBAL float4 *lut_b,  \
        ATMO_GLOBAL float4 *lut_c
#define ATMO_LUT_ARGS lut_transmittance, lut_a, lut_b, lut_c

#endif
