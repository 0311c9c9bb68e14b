/* planet.h — the planet's ground sphere as an occluder of the sun, the first of the plan's
 * composition of occluders (visibility.h): a point is lit iff the ray from it toward the sun (a
 * point sun, as the host reference has it) misses the ground sphere, in closed form on the
 * point's radius r and sun cosine mu_s: shadowed iff mu_s < 0 and r^2 (mu_s^2 - 1) + R^2 >= 0
 * (geometry.h, whose discriminant keeps its precision at planet scale). */
#ifndef ATMO_MEDIA_PLANET_H
#define ATMO_MEDIA_PLANET_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/geometry.h"
#include "atmosphere/sky_method.h"
#include "media/ray.h"
#include "atmo/gpu_types.h"
#endif

/* 1 where the planet leaves the sun visible from the point, 0 in its shadow. */
ATMO_FN float planet_sun_visibility(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                    const medium_point *q)
{
    return geometry_ray_hits_ground(q->r, q->mu_s, s->atmosphere.bottom_radius) ? 0.0f : 1.0f;
}

#endif
