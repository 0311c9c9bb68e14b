/* test_march — method "march" (kernels/atmosphere/method_march.h, kernels/atmosphere/ms_lut.h) against its limits.
 * labels: kernel
 *
 * Oracles:
 *  1. Zero multiple scattering: with the Psi_ms LUT zeroed, the march must be method "single"
 *     term for term (same segments, same random offsets from the same seed). Tolerance 1e-5
 *     relative: float rounding of a 32-term sum (~32 x 6e-8), no modelling error allowed.
 *  2. Energy: orders >= 2 only add light, so march > single on every sky ray in daylight, and
 *     by no more than the published shortfall of single scattering (atmosphere.md: single is
 *     8-34 % short in luminance, up to ~47 % in blue, more near the sunset horizon) — bounded
 *     here generously at march / single <= 2.5 for sun zenith <= 80 deg.
 *  3. Optically thin limit: the second order grows as the square of the scattering coefficients
 *     and the first linearly, so (march - single) / single must fall in proportion to a common
 *     factor k on Rayleigh and aerosol coefficients (ground albedo 0, so the lit ground does
 *     not add a first-order source): the ratio of that excess at k = 0.01 and k = 0.1 must be
 *     0.1 within the O(tau) correction of the thin limit (tau <= 0.1 at k = 0.1 even along
 *     the 5-degree rays used: +-30 %).
 *  4. No NaN/Inf: cameras from the ground to 1e8 m, sun zenith 0..180 deg, all view directions
 *     (method_fast's fallback uses the same march; test_fast scans the LUT path).
 * Each probe averages 16 samples (16 random offsets) of sky_probe, as a render would. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "testlib.h"
#include "testscene.h"

#define MAX_RAYS 4096
#define SAMPLES 16u

typedef struct probe_ctx {
    atmo_cl cl;
    cl_program prog;
    cl_mem scene, luts[ATMO_PLAN_MAX_BUFFERS];
} probe_ctx;

static void ctx_open(probe_ctx *c, atmo_cl *cl, const atmo_plan *p)
{
    c->cl = *cl;
    c->prog = test_plan_program(cl, p, NULL);
    c->scene = test_cl_buffer(cl, sizeof p->gpu, &p->gpu);
    test_precompute(cl, c->prog, c->scene, p, c->luts);
}

static void ctx_close(probe_ctx *c)
{
    test_release_luts(c->luts);
    clReleaseMemObject(c->scene);
    clReleaseProgram(c->prog);
}

static void probe(probe_ctx *c, const float4 *rays, int n, float (*out)[4])
{
    cl_int err;
    cl_mem b_rays = test_cl_buffer(&c->cl, sizeof(float4) * (size_t)n, rays);
    cl_mem b_out = test_cl_buffer(&c->cl, sizeof(float4) * (size_t)n, NULL);
    cl_kernel k = clCreateKernel(c->prog, "sky_probe", &err);
    cl_uint count = (cl_uint)n, samples = SAMPLES;
    clSetKernelArg(k, 0, sizeof c->scene, &c->scene);
    int a = test_bind_buffers(k, c->luts);
    clSetKernelArg(k, a, sizeof b_rays, &b_rays);
    clSetKernelArg(k, a + 1, sizeof b_out, &b_out);
    clSetKernelArg(k, a + 2, sizeof count, &count);
    clSetKernelArg(k, a + 3, sizeof samples, &samples);
    test_cl_run_1d(&c->cl, k, (size_t)n);
    test_cl_read(&c->cl, b_out, sizeof(float4) * (size_t)n, out);
    clReleaseKernel(k);
    clReleaseMemObject(b_out);
    clReleaseMemObject(b_rays);
}

/* Rays from the ground (1 m) for sun zenith 0..80 deg, views from the zenith to 5 deg above
 * the horizon toward, across and away from the sun. */
static int sky_rays(double bottom_m, float4 *rays)
{
    static const double sz[] = {0, 30, 60, 80}, vz[] = {0, 30, 60, 75, 85}, va[] = {0, 90, 180};
    int n = 0;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 5; j++)
            for (int k = 0; k < 3; k++) {
                double ts = sz[i] * M_PI / 180, tv = vz[j] * M_PI / 180, pv = va[k] * M_PI / 180;
                float4 q = {(float)(bottom_m + 1.0), (float)cos(tv), (float)cos(ts),
                            (float)(sin(tv) * sin(ts) * cos(pv) + cos(tv) * cos(ts))};
                rays[n++] = q;
            }
    return n;
}

static void run(atmo_cl *cl, const char *method, const char *const *sets, int nsets,
                int zero_ms, const float4 *rays, int n, float (*out)[4])
{
    atmo_scene s;
    atmo_plan p;
    char buf[64];
    test_scene_preset(&s, "sky-noon");
    snprintf(buf, sizeof buf, "atmosphere.method=%s", method);
    test_scene_set(&s, buf);
    for (int i = 0; i < nsets; i++)
        test_scene_set(&s, sets[i]);
    test_plan(&s, &p);
    probe_ctx c;
    ctx_open(&c, cl, &p);
    if (zero_ms) {
        float zero = 0.0f;
        clEnqueueFillBuffer(cl->queue, test_plan_buffer(&p, c.luts, "ms_lut"), &zero, sizeof zero,
                            0, atmo_plan_buffer_find(&p, "ms_lut")->bytes, 0, NULL, NULL);
        clFinish(cl->queue);
    }
    probe(&c, rays, n, out);
    ctx_close(&c);
}

