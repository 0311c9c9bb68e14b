/* visibility.h — the sun's visibility from a 3-D point and the opaque surfaces a ray can meet,
 * composed in one place from the visibility sources the plan includes.
 *
 * Sources: the planet (always): a point is lit iff the ray from it toward the sun (a point
 * sun, as the host reference has it) misses the ground sphere, in closed form on the point's
 * radius r and sun cosine mu_s: shadowed iff mu_s < 0 and r^2 (mu_s^2 - 1) + R^2 >= 0
 * (geometry.h, whose discriminant keeps its precision at planet scale); under -DATMO_CLOUD the
 * observer sphere (observer.h) at the point's camera-relative position, and the cloud shell's
 * transmittance along the sun's chord through it (cloud_shell.h); under -DATMO_CLOUDS the fBm
 * layer's light march (cloud_layer.h), or its sun shadow map under -DATMO_CLOUDS_SHADOW_MAP
 * (cloud_shadow_map.h, buffer `clouds_shadow_map`), so every caller gets cloud shadows in the
 * air (light shafts through gaps) and on the ground; under -DATMO_OBJECTS the scene's spheres and boxes
 * (render/objects.h, buffer `objects`) block the ray toward the sun (a point sun: binary
 * shadows; the path tracer, -DATMO_PATH, samples the disc itself and casts soft ones, so there
 * they are left out here). Under -DATMO_TERRAIN the
 * terrain (kernels/terrain/terrain.h): a shadow ray from the point toward the sun's centre (a
 * point sun, as for the planet) with the shortcuts of terrain.shafts (terrain_shafts.h; those
 * that remember earlier samples of the ray need the integrator's per-ray state,
 * visibility_ray, through the *_on_ray forms), and the terrain's surface with its light
 * (terrain_shade.h; not under -DATMO_PATH, whose surfaces.h traces the terrain as a surface of
 * its own, and whose surface points take visibility_sun_surface).
 * visibility_sun_occluders is the product of the opaque sources (0 or 1), visibility_sun adds
 * the shadowing media (per wavelength, 0..1); both get the buffers, where a source keeps its
 * data (a heightmap, a density grid). The atmosphere's own transmittance toward the
 * sun is not a visibility: the integrator takes it from the transmittance LUT, the Monte Carlo
 * reference tracks it.
 * Under -DATMO_CLOUDS_VOLUME (path.clouds = volume) the fBm layer is the path tracer's medium
 * (render/volume_stage.h) and no source of visibility_sun; the air's samples (medium.h's
 * pieces, the reference's sunlight) take its transmittance toward the sun apart,
 * visibility_air_volume (not the surfaces: the path tracer's shadow function tracks the layer
 * for them itself). It is cloud_walk.h's ratio tracking against the majorant grid
 * (clouds_sun_ratio, the surfaces' and cloud vertices' walk) on a stream of its own: rng.h's
 * stream of the render seed at the "pixel" clouds_point_hash(p, seed) of the sample point's
 * bits. Unbiased: for a fixed point q the walk's estimate R has
 * E[R | q] = T_clouds(q) (ratio tracking, Novak et al. 2014; its roulette divides by the
 * survival probability) for any stream of independent uniform numbers, and the stream is a
 * full-avalanche hash of q's bits, as independent of the path's own numbers as rng.h's
 * counters are of each other. The point q is a function of the path's numbers (the camera,
 * the integrator's jitter, the bounces), so for the air's integrand f at q,
 *     E[f(q) R] = E[f(q) E[R | q]] = E[f(q) T_clouds(q)].
 * Two samples share numbers only where their points are the same floats, which jittered
 * samples of different paths almost never are (correlated then, not biased); and the same
 * point gives the same estimate in any tile and launch, so the image stays a function of the
 * seed. The estimate multiplies the sunlight and, as the marched layer's light march does,
 * the method's multiple-scattering source (medium.h). */
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
#ifdef ATMO_CLOUDS_SHADOW_MAP
#include "media/cloud_shadow_map.h"
#endif
#ifdef ATMO_OBJECTS
#include "render/objects.h"
#endif
#ifdef ATMO_TERRAIN
#include "terrain/terrain.h"
#include "terrain/terrain_shafts.h"
#include "terrain/terrain_shade.h"
#endif
#include "atmo/gpu_types.h"
#endif

