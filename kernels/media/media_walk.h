/* media_walk.h — the one majorant walk (majorant_walk.h) through the composed media: the walk of
 * method reference's camera rays, bounces and shadow rays, and of the path tracer's volume
 * stage (its free flights and shadow rays through the volume media, render/volume_stage.h).
 *
 * Modes (media.h): MEDIA_WALK_MEDIA, the scene's media with the air; MEDIA_WALK_SHADOW, the
 * same toward the sun; MEDIA_WALK_VOLUME, the path tracer's volume media alone (no air: the
 * method's sky_trace gives the air's light and transmittance along the path's segments),
 * except in the free flight where the plan makes the air a volume medium (path.air = medium:
 * MEDIA_VOLUME_AIR 1), whose rate then adds the air's bound and whose pick adds the air's
 * Rayleigh and aerosol components; the shadow query in volume mode never tracks the air (the
 * path tracer takes the air's sun transmittance from the LUT).
 *
 * Majorant. On the ray origin + t dir, t in [0, end] (radius r and cosine mu at the origin), the
 * rate is the air's bound on the whole ray (media_air_majorant: its extinction at the ray's
 * lowest altitude; zero in volume mode) plus the sum of the media's own majorants (the plan's
 * composition media_majorant_segment over the features' slots, for the walk's mode: a cloud
 * shell's parts, a cloud layer's majorant grid), piecewise constant; each segment ends where the
 * first of the media's segments ends. Every term bounds its medium's extinction, so the sum
 * bounds sigma_t of the walk's media and every tracking policy of the walk stays unbiased;
 * empty space adds nothing and draws no number.
 *
 * The shadow query (media_walk_sun_transmittance): the transmittance toward the sun from a
 * point q to the top of the atmosphere (the ray must not hit the ground) is
 *     T = T_exact x T_tracked,
 * T_exact the product of the media whose sun transmittance has a closed form (a homogeneous
 * shell's chord: the slot's sun_exact; no noise and no walk through them; none in volume mode),
 * T_tracked the ratio tracking (Novak et al. 2014) of the others with the walk in shadow or
 * volume mode (their majorants only): W = prod over the points of (1 - sigma_t / sigma_bar),
 * unbiased, each factor in [0, 1]. Where a medium with a majorant of its own is walked
 * (MEDIA_TRACKED > 0: clouds; the volume media always), W below MEDIA_WALK_ROULETTE_T goes
 * through Russian roulette (tracking_roulette: kept with probability W / threshold and divided
 * by it, unbiased), which ends walks through opaque cloud after a few optical depths instead of
 * kilometres.
 *
 * The free flight (media_walk_volume_flight; spectral tracking, Kutz et al. 2017, over the
 * components MEDIA_WALK_VOLUME_*: the one volume medium the composition may hold, then with
 * MEDIA_VOLUME_AIR the air's Rayleigh and aerosols): at each tentative
 * point, scatter with sigma_s or null with sigma_bar - sigma_t, picked with probabilities
 * proportional to max_c of w sigma_s and w (sigma_bar - sigma_t), the vec3 weight w multiplied
 * by sigma_event / (sigma_bar P_event) (walk_pick): absorption folds into the weight, so the
 * first scattering point t_c has density T(0, t_c) sigma_s(t_c) in every channel after the
 * weight. For a grey medium (the same extinction and albedo in every channel) both events
 * multiply w by the same 1 - (1 - albedo) sigma_t / sigma_bar, and with albedo 1 w stays 1:
 * plain delta tracking. No scattering before `end`: the ray passes with weight w, an unbiased
 * estimate of T_volume(0, end). A point of zero extinction is null for certain and draws no pick.
 * The flight is an iterator (media_walk_volume_flight_begin, media_walk_volume_point, then the
 * caller's walk_pick), so a caller can estimate at every tentative point with the weight the
 * point is reached with (the path tracer's sun in the air, render/path.h's path_flight); with
 * the air in the walk the rate has a floor of a given number of points over the flight.
 *
 * The volume media's shadow on the air's samples (media_walk_volume_sun, which medium.h and the
 * reference multiply into the air's sunlight and multiple-scattering source): the shadow query
 * in volume mode on a stream of its own, rng.h's stream of the render seed at the "pixel"
 * rng_point_hash(q, seed) of the sample point's bits. Unbiased: for a fixed point q the walk's
 * estimate R has E[R | q] = T_volume(q) for any stream of independent uniform numbers, and the
 * stream is a full-avalanche hash of q's bits, as independent of the path's own numbers as
 * rng.h's counters are of each other; q is a function of the path's numbers, so for the air's
 * integrand f at q, E[f(q) R] = E[f(q) E[R | q]] = E[f(q) T_volume(q)]. Two samples share
 * numbers only where their points are the same floats (correlated then, not biased), and the
 * same point gives the same estimate in any tile and launch, so the image stays a function of
 * the seed. A sun ray that meets no cell of non-zero bound draws at most one number and returns
 * 1, which is T exactly, so clear air stays noise-free.
 * Units: metres, 1/m. Random numbers: the walk's (one per tentative point, none over a segment
 * of rate zero), one per pick where the extinction is not zero, one per roulette, from the
 * caller's stream. Without volume media (MEDIA_VOLUME = 0) the volume queries draw none and
 * return no scattering and T = 1. */
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
 * `least`, in mode `mode` (media.h: MEDIA_WALK_MEDIA, MEDIA_WALK_SHADOW, MEDIA_WALK_VOLUME). */
