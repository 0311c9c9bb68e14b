/* cloud_walk.h — the fBm cloud layer alone as a tracked medium (-DATMO_CLOUDS_VOLUME, where no
 * method sees the layer): the tentative points of a ray through the layer's majorant, a free
 * flight to the first real scattering by spectral tracking, and the sun's transmittance through
 * the layer by ratio tracking, for the path tracer's volume stage (render/volume_stage.h).
 *
 * Majorant. The layer's extinction is sigma_t(x) = d(x) k, d the density (cloud_layer.h) and k
 * its extinction per unit density per wavelength. Along the ray origin + t dir it is zero
 * outside the layer's shell, so the walk takes tentative points only in the parts of the ray
 * inside the shell (clouds_shell_parts: at most two, in order); there the rate is piecewise
 * constant, as the reference's walk has it (method_reference.h):
 *     sigma_bar = b_cell max_c k_c x 1.001   inside the majorant grid (cloud_majorant.h's DDA,
 *                                            b_cell the cell's density bound)
 *     sigma_bar = density max_c k_c x 1.001  beyond the grid (the global bound d <= density)
 * and 0 between the parts (no point there: the walk moves to the next part's start). The same
 * tracking.h walk spends each tentative point's optical depth -ln(1 - u) over these segments.
 *
 * Free flight (clouds_free_flight; spectral tracking, Kutz et al. 2017, one scattering
 * component): at each tentative point, scatter with sigma_s = albedo sigma_t or null with
 * sigma_bar - sigma_t, picked with probabilities proportional to max_c of w sigma_s and
 * w (sigma_bar - sigma_t), the vec3 weight w multiplied by sigma_event / (sigma_bar P_event)
 * (tracking_spectral_pick): absorption folds into the weight, so the first scattering point t_c
 * has density T(0, t_c) sigma_s(t_c) in every channel after the weight. For a grey layer
 * (k and the albedo the same in every channel: clouds.extinction_per_m > 0) both events
 * multiply w by the same 1 - (1 - albedo) sigma_t / sigma_bar (the ratio-tracking weight of the
 * absorption alone), and with albedo 1 w stays 1: plain delta tracking. No scattering before
 * `end`: the ray passes the layer with weight w, an unbiased estimate of T_clouds(0, end).
 *
 * Sun transmittance (clouds_sun_ratio; ratio tracking, Novak et al. 2014): along the sun's
 * direction from the point to where the ray leaves the shell,
 *     T = prod over the tentative points of (1 - sigma_t / sigma_bar),
 * unbiased for T_clouds; a weight below CLOUDS_WALK_ROULETTE_T goes through Russian roulette
 * (tracking_roulette: unbiased), which ends the walks through opaque cloud after a few optical
 * depths.
 * The same walk gives the air's samples their sun through the layer (media/visibility.h's
 * visibility_air_volume, on a stream hashed from the sample point): a walk whose sun ray meets
 * no cell of non-zero bound draws at most one number and returns 1, which is T exactly, so
 * clear air stays noise-free. The air's walks take no roulette at their first tentative point
 * (go on with probability P and weight 1 / P, else 0: unbiased, but at P = 1/4 on thesis-6 in
 * path mode 2.8 times less CPU time for 23 times the median pixel's variance:
 * docs/notes/path.md).
 * Random numbers: the caller's stream, one per tentative point, one per pick where the density is
 * not zero, one per roulette. Units: metres, 1/m. */
#ifndef ATMO_MEDIA_CLOUD_WALK_H
#define ATMO_MEDIA_CLOUD_WALK_H
#ifdef ATMO_CLOUDS_VOLUME
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/geometry.h"
#include "common/rng.h"
#include "media/ray.h"
#include "media/tracking.h"
#include "media/cloud_layer.h"
#include "media/cloud_majorant.h"
#include "atmo/gpu_types.h"
#endif

#define CLOUDS_WALK_ROULETTE_T 0.1f /* shadow weights below this go through roulette */

typedef struct clouds_walk {
    tracking_walk w;
    clouds_grid_walk grid;
    float scale;        /* density -> extinction bound: max_c k_c x 1.001, 1/m */
    float outside;      /* the rate beyond the grid, 1/m */
    float lo[2], hi[2]; /* the ray's parts inside the shell */
    int parts, part;    /* their count; the one the walk is in or before */
} clouds_walk;

/* The rate from the walk's point to the end of its segment (see the top of the file). */
ATMO_FN void clouds_walk_segment(clouds_walk *cw, ATMO_GLOBAL const float *grid)
{
    float t = cw->w.t;
    while (cw->part < cw->parts && t >= cw->hi[cw->part])
        cw->part++;
    if (cw->part >= cw->parts) {
        tracking_segment(&cw->w, 0.0f, cw->w.end);
        return;
    }
    if (t < cw->lo[cw->part]) {
        tracking_segment(&cw->w, 0.0f, cw->lo[cw->part]);
        return;
    }
    float seg_end, b = clouds_grid_segment(&cw->grid, grid, t, &seg_end);
    tracking_segment(&cw->w, b < 0.0f ? cw->outside : b * cw->scale,
                     fminf(seg_end, cw->hi[cw->part]));
}

/* The walk of the ray origin + t dir (camera-relative, dir unit; radius r and cosine mu at the
 * origin) over [0, end]. */
