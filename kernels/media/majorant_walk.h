/* majorant_walk.h — the one majorant walk of the Monte Carlo estimators: the tentative
 * collisions along a ray under a piecewise-constant majorant, handed one at a time to the
 * caller, which decides what each one is (the shape of pbrt-v4's SampleT_maj, as an iterator:
 * OpenCL C has no function pointers, so the per-point callback is the caller's loop body).
 *
 *     majorant_walk w = walk_begin(end, least);
 *     for (int ev; (ev = walk_next(&w, g)) != WALK_END;) {
 *         if (ev == WALK_SEGMENT) { walk_segment(&w, sigma_bar, seg_end); continue; }
 *         ... WALK_POINT at w.t, rate w.sigma_bar: walk_ratio, walk_pick ...
 *     }
 *
 * Math. Along the ray x(t), t in [0, end], let sigma_bar(t) >= sigma_t(t) (1/m) be a majorant,
 * constant on segments [t_i, t_i+1) that the caller gives as the walk reaches them (WALK_SEGMENT:
 * the walk stands at t_i and asks for the rate and its end; a medium's bound, a majorant grid's
 * cell, zero over empty space). Tentative collisions are a Poisson process of rate sigma_bar(t);
 * with the majorant's optical depth Tau(a, b) = int_a^b sigma_bar dt, the next point after t
 * lies where Tau(t, t') reaches tau = -ln(1 - u), u uniform in [0, 1) (the time change of a
 * Poisson process to unit rate; 1 - u in (0, 1], so tau is finite). walk_next spends tau over
 * the current segment: t' = t + tau / sigma_bar if that is before the segment's end, else it
 * keeps tau - sigma_bar (t_i+1 - t) for the next segment. A segment of rate zero holds no point
 * and draws no number (empty space costs one segment query). A floor `least` (1/m) on the rate
 * keeps a short segment from seeing no point at all (any rate >= sigma_t stays unbiased).
 *
 * Policies, at each point (WALK_POINT) with the media's sigma_t and sigma_s,k there:
 *   - ratio tracking (Novak et al. 2014, walk_ratio): W = prod over the points before t of
 *     (1 - sigma_t / sigma_bar) has E[W] = T(0, t) = exp(-int_0^t sigma_t); with W at the end it
 *     is the transmittance query of shadow rays. By Campbell's theorem
 *     E[sum_points W f / sigma_bar] = int_0^end T f dt, so an estimate made at every point
 *     (next-event estimation, f = sigma_s p L_sun) samples the in-scattering of the whole ray.
 *   - delta / spectral tracking (Woodcock; Kutz et al. 2017, walk_pick): the point is a real
 *     scattering by component k or a null collision, picked with probabilities proportional to
 *     max_c w_c sigma_s,k,c and max_c w_c (sigma_bar - sigma_t)_c; the vec3 weight w is
 *     multiplied by sigma_event / (sigma_bar P_event), so every channel is unbiased with one
 *     shared path, and absorption is folded into the weight (there is no absorption event:
 *     the walk goes on through a point that absorbs, with a smaller weight). With one channel
 *     and albedo 1 it is plain delta tracking, w = 1: the first scattering has density
 *     T(0, t) sigma_s(t).
 * Units: metres, 1/m. Random numbers: the caller's stream, one per tentative point (none over a
 * segment of rate zero), one per pick. */
#ifndef ATMO_MEDIA_MAJORANT_WALK_H
#define ATMO_MEDIA_MAJORANT_WALK_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/rng.h"
#include "media/tracking.h"
#endif

/* walk_next's events */
#define WALK_END 0     /* past the walk's end: no more points */
#define WALK_POINT 1   /* a tentative collision at w.t, rate w.sigma_bar there */
#define WALK_SEGMENT 2 /* at w.t the segment ended: give the next one (walk_segment) */
/* walk_pick's answer for a null collision (a scattering answers its component, >= 0) */
#define WALK_NULL (-1)

typedef struct majorant_walk {
    float t, end;   /* the current point and the walk's end, m */
    float sigma_bar; /* the majorant on the current segment, 1/m */
    float seg_end;   /* the current segment's end, m */
    float least;     /* the floor on the rate, 1/m */
    float tau;       /* the majorant's optical depth left to the next point (< 0: not drawn) */
} majorant_walk;

/* A walk over [0, end] whose rate is at least `least`; its first event asks for a segment. */
ATMO_FN majorant_walk walk_begin(float end, float least)
{
    majorant_walk w;
    w.t = 0.0f;
    w.end = end;
    w.sigma_bar = 0.0f;
    w.seg_end = 0.0f;
    w.least = least;
    w.tau = -1.0f;
    return w;
}

/* The segment from w->t: rate max(sigma_bar, least) (>= 0) up to seg_end. */
ATMO_FN void walk_segment(majorant_walk *w, float sigma_bar, float seg_end)
{
    w->sigma_bar = fmaxf(sigma_bar, w->least);
    w->seg_end = fmaxf(seg_end, w->t);
}

/* The next event (see the top of the file). */
ATMO_FN int walk_next(majorant_walk *w, rng_stream *g)
{
    if (w->t >= w->end)
        return WALK_END;
    if (w->t >= w->seg_end)
        return WALK_SEGMENT;
    if (w->sigma_bar > 0.0f) {
        if (w->tau < 0.0f)
            w->tau = -logf(1.0f - rng_next(g));
        float t = w->t + w->tau / w->sigma_bar;
        if (t < w->seg_end) {
            w->t = t;
            w->tau = -1.0f;
            return t < w->end ? WALK_POINT : WALK_END;
        }
        w->tau = fmaxf(w->tau - (w->seg_end - w->t) * w->sigma_bar, 0.0f);
    }
    w->t = w->seg_end;
    return w->t < w->end ? WALK_SEGMENT : WALK_END;
}

/* Ratio tracking: the weight W after a point with extinction sigma_t. */
ATMO_FN vec3 walk_ratio(const majorant_walk *w, vec3 W, vec3 sigma_t)
{
    return v3_mul(W, v3_sub(v3(1.0f, 1.0f, 1.0f), v3_scale(sigma_t, 1.0f / w->sigma_bar)));
}

/* Spectral (delta) tracking at a point with scattering coefficients sigma[0..count-1] and
 * extinction sigma_t: the component that scatters, or WALK_NULL; *ws takes the event's weight.
 * count <= 4. */
ATMO_FN int walk_pick(const majorant_walk *w, rng_stream *g, vec3 *ws, const vec3 *sigma,
                      int count, vec3 sigma_t)
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
    return WALK_NULL;
}

#endif
