/* test_majorant_walk — the one majorant walk (kernels/media/majorant_walk.h, host build of the
 * shared header): its tentative points under a piecewise-constant majorant, delta and spectral
 * tracking's collisions, ratio tracking's transmittance.
 * labels: unit stat
 *
 * Media (1-D, along t in metres):
 *   - homogeneous: sigma_t = 2 1/m to infinity;
 *   - piecewise, two majorant segments and an empty gap: sigma_t = 1 on [0, 0.5) under the
 *     majorant 1.5, 0 on [0.5, 1.2) under the majorant 0 (empty space), 4 on [1.2, 2) under 5;
 *     per channel the extinction is scaled by (0.5, 1, 1.2) for ratio tracking.
 * Oracles:
 *   - collision distances (chi-square): the first point of the homogeneous medium under the
 *     majorant sigma_t (every point real), and its first real collision under 3 sigma_t by delta
 *     tracking (walk_pick, albedo 1), have the CDF F(t) = 1 - exp(-2 t); in the piecewise medium
 *     delta tracking's first collision has F(t) = 1 - exp(-tau(t)), tau the optical depth
 *     above, and it passes with probability exp(-3.7). The values u = F(t) fall in 32
 *     bins of equal probability (plus the pass) and the chi-square statistic of N = 200000
 *     walks must stay below the critical value at p = 1e-4 (testlib's Wilson-Hilferty); no
 *     point may lie in the gap.
 *   - ratio tracking (z-test): the mean of W at the end of the piecewise medium must lie within
 *     4.5 of its sample standard errors of exp(-tau_c), tau_c = 3.7 (0.5, 1, 1.2) per channel.
 *   - spectral tracking with absorption (z-test): a homogeneous slab of length 1 with
 *     sigma_t = (0.5, 1, 2), albedo (0.9, 0.5, 0.99), majorant 2.5: the weight of the walks
 *     that pass has mean exp(-sigma_t) per channel (absorption is folded into the weight:
 *     E = sum_k e^{-a} a^k / k! (1 - sigma_t / sigma_bar)^k = e^{-sigma_t}, a = sigma_bar L), and
 *     the weight of the walks that scatter has mean (sigma_s / sigma_t)(1 - e^{-sigma_t}).
 *   - the floor: in an empty medium (majorant 0) with least = 3 1/m over 1 m the number of
 *     points is Poisson with mean 3 (z-test) and W = 1 exactly; with least = 0 the walk draws no
 *     random number at all. */
#include <math.h>
#include <stdio.h>
#include "common/compat.h"
#include "common/rng.h"
#include "media/tracking.h"
#include "media/majorant_walk.h"
#include "testlib.h"

#define N_WALKS 200000
#define N_BINS 32
#define Z_MAX 4.5

/* The piecewise medium: extinction (channel 1) and majorant at t, and the segment's end. */
static float piece(float t, float *sigma, float *seg_end)
{
    if (t < 0.5f) {
        *sigma = 1.0f, *seg_end = 0.5f;
        return 1.5f;
    }
    if (t < 1.2f) {
        *sigma = 0.0f, *seg_end = 1.2f;
        return 0.0f;
    }
    *sigma = 4.0f, *seg_end = INFINITY;
    return 5.0f;
}

static double piece_tau(double t)
{
    if (t < 0.5)
        return t;
    if (t < 1.2)
        return 0.5;
    return 0.5 + 4.0 * (t - 1.2);
}

/* The next point of a walk through the piecewise medium; *sigma its extinction there. */
static int piece_next(majorant_walk *w, rng_stream *g, float *sigma)
{
    int ev;
    float seg_end;
    while ((ev = walk_next(w, g)) == WALK_SEGMENT) {
        float sigma_bar = piece(w->t, sigma, &seg_end);
        walk_segment(w, sigma_bar, seg_end);
    }
    if (ev == WALK_POINT)
        piece(w->t, sigma, &seg_end);
    return ev == WALK_POINT;
}

/* The next point under a constant majorant (one segment to infinity). */
static int constant_next(majorant_walk *w, float sigma_bar, rng_stream *g)
{
    int ev;
    while ((ev = walk_next(w, g)) == WALK_SEGMENT)
        walk_segment(w, sigma_bar, INFINITY);
    return ev == WALK_POINT;
}

