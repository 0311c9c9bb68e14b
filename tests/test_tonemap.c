/* test_tonemap.c — tone mapping operators, transfer curves and the host display pipeline.
 * labels: unit
 *
 * Oracles:
 *   - closed-form values of each operator (kernels/post/tonemap.h) at inputs where the formula reduces
 *     to simple numbers: exposure 1 - e^-1; Reinhard 1/2 and 3/4; Reinhard-white maps w to exactly
 *     1; ACES(1) = 2.54/3.16; Unreal 3 at x = 0.155 is 1.019/2 before linearisation; Uchimura is
 *     the identity on its linear part [m, S0] = [0.22, 0.532], continuous into the shoulder at
 *     S0, and at m/2 the smoothstep weight is exactly 1/2; Lottes maps midIn to midOut and hdrMax
 *     to 1 by construction of its b, c. Tolerance 1e-5 absolute: each is a handful of float
 *     operations on values <= 1 (rounding ~1e-7 each) with powf (<= 1 ulp) — 1e-5 is 100x that,
 *     yet a wrong constant (e.g. 0.59 -> 0.6 in ACES) moves the value by > 1e-3.
 *   - monotonicity on a geometric grid (ratio 1.01 from 1e-4 to 1e3): every operator must be
 *     non-decreasing; the step is far larger than float rounding, so a decrease is a real defect.
 *   - the sRGB curve against its definition (IEC 61966-2-1) evaluated in double: relative 1e-6
 *     (a few float roundings and one powf); its continuity at the 0.0031308 knee: the standard's
 *     rounded constants leave a jump of 2.85e-8 there, and float rounding adds ~1e-8, so the two
 *     float values beside the knee must agree within 1e-7; the inverse round trip
 *     decode(encode(v)) = v within relative 2e-6 (a chain of ~10 float roundings, the 2.4 power
 *     amplifying relative errors 2.4-fold: ~7e-7 worst case).
 *   - atmo_post_pixel composes white balance, exposure, operator and curve in that order: checked
 *     with the identity operator and gamma 2.2, where the result is (in / wb * E)^(1/2.2). */
#include <math.h>
#include "atmo/image.h"
#include "atmo/scene.h"
#include "testlib.h"
#include "post/tonemap.h"

static const int all_ops[] = {ATMO_TONEMAP_NONE,     ATMO_TONEMAP_EXPOSURE, ATMO_TONEMAP_REINHARD,
                              ATMO_TONEMAP_REINHARD_WHITE, ATMO_TONEMAP_ACES, ATMO_TONEMAP_UNREAL3,
                              ATMO_TONEMAP_UCHIMURA, ATMO_TONEMAP_LOTTES};

