/* test_kernel_math — the cheap forms the kernels use in place of costly library calls (host
 * build of the shared headers, float): fast_acos (kernels/atmosphere/method_fast.h, the
 * sky-view LUT's angles) and medium_segment_weight / medium_segment_step3
 * (kernels/media/medium.h, every medium step's exact-exponential weight).
 * labels: unit
 * composes: atmosphere ms_lut visibility medium ms_lut_passes fast
 *
 * Oracles (closed forms in double):
 *  1. fast_acos(x) against acos(x) at 2e6 + 1 float x evenly over [-1, 1] and at the ends:
 *     its arcsin polynomial (Cephes' single-precision minimax) is within ~1 ulp; the float
 *     evaluation (one sqrt, five multiply-adds, pi - 2 q or pi/2 -+ q) rounds to a few ulp of
 *     the result <= pi (ulp(pi) = 2.4e-7): bound 3 ulp(pi) = 7.2e-7 rad. The library's acosf
 *     is measured beside it for comparison.
 *  2. medium_segment_weight(sigma, dt, e) with e = expf(-sigma dt) against
 *     (1 - e^{-x}) / sigma in double, x = sigma dt log-spaced over 1e-9 .. 1e3 (200 per
 *     decade) for sigma = 1e-6 and 1e-3 1/m: where x > 0.1 the weight is (1 - e) / sigma,
 *     whose relative error is e's (1 ulp, 6e-8) over 1 - e >= 0.095 plus two roundings:
 *     <= 7e-7; below, the series to x^5 (truncation x^6 / 5040 <= 2e-10) in five rounded
 *     steps: <= 4e-7. Bound 1e-6 relative for both.
 *  3. medium_segment_step3 returns per channel the transmittance e^{-x} of its float exponent
 *     x = sigma dt to 1 ulp (bound 1.2e-7 relative where it is above 1e-30) and the weights of
 *     medium_segment_weight exactly. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "testlib.h"
#include "testprobe.h"
#include "kernels_composed.h"

int main(void)
{
    const double ulp_pi = 2.384185791015625e-7; /* 2^-22, the spacing of floats near pi */
    double worst = 0.0, worst_lib = 0.0, at = 0.0;
    const int n = 2000000;
    for (int i = 0; i <= n; i++) {
        float x = (float)(-1.0 + 2.0 * i / n);
        double want = acos((double)x);
        double err = fabs((double)fast_acos(x) - want);
        if (err > worst)
            worst = err, at = x;
        worst_lib = fmax(worst_lib, fabs((double)acosf(x) - want));
    }
    CHECK(worst <= 3.0 * ulp_pi);
    CHECK(fast_acos(1.0f) == 0.0f);
    CHECK_ABS(fast_acos(-1.0f), M_PI, 3.0 * ulp_pi);
    CHECK_ABS(fast_acos(0.0f), M_PI / 2.0, 3.0 * ulp_pi);
    printf("fast_acos: worst %.2e rad (at x = %.6f; bound %.2e), library acosf %.2e\n", worst,
           at, 3.0 * ulp_pi, worst_lib);

    static const float sigmas[] = {1e-6f, 1e-3f};
    double worst_w = 0.0, worst_e = 0.0;
    for (int k = 0; k < 2; k++)
        for (int j = 0; j <= 12 * 200; j++) {
            float sigma = sigmas[k];
            float x = (float)pow(10.0, -9.0 + j / 200.0);
            float dt = x / sigma;
            double xd = (double)sigma * dt;
            double exact = -expm1(-xd);
            float e = expf(-sigma * dt);
            float w = medium_segment_weight(sigma, dt, e);
            double rel = fabs(w * (double)sigma / exact - 1.0);
            worst_w = fmax(worst_w, rel);
            CHECK(rel <= 1e-6);
            vec3 step;
            vec3 w3 = medium_segment_step3(v3(sigma, 2.0f * sigma, 0.5f * sigma), dt, &step);
            float x2 = (2.0f * sigma) * dt; /* the exponent as the kernel rounds it */
            double want = exp(-(double)x2), de = fabs(step.y - want) / want;
            if (want > 1e-30)
                worst_e = fmax(worst_e, de);
            CHECK(want <= 1e-30 || de <= 1.2e-7);
            CHECK(w3.x == w);
        }
    printf("medium_segment_weight: worst %.2e relative (bound 1e-6); step3's transmittance "
           "%.2e relative (bound 1.2e-7)\n",
           worst_w, worst_e);
    return test_finish();
}
