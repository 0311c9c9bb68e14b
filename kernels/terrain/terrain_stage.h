/* terrain_stage.h — the terrain in front of the camera: what the medium integrator's own
 * surface term cannot give.
 *
 * Tables (terrain_stage_trace_tables, the camera stage of methods fast and lut, which read
 * whole rays from tables
 * that know no terrain: fast's sky-view LUT, lut's scattering tables): a camera ray that meets
 * the terrain (terrain.h's tracer) is integrated by the medium integrator with the method's
 * multiple-scattering source (use_ms = 1: Psi_ms for fast, the stored density J for lut), as
 * each method's sky_trace does for a finite segment; the integrator ends the segment at the
 * surface (visibility_surface_hit) and adds T L_surface, the terrain's light (terrain_shade.h),
 * so the air in front is the aerial perspective of the same method. Methods single and march
 * integrate the terrain in their own sky_trace (terrain_stage_trace, their camera stage, adds
 * the water's mirror alone). Every ray that meets no terrain goes to the method's sky_trace
 * over its whole length. The plan composes the stage into the preview's camera rays
 * (render/sky.cl's render_camera_trace: the slot `camera_stage`).
 *
 * The water's mirror (every method): where the ray ends on water, the sky it reflects is the
 * method's own sky along the mirror ray, r = d - 2 (d . n) n with n the vertical, traced by
 * sky_trace from the water (lifted off it by terrain_shade.h's shadow offset) over its whole
 * length, with the Fresnel reflectance of the view angle (water.h):
 *     L += T(camera, water) F(-d . n) L_sky(r).
 * The reflected sun disc is left out: the glint (terrain_shade.h) is the sun's reflection from
 * the wind-roughened sea, of which a mirror's disc would count part twice. A mirror ray that
 * meets land shows it (the integrator's surface). terrain_radiance omits the water's uniform-
 * sky reflection under this stage. */
#ifndef ATMO_TERRAIN_TERRAIN_STAGE_H
#define ATMO_TERRAIN_TERRAIN_STAGE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/rng.h"
#include "atmosphere/sky_method.h"
#include "media/medium.h"
#include "terrain/terrain.h"
#include "terrain/terrain_material.h"
#include "terrain/terrain_shade.h"
#include "terrain/water.h"
#endif

/* The sky the water at distance t along the ray reflects toward the ray's origin (see the top
 * of the file), zero where the surface there is land. */
ATMO_FN vec3 terrain_stage_water_sky(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                     const medium_ray *ray, float t, rng_stream *g)
{
    vec3 p = v3_add(ray->origin, v3_scale(ray->dir, t));
    float distance = v3_length(p);
    terrain_surface_point sp = terrain_material(s, heightmap, p, distance);
    vec3 n = sp.vertical;
    float c = -v3_dot(ray->dir, n);
    if (sp.weight[TERRAIN_WATER] <= 0.0f || c <= 0.0f)
        return v3(0.0f, 0.0f, 0.0f);
    vec3 r = v3_normalize(v3_add(ray->dir, v3_scale(n, 2.0f * c)));
    float lift = TERRAIN_SHADOW_OFFSET_M + 2.0f * s->terrain.tolerance * distance;
    medium_ray mirror = medium_ray_make(s, v3_add(p, v3_scale(n, lift)), r);
    vec3 sky, sun, view_t;
    sky_trace(s, ATMO_LUT_ARGS, &mirror, INFINITY, g, &sky, &sun, &view_t);
    return v3_scale(sky, sp.weight[TERRAIN_WATER] * water_fresnel(c, WATER_INDEX));
}

/* The camera ray with the terrain for methods single and march: the method's sky_trace over
 * the whole ray, plus the sky the water reflects where the ray ends on it. Returns 1 (the
 * stage traces every ray). */
ATMO_FN int terrain_stage_trace(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                const medium_ray *ray, rng_stream *g, vec3 *sky, vec3 *sun,
                                vec3 *view_t)
{
    float t;
    int hit = terrain_trace(s, heightmap, ray->origin, ray->dir, 0.0f, INFINITY, s->terrain.steps,
                            &t, 0);
    sky_trace(s, ATMO_LUT_ARGS, ray, INFINITY, g, sky, sun, view_t);
    if (hit)
        *sky = v3_add(*sky, v3_mul(*view_t, terrain_stage_water_sky(s, ATMO_LUT_ARGS, ray, t, g)));
    return 1;
}

/* The camera ray with the terrain for methods fast and lut: a ray that meets the terrain
 * through the medium integrator with the method's multiple-scattering source, plus the water's
 * mirror; any other through the method's sky_trace. Returns 1 (every ray). */
ATMO_FN int terrain_stage_trace_tables(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                       const medium_ray *ray, rng_stream *g, vec3 *sky,
                                       vec3 *sun, vec3 *view_t)
{
    float t;
    if (!terrain_trace(s, heightmap, ray->origin, ray->dir, 0.0f, INFINITY, s->terrain.steps, &t,
                       0)) {
        sky_trace(s, ATMO_LUT_ARGS, ray, INFINITY, g, sky, sun, view_t);
        return 1;
    }
    medium_result res;
    medium_integrate(s, ATMO_LUT_ARGS, ray, 0.0f, INFINITY, s->view_steps, rng_next(g), 1, &res);
    *sky = medium_radiance(s, ATMO_LUT_ARGS, &res, ray->nu);
    *sun = res.sun;
    *view_t = res.view_t;
    *sky = v3_add(*sky, v3_mul(*view_t, terrain_stage_water_sky(s, ATMO_LUT_ARGS, ray, t, g)));
    return 1;
}

#endif
