/* medium_air.h — the air's own light per unit length at a point, for a medium that integrates
 * its own part of a ray (media_interval) and so must add the air there itself. Over the plan's
 * composition of the media (media_at, media_phase, medium_ms_source), before the media's own
 * stepping (cloud_shell_march.h). */
#ifndef ATMO_MEDIA_MEDIUM_AIR_H
#define ATMO_MEDIA_MEDIUM_AIR_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/sky_method.h"
#include "media/ray.h"
#include "media/media.h"
#include "atmo/gpu_types.h"
#endif

/* The air's light toward the viewer per unit length at a point q of a ray with view-sun cosine
 * nu, under the sunlight sun_e (E T_sun V): sum over the air's components of
 * sigma_s,k p_k(nu) sun_e, plus with use_ms the method's multiple-scattering source. A medium
 * that integrates its own part of a ray (media_interval) adds it for the air there. */
ATMO_FN vec3 medium_air_source(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                               const medium_point *q, float nu, vec3 sun_e, int use_ms,
                               int ground)
{
    media_sample ms = media_at(s, ATMO_LUT_ARGS, q);
    vec3 air = v3_add(v3_mul(ms.scattering[MEDIA_RAYLEIGH],
                             media_phase(s, ATMO_LUT_ARGS, MEDIA_RAYLEIGH, nu)),
                      v3_mul(ms.scattering[MEDIA_MIE], media_phase(s, ATMO_LUT_ARGS, MEDIA_MIE, nu)));
    vec3 L = v3_mul(air, sun_e);
    if (use_ms)
        L = v3_add(L, medium_ms_source(s, ATMO_LUT_ARGS, q, nu, &ms, ground));
    return L;
}

#endif
