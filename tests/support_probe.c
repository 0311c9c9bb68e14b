/* Implementation of tests/testprobe.h. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "testprobe.h"

static const char probe_source[] =
    "__kernel void test_probe(__global const atmo_gpu_scene *s, ATMO_LUT_PARAMS,\n"
    "                         __global const float4 *rays, __global float4 *sky_out,\n"
    "                         __global float4 *sun_out, uint n, uint batches, uint samples,\n"
    "                         uint stride) {\n"
    "  uint g = get_global_id(0);\n"
    "  if (g >= n * batches) return;\n"
    "  uint i = g / batches, b = g % batches;\n"
    "  float4 q = rays[i];\n"
    "  float3 sky_sum = (float3)(0.0f), sun_sum = (float3)(0.0f);\n"
    "  uint bad = 0u;\n"
    "  for (uint k = 0u; k < samples; k++) {\n"
    "    float3 sky, sun;\n"
    "    sky_radiance(s, ATMO_LUT_ARGS, q.x, q.y, q.z, q.w, i * stride + b, k, &sky, &sun);\n"
    "    int ok = all(isfinite(sky)) && all(isfinite(sun)) && all(sky >= 0.0f) &&\n"
    "             all(sun >= 0.0f);\n"
    "    bad += ok ? 0u : 1u;\n"
    "    sky_sum += sky;\n"
    "    sun_sum += sun;\n"
    "  }\n"
    "  sky_out[g] = (float4)(sky_sum / (float)samples, (float)bad);\n"
    "  sun_out[g] = (float4)(sun_sum / (float)samples, 0.0f);\n"
    "}\n";

void test_probe_open(test_probe *t, atmo_cl *cl, const atmo_plan *plan)
{
    memset(t, 0, sizeof *t);
    t->cl = cl;
    t->program = test_plan_program(cl, plan, probe_source);
    t->scene = test_cl_buffer(cl, sizeof plan->gpu, &plan->gpu);
    test_precompute(cl, t->program, t->scene, plan, t->luts);
}

void test_probe_rays(test_probe *t, const float4 *rays, int n, int batches, int samples,
                     int stride, double (*mean)[3], double (*se)[3], double (*sun)[3], int *bad)
{
    size_t items = (size_t)n * (size_t)batches;
    float4 *sky_h = malloc(sizeof(float4) * items), *sun_h = malloc(sizeof(float4) * items);
    if (!sky_h || !sun_h) {
        fprintf(stderr, "test_probe_rays: out of memory for %d rays\n", n);
        exit(1);
    }
    cl_mem b_rays = test_cl_buffer(t->cl, sizeof(float4) * (size_t)n, rays);
    cl_mem b_sky = test_cl_buffer(t->cl, sizeof(float4) * items, NULL);
    cl_mem b_sun = test_cl_buffer(t->cl, sizeof(float4) * items, NULL);
    cl_int err;
    cl_kernel k = clCreateKernel(t->program, "test_probe", &err);
    if (err != CL_SUCCESS) {
        fprintf(stderr, "clCreateKernel(test_probe): %s\n", atmo_cl_error_string(err));
        exit(1);
    }
    cl_uint u_n = (cl_uint)n, u_batches = (cl_uint)batches, u_samples = (cl_uint)samples;
    cl_uint u_stride = stride == TEST_PROBE_COMMON ? 0u : (cl_uint)batches;
    err = clSetKernelArg(k, 0, sizeof t->scene, &t->scene);
    int a = test_bind_buffers(k, t->luts);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, a, sizeof b_rays, &b_rays);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, a + 1, sizeof b_sky, &b_sky);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, a + 2, sizeof b_sun, &b_sun);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, a + 3, sizeof u_n, &u_n);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, a + 4, sizeof u_batches, &u_batches);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, a + 5, sizeof u_samples, &u_samples);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, a + 6, sizeof u_stride, &u_stride);
    if (err != CL_SUCCESS) {
        fprintf(stderr, "clSetKernelArg(test_probe): %s\n", atmo_cl_error_string(err));
        exit(1);
    }
    test_cl_run_1d(t->cl, k, items);
    test_cl_read(t->cl, b_sky, sizeof(float4) * items, sky_h);
    test_cl_read(t->cl, b_sun, sizeof(float4) * items, sun_h);
    for (int i = 0; i < n; i++) {
        int nbad = 0;
        for (int c = 0; c < 3; c++) {
            double s = 0.0, s2 = 0.0, s_sun = 0.0;
            for (int b = 0; b < batches; b++) {
                const float4 *o = &sky_h[(size_t)i * (size_t)batches + (size_t)b];
                const float4 *p = &sun_h[(size_t)i * (size_t)batches + (size_t)b];
                double x = c == 0 ? o->x : c == 1 ? o->y : o->z;
                s += x, s2 += x * x;
                s_sun += c == 0 ? p->x : c == 1 ? p->y : p->z;
                if (c == 0)
                    nbad += (int)o->w;
            }
            double m = s / batches;
            mean[i][c] = m;
            if (se)
                se[i][c] = batches > 1 ? sqrt(fmax(s2 / batches - m * m, 0.0) / (batches - 1))
                                       : 0.0;
            if (sun)
                sun[i][c] = s_sun / batches;
        }
        if (bad)
            bad[i] = nbad;
    }
    clReleaseKernel(k);
    clReleaseMemObject(b_sun);
    clReleaseMemObject(b_sky);
    clReleaseMemObject(b_rays);
    free(sun_h);
    free(sky_h);
}

void test_probe_close(test_probe *t)
{
    test_release_luts(t->luts);
    if (t->scene)
        clReleaseMemObject(t->scene);
    if (t->program)
        clReleaseProgram(t->program);
    memset(t, 0, sizeof *t);
}
