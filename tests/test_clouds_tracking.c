/* test_clouds_tracking — the transmittance estimators of kernels/media/majorant_walk.h (delta and
 * ratio tracking under a constant majorant, host build of the shared header), the bias of a naive jittered ray march, and
 * a furnace for the random walk with the clouds' tabulated Mie phase (phase_table.h).
 * labels: unit stat
 *
 * Oracles:
 *   - Homogeneous slab of optical depth tau = 0.1, 1, 10, 40 (length 1 m, majorant 2 sigma, so
 *     half the tentative points are null): E[T] = e^-tau (Beer-Lambert). Delta tracking's
 *     estimate is Bernoulli(e^-tau); ratio tracking's W = (1/2)^k, k ~ Poisson(2 tau), has
 *     E[W^2] = e^{-2 tau (1 - 1/4)} = e^{-3 tau / 2}. Both means must lie within 4.5 of their
 *     analytic standard errors of e^-tau (N = 200000 walks each; a false alarm has p ~ 7e-6).
 *   - Heterogeneous medium sigma(t) = s0 (1 + 0.9 sin(2 pi f t)) on [0, L] with the analytic
 *     optical depth tau = s0 (L + 0.9 (1 - cos(2 pi f L)) / (2 pi f)): the same two estimators
 *     with majorant 1.9 s0, the same bounds (ratio tracking with its sample standard error).
 *   - The naive march: n equal steps sampled at the fractions (i + u) / n with one uniform u per
 *     ray estimates tau without bias (stratified sampling), so by Jensen's inequality
 *     E[e^{-X}] >= e^{-tau}; with X in [X_min, X_max] Taylor's remainder bounds the excess by
 *     e^{-X_min} Var(X) / 2. The excess (by 8192-point quadrature over u, double) must be
 *     positive, within that bound and shrinking with n = 1, 2, 4, 8, and a Monte Carlo run of
 *     the estimator must agree with the quadrature within 4.5 standard errors (the excess is
 *     what the clouds' light march over-estimates; it is printed).
 *   - Furnace: a sphere of radius 1 m, sigma = 5 1/m, albedo 1, in a uniform environment of
 *     radiance 1: whatever the phase function, the radiance of every ray into it is 1. Walks
 *     by delta tracking (majorant = sigma) with new directions from Henyey-Greenstein g = 0.85
 *     (exact sampling, weight 1) and from the cumulus Mie table by its CDF (phase_rows_sample,
 *     weight P / q per wavelength), each with sun guiding 0, 0.15 and 0.3 (phase_table.h's
 *     cloud_phase_direction, weight p / q), must average 1 within 4.5 standard errors in each
 *     channel. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "common/compat.h"
#include "common/phase.h"
#include "common/rng.h"
#include "media/tracking.h"
#include "media/majorant_walk.h"
#include "media/phase_table.h"
#include "atmo/plan.h"
#include "testlib.h"
#include "testscene.h"

#define N_WALKS 200000
#define Z_MAX 4.5

typedef struct medium1d {
    double s0, amp, f, L; /* sigma(t) = s0 (1 + amp sin(2 pi f t)) on [0, L] */
} medium1d;

static double sigma_at(const medium1d *m, double t)
{
    return m->s0 * (1.0 + m->amp * sin(2.0 * M_PI * m->f * t));
}

static double tau_of(const medium1d *m)
{
    if (m->amp == 0.0)
        return m->s0 * m->L;
    return m->s0 * (m->L + m->amp * (1.0 - cos(2.0 * M_PI * m->f * m->L)) / (2.0 * M_PI * m->f));
}

/* The next tentative point of a walk under the constant majorant sigma_bar (one segment). */
static int next_point(majorant_walk *w, float sigma_bar, rng_stream *g)
{
    int ev;
    while ((ev = walk_next(w, g)) == WALK_SEGMENT)
        walk_segment(w, sigma_bar, INFINITY);
    return ev == WALK_POINT;
}

/* One delta-tracking walk: 1 if it leaves the medium without a real collision. */
static double delta_walk(const medium1d *m, float sigma_bar, rng_stream *g)
{
    majorant_walk w = walk_begin((float)m->L, 0.0f);
    while (next_point(&w, sigma_bar, g))
        if (rng_next(g) < sigma_at(m, w.t) / sigma_bar)
            return 0.0;
    return 1.0;
}

