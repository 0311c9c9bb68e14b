/* test_sky_psnr — images of the single-scattering kernel against the host double-precision
 * model, scored by PSNR against Bruneton's own thresholds (47 dB radiance, 40 dB luminance,
 * 35 dB at sunset).
 * labels: kernel
 *
 * Oracle: atmo_ref_single_scattering + atmo_ref_ground_radiance (host/atmosphere/atmosphere_ref.c:
 * single scattering of the point sun and the directly lit ground, adaptive Gauss-Kronrod
 * quadrature, relative error < 1e-9), the model method `single` computes in float on the device
 * (32 march segments, the default render.view_steps; transmittance LUT 256 x 256). Images: 64 x 32
 * latitude-longitude panoramas (the whole sphere of directions, azimuth from the sun) from a
 * camera at the ground (1.7 m, the default camera) and at 10 km, sun zenith 65 deg (Bruneton's day
 * scene) and 88 deg (his sunset). Each kernel pixel is the mean of 256 samples (64 independent
 * batches of 4, as a render draws them: the march offsets are random); the noise-limited PSNR 10
 * log10(peak^2 / mean se^2) is printed to show that noise is far below the thresholds.
 *
 * Two PSNRs per image:
 *  - Bruneton's (precomputed_atmospheric_scattering, atmosphere/reference/model_test.cc,
 *    ComputePSNR): both images tone-mapped per channel to 8 bits, v = floor(255 (1 -
 *    exp(-x exposure))^(1/2.2)) with exposure 10 for radiance and 1e-4 for luminance, and
 *    PSNR = 10 log10(255^2 / sqrt(sum of squared channel differences / pixels)); note the
 *    square root, which his thresholds were set with. Asserted: radiance >= 47 dB and
 *    luminance >= 40 dB by day, both >= 35 dB at sunset.
 *  - linear: peak = the largest value of the reference image, MSE over pixels and channels,
 *    PSNR = 10 log10(peak^2 / MSE) (no tone map, no quantisation: stricter where the errors
 *    sit in bright pixels). Asserted against the same thresholds.
 * Luminance is the three channels of linear sRGB in cd/m^2, k_c L(lambda_c) with Bruneton's
 * sky constants (atmo_luminance_factors, p = -3), on both sides: it weighs the same radiance
 * errors differently; the 3-wavelength approximation itself is not tested here (the model has
 * no spectral reference; test_spectral_mode compares the spectral mode).
 * Measured (PoCL, loaded machine): Bruneton's PSNR 51.6-53.2 dB radiance, 51.6-53.5 dB
 * luminance (an RMS of ~0.4 of an 8-bit level, from values that round to neighbouring levels);
 * linear 61-77 dB radiance, 61-82 dB luminance, the worst (ground, sun 65 deg) close to its
 * noise-alone 62.6 dB; host reference 4 s for the 8192 rays. Method lut's order 1 computes
 * the same model but is not scored here (it needs its 4-D precompute; test_lut_method compares
 * it with the same oracle ray by ray). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "atmo/atmosphere_ref.h"
#include "atmo/colour.h"
#include "testlib.h"
#include "testprobe.h"

#define DEG (M_PI / 180.0)
#define WIDTH 64
#define HEIGHT 32
#define PIXELS (WIDTH * HEIGHT)

static double seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Bruneton's tone map of one channel to 8 bits */
static int tone_8bit(double x, double exposure)
{
    return (int)(255.0 * pow(1.0 - exp(-x * exposure), 1.0 / 2.2));
}

static double psnr_bruneton(const double (*a)[3], const double (*b)[3], double exposure)
{
    double sum = 0.0;
    for (int i = 0; i < PIXELS; i++)
        for (int c = 0; c < 3; c++) {
            double d = tone_8bit(a[i][c], exposure) - tone_8bit(b[i][c], exposure);
            sum += d * d;
        }
    double rms = sqrt(sum / PIXELS);
    return rms > 0.0 ? 10.0 * log10(255.0 * 255.0 / rms) : INFINITY;
}