int main(void)
{
    atmo_cl cl;
    test_cl_open(&cl);
    static float4 rays[MAX_RAYS];
    static float single[MAX_RAYS][4], march[MAX_RAYS][4], zeroed[MAX_RAYS][4];
    const double R = 6360e3;
    int n = sky_rays(R, rays);

    /* 1 and 2 */
    run(&cl, "single", NULL, 0, 0, rays, n, single);
    run(&cl, "march", NULL, 0, 1, rays, n, zeroed);
    run(&cl, "march", NULL, 0, 0, rays, n, march);
    double worst_zero = 0.0, lo = 1e9, hi = 0.0;
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            CHECK_REL(zeroed[i][c], single[i][c], 1e-5);
            worst_zero = fmax(worst_zero, fabs(zeroed[i][c] / single[i][c] - 1.0));
            double ratio = march[i][c] / single[i][c];
            CHECK(ratio > 1.0 && ratio <= 2.5);
            lo = fmin(lo, ratio), hi = fmax(hi, ratio);
        }
    printf("zeroed Psi vs single: worst %.2e; march/single on sky rays: %.3f .. %.3f\n",
           worst_zero, lo, hi);

    /* 3: views at 0, 60 and 85 deg, sun at 30 deg, toward and away from the sun */
    static const char *const thin[2][4] = {
        {"atmosphere.rayleigh_coefficient=1.24062e-7", "atmosphere.mie_extinction_per_m=4.44e-7",
         "atmosphere.ground_albedo=0", "atmosphere.ozone_column_du=0"},
        {"atmosphere.rayleigh_coefficient=1.24062e-8", "atmosphere.mie_extinction_per_m=4.44e-8",
         "atmosphere.ground_albedo=0", "atmosphere.ozone_column_du=0"}};
    static const int pick[] = {15, 17, 21, 23, 27, 29};
    float4 thin_rays[6];
    for (int i = 0; i < 6; i++)
        thin_rays[i] = rays[pick[i]];
    float s_thin[2][6][4], m_thin[2][6][4];
    double excess[2][6][3];
    for (int k = 0; k < 2; k++) {
        run(&cl, "single", thin[k], 4, 0, thin_rays, 6, s_thin[k]);
        run(&cl, "march", thin[k], 4, 0, thin_rays, 6, m_thin[k]);
        for (int i = 0; i < 6; i++)
            for (int c = 0; c < 3; c++)
                excess[k][i][c] = m_thin[k][i][c] / s_thin[k][i][c] - 1.0;
    }
    double rmin = 1e9, rmax = 0.0;
    for (int i = 0; i < 6; i++)
        for (int c = 0; c < 3; c++) {
            double q = excess[1][i][c] / excess[0][i][c];
            CHECK(q > 0.07 && q < 0.13);
            rmin = fmin(rmin, q), rmax = fmax(rmax, q);
        }
    printf("thin limit: excess(k=0.01) / excess(k=0.1) = %.3f .. %.3f (0.1 expected)\n", rmin,
           rmax);

    /* 4 */
    static const char *const alt_sets[] = {"camera.position_m=0,0,0", "camera.position_m=0,1,0",
                                           "camera.position_m=0,1e4,0",
                                           "camera.position_m=0,6e4,0",
                                           "camera.position_m=0,1e6,0",
                                           "camera.position_m=0,1e8,0"};
    static const double altitudes[] = {0, 1, 1e4, 6e4, 1e6, 1e8};
    int bad = 0, total = 0;
    for (int ia = 0; ia < 6; ia++) {
        const char *set[1] = {alt_sets[ia]};
        int m = 0;
        for (int is = 0; is <= 18; is++)
            for (int iv = 0; iv <= 24; iv++)
                for (int iz = 0; iz < 3; iz++) {
                    double ts = is * 10.0 * M_PI / 180, tv = iv * 7.5 * M_PI / 180;
                    double pv = iz * 90.0 * M_PI / 180;
                    float4 q = {(float)(R + altitudes[ia]), (float)cos(tv), (float)cos(ts),
                                (float)(sin(tv) * sin(ts) * cos(pv) + cos(tv) * cos(ts))};
                    rays[m++] = q;
                }
        run(&cl, "march", set, 1, 0, rays, m, march);
        for (int i = 0; i < m; i++)
            for (int c = 0; c < 3; c++) {
                total++;
                if (!isfinite(march[i][c]) || march[i][c] < 0.0f)
                    bad++;
            }
    }
    CHECK(bad == 0);
    printf("scan: %d of %d values non-finite or negative\n", bad, total);
    atmo_cl_close(&cl);
    return test_finish();
}
