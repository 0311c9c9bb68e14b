/* probe.c — a method's radiance for rays, outside of an image (atmo/probe.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/probe.h"
#include "atmo/render.h"

int atmo_probe_open(atmo_probe *p, const atmo_plan *plan, const char *device, atmo_err *e)
{
    int rc;
    cl_int err;
    if ((rc = atmo_cl_open(&p->cl, device, e)))
        return rc;
    p->cl_open = 1;
    atmo_cl_build_options bo = {plan->fragments, plan->fragment_count, plan->defines, NULL, 1,
                                NULL};
    atmo_cl_build_info bi;
    if ((rc = atmo_cl_build(&p->cl, &bo, &p->program, &bi, e)))
        return rc;
    p->seconds_build = bi.seconds;
    p->scene = clCreateBuffer(p->cl.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                              sizeof plan->gpu, (void *)&plan->gpu, &err);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clCreateBuffer(scene)", err);
    atmo_precompute_info info;
    rc = atmo_precompute(&p->cl, p->program, plan, p->scene, p->luts, &info, e);
    p->seconds_precompute = info.seconds;
    return rc;
}

int atmo_probe_rays(atmo_probe *p, const float4 *rays, int n, int samples, double (*mean)[3],
                    double (*se)[3], atmo_err *e)
{
    atmo_cl *cl = &p->cl;
    int rc = ATMO_OK, per = (samples + ATMO_PROBE_BATCHES - 1) / ATMO_PROBE_BATCHES;
    size_t items = (size_t)n * ATMO_PROBE_BATCHES;
    float4 *all = malloc(sizeof(float4) * items), *out = malloc(sizeof(float4) * items);
    cl_mem b_rays = NULL, b_out = NULL;
    cl_kernel k = NULL;
    cl_int err;
    if (!all || !out) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for %d rays", n);
        goto cleanup;
    }
    for (size_t i = 0; i < items; i++)
        all[i] = rays[i / ATMO_PROBE_BATCHES];
    b_rays = clCreateBuffer(cl->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                            sizeof(float4) * items, all, &err);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, "clCreateBuffer(rays)", err);
        goto cleanup;
    }
    b_out = clCreateBuffer(cl->context, CL_MEM_WRITE_ONLY, sizeof(float4) * items, NULL, &err);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, "clCreateBuffer(radiance)", err);
        goto cleanup;
    }
    k = clCreateKernel(p->program, "sky_probe", &err);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, "clCreateKernel(sky_probe)", err);
        goto cleanup;
    }
    cl_uint count = (cl_uint)items, n_samples = (cl_uint)per;
    err = clSetKernelArg(k, 0, sizeof p->scene, &p->scene);
    for (int i = 0; i < ATMO_PLAN_LUTS && err == CL_SUCCESS; i++)
        err = clSetKernelArg(k, 1 + i, sizeof p->luts[i], &p->luts[i]);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, 1 + ATMO_PLAN_LUTS, sizeof b_rays, &b_rays);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, 2 + ATMO_PLAN_LUTS, sizeof b_out, &b_out);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, 3 + ATMO_PLAN_LUTS, sizeof count, &count);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, 4 + ATMO_PLAN_LUTS, sizeof n_samples, &n_samples);
    size_t local = 64, global = (items + local - 1) / local * local;
    if (err == CL_SUCCESS)
        err = clEnqueueNDRangeKernel(cl->queue, k, 1, NULL, &global, &local, 0, NULL, NULL);
    if (err == CL_SUCCESS)
        err = clEnqueueReadBuffer(cl->queue, b_out, CL_TRUE, 0, sizeof(float4) * items, out, 0,
                                  NULL, NULL);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, "sky_probe", err);
        goto cleanup;
    }
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            double s = 0.0, s2 = 0.0;
            for (int b = 0; b < ATMO_PROBE_BATCHES; b++) {
                const float4 *o = &out[(size_t)i * ATMO_PROBE_BATCHES + (size_t)b];
                double x = c == 0 ? o->x : c == 1 ? o->y : o->z;
                s += x, s2 += x * x;
            }
            double m = s / ATMO_PROBE_BATCHES;
            mean[i][c] = m;
            if (se)
                se[i][c] = sqrt(fmax(s2 / ATMO_PROBE_BATCHES - m * m, 0.0) /
                                (ATMO_PROBE_BATCHES - 1));
        }
cleanup:
    if (k)
        clReleaseKernel(k);
    if (b_out)
        clReleaseMemObject(b_out);
    if (b_rays)
        clReleaseMemObject(b_rays);
    free(out);
    free(all);
    return rc;
}


void atmo_probe_close(atmo_probe *p)
{
    for (int i = ATMO_PLAN_LUTS - 1; i >= 0; i--)
        if (p->luts[i])
            clReleaseMemObject(p->luts[i]);
    if (p->scene)
        clReleaseMemObject(p->scene);
    if (p->program)
        clReleaseProgram(p->program);
    if (p->cl_open)
        atmo_cl_close(&p->cl);
    memset(p, 0, sizeof *p);
}
