/* probe.c — a method's radiance for rays, outside of an image (atmo/probe.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/probe.h"

int atmo_probe_open(atmo_probe *p, const atmo_plan *plan, const char *device, atmo_err *e)
{
    atmo_render_settings rs;
    atmo_render_settings_default(&rs);
    rs.device = device;
    int rc = atmo_session_open(&p->session, plan, &rs, e);
    if (rc)
        return rc;
    const atmo_session_info *in = atmo_session_get_info(p->session);
    p->seconds_build = in->seconds_build;
    p->seconds_precompute = in->seconds_precompute;
    return ATMO_OK;
}

/* Mean and standard error of each ray over its ATMO_PROBE_BATCHES batch means in out. */
static void batch_stats(const float4 *out, int n, double (*mean)[3], double (*se)[3])
{
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
}

/* sky_probe (distances NULL) or sky_probe_segment over n rays, each as ATMO_PROBE_BATCHES
 * items with distinct pixel indices. */
static int run_fast_probe(atmo_probe *p, const float4 *rays, const float *distances, int n,
                       int samples, double (*mean)[3], double (*se)[3], double (*t_mean)[3],
                       double (*t_se)[3], atmo_err *e)
{
    atmo_cl *cl = atmo_session_cl(p->session);
    const char *name = distances ? "sky_probe_segment" : "sky_probe";
    int rc = ATMO_OK, per = (samples + ATMO_PROBE_BATCHES - 1) / ATMO_PROBE_BATCHES;
    size_t items = (size_t)n * ATMO_PROBE_BATCHES;
    float4 *all = malloc(sizeof(float4) * items), *out = malloc(sizeof(float4) * items);
    float4 *out_t = distances ? malloc(sizeof(float4) * items) : NULL;
    float *all_d = distances ? malloc(sizeof(float) * items) : NULL;
    cl_mem b_rays = NULL, b_dist = NULL, b_out = NULL, b_out_t = NULL;
    cl_kernel k = NULL;
    cl_int err;
    if (!all || !out || (distances && (!out_t || !all_d))) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for %d rays", n);
        goto cleanup;
    }
    for (size_t i = 0; i < items; i++) {
        all[i] = rays[i / ATMO_PROBE_BATCHES];
        if (distances)
            all_d[i] = distances[i / ATMO_PROBE_BATCHES];
    }
    b_rays = clCreateBuffer(cl->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                            sizeof(float4) * items, all, &err);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, "clCreateBuffer(rays)", err);
        goto cleanup;
    }
    if (distances) {
        b_dist = clCreateBuffer(cl->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                sizeof(float) * items, all_d, &err);
        if (err != CL_SUCCESS) {
            rc = atmo_cl_fail(e, "clCreateBuffer(distances)", err);
            goto cleanup;
        }
        b_out_t = clCreateBuffer(cl->context, CL_MEM_WRITE_ONLY, sizeof(float4) * items, NULL,
                                 &err);
        if (err != CL_SUCCESS) {
            rc = atmo_cl_fail(e, "clCreateBuffer(transmittance)", err);
            goto cleanup;
        }
    }
    b_out = clCreateBuffer(cl->context, CL_MEM_WRITE_ONLY, sizeof(float4) * items, NULL, &err);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, "clCreateBuffer(radiance)", err);
        goto cleanup;
    }
    k = clCreateKernel(atmo_session_program(p->session), name, &err);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, distances ? "clCreateKernel(sky_probe_segment)"
                                       : "clCreateKernel(sky_probe)", err);
        goto cleanup;
    }
    cl_uint count = (cl_uint)items, n_samples = (cl_uint)per, arg = 0;
    if ((rc = atmo_session_bind(p->session, k, &arg, e)))
        goto cleanup;
    err = clSetKernelArg(k, arg++, sizeof b_rays, &b_rays);
    if (err == CL_SUCCESS && distances)
        err = clSetKernelArg(k, arg++, sizeof b_dist, &b_dist);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, arg++, sizeof b_out, &b_out);
    if (err == CL_SUCCESS && distances)
        err = clSetKernelArg(k, arg++, sizeof b_out_t, &b_out_t);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, arg++, sizeof count, &count);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, arg++, sizeof n_samples, &n_samples);
    size_t local = 64, global = (items + local - 1) / local * local;
    if (err == CL_SUCCESS)
        err = clEnqueueNDRangeKernel(cl->queue, k, 1, NULL, &global, &local, 0, NULL, NULL);
    if (err == CL_SUCCESS)
        err = clEnqueueReadBuffer(cl->queue, b_out, CL_TRUE, 0, sizeof(float4) * items, out, 0,
                                  NULL, NULL);
    if (err == CL_SUCCESS && distances)
        err = clEnqueueReadBuffer(cl->queue, b_out_t, CL_TRUE, 0, sizeof(float4) * items, out_t,
                                  0, NULL, NULL);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, name, err);
        goto cleanup;
    }
    batch_stats(out, n, mean, se);
    if (distances)
        batch_stats(out_t, n, t_mean, t_se);
