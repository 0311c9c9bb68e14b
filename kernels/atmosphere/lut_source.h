/* lut_source.h — method lut's multiple-scattering source in the plan's composition (media.h:
 * medium_ms_source, medium_ms_ground_irradiance): the density J of orders >= 2 toward the ray
 * (`ground` the ray's side of the horizon) and the sky's irradiance on the ground, read from
 * buffer scattering_mie (LUT_DENSITY_SUM and LUT_TEXELS, lut_scattering.h). The medium
 * integrator marches segments with it (method_lut.h), so it comes before the composition. */
#ifndef ATMO_LUT_SOURCE_H
#define ATMO_LUT_SOURCE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "atmosphere/lut_scattering.h"
#include "atmosphere/sky_method.h"
#include "media/ray.h"
#include "media/media.h"
#include "atmo/gpu_types.h"
#endif

ATMO_FN vec3 lut_ms_source(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                           const medium_point *q, float nu, const media_sample *m, int ground)
{
    ATMO_GLOBAL const int *dims = s->lut.dims;
    return lut_scattering_lookup(&s->atmosphere, scattering_mie + LUT_DENSITY_SUM(dims), dims,
                                 q->r, atmo_clamp_cos(q->mu), q->mu_s, nu, ground);
}

ATMO_FN vec3 lut_ms_ground_irradiance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                      float mu_s)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    ATMO_GLOBAL const int *dims = s->lut.dims;
    return lut_irradiance_lookup(a, scattering_mie + LUT_TEXELS(dims), dims, a->bottom_radius,
                                 mu_s);
}

#endif
