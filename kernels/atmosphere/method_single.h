/* method_single.h — atmosphere method "single": single scattering only, the medium integrator
 * (kernels/media/medium.h) without a multiple-scattering source, s->view_steps segments and one
 * random offset of the segment samples per sample. Multiple scattering is left out, so the sky
 * is 8-34 % too dark (atmosphere.md); it exists as the cheapest method and as the first order
 * that the others are checked against. */
#ifndef ATMO_METHOD_SINGLE_H
#define ATMO_METHOD_SINGLE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/rng.h"
#include "atmosphere/sky_method.h"
#include "media/medium.h"
#endif

ATMO_FN void sky_trace(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, const medium_ray *m,
                       float t_max, rng_stream *g, vec3 *sky, vec3 *sun, vec3 *view_t)
{
    medium_result res;
    medium_integrate(s, ATMO_LUT_ARGS, m, 0.0f, t_max, s->view_steps, rng_next(g), 0, &res);
    *sky = medium_radiance(s, ATMO_LUT_ARGS, &res, m->nu);
    *sun = res.sun;
    *view_t = res.view_t;
}

#endif
