/* test_rng — the counter-based RNG of kernels/common/rng.h.
 * labels: stat kernel
 *
 * Oracle: statistical tests. Chi-square goodness of fit of 10^6 draws to the uniform
 * distribution on 256 bins for each of the dimensions the renderer uses; independence by
 * chi-square on a 32 x 32 grid of pairs (two dimensions of one sample, the same dimension of
 * neighbouring samples, of neighbouring pixels, and of two seeds). Each statistic must stay
 * below the p = 1e-4 critical value; the counters are fixed, so the test is deterministic.
 * Second oracle: the same header compiled by PoCL gives bitwise the same numbers as the host. */
#include <stdlib.h>
#include <string.h>
#include "common/rng.h"
#include "testcl.h"
#include "testlib.h"

#define N 1000000

static double chi2_uniform(uint seed, uint dim, int bins)
{
    int *count = calloc((size_t)bins, sizeof *count);
    for (uint i = 0; i < N; i++) {
        /* walk pixels and samples together, as a render does */
        float u = rng_uniform(seed, i % 4096u, i / 4096u, dim);
        count[(int)(u * (float)bins)]++;
    }
    double expect = (double)N / bins, chi2 = 0.0;
    for (int b = 0; b < bins; b++)
        chi2 += (count[b] - expect) * (count[b] - expect) / expect;
    free(count);
    return chi2;
}

typedef struct { uint seed, pixel, sample, dim; } counter;

static double chi2_pairs(counter step_a, counter step_b, counter offset_b)
{
    enum { G = 32 };
    static int count[G * G];
    for (int i = 0; i < G * G; i++)
        count[i] = 0;
    for (uint i = 0; i < N; i++) {
        uint p = i % 1000u, s = i / 1000u;
        float a = rng_uniform(step_a.seed, p * step_a.pixel, s * step_a.sample, step_a.dim);
        float b = rng_uniform(step_b.seed + offset_b.seed, p * step_b.pixel + offset_b.pixel,
                              s * step_b.sample + offset_b.sample, step_b.dim + offset_b.dim);
        count[(int)(a * G) * G + (int)(b * G)]++;
    }
    double expect = (double)N / (G * G), chi2 = 0.0;
    for (int i = 0; i < G * G; i++)
        chi2 += (count[i] - expect) * (count[i] - expect) / expect;
    return chi2;
}

static const char probe[] =
    "__kernel void probe(__global uint *out, uint n) {\n"
    "  uint i = get_global_id(0); if (i >= n) return;\n"
    "  out[2 * i] = rng_hash(7u, i, i * 3u, i % 5u);\n"
    "  out[2 * i + 1] = as_uint(rng_uniform(i, 11u, i, 2u));\n"
    "}\n";

int main(void)
{
    double crit_uniform = test_chi2_critical_1e4(255);
    for (uint dim = 0; dim < 4; dim++) {
        double c = chi2_uniform(1234u, dim, 256);
        CHECK_ABS(c, 0.0, crit_uniform);
    }
    CHECK_ABS(chi2_uniform(0u, 0u, 256), 0.0, crit_uniform); /* seed 0 is not special */

    double crit_pairs = test_chi2_critical_1e4(32 * 32 - 1);
    counter unit = {5u, 1u, 1u, 0u};
    counter dim1 = {5u, 1u, 1u, 1u}, none = {0u, 0u, 0u, 0u};
    CHECK_ABS(chi2_pairs(unit, dim1, none), 0.0, crit_pairs);            /* dims 0 and 1 */
    CHECK_ABS(chi2_pairs(unit, unit, (counter){0u, 0u, 1u, 0u}), 0.0, crit_pairs); /* sample + 1 */
    CHECK_ABS(chi2_pairs(unit, unit, (counter){0u, 1u, 0u, 0u}), 0.0, crit_pairs); /* pixel + 1 */
    CHECK_ABS(chi2_pairs(unit, unit, (counter){1u, 0u, 0u, 0u}), 0.0, crit_pairs); /* seed + 1 */

    /* host and device agree bit for bit */
    atmo_cl cl;
    test_cl_open(&cl);
    const char *fragments[] = {"kernels/common/compat.h", "kernels/common/rng.h"};
    cl_program prog = test_cl_build(&cl, fragments, 2, probe);
    cl_int err;
    cl_kernel k = clCreateKernel(prog, "probe", &err);
    enum { M = 4096 };
    cl_mem out = test_cl_buffer(&cl, sizeof(uint) * 2 * M, NULL);
    cl_uint n = M;
    clSetKernelArg(k, 0, sizeof out, &out);
    clSetKernelArg(k, 1, sizeof n, &n);
    test_cl_run_1d(&cl, k, M);
    static uint got[2 * M];
    test_cl_read(&cl, out, sizeof got, got);
    int mismatches = 0;
    for (uint i = 0; i < M; i++) {
        float u = rng_uniform(i, 11u, i, 2u);
        uint ubits;
        memcpy(&ubits, &u, sizeof ubits);
        mismatches += got[2 * i] != rng_hash(7u, i, i * 3u, i % 5u);
        mismatches += got[2 * i + 1] != ubits;
    }
    CHECK(mismatches == 0);
    clReleaseMemObject(out);
    clReleaseKernel(k);
    clReleaseProgram(prog);
    atmo_cl_close(&cl);
    return test_finish();
}
