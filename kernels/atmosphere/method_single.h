/* method_single.h — atmosphere method "single": single scattering only (sky_single.h), with
 * one random offset of the march samples per sample. Multiple scattering is left out, so the
 * sky is 8-34 % too dark (atmosphere.md); it exists as the cheapest method and as the first
 * order that the others are checked against. */
#ifndef ATMO_METHOD_SINGLE_H
#define ATMO_METHOD_SINGLE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/rng.h"
#include "atmosphere/sky_method.h"
#include "atmosphere/sky_single.h"
#endif

ATMO_FN void sky_radiance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, float r,
                          float mu, float mu_s, float nu, uint pixel, uint sample, vec3 *sky,
                          vec3 *sun)
{
    float jitter = rng_uniform(s->seed, pixel, sample, ATMO_RNG_METHOD_DIM);
#ifdef ATMO_CLOUD /* a cloud shell or observer (cloud_shell.h) */
    vec3 view_t;
    cloud_integrate(s, transmittance_lut, cloud_phase_table, transmittance_lut, 0, 0, 0, r, mu,
                    mu_s, nu, INFINITY, s->view_steps, jitter, sky, sun, &view_t);
#else
    sky_single_scattering(s, transmittance_lut, r, mu, mu_s, nu, jitter, sky, sun);
#endif
}

/* The segment [0, d]: the same march, ended at d (sky_single.h, cloud_shell.h). */
ATMO_FN void sky_segment(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, float r, float mu,
                         float mu_s, float nu, float d, uint pixel, uint sample, vec3 *inscatter,
                         vec3 *transmittance)
{
    float jitter = rng_uniform(s->seed, pixel, sample, ATMO_RNG_METHOD_DIM);
#ifdef ATMO_CLOUD
    vec3 sun;
    cloud_integrate(s, transmittance_lut, cloud_phase_table, transmittance_lut, 0, 0, 0, r, mu,
                    mu_s, nu, d, s->view_steps, jitter, inscatter, &sun, transmittance);
#else
    sky_single_segment(s, transmittance_lut, r, mu, mu_s, nu, d, jitter, inscatter,
                       transmittance);
#endif
}

#endif
