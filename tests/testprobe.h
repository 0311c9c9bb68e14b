/* testprobe.h — a method's sky and sun radiance for rays (r, mu, mu_s, nu), with the random
 * numbers under the test's control (the probe kernel of atmo/probe.h gives every ray its own).
 *
 * test_probe_rays runs `batches` independent batches of `samples` samples of the method's
 * sky_radiance per ray and returns the mean over batches and its standard error (the spread of
 * the batch means over sqrt(batches)). Batch b of ray i draws its random numbers as pixel
 * i * stride + b:
 *   stride = TEST_PROBE_COMMON (0): every ray gets the same random numbers (common random
 *     numbers): a scan over a smooth family of rays stays smooth, and two rays that are the
 *     same ray written two ways (e.g. from space and from the top of the atmosphere) get the same
 *     march offsets, so a deterministic integrator differs only by float rounding;
 *   stride = TEST_PROBE_INDEPENDENT: each ray its own stream, as a render has (z-tests).
 * `bad` counts, per ray, the samples whose sky or sun radiance was NaN, infinite or negative
 * (a mean could hide a negative sample). Any pointer but mean may be NULL. */
#ifndef ATMO_TESTPROBE_H
#define ATMO_TESTPROBE_H
#include "testscene.h"

#define TEST_PROBE_COMMON 0
#define TEST_PROBE_INDEPENDENT 1

typedef struct test_probe {
    atmo_cl *cl;
    cl_program program;
    cl_mem scene;
    cl_mem luts[ATMO_PLAN_MAX_BUFFERS];
} test_probe;

/* Build the plan's program with the probe kernel (cached binaries), upload the scene, run the
 * precompute passes (exits 1 on any error). */
void test_probe_open(test_probe *t, atmo_cl *cl, const atmo_plan *plan);
void test_probe_rays(test_probe *t, const float4 *rays, int n, int batches, int samples,
                     int stride, double (*mean)[3], double (*se)[3], double (*sun)[3], int *bad);
void test_probe_close(test_probe *t);

#endif
