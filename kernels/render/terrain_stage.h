/* terrain_stage.h — the terrain in front of the methods that read whole rays from tables
 * (fast's sky-view LUT, lut's scattering tables), which know no terrain.
 *
 * terrain_stage_trace: a camera ray that meets the terrain (terrain.h's tracer) is integrated
 * by the medium integrator with the method's multiple-scattering source (use_ms = 1: Psi_ms
 * for fast, the stored density J for lut), as each method's sky_trace does for a finite
 * segment; the integrator ends the segment at the surface (visibility_surface_hit) and adds
 * T L_surface, the terrain's light (terrain_shade.h), so the air in front is the aerial
 * perspective of the same method. Every other ray goes to the method's sky_trace over its
 * whole length. */
#ifndef ATMO_RENDER_TERRAIN_STAGE_H
#define ATMO_RENDER_TERRAIN_STAGE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/rng.h"
#include "atmosphere/sky_method.h"
#include "media/medium.h"
#include "terrain/terrain.h"
#endif

ATMO_FN void terrain_stage_trace(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                 const medium_ray *ray, rng_stream *g, vec3 *sky, vec3 *sun,
                                 vec3 *view_t)
{
    float t;
    if (!terrain_trace(s, heightmap, ray->origin, ray->dir, 0.0f, INFINITY, s->terrain.steps, &t,
                       0)) {
        sky_trace(s, ATMO_LUT_ARGS, ray, INFINITY, g, sky, sun, view_t);
        return;
    }
    medium_result res;
    medium_integrate(s, ATMO_LUT_ARGS, ray, 0.0f, INFINITY, s->view_steps, rng_next(g), 1, &res);
    *sky = medium_radiance(s, ATMO_LUT_ARGS, &res, ray->nu);
    *sun = res.sun;
    *view_t = res.view_t;
}

#endif
