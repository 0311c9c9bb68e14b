/* path_hit.h — the hit record of the path tracer's surfaces (render/surfaces.h): what a surface
 * source writes where its surface is the nearest so far along a ray, and what the shading needs
 * of it.
 *
 * A source (the ground sphere in surfaces.h; a feature's slot `path_hit`, composed by the plan:
 * the terrain's terrain/terrain_path.h, the objects' render/objects_path.h) is asked with the
 * record of the sources before it and replaces it only with a hit nearer than h.t, so the
 * nearest wins whatever their order. The record: distance t along the ray, the outward unit
 * normal, albedo (Lambertian, BRDF albedo / pi), emitted radiance, the material kind
 * (SURFACES_*) and the lift of new rays' origins off the surface along the normal (each source
 * says why its lift clears its own surface). Units: metres; radiance in W m^-2 sr^-1 nm^-1. */
#ifndef ATMO_RENDER_PATH_HIT_H
#define ATMO_RENDER_PATH_HIT_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
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
    float march_from; /* m: where the marched surfaces start looking (surfaces.h) */
} path_hit;

/* The lift of the ground's and the objects' new rays at the camera-relative point p:
 * 1e-4 m + 1e-6 |p|, above the float spacing of camera-relative positions |p| ulp ~ 6e-8 |p|
 * and far below the size of any object of interest. */
ATMO_FN float surfaces_lift(vec3 p) { return 1e-4f + 1e-6f * v3_length(p); }

/* The record of no surface before t_max. */
ATMO_FN path_hit path_hit_none(float t_max)
{
    path_hit h;
    h.t = t_max;
    h.kind = SURFACES_NONE;
    h.normal = v3(0.0f, 0.0f, 0.0f);
    h.albedo = v3(0.0f, 0.0f, 0.0f);
    h.emission = v3(0.0f, 0.0f, 0.0f);
    h.lift = 0.0f;
    h.march_from = 0.0f;
    return h;
}

#endif
