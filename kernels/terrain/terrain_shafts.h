/* terrain_shafts.h — the terrain's shadow at the samples of one ray of the medium integrator
 * (light shafts), with the thesis' shortcuts (presets.md), each a bit of terrain.shafts
 * (ATMO_TERRAIN_SHAFT_*, gpu_enums.h).
 *
 * Exact: a sample of the integrator at the camera-relative point p is lit by the terrain iff
 * the ray p + u s (s the sun's direction, a point sun as the planet's shadow has it) meets no
 * terrain for 0 < u <= shadow_far_m (terrain.h's tracer). Every sample of every ray asks it,
 * which is nearly the whole cost of a low sun over mountains: a sun ray a few degrees high
 * stays inside the terrain's shell for tens of kilometres.
 * Map: with terrain.sun_visibility = map (the default outside path mode) a point inside the
 * sun-height map baked for this camera and sun (terrain_sun.h) takes the map's lookup instead
 * of the march, with a soft edge of a few metres (so a sample's answer lies in [0, 1]); points
 * outside it, and every point without a map, march. The shortcuts below apply either way,
 * except (4), which the map, holding the whole ray, does not need.
 *
 * Shortcuts, with the ray's state in terrain_shafts (the integrator's walk carries it from
 * one sample to the next, pbrt-v4's SampleT_maj shape; t the sample's distance along the ray,
 * d the end of the ray's segment, t_s the distance to the terrain surface it ends at):
 *   (1) BELOW_HORIZON  the sun below the sample's horizon (mu_s < 0): shadowed (the sun ray
 *                      descends into the terrain's shell; wrong only where it passes over a
 *                      valley to the sea's horizon).
 *   (2) SURFACE        the ray's surface point is itself in the terrain's shadow and
 *                      t_s - t < 400 m: shadowed (the surface's shadow is traced once per ray,
 *                      when the first sample comes within 400 m).
 *   (3) SPARSE         looking away from the sun (view . sun < 0.4): only every 6th sample is
 *                      traced, the others repeat the last traced answer.
 *   (4) START          the shadow march starts at u = 0.6 (t_s - t) instead of 0.
 *   (5) REST           once a sample beyond half the segment (t > d / 2) is shadowed with
 *                      view and sun aligned in the camera's tangent plane (the cosine of their
 *                      horizontal parts above TERRAIN_SHAFT_ALIGN_COS = 0.9, 26 degrees; the
 *                      thesis gives no number), every later sample is shadowed.
 *   (6) FAR            a sample beyond shadow_far_m from the camera: lit. (A sample above the
 *                      highest terrain whose sun ray rises is lit exactly, with no shortcut:
 *                      the tracer's shell test returns at once.)
 * Their errors against the exact march and their speed-ups: `atmo bench terrain` (rows
 * "shafts"), docs/notes/terrain.md. The default, ATMO_TERRAIN_SHAFT_DEFAULT, is (3) alone: the
 * only one that pays (2.5x turned away from the sun at 0.3 % RMS; facing the sun no shortcut
 * changes the time, and (1) costs 1.6 % turned away). */
#ifndef ATMO_TERRAIN_SHAFTS_H
#define ATMO_TERRAIN_SHAFTS_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/geometry.h"
#include "atmosphere/sky_method.h"
#include "media/ray.h"
#include "terrain/terrain.h"
#include "terrain/terrain_sun.h"
#include "atmo/gpu_types.h"
#endif

#define TERRAIN_SHAFT_SURFACE_M 400.0f
#define TERRAIN_SHAFT_SPARSE_NU 0.4f
#define TERRAIN_SHAFT_SPARSE_EVERY 6
#define TERRAIN_SHAFT_START 0.6f
#define TERRAIN_SHAFT_ALIGN_COS 0.9f
#define TERRAIN_SHAFT_LIFT_M 0.1f

/* The state of the shortcuts along one ray. */
typedef struct terrain_shafts {
    vec3 surface_p;     /* the surface point the ray ends at (camera-relative) */
    float surface_t;    /* its distance along the ray, m; < 0: the ray ends at no terrain */
    float end;          /* the end of the ray's segment, m */
    float last;         /* the last traced answer (shortcut 3) */
    int sparse;         /* shortcut 3 applies to this ray */
    int aligned;        /* view and sun aligned in the tangent plane (shortcut 5) */
    int count;          /* samples that reached shortcut 3 */
    int surface_shadow; /* -1: not traced yet; 0 lit; 1 shadowed */
    int rest_shadowed;  /* shortcut 5 has fired */
} terrain_shafts;

/* The state for the ray m whose segment ends at `end`, at the terrain's surface when
 * surface_t >= 0. */