cleanup:
    if (k)
        clReleaseKernel(k);
    if (b_out)
        clReleaseMemObject(b_out);
    if (b_out_t)
        clReleaseMemObject(b_out_t);
    if (b_dist)
        clReleaseMemObject(b_dist);
    if (b_rays)
        clReleaseMemObject(b_rays);
    free(all_d);
    free(out_t);
    free(out);
    free(all);
    return rc;
}

int atmo_probe_rays(atmo_probe *p, const float4 *rays, int n, int samples, double (*mean)[3],
                    double (*se)[3], atmo_err *e)
{
    return run_fast_probe(p, rays, NULL, n, samples, mean, se, NULL, NULL, e);
}

int atmo_probe_segments(atmo_probe *p, const float4 *rays, const float *distances, int n,
                        int samples, double (*mean)[3], double (*se)[3], double (*t_mean)[3],
                        double (*t_se)[3], atmo_err *e)
{
    return run_fast_probe(p, rays, distances, n, samples, mean, se, t_mean, t_se, e);
}

int atmo_probe_sun(atmo_probe *p, const float4 *rays, int n, double (*visibility)[3],
                   atmo_err *e)
{
    atmo_cl *cl = atmo_session_cl(p->session);
    int rc = ATMO_OK;
    float4 *out = malloc(sizeof(float4) * (size_t)n);
    cl_mem b_rays = NULL, b_out = NULL;
    cl_kernel k = NULL;
    cl_int err;
    if (!out) {
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for %d rays", n);
        goto cleanup;
    }
    b_rays = clCreateBuffer(cl->context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                            sizeof(float4) * (size_t)n, (void *)rays, &err);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, "clCreateBuffer(rays)", err);
        goto cleanup;
    }
    b_out = clCreateBuffer(cl->context, CL_MEM_WRITE_ONLY, sizeof(float4) * (size_t)n, NULL, &err);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, "clCreateBuffer(visibility)", err);
        goto cleanup;
    }
    k = clCreateKernel(atmo_session_program(p->session), "sky_probe_sun", &err);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, "clCreateKernel(sky_probe_sun)", err);
        goto cleanup;
    }
    cl_uint count = (cl_uint)n, arg = 0;
    if ((rc = atmo_session_bind(p->session, k, &arg, e)))
        goto cleanup;
    err = clSetKernelArg(k, arg++, sizeof b_rays, &b_rays);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, arg++, sizeof b_out, &b_out);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, arg++, sizeof count, &count);
    size_t local = 64, global = ((size_t)n + local - 1) / local * local;
    if (err == CL_SUCCESS)
        err = clEnqueueNDRangeKernel(cl->queue, k, 1, NULL, &global, &local, 0, NULL, NULL);
    if (err == CL_SUCCESS)
        err = clEnqueueReadBuffer(cl->queue, b_out, CL_TRUE, 0, sizeof(float4) * (size_t)n, out,
                                  0, NULL, NULL);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, "sky_probe_sun", err);
        goto cleanup;
    }
    for (int i = 0; i < n; i++)
        visibility[i][0] = out[i].x, visibility[i][1] = out[i].y, visibility[i][2] = out[i].z;
cleanup:
    if (k)
        clReleaseKernel(k);
    if (b_out)
        clReleaseMemObject(b_out);
    if (b_rays)
        clReleaseMemObject(b_rays);
    free(out);
    return rc;
}

void atmo_probe_close(atmo_probe *p)
{
    atmo_session_close(p->session);
    memset(p, 0, sizeof *p);
}
