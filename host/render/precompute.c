/* precompute.c — run the plan's precompute passes (atmo/render.h).
 *
 * Host tables (plan->uploads) are copied first; then the passes run. Every precompute kernel
 * takes (scene, lut0, lut1, lut2, lut3, int arg) (kernels/atmosphere/sky_method.h), so one loop runs any
 * method's passes: LUT sizes and the list of launches come from the plan.
 * 2-D passes use 8 x 8 work-groups and 3-D passes 4 x 4 x 4; global sizes are padded to them and
 * the kernels bounds-check.
 *
 * Disk cache (plan->cache_luts): LUTs that took more than ATMO_LUT_CACHE_MIN_SECONDS to compute
 * are stored in the cache directory under a 64-bit FNV-1a hash of everything they can depend on
 * (the kernel sources and -D flags, the device struct of the scene byte for byte without the
 * camera, the sun and the output factors, the LUT sizes, the passes and the uploaded tables),
 * and loaded instead of recomputed next time, so every view of one atmosphere shares them.
 * Buffers that hold one camera and sun (plan->lut_follows_view, e.g. a sky-view LUT) are never
 * stored; the passes that write them (follows_view) run after a load too. Cheap LUTs are not
 * stored: writing them would cost more than it saves. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "atmo/embedded.h"
#include "atmo/fileio.h"
#include "atmo/render.h"

#define ATMO_LUT_CACHE_MIN_SECONDS 0.5
#define ATMO_LUT_CACHE_MAGIC "atmo-luts-1"

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static size_t pad_to(int n, size_t m) { return ((size_t)n + m - 1) / m * m; }

static unsigned long long fnv(unsigned long long h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

static unsigned long long lut_key(const atmo_plan *plan)
{
    unsigned long long h = 1469598103934665603ull;
    for (int i = 0; i < plan->fragment_count; i++) {
        const struct atmo_embedded_file *f = atmo_embedded_find(atmo_kernel_sources,
                                                                plan->fragments[i]);
        if (f)
            h = fnv(h, f->text, f->size);
    }
    h = fnv(h, plan->defines, strlen(plan->defines));
    /* cached LUTs serve any ray: the camera, the sun and the output factors stay out of the key */
    atmo_gpu_scene g = plan->gpu;
    memset(&g.camera, 0, sizeof g.camera);
    memset(&g.sun_direction, 0, sizeof g.sun_direction);
    memset(&g.sky_factor, 0, sizeof g.sky_factor);
    memset(&g.sun_factor, 0, sizeof g.sun_factor);
    g.seed = 0;
    h = fnv(h, &g, sizeof g);
    h = fnv(h, plan->lut_bytes, sizeof plan->lut_bytes);
    for (int p = 0; p < plan->pass_count; p++) {
        const atmo_plan_pass *pass = &plan->passes[p];
        if (pass->follows_view)
            continue;
        h = fnv(h, pass->kernel, strlen(pass->kernel));
        int dims[4] = {pass->width, pass->height, pass->depth, pass->arg};
        h = fnv(h, dims, sizeof dims);
    }
    for (int u = 0; u < plan->upload_count; u++)
        h = fnv(h, plan->uploads[u].data, plan->uploads[u].bytes);
    return h;
}

static void lut_path(const atmo_plan *plan, char *path, size_t size, int *ok)
{
    char dir[1024];
    *ok = plan->cache_luts && atmo_cache_dir(dir, sizeof dir) == 0;
    if (*ok)
        snprintf(path, size, "%s/luts-%016llx.bin", dir, lut_key(plan));
}

/* Fill the LUT buffers from a cache file; 0 on success. */
static int lut_load(atmo_cl *cl, const atmo_plan *plan, const char *path,
                      cl_mem luts[ATMO_PLAN_LUTS])
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    char magic[sizeof ATMO_LUT_CACHE_MAGIC];
    size_t bytes[ATMO_PLAN_LUTS];
    int rc = fread(magic, sizeof magic, 1, f) == 1 && fread(bytes, sizeof bytes, 1, f) == 1 &&
                     memcmp(magic, ATMO_LUT_CACHE_MAGIC, sizeof magic) == 0 &&
                     memcmp(bytes, plan->lut_bytes, sizeof bytes) == 0
                 ? 0
                 : -1;
    for (int i = 0; i < ATMO_PLAN_LUTS && rc == 0; i++) {
        if (!bytes[i] || plan->lut_follows_view[i])
            continue;
        void *data = malloc(bytes[i]);
        rc = data && fread(data, bytes[i], 1, f) == 1 &&
                     clEnqueueWriteBuffer(cl->queue, luts[i], CL_TRUE, 0, bytes[i], data, 0,
                                          NULL, NULL) == CL_SUCCESS
                 ? 0
                 : -1;
        free(data);
    }
    fclose(f);
    return rc;
}

