/* test_cloud_noise — the cloud layer's noise (kernels/clouds/cloud_noise.h) is bitwise the same
 * on the device as on the host, stays in its range, and its fBm has the spread the coverage
 * field's contrast assumes.
 * labels: kernel unit
 *
 * Oracles:
 *   - bit equality: the host build of the same header (integer lattice hash, correctly rounded
 *     +, -, *, contraction off) against the OpenCL device, for value noise, 6-octave fBm and
 *     the warp at 4096 points spread over [-2e4, 2e4] lattice units (negative cells, cell
 *     borders at integers and halves included): every float must match exactly;
 *   - range: value noise and fBm in [0, 1) (a convex combination of lattice values in
 *     [0, 1 - 2^-24]), the warp in (-1, 1);
 *   - statistics: the lattice values are uniform, so value noise has mean 1/2; over the 2048
 *     points spread over [-2e4, 2e4] (hundreds of cells apart, so independent) the fBm's mean
 *     must be 1/2 within 5 standard errors and its standard deviation
 *     between 0.05 and 0.25 (a 6-octave value fBm: about 0.12; the coverage contrast 3 of
 *     cloud_layer.h maps +-1 such deviation to +-0.36 of coverage). */
#include <math.h>
#include <string.h>
#include "common/compat.h"
#include "clouds/cloud_noise.h"
#include "testcl.h"
#include "testlib.h"

#define NP 4096

static const char probe[] =
    "__kernel void probe(__global const float4 *x, __global float4 *out) {\n"
    "  int i = get_global_id(0);\n"
    "  vec3 p = v3(x[i].x, x[i].y, x[i].z);\n"
    "  vec3 w = noise_warp(p, 7u);\n"
    "  out[2 * i] = (float4)(noise_value(p, 3u), noise_fbm(p, 6, 5u), w.x, w.y);\n"
    "  out[2 * i + 1] = (float4)(w.z, noise_value(p, 0u), 0.0f, 0.0f);\n"
    "}\n";

int main(void)
{
    static float4 x[NP], got[2 * NP];
    for (int i = 0; i < NP; i++) {
        float a = rng_uniform(1u, (uint)i, 0u, 0u), b = rng_uniform(1u, (uint)i, 0u, 1u);
        float c = rng_uniform(1u, (uint)i, 0u, 2u);
        float scale = i < NP / 4 ? 4.0f : (i < NP / 2 ? 400.0f : 40000.0f);
        x[i].x = (a - 0.5f) * scale;
        x[i].y = (b - 0.5f) * scale;
        x[i].z = (c - 0.5f) * scale;
        if (i % 16 == 0) /* on cell borders */
            x[i].x = floorf(x[i].x), x[i].y = floorf(x[i].y) + 0.5f;
        x[i].w = 0.0f;
    }
    atmo_cl cl;
    test_cl_open(&cl);
    const char *fragments[] = {"kernels/common/compat.h", "kernels/common/rng.h",
                               "kernels/clouds/cloud_noise.h"};
    cl_program prog = test_cl_build(&cl, fragments, 3, probe);
    cl_int err;
    cl_kernel k = clCreateKernel(prog, "probe", &err);
    CHECK(err == CL_SUCCESS);
    cl_mem bx = test_cl_buffer(&cl, sizeof x, x), bo = test_cl_buffer(&cl, sizeof got, NULL);
    CHECK(clSetKernelArg(k, 0, sizeof bx, &bx) == CL_SUCCESS);
    CHECK(clSetKernelArg(k, 1, sizeof bo, &bo) == CL_SUCCESS);
    test_cl_run_1d(&cl, k, NP);
    test_cl_read(&cl, bo, sizeof got, got);
    int differ = 0, out_of_range = 0;
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < NP; i++) {
        vec3 p = v3(x[i].x, x[i].y, x[i].z), w = noise_warp(p, 7u);
        float want[6] = {noise_value(p, 3u), noise_fbm(p, 6, 5u), w.x, w.y, w.z,
                         noise_value(p, 0u)};
        float have[6] = {got[2 * i].x, got[2 * i].y, got[2 * i].z, got[2 * i].w,
                         got[2 * i + 1].x, got[2 * i + 1].y};
        differ += memcmp(want, have, sizeof want) != 0;
        out_of_range += !(want[0] >= 0.0f && want[0] < 1.0f && want[1] >= 0.0f &&
                          want[1] < 1.0f && want[5] >= 0.0f && want[5] < 1.0f);
        for (int c = 2; c < 5; c++)
            out_of_range += !(want[c] > -1.0f && want[c] < 1.0f);
        if (i >= NP / 2) { /* points cells apart: independent samples */
            sum += want[1];
            sum2 += (double)want[1] * want[1];
        }
    }
    int ns = NP - NP / 2;
    double mean = sum / ns, sd = sqrt(fmax(sum2 / ns - mean * mean, 0.0));
    printf("noise: %d of %d points differ between host and device, %d out of range; fBm mean "
           "%.4f, sd %.4f\n",
           differ, NP, out_of_range, mean, sd);
    CHECK(differ == 0);
    CHECK(out_of_range == 0);
    CHECK_ABS(mean, 0.5, 5.0 * sd / sqrt((double)ns));
    CHECK(sd > 0.05 && sd < 0.25);
    clReleaseMemObject(bo);
    clReleaseMemObject(bx);
    clReleaseKernel(k);
    clReleaseProgram(prog);
    atmo_cl_close(&cl);
    return test_finish();
}
