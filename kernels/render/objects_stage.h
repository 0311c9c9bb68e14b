/* objects_stage.h — the preview's objects in front of the camera (the slot `camera_stage`,
 * composed by the plan into render/sky.cl's render_camera_trace, before the terrain's stage):
 * a camera ray whose first surface is an object (render/objects.h, nearer than the ground
 * sphere) gets the air in front from the method's sky_trace, stopped OBJECTS_STAGE_SHORTEN of
 * the distance short of the object so a method that ends its own segments at surfaces (single,
 * march) does not count it twice, plus the object's light (objects_light.h, through the
 * composition's visibility_surface_radiance) times the view transmittance; no sun disc. Other
 * rays go on to the next stage. Units: metres; radiance in W m^-2 sr^-1 nm^-1. */
#ifndef ATMO_RENDER_OBJECTS_STAGE_H
#define ATMO_RENDER_OBJECTS_STAGE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/geometry.h"
#include "common/rng.h"
#include "atmosphere/sky_method.h"
#include "media/ray.h"
#include "media/visibility.h"
#include "render/objects.h"
#include "atmo/gpu_types.h"
#endif

#define OBJECTS_STAGE_SHORTEN 0.99999f

/* The distance to the object a camera ray sees before the ground, or -1. */
ATMO_FN float objects_stage_distance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                     const medium_ray *ray)
{
    float t = objects_surface_hit(s, ATMO_LUT_ARGS, ray, INFINITY);
    if (t < 0.0f)
        return -1.0f;
    float R = s->atmosphere.bottom_radius;
    if (geometry_ray_hits_ground(ray->r, ray->mu, R) &&
        geometry_distance_to_bottom(ray->r, ray->mu, R) < t)
        return -1.0f;
    return t;
}

/* The camera ray that sees an object (see the top of the file): 1 with its light, else 0. */
ATMO_FN int objects_stage_trace(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                const medium_ray *ray, rng_stream *g, vec3 *sky, vec3 *sun,
                                vec3 *view_t)
{
    float t = objects_stage_distance(s, ATMO_LUT_ARGS, ray);
    if (t <= 0.0f)
        return 0;
    sky_trace(s, ATMO_LUT_ARGS, ray, t * OBJECTS_STAGE_SHORTEN, g, sky, sun, view_t);
    *sky = v3_add(*sky, v3_mul(*view_t, visibility_surface_radiance(s, ATMO_LUT_ARGS, ray, t)));
    *sun = v3(0.0f, 0.0f, 0.0f);
    return 1;
}

#endif
