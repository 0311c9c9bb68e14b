/* phase_table.h — a tabulated phase function that can be evaluated and sampled: the format the
 * cloud shell (cloud_shell.h) and the fBm cloud layer (cloud_layer.h) read their droplets'
 * Mie phase function in.
 *
 * A table is `n` float4 rows (P_0, P_1, P_2, theta), theta in radians ascending from 0 to pi,
 * P_c the 4pi-normalised phase function at render wavelength c (host/mie: int P dOmega = 4pi);
 * between rows P is linear in theta. Its sampling CDF is `n` floats, C_j = int_0^theta_j
 * P_1 / (4 pi) dOmega of the middle wavelength (trapezoids in cos theta, host double precision,
 * plan_clouds.c), C_0 = 0, C_{n-1} = 1. (phase.h's phase_table_* read another layout:
 * cosines descending with a separate P array.) phase_rows_sample draws a row interval by
 * the CDF (binary search) and cos theta uniformly inside it, so its density per steradian is
 *     q(theta) = (C_{j+1} - C_j) / (2 pi (cos theta_j - cos theta_{j+1}))
 * and returns the weight P_c(theta) / (4 pi q) per wavelength: the estimator stays unbiased
 * for every channel whatever the table's resolution (the weight is ~1 on a fine table).
 * cloud_phase_eval, cloud_phase_sample and cloud_phase_pdf evaluate, draw from and give the
 * sampling density of whichever phase a cloud medium (the shell or the layer) uses: the table,
 * Henyey-Greenstein or Jendersie-d'Eon (ATMO_CLOUD_PHASE_*).
 *
 * Sun guiding (cloud_phase_direction, the new direction at a cloud vertex of the Monte Carlo
 * reference and of the path tracer's volume stage). Light reaches the camera through the sun's
 * next-event estimates, sigma_s p(d . s) E T_sun / sigma_bar at each point of a segment of
 * direction d; the forward peak (the cumulus table's p(1) ~ 560 / sr, ~1000 times its mean)
 * makes them heavy-tailed: the rare paths whose d falls near the sun carry much of the
 * estimate. Detector-directional importance sampling (Buras & Mayer 2011, JQSRT 112, 434-447:
 * DDIS, the detector being the sun of this backward walk) draws the continuation w from
 *     q(w) = (1 - eps) q_p(d . w) + eps q_p(s . w)
 * (q_p the sampler's density: cloud_phase_pdf; the second lobe is the phase function centred
 * on the sun's direction s, drawn by the same sampler and rotated about s) and weighs it
 *     f_c = p_c(d . w) / q(w)                               (per channel c; unbiased: q > 0
 * wherever p_y > 0). Paths head toward the sun eps of the time, so the large p(d . s) of the
 * next segment comes with a small weight: q >= eps p(s . w) bounds the product f p(w . s) by
 * about p(d . w) / eps, and f <= 1 / (1 - eps) on the sampled channel. The lobe is chosen by
 * u1 (u1 < eps: the sun's, with u1 / eps; else (u1 - eps) / (1 - eps)), so no extra number
 * is drawn and eps = 0 draws exactly as cloud_phase_sample with its weight. The price: away
 * from the sun f = 1 / (1 - eps), so a path's weight grows by that at each vertex that does
 * not turn toward the sun, a product that over the tens of vertices of thick cloud spreads the
 * weights into a heavy tail. So the mixture's share is scaled down by the path's throughput,
 *     eps_b = eps / max(1, beta_max)          (beta_max: the largest channel of beta),
 * a choice made from the path's past alone (the estimator stays unbiased). A vertex that does
 * not turn sunward then takes beta to beta / (1 - eps_b): for beta_max <= 1 the factor is
 * 1 / (1 - eps) as before, and above it the growth is additive,
 *     beta / (1 - eps / beta) - beta = eps beta / (beta - eps) <= eps / (1 - eps),
 * so after n such vertices beta_max <= 1 + n eps / (1 - eps) instead of (1 - eps)^-n (eps 0.1
 * and 40 vertices: 5.4 instead of 67), far inside float's range. A Russian roulette weighing
 * survival by the throughput alone would undo the guiding (a path heading to the sun carries a
 * small weight for a large next-event estimate), so the walks weigh it by cloud_roulette_gain
 * (measurements: docs/notes/clouds.md). */
#ifndef ATMO_MEDIA_PHASE_TABLE_H
#define ATMO_MEDIA_PHASE_TABLE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "common/frame.h"
#include "common/phase.h"
#include "common/rng.h"
#include "atmo/gpu_enums.h"
#endif

