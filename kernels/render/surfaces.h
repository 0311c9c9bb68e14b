/* surfaces.h — the path tracer's surfaces: the first opaque surface along a ray and what the
 * shading needs of it (the hit record), composed from the surface sources the plan includes.
 *
 * Sources: the planet's ground sphere (path.ground = 1; radius R around the planet centre,
 * which lies at -r_c up from the camera), its distance in the (r, mu) form of geometry.h that
 * keeps its precision at planet scale, its albedo the atmosphere's ground albedo (the one the
 * methods' multiple-scattering tables assume); under -DATMO_TERRAIN the terrain
 * (kernels/terrain/): terrain_intersect's sphere-traced hit and normal, terrain_material's
 * albedo (grass, dirt, rock, snow by altitude and slope); where the height is at or below sea
 * level the hit is the sea (SURFACES_WATER: the vertical for its normal, the water body's dark
 * albedo, shaded by render/bsdf_water.h); under -DATMO_OBJECTS the scene's spheres and boxes
 * (render/objects.h). The nearest wins. The terrain replaces the ground sphere: its surface
 * lies at or above sea level everywhere and its tracer ends every ray that reaches sea level
 * (terrain.h), so the ground would add nothing but, on the sea, where the two coincide, a
 * second surface whose float distance (the (r, mu) form's) and the tracer's differ by more
 * than the tracer's tolerance, taking pixels from the sea at random.
 * The hit record: distance t along the ray, the outward unit normal, albedo (Lambertian, BRDF
 * albedo / pi), emitted radiance, the material kind (SURFACES_*) and the lift of new rays'
 * origins off the surface along the normal:
 *   ground and objects: 1e-4 m + 1e-6 |p|, above the float spacing of camera-relative positions
 *   |p| ulp ~ 6e-8 |p| and far below the size of any object of interest;
 *   terrain: TERRAIN_SHADOW_OFFSET_M + 2 tau t (tau = terrain.tolerance, t the distance along
 *   the ray that found the hit) + 1e-6 |p|: a terrain hit lies up to the tracer's tolerance
 *   eps(t) = 0.01 m + tau t above the surface, and a new ray's march counts a point closer than
 *   eps(0) = 0.01 m to it as a hit, so the lift clears both (the lift terrain_shade.h gives its
 *   own shadow rays).
 * surfaces_occluded: whether an object or the terrain blocks the shadow ray toward the point of
 * the sun's disc that light_sun.h sampled (the terrain within terrain.shadow_far_m, with
 * terrain.shadow_steps sphere-tracing steps; none with terrain.shadow = none), so both cast
 * shadows with the disc's penumbra; the planet's shadow and the shadowing media are the
 * visibility's (media/visibility.h, visibility_sun_surface), asked at the point. */
#ifndef ATMO_RENDER_SURFACES_H
#define ATMO_RENDER_SURFACES_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/geometry.h"
#include "media/ray.h"
#include "render/objects.h"
#ifdef ATMO_TERRAIN
#include "terrain/terrain.h"
#include "terrain/terrain_material.h"
#include "terrain/terrain_shade.h"
#endif
#include "atmo/gpu_types.h"
#endif

enum {
    SURFACES_NONE = 0,
    SURFACES_GROUND = 1,
    SURFACES_OBJECT = 2,
    SURFACES_TERRAIN = 3,
    SURFACES_WATER = 4
};

typedef struct path_hit {
    float t;
    vec3 normal;   /* outward, unit */
    vec3 albedo;
    vec3 emission;
    int kind;      /* SURFACES_* */
    float lift;    /* m: new rays start this far off the surface along the normal */
} path_hit;

/* The lift of the ground's and the objects' new rays at the camera-relative point p. */
ATMO_FN float surfaces_lift(vec3 p) { return 1e-4f + 1e-6f * v3_length(p); }

/* The first surface along the ray m before t_max; kind SURFACES_NONE when there is none. */
ATMO_FN path_hit surfaces_hit(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                              const medium_ray *m, float t_max)
{
    path_hit h;
    h.t = t_max;
    h.kind = SURFACES_NONE;
    h.normal = v3(0.0f, 0.0f, 0.0f);
    h.albedo = v3(0.0f, 0.0f, 0.0f);
    h.emission = v3(0.0f, 0.0f, 0.0f);
    h.lift = 0.0f;
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
#ifdef ATMO_TERRAIN
    int ground = 0;
#else
    int ground = s->path.ground;
#endif
    if (ground && geometry_ray_hits_ground(m->r, m->mu, a->bottom_radius)) {
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
#ifdef ATMO_TERRAIN
    float t_ter;
    vec3 n_ter;
    if (terrain_intersect(s, heightmap, m->origin, m->dir, h.t, &t_ter, &n_ter) && t_ter < h.t) {
        vec3 p = v3_add(m->origin, v3_scale(m->dir, t_ter));
        float distance = v3_length(p);
        terrain_surface_point sp = terrain_material(s, heightmap, p, distance);
        int water = sp.weight[TERRAIN_WATER] > 0.0f;
        h.t = t_ter;
        h.kind = water ? SURFACES_WATER : SURFACES_TERRAIN;
        h.normal = water ? sp.vertical : n_ter;
        h.albedo = sp.albedo;
        h.lift = TERRAIN_SHADOW_OFFSET_M + 2.0f * s->terrain.tolerance * t_ter + 1e-6f * distance;
    }
#endif
#ifdef ATMO_OBJECTS
    float t_obj;
    int k = objects_hit(objects, s->path.object_count, m->origin, m->dir, 0.0f, h.t, &t_obj);
    if (k >= 0) {
        ATMO_GLOBAL const atmo_gpu_object *ob = &objects[k];
        h.t = t_obj;
        h.kind = SURFACES_OBJECT;
        h.normal = objects_normal(ob, v3_add(m->origin, v3_scale(m->dir, t_obj)));
        h.albedo = v3_from4(ob->albedo);
        h.emission = v3_from4(ob->emission);
        h.lift = surfaces_lift(v3_add(m->origin, v3_scale(m->dir, t_obj)));
    }
#endif
    return h;
}

/* 1 when an object or the terrain blocks the ray from o along d (the shadow ray toward the
 * sun). */
ATMO_FN int surfaces_occluded(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, vec3 o,
                              vec3 d)
{
#ifdef ATMO_OBJECTS
    if (objects_occluded(objects, s->path.object_count, o, d, 0.0f, INFINITY))
        return 1;
#endif
#ifdef ATMO_TERRAIN
    ATMO_GLOBAL const atmo_gpu_terrain *tr = &s->terrain;
    float t;
    if (tr->shadow != ATMO_TERRAIN_SHADOW_NONE &&
        terrain_trace(s, heightmap, o, d, 0.0f, tr->shadow_far_m, tr->shadow_steps, &t, 0))
        return 1;
#endif
    return 0;
}

#endif