/* peak = the largest value of the reference b; MSE over pixels and channels */
static double psnr_linear(const double (*a)[3], const double (*b)[3])
{
    double peak = 0.0, sum = 0.0;
    for (int i = 0; i < PIXELS; i++)
        for (int c = 0; c < 3; c++) {
            peak = fmax(peak, b[i][c]);
            sum += (a[i][c] - b[i][c]) * (a[i][c] - b[i][c]);
        }
    return sum > 0.0 ? 10.0 * log10(peak * peak / (sum / (3.0 * PIXELS))) : INFINITY;
}

int main(void)
{
    atmo_cl cl;
    test_cl_open(&cl);
    atmo_scene s;
    atmo_plan p;
    test_scene_preset(&s, "sky-noon");
    test_scene_set(&s, "atmosphere.method=single");
    test_plan(&s, &p);
    const atmo_atmosphere *a = &p.atmosphere;
    double k[3];
    atmo_luminance_factors(a->wavelengths_nm, -3.0, k);
    test_probe t;
    test_probe_open(&t, &cl, &p);

    static const double altitude_m[2] = {1.7, 10e3}, sun_zenith[2] = {65.0, 88.0};
    static float4 rays[PIXELS];
    static double L[PIXELS][3], se[PIXELS][3], ref[PIXELS][3], Y[PIXELS][3], Y_ref[PIXELS][3];
    double host_seconds = 0.0;
    for (int is = 0; is < 2; is++)
        for (int ia = 0; ia < 2; ia++) {
            double ts = sun_zenith[is] * DEG, r = a->bottom_radius_m + altitude_m[ia];
            for (int y = 0; y < HEIGHT; y++)
                for (int x = 0; x < WIDTH; x++) {
                    double tv = (y + 0.5) / HEIGHT * M_PI, phi = (x + 0.5) / WIDTH * 2.0 * M_PI;
                    float4 q = {(float)r, (float)cos(tv), (float)cos(ts),
                                (float)(sin(tv) * sin(ts) * cos(phi) + cos(tv) * cos(ts))};
                    rays[y * WIDTH + x] = q;
                }
            test_probe_rays(&t, rays, PIXELS, 64, 4, TEST_PROBE_INDEPENDENT, L, se, NULL, NULL);
            double t0 = seconds();
            for (int i = 0; i < PIXELS; i++) {
                float4 q = rays[i];
                double g[3] = {0.0, 0.0, 0.0};
                atmo_ref_single_scattering(a, q.x, q.y, q.z, q.w, ref[i]);
                if (atmo_ref_ray_hits_ground(q.x, q.y, a->bottom_radius_m))
                    atmo_ref_ground_radiance(a, q.x, q.y, q.z, q.w, g);
                for (int c = 0; c < 3; c++)
                    ref[i][c] += g[c];
            }
            host_seconds += seconds() - t0;
            for (int i = 0; i < PIXELS; i++)
                for (int c = 0; c < 3; c++) {
                    Y[i][c] = k[c] * L[i][c];
                    Y_ref[i][c] = k[c] * ref[i][c];
                }
            double rb = psnr_bruneton(L, ref, 10.0), yb = psnr_bruneton(Y, Y_ref, 1e-4);
            double rl = psnr_linear(L, ref), yl = psnr_linear(Y, Y_ref);
            double peak = 0.0, s2 = 0.0; /* the kernel's noise: the variance of its mean */
            for (int i = 0; i < PIXELS; i++)
                for (int c = 0; c < 3; c++)
                    peak = fmax(peak, ref[i][c]), s2 += se[i][c] * se[i][c];
            double noise = 10.0 * log10(peak * peak / (s2 / (3.0 * PIXELS)));
            double need_r = is ? 35.0 : 47.0, need_y = is ? 35.0 : 40.0;
            printf("sun %2.0f deg, camera %5.0f m: radiance %.1f dB (linear %.1f), luminance "
                   "%.1f dB (linear %.1f); thresholds %.0f / %.0f; noise alone %.1f dB\n",
                   sun_zenith[is], altitude_m[ia], rb, rl, yb, yl, need_r, need_y, noise);
            CHECK(rb >= need_r);
            CHECK(rl >= need_r);
            CHECK(yb >= need_y);
            CHECK(yl >= need_y);
        }
    printf("host reference: %.1f s for %d rays\n", host_seconds, 4 * PIXELS);
    test_probe_close(&t);
    atmo_cl_close(&cl);
    return test_finish();
}
