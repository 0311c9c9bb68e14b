/* tracking.h — free-flight sampling through a majorant: the walk that the Monte Carlo
 * estimators share (method reference's view rays, bounces and shadow rays alike).
 *
 * Along a ray, tentative collisions form a Poisson process whose rate sigma_bar(t) >= sigma_t(t)
 * everywhere on it: constant (tracking_begin), or piecewise constant over the segments a
 * majorant iterator yields (the cloud layer's majorant grid, cloud_majorant.h; pbrt-v4's
 * SampleT_maj has the same shape). By the time change of a Poisson process, the next point
 * lies where the majorant's optical depth from the current one reaches tau = -ln(1 - u)
 * (1 - u in (0, 1], so the log is finite): tracking_advance spends tau over the current segment
 * and reports whether the point falls inside it; if not, the caller's iterator gives the next
 * segment (tracking_segment) and the rest of tau is spent there. A constant majorant is one
 * segment to infinity, tracking_next: step -ln(1 - u) / sigma_bar. Walked one point at a time
 * (the loop body is the per-point callback), the points serve
 *   - ratio tracking (Novak et al. 2014): T(0, t) is estimated without bias by
 *     W = prod over the points before t of (1 - sigma_t / sigma_bar) (tracking_ratio), and by
 *     Campbell's theorem E[sum W sigma_s / sigma_bar f] = int T sigma_s f dt, so a next-event
 *     estimate at every point samples the in-scattering along the whole ray (sigma_bar the
 *     rate at that point);
 *   - spectral tracking (Kutz et al. 2017, absorption folded into the weight): at each point one
 *     of the events "scatter by component k" or "null" is picked with probability proportional
 *     to the maximum over channels of w sigma_s,k and of w (sigma_bar - sigma_t), and the vec3
 *     weight w is multiplied by sigma_event / (sigma_bar P_event) (tracking_spectral_pick), so
 *     every channel stays unbiased with one shared path;
 *   - delta tracking, the same with one channel and w = 1.
 * Russian roulette on a weight that has become small (tracking_roulette: kept with probability
 * q = max W / threshold and divided by q) keeps every estimate linear in W unbiased and ends
 * walks through opaque media after a few optical depths instead of their whole length.
 * The walk draws its numbers from the caller's rng stream (rng.h), one per tentative point (and
 * one per roulette).
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

typedef struct tracking_walk {
    float t, end, sigma_bar; /* the current point, the ray's end (m), the majorant (1/m) there */
    float seg_end;           /* sigma_bar holds up to here (INFINITY: to the end) */
} tracking_walk;

ATMO_FN tracking_walk tracking_begin(float end, float sigma_bar)
{
    tracking_walk w;
    w.t = 0.0f;
    w.end = end;
    w.sigma_bar = sigma_bar;
    w.seg_end = INFINITY;
    return w;
}

/* Steps to the next tentative point under a constant majorant; 0 once the walk has passed the
 * end. */
ATMO_FN int tracking_next(tracking_walk *w, rng_stream *g)
{
    w->t += -logf(1.0f - rng_next(g)) / w->sigma_bar;
    return w->t < w->end;
}

/* The majorant's optical depth to the next tentative point, -ln(1 - u). */
ATMO_FN float tracking_depth(rng_stream *g) { return -logf(1.0f - rng_next(g)); }

/* Spends *tau in the current segment: 1 with w->t at the point if it falls before the
 * segment's end, else 0 with w->t at the segment's end and *tau reduced by the segment's
 * optical depth (the caller then sets the next segment or stops at w->end). */
ATMO_FN int tracking_advance(tracking_walk *w, float *tau)
{
    float t = w->t + *tau / w->sigma_bar;
    if (t < w->seg_end) {
        w->t = t;
        return 1;
    }
    *tau = fmaxf(*tau - (w->seg_end - w->t) * w->sigma_bar, 0.0f);
    w->t = w->seg_end;
    return 0;
}

/* The next segment: rate sigma_bar (> 0) from w->t up to seg_end (>= w->t). */
ATMO_FN void tracking_segment(tracking_walk *w, float sigma_bar, float seg_end)
{
    w->sigma_bar = sigma_bar;
    w->seg_end = fmaxf(seg_end, w->t);
}

ATMO_FN float tracking_max3(vec3 v) { return fmaxf(v.x, fmaxf(v.y, v.z)); }

/* The ratio-tracking weight after a point with extinction sigma_t. */
ATMO_FN vec3 tracking_ratio(const tracking_walk *w, vec3 W, vec3 sigma_t)
{
    return v3_mul(W, v3_sub(v3(1.0f, 1.0f, 1.0f), v3_scale(sigma_t, 1.0f / w->sigma_bar)));
}

/* Spectral tracking at a point with scattering coefficients sigma[0..count-1] and extinction
 * sigma_t: returns the component that scatters, or -1 for a null collision, and updates the
 * weight *ws. count <= 4. */
ATMO_FN int tracking_spectral_pick(const tracking_walk *w, rng_stream *g, vec3 *ws,
                                   const vec3 *sigma, int count, vec3 sigma_t)
{
    float sb = w->sigma_bar, q[4], total = 0.0f;
    vec3 sigma_n = v3_sub(v3(sb, sb, sb), sigma_t);
    for (int k = 0; k < count; k++)
        total += q[k] = tracking_max3(v3_mul(*ws, sigma[k]));
    float q_n = tracking_max3(v3_mul(*ws, sigma_n));
    total += q_n; /* q_n > 0 while ws > 0: sigma_bar > sigma_t */
    float u = rng_next(g) * total, below = 0.0f;
    for (int k = 0; k < count; k++) {
        below += q[k];
        if (u < below) {
            *ws = v3_scale(v3_mul(*ws, sigma[k]), total / (q[k] * sb));
            return k;
        }
    }
    *ws = v3_scale(v3_mul(*ws, sigma_n), total / (q_n * sb));
    return -1;
}

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