#if defined(ATMO_OBJECTS) && !defined(ATMO_PATH)
/* the preview's objects: lit by the method's sky irradiance (media/medium.h, after this file) */
#define VISIBILITY_OBJECTS 1
ATMO_FN vec3 medium_ms_ground_irradiance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                         float mu_s);
#endif

/* The state the visibility sources keep along one ray of the integrator, sample to sample
 * (visibility_ray_begin, then `t` set before each sample): the terrain's light-shaft
 * shortcuts (terrain_shafts.h). */
typedef struct visibility_ray {
    float t; /* the sample's distance along the ray, m */
#ifdef ATMO_TERRAIN
    terrain_shafts terrain;
#endif
} visibility_ray;

/* The state of the ray m whose segment ends at `end`, at an opaque surface when surface_t >= 0
 * (visibility_surface_hit's distance). */
ATMO_FN void visibility_ray_begin(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_ray *m,
                                  float end, float surface_t, visibility_ray *vr)
{
    vr->t = 0.0f;
#ifdef ATMO_TERRAIN
    terrain_shafts_begin(s, m, end, surface_t, &vr->terrain);
#else
    (void)s, (void)m, (void)end, (void)surface_t;
#endif
}

#ifdef ATMO_CLOUDS_VOLUME
/* the layer's ratio tracking toward the sun, in kernels/media/cloud_walk.h (after the
 * integrator: it walks with tracking.h) */
ATMO_FN vec3 clouds_sun_ratio(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float *grid,
                              const medium_point *q, rng_stream *g);
#endif

/* The transmittance toward the sun, at a sample of the air, of the media that only the path
 * tracer's volume stage holds (see the top of the file): under -DATMO_CLOUDS_VOLUME the fBm
 * layer's, ratio-tracked with a stream of its own: the render seed's, at the "pixel" of a hash
 * of the point's bits (clouds_point_hash); 1 otherwise. */
ATMO_FN vec3 visibility_air_volume(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                   const medium_point *q)
{
#ifdef ATMO_CLOUDS_VOLUME
    rng_stream g = rng_stream_stage(s->seed, clouds_point_hash(q->p, s->clouds.seed), 0u, 0u);
    return clouds_sun_ratio(s, clouds_majorant, q, &g);
#else
    (void)s, (void)q;
    return v3(1.0f, 1.0f, 1.0f);
#endif
}

#ifdef ATMO_TERRAIN
/* The terrain's shadow at a point, 0 or 1, with the shortcuts of terrain.shafts (gpu_enums.h):
 * all of them on a ray with state vr, the stateless ones where vr is 0. */
ATMO_FN float visibility_terrain(ATMO_GLOBAL const atmo_gpu_scene *s,
                                 ATMO_GLOBAL const float *heightmap, const medium_point *q,
                                 visibility_ray *vr)
{
    return terrain_shafts_visibility(s, heightmap, q, vr ? vr->t : 0.0f, vr ? &vr->terrain : 0);
}
#endif

/* 1 where the planet leaves the sun visible from the point, 0 in its shadow. */
ATMO_FN float visibility_planet(ATMO_GLOBAL const atmo_gpu_atmosphere *a, const medium_point *q)
{
    return geometry_ray_hits_ground(q->r, q->mu_s, a->bottom_radius) ? 0.0f : 1.0f;
}