static double chi2(const long *count, const double *p, int bins, long n)
{
    double x = 0.0;
    for (int i = 0; i < bins; i++) {
        double e = p[i] * (double)n;
        x += ((double)count[i] - e) * ((double)count[i] - e) / e;
    }
    return x;
}

/* The homogeneous medium: the first point under sigma_bar = sigma (delta = 0) or the first real
 * collision under 3 sigma by delta tracking (delta = 1). */
static void check_homogeneous(int delta)
{
    const float sigma = 2.0f, sigma_bar = delta ? 3.0f * sigma : sigma;
    long count[N_BINS] = {0};
    double p[N_BINS];
    for (int i = 0; i < N_BINS; i++)
        p[i] = 1.0 / N_BINS;
    for (int i = 0; i < N_WALKS; i++) {
        rng_stream g = rng_stream_stage(5u, (uint)i, (uint)delta, 0u);
        majorant_walk w = walk_begin(INFINITY, 0.0f);
        vec3 ws = v3(1.0f, 1.0f, 1.0f), st = v3(sigma, sigma, sigma);
        while (constant_next(&w, sigma_bar, &g))
            if (!delta || walk_pick(&w, &g, &ws, &st, 1, st) == 0)
                break;
        double u = 1.0 - exp(-(double)sigma * w.t);
        count[u < 1.0 ? (int)(u * N_BINS) : N_BINS - 1]++;
    }
    double x = chi2(count, p, N_BINS, N_WALKS), crit = test_chi2_critical_1e4(N_BINS - 1);
    printf("homogeneous, %s: chi2 %.1f (critical %.1f, %d dof)\n",
           delta ? "delta tracking under 3 sigma" : "majorant = sigma", x, crit, N_BINS - 1);
    CHECK(x < crit);
}

/* Delta tracking's first collision in the piecewise medium (and no point in its gap). */
static void check_piecewise_collisions(void)
{
    const double tau_end = piece_tau(2.0), pass = exp(-tau_end);
    long count[N_BINS + 1] = {0}, in_gap = 0;
    double p[N_BINS + 1];
    for (int i = 0; i < N_BINS; i++)
        p[i] = (1.0 - pass) / N_BINS;
    p[N_BINS] = pass;
    for (int i = 0; i < N_WALKS; i++) {
        rng_stream g = rng_stream_stage(7u, (uint)i, 0u, 0u);
        majorant_walk w = walk_begin(2.0f, 0.0f);
        vec3 ws = v3(1.0f, 1.0f, 1.0f);
        float sigma;
        int bin = N_BINS;
        while (piece_next(&w, &g, &sigma)) {
            in_gap += w.t >= 0.5f && w.t < 1.2f;
            vec3 st = v3(sigma, sigma, sigma);
            if (walk_pick(&w, &g, &ws, &st, 1, st) == 0) {
                double u = (1.0 - exp(-piece_tau(w.t))) / (1.0 - pass);
                bin = u < 1.0 ? (int)(u * N_BINS) : N_BINS - 1;
                break;
            }
        }
        count[bin]++;
    }
    double x = chi2(count, p, N_BINS + 1, N_WALKS), crit = test_chi2_critical_1e4(N_BINS);
    printf("piecewise, delta tracking: chi2 %.1f (critical %.1f, %d dof), passed %.5f "
           "(exp(-3.7) = %.5f)\n",
           x, crit, N_BINS, (double)count[N_BINS] / N_WALKS, pass);
    CHECK(x < crit);
    CHECK(in_gap == 0);
}

/* Ratio tracking's transmittance through the piecewise medium, per channel. */
static void check_piecewise_ratio(void)
{
    const double scale[3] = {0.5, 1.0, 1.2};
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    for (int i = 0; i < N_WALKS; i++) {
        rng_stream g = rng_stream_stage(11u, (uint)i, 0u, 0u);
        majorant_walk w = walk_begin(2.0f, 0.0f);
        vec3 W = v3(1.0f, 1.0f, 1.0f);
        float sigma;
        while (piece_next(&w, &g, &sigma))
            W = walk_ratio(&w, W, v3(0.5f * sigma, sigma, 1.2f * sigma));
        double v[3] = {W.x, W.y, W.z};
        for (int c = 0; c < 3; c++)
            sum[c] += v[c], sum2[c] += v[c] * v[c];
    }
    for (int c = 0; c < 3; c++) {
        double mean = sum[c] / N_WALKS, var = sum2[c] / N_WALKS - mean * mean;
        double se = sqrt(var / (N_WALKS - 1)), want = exp(-piece_tau(2.0) * scale[c]);
        printf("piecewise, ratio tracking, channel %d: %.6f +- %.6f, exp(-tau) %.6f (z %.2f)\n",
               c, mean, se, want, (mean - want) / se);
        CHECK(fabs(mean - want) <= Z_MAX * se);
    }
}

