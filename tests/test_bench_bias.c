/* test_bench_bias — bench_block_bias (host/bench/bench_common.c), the noise-corrected relative
 * bias of an image against a reference that `atmo bench views` reports.
 * labels: unit
 *
 * Synthetic images of 320 x 180 pixels: a truth T (a smooth field from 0.2 to 1.8, plus a
 * dark corner below the brightness cut), the estimator x_s = T (1 + beta) (1 + sigma_x g) and
 * the reference a_s = T (1 + sigma_r g') for seeds s = 1, 2 (g, g' independent standard normal
 * per pixel, Box-Muller over a 64-bit LCG). Blocks of 4 x 4: 3600 of them, a 6 % relative
 * noise per block mean at sigma 0.3 (like a 32-sample path-traced reference), the bias a few
 * per cent.
 * Oracles:
 *  1. Unbiasedness: over 40 independent image sets (sigma_x 0.1, sigma_r 0.3) at beta 0.03,
 *     0.1 and +-0.05 (stripes 16 pixels wide of either sign: the RMS is 0.05, the mean 0), the
 *     mean of the squared estimate is the mean beta^2 within 4 standard errors of that mean
 *     (the sets' spread), and the stated standard error (*se) lies within a factor 2 of the
 *     spread of the estimates across the sets; at beta 0, where the function clamps the
 *     noise's negative means at 0, the RMS of the estimates stays below 3 stated standard
 *     errors. (Without the term for the reference's noise in the denominator the mean squared
 *     estimate at beta 0.03 is 0.00129, 17 standard errors above 0.0009.)
 *  2. Power: the naive per-pixel RMS of (x - a) / a on the same images is far above beta
 *     (the references' noise, > 0.25), which the correction removes.
 *  3. Exact cases: with no noise the estimate is |beta| to 1e-12 and the mean bias beta to
 *     1e-12; a skip mask over the left half leaves exactly the right half's blocks; blocks whose
 *     reference is below the brightness cut are not counted. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include "atmo/bench.h"
#include "testlib.h"

#define W 320
#define H 180
#define N (W * H)
#define B 4
#define SETS 40

static uint64_t rng_state = 88172645463325252ull;

static double uniform(void)
{
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    return ((double)(rng_state >> 11) + 0.5) / 9007199254740992.0;
}

static double normal(void)
{
    return sqrt(-2.0 * log(uniform())) * cos(2.0 * M_PI * uniform());
}

static double truth(int x, int y)
{
    if (x < 40 && y < 40) /* below the cut: 1 % of the mean */
        return 1e-3;
    return 1.0 + 0.8 * sin(x * 0.05) * cos(y * 0.07);
}

/* One set of images: x1, x2 at bias beta and noise sx, a, b at noise sr. */
static void images(double beta, double sx, double sr, double *x1, double *x2, double *a, double *b)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int i = y * W + x;
            double t = truth(x, y), bias = beta < 0.0 ? (x / 16 % 2 ? beta : -beta) : beta;
            x1[i] = t * (1.0 + bias) * (1.0 + sx * normal());
            x2[i] = t * (1.0 + bias) * (1.0 + sx * normal());
            a[i] = t * (1.0 + sr * normal());
            b[i] = t * (1.0 + sr * normal());
        }
}

/* Over SETS image sets at bias beta: the mean of the squared estimate and its standard error,
 * the mean stated se and the spread (standard deviation) of the estimates. */
static void sets(double beta, double *mean_b2, double *se_b2, double *mean_se, double *spread,
                 double *x1, double *x2, double *a, double *b)
{
    double s1 = 0, s2 = 0, e1 = 0, b1 = 0, bb = 0;
    for (int k = 0; k < SETS; k++) {
        double se, mean_bias;
        int blocks;
        images(beta, 0.1, 0.3, x1, x2, a, b);
        double est = bench_block_bias(x1, x2, a, b, NULL, W, H, B, 0.01, &se, &mean_bias, &blocks);
        s1 += est * est, s2 += est * est * est * est, e1 += se, b1 += est, bb += est * est;
    }
    *mean_b2 = s1 / SETS;
    *se_b2 = sqrt(fmax(s2 / SETS - *mean_b2 * *mean_b2, 0.0) / (SETS - 1));
    *mean_se = e1 / SETS;
    *spread = sqrt(fmax(bb / SETS - (b1 / SETS) * (b1 / SETS), 0.0) * SETS / (SETS - 1));
}

int main(void)
{
    double *x1 = malloc(N * sizeof *x1), *x2 = malloc(N * sizeof *x2);
    double *a = malloc(N * sizeof *a), *b = malloc(N * sizeof *b);
    unsigned char *skip = calloc(N, 1);
    if (!x1 || !x2 || !a || !b || !skip)
        return 1;

    /* 3: exact cases */
    double se, mean_bias;
    int blocks;
    images(0.04, 0.0, 0.0, x1, x2, a, b);
    double est = bench_block_bias(x1, x2, a, b, NULL, W, H, B, 0.01, &se, &mean_bias, &blocks);
    CHECK_ABS(est, 0.04, 1e-12);
    CHECK_ABS(mean_bias, 0.04, 1e-12);
    CHECK(blocks == (W / B) * (H / B) - (40 / B) * (40 / B));
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W / 2; x++)
            skip[y * W + x] = 1;
    bench_block_bias(x1, x2, a, b, skip, W, H, B, 0.01, &se, &mean_bias, &blocks);
    CHECK(blocks == (W / 2 / B) * (H / B));

    /* 1: unbiased at beta 0.03, 0.1 and +-0.05 in stripes 16 pixels wide; the stated error */
    double m, s, mse, spread, betas[3] = {0.03, 0.1, -0.05};
    for (int k = 0; k < 3; k++) {
        double want = betas[k] * betas[k];
        sets(betas[k], &m, &s, &mse, &spread, x1, x2, a, b);
        printf("beta %g: mean squared estimate %.4g (want %.4g, se %.2g); stated se %.3g, "
               "spread %.3g\n", betas[k], m, want, s, mse, spread);
        CHECK(fabs(m - want) < 4.0 * s);
        CHECK(mse < 2.0 * spread && spread < 2.0 * mse);
    }
    /* at beta 0: the estimates stay within their own noise of 0 */
    sets(0.0, &m, &s, &mse, &spread, x1, x2, a, b);
    printf("beta 0: mean squared estimate %.3g (clamped at 0; stated se %.3g)\n", m, mse);
    CHECK(sqrt(m) < 3.0 * mse);

    /* 2: power: the naive per-pixel ratio is dominated by the reference's noise */
    images(0.03, 0.1, 0.3, x1, x2, a, b);
    double naive = 0.0;
    int used = 0;
    for (int i = 0; i < N; i++)
        if (a[i] > 0.01) {
            double d = (x1[i] - a[i]) / a[i];
            naive += d * d, used++;
        }
    naive = sqrt(naive / used);
    est = bench_block_bias(x1, x2, a, b, NULL, W, H, B, 0.01, &se, &mean_bias, &blocks);
    printf("naive per-pixel RMS %.3f; block estimate %.4f (se %.4f), mean bias %.4f\n", naive,
           est, se, mean_bias);
    CHECK(naive > 0.25);
    CHECK(fabs(est - 0.03) < 4.0 * se);

    free(x1), free(x2), free(a), free(b), free(skip);
    return test_finish();
}
