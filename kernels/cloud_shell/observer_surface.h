/* observer_surface.h — the observer sphere (observer.h) in the plan's composition
 * (visibility.h): an occluder of the sun, at every point and at the path tracer's surfaces, and
 * an opaque surface the view ray can meet. The observer is small, so it is lit like the camera's
 * surroundings: sunlight with the atmosphere's and the cloud shell's transmittance at the ray's
 * origin (its own shadow test would block it). */
#ifndef ATMO_CLOUD_SHELL_OBSERVER_SURFACE_H
#define ATMO_CLOUD_SHELL_OBSERVER_SURFACE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "atmosphere/sky_method.h"
#include "media/ray.h"
#include "cloud_shell/observer.h"
#include "cloud_shell/cloud_shell.h"
#include "atmo/gpu_types.h"
#endif

ATMO_FN float observer_sun_visibility(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                      const medium_point *q)
{
    return observer_blocks(s->cloud.observer, q->p, v3_from4(s->sun_direction)) ? 0.0f : 1.0f;
}

/* The distance along the ray to the observer, or -1 (t_max unused: the observer is the first
 * surface the composition asks). */
ATMO_FN float observer_surface_hit(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                   const medium_ray *m, float t_max)
{
    return observer_hit(s->cloud.observer, m);
}

/* The observer's light toward the ray's origin when it is the surface at distance t, else
 * x = -1. */
ATMO_FN vec3 observer_surface_radiance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                       const medium_ray *m, float t)
{
    float t_observer = observer_hit(s->cloud.observer, m);
    if (!(t_observer >= 0.0f && t_observer <= t))
        return v3(-1.0f, 0.0f, 0.0f);
    ATMO_GLOBAL const float4 *transmittance = transmittance_lut;
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    medium_point q = medium_ray_at(m, 0.0f, a->bottom_radius);
    vec3 sun_t = v3_mul(atmosphere_sun_transmittance(a, transmittance, s->transmittance_width,
                                                     s->transmittance_height, q.r, q.mu_s),
                        cloud_shell_sun_transmittance(s, &q, a->bottom_radius));
    return observer_radiance(s->cloud.observer, m, t, v3_mul(v3_from4(a->solar_irradiance), sun_t));
}

#endif
