/* medium.h — the medium integrator: radiance along a camera-relative 3-D segment through the
 * scene's participating media (media.h), with the sun's visibility at each sample from the
 * visibility sources (visibility.h). Sky pixels, aerial perspective, the sky-view LUT of
 * method fast, and later light shafts and the path tracer's bounces all call it.
 *
 * For the segment [t0, t1] of a ray (ray.h), with T(a, b) the transmittance between two of
 * its points,
 *     L = int_t0^d T(t0, t) [sum_k sigma_s,k(t) p_k(nu) E T_sun(t) V(t) + J_ms(t)] dt
 *       + T(t0, d) L_surface(d)
 * (the radiative transfer equation's single-scattering form with a point sun of irradiance E;
 * Nishita et al. 1993, Hillaire 2020 eq. 1), d = min(t1, ground, top of the atmosphere, an
 * opaque surface), T_sun the atmosphere's transmittance toward the sun from the transmittance
 * LUT, V the visibility (visibility_sun: the occluders and the shadowing media), J_ms the
 * method's multiple-scattering source (medium_ms_source: whatever the method registers, e.g.
 * method march's Psi_ms or method lut's stored density J; none for method single), L_surface
 * the lit ground (sun and, with J_ms, the sky) or an opaque surface; the sun disc (E / Omega_sun through the atmosphere, Omega_sun = 2 pi (1 - cos
 * alpha)) comes apart where the ray sees it. A segment that ends at t1 before the ground or the
 * top ends at a black surface there: no surface term, no sun disc.
 *
 * Stepping (pbrt-v4's SampleT_maj shape: one walk, one per-point evaluation that carries the
 * ray's small visibility state, visibility_ray: what the terrain's light-shaft shortcuts
 * remember from one sample to the next). The ray is first moved to where it enters the
 * atmosphere (atmosphere_enter), then [0, d] is walked by the deterministic methods' one
 * stepping loop, quadrature_walk.h: n segments growing as (i/n)^2 from the start,
 * [d (i/n)^2, d ((i+1)/n)^2], short where the density changes fastest along rays that start
 * low (worst 0.09 % against the double-precision reference with 64 segments,
 * tests/test_sky_single.c; measured choices: docs/notes/medium.md). The media add break points
 * (media_intervals: the cloud shell's spheres), the walk's parts: a part of the ray inside such
 * a medium is integrated with that medium's own stepping (media_interval: optical-depth steps in
 * the cloud) and the grid segments are clipped to the rest. In each segment or clipped piece the
 * coefficients are taken at one point, at the fraction `jitter` of its length (a random number
 * per sample, so averaging samples removes the banding of a fixed point), and the piece is
 * integrated exactly for constant coefficients (Hillaire 2015; media.h's medium_piece_weight):
 *     L_k += T w sigma_s,k E T_sun V,  w = (1 - e^{-sigma_t dt}) / sigma_t,  T *= e^{-sigma_t dt}
 * which conserves energy however long the piece. A ray that meets no break point walks exactly
 * the grid of the air alone, so a medium the ray never meets changes nothing.
 *
 * Results come in parts (medium_result): nu is constant along a straight ray, so the phase
 * functions factor out of single scattering, L = sum_k p_k(nu) single[k] + rest; the sky-view
 * LUT of method fast stores the parts. The multiple-scattering source is multiplied by the
 * shadowing media's transmittance toward the sun (not by the opaque occluders): an
 * approximation that darkens the haze under a thick cloud deck.
 *
 * This file names no medium, occluder or method: media_at, media_phase, media_sun_attenuate,
 * medium_ms_source, medium_ms_ground_irradiance, media_intervals and media_interval are the
 * plan's generated composition of the scene's features (media.h, host/plan/compose.c), placed
 * before this file in the assembled program. */
#ifndef ATMO_MEDIA_MEDIUM_H
#define ATMO_MEDIA_MEDIUM_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/geometry.h"
#include "atmosphere/sky_method.h"
#include "media/ray.h"
#include "media/media.h"
#include "media/quadrature_walk.h"
#include "media/visibility.h"
#include "media/media_walk.h"
#include "atmo/gpu_types.h"
#endif

typedef struct medium_result {
    vec3 single[MEDIA_COMPONENTS]; /* in-scattered sunlight of each component, without its phase */
    vec3 rest;                     /* the multiple-scattering source, the media's own intervals
                                      (phases included) and the lit surface */
    vec3 sun;                      /* the sun disc where the ray sees it */
    vec3 view_t;                   /* T(t0, end of the segment) */
} medium_result;

