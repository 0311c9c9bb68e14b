/* visibility.h — the sun's visibility from a 3-D point and the opaque surfaces a ray can meet,
 * composed in one place from the visibility sources the plan includes.
 *
 * Sources: the planet (always): a point is lit iff the ray from it toward the sun (a point
 * sun, as the host reference has it) misses the ground sphere, in closed form on the point's
 * radius r and sun cosine mu_s: shadowed iff mu_s < 0 and r^2 (mu_s^2 - 1) + R^2 >= 0
 * (geometry.h, whose discriminant keeps its precision at planet scale); under -DATMO_CLOUD the
 * observer sphere (observer.h) at the point's camera-relative position, and the cloud shell's
 * transmittance along the sun's chord through it (cloud_shell.h); under -DATMO_CLOUDS the fBm
 * layer's light march (cloud_layer.h), so every caller gets cloud shadows in the air (light
 * shafts through gaps) and on the ground. Terrain (a heightmap march toward the sun) plugs in
 * here.
 * visibility_sun_occluders is the product of the opaque sources (0 or 1), visibility_sun adds
 * the shadowing media (per wavelength, 0..1); both get the buffers, where a source keeps its
 * data (a heightmap, a density grid). The atmosphere's own transmittance toward the
 * sun is not a visibility: the integrator takes it from the transmittance LUT, the Monte Carlo
 * reference tracks it. */
#ifndef ATMO_MEDIA_VISIBILITY_H
#define ATMO_MEDIA_VISIBILITY_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/geometry.h"
#include "media/ray.h"
#include "media/media.h"
#ifdef ATMO_CLOUD
#include "media/observer.h"
#endif
#include "atmo/gpu_types.h"
#endif

/* 1 where the planet leaves the sun visible from the point, 0 in its shadow. */
ATMO_FN float visibility_planet(ATMO_GLOBAL const atmo_gpu_atmosphere *a, const medium_point *q)
{
    return geometry_ray_hits_ground(q->r, q->mu_s, a->bottom_radius) ? 0.0f : 1.0f;
}

ATMO_FN float visibility_sun_occluders(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                       const medium_point *q)
{
    float v = visibility_planet(&s->atmosphere, q);
#ifdef ATMO_CLOUD
    if (observer_blocks(s->cloud.observer, q->p, v3_from4(s->sun_direction)))
        v = 0.0f;
#endif
    return v;
}

ATMO_FN vec3 visibility_sun(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                            const medium_point *q)
{
    float v = visibility_sun_occluders(s, ATMO_LUT_ARGS, q);
    vec3 vis = v3(v, v, v);
#ifdef ATMO_CLOUD
    if (v > 0.0f)
        vis = v3_scale(cloud_shell_sun_transmittance(s, q, s->atmosphere.bottom_radius), v);
#endif
#ifdef ATMO_CLOUDS
    if (v > 0.0f)
        vis = v3_mul(vis, clouds_sun_transmittance(s, q));
#endif
    return vis;
}

/* Distance along the ray to the first opaque surface other than the ground (the observer), or
 * -1 when there is none. */
ATMO_FN float visibility_surface_hit(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_ray *m)
{
#ifdef ATMO_CLOUD
    return observer_hit(s->cloud.observer, m);
#else
    return -1.0f;
#endif
}

/* Radiance leaving that surface toward the ray's origin, at distance t along the ray (without
 * the air in between). The observer is small, so it is lit like the camera's surroundings:
 * sunlight with the atmosphere's and the shell's transmittance at the ray's origin (its own
 * shadow test would block it). */
ATMO_FN vec3 visibility_surface_radiance(ATMO_GLOBAL const atmo_gpu_scene *s,
                                         ATMO_GLOBAL const float4 *transmittance,
                                         const medium_ray *m, float t)
{
#ifdef ATMO_CLOUD
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    medium_point q = medium_ray_at(m, 0.0f, a->bottom_radius);
    vec3 sun_t = v3_mul(atmosphere_sun_transmittance(a, transmittance, s->transmittance_width,
                                                     s->transmittance_height, q.r, q.mu_s),
                        cloud_shell_sun_transmittance(s, &q, a->bottom_radius));
    return observer_radiance(s->cloud.observer, m, t, v3_mul(v3_from4(a->solar_irradiance), sun_t));
#else
    return v3(0.0f, 0.0f, 0.0f);
#endif
}

#endif
