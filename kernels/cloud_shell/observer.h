/* observer.h — the observer sphere: a visibility source (it shadows the sun) and a surface the
 * view ray can meet (compiled under -DATMO_CLOUD with the cloud shell, plan_cloud.c).
 *
 * The sphere has centre s->cloud.observer.xyz, camera-relative in the world's axes (m), and radius
 * s->cloud.observer.w (0: none). A point p is in its shadow when the half-line p + t sun, t >= 0,
 * meets the sphere: with oc = p - c, b = oc . sun, c' = |oc|^2 - R^2, when c' <= 0 (inside) or
 * b < 0 and b^2 >= c'. A view ray that meets it ends there, on a Lambertian surface of albedo
 * OBSERVER_ALBEDO lit by the sun only (a dark silhouette: the Brocken spectre's figure). A
 * sphere around the camera is the photographer: it casts its shadow but is not seen. */
#ifndef ATMO_CLOUD_SHELL_OBSERVER_H
#define ATMO_CLOUD_SHELL_OBSERVER_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/geometry.h"
#include "media/ray.h"
#include "atmo/gpu_types.h"
#endif

#define OBSERVER_ALBEDO 0.1f

/* 1 when the half-line from p toward the sun meets the sphere o (centre xyz, radius w). */
ATMO_FN int observer_blocks(float4 o, vec3 p, vec3 sun)
{
    if (o.w <= 0.0f)
        return 0;
    vec3 oc = v3_sub(p, v3(o.x, o.y, o.z));
    float b = v3_dot(oc, sun), c = v3_dot(oc, oc) - o.w * o.w;
    return c <= 0.0f || (b < 0.0f && b * b - c >= 0.0f);
}

/* Distance along the ray to the sphere, or -1 (also -1 from inside it). */
ATMO_FN float observer_hit(float4 o, const medium_ray *m)
{
    float t0, t1;
    if (o.w <= 0.0f)
        return -1.0f;
    vec3 oc = v3_sub(m->origin, v3(o.x, o.y, o.z));
    if (!geometry_sphere_roots(v3_dot(oc, m->dir), v3_dot(oc, oc) - o.w * o.w, &t0, &t1) ||
        t0 <= 0.0f)
        return -1.0f;
    return t0;
}

/* Radiance of the sphere's surface at distance t along the ray, lit by the sunlight `sun_e`
 * (irradiance on a surface facing the sun, W m^-2 nm^-1). */
ATMO_FN vec3 observer_radiance(float4 o, const medium_ray *m, float t, vec3 sun_e)
{
    vec3 p = v3_add(m->origin, v3_scale(m->dir, t));
    vec3 normal = v3_normalize(v3_sub(p, v3(o.x, o.y, o.z)));
    float cos_i = fmaxf(v3_dot(normal, m->sun), 0.0f);
    return v3_scale(sun_e, OBSERVER_ALBEDO * cos_i / ATMO_PI);
}

#endif
