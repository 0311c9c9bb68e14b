/* test_fast_horizon — method fast's sky just above the terrain's silhouette is method march's
 * sky (thesis-3's far ridges, issue 28's "shelf").
 * labels: render slow
 *
 * Oracle, a statistical test: thesis-3 at 160 x 90, 1 sample per pixel, rendered with fast
 * (seed 1) and with march (seeds 1 and 2). fast reads a sky ray's light from its sky-view LUT
 * (noise-free), march integrates the same ray with a random offset, so on sky pixels fast -
 * march has the march's noise alone, of standard deviation sigma per pixel (relative, on
 * luminance), estimated from the two march seeds: the sample standard deviation of their
 * relative difference over the same pixels is sqrt(2) sigma. The pixels judged: sky pixels
 * (every guide ray misses every surface: guide depth ATMO_GUIDES_NO_HIT_DEPTH_M) whose
 * neighbour one or two rows below holds terrain (a guide depth below it), n of them. Two
 * criteria: the mean relative difference fast / march - 1 over them lies within
 * 4 sigma / sqrt(n) plus 0.5 %, the LUT's own accuracy against a converged march
 * (docs/notes/fast_method.md: worst 0.46 % on any ray); and its root mean square is at most
 * 1.5 times sigma + 0.5 % (the RMS of n = 320 Gaussian differences scatters by ~4 % of
 * itself, so 1.5 leaves room for the march's heavier tails and still catches a few pixels off
 * by tens of percent, which the mean dilutes).
 *
 * What it catches: a sky-view LUT whose texels stop at the terrain (the texel's ray is a real
 * 3-D ray from the camera, on one side of the sun's vertical plane) hands its neighbouring sky
 * rows the terrain's darker light. Measured (PoCL) with such a LUT: mean -0.71 % (bound
 * 1.02 %), RMS 5.3 % against sigma 2.3 % (ratio 1.86: fails), worst pixel -43 %; with the LUT
 * of the air alone: mean +0.45 %, RMS 1.9 % (ratio 0.67), worst pixel 7.9 %. The guides'
 * pass (21 s) dominates the time. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "atmo/guides.h"
#include "atmo/render.h"
#include "testlib.h"
#include "testscene.h"

#define W 160
#define H 90
#define K_SIGMA 4.0
#define LUT_ACCURACY 0.005
#define RMS_RATIO 1.5

/* thesis-3 with `method` and `seed` at W x H, 1 sample per pixel (r: the result; the guides
 * too where `guides`). */
static void render(const char *method, int seed, int guides, atmo_render_result *r)
{
    atmo_scene s;
    char buf[64];
    test_scene_preset(&s, "thesis-3");
    snprintf(buf, sizeof buf, "atmosphere.method=%s", method);
    test_scene_set(&s, buf);
    test_scene_image(&s, W, H, 1, seed);
    atmo_plan p;
    test_plan(&s, &p);
    atmo_render_settings rs;
    atmo_render_settings_default(&rs);
    rs.guides = guides;
    atmo_err e;
    if (atmo_render(&p, &rs, r, &e)) {
        fprintf(stderr, "render failed: %s\n", e.msg);
        exit(1);
    }
    atmo_plan_free(&p);
    printf("%s seed %d: build %.1f s, precompute %.1f s, guides %.1f s, render %.1f s\n", method,
           seed, r->seconds_build, r->seconds_precompute, r->seconds_guides, r->seconds_render);
    CHECK(r->nonfinite == 0);
    CHECK(!guides || r->guides != NULL);
    if (guides && !r->guides)
        exit(1);
}

static double luminance(const float *rgb, int i)
{
    return 0.2126 * rgb[3 * i] + 0.7152 * rgb[3 * i + 1] + 0.0722 * rgb[3 * i + 2];
}

int main(void)
{
    atmo_render_result fast, m1, m2;
    render("fast", 1, 1, &fast);
    render("march", 1, 0, &m1);
    render("march", 2, 0, &m2);
    const float *depth = fast.guides + 6 * W * H;
    double sum_d = 0.0, sum_d2 = 0.0, sum_e = 0.0, sum_e2 = 0.0, worst = 0.0;
    int n = 0;
    for (int y = 0; y + 1 < H; y++)
        for (int x = 0; x < W; x++) {
            int i = y * W + x;
            int below = depth[i + W] < ATMO_GUIDES_NO_HIT_DEPTH_M ||
                        (y + 2 < H && depth[i + 2 * W] < ATMO_GUIDES_NO_HIT_DEPTH_M);
            if (depth[i] < ATMO_GUIDES_NO_HIT_DEPTH_M || !below)
                continue;
            double lf = luminance(fast.rgb, i), l1 = luminance(m1.rgb, i);
            double l2 = luminance(m2.rgb, i);
            CHECK(l1 > 0.0 && l2 > 0.0);
            if (l1 <= 0.0 || l2 <= 0.0)
                continue;
            double d = lf / l1 - 1.0, e = l1 / l2 - 1.0;
            sum_d += d;
            sum_d2 += d * d;
            sum_e += e;
            sum_e2 += e * e;
            worst = fmax(worst, fabs(d));
            n++;
        }
    CHECK(n >= 50); /* the view's ridges span most of its width */
    if (n < 2)
        return test_finish();
    double mean_d = sum_d / n, mean_e = sum_e / n;
    double sigma = sqrt(fmax(sum_e2 - n * mean_e * mean_e, 0.0) / (n - 1)) / sqrt(2.0);
    double bound = K_SIGMA * sigma / sqrt((double)n) + LUT_ACCURACY;
    double rms_d = sqrt(sum_d2 / n), rms_e = sqrt(sum_e2 / n) / sqrt(2.0);
    double ratio = rms_d / (rms_e + LUT_ACCURACY);
    printf("%d sky pixels above the terrain: mean fast/march - 1 = %+.4f (bound %.4f: march "
           "noise %.4f per pixel from two seeds), rms %.4f against the march pair's %.4f "
           "(ratio %.2f, bound %.2f), worst pixel %.3f\n",
           n, mean_d, bound, sigma, rms_d, rms_e, ratio, RMS_RATIO, worst);
    CHECK(fabs(mean_d) <= bound);
    CHECK(ratio <= RMS_RATIO);
    atmo_render_result_free(&fast);
    atmo_render_result_free(&m1);
    atmo_render_result_free(&m2);
    return test_finish();
}