static void test_closed_forms(void)
{
    const double tol = 1e-5;
    CHECK_ABS(tonemap_exposure(0.0f), 0.0, tol);
    CHECK_ABS(tonemap_exposure(1.0f), 1.0 - exp(-1.0), tol);
    CHECK_ABS(tonemap_exposure(2.0f), 1.0 - exp(-2.0), tol);
    CHECK_ABS(tonemap_reinhard(1.0f), 0.5, tol);
    CHECK_ABS(tonemap_reinhard(3.0f), 0.75, tol);
    CHECK_ABS(tonemap_reinhard_white(4.0f, 4.0f), 1.0, tol);
    CHECK_ABS(tonemap_reinhard_white(1.0f, 4.0f), (1.0 + 1.0 / 16.0) / 2.0, tol);
    /* With w -> infinity Reinhard-white is plain Reinhard. */
    CHECK_ABS(tonemap_reinhard_white(3.0f, 1e6f), 0.75, tol);
    CHECK_ABS(tonemap_aces(0.0f), 0.0, tol);
    CHECK_ABS(tonemap_aces(1.0f), 2.54 / 3.16, tol);
    CHECK_ABS(tonemap_unreal3(0.155f), pow(1.019 / 2.0, 2.2), tol);
    CHECK_ABS(transfer_gamma22_encode(tonemap_unreal3(0.155f)), 1.019 / 2.0, tol);
    CHECK_ABS(tonemap_unreal3(100.0f), 1.0, tol); /* past the clamp */

    /* Uchimura: linear part m + a (x - m) = x (a = 1), shoulder starts at S0 = 0.532. */
    CHECK_ABS(tonemap_uchimura(0.22f), 0.22, tol);
    CHECK_ABS(tonemap_uchimura(0.4f), 0.4, tol);
    CHECK_ABS(tonemap_uchimura(0.5319f), 0.5319, tol);
    CHECK_ABS(tonemap_uchimura(0.532f), 0.532, tol);
    CHECK_ABS(tonemap_uchimura(0.0f), 0.0, tol);
    /* At x = m/2: smoothstep weight 1/2 between toe m (1/2)^c and the line x. */
    CHECK_ABS(tonemap_uchimura(0.11f), 0.5 * 0.22 * pow(0.5, 1.33) + 0.5 * 0.11, tol);
    /* Shoulder: P - (P - S1) exp(-a P / (P - S1) (x - S0)) at x = 1. */
    CHECK_ABS(tonemap_uchimura(1.0f), 1.0 - 0.468 * exp(-(1.0 / 0.468) * 0.468), tol);

    float hdr_max[] = {1.0f, 4.0f, 8.0f};
    for (int i = 0; i < 3; i++) {
        CHECK_ABS(tonemap_lottes(0.18f, hdr_max[i]), 0.267, tol);
        CHECK_ABS(tonemap_lottes(hdr_max[i], hdr_max[i]), 1.0, tol);
        CHECK_ABS(tonemap_lottes(0.0f, hdr_max[i]), 0.0, tol);
    }

    /* The dispatcher clamps to [0, 1] and maps negative / NaN input to 0. */
    CHECK_ABS(tonemap_apply(ATMO_TONEMAP_NONE, 2.0f, 4.0f), 1.0, 0.0);
    CHECK_ABS(tonemap_apply(ATMO_TONEMAP_NONE, 0.25f, 4.0f), 0.25, 0.0);
    CHECK_ABS(tonemap_apply(ATMO_TONEMAP_ACES, 50.0f, 4.0f), 1.0, 0.0);
    CHECK_ABS(tonemap_apply(ATMO_TONEMAP_LOTTES, 16.0f, 4.0f), 1.0, 0.0);
    CHECK_ABS(tonemap_apply(ATMO_TONEMAP_REINHARD_WHITE, 4.0f, 4.0f), 1.0, tol);
    /* Lottes with an unusable white point (below 0.41) still yields a value in [0, 1]. */
    for (double x = 1e-3; x < 1e3; x *= 1.5) {
        float y = tonemap_apply(ATMO_TONEMAP_LOTTES, (float)x, 0.1f);
        CHECK(y >= 0.0f && y <= 1.0f);
    }
    for (int i = 0; i < 8; i++) {
        CHECK_ABS(tonemap_apply(all_ops[i], -1.0f, 4.0f), 0.0, 0.0);
        CHECK_ABS(tonemap_apply(all_ops[i], NAN, 4.0f), 0.0, 0.0);
    }
}

static void test_monotonic(void)
{
    for (int i = 0; i < 8; i++) {
        int decreases = 0;
        float prev = tonemap_apply(all_ops[i], 0.0f, 4.0f);
        for (double x = 1e-4; x < 1e3; x *= 1.01) {
            float y = tonemap_apply(all_ops[i], (float)x, 4.0f);
            decreases += y < prev;
            prev = y;
        }
        if (decreases)
            fprintf(stderr, "operator %d decreases %d times\n", all_ops[i], decreases);
        CHECK(decreases == 0);
        /* Every operator reaches (or nearly reaches) white for very bright input. */
        CHECK(tonemap_apply(all_ops[i], 1e3f, 4.0f) > 0.99f);
    }
    for (int t = 0; t < 2; t++) {
        int decreases = 0;
        float prev = transfer_encode(t, 0.0f);
        for (double v = 1e-6; v <= 1.0; v *= 1.01) {
            float y = transfer_encode(t, (float)v);
            decreases += y < prev;
            prev = y;
        }
        CHECK(decreases == 0);
    }
}

