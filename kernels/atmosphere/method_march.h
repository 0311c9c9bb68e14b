/* method_march.h — atmosphere method "march": per-pixel ray march of single scattering plus
 * the multiple-scattering term sigma_s Psi_ms (ms_lut.h, after Hillaire 2020 sec. 5.5): the
 * medium integrator (kernels/media/medium.h) with the Psi_ms source, whose sun visibility per
 * sample gives light shafts and shadows.
 *
 * LUT: the buffer ms_lut, Psi_ms, its anisotropy and scratch (14 planes), each plane
 * s->ms.width x s->ms.height (mu_s x altitude), filled by ms_lut.cl.
 * Knobs: s->view_steps segments per view ray; one random offset of the segment samples per
 * sample (the first number of the method's stream), as method "single" draws, so both agree
 * exactly where Psi is zero. */
#ifndef ATMO_METHOD_MARCH_H
#define ATMO_METHOD_MARCH_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/rng.h"
#include "atmosphere/sky_method.h"
#include "atmosphere/ms_lut.h"
#include "media/medium.h"
#endif

ATMO_FN void sky_trace(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, const medium_ray *m,
                       float t_max, rng_stream *g, vec3 *sky, vec3 *sun, vec3 *view_t)
{
    march_trace(s, ATMO_LUT_ARGS, m, t_max, rng_next(g), sky, sun, view_t);
}

#endif
