/* method_march.h — atmosphere method "march": per-pixel ray march of single scattering plus
 * the multiple-scattering term sigma_s Psi_ms (ms_lut.h, after Hillaire 2020 sec. 5.5), with a
 * sun-visibility hook per sample for light shafts.
 *
 * Buffers: ms_lut = Psi_ms, its anisotropy and scratch (14 planes), s->ms.width x s->ms.height
 * the size of a plane (mu_s x altitude), filled by ms_lut.cl.
 * Knobs: s->view_steps segments per view ray; one random offset of the segment samples per
 * sample (dimension ATMO_RNG_METHOD_DIM), as method "single" does, so both draw the same
 * offsets and agree exactly where Psi is zero. */
#ifndef ATMO_METHOD_MARCH_H
#define ATMO_METHOD_MARCH_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/rng.h"
#include "atmosphere/sky_method.h"
#include "atmosphere/ms_lut.h"
#endif

ATMO_FN void sky_radiance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, float r,
                          float mu, float mu_s, float nu, uint pixel, uint sample, vec3 *sky,
                          vec3 *sun)
{
    float jitter = rng_uniform(s->seed, pixel, sample, ATMO_RNG_METHOD_DIM);
#ifdef ATMO_CLOUD /* a cloud shell or observer (cloud_shell.h) */
    vec3 view_t;
    cloud_integrate(s, transmittance_lut, cloud_phase_table, ms_lut, s->ms.width, s->ms.height,
                    1, r, mu, mu_s, nu, INFINITY, s->view_steps, jitter, sky, sun, &view_t);
#else
    march_integrate(s, transmittance_lut, ms_lut, s->ms.width, s->ms.height, r, mu,
                    mu_s, nu, s->view_steps, jitter, sky, sun);
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
    cloud_integrate(s, transmittance_lut, cloud_phase_table, ms_lut, s->ms.width, s->ms.height,
                    1, r, mu, mu_s, nu, d, s->view_steps, jitter, inscatter, &sun, transmittance);
#else
    march_segment(s, transmittance_lut, ms_lut, s->ms.width, s->ms.height, r, mu, mu_s,
                  nu, d, s->view_steps, jitter, inscatter, transmittance);
#endif
}

#endif