static double srgb_definition(double v)
{
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

static void test_srgb(void)
{
    CHECK_ABS(transfer_srgb_encode(0.0f), 0.0, 0.0);
    CHECK_ABS(transfer_srgb_encode(1.0f), 1.0, 1e-6);
    CHECK_ABS(transfer_srgb_encode(0.5f), 0.7353569830524495, 1e-6);
    int worst_def = 0, worst_trip = 0;
    for (double v = 1e-7; v <= 1.0; v *= 1.003) {
        float fv = (float)v;
        worst_def += !CHECK_REL(transfer_srgb_encode(fv), srgb_definition(fv), 1e-6);
        worst_trip += !CHECK_REL(transfer_srgb_decode(transfer_srgb_encode(fv)), fv, 2e-6);
        CHECK_REL(transfer_gamma22_decode(transfer_gamma22_encode(fv)), fv, 2e-6);
        CHECK_REL(transfer_gamma22_encode(fv), pow(fv, 1.0 / 2.2), 1e-6);
    }
    CHECK(worst_def == 0 && worst_trip == 0);
    float knee = 0.0031308f;
    float below = transfer_srgb_encode(nextafterf(knee, 0.0f));
    float above = transfer_srgb_encode(nextafterf(knee, 1.0f));
    CHECK_ABS(above, below, 1e-7);
    CHECK_ABS(transfer_srgb_decode(0.04045f), 0.04045 / 12.92, 1e-9);
    float dbelow = transfer_srgb_decode(nextafterf(0.04045f, 0.0f));
    float dabove = transfer_srgb_decode(nextafterf(0.04045f, 1.0f));
    CHECK_ABS(dabove, dbelow, 1e-8);
    CHECK_ABS(transfer_encode(ATMO_TRANSFER_SRGB, 0.5f), 0.7353569830524495, 1e-6);
    CHECK_ABS(transfer_encode(ATMO_TRANSFER_GAMMA22, 0.5f), pow(0.5, 1.0 / 2.2), 1e-6);
}

static void test_post_pixel(void)
{
    atmo_post post = {.exposure = 2.0f,
                      .tonemap = ATMO_TONEMAP_NONE,
                      .white_point = 4.0f,
                      .white_balance = 1,
                      .white_balance_rgb = {1.08241f, 0.96756f, 0.95003f},
                      .transfer = ATMO_TRANSFER_GAMMA22};
    /* Sunlight-coloured input at quarter strength: white-balanced to grey 0.25, exposed to 0.5. */
    float in[3] = {0.25f * 1.08241f, 0.25f * 0.96756f, 0.25f * 0.95003f}, out[3];
    atmo_post_pixel(&post, in, out);
    for (int c = 0; c < 3; c++)
        CHECK_ABS(out[c], pow(0.5, 1.0 / 2.2), 1e-6);

    post.white_balance = 0;
    atmo_post_pixel(&post, in, out);
    for (int c = 0; c < 3; c++)
        CHECK_ABS(out[c], pow(2.0 * in[c], 1.0 / 2.2), 1e-6);

    /* Operator and sRGB curve: Reinhard of exposed 1 is 1/2, sRGB(1/2) = 0.73536. */
    post.tonemap = ATMO_TONEMAP_REINHARD;
    post.transfer = ATMO_TRANSFER_SRGB;
    post.exposure = 4.0f;
    float quarter[3] = {0.25f, 0.25f, 0.25f};
    atmo_post_pixel(&post, quarter, out);
    for (int c = 0; c < 3; c++)
        CHECK_ABS(out[c], 0.7353569830524495, 1e-6);

    /* Out-of-range input stays in [0, 1]. */
    float wild[3] = {-5.0f, 1e30f, NAN};
    atmo_post_pixel(&post, wild, out);
    CHECK(out[0] == 0.0f && out[1] <= 1.0f && out[1] > 0.99f && out[2] == 0.0f);
}

int main(void)
{
    test_closed_forms();
    test_monotonic();
    test_srgb();
    test_post_pixel();
    return test_finish();
}
