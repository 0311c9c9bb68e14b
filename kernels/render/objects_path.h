/* objects_path.h — the scene's spheres and boxes (render/objects.h) as surfaces of the path
 * tracer and its guides (the slots `path_hit` and `path_occluded`, composed by the plan into
 * render/surfaces.h's queries): the nearest object before the record's distance with its
 * outward normal, albedo and emission, its new rays lifted by surfaces_lift; and whether an
 * object lies on a shadow ray, so objects cast shadows with the sun disc's penumbra.
 * Units: metres; emission in W m^-2 sr^-1 nm^-1. */
#ifndef ATMO_RENDER_OBJECTS_PATH_H
#define ATMO_RENDER_OBJECTS_PATH_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "media/ray.h"
#include "render/path_hit.h"
#include "render/objects.h"
#include "atmo/gpu_types.h"
#endif

/* The nearest object along m where it is nearer than the record's. */
ATMO_FN void objects_path_hit(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                              const medium_ray *m, path_hit *h)
{
    float t;
    int k = objects_hit(objects, s->path.object_count, m->origin, m->dir, 0.0f, h->t, &t);
    if (k < 0)
        return;
    ATMO_GLOBAL const atmo_gpu_object *ob = &objects[k];
    vec3 p = v3_add(m->origin, v3_scale(m->dir, t));
    h->t = t;
    h->kind = SURFACES_OBJECT;
    h->normal = objects_normal(ob, p);
    h->albedo = v3_from4(ob->albedo);
    h->emission = v3_from4(ob->emission);
    h->lift = surfaces_lift(p);
}

/* 1 when an object lies on the shadow ray from o along d. */
ATMO_FN int objects_path_occluded(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, vec3 o,
                                  vec3 d)
{
    return objects_occluded(objects, s->path.object_count, o, d, 0.0f, INFINITY);
}

#endif