ATMO_FN clouds_walk clouds_walk_begin(ATMO_GLOBAL const atmo_gpu_scene *s,
                                      ATMO_GLOBAL const float *grid, vec3 origin, vec3 dir,
                                      float r, float mu, float end)
{
    ATMO_GLOBAL const atmo_gpu_clouds *c = &s->clouds;
    clouds_walk cw;
    cw.parts = clouds_shell_parts(s->atmosphere.bottom_radius, c->bottom_m, c->top_m, r, mu,
                                  0.0f, end, cw.lo, cw.hi);
    cw.part = 0;
    cw.w = tracking_begin(cw.parts > 0 ? cw.hi[cw.parts - 1] : 0.0f, 0.0f);
    cw.scale = tracking_max3(v3_from4(c->extinction)) * 1.001f;
    cw.outside = c->majorant * cw.scale;
    clouds_grid_frame f = clouds_grid_frame_make(s);
    cw.grid = clouds_grid_begin(&f, origin, dir, cw.w.end);
    if (cw.parts > 0)
        clouds_walk_segment(&cw, grid);
    return cw;
}

/* The next tentative point (cw->w.t, rate cw->w.sigma_bar there); 0 once past the end. */
ATMO_FN int clouds_walk_next(clouds_walk *cw, ATMO_GLOBAL const float *grid, rng_stream *g)
{
    if (cw->parts == 0)
        return 0;
    float tau = tracking_depth(g);
    for (;;) {
        if (cw->w.sigma_bar > 0.0f) {
            if (tracking_advance(&cw->w, &tau))
                return cw->w.t < cw->w.end;
        } else {
            cw->w.t = cw->w.seg_end; /* no point where the rate is zero */
        }
        if (cw->w.t >= cw->w.end)
            return 0;
        clouds_walk_segment(cw, grid);
    }
}

/* The layer's extinction at distance t of the walk's ray. */
ATMO_FN vec3 clouds_walk_extinction(ATMO_GLOBAL const atmo_gpu_scene *s, vec3 origin, vec3 dir,
                                    float r, float mu, float t)
{
    float h = geometry_altitude_at(r, mu, t, s->atmosphere.bottom_radius);
    float d = clouds_density(&s->clouds, v3_add(origin, v3_scale(dir, t)), h);
    return v3_scale(v3_from4(s->clouds.extinction), d);
}

/* The free flight along the ray m over [0, end]: 1 with the first scattering's distance in
 * *t_hit, else 0; *w the spectral-tracking weight (see the top of the file). */
ATMO_FN int clouds_free_flight(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float *grid,
                               const medium_ray *m, float end, rng_stream *g, float *t_hit,
                               vec3 *w)
{
    *w = v3(1.0f, 1.0f, 1.0f);
    clouds_walk cw = clouds_walk_begin(s, grid, m->origin, m->dir, m->r, m->mu, end);
    while (clouds_walk_next(&cw, grid, g)) {
        vec3 sigma_t = clouds_walk_extinction(s, m->origin, m->dir, m->r, m->mu, cw.w.t);
        if (tracking_max3(sigma_t) <= 0.0f)
            continue; /* a null point for certain: the weight is unchanged */
        vec3 sigma_s = v3_mul(sigma_t, v3_from4(s->clouds.albedo));
        if (tracking_spectral_pick(&cw.w, g, w, &sigma_s, 1, sigma_t) == 0) {
            *t_hit = cw.w.t;
            return 1;
        }
    }
    return 0;
}

/* The layer's transmittance toward the sun's centre from the point q (ratio tracking). */
ATMO_FN vec3 clouds_sun_ratio(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_GLOBAL const float *grid,
                              const medium_point *q, rng_stream *g)
{
    vec3 sun = v3_from4(s->sun_direction), T = v3(1.0f, 1.0f, 1.0f);
    clouds_walk cw = clouds_walk_begin(s, grid, q->p, sun, q->r, q->mu_s, INFINITY);
    while (clouds_walk_next(&cw, grid, g)) {
        T = tracking_ratio(&cw.w, T, clouds_walk_extinction(s, q->p, sun, q->r, q->mu_s, cw.w.t));
        T = tracking_roulette(T, CLOUDS_WALK_ROULETTE_T, g);
        if (tracking_max3(T) <= 0.0f)
            break;
    }
    return T;
}

/* Under path.clouds = volume the fBm layer is the path tracer's medium
 * (render/volume_stage.h) and no medium of the methods; the air's samples (medium.h's
 * pieces, the reference's sunlight) take its transmittance toward the sun apart through this
 * function, the plan's visibility_air_volume (media.h; not the surfaces: the path tracer's
 * shadow function tracks the layer for them itself). It is the ratio tracking above
 * (clouds_sun_ratio, the surfaces' and cloud vertices' walk) on a stream of its own: rng.h's
 * stream of the render seed at the "pixel" clouds_point_hash(p, seed) of the sample point's
 * bits. Unbiased: for a fixed point q the walk's estimate R has
 * E[R | q] = T_clouds(q) (ratio tracking, Novak et al. 2014; its roulette divides by the
 * survival probability) for any stream of independent uniform numbers, and the stream is a
 * full-avalanche hash of q's bits, as independent of the path's own numbers as rng.h's
 * counters are of each other. The point q is a function of the path's numbers (the camera,
 * the integrator's jitter, the bounces), so for the air's integrand f at q,
 *     E[f(q) R] = E[f(q) E[R | q]] = E[f(q) T_clouds(q)].
 * Two samples share numbers only where their points are the same floats, which jittered
 * samples of different paths almost never are (correlated then, not biased); and the same
 * point gives the same estimate in any tile and launch, so the image stays a function of the
 * seed. The estimate multiplies the sunlight and, as the marched layer's light march does,
 * the method's multiple-scattering source (medium.h). */
ATMO_FN vec3 clouds_volume_sun(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                               const medium_point *q)
{
    rng_stream g = rng_stream_stage(s->seed, clouds_point_hash(q->p, s->clouds.seed), 0u, 0u);
    return clouds_sun_ratio(s, clouds_majorant, q, &g);
}

#endif
#endif
