/* tracking.h — the weights' roulettes of the Monte Carlo estimators (method reference's walk,
 * the path tracer's surface and cloud vertices); the walk itself, its tentative points and its
 * ratio and spectral tracking, is majorant_walk.h.
 *
 * Russian roulette on a weight that has become small (tracking_roulette: kept with probability
 * q = max W / threshold and divided by q) keeps every estimate linear in W unbiased and ends
 * walks through opaque media after a few optical depths instead of their whole length.
 * One number from the caller's stream (rng.h) per roulette.
 * A path's Russian roulette at its scattering events (tracking_survival: the reference's walk,
 * the path tracer's surface and cloud vertices) keeps the path with probability
 *     P = min(P_max, gain x max_c w_c),
 *     P_max = 1 before TRACKING_ROULETTE_LONG events, 0.95 from there on,
 * and the caller divides the throughput w by P: E[w'] = P (w / P) = w (unbiased). gain >= 1
 * raises the survival of paths whose next estimates are large for their weight (the clouds'
 * cloud_roulette_gain, phase_table.h; 1 elsewhere). A path with w gain >= 1 goes on with its
 * weight unchanged; a cap P_max < 1 would multiply the weight of every such path by 1 / P_max
 * at every vertex, (1 / 0.95)^40 = 7.8 over 40 vertices (an order common among the largest
 * contributions through a cloud of optical depth 10): a heavy tail of rare paths of large
 * weight (measured: docs/notes/clouds.md). The cap from TRACKING_ROULETTE_LONG events on
 * bounds the length of the paths through thick cloud of albedo ~1, where the weights do not
 * fall. */
#ifndef ATMO_MEDIA_TRACKING_H
#define ATMO_MEDIA_TRACKING_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/rng.h"
#endif

#define TRACKING_ROULETTE_LONG 256 /* events from which a path's roulette survival is capped */
#define TRACKING_ROULETTE_CAP 0.95f /* the cap P_max from there on */

ATMO_FN float tracking_max3(vec3 v) { return fmaxf(v.x, fmaxf(v.y, v.z)); }

/* Russian roulette on a weight: unchanged while its largest channel is at least threshold,
 * else kept with probability q = max W / threshold and divided by q, or zero. */
ATMO_FN vec3 tracking_roulette(vec3 W, float threshold, rng_stream *g)
{
    float q = tracking_max3(W) / threshold;
    if (q >= 1.0f)
        return W;
    return q > 0.0f && rng_next(g) < q ? v3_scale(W, 1.0f / q) : v3(0.0f, 0.0f, 0.0f);
}

/* A path's Russian roulette survival probability after `events` scattering events (as its
 * walk counts them) with throughput w: min(P_max, gain x max w), P_max as in the header (and
 * its derivation there). The caller draws u, ends the path where u >= P and divides w by P. */
ATMO_FN float tracking_survival(vec3 w, float gain, int events)
{
    float cap = events < TRACKING_ROULETTE_LONG ? 1.0f : TRACKING_ROULETTE_CAP;
    return fminf(cap, tracking_max3(w) * gain);
}

#endif