ATMO_FN media_walk media_walk_begin(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                    vec3 origin, vec3 dir, float r, float mu, float end,
                                    float least, int mode)
{
    media_walk mw;
    mw.w = walk_begin(end, least);
    mw.air = mode == MEDIA_WALK_VOLUME ? 0.0f : media_air_majorant(s, r, mu, end);
    media_majorant_begin(s, ATMO_LUT_ARGS, origin, dir, r, mu, end, mode, &mw.majorant);
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

/* The transmittance toward the sun from q to the top of the atmosphere (see the top of the
 * file) through the scene's media (mode MEDIA_WALK_SHADOW) or the volume media alone
 * (MEDIA_WALK_VOLUME). */
ATMO_FN vec3 media_walk_sun_transmittance(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                          const medium_point *q, int mode, rng_stream *g)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    /* flags of 0 or 1, joined bitwise: a composed constant in a logical operator is a warning */
    const int volume = mode == MEDIA_WALK_VOLUME;
    const int roulette = volume | (MEDIA_TRACKED > 0);
    vec3 T = v3(1.0f, 1.0f, 1.0f), sun = v3_from4(s->sun_direction), sigma_s;
    if (volume & (MEDIA_VOLUME == 0))
        return T;
    float r = q->r, mu = q->mu_s;
    float d = geometry_distance_to_top(r, mu, a->top_radius);
    media_walk mw = media_walk_begin(s, ATMO_LUT_ARGS, q->p, sun, r, mu, d, 0.0f, mode);
    while (media_walk_next(s, ATMO_LUT_ARGS, &mw, g)) {
        medium_point x = *q;
        x.p = v3_add(q->p, v3_scale(sun, mw.w.t));
        x.h = geometry_altitude_at(r, mu, mw.w.t, a->bottom_radius);
        T = walk_ratio(&mw.w, T,
                       volume ? media_volume_at(s, ATMO_LUT_ARGS, &x, &sigma_s)
                              : media_tracked_extinction(s, ATMO_LUT_ARGS, &x));
        if (roulette)
            T = tracking_roulette(T, MEDIA_WALK_ROULETTE_T, g);
        if (tracking_max3(T) <= 0.0f)
            break;
    }
    return volume ? T : media_sun_exact_attenuate(s, ATMO_LUT_ARGS, q, T);
}

/* The components a free flight through the volume media scatters by (the walk's pick order):
 * the volume medium, then with MEDIA_VOLUME_AIR the air's Rayleigh and Mie components. */
#define MEDIA_WALK_VOLUME_MEDIUM 0
#define MEDIA_WALK_VOLUME_RAYLEIGH 1
#define MEDIA_WALK_VOLUME_MIE 2

/* The air of the volume walk at x: its extinction into *sigma_t (added), its Rayleigh and Mie
 * scattering into sigma[MEDIA_WALK_VOLUME_RAYLEIGH], sigma[MEDIA_WALK_VOLUME_MIE]; no air above
 * the top of the atmosphere, where the methods' integrals end too. */
ATMO_FN void media_walk_volume_air(ATMO_GLOBAL const atmo_gpu_scene *s, const medium_point *x,
                                   vec3 *sigma, vec3 *sigma_t)
{
    if (x->r > s->atmosphere.top_radius) {
        sigma[MEDIA_WALK_VOLUME_RAYLEIGH] = v3(0.0f, 0.0f, 0.0f);
        sigma[MEDIA_WALK_VOLUME_MIE] = v3(0.0f, 0.0f, 0.0f);
        return;
    }
    media_sample air = media_air_at(s, x);
    sigma[MEDIA_WALK_VOLUME_RAYLEIGH] = air.scattering[MEDIA_RAYLEIGH];
    sigma[MEDIA_WALK_VOLUME_MIE] = air.scattering[MEDIA_MIE];
    *sigma_t = v3_add(*sigma_t, air.extinction);
}