/* One ratio-tracking walk: the product of (1 - sigma / sigma_bar) over the tentative points. */
static double ratio_walk(const medium1d *m, float sigma_bar, rng_stream *g)
{
    majorant_walk w = walk_begin((float)m->L, 0.0f);
    vec3 W = v3(1.0f, 1.0f, 1.0f);
    while (next_point(&w, sigma_bar, g)) {
        float s = (float)sigma_at(m, w.t);
        W = walk_ratio(&w, W, v3(s, s, s));
    }
    return W.y;
}

static void check_estimators(const char *what, const medium1d *m, float sigma_bar,
                             double ratio_second_moment)
{
    double T = exp(-tau_of(m)), sum_d = 0.0, sum_r = 0.0, sum_r2 = 0.0;
    for (int i = 0; i < N_WALKS; i++) {
        rng_stream g = rng_stream_stage(11u, (uint)i, 0u, 0u);
        sum_d += delta_walk(m, sigma_bar, &g);
        double r = ratio_walk(m, sigma_bar, &g);
        sum_r += r;
        sum_r2 += r * r;
    }
    double mean_d = sum_d / N_WALKS, mean_r = sum_r / N_WALKS;
    double se_d = sqrt(T * (1.0 - T) / N_WALKS);
    double var_r = ratio_second_moment >= 0.0 ? ratio_second_moment - T * T
                                              : sum_r2 / N_WALKS - mean_r * mean_r;
    double se_r = sqrt(fmax(var_r, 0.0) / N_WALKS);
    printf("%s: tau %.4g  T %.6e  delta %.6e (z %.2f)  ratio %.6e (z %.2f)\n", what, tau_of(m),
           T, mean_d, se_d > 0 ? (mean_d - T) / se_d : 0.0, mean_r,
           se_r > 0 ? (mean_r - T) / se_r : 0.0);
    /* a tiny floor for tau = 40, whose T (4e-18) is below what float walks resolve */
    CHECK_ABS(mean_d, T, Z_MAX * se_d + 1e-15);
    CHECK_ABS(mean_r, T, Z_MAX * se_r + 1e-15);
}

/* X(u) = sum_i sigma(L (i + u) / n) L / n, the naive march's optical depth. */
static double march_depth(const medium1d *m, int n, double u)
{
    double x = 0.0, dt = m->L / n;
    for (int i = 0; i < n; i++)
        x += sigma_at(m, (i + u) * dt) * dt;
    return x;
}

static double check_march(const medium1d *m, int n)
{
    enum { Q = 8192 };
    double tau = tau_of(m), mean_x = 0.0, mean_t = 0.0, mean_x2 = 0.0, x_min = INFINITY;
    for (int k = 0; k < Q; k++) {
        double x = march_depth(m, n, (k + 0.5) / Q);
        mean_x += x / Q;
        mean_x2 += x * x / Q;
        mean_t += exp(-x) / Q;
        x_min = fmin(x_min, x);
    }
    double var = mean_x2 - mean_x * mean_x, excess = mean_t - exp(-tau);
    double bound = exp(-x_min) * var / 2.0;
    CHECK_ABS(mean_x, tau, 1e-6 * tau); /* stratified: unbiased in the optical depth */
    CHECK(excess > 0.0);
    CHECK(excess <= bound * (1.0 + 1e-9));
    /* the estimator itself, by Monte Carlo, against the quadrature */
    double s = 0.0, s2 = 0.0;
    for (int i = 0; i < N_WALKS / 4; i++) {
        double t = exp(-march_depth(m, n, rng_uniform(5u, (uint)i, 0u, 0u)));
        s += t;
        s2 += t * t;
    }
    int N = N_WALKS / 4;
    double mc = s / N, se = sqrt(fmax(s2 / N - mc * mc, 0.0) / N);
    CHECK_ABS(mc, mean_t, Z_MAX * se + 1e-12);
    printf("march n = %d: E[e^-X] %.6f vs e^-tau %.6f: over-estimate %.3e (%.2f %%), Jensen "
           "bound %.3e\n",
           n, mean_t, exp(-tau), excess, 100.0 * excess / exp(-tau), bound);
    return excess;
}

