/* terrain_path.h — the terrain as a surface of the path tracer and its guides (the slots
 * `path_hit` and `path_occluded`, composed by the plan into render/surfaces.h's queries).
 *
 * Hit: terrain_intersect's sphere-traced hit and normal before the record's distance (from
 * its march_from: the guides' cone start, terrain_path_cone_start below, else 0),
 * terrain_material's albedo (grass, dirt, rock, snow by altitude and slope); where the height
 * is at or below sea level the hit is the sea (SURFACES_WATER: the vertical for its normal, the
 * water body's dark albedo, shaded by render/bsdf_water.h). Lift: TERRAIN_SHADOW_OFFSET_M +
 * 2 tau t (tau = terrain.tolerance, t the distance along the ray that found the hit) +
 * 1e-6 |p|: a terrain hit lies up to the tracer's tolerance eps(t) = 0.01 m + tau t above the
 * surface, and a new ray's march counts a point closer than eps(0) = 0.01 m to it as a hit, so
 * the lift clears both (the lift terrain_shade.h gives its own shadow rays).
 * The terrain replaces the ground sphere (the slot `path_replaces_ground`): its surface lies at
 * or above sea level everywhere and its tracer ends every ray that reaches sea level
 * (terrain.h), so the ground would add nothing but, on the sea, where the two coincide, a
 * second surface whose float distance (the (r, mu) form's) and the tracer's differ by more
 * than the tracer's tolerance, taking pixels from the sea at random.
 * Occlusion: whether the terrain blocks the shadow ray from o along d within
 * terrain.shadow_far_m, in terrain.shadow_steps sphere-tracing steps (never with
 * terrain.shadow = none). Units: metres. */
#ifndef ATMO_TERRAIN_TERRAIN_PATH_H
#define ATMO_TERRAIN_TERRAIN_PATH_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "media/ray.h"
#include "render/path_hit.h"
#include "terrain/terrain.h"
#include "terrain/terrain_material.h"
#include "terrain/terrain_shade.h"
#include "atmo/gpu_types.h"
#endif

/* The terrain's hit along m where it is nearer than the record's (see the top of the file). */
ATMO_FN void terrain_path_hit(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                              const medium_ray *m, path_hit *h)
{
    float t;
    vec3 n;
    if (!terrain_intersect(s, heightmap, m->origin, m->dir, h->march_from, h->t, &t, &n) ||
        !(t < h->t))
        return;
    vec3 p = v3_add(m->origin, v3_scale(m->dir, t));
    float distance = v3_length(p);
    terrain_surface_point sp = terrain_material(s, heightmap, p, distance);
    int water = sp.weight[TERRAIN_WATER] > 0.0f;
    h->t = t;
    h->kind = water ? SURFACES_WATER : SURFACES_TERRAIN;
    h->normal = water ? sp.vertical : n;
    h->albedo = sp.albedo;
    h->lift = TERRAIN_SHADOW_OFFSET_M + 2.0f * s->terrain.tolerance * t + 1e-6f * distance;
}

/* Where the rays from m's origin within the chord `spread` of its direction may first meet the
 * terrain (terrain.h's terrain_cone_start, in the tracer's step budget): the guides' rays of
 * one pixel start their march there. */
ATMO_FN float terrain_path_cone_start(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                      const medium_ray *m, float spread)
{
    return terrain_cone_start(s, heightmap, m->origin, m->dir, spread, s->terrain.steps);
}

/* 1 when the terrain blocks the shadow ray from o along d (see the top of the file). */
ATMO_FN int terrain_path_occluded(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, vec3 o,
                                  vec3 d)
{
    ATMO_GLOBAL const atmo_gpu_terrain *tr = &s->terrain;
    float t;
    return tr->shadow != ATMO_TERRAIN_SHADOW_NONE &&
           terrain_trace(s, heightmap, o, d, 0.0f, tr->shadow_far_m, tr->shadow_steps, &t, 0);
}

#endif
