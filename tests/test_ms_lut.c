/* test_ms_lut — the multiple-scattering transfer LUT Psi_ms (kernels/atmosphere/ms_lut.h, ms_lut.cl).
 * labels: kernel
 *
 * Oracles:
 *  1. Quadrature convergence: the default LUT (16 x 8 directions, 20 segments) against one
 *     with 4x the directions and 3x the segments (64 x 16, 60): every texel where Psi is above
 *     1e-3 of its maximum within 2 % (the default's quadrature error; the fine one's is several
 *     times smaller, since both the direction midpoints and the exact-exponential segments
 *     converge at least as 1/n).
 *  2. Properties: finite and >= 0 everywhere, > 0 wherever the sun is above the horizon,
 *     0 < f_ms < 1 (a fraction of scattered light), Psi growing with mu_s at the ground
 *     for mu_s > 0 (more light, less extinction), and smooth along mu_s: no second difference
 *     above 10 % of the row's maximum on the 64-point grid (a kink or a band of bad texels
 *     shows up as such) for mu_s >= 0.1. Across the terminator (mu_s ~ 0) Psi at low altitude
 *     rises from ~0 within a few degrees; the mu_s axis is sqrt-mapped (ms_lut.h) to resolve it.
 *     The convergence check (1) is likewise limited to mu_s >= 0: twilight texels, below 1e-2
 *     of the maximum, converge slower (measured: up to 32 % off the finer grid).
 *  3. Thin limit: Psi is first-order light, so it scales as the scattering coefficients when
 *     they fall by k (ground albedo 0: the lit ground would add a source independent of k);
 *     Psi(k = 0.01) / Psi(k = 0.1) = 0.1 within the O(tau) attenuation difference of the thin
 *     limit (+-25 % at mu_s >= 0.29, where the sun's air mass keeps tau <= 0.15 at k = 0.1).
 *  4. f_ms -> 0 likewise (0.1 within +-25 %).
 *  5. The plan's Legendre coefficients g_1, g_2 of the aerosol phase function (ms.g1,
 *     [2]; ms_lut.h's Mie anisotropy) against closed forms: Henyey-Greenstein g_l = g^l, and
 *     Cornette-Shanks g_1 = 3g(4 + g^2) / (5(2 + g^2)) (phase.h), within 1e-5 (a double
 *     midpoint rule on 20000 intervals of the scattering angle, stored as float). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include "atmo/plan_march.h"
#include "testlib.h"
#include "testscene.h"

#define W ATMO_MS_LUT_WIDTH
#define H ATMO_MS_LUT_HEIGHT

static void make_lut(atmo_cl *cl, const char *const *sets, int nsets, int fine, float (*lut)[4])
{
    atmo_scene s;
    atmo_plan p;
    test_scene_preset(&s, "sky-noon");
    test_scene_set(&s, "atmosphere.method=march");
    for (int i = 0; i < nsets; i++)
        test_scene_set(&s, sets[i]);
    test_plan(&s, &p);
    if (fine) {
        p.gpu.ms.directions_mu *= 2;
        p.gpu.ms.directions_phi *= 2;
        p.gpu.ms.steps *= 3;
    }
    cl_program prog = test_plan_program(cl, &p, NULL);
    cl_mem scene = test_cl_buffer(cl, sizeof p.gpu, &p.gpu);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    test_precompute(cl, prog, scene, &p, luts);
    test_cl_read(cl, test_plan_buffer(&p, luts, "ms_lut"), sizeof(float4) * W * H, lut);
    test_release_luts(luts);
    clReleaseMemObject(scene);
    clReleaseProgram(prog);
}

int main(void)
{
    atmo_cl cl;
    test_cl_open(&cl);
    static float base[W * H][4], fine[W * H][4], thin1[W * H][4], thin2[W * H][4];
    make_lut(&cl, NULL, 0, 0, base);
    make_lut(&cl, NULL, 0, 1, fine);

    double max_psi[3] = {0, 0, 0}, worst_conv = 0.0;
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 3; c++)
            max_psi[c] = fmax(max_psi[c], base[i][c]);
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            const float *t = base[j * W + i];
            double y = 2.0 * i / (W - 1) - 1.0, mu_s = y * fabs(y); /* ms_lut_r_mu_s */
            CHECK(t[3] > 0.0f && t[3] < 1.0f);
            for (int c = 0; c < 3; c++) {
                CHECK(isfinite(t[c]) && t[c] >= 0.0f);
                if (mu_s > 0.0)
                    CHECK(t[c] > 0.0f);
                if (mu_s >= 0.0 && t[c] > 1e-3 * max_psi[c]) {
                    CHECK_REL(t[c], fine[j * W + i][c], 0.02);
                    worst_conv = fmax(worst_conv, fabs(t[c] / fine[j * W + i][c] - 1.0));
                }
                if (j == 0 && mu_s > 0.0 && i > 0)
                    CHECK(t[c] > base[i - 1][c]);
                if (i > 0 && i < W - 1 && mu_s >= 0.1) {
                    double d2 = base[j * W + i - 1][c] - 2.0 * t[c] + base[j * W + i + 1][c];
                    double row_max = 0.0;
                    for (int k = 0; k < W; k++)
                        row_max = fmax(row_max, base[j * W + k][c]);
                    if (fabs(d2) > 0.1 * row_max)
                        fprintf(stderr, "kink at i=%d j=%d c=%d\n", i, j, c);
                    CHECK(fabs(d2) <= 0.1 * row_max);
                }
            }
        }
    printf("Psi max (680/550/440 nm): %.4g %.4g %.4g; f_ms at the ground, sun at zenith %.4f; "
           "quadrature: worst %.2e vs the fine LUT\n",
           max_psi[0], max_psi[1], max_psi[2], base[W - 1][3], worst_conv);

    static const char *const thin[2][4] = {
        {"atmosphere.rayleigh_coefficient=1.24062e-7", "atmosphere.mie_extinction_per_m=4.44e-7",
         "atmosphere.ground_albedo=0", "atmosphere.ozone_column_du=0"},
        {"atmosphere.rayleigh_coefficient=1.24062e-8", "atmosphere.mie_extinction_per_m=4.44e-8",
         "atmosphere.ground_albedo=0", "atmosphere.ozone_column_du=0"}};
    make_lut(&cl, thin[0], 4, 0, thin1);
    make_lut(&cl, thin[1], 4, 0, thin2);
    double qmin = 1e9, qmax = 0.0;
    for (int j = 0; j < H; j++)
        for (int i = 49; i < W; i++) { /* mu_s >= 0.29: air mass <= 3.5 */
            const float *a = thin1[j * W + i], *b = thin2[j * W + i];
            for (int c = 0; c < 4; c++) {
                double q = b[c] / a[c];
                CHECK(q > 0.075 && q < 0.125);
                qmin = fmin(qmin, q), qmax = fmax(qmax, q);
            }
        }
    printf("thin limit: Psi and f_ms ratio k=0.01 / k=0.1 = %.4f .. %.4f (0.1 expected)\n", qmin,
           qmax);

    static const char *const phases[] = {"henyey-greenstein", "cornette-shanks"};
    static const double gs[] = {0.8, 0.3, -0.5, 0.95};
    double worst_g = 0.0;
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < 4; i++) {
            atmo_scene sc;
            atmo_plan p;
            char buf[64];
            test_scene_preset(&sc, "sky-noon");
            test_scene_set(&sc, "atmosphere.method=march");
            snprintf(buf, sizeof buf, "atmosphere.mie_phase=%s", phases[k]);
            test_scene_set(&sc, buf);
            snprintf(buf, sizeof buf, "atmosphere.mie_g=%g", gs[i]);
            test_scene_set(&sc, buf);
            test_plan(&sc, &p);
            double g = (float)gs[i];
            double g1 = k ? 3.0 * g * (4.0 + g * g) / (5.0 * (2.0 + g * g)) : g;
            CHECK(fabs(p.gpu.ms.g1 - g1) <= 1e-5);
            worst_g = fmax(worst_g, fabs(p.gpu.ms.g1 - g1));
            if (!k) {
                CHECK(fabs(p.gpu.ms.g2 - g * g) <= 1e-5);
                worst_g = fmax(worst_g, fabs(p.gpu.ms.g2 - g * g));
            }
        }
    printf("aerosol phase Legendre coefficients: worst %.1e from the closed forms\n", worst_g);
    atmo_cl_close(&cl);
    return test_finish();
}