/* The walk of a free flight through the volume media along m over [0, end] (see the top of
 * the file), into *mw; 0 where there are no volume media (no walk, no number drawn). With the
 * air in the walk (MEDIA_VOLUME_AIR) the walk ends at the ground and at the top of the
 * atmosphere (an escaping ray's end is infinite), and its rate adds the air's bound on the ray
 * (media_air_majorant: the extinction at the ray's lowest altitude, where the densities, which
 * fall with altitude, are largest), at least `points` / (the walk's length): any rate at or
 * above sigma_t is a majorant, and the floor gives a segment of thin air about `points`
 * tentative points to estimate at (the path tracer's sun at every tentative point; 0: none). */
ATMO_FN int media_walk_volume_flight_begin(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                           const medium_ray *m, float end, int points,
                                           media_walk *mw)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    if ((MEDIA_VOLUME | MEDIA_VOLUME_AIR) == 0)
        return 0;
    float least = 0.0f;
    if (MEDIA_VOLUME_AIR) {
        end = fminf(end, geometry_distance_to_top(m->r, m->mu, a->top_radius));
        if (geometry_ray_hits_ground(m->r, m->mu, a->bottom_radius))
            end = fminf(end, geometry_distance_to_bottom(m->r, m->mu, a->bottom_radius));
        least = end > 0.0f ? (float)points / end : 0.0f;
    }
    *mw = media_walk_begin(s, ATMO_LUT_ARGS, m->origin, m->dir, m->r, m->mu, end, least,
                           MEDIA_WALK_VOLUME);
    if (MEDIA_VOLUME_AIR)
        mw->air = media_air_majorant(s, m->r, m->mu, end);
    return 1;
}

/* The flight's next tentative point of non-zero extinction (a point of zero extinction is null
 * for certain and leaves the weight unchanged): 1 with the point in *x, the components'
 * scattering coefficients in sigma[MEDIA_WALK_VOLUME_*] (the air's zero without
 * MEDIA_VOLUME_AIR) and the extinction in *sigma_t, the rate there mw->w.sigma_bar; 0 past the
 * end. The caller picks the event (walk_pick, count media_walk_volume_components()). */
ATMO_FN int media_walk_volume_point(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                    media_walk *mw, const medium_ray *m, rng_stream *g,
                                    medium_point *x, vec3 *sigma, vec3 *sigma_t)
{
    while (media_walk_next(s, ATMO_LUT_ARGS, mw, g)) {
        *x = medium_ray_at(m, mw->w.t, s->atmosphere.bottom_radius);
        *sigma_t = media_volume_at(s, ATMO_LUT_ARGS, x, &sigma[MEDIA_WALK_VOLUME_MEDIUM]);
        sigma[MEDIA_WALK_VOLUME_RAYLEIGH] = v3(0.0f, 0.0f, 0.0f);
        sigma[MEDIA_WALK_VOLUME_MIE] = v3(0.0f, 0.0f, 0.0f);
        if (MEDIA_VOLUME_AIR)
            media_walk_volume_air(s, x, sigma, sigma_t);
        if (tracking_max3(*sigma_t) > 0.0f)
            return 1;
    }
    return 0;
}

/* The number of components the flight picks among: the volume medium, and the air's two. */
ATMO_FN int media_walk_volume_components(void)
{
    return MEDIA_VOLUME_AIR ? 3 : 1;
}

/* The free flight through the volume media along m over [0, end] with no estimate at its
 * tentative points: the component that scatters first (MEDIA_WALK_VOLUME_*) with its distance
 * in *t_hit, else WALK_NULL; *w the spectral-tracking weight (see the top of the file). */
ATMO_FN int media_walk_volume_flight(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                     const medium_ray *m, float end, rng_stream *g, float *t_hit,
                                     vec3 *w)
{
    media_walk mw;
    medium_point x;
    vec3 sigma[3], sigma_t;
    *w = v3(1.0f, 1.0f, 1.0f);
    if (!media_walk_volume_flight_begin(s, ATMO_LUT_ARGS, m, end, 0, &mw))
        return WALK_NULL;
    while (media_walk_volume_point(s, ATMO_LUT_ARGS, &mw, m, g, &x, sigma, &sigma_t)) {
        int k = walk_pick(&mw.w, g, w, sigma, media_walk_volume_components(), sigma_t);
        if (k != WALK_NULL) {
            *t_hit = mw.w.t;
            return k;
        }
    }
    return WALK_NULL;
}

/* The volume media's transmittance toward the sun from an air sample q, on the stream of q's
 * bits (see the top of the file); 1 without volume media. */
ATMO_FN vec3 media_walk_volume_sun(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                                   const medium_point *q)
{
    if (MEDIA_VOLUME == 0)
        return v3(1.0f, 1.0f, 1.0f);
    rng_stream g = rng_stream_stage(s->seed, rng_point_hash(q->p, s->seed), 0u, 0u);
    return media_walk_sun_transmittance(s, ATMO_LUT_ARGS, q, MEDIA_WALK_VOLUME, &g);
}

#endif
