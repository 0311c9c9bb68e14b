/* sky_cosines.h — the method's sky_trace (sky_method.h) for a ray given by its cosines: what
 * the probes (`atmo radiance`, the tests) and the LUT precomputes ask for.
 *
 *   sky_radiance(s, luts, r, mu, mu_s, nu, pixel, sample, &sky, &sun)
 *   sky_segment(s, luts, r, mu, mu_s, nu, d, pixel, sample, &inscatter, &transmittance)
 *
 * the light reaching a camera at radius r along a ray with view cosine mu, sun cosine mu_s and
 * view-sun cosine nu (spherical symmetry makes these four numbers enough for the atmosphere;
 * the 3-D ray is medium_ray_from_cosines'), over the whole ray or over [0, d] toward a black
 * surface at d (m). Ray `pixel`'s sample `sample` draws the random numbers a pixel's ray draws
 * after its camera (stage 0 past CAMERA_RNG_DIMS), so a probe and a render agree sample for
 * sample. */
#ifndef ATMO_SKY_COSINES_H
#define ATMO_SKY_COSINES_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/camera.h"
#include "common/rng.h"
#include "atmosphere/sky_method.h"
#include "media/ray.h"
#endif

ATMO_FN rng_stream sky_probe_stream(ATMO_GLOBAL const atmo_gpu_scene *s, uint pixel, uint sample)
{
    rng_stream g = rng_stream_stage(s->seed, pixel, sample, 0u);
    g.dim += CAMERA_RNG_DIMS;
    return g;
}

ATMO_FN void sky_radiance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, float r, float mu,
                          float mu_s, float nu, uint pixel, uint sample, vec3 *sky, vec3 *sun)
{
    medium_ray m = medium_ray_from_cosines(s, r, mu, mu_s, nu);
    rng_stream g = sky_probe_stream(s, pixel, sample);
    vec3 view_t;
    sky_trace(s, ATMO_LUT_ARGS, &m, INFINITY, &g, sky, sun, &view_t);
}

ATMO_FN void sky_segment(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, float r, float mu,
                         float mu_s, float nu, float d, uint pixel, uint sample, vec3 *inscatter,
                         vec3 *transmittance)
{
    medium_ray m = medium_ray_from_cosines(s, r, mu, mu_s, nu);
    rng_stream g = sky_probe_stream(s, pixel, sample);
    vec3 sun;
    sky_trace(s, ATMO_LUT_ARGS, &m, d, &g, inscatter, &sun, transmittance);
}

#endif
