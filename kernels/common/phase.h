/* phase.h — phase functions, per steradian (each integrates to 1 over the sphere).
 *
 * nu is the cosine of the scattering angle (1 = forward).
 *   Rayleigh:          p(nu) = 3 (1 + nu^2) / (16 pi)
 *   Henyey-Greenstein: p(nu) = (1 - g^2) / (4 pi (1 + g^2 - 2 g nu)^(3/2))
 *   Cornette-Shanks:   p(nu) = 3/(8 pi) (1 - g^2)/(2 + g^2) (1 + nu^2)/(1 + g^2 - 2 g nu)^(3/2)
 *                      (Cornette & Shanks 1992, eq. 4; its mean cosine is 3g(4+g^2)/(5(2+g^2)))
 * Float precision for g near 1: the forward peak has 1 + g^2 - 2 g nu ~ (1 - g)^2, which the
 * textbook form gets by cancellation (an absolute error of ~1e-7 against 2.5e-5 at g = 0.995, a
 * 0.6 % error in p). It is formed instead as (1 - g)^2 + 2 g (1 - nu), a sum of non-negative
 * terms with 1 - nu exact for nu >= 0.5 (Sterbenz), and 1 - g^2 as (1 - g)(1 + g).
 * Shared by kernels and host tests (compat.h). */
#ifndef ATMO_PHASE_H
#define ATMO_PHASE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#endif

ATMO_FN float phase_rayleigh(float nu)
{
    return 3.0f / (16.0f * ATMO_PI) * (1.0f + nu * nu);
}

/* 1 + g^2 - 2 g nu without cancellation in the lobe's peak (see above; mirrored for g < 0) */
ATMO_FN float phase_hg_denominator(float nu, float g)
{
    float a = 1.0f - fabsf(g);
    return fmaxf(a * a + 2.0f * fabsf(g) * (1.0f - (g < 0.0f ? -nu : nu)), 0.0f);
}

ATMO_FN float phase_henyey_greenstein(float nu, float g)
{
    float denom = phase_hg_denominator(nu, g);
    return (1.0f - g) * (1.0f + g) / (4.0f * ATMO_PI * denom * sqrtf(denom));
}

ATMO_FN float phase_cornette_shanks(float nu, float g)
{
    float denom = phase_hg_denominator(nu, g);
    return 3.0f / (8.0f * ATMO_PI) * (1.0f - g) * (1.0f + g) / (2.0f + g * g) * (1.0f + nu * nu) /
           (denom * sqrtf(denom));
}

/* ---- sampling ------------------------------------------------------------------------------
 * Each sampler maps uniform numbers u1 (inversion) and u2 (lobe choice in mixtures) in [0, 1) to
 * the cosine of the scattering angle; the azimuth is uniform and left to the caller. Each pdf is
 * per steradian and equals the phase function where the sampling is exact (all but the table,
 * whose pdf is its own piecewise-constant density).
 *   HG:              exact inversion, mu = (1 + g^2 - s^2) / (2 g), s = (1 - g^2)/(1 - g + 2 g u),
 *                    computed as 1 - mu = (s + 1 - g)(1 - g)(1 - u) / (1 - g + 2 g u): no
 *                    cancellation in a forward peak, and no division by g (g = 0 gives 2u - 1).
 *   Draine (2003):   p_D = HG(g) (1 + alpha mu^2) / (1 + alpha (1 + 2 g^2)/3). Its CDF in closed
 *                    form, with t = sqrt(1 + g^2 - 2 g mu) and c = 1 + g^2:
 *                    A(mu) = (1 - g^2)/(2 N g) [1/t + alpha/(4 g^2) (c^2/t + 2 c t - t^3/3)],
 *                    inverted exactly (to float rounding) by Newton's method safeguarded with
 *                    bisection, started from the HG sample. (Jendersie & d'Eon give a closed-form
 *                    quartic root; Newton is simpler to keep accurate in float.)
 *   Cornette-Shanks: is Draine with alpha = 1, and is sampled as such.
 *   two-term HG:     w HG(g1) + (1 - w) HG(g2), lobe chosen by u2.
 *   Jendersie & d'Eon 2023 fit for droplet diameter d (um, 5..50):
 *                    (1 - w_D) HG(g_HG) + w_D Draine(g_D, alpha), lobe chosen by u2.
 *   table:           CDF on the table's angle grid (host/mie/mie_table.c), binary search, then
 *                    linear inversion in cos(theta) within the interval. */

ATMO_FN float phase_henyey_greenstein_sample(float g, float u1)
{
    float a = 1.0f - g, d = a + 2.0f * g * u1;
    float s = a * (1.0f + g) / d;
    return atmo_clamp_cos(1.0f - (s + a) * a * (1.0f - u1) / d);
}

ATMO_FN float phase_henyey_greenstein_pdf(float nu, float g) { return phase_henyey_greenstein(nu, g); }

ATMO_FN float phase_draine(float nu, float g, float alpha)
{
    return phase_henyey_greenstein(nu, g) * (1.0f + alpha * nu * nu) /
           (1.0f + alpha * (1.0f + 2.0f * g * g) / 3.0f);
}

ATMO_FN float phase_draine_pdf(float nu, float g, float alpha) { return phase_draine(nu, g, alpha); }