/* The last row j with rows[j].w <= theta (0 <= j < n - 1). */
ATMO_FN int phase_rows_find(ATMO_GLOBAL const float4 *rows, int n, float theta)
{
    int lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (rows[mid].w <= theta)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* The phase function per steradian at scattering-angle cosine c, one value per wavelength. */
ATMO_FN vec3 phase_rows_eval(ATMO_GLOBAL const float4 *rows, int n, float c)
{
    float theta = acosf(atmo_clamp_cos(c));
    int lo = phase_rows_find(rows, n, theta), hi = n > 1 ? lo + 1 : lo;
    float4 a = rows[lo], b = rows[hi];
    float f = b.w > a.w ? clamp((theta - a.w) / (b.w - a.w), 0.0f, 1.0f) : 0.0f;
    float k = 1.0f / (4.0f * ATMO_PI);
    return v3(mix(a.x, b.x, f) * k, mix(a.y, b.y, f) * k, mix(a.z, b.z, f) * k);
}

/* A scattering-angle cosine drawn from the table by its CDF with the uniform number u, and in
 * *weight the phase function over the density the cosine was drawn with (per wavelength). */
ATMO_FN float phase_rows_sample(ATMO_GLOBAL const float4 *rows, ATMO_GLOBAL const float *cdf,
                                 int n, float u, vec3 *weight)
{
    int lo = 0, hi = n - 1; /* cdf[lo] <= u < cdf[hi] */
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (cdf[mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    float c0 = cosf(rows[lo].w), c1 = cosf(rows[hi].w), mass = cdf[hi] - cdf[lo];
    float f = mass > 0.0f ? clamp((u - cdf[lo]) / mass, 0.0f, 1.0f) : 0.5f;
    float c = atmo_clamp_cos(c0 + f * (c1 - c0));
    float q = mass / (2.0f * ATMO_PI * fmaxf(c0 - c1, 1e-12f));
    vec3 p = phase_rows_eval(rows, n, c);
    *weight = q > 0.0f ? v3_scale(p, 1.0f / q) : v3(0.0f, 0.0f, 0.0f);
    return c;
}

/* The density per steradian with which phase_rows_sample draws the cosine c: its row
 * interval's CDF mass over the interval's solid angle. */
ATMO_FN float phase_rows_pdf(ATMO_GLOBAL const float4 *rows, ATMO_GLOBAL const float *cdf, int n,
                             float c)
{
    int lo = phase_rows_find(rows, n, acosf(atmo_clamp_cos(c))), hi = n > 1 ? lo + 1 : lo;
    float c0 = cosf(rows[lo].w), c1 = cosf(rows[hi].w);
    return (cdf[hi] - cdf[lo]) / (2.0f * ATMO_PI * fmaxf(c0 - c1, 1e-12f));
}

/* A cloud's phase function per steradian at scattering-angle cosine c, per channel
 * (ATMO_CLOUD_PHASE_*: the table `rows`, Henyey-Greenstein with g_hg per channel, or
 * Jendersie-d'Eon for the effective diameter). */
ATMO_FN vec3 cloud_phase_eval(int phase, vec3 g_hg, float diameter_um,
                              ATMO_GLOBAL const float4 *rows, int n, float c)
{
    if (phase == ATMO_CLOUD_PHASE_HG)
        return v3(phase_henyey_greenstein(c, g_hg.x), phase_henyey_greenstein(c, g_hg.y),
                  phase_henyey_greenstein(c, g_hg.z));
    if (phase == ATMO_CLOUD_PHASE_JENDERSIE_DEON) {
        float p = phase_jendersie_deon(c, phase_jendersie_deon_params(diameter_um));
        return v3(p, p, p);
    }
    return phase_rows_eval(rows, n, c);
}

/* A scattering-angle cosine drawn from a cloud's phase function (ATMO_CLOUD_PHASE_*: the table
 * `rows` with its CDF, Henyey-Greenstein with asymmetry g_hg per channel, or Jendersie-d'Eon
 * for the effective diameter) with the uniform number u1, and one more from g for
 * Jendersie-d'Eon's mixture. *weight gets the phase over the density the cosine was drawn with,
 * per channel: the table by its CDF (P / q, phase_rows_sample), Henyey-Greenstein by the middle
 * channel's g (p_c / p_y), Jendersie-d'Eon exactly (1). */
ATMO_FN float cloud_phase_sample(int phase, vec3 g_hg, float diameter_um,
                                 ATMO_GLOBAL const float4 *rows, ATMO_GLOBAL const float *cdf,
                                 int n, float u1, rng_stream *g, vec3 *weight)
{
    *weight = v3(1.0f, 1.0f, 1.0f);
    if (phase == ATMO_CLOUD_PHASE_JENDERSIE_DEON)
        return phase_jendersie_deon_sample(phase_jendersie_deon_params(diameter_um), u1,
                                           rng_next(g));
    if (phase == ATMO_CLOUD_PHASE_HG) {
        float cs = phase_henyey_greenstein_sample(g_hg.y, u1);
        float py = phase_henyey_greenstein(cs, g_hg.y);
        *weight = v3(phase_henyey_greenstein(cs, g_hg.x) / py, 1.0f,
                     phase_henyey_greenstein(cs, g_hg.z) / py);
        return cs;
    }
    return phase_rows_sample(rows, cdf, n, u1, weight);
}

/* The density per steradian with which cloud_phase_sample draws the cosine c: the table's
 * (phase_rows_pdf), Henyey-Greenstein's of the middle channel, Jendersie-d'Eon's own. */
ATMO_FN float cloud_phase_pdf(int phase, vec3 g_hg, float diameter_um,
                              ATMO_GLOBAL const float4 *rows, ATMO_GLOBAL const float *cdf, int n,
                              float c)
{
    if (phase == ATMO_CLOUD_PHASE_HG)
        return phase_henyey_greenstein(c, g_hg.y);
    if (phase == ATMO_CLOUD_PHASE_JENDERSIE_DEON)
        return phase_jendersie_deon(c, phase_jendersie_deon_params(diameter_um));
    return phase_rows_pdf(rows, cdf, n, c);
}

/* The mixture's density q(w) per steradian of the header: (1 - eps) q_p(d . w) + eps q_p(s . w)
 * for the unit vectors d (the path's direction), sun and w. */
ATMO_FN float cloud_guiding_pdf(int phase, vec3 g_hg, float diameter_um,
                                ATMO_GLOBAL const float4 *rows, ATMO_GLOBAL const float *cdf,
                                int n, vec3 d, vec3 sun, float eps, vec3 w)
{
    float c_d = atmo_clamp_cos(v3_dot(d, w)), c_s = atmo_clamp_cos(v3_dot(sun, w));
    return (1.0f - eps) * cloud_phase_pdf(phase, g_hg, diameter_um, rows, cdf, n, c_d) +
           eps * cloud_phase_pdf(phase, g_hg, diameter_um, rows, cdf, n, c_s);
}

/* The probability of the sun's lobe at a vertex of a path of throughput beta, for the
 * guiding probability eps: eps / max(1, beta_max) (the header's eps_b). */
ATMO_FN float cloud_guiding_share(float eps, vec3 beta)
{
    return eps / fmaxf(1.0f, fmaxf(beta.x, fmaxf(beta.y, beta.z)));
}

/* The new direction at a cloud vertex reached along the unit d by a path of throughput beta,
 * with the unit sun direction `sun` and the sun-guiding probability eps (0 <= eps < 1): drawn
 * from the mixture q of the header with the share eps_b = cloud_guiding_share(eps, beta), the
 * uniform numbers u1 (lobe and cosine) and u2 (azimuth 2 pi u2), and one more from g for
 * Jendersie-d'Eon's mixture; *weight gets p_c(d . w) / q(w) per channel. */
ATMO_FN vec3 cloud_phase_direction(int phase, vec3 g_hg, float diameter_um,
                                   ATMO_GLOBAL const float4 *rows, ATMO_GLOBAL const float *cdf,
                                   int n, vec3 d, vec3 sun, float eps, vec3 beta, float u1,
                                   float u2, rng_stream *g, vec3 *weight)
{
    eps = cloud_guiding_share(eps, beta);
    int guided = u1 < eps;
    float u = guided ? u1 / eps : (u1 - eps) / (1.0f - eps);
    float c = cloud_phase_sample(phase, g_hg, diameter_um, rows, cdf, n, fminf(u, 1.0f), g,
                                 weight);
    vec3 w = frame_direction(guided ? sun : d, c, 2.0f * ATMO_PI * u2);
    if (eps > 0.0f) {
        float q = cloud_guiding_pdf(phase, g_hg, diameter_um, rows, cdf, n, d, sun, eps, w);
        vec3 p = cloud_phase_eval(phase, g_hg, diameter_um, rows, n,
                                  atmo_clamp_cos(v3_dot(d, w)));
        *weight = q > 0.0f ? v3_scale(p, 1.0f / q) : v3(0.0f, 0.0f, 0.0f);
    }
    return w;
}

/* The factor a Russian roulette after a cloud vertex multiplies the path's throughput by to
 * get its survival probability: 4 pi p_c(d . s) at most over the channels, at least 1 (p_sun:
 * the phase at the cosine between the new direction d and the sun). A path the sun guiding sent
 * toward the sun carries a small weight for the large p of its next-event estimates; weighed by
 * its throughput alone, it would be ended nearly always and, the few times it survives, be
 * rescaled to the large estimate the guiding removed. */
ATMO_FN float cloud_roulette_gain(vec3 p_sun)
{
    return fmaxf(1.0f, 4.0f * ATMO_PI * fmaxf(p_sun.x, fmaxf(p_sun.y, p_sun.z)));
}

#endif
