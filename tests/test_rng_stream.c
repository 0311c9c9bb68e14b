/* test_rng_stream — the per-stage random streams of kernels/common/rng.h.
 * labels: unit stat
 *
 * Oracles:
 *  1. the documented layout, exactly: stage k's stream draws rng_uniform(seed, pixel, sample,
 *     k 2^24 + i) for its i-th number, so stage 0 after the camera's CAMERA_RNG_DIMS numbers is
 *     the dimension the methods have always drawn first (images and probes keep their numbers),
 *     and rng_stream_next_stage of any stage-k stream starts stage k + 1;
 *  2. chi-square independence (32 x 32 grid of pairs, p = 1e-4 critical value, fixed counters,
 *     so the test is deterministic) between the first numbers of consecutive stages (a path's
 *     bounces) and between stage 1's first and second numbers, and uniformity of stage 3's
 *     first number on 256 bins. */
#include <stdio.h>
#include "common/camera.h"
#include "common/rng.h"
#include "testlib.h"

#define N 1000000

int main(void)
{
    int mismatches = 0;
    for (uint i = 0; i < 1000; i++) {
        rng_stream g = rng_stream_stage(9u, i, 3u * i, 0u);
        g.dim += CAMERA_RNG_DIMS;
        mismatches += rng_next(&g) != rng_uniform(9u, i, 3u * i, 2u);
        rng_stream b = rng_stream_next_stage(&g);
        rng_stream c = rng_stream_stage(9u, i, 3u * i, 1u);
        mismatches += rng_next(&b) != rng_next(&c);
        mismatches += rng_next(&b) != rng_uniform(9u, i, 3u * i, (1u << RNG_STAGE_BITS) + 1u);
        rng_stream d = rng_stream_next_stage(&b);
        mismatches += d.dim != 2u << RNG_STAGE_BITS;
    }
    CHECK(mismatches == 0);

    enum { G = 32 };
    static int pairs[3][G * G], bins[256];
    for (uint i = 0; i < N; i++) {
        uint p = i % 1000u, s = i / 1000u;
        rng_stream s0 = rng_stream_stage(5u, p, s, 0u), s1 = rng_stream_next_stage(&s0);
        rng_stream s2 = rng_stream_next_stage(&s1), s3 = rng_stream_next_stage(&s2);
        float a = rng_next(&s0), b = rng_next(&s1), b2 = rng_next(&s1), c = rng_next(&s2);
        pairs[0][(int)(a * G) * G + (int)(b * G)]++;
        pairs[1][(int)(b * G) * G + (int)(c * G)]++;
        pairs[2][(int)(b * G) * G + (int)(b2 * G)]++;
        bins[(int)(rng_next(&s3) * 256.0f)]++;
    }
    double crit_pairs = test_chi2_critical_1e4(G * G - 1), expect = (double)N / (G * G);
    const char *what[3] = {"stage 0 / stage 1", "stage 1 / stage 2", "stage 1, two numbers"};
    for (int k = 0; k < 3; k++) {
        double chi2 = 0.0;
        for (int j = 0; j < G * G; j++)
            chi2 += (pairs[k][j] - expect) * (pairs[k][j] - expect) / expect;
        printf("%s: chi2 %.1f (critical %.1f)\n", what[k], chi2, crit_pairs);
        CHECK_ABS(chi2, 0.0, crit_pairs);
    }
    double chi2 = 0.0, e1 = (double)N / 256;
    for (int j = 0; j < 256; j++)
        chi2 += (bins[j] - e1) * (bins[j] - e1) / e1;
    printf("stage 3 uniformity: chi2 %.1f (critical %.1f)\n", chi2, test_chi2_critical_1e4(255));
    CHECK_ABS(chi2, 0.0, test_chi2_critical_1e4(255));
    return test_finish();
}
