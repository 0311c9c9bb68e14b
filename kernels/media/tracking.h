/* tracking.h — free-flight sampling through a majorant: the walk that the Monte Carlo
 * estimators share (method reference's paths; delta tracking through a medium's majorant grid
 * takes the same steps).
 *
 * Along a ray, tentative collisions form a homogeneous Poisson process of rate sigma_bar >=
 * sigma_t everywhere on it: steps -ln(1 - u) / sigma_bar (1 - u in (0, 1], so the log is
 * finite). Walked one point at a time (tracking_next, the per-point callback's loop), the
 * points serve
 *   - ratio tracking (Novak et al. 2014): T(0, t) is estimated without bias by
 *     W = prod over the points before t of (1 - sigma_t / sigma_bar) (tracking_ratio), and by
 *     Campbell's theorem E[sum W sigma_s / sigma_bar f] = int T sigma_s f dt, so a next-event
 *     estimate at every point samples the in-scattering along the whole ray;
 *   - spectral tracking (Kutz et al. 2017, absorption folded into the weight): at each point one
 *     of the events "scatter by component k" or "null" is picked with probability proportional
 *     to the maximum over channels of w sigma_s,k and of w (sigma_bar - sigma_t), and the vec3
 *     weight w is multiplied by sigma_event / (sigma_bar P_event) (tracking_spectral_pick), so
 *     every channel stays unbiased with one shared path;
 *   - delta tracking, the same with one channel and w = 1.
 * The walk draws its numbers from the caller's rng stream (rng.h), one per step. */
#ifndef ATMO_MEDIA_TRACKING_H
#define ATMO_MEDIA_TRACKING_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/rng.h"
#endif

typedef struct tracking_walk {
    float t, end, sigma_bar; /* the current point, the ray's end (m), the majorant (1/m) */
} tracking_walk;

ATMO_FN tracking_walk tracking_begin(float end, float sigma_bar)
{
    tracking_walk w;
    w.t = 0.0f;
    w.end = end;
    w.sigma_bar = sigma_bar;
    return w;
}

/* Steps to the next tentative point; 0 once the walk has passed the end. */
ATMO_FN int tracking_next(tracking_walk *w, rng_stream *g)
{
    w->t += -logf(1.0f - rng_next(g)) / w->sigma_bar;
    return w->t < w->end;
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

#endif