ATMO_FN void terrain_shafts_begin(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_ray *m,
                                  float end, float surface_t, terrain_shafts *st)
{
    int bits = s->terrain.shafts;
    vec3 sun = v3_from4(s->sun_direction);
    st->surface_t = surface_t;
    st->surface_p = v3_add(m->origin, v3_scale(m->dir, fmaxf(surface_t, 0.0f)));
    st->end = end;
    st->last = 1.0f;
    st->count = 0;
    st->surface_shadow = -1;
    st->rest_shadowed = 0;
    st->sparse = (bits & ATMO_TERRAIN_SHAFT_SPARSE) && m->nu < TERRAIN_SHAFT_SPARSE_NU;
    vec3 dh = v3_sub(m->dir, v3_scale(m->up, v3_dot(m->up, m->dir)));
    vec3 sh = v3_sub(sun, v3_scale(m->up, v3_dot(m->up, sun)));
    float norms = v3_length(dh) * v3_length(sh);
    st->aligned = (bits & ATMO_TERRAIN_SHAFT_REST) && norms > 0.0f &&
                  v3_dot(dh, sh) > TERRAIN_SHAFT_ALIGN_COS * norms;
}

/* 1 where the terrain leaves the sun's centre visible from the point q, 0 where it hides it:
 * the sun-height map's lookup where it answers (terrain_sun.h; it holds the whole ray, so
 * start does not apply), else the march. */
ATMO_FN float terrain_shafts_trace(ATMO_GLOBAL const atmo_gpu_scene *s,
                                   ATMO_GLOBAL const float *hm, ATMO_GLOBAL const float *sun_map,
                                   vec3 p, float start)
{
    ATMO_GLOBAL const atmo_gpu_terrain *tr = &s->terrain;
    float t, v = terrain_sun_map_visibility(s, sun_map, p);
    if (v >= 0.0f)
        return v;
    return terrain_trace(s, hm, p, v3_from4(s->sun_direction), start, tr->shadow_far_m,
                         tr->shadow_steps, &t, 0)
               ? 0.0f
               : 1.0f;
}

/* The terrain's shadow, 0 to 1, at the sample q at distance t along the ray of state st (st
 * may be 0: a point on no ray, only the stateless shortcuts (1) and (6) apply); sun_map: the
 * sun-height map, or 0 (every point marches). */
ATMO_FN float terrain_shafts_visibility(ATMO_GLOBAL const atmo_gpu_scene *s,
                                        ATMO_GLOBAL const float *hm,
                                        ATMO_GLOBAL const float *sun_map, const medium_point *q,
                                        float t, terrain_shafts *st)
{
    ATMO_GLOBAL const atmo_gpu_terrain *tr = &s->terrain;
    int bits = tr->shafts;
    if ((bits & ATMO_TERRAIN_SHAFT_BELOW_HORIZON) && q->mu_s < 0.0f)
        return 0.0f;
    if ((bits & ATMO_TERRAIN_SHAFT_FAR) && v3_dot(q->p, q->p) > atmo_sq(tr->shadow_far_m))
        return 1.0f;
    if (!st)
        return terrain_shafts_trace(s, hm, sun_map, q->p, 0.0f);
    if (st->rest_shadowed)
        return 0.0f;
    float left = st->surface_t - t; /* to the surface */
    if ((bits & ATMO_TERRAIN_SHAFT_SURFACE) && st->surface_t >= 0.0f &&
        left < TERRAIN_SHAFT_SURFACE_M) {
        if (st->surface_shadow < 0) {
            vec3 n = terrain_vertical(s, st->surface_p);
            vec3 lifted = v3_add(st->surface_p,
                                 v3_scale(n, TERRAIN_SHAFT_LIFT_M +
                                                 2.0f * tr->tolerance * st->surface_t));
            st->surface_shadow = terrain_shafts_trace(s, hm, sun_map, lifted, 0.0f) > 0.0f ? 0 : 1;
        }
        if (st->surface_shadow)
            return 0.0f;
    }
    if (st->sparse && (st->count++ % TERRAIN_SHAFT_SPARSE_EVERY) != 0)
        return st->last;
    float start = (bits & ATMO_TERRAIN_SHAFT_START) && st->surface_t >= 0.0f && left > 0.0f
                      ? TERRAIN_SHAFT_START * left
                      : 0.0f;
    float v = terrain_shafts_trace(s, hm, sun_map, q->p, start);
    st->last = v;
    if (st->aligned && v == 0.0f && t > 0.5f * st->end)
        st->rest_shadowed = 1;
    return v;
}

/* The terrain as an occluder of the sun along a ray (the plan's composition, visibility.h): its
 * shadow at the sample q at distance t of the ray whose state is st (0: no ray). */
ATMO_FN float terrain_shafts_sun_visibility(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                            const medium_point *q, float t, terrain_shafts *st)
{
#ifdef ATMO_TERRAIN_SUN_MAP
    return terrain_shafts_visibility(s, heightmap, terrain_sun_map, q, t, st);
#else
    return terrain_shafts_visibility(s, heightmap, 0, q, t, st);
#endif
}

#endif
