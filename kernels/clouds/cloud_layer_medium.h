/* cloud_layer_medium.h — the fBm cloud layer (cloud_layer.h) as a medium of the methods, in the
 * plan's composition (media.h): its coefficients added at a point (component MEDIA_CLOUDS),
 * its phase function, the sun's transmittance through it, and its break points along a ray
 * (the layer's shell; cloud_march.h steps inside them). Not compiled when the layer is the path
 * tracer's volume alone (path.clouds = volume): no method sees it then.
 *
 * The sun's light through the layer to a point q outside the clouds (the air, a surface) is
 * exp(-extinction D), D the density integral toward the sun over the whole chord through the
 * layer: the sun shadow map's under -DATMO_CLOUDS_SHADOW_MAP (cloud_shadow_map.h; the light
 * march where the map does not reach), else the light march (cloud_layer.h) over the whole
 * chord with the point's own jitter (clouds_point_jitter). The march's cut at light_distance_m
 * is for the samples inside the clouds alone (cloud_march.h), whose octaves were fitted with
 * it; in the air and on the ground what matters is whether a cloud anywhere along the chord
 * hides the sun, and under a low sun those clouds lie tens of kilometres away (with the sun 10
 * degrees high a 7 km layer's chord is 40 km), so the same number of steps spreads over the
 * whole chord there, at the same cost. Units: metres, 1/m. */
#ifndef ATMO_CLOUDS_CLOUD_LAYER_MEDIUM_H
#define ATMO_CLOUDS_CLOUD_LAYER_MEDIUM_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/sky_method.h"
#include "media/ray.h"
#include "media/media.h"
#include "clouds/cloud_layer.h"
#ifdef ATMO_CLOUDS_SHADOW_MAP
#include "clouds/cloud_shadow_map.h"
#endif
#include "atmo/gpu_types.h"
#endif

ATMO_FN void clouds_media_add(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                              const medium_point *q, media_sample *m)
{
    vec3 layer = v3_scale(v3_from4(s->clouds.extinction), clouds_density(&s->clouds, q->p, q->h));
    m->scattering[MEDIA_CLOUDS] = v3_mul(layer, v3_from4(s->clouds.albedo));
    m->extinction = v3_add(m->extinction, layer);
}

ATMO_FN vec3 clouds_media_phase(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, float nu)
{
    return clouds_phase(s, clouds_phase_table, nu);
}

/* The density integral D (m) toward the sun from q over the whole chord through the layer: the
 * shadow map's, else the light march in n steps (see the top). */
ATMO_FN float clouds_chord_density(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                   const medium_point *q, int n)
{
#ifdef ATMO_CLOUDS_SHADOW_MAP
    (void)n;
    return clouds_shadow_map_density(s, clouds_shadow_map, q);
#else
    return clouds_sun_density_chord(s, q, clouds_point_jitter(q->p, s->clouds.seed), n);
#endif
}

/* The sun's transmittance through the layer to q in the air, exp(-extinction D), the chord in
 * the light march's light_steps steps. */
ATMO_FN vec3 clouds_media_sun(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                              const medium_point *q)
{
    float D = clouds_chord_density(s, ATMO_LUT_ARGS, q, s->clouds.light_steps);
    return v3_exp(v3_scale(v3_from4(s->clouds.extinction), -D));
}

/* The same to a surface point q (the terrain, an object), in CLOUDS_SURFACE_LIGHT_STEPS steps or
 * light_steps where they are more: a surface is asked once per camera ray, where the air's
 * samples ask many times. */
ATMO_FN vec3 clouds_media_sun_surface(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                      const medium_point *q)
{
    int n = s->clouds.light_steps > CLOUDS_SURFACE_LIGHT_STEPS ? s->clouds.light_steps
                                                                : CLOUDS_SURFACE_LIGHT_STEPS;
    float D = clouds_chord_density(s, ATMO_LUT_ARGS, q, n);
    return v3_exp(v3_scale(v3_from4(s->clouds.extinction), -D));
}

/* The parts of [t_start, t_end] of the ray inside the layer's shell, in order. */
ATMO_FN int clouds_media_intervals(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_ray *m,
                                   float t_start, float t_end, float *lo, float *hi)
{
    return geometry_shell_parts(s->atmosphere.bottom_radius, s->clouds.bottom_m, s->clouds.top_m,
                              m->r, m->mu, t_start, t_end, lo, hi);
}

#endif
