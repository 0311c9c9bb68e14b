/* phase_table.h — a tabulated phase function that can be evaluated and sampled: the format the
 * cloud shell (cloud_shell.h) and the fBm cloud layer (cloud_layer.h) read their droplets'
 * Mie phase function in.
 *
 * A table is `n` float4 rows (P_0, P_1, P_2, theta), theta in radians ascending from 0 to pi,
 * P_c the 4pi-normalised phase function at render wavelength c (host/mie: int P dOmega = 4pi);
 * between rows P is linear in theta. Its sampling CDF is `n` floats, C_j = int_0^theta_j
 * P_1 / (4 pi) dOmega of the middle wavelength (trapezoids in cos theta, host double precision,
 * host/plan/plan_clouds.c), C_0 = 0, C_{n-1} = 1. (phase.h's phase_table_* read another layout:
 * cosines descending with a separate P array.) phase_rows_sample draws a row interval by
 * the CDF (binary search) and cos theta uniformly inside it, so its density per steradian is
 *     q(theta) = (C_{j+1} - C_j) / (2 pi (cos theta_j - cos theta_{j+1}))
 * and returns the weight P_c(theta) / (4 pi q) per wavelength: the estimator stays unbiased
 * for every channel whatever the table's resolution (the weight is ~1 on a fine table).
 * cloud_phase_sample draws from whichever phase a cloud medium (the shell or the layer) uses:
 * the table, Henyey-Greenstein or Jendersie-d'Eon (ATMO_CLOUD_PHASE_*). */
#ifndef ATMO_MEDIA_PHASE_TABLE_H
#define ATMO_MEDIA_PHASE_TABLE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
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

#endif