/* The sunlight arriving at a point: E T_sun V, V at a sample of a ray with the visibility's
 * state vr (0: a point on no ray). */
ATMO_FN vec3 medium_sunlight_on_ray(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                    const medium_point *q, visibility_ray *vr)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    vec3 vis = visibility_sun_on_ray(s, ATMO_LUT_ARGS, q, vr);
    if (vis.x <= 0.0f && vis.y <= 0.0f && vis.z <= 0.0f)
        return v3(0.0f, 0.0f, 0.0f);
    vec3 to_sun = atmosphere_transmittance_to_top(a, transmittance_lut, s->transmittance_width,
                                                  s->transmittance_height, q->r, q->mu_s);
    return v3_mul(v3_from4(a->solar_irradiance), v3_mul(to_sun, vis));
}

ATMO_FN vec3 medium_sunlight(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                             const medium_point *q)
{
    return medium_sunlight_on_ray(s, ATMO_LUT_ARGS, q, 0);
}

/* One piece of the walk sampled at t, dt long: the per-point evaluation, with the ray's
 * visibility state vr. */
ATMO_FN void medium_piece(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                          const medium_ray *m, float t, float dt, int use_ms, int ground,
                          visibility_ray *vr, medium_result *out, vec3 *T)
{
    medium_point q = medium_ray_at(m, t, s->atmosphere.bottom_radius);
    media_sample ms = media_at(s, ATMO_LUT_ARGS, &q);
    vr->t = t;
    vec3 sun_e = medium_sunlight_on_ray(s, ATMO_LUT_ARGS, &q, vr);
    /* the path tracer's volume medium toward the sun (media_walk_volume_sun), for the sun and
     * the multiple-scattering source alike; not tracked where neither needs it */
    vec3 volume_t = use_ms || sun_e.x > 0.0f || sun_e.y > 0.0f || sun_e.z > 0.0f
                        ? media_walk_volume_sun(s, ATMO_LUT_ARGS, &q)
                        : v3(1.0f, 1.0f, 1.0f);
    sun_e = v3_mul(sun_e, volume_t);
    vec3 Tw = medium_piece_weight(ms.extinction, dt, T);
    vec3 lit = v3_mul(Tw, sun_e);
    for (int k = 0; k < MEDIA_COMPONENTS; k++)
        out->single[k] = v3_add(out->single[k], v3_mul(lit, ms.scattering[k]));
    if (use_ms) {
        vec3 j = medium_ms_source(s, ATMO_LUT_ARGS, &q, m->nu, &ms, ground);
        j = media_sun_attenuate(s, ATMO_LUT_ARGS, &q, j);
        j = v3_mul(j, volume_t);
        out->rest = v3_add(out->rest, v3_mul(Tw, j));
    }
}

/* The integral above over [t0, t1] of the ray (t1 = INFINITY: to the ground or the top) with
 * n grid segments and sample offset jitter in [0, 1); use_ms adds the method's
 * multiple-scattering source and the sky's light on the ground; surfaces = 0 asks no opaque
 * surface (visibility_surface_hit), so the ray ends only at t1, the ground or the top (the
 * occluders' shadows on its samples stay). */
