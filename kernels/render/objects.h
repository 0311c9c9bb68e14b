/* objects.h — rays against the scene's objects: Lambertian spheres and axis-aligned boxes
 * (atmo_gpu_object, include/atmo/gpu_path.h), camera-relative, in the buffer `objects`.
 *
 * Sphere of centre c and radius R, ray o + t d (|d| = 1): with f = o - c, b = f . d and the
 * closest approach h = f - b d, the roots are t = -b -+ sqrt(R^2 - |h|^2). Forming the
 * discriminant from |h|^2 rather than |f|^2 - b^2 keeps it exact when the sphere is small and
 * far (|f|^2 ~ 1e6 m^2 would swallow R^2 ~ 0.01 m^2 in float; Haines et al., "Precision
 * improvements for ray/sphere intersection", Ray Tracing Gems, 2019, ch. 7).
 * Box [lo, hi]: the slab method (Kay and Kajiya 1986): t_near = max over axes of
 * min((lo - o)/d, (hi - o)/d), t_far = min of the max; a hit where t_near <= t_far. A ray from
 * inside an object hits its far side (the camera inside an emitting sphere: the furnace).
 * The outward normal: (p - c) / R for a sphere; for a box the axis along which the hit point
 * is farthest from the centre relative to the half size.
 * objects_hit gives the nearest hit in (t_min, t_max) and the object's index; objects_occluded
 * whether any object lies in (t_min, t_max) (shadow rays). The preview's surfaces and sun
 * shadows (objects_sun_visibility, objects_surface_hit and objects_light.h, in the plan's
 * composition of visibility.h) and the path tracer's (render/surfaces.h) call them. */
#ifndef ATMO_RENDER_OBJECTS_H
#define ATMO_RENDER_OBJECTS_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/sky_method.h"
#include "media/ray.h"
#include "atmo/gpu_types.h"
#endif

/* Nearest root of the sphere in (t_min, t_max), or -1. */
ATMO_FN float objects_sphere_t(vec3 c, float radius, vec3 o, vec3 d, float t_min, float t_max)
{
    vec3 f = v3_sub(o, c);
    float b = v3_dot(f, d);
    vec3 h = v3_sub(f, v3_scale(d, b));
    float disc = radius * radius - v3_dot(h, h);
    if (disc < 0.0f)
        return -1.0f;
    float q = sqrtf(disc);
    float t0 = -b - q, t1 = -b + q;
    if (t0 > t_min && t0 < t_max)
        return t0;
    if (t1 > t_min && t1 < t_max)
        return t1;
    return -1.0f;
}

ATMO_FN float objects_slab_lo(float lo, float hi, float o, float inv)
{
    return fminf((lo - o) * inv, (hi - o) * inv);
}
ATMO_FN float objects_slab_hi(float lo, float hi, float o, float inv)
{
    return fmaxf((lo - o) * inv, (hi - o) * inv);
}

/* Nearest crossing of the box's surface in (t_min, t_max), or -1. */
ATMO_FN float objects_box_t(vec3 lo, vec3 hi, vec3 o, vec3 d, float t_min, float t_max)
{
    vec3 inv = v3(1.0f / d.x, 1.0f / d.y, 1.0f / d.z);
    float tn = fmaxf(objects_slab_lo(lo.x, hi.x, o.x, inv.x),
                     fmaxf(objects_slab_lo(lo.y, hi.y, o.y, inv.y),
                           objects_slab_lo(lo.z, hi.z, o.z, inv.z)));
    float tf = fminf(objects_slab_hi(lo.x, hi.x, o.x, inv.x),
                     fminf(objects_slab_hi(lo.y, hi.y, o.y, inv.y),
                           objects_slab_hi(lo.z, hi.z, o.z, inv.z)));
    if (!(tn <= tf))
        return -1.0f;
    if (tn > t_min && tn < t_max)
        return tn;
    if (tf > t_min && tf < t_max)
        return tf;
    return -1.0f;
}

/* Distance to object k in (t_min, t_max), or -1. */
ATMO_FN float objects_t(ATMO_GLOBAL const atmo_gpu_object *ob, vec3 o, vec3 d, float t_min,
                        float t_max)
{
    if (ob->kind == ATMO_OBJECT_SPHERE)
        return objects_sphere_t(v3_from4(ob->a), ob->a.w, o, d, t_min, t_max);
    return objects_box_t(v3_from4(ob->a), v3_from4(ob->b), o, d, t_min, t_max);
}

/* Outward unit normal of the object at its surface point p. */
ATMO_FN vec3 objects_normal(ATMO_GLOBAL const atmo_gpu_object *ob, vec3 p)
{
    if (ob->kind == ATMO_OBJECT_SPHERE)
        return v3_normalize(v3_sub(p, v3_from4(ob->a)));
    vec3 lo = v3_from4(ob->a), hi = v3_from4(ob->b);
    vec3 c = v3_scale(v3_add(lo, hi), 0.5f), ext = v3_scale(v3_sub(hi, lo), 0.5f);
    vec3 q = v3_sub(p, c);
    float ax = fabsf(q.x) / ext.x, ay = fabsf(q.y) / ext.y, az = fabsf(q.z) / ext.z;
    if (ax >= ay && ax >= az)
        return v3(q.x >= 0.0f ? 1.0f : -1.0f, 0.0f, 0.0f);
    if (ay >= az)
        return v3(0.0f, q.y >= 0.0f ? 1.0f : -1.0f, 0.0f);
    return v3(0.0f, 0.0f, q.z >= 0.0f ? 1.0f : -1.0f);
}

/* The nearest object along o + t d in (t_min, t_max): its index, or -1; *t its distance. */
ATMO_FN int objects_hit(ATMO_GLOBAL const atmo_gpu_object *list, int count, vec3 o, vec3 d,
                        float t_min, float t_max, float *t)
{
    int best = -1;
    float t_best = t_max;
    for (int k = 0; k < count; k++) {
        float tk = objects_t(&list[k], o, d, t_min, t_best);
        if (tk >= 0.0f) {
            t_best = tk;
            best = k;
        }
    }
    *t = t_best;
    return best;
}

/* 1 when an object lies along o + t d in (t_min, t_max). */
ATMO_FN int objects_occluded(ATMO_GLOBAL const atmo_gpu_object *list, int count, vec3 o, vec3 d,
                             float t_min, float t_max)
{
    for (int k = 0; k < count; k++)
        if (objects_t(&list[k], o, d, t_min, t_max) >= 0.0f)
            return 1;
    return 0;
}

/* The objects as an occluder of the sun at q (a point sun: binary shadows), 1 or 0. */
ATMO_FN float objects_sun_visibility(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                     const medium_point *q)
{
    return objects_occluded(objects, s->path.object_count, q->p, v3_from4(s->sun_direction), 0.0f,
                            INFINITY)
               ? 0.0f
               : 1.0f;
}

/* The distance along the ray to the nearest object before t_max, or -1. */
ATMO_FN float objects_surface_hit(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                  const medium_ray *m, float t_max)
{
    float t;
    return objects_hit(objects, s->path.object_count, m->origin, m->dir, 0.0f, t_max, &t) >= 0
               ? t
               : -1.0f;
}

#endif
