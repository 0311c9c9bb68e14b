/* precompute.c — run the plan's precompute passes (atmo/render.h).
 *
 * Host tables (plan->uploads) are copied first; then the passes run. Every precompute kernel
 * takes (scene, lut0, lut1, lut2, lut3, int arg) (kernels/sky_method.h), so one loop runs any
 * method's passes: LUT sizes and the list of launches come from the plan.
 * 2-D passes use 8 x 8 work-groups and 3-D passes 4 x 4 x 4; global sizes are padded to them and
 * the kernels bounds-check. */
#include <time.h>
#include "atmo/render.h"

static double __now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static size_t __pad(int n, size_t m) { return ((size_t)n + m - 1) / m * m; }

int atmo_precompute(atmo_cl *cl, cl_program program, const atmo_plan *plan, cl_mem scene,
                    cl_mem luts[ATMO_PLAN_LUTS], double *seconds, atmo_err *e)
{
    double t0 = __now();
    cl_int err;
    for (int i = 0; i < ATMO_PLAN_LUTS; i++) {
        size_t bytes = plan->lut_bytes[i] ? plan->lut_bytes[i] : 16;
        luts[i] = clCreateBuffer(cl->context, CL_MEM_READ_WRITE, bytes, NULL, &err);
        if (err != CL_SUCCESS)
            return atmo_cl_fail(e, "clCreateBuffer(LUT)", err);
    }
    for (int u = 0; u < plan->upload_count; u++) {
        const atmo_plan_upload *up = &plan->uploads[u];
        err = clEnqueueWriteBuffer(cl->queue, luts[up->lut], CL_FALSE, up->offset, up->bytes,
                                   up->data, 0, NULL, NULL);
        if (err != CL_SUCCESS)
            return atmo_cl_fail(e, "clEnqueueWriteBuffer(table)", err);
    }
    for (int p = 0; p < plan->pass_count; p++) {
        const atmo_plan_pass *pass = &plan->passes[p];
        cl_kernel k = clCreateKernel(program, pass->kernel, &err);
        if (err != CL_SUCCESS)
            return atmo_cl_fail(e, "clCreateKernel(precompute)", err);
        err = clSetKernelArg(k, 0, sizeof scene, &scene);
        for (int i = 0; i < ATMO_PLAN_LUTS && err == CL_SUCCESS; i++)
            err = clSetKernelArg(k, 1 + i, sizeof luts[i], &luts[i]);
        if (err == CL_SUCCESS)
            err = clSetKernelArg(k, 1 + ATMO_PLAN_LUTS, sizeof pass->arg, &pass->arg);
        int three_d = pass->depth > 1;
        size_t local[3] = {three_d ? 4 : 8, three_d ? 4 : 8, three_d ? 4 : 1};
        size_t global[3] = {__pad(pass->width, local[0]), __pad(pass->height, local[1]),
                            __pad(pass->depth, local[2])};
        if (err == CL_SUCCESS)
            err = clEnqueueNDRangeKernel(cl->queue, k, three_d ? 3 : 2, NULL, global, local, 0,
                                         NULL, NULL);
        clReleaseKernel(k);
        if (err != CL_SUCCESS)
            return atmo_cl_fail(e, pass->kernel, err);
    }
    err = clFinish(cl->queue);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clFinish(precompute)", err);
    *seconds = __now() - t0;
    return ATMO_OK;
}