/* Probability that the cosine is below nu (see above; the g -> 0 limit below |g| = 1e-3). */
ATMO_FN float phase_draine_cdf(float nu, float g, float alpha)
{
    float N = 1.0f + alpha * (1.0f + 2.0f * g * g) / 3.0f;
    if (fabsf(g) < 1e-3f)
        return (nu + 1.0f + alpha * (nu * nu * nu + 1.0f) / 3.0f) / (2.0f * N);
    float c = 1.0f + g * g, k = alpha / (4.0f * g * g);
    float t = sqrtf(phase_hg_denominator(nu, g)), t0 = 1.0f + g; /* t0: nu = -1 */
    float a = 1.0f / t + k * (c * c / t + 2.0f * c * t - t * t * t / 3.0f);
    float a0 = 1.0f / t0 + k * (c * c / t0 + 2.0f * c * t0 - t0 * t0 * t0 / 3.0f);
    return clamp((1.0f - g * g) / (2.0f * N * g) * (a - a0), 0.0f, 1.0f);
}

ATMO_FN float phase_draine_sample(float g, float alpha, float u1)
{
    float lo = -1.0f, hi = 1.0f, mu = phase_henyey_greenstein_sample(g, u1);
    for (int i = 0; i < 40; i++) {
        float f = phase_draine_cdf(mu, g, alpha) - u1;
        if (f < 0.0f)
            lo = mu;
        else
            hi = mu;
        float d = 2.0f * ATMO_PI * phase_draine(mu, g, alpha);
        float next = mu - f / d;
        if (!(next > lo && next < hi)) /* Newton left the bracket: bisect */
            next = 0.5f * (lo + hi);
        if (fabsf(next - mu) < 1e-7f || hi - lo < 1e-7f)
            return next;
        mu = next;
    }
    return mu;
}

ATMO_FN float phase_cornette_shanks_sample(float g, float u1) { return phase_draine_sample(g, 1.0f, u1); }

ATMO_FN float phase_cornette_shanks_pdf(float nu, float g) { return phase_cornette_shanks(nu, g); }

ATMO_FN float phase_two_term_hg(float nu, float g1, float g2, float w)
{
    return w * phase_henyey_greenstein(nu, g1) + (1.0f - w) * phase_henyey_greenstein(nu, g2);
}

ATMO_FN float phase_two_term_hg_pdf(float nu, float g1, float g2, float w)
{
    return phase_two_term_hg(nu, g1, g2, w);
}

ATMO_FN float phase_two_term_hg_sample(float g1, float g2, float w, float u1, float u2)
{
    return phase_henyey_greenstein_sample(u2 < w ? g1 : g2, u1);
}

/* Jendersie & d'Eon 2023 fit, droplet diameter d in um (5 <= d <= 50). */
typedef struct phase_jd_params {
    float g_hg, g_d, alpha, w_d;
} phase_jd_params;

ATMO_FN phase_jd_params phase_jendersie_deon_params(float d)
{
    phase_jd_params p;
    p.g_hg = expf(-0.0990567f / (d - 1.67154f));
    p.g_d = expf(-2.20679f / (d + 3.91029f) - 0.428934f);
    p.alpha = expf(3.62489f - 8.29288f / (d + 5.52825f));
    p.w_d = expf(-0.599085f / (d - 0.641583f) - 0.665888f);
    return p;
}

ATMO_FN float phase_jendersie_deon(float nu, phase_jd_params p)
{
    return (1.0f - p.w_d) * phase_henyey_greenstein(nu, p.g_hg) + p.w_d * phase_draine(nu, p.g_d, p.alpha);
}

ATMO_FN float phase_jendersie_deon_pdf(float nu, phase_jd_params p) { return phase_jendersie_deon(nu, p); }

ATMO_FN float phase_jendersie_deon_sample(phase_jd_params p, float u1, float u2)
{
    return u2 < p.w_d ? phase_draine_sample(p.g_d, p.alpha, u1)
                      : phase_henyey_greenstein_sample(p.g_hg, u1);
}

/* Tabulated phase: mu[0..n-1] descending from 1 to -1, P 4pi-normalised, cdf ascending 0..1. */
ATMO_FN int phase_table_interval(const ATMO_GLOBAL float *mu, int n, float nu)
{
    int lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (mu[mid] >= nu)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

ATMO_FN float phase_table(float nu, const ATMO_GLOBAL float *mu, const ATMO_GLOBAL float *P, int n)
{
    int i = phase_table_interval(mu, n, nu);
    float t = (mu[i] - nu) / (mu[i] - mu[i + 1]);
    return mix(P[i], P[i + 1], clamp(t, 0.0f, 1.0f)) / (4.0f * ATMO_PI);
}

ATMO_FN float phase_table_pdf(float nu, const ATMO_GLOBAL float *mu, const ATMO_GLOBAL float *cdf, int n)
{
    int i = phase_table_interval(mu, n, nu);
    return (cdf[i + 1] - cdf[i]) / (2.0f * ATMO_PI * (mu[i] - mu[i + 1]));
}

ATMO_FN float phase_table_sample(const ATMO_GLOBAL float *mu, const ATMO_GLOBAL float *cdf, int n, float u1)
{
    int lo = 0, hi = n - 1; /* cdf[lo] <= u1 < cdf[hi] */
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (cdf[mid] <= u1)
            lo = mid;
        else
            hi = mid;
    }
    float w = cdf[hi] - cdf[lo];
    float t = w > 0.0f ? (u1 - cdf[lo]) / w : 0.5f;
    return mix(mu[lo], mu[hi], t);
}

#endif
