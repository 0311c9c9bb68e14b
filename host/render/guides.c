/* guides.c — the denoiser's guides of a session's image (atmo/guides.h): guide_render
 * (kernels/render/guides.cl) over the image's pixels, in launches of GUIDES_LAUNCH_ITEMS work
 * items so that none runs long on a GPU with a watchdog; with a cancel token each launch is
 * waited for and the token checked before the next, so a cancel stops the pass within one. */
#include <stdlib.h>
#include "atmo/gpu_enums.h"
#include "atmo/guides.h"

#define GUIDES_LOCAL 64
#define GUIDES_LAUNCH_ITEMS (GUIDES_LOCAL * 256)

int atmo_guides_apply(const atmo_scene *scene)
{
    int lens = scene->path.mode == ATMO_RENDER_PATH && scene->path.aperture_m > 0.0;
    return !lens && scene->render.spectral_bands == 0;
}

/* guide_render over every pixel into the two device buffers. */
static int launch_all(atmo_session *s, cl_mem b_albedo, cl_mem b_normal, cl_uint pixels,
                      const atmo_cancel *cancel, atmo_err *e)
{
    atmo_cl *cl = atmo_session_cl(s);
    cl_int err;
    int rc = ATMO_OK;
    cl_kernel k = clCreateKernel(atmo_session_program(s), "guide_render", &err);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clCreateKernel(guide_render)", err);
    cl_uint arg = 0;
    if ((rc = atmo_session_bind(s, k, &arg, e)))
        goto cleanup;
    err = clSetKernelArg(k, arg, sizeof b_albedo, &b_albedo);
    if (err == CL_SUCCESS)
        err = clSetKernelArg(k, arg + 1, sizeof b_normal, &b_normal);
    for (cl_uint first = 0; err == CL_SUCCESS && first < pixels; first += GUIDES_LAUNCH_ITEMS) {
        cl_uint count = pixels - first < GUIDES_LAUNCH_ITEMS ? pixels - first
                                                               : GUIDES_LAUNCH_ITEMS;
        size_t local = GUIDES_LOCAL, global = (count + local - 1) / local * local;
        err = clSetKernelArg(k, arg + 2, sizeof first, &first);
        if (err == CL_SUCCESS)
            err = clSetKernelArg(k, arg + 3, sizeof count, &count);
        if (err == CL_SUCCESS)
            err = clEnqueueNDRangeKernel(cl->queue, k, 1, NULL, &global, &local, 0, NULL, NULL);
        if (err == CL_SUCCESS && cancel)
            err = clFinish(cl->queue);
        if (err == CL_SUCCESS && atmo_cancel_requested(cancel)) {
            rc = atmo_fail(e, ATMO_INTERRUPTED_EMPTY, "the guide pass was cancelled");
            break;
        }
    }
    if (err == CL_SUCCESS)
        err = clFinish(cl->queue);
    if (err != CL_SUCCESS)
        rc = atmo_cl_fail(e, "guide_render", err);
cleanup:
    clReleaseKernel(k);
    return rc;
}

int atmo_session_guides(atmo_session *s, float *albedo, float *normal, float *depth,
                        float *disc, const atmo_cancel *cancel, atmo_err *e)
{
    const atmo_plan *p = atmo_session_plan(s);
    atmo_cl *cl = atmo_session_cl(s);
    size_t pixels = (size_t)p->width * (size_t)p->height;
    float *host = malloc(sizeof(float) * 8 * pixels);
    cl_mem b_albedo = NULL, b_normal = NULL;
    cl_int err;
    int rc = ATMO_OK;
    if (!host)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory for the denoiser's guides");
    b_albedo = clCreateBuffer(cl->context, CL_MEM_WRITE_ONLY, sizeof(float) * 4 * pixels, NULL,
                              &err);
    if (err == CL_SUCCESS)
        b_normal = clCreateBuffer(cl->context, CL_MEM_WRITE_ONLY, sizeof(float) * 4 * pixels,
                                  NULL, &err);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, "clCreateBuffer(guides)", err);
        goto cleanup;
    }
    if ((rc = launch_all(s, b_albedo, b_normal, (cl_uint)pixels, cancel, e)))
        goto cleanup;
    err = clEnqueueReadBuffer(cl->queue, b_albedo, CL_TRUE, 0, sizeof(float) * 4 * pixels, host,
                              0, NULL, NULL);
    if (err == CL_SUCCESS)
        err = clEnqueueReadBuffer(cl->queue, b_normal, CL_TRUE, 0, sizeof(float) * 4 * pixels,
                                  host + 4 * pixels, 0, NULL, NULL);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, "clEnqueueReadBuffer(guides)", err);
        goto cleanup;
    }
    for (size_t i = 0; i < pixels; i++) {
        for (int c = 0; c < 3; c++) {
            albedo[3 * i + c] = host[4 * i + c];
            normal[3 * i + c] = host[4 * (pixels + i) + c];
        }
        if (depth)
            depth[i] = host[4 * (pixels + i) + 3];
        if (disc)
            disc[i] = host[4 * i + 3];
    }
cleanup:
    if (b_normal)
        clReleaseMemObject(b_normal);
    if (b_albedo)
        clReleaseMemObject(b_albedo);
    free(host);
    return rc;
}