/* visibility_sun_occluders at a sample of a ray with state vr (0: none). */
ATMO_FN float visibility_sun_occluders_on_ray(ATMO_GLOBAL const atmo_gpu_scene *s,
                                              ATMO_LUT_PARAMS, const medium_point *q,
                                              visibility_ray *vr)
{
    float v = visibility_planet(&s->atmosphere, q);
#ifdef ATMO_CLOUD
    if (observer_blocks(s->cloud.observer, q->p, v3_from4(s->sun_direction)))
        v = 0.0f;
#endif
#ifdef VISIBILITY_OBJECTS
    if (v > 0.0f && objects_occluded(objects, s->path.object_count, q->p,
                                     v3_from4(s->sun_direction), 0.0f, INFINITY))
        v = 0.0f;
#endif
#ifdef ATMO_TERRAIN
    if (v > 0.0f)
        v *= visibility_terrain(s, heightmap, q, vr);
#else
    (void)vr;
#endif
    return v;
}

ATMO_FN float visibility_sun_occluders(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                       const medium_point *q)
{
    return visibility_sun_occluders_on_ray(s, ATMO_LUT_ARGS, q, 0);
}

#ifdef ATMO_CLOUDS
/* The density integral toward the sun from q through the fBm layer: the sun shadow map's under
 * -DATMO_CLOUDS_SHADOW_MAP (cloud_shadow_map.h; the light march where the map does not reach),
 * else the light march (cloud_layer.h). */
ATMO_FN float visibility_clouds_density(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                        const medium_point *q)
{
#ifdef ATMO_CLOUDS_SHADOW_MAP
    return clouds_shadow_map_density(s, clouds_shadow_map, q);
#else
    return clouds_sun_density(s, q, clouds_point_jitter(q->p, s->clouds.seed));
#endif
}

/* The sun's transmittance through the fBm layer to q, exp(-extinction D). */
ATMO_FN vec3 visibility_clouds_transmittance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                             const medium_point *q)
{
    float D = visibility_clouds_density(s, ATMO_LUT_ARGS, q);
    return v3_exp(v3_scale(v3_from4(s->clouds.extinction), -D));
}
#endif

/* v, the opaque sources' visibility of the sun from q, times the transmittance toward the sun of
 * the shadowing media (per wavelength). */
ATMO_FN vec3 visibility_media_sun(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                  const medium_point *q, float v)
{
    vec3 vis = v3(v, v, v);
#ifdef ATMO_CLOUD
    if (v > 0.0f)
        vis = v3_scale(cloud_shell_sun_transmittance(s, q, s->atmosphere.bottom_radius), v);
#endif
#ifdef ATMO_CLOUDS
    if (v > 0.0f)
        vis = v3_mul(vis, visibility_clouds_transmittance(s, ATMO_LUT_ARGS, q));
#endif
    return vis;
}

/* visibility_sun at a sample of a ray with state vr (0: none). */
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

#ifdef ATMO_PATH
/* The path tracer's sun visibility at a surface point: visibility_sun without the terrain, whose
 * shadow the path tracer traces itself toward the point it samples on the sun's disc
 * (render/surfaces.h), so the terrain's shadows get the disc's penumbra (the objects are no
 * source under ATMO_PATH). */
ATMO_FN vec3 visibility_sun_surface(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                    const medium_point *q)
{
    float v = visibility_planet(&s->atmosphere, q);
#ifdef ATMO_CLOUD
    if (observer_blocks(s->cloud.observer, q->p, v3_from4(s->sun_direction)))
        v = 0.0f;
#endif
    return visibility_media_sun(s, ATMO_LUT_ARGS, q, v);
}
#endif

/* Distance along the ray to the first opaque surface other than the ground (the observer, the
 * preview's objects, the terrain), or -1 when there is none. */
ATMO_FN float visibility_surface_hit(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                     const medium_ray *m)
{
    float hit = -1.0f;
#ifdef ATMO_CLOUD
    hit = observer_hit(s->cloud.observer, m);
#endif
#ifdef VISIBILITY_OBJECTS
    float t_obj;
    if (objects_hit(objects, s->path.object_count, m->origin, m->dir, 0.0f,
                    hit >= 0.0f ? hit : INFINITY, &t_obj) >= 0)
        hit = t_obj;
#endif
#if defined(ATMO_TERRAIN) && !defined(ATMO_PATH)
    /* the terrain covers the ground sphere (its surface lies at or above sea level >= 0): a
     * hit is never beyond the ground's distance, computed as the integrator computes it */
    float t;
    if (terrain_trace(s, heightmap, m->origin, m->dir, 0.0f, hit >= 0.0f ? hit : INFINITY,
                      s->terrain.steps, &t, 0)) {
        ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
        if (geometry_ray_hits_ground(m->r, m->mu, a->bottom_radius))
            t = fminf(t, geometry_distance_to_bottom(m->r, m->mu, a->bottom_radius));
        hit = t;
    }
#endif
    return hit;
}

