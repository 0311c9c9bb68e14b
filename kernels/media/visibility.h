/* visibility.h — the sun's visibility from a 3-D point and the opaque surfaces a ray can meet:
 * the occluder contract of the integrator (medium.h), the Monte Carlo reference and the path
 * tracer.
 *
 * An occluder (the planet, an observer sphere, the preview's objects, the terrain) is a feature
 * that registers its functions in the plan's registry (host/plan/features.c, atmo_slots); the
 * plan generates their composition (host/plan/compose.c), placed before this file:
 *     visibility_ray, visibility_ray_begin   the state the occluders keep along one ray of the
 *                                            integrator, sample to sample (`t` set before each
 *                                            sample): the terrain's light-shaft shortcuts
 *     visibility_sun_occluders(_on_ray)      the product of the occluders' visibility of the
 *                                            sun (0 or 1: a point sun, binary shadows), at a
 *                                            point or at a sample of a ray with state vr
 *     visibility_surface_occluders           the same for the occluders that also shadow
 *                                            surface points (the planet, the observer, the
 *                                            preview's objects; a surface's own shadow is its
 *                                            own: the terrain's is traced toward the sun's disc,
 *                                            terrain.h, surfaces.h)
 * and, after the surfaces' own light,
 *     visibility_surface_hit                 the distance to the nearest opaque surface other
 *                                            than the ground along a ray, or -1
 *     visibility_surface_radiance            the light leaving the surface at distance t
 *                                            toward the ray's origin (without the air between)
 * Media that shadow the sun (a cloud shell, an fBm layer) are not occluders: their
 * transmittance toward the sun is per wavelength and 0..1 (media_sun_attenuate, media.h), and
 * it multiplies the occluders' answer here. The atmosphere's own transmittance toward the sun
 * is not a visibility: the integrator takes it from the transmittance LUT, the Monte Carlo
 * reference tracks it. This file names no feature. */
#ifndef ATMO_MEDIA_VISIBILITY_H
#define ATMO_MEDIA_VISIBILITY_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "atmosphere/sky_method.h"
#include "media/ray.h"
#include "media/media.h"
#include "atmo/gpu_types.h"
#endif

/* v, the occluders' visibility of the sun from q, times the transmittance toward the sun of
 * the shadowing media (per wavelength). */
ATMO_FN vec3 visibility_media_sun(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                  const medium_point *q, float v)
{
    vec3 vis = v3(v, v, v);
    return v > 0.0f ? media_sun_attenuate(s, ATMO_LUT_ARGS, q, vis) : vis;
}

/* The sun's visibility at a sample of a ray with state vr (0: none), per wavelength. */
ATMO_FN vec3 visibility_sun_on_ray(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                   const medium_point *q, visibility_ray *vr)
{
    return visibility_media_sun(s, ATMO_LUT_ARGS, q,
                                visibility_sun_occluders_on_ray(s, ATMO_LUT_ARGS, q, vr));
}

ATMO_FN vec3 visibility_sun(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                            const medium_point *q)
{
    return visibility_sun_on_ray(s, ATMO_LUT_ARGS, q, 0);
}

/* v, the occluders' visibility of the sun from a surface point q, times the media's
 * transmittance toward the sun at a surface (media_sun_surface_attenuate, per wavelength). */
ATMO_FN vec3 visibility_media_sun_surface(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                          const medium_point *q, float v)
{
    vec3 vis = v3(v, v, v);
    return v > 0.0f ? media_sun_surface_attenuate(s, ATMO_LUT_ARGS, q, vis) : vis;
}

/* The sun's visibility at a surface point with its own shadow (the path tracer's, the
 * preview's terrain): the surface occluders and the media, per wavelength. */
ATMO_FN vec3 visibility_sun_surface(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                    const medium_point *q)
{
    return visibility_media_sun_surface(s, ATMO_LUT_ARGS, q,
                                        visibility_surface_occluders(s, ATMO_LUT_ARGS, q));
}

/* The same at a surface point that every occluder shades (the preview's objects,
 * objects_light.h, on which the terrain casts its shadow as a ray occluder). */
ATMO_FN vec3 visibility_sun_surface_all(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                        const medium_point *q)
{
    return visibility_media_sun_surface(s, ATMO_LUT_ARGS, q,
                                        visibility_sun_occluders(s, ATMO_LUT_ARGS, q));
}

#endif