/* Distance from p (inside the unit sphere) along the unit d to its surface. */
static float exit_distance(vec3 p, vec3 d)
{
    float b = v3_dot(p, d), c = v3_dot(p, p) - 1.0f;
    return -b + sqrtf(fmaxf(b * b - c, 0.0f));
}

/* The furnace: rays from outside at impact parameter b into the sphere; phase: HG g = 0.85
 * (rows == NULL) or the table; new directions by phase_table.h's cloud_phase_direction with the
 * sun-guiding probability eps toward the fixed direction `sun`. */
static void furnace(const char *what, const float4 *rows, const float *cdf, int n, float eps)
{
    const float sigma = 5.0f;
    const vec3 sun = v3_normalize(v3(0.3f, 0.8f, 0.52f)), g_hg = v3(0.8f, 0.85f, 0.9f);
    int phase = rows ? ATMO_CLOUD_PHASE_MIE : ATMO_CLOUD_PHASE_HG;
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0}, worst = 0.0;
    long scatterings = 0;
    for (int i = 0; i < N_WALKS / 4; i++) {
        rng_stream g = rng_stream_stage(23u, (uint)i, 0u, 0u);
        float b = sqrtf(rng_next(&g)) * 0.999f; /* uniform over the disc the sphere shows */
        vec3 p = v3(b, -sqrtf(1.0f - b * b), 0.0f), d = v3(0.0f, 1.0f, 0.0f);
        vec3 w = v3(1.0f, 1.0f, 1.0f);
        for (int bounce = 0; bounce < 100000; bounce++) {
            majorant_walk walk = walk_begin(exit_distance(p, d), 0.0f);
            if (!next_point(&walk, sigma, &g))
                break; /* leaves: picks up the environment's radiance 1 */
            p = v3_add(p, v3_scale(d, walk.t));
            float u1 = rng_next(&g), u2 = rng_next(&g);
            vec3 weight;
            d = cloud_phase_direction(phase, g_hg, 20.0f, rows, cdf, n, d, sun, eps, w, u1, u2, &g,
                                      &weight);
            w = v3_mul(w, weight);
            scatterings++;
        }
        float wc[3] = {w.x, w.y, w.z};
        for (int k = 0; k < 3; k++)
            sum[k] += wc[k], sum2[k] += (double)wc[k] * wc[k], worst = fmax(worst, wc[k]);
    }
    int N = N_WALKS / 4;
    for (int k = 0; k < 3; k++) {
        double mean = sum[k] / N, se = sqrt(fmax(sum2[k] / N - mean * mean, 0.0) / N);
        printf("furnace %s, guiding %.2f, channel %d: %.6f +- %.6f (%.2f scatterings per path, "
               "largest weight %.1f)\n",
               what, eps, k, mean, se, (double)scatterings / N, worst);
        CHECK_ABS(mean, 1.0, Z_MAX * se + 1e-6);
    }
}

int main(void)
{
    const double taus[] = {0.1, 1.0, 10.0, 40.0};
    for (int i = 0; i < 4; i++) {
        medium1d m = {taus[i], 0.0, 0.0, 1.0};
        float sigma_bar = (float)(2.0 * taus[i]);
        check_estimators("slab", &m, sigma_bar, exp(-1.5 * taus[i]));
    }
    medium1d het = {0.8, 0.9, 0.37, 2.5};
    check_estimators("sine medium", &het, (float)(1.9 * het.s0), -1.0);

    medium1d bumpy = {1.5, 0.9, 0.83, 2.0};
    double previous = INFINITY;
    for (int n = 1; n <= 8; n *= 2) {
        double excess = check_march(&bumpy, n);
        CHECK(excess < previous);
        previous = excess;
    }

    for (int k = 0; k < 3; k++)
        furnace("HG g = 0.85", NULL, NULL, 0, 0.15f * k);
    atmo_plan p;
    const void *rows, *cdf;
    int n = test_cumulus_phase_table(&p, &rows, &cdf);
    for (int k = 0; k < 3; k++)
        furnace("cumulus Mie table", rows, cdf, n, 0.15f * k);
    atmo_plan_free(&p);
    return test_finish();
}
