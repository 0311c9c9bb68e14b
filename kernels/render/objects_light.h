/* objects_light.h — the preview's objects (objects.h) as surfaces of the plan's composition
 * (visibility.h; not in path mode, whose surfaces.h traces them itself): their light toward
 * the view ray, lit by the sun with the composed occluders' shadows and by the method's sky
 * irradiance (medium_ms_ground_irradiance), so it comes after the composition of the sun. */
#ifndef ATMO_RENDER_OBJECTS_LIGHT_H
#define ATMO_RENDER_OBJECTS_LIGHT_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "atmosphere/sky_method.h"
#include "media/ray.h"
#include "render/objects.h"
#include "media/visibility.h"
#include "atmo/gpu_types.h"
#endif

/* The preview's light from an object at distance t along the ray, or -1 in x when the surface
 * there is not an object: albedo / pi (E T_sun V max(0, n . s) + E_sky (1 + n . up) / 2), the
 * sun with binary shadows from the occluders (the point offset along the normal so it does not
 * shadow itself) times the shadowing media's transmittance at a surface
 * (visibility_sun_surface_all: a cloud shell or layer, per wavelength), the sky's irradiance
 * E_sky that of the ground at the point's sun cosine from the method's tables, weighted by the
 * fraction of the sky a tilted surface sees (1 + n . up)/2 (an isotropic sky; zero for method
 * single, which has no sky irradiance). */
ATMO_FN vec3 objects_light_radiance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
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
    if (cos_sun > 0.0f)
        e = v3_scale(v3_mul(v3_mul(v3_from4(a->solar_irradiance),
                                   atmosphere_transmittance_to_top(a, transmittance_lut,
                                                                   s->transmittance_width,
                                                                   s->transmittance_height, q.r,
                                                                   q.mu_s)),
                            visibility_sun_surface_all(s, ATMO_LUT_ARGS, &q)),
                     cos_sun);
    vec3 sky = medium_ms_ground_irradiance(s, ATMO_LUT_ARGS, q.mu_s);
    e = v3_add(e, v3_scale(sky, 0.5f * (1.0f + v3_dot(n, up_q))));
    return v3_add(v3_scale(v3_mul(v3_from4(ob->albedo), e), 1.0f / ATMO_PI),
                  v3_from4(ob->emission));
}

#endif