#ifdef VISIBILITY_OBJECTS
/* The preview's light from an object at distance t along the ray, or -1 in x when the surface
 * there is not an object: albedo / pi (E T_sun V max(0, n . s) + E_sky (1 + n . up) / 2), the
 * sun with binary shadows from the occluders (the point offset along the normal so it does not
 * shadow itself), the sky's irradiance E_sky that of the ground at the point's sun cosine from
 * the method's tables, weighted by the fraction of the sky a tilted surface sees (1 + n . up)/2
 * (an isotropic sky; zero for method single, which has no sky irradiance). */
ATMO_FN vec3 visibility_object_radiance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                        const medium_ray *m, float t)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    float t_obj;
    int k = objects_hit(objects, s->path.object_count, m->origin, m->dir, 0.0f, t * 1.0001f,
                        &t_obj);
    if (k < 0)
        return v3(-1.0f, 0.0f, 0.0f);
    ATMO_GLOBAL const atmo_gpu_object *ob = &objects[k];
    medium_point q = medium_ray_at(m, t_obj, a->bottom_radius);
    vec3 n = objects_normal(ob, q.p);
    if (v3_dot(n, m->dir) > 0.0f) /* seen from inside */
        n = v3_scale(n, -1.0f);
    q.p = v3_add(q.p, v3_scale(n, 1e-4f + 1e-6f * v3_length(q.p)));
    vec3 sun = v3_from4(s->sun_direction), up_q = v3_normalize(v3_add(v3_scale(m->up, m->r_c), q.p));
    float cos_sun = fmaxf(v3_dot(n, sun), 0.0f);
    vec3 e = v3(0.0f, 0.0f, 0.0f);
    if (cos_sun > 0.0f && visibility_sun_occluders(s, ATMO_LUT_ARGS, &q) > 0.0f)
        e = v3_scale(v3_mul(v3_from4(a->solar_irradiance),
                            atmosphere_transmittance_to_top(a, transmittance_lut,
                                                            s->transmittance_width,
                                                            s->transmittance_height, q.r,
                                                            q.mu_s)),
                     cos_sun);
    vec3 sky = medium_ms_ground_irradiance(s, ATMO_LUT_ARGS, q.mu_s);
    e = v3_add(e, v3_scale(sky, 0.5f * (1.0f + v3_dot(n, up_q))));
    return v3_add(v3_scale(v3_mul(v3_from4(ob->albedo), e), 1.0f / ATMO_PI),
                  v3_from4(ob->emission));
}
#endif

/* Radiance leaving that surface toward the ray's origin, at distance t along the ray (without
 * the air in between). The observer is small, so it is lit like the camera's surroundings:
 * sunlight with the atmosphere's and the shell's transmittance at the ray's origin (its own
 * shadow test would block it). The terrain's light is terrain_radiance (terrain_shade.h). */
ATMO_FN vec3 visibility_surface_radiance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                         const medium_ray *m, float t)
{
#ifdef VISIBILITY_OBJECTS
    vec3 lit = visibility_object_radiance(s, ATMO_LUT_ARGS, m, t);
    if (lit.x >= 0.0f)
        return lit;
#endif
#if defined(ATMO_TERRAIN) && !defined(ATMO_PATH)
#ifdef ATMO_CLOUD
    float t_observer = observer_hit(s->cloud.observer, m);
    if (!(t_observer >= 0.0f && t_observer <= t))
#endif
        return terrain_radiance(s, ATMO_LUT_ARGS, m, t);
#endif
#ifdef ATMO_CLOUD
    ATMO_GLOBAL const float4 *transmittance = transmittance_lut;
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