ATMO_FN void medium_integrate_any(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                  const medium_ray *ray, float t0, float t1, int n, float jitter,
                                  int use_ms, int surfaces, medium_result *out)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    for (int k = 0; k < MEDIA_COMPONENTS; k++)
        out->single[k] = v3(0.0f, 0.0f, 0.0f);
    out->rest = v3(0.0f, 0.0f, 0.0f);
    out->sun = v3(0.0f, 0.0f, 0.0f);
    out->view_t = v3(1.0f, 1.0f, 1.0f);
    medium_ray m = t0 > 0.0f ? medium_ray_advance(ray, t0) : *ray;
    float t_max = t1 - fmaxf(t0, 0.0f);
    int looks_at_sun = m.nu >= s->sun_direction.w;

    float t_entry = atmosphere_entry_distance(a, m.r, m.mu);
    if (!atmosphere_enter(a, &m.r, &m.mu, &m.mu_s, m.nu)) { /* the ray misses the atmosphere */
        if (looks_at_sun)
            out->sun = atmosphere_sun_disc_radiance(a, s->sun_direction.w);
        return;
    }
    t_max -= t_entry;
    m.origin = v3_add(m.origin, v3_scale(m.dir, t_entry));
    if (t_max <= 0.0f) /* the surface lies before the atmosphere */
        return;

    int ground = geometry_ray_hits_ground(m.r, m.mu, a->bottom_radius);
    float d = atmosphere_ray_length(a, m.r, m.mu, ground);
    float t_surface = surfaces ? visibility_surface_hit(s, ATMO_LUT_ARGS, &m) : -1.0f;
    int hits_surface = t_surface >= 0.0f && t_surface <= d; /* a surface on the ground wins */
    if (hits_surface)
        d = t_surface;
    int blocked = t_max < d; /* by the black surface at t_max */
    int hits_ground = ground && !hits_surface && !blocked;
    hits_surface = hits_surface && !blocked;
    if (blocked)
        d = t_max;
    visibility_ray vr;
    visibility_ray_begin(s, &m, d, hits_surface ? d : -1.0f, &vr);

    quadrature_walk q = quadrature_begin(d, n, jitter);
    q.parts = media_intervals(s, &m, 0.0f, d, q.lo, q.hi);
    vec3 T = v3(1.0f, 1.0f, 1.0f), medium_t = v3(1.0f, 1.0f, 1.0f);
    for (int ev; (ev = quadrature_next(&q)) != QUADRATURE_END;) {
        if (ev == QUADRATURE_PART)
            media_interval(s, ATMO_LUT_ARGS, &m, q.start, q.end, jitter, use_ms, ground, d, n,
                           &out->rest, &T, &medium_t);
        else
            medium_piece(s, ATMO_LUT_ARGS, &m, q.t, q.dt, use_ms, ground, &vr, out, &T);
    }

    if (hits_surface) {
        out->rest = v3_add(out->rest,
                           v3_mul(T, visibility_surface_radiance(s, ATMO_LUT_ARGS, &m, d)));
    } else if (hits_ground) {
        medium_point g;
        g.p = v3_add(m.origin, v3_scale(m.dir, d));
        g.r = a->bottom_radius;
        g.h = 0.0f;
        g.mu = atmo_clamp_cos((m.r * m.mu + d) / a->bottom_radius);
        g.mu_s = atmo_clamp_cos((m.r * m.mu_s + d * m.nu) / a->bottom_radius);
        vec3 irradiance = v3_scale(medium_sunlight(s, ATMO_LUT_ARGS, &g), fmaxf(g.mu_s, 0.0f));
        if (use_ms) /* plus the sky's */
            irradiance = v3_add(irradiance, medium_ms_ground_irradiance(s, ATMO_LUT_ARGS, g.mu_s));
        out->rest = v3_add(out->rest, v3_mul(T, v3_scale(v3_mul(v3_from4(a->ground_albedo),
                                                                irradiance),
                                                         1.0f / ATMO_PI)));
    } else if (looks_at_sun && !blocked) {
        vec3 to_space = atmosphere_transmittance_to_top(a, transmittance_lut,
                                                        s->transmittance_width,
                                                        s->transmittance_height, m.r, m.mu);
        out->sun = v3_mul(v3_mul(atmosphere_sun_disc_radiance(a, s->sun_direction.w), to_space),
                          medium_t);
    }
    out->view_t = T;
}

/* medium_integrate_any with the opaque surfaces: what a ray of the scene sees. */
ATMO_FN void medium_integrate(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                              const medium_ray *ray, float t0, float t1, int n, float jitter,
                              int use_ms, medium_result *out)
{
    medium_integrate_any(s, ATMO_LUT_ARGS, ray, t0, t1, n, jitter, use_ms, 1, out);
}

/* medium_integrate_any without them: the air along the ray to the ground or the top, for a
 * table of rays whose surfaces the renderer finds itself (method fast's sky-view LUT). */
ATMO_FN void medium_integrate_air(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                  const medium_ray *ray, float t0, float t1, int n, float jitter,
                                  int use_ms, medium_result *out)
{
    medium_integrate_any(s, ATMO_LUT_ARGS, ray, t0, t1, n, jitter, use_ms, 0, out);
}

/* The parts put together: L = sum_k p_k(nu) single[k] + rest. */
ATMO_FN vec3 medium_radiance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                             const medium_result *r, float nu)
{
    vec3 L = v3_mul(r->single[0], media_phase(s, ATMO_LUT_ARGS, 0, nu));
    for (int k = 1; k < MEDIA_COMPONENTS; k++)
        L = v3_add(L, v3_mul(r->single[k], media_phase(s, ATMO_LUT_ARGS, k, nu)));
    return v3_add(L, r->rest);
}

#endif
