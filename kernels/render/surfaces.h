/* surfaces.h — the path tracer's surfaces: the first opaque surface along a ray and what the
 * shading needs of it (the hit record, render/path_hit.h), and whether a shadow ray is blocked;
 * the path tracer's stages (render/path.h) and the denoiser's guides (render/guides.cl) ask it.
 *
 * Sources: the planet's ground sphere (radius R around the planet centre, which lies at -r_c up
 * from the camera), its distance in the (r, mu) form of geometry.h that keeps its precision at
 * planet scale, its albedo the atmosphere's ground albedo (the one the methods'
 * multiple-scattering tables assume); then the features' surfaces, in the plan's composition
 * (plan/path_surfaces: surfaces_features_hit over the slots `path_hit`, the terrain's and the
 * objects'), each replacing the record with a nearer hit, so the nearest wins. The ground is a
 * surface where the GPU's path.ground is set (the scene's path.ground in path mode; always in
 * the preview, whose methods all have it) and no feature's surface replaces it
 * (SURFACES_GROUND_SPHERE: the terrain's does, terrain/terrain_path.h says why).
 * surfaces_occluded: whether a feature's surface blocks the shadow ray toward the point of the
 * sun's disc that light_sun.h sampled (surfaces_features_occluded over the slots
 * `path_occluded`), so they cast shadows with the disc's penumbra; the planet's shadow and the
 * shadowing media are the visibility's (media/visibility.h, visibility_sun_surface), asked at
 * the point.
 * Cones: the guides trace a pixel's rays, which differ by a fraction of a pixel, and a marched
 * surface (the terrain's sphere tracing) would walk each of them the same way to its hit.
 * surfaces_cone_start gives, for a cone of rays (an axis and a chord `spread`), the least over
 * the marched surfaces' slots `cone_start` of a distance before which no ray of the cone meets
 * that surface; surfaces_hit_from hands it to every slot in the record's march_from, and the
 * marched surfaces start there (the analytic ones, the ground sphere and the objects, ignore
 * it: they cost no march). 0 where no surface marches (SURFACES_MARCHED, composed: how many
 * do, so a caller skips the cone where none does). Units: metres. */
#ifndef ATMO_RENDER_SURFACES_H
#define ATMO_RENDER_SURFACES_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/geometry.h"
#include "media/ray.h"
#include "render/path_hit.h"
#include "atmo/gpu_types.h"
#endif

/* The first surface along the ray m before t_max, the marched surfaces looked for from
 * march_from on (0, or surfaces_cone_start's bound for a cone that holds m); kind
 * SURFACES_NONE when there is none. */
ATMO_FN path_hit surfaces_hit_from(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                   const medium_ray *m, float march_from, float t_max)
{
    path_hit h = path_hit_none(t_max);
    h.march_from = march_from;
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    if ((SURFACES_GROUND_SPHERE & s->path.ground) &&
        geometry_ray_hits_ground(m->r, m->mu, a->bottom_radius)) {
        float t = geometry_distance_to_bottom(m->r, m->mu, a->bottom_radius);
        if (t < h.t) {
            h.t = t;
            h.kind = SURFACES_GROUND;
            vec3 p = v3_add(m->origin, v3_scale(m->dir, t));
            h.normal = v3_normalize(v3_add(v3_scale(m->up, m->r_c), p));
            h.albedo = v3_from4(a->ground_albedo);
            h.lift = surfaces_lift(p);
        }
    }
    surfaces_features_hit(s, ATMO_LUT_ARGS, m, &h);
    return h;
}

/* The first surface along the ray m before t_max; kind SURFACES_NONE when there is none. */
ATMO_FN path_hit surfaces_hit(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                              const medium_ray *m, float t_max)
{
    return surfaces_hit_from(s, ATMO_LUT_ARGS, m, 0.0f, t_max);
}

/* The distance before which no ray from m's origin within the chord `spread` of its direction
 * meets a marched surface (see the top of the file); 0 where none marches. */
ATMO_FN float surfaces_cone_start(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                  const medium_ray *m, float spread)
{
    return surfaces_features_cone_start(s, ATMO_LUT_ARGS, m, spread);
}

/* 1 when a feature's surface blocks the shadow ray from o along d (the shadow ray toward the
 * sun). */
ATMO_FN int surfaces_occluded(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, vec3 o,
                              vec3 d)
{
    return surfaces_features_occluded(s, ATMO_LUT_ARGS, o, d);
}

#endif