/* Store the LUT buffers; a failure only costs the next run a precompute. */
static void lut_store(atmo_cl *cl, const atmo_plan *plan, const char *path,
                        cl_mem luts[ATMO_PLAN_LUTS])
{
    char tmp[ATMO_TMP_PATH_MAX];
    FILE *f = atmo_atomic_open(path, tmp, NULL);
    if (!f)
        return;
    int ok = fwrite(ATMO_LUT_CACHE_MAGIC, sizeof ATMO_LUT_CACHE_MAGIC, 1, f) == 1 &&
             fwrite(plan->lut_bytes, sizeof plan->lut_bytes, 1, f) == 1;
    for (int i = 0; i < ATMO_PLAN_LUTS && ok; i++) {
        if (!plan->lut_bytes[i] || plan->lut_follows_view[i])
            continue;
        void *data = malloc(plan->lut_bytes[i]);
        ok = data &&
             clEnqueueReadBuffer(cl->queue, luts[i], CL_TRUE, 0, plan->lut_bytes[i], data, 0,
                                 NULL, NULL) == CL_SUCCESS &&
             fwrite(data, plan->lut_bytes[i], 1, f) == 1;
        free(data);
    }
    if (ok)
        atmo_atomic_commit(f, tmp, path, NULL);
    else
        atmo_atomic_abort(f, tmp);
}

/* One pass: kernel(scene, lut0..lut3, arg) over its padded global size. */
static int run_pass(atmo_cl *cl, cl_program program, const atmo_plan_pass *pass, cl_mem scene,
                    cl_mem luts[ATMO_PLAN_LUTS], atmo_err *e)
{
    cl_int err;
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
    size_t global[3] = {pad_to(pass->width, local[0]), pad_to(pass->height, local[1]),
                        pad_to(pass->depth, local[2])};
    if (err == CL_SUCCESS)
        err = clEnqueueNDRangeKernel(cl->queue, k, three_d ? 3 : 2, NULL, global, local, 0, NULL,
                                     NULL);
    clReleaseKernel(k);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, pass->kernel, err);
    return ATMO_OK;
}

int atmo_precompute(atmo_cl *cl, cl_program program, const atmo_plan *plan, cl_mem scene,
                    cl_mem luts[ATMO_PLAN_LUTS], atmo_precompute_info *info, atmo_err *e)
{
    double t0 = now_seconds();
    cl_int err;
    char path[1200];
    int cacheable;
    info->cache_hit = 0;
    for (int i = 0; i < ATMO_PLAN_LUTS; i++) {
        size_t bytes = plan->lut_bytes[i] ? plan->lut_bytes[i] : 16;
        luts[i] = clCreateBuffer(cl->context, CL_MEM_READ_WRITE, bytes, NULL, &err);
        if (err != CL_SUCCESS)
            return atmo_cl_fail(e, "clCreateBuffer(LUT)", err);
    }
    lut_path(plan, path, sizeof path, &cacheable);
    info->cache_hit = cacheable && lut_load(cl, plan, path, luts) == 0;
    for (int u = 0; u < plan->upload_count && !info->cache_hit; u++) {
        const atmo_plan_upload *up = &plan->uploads[u];
        err = clEnqueueWriteBuffer(cl->queue, luts[up->lut], CL_FALSE, up->offset, up->bytes,
                                   up->data, 0, NULL, NULL);
        if (err != CL_SUCCESS)
            return atmo_cl_fail(e, "clEnqueueWriteBuffer(table)", err);
    }
    for (int p = 0; p < plan->pass_count; p++) {
        const atmo_plan_pass *pass = &plan->passes[p];
        if (info->cache_hit && !pass->follows_view)
            continue;
        int rc = run_pass(cl, program, pass, scene, luts, e);
        if (rc)
            return rc;
    }
    err = clFinish(cl->queue);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clFinish(precompute)", err);
    info->seconds = now_seconds() - t0;
    if (cacheable && !info->cache_hit &&
        (info->seconds > ATMO_LUT_CACHE_MIN_SECONDS || plan->cache_luts == 2))
        lut_store(cl, plan, path, luts);
    return ATMO_OK;
}

int atmo_precompute_view(atmo_cl *cl, cl_program program, const atmo_plan *plan, cl_mem scene,
                         cl_mem luts[ATMO_PLAN_LUTS], double *seconds, atmo_err *e)
{
    double t0 = now_seconds();
    for (int p = 0; p < plan->pass_count; p++) {
        int rc = plan->passes[p].follows_view
                     ? run_pass(cl, program, &plan->passes[p], scene, luts, e)
                     : ATMO_OK;
        if (rc)
            return rc;
    }
    cl_int err = clFinish(cl->queue);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clFinish(precompute)", err);
    *seconds = now_seconds() - t0;
    return ATMO_OK;
}
