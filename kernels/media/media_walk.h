/* media_walk.h — the one majorant walk (majorant_walk.h) through the composed media: the walk of
 * method reference's camera rays, bounces and shadow rays.
 *
 * Majorant. On the ray origin + t dir, t in [0, end] (radius r and cosine mu at the origin), the
 * rate is the air's bound on the whole ray (media_air_majorant: its extinction at the ray's
 * lowest altitude) plus the sum of the media's own majorants (the plan's composition
 * media_majorant_segment over the features' slots: a cloud shell's parts, a cloud layer's
 * majorant grid), piecewise constant; each segment ends where the first of the media's
 * segments ends. Every term bounds its medium's extinction, so the sum bounds sigma_t of
 * media_at and every tracking policy of the walk stays unbiased; empty space adds nothing.
 *
 * The shadow query (media_walk_sun_transmittance): the transmittance toward the sun from a
 * point q to the top of the atmosphere (the ray must not hit the ground) is
 *     T = T_exact x T_tracked,
 * T_exact the product of the media whose sun transmittance has a closed form (a homogeneous
 * shell's chord: the slot's sun_exact; no noise and no walk through them), T_tracked the ratio
 * tracking (Novak et al. 2014) of the others with the walk in shadow mode (their majorants
 * only): W = prod over the points of (1 - sigma_t / sigma_bar), unbiased, each factor in [0, 1].
 * Where a medium with a majorant of its own is present (MEDIA_TRACKED > 0: clouds), W below
 * MEDIA_WALK_ROULETTE_T goes through Russian roulette (tracking_roulette: kept with probability
 * W / threshold and divided by it, unbiased), which ends walks through opaque cloud after a few
 * optical depths instead of kilometres. Units: metres, 1/m. Random numbers: the walk's (one per
 * tentative point) and one per roulette, from the caller's stream. */
#ifndef ATMO_MEDIA_MEDIA_WALK_H
#define ATMO_MEDIA_MEDIA_WALK_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/geometry.h"
#include "common/rng.h"
#include "media/ray.h"
#include "media/media.h"
#include "media/tracking.h"
#include "media/majorant_walk.h"
#include "atmo/gpu_types.h"
#endif

#define MEDIA_WALK_ROULETTE_T 0.1f /* shadow weights below this go through roulette (clouds) */

typedef struct media_walk {
    majorant_walk w;
    media_majorant majorant; /* the media's own majorants (the composition) */
    float air;               /* the air's bound on the whole ray, 1/m */
} media_walk;

/* The walk along origin + t dir over [0, end] (r, mu at the origin), with rate at least
 * `least`; shadow: toward the sun (the media of exact sun transmittance left out). */
ATMO_FN media_walk media_walk_begin(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                    vec3 origin, vec3 dir, float r, float mu, float end,
                                    float least, int shadow)
{
    media_walk mw;
    mw.w = walk_begin(end, least);
    mw.air = media_air_majorant(s, r, mu, end);
    media_majorant_begin(s, ATMO_LUT_ARGS, origin, dir, r, mu, end, shadow, &mw.majorant);
    return mw;
}

/* The next tentative point (mw->w.t, rate mw->w.sigma_bar there); 0 once past the end. */
ATMO_FN int media_walk_next(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS, media_walk *mw,
                            rng_stream *g)
{
    int ev;
    while ((ev = walk_next(&mw->w, g)) == WALK_SEGMENT) {
        float seg_end, rate = media_majorant_segment(s, ATMO_LUT_ARGS, &mw->majorant, mw->w.t,
                                                     &seg_end);
        walk_segment(&mw->w, mw->air + rate, seg_end);
    }
    return ev == WALK_POINT;
}

/* The media's transmittance toward the sun from q to the top of the atmosphere (see the top of
 * the file). */
ATMO_FN vec3 media_walk_sun_transmittance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                          const medium_point *q, rng_stream *g)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    float r = q->r, mu = q->mu_s;
    float d = geometry_distance_to_top(r, mu, a->top_radius);
    vec3 T = v3(1.0f, 1.0f, 1.0f), sun = v3_from4(s->sun_direction);
    media_walk mw = media_walk_begin(s, ATMO_LUT_ARGS, q->p, sun, r, mu, d, 0.0f, 1);
    while (media_walk_next(s, ATMO_LUT_ARGS, &mw, g)) {
        medium_point x = *q;
        x.p = v3_add(q->p, v3_scale(sun, mw.w.t));
        x.h = geometry_altitude_at(r, mu, mw.w.t, a->bottom_radius);
        T = walk_ratio(&mw.w, T, media_tracked_extinction(s, ATMO_LUT_ARGS, &x));
        if (MEDIA_TRACKED > 0)
            T = tracking_roulette(T, MEDIA_WALK_ROULETTE_T, g);
        if (tracking_max3(T) <= 0.0f)
            break;
    }
    return media_sun_exact_attenuate(s, ATMO_LUT_ARGS, q, T);
}

#endif
