/* surfaces.h — the path tracer's surfaces: the first opaque surface along a ray and what the
 * shading needs of it (the hit record), composed from the surface sources the plan includes.
 *
 * Sources: the planet's ground sphere (path.ground = 1; radius R around the planet centre,
 * which lies at -r_c up from the camera), its distance in the (r, mu) form of geometry.h that
 * keeps its precision at planet scale, its albedo the atmosphere's ground albedo (the one the
 * methods' multiple-scattering tables assume); under -DATMO_OBJECTS the scene's spheres and
 * boxes (render/objects.h). Terrain adds its heightmap here: the nearer of terrain_intersect's
 * distance and the others', with terrain_material's albedo, as one more source of
 * surfaces_hit and surfaces_occluded.
 * The hit record: distance t along the ray, the outward unit normal, albedo (Lambertian, BRDF
 * albedo / pi), emitted radiance, and the material kind (SURFACES_*).
 * surfaces_occluded: whether an object blocks a shadow ray (the planet's shadow is the
 * visibility's, media/visibility.h, asked at the point).
 * surfaces_offset: a new ray's origin is moved off the surface along the normal by
 * 1e-4 m + 1e-6 |p|, above the float spacing of camera-relative positions |p| ulp ~ 6e-8 |p|
 * and far below the size of any object of interest. */
#ifndef ATMO_RENDER_SURFACES_H
#define ATMO_RENDER_SURFACES_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/geometry.h"
#include "media/ray.h"
#include "render/objects.h"
#include "atmo/gpu_types.h"
#endif

enum { SURFACES_NONE = 0, SURFACES_GROUND = 1, SURFACES_OBJECT = 2 };

typedef struct path_hit {
    float t;
    vec3 normal;   /* outward, unit */
    vec3 albedo;
    vec3 emission;
    int kind;      /* SURFACES_* */
} path_hit;

ATMO_FN vec3 surfaces_offset(vec3 p, vec3 n)
{
    return v3_add(p, v3_scale(n, 1e-4f + 1e-6f * v3_length(p)));
}

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
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    if (s->path.ground && geometry_ray_hits_ground(m->r, m->mu, a->bottom_radius)) {
        float t = geometry_distance_to_bottom(m->r, m->mu, a->bottom_radius);
        if (t < h.t) {
            h.t = t;
            h.kind = SURFACES_GROUND;
            vec3 p = v3_add(m->origin, v3_scale(m->dir, t));
            h.normal = v3_normalize(v3_add(v3_scale(m->up, m->r_c), p));
            h.albedo = v3_from4(a->ground_albedo);
        }
    }
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
    }
#endif
    return h;
}

/* 1 when an object blocks the ray from o along d (the shadow ray toward the sun). */
ATMO_FN int surfaces_occluded(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, vec3 o,
                              vec3 d)
{
#ifdef ATMO_OBJECTS
    return objects_occluded(objects, s->path.object_count, o, d, 0.0f, INFINITY);
#else
    return 0;
#endif
}

#endif
