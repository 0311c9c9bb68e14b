/* test_transmittance — the transmittance LUT kernel and its lookup, on the OpenCL device.
 * labels: kernel
 *
 * Oracles: (1) the published slant transmittances from sea level and from 10 km of
 * shared/reference/atmosphere.md (numerical integration with 4e5 Simpson intervals, six digits);
 * (2) the host double-precision quadrature atmo_ref_transmittance (1e-7 relative) on a grid of
 * altitudes and view angles covering the whole LUT. Target: relative error <= 1e-3
 * wherever T > 1e-2 (below that the relative error of an absolute float error grows without
 * meaning; there we require an absolute error <= 1e-5). The default 256 x 64 LUT is used. */
#include <math.h>
#include <stdlib.h>
#include "atmo/atmosphere_ref.h"
#include "testlib.h"
#include "testscene.h"

static const char probe[] =
    "__kernel void probe(__global const atmo_gpu_scene *s, __global const float4 *lut,\n"
    "                    __global const float2 *rm, __global float4 *out, uint n) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  float3 t = atmosphere_transmittance_to_top(&s->atmosphere, lut, s->transmittance_width,\n"
    "                                            s->transmittance_height, rm[i].x, rm[i].y);\n"
    "  out[i] = (float4)(t, 0.0f);\n"
    "}\n";

#define MAX_RAYS 4096

static void check_t(double got, double want, const char *what, double r, double mu)
{
    double tol = want > 1e-2 ? 1e-3 * want : 1e-5;
    if (fabs(got - want) > tol)
        fprintf(stderr, "%s at r = %.1f m, mu = %.6f:\n", what, r, mu);
    CHECK_ABS(got, want, tol);
}

int main(void)
{
    atmo_scene scene;
    atmo_plan plan;
    test_scene_preset(&scene, "sky-noon");
    test_plan(&scene, &plan);
    atmo_cl cl;
    test_cl_open(&cl);
    cl_program prog = test_plan_program(&cl, &plan, probe);
    cl_mem b_scene = test_cl_buffer(&cl, sizeof plan.gpu, &plan.gpu);
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
    test_precompute(&cl, prog, b_scene, &plan, luts);
    cl_mem b_lut = luts[0];

    /* rays: the published table first, then a grid */
    static float2 rm[MAX_RAYS];
    static double want[MAX_RAYS][3];
    int n = 0;
    const double R = 6360e3;
    static const double zenith[] = {0, 30, 45, 60, 70, 80, 85, 88, 89, 90};
    static const double table[][3] = {
        {0.940384, 0.867670, 0.762421}, {0.931519, 0.848905, 0.731183},
        {0.916869, 0.818410, 0.681717}, {0.884830, 0.753950, 0.582446},
        {0.837237, 0.663808, 0.455719}, {0.713027, 0.459509, 0.221771},
        {0.543730, 0.249563, 0.0636832}, {0.330864, 0.0853145, 6.1637e-3},
        {0.226211, 0.0392558, 1.0956e-3}, {0.106443, 9.5845e-3, 5.2123e-5}};
    for (int i = 0; i < 10; i++, n++) {
        rm[n].x = (float)R;
        rm[n].y = (float)cos(zenith[i] * M_PI / 180.0);
        for (int c = 0; c < 3; c++)
            want[n][c] = table[i][c];
    }
    static const double z10[] = {0, 80, 90};
    static const double t10[][3] = {{0.977242, 0.942490, 0.925893},
                                    {0.881546, 0.723375, 0.652278},
                                    {0.533877, 0.211402, 0.0669423}};
    for (int i = 0; i < 3; i++, n++) {
        rm[n].x = (float)(R + 10e3);
        rm[n].y = (float)cos(z10[i] * M_PI / 180.0);
        for (int c = 0; c < 3; c++)
            want[n][c] = t10[i][c];
    }
    int n_table = n;
    for (int i = 0; i <= 30; i++)
        for (int j = 0; j <= 60; j++, n++) {
            double r = R + 60e3 * pow(i / 30.0, 2.0); /* denser near the ground */
            double mu_h = -sqrt(fmax(1.0 - R * R / (r * r), 0.0));
            double mu = mu_h + (1.0 - mu_h) * pow(j / 60.0, 3.0); /* denser near the horizon */
            rm[n].x = (float)r;
            rm[n].y = (float)mu;
            /* the float ray is the one evaluated: give the reference the same numbers, and
             * leave out rays that rounding turned into ground hits (the LUT holds sky rays) */
            if (atmo_ref_ray_hits_ground((double)rm[n].x, (double)rm[n].y, R)) {
                n--;
                continue;
            }
            atmo_ref_transmittance(&plan.atmosphere, (double)rm[n].x, (double)rm[n].y, want[n]);
        }

    cl_mem b_rm = test_cl_buffer(&cl, sizeof rm, rm);
    cl_mem b_out = test_cl_buffer(&cl, sizeof(float) * 4 * MAX_RAYS, NULL);
    cl_int err;
    cl_kernel k = clCreateKernel(prog, "probe", &err);
    cl_uint count = (cl_uint)n;
    clSetKernelArg(k, 0, sizeof b_scene, &b_scene);
    clSetKernelArg(k, 1, sizeof b_lut, &b_lut);
    clSetKernelArg(k, 2, sizeof b_rm, &b_rm);
    clSetKernelArg(k, 3, sizeof b_out, &b_out);
    clSetKernelArg(k, 4, sizeof count, &count);
    test_cl_run_1d(&cl, k, (size_t)n);
    static float out[MAX_RAYS][4];
    test_cl_read(&cl, b_out, sizeof out, out);

    double worst = 0.0;
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            check_t(out[i][c], want[i][c], i < n_table ? "published table" : "double reference",
                    rm[i].x, rm[i].y);
            if (want[i][c] > 1e-2)
                worst = fmax(worst, fabs(out[i][c] - want[i][c]) / want[i][c]);
        }
    printf("transmittance LUT %dx%d: worst relative error %.2e where T > 1e-2 (%d rays)\n",
           plan.gpu.transmittance_width, plan.gpu.transmittance_height, worst, n);

    clReleaseKernel(k);
    clReleaseMemObject(b_out);
    clReleaseMemObject(b_rm);
    test_release_luts(luts);
    clReleaseMemObject(b_scene);
    clReleaseProgram(prog);
    atmo_cl_close(&cl);
    return test_finish();
}
