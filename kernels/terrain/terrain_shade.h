/* terrain_shade.h — the terrain's surface: procedural materials and the light it sends back.
 *
 * Materials: terrain_material.h.
 *
 * Light (Lambertian, BRDF albedo / pi): with E the solar irradiance, T_sun the atmosphere's
 * transmittance toward the sun at the point, V the visible fraction of the sun disc (the
 * terrain's soft shadow, terrain.h, times the planet's, times the other occluders' and the
 * shadowing media's, visibility_sun_surface: the preview's objects, an observer, a cloud
 * shell or layer, per wavelength), E_sky the method's sky irradiance on
 * level ground (medium_ms_ground_irradiance, the plan's composition before this file: zero for
 * method single, as its ground has) scaled
 * by the part of the sky a tilted surface sees, (1 + N . n) / 2,
 *     L = albedo / pi (E T_sun V max(N . s, 0) + E_sky (1 + N . n) / 2).
 * Water: the sky reflected with the Fresnel reflectance of the view angle, the sun glint
 * (water.h), and a dark water body of albedo (terrain_material.h) lit by what the surface
 * transmits:
 *     L = F L_sky + E T_sun V glint + (1 - F) albedo_w / pi (E T_sun V mu_s + E_sky),
 * with L_sky the method's sky along the mirror ray, which the render stage adds
 * (terrain/terrain_stage.h, -DATMO_TERRAIN_STAGE: every camera ray of single, march, fast and
 * lut); elsewhere (a ray of no stage) the sky is taken as uniform, L_sky = E_sky / pi.
 * The air between the camera and the surface is the integrator's (aerial perspective). */
#ifndef ATMO_TERRAIN_SHADE_H
#define ATMO_TERRAIN_SHADE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "atmosphere/sky_method.h"
#include "media/ray.h"
#include "terrain/noise.h"
#include "terrain/terrain.h"
#include "terrain/water.h"
#include "terrain/terrain_material.h"
#include "media/visibility.h"
#include "atmo/gpu_types.h"
#endif

#define TERRAIN_SHADOW_OFFSET_M 0.1f

/* The radiance the terrain sends back along the ray m from its point at distance t (without
 * the air in between; see the top of the file). */
ATMO_FN vec3 terrain_radiance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                              const medium_ray *m, float t)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    vec3 p = v3_add(m->origin, v3_scale(m->dir, t));
    float distance = v3_length(p);
    terrain_surface_point sp = terrain_material(s, heightmap, p, distance);
    vec3 sun = v3_from4(s->sun_direction);
    float mu_s = v3_dot(sp.vertical, sun);
    float r = a->bottom_radius + sp.altitude_m;
    vec3 sun_e = v3(0.0f, 0.0f, 0.0f);
    if (!geometry_ray_hits_ground(r, mu_s, a->bottom_radius)) {
        float lift = TERRAIN_SHADOW_OFFSET_M + 2.0f * s->terrain.tolerance * distance;
        vec3 lifted = v3_add(p, v3_scale(sp.normal, lift));
        float v = terrain_sun_visible(s, heightmap, lifted, 0.0f);
        vec3 to_sun = atmosphere_transmittance_to_top(a, transmittance_lut, s->transmittance_width,
                                                      s->transmittance_height, r, mu_s);
        sun_e = v3_scale(v3_mul(v3_from4(a->solar_irradiance), to_sun), v);
        if (v > 0.0f) { /* the other occluders and the shadowing media */
            medium_point q = medium_ray_at(m, t, a->bottom_radius);
            q.p = lifted;
            sun_e = v3_mul(sun_e, visibility_sun_surface(s, ATMO_LUT_ARGS, &q));
        }
    }
    vec3 sky_e = medium_ms_ground_irradiance(s, ATMO_LUT_ARGS, mu_s);
    vec3 view = v3_scale(m->dir, -1.0f);
    if (sp.weight[TERRAIN_WATER] > 0.0f) {
        float f = water_fresnel(v3_dot(view, sp.vertical), WATER_INDEX);
        vec3 body = v3_add(v3_scale(sun_e, fmaxf(mu_s, 0.0f)), sky_e);
#ifdef ATMO_TERRAIN_STAGE
        vec3 L = v3_scale(sun_e, water_glint(sp.vertical, view, sun));
#else
        vec3 L = v3_add(v3_scale(sky_e, f / ATMO_PI),
                        v3_scale(sun_e, water_glint(sp.vertical, view, sun)));
#endif
        return v3_add(L, v3_mul(v3_scale(body, (1.0f - f) / ATMO_PI), sp.albedo));
    }
    float cos_i = fmaxf(v3_dot(sp.normal, sun), 0.0f);
    vec3 e = v3_add(v3_scale(sun_e, cos_i),
                    v3_scale(sky_e, 0.5f * (1.0f + v3_dot(sp.normal, sp.vertical))));
    return v3_scale(v3_mul(sp.albedo, e), 1.0f / ATMO_PI);
}

/* The terrain as a surface of the plan's composition (visibility.h; not in path mode, whose
 * surfaces.h traces it itself): the distance along the ray to its surface before t_max, or -1.
 * It covers the ground sphere (its surface lies at or above sea level >= 0), so a hit is never
 * beyond the ground's distance, computed as the integrator computes it. Its light is
 * terrain_radiance. */
ATMO_FN float terrain_surface_hit(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                  const medium_ray *m, float t_max)
{
    float t;
    if (!terrain_trace(s, heightmap, m->origin, m->dir, 0.0f, t_max, s->terrain.steps, &t, 0))
        return -1.0f;
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    if (geometry_ray_hits_ground(m->r, m->mu, a->bottom_radius))
        t = fminf(t, geometry_distance_to_bottom(m->r, m->mu, a->bottom_radius));
    return t;
}

#endif