/* Spectral tracking with absorption through a homogeneous slab of length 1. */
static void check_spectral(void)
{
    const float sigma_t[3] = {0.5f, 1.0f, 2.0f}, albedo[3] = {0.9f, 0.5f, 0.99f};
    vec3 st = v3(sigma_t[0], sigma_t[1], sigma_t[2]);
    vec3 ss = v3_mul(st, v3(albedo[0], albedo[1], albedo[2]));
    double pass[3] = {0, 0, 0}, pass2[3] = {0, 0, 0}, scat[3] = {0, 0, 0}, scat2[3] = {0, 0, 0};
    for (int i = 0; i < N_WALKS; i++) {
        rng_stream g = rng_stream_stage(13u, (uint)i, 0u, 0u);
        majorant_walk w = walk_begin(1.0f, 0.0f);
        vec3 ws = v3(1.0f, 1.0f, 1.0f);
        int scattered = 0;
        while (!scattered && constant_next(&w, 2.5f, &g))
            scattered = walk_pick(&w, &g, &ws, &ss, 1, st) == 0;
        double v[3] = {ws.x, ws.y, ws.z};
        double *s1 = scattered ? scat : pass, *s2 = scattered ? scat2 : pass2;
        for (int c = 0; c < 3; c++)
            s1[c] += v[c], s2[c] += v[c] * v[c];
    }
    for (int c = 0; c < 3; c++) {
        double T = exp(-(double)sigma_t[c]), want[2] = {T, albedo[c] * (1.0 - T)};
        double *s1[2] = {pass, scat}, *s2[2] = {pass2, scat2};
        for (int e = 0; e < 2; e++) {
            double mean = s1[e][c] / N_WALKS, var = s2[e][c] / N_WALKS - mean * mean;
            double se = sqrt(var / (N_WALKS - 1));
            printf("spectral tracking, channel %d, %s weight: %.6f +- %.6f, want %.6f "
                   "(z %.2f)\n",
                   c, e ? "scattered" : "passing", mean, se, want[e], (mean - want[e]) / se);
            CHECK(fabs(mean - want[e]) <= Z_MAX * se);
        }
    }
}

/* The floor on the rate, and empty space's cost. */
static void check_floor(void)
{
    double points = 0.0, points2 = 0.0;
    int exact = 1;
    for (int i = 0; i < N_WALKS; i++) {
        rng_stream g = rng_stream_stage(17u, (uint)i, 0u, 0u);
        majorant_walk w = walk_begin(1.0f, 3.0f);
        vec3 W = v3(1.0f, 1.0f, 1.0f);
        int k = 0;
        while (constant_next(&w, 0.0f, &g))
            W = walk_ratio(&w, W, v3(0.0f, 0.0f, 0.0f)), k++;
        exact &= W.x == 1.0f && W.y == 1.0f && W.z == 1.0f;
        points += k, points2 += (double)k * k;
    }
    double mean = points / N_WALKS, se = sqrt((points2 / N_WALKS - mean * mean) / (N_WALKS - 1));
    printf("floor 3 /m over 1 m of empty space: %.4f +- %.4f points (Poisson mean 3)\n", mean, se);
    CHECK(fabs(mean - 3.0) <= Z_MAX * se);
    CHECK(exact);
    rng_stream g = rng_stream_stage(19u, 0u, 0u, 0u);
    uint dim = g.dim;
    majorant_walk w = walk_begin(1.0f, 0.0f);
    CHECK(!constant_next(&w, 0.0f, &g));
    CHECK(g.dim == dim);
}

int main(void)
{
    check_homogeneous(0);
    check_homogeneous(1);
    check_piecewise_collisions();
    check_piecewise_ratio();
    check_spectral();
    check_floor();
    return test_finish();
}
